# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Applying the feed-rotation correction to phases and visibilities (Appendix D, Eq 46).

Conventions (see ``docs/correction.rst`` for the derivation):

* The feed rotation :math:`\\Phi` taken by every function here is the RCP
  feed rotation of the paper, as `~astropy_feedrot.Antenna.feed_rotation`
  returns it for a natural source: the position angle of the receiver's
  effective dipole, measured from north through east (the parallactic angle
  for an alt-az Cassegrain antenna, positive west of the meridian).
* A feed rotated by :math:`\\Phi` multiplies its RCP voltage by
  :math:`e^{-i\\Phi}` and its LCP voltage by :math:`e^{+i\\Phi}`; a measured
  phase (which grows with delay, :math:`\\phi = -\\arg v`) gains
  :math:`+\\Phi` in RCP and :math:`-\\Phi` in LCP. Hence Appendix D: subtract
  :math:`\\Phi` from RCP phases, add it to LCP phases.
* A visibility is :math:`V_{pq} = \\langle v_{1p} v_{2q}^* \\rangle` (antenna 2
  conjugated), so the RR phase gains :math:`\\Phi_2 - \\Phi_1` and LL
  :math:`\\Phi_1 - \\Phi_2`, as in Eq 46. This is the measurement equation of
  Hamaker, Bregman and Sault (1996) with CASA's parallactic-angle Jones matrix
  (``PJones``): :math:`\\mathrm{diag}(e^{-i\\Phi}, e^{i\\Phi})` for circular
  feeds and :math:`[[\\cos\\Phi, \\sin\\Phi], [-\\sin\\Phi, \\cos\\Phi]]` for
  linear ones.
* Masked inputs: a masked angle (astropy's `~astropy.utils.masked.Masked`
  quantities) counts as NaN; masked visibilities (`numpy.ma.MaskedArray` or
  `~astropy.utils.masked.Masked`) come back with their mask, of the same
  kind (for linear feeds a sample's four products share it, since the
  correction mixes them).
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle
from astropy.utils.masked import Masked

from ..antennas.receptors import RECEPTOR_TYPES, basis_of
from ..core import kernel
from ..core.inputs import as_radians
from ..core.polarization import polarization_sign
from ..earth.frames import broadcast_shape

__all__ = [
    "correct_phase",
    "correct_visibilities",
    "rotation_matrix",
    "correct_linear_visibilities",
    "correct_receptor_visibilities",
]

#: Names of the correlation products of circular feeds (any order, any subset).
CIRCULAR_PRODUCTS = ("RR", "RL", "LR", "LL")

#: Names of the correlation products of linear feeds (all four, any order).
LINEAR_PRODUCTS = ("XX", "XY", "YX", "YY")

#: The two directions of `correct_receptor_visibilities`: remove the feed
#: rotation (measured to sky-fixed receptors) or apply it (the inverse).
DIRECTIONS = ("remove", "apply")


# --- input checks ------------------------------------------------------------


def _to_angle(radians, unit=u.deg):
    """Radians to an `~astropy.coordinates.Angle` in ``unit``; 0-d becomes scalar."""
    radians = np.asarray(radians)
    return Angle(radians[()] if radians.ndim == 0 else radians, u.rad).to(unit)


def _fit(target, **shapes):
    """Check that each named shape broadcasts to ``target`` without enlarging it."""
    for name, shape in shapes.items():
        try:
            fits = np.broadcast_shapes(shape, target) == tuple(target)
        except ValueError:
            fits = False
        if not fits:
            raise ValueError(
                f"{name} has shape {shape}, which does not broadcast to the shape "
                f"{tuple(target)} of visibilities[..., 0] (one angle per visibility "
                "sample; the last axis of visibilities holds the products)"
            )


