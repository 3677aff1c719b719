# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rotators: a feed turned about the line of sight, beyond the paper.

The paper's receivers are a mount and its optics. Some antennas also turn the
feed itself about the optical axis: the third (polarization) axis of ASKAP's
antennas, which keeps the feed at a fixed angle on the sky, and the field
derotators of many receiver cabins. A `Rotator` describes such a turn; an
`~astropy_feedrot.Antenna` carries it (``Antenna(..., rotator=Rotator('sky'))``)
and the wind-up engine (`~astropy_feedrot.engine.equations`) applies it for every
front-end.

The dipole model (Eq 7) gives the feed rotation :math:`\\Phi` as the angle,
about the line of sight :math:`\\hat{s}`, from the receiver's effective dipole
:math:`r` to the transmitter's :math:`t`; for a natural source :math:`t` is the
projected celestial pole (Eq 11), so :math:`\\Phi` is the position angle of
:math:`r`, counted from north through east as the observer sees the sky. A
rotator at angle :math:`\\rho` turns :math:`r` on the sky by :math:`\\rho` in
the same sense, so :math:`\\Phi' = \\Phi + \\rho` (see :doc:`/rotators` for
the derivation). Three modes:

* ``'fixed'``: held at :math:`\\rho_0` in the cabin, :math:`\\Phi' = \\Phi +
  \\rho_0`;
* ``'sky'``: turned with the sky so that the feed keeps the position angle
  :math:`\\rho_0` (:math:`\\rho = \\rho_0 - \\Phi_\\mathrm{rx}`): the receiver
  term is :math:`\\rho_0` at every epoch, and a natural source has
  :math:`\\Phi' = \\rho_0`;
* ``'series'``: following a logged angle :math:`\\rho(t)`, interpolated
  linearly in time.

This module is a receiver layer: it knows times and angles, not lines of
sight.
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle
from astropy.time import Time

from ..core.inputs import as_time
from ..core.kernel import unwrap_phase
from ..earth.frames import fill_masked

__all__ = ["MODES", "RATE_STEP", "Rotator", "as_rotator", "rotation_angles", "rotation_rates"]

#: Modes of a `Rotator`.
MODES = ("sky", "fixed", "series")

#: Half the interval, in seconds, of the centred differences that give the
#: rate of a ``'series'`` rotator (`Rotator.rate`).
RATE_STEP = 0.5


def _angle(value, name):
    """One finite angle in radians from an angle Quantity."""
    if not isinstance(value, u.Quantity):
        raise TypeError(f"{name} must be an angle Quantity (e.g. 30 * u.deg), got "
                        f"{type(value).__name__} {value!r}; a plain number could be degrees "
                        "or radians")
    if value.unit.physical_type != "angle":
        raise u.UnitsError(f"{name} must be an angle (e.g. 30 * u.deg), got a quantity in "
                           f"{value.unit.to_string() or 'dimensionless units'}")
    if not value.isscalar or not np.isfinite(value.value):
        raise ValueError(f"{name} must be one finite angle, got {value}")
    return float(value.to_value(u.rad))


