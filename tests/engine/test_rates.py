# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rates of the feed rotation.

References: a centred difference of `Antenna.feed_rotation` through astropy's
full transformation at every epoch (``conf.fast_path = False``), computed here
with its own stencil; the classical rates of the parallactic angle, azimuth
and elevation (spherical trigonometry, derived in ``docs/rates.rst``); the CIP
as astropy's CIRS pole seen in ITRS; the closed forms of Eqs 38-39 for the
mirror trains of Appendix C.

The step of the reference difference, h = 0.01 s: its truncation error
h^2 |Phi'''| / 6 is below 1e-12 rad/s at 1 deg from a singular direction
(|Phi'''| ~ (omega / sin 1 deg)^3 ~ 7e-8 rad/s^3), and its rounding error,
with angles that scatter as if the epochs were rounded to ~2e-10 s, is
2e-10 s * |Phi'| / h ~ 5e-11 rad/s there (measured: 5e-10 rad/s at h = 1 ms,
1e-10 rad/s from 3 ms to 30 ms, 7e-10 rad/s at 0.3 s).
"""

import types
import warnings

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import CIRS, ITRS, AltAz, SkyCoord
from astropy.time import Time
from astropy.utils import iers
from helpers import SITES, sky_grid

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    CassegrainFocus,
    DegenerateGeometryWarning,
    EquatorialMount,
    FixedAxisMount,
    MirrorTrain,
    NasmythFocus,
    Satellite,
    StaleEarthOrientationWarning,
    StationaryMount,
    TLEOrbit,
    XYMount,
    conf,
)
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
from astropy_feedrot.core.kernel import NORTH_POLE, project, receiver_term, wrap_phase
from astropy_feedrot.earth.frames import (
    LocalFrame,
    horizontal,
    local_frame,
    location_xyz,
    source_direction,
)
from astropy_feedrot.engine import rates
from astropy_feedrot.transmitters.attitude_interface import sun_position

OMEGA = rates.EARTH_ROTATION_ANGLE_RATE
T0 = Time("2023-01-25T20:00:00", scale="utc")
JULY = Time("2023-07-01T03:00:00", scale="utc")  # polar motion 0.54 arcsec, fast nutation
STEP = 0.01  # s, see the module docstring
TOLERANCE = 1e-9  # rad/s
TILT = [0.3, -0.2, 1.0]  # east-north-up axis of a tilted FixedAxisMount, 21 deg from up


def rigorous_rate(antenna, target, obstime, h=STEP, **kwargs):
    """Centred difference of the feed rotation through astropy's transformation."""
    with conf.set_temp("fast_path", False):
        ahead = antenna.feed_rotation(target, obstime + h * u.s, **kwargs).rad
        behind = antenna.feed_rotation(target, obstime - h * u.s, **kwargs).rad
    return wrap_phase(ahead - behind) / (2 * h)


def separation(s, v):
    """Angle (rad) between unit vectors s (..., 3) and v (3,)."""
    return np.arccos(np.clip(s @ v, -1, 1))


def ring(site, obstime, center, radii, n=12):
    """ICRS directions at ``radii`` (deg) around the ITRS unit vector ``center``."""
    a = np.cross(center, NORTH_POLE)
    a /= np.linalg.norm(a)
    b = np.cross(center, a)
    phi = np.linspace(0, 2 * np.pi, n, endpoint=False)[:, np.newaxis]
    vectors = []
    for radius in np.radians(radii):
        vectors.append(np.cos(radius) * center
                       + np.sin(radius) * (np.cos(phi) * a + np.sin(phi) * b))
    x, y, z = np.concatenate(vectors).T
    itrs = ITRS(x=x, y=y, z=z, representation_type="cartesian", obstime=obstime,
                location=site)
    return SkyCoord(itrs).icrs


@pytest.fixture(scope="module", params=[("WETTZ13S", T0), ("WARKWORTH", T0),
                                        ("FD-VLBA", JULY)],
                ids=["WETTZ13S", "WARKWORTH", "FD-VLBA-July"])
