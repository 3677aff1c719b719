# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation on a grid of epochs x antennas x targets, for networks and long series.

`Antenna.feed_rotation <astropy_feedrot.Antenna.feed_rotation>` computes one
antenna and one target at a time: every call propagates the orbit, rotates it
to the Earth-fixed frame and finds the Sun again. For a network observing a
constellation, those per-epoch quantities are shared: this module computes
them once per epoch for all satellites (one SGP4 call for all element sets,
one Earth orientation, one Sun), and hands the whole grid of epochs (T) x
antennas (A) x targets (S) to the wind-up engine (`~astropy_feedrot.engine.equations`),
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

from ..antennas.rotators import rotation_angles
from ..core import kernel
from ..core.extras import install_hint
from ..core.polarization import polarization_sign
from ..earth.eop import iers_context
from ..earth.epochs import Epochs
from ..earth.frames import as_elevation_limit, as_skycoord, as_time, location_xyz, source_direction
from ..earth.orientation import distance_less
from ..transmitters.attitude_interface import Attitude
from ..transmitters.orbits import Orbit
from ..transmitters.satellite import Satellite, check_transmitter_positions
from . import equations, rates
from .antenna import Antenna
from .continuity import delay_of_difference, frequency_hz
from .equations import ReceiverArrays, Receivers, check_form
from .grid_arrays import (
    FOCUS_TERMS,
    UNIT_TOLERANCE,
    grid_block,
    nominal_attitude,
    wind_up,
)
from .grid_natural import natural_grid, topocentric

__all__ = [
    "UNIT_TOLERANCE",
    "FOCUS_TERMS",
    "ReceiverArrays",
    "receiver_arrays",
    "wind_up",
    "nominal_attitude",
    "feed_rotation_grid",
    "feed_rotation_grid_dask",
    "feed_rotation_rate_grid",
    "rotation_delay_grid",
]


#: Default number of grid points per chunk of `feed_rotation_grid_dask`.
DASK_CHUNK_POINTS = 2**21


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


def _receivers_each(antennas):
    return [_receivers([antenna]) for antenna in _check_antennas(antennas)]


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
    >>> from astropy_feedrot.engine.grid import receiver_arrays
    >>> from astropy_feedrot.stations.catalogue import get_antenna
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
    # For fixed natural sources: their geocentric apparent directions (S, T, 3) and
    # the geocentre's velocity (T, 3), shared by every antenna (target is then
    # None: no (T, A, S, 3) array is held).
    per_antenna: tuple = None


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


def _earth_orientation(epochs):
    """The Earth orientation of `~astropy_feedrot.Epochs` where it serves, else None."""
    return epochs.orientation if epochs.uses_nodes() else None


def _satellite_arrays(satellites, epochs, polarization):
    """Positions and dipoles (T, S, 3) of satellites, and their signs (S,).

    Every orbit class propagates its members in one batch and every attitude
    model with the Sun shares one Sun (`Orbit.positions`,
    `Attitude.dipoles_many`); one Earth orientation serves them all. NaN at
    ``masked`` epochs (True), where ``obstime`` holds stand-ins.
    """
    obstime, masked = epochs.filled, epochs.mask
    n_t, n_s = obstime.size, len(satellites)
    sign = np.array([equations.receiver_sign(sat, polarization) for sat in satellites], dtype=float)
    if masked is not None and masked.all():
        nothing = np.full((n_t, n_s, 3), np.nan)
        return nothing, nothing.copy(), nothing.copy(), sign
    orbits = [sat.orbit for sat in satellites]
    attitudes = [sat.attitude for sat in satellites]
    orientation = None
    if any(o.uses_orientation for o in orbits) or any(a.needs_sun for a in attitudes):
        orientation = _earth_orientation(epochs)
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


