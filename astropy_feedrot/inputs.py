# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Checks and coercions of the user's inputs: times, sites, targets, shapes.

The bottom layer of the package: every other module may import it, and it
imports nothing from the package. Each function either returns the input as
the astropy object the rest of the package computes with, or raises at once
with a message that says what was wrong and how to fix it.
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import BaseCoordinateFrame, EarthLocation, SkyCoord
from astropy.time import Time, TimeDelta

__all__ = ["as_location", "as_time", "as_skycoord", "broadcast_shape"]


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
    >>> from astropy_feedrot.inputs import as_location
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
        an `~astropy_feedrot.epochs.Epochs` (its time is returned).

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
    `~astropy_feedrot.frames.fill_masked`.

    Examples
    --------
    >>> from astropy_feedrot.inputs import as_time
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
    >>> from astropy_feedrot.inputs import as_skycoord
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
    >>> from astropy_feedrot.inputs import broadcast_shape
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
