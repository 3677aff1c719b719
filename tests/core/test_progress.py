# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Progress steps and tables written in blocks of rows (core.progress, core.outputs)."""

import io
import os
import pty
import sys

import astropy.units as u
import numpy as np
import pytest
from astropy.table import Table
from astropy.time import Time

from astropy_feedrot.core import outputs
from astropy_feedrot.core.outputs import table_writer, write_table_blocks
from astropy_feedrot.core.progress import bar_drawn, progress_steps


def test_a_callable_is_told_the_units_done():
    calls = []
    with progress_steps(lambda done, total: calls.append((done, total)), 10) as step:
        step()
        step(4)
        step(5)
    assert calls == [(1, 10), (5, 10), (10, 10)]


@pytest.mark.parametrize("progress", [False, None])
def test_no_progress_is_silent(capsys, progress):
    with progress_steps(progress, 3) as step:
        step()
        step(2)
    assert capsys.readouterr() == ("", "")


def test_a_bar_on_a_standard_error_that_is_not_a_terminal_is_silent(capsys):
    with progress_steps(True, 3) as step:
        step(3)
        assert not bar_drawn()
    assert capsys.readouterr() == ("", "")


def test_a_bar_on_a_terminal_is_drawn_at_each_step(monkeypatch):
    main, side = pty.openpty()
    with os.fdopen(side, "w") as terminal:
        monkeypatch.setattr(sys, "stderr", terminal)
        with progress_steps(True, 300) as step:
            for _ in range(3):
                step(100)
            assert bar_drawn()  # messages meanwhile start on a new line
        assert not bar_drawn()  # once the bar is finished
    chunks = []
    while True:  # everything written, until the closed side gives EIO
        try:
            data = os.read(main, 65536)
        except OSError:
            break
        if not data:
            break
        chunks.append(data)
    os.close(main)
    drawn = b"".join(chunks).decode()
    # Drawn at 0 on creation, after each step, and once more at the end.
    assert drawn.count("\r") >= 4
    assert "100 /300" in drawn and "200 /300" in drawn and "(100.00%)" in drawn


def test_a_bad_progress_is_refused():
    with pytest.raises(TypeError, match="progress must be True, False or a callable "
                                        r"\(done, total\), got str"):
        with progress_steps("yes", 3):
            pass


def _tables():
    """Tables like those the commands write: times, floats with NaN, strings."""
    times = Time("2023-01-25T00:00") + np.arange(95) * u.min
    angles = np.linspace(-180, 180, 95) * u.deg
    angles[10:20] = np.nan
    natural = Table({"time": times, "total": angles, "rate": angles / u.s})
    natural.meta.update(antenna="EFLSBERG", natural=True)
    gnss = Table({"time": times, "prn": np.where(np.arange(95) % 2, "G01", "E11"),
                  "windup": angles.value * u.cycle})
    return {"natural": natural, "gnss": gnss}


@pytest.mark.parametrize("fmt", ["ascii.ecsv", "ascii.csv", "ascii.html"])
@pytest.mark.parametrize("kind", ["natural", "gnss"])
def test_blocks_are_the_table_written_at_once_byte_for_byte(monkeypatch, kind, fmt):
    monkeypatch.setattr(outputs, "BLOCK_ROWS", 10)
    table = _tables()[kind]
    whole, blocks, steps = io.StringIO(), io.StringIO(), []
    table.write(whole, format=fmt)
    write_table_blocks(table, fmt, blocks, steps.append)
    assert blocks.getvalue() == whole.getvalue()
    # ECSV and CSV in blocks of 10 rows; HTML (not one line per row) at once.
    assert steps == ([10] * 9 + [5] if fmt != "ascii.html" else [95])


@pytest.mark.parametrize("extension, fmt", [(".ecsv", "ascii.ecsv"), (".csv", "ascii.csv"),
                                            (".fits", "fits")])
def test_files_written_in_blocks_are_those_astropy_writes(monkeypatch, tmp_path, extension,
                                                          fmt):
    monkeypatch.setattr(outputs, "BLOCK_ROWS", 10)
    table = _tables()["natural"]
    table.write(tmp_path / f"whole{extension}", format=fmt)
    steps = []
    table_writer(table, fmt, steps.append)(tmp_path / f"blocks{extension}")
    assert ((tmp_path / f"blocks{extension}").read_bytes()
            == (tmp_path / f"whole{extension}").read_bytes())
    assert sum(steps) == len(table) and len(steps) == (1 if fmt == "fits" else 10)


def test_strings_with_line_breaks_are_written_at_once(monkeypatch):
    monkeypatch.setattr(outputs, "BLOCK_ROWS", 2)
    table = Table({"note": ["a", "b\nc", "d", "e", "f"]})
    whole, blocks, steps = io.StringIO(), io.StringIO(), []
    table.write(whole, format="ascii.ecsv")
    write_table_blocks(table, "ascii.ecsv", blocks, steps.append)
    assert blocks.getvalue() == whole.getvalue() and steps == [5]


def test_a_header_that_changes_between_blocks_is_refused(monkeypatch):
    monkeypatch.setattr(outputs, "BLOCK_ROWS", 2)

    class Drifting(Table):
        def write(self, stream, format=None):  # a header naming the block's first value
            stream.write(f"# first {self['a'][0]}\n" + "".join(f"{v}\n" for v in self["a"]))

    with pytest.raises(RuntimeError, match="the ascii.ecsv header of rows 2 to 4 differs from "
                                           r"that of the first rows; write the table at once"):
        write_table_blocks(Drifting({"a": [1, 2, 3, 4, 5]}), "ascii.ecsv", io.StringIO())
