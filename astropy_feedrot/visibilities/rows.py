# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The feed rotation of every row of a visibility table.

A visibility file is a table of rows, each a baseline (two antenna numbers),
an epoch and a source (a phase centre). `feed_rotation_rows` gives the feed
rotation of both antennas of every row, computed once per distinct epoch,
antenna and source with the grid engine
(`~astropy_feedrot.feed_rotation_grid`), and `frame_position_angle` the angle
between the apparent north of date, to which feed rotations refer, and the
north of a catalogue frame. The data front-ends (`astropy_feedrot.visibilities.uvdata`,
`astropy_feedrot.visibilities.fitsidi`, `astropy_feedrot.visibilities.ms`) are built on these two.
"""

import warnings

import numpy as np
from astropy import units as u
from astropy.coordinates import (
    CIRS,
    Angle,
    BaseCoordinateFrame,
    SkyCoord,
    UnitSphericalRepresentation,
    frame_transform_graph,
)

from ..core.exceptions import DegenerateGeometryWarning, warn_caller
from ..core.inputs import as_skycoord, as_time
from ..earth.eop import iers_context
from ..engine.antenna import Antenna
from ..engine.grid import feed_rotation_grid
from .unusable import UnusableAntenna

__all__ = ["feed_rotation_rows", "frame_position_angle", "distinct_epochs", "FRAMES"]

#: Reference frames of the position angles: ``'apparent'`` (the true equator
#: and pole of date, to which feed rotations refer), ``'catalogue'`` (each
#: source's own frame), or any celestial frame astropy names (``'icrs'``,
#: ``'fk5'``, ``'fk4'``, ``'galactic'``...).
FRAMES = ("apparent", "catalogue")

# Offset toward the frame's north used to carry that direction into the
# apparent frame: small enough that the curvature of the sky does not matter,
# large enough for double precision (1e-16 / 5e-6 rad = 4 microarcseconds).
_OFFSET = 1 * u.arcsec


def _celestial_frame(frame):
    """A celestial frame (instance) named by ``frame``, or None for ``'catalogue'``."""
    if isinstance(frame, str):
        name = frame.strip().lower()
        if name == "catalogue" or name == "catalog":
            return None
        cls = frame_transform_graph.lookup_name(name)
        if cls is None:
            raise ValueError(f"unknown frame {frame!r}: give 'apparent', 'catalogue' or a "
                             f"celestial frame astropy knows, e.g. 'icrs', 'fk5', 'fk4'")
        frame = cls()
    elif isinstance(frame, type) and issubclass(frame, BaseCoordinateFrame):
        frame = frame()
    if not isinstance(frame, BaseCoordinateFrame):
        raise TypeError(f"frame must be a name or an astropy frame, got {type(frame).__name__}")
    if getattr(frame, "location", None) is not None or frame.name in ("altaz", "hadec", "itrs"):
        raise ValueError(f"frame must be celestial, got the Earth-bound {frame.name!r}")
    return frame


@iers_context()
def frame_position_angle(target, obstime, frame="icrs"):
    """The position angle of a frame's north, seen in the apparent frame of date.

    Feed rotations (`~astropy_feedrot.Antenna.feed_rotation`) are position
    angles from the apparent north of date, the direction toward the
    celestial intermediate pole. A polarization angle measured from the
    north of a catalogue frame (ICRS, FK5 J2000, FK4 B1950) differs by this
    angle :math:`\\delta`: :math:`\\chi_\\mathrm{frame} = \\chi_\\mathrm{apparent}
    - \\delta`.

    Parameters
    ----------
    target : `~astropy.coordinates.SkyCoord`
        The source(s), in any celestial frame.
    obstime : `~astropy.time.Time`
        Epoch(s) of observation; broadcast with ``target``.
    frame : str or `~astropy.coordinates.BaseCoordinateFrame`, optional
        The frame whose north is measured: ``'icrs'`` (default), another
        frame name or an instance such as ``FK4(equinox='B1950')``, or
        ``'catalogue'`` for the frame of ``target`` itself.

    Returns
    -------
    `~astropy.coordinates.Angle`
        :math:`\\delta` in degrees, in (-180, 180], positive from the apparent
        north toward east, with the broadcast shape of ``target`` and
        ``obstime``.

    Raises
    ------
    TypeError
        If ``target`` is not a coordinate or ``frame`` not a frame.
    ValueError
        For an unknown or Earth-bound frame.

    Notes
    -----
    A point 1 arcsec toward the frame's north is carried with the source into
    the geocentric apparent frame (astropy's `~astropy.coordinates.CIRS`:
    precession, nutation, aberration, light deflection), and the position
    angle between the two is measured there. Pure rotations map the great
    circle through the two points onto a great circle, so the result does not
    depend on the size of the offset; differential aberration changes it by
    less than a microarcsecond.

    Examples
    --------
    Precession turns the north of a source at RA 6 h on the equator by about
    20 arcsec a year (the precession in declination), 0.145 deg from J2000 to
    2026:

    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.visibilities.rows import frame_position_angle
    >>> source = SkyCoord(90 * u.deg, 0 * u.deg)
    >>> frame_position_angle(source, Time("2026-01-01"))  # doctest: +FLOAT_CMP
    <Angle 0.14534580 deg>
    """
    target = as_skycoord(target)
    obstime = as_time(obstime)
    frame = _celestial_frame(frame)
    north = target if frame is None else target.transform_to(frame)
    offset = north.directional_offset_by(0 * u.deg, _OFFSET)
    apparent = CIRS(obstime=obstime)
    here, there = north.transform_to(apparent), offset.transform_to(apparent)
    return Angle(here.position_angle(there)).wrap_at(180 * u.deg).to(u.deg)


def distinct_epochs(obstime):
    """The distinct epochs of a table and, for each row, the index of its epoch.

    Parameters
    ----------
    obstime : `~astropy.time.Time`
        One epoch per row (1-d).

    Returns
    -------
    epochs : `~astropy.time.Time`
        The distinct epochs in increasing order (compared exactly, on both
        parts of the Julian date).
    index : `~numpy.ndarray`
        For each row, the position of its epoch in ``epochs``.

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.visibilities.rows import distinct_epochs
    >>> epochs, index = distinct_epochs(Time([60000.5, 60000.0, 60000.5], format="mjd"))
    >>> epochs.mjd, index
    (array([60000. , 60000.5]), array([1, 0, 1]))
    """
    obstime = as_time(obstime)
    if obstime.ndim != 1:
        raise ValueError(f"obstime must be 1-d (one epoch per row), got shape {obstime.shape}")
    # Masked epochs by their hidden values (they give NaN later); plain arrays, as
    # numpy.unique takes no masked array on astropy 6.0.
    plain = obstime.unmasked if obstime.masked else obstime
    pairs = np.column_stack([np.asarray(plain.jd1, dtype=float),
                             np.asarray(plain.jd2, dtype=float)])
    # Normalize so that equal epochs have equal pairs.
    day = np.floor(pairs[:, 0] + pairs[:, 1])
    pairs = np.column_stack([day, (pairs[:, 0] - day) + pairs[:, 1]])
    _, first, index = np.unique(pairs, axis=0, return_index=True, return_inverse=True)
    return obstime[first], index.reshape(-1)


def _antenna_numbers(values, name):
    """Antenna numbers as a 1-d int array; ValueError for what is not whole numbers."""
    array = np.asarray(values).reshape(-1)
    whole = np.issubdtype(array.dtype, np.integer) or (
        np.issubdtype(array.dtype, np.floating) and bool(np.all(np.isfinite(array)))
        and bool(np.all(array == np.round(array))))
    if not whole:
        raise ValueError(f"{name} must be whole antenna numbers, one per row; got "
                         f"{array[:5].tolist()}")
    return array.astype(int)


def _antenna_list(antennas, antenna1, antenna2):
    """The antennas the rows use, and each row's two positions in that list."""
    if not hasattr(antennas, "keys"):
        raise TypeError(f"antennas must be a mapping {{antenna number: Antenna}}, got "
                        f"{type(antennas).__name__}")
    numbers = np.unique(np.concatenate([antenna1, antenna2]))
    missing = [int(n) for n in numbers if int(n) not in antennas]
    if missing:
        raise ValueError(f"rows use antenna numbers {missing[:10]} that antennas lacks "
                         f"(it has {sorted(antennas)[:20]})")
    used = []
    for n in numbers:
        antenna = antennas[int(n)]
        if isinstance(antenna, UnusableAntenna):
            raise ValueError(f"antenna {int(n)} ({antenna.name}) cannot be used: "
                             f"{antenna.reason}")
        if not isinstance(antenna, Antenna):
            raise TypeError(f"antennas[{int(n)}] must be an Antenna, got "
                            f"{type(antenna).__name__}")
        used.append(antenna)
    return used, np.searchsorted(numbers, antenna1), np.searchsorted(numbers, antenna2)


