# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Planning polarization calibration: how much feed rotation a source offers.

A polarization calibrator separates the source's polarization from the
instrumental one (the leakage, or D-terms) because the two turn differently
as the feed rotates: the source's polarization turns with the feed rotation
and the leakage does not. The wider the range of feed rotation a calibrator
sweeps at *every* station while it is above the elevation limit, the better
the two are separated (a range of 90 deg or more is the usual aim; an
equatorial mount has none to offer, since its feed rotation is 0, Eq 17).

`feed_rotation_coverage` tabulates that range for every antenna and target
over a span of time, from one grid (`~astropy_feedrot.engine.grid.feed_rotation_grid`);
`rank_sources` orders the targets by their worst station, and
`plot_coverage` draws the tracks (matplotlib, imported on use).
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle, BaseCoordinateFrame, SkyCoord
from astropy.table import Table

from ..core.inputs import as_time
from ..core.progress import check_progress, progress_steps
from ..earth.epochs import Epochs
from ..earth.frames import as_elevation_limit
from ..engine.antenna import Antenna
from ..engine.continuity import unwrap
from ..engine.grid import feed_rotation_grid
from .plotting import line_styles, outside_legend, pyplot

__all__ = ["feed_rotation_coverage", "rank_sources", "plot_coverage"]


def _coordinate(value, name):
    if isinstance(value, BaseCoordinateFrame):
        value = SkyCoord(value)
    if not isinstance(value, SkyCoord):
        raise TypeError(f"target {name!r} must be a SkyCoord, got {type(value).__name__}; "
                        "names are not looked up (no network): give coordinates, e.g. "
                        "SkyCoord('03h19m48.16s +41d30m42.1s')")
    if not (value.isscalar or value.size == 1):
        raise ValueError(f"target {name!r} must be one source, got a coordinate of shape "
                         f"{value.shape}")
    return value.reshape(())


def _targets(targets, names):
    """Names (list of str) and one 1-d ICRS SkyCoord of the targets."""
    if isinstance(targets, str):
        raise TypeError(f"targets must be coordinates, got the str {targets!r}; names are not "
                        "looked up (no network): give {name: SkyCoord(...)}")
    if isinstance(targets, (SkyCoord, BaseCoordinateFrame)):
        coords = SkyCoord(targets)
        if coords.ndim > 1:
            raise ValueError(f"targets must be a scalar or 1-d SkyCoord, got shape "
                             f"{coords.shape}")
        coords = coords.reshape((coords.size,))
        if names is None:
            names = [c.to_string("hmsdms", precision=1) for c in coords]
        names = [str(name) for name in names]
        if len(names) != coords.size:
            raise ValueError(f"names holds {len(names)} names for {coords.size} targets")
        pairs = list(zip(names, coords))
    else:
        if names is not None:
            raise ValueError("names goes with a SkyCoord of targets; a dict or a sequence of "
                             "(name, SkyCoord) pairs names its targets itself")
        if isinstance(targets, dict):
            pairs = list(targets.items())
        else:
            try:
                pairs = [tuple(pair) for pair in targets]
            except TypeError:
                raise TypeError(f"targets must be a SkyCoord, a dict {{name: SkyCoord}} or a "
                                f"sequence of (name, SkyCoord) pairs, got "
                                f"{type(targets).__name__}") from None
            if any(len(pair) != 2 for pair in pairs):
                raise TypeError("targets must be a sequence of (name, SkyCoord) pairs")
        pairs = [(str(name), _coordinate(coord, str(name))) for name, coord in pairs]
    if not pairs:
        raise ValueError("targets is empty; give at least one source with its coordinates")
    names = [name for name, _ in pairs]
    repeated = sorted({name for name in names if names.count(name) > 1})
    if repeated:
        raise ValueError(f"target names must differ; repeated: {', '.join(repeated)}")
    # One SkyCoord from the list of them (numpy's concatenate gives an object array of
    # SkyCoords on astropy 6.0, and astropy's fails on a list of one).
    coords = SkyCoord([SkyCoord(coord).icrs.reshape(()) for _, coord in pairs])
    return names, coords