def sky(request):
    """Sources over the sky of northern and southern sites at one epoch.

    A golden-spiral grid plus rings 1.2-3 deg around the zenith and around the
    tilted axis; kept above 5 deg elevation and beyond 1 deg from the zenith,
    the tilted axis and the celestial pole.
    """
    name, obstime = request.param
    site = SITES[name]
    local = local_frame(site)
    tilted = FixedAxisMount(TILT, frame="enu").fixed_axis(local)
    grid = sky_grid(300)
    near = [ring(site, obstime, center, [1.2, 2, 3]) for center in (local.up, tilted)]
    targets = SkyCoord(np.concatenate([grid.ra.deg] + [c.ra.deg for c in near]) * u.deg,
                       np.concatenate([grid.dec.deg] + [c.dec.deg for c in near]) * u.deg)
    with conf.set_temp("fast_path", False):
        s = source_direction(targets, site, obstime)
    _, elevation = horizontal(s, local)
    one = np.radians(1)
    keep = ((elevation > np.radians(5)) & (separation(s, local.up) > one)
            & (separation(s, tilted) > one) & (separation(s, NORTH_POLE) > one)
            & (separation(s, -NORTH_POLE) > one))
    s = s[keep]
    s_rate = rates.source_direction_rate(s, rates.celestial_pole(obstime),
                                         location_xyz(site), sun_position(obstime))
    assert np.degrees(separation(s, local.up)).min() < 1.3  # the rings are there
    return types.SimpleNamespace(name=name, site=site, obstime=obstime, local=local,
                                 targets=targets[keep], s=s, s_rate=s_rate)


def test_source_direction_rate_against_astropy(sky):
    # Reference: a centred difference of astropy's apparent topocentric ITRS
    # direction (2.5-6.6e-12 rad/s apart over 2023: the motion of the CIP on the sky).
    with conf.set_temp("fast_path", False):
        ahead = source_direction(sky.targets, sky.site, sky.obstime + STEP * u.s)
        behind = source_direction(sky.targets, sky.site, sky.obstime - STEP * u.s)
    reference = (ahead - behind) / (2 * STEP)
    assert np.abs(sky.s_rate - reference).max() < 1e-11
    # Each term left out costs what the docstring says (the ITRS z axis alone
    # misses polar motion and aberration: a few 1e-10 rad/s).
    plain = rates.source_direction_rate(sky.s)
    assert 5e-11 < np.abs(plain - reference).max() < 5e-10
    no_sun = rates.source_direction_rate(sky.s, rates.celestial_pole(sky.obstime),
                                         location_xyz(sky.site))
    assert 5e-12 < np.abs(no_sun - reference).max() < 3e-11
    # The rate is perpendicular to the line of sight.
    assert np.abs(np.einsum("...i,...i", sky.s_rate, sky.s)).max() < 1e-19


def test_celestial_pole_is_astropy_cirs_pole():
    # Reference: the CIRS z axis (the CIP) transformed by astropy to ITRS.
    times = T0 + [0, 100, 200] * u.day
    pole = rates.celestial_pole(times)
    cirs = CIRS(x=[0.0] * 3, y=[0.0] * 3, z=[1.0] * 3, representation_type="cartesian",
                obstime=times)
    expected = np.moveaxis(cirs.transform_to(ITRS(obstime=times)).cartesian.xyz.value, 0, -1)
    assert pole.shape == (3, 3)
    assert np.abs(pole - expected).max() < 1e-12
    offset = np.degrees(np.arccos(pole[:, 2])) * 3600
    assert np.all((offset > 0.05) & (offset < 0.6))  # polar motion, arcsec


def test_celestial_pole_masked_epochs():
    times = T0 + [0, 1, 2] * u.hour
    times[1] = np.ma.masked
    pole = rates.celestial_pole(times)
    assert np.all(np.isnan(pole[1])) and np.all(np.isfinite(pole[[0, 2]]))
    times[:] = np.ma.masked
    assert np.all(np.isnan(rates.celestial_pole(times)))


FIXED_AXIS_CASES = [
    ("alt-az Cassegrain", AltAzMount(), CassegrainFocus(), (0, 0)),
    ("equatorial", EquatorialMount(), CassegrainFocus(), (0, 0)),
    ("X-Y north", XYMount("north"), CassegrainFocus(), (0, 0)),
    ("X-Y east", XYMount("east"), CassegrainFocus(), (0, 0)),
    ("tilted", FixedAxisMount(TILT, frame="enu"), CassegrainFocus(), (0, 0)),
    ("Nasmyth right", AltAzMount(), NasmythFocus("right"), (1, 0)),
    ("Nasmyth left", AltAzMount(), NasmythFocus("left"), (-1, 0)),
    ("BWG right", AltAzMount(), BeamWaveguideFocus("right"), (1, -1)),
    ("BWG left", AltAzMount(), BeamWaveguideFocus("left"), (-1, 1)),
]


