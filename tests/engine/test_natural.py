# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation of natural sources for every mount and focus type.

References: ERFA's ``hd2pa`` and the spherical-trigonometry form of Eq 16,
both fed with hour angle and declination from astropy's `HADec` frame (an
independent route through ERFA's observed-place routines); closed forms
derived in the docstrings (X-Y mounts); the closed forms of Eqs 38-39 against
the reflection tracing of Appendix C; Eq 33 as printed.
"""

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import HADec, SkyCoord
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time
from helpers import DAY, MAS, SITES, angle_spread, max_angle_difference, sky_grid
from numpy.testing import assert_allclose

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    BeamWaveguideFocus,
    CassegrainFocus,
    EquatorialMount,
    FixedAxisMount,
    GregorianFocus,
    MirrorTrain,
    NasmythFocus,
    PrimeFocus,
    StationaryMount,
    XYMount,
)
from astropy_feedrot.core import kernel as k
from astropy_feedrot.earth.frames import local_frame, source_direction

GRID = sky_grid(60)[:, np.newaxis]  # 60 directions x 96 epochs


@pytest.fixture(scope="module", params=["WETTZ13S", "WARKWORTH", "FD-VLBA"])
def site(request):
    return SITES[request.param]


@pytest.fixture(scope="module")
def hadec(site):
    """Hour angle, declination (rad) from astropy's HADec, and geodetic latitude."""
    frame = GRID.transform_to(HADec(obstime=DAY, location=site))
    return frame.ha.rad, frame.dec.rad, site.to_geodetic("WGS84").lat.rad


def test_parallactic_angle_against_erfa_hd2pa(site, hadec):
    ha, dec, lat = hadec
    psi = Antenna(site, AltAzMount()).feed_rotation(GRID, DAY)
    assert psi.shape == (60, 96)
    reference = erfa.hd2pa(ha, dec, lat)
    assert max_angle_difference(psi.rad, reference) < 1 * MAS


def test_parallactic_angle_against_eq16(site, hadec):
    ha, dec, lat = hadec
    # Eq 16 as printed, with atan2 (Sec. 2.1: "use the four-quadrant arctangent").
    eq16 = np.arctan2(np.sin(ha), np.cos(dec) * np.tan(lat) - np.sin(dec) * np.cos(ha))
    antenna = Antenna(site, AltAzMount())
    assert max_angle_difference(antenna.parallactic_angle(GRID, DAY).rad, eq16) < 1 * MAS
    assert max_angle_difference(antenna.feed_rotation(GRID, DAY).rad, eq16) < 1 * MAS


@pytest.mark.parametrize("focus", [PrimeFocus(), CassegrainFocus(), GregorianFocus()])
def test_conventional_foci_add_nothing(focus):
    site = SITES["YEBES"]
    psi = Antenna(site, AltAzMount()).parallactic_angle(GRID, DAY)
    assert_quantity_allclose(Antenna(site, AltAzMount(), focus).feed_rotation(GRID, DAY), psi,
                             atol=1e-12 * u.deg)


def test_equatorial_mount_gives_zero(site):
    # Eq 17: z^T S^T z = 0.
    phi = Antenna(site, EquatorialMount()).feed_rotation(GRID, DAY)
    assert_quantity_allclose(phi, 0 * u.deg, atol=1e-12 * u.deg)


def test_xy_mount_north_against_spherical_trigonometry(site, hadec):
    ha, dec, lat = hadec
    expected = np.arctan2(-np.sin(lat) * np.sin(ha),
                          np.cos(lat) * np.cos(dec) + np.sin(lat) * np.sin(dec) * np.cos(ha))
    phi = Antenna(site, XYMount("north")).feed_rotation(GRID, DAY)
    assert max_angle_difference(phi.rad, expected) < 1 * MAS
    # The form is the parallactic angle at latitude lat - 90 deg, plus 180 deg.
    psi_shifted = erfa.hd2pa(ha, dec, lat - np.pi / 2) + np.pi
    assert max_angle_difference(phi.rad, psi_shifted) < 1 * MAS


