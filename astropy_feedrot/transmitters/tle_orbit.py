# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Orbits from two-line element sets, propagated with SGP4 and rotated from TEME to ITRS.

`TLEOrbit` is one element set; `propagate_tles` propagates many at many
epochs with one SGP4 call; `teme_to_itrs` is the rotation of SGP4's output
frame to the Earth-fixed frame (from the epochs' Earth orientation where the
fast path applies).
"""

import datetime
import warnings

import numpy as np
from astropy import units as u
from astropy.coordinates import ITRS, TEME, CartesianRepresentation
from astropy.time import Time
from erfa import ErfaWarning

from ..core.config import conf
from ..core.exceptions import OrbitWarning, warn_caller
from ..earth.eop import iers_context
from ..earth.frames import as_time
from ..earth.orientation import fast_path_applies, orientation_of
from ..io.tle import check_tle_pair
from .orbit_interface import Orbit, check_orientation
from .propagation import SGP4_MISSING, propagate

__all__ = ["TLEOrbit", "propagate_tles", "teme_to_itrs"]


# WGS72 constants used by SGP4 (Vallado and Crawford 2008).
_WGS72_MU = 398600.8  # km^3 / s^2


_WGS72_RADIUS = 6378.135  # km


def _sgp4():
    """The sgp4 package's ``api`` module (an optional dependency, imported when first needed)."""
    try:
        from sgp4 import api
    except ImportError:  # exercised by tests/cli/test_cli_extras.py, without sgp4
        raise ImportError(SGP4_MISSING) from None
    return api


def teme_to_itrs(position, obstime, orientation=None):
    """Rotate TEME positions (SGP4's frame) to geocentric ITRS.

    With an ``orientation``, or where the fast path applies
    (`~astropy_feedrot.earth.orientation.fast_path_applies`), the rotation is computed
    once per epoch from interpolated Earth orientation
    (`~astropy_feedrot.earth.orientation.EarthOrientation`: GMST 1982 from UT1 and polar
    motion, as astropy's ``TEME`` to ``ITRS`` transformation); otherwise
    through astropy's frames.

    Parameters
    ----------
    position : ndarray, shape (...,) + obstime.shape + (3,)
        TEME positions in metres (leading axes for several satellites).
    obstime : `~astropy.time.Time`
        Epochs.
    orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`, optional
        Earth orientation at exactly these epochs, if one is at hand.

    Returns
    -------
    ndarray
        ITRS positions in metres, same shape.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.transmitters.orbits import teme_to_itrs
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
        orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`, optional
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
        >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
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
    within 0.1 mm of SGP4 at every epoch (``astropy_feedrot.transmitters.propagation``);
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
    >>> from astropy_feedrot.transmitters.orbits import propagate_tles
    >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
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
