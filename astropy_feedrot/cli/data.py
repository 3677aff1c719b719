# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot antennas`` and ``feedrot correct``: the antennas of a visibility
file as read, and the feed rotation removed (or applied): a corrected copy of
any file, or a Measurement Set corrected in place."""

import argparse
import contextlib
import os
import shutil
import sys
import tempfile
from pathlib import Path

from ..core.extras import install_hint
from ..core.outputs import (
    TABLE_FORMATS,
    CommandError,
    check_outputs,
    publish,
    same_file,
    table_format,
    table_writer,
    write_files,
)
from ..visibilities import (
    MOUNTS,
    CorrectionRefused,
    antenna_table,
    check_output_format,
    correct_file,
    correct_ms,
    file_kind,
    parse_feeds,
    read_antennas,
)
from ..visibilities.poles import CONVENTIONS, convention_options
from .common import CELESTIAL_FRAMES, examples, one_line

__all__ = ["EXAMPLES", "check_correct_output", "register"]

#: Examples of ``feedrot antennas`` and ``feedrot correct``, one command line each.
EXAMPLES = {
    "antennas": ["feedrot antennas experiment.idifits",
                 "feedrot antennas vla.ms -o antennas.ecsv",
                 "feedrot antennas vla.uvfits --mounts catalogue"],
    "correct": ["feedrot correct vla.uvfits -o vla_corrected.uvfits",
                "feedrot correct experiment.idifits -o corrected.idifits --frame icrs",
                "feedrot correct vla.ms -o vla_corrected.ms --vertical geocentric",
                "feedrot correct vla.ms --in-place",
                "feedrot correct vla.ms --in-place --column MODEL_DATA --apply",
                "feedrot correct vla.uvfits -o vla_given.uvfits --feeds R,L",
                "feedrot correct vla.uvfits -o vla_catalogue.uvfits --mounts catalogue",
                "feedrot correct vla.ms --in-place --convention casa --workers 2"],
}


#: The help of ``--mounts``.
MOUNTS_HELP = ("whose mount and focus an antenna within 100 m of a station of the catalogue "
               "takes where the two differ (said in a warning): the file's (default; many "
               "writers put MNTSTA 0, alt-az, for every antenna) or the catalogue's, which "
               "also gives its mount to an antenna whose MOUNT is empty or unknown")


def _run_antennas(args):
    paths = check_outputs([("-o/--output", args.output, tuple(TABLE_FORMATS))],
                          [("FILE", args.file)], args.overwrite)
    antennas, software = read_antennas(args.file, vertical=args.vertical, mounts=args.mounts)
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
    (`~astropy_feedrot.visibilities.check_output_format`).
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
        raise CommandError("--dask and --workers need dask.distributed: "
                           + install_hint("dask", "'dask[distributed]'")) from None
    if args.dask is not None:
        with distributed.Client(args.dask, timeout="20s") as client:
            yield client
        return
    with distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        yield client


def _run_in_place(args, options):
    if args.output is not None:
        raise CommandError("-o/--output and --in-place exclude each other: a Measurement "
                           "Set is corrected in place, other files into a copy")
    try:
        kind = file_kind(args.input)
    except (OSError, ValueError) as error:
        raise CommandError(f"INPUT: {one_line(error)}") from None
    if kind != "ms":
        raise CommandError(f"--in-place: {args.input!r} is not a Measurement Set; other "
                           "files are corrected into a copy (-o OUTPUT)")
    try:
        with _client(args) as client:
            correct_ms(args.input, client=client, **_columns(args), **options)
    except ImportError as error:
        raise CommandError(one_line(error)) from None
    except CorrectionRefused as error:  # in the command line's words (--redo)
        raise CommandError(one_line(error.command_line())) from None
    source = args.data_column or (args.column if args.apply and args.column else "DATA")
    _summary(args, args.input, f"in place, {source} -> {args.column or 'CORRECTED_DATA'}")
    return 0


def _summary(args, path, what):
    """One line on standard error (as feedrot rinex gives) saying what was written,
    with the conventions used; none with --quiet."""
    if args.quiet:
        return
    done = "applied" if args.apply else "removed"
    print(f"feedrot: {path}: feed rotation {done} {what} ({args.convention} convention: "
          f"vertical {args.vertical}, pole {args.pole}; frame {args.frame})", file=sys.stderr)


def _columns(args):
    """The columns of a Measurement Set read and written (--data-column, --column)."""
    return dict(data_column=args.data_column, corrected_column=args.column or "CORRECTED_DATA",
                overwrite_column=args.overwrite_column)


def _run_correct(args):
    args.vertical, args.pole = convention_options(args.convention, args.vertical, args.pole)
    options = dict(direction="apply" if args.apply else "remove", frame=args.frame,
                   vertical=args.vertical, progress=not args.quiet and sys.stderr.isatty(),
                   feeds=_feeds(args), redo=args.redo, pole=args.pole, mounts=args.mounts)
    if args.in_place:
        return _run_in_place(args, options)
    if args.output is None:
        raise CommandError("give -o/--output OUTPUT for the corrected copy, or --in-place "
                           "for a Measurement Set")
    target = check_correct_output(args.input, args.output, args.overwrite)
    columns = {}
    if file_kind(args.input) == "ms" and target.suffix.lower() == ".ms":
        columns = _columns(args)
    else:
        for option, value in (("--data-column", args.data_column is not None),
                              ("--column", args.column is not None),
                              ("--overwrite-column", args.overwrite_column)):
            if value:
                raise CommandError(f"{option} is for a Measurement Set, corrected --in-place "
                                   "or into a Measurement Set copy (-o OUTPUT.ms)")
    # Corrected into a directory of its own beside the target, then published in one
    # step: exclusively unless --overwrite, so two runs into one name cannot both succeed.
    work = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}."))
    try:
        temporary = work / target.name
        try:
            with _client(args) as client:
                correct_file(args.input, temporary, client=client, **columns, **options)
        except ImportError as error:
            raise CommandError(one_line(error)) from None
        except CorrectionRefused as error:  # in the command line's words (--redo)
            raise CommandError(one_line(error.command_line())) from None
        try:
            publish(temporary, target, overwrite=args.overwrite)
        except FileExistsError as error:
            raise CommandError(f"-o/--output: {one_line(error)}; add --overwrite to replace "
                               "it") from None
    finally:
        with contextlib.suppress(OSError):
            shutil.rmtree(work)
    _summary(args, args.output, f"from {args.input}")
    return 0


def register(commands):
    """Add ``antennas`` and ``correct`` to the subparsers ``commands``."""
    antennas = commands.add_parser(
        "antennas", help="the antennas of a visibility file, as read",
        description="The antennas of a visibility file (FITS-IDI, UVFITS, uvh5, Measurement "
        "Set, Miriad, SMA Mir) as read for the correction: number, name, ITRF position, "
        "mount label (in the file's convention), mount, focus, receptors and their angles, "
        "the station catalogue's station within 100 m with its mount and focus, and what "
        "keeps an antenna from being corrected as the file gives it (an orbiting antenna, a "
        "mount without a model, receptors that cannot be used, a mount that differs from "
        "the catalogue's).",
        epilog=examples(EXAMPLES["antennas"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    antennas.add_argument("file", metavar="FILE", help="a visibility file or directory")
    antennas.add_argument("--vertical", choices=("geodetic", "geocentric"), default="geodetic",
                          help="the local vertical (geocentric reproduces CASA)")
    antennas.add_argument("--mounts", choices=MOUNTS, default="file", help=MOUNTS_HELP)
    antennas.add_argument("-o", "--output", metavar="FILE",
                          help="write the table here (format of its extension) instead of "
                          "standard output")
    antennas.add_argument("--overwrite", action="store_true",
                          help="replace an existing output file")
    antennas.set_defaults(run=_run_antennas)

    correct = commands.add_parser(
        "correct", help="remove (or apply) the feed rotation of a visibility file",
        description="Remove the feed rotation from every visibility (or, with --apply, "
        "apply it to a model): into a copy, FITS-IDI to FITS-IDI (a chunk at a time), a "
        "Measurement Set to .ms as a casacore copy corrected as --in-place would, and every "
        "format pyuvdata reads to the format of the output's extension (.uvfits, .uvh5, "
        ".ms; .fits is the input's kind), the input never modified; or a Measurement Set "
        "in place (--in-place), from one column into another (python-casacore), every other "
        "column left as it was. Data whose history says they were corrected already (by "
        "feedrot, AIPS CLCOR PANG or CASA applycal parang=True) are refused without --redo, "
        "and columns feedrot did not write without --overwrite-column.",
        epilog=examples(EXAMPLES["correct"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    correct.add_argument("input", metavar="INPUT", help="a visibility file or directory")
    correct.add_argument("-o", "--output", metavar="OUTPUT",
                         help="the corrected copy (not with --in-place)")
    correct.add_argument("--in-place", action="store_true",
                         help="correct a Measurement Set in place: read --data-column, write "
                         "--column")
    correct.add_argument("--data-column", metavar="COLUMN",
                         help="Measurement Sets: the column read (default DATA; with --apply, "
                         "--column itself: a model corrupted in place)")
    correct.add_argument("--column", metavar="COLUMN",
                         help="Measurement Sets (--in-place, or -o OUTPUT.ms: a casacore copy "
                         "corrected in place): the visibility column written, created if "
                         "missing (default CORRECTED_DATA)")
    correct.add_argument("--overwrite-column", action="store_true",
                         help="write into an existing column that feedrot did not write "
                         "(MODEL_DATA, a CORRECTED_DATA that CASA filled): its values are "
                         "replaced")
    correct.add_argument("--apply", action="store_true",
                         help="apply the feed rotation (corrupt a sky model) instead of "
                         "removing it")
    correct.add_argument("--feeds", metavar="R,L|X,Y",
                         help="receptors for antennas the file gives none (ATCA Miriad, old "
                         "UVFITS) or unusable ones (linear dipoles both at angle 0, as LWA and "
                         "PAPER Measurement Sets give): two letters with optional angles in "
                         "degrees, e.g. X:0,Y:90; without it, antennas without receptors take "
                         "the station catalogue's where it states them: for the station of "
                         "their name within 100 m, else for the pad within 5 m, else for every "
                         "station of the file's telescope alike (said in a warning); antennas "
                         "with unusable ones are refused, named")
    correct.add_argument("--mounts", choices=MOUNTS, default="file", help=MOUNTS_HELP)
    correct.add_argument("--redo", action="store_true",
                         help="correct data whose history says they were corrected in the "
                         "same direction already (by feedrot, by AIPS CLCOR PANG, by CASA "
                         "applycal parang=True), or recompute a column that holds this "
                         "correction already")
    correct.add_argument("--frame", default="apparent", choices=("apparent",) + CELESTIAL_FRAMES,
                         help="north of the corrected polarization angles: the pole of date "
                         "(default, as in Python, CASA and AIPS) or a catalogue frame such "
                         "as icrs")
    correct.add_argument("--convention", choices=tuple(CONVENTIONS), default="rigorous",
                         help="rigorous (default: the geodetic vertical and the Earth-fixed "
                         "pole) or casa (CASA's applycal(parang=True): the geocentric vertical "
                         "and the pole of date); --vertical and --pole replace its choices")
    correct.add_argument("--vertical", choices=("geodetic", "geocentric"),
                         help="the local vertical (default: the convention's; geocentric "
                         "reproduces CASA)")
    correct.add_argument("--pole", choices=("itrs", "casa"),
                         help="the pole of the parallactic angle: the Earth-fixed z axis with "
                         "polar motion or CASA's, without (default: the convention's)")
    correct.add_argument("--dask", metavar="SCHEDULER",
                         help="correct the chunks of a Measurement Set or FITS-IDI file on "
                         "the workers of this dask.distributed scheduler (its address)")
    correct.add_argument("--workers", type=int, metavar="N",
                         help="correct the chunks on a local dask cluster of N worker "
                         "processes")
    correct.add_argument("--overwrite", action="store_true",
                         help="replace an existing output (never the input)")
    correct.add_argument("--quiet", action="store_true",
                         help="no progress bar, and no summary line on success")
    correct.set_defaults(run=_run_correct)