def test_xy_mount_east_against_spherical_trigonometry(site, hadec):
    ha, dec, _ = hadec
    expected = np.arctan2(np.cos(ha), np.sin(dec) * np.sin(ha))
    phi = Antenna(site, XYMount("east")).feed_rotation(GRID, DAY)
    assert max_angle_difference(phi.rad, expected) < 1 * MAS


def test_fixed_axis_mount_reproduces_named_mounts(site):
    local = local_frame(site)
    pairs = [
        (FixedAxisMount([0, 0, 1], frame="enu"), AltAzMount()),
        (FixedAxisMount(local.up), AltAzMount()),
        (FixedAxisMount([0, 0, 5.0]), EquatorialMount()),
        (FixedAxisMount([0, 1, 0], frame="enu"), XYMount("north")),
        (FixedAxisMount(local.east * 2), XYMount("east")),
    ]
    for general, named in pairs:
        assert_quantity_allclose(Antenna(site, general).feed_rotation(GRID, DAY),
                                 Antenna(site, named).feed_rotation(GRID, DAY), atol=1e-9 * u.deg)


def test_stationary_mount_is_eq33(site):
    # Eq 33 as printed, with the matrices of Eqs 4 and 6 built independently.
    antenna = Antenna(site, StationaryMount())
    s = source_direction(GRID, site, DAY)
    e, n, _ = local_frame(site)
    z = k.NORTH_POLE
    sx = k.cross_matrix(s)
    p = k.projection_matrix(s)
    sxt_z = np.einsum("...ji,j->...i", sx, z)  # S^T z
    pz = p @ z
    eq33 = np.arctan2(sxt_z @ e + pz @ n, pz @ e - sxt_z @ n)
    phi = antenna.feed_rotation(GRID, DAY)
    assert max_angle_difference(phi.rad, eq33) < 1e-9


def test_stationary_mount_is_parallactic_angle_minus_azimuth(site):
    # A levelled crossed dipole (aligned east, transverse north) is an alt-az
    # feed whose dipoles do not follow the azimuth: Phi = Psi - A - 90 deg
    # (Psi checked against erfa.hd2pa above; A from the same direction).
    antenna = Antenna(site, StationaryMount())
    psi = Antenna(site, AltAzMount()).parallactic_angle(GRID, DAY)
    azimuth, elevation = antenna.altaz(GRID, DAY)
    expected = (psi - azimuth - 90 * u.deg).wrap_at(180 * u.deg)
    away = elevation < 89 * u.deg  # the azimuth is undefined at the zenith
    difference = (antenna.feed_rotation(GRID, DAY) - expected).wrap_at(180 * u.deg)[away]
    assert np.abs(difference).max() < 1 * u.mas


def test_stationary_mount_at_zenith_is_pole_azimuth():
    # Hand-built geometry: a source at the zenith of a GNSS antenna at latitude
    # 0, longitude 0 (s = ITRS x; east = y, north = z). The projected pole is
    # the north dipole, so the wind-up is the angle from the aligned (east)
    # dipole to north about s: +90 deg.
    s = np.array([1.0, 0.0, 0.0])
    r = k.receiver_effective_dipole(s, [0, 1.0, 0], [0, 0, 1.0])
    assert_allclose(np.degrees(k.wu_phase(s, r, k.project(k.NORTH_POLE, s))), 90.0)


@pytest.mark.parametrize("band", ["S", "C", "X"])
def test_nasmyth_closed_form_equals_traced_yebes40m(band):
    # Sec. 3.3: equal up to one constant (here +90 deg, set by which feed
    # dipole is called aligned).
    site = SITES["YEBES"]
    closed = Antenna(site, AltAzMount(), NasmythFocus("right"))
    traced = Antenna(site, AltAzMount(), MirrorTrain.yebes40m(band))
    a, e = closed.altaz(GRID, DAY)
    up = e.deg > 0.5
    spread, constant = angle_spread(traced.feed_rotation(GRID, DAY).rad[up],
                                    closed.feed_rotation(GRID, DAY).rad[up])
    assert spread < 1e-9
    assert_allclose(np.degrees(constant), 90.0, atol=1e-9)