def _products(products, valid, all_required):
    """Upper-case product names, checked against ``valid``."""
    if isinstance(products, str):
        raise TypeError(
            f"products must be a sequence of names such as {valid}, not the single "
            f"string {products!r}"
        )
    try:
        names = tuple(name.upper() for name in products)
    except (TypeError, AttributeError):
        raise TypeError(
            f"products must be a sequence of names such as {valid}, got {products!r}"
        ) from None
    unknown = [name for name in names if name not in valid]
    if unknown or not names:
        raise ValueError(
            f"unknown product names {unknown}; valid names are {valid}"
            if unknown else f"products is empty; valid names are {valid}"
        )
    duplicates = sorted({name for name in names if names.count(name) > 1})
    if duplicates:
        raise ValueError(f"products names {duplicates} more than once; each of {valid} "
                         "may appear at most once")
    missing = [name for name in valid if name not in names]
    if all_required and missing:
        raise ValueError(
            f"products lacks {missing}: the feed rotation of linear feeds mixes all "
            f"four products, so visibilities must hold {valid} (in any order)"
        )
    return names


def _visibilities(visibilities, names):
    """The complex values (ndarray), unit (or None) and mask (see `_finish`)."""
    mask = None
    if isinstance(visibilities, Masked):
        mask = ("astropy", np.array(visibilities.mask, dtype=bool))
        visibilities = visibilities.unmasked
    elif np.ma.isMaskedArray(visibilities):
        mask = ("numpy", np.ma.getmaskarray(visibilities))
        visibilities = np.ma.getdata(visibilities)
    unit = None
    if isinstance(visibilities, u.Quantity):
        unit = visibilities.unit
        visibilities = visibilities.value
    values = np.asarray(visibilities)
    if not np.issubdtype(values.dtype, np.complexfloating):
        raise TypeError(
            f"visibilities must be complex, got dtype {values.dtype}; a real array has "
            "no phase to correct (build it with a complex dtype, e.g. "
            "amplitude * np.exp(1j * phase))"
        )
    if values.ndim == 0 or values.shape[-1] != len(names):
        raise ValueError(
            f"the last axis of visibilities must hold the {len(names)} products "
            f"{names}, got shape {values.shape}"
        )
    return values, unit, mask


def _finish(values, dtype, unit, mask=None):
    """Values of ``dtype``, with the unit and the mask (its kind and flags) given back."""
    values = values.astype(dtype, copy=False)
    values = values if unit is None else u.Quantity(values, unit, copy=False)
    if mask is None:
        return values
    kind, flags = mask
    return Masked(values, mask=flags) if kind == "astropy" else np.ma.MaskedArray(values, flags)


# --- single antenna ------------------------------------------------------------


def correct_phase(phase, feed_rotation, polarization="RCP", wrap=False):
    """Remove the feed rotation from phases measured by one antenna (Appendix D).

    Parameters
    ----------
    phase : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        Measured carrier phases, in any angle unit. A phase here grows with
        delay (Eq 1): it is the negative of the argument of the voltage.
    feed_rotation : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        The RCP feed rotation :math:`\\Phi`, as
        `~astropy_feedrot.Antenna.feed_rotation` returns it with
        ``polarization='RCP'`` (the default for natural sources).
    polarization : str, optional
        Hand of the measured phase: ``'RCP'`` (default) or ``'LCP'``;
        ``'RHCP'``/``'LHCP'`` and ``'R'``/``'L'`` are accepted, in any case.
    wrap : bool, optional
        If True, wrap the result to (-180, 180] deg. By default it is not
        wrapped, so that a continuous series stays continuous.

    Returns
    -------
    `~astropy.coordinates.Angle`
        :math:`\\phi - \\Phi` for RCP, :math:`\\phi + \\Phi` for LCP, in the
        unit of ``phase``, with the broadcast shape of ``phase`` and
        ``feed_rotation`` (a scalar for scalar inputs); NaN where either is NaN.

    Raises
    ------
    TypeError
        If an angle is a plain number or array instead of a Quantity.
    astropy.units.UnitsError
        If an angle has a unit that is not an angle.
    ValueError
        For an unknown ``polarization`` (listing the valid names), or shapes
        that do not broadcast.

    Notes
    -----
    The feed rotation of an LCP receiver is :math:`-\\Phi`: this is what
    `~astropy_feedrot.Antenna.feed_rotation` returns with
    ``polarization='LCP'``, or by default for an LCP satellite. Do not pass
    that value together with ``polarization='LCP'``, which would negate it
    twice: pass its negative, or equivalently subtract it directly.

    Examples
    --------
    An antenna whose feed has turned by 30 deg measures an RCP phase 30 deg
    larger, and an LCP phase 30 deg smaller, than an unrotated one:

    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.correction import correct_phase
    >>> correct_phase(130 * u.deg, 30 * u.deg)  # doctest: +FLOAT_CMP
    <Angle 100. deg>
    >>> correct_phase(70 * u.deg, 30 * u.deg, polarization="LCP")  # doctest: +FLOAT_CMP
    <Angle 100. deg>
    >>> correct_phase([170, 190] * u.deg, -30 * u.deg, wrap=True)  # doctest: +FLOAT_CMP
    <Angle [-160., -140.] deg>
    """
    sign = polarization_sign(polarization)
    measured = as_radians(phase, "phase")
    rotation = as_radians(feed_rotation, "feed_rotation")
    broadcast_shape(phase=measured.shape, feed_rotation=rotation.shape)
    corrected = measured - sign * rotation
    if wrap:
        corrected = kernel.wrap_phase(corrected)
    return _to_angle(corrected, phase.unit)


