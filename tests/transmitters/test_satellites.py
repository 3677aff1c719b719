# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Satellites: orbits, attitude, the two terms, continuity and the rotation delay.

References: identities of the paper (Eq 20; Eq 30 = Eq 31 when the transmitter
faces the receiver, Appendix A), hand-built geometries worked out in the
comments, ERFA's GMST (``gmst82``) for the TEME rotation, Rodrigues' rotation
formula for quaternions, and the published numbers of Sec. 4.
"""

import re
import warnings

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import (
    GCRS,
    ITRS,
    TEME,
    CartesianRepresentation,
    EarthLocation,
    SkyCoord,
)
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time
from helpers import SITES, SP3_DESCRIPTORS, angle_spread, max_angle_difference
from numpy.testing import assert_allclose
from sgp4.api import Satrec

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    ContinuityWarning,
    CoordinateOrbit,
    DegenerateGeometryWarning,
    EquatorialMount,
    MirrorTrain,
    NasmythFocus,
    NominalAttitude,
    QuaternionAttitude,
    Satellite,
    SP3Orbit,
    StaleEarthOrientationWarning,
    StationaryMount,
    TLEOrbit,
    XYMount,
    rotation_delay,
    unwrap,
)
from astropy_feedrot.applied.simulations import (
    GPS_SVN76_TLE,
    genesis,
    genesis_long_baseline,
    gps_short_baseline,
    gps_svn76,
    paper_antenna,
)
from astropy_feedrot.core import kernel as k
from astropy_feedrot.earth.frames import location_xyz
from astropy_feedrot.earth.orientation import EarthOrientation
from astropy_feedrot.engine.grid import feed_rotation_grid
from astropy_feedrot.transmitters.attitude_interface import Attitude, sun_position
from astropy_feedrot.transmitters.nominal_attitude import nominal_dipoles
from astropy_feedrot.transmitters.orbits import Orbit, lagrange_interpolate
from astropy_feedrot.transmitters.quaternion_attitude import slerp

PASS = Time("2023-01-25T08:00") + np.arange(0, 7.5 * 3600, 120) * u.s


# --- orbits --------------------------------------------------------------------


def test_tle_errors_name_line_and_expectation():
    l1, l2 = GPS_SVN76_TLE
    with pytest.raises(ValueError, match="TLE line 1 must have 69 characters, got 68"):
        TLEOrbit(l1[:-1], l2)
    with pytest.raises(ValueError, match="TLE line 2 must start with '2 '"):
        TLEOrbit(l1, "3" + l2[1:])
    with pytest.raises(ValueError, match="TLE line 2 checksum: expected 2 in column 69, got '3'"):
        TLEOrbit(l1, l2[:-1] + "3")
    with pytest.raises(ValueError, match="different satellites: '41328' and '41329'"):
        TLEOrbit(l1, l2[:6] + "9" + l2[7:68] + str((int(l2[68]) + 1) % 10))
    with pytest.raises(TypeError, match="TLE line 1 must be a str, got bytes"):
        TLEOrbit(l1.encode(), l2)


def test_tle_epoch_and_repr():
    orbit = TLEOrbit(*GPS_SVN76_TLE, name="GPS SVN 76")
    # Epoch 23024.39332179: day 24.39332179 of 2023 (Table 2).
    assert abs((orbit.epoch - Time("2023-01-24T09:26:23.0", scale="utc")).to_value(u.s)) < 1
    assert "GPS SVN 76" in repr(orbit)


def test_teme_to_itrs_against_gmst_rotation():
    # Independent route: rotate TEME by GMST (IAU 1982, ERFA gmst82) about z.
    # Polar motion (< 0.5") is the only difference: < 100 m at 26,600 km.
    orbit = TLEOrbit(*GPS_SVN76_TLE)
    t = PASS[::20]
    itrs = orbit.position(t)
    error, r, _ = orbit._satrec.sgp4_array(np.ascontiguousarray(t.utc.jd1),
                                           np.ascontiguousarray(t.utc.jd2))
    assert np.all(error == 0)
    theta = erfa.gmst82(t.ut1.jd1, t.ut1.jd2)
    c, s = np.cos(theta), np.sin(theta)
    r = np.asarray(r) * 1e3
    pef = np.stack([c * r[:, 0] + s * r[:, 1], -s * r[:, 0] + c * r[:, 1], r[:, 2]], axis=-1)
    assert np.max(np.linalg.norm(itrs - pef, axis=-1)) < 100
    # GPS orbit radius ~ 26,560 km (a for 2.0056 rev/day).
    radius = np.linalg.norm(itrs, axis=-1)
    assert np.all((26.3e6 < radius) & (radius < 26.8e6))


def test_from_elements_genesis_orbit():
    orbit = genesis().orbit
    t = Time("2023-01-25") + np.arange(0, 3 * 3600, 60) * u.s
    # Back to an inertial frame to check the plane: inclination 97 deg.
    itrs = orbit.position(t)
    gcrs = SkyCoord(ITRS(CartesianRepresentation(itrs.T * u.m), obstime=t)).transform_to(
        GCRS(obstime=t))
    xyz = gcrs.cartesian.xyz.to_value(u.m).T
    normal = np.cross(xyz[:-1], xyz[1:]).mean(axis=0)
    inclination = np.degrees(np.arccos(normal[2] / np.linalg.norm(normal)))
    assert abs(inclination - 97) < 0.3
    radius = np.linalg.norm(itrs, axis=-1) / 1e3
    assert np.all(np.abs(radius - (6378.135 + 6000)) < 30)  # circular, ~6000 km altitude


def test_from_elements_mean_motion_and_errors():
    t = Time("2023-01-25")
    orbit = TLEOrbit.from_elements(t, inclination=55 * u.deg, raan=0 * u.deg,
                                   mean_motion=2.0056 * u.cycle / u.day)
    assert orbit.line2[52:63] == " 2.00560000"
    with pytest.raises(ValueError, match="exactly one of altitude and mean_motion"):
        TLEOrbit.from_elements(t, inclination=55 * u.deg, raan=0 * u.deg)
    with pytest.raises(ValueError, match="exactly one of altitude and mean_motion"):
        TLEOrbit.from_elements(t, inclination=55 * u.deg, raan=0 * u.deg,
                               altitude=1 * u.km, mean_motion=1 * u.cycle / u.day)
    with pytest.raises(ValueError, match="altitude must be positive"):
        TLEOrbit.from_elements(t, inclination=55 * u.deg, raan=0 * u.deg, altitude=-1 * u.km)
    with pytest.raises(ValueError, match="mean_motion must be positive"):
        TLEOrbit.from_elements(t, inclination=55 * u.deg, raan=0 * u.deg,
                               mean_motion=0 * u.cycle / u.day)
    with pytest.raises(ValueError, match=r"eccentricity must be in \[0, 1\)"):
        TLEOrbit.from_elements(t, inclination=55 * u.deg, raan=0 * u.deg,
                               altitude=1000 * u.km, eccentricity=1.5)
    with pytest.raises(ValueError, match="inclination must be within 0-180 deg"):
        TLEOrbit.from_elements(t, inclination=200 * u.deg, raan=0 * u.deg, altitude=1000 * u.km)
    with pytest.raises(u.UnitsError):
        TLEOrbit.from_elements(t, inclination=55 * u.m, raan=0 * u.deg, altitude=1000 * u.km)


def test_lagrange_interpolation_is_exact_for_polynomials():
    x = np.linspace(0, 900 * 20, 21)
    coefficients = np.array([3.0, -2e-3, 5e-7, 1e-12])
    y = np.polyval(coefficients, x)[:, np.newaxis] * [1.0, 2.0, -1.0]
    x_new = np.array([0.0, 123.4, 9000.1, 17999.0, 18000.0])
    expected = np.polyval(coefficients, x_new)[:, np.newaxis] * [1.0, 2.0, -1.0]
    assert_allclose(lagrange_interpolate(x, y, x_new, 4), expected, rtol=1e-10)
    assert_allclose(lagrange_interpolate(x, y, x_new, 10), expected, rtol=1e-9)
    # A NaN in the window propagates.
    y[10] = np.nan
    out = lagrange_interpolate(x, y, np.array([9000.1, 100.0]), 4)
    assert np.all(np.isnan(out[0])) and np.all(np.isfinite(out[1]))


def test_coordinate_orbit():
    t = Time("2023-01-25")
    xyz = [2.0e7, 1.0e7, 1.5e7]
    itrs = SkyCoord(ITRS(*(np.array(xyz) * u.m), obstime=t, representation_type="cartesian"))
    assert_allclose(CoordinateOrbit(itrs).position(t), xyz)
    # The same point in GCRS comes back (round trip through astropy, < 1 mm).
    gcrs = itrs.transform_to(GCRS(obstime=t))
    assert_allclose(CoordinateOrbit(gcrs).position(t), xyz, atol=1e-3)
    # A topocentric ITRS position.
    site = SITES["WETTZ13S"]
    geo = location_xyz(site)
    topo = SkyCoord(ITRS(*((np.array(xyz) - geo) * u.m), obstime=t, location=site,
                         representation_type="cartesian"))
    assert_allclose(CoordinateOrbit(topo).position(t), xyz, atol=1e-6)
    with pytest.raises(ValueError, match="needs a distance"):
        CoordinateOrbit(SkyCoord(ra=1 * u.deg, dec=2 * u.deg))
    with pytest.raises(TypeError, match="coord must be a SkyCoord, got list"):
        CoordinateOrbit(xyz)


# --- attitude --------------------------------------------------------------------


def test_nominal_attitude_geometry():
    t = PASS[::10]
    position = TLEOrbit(*GPS_SVN76_TLE).position(t)
    aligned, transverse = NominalAttitude().dipoles(t, position)
    boresight = np.cross(aligned, transverse)
    # Eq 26: boresight to the geocentre, orthonormal right-handed set,
    # transverse dipole perpendicular to the Sun direction (Eq 27).
    assert_allclose(boresight, -position / np.linalg.norm(position, axis=-1, keepdims=True),
                    atol=1e-12)
    assert_allclose(k.dot(aligned, transverse), 0, atol=1e-12)
    to_sun = k.unit(sun_position(t) - position)
    assert_allclose(k.dot(transverse, to_sun), 0, atol=1e-12)
    # The aligned dipole leans towards the Sun (solar panels face it).
    assert np.all(k.dot(aligned, to_sun) > 0)


def test_nominal_attitude_sun_collinear_gives_nan_and_one_warning():
    t = Time("2023-01-25T12:00")
    sun = k.unit(sun_position(t))
    positions = np.array([26.6e6 * sun, -26.6e6 * sun, [26.6e6, 0, 0]])
    with pytest.warns(DegenerateGeometryWarning, match="undefined at 2 of 3 epochs") as record:
        aligned, transverse = NominalAttitude().dipoles(t, positions)
    assert len(record) == 1
    assert np.all(np.isnan(transverse[:2])) and np.all(np.isfinite(transverse[2]))


def rodrigues(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    kx = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * kx @ kx


@pytest.mark.parametrize("axis,angle", [([0, 0, 1], 0.7), ([1, 2, 3], -2.1), ([0, 1, 0], 3.0)])
def test_quaternion_rows_are_the_body_axes(axis, angle):
    # A rotation R mapping body to Earth-fixed components has the body axes as
    # columns; its inverse (Earth to body) has them as rows (Eqs 24, 25).
    body_to_earth = rodrigues(axis, angle)
    unit_axis = np.asarray(axis, float) / np.linalg.norm(axis)
    q = np.r_[np.cos(angle / 2), np.sin(angle / 2) * unit_axis]  # body-to-Earth rotation
    t = Time("2023-01-25") + [0, 1] * u.min
    from_conjugate = QuaternionAttitude(t, [q, q], convention="body_to_earth")
    aligned, transverse = from_conjugate.dipoles(t[0], [2.6e7, 0, 0])
    assert_allclose(aligned, body_to_earth[:, 0], atol=1e-12)
    assert_allclose(transverse, body_to_earth[:, 1], atol=1e-12)
    conjugate = q * [1, -1, -1, -1]
    direct = QuaternionAttitude(t, [conjugate, conjugate])
    assert_allclose(direct.dipoles(t[0], [2.6e7, 0, 0])[0], body_to_earth[:, 0], atol=1e-12)


def test_slerp_and_interpolation():
    # Rotation about a fixed axis: interpolation is linear in the angle.
    t = Time("2023-01-25") + [0, 60, 120] * u.s
    angles = np.array([0.0, 0.9, 2.0])
    q = np.stack([np.cos(angles / 2), 0 * angles, 0 * angles, np.sin(angles / 2)], axis=-1)
    attitude = QuaternionAttitude(t, q)
    at = t[0] + [30, 60, 90, 120] * u.s
    got = attitude.quaternion(at)
    expected_angle = np.array([0.45, 0.9, 1.45, 2.0])
    assert_allclose(2 * np.arctan2(got[:, 3], got[:, 0]), expected_angle, atol=1e-12)
    # The shorter arc: q and -q are the same rotation.
    half = slerp(np.array([1.0, 0, 0, 0]), -np.array([1.0, 0, 0, 0]), 0.5)
    assert_allclose(np.abs(half), [1, 0, 0, 0], atol=1e-12)


def test_quaternion_validation():
    t = Time("2023-01-25") + [0, 60] * u.s
    slightly_off = np.array([[1.0005, 0, 0, 0], [1, 0, 0, 0]])
    assert_allclose(QuaternionAttitude(t, slightly_off).quaternions[0], [1, 0, 0, 0])
    with pytest.raises(ValueError, match="quaternion 0 at 2023-01-25T00:00:00.000 has norm 1.01"):
        QuaternionAttitude(t, [[1.01, 0, 0, 0], [1, 0, 0, 0]])
    with pytest.raises(ValueError, match=r"obstime has shape \(2,\), quaternions \(3, 4\)"):
        QuaternionAttitude(t, np.tile([1.0, 0, 0, 0], (3, 1)))
    with pytest.raises(ValueError, match="must increase strictly"):
        QuaternionAttitude(t[::-1], [[1, 0, 0, 0], [1, 0, 0, 0]])
    with pytest.raises(ValueError, match="convention must be one of"):
        QuaternionAttitude(t, [[1, 0, 0, 0], [1, 0, 0, 0]], convention="passive")
    with pytest.raises(ValueError, match="frame must be one of"):
        QuaternionAttitude(t, [[1, 0, 0, 0], [1, 0, 0, 0]], frame="eme2000")
    attitude = QuaternionAttitude(t, [[1, 0, 0, 0], [1, 0, 0, 0]])
    with pytest.raises(ValueError, match="outside the coverage .* 2023-01-25T00:00:00.000 to "
                                         "2023-01-25T00:01:00.000 UTC"):
        attitude.quaternion(t[0] - 1 * u.s)


def test_quaternions_in_gcrs_are_rotated_to_itrs():
    t = Time("2023-01-25") + [0, 60] * u.s
    attitude = QuaternionAttitude(t, [[1, 0, 0, 0], [1, 0, 0, 0]], frame="gcrs")
    aligned, _ = attitude.dipoles(t[0], [2.6e7, 0, 0])
    expected = SkyCoord(GCRS(CartesianRepresentation([1, 0, 0] * u.one), obstime=t[0])
                        ).transform_to(ITRS(obstime=t[0])).cartesian.xyz.value
    assert_allclose(aligned, expected, atol=1e-12)
    # Earth rotation: ITRS x is far from GCRS x at a random epoch.
    assert abs(aligned[0]) < 0.999


# --- satellites as targets --------------------------------------------------------


class FacingAttitude(Attitude):
    """A transmitter whose boresight points at a given site (t^b = -s)."""

    def __init__(self, site, gamma=0.3):
        self.site = location_xyz(site)
        self.gamma = gamma

    def dipoles(self, obstime, position):
        s = k.unit(position - self.site)
        helper = np.broadcast_to([0.0, 0.0, 1.0], s.shape)
        e1 = k.unit(np.cross(helper, s))
        e2 = np.cross(s, e1)
        aligned = np.cos(self.gamma) * e1 + np.sin(self.gamma) * e2
        return aligned, np.cross(aligned, s)  # a x (a x s) = -s: boresight on -s


def test_facing_attitude_is_right_handed():
    site = SITES["DBR205"]
    attitude = FacingAttitude(site)
    position = TLEOrbit(*GPS_SVN76_TLE).position(PASS[:3])
    a, t = attitude.dipoles(PASS[:3], position)
    s = k.unit(position - attitude.site)
    assert_allclose(np.cross(a, t), -s, atol=1e-12)


def test_beyerle_equals_wu_when_transmitter_faces_receiver():
    # Eq 30 = Eq 31 when the transmitter boresight is antiparallel to s (Sec. 3.1).
    site = SITES["DBR205"]
    satellite = Satellite(TLEOrbit(*GPS_SVN76_TLE), FacingAttitude(site))
    antenna = Antenna(site, StationaryMount())
    beyerle = antenna.feed_rotation(satellite, PASS)
    wu = antenna.feed_rotation(satellite, PASS, form="wu")
    assert max_angle_difference(beyerle.rad, wu.rad) < 1e-10


def test_beyerle_differs_from_wu_for_nadir_pointing_gnss():
    # Sec. 2.1: for GNSS satellites the forms differ by at most a few mrad.
    antenna = paper_antenna("DBR205")
    satellite = gps_svn76()
    _, el = antenna.altaz(satellite, PASS)
    up = el > 10 * u.deg
    d = max_angle_difference(antenna.feed_rotation(satellite, PASS).rad[up],
                             antenna.feed_rotation(satellite, PASS, form="wu").rad[up])
    assert 1e-6 < d < 5e-3


def test_hand_built_overhead_geometry():
    # A GNSS antenna at latitude 0, longitude 0 (east = y, north = z, up = x) and
    # a satellite straight overhead with body axes along ITRS (aligned x,
    # transverse y, boresight z). s = x; t = P x + x * y = z; the receiver's
    # effective dipole is 2y; Phi = atan2(x.(2y * z), 2y.z) = +90 deg (Eq 7).
    # Receiver term: 2y against the projected pole z: +90 deg; transmitter term:
    # z against z: 0.
    site = EarthLocation.from_geocentric(6378137.0, 0, 0, unit=u.m)
    t = Time("2023-01-25") + [0, 60] * u.s
    where = SkyCoord(ITRS(x=2.66e7 * u.m, y=0 * u.m, z=0 * u.m, obstime=t[0],
                          representation_type="cartesian"))
    satellite = Satellite(where, QuaternionAttitude(t, [[1, 0, 0, 0], [1, 0, 0, 0]]))
    gnss = Antenna(site, StationaryMount())
    assert_quantity_allclose(gnss.feed_rotation(satellite, t[0]), 90 * u.deg, atol=1e-9 * u.deg)
    terms = gnss.feed_rotation_terms(satellite, t[0])
    assert_quantity_allclose(terms.transmitter, 0 * u.deg, atol=1e-9 * u.deg)
    assert_quantity_allclose(terms.receiver, 90 * u.deg, atol=1e-9 * u.deg)
    # An equatorial telescope there: its feed is the projected pole z, which is t.
    polar = Antenna(site, EquatorialMount())
    assert_quantity_allclose(polar.feed_rotation(satellite, t[0]), 0 * u.deg, atol=1e-9 * u.deg)
    # An alt-az telescope looks at its zenith: undefined.
    with pytest.warns(DegenerateGeometryWarning):
        assert np.isnan(Antenna(site, AltAzMount()).feed_rotation(satellite, t[0]))


ANTENNAS = [
    (StationaryMount(), None),
    (AltAzMount(), None),
    (EquatorialMount(), None),
    (XYMount("north"), None),
    (AltAzMount(), NasmythFocus("left")),
    (AltAzMount(), BeamWaveguideFocus("right")),
    (AltAzMount(), MirrorTrain.yebes40m("S")),
    (AltAzMount(), MirrorTrain.wark30m()),
]


@pytest.mark.parametrize("mount,focus", ANTENNAS)
def test_split_terms_add_up_for_every_antenna(mount, focus):
    # Eq 20: Phi = Phi_tx + Phi_rx (modulo 2 pi), in the effective-dipole form.
    antenna = Antenna(SITES["FD-VLBA"], mount, focus)
    satellite = gps_svn76()
    terms = antenna.feed_rotation_terms(satellite, PASS)
    total = antenna.feed_rotation(satellite, PASS, form="wu")
    assert max_angle_difference(terms.total.rad, total.rad) < 1e-9
    assert max_angle_difference((terms.transmitter + terms.receiver).rad, total.rad) < 1e-9
    # The receiver term is the feed rotation of a natural source in the same
    # direction: for a telescope it does not depend on the transmitter.
    other = Satellite(gps_svn76().orbit, FacingAttitude(SITES["FD-VLBA"]))
    other_terms = antenna.feed_rotation_terms(other, PASS)
    assert max_angle_difference(other_terms.receiver.rad, terms.receiver.rad) < 1e-12


def test_mirror_train_traces_satellite_dipole():
    # Eqs 40, 41: with a satellite the traced train still equals the closed
    # form (receiver term) plus the transmitter term, up to the same constant.
    site = SITES["FD-VLBA"]
    satellite = gps_svn76()
    traced = Antenna(site, AltAzMount(), MirrorTrain.wark30m()).feed_rotation(satellite, PASS)
    closed = Antenna(site, AltAzMount(), BeamWaveguideFocus("right")).feed_rotation(
        satellite, PASS)
    spread, constant = angle_spread(traced.rad, closed.rad)
    assert spread < 1e-9
    assert_allclose(constant, 2 * np.arctan(2500 / 9500) - np.pi, atol=1e-9)


def test_lcp_on_both_ends_flips_signs():
    antenna = paper_antenna("FD-VLBA")
    rcp = Satellite(gps_svn76().orbit)
    lcp = Satellite(gps_svn76().orbit, polarization="LCP")
    assert_quantity_allclose(antenna.feed_rotation(lcp, PASS), -antenna.feed_rotation(rcp, PASS))
    terms_r = antenna.feed_rotation_terms(rcp, PASS)
    terms_l = antenna.feed_rotation_terms(lcp, PASS, polarization="LCP")
    assert_quantity_allclose(terms_l.transmitter, -terms_r.transmitter)
    assert_quantity_allclose(terms_l.receiver, -terms_r.receiver)


def test_satellite_errors():
    orbit = TLEOrbit(*GPS_SVN76_TLE)
    with pytest.raises(TypeError, match=r"did you mean NominalAttitude\(\)\?"):
        Satellite(orbit, NominalAttitude)
    with pytest.raises(TypeError, match="attitude must be a NominalAttitude or "
                                        "QuaternionAttitude instance, got str"):
        Satellite(orbit, "nominal")
    with pytest.raises(TypeError, match="orbit must be a TLEOrbit, SP3Orbit, CoordinateOrbit "
                                        "or a SkyCoord with a distance, got tuple"):
        Satellite(GPS_SVN76_TLE)
    with pytest.raises(ValueError, match="polarization must be one of"):
        Satellite(orbit, polarization="H")
    antenna = paper_antenna("FD-VLBA")
    with pytest.raises(ValueError, match="an RCP receiver does not receive the LCP signal"):
        antenna.feed_rotation(Satellite(orbit, polarization="LCP"), PASS, polarization="RCP")
    with pytest.raises(ValueError, match=r"form must be one of \('beyerle', 'wu'\)"):
        antenna.feed_rotation(Satellite(orbit), PASS, form="exact")


def test_below_horizon_is_computed_and_can_be_masked():
    antenna = paper_antenna("FD-VLBA")
    satellite = gps_svn76()
    t = Time("2023-01-25T02:00") + np.arange(0, 8 * 3600, 600) * u.s
    _, el = antenna.altaz(satellite, t)
    assert np.any(el < 0 * u.deg)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        phi = antenna.feed_rotation(satellite, t)
        masked = antenna.feed_rotation(satellite, t, min_elevation=10 * u.deg)
    assert np.all(np.isfinite(phi))
    assert np.array_equal(np.isnan(masked), el < 10 * u.deg)
    assert_quantity_allclose(masked[el >= 10 * u.deg], phi[el >= 10 * u.deg])


# --- continuity and the rotation delay --------------------------------------------


def test_unwrap_restarts_after_mask_and_gap():
    values = np.array([170.0, -170.0, -150.0, 170.0, -170.0]) * u.deg
    assert_quantity_allclose(unwrap(values), [170, 190, 210, 170, 190] * u.deg)
    masked = unwrap(values, mask=[False, False, True, False, False])
    assert_quantity_allclose(masked[[0, 1, 3, 4]], [170, 190, 170, 190] * u.deg)
    t = Time("2023-01-25") + [0, 60, 120, 3600, 3660] * u.s
    # Without the gap limit, the sample after the gap joins the old cycle.
    values = np.array([170.0, -170.0, -150.0, -170.0, 170.0]) * u.deg
    assert_quantity_allclose(unwrap(values), [170, 190, 210, 190, 170] * u.deg)
    assert_quantity_allclose(unwrap(values, obstime=t, max_gap=10 * u.min),
                             [170, 190, 210, -170, -190] * u.deg)


def test_unwrap_axis_units_and_warning():
    series = np.array([[3.0, -3.0], [0.1, 0.2]])
    out = unwrap(series, axis=-1)
    assert out.unit == u.rad
    assert_allclose(out.value, [[3.0, 2 * np.pi - 3.0], [0.1, 0.2]])
    assert_allclose(unwrap(series.T, axis=0).value, out.value.T)
    # 0 -> 170 and 170 -> 350 (= -10) are both steps of more than 162 deg.
    with pytest.warns(ContinuityWarning, match="2 consecutive steps exceed 162 deg"):
        unwrap([0, 170, -10] * u.deg)
    with pytest.raises(ValueError, match="max_gap needs obstime"):
        unwrap([0, 1] * u.deg, max_gap=1 * u.s)
    with pytest.raises(ValueError, match=r"angle has shape \(2,\), obstime has shape \(3,\)"):
        unwrap([0, 1] * u.deg, obstime=Time("2023-01-25") + [0, 1, 2] * u.s, max_gap=1 * u.s)


def test_rotation_delay_definition_and_errors():
    a1, a2 = paper_antenna("DBR205"), paper_antenna("FD-VLBA")
    satellite = gps_svn76()
    f = 1575.42 * u.MHz
    result = rotation_delay(a1, a2, satellite, PASS, f)
    phi = unwrap(a2.feed_rotation(satellite, PASS) - a1.feed_rotation(satellite, PASS))
    assert_quantity_allclose(result.delay * 2 * np.pi * f, phi.to(u.rad).value * u.one,
                             atol=1e-9 * u.one)
    # Sec. 4.1: "The phase ambiguity interval ... is 634.8 ps".
    assert_quantity_allclose(result.ambiguity, 634.8 * u.ps, atol=0.05 * u.ps)
    with pytest.raises(ValueError, match="frequency must be positive"):
        rotation_delay(a1, a2, satellite, PASS, 0 * u.Hz)
    with pytest.raises(u.UnitsError):
        rotation_delay(a1, a2, satellite, PASS, 1 * u.m / u.s)
    with pytest.raises(TypeError, match="antenna2 must be an Antenna, got str"):
        rotation_delay(a1, "FD-VLBA", satellite, PASS, f)
    # Two identical antennas: no delay.
    same = rotation_delay(a2, a2, satellite, PASS, f)
    assert_quantity_allclose(same.delay, 0 * u.ps, atol=1e-12 * u.ps)


# --- Section 4 of the paper -----------------------------------------------------


@pytest.fixture(scope="module")
def gps_table():
    return gps_short_baseline(step=60 * u.s)


def test_gps_pass_times(gps_table):
    # Sec. 4.1 (and its figures): above 10 deg near 08:06 to 15:07 UTC.
    visible = gps_table["both_visible"]
    rise, set_ = gps_table["time"][visible][[0, -1]]
    assert abs((rise - Time("2023-01-25T08:06")).to_value(u.min)) <= 2
    assert abs((set_ - Time("2023-01-25T15:07")).to_value(u.min)) <= 2


def test_gps_satellite_term_is_common_on_short_baseline(gps_table):
    visible = gps_table["both_visible"]
    d = k.wrap_phase(np.radians(gps_table["FD-VLBA_transmitter"] - gps_table["DBR205_transmitter"]))
    # 73 m at 20,000 km: directions differ by ~0.8", so the terms nearly cancel.
    assert np.max(np.abs(np.degrees(d[visible]))) < 0.01
    # ... while the receiver terms differ widely (Fig. 10).
    drx = k.wrap_phase(np.radians(gps_table["FD-VLBA_receiver"] - gps_table["DBR205_receiver"]))
    assert np.max(np.abs(np.degrees(drx[visible]))) > 90


def test_gps_rotation_delay_spans_hundreds_of_ps(gps_table):
    delay = gps_table["rotation_delay"].quantity[gps_table["both_visible"]]
    span = np.nanmax(delay) - np.nanmin(delay)
    # Sec. 4.1: "at the level of hundreds of picoseconds - a significant fraction
    # of this ambiguity interval" (634.8 ps).
    assert 100 * u.ps < span < 634.8 * u.ps
    assert np.all(np.isfinite(delay))


def test_genesis_satellite_term_differs_on_long_baseline():
    table = genesis_long_baseline(step=120 * u.s)
    visible = table["both_visible"]
    assert visible.sum() > 10
    d = k.wrap_phase(np.radians(table["WETTZ13S_transmitter"] - table["GGAO12M_transmitter"]))
    # Sec. 4.2: "noticeably different between the two observing telescopes".
    assert np.max(np.abs(np.degrees(d[visible]))) > 30
    assert table.meta["satellite"] == "GENESIS"


# --- SP3 orbits and ORBEX attitude ---------------------------------------------------


def write_sp3(path, satellite, times, positions_m):
    """Write positions as a minimal SP3-c file (GPS time tags, km)."""
    header = [
        f"#cP{times[0].datetime.strftime('%Y %m %d %H %M')}  0.00000000 {len(times):6d} "
        "ORBIT IGS20 HLM  IGS",
        "## 2246 259200.00000000   900.00000000 59969 0.0000000000000",
        f"+    1   {satellite}" + "  0" * 16,
    ] + ["+          " + "  0" * 17] * 4 + ["++         " + "  0" * 17] * 5 + SP3_DESCRIPTORS + [
        "/* WRITTEN BY THE TESTS FROM SGP4 POSITIONS",
    ]
    lines = list(header)
    gps = (times.tai - 19 * u.s)  # GPS time tags
    for t, xyz in zip(gps, positions_m / 1e3):
        y, mo, d, h, mi, s = t.ymdhms
        lines.append(f"*  {y:4d} {mo:2d} {d:2d} {h:2d} {mi:2d} {s:11.8f}")
        lines.append(f"P{satellite}{xyz[0]:14.6f}{xyz[1]:14.6f}{xyz[2]:14.6f}     0.000000")
    lines.append("EOF")
    path.write_text("\n".join(lines) + "\n")


def test_sp3_orbit_interpolates_to_millimetres(tmp_path):
    # Independent reference: SGP4 positions of GPS SVN 76 tabulated every
    # 15 min (to 1 mm, the SP3 resolution) and interpolated back at 1-min
    # epochs with the default 10-point window.
    tle = TLEOrbit(*GPS_SVN76_TLE)
    grid = Time("2023-01-25T06:00", scale="utc") + np.arange(0, 12 * 3600 + 1, 900) * u.s
    path = tmp_path / "svn76.sp3"
    write_sp3(path, "G05", grid, tle.position(grid))
    orbit = SP3Orbit(path, "G05")
    fine = Time("2023-01-25T08:00", scale="utc") + np.arange(0, 6 * 3600, 60) * u.s
    error = np.linalg.norm(orbit.position(fine) - tle.position(fine), axis=-1)
    assert error.max() < 0.005  # 5 mm (0.5 mm rounding of the file + interpolation)
    # A satellite of the file as a target.
    satellite = Satellite(orbit, name="G05")
    phi = paper_antenna("FD-VLBA").feed_rotation(satellite, fine)
    reference = paper_antenna("FD-VLBA").feed_rotation(Satellite(tle), fine)
    assert max_angle_difference(phi.rad, reference.rad) < 1e-8


def test_sp3_orbit_errors():
    from astropy_feedrot.data import sample_file

    with pytest.raises(ValueError, match="satellite 'G02' is not in the SP3 file; it has "
                                         "G01, G05, E11"):
        SP3Orbit(sample_file("sample.sp3"), "G02")
    with pytest.raises(ValueError, match="has 4 epochs, fewer than the 10 points"):
        SP3Orbit(sample_file("sample.sp3"), "G01")
    with pytest.raises(ValueError, match="points must be at least 2"):
        SP3Orbit(sample_file("sample.sp3"), "G01", points=1)
    # 2.5 was cut to 2 (linear interpolation, km-level errors) without a word.
    for points in (2.5, 4.0, "4", True):
        with pytest.raises(TypeError, match=r"^points must be a whole number of epochs \(int\), "
                                            rf"got {re.escape(repr(points))}$"):
            SP3Orbit(sample_file("sample.sp3"), "G01", points=points)
    assert SP3Orbit(sample_file("sample.sp3"), "G01", points=np.int64(4)).points == 4
    orbit = SP3Orbit(sample_file("sample.sp3"), "G01", points=4)
    with pytest.raises(ValueError, match="outside the coverage of the SP3 orbit of G01: "
                                         r"2023-01-25T00:00:19.000 to 2023-01-25T00:45:19.000 TAI"):
        orbit.position(Time("2023-01-25T01:00", scale="tai"))
    assert "G01" in repr(orbit)


def test_orbex_attitude_as_transmitter():
    from astropy_feedrot.data import sample_file
    from astropy_feedrot.io import read_orbex

    attitude = QuaternionAttitude.from_orbex(sample_file("sample.obx"), "G01")
    data = read_orbex(sample_file("sample.obx"))
    times, quaternions = data.attitude["G01"]
    # At a tabulated epoch the dipoles are the rows of the file's quaternion (Eqs 24-25).
    aligned, transverse = attitude.dipoles(times[1], [0, 0, 0])
    q = quaternions[1] / np.linalg.norm(quaternions[1])
    w, x, y, z = q
    assert_allclose(aligned, [w * w + x * x - y * y - z * z, 2 * (x * y - w * z),
                              2 * (x * z + w * y)], atol=1e-12)
    assert_allclose(transverse, [2 * (x * y + w * z), w * w - x * x + y * y - z * z,
                                 2 * (y * z - w * x)], atol=1e-12)
    orbit = SP3Orbit(sample_file("sample.sp3"), "G01", points=4)
    satellite = Satellite(orbit, attitude, name="G01")
    phi = paper_antenna("WETTZ13S").feed_rotation(satellite, times)
    assert phi.shape == (3,) and np.all(np.isfinite(phi))
    with pytest.raises(ValueError, match="satellite 'G02' has no attitude in the ORBEX file; "
                                         "it has G01, G05, E11"):
        QuaternionAttitude.from_orbex(sample_file("sample.obx"), "G02")


# --- the object API on many epochs: one Earth orientation, batch interfaces -----

#: A GPS pass over the short baseline at 2 s (1500 epochs: the fast path).
DENSE = Time("2023-01-25T08:30") + np.arange(0, 3000, 2) * u.s


class ExactNominalAttitude(Attitude):
    """Eqs 26-27 with the Sun computed exactly at every epoch (the path before nodes)."""

    def dipoles(self, obstime, position):
        return nominal_dipoles(position, sun_position(obstime))


def exact_positions(tle, obstime):
    """ITRS positions from SGP4 at every epoch, rotated by astropy's TEME -> ITRS."""
    e, r, _ = Satrec.twoline2rv(tle.line1, tle.line2).sgp4_array(
        np.ascontiguousarray(obstime.utc.jd1), np.ascontiguousarray(obstime.utc.jd2))
    assert np.all(e == 0)
    rep = CartesianRepresentation(np.moveaxis(np.asarray(r), -1, 0) * u.km)
    return SkyCoord(TEME(rep, obstime=obstime)).transform_to(ITRS(obstime=obstime))


