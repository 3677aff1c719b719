# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""faraday_table: each column against the Antenna method that gives it, and every refusal."""

import os

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import AltAz, SkyCoord
from astropy.table import QTable
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time
from helpers import import_or_skip

from astropy_feedrot.applied.faraday_tables import faraday_table, frequency_label
from astropy_feedrot.ionosphere import Ionosphere, IonosphereError
from astropy_feedrot.stations.catalogue import get_antenna
from astropy_feedrot.transmitters.orbits import TLEOrbit
from astropy_feedrot.transmitters.satellite import Satellite
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE

SOURCE = SkyCoord("03h19m48.16s +41d30m42.1s")  # 3C 84: up from 02:00 to 19:00 UTC in June
STATIONS = [get_antenna("EFLSBERG"), get_antenna("YEBES40M")]
FREQUENCIES = [150, 1400, 5000] * u.MHz
# Up at both stations all along.
TIMES = Time("2024-06-01T06:00") + np.arange(0, 6 * 3600, 900) * u.s
RM = QTable({"time": Time(["2024-06-01T00:00", "2024-06-01T12:00", "2024-06-02T00:00"] * 2),
             "rm": [0.5, 2.5, 1.0, -0.2, 1.8, 0.3] * u.rad / u.m**2,
             "antenna": ["EFLSBERG"] * 3 + ["YEBES40M"] * 3})


def column(table, name, station):
    return table[name][table["antenna"] == station.name]


def check_against_antenna(table, stations, source, times, ionosphere):
    """Each column equals what the Antenna gives, station by station (an independent path:
    one site per call, the feed rotation from feed_rotation, chi from faraday_rotation)."""
    assert len(table) == len(times) * len(stations)
    # By epoch, then station.
    assert list(table["antenna"][:len(stations)]) == [s.name for s in stations]
    for station in stations:
        rows = table["antenna"] == station.name
        assert np.all(table["time"][rows] == times)
        rm = station.rotation_measure(source, times, ionosphere)
        assert_quantity_allclose(column(table, "rm", station), rm, rtol=1e-12)
        phi = station.feed_rotation(source, times, min_elevation=0 * u.deg)
        assert_quantity_allclose(column(table, "feed_rotation", station), phi, atol=1e-9 * u.deg)
        chi = station.faraday_rotation(source, times, FREQUENCIES, ionosphere)
        psi = station.polarization_rotation(source, times, FREQUENCIES, ionosphere,
                                            min_elevation=0 * u.deg)
        for k, frequency in enumerate(FREQUENCIES):
            label = frequency_label(frequency)
            assert_quantity_allclose(column(table, f"chi_{label}", station), chi[:, k],
                                     rtol=1e-12)
            assert_quantity_allclose(column(table, f"psi_{label}", station), psi[:, k],
                                     atol=1e-9 * u.deg)
            # psi = Phi - RM c^2 / nu^2 (the closed form, by hand).
            by_hand = (phi.to_value(u.deg) - np.degrees(
                rm.to_value(u.rad / u.m**2) * (299792458.0 / frequency.to_value(u.Hz)) ** 2))
            assert np.allclose(column(table, f"psi_{label}", station).to_value(u.deg), by_hand,
                               rtol=0, atol=1e-9)
        elevation = station.altaz(source, times)[1]
        assert_quantity_allclose(column(table, "elevation", station), elevation,
                                 atol=1e-9 * u.deg)
        # and astropy's AltAz (no refraction) to 1 arcsec.
        alt = source.transform_to(AltAz(obstime=times, location=station.location)).alt
        assert_quantity_allclose(column(table, "elevation", station), alt, atol=1 * u.arcsec)


def test_columns_from_a_table_of_rm():
    ionosphere = Ionosphere.from_rm(RM)
    table = faraday_table(STATIONS, SOURCE, TIMES, ionosphere, FREQUENCIES)
    assert table.colnames == ["time", "antenna", "elevation", "rm", "chi_150MHz", "chi_1.4GHz",
                              "chi_5GHz", "feed_rotation", "psi_150MHz", "psi_1.4GHz",
                              "psi_5GHz"]
    assert table["rm"].unit == u.rad / u.m**2 and table["chi_5GHz"].unit == u.deg
    check_against_antenna(table, STATIONS, SOURCE, TIMES, ionosphere)
    # The table's RM at 06:00 is linear between 0.5 (00:00) and 2.5 (12:00): 1.5.
    assert_quantity_allclose(table["rm"][0], 1.5 * u.rad / u.m**2)
    assert table.meta["antennas"] == ["EFLSBERG", "YEBES40M"]
    assert table.meta["labels"] == ["150MHz", "1.4GHz", "5GHz"]
    assert table.meta["ionex"] == []


def test_one_antenna_one_frequency_scalar_time():
    one = faraday_table(STATIONS[0], SOURCE, TIMES[:1], Ionosphere.from_rm(RM), 1.4 * u.GHz)
    assert len(one) == 1 and one.colnames[-1] == "psi_1.4GHz"


def test_below_the_horizon_and_the_limit_is_nan_without_warning():
    # 3C 84 sets at Yebes about 19:15 UTC and at Effelsberg about 21:00 on 2024 June 1.
    times = Time("2024-06-01T16:00") + np.arange(0, 8 * 3600, 1800) * u.s
    table = faraday_table(STATIONS, SOURCE, times, Ionosphere.from_rm(RM), FREQUENCIES,
                          min_elevation=10 * u.deg)  # any warning would fail the test
    low = u.Quantity(table["elevation"]) < 10 * u.deg
    assert low.any() and not low.all()
    assert np.all(np.isfinite(u.Quantity(table["elevation"])))
    for name in table.colnames[3:]:
        values = u.Quantity(table[name]).value
        assert np.all(np.isnan(values[low])), name
        assert np.all(np.isfinite(values[~low])), name
    # Without a limit: NaN exactly below the horizon.
    table = faraday_table(STATIONS, SOURCE, times, Ionosphere.from_rm(RM), FREQUENCIES)
    below = u.Quantity(table["elevation"]) < 0 * u.deg
    assert below.any()
    assert np.array_equal(np.isnan(u.Quantity(table["rm"])), below)
    assert np.array_equal(np.isnan(u.Quantity(table["psi_150MHz"])), below)


