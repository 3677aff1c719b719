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
import hashlib
import math
import os
import pathlib
import re
import tempfile
import threading
import time
import warnings
from importlib import metadata
from typing import NamedTuple

import astropy
import erfa
import numpy as np
from astropy import units as u
from astropy.config import get_cache_dir, get_config
from astropy.coordinates.builtin_frames.utils import get_polar_motion
from astropy.time import Time, update_leap_seconds
from astropy.utils import iers
from astropy.utils.exceptions import AstropyWarning

from ..core.config import conf
from ..core.exceptions import StaleEarthOrientationWarning, warn_caller
from ..io import FileFormatError
from .iers_files import bundled_arrays

__all__ = [
    "EarthOrientationStatus",
    "earth_orientation_status",
    "iers_context",
    "downloads_allowed",
    "utc_earth_orientation",
    "table_arrays",
    "table_in_use",
    "TableArrays",
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


# Polar motion astropy uses outside the tables (the 1962-2014 mean of IERS B,
# astropy.coordinates.builtin_frames.utils), in radians.
_DEFAULT_PM = (0.035 * u.arcsec).to_value(u.rad), (0.29 * u.arcsec).to_value(u.rad)

_ARRAYS = {}
_ARRAYS_LOCK = threading.Lock()


class TableArrays(NamedTuple):
    """The columns of an Earth-orientation table that the package interpolates.

    Examples
    --------
    >>> from astropy_feedrot.earth.eop import table_arrays
    >>> arrays = table_arrays()
    >>> bool(arrays.mjd[0] <= 41684.0 < arrays.mjd[-1])  # IERS values since 1973
    True
    """

    #: The days of the table (MJD, UTC).
    mjd: np.ndarray
    #: UT1 - UTC (s).
    ut1_utc: np.ndarray
    #: Polar motion x_p, y_p (rad).
    xp: np.ndarray
    yp: np.ndarray
    #: The first day of predictions (MJD), or the day after the table.
    predictive_mjd: float


def downloads_allowed():
    """Whether astropy may download IERS tables here (read once per outermost `iers_context`).

    Returns
    -------
    bool
        ``astropy_feedrot.conf.iers_auto_download``, as the outermost
        `iers_context` read it.

    Examples
    --------
    >>> from astropy_feedrot.earth.eop import downloads_allowed
    >>> downloads_allowed()
    False
    """
    scope = _SCOPE.get()
    return conf.iers_auto_download if scope is None else scope.downloads


def table_in_use():
    """The Earth-orientation table astropy uses, if it has one loaded; else None.

    None stands for the tables bundled with astropy before astropy has read
    them (`table_arrays` then reads a kept copy of their arrays). With
    ``astropy_feedrot.conf.iers_auto_download`` on, astropy's table (loaded
    now if need be).

    Returns
    -------
    `~astropy.utils.iers.IERS` or None

    Examples
    --------
    >>> from astropy.utils import iers
    >>> from astropy_feedrot.earth.eop import table_in_use
    >>> b = iers.IERS_B.open(iers.IERS_B_FILE)
    >>> with iers.earth_orientation_table.set(b):
    ...     table_in_use() is b
    True
    """
    if downloads_allowed():
        return _table()
    value = getattr(iers.earth_orientation_table, "_value", None)
    if value is not None:
        return value
    return iers.IERS_Auto.iers_table  # what earth_orientation_table.get() would return


def _arrays_of(table):
    mjd = np.asarray(table["MJD"].to_value(u.day), dtype=float)
    return TableArrays(mjd,
                       np.asarray(u.Quantity(table["UT1_UTC"]).to_value(u.s), dtype=float),
                       np.asarray(u.Quantity(table["PM_x"]).to_value(u.rad), dtype=float),
                       np.asarray(u.Quantity(table["PM_y"]).to_value(u.rad), dtype=float),
                       float(table.meta.get("predictive_mjd", mjd[-1] + 1)))


def _bundled_arrays():
    """The arrays of the tables astropy ships, read by their columns (`iers_files`);
    astropy's own reader where the files do not follow their format."""
    try:
        return TableArrays(*bundled_arrays())
    except (OSError, FileFormatError):
        return _arrays_of(_table())


def _kept_path():
    """Where the arrays of the bundled tables are kept, named after their files."""
    files = [iers.IERS_A_FILE, iers.IERS_B_FILE]
    stamp = [astropy.__version__] + [(str(f), os.stat(f).st_size, os.stat(f).st_mtime_ns)
                                     for f in files]
    key = hashlib.blake2b(repr(stamp).encode(), digest_size=10).hexdigest()
    return pathlib.Path(get_cache_dir()) / "astropy_feedrot" / f"iers-{key}.npz"


def _read_kept():
    try:
        with np.load(_kept_path()) as kept:
            return TableArrays(kept["mjd"], kept["ut1_utc"], kept["xp"], kept["yp"],
                               float(kept["predictive_mjd"]))
    except (OSError, KeyError, ValueError):  # not kept yet, or unreadable: read the tables
        return None


def _keep(arrays):
    try:
        path = _kept_path()
        path.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path.parent, suffix=".npz", delete=False) as f:
            np.savez(f, **arrays._asdict())
        os.replace(f.name, path)  # whole or not at all, for processes reading at once
    except OSError:  # a read-only cache: the tables are read again next time
        pass


