# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation on a grid of epochs x antennas x targets, for networks and long series.

`Antenna.feed_rotation <astropy_feedrot.Antenna.feed_rotation>` computes one
antenna and one target at a time: every call propagates the orbit, rotates it
to the Earth-fixed frame and finds the Sun again. For a network observing a
constellation, those per-epoch quantities are shared: this module computes
them once per epoch for all satellites (one SGP4 call for all element sets,
one Earth orientation, one Sun), and hands the whole grid of epochs (T) x
antennas (A) x targets (S) to the wind-up engine (`~astropy_feedrot.engine`),
the same one `~astropy_feedrot.Antenna` uses, block by block.

Three layers, as in the rest of the package:

* `wind_up`: plain arrays in, radians out, shape (T, A, S); no astropy object.
  `nominal_attitude` gives the transmitter dipoles of Eqs 26-27 from arrays.
* `feed_rotation_grid`: `~astropy_feedrot.Antenna` and
  `~astropy_feedrot.Satellite` objects (or a `~astropy.coordinates.SkyCoord`
  of natural sources) and a `~astropy.time.Time` in, an
  `~astropy.coordinates.Angle` of shape (T, A, S) out, equal to
  ``antenna.feed_rotation(target, obstime)`` for every pair;
  `rotation_delay_grid` turns it into continuous rotation delays.
* `feed_rotation_grid_dask`: the same computation as a `dask.array` chunked
  over time, for grids that do not fit in memory or that are spread over a
  cluster.
"""

from typing import NamedTuple

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle, BaseCoordinateFrame, SkyCoord

from . import engine
from .antenna import Antenna
from .attitude import Attitude, nominal_dipoles
from .continuity import delay_of_difference, frequency_hz
from .earth import fast_path_applies, orientation_of
from .engine import ReceiverArrays, Receivers, check_form
from .eop import iers_context
from .frames import (
    as_elevation_limit,
    as_skycoord,
    as_time,
    check_station_xyz,
    fill_masked,
    location_xyz,
    source_direction,
)
from .orbits import Orbit
from .polarization import polarization_sign
from .rotators import rotation_angles
from .satellite import Satellite, check_transmitter_positions

__all__ = [
    "UNIT_TOLERANCE",
    "FOCUS_TERMS",
    "ReceiverArrays",
    "receiver_arrays",
    "wind_up",
    "nominal_attitude",
    "feed_rotation_grid",
    "feed_rotation_grid_dask",
    "rotation_delay_grid",
]

#: Grid points (epochs x antennas x targets) evaluated at once: the working
#: memory of a block is about 200 bytes per point, so about 50 MB.
BLOCK_POINTS = 2**18

#: Default number of grid points per chunk of `feed_rotation_grid_dask`.
DASK_CHUNK_POINTS = 2**21

_RAD_TO_DEG = u.rad.to(u.deg)

# Doctests that need the optional dask (pytest-doctestplus).
__doctest_requires__ = {("feed_rotation_grid_dask",): ["dask"]}


def _check_antennas(antennas):
    if isinstance(antennas, Antenna):
        raise TypeError("antennas must be a sequence of Antenna objects; wrap a single "
                        "antenna in a list: [antenna]")
    try:
        antennas = list(antennas)
    except TypeError:
        raise TypeError(f"antennas must be a sequence of Antenna objects, got "
                        f"{type(antennas).__name__}") from None
    if not antennas:
        raise ValueError("antennas is empty; give at least one Antenna")
    for i, antenna in enumerate(antennas):
        if not isinstance(antenna, Antenna):
            raise TypeError(f"antennas[{i}] must be an Antenna, got {type(antenna).__name__}")
    return antennas


def _receivers(antennas):
    """The engine's description of the antennas."""
    return Receivers.from_mounts(
        np.stack([location_xyz(antenna.location) for antenna in antennas]),
        np.stack([np.stack(antenna.local_frame) for antenna in antennas]),
        [antenna.mount for antenna in antennas], [antenna.focus for antenna in antennas],
        [antenna.rotator for antenna in antennas])