def _epochs(start, stop, step):
    start, stop = as_time(start), as_time(stop)
    for name, value in (("start", start), ("stop", stop)):
        if not value.isscalar:
            raise ValueError(f"{name} must be one epoch, got shape {value.shape}")
    if not isinstance(step, u.Quantity):
        raise TypeError(f"step must be a time Quantity (e.g. 10 * u.min), got "
                        f"{type(step).__name__} {step!r}")
    if step.unit.physical_type != "time":
        raise u.UnitsError(f"step must be a time (e.g. 10 * u.min), got a quantity in "
                           f"{step.unit.to_string() or 'dimensionless units'}")
    if not step.isscalar or not np.isfinite(step.value) or step.value <= 0:
        raise ValueError(f"step must be one positive finite time, got {step}")
    span = (stop - start).to(u.s)
    if span <= 0 * u.s:
        raise ValueError(f"stop ({stop.utc.isot}) must be after start ({start.utc.isot})")
    count = int(np.floor((span / step).to_value(u.one) * (1 + 1e-12))) + 1
    times = start + np.arange(count) * step
    times.format = "isot"
    return times


def _span(values):
    """(min, max) of a continuous series split into passes (NaN between them).

    Each pass is continuous on its own (Eq 9) but starts in (-180, 180] deg;
    passes after the first are moved by whole turns to where they widen the
    span least, so that passes that repeat each other (day after day) overlap
    and a pass cut by the ends of the span joins the rest of its track.
    """
    valid = np.isfinite(values)
    starts = np.flatnonzero(valid & ~np.concatenate([[False], valid[:-1]]))
    stops = np.flatnonzero(valid & ~np.concatenate([valid[1:], [False]])) + 1
    low, high = np.inf, -np.inf
    for first, last in zip(starts, stops):
        lo, hi = np.min(values[first:last]), np.max(values[first:last])
        if np.isfinite(low):
            k = np.round(((low + high) - (lo + hi)) / 720)
            turns = min((k - 1, k, k + 1), key=lambda t: max(high, hi + 360 * t)
                        - min(low, lo + 360 * t))
            lo, hi = lo + 360 * turns, hi + 360 * turns
        low, high = min(low, lo), max(high, hi)
    return low, high


