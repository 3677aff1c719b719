# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Running a parsed command of ``feedrot``: warnings, Earth orientation and errors.

`astropy_feedrot.cli.main` imports this module (and so astropy) only once the
command line has parsed into a command. `run_command` runs it inside one
Earth-orientation context, with each warning printed once on one line, and
turns every error into one line on standard error and an exit status.
"""

import contextlib
import importlib
import os
import sys
import warnings

from astropy import units as u

from ..core.outputs import CommandError
from ..core.progress import bar_drawn
from ..earth.eop import iers_context
from ..io import FileFormatError
from .parser import COMMANDS
from .shared import one_line

__all__ = ["run_command", "command_function"]


def command_function(name):
    """The function that runs a command: from its module, named in the parser's table
    (`astropy_feedrot.cli.parser.COMMANDS`), imported now (with astropy, and what the
    command's family needs).

    Examples
    --------
    >>> from astropy_feedrot.cli.running import command_function
    >>> command_function("correct").__module__
    'astropy_feedrot.cli.data'
    """
    module, function = COMMANDS[name]
    return getattr(importlib.import_module(f"{__package__}.{module}"), function)


def run_command(args):
    """Run the command of parsed arguments ``args`` (``args.command``).

    Parameters
    ----------
    args : argparse.Namespace
        From `astropy_feedrot.cli.build_parser`, with a command.

    Returns
    -------
    int
        The exit status (see `astropy_feedrot.cli.main`).
    """
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


def _warning_printer():
    """A ``warnings.showwarning`` that prints each distinct warning once, on one line.

    (pyuvdata gives its uvw warning once on reading and again on writing.)
    """
    shown = set()

    def show(message, category, filename, lineno, file=None, line=None):
        text = one_line(message)
        if text not in shown:
            shown.add(text)
            # On a line of its own, not after a progress bar being drawn.
            start = "\n" if bar_drawn() else ""
            print(f"{start}feedrot: warning: {text}", file=sys.stderr)
    return show


def _run(args):
    """Run a parsed command: its exit status, and any error as one line on stderr."""
    try:
        status = command_function(args.command)(args)
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
