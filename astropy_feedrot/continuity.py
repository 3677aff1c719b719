# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Cycle continuity of feed-rotation series (Eq 9) and the rotation delay of a baseline."""

import warnings
from typing import NamedTuple

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle
from astropy.utils.exceptions import AstropyUserWarning

from . import kernel
from .frames import as_time, broadcast_shape

__all__ = ["ContinuityWarning", "unwrap", "RotationDelay", "rotation_delay"]

#: A step between consecutive samples larger than this (radians) cannot be
#: told apart from one of the opposite sign and a whole cycle (Sec. 2.1).
AMBIGUOUS_STEP = 0.9 * np.pi


class ContinuityWarning(AstropyUserWarning):
    """Consecutive samples differ by nearly half a cycle: the cycle count is ambiguous.

    Examples
    --------
    >>> from astropy_feedrot.continuity import ContinuityWarning
    >>> issubclass(ContinuityWarning, UserWarning)
    True
    """


def unwrap(angle, axis=-1, obstime=None, max_gap=None, mask=None):
    """Make a feed-rotation series continuous across cycle boundaries (Eq 9).

    Each sample is moved to the cycle nearest to the previous sample of its
    segment. A segment restarts (keeps its own first value, with no cycle
    carried over) after masked or NaN samples, and after a time gap longer
    than ``max_gap``.

    Parameters
    ----------
    angle : `~astropy.units.Quantity` or array-like
        Angles (radians if plain numbers).
    axis : int, optional
        The time axis.
    obstime : `~astropy.time.Time`, optional
        The epochs (broadcastable to ``angle``), needed with ``max_gap``.
    max_gap : `~astropy.units.Quantity`, optional
        Restart after a time step longer than this.
    mask : array-like of bool, optional
        True where a sample is to be left out (for example a satellite below
        an elevation limit); those samples become NaN.

    Returns
    -------
    `~astropy.coordinates.Angle`
        Same shape and unit as the input (radians for plain numbers).

    Raises
    ------
    ValueError
        If ``max_gap`` is given without ``obstime``, or shapes do not broadcast.

    Warns
    -----
    ContinuityWarning
        Once, if consecutive samples of a segment differ by more than
        0.9 x 180 deg: the series is sampled too coarsely to tell the cycle.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot import unwrap
    >>> unwrap([170, -170, -150] * u.deg)
    <Angle [170., 190., 210.] deg>
    >>> unwrap([170, -170, -150, -130] * u.deg, mask=[False, False, True, False])
    <Angle [ 170.,  190.,   nan, -130.] deg>
    """
    angle = u.Quantity(angle, u.rad) if not isinstance(angle, u.Quantity) else angle
    unit = angle.unit if angle.unit.physical_type == "angle" else u.rad
    values = np.array(angle.to_value(unit) * (1 * unit).to_value(u.rad), dtype=float, ndmin=1)
    shape = values.shape
    if mask is not None:
        values = np.where(np.broadcast_to(np.asarray(mask, dtype=bool), shape), np.nan, values)
    values = np.moveaxis(values, axis, -1)
    valid = np.isfinite(values)
    previous = np.concatenate([np.zeros(valid.shape[:-1] + (1,), bool), valid[..., :-1]], -1)
    start = valid & ~previous
    if max_gap is not None:
        if obstime is None:
            raise ValueError("max_gap needs obstime, the epochs along the time axis")
        obstime = as_time(obstime)
        seconds = (obstime - obstime.ravel()[0]).to_value(u.s)
        seconds = np.moveaxis(
            np.broadcast_to(seconds, broadcast_shape(angle=shape, obstime=obstime.shape)),
            axis, -1)
        step = np.diff(seconds, axis=-1, prepend=-np.inf)
        start |= valid & (step > u.Quantity(max_gap).to_value(u.s))
    index = np.arange(values.shape[-1])
    segment = np.maximum.accumulate(np.where(start, index, 0), axis=-1)
    # Eq 9 over the whole series, then cancel the cycles carried into each segment.
    cycles = np.nan_to_num(kernel.unwrap_phase(values, axis=-1) - values)
    cycles -= np.take_along_axis(cycles, segment, axis=-1)
    out = np.where(valid, values + cycles, np.nan)
    within = np.diff(segment, axis=-1) == 0
    ambiguous = (np.abs(np.diff(out, axis=-1)) > AMBIGUOUS_STEP) & within
    if np.any(ambiguous):
        warnings.warn(
            f"{np.count_nonzero(ambiguous)} consecutive steps exceed "
            f"{np.degrees(AMBIGUOUS_STEP):.0f} deg: the cycle count there is ambiguous; "
            "sample more densely or split the series with max_gap or mask",
            ContinuityWarning,
            stacklevel=2,
        )
    out = np.moveaxis(out, -1, axis).reshape(shape)
    if angle.ndim == 0:
        out = out[0]
    return Angle(out, u.rad).to(unit)


