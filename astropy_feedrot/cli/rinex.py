# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot rinex``: a copy of a RINEX observation file with the carrier-phase
wind-up removed from its phases (`astropy_feedrot.gnss.correct_rinex`)."""

import argparse
import re
import sys

import numpy as np
from astropy import units as u

from ..core.outputs import (
    TABLE_FORMATS,
    CommandError,
    check_outputs,
    table_format,
    table_writer,
    write_files,
)
from ..gnss import correct_rinex
from .common import add_units_option, examples, in_units, one_line, parse_quantity, read_path

__all__ = ["EXAMPLES", "register", "summary"]

#: Examples of ``feedrot rinex``, one command line each (the tests run them with the
#: package's GNSS samples under these names).
EXAMPLES = [
    "feedrot rinex obs.rnx --sp3 gnss.sp3 -o corrected.rnx",
    "feedrot rinex obs.rnx --sp3 gnss.sp3 -o out.rnx --table windup.ecsv --units deg",
]

# Compact RINEX names: written only as plain or gzip-compressed RINEX.
_COMPACT = re.compile(r"(\.crx|\.\d\dd)(\.gz)?$", re.IGNORECASE)


def _position(text):
    try:
        xyz = np.array([float(v) for v in text.split(",")])
    except ValueError:
        xyz = np.zeros(0)
    if xyz.shape != (3,):
        raise CommandError(f"--position: expected X,Y,Z in metres (ITRS), got {text!r}")
    return xyz


def _run_rinex(args):
    if _COMPACT.search(str(args.output)):
        raise CommandError(f"-o/--output: {args.output!r} names a Compact RINEX (Hatanaka) "
                           "file, which is not written; name it .rnx (or .rnx.gz) and "
                           "compress it with rnx2crx if needed")
    attitude = args.attitude
    if attitude == "orbex" and not args.orbex:
        raise CommandError("--attitude orbex needs --orbex FILE...")
    if args.orbex and attitude in ("nominal", "model"):
        raise CommandError("--orbex goes with --attitude orbex (the default when it is given)")
    if args.metadata is not None and attitude != "model":
        raise CommandError("--metadata goes with --attitude model")
    inputs = [("OBS", args.obs)] + [("--sp3", p) for p in args.sp3] + [
        ("--orbex", p) for p in args.orbex or []] + [
        ("--metadata", p) for p in [args.metadata] if p is not None]
    for option, path in inputs:
        read_path(path, option)
    table = check_outputs([("-o/--output", args.output, None),
                           ("--table", args.table, tuple(TABLE_FORMATS))], inputs,
                          args.overwrite)[1]
    max_gap = parse_quantity(args.max_gap, u.s, "--max-gap")
    try:
        report = correct_rinex(args.obs, args.output, args.sp3, orbex=args.orbex,
                               attitude=attitude, max_gap=max_gap, points=args.points,
                               position=None if args.position is None else
                               _position(args.position),
                               form=args.form, table=table is not None,
                               metadata=args.metadata,
                               overwrite=args.overwrite)
    except FileExistsError as error:
        raise CommandError(f"-o/--output: {one_line(error)}") from None
    except ImportError as error:
        raise CommandError(one_line(error)) from None
    if table is not None:
        windup = in_units(report.windup, args.units, ["windup"])
        write_files([(table, table_writer(windup, table_format(table)))],
                    overwrite=args.overwrite)
    print(f"feedrot: {report.output}: {summary(report)}", file=sys.stderr)
    return 0


def _count(n, what):
    return f"{n} {what}{'' if n == 1 else 's'}"


def summary(report):
    """The summary line of a `~astropy_feedrot.gnss.RinexCorrection`.

    Examples
    --------
    >>> from astropy_feedrot.gnss import RinexCorrection
    >>> from astropy_feedrot.cli.rinex import summary
    >>> summary(RinexCorrection("out.rnx", 2, 6, 12, 1, {"G07": "not in the SP3 files"},
    ...                         None, 1, 0))
    '12 carrier phases of 6 observations at 2 epochs corrected, 1 arc, 1 epoch untouched, \
1 satellite untouched'
    """
    parts = [f"{_count(report.phases, 'carrier phase')} of "
             f"{_count(report.observations, 'observation')} at {_count(report.epochs, 'epoch')} "
             f"corrected", _count(report.arcs, "arc")]
    if report.extrapolated_epochs:
        parts.append(f"{_count(report.extrapolated_epochs, 'epoch')} of orbits extrapolated")
    parts.append(f"{_count(report.untouched_epochs, 'epoch')} untouched")
    if report.untouched:
        parts.append(f"{_count(len(report.untouched), 'satellite')} untouched")
    return ", ".join(parts)


def register(commands):
    """Add ``rinex`` to the subparsers ``commands``."""
    rinex = commands.add_parser(
        "rinex", help="a copy of a RINEX observation file with the phase wind-up removed",
        description="Write a copy of a RINEX observation file (2.11, 3.0x, 4.0x; plain, gzip "
        "or Hatanaka-compressed) with the carrier-phase wind-up of every satellite (GPS, "
        "GLONASS, Galileo, BeiDou, QZSS, NavIC; PRNs as G05, E11) subtracted from every "
        "carrier phase (L) of it: the RHCP wind-up in cycles, the same at every frequency "
        "(L_corrected = L - windup), continuous along each satellite's arc through loss-of-"
        "lock flags (a new arc only after a gap longer than --max-gap), the receiver turned "
        "by the header's ANTENNA: ZERODIR AZI (and by events that change it). Every other "
        "byte of the file is kept; two COMMENT lines say what was applied. Epochs up to one "
        "SP3 interval (900 s at most) beyond the SP3 files get extrapolated orbits; further "
        "ones, and satellites without an orbit or attitude, are left untouched and counted.",
        epilog=examples(EXAMPLES),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    rinex.add_argument("obs", metavar="OBS", help="the RINEX observation file")
    rinex.add_argument("--sp3", nargs="+", required=True, metavar="SP3",
                       help="SP3 orbit files covering the observations (days are joined)")
    rinex.add_argument("--orbex", nargs="+", metavar="OBX",
                       help="ORBEX attitude files (then --attitude orbex is the default)")
    rinex.add_argument("--attitude", choices=("nominal", "model", "orbex"),
                       help="transmitter attitude: nominal yaw steering (default without "
                       "--orbex), the yaw model of each satellite's block through noon and "
                       "midnight turns and shadows, or the ORBEX quaternions")
    rinex.add_argument("--metadata", metavar="SNX",
                       help="IGS satellite metadata SINEX file for --attitude model (default: "
                       "the shipped copy, release 2404)")
    rinex.add_argument("-o", "--output", required=True, metavar="OUT",
                       help="the corrected copy (.gz: gzip-compressed); never the input")
    rinex.add_argument("--max-gap", default="300s", metavar="DURATION",
                       help="a longer gap starts a new arc (default 300s; compared with a "
                       "tolerance of half the sampling interval)")
    rinex.add_argument("--points", type=int, metavar="N",
                       help="points of the orbit interpolation (default 10); fewer than the "
                       "orbits' sampling needs for 1e-4 cycle (7 at 15 min, 5 at 5 min for "
                       "GPS) are refused")
    rinex.add_argument("--position", metavar="X,Y,Z",
                       help="the antenna's ITRS position in metres (default APPROX POSITION "
                       "XYZ of the header)")
    rinex.add_argument("--form", choices=("beyerle", "wu"), default="beyerle",
                       help="wind-up form: Eq 30 crossed dipoles (default) or Eq 31 effective "
                       "dipoles (as RTKLIB)")
    rinex.add_argument("--table", metavar="FILE",
                       help="also write the wind-up removed, one row per epoch and satellite "
                       "(time, prn, windup), in the format of the extension")
    add_units_option(rinex, "cycles")
    rinex.add_argument("--overwrite", action="store_true",
                       help="replace existing outputs (never the input)")
    rinex.set_defaults(run=_run_rinex)
