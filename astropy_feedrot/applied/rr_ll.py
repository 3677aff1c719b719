# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The RR - LL phase that the feed rotation of a baseline's two antennas
predicts for a weakly polarized natural source (Eq 46).
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle

from ..core import kernel
from ..core.inputs import as_radians
from ..earth.frames import as_time, broadcast_shape, time_axis
from ..engine.antenna import Antenna
from ..engine.continuity import unwrap
from ..transmitters.satellite import Satellite

__all__ = ["rr_minus_ll", "baseline_rr_ll"]


def _degrees(radians):
    """Radians to an `~astropy.coordinates.Angle` in degrees; 0-d becomes scalar."""
    radians = np.asarray(radians)
    return Angle(radians[()] if radians.ndim == 0 else radians, u.rad).to(u.deg)


def rr_minus_ll(feed_rotation1, feed_rotation2, wrap=True):
    """The RR - LL phase difference that feed rotation causes on a baseline (Eq 46).

    Parameters
    ----------
    feed_rotation1, feed_rotation2 : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        RCP feed rotations :math:`\\Phi_1`, :math:`\\Phi_2` of the two antennas
        (antenna 2 is the conjugated one, :math:`V = \\langle v_1 v_2^*
        \\rangle`).
    wrap : bool, optional
        Wrap the result to (-180, 180] deg (default). If False, return
        :math:`2(\\Phi_2 - \\Phi_1)` as it comes, continuous when the inputs
        are.

    Returns
    -------
    `~astropy.coordinates.Angle`
        :math:`\\phi^R - \\phi^L = 2(\\Phi_2 - \\Phi_1)` in degrees, broadcast
        shape of the inputs (a scalar for scalars); NaN where either is NaN.

    Raises
    ------
    TypeError
        If an angle is not a Quantity.
    astropy.units.UnitsError
        If an angle has a unit that is not an angle.
    ValueError
        If the shapes do not broadcast.

    Notes
    -----
    Eq 46 without the instrumental offset :math:`\\Phi_\\mathrm{instr}`,
    which is constant (fit and remove it when comparing with fringe phases, as
    for Fig. 7 of the paper). The prediction holds for a weakly polarized
    natural source, whose RR and LL visibilities are equal before the feeds
    rotate them.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.rr_ll import rr_minus_ll
    >>> rr_minus_ll(10 * u.deg, 40 * u.deg)  # doctest: +FLOAT_CMP
    <Angle 60. deg>
    >>> rr_minus_ll(-60 * u.deg, [40, 60] * u.deg)  # doctest: +FLOAT_CMP
    <Angle [-160., -120.] deg>
    >>> rr_minus_ll(-60 * u.deg, [40, 60] * u.deg, wrap=False)  # doctest: +FLOAT_CMP
    <Angle [200., 240.] deg>
    """
    phi1 = as_radians(feed_rotation1, "feed_rotation1")
    phi2 = as_radians(feed_rotation2, "feed_rotation2")
    broadcast_shape(feed_rotation1=phi1.shape, feed_rotation2=phi2.shape)
    difference = 2 * (phi2 - phi1)
    return _degrees(kernel.wrap_phase(difference) if wrap else difference)