@pytest.mark.parametrize("label, mount, focus, multiples", FIXED_AXIS_CASES,
                         ids=[case[0] for case in FIXED_AXIS_CASES])
def test_fixed_axis_rate_against_rigorous_difference(sky, label, mount, focus, multiples):
    antenna = Antenna(sky.site, mount, focus)
    axis = mount.fixed_axis(sky.local)
    analytic = rates.fixed_axis_rate(sky.s, sky.s_rate, axis, sky.local, multiples)
    reference = rigorous_rate(antenna, sky.targets, sky.obstime)
    assert np.all(np.isfinite(analytic))
    assert np.abs(analytic - reference).max() < TOLERANCE
    if isinstance(mount, EquatorialMount):
        assert np.all(analytic == 0)  # Eq 17: no feed rotation, no rate
    else:
        assert np.abs(analytic).max() > 1e-4  # near the axis: 20 deg/h and more


def test_stationary_rate_against_rigorous_difference(sky):
    analytic = rates.stationary_rate(sky.s, sky.s_rate, sky.local)
    reference = rigorous_rate(Antenna(sky.site, StationaryMount()), sky.targets,
                              sky.obstime)
    assert np.abs(analytic - reference).max() < TOLERANCE


@pytest.mark.parametrize("train, multiples", [
    (MirrorTrain.yebes40m("X"), (1, 0)),
    (MirrorTrain.yebes40m("S"), (1, 0)),
    (MirrorTrain.wark30m(), (1, -1)),
], ids=["yebes40m X", "yebes40m S", "wark30m"])
def test_mirror_train_rate_by_directional_difference(sky, train, multiples):
    up = sky.local.up

    def phase(v):
        return train.receiver_phase(v, project(NORTH_POLE, v), up, sky.local)

    numeric = rates.directional_rate(phase, sky.s, sky.s_rate)
    reference = rigorous_rate(Antenna(sky.site, AltAzMount(), train), sky.targets,
                              sky.obstime)
    assert np.abs(numeric - reference).max() < TOLERANCE
    # The trains trace to the closed forms plus a constant (Appendix C), whose
    # rate is the same (8e-13 rad/s at 1 deg from the zenith, 1e-13 beyond 5 deg).
    closed = rates.fixed_axis_rate(sky.s, sky.s_rate, up, sky.local, multiples)
    assert np.abs(numeric - closed).max() < 2e-12


def test_altaz_rates_against_classical_closed_forms(sky):
    # Spherical trigonometry for a sky turning about z at omega (docs/rates.rst):
    # dPsi/dt = -omega cos(lat) cos(A) / cos(E), dE/dt = omega cos(lat) sin(A),
    # dA/dt = omega (sin(lat) - cos(lat) cos(A) tan(E)), with the geodetic
    # latitude of astropy and A, E of the same line of sight.
    lat = sky.site.to_geodetic("WGS84").lat.rad
    azimuth, elevation = horizontal(sky.s, sky.local)
    s_rate = rates.source_direction_rate(sky.s)
    psi_rate = rates.fixed_axis_rate(sky.s, s_rate, sky.local.up)
    expected = -OMEGA * np.cos(lat) * np.cos(azimuth) / np.cos(elevation)
    np.testing.assert_allclose(psi_rate, expected, rtol=1e-9, atol=1e-16)
    azimuth_rate, elevation_rate = rates.horizontal_rate(sky.s, s_rate, sky.local)
    np.testing.assert_allclose(elevation_rate, OMEGA * np.cos(lat) * np.sin(azimuth),
                               rtol=1e-9, atol=1e-16)
    np.testing.assert_allclose(
        azimuth_rate,
        OMEGA * (np.sin(lat) - np.cos(lat) * np.cos(azimuth) * np.tan(elevation)),
        rtol=1e-9, atol=1e-16)