def test_yebes40m_bands_agree_up_to_a_constant():
    site = SITES["YEBES"]
    phis = [Antenna(site, AltAzMount(), MirrorTrain.yebes40m(b)).feed_rotation(GRID, DAY).rad
            for b in "SCX"]
    assert angle_spread(phis[0], phis[1])[0] < 1e-9
    assert angle_spread(phis[0], phis[2])[0] < 1e-9


def test_beam_waveguide_closed_form_equals_traced_wark30m():
    site = SITES["WARKWORTH"]
    closed = Antenna(site, AltAzMount(), BeamWaveguideFocus("right"))
    traced = Antenna(site, AltAzMount(), MirrorTrain.wark30m())
    _, e = closed.altaz(GRID, DAY)
    up = e.deg > 0.5
    spread, constant = angle_spread(traced.feed_rotation(GRID, DAY).rad[up],
                                    closed.feed_rotation(GRID, DAY).rad[up])
    assert spread < 1e-9
    # The constant documented in MirrorTrain.wark30m.
    assert_allclose(constant, 2 * np.arctan(2500 / 9500) - np.pi, atol=1e-9)


def test_closed_forms_match_paper_expressions():
    # Eqs 38, 39 with E and A from astropy's AltAz (independent of our vectors).
    from astropy.coordinates import AltAz

    site = SITES["YEBES"]
    sources = GRID[::6]
    altaz = sources.transform_to(AltAz(obstime=DAY, location=site))
    psi = Antenna(site, AltAzMount()).parallactic_angle(sources, DAY).rad
    el, az = altaz.alt.rad, altaz.az.rad
    cases = {
        NasmythFocus("right"): psi + el,
        NasmythFocus("left"): psi - el,
        BeamWaveguideFocus("right"): psi + el - az,
        BeamWaveguideFocus("left"): psi - el + az,
    }
    for focus, expected in cases.items():
        phi = Antenna(site, AltAzMount(), focus).feed_rotation(sources, DAY).rad
        assert max_angle_difference(phi, expected) < 1 * MAS, focus


def test_wrong_handedness_trace_is_detected():
    # The tests above can fail: a left-handed closed form does not match the
    # YEBES40M trace up to any constant.
    site = SITES["YEBES"]
    left = Antenna(site, AltAzMount(), NasmythFocus("left")).feed_rotation(GRID, DAY).rad
    traced = Antenna(site, AltAzMount(), MirrorTrain.yebes40m("X")).feed_rotation(GRID, DAY).rad
    assert angle_spread(traced, left)[0] > 0.1


def test_user_defined_single_mirror_nasmyth():
    # One tertiary mirror towards -eta is a right-handed Nasmyth focus (+180 deg),
    # towards +eta a left-handed one.
    site = SITES["YEBES"]
    cases = [([0, -1, 0], [1, 0, 0], "right"), ([0, 1, 0], [-1, 0, 0], "left")]
    for wave, transverse, hand in cases:
        train = MirrorTrain([wave], feed_aligned=[0, 0, 1], feed_transverse=transverse)
        traced = Antenna(site, AltAzMount(), train).feed_rotation(GRID, DAY).rad
        closed = Antenna(site, AltAzMount(), NasmythFocus(hand)).feed_rotation(GRID, DAY).rad
        spread, constant = angle_spread(traced, closed)
        assert spread < 1e-9
        assert_allclose(abs(constant), np.pi, atol=1e-9)


