# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The natural grid's shared directions: each site's diurnal aberration, each antenna's angle."""

import warnings

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord, golden_spiral_grid
from astropy.time import Time

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    EquatorialMount,
    MirrorTrain,
    NasmythFocus,
    Rotator,
    XYMount,
    feed_rotation_grid,
    get_antenna,
)
from astropy_feedrot.earth.frames import location_xyz
from astropy_feedrot.engine.equations import Receivers, feed_rotation
from astropy_feedrot.engine.grid_natural import (
    diurnal_beta,
    fast_receiver,
    feed_rotation_block,
    shared_block,
    topocentric,
    traced_block,
    traced_receiver,
)

MAS = np.radians(1 / 3.6e6)


def receivers_of(antennas):
    return Receivers.from_mounts(
        [location_xyz(a.location) for a in antennas], [np.stack(a.local_frame) for a in antennas],
        [a.mount for a in antennas], [a.focus for a in antennas], [a.rotator for a in antennas])


def unit_sky(n=500, seed=3):
    p = np.random.default_rng(seed).normal(size=(n, 3))
    return p / np.linalg.norm(p, axis=-1, keepdims=True)


def test_topocentric_against_erfa_aberration():
    # Reference: ERFA ab (relativistic aberration) with the geocentre's velocity V
    # and with V + beta, beta from ERFA pvtob's speed of a site on the equator.
    p = unit_sky()
    v = np.array([9.8e-5, -2.1e-5, -0.9e-5])  # |V| ~ 30 km/s, in units of c
    site = np.array([6378137.0, 0.0, 0.0])
    beta = diurnal_beta(site)
    speed = np.linalg.norm(erfa.pvtob(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)[1])  # m/s
    assert np.isclose(np.linalg.norm(beta) * erfa.CMPS, speed, rtol=1e-6)

    def aberrated(velocity):
        return erfa.ab(p, velocity, 1e9, np.sqrt(1 - velocity @ velocity))

    geocentric, exact = aberrated(v), aberrated(v + beta)
    site_s = topocentric(geocentric, site, np.broadcast_to(v, p.shape))
    error = np.linalg.norm(np.cross(site_s, exact), axis=-1)
    assert error.max() < 2e-4 * MAS
    assert np.abs(np.linalg.norm(site_s, axis=-1) - 1).max() < 1e-11
    # The first order alone would be off by ~0.006 mas: the beta V term counts.
    first = geocentric + beta - (geocentric @ beta)[:, np.newaxis] * geocentric
    assert np.linalg.norm(np.cross(first, exact), axis=-1).max() > 10 * error.max()


SITE = EarthLocation.from_geodetic(-3.09 * u.deg, 40.52 * u.deg, 990 * u.m)


@pytest.mark.parametrize("mount, focus, rotator", [
    (AltAzMount(), None, None),
    (AltAzMount(), NasmythFocus("right"), None),
    (AltAzMount(), BeamWaveguideFocus("left"), None),
    (EquatorialMount(), None, None),
    (XYMount("north"), None, None),
    (XYMount("east"), None, Rotator("fixed", -45 * u.deg)),
    (AltAzMount(), None, Rotator("fixed", 30 * u.deg)),
    (AltAzMount(), NasmythFocus("right"), Rotator("sky", -20 * u.deg)),
])
@pytest.mark.parametrize("min_sine", [None, 0.1])
def test_block_is_the_engine_on_the_site_lines_of_sight(mount, focus, rotator, min_sine):
    # Reference: the engine (Eq 13 and the focus terms from lines of sight) on
    # the same topocentric directions; the block works from scalar products.
    antenna = Antenna(SITE, mount, focus, rotator=rotator)
    rx = receivers_of([antenna])
    assert fast_receiver(rx)
    s = unit_sky(600).reshape(20, 30, 3)
    s[0, 0] = [0.0, 0.0, 1.0]  # the pole: undefined (NaN) but for a sky rotator
    s[1, 0] = antenna.local_frame.up  # the zenith
    v = np.tile([9.8e-5, -2.1e-5, -0.9e-5], (30, 1))
    phase, below = feed_rotation_block(shared_block(s, v), rx, min_sine=min_sine)
    lines = topocentric(s, rx.station_xyz[0], v)
    lines /= np.linalg.norm(lines, axis=-1, keepdims=True)  # the engine's elevation needs it
    reference, ref_below = feed_rotation(rx, lines[..., np.newaxis, np.newaxis, :],
                                         min_sine=min_sine)
    reference = reference[..., 0, 0]
    assert np.array_equal(np.isnan(phase), np.isnan(reference))
    difference = np.abs(np.angle(np.exp(1j * (phase - reference))))
    # The same to rounding (1e-10 rad = 2e-5 mas: the elevation's arcsine near
    # the zenith); within an arcsecond of the pole or the fixed axis, where the
    # angle turns a million times faster than the line, to 1e-9.
    axis = rx.fixed_axis[0]
    near = ((np.linalg.norm(np.cross(lines, axis), axis=-1) < 5e-6)
            | (np.linalg.norm(lines[..., :2], axis=-1) < 5e-6))
    assert np.nanmax(np.where(near, 0.0, difference)) < 1e-10
    assert np.nanmax(difference) < 1e-9
    if min_sine is None:
        assert below is None and ref_below is None
    else:
        assert np.array_equal(below, ref_below[..., 0, 0])