def test_parallactic_angle_rate_sign_at_transit():
    # A source transiting south of the zenith of a northern site: the
    # parallactic angle goes from east (negative) to west (positive).
    site = SITES["WETTZ13S"]
    antenna = Antenna(site, AltAzMount())
    lat = site.to_geodetic("WGS84").lat
    # CIRS right ascension is counted from the CIO: hour angle = ERA + longitude - RA.
    era = T0.earth_rotation_angle(longitude=site.lon)
    source = SkyCoord(ra=era, dec=lat - 30 * u.deg, frame="cirs", obstime=T0)
    before, after = antenna.feed_rotation(source, T0 + [-60, 60] * u.s).rad
    assert before < 0 < after
    s = source_direction(source, site, T0)
    rate = rates.fixed_axis_rate(s, rates.source_direction_rate(s), antenna.local_frame.up)
    assert 0 < rate == pytest.approx((after - before) / 120, rel=1e-4)


def test_nan_where_the_angle_is_undefined():
    lat = np.radians(45)
    local = LocalFrame(east=np.array([0.0, 1, 0]),
                       north=np.array([-np.sin(lat), 0, np.cos(lat)]),
                       up=np.array([np.cos(lat), 0, np.sin(lat)]))
    generic = np.array([0.6, 0.0, 0.8])
    s = np.stack([local.up, NORTH_POLE, -local.up, generic])
    s_rate = rates.source_direction_rate(s)
    cassegrain = rates.fixed_axis_rate(s, s_rate, local.up)
    nasmyth = rates.fixed_axis_rate(s, s_rate, local.up, local, (1, 0))
    equatorial = rates.fixed_axis_rate(s, s_rate, NORTH_POLE)
    stationary = rates.stationary_rate(s, s_rate, local)
    azimuth_rate, elevation_rate = rates.horizontal_rate(s, s_rate, local)
    # The angles (kernel) and their rates are NaN at the same places.
    angle = receiver_term(s, local.up)
    np.testing.assert_array_equal(np.isnan(cassegrain), np.isnan(angle))
    np.testing.assert_array_equal(np.isnan(cassegrain), [True, True, True, False])
    np.testing.assert_array_equal(np.isnan(nasmyth), [True, True, True, False])
    np.testing.assert_array_equal(np.isnan(equatorial), [False, True, False, False])
    assert np.all(equatorial[[0, 2, 3]] == 0)
    np.testing.assert_array_equal(np.isnan(stationary), [False, True, True, False])
    np.testing.assert_array_equal(np.isnan(azimuth_rate), [True, False, True, False])
    np.testing.assert_array_equal(np.isnan(elevation_rate), [True, False, True, False])


def test_wu_phase_rate_with_moving_dipoles():
    # Rotating both dipoles about the line of sight: Phi = beta(t) - alpha(t).
    s = np.array([0.0, 0.0, 1.0])
    zero = np.zeros(3)
    alpha, beta, alpha_rate, beta_rate = 0.3, 1.1, 2e-3, -5e-4
    r = np.array([np.cos(alpha), np.sin(alpha), 0.0])
    t = np.array([np.cos(beta), np.sin(beta), 0.0])
    r_rate = alpha_rate * np.array([-np.sin(alpha), np.cos(alpha), 0.0])
    t_rate = beta_rate * np.array([-np.sin(beta), np.cos(beta), 0.0])
    rate = rates.wu_phase_rate(s, zero, r, t, r_rate, t_rate)
    assert rate == pytest.approx(beta_rate - alpha_rate, rel=1e-14)


@pytest.fixture(scope="module")
def gps_pass():
    """GPS SVN 76 (Table 2) over 06:00-17:00 UTC at 10 min, as in Sec. 4.1."""
    gps = Satellite(TLEOrbit(*GPS_SVN76_TLE))
    times = Time("2023-01-25T06:00") + np.arange(0, 11 * 3600 + 1, 600) * u.s
    return gps, times


@pytest.mark.parametrize("name, mount", [("DBR205", StationaryMount()),
                                         ("FD-VLBA", AltAzMount())])
def test_satellite_rate_by_time_difference(gps_pass, name, mount):
    gps, times = gps_pass
    antenna = Antenna(SITES[name], mount)
    visible = horizontal(gps.line_of_sight(antenna.location, times).s,
                         antenna.local_frame)[1] > np.radians(5)
    assert visible.sum() > 30
    # The default step, and the fast path where it applies (66 epochs) ...
    rate = rates.difference_rate(lambda t: antenna.feed_rotation(gps, t), times)
    # ... against a finer difference of the rigorous path: fourth order,
    # h = 5 ms (truncation h^4 Phi^(5) / 30, below 1e-17 rad/s).
    h = 0.005
    with conf.set_temp("fast_path", False):
        f = [antenna.feed_rotation(gps, times + k * h * u.s).rad for k in (-2, -1, 1, 2)]
    reference = (8 * wrap_phase(f[2] - f[1]) - wrap_phase(f[3] - f[0])) / (12 * h)
    assert np.abs(rate - reference)[visible].max() < TOLERANCE
    assert np.abs(rate[visible]).max() > 1e-4


