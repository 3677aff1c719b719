# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Checks and coercions of the user's inputs: times, sites, targets, shapes.

The bottom layer of the package: every other module may import it, and it
imports nothing from the package. Each function either returns the input as
the astropy object the rest of the package computes with, or raises at once
with a message that says what was wrong and how to fix it.
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import (
    CIRS,
    GCRS,
    ITRS,
    TEME,
    TETE,
    AltAz,
    BaseCoordinateFrame,
    EarthLocation,
    HADec,
    PrecessedGeocentric,
    SkyCoord,
    UnitSphericalRepresentation,
)
from astropy.time import Time, TimeDelta
from astropy.utils.masked import Masked

__all__ = ["as_location", "as_time", "as_skycoord", "as_radians", "broadcast_shape",
           "MIN_GEOCENTRIC_DISTANCE"]

#: A target with a distance closer to the geocentre than this is inside the Earth
#: (the polar radius is 6,357 km): refused, as kilometres read as metres would be.
MIN_GEOCENTRIC_DISTANCE = 6.3e6 * u.m

# Frames whose origin is the geocentre, where a distance is a geocentric radius.
_GEOCENTRIC = (GCRS, CIRS, TETE, TEME, PrecessedGeocentric, ITRS)

# Frames of a site's sky: a direction there depends on the epoch.
_OBSERVED = (AltAz, HADec)

