# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ``feedrot`` command line.

``feedrot natural``, ``feedrot satellite`` and ``feedrot baseline`` tabulate
feed rotation over a span of time (ECSV on standard output, or a file whose
format follows its extension, and optionally a figure); ``feedrot demo`` runs
the paper's Section 4.1 simulation on embedded data; ``feedrot stations``
lists the station catalogue (``--network``, ``--mount``); ``feedrot
coverage`` tabulates the range of feed rotation that candidate polarization
calibrators offer a network. ``feedrot antennas`` lists the antennas of a
visibility file as read, and ``feedrot correct`` writes a copy of a
visibility file with the feed rotation removed, or corrects a Measurement Set
in place (see `astropy_feedrot.visibilities`). ``feedrot rinex`` writes a copy
of a RINEX observation file with the carrier-phase wind-up removed (see
`astropy_feedrot.gnss`).

Each family of commands is a module of this package (``tables``, ``demo``,
``stations``, ``coverage``, ``data``) with a ``register(commands)`` that adds
its subparsers; what they share is in ``common``.

Every error is one line on standard error and a non-zero exit status. No file
is lost: every output is checked before any work is done (format, directory,
an existing file needs ``--overwrite``, never one of the inputs, never the
table and the figure in one file), written to a temporary file beside its
target and renamed into place once everything has been written.

May import: every subpackage (``core``, ``io``, ``earth``, ``antennas``,
``transmitters``, ``ionosphere``, ``engine``, ``stations``, ``applied``,
``visibilities``, ``gnss``); it is the top layer.
"""

import argparse
import contextlib
import os
import sys
import warnings

from astropy import units as u

from ..core.outputs import TABLE_FORMATS, CommandError
from ..core.version import version as __version__
from ..earth.eop import iers_context
from ..io import FileFormatError
from . import coverage, data, demo, rinex, samples, stations, tables
from .common import CELESTIAL_FRAMES, MAX_EPOCHS, Parser, UsageError, examples, one_line

__all__ = ["main", "build_parser", "CommandError", "MAX_EPOCHS", "TABLE_FORMATS",
           "CELESTIAL_FRAMES"]


def build_parser():
    """The argument parser of ``feedrot``, with every command family registered."""
    parser = Parser(
        prog="feedrot",
        description="Feed rotation (parallactic angle, carrier-phase wind-up) of radio "
        "telescopes and GNSS antennas, as tables: time, azimuth, elevation, parallactic "
        "angle, transmitter and receiver terms, total and continuous total (degrees), and "
        "the rate of the feed rotation (deg/s).",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=examples(["feedrot demo", "feedrot stations"]
                        + [lines[0] for lines in tables.EXAMPLES.values()]
                        + [coverage.EXAMPLES[1], data.EXAMPLES["antennas"][0],
                           data.EXAMPLES["correct"][0], rinex.EXAMPLES[0]])
        + "\n\n'feedrot COMMAND --help' shows each command's options and more examples; "
        "'feedrot samples' lists the sample files shipped with the package.",
    )
    parser.add_argument("--version", action="version", version=f"feedrot {__version__}",
                        help="show the version of astropy_feedrot and exit")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")

    for family in (tables, demo, stations, coverage, data, rinex, samples):
        family.register(commands)
    return parser


def _protect_sites(argv):
    # A southern or western site such as -33.0,148.26,415 (or a place such as
    # --near's -3.09,40.52) would look like an option to argparse; a leading
    # space keeps it a value.
    return [f" {arg}" if arg.startswith("-") and not arg.startswith("--")
            and 1 <= arg.count(",") <= 2 else arg for arg in argv]


def _warning_printer():
    """A ``warnings.showwarning`` that prints each distinct warning once, on one line.

    (pyuvdata gives its uvw warning once on reading and again on writing.)
    """
    shown = set()

    def show(message, category, filename, lineno, file=None, line=None):
        text = one_line(message)
        if text not in shown:
            shown.add(text)
            print(f"feedrot: warning: {text}", file=sys.stderr)
    return show


def _run(args):
    """Run a parsed command: its exit status, and any error as one line on stderr."""
    try:
        status = args.run(args)
        sys.stdout.flush()
        return status
    except (CommandError, FileFormatError, ValueError, TypeError, KeyError, OSError,
            u.UnitsError) as error:
        if isinstance(error, BrokenPipeError):
            # The reader of standard output has gone (feedrot ... | head): stop quietly.
            with contextlib.suppress(OSError, ValueError):
                os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            return 1
        message = error.args[0] if isinstance(error, KeyError) and error.args else error
        print(f"feedrot: error: {one_line(message)}", file=sys.stderr)
        return 1
    except ImportError as error:
        # An optional dependency that is not installed: the message names the extra.
        print(f"feedrot: error: {one_line(error)}", file=sys.stderr)
        return 1
    except MemoryError:
        print("feedrot: error: out of memory; use fewer epochs (a larger --step or a shorter "
              "span)", file=sys.stderr)
        return 1
    except KeyboardInterrupt as error:
        # Long corrections say what an interruption left behind.
        detail = f": {one_line(error)}" if error.args else ""
        print(f"feedrot: interrupted{detail}", file=sys.stderr)
        return 130
    except Exception as error:
        print(f"feedrot: error: internal error ({type(error).__name__}: {one_line(error)}); "
              "please report it with the command line", file=sys.stderr)
        return 1


def main(argv=None):
    """Run the ``feedrot`` command line.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status: 0 on success, 1 for bad input or a failed
        computation, 2 for a command line that does not parse, 130 when
        interrupted. Every error is one line on standard error.

    Examples
    --------
    >>> from astropy_feedrot.cli import main
    >>> main(["natural", "EFLSBERG", "--source", "03h19m48.16s +41d30m42.1s",
    ...       "--start", "2023-01-25T18:00", "--stop", "2023-01-25T19:00",
    ...       "--step", "1h"])  # doctest: +ELLIPSIS
    # %ECSV 1.0
    ...
    0
    """
    parser = build_parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        args = parser.parse_args(_protect_sites(argv))
    except UsageError as error:
        print(f"feedrot: error: {one_line(error)}", file=sys.stderr)
        return 2
    if not hasattr(args, "run"):
        parser.print_help()
        return 2
    # One Earth-orientation context for the whole run: at most one warning
    # (one line) about stale tables, however many computations it makes.
    with warnings.catch_warnings():
        warnings.simplefilter("default")
        # Deprecations inside the libraries are for their developers, not for users.
        for category in (DeprecationWarning, PendingDeprecationWarning, FutureWarning):
            warnings.simplefilter("ignore", category)
        warnings.showwarning = _warning_printer()
        with iers_context():
            return _run(args)