def test_satellite_wu_rate_from_moving_vectors(gps_pass):
    # A tracking antenna sees Eq 7 with the transmitter's effective dipole:
    # wu_phase_rate with the rates of s and t (here differenced) gives the
    # same rate as the time difference of the whole feed rotation.
    gps, times = gps_pass
    antenna = Antenna(SITES["FD-VLBA"], AltAzMount())
    los = gps.line_of_sight(antenna.location, times)
    ahead = gps.line_of_sight(antenna.location, times + STEP * u.s)
    behind = gps.line_of_sight(antenna.location, times - STEP * u.s)
    s_rate = (ahead.s - behind.s) / (2 * STEP)
    t_rate = (ahead.t - behind.t) / (2 * STEP)
    rate = rates.wu_phase_rate(los.s, s_rate, antenna.local_frame.up, los.t, t_rate=t_rate)
    reference = rates.difference_rate(lambda t: antenna.feed_rotation(gps, t), times)
    visible = horizontal(los.s, antenna.local_frame)[1] > np.radians(5)
    assert np.abs(rate - reference)[visible].max() < TOLERANCE


@pytest.fixture(params=["scalar", "array"])
def epochs(request):
    """A scalar and an array of epochs."""
    return T0 if request.param == "scalar" else T0 + [0, 3, 6] * u.hour


def test_difference_rate_shapes_and_units(epochs):
    antenna = Antenna(SITES["YEBES"], AltAzMount())
    target = SkyCoord("03h19m48.16s +41d30m42.1s")
    rate = rates.difference_rate(lambda t: antenna.feed_rotation(target, t), epochs)
    assert rate.shape == epochs.shape
    s = source_direction(target, antenna.location, epochs)
    analytic = rates.fixed_axis_rate(
        s, rates.source_direction_rate(s, rates.celestial_pole(epochs),
                                       location_xyz(antenna.location), sun_position(epochs)),
        antenna.local_frame.up)
    assert np.abs(rate - analytic).max() < TOLERANCE
    # Plain radians and a step as a Quantity give the same.
    plain = rates.difference_rate(lambda t: antenna.feed_rotation(target, t).rad, epochs,
                                  step=10 * u.ms)
    assert np.abs(plain - rate).max() < 1e-15


def test_difference_rate_wraps_across_180_deg():
    start = Time("2023-01-25T00:00")

    def phase(t):  # 2 deg/s, through +-180 deg at 90 s
        return wrap_phase(np.radians(2.0 * (t - start).to_value(u.s)))

    rate = rates.difference_rate(phase, start + [89.995, 90.0, 90.005] * u.s)
    np.testing.assert_allclose(rate, np.radians(2.0), rtol=1e-6)


@pytest.fixture
def stale_tables():
    """The bundled Earth-orientation tables cut to end on 2021-01-01 (as in test_eop)."""
    table = iers.IERS_Auto.open()
    mjd = table["MJD"].to_value(u.day)
    fake = table[mjd <= 59215.0]
    fake.meta["predictive_mjd"] = 58850.0
    fake.meta["predictive_index"] = int(np.searchsorted(mjd, 58850.0))
    with iers.earth_orientation_table.set(fake):
        yield


def test_difference_rate_warns_once_per_category(stale_tables):
    site = SITES["YEBES"]
    antenna = Antenna(site, AltAzMount())
    up = local_frame(site).up
    # The zenith (an Earth-fixed direction) is degenerate at every epoch, and
    # the epochs lie two years beyond the tables.
    zenith = SkyCoord(ITRS(x=up[0], y=up[1], z=up[2], representation_type="cartesian"))
    times = T0 + [0, 1] * u.hour
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rate = rates.difference_rate(lambda t: antenna.feed_rotation(zenith, t), times)
    assert np.all(np.isnan(rate))
    categories = [w.category for w in caught]
    assert categories.count(DegenerateGeometryWarning) == 1
    assert categories.count(StaleEarthOrientationWarning) == 1
    assert len(caught) == 2
    assert all(w.filename == __file__ for w in caught)  # the user's line


