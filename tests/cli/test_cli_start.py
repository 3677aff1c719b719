# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot --help`` and ``--version`` start without astropy.

The parser (`astropy_feedrot.cli.parser`) is built from plain constants, and
each command imports its modules when it runs: these tests look at what a
fresh interpreter has imported, not at the clock (benchmarks/start.py times it).
"""

import subprocess
import sys
from pathlib import Path

import pytest

from astropy_feedrot.cli import build_parser
from astropy_feedrot.cli.common import PHASE_UNITS
from astropy_feedrot.cli.parser import PHASE_UNIT_NAMES
from astropy_feedrot.core import choices
from astropy_feedrot.gnss import ATTITUDES
from astropy_feedrot.stations import FOCUS_NAMES
from astropy_feedrot.visibilities import MOUNTS, POLES
from astropy_feedrot.visibilities.poles import CONVENTIONS

ROOT = Path(__file__).parent.parent.parent

# What a fresh interpreter imports beyond the standard library and the package,
# after running the statements given (the interpreter's own start, such as the
# editable install's finder, is left out).
IMPORTED = """
import sys
before = set(sys.modules)
{statements}
extra = sorted(m for m in set(sys.modules) - before
               if m.split('.')[0] not in sys.stdlib_module_names
               and m.split('.')[0] != 'astropy_feedrot')
print(extra, file=sys.stderr)
"""

COMMANDS = [name for name in build_parser()._subparsers._group_actions[0].choices]


def imported(statements):
    run = subprocess.run([sys.executable, "-c", IMPORTED.format(statements=statements)],
                         capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert run.returncode == 0, run.stderr
    return run.stderr.strip().splitlines()[-1]


def test_building_the_parser_imports_nothing_beyond_the_standard_library():
    # Not astropy, not numpy: they take most of a second to import.
    assert imported("from astropy_feedrot.cli import build_parser; build_parser()") == "[]"


@pytest.mark.parametrize("argv", [["--version"], ["--help"], []]
                         + [[command, "--help"] for command in COMMANDS],
                         ids=lambda argv: " ".join(argv) or "no command")
def test_help_and_version_import_nothing_beyond_the_standard_library(argv):
    # As the feedrot script runs them (main), until the process ends.
    statements = ("import contextlib, io\n"
                  "from astropy_feedrot.cli import main\n"
                  "with contextlib.redirect_stdout(io.StringIO()):\n"
                  "    try:\n"
                  f"        main({argv!r})\n"
                  "    except SystemExit:\n"
                  "        pass")
    assert imported(statements) == "[]"


def test_a_usage_error_imports_nothing_beyond_the_standard_library():
    statements = ("import contextlib, io\n"
                  "from astropy_feedrot.cli import main\n"
                  "with contextlib.redirect_stderr(io.StringIO()):\n"
                  "    assert main(['natural', '--nope']) == 2")
    assert imported(statements) == "[]"


@pytest.mark.parametrize("argv", [["samples"], ["samples", "gps.tle"], ["samples", "nope.tle"]],
                         ids=" ".join)
def test_the_samples_import_nothing_beyond_the_standard_library(argv):
    # The printed examples call 'feedrot samples NAME' for every file they name: it
    # needs neither astropy nor the Earth's orientation, and its error is one line.
    statements = ("import contextlib, io\n"
                  "from astropy_feedrot.cli import main\n"
                  "out, err = io.StringIO(), io.StringIO()\n"
                  "with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):\n"
                  f"    status = main({argv!r})\n"
                  f"assert status == {int('nope.tle' in argv)}, status\n"
                  "assert len(err.getvalue().splitlines()) == status, err.getvalue()")
    assert imported(statements) == "[]"


def test_a_command_imports_what_it_needs_when_it_runs():
    # The other side: running a command does import astropy.
    statements = ("import contextlib, io\n"
                  "from astropy_feedrot.cli import main\n"
                  "with contextlib.redirect_stdout(io.StringIO()):\n"
                  "    assert main(['stations', 'YEBES40M', '--format', 'ecsv']) == 0")
    assert "astropy" in imported(statements)


def test_the_choices_are_those_of_the_modules_that_use_them():
    # One definition in core.choices; the modules that act on a choice use it.
    assert MOUNTS is choices.MOUNTS
    assert POLES is choices.POLES
    assert CONVENTIONS is choices.CONVENTIONS
    assert ATTITUDES is choices.ATTITUDES
    # Two lists, the names here and the foci they stand for there: the same names.
    assert tuple(name for name in FOCUS_NAMES if name) == choices.FOCI
    assert tuple(PHASE_UNITS) == PHASE_UNIT_NAMES


def test_the_parser_offers_the_choices():
    commands = build_parser()._subparsers._group_actions[0].choices
    options = {(command, option): action for command, parser in commands.items()
               for action in parser._actions for option in action.option_strings}
    assert tuple(options["correct", "--pole"].choices) == choices.POLES
    assert tuple(options["correct", "--convention"].choices) == tuple(choices.CONVENTIONS)
    assert tuple(options["correct", "--mounts"].choices) == choices.MOUNTS
    assert tuple(options["rinex", "--attitude"].choices) == choices.ATTITUDES
    assert tuple(options["satellite", "--units"].choices) == tuple(PHASE_UNITS)
    assert all(name in options["natural", "--focus"].help for name in FOCUS_NAMES)
