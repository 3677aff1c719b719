# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""From astropy objects to Earth-fixed unit vectors.

This is the only module that turns `~astropy.time.Time`,
`~astropy.coordinates.EarthLocation` and `~astropy.coordinates.SkyCoord` into
the plain ``(..., 3)`` arrays of the geometry kernel. All vectors are in the
Earth-fixed ITRS, in which the north celestial pole of the paper is
``z = [0, 0, 1]`` (Appendix D).

The transformations go through astropy, i.e. ERFA with precession-nutation,
UT1-UTC and polar motion from the IERS tables bundled with astropy; see
`~astropy_feedrot.eop.iers_context` for how downloads are kept off and what
happens beyond the tables.
"""

from typing import NamedTuple

import numpy as np
from astropy import units as u
from astropy.coordinates import (
    FK4,
    FK5,
    ICRS,
    ITRS,
    BarycentricMeanEcliptic,
    BarycentricTrueEcliptic,
    BaseCoordinateFrame,
    EarthLocation,
    FK4NoETerms,
    Galactic,
    SkyCoord,
    Supergalactic,
    UnitSphericalRepresentation,
)
from astropy.time import Time

from .config import conf
from .eop import iers_context
from .kernel import dot, unit

__all__ = [
    "LocalFrame",
    "VERTICALS",
    "as_location",
    "as_time",
    "as_skycoord",
    "broadcast_shape",
    "horizontal",
    "local_frame",
    "location_xyz",
    "source_direction",
]

#: Accepted definitions of the local vertical: the ellipsoid normal or the
#: geocentric direction (see `local_frame`).
VERTICALS = ("geodetic", "geocentric")


class LocalFrame(NamedTuple):
    """The local east, north and up unit vectors of a site, in ITRS.

    Each field is an ndarray of shape ``(..., 3)`` (the shape of the location
    plus a last axis of 3).
    """

    east: np.ndarray
    north: np.ndarray
    up: np.ndarray


def as_location(location, name="location"):
    """Check that ``location`` is an `~astropy.coordinates.EarthLocation`.

    Parameters
    ----------
    location : `~astropy.coordinates.EarthLocation`
        The object to check.
    name : str, optional
        How to call it in the error message.

    Returns
    -------
    `~astropy.coordinates.EarthLocation`

    Raises
    ------
    TypeError
        If ``location`` is anything else.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from astropy_feedrot.frames import as_location
    >>> loc = as_location(EarthLocation.from_geodetic(-3.0869 * u.deg, 40.5247 * u.deg))
    """
    if not isinstance(location, EarthLocation):
        raise TypeError(
            f"{name} must be an astropy EarthLocation, got {type(location).__name__}; "
            "build one with EarthLocation.from_geocentric(x, y, z, unit=u.m) or "
            "EarthLocation.from_geodetic(lon, lat, height)"
        )
    return location


def as_time(obstime):
    """Coerce ``obstime`` to `~astropy.time.Time`.

    Parameters
    ----------
    obstime : `~astropy.time.Time` or str or sequence of str
        Epoch(s) of observation; anything else `~astropy.time.Time` parses
        without a ``format`` argument (ISO strings, `datetime.datetime`).

    Returns
    -------
    `~astropy.time.Time`

    Raises
    ------
    TypeError
        If ``obstime`` cannot be read as a time.

    Examples
    --------
    >>> from astropy_feedrot.frames import as_time
    >>> as_time("2023-01-25T08:00").isot
    '2023-01-25T08:00:00.000'
    """
    if isinstance(obstime, Time):
        return obstime
    try:
        return Time(obstime)
    except Exception as exc:
        raise TypeError(
            f"obstime must be an astropy Time (or ISO strings that Time() reads), "
            f"got {type(obstime).__name__}: {exc}"
        ) from None


def as_skycoord(target):
    """Coerce a celestial ``target`` to `~astropy.coordinates.SkyCoord`.

    Parameters
    ----------
    target : `~astropy.coordinates.SkyCoord` or coordinate frame with data
        The observed direction, in any celestial frame.

    Returns
    -------
    `~astropy.coordinates.SkyCoord`

    Raises
    ------
    TypeError
        If ``target`` is not a coordinate.
    ValueError
        If ``target`` is a frame without coordinate data.

    Examples
    --------
    >>> from astropy_feedrot.frames import as_skycoord
    >>> as_skycoord(SkyCoord("03h19m48.16s +41d30m42.1s")).shape
    ()
    """
    if isinstance(target, SkyCoord):
        return target
    if isinstance(target, BaseCoordinateFrame):
        if not target.has_data:
            raise ValueError(
                f"target is a {type(target).__name__} frame without a direction; "
                "give coordinates, e.g. SkyCoord(ra=..., dec=..., frame='icrs')"
            )
        return SkyCoord(target)
    raise TypeError(
        f"target must be an astropy SkyCoord (or a coordinate frame with data), got "
        f"{type(target).__name__}; e.g. SkyCoord('03h19m48.16s +41d30m42.1s')"
    )


def broadcast_shape(**shapes):
    """Broadcast named shapes, naming them all when they do not fit.

    Parameters
    ----------
    **shapes : tuple of int
        The shapes, keyed by the name of the argument they belong to.

    Returns
    -------
    tuple of int
        The broadcast shape.

    Raises
    ------
    ValueError
        If the shapes do not broadcast.

    Examples
    --------
    >>> from astropy_feedrot.frames import broadcast_shape
    >>> broadcast_shape(target=(3, 1), obstime=(24,))
    (3, 24)
    """
    try:
        return np.broadcast_shapes(*shapes.values())
    except ValueError:
        described = ", ".join(f"{key} has shape {value}" for key, value in shapes.items())
        raise ValueError(
            f"shapes do not broadcast: {described}; add axes so that they do, e.g. "
            "target[:, np.newaxis] for every target at every time"
        ) from None


def local_frame(location, vertical="geodetic"):
    """East, north and up unit vectors of a site in ITRS.

    Parameters
    ----------
    location : `~astropy.coordinates.EarthLocation`
        The site (scalar or array).
    vertical : {'geodetic', 'geocentric'}, optional
        ``'geodetic'`` (default) takes *up* as the normal of the WGS84
        ellipsoid, the vertical of a levelled antenna and the one astropy's
        `~astropy.coordinates.AltAz` uses. ``'geocentric'`` takes the
        direction from the geocentre, :math:`r_\\mathrm{ant}/|r_\\mathrm{ant}|`
        as printed in Eq 28; the two differ by up to 0.19 deg at mid-latitudes.

    Returns
    -------
    LocalFrame
        Named tuple ``(east, north, up)`` of ``(..., 3)`` arrays, right-handed
        (``east x north = up``), with north in the plane of ``up`` and the
        pole ``z`` (Eq 28).

    Raises
    ------
    ValueError
        For an unknown ``vertical``.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from astropy_feedrot.frames import local_frame
    >>> site = EarthLocation.from_geodetic(0 * u.deg, 45 * u.deg)
    >>> local_frame(site).up  # doctest: +FLOAT_CMP
    array([0.70710678, 0.        , 0.70710678])
    """
    location = as_location(location)
    if vertical not in VERTICALS:
        raise ValueError(f"vertical must be one of {VERTICALS}, got {vertical!r}")
    lon = location.geodetic.lon.to_value(u.rad)
    if vertical == "geodetic":
        lat = location.to_geodetic("WGS84").lat.to_value(u.rad)
    else:
        xyz = location.get_itrs().cartesian.xyz.to_value(u.m)
        lat = np.arctan2(xyz[2], np.hypot(xyz[0], xyz[1]))
    clat, slat = np.cos(lat), np.sin(lat)
    clon, slon = np.cos(lon), np.sin(lon)
    east = np.stack([-slon, clon, np.zeros_like(lon)], axis=-1)
    north = np.stack([-slat * clon, -slat * slon, clat], axis=-1)
    up = np.stack([clat * clon, clat * slon, slat], axis=-1)
    return LocalFrame(east, north, up)


def horizontal(s, local):
    """Azimuth and elevation of directions above a site's horizon.

    Parameters
    ----------
    s : ndarray, shape (..., 3)
        Unit direction vectors in ITRS.
    local : LocalFrame
        East, north and up vectors of the site.

    Returns
    -------
    azimuth, elevation : ndarray, shape (...)
        In radians: azimuth from north through east in [0, 2 pi), elevation
        above the plane normal to ``local.up``.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.frames import LocalFrame, horizontal
    >>> az, el = horizontal(np.array([1.0, 0.0, 1.0]) / np.sqrt(2), LocalFrame(*np.eye(3)))
    >>> np.degrees([az, el])  # doctest: +FLOAT_CMP
    array([90., 45.])
    """
    azimuth = np.mod(np.arctan2(dot(s, local.east), dot(s, local.north)), 2 * np.pi)
    elevation = np.arcsin(np.clip(dot(s, local.up), -1.0, 1.0))
    return azimuth, elevation


def _itrs_xyz(coord):
    """Cartesian ITRS components of a coordinate as a (..., 3) array."""
    return np.moveaxis(coord.cartesian.xyz.value, 0, -1)


def source_direction(target, location, obstime):
    """Topocentric direction of a celestial target in ITRS (Eq 2).

    Parameters
    ----------
    target : `~astropy.coordinates.SkyCoord`
        Natural source(s), in any celestial frame; a distance, if given, is
        used for the parallax. A target already in `~astropy.coordinates.ITRS`
        is taken as it is (positions are differenced with the site, without
        the aberration a route through celestial frames would add).
    location : `~astropy.coordinates.EarthLocation`
        The observing site (scalar).
    obstime : `~astropy.time.Time`
        Epoch(s) of observation.

    Returns
    -------
    ndarray, shape (..., 3)
        The apparent topocentric unit vector :math:`\\hat{s}` (receiver to
        source) in ITRS, with the broadcast shape of ``target`` and
        ``obstime``. It includes precession-nutation, aberration and light
        deflection, UT1 and polar motion (astropy's ``ITRS(location=...)``
        frame) and agrees with astropy's `~astropy.coordinates.HADec` and
        `~astropy.coordinates.AltAz` far below 1 mas. No refraction.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.frames import source_direction
    >>> site = EarthLocation.from_geocentric(4075659.180, 931824.551, 4801516.102, u.m)
    >>> s = source_direction(SkyCoord(ra=49.95 * u.deg, dec=41.51 * u.deg), site,
    ...                      Time("2023-01-25T20:00") + [0, 6] * u.hour)
    >>> s.shape
    (2, 3)
    """
    target = as_skycoord(target)
    location = as_location(location)
    obstime = as_time(obstime)
    shape = broadcast_shape(target=target.shape, obstime=obstime.shape)
    if isinstance(target.frame, ITRS):
        xyz = _earth_fixed_offset(target, location)
    elif _fast_path_applies(target, obstime, shape):
        with iers_context(obstime):  # one check of the tables for all the nodes
            return _interpolated_direction(target, location, obstime, shape)
    else:
        # NaN coordinates propagate as NaN; ERFA's ufuncs need not warn about them.
        with iers_context(obstime), np.errstate(invalid="ignore"):
            itrs = ITRS(obstime=obstime, location=location)
            xyz = _itrs_xyz(target.transform_to(itrs))
    return np.broadcast_to(unit(xyz), shape + (3,))


#: Celestial frames whose transformation to ICRS does not depend on the time
#: of observation (their own equinox or obstime attributes are fixed).
FIXED_FRAMES = (ICRS, FK5, FK4, FK4NoETerms, Galactic, Supergalactic,
                BarycentricMeanEcliptic, BarycentricTrueEcliptic)

# Below this many epochs the exact nodes of the fast path cost as much as the
# rigorous transformation at every epoch.
_FAST_PATH_MIN_EPOCHS = 16

# Nearer sources have a diurnal parallax the cubic interpolation would not
# follow to 0.1 mas (1 au: 8.8 arcsec, interpolated to 0.007 mas).
_FAST_PATH_MIN_DISTANCE = 1 * u.au


def _fast_path_applies(target, obstime, shape):
    """Whether `source_direction` may interpolate Earth orientation (see `earth`)."""
    if not conf.fast_path or obstime.size < _FAST_PATH_MIN_EPOCHS:
        return False
    if not isinstance(target.frame, FIXED_FRAMES) or target.data.differentials:
        return False
    if not isinstance(target.data, UnitSphericalRepresentation):
        distance = target.spherical.distance
        if distance.unit.physical_type != "length" or not np.all(
                np.abs(distance) >= _FAST_PATH_MIN_DISTANCE):
            return False
    # Targets and epochs must pair as an outer product (or a single target).
    return int(np.prod(shape)) == target.size * obstime.size


def _interpolated_direction(target, location, obstime, shape):
    from .earth import EarthOrientation

    orientation = EarthOrientation(obstime, step=conf.fast_path_step * u.min)
    s = orientation.source_directions(target.icrs, location)
    if target.size == 1:
        return np.broadcast_to(s.reshape(obstime.shape + (3,)), shape + (3,))
    full = s.reshape(target.size, obstime.size, 3)
    t_index, o_index = np.broadcast_arrays(np.arange(target.size).reshape(target.shape),
                                           np.arange(obstime.size).reshape(obstime.shape))
    return full[t_index, o_index]


def _earth_fixed_offset(target, location):
    """Vector from the site to an ITRS target, or its direction if distance-less.

    An ITRS direction without distance (unit sphere) is a source at infinity
    and is returned as it is; a position is differenced with the site (Eq 2),
    which keeps satellites free of the aberration astropy's route through
    celestial frames would add.
    """
    if target.cartesian.x.unit == u.one:
        return _itrs_xyz(target)
    xyz = np.moveaxis(target.cartesian.xyz.to_value(u.m), 0, -1)
    if target.frame.location is not None:  # topocentric ITRS: back to geocentric
        xyz = xyz + location_xyz(target.frame.location)
    return xyz - location_xyz(location)


def location_xyz(location):
    """Geocentric ITRS position of a site in metres.

    Parameters
    ----------
    location : `~astropy.coordinates.EarthLocation`
        The site (scalar or array).

    Returns
    -------
    ndarray, shape location.shape + (3,)

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from astropy_feedrot.frames import location_xyz
    >>> location_xyz(EarthLocation.from_geocentric(1.0, 2.0, 3.0, unit=u.km))
    array([1000., 2000., 3000.])
    """
    return np.stack([c.to_value(u.m) for c in location.to_geocentric()], axis=-1)
