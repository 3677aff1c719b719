# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Natural sources on a grid: one set of apparent directions for every antenna.

What the apparent direction of a source fixed in a celestial frame owes to
the site is small: the diurnal aberration (the site's velocity
:math:`\\Omega\\,\\hat{z}\\times\\vec{r}`, at most 465 m/s, moves it by up to
0.32"), the parallax of the light deflection (below 1e-4 mas) and, for
sources with a distance, the parallax (these are left to the per-site path).
Everything else (precession-nutation, annual aberration, light deflection,
the Earth's rotation and polar motion) is the same at every site. So a network
computes the geocentric apparent directions once per epoch and source
(`~astropy_feedrot.earth.orientation.EarthOrientation.source_directions` with no site),
and each antenna adds its diurnal aberration
(`~astropy_feedrot.earth.diurnal.topocentric`, to 1e-4 mas).

For tracking antennas whose focus has a closed form (`feed_rotation_block`;
fixed and sky rotators included),
Eq 13 needs no line of sight at all, only its scalar products with a few
vectors fixed at the site, :math:`\\hat{s}\\cdot(\\hat{a}\\times\\hat{z})`,
:math:`\\hat{s}\\cdot\\hat{a}` and :math:`\\hat{s}\\cdot\\hat{z}` (and the
site's east, north and up for a focus term or an elevation limit): one small
matrix product per antenna and block of epochs, the diurnal aberration
applied to the products. Antennas behind a traced
`~astropy_feedrot.MirrorTrain` (`traced_block`) take the site's lines of
sight by their components, without a rotator. Other antennas (stationary
dipoles, rotators turned by a series, optics of one's own) go through the
engine on the corrected lines of sight.
"""

from typing import NamedTuple

import numpy as np

from ..antennas.focus import MirrorTrain
from ..core import kernel
from ..core.cache import helper_thread, on_helper_thread
from ..earth.diurnal import diurnal_beta, topocentric
from ..earth.frames import LocalFrame
from . import equations
from .grid_arrays import epoch_blocks

__all__ = ["SharedBlock", "shared_block", "feed_rotation_block",
           "fast_receiver", "traced_block", "traced_receiver", "engine_block", "natural_grid",
           "PARALLEL_POINTS"]


#: Products of near-polar lines of sight are checked again from their x and y
#: components below this value of 1 - s_z**2 (the kernel's own test).
_NEAR_POLE = 1e-10


class SharedBlock(NamedTuple):
    """What every antenna shares in a block of epochs (`shared_block`)."""

    components: np.ndarray  # (3, S, t): x, y, z of the geocentric directions
    g: np.ndarray  # (S, t): 1 - s.V / 2
    half_velocity: np.ndarray  # (3, t): V / 2


def shared_block(geocentric, velocity):
    """The shared part of `feed_rotation_block` for a block of epochs.

    Parameters
    ----------
    geocentric : ndarray, shape (S, t, 3)
        Geocentric apparent unit vectors in ITRS.
    velocity : ndarray, shape (t, 3)
        The geocentre's barycentric velocity in ITRS, in units of c.

    Returns
    -------
    SharedBlock

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.engine.grid_natural import shared_block
    >>> block = shared_block(np.array([[[0.0, 0.0, 1.0]]]), np.array([[0.0, 0.0, 1e-4]]))
    >>> block.components.shape, float(block.g[0, 0])
    ((3, 1, 1), 0.99995)
    """
    components = np.ascontiguousarray(np.moveaxis(geocentric, -1, 0))
    half = 0.5 * np.ascontiguousarray(velocity.T)
    g = components[0] * -half[0]
    g -= components[1] * half[1]
    g -= components[2] * half[2]
    g += 1.0
    return SharedBlock(components, g, half)


def _dot(c, sx, sy, sz):
    """A line of sight given by its components, dotted with a constant vector."""
    value = sx * c[0]
    value += sy * c[1]
    if c[2]:
        value += sz * c[2]
    return value


def _site_line(block, beta):
    """The site's line of sight (the module's form, not normalized) from the shared
    geocentric directions: its components ``sx, sy, sz`` and ``|s|^2 - 1``.

    :math:`\\hat{s}(1 - k) + g\\vec{\\beta} + k\\vec{V}/2` with
    :math:`k = \\hat{s}\\cdot\\vec{\\beta}` (``beta`` has no z) and
    :math:`g = 1 - \\hat{s}\\cdot\\vec{V}/2`; ``|s|^2 - 1`` is of order
    :math:`\\beta^2`, to second order.
    """
    gx, gy, gz = block.components
    half = block.half_velocity
    k = gx * beta[0]
    k += gy * beta[1]
    f = 1.0 - k
    sx = gx * f
    sx += block.g * beta[0]
    sx += k * half[0]
    sy = gy * f
    sy += block.g * beta[1]
    sy += k * half[1]
    sz = gz * f
    sz += k * half[2]
    long = block.g * block.g
    long *= beta @ beta
    long -= k * k
    long += block.g * k * (2.0 * (beta[0] * half[0] + beta[1] * half[1]))
    return sx, sy, sz, long


def feed_rotation_block(block, receivers, *, min_sine=None):
    """Feed rotation (RCP, radians) of one antenna from geocentric apparent directions.

    Parameters
    ----------
    block : SharedBlock
        The geocentric directions of S sources at t epochs (`shared_block`).
    receivers : `~astropy_feedrot.engine.equations.Receivers`
        One tracking antenna whose focus has a closed form, without a
        ``'series'`` rotator (`fast_receiver`).
    min_sine : float, optional
        NaN where the sine of the elevation is below this.

    Returns
    -------
    phase : ndarray, shape (S, t)
        As ``equations.feed_rotation(receivers, s)`` with the site's lines of
        sight ``s = topocentric(geocentric, site, velocity)``
        (`~astropy_feedrot.earth.diurnal.topocentric`): Eq 13 with the fixed
        axis, plus the focus terms (Eqs 38-41), NaN where undefined or below
        the limit.
    below : ndarray of bool, shape (S, t), or None
        Where the source is below the limit (None without one).

    Raises
    ------
    ValueError
        For receivers that `fast_receiver` refuses.

    Notes
    -----
    The products are sums over the three rows, not a matrix product: a
    multithreaded BLAS on a busy machine costs more than it saves here.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot import AltAzMount
    >>> from astropy_feedrot.engine.equations import Receivers, feed_rotation
    >>> from astropy_feedrot.earth.diurnal import topocentric
    >>> from astropy_feedrot.engine.grid_natural import feed_rotation_block, shared_block
    >>> r = np.sqrt(0.5)
    >>> enu = [[0, 1.0, 0], [-r, 0, r], [r, 0, r]]  # latitude 45 deg, longitude 0
    >>> rx = Receivers.from_mounts([[4.5e6, 0, 4.5e6]], [enu], [AltAzMount()], [None])
    >>> s = np.array([[[0.0, -1.0, 0.0], [0.6, 0.0, 0.8]]])  # 1 source, 2 epochs
    >>> v = np.array([[1e-4, 0.0, 0.0], [0.0, 1e-4, 0.0]])
    >>> phase, below = feed_rotation_block(shared_block(s, v), rx)
    >>> site_s = topocentric(s, [4.5e6, 0, 4.5e6], v)
    >>> engine_phase, _ = feed_rotation(rx, site_s[..., None, None, :])
    >>> bool(np.allclose(phase, engine_phase[..., 0, 0], rtol=0, atol=1e-15))
    True
    """
    if not fast_receiver(receivers):
        raise ValueError(f"feed_rotation_block takes one tracking antenna with a closed-form "
                         f"focus and no 'series' rotator, got {receivers!r}; use "
                         "engine_block")
    axis = receivers.fixed_axis[0]
    east, north, up = receivers.station_axes[0]
    m_e, m_a = receivers.focus_terms[0]
    beta = diurnal_beta(receivers.station_xyz[0])
    across = np.cross(axis, kernel.NORTH_POLE)  # a x z (no z component)
    with np.errstate(invalid="ignore", divide="ignore"):
        sx, sy, tz, long = _site_line(block, beta)
        num = _dot(across, sx, sy, tz)
        along = _dot(axis, sx, sy, tz)
        # a.z |P z|^2 - (s.z)(s.a - (s.z)(a.z)), Eq 13 as the kernel writes it
        den = axis[2] * long
        den += axis[2]
        den -= tz * along
        pole = (1.0 - tz) * (1.0 + tz)
        pole += long
        near = np.flatnonzero(pole < _NEAR_POLE)
        if near.size:  # the exact |P z|^2 from the x and y components
            x, y = sx.ravel()[near], sy.ravel()[near]
            pole.ravel()[near] = x * x + y * y
            den.ravel()[near] = (axis[2] * pole.ravel()[near]
                                 - tz.ravel()[near] * (axis[0] * x + axis[1] * y))
        # Undefined (the kernel's receiver_term): the line of sight within about
        # 0.2 mas of the pole or of the fixed axis.
        tiny = kernel.DEGENERATE_NORM**2
        defined = (pole >= tiny) & (num * num + den * den >= tiny * pole)
        phase = np.arctan2(num, den)
        phase[~defined] = np.nan
        sine = None
        if m_e or min_sine is not None:
            sine = along if np.array_equal(up, axis) else _dot(up, sx, sy, tz)
            sine = sine * (1.0 - 0.5 * long)  # of the unit line of sight
        if m_e or m_a:
            if m_e:
                phase += m_e * np.arcsin(np.clip(sine, -1.0, 1.0))
            if m_a:
                phase += m_a * np.mod(np.arctan2(_dot(east, sx, sy, tz), _dot(north, sx, sy, tz)),
                                      2 * np.pi)
            phase = kernel.wrap_phase(phase)
        # Rotators (as the engine's): 'fixed' adds its angle; 'sky' holds the
        # receiver term at its angle, and a natural source's transmitter term is
        # 0 wherever the pole projects (NaN at the celestial pole).
        angle = receivers.rotator_angle[0]
        if receivers.fixed_index.size:
            phase = kernel.wrap_phase(phase + angle)
        elif receivers.sky_index.size:
            phase = np.where(pole >= tiny, float(kernel.wrap_phase(angle)), np.nan)
        below = None
        if min_sine is not None:
            below = sine < min_sine
            phase[below] = np.nan
    return phase, below


def fast_receiver(receivers):
    """Whether `feed_rotation_block` serves these receivers (one tracking antenna with a
    closed-form focus, without a ``'series'`` rotator).

    Examples
    --------
    >>> from astropy_feedrot.engine.grid import receiver_arrays
    >>> from astropy_feedrot.engine.equations import Receivers
    >>> from astropy_feedrot.engine.grid_natural import fast_receiver
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> fast_receiver(Receivers.from_arrays(receiver_arrays([get_antenna("WETTZ13S")])))
    True
    """
    return (len(receivers) == 1 and not receivers.stationary[0]
            and not receivers.traced_index.size and not receivers.series_index.size)


def traced_block(block, receivers, *, min_sine=None):
    """`feed_rotation_block` for one antenna whose `~astropy_feedrot.MirrorTrain` is traced.

    Parameters
    ----------
    block : SharedBlock
        The geocentric directions of S sources at t epochs (`shared_block`).
    receivers : `~astropy_feedrot.engine.equations.Receivers`
        One tracking antenna with a traced `~astropy_feedrot.MirrorTrain` and
        no rotator (`traced_receiver`).
    min_sine : float, optional
        NaN where the sine of the elevation is below this.

    Returns
    -------
    phase : ndarray, shape (S, t)
        As ``equations.feed_rotation(receivers, s)`` with the site's unit lines of
        sight: the mirrors traced with the projected pole (Eqs 11, 42-45).
    below : ndarray of bool, shape (S, t), or None
        Where the source is below the limit (None without one).

    Raises
    ------
    ValueError
        For receivers that `traced_receiver` refuses.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.engine.equations import Receivers, feed_rotation
    >>> from astropy_feedrot.earth.frames import location_xyz
    >>> from astropy_feedrot.earth.diurnal import topocentric
    >>> from astropy_feedrot.engine.grid_natural import shared_block, traced_block
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> a = get_antenna("YEBES40M")
    >>> xyz = location_xyz(a.location)
    >>> rx = Receivers.from_mounts([xyz], [a.local_frame], [a.mount], [a.focus])
    >>> s = np.array([[[0.6, 0.0, 0.8], [0.0, 0.6, 0.8]]])  # 1 source, 2 epochs
    >>> v = np.array([[1e-4, 0.0, 0.0], [0.0, 1e-4, 0.0]])
    >>> phase, below = traced_block(shared_block(s, v), rx)
    >>> site_s = topocentric(s, rx.station_xyz[0], v)
    >>> engine_phase, _ = feed_rotation(rx, site_s[..., None, None, :])
    >>> bool(np.allclose(phase, engine_phase[..., 0, 0], rtol=0, atol=1e-12))
    True
    """
    if not traced_receiver(receivers):
        raise ValueError(f"traced_block takes one tracking antenna with a traced MirrorTrain "
                         f"and no rotator, got {receivers!r}; use engine_block")
    focus = receivers.traced[int(receivers.traced_index[0])]
    east, north, up = receivers.station_axes[0]
    with np.errstate(invalid="ignore", divide="ignore"):
        sx, sy, sz, long = _site_line(block, diurnal_beta(receivers.station_xyz[0]))
        norm = 1.0 - 0.5 * long  # 1 / |s| to second order in beta
        sx *= norm
        sy *= norm
        sz *= norm
        t = (-sz * sx, -sz * sy, (1.0 - sz) * (1.0 + sz))  # the projected pole, Eq 11
        phase = focus.receiver_phase_from_components(
            (sx, sy, sz), t, receivers.fixed_axis[0],
            LocalFrame(east, north, up))
        below = None
        if min_sine is not None:
            below = _dot(up, sx, sy, sz) < min_sine
            phase[below] = np.nan
    return phase, below


def traced_receiver(receivers):
    """Whether `traced_block` serves these receivers (one tracking antenna with a
    traced `~astropy_feedrot.MirrorTrain`, no rotator).

    Examples
    --------
    >>> from astropy_feedrot.engine.equations import Receivers
    >>> from astropy_feedrot.earth.frames import location_xyz
    >>> from astropy_feedrot.engine.grid_natural import traced_receiver
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> a = get_antenna("WARK30M")
    >>> xyz = location_xyz(a.location)
    >>> traced_receiver(Receivers.from_mounts([xyz], [a.local_frame], [a.mount], [a.focus]))
    True
    """
    return (len(receivers) == 1 and receivers.traced_index.size == 1 and not receivers.rotators
            and isinstance(receivers.traced[int(receivers.traced_index[0])], MirrorTrain))


def engine_block(geocentric, velocity, receivers, *, min_sine=None):
    """`feed_rotation_block` for any antenna: the engine on the site's lines of sight.

    Parameters
    ----------
    geocentric : ndarray, shape (S, t, 3)
        Geocentric apparent unit vectors in ITRS.
    velocity : ndarray, shape (t, 3)
        The geocentre's barycentric velocity in ITRS, in units of c.
    receivers : `~astropy_feedrot.engine.equations.Receivers`
        One antenna (without a ``'series'`` rotator).
    min_sine : float, optional
        As for `~astropy_feedrot.engine.equations.feed_rotation`.

    Returns
    -------
    phase, below : ndarray, shape (S, t), and ndarray or None
        As `~astropy_feedrot.engine.equations.feed_rotation`.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.engine.grid import receiver_arrays
    >>> from astropy_feedrot.engine.equations import Receivers
    >>> from astropy_feedrot.engine.grid_natural import engine_block
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> rx = Receivers.from_arrays(receiver_arrays([get_antenna("DBR205")]))
    >>> phase, below = engine_block(np.array([[[0.6, 0.0, 0.8]]]), np.zeros((1, 3)), rx)
    >>> phase.shape
    (1, 1)
    """
    s = topocentric(geocentric, receivers.station_xyz[0], velocity)
    phase, below = equations.feed_rotation(receivers, s[:, :, np.newaxis, np.newaxis, :],
                                           min_sine=min_sine)
    return phase[..., 0, 0], None if below is None else below[..., 0, 0]


def natural_grid(geocentric, velocity, receivers, sign=1.0, min_sine=None):
    """Feed rotation (T, A, S) in degrees of antennas from shared geocentric directions.

    Blocks of epochs (`~astropy_feedrot.engine.grid_arrays.epoch_blocks`), each
    antenna in turn: `feed_rotation_block` where it serves (`fast_receiver`),
    `traced_block` for a traced mirror train (`traced_receiver`), else
    `engine_block`.

    Parameters
    ----------
    geocentric : ndarray, shape (S, T, 3)
        Geocentric apparent unit vectors in ITRS (NaN at masked epochs).
    velocity : ndarray, shape (T, 3)
        The geocentre's barycentric velocity in ITRS, in units of c.
    receivers : list of `~astropy_feedrot.engine.equations.Receivers`
        One per antenna (A), none with a ``'series'`` rotator.
    sign : float, optional
        +1 (RCP) or -1 (LCP).
    min_sine : float, optional
        NaN below this sine of the elevation.

    Returns
    -------
    out : ndarray, shape (T, A, S)
        Degrees.
    degenerate : int
        Grid points NaN for their geometry (not masked, not below the limit).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.engine.equations import Receivers
    >>> from astropy_feedrot.engine.grid import receiver_arrays
    >>> from astropy_feedrot.engine.grid_natural import natural_grid
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> rx = [Receivers.from_arrays(receiver_arrays([get_antenna(n)]))
    ...       for n in ("WETTZ13S", "GGAO12M")]
    >>> s = np.array([[[0.6, 0.0, 0.8], [0.0, 0.6, 0.8]]])  # 1 source, 2 epochs
    >>> out, degenerate = natural_grid(s, np.zeros((2, 3)), rx)
    >>> out.shape, degenerate
    ((2, 2, 1), 0)
    """
    n_s, n_t = geocentric.shape[:2]
    out = np.empty((n_t, len(receivers), n_s))
    scale = sign * np.degrees(1.0)
    # Two halves of the antennas at once, one on the helper thread, where the
    # grid is large: numpy releases the GIL, so both cores work.
    halves = (len(receivers) > 1 and n_t * n_s * len(receivers) >= PARALLEL_POINTS
              and not on_helper_thread())
    # Blocks of a quarter of the engine's (a twelfth with two antennas at once):
    # the memory of the traced mirrors' temporaries stays below that of a loop
    # over antennas.
    degenerate = 0
    for block in epoch_blocks(n_t, n_s * (12 if halves else 4)):
        g, v = geocentric[:, block], velocity[block]  # (S, t, 3), (t, 3)
        shared = shared_block(g, v)
        valid = np.isfinite(shared.components[2])  # False at masked epochs
        valid = None if valid.all() else valid
        work = (shared, g, v, receivers, valid, min_sine, out[block], scale)
        if not halves:
            degenerate += _antennas(range(len(receivers)), *work)
            continue
        # Alternate antennas, so that each half has its share of costly foci.
        other = helper_thread().submit(_antennas, range(1, len(receivers), 2), *work)
        try:
            degenerate += _antennas(range(0, len(receivers), 2), *work)
        finally:
            degenerate += other.result()  # waited for, even when this half failed
    return out, degenerate


def _antennas(indices, shared, g, v, receivers, valid, min_sine, out, scale):
    """`natural_grid` for the antennas ``indices`` in a block: into ``out`` (t, A, S),
    returning the number of degenerate grid points."""
    count = 0
    for i in indices:
        rx = receivers[i]
        if fast_receiver(rx):
            phase, below = feed_rotation_block(shared, rx, min_sine=min_sine)
        elif traced_receiver(rx):
            phase, below = traced_block(shared, rx, min_sine=min_sine)
        else:
            phase, below = engine_block(g, v, rx, min_sine=min_sine)
        nan = np.isnan(phase)  # degenerate: NaN but neither masked nor below the limit
        if below is not None:
            nan &= ~below
        if valid is not None:
            nan &= valid
        count += int(np.count_nonzero(nan))
        np.multiply(phase.T, scale, out=out[:, i])
    return count


#: Grid points (epochs x antennas x sources) from which `natural_grid` computes
#: two halves of the antennas at once.
PARALLEL_POINTS = 2**16
