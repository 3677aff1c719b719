# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation on grids: every receiver against the paper's equations as printed (explicit
matrices of Eqs 4 and 6) and the traced mirror trains of Appendix C; the grid's batched
orbits, attitudes and Earth orientation against Antenna one pair at a time; dask; errors."""

import sys
import warnings

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import ITRS, Angle, SkyCoord
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time
from helpers import SITES, sky_grid
from numpy.testing import assert_allclose

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    DegenerateGeometryWarning,
    EquatorialMount,
    FixedAxisMount,
    Focus,
    GregorianFocus,
    MirrorTrain,
    NasmythFocus,
    NominalAttitude,
    PrimeFocus,
    QuaternionAttitude,
    Satellite,
    SP3Orbit,
    StationaryMount,
    TLEOrbit,
    XYMount,
    conf,
    rotation_delay,
)
from astropy_feedrot.applied.simulations import genesis, gps_svn76
from astropy_feedrot.core import kernel as k
from astropy_feedrot.data import sample_file
from astropy_feedrot.earth.frames import LocalFrame, local_frame, location_xyz
from astropy_feedrot.earth.orientation import EarthOrientation
from astropy_feedrot.engine.grid import (
    feed_rotation_grid,
    feed_rotation_grid_dask,
    nominal_attitude,
    receiver_arrays,
    rotation_delay_grid,
    wind_up,
)
from astropy_feedrot.stations.catalogue import get_antenna
from astropy_feedrot.transmitters.attitude_interface import interpolated_sun_position, sun_position

#: The agreement promised with Antenna.feed_rotation, pair by pair.
TOLERANCE = 1e-6 * u.deg

DATE = Time("2023-01-25T00:00:00", scale="utc")

#: About 100 epochs over a day, irregularly spaced.
TIMES = DATE + np.cumsum(np.r_[0, np.full(99, 14.4) + np.sin(np.arange(99))]) * u.min

L1 = 1575.42 * u.MHz


def gps_like(k_plane, k_slot):
    orbit = TLEOrbit.from_elements(DATE, inclination=55 * u.deg, raan=60 * k_plane * u.deg,
                                   altitude=20200 * u.km, mean_anomaly=72 * k_slot * u.deg,
                                   satnum=90000 + 10 * k_plane + k_slot)
    return Satellite(orbit, name=f"GPS-like {k_plane}/{k_slot}")


@pytest.fixture(scope="module")
def antennas():
    # A GNSS antenna, an alt-az telescope 73 m away (Table 1), and one far away.
    return [get_antenna("DBR205"), get_antenna("FD-VLBA"), get_antenna("WETTZ13S")]


@pytest.fixture(scope="module")
def satellites():
    return [gps_svn76(), gps_like(1, 2), gps_like(4, 0)]


def assert_same_angle(grid_value, reference, tolerance=TOLERANCE, what=""):
    """Equal modulo 360 deg, with NaN at the same places."""
    grid_value, reference = Angle(grid_value), Angle(reference)
    assert np.array_equal(np.isnan(grid_value), np.isnan(reference)), what
    difference = (grid_value - reference).wrap_at(180 * u.deg)
    finite = np.isfinite(difference)
    assert np.all(np.abs(difference[finite]) < tolerance), what


def test_grid_agrees_with_antenna_pair_by_pair(antennas, satellites):
    # Reference: Antenna.feed_rotation, one antenna and one satellite per call.
    phi = feed_rotation_grid(antennas, satellites, TIMES)
    assert isinstance(phi, Angle) and phi.unit == u.deg
    assert phi.shape == (TIMES.size, 3, 3)
    for i, antenna in enumerate(antennas):
        for j, satellite in enumerate(satellites):
            assert_same_angle(phi[:, i, j], antenna.feed_rotation(satellite, TIMES))
    assert np.all(np.abs(phi) <= 180 * u.deg)


@pytest.mark.parametrize("form", ["beyerle", "wu"])
@pytest.mark.parametrize("min_elevation", [None, 10 * u.deg])
def test_forms_and_elevation_limit(antennas, satellites, form, min_elevation):
    phi = feed_rotation_grid(antennas, satellites, TIMES, form=form,
                             min_elevation=min_elevation)
    for i, antenna in enumerate(antennas):
        for j, satellite in enumerate(satellites):
            reference = antenna.feed_rotation(satellite, TIMES, form=form,
                                              min_elevation=min_elevation)
            assert_same_angle(phi[:, i, j], reference)
    if min_elevation is not None:
        # Below the horizon about half of the time.
        assert 0.2 < np.mean(np.isnan(phi)) < 0.8


# -- References: the paper's equations as printed, with explicit matrices -------------------


def printed_matrices(s):
    """P (Eq 4) and S_x (Eq 6), built element by element."""
    p = np.eye(3) - s[..., :, np.newaxis] * s[..., np.newaxis, :]
    sx = np.zeros(s.shape + (3,))
    sx[..., 0, 1], sx[..., 0, 2] = -s[..., 2], s[..., 1]
    sx[..., 1, 0], sx[..., 1, 2] = s[..., 2], -s[..., 0]
    sx[..., 2, 0], sx[..., 2, 1] = -s[..., 1], s[..., 0]
    return p, sx


def mat(m, v):
    return np.einsum("...ij,...j->...i", m, v)


def inner(a, b):
    return np.sum(a * b, axis=-1)


def eq8_transmitter(s, ta, tt):
    """Eq 8: t = P t^a + S_x t^t."""
    p, sx = printed_matrices(s)
    return mat(p, ta) + mat(sx, tt)


def eq7_fixed_axis(s, t, axis):
    """Eq 7 with the projected fixed axis r = P a (Eqs 10, 13, 35): tan = r^T S^T t / r^T t."""
    p, sx = printed_matrices(s)
    r = mat(p, np.broadcast_to(axis, s.shape))
    return np.arctan2(inner(r, mat(np.swapaxes(sx, -1, -2), t)), inner(r, t))


def eq30_beyerle(s, ra, rt, ta, tt):
    """Eq 30 (Eq 5): tan = (r^a P t^t + r^t P t^a) / (r^a P t^a - r^t P t^t)."""
    p, _ = printed_matrices(s)
    pta, ptt = mat(p, ta), mat(p, tt)
    return np.arctan2(inner(ra, ptt) + inner(rt, pta), inner(ra, pta) - inner(rt, ptt))


def eq31_wu(s, ra, rt, t):
    """Eq 31: tan = (r^a S^T t + r^t t) / (r^a t - r^t S^T t)."""
    _, sx = printed_matrices(s)
    sxt = mat(np.swapaxes(sx, -1, -2), t)
    return np.arctan2(inner(ra, sxt) + inner(rt, t), inner(ra, t) - inner(rt, sxt))


def elevation_azimuth(s, enu):
    """Elevation and azimuth (north through east) by their definitions."""
    east, north, up = enu
    return np.arcsin(inner(s, up)), np.arctan2(inner(s, east), inner(s, north))


class TurnedGnss(StationaryMount):
    """A GNSS antenna whose dipoles are turned by ``alpha`` from east towards north."""

    def __init__(self, alpha):
        self.alpha = alpha

    def dipoles(self, local):
        c, s = np.cos(self.alpha), np.sin(self.alpha)
        return c * local.east + s * local.north, c * local.north - s * local.east, local.up


class CoudeFocus(Focus):
    """A user's focus: the beam down the azimuth axis to the ground (Psi + E - A)."""

    closed_form = (1, -1)