class Rotator:
    """A feed turned about the line of sight by an angle :math:`\\rho`.

    Parameters
    ----------
    mode : {'sky', 'fixed', 'series'}
        ``'sky'`` tracks the sky: the feed keeps the position angle ``angle``
        on the sky (north through east) at every epoch, whatever the mount
        and optics do (ASKAP's polarization axis). ``'fixed'`` is held at
        ``angle`` in the cabin: a constant added to the feed rotation.
        ``'series'`` follows the angles ``angles`` at the epochs ``times``,
        interpolated linearly in time.
    angle : `~astropy.units.Quantity`, optional
        :math:`\\rho_0` for ``'sky'`` and ``'fixed'`` (default 0 deg).
    times : `~astropy.time.Time`, optional
        For ``'series'``: the epochs of the logged angles, one-dimensional,
        at least two, strictly increasing, none masked.
    angles : `~astropy.units.Quantity`, optional
        For ``'series'``: the rotator's angle at each of ``times``, finite.
        Consecutive angles are taken to differ by less than 180 deg (the
        series is made continuous, Eq 9, before it is interpolated).

    Raises
    ------
    TypeError
        If ``angle`` or ``angles`` is not an angle Quantity (plain numbers
        are refused: degrees or radians?), or ``times`` not a
        `~astropy.time.Time`.
    ValueError
        For an unknown ``mode``; ``times``/``angles`` given with ``'sky'`` or
        ``'fixed'``, or missing (or ``angle`` given) with ``'series'``; a
        series that is not one-dimensional, shorter than two, not strictly
        increasing, masked, not finite, or whose two arrays differ in shape.
    astropy.units.UnitsError
        If an angle is in another unit.

    Notes
    -----
    The angle :math:`\\rho` is measured on the sky, as the position angle
    (north through east seen by the observer): a rotator at :math:`\\rho`
    adds :math:`\\rho` to the RCP feed rotation, :math:`\\Phi' = \\Phi + \\rho`
    (and subtracts it from the LCP one). Behind an odd number of mirrors the
    mechanical sense of the rotator is the mirror image of its sense on the
    sky: give :math:`\\rho` as seen on the sky. See :doc:`/rotators`.

    Examples
    --------
    A feed that tracks the sky keeps one position angle (here 45 deg) for
    every epoch:

    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot import Antenna, AltAzMount, Rotator
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> site = get_antenna("WETTZ13S").location
    >>> antenna = Antenna(site, AltAzMount(), rotator=Rotator("sky", 45 * u.deg))
    >>> times = Time("2023-01-25T18:00") + [0, 3, 6] * u.hour
    >>> antenna.feed_rotation(SkyCoord("03h19m48.16s +41d30m42.1s"), times)  # doctest: +FLOAT_CMP
    <Angle [45., 45., 45.] deg>

    A logged series, interpolated between its epochs:

    >>> log = Rotator("series", times=Time("2023-01-25T18:00") + [0, 1] * u.hour,
    ...               angles=[10, 40] * u.deg)
    >>> log.angle_at(Time("2023-01-25T18:20"))  # doctest: +FLOAT_CMP
    <Angle 20. deg>
    """

    def __init__(self, mode, angle=None, *, times=None, angles=None):
        if not isinstance(mode, str) or mode not in MODES:
            raise ValueError(f"Rotator mode must be one of {MODES}, got {mode!r}")
        self._mode = mode
        self._times = self._angles = self._seconds = None
        if mode != "series":
            if times is not None or angles is not None:
                raise ValueError(f"times and angles go with mode 'series'; a {mode!r} "
                                 "rotator takes one angle, e.g. Rotator("
                                 f"{mode!r}, 30 * u.deg)")
            self._angle = 0.0 if angle is None else _angle(angle, "angle")
            return
        if angle is not None:
            raise ValueError("a 'series' rotator follows its angles; give times= and angles= "
                             "instead of angle")
        if times is None or angles is None:
            raise ValueError("a 'series' rotator needs times= (a Time array) and angles= (an "
                             "angle Quantity array of the same shape)")
        if not isinstance(times, Time):
            raise TypeError(f"times must be an astropy Time array, got {type(times).__name__}")
        times = as_time(times)
        if not isinstance(angles, u.Quantity):
            raise TypeError(f"angles must be an angle Quantity array (e.g. [0, 10] * u.deg), "
                            f"got {type(angles).__name__}")
        if angles.unit.physical_type != "angle":
            raise u.UnitsError(f"angles must be angles (e.g. [0, 10] * u.deg), got a quantity "
                               f"in {angles.unit.to_string() or 'dimensionless units'}")
        if times.ndim != 1 or times.size < 2:
            raise ValueError(f"times must be a one-dimensional series of at least two epochs, "
                             f"got shape {times.shape}")
        if angles.shape != times.shape:
            raise ValueError(f"angles has shape {angles.shape} but times has shape "
                             f"{times.shape}; give one angle per epoch")
        if times.masked and np.any(times.mask):
            raise ValueError("times has masked epochs; drop them (and their angles)")
        radians = angles.to_value(u.rad).astype(float)
        if not np.all(np.isfinite(radians)):
            raise ValueError("angles must all be finite; drop the epochs without an angle")
        seconds = (times - times[0]).to_value(u.s)
        if np.any(np.diff(seconds) <= 0):
            raise ValueError("times must increase strictly; sort the series by time "
                             "(np.argsort(times)) and drop repeated epochs")
        self._angle = None
        self._times = times
        self._seconds = seconds
        self._angles = unwrap_phase(radians)

    def __repr__(self):
        if self._mode == "series":
            return (f"Rotator('series', {self._times.size} epochs, "
                    f"{self._times[0].utc.isot} to {self._times[-1].utc.isot})")
        return f"Rotator({self._mode!r}, {np.degrees(self._angle):.12g} deg)"

    def __eq__(self, other):
        if not isinstance(other, Rotator) or other._mode != self._mode:
            return False
        if self._mode != "series":
            return self._angle == other._angle
        return (np.array_equal(self._angles, other._angles)
                and np.array_equal(self._seconds, other._seconds)
                and bool(self._times[0] == other._times[0]))

    __hash__ = None

    @property
    def mode(self):
        """``'sky'``, ``'fixed'`` or ``'series'``."""
        return self._mode

    @property
    def angle(self):
        """:math:`\\rho_0` as an `~astropy.coordinates.Angle` (None for ``'series'``)."""
        return None if self._angle is None else Angle(np.degrees(self._angle), u.deg)

    @property
    def radians(self):
        """:math:`\\rho_0` in radians, a float (None for ``'series'``)."""
        return self._angle

    @property
    def times(self):
        """The epochs of a ``'series'`` rotator (None otherwise)."""
        return self._times

    @property
    def angles(self):
        """The angles of a ``'series'`` rotator, made continuous (None otherwise)."""
        return None if self._angles is None else Angle(np.degrees(self._angles), u.deg)

    def _seconds_at(self, obstime):
        """Seconds since the first epoch of the series (NaN where masked)."""
        filled, masked = fill_masked(as_time(obstime))
        seconds = np.array((filled - self._times[0]).to_value(u.s), dtype=float, ndmin=0)
        if masked is not None:
            seconds[masked] = np.nan
        outside = (seconds < 0) | (seconds > self._seconds[-1])
        if np.any(outside):
            raise ValueError(
                f"{np.count_nonzero(outside)} epochs lie outside the rotator's series "
                f"({self._times[0].utc.isot} to {self._times[-1].utc.isot}); its angle is "
                "unknown there: extend the series or restrict the epochs")
        return seconds

    def _interpolate(self, seconds):
        out = np.interp(seconds, self._seconds, self._angles)
        return np.where(np.isnan(seconds), np.nan, out)

    def angle_at(self, obstime):
        """The rotator's angle at some epochs (``'sky'``: see Returns).

        Parameters
        ----------
        obstime : `~astropy.time.Time`
            Epoch(s); masked epochs give NaN.

        Returns
        -------
        `~astropy.coordinates.Angle`
            In degrees, with the shape of ``obstime``: :math:`\\rho_0` for
            ``'fixed'``; the series interpolated linearly in time (continuous,
            not wrapped) for ``'series'``; for ``'sky'`` the position angle
            :math:`\\rho_0` the feed keeps on the sky (the mechanical angle
            depends on the line of sight: :math:`\\rho_0 - \\Phi_\\mathrm{rx}`).

        Raises
        ------
        TypeError
            If ``obstime`` is not a time.
        ValueError
            If a (unmasked) epoch lies outside a ``'series'``.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Rotator
        >>> Rotator("fixed", 30 * u.deg).angle_at(Time("2023-01-25T18:00"))
        <Angle 30. deg>
        """
        return Angle(np.degrees(self.radians_at(obstime)), u.deg)

    def radians_at(self, obstime):
        """`angle_at` in radians, as a float array (what the engine adds).

        Parameters
        ----------
        obstime : `~astropy.time.Time`
            Epoch(s); masked epochs give NaN.

        Returns
        -------
        ndarray
            Shape of ``obstime`` (0-d for a scalar).

        Raises
        ------
        TypeError, ValueError
            As `angle_at`.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Rotator
        >>> start = Time("2023-01-25T18:00")
        >>> log = Rotator("series", times=start + [0, 1] * u.h, angles=[0, 90] * u.deg)
        >>> float(log.radians_at(start + 30 * u.min))  # doctest: +FLOAT_CMP
        0.7853981633974483
        """
        if self._mode != "series":
            filled, masked = fill_masked(as_time(obstime))
            out = np.full(filled.shape, self._angle)
            if masked is not None:
                out[masked] = np.nan
            return out
        return self._interpolate(self._seconds_at(obstime))

    def rate(self, obstime):
        """The rate at which the rotator turns the feed, in rad/s.

        Parameters
        ----------
        obstime : `~astropy.time.Time`
            Epoch(s); masked epochs give NaN.

        Returns
        -------
        ndarray
            Shape of ``obstime``: 0 for ``'fixed'``; for ``'series'`` the
            centred difference of the linear interpolation over
            :math:`\\pm` `RATE_STEP` s (the slope of the segment, the mean
            of the two slopes within `RATE_STEP` of a logged epoch,
            one-sided at the ends of the series). For ``'sky'`` the rotator
            holds the receiver term constant; its own rate, which depends on
            the line of sight, is not given here (NaN).

        Raises
        ------
        TypeError, ValueError
            As `angle_at`.

        Examples
        --------
        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Rotator
        >>> start = Time("2023-01-25T18:00")
        >>> log = Rotator("series", times=start + [0, 1] * u.h, angles=[0, 90] * u.deg)
        >>> float(np.degrees(log.rate(start + 30 * u.min)) * 3600)  # deg/h  # doctest: +FLOAT_CMP
        90.0
        """
        if self._mode != "series":
            filled, masked = fill_masked(as_time(obstime))
            out = np.full(filled.shape, 0.0 if self._mode == "fixed" else np.nan)
            if masked is not None:
                out[masked] = np.nan
            return out
        seconds = self._seconds_at(obstime)
        ahead = np.minimum(seconds + RATE_STEP, self._seconds[-1])
        behind = np.maximum(seconds - RATE_STEP, 0.0)
        with np.errstate(invalid="ignore"):
            return (self._interpolate(ahead) - self._interpolate(behind)) / (ahead - behind)


