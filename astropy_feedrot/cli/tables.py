# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot natural``, ``feedrot satellite`` and ``feedrot baseline``: tables
of the feed rotation of one antenna, or of both antennas of a baseline with
their rotation delay, over a span of time."""

import warnings

import numpy as np
from astropy import units as u
from astropy.table import vstack

from ..applied.feed_rotation_tables import baseline_table, feed_rotation_table
from ..core.exceptions import OrbitWarning, warn_caller
from ..core.outputs import CommandError
from ..core.progress import progress_steps
from ..io import read_sp3, read_tle
from ..transmitters.nominal_attitude import NominalAttitude
from ..transmitters.orbits import SP3Orbit, TLEOrbit
from ..transmitters.quaternion_attitude import QuaternionAttitude
from ..transmitters.satellite import Satellite
from ..transmitters.sp3_orbit import POSITION_TOLERANCE, points_needed
from .common import (
    elevation_limit,
    in_units,
    natural_target,
    parse_antenna,
    parse_quantity,
    read_input,
    show_progress,
    station_catalogue,
    table_outputs,
    time_span,
    write_table,
    wrote,
)
from .shared import one_line

__all__ = ["run_natural", "run_satellite", "run_baseline"]

_SATELLITE_OPTIONS = ("tle", "sp3", "sat", "orbex", "points", "satellite_polarization")


_NATURAL_OPTIONS = ("source", "ra", "dec", "frame")

#: The columns ``--units`` converts (azimuth and elevation stay in degrees).
_PHASE_COLUMNS = ("parallactic_angle", "transmitter", "receiver", "total", "continuous",
                  "windup", "rate")


def _given(args, names):
    return ["--" + name.replace("_", "-") for name in names
            if getattr(args, name, None) is not None]


def _satellite(args):
    hand = args.satellite_polarization or "RCP"
    if args.polarization is not None and args.polarization != hand:
        # The rule of Antenna.feed_rotation: a receiver hears its own hand only.
        raise CommandError(
            f"an {args.polarization} receiver (--polarization {args.polarization}) does not "
            f"receive the {hand} signal of the satellite; leave --polarization unset or give "
            f"--polarization {hand} (--satellite-polarization sets the satellite's hand, "
            "RCP by default as for GNSS)")
    if args.tle is not None:
        for option in ("sp3", "orbex", "points"):
            if getattr(args, option) is not None:
                raise CommandError(f"--{option} goes with --sp3; --tle is the other orbit source")
        records = read_input(read_tle, args.tle, "--tle")
        if args.sat is not None:
            chosen = [r for r in records
                      if args.sat.strip().upper() in (r.name.upper(), r.catalog_number)]
            if not chosen:
                raise CommandError(f"--sat {args.sat!r} is not in {args.tle}; it has "
                                   + ", ".join(f"{r.name} ({r.catalog_number})" for r in records))
        elif len(records) > 1:
            raise CommandError(f"{args.tle} has {len(records)} satellites; choose one with --sat "
                               "(name or catalogue number)")
        else:
            chosen = records
        record = chosen[0]
        orbit = TLEOrbit(record.line1, record.line2, name=record.name)
        return Satellite(orbit, polarization=hand, name=record.name), None
    if args.sp3 is None:
        raise CommandError("give the satellite's orbit with --tle FILE or --sp3 FILE [--sat NAME]")
    data = read_input(read_sp3, args.sp3, "--sp3")
    points = min(10, len(data.epochs)) if args.points is None else args.points
    if points < 2:
        raise CommandError(f"--points must be at least 2 (epochs of the interpolation window), "
                           f"got {points}")
    needed = points_needed(data.interval)
    if points < min(needed, len(data.epochs)):
        # Fewer points than the file allows and its sampling needs: said, not refused
        # (a table for planning; feedrot rinex refuses it).
        warn_caller(f"--points {points} at the SP3 file's {data.interval:g} s interval: its "
                    f"positions may be off by more than {POSITION_TOLERANCE:g} m between "
                    f"epochs; --points {min(needed, len(data.epochs))} keeps them within",
                    OrbitWarning)
    span = (data.epochs[0].utc, data.epochs[-1].utc)
    if args.sat is not None:
        return _sp3_satellite(args, data, args.sat.strip(), points, hand), span
    if getattr(args, "antennas", None) is not None:
        raise CommandError("--sp3 needs --sat with two antennas, the satellite's SP3 name "
                           "(e.g. G05)")
    satellites, skipped = [], []
    for name in data.satellites:
        try:
            satellites.append(_sp3_satellite(args, data, name, points, hand))
        except CommandError as error:
            skipped.append(f"{name} ({str(error).removeprefix('--sp3: ')})")
    if not satellites:
        raise CommandError(f"no satellite of {args.sp3} can be interpolated: "
                           + "; ".join(skipped))
    if skipped:
        warn_caller(f"left out: {'; '.join(skipped)}", OrbitWarning)
    return satellites, span


def _sp3_satellite(args, data, name, points, hand):
    try:
        orbit = SP3Orbit(data, name, points=points)
    except ValueError as error:
        raise CommandError(f"--sp3: {one_line(error)}") from None
    if args.orbex is not None:
        attitude = read_input(QuaternionAttitude.from_orbex, args.orbex, "--orbex", name)
    else:
        attitude = NominalAttitude()
    return Satellite(orbit, attitude, polarization=hand, name=name)


def _target(args):
    """The target (a SkyCoord or a Satellite) and the default span of time (or None)."""
    satellite, natural = _given(args, _SATELLITE_OPTIONS), _given(args, _NATURAL_OPTIONS)
    if satellite and natural:
        raise CommandError(f"give one target: a natural source or a satellite, not both "
                           f"({', '.join(natural)} and {', '.join(satellite)})")
    if satellite:
        return _satellite(args)
    return natural_target(args), None


def _rows(count):
    return f"{count} row{'' if count == 1 else 's'}"


def _run_single(args):
    paths = table_outputs(args)
    catalogue = station_catalogue(args)
    antenna = parse_antenna(args.antenna, args, catalogue)
    min_elevation = elevation_limit(args)
    target, span = _target(args)
    times = time_span(args, default=span)
    if isinstance(target, list) and args.plot is not None:
        raise CommandError("--plot draws one satellite; choose it with --sat (e.g. --sat "
                           f"{target[0].name})")
    rows = times.size * (len(target) if isinstance(target, list) else 1)
    # One bar over the rows written: drawn at once (the table is computed at 0 %),
    # moved by each block of rows written.
    with progress_steps(show_progress(args), rows) as step:
        table = _single_table(args, antenna, target, times, min_elevation)
        write_table(table, paths, "feed_rotation", overwrite=args.overwrite, form=args.format,
                    step=step)
    wrote([args.output, args.plot], f"{_rows(len(table))} of the feed rotation of "
          f"{table.meta['antenna']} observing {table.meta['target']}")
    return 0


def _single_table(args, antenna, target, times, min_elevation):
    if isinstance(target, list):  # every satellite of an SP3 file
        tables = []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OrbitWarning)  # holes: NaN rows, as documented
            for satellite in target:
                one = feed_rotation_table(antenna, satellite, times,
                                          polarization=args.polarization,
                                          min_elevation=min_elevation)
                one.add_column([satellite.name] * len(one), name="prn", index=1)
                tables.append(one)
        table = vstack(tables, metadata_conflicts="silent")
        table = table[np.argsort(table["time"].jd, kind="stable")]  # by epoch, then PRN
        table.meta["target"] = ", ".join(satellite.name for satellite in target)
    else:
        table = feed_rotation_table(antenna, target, times, polarization=args.polarization,
                                    min_elevation=min_elevation)
        if getattr(args, "sp3", None) is not None:
            table.add_column([target.name] * len(table), name="prn", index=1)
    if getattr(args, "sp3", None) is not None:  # the GNSS name of the continuous total
        table.add_column(table["continuous"], name="windup",
                         index=table.colnames.index("continuous") + 1)
    if getattr(args, "units", None) is not None:
        in_units(table, args.units, _PHASE_COLUMNS)
    return table


def run_natural(args):
    return _run_single(args)


def run_satellite(args):
    if args.tle is None and args.sp3 is None:
        raise CommandError("give the satellite's orbit with --tle FILE or --sp3 FILE --sat NAME")
    return _run_single(args)


def run_baseline(args):
    paths = table_outputs(args)
    frequency = parse_quantity(args.frequency, u.MHz, "--frequency")
    catalogue = station_catalogue(args)
    first, second = (parse_antenna(name, args, catalogue) for name in args.antennas)
    min_elevation = elevation_limit(args)
    target, span = _target(args)
    times = time_span(args, default=span)
    with progress_steps(show_progress(args), times.size) as step:
        table = baseline_table(first, second, target, times, frequency,
                               polarization=args.polarization, min_elevation=min_elevation)
        in_units(table, args.units, [f"{antenna}_{name}" for antenna in table.meta["antennas"]
                                     for name in _PHASE_COLUMNS])
        write_table(table, paths, "baseline", overwrite=args.overwrite, form=args.format,
                    step=step)
    first, second = table.meta["antennas"]
    wrote([args.output, args.plot], f"{_rows(len(table))} of the feed rotation of {first} and "
          f"{second} observing {table.meta['target']}, and their rotation delay at "
          f"{table.meta['frequency']}")
    return 0