#: The constant of MirrorTrain.wark30m (its docstring: 2 atan(2500/9500) - 180 deg).
WARK30M_CONSTANT = 2 * np.arctan(2500 / 9500) - np.pi

#: Every kind of receiver at once (name, antenna, reference): the references are
#: functions of the line of sight s, the transmitter's effective dipole t (Eq 8)
#: and dipoles, the site's east-north-up vectors, elevation E and azimuth A.
FD, DBR = SITES["FD-VLBA"], SITES["DBR205"]
EVERY_RECEIVER = [
    ("alt-az", Antenna(FD, AltAzMount()),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[2])),
    ("equatorial", Antenna(FD, EquatorialMount(), PrimeFocus()),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, [0, 0, 1.0])),
    ("X-Y north", Antenna(FD, XYMount("north"), GregorianFocus()),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[1])),
    ("X-Y east", Antenna(FD, XYMount("east")),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[0])),
    ("fixed axis", Antenna(FD, FixedAxisMount([1.0, 2.0, 3.0])),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, np.array([1, 2, 3]) / 14**0.5)),
    # Eqs 38-41: Psi-like term plus elevation (Nasmyth), minus azimuth (beam waveguide).
    ("Nasmyth right", Antenna(FD, AltAzMount(), NasmythFocus("right")),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[2]) + e),
    ("Nasmyth left", Antenna(FD, AltAzMount(), NasmythFocus("left")),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[2]) - e),
    ("BWG right", Antenna(FD, AltAzMount(), BeamWaveguideFocus("right")),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[2]) + e - a),
    ("BWG left", Antenna(FD, AltAzMount(), BeamWaveguideFocus("left")),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[2]) - e + a),
    ("user closed form", Antenna(FD, AltAzMount(), CoudeFocus()),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[2]) + e - a),
    # Traced mirror trains: the closed forms plus their documented constants.
    ("YEBES40M X", Antenna(FD, AltAzMount(), MirrorTrain.yebes40m("X")),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[2]) + e + np.pi / 2),
    ("WARK30M", Antenna(FD, AltAzMount(), MirrorTrain.wark30m()),
     lambda s, t, ta, tt, enu, e, a: eq7_fixed_axis(s, t, enu[2]) + e - a + WARK30M_CONSTANT),
    # Stationary crossed dipoles: Eq 30 with their dipoles (Eq 28).
    ("GNSS", Antenna(DBR, StationaryMount()),
     lambda s, t, ta, tt, enu, e, a: eq30_beyerle(s, enu[0], enu[1], ta, tt)),
    ("GNSS geocentric", Antenna(SITES["GGAO12M"], StationaryMount(), vertical="geocentric"),
     lambda s, t, ta, tt, enu, e, a: eq30_beyerle(s, enu[0], enu[1], ta, tt)),
    ("GNSS turned", Antenna(DBR, TurnedGnss(0.5)),
     lambda s, t, ta, tt, enu, e, a: eq30_beyerle(
         s, np.cos(0.5) * enu[0] + np.sin(0.5) * enu[1],
         np.cos(0.5) * enu[1] - np.sin(0.5) * enu[0], ta, tt)),
]


