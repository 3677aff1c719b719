# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Satellite orbits: Earth-fixed (ITRS) positions at any time.

Three sources of positions: a two-line element set propagated with SGP4
(`TLEOrbit`), an IGS SP3 precise-orbit file interpolated with sliding-window
Lagrange polynomials (`SP3Orbit`), and positions the user already has as a
`~astropy.coordinates.SkyCoord` (`CoordinateOrbit`).

Every orbit gives its positions one orbit at a time (`Orbit.position`) or many
orbits together (`Orbit.positions`: one SGP4 call for all element sets); both
take an optional `~astropy_feedrot.earth.EarthOrientation` of the epochs, so
that several consumers of the same epochs share one.
"""

import datetime
import warnings

import numpy as np
from astropy import units as u
from erfa import ErfaWarning
from astropy.coordinates import ITRS, TEME, CartesianRepresentation, SkyCoord
from astropy.time import Time

from .config import conf
from .earth import EarthOrientation, fast_path_applies, orientation_of
from .eop import iers_context
from .exceptions import OrbitWarning, warn_caller
from .frames import as_time, location_xyz
from .io import SP3Data, read_sp3
from .io.tle import check_tle_pair
from .propagation import SGP4_MISSING, propagate

__all__ = ["Orbit", "TLEOrbit", "SP3Orbit", "CoordinateOrbit", "as_orbit", "propagate_tles",
           "check_orientation"]

# WGS72 constants used by SGP4 (Vallado and Crawford 2008).
_WGS72_MU = 398600.8  # km^3 / s^2
_WGS72_RADIUS = 6378.135  # km


class Orbit:
    """Base class of orbits: Earth-fixed positions as a function of time.

    A subclass implements `position`. Orbits that are cheaper computed
    together (element sets: one SGP4 call) also implement the class method
    `batch_positions`, which `positions` calls once per class with all the
    orbits of that class.

    Attributes
    ----------
    uses_orientation : bool
        Whether `position` uses an `~astropy_feedrot.earth.EarthOrientation`
        when given one (class attribute: False here, True for `TLEOrbit`).
        Callers build one for their epochs only when some orbit (or attitude)
        will use it.
    coverage : tuple of `~astropy.time.Time` or None
        ``(start, stop)`` outside which `position` cannot give positions (an
        orbit file's span); None (here) where there is no such limit.

    Examples
    --------
    >>> from astropy_feedrot import CoordinateOrbit, SP3Orbit, TLEOrbit
    >>> from astropy_feedrot.orbits import Orbit
    >>> all(issubclass(c, Orbit) for c in (TLEOrbit, SP3Orbit, CoordinateOrbit))
    True
    >>> TLEOrbit.uses_orientation, CoordinateOrbit.coverage
    (True, None)
    """

    uses_orientation = False
    coverage = None

    def position(self, obstime, orientation=None):
        """Geocentric ITRS position(s), in metres.

        Parameters
        ----------
        obstime : `~astropy.time.Time`
            Epoch(s).
        orientation : `~astropy_feedrot.earth.EarthOrientation`, optional
            Earth orientation at exactly these epochs (same shape), shared
            with other computations at the same epochs; orbits that need no
            Earth rotation ignore it. By default the orbit makes its own when
            it needs one.

        Returns
        -------
        ndarray, shape obstime.shape + (3,)
            Cartesian ITRS coordinates in metres; NaN where the orbit cannot
            give a position.

        Examples
        --------
        GPS SVN 76 (the paper's Table 2) is some 26,600 km from the geocentre:

        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import TLEOrbit
        >>> from astropy_feedrot.simulations import GPS_SVN76_TLE
        >>> xyz = TLEOrbit(*GPS_SVN76_TLE).position(Time("2023-01-25T12:00") + [0, 1] * u.h)
        >>> xyz.shape, bool(np.all(np.abs(np.linalg.norm(xyz, axis=-1) - 2.66e7) < 2e5))
        ((2, 3), True)
        """
        raise NotImplementedError  # pragma: no cover

    @classmethod
    def batch_positions(cls, orbits, obstime, orientation=None):
        """Positions of several orbits of this class at the same epochs.

        The default calls `position` for each orbit; a class whose orbits are
        cheaper together overrides it.

        Parameters
        ----------
        orbits : list of `Orbit`
            Orbits of this class.
        obstime : `~astropy.time.Time`
            Epochs, any shape.
        orientation : `~astropy_feedrot.earth.EarthOrientation`, optional
            As for `position`.

        Returns
        -------
        ndarray, shape (len(orbits),) + obstime.shape + (3,)
            ITRS metres.

        Raises
        ------
        ValueError
            If an orbit does not give one position per epoch.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import ITRS, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import CoordinateOrbit
        >>> here = CoordinateOrbit(SkyCoord(ITRS(x=2.6e7 * u.m, y=0 * u.m, z=0 * u.m,
        ...                                      representation_type="cartesian")))
        >>> times = Time("2023-01-25") + [0, 1] * u.hour
        >>> CoordinateOrbit.batch_positions([here, here], times).shape
        (2, 2, 3)
        """
        out = np.empty((len(orbits),) + obstime.shape + (3,))
        for i, orbit in enumerate(orbits):
            xyz = np.asarray(orbit.position(obstime, orientation), dtype=float)
            if xyz.shape != obstime.shape + (3,):
                raise ValueError(
                    f"{orbit!r} gives positions of shape {xyz.shape} for obstime of shape "
                    f"{obstime.shape}; a batch of orbits needs one position per epoch")
            out[i] = xyz
        return out

    @staticmethod
    def positions(orbits, obstime, orientation=None):
        """Positions of many orbits at the same epochs, each class in one batch.

        Parameters
        ----------
        orbits : sequence of `Orbit`
            Orbits of any classes: element sets are propagated together (one
            SGP4 call), the others one by one.
        obstime : `~astropy.time.Time`
            Epochs, any shape.
        orientation : `~astropy_feedrot.earth.EarthOrientation`, optional
            Earth orientation at exactly these epochs, shared by every orbit
            that needs one (element sets: the rotation from TEME to ITRS). By
            default each class makes its own when it needs one.

        Returns
        -------
        ndarray, shape (len(orbits),) + obstime.shape + (3,)
            Geocentric ITRS positions in metres; NaN where an orbit cannot
            give one (with that orbit's warning, once per class).

        Raises
        ------
        TypeError
            If an item is not an `Orbit`.
        ValueError
            If ``orientation`` is not for these epochs, or an orbit does not
            give one position per epoch (a `CoordinateOrbit` of several
            positions at one time, for instance).

        Examples
        --------
        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import TLEOrbit
        >>> from astropy_feedrot.orbits import Orbit
        >>> from astropy_feedrot.simulations import GPS_SVN76_TLE
        >>> gps = TLEOrbit(*GPS_SVN76_TLE)
        >>> genesis = TLEOrbit.from_elements(Time("2023-01-25"), inclination=97 * u.deg,
        ...                                  raan=30 * u.deg, altitude=6000 * u.km)
        >>> times = Time("2023-01-25") + np.arange(0, 3600, 60) * u.s
        >>> xyz = Orbit.positions([gps, genesis], times)
        >>> xyz.shape
        (2, 60, 3)
        >>> np.round(np.linalg.norm(xyz[:, 0], axis=-1) / 1e6, 1)  # thousands of km
        array([26.7, 12.4])
        """
        orbits = list(orbits)
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        kinds = {}
        for i, orbit in enumerate(orbits):
            if not isinstance(orbit, Orbit):
                raise TypeError(f"orbits[{i}] must be an Orbit, got {type(orbit).__name__}")
            kinds.setdefault(type(orbit), []).append(i)
        shape = (len(orbits),) + obstime.shape + (3,)
        if len(kinds) == 1:  # one class: its batch is the answer, without a copy
            (kind,) = kinds
            out = np.asarray(kind.batch_positions(orbits, obstime, orientation), dtype=float)
            if out.shape != shape:
                raise ValueError(f"{kind.__name__}.batch_positions gives shape {out.shape} "
                                 f"for {len(orbits)} orbits at epochs of shape "
                                 f"{obstime.shape}; it must give {shape}")
            return out
        out = np.empty(shape)
        for kind, members in kinds.items():
            out[members] = kind.batch_positions([orbits[i] for i in members], obstime,
                                                orientation)
        return out


def check_orientation(orientation, obstime):
    """Check that an Earth orientation is one for the given epochs.

    Parameters
    ----------
    orientation : `~astropy_feedrot.earth.EarthOrientation` or None
        None passes.
    obstime : `~astropy.time.Time`
        The epochs it must describe.

    Raises
    ------
    TypeError
        If ``orientation`` is neither None nor an
        `~astropy_feedrot.earth.EarthOrientation`.
    ValueError
        If its epochs have another shape than ``obstime``.

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth import EarthOrientation
    >>> from astropy_feedrot.orbits import check_orientation
    >>> times = Time(["2023-01-25T00:00", "2023-01-25T06:00"])
    >>> check_orientation(EarthOrientation(times), times)
    """
    if orientation is None:
        return
    if not isinstance(orientation, EarthOrientation):
        raise TypeError(f"orientation must be an EarthOrientation or None, got "
                        f"{type(orientation).__name__}")
    if orientation.shape != obstime.shape:
        raise ValueError(f"orientation is for epochs of shape {orientation.shape}, obstime has "
                         f"shape {obstime.shape}: build the EarthOrientation from these epochs")


def _sgp4():
    """The sgp4 package's ``api`` module (an optional dependency, imported when first needed)."""
    try:
        from sgp4 import api
    except ImportError:  # exercised by tests/test_cli_extras.py, without sgp4
        raise ImportError(SGP4_MISSING) from None
    return api


def teme_to_itrs(position, obstime, orientation=None):
    """Rotate TEME positions (SGP4's frame) to geocentric ITRS.

    With an ``orientation``, or where the fast path applies
    (`~astropy_feedrot.earth.fast_path_applies`), the rotation is computed
    once per epoch from interpolated Earth orientation
    (`~astropy_feedrot.earth.EarthOrientation`: GMST 1982 from UT1 and polar
    motion, as astropy's ``TEME`` to ``ITRS`` transformation); otherwise
    through astropy's frames.

    Parameters
    ----------
    position : ndarray, shape (...,) + obstime.shape + (3,)
        TEME positions in metres (leading axes for several satellites).
    obstime : `~astropy.time.Time`
        Epochs.
    orientation : `~astropy_feedrot.earth.EarthOrientation`, optional
        Earth orientation at exactly these epochs, if one is at hand.

    Returns
    -------
    ndarray
        ITRS positions in metres, same shape.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.orbits import teme_to_itrs
    >>> xyz = teme_to_itrs(np.array([7.0e6, 0.0, 0.0]), Time("2023-01-25"))
    >>> bool(np.isclose(np.linalg.norm(xyz), 7.0e6))
    True
    """
    position = np.asarray(position, dtype=float)
    check_orientation(orientation, obstime)
    if orientation is None and fast_path_applies(None, obstime):
        orientation = orientation_of(obstime)
    if orientation is not None:
        flat = position.reshape(position.shape[:-1 - obstime.ndim] + (obstime.size, 3))
        return orientation.teme_to_itrs(flat).reshape(position.shape)
    if position.size == 0:  # nothing to rotate (astropy 6.0 fails on empty epochs)
        return position.copy()
    rep = CartesianRepresentation(np.moveaxis(position, -1, 0) * u.m)
    with iers_context(obstime), np.errstate(invalid="ignore"):
        itrs = TEME(rep, obstime=obstime).transform_to(ITRS(obstime=obstime))
    return np.moveaxis(itrs.cartesian.xyz.to_value(u.m), 0, -1)


class TLEOrbit(Orbit):
    """An orbit from a two-line element set, propagated with SGP4.

    Parameters
    ----------
    line1, line2 : str
        The two lines of the element set (69 characters each, every field in
        its format, valid checksums; see `astropy_feedrot.io.check_tle_line`).
    name : str, optional
        A label (e.g. ``'GPS SVN 76'``).

    Attributes
    ----------
    max_age : `~astropy.units.Quantity`
        How far from the epoch of the element set positions are computed
        without a warning: 30 days (class attribute; set it on an instance
        to change it for that orbit).

    Raises
    ------
    TypeError
        If a line is not a string.
    ValueError
        If a line is malformed (its length, line number, a blank column, a
        field that does not read, even with a valid checksum, or the
        checksum), naming which line, field and columns; or if SGP4 refuses
        the elements at their epoch.
    ImportError
        If the ``sgp4`` package is not installed.

    Notes
    -----
    SGP4 (the ``sgp4`` package) gives positions in the TEME frame; astropy
    rotates them to ITRS with Greenwich mean sidereal time, UT1 and polar
    motion.

    Where SGP4 fails (a decayed satellite, an eccentricity driven out of
    range by drag, ...) the positions are NaN and one
    `~astropy_feedrot.OrbitWarning` says how many epochs and why.

    An element set is a fit to a few days of observations; propagated away
    from its epoch its errors grow, for GNSS orbits to kilometres within
    weeks and faster for low, dragged orbits (Kelso 2007, "Validation of SGP4
    and IS-GPS-200D against GPS precision ephemerides", AAS 07-127). Beyond
    `max_age` (30 days: a month-old element set has been superseded many
    times over, and at GNSS distance kilometres are already hundredths of a
    degree of direction) positions are still computed, with one
    `~astropy_feedrot.OrbitWarning` per call: use a fresher element set.

    Examples
    --------
    GPS SVN 76 on 2023-01-25 (Table 2 of the paper):

    >>> from astropy.time import Time
    >>> from astropy_feedrot import TLEOrbit
    >>> orbit = TLEOrbit(
    ...     "1 41328U 16007A   23024.39332179  .00000015  00000-0  00000+0 0  9995",
    ...     "2 41328  54.9577 138.7050 0066950 231.2234 128.1638  2.00560135 51012")
    >>> import numpy as np
    >>> radius = np.linalg.norm(orbit.position(Time("2023-01-25T12:00")))
    >>> round(radius / 1e3)  # km from the geocentre
    26713
    >>> orbit.max_age
    <Quantity 30. d>
    """

    max_age = 30 * u.day
    uses_orientation = True  # TEME to ITRS

    def __init__(self, line1, line2, name=None):
        self.line1, self.line2 = check_tle_pair(line1, line2)
        satrec = _sgp4().Satrec.twoline2rv(self.line1, self.line2)
        if satrec.error:
            raise ValueError(f"SGP4 cannot start from this element set: "
                             f"{_sgp4_error(satrec.error)}: {self.line1!r}, {self.line2!r}")
        self._satrec = satrec
        self.name = name

    def __repr__(self):
        label = f", name={self.name!r}" if self.name else ""
        return f"TLEOrbit({self.line1!r}, {self.line2!r}{label})"

    @property
    def label(self):
        """str: The name, or the catalogue number when there is none."""
        return self.name or self.line1[2:7].strip()

    @property
    def epoch(self):
        """The epoch of the element set, as `~astropy.time.Time` (UTC)."""
        return Time(self._satrec.jdsatepoch, self._satrec.jdsatepochF, format="jd", scale="utc")

    @classmethod
    def from_elements(
        cls,
        epoch,
        *,
        inclination,
        raan,
        altitude=None,
        mean_motion=None,
        eccentricity=0.0,
        argument_of_perigee=0 * u.deg,
        mean_anomaly=0 * u.deg,
        bstar=0.0,
        satnum=99999,
        name=None,
    ):
        """A hypothetical orbit from mean elements, such as the paper's GENESIS.

        Parameters
        ----------
        epoch : `~astropy.time.Time`
            Epoch of the elements, one instant from 1957 to 2056 (UTC): the
            two-digit year of an element set reads 57-99 as 1957-1999 and
            00-56 as 2000-2056.
        inclination, raan : `~astropy.units.Quantity` (angle)
            Inclination (0-180 deg) and right ascension of the ascending node
            (any angle; it is wrapped to 0-360 deg).
        altitude : `~astropy.units.Quantity` (length), optional
            Altitude of a circular orbit above the SGP4 (WGS72) equatorial
            radius; gives the mean motion by Kepler's third law. Give either
            this or ``mean_motion``.
        mean_motion : `~astropy.units.Quantity` (angle / time), optional
            Mean motion, e.g. ``2.0056 * u.cycle / u.day``; below 100
            revolutions per day, as the element set can hold.
        eccentricity : float, optional
        argument_of_perigee, mean_anomaly : `~astropy.units.Quantity` (angle), optional
            Wrapped to 0-360 deg.
        bstar : float, optional
            Drag term (1 / Earth radii); 0 for no drag.
        satnum : int, optional
            Catalogue number written into the element set, 0-339999 (above
            99999 as the letter-and-four-digits form).
        name : str, optional

        Returns
        -------
        TLEOrbit
            With the element set written out as two lines.

        Raises
        ------
        ValueError
            If neither or both of ``altitude`` and ``mean_motion`` are given,
            an element is out of range or not finite, or the epoch is not one
            instant the two-digit year can hold.
        TypeError
            If ``satnum`` is not an integer.
        astropy.units.UnitsError
            If an element has the wrong units.

        Examples
        --------
        The GENESIS-like orbit of Sec. 4.2: circular, 6000 km altitude,
        inclination 97 deg, ascending node at 30 deg:

        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import TLEOrbit
        >>> genesis = TLEOrbit.from_elements(Time("2023-01-25"), inclination=97 * u.deg,
        ...                                  raan=30 * u.deg, altitude=6000 * u.km)
        >>> genesis.line2[8:16]
        ' 97.0000'
        """
        if (altitude is None) == (mean_motion is None):
            raise ValueError("give exactly one of altitude and mean_motion")
        if altitude is not None:
            a_km = _WGS72_RADIUS + u.Quantity(altitude).to_value(u.km)
            if not a_km > _WGS72_RADIUS:
                raise ValueError(f"altitude must be positive, got {altitude}")
            n = np.sqrt(_WGS72_MU / a_km**3) * 60.0  # rad / min
        else:
            n = u.Quantity(mean_motion).to_value(u.rad / u.min)  # u.cycle converts too
            if not n > 0:
                raise ValueError(f"mean_motion must be positive, got {mean_motion}")
        if not n < _MAX_MEAN_MOTION:
            raise ValueError(f"mean_motion must be below 100 revolutions per day (what an "
                             f"element set holds), got {mean_motion}")
        if not 0 <= eccentricity < 1:
            raise ValueError(f"eccentricity must be in [0, 1), got {eccentricity}")
        inc = u.Quantity(inclination).to_value(u.rad)
        if not 0 <= inc <= np.pi:
            raise ValueError(f"inclination must be within 0-180 deg, got {inclination}")
        angles = {}
        for key, value in (("raan", raan), ("argument_of_perigee", argument_of_perigee),
                           ("mean_anomaly", mean_anomaly)):
            rad = u.Quantity(value).to_value(u.rad)
            if np.ndim(rad) or not np.isfinite(rad):
                raise ValueError(f"{key} must be one finite angle, got {value}")
            angles[key] = float(np.mod(rad, 2 * np.pi))
        if not np.isfinite(bstar):
            raise ValueError(f"bstar must be finite, got {bstar}")
        if isinstance(satnum, bool) or not isinstance(satnum, (int, np.integer)):
            raise TypeError(f"satnum must be an integer, got {type(satnum).__name__}")
        if not 0 <= satnum <= _MAX_SATNUM:
            raise ValueError(f"satnum must be within 0-{_MAX_SATNUM}, got {satnum}")
        epoch = as_time(epoch).utc
        if not epoch.isscalar:
            raise ValueError(f"epoch must be one instant, got shape {epoch.shape}")
        if not _TLE_FIRST_JD <= epoch.jd1 + epoch.jd2 < _TLE_END_JD:
            with warnings.catch_warnings():  # ERFA finds UTC so far away "dubious"
                warnings.simplefilter("ignore", ErfaWarning)
                when = epoch.isot
            raise ValueError(f"epoch must be within 1957-2056, the years a TLE's two-digit "
                             f"year can hold (57-99: 1957-1999, 00-56: 2000-2056), got {when}")
        satrec = _sgp4().Satrec()
        satrec.sgp4init(
            0,  # WGS72
            "i",
            int(satnum),
            epoch.jd - 2433281.5,
            float(bstar),
            0.0,
            0.0,
            float(eccentricity),
            angles["argument_of_perigee"],
            inc,
            angles["mean_anomaly"],
            n,
            angles["raan"],
        )
        from sgp4.exporter import export_tle  # optional dependency, as in _sgp4

        line1, line2 = export_tle(satrec)
        return cls(line1, line2, name=name)

    def position(self, obstime, orientation=None):
        obstime = as_time(obstime)
        return self.batch_positions([self], obstime, orientation)[0]

    @classmethod
    def batch_positions(cls, orbits, obstime, orientation=None):
        """Positions of several element sets: one SGP4 call (`propagate_tles`).

        Parameters
        ----------
        orbits : list of `TLEOrbit`
        obstime : `~astropy.time.Time`
            Epochs, any shape.
        orientation : `~astropy_feedrot.earth.EarthOrientation`, optional
            Earth orientation at exactly these epochs for the rotation from
            TEME to ITRS; by default `teme_to_itrs` makes its own.

        Returns
        -------
        ndarray, shape (len(orbits),) + obstime.shape + (3,)
            ITRS metres; NaN where SGP4 fails (one warning).

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot import TLEOrbit
        >>> from astropy_feedrot.simulations import GPS_SVN76_TLE
        >>> gps = TLEOrbit(*GPS_SVN76_TLE)
        >>> TLEOrbit.batch_positions([gps, gps], Time(["2023-01-25", "2023-01-26"])).shape
        (2, 2, 3)
        """
        obstime = as_time(obstime)
        return teme_to_itrs(propagate_tles(orbits, obstime), obstime, orientation)


# Largest mean motion an element set holds (99.99999999 rev/day), in rad/min;
# largest catalogue number (Z9999 in the letter-and-four-digits form).
_MAX_MEAN_MOTION = 100 * 2 * np.pi / 1440
_MAX_SATNUM = 339999
# Julian dates (UTC) of 1957-01-01 and 2057-01-01 (proleptic Gregorian ordinal day
# + 1721424.5): the span a two-digit TLE year holds.
_TLE_FIRST_JD = datetime.date(1957, 1, 1).toordinal() + 1721424.5
_TLE_END_JD = datetime.date(2057, 1, 1).toordinal() + 1721424.5


def _sgp4_error(code):
    """SGP4's words for an error code."""
    return _sgp4().SGP4_ERRORS.get(int(code), f"error {int(code)}")


def propagate_tles(orbits, obstime):
    """TEME positions of several element sets at the same epochs, with one SGP4 call.

    Parameters
    ----------
    orbits : sequence of `TLEOrbit`
        The element sets.
    obstime : `~astropy.time.Time`
        Epochs, any shape.

    Returns
    -------
    ndarray, shape (len(orbits),) + obstime.shape + (3,)
        Positions in the TEME frame of SGP4, in metres; NaN where SGP4 fails.

    Notes
    -----
    With ``conf.fast_path`` (the default) and dense epochs (two or more per
    node), SGP4 is evaluated at nodes a power of two seconds apart (1 s to
    17 min, from each orbit's mean motion and eccentricity) and interpolated,
    within 0.1 mm of SGP4 at every epoch (``astropy_feedrot.propagation``);
    sparse epochs, epochs near a failure of SGP4, and every epoch with
    ``conf.fast_path = False``, are computed directly.

    Warns
    -----
    `~astropy_feedrot.OrbitWarning`
        Once if SGP4 fails at some epochs (their positions are NaN; the
        message gives the counts and SGP4's reasons), and once if some epochs
        lie further than `TLEOrbit.max_age` from the epoch of their element
        set.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot import TLEOrbit
    >>> from astropy_feedrot.orbits import propagate_tles
    >>> from astropy_feedrot.simulations import GPS_SVN76_TLE
    >>> t = Time("2023-01-25") + [0, 1, 2] * u.hour
    >>> r = propagate_tles([TLEOrbit(*GPS_SVN76_TLE)], t)
    >>> r.shape
    (1, 3, 3)
    >>> np.round(np.linalg.norm(r, axis=-1) / 1e6, 1)  # thousands of km
    array([[26.7, 26.7, 26.6]])
    """
    orbits = list(orbits)
    for i, orbit in enumerate(orbits):
        if not isinstance(orbit, TLEOrbit):
            raise TypeError(f"orbits[{i}] must be a TLEOrbit, got {type(orbit).__name__}")
    obstime = as_time(obstime)
    utc = obstime.utc
    jd1 = np.ascontiguousarray(utc.jd1, dtype=float).ravel()  # sgp4 needs C order
    jd2 = np.ascontiguousarray(utc.jd2, dtype=float).ravel()
    error, r = propagate([orbit._satrec for orbit in orbits], jd1, jd2,
                         interpolate=conf.fast_path)
    r[error != 0] = np.nan
    if np.any(error != 0):
        parts = []
        for orbit, codes in zip(orbits, error):
            for code in np.unique(codes[codes != 0]):
                parts.append(f"{orbit.label}: {np.count_nonzero(codes == code)} epochs, "
                             f"{_sgp4_error(code)}")
        warn_caller(
            f"SGP4 fails at {np.count_nonzero(error)} of {error.size} epochs "
            f"({'; '.join(parts)}); their positions are NaN", OrbitWarning)
    epochs = np.array([[o._satrec.jdsatepoch, o._satrec.jdsatepochF] for o in orbits])
    age = np.abs((jd1 - epochs[:, :1]) + (jd2 - epochs[:, 1:]))  # days, (S, T)
    limits = np.array([u.Quantity(o.max_age).to_value(u.day) for o in orbits])[:, np.newaxis]
    stale = age > limits
    if np.any(stale):
        worst = [f"{o.label} (epoch {o.epoch.iso[:10]}) up to {a.max():.1f} days away"
                 for o, a, s in zip(orbits, age, stale) if s.any()]
        warn_caller(
            f"{np.count_nonzero(stale)} of {stale.size} epochs lie more than "
            f"{limits.min():g} days from the epoch of their element set "
            f"({'; '.join(worst)}); SGP4 positions degrade away from the epoch (kilometres "
            "within weeks): use an element set closer to the observation", OrbitWarning)
    return r.reshape((len(orbits),) + obstime.shape + (3,))


class SP3Orbit(Orbit):
    """An orbit from an IGS SP3 precise-orbit file, interpolated in time.

    Parameters
    ----------
    source : str, path-like, file object or `~astropy_feedrot.io.SP3Data`
        An SP3-c or SP3-d file, or its contents (several days joined by
        `~astropy_feedrot.io.sp3.join_sp3`, for instance).
    satellite : str
        The satellite's SP3 name, e.g. ``'G05'``.
    points : int, optional
        Number of consecutive epochs of the sliding window of the Lagrange
        interpolating polynomial (default 10, i.e. degree 9, the usual choice
        for 5- and 15-minute IGS orbits).

    Attributes
    ----------
    satellite, points : str, int
        As given.
    epochs : `~astropy.time.Time`
        The epochs of the file.
    interval : `~astropy.units.Quantity`
        The epoch interval of the file's header.
    spans : `~astropy.time.Time`, shape (K, 2)
        Start and end of each stretch where positions are interpolated:
        ``points`` or more consecutive epochs at the file's interval, all
        with a valid position of the satellite.

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        If the file is malformed (naming the line and what was expected).
    TypeError
        If ``points`` is not an integer (2.5 would be cut to 2 otherwise).
    ValueError
        If ``satellite`` is not in the file (listing those that are), the
        file has fewer epochs than ``points``, or the satellite has nowhere
        ``points`` consecutive valid epochs.

    Warns
    -----
    `~astropy_feedrot.OrbitWarning`
        From `position`, once per call, when some times fall in a hole.

    Notes
    -----
    Positions are interpolated coordinate by coordinate with a polynomial
    through ``points`` consecutive epochs around each requested time (a
    centred window, shifted at the ends of a stretch). Times outside the
    file's epochs raise an error.

    The window is made only of consecutive epochs at the interval of the
    file's header where the satellite has a valid position. A hole is any
    break in that: epochs the file skips, an epoch without a record of the
    satellite, a position marked bad or absent (0.000000 for x, y and z). A
    requested time that cannot be given such a window (in a hole, or in a
    stretch of fewer than ``points`` valid epochs between holes) gets NaN,
    and each call warns once (`~astropy_feedrot.OrbitWarning`) with the
    number of such times: no position is ever interpolated across a hole.
    Within a stretch, times near a hole use a window shifted away from it, as
    at the ends of the file. (In a file in UTC or GLONASS time, a leap second
    between two epochs breaks the interval too, and makes a hole.)

    Examples
    --------
    The sample file has four 15-minute epochs, enough for a cubic:

    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot import SP3Orbit
    >>> from astropy_feedrot.data import sample_file
    >>> orbit = SP3Orbit(sample_file("sample.sp3"), "G01", points=4)
    >>> xyz = orbit.position(Time("2023-01-25T00:20:00", scale="tai"))
    >>> round(float(np.linalg.norm(xyz)) / 1e3)  # km from the geocentre
    26560
    >>> orbit.spans.isot
    array([['2023-01-25T00:00:19.000', '2023-01-25T00:45:19.000']], dtype='<U23')
    """

    def __init__(self, source, satellite, points=10):
        data = source if isinstance(source, SP3Data) else read_sp3(source)
        if satellite not in data.positions:
            raise ValueError(
                f"satellite {satellite!r} is not in the SP3 file; it has "
                f"{', '.join(data.satellites)}"
            )
        if isinstance(points, bool) or not isinstance(points, (int, np.integer)):
            raise TypeError(f"points must be a whole number of epochs (int), got {points!r}")
        points = int(points)
        if points < 2:
            raise ValueError(f"points must be at least 2, got {points}")
        if len(data.epochs) < points:
            raise ValueError(
                f"the SP3 file has {len(data.epochs)} epochs, fewer than the {points} "
                "points of the interpolation window"
            )
        self.satellite = satellite
        self.points = points
        self.epochs = data.epochs
        self.interval = data.interval * u.s
        self.coordinate_system = data.coordinate_system
        self._t0 = data.epochs[0]
        self._seconds = (data.epochs - self._t0).to_value(u.s)
        self._xyz = data.positions[satellite]
        self._run_start, self._run_end = _stretches(self._seconds, self._xyz, data.interval)
        long_enough = self._run_end - self._run_start + 1 >= points
        if not np.any(long_enough):
            raise ValueError(
                f"{satellite} has no {points} consecutive epochs at the {data.interval:g} s "
                "interval of the SP3 file with a valid position, as the interpolation window "
                f"needs (its longest stretch has {np.max(self._run_end - self._run_start) + 1}); "
                "give fewer points or a file without holes"
            )
        self._usable = long_enough

    def __repr__(self):
        return (
            f"<SP3Orbit {self.satellite} {self.coordinate_system}, {len(self.epochs)} epochs "
            f"{self.epochs[0].isot} to {self.epochs[-1].isot}>"
        )

    @property
    def spans(self):
        """`~astropy.time.Time`, shape (K, 2): where positions are interpolated."""
        start = self._run_start[self._usable]
        end = self._run_end[self._usable]
        return self.epochs[np.stack([start, end], axis=-1)]

    @property
    def coverage(self):
        """(start, stop): the first and last epochs of the file, outside which
        `position` raises."""
        return self.epochs[0], self.epochs[-1]

    def position(self, obstime, orientation=None):
        # The file's positions are Earth-fixed already: no Earth orientation needed.
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        x = np.atleast_1d((obstime - self._t0).to_value(u.s)).ravel()
        tol = 1e-6
        outside = (x < self._seconds[0] - tol) | (x > self._seconds[-1] + tol)
        if np.any(outside):
            raise ValueError(
                f"times outside the coverage of the SP3 orbit of {self.satellite}: "
                f"{self.epochs[0].isot} to {self.epochs[-1].isot} {self.epochs.scale.upper()}"
            )
        run = _stretch_of(self._seconds, self._run_start, self._run_end, x, tol)
        ok = run >= 0
        ok[ok] = self._usable[run[ok]]
        out = np.full(x.shape + (3,), np.nan)
        if np.any(ok):
            first = self._run_start[run[ok]]
            last = self._run_end[run[ok]]
            start = np.searchsorted(self._seconds, x[ok]) - self.points // 2
            start = np.clip(start, first, last - self.points + 1)
            out[ok] = _lagrange(self._seconds, self._xyz, x[ok], start, self.points)
        if not np.all(ok):
            bad = np.flatnonzero(~ok)
            first_bad = (self._t0 + x[bad[0]] * u.s).isot
            warn_caller(
                f"{bad.size} of {x.size} times fall in holes of the SP3 orbit of "
                f"{self.satellite} (the first at {first_bad} {self.epochs.scale.upper()}), "
                f"where no {self.points} consecutive epochs at the {self.interval.value:g} s "
                "interval have valid positions: skipped epochs, missing records or positions "
                "marked bad; NaN is returned there (SP3Orbit.spans lists where positions are "
                "interpolated)",
                OrbitWarning,
            )
        return out.reshape(obstime.shape + (3,))


def _stretches(seconds, xyz, interval, tol=1e-3):
    """First and last index of each stretch of consecutive valid epochs at the interval.

    An epoch without a valid position is a stretch of its own, never usable
    (its length is counted as 0 by making its last index precede its first).
    """
    valid = np.all(np.isfinite(xyz), axis=-1)
    step = np.abs(np.diff(seconds) - interval) < tol
    link = valid[:-1] & valid[1:] & step
    starts = np.flatnonzero(np.r_[True, ~link])
    ends = np.r_[starts[1:] - 1, len(seconds) - 1]
    ends = np.where(valid[starts], ends, starts - 1)
    return starts, ends


def _stretch_of(seconds, run_start, run_end, x, tol):
    """Index of the stretch each time lies in, -1 in a hole."""
    node = np.clip(np.searchsorted(seconds, x - tol, side="left"), 0, len(seconds) - 1)
    # The last node at or before x (up to tol), and the stretch holding it.
    node = np.where(seconds[node] > x + tol, node - 1, node)
    node = np.clip(node, 0, len(seconds) - 1)
    run = np.searchsorted(run_start, node, side="right") - 1
    at_node = np.abs(seconds[node] - x) <= tol
    next_in_run = (node + 1 <= run_end[run])
    inside = (node <= run_end[run]) & (at_node | next_in_run)
    return np.where(inside, run, -1)


def lagrange_interpolate(x, y, x_new, points):
    """Sliding-window Lagrange interpolation of tabulated values.

    Parameters
    ----------
    x : ndarray, shape (N,)
        Increasing abscissae of the table.
    y : ndarray, shape (N, ...)
        Tabulated values.
    x_new : ndarray, shape (M,)
        Where to interpolate (within ``x[0]..x[-1]``).
    points : int
        Window length: the polynomial goes through the ``points`` table
        entries nearest to each ``x_new``.

    Returns
    -------
    ndarray, shape (M, ...)
        Interpolated values; NaN where the window holds a NaN.

    Notes
    -----
    The window is chosen by position in the table only: this function does
    not know about holes in it. `SP3Orbit` chooses windows that avoid them.

    Examples
    --------
    A cubic is reproduced exactly by a 4-point window:

    >>> import numpy as np
    >>> from astropy_feedrot.orbits import lagrange_interpolate
    >>> x = np.arange(10.0)
    >>> float(lagrange_interpolate(x, x**3, np.array([4.5]), 4)[0])
    91.125
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    x_new = np.asarray(x_new, dtype=float)
    n = len(x)
    start = np.searchsorted(x, x_new) - points // 2
    start = np.clip(start, 0, n - points)
    return _lagrange(x, y, x_new, start, points)


def _lagrange(x, y, x_new, start, points):
    """Lagrange interpolation through the window ``start[m]:start[m] + points`` for each x_new."""
    window = start[:, np.newaxis] + np.arange(points)  # (M, points)
    xs = x[window]
    # Lagrange basis: w_j = prod_{k != j} (x_new - x_k) / (x_j - x_k)
    diff = x_new[:, np.newaxis] - xs  # (M, points)
    denom = xs[:, :, np.newaxis] - xs[:, np.newaxis, :]  # (M, points, points)
    eye = np.eye(points, dtype=bool)
    denom[:, eye] = 1.0
    numer = np.broadcast_to(diff[:, np.newaxis, :], denom.shape).copy()
    numer[:, eye] = 1.0
    weights = np.prod(numer / denom, axis=-1)  # (M, points)
    values = y[window]  # (M, points, ...)
    return np.einsum("mp,mp...->m...", weights, values)


class CoordinateOrbit(Orbit):
    """Positions the user already has, as a `~astropy.coordinates.SkyCoord`.

    Parameters
    ----------
    coord : `~astropy.coordinates.SkyCoord`
        Satellite position(s) with a distance, in any frame astropy can
        transform to ITRS. Positions in ITRS are used as they are; those in
        other frames are transformed to ITRS at the requested times (their
        shape must broadcast with them).

    Raises
    ------
    TypeError
        If ``coord`` is not a coordinate.
    ValueError
        If ``coord`` has no distance.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import ITRS, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot import CoordinateOrbit
    >>> where = SkyCoord(ITRS(x=2.6e7 * u.m, y=0 * u.m, z=0 * u.m,
    ...                       representation_type="cartesian"))
    >>> CoordinateOrbit(where).position(Time("2023-01-25"))  # doctest: +FLOAT_CMP
    array([26000000.,        0.,        0.])
    """

    def __init__(self, coord):
        if not isinstance(coord, SkyCoord):
            raise TypeError(f"coord must be a SkyCoord, got {type(coord).__name__}")
        if coord.cartesian.x.unit.physical_type != "length":
            raise ValueError(
                "a satellite position needs a distance; this SkyCoord is a direction only"
            )
        self.coord = coord

    def __repr__(self):
        return f"<CoordinateOrbit shape={self.coord.shape} frame={self.coord.frame.name}>"

    def position(self, obstime, orientation=None):
        # Positions in celestial frames go through astropy's transformation at
        # each epoch (exact, whatever the frame): no interpolated orientation.
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        coord = self.coord
        if not isinstance(coord.frame, ITRS):
            with iers_context(obstime):
                coord = coord.transform_to(ITRS(obstime=obstime))
        xyz = np.moveaxis(coord.cartesian.xyz.to_value(u.m), 0, -1)
        if coord.frame.location is not None:
            xyz = xyz + location_xyz(coord.frame.location)
        shape = np.broadcast_shapes(xyz.shape[:-1], obstime.shape)
        return np.broadcast_to(xyz, shape + (3,))


def as_orbit(orbit):
    """Coerce an orbit-like object to an `Orbit`.

    Parameters
    ----------
    orbit : `Orbit` or `~astropy.coordinates.SkyCoord`
        An orbit, or satellite positions with a distance.

    Returns
    -------
    `Orbit`

    Raises
    ------
    TypeError
        For anything else.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import ITRS, SkyCoord
    >>> from astropy_feedrot.orbits import as_orbit
    >>> as_orbit(SkyCoord(ITRS(x=2.6e7 * u.m, y=0 * u.m, z=0 * u.m,
    ...                        representation_type="cartesian")))
    <CoordinateOrbit shape=() frame=itrs>
    """
    if isinstance(orbit, Orbit):
        return orbit
    if isinstance(orbit, SkyCoord):
        return CoordinateOrbit(orbit)
    raise TypeError(
        f"orbit must be a TLEOrbit, SP3Orbit, CoordinateOrbit or a SkyCoord with a "
        f"distance, got {type(orbit).__name__}"
    )
