# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rotation measure from IONEX maps against spinifex's own functions, on the IONEX files it ships.

Every test runs with the network cut (sockets refuse to connect): spinifex is
given its files in a local ``output_directory``, named as it names them, and
the Ionosphere object reads the same files from their paths.
"""

import pickle
import shutil
import socket
import warnings

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.time import Time
from helpers import import_or_skip

import_or_skip("spinifex", "ionosphere", "FEEDROT_REQUIRE_SPINIFEX")

from spinifex.geometry import R_EARTH_MEAN, get_ipp_from_skycoord  # noqa: E402
from spinifex.get_rm import _get_rm_from_skycoord, get_rm_from_skycoord  # noqa: E402
from spinifex.ionospheric.models import ionospheric_models  # noqa: E402
from spinifex.ionospheric.tec_data import IonexOptions  # noqa: E402
from spinifex.magnetic import magnetic_models  # noqa: E402

from astropy_feedrot.core.exceptions import DegenerateGeometryWarning  # noqa: E402
from astropy_feedrot.earth.frames import location_xyz, source_direction  # noqa: E402
from astropy_feedrot.ionosphere import Ionosphere, sample_ionex  # noqa: E402
from astropy_feedrot.ionosphere.pierce_points import (  # noqa: E402
    EARTH_RADIUS_KM,
    pierce_points,
)

WSRT = EarthLocation.from_geodetic(6.60 * u.deg, 52.91 * u.deg, 16 * u.m)
ASKAP = EarthLocation.from_geodetic(116.63 * u.deg, -26.70 * u.deg, 360 * u.m)
VIRGO_A = SkyCoord("12h30m49.42s +12d23m28.0s")

# The shipped files, the day they start, and the options under which spinifex's
# get_rm_from_skycoord finds them by name in its output_directory; spinifex wants
# the next day's file for the last midnight unless remove_midnight_jumps is off
# (the IGS file has no next day among the shipped ones).
CASES = [
    ("codg00[89]0.20i.Z", "2020-01-08", {"server": "cddis", "prefix": "cod"}),
    ("esag0*", "2020-01-09", {"server": "cddis", "prefix": "esa"}),
    ("uqrg*", "2019-04-25", {"server": "chapman", "prefix": "uqr"}),
    ("IGS0OPSFIN*", "2024-12-14",
     {"server": "cddis", "prefix": "igs", "remove_midnight_jumps": False}),
]


@pytest.fixture(autouse=True)
def no_network(monkeypatch):
    """Any attempt to open a connection fails the test: everything here is offline."""
    def refuse(*args, **kwargs):
        raise AssertionError(f"network access attempted: {args}")
    monkeypatch.setattr(socket.socket, "connect", refuse)
    monkeypatch.setattr(socket, "create_connection", refuse)


@pytest.fixture(scope="module")
def ionex_directory(tmp_path_factory):
    """spinifex's output_directory holding every shipped IONEX file under its own name."""
    folder = tmp_path_factory.mktemp("ionex")
    for path in sample_ionex():
        shutil.copy(path, folder / path.name)
    return folder


