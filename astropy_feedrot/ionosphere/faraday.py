# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Faraday rotation: the turn of the wave's plane of polarization, RM * lambda^2."""

import numpy as np
from astropy import constants as const
from astropy import units as u
from astropy.coordinates import Angle

from .rm_table import RM_UNIT

__all__ = ["faraday_rotation", "polarization_rotation", "wavelength_squared"]

_C = const.c.to_value(u.m / u.s)


def wavelength_squared(hertz, message="frequency must be positive and finite, got {hertz:g} Hz"):
    """lambda^2 = (c / nu)^2 in m^2 of frequencies in Hz, each positive and finite.

    Parameters
    ----------
    hertz : array-like
        Frequencies in Hz.
    message : str, optional
        The error's text, formatted with the first bad frequency as ``hertz``.

    Returns
    -------
    `~numpy.ndarray`
        Of the shape of ``hertz``.

    Raises
    ------
    ValueError
        If a frequency is not positive and finite: lambda^2 would be wrong.

    Examples
    --------
    >>> from astropy_feedrot.ionosphere.faraday import wavelength_squared
    >>> wavelength_squared([1.4e9, 5e9])  # doctest: +FLOAT_CMP
    array([0.04585486, 0.00359502])
    """
    hertz = np.asarray(hertz, dtype=float)
    good = np.isfinite(hertz) & (hertz > 0)
    if not np.all(good):
        raise ValueError(message.format(hertz=hertz[~good].ravel()[0]))
    return (_C / hertz) ** 2


def faraday_rotation(rm, frequency):
    """The rotation RM * (c / nu)^2 of the plane of polarization, per frequency.

    Parameters
    ----------
    rm : `~astropy.units.Quantity`
        Rotation measure(s) in rad m^-2, any shape ``S`` (e.g. epochs x
        antennas from `Ionosphere.rotation_measure`).
    frequency : `~astropy.units.Quantity`
        Frequency (or frequencies, any shape ``F``, e.g. the channels of a
        spectral window), or wavelength: anything with a spectral unit.

    Returns
    -------
    `~astropy.coordinates.Angle`
        chi = RM lambda^2 in degrees, of shape ``S + F`` (frequency last),
        not wrapped (at low frequencies it spans many turns). Positive: the
        plane turns from north through east, so a source of intrinsic angle
        chi0 is seen at chi0 + chi. NaN where ``rm`` is NaN.

    Raises
    ------
    TypeError
        If ``rm`` or ``frequency`` is not a Quantity.
    astropy.units.UnitsError
        If ``rm`` is not in rad m^-2, or ``frequency`` has no spectral unit.
    ValueError
        If a frequency is not positive and finite.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.ionosphere import faraday_rotation
    >>> faraday_rotation(1.0 * u.rad / u.m**2, [1.4, 5.0] * u.GHz)  # doctest: +FLOAT_CMP
    <Angle [2.62728972, 0.20597951] deg>
    """
    if not isinstance(rm, u.Quantity):
        raise TypeError(f"rm must be a Quantity in rad / m2 (e.g. 1.0 * u.rad / u.m**2), "
                        f"got {type(rm).__name__}")
    try:
        rm_value = rm.to_value(RM_UNIT, equivalencies=u.dimensionless_angles())
    except u.UnitConversionError:
        raise u.UnitsError(f"rm must be a rotation measure in rad / m2, got a quantity in "
                           f"{rm.unit.to_string() or 'dimensionless units'}") from None
    if not isinstance(frequency, u.Quantity):
        raise TypeError(f"frequency must be a Quantity (e.g. 1.4 * u.GHz), got "
                        f"{type(frequency).__name__}")
    try:
        hertz = frequency.to_value(u.Hz, equivalencies=u.spectral())
    except u.UnitConversionError:
        unit = frequency.unit.to_string() or "dimensionless units"
        raise u.UnitsError(f"frequency must be a frequency or a wavelength (e.g. 1.4 * u.GHz), "
                           f"got a quantity in {unit}") from None
    lambda2 = wavelength_squared(hertz)
    rm_value = np.asarray(rm_value, dtype=float)
    chi = rm_value.reshape(rm_value.shape + (1,) * lambda2.ndim) * lambda2
    return Angle(chi, u.rad).to(u.deg)


def polarization_rotation(feed_rotation, rm, frequency):
    """The one angle a correction needs: the feed rotation minus the Faraday rotation.

    With the package's convention a feed turned by Phi moves the apparent
    polarization angle by -Phi, while the ionosphere moves it by
    +chi = +RM lambda^2; psi = Phi - chi therefore enters a correction exactly
    as the feed rotation does, and removing it leaves the source's intrinsic
    angle.

    Parameters
    ----------
    feed_rotation : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        The feed rotation Phi, shape ``S`` (e.g. epochs, or epochs x antennas).
    rm : `~astropy.units.Quantity`
        Rotation measure(s) in rad m^-2, a shape that broadcasts with ``S``.
    frequency : `~astropy.units.Quantity`
        Frequency (or frequencies, shape ``F``), or wavelength.

    Returns
    -------
    `~astropy.coordinates.Angle`
        psi = Phi - RM lambda^2 in degrees, of shape ``S + F`` (frequency
        last), not wrapped.

    Raises
    ------
    TypeError, astropy.units.UnitsError, ValueError
        As `faraday_rotation`; `~astropy.units.UnitsError` too if
        ``feed_rotation`` is not an angle.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.ionosphere import polarization_rotation
    >>> polarization_rotation([10.0, 20.0] * u.deg, 1.0 * u.rad / u.m**2,
    ...                       [1.4, 5.0] * u.GHz)  # doctest: +FLOAT_CMP
    <Angle [[ 7.37271028,  9.79402049],
            [17.37271028, 19.79402049]] deg>
    """
    if not isinstance(feed_rotation, u.Quantity) or feed_rotation.unit.physical_type != "angle":
        raise u.UnitsError(f"feed_rotation must be an angle (e.g. an Angle in deg), got "
                           f"{feed_rotation!r}")
    phi = np.asarray(feed_rotation.to_value(u.deg), dtype=float)
    rm = np.broadcast_to(rm, np.broadcast_shapes(np.shape(rm), phi.shape), subok=True)
    chi = faraday_rotation(rm, frequency)
    extra = chi.ndim - rm.ndim
    return Angle(phi.reshape(phi.shape + (1,) * extra) - chi.to_value(u.deg), u.deg)
