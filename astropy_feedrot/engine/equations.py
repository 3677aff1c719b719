# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The wind-up engine: the feed rotation of many receivers seeing many targets, on arrays.

This module is the one place that decides which equation a receiver uses. The
receivers declare what they are (`~astropy_feedrot.antennas.mounts`,
`~astropy_feedrot.antennas.focus`) and `Receivers` reads that declaration once:

* a mount that does not track gives its dipoles (`StationaryMount.dipoles
  <astropy_feedrot.StationaryMount.dipoles>`, Eq 28): Beyerle's crossed-dipole
  form (Eq 30) for a transmitter with dipoles, or the effective-dipole form
  (Eq 31) on request, and Eq 33 for a natural source;
* a mount that tracks gives its fixed axis (Eq 10), and its focus the
  multiples of elevation and azimuth it adds (`Focus.closed_form
  <astropy_feedrot.Focus.closed_form>`): Eq 13 (Eq 35 for a satellite) plus
  those terms (Eqs 38-41), in `~astropy_feedrot.antennas.focus.closed_form_phase`;
* a focus without closed form (`~astropy_feedrot.MirrorTrain`) traces its
  mirrors (Eqs 42-45) in its ``receiver_phase``;
* a `~astropy_feedrot.Rotator` (beyond the paper) then turns the receiver's
  effective dipole about the line of sight: its angle is added to the feed
  rotation (``'fixed'``, ``'series'``), or the receiver term is held at its
  angle (``'sky'``).