@pytest.fixture(scope="module")
def dense_pair():
    """The object API and the exact path (SGP4 and the Sun at every epoch) on DENSE."""
    tle = TLEOrbit(*GPS_SVN76_TLE)
    exact = Satellite(CoordinateOrbit(exact_positions(tle, DENSE)), ExactNominalAttitude())
    return Satellite(tle), exact


@pytest.mark.parametrize("name", ["DBR205", "FD-VLBA", "WETTZ13S"])
def test_object_api_matches_the_exact_path(dense_pair, name):
    # Reference: SGP4 and the Sun at every epoch, astropy's TEME -> ITRS. The
    # nodes (SGP4 within 0.1 mm, the Sun within 1e-10 rad) move angles by < 1e-6 deg.
    fast, exact = dense_pair
    antenna = paper_antenna(name) if name != "WETTZ13S" else Antenna(SITES[name], AltAzMount())
    phi = antenna.feed_rotation(fast, DENSE)
    reference = antenna.feed_rotation(exact, DENSE)
    assert np.all(np.isfinite(phi))
    assert max_angle_difference(phi.rad, reference.rad) < np.deg2rad(1e-6)


def test_object_api_equals_the_grid():
    # The same computation one antenna and one satellite at a time: equal to 1e-9 deg.
    antennas = [paper_antenna("DBR205"), paper_antenna("FD-VLBA"),
                Antenna(SITES["WETTZ13S"], AltAzMount(), NasmythFocus("right"))]
    satellites = [gps_svn76(), genesis()]
    phi = feed_rotation_grid(antennas, satellites, DENSE)
    for i, antenna in enumerate(antennas):
        for j, satellite in enumerate(satellites):
            one = antenna.feed_rotation(satellite, DENSE)
            assert max_angle_difference(phi[:, i, j].rad, one.rad) < np.deg2rad(1e-9)


