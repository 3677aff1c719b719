# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot antennas`` and ``feedrot correct``: the antennas of a visibility
file as read, and a copy of the file with the feed rotation removed."""

import argparse
import contextlib
import os
import shutil
import sys
import tempfile
from pathlib import Path

from ..outputs import (
    TABLE_FORMATS,
    CommandError,
    check_outputs,
    publish,
    same_file,
    table_format,
    table_writer,
    write_files,
)
from ..visibility_files import (
    antenna_table,
    check_output_format,
    correct_file,
    file_kind,
    read_antennas,
)
from .common import CELESTIAL_FRAMES, examples, one_line

__all__ = ["EXAMPLES", "check_correct_output", "register"]

#: Examples of ``feedrot antennas`` and ``feedrot correct``, one command line each.
EXAMPLES = {
    "antennas": ["feedrot antennas experiment.idifits",
                 "feedrot antennas vla.ms -o antennas.ecsv"],
    "correct": ["feedrot correct vla.uvfits -o vla_corrected.uvfits",
                "feedrot correct experiment.idifits -o corrected.idifits --frame icrs",
                "feedrot correct vla.ms -o vla_corrected.ms --vertical geocentric"],
}


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
    write_files(files, then, overwrite=args.overwrite)
    return 0


def check_correct_output(source, output, overwrite):
    """The resolved output of ``feedrot correct``, checked against the input before any work.

    The output's extension must name the format written
    (`~astropy_feedrot.visibility_files.check_output_format`).
    """
    try:
        kind = file_kind(source)
    except (OSError, ValueError) as error:
        raise CommandError(f"INPUT: {one_line(error)}") from None
    try:
        check_output_format(kind, output)
    except ValueError as error:
        raise CommandError(f"-o/--output: {one_line(error)}") from None
    given = Path(output).expanduser()
    target = given.resolve()
    if same_file(target, Path(source).expanduser().resolve()):
        raise CommandError(f"-o/--output: {output!r} is the INPUT, which is never modified; "
                           "choose another name")
    if not target.parent.is_dir():
        raise CommandError(f"-o/--output: cannot write {output!r}: directory "
                           f"{str(target.parent)!r} does not exist")
    if (target.exists() or target.is_symlink()) and not overwrite:
        raise CommandError(f"-o/--output: {output!r} exists; add --overwrite to replace it, "
                           "or choose another name")
    if not os.access(target.parent, os.W_OK | os.X_OK):
        raise CommandError(f"-o/--output: cannot write {output!r}: permission denied in "
                           f"{str(target.parent)!r}")
    return target


def _run_correct(args):
    target = check_correct_output(args.input, args.output, args.overwrite)
    # Corrected into a directory of its own beside the target, then published in one
    # step: exclusively unless --overwrite, so two runs into one name cannot both succeed.
    work = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}."))
    try:
        temporary = work / target.name
        try:
            correct_file(args.input, temporary, frame=args.frame, vertical=args.vertical,
                         progress=not args.quiet and sys.stderr.isatty())
        except ImportError as error:
            raise CommandError(one_line(error)) from None
        try:
            publish(temporary, target, overwrite=args.overwrite)
        except FileExistsError as error:
            raise CommandError(f"-o/--output: {one_line(error)}; add --overwrite to replace "
                               "it") from None
    finally:
        with contextlib.suppress(OSError):
            shutil.rmtree(work)
    return 0


def register(commands):
    """Add ``antennas`` and ``correct`` to the subparsers ``commands``."""
    antennas = commands.add_parser(
        "antennas", help="the antennas of a visibility file, as read",
        description="The antennas of a visibility file (FITS-IDI, UVFITS, uvh5, Measurement "
        "Set, Miriad, SMA Mir) as read for the correction: number, name, ITRF position, "
        "mount label (in the file's convention), mount, focus, receptors and their angles.",
        epilog=examples(EXAMPLES["antennas"]),
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
        epilog=examples(EXAMPLES["correct"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    correct.add_argument("input", metavar="INPUT", help="a visibility file or directory")
    correct.add_argument("-o", "--output", required=True, metavar="OUTPUT",
                         help="the corrected copy")
    correct.add_argument("--frame", default="apparent", choices=("apparent",) + CELESTIAL_FRAMES,
                         help="north of the corrected polarization angles: the pole of date "
                         "(default, as in Python, CASA and AIPS) or a catalogue frame such "
                         "as icrs")
    correct.add_argument("--vertical", choices=("geodetic", "geocentric"), default="geodetic",
                         help="the local vertical (geocentric reproduces CASA)")
    correct.add_argument("--overwrite", action="store_true",
                         help="replace an existing output (never the input)")
    correct.add_argument("--quiet", action="store_true", help="no progress bar")
    correct.set_defaults(run=_run_correct)