# --- circular feeds ------------------------------------------------------------


def correct_visibilities(visibilities, feed_rotation1, feed_rotation2, products):
    """Remove the feed rotation from visibilities of circular feeds.

    Parameters
    ----------
    visibilities : array-like or `~astropy.units.Quantity`, complex
        Visibilities :math:`V_{pq} = \\langle v_{1p} v_{2q}^* \\rangle` of one
        baseline (antenna 2 conjugated), with the correlation products along
        the last axis.
    feed_rotation1, feed_rotation2 : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        RCP feed rotations :math:`\\Phi_1`, :math:`\\Phi_2` of the two antennas
        (as `~astropy_feedrot.Antenna.feed_rotation` returns them for a natural
        source); each must broadcast to ``visibilities[..., 0]``.
    products : sequence of str
        The products along the last axis of ``visibilities``, any subset of
        ``('RR', 'RL', 'LR', 'LL')`` in any order and case.

    Returns
    -------
    `~numpy.ndarray` or `~astropy.units.Quantity`
        New corrected visibilities, of the same shape, dtype (complex64 stays
        complex64), unit and mask as ``visibilities``; NaN where an angle is
        NaN or masked. The input is not modified.

    Raises
    ------
    TypeError
        If ``visibilities`` is not complex, if an angle is not a Quantity, or
        if ``products`` is not a sequence of names.
    astropy.units.UnitsError
        If an angle has a unit that is not an angle.
    ValueError
        For unknown or repeated product names (listing the valid ones), a last
        axis whose length is not that of ``products``, or angles that do not
        broadcast to ``visibilities[..., 0]``.

    Notes
    -----
    The feeds multiply the visibilities by
    :math:`e^{-i(s_p\\Phi_1 - s_q\\Phi_2)}`, with :math:`s_R = +1` and
    :math:`s_L = -1`: RR by :math:`e^{i(\\Phi_2-\\Phi_1)}`, LL by
    :math:`e^{-i(\\Phi_2-\\Phi_1)}`, RL by :math:`e^{-i(\\Phi_1+\\Phi_2)}`, LR by
    :math:`e^{i(\\Phi_1+\\Phi_2)}` (Eq 46 for RR and LL; CASA's ``PJones`` for
    circular feeds). The correction multiplies by the inverse.

    Examples
    --------
    A source of phase 10 deg seen with feed rotations of 50 deg and 20 deg:
    the RR phase is 10 + (20 - 50) deg, the LL phase 10 - (20 - 50) deg.

    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.correction import correct_visibilities
    >>> observed = np.exp(1j * np.radians([10 - 30, 10 + 30]))
    >>> corrected = correct_visibilities(observed, 50 * u.deg, 20 * u.deg, ("RR", "LL"))
    >>> np.degrees(np.angle(corrected))  # doctest: +FLOAT_CMP
    array([10., 10.])
    """
    names = _products(products, CIRCULAR_PRODUCTS, all_required=False)
    values, unit, mask = _visibilities(visibilities, names)
    phi1 = as_radians(feed_rotation1, "feed_rotation1")
    phi2 = as_radians(feed_rotation2, "feed_rotation2")
    _fit(values.shape[:-1], feed_rotation1=phi1.shape, feed_rotation2=phi2.shape)
    hand1 = np.array([polarization_sign(name[0]) for name in names], dtype=float)
    hand2 = np.array([polarization_sign(name[1]) for name in names], dtype=float)
    angle = phi1[..., np.newaxis] * hand1 - phi2[..., np.newaxis] * hand2
    return _finish(values * np.exp(1j * angle), values.dtype, unit, mask)