def as_rotator(rotator):
    """A `Rotator` or None, checked.

    Parameters
    ----------
    rotator : `Rotator` or None

    Returns
    -------
    `Rotator` or None

    Raises
    ------
    TypeError
        For anything else (a mode name alone, say).

    Examples
    --------
    >>> from astropy_feedrot.antennas.rotators import Rotator, as_rotator
    >>> as_rotator(None) is None
    True
    >>> as_rotator(Rotator("sky"))
    Rotator('sky', 0 deg)
    """
    if rotator is None or isinstance(rotator, Rotator):
        return rotator
    hint = f"; write Rotator({rotator!r})" if isinstance(rotator, str) else ""
    raise TypeError(f"rotator must be a Rotator or None, got {type(rotator).__name__}{hint}")


def _series(rotators, obstime, method):
    rotators = list(rotators)
    if not any(r is not None and r.mode == "series" for r in rotators):
        return None
    filled, _ = fill_masked(as_time(obstime))
    out = np.zeros(filled.shape + (len(rotators),))
    for i, rotator in enumerate(rotators):
        if rotator is not None and rotator.mode == "series":
            out[..., i] = getattr(rotator, method)(obstime)
    return out


def rotation_angles(rotators, obstime):
    """The angles of the ``'series'`` rotators of A antennas at some epochs, in radians.

    What the wind-up engine adds for them (`~astropy_feedrot.engine.equations.feed_rotation`
    knows the constant angles of the other modes itself).

    Parameters
    ----------
    rotators : sequence of `Rotator` or None
        One per antenna.
    obstime : `~astropy.time.Time`
        The epochs.

    Returns
    -------
    ndarray or None
        Shape ``obstime.shape + (A,)``, 0 for antennas without a
        ``'series'`` rotator, NaN at masked epochs; None if no antenna has
        one.

    Raises
    ------
    TypeError, ValueError
        As `Rotator.angle_at`.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.antennas.rotators import Rotator, rotation_angles
    >>> start = Time("2023-01-25T18:00")
    >>> log = Rotator("series", times=start + [0, 1] * u.h, angles=[0, 90] * u.deg)
    >>> rotation_angles([None, log], start + [0, 60] * u.min).round(6).tolist()
    [[0.0, 0.0], [0.0, 1.570796]]
    >>> rotation_angles([None, Rotator("sky")], start) is None
    True
    """
    return _series(rotators, obstime, "radians_at")


def rotation_rates(rotators, obstime):
    """The rates of the ``'series'`` rotators of A antennas, in rad/s.

    Parameters
    ----------
    rotators : sequence of `Rotator` or None
        One per antenna.
    obstime : `~astropy.time.Time`
        The epochs.

    Returns
    -------
    ndarray or None
        Shape ``obstime.shape + (A,)`` (`Rotator.rate`), 0 for antennas
        without a ``'series'`` rotator; None if no antenna has one.

    Raises
    ------
    TypeError, ValueError
        As `Rotator.angle_at`.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.antennas.rotators import Rotator, rotation_rates
    >>> start = Time("2023-01-25T18:00")
    >>> log = Rotator("series", times=start + [0, 1] * u.h, angles=[0, 36] * u.deg)
    >>> rotation_rates([log], start + 10 * u.min).shape
    (1,)
    """
    return _series(rotators, obstime, "rate")