The transmitter is a natural source, whose effective dipole is the projected
celestial pole (Eq 11), or a satellite with aligned and transverse dipoles
(Eq 8). `feed_rotation` evaluates all of that on arrays of lines of sight
shaped ``(..., antennas, targets, 3)`` (or on geocentric positions of the
targets, from which Eq 30 is contracted without forming those arrays);
`feed_rotation_terms` splits it into transmitter and receiver terms (Eqs
20-22). Angles are radians, positions metres, and nothing here knows of
astropy's units, times or coordinates: `~astropy_feedrot.Antenna` is the case
of one antenna, `~astropy_feedrot.engine.grid` the case of many, and both attach the
units.
"""


import numpy as np

from ..antennas.focus import closed_form_phase
from ..core import kernel
from ..core.exceptions import DegenerateGeometryWarning, warn_caller
from ..core.polarization import polarization_sign
from ..earth.frames import LocalFrame
from ..transmitters.satellite import Satellite
from . import rates
from .receivers import ReceiverArrays, Receivers

__all__ = [
    "FORMS",
    "check_form",
    "ReceiverArrays",
    "Receivers",
    "receiver_sign",
    "feed_rotation",
    "feed_rotation_terms",
    "feed_rotation_rate",
    "parallactic_angle",
    "min_sine",
    "degenerate",
    "warn_degenerate",
]

#: Forms of the wind-up of a stationary crossed dipole seeing a satellite:
#: Beyerle's crossed-dipole form (Eq 30, the default) and Wu's effective-dipole
#: form (Eq 31).
FORMS = ("beyerle", "wu")


def check_form(form):
    """The form of the wind-up to use; None is Beyerle's.

    Parameters
    ----------
    form : {'beyerle', 'wu'} or None

    Returns
    -------
    str
        ``'beyerle'`` or ``'wu'``.

    Raises
    ------
    ValueError
        For another value.

    Examples
    --------
    >>> from astropy_feedrot.engine.equations import check_form
    >>> check_form(None)
    'beyerle'
    """
    if form is None:
        return "beyerle"
    if form not in FORMS:
        raise ValueError(f"form must be one of {FORMS}, got {form!r}")
    return form


def receiver_sign(target, polarization):
    """+1 or -1, the sign of the feed rotation a receiver of a hand sees.

    Parameters
    ----------
    target : `~astropy_feedrot.Satellite` or other
        A satellite (whose hand the receiver must share), or a natural
        source.
    polarization : {'RCP', 'LCP'} or None
        The receiver's hand: the satellite's own, or RCP for a natural
        source, by default.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        For an unknown hand, or one that differs from the satellite's.

    Examples
    --------
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy_feedrot.engine.equations import receiver_sign
    >>> receiver_sign(SkyCoord("03h19m48.16s +41d30m42.1s"), "LCP")
    -1
    """
    if isinstance(target, Satellite):
        return target.receiver_sign(polarization)
    return polarization_sign("RCP" if polarization is None else polarization)


def min_sine(limit):
    """The sine of an elevation limit below which angles are masked.

    Parameters
    ----------
    limit : float or None
        Radians in [-pi/2, pi/2], or None (no limit).

    Returns
    -------
    float or None
        ``sin(limit)``; minus infinity for -pi/2 (nothing is below it, the
        rounding of lines of sight included); None for None.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.engine.equations import min_sine
    >>> min_sine(np.pi / 6)  # doctest: +FLOAT_CMP
    0.5
    """
    if limit is None:
        return None
    return -np.inf if limit <= -np.pi / 2 else float(np.sin(limit))


def _take(array, index, n):
    """``array[..., index, :, :]``, without a copy when ``index`` is all of ``n`` or the
    axis is 1 long (shared by every receiver)."""
    if array.shape[-3] == 1 or len(index) == n:
        return array
    return array[..., index, :, :]


def _beyerle_by_contraction(rx, index, target, aligned, transverse, need_sine):
    """Eq 30 for stationary receivers from geocentric positions, shape (..., a, S).

    The scalar products of `kernel.beyerle_phase_from_products` with the line
    of sight ``s = (target - xyz) / |target - xyz|`` are written with those of
    the per-epoch transmitter vectors (position, dipoles) and the per-site
    receiver vectors (position, dipoles, up), all from one contraction; no
    (..., a, S, 3) array is formed.
    """
    xyz = rx.station_xyz[index]
    ra, rt = rx.dipoles[index, 0], rx.dipoles[index, 1]
    up = rx.station_axes[index, 2]
    n_a = len(index)
    columns = [xyz, ra, rt] + ([up] if need_sine else [])
    receivers = np.ascontiguousarray(np.concatenate(columns).T)  # (3, k a)
    # All scalar products [g, ta, tt] . [x, ra, rt, up] at once. einsum's own loops
    # rather than a BLAS matrix product: the same arithmetic whatever the block
    # size, and no BLAS threads competing with the workers of a parallel scheduler.
    products = np.einsum("k...i,ij->k...j", np.stack([target, aligned, transverse]), receivers)
    g, ta, tt = products.reshape(products.shape[:-1] + (len(columns), n_a))  # (..., S, k, a)
    x_ra, x_rt, x_up, x_x = (kernel.dot(v, xyz) for v in (ra, rt, up, xyz))
    g_g, g_ta, g_tt = (kernel.dot(target, v)[..., np.newaxis]
                       for v in (target, aligned, transverse))
    inverse = g_g + x_x
    inverse -= 2 * g[..., 0, :]
    np.sqrt(inverse, out=inverse)
    np.divide(1.0, inverse, out=inverse)  # 1 / |target - xyz|
    phase = kernel.beyerle_phase_from_products(
        ta[..., 1, :], tt[..., 1, :], ta[..., 2, :], tt[..., 2, :],
        (g[..., 1, :] - x_ra) * inverse, (g[..., 2, :] - x_rt) * inverse,
        (g_ta - ta[..., 0, :]) * inverse, (g_tt - tt[..., 0, :]) * inverse)
    sine = None
    if need_sine:
        sine = ((g[..., 3, :] - x_up) * inverse).swapaxes(-1, -2)
    return phase.swapaxes(-1, -2), sine


def _series_rotation(rx, rotation, name="rotation"):
    """``rotation`` as a float array (..., A), checked; None if no receiver needs it."""
    if not rx.series_index.size:
        return None
    if rotation is None:
        raise ValueError(f"receivers {rx.series_index.tolist()} have a 'series' rotator, whose "
                         f"angle depends on the epochs: pass {name} (radians, shape (..., "
                         f"{len(rx)}), from astropy_feedrot.antennas.rotators)")
    rotation = np.asarray(rotation, dtype=float)
    if rotation.ndim < 1 or rotation.shape[-1] != len(rx):
        raise ValueError(f"{name} must have shape (..., {len(rx)}), one value per receiver, "
                         f"got {rotation.shape}")
    return rotation


def _apply_rotators(rx, phase, rest, where, s, dipole, rotation):
    """Turn the receivers' effective dipoles by their rotators (in place on ``phase``).

    ``'fixed'`` and ``'series'`` add their angle; ``'sky'`` holds the receiver
    term at its angle, so the phase is that angle plus the transmitter term
    (Eq 21), which is 0 for a natural source (NaN at the celestial pole).
    """
    n_rest = rest.size
    for index, series in ((rx.fixed_index, False), (rx.series_index, True)):
        index = index[where[index] >= 0]
        if not index.size:
            continue
        if series:
            added = rotation[..., index][..., np.newaxis]  # (..., a, 1)
        else:
            added = rx.rotator_angle[index][:, np.newaxis]  # (a, 1)
        phase[..., index, :] = kernel.wrap_phase(phase[..., index, :] + added)
    for i in rx.sky_index:
        if where[i] < 0:
            continue
        j = [where[i]]
        term = kernel.transmitter_term(_take(s, j, n_rest), dipole(j))[..., 0, :]
        phase[..., i, :] = kernel.wrap_phase(rx.rotator_angle[i] + term)


def feed_rotation(receivers, target, aligned=None, transverse=None, *, positions=False,
                  form="beyerle", min_sine=None, rotation=None):
    """Feed rotation of every receiver seeing every target (RCP, radians).

    Parameters
    ----------
    receivers : Receivers
        The receivers (A of them).
    target : ndarray
        Unit vectors from the receivers to the targets in ITRS, shape
        (..., A, S, 3), or (..., 1, S, 3) for directions shared by all
        receivers; or, with ``positions``, geocentric ITRS positions of the
        targets in metres, shape (..., S, 3).
    aligned, transverse : ndarray, shape (..., S, 3), optional
        The transmitters' dipoles in ITRS; None for natural sources.
    positions : bool, optional
        Whether ``target`` holds positions.
    form : {'beyerle', 'wu'}, optional
        For stationary receivers seeing transmitters with dipoles: Eq 30
        (default) or Eq 31.
    min_sine : float, optional
        NaN where the sine of a target's elevation is below this (see
        `min_sine`).
    rotation : ndarray, shape (..., A), optional
        The angles in radians of the receivers' ``'series'`` rotators at the
        epochs of ``target`` (`~astropy_feedrot.antennas.rotators.rotation_angles`);
        needed when some receiver has one, ignored for the others.

    Returns
    -------
    phase : ndarray, shape (..., A, S)
        The feed rotation in radians, in [-pi, pi]; NaN where undefined,
        where an input is NaN, or below the elevation limit. Negate it for
        LCP.
    below : ndarray of bool, shape (..., A, S), or None
        Where the target is below the elevation limit (None without one).

    Notes
    -----
    Which equation each receiver takes is decided by `Receivers` from what
    its mount and focus declare; see this module's description. With
    ``positions``, Eq 30 for the stationary receivers is contracted from
    scalar products (`kernel.beyerle_phase_from_products
    <astropy_feedrot.core.kernel.beyerle_phase_from_products>`) and the other
    receivers form their lines of sight (Eq 2) here.

    Examples
    --------
    The parallactic angle (Eq 15) of a source setting due west, seen by an
    alt-az receiver at latitude 45 deg and longitude 0 (Eq 16 gives
    :math:`\\mathrm{atan2}(1, \\tan 45^\\circ)`):

    >>> import numpy as np
    >>> from astropy_feedrot import AltAzMount
    >>> from astropy_feedrot.engine.equations import Receivers, feed_rotation
    >>> r = np.sqrt(0.5)
    >>> enu = [[0, 1.0, 0], [-r, 0, r], [r, 0, r]]  # east, north, up in ITRS
    >>> rx = Receivers.from_mounts([[4.5e6, 0, 4.5e6]], [enu], [AltAzMount()], [None])
    >>> west = np.array([0.0, -1.0, 0.0])
    >>> phase, below = feed_rotation(rx, west.reshape(1, 1, 3))
    >>> float(np.degrees(phase[0, 0]))  # doctest: +FLOAT_CMP
    45.0
    """
    rx = receivers
    rotation = _series_rotation(rx, rotation)
    n_a = len(rx)
    lead = target.shape[:-2] if positions else target.shape[:-3]
    n_s = target.shape[-2]
    phase = np.empty(lead + (n_a, n_s))
    need_sine = min_sine is not None
    sine = np.empty(phase.shape) if need_sine else None
    satellite = aligned is not None
    with np.errstate(invalid="ignore", divide="ignore"):
        rest = np.arange(n_a)
        if positions and satellite and form == "beyerle" and rx.stationary_index.size:
            index = rx.stationary_index
            p, e = _beyerle_by_contraction(rx, index, target, aligned, transverse, need_sine)
            phase[..., index, :] = p
            if need_sine:
                sine[..., index, :] = e
            rest = np.flatnonzero(~rx.stationary)
        if rest.size:
            _from_lines_of_sight(rx, rest, target, aligned, transverse, positions, form,
                                 phase, sine, rotation)
        below = None
        if need_sine:
            below = sine < min_sine
            phase[below] = np.nan
    return phase, below


def _from_lines_of_sight(rx, rest, target, aligned, transverse, positions, form, phase, sine,
                         rotation=None):
    """Fill ``phase`` (and ``sine``) for the receivers ``rest``, from their lines of sight."""
    n_a, n_rest = len(rx), rest.size
    if positions:
        s = kernel.unit(target[..., np.newaxis, :, :] - rx.station_xyz[rest][:, np.newaxis])
    else:
        s = _take(target, rest, n_a)
    satellite = aligned is not None
    ta = tt = t = None
    if satellite:
        ta, tt = aligned[..., np.newaxis, :, :], transverse[..., np.newaxis, :, :]

    def dipole(j):
        """The transmitter's effective dipole (Eqs 8, 11) on the lines of sight ``j``."""
        nonlocal t
        if t is None:
            t = kernel.transmitter_dipole(s, ta, tt)
        return _take(t, j, n_rest)

    axes = rx.station_axes[rest][:, :, np.newaxis]  # (a, 3, 1, 3)
    if sine is not None:
        sine[..., rest, :] = kernel.dot(s, axes[:, 2])
    # Positions of each group within ``rest``.
    where = np.full(n_a, -1)
    where[rest] = np.arange(n_rest)
    for group in (rx.stationary_index, rx.plain_index, rx.focus_index):
        group = group[where[group] >= 0]
        if not group.size:
            continue
        j = where[group]
        s_j = _take(s, j, n_rest)
        if rx.stationary[group[0]]:
            ra, rt = rx.dipoles[group, 0, np.newaxis], rx.dipoles[group, 1, np.newaxis]
            if satellite and form == "beyerle":  # Eq 30
                p = kernel.beyerle_phase(s_j, ra, rt, ta, tt)
            else:  # Eq 7 with the receiver's effective dipole (Eqs 31, 33)
                p = kernel.wu_phase(s_j, kernel.receiver_effective_dipole(s_j, ra, rt),
                                    dipole(j))
        else:  # Eq 13 with the fixed axis (Eq 35), and the focus terms (Eqs 38-41)
            local = LocalFrame(*np.moveaxis(axes[j], 1, 0))
            terms = rx.focus_terms[group, :, np.newaxis]  # (a, 2, 1)
            p = closed_form_phase(s_j, dipole(j) if satellite else None,
                                  rx.fixed_axis[group, np.newaxis], local, terms[:, 0],
                                  terms[:, 1])
        phase[..., group, :] = p
    for i in rx.traced_index:  # the mirrors traced (Eqs 42-45)
        if where[i] < 0:
            continue
        j = [where[i]]
        phase[..., i, :] = rx.traced[i].receiver_phase(
            _take(s, j, n_rest)[..., 0, :, :], dipole(j)[..., 0, :, :], rx.fixed_axis[i],
            LocalFrame(*rx.station_axes[i]))
    if rx.rotators:
        _apply_rotators(rx, phase, rest, where, s, dipole, rotation)