def test_mirror_train_on_another_mount():
    # A ground-fixed feed below an equatorial mount's polar axis, fed by a
    # periscope along the axis: the feed is fixed, so the angle is the mount's
    # (0) plus the rotation of the optics with the hour angle, i.e. a linear
    # function of the hour angle (the 'azimuth' about the pole).
    site = SITES["WETTZ13S"]
    local = local_frame(site)
    # Local frame (xi, eta, a); feed dipoles in ENU facing up the polar axis.
    axis_enu = np.array([local.east, local.north, local.up]) @ k.NORTH_POLE
    aligned = np.cross(axis_enu, [1.0, 0, 0])
    aligned /= np.linalg.norm(aligned)
    transverse = np.cross(axis_enu, aligned)  # aligned x transverse = axis (facing up it)
    train = MirrorTrain([[0, -1, 0], [0, 0, -1]], aligned, transverse, feed_rotates=False)
    antenna = Antenna(site, EquatorialMount(), train)
    sources = SkyCoord(ra=[30, 200] * u.deg, dec=[20, -10] * u.deg)[:, np.newaxis]
    phi = antenna.feed_rotation(sources, DAY).rad
    ha = sources.transform_to(HADec(obstime=DAY, location=site)).ha.rad
    for row in range(2):
        slope, _ = np.polyfit(np.unwrap(ha[row]), np.unwrap(phi[row]), 1)
        assert_allclose(abs(slope), 1.0, atol=1e-9)


def literal_trace(train, s, t, axis, local):
    """Eqs 42-45 as printed, wave by wave in ITRS: the kernel's mirror normal,
    reflection and feed read-out, with the frame of Eq C15 at each line of sight."""
    eta = k.unit(np.cross(axis, s))
    xi = np.cross(eta, axis)

    def in_local(c):
        return c[0] * xi + c[1] * eta + c[2] * axis

    waves = [-s] + [in_local(c) for c in train.wave_vectors]
    q = k.trace_dipole(t, waves)
    if train.feed_rotates:
        ra, rt = in_local(train.feed_aligned), in_local(train.feed_transverse)
    else:
        ra, rt = (c[0] * local.east + c[1] * local.north + c[2] * local.up
                  for c in (train.feed_aligned, train.feed_transverse))
    phi = k.feed_phase(q, waves[-1], ra, rt)
    return -phi if train.reflections % 2 else phi


def random_train(rng, rotates):
    """A train of 1-5 mirrors in random directions, its feed facing the last wave."""
    waves = rng.normal(size=(rng.integers(1, 6), 3))
    if not rotates:
        waves[-1] = [0.0, 0.0, rng.choice([-1.0, 1.0])]
    waves /= np.linalg.norm(waves, axis=-1, keepdims=True)
    aligned = k.unit(np.cross(waves[-1], rng.normal(size=3)))
    boresight = -waves[-1] if rotates else np.array([0.0, 0.0, 1.0])
    transverse = np.cross(boresight, aligned)
    if not rotates:  # fixed feed: dipoles in east-north-up, facing up the (vertical) axis
        aligned = np.array([np.cos(0.4), np.sin(0.4), 0.0])
        transverse = np.array([-np.sin(0.4), np.cos(0.4), 0.0])
        if waves[-1][2] > 0:
            aligned, transverse = transverse, aligned
    return MirrorTrain(waves, aligned, transverse, feed_rotates=rotates)


@pytest.mark.parametrize("rotates", [True, False])
def test_mirror_train_equals_the_literal_trace(rotates):
    # The traced phase is computed with the mirrors after the first combined
    # into one matrix; the literal wave-by-wave trace of Eqs 42-45 must give the
    # same angle (rounding only) for any train, line of sight and dipole t
    # (a natural source's projected pole, or a satellite's transmitter dipole).
    rng = np.random.default_rng(42)
    local = local_frame(SITES["YEBES"])
    for _ in range(20):
        train = random_train(rng, rotates)
        s = k.unit(rng.normal(size=(500, 3)))
        t = rng.normal(size=(500, 3))
        t -= k.dot(t, s)[:, None] * s  # perpendicular to s
        for pole in (True, False):
            dipole = k.project(k.NORTH_POLE, s) if pole else t
            got = train.receiver_phase(s, dipole, local.up, local)
            want = literal_trace(train, s, dipole, local.up, local)
            assert np.array_equal(np.isnan(got), np.isnan(want))
            assert max_angle_difference(got, want) < 1e-12
    # and the degenerate lines of sight (along the fixed axis) are NaN in both
    train = MirrorTrain.yebes40m("X")
    s = np.array([local.up, -local.up])
    got = train.receiver_phase(s, k.project(k.NORTH_POLE, s), local.up, local)
    assert np.isnan(got).all()
    assert np.isnan(literal_trace(train, s, k.project(k.NORTH_POLE, s), local.up, local)).all()


