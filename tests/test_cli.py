# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ``feedrot`` command line."""

import os
import subprocess
import sys

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import HADec, SkyCoord
from astropy.table import Table
from astropy.time import Time

from astropy_feedrot.cli import main
from astropy_feedrot.simulations import GPS_SVN76_TLE
from astropy_feedrot.stations import get_antenna

from helpers import MAS

SOURCE = "03h19m48.16s +41d30m42.1s"  # 3C 84
SPAN = ["--start", "2023-01-25T18:00", "--stop", "2023-01-25T22:00", "--step", "1h"]


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def read(out):
    return Table.read(out, format="ascii.ecsv")


@pytest.fixture
def tle_file(tmp_path):
    path = tmp_path / "gps.tle"
    path.write_text("GPS SVN 76\n" + "\n".join(GPS_SVN76_TLE) + "\n")
    return path


def test_natural_parallactic_angle_against_erfa(capsys):
    status, out, err = run(capsys, "natural", "EFLSBERG", "--source", SOURCE, *SPAN)
    assert status == 0 and err == ""
    table = read(out)
    assert table.colnames == ["time", "azimuth", "elevation", "parallactic_angle", "transmitter",
                              "receiver", "total", "continuous"]
    assert len(table) == 5
    # Independent: erfa.hd2pa from astropy's HADec frame.
    antenna = get_antenna("EFLSBERG")
    times = Time(table["time"])
    hadec = SkyCoord(SOURCE).transform_to(HADec(obstime=times, location=antenna.location))
    pa = erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, antenna.location.lat.rad)
    assert np.max(np.abs(u.Quantity(table["parallactic_angle"]).to_value(u.rad) - pa)) < MAS
    # Gregorian focus: the feed rotation is the parallactic angle; the transmitter
    # term of a natural source is 0 up to rounding.
    assert np.allclose(table["total"], table["parallactic_angle"], atol=1e-9)
    assert np.all(np.abs(table["transmitter"]) < 1e-12)


def test_ra_dec_options_and_output_file(capsys, tmp_path):
    path = tmp_path / "out.ecsv"
    status, out, _ = run(capsys, "natural", "ef", "--ra", "03:19:48.16", "--dec", "+41:30:42.1",
                         *SPAN, "-o", str(path))
    assert status == 0 and out == ""
    by_string = read(run(capsys, "natural", "EFLSBERG", "--source", SOURCE, *SPAN)[1])
    assert np.allclose(Table.read(path)["total"], by_string["total"], atol=1e-9)
    # Degrees as plain numbers: RA 49.950667 deg = 03h19m48.16s.
    degrees = read(run(capsys, "natural", "EFLSBERG", "--ra", "49.9506667", "--dec",
                       "41.5116944", *SPAN)[1])
    assert np.allclose(degrees["total"], by_string["total"], atol=1e-4)


def test_site_given_as_latitude_longitude_height(capsys):
    # A southern, western site: -33.0 must not be taken for an option.
    status, out, err = run(capsys, "natural", "-33.0,-70.0,2500", "--mount", "NASL",
                           "--source", SOURCE, *SPAN)
    assert status == 0, err
    table = read(out)
    # Nasmyth left: parallactic angle minus elevation (Eq 38).
    expected = (table["parallactic_angle"] - table["elevation"] + 180 * u.deg) % (360 * u.deg)
    assert np.allclose(expected - 180 * u.deg, table["total"], atol=1e-8 * u.deg)
    status, out, _ = run(capsys, "natural", "40.5,-3.1,990", "--focus", "nasmyth-right",
                         "--source", SOURCE, *SPAN)
    assert status == 0


def test_satellite_tle(capsys, tle_file):
    status, out, err = run(capsys, "satellite", "DBR205", "--tle", str(tle_file), "--start",
                           "2023-01-25T08:00", "--stop", "2023-01-25T15:00", "--step", "1h",
                           "--min-elevation", "10")
    assert status == 0, err
    table = read(out)
    # Sec. 4.1: the satellite is above 10 deg at FD-VLBA/DBR205 from about 08:06 to 15:07.
    assert np.isnan(table["total"][0]) and np.all(np.isfinite(table["total"][1:]))
    assert table.meta["antenna"] == "DBR205"
    assert np.any(table["transmitter"] != 0)


def test_satellite_sp3_with_orbex(capsys):
    from astropy_feedrot.data import sample_file

    status, out, err = run(capsys, "satellite", "FD-VLBA", "--sp3", str(sample_file("sample.sp3")),
                           "--sat", "G01", "--orbex", str(sample_file("sample.obx")),
                           "--points", "4",
                           "--start", "2023-01-25T00:00:20", "--stop", "2023-01-25T00:00:40",
                           "--step", "10s")
    assert status == 0, err
    assert len(read(out)) == 3