def feed_rotation_terms(receivers, s, aligned=None, transverse=None, *, min_sine=None,
                        rotation=None):
    """The feed rotation split into transmitter and receiver terms (Eqs 20-22), in radians.

    Parameters
    ----------
    receivers : Receivers
        The receivers.
    s : ndarray, shape (..., A or 1, S, 3)
        Unit vectors from the receivers to the targets in ITRS.
    aligned, transverse : ndarray, shape (..., S, 3), optional
        The transmitters' dipoles; None for natural sources.
    min_sine : float, optional
        NaN below this sine of the elevation (see `min_sine`).
    rotation : ndarray, shape (..., A), optional
        As for `feed_rotation`: the rotators turn the receiver term.

    Returns
    -------
    transmitter, receiver : ndarray, shape (..., A, S)
        :math:`\\Phi_\\mathrm{tx}` (Eq 21), the transmitter's effective dipole
        measured from the projected north celestial pole, and
        :math:`\\Phi_\\mathrm{rx}`, the receiver's feed rotation for a
        natural source in the same direction (Eq 22 and the focus terms).
        RCP; NaN where undefined or below the limit.
    below : ndarray of bool or None
        As for `feed_rotation`.

    Examples
    --------
    A natural source has no transmitter term:

    >>> import numpy as np
    >>> from astropy_feedrot import AltAzMount
    >>> from astropy_feedrot.engine.equations import Receivers, feed_rotation_terms
    >>> rx = Receivers.from_mounts([[0.0, 0, 6.4e6]], [np.eye(3)], [AltAzMount()], [None])
    >>> tx, rx_term, _ = feed_rotation_terms(rx, np.array([[[0.6, 0.0, 0.8]]]))
    >>> float(tx[0, 0])
    0.0
    """
    ta = tt = None
    if aligned is not None:
        ta, tt = aligned[..., np.newaxis, :, :], transverse[..., np.newaxis, :, :]
    with np.errstate(invalid="ignore"):
        transmitter = kernel.transmitter_term(s, kernel.transmitter_dipole(s, ta, tt))
    receiver, below = feed_rotation(receivers, s, min_sine=min_sine, rotation=rotation)
    transmitter = np.array(np.broadcast_to(transmitter, receiver.shape))
    if below is not None:
        transmitter[below] = np.nan
    return transmitter, receiver, below


