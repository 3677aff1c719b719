# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot antennas`` and ``feedrot correct``: the antennas of a visibility
file as read, and the feed rotation removed (or applied): a corrected copy of
any file, or a Measurement Set corrected in place."""

import argparse
import contextlib
import sys

from ..outputs import (
    TABLE_FORMATS,
    CommandError,
    check_outputs,
    table_format,
    table_writer,
    write_files,
)
from ..visibilities import (
    antenna_table,
    correct_file,
    correct_ms,
    file_kind,
    parse_feeds,
    read_antennas,
)
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


def _feeds(args):
    if args.feeds is None:
        return None
    try:
        return parse_feeds(args.feeds)
    except ValueError as error:
        raise CommandError(f"--feeds: {one_line(error)}") from None


@contextlib.contextmanager
def _client(args):
    """A dask.distributed client for --dask or --workers, or None."""
    if args.dask is None and args.workers is None:
        yield None
        return
    if args.dask is not None and args.workers is not None:
        raise CommandError("--dask and --workers exclude each other: connect to a scheduler, "
                           "or start a local cluster of N workers")
    if args.workers is not None and args.workers < 1:
        raise CommandError(f"--workers must be at least 1, got {args.workers}")
    try:
        import distributed  # optional: only --dask and --workers need it
    except ImportError:
        raise CommandError("--dask and --workers need dask.distributed: pip install "
                           "'astropy_feedrot[dask]'") from None
    if args.dask is not None:
        with distributed.Client(args.dask, timeout="20s") as client:
            yield client
        return
    with distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        yield client


def _run_correct(args):
    direction = "apply" if args.apply else "remove"
    progress = not args.quiet and sys.stderr.isatty()
    feeds = _feeds(args)
    if args.in_place:
        if args.output is not None:
            raise CommandError("-o/--output and --in-place exclude each other: a Measurement "
                               "Set is corrected in place, other files into a copy")
        if file_kind(args.input) != "ms":
            raise CommandError(f"--in-place: {args.input!r} is not a Measurement Set; other "
                               "files are corrected into a copy (-o OUTPUT)")
        try:
            with _client(args) as client:
                correct_ms(args.input, data_column=args.data_column,
                           corrected_column=args.column, direction=direction,
                           frame=args.frame, vertical=args.vertical, progress=progress,
                           feeds=feeds, redo=args.redo, pole=args.pole, client=client)
        except ImportError as error:
            raise CommandError(one_line(error)) from None
        return 0
    if args.output is None:
        raise CommandError("give -o/--output OUTPUT for the corrected copy, or --in-place "
                           "for a Measurement Set")
    for option, value in (("--data-column", args.data_column != "DATA"),
                          ("--column", args.column != "CORRECTED_DATA")):
        if value:
            raise CommandError(f"{option} is for a Measurement Set corrected --in-place")
    try:
        with _client(args) as client:
            correct_file(args.input, args.output, frame=args.frame, vertical=args.vertical,
                         overwrite=args.overwrite, progress=progress, direction=direction,
                         feeds=feeds, redo=args.redo, pole=args.pole, client=client)
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
        "correct", help="remove (or apply) the feed rotation of a visibility file",
        description="Remove the feed rotation from every visibility (or, with --apply, "
        "apply it to a model): into a copy, FITS-IDI to FITS-IDI (memory-mapped) and every "
        "format pyuvdata reads to the format of the output's extension (.uvfits, .uvh5, "
        ".ms), the input never modified; or a Measurement Set in place (--in-place), from "
        "one column into another (python-casacore), every other column left as it was.",
        epilog="examples:\n  feedrot correct vla.uvfits -o vla_corrected.uvfits\n"
        "  feedrot correct experiment.idifits -o corrected.idifits --frame icrs\n"
        "  feedrot correct obs.ms --in-place\n"
        "  feedrot correct obs.ms --in-place --data-column MODEL_DATA --column MODEL_DATA "
        "--apply\n"
        "  feedrot correct atca.uv -o atca.uvfits --feeds X,Y",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    correct.add_argument("input", metavar="INPUT", help="a visibility file or directory")
    correct.add_argument("-o", "--output", metavar="OUTPUT",
                         help="the corrected copy (not with --in-place)")
    correct.add_argument("--in-place", action="store_true",
                         help="correct a Measurement Set in place: read --data-column, write "
                         "--column")
    correct.add_argument("--data-column", default="DATA", metavar="COLUMN",
                         help="with --in-place: the column read (default DATA)")
    correct.add_argument("--column", default="CORRECTED_DATA", metavar="COLUMN",
                         help="with --in-place: the column written, created if missing "
                         "(default CORRECTED_DATA)")
    correct.add_argument("--apply", action="store_true",
                         help="apply the feed rotation (corrupt a sky model) instead of "
                         "removing it")
    correct.add_argument("--feeds", metavar="R,L|X,Y",
                         help="receptors for antennas the file gives none (ATCA Miriad, old "
                         "UVFITS): two letters with optional angles in degrees, e.g. "
                         "X:0,Y:90")
    correct.add_argument("--redo", action="store_true",
                         help="correct data whose history says they were corrected in the "
                         "same direction already")
    correct.add_argument("--frame", default="apparent", choices=("apparent",) + CELESTIAL_FRAMES,
                         help="north of the corrected polarization angles: the apparent pole "
                         "of date (default) or a catalogue frame such as icrs")
    correct.add_argument("--vertical", choices=("geodetic", "geocentric"), default="geodetic",
                         help="the local vertical (geocentric reproduces CASA)")
    correct.add_argument("--pole", choices=("itrs", "casa"), default="itrs",
                         help="the pole of the parallactic angle: the Earth-fixed z axis with "
                         "polar motion (default) or CASA's, without; --vertical geocentric "
                         "--pole casa reproduces CASA's applycal(parang=True)")
    correct.add_argument("--dask", metavar="SCHEDULER",
                         help="correct the chunks of a Measurement Set or FITS-IDI file on "
                         "the workers of this dask.distributed scheduler (its address)")
    correct.add_argument("--workers", type=int, metavar="N",
                         help="correct the chunks on a local dask cluster of N worker "
                         "processes")
    correct.add_argument("--overwrite", action="store_true",
                         help="replace an existing output (never the input)")
    correct.add_argument("--quiet", action="store_true", help="no progress bar")
    correct.set_defaults(run=_run_correct)