def test_masked_epochs_stay_nan_on_the_fast_path():
    times = DENSE.copy()
    times[[0, 7, 8, 1499]] = np.ma.masked
    satellite = gps_svn76()
    antenna = paper_antenna("FD-VLBA")
    phi = antenna.feed_rotation(satellite, times)
    reference = antenna.feed_rotation(satellite, DENSE)
    masked = np.zeros(DENSE.shape, dtype=bool)
    masked[[0, 7, 8, 1499]] = True
    assert np.all(np.isnan(phi[masked])) and np.all(np.isfinite(phi[~masked]))
    assert max_angle_difference(phi.rad[~masked], reference.rad[~masked]) < np.deg2rad(1e-9)
    los = satellite.line_of_sight(SITES["FD-VLBA"], times)
    for vector in (los.s, los.aligned, los.transverse):
        assert np.all(np.isnan(vector[masked])) and np.all(np.isfinite(vector[~masked]))


def test_orbit_positions_of_mixed_orbits():
    # Reference: each orbit's own position(); element sets go together.
    times = DENSE[:300]
    itrs = TLEOrbit(*GPS_SVN76_TLE).position(times)
    coordinate = CoordinateOrbit(SkyCoord(ITRS(*(itrs.T * u.m), representation_type="cartesian",
                                               obstime=times)))
    orbits = [TLEOrbit(*GPS_SVN76_TLE), coordinate, genesis().orbit]
    orientation = EarthOrientation(times)
    xyz = Orbit.positions(orbits, times, orientation)
    assert xyz.shape == (3, 300, 3)
    for i, o in enumerate(orbits):
        assert_allclose(xyz[i], o.position(times), rtol=0, atol=1e-6)
        assert_allclose(xyz[i], o.position(times, orientation), rtol=0, atol=1e-6)
    assert_allclose(xyz[1], itrs, rtol=0, atol=1e-6)
    assert_allclose(TLEOrbit.batch_positions(orbits[::2], times), xyz[::2], rtol=0, atol=1e-6)


