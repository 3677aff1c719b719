# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation on a grid from plain arrays: radians out, no astropy object.

`wind_up` takes the stations and the targets as arrays (positions or
directions in ITRS, the transmitters' dipoles) and returns the feed rotation
of every antenna and target at every epoch, shape (T, A, S), evaluated by the
wind-up engine block by block (`grid_block`); `nominal_attitude` gives the
transmitter dipoles of Eqs 26-27 from arrays. `~astropy_feedrot.engine.grid` builds
these arrays from `~astropy_feedrot.Antenna` and `~astropy_feedrot.Satellite`
objects.
"""


import numpy as np
from astropy import units as u

from ..earth.frames import check_station_xyz
from ..transmitters.nominal_attitude import nominal_dipoles
from . import equations
from .equations import ReceiverArrays, Receivers, check_form

__all__ = ["UNIT_TOLERANCE", "FOCUS_TERMS", "BLOCK_POINTS", "wind_up", "nominal_attitude",
           "grid_block", "epoch_blocks"]


#: Grid points (epochs x antennas x targets) evaluated at once: the working
#: memory of a block is about 200 bytes per point, so about 50 MB.
BLOCK_POINTS = 2**18


_RAD_TO_DEG = u.rad.to(u.deg)


def _shape_error(name, shape, expected, why):
    return ValueError(f"{name} has shape {shape}, but {why} needs {expected}")


#: Tolerance on the length of the unit vectors given to `wind_up` (directions,
#: axes, dipoles): within it they are normalized (rounding), beyond it refused.
UNIT_TOLERANCE = 1e-6


#: The focus terms `wind_up` accepts: conventional, Nasmyth right and left,
#: beam waveguide right and left.
FOCUS_TERMS = ((0, 0), (1, 0), (-1, 0), (1, -1), (-1, 1))


# Transmitters closer to the geocentre than this (metres) are inside the Earth:
# positions in kilometres read as metres.
_MIN_TRANSMITTER_RADIUS = 6.3e6


def _floats(value, name):
    """A float ndarray; TypeError for what is not numbers."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be an array of numbers, got "
                        f"{type(value).__name__}") from None
    return array


def _unit_vectors(vectors, name, allow_nan):
    """Vectors (..., 3) normalized; ValueError if a length is off by more than UNIT_TOLERANCE.

    With ``allow_nan``, a vector with a NaN component is missing data and
    becomes all NaN; infinities are always refused.
    """
    if np.any(np.isinf(vectors)):
        raise ValueError(f"{name} has infinite components")
    missing = np.any(np.isnan(vectors), axis=-1)
    if np.any(missing) and not allow_nan:
        raise ValueError(f"{name} has NaN components")
    norm = np.sqrt(np.einsum("...i,...i->...", vectors, vectors))
    bad = ~missing & ~(np.abs(norm - 1) <= UNIT_TOLERANCE)
    if np.any(bad):
        where = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ValueError(
            f"{name} must be unit vectors (length within {UNIT_TOLERANCE:g} of 1), but "
            f"{name}[{', '.join(map(str, where))}] has length {norm[where]:.6g}; normalize "
            "them (v / np.linalg.norm(v, axis=-1, keepdims=True)); a zero vector has no "
            "direction"
        )
    with np.errstate(invalid="ignore"):
        return np.where(missing[..., np.newaxis], np.nan, vectors / norm[..., np.newaxis])