def receiver_arrays(antennas):
    """Plain-array description of antennas, for `wind_up`.

    Parameters
    ----------
    antennas : sequence of `~astropy_feedrot.Antenna`
        Stationary crossed dipoles, and fixed-axis mounts (alt-az, equatorial,
        X-Y, any fixed axis) with a prime, Cassegrain, Gregorian, Nasmyth or
        beam-waveguide focus.

    Returns
    -------
    ReceiverArrays
        Named tuple whose fields are the keyword arguments of `wind_up`.

    Raises
    ------
    TypeError
        If an element is not an `~astropy_feedrot.Antenna`.
    ValueError
        For an antenna without a closed form (a `~astropy_feedrot.MirrorTrain`
        focus, a `~astropy_feedrot.Rotator`, or a stationary mount whose
        dipoles are not east and north); `feed_rotation_grid` evaluates those
        too.

    Examples
    --------
    >>> from astropy_feedrot.grid import receiver_arrays
    >>> from astropy_feedrot.stations import get_antenna
    >>> rx = receiver_arrays([get_antenna("DBR205"), get_antenna("FD-VLBA")])
    >>> rx.stationary
    array([ True, False])
    >>> rx.station_axes.shape
    (2, 3, 3)
    """
    antennas = _check_antennas(antennas)
    receivers = _receivers(antennas)
    arrays = receivers.as_arrays()
    if arrays is None:
        i = int(receivers.unrepresentable()[0])
        antenna = antennas[i]
        raise ValueError(
            f"antennas[{i}] ({antenna!r}) has no closed form for wind_up (mount "
            f"{antenna.mount!r}, focus {antenna.focus!r}, rotator {antenna.rotator!r}); "
            "feed_rotation_grid evaluates such antennas"
        )
    return arrays


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