@pytest.mark.parametrize("focus", [MirrorTrain.yebes40m("X"), MirrorTrain.yebes40m("S"),
                                   MirrorTrain.wark30m()])
@pytest.mark.parametrize("min_sine", [None, 0.1])
def test_traced_block_is_the_engine_on_the_site_lines_of_sight(focus, min_sine):
    # Reference: the engine tracing the mirrors on the same topocentric
    # directions; the block starts from the shared directions' components.
    antenna = Antenna(SITE, AltAzMount(), focus)
    rx = receivers_of([antenna])
    assert traced_receiver(rx) and not fast_receiver(rx)
    s = unit_sky(600).reshape(20, 30, 3)
    s[0, 0] = [0.0, 0.0, 1.0]  # near the pole and the zenith (aberration moves them)
    s[1, 0] = antenna.local_frame.up
    v = np.tile([9.8e-5, -2.1e-5, -0.9e-5], (30, 1))
    phase, below = traced_block(shared_block(s, v), rx, min_sine=min_sine)
    lines = topocentric(s, rx.station_xyz[0], v)
    lines /= np.linalg.norm(lines, axis=-1, keepdims=True)
    reference, ref_below = feed_rotation(rx, lines[..., np.newaxis, np.newaxis, :],
                                         min_sine=min_sine)
    reference = reference[..., 0, 0]
    assert np.array_equal(np.isnan(phase), np.isnan(reference))
    difference = np.abs(np.angle(np.exp(1j * (phase - reference))))
    assert np.nanmax(difference) < 1e-10
    if min_sine is None:
        assert below is None and ref_below is None
    else:
        assert np.array_equal(below, ref_below[..., 0, 0])


def test_traced_block_refuses_what_it_cannot_do():
    for antenna in (get_antenna("WETTZ13S"),  # a closed form: feed_rotation_block
                    Antenna(SITE, AltAzMount(), MirrorTrain.wark30m(),
                            rotator=Rotator("fixed", 10 * u.deg))):
        rx = receivers_of([antenna])
        assert not traced_receiver(rx)
        with pytest.raises(ValueError, match="one tracking antenna with a traced MirrorTrain"):
            traced_block(shared_block(np.array([[[0.6, 0.0, 0.8]]]), np.zeros((1, 3))), rx)


def test_block_refuses_what_it_cannot_do():
    rx = receivers_of([get_antenna("DBR205")])  # a stationary crossed dipole
    assert not fast_receiver(rx)
    s = np.array([[[0.6, 0.0, 0.8]]])
    with pytest.raises(ValueError, match="one tracking antenna with a closed-form focus"):
        feed_rotation_block(shared_block(s, np.zeros((1, 3))), rx)


def test_grid_with_every_kind_of_antenna_against_each_antenna():
    # Reference: Antenna.feed_rotation (its own topocentric directions) for
    # tracking, traced-mirror, rotator and stationary antennas in one grid.
    antennas = [get_antenna(name) for name in ("WETTZ13S", "YEBES40M", "WARK30M",
                                               "ASKAP32", "DBR205")]
    sky = golden_spiral_grid(30)
    sources = SkyCoord(sky.lon, sky.lat, frame="icrs")
    t = Time("2023-01-25T00:00") + np.arange(0, 24, 0.25) * u.hour
    grid = feed_rotation_grid(antennas, sources, t, min_elevation=5 * u.deg)
    for i, antenna in enumerate(antennas):
        one = antenna.feed_rotation(sources[:, np.newaxis], t, min_elevation=5 * u.deg).T
        assert np.array_equal(np.isnan(one), np.isnan(grid[:, i]))
        difference = np.abs((one - grid[:, i]).wrap_at(180 * u.deg)).to_value(u.mas)
        assert np.nanmax(difference) < 0.05


def test_grid_in_two_halves_is_the_grid_in_turn(monkeypatch):
    # Large grids compute two halves of the antennas at once (one on the helper
    # thread): every antenna's arithmetic is the same, so the same bits, and
    # the same warnings. On the helper thread itself the
    # grid runs in turn (it must not wait for its own thread).
    import astropy_feedrot.engine.grid_natural as grid_natural
    from astropy_feedrot.core.cache import helper_thread

    antennas = [get_antenna(name) for name in ("WETTZ13S", "YEBES40M", "WARK30M",
                                               "ASKAP32", "DBR205")]
    sources = SkyCoord([0, 90, 180] * u.deg, [89.99999, 20, -30] * u.deg)
    t = Time("2023-01-25T00:00") + np.arange(0, 24, 0.5) * u.hour

    def run():
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            out = feed_rotation_grid(antennas, sources, t, min_elevation=5 * u.deg)
        return out, [str(w.message) for w in record]

    monkeypatch.setattr(grid_natural, "PARALLEL_POINTS", 10**12)
    in_turn, message = run()
    monkeypatch.setattr(grid_natural, "PARALLEL_POINTS", 1)
    halves, halves_message = run()
    assert np.isnan(in_turn).any() and np.isfinite(in_turn).any()
    assert np.array_equal(in_turn, halves, equal_nan=True)
    assert halves_message == message
    on_helper, helper_message = helper_thread().submit(run).result(timeout=60)
    assert np.array_equal(in_turn, on_helper, equal_nan=True)
    assert helper_message == message
