# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The examples of every ``--help`` are whole lines; ``feedrot --version``.

That each example runs as printed, in an empty directory, is
tests/cli/test_cli_examples.py.
"""

import contextlib
import io

import pytest

from astropy_feedrot import __version__
from astropy_feedrot.cli import main

COMMANDS = ["", "natural", "satellite", "baseline", "faraday", "demo", "stations", "coverage",
            "antennas", "correct", "rinex", "samples"]


def help_of(command):
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit) as stop:
        main(([command] if command else []) + ["--help"])
    assert stop.value.code == 0
    return out.getvalue()


def printed_examples():
    """(command, line) for every example line of every --help, as printed."""
    found = []
    for command in COMMANDS:
        text = help_of(command)
        assert "examples:\n" in text, command
        section = text.split("examples:\n", 1)[1]
        for line in section.splitlines():
            if not line.startswith("  feedrot"):
                break
            found.append((command or "feedrot", line.strip()))
    return found


def test_examples_are_whole_lines():
    # Three examples of 'feedrot --help' ended in a backslash: pasted, they joined.
    examples = printed_examples()
    assert len(examples) >= 20
    for _, line in examples:
        assert not line.endswith("\\"), line


def test_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out == f"feedrot {__version__}\n"