# --- linear feeds --------------------------------------------------------------


def _rotation(radians):
    c, s = np.cos(radians), np.sin(radians)
    return np.stack([np.stack([c, -s], axis=-1), np.stack([s, c], axis=-1)], axis=-2)


def rotation_matrix(feed_rotation):
    """The 2x2 matrix that turns a plane vector by an angle.

    Parameters
    ----------
    feed_rotation : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        The angle :math:`\\Phi`.

    Returns
    -------
    `~numpy.ndarray`
        :math:`R(\\Phi) = [[\\cos\\Phi, -\\sin\\Phi], [\\sin\\Phi, \\cos\\Phi]]`,
        of shape ``feed_rotation.shape + (2, 2)``. Acting on (north, east)
        components it turns a vector from north toward east by :math:`\\Phi`.

    Raises
    ------
    TypeError
        If the angle is not a Quantity.
    astropy.units.UnitsError
        If it is not an angle.

    Notes
    -----
    A linear feed whose X dipole lies at position angle :math:`\\Phi` (and Y
    at :math:`\\Phi + 90^\\circ`) measures :math:`(v_X, v_Y) = R(-\\Phi)\\,
    (E_\\mathrm{north}, E_\\mathrm{east})`: its Jones matrix is
    :math:`R(-\\Phi) = R(\\Phi)^T`, the linear ``PJones`` of CASA, and
    `correct_linear_visibilities` applies :math:`R(\\Phi_1)\\,V\\,R(\\Phi_2)^T`.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.correction import rotation_matrix
    >>> rotation_matrix(30 * u.deg)  # doctest: +FLOAT_CMP
    array([[ 0.8660254, -0.5      ],
           [ 0.5      ,  0.8660254]])
    >>> rotation_matrix([0, 90, 180] * u.deg).shape
    (3, 2, 2)
    """
    return _rotation(as_radians(feed_rotation, "feed_rotation"))


