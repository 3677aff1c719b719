# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rotation measures from a user's table, and the Faraday rotation; spinifex is not needed."""

import numpy as np
import pytest
from astropy import constants as const, units as u
from astropy.coordinates import AltAz, EarthLocation, SkyCoord
from astropy.table import QTable, Table
from astropy.time import Time

from astropy_feedrot.core.exceptions import DegenerateGeometryWarning
from astropy_feedrot.ionosphere import (
    Ionosphere,
    IonosphereError,
    faraday_rotation,
    polarization_rotation,
)

RM = u.rad / u.m**2
EF = EarthLocation.from_geodetic(6.8836 * u.deg, 50.5248 * u.deg, 416.7 * u.m)
WB = EarthLocation.from_geodetic(6.6036 * u.deg, 52.9145 * u.deg, 16.0 * u.m)
CRAB = SkyCoord("05h34m31.94s +22d00m52.2s")
START = Time("2020-01-08T20:00")  # the Crab is high over both from 20:00 to 04:00 UTC


def linear_table():
    """RM of EF rising 1 rad/m^2 per hour from 0.5; WB's constant at -0.25."""
    hours = np.arange(0, 7)
    times = START + hours * u.h
    return QTable({"time": Time(np.r_[times, times]),
                   "rm": np.r_[0.5 + hours, np.full(7, -0.25)] * RM,
                   "antenna": ["EF"] * 7 + ["WB"] * 7})


def test_interpolation_against_the_closed_form():
    iono = Ionosphere.from_rm(linear_table())
    seconds = np.linspace(0, 6 * 3600, 97)
    epochs = START + seconds * u.s
    both = EarthLocation.from_geodetic([6.8836, 6.6036] * u.deg, [50.5248, 52.9145] * u.deg,
                                       [416.7, 16.0] * u.m)
    rm = iono.rotation_measure(both, CRAB, epochs, antenna=["EF", "WB"])
    assert rm.shape == (97, 2)
    # Reference: the closed form 0.5 + t / 1 h for EF, -0.25 for WB
    np.testing.assert_allclose(rm[:, 0].to_value(RM), 0.5 + seconds / 3600, rtol=0, atol=1e-9)
    np.testing.assert_allclose(rm[:, 1].to_value(RM), -0.25, rtol=0, atol=1e-12)
    # one antenna at a time, by name, any case; a scalar epoch gives a scalar
    one = iono.rotation_measure(EF, CRAB, START + 90 * u.min, antenna="ef")
    assert one.shape == () and abs(one - 2.0 * RM) < 1e-9 * RM


def test_one_series_serves_every_antenna():
    table = Table({"time": START + [0, 2] * u.h, "rm": [1.0, 3.0]})
    table["rm"].unit = "rad / m2"  # a plain Table with a unit on the column
    iono = Ionosphere.from_rm(table)
    assert repr(iono) == "<Ionosphere from a table of rotation measures for every antenna>"
    rm = iono.rotation_measure(EF, CRAB, START + [30, 60] * u.min, antenna="anything")
    np.testing.assert_allclose(rm.to_value(RM), [1.5, 2.0], atol=1e-9)
    assert iono.files == () and iono.coverage is None


def test_rows_in_any_order_and_time_scale():
    table = linear_table()[::-1]
    table["time"] = table["time"].tai
    rm = Ionosphere.from_rm(table).rotation_measure(WB, CRAB, (START + 1 * u.h).tt, antenna="WB")
    assert abs(rm + 0.25 * RM) < 1e-12 * RM


def test_below_the_horizon_is_nan():
    iono = Ionosphere.from_rm(QTable({"time": START + [0, 24] * u.h, "rm": [1.0, 1.0] * RM}))
    epochs = START + np.arange(0, 24 * 60, 10) * u.min
    with pytest.warns(DegenerateGeometryWarning,
                      match=r"undefined at \d+ of 144 epochs x sites, where the target is below"):
        rm = iono.rotation_measure(EF, CRAB, epochs)
    # Reference: astropy's AltAz (no refraction), away from the crossings
    altitude = CRAB.transform_to(AltAz(obstime=epochs, location=EF)).alt.deg
    clear = np.abs(altitude) > 0.01
    np.testing.assert_array_equal(np.isnan(rm[clear]), altitude[clear] < 0)
    assert np.all(rm[clear & (altitude > 0)] == 1.0 * RM)


