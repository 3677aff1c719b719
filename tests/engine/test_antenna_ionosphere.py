# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Antenna.rotation_measure, faraday_rotation and polarization_rotation: thin
wrappers of astropy_feedrot.ionosphere, checked against the closed form
chi = RM (c/nu)^2 and psi = Phi - chi by hand."""

import numpy as np
import pytest
from astropy import constants as const
from astropy import units as u
from astropy.coordinates import AltAz, SkyCoord
from astropy.table import QTable
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time

from astropy_feedrot import Antenna, CassegrainFocus, DegenerateGeometryWarning, get_antenna
from astropy_feedrot.ionosphere import Ionosphere

SOURCE = SkyCoord("03h19m48.16s +41d30m42.1s")  # 3C 84
TIMES = Time("2024-06-01T04:00") + np.arange(0, 121, 30) * u.min
FREQUENCIES = [0.15, 1.4, 5.0] * u.GHz


@pytest.fixture
def per_antenna():
    # RM rising linearly at EF (1 -> 3 rad/m^2 over 2 h), constant -0.5 at YEBES40M.
    return Ionosphere.from_rm(QTable({
        "time": Time(["2024-06-01T04:00", "2024-06-01T06:00"] * 2),
        "rm": [1.0, 3.0, -0.5, -0.5] * u.rad / u.m**2,
        "antenna": ["EFLSBERG", "EFLSBERG", "YEBES40M", "YEBES40M"]}))


def test_rotation_measure_follows_the_antennas_own_series(per_antenna):
    ef, wb = get_antenna("EFLSBERG"), get_antenna("YEBES40M")
    # Linear interpolation by hand: 1 + 2 * (minutes / 120).
    expected = (1 + 2 * np.arange(0, 121, 30) / 120) * u.rad / u.m**2
    assert_quantity_allclose(ef.rotation_measure(SOURCE, TIMES, per_antenna), expected,
                             rtol=1e-9)
    assert_quantity_allclose(wb.rotation_measure(SOURCE, TIMES, per_antenna),
                             np.full(5, -0.5) * u.rad / u.m**2, rtol=1e-9)


def test_faraday_rotation_is_rm_lambda_squared(per_antenna):
    ef = get_antenna("EFLSBERG")
    chi = ef.faraday_rotation(SOURCE, TIMES, FREQUENCIES, per_antenna)
    assert chi.shape == (5, 3)  # epochs first, frequency last
    rm = ef.rotation_measure(SOURCE, TIMES, per_antenna)
    by_hand = rm[:, np.newaxis] * (const.c / FREQUENCIES) ** 2
    assert_quantity_allclose(chi, by_hand.to(u.rad, u.dimensionless_angles()), rtol=1e-12)
    # 150 MHz, RM 1 rad/m^2: lambda^2 = (299792458 / 150e6)^2 = 3.99445 m^2 = 228.8661 deg.
    assert_quantity_allclose(chi[0, 0], 228.8661 * u.deg, atol=1e-3 * u.deg)


def test_polarization_rotation_is_feed_minus_faraday(per_antenna):
    ef = get_antenna("EFLSBERG")
    phi = ef.feed_rotation(SOURCE, TIMES)
    chi = ef.faraday_rotation(SOURCE, TIMES, FREQUENCIES, per_antenna)
    psi = ef.polarization_rotation(SOURCE, TIMES, FREQUENCIES, per_antenna)
    assert_quantity_allclose(psi, phi[:, np.newaxis] - chi, atol=1e-9 * u.deg)
    # Without an ionosphere: the feed rotation, repeated over the frequencies.
    plain = ef.polarization_rotation(SOURCE, TIMES, FREQUENCIES)
    assert_quantity_allclose(plain, np.repeat(phi[:, np.newaxis], 3, axis=1), atol=0 * u.deg)
    # Keywords reach feed_rotation (here the hand).
    lhcp = ef.polarization_rotation(SOURCE, TIMES, FREQUENCIES, polarization="LCP")
    assert_quantity_allclose(lhcp[:, 0], ef.feed_rotation(SOURCE, TIMES, polarization="LCP"),
                             atol=0 * u.deg)
    # An LCP receiver sees both rotations with the other sign: -(Phi - chi).
    lhcp = ef.polarization_rotation(SOURCE, TIMES, FREQUENCIES, per_antenna, polarization="LCP")
    assert_quantity_allclose(lhcp, -(phi[:, np.newaxis] - chi), atol=1e-9 * u.deg)


def test_a_named_series_needs_a_named_antenna(per_antenna):
    nameless = Antenna(get_antenna("EFLSBERG").location, get_antenna("EFLSBERG").mount,
                       CassegrainFocus())
    with pytest.raises(ValueError, match="antenna"):
        nameless.rotation_measure(SOURCE, TIMES, per_antenna)
    with pytest.raises(ValueError, match="YEBES40M|EFLSBERG"):
        get_antenna("PARKES").rotation_measure(SOURCE, TIMES, per_antenna)


def test_below_the_horizon_is_nan_with_one_warning(per_antenna):
    # From Parkes (dec -33) 3C 84 (dec +41.5) rises only 15 deg; it sets there
    # near 05:00 UTC on 2024-06-01 (elevation by astropy).
    parkes = get_antenna("PARKES")
    table = Ionosphere.from_rm(QTable({"time": TIMES[[0, -1]],
                                       "rm": [1.0, 1.0] * u.rad / u.m**2}))
    altitude = SOURCE.transform_to(AltAz(obstime=TIMES, location=parkes.location)).alt
    with pytest.warns(DegenerateGeometryWarning) as caught:
        rm = parkes.rotation_measure(SOURCE, TIMES, table)
    assert len(caught) == 1
    assert np.array_equal(np.isnan(rm), altitude < 0 * u.deg)
    assert np.any(altitude < 0 * u.deg)