def test_every_mount_and_focus(satellites):
    # Every receiver in one grid (so the engine sorts them), each against the
    # paper's equation as printed for it, with the satellites' positions and
    # dipoles from the orbit and attitude models one by one.
    antennas = [antenna for _, antenna, _ in EVERY_RECEIVER]
    phi = feed_rotation_grid(antennas, satellites, TIMES, polarization="RCP")
    for j, satellite in enumerate(satellites):
        position = satellite.position(TIMES)
        ta, tt = satellite.attitude.dipoles(TIMES, position)
        for i, (name, antenna, reference) in enumerate(EVERY_RECEIVER):
            offset = position - location_xyz(antenna.location)
            s = offset / np.linalg.norm(offset, axis=-1, keepdims=True)  # Eq 2
            enu = np.stack(antenna.local_frame)
            e, a = elevation_azimuth(s, enu)
            expected = reference(s, eq8_transmitter(s, ta, tt), ta, tt, enu, e, a)
            assert_same_angle(phi[:, i, j], expected * u.rad, what=name)


def test_every_stationary_receiver_in_the_effective_dipole_form(satellites):
    # form="wu": Eq 31 as printed for the crossed dipoles; the telescopes unchanged.
    antennas = [antenna for _, antenna, _ in EVERY_RECEIVER]
    wu = feed_rotation_grid(antennas, satellites, TIMES, form="wu")
    beyerle = feed_rotation_grid(antennas, satellites, TIMES)
    for j, satellite in enumerate(satellites):
        position = satellite.position(TIMES)
        ta, tt = satellite.attitude.dipoles(TIMES, position)
        for i, (name, antenna, _) in enumerate(EVERY_RECEIVER):
            if antenna.mount.tracks:
                assert_same_angle(wu[:, i, j], beyerle[:, i, j])
                continue
            dipoles = antenna.mount.dipoles(antenna.local_frame)
            offset = position - location_xyz(antenna.location)
            s = offset / np.linalg.norm(offset, axis=-1, keepdims=True)
            expected = eq31_wu(s, dipoles[0], dipoles[1], eq8_transmitter(s, ta, tt))
            assert_same_angle(wu[:, i, j], expected * u.rad, what=name)


def test_natural_sources(antennas):
    # Natural sources (Eq 11) in every direction, LCP: against Antenna per source.
    sources = sky_grid(12)
    everyone = antennas + [Antenna(SITES["YEBES"], AltAzMount(), NasmythFocus("right")),
                           Antenna(SITES["YEBES"], AltAzMount(), MirrorTrain.yebes40m("S"))]
    phi = feed_rotation_grid(everyone, sources, TIMES, polarization="LCP")
    assert phi.shape == (TIMES.size, 5, 12)
    for i, antenna in enumerate(everyone):
        for j in range(12):
            reference = antenna.feed_rotation(sources[j], TIMES, polarization="LCP")
            assert_same_angle(phi[:, i, j], reference)