def correct_linear_visibilities(visibilities, feed_rotation1, feed_rotation2,
                                products=LINEAR_PRODUCTS):
    """Remove the feed rotation from visibilities of linear feeds.

    Parameters
    ----------
    visibilities : array-like or `~astropy.units.Quantity`, complex
        Visibilities :math:`V_{pq} = \\langle v_{1p} v_{2q}^* \\rangle` of one
        baseline with the four products along the last axis.
    feed_rotation1, feed_rotation2 : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        Feed rotations :math:`\\Phi_1`, :math:`\\Phi_2`: the position angle of
        each antenna's X dipole (north through east; Y lies 90 deg further
        toward east), i.e. `~astropy_feedrot.Antenna.feed_rotation` plus the
        constant angle of the dipole. Each must broadcast to
        ``visibilities[..., 0]``.
    products : sequence of str, optional
        The order of the last axis: the four names ``'XX'``, ``'XY'``,
        ``'YX'``, ``'YY'`` in any order and case (default in that order).

    Returns
    -------
    `~numpy.ndarray` or `~astropy.units.Quantity`
        New visibilities :math:`R(\\Phi_1)\\,V\\,R(\\Phi_2)^T` in the frame of
        (north, east) dipoles, same shape, dtype and unit as the input; masked
        as the input, a sample wholly where any of its products is; the input
        is not modified.

    Raises
    ------
    TypeError
        If ``visibilities`` is not complex, if an angle is not a Quantity, or
        if ``products`` is not a sequence of names.
    astropy.units.UnitsError
        If an angle has a unit that is not an angle.
    ValueError
        For unknown, repeated or missing product names, a last axis whose
        length is not 4, or angles that do not broadcast to
        ``visibilities[..., 0]``.

    Notes
    -----
    With the feed Jones matrices :math:`R(-\\Phi_i)` (see `rotation_matrix`)
    the observed coherency is :math:`R(-\\Phi_1)\\,V\\,R(-\\Phi_2)^T`, whose
    inverse is applied here. For a source with Stokes :math:`(I, Q, U)` seen
    with :math:`\\Phi_1 = \\Phi_2 = \\chi`, the feeds see :math:`Q` and
    :math:`U` turned by :math:`-2\\chi`. Converted to circular products with
    :math:`R = (X + iY)/\\sqrt{2}`, :math:`L = (X - iY)/\\sqrt{2}` (IEEE
    right-handed, IAU :math:`RR = I + V`, :math:`RL = Q + iU`), this correction
    is exactly `correct_visibilities`.

    Examples
    --------
    A source with Stokes I = 1, Q = 0.1, seen by two feeds turned by 30 deg,
    has the linear polarization turned by -60 deg: XX = I + Q cos 60 deg,
    XY = YX = -Q sin 60 deg, YY = I - Q cos 60 deg. The correction recovers
    XX = I + Q, YY = I - Q and no cross-hand signal:

    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.correction import correct_linear_visibilities
    >>> q, c, s = 0.1, np.cos(np.radians(60)), np.sin(np.radians(60))
    >>> observed = np.array([1 + q * c, -q * s, -q * s, 1 - q * c], dtype=complex)
    >>> corrected = correct_linear_visibilities(observed, 30 * u.deg, 30 * u.deg)
    >>> np.allclose(corrected, [1.1, 0, 0, 0.9], rtol=0, atol=1e-15)
    True
    """
    names = _products(products, LINEAR_PRODUCTS, all_required=True)
    values, unit, mask = _visibilities(visibilities, names)
    if mask is not None:  # R V R^T mixes the four products of a sample
        mask = (mask[0], np.broadcast_to(np.any(mask[1], axis=-1, keepdims=True),
                                         values.shape).copy())
    phi1 = as_radians(feed_rotation1, "feed_rotation1")
    phi2 = as_radians(feed_rotation2, "feed_rotation2")
    _fit(values.shape[:-1], feed_rotation1=phi1.shape, feed_rotation2=phi2.shape)
    order = [names.index(name) for name in LINEAR_PRODUCTS]
    matrix = values[..., order].reshape(values.shape[:-1] + (2, 2))
    corrected = _rotation(phi1) @ matrix @ np.swapaxes(_rotation(phi2), -1, -2)
    out = np.empty(values.shape, dtype=np.result_type(values.dtype, corrected.dtype))
    out[..., order] = corrected.reshape(values.shape)
    return _finish(out, values.dtype, unit, mask)


# --- receptor by receptor --------------------------------------------------------


# Rows multiplied at once by `_multiply`: about this many bytes of visibilities (they
# stay in the cache while their factor is repeated and applied).
_BLOCK_BYTES = 2**18


def _rows_contiguous(a):
    """Whether each row (the first axis) of ``a`` lies contiguous in memory."""
    expected = a.itemsize
    for size, stride in zip(a.shape[:0:-1], a.strides[:0:-1]):
        if size != 1 and stride != expected:
            return False
        expected *= size
    return True