def test_orbit_positions_errors():
    times = DENSE[:20]
    gps = TLEOrbit(*GPS_SVN76_TLE)
    with pytest.raises(TypeError, match=r"orbits\[1\] must be an Orbit, got str"):
        Orbit.positions([gps, "ISS"], times)
    x = np.full((3, 1), 2e7) * u.m
    column = CoordinateOrbit(SkyCoord(ITRS(x=x, y=0 * x, z=x / 2,
                                           representation_type="cartesian")))
    with pytest.raises(ValueError, match=r"gives positions of shape \(3, 20, 3\) for obstime "
                                         r"of shape \(20,\); a batch of orbits needs one "
                                         "position per epoch"):
        Orbit.positions([gps, column], times)
    with pytest.raises(ValueError, match=r"orientation is for epochs of shape \(19,\), obstime "
                                         r"has shape \(20,\)"):
        Orbit.positions([gps], times, EarthOrientation(times[:19]))
    with pytest.raises(ValueError, match=r"orientation is for epochs of shape \(19,\)"):
        gps.position(times, EarthOrientation(times[:19]))
    with pytest.raises(TypeError, match="orientation must be an EarthOrientation or None, "
                                        "got str"):
        gps.position(times, "fast")


def test_nominal_attitude_with_earth_orientation():
    # The Sun from the orientation's nodes (1e-10 rad) against the exact Sun.
    times = DENSE[::10]
    position = TLEOrbit(*GPS_SVN76_TLE).position(times)
    exact = NominalAttitude().dipoles(times, position)
    fast = NominalAttitude().dipoles(times, position, EarthOrientation(times))
    for a, b in zip(exact, fast):
        assert_allclose(a, b, rtol=0, atol=1e-9)


