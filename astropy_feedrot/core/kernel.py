# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Pure-numpy geometry kernel of feed rotation.

Every function here works on plain floating-point arrays whose last axis has
length 3 (Cartesian vectors, all expressed in one common frame, normally the
Earth-fixed ITRS) and broadcasts over all leading axes like a numpy ufunc.
Angles are in radians. No astropy object enters or leaves this module; the
layers above turn `~astropy.time.Time`, `~astropy.coordinates.EarthLocation`
and `~astropy.coordinates.SkyCoord` into such arrays, and attach units to what
comes back.

Equation numbers refer to Skeens et al., "A unified model of feed rotation in
radio telescopes and GNSS antennas" (the specification of this package).

Where the geometry is degenerate (an effective dipole of zero length: a source
along a telescope's fixed axis, a source at the celestial pole, ...), the
angle is undefined and the functions return NaN for that element instead of
the arbitrary value ``atan2(0, 0) = 0``. A vector counts as zero when its norm
is below `DEGENERATE_NORM`, i.e. when the line of sight is within about
0.2 mas of the offending direction.
"""

import numpy as np

__all__ = [
    "DEGENERATE_NORM",
    "NORTH_POLE",
    "dot",
    "over_components",
    "unit",
    "projection_matrix",
    "cross_matrix",
    "project",
    "receiver_effective_dipole",
    "transmitter_effective_dipole",
    "transmitter_dipole",
    "wu_phase",
    "beyerle_phase",
    "beyerle_phase_from_products",
    "transmitter_term",
    "receiver_term",
    "wrap_phase",
    "nearest_cycle",
    "unwrap_phase",
    "mirror_normal",
    "reflect_dipole",
    "trace_dipole",
    "feed_phase",
]

#: Norm below which a vector built from unit vectors counts as zero (a
#: direction known to worse than ~0.2 mas), making the angle undefined.
DEGENERATE_NORM = 1e-9

#: The north celestial pole in the Earth-fixed frame, ``z = [0, 0, 1]``
#: (Appendix D of the paper).
NORTH_POLE = np.array([0.0, 0.0, 1.0])


def dot(a, b):
    """Scalar product over the last axis, broadcasting the others.

    Parameters
    ----------
    a, b : array-like, shape (..., 3)
        Vectors.

    Returns
    -------
    ndarray, shape (...)
        ``sum(a * b, axis=-1)``.

    Examples
    --------
    >>> from astropy_feedrot.core.kernel import dot
    >>> float(dot([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]))
    32.0
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return np.einsum("...i,...i->...", a, b)


def over_components(x, n=3):
    """Scalars repeated over the ``n`` components of a vector, contiguous.

    Multiplying vectors of shape (..., 3) by scalars broadcast as (..., 1)
    makes numpy's inner loop 3 elements long; the scalars repeated to
    (..., 3) first make it the length of the array, several times faster
    for the same arithmetic (the same bits).

    Parameters
    ----------
    x : array-like, shape (...)
        Scalars.
    n : int, optional
        Components.

    Returns
    -------
    ndarray, shape (..., n)

    Examples
    --------
    >>> from astropy_feedrot.core.kernel import over_components
    >>> over_components([1.0, 2.0])
    array([[1., 1., 1.],
           [2., 2., 2.]])
    """
    x = np.asarray(x, dtype=float)
    out = np.empty(x.shape + (n,))
    for j in range(n):  # n column copies: faster than np.repeat for a few components
        out[..., j] = x
    return out


def unit(v):
    """Normalize vectors to unit length; NaN where the norm is degenerate.

    Parameters
    ----------
    v : array-like, shape (..., 3)
        Vectors.

    Returns
    -------
    ndarray, shape (..., 3)
        ``v / |v|``, with NaN components where ``|v| < DEGENERATE_NORM``.

    Examples
    --------
    >>> from astropy_feedrot.core.kernel import unit
    >>> unit([3.0, 0.0, 4.0])
    array([0.6, 0. , 0.8])
    """
    v = np.asarray(v, dtype=float)
    norm = np.sqrt(dot(v, v))[..., np.newaxis]
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(norm < DEGENERATE_NORM, np.nan, v / norm)


def projection_matrix(s):
    """Projection onto the plane perpendicular to the line of sight (Eq 4).

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Source unit vector(s) :math:`\\hat{s}`.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        :math:`P = I - \\hat{s}\\hat{s}^T`.

    See Also
    --------
    project : applies the projection without forming the matrix.

    Examples
    --------
    >>> from astropy_feedrot.core.kernel import projection_matrix
    >>> projection_matrix([0.0, 0.0, 1.0])
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 0.]])
    """
    s = np.asarray(s, dtype=float)
    return np.eye(3) - s[..., :, np.newaxis] * s[..., np.newaxis, :]


def cross_matrix(s):
    """Matrix of the cross product with the line of sight (Eq 6).

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Source unit vector(s).

    Returns
    -------
    ndarray, shape (..., 3, 3)
        :math:`S_\\times` such that ``S_x @ v == np.cross(s, v)``.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import cross_matrix
    >>> cross_matrix([0.0, 0.0, 1.0]) @ np.array([1.0, 0.0, 0.0])
    array([0., 1., 0.])
    """
    s = np.asarray(s, dtype=float)
    x, y, z = s[..., 0], s[..., 1], s[..., 2]
    zero = np.zeros_like(x)
    return np.stack(
        [
            np.stack([zero, -z, y], axis=-1),
            np.stack([z, zero, -x], axis=-1),
            np.stack([-y, x, zero], axis=-1),
        ],
        axis=-2,
    )


def project(v, s):
    """Apply the projection of Eq 4 without forming the matrix.

    Parameters
    ----------
    v : array-like, shape (..., 3)
        Vector(s) to project.
    s : array-like, shape (..., 3)
        Source unit vector(s).

    Returns
    -------
    ndarray, shape (..., 3)
        The component of ``v`` perpendicular to ``s`` (Eqs 10, 11).

    Examples
    --------
    >>> from astropy_feedrot.core.kernel import project
    >>> project([1.0, 1.0, 1.0], [0.0, 0.0, 1.0])
    array([1., 1., 0.])
    """
    v = np.asarray(v, dtype=float)
    s = np.asarray(s, dtype=float)
    return v - dot(v, s)[..., np.newaxis] * s


def receiver_effective_dipole(s, aligned, transverse):
    """Effective dipole of a receiving crossed dipole (Eq 8).

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Source unit vector (receiver to transmitter).
    aligned, transverse : array-like, shape (..., 3)
        Aligned and transverse dipole unit vectors :math:`\\hat{r}^a`,
        :math:`\\hat{r}^t` of the receiver (a right-handed set with the
        boresight :math:`\\hat{r}^b = \\hat{r}^a \\times \\hat{r}^t`).

    Returns
    -------
    ndarray, shape (..., 3)
        :math:`r = P\\hat{r}^a - S_\\times \\hat{r}^t`, perpendicular to ``s``.

    Examples
    --------
    A GNSS antenna (dipoles east and north) seeing a source at its zenith
    (Eq 29): the effective dipole is twice the east vector (Eq A1).

    >>> from astropy_feedrot.core.kernel import receiver_effective_dipole
    >>> receiver_effective_dipole([0, 0, 1.0], [1.0, 0, 0], [0, 1.0, 0])
    array([2., 0., 0.])
    """
    s = np.asarray(s, dtype=float)
    return project(aligned, s) - np.cross(s, np.asarray(transverse, dtype=float))


def transmitter_effective_dipole(s, aligned, transverse):
    """Effective dipole of a transmitting crossed dipole (Eq 8).

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Source unit vector (receiver to transmitter).
    aligned, transverse : array-like, shape (..., 3)
        Aligned and transverse dipole unit vectors :math:`\\hat{t}^a`,
        :math:`\\hat{t}^t` of the transmitter.

    Returns
    -------
    ndarray, shape (..., 3)
        :math:`t = P\\hat{t}^a + S_\\times \\hat{t}^t`, perpendicular to ``s``.

    Examples
    --------
    A transmitter whose boresight points at the receiver (Eq A4):

    >>> from astropy_feedrot.core.kernel import transmitter_effective_dipole
    >>> transmitter_effective_dipole([0, 0, 1.0], [1.0, 0, 0], [0, -1.0, 0])
    array([2., 0., 0.])
    """
    s = np.asarray(s, dtype=float)
    return project(aligned, s) + np.cross(s, np.asarray(transverse, dtype=float))


def transmitter_dipole(s, aligned=None, transverse=None):
    """Effective dipole of the transmitter along lines of sight (Eqs 8, 11).

    Parameters
    ----------
    s : ndarray, shape (..., 3)
        Source unit vectors (receiver to transmitter) in ITRS.
    aligned, transverse : ndarray, shape (..., 3), optional
        The transmitter's dipoles; None for a natural source.

    Returns
    -------
    ndarray, shape (..., 3)
        :math:`P\\hat{t}^a + S_\\times\\hat{t}^t` (Eq 8), or the projected
        celestial pole :math:`P\\hat{z}` of a natural source (Eq 11).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import transmitter_dipole
    >>> transmitter_dipole(np.array([1.0, 0.0, 0.0]))
    array([0., 0., 1.])
    """
    if aligned is None:
        return project(NORTH_POLE, s)
    return transmitter_effective_dipole(s, aligned, transverse)


def _atan2_defined(num, den, defined):
    with np.errstate(invalid="ignore"):
        out = np.arctan2(num, den)
    if out.ndim == 0 or np.broadcast_shapes(out.shape, np.shape(defined)) != out.shape:
        return np.where(defined, out, np.nan)
    out[~np.broadcast_to(defined, out.shape)] = np.nan  # in place: no third array
    return out


def wu_phase(s, r, t):
    """Phase wind-up from effective dipoles, the form of Wu et al. (Eq 7).

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Source unit vector.
    r, t : array-like, shape (..., 3)
        Receiver and transmitter effective dipoles (Eq 8), or any vectors whose
        projections perpendicular to ``s`` are those dipoles.

    Returns
    -------
    ndarray, shape (...)
        :math:`\\Phi = \\mathrm{atan2}(\\hat{s}\\cdot(r \\times t),\\; r\\cdot t)`
        in radians, in :math:`(-\\pi, \\pi]`; NaN where the projection of ``r``
        or ``t`` on the plane of the sky is degenerate.

    Notes
    -----
    Only the components of ``r`` and ``t`` perpendicular to ``s`` enter, so
    ``r`` may be any fixed-axis vector (Eqs 10, 13): ``wu_phase(s, a, z)`` is
    the feed rotation of Eq 13.

    Examples
    --------
    The parallactic angle (Eq 15) of a source due west of the zenith at a
    latitude of 45 degrees, in a local east-north-up frame:

    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import wu_phase
    >>> up = np.array([0.0, 0.0, 1.0])
    >>> pole = np.array([0.0, np.cos(np.pi / 4), np.sin(np.pi / 4)])
    >>> west = np.array([-1.0, 0.0, 0.0])
    >>> float(np.degrees(wu_phase(west, up, pole)))  # doctest: +FLOAT_CMP
    45.0
    """
    s = np.asarray(s, dtype=float)
    r = project(r, s)
    t = project(t, s)
    defined = (dot(r, r) >= DEGENERATE_NORM**2) & (dot(t, t) >= DEGENERATE_NORM**2)
    return _atan2_defined(dot(s, np.cross(r, t)), dot(r, t), defined)


def beyerle_phase(s, r_aligned, r_transverse, t_aligned, t_transverse):
    """Phase wind-up of two crossed dipoles, the form of Beyerle (Eq 5).

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Source unit vector (receiver to transmitter).
    r_aligned, r_transverse : array-like, shape (..., 3)
        Receiver aligned and transverse dipole unit vectors.
    t_aligned, t_transverse : array-like, shape (..., 3)
        Transmitter aligned and transverse dipole unit vectors.

    Returns
    -------
    ndarray, shape (...)
        The phase in radians, in :math:`(-\\pi, \\pi]`; NaN where both the
        numerator and the denominator of Eq 5 vanish.

    Notes
    -----
    Unlike `wu_phase`, this form keeps the response of a receiver that does
    not point at the transmitter to the cross-hand (LHCP) part of an
    off-boresight signal. It equals `wu_phase` of the effective dipoles when
    either boresight lies along the line of sight (Appendix A). The scalar
    products are formed here and handed to `beyerle_phase_from_products`,
    which holds the equation.

    Examples
    --------
    Receiver dipoles rotated by 30 degrees about the line of sight with
    respect to the transmitter's:

    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import beyerle_phase
    >>> c, s30 = np.cos(np.radians(30)), np.sin(np.radians(30))
    >>> phi = beyerle_phase([0, 0, 1.0], [c, s30, 0], [-s30, c, 0],
    ...                     [1.0, 0, 0], [0, -1.0, 0])
    >>> float(np.degrees(phi))  # doctest: +FLOAT_CMP
    -30.0
    """
    s = np.asarray(s, dtype=float)
    return beyerle_phase_from_products(
        dot(r_aligned, t_aligned), dot(r_aligned, t_transverse),
        dot(r_transverse, t_aligned), dot(r_transverse, t_transverse),
        dot(s, r_aligned), dot(s, r_transverse), dot(s, t_aligned), dot(s, t_transverse))


def beyerle_phase_from_products(ra_ta, ra_tt, rt_ta, rt_tt, s_ra, s_rt, s_ta, s_tt):
    """Beyerle's form (Eq 5) from the scalar products of the dipoles and the line of sight.

    With :math:`P v = v - (v\\cdot\\hat{s})\\hat{s}` (Eq 4) every term of
    Eq 5 is a scalar product of the unit vectors, so the phase needs only
    these eight numbers per line of sight, however they were obtained (from
    the vectors, as `beyerle_phase` does, or by contracting positions and
    dipoles of many receivers and transmitters at once).

    Parameters
    ----------
    ra_ta, ra_tt, rt_ta, rt_tt : array-like
        :math:`\\hat{r}^a\\cdot\\hat{t}^a`, :math:`\\hat{r}^a\\cdot\\hat{t}^t`,
        :math:`\\hat{r}^t\\cdot\\hat{t}^a`, :math:`\\hat{r}^t\\cdot\\hat{t}^t`.
    s_ra, s_rt, s_ta, s_tt : array-like
        The scalar products of the source unit vector with the receiver's
        aligned and transverse dipoles and the transmitter's.

    Returns
    -------
    ndarray
        The phase in radians, in :math:`(-\\pi, \\pi]`, with the broadcast shape
        of the arguments; NaN where both the numerator and the denominator of
        Eq 5 are below `DEGENERATE_NORM`.

    Examples
    --------
    Dipoles of the receiver turned by 90 degrees from the transmitter's
    about a line of sight they both face:

    >>> from astropy_feedrot.core.kernel import beyerle_phase_from_products
    >>> phi = beyerle_phase_from_products(0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    >>> float(phi)  # doctest: +FLOAT_CMP
    1.5707963267948966
    """
    # num = r_a . P t_t + r_t . P t_a,  den = r_a . P t_a - r_t . P t_t
    num = np.asarray(ra_tt, dtype=float) + rt_ta - np.multiply(s_tt, s_ra) - np.multiply(s_ta, s_rt)
    den = np.asarray(ra_ta, dtype=float) - rt_tt - np.multiply(s_ta, s_ra) + np.multiply(s_tt, s_rt)
    phase = np.arctan2(num, den)
    return np.where(num * num + den * den < DEGENERATE_NORM**2, np.nan, phase)


def transmitter_term(s, t):
    """Transmitter rotation term of the split wind-up (Eq 21).

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Source unit vector.
    t : array-like, shape (..., 3)
        Transmitter effective dipole (Eq 8).

    Returns
    -------
    ndarray, shape (...)
        :math:`\\Phi_\\mathrm{tx}`, the angle of ``t`` measured from the
        projected north celestial pole (Eq B6), in radians; NaN at the pole.

    Examples
    --------
    For a natural source the transmitter dipole is the projected pole itself
    (Eq 11), so the term vanishes:

    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import transmitter_term, project, NORTH_POLE
    >>> s = np.array([0.6, 0.0, 0.8])
    >>> float(transmitter_term(s, project(NORTH_POLE, s)))
    0.0
    """
    return wu_phase(s, NORTH_POLE, t)


def receiver_term(s, r):
    """Receiver rotation term of the split wind-up (Eq 22).

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Source unit vector.
    r : array-like, shape (..., 3)
        Receiver effective dipole (Eq 8), or a fixed-axis vector (Eq 10).

    Returns
    -------
    ndarray, shape (...)
        :math:`\\Phi_\\mathrm{rx}` in radians, which for a fixed-axis
        telescope is the feed rotation of a natural source (Eq 13); NaN where
        the projection of ``r`` or of the pole on the plane of the sky is
        degenerate.

    Notes
    -----
    With the pole :math:`\\hat{z}` written out, Eq 22 (Eq 13) is a closed form
    in the components of :math:`\\hat{s}`: :math:`r^T S_\\times^T \\hat{z} =
    s_x r_y - s_y r_x` and :math:`r^T P \\hat{z} = r_z (s_x^2 + s_y^2) - s_z
    (r_x s_x + r_y s_y)`, using :math:`1 - s_z^2 = s_x^2 + s_y^2 =
    |P\\hat{z}|^2`. Both keep their precision near the pole and near
    ``r``, so the degenerate directions are those of `wu_phase`, found at a
    fraction of its cost.

    Examples
    --------
    An equatorial mount (fixed axis along the pole, Eq 17) has no feed
    rotation:

    >>> from astropy_feedrot.core.kernel import receiver_term, NORTH_POLE
    >>> float(receiver_term([0.6, 0.0, 0.8], NORTH_POLE))
    0.0
    """
    s = np.asarray(s, dtype=float)
    r = np.asarray(r, dtype=float)
    sx, sy, sz = s[..., 0], s[..., 1], s[..., 2]
    rx, ry, rz = r[..., 0], r[..., 1], r[..., 2]
    # Sums in place (each term has the whole shape): the same arithmetic with
    # fewer arrays, which over a million epochs is a fifth of the time.
    num = sx * ry
    num -= sy * rx
    pole = sx * sx
    pole += sy * sy  # |P z|^2
    den = rx * sx
    den += ry * sy
    den *= sz
    den = rz * pole - den
    # hypot(num, den) = |P r| |P z|: NaN where either is degenerate.
    norm = num * num
    norm += den * den
    defined = norm >= DEGENERATE_NORM**2 * pole
    defined &= pole >= DEGENERATE_NORM**2
    return _atan2_defined(num, den, defined)


def wrap_phase(phase):
    """Wrap angles in radians to the interval :math:`(-\\pi, \\pi]`.

    Parameters
    ----------
    phase : array-like
        Angles in radians.

    Returns
    -------
    ndarray
        The same angles modulo :math:`2\\pi`, in :math:`(-\\pi, \\pi]`.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import wrap_phase
    >>> wrap_phase(np.array([3 * np.pi / 2, -np.pi]))  # doctest: +FLOAT_CMP
    array([-1.57079633,  3.14159265])
    """
    phase = np.asarray(phase, dtype=float)
    wrapped = np.remainder(phase + np.pi, 2 * np.pi) - np.pi
    return np.where(wrapped == -np.pi, np.pi, wrapped)


def nearest_cycle(phase, previous):
    """Move a phase to the cycle of a previous value (Eq 9).

    Parameters
    ----------
    phase : array-like
        New phase(s) in radians (any cycle).
    previous : array-like
        The previous, continuous value(s) in radians.

    Returns
    -------
    ndarray
        :math:`\\Phi + 2\\pi\\,\\mathrm{round}((\\Phi_i - \\Phi)/2\\pi)`, the
        value congruent to ``phase`` closest to ``previous``.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import nearest_cycle
    >>> float(nearest_cycle(-3.0, 3.0)) == -3.0 + 2 * np.pi
    True
    """
    phase = np.asarray(phase, dtype=float)
    return phase + 2 * np.pi * np.round((np.asarray(previous) - phase) / (2 * np.pi))


def unwrap_phase(phase, axis=-1):
    """Apply Eq 9 along an axis: a series continuous across cycle boundaries.

    Each sample is moved to the cycle nearest to the previous finite sample, so
    NaN samples (degenerate or masked epochs) are kept as NaN and skipped
    without breaking the continuity of the rest.

    Parameters
    ----------
    phase : array-like
        Phases in radians.
    axis : int, optional
        The axis along which the samples are consecutive (time).

    Returns
    -------
    ndarray
        Continuous phases, same shape; the first finite sample of each series
        is unchanged.

    Notes
    -----
    Continuity is only guaranteed when consecutive finite samples differ by
    less than half a cycle (Sec. 2.1 of the paper).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import unwrap_phase
    >>> unwrap_phase(np.array([3.0, -3.0, np.nan, -2.5]))  # doctest: +FLOAT_CMP
    array([3.        , 3.28318531,        nan, 3.78318531])
    """
    phase = np.asarray(phase, dtype=float)
    if phase.ndim == 0 or phase.size == 0:
        return phase.copy()
    x = np.moveaxis(phase, axis, -1)
    finite = np.isfinite(x)
    index = np.arange(x.shape[-1])
    # Index of the latest finite sample at or before each position; positions
    # before the first finite sample take the first finite sample.
    last = np.maximum.accumulate(np.where(finite, index, -1), axis=-1)
    first = np.argmax(finite, axis=-1)[..., np.newaxis]
    last = np.where(last < 0, first, last)
    filled = np.take_along_axis(x, last, axis=-1)
    out = np.unwrap(np.nan_to_num(filled, nan=0.0), axis=-1)
    out = np.where(finite, out, np.nan)
    return np.moveaxis(out, -1, axis)


def mirror_normal(k_in, k_out):
    """Normal of a mirror reflecting ``k_in`` into ``k_out`` (Eq 42).

    Parameters
    ----------
    k_in, k_out : array-like, shape (..., 3)
        Incoming and outgoing unit wave vectors.

    Returns
    -------
    ndarray, shape (..., 3)
        :math:`\\hat{n} = (\\hat{k}_\\mathrm{out} - \\hat{k}_\\mathrm{in}) /
        \\|\\hat{k}_\\mathrm{out} - \\hat{k}_\\mathrm{in}\\|`; NaN where the two
        wave vectors are equal (no reflection).

    Examples
    --------
    >>> from astropy_feedrot.core.kernel import mirror_normal
    >>> mirror_normal([0, 0, -1.0], [1.0, 0, 0])  # doctest: +FLOAT_CMP
    array([0.70710678, 0.        , 0.70710678])
    """
    return unit(np.asarray(k_out, dtype=float) - np.asarray(k_in, dtype=float))


def reflect_dipole(q, n):
    """Reflect an effective dipole in a mirror, with the phase flip (Eq 43).

    Parameters
    ----------
    q : array-like, shape (..., 3)
        Effective dipole before the reflection.
    n : array-like, shape (..., 3)
        Unit normal of the mirror (Eq 42).

    Returns
    -------
    ndarray, shape (..., 3)
        :math:`-(q - 2(q\\cdot\\hat{n})\\hat{n})` (Eqs 43, 44).

    Examples
    --------
    >>> from astropy_feedrot.core.kernel import reflect_dipole
    >>> reflect_dipole([1.0, 0, 0], [0.0, 0, 1.0])
    array([-1., -0., -0.])
    """
    q = np.asarray(q, dtype=float)
    n = np.asarray(n, dtype=float)
    return -(q - 2 * dot(q, n)[..., np.newaxis] * n)


def trace_dipole(q, wave_vectors):
    """Carry an effective dipole through a train of mirrors (Eqs 42-44).

    Parameters
    ----------
    q : array-like, shape (..., 3)
        Effective dipole of the arriving wave (perpendicular to the first wave
        vector).
    wave_vectors : sequence of array-like, each shape (..., 3)
        The unit wave vectors :math:`\\hat{k}_1, \\hat{k}_2, \\ldots` of the
        beam, the first one before the first mirror; each consecutive pair
        defines one mirror.

    Returns
    -------
    ndarray, shape (..., 3)
        The effective dipole after the last mirror, perpendicular to the last
        wave vector.

    Examples
    --------
    Two plane mirrors folding a vertical beam back into itself:

    >>> from astropy_feedrot.core.kernel import trace_dipole
    >>> trace_dipole([1.0, 0, 0], [[0, 0, -1.0], [1.0, 0, 0], [0, 0, 1.0]]) + 0.0
    array([-1.,  0.,  0.])
    """
    q = np.asarray(q, dtype=float)
    for k_in, k_out in zip(wave_vectors[:-1], wave_vectors[1:]):
        q = reflect_dipole(q, mirror_normal(k_in, k_out))
    return q


def feed_phase(q, k_out, r_aligned, r_transverse):
    """Phase at a feed of the effective dipole arriving after mirrors (Eq 45).

    Parameters
    ----------
    q : array-like, shape (..., 3)
        Effective dipole of the wave arriving at the feed.
    k_out : array-like, shape (..., 3)
        Unit wave vector of the wave arriving at the feed; the feed's boresight
        is :math:`-\\hat{k}_\\mathrm{out}`.
    r_aligned, r_transverse : array-like, shape (..., 3)
        Aligned and transverse dipoles of the feed.

    Returns
    -------
    ndarray, shape (...)
        The phase in radians, NaN where ``q`` is degenerate.

    Notes
    -----
    The cross product is taken as :math:`\\hat{k}_\\mathrm{out}\\times q`, not
    as printed in Eq 45 (:math:`q\\times\\hat{k}_\\mathrm{out}`): with this
    order the expression reproduces Eq 31 when there is no mirror
    (:math:`\\hat{k}_\\mathrm{out} = -\\hat{s}`, :math:`q = t`), whereas the
    printed order reverses the sign of the rotation.

    Examples
    --------
    With no mirror the result equals the effective-dipole form (Eq 31):

    >>> import numpy as np
    >>> from astropy_feedrot.core.kernel import feed_phase
    >>> q = np.array([np.cos(0.3), np.sin(0.3), 0.0])
    >>> float(feed_phase(q, [0, 0, -1.0], [1.0, 0, 0], [0, 1.0, 0]))  # doctest: +FLOAT_CMP
    0.3
    """
    q = np.asarray(q, dtype=float)
    kq = np.cross(np.asarray(k_out, dtype=float), q)
    num = dot(r_aligned, kq) + dot(r_transverse, q)
    den = dot(r_aligned, q) - dot(r_transverse, kq)
    defined = dot(q, q) >= DEGENERATE_NORM**2
    return _atan2_defined(num, den, defined)
