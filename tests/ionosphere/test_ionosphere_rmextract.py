# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rotation measure against RMextract, spinifex's predecessor, on the same IONEX file, offline.

RMextract differs by design: the World Magnetic Model (WMM) instead of IGRF, a
pierce point on a sphere of 6364.62 km instead of 6371 km, geodetic
coordinates, and the day's own 24:00 map at midnight. With the maps rotated
with the Earth in both (RMextract's ``earth_rot=1``; its default 0 differs by
up to 9 % from spinifex's default), the two agree within 0.6 % above 10 deg
elevation (measured 0.53 % at most, 0.16 % median, 0.007 rad/m^2 at most on
2020 January 8 for WSRT and ASKAP).
"""

import socket

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.time import Time
from helpers import import_or_skip

import_or_skip("spinifex", "ionosphere", "FEEDROT_REQUIRE_SPINIFEX")
getRM = pytest.importorskip("RMextract.getRM").getRM

from unlzw_cython import unlzw  # noqa: E402

from astropy_feedrot.ionosphere import Ionosphere, sample_ionex  # noqa: E402

VIRGO_A = SkyCoord("12h30m49.42s +12d23m28.0s")


@pytest.fixture(autouse=True)
def no_network(monkeypatch):
    """Any attempt to open a connection fails the test: everything here is offline."""
    def refuse(*args, **kwargs):
        raise AssertionError(f"network access attempted: {args}")
    monkeypatch.setattr(socket.socket, "connect", refuse)
    monkeypatch.setattr(socket, "create_connection", refuse)


@pytest.mark.filterwarnings("ignore")  # RMextract and casacore's own messages
@pytest.mark.parametrize("site", [
    EarthLocation.from_geodetic(6.60 * u.deg, 52.91 * u.deg, 16 * u.m),
    EarthLocation.from_geodetic(116.63 * u.deg, -26.70 * u.deg, 360 * u.m),
], ids=["WSRT", "ASKAP"])
def test_agreement_with_rmextract(site, tmp_path):
    # RMextract finds a local file only uncompressed and under its upper-case name.
    path = sample_ionex("codg0080.20i.Z")[0]
    (tmp_path / "CODG0080.20I").write_bytes(unlzw(path.read_bytes()))
    start = Time("2020-01-08T00:10").mjd * 86400  # RMextract starts one step earlier
    result = getRM(ionexPath=str(tmp_path) + "/", prefix="codg", timerange=[start, start + 84600],
                   timestep=600, radec=[VIRGO_A.ra.rad, VIRGO_A.dec.rad], earth_rot=1,
                   stat_positions=[np.array([site.x.value, site.y.value, site.z.value])])
    times = Time(result["times"] / 86400, format="mjd", scale="utc")
    reference = np.ravel(result["RM"]["st1"])
    high = np.ravel(result["elev"]["st1"]) > np.radians(10)
    assert high.sum() > 40
    iono = Ionosphere.from_ionex([path], step=0 * u.s)
    ours = iono.rotation_measure(site, VIRGO_A, times[high])
    relative = np.abs(ours.value / reference[high] - 1)
    assert relative.max() < 0.006
    assert np.median(relative) < 0.003