def test_dipoles_many_equals_each_model():
    # Reference: each model's own dipoles(); the nominal ones share one Sun.
    times = DENSE[:300]
    orbits = [TLEOrbit(*GPS_SVN76_TLE), genesis().orbit, TLEOrbit(*GPS_SVN76_TLE)]
    positions = Orbit.positions(orbits, times)
    quaternions = QuaternionAttitude(times[[0, -1]], [[1, 0, 0, 0], [0.8, 0, 0, 0.6]])
    attitudes = [NominalAttitude(), FacingAttitude(SITES["DBR205"]), quaternions]
    orientation = EarthOrientation(times)
    aligned, transverse = Attitude.dipoles_many(attitudes, times, positions, orientation)
    assert aligned.shape == transverse.shape == positions.shape
    for i, attitude in enumerate(attitudes):
        a, t = attitude.dipoles(times, positions[i])
        assert_allclose(aligned[i], a, rtol=0, atol=1e-9)
        assert_allclose(transverse[i], t, rtol=0, atol=1e-9)
    assert NominalAttitude.needs_sun and not Attitude.needs_sun
    assert not QuaternionAttitude.needs_sun


def test_dipoles_many_warns_once_for_all_satellites():
    t = Time("2023-01-25T12:00")
    sun = k.unit(sun_position(t))
    positions = np.array([26.6e6 * sun, -26.6e6 * sun, [26.6e6, 0, 0]])
    with pytest.warns(DegenerateGeometryWarning, match="undefined at 2 of 3 epochs") as record:
        aligned, transverse = Attitude.dipoles_many([NominalAttitude()] * 3, t, positions)
    assert len(record) == 1
    assert np.all(np.isnan(transverse[:2])) and np.all(np.isfinite(transverse[2]))