def _source_table(sources, source_index, n_rows):
    """{key: source} and the key of each row."""
    if source_index is None:
        if hasattr(sources, "keys"):
            raise ValueError("sources is a mapping, so source_index must give each row's key")
        return {0: sources}, np.zeros(n_rows, dtype=int)
    if not hasattr(sources, "keys"):
        raise TypeError("with source_index, sources must be a mapping {key: source}")
    source_index = np.asarray(source_index)
    if source_index.shape != (n_rows,):
        raise ValueError(f"source_index must give one key per row, shape ({n_rows},), got "
                         f"{source_index.shape}")
    missing = [k.item() for k in np.unique(source_index) if k.item() not in sources]
    if missing:
        raise ValueError(f"rows use source keys {missing[:10]} that sources lacks "
                         f"(it has {list(sources)[:20]})")
    return sources, source_index


def _check_finite(coord, key):
    """ValueError naming the source if some of its directions are not finite numbers."""
    direction = coord.represent_as(UnitSphericalRepresentation)
    bad = ~(np.isfinite(direction.lon.value) & np.isfinite(direction.lat.value))
    if np.any(bad):
        raise ValueError(f"source {key!r} has coordinates that are not numbers "
                         f"({int(np.count_nonzero(bad))} of {bad.size} positions, e.g. "
                         f"lon {np.ravel(direction.lon.deg)[np.ravel(bad)][0]}, lat "
                         f"{np.ravel(direction.lat.deg)[np.ravel(bad)][0]} deg): every angle "
                         "of its rows would be NaN; give the source's position")