def test_natural_sources_few_epochs_and_scalar(antennas):
    # Fewer than 16 epochs: astropy's transformation at every epoch, as Antenna.
    sources = sky_grid(3)
    phi = feed_rotation_grid(antennas, sources, TIMES[:5])
    for i, antenna in enumerate(antennas):
        assert_same_angle(phi[:, i], antenna.feed_rotation(sources[:, np.newaxis], TIMES[:5]).T)
    one = feed_rotation_grid(antennas, sources[1], TIMES[7])
    assert one.shape == (3, 1)
    for i, antenna in enumerate(antennas):
        assert_same_angle(one[i, 0], antenna.feed_rotation(sources[1], TIMES[7]))


@pytest.mark.parametrize("fast_path", [True, False])
def test_scalar_and_few_epochs(antennas, satellites, fast_path):
    # A scalar time drops the time axis; below 16 epochs (or with the fast
    # path off) orbits go through astropy's TEME frame and the exact Sun.
    with conf.set_temp("fast_path", fast_path):
        one = feed_rotation_grid(antennas, satellites, TIMES[40])
        few = feed_rotation_grid(antennas, satellites, TIMES[40:60])
        for i, antenna in enumerate(antennas):
            for j, satellite in enumerate(satellites):
                assert_same_angle(one[i, j], antenna.feed_rotation(satellite, TIMES[40]))
                assert_same_angle(few[:, i, j], antenna.feed_rotation(satellite, TIMES[40:60]))
    assert one.shape == (3, 3)


def test_mixed_orbits_and_attitudes(antennas):
    # An SP3 orbit with ORBEX quaternions, a coordinate orbit, TLEs (one LCP).
    attitude = QuaternionAttitude.from_orbex(sample_file("sample.obx"), "G01")
    times = attitude.epochs[0] + np.linspace(0, 60, 20) * u.s
    sp3 = Satellite(SP3Orbit(sample_file("sample.sp3"), "G01", points=4), attitude)
    fixed = Satellite(SkyCoord(ITRS(x=-3e6 * u.m, y=-2.0e7 * u.m, z=1.5e7 * u.m,
                                    representation_type="cartesian")), NominalAttitude())
    satellites = [gps_svn76(), sp3, fixed, genesis()]
    phi = feed_rotation_grid(antennas, satellites, times)
    for i, antenna in enumerate(antennas):
        for j, satellite in enumerate(satellites):
            assert_same_angle(phi[:, i, j], antenna.feed_rotation(satellite, times))


def test_rotation_delay_agrees_with_baseline_function(antennas, satellites):
    # Reference: continuity.rotation_delay per satellite, with restarts below
    # the elevation limit and after long gaps.
    times = DATE + np.r_[np.arange(0, 300, 2.0), np.arange(400, 900, 2.0)] * u.min
    phi = feed_rotation_grid(antennas, satellites, times, min_elevation=10 * u.deg)
    delay, ambiguity = rotation_delay_grid(phi, L1, (0, 1), obstime=times,
                                           max_gap=30 * u.min)
    assert delay.shape == (times.size, 3) and delay.unit == u.ps
    assert_quantity_allclose(ambiguity, 634.75136789 * u.ps)  # Sec. 4.1: 634.8 ps
    for j, satellite in enumerate(satellites):
        reference = rotation_delay(antennas[0], antennas[1], satellite, times, L1,
                                   min_elevation=10 * u.deg, max_gap=30 * u.min)
        assert np.array_equal(np.isnan(delay[:, j]), np.isnan(reference.delay))
        finite = np.isfinite(reference.delay)
        # 1e-6 deg at L1 is 1.8e-6 ps.
        assert_quantity_allclose(delay[:, j][finite], reference.delay[finite], atol=2e-6 * u.ps)
    several, _ = rotation_delay_grid(phi, L1, [(0, 1), (1, 2), (2, 0)])
    assert several.shape == (times.size, 3, 3)
    assert_quantity_allclose(several[:, 0][np.isfinite(delay)],
                             rotation_delay_grid(phi, L1)[0][np.isfinite(delay)])