def test_baseline_and_plot(capsys, tmp_path, tle_file):
    pytest.importorskip("matplotlib")
    png = tmp_path / "baseline.png"
    status, out, err = run(capsys, "baseline", "DBR205", "FD-VLBA", "--tle", str(tle_file),
                           "--start", "2023-01-25T09:00", "--stop", "2023-01-25T10:00",
                           "--step", "10min", "--frequency", "1575.42MHz", "--plot", str(png))
    assert status == 0, err
    table = read(out)
    # Ambiguity 1/f at L1 (Sec. 4.1: 634.8 ps).
    assert u.Quantity(table.meta["ambiguity"]).to_value(u.ps) == pytest.approx(634.75, abs=0.01)
    assert "rotation_delay" in table.colnames and "FD-VLBA_continuous" in table.colnames
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_natural_plot(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    png = tmp_path / "n.png"
    span = [*SPAN[:4], "--step", "10min"]
    assert run(capsys, "natural", "YEBES40M", "--source", SOURCE, *span, "--plot", str(png))[0] == 0
    assert png.stat().st_size > 1000


def test_warnings_are_one_line(capsys):
    # Hourly samples of a Nasmyth telescope near transit jump by more than
    # 162 deg: the continuity warning reaches stderr as one line, the table stdout.
    status, out, err = run(capsys, "natural", "YEBES40M", "--source", SOURCE, *SPAN)
    assert status == 0 and len(read(out)) == 5
    assert err.startswith("feedrot: warning: 1 consecutive steps exceed 162 deg")
    assert err.count("\n") == 1


def test_demo_writes_table_and_figure(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    status, out, err = run(capsys, "demo", "--output-dir", str(tmp_path), "--step", "5min")
    assert status == 0, err
    assert "GPS SVN 76 over DBR205 and FD-VLBA" in out
    assert "ambiguity 634.8 ps" in out
    table = Table.read(tmp_path / "feedrot_demo.ecsv")
    assert table.meta["antennas"] == ["DBR205", "FD-VLBA"]
    assert (tmp_path / "feedrot_demo.png").stat().st_size > 1000


def test_stations_listing(capsys):
    status, out, _ = run(capsys, "stations")
    assert status == 0
    assert list(read(out)["name"])[-1] == "PARKES"


def test_help_teaches_by_example(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["natural", "--help"])
    assert exit_.value.code == 0
    out = capsys.readouterr().out
    assert "examples:" in out and "feedrot natural YEBES40M" in out
    assert main([]) == 2
    assert "feedrot demo" in capsys.readouterr().out


@pytest.mark.parametrize("argv, match", [
    (["natural", "YEBES40", "--source", SOURCE, *SPAN], r"unknown antenna 'YEBES40'.*YEBES40M"),
    (["natural", "EFLSBERG", "--source", "3C 84", *SPAN],
     r"--source: cannot read '3C 84' as coordinates.*needs the internet"),
    (["natural", "EFLSBERG", "--ra", "3h19m", *SPAN], r"with both --ra and --dec"),
    (["natural", "EFLSBERG", "--ra", "xx", "--dec", "41", *SPAN], r"--ra/--dec: cannot read"),
    (["natural", "EFLSBERG", "--source", SOURCE, "--ra", "1", "--dec", "2", *SPAN],
     r"either with --source or with --ra and --dec"),
    (["natural", "EFLSBERG", "--source", SOURCE, "--start", "yesterday", "--stop", "2023-01-26"],
     r"--start: cannot read 'yesterday' as a time"),
    (["natural", "EFLSBERG", "--source", SOURCE, "--start", "2023-01-26", "--stop", "2023-01-25"],
     r"--stop \(2023-01-25T00:00:00.000\) is before --start"),
    (["natural", "EFLSBERG", "--source", SOURCE, "--start", "2023-01-25"],
     r"give the span of time with --start and --stop"),
    ([*["natural", "EFLSBERG", "--source", SOURCE], *SPAN[:4], "--step", "0s"],
     r"--step must be positive and finite, got '0s'"),
    ([*["natural", "EFLSBERG", "--source", SOURCE], *SPAN[:4], "--step=-5min"],
     r"--step must be positive"),
    ([*["natural", "EFLSBERG", "--source", SOURCE], *SPAN[:4], "--step", "5deg"],
     r"--step: '5deg' is not in a unit of time"),
    ([*["natural", "EFLSBERG", "--source", SOURCE], *SPAN[:4], "--step", "fast"],
     r"--step: cannot read 'fast'"),
    ([*["natural", "EFLSBERG", "--source", SOURCE], "--start", "2000-01-01", "--stop",
      "2023-01-01", "--step", "1s"], r"--step 1s gives 7.26e\+08 epochs from --start to --stop, "
     r"more than the 1000000 of one run"),
    (["natural", "EFLSBERG", "--source", SOURCE, *SPAN, "--min-elevation", "95"],
     r"--min-elevation must be one angle within \[-90, 90\] deg"),
    (["natural", "EFLSBERG", "--source", SOURCE, *SPAN, "--min-elevation", "10s"],
     r"--min-elevation: '10s' is not an angle"),
    (["natural", "EFLSBERG", "--mount", "EQUA", "--source", SOURCE, *SPAN],
     r"--mount and --focus go with a site"),
    (["natural", "95,10,0", "--source", SOURCE, *SPAN], r"latitude 95 .* is not in \[-90, 90\]"),
    (["natural", "40,10,0", "--mount", "ALTAZ", "--source", SOURCE, *SPAN], r"ALTAZ"),
    (["natural", "40,10,0", "--focus", "coude", "--source", SOURCE, *SPAN],
     r"--focus: unknown focus 'coude'"),
    (["natural", "EFLSBERG", "--source", SOURCE, *SPAN, "-o", "/nonexistent/dir/out.ecsv"],
     r"-o/--output: cannot write '/nonexistent/dir/out.ecsv': directory '/nonexistent/dir' does "
     r"not exist"),
    (["natural", "EFLSBERG", "--source", SOURCE, *SPAN, "--catalogue", "/nonexistent.ecsv"],
     r"--catalogue: no such file"),
    (["satellite", "DBR205", *SPAN], r"give the satellite's orbit with --tle FILE or --sp3"),
    (["satellite", "DBR205", "--tle", "/nonexistent.tle", *SPAN], r"--tle: no such file"),
    (["satellite", "DBR205", "--sp3", "/nonexistent.sp3", "--sat", "G01"], r"--sp3: no such file"),
    (["baseline", "DBR205", "FD-VLBA", "--source", SOURCE, *SPAN, "--frequency=-1GHz"],
     r"--frequency must be positive"),
    (["baseline", "DBR205", "FD-VLBA", "--source", SOURCE, *SPAN, "--frequency", "0"],
     r"--frequency must be positive"),
    (["baseline", "DBR205", "FD-VLBA", "--source", SOURCE, *SPAN, "--frequency", "3m"],
     r"--frequency: '3m' is not in a unit of frequency"),
    (["baseline", "DBR205", "dbr205", "--source", SOURCE, *SPAN, "--frequency", "1GHz"],
     r"the two antennas of a baseline must differ"),
    (["demo", "--output-dir", "/nonexistent"], r"--output-dir: '/nonexistent' is not a directory"),
])
def test_bad_input_is_one_line(capsys, argv, match):
    status, out, err = run(capsys, *argv)
    assert status == 1
    assert err.count("\n") == 1 and err.startswith("feedrot: error: ")
    assert __import__("re").search(match, err), err


def test_tle_file_choices(capsys, tmp_path):
    iss = ("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
           "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
    path = tmp_path / "two.tle"
    path.write_text("GPS SVN 76\n" + "\n".join(GPS_SVN76_TLE) + "\nISS\n" + "\n".join(iss) + "\n")
    status, _, err = run(capsys, "satellite", "DBR205", "--tle", str(path), *SPAN)
    assert status == 1 and "has 2 satellites; choose one with --sat" in err
    status, _, err = run(capsys, "satellite", "DBR205", "--tle", str(path), "--sat", "X", *SPAN)
    assert "--sat 'X' is not in" in err and "GPS SVN 76 (41328), ISS (25544)" in err
    assert run(capsys, "satellite", "DBR205", "--tle", str(path), "--sat", "41328", *SPAN)[0] == 0
    bad = tmp_path / "bad.tle"
    bad.write_text(GPS_SVN76_TLE[0] + "\n")
    status, _, err = run(capsys, "satellite", "DBR205", "--tle", str(bad), *SPAN)
    assert status == 1 and "bad.tle, line 2: expected line 2" in err


def test_unwritable_output(capsys, tmp_path):
    if os.geteuid() == 0:
        pytest.skip("root can write anywhere")
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    status, _, err = run(capsys, "natural", "EFLSBERG", "--source", SOURCE, *SPAN, "-o",
                         str(locked / "x.ecsv"))
    assert status == 1 and "permission denied" in err


def test_output_is_a_directory(capsys, tmp_path):
    status, _, err = run(capsys, "natural", "EFLSBERG", "--source", SOURCE, *SPAN, "-o",
                         str(tmp_path))
    assert status == 1 and "is a directory" in err


def test_console_entry_point_without_traceback():
    result = subprocess.run([sys.executable, "-m", "astropy_feedrot", "natural", "NOPE",
                             "--source", SOURCE, *SPAN], capture_output=True, text=True)
    assert result.returncode == 1
    assert "Traceback" not in result.stderr
    assert result.stderr.startswith("feedrot: error: unknown antenna 'NOPE'")


def test_every_option_is_documented():
    from pathlib import Path

    from astropy_feedrot.cli import _parser

    text = (Path(__file__).parent.parent / "docs" / "cli.rst").read_text()
    parser = _parser()
    commands = parser._subparsers._group_actions[0].choices
    for name, command in commands.items():
        assert f"feedrot {name}" in text
        for action in command._actions:
            for option in action.option_strings:
                if option.startswith("--") and option != "--help":
                    assert f"``{option}" in text, f"{option} of feedrot {name} is not in cli.rst"
