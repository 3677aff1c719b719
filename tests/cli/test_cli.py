# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ``feedrot`` command line."""

import importlib.util
import os
import re
import shutil
import stat
import subprocess
import sys

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import HADec, SkyCoord
from astropy.table import Table
from astropy.time import Time
from helpers import MAS

from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
from astropy_feedrot.cli import main
from astropy_feedrot.stations.catalogue import get_antenna

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
                              "receiver", "total", "continuous", "rate"]
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
    assert "PARKES" in list(read(out)["name"])


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
    (["demo", "--output-dir", "/dev/null/results"],
     r"--output-dir: cannot make '/dev/null/results': Not a directory"),
])
def test_bad_input_is_one_line(capsys, argv, match):
    status, out, err = run(capsys, *argv)
    assert status == 1
    assert err.count("\n") == 1 and err.startswith("feedrot: error: ")
    assert re.search(match, err), err


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

    from astropy_feedrot.cli import build_parser

    text = (Path(__file__).parent.parent.parent / "docs" / "cli.rst").read_text()
    parser = build_parser()
    commands = parser._subparsers._group_actions[0].choices
    for name, command in commands.items():
        assert f"feedrot {name}" in text
        for action in command._actions:
            for option in action.option_strings:
                if option.startswith("--") and option != "--help":
                    assert f"``{option}" in text, f"{option} of feedrot {name} is not in cli.rst"


# Output files: checked first, never lost ------------------------------------------------------


NATURAL = ["natural", "EFLSBERG", "--source", SOURCE, *SPAN]


def listing(directory):
    """Names and bytes of every file in a directory (temporary files included)."""
    return {path.name: path.read_bytes() for path in directory.iterdir() if path.is_file()}


@pytest.mark.parametrize("option, name", [("-o", "out.ecsv"), ("--plot", "out.png")])
def test_existing_output_needs_overwrite(capsys, tmp_path, option, name):
    if option == "--plot":
        pytest.importorskip("matplotlib")
    path = tmp_path / name
    path.write_bytes(b"precious")
    status, out, err = run(capsys, *NATURAL, option, str(path))
    assert status == 1 and out == ""
    assert err == (f"feedrot: error: {'-o/--output' if option == '-o' else '--plot'}: "
                   f"{str(path)!r} exists; add --overwrite to replace it, or choose another "
                   "name\n")
    assert listing(tmp_path) == {name: b"precious"}
    status, _, err = run(capsys, *NATURAL, option, str(path), "--overwrite")
    assert status == 0, err
    assert set(listing(tmp_path)) == {name} and path.read_bytes() != b"precious"


def test_replaced_file_keeps_its_mode_new_file_follows_umask(capsys, tmp_path):
    old = tmp_path / "old.ecsv"
    old.write_text("x")
    old.chmod(0o640)
    assert run(capsys, *NATURAL, "-o", str(old), "--overwrite")[0] == 0
    assert stat.S_IMODE(old.stat().st_mode) == 0o640
    umask = os.umask(0o027)
    try:
        assert run(capsys, *NATURAL, "-o", str(tmp_path / "new.ecsv"))[0] == 0
    finally:
        os.umask(umask)
    assert stat.S_IMODE((tmp_path / "new.ecsv").stat().st_mode) == 0o640


def test_symbolic_link_output_is_written_through(capsys, tmp_path):
    target = tmp_path / "target.ecsv"
    target.write_text("old")
    link = tmp_path / "link.ecsv"
    link.symlink_to(target)
    assert run(capsys, *NATURAL, "-o", str(link), "--overwrite")[0] == 0
    assert link.is_symlink() and len(Table.read(target)) == 5


@pytest.fixture
def catalogue_file(tmp_path):
    from astropy_feedrot.data import sample_file

    path = tmp_path / "mine.ecsv"
    path.write_bytes(sample_file("stations.ecsv").read_bytes())
    return path