def test_wind_up_arrays_against_printed_equations():
    # Random geometry, each receiver against the paper's equation as printed
    # (explicit matrices): Eq 30 / Eq 31 for stationary crossed dipoles (Eq 28),
    # Eq 7 with the projected fixed axis for tracking antennas, and for alt-az
    # antennas with focus terms the traced mirror trains of Appendix C, which
    # reproduce Eqs 38-39 up to their constants.
    rng = np.random.default_rng(5)
    n_t, n_a, n_s = 7, 7, 5
    xyz = k.unit(rng.normal(size=(n_a, 3))) * 6.371e6  # on the Earth's surface
    enu = np.stack([np.stack(local_frame_of(x)) for x in xyz])
    stationary = np.array([True, False, True, False, False, False, False])
    axis = k.unit(rng.normal(size=(n_a, 3)))
    axis[3:] = enu[3:, 2]  # alt-az mounts for the foci
    terms = np.array([[0, 0], [0, 0], [0, 0], [0, 0], [1, 0], [1, -1], [-1, 1.0]])
    target = rng.normal(size=(n_t, n_s, 3)) * 2.6e7
    aligned = k.unit(rng.normal(size=(n_t, n_s, 3)))
    transverse = k.unit(np.cross(aligned, rng.normal(size=(n_t, n_s, 3))))
    offset = target[:, np.newaxis] - xyz[:, np.newaxis]
    s = offset / np.linalg.norm(offset, axis=-1, keepdims=True)  # (T, A, S, 3), Eq 2
    ta, tt = aligned[:, np.newaxis], transverse[:, np.newaxis]
    t = eq8_transmitter(s, ta, tt)

    def reference(form):
        out = np.empty((n_t, n_a, n_s))
        for i in range(n_a):
            e, n, up = enu[i]
            if stationary[i]:
                out[:, i] = (eq30_beyerle(s[:, i], e, n, ta[:, 0], tt[:, 0]) if form == "beyerle"
                             else eq31_wu(s[:, i], e, n, t[:, i]))
            elif not np.any(terms[i]):
                out[:, i] = eq7_fixed_axis(s[:, i], t[:, i], axis[i])
            else:
                local = LocalFrame(e, n, up)
                nasmyth = MirrorTrain.yebes40m("C").receiver_phase(s[:, i], t[:, i], up, local)
                bwg = MirrorTrain.wark30m().receiver_phase(s[:, i], t[:, i], up, local)
                conventional = eq7_fixed_axis(s[:, i], t[:, i], up)
                out[:, i] = {(1, 0): nasmyth - np.pi / 2,  # Psi + E
                             (1, -1): bwg - WARK30M_CONSTANT,  # Psi + E - A
                             (-1, 1): 2 * conventional - bwg + WARK30M_CONSTANT,  # Psi - E + A
                             }[tuple(terms[i])]
        return out

    for form in ("beyerle", "wu"):
        phi = wind_up(xyz, enu, stationary, target, aligned, transverse, fixed_axis=axis,
                      focus_terms=terms, form=form)
        assert phi.shape == (n_t, n_a, n_s)
        assert_allclose(k.wrap_phase(phi - reference(form)), 0, atol=1e-9)
        # The same lines of sight given as directions, per antenna: Eq 30 from
        # the vectors instead of the scalar products of positions.
        directed = wind_up(xyz, enu, stationary, s, aligned, transverse, fixed_axis=axis,
                           focus_terms=terms, form=form, directions=True)
        assert_allclose(k.wrap_phase(directed - phi), 0, atol=1e-12)
    # Eq 30 = Eq 31 when the transmitters face the receivers (Appendix A, Eqs A4-A5):
    # dipoles perpendicular to the line of sight of antenna 0, boresight -s.
    s0 = s[:, 0]
    facing = k.unit(np.cross(s0, rng.normal(size=s0.shape)))
    other = np.cross(facing, s0)  # facing x other = -s
    beyerle = wind_up(xyz[:1], enu[:1], [True], target, facing, other)
    wu = wind_up(xyz[:1], enu[:1], [True], target, facing, other, form="wu")
    assert_allclose(k.wrap_phase(beyerle - wu), 0, atol=1e-12)
    assert np.ptp(beyerle) > 1  # and not trivially
    # Natural sources: directions shared by all antennas, Eq 33 and Eq 13 as
    # printed, with the projected pole as the transmitter's dipole (Eq 11).
    sources = k.unit(rng.normal(size=(n_t, n_s, 3)))
    phi = wind_up(xyz, enu, stationary, sources, directions=True, fixed_axis=axis)
    p, _ = printed_matrices(sources)
    pole = mat(p, k.NORTH_POLE)
    for i in range(n_a):
        expected = (eq31_wu(sources, enu[i, 0], enu[i, 1], pole) if stationary[i]
                    else eq7_fixed_axis(sources, pole, axis[i]))
        assert_allclose(k.wrap_phase(phi[:, i] - expected), 0, atol=1e-12)


def local_frame_of(xyz):
    from astropy.coordinates import EarthLocation

    return local_frame(EarthLocation.from_geocentric(*xyz, unit=u.m))


