# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot rinex``: a copy of a RINEX observation file with the carrier-phase
wind-up removed from its phases (`astropy_feedrot.gnss.correct_rinex`)."""

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
from ..core.progress import progress_steps
from ..gnss import correct_rinex
from .common import in_units, parse_quantity, read_path, show_progress
from .shared import one_line

__all__ = ["run_rinex", "summary"]

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


def run_rinex(args):
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
                               overwrite=args.overwrite, progress=show_progress(args))
    except FileExistsError as error:
        raise CommandError(f"-o/--output: {one_line(error)}") from None
    except ImportError as error:
        raise CommandError(one_line(error)) from None
    if table is not None:
        windup = in_units(report.windup, args.units, ["windup"])
        with progress_steps(show_progress(args), len(windup)) as step:  # a second bar: rows
            write_files([(table, table_writer(windup, table_format(table), step))],
                        overwrite=args.overwrite)
    # The outputs named as given.
    named = " and ".join(str(path) for path in (args.output, args.table) if path is not None)
    print(f"feedrot: {named}: {summary(report)}", file=sys.stderr)
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
