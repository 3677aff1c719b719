# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Cycle continuity of feed-rotation series (Eq 9) and the rotation delay of a baseline."""

import operator
from typing import NamedTuple

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle
from astropy.utils.exceptions import AstropyUserWarning
from astropy.utils.masked import Masked

from ..core import kernel
from ..core.exceptions import warn_caller
from ..earth.eop import iers_context
from ..earth.frames import as_time, broadcast_shape, fill_masked, time_axis
from .antenna import Antenna

__all__ = ["ContinuityWarning", "unwrap", "RotationDelay", "rotation_delay", "frequency_hz",
           "delay_of_difference"]

#: A step between consecutive samples larger than this (radians) cannot be
#: told apart from one of the opposite sign and a whole cycle (Sec. 2.1).
AMBIGUOUS_STEP = 0.9 * np.pi


class ContinuityWarning(AstropyUserWarning):
    """Consecutive samples differ by nearly half a cycle: the cycle count is ambiguous.

    Examples
    --------
    >>> from astropy_feedrot.engine.continuity import ContinuityWarning
    >>> issubclass(ContinuityWarning, UserWarning)
    True
    """


def _angle_values(angle):
    """Radians (float ndarray), the output unit and the input's own mask (or None)."""
    mask = None
    if isinstance(angle, Masked):  # astropy's masked arrays and quantities
        mask = np.array(angle.mask, dtype=bool)
        angle = angle.unmasked
    elif np.ma.isMaskedArray(angle):
        mask = np.ma.getmaskarray(angle)
        angle = np.ma.getdata(angle)
    if isinstance(angle, u.Quantity):
        if angle.unit.physical_type not in ("angle", "dimensionless"):
            raise u.UnitsError(
                f"angle must be an angle (e.g. in deg or rad), got a quantity in "
                f"{angle.unit}"
            )
        unit = angle.unit if angle.unit.physical_type == "angle" else u.rad
        radians = angle.to_value(u.rad, equivalencies=u.dimensionless_angles())
    else:
        unit = u.rad
        radians = np.asarray(angle)
        if radians.dtype.kind not in "biuf":
            try:
                radians = radians.astype(float)
            except (TypeError, ValueError):
                raise TypeError(
                    f"angle must be an angle Quantity or numbers (radians), got "
                    f"{type(angle).__name__} of dtype {radians.dtype}"
                ) from None
    return np.array(radians, dtype=float, ndmin=1), unit, mask


def _check_axis(axis, ndim):
    try:
        axis = operator.index(axis)
    except TypeError:
        raise TypeError(f"axis must be an integer, got {type(axis).__name__} "
                        f"{axis!r}") from None
    if not -ndim <= axis < ndim:
        raise ValueError(f"axis {axis} is out of range for angles with {ndim} "
                         f"dimension{'s' if ndim > 1 else ''}; give one of "
                         f"{-ndim}..{ndim - 1}")
    return axis % ndim


def _seconds_along(obstime, shape, axis):
    """Seconds of ``obstime`` broadcast to ``shape``, and its mask (or None).

    ValueError unless the epochs fit ``shape`` and run along ``axis`` only.
    """
    filled, masked = fill_masked(obstime)
    broadcast_shape(angle=shape, obstime=filled.shape)
    along = time_axis(filled.shape, shape)  # ValueError if several axes or larger
    if along is not None and along != axis:
        raise ValueError(
            f"obstime of shape {filled.shape} runs along axis {along} of the angles of "
            f"shape {shape}, but axis={axis}: pass axis={along}, or give obstime the "
            "shape of the time axis"
        )
    # Masked epochs hold the previous valid epoch (see fill_masked): no step back.
    seconds = (filled - filled.ravel()[0]).to_value(u.s) if filled.size else np.zeros(0)
    seconds = np.broadcast_to(seconds, shape)
    if masked is not None:
        masked = np.broadcast_to(masked, shape)
    if np.any(np.diff(seconds, axis=axis) < 0):
        raise ValueError("obstime decreases along the time axis; sort the series by time "
                         "first (a continuous series follows time)")
    return seconds, masked


def _gap_seconds(max_gap):
    if not isinstance(max_gap, u.Quantity):
        raise TypeError(f"max_gap must be a time Quantity (e.g. 5 * u.min), got "
                        f"{type(max_gap).__name__} {max_gap!r}")
    if max_gap.unit.physical_type != "time":
        raise u.UnitsError(f"max_gap must be a time (e.g. 5 * u.min), got a quantity in "
                           f"{max_gap.unit}")
    if not max_gap.isscalar or not max_gap.value > 0 or not np.isfinite(max_gap.value):
        raise ValueError(f"max_gap must be one positive finite time, got {max_gap}")
    return float(max_gap.to_value(u.s))


