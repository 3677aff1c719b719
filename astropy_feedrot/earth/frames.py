# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""From astropy objects to Earth-fixed unit vectors.

This is the only module that turns `~astropy.time.Time`,
`~astropy.coordinates.EarthLocation` and `~astropy.coordinates.SkyCoord` into
the plain ``(..., 3)`` arrays of the geometry kernel. All vectors are in the
Earth-fixed ITRS, in which the north celestial pole of the paper is
``z = [0, 0, 1]`` (Appendix D).

The transformations go through astropy, i.e. ERFA with precession-nutation,
UT1-UTC and polar motion from the IERS tables bundled with astropy; see
`~astropy_feedrot.earth.eop.iers_context` for how downloads are kept off and what
happens beyond the tables.
"""

import warnings
from typing import NamedTuple

import erfa
import numpy as np
from astropy import units as u
from astropy.coordinates import ITRS, SkyCoord

from ..core.inputs import as_location, as_skycoord, as_time, broadcast_shape
from ..core.kernel import dot, unit
from .eop import iers_context
from .epochs import as_epochs, fill_masked

__all__ = [
    "LocalFrame",
    "VERTICALS",
    "STATION_HEIGHTS",
    "as_location",
    "as_time",
    "as_skycoord",
    "as_elevation_limit",
    "broadcast_shape",
    "at_epochs",
    "check_station_xyz",
    "fill_masked",
    "time_axis",
    "horizontal",
    "local_frame",
    "location_xyz",
    "source_direction",
]

#: Accepted definitions of the local vertical: the ellipsoid normal or the
#: geocentric direction (see `local_frame`).
VERTICALS = ("geodetic", "geocentric")

#: Geodetic heights (metres above the WGS84 ellipsoid) between which a
#: position is taken as an Earth station. The lowest covers the deepest places
#: people have put instruments (the Challenger Deep, 10.9 km below the sea,
#: and deep mines, 4 km) with margin; the highest covers aircraft and
#: stratospheric balloons (below 55 km) up to the Karman line at 100 km, above
#: which an antenna is a spacecraft. A position outside is almost always in
#: the wrong unit (kilometres read as metres put a station near the geocentre).
STATION_HEIGHTS = (-12e3, 100e3)


class LocalFrame(NamedTuple):
    """The local east, north and up unit vectors of a site, in ITRS.

    Each field is an ndarray of shape ``(..., 3)`` (the shape of the location
    plus a last axis of 3).

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from astropy_feedrot.earth.frames import local_frame
    >>> frame = local_frame(EarthLocation.from_geodetic(0 * u.deg, 0 * u.deg, 0 * u.m))
    >>> frame.up.round(12) + 0.0, frame.east.round(12) + 0.0
    (array([1., 0., 0.]), array([0., 1., 0.]))
    """

    east: np.ndarray
    north: np.ndarray
    up: np.ndarray


def time_axis(obstime_shape, shape):
    """The axis of a broadcast shape along which the epochs run.

    Parameters
    ----------
    obstime_shape : tuple of int
        Shape of the epochs.
    shape : tuple of int
        The broadcast shape of a result (epochs with targets, or angles).

    Returns
    -------
    int or None
        The index (in ``shape``, counted from 0) of the one axis along which
        ``obstime`` has more than one epoch, aligned as numpy broadcasts
        (trailing axes first); None for a single epoch, where each element is
        a series of one sample.

    Raises
    ------
    ValueError
        If the epochs do not broadcast to ``shape`` without enlarging it, or
        run along more than one axis (which of them is time would be a guess).

    Examples
    --------
    Epochs of shape (T,) with sources of shape (S, 1) run along the last axis;
    epochs of shape (T, 1) with sources of shape (S,) along the first:

    >>> from astropy_feedrot.earth.frames import time_axis
    >>> time_axis((24,), (3, 24))
    1
    >>> time_axis((24, 1), (24, 3))
    0
    >>> time_axis((), (3,)) is None
    True
    """
    obstime_shape, shape = tuple(obstime_shape), tuple(shape)
    if len(obstime_shape) > len(shape) or broadcast_shape(
            obstime=obstime_shape, angles=shape) != shape:
        raise ValueError(f"obstime has shape {obstime_shape}, which does not broadcast to "
                         f"the shape {shape} of the series without enlarging it")
    aligned = (1,) * (len(shape) - len(obstime_shape)) + obstime_shape
    varying = [k for k, n in enumerate(aligned) if n > 1]
    if len(varying) > 1:
        raise ValueError(
            f"obstime of shape {obstime_shape} runs along axes {varying} of the shape "
            f"{shape}; a continuous series needs the epochs along one axis: give obstime "
            "of shape (T,) and targets of shape (S, 1), or compute one series at a time"
        )
    return varying[0] if varying else None


def as_elevation_limit(min_elevation, name="min_elevation"):
    """Check an elevation limit and return it in radians.

    Parameters
    ----------
    min_elevation : `~astropy.units.Quantity` or None
        A single angle in [-90, 90] deg, or None for no limit.
    name : str, optional
        How to call it in error messages.

    Returns
    -------
    float or None
        The limit in radians (None for None).

    Raises
    ------
    TypeError
        If it is a plain number (degrees and radians cannot be told apart) or
        not a number at all.
    astropy.units.UnitsError
        If its unit is not an angle.
    ValueError
        If it is not a single value, is NaN or infinite, or lies outside
        [-90, 90] deg.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.earth.frames import as_elevation_limit
    >>> as_elevation_limit(30 * u.deg)  # doctest: +FLOAT_CMP
    0.5235987755982988
    """
    if min_elevation is None:
        return None
    if not isinstance(min_elevation, u.Quantity):
        raise TypeError(
            f"{name} must be an angle Quantity (e.g. 10 * u.deg) or None, got "
            f"{type(min_elevation).__name__} {min_elevation!r}; plain numbers are refused "
            "because degrees and radians cannot be told apart"
        )
    if min_elevation.unit.physical_type != "angle":
        raise u.UnitsError(f"{name} must be an angle (e.g. 10 * u.deg), got a quantity in "
                           f"{min_elevation.unit.to_string() or 'dimensionless units'}")
    if not min_elevation.isscalar:
        raise ValueError(f"{name} must be a single angle, got shape {min_elevation.shape}")
    degrees = float(min_elevation.to_value(u.deg))
    if not -90 <= degrees <= 90:  # also False for NaN
        raise ValueError(f"{name} must be within [-90, 90] deg, got {min_elevation}")
    return float(np.radians(degrees))


def _index(where):
    """``[i, j]`` for a non-empty index tuple, nothing for a scalar."""
    return f"[{', '.join(str(int(i)) for i in where)}]" if where else ""


def check_station_xyz(xyz, name="location"):
    """Check that geocentric positions (metres) are on or near the Earth's surface.

    Parameters
    ----------
    xyz : array-like, shape (..., 3)
        Geocentric ITRS positions in metres.
    name : str, optional
        How to call them in error messages.

    Returns
    -------
    ndarray, shape (..., 3)
        The positions as floats.

    Raises
    ------
    ValueError
        If a coordinate is NaN or infinite, or a geodetic height (WGS84) is
        outside `STATION_HEIGHTS`: the geocentre, coordinates in kilometres,
        a satellite.

    Examples
    --------
    >>> from astropy_feedrot.earth.frames import check_station_xyz
    >>> check_station_xyz([4075659.180, 931824.551, 4801516.102]).shape
    (3,)
    >>> check_station_xyz([4075.659, 931.825, 4801.516])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: location is 6367 m from the geocentre, at a geodetic height of ... km; ...
    """
    xyz = np.asarray(xyz, dtype=float)
    if xyz.ndim == 0 or xyz.shape[-1] != 3:
        raise ValueError(f"{name} must be geocentric x, y, z, got shape {xyz.shape}")
    finite = np.all(np.isfinite(xyz), axis=-1)
    if not np.all(finite):
        where = tuple(np.argwhere(~finite)[0])
        raise ValueError(f"{name}{_index(where)} has a NaN or infinite coordinate: "
                         f"{xyz[where].tolist()}; give finite geocentric coordinates")
    with np.errstate(all="ignore"):  # ERFA overflows far from the Earth: NaN, refused below
        height = erfa.gc2gd(1, xyz)[2]  # 1: WGS84
    low, high = STATION_HEIGHTS
    bad = ~((height >= low) & (height <= high))  # NaN where ERFA overflows: bad too
    if np.any(bad):
        where = tuple(np.argwhere(bad)[0])
        which = _index(where)
        radius = float(np.linalg.norm(xyz[where]))
        raise ValueError(
            f"{name}{which} is {radius:.0f} m from the geocentre, at a geodetic height of "
            f"{float(height[where]) / 1e3:.1f} km; an Earth station lies between "
            f"{low / 1e3:.0f} and {high / 1e3:.0f} km from the WGS84 ellipsoid (are the "
            "coordinates in metres?)"
        )
    return xyz


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
    >>> from astropy_feedrot.earth.frames import local_frame
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
    >>> from astropy_feedrot.earth.frames import LocalFrame, horizontal
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
    >>> from astropy_feedrot.earth.frames import source_direction
    >>> site = EarthLocation.from_geocentric(4075659.180, 931824.551, 4801516.102, u.m)
    >>> s = source_direction(SkyCoord(ra=49.95 * u.deg, dec=41.51 * u.deg), site,
    ...                      Time("2023-01-25T20:00") + [0, 6] * u.hour)
    >>> s.shape
    (2, 3)
    """
    location = as_location(location)
    epochs = as_epochs(obstime)
    masked = epochs.mask
    target = as_skycoord(target, epochs.filled)
    shape = broadcast_shape(target=target.shape, obstime=epochs.shape)
    if 0 in shape:  # nothing to compute (astropy 6.0 fails on empty epochs)
        return np.empty(shape + (3,))
    if masked is not None and masked.all():
        return np.full(shape + (3,), np.nan)
    s = _apparent_direction(at_epochs(target, epochs.filled), location, epochs)
    if masked is None:
        return s
    return np.where(np.broadcast_to(masked, shape)[..., np.newaxis], np.nan, s)