def feed_rotation_coverage(antennas, targets, start, stop, step, min_elevation=10 * u.deg, *,
                           names=None, tracks=False, progress=False):
    """The range of feed rotation each antenna sees on each target above an elevation limit.

    Parameters
    ----------
    antennas : sequence of `~astropy_feedrot.Antenna`
        The stations (a network), of any mount, focus and rotator.
    targets : dict, sequence of pairs, or `~astropy.coordinates.SkyCoord`
        The candidate sources: ``{name: SkyCoord}``, a sequence of ``(name,
        SkyCoord)`` pairs, or a scalar or 1-d `~astropy.coordinates.SkyCoord`
        (named by ``names``, or by their coordinates). Names are never looked
        up: coordinates are required.
    start, stop : `~astropy.time.Time`
        The span; the epochs are ``start + k * step`` up to ``stop``.
    step : `~astropy.units.Quantity`
        The sampling interval (a positive time). Near the zenith of an alt-az
        antenna the feed rotation turns fast; a step of a few minutes keeps
        the continuous series unambiguous.
    min_elevation : `~astropy.units.Quantity`, optional
        The elevation limit (default 10 deg).
    names : sequence of str, optional
        Names of the targets when ``targets`` is a `~astropy.coordinates.SkyCoord`.
    tracks : bool, optional
        Also return the epochs and the continuous feed rotation (for
        `plot_coverage`).

    Returns
    -------
    `~astropy.table.Table`, or (table, times, continuous) with ``tracks``
        One row per antenna and target (antennas first): ``antenna``,
        ``target``; ``range``, ``min`` and ``max`` (deg) of the continuous
        feed rotation (`~astropy_feedrot.unwrap`, Eq 9) over all epochs at
        which the target is above the limit; ``hours`` above the limit (the
        number of such epochs times ``step``) and ``epochs``. A target that
        never rises above the limit at an antenna has NaN angles, 0 h and 0
        epochs there. ``meta`` holds the span, the step and the limit.
        With ``tracks``, also the epochs (`~astropy.time.Time`, shape (T,))
        and the continuous feed rotation (`~astropy.coordinates.Angle`,
        shape (T, A, S), NaN below the limit).

    Raises
    ------
    TypeError
        If ``antennas`` are not antennas, a target is not a coordinate (a
        name alone), ``start``/``stop`` are not times, ``step`` is a plain
        number, or ``progress`` is neither a bool nor a callable.
    ValueError
        If ``targets`` is empty or names repeat, ``step`` is not positive,
        ``stop`` is not after ``start``, ``min_elevation`` is not one angle
        in [-90, 90] deg, or no antenna sees any target above the limit.
    astropy.units.UnitsError
        If ``step`` is not a time or ``min_elevation`` not an angle.

    Warns
    -----
    ContinuityWarning
        If consecutive epochs of a series differ by more than 162 deg (a
        pass close to the zenith of an alt-az antenna): use a smaller step.
    DegenerateGeometryWarning
        If a target passes within 0.2 mas of a singular direction.

    Notes
    -----
    ``progress`` (True: astropy's `~astropy.utils.console.ProgressBar` on
    standard error when it is a terminal; or a callable ``progress(done,
    total)``) counts the grid as one step, each antenna's elevations as one,
    and the continuous series and their ranges as one.

    The feed rotation of every antenna, target and epoch comes from one call
    of `~astropy_feedrot.engine.grid.feed_rotation_grid`; elevations from
    `~astropy_feedrot.Antenna.altaz` (one call per antenna, all sharing one
    `~astropy_feedrot.Epochs`). The continuous
    series restarts after each time the target sets (each pass keeps its
    own first value, in (-180, 180] deg), and the range is the span of all
    its values, each pass after the first moved by whole turns to where it
    widens the span least: passes that repeat each other (day after day)
    overlap, and a pass cut by the start of the span joins the rest of its
    track cut by the stop a sidereal day later.

    Examples
    --------
    3C 84 and 3C 286 from Effelsberg and Yebes over a day:

    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.applied.planning import feed_rotation_coverage
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> antennas = [get_antenna("EFLSBERG"), get_antenna("YEBES40M")]
    >>> sources = {"3C84": SkyCoord("03h19m48.16s +41d30m42.1s"),
    ...            "3C286": SkyCoord("13h31m08.29s +30d30m33.0s")}
    >>> table = feed_rotation_coverage(antennas, sources, Time("2024-03-01T00:00"),
    ...                                Time("2024-03-02T00:00"), 10 * u.min)
    >>> for row in table:
    ...     print(f"{row['antenna']:8s} {row['target']:5s} {row['range']:6.1f} deg "
    ...           f"{row['hours']:5.1f} h")
    EFLSBERG 3C84   116.4 deg  18.2 h
    EFLSBERG 3C286   94.9 deg  15.2 h
    YEBES40M 3C84   293.6 deg  15.8 h
    YEBES40M 3C286  162.5 deg  14.2 h
    """
    antennas = list(antennas) if not isinstance(antennas, Antenna) else antennas
    names_, coords = _targets(targets, names)
    times = _epochs(start, stop, step)
    limit = as_elevation_limit(min_elevation)
    check_progress(progress)
    # Steps: the grid, each antenna's elevations, the continuous series.
    steps = (len(antennas) if isinstance(antennas, list) else 1) + 2
    with progress_steps(progress, steps) as done:
        # The epochs converted once: one Epochs for the grid, one (T, 1) for the
        # elevations, which every antenna shares.
        phi = feed_rotation_grid(antennas, coords, Epochs(times))  # (T, A, S); checks antennas
        done()
        column = Epochs(times[:, np.newaxis])
        above = np.empty(phi.shape, dtype=bool)
        for i, antenna in enumerate(antennas):
            _, elevation = antenna.altaz(coords[np.newaxis, :], column)
            above[:, i] = elevation.rad >= limit
            done()
        if not above.any():
            raise ValueError(f"no antenna sees any target above {min_elevation} from "
                             f"{times[0].isot} to {times[-1].isot}; lower min_elevation, "
                             "widen the span or choose other targets")
        continuous = unwrap(phi, axis=0, mask=~above).to_value(u.deg)
        epochs = above.sum(axis=0)  # (A, S)
        low = np.full(epochs.shape, np.nan)
        high = np.full(epochs.shape, np.nan)
        for index in zip(*np.nonzero(epochs)):
            low[index], high[index] = _span(continuous[(slice(None),) + index])
        done()
    n_a, n_s = epochs.shape
    antenna_names = [antenna.name or repr(antenna) for antenna in antennas]
    table = Table({
        "antenna": np.repeat(antenna_names, n_s),
        "target": np.tile(names_, n_a),
        "range": (high - low).ravel() * u.deg,
        "min": low.ravel() * u.deg,
        "max": high.ravel() * u.deg,
        "hours": (epochs.ravel() * step).to(u.h),
        "epochs": epochs.ravel(),
    })
    table.meta.update(start=times[0].utc.isot, stop=times[-1].utc.isot, step=str(step),
                      min_elevation=str(u.Quantity(min_elevation)))
    if tracks:
        return table, times, Angle(continuous, u.deg)
    return table


