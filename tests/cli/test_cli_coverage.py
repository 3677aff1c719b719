# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ``feedrot coverage`` command."""

import importlib.util
import re

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import SkyCoord
from astropy.table import Table
from astropy.time import Time

from astropy_feedrot import feed_rotation_coverage
from astropy_feedrot.cli import main
from astropy_feedrot.stations.catalogue import get_antenna

SOURCES = ["--source", "3C84=03h19m48.16s +41d30m42.1s",
           "--source", "3C286=13h31m08.29s +30d30m33.0s"]
SPAN = ["--start", "2024-03-01T00:00", "--stop", "2024-03-02T00:00", "--step", "20min"]
STATIONS = ["--stations", "EFLSBERG", "WETTZ13S"]


def run(capsys, *argv):
    status = main(["coverage", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_prints_the_table_and_the_ranking(capsys, tmp_path):
    output = tmp_path / "coverage.ecsv"
    status, out, err = run(capsys, *STATIONS, *SOURCES, *SPAN, "-o", str(output))
    assert status == 0, err
    assert err == ""
    assert "Sources ranked by the range of their worst station:" in out
    table = Table.read(output)
    # The same numbers as the function (the command adds nothing of its own).
    expected = feed_rotation_coverage(
        [get_antenna("EFLSBERG"), get_antenna("WETTZ13S")],
        {"3C84": SkyCoord("03h19m48.16s +41d30m42.1s"),
         "3C286": SkyCoord("13h31m08.29s +30d30m33.0s")},
        Time("2024-03-01T00:00"), Time("2024-03-02T00:00"), 20 * u.min)
    assert list(table["target"]) == list(expected["target"])
    assert np.allclose(table["range"], expected["range"], rtol=0, atol=1e-9)
    ranking = out.split("worst station:")[1]
    assert ranking.index("3C84") < ranking.index("3C286")
    assert f"table: {output}" in out


@pytest.mark.skipif(importlib.util.find_spec("matplotlib") is None, reason="needs matplotlib")
def test_plots_the_tracks(capsys, tmp_path):
    figure = tmp_path / "tracks.png"
    status, out, err = run(capsys, *STATIONS, *SOURCES, *SPAN, "--plot", str(figure))
    assert status == 0, err
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    status, out, err = run(capsys, *STATIONS, *SOURCES, *SPAN, "--plot", str(figure))
    assert status == 1
    assert "exists; add --overwrite" in err


@pytest.mark.parametrize("argv, message", [
    (["--stations", "NOWHERE", *SOURCES, *SPAN], "NOWHERE"),
    # A bare coordinate is taken, as by every other command; a bare name is not one.
    ([*STATIONS, "--source", "3C84", *SPAN], r"--source 3C84: cannot read '3C84' as "
     r"coordinates .*\(names are not looked up\)"),
    ([*STATIONS, "--source", "=03h19m48s +41d30m", *SPAN],
     "write COORDINATES or NAME=COORDINATES"),
    ([*STATIONS, "--source", "X=nowhere", *SPAN],
     r"--source X: cannot read 'nowhere' as coordinates"),
    ([*STATIONS, "--source", "A=10d 20d", "--source", "A=30d 40d", *SPAN],
     "the name 'A' is given twice"),
    ([*STATIONS, "--source", "S=05h00m00s -70d00m00s", *SPAN],
     "no antenna sees any target above 10.0 deg"),
    ([*STATIONS, *SOURCES, "--start", "2024-03-02", "--stop", "2024-03-01"],
     r"--stop \(2024-03-01T00:00:00.000\) is before --start"),
    ([*STATIONS, *SOURCES, "--start", "2024-03-01", "--stop", "2024-03-01"],
     "--stop must be after --start by at least one --step"),
    ([*STATIONS, *SOURCES, *SPAN[:4], "--step=-5min"], "--step must be positive"),
    ([*STATIONS, *SOURCES, *SPAN, "--min-elevation", "100"],
     "--min-elevation must be one angle within"),
    ([*STATIONS, *SOURCES, *SPAN, "-o", "table.xyz"],
     "cannot tell a format from the extension"),
])
def test_errors_are_one_line(capsys, argv, message):
    status, out, err = run(capsys, *argv)
    assert status == 1
    assert err.count("\n") == 1 and err.startswith("feedrot: error: ")
    assert re.search(message, err), err
    assert out == ""


def test_usage_errors(capsys):
    status, out, err = run(capsys, *SOURCES, *SPAN)
    assert status == 2
    assert "the following arguments are required: --stations" in err
    assert err.count("\n") == 1