def at_epochs(target, obstime):
    """A target moved to the epochs of observation by its space motion.

    Parameters
    ----------
    target : `~astropy.coordinates.SkyCoord`
        Natural source(s). With a proper motion or radial velocity, the
        position is the one at ``target.obstime`` (the catalogue epoch, e.g.
        J2015.5 for Gaia DR2), and it is moved to every epoch of ``obstime``
        with astropy's `~astropy.coordinates.SkyCoord.apply_space_motion`
        (ERFA ``pmsafe``; a target without distance is taken as very far).
        An `~astropy.coordinates.ITRS` target (a position at the epochs) and
        a target without space motion are returned as they are.
    obstime : `~astropy.time.Time`
        Epoch(s) of observation, unmasked.

    Returns
    -------
    `~astropy.coordinates.SkyCoord`
        Without velocities; for a moving target the positions at the
        broadcast shape of ``target`` and ``obstime``.

    Raises
    ------
    ValueError
        If the target moves but has no epoch (``obstime``) for its position.

    Examples
    --------
    Barnard's star (Gaia DR2: Gaia Collaboration, Brown et al. 2018, A&A 616,
    A1; epoch J2015.5) moves 10.4 arcsec a year:

    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.frames import at_epochs
    >>> barnard = SkyCoord(ra=269.452075 * u.deg, dec=4.693391 * u.deg,
    ...                    pm_ra_cosdec=-801.551 * u.mas / u.yr,
    ...                    pm_dec=10362.394 * u.mas / u.yr, distance=1.8266 * u.pc,
    ...                    radial_velocity=-110.6 * u.km / u.s,
    ...                    obstime=Time("J2015.5", scale="tcb"))
    >>> later = at_epochs(barnard, Time("J2025.5", scale="tcb"))
    >>> later.separation(barnard).to(u.arcsec)  # doctest: +FLOAT_CMP
    <Angle 103.99788719 arcsec>
    """
    target = as_skycoord(target)
    if isinstance(target.frame, ITRS) or not target.data.differentials:
        return target
    motion = next(iter(target.data.differentials.values()))
    static = SkyCoord(target.frame.realize_frame(target.data.without_differentials()))
    if all(np.all(getattr(motion, name) == 0) for name in motion.components):
        return static
    if target.obstime is None:
        raise ValueError(
            "target has a proper motion or radial velocity but no epoch for its position; "
            "give the catalogue epoch, e.g. SkyCoord(..., obstime=Time('J2015.5', "
            "scale='tcb')) for Gaia DR2, or drop the motion"
        )
    with warnings.catch_warnings():
        # A target without distance is taken as very distant, as ERFA says.
        warnings.filterwarnings("ignore", message=".*distance overridden",
                                category=erfa.ErfaWarning)
        moved = target.apply_space_motion(new_obstime=obstime)
    return SkyCoord(moved.frame.realize_frame(moved.data.without_differentials()))


