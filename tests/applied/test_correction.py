# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Applying the correction: phases, circular and linear visibilities, Eq 46.

The reference values do not come from the module under test. They come from
a voltage-level model written out here:

* sky components are (north, east); a feed at position angle ``phi`` has its
  X dipole along (cos phi, sin phi) and its Y dipole along (-sin phi, cos phi);
* a wave has complex amplitudes ``E`` with the time factor exp(+i w t); the
  IEEE right-handed wave (Sec. 2: counterclockwise seen by the receiver, i.e.
  turning from north to east on the sky) is E = (1, -i) / sqrt(2);
* dipole voltages are projections, v_X = E . X, v_Y = E . Y; circular voltages
  are v_R = (v_X + i v_Y) / sqrt(2), v_L = (v_X - i v_Y) / sqrt(2);
* a measured phase grows with delay (Eq 1): phase = -arg(v);
* a visibility is V_pq = sum over field samples of v1_p conj(v2_q).

The package's feed rotation is the position angle of the receiver's dipole,
north through east (checked below against astropy's position angle of the
zenith), so it is the ``phi`` of this model. CASA's parallactic-angle Jones
matrix (casacore/CASA ``PJones::calcOneJones``: circular diag(exp(-i pa),
exp(+i pa)); linear [[cos pa, sin pa], [-sin pa, cos pa]]) is what this model
gives, and Eq 46 of the paper (RR phase gains Phi_2 - Phi_1) follows from it.
"""

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import TETE, AltAz, EarthLocation, SkyCoord
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time
from helpers import SITES
from hypothesis import given, settings, strategies as st

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    CassegrainFocus,
    GregorianFocus,
    NasmythFocus,
    Satellite,
    TLEOrbit,
    unwrap,
)
from astropy_feedrot.applied.correction import (
    CIRCULAR_PRODUCTS,
    LINEAR_PRODUCTS,
    correct_linear_visibilities,
    correct_phase,
    correct_visibilities,
    rotation_matrix,
)
from astropy_feedrot.applied.rr_ll import baseline_rr_ll, rr_minus_ll
from astropy_feedrot.core.kernel import wrap_phase

#: X/Y to R/L: rows R = (X + iY)/sqrt(2), L = (X - iY)/sqrt(2).
T = np.array([[1, 1j], [1, -1j]]) / np.sqrt(2)

#: The IEEE right- and left-handed waves in (north, east) components.
RCP_WAVE = np.array([1, -1j]) / np.sqrt(2)
LCP_WAVE = np.array([1, 1j]) / np.sqrt(2)

NANO_DEG = 1e-9 * u.deg
SOURCE = SkyCoord("03h19m48.16s +41d30m42.1s")
NIGHT = Time("2023-01-25T12:00") + np.arange(0, 13, 0.5) * u.hour
#: Effelsberg 100 m (Gregorian focus), approximate geodetic position.
EFFELSBERG = EarthLocation.from_geodetic(6.8836 * u.deg, 50.5248 * u.deg, 417 * u.m)


# --- the voltage-level model ---------------------------------------------------


def dipoles(phi):
    """X and Y dipoles of a feed at position angle ``phi`` (radians), (north, east)."""
    phi = np.asarray(phi, dtype=float)
    x = np.stack([np.cos(phi), np.sin(phi)], axis=-1)
    y = np.stack([-np.sin(phi), np.cos(phi)], axis=-1)
    return x, y


def voltages(field, phi, basis):
    """Voltages (..., k, 2) of a feed at ``phi`` for field samples ``field`` (k, 2)."""
    x, y = dipoles(phi)
    vx = np.einsum("...kc,...c->...k", field, x)
    vy = np.einsum("...kc,...c->...k", field, y)
    if basis == "circular":
        return np.stack([(vx + 1j * vy) / np.sqrt(2), (vx - 1j * vy) / np.sqrt(2)], axis=-1)
    return np.stack([vx, vy], axis=-1)


def observe(coherency, phi1, phi2, basis, geometric=0.0):
    """Visibilities (..., 4) (RR RL LR LL or XX XY YX YY) of a source of ``coherency``.

    ``coherency`` is <E E^H> in (north, east); the field samples are the columns
    of its Cholesky factor. Antenna 2 sees the wave delayed by ``geometric``
    radians of phase.
    """
    field = np.linalg.cholesky(np.asarray(coherency, dtype=complex)).T
    v1 = voltages(field, phi1, basis)
    v2 = voltages(field * np.exp(-1j * geometric), phi2, basis)
    vis = np.einsum("...kp,...kq->...pq", v1, v2.conj())
    return vis.reshape(vis.shape[:-2] + (4,))


def stokes(i=1.0, q=0.0, uu=0.0, v=0.0):
    """Coherency <E E^H> in (north, east) for Stokes parameters (IAU)."""
    return np.array([[i + q, uu + 1j * v], [uu - 1j * v, i - q]])


def phase_of(v):
    """Measured phase (grows with delay, Eq 1) of a voltage, as an Angle in deg."""
    return (-np.angle(v) * u.rad).to(u.deg)


def to_circular(linear):
    """Linear products (..., 4) to circular (..., 4): T V T^H."""
    matrix = linear.reshape(linear.shape[:-1] + (2, 2))
    return (T @ matrix @ T.conj().T).reshape(linear.shape)


# --- the conventions themselves ------------------------------------------------


def test_ieee_rcp_excites_r_only_and_has_positive_v():
    # The field (1, -i)/sqrt(2) e^{iwt} is (cos wt, sin wt): north toward east.
    t = np.linspace(0, 1, 5)
    real_field = np.real(np.sqrt(2) * RCP_WAVE[:, None] * np.exp(1j * np.pi / 2 * t))
    assert np.allclose(real_field, [np.cos(np.pi / 2 * t), np.sin(np.pi / 2 * t)])
    r, ell = voltages(RCP_WAVE[None], 0.0, "circular")[0]
    assert abs(abs(r) - 1) < 1e-15 and abs(ell) < 1e-15
    r, ell = voltages(LCP_WAVE[None], 0.0, "circular")[0]
    assert abs(r) < 1e-15 and abs(abs(ell) - 1) < 1e-15
    # IAU: V > 0 for this wave, RR = I + V.
    coherency = np.outer(RCP_WAVE, RCP_WAVE.conj())
    assert np.allclose(coherency, stokes(i=0.5, v=0.5))


def test_feed_rotation_is_position_angle_of_the_feed():
    # Alt-az Cassegrain: the feed's reference is the zenith direction; its
    # position angle (north through east, true equator of date) from astropy
    # agrees with the package's feed rotation to well below 1 arcsec.
    site = SITES["WETTZ13S"]
    times = Time("2023-01-25T00:00") + np.arange(0, 24, 3) * u.hour
    sources = SkyCoord(ra=[49.95, 200.0] * u.deg, dec=[41.51, -10.0] * u.deg)[:, np.newaxis]
    phi = Antenna(site, AltAzMount()).feed_rotation(sources, times)
    frame = TETE(obstime=times, location=site)
    zenith = SkyCoord(alt=np.full(times.shape, 90) * u.deg, az=0 * u.deg,
                      frame=AltAz(obstime=times, location=site))
    pa = sources.transform_to(frame).position_angle(zenith.transform_to(frame))
    assert_quantity_allclose((phi - pa).wrap_at(180 * u.deg), 0 * u.deg, atol=1 * u.arcsec)


def test_feed_voltages_match_casa_pjones():
    # A feed at phi multiplies R by exp(-i phi), L by exp(+i phi) (CASA PJones,
    # circular), and X/Y by [[cos, sin], [-sin, cos]] = R(-phi) (PJones, linear).
    phi = 0.7
    field = np.array([[0.3 + 0.2j, -0.5 + 0.1j]])
    r0, l0 = voltages(field, 0.0, "circular")[0]
    r, ell = voltages(field, phi, "circular")[0]
    assert np.isclose(r, np.exp(-1j * phi) * r0) and np.isclose(ell, np.exp(1j * phi) * l0)
    pjones_linear = np.array([[np.cos(phi), np.sin(phi)], [-np.sin(phi), np.cos(phi)]])
    assert np.allclose(voltages(field, phi, "linear")[0], pjones_linear @ field[0])
    assert np.allclose(pjones_linear, rotation_matrix(-phi * u.rad))


# --- single-antenna phases -----------------------------------------------------


@pytest.mark.parametrize("hand, wave, index", [("RCP", RCP_WAVE, 0), ("LCP", LCP_WAVE, 1)])
@pytest.mark.parametrize("phi", [0.0, 30.0, -100.0, 179.0])
def test_correct_phase_undoes_a_turned_feed(hand, wave, index, phi):
    # The phase measured by a feed turned by phi, corrected, is the phase of
    # the unturned feed (Appendix D: subtract for RHCP, add for LHCP).
    turned = phase_of(voltages(wave[None], np.radians(phi), "circular")[0, index])
    reference = phase_of(voltages(wave[None], 0.0, "circular")[0, index])
    corrected = correct_phase(turned, phi * u.deg, polarization=hand)
    assert_quantity_allclose((corrected - reference).wrap_at(180 * u.deg), 0 * u.deg,
                             atol=NANO_DEG)


@pytest.mark.parametrize("spelling, sign", [
    ("RCP", 1), ("rcp", 1), ("RHCP", 1), ("R", 1), ("r", 1),
    ("LCP", -1), ("lhcp", -1), ("L", -1), ("l", -1),
])
def test_correct_phase_spellings(spelling, sign):
    # Measured = true + sign * Phi (Eq 1 and Appendix D), so true comes back.
    true, phi = 12.5 * u.deg, 40 * u.deg
    assert_quantity_allclose(correct_phase(true + sign * phi, phi, spelling), true,
                             atol=NANO_DEG)


def test_correct_phase_scalar_array_and_units():
    result = correct_phase(1 * u.rad, 0.25 * u.rad)
    assert result.isscalar and result.unit == u.rad
    assert_quantity_allclose(result, 0.75 * u.rad, atol=1e-15 * u.rad)
    # Result in the unit of the phase; the feed rotation in any angle unit.
    result = correct_phase([0.5, 0.25] * u.cycle, [90, 45] * u.deg)
    assert result.unit == u.cycle
    assert_quantity_allclose(result, [0.25, 0.125] * u.cycle, atol=1e-15 * u.cycle)
    # Broadcasting: (3, 1) phases against (2,) feed rotations.
    phases = [[0], [10], [20]] * u.deg
    result = correct_phase(phases, [1, 2] * u.deg, "LCP")
    assert result.shape == (3, 2)
    assert_quantity_allclose(result, [[1, 2], [11, 12], [21, 22]] * u.deg, atol=NANO_DEG)


def test_correct_phase_keeps_continuity_unless_wrapped():
    phases = [170, 200, 400] * u.deg
    assert_quantity_allclose(correct_phase(phases, -30 * u.deg), [200, 230, 430] * u.deg,
                             atol=NANO_DEG)
    wrapped = correct_phase(phases, -30 * u.deg, wrap=True)
    assert_quantity_allclose(wrapped, [-160, -130, 70] * u.deg, atol=NANO_DEG)
    # (-180, 180]: +180 stays, -180 becomes +180.
    assert_quantity_allclose(correct_phase([170, -190] * u.deg, -10 * u.deg, wrap=True),
                             [180, 180] * u.deg, atol=NANO_DEG)


def test_correct_phase_nan_propagates():
    result = correct_phase([1, 2] * u.deg, [np.nan, 1] * u.deg)
    assert np.isnan(result[0]) and result[1] == 1 * u.deg
    assert np.isnan(correct_phase(1 * u.deg, np.nan * u.deg, wrap=True))


def test_correct_phase_does_not_modify_inputs():
    phase = np.array([1.0, 2.0]) * u.deg
    phi = np.array([0.5, 0.5]) * u.deg
    copies = phase.copy(), phi.copy()
    result = correct_phase(phase, phi)
    assert np.array_equal(phase, copies[0]) and np.array_equal(phi, copies[1])
    assert not np.shares_memory(result, phase) and not np.shares_memory(result, phi)
    # Zero rotation still gives a new array.
    assert not np.shares_memory(correct_phase(phase, 0 * u.deg), phase)


# --- circular visibilities -----------------------------------------------------


@pytest.mark.parametrize("source", [
    stokes(),
    stokes(q=0.1, uu=-0.05),
    stokes(q=0.02, uu=0.03, v=0.01),
    stokes(i=0.5, v=0.5),  # a fully RCP source
])
def test_correct_visibilities_recovers_the_sky(source):
    # Visibilities of feeds at (phi1, phi2), corrected, equal those of feeds
    # at (0, 0) (the sky frame), for any source and geometric phase.
    phi1 = np.radians([0, 20, -75, 160])
    phi2 = np.radians([0, -40, 95, 170])
    observed = observe(source, phi1, phi2, "circular", geometric=0.4)
    sky = observe(source, 0.0, 0.0, "circular", geometric=0.4)
    corrected = correct_visibilities(observed, phi1 * u.rad, phi2 * u.rad, CIRCULAR_PRODUCTS)
    np.testing.assert_allclose(corrected, np.broadcast_to(sky, observed.shape), atol=1e-14)
    # The sky-frame circular products are those of IAU Stokes: RR = I + V,
    # RL = Q + iU, LR = Q - iU, LL = I - V (times the geometric phase).
    i, q, uu, v = (source[0, 0] + source[1, 1]).real / 2, (source[0, 0] - source[1, 1]).real / 2, \
        source[0, 1].real, source[0, 1].imag
    expected = np.array([i + v, q + 1j * uu, q - 1j * uu, i - v]) * np.exp(0.4j)
    np.testing.assert_allclose(sky, expected, atol=1e-14)


def test_circular_closed_forms():
    # The inverse of RR e^{i(phi2 - phi1)}, LL e^{-i(phi2 - phi1)},
    # RL e^{-i(phi1 + phi2)}, LR e^{i(phi1 + phi2)}.
    phi1, phi2 = 0.3, -1.1
    observed = np.array([np.exp(1j * (phi2 - phi1)), np.exp(-1j * (phi1 + phi2)),
                         np.exp(1j * (phi1 + phi2)), np.exp(-1j * (phi2 - phi1))])
    result = correct_visibilities(observed, phi1 * u.rad, phi2 * u.rad,
                                  ("RR", "RL", "LR", "LL"))
    np.testing.assert_allclose(result, np.ones(4), atol=1e-15)


def test_correct_visibilities_product_order_case_and_subsets():
    rng = np.random.default_rng(1)
    vis = rng.normal(size=(6, 4)) + 1j * rng.normal(size=(6, 4))
    phi1, phi2 = np.linspace(0, 3, 6) * u.rad, -40 * u.deg
    reference = correct_visibilities(vis, phi1, phi2, ("RR", "RL", "LR", "LL"))
    order = [3, 0, 2, 1]
    shuffled = correct_visibilities(vis[:, order], phi1, phi2, ("ll", "rr", "Lr", "rL"))
    np.testing.assert_allclose(shuffled, reference[:, order], atol=1e-15)
    parallel = correct_visibilities(vis[:, [0, 3]], phi1, phi2, ["RR", "LL"])
    np.testing.assert_allclose(parallel, reference[:, [0, 3]], atol=1e-15)
    single = correct_visibilities(vis[:, 1:2], phi1, phi2, ("RL",))
    np.testing.assert_allclose(single, reference[:, 1:2], atol=1e-15)


@pytest.mark.parametrize("dtype", [np.complex64, np.complex128])
def test_correct_visibilities_shapes_dtypes_and_no_aliasing(dtype):
    rng = np.random.default_rng(2)
    vis = (rng.normal(size=(5, 3, 4)) + 1j * rng.normal(size=(5, 3, 4))).astype(dtype)
    phi1 = np.linspace(-2, 2, 5)[:, np.newaxis] * u.rad   # (5, 1)
    phi2 = np.linspace(0, 90, 3) * u.deg                  # (3,)
    copies = vis.copy(), phi1.copy(), phi2.copy()
    result = correct_visibilities(vis, phi1, phi2, CIRCULAR_PRODUCTS)
    assert result.shape == vis.shape and result.dtype == dtype
    assert not np.shares_memory(result, vis)
    assert np.array_equal(vis, copies[0])
    assert np.array_equal(phi1, copies[1]) and np.array_equal(phi2, copies[2])
    # Same numbers as the complex128 computation, to the precision of dtype.
    exact = correct_visibilities(vis.astype(complex), phi1, phi2, CIRCULAR_PRODUCTS)
    tolerance = 1e-6 if dtype == np.complex64 else 1e-15
    np.testing.assert_allclose(result, exact, rtol=tolerance, atol=tolerance)
    # Zero rotation still returns a new array.
    zero = correct_visibilities(vis, 0 * u.deg, 0 * u.deg, CIRCULAR_PRODUCTS)
    assert not np.shares_memory(zero, vis) and np.array_equal(zero, vis)


def test_correct_visibilities_scalar_row_list_and_quantity():
    # A single sample (4,) with scalar angles; a list of complex numbers.
    row = [1 + 0j, 0j, 0j, 1 + 0j]
    result = correct_visibilities(row, 10 * u.deg, 40 * u.deg, CIRCULAR_PRODUCTS)
    assert result.shape == (4,)
    np.testing.assert_allclose(np.degrees(np.angle(result[[0, 3]])), [-30, 30], atol=1e-12)
    # A complex Quantity keeps its unit and dtype.
    vis = np.ones((2, 4), dtype=np.complex64) * u.Jy
    result = correct_visibilities(vis, 0 * u.deg, 90 * u.deg, CIRCULAR_PRODUCTS)
    assert isinstance(result, u.Quantity) and result.unit == u.Jy
    assert result.dtype == np.complex64
    # RR e^{i(phi1 - phi2)}, RL e^{i(phi1 + phi2)}, LR e^{-i(...)}, LL e^{-i(phi1 - phi2)}.
    np.testing.assert_allclose(result.value[0], [-1j, 1j, -1j, 1j], atol=1e-7)


def test_correct_visibilities_nan_propagates():
    vis = np.ones((2, 2), dtype=complex)
    result = correct_visibilities(vis, [np.nan, 0] * u.deg, 0 * u.deg, ("RR", "LL"))
    assert np.all(np.isnan(result[0])) and np.allclose(result[1], 1)


# --- linear feeds --------------------------------------------------------------


def test_rotation_matrix_convention():
    # R(90 deg) turns north (1, 0) to east (0, 1); R(a) R(b) = R(a + b);
    # orthogonal with determinant 1.
    np.testing.assert_allclose(rotation_matrix(90 * u.deg) @ [1, 0], [0, 1], atol=1e-15)
    a, b = rotation_matrix(0.3 * u.rad), rotation_matrix(1.1 * u.rad)
    np.testing.assert_allclose(a @ b, rotation_matrix(1.4 * u.rad), atol=1e-15)
    np.testing.assert_allclose(a @ a.T, np.eye(2), atol=1e-15)
    assert np.isclose(np.linalg.det(b), 1)
    # The dipoles of a feed at phi are the rows of R(-phi) (projections).
    x, y = dipoles(0.8)
    np.testing.assert_allclose(rotation_matrix(-0.8 * u.rad), np.stack([x, y]), atol=1e-15)
    stack = rotation_matrix([[0, 30, 60], [90, 120, 150]] * u.deg)
    assert stack.shape == (2, 3, 2, 2) and stack.dtype == float
    np.testing.assert_allclose(stack[1, 0], [[0, -1], [1, 0]], atol=1e-15)
    assert np.all(np.isnan(rotation_matrix(np.nan * u.deg)))


@pytest.mark.parametrize("source", [stokes(q=0.1), stokes(uu=0.1), stokes(q=0.03, uu=-0.04,
                                                                          v=0.02)])
def test_correct_linear_visibilities_recovers_the_sky(source):
    phi1 = np.radians([0, 20, -75, 160])
    phi2 = np.radians([0, -40, 95, 170])
    observed = observe(source, phi1, phi2, "linear", geometric=-1.2)
    sky = observe(source, 0.0, 0.0, "linear", geometric=-1.2)
    corrected = correct_linear_visibilities(observed, phi1 * u.rad, phi2 * u.rad)
    np.testing.assert_allclose(corrected, np.broadcast_to(sky, observed.shape), atol=1e-14)
    # Sky frame: XX = I + Q, XY = U + iV, YX = U - iV, YY = I - Q.
    # (A delay at antenna 2 multiplies V = <v1 v2*> by exp(+i geometric).)
    np.testing.assert_allclose(sky, source.reshape(4) * np.exp(-1.2j), atol=1e-14)


@pytest.mark.parametrize("chi", [0.0, 25.0, 45.0, -80.0])
def test_q_and_u_turn_by_twice_the_feed_rotation(chi):
    # Feeds turned by chi see the polarization angle reduced by chi:
    # Q' = Q cos 2chi + U sin 2chi, U' = -Q sin 2chi + U cos 2chi (from the
    # dipole projections: a wave along north gives v_X = cos chi, v_Y = -sin chi).
    i, q, uu = 1.0, 0.2, -0.1
    c, s = np.cos(np.radians(2 * chi)), np.sin(np.radians(2 * chi))
    qq, uq = q * c + uu * s, -q * s + uu * c
    observed = np.array([i + qq, uq, uq, i - qq], dtype=complex)
    np.testing.assert_allclose(observe(stokes(i, q, uu), np.radians(chi), np.radians(chi),
                                       "linear"), observed, atol=1e-14)
    corrected = correct_linear_visibilities(observed, chi * u.deg, chi * u.deg)
    np.testing.assert_allclose(corrected, [i + q, uu, uu, i - q], atol=1e-14)


def test_unpolarized_source():
    # Equal feed rotations leave I [[1, 0], [0, 1]] unchanged; unequal ones
    # turn it into R(phi2 - phi1) (R(-phi1) I R(-phi2)^T), which the
    # correction undoes. In circular products RR gains e^{i(phi2 - phi1)}.
    identity = np.array([1, 0, 0, 1], dtype=complex)
    np.testing.assert_allclose(observe(np.eye(2), 0.9, 0.9, "linear"), identity, atol=1e-15)
    np.testing.assert_allclose(correct_linear_visibilities(identity, 0.9 * u.rad, 0.9 * u.rad),
                               identity, atol=1e-15)
    d = 0.4 - 1.3
    observed = np.array([np.cos(d), -np.sin(d), np.sin(d), np.cos(d)], dtype=complex)
    np.testing.assert_allclose(observe(np.eye(2), 1.3, 0.4, "linear"), observed, atol=1e-15)
    np.testing.assert_allclose(correct_linear_visibilities(observed, 1.3 * u.rad, 0.4 * u.rad),
                               identity, atol=1e-15)
    circular = to_circular(observed)
    np.testing.assert_allclose(circular, [np.exp(1j * d), 0, 0, np.exp(-1j * d)], atol=1e-15)


def test_linear_and_circular_corrections_agree():
    # Independent cross-check between bases: converting the corrected linear
    # products to circular ones gives the circular correction of the
    # converted observed products, for arbitrary (non-Hermitian) visibilities.
    rng = np.random.default_rng(3)
    linear = rng.normal(size=(7, 4)) + 1j * rng.normal(size=(7, 4))
    phi1, phi2 = rng.uniform(-np.pi, np.pi, 7) * u.rad, rng.uniform(-np.pi, np.pi, 7) * u.rad
    via_linear = to_circular(correct_linear_visibilities(linear, phi1, phi2))
    via_circular = correct_visibilities(to_circular(linear), phi1, phi2, CIRCULAR_PRODUCTS)
    np.testing.assert_allclose(via_linear, via_circular, atol=1e-13)


@pytest.mark.parametrize("dtype", [np.complex64, np.complex128])
def test_correct_linear_visibilities_order_shapes_dtypes(dtype):
    rng = np.random.default_rng(4)
    vis = (rng.normal(size=(3, 5, 4)) + 1j * rng.normal(size=(3, 5, 4))).astype(dtype)
    phi1 = np.linspace(0, 1, 5) * u.rad
    phi2 = [[10], [20], [30]] * u.deg
    copies = vis.copy(), phi1.copy(), phi2.copy()
    reference = correct_linear_visibilities(vis, phi1, phi2)
    assert reference.shape == vis.shape and reference.dtype == dtype
    assert not np.shares_memory(reference, vis) and np.array_equal(vis, copies[0])
    assert np.array_equal(phi1, copies[1]) and np.array_equal(phi2, copies[2])
    order = [3, 1, 0, 2]
    shuffled = correct_linear_visibilities(vis[..., order], phi1, phi2,
                                           ("yy", "XY", "xx", "Yx"))
    np.testing.assert_allclose(shuffled, reference[..., order], rtol=1e-6, atol=1e-6)
    row = correct_linear_visibilities([1 + 0j, 0j, 0j, 1 + 0j], 0 * u.deg, 0 * u.deg)
    assert row.shape == (4,) and np.array_equal(row, [1, 0, 0, 1])
    quantity = correct_linear_visibilities(vis * u.Jy, phi1, phi2)
    assert quantity.unit == u.Jy and quantity.dtype == dtype


def test_correct_linear_visibilities_nan_propagates():
    vis = np.tile(np.array([1, 0, 0, 1], dtype=complex), (2, 1))
    result = correct_linear_visibilities(vis, [0, np.nan] * u.deg, 0 * u.deg)
    assert np.all(np.isnan(result[1])) and np.allclose(result[0], [1, 0, 0, 1])


# --- Eq 46 ---------------------------------------------------------------------


def test_rr_minus_ll_from_visibilities():
    # Eq 46 against the RR - LL phase of visibilities of an unpolarized source
    # built with the voltage model (geometric phase cancels).
    phi1 = np.radians(np.linspace(-170, 170, 9))
    phi2 = np.radians(np.linspace(60, -100, 9))
    vis = observe(np.eye(2), phi1, phi2, "circular", geometric=2.5)
    measured = wrap_phase(np.angle(vis[:, 0]) - np.angle(vis[:, 3])) * u.rad
    predicted = rr_minus_ll(phi1 * u.rad, phi2 * u.rad)
    assert_quantity_allclose(predicted, measured.to(u.deg), atol=NANO_DEG)
    # Antenna 1 leading: RR - LL = 2 (Phi_2 - Phi_1), not 2 (Phi_1 - Phi_2).
    assert_quantity_allclose(rr_minus_ll(0 * u.deg, 30 * u.deg), 60 * u.deg, atol=NANO_DEG)


def test_rr_minus_ll_wrap_shapes_nan():
    result = rr_minus_ll(0.1 * u.rad, 0.3 * u.rad)
    assert result.isscalar and result.unit == u.deg
    assert_quantity_allclose(result, np.degrees(0.4) * u.deg, atol=NANO_DEG)
    assert_quantity_allclose(rr_minus_ll(0 * u.deg, [90, -90, 100] * u.deg),
                             [180, 180, -160] * u.deg, atol=NANO_DEG)
    assert_quantity_allclose(rr_minus_ll(0 * u.deg, [90, -90, 100] * u.deg, wrap=False),
                             [180, -180, 200] * u.deg, atol=NANO_DEG)
    assert rr_minus_ll([[0], [1]] * u.deg, [0, 1, 2] * u.deg).shape == (2, 3)
    assert np.isnan(rr_minus_ll(np.nan * u.deg, 1 * u.deg))
    phi1, phi2 = [1.0, 2.0] * u.deg, [3.0, 4.0] * u.deg
    copies = phi1.copy(), phi2.copy()
    rr_minus_ll(phi1, phi2)
    assert np.array_equal(phi1, copies[0]) and np.array_equal(phi2, copies[1])


@pytest.mark.parametrize("times", [NIGHT[10], NIGHT], ids=["scalar", "array"])
def test_baseline_rr_ll_nasmyth_against_cassegrain(times):
    # Same site: Nasmyth-right minus Cassegrain is the elevation (Eq 38), so
    # RR - LL is twice the elevation.
    site = SITES["YEBES"]
    cassegrain = Antenna(site, AltAzMount(), CassegrainFocus())
    nasmyth = Antenna(site, AltAzMount(), NasmythFocus("right"))
    result = baseline_rr_ll(cassegrain, nasmyth, SOURCE, times)
    expected = (2 * cassegrain.altaz(SOURCE, times)[1]).wrap_at(180 * u.deg)
    assert result.shape == np.shape(times)
    assert_quantity_allclose(result, expected, atol=1e-6 * u.deg)
    # Swapping the antennas negates it.
    assert_quantity_allclose(baseline_rr_ll(nasmyth, cassegrain, SOURCE, times),
                             -expected, atol=1e-6 * u.deg)


def test_baseline_rr_ll_end_to_end_eq46():
    # EFLSBERG (Gregorian) - YEBES40M (Nasmyth right), the baseline of Fig. 7:
    # the RR - LL phase of visibilities built from the two feed rotations.
    effelsberg = Antenna(EFFELSBERG, AltAzMount(), GregorianFocus())
    yebes = Antenna(SITES["YEBES"], AltAzMount(), NasmythFocus("right"))
    phi1 = effelsberg.feed_rotation(SOURCE, NIGHT).to_value(u.rad)
    phi2 = yebes.feed_rotation(SOURCE, NIGHT).to_value(u.rad)
    vis = observe(np.eye(2), phi1, phi2, "circular", geometric=1.0)
    measured = (wrap_phase(np.angle(vis[:, 0]) - np.angle(vis[:, 3])) * u.rad).to(u.deg)
    predicted = baseline_rr_ll(effelsberg, yebes, SOURCE, NIGHT)
    assert_quantity_allclose(predicted, measured, atol=1e-6 * u.deg)
    # And the corrected visibilities have RR = LL: nothing left to see.
    corrected = correct_visibilities(vis, phi1 * u.rad, phi2 * u.rad, CIRCULAR_PRODUCTS)
    np.testing.assert_allclose(corrected[:, 0], corrected[:, 3], atol=1e-12)


def test_baseline_rr_ll_continuous():
    # A hypothetical Nasmyth-left antenna at Effelsberg against YEBES40M
    # (Nasmyth right): RR - LL spans more than half a cycle and crosses
    # +-180 deg during the day; wrap=False keeps it continuous.
    effelsberg = Antenna(EFFELSBERG, AltAzMount(), NasmythFocus("left"))
    yebes = Antenna(SITES["YEBES"], AltAzMount(), NasmythFocus("right"))
    source = SkyCoord(ra=187.28 * u.deg, dec=20 * u.deg)
    day = Time("2023-01-25T00:00") + np.arange(0, 24, 0.25) * u.hour
    wrapped = baseline_rr_ll(effelsberg, yebes, source, day)
    continuous = baseline_rr_ll(effelsberg, yebes, source, day, wrap=False)
    assert np.all(wrapped > -180 * u.deg) and np.all(wrapped <= 180 * u.deg)
    assert np.max(np.abs(np.diff(wrapped))) > 180 * u.deg  # a cycle boundary is crossed
    assert np.max(np.abs(np.diff(continuous))) < 20 * u.deg
    assert_quantity_allclose((continuous - wrapped).wrap_at(180 * u.deg), 0 * u.deg,
                             atol=1e-9 * u.deg)
    # Continuous feed rotations give the same through rr_minus_ll(wrap=False).
    phi1 = unwrap(effelsberg.feed_rotation(source, day))
    phi2 = unwrap(yebes.feed_rotation(source, day))
    assert_quantity_allclose((rr_minus_ll(phi1, phi2, wrap=False) - continuous)
                             .wrap_at(180 * u.deg), 0 * u.deg, atol=1e-9 * u.deg)
    assert np.max(np.abs(np.diff(rr_minus_ll(phi1, phi2, wrap=False)))) < 20 * u.deg
    # Restarts after a gap: each scan starts from 2 (Phi_2 - Phi_1) with the
    # difference in (-180, 180] deg, and is continuous within itself.
    scans = day[[16, 17, 18, 60, 61, 62]]
    restarted = baseline_rr_ll(effelsberg, yebes, source, scans, wrap=False,
                               max_gap=2 * u.hour)
    difference = yebes.feed_rotation(source, scans) - effelsberg.feed_rotation(source, scans)
    starts = 2 * difference.wrap_at(180 * u.deg)[[0, 3]]
    assert_quantity_allclose(restarted[[0, 3]], starts, atol=1e-9 * u.deg)
    assert_quantity_allclose(restarted[:3], continuous[16:19], atol=1e-9 * u.deg)
    assert np.max(np.abs(np.diff(restarted[3:]))) < 20 * u.deg


def test_baseline_rr_ll_min_elevation():
    site1, site2 = SITES["YEBES"], SITES["WETTZ13S"]
    a1, a2 = Antenna(site1, AltAzMount()), Antenna(site2, AltAzMount())
    day = Time("2023-01-25T00:00") + np.arange(0, 24, 1) * u.hour
    south = SkyCoord(ra=200 * u.deg, dec=-30 * u.deg)
    result = baseline_rr_ll(a1, a2, south, day, min_elevation=10 * u.deg)
    low = ((a1.altaz(south, day)[1] < 10 * u.deg) | (a2.altaz(south, day)[1] < 10 * u.deg))
    assert np.any(low) and np.any(~low)
    assert np.array_equal(np.isnan(result), low)


# --- invariants ----------------------------------------------------------------

angles = st.floats(-1e3, 1e3, allow_nan=False)


@settings(max_examples=50, deadline=None)
@given(angles, angles, st.sampled_from(["RCP", "LCP"]))
def test_phase_correction_round_trip(phase, phi, hand):
    # Correcting with Phi and then with -Phi is the identity; RCP with Phi is
    # LCP with -Phi.
    once = correct_phase(phase * u.deg, phi * u.deg, hand)
    back = correct_phase(once, -phi * u.deg, hand)
    assert_quantity_allclose(back, phase * u.deg, atol=1e-9 * u.deg)
    other = "LCP" if hand == "RCP" else "RCP"
    assert_quantity_allclose(correct_phase(phase * u.deg, -phi * u.deg, other), once,
                             atol=1e-9 * u.deg)


@settings(max_examples=50, deadline=None)
@given(angles, angles, angles, angles)
def test_visibility_corrections_compose(a1, a2, b1, b2):
    # Correcting by (a1, a2) then (b1, b2) is correcting by their sums, in both
    # bases; with b = -a it is the identity.
    rng = np.random.default_rng(5)
    vis = rng.normal(size=4) + 1j * rng.normal(size=4)
    for correct, products in ((correct_visibilities, CIRCULAR_PRODUCTS),
                              (correct_linear_visibilities, LINEAR_PRODUCTS)):
        twice = correct(correct(vis, a1 * u.deg, a2 * u.deg, products),
                        b1 * u.deg, b2 * u.deg, products)
        once = correct(vis, (a1 + b1) * u.deg, (a2 + b2) * u.deg, products)
        np.testing.assert_allclose(twice, once, atol=1e-9)
        back = correct(correct(vis, a1 * u.deg, a2 * u.deg, products),
                       -a1 * u.deg, -a2 * u.deg, products)
        np.testing.assert_allclose(back, vis, atol=1e-12)


@settings(max_examples=50, deadline=None)
@given(angles, angles)
def test_bases_agree_for_any_angles(phi1, phi2):
    linear = np.array([1.2 + 0.1j, 0.3 - 0.2j, -0.1 + 0.4j, 0.8 - 0.3j])
    via_linear = to_circular(correct_linear_visibilities(linear, phi1 * u.deg, phi2 * u.deg))
    via_circular = correct_visibilities(to_circular(linear), phi1 * u.deg, phi2 * u.deg,
                                        CIRCULAR_PRODUCTS)
    np.testing.assert_allclose(via_linear, via_circular, atol=1e-12)


# --- errors --------------------------------------------------------------------

VIS = np.ones((3, 4), dtype=complex)


@pytest.mark.parametrize("call", [
    lambda bad: correct_phase(bad, 1 * u.deg),
    lambda bad: correct_phase(1 * u.deg, bad),
    lambda bad: correct_visibilities(VIS, bad, 1 * u.deg, CIRCULAR_PRODUCTS),
    lambda bad: correct_visibilities(VIS, 1 * u.deg, bad, CIRCULAR_PRODUCTS),
    lambda bad: correct_linear_visibilities(VIS, bad, 1 * u.deg),
    lambda bad: rotation_matrix(bad),
    lambda bad: rr_minus_ll(bad, 1 * u.deg),
    lambda bad: rr_minus_ll(1 * u.deg, bad),
])
def test_angles_need_units(call):
    with pytest.raises(TypeError, match=r"must be an angle Quantity .* got float; plain "
                                        "numbers are refused"):
        call(0.5)
    with pytest.raises(TypeError, match="got list"):
        call([0.5, 1.0])
    with pytest.raises(u.UnitsError, match=r"must be an angle .* got a quantity in m"):
        call(3 * u.m)
    with pytest.raises(u.UnitsError, match="dimensionless units; attach an angle unit"):
        call(0.5 * u.one)


def test_correct_phase_errors():
    with pytest.raises(ValueError, match=r"polarization must be one of \['L', 'LCP'"):
        correct_phase(1 * u.deg, 1 * u.deg, "X")
    with pytest.raises(ValueError, match="polarization must be one of"):
        correct_phase(1 * u.deg, 1 * u.deg, None)
    with pytest.raises(ValueError, match=r"phase has shape \(3,\), feed_rotation has shape "
                                         r"\(2,\)"):
        correct_phase([1, 2, 3] * u.deg, [1, 2] * u.deg)


def test_rr_minus_ll_shape_error():
    with pytest.raises(ValueError, match=r"feed_rotation1 has shape \(3,\), feed_rotation2 "
                                         r"has shape \(2,\)"):
        rr_minus_ll([1, 2, 3] * u.deg, [1, 2] * u.deg)


@pytest.mark.parametrize("correct, valid", [
    (correct_visibilities, CIRCULAR_PRODUCTS),
    (correct_linear_visibilities, LINEAR_PRODUCTS),
])
def test_product_errors(correct, valid):
    def call(products, vis=VIS):
        return correct(vis, 1 * u.deg, 2 * u.deg, products)

    with pytest.raises(TypeError, match="a sequence of names .* not the single string"):
        call("".join(valid))
    with pytest.raises(TypeError, match="a sequence of names .* got 5"):
        call(5)
    with pytest.raises(TypeError, match="a sequence of names"):
        call((1, 2, 3, 4))
    wrong = ("XX", "XY", "YX", "YY") if valid == CIRCULAR_PRODUCTS else ("RR", "RL", "LR", "LL")
    with pytest.raises(ValueError, match=r"unknown product names \['%s'" % wrong[0]):
        call(wrong)
    with pytest.raises(ValueError, match=r"valid names are \('%s'" % valid[0]):
        call(valid[:3] + ("QQ",))
    with pytest.raises(ValueError, match=r"products names \['%s'\] more than once" % valid[0]):
        call((valid[0],) + valid[:3])
    with pytest.raises(ValueError, match="products is empty"):
        call(())
    with pytest.raises(ValueError, match=r"last axis of visibilities must hold the 4 products"
                                         r".* got shape \(3, 3\)"):
        call(valid, VIS[:, :3])
    with pytest.raises(ValueError, match=r"got shape \(\)"):
        call(valid, np.complex128(1))


def test_linear_needs_all_four_products():
    with pytest.raises(ValueError, match=r"products lacks \['YX', 'YY'\]: the feed rotation "
                                         "of linear feeds mixes all four"):
        correct_linear_visibilities(VIS[:, :2], 1 * u.deg, 1 * u.deg, ("XX", "XY"))


@pytest.mark.parametrize("correct, products", [
    (correct_visibilities, CIRCULAR_PRODUCTS),
    (correct_linear_visibilities, LINEAR_PRODUCTS),
])
def test_visibility_errors(correct, products):
    for real in (np.ones((3, 4)), np.ones((3, 4), dtype=int), np.ones((3, 4)) * u.Jy):
        with pytest.raises(TypeError, match="visibilities must be complex, got dtype"):
            correct(real, 1 * u.deg, 1 * u.deg, products)
    with pytest.raises(TypeError, match="got dtype <U1"):
        correct(np.array(["a"] * 4), 1 * u.deg, 1 * u.deg, products)
    with pytest.raises(ValueError, match=r"feed_rotation1 has shape \(4,\), which does not "
                                         r"broadcast to the shape \(3,\) of visibilities"):
        correct(VIS, [1, 2, 3, 4] * u.deg, 1 * u.deg, products)
    # An angle that would enlarge the visibilities is refused too.
    with pytest.raises(ValueError, match=r"feed_rotation2 has shape \(2, 3\), which does not "
                                         r"broadcast to the shape \(3,\)"):
        correct(VIS, 1 * u.deg, np.zeros((2, 3)) * u.deg, products)


def test_baseline_rr_ll_errors():
    site = SITES["YEBES"]
    antenna = Antenna(site, AltAzMount())
    with pytest.raises(TypeError, match="antenna1 must be an Antenna, got EarthLocation"):
        baseline_rr_ll(site, antenna, SOURCE, NIGHT)
    with pytest.raises(TypeError, match="antenna2 must be an Antenna, got str"):
        baseline_rr_ll(antenna, "YEBES", SOURCE, NIGHT)
    gps = Satellite(TLEOrbit(
        "1 41328U 16007A   23024.39332179  .00000015  00000-0  00000+0 0  9995",
        "2 41328  54.9577 138.7050 0066950 231.2234 128.1638  2.00560135 51012"))
    with pytest.raises(TypeError, match="weakly polarized natural source; .* transmits RCP "
                                        "only"):
        baseline_rr_ll(antenna, antenna, gps, NIGHT)
    with pytest.raises(ValueError, match="max_gap applies to the continuous series only; "
                                         "pass wrap=False"):
        baseline_rr_ll(antenna, antenna, SOURCE, NIGHT, max_gap=1 * u.hour)
