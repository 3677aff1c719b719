# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Earth orientation at many epochs, each quantity computed as often as it needs.

Astropy's transformation from a celestial frame to the topocentric ITRS
(``ITRS(location=...)``) spends nearly all its time on two series that change
over days: precession-nutation (ERFA ``pnm06a``, whose CIP coordinates X, Y
and CIO locator s set the GCRS to CIRS rotation) and the Earth's ephemeris
(``epv00``: barycentric velocity and heliocentric position, which set the
annual aberration and the light deflection by the Sun). `EarthOrientation`
computes what astropy computes (ERFA ``apco`` and astropy's ``atciqz``:
deflection ``ld``, aberration ``ab`` with the site's velocity, the CIO-based
rotation to ITRS), but takes each input where it is cheap:

* UT1 - UTC, polar motion and TT - UTC are linear within each UTC day (the
  IERS values are daily and astropy interpolates them linearly; ERFA spreads
  a leap second over its day): astropy gives them once at the start of each
  day with epochs and of the next, and the Earth rotation angle, GMST 1982,
  TT and polar motion follow exactly at any instant;
* X, Y and s come from ERFA every day of TT, the ephemeris every 1.5 days,
  through Lagrange polynomials of 16 and 10 nodes (1e-13 rad and 5e-5 m/s);
  for sparse epochs over long spans (fewer than 100 per node) every 1.5 and
  2.5 days through 24 and 20 nodes (0.002 mas and 0.0012 m/s); or from ERFA
  at the instants themselves when they are fewer than the nodes;
* the site's position and velocity (diurnal aberration), the Earth's
  rotation and polar motion are computed at each instant.