def plot_coverage(table, times, continuous, path=None):
    """Draw the tracks of `feed_rotation_coverage`: one panel per target, one line per antenna.

    Parameters
    ----------
    table : `~astropy.table.Table`
        The table of `feed_rotation_coverage` (``tracks=True``).
    times : `~astropy.time.Time`
        Its epochs, shape (T,).
    continuous : `~astropy.coordinates.Angle`
        Its continuous feed rotation, shape (T, A, S).
    path : str or path-like, optional
        Save the figure there (the format follows the extension).

    Returns
    -------
    `matplotlib.figure.Figure`
        Continuous feed rotation (deg) against hours since the first epoch,
        above the elevation limit only, one colour and line style per
        antenna (`~astropy_feedrot.applied.plotting.line_styles`), the legend to the
        right of the tracks; each panel's title gives the target's worst
        range, or the stations that never see it above the limit.

    Raises
    ------
    ImportError
        Without matplotlib.
    ValueError
        If the shapes do not match the table.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.applied.planning import feed_rotation_coverage, plot_coverage
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> result = feed_rotation_coverage([get_antenna("EFLSBERG")],
    ...                                 {"3C84": SkyCoord("03h19m48.16s +41d30m42.1s")},
    ...                                 Time("2024-03-01"), Time("2024-03-02"), 30 * u.min,
    ...                                 tracks=True)
    >>> fig = plot_coverage(*result)
    >>> len(fig.axes)
    1
    """
    values = u.Quantity(continuous, u.deg).value
    antennas = list(dict.fromkeys(str(name) for name in table["antenna"]))
    targets = list(dict.fromkeys(str(name) for name in table["target"]))
    if values.shape != (len(times), len(antennas), len(targets)):
        raise ValueError(f"continuous has shape {values.shape}, but the table and times need "
                         f"{(len(times), len(antennas), len(targets))}")
    plt = pyplot()
    fig, axes = plt.subplots(len(targets), 1, sharex=True, squeeze=False,
                             figsize=(8, 2.2 + 2.3 * len(targets)))
    hours = (times - times[0]).to_value(u.hour)
    ranked = {row["target"]: row for row in rank_sources(table)}
    styles = line_styles(len(antennas))
    for j, (target, ax) in enumerate(zip(targets, axes[:, 0])):
        for i, antenna in enumerate(antennas):
            colour, linestyle = styles[i]
            ax.plot(hours, values[:, i, j], color=colour, linestyle=linestyle, label=antenna)
        ax.set_title(f"{target}: {_coverage_title(ranked[target], len(antennas))}",
                     fontsize="medium")
        ax.set_ylabel("feed rotation (deg)")
        ax.grid(alpha=0.3)
    outside_legend(axes[0, 0], fontsize="small", ncol=1 + (len(antennas) - 1) // 16)
    axes[-1, 0].set_xlabel(f"hours since {times[0].utc.isot[:19]} UTC "
                           f"(above {table.meta.get('min_elevation', 'the limit')})")
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=100, bbox_inches="tight")
    return fig