def test_target_per_epoch_with_a_table():
    # One direction per epoch (the Crab, then a source at the celestial south pole):
    # the elevation is taken at each epoch, the RM from the table.
    iono = Ionosphere.from_rm(QTable({"time": START + [0, 1] * u.h, "rm": [1.0, 2.0] * RM}))
    targets = SkyCoord([83.63, 0.0] * u.deg, [22.01, -89.9] * u.deg)
    with pytest.warns(DegenerateGeometryWarning, match="undefined at 1 of 2 epochs x sites"):
        rm = iono.rotation_measure(EF, targets, START + [30, 45] * u.min)
    np.testing.assert_allclose(rm[0].to_value(RM), 1.5, atol=1e-9)
    assert np.isnan(rm[1])


def test_outside_the_table_and_unknown_antennas():
    iono = Ionosphere.from_rm(linear_table())
    with pytest.raises(IonosphereError,
                       match=r"^1 of 2 epochs \(2020-01-09T03:00:00 UTC\) lie outside the table "
                             r"of rotation measures of antenna 'EF', which covers "
                             r"2020-01-08T20:00:00 to 2020-01-09T02:00:00 UTC; give rows"):
        iono.rotation_measure(EF, CRAB, START + [1, 7] * u.h, antenna="EF")
    with pytest.raises(IonosphereError, match="the table of rotation measures has no antenna "
                       "'MC'; it has EF, WB: add its rows"):
        iono.rotation_measure(EF, CRAB, START, antenna="MC")
    with pytest.raises(ValueError, match=r"the table gives rotation measures per antenna "
                       r"\(EF, WB\): say which with antenna=<name>"):
        iono.rotation_measure(EF, CRAB, START)
    with pytest.raises(ValueError, match=r"antenna gives 1 name\(s\) for locations of shape "
                       r"\(2,\); give one name per location"):
        iono.rotation_measure(EarthLocation.from_geodetic([0, 1] * u.deg, [50, 50] * u.deg),
                              CRAB, START, antenna=["EF"])


@pytest.mark.parametrize("table, error, message", [
    ({"time": Time(["2020-01-08T00:00"]), "rm": [1.0] * RM}, TypeError,
     "table must be an astropy QTable"),
    (QTable({"time": Time(["2020-01-08T00:00"])}), ValueError,
     "table lacks column\\(s\\) 'rm'; it has 'time'"),
    (QTable({"time": ["2020-01-08T00:00"], "rm": [1.0] * RM}), TypeError,
     "table column 'time' must be an astropy Time, got Column"),
    (QTable({"time": Time(["2020-01-08T00:00"]), "rm": [1.0]}), TypeError,
     "table column 'rm' has no unit"),
    (QTable({"time": Time(["2020-01-08T00:00"]), "rm": [1.0] * u.deg}), u.UnitsError,
     "table column 'rm' must be a rotation measure in rad / m2, got deg"),
    (QTable({"time": Time(["2020-01-08T00:00"] * 2), "rm": [1.0, 2.0] * RM,
             "antenna": ["EF", "EF"]}), ValueError,
     "table gives antenna 'EF' two rotation measures at 2020-01-08T00:00:00 UTC"),
])
def test_bad_tables(table, error, message):
    with pytest.raises(error, match=message):
        Ionosphere.from_rm(table)


def test_rm_in_inverse_square_metres_is_accepted():
    table = QTable({"time": START + [0, 1] * u.h, "rm": [2.0, 2.0] / u.m**2})
    assert Ionosphere.from_rm(table).rotation_measure(EF, CRAB, START) == 2.0 * RM