def unwrap(angle, axis=-1, obstime=None, max_gap=None, mask=None):
    """Make a feed-rotation series continuous across cycle boundaries (Eq 9).

    Each sample is moved to the cycle nearest to the previous sample of its
    segment. A segment restarts (keeps its own first value, with no cycle
    carried over) after masked or NaN samples, and after a time gap longer
    than ``max_gap``.

    Parameters
    ----------
    angle : `~astropy.units.Quantity` or array-like
        Angles (radians if plain numbers or dimensionless). A masked array
        (`numpy.ma.MaskedArray`, or astropy's masked
        `~astropy.utils.masked.Masked` quantities) has its masked samples
        left out as with ``mask``.
    axis : int, optional
        The time axis.
    obstime : `~astropy.time.Time`, optional
        The epochs, broadcastable to ``angle`` and running along ``axis``,
        never decreasing; needed with ``max_gap``. Masked epochs are left
        out as with ``mask``.
    max_gap : `~astropy.units.Quantity`, optional
        Restart after a time step longer than this.
    mask : array-like of bool, optional
        True where a sample is to be left out (for example a satellite below
        an elevation limit).

    Returns
    -------
    `~astropy.coordinates.Angle`
        Same shape and unit as the input (radians for plain numbers); NaN
        where a sample is NaN or left out (never a masked array), the series
        restarting after it.

    Raises
    ------
    TypeError
        If ``angle`` is not numbers or a quantity, ``axis`` not an integer,
        or ``obstime`` not a time.
    astropy.units.UnitsError
        If ``angle`` is a quantity but not an angle.
    ValueError
        If ``axis`` is out of range, ``max_gap`` is given without
        ``obstime``, ``obstime`` runs along another axis than ``axis`` or
        decreases, or shapes do not broadcast.

    Warns
    -----
    ContinuityWarning
        Once, if consecutive samples of a segment differ by more than
        0.9 x 180 deg: the series is sampled too coarsely to tell the cycle.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy_feedrot import unwrap
    >>> unwrap([170, -170, -150] * u.deg)
    <Angle [170., 190., 210.] deg>
    >>> unwrap([170, -170, -150, -130] * u.deg, mask=[False, False, True, False])
    <Angle [ 170.,  190.,   nan, -130.] deg>
    >>> unwrap(np.ma.masked_array(np.radians([170, -170, 10, -130]), mask=[0, 0, 1, 0]))
    <Angle [ 2.96705973,  3.31612558,         nan, -2.26892803] rad>
    """
    values, unit, own_mask = _angle_values(angle)
    shape = values.shape
    axis = _check_axis(axis, values.ndim)
    left_out = np.zeros(shape, dtype=bool)
    for name, given in (("angle's mask", own_mask), ("mask", mask)):
        if given is None:
            continue
        given = np.asarray(given)
        if given.dtype.kind not in "biu":
            raise TypeError(f"{name} must be booleans, got dtype {given.dtype}")
        broadcast_shape(angle=shape, mask=given.shape)
        left_out |= np.broadcast_to(given.astype(bool), shape)
    if max_gap is not None:
        if obstime is None:
            raise ValueError("max_gap needs obstime, the epochs along the time axis")
        max_gap = _gap_seconds(max_gap)
    seconds = None
    if obstime is not None:
        seconds, masked_epochs = _seconds_along(obstime, shape, axis)
        if masked_epochs is not None:
            left_out |= masked_epochs
    values = np.moveaxis(np.where(left_out, np.nan, values), axis, -1)
    valid = np.isfinite(values)
    previous = np.concatenate([np.zeros(valid.shape[:-1] + (1,), bool), valid[..., :-1]], -1)
    start = valid & ~previous
    if max_gap is not None:
        step = np.diff(np.moveaxis(seconds, axis, -1), axis=-1, prepend=-np.inf)
        start |= valid & (step > max_gap)
    index = np.arange(values.shape[-1])
    segment = np.maximum.accumulate(np.where(start, index, 0), axis=-1)
    # Eq 9 over the whole series, then cancel the cycles carried into each segment.
    cycles = np.nan_to_num(kernel.unwrap_phase(values, axis=-1) - values)
    cycles -= np.take_along_axis(cycles, segment, axis=-1)
    out = np.where(valid, values + cycles, np.nan)
    within = np.diff(segment, axis=-1) == 0
    ambiguous = (np.abs(np.diff(out, axis=-1)) > AMBIGUOUS_STEP) & within
    if np.any(ambiguous):
        warn_caller(
            f"{np.count_nonzero(ambiguous)} consecutive steps exceed "
            f"{np.degrees(AMBIGUOUS_STEP):.0f} deg: the cycle count there is ambiguous; "
            "sample more densely or split the series with max_gap or mask",
            ContinuityWarning,
        )
    out = np.moveaxis(out, -1, axis).reshape(shape)
    if np.ndim(angle) == 0:
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


