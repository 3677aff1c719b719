# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot antennas`` and ``feedrot correct``: the antennas of a visibility
file as read, and a copy of the file with the feed rotation removed."""

import argparse
import sys

from ..outputs import (
    TABLE_FORMATS,
    CommandError,
    check_outputs,
    table_format,
    table_writer,
    write_files,
)
from ..visibility_files import antenna_table, correct_file, read_antennas
from .common import CELESTIAL_FRAMES, one_line

__all__ = ["register"]


def _run_antennas(args):
    paths = check_outputs([("-o/--output", args.output, tuple(TABLE_FORMATS))],
                          [("FILE", args.file)], args.overwrite)
    antennas, software = read_antennas(args.file, vertical=args.vertical)
    table = antenna_table(antennas, software)
    table.meta["file"] = str(args.file)
    table.meta["labels"] = software
    files = [] if paths[0] is None else [(paths[0], table_writer(table,
                                                                 table_format(paths[0])))]
    then = None if files else (lambda: table.write(sys.stdout, format="ascii.ecsv"))
    write_files(files, then)
    return 0


def _run_correct(args):
    try:
        correct_file(args.input, args.output, frame=args.frame, vertical=args.vertical,
                     overwrite=args.overwrite, progress=not args.quiet and sys.stderr.isatty())
    except FileExistsError as error:
        raise CommandError(f"-o/--output: {one_line(error)}") from None
    except ImportError as error:
        raise CommandError(one_line(error)) from None
    return 0


def register(commands):
    """Add ``antennas`` and ``correct`` to the subparsers ``commands``."""
    antennas = commands.add_parser(
        "antennas", help="the antennas of a visibility file, as read",
        description="The antennas of a visibility file (FITS-IDI, UVFITS, uvh5, Measurement "
        "Set, Miriad, SMA Mir) as read for the correction: number, name, ITRF position, "
        "mount label (in the file's convention), mount, focus, receptors and their angles.",
        epilog="examples:\n  feedrot antennas experiment.idifits\n"
        "  feedrot antennas vla.ms -o antennas.ecsv",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    antennas.add_argument("file", metavar="FILE", help="a visibility file or directory")
    antennas.add_argument("--vertical", choices=("geodetic", "geocentric"), default="geodetic",
                          help="the local vertical (geocentric reproduces CASA)")
    antennas.add_argument("-o", "--output", metavar="FILE",
                          help="write the table here (format of its extension) instead of "
                          "standard output")
    antennas.add_argument("--overwrite", action="store_true",
                          help="replace an existing output file")
    antennas.set_defaults(run=_run_antennas)

    correct = commands.add_parser(
        "correct", help="a copy of a visibility file with the feed rotation removed",
        description="Write a copy of a visibility file with the feed rotation removed from "
        "every visibility: FITS-IDI to FITS-IDI (memory-mapped), and every format pyuvdata "
        "reads to the format of the output's extension (.uvfits, .uvh5, .ms). The input is "
        "never modified.",
        epilog="examples:\n  feedrot correct vla.uvfits -o vla_corrected.uvfits\n"
        "  feedrot correct experiment.idifits -o corrected.idifits --frame icrs\n"
        "  feedrot correct alma.ms -o alma_corrected.ms --vertical geocentric",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    correct.add_argument("input", metavar="INPUT", help="a visibility file or directory")
    correct.add_argument("-o", "--output", required=True, metavar="OUTPUT",
                         help="the corrected copy")
    correct.add_argument("--frame", default="apparent", choices=("apparent",) + CELESTIAL_FRAMES,
                         help="north of the corrected polarization angles: the apparent pole "
                         "of date (default) or a catalogue frame such as icrs")
    correct.add_argument("--vertical", choices=("geodetic", "geocentric"), default="geodetic",
                         help="the local vertical (geocentric reproduces CASA)")
    correct.add_argument("--overwrite", action="store_true",
                         help="replace an existing output (never the input)")
    correct.add_argument("--quiet", action="store_true", help="no progress bar")
    correct.set_defaults(run=_run_correct)