def _blocks(n_epochs, points_per_epoch):
    """Slices of epochs holding about `BLOCK_POINTS` grid points each."""
    step = max(1, BLOCK_POINTS // max(1, points_per_epoch))
    for start in range(0, n_epochs, step):
        yield slice(start, min(start + step, n_epochs))


def wind_up(station_xyz, station_axes, stationary, target, aligned=None, transverse=None, *,
            fixed_axis=None, focus_terms=None, directions=False, form="beyerle"):
    """Feed rotation (carrier-phase wind-up) on a grid, from plain arrays.

    Every antenna sees every target at every epoch: the result has shape
    (T, A, S) for T epochs, A antennas and S targets.

    Parameters
    ----------
    station_xyz : array-like, shape (A, 3)
        Geocentric ITRS positions of the antennas, in metres: finite, and
        Earth stations (see `~astropy_feedrot.frames.check_station_xyz`).
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
        (see `~astropy_feedrot.kernel`; a transmitter at an antenna's
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
    >>> from astropy_feedrot.grid import wind_up
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
    return _grid_block(target, aligned, transverse, receivers=Receivers.from_arrays(rx),
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
        unit (`~astropy_feedrot.attitude.sun_position`, or
        `~astropy_feedrot.attitude.interpolated_sun_position` for many
        epochs): one per epoch for all satellites.

    Returns
    -------
    aligned, transverse : ndarray, shape (T, S, 3)
        The transmitter dipoles of `~astropy_feedrot.NominalAttitude` (the
        same arithmetic, `~astropy_feedrot.attitude.nominal_dipoles`); NaN
        without a warning where the Sun, a satellite and the geocentre are
        aligned.

    Raises
    ------
    ValueError
        If the shapes do not fit (naming both).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.grid import nominal_attitude
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


# -- From astropy objects to arrays --------------------------------------------------------


class _Grid(NamedTuple):
    """Everything a block of epochs needs, as arrays."""

    receivers: Receivers
    target: np.ndarray
    aligned: np.ndarray
    transverse: np.ndarray
    positions: bool
    form: str
    sign: np.ndarray
    min_sine: float
    shape: tuple
    rotation: np.ndarray = None  # (T, A) angles of 'series' rotators, or None


def _check_targets_objects(targets):
    """('satellites', list) or ('sources', 1-d SkyCoord)."""
    if isinstance(targets, (SkyCoord, BaseCoordinateFrame)):
        sources = as_skycoord(targets)
        if sources.ndim > 2:
            raise ValueError(f"natural sources must be a scalar or 1-d SkyCoord (or 2-d for "
                             f"moving sources), got shape {sources.shape}; flatten it with "
                             ".ravel()")
        if sources.ndim == 2:  # moving sources: [epoch, source]
            return "sources", sources
        return "sources", sources.reshape((sources.size,))
    if isinstance(targets, Satellite):
        raise TypeError("targets must be a sequence of Satellite objects or a SkyCoord of "
                        "sources; wrap a single satellite in a list: [satellite]")
    if isinstance(targets, str):
        raise TypeError(f"targets must be Satellite objects or a SkyCoord, got a str "
                        f"{targets!r}; e.g. SkyCoord({targets!r})")
    try:
        targets = list(targets)
    except TypeError:
        raise TypeError(f"targets must be a sequence of Satellite objects or a SkyCoord, got "
                        f"{type(targets).__name__}") from None
    if not targets:
        raise ValueError("targets is empty; give at least one Satellite")
    for i, target in enumerate(targets):
        if not isinstance(target, Satellite):
            hint = ("; put natural sources in one SkyCoord, e.g. SkyCoord([c1, c2])"
                    if isinstance(target, (SkyCoord, BaseCoordinateFrame)) else "")
            raise TypeError(f"targets[{i}] must be a Satellite, got "
                            f"{type(target).__name__}{hint}")
    return "satellites", targets


def _earth_orientation(obstime):
    """The one Earth orientation of the grid, or None where orbits use astropy's frames."""
    if fast_path_applies(None, obstime):
        return orientation_of(obstime)
    return None


def _satellite_arrays(satellites, obstime, polarization, masked=None):
    """Positions and dipoles (T, S, 3) of satellites, and their signs (S,).

    Every orbit class propagates its members in one batch and every attitude
    model with the Sun shares one Sun (`Orbit.positions`,
    `Attitude.dipoles_many`); one Earth orientation serves them all. NaN at
    ``masked`` epochs (True), where ``obstime`` holds stand-ins.
    """
    n_t, n_s = obstime.size, len(satellites)
    sign = np.array([engine.receiver_sign(sat, polarization) for sat in satellites], dtype=float)
    if masked is not None and masked.all():
        nothing = np.full((n_t, n_s, 3), np.nan)
        return nothing, nothing.copy(), nothing.copy(), sign
    orbits = [sat.orbit for sat in satellites]
    attitudes = [sat.attitude for sat in satellites]
    orientation = None
    if any(o.uses_orientation for o in orbits) or any(a.needs_sun for a in attitudes):
        orientation = _earth_orientation(obstime)
    try:
        xyz = Orbit.positions(orbits, obstime, orientation)  # (S, T, 3)
    except ValueError:
        for i, orbit in enumerate(orbits):  # name the target, as the grid's users know it
            shape = np.shape(orbit.position(obstime, orientation))
            if shape != (n_t, 3):
                raise ValueError(f"the orbit of targets[{i}] gives positions of shape {shape} "
                                 f"for obstime of shape {obstime.shape}; a grid needs one "
                                 "position per epoch") from None
        raise
    for i, sat in enumerate(satellites):
        check_transmitter_positions(xyz[i], sat.name or f"targets[{i}]")
    if masked is not None:
        xyz[:, masked] = np.nan
    aligned, transverse = Attitude.dipoles_many(attitudes, obstime, xyz, orientation)
    position, aligned, transverse = (np.swapaxes(v, 0, 1) for v in (xyz, aligned, transverse))
    if masked is not None:
        aligned[masked] = transverse[masked] = np.nan
    return position, aligned, transverse, sign


def _source_directions(sources, antennas, obstime):
    """Apparent topocentric directions (T, A, S, 3) of natural sources at each antenna.

    A 2-d ``sources`` (T, S) moves: element [k, j] is source j at epoch k.
    """
    n_t, n_s = obstime.size, sources.shape[-1] if sources.ndim else 1
    out = np.empty((n_t, len(antennas), n_s, 3))
    if sources.ndim == 2:
        for i, antenna in enumerate(antennas):
            out[:, i] = source_direction(sources, antenna.location, obstime[:, np.newaxis])
        return out
    column = sources.reshape((n_s, 1))
    orientation = None
    if fast_path_applies(column, obstime):  # every source at every epoch
        orientation = orientation_of(obstime)
        icrs = sources.icrs
    for i, antenna in enumerate(antennas):
        if orientation is not None:
            s = orientation.source_directions(icrs, antenna.location)
        else:
            s = source_direction(column, antenna.location, obstime)
        out[:, i] = np.swapaxes(s.reshape(n_s, n_t, 3), 0, 1)
    return out


def _prepare(antennas, targets, obstime, polarization, form, min_elevation):
    antennas = _check_antennas(antennas)
    kind, targets = _check_targets_objects(targets)
    obstime = as_time(obstime)
    if obstime.ndim > 1:
        raise ValueError(f"obstime must be a scalar or 1-d Time (the time axis of the grid), "
                         f"got shape {obstime.shape}; flatten it with .ravel()")
    shape = obstime.shape
    obstime, masked = fill_masked(obstime.reshape((obstime.size,)))
    form = check_form(form)
    min_sine = engine.min_sine(as_elevation_limit(min_elevation))
    receivers = _receivers(antennas)
    if kind == "sources" and targets.ndim == 2 and targets.shape[0] != obstime.size:
        raise ValueError(f"moving sources (a 2-d SkyCoord) need one row per epoch: shape "
                         f"{targets.shape} for {obstime.size} epochs")
    if kind == "satellites":
        target, aligned, transverse, sign = _satellite_arrays(targets, obstime, polarization,
                                                              masked)
        positions = True
    else:
        sign = np.full(targets.shape[-1] if targets.ndim else 1, polarization_sign(
            "RCP" if polarization is None else polarization), dtype=float)
        if masked is not None and masked.all():
            target = np.full((obstime.size, len(antennas), len(sign), 3), np.nan)
        else:
            target = _source_directions(targets, antennas, obstime)
        if masked is not None:  # NaN directions: NaN feed rotation, not degenerate
            target[masked] = np.nan
        aligned = transverse = None
        positions = False
    rotation = rotation_angles([antenna.rotator for antenna in antennas], obstime)
    if rotation is not None and masked is not None:
        rotation[masked] = np.nan
    return _Grid(receivers, target, aligned, transverse, positions, form, sign, min_sine,
                 shape + (len(antennas), len(sign)), rotation)


def _grid_block(target, aligned=None, transverse=None, rotation=None, *, receivers, positions,
                form, sign, min_sine, degrees=True, count=False):
    """Feed rotation (t, A, S) of a block of epochs, by the engine in blocks of
    `BLOCK_POINTS`; with ``count`` also the number of degenerate grid points (NaN
    where the target is finite and not masked)."""
    n_t, n_s = target.shape[0], target.shape[-2]
    out = np.empty((n_t, len(receivers), n_s))
    degenerate = 0
    scale = sign * _RAD_TO_DEG if degrees else sign
    for block in _blocks(n_t, len(receivers) * n_s):
        tb = target[block]
        phase, below = engine.feed_rotation(
            receivers, tb, None if aligned is None else aligned[block],
            None if transverse is None else transverse[block], positions=positions,
            form=form, min_sine=min_sine,
            rotation=None if rotation is None else rotation[block])
        if count:
            degenerate += int(np.count_nonzero(engine.degenerate(phase, tb, below, positions)))
        np.multiply(phase, scale, out=out[block])
    return (out, degenerate) if count else out


def _dask_block(*arrays, all_rotation=None, block_info=None, **kwargs):
    rotation = None
    if all_rotation is not None:  # (T, A), small: sliced to the block's epochs here
        start, stop = block_info[None]["array-location"][0]
        rotation = all_rotation[start:stop]
    arrays = arrays + (None,) * (3 - len(arrays))
    return _grid_block(*arrays, rotation, **kwargs)


def _block_arguments(grid):
    return dict(receivers=grid.receivers, positions=grid.positions, form=grid.form,
                sign=grid.sign, min_sine=grid.min_sine)


@iers_context()  # one check of the Earth-orientation tables per call
def feed_rotation_grid(antennas, targets, obstime, *, polarization=None, form=None,
                       min_elevation=None):
    """Feed rotation of every antenna observing every target at every epoch.

    Parameters
    ----------
    antennas : sequence of `~astropy_feedrot.Antenna`
        The receivers (A of them), of any mount and focus type.
    targets : sequence of `~astropy_feedrot.Satellite`, or `~astropy.coordinates.SkyCoord`
        S satellites (TLE, SP3 or coordinate orbits; nominal or quaternion
        attitude), or natural sources as one scalar or 1-d coordinate; or
        moving natural sources (an ephemeris, a direction fixed in the local
        frame) as a 2-d coordinate of shape (T, S), whose element ``[k, j]``
        is source ``j`` at epoch ``k``.
    obstime : `~astropy.time.Time`
        The epochs, scalar or 1-d (T of them); masked epochs give NaN, without
        a warning.
    polarization : {'RCP', 'LCP'}, optional
        Hand of the receivers: each satellite's own hand by default, RCP for
        natural sources; see `~astropy_feedrot.Antenna.feed_rotation`.
    form : {'beyerle', 'wu'}, optional
        Form for stationary crossed dipoles seeing satellites (Eq 30 by
        default, or Eq 31).
    min_elevation : `~astropy.units.Quantity`, optional
        NaN (without a warning) where a target is lower than this above an
        antenna's horizon: one angle in [-90, 90] deg.

    Returns
    -------
    `~astropy.coordinates.Angle`
        Shape (T, A, S), or (A, S) for a scalar ``obstime``; degrees in
        [-180, 180]. Element ``[k, i, j]`` equals
        ``antennas[i].feed_rotation(targets[j], obstime[k], ...)``.

    Raises
    ------
    TypeError
        If ``antennas`` or ``targets`` hold objects of the wrong kind (a single
        antenna or satellite must be put in a list), ``obstime`` is not a time
        or ``min_elevation`` a plain number.
    ValueError
        For a multi-dimensional ``obstime``, an unknown ``polarization`` or
        ``form``, a receiver hand that differs from a satellite's, an orbit
        that does not give one position per epoch, or a ``min_elevation``
        that is not one angle in [-90, 90] deg.
    astropy.units.UnitsError
        If ``min_elevation`` is not an angle.

    Warns
    -----
    DegenerateGeometryWarning
        Once, with the count, if some grid points are degenerate (and once
        more if the nominal attitude of some satellite is undefined).

    Notes
    -----
    Satellites with TLE orbits are propagated together (SGP4's
    ``SatrecArray``) and rotated from TEME to ITRS with one
    `~astropy_feedrot.earth.EarthOrientation`; the Sun of the nominal
    attitude is computed once per epoch for all satellites
    (`~astropy_feedrot.attitude.interpolated_sun_position`). With
    ``conf.fast_path`` off the rigorous astropy transformations are used, as
    `~astropy_feedrot.Antenna.feed_rotation` does
    (`~astropy_feedrot.earth.fast_path_applies`). The per-epoch arrays take
    72 bytes per epoch and satellite (natural sources: 24 bytes per epoch,
    antenna and source), the result 8 bytes per
    grid point; the wind-up itself is evaluated in blocks of
    `BLOCK_POINTS` grid points. See `feed_rotation_grid_dask` for grids
    larger than memory.

    Examples
    --------
    GPS SVN 76 over the GNSS antenna DBR205 and the telescope FD-VLBA (Sec. 4.1):

    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.grid import feed_rotation_grid
    >>> from astropy_feedrot.simulations import gps_svn76
    >>> from astropy_feedrot.stations import get_antenna
    >>> antennas = [get_antenna("DBR205"), get_antenna("FD-VLBA")]
    >>> times = Time("2023-01-25T08:10") + np.arange(0, 7, 0.5) * u.hour
    >>> phi = feed_rotation_grid(antennas, [gps_svn76()], times)
    >>> phi.shape
    (14, 2, 1)
    >>> reference = antennas[1].feed_rotation(gps_svn76(), times)
    >>> bool(np.all(np.abs((phi[:, 1, 0] - reference).wrap_at(180 * u.deg)) < 1e-9 * u.deg))
    True
    """
    grid = _prepare(antennas, targets, obstime, polarization, form, min_elevation)
    out, degenerate = _grid_block(grid.target, grid.aligned, grid.transverse, grid.rotation,
                                  count=True, **_block_arguments(grid))
    engine.warn_degenerate(degenerate, out.size, points="grid points")
    return Angle(out.reshape(grid.shape), u.deg, copy=False)


def _dask_array():
    try:
        import dask.array
    except ImportError:  # pragma: no cover - exercised only without dask
        raise ImportError(
            "feed_rotation_grid_dask needs dask: python -m pip install 'dask[array]' "
            "(or astropy_feedrot[dask], which adds dask.distributed for clusters)"
        ) from None
    return dask.array


@iers_context()  # one check of the Earth-orientation tables per call
def feed_rotation_grid_dask(antennas, targets, obstime, *, polarization=None, form=None,
                            min_elevation=None, chunks=None):
    """`feed_rotation_grid` as a `dask.array`, chunked over time.

    The per-epoch quantities (orbits, attitude, Earth orientation, source
    directions) are computed here, at once; the wind-up of each chunk of epochs
    is a task, computed when the result is (``.compute()``, a reduction, or
    ``dask.array.to_npy_stack`` and friends that write chunk by chunk), by
    whichever dask scheduler is active: threads by default, or a
    ``dask.distributed`` cluster.

    Parameters
    ----------
    antennas, targets, obstime, polarization, form, min_elevation
        As for `feed_rotation_grid`.
    chunks : int or tuple of int, optional
        Epochs per chunk (or the sizes of all chunks along time). By default
        chunks of about `DASK_CHUNK_POINTS` grid points (16 MB of float64).

    Returns
    -------
    `dask.array.Array`
        Shape (T, A, S) (or (A, S) for a scalar ``obstime``), float64, in
        degrees; computed, it equals the value of `feed_rotation_grid`.
        Degenerate grid points are NaN, without a warning (count them with
        ``dask.array.isnan``).

    Raises
    ------
    ImportError
        If dask is not installed.
    TypeError, ValueError
        As for `feed_rotation_grid`.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.grid import feed_rotation_grid, feed_rotation_grid_dask
    >>> from astropy_feedrot.simulations import gps_svn76
    >>> from astropy_feedrot.stations import get_antenna
    >>> antennas = [get_antenna("DBR205"), get_antenna("FD-VLBA")]
    >>> times = Time("2023-01-25T08:00") + np.arange(120) * u.min
    >>> lazy = feed_rotation_grid_dask(antennas, [gps_svn76()], times, chunks=50)
    >>> lazy.chunks
    ((50, 50, 20), (2,), (1,))
    >>> eager = feed_rotation_grid(antennas, [gps_svn76()], times)
    >>> bool(np.allclose(lazy.compute(), eager.deg, rtol=0, atol=1e-12))
    True
    """
    da = _dask_array()
    grid = _prepare(antennas, targets, obstime, polarization, form, min_elevation)
    n_a, n_s = grid.shape[-2:]
    if chunks is None:
        chunks = max(1, DASK_CHUNK_POINTS // (n_a * n_s))
    arrays = [grid.target] if grid.aligned is None else [
        grid.target, grid.aligned, grid.transverse]
    lazy = [da.from_array(a, chunks=(chunks,) + a.shape[1:]) for a in arrays]
    result = da.map_blocks(
        _dask_block, *lazy,
        chunks=(lazy[0].chunks[0], (n_a,), (n_s,)),
        drop_axis=[3] if grid.target.ndim == 4 else [],
        dtype=float, meta=np.empty((0, 0, 0)), all_rotation=grid.rotation,
        **_block_arguments(grid),
    )
    if len(grid.shape) == 2:
        result = result.reshape(grid.shape)
    return result


def _as_degrees(feed_rotation):
    if isinstance(feed_rotation, u.Quantity):
        return feed_rotation.to_value(u.deg), False
    if hasattr(feed_rotation, "dask"):  # a dask array from feed_rotation_grid_dask
        return feed_rotation, True
    raise TypeError(
        f"feed_rotation must be an Angle (from feed_rotation_grid) or a dask array in degrees "
        f"(from feed_rotation_grid_dask), got {type(feed_rotation).__name__}; wrap radians "
        "as Angle(values, u.rad)"
    )


def rotation_delay_grid(feed_rotation, frequency, baseline=(0, 1), *, obstime=None,
                        max_gap=None):
    """Rotation delays of baselines for every target, continuous along time (Sec. 4.1).

    Parameters
    ----------
    feed_rotation : `~astropy.coordinates.Angle` or `dask.array.Array`
        Shape (T, A, S), from `feed_rotation_grid` (or, in degrees, from
        `feed_rotation_grid_dask`; only the baselines' columns are computed).
    frequency : `~astropy.units.Quantity`
        Observing (sky) frequency: one positive frequency (not a wavelength,
        not a plain number).
    baseline : (int, int) or sequence of them, optional
        Indices ``(i, j)`` of the two antennas: the delay is antenna ``j``
        minus antenna ``i``, as ``rotation_delay(antennas[i], antennas[j],
        ...)``. Several pairs give one delay series each.
    obstime : `~astropy.time.Time`, optional
        The T epochs (shape (T,)), needed with ``max_gap``; masked ones
        restart the series.
    max_gap : `~astropy.units.Quantity`, optional
        Restart the continuous series after longer time steps (see
        `~astropy_feedrot.unwrap`).

    Returns
    -------
    `~astropy_feedrot.RotationDelay`
        ``(delay, ambiguity)``: the delay in ps, shape (T, S) for one pair or
        (T, B, S) for B pairs, continuous along time (Eq 9) within each
        segment between NaN samples (e.g. below ``min_elevation``); the
        ambiguity :math:`1/f` in ps.

    Raises
    ------
    TypeError
        If ``feed_rotation`` is not an angle or dask array, or ``frequency``
        not a Quantity.
    ValueError
        If ``feed_rotation`` is not (T, A, S), a baseline is not a pair of
        antenna indices, ``frequency`` is not one positive finite value, or
        ``obstime`` does not hold T epochs in order.
    astropy.units.UnitsError
        If ``frequency`` is not a frequency.

    Warns
    -----
    ContinuityWarning
        As `~astropy_feedrot.unwrap`, if the sampling is too coarse.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.grid import feed_rotation_grid, rotation_delay_grid
    >>> from astropy_feedrot.simulations import gps_svn76
    >>> from astropy_feedrot.stations import get_antenna
    >>> antennas = [get_antenna("DBR205"), get_antenna("FD-VLBA")]
    >>> times = Time("2023-01-25T08:10") + np.arange(0, 7, 0.5) * u.hour
    >>> phi = feed_rotation_grid(antennas, [gps_svn76()], times, min_elevation=10 * u.deg)
    >>> delay, ambiguity = rotation_delay_grid(phi, 1575.42 * u.MHz)
    >>> delay.shape
    (14, 1)
    >>> ambiguity  # doctest: +FLOAT_CMP
    <Quantity 634.75136789 ps>
    """
    degrees, lazy = _as_degrees(feed_rotation)
    if degrees.ndim != 3:
        raise ValueError(f"feed_rotation must have shape (T, A, S), got {degrees.shape}")
    pairs = np.asarray(baseline)
    single = pairs.ndim == 1
    pairs = np.atleast_2d(pairs)
    n_a = degrees.shape[1]
    if (pairs.ndim != 2 or pairs.shape[1] != 2 or not np.issubdtype(pairs.dtype, np.integer)
            or np.any(pairs < -n_a) or np.any(pairs >= n_a)):
        raise ValueError(f"baseline must be a pair of antenna indices (or pairs), each in "
                         f"0..{n_a - 1}, got {baseline!r}")
    f_hz = frequency_hz(frequency)
    if obstime is not None:
        obstime = as_time(obstime)
        if obstime.shape != degrees.shape[:1]:
            raise ValueError(f"obstime must hold the {degrees.shape[0]} epochs of the grid "
                             f"(shape ({degrees.shape[0]},)), got shape {obstime.shape}")
    difference = degrees[:, pairs[:, 1]] - degrees[:, pairs[:, 0]]
    if lazy:
        difference = difference.compute()
    if single:
        difference = difference[:, 0]
    if obstime is not None:
        obstime = obstime.reshape((obstime.size,) + (1,) * (difference.ndim - 1))
    return delay_of_difference(Angle(difference, u.deg), f_hz, axis=0, obstime=obstime,
                               max_gap=max_gap)