def test_ionex_maps():
    import_or_skip("spinifex", "ionosphere", "FEEDROT_REQUIRE_SPINIFEX")
    from astropy_feedrot.ionosphere import sample_ionex

    # CODE's maps of 2020 January 8 and 9 (the days spinifex ships); the Crab is up at
    # Effelsberg and Yebes from 16:00 to 05:00 UTC.
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    ionosphere = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
    times = Time("2020-01-08T17:00") + np.arange(0, 10 * 3600, 1200) * u.s
    table = faraday_table(STATIONS, crab, times, ionosphere, FREQUENCIES)
    check_against_antenna(table, STATIONS, crab, times, ionosphere)
    assert [os.path.basename(p) for p in table.meta["ionex"]] == ["codg0080.20i.Z",
                                                                  "codg0090.20i.Z"]
    # Quiet-Sun night-time ionosphere at mid-latitudes: RM of a few 0.1 rad/m2.
    assert 0.05 < np.nanmin(table["rm"].value) < np.nanmax(table["rm"].value) < 1.0
    with pytest.raises(IonosphereError, match="2020-01-10"):
        faraday_table(STATIONS, crab, Time(["2020-01-10T12:00"]), ionosphere, FREQUENCIES)


def test_frequency_label():
    assert frequency_label(1.4 * u.GHz) == "1.4GHz"
    assert frequency_label(1575.42 * u.MHz) == "1.57542GHz"
    assert frequency_label(150 * u.MHz) == "150MHz"
    assert frequency_label(500 * u.kHz) == "500kHz"
    assert frequency_label(1 * u.m) == "299.792MHz"  # a wavelength, through c


@pytest.mark.parametrize("kwargs, error, match", [
    ({"antennas": [STATIONS[0], STATIONS[0]]}, ValueError,
     r"antenna 'EFLSBERG' is given twice; give each station once"),
    ({"antennas": []}, ValueError, r"give at least one antenna"),
    ({"antennas": ["EFLSBERG"]}, TypeError, r"antennas must be Antenna objects, got str"),
    ({"frequency": [1.4, 1.4] * u.GHz}, ValueError, r"frequency 1.4GHz is given twice"),
    ({"frequency": [1400 * u.MHz, 1.4 * u.GHz]}, ValueError, r"frequency 1.4GHz is given twice"),
    ({"frequency": 1.4}, TypeError, r"frequency must be a Quantity"),
    ({"frequency": [[1, 2]] * u.GHz}, ValueError, r"frequency must be one value or a one-dim"),
    ({"frequency": 1 * u.s}, u.UnitsError, r"frequency must be a frequency or a wavelength"),
    ({"frequency": -1 * u.GHz}, ValueError, r"frequency must be positive and finite"),
    ({"ionosphere": RM}, TypeError, r"ionosphere must be an Ionosphere \(Ionosphere.from_ionex "
     r"or Ionosphere.from_rm\), got QTable"),
    ({"target": SkyCoord([1, 2], [3, 4], unit="deg")}, ValueError, r"a table follows one target"),
    ({"target": Satellite(TLEOrbit(*GPS_SVN76_TLE))}, TypeError,
     r"target must be a natural source \(a SkyCoord\)"),
    ({"min_elevation": -5 * u.deg}, ValueError, r"min_elevation must be from 0 to 90 deg, got "
     r"-5.0 deg: the rotation measure is undefined below the horizon"),
    ({"min_elevation": 5}, TypeError, r"min_elevation"),
    ({"obstime": TIMES[::-1]}, ValueError, r"obstime must increase strictly"),
    ({"obstime": Time("2024-06-03T06:00") + np.arange(2) * u.h}, IonosphereError,
     r"2024-06-0[23]"),
    ({"antennas": [get_antenna("WSTRBORK")]}, IonosphereError, r"WB_RT1"),
])
def test_refusals(kwargs, error, match):
    arguments = {"antennas": STATIONS, "target": SOURCE, "obstime": TIMES,
                 "ionosphere": Ionosphere.from_rm(RM), "frequency": FREQUENCIES, **kwargs}
    with pytest.raises(error, match=match):
        faraday_table(**arguments)


def test_plot_faraday():
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from astropy_feedrot.applied.plotting import plot_faraday

    table = faraday_table(STATIONS, SOURCE, TIMES, Ionosphere.from_rm(RM), FREQUENCIES)
    fig = plot_faraday(table)
    # elevation, RM, feed rotation, then one panel per frequency.
    assert [ax.get_ylabel() for ax in fig.axes] == [
        "elevation [deg]", "RM [rad/m$^2$]", "feed rotation [deg]", "150MHz [deg]",
        "1.4GHz [deg]", "5GHz [deg]"]
    # One line per station in the RM panel, drawn from the table's own numbers.
    lines = fig.axes[1].get_lines()
    assert len(lines) == 2
    assert np.array_equal(lines[0].get_ydata(), column(table, "rm", STATIONS[0]).value)
    assert any("RM from a table" in text.get_text() for text in fig.texts)
    plt.close(fig)
    del table["psi_5GHz"]
    with pytest.raises(KeyError, match="the table lacks column.s. psi_5GHz; plot a "
                                       "faraday_table"):
        plot_faraday(table)