def _source_directions(sources, antennas, epochs):
    """Apparent topocentric directions (T, A, S, 3) of natural sources at each antenna.

    A 2-d ``sources`` (T, S) moves: element [k, j] is source j at epoch k.
    """
    obstime = epochs.filled
    n_t, n_s = obstime.size, sources.shape[-1] if sources.ndim else 1
    out = np.empty((n_t, len(antennas), n_s, 3))
    if sources.ndim == 2:
        for i, antenna in enumerate(antennas):
            out[:, i] = source_direction(sources, antenna.location, obstime[:, np.newaxis])
        return out
    shared = _geocentric_directions(sources, epochs, None)
    if shared is not None:  # the geocentric directions, each site's diurnal aberration
        for i, antenna in enumerate(antennas):
            out[:, i] = np.swapaxes(topocentric(*shared[:1], location_xyz(antenna.location),
                                                shared[1]), 0, 1)
        return out
    column = sources.reshape((n_s, 1))
    orientation = None
    if epochs.uses_nodes(column):  # every source at every epoch
        orientation = epochs.orientation
        icrs = sources.icrs
    for i, antenna in enumerate(antennas):
        if orientation is not None:
            s = orientation.source_directions(icrs, antenna.location)
        else:
            s = source_direction(column, antenna.location, obstime)
        out[:, i] = np.swapaxes(s.reshape(n_s, n_t, 3), 0, 1)
    return out


def _geocentric_directions(sources, epochs, masked):
    """Geocentric apparent directions (S, T, 3) of fixed natural sources and the
    geocentre's velocity (T, 3) in units of c, or None.

    One set for every antenna (`~astropy_feedrot.engine.grid_natural`): None for
    moving sources, sources with a distance (their parallax differs between
    sites), or where the epochs' Earth orientation does not serve them
    (`~astropy_feedrot.earth.epochs.Epochs.uses_nodes`). NaN at masked epochs.
    """
    if sources.ndim == 2:  # moving sources
        return None
    n_s = sources.shape[-1] if sources.ndim else 1
    icrs = sources.icrs
    if not epochs.uses_nodes(sources.reshape((n_s, 1))) or not distance_less(icrs.data):
        return None
    s = epochs.orientation.source_directions(icrs, None).reshape(n_s, epochs.size, 3)
    if masked is not None:  # NaN directions: NaN feed rotation, not degenerate
        s[:, masked] = np.nan
    return s, epochs.orientation.geocentre_velocity()


def _prepare(antennas, targets, obstime, polarization, form, min_elevation, lazy=False):
    antennas = _check_antennas(antennas)
    kind, targets = _check_targets_objects(targets)
    time = as_time(obstime)
    if time.ndim > 1:
        raise ValueError(f"obstime must be a scalar or 1-d Time (the time axis of the grid), "
                         f"got shape {time.shape}; flatten it with .ravel()")
    shape = time.shape
    # One Epochs for the whole grid (the caller's, if 1-d), handed to every step.
    epochs = obstime if isinstance(obstime, Epochs) and time.ndim == 1 else Epochs(
        time.reshape((time.size,)))
    obstime, masked = epochs.filled, epochs.mask
    form = check_form(form)
    min_sine = equations.min_sine(as_elevation_limit(min_elevation))
    receivers = _receivers(antennas)
    if kind == "sources" and targets.ndim == 2 and targets.shape[0] != obstime.size:
        raise ValueError(f"moving sources (a 2-d SkyCoord) need one row per epoch: shape "
                         f"{targets.shape} for {obstime.size} epochs")
    per_antenna = None
    if kind == "satellites":
        target, aligned, transverse, sign = _satellite_arrays(targets, epochs, polarization)
        positions = True
    else:
        sign = np.full(targets.shape[-1] if targets.ndim else 1, polarization_sign(
            "RCP" if polarization is None else polarization), dtype=float)
        per_antenna = None
        plain = all(antenna.rotator is None or antenna.rotator.mode != "series"
                    for antenna in antennas)
        if lazy and plain and not (masked is not None and masked.all()):
            per_antenna = _geocentric_directions(targets, epochs, masked)
        if per_antenna is not None:
            target = None
        elif masked is not None and masked.all():
            target = np.full((obstime.size, len(antennas), len(sign), 3), np.nan)
        else:
            target = _source_directions(targets, antennas, epochs)
        if masked is not None and target is not None:  # NaN: NaN feed rotation
            target[masked] = np.nan
        aligned = transverse = None
        positions = False
    rotation = rotation_angles([antenna.rotator for antenna in antennas], obstime)
    if rotation is not None and masked is not None:
        rotation[masked] = np.nan
    return _Grid(receivers, target, aligned, transverse, positions, form, sign, min_sine,
                 shape + (len(antennas), len(sign)), rotation, per_antenna)