class RotationDelay(NamedTuple):
    """The rotation delay of a baseline and its ambiguity interval.

    Attributes
    ----------
    delay : `~astropy.units.Quantity`
        :math:`\\tau = (\\Phi_2 - \\Phi_1) / (2\\pi f)`, continuous along time,
        in picoseconds.
    ambiguity : `~astropy.units.Quantity`
        :math:`1/f`, the delay of one cycle, in picoseconds.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot import RotationDelay
    >>> RotationDelay([0.0, 12.5] * u.ps, 634.75 * u.ps).ambiguity
    <Quantity 634.75 ps>
    """

    delay: u.Quantity
    ambiguity: u.Quantity


def rotation_delay(antenna1, antenna2, target, obstime, frequency, polarization=None,
                   min_elevation=None, max_gap=None):
    """Delay caused by the difference of two antennas' feed rotations (Sec. 4.1).

    Parameters
    ----------
    antenna1, antenna2 : `~astropy_feedrot.Antenna`
        The baseline (the delay is antenna 2 minus antenna 1).
    target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
        What both observe.
    obstime : `~astropy.time.Time`
        Epochs; time must be the last axis of the broadcast shape.
    frequency : `~astropy.units.Quantity`
        Observing (sky) frequency, positive.
    polarization, min_elevation : optional
        As for `~astropy_feedrot.Antenna.feed_rotation`; an epoch is masked
        when the target is below ``min_elevation`` at either antenna.
    max_gap : `~astropy.units.Quantity`, optional
        Restart the continuous series after longer gaps (see `unwrap`).

    Returns
    -------
    RotationDelay
        ``(delay, ambiguity)``: the continuous delay in ps and the ambiguity
        interval :math:`1/f` in ps.

    Raises
    ------
    TypeError
        If an antenna is not an `~astropy_feedrot.Antenna`.
    ValueError
        If ``frequency`` is not positive.
    astropy.units.UnitsError
        If ``frequency`` is not a frequency.

    Examples
    --------
    The ambiguity interval at the GPS L1 frequency (Sec. 4.1: 634.8 ps):

    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot import Antenna, AltAzMount, StationaryMount, rotation_delay
    >>> fd = EarthLocation.from_geocentric(-1324009.454, -5332181.955, 3231962.369, u.m)
    >>> dbr = EarthLocation.from_geocentric(-1324070.478, -5332176.001, 3231921.799, u.m)
    >>> result = rotation_delay(Antenna(dbr, StationaryMount()), Antenna(fd, AltAzMount()),
    ...                         SkyCoord("03h19m48.16s +41d30m42.1s"),
    ...                         Time("2023-01-25T06:00") + [0, 1, 2] * u.hour,
    ...                         1575.42 * u.MHz)
    >>> result.ambiguity  # doctest: +FLOAT_CMP
    <Quantity 634.75136789 ps>
    """
    from .antenna import Antenna

    for name, antenna in (("antenna1", antenna1), ("antenna2", antenna2)):
        if not isinstance(antenna, Antenna):
            raise TypeError(f"{name} must be an Antenna, got {type(antenna).__name__}")
    f_hz = _frequency_hz(frequency)
    obstime = as_time(obstime)
    phi1 = antenna1.feed_rotation(target, obstime, polarization, min_elevation=min_elevation)
    phi2 = antenna2.feed_rotation(target, obstime, polarization, min_elevation=min_elevation)
    broadcast_shape(antenna1=phi1.shape, antenna2=phi2.shape)
    return _delay_of_difference(phi2 - phi1, f_hz, axis=-1, obstime=obstime, max_gap=max_gap)


def _frequency_hz(frequency):
    """A positive frequency (or wavelength) in Hz; ValueError otherwise."""
    frequency = u.Quantity(frequency)
    f_hz = frequency.to_value(u.Hz, equivalencies=u.spectral())
    if not np.all(f_hz > 0):
        raise ValueError(f"frequency must be positive, got {frequency}")
    return f_hz


def _delay_of_difference(difference, f_hz, axis=-1, obstime=None, max_gap=None):
    """`RotationDelay` of a feed-rotation difference, made continuous along ``axis``."""
    continuous = unwrap(u.Quantity(difference).to(u.rad), axis=axis, obstime=obstime,
                        max_gap=max_gap)
    delay = (continuous.to_value(u.rad) / (2 * np.pi * f_hz)) * u.s
    return RotationDelay(delay.to(u.ps), (1 / (f_hz * u.Hz)).to(u.ps))