def _apparent_direction(target, location, epochs):
    """`source_direction` for a target without space motion at `~astropy_feedrot.Epochs`."""
    obstime = epochs.filled
    shape = broadcast_shape(target=target.shape, obstime=obstime.shape)
    if isinstance(target.frame, ITRS):
        xyz = _earth_fixed_offset(target, location)
    elif _fast_path_applies(target, epochs, shape):
        return _interpolated_direction(target, location, epochs, shape)
    else:
        # NaN coordinates propagate as NaN; ERFA's ufuncs need not warn about them.
        with iers_context(obstime), np.errstate(invalid="ignore"):
            itrs = ITRS(obstime=obstime, location=location)
            xyz = _itrs_xyz(target.transform_to(itrs))
    return np.broadcast_to(unit(xyz), shape + (3,))


def _fast_path_applies(target, epochs, shape):
    """Whether `source_direction` takes the epochs' `~.orientation.EarthOrientation`.

    The rule is `~astropy_feedrot.earth.epochs.Epochs.uses_nodes`; ``shape`` is the
    shape of the result, which must pair every target with every epoch.
    """
    pairs = target.size == 1 or int(np.prod(shape)) == target.size * epochs.size
    return pairs and epochs.uses_nodes(target)


def _interpolated_direction(target, location, epochs, shape):
    obstime = epochs.filled
    s = epochs.orientation.source_directions(target.icrs, location)
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
    >>> from astropy_feedrot.earth.frames import location_xyz
    >>> location_xyz(EarthLocation.from_geocentric(1.0, 2.0, 3.0, unit=u.km))
    array([1000., 2000., 3000.])
    """
    return np.stack([c.to_value(u.m) for c in location.to_geocentric()], axis=-1)
