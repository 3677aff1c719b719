# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Shared data and helpers for the tests: the paper's sites, sky grids, file sources."""

import gzip
import importlib
import io
import os

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import ITRS, EarthLocation, SkyCoord
from astropy.time import Time

from astropy_feedrot.core.kernel import wrap_phase

#: 1 milliarcsecond in radians.
MAS = (1 * u.mas).to_value(u.rad)

#: Sites from the paper: Tables 1 and 3 (ITRF, metres), and Yebes and
#: Warkworth from their geodetic latitudes and longitudes (used here only as
#: test sites north and south of the equator).
SITES = {
    "FD-VLBA": EarthLocation.from_geocentric(-1324009.454, -5332181.955, 3231962.369, u.m),
    "DBR205": EarthLocation.from_geocentric(-1324070.478, -5332176.001, 3231921.799, u.m),
    "GGAO12M": EarthLocation.from_geocentric(1130730.179, -4831245.954, 3994228.241, u.m),
    "WETTZ13S": EarthLocation.from_geocentric(4075659.180, 931824.551, 4801516.102, u.m),
    "YEBES": EarthLocation.from_geodetic(-3.0869 * u.deg, 40.5247 * u.deg, 988 * u.m),
    "WARKWORTH": EarthLocation.from_geodetic(174.6630 * u.deg, -36.4348 * u.deg, 128 * u.m),
}

#: One day at 15 min on the date of the paper's simulations (Sec. 4).
DAY = Time("2023-01-25T00:00:00", scale="utc") + np.arange(96) * 15 * u.min


def sky_grid(n):
    """A golden-spiral grid of ``n`` ICRS directions covering the sphere."""
    i = np.arange(n) + 0.5
    dec = np.arcsin(1 - 2 * i / n)
    ra = np.mod(np.pi * (1 + 5**0.5) * i, 2 * np.pi)
    return SkyCoord(ra=ra * u.rad, dec=dec * u.rad, frame="icrs")


def itrs_direction(vector, obstime=None):
    """A distance-less ITRS direction (a source at infinity) as a SkyCoord."""
    x, y, z = np.moveaxis(np.asarray(vector, dtype=float), -1, 0)
    return SkyCoord(ITRS(x=x, y=y, z=z, representation_type="cartesian", obstime=obstime))


def angle_spread(a, b):
    """Max deviation of a - b from its circular mean (radians): 0 if equal up to a constant."""
    d = wrap_phase(np.asarray(a) - np.asarray(b))
    d = d[np.isfinite(d)]
    c = np.angle(np.mean(np.exp(1j * d)))
    return float(np.max(np.abs(wrap_phase(d - c)))), float(c)


def max_angle_difference(a, b):
    """Max |a - b| modulo 2 pi (radians), ignoring NaN where both are NaN."""
    d = wrap_phase(np.asarray(a) - np.asarray(b))
    assert np.array_equal(np.isnan(a), np.isnan(b)), "NaN in different places"
    return float(np.nanmax(np.abs(d)))


#: The kinds of source the file readers accept.
SOURCE_KINDS = ["str", "path", "text file", "binary file", "stringio", "gzip"]


def read_as(kind, reader, path, tmp_path):
    """Call ``reader`` on the file at ``path`` given as a source of ``kind``."""
    if kind == "str":
        return reader(str(path))
    if kind == "path":
        return reader(path)
    if kind in ("text file", "binary file"):
        with open(path, "r" if kind == "text file" else "rb") as fh:
            return reader(fh)
    if kind == "stringio":
        return reader(io.StringIO(path.read_text()))
    compressed = tmp_path / (path.name + ".gz")
    with gzip.open(compressed, "wt") as fh:
        fh.write(path.read_text())
    return reader(compressed)


#: The %c, %f and %i lines of an SP3-c/d header (GPS time, default bases).
SP3_DESCRIPTORS = [
    "%c M  cc GPS ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc",
    "%c cc cc ccc ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc",
    "%f  1.2500000  1.025000000  0.00000000000  0.000000000000000",
    "%f  0.0000000  0.000000000  0.00000000000  0.000000000000000",
    "%i    0    0    0    0      0      0      0      0         0",
    "%i    0    0    0    0      0      0      0      0         0",
]


def import_or_skip(name, extra, require):
    """A module the tests of an optional feature need: skipped without it, saying
    which extra installs it, except where the environment variable ``require`` is
    set (``.ci/run`` sets it): there a missing module fails the tests."""
    if os.environ.get(require):
        return importlib.import_module(name)
    return pytest.importorskip(name, reason=f"{name} is not installed: python -m pip install "
                                            f"-e '.[{extra}]'")