def test_dipoles_many_errors():
    t = DENSE[:3]
    positions = np.zeros((2, 3, 3))
    with pytest.raises(TypeError, match=r"attitudes\[1\] must be an Attitude, got type"):
        Attitude.dipoles_many([NominalAttitude(), NominalAttitude], t, positions)
    with pytest.raises(ValueError, match=r"positions must hold one array per attitude: shape "
                                         r"\(3, \.\.\., 3\), got \(2, 3, 3\)"):
        Attitude.dipoles_many([NominalAttitude()] * 3, t, positions)
    with pytest.raises(ValueError, match=r"orientation is for epochs of shape \(2,\)"):
        Attitude.dipoles_many([NominalAttitude()] * 2, t, positions, EarthOrientation(t[:2]))
    with pytest.raises(NotImplementedError, match="QuaternionAttitude does not take its dipoles "
                                                  r"from the Sun \(needs_sun is False\)"):
        QuaternionAttitude(t[:1], [[1, 0, 0, 0]]).sun_dipoles([1, 0, 0], [0, 1, 0])


def test_no_earth_orientation_unless_used():
    # An ITRS position and ITRS quaternions need no Earth orientation: a year
    # after the end of (faked) tables there is nothing to warn about. A TLE
    # orbit (TEME -> ITRS) or the nominal attitude (the Sun) use it, and warn once.
    from astropy.utils import iers

    table = iers.IERS_Auto.open()
    fake = table[table["MJD"].to_value(u.day) <= 59215.0]  # to 2021-01-01
    fake.meta["predictive_mjd"] = 58850.0
    fake.meta["predictive_index"] = int(np.searchsorted(fake["MJD"].to_value(u.day), 58850.0))
    times = Time("2022-01-01T00:00") + np.arange(20) * u.min
    fixed = CoordinateOrbit(SkyCoord(ITRS(x=2e7 * u.m, y=1e7 * u.m, z=1e7 * u.m,
                                          representation_type="cartesian")))
    tabulated = QuaternionAttitude(times[[0, -1]], [[1, 0, 0, 0], [1, 0, 0, 0]])
    antenna = paper_antenna("FD-VLBA")
    with iers.earth_orientation_table.set(fake):
        phi = antenna.feed_rotation(Satellite(fixed, tabulated), times)  # no warning
        assert np.all(np.isfinite(phi))
        elements = TLEOrbit.from_elements(times[0], inclination=55 * u.deg, raan=0 * u.deg,
                                          altitude=20200 * u.km)
        for satellite in (Satellite(fixed), Satellite(elements, tabulated)):
            with pytest.warns(StaleEarthOrientationWarning, match="past the predictions") as w:
                antenna.feed_rotation(satellite, times)
            assert len(w) == 1