@pytest.mark.parametrize("how", ["same path", "other spelling", "symbolic link", "hard link"])
def test_never_writes_over_an_input(capsys, tmp_path, catalogue_file, how):
    before = catalogue_file.read_bytes()
    output = {"same path": catalogue_file,
              "other spelling": tmp_path / "sub" / ".." / "mine.ecsv",
              "symbolic link": tmp_path / "link.ecsv",
              "hard link": tmp_path / "hard.ecsv"}[how]
    (tmp_path / "sub").mkdir()
    if how == "symbolic link":
        output.symlink_to(catalogue_file)
    elif how == "hard link":
        os.link(catalogue_file, output)
    status, _, err = run(capsys, *NATURAL, "--catalogue", str(catalogue_file), "-o", str(output),
                         "--overwrite")
    assert status == 1
    assert err == (f"feedrot: error: -o/--output: {str(output)!r} is the --catalogue input, "
                   "which is never overwritten; choose another name\n")
    assert catalogue_file.read_bytes() == before


def test_never_writes_over_the_embedded_catalogue(capsys):
    from astropy_feedrot.data import sample_file

    path = sample_file("stations.ecsv")
    before = path.read_bytes()
    status, _, err = run(capsys, *NATURAL, "-o", str(path), "--overwrite")
    assert status == 1 and "is the embedded station catalogue input" in err
    assert path.read_bytes() == before


