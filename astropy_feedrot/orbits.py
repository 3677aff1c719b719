# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Satellite orbits: Earth-fixed (ITRS) positions at any time.

Three sources of positions: a two-line element set propagated with SGP4
(`TLEOrbit`), an IGS SP3 precise-orbit file interpolated with sliding-window
Lagrange polynomials (`SP3Orbit`), and positions the user already has as a
`~astropy.coordinates.SkyCoord` (`CoordinateOrbit`).
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import ITRS, TEME, CartesianRepresentation, SkyCoord
from astropy.time import Time

from .config import conf
from .eop import iers_context
from .frames import as_time, location_xyz

__all__ = ["Orbit", "TLEOrbit", "SP3Orbit", "CoordinateOrbit", "as_orbit"]

# WGS72 constants used by SGP4 (Vallado and Crawford 2008).
_WGS72_MU = 398600.8  # km^3 / s^2
_WGS72_RADIUS = 6378.135  # km


class Orbit:
    """Base class of orbits: Earth-fixed positions as a function of time."""

    def position(self, obstime):
        """Geocentric ITRS position(s), in metres.

        Parameters
        ----------
        obstime : `~astropy.time.Time`
            Epoch(s).

        Returns
        -------
        ndarray, shape obstime.shape + (3,)
            Cartesian ITRS coordinates in metres; NaN where the orbit cannot
            give a position.
        """
        raise NotImplementedError  # pragma: no cover


def _tle_checksum(line):
    return sum(int(c) if c.isdigit() else c == "-" for c in line[:68]) % 10


def _check_tle_line(line, number):
    if not isinstance(line, str):
        raise TypeError(f"TLE line {number} must be a str, got {type(line).__name__}")
    line = line.rstrip()
    if len(line) != 69:
        raise ValueError(
            f"TLE line {number} must have 69 characters, got {len(line)}: {line!r}"
        )
    if line[0] != str(number) or line[1] != " ":
        raise ValueError(f"TLE line {number} must start with '{number} ', got {line[:2]!r}")
    if not line[68].isdigit() or int(line[68]) != _tle_checksum(line):
        raise ValueError(
            f"TLE line {number} checksum: expected {_tle_checksum(line)} in column 69, "
            f"got {line[68]!r}: {line!r}"
        )
    return line


def _sgp4():
    try:
        from sgp4.api import Satrec
    except ImportError:  # pragma: no cover - exercised only without sgp4
        raise ImportError(
            "TLE orbits need the sgp4 package: python -m pip install sgp4 "
            "(or astropy_feedrot[all])"
        ) from None
    return Satrec