def _multiply(values, factor, out):
    """``np.multiply(values, factor, out=out)`` where ``factor`` (rows, 1, ..., 1,
    products) is the same along the axes between (channels, bands).

    Broadcast so, numpy's inner loop is as long as the last axis, a few
    products; the factor repeated over the middle axes, a block of rows at a
    time, makes it as long as the block: several times faster, the same bits.
    """
    shape = values.shape
    middle = int(np.prod(shape[1:-1])) if values.ndim >= 3 else 0
    if middle < 8 or out.shape != shape \
            or factor.shape != (shape[0],) + (1,) * (values.ndim - 2) + (shape[-1],) \
            or not (_rows_contiguous(values) and _rows_contiguous(out)):
        np.multiply(values, factor, out=out, casting="same_kind")
        return
    n, k = shape[0], shape[-1]
    v, o, f = values.reshape(n, middle, k), out.reshape(n, middle, k), factor.reshape(n, 1, k)
    if not np.may_share_memory(o, out):  # a copy: not the rows of out
        np.multiply(values, factor, out=out, casting="same_kind")
        return
    step = max(1, _BLOCK_BYTES // (middle * k * values.itemsize))
    for a in range(0, n, step):
        np.multiply(v[a:a + step], np.repeat(f[a:a + step], middle, axis=1), out=o[a:a + step],
                    casting="same_kind")


def _product_names(products):
    """Upper-case two-letter product names, their basis, checked."""
    if isinstance(products, str):
        raise TypeError(f"products must be a sequence of names such as ('RR', 'LL'), not "
                        f"the single string {products!r}")
    try:
        names = tuple(str(name).strip().upper() for name in products)
    except TypeError:
        raise TypeError(f"products must be a sequence of names such as ('RR', 'LL'), got "
                        f"{products!r}") from None
    if not names or any(len(name) != 2 for name in names):
        raise ValueError(f"products are pairs of receptor letters such as 'RR', 'RL', "
                         f"'XY'; got {products!r}")
    basis = basis_of(names)
    duplicates = sorted({name for name in names if names.count(name) > 1})
    if duplicates:
        raise ValueError(f"products names {duplicates} more than once")
    return names, basis


def _linear_rows(theta):
    """The rows (..., 2, 2) of the linear feed at position angles (X, Y) ``theta``."""
    rows = np.empty(theta.shape[:-1] + (2, 2))
    rows[..., 0, 0], rows[..., 0, 1] = np.cos(theta[..., 0]), np.sin(theta[..., 0])
    rows[..., 1, 0], rows[..., 1, 1] = np.cos(theta[..., 1]), np.sin(theta[..., 1])
    return rows


def _linear_inverse(theta):
    """Inverse (..., 2, 2) of the linear feed's rows at position angles (X, Y) ``theta``."""
    a, b = theta[..., 0], theta[..., 1]
    det = np.sin(b - a)
    if np.any(np.abs(det[np.isfinite(det)]) < 1e-6):
        raise ValueError("the X and Y receptors of a feed are parallel in position_angles; "
                         "their signals cannot be separated")
    inverse = np.empty(theta.shape[:-1] + (2, 2))
    inverse[..., 0, 0], inverse[..., 0, 1] = np.sin(b) / det, -np.sin(a) / det
    inverse[..., 1, 0], inverse[..., 1, 1] = -np.cos(b) / det, np.cos(a) / det
    return inverse


def correct_receptor_visibilities(visibilities, position_angles1, position_angles2, products,
                                  *, conjugate=False, out=None, direction="remove"):
    """Remove (or apply) the feed rotation of visibilities, receptor by receptor.

    The general form of `correct_visibilities` and
    `correct_linear_visibilities`: each receptor has its own position angle
    on the sky (feed rotation plus receptor angle, see
    `~astropy_feedrot.antennas.receptors`), the two linear receptors need not be 90 deg
    apart nor in the order X then Y, and the visibilities may follow
    pyuvdata's conjugation.

    Parameters
    ----------
    visibilities : array-like or `~astropy.units.Quantity`, complex
        Correlation products along the last axis; a `numpy.ma.MaskedArray`
        or an astropy `~astropy.utils.masked.Masked` array keeps its mask.
    position_angles1, position_angles2 : `~astropy.units.Quantity` or `~astropy.coordinates.Angle`
        Position angles :math:`\\theta` of the receptors of antenna 1 and 2,
        shape ``(..., 2)`` with the last axis in the order ``(R, L)`` or
        ``(X, Y)`` (whatever the order of the file), broadcasting to
        ``visibilities[..., 0]``; for example
        `~astropy_feedrot.antennas.receptors.Receptors.position_angles`.
    products : sequence of str
        The products along the last axis: any subset of ``RR``, ``RL``,
        ``LR``, ``LL``, or all four of ``XX``, ``XY``, ``YX``, ``YY``, in any
        order; the first letter is antenna 1's receptor.
    conjugate : bool, optional
        False (default) for :math:`V_{pq} = \\langle v_{1p} v_{2q}^* \\rangle`,
        the convention of UVFITS, FITS-IDI and Measurement Sets; True for
        their complex conjugate, the convention of pyuvdata's
        ``data_array``.
    out : `~numpy.ndarray`, optional
        Where to write the result, of the shape of ``visibilities``; it may
        be ``visibilities`` itself, to correct in place.
    direction : {'remove', 'apply'}, optional
        ``'remove'`` (default): from the visibilities of the receptors as
        they turn, those of receptors fixed on the sky. ``'apply'``: the
        inverse, from sky-fixed receptors (e.g. a model) to the turning
        ones, as the antennas would measure them.

    Returns
    -------
    `~numpy.ndarray` or `~astropy.units.Quantity`
        With ``'remove'``, the visibilities of receptors fixed on the sky,
        in the same convention, dtype, unit and mask: circular R and L of
        the sky, or linear X toward north and Y toward east (IAU; a sample
        is masked wholly where any of its four products is); with
        ``'apply'``, those of the receptors at ``position_angles``. NaN where
        an angle is NaN.

    Raises
    ------
    TypeError
        If ``visibilities`` is not complex, an angle is not a Quantity, or
        ``products`` is not a sequence of names.
    astropy.units.UnitsError
        If an angle is not an angle.
    ValueError
        For unknown, repeated or mixed products; linear products without all
        four (the correction mixes them, so parallel hands alone cannot be
        corrected per visibility: rotate Stokes Q and U by twice the feed
        rotation instead); angles whose last axis is not 2 or that do not
        broadcast; parallel linear receptors; ``out`` of another shape; a
        ``direction`` other than ``'remove'`` or ``'apply'``.

    Notes
    -----
    With receptor rows :math:`J_i` (`~astropy_feedrot.antennas.receptors.Receptors.jones`)
    the observed coherency is :math:`V = J_1 B J_2^H`. For circular
    receptors :math:`J_i` is diagonal in the circular basis and
    :math:`B_{pq} = V_{pq}\\, e^{i(s_p\\theta_{1p} - s_q\\theta_{2q})}`
    (:math:`s_R = 1`, :math:`s_L = -1`), one product at a time; for linear
    receptors :math:`B = J_1^{-1} V J_2^{-T}`. Conjugated data take the
    conjugate factor (the linear rows are real, so they are unchanged).
    ``'apply'`` computes :math:`V` from :math:`B`, so that applying then
    removing gives the input back to rounding.

    Examples
    --------
    An ATA-like feed (X horizontal at 90 deg, Y vertical at 0 deg) turned by a
    parallactic angle of 30 deg sees an unpolarized source as XX = YY = 1:
    that stays so, and the cross hands stay empty:

    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.correction import correct_receptor_visibilities
    >>> theta = [30 + 90, 30 + 0] * u.deg  # (X, Y)
    >>> v = np.array([1, 0, 0, 1], dtype=complex)
    >>> out = correct_receptor_visibilities(v, theta, theta, ["XX", "XY", "YX", "YY"])
    >>> np.allclose(out, [1, 0, 0, 1], rtol=0, atol=1e-15)
    True

    RR of a source of phase 10 deg, seen with position angles 50 deg and
    20 deg, has phase 10 + (20 - 50) deg; pyuvdata stores its conjugate:

    >>> theta1, theta2 = [50, -50] * u.deg, [20, -20] * u.deg
    >>> rr = np.exp(1j * np.radians([10 - 30]))
    >>> out = correct_receptor_visibilities(rr.conj(), theta1, theta2, ["RR"], conjugate=True)
    >>> np.degrees(np.angle(out.conj()))  # doctest: +FLOAT_CMP
    array([10.])

    Applying the rotation to that corrected value gives the data back:

    >>> back = correct_receptor_visibilities(out, theta1, theta2, ["RR"], conjugate=True,
    ...                                      direction="apply")
    >>> bool(np.allclose(back, rr.conj()))
    True
    """
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    names, basis = _product_names(products)
    values, unit, mask = _visibilities(visibilities, names)
    theta1 = as_radians(position_angles1, "position_angles1")
    theta2 = as_radians(position_angles2, "position_angles2")
    for name, theta in (("position_angles1", theta1), ("position_angles2", theta2)):
        if theta.ndim == 0 or theta.shape[-1] != 2:
            raise ValueError(f"{name} must have a last axis of 2 (the receptors "
                             f"{RECEPTOR_TYPES[basis]}), got shape {theta.shape}")
    _fit(values.shape[:-1], position_angles1=theta1.shape[:-1],
         position_angles2=theta2.shape[:-1])
    if out is None:
        out = np.empty_like(values)
    elif out.shape != values.shape:
        raise ValueError(f"out has shape {out.shape}, visibilities {values.shape}")
    sign = -1.0 if conjugate else 1.0
    if direction == "apply":
        sign = -sign
    if basis == "circular":
        index = {letter: k for k, letter in enumerate(RECEPTOR_TYPES["circular"])}
        factors = []
        for name in names:
            p, q = name
            angle = (polarization_sign(p) * theta1[..., index[p]]
                     - polarization_sign(q) * theta2[..., index[q]])
            factors.append(np.exp(1j * sign * angle))
        # One factor per product, then one pass over the data; single-precision
        # data (visibility files) take single-precision factors, so that the
        # multiplication needs no wider copy.
        factor = np.stack(np.broadcast_arrays(*factors), axis=-1)
        if values.dtype.itemsize == 8:  # complex64, in either byte order
            factor = factor.astype(np.complex64)
        _multiply(values, factor, out)
        return _finish(out, values.dtype, unit, mask)
    missing = [name for name in LINEAR_PRODUCTS if name not in names]
    if missing:
        raise ValueError(
            f"linear products {names} lack {missing}: the feed rotation of linear feeds "
            "mixes XX, XY, YX and YY, so it cannot be removed visibility by visibility "
            "without all four. With parallel hands only, rotate Stokes Q + iU by minus "
            "twice the feed rotation after imaging instead"
        )
    if mask is not None:  # the correction mixes the four products of a sample
        mask = (mask[0], np.broadcast_to(np.any(mask[1], axis=-1, keepdims=True),
                                         values.shape).copy())
    if direction == "apply":
        m1, m2 = _linear_rows(theta1), _linear_rows(theta2)
    else:
        m1, m2 = _linear_inverse(theta1), _linear_inverse(theta2)
    order = [names.index(name) for name in LINEAR_PRODUCTS]
    v = [values[..., k] for k in order]  # XX, XY, YX, YY
    # M1 V: rows of V mixed.
    a00 = m1[..., 0, 0] * v[0] + m1[..., 0, 1] * v[2]
    a01 = m1[..., 0, 0] * v[1] + m1[..., 0, 1] * v[3]
    a10 = m1[..., 1, 0] * v[0] + m1[..., 1, 1] * v[2]
    a11 = m1[..., 1, 0] * v[1] + m1[..., 1, 1] * v[3]
    # (M1 V) M2^T: columns mixed.
    result = (a00 * m2[..., 0, 0] + a01 * m2[..., 0, 1],
              a00 * m2[..., 1, 0] + a01 * m2[..., 1, 1],
              a10 * m2[..., 0, 0] + a11 * m2[..., 0, 1],
              a10 * m2[..., 1, 0] + a11 * m2[..., 1, 1])
    for k, value in zip(order, result):
        out[..., k] = value
    return _finish(out, values.dtype, unit, mask)


# --- the dual-polarization check (Eq 46) ----------------------------------------