def test_orbit_input_is_never_an_output(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    sp3 = tmp_path / "orbit.sp3"
    from astropy_feedrot.data import sample_file

    sp3.write_bytes(sample_file("sample.sp3").read_bytes())
    alias = tmp_path / "orbit.png"
    alias.symlink_to(sp3)
    status, _, err = run(capsys, "satellite", "FD-VLBA", "--sp3", str(sp3), "--sat", "G01",
                         "--points", "4", "--plot", str(alias), "--overwrite")
    assert status == 1 and f"--plot: {str(alias)!r} is the --sp3 input" in err
    assert sp3.read_bytes() == sample_file("sample.sp3").read_bytes()


def test_table_and_figure_never_share_a_file(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    table = tmp_path / "t.ecsv"
    table.write_text("old")
    figure = tmp_path / "t.png"
    os.link(table, figure)
    status, _, err = run(capsys, *NATURAL, "-o", str(table), "--plot", str(figure), "--overwrite")
    assert status == 1
    assert err == (f"feedrot: error: --plot and -o/--output name the same file {str(figure)!r}; "
                   "each needs its own\n")
    assert table.read_text() == "old"


@pytest.mark.parametrize("argv, match", [
    # Computation fails after every check: the SP3 file does not cover the span.
    (["satellite", "FD-VLBA", "--sp3", "SP3", "--sat", "G01", "--points", "4",
      "--start", "2023-01-26", "--stop", "2023-01-26T01:00"],
     r"times outside the coverage of the SP3 orbit of G01"),
    # A value refused after the outputs were checked.
    (["baseline", "DBR205", "FD-VLBA", "--source", SOURCE, *SPAN, "--frequency", "0"],
     r"--frequency must be positive"),
    (["baseline", "DBR205", "FD-VLBA", "--source", SOURCE, *SPAN, "--frequency", "1GHz",
      "--polarization", "LCP", "--min-elevation", "91"], r"--min-elevation"),
])
def test_failed_run_leaves_files_as_they_were(capsys, tmp_path, argv, match):
    pytest.importorskip("matplotlib")
    from astropy_feedrot.data import sample_file

    argv = [str(sample_file("sample.sp3")) if arg == "SP3" else arg for arg in argv]
    (tmp_path / "out.ecsv").write_bytes(b"old table")
    (tmp_path / "out.png").write_bytes(b"old figure")
    status, out, err = run(capsys, *argv, "-o", str(tmp_path / "out.ecsv"), "--plot",
                           str(tmp_path / "out.png"), "--overwrite")
    assert status == 1 and out == "" and re.search(match, err), err
    assert listing(tmp_path) == {"out.ecsv": b"old table", "out.png": b"old figure"}


@pytest.mark.skipif(shutil.which("xelatex") is not None, reason="xelatex draws .pgf figures")
def test_failed_figure_leaves_the_table_as_it_was(capsys, tmp_path):
    # A .pgf figure needs LaTeX: drawing fails after the table was written
    # to its temporary file; neither file changes and nothing is left behind.
    pytest.importorskip("matplotlib")
    (tmp_path / "out.ecsv").write_bytes(b"old table")
    status, out, err = run(capsys, *NATURAL, "-o", str(tmp_path / "out.ecsv"), "--plot",
                           str(tmp_path / "out.pgf"), "--overwrite")
    assert status == 1 and out == ""
    assert err.startswith(f"feedrot: error: --plot: cannot draw {str(tmp_path / 'out.pgf')!r}: ")
    assert "xelatex" in err and err.count("\n") == 1
    assert listing(tmp_path) == {"out.ecsv": b"old table"}


def test_failed_figure_writes_nothing_to_standard_output(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    if shutil.which("xelatex") is not None:
        pytest.skip("xelatex draws .pgf figures")
    status, out, _ = run(capsys, *NATURAL, "--plot", str(tmp_path / "out.pgf"))
    assert status == 1 and out == "" and listing(tmp_path) == {}


def test_demo_twice_asks_for_overwrite(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    assert run(capsys, "demo", "--output-dir", str(tmp_path), "--step", "30min")[0] == 0
    before = listing(tmp_path)
    assert set(before) == {"feedrot_demo.ecsv", "feedrot_demo.png"}
    status, out, err = run(capsys, "demo", "--output-dir", str(tmp_path), "--step", "30min")
    assert status == 1 and out == ""
    assert err == (f"feedrot: error: --output-dir: {str(tmp_path / 'feedrot_demo.ecsv')!r} "
                   "exists; add --overwrite to replace it, or choose another --output-dir\n")
    assert listing(tmp_path) == before
    status, _, err = run(capsys, "demo", "--output-dir", str(tmp_path), "--step", "20min",
                         "--overwrite")
    assert status == 0, err
    assert len(Table.read(tmp_path / "feedrot_demo.ecsv")) == 34  # 06:00-17:00 every 20 min


def test_demo_epochs_are_capped(capsys, tmp_path):
    status, _, err = run(capsys, "demo", "--output-dir", str(tmp_path), "--step", "1ms")
    assert status == 1
    assert err == ("feedrot: error: --step 1ms gives 3.96e+07 epochs over the 11 hours of the "
                   "demo, more than the 1000000 of one run; use a larger --step\n")
    assert listing(tmp_path) == {}


@pytest.mark.parametrize("argv, match", [
    ([*NATURAL, "-o", "out.txt"], r"-o/--output: cannot tell a format from the extension of "
     r"'.*out.txt'; use one of .ecsv, .csv, .fits, .fit, .fts, .hdf5, .h5, .html$"),
    ([*NATURAL, "-o", "out"], r"-o/--output: cannot tell a format from the extension"),
    ([*NATURAL, "-o", "out.ecsv.gz"], r"-o/--output: cannot tell a format from the extension"),
    ([*NATURAL, "--plot", "figure.ecsv"], r"--plot: cannot tell a format from the extension of "
     r"'.*figure.ecsv'; use one of .*\.pdf.*\.png.*\.svg"),
    ([*NATURAL, "--plot", "figure"], r"--plot: cannot tell a format"),
])
def test_output_format_follows_the_extension(capsys, tmp_path, argv, match):
    pytest.importorskip("matplotlib")
    argv = [str(tmp_path / arg) if arg.startswith(("out", "figure")) else arg for arg in argv]
    status, out, err = run(capsys, *argv)
    assert status == 1 and out == "" and err.count("\n") == 1
    assert re.search(match, err.strip()), err
    assert listing(tmp_path) == {}


def test_output_that_is_not_a_regular_file(capsys, tmp_path):
    fifo = tmp_path / "pipe.ecsv"
    os.mkfifo(fifo)
    status, _, err = run(capsys, *NATURAL, "-o", str(fifo), "--overwrite")
    assert status == 1
    assert err == f"feedrot: error: -o/--output: {str(fifo)!r} is not a regular file\n"


def test_table_formats_are_those_astropy_identifies():
    from astropy.io import registry

    from astropy_feedrot.cli import TABLE_FORMATS

    for extension, fmt in TABLE_FORMATS.items():
        assert registry.identify_format("write", Table, "x" + extension, None, [], {}) == [fmt]


def test_hdf5_needs_h5py(capsys, tmp_path):
    if importlib.util.find_spec("h5py") is not None:
        pytest.skip("h5py is installed")
    status, _, err = run(capsys, *NATURAL, "-o", str(tmp_path / "t.h5"))
    assert status == 1
    assert err == "feedrot: error: -o/--output: writing .h5 files needs h5py (pip install h5py)\n"


def _read_back(path, extension):
    """A written table read with astropy, its time column as Time and units attached."""
    if extension in (".fits", ".fit", ".fts"):
        return Table.read(path, astropy_native=True)
    if extension in (".hdf5", ".h5"):
        return Table.read(path, path="feedrot")
    if extension == ".html":
        pytest.importorskip("bs4")
    table = Table.read(path, format={".csv": "ascii.csv", ".html": "ascii.html",
                                     ".ecsv": "ascii.ecsv"}[extension])
    if extension in (".csv", ".html"):
        # Values only: ISO UTC times and plain numbers.
        table["time"] = Time(list(table["time"]), scale="utc")
    return table


@pytest.mark.parametrize("extension", [".ecsv", ".csv", ".fits", ".fit", ".fts", ".hdf5", ".h5",
                                       ".html"])
@pytest.mark.parametrize("kind", ["natural", "baseline"])
def test_every_format_reads_back_to_the_ecsv_values(capsys, tmp_path, extension, kind):
    if extension in (".hdf5", ".h5"):
        pytest.importorskip("h5py")
    argv = (NATURAL if kind == "natural" else
            ["baseline", "DBR205", "FD-VLBA", "--source", SOURCE, *SPAN, "--frequency", "8.4GHz",
             "--min-elevation", "30"])
    status, out, err = run(capsys, *argv)
    assert status == 0, err
    reference = read(out)
    path = tmp_path / f"table{extension}"
    status, _, err = run(capsys, *argv, "-o", str(path))
    # One line on success: the file, as named, and what it holds.
    assert status == 0 and err.startswith(f"feedrot: {path}: {len(reference)} rows of the "
                                          "feed rotation of ") and err.count("\n") == 1, err
    assert set(listing(tmp_path)) == {path.name}
    table = _read_back(path, extension)
    assert table.colnames == reference.colnames
    assert np.all(np.abs((Time(table["time"]) - reference["time"]).to_value(u.s)) < 1e-3)
    for name in reference.colnames[1:]:
        expected = reference[name]
        if expected.dtype == bool:
            assert [str(v) for v in table[name]] == [str(v) for v in expected], name
            continue
        values = np.asarray(table[name], dtype=float)
        assert np.array_equal(np.isnan(values), np.isnan(expected)), name
        assert np.allclose(values, expected, rtol=1e-12, atol=0, equal_nan=True), name
        if extension in (".ecsv", ".fits", ".fit", ".fts", ".hdf5", ".h5"):
            assert table[name].unit == expected.unit, name
    if extension in (".fits", ".fit", ".fts", ".hdf5", ".h5"):
        assert table["time"].scale == "utc"
        assert table.meta.get("antenna", table.meta.get("ANTENNA")) == reference.meta.get(
            "antenna")


# The satellite's hand is its own -------------------------------------------------------------


SATELLITE_SPAN = ["--start", "2023-01-25T09:00", "--stop", "2023-01-25T11:00", "--step", "30min"]


def test_receiver_of_the_other_hand_is_refused(capsys, tle_file):
    for argv in (["satellite", "DBR205", "--tle", str(tle_file)],
                 ["baseline", "DBR205", "FD-VLBA", "--tle", str(tle_file), "--frequency", "1GHz"]):
        status, out, err = run(capsys, *argv, *SATELLITE_SPAN, "--polarization", "LCP")
        assert status == 1 and out == ""
        assert err == ("feedrot: error: an LCP receiver (--polarization LCP) does not receive "
                       "the RCP signal of the satellite; leave --polarization unset or give "
                       "--polarization RCP (--satellite-polarization sets the satellite's hand, "
                       "RCP by default as for GNSS)\n")
        status, _, err = run(capsys, *argv, *SATELLITE_SPAN, "--polarization", "RCP",
                             "--satellite-polarization", "LCP")
        assert status == 1
        assert "an RCP receiver (--polarization RCP) does not receive the LCP" in err


def test_lcp_satellite_and_receiver(capsys, tle_file):
    argv = ["satellite", "DBR205", "--tle", str(tle_file), *SATELLITE_SPAN]
    rcp = read(run(capsys, *argv)[1])
    assert rcp.meta["polarization"] == "RCP"
    for extra in (["--satellite-polarization", "LCP"],
                  ["--satellite-polarization", "lcp", "--polarization", "LCP"]):
        status, out, err = run(capsys, *argv, *extra)
        assert status == 0, err
        lcp = read(out)
        assert lcp.meta["polarization"] == "LCP"
        # Appendix D: the LCP feed rotation is the RCP one with the opposite sign.
        for name in ("transmitter", "receiver", "total"):
            assert np.allclose(lcp[name], -rcp[name], atol=1e-9), name


@pytest.mark.parametrize("extra, match", [
    (["--satellite-polarization", "LCP"], r"give one target: a natural source or a satellite, "
     r"not both \(--source and --satellite-polarization\)"),
    (["--tle", "gps.tle"], r"not both \(--source and --tle\)"),
    (["--sat", "G01"], r"not both \(--source and --sat\)"),
])
def test_baseline_target_is_natural_or_a_satellite(capsys, extra, match):
    status, _, err = run(capsys, "baseline", "DBR205", "FD-VLBA", "--source", SOURCE, *SPAN,
                         "--frequency", "1GHz", *extra)
    assert status == 1 and re.search(match, err), err


def test_sp3_span_defaults_to_the_file_in_utc(capsys):
    from astropy_feedrot.data import sample_file

    status, out, err = run(capsys, "satellite", "FD-VLBA", "--sp3",
                           str(sample_file("sample.sp3")), "--sat", "G01", "--points", "4",
                           "--step", "15min")
    assert status == 0, err
    times = read(out)["time"]
    assert times.scale == "utc" and len(times) == 4
    # The file starts at 2023-01-25 00:00:00 GPS time = TAI - 19 s = UTC + 18 s.
    assert times[0].isot == "2023-01-24T23:59:42.000"


def test_start_now(capsys):
    status, out, err = run(capsys, "natural", "EFLSBERG", "--source", SOURCE, "--start", "now",
                           "--stop", "now")
    assert status == 0, err
    # The bundled Earth-orientation tables may be old: at most one warning line.
    assert err == "" or (err.startswith("feedrot: warning: computed anyway") and
                         err.count("\n") == 1)
    table = read(out)
    assert len(table) == 1
    assert abs((Time(table["time"][0]) - Time.now()).to_value(u.s)) < 600


def test_table_metadata_names_the_source_not_its_frame(capsys):
    # A SkyCoord's .name is the name of its frame ('icrs'), not of the source.
    status = main(["natural", "EFLSBERG", "--source", "03h19m48.16s +41d30m42.1s",
                   "--start", "2023-01-25T18:00", "--stop", "2023-01-25T19:00", "--step", "1h"])
    assert status == 0
    table = Table.read(capsys.readouterr().out, format="ascii.ecsv")
    assert table.meta["target"] == "03h19m48.16s +41d30m42.1s (icrs)"


def test_correct_says_what_it_wrote_in_one_line(tmp_path, capsys, monkeypatch):
    pytest.importorskip("pyuvdata")
    from astropy_feedrot.data import sample_file

    # As feedrot rinex does: one line on standard error on success, with the
    # conventions used; the output named as given (relative here).
    monkeypatch.chdir(tmp_path)
    source = str(sample_file("vla_day2_8chan.uvfits"))
    assert main(["correct", source, "-o", "vla_c.uvfits", "--vertical", "geocentric"]) == 0
    out, err = capsys.readouterr()
    summary = [line for line in err.splitlines() if not line.startswith("feedrot: warning:")]
    assert out == "" and summary == [
        f"feedrot: vla_c.uvfits: feed rotation removed from {source} (rigorous convention: "
        "vertical geocentric, pole itrs; frame apparent)"]
    assert main(["correct", source, "-o", "vla_casa.uvfits", "--convention", "casa"]) == 0
    assert (f"feedrot: vla_casa.uvfits: feed rotation removed from {source} (casa "
            "convention: vertical geocentric, pole casa; frame apparent)"
            ) in capsys.readouterr().err.splitlines()
    assert main(["correct", source, "-o", "vla_q.uvfits", "--quiet"]) == 0
    assert not [line for line in capsys.readouterr().err.splitlines()
                if not line.startswith("feedrot: warning:")]


def test_demo_makes_its_output_folder(tmp_path, capsys):
    folder = tmp_path / "results" / "today"
    status, out, err = run(capsys, "demo", "--output-dir", str(folder), "--step", "30min")
    assert status == 0, err
    assert (folder / "feedrot_demo.ecsv").is_file()