def feed_rotation_rate(receivers, s, s_rate, rotation_rate=None):
    """Rate of the feed rotation of natural sources (RCP), in rad/s.

    The receivers are taken as `feed_rotation` takes them, each by its own
    equation: a stationary crossed dipole by the rate of Eq 33, a tracking
    receiver with a closed form by the rate of Eq 13 plus its multiples of
    elevation and azimuth (Eqs 38, 39), both analytic
    (`~astropy_feedrot.engine.rates`), and traced mirrors by the derivative of the
    traced phase along the motion of the line of sight.

    Parameters
    ----------
    receivers : Receivers
        The receivers (A of them).
    s, s_rate : ndarray, shape (..., A, S, 3)
        Unit vectors from the receivers to the sources in ITRS, and their
        rates in rad/s (`~astropy_feedrot.engine.rates.source_direction_rate`).
    rotation_rate : ndarray, shape (..., A), optional
        The rates in rad/s of the receivers' ``'series'`` rotators
        (`~astropy_feedrot.antennas.rotators.rotation_rates`); needed when some
        receiver has one.

    Returns
    -------
    ndarray, shape (..., A, S)
        :math:`d\\Phi/dt` in rad/s; NaN where the feed rotation is undefined.
        A ``'fixed'`` rotator changes nothing, a ``'sky'`` one makes it 0
        (the feed keeps its angle on the sky), a ``'series'`` one adds its
        rate.

    Examples
    --------
    An alt-az antenna at latitude 45 deg and a source due south at 45 deg
    elevation (on the meridian): :math:`\\dot\\Psi = -\\omega\\cos\\phi\\cos A/\\cos E
    = \\omega` there.

    >>> import numpy as np
    >>> from astropy_feedrot import AltAzMount
    >>> from astropy_feedrot.engine.equations import Receivers, feed_rotation_rate
    >>> from astropy_feedrot.engine.rates import source_direction_rate
    >>> c = np.sqrt(0.5)
    >>> east, north, up = [0.0, 1, 0], [-c, 0, c], [c, 0, c]
    >>> rx = Receivers.from_mounts([[4.5e6, 0, 4.5e6]], [[east, north, up]],
    ...                            [AltAzMount()], [None])
    >>> s = np.array([[[1.0, 0, 0]]])  # south of the zenith by 45 deg: the equator
    >>> rate = feed_rotation_rate(rx, s, source_direction_rate(s))
    >>> float(rate[0, 0] / 7.292115e-5)  # doctest: +FLOAT_CMP
    1.0
    """
    s = np.asarray(s, dtype=float)
    s_rate = np.asarray(s_rate, dtype=float)
    rotation_rate = _series_rotation(receivers, rotation_rate, "rotation_rate")
    out = np.full(np.broadcast_shapes(s.shape, s_rate.shape)[:-1], np.nan)
    for i in range(len(receivers)):
        s_i, rate_i = s[..., i, :, :], s_rate[..., i, :, :]
        rotator = receivers.rotators.get(i)
        if rotator is not None and rotator.mode == "sky":
            # The receiver term is held constant; a natural source has no transmitter term.
            with np.errstate(invalid="ignore"):
                defined = np.isfinite(kernel.transmitter_term(s_i, kernel.project(
                    kernel.NORTH_POLE, s_i))) & np.all(np.isfinite(rate_i), axis=-1)
            out[..., i, :] = np.where(defined, 0.0, np.nan)
            continue
        east, north, up = receivers.station_axes[i]
        local = LocalFrame(east, north, up)
        if receivers.stationary[i]:
            aligned, transverse = receivers.dipoles[i]
            rate = rates.stationary_rate(s_i, rate_i, LocalFrame(aligned, transverse, up))
        elif i in receivers.traced:
            focus, axis = receivers.traced[i], receivers.fixed_axis[i]

            def phase(v, focus=focus, axis=axis, local=local):
                return focus.receiver_phase(v, kernel.project(kernel.NORTH_POLE, v), axis, local)

            rate = rates.directional_rate(phase, s_i, rate_i)
        else:
            rate = rates.fixed_axis_rate(s_i, rate_i, receivers.fixed_axis[i], local,
                                         tuple(receivers.focus_terms[i]))
        if rotator is not None and rotator.mode == "series":
            rate = rate + rotation_rate[..., i, np.newaxis]
        out[..., i, :] = rate
    return out