def _check_receivers(station_xyz, station_axes, stationary, fixed_axis, focus_terms):
    xyz = _floats(station_xyz, "station_xyz")
    if xyz.ndim != 2 or xyz.shape[1] != 3:
        raise ValueError(f"station_xyz must have shape (A, 3), got {xyz.shape}")
    check_station_xyz(xyz, "station_xyz")
    n = len(xyz)
    axes = _floats(station_axes, "station_axes")
    if axes.shape != (n, 3, 3):
        raise _shape_error("station_axes", axes.shape, (n, 3, 3),
                           f"station_xyz of shape {xyz.shape}")
    axes = _unit_vectors(axes, "station_axes", allow_nan=False)
    gram = np.einsum("aij,akj->aik", axes, axes) - np.eye(3)
    handed = np.einsum("ai,ai->a", np.cross(axes[:, 0], axes[:, 1]), axes[:, 2])
    bad = np.flatnonzero((np.max(np.abs(gram), axis=(1, 2)) > UNIT_TOLERANCE) | (handed < 0))
    if bad.size:
        raise ValueError(f"station_axes[{bad[0]}] must hold east, north and up as an "
                         "orthonormal right-handed set of rows (east x north = up), e.g. "
                         "np.stack(local_frame(location))")
    raw = np.asarray(stationary)
    if raw.dtype.kind not in "biu" or (raw.dtype.kind != "b" and np.any((raw != 0) & (raw != 1))):
        raise TypeError(f"stationary must be booleans (True for a ground-fixed crossed "
                        f"dipole), got {raw.dtype} values")
    station = raw.astype(bool)
    if station.shape != (n,):
        raise _shape_error("stationary", station.shape, (n,),
                           f"station_xyz of shape {xyz.shape}")
    if fixed_axis is None:
        axis = axes[:, 2]
    else:
        axis = _floats(fixed_axis, "fixed_axis")
        if axis.shape != (n, 3):
            raise _shape_error("fixed_axis", axis.shape, (n, 3),
                               f"station_xyz of shape {xyz.shape}")
        axis = _unit_vectors(axis, "fixed_axis", allow_nan=False)
    if focus_terms is None:
        terms = np.zeros((n, 2))
    else:
        terms = _floats(focus_terms, "focus_terms")
        if terms.shape != (n, 2):
            raise _shape_error("focus_terms", terms.shape, (n, 2),
                               f"station_xyz of shape {xyz.shape}")
        known = np.array(FOCUS_TERMS, dtype=float)
        valid = np.any(np.all(terms[:, np.newaxis] == known, axis=-1), axis=-1)
        if not np.all(valid):
            i = int(np.flatnonzero(~valid)[0])
            raise ValueError(f"focus_terms[{i}] is {terms[i].tolist()}; it must be one of "
                             f"{list(FOCUS_TERMS)} (conventional, Nasmyth right and left, "
                             "beam waveguide right and left)")
    return ReceiverArrays(xyz, axes, station, axis, terms)


def _check_targets(target, aligned, transverse, directions, n_antennas, xyz_shape):
    if not isinstance(directions, (bool, np.bool_)):
        raise TypeError(f"directions must be True or False, got {directions!r}")
    target = _floats(target, "target")
    if directions:
        if target.ndim == 4:
            if target.shape[1] != n_antennas or target.shape[-1] != 3:
                raise _shape_error("target", target.shape,
                                   f"(T, {n_antennas}, S, 3) or (T, S, 3)",
                                   f"station_xyz of shape {xyz_shape}")
        elif target.ndim != 3 or target.shape[-1] != 3:
            raise ValueError(f"target directions must have shape (T, S, 3) or (T, A, S, 3), "
                             f"got {target.shape}")
    elif target.ndim != 3 or target.shape[-1] != 3:
        raise ValueError(f"target positions must have shape (T, S, 3), got {target.shape}; "
                         "for directions pass directions=True")
    if (aligned is None) != (transverse is None):
        raise ValueError("give both aligned and transverse (a transmitter) or neither "
                         "(natural sources)")
    if directions:
        target = _unit_vectors(target, "target directions", allow_nan=True)
    else:
        if np.any(np.isinf(target)):
            raise ValueError("target positions have infinite components")
        with np.errstate(invalid="ignore"):
            radius = np.sqrt(np.einsum("...i,...i->...", target, target))
        inside = radius < _MIN_TRANSMITTER_RADIUS  # False for NaN: missing data
        if np.any(inside):
            where = tuple(int(i) for i in np.argwhere(inside)[0])
            raise ValueError(
                f"target[{', '.join(map(str, where))}] is {radius[where]:.0f} m from the "
                "geocentre, inside the Earth; target positions are geocentric ITRS in "
                "metres (kilometres?), or pass unit directions with directions=True"
            )
    expected = target.shape[:1] + target.shape[-2:]
    if aligned is not None:
        aligned = _floats(aligned, "aligned")
        transverse = _floats(transverse, "transverse")
        for name, value in (("aligned", aligned), ("transverse", transverse)):
            if value.shape != expected:
                raise _shape_error(name, value.shape, expected,
                                   f"target of shape {target.shape}")
        aligned = _unit_vectors(aligned, "aligned", allow_nan=True)
        transverse = _unit_vectors(transverse, "transverse", allow_nan=True)
        with np.errstate(invalid="ignore"):
            skew = np.abs(np.einsum("...i,...i->...", aligned, transverse)) > UNIT_TOLERANCE
        if np.any(skew):
            where = ", ".join(str(int(i)) for i in np.argwhere(skew)[0])
            raise ValueError(f"aligned[{where}] and transverse[{where}] must be orthogonal "
                             "(a crossed dipole)")
    return target, aligned, transverse