def table_arrays():
    """The Earth-orientation table in use, as plain arrays.

    Astropy reads its bundled IERS tables (``astropy-iers-data``) on first
    use, which takes about a second and a half. Until astropy has a table
    loaded (or when the user has set none), these arrays are read instead
    from the bundled files' own columns (`astropy_feedrot.earth.iers_files`, bit
    for bit astropy's values, in a few tens of milliseconds), and kept in
    astropy's cache directory, named after the bundled files (their paths,
    sizes and times, and astropy's version): a later process gets UT1 and
    polar motion in a millisecond. A table set with ``iers.earth_orientation_table.set`` or
    already loaded by astropy is read directly (and with
    ``astropy_feedrot.conf.iers_auto_download`` on, astropy's own table,
    which it may refresh).

    Returns
    -------
    TableArrays

    Examples
    --------
    >>> from astropy_feedrot.earth.eop import table_arrays
    >>> arrays = table_arrays()
    >>> arrays.mjd.shape == arrays.ut1_utc.shape
    True
    """
    table = table_in_use()
    key = "bundled" if table is None else id(table)
    with _ARRAYS_LOCK:
        kept = _ARRAYS.get(key)
    if kept is not None and kept[0] is table:  # the entry keeps its table alive
        return kept[1]
    arrays = None if table is not None else _read_kept()
    if arrays is None:
        arrays = _arrays_of(table) if table is not None else _bundled_arrays()
        if table is None:
            _keep(arrays)
    with _ARRAYS_LOCK:
        _ARRAYS.clear()
        _ARRAYS[key] = (table, arrays)
    return arrays


def _table_facts():
    """(start, end of the predictions, last measured) MJD of the tables in use."""
    arrays = table_arrays()
    start, end = float(arrays.mjd[0]), float(arrays.mjd[-1])
    return start, end, min(arrays.predictive_mjd - 1, end)


def utc_earth_orientation(jd1, jd2):
    """TT, UT1 and polar motion at UTC instants, as astropy's `~astropy.time.Time` gives them.

    The same numbers as ``Time(jd1, jd2, format="jd", scale="utc")``'s
    ``.tt`` and ``.ut1`` and astropy's ``get_polar_motion`` (linear
    interpolation of the daily IERS values in UTC, a leap second taken out of
    the UT1 - UTC step, the first or last values outside the tables and the
    50-year mean polar motion there; ERFA ``utctai``, ``taitt``, ``utcut1``),
    from plain arrays, without building a `~astropy.time.Time`: a few
    microseconds instead of a few hundred. With
    ``astropy_feedrot.conf.iers_auto_download`` on, astropy is asked (it may
    then refresh its tables). Call it inside `iers_context`.

    Parameters
    ----------
    jd1, jd2 : array-like
        Two-part Julian dates in UTC (same shape).

    Returns
    -------
    tt1, tt2, ut11, ut12, xp, yp : ndarray
        Two-part Julian dates of TT and UT1, and the polar motion in radians.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.eop import iers_context, utc_earth_orientation
    >>> t = Time(["2023-01-25T00:00", "2023-01-26T00:00"])
    >>> with iers_context(t):
    ...     tt1, tt2, ut11, ut12, xp, yp = utc_earth_orientation(t.jd1, t.jd2)
    ...     ut1 = t.ut1
    >>> bool(np.allclose((ut11 - ut1.jd1) + (ut12 - ut1.jd2), 0, atol=1e-15))  # astropy's
    True
    """
    jd1 = np.asarray(jd1, dtype=float)
    jd2 = np.asarray(jd2, dtype=float)
    # ERFA's ufuncs directly: the status of utctai and utcut1 says only "dubious
    # year", which iers_context silences, or "unacceptable date" (before -4799),
    # which a Time cannot hold.
    tai1, tai2, _ = erfa.ufunc.utctai(jd1, jd2)
    tt1, tt2, _ = erfa.ufunc.taitt(tai1, tai2)
    if downloads_allowed():  # astropy's own route, which may refresh its tables
        t = Time(jd1, jd2, format="jd", scale="utc")
        ut1 = t.ut1
        xp, yp = get_polar_motion(t)
        return tt1, tt2, ut1.jd1, ut1.jd2, xp, yp
    mjd_table, dut_table, xp_table, yp_table, _ = table_arrays()
    # As astropy's IERS._interpolate.
    mjd = np.floor(jd1 - erfa.DJM0 + jd2)
    utc = jd1 - (erfa.DJM0 + mjd) + jd2
    i = np.searchsorted(mjd_table, mjd, side="right")
    i1 = np.clip(i, 1, mjd_table.size - 1)
    i0 = i1 - 1
    fraction = (mjd - mjd_table[i0] + utc) / (mjd_table[i1] - mjd_table[i0])
    step = dut_table[i1] - dut_table[i0]
    step -= step.round()  # a leap second is not a change of UT1 - UTC
    dut = dut_table[i0] + fraction * step
    xp = xp_table[i0] + fraction * (xp_table[i1] - xp_table[i0])
    yp = yp_table[i0] + fraction * (yp_table[i1] - yp_table[i0])
    before, after = i == 0, i == mjd_table.size
    dut = np.where(before, dut_table[0], np.where(after, dut_table[-1], dut))
    outside = before | after
    xp = np.where(outside, _DEFAULT_PM[0], xp)
    yp = np.where(outside, _DEFAULT_PM[1], yp)
    ut11, ut12, _ = erfa.ufunc.utcut1(jd1, jd2, dut)
    return tt1, tt2, ut11, ut12, xp, yp


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
    masked = obstime.masked
    plain = obstime.unmasked if masked else obstime
    mjd = (np.asarray(plain.jd1, dtype=float) - 2400000.5) + np.asarray(plain.jd2, dtype=float)
    if mjd.size == 1 and not masked:  # one epoch: the common case, kept cheap
        value = float(mjd.flat[0])
        return (value, value) if math.isfinite(value) else None
    keep = np.isfinite(mjd)
    if masked:
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
    >>> from astropy_feedrot.earth.eop import earth_orientation_status
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
    """The epochs seen by the nested contexts of one call.

    The contexts of one call are mostly given the same `~astropy.time.Time`
    objects: each is kept once (by identity) and its span read when the
    outermost context ends.
    """

    def __init__(self):
        self._times = {}
        # Read once per call: the configuration costs microseconds a read.
        self.downloads = conf.iers_auto_download

    def add(self, obstime):
        self._times.setdefault(id(obstime), obstime)

    def span(self):
        """(first, last) MJD of all the epochs, or None."""
        spans = [s for s in map(_mjd_range, self._times.values()) if s is not None]
        if not spans:
            return None
        return min(s[0] for s in spans), max(s[1] for s in spans)


