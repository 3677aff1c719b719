# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot antennas`` and ``feedrot correct``: the antennas of a visibility
file as read, and the feed rotation removed (or applied): a corrected copy of
any file, or a Measurement Set corrected in place."""

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
    CorrectionRefused,
    antenna_table,
    check_output_format,
    correct_file,
    correct_ms,
    correct_processing_set,
    file_kind,
    parse_feeds,
    read_antennas,
)
from ..ionosphere import IonosphereError
from ..visibilities.msv4 import data_groups
from ..visibilities.poles import convention_options
from .archives import run_correct_files
from .common import wrote
from .faraday import ionosphere_option
from .shared import one_line

__all__ = ["run_antennas", "run_correct", "check_correct_output"]


def run_antennas(args):
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
    count = len(table)
    wrote([args.output], f"{count} antenna{'s' if count != 1 else ''} of {args.file}, as read")
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
    if kind == "msv4":
        return _run_processing_set(args, options)
    if kind != "ms":
        raise CommandError(f"--in-place: {args.input!r} is neither a Measurement Set nor an "
                           "MSv4 processing set; other files are corrected into a copy "
                           "(-o OUTPUT)")
    try:
        with _client(args) as client, _ionosphere_errors(args):
            correct_ms(args.input, client=client, **_columns(args), **options)
    except ImportError as error:
        raise CommandError(one_line(error)) from None
    except CorrectionRefused as error:  # in the command line's words (--redo)
        raise CommandError(one_line(error.command_line())) from None
    source = args.data_column or (args.column if args.apply and args.column else "DATA")
    _summary(args, args.input, f"in place, {source} -> {args.column or 'CORRECTED_DATA'}")
    return 0


def _run_processing_set(args, options):
    """An MSv4 processing set, in place: a new data group in every partition."""
    for option, value in (("--data-column", args.data_column is not None),
                          ("--column", args.column is not None),
                          ("--overwrite-column", args.overwrite_column)):
        if value:
            raise CommandError(f"{option} is for Measurement Sets v2; a processing set gains "
                               "the data group 'corrected' (VISIBILITY_CORRECTED; with "
                               "--apply, 'model_corrupted')")
    options = {k: v for k, v in options.items() if k != "progress"}
    try:
        source, new, variable = data_groups(options["direction"], args.data_group, args.group)
        # The graph is computed on the active scheduler: the cluster's with --dask or
        # --workers, dask's threads otherwise.
        with _client(args), _ionosphere_errors(args):
            correct_processing_set(args.input, data_group=source, new_group=new, write=True,
                                   **options)
    except ImportError as error:
        raise CommandError(one_line(error)) from None
    except CorrectionRefused as error:  # in the command line's words (--redo)
        raise CommandError(one_line(error.command_line())) from None
    except ValueError as error:
        raise CommandError(one_line(str(error).replace("new_group=, ", "")
                                    .replace("new_group", "--group"))) from None
    _summary(args, args.input, f"in place, data group {source} -> {new} ({variable})")
    return 0


def _summary(args, path, what):
    """One line on standard error (as feedrot rinex gives) saying what was written,
    with the conventions used; none with --quiet."""
    if args.quiet:
        return
    done = "applied" if args.apply else "removed"
    faraday = "" if args.ionex is None and args.rm_table is None else \
        " and ionospheric Faraday rotation"
    print(f"feedrot: {path}: feed rotation{faraday} {done} {what} ({args.convention} convention: "
          f"vertical {args.vertical}, pole {args.pole}; frame {args.frame})", file=sys.stderr)


def _columns(args):
    """The columns of a Measurement Set read and written (--data-column, --column)."""
    return dict(data_column=args.data_column, corrected_column=args.column or "CORRECTED_DATA",
                overwrite_column=args.overwrite_column)


@contextlib.contextmanager
def _ionosphere_errors(args):
    """An ionosphere that does not cover the data (or lacks an antenna) as one line naming
    the option that gave it."""
    try:
        yield
    except IonosphereError as error:
        option = "--ionex" if args.ionex is not None else "--rm-table"
        raise CommandError(f"{option}: {one_line(error)}") from None


def _kind(path):
    try:
        return file_kind(path)
    except (OSError, ValueError):
        return None  # said where the input is read


def _many(args):
    """Whether the command corrects an archive: several inputs, or -o naming a
    directory (a trailing separator)."""
    if len(args.input) > 1:
        return True
    return args.output is not None and args.output.endswith(("/", os.sep))


def run_correct(args):
    args.vertical, args.pole = convention_options(args.convention, args.vertical, args.pole)
    many = _many(args)
    if not many:
        args.input = args.input[0]
    for option, value in (("--data-group", args.data_group), ("--group", args.group)):
        if value is not None and (many or _kind(args.input) != "msv4"):
            raise CommandError(f"{option} is for one MSv4 processing set, corrected in "
                               "place; a Measurement Set is read from --data-column into "
                               "--column")
    ionosphere = None
    if args.ionex is not None or args.rm_table is not None:  # before any work
        ionosphere, _ = ionosphere_option(args)
    options = dict(direction="apply" if args.apply else "remove", frame=args.frame,
                   vertical=args.vertical, progress=not args.quiet and sys.stderr.isatty(),
                   feeds=_feeds(args), redo=args.redo, pole=args.pole, mounts=args.mounts,
                   ionosphere=ionosphere)
    if many:
        with _client(args) as client, _ionosphere_errors(args):
            return run_correct_files(args, options, client)
    if args.in_place or (args.output is None and _kind(args.input) == "msv4"):
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
            with _client(args) as client, _ionosphere_errors(args):
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
