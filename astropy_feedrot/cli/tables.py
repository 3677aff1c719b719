# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot natural``, ``feedrot satellite`` and ``feedrot baseline``: tables
of the feed rotation of one antenna, or of both antennas of a baseline with
their rotation delay, over a span of time."""

import argparse
import warnings

import numpy as np
from astropy import units as u
from astropy.table import vstack

from ..applied.feed_rotation_tables import baseline_table, feed_rotation_table
from ..core.exceptions import OrbitWarning, warn_caller
from ..core.outputs import CommandError
from ..io import read_sp3, read_tle
from ..transmitters.nominal_attitude import NominalAttitude
from ..transmitters.orbits import SP3Orbit, TLEOrbit
from ..transmitters.quaternion_attitude import QuaternionAttitude
from ..transmitters.satellite import Satellite
from ..transmitters.sp3_orbit import POSITION_TOLERANCE, points_needed
from .common import (
    ANTENNA_HELP,
    add_common_options,
    add_natural_options,
    add_time_options,
    add_units_option,
    elevation_limit,
    examples,
    in_units,
    natural_target,
    one_line,
    parse_antenna,
    parse_quantity,
    read_input,
    station_catalogue,
    table_outputs,
    time_span,
    write_table,
)

__all__ = ["EXAMPLES", "register"]

#: Examples of each command, one command line each (``--help`` prints them as they are;
#: the tests run each of them, with the sample files under the names they use).
EXAMPLES = {
    "natural": [
        'feedrot natural YEBES40M --source "03h19m48.16s +41d30m42.1s" '
        "--start 2023-01-25T18:00 --stop 2023-01-26T06:00 --step 10min",
        "feedrot natural EFLSBERG --ra 12:29:06.7 --dec +02:03:09 --start 2024-03-01 "
        "--stop 2024-03-02 -o 3c273.ecsv --plot 3c273.png",
        'feedrot natural 40.5247,-3.0869,988 --mount NASR --source "187.27d 2.05d" '
        "--start 2024-03-01T20:00 --stop 2024-03-01T22:00 --step 1min",
    ],
    "satellite": [
        "feedrot satellite DBR205 --tle gps.tle --sat 41328 --start 2023-01-25T06:00 "
        "--stop 2023-01-25T17:00 --step 30s --min-elevation 10",
        "feedrot satellite FD-VLBA --sp3 igs.sp3 --sat G01 --points 4 -o g01.fits",
        "feedrot satellite GGAO12M --sp3 igs.sp3 --points 4 --step 30s --units cycles "
        "-o all.ecsv",
    ],
    "baseline": [
        "feedrot baseline DBR205 FD-VLBA --tle gps.tle --start 2023-01-25T06:00 "
        "--stop 2023-01-25T17:00 --frequency 1575.42MHz --min-elevation 10",
        'feedrot baseline EFLSBERG YEBES40M --source "03h19m48.16s +41d30m42.1s" '
        "--start 2023-01-25T18:00 --stop 2023-01-26T06:00 --frequency 8.4GHz",
    ],
}


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


def _run_single(args):
    paths = table_outputs(args)
    catalogue = station_catalogue(args)
    antenna = parse_antenna(args.antenna, args, catalogue)
    min_elevation = elevation_limit(args)
    target, span = _target(args)
    times = time_span(args, default=span)
    if isinstance(target, list):  # every satellite of an SP3 file
        if args.plot is not None:
            raise CommandError("--plot draws one satellite; choose it with --sat (e.g. --sat "
                               f"{target[0].name})")
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
    write_table(table, paths, "feed_rotation", overwrite=args.overwrite, form=args.format)
    return 0


def _run_natural(args):
    return _run_single(args)


def _run_satellite(args):
    if args.tle is None and args.sp3 is None:
        raise CommandError("give the satellite's orbit with --tle FILE or --sp3 FILE --sat NAME")
    return _run_single(args)


def _run_baseline(args):
    paths = table_outputs(args)
    frequency = parse_quantity(args.frequency, u.MHz, "--frequency")
    catalogue = station_catalogue(args)
    first, second = (parse_antenna(name, args, catalogue) for name in args.antennas)
    min_elevation = elevation_limit(args)
    target, span = _target(args)
    times = time_span(args, default=span)
    table = baseline_table(first, second, target, times, frequency,
                           polarization=args.polarization, min_elevation=min_elevation)
    in_units(table, args.units, [f"{antenna}_{name}" for antenna in table.meta["antennas"]
                                 for name in _PHASE_COLUMNS])
    write_table(table, paths, "baseline", overwrite=args.overwrite, form=args.format)
    return 0


def _add_satellite_options(parser):
    group = parser.add_argument_group("satellite")
    group.add_argument("--tle", metavar="FILE", help="two- or three-line element file")
    group.add_argument("--sp3", metavar="FILE", help="IGS SP3 orbit file (nominal attitude "
                       "unless --orbex)")
    group.add_argument("--sat", metavar="NAME", help="satellite: SP3 name (G05), or TLE name or "
                       "catalogue number when the file has several; without it, every "
                       "satellite of an SP3 file (one row per epoch and satellite, column prn)")
    group.add_argument("--orbex", metavar="FILE", help="ORBEX attitude quaternions (with --sp3)")
    group.add_argument("--points", metavar="N", type=int,
                       help="epochs of the SP3 interpolation window (default 10, or all epochs "
                       "of a shorter file)")
    group.add_argument("--satellite-polarization", choices=("RCP", "LCP"), type=str.upper,
                       help="hand the satellite transmits (default RCP, as GNSS satellites)")


def register(commands):
    """Add ``natural``, ``satellite`` and ``baseline`` to the subparsers ``commands``."""
    natural = commands.add_parser(
        "natural", help="a natural radio source seen by one antenna",
        description="Feed rotation of one antenna observing a natural radio source.",
        epilog=examples(EXAMPLES["natural"]), formatter_class=argparse.RawDescriptionHelpFormatter)
    natural.add_argument("antenna", metavar="ANTENNA", help=ANTENNA_HELP)
    add_natural_options(natural)
    add_time_options(natural)
    add_common_options(natural)
    natural.set_defaults(run=_run_natural)

    satellite = commands.add_parser(
        "satellite", help="a satellite seen by one antenna",
        description="Feed rotation (wind-up) of one antenna observing a satellite, split into "
        "transmitter and receiver terms.",
        epilog=examples(EXAMPLES["satellite"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    satellite.add_argument("antenna", metavar="ANTENNA", help=ANTENNA_HELP)
    _add_satellite_options(satellite)
    add_units_option(satellite, "deg")
    add_time_options(satellite, required=False)
    add_common_options(satellite)
    satellite.set_defaults(run=_run_satellite)

    baseline = commands.add_parser(
        "baseline", help="both antennas of a baseline and the rotation delay",
        description="Feed rotation at both ends of a baseline and the rotation delay "
        "(antenna 2 minus antenna 1) at a frequency. The target is a natural source "
        "(--source or --ra/--dec) or a satellite (--tle or --sp3).",
        epilog=examples(EXAMPLES["baseline"]), formatter_class=argparse.RawDescriptionHelpFormatter)
    baseline.add_argument("antennas", metavar="ANTENNA", nargs=2, help=ANTENNA_HELP)
    baseline.add_argument("--frequency", required=True, metavar="FREQ",
                          help="observing frequency with a unit (1575.42MHz; plain: MHz)")
    add_natural_options(baseline)
    _add_satellite_options(baseline)
    add_units_option(baseline, "deg")
    add_time_options(baseline, required=False)
    add_common_options(baseline)
    baseline.set_defaults(run=_run_baseline)