_SCOPE = contextvars.ContextVar("astropy_feedrot_eop_scope", default=None)


@contextlib.contextmanager
def iers_context(obstime=None):
    """Context (or decorator) in which Earth orientation is offline and checked.

    Inside it, astropy downloads IERS tables only if the user opted in with
    ``astropy_feedrot.conf.iers_auto_download = True``. Otherwise astropy's
    age check is off, epochs beyond the tables are computed as described in
    `astropy_feedrot.earth.eop`, and astropy's own messages about them (polar motion
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
    >>> from astropy_feedrot.earth.eop import iers_context
    >>> with iers_context(Time("2023-01-25T12:00")):
    ...     iers.conf.auto_download
    False
    """
    scope = _SCOPE.get()
    if scope is not None:  # nested: the outermost context has set everything up
        if obstime is not None:
            scope.add(obstime)
        yield
        return
    scope = _Scope()
    token = _SCOPE.set(scope)
    if obstime is not None:
        scope.add(obstime)
    try:
        if scope.downloads:
            with iers.conf.set_temp("auto_download", True):
                yield
        else:
            with _offline(), _quiet():
                yield
    finally:
        _SCOPE.reset(token)
    span = scope.span()
    if span is not None and not _covered(*span):
        message = earth_orientation_status(
            Time(list(span), format="mjd", scale="utc")).message
        if message is not None:
            warn_caller(message, StaleEarthOrientationWarning)


# Astropy's IERS settings inside iers_context when downloads are off.
_OFFLINE = (("auto_download", False), ("auto_max_age", None),
            ("iers_degraded_accuracy", "ignore"))
_ABSENT = object()


def _offline_items():
    """Astropy's configuration items of `_OFFLINE` and their values, validated once."""
    items = []
    for name, value in _OFFLINE:
        item = getattr(type(iers.conf), name)
        items.append((item, item._validate_val(value)))
    return tuple(items)


_OFFLINE_ITEMS = _offline_items()


@contextlib.contextmanager
def _offline():
    """Astropy's IERS settings `_OFFLINE` inside, and exactly what was there after.

    The values are put into astropy's configuration sections as
    ``ConfigItem.set_temp`` puts them, without validating them again on every
    entry (they were validated once, at import): set_temp reads, validates and
    writes each item twice, about 16 us an item, which was a tenth of a call
    with ten epochs. An item that has aliases takes astropy's own route.
    """
    saved = []
    with contextlib.ExitStack() as stack:
        try:
            for item, value in _OFFLINE_ITEMS:
                if item.aliases:
                    stack.enter_context(item.set_temp(value))
                    continue
                section = get_config(item.module, rootname=item.rootname)
                saved.append((section, item.name, section.get(item.name, _ABSENT)))
                section[item.name] = value
            yield
        finally:
            for section, name, old in reversed(saved):
                if old is not _ABSENT:
                    section[name] = old
                elif name in section:
                    del section[name]


@contextlib.contextmanager
def _quiet():
    """Silence astropy's and ERFA's messages that the one warning replaces."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "Tried to get polar motions", AstropyWarning)
        warnings.filterwarnings("ignore", ".*dubious year", erfa.ErfaWarning)
        warnings.filterwarnings("ignore", "leap-second file is expired", AstropyWarning)
        yield