# The epochs of an observed-frame target and of the observation agree within this.
_SAME_EPOCH = 1 * u.us


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
    >>> from astropy_feedrot.core.inputs import as_location
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
        without a ``format`` argument (ISO strings, `datetime.datetime`), or
        an `~astropy_feedrot.earth.epochs.Epochs` (its time is returned).

    Returns
    -------
    `~astropy.time.Time`

    Raises
    ------
    TypeError
        If ``obstime`` cannot be read as a time: plain numbers (their format,
        MJD, JD or seconds, cannot be guessed), a `~astropy.time.TimeDelta`
        (a duration, not an epoch) or unreadable strings.

    Notes
    -----
    A masked `~astropy.time.Time` is returned as it is; see
    `~astropy_feedrot.earth.frames.fill_masked`.

    Examples
    --------
    >>> from astropy_feedrot.core.inputs import as_time
    >>> as_time("2023-01-25T08:00").isot
    '2023-01-25T08:00:00.000'
    """
    if isinstance(obstime, Time):
        return obstime
    if getattr(type(obstime), "holds_epochs", False):  # an astropy_feedrot.Epochs
        return obstime.epochs_time
    if isinstance(obstime, TimeDelta):
        raise TypeError(
            "obstime must be an astropy Time (an epoch), got a TimeDelta (a duration); "
            "add it to a start epoch, e.g. Time('2023-01-25T08:00') + offsets"
        )
    if isinstance(obstime, u.Quantity):
        raise TypeError(
            f"obstime must be an astropy Time, got a Quantity in {obstime.unit}; "
            "add durations to a start epoch, e.g. Time('2023-01-25T08:00') + offsets"
        )
    try:
        kind = "U" if isinstance(obstime, str) else np.asarray(obstime).dtype.kind
    except ValueError:  # ragged nested sequences
        kind = "O"
    if kind in "biufc":
        raise TypeError(
            f"obstime must be an astropy Time (or ISO strings that Time() reads), "
            f"got {type(obstime).__name__} of plain numbers; their format cannot be "
            "guessed: say it, e.g. Time(values, format='mjd', scale='utc')"
        )
    try:
        return Time(obstime)
    except Exception as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise TypeError(
            f"obstime must be an astropy Time (or ISO strings that Time() reads), "
            f"got {type(obstime).__name__}: {reason}"
        ) from None


def as_skycoord(target, obstime=None):
    """Coerce a celestial ``target`` to `~astropy.coordinates.SkyCoord`, in one step.

    Parameters
    ----------
    target : `~astropy.coordinates.SkyCoord` or coordinate frame with data
        The observed direction (or position), in any frame.
    obstime : `~astropy.time.Time`, optional
        The epochs of observation, if known: an `~astropy.coordinates.AltAz`
        or `~astropy.coordinates.HADec` target must be at these epochs.

    Returns
    -------
    `~astropy.coordinates.SkyCoord`
        The target; one with a proper motion or radial velocity in a frame
        that depends on time (FK4, GCRS...) is returned in ICRS, with its
        motion and catalogue epoch, since astropy moves positions in time
        only in frames that do not.

    Raises
    ------
    TypeError
        If ``target`` is not a coordinate.
    ValueError
        If ``target`` is a frame without coordinate data; an AltAz or HADec
        target without an ``obstime``, or with one other than the epochs of
        observation; a position closer to the geocentre than
        `MIN_GEOCENTRIC_DISTANCE` (inside the Earth) in a geocentric frame.

    Notes
    -----
    One rule for targets in Earth-bound frames: an `~astropy.coordinates.ITRS`
    target is fixed on the Earth (a position, or a direction, that turns with
    it); an AltAz or HADec target is where astropy puts it at its own
    ``obstime``, which must therefore be the epochs of observation, where
    both readings agree. Anything else is ambiguous and refused: give a
    direction fixed in the sky as ICRS (``target.icrs``), one fixed on the
    Earth as ITRS (``target.itrs``).

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import AltAz, EarthLocation
    >>> from astropy_feedrot.core.inputs import as_skycoord
    >>> as_skycoord(SkyCoord("03h19m48.16s +41d30m42.1s")).shape
    ()
    >>> site = EarthLocation.from_geodetic(6.88 * u.deg, 50.52 * u.deg, 416 * u.m)
    >>> as_skycoord(SkyCoord(AltAz(az=30 * u.deg, alt=40 * u.deg, location=site)))
    Traceback (most recent call last):
    ...
    ValueError: target is in AltAz without an obstime: ...
    """
    if isinstance(target, SkyCoord):
        coord = target
    elif isinstance(target, BaseCoordinateFrame):
        if not target.has_data:
            raise ValueError(
                f"target is a {type(target).__name__} frame without a direction; "
                "give coordinates, e.g. SkyCoord(ra=..., dec=..., frame='icrs')"
            )
        coord = SkyCoord(target)
    else:
        raise TypeError(
            f"target must be an astropy SkyCoord (or a coordinate frame with data), got "
            f"{type(target).__name__}; e.g. SkyCoord('03h19m48.16s +41d30m42.1s')"
        )
    frame = coord.frame
    name = type(frame).__name__
    if isinstance(frame, _OBSERVED):
        if frame.obstime is None:
            raise ValueError(
                f"target is in {name} without an obstime: the {name} of a direction changes "
                f"with time (astropy refuses to transform it too); give {name}(..., "
                "obstime=<the epochs of observation>), or the direction as ICRS (fixed in "
                "the sky) or ITRS (fixed on the Earth)")
        if obstime is not None and not _same_epochs(frame.obstime, obstime):
            raise ValueError(
                f"target is in {name} at obstime {_describe(frame.obstime)}, not at the "
                f"epochs of observation ({_describe(obstime)}): whether its {name} "
                "direction should stay fixed on the Earth or follow the sky is ambiguous; "
                "give target.icrs for a direction fixed in the sky, target.itrs for one "
                "fixed on the Earth")
    if isinstance(frame, _GEOCENTRIC) and not _topocentric(frame):
        _check_outside_the_earth(coord, name)
    if coord.data.differentials and not isinstance(frame, (ITRS,) + _OBSERVED) \
            and "obstime" in frame.frame_attributes and name != "ICRS":
        try:
            coord = coord.icrs
        except Exception as error:  # astropy's reason, on one line
            raise ValueError(
                f"target in {name} has a proper motion or radial velocity that astropy "
                f"cannot carry to ICRS ({type(error).__name__}: {str(error).splitlines()[0]}"
                "); give it in ICRS, or drop the motion") from None
    return coord


def _topocentric(frame):
    """Whether an ITRS frame has its origin at a site rather than the geocentre."""
    location = getattr(frame, "location", None)
    if location is None:
        return False
    return bool(np.any(u.Quantity([location.x, location.y, location.z]) != 0))


def _same_epochs(epochs, obstime):
    """Whether two Time arrays broadcast and agree element-wise within _SAME_EPOCH."""
    try:
        difference = np.abs((epochs - as_time(obstime)).to(u.s))
    except ValueError:  # shapes that do not broadcast
        return False
    return bool(np.all(difference < _SAME_EPOCH))


def _describe(epochs):
    """The epochs, or their first and last, in ISO format."""
    if epochs.isscalar:
        return epochs.isot
    if epochs.size == 0:
        return "no epochs"
    flat = epochs.ravel()
    return f"{flat[0].isot} ... {flat[-1].isot}, shape {epochs.shape}"


def _check_outside_the_earth(coord, name):
    data = coord.data
    if isinstance(data, UnitSphericalRepresentation) or data.to_cartesian().x.unit == u.one:
        return  # a direction
    cartesian = data.to_cartesian()
    if cartesian.x.unit.physical_type != "length":
        return
    with np.errstate(invalid="ignore"):
        radius = cartesian.norm().to(u.m)
        inside = radius < MIN_GEOCENTRIC_DISTANCE  # False for NaN
    if np.any(inside):
        where = np.argwhere(np.atleast_1d(inside))[0]
        value = np.atleast_1d(radius)[tuple(where)]
        at = "" if coord.isscalar else f"[{', '.join(str(int(i)) for i in where)}]"
        raise ValueError(
            f"target{at} in {name} is {value.to_value(u.km):.0f} km from the geocentre, inside "
            "the Earth; a position needs its distance from the geocentre (kilometres given "
            "as metres?), a direction no distance at all")


def as_radians(value, name):
    """An angle as a float array in radians, NaN where masked.

    Parameters
    ----------
    value : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        An angle of any shape, possibly an astropy `~astropy.utils.masked.Masked`
        quantity.
    name : str
        The argument's name, for the error messages.

    Returns
    -------
    `~numpy.ndarray`
        The angle in radians, of the input's shape (0-d for a scalar), NaN
        where the input was masked.

    Raises
    ------
    TypeError
        If ``value`` is not a Quantity: plain numbers are refused, because
        degrees and radians cannot be told apart.
    astropy.units.UnitsError
        If its unit is not an angle.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.core.inputs import as_radians
    >>> as_radians([0, 90] * u.deg, "angle")  # doctest: +FLOAT_CMP
    array([0.        , 1.57079633])
    >>> as_radians(30, "feed_rotation")
    Traceback (most recent call last):
    ...
    TypeError: feed_rotation must be an angle Quantity or Angle (e.g. 30 * u.deg), got int; ...
    """
    mask = None
    if isinstance(value, Masked):
        mask = np.array(value.mask, dtype=bool)
        value = value.unmasked
    if not isinstance(value, u.Quantity):
        raise TypeError(
            f"{name} must be an angle Quantity or Angle (e.g. 30 * u.deg), got "
            f"{type(value).__name__}; plain numbers are refused because degrees and "
            "radians cannot be told apart"
        )
    if value.unit.physical_type != "angle":
        raise u.UnitsError(
            f"{name} must be an angle (e.g. in deg or rad), got a quantity in "
            f"{value.unit.to_string() or 'dimensionless units'}; attach an angle unit, "
            "e.g. value * u.rad"
        )
    radians = np.asarray(value.to_value(u.rad), dtype=float)
    return radians if mask is None else np.where(mask, np.nan, radians)


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
    >>> from astropy_feedrot.core.inputs import broadcast_shape
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