def parallactic_angle(s, up):
    """Parallactic angle of lines of sight at a site (Eq 15), in radians.

    Parameters
    ----------
    s : ndarray, shape (..., 3)
        Source unit vectors in ITRS.
    up : ndarray, shape (..., 3)
        The site's vertical.

    Returns
    -------
    ndarray, shape (...)
        :math:`\\Psi`, positive west of the meridian (as ERFA's ``hd2pa``);
        NaN at the zenith and at the pole.

    Examples
    --------
    A source setting due west at latitude 45 deg, longitude 0:

    >>> import numpy as np
    >>> from astropy_feedrot.engine.equations import parallactic_angle
    >>> up = np.array([1.0, 0.0, 1.0]) / np.sqrt(2)
    >>> float(np.degrees(parallactic_angle([0.0, -1.0, 0.0], up)))  # doctest: +FLOAT_CMP
    45.0
    """
    return kernel.receiver_term(s, up)


def degenerate(phase, target, below=None, positions=False):
    """Where a feed rotation is NaN because the geometry is degenerate.

    Parameters
    ----------
    phase : ndarray, shape (..., A, S)
        From `feed_rotation` (or a term of `feed_rotation_terms`).
    target : ndarray
        The ``target`` given to it: NaN there is missing data, not
        degenerate geometry.
    below : ndarray of bool, optional
        Below the elevation limit: not degenerate either.
    positions : bool, optional
        Whether ``target`` held positions, shape (..., S, 3).

    Returns
    -------
    ndarray of bool, shape (..., A, S)

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.engine.equations import degenerate
    >>> degenerate(np.array([[np.nan, 1.0, np.nan]]),
    ...            np.array([[[0, 0, 1.0], [0, 1.0, 0], [np.nan] * 3]])).tolist()
    [[True, False, False]]
    """
    undefined = np.isnan(phase)
    target = np.asarray(target)
    if not undefined.any():  # the usual case: no need to look at the targets
        shape = target.shape[:-1]
        if positions:
            shape = shape[:-1] + (1,) + shape[-1:]
        return np.zeros(np.broadcast_shapes(undefined.shape, shape), dtype=bool)
    finite = np.all(np.isfinite(target), axis=-1)
    if positions:
        finite = finite[..., np.newaxis, :]
    bad = undefined & finite
    if below is not None:
        bad &= ~below
    return bad


