# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The wind-up engine: new mounts and foci plug in once, and every front-end has them.

References: ERFA's ``hd2pa`` fed with hour angle and declination from
astropy's `HADec` frame, elevation and azimuth from astropy's `AltAz` frame
(Eqs 15, 38, 39, 41, independent of this package's vectors); the traced
mirror trains of Appendix C; Eq 17 (an equatorial mount does not rotate).
"""

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import AltAz, HADec
from helpers import DAY, MAS, SITES, max_angle_difference, sky_grid

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    EquatorialMount,
    Focus,
    MirrorTrain,
    Mount,
    NasmythFocus,
    StationaryMount,
    feed_rotation_grid,
)
from astropy_feedrot.applied.simulations import gps_svn76
from astropy_feedrot.core.kernel import wrap_phase
from astropy_feedrot.earth.frames import location_xyz
from astropy_feedrot.engine.equations import Receivers
from astropy_feedrot.engine.grid import receiver_arrays

SITE = SITES["YEBES"]
SOURCES = sky_grid(24)
TIMES = DAY[::3]  # 32 epochs over a day


@pytest.fixture(scope="module")
def sky():
    """Psi (ERFA), elevation and azimuth (astropy), shape (T, S), for SOURCES at SITE."""
    grid = SOURCES[np.newaxis, :]
    times = TIMES[:, np.newaxis]
    hadec = grid.transform_to(HADec(obstime=times, location=SITE))
    altaz = grid.transform_to(AltAz(obstime=times, location=SITE))
    lat = SITE.to_geodetic("WGS84").lat.rad
    return erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, lat), altaz.alt.rad, altaz.az.rad


class CoudeFocus(Focus):
    """The beam sent down the azimuth axis to a room fixed to the ground."""

    closed_form = (1, -1)


class TracedNasmyth(Focus):
    """A user's traced focus: the one-mirror Nasmyth train of MirrorTrain's example."""

    closed_form = None

    def __init__(self):
        self.train = MirrorTrain([[0, -1, 0]], feed_aligned=[0, 0, 1],
                                 feed_transverse=[1, 0, 0])

    def receiver_phase(self, s, t, axis, local):
        return self.train.receiver_phase(s, t, axis, local)


class OwnPhase(Focus):
    """A focus written before closed forms were declared: it only computes its phase."""

    def receiver_phase(self, s, t, axis, local):
        return MirrorTrain([[0, -1, 0]], feed_aligned=[0, 0, 1],
                           feed_transverse=[1, 0, 0]).receiver_phase(s, t, axis, local)


class PolarAxis(Mount):
    """A user's tracking mount: the first axis along the celestial pole."""

    def fixed_axis(self, local):
        return np.array([0.0, 0.0, 1.0])


def both_front_ends(antenna):
    """The feed rotation of SOURCES at TIMES from Antenna and from the grid, (T, S) rad."""
    one = antenna.feed_rotation(SOURCES[np.newaxis, :], TIMES[:, np.newaxis]).rad
    many = feed_rotation_grid([Antenna(SITES["DBR205"], StationaryMount()), antenna],
                              SOURCES, TIMES)[:, 1].rad
    return one, many


@pytest.mark.parametrize("focus, expected", [
    (CoudeFocus(), lambda psi, e, a: psi + e - a),  # Eq 39, right-handed
    (NasmythFocus("left"), lambda psi, e, a: psi - e),  # Eq 38, left-handed
    (TracedNasmyth(), lambda psi, e, a: psi + e + np.pi),  # MirrorTrain's example
    (OwnPhase(), lambda psi, e, a: psi + e + np.pi),
], ids=["user closed form", "Nasmyth left", "user traced focus", "user receiver_phase"])
def test_a_new_focus_plugs_in_once(sky, focus, expected):
    # The same numbers from Antenna and from feed_rotation_grid, both equal to
    # ERFA's parallactic angle plus astropy's elevation and azimuth.
    psi, e, a = sky
    up = e > np.radians(0.5)
    for phi in both_front_ends(Antenna(SITE, AltAzMount(), focus)):
        assert max_angle_difference(phi[up], expected(psi, e, a)[up]) < 1 * MAS


def test_a_new_mount_plugs_in_once():
    # Eq 17: a mount turning about the pole does not rotate the feed.
    for phi in both_front_ends(Antenna(SITE, PolarAxis())):
        assert np.nanmax(np.abs(phi)) < 1e-12
    equatorial = both_front_ends(Antenna(SITE, EquatorialMount()))[0]
    assert np.array_equal(np.isnan(equatorial), np.isnan(both_front_ends(
        Antenna(SITE, PolarAxis()))[0]))


def test_closed_forms_equal_their_traced_trains():
    # Appendix C: the built-in closed forms and the traced trains they stand for.
    nasmyth = both_front_ends(Antenna(SITE, AltAzMount(), NasmythFocus("right")))
    yebes = both_front_ends(Antenna(SITE, AltAzMount(), MirrorTrain.yebes40m("S")))
    bwg = both_front_ends(Antenna(SITE, AltAzMount(), BeamWaveguideFocus("right")))
    wark = both_front_ends(Antenna(SITE, AltAzMount(), MirrorTrain.wark30m()))
    for k in range(2):  # Antenna, then the grid
        assert np.nanmax(np.abs(wrap_phase(yebes[k] - nasmyth[k] - np.pi / 2))) < 1e-9
        constant = 2 * np.arctan(2500 / 9500) - np.pi  # MirrorTrain.wark30m's docstring
        assert np.nanmax(np.abs(wrap_phase(wark[k] - bwg[k] - constant))) < 1e-9


class Turned(StationaryMount):
    def dipoles(self, local):
        return local.north, -local.east, local.up


def test_stationary_dipoles_are_declared_not_recognised():
    # A ground-fixed crossed dipole turned by 90 deg: the grid evaluates it like
    # Antenna; only the plain arrays of wind_up cannot describe it.
    turned = Antenna(SITES["DBR205"], Turned())
    satellite = gps_svn76()
    times = DAY[32:48]
    grid = feed_rotation_grid([turned], [satellite], times)[:, 0, 0]
    assert max_angle_difference(grid.rad, turned.feed_rotation(satellite, times).rad) < 1e-12
    plain = Antenna(SITES["DBR205"], StationaryMount()).feed_rotation(satellite, times)
    assert max_angle_difference(grid.rad, plain.rad) > 0.1
    with pytest.raises(ValueError, match=r"antennas\[0\] .* has no closed form for wind_up"):
        receiver_arrays([turned])


def test_receivers_are_sorted_by_equation():
    antennas = [Antenna(SITE, StationaryMount()), Antenna(SITE, AltAzMount()),
                Antenna(SITE, AltAzMount(), NasmythFocus("right")),
                Antenna(SITE, AltAzMount(), MirrorTrain.wark30m())]
    rx = Receivers.from_mounts(np.stack([location_xyz(a.location) for a in antennas]),
                               np.stack([np.stack(a.local_frame) for a in antennas]),
                               [a.mount for a in antennas], [a.focus for a in antennas])
    assert len(rx) == 4
    assert rx.stationary_index.tolist() == [0]
    assert rx.plain_index.tolist() == [1]
    assert rx.focus_index.tolist() == [2]
    assert rx.traced_index.tolist() == [3]
    assert rx.as_arrays() is None
    assert rx.unrepresentable().tolist() == [3]
    assert "4 antennas, 1 stationary, 2 closed-form, 1 traced" in repr(rx)


class NoAxis(Mount):
    pass


class NoDipoles(Mount):
    tracks = False


class BadForm(Focus):
    def __init__(self, form):
        self.closed_form = form


class Untraced(Focus):
    closed_form = None


@pytest.mark.parametrize("mount, focus, error, match", [
    (NoAxis(), None, TypeError, r"NoAxis\(\) tracks but has no fixed_axis\(local\)"),
    (NoDipoles(), None, TypeError, r"NoDipoles\(\) does not track but has no dipoles\(local\)"),
    (AltAzMount(), BadForm("E"), TypeError,
     r"closed_form must be None or two numbers .* got 'E'"),
    (AltAzMount(), BadForm((1, 0, 0)), ValueError, r"closed_form must be None or two finite"),
    (AltAzMount(), BadForm((np.nan, 0)), ValueError, r"closed_form must be None or two finite"),
    (StationaryMount(), CoudeFocus(), ValueError,
     r"a StationaryMount has no optics to add terms; CoudeFocus\(\) needs a steerable mount"),
])
def test_what_a_receiver_must_declare(mount, focus, error, match):
    with pytest.raises(error, match=match):
        Antenna(SITE, mount, focus)


def test_a_focus_without_closed_form_must_trace():
    antenna = Antenna(SITE, AltAzMount(), Untraced())
    with pytest.raises(NotImplementedError, match=r"Untraced\(\) has no closed form .* "
                                                  r"override receiver_phase"):
        antenna.feed_rotation(SOURCES[0], TIMES)


def test_angles_are_the_methods_values():
    antenna = Antenna(SITE, AltAzMount(), NasmythFocus("left"))
    satellite = gps_svn76()
    times = DAY[32:48]
    angles = antenna.angles(satellite, times, min_elevation=10 * u.deg)
    azimuth, elevation = antenna.altaz(satellite, times)
    terms = antenna.feed_rotation_terms(satellite, times, min_elevation=10 * u.deg)
    expected = dict(azimuth=azimuth, elevation=elevation,
                    parallactic_angle=antenna.parallactic_angle(satellite, times),
                    transmitter=terms.transmitter, receiver=terms.receiver,
                    total=antenna.feed_rotation(satellite, times, min_elevation=10 * u.deg))
    for name, value in expected.items():
        assert np.array_equal(getattr(angles, name), value, equal_nan=True), name
    assert np.any(np.isnan(angles.total)) and not np.any(np.isnan(angles.elevation))


@pytest.mark.parametrize("positions", [False, True])
@pytest.mark.parametrize("nan_phase", [False, True])
def test_degenerate_mask_shape_and_values(positions, nan_phase):
    # The mask of degenerate angles: NaN phase where the target is finite and not
    # below the limit, written out here element by element; the same shape
    # whether or not any phase is NaN (then no target is looked at).
    from astropy_feedrot.engine.equations import degenerate

    rng = np.random.default_rng(3)
    n_e, n_a, n_s = 4, 2, 3
    phase = rng.uniform(-1, 1, (n_e, n_a, n_s))
    if nan_phase:
        phase[rng.uniform(size=phase.shape) < 0.5] = np.nan
    target = rng.normal(size=(n_e, n_s, 3) if positions else (n_e, n_a, n_s, 3))
    target[0, ..., 1] = np.nan  # missing data at the first epoch
    below = rng.uniform(size=(n_e, n_a, n_s)) < 0.3
    expected = np.zeros(phase.shape, dtype=bool)
    for i in np.ndindex(phase.shape):
        e, a, s = i
        point = target[e, s] if positions else target[i]
        expected[i] = np.isnan(phase[i]) and np.all(np.isfinite(point)) and not below[i]
    got = degenerate(phase, target, below, positions=positions)
    assert got.shape == phase.shape
    assert np.array_equal(got, expected)
    assert expected.any() == nan_phase
