# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""UTC days, and the Earth's rotation at instants within them.

UT1 - UTC, polar motion and TT - UTC are linear within each UTC day (the
IERS values are daily and astropy interpolates them linearly; ERFA spreads a
leap second over its day). `UtcDays` takes them at the start of each day
with epochs and of the next (`~astropy_feedrot.earth.eop.utc_earth_orientation`),
and `Instants` gives TT, the Earth rotation angle, GMST 1982, polar motion
and the site's motion at any instant within those days, exactly as astropy
would at that instant. `~astropy_feedrot.earth.orientation.EarthOrientation` is built on
them.
"""

import erfa
import numpy as np

from ..core.cache import KeptLast
from .eop import downloads_allowed, iers_context, table_arrays, utc_earth_orientation
from .nodes import unique_integers

__all__ = ["UtcDays", "Instants", "distinct", "terrestrial", "ERA_RATE", "OMEGA"]

_DAY = 86400.0

# d(ERA)/d(UT1) in radians per day (ERFA era00).
#: d(ERA)/d(UT1) in radians per day (ERFA ``era00``).
ERA_RATE = 2 * np.pi * 1.00273781191135448


# The Earth's angular velocity in rad/s, as ERFA's pvtob.
OMEGA = ERA_RATE / _DAY


def distinct(values, limit):
    """Distinct values of a float array of integers, and a function of each element's index.

    If the values span at most ``limit``, every integer of their range is
    taken (the index is then a subtraction); otherwise only those present.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.utc_days import distinct
    >>> values, index = distinct(np.array([3.0, 5.0, 3.0]), 10)
    >>> values, index()
    (array([3., 4., 5.]), array([0, 2, 0]))
    """
    low, high = values.min(), values.max()
    if high - low < limit:
        return np.arange(low, high + 1), lambda: (values - low).astype(np.intp)
    distinct, index = unique_integers(values.ravel(), low)
    return distinct, lambda: index.reshape(values.shape)


class UtcDays:
    """The UTC days of some epochs and the quantities linear within each day.

    Every epoch is a day number ``day`` (UTC midnights counted from ``ref``)
    and a fraction ``frac`` of that day. At the start of each day with epochs
    and of the next, astropy gives TT, UT1 and polar motion; between them they
    are linear (astropy interpolates the daily IERS values linearly in UTC,
    and ERFA spreads a leap second over its day), so the tables hold the value
    at the start of the day and the change over the day.

    Parameters
    ----------
    obstime : `~astropy.time.Time`
        Unmasked epochs (any shape, flattened; any scale, converted to UTC once).

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.utc_days import UtcDays
    >>> days = UtcDays(Time(["2023-01-25T06:00", "2023-01-27T18:00"]))
    >>> days.days, days.frac
    (array([0., 2.]), array([0.25, 0.75]))
    """

    def __init__(self, obstime):
        jd1 = np.asarray(obstime.jd1, dtype=float).ravel()
        jd2 = np.asarray(obstime.jd2, dtype=float).ravel()
        first = int(np.argmin(jd1 + jd2)) if jd1.size > 1 else 0
        with iers_context(obstime):
            if obstime.scale != "utc":
                utc = obstime.utc
                jd1 = np.asarray(utc.jd1, dtype=float).ravel()
                jd2 = np.asarray(utc.jd2, dtype=float).ravel()
            # The UTC midnight before the first epoch (a JD, exact in a float).
            self.ref1 = erfa.DJM0 + np.floor((jd1[first] - erfa.DJM0) + jd2[first])
            self.ref2 = 0.0
            a = jd1 - self.ref1
            b = jd2
            self.u = a + b
            day = np.floor(self.u)
            # At a midnight the rounding of a + b may leave the fraction a hair outside.
            self.day, self.frac = day, np.clip((a - day) + b, 0.0, 1.0 - 2.0**-53)
            self.days, self._slot = distinct(day, max(day.size, 2))
            self._tables()

    @property
    def slot(self):
        """Each epoch's index into the day tables."""
        if callable(self._slot):
            self._slot = self._slot()
        return self._slot

    def slot_of(self, day):
        """Indices into the day tables of days (which must be in them)."""
        return np.searchsorted(self.days, day)

    def _tables(self):
        # Values at the start of each day and of the next one: within a UTC day
        # they are linear, and continuous across midnights (a leap second is
        # spread over its day). They depend on nothing but the days and the
        # IERS table, so the last few sets are kept (a scan, a source, a call
        # per epoch asks for the same days again).
        key = arrays = None
        if self.days.size <= _KEPT_DAYS and not downloads_allowed():
            arrays = table_arrays()
            key = (self.ref1, self.days.tobytes())
            tables = _DAY_TABLES.get(key, tag=arrays)
            if tables is not None:
                self.__dict__.update(tables)
                return
        tables = _day_tables(self.ref1, self.ref2, self.days)
        self.__dict__.update(tables)
        if key is not None:
            _DAY_TABLES.put(key, tables, tag=arrays)

    def at(self, slot, frac):
        """The quantities at instants given by day slots and fractions of day."""
        return Instants(self, slot, frac)


#: How many sets of days `UtcDays` keeps the tables of, and the most days a set kept.
DAY_TABLES_CACHE_SIZE = 16
_KEPT_DAYS = 4096
_DAY_TABLES = KeptLast(DAY_TABLES_CACHE_SIZE)