def warn_degenerate(count, total, what="feed rotation", points="epochs",
                    receiver="a mount"):
    """One `~astropy_feedrot.DegenerateGeometryWarning` for ``count`` undefined angles.

    Nothing happens if ``count`` is 0. The warning points at the caller's line
    outside the package (`~astropy_feedrot.core.exceptions.warn_caller`).

    Parameters
    ----------
    count, total : int
        How many angles are undefined, out of how many.
    what : str, optional
        The quantity (``'feed rotation'``, ``'parallactic angle'``...).
    points : str, optional
        What the angles are counted in (``'epochs'``, ``'grid points'``).
    receiver : str, optional
        The receiver's mount and focus, or ``'a mount'`` for several.

    Examples
    --------
    >>> from astropy_feedrot.engine.equations import warn_degenerate
    >>> warn_degenerate(0, 10)  # nothing to say
    """
    if not count:
        return
    article = "the" if points == "epochs" else "a"
    warn_caller(
        f"{what} is undefined at {count} of {total} {points}, where {article} line of sight "
        f"is within 0.2 mas of a singular direction of {receiver} (a fixed axis such as the "
        "zenith of an alt-az mount) or of the celestial pole, or where a transmitter is seen "
        "edge-on; NaN is returned there",
        DegenerateGeometryWarning,
    )
