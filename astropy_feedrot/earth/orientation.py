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
* X, Y and s, the Earth's velocity and its positions come from ERFA at
  whole days of TT through Lagrange polynomials of 16, 10 and 14 nodes
  (below 1e-13 rad and 5e-5 m/s); the nodes are computed a year at a time
  and kept, in memory and in astropy's cache directory
  (`~astropy_feedrot.earth.nodes.KeptSeries`), so that sparse epochs cost an
  interpolation each and later computations and processes reuse them;
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

import hashlib

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

from ..core.cache import KeptLast
from ..core.config import conf
from ..core.inputs import as_location, as_skycoord, as_time
from ..core.kernel import over_components
from .eop import iers_context, table_in_use
from .nodes import KeptSeries, Series, chebyshev, combine, horner, lagrange_weights, monomials
from .utc_days import UtcDays, distinct, terrestrial

__all__ = [
    "EarthOrientation",
    "orientation_of",
    "clear_orientation_cache",
    "fast_path_applies",
    "site_position",
    "distance_less",
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
# Metres per second in au per day, and au per day in units of c (ERFA apcs).
_AU_PER_DAY = erfa.DAU / _DAY
_C_AU_PER_DAY = erfa.DAU / erfa.CMPS / _DAY
_AU = erfa.DAU  # metres

# Slow series: (node spacing in days of TT, number of nodes per Lagrange polynomial).
# X, Y, s: 16 nodes a day apart interpolate the nutation's 5- to 14-day terms to
# 0.00002 mas (1e-13 rad). The ephemeris: 10 nodes a day apart give the Earth's
# velocity to 5e-5 m/s (0.00003 mas of aberration), enough for sources without a
# distance; 14 nodes a day apart give the positions to 1 cm, for the Sun (1e-13 rad)
# and the parallax of sources with a distance.
_CIP_GRID = (1.0, 16)
_VELOCITY_GRID = (1.0, 10)
_POSITION_GRID = (1.0, 14)

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
        `~astropy_feedrot.core.inputs.as_time` and
        `~astropy_feedrot.core.inputs.as_skycoord`).

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.orientation import fast_path_applies
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
    if not distance_less(target.data):
        distance = target.spherical.distance
        if distance.unit.physical_type != "length" or not np.all(
                np.abs(distance) >= FAST_PATH_MIN_DISTANCE):
            return False
    try:
        shape = np.broadcast_shapes(target.shape, obstime.shape)
    except ValueError:
        return False
    return target.size == 1 or int(np.prod(shape)) == target.size * obstime.size


def distance_less(data):
    """Whether astropy treats coordinate data as a direction without distance.

    Parameters
    ----------
    data : `~astropy.coordinates.BaseRepresentation`
        The data of a coordinate (``coord.data``).

    Returns
    -------
    bool

    Examples
    --------
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy_feedrot.earth.orientation import distance_less
    >>> distance_less(SkyCoord("03h19m48s +41d30m42s").data)
    True
    """
    return (isinstance(data, UnitSphericalRepresentation)
            or data.to_cartesian().x.unit == u.one)


#: How many sites `site_position` keeps.
SITE_CACHE_SIZE = 256