def test_receiver_arrays(antennas):
    rx = receiver_arrays(antennas + [Antenna(SITES["YEBES"], EquatorialMount()),
                                     Antenna(SITES["YEBES"], AltAzMount(),
                                             BeamWaveguideFocus("left"))])
    assert rx.stationary.tolist() == [True, False, False, False, False]
    assert_allclose(rx.station_xyz[0], location_xyz(antennas[0].location))
    assert_allclose(rx.fixed_axis[3], [0, 0, 1])
    assert_allclose(rx.focus_terms[4], [-1, 1])
    assert_allclose(rx.station_axes[1], np.stack(antennas[1].local_frame))
    with pytest.raises(ValueError, match=r"antennas\[1\] .* has no closed form"):
        receiver_arrays([antennas[0], Antenna(SITES["YEBES"], AltAzMount(),
                                              MirrorTrain.yebes40m("X"))])


def test_nominal_attitude_matches_the_attitude_model():
    # Reference: NominalAttitude.dipoles (exact Sun) for each satellite; the
    # grid's Sun is interpolated from 15-min nodes (5e-14 rad).
    times = DATE + np.arange(0, 86400, 600) * u.s
    position = np.stack([gps_like(p, 1).position(times) for p in range(4)], axis=1)
    sun = interpolated_sun_position(EarthOrientation(times))
    sine = np.linalg.norm(np.cross(k.unit(sun), k.unit(sun_position(times))), axis=-1)
    assert np.all(sine < 1e-12)
    aligned, transverse = nominal_attitude(position, sun)
    assert aligned.shape == position.shape
    for j in range(4):
        reference = NominalAttitude().dipoles(times, position[:, j])
        assert_allclose(aligned[:, j], reference[0], atol=1e-12)
        assert_allclose(transverse[:, j], reference[1], atol=1e-12)


def test_degenerate_geometry_nan_and_one_warning(antennas):
    # A satellite fixed at the zenith of FD-VLBA: the parallactic angle is
    # undefined (Eq 15) at every epoch; NaN and one warning with the count.
    fd = antennas[1]
    above = location_xyz(fd.location) + 2e7 * fd.local_frame.up
    zenith = Satellite(SkyCoord(ITRS(*(above * u.m), representation_type="cartesian")))
    with pytest.warns(DegenerateGeometryWarning, match=f"undefined at {TIMES.size} of "
                      f"{3 * 2 * TIMES.size} grid points") as record:
        phi = feed_rotation_grid(antennas, [gps_svn76(), zenith], TIMES)
    assert len(record) == 1
    assert np.all(np.isnan(phi[:, 1, 1]))
    assert np.all(np.isfinite(phi[:, [0, 2], :])) and np.all(np.isfinite(phi[:, 1, 0]))
    # No warning below the elevation limit, or on dask: a satellite at the nadir
    # of FD-VLBA (on its fixed axis too) is below every antenna's horizon.
    nadir = Satellite(SkyCoord(ITRS(*((above - 4e7 * fd.local_frame.up) * u.m),
                                    representation_type="cartesian")))
    lazy = feed_rotation_grid_dask(antennas, [nadir], TIMES, min_elevation=0 * u.deg)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        feed_rotation_grid(antennas, [nadir], TIMES, min_elevation=0 * u.deg)
        assert np.all(np.isnan(lazy.compute()))


@pytest.mark.parametrize("natural", [False, True])
def test_dask_equals_numpy(antennas, satellites, natural):
    targets = sky_grid(4) if natural else satellites + [genesis()]
    everyone = antennas + [Antenna(SITES["YEBES"], AltAzMount(), MirrorTrain.yebes40m("C"))]
    eager = feed_rotation_grid(everyone, targets, TIMES, min_elevation=5 * u.deg)
    lazy = feed_rotation_grid_dask(everyone, targets, TIMES, min_elevation=5 * u.deg,
                                   chunks=13)
    assert lazy.shape == eager.shape
    assert lazy.chunks[0] == (13,) * 7 + (9,)
    values = lazy.compute()
    assert np.array_equal(np.isnan(values), np.isnan(eager.deg))
    # Natural sources: the same lines of sight, but the numpy grid takes the
    # angle of most antennas from scalar products (grid_natural), the dask path
    # from the engine: rounding, up to 1e-10 rad near the zenith and the pole.
    atol = 1e-8 if natural else 1e-12
    np.testing.assert_allclose(values, eager.deg, rtol=0, atol=atol)
    # Default chunks, and the scalar-time shape.
    np.testing.assert_allclose(feed_rotation_grid_dask(everyone, targets, TIMES).compute(),
                               feed_rotation_grid(everyone, targets, TIMES).deg,
                               rtol=0, atol=atol)
    one = feed_rotation_grid_dask(everyone, targets, TIMES[3])
    assert one.shape == eager.shape[1:]
    # Rotation delays straight from the dask array (only two columns computed).
    # (the GPS-like satellites: the low orbiter moves too far between samples)
    assert_quantity_allclose(rotation_delay_grid(lazy[:, :, :3], L1, (0, 1))[0],
                             rotation_delay_grid(eager[:, :, :3], L1, (0, 1))[0],
                             atol=1e-9 * u.ps)


