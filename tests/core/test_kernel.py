# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Identities of the geometry kernel.

Every reference here is an identity the paper states (its equation number is
given) or elementary vector algebra computed a second, independent way
(explicit 3x3 matrices instead of the kernel's vector shortcuts).
"""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from hypothesis.extra.numpy import arrays
from numpy.testing import assert_allclose

from astropy_feedrot.core import kernel as k

# Tolerance of identities between two double-precision evaluations of the same
# angle, in radians (2e-10 rad = 40 microarcsec).
ATOL = 2e-10

finite = st.floats(-1.0, 1.0, allow_nan=False, allow_infinity=False)
vec3 = arrays(np.float64, 3, elements=finite).filter(lambda v: np.linalg.norm(v) > 0.2)
unit3 = vec3.map(lambda v: v / np.linalg.norm(v))
angle = st.floats(-np.pi, np.pi, allow_nan=False)
quaternion = arrays(np.float64, 4, elements=finite).filter(lambda q: np.linalg.norm(q) > 0.2)


def rotation(q):
    """Rotation matrix of a (not necessarily unit) quaternion, scalar first."""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def triad(q):
    """A right-handed orthonormal triad (aligned, transverse, boresight)."""
    m = rotation(q)
    return m[:, 0], m[:, 1], m[:, 2]


def dipoles_facing(s, gamma, sign=1):
    """Aligned/transverse dipoles whose boresight is ``sign * s``."""
    helper = np.array([1.0, 0, 0]) if abs(s[0]) < 0.9 else np.array([0, 1.0, 0])
    e1 = np.cross(helper, s)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(s, e1)
    a = np.cos(gamma) * e1 + np.sin(gamma) * e2
    t = sign * np.cross(s, a)  # a x t = sign * s
    return a, t


def same_angle(a, b, atol=ATOL):
    """Assert two angles agree modulo 2 pi."""
    assert_allclose(k.wrap_phase(np.asarray(a) - np.asarray(b)), 0.0, atol=atol)


# --- Eqs 4 and 6 ----------------------------------------------------------


@given(unit3, vec3)
def test_projection_and_cross_matrices(s, v):
    p = k.projection_matrix(s)
    sx = k.cross_matrix(s)
    # Properties stated below Eq 5: symmetric, idempotent, P = S S^T.
    assert_allclose(p, p.T, atol=1e-15)
    assert_allclose(p @ p, p, atol=1e-14)
    assert_allclose(sx @ sx.T, p, atol=1e-14)
    # S v = s x v (Eq 6) and P v = v - (v.s) s.
    assert_allclose(sx @ v, np.cross(s, v), atol=1e-14)
    assert_allclose(k.project(v, s), p @ v, atol=1e-14)


def test_matrices_broadcast():
    s = np.array([[0.0, 0, 1], [1.0, 0, 0]])
    assert k.projection_matrix(s).shape == (2, 3, 3)
    assert k.cross_matrix(s).shape == (2, 3, 3)
    assert_allclose(k.cross_matrix(s)[1] @ [0, 1.0, 0], [0, 0, 1.0])


# --- Eqs 5, 7, 8: the two forms agree when a boresight is on the line of sight


@given(unit3, angle, quaternion)
def test_beyerle_equals_wu_receiver_boresight_on_line_of_sight(s, gamma, qt):
    # Appendix A, Eqs A1-A3: receiver boresight r^b = s.
    ra, rt = dipoles_facing(s, gamma, sign=1)
    ta, tt, _ = triad(qt)
    r = k.receiver_effective_dipole(s, ra, rt)
    t = k.transmitter_effective_dipole(s, ta, tt)
    if np.linalg.norm(t) < 1e-3:  # transmitter seen edge-on: both undefined
        return
    same_angle(k.beyerle_phase(s, ra, rt, ta, tt), k.wu_phase(s, r, t), atol=1e-9)


@given(unit3, angle, quaternion)
def test_beyerle_equals_wu_transmitter_boresight_on_line_of_sight(s, gamma, qr):
    # Appendix A, Eqs A4-A5: transmitter boresight t^b = -s.
    ta, tt = dipoles_facing(s, gamma, sign=-1)
    ra, rt, _ = triad(qr)
    r = k.receiver_effective_dipole(s, ra, rt)
    t = k.transmitter_effective_dipole(s, ta, tt)
    if np.linalg.norm(r) < 1e-3:
        return
    same_angle(k.beyerle_phase(s, ra, rt, ta, tt), k.wu_phase(s, r, t), atol=1e-9)


def test_beyerle_differs_from_wu_off_boresight():
    # Neither boresight on the line of sight: the forms differ (Sec. 2.1), which
    # shows the test above can fail.
    s = np.array([0.0, 0.8, 0.6])
    ra, rt, _ = triad(np.array([1.0, 0.0, 0.0, 0.0]))
    ta, tt, _ = triad(np.array([1.0, 0.0, 0.7, 0.3]))
    r = k.receiver_effective_dipole(s, ra, rt)
    t = k.transmitter_effective_dipole(s, ta, tt)
    assert abs(k.wrap_phase(k.beyerle_phase(s, ra, rt, ta, tt) - k.wu_phase(s, r, t))) > 0.1


@given(unit3, quaternion, quaternion)
def test_beyerle_phase_matches_matrix_form(s, qr, qt):
    # Eq 5 as printed, with the explicit projection matrix of Eq 4:
    # tan(Phi) = (r^a P t^t + r^t P t^a) / (r^a P t^a - r^t P t^t).
    ra, rt, _ = triad(qr)
    ta, tt, _ = triad(qt)
    p = k.projection_matrix(s)
    num = ra @ p @ tt + rt @ p @ ta
    den = ra @ p @ ta - rt @ p @ tt
    if np.hypot(num, den) < 1e-3:  # ill-conditioned (both boresights on the sky plane)
        return
    same_angle(k.beyerle_phase(s, ra, rt, ta, tt), np.arctan2(num, den))
    # The same from the eight scalar products alone.
    products = [ra @ ta, ra @ tt, rt @ ta, rt @ tt, s @ ra, s @ rt, s @ ta, s @ tt]
    same_angle(k.beyerle_phase_from_products(*products), np.arctan2(num, den))


@given(unit3, vec3, vec3)
def test_effective_dipoles_are_on_the_sky_plane(s, a, b):
    # "These vectors are by construction orthogonal to s" (below Eq 8).
    assert abs(k.dot(k.receiver_effective_dipole(s, a, b), s)) < 1e-14
    assert abs(k.dot(k.transmitter_effective_dipole(s, a, b), s)) < 1e-14


@given(unit3, vec3, vec3)
def test_wu_phase_matches_matrix_form(s, r, t):
    # Eq 7 evaluated with the explicit matrices of Eqs 4 and 6:
    # tan(Phi) = r^T S^T t / r^T t for r, t on the sky plane.
    p = k.projection_matrix(s)
    sx = k.cross_matrix(s)
    rp, tp = p @ r, p @ t
    if min(np.linalg.norm(rp), np.linalg.norm(tp)) < 1e-3:
        return
    expected = np.arctan2(rp @ sx.T @ tp, rp @ tp)
    same_angle(k.wu_phase(s, r, t), expected)


# --- Eqs 20-22: the split terms add up ------------------------------------


@given(unit3, vec3, vec3)
def test_split_terms_add_up(s, r, t):
    z = k.NORTH_POLE
    r = k.project(r, s)
    t = k.project(t, s)
    if min(np.linalg.norm(r), np.linalg.norm(t), np.linalg.norm(k.project(z, s))) < 1e-3:
        return
    total = k.wu_phase(s, r, t)
    same_angle(k.transmitter_term(s, t) + k.receiver_term(s, r), total, atol=1e-9)


@given(unit3, vec3)
def test_transmitter_term_printed_form(s, t):
    # Eq 21 as printed: tan(Phi_tx) = z^T S^T t / z^T t (t on the sky plane).
    z = k.NORTH_POLE
    t = k.project(t, s)
    if min(np.linalg.norm(t), np.linalg.norm(k.project(z, s))) < 1e-3:
        return
    sx = k.cross_matrix(s)
    same_angle(k.transmitter_term(s, t), np.arctan2(z @ sx.T @ t, z @ t))
    # Eq 22 as printed: tan(Phi_rx) = r^T S^T z / r^T z.
    same_angle(k.receiver_term(s, t), np.arctan2(t @ sx.T @ z, t @ z))


# --- Invariance under a common rotation ----------------------------------


@given(unit3, quaternion, quaternion, quaternion)
def test_angles_invariant_under_common_rotation(s, qr, qt, qrot):
    ra, rt, _ = triad(qr)
    ta, tt, _ = triad(qt)
    rot = rotation(qrot)
    r = k.receiver_effective_dipole(s, ra, rt)
    t = k.transmitter_effective_dipole(s, ta, tt)
    if min(np.linalg.norm(r), np.linalg.norm(t)) < 1e-3:
        return
    rs, rra, rrt, rta, rtt = (rot @ v for v in (s, ra, rt, ta, tt))
    same_angle(k.wu_phase(rs, rot @ r, rot @ t), k.wu_phase(s, r, t), atol=1e-9)
    # Eq 5's numerator and denominator; where both are tiny the angle is
    # ill-conditioned (a receiver dipole along the line of sight).
    pta, ptt = k.project(ta, s), k.project(tt, s)
    if np.hypot(ra @ ptt + rt @ pta, ra @ pta - rt @ ptt) > 1e-3:
        same_angle(
            k.beyerle_phase(rs, rra, rrt, rta, rtt), k.beyerle_phase(s, ra, rt, ta, tt), atol=1e-9
        )
    # Effective dipoles are covariant.
    assert_allclose(k.receiver_effective_dipole(rs, rra, rrt), rot @ r, atol=1e-13)
    # A mirror train: the traced phase is invariant too.
    if np.linalg.norm(np.cross(s, ra)) < 1e-3:
        return
    kv = [-s, k.unit(np.cross(s, ra)), ra]
    if min(np.linalg.norm(kv[1] - kv[0]), np.linalg.norm(kv[2] - kv[1])) < 1e-3:
        return
    fa, ft = dipoles_facing(-kv[-1], 0.4, sign=1)
    phi = k.feed_phase(k.trace_dipole(t, kv), kv[-1], fa, ft)
    rphi = k.feed_phase(k.trace_dipole(rot @ t, [rot @ v for v in kv]), rot @ kv[-1],
                        rot @ fa, rot @ ft)
    same_angle(rphi, phi, atol=1e-9)


@given(unit3, vec3, vec3, angle)
def test_split_terms_invariant_under_rotation_about_pole(s, r, t, alpha):
    # The split terms refer to the pole z, which a rotation about z keeps.
    rot = np.array([[np.cos(alpha), -np.sin(alpha), 0], [np.sin(alpha), np.cos(alpha), 0],
                    [0, 0, 1.0]])
    r = k.project(r, s)
    t = k.project(t, s)
    if min(np.linalg.norm(r), np.linalg.norm(t), np.linalg.norm(k.project(k.NORTH_POLE, s))) < 1e-3:
        return
    same_angle(k.transmitter_term(rot @ s, rot @ t), k.transmitter_term(s, t), atol=1e-9)
    same_angle(k.receiver_term(rot @ s, rot @ r), k.receiver_term(s, r), atol=1e-9)


# --- Eqs 42-45: reflections ----------------------------------------------


@given(unit3, unit3, vec3)
def test_reflection_keeps_dipole_on_sky_plane(k_in, k_out, q):
    if np.linalg.norm(k_out - k_in) < 1e-3:
        return
    q = k.project(q, k_in)
    n = k.mirror_normal(k_in, k_out)
    # Law of reflection: k_out = k_in - 2 (k_in . n) n.
    assert_allclose(k_in - 2 * k.dot(k_in, n) * n, k_out, atol=1e-12)
    q2 = k.reflect_dipole(q, n)
    assert_allclose(np.linalg.norm(q2), np.linalg.norm(q), rtol=1e-12)
    assert abs(k.dot(q2, k_out)) < 1e-12


@given(unit3, angle, vec3)
def test_feed_phase_without_mirrors_is_eq31(s, gamma, t):
    # With k_out x q (not the printed q x k_out), Eq 45 reduces to Eq 31 when there is no
    # mirror (k_out = -s, q = t), for receiver dipoles in any orientation.
    t = k.project(t, s)
    if np.linalg.norm(t) < 1e-3:
        return
    ra, rt, _ = triad(np.array([np.cos(gamma), 0.3, np.sin(gamma), -0.2]))
    r = k.receiver_effective_dipole(s, ra, rt)
    if np.linalg.norm(r) < 1e-3:
        return
    # Eq 31, numerator and denominator as printed.
    sx = k.cross_matrix(s)
    eq31 = np.arctan2(ra @ sx.T @ t + rt @ t, ra @ t - rt @ sx.T @ t)
    same_angle(k.feed_phase(t, -s, ra, rt), eq31, atol=1e-9)
    same_angle(k.feed_phase(t, -s, ra, rt), k.wu_phase(s, r, t), atol=1e-9)


def test_two_mirror_periscope_preserves_phase():
    # Two parallel plane mirrors (a periscope) return the beam to its original
    # direction; the dipole is reflected twice and its phase is unchanged.
    s = np.array([0.0, 0.0, 1.0])
    kv = [-s, np.array([1.0, 0, 0]), -s]
    t = np.array([np.cos(0.7), np.sin(0.7), 0.0])
    ra, rt = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    assert_allclose(k.trace_dipole(t, kv), t, atol=1e-15)
    assert_allclose(k.feed_phase(k.trace_dipole(t, kv), kv[-1], ra, rt),
                    k.feed_phase(t, -s, ra, rt), atol=1e-15)


# --- Degenerate and NaN input --------------------------------------------


def test_degenerate_geometry_gives_nan():
    s = np.array([0.0, 0.0, 1.0])
    # Fixed axis along the line of sight: P a = 0.
    assert np.isnan(k.receiver_term(s, [0, 0, 1.0]))
    # Source at the celestial pole: the reference direction vanishes.
    assert np.isnan(k.transmitter_term(s, [1.0, 0, 0]))
    assert np.isnan(k.wu_phase(s, [1.0, 0, 0], [0, 0, 2.0]))
    assert np.isnan(k.beyerle_phase(s, [0, 0, 1.0], [0, 0, 1.0], [0, 0, 1.0], [0, 0, 1.0]))
    assert np.isnan(k.feed_phase([0, 0, 0.0], -s, [1.0, 0, 0], [0, 1.0, 0]))
    assert np.all(np.isnan(k.mirror_normal(s, s)))
    assert np.all(np.isnan(k.unit([0.0, 0, 0])))
    # Just outside the tolerance the angle is defined.
    tilt = np.array([0.0, 1e-8, 1.0])
    assert np.isfinite(k.receiver_term(k.unit(tilt), [0, 0, 1.0]))


def test_nan_in_nan_out():
    s = np.array([[0.0, 0.6, 0.8], [np.nan, 0.0, 1.0]])
    out = k.receiver_term(s, [0.0, 0.0, 1.0])
    assert np.isfinite(out[0]) and np.isnan(out[1])
    out = k.beyerle_phase(s, [1.0, 0, 0], [0, 1.0, 0], [1.0, 0, 0], [0, -1.0, 0])
    assert np.isfinite(out[0]) and np.isnan(out[1])


# --- Eq 9: cycle continuity -----------------------------------------------


@settings(max_examples=50)
@given(arrays(np.float64, st.integers(1, 60), elements=st.floats(-3.0, 3.0)), angle)
def test_unwrap_recovers_series_with_small_steps(steps, start):
    truth = start + np.cumsum(steps)
    wrapped = k.wrap_phase(truth)
    out = k.unwrap_phase(wrapped)
    # Continuous: equal to the truth up to one whole number of cycles.
    offset = (out - truth) / (2 * np.pi)
    assert_allclose(offset, np.round(offset[0]), atol=1e-9)
    assert out[0] == wrapped[0]
    assert_allclose(out, np.unwrap(wrapped), atol=1e-12)


def test_unwrap_skips_nan_and_works_along_an_axis():
    series = np.array([[np.nan, 3.0, -3.0, np.nan, -2.5], [0.0, 1.0, 2.0, 3.0, -3.0]])
    out = k.unwrap_phase(series, axis=1)
    assert np.isnan(out[0, 0]) and np.isnan(out[0, 3])
    assert_allclose(out[0, [1, 2, 4]], [3.0, 2 * np.pi - 3.0, 2 * np.pi - 2.5])
    assert_allclose(out[1], [0.0, 1.0, 2.0, 3.0, 2 * np.pi - 3.0])
    assert_allclose(k.unwrap_phase(series.T, axis=0), out.T)
    assert np.all(np.isnan(k.unwrap_phase(np.full(4, np.nan))))
    assert k.unwrap_phase(np.float64(1.0)) == 1.0


@given(st.floats(-100, 100), st.floats(-100, 100))
def test_nearest_cycle(phase, previous):
    out = k.nearest_cycle(phase, previous)
    assert -np.pi - 1e-9 <= out - previous <= np.pi + 1e-9
    cycles = (out - phase) / (2 * np.pi)
    assert abs(cycles - round(cycles)) < 1e-9


@given(st.floats(-1e3, 1e3))
def test_wrap_phase_interval(x):
    w = k.wrap_phase(x)
    assert -np.pi < w <= np.pi
    cycles = (w - x) / (2 * np.pi)
    assert abs(cycles - round(cycles)) < 1e-9


@pytest.mark.parametrize("shape", [(), (4,), (2, 3)])
def test_kernel_broadcasts(shape):
    rng = np.random.default_rng(1)
    s = k.unit(rng.normal(size=shape + (3,)))
    a = np.array([0.0, 0.0, 1.0])
    assert k.receiver_term(s, a).shape == shape
    assert k.wu_phase(s[..., np.newaxis, :], a, k.NORTH_POLE).shape == shape + (1,)