def _coverage_title(row, stations):
    """What a panel of `plot_coverage` says of its target: its worst range, or who
    never sees it above the limit."""
    worst = u.Quantity(row["worst_range"], u.deg).value
    if np.isfinite(worst):
        return f"worst range {worst:.1f} deg ({row['worst_antenna']})"
    if row["stations_above"] == 0:
        return "never above the limit at any station"
    unseen = stations - row["stations_above"]
    others = f" and {unseen - 1} other station{'s' if unseen > 2 else ''}" if unseen > 1 else ""
    return f"never above the limit at {row['worst_antenna']}{others}"


def rank_sources(table):
    """The targets of a `feed_rotation_coverage` table, best polarization calibrators first.

    Parameters
    ----------
    table : `~astropy.table.Table`
        From `feed_rotation_coverage`.

    Returns
    -------
    `~astropy.table.Table`
        One row per target: ``rank`` (1 for the best), ``target``, its worst
        station ``worst_antenna`` and that station's ``worst_range`` (deg),
        the ``best_range`` (deg) over the stations, and ``stations_above``
        (how many see it above the limit). Sorted by ``worst_range``,
        descending: the feed rotation a calibrator offers the whole network
        is that of its worst station. A target that some station never sees
        above the limit has a NaN ``worst_range`` (that station) and comes
        last.

    Raises
    ------
    TypeError
        If ``table`` is not an `~astropy.table.Table`.
    ValueError
        If it lacks the columns of `feed_rotation_coverage`.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.applied.planning import feed_rotation_coverage, rank_sources
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> antennas = [get_antenna("EFLSBERG"), get_antenna("YEBES40M")]
    >>> sources = {"3C84": SkyCoord("03h19m48.16s +41d30m42.1s"),
    ...            "3C286": SkyCoord("13h31m08.29s +30d30m33.0s")}
    >>> table = feed_rotation_coverage(antennas, sources, Time("2024-03-01T00:00"),
    ...                                Time("2024-03-02T00:00"), 10 * u.min)
    >>> for row in rank_sources(table):
    ...     print(row["rank"], row["target"], row["worst_antenna"], round(row["worst_range"]))
    1 3C84 EFLSBERG 116
    2 3C286 EFLSBERG 95
    """
    if not isinstance(table, Table):
        raise TypeError(f"table must be an astropy Table from feed_rotation_coverage, got "
                        f"{type(table).__name__}")
    missing = [name for name in ("antenna", "target", "range", "epochs")
               if name not in table.colnames]
    if missing:
        raise ValueError(f"table is not from feed_rotation_coverage: it lacks "
                         f"{', '.join(missing)}")
    targets = list(dict.fromkeys(str(name) for name in table["target"]))
    ranges = u.Quantity(table["range"], u.deg).value
    rows = []
    for target in targets:
        mine = np.flatnonzero(np.asarray(table["target"]) == target)
        values = ranges[mine]
        unseen = np.isnan(values)
        worst = int(mine[np.argmax(unseen)] if unseen.any() else mine[np.argmin(values)])
        rows.append((target, str(table["antenna"][worst]), ranges[worst],
                     np.nanmax(values) if not unseen.all() else np.nan,
                     int(np.count_nonzero(np.asarray(table["epochs"])[mine] > 0))))
    # Descending by the worst range; NaN (a station that never sees it) last.
    order = sorted(range(len(rows)),
                   key=lambda k: (np.isnan(rows[k][2]), -np.nan_to_num(rows[k][2])))
    rows = [rows[k] for k in order]
    return Table({
        "rank": np.arange(1, len(rows) + 1),
        "target": [row[0] for row in rows],
        "worst_antenna": [row[1] for row in rows],
        "worst_range": [row[2] for row in rows] * u.deg,
        "best_range": [row[3] for row in rows] * u.deg,
        "stations_above": np.array([row[4] for row in rows], dtype=int),
    }, meta=dict(table.meta))