def spinifex_rm(location, times, target, **options):
    """spinifex's get_rm_from_skycoord, its INFO messages kept quiet."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # spinifex logs; nothing of ours is hidden here
        return get_rm_from_skycoord(location, times, target, **options)


@pytest.mark.parametrize("pattern, day, options", CASES)
@pytest.mark.parametrize("site", [WSRT, ASKAP], ids=["WSRT", "ASKAP"])
def test_same_numbers_as_spinifex(pattern, day, options, site, ionex_directory):
    # Reference: spinifex's get_rm_from_skycoord (450 km, IGRF through ppigrf) on
    # the same files; every 7 min over the day, the target rising and setting.
    times = Time(day) + np.arange(0, 24 * 60, 7) * u.min
    reference = spinifex_rm(site, times, VIRGO_A, output_directory=ionex_directory, **options)
    iono = Ionosphere.from_ionex(sample_ionex(pattern), step=0 * u.s)
    up = reference.elevation > 0
    assert 0 < up.sum() < up.size  # both cases occur
    with pytest.warns(DegenerateGeometryWarning, match="below the horizon"):
        rm = iono.rotation_measure(site, VIRGO_A, times)
    assert rm.unit == u.rad / u.m**2
    np.testing.assert_allclose(rm.value[up], reference.rm[up], rtol=1e-9, atol=0)  # 7e-12
    assert np.all(np.isnan(rm.value[~up]))


@pytest.mark.parametrize("height", [300, 450, 1000] * u.km)
@pytest.mark.parametrize("site", [WSRT, ASKAP], ids=["WSRT", "ASKAP"])
def test_pierce_points_are_spinifexs(site, height):
    # Reference: spinifex's get_ipp_from_skycoord (one site, astropy's topocentric
    # ITRS) against the package's directions and its pierce points for all sites at
    # once; the directions agree to 0.001 mas, the pierce points to a millimetre.
    assert EARTH_RADIUS_KM == R_EARTH_MEAN.to_value(u.km)
    times = Time("2020-01-08") + np.arange(0, 24 * 60, 13) * u.min
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # spinifex logs
        reference = get_ipp_from_skycoord(site, times, VIRGO_A, u.Quantity([height]))
    s = source_direction(VIRGO_A, site, times)
    ours = pierce_points(location_xyz(site) / 1e3, s, height.to_value(u.km))
    np.testing.assert_allclose(ours.lon, reference.lon.to_value(u.deg)[:, 0], rtol=0,
                               atol=1e-8)
    np.testing.assert_allclose(ours.lat, reference.lat.to_value(u.deg)[:, 0], rtol=0,
                               atol=1e-8)
    np.testing.assert_allclose(ours.radius, reference.height.to_value(u.km)[:, 0], rtol=1e-12)
    np.testing.assert_allclose(ours.slant, reference.airmass[:, 0], rtol=1e-9)
    np.testing.assert_allclose(s, reference.los, rtol=0, atol=1e-11)


def test_height_is_honoured(ionex_directory):
    # Reference: spinifex's single-layer computation with the shell at the same
    # height (the function get_rm_from_skycoord calls, with its height argument).
    times = Time("2020-01-08T17:00") + np.arange(0, 6 * 60, 11) * u.min  # target up
    results = {}
    for height in (300, 450, 600) * u.km:
        options = IonexOptions(server="cddis", prefix="cod", height=height,
                               output_directory=ionex_directory)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            reference = _get_rm_from_skycoord(
                ASKAP, times, VIRGO_A, ionospheric_models.ionex, magnetic_models.ppigrf,
                height_array=u.Quantity([height]), iono_options=options)
        iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"), height=height,
                                     step=0 * u.s)
        rm = iono.rotation_measure(ASKAP, VIRGO_A, times)
        np.testing.assert_allclose(rm.value, reference.rm, rtol=1e-9, atol=0)
        results[height.value] = rm.value
    # the height matters: a few per cent between 300 and 600 km here
    change = np.abs(results[300] - results[600]) / np.abs(results[450])
    assert change.max() > 0.01


@pytest.mark.parametrize("pattern, start, tolerance, tolerance_10s", [
    # hourly maps: measured 1.6e-4 at 60 s, 3.8e-5 at 10 s
    ("codg00[89]0.20i.Z", "2020-01-08T16:00", 2e-4, 5e-5),
    # 15 min maps: measured 1.1e-3 at 60 s, 1.0e-4 at 10 s
    ("uqrg*", "2019-04-25T08:00", 1.5e-3, 1.5e-4),
])
def test_coarse_grid_agrees_with_every_epoch(pattern, start, tolerance, tolerance_10s):
    # Reference: the same maps evaluated at every epoch (step 0), over 12 h at 5 s
    # for two sites. The 60 s grid misses most where the pierce point, carried by
    # the maps' rotation with the Earth, crosses the maps' 5 deg cells; its rms
    # error is 30 times smaller than its largest.
    times = Time(start) + np.arange(0, 12 * 3600, 5) * u.s
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    sites = EarthLocation.from_geodetic([6.60, -3.09] * u.deg, [52.91, 40.52] * u.deg)
    files = sample_ionex(pattern)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegenerateGeometryWarning)  # below the horizon: NaN
        coarse = Ionosphere.from_ionex(files).rotation_measure(sites, crab, times)
        exact = Ionosphere.from_ionex(files, step=0 * u.s).rotation_measure(sites, crab, times)
    assert coarse.shape == (times.size, 2)
    up = np.isfinite(exact)
    assert up.sum() > 0.8 * up.size
    np.testing.assert_array_equal(np.isfinite(coarse), up)
    assert np.max(np.abs(coarse - exact)[up]) < tolerance * u.rad / u.m**2
    fine = Ionosphere.from_ionex(files, step=10 * u.s)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegenerateGeometryWarning)
        assert np.max(np.abs(fine.rotation_measure(sites, crab, times) - exact)[up]) \
            < tolerance_10s * u.rad / u.m**2


def test_shapes_epochs_first_sites_last():
    iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    sites = EarthLocation.from_geodetic([6.60, -3.09, 11.93] * u.deg,
                                        [52.91, 40.52, 57.39] * u.deg)
    epochs = Time("2020-01-08T20:00") + np.arange(6).reshape(2, 3) * u.h
    rm = iono.rotation_measure(sites, crab, epochs)
    assert rm.shape == (2, 3, 3)
    # antenna names are not used by maps
    named = iono.rotation_measure(sites, crab, epochs, antenna=["WB", "YS", "ON"])
    np.testing.assert_array_equal(named.value, rm.value)
    # each site alone, each epoch alone: the same values (scalar in, scalar out)
    one = iono.rotation_measure(sites[1], crab, epochs[1, 2])
    assert one.shape == ()
    np.testing.assert_allclose(one.value, rm[1, 2, 1].value, rtol=1e-9)
    # repeated epochs (rows of a visibility file) give repeated values
    repeated = iono.rotation_measure(sites[0], crab, epochs.ravel()[[0, 0, 3, 3, 3]])
    np.testing.assert_allclose(repeated.value, rm.value.reshape(6, 3)[[0, 0, 3, 3, 3], 0],
                               rtol=1e-9)


def test_target_per_epoch_is_evaluated_at_each():
    # A target with one direction per epoch (here the same direction repeated):
    # no coarse grid, the same numbers as the fixed target evaluated at every epoch.
    iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"), step=0 * u.s)
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    epochs = Time("2020-01-08T20:00") + np.arange(4) * u.h
    fixed = iono.rotation_measure(WSRT, crab, epochs)
    per_epoch = iono.rotation_measure(WSRT, SkyCoord([crab.ra] * 4, [crab.dec] * 4), epochs)
    # The fixed target's directions come once for the network plus the site's diurnal
    # aberration, the others site by site: 4e-4 mas apart, 3e-12 in the RM measured.
    np.testing.assert_allclose(per_epoch.value, fixed.value, rtol=1e-10)


def test_time_scale_does_not_matter():
    iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    epochs = Time("2020-01-08T20:00") + np.arange(0, 3600, 600) * u.s
    np.testing.assert_allclose(iono.rotation_measure(WSRT, crab, epochs.tt).value,
                               iono.rotation_measure(WSRT, crab, epochs).value, rtol=1e-12)


def test_across_midnight_with_the_next_day():
    # Epochs on both days: each day's file serves its epochs, continuously.
    iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"), step=0 * u.s)
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    epochs = Time("2020-01-08T23:00") + np.arange(0, 7200, 60) * u.s
    rm = iono.rotation_measure(WSRT, crab, epochs).value
    assert np.all(np.isfinite(rm))
    assert np.max(np.abs(np.diff(rm))) < 0.01  # no jump at midnight (steps of 60 s)


def test_below_the_horizon_is_nan_with_one_warning():
    iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    epochs = Time("2020-01-08T00:00") + np.arange(0, 24 * 3600, 60) * u.s
    sites = EarthLocation.from_geodetic([6.60, 116.63] * u.deg, [52.91, -26.70] * u.deg)
    with pytest.warns(DegenerateGeometryWarning,
                      match=r"undefined at \d+ of 2880 epochs x sites, where the target is "
                            "below the horizon") as caught:
        rm = iono.rotation_measure(sites, crab, epochs)
    assert len(caught) == 1
    # Reference: astropy's AltAz of the target (no refraction), away from the crossings
    from astropy.coordinates import AltAz
    for k in range(2):
        altitude = crab.transform_to(AltAz(obstime=epochs, location=sites[k])).alt.deg
        clear = np.abs(altitude) > 0.01
        np.testing.assert_array_equal(np.isnan(rm[clear, k]), altitude[clear] < 0)


def test_pickled_ionosphere_gives_the_same_numbers():
    # What a dask worker receives: the maps themselves, not paths to read again.
    iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"), height=400 * u.km)
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    epochs = Time("2020-01-08T20:00") + np.arange(0, 4 * 3600, 300) * u.s
    copy = pickle.loads(pickle.dumps(iono))
    assert copy.height == 400 * u.km and copy.files == iono.files
    np.testing.assert_array_equal(copy.rotation_measure(WSRT, crab, epochs).value,
                                  iono.rotation_measure(WSRT, crab, epochs).value)


def test_astropy_does_not_read_its_tables_again():
    # The lines of sight come from the package's frames, with its Earth-orientation
    # arrays (bit for bit astropy's), not from astropy reading its bundled tables
    # anew (1-2.5 s a process). In a fresh interpreter astropy's table stays
    # unread, and the numbers do not change once astropy has read it.
    import subprocess
    import sys

    script = (
        "import astropy.units as u\n"
        "from astropy.coordinates import EarthLocation, SkyCoord\n"
        "from astropy.time import Time\n"
        "from astropy.utils import iers\n"
        "from astropy_feedrot.ionosphere import Ionosphere, sample_ionex\n"
        "iono = Ionosphere.from_ionex(sample_ionex('codg00[89]0.20i.Z'), step=0 * u.s)\n"
        "site = EarthLocation.from_geodetic(6.6045 * u.deg, 52.9153 * u.deg, 16 * u.m)\n"
        "crab = SkyCoord('05h34m31.94s +22d00m52.2s')\n"
        "t = Time('2020-01-08T22:00') + [0, 1, 2] * u.h\n"
        "ours = iono.rotation_measure(site, crab, t)\n"
        "assert iers.IERS_Auto.iers_table is None, 'astropy read its tables'\n"
        "iers.IERS_Auto.open()\n"
        "assert iers.IERS_Auto.iers_table is not None\n"
        "assert (iono.rotation_measure(site, crab, t) == ours).all()\n")
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