def test_antennas_in_turn_share_the_transmitter_and_its_warnings():
    """A second antenna at the same epochs reuses the satellite's positions and
    dipoles, gets the same numbers as a satellite computed afresh, and gets the
    orbit's warnings again (here: an element set 40 days from its epoch)."""
    from astropy_feedrot import OrbitWarning

    times = Time("2023-03-06T00:00") + np.arange(0, 3600, 60) * u.s  # 40 days on
    shared = Satellite(TLEOrbit(*GPS_SVN76_TLE))
    first = Antenna(SITES["DBR205"], StationaryMount())
    second = Antenna(SITES["FD-VLBA"], AltAzMount())
    with pytest.warns(OrbitWarning, match="days from the epoch of their element set"):
        first.feed_rotation(shared, times)
    with pytest.warns(OrbitWarning, match="days from the epoch of their element set") as caught:
        reused = second.feed_rotation(shared, times)
    assert [w.filename for w in caught] == [__file__]
    with pytest.warns(OrbitWarning):
        fresh = second.feed_rotation(Satellite(TLEOrbit(*GPS_SVN76_TLE)), times)
    assert np.array_equal(reused, fresh, equal_nan=True)
    with pytest.warns(OrbitWarning):
        los = shared.line_of_sight(second.location, times)
    los.aligned[:] = 0  # the returned arrays are the caller's: what is kept stays
    with pytest.warns(OrbitWarning):
        again = second.feed_rotation(shared, times)
    assert np.array_equal(again, fresh, equal_nan=True)
