# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Signs of life: the progress bars of long commands, on a terminal only, and the line
that says what was written."""

import argparse
import io
import os
import pathlib
import pty
import subprocess
import sys
import threading

import pytest

import astropy_feedrot
from astropy_feedrot.cli import main
from astropy_feedrot.cli.common import show_progress
from astropy_feedrot.data import sample_file

SOURCE = "03h19m48.16s +41d30m42.1s"  # 3C 84
# 30,001 epochs: two blocks of rows (core.outputs.BLOCK_ROWS) in a text file.
LONG = ["natural", "EFLSBERG", "--source", SOURCE, "--start", "2023-01-25T00:00",
        "--stop", "2023-01-25T08:20", "--step", "1s"]
# This checkout's package, whatever the subprocess's working directory.
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join(
    [str(pathlib.Path(astropy_feedrot.__file__).parents[1])]
    + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))


def feedrot(argv, cwd, terminal):
    """Run feedrot with standard error on a terminal (a pseudo-terminal) or a pipe:
    (exit status, standard output, standard error)."""
    command = [sys.executable, "-m", "astropy_feedrot", *argv]
    if not terminal:
        done = subprocess.run(command, cwd=cwd, env=ENV, capture_output=True, timeout=300)
        return done.returncode, done.stdout, done.stderr.decode()
    main_fd, side = pty.openpty()
    process = subprocess.Popen(command, cwd=cwd, env=ENV, stdout=subprocess.PIPE,
                               stderr=side)
    os.close(side)
    drawn = []

    def read_terminal():  # as it is written, until the process closes it
        while True:
            try:
                data = os.read(main_fd, 65536)
            except OSError:  # EIO: the other side is closed
                return
            if not data:
                return
            drawn.append(data)

    reader = threading.Thread(target=read_terminal)
    reader.start()
    out, _ = process.communicate(timeout=300)  # standard output read meanwhile
    reader.join(timeout=60)
    os.close(main_fd)
    # A terminal turns "\n" into "\r\n".
    return process.returncode, out, b"".join(drawn).decode().replace("\r\n", "\n")


def bars(err):
    """The drawings of the bar (each starts with a carriage return)."""
    return [line for line in err.split("\r") if line.startswith("|")]


def test_a_bar_on_a_terminal_while_a_long_table_is_written_and_the_same_file(tmp_path):
    status, out, err = feedrot(LONG + ["-o", "bar.ecsv"], tmp_path, terminal=True)
    assert status == 0, err
    drawn = bars(err)
    # Drawn at 0 % while the table is computed, after each of the two blocks, at the end.
    assert len(drawn) >= 4, err
    assert "( 0.00%)" in drawn[0] and "(100.00%)" in drawn[-1]
    shown = {line.split("(")[1].split(")")[0] for line in drawn}
    assert "83.33%" in shown, shown  # a block of 25,000 rows of 30,001, then the rest
    assert err.endswith("\nfeedrot: bar.ecsv: 30001 rows of the feed rotation of EFLSBERG "
                        f"observing {SOURCE} (icrs)\n")
    # Without a terminal: no bar, the one summary line, and the same bytes written.
    status, out, err = feedrot(LONG + ["-o", "plain.ecsv"], tmp_path, terminal=False)
    assert status == 0 and "\r" not in err
    assert err == ("feedrot: plain.ecsv: 30001 rows of the feed rotation of EFLSBERG "
                   f"observing {SOURCE} (icrs)\n")
    assert (tmp_path / "bar.ecsv").read_bytes() == (tmp_path / "plain.ecsv").read_bytes()


@pytest.mark.parametrize("form", ["ecsv", "csv"])
def test_a_table_on_a_pipe_is_the_same_with_a_bar(tmp_path, form):
    status, with_bar, err = feedrot(LONG + ["--format", form], tmp_path, terminal=True)
    assert status == 0 and len(bars(err)) >= 4, err
    status, without, err = feedrot(LONG + ["--format", form], tmp_path, terminal=False)
    # Nothing written to a file: no summary line either.
    assert status == 0 and err == ""
    assert with_bar == without and without.count(b"\n") > 30001


def test_nothing_but_the_summary_line_in_the_tests(capsys, tmp_path):
    # Standard error is not a terminal here: no bar, one line.
    argv = LONG[:-4] + ["--stop", "2023-01-25T00:10", "--step", "1min"]
    assert main(argv + ["-o", str(tmp_path / "t.fits"), "--plot", str(tmp_path / "t.png")]) == 0
    out, err = capsys.readouterr()
    assert out == ""
    assert err == (f"feedrot: {tmp_path / 't.fits'} and {tmp_path / 't.png'}: 11 rows of the "
                   f"feed rotation of EFLSBERG observing {SOURCE} (icrs)\n")


def test_the_baseline_summary_names_both_antennas_and_the_frequency(capsys, tmp_path):
    assert main(["baseline", "EFLSBERG", "YEBES40M", "--source", SOURCE, "--start",
                 "2023-01-25T18:00", "--stop", "2023-01-25T19:00", "--frequency", "8.4GHz",
                 "-o", str(tmp_path / "b.ecsv")]) == 0
    assert capsys.readouterr().err == (
        f"feedrot: {tmp_path / 'b.ecsv'}: 7 rows of the feed rotation of EFLSBERG and "
        f"YEBES40M observing {SOURCE} (icrs), and their rotation delay at 8400.0 MHz\n")


class Terminal(io.StringIO):
    def isatty(self):
        return True


@pytest.mark.parametrize("output, form, stdout_terminal, expected", [
    ("t.ecsv", None, True, True),       # a file: the bar
    (None, None, False, True),          # ECSV on a pipe: the bar
    (None, None, True, False),          # the text view on the terminal: its lines
    (None, "text", False, False),       # the text view, printed at once
    (None, "ecsv", True, True),         # ECSV asked for on the terminal, in blocks
])
def test_when_a_bar_is_drawn(monkeypatch, output, form, stdout_terminal, expected):
    monkeypatch.setattr(sys, "stdout", Terminal() if stdout_terminal else io.StringIO())
    args = argparse.Namespace(output=output, format=form)
    assert show_progress(args, Terminal()) is expected
    assert show_progress(args, io.StringIO()) is False


def test_rinex_draws_its_bar_on_a_terminal_and_names_the_outputs_as_given(tmp_path):
    rnx, sp3 = (str(sample_file(name)) for name in ("gnss_sample.rnx", "gnss_sample.sp3"))
    argv = ["rinex", rnx, "--sp3", sp3, "-o", "out.rnx", "--table", "windup.ecsv"]
    status, _, err = feedrot(argv, tmp_path, terminal=True)
    assert status == 0, err
    drawn = bars(err)
    # Two bars: the bytes of the file read (one block), then the rows of the table.
    assert sum("( 0.00%)" in line for line in drawn) == 2, err
    assert sum("(100.00%)" in line for line in drawn) >= 2, err
    summary = ("feedrot: out.rnx and windup.ecsv: 1920 carrier phases of 640 observations at "
               "40 epochs corrected, 16 arcs, 0 epochs untouched\n")
    assert err.endswith("\n" + summary)
    status, _, err = feedrot(argv[:-4] + ["-o", "plain.rnx"], tmp_path, terminal=False)
    assert status == 0 and err == summary.replace("out.rnx and windup.ecsv", "plain.rnx")
    assert (tmp_path / "out.rnx").read_bytes() == (tmp_path / "plain.rnx").read_bytes()


def test_faraday_draws_its_bar_and_writes_the_same_file(tmp_path):
    rm = str(sample_file("rm_effelsberg.ecsv"))
    argv = ["faraday", "EFLSBERG", "--source", SOURCE, "--start", "2024-06-01T08:00",
            "--stop", "2024-06-01T10:00", "--step", "1s", "--rm-table", rm, "--frequency",
            "1.4GHz"]
    status, _, err = feedrot(argv + ["-o", "bar.ecsv"], tmp_path, terminal=True)
    assert status == 0, err
    drawn = bars(err)
    assert "( 0.00%)" in drawn[0] and "(100.00%)" in drawn[-1], err
    summary = ("feedrot: {}: 7201 rows of the rotation measure, Faraday and feed rotation of "
               f"EFLSBERG observing {SOURCE} (icrs) at 1.4GHz\n")
    assert err.endswith("\n" + summary.format("bar.ecsv"))
    status, _, err = feedrot(argv + ["-o", "plain.ecsv"], tmp_path, terminal=False)
    assert status == 0 and err == summary.format("plain.ecsv")
    assert (tmp_path / "bar.ecsv").read_bytes() == (tmp_path / "plain.ecsv").read_bytes()


def test_correct_draws_its_bar_before_the_read(tmp_path):
    pytest.importorskip("pyuvdata")
    uvfits = str(sample_file("vla_day2_8chan.uvfits"))
    status, _, err = feedrot(["correct", uvfits, "-o", "out.uvfits"], tmp_path, terminal=True)
    assert status == 0, err
    drawn = bars(err)
    # At 0 % before pyuvdata reads, at a third once it has, through the chunks
    # corrected, at two thirds before the write, at 100 % once written.
    assert "( 0.00%)" in drawn[0] and "(100.00%)" in drawn[-1]
    shown = {line.split("(")[1].split(")")[0] for line in drawn}
    assert {"33.33%", "66.67%"} <= shown and len(shown) > 4, shown
    # pyuvdata's warning on this file, on a line of its own below the bar.
    assert "\nfeedrot: warning: " in err and "%)feedrot" not in err
    assert err.endswith(f"\nfeedrot: out.uvfits: feed rotation removed from {uvfits} "
                        "(rigorous convention: vertical geodetic, pole itrs; frame apparent)\n")


def test_coverage_draws_its_bar_and_prints_the_same_tables(tmp_path):
    argv = ["coverage", "--stations", "EFLSBERG", "YEBES40M", "--source", SOURCE,
            "--start", "2024-03-01", "--stop", "2024-03-02"]
    status, with_bar, err = feedrot(argv, tmp_path, terminal=True)
    assert status == 0, err
    drawn = bars(err)
    # The grid, each of the two stations, the continuous series: 4 steps.
    assert "( 0.00%)" in drawn[0] and "(100.00%)" in drawn[-1]
    assert {"25.00%", "50.00%", "75.00%"} <= {line.split("(")[1].split(")")[0]
                                              for line in drawn}
    status, without, err = feedrot(argv, tmp_path, terminal=False)
    assert status == 0 and err == "" and with_bar == without
