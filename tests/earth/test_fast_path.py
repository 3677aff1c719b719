# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The fast path (earth.orientation) against astropy's transformation at every epoch.

Every reference here is astropy's rigorous ``ITRS(location=...)`` transformation
(``conf.fast_path = False``), astropy's `~astropy.coordinates.HADec` with
``erfa.hd2pa``, or astropy's TEME to ITRS transformation.
"""

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import (
    ITRS,
    TEME,
    AltAz,
    CartesianRepresentation,
    Galactic,
    HADec,
    SkyCoord,
)
from astropy.time import Time
from helpers import MAS, SITES, sky_grid

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    EquatorialMount,
    FixedAxisMount,
    MirrorTrain,
    NasmythFocus,
    StationaryMount,
    XYMount,
    conf,
)
from astropy_feedrot.earth.frames import source_direction
from astropy_feedrot.earth.orientation import EarthOrientation, fast_path_applies
from astropy_feedrot.transmitters.orbits import teme_to_itrs

#: The accuracy the fast path promises against the rigorous path, in the feed
#: rotation, and (DIRECTION_LIMIT) in the directions themselves; with fewer
#: than 100 epochs per day of nodes over a long span, SPARSE_LIMIT.
LIMIT = 0.1 * MAS
DIRECTION_LIMIT = 0.001 * MAS
SPARSE_LIMIT = 0.005 * MAS

NORTH, SOUTH = "WETTZ13S", "WARKWORTH"


def angle_between(a, b):
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


def rigorous_direction(target, site, times):
    with conf.set_temp("fast_path", False):
        return source_direction(target, site, times)


def series(start, step, count):
    """``count`` UTC epochs ``step`` apart from ``start``."""
    return Time(start, scale="utc") + np.arange(count) * step


#: The sampling regimes of the benchmark (benchmarks/natural.py), at the same
#: density; the largest are compared with the rigorous path on a subsample.
#: name: (epochs, every how many to compare, accuracy of the directions)
REGIMES = {
    "1 s for 2 hours": (series("2023-01-25T05:00", 1 * u.s, 7200), 1, DIRECTION_LIMIT),
    "1 min for a week": (series("2023-01-25T00:00", 1 * u.min, 10080), 1, DIRECTION_LIMIT),
    "2.6 s for 3 days": (series("2023-01-25T00:00", 2.6 * u.s, 99692), 50, DIRECTION_LIMIT),
    "1 h for a year": (series("2023-01-01T00:00", 1 * u.hour, 8760), 1, SPARSE_LIMIT),
    "a few epochs": (series("2023-01-25T03:00", 37 * u.min, 5), 1, DIRECTION_LIMIT),
}


@pytest.mark.parametrize("regime", list(REGIMES))
@pytest.mark.parametrize("site", [NORTH, SOUTH])
def test_directions_in_every_regime(regime, site):
    # Directions over the sky within 0.001 mas of astropy's at every epoch compared.
    times, every, limit = REGIMES[regime]
    every = max(every, times.size // 2000)
    sources = sky_grid(6)[:, np.newaxis]
    fast = source_direction(sources, SITES[site], times)[:, ::every]
    assert fast.shape == (6, times[::every].size, 3)
    reference = rigorous_direction(sources, SITES[site], times[::every])
    assert angle_between(fast, reference).max() < limit
    assert np.allclose(np.linalg.norm(fast, axis=-1), 1, rtol=0, atol=1e-15)


def test_directions_every_30_s_for_a_year():
    # 1.05 million epochs: the fast path at all, the rigorous path at every 500th.
    times = series("2023-01-01T00:00", 30 * u.s, 1051200)
    source = SkyCoord("03h19m48.16s +41d30m42.1s")
    fast = source_direction(source, SITES[NORTH], times)[::500]
    reference = rigorous_direction(source, SITES[NORTH], times[::500])
    assert angle_between(fast, reference).max() < DIRECTION_LIMIT


@pytest.mark.parametrize("site", ["FD-VLBA", NORTH, SOUTH])
def test_directions_over_the_sky_and_a_day(site):
    sources = sky_grid(30)[:, np.newaxis]
    times = series("2023-01-25T00:00", 97 * u.s, 891)
    fast = source_direction(sources, SITES[site], times)
    assert fast.shape == (30, times.size, 3)
    assert angle_between(fast, rigorous_direction(sources, SITES[site], times)).max() < (
        DIRECTION_LIMIT)


MOUNTS = [
    (AltAzMount(), None),
    (AltAzMount(), NasmythFocus("right")),
    (AltAzMount(), BeamWaveguideFocus("left")),
    (AltAzMount(), MirrorTrain.wark30m()),
    (EquatorialMount(), None),
    (XYMount("north"), None),
    (XYMount("east"), None),
    (FixedAxisMount([0.3, 0.4, 0.5], frame="enu"), None),
    (StationaryMount(), None),
]


def assert_feed_rotation_agrees(antenna, sources, times, every=1, min_elevation=-5 * u.deg):
    fast = antenna.feed_rotation(sources, times, min_elevation=min_elevation)[..., ::every]
    times = times[::every]
    with conf.set_temp("fast_path", False):
        rigorous = antenna.feed_rotation(sources, times, min_elevation=min_elevation)
    assert np.array_equal(np.isfinite(rigorous), np.isfinite(fast))
    # Within 0.1 deg of the zenith, angles that involve the azimuth change
    # by 1/sin(z) times any change of direction; leave those epochs out.
    _, elevation = antenna.altaz(sources, times)
    finite = np.isfinite(rigorous) & (elevation < 89.9 * u.deg)
    # Equatorial: 0 either way (exactly or to rounding).
    difference = (fast - rigorous).wrap_at(180 * u.deg).to_value(u.rad)[finite]
    assert np.abs(difference).max() < LIMIT


@pytest.mark.parametrize("mount, focus", MOUNTS)
def test_feed_rotation_matches_the_rigorous_path(mount, focus):
    antenna = Antenna(SITES[NORTH], mount, focus)
    sources = sky_grid(12)[:, np.newaxis]
    assert_feed_rotation_agrees(antenna, sources, series("2023-01-25T00:00", 300 * u.s, 288))


@pytest.mark.parametrize("regime", list(REGIMES))
@pytest.mark.parametrize("site", [NORTH, SOUTH])
@pytest.mark.parametrize("mount, focus", [(AltAzMount(), NasmythFocus("left")),
                                          (XYMount("east"), None)])
def test_feed_rotation_in_every_regime(regime, site, mount, focus):
    # Above 5 deg of elevation: the XY mount's keyhole is on the horizon, where
    # its angle changes as 1/sin of the distance to it times any change of direction.
    times, every, _ = REGIMES[regime]
    antenna = Antenna(SITES[site], mount, focus)
    sources = sky_grid(3)[:, np.newaxis]
    assert_feed_rotation_agrees(antenna, sources, times, every=max(every, times.size // 2000),
                                min_elevation=5 * u.deg)


@pytest.mark.parametrize("site", [NORTH, SOUTH])
def test_parallactic_angle_against_hadec_and_hd2pa(site):
    # Independent reference: astropy's HADec frame at every epoch and ERFA's hd2pa.
    location = SITES[site]
    antenna = Antenna(location, AltAzMount())
    source = SkyCoord(ra=80 * u.deg, dec=-10 * u.deg)
    times = series("2023-01-25T00:00", 40 * u.s, 2160)
    angle = antenna.parallactic_angle(source, times).to_value(u.rad)
    hadec = source.transform_to(HADec(obstime=times, location=location))
    reference = erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, location.lat.rad)
    high = hadec.transform_to(AltAz(obstime=times, location=location)).alt < 89.9 * u.deg
    difference = np.angle(np.exp(1j * (angle - reference)))[high]
    assert np.abs(difference).max() < LIMIT


@pytest.mark.parametrize("scalar", [True, False])
def test_scalar_and_array_times(scalar):
    times = series("2023-01-25T20:00", 1 * u.min, 50)
    source = SkyCoord("03h19m48.16s +41d30m42.1s")
    antenna = Antenna(SITES[SOUTH], AltAzMount(), NasmythFocus("right"))
    epoch = times[17] if scalar else times[17:18]
    result = antenna.feed_rotation(source, epoch)
    assert result.shape == epoch.shape
    with conf.set_temp("fast_path", False):
        reference = antenna.feed_rotation(source, epoch)
    assert abs((result - reference).wrap_at(180 * u.deg).to_value(u.rad)).max() < LIMIT
    # The same epoch within a series gives the same angle.
    assert abs((antenna.feed_rotation(source, times)[17] - result.ravel()[0]).to_value(
        u.rad)) < DIRECTION_LIMIT


def test_sparse_epochs_over_years_and_a_leap_second():
    # Epochs scattered over 2012-2022, and one minute around the leap second at
    # the end of 2016: ERFA is evaluated at no more instants than there are epochs.
    rng = np.random.default_rng(3)
    scattered = Time("2012-01-01", scale="utc") + np.sort(rng.uniform(0, 3650, 200)) * u.day
    leap = Time("2016-12-31T23:59:30", scale="utc") + np.arange(61) * u.s
    times = Time(np.concatenate([scattered.jd, leap.jd]), format="jd", scale="utc")
    source = SkyCoord("12h29m06.7s +02d03m09s")
    orientation = EarthOrientation(times)
    assert orientation.nodes.size <= times.size
    fast = source_direction(source, SITES["GGAO12M"], times)
    assert angle_between(fast, rigorous_direction(source, SITES["GGAO12M"], times)).max() < (
        DIRECTION_LIMIT)


def test_dense_epochs_across_a_leap_second():
    # Every second from 23:00 on 2016-12-31 to 01:00 UTC, 23:59:60 included.
    # (A tenth of a second off the full seconds: see test_earth.EPOCHS for the
    # epoch where astropy's own UT1 jumps.)
    times = series("2016-12-31T23:00:00.1", 1 * u.s, 7202)
    assert "2016-12-31 23:59:60.100" in times.iso
    antenna = Antenna(SITES[NORTH], AltAzMount(), BeamWaveguideFocus("right"))
    source = SkyCoord(ra=120 * u.deg, dec=30 * u.deg)
    fast = source_direction(source, antenna.location, times)
    assert angle_between(fast, rigorous_direction(source, antenna.location, times)).max() < (
        DIRECTION_LIMIT)
    assert_feed_rotation_agrees(antenna, source, times)


def test_unsorted_and_repeated_epochs():
    rng = np.random.default_rng(11)
    offsets = rng.uniform(0, 5 * 86400, 5000)
    offsets[:50] = offsets[50:100]  # repeated epochs
    times = Time("2023-01-25T00:00") + offsets * u.s
    source = SkyCoord(l=30 * u.deg, b=5 * u.deg, frame="galactic")
    fast = source_direction(source, SITES[SOUTH], times)
    assert np.array_equal(fast[:50], fast[50:100])
    assert angle_between(fast, rigorous_direction(source, SITES[SOUTH], times)).max() < (
        DIRECTION_LIMIT)


@pytest.mark.parametrize("scale", ["tt", "tai", "tdb", "ut1"])
def test_time_scales(scale):
    times = getattr(series("2023-01-25T00:00", 45 * u.s, 3000), scale)
    source = SkyCoord(ra=300 * u.deg, dec=60 * u.deg)
    fast = source_direction(source, SITES[NORTH], times)
    assert angle_between(fast, rigorous_direction(source, SITES[NORTH], times)).max() < (
        DIRECTION_LIMIT)


def test_masked_epochs_give_nan():
    times = series("2023-01-25T00:00", 10 * u.s, 2000)
    masked = times.copy()
    masked[[0, 700, 1999]] = np.ma.masked
    antenna = Antenna(SITES[NORTH], XYMount("north"))
    source = SkyCoord(ra=49.95 * u.deg, dec=41.51 * u.deg)
    result = antenna.feed_rotation(source, masked)
    assert np.all(np.isnan(result[[0, 700, 1999]]))
    keep = np.ones(times.size, bool)
    keep[[0, 700, 1999]] = False
    with conf.set_temp("fast_path", False):
        reference = antenna.feed_rotation(source, times)
    assert np.abs((result - reference)[keep].wrap_at(180 * u.deg).to_value(u.rad)).max() < LIMIT


def test_sources_near_the_sun():
    # Light deflection by the Sun grows to 1.75 arcsec at the limb.
    times = series("2023-01-25T00:00", 60 * u.s, 2880)
    sun = SkyCoord(ra=307.4 * u.deg, dec=-18.8 * u.deg)  # near the Sun on 2023-01-26
    sources = SkyCoord([sun.directional_offset_by(0 * u.deg, d * u.deg)
                        for d in (0.5, 1, 3, 10)])[:, np.newaxis]
    fast = source_direction(sources, SITES[NORTH], times)
    assert angle_between(fast, rigorous_direction(sources, SITES[NORTH], times)).max() < (
        DIRECTION_LIMIT)


@pytest.mark.parametrize("distance", [1.5 * u.au, 40 * u.au, 10 * u.pc])
def test_sources_with_a_distance(distance):
    # Parallax from the Earth's barycentric position and the site.
    times = series("2023-01-25T00:00", 60 * u.s, 2880)
    source = SkyCoord(ra=[10, 200] * u.deg, dec=[20, -30] * u.deg, distance=distance)
    fast = source_direction(source[:, np.newaxis], SITES[SOUTH], times)
    reference = rigorous_direction(source[:, np.newaxis], SITES[SOUTH], times)
    assert angle_between(fast, reference).max() < DIRECTION_LIMIT


@pytest.mark.parametrize("target_shape, time_shape", [((), (40,)), ((3, 1), (40,)),
                                                      ((2, 1, 1), (5, 8)), ((1,), (4, 10))])
def test_broadcast_shapes(target_shape, time_shape):
    n = int(np.prod(target_shape))
    target = sky_grid(max(n, 1)).reshape(target_shape) if target_shape else sky_grid(1)[0]
    times = (Time("2023-01-25T00:00") + np.arange(int(np.prod(time_shape))) * u.min).reshape(
        time_shape)
    fast = source_direction(target, SITES["YEBES"], times)
    assert fast.shape == np.broadcast_shapes(target_shape, time_shape) + (3,)
    assert angle_between(fast, rigorous_direction(target, SITES["YEBES"], times)).max() < (
        DIRECTION_LIMIT)


def test_when_the_fast_path_applies():
    times = Time("2023-01-25") + np.arange(100) * u.min
    site = SITES["YEBES"]
    ok = SkyCoord(ra=10 * u.deg, dec=20 * u.deg)
    assert fast_path_applies(ok, times)
    assert fast_path_applies(ok.transform_to(Galactic()), times)
    assert fast_path_applies(SkyCoord(ra=10 * u.deg, dec=20 * u.deg, distance=10 * u.pc), times)
    # Any number of epochs: EarthOrientation costs less than astropy at every N
    # (benchmarks/natural.py measures it).
    assert fast_path_applies(ok, times[0])
    assert fast_path_applies(ok, times[:2])
    assert fast_path_applies(None, times[:1])
    # Near sources, time-dependent frames, space motion, element-wise pairing
    # of targets and epochs, switched off.
    near = SkyCoord(ra=10 * u.deg, dec=20 * u.deg, distance=0.5 * u.au)
    assert not fast_path_applies(near, times)
    altaz = SkyCoord(az=10 * u.deg, alt=40 * u.deg, frame=AltAz(obstime=times[0], location=site))
    assert not fast_path_applies(altaz, times)
    moving = SkyCoord(ra=10 * u.deg, dec=20 * u.deg, pm_ra_cosdec=1 * u.mas / u.yr,
                      pm_dec=1 * u.mas / u.yr)
    assert not fast_path_applies(moving, times)
    paired = SkyCoord(ra=np.arange(100) * u.deg, dec=np.zeros(100) * u.deg)
    assert not fast_path_applies(paired, times)
    assert not fast_path_applies(paired, times[:3])  # shapes that do not broadcast
    assert fast_path_applies(paired[:, np.newaxis], times)
    with conf.set_temp("fast_path", False):
        assert not fast_path_applies(ok, times)
        assert not fast_path_applies(None, times)


@pytest.mark.parametrize("target, obstime, error", [
    (SkyCoord(ra=10 * u.deg, dec=20 * u.deg), 59969.0, "format cannot be guessed"),
    ("3C 84", Time("2023-01-25"), "target must be an astropy SkyCoord"),
])
def test_fast_path_applies_refuses_bad_input(target, obstime, error):
    with pytest.raises(TypeError, match=error):
        fast_path_applies(target, obstime)


def test_near_sources_take_the_rigorous_path():
    times = Time("2023-01-25") + np.arange(100) * u.min
    near = SkyCoord(ra=10 * u.deg, dec=20 * u.deg, distance=0.5 * u.au)
    assert np.array_equal(source_direction(near, SITES["YEBES"], times),
                          rigorous_direction(near, SITES["YEBES"], times))


@pytest.mark.parametrize("count", [1, 5, 16, 5760])
def test_teme_rotation_matches_astropy(count):
    # Reference: astropy's TEME -> ITRS frame transformation at every epoch.
    times = series("2023-01-25T00:00", 15 * u.s, count)
    rng = np.random.default_rng(5)
    teme = rng.normal(size=times.shape + (3,)) * 2.0e7
    rep = CartesianRepresentation(np.moveaxis(teme, -1, 0) * u.m)
    reference = TEME(rep, obstime=times).transform_to(ITRS(obstime=times))
    reference = np.moveaxis(reference.cartesian.xyz.to_value(u.m), 0, -1)
    # 1 mm at 20 000 km is 0.01 mas.
    assert np.abs(teme_to_itrs(teme, times) - reference).max() < 1e-3
    assert np.abs(EarthOrientation(times).teme_to_itrs(teme) - reference).max() < 1e-3


def test_nan_coordinates_propagate():
    times = Time("2023-01-25") + np.arange(50) * u.min
    target = SkyCoord(ra=[10, np.nan] * u.deg, dec=[20, 30] * u.deg)[:, np.newaxis]
    s = source_direction(target, SITES["YEBES"], times)
    assert np.all(np.isfinite(s[0])) and np.all(np.isnan(s[1]))


def test_network_directions_follow_the_fast_path_switch():
    # A network's directions (earth.diurnal) are the fast path's: with conf.fast_path off
    # each site takes astropy's transformation. Reference: astropy's ITRS(location=...).
    from astropy.coordinates import EarthLocation

    from astropy_feedrot.earth.diurnal import network_applies, network_directions

    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    times = Time("2020-01-08T20:00") + np.arange(0, 6 * 3600, 600) * u.s
    assert network_applies(crab, times)
    with conf.set_temp("fast_path", False):
        assert not network_applies(crab, times)
    assert not network_applies(SkyCoord(ra=83.6 * u.deg, dec=22.0 * u.deg,
                                        distance=1 * u.pc), times)
    assert not network_applies(SkyCoord([83.6, 84.0] * u.deg, [22.0, 22.0] * u.deg), times)
    sites = EarthLocation.from_geodetic([6.88, -3.09] * u.deg, [50.52, 40.52] * u.deg)
    xyz = np.stack([sites.x, sites.y, sites.z], axis=-1).to_value(u.m)
    s = network_directions(crab, xyz, times)
    for k in range(2):
        astropy = crab.transform_to(ITRS(obstime=times, location=sites[k])).cartesian
        # measured: 4e-4 mas
        np.testing.assert_allclose(s[:, k], astropy.xyz.value.T, rtol=0, atol=1e-3 * MAS)