def _day_tables(ref1, ref2, days):
    """TT, the Earth rotation angle, GMST, polar motion and s' at the start of each
    day (UTC midnights ``ref1 + ref2 + days``) and their change over it (read-only)."""
    starts = np.union1d(days, days + 1)
    this, following = np.searchsorted(starts, days), np.searchsorted(starts, days + 1)
    tt1, tt2, ut11, ut12, xp, yp = utc_earth_orientation(
        ref1 + starts, np.full(starts.shape, ref2))
    t = {}
    # TT is counted in days from the start of the first day of the tables.
    t["tt1"], t["tt2"] = float(tt1[0]), float(tt2[0])
    t["tt0"] = ((tt1 - t["tt1"]) + (tt2 - t["tt2"]))[this]
    t["tt_rate"] = _length(tt1, tt2, this, following)
    era = erfa.ufunc.era00(ut11, ut12)
    t["era0"] = era[this]
    t["era_rate"] = ERA_RATE * _length(ut11, ut12, this, following)
    gmst = erfa.ufunc.gmst82(ut11, ut12)
    t["gmst0"] = gmst[this]
    # GMST turns by a little more than 2 pi in a day.
    t["gmst_rate"] = 2 * np.pi + np.mod(gmst[following] - gmst[this], 2 * np.pi)
    t["xp0"], t["xp_rate"] = xp[this], xp[following] - xp[this]
    t["yp0"], t["yp_rate"] = yp[this], yp[following] - yp[this]
    t["sp"] = erfa.ufunc.sp00(tt1[this], tt2[this])
    for value in t.values():
        if isinstance(value, np.ndarray):
            value.flags.writeable = False
    return t


def _length(jd1, jd2, this, following):
    """Days from ``[this]`` to ``[following]`` of a two-part JD, to its precision."""
    return (jd1[following] - jd1[this]) + (jd2[following] - jd2[this])


class Instants:
    """Instants within the days of a `UtcDays`, with their exact Earth orientation.

    Examples
    --------
    >>> import erfa
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.utc_days import UtcDays
    >>> t = Time(["2023-01-25T06:00"])
    >>> days = UtcDays(t)
    >>> instants = days.at(days.slot, days.frac)
    >>> ut1 = t.ut1  # astropy's UT1, for comparison
    >>> float(instants.era[0] - erfa.era00(ut1.jd1, ut1.jd2)[0])  # doctest: +FLOAT_CMP
    0.0
    """

    def __init__(self, days, slot, frac):
        self.size = frac.size
        self.tt = days.tt0[slot] + days.tt_rate[slot] * frac  # days from days.tt1 + tt2
        self.tt1, self.tt2 = days.tt1, days.tt2 + self.tt
        self.era = days.era0[slot] + days.era_rate[slot] * frac
        self.xp = days.xp0[slot] + days.xp_rate[slot] * frac
        self.yp = days.yp0[slot] + days.yp_rate[slot] * frac
        self.sp = days.sp[slot]
        self._days, self._slot, self._frac = days, slot, frac

    @property
    def gmst82(self):
        days = self._days
        return days.gmst0[self._slot] + days.gmst_rate[self._slot] * self._frac

    def to_itrs(self, vectors):
        """CIRS vectors (..., P, 3) to ITRS, as astropy's ``cirs_to_itrs_mat``."""
        return terrestrial(vectors, self.era + self.sp, self.xp, self.yp)

    def site(self, xyz):
        """Position and velocity (m, m/s) in CIRS of a site at ITRS ``xyz`` (ERFA ``pvtob``)."""
        x, y, z = xyz
        # ERFA's pom00 transposed: R_z(-s') R_y(x_p) R_x(y_p), then R_z(-ERA).
        cy, sy = np.cos(self.yp), np.sin(self.yp)
        y, z = cy * y + sy * z, cy * z - sy * y
        cx, sx = np.cos(self.xp), np.sin(self.xp)
        x, z = cx * x - sx * z, cx * z + sx * x
        angle = self.era + self.sp
        c, s = np.cos(angle), np.sin(angle)
        position = np.stack([c * x - s * y, s * x + c * y, z], axis=-1)
        velocity = OMEGA * np.stack([-s * x - c * y, c * x - s * y, np.zeros_like(x)], axis=-1)
        return position, velocity


def terrestrial(vectors, angle, xp, yp):
    """W(x_p, y_p) R_z(angle) applied to vectors (..., N, 3); W = R_x(-y_p) R_y(-x_p).

    Polar motion is below 1e-5 rad, so that cos = 1 - a**2 / 2 and sin = a
    are exact to 1e-17.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.utc_days import terrestrial
    >>> terrestrial(np.array([[1.0, 0, 0]]), np.pi / 2, 0.0, 0.0).round(12) + 0.0
    array([[ 0., -1.,  0.]])
    """
    vectors = np.asarray(vectors, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    x = c * vectors[..., 0] + s * vectors[..., 1]
    y = c * vectors[..., 1] - s * vectors[..., 0]
    z = vectors[..., 2]
    cx = 1 - 0.5 * xp * xp
    x, z = cx * x + xp * z, cx * z - xp * x
    cy = 1 - 0.5 * yp * yp
    y, z = cy * y - yp * z, cy * z + yp * y
    return np.stack([x, y, z], axis=-1)