def _track(source, epochs, key):
    """The source at the epochs: a fixed SkyCoord, or a (T, 1) one for a moving source."""
    if callable(source) and not isinstance(source, (SkyCoord, BaseCoordinateFrame)):
        track = as_skycoord(source(epochs))
        if track.shape != epochs.shape:
            raise ValueError(f"the moving source {key!r} gave positions of shape "
                             f"{track.shape} for {epochs.shape} epochs")
        _check_finite(track, key)
        return track.reshape((epochs.size, 1)), track
    coord = as_skycoord(source)
    if not coord.isscalar:
        raise ValueError(f"source {key!r} must be one direction (a scalar SkyCoord), or a "
                         f"function of the epochs for a moving source; got shape "
                         f"{coord.shape}")
    _check_finite(coord, key)
    return coord, coord


@iers_context()
def feed_rotation_rows(antennas, antenna1, antenna2, obstime, sources, source_index=None, *,
                       frame="apparent", min_elevation=None):
    """Feed rotation of both antennas of every row of a visibility table.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna}``, for example from
        `~astropy_feedrot.visibilities.fitsidi_antennas`.
    antenna1, antenna2 : array-like of int
        The antenna numbers of each row (N rows).
    obstime : `~astropy.time.Time`
        The epoch of each row, shape (N,).
    sources : `~astropy.coordinates.SkyCoord`, callable, or mapping of them
        What the antennas point at: a fixed source (a scalar coordinate in any
        celestial frame, proper motion applied), or a moving one given as a
        function that takes a `~astropy.time.Time` of shape (T,) and returns
        the source at those epochs (a coordinate of shape (T,), for example an
        interpolated ephemeris, or an `~astropy.coordinates.AltAz` direction
        for a drift scan). With ``source_index``, a mapping ``{key: source}``.
    source_index : array-like, optional
        The key of each row's source in ``sources`` (N,).
    frame : str or `~astropy.coordinates.BaseCoordinateFrame`, optional
        North of reference: ``'apparent'`` (default, the true pole of date)
        or a celestial frame (``'icrs'``, ``'catalogue'``...; see
        `frame_position_angle`), whose angle :math:`\\delta` is then
        subtracted.
    min_elevation : `~astropy.units.Quantity`, optional
        NaN where a source is lower than this at an antenna.

    Returns
    -------
    `~astropy.coordinates.Angle`
        Shape (N, 2): the feed rotation :math:`\\Phi` (RCP, degrees) of the
        first and the second antenna of each row; NaN where undefined.

    Raises
    ------
    TypeError
        If ``antennas`` is not a mapping of `~astropy_feedrot.Antenna`, or
        ``sources`` and ``source_index`` do not fit.
    ValueError
        For rows of other lengths, antenna numbers that are not whole
        numbers, antenna numbers or source keys that the mappings lack, a
        moving source that does not give one position per epoch, a source
        whose coordinates are not numbers (NaN; the message names its key),
        or an unknown ``frame``.

    Warns
    -----
    DegenerateGeometryWarning
        Once, with the number of rows, if some feed rotations are undefined
        (an alt-az antenna at the zenith, an equatorial one at the pole).

    Notes
    -----
    Each source is computed at its distinct epochs only, for every antenna
    at once (`~astropy_feedrot.feed_rotation_grid`); the rows then pick their
    two values. The cost grows with the number of distinct epochs times
    antennas, not with the number of baselines.

    Examples
    --------
    Two VLBA antennas on one baseline, three rows:

    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.visibilities.rows import feed_rotation_rows
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> antennas = {1: get_antenna("FD-VLBA"), 2: get_antenna("EFLSBERG")}
    >>> times = Time("2023-01-25T20:00") + [0, 0, 1] * u.hour
    >>> rows = feed_rotation_rows(antennas, [1, 2, 1], [2, 1, 2], times,
    ...                           SkyCoord("03h19m48.16s +41d30m42.1s"))
    >>> rows.shape
    (3, 2)
    >>> bool(rows[0, 0] == rows[1, 1])
    True
    """
    antenna1 = _antenna_numbers(antenna1, "antenna1")
    antenna2 = _antenna_numbers(antenna2, "antenna2")
    obstime = as_time(obstime)
    n_rows = antenna1.size
    if antenna2.size != n_rows or obstime.shape != (n_rows,):
        raise ValueError(f"antenna1, antenna2 and obstime must give one value per row: "
                         f"{antenna1.size}, {antenna2.size} and {obstime.shape}")
    reference = None if isinstance(frame, str) and frame.strip().lower() == "apparent" \
        else frame
    if reference is not None:
        _celestial_frame(reference)  # refuse a bad frame before computing
    used, pos1, pos2 = _antenna_list(antennas, antenna1, antenna2)
    sources, keys = _source_table(sources, source_index, n_rows)
    out = np.full((n_rows, 2), np.nan)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", DegenerateGeometryWarning)
        for key in np.unique(keys):
            rows = np.flatnonzero(keys == key)
            epochs, index = distinct_epochs(obstime[rows])
            target, coord = _track(sources[key.item()], epochs, key.item())
            phi = feed_rotation_grid(used, target, epochs, min_elevation=min_elevation)
            phi = phi.to_value(u.deg)[:, :, 0]  # (T, A)
            if reference is not None:
                delta = frame_position_angle(coord, epochs, reference).to_value(u.deg)
                phi = phi - np.reshape(delta, (-1, 1))
            out[rows, 0] = phi[index, pos1[rows]]
            out[rows, 1] = phi[index, pos2[rows]]
    degenerate = False
    for record in caught:
        if issubclass(record.category, DegenerateGeometryWarning):
            degenerate = True
        else:
            warnings.warn_explicit(record.message, record.category, record.filename,
                                   record.lineno)
    if degenerate:
        count = int(np.count_nonzero(np.isnan(out).any(axis=1)))
        warn_caller(f"the feed rotation is undefined in {count} of {n_rows} rows (an alt-az "
                    "antenna pointing at the zenith, or an equatorial one at the pole); "
                    "they are NaN", DegenerateGeometryWarning)
    return Angle(out, u.deg, copy=False)