def teme_to_itrs(position, obstime):
    """Rotate TEME positions (SGP4's frame) to geocentric ITRS.

    With ``conf.fast_path`` (the default) and 16 or more epochs the rotation
    is computed once per epoch from interpolated Earth orientation
    (`~astropy_feedrot.earth.EarthOrientation`: GMST 1982 from UT1 and polar
    motion, as astropy's ``TEME`` to ``ITRS`` transformation); otherwise
    through astropy's frames.

    Parameters
    ----------
    position : ndarray, shape obstime.shape + (3,)
        TEME positions in metres.
    obstime : `~astropy.time.Time`
        Epochs.

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
    if conf.fast_path and obstime.size >= 16:
        from .earth import EarthOrientation

        flat = position.reshape(-1, 3)
        orientation = EarthOrientation(obstime, step=conf.fast_path_step * u.min)
        return orientation.teme_to_itrs(flat).reshape(position.shape)
    rep = CartesianRepresentation(np.moveaxis(position, -1, 0) * u.m)
    with iers_context(obstime), np.errstate(invalid="ignore"):
        itrs = TEME(rep, obstime=obstime).transform_to(ITRS(obstime=obstime))
    return np.moveaxis(itrs.cartesian.xyz.to_value(u.m), 0, -1)


class TLEOrbit(Orbit):
    """An orbit from a two-line element set, propagated with SGP4.

    Parameters
    ----------
    line1, line2 : str
        The two lines of the element set (69 characters each, with valid
        checksums).
    name : str, optional
        A label (e.g. ``'GPS SVN 76'``).

    Raises
    ------
    TypeError
        If a line is not a string.
    ValueError
        If a line is malformed: its length, line number or checksum, naming
        which line and what was expected.
    ImportError
        If the ``sgp4`` package is not installed.

    Notes
    -----
    SGP4 (the ``sgp4`` package) gives positions in the TEME frame; astropy
    rotates them to ITRS with Greenwich mean sidereal time, UT1 and polar
    motion. Epochs where SGP4 fails (decayed orbit) are NaN.

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
    """

    def __init__(self, line1, line2, name=None):
        self.line1 = _check_tle_line(line1, 1)
        self.line2 = _check_tle_line(line2, 2)
        if self.line1[2:7] != self.line2[2:7]:
            raise ValueError(
                f"TLE lines describe different satellites: {self.line1[2:7]!r} and "
                f"{self.line2[2:7]!r}"
            )
        self._satrec = _sgp4().twoline2rv(self.line1, self.line2)
        self.name = name

    def __repr__(self):
        label = f", name={self.name!r}" if self.name else ""
        return f"TLEOrbit({self.line1!r}, {self.line2!r}{label})"

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
            Epoch of the elements.
        inclination, raan : `~astropy.units.Quantity` (angle)
            Inclination and right ascension of the ascending node.
        altitude : `~astropy.units.Quantity` (length), optional
            Altitude of a circular orbit above the SGP4 (WGS72) equatorial
            radius; gives the mean motion by Kepler's third law. Give either
            this or ``mean_motion``.
        mean_motion : `~astropy.units.Quantity` (angle / time), optional
            Mean motion, e.g. ``2.0056 * u.cycle / u.day``.
        eccentricity : float, optional
        argument_of_perigee, mean_anomaly : `~astropy.units.Quantity` (angle), optional
        bstar : float, optional
            Drag term (1 / Earth radii); 0 for no drag.
        satnum : int, optional
            Catalogue number written into the element set.
        name : str, optional

        Returns
        -------
        TLEOrbit
            With the element set written out as two lines.

        Raises
        ------
        ValueError
            If neither or both of ``altitude`` and ``mean_motion`` are given,
            or an element is out of range.
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
            if a_km <= _WGS72_RADIUS:
                raise ValueError(f"altitude must be positive, got {altitude}")
            n = np.sqrt(_WGS72_MU / a_km**3) * 60.0  # rad / min
        else:
            n = u.Quantity(mean_motion).to_value(u.rad / u.min)  # u.cycle converts too
            if n <= 0:
                raise ValueError(f"mean_motion must be positive, got {mean_motion}")
        if not 0 <= eccentricity < 1:
            raise ValueError(f"eccentricity must be in [0, 1), got {eccentricity}")
        inc = u.Quantity(inclination).to_value(u.rad)
        if not 0 <= inc <= np.pi:
            raise ValueError(f"inclination must be within 0-180 deg, got {inclination}")
        epoch = as_time(epoch).utc
        satrec = _sgp4()()
        satrec.sgp4init(
            0,  # WGS72
            "i",
            int(satnum),
            epoch.jd - 2433281.5,
            float(bstar),
            0.0,
            0.0,
            float(eccentricity),
            u.Quantity(argument_of_perigee).to_value(u.rad),
            inc,
            u.Quantity(mean_anomaly).to_value(u.rad),
            n,
            u.Quantity(raan).to_value(u.rad),
        )
        from sgp4.exporter import export_tle

        line1, line2 = export_tle(satrec)
        return cls(line1, line2, name=name)

    def position(self, obstime):
        obstime = as_time(obstime)
        utc = obstime.utc
        jd1 = np.ascontiguousarray(utc.jd1, dtype=float).ravel()  # sgp4 needs C order
        jd2 = np.ascontiguousarray(utc.jd2, dtype=float).ravel()
        error, r, _ = self._satrec.sgp4_array(jd1, jd2)
        r = np.asarray(r, dtype=float) * 1e3
        r[np.asarray(error) != 0] = np.nan
        return teme_to_itrs(r.reshape(obstime.shape + (3,)), obstime)


class SP3Orbit(Orbit):
    """An orbit from an IGS SP3 precise-orbit file, interpolated in time.

    Parameters
    ----------
    source : str, path-like or file object
        An SP3-c or SP3-d file.
    satellite : str
        The satellite's SP3 name, e.g. ``'G05'``.
    points : int, optional
        Number of consecutive epochs of the sliding window of the Lagrange
        interpolating polynomial (default 10, i.e. degree 9, the usual choice
        for 5- and 15-minute IGS orbits).

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        If the file is malformed (naming the line and what was expected).
    ValueError
        If ``satellite`` is not in the file (listing those that are), or it has
        fewer epochs than ``points``.

    Notes
    -----
    Positions are interpolated coordinate by coordinate with a polynomial
    through the ``points`` epochs nearest to each requested time (a centred
    window, shifted at the ends of the file). Times outside the file's epochs
    raise an error; a window containing a missing record gives NaN.

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
    """

    def __init__(self, source, satellite, points=10):
        from .io import read_sp3

        data = read_sp3(source)
        if satellite not in data.positions:
            raise ValueError(
                f"satellite {satellite!r} is not in the SP3 file; it has "
                f"{', '.join(data.satellites)}"
            )
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
        self.coordinate_system = data.coordinate_system
        self._t0 = data.epochs[0]
        self._seconds = (data.epochs - self._t0).to_value(u.s)
        self._xyz = data.positions[satellite]

    def __repr__(self):
        return (
            f"<SP3Orbit {self.satellite} {self.coordinate_system}, {len(self.epochs)} epochs "
            f"{self.epochs[0].isot} to {self.epochs[-1].isot}>"
        )

    def position(self, obstime):
        obstime = as_time(obstime)
        x = np.atleast_1d((obstime - self._t0).to_value(u.s))
        outside = (x < self._seconds[0] - 1e-6) | (x > self._seconds[-1] + 1e-6)
        if np.any(outside):
            raise ValueError(
                f"times outside the coverage of the SP3 orbit of {self.satellite}: "
                f"{self.epochs[0].isot} to {self.epochs[-1].isot} {self.epochs.scale.upper()}"
            )
        return lagrange_interpolate(self._seconds, self._xyz, x, self.points).reshape(
            obstime.shape + (3,))


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

    def position(self, obstime):
        obstime = as_time(obstime)
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
