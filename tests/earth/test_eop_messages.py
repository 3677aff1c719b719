# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The Earth-orientation warning: silent with the newest tables, short otherwise."""

import re
from importlib import metadata

import erfa
import pytest
from astropy import units as u
from astropy.time import Time
from astropy.utils import iers

from astropy_feedrot.earth.eop import earth_orientation_status


@pytest.fixture
def installed_tables():
    """The IERS-A tables astropy-iers-data installs, in use (astropy 6.0 offline would
    take IERS-B alone, without predictions)."""
    with iers.earth_orientation_table.set(iers.IERS_A.open(iers.IERS_A_FILE)):
        yield


def release_of_installed_tables():
    """The release date of astropy-iers-data, from its version (0.YYYY.MM.DD...)."""
    year, month, day = re.match(r"0\.(\d{4})\.(\d{1,2})\.(\d{1,2})",
                                metadata.version("astropy-iers-data")).groups()
    return Time(f"{year}-{int(month):02d}-{int(day):02d}", scale="utc")


def test_newest_tables_within_their_predictions_are_silent(installed_tables):
    # The installed astropy-iers-data taken as the newest one can get (released 29 days
    # before the clock): today and the coming months lie within its predictions. The
    # warning used to count the 30 days from the last measured value (a week or two
    # before the release), and told to upgrade to tables that did not exist.
    now = release_of_installed_tables() + 29 * u.day
    status = earth_orientation_status(now + [0, 100] * u.day, now=now)
    assert status.message is None
    assert abs(status.age - 29 * u.day) < 1 * u.s
    assert status.beyond_measured > 0 * u.day  # predictions, not measured values


def test_old_installed_tables_warn_and_say_how_to_refresh(installed_tables):
    now = release_of_installed_tables() + 90 * u.day
    status = earth_orientation_status(now, now=now)
    assert re.fullmatch(
        r"computed anyway: epochs up to \d{4}-\d\d-\d\d lie \d+ days after the last measured "
        r"value of the Earth-orientation tables in use \(90 days old\), within predictions "
        r"older than the 30 days astropy accepts; UT1 may be off by [0-9.e-]+ s, which turns "
        r"hour angles by [0-9.e-]+ arcsec and parallactic angles by up to [0-9.e-]+ arcsec at "
        r"80 deg elevation; newer tables: python -m pip install -U astropy-iers-data \(or, "
        r"online, astropy_feedrot\.conf\.iers_auto_download = True\)", status.message)


def test_past_the_newest_predictions_the_warning_is_short(installed_tables):
    # No newer tables reach further: no advice that cannot help, and one short line
    # (it was 640 characters), with the error in arcseconds.
    now = release_of_installed_tables()
    status = earth_orientation_status(status_end(now) + 200 * u.day, now=now)
    assert "\n" not in status.message and len(status.message) < 480
    assert re.search(r"parallactic angles by up to [0-9.]+ arcsec at 80 deg elevation; ",
                     status.message)
    assert status.message.endswith("; no tables predict further")
    assert "pip install" not in status.message


def status_end(now):
    return earth_orientation_status(now=now).predicted_until


def test_leap_second_expiry_is_astropys_not_erfas_builtin():
    # ERFA's built-in table expired in 2017; astropy replaces it from astropy-iers-data.
    status = earth_orientation_status(Time("2023-01-25"))
    assert status.leap_seconds_expire > Time(erfa.leap_seconds.expires) - 1 * u.day
    assert status.leap_seconds_expire > Time("2020-01-01")