def test_bad_inputs_to_rotation_measure():
    iono = Ionosphere.from_rm(QTable({"time": START + [0, 1] * u.h, "rm": [2.0, 2.0] * RM}))
    with pytest.raises(TypeError, match="location must be an astropy EarthLocation"):
        iono.rotation_measure((0, 0, 0), CRAB, START)
    with pytest.raises(TypeError, match="target must be an astropy SkyCoord"):
        iono.rotation_measure(EF, (83.6, 22.0), START)
    with pytest.raises(TypeError, match="obstime must be an astropy Time"):
        iono.rotation_measure(EF, CRAB, 58856.8)
    with pytest.raises(ValueError, match="shapes do not broadcast"):
        iono.rotation_measure(EF, SkyCoord([1, 2, 3] * u.deg, [4, 5, 6] * u.deg),
                              START + [0, 1] * u.min)
    with pytest.raises(TypeError, match=r"make an Ionosphere with Ionosphere.from_ionex"):
        Ionosphere()


def test_faraday_rotation_is_rm_lambda_squared():
    rm = [[0.5, -1.0], [2.0, np.nan]] * RM
    frequency = [150.0, 1400.0, 5000.0] * u.MHz
    chi = faraday_rotation(rm, frequency)
    assert chi.shape == (2, 2, 3) and chi.unit == u.deg
    # Reference: chi = RM (c / nu)^2 by hand
    wavelength = const.c.value / np.array([150e6, 1.4e9, 5e9])
    expected = np.degrees(np.array([[0.5, -1.0], [2.0, np.nan]])[..., None] * wavelength**2)
    np.testing.assert_allclose(chi.deg, expected, rtol=1e-14)
    # 1 rad/m^2 at 21 cm: 2.63 deg; a wavelength instead of a frequency
    assert abs(faraday_rotation(1 * RM, 1.4 * u.GHz) - 2.62728972 * u.deg) < 1e-8 * u.deg
    assert abs(faraday_rotation(1 * RM, 0.5 * u.m) - 0.25 * u.rad) < 1e-12 * u.rad
    # not wrapped: 150 MHz and 3 rad/m^2 is 12 rad
    assert faraday_rotation(3 * RM, 150 * u.MHz).to_value(u.rad) > 11.9


@pytest.mark.parametrize("rm, frequency, error, message", [
    (1.0, 1 * u.GHz, TypeError, "rm must be a Quantity in rad / m2"),
    (1 * u.deg, 1 * u.GHz, u.UnitsError, "rm must be a rotation measure in rad / m2, got"),
    (1 * RM, 1.4, TypeError, "frequency must be a Quantity"),
    (1 * RM, 1 * u.s, u.UnitsError, "frequency must be a frequency or a wavelength"),
    (1 * RM, [1, 0] * u.GHz, ValueError, "frequency must be positive and finite, got 0 Hz"),
])
def test_faraday_rotation_refuses(rm, frequency, error, message):
    with pytest.raises(error, match=message):
        faraday_rotation(rm, frequency)


def test_polarization_rotation_removes_feed_and_ionosphere():
    # A source of intrinsic angle chi0 is seen through the ionosphere at chi0 + RM lambda^2,
    # and through a feed turned by Phi at that minus Phi (the package's convention).
    chi0 = 33.0 * u.deg
    phi = [[-40.0, 10.0], [75.0, 120.0]] * u.deg  # epochs x antennas
    rm = [[0.8, -0.3], [1.5, 2.2]] * RM
    frequency = np.linspace(1.2, 1.8, 7) * u.GHz
    chi = faraday_rotation(rm, frequency)
    apparent = chi0 + chi - phi[..., np.newaxis]
    psi = polarization_rotation(phi, rm, frequency)
    assert psi.shape == (2, 2, 7)
    # psi enters as Phi does: adding it back gives chi0 at every channel
    np.testing.assert_allclose((apparent + psi).to_value(u.deg), chi0.value, atol=1e-12)
    # no ionosphere: the feed rotation at every channel; one RM for every antenna
    np.testing.assert_allclose(polarization_rotation(phi, 0 * RM, frequency).deg,
                               np.repeat(phi.value[..., np.newaxis], 7, axis=-1))
    assert polarization_rotation(phi, 1 * RM, 1.4 * u.GHz).shape == (2, 2)
    with pytest.raises(u.UnitsError, match="feed_rotation must be an angle"):
        polarization_rotation(10.0, 1 * RM, 1.4 * u.GHz)