def epoch_blocks(n_epochs, points_per_epoch):
    """Slices of epochs holding about `BLOCK_POINTS` grid points each.

    Parameters
    ----------
    n_epochs : int
        Epochs of the grid.
    points_per_epoch : int
        Grid points per epoch (antennas x targets).

    Yields
    ------
    slice

    Examples
    --------
    >>> from astropy_feedrot.engine.grid_arrays import epoch_blocks
    >>> len(list(epoch_blocks(2880, 3000)))  # 30 antennas x 100 sources: 87 epochs each
    34
    """
    step = max(1, BLOCK_POINTS // max(1, points_per_epoch))
    for start in range(0, n_epochs, step):
        yield slice(start, min(start + step, n_epochs))


def grid_block(target, aligned=None, transverse=None, rotation=None, *, receivers, positions,
               form, sign, min_sine, degrees=True, count=False):
    """Feed rotation (t, A, S) of a block of epochs, by the engine in blocks of
    `BLOCK_POINTS`; with ``count`` also the number of degenerate grid points (NaN
    where the target is finite and not masked).

    Parameters
    ----------
    target, aligned, transverse : ndarray
        As `~astropy_feedrot.engine.equations.feed_rotation` takes them, with a leading
        axis of epochs.
    rotation : ndarray, shape (t, A), optional
        Angles of 'series' rotators.
    receivers : `~astropy_feedrot.engine.equations.Receivers`
        The antennas.
    positions, form, min_sine
        As for `~astropy_feedrot.engine.equations.feed_rotation`.
    sign : float or ndarray, shape (S,)
        +1 (RCP) or -1 (LCP) per target.
    degrees : bool, optional
        Degrees (default) or radians.
    count : bool, optional
        Also return the number of degenerate points.

    Returns
    -------
    ndarray, shape (t, A, S), and with ``count`` an int

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot import AltAzMount
    >>> from astropy_feedrot.engine.equations import Receivers
    >>> from astropy_feedrot.engine.grid_arrays import grid_block
    >>> r = np.sqrt(0.5)
    >>> enu = [[0, 1.0, 0], [-r, 0, r], [r, 0, r]]  # latitude 45 deg, longitude 0
    >>> rx = Receivers.from_mounts([[4.5e6, 0, 4.5e6]], [enu], [AltAzMount()], [None])
    >>> west = np.array([0.0, -1.0, 0.0]).reshape(1, 1, 1, 3)  # setting due west
    >>> grid_block(west, receivers=rx, positions=False, form="beyerle", sign=1.0,
    ...            min_sine=None)  # doctest: +FLOAT_CMP
    array([[[45.]]])
    """
    n_t, n_s = target.shape[0], target.shape[-2]
    out = np.empty((n_t, len(receivers), n_s))
    degenerate = 0
    scale = sign * _RAD_TO_DEG if degrees else sign
    for block in epoch_blocks(n_t, len(receivers) * n_s):
        tb = target[block]
        phase, below = equations.feed_rotation(
            receivers, tb, None if aligned is None else aligned[block],
            None if transverse is None else transverse[block], positions=positions,
            form=form, min_sine=min_sine,
            rotation=None if rotation is None else rotation[block])
        if count:
            degenerate += int(np.count_nonzero(equations.degenerate(phase, tb, below, positions)))
        np.multiply(phase, scale, out=out[block])
    return (out, degenerate) if count else out


def wind_up(station_xyz, station_axes, stationary, target, aligned=None, transverse=None, *,
            fixed_axis=None, focus_terms=None, directions=False, form="beyerle"):
    """Feed rotation (carrier-phase wind-up) on a grid, from plain arrays.

    Every antenna sees every target at every epoch: the result has shape
    (T, A, S) for T epochs, A antennas and S targets.

    Parameters
    ----------
    station_xyz : array-like, shape (A, 3)
        Geocentric ITRS positions of the antennas, in metres: finite, and
        Earth stations (see `~astropy_feedrot.earth.frames.check_station_xyz`).
    station_axes : array-like, shape (A, 3, 3)
        East, north and up unit vectors of each site in ITRS (the rows of
        ``np.stack(local_frame(location))``), orthonormal and right-handed.
    stationary : array-like of bool, shape (A,)
        True for a crossed dipole fixed to the ground (aligned dipole east,
        transverse north, boresight up, Eq 28), False for a tracking antenna
        turning about ``fixed_axis``.
    target : array-like, shape (T, S, 3) or (T, A, S, 3)
        Geocentric ITRS positions of transmitters in metres, shape (T, S, 3),
        outside the Earth; or, with ``directions=True``, unit vectors from the
        antennas to the targets, shape (T, S, 3) (the same for every antenna)
        or (T, A, S, 3). A vector with a NaN component is missing data.
    aligned, transverse : array-like, shape (T, S, 3), optional
        The transmitters' aligned and transverse dipoles in ITRS (from
        `nominal_attitude`, or measured): orthogonal unit vectors, or NaN
        where unknown. Leave both out for natural sources, whose transmitter
        dipole is the projected celestial pole (Eq 11).
    fixed_axis : array-like, shape (A, 3), optional
        Fixed axis of each tracking mount in ITRS (Eq 10), a unit vector: the
        up vector for alt-az (the default), ``[0, 0, 1]`` for equatorial,
        north or east for X-Y. Ignored for stationary antennas.
    focus_terms : array-like, shape (A, 2), optional
        Multiples of the elevation and the azimuth that the focus adds, each
        row one of `FOCUS_TERMS` (see `ReceiverArrays`); zero (a
        conventional focus) by default.
    directions : bool, optional
        Whether ``target`` holds directions instead of positions.
    form : {'beyerle', 'wu'}, optional
        For stationary antennas and transmitters with dipoles: the crossed-dipole
        form (Eq 30, default) or the effective-dipole form (Eq 31).

    Returns
    -------
    ndarray, shape (T, A, S)
        The feed rotation of a right-hand (RCP) receiver in radians, in
        [-pi, pi]; negate it for LCP. NaN where the geometry is degenerate
        (see `~astropy_feedrot.core.kernel`; a transmitter at an antenna's
        position too) or a vector is missing (NaN), without a warning.

    Raises
    ------
    TypeError
        If an array is not numbers, ``stationary`` not booleans or
        ``directions`` not a bool.
    ValueError
        If the shapes do not fit (naming both), for an unknown ``form``, a
        station that is not on the Earth (NaN, infinite, in km), a unit
        vector (direction, axis, dipole) whose length is off by more than
        `UNIT_TOLERANCE` (those within it are normalized), axes that are not
        an orthonormal right-handed set, dipoles that are not orthogonal,
        transmitter positions inside the Earth or infinite, or focus terms
        not in `FOCUS_TERMS`.

    Notes
    -----
    Tracking antennas: Eq 7 with the fixed-axis vector as receiver dipole
    (Eq 13; Eqs 35, 38-41 with the focus terms). Stationary crossed dipoles:
    Eq 30 (Beyerle's form, Eq 5) for transmitters with dipoles, evaluated from
    scalar products without forming a (T, A, S, 3) array; Eq 7 with the
    effective dipole of Eq 8 otherwise (Eq 33 for natural sources). The grid
    is evaluated in blocks of epochs to bound the working memory.
    `receiver_arrays` builds the antenna arguments from
    `~astropy_feedrot.Antenna` objects.

    Examples
    --------
    A GNSS antenna on the equator and a transmitter straight above it, facing
    it, with dipoles turned by 30 degrees from east towards north:

    >>> import numpy as np
    >>> from astropy_feedrot.engine.grid import wind_up
    >>> enu = np.array([[[0.0, 1, 0], [0, 0, 1], [1, 0, 0]]])  # east, north, up at lon 0
    >>> c, s = np.cos(np.radians(30)), np.sin(np.radians(30))
    >>> phi = wind_up([[6.378e6, 0, 0]], enu, [True], [[[2.6e7, 0, 0]]],
    ...               aligned=[[[0, c, s]]], transverse=[[[0, s, -c]]])
    >>> phi.shape
    (1, 1, 1)
    >>> float(np.degrees(phi[0, 0, 0]))  # doctest: +FLOAT_CMP
    30.0
    """
    rx = _check_receivers(station_xyz, station_axes, stationary, fixed_axis, focus_terms)
    form = check_form(form)
    target, aligned, transverse = _check_targets(target, aligned, transverse, directions,
                                                 len(rx.station_xyz), rx.station_xyz.shape)
    if directions and target.ndim == 3:  # the same directions for every antenna
        target = target[:, np.newaxis]
    return grid_block(target, aligned, transverse, receivers=Receivers.from_arrays(rx),
                      positions=not directions, form=form, sign=1.0, min_sine=None,
                      degrees=False)


def nominal_attitude(position, sun):
    """Dipoles of nominally pointed satellites on a grid of epochs (Eqs 26, 27).

    Parameters
    ----------
    position : array-like, shape (T, S, 3)
        Geocentric ITRS positions of S satellites at T epochs.
    sun : array-like, shape (T, 3)
        Geocentric ITRS position of the Sun at the same epochs, in the same
        unit (`~astropy_feedrot.transmitters.nominal_attitude.sun_position`, or
        `~astropy_feedrot.transmitters.nominal_attitude.interpolated_sun_position` for many
        epochs): one per epoch for all satellites.

    Returns
    -------
    aligned, transverse : ndarray, shape (T, S, 3)
        The transmitter dipoles of `~astropy_feedrot.NominalAttitude` (the
        same arithmetic, `~astropy_feedrot.transmitters.nominal_attitude.nominal_dipoles`); NaN
        without a warning where the Sun, a satellite and the geocentre are
        aligned.

    Raises
    ------
    ValueError
        If the shapes do not fit (naming both).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.engine.grid import nominal_attitude
    >>> position = np.array([[[2.6e7, 0, 0], [0, 2.6e7, 0]]])  # one epoch, two satellites
    >>> aligned, transverse = nominal_attitude(position, [[0, 0, 1.5e11]])
    >>> transverse  # doctest: +FLOAT_CMP
    array([[[ 0.,  1.,  0.],
            [-1.,  0.,  0.]]])
    """
    position = np.asarray(position, dtype=float)
    sun = np.asarray(sun, dtype=float)
    if position.ndim != 3 or position.shape[-1] != 3:
        raise ValueError(f"position must have shape (T, S, 3), got {position.shape}")
    if sun.shape != (position.shape[0], 3):
        raise _shape_error("sun", sun.shape, (position.shape[0], 3),
                           f"position of shape {position.shape}")
    return nominal_dipoles(position, sun[:, np.newaxis])