def test_difference_rate_masked_epochs():
    antenna = Antenna(SITES["YEBES"], AltAzMount())
    target = SkyCoord("03h19m48.16s +41d30m42.1s")
    times = T0 + [0, 1, 2] * u.hour
    times[1] = np.ma.masked
    rate = rates.difference_rate(lambda t: antenna.feed_rotation(target, t), times)
    assert np.isnan(rate[1]) and np.all(np.isfinite(rate[[0, 2]]))


def test_directional_rate_where_the_line_of_sight_does_not_move():
    s = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])
    rate = rates.directional_rate(lambda v: np.arctan2(v[..., 1], v[..., 0] + 2),
                                  s, rates.source_direction_rate(s))
    assert rate[0] == 0  # at the pole the sky does not move
    # atan2(y, x + 2) at (1, 0, 0) moving along -y at omega: -omega / 3.
    assert rate[1] == pytest.approx(-OMEGA / 3, rel=1e-10)


def test_atan2_rate():
    angle = np.linspace(-3, 3, 7)
    rate = rates.atan2_rate(2 * np.sin(angle), 2 * np.cos(angle),
                            2 * 0.1 * np.cos(angle), -2 * 0.1 * np.sin(angle))
    np.testing.assert_allclose(rate, 0.1, rtol=1e-14)
    assert np.isnan(rates.atan2_rate(0.0, 0.0, 1.0, 1.0))


def test_earth_rotation_angle_rate_is_erfa():
    # Reference: ERFA's era00 over one UT1 day (its definition, IAU 2000).
    turn = erfa.era00(2460000.5, 1.0) - erfa.era00(2460000.5, 0.0)
    assert np.mod(turn, 2 * np.pi) + 2 * np.pi == pytest.approx(OMEGA * 86400, rel=1e-12)


def test_altaz_frame_agrees_with_horizontal_rate():
    # Reference: astropy's AltAz differenced in time (rigorous, refraction off).
    site = SITES["WARKWORTH"]
    target = sky_grid(40)
    frame = AltAz(obstime=T0 + [-STEP, STEP] * u.s, location=site)
    altaz = target[:, np.newaxis].transform_to(frame)
    azimuth_rate = wrap_phase(np.diff(altaz.az.rad, axis=-1)[:, 0]) / (2 * STEP)
    elevation_rate = np.diff(altaz.alt.rad, axis=-1)[:, 0] / (2 * STEP)
    with conf.set_temp("fast_path", False):
        s = source_direction(target, site, T0)
    local = local_frame(site)
    s_rate = rates.source_direction_rate(s, rates.celestial_pole(T0), location_xyz(site),
                                         sun_position(T0))
    az_rate, el_rate = rates.horizontal_rate(s, s_rate, local)
    elevation = horizontal(s, local)[1]
    ok = (elevation > np.radians(5)) & (elevation < np.radians(89))
    assert np.abs(az_rate - azimuth_rate)[ok].max() < TOLERANCE
    assert np.abs(el_rate - elevation_rate)[ok].max() < TOLERANCE


# Error paths


def test_bad_vectors():
    with pytest.raises(ValueError, match=r"s must have a last axis of length 3.*\(2,\)"):
        rates.source_direction_rate([1.0, 0.0])
    with pytest.raises(TypeError, match="s must be an array of 3-vectors, got str"):
        rates.horizontal_rate("zenith", [0, 0, 0], LocalFrame(*np.eye(3)))
    with pytest.raises(ValueError, match="site must have a last axis of length 3"):
        rates.source_direction_rate([1.0, 0, 0], site=5.0)
    with pytest.raises(ValueError, match="r_rate must have a last axis"):
        rates.wu_phase_rate([0, 0, 1.0], [0, 0, 0], [1.0, 0, 0], NORTH_POLE, r_rate=[1.0])


def test_bad_local_frame():
    with pytest.raises(TypeError, match="local must be a LocalFrame .* got float"):
        rates.stationary_rate([0, 0, 1.0], [0, 0, 0], 3.0)
    with pytest.raises(ValueError, match="local.up must have a last axis of length 3"):
        rates.horizontal_rate([0, 0, 1.0], [0, 0, 0], ([1.0, 0, 0], [0, 1.0, 0], [1.0]))