def test_dask_distributed_local_cluster(antennas, satellites):
    distributed = pytest.importorskip("distributed")
    eager = feed_rotation_grid(antennas, satellites, TIMES)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=":0") as cluster:
        with distributed.Client(cluster) as client:
            lazy = feed_rotation_grid_dask(antennas, satellites, TIMES, chunks=25)
            values = client.compute(lazy).result()
            maximum = float(abs(lazy).max().compute())
    np.testing.assert_allclose(values, eager.deg, rtol=0, atol=1e-12)
    assert maximum == pytest.approx(float(np.nanmax(np.abs(eager.deg))))


def test_missing_dask_is_explained(antennas, satellites, monkeypatch):
    monkeypatch.setitem(sys.modules, "dask.array", None)
    with pytest.raises(ImportError, match=r"feed_rotation_grid_dask needs dask: python -m pip "
                                          r"install 'dask\[array\]'"):
        feed_rotation_grid_dask(antennas, satellites, TIMES)


# -- Errors -------------------------------------------------------------------------------


@pytest.mark.parametrize("antennas_arg, targets_arg, error, match", [
    ("one antenna", "satellites", TypeError, r"wrap a single antenna in a list: \[antenna\]"),
    ("a string", "satellites", TypeError, r"antennas\[0\] must be an Antenna, got str"),
    ("nothing", "satellites", ValueError, "antennas is empty"),
    (42, "satellites", TypeError, "antennas must be a sequence of Antenna objects, got int"),
    ("antennas", "one satellite", TypeError,
     r"wrap a single satellite in a list: \[satellite\]"),
    ("antennas", "mixed", TypeError,
     r"targets\[1\] must be a Satellite, got SkyCoord; put natural sources in one SkyCoord"),
    ("antennas", "nothing", ValueError, "targets is empty"),
    ("antennas", "3C 84", TypeError, "got a str '3C 84'"),
    ("antennas", 3.0, TypeError, "targets must be a sequence of Satellite objects or a "
                                 "SkyCoord, got float"),
])
def test_wrong_objects(antennas, satellites, antennas_arg, targets_arg, error, match):
    choices = {"one antenna": antennas[0], "a string": ["DBR205"], "nothing": [],
               "antennas": antennas, "satellites": satellites, "one satellite": satellites[0],
               "mixed": [satellites[0], SkyCoord("03h19m48s +41d30m42s")]}
    with pytest.raises(error, match=match):
        feed_rotation_grid(choices.get(antennas_arg, antennas_arg),
                           choices.get(targets_arg, targets_arg), TIMES)


def test_bad_options(antennas, satellites):
    with pytest.raises(ValueError, match=r"obstime must be a scalar or 1-d Time .* got shape "
                                         r"\(10, 10\)"):
        feed_rotation_grid(antennas, satellites, TIMES[:100].reshape(10, 10))
    with pytest.raises(ValueError, match=r"form must be one of \('beyerle', 'wu'\), got 'x'"):
        feed_rotation_grid(antennas, satellites, TIMES, form="x")
    with pytest.raises(ValueError, match="an LCP receiver does not receive the RCP signal"):
        feed_rotation_grid(antennas, satellites, TIMES, polarization="LCP")
    with pytest.raises(ValueError, match="polarization must be one of"):
        feed_rotation_grid(antennas, sky_grid(2), TIMES, polarization="X")
    with pytest.raises(ValueError, match=r"natural sources must be a scalar or 1-d SkyCoord "
                                         r"\(or 2-d for moving sources\), got shape "
                                         r"\(2, 2, 1\)"):
        feed_rotation_grid(antennas, sky_grid(4).reshape(2, 2, 1), TIMES)
    with pytest.raises(ValueError, match=r"moving sources \(a 2-d SkyCoord\) need one row per "
                                         r"epoch: shape \(2, 2\) for 100 epochs"):
        feed_rotation_grid(antennas, sky_grid(4).reshape(2, 2), TIMES)
    x = np.full((TIMES.size, 1), 2e7) * u.m
    column = Satellite(SkyCoord(ITRS(x=x, y=0 * x, z=x / 2, representation_type="cartesian")))
    with pytest.raises(ValueError, match=r"the orbit of targets\[0\] gives positions of shape "
                                         r"\(100, 100, 3\) for obstime of shape \(100,\); a "
                                         "grid needs one position per epoch"):
        feed_rotation_grid(antennas, [column], TIMES)
    with pytest.raises(u.UnitsError):
        feed_rotation_grid(antennas, satellites, TIMES, min_elevation=10 * u.m)