Many epochs close together share the work: within each cell of a fixed grid
of UTC (15 min to 4 h, chosen by the density of the epochs, never across a
UTC midnight) the ITRS direction is computed at the Chebyshev points of the
cell and is a polynomial (degree 5 to 10) in time at every epoch, to 3e-5 mas;
cells with too few epochs are computed at the epochs. The cost is a few ERFA
series per day of the span and under 0.1 us per epoch, and at no number of
epochs more than astropy's own transformation (see `fast_path_applies`).
"""

import collections
import concurrent.futures
import hashlib
import math
import threading

import erfa
import numpy as np
from astropy import units as u
from astropy.coordinates import (
    FK4,
    FK5,
    ICRS,
    BarycentricMeanEcliptic,
    BarycentricTrueEcliptic,
    FK4NoETerms,
    Galactic,
    Supergalactic,
    UnitSphericalRepresentation,
)
from astropy.time import Time
from astropy.utils import iers

from .config import conf
from .eop import iers_context, utc_earth_orientation
from .inputs import as_location, as_skycoord, as_time

__all__ = [
    "EarthOrientation",
    "orientation_of",
    "clear_orientation_cache",
    "fast_path_applies",
    "site_position",
    "FIXED_FRAMES",
    "FAST_PATH_MIN_DISTANCE",
    "DEFAULT_STEP",
]

#: The default of the ``step`` argument of `EarthOrientation`, kept for
#: compatibility: node spacings are now chosen per quantity.
DEFAULT_STEP = 15 * u.min

#: Celestial frames whose transformation to ICRS does not depend on the time
#: of observation (their own equinox or obstime attributes are fixed).
FIXED_FRAMES = (ICRS, FK5, FK4, FK4NoETerms, Galactic, Supergalactic,
                BarycentricMeanEcliptic, BarycentricTrueEcliptic)

#: Sources nearer than this take astropy's transformation at every epoch (a
#: distance-less source is infinitely far).
FAST_PATH_MIN_DISTANCE = 1 * u.au

_DAY = 86400.0
# d(ERA)/d(UT1) in radians per day (ERFA era00).
_ERA_RATE = 2 * np.pi * 1.00273781191135448
# The Earth's angular velocity in rad/s, as ERFA's pvtob.
_OMEGA = _ERA_RATE / _DAY
# Metres per second in au per day, and au per day in units of c (ERFA apcs).
_AU_PER_DAY = erfa.DAU / _DAY
_C_AU_PER_DAY = erfa.DAU / erfa.CMPS / _DAY
_AU = erfa.DAU  # metres

# Slow series: (node spacing in days of TT, number of nodes per Lagrange polynomial).
# X, Y, s: 16 nodes a day apart interpolate the nutation's 5- to 14-day terms to
# 0.00002 mas (1e-13 rad). The ephemeris: 10 nodes 1.5 days apart give the Earth's
# velocity to 5e-5 m/s (0.00003 mas of aberration), enough for sources without a
# distance; 14 nodes a day apart give the positions to 1 cm, for the Sun (1e-13 rad)
# and the parallax of sources with a distance.
_CIP_GRID = (1.0, 16)
_VELOCITY_GRID = (1.5, 10)
_POSITION_GRID = (1.0, 14)
# With fewer than _SPARSE epochs per node of _CIP_GRID the nodes cost more than the
# epochs, and sparser grids take over for the directions of sources (the Sun keeps
# the others): 0.002 mas for X and Y, 0.0012 m/s (0.0008 mas).
_SPARSE = 100
_SPARSE_CIP_GRID = (1.5, 24)
_SPARSE_VELOCITY_GRID = (2.5, 20)
# With many instants in an interval of a grid, the interpolant is reduced there to
# a polynomial of this degree (Chebyshev points), below 1e-6 mas.
_PIECE_DEGREE = 5

# Cells of UTC: (cells per day, polynomial degree). The direction turns with the
# Earth by 2 pi / (cells per day) within a cell; these degrees keep the error of
# the polynomials below 3e-5 mas (and 1e-13 rad for the Sun).
_CELLS = ((96, 5), (48, 6), (24, 7), (12, 8), (6, 10))

# Cost model of the choice between cells and evaluation at the epochs, in
# units of one exact evaluation at an instant: a polynomial of degree m costs
# (_HORNER_BASE + _HORNER_PER_DEGREE * m) per epoch.
_HORNER_BASE = 0.05
_HORNER_PER_DEGREE = 0.015


def fast_path_applies(target, obstime):
    """Whether Earth orientation at these epochs comes from `EarthOrientation`.

    This is the one rule of the package for its fast path. Where it holds,
    directions, rotations and the Sun come from `EarthOrientation`, which
    agrees with astropy's transformation at every epoch to 0.0001 mas (0.003
    mas for sparse epochs over long spans) and costs less at any number of
    epochs (``benchmarks/natural.py`` measures it); elsewhere astropy's frames
    are used at every epoch.

    Parameters
    ----------
    target : `~astropy.coordinates.SkyCoord` or None
        The natural source(s), or None for Earth rotation alone (the TEME to
        ITRS rotation of SGP4 orbits, the Sun).
    obstime : `~astropy.time.Time`
        The epochs.

    Returns
    -------
    bool
        True if ``astropy_feedrot.conf.fast_path`` is on (the default) and,
        for a target, it is fixed in one of `FIXED_FRAMES`, has no proper
        motion or radial velocity, is at least `FAST_PATH_MIN_DISTANCE` away
        (or has no distance), and its shape and that of ``obstime`` pair every
        target with every epoch (or there is one target); the shapes (3, 1)
        and (24,) do, (24,) and (24,) do not.

    Raises
    ------
    TypeError
        If ``obstime`` is not a time or ``target`` not a coordinate (see
        `~astropy_feedrot.inputs.as_time` and
        `~astropy_feedrot.inputs.as_skycoord`).

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth import fast_path_applies
    >>> times = Time("2023-01-25") + np.arange(24) * u.hour
    >>> fast_path_applies(SkyCoord(ra=10 * u.deg, dec=20 * u.deg), times)
    True
    >>> fast_path_applies(SkyCoord(ra=10 * u.deg, dec=20 * u.deg, distance=0.5 * u.au), times)
    False
    >>> fast_path_applies(None, times)
    True
    """
    obstime = as_time(obstime)
    if not conf.fast_path or obstime.size == 0:
        return False
    if target is None:
        return True
    target = as_skycoord(target)
    if not isinstance(target.frame, FIXED_FRAMES) or target.data.differentials:
        return False
    if not _distance_less(target.data):
        distance = target.spherical.distance
        if distance.unit.physical_type != "length" or not np.all(
                np.abs(distance) >= FAST_PATH_MIN_DISTANCE):
            return False
    try:
        shape = np.broadcast_shapes(target.shape, obstime.shape)
    except ValueError:
        return False
    return target.size == 1 or int(np.prod(shape)) == target.size * obstime.size


def _distance_less(data):
    """Whether astropy treats coordinate data as a direction without distance."""
    return (isinstance(data, UnitSphericalRepresentation)
            or data.to_cartesian().x.unit == u.one)


#: How many sites `site_position` keeps.
SITE_CACHE_SIZE = 256

_SITES = collections.OrderedDict()
_SITES_LOCK = threading.Lock()


def site_position(location):
    """The ITRS position (m) of a site as astropy's transformations use it.

    Astropy hands ERFA's ``apco`` the site's WGS84 geodetic coordinates, and
    ERFA's ``pvtob`` turns them back into a position (``gd2gc``). The round
    trip costs 0.1 ms (astropy's geodetic representation), so each site's is
    computed once and kept (the last `SITE_CACHE_SIZE` sites, keyed on their
    coordinates).

    Parameters
    ----------
    location : `~astropy.coordinates.EarthLocation`
        A single site.

    Returns
    -------
    ndarray, shape (3,)

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from astropy_feedrot.earth import site_position
    >>> site = EarthLocation.from_geocentric(4075659.180, 931824.551, 4801516.102, u.m)
    >>> site_position(site)  # doctest: +FLOAT_CMP
    array([4075659.18 ,  931824.551, 4801516.102])
    """
    key = (np.asarray(location.value).tobytes(), str(location.unit))
    with _SITES_LOCK:
        site = _SITES.get(key)
    if site is None:
        lon, lat, height = location.to_geodetic("WGS84")
        site = erfa.gd2gc(1, lon.to_value(u.rad), lat.to_value(u.rad), height.to_value(u.m))
        site.flags.writeable = False
        with _SITES_LOCK:
            _SITES[key] = site
            while len(_SITES) > SITE_CACHE_SIZE:
                _SITES.popitem(last=False)
    return site


def _distinct(values, limit):
    """Distinct values of a float array of integers, and a function of each element's index.

    If the values span at most ``limit``, every integer of their range is
    taken (the index is then a subtraction); otherwise only those present.
    """
    low, high = values.min(), values.max()
    if high - low < limit:
        return np.arange(low, high + 1), lambda: (values - low).astype(np.intp)
    distinct, index = np.unique(values, return_inverse=True)
    return distinct, lambda: index.reshape(values.shape)


class _Days:
    """The UTC days of some epochs and the quantities linear within each day.

    Every epoch is a day number ``day`` (UTC midnights counted from ``ref``)
    and a fraction ``frac`` of that day. At the start of each day with epochs
    and of the next, astropy gives TT, UT1 and polar motion; between them they
    are linear (astropy interpolates the daily IERS values linearly in UTC,
    and ERFA spreads a leap second over its day), so the tables hold the value
    at the start of the day and the change over the day.
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
            self.days, self._slot = _distinct(day, max(day.size, 2))
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
        # spread over its day).
        days = self.days
        starts = np.union1d(days, days + 1)
        this, following = np.searchsorted(starts, days), np.searchsorted(starts, days + 1)
        tt1, tt2, ut11, ut12, xp, yp = utc_earth_orientation(
            self.ref1 + starts, np.full(starts.shape, self.ref2))
        # TT is counted in days from the start of the first day of the tables.
        self.tt1, self.tt2 = float(tt1[0]), float(tt2[0])
        self.tt0 = ((tt1 - self.tt1) + (tt2 - self.tt2))[this]
        self.tt_rate = _length(tt1, tt2, this, following)
        era = erfa.era00(ut11, ut12)
        self.era0 = era[this]
        self.era_rate = _ERA_RATE * _length(ut11, ut12, this, following)
        gmst = erfa.gmst82(ut11, ut12)
        self.gmst0 = gmst[this]
        # GMST turns by a little more than 2 pi in a day.
        self.gmst_rate = 2 * np.pi + np.mod(gmst[following] - gmst[this], 2 * np.pi)
        self.xp0, self.xp_rate = xp[this], xp[following] - xp[this]
        self.yp0, self.yp_rate = yp[this], yp[following] - yp[this]
        self.sp = erfa.sp00(tt1[this], tt2[this])

    def at(self, slot, frac):
        """The quantities at instants given by day slots and fractions of day."""
        return _Instants(self, slot, frac)


def _length(jd1, jd2, this, following):
    """Days from ``[this]`` to ``[following]`` of a two-part JD, to its precision."""
    return (jd1[following] - jd1[this]) + (jd2[following] - jd2[this])


class _Instants:
    """Instants within the days of a `_Days`, with their exact Earth orientation."""

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
        return _terrestrial(vectors, self.era + self.sp, self.xp, self.yp)

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
        velocity = _OMEGA * np.stack([-s * x - c * y, c * x - s * y, np.zeros_like(x)], axis=-1)
        return position, velocity


def _terrestrial(vectors, angle, xp, yp):
    """W(x_p, y_p) R_z(angle) applied to vectors (..., N, 3); W = R_x(-y_p) R_y(-x_p).

    Polar motion is below 1e-5 rad, so that cos = 1 - a**2 / 2 and sin = a
    are exact to 1e-17.
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


def _node_count(days, *grids):
    """About how many nodes of these grids a series of ``days`` days needs."""
    return sum(days / spacing + order for spacing, order in grids)


def _lagrange_weights(xi, offsets):
    """Weights (P, n) of the Lagrange polynomials through nodes at integer ``offsets``.

    The barycentric form for consecutive integers: w_k = b_k / (xi - o_k),
    normalized, with b_k = (-1)**k binomial(n - 1, k).
    """
    n = offsets.size
    b = np.array([(-1) ** k * math.comb(n - 1, k) for k in range(n)], dtype=float)
    distance = xi[:, np.newaxis] - offsets
    with np.errstate(divide="ignore", invalid="ignore"):
        weights = b / distance
        weights /= weights.sum(axis=1, keepdims=True)
    on_node = distance == 0
    rows = np.any(on_node, axis=1)
    if np.any(rows):
        weights[rows] = on_node[rows]
    return weights


def _combine(values, start, weights):
    """Sum of ``weights[:, k]`` times ``values[start + k]`` (values (M, ...) -> (P, ...))."""
    out = weights[:, 0, np.newaxis] * values[start]
    for k in range(1, weights.shape[1]):
        out += weights[:, k, np.newaxis] * values[start + k]
    return out


#: Nodes from which `_in_parallel` splits an ERFA evaluation between threads.
_PARALLEL_NODES = 64


def _in_parallel(evaluate, tt1, tt2):
    """``evaluate(tt1, tt2)`` on halves of the nodes in two threads, where there are many.

    pyerfa's functions release the GIL, so the nutation series and the
    ephemeris of long sparse series (a year of hourly epochs needs a few
    hundred nodes) take half the time on two cores.
    """
    if tt2.size < _PARALLEL_NODES:
        return evaluate(tt1, tt2)
    half = tt2.size // 2
    first = _helper_thread().submit(evaluate, tt1, tt2[:half])
    second = evaluate(tt1, tt2[half:])
    return np.concatenate([first.result(), second])


_HELPER = []
_HELPER_LOCK = threading.Lock()


def _helper_thread():
    """One worker thread, started on first use and kept (starting one costs ~2 ms)."""
    with _HELPER_LOCK:
        if not _HELPER:
            _HELPER.append(concurrent.futures.ThreadPoolExecutor(
                max_workers=1, thread_name_prefix="astropy_feedrot-erfa"))
        return _HELPER[0]


class _Series:
    """A slow quantity from ERFA on a grid of TT, interpolated to instants.

    ``evaluate(tt1, tt2)`` returns an (M, C) array at M instants of TT.
    Values at the grid nodes are kept, so that instants asked for later reuse
    the nodes already computed.
    """

    def __init__(self, evaluate, spacing, order, tt1, tt2):
        self.evaluate, self.spacing, self.order = evaluate, spacing, order
        self.tt1, self.tt2 = tt1, tt2
        self.offsets = np.arange(order) - (order // 2 - 1)
        self._nodes = {}

    def plan(self, tt):
        """Grid nodes (integers, sorted) needed by instants at ``tt``, or None.

        None when there are no more instants than the nodes they would need:
        ERFA is then evaluated at the instants themselves.
        """
        if tt.size <= self.order:
            return None
        needed = np.unique(np.unique(np.floor(tt / self.spacing))[:, np.newaxis]
                           + self.offsets)
        return None if tt.size <= needed.size else needed

    def at(self, tt):
        """The quantity at instants ``tt`` (days from the reference), shape (P, C).

        From ERFA at the instants, the Lagrange polynomial through the grid
        nodes around each instant, or, with many instants per interval of the
        grid, that polynomial reduced to a Chebyshev interpolant of degree
        `_PIECE_DEGREE` in each interval (below 1e-6 mas).
        """
        if tt.size <= self.order:  # fewer instants than the nodes of one interval
            return self.evaluate(self.tt1, self.tt2 + tt)
        x = tt / self.spacing
        j = np.floor(x)
        intervals, slot = np.unique(j, return_inverse=True)
        needed = np.unique(intervals[:, np.newaxis] + self.offsets)
        if tt.size <= needed.size:
            return self.evaluate(self.tt1, self.tt2 + tt)
        values = self.nodes(needed)
        # The nodes of a stencil are consecutive integers, hence consecutive in needed.
        first = np.searchsorted(needed, intervals + self.offsets[0])
        offsets = self.offsets.astype(float)
        if tt.size <= 2 * (_PIECE_DEGREE + 1) * intervals.size:
            return _combine(values, first[slot], _lagrange_weights(x - j, offsets))
        points, inverse = _chebyshev(_PIECE_DEGREE)
        weights = _lagrange_weights((points + 1) / 2, offsets)  # (K, order), every interval
        # The interpolant at the K Chebyshev points of each interval: (K, intervals, C).
        at_points = weights[:, 0, np.newaxis, np.newaxis] * values[first]
        for k in range(1, self.order):
            at_points += weights[:, k, np.newaxis, np.newaxis] * values[first + k]
        coefficients = _monomials(inverse, at_points)[:, np.newaxis]
        return _horner(coefficients, slot.reshape(-1), 2 * (x - j) - 1)[0]

    def nodes(self, needed):
        """Values at grid nodes ``needed`` (integers), computing those not yet known."""
        missing = [j for j in needed.tolist() if j not in self._nodes]
        if missing:
            tt = np.array(missing) * self.spacing
            for j, row in zip(missing, _in_parallel(self.evaluate, self.tt1, self.tt2 + tt)):
                self._nodes[j] = row
        return np.array([self._nodes[j] for j in needed.tolist()])


def _cip(tt1, tt2):
    """CIP X, Y and CIO locator s (IAU 2006/2000A, as astropy's ``get_cip``)."""
    x, y = erfa.bpn2xy(erfa.pnm06a(tt1, tt2))
    return np.stack([x, y, erfa.s06(tt1, tt2, x, y)], axis=-1)


def _ephemeris(tt1, tt2):
    """The Earth's heliocentric position, barycentric position and velocity (au, au/d).

    At TDB = TT + ERFA ``dtdb`` (geocentric), as astropy's ``Time.tdb`` for a
    time without location, from ERFA ``epv00``.
    """
    tdb2 = tt2 + erfa.dtdb(tt1, tt2, 0.0, 0.0, 0.0, 0.0) / _DAY
    heliocentric, barycentric = erfa.epv00(tt1, tdb2)
    return np.concatenate([heliocentric["p"], barycentric["p"], barycentric["v"]], axis=-1)


def _velocity(tt1, tt2):
    """The Earth's heliocentric position and barycentric velocity (au, au/d) at TDB = TT.

    Enough for sources without a distance: over the 1.7 ms of TDB - TT the
    velocity changes by 1e-5 m/s (7e-6 mas of aberration) and the
    heliocentric direction by 3e-10 rad.
    """
    heliocentric, barycentric = erfa.epv00(tt1, tt2)
    return np.concatenate([heliocentric["p"], barycentric["v"]], axis=-1)


def _chebyshev(degree):
    """Chebyshev points of the first kind in (-1, 1) and the monomial fit through them."""
    n = degree + 1
    points = np.cos(np.pi * (np.arange(n) + 0.5) / n)
    return points, np.linalg.inv(np.vander(points, n, increasing=True))


class EarthOrientation:
    """Earth orientation, apparent directions and the Sun at a set of epochs.

    The epochs object of the package: one instance serves every quantity at
    its epochs, each computed as often as it needs (see `astropy_feedrot.earth`).

    Parameters
    ----------
    obstime : `~astropy.time.Time`
        The epochs (any shape, any scale; UTC is the cheapest).
    step : `~astropy.units.Quantity`, optional
        Accepted for compatibility and checked, but no longer used: the
        spacing of the exact evaluations is chosen per quantity and by the
        density of the epochs.

    Raises
    ------
    TypeError
        If ``obstime`` is not a time (see `~astropy_feedrot.inputs.as_time`).
    ValueError
        If ``step`` is not positive.

    Notes
    -----
    Results are at the flattened epochs (``obstime.ravel()``): arrays of
    shape (..., N, 3) or (N,) with N = ``obstime.size``.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth import EarthOrientation
    >>> times = Time("2023-01-25T00:00") + np.arange(1000) * u.min
    >>> orientation = EarthOrientation(times)
    >>> orientation.nodes.size  # nodes of the nutation series, a day apart around the epochs
    16
    """

    def __init__(self, obstime, step=DEFAULT_STEP):
        obstime = as_time(obstime)
        if step is not None:
            step = u.Quantity(step, u.s).value
            if not step > 0:
                raise ValueError(f"step must be positive, got {step} s")
        self.obstime = obstime
        self.shape = obstime.shape
        self.size = obstime.size
        flat = obstime.ravel()
        if flat.masked:
            flat = flat.unmasked
        self._days = days = _Days(flat)
        self._sun_cip = _Series(_cip, *_CIP_GRID, days.tt1, days.tt2)
        self._cip = self._sun_cip
        self._velocity = _Series(_velocity, *_VELOCITY_GRID, days.tt1, days.tt2)
        if (self.size < _SPARSE * _node_count(days.days.size, _CIP_GRID)
                and _node_count(days.days.size, _SPARSE_CIP_GRID, _SPARSE_VELOCITY_GRID)
                < _node_count(days.days.size, _CIP_GRID, _VELOCITY_GRID)):
            self._cip = _Series(_cip, *_SPARSE_CIP_GRID, days.tt1, days.tt2)
            self._velocity = _Series(_velocity, *_SPARSE_VELOCITY_GRID, days.tt1, days.tt2)
        self._position = _Series(_ephemeris, *_POSITION_GRID, days.tt1, days.tt2)
        self._epochs = None

    # --- the epochs themselves ---------------------------------------------

    def _at_epochs(self):
        if self._epochs is None:
            self._epochs = self._days.at(self._days.slot, self._days.frac)
        return self._epochs

    @property
    def era(self):
        """ndarray: The Earth rotation angle (rad, in [0, 2 pi)) at each epoch (flattened)."""
        return np.mod(self._at_epochs().era, 2 * np.pi)

    @property
    def gmst82(self):
        """ndarray: Greenwich mean sidereal time (IAU 1982, rad), as used with TEME."""
        return np.mod(self._at_epochs().gmst82, 2 * np.pi)

    @property
    def nodes(self):
        """`~astropy.time.Time`: Instants (TT) at which slow quantities are evaluated exactly.

        Days of TT around the epochs (those at which ERFA's nutation series is
        evaluated for the Sun, and for sources unless the epochs are sparse),
        or the epochs themselves where they are fewer; `interpolate` takes
        values given there to the epochs.
        """
        tt = self._at_epochs().tt
        needed = self._sun_cip.plan(tt)
        offsets = tt if needed is None else needed * self._sun_cip.spacing
        return Time(self._days.tt1, self._days.tt2 + offsets, format="jd", scale="tt")

    def interpolate(self, node_values):
        """Interpolate values given at `nodes` to the epochs.

        Parameters
        ----------
        node_values : array-like, shape (..., K, C)
            Values at the K `nodes` of a quantity that changes over days.

        Returns
        -------
        ndarray, shape (..., N, C)
            At the flattened epochs: the Lagrange polynomial through 16 nodes
            a day apart (or the values themselves where the nodes are the
            epochs).

        Examples
        --------
        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot.earth import EarthOrientation
        >>> orientation = EarthOrientation(Time("2023-01-25") + np.arange(100) * u.hour)
        >>> days = (orientation.nodes - orientation.nodes[0]).jd
        >>> values = np.stack([days, days ** 2], axis=-1)  # a polynomial is reproduced
        >>> result = orientation.interpolate(values)
        >>> epochs = (orientation.obstime - orientation.nodes[0]).jd
        >>> bool(np.allclose(result, np.stack([epochs, epochs ** 2], axis=-1), atol=1e-11))
        True
        """
        node_values = np.asarray(node_values, dtype=float)
        series = self._sun_cip
        tt = self._at_epochs().tt
        needed = series.plan(tt)
        if needed is None:
            return node_values.copy()
        x = tt / series.spacing
        j = np.floor(x)
        start = np.searchsorted(needed, j + series.offsets[0])
        weights = _lagrange_weights(x - j, series.offsets.astype(float))
        return np.moveaxis(_combine(np.moveaxis(node_values, -2, 0), start,
                                    weights[(...,) + (np.newaxis,) * (node_values.ndim - 2)]),
                           0, -2)

    # --- rotations at each epoch -------------------------------------------

    def cirs_to_itrs(self, vectors):
        """Rotate CIRS vectors to ITRS at each epoch.

        Parameters
        ----------
        vectors : array-like, shape (..., N, 3)
            Vectors whose second-last axis runs over the flattened epochs.

        Returns
        -------
        ndarray, shape (..., N, 3)
            W(x_p, y_p, s') R_z(ERA) applied to each, as astropy's
            ``cirs_to_itrs_mat``.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot.earth import EarthOrientation
        >>> orientation = EarthOrientation(Time(["2023-01-25T00:00", "2023-01-25T06:00"]))
        >>> z = orientation.cirs_to_itrs([[0, 0, 1.0], [0, 0, 1.0]])  # the CIP
        >>> bool(np.allclose(z, [0, 0, 1], atol=1e-5))  # polar motion: below 1 arcsec
        True
        """
        return self._at_epochs().to_itrs(vectors)

    def teme_to_itrs(self, vectors):
        """Rotate TEME vectors (SGP4 output) to ITRS at each epoch.

        Parameters
        ----------
        vectors : array-like, shape (..., N, 3)
            Vectors whose second-last axis runs over the flattened epochs.

        Returns
        -------
        ndarray, shape (..., N, 3)
            W(x_p, y_p, 0) R_z(GMST82) applied to each, as astropy's
            ``teme_to_itrs_mat``.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot.earth import EarthOrientation
        >>> orientation = EarthOrientation(Time(["2023-01-25T00:00"]))
        >>> float(np.linalg.norm(orientation.teme_to_itrs([[7000.0, 0, 0]])))  # doctest: +FLOAT_CMP
        7000.0
        """
        epochs = self._at_epochs()
        return _terrestrial(vectors, epochs.gmst82, epochs.xp, epochs.yp)

    # --- directions and the Sun at each epoch ------------------------------

    def source_directions(self, target, location):
        """Apparent topocentric ITRS directions of fixed celestial sources.

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord`
            Directions fixed in a celestial frame (shape S), with or without
            distance.
        location : `~astropy.coordinates.EarthLocation`
            The site (a single one).

        Returns
        -------
        ndarray, shape S + (N, 3)
            Unit vectors at the flattened epochs: astropy's
            ``target.transform_to(ITRS(obstime=..., location=location))``
            (aberration with the site's velocity, light deflection by the
            Sun, precession-nutation, UT1 and polar motion), to about
            0.001 mas.

        Raises
        ------
        ValueError
            If ``location`` holds more than one site.

        Examples
        --------
        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.coordinates import EarthLocation, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot.earth import EarthOrientation
        >>> site = EarthLocation.from_geodetic(6.88 * u.deg, 50.52 * u.deg, 416 * u.m)
        >>> times = Time("2023-01-25T00:00") + np.arange(100) * u.min
        >>> s = EarthOrientation(times).source_directions(SkyCoord("03h19m48s +41d30m42s"), site)
        >>> s.shape
        (100, 3)
        """
        target = as_skycoord(target)
        location = as_location(location)
        if not location.isscalar:
            raise ValueError(f"location must be a single site, got shape {location.shape}")
        icrs = target if isinstance(target.frame, ICRS) else target.icrs
        shape = icrs.shape
        data = icrs.data.without_differentials()
        unit_vectors = data.represent_as(UnitSphericalRepresentation)
        pco = erfa.s2c(unit_vectors.lon.to_value(u.rad), unit_vectors.lat.to_value(u.rad))
        pco = pco.reshape(-1, 3)
        distance = None
        if not _distance_less(data):
            distance = icrs.spherical.distance.to_value(u.au).reshape(-1)
        site = site_position(location)

        def evaluate(instants):
            return self._directions_at(instants, pco, distance, site)

        with np.errstate(invalid="ignore"):
            s = self._per_epoch(evaluate, pco.shape[0])
            # The polynomials of the cells keep the length to about 1e-13.
            s /= np.sqrt(np.einsum("...i,...i->...", s, s))[..., np.newaxis]
        return s.reshape(shape + (self.size, 3))

    def sun_position(self):
        """Geocentric ITRS position of the Sun at each epoch, in metres.

        Returns
        -------
        ndarray, shape (N, 3)
            At the flattened epochs, as `astropy_feedrot.attitude.sun_position`
            (ERFA ``epv00`` in GCRS, rotated to ITRS) to about 2e-13 rad.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot.earth import EarthOrientation
        >>> sun = EarthOrientation(Time("2023-01-25")).sun_position()
        >>> round(float(np.linalg.norm(sun) / 1.495978707e11), 3)  # au
        0.984
        """
        return self._per_epoch(self._sun_at, 1)[0]

    def _sun_at(self, instants):
        x, y, s = self._sun_cip.at(instants.tt).T
        sun = -self._position.at(instants.tt)[:, 0:3] * _AU
        return instants.to_itrs(erfa.rxp(erfa.c2ixys(x, y, s), sun))[np.newaxis]

    def _directions_at(self, instants, pco, distance, site):
        """Astropy's ICRS -> ITRS(location) at instants (ERFA apco and astropy's atciqz).

        ``pco`` are the (S, 3) ICRS unit vectors, ``distance`` their distances
        in au or None, ``site`` the ITRS position of the site in metres.
        """
        x, y, s = self._cip.at(instants.tt).T
        bpn = erfa.c2ixys(x, y, s)
        position, velocity = instants.site(site)
        # The site in GCRS, in au and in au/day (ERFA apco, apcs).
        dp = erfa.trxp(bpn, position) / _AU
        dv = erfa.trxp(bpn, velocity) / _AU_PER_DAY
        if distance is None:
            ephemeris = self._velocity.at(instants.tt)
            heliocentric, barycentric_v = ephemeris[:, 0:3], ephemeris[:, 3:6]
        else:
            ephemeris = self._position.at(instants.tt)
            heliocentric, barycentric_v = ephemeris[:, 0:3], ephemeris[:, 6:9]
        em, eh = erfa.pn(heliocentric + dp)
        v = (barycentric_v + dv) * _C_AU_PER_DAY
        bm1 = np.sqrt(1.0 - np.einsum("...i,...i->...", v, v))
        if distance is None:
            p = q = pco[:, np.newaxis, :]
        else:  # astropy's atciqz: parallax first, then deflection from the Sun
            eb = ephemeris[:, 3:6] + dp
            r, p = erfa.pn(distance[:, np.newaxis, np.newaxis] * pco[:, np.newaxis, :] - eb)
            sun_distance, q = erfa.pn(em[:, np.newaxis] * eh + r[..., np.newaxis] * p)
            q = np.where(sun_distance[..., np.newaxis] > 1e-10, q, p)
        natural = erfa.ld(1.0, p, q, eh, em, 1e-6)
        proper = erfa.ab(natural, v, em, bm1)
        return instants.to_itrs(erfa.rxp(bpn, proper))

    def _per_epoch(self, evaluate, count):
        """``evaluate`` (instants -> (count, P, 3)) at every epoch, through cells where they pay."""
        days = self._days
        choice = self._choose_cells()
        if choice is None:
            return evaluate(self._at_epochs())
        per_day, degree = choice
        scaled = days.frac * per_day
        within = np.floor(scaled)
        x = scaled - within
        x *= 2
        x -= 1
        cells, slot = _distinct(days.day * per_day + within, 2 * self.size)
        slot = slot()
        counts = np.bincount(slot, minlength=cells.size)
        # A cell pays when its epochs outnumber its points (with the Horner margin).
        full = counts * (1 - _horner_cost(degree)) > degree + 1
        coefficients = np.zeros((degree + 1, count, cells.size, 3))
        if np.any(full):
            coefficients[:, :, full] = self._cell_polynomials(evaluate, count, cells[full],
                                                              per_day, degree)
        out = _horner(coefficients, slot, x)
        if not np.all(full[counts > 0]):
            rest = np.flatnonzero(~full[slot])
            out[:, rest] = evaluate(days.at(days.slot[rest], days.frac[rest]))
        return out

    def _choose_cells(self):
        """The cells (per day, degree) that cost least, or None for the epochs themselves."""
        days = self._days
        n = self.size
        if n < 2:
            return None
        span = float(days.u.max() - days.u.min())
        best, best_cost = None, float(n)
        for per_day, degree in _CELLS:
            occupied = min(n, np.ceil(span * per_day) + 1)
            cost = occupied * (degree + 1) + n * _horner_cost(degree)
            if cost < best_cost:
                best, best_cost = (per_day, degree), cost
        return best

    def _cell_polynomials(self, evaluate, count, cells, per_day, degree):
        """Monomial coefficients (degree + 1, count, cells, 3) of each cell's polynomial."""
        days = self._days
        points, inverse = _chebyshev(degree)
        day = np.floor(cells / per_day)
        within = cells - day * per_day
        frac = (within[:, np.newaxis] + (points + 1) / 2) / per_day
        instants = days.at(np.repeat(days.slot_of(day), points.size), frac.ravel())
        values = evaluate(instants).reshape(count, cells.size, points.size, 3)
        return _monomials(inverse, np.moveaxis(values, 2, 0))


def _monomials(inverse, values):
    """Monomial coefficients (K, ...) from values (K, ...) at the Chebyshev points.

    ``inverse`` is the inverse Vandermonde matrix of `_chebyshev`; the sums run
    element by element (not through BLAS), so that each coefficient is the same
    whatever else is computed with it.
    """
    out = inverse[:, 0].reshape((-1,) + (1,) * (values.ndim - 1)) * values[0]
    for j in range(1, values.shape[0]):
        out += inverse[:, j].reshape((-1,) + (1,) * (values.ndim - 1)) * values[j]
    return out


def _horner_cost(degree):
    """Cost of a polynomial of ``degree`` at an epoch, in exact evaluations at an instant."""
    return _HORNER_BASE + _HORNER_PER_DEGREE * degree


def _horner(coefficients, slot, x):
    """Evaluate each epoch's cell polynomial: coefficients (m + 1, S, cells, 3) -> (S, N, 3)."""
    x = x[:, np.newaxis]
    out = np.take(coefficients[-1], slot, axis=1)
    for k in range(coefficients.shape[0] - 2, -1, -1):
        out *= x
        out += np.take(coefficients[k], slot, axis=1)
    return out


#: How many `EarthOrientation` objects `orientation_of` keeps.
ORIENTATION_CACHE_SIZE = 4

_ORIENTATIONS = collections.OrderedDict()
_ORIENTATIONS_LOCK = threading.Lock()


def orientation_of(obstime):
    """The `EarthOrientation` of these epochs, shared by every computation at them.

    Several antennas observing at the same epochs (`~astropy_feedrot.Antenna`
    methods called one antenna at a time, tables of baselines) need the same
    Earth orientation and the same Sun. The last `ORIENTATION_CACHE_SIZE`
    of them are kept, keyed on the epochs' values, scale and shape and on the
    IERS table in use, so that the first computation builds it and the others
    reuse it.

    Parameters
    ----------
    obstime : `~astropy.time.Time`
        The epochs (unmasked; a masked Time is built anew, never cached).

    Returns
    -------
    EarthOrientation

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth import orientation_of
    >>> times = Time("2023-01-25") + np.arange(100) * u.min
    >>> orientation_of(times) is orientation_of(times.copy())  # the same epochs
    True
    """
    obstime = as_time(obstime)
    if obstime.masked:
        return EarthOrientation(obstime)
    table = iers.earth_orientation_table.get()
    digest = hashlib.blake2b(np.ascontiguousarray(obstime.jd1, dtype=float).tobytes())
    digest.update(np.ascontiguousarray(obstime.jd2, dtype=float).tobytes())
    key = (obstime.scale, obstime.shape, digest.digest(), id(table))
    with _ORIENTATIONS_LOCK:
        hit = _ORIENTATIONS.get(key)
        if hit is not None and hit[0] is table:  # the entry keeps its table alive
            _ORIENTATIONS.move_to_end(key)
    if hit is not None and hit[0] is table:
        with iers_context(obstime):  # the same check of the tables as a new one makes
            return hit[1]
    orientation = EarthOrientation(obstime)
    with _ORIENTATIONS_LOCK:
        _ORIENTATIONS[key] = (table, orientation)
        while len(_ORIENTATIONS) > ORIENTATION_CACHE_SIZE:
            _ORIENTATIONS.popitem(last=False)
    return orientation


def clear_orientation_cache():
    """Forget the Earth orientations `orientation_of` keeps.

    For timing a computation from nothing (the benchmarks), or to free their
    memory.

    Examples
    --------
    >>> from astropy_feedrot.earth import clear_orientation_cache
    >>> clear_orientation_cache()
    """
    with _ORIENTATIONS_LOCK:
        _ORIENTATIONS.clear()