@pytest.mark.parametrize("multiples, message", [
    ((1,), "multiples must be two numbers"),
    ("right", "multiples must be two numbers"),
    ((1, np.nan), "multiples must be finite"),
])
def test_bad_multiples(multiples, message):
    with pytest.raises(ValueError, match=message):
        rates.fixed_axis_rate([0.6, 0, 0.8], [0, 0, 0], [0, 0, 1.0], LocalFrame(*np.eye(3)),
                              multiples)


def test_multiples_need_the_local_frame():
    with pytest.raises(ValueError, match=r"give the site's local frame \(local="):
        rates.fixed_axis_rate([0.6, 0, 0.8], [0, 0, 0], [0, 0, 1.0], multiples=(1, -1))


@pytest.mark.parametrize("step, error, message", [
    (0.0, ValueError, "step must be positive and finite, got 0.0"),
    (-1.0, ValueError, "step must be positive and finite"),
    (np.inf, ValueError, "step must be positive and finite"),
    ("1s", TypeError, r"step must be a number \(s\), got str"),
    (True, TypeError, r"step must be a number \(s\), got bool"),
    (1 * u.m, u.UnitsError, "step must be in s, got m"),
])
def test_bad_difference_step(step, error, message):
    with pytest.raises(error, match=message):
        rates.difference_rate(lambda t: np.zeros(t.shape), T0, step=step)


def test_bad_directional_step():
    with pytest.raises(u.UnitsError, match="step must be in rad, got s"):
        rates.directional_rate(lambda v: v[..., 0], [1.0, 0, 0], [0, 1.0, 0], step=1 * u.s)
    with pytest.raises(ValueError, match="step must be positive and finite"):
        rates.directional_rate(lambda v: v[..., 0], [1.0, 0, 0], [0, 1.0, 0], step=-1e-6)


def test_bad_phase_callable():
    with pytest.raises(TypeError, match="phase must be a callable returning angles, got Quantity"):
        rates.difference_rate(np.zeros(3) * u.deg, T0)
    with pytest.raises(TypeError, match="phase must be a callable"):
        rates.directional_rate(None, [1.0, 0, 0], [0, 1.0, 0])
    with pytest.raises(u.UnitsError, match="phase must return angles, got a quantity in m"):
        rates.difference_rate(lambda t: np.zeros(t.shape) * u.m, T0)


def test_bad_obstime():
    with pytest.raises(TypeError, match="obstime must be an astropy Time"):
        rates.difference_rate(lambda t: 0.0, 60000.0)
    with pytest.raises(TypeError, match="obstime must be an astropy Time"):
        rates.celestial_pole([1, 2])


# --- Antenna.feed_rotation_rate: the front-end ------------------------------------------


ANTENNA_CASES = FIXED_AXIS_CASES + [
    ("stationary", StationaryMount(), CassegrainFocus(), None),
    ("YEBES40M train", AltAzMount(), MirrorTrain.yebes40m("X"), None),
    ("WARK30M train", AltAzMount(), MirrorTrain.wark30m(), None),
]


@pytest.mark.parametrize("label, mount, focus, multiples", ANTENNA_CASES,
                         ids=[case[0] for case in ANTENNA_CASES])
def test_antenna_rate_against_rigorous_difference(sky, label, mount, focus, multiples):
    antenna = Antenna(sky.site, mount, focus)
    rate = antenna.feed_rotation_rate(sky.targets, sky.obstime)
    assert rate.unit == u.deg / u.s and rate.shape == sky.targets.shape
    reference = rigorous_rate(antenna, sky.targets, sky.obstime)
    assert np.abs(rate.to_value(u.rad / u.s) - reference).max() < TOLERANCE


def test_antenna_rate_over_a_day_fast_path():
    """Dense epochs (the fast path) at one source, against the rigorous difference."""
    antenna = Antenna(SITES["YEBES"], AltAzMount(), NasmythFocus("right"))
    source = SkyCoord("03h19m48.16s +41d30m42.1s")
    times = T0 + np.arange(0, 86400, 1800) * u.s
    rate = antenna.feed_rotation_rate(source, times).to_value(u.rad / u.s)
    reference = rigorous_rate(antenna, source, times)
    _, elevation = antenna.altaz(source, times)
    up = (elevation > 5 * u.deg) & (elevation < 89 * u.deg)
    assert up.sum() > 20
    assert np.abs(rate - reference)[up].max() < TOLERANCE