def _dask_block(*arrays, all_rotation=None, block_info=None, **kwargs):
    rotation = None
    if all_rotation is not None:  # (T, A), small: sliced to the block's epochs here
        start, stop = block_info[None]["array-location"][0]
        rotation = all_rotation[start:stop]
    arrays = arrays + (None,) * (3 - len(arrays))
    return grid_block(*arrays, rotation, **kwargs)


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
    `~astropy_feedrot.earth.orientation.EarthOrientation`; the Sun of the nominal
    attitude is computed once per epoch for all satellites
    (`~astropy_feedrot.transmitters.nominal_attitude.interpolated_sun_position`). With
    ``conf.fast_path`` off the rigorous astropy transformations are used, as
    `~astropy_feedrot.Antenna.feed_rotation` does
    (`~astropy_feedrot.earth.orientation.fast_path_applies`). The per-epoch arrays take
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
    >>> from astropy_feedrot.engine.grid import feed_rotation_grid
    >>> from astropy_feedrot.applied.simulations import gps_svn76
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> antennas = [get_antenna("DBR205"), get_antenna("FD-VLBA")]
    >>> times = Time("2023-01-25T08:10") + np.arange(0, 7, 0.5) * u.hour
    >>> phi = feed_rotation_grid(antennas, [gps_svn76()], times)
    >>> phi.shape
    (14, 2, 1)
    >>> reference = antennas[1].feed_rotation(gps_svn76(), times)
    >>> bool(np.all(np.abs((phi[:, 1, 0] - reference).wrap_at(180 * u.deg)) < 1e-9 * u.deg))
    True
    """
    grid = _prepare(antennas, targets, obstime, polarization, form, min_elevation, lazy=True)
    if grid.per_antenna is None:
        out, degenerate = grid_block(grid.target, grid.aligned, grid.transverse, grid.rotation,
                                     count=True, **_block_arguments(grid))
    else:  # fixed natural sources: shared directions, each antenna's aberration and angle
        out, degenerate = natural_grid(*grid.per_antenna, _receivers_each(antennas), grid.sign[0],
                                       grid.min_sine)
    equations.warn_degenerate(degenerate, out.size, points="grid points")
    return Angle(out.reshape(grid.shape), u.deg, copy=False)


@iers_context()  # one check of the Earth-orientation tables per call
def feed_rotation_rate_grid(antennas, sources, obstime, *, polarization=None,
                            min_elevation=None):
    """Rate of the feed rotation of every antenna observing every natural source.

    Parameters
    ----------
    antennas : sequence of `~astropy_feedrot.Antenna`
        The receivers (A of them).
    sources : `~astropy.coordinates.SkyCoord`
        S natural sources, one scalar or 1-d coordinate, fixed in a celestial
        frame.
    obstime : `~astropy.time.Time` or `~astropy_feedrot.Epochs`
        The epochs, scalar or 1-d (T of them); masked epochs give NaN.
    polarization : {'RCP', 'LCP'}, optional
        Hand of the receivers (RCP by default).
    min_elevation : `~astropy.units.Quantity`, optional
        NaN where a source is lower than this above an antenna's horizon.

    Returns
    -------
    `~astropy.units.Quantity`
        In deg/s, shape (T, A, S) (or (A, S) for a scalar ``obstime``):
        element ``[k, i, j]`` equals
        ``antennas[i].feed_rotation_rate(sources[j], obstime[k])``.

    Raises
    ------
    TypeError
        If ``sources`` is not a coordinate (satellites: use
        `Antenna.feed_rotation_rate <astropy_feedrot.Antenna.feed_rotation_rate>`),
        or an argument is not of the expected kind.
    ValueError
        For moving sources (a 2-d coordinate), a multi-dimensional
        ``obstime`` or a bad ``min_elevation``.

    Warns
    -----
    DegenerateGeometryWarning
        Once, with the count, if some grid points are degenerate.

    Notes
    -----
    One `~astropy_feedrot.Epochs` serves every antenna: its celestial pole
    and its Sun (for the rate of the annual aberration), and the directions
    from its Earth orientation; the rate of each antenna is then
    `~astropy_feedrot.engine.equations.feed_rotation_rate`, as for
    `Antenna.feed_rotation_rate <astropy_feedrot.Antenna.feed_rotation_rate>`.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.engine.grid import feed_rotation_rate_grid
    >>> antennas = [get_antenna("WETTZ13S"), get_antenna("YEBES40M")]
    >>> sources = SkyCoord(["03h19m48.16s +41d30m42.1s", "12h29m06.7s +02d03m09s"])
    >>> times = Time("2023-01-25T18:00") + np.arange(3) * u.hour
    >>> rate = feed_rotation_rate_grid(antennas, sources, times)
    >>> rate.shape, rate.unit
    ((3, 2, 2), Unit("deg / s"))
    >>> one = antennas[1].feed_rotation_rate(sources[1], times)
    >>> bool(np.allclose(rate[:, 1, 1], one, rtol=0, atol=1e-10 * u.deg / u.s))
    True
    """
    antennas = _check_antennas(antennas)
    kind, sources = _check_targets_objects(sources)
    if kind != "sources":
        raise TypeError("feed_rotation_rate_grid takes natural sources (a SkyCoord); for "
                        "satellites use Antenna.feed_rotation_rate")
    if sources.ndim > 1:
        raise ValueError(f"sources must be a scalar or 1-d SkyCoord of fixed sources, got "
                         f"shape {sources.shape}")
    time = as_time(obstime)
    if time.ndim > 1:
        raise ValueError(f"obstime must be a scalar or 1-d Time (the time axis of the grid), "
                         f"got shape {time.shape}; flatten it with .ravel()")
    epochs = obstime if isinstance(obstime, Epochs) and time.ndim == 1 else Epochs(
        time.reshape((time.size,)))
    sign = polarization_sign("RCP" if polarization is None else polarization)
    limit = equations.min_sine(as_elevation_limit(min_elevation))
    n_s, n_t = sources.size, epochs.size
    column = sources.reshape((n_s, 1))
    pole = epochs.celestial_pole()[np.newaxis]  # (1, T, 3)
    sun = epochs.sun_position()[np.newaxis]
    out = np.empty((n_t, len(antennas), n_s))
    degenerate = 0
    geocentric = _geocentric_directions(sources, epochs, epochs.mask)
    for i, antenna in enumerate(antennas):
        site = location_xyz(antenna.location)
        if geocentric is None:
            s = source_direction(column, antenna.location, epochs)  # (S, T, 3)
        else:  # the shared directions, with this site's diurnal aberration
            s = topocentric(geocentric[0], site, geocentric[1])
        s_rate = rates.source_direction_rate(s, pole, site, sun)
        rotation_rate = None
        if antenna.rotator is not None and antenna.rotator.mode == "series":
            rotation_rate = np.broadcast_to(antenna.rotator.rate(epochs),
                                            s.shape[:-1])[..., np.newaxis]
        rate = equations.feed_rotation_rate(_receivers([antenna]), s[:, :, np.newaxis, np.newaxis],
                                            s_rate[:, :, np.newaxis, np.newaxis],
                                            rotation_rate)[..., 0, 0]
        below = None
        if limit is not None:
            below = kernel.dot(s, antenna.local_frame.up) < limit
        degenerate += int(np.count_nonzero(equations.degenerate(rate, s, below)))
        if below is not None:
            rate = np.where(below, np.nan, rate)
        out[:, i, :] = sign * rate.T
    equations.warn_degenerate(degenerate, out.size, "feed rotation rate", "grid points")
    shape = time.shape + (len(antennas), n_s)
    return u.Quantity(out.reshape(shape), u.rad / u.s).to(u.deg / u.s)


def _dask_array():
    try:
        import dask.array
    except ImportError:  # pragma: no cover - exercised only without dask
        raise ImportError(
            "feed_rotation_grid_dask needs dask: " + install_hint("dask", "'dask[array]'")
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
    >>> from astropy_feedrot.engine.grid import feed_rotation_grid, feed_rotation_grid_dask
    >>> from astropy_feedrot.applied.simulations import gps_svn76
    >>> from astropy_feedrot.stations.catalogue import get_antenna
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
    >>> from astropy_feedrot.engine.grid import feed_rotation_grid, rotation_delay_grid
    >>> from astropy_feedrot.applied.simulations import gps_svn76
    >>> from astropy_feedrot.stations.catalogue import get_antenna
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
