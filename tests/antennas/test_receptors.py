# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Receptors and the receptor-by-receptor correction of visibilities.

The references are a voltage-level model written here from the definitions
(a dipole at position angle theta answers cos(theta) E_north + sin(theta)
E_east; IEEE right-hand circular R = (X + iY)/sqrt(2) with Y 90 deg east of
X), and the identities with `correct_visibilities` and
`correct_linear_visibilities`, which take one angle per antenna.
"""

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.utils.masked import Masked

from astropy_feedrot import AltAzMount, Antenna
from astropy_feedrot.antennas.receptors import Receptors, basis_of
from astropy_feedrot.applied.correction import (
    correct_linear_visibilities,
    correct_receptor_visibilities,
    correct_visibilities,
)

LINEAR = ["XX", "XY", "YX", "YY"]
CIRCULAR = ["RR", "RL", "LR", "LL"]


def dipole(theta):
    """The row of a dipole at position angle theta (radians), north through east."""
    return np.array([np.cos(theta), np.sin(theta)])


def coherency(i, q, u_, v):
    """<E E^H> in (north, east) for Stokes I, Q, U, V (IAU: Q along north-south,
    U at 45 deg toward east, V > 0 right-handed in the IEEE sense)."""
    return 0.5 * np.array([[i + q, u_ + 1j * v], [u_ - 1j * v, i - q]])


def observe(jones1, jones2, sky):
    """V_pq = <v1p v2q*> = (J1 B J2^H)_pq."""
    return jones1 @ sky @ jones2.conj().T


def linear_rows(theta_x, theta_y):
    return np.array([dipole(theta_x), dipole(theta_y)])


def circular_rows(theta_r, theta_l):
    # R from two dipoles at theta and theta + 90 deg: (X + iY)/sqrt(2); L: (X - iY)/sqrt(2).
    r = (dipole(theta_r) + 1j * dipole(theta_r + np.pi / 2)) / np.sqrt(2)
    ell = (dipole(theta_l) - 1j * dipole(theta_l + np.pi / 2)) / np.sqrt(2)
    return np.array([r, ell])


SKY = coherency(1.0, 0.1 * np.cos(np.radians(53.2)), 0.1 * np.sin(np.radians(53.2)), 0.02)


def test_jones_rows_follow_the_definitions():
    for theta in np.radians([0.0, 17.0, 123.0, -80.0]):
        phi = np.degrees(theta) * u.deg
        np.testing.assert_allclose(Receptors("XY").jones(phi),
                                   linear_rows(theta, theta + np.pi / 2), atol=1e-15)
        np.testing.assert_allclose(Receptors("RL").jones(phi), circular_rows(theta, theta),
                                   atol=1e-15)
        # An RCP voltage rotated by Phi is multiplied by exp(-i Phi) (Appendix D).
        np.testing.assert_allclose(Receptors("R").jones(phi)[0],
                                   np.exp(-1j * theta) * np.array([1, 1j]) / np.sqrt(2),
                                   atol=1e-15)


@pytest.mark.parametrize("types, angles", [
    ("XY", [0, 90]),      # IAU X north, Y east at zero feed rotation
    ("XY", [90, 0]),      # pyuvdata's ATA default: Y 90 deg before X
    ("YX", [0, 90]),      # the file lists Y first
    ("XY", [45, -45]),    # pyuvdata's SMA default
    ("XY", [12.5, 99.0]),  # not perpendicular
])
@pytest.mark.parametrize("conjugate", [False, True])
def test_linear_voltage_model(types, angles, conjugate):
    rng = np.random.default_rng(1)
    phi1, phi2 = rng.uniform(-180, 180, (2, 7))
    receptors = Receptors(types, angles * u.deg)
    order = [types.index(letter) for letter in "XY"]
    data = []
    for p1, p2 in zip(phi1, phi2):
        t1 = np.radians(p1 + np.asarray(angles, float))[order]
        t2 = np.radians(p2 + np.asarray(angles, float))[order]
        v = observe(linear_rows(*t1), linear_rows(*t2), SKY)
        data.append(v.ravel())  # XX, XY, YX, YY
    data = np.array(data)
    if conjugate:
        data = data.conj()
    theta1 = receptors.position_angles(phi1 * u.deg)[:, order]
    theta2 = receptors.position_angles(phi2 * u.deg)[:, order]
    out = correct_receptor_visibilities(data, theta1, theta2, LINEAR, conjugate=conjugate)
    expected = np.broadcast_to(SKY.ravel(), out.shape)
    np.testing.assert_allclose(out.conj() if conjugate else out, expected, atol=1e-14)


@pytest.mark.parametrize("products", [CIRCULAR, ["LL", "RR"], ["RL"], ["LR", "RR"]])
@pytest.mark.parametrize("conjugate", [False, True])
def test_circular_voltage_model(products, conjugate):
    rng = np.random.default_rng(2)
    phi1, phi2 = rng.uniform(-180, 180, (2, 5))
    alpha1, alpha2 = np.array([10.0, -3.0]), np.array([0.5, 7.0])  # (R, L) receptor angles
    sky_circular = circular_rows(0, 0) @ SKY @ circular_rows(0, 0).conj().T
    names = ["RR", "RL", "LR", "LL"]
    rows = []
    for p1, p2 in zip(phi1, phi2):
        t1, t2 = np.radians(p1 + alpha1), np.radians(p2 + alpha2)
        v = observe(circular_rows(*t1), circular_rows(*t2), SKY).ravel()
        rows.append([v[names.index(p)] for p in products])
    data = np.array(rows)
    if conjugate:
        data = data.conj()
    theta1 = (phi1[:, None] + alpha1) * u.deg
    theta2 = (phi2[:, None] + alpha2) * u.deg
    out = correct_receptor_visibilities(data, theta1, theta2, products, conjugate=conjugate)
    expected = [sky_circular.ravel()[names.index(p)] for p in products]
    np.testing.assert_allclose(out.conj() if conjugate else out,
                               np.broadcast_to(expected, out.shape), atol=1e-14)


def test_identities_with_one_angle_per_antenna():
    rng = np.random.default_rng(3)
    data = rng.normal(size=(6, 3, 4)) + 1j * rng.normal(size=(6, 3, 4))
    phi1, phi2 = rng.uniform(-180, 180, (2, 6, 1)) * u.deg
    # Circular, zero receptor angles: correct_visibilities.
    theta1 = Receptors("RL").position_angles(phi1)
    theta2 = Receptors("RL").position_angles(phi2)
    np.testing.assert_allclose(
        correct_receptor_visibilities(data, theta1, theta2, CIRCULAR),
        correct_visibilities(data, phi1, phi2, CIRCULAR), atol=1e-13)
    # Linear, X at 0 and Y at 90 deg: correct_linear_visibilities.
    theta1 = Receptors("XY").position_angles(phi1)
    theta2 = Receptors("XY").position_angles(phi2)
    np.testing.assert_allclose(
        correct_receptor_visibilities(data, theta1, theta2, LINEAR),
        correct_linear_visibilities(data, phi1, phi2), atol=1e-13)


def test_in_place_and_complex64():
    rng = np.random.default_rng(4)
    data = (rng.normal(size=(5, 4)) + 1j * rng.normal(size=(5, 4))).astype(np.complex64)
    theta = rng.uniform(-180, 180, (5, 2)) * u.deg
    expected = correct_receptor_visibilities(data.astype(complex), theta, theta, CIRCULAR)
    out = correct_receptor_visibilities(data, theta, theta, CIRCULAR, out=data)
    assert out is data and data.dtype == np.complex64
    np.testing.assert_allclose(data, expected, rtol=1e-6, atol=1e-6)


def test_nan_angles_give_nan():
    data = np.ones((2, 4), complex)
    theta = [[0, 90], [np.nan, np.nan]] * u.deg
    out = correct_receptor_visibilities(data, theta, theta, LINEAR)
    assert np.all(np.isfinite(out[0])) and np.all(np.isnan(out[1]))


def test_parallel_hands_of_linear_feeds_are_refused():
    with pytest.raises(ValueError, match="cannot be removed visibility by visibility"):
        correct_receptor_visibilities(np.ones((2, 2), complex), [0, 90] * u.deg,
                                      [0, 90] * u.deg, ["XX", "YY"])


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(products="RR"), TypeError, "not the single string"),
    (dict(products=["RR", "XX"]), ValueError, "mixes circular"),
    (dict(products=["RR", "RR"]), ValueError, "more than once"),
    (dict(products=["R"]), ValueError, "pairs of receptor letters"),
    (dict(products=["QQ"]), ValueError, "receptor types are R and L"),
    (dict(products=None), TypeError, "sequence of names"),
    (dict(visibilities=np.ones(2)), TypeError, "must be complex"),
    (dict(visibilities=np.ones(3, complex)), ValueError, "last axis of visibilities"),
    (dict(position_angles1=[0, 0]), TypeError, "Quantity"),
    (dict(position_angles1=[0, 0, 0] * u.deg), ValueError, "last axis of 2"),
    (dict(position_angles1=[[0, 0]] * 3 * u.deg), ValueError, "does not broadcast"),
    (dict(position_angles1=[0, 0] * u.m), u.UnitsError, "angle"),
    (dict(out=np.ones(3, complex)), ValueError, "out has shape"),
])
def test_errors(kwargs, error, match):
    arguments = dict(visibilities=np.ones(2, complex), position_angles1=[0, 0] * u.deg,
                     position_angles2=[0, 0] * u.deg, products=["RR", "LL"])
    arguments.update(kwargs)
    with pytest.raises(error, match=match):
        correct_receptor_visibilities(**arguments)


def test_parallel_linear_receptors_in_angles():
    with pytest.raises(ValueError, match="parallel"):
        correct_receptor_visibilities(np.ones(4, complex), [10, 10] * u.deg, [0, 90] * u.deg,
                                      LINEAR)


@pytest.mark.parametrize("args, error, match", [
    (("RLX",), ValueError, "one or two receptors"),
    (("",), ValueError, "one or two receptors"),
    (("RX",), ValueError, "mixes circular"),
    (("RR",), ValueError, "repeat"),
    (("Q",), ValueError, "receptor types are R and L"),
    ((3,), TypeError, "types must be a string"),
    (("XY", [0, 90]), TypeError, "angle Quantity"),
    (("XY", [0, 90] * u.m), u.UnitsError, "angles"),
    (("XY", [0] * u.deg), ValueError, "one angle per receptor"),
    (("XY", [0, np.nan] * u.deg), ValueError, "finite"),
    (("XY", Masked([0, 90] * u.deg, mask=[False, True])), ValueError, "must all be known"),
    (("XY", [10, 190] * u.deg), ValueError, "parallel"),
])
def test_receptor_errors(args, error, match):
    with pytest.raises(error, match=match):
        Receptors(*args)


def test_receptor_accessors():
    feed = Receptors(["y", "x"], [0, 90] * u.deg)
    assert feed.types == "YX" and feed.basis == "linear"
    assert feed.angle("x") == 90 * u.deg
    same = Receptors("YX", [0, 90] * u.deg)
    assert feed == same and len({feed, same}) == 1
    assert feed != Receptors("XY")
    assert eval(repr(feed), {"Receptors": Receptors, "u": u}) == feed
    with pytest.raises(ValueError, match="not 'R'"):
        feed.angle("R")
    with pytest.raises(TypeError, match="Quantity"):
        feed.position_angles(3)
    with pytest.raises(u.UnitsError, match="angle"):
        feed.position_angles(3 * u.m)
    assert basis_of(b"RL".decode()) == "circular"
    with pytest.raises(ValueError, match="receptor types"):
        basis_of("")


def test_antenna_carries_receptors():
    site = EarthLocation.from_geodetic(-107.6 * u.deg, 34.08 * u.deg, 2124 * u.m)
    antenna = Antenna(site, AltAzMount(), receptors=Receptors("RL"))
    assert antenna.receptors == Receptors("RL", [0, 0] * u.deg)
    assert "Receptors('RL'" in repr(antenna)
    with pytest.raises(TypeError, match="Receptors object"):
        Antenna(site, AltAzMount(), receptors="RL")


def test_masks_and_units_are_kept():
    # A masked sample stays masked (for linear feeds the whole sample, whose four
    # products the correction mixes), and the values are those of the plain array.
    rng = np.random.default_rng(5)
    data = rng.normal(size=(3, 4)) + 1j * rng.normal(size=(3, 4))
    theta = rng.uniform(-180, 180, (3, 2)) * u.deg
    flags = np.zeros((3, 4), bool)
    flags[1, 2] = True
    for products, expected_flags in ((CIRCULAR, flags), (LINEAR, np.repeat(
            flags.any(axis=1, keepdims=True), 4, axis=1))):
        plain = correct_receptor_visibilities(data, theta, theta, products)
        masked = correct_receptor_visibilities(np.ma.MaskedArray(data, flags), theta, theta,
                                               products)
        assert np.ma.isMaskedArray(masked)
        np.testing.assert_array_equal(np.ma.getmaskarray(masked), expected_flags)
        np.testing.assert_allclose(masked.data[~expected_flags], plain[~expected_flags])
        astropy_masked = correct_receptor_visibilities(Masked(data, mask=flags), theta, theta,
                                                       products)
        np.testing.assert_array_equal(astropy_masked.mask, expected_flags)
    jansky = correct_receptor_visibilities(data * u.Jy, theta, theta, CIRCULAR)
    assert jansky.unit == u.Jy
    np.testing.assert_allclose(jansky.value,
                               correct_receptor_visibilities(data, theta, theta, CIRCULAR))