@pytest.mark.parametrize("mount", [AltAzMount(), XYMount("east"), StationaryMount()])
def test_lcp_is_negated(mount):
    antenna = Antenna(SITES["DBR205"], mount)
    rcp = antenna.feed_rotation(GRID, DAY)
    assert_quantity_allclose(antenna.feed_rotation(GRID, DAY, polarization="LCP"), -rcp)
    assert_quantity_allclose(antenna.feed_rotation(GRID, DAY, polarization="lhcp"), -rcp)


@pytest.mark.parametrize("obstime", [DAY[7], DAY[:5]], ids=["scalar", "array"])
def test_scalar_and_array_time(obstime):
    antenna = Antenna(SITES["WETTZ13S"], AltAzMount())
    source = SkyCoord(ra=49.95 * u.deg, dec=41.51 * u.deg)
    phi = antenna.feed_rotation(source, obstime)
    assert phi.shape == obstime.shape
    assert phi.unit == u.deg
    assert phi.isscalar == obstime.isscalar
    # Each element equals the scalar computation.
    for i, t in enumerate(np.atleast_1d(obstime)):
        one = antenna.feed_rotation(source, t)
        assert one.isscalar
        assert_quantity_allclose(np.atleast_1d(phi)[i], one, atol=1e-12 * u.deg)


def test_broadcasting_targets_and_times():
    antenna = Antenna(SITES["WETTZ13S"], AltAzMount())
    sources = SkyCoord(ra=[10, 20, 30] * u.deg, dec=[0, 10, 20] * u.deg)
    assert antenna.feed_rotation(sources[:, np.newaxis], DAY).shape == (3, 96)
    assert antenna.feed_rotation(sources, DAY[:3]).shape == (3,)
    with pytest.raises(ValueError, match=r"target has shape \(3,\), obstime has shape \(96,\)"):
        antenna.feed_rotation(sources, DAY)


def test_geodetic_and_geocentric_vertical():
    # At mid-latitudes the geodetic and geocentric verticals differ by ~0.17-0.19 deg.
    site = SITES["FD-VLBA"]
    geodetic = local_frame(site).up
    geocentric = local_frame(site, vertical="geocentric").up
    angle = np.degrees(np.arccos(geodetic @ geocentric))
    assert 0.15 < angle < 0.2
    # Below 75 deg elevation the parallactic angle moves by up to ~0.6 deg
    # (it diverges towards the zenith, where Psi itself is singular).
    antenna = Antenna(site, AltAzMount())
    a = antenna.feed_rotation(GRID, DAY)
    b = Antenna(site, AltAzMount(), vertical="geocentric").feed_rotation(GRID, DAY)
    low = (antenna.altaz(GRID, DAY)[1] < 75 * u.deg) & (antenna.altaz(GRID, DAY)[1] > 0 * u.deg)
    shift = np.degrees(np.abs(k.wrap_phase((a - b).rad[low])))
    assert 0.3 < shift.max() < 0.7


def test_time_scales_and_strings():
    antenna = Antenna(SITES["YEBES"], AltAzMount())
    source = SkyCoord(ra=49.95 * u.deg, dec=41.51 * u.deg)
    utc = antenna.feed_rotation(source, Time("2023-01-25T20:00:00", scale="utc"))
    tai = antenna.feed_rotation(source, Time("2023-01-25T20:00:00", scale="utc").tai)
    text = antenna.feed_rotation(source, "2023-01-25T20:00:00")
    assert_quantity_allclose(tai, utc, atol=1e-12 * u.deg)
    assert_quantity_allclose(text, utc, atol=1e-12 * u.deg)
