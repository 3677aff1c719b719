# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation of one antenna or a baseline over time, as astropy Tables.

These are the tables that the ``feedrot`` command writes and that
`astropy_feedrot.applied.plotting` draws. Angles are in degrees; the ``continuous``
column is made continuous with `~astropy_feedrot.unwrap` (Eq 9), restarting
after epochs below the elevation limit and after gaps of more than two
sampling steps.
"""

import numpy as np
from astropy import units as u
from astropy.table import Table

from ..earth.eop import iers_context
from ..earth.frames import as_elevation_limit, as_skycoord, fill_masked
from ..engine.antenna import Antenna
from ..engine.continuity import delay_of_difference, frequency_hz, unwrap
from ..transmitters.satellite import Satellite

__all__ = ["COLUMNS", "feed_rotation_table", "baseline_table", "baseline_summary", "check_times",
           "target_name"]

#: Columns of `feed_rotation_table` (after ``time``), in order.
COLUMNS = ("azimuth", "elevation", "parallactic_angle", "transmitter", "receiver", "total",
           "continuous", "rate")


def _max_gap(times):
    """Two sampling steps: the longest step between valid epochs, doubled."""
    filled, masked = fill_masked(times)
    jd = filled.jd if masked is None else filled.jd[~masked]
    if jd.size < 2:
        return None
    return 2 * np.max(np.diff(jd)) * u.day


def check_times(obstime):
    """``obstime`` checked as a table's epochs: one-dimensional, strictly increasing.

    Parameters
    ----------
    obstime : `~astropy.time.Time`
        Epochs; masked ones are kept (their rows are NaN).

    Returns
    -------
    `~astropy.time.Time`

    Raises
    ------
    ValueError
        If ``obstime`` is not one-dimensional or does not increase strictly.

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.applied.feed_rotation_tables import check_times
    >>> check_times(Time(["2024-01-01", "2023-01-01"]))
    Traceback (most recent call last):
    ...
    ValueError: obstime must increase strictly (masked epochs aside); sort it, e.g. \
