# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rows corrected from the angles and rotation measures of their places (an antenna at an
epoch): the one-pass circular path against the general one, angle by angle."""

import numpy as np
import pytest
from astropy import units as u

from astropy_feedrot.applied.correction import correct_receptor_visibilities
from astropy_feedrot.visibilities.faraday import (
    correct_circular,
    correct_rows,
    faraday_angles,
    row_places,
    rows_lambda_squared,
)

RNG = np.random.default_rng(20261127)


def places_and_tables(n_rows, n_places, same_hands):
    place1 = RNG.integers(0, n_places, n_rows)
    place2 = RNG.integers(0, n_places, n_rows)
    angles = RNG.uniform(-180, 180, (n_places, 2))
    if same_hands:
        angles[:, 1] = angles[:, 0]
    rm = RNG.normal(0, 3, n_places)
    return place1, place2, angles, rm


def general(data, angles, rm, place1, place2, lambda2, products, conjugate, direction):
    """Reference: the angles per sample (faraday_angles, theta - RM lambda^2) through the
    general correction, receptor by receptor."""
    theta1 = faraday_angles(angles[place1], rm[place1], lambda2)
    theta2 = faraday_angles(angles[place2], rm[place2], lambda2)
    return correct_receptor_visibilities(data, theta1 * u.deg, theta2 * u.deg, products,
                                         conjugate=conjugate, direction=direction)


@pytest.mark.parametrize("products", [["RR", "RL", "LR", "LL"], ["LL", "RR"], ["LR"]])
@pytest.mark.parametrize("conjugate", [False, True])
@pytest.mark.parametrize("direction", ["remove", "apply"])
@pytest.mark.parametrize("same_hands", [True, False])
def test_one_pass_equals_the_general_path(products, conjugate, direction, same_hands):
    n_rows, shape = 700, (3, 16)  # 3 bands of 16 channels: lambda^2 per band and channel
    place1, place2, angles, rm = places_and_tables(n_rows, 90, same_hands)
    lambda2 = (0.21 * RNG.uniform(0.8, 1.2, shape)) ** 2
    data = (RNG.normal(size=(n_rows,) + shape + (len(products),))
            + 1j * RNG.normal(size=(n_rows,) + shape + (len(products),)))
    expected = general(data, angles, rm, place1, place2, lambda2, products, conjugate,
                       direction)
    correct_circular(data, angles, rm, place1, place2, lambda2, products,
                     conjugate=conjugate, direction=direction)
    np.testing.assert_allclose(data, expected, rtol=0, atol=1e-12)


def test_single_precision_big_endian_in_place():
    # FITS-IDI's rows: big-endian complex64, corrected where they lie.
    products = ["RR", "LL", "RL", "LR"]
    place1, place2, angles, rm = places_and_tables(300, 40, False)
    lambda2 = np.linspace(0.04, 0.05, 32)
    values = (RNG.normal(size=(300, 32, 4)) + 1j * RNG.normal(size=(300, 32, 4)))
    data = values.astype(">c8")
    expected = general(values, angles, rm, place1, place2, lambda2, products, True, "remove")
    view = data[...]
    correct_circular(view, angles, rm, place1, place2, lambda2, products, conjugate=True)
    assert data.dtype == np.dtype(">c8")
    np.testing.assert_allclose(data, expected, rtol=0, atol=2e-6)


def test_places_far_apart_take_the_same_numbers():
    # Rows whose places span more than a few epochs' worth: the places are compacted by a
    # sort instead of a short table; the numbers are the same.
    products = ["RR", "LL"]
    place1, place2, angles, rm = places_and_tables(50, 20, False)
    spread = np.arange(20) * 1000  # the same places, numbered far apart
    big_angles = np.full((20 * 1000, 2), np.nan)
    big_rm = np.full(20 * 1000, np.nan)
    big_angles[spread], big_rm[spread] = angles, rm
    data = np.exp(1j * RNG.uniform(0, 6, (50, 8, 2)))
    lambda2 = np.linspace(1, 2, 8)
    near, far = data.copy(), data.copy()
    correct_circular(near, angles, rm, place1, place2, lambda2, products)
    correct_circular(far, big_angles, big_rm, spread[place1], spread[place2], lambda2, products)
    np.testing.assert_array_equal(near, far)


def test_no_rows():
    data = np.empty((0, 4, 2), complex)
    for lambda2 in (None, np.ones(4)):
        bad = correct_rows(data, np.zeros((3, 2)), np.zeros(3), np.zeros(0, int),
                           np.zeros(0, int), ["RR", "LL"], lambda2=lambda2)
        assert bad.shape == (0,)


def test_rows_with_nan_angles_or_rm_are_named():
    products = ["RR", "LL"]
    place1, place2 = np.array([0, 1, 2]), np.array([1, 2, 0])
    angles = np.array([[10.0, 10.0], [np.nan, np.nan], [30.0, 30.0]])
    rm = np.array([0.5, 0.1, np.nan])
    data = np.ones((3, 4, 2), complex)
    bad = correct_rows(data, angles, rm, place1, place2, products, lambda2=np.ones(4))
    np.testing.assert_array_equal(bad, [True, True, True])
    data = np.ones((3, 4, 2), complex)
    bad = correct_rows(data, angles, None, place1, place2, products)  # no ionosphere
    np.testing.assert_array_equal(bad, [True, True, False])
    assert np.all(np.isfinite(data[2]))


@pytest.mark.parametrize("lambda2", [None, np.linspace(0.01, 0.02, 5)])
def test_linear_products_take_the_angles_per_channel(lambda2):
    products = ["XX", "XY", "YX", "YY"]
    place1, place2, angles, rm = places_and_tables(40, 10, False)
    angles[:, 1] = angles[:, 0] + 90  # X and Y receptors
    data = RNG.normal(size=(40, 5, 4)) + 1j * RNG.normal(size=(40, 5, 4))
    if lambda2 is None:
        expected = correct_receptor_visibilities(
            data, angles[place1][:, None] * u.deg, angles[place2][:, None] * u.deg, products)
    else:
        expected = general(data, angles, rm, place1, place2, lambda2, products, False,
                           "remove")
    correct_rows(data, angles, rm, place1, place2, products, lambda2=lambda2)
    np.testing.assert_allclose(data, expected, rtol=0, atol=1e-12)


def test_row_places_are_distinct_epoch_centre_antenna():
    time = np.array([1.0, 1.0, 2.0, 2.0, 1.0])
    centre = np.array([0, 0, 0, 1, 1])
    ant1, ant2 = np.array([3, 3, 3, 3, 3]), np.array([7, 9, 9, 9, 7])
    place1, place2 = row_places(time, centre, ant1, ant2)
    keys = {}
    for t, c, a, p in zip(np.r_[time, time], np.r_[centre, centre], np.r_[ant1, ant2],
                          np.r_[place1, place2]):
        assert keys.setdefault((t, c, a), p) == p  # one place per (epoch, centre, antenna)
    assert len(set(keys.values())) == len(keys) == max(keys.values()) + 1


def test_rows_lambda_squared_of_setups():
    faraday = {1: np.array([0.04, 0.05]), 2: np.array([0.01, 0.02])}
    one, per_row = rows_lambda_squared({1: faraday[1]})
    assert not per_row and one is faraday[1]
    rows, per_row = rows_lambda_squared(faraday, np.array([2, 1, 2]))
    assert per_row
    np.testing.assert_array_equal(rows, [faraday[2], faraday[1], faraday[2]])
    with pytest.raises(ValueError, match=r"rows use FREQID \[3\] that the FREQUENCY table "
                                         r"lacks \(it has \[1, 2\]\)"):
        rows_lambda_squared(faraday, np.array([1, 3]))
    with pytest.raises(ValueError, match=r"rows use FREQID \[2\]"):
        rows_lambda_squared({1: faraday[1]}, np.array([1, 2]))