@iers_context()  # one check of the Earth-orientation tables per call
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
        Epochs, never decreasing along the time axis; masked epochs give NaN
        and restart the series. The time axis is the one axis of the
        broadcast shape of ``target`` and ``obstime`` along which the epochs
        run (the last one for 1-d epochs, the first one for epochs of shape
        (T, 1) with targets of shape (S,)); with a single epoch each element
        is its own series and nothing is made continuous.
    frequency : `~astropy.units.Quantity`
        Observing (sky) frequency: one positive, finite frequency (Hz, MHz,
        GHz...). A wavelength or a plain number is refused.
    polarization, min_elevation : optional
        As for `~astropy_feedrot.Antenna.feed_rotation`; an epoch is masked
        when the target is below ``min_elevation`` at either antenna.
    max_gap : `~astropy.units.Quantity`, optional
        Restart the continuous series after longer gaps (see `unwrap`).

    Returns
    -------
    RotationDelay
        ``(delay, ambiguity)``: the continuous delay in ps, with the broadcast
        shape of ``target`` and ``obstime``, and the ambiguity interval
        :math:`1/f` in ps.

    Raises
    ------
    TypeError
        If an antenna is not an `~astropy_feedrot.Antenna`, or ``frequency``
        is not a Quantity.
    ValueError
        If ``frequency`` is not one positive finite value, the epochs run
        along several axes or go back in time, or as
        `~astropy_feedrot.Antenna.feed_rotation`.
    astropy.units.UnitsError
        If ``frequency`` is not a frequency (a wavelength included).

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
    for name, antenna in (("antenna1", antenna1), ("antenna2", antenna2)):
        if not isinstance(antenna, Antenna):
            raise TypeError(f"{name} must be an Antenna, got {type(antenna).__name__}")
    f_hz = frequency_hz(frequency)
    if max_gap is not None:
        _gap_seconds(max_gap)
    obstime = as_time(obstime)
    phi1 = antenna1.feed_rotation(target, obstime, polarization, min_elevation=min_elevation)
    phi2 = antenna2.feed_rotation(target, obstime, polarization, min_elevation=min_elevation)
    shape = broadcast_shape(antenna1=phi1.shape, antenna2=phi2.shape)
    axis = time_axis(obstime.shape, shape)
    return delay_of_difference(phi2 - phi1, f_hz, axis=axis, obstime=obstime, max_gap=max_gap)


def frequency_hz(frequency, name="frequency"):
    """Check an observing frequency and return it in Hz.

    Parameters
    ----------
    frequency : `~astropy.units.Quantity`
        One positive, finite frequency.
    name : str, optional
        How to call it in error messages.

    Returns
    -------
    float
        The frequency in Hz.

    Raises
    ------
    TypeError
        If ``frequency`` is not a Quantity (a plain number could be Hz, MHz
        or GHz).
    astropy.units.UnitsError
        If it is not a frequency; a wavelength is refused too (which one,
        vacuum or in the medium, would be a guess), with how to convert it.
    ValueError
        If it is not a single value, or is zero, negative, NaN or infinite.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.engine.continuity import frequency_hz
    >>> frequency_hz(1575.42 * u.MHz)
    1575420000.0
    """
    if not isinstance(frequency, u.Quantity):
        raise TypeError(
            f"{name} must be a frequency Quantity (e.g. 1575.42 * u.MHz), got "
            f"{type(frequency).__name__} {frequency!r}; plain numbers are refused because "
            "Hz, MHz and GHz cannot be told apart"
        )
    if frequency.unit.physical_type != "frequency":
        hint = ("; for a wavelength convert it first: wavelength.to(u.GHz, "
                "equivalencies=u.spectral())"
                if frequency.unit.physical_type == "length" else "")
        raise u.UnitsError(
            f"{name} must be a frequency (e.g. in MHz or GHz), got a quantity in "
            f"{frequency.unit.to_string() or 'dimensionless units'}{hint}"
        )
    if not frequency.isscalar:
        raise ValueError(f"{name} must be a single frequency, got shape {frequency.shape}; "
                         "compute one delay per frequency")
    f_hz = float(frequency.to_value(u.Hz))
    if not (np.isfinite(f_hz) and f_hz > 0):
        raise ValueError(f"{name} must be positive and finite, got {frequency}")
    return f_hz


def delay_of_difference(difference, f_hz, axis=-1, obstime=None, max_gap=None):
    """`RotationDelay` of a feed-rotation difference, made continuous along ``axis``.

    Parameters
    ----------
    difference : `~astropy.units.Quantity`
        :math:`\\Phi_2 - \\Phi_1`, an angle.
    f_hz : float
        Frequency in Hz (from `frequency_hz`).
    axis : int or None, optional
        The time axis; None for single epochs (nothing is unwrapped).
    obstime, max_gap : optional
        As for `unwrap`.

    Returns
    -------
    RotationDelay

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.engine.continuity import delay_of_difference
    >>> delay_of_difference([170, -170] * u.deg, 1e9).delay  # doctest: +FLOAT_CMP
    <Quantity [472.22222222, 527.77777778] ps>
    """
    difference = u.Quantity(difference).to(u.rad)
    if axis is None:
        continuous = difference
    else:
        continuous = unwrap(difference, axis=axis, obstime=obstime, max_gap=max_gap)
    delay = (continuous.to_value(u.rad) / (2 * np.pi * f_hz)) * u.s
    return RotationDelay(delay.to(u.ps), (1 / (f_hz * u.Hz)).to(u.ps))