obstime[np.argsort(obstime)], and drop repeated epochs
    """
    times, masked = fill_masked(obstime)
    if times.ndim != 1:
        raise ValueError(f"obstime must be a one-dimensional series of epochs, got shape "
                         f"{times.shape}")
    jd = times.jd if masked is None else times.jd[~masked]
    if jd.size > 1 and np.any(np.diff(jd) <= 0):
        raise ValueError("obstime must increase strictly (masked epochs aside); sort it, "
                         "e.g. obstime[np.argsort(obstime)], and drop repeated epochs")
    return obstime if masked is not None else times


def _check_target(target):
    """One satellite or one natural source."""
    if isinstance(target, Satellite):
        return target
    coord = as_skycoord(target)
    if not coord.isscalar and coord.size != 1:
        raise ValueError(f"a table follows one target, got a coordinate of shape "
                         f"{coord.shape}; make one table per source, or use "
                         "astropy_feedrot.engine.grid.feed_rotation_grid for many")
    return coord.reshape(())


def _antenna_columns(antenna, target, times, polarization, min_elevation, limit):
    if not isinstance(antenna, Antenna):
        raise TypeError(f"antenna must be an Antenna, got {type(antenna).__name__}")
    # One line of sight (orbit propagation, Earth rotation) serves every column.
    angles = antenna.angles(target, times, polarization, min_elevation=min_elevation)
    # Visible: a finite elevation (not a masked epoch) at or above the limit.
    lowest = -np.inf if limit is None else limit
    elevation = angles.elevation.rad
    visible = np.isfinite(elevation) & (elevation >= lowest)
    columns = {name: getattr(angles, name).to(u.deg) for name in COLUMNS[:-2]}
    if not isinstance(target, Satellite):
        # A natural source has no transmitter term (Eq 21 is zero by definition;
        # the engine's value is rounding, ~1e-16 deg).
        # NaN stays where the angles are undefined (below the limit, masked epochs).
        defined = np.isfinite(columns["transmitter"].value)
        columns["transmitter"] = np.where(defined, 0.0, np.nan) * u.deg
    columns["continuous"] = unwrap(columns["total"], mask=~visible, obstime=times,
                                   max_gap=_max_gap(times)).to(u.deg)
    columns["rate"] = antenna.feed_rotation_rate(target, times, polarization,
                                                 min_elevation=min_elevation)
    return {name: u.Quantity(value) for name, value in columns.items()}, visible


def target_name(target):
    """A satellite's name, or a natural source's coordinates and frame, for a table's meta.

    Examples
    --------
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy_feedrot.applied.feed_rotation_tables import target_name
    >>> target_name(SkyCoord("03h19m48.16s +41d30m42.1s"))
    '03h19m48.16s +41d30m42.1s (icrs)'
    """
    if isinstance(target, Satellite):
        return str(target.name) if target.name else repr(target)
    # A SkyCoord's ``name`` is the name of its frame, not of the source.
    return f"{target.to_string('hmsdms')} ({target.frame.name})"


@iers_context()  # one check of the Earth-orientation tables per call
def feed_rotation_table(antenna, target, obstime, polarization=None, min_elevation=None):
    """Feed rotation of one antenna over a series of epochs.

    Parameters
    ----------
    antenna : `~astropy_feedrot.Antenna`
        The receiving antenna.
    target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
        One natural source or one satellite.
    obstime : `~astropy.time.Time`
        Strictly increasing epochs (one-dimensional); masked epochs are kept
        as rows whose angles are NaN.
    polarization, min_elevation : optional
        As for `~astropy_feedrot.Antenna.feed_rotation`.

    Returns
    -------
    `~astropy.table.Table`
        Columns ``time`` and then `COLUMNS`: azimuth and elevation (deg),
        parallactic angle (Eq 15), the transmitter and receiver terms
        (Eqs 21, 22), the total feed rotation wrapped to (-180, 180] deg,
        the continuous total and the rate of the feed rotation (deg/s,
        `~astropy_feedrot.Antenna.feed_rotation_rate`). Angles are NaN below
        ``min_elevation``. The ``meta`` records antenna, target, whether it
        is a natural source (``natural``), polarization and elevation limit.

    Raises
    ------
    TypeError
        If ``antenna`` is not an `~astropy_feedrot.Antenna`, and for the
        errors of `~astropy_feedrot.Antenna.feed_rotation`.
    ValueError
        If ``obstime`` is not a one-dimensional increasing series, ``target``
        holds several sources, or for the errors of
        `~astropy_feedrot.Antenna.feed_rotation`.
    astropy.units.UnitsError
        If ``min_elevation`` is not an angle.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> from astropy_feedrot.applied.feed_rotation_tables import feed_rotation_table
    >>> times = Time("2023-01-25T18:00") + np.arange(3) * u.hour
    >>> table = feed_rotation_table(get_antenna("EFLSBERG"),
    ...                             SkyCoord("03h19m48.16s +41d30m42.1s"), times)
    >>> table["total"].quantity  # doctest: +FLOAT_CMP
    <Quantity [-30.90395267,  24.10716885,  51.55021012] deg>
    """
    times = check_times(obstime)
    target = _check_target(target)
    limit = as_elevation_limit(min_elevation)
    columns, _ = _antenna_columns(antenna, target, times, polarization, min_elevation, limit)
    table = Table({"time": times, **columns})
    table.meta.update(antenna=antenna.name or repr(antenna), target=target_name(target),
                      natural=not isinstance(target, Satellite),
                      polarization=str(polarization or getattr(target, "polarization", "RCP")),
                      min_elevation=str(min_elevation))
    return table


@iers_context()  # one check of the Earth-orientation tables per call
def baseline_table(antenna1, antenna2, target, obstime, frequency, polarization=None,
                   min_elevation=None):
    """Feed rotation at both ends of a baseline and the rotation delay between them.

    Parameters
    ----------
    antenna1, antenna2 : `~astropy_feedrot.Antenna`
        The baseline; the delay is antenna 2 minus antenna 1.
    target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
        What both observe.
    obstime : `~astropy.time.Time`
        Strictly increasing epochs (one-dimensional); masked epochs are kept
        as rows whose angles and delay are NaN.
    frequency : `~astropy.units.Quantity`
        Observing frequency of the rotation delay (see
        `~astropy_feedrot.rotation_delay`).
    polarization, min_elevation : optional
        As for `~astropy_feedrot.Antenna.feed_rotation`.

    Returns
    -------
    `~astropy.table.Table`
        ``time``; for each antenna the columns of `feed_rotation_table`
        prefixed with the antenna's name and ``_``; ``rotation_delay`` (ps,
        continuous, NaN where the target is below the limit at either
        antenna) and ``both_visible`` (False at masked epochs too).
        ``meta["ambiguity"]`` is the delay ambiguity :math:`1/f`.

    Raises
    ------
    TypeError, astropy.units.UnitsError
        As `feed_rotation_table` and `~astropy_feedrot.rotation_delay`.
    ValueError
        If the two antennas have the same name, or as `feed_rotation_table`
        and `~astropy_feedrot.rotation_delay`.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> from astropy_feedrot.applied.feed_rotation_tables import baseline_table
    >>> times = Time("2023-01-25T18:00") + np.arange(3) * 10 * u.min
    >>> table = baseline_table(get_antenna("EFLSBERG"), get_antenna("YEBES40M"),
    ...                        SkyCoord("03h19m48.16s +41d30m42.1s"), times, 8.4 * u.GHz)
    >>> table.meta["ambiguity"]
    '119.04761904761905 ps'
    """
    times = check_times(obstime)
    names = [antenna.name if isinstance(antenna, Antenna) else None
             for antenna in (antenna1, antenna2)]
    prefixes = [name or f"antenna{i}" for i, name in enumerate(names, start=1)]
    if prefixes[0] == prefixes[1]:
        raise ValueError(f"the two antennas of a baseline must differ; both are {prefixes[0]!r}")
    f_hz = frequency_hz(frequency)
    target = _check_target(target)
    limit = as_elevation_limit(min_elevation)
    table = Table({"time": times})
    visible = np.ones(times.shape, bool)
    totals = []
    for prefix, antenna in zip(prefixes, (antenna1, antenna2)):
        columns, above = _antenna_columns(antenna, target, times, polarization, min_elevation,
                                          limit)
        visible &= above
        totals.append(columns["total"])
        for name, value in columns.items():
            table[f"{prefix}_{name}"] = value
    # The delay of `~astropy_feedrot.rotation_delay`, from the totals above.
    result = delay_of_difference(totals[1] - totals[0], f_hz, axis=0, obstime=times,
                                 max_gap=_max_gap(times))
    table["rotation_delay"] = result.delay
    table["both_visible"] = visible
    table.meta.update(antennas=prefixes, target=target_name(target),
                      natural=not isinstance(target, Satellite),
                      frequency=str(u.Quantity(frequency)), min_elevation=str(min_elevation),
                      ambiguity=str(result.ambiguity))
    return table


def _span(values):
    values = u.Quantity(values)
    return np.nanmin(values), np.nanmax(values)


def _check_baseline_table(table):
    """The two antenna prefixes of a `baseline_table`; ValueError if it is not one."""
    if not isinstance(table, Table):
        raise TypeError(f"table must be an astropy Table from baseline_table, got "
                        f"{type(table).__name__}")
    antennas = table.meta.get("antennas")
    if not isinstance(antennas, (list, tuple)) or len(antennas) != 2:
        raise ValueError("table is not from baseline_table: its meta has no 'antennas' "
                         "pair; build it with astropy_feedrot.baseline_table")
    needed = ["time", "both_visible", "rotation_delay"] + [
        f"{name}_{column}" for name in antennas
        for column in ("receiver", "transmitter", "continuous")]
    missing = [name for name in needed if name not in table.colnames]
    missing += [key for key in ("min_elevation", "frequency", "ambiguity")
                if key not in table.meta]
    if missing:
        raise ValueError(f"table is not from baseline_table: it lacks {', '.join(missing)}")
    return antennas


def baseline_summary(table):
    """A few lines that summarize a `baseline_table`.

    Parameters
    ----------
    table : `~astropy.table.Table`
        A table from `baseline_table`.

    Returns
    -------
    str
        When the target is above the limit at both antennas; per antenna the
        ranges of the receiver and transmitter terms and the span of the
        continuous total; the largest difference of the transmitter terms; the
        range of the rotation delay and its ambiguity.

    Raises
    ------
    TypeError
        If ``table`` is not an `~astropy.table.Table`.
    ValueError
        If ``table`` is not one from `baseline_table` (a column or ``meta``
        entry is missing), or the target is never visible from both antennas.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.simulations import gps_short_baseline
    >>> from astropy_feedrot.applied.feed_rotation_tables import baseline_summary
    >>> print(baseline_summary(gps_short_baseline(step=10 * u.min)))  # doctest: +ELLIPSIS
    GPS SVN 76 over DBR205 and FD-VLBA
      both above 10.0 deg: 42 epochs, 2023-01-25T08:10:00.000 to 2023-01-25T15:00:00.000
    ...
    """
    first, second = _check_baseline_table(table)
    visible = np.asarray(table["both_visible"])
    if not visible.any():
        raise ValueError("the target is never above the elevation limit at both antennas")
    times = table["time"][visible]
    lines = [f"{table.meta.get('satellite', table.meta.get('target', ''))} over {first} and "
             f"{second}",
             f"  both above {table.meta['min_elevation']}: {visible.sum()} epochs, "
             f"{times[0].isot} to {times[-1].isot}"]
    for name in (first, second):
        rx = _span(table[f"{name}_receiver"][visible])
        tx = _span(table[f"{name}_transmitter"][visible])
        cont = _span(table[f"{name}_continuous"][visible])
        lines.append(f"  {name}: receiver term {rx[0]:.1f} to {rx[1]:.1f}, transmitter term "
                     f"{tx[0]:.1f} to {tx[1]:.1f}, continuous total spans "
                     f"{cont[1] - cont[0]:.1f}")
    dtx = u.Quantity(table[f"{second}_transmitter"] - table[f"{first}_transmitter"])
    dtx = ((dtx + 180 * u.deg) % (360 * u.deg) - 180 * u.deg)[visible]
    lines.append(f"  difference of the transmitter terms: up to {np.nanmax(np.abs(dtx)):.4f}")
    delay = _span(table["rotation_delay"][visible])
    lines.append(f"  rotation delay {second} - {first} at {table.meta['frequency']}: "
                 f"{delay[0]:.1f} to {delay[1]:.1f} (span {delay[1] - delay[0]:.1f}); "
                 f"ambiguity {u.Quantity(table.meta['ambiguity']):.1f}")
    return "\n".join(lines)