_SITES = KeptLast(SITE_CACHE_SIZE)


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
    >>> from astropy_feedrot.earth.orientation import site_position
    >>> site = EarthLocation.from_geocentric(4075659.180, 931824.551, 4801516.102, u.m)
    >>> site_position(site)  # doctest: +FLOAT_CMP
    array([4075659.18 ,  931824.551, 4801516.102])
    """
    key = (np.asarray(location.value).tobytes(), str(location.unit))
    site = _SITES.get(key)
    if site is None:
        lon, lat, height = location.to_geodetic("WGS84")
        site = erfa.gd2gc(1, lon.to_value(u.rad), lat.to_value(u.rad), height.to_value(u.m))
        site.flags.writeable = False
        _SITES.put(key, site)
    return site


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


class EarthOrientation:
    """Earth orientation, apparent directions and the Sun at a set of epochs.

    The epochs object of the package: one instance serves every quantity at
    its epochs, each computed as often as it needs (see `astropy_feedrot.earth.orientation`).

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
        If ``obstime`` is not a time (see `~astropy_feedrot.core.inputs.as_time`).
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
    >>> from astropy_feedrot.earth.orientation import EarthOrientation
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
        self._days = days = UtcDays(obstime.unmasked if obstime.masked else obstime)
        # The nodes of `nodes` and `interpolate`, a day apart around the epochs.
        self._sun_cip = Series(_cip, *_CIP_GRID, days.tt1, days.tt2)
        # The slow series themselves: whole days of TT, kept between computations
        # (and processes), or over the span of the epochs when it is short.
        self._cip = KeptSeries("cip", _cip, _CIP_GRID[1], days.tt1, days.tt2)
        self._velocity = KeptSeries("velocity", _velocity, _VELOCITY_GRID[1], days.tt1,
                                    days.tt2)
        self._position = KeptSeries("ephemeris", _ephemeris, _POSITION_GRID[1], days.tt1,
                                    days.tt2)
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
        >>> from astropy_feedrot.earth.orientation import EarthOrientation
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
        weights = lagrange_weights(x - j, series.offsets.astype(float))
        return np.moveaxis(combine(np.moveaxis(node_values, -2, 0), start,
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
        >>> from astropy_feedrot.earth.orientation import EarthOrientation
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
        >>> from astropy_feedrot.earth.orientation import EarthOrientation
        >>> orientation = EarthOrientation(Time(["2023-01-25T00:00"]))
        >>> float(np.linalg.norm(orientation.teme_to_itrs([[7000.0, 0, 0]])))  # doctest: +FLOAT_CMP
        7000.0
        """
        epochs = self._at_epochs()
        return terrestrial(vectors, epochs.gmst82, epochs.xp, epochs.yp)

    # --- directions and the Sun at each epoch ------------------------------

    def source_directions(self, target, location):
        """Apparent topocentric ITRS directions of fixed celestial sources.

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord`
            Directions fixed in a celestial frame (shape S), with or without
            distance.
        location : `~astropy.coordinates.EarthLocation` or None
            The site (a single one), or None for the geocentre (the
            directions a network shares; `~astropy_feedrot.engine.grid_natural`
            adds each site's diurnal aberration).

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
        >>> from astropy_feedrot.earth.orientation import EarthOrientation
        >>> site = EarthLocation.from_geodetic(6.88 * u.deg, 50.52 * u.deg, 416 * u.m)
        >>> times = Time("2023-01-25T00:00") + np.arange(100) * u.min
        >>> s = EarthOrientation(times).source_directions(SkyCoord("03h19m48s +41d30m42s"), site)
        >>> s.shape
        (100, 3)
        """
        target = as_skycoord(target)
        location = None if location is None else as_location(location)
        if location is not None and not location.isscalar:
            raise ValueError(f"location must be a single site, got shape {location.shape}")
        icrs = target if isinstance(target.frame, ICRS) else target.icrs
        shape = icrs.shape
        data = icrs.data.without_differentials()
        unit_vectors = data.represent_as(UnitSphericalRepresentation)
        pco = erfa.s2c(unit_vectors.lon.to_value(u.rad), unit_vectors.lat.to_value(u.rad))
        pco = pco.reshape(-1, 3)
        distance = None
        if not distance_less(data):
            distance = icrs.spherical.distance.to_value(u.au).reshape(-1)
        site = np.zeros(3) if location is None else site_position(location)

        def evaluate(instants):
            return self._directions_at(instants, pco, distance, site)

        with np.errstate(invalid="ignore"):
            s = self._per_epoch(evaluate, pco.shape[0])
            # The polynomials of the cells keep the length to about 1e-13.
            s /= over_components(np.sqrt(np.einsum("...i,...i->...", s, s)))
        return s.reshape(shape + (self.size, 3))

    def sun_position(self):
        """Geocentric ITRS position of the Sun at each epoch, in metres.

        Returns
        -------
        ndarray, shape (N, 3)
            At the flattened epochs, as `astropy_feedrot.transmitters.nominal_attitude.sun_position`
            (ERFA ``epv00`` in GCRS, rotated to ITRS) to about 2e-13 rad.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot.earth.orientation import EarthOrientation
        >>> sun = EarthOrientation(Time("2023-01-25")).sun_position()
        >>> round(float(np.linalg.norm(sun) / 1.495978707e11), 3)  # au
        0.984
        """
        return self._per_epoch(self._sun_at, 1)[0]

    def geocentre_velocity(self):
        """Barycentric velocity of the geocentre in ITRS, in units of c, at each epoch.

        Returns
        -------
        ndarray, shape (N, 3)
            ERFA ``epv00`` (the velocity of the annual aberration) rotated to
            ITRS, at the flattened epochs.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot.earth.orientation import EarthOrientation
        >>> v = EarthOrientation(Time("2023-01-25")).geocentre_velocity()
        >>> round(float(np.linalg.norm(v)) * 299792.458, 1)  # km/s
        30.3
        """
        return self._per_epoch(self._velocity_at, 1)[0]

    def _velocity_at(self, instants):
        x, y, s = self._cip.at(instants.tt).T
        v = self._velocity.at(instants.tt)[:, 3:6] * _C_AU_PER_DAY
        return instants.to_itrs(erfa.rxp(erfa.c2ixys(x, y, s), v))[np.newaxis]

    def _sun_at(self, instants):
        x, y, s = self._cip.at(instants.tt).T
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
        cells, slot = distinct(days.day * per_day + within, 2 * self.size)
        slot = slot()
        counts = np.bincount(slot, minlength=cells.size)
        # A cell pays when its epochs outnumber its points (with the Horner margin).
        full = counts * (1 - _horner_cost(degree)) > degree + 1
        coefficients = np.zeros((degree + 1, count, cells.size, 3))
        if np.any(full):
            coefficients[:, :, full] = self._cell_polynomials(evaluate, count, cells[full],
                                                              per_day, degree)
        out = horner(coefficients, slot, x)
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
        points, inverse = chebyshev(degree)
        day = np.floor(cells / per_day)
        within = cells - day * per_day
        frac = (within[:, np.newaxis] + (points + 1) / 2) / per_day
        instants = days.at(np.repeat(days.slot_of(day), points.size), frac.ravel())
        values = evaluate(instants).reshape(count, cells.size, points.size, 3)
        return monomials(inverse, np.moveaxis(values, 2, 0))


def _horner_cost(degree):
    """Cost of a polynomial of ``degree`` at an epoch, in exact evaluations at an instant."""
    return _HORNER_BASE + _HORNER_PER_DEGREE * degree


#: How many `EarthOrientation` objects `orientation_of` keeps.
ORIENTATION_CACHE_SIZE = 4

_ORIENTATIONS = KeptLast(ORIENTATION_CACHE_SIZE)


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
    >>> from astropy_feedrot.earth.orientation import orientation_of
    >>> times = Time("2023-01-25") + np.arange(100) * u.min
    >>> orientation_of(times) is orientation_of(times.copy())  # the same epochs
    True
    """
    obstime = as_time(obstime)
    if obstime.masked:
        return EarthOrientation(obstime)
    table = table_in_use()  # None: the bundled tables, not yet loaded by astropy
    # SHA-256 of the arrays as they lie (no copy): the CPU's SHA instructions make it
    # twice as fast as BLAKE2b here, a few ms for a million epochs.
    digest = hashlib.sha256(memoryview(np.ascontiguousarray(obstime.jd1, dtype=float)))
    digest.update(memoryview(np.ascontiguousarray(obstime.jd2, dtype=float)))
    key = (obstime.scale, obstime.shape, digest.digest(), id(table))
    hit = _ORIENTATIONS.get(key, tag=table)  # the entry keeps its table alive
    if hit is not None:
        with iers_context(obstime):  # the same check of the tables as a new one makes
            return hit
    return _ORIENTATIONS.put(key, EarthOrientation(obstime), tag=table)


def clear_orientation_cache():
    """Forget the Earth orientations `orientation_of` keeps.

    For timing a computation from nothing but the tables every process has
    after its first call (the benchmarks), or to free their memory. The
    nodes of the slow series (`~astropy_feedrot.earth.nodes.clear_kept_nodes`),
    the IERS arrays and the sites' positions stay: they depend on nothing
    but the day, the tables and the site.

    Examples
    --------
    >>> from astropy_feedrot.earth.orientation import clear_orientation_cache
    >>> clear_orientation_cache()
    """
    _ORIENTATIONS.clear()
