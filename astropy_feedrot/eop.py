# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Earth-orientation tables: offline by default, and one warning when they fall short.

Every transformation of this package that needs UT1 - UTC or polar motion runs
inside `iers_context`. There, astropy never reaches for the network unless the
user opted in (``astropy_feedrot.conf.iers_auto_download = True``), and epochs
that the tables bundled with astropy (the ``astropy-iers-data`` package) do not
cover well are still computed, the way astropy itself would compute them once
its own age check is off:

* between the last measured value and the end of the predictions, UT1 - UTC
  and polar motion come from the IERS predictions;
* after the end of the predictions, UT1 - UTC is held at its last predicted
  value and polar motion at its 50-year mean;
* before the start of the tables, UT1 - UTC and polar motion are held at their
  first values.

Instead of astropy's error ("interpolating from IERS_Auto using predictive
values that are more than 30 days old") or its scattered messages, each call
then emits one `~astropy_feedrot.StaleEarthOrientationWarning` that says how
old the tables are, how far the epochs lie beyond the measured values, how
large the UT1 error may be and what that does to hour and parallactic angles
(see `earth_orientation_status`).
"""

import contextlib
import contextvars
import re
import time
import warnings
from importlib import metadata
from typing import NamedTuple

import erfa
import numpy as np
from astropy import units as u
from astropy.time import Time, update_leap_seconds
from astropy.utils import iers
from astropy.utils.exceptions import AstropyWarning

from .config import conf
from .exceptions import StaleEarthOrientationWarning, warn_caller

__all__ = [
    "EarthOrientationStatus",
    "earth_orientation_status",
    "iers_context",
    "EARTH_ROTATION_RATE",
    "MAX_TABLE_AGE",
]

#: The Earth's rotation rate: a UT1 error of ``dt`` moves every hour angle by
#: ``EARTH_ROTATION_RATE * dt`` (15.04 arcsec per second of time).
EARTH_ROTATION_RATE = 7.292115e-5 * u.rad / u.s

#: Age of the last measured value beyond which predictions are called stale
#: (astropy's ``auto_max_age`` default: the IERS publishes new values weekly).
MAX_TABLE_AGE = 30 * u.day

# Elevation at which the warning quotes the parallactic-angle bound.
_QUOTED_ELEVATION = 80 * u.deg

# The accuracy of the IERS Bulletin A predictions of UT1 - UTC, d days after
# the last measured value: S_t = 0.00025 d**0.75 s (Bulletin A, "the
# predictions' accuracy may be estimated from the expressions").
_BULLETIN_A_UT1 = 0.00025


class EarthOrientationStatus(NamedTuple):
    """How well the Earth-orientation tables in use cover some epochs.

    Returned by `earth_orientation_status`. Dates are `~astropy.time.Time`
    (UTC), spans and ages `~astropy.units.Quantity` in days, the UT1 error in
    seconds and the angle bounds in arcseconds.

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot import earth_orientation_status
    >>> status = earth_orientation_status(Time("2023-01-25"))
    >>> type(status).__name__, status._fields[0]
    ('EarthOrientationStatus', 'table_start')
    """

    #: Start of the tables.
    table_start: Time
    #: Last measured (not predicted) UT1 - UTC.
    measured_until: Time
    #: End of the predictions (the last row of the tables).
    predicted_until: Time
    #: The leap-second table's expiry: later leap seconds are not known.
    leap_seconds_expire: Time
    #: Days from the release of the tables to ``now``: astropy-iers-data's
    #: release date (its version) for the tables it installs, else the last
    #: measured value.
    age: u.Quantity
    #: First and last (unmasked, finite) epochs; None if there were none.
    first: Time
    last: Time
    #: Days from ``measured_until`` to ``last`` (negative: within the measurements).
    beyond_measured: u.Quantity
    #: Days from ``predicted_until`` to ``last`` (positive: past the predictions).
    beyond_predicted: u.Quantity
    #: Days from ``first`` to ``table_start`` (positive: before the tables).
    before_start: u.Quantity
    #: Likely UT1 error at ``last`` (Bulletin A's prediction accuracy, plus the
    #: drift of UT1 - UTC over any span past the predictions).
    ut1_error: u.Quantity
    #: The hour-angle error that ``ut1_error`` makes.
    hour_angle_error: u.Quantity
    #: Its bound on the parallactic-angle error at 80 deg elevation
    #: (``hour_angle_error / cos(80 deg)``; see `earth_orientation_status`).
    parallactic_angle_error: u.Quantity
    #: What the warning says, or None when the tables cover the epochs well.
    message: str


def _table():
    return iers.earth_orientation_table.get()


_FACTS = {}


def _table_facts():
    """(start, end of the predictions, last measured) MJD of the tables in use."""
    table = _table()
    facts = _FACTS.get(id(table))
    if facts is None or facts[0] is not table:  # the entry keeps its table alive
        mjd = np.asarray(table["MJD"].to_value(u.day), dtype=float)
        start, end = float(mjd[0]), float(mjd[-1])
        measured = min(float(table.meta.get("predictive_mjd", end + 1)) - 1, end)
        facts = (table, start, end, measured)
        _FACTS.clear()
        _FACTS[id(table)] = facts
    return facts[1:]


def _covered(low, high):
    """Whether epochs from MJD ``low`` to ``high`` need no warning (the quick check)."""
    start, end, measured = _table_facts()
    age = time.time() / 86400.0 + 40587.0 - measured  # the clock, as Time.now()
    stale = high > measured and age > MAX_TABLE_AGE.to_value(u.day)
    return not (stale or high > end or low < start)


def _mjd_range(obstime):
    """First and last finite, unmasked MJD of a Time (any scale), or None."""
    if obstime is None or obstime.size == 0:
        return None
    plain = obstime.unmasked if obstime.masked else obstime
    mjd = np.asarray(plain.jd1, dtype=float) + np.asarray(plain.jd2, dtype=float) - 2400000.5
    keep = np.isfinite(mjd)
    if obstime.masked:
        keep &= ~np.broadcast_to(obstime.mask, mjd.shape)
    if not np.any(keep):
        return None
    mjd = mjd[keep]
    return float(mjd.min()), float(mjd.max())


def _ut1_drift(table, days=30):
    """|d(UT1 - UTC)/dt| in s/day over the last ``days`` of the tables."""
    mjd = np.asarray(table["MJD"].to_value(u.day), dtype=float)
    dut = np.asarray(u.Quantity(table["UT1_UTC"]).to_value(u.s), dtype=float)
    last = mjd >= mjd[-1] - days
    if last.sum() < 2:
        return 0.0
    # Leap seconds jump UT1 - UTC by 1 s; they are not drift.
    steps = np.diff(dut[last])
    steps = steps[np.abs(steps) < 0.5]
    span = np.diff(mjd[last])[: steps.size].sum()
    return float(abs(steps.sum()) / span) if span > 0 else 0.0


def _date(time):
    return time.utc.iso[:10]


# Days between the last measured value of the IERS-A tables that astropy-iers-data
# installs and the date of its release (its version number): a week or two.
_RELEASE_LAG = 45.0


def _release_mjd(measured):
    """MJD of the release of the tables in use.

    The tables astropy-iers-data installs carry its release date in its
    version (``0.2026.11.2.0.34.55``: 2026-11-02), a week or two after their
    last measured value; for any other tables (downloaded, or made by hand),
    the last measured value stands for it.
    """
    try:
        version = metadata.version("astropy-iers-data")
    except metadata.PackageNotFoundError:  # pragma: no cover - astropy requires it
        return measured
    match = re.match(r"0\.(\d{4})\.(\d{1,2})\.(\d{1,2})", version)
    if match is None:
        return measured
    year, month, day = (int(g) for g in match.groups())
    try:
        released = float(erfa.cal2jd(year, month, day)[1])
    except erfa.ErfaError:
        return measured
    return released if 0 <= released - measured <= _RELEASE_LAG else measured


def earth_orientation_status(obstime=None, now=None):
    """How well the Earth-orientation tables in use cover some epochs.

    Parameters
    ----------
    obstime : `~astropy.time.Time`, optional
        The epochs (any shape and scale; masked and non-finite ones are
        ignored). Without them only the tables are described.
    now : `~astropy.time.Time`, optional
        The present, for the age of the tables (default: the clock).

    Returns
    -------
    EarthOrientationStatus
        Its ``message`` is None when the epochs lie within the measured values,
        or within the predictions of tables less than `MAX_TABLE_AGE` old.
        Otherwise it is the text of the warning: the tables are stale and the
        epochs lie beyond their measured values, or the epochs lie past the end
        of the predictions or before the start of the tables.

    Notes
    -----
    The UT1 error is estimated as IERS Bulletin A estimates the accuracy of its
    predictions, :math:`0.00025\\,d^{0.75}` s at :math:`d` days after the last
    measured value, plus, past the end of the predictions (where UT1 - UTC is
    held constant), the drift of UT1 - UTC over the last 30 days of the
    tables times the days past them. A UT1 error :math:`\\delta t` turns the
    Earth by :math:`\\omega\\,\\delta t` (15.04 arcsec per second) and moves the
    parallactic angle by :math:`-\\omega\\,\\delta t\\,\\cos\\phi\\cos A/\\cos E`
    (the derivative of Eq 16 with respect to the hour angle), at most
    :math:`\\omega\\,\\delta t/\\cos E`: 5.8 times the hour-angle error at
    80 deg elevation, without bound at the zenith. Satellite positions from
    TLEs (TEME) turn with the Earth by the same angle; SP3 orbits and the
    directions from a site to an Earth-fixed point do not depend on UT1.

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.eop import earth_orientation_status
    >>> status = earth_orientation_status(Time("2023-01-25T12:00"))
    >>> status.message is None  # measured values cover 2023
    True
    >>> float(status.ut1_error.to_value("s"))
    0.0
    """
    with _quiet():
        return _status(obstime, now)


def _status(obstime, now):
    table = _table()
    start, end, measured = _table_facts()
    now_mjd = (Time.now() if now is None else Time(now)).utc.mjd
    expires = Time(erfa.leap_seconds.expires)
    if expires.mjd < now_mjd:
        # ERFA's built-in table until astropy's first UTC conversion replaces it with its
        # own (astropy-iers-data's): ask astropy for it.
        update_leap_seconds()
        expires = Time(erfa.leap_seconds.expires)
    age = now_mjd - _release_mjd(measured)
    span = _mjd_range(obstime)
    if span is None:
        first = last = None
        beyond_measured = beyond_predicted = before_start = -np.inf
    else:
        first = Time(span[0], format="mjd", scale="utc")
        last = Time(span[1], format="mjd", scale="utc")
        beyond_measured = span[1] - measured
        beyond_predicted = span[1] - end
        before_start = start - span[0]
    ut1_error = 0.0
    if beyond_measured > 0:
        ut1_error = _BULLETIN_A_UT1 * beyond_measured ** 0.75
    if beyond_predicted > 0:
        ut1_error += _ut1_drift(table) * beyond_predicted
    hour_angle = (EARTH_ROTATION_RATE * ut1_error * u.s).to(u.arcsec, u.dimensionless_angles())
    parallactic = hour_angle / np.cos(_QUOTED_ELEVATION)
    fields = dict(
        table_start=Time(start, format="mjd", scale="utc"),
        measured_until=Time(measured, format="mjd", scale="utc"),
        predicted_until=Time(end, format="mjd", scale="utc"),
        leap_seconds_expire=expires,
        age=age * u.day, first=first, last=last,
        beyond_measured=beyond_measured * u.day, beyond_predicted=beyond_predicted * u.day,
        before_start=before_start * u.day, ut1_error=ut1_error * u.s,
        hour_angle_error=hour_angle, parallactic_angle_error=parallactic,
    )
    stale = beyond_measured > 0 and age > MAX_TABLE_AGE.to_value(u.day)
    if not (stale or beyond_predicted > 0 or before_start > 0):
        return EarthOrientationStatus(message=None, **fields)
    return EarthOrientationStatus(message=_message(fields, stale), **fields)


def _message(f, stale):
    """The one line of the warning."""
    tables = (f"the Earth-orientation tables in use ({f['age'].to_value(u.day):.0f} days "
              "old)")
    parts = []
    if f["before_start"] > 0:
        parts.append(f"epochs from {_date(f['first'])} lie "
                     f"{f['before_start'].to_value(u.day):.0f} days before the "
                     f"Earth-orientation tables start ({_date(f['table_start'])}), where UT1 "
                     "- UTC and polar motion are held at their first values (UT1 off by up "
                     "to about a second)")
    if f["beyond_measured"] > 0:
        where = (f"epochs up to {_date(f['last'])} lie {f['beyond_measured'].to_value(u.day):.0f}"
                 f" days after the last measured value of {tables}")
        if f["beyond_predicted"] > 0:
            where += (f", {f['beyond_predicted'].to_value(u.day):.0f} days past the predictions, "
                      "where UT1 - UTC is held at its last predicted value and polar motion at "
                      "its mean")
        elif stale:
            where += ", within predictions older than the 30 days astropy accepts"
        parts.append(where)
        parts.append(f"UT1 may be off by {f['ut1_error'].to_value(u.s):.2g} s, which turns hour "
                     f"angles by {f['hour_angle_error'].to_value(u.arcsec):.2g} arcsec and "
                     "parallactic angles by up to "
                     f"{f['parallactic_angle_error'].to_value(u.arcsec):.2g} arcsec at 80 deg "
                     "elevation")
    if f["last"] is not None and f["last"] > f["leap_seconds_expire"]:
        parts.append(f"leap seconds after {_date(f['leap_seconds_expire'])} are not known")
    if stale:
        parts.append("newer tables: python -m pip install -U astropy-iers-data (or, online, "
                     "astropy_feedrot.conf.iers_auto_download = True)")
    elif f["beyond_predicted"] > 0:  # recent tables: no newer ones reach further
        parts.append("no tables predict further")
    return "computed anyway: " + "; ".join(parts)


class _Scope:
    """The epochs seen by the nested contexts of one call."""

    def __init__(self):
        self.low = np.inf
        self.high = -np.inf

    def add(self, obstime):
        span = _mjd_range(obstime)
        if span is not None:
            self.low = min(self.low, span[0])
            self.high = max(self.high, span[1])

    def epochs(self):
        if self.high < self.low:
            return None
        return Time([self.low, self.high], format="mjd", scale="utc")


_SCOPE = contextvars.ContextVar("astropy_feedrot_eop_scope", default=None)


@contextlib.contextmanager
def iers_context(obstime=None):
    """Context (or decorator) in which Earth orientation is offline and checked.

    Inside it, astropy downloads IERS tables only if the user opted in with
    ``astropy_feedrot.conf.iers_auto_download = True``. Otherwise astropy's
    age check is off, epochs beyond the tables are computed as described in
    `astropy_feedrot.eop`, and astropy's own messages about them (polar motion
    beyond the tables, ERFA's "dubious year", the expired leap-second table)
    are replaced by one `~astropy_feedrot.StaleEarthOrientationWarning` when the
    outermost context ends, naming what `earth_orientation_status` found for
    all the epochs given to the contexts nested in it. Astropy's settings are
    restored on exit.

    Parameters
    ----------
    obstime : `~astropy.time.Time`, optional
        Epochs the code inside will transform (checked on exit).

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy.utils import iers
    >>> from astropy_feedrot.eop import iers_context
    >>> with iers_context(Time("2023-01-25T12:00")):
    ...     iers.conf.auto_download
    False
    """
    scope = _SCOPE.get()
    outermost = scope is None
    if outermost:
        scope = _Scope()
        token = _SCOPE.set(scope)
    if obstime is not None:
        scope.add(obstime)
    try:
        if conf.iers_auto_download:
            with iers.conf.set_temp("auto_download", True):
                yield
        else:
            with iers.conf.set_temp("auto_download", False), \
                    iers.conf.set_temp("auto_max_age", None), \
                    iers.conf.set_temp("iers_degraded_accuracy", "ignore"), \
                    _quiet():
                yield
    finally:
        if outermost:
            _SCOPE.reset(token)
    if outermost and scope.high >= scope.low and not _covered(scope.low, scope.high):
        message = earth_orientation_status(scope.epochs()).message
        if message is not None:
            warn_caller(message, StaleEarthOrientationWarning)


@contextlib.contextmanager
def _quiet():
    """Silence astropy's and ERFA's messages that the one warning replaces."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "Tried to get polar motions", AstropyWarning)
        warnings.filterwarnings("ignore", ".*dubious year", erfa.ErfaWarning)
        warnings.filterwarnings("ignore", "leap-second file is expired", AstropyWarning)
        yield
