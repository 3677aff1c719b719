# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ``feedrot`` command line.

``feedrot natural``, ``feedrot satellite`` and ``feedrot baseline`` tabulate
feed rotation over a span of time (ECSV on standard output, or a file whose
format follows its extension, and optionally a figure); ``feedrot demo`` runs
the paper's Section 4.1 simulation on embedded data; ``feedrot stations``
lists the station catalogue (``--network``, ``--mount``); ``feedrot
coverage`` tabulates the range of feed rotation that candidate polarization
calibrators offer a network. ``feedrot faraday`` tabulates the ionosphere's
rotation measure, its Faraday rotation and the feed rotation of stations.
``feedrot antennas`` lists the antennas of a
visibility file as read, and ``feedrot correct`` writes a copy of a
visibility file with the feed rotation removed, or corrects a Measurement Set
in place (see `astropy_feedrot.visibilities`). ``feedrot rinex`` writes a copy
of a RINEX observation file with the carrier-phase wind-up removed (see
`astropy_feedrot.gnss`).

The grammar of every command (arguments, options, help, examples) is
`astropy_feedrot.cli.parser`, built without importing astropy: ``feedrot
--version`` and ``feedrot --help`` start at once. Each family of commands is
a module of this package (``tables``, ``faraday``, ``demo``, ``stations``,
``coverage``, ``data``, ``rinex``, ``samples``), imported when one of its commands runs,
through `astropy_feedrot.cli.running`; what they share is in ``common``.

Every error is one line on standard error and a non-zero exit status. No file
is lost: every output is checked before any work is done (format, directory,
an existing file needs ``--overwrite``, never one of the inputs, never the
table and the figure in one file), written to a temporary file beside its
target and renamed into place once everything has been written.

May import: every subpackage (``core``, ``io``, ``earth``, ``antennas``,
``transmitters``, ``ionosphere``, ``engine``, ``stations``, ``applied``,
``visibilities``, ``gnss``); it is the top layer.
"""

import sys

from ..core.outputs import TABLE_FORMATS, CommandError
from .parser import build_parser
from .shared import CELESTIAL_FRAMES, MAX_EPOCHS, UsageError, one_line

__all__ = ["main", "build_parser", "CommandError", "MAX_EPOCHS", "TABLE_FORMATS",
           "CELESTIAL_FRAMES"]


def _protect_sites(argv):
    # A southern or western site such as -33.0,148.26,415 (or a place such as
    # --near's -3.09,40.52) would look like an option to argparse; a leading
    # space keeps it a value.
    return [f" {arg}" if arg.startswith("-") and not arg.startswith("--")
            and 1 <= arg.count(",") <= 2 else arg for arg in argv]


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
    if args.command is None:
        parser.print_help()
        return 2
    if getattr(args, "light", False):
        # Listing or copying a sample needs neither astropy nor the Earth's orientation.
        try:
            return args.run(args)
        except (CommandError, OSError) as error:
            print(f"feedrot: error: {one_line(error)}", file=sys.stderr)
            return 1
    # The command's modules, astropy among them, only now: the parser needed none.
    from .running import run_command

    return run_command(args)