def test_wind_up_shape_errors():
    xyz = np.zeros((2, 3)) + [6.4e6, 0, 0]
    enu = np.tile(np.eye(3), (2, 1, 1))
    target = np.ones((4, 3, 3)) * 2e7
    with pytest.raises(ValueError, match=r"station_axes has shape \(3, 3, 3\), but "
                                         r"station_xyz of shape \(2, 3\) needs \(2, 3, 3\)"):
        wind_up(xyz, np.tile(np.eye(3), (3, 1, 1)), [True, False], target)
    with pytest.raises(ValueError, match=r"station_xyz must have shape \(A, 3\), got \(2, 2\)"):
        wind_up(xyz[:, :2], enu, [True, False], target)
    with pytest.raises(ValueError, match=r"stationary has shape \(3,\), but station_xyz of "
                                         r"shape \(2, 3\) needs \(2,\)"):
        wind_up(xyz, enu, [True, False, True], target)
    with pytest.raises(ValueError, match=r"fixed_axis has shape \(3,\), but"):
        wind_up(xyz, enu, [True, False], target, fixed_axis=[0, 0, 1])
    with pytest.raises(ValueError, match=r"focus_terms has shape \(2,\), but"):
        wind_up(xyz, enu, [True, False], target, focus_terms=[1, 0])
    with pytest.raises(ValueError, match=r"aligned has shape \(4, 2, 3\), but target of shape "
                                         r"\(4, 3, 3\) needs \(4, 3, 3\)"):
        wind_up(xyz, enu, [True, False], target, np.ones((4, 2, 3)), np.ones((4, 2, 3)))
    with pytest.raises(ValueError, match="give both aligned and transverse"):
        wind_up(xyz, enu, [True, False], target, aligned=target)
    with pytest.raises(ValueError, match=r"target positions must have shape \(T, S, 3\), got "
                                         r"\(4, 2, 3, 3\); for directions pass directions"):
        wind_up(xyz, enu, [True, False], np.ones((4, 2, 3, 3)))
    with pytest.raises(ValueError, match=r"target has shape \(4, 3, 3, 3\), but station_xyz "
                                         r"of shape \(2, 3\) needs \(T, 2, S, 3\)"):
        wind_up(xyz, enu, [True, False], np.ones((4, 3, 3, 3)), directions=True)
    with pytest.raises(ValueError, match=r"target directions must have shape \(T, S, 3\) or "
                                         r"\(T, A, S, 3\), got \(4, 3\)"):
        wind_up(xyz, enu, [True, False], np.ones((4, 3)), directions=True)
    with pytest.raises(ValueError, match="form must be one of"):
        wind_up(xyz, enu, [True, False], target, form="beyer")
    with pytest.raises(ValueError, match=r"sun has shape \(3,\), but position of shape "
                                         r"\(4, 3, 3\) needs \(4, 3\)"):
        nominal_attitude(target, [1.5e11, 0, 0])
    with pytest.raises(ValueError, match=r"position must have shape \(T, S, 3\), got \(3,\)"):
        nominal_attitude([2e7, 0, 0], [[1.5e11, 0, 0]])


def test_rotation_delay_grid_errors(antennas, satellites):
    phi = feed_rotation_grid(antennas, satellites, TIMES[:20])
    with pytest.raises(TypeError, match="feed_rotation must be an Angle .* got ndarray; wrap "
                                        "radians as Angle"):
        rotation_delay_grid(phi.rad, L1)
    with pytest.raises(ValueError, match=r"feed_rotation must have shape \(T, A, S\), got "
                                         r"\(3, 3\)"):
        rotation_delay_grid(phi[0], L1)
    with pytest.raises(ValueError, match=r"baseline must be a pair of antenna indices .* each "
                                         r"in 0..2, got \(0, 3\)"):
        rotation_delay_grid(phi, L1, (0, 3))
    with pytest.raises(ValueError, match="baseline must be a pair"):
        rotation_delay_grid(phi, L1, (0, 1, 2))
    with pytest.raises(ValueError, match="frequency must be positive"):
        rotation_delay_grid(phi, -L1)
    with pytest.raises(u.UnitsError):
        rotation_delay_grid(phi, 3 * u.m / u.kg)
    with pytest.raises(ValueError, match="max_gap needs obstime"):
        rotation_delay_grid(phi, L1, max_gap=1 * u.h)