def test_antenna_rate_of_a_satellite(gps_pass):
    gps, times = gps_pass
    antenna = Antenna(SITES["FD-VLBA"], AltAzMount())
    rate = antenna.feed_rotation_rate(gps, times, min_elevation=5 * u.deg)
    h = 0.005
    with conf.set_temp("fast_path", False):
        f = [antenna.feed_rotation(gps, times + k * h * u.s).rad for k in (-2, -1, 1, 2)]
    reference = (8 * wrap_phase(f[2] - f[1]) - wrap_phase(f[3] - f[0])) / (12 * h)
    _, elevation = antenna.altaz(gps, times)
    visible = elevation > 5 * u.deg
    assert np.all(np.isnan(rate[~visible]))
    assert np.abs(rate.to_value(u.rad / u.s) - reference)[visible].max() < TOLERANCE


def test_antenna_rate_lcp_scalar_masked_and_below():
    antenna = Antenna(SITES["WETTZ13S"], AltAzMount())
    source = SkyCoord("03h19m48.16s +41d30m42.1s")
    rcp = antenna.feed_rotation_rate(source, T0)
    assert rcp.shape == () and np.isfinite(rcp)
    assert antenna.feed_rotation_rate(source, T0, polarization="LCP") == -rcp
    times = T0 + np.arange(3) * u.hour
    times[1] = np.ma.masked
    rate = antenna.feed_rotation_rate(source, times)
    assert np.isnan(rate[1]) and np.all(np.isfinite(rate[[0, 2]]))
    below = antenna.feed_rotation_rate(source, times, min_elevation=89 * u.deg)
    assert np.all(np.isnan(below))


def test_antenna_rate_at_the_zenith_is_nan_with_one_warning():
    site = SITES["WETTZ13S"]
    antenna = Antenna(site, AltAzMount())
    up = local_frame(site).up
    zenith = SkyCoord(ITRS(x=up[0], y=up[1], z=up[2], representation_type="cartesian",
                           obstime=T0, location=site)).icrs
    with pytest.warns(DegenerateGeometryWarning, match="feed rotation rate is undefined at 1 "
                                                       "of 1 epochs") as caught:
        rate = antenna.feed_rotation_rate(zenith, T0)
    assert len(caught) == 1 and np.isnan(rate)


def test_antenna_rate_errors(gps_pass):
    gps, times = gps_pass
    antenna = Antenna(SITES["FD-VLBA"], AltAzMount())
    with pytest.raises(ValueError, match="an LCP receiver does not receive the RCP signal"):
        antenna.feed_rotation_rate(gps, times, polarization="LCP")
    with pytest.raises(ValueError, match=r"form must be one of \('beyerle', 'wu'\)"):
        antenna.feed_rotation_rate(gps, times, form="x")
    with pytest.raises(u.UnitsError):
        antenna.feed_rotation_rate(gps, times, min_elevation=10 * u.m)
    with pytest.raises(TypeError, match="obstime must be an astropy Time"):
        antenna.feed_rotation_rate(SkyCoord("03h19m48.16s +41d30m42.1s"), 3.0)


def test_antenna_rate_at_the_ends_of_an_sp3_file():
    """One-sided differences inside the file's coverage, equal to the central ones."""
    from astropy_feedrot import SP3Orbit
    from astropy_feedrot.data import sample_file

    orbit = SP3Orbit(sample_file("sample.sp3"), "G01", points=4)
    gps = Satellite(orbit)
    antenna = Antenna(SITES["FD-VLBA"], StationaryMount())
    start, stop = orbit.coverage
    ends = Time([start.utc.isot, stop.utc.isot], scale="utc")
    rate = antenna.feed_rotation_rate(gps, ends).to_value(u.rad / u.s)
    assert np.all(np.isfinite(rate))
    # Reference: the second-order one-sided differences (-3 f0 + 4 f1 - f2) / 2h,
    # inwards (error h^2 |d3Phi/dt3| / 3); the package's first-order one differs
    # by h |d2Phi/dt2| / 2, below 1e-9 rad/s for a GNSS orbit.
    h = 0.01
    inwards = np.array([1.0, -1.0])
    f = [antenna.feed_rotation(gps, ends + k * h * inwards * u.s).rad for k in (0, 1, 2)]
    reference = inwards * (-3 * f[0] + 4 * f[1] - f[2]) / (2 * h)
    assert np.abs(rate - reference).max() < 1e-9
    with pytest.raises(ValueError, match="times outside the coverage of the SP3 orbit"):
        antenna.feed_rotation_rate(gps, ends - [1, 0] * u.s)
