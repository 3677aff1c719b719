# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The fast path: interpolated Earth orientation against astropy at every epoch."""

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import (
    ITRS,
    TEME,
    AltAz,
    CartesianRepresentation,
    Galactic,
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
from astropy_feedrot.earth import EarthOrientation
from astropy_feedrot.frames import _fast_path_applies, source_direction
from astropy_feedrot.orbits import teme_to_itrs

#: The accuracy the fast path promises against the rigorous path.
LIMIT = 0.1 * MAS


def angle_between(a, b):
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


def rigorous_direction(target, site, times):
    with conf.set_temp("fast_path", False):
        return source_direction(target, site, times)


@pytest.mark.parametrize("site", ["FD-VLBA", "WETTZ13S", "WARKWORTH"])
def test_directions_over_the_sky_and_a_day(site):
    # Reference: astropy's ICRS -> ITRS(location) transformation at every epoch.
    sources = sky_grid(30)[:, np.newaxis]
    times = Time("2023-01-25T00:00", scale="utc") + np.arange(0, 86400, 97) * u.s
    fast = source_direction(sources, SITES[site], times)
    assert fast.shape == (30, times.size, 3)
    assert angle_between(fast, rigorous_direction(sources, SITES[site], times)).max() < LIMIT


def test_sparse_epochs_over_years_and_a_leap_second():
    # Epochs scattered over 2012-2022 (nodes only where needed), and one
    # minute around the leap second at the end of 2016.
    rng = np.random.default_rng(3)
    scattered = Time("2012-01-01", scale="utc") + np.sort(rng.uniform(0, 3650, 200)) * u.day
    leap = Time("2016-12-31T23:59:30", scale="utc") + np.arange(61) * u.s
    times = Time(np.concatenate([scattered.jd, leap.jd]), format="jd", scale="utc")
    source = SkyCoord("12h29m06.7s +02d03m09s")
    orientation = EarthOrientation(times)
    assert orientation.nodes.size <= 4 * times.size
    fast = source_direction(source, SITES["GGAO12M"], times)
    assert angle_between(fast, rigorous_direction(source, SITES["GGAO12M"], times)).max() < LIMIT


def test_step_sets_the_accuracy():
    # The error of the cubic grows as step**4: 0.002 mas at 30 min, below
    # 0.1 mas still at 1 h (as conf.fast_path_step documents).
    source = SkyCoord(ra=80 * u.deg, dec=-10 * u.deg)
    times = Time("2023-01-25T00:00") + np.arange(0, 2 * 86400, 61) * u.s
    reference = rigorous_direction(source, SITES["YEBES"], times)
    errors = {}
    for minutes in (30, 60):
        with conf.set_temp("fast_path_step", minutes):
            errors[minutes] = angle_between(source_direction(source, SITES["YEBES"], times),
                                            reference).max()
    assert errors[30] < 0.005 * MAS
    assert errors[60] < LIMIT
    assert 8 < errors[60] / errors[30] < 24
    # The default step (15 min) is 16 times better again.
    assert angle_between(source_direction(source, SITES["YEBES"], times),
                         reference).max() < 0.001 * MAS


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


@pytest.mark.parametrize("mount, focus", MOUNTS)
def test_feed_rotation_matches_the_rigorous_path(mount, focus):
    antenna = Antenna(SITES["WETTZ13S"], mount, focus)
    sources = sky_grid(12)[:, np.newaxis]
    times = Time("2023-01-25T00:00") + np.arange(0, 86400, 300) * u.s
    fast = antenna.feed_rotation(sources, times, min_elevation=-5 * u.deg)
    with conf.set_temp("fast_path", False):
        rigorous = antenna.feed_rotation(sources, times, min_elevation=-5 * u.deg)
    assert np.array_equal(np.isfinite(rigorous), np.isfinite(fast))
    # Within 0.1 deg of the zenith, angles that involve the azimuth change
    # by 1/sin(z) times any change of direction; leave those epochs out.
    _, elevation = antenna.altaz(sources, times)
    finite = np.isfinite(rigorous) & (elevation < 89.9 * u.deg)
    # Equatorial: 0 either way (exactly or to rounding).
    difference = (fast - rigorous).wrap_at(180 * u.deg).to_value(u.rad)[finite]
    assert np.abs(difference).max() < LIMIT


@pytest.mark.parametrize("target_shape, time_shape", [((), (40,)), ((3, 1), (40,)),
                                                      ((2, 1, 1), (5, 8)), ((1,), (4, 10))])
def test_broadcast_shapes(target_shape, time_shape):
    n = int(np.prod(target_shape))
    target = sky_grid(max(n, 1)).reshape(target_shape) if target_shape else sky_grid(1)[0]
    times = (Time("2023-01-25T00:00") + np.arange(int(np.prod(time_shape))) * u.min).reshape(
        time_shape)
    fast = source_direction(target, SITES["YEBES"], times)
    assert fast.shape == np.broadcast_shapes(target_shape, time_shape) + (3,)
    assert angle_between(fast, rigorous_direction(target, SITES["YEBES"], times)).max() < LIMIT


def test_when_the_fast_path_applies():
    times = Time("2023-01-25") + np.arange(100) * u.min
    site = SITES["YEBES"]
    ok = SkyCoord(ra=10 * u.deg, dec=20 * u.deg)
    assert _fast_path_applies(ok, times, times.shape)
    assert _fast_path_applies(ok.transform_to(Galactic()), times, times.shape)
    assert _fast_path_applies(SkyCoord(ra=10 * u.deg, dec=20 * u.deg, distance=10 * u.pc),
                              times, times.shape)
    # Too few epochs, near sources (diurnal parallax), time-dependent frames,
    # space motion, element-wise pairing of targets and epochs, switched off.
    assert not _fast_path_applies(ok, times[:10], (10,))
    near = SkyCoord(ra=10 * u.deg, dec=20 * u.deg, distance=0.5 * u.au)
    assert not _fast_path_applies(near, times, times.shape)
    altaz = SkyCoord(az=10 * u.deg, alt=40 * u.deg, frame=AltAz(obstime=times[0], location=site))
    assert not _fast_path_applies(altaz, times, times.shape)
    moving = SkyCoord(ra=10 * u.deg, dec=20 * u.deg, pm_ra_cosdec=1 * u.mas / u.yr,
                      pm_dec=1 * u.mas / u.yr)
    assert not _fast_path_applies(moving, times, times.shape)
    paired = SkyCoord(ra=np.arange(100) * u.deg, dec=np.zeros(100) * u.deg)
    assert not _fast_path_applies(paired, times, times.shape)
    with conf.set_temp("fast_path", False):
        assert not _fast_path_applies(ok, times, times.shape)


def test_near_sources_take_the_rigorous_path():
    times = Time("2023-01-25") + np.arange(100) * u.min
    near = SkyCoord(ra=10 * u.deg, dec=20 * u.deg, distance=0.5 * u.au)
    assert np.array_equal(source_direction(near, SITES["YEBES"], times),
                          rigorous_direction(near, SITES["YEBES"], times))


def test_teme_rotation_matches_astropy():
    # Reference: astropy's TEME -> ITRS frame transformation at every epoch.
    times = Time("2023-01-25T00:00") + np.arange(0, 86400, 150) * u.s
    rng = np.random.default_rng(5)
    teme = rng.normal(size=times.shape + (3,)) * 2.0e7
    fast = teme_to_itrs(teme, times)
    rep = CartesianRepresentation(np.moveaxis(teme, -1, 0) * u.m)
    reference = TEME(rep, obstime=times).transform_to(ITRS(obstime=times))
    reference = np.moveaxis(reference.cartesian.xyz.to_value(u.m), 0, -1)
    # 1 mm at 20 000 km is 0.01 mas.
    assert np.abs(fast - reference).max() < 1e-3


def test_nan_coordinates_propagate():
    times = Time("2023-01-25") + np.arange(50) * u.min
    target = SkyCoord(ra=[10, np.nan] * u.deg, dec=[20, 30] * u.deg)[:, np.newaxis]
    s = source_direction(target, SITES["YEBES"], times)
    assert np.all(np.isfinite(s[0])) and np.all(np.isnan(s[1]))


@pytest.mark.parametrize("step, error", [(0 * u.min, "step must be positive"),
                                         (-1 * u.min, "step must be positive")])
def test_bad_step(step, error):
    with pytest.raises(ValueError, match=error):
        EarthOrientation(Time("2023-01-25") + np.arange(3) * u.min, step=step)