def baseline_rr_ll(antenna1, antenna2, target, obstime, wrap=True, min_elevation=None,
                   max_gap=None):
    """The predicted RR - LL phase of a baseline observing a natural source (Eq 46).

    Parameters
    ----------
    antenna1, antenna2 : `~astropy_feedrot.Antenna`
        The baseline (antenna 2 is the conjugated one, :math:`V = \\langle v_1
        v_2^* \\rangle`).
    target : `~astropy.coordinates.SkyCoord`
        Natural source(s), weakly polarized.
    obstime : `~astropy.time.Time`
        Epoch(s); masked epochs give NaN. With ``wrap=False`` the series runs
        along the one axis of the broadcast shape along which the epochs run
        (as for `~astropy_feedrot.rotation_delay`).
    wrap : bool, optional
        Wrap to (-180, 180] deg (default). If False, :math:`\\Phi_2 - \\Phi_1`
        is made continuous along the time axis (Eq 9, see
        `~astropy_feedrot.unwrap`), starting each segment in (-180, 180] deg,
        and then doubled.
    min_elevation : `~astropy.units.Quantity`, optional
        NaN where the source is lower than this at either antenna.
    max_gap : `~astropy.units.Quantity`, optional
        With ``wrap=False``, restart the continuous series after longer gaps
        (for example between scans).

    Returns
    -------
    `~astropy.coordinates.Angle`
        :math:`2(\\Phi_2 - \\Phi_1)` in degrees with the RCP feed rotations of
        `~astropy_feedrot.Antenna.feed_rotation`, broadcast shape of ``target``
        and ``obstime``.

    Raises
    ------
    TypeError
        If an antenna is not an `~astropy_feedrot.Antenna`, or ``target`` is a
        `~astropy_feedrot.Satellite` (it transmits one hand only).
    ValueError
        If ``max_gap`` is given with ``wrap=True``, with ``wrap=False`` if
        the epochs run along several axes or go back in time, and as for
        `~astropy_feedrot.Antenna.feed_rotation`.

    Warns
    -----
    DegenerateGeometryWarning, ContinuityWarning
        As `~astropy_feedrot.Antenna.feed_rotation` and `~astropy_feedrot.unwrap`.

    Examples
    --------
    The Yebes 40 m telescope (Nasmyth, right) against a Cassegrain antenna at
    the same site: the difference of the feed rotations is the elevation, so
    RR - LL is twice the elevation (Eqs 38 and 46):

    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot import Antenna, AltAzMount, NasmythFocus
    >>> from astropy_feedrot.applied.rr_ll import baseline_rr_ll
    >>> yebes = EarthLocation.from_geodetic(-3.0869 * u.deg, 40.5247 * u.deg, 988 * u.m)
    >>> cassegrain = Antenna(yebes, AltAzMount())
    >>> nasmyth = Antenna(yebes, AltAzMount(), NasmythFocus("right"))
    >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
    >>> times = Time("2023-01-25T20:00") + [0, 2] * u.hour
    >>> baseline_rr_ll(cassegrain, nasmyth, source, times)  # doctest: +FLOAT_CMP
    <Angle [162.61771062, 117.94659972] deg>
    >>> 2 * cassegrain.altaz(source, times)[1]  # doctest: +FLOAT_CMP
    <Angle [162.61771062, 117.94659972] deg>
    """
    for name, antenna in (("antenna1", antenna1), ("antenna2", antenna2)):
        if not isinstance(antenna, Antenna):
            raise TypeError(f"{name} must be an Antenna, got {type(antenna).__name__}")
    if isinstance(target, Satellite):
        raise TypeError(
            f"Eq 46 compares the RR and LL phases of a weakly polarized natural source; "
            f"{target!r} transmits {target.polarization} only. Give a SkyCoord, or compare "
            "feed rotations with Antenna.feed_rotation"
        )
    if wrap and max_gap is not None:
        raise ValueError("max_gap applies to the continuous series only; pass wrap=False")
    obstime = as_time(obstime)
    phi1 = antenna1.feed_rotation(target, obstime, "RCP", min_elevation=min_elevation)
    phi2 = antenna2.feed_rotation(target, obstime, "RCP", min_elevation=min_elevation)
    if wrap:
        return rr_minus_ll(phi1, phi2)
    # Eq 9 on the difference of the feed rotations, then doubled: each segment
    # starts from Phi_2 - Phi_1 in (-180, 180] deg.
    difference = kernel.wrap_phase(phi2.to_value(u.rad) - phi1.to_value(u.rad)) * u.rad
    axis = time_axis(obstime.shape, difference.shape)
    if axis is not None:  # a single epoch has nothing to make continuous
        difference = unwrap(difference, axis=axis, obstime=obstime, max_gap=max_gap)
    return _degrees(2 * difference.to_value(u.rad))
