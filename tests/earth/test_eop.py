# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Earth orientation beyond the tables: computed offline, with one warning.

The tables are faked (the bundled ones cut short), so that nothing here depends
on the machine's clock or on which astropy-iers-data is installed.
"""

import warnings

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import HADec, SkyCoord
from astropy.time import Time
from astropy.utils import iers
from helpers import MAS, SITES, sky_grid

from astropy_feedrot import AltAzMount, Antenna, CassegrainFocus, StaleEarthOrientationWarning
from astropy_feedrot.cli import main
from astropy_feedrot.earth.eop import EARTH_ROTATION_RATE, earth_orientation_status, iers_context

SOURCE = SkyCoord("03h19m48.16s +41d30m42.1s")
SITE = SITES["WETTZ13S"]
ANTENNA = Antenna(SITE, AltAzMount(), CassegrainFocus(), name="WETTZ13S")

#: The faked tables: measured values to 2020-01-01 (MJD 58849), predictions
#: (really measured values, which does not matter here) to 2021-01-01.
MEASURED_UNTIL = 58849.0
PREDICTED_UNTIL = 59215.0
#: A year after the end of the faked tables.
LATER = Time("2022-01-01T00:00", scale="utc")


def _cut(table, last, predictive):
    mjd = table["MJD"].to_value(u.day)
    fake = table[mjd <= last]
    fake.meta["predictive_mjd"] = predictive
    fake.meta["predictive_index"] = int(np.searchsorted(mjd, predictive))
    return fake


@pytest.fixture
def stale_tables():
    """Tables whose measured values end on 2020-01-01 and predictions on 2021-01-01."""
    fake = _cut(iers.IERS_Auto.open(), PREDICTED_UNTIL, MEASURED_UNTIL + 1)
    with iers.earth_orientation_table.set(fake):
        yield fake


def _caught(function, *args, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = function(*args, **kwargs)
    return result, caught


# --- the status ------------------------------------------------------------


def test_status_within_measured_values(stale_tables):
    status = earth_orientation_status(Time("2019-06-01"), now=Time("2026-01-01"))
    assert status.message is None
    assert status.ut1_error == 0 * u.s
    assert status.measured_until.iso.startswith("2020-01-01")
    assert status.predicted_until.iso.startswith("2021-01-01")


def test_status_fresh_predictions_are_quiet(stale_tables):
    # 14 days after the last measured value, predictions are what astropy uses.
    status = earth_orientation_status(Time("2020-06-01"), now=Time("2020-01-15"))
    assert status.message is None
    # Bulletin A's accuracy of a prediction 152 days ahead: 0.00025 * 152**0.75 s.
    assert status.ut1_error.to_value(u.s) == pytest.approx(0.00025 * 152**0.75)


def test_status_stale_predictions_warn(stale_tables):
    status = earth_orientation_status(Time("2020-06-01"), now=Time("2020-03-01"))
    assert status.age == 60 * u.day
    assert "60 days old" in status.message
    assert "152 days after the last measured value" in status.message
    assert "within predictions older than the 30 days astropy accepts" in status.message


def test_status_past_the_predictions(stale_tables):
    status = earth_orientation_status(LATER, now=Time("2020-01-15"))
    assert "731 days after the last measured value" in status.message
    assert "365 days past the predictions" in status.message
    assert "UT1 - UTC is held at its last predicted value" in status.message
    # Tables 14 days old: no newer ones predict further, so no upgrade is suggested.
    assert status.message.endswith("; no tables predict further")
    assert "pip install" not in status.message
    old = earth_orientation_status(LATER, now=Time("2020-03-01"))
    assert old.message.endswith("; newer tables: python -m pip install -U astropy-iers-data "
                                "(or, online, astropy_feedrot.conf.iers_auto_download = True)")
    # At least Bulletin A's accuracy 731 days ahead, and the hour angle turns
    # by 15.04 arcsec per second of UT1 error (the Earth's rotation rate).
    assert status.ut1_error.to_value(u.s) >= 0.00025 * 731**0.75
    assert status.hour_angle_error.to_value(u.arcsec) == pytest.approx(
        status.ut1_error.to_value(u.s) * 15.0411, rel=1e-4)
    assert status.parallactic_angle_error.to_value(u.arcsec) == pytest.approx(
        status.hour_angle_error.to_value(u.arcsec) / np.cos(np.radians(80)))


def test_status_before_the_tables():
    # A year before the tables in use start (1973 or 1962, as astropy's version has them).
    start = earth_orientation_status().table_start
    status = earth_orientation_status(start - 365 * u.day, now=Time("2020-01-01"))
    assert "before the Earth-orientation tables" in status.message


def test_status_ignores_masked_and_empty_epochs(stale_tables):
    times = LATER - [800, 0] * u.day
    times[1] = np.ma.masked
    assert earth_orientation_status(times, now=Time("2026-01-01")).message is None
    empty = earth_orientation_status(Time([], format="mjd"), now=Time("2026-01-01"))
    assert empty.message is None and empty.last is None


def test_status_leap_seconds_beyond_the_table(stale_tables):
    expires = earth_orientation_status().leap_seconds_expire  # astropy's table, not ERFA's
    status = earth_orientation_status(expires + 400 * u.day, now=Time("2020-01-15"))
    assert "leap seconds after" in status.message


# --- computing anyway, with one warning ------------------------------------


@pytest.mark.parametrize("n_epochs", [3, 100])  # the rigorous and the fast path
def test_a_year_after_the_tables_works_and_warns_once(stale_tables, n_epochs):
    times = LATER + np.linspace(0, 12, n_epochs) * u.hour
    psi, caught = _caught(ANTENNA.feed_rotation, SOURCE, times)
    assert len(caught) == 1, [str(w.message) for w in caught]
    assert caught[0].category is StaleEarthOrientationWarning
    assert caught[0].filename == __file__  # it points at the caller's line
    assert "days past the predictions" in str(caught[0].message)
    # The same as ERFA's parallactic angle from astropy's HADec frame computed
    # with the same tables, offline and astropy's age check off (its extrapolation;
    # outside iers_context astropy 6.0 tries to download, then falls back to IERS-B).
    with iers_context(), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        hadec = SOURCE.transform_to(HADec(obstime=times, location=SITE))
    expected = erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, SITE.lat.rad)
    difference = np.angle(np.exp(1j * (psi.rad - expected)))
    assert np.abs(difference).max() < 1 * MAS


def test_one_warning_for_every_method(stale_tables):
    times = LATER + np.arange(24) * u.hour
    for method in (ANTENNA.parallactic_angle, ANTENNA.altaz, ANTENNA.feed_rotation_terms):
        _, caught = _caught(method, SOURCE, times)
        assert [w.category for w in caught] == [StaleEarthOrientationWarning], method


def test_within_measured_values_is_quiet(stale_tables):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ANTENNA.feed_rotation(SOURCE, Time("2019-06-01") + np.arange(20) * u.hour)


def test_ut1_error_moves_the_parallactic_angle_as_stated():
    """A UT1 error dt moves Psi by -omega dt cos(lat) cos(A) / cos(E).

    The derivative of Eq 16 with respect to the hour angle (a closed form,
    independent of the package's vector path); the warning quotes its bound.
    """
    def epochs():  # new Time objects: a Time caches its UT1 - UTC
        return Time("2023-01-25T00:00") + np.arange(0, 24, 3) * u.hour

    sources = sky_grid(40)[:, np.newaxis]
    dt = 0.5 * u.s
    shifted = iers.IERS_Auto.open().copy()
    shifted["UT1_UTC"] = shifted["UT1_UTC"] + dt
    psi = ANTENNA.parallactic_angle(sources, epochs())
    azimuth, elevation = ANTENNA.altaz(sources, epochs())
    with iers.earth_orientation_table.set(shifted):
        moved = ANTENNA.parallactic_angle(sources, epochs())
    change = np.angle(np.exp(1j * (moved - psi).to_value(u.rad)))
    rate = (EARTH_ROTATION_RATE * dt).to_value(u.rad, u.dimensionless_angles())
    lat = SITE.lat.rad
    keep = elevation < 80 * u.deg
    predicted = -rate * np.cos(lat) * np.cos(azimuth.rad) / np.cos(elevation.rad)
    assert np.abs(change - predicted)[keep].max() < 1e-3 * rate / np.cos(np.radians(80))
    bound = rate * np.cos(lat) / np.cos(elevation.rad)
    assert np.all(np.abs(change)[keep] <= bound[keep] * (1 + 1e-3))


def test_context_restores_astropy_settings():
    before = (iers.conf.auto_max_age, iers.conf.iers_degraded_accuracy)
    with iers_context():
        assert iers.conf.auto_max_age is None
        assert iers.conf.iers_degraded_accuracy == "ignore"
    assert (iers.conf.auto_max_age, iers.conf.iers_degraded_accuracy) == before


def test_context_puts_back_exactly_what_astropy_had():
    # The settings are written into astropy's configuration section directly:
    # an item the section lacked is absent again afterwards, one it held has
    # its value again, also when the code inside fails.
    from astropy.config import get_config

    section = get_config(type(iers.conf).auto_max_age.module, rootname="astropy")
    held = {name: section.get(name, "absent") for name in
            ("auto_download", "auto_max_age", "iers_degraded_accuracy")}
    section.pop("iers_degraded_accuracy", None)
    try:
        with pytest.raises(ZeroDivisionError), iers_context():
            assert iers.conf.auto_download is False
            assert iers.conf.iers_degraded_accuracy == "ignore"
            raise ZeroDivisionError
        assert "iers_degraded_accuracy" not in section
        assert section.get("auto_max_age", "absent") == held["auto_max_age"]
        assert section.get("auto_download", "absent") == held["auto_download"]
    finally:
        if held["iers_degraded_accuracy"] != "absent":
            section["iers_degraded_accuracy"] = held["iers_degraded_accuracy"]


def test_nested_contexts_warn_once_at_the_end(stale_tables):
    def work():
        with iers_context(LATER):
            with iers_context(LATER + 1 * u.day):
                pass
            with iers_context(LATER + 2 * u.day):
                pass

    _, caught = _caught(work)
    assert len(caught) == 1
    assert "epochs up to 2022-01-03" in str(caught[0].message)


def test_no_warning_when_the_call_fails(stale_tables):
    def fails():
        with iers_context(LATER):
            raise ZeroDivisionError

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ZeroDivisionError):
            fails()


# --- the command line -------------------------------------------------------


@pytest.mark.parametrize("step", ["1h", "5min"])  # 7 and 73 epochs
def test_command_line_prints_one_line(stale_tables, capsys, step):
    status = main(["natural", "EFLSBERG", "--source", "03h19m48.16s +41d30m42.1s",
                   "--start", "2022-01-01T00:00", "--stop", "2022-01-01T06:00",
                   "--step", step])
    assert status == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1, err
    assert err[0].startswith("feedrot: warning: computed anyway: epochs up to 2022-01-01")


def test_command_line_start_now_works_offline(stale_tables, capsys):
    status = main(["natural", "EFLSBERG", "--source", "03h19m48.16s +41d30m42.1s",
                   "--start", "now", "--stop", "now"])
    assert status == 0
    out, err = capsys.readouterr()
    assert "# %ECSV" in out
    assert err.count("\n") == 1 and "days past the predictions" in err


def _front_ends():
    from astropy_feedrot import Satellite, TLEOrbit, rotation_delay
    from astropy_feedrot.applied.feed_rotation_tables import baseline_table, feed_rotation_table
    from astropy_feedrot.engine.grid import feed_rotation_grid, feed_rotation_grid_dask
    from astropy_feedrot.stations.catalogue import get_antenna

    first, second = get_antenna("FD-VLBA"), get_antenna("DBR205")
    satellite = Satellite(TLEOrbit.from_elements(LATER, inclination=55 * u.deg,
                                                 raan=10 * u.deg, altitude=20200 * u.km))
    for name, target in (("natural source", SOURCE), ("satellite", satellite)):
        many = target if target is SOURCE else [target]
        yield name, "feed_rotation", lambda t, x=target: first.feed_rotation(x, t)
        yield name, "feed_rotation_terms", lambda t, x=target: first.feed_rotation_terms(x, t)
        yield name, "parallactic_angle", lambda t, x=target: first.parallactic_angle(x, t)
        yield name, "altaz", lambda t, x=target: first.altaz(x, t)
        yield name, "rotation_delay", lambda t, x=target: rotation_delay(
            first, second, x, t, 1.5 * u.GHz)
        yield name, "feed_rotation_grid", lambda t, x=many: feed_rotation_grid(
            [first, second], x, t)
        yield name, "feed_rotation_grid_dask", lambda t, x=many: feed_rotation_grid_dask(
            [first, second], x, t).compute(scheduler="synchronous")
        yield name, "feed_rotation_table", lambda t, x=target: feed_rotation_table(first, x, t)
        yield name, "baseline_table", lambda t, x=target: baseline_table(
            first, second, x, t, 1.5 * u.GHz)
    yield "satellite", "Satellite.line_of_sight", lambda t: satellite.line_of_sight(
        first.location, t)


@pytest.mark.parametrize("n_epochs", [3, 40])
def test_every_front_end_warns_once(stale_tables, n_epochs):
    """However many transformations a call makes, it warns once, at the caller."""
    times = LATER + np.arange(n_epochs) * 15 * u.min
    for target, name, call in _front_ends():
        _, caught = _caught(call, times)
        stale = [w for w in caught if w.category is StaleEarthOrientationWarning]
        assert len(stale) == 1, (target, name, len(stale))
        assert stale[0].filename == __file__, (target, name)


def test_a_second_call_at_the_same_epochs_warns_again(stale_tables):
    # The Earth orientation of these epochs is reused (earth.orientation_of);
    # the tables are checked again all the same.
    times = LATER + np.arange(40) * 15 * u.min
    for _ in range(2):
        _, caught = _caught(ANTENNA.feed_rotation, SOURCE, times)
        assert [w.category for w in caught] == [StaleEarthOrientationWarning]
