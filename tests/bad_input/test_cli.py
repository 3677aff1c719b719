# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The command line, probed as a hostile user would: every refusal is one line.

Each subcommand (natural, satellite, baseline, faraday, stations, demo) gets absurd
steps, spans and times, frames that need an observer, sites off the Earth,
unreadable, empty, binary and directory inputs, wrong units and unknown
choices. Each must end with a non-zero exit status and exactly one line on
standard error starting ``feedrot: error:`` (the message matched), nothing on
standard output, no traceback and no internal error; property-based tests
throw arbitrary text and combinations of bad values at every option.
"""

import os
import re
import subprocess
import sys

import pytest
from astropy import units as u
from astropy.table import QTable, Table
from astropy.time import Time
from hypothesis import HealthCheck, given, settings, strategies as st

import astropy_feedrot.cli.common
import astropy_feedrot.cli.tables
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
from astropy_feedrot.cli import CELESTIAL_FRAMES, main
from astropy_feedrot.data import sample_file

SOURCE = "03h19m48.16s +41d30m42.1s"  # 3C 84
SPAN = ["--start", "2023-01-25T18:00", "--stop", "2023-01-25T22:00", "--step", "1h"]
SAT_SPAN = ["--start", "2023-01-25T09:00", "--stop", "2023-01-25T11:00", "--step", "1h"]

FAST = settings(max_examples=30, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture])


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """Inputs good and bad: {placeholder: path}."""
    root = tmp_path_factory.mktemp("inputs")
    tle = root / "gps.tle"
    tle.write_text("GPS SVN 76\n" + "\n".join(GPS_SVN76_TLE) + "\n")
    empty = root / "empty.txt"
    empty.write_bytes(b"")
    garbage = root / "garbage.bin"
    garbage.write_bytes(bytes(range(256)) * 8 + b"\xff\xfe\x00" * 100)
    directory = root / "a-directory"
    directory.mkdir()
    (root / "out").mkdir()
    rm = root / "rm.ecsv"  # rotation measures for feedrot faraday, over SPAN
    QTable({"time": Time(["2023-01-25T00:00", "2023-01-26T00:00"]),
            "rm": [0.5, 1.5] * u.rad / u.m**2}).write(rm)
    return {"{RM}": rm, "{TLE}": tle, "{EMPTY}": empty, "{GARBAGE}": garbage, "{DIR}": directory,
            "{MISSING}": root / "missing.txt", "{SP3}": sample_file("sample.sp3"),
            "{OBX}": sample_file("sample.obx"), "{OUT}": root / "out"}


def run(capsys, files, argv):
    argv = [str(files[arg]) if arg in files else arg for arg in argv]
    status = main(argv)
    out, err = capsys.readouterr()
    return status, out, err


def assert_one_line_error(status, out, err, match, usage=False):
    assert status == (2 if usage else 1), err
    assert out == ""
    assert err.startswith("feedrot: error: ") and err.endswith("\n") and err.count("\n") == 1, err
    assert "Traceback" not in err and "internal error" not in err, err
    assert re.search(match, err), err


NATURAL = ["natural", "EFLSBERG", "--source", SOURCE, *SPAN]
SATELLITE = ["satellite", "DBR205", "--tle", "{TLE}", *SAT_SPAN]
SP3 = ["satellite", "FD-VLBA", "--sp3", "{SP3}", "--sat", "G01", "--points", "4"]
BASELINE = ["baseline", "DBR205", "FD-VLBA", "--frequency", "1GHz", "--source", SOURCE, *SPAN]
BASELINE_SAT = ["baseline", "DBR205", "FD-VLBA", "--frequency", "1GHz", "--tle", "{TLE}",
                *SAT_SPAN]
FARADAY = ["faraday", "EFLSBERG", "--source", SOURCE, *SPAN, "--rm-table", "{RM}",
           "--frequency", "1.4GHz"]
TIMED = {"natural": NATURAL, "satellite": SATELLITE, "baseline": BASELINE,
         "baseline-satellite": BASELINE_SAT, "faraday": FARADAY}

#: Options any timed command refuses, with the message.
TIMED_CASES = [
    (["--step", "0"], r"--step must be positive and finite, got '0'"),
    (["--step=-1s"], r"--step must be positive and finite, got '-1s'"),
    (["--step", "-1s"], r"argument --step: expected one argument \(write --option=VALUE"),
    (["--step", "nan"], r"--step must be positive and finite, got 'nan'"),
    (["--step", "inf"], r"--step must be positive and finite, got 'inf'"),
    (["--step=-inf"], r"--step must be positive and finite"),
    (["--step", "1e-9 s"], r"--step 1e-9 s gives 7.2e\+12 epochs|--step 1e-9 s gives 1.44e\+13"),
    (["--step", "1e-300s"], r"--step 1e-300s gives .*e\+30\d epochs from --start to --stop, more "
     r"than the 1000000 of one run; use a larger --step or a shorter span"),
    (["--step", "abc"], r"--step: cannot read 'abc' as a number with a unit \(e.g. 30s, 10min\)"),
    (["--step", "10 parsec"], r"--step: '10 parsec' is not in a unit of time"),
    (["--step", "[1, 2] s"], r"--step: cannot read|--step: give one value"),
    (["--start", "1900-01-01", "--stop", "2100-01-01", "--step", "1s"],
     r"epochs from --start to --stop, more than the 1000000 of one run"),
    (["--start", "2023-01-25T18:00", "--stop", "2023-01-25T17:00"],
     r"--stop \(2023-01-25T17:00:00.000\) is before --start \(2023-01-25T18:00:00.000\)"),
    (["--start", "now", "--stop", "2000-01-01"], r"--stop \(2000-01-01T00:00:00.000\) is before"),
    (["--start", "2023-02-30"], r"--start: cannot read '2023-02-30' as a time; use ISO format"),
    (["--start", "2023-13-45"], r"--start: cannot read '2023-13-45' as a time"),
    (["--stop", "tomorrow"], r"--stop: cannot read 'tomorrow' as a time"),
    (["--start", "2023-01-01 00:00 +0200"], r"--start: cannot read"),
    (["--min-elevation", "nan"], r"--min-elevation must be one angle within \[-90, 90\] deg, "
     r"got 'nan'"),
    (["--min-elevation", "100"], r"--min-elevation must be one angle within \[-90, 90\] deg"),
    (["--min-elevation=-91"], r"--min-elevation must be one angle within"),
    (["--min-elevation", "inf"], r"--min-elevation must be one angle within"),
    (["--min-elevation", "1 parsec"], r"--min-elevation: '1 parsec' is not an angle"),
    (["--min-elevation", "abc"], r"--min-elevation: cannot read 'abc' as an angle"),
    (["--polarization", "XX"], r"argument --polarization: invalid choice: 'XX'.*see 'feedrot "),
    (["--catalogue", "{EMPTY}"], r"empty.txt.*ECSV"),
    (["--catalogue", "{GARBAGE}"], r"--catalogue: .*garbage.bin' is not a text file"
     r"|garbage.bin.*not a readable ECSV"),
    (["--catalogue", "{DIR}"], r"--catalogue: '.*a-directory' is a directory, not a file"),
    (["--catalogue", "{MISSING}"], r"--catalogue: no such file '.*missing.txt'"),
    (["--catalogue", "{TLE}"], r"gps.tle.*ECSV"),
    (["-o", "{DIR}"], r"-o/--output: '.*a-directory' is a directory"),
    (["-o", "{MISSING}"], r"-o/--output: cannot tell a format from the extension of "
     r"'.*missing.txt'; use one of .ecsv"),
    (["-o", "/nonexistent/x.ecsv"], r"-o/--output: cannot write '/nonexistent/x.ecsv': directory "
     r"'/nonexistent' does not exist"),
    (["--bogus"], r"unrecognized arguments: --bogus"),
]


@pytest.mark.parametrize("command", TIMED)
@pytest.mark.parametrize("extra, match", TIMED_CASES)
def test_timed_commands(capsys, files, command, extra, match):
    if command == "faraday" and "--polarization" in extra:
        # The plane's rotation has no hand: faraday has no --polarization.
        match = r"unrecognized arguments: --polarization"
    status, out, err = run(capsys, files, [*TIMED[command], *extra])
    usage = "argument" in match or "unrecognized" in match
    assert_one_line_error(status, out, err, match, usage=usage)


NATURAL_CASES = [
    (["--frame", "altaz"], r"--frame 'altaz': a frame tied to an observing time or place; give "
     r"the coordinates in a celestial frame: " + ", ".join(CELESTIAL_FRAMES) + "$"),
    (["--frame", "hadec"], r"--frame 'hadec': a frame tied to an observing time or place"),
    (["--frame", "gcrs"], r"--frame 'gcrs': a frame tied to an observing time or place"),
    (["--frame", "itrs"], r"--frame 'itrs': a frame tied"),
    (["--frame", "nonsense"], r"--frame 'nonsense': unknown frame; give the coordinates in a "
     r"celestial frame: icrs, fk5"),
    (["--frame", ""], r"--frame '': unknown frame"),
    (["--source", "3C 84"], r"--source: cannot read '3C 84' as coordinates .*needs the internet"),
    (["--source", "1d 200d"], r"--source: cannot read '1d 200d' as coordinates \(.*200d.*dec\)"),
    (["--source", "nan nan"], r"--source: cannot read 'nan nan'"),
    (["--source", "1.E400"], r"--source: cannot read '1.E400' as coordinates"),
    (["--source", "1e400 1e400"], r"--source: (cannot read|the coordinates '1e400 1e400' are "
                                  r"not finite)"),
    (["--source", "[1, 2] [3, 4]"], r"--source: cannot read|--source: give one source"),
    (["--source", ""], r"--source: cannot read ''"),
    (["--source", SOURCE, "--tle", "{TLE}"], r"give one target: a natural source or a satellite, "
     r"not both \(--source and --tle\)"),
]


@pytest.mark.parametrize("command", ["natural", "baseline", "faraday"])
@pytest.mark.parametrize("extra, match", NATURAL_CASES)
def test_natural_targets(capsys, files, command, extra, match):
    base = TIMED[command]
    if "--tle" in extra and command in ("natural", "faraday"):
        match = r"unrecognized arguments: --tle"
    status, out, err = run(capsys, files, [*base, *extra])
    assert_one_line_error(status, out, err, match, usage="unrecognized" in match)


@pytest.mark.parametrize("argv, match", [
    (["natural", "EFLSBERG", "--ra", "nan", "--dec", "0", *SPAN], r"--ra/--dec: cannot read "),
    (["natural", "EFLSBERG", "--ra", "1", "--dec", "91", *SPAN], r"--ra/--dec: cannot read "),
    (["natural", "EFLSBERG", "--dec", "10", *SPAN], r"with both --ra and --dec"),
    (["natural", "EFLSBERG", *SPAN], r"give the source with --source, or with both --ra and "),
])
def test_ra_dec(capsys, files, argv, match):
    assert_one_line_error(*run(capsys, files, argv), match)


SITES = [
    ("nan,nan,nan", r"site 'nan,nan,nan': LAT, LON and HEIGHT must be finite numbers"),
    ("inf,0,0", r"site 'inf,0,0': LAT, LON and HEIGHT must be finite numbers"),
    ("0,0,-inf", r"site '0,0,-inf': LAT, LON and HEIGHT must be finite numbers"),
    ("-nan,0,0", r"site '-nan,0,0': LAT, LON and HEIGHT must be finite"),
    ("91,0,0", r"latitude 91 of site '91,0,0' is not in \[-90, 90\] deg; the order is "
     r"LAT,LON,HEIGHT"),
    ("-90.5,0,0", r"latitude -90.5 of site '-90.5,0,0' is not in \[-90, 90\] deg"),
    ("45,400,0", r"longitude 400 of site '45,400,0' is not in \[-180, 360\] deg"),
    ("45,-181,0", r"longitude -181 of site '45,-181,0' is not in \[-180, 360\] deg"),
    ("45,0,1e9", r"site '45,0,1e9': .*height"),
    ("0,0,-7e6", r"site '0,0,-7e6': .*height"),
    ("45,0", r"site '45,0': expected LAT,LON,HEIGHT in degrees, degrees and metres, e.g. "),
    ("1,2,3,4", r"site '1,2,3,4': expected LAT,LON,HEIGHT"),
    ("a,b,c", r"site 'a,b,c': expected LAT,LON,HEIGHT"),
    (",,", r"site ',,': expected LAT,LON,HEIGHT"),
    ("NOWHERE", r"unknown antenna 'NOWHERE'"),
    ("", r"unknown antenna ''"),
]


@pytest.mark.parametrize("site, match", SITES)
@pytest.mark.parametrize("command", ["natural", "satellite", "baseline", "faraday"])
def test_sites(capsys, files, site, match, command):
    base = TIMED[command]
    argv = ([base[0], site, *base[2:]] if command != "baseline" else
            [base[0], "DBR205", site, *base[3:]])
    assert_one_line_error(*run(capsys, files, argv), match)


@pytest.mark.parametrize("extra, match", [
    (["--mount", "FOO"], r"--mount: unknown geodetic mount label 'FOO'.*'AZEL'"),
    (["--mount", ""], r"--mount: unknown geodetic mount label ''"),
    (["--focus", "FOO"], r"--focus: unknown focus 'FOO'; expected one of prime"),
    (["--focus", "nasmyth-left", "--mount", "EQUA"], r"."),
])
def test_mount_and_focus_of_a_site(capsys, files, extra, match):
    argv = ["natural", "40,-3,900", "--source", SOURCE, *SPAN, *extra]
    status, out, err = run(capsys, files, argv)
    if match == ".":
        # A Nasmyth focus on an equatorial mount: refused or computed, never a traceback.
        assert status == 0 or (status == 1 and err.count("\n") == 1), err
        return
    assert_one_line_error(status, out, err, match)
    assert_one_line_error(*run(capsys, files, ["natural", "EFLSBERG", *argv[2:]]),
                          r"--mount and --focus go with a site LAT,LON,HEIGHT, not with the "
                          r"catalogue station 'EFLSBERG'")


ORBIT_FILES = [
    ("{EMPTY}", r"empty.txt.*(empty|end of file)"),
    ("{GARBAGE}", r"garbage.bin"),
    ("{DIR}", r"'.*a-directory' is a directory, not a file"),
    ("{MISSING}", r"no such file '.*missing.txt'"),
]


@pytest.mark.parametrize("option", ["--tle", "--sp3", "--orbex"])
@pytest.mark.parametrize("path, match", ORBIT_FILES)
@pytest.mark.parametrize("command", ["satellite", "baseline"])
def test_orbit_and_attitude_files(capsys, files, option, path, match, command):
    base = ["satellite", "FD-VLBA"] if command == "satellite" else [*BASELINE_SAT[:5]]
    argv = {"--tle": [*base, "--tle", path, *SAT_SPAN],
            "--sp3": [*base, "--sp3", path, "--sat", "G01"],
            "--orbex": [*base, "--sp3", "{SP3}", "--sat", "G01", "--points", "4",
                        "--orbex", path]}[option]
    if command == "baseline":
        argv = [a for a in argv if a not in ("--tle", "{TLE}")] if option != "--tle" else argv
    assert_one_line_error(*run(capsys, files, argv), match)


@pytest.mark.parametrize("extra, match", [
    (["--points", "0"], r"--points must be at least 2 \(epochs of the interpolation window\), "
     r"got 0"),
    (["--points", "1"], r"--points must be at least 2"),
    (["--points=-3"], r"--points must be at least 2 .*got -3"),
    (["--points", "1000000"], r"--sp3: the SP3 file has 4 epochs, fewer than the 1000000 points"),
    (["--points", "abc"], r"argument --points: invalid int value: 'abc'"),
    (["--points", "1e6"], r"argument --points: invalid int value: '1e6'"),
    (["--sat", "G99"], r"satellite 'G99' is not in the SP3 file; it has G01, G05, E11"),
    (["--start", "2023-01-26", "--stop", "2023-01-26T01:00"],
     r"times outside the coverage of the SP3 orbit of G01"),
    (["--tle", "{TLE}"], r"--tle goes alone|--sp3 goes with|goes with --sp3"),
    (["--polarization", "LCP"], r"an LCP receiver \(--polarization LCP\) does not receive the "
     r"RCP signal of the satellite"),
    (["--satellite-polarization", "XX"], r"argument --satellite-polarization: invalid choice"),
])
def test_sp3_options(capsys, files, extra, match):
    # Later options replace earlier ones: --points, --sat and the span.
    status, out, err = run(capsys, files, [*SP3, *extra])
    assert_one_line_error(status, out, err, match, usage="argument" in match)


@pytest.mark.parametrize("extra, match", [
    (["--points", "4"], r"--points goes with --sp3; --tle is the other orbit source"),
    (["--orbex", "{OBX}"], r"--orbex goes with --sp3"),
    (["--sp3", "{SP3}"], r"--sp3 goes with --sp3|--tle is the other orbit source"),
    (["--sat", "NOPE"], r"--sat 'NOPE' is not in .*gps.tle; it has GPS SVN 76 \(41328\)"),
    (["--polarization", "LCP"], r"an LCP receiver \(--polarization LCP\) does not receive"),
    (["--satellite-polarization", "LCP", "--polarization", "RCP"],
     r"an RCP receiver \(--polarization RCP\) does not receive the LCP signal"),
])
@pytest.mark.parametrize("command", ["satellite", "baseline-satellite"])
def test_tle_options(capsys, files, extra, match, command):
    assert_one_line_error(*run(capsys, files, [*TIMED[command], *extra]), match)


@pytest.mark.parametrize("frequency, match", [
    ("0", r"--frequency must be positive and finite, got '0'"),
    ("10m", r"--frequency: '10m' is not in a unit of frequency"),
    ("nan", r"--frequency must be positive and finite, got 'nan'"),
    ("inf", r"--frequency must be positive and finite, got 'inf'"),
    ("=-1GHz", r"--frequency must be positive and finite, got '-1GHz'"),
    ("abc", r"--frequency: cannot read 'abc' as a number with a unit \(e.g. 1575.42MHz"),
    ("1 parsec", r"--frequency: '1 parsec' is not in a unit of frequency"),
])
@pytest.mark.parametrize("command", ["baseline", "baseline-satellite"])
def test_baseline_frequency(capsys, files, frequency, match, command):
    base = [a for a in TIMED[command] if a not in ("--frequency", "1GHz")]
    option = (["--frequency" + frequency] if frequency.startswith("=") else
              ["--frequency", frequency])
    assert_one_line_error(*run(capsys, files, [*base, *option]), match)


@pytest.mark.parametrize("first, second, name", [
    ("DBR205", "DBR205", "DBR205"),
    ("DBR205", "dbr-205", "DBR205"),
    ("40,0,0", "40.0,0,0", "site 40,0,0"),
    ("-33,148.5,415", "-33.000,148.50,415.0", "site -33,148.5,415"),
])
def test_duplicated_antenna(capsys, files, first, second, name):
    argv = ["baseline", first, second, "--source", SOURCE, *SPAN, "--frequency", "1GHz"]
    assert_one_line_error(*run(capsys, files, argv),
                          rf"the two antennas of a baseline must differ; both are '{name}'")


@pytest.mark.parametrize("argv, match", [
    (["--step", "1ms"], r"--step 1ms gives 3.96e\+07 epochs over the 11 hours of the demo, more "
     r"than the 1000000 of one run; use a larger --step"),
    (["--step", "1e-9 s"], r"--step 1e-9 s gives 3.96e\+13 epochs"),
    (["--step", "0"], r"--step must be positive and finite, got '0'"),
    (["--step", "nan"], r"--step must be positive and finite, got 'nan'"),
    (["--step=-1min"], r"--step must be positive and finite"),
    (["--step", "abc"], r"--step: cannot read 'abc'"),
    (["--step", "10 parsec"], r"--step: '10 parsec' is not in a unit of time"),
    (["--step", "12h"], r"the target is never above the elevation limit at both antennas"),
    (["--output-dir", "/dev/null/results"], r"--output-dir: cannot make "
     "'/dev/null/results': Not a directory"),
    (["--output-dir", "{TLE}"], r"--output-dir: '.*gps.tle' is not a directory"),
    (["--output", "x"], r"unrecognized arguments: --output x|ambiguous option: --output"),
])
def test_demo(capsys, files, argv, match):
    argv = ["demo", "--output-dir", "{OUT}", *argv]
    status, out, err = run(capsys, files, argv)
    assert_one_line_error(status, out, err, match, usage="unrecognized" in match
                          or "ambiguous" in match)
    assert list(files["{OUT}"].iterdir()) == []


@pytest.mark.parametrize("path, match", [
    ("{EMPTY}", r"empty.txt.*ECSV"),
    ("{GARBAGE}", r"garbage.bin"),
    ("{DIR}", r"--catalogue: '.*a-directory' is a directory, not a file"),
    ("{MISSING}", r"--catalogue: no such file '.*missing.txt'"),
    ("{TLE}", r"gps.tle.*ECSV"),
])
def test_stations(capsys, files, path, match):
    assert_one_line_error(*run(capsys, files, ["stations", "--catalogue", path]), match)


@pytest.mark.parametrize("argv, match", [
    (["nosuch"], r"argument COMMAND: invalid choice: 'nosuch' \(choose from 'natural', "
     r"'satellite', 'baseline', 'faraday', 'demo', 'stations', 'coverage', 'antennas', 'correct', "
     r"'rinex', 'samples'\); "
     r"see 'feedrot --help'"),
    (["natural"], r"the following arguments are required: ANTENNA; see 'feedrot natural --help'"),
    (["baseline", "DBR205"], r"the following arguments are required"),
    (["stations", "YEBES40M", "extra"], r"unrecognized arguments: extra"),  # one NAME at most
    (["natural", "EFLSBERG", "--step"], r"argument --step: expected one argument"),
    (["natural", "EFLSBERG", "--min-elevation", "-5deg"], r"argument --min-elevation: expected one "
     r"argument \(write --option=VALUE for a value that starts with '-'\)"),
])
def test_command_lines_that_do_not_parse(capsys, files, argv, match):
    assert_one_line_error(*run(capsys, files, argv), match, usage=True)


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads every file")
@pytest.mark.parametrize("option", ["--tle", "--catalogue"])
def test_unreadable_input(capsys, files, tmp_path, option):
    locked = tmp_path / "locked.txt"
    locked.write_text("x")
    locked.chmod(0)
    argv = ([*SATELLITE[:2], "--tle", str(locked), *SAT_SPAN] if option == "--tle" else
            [*NATURAL, "--catalogue", str(locked)])
    assert_one_line_error(*run(capsys, files, argv),
                          rf"{option}: cannot read '.*locked.txt': permission denied")


# Property-based: anything at all in one option, and combinations of bad values ----------------


#: For each option: the command it is tried with and a span short enough
#: that any step the cap lets through computes fast.
FUZZED = {
    "--step": ["natural", "EFLSBERG", "--source", SOURCE, "--start", "2023-01-25T18:00",
               "--stop", "2023-01-25T18:00:01"],
    "--start": ["natural", "EFLSBERG", "--source", SOURCE, "--stop", "2023-01-25T18:00",
                "--step", "3000d"],
    "--stop": ["natural", "EFLSBERG", "--source", SOURCE, "--start", "2023-01-25T18:00",
               "--step", "3000d"],
    "--min-elevation": NATURAL,
    "--frequency": ["baseline", "DBR205", "FD-VLBA", "--source", SOURCE, *SPAN],
    "--source": ["natural", "EFLSBERG", *SPAN],
    "--frame": NATURAL,
    "--points": SP3[:6],
    "--sat": SP3[:4] + ["--points", "4"],
    "--mount": ["natural", "40,0,0", "--source", SOURCE, *SPAN],
    "--focus": ["natural", "40,0,0", "--source", SOURCE, *SPAN],
    "ANTENNA": ["natural", "--source", SOURCE, *SPAN],
    "--output-dir": ["demo", "--step", "1h"],
}


def check_outcome(status, out, err):
    """Success, or one error line; never a traceback or an internal error."""
    assert "Traceback" not in err and "internal error" not in err, err
    if status == 0:
        assert all(line.startswith("feedrot: warning: ") for line in err.splitlines()), err
    else:
        assert status in (1, 2) and out == "", err
        assert err.startswith("feedrot: error: ") and err.count("\n") == 1, err


#: Numbers with or without a unit, as a user might type them.
NUMBER = (r"[-+]?(\d{1,3}(\.\d{0,3})?|\.\d|nan|inf)(e[-+]?\d{1,3})? ?"
          r"(s|ms|min|h|d|yr|Hz|MHz|GHz|deg|rad|arcsec|m|km|parsec)?")


@FAST
@given(option=st.sampled_from(sorted(FUZZED)),
       value=st.one_of(st.text(max_size=12), st.from_regex(NUMBER, fullmatch=True)))
def test_any_text_in_any_option(capsys, files, tmp_path_factory, option, value):
    base = FUZZED[option]
    if option == "ANTENNA":
        argv = [base[0], value, *base[1:]]
    elif option == "--output-dir":
        # Never into a real directory: the demo would write there.
        argv = [*base, "--output-dir=" + str(files["{MISSING}"]) + value]
    else:
        argv = [*base, f"{option}={value}"]
    check_outcome(*run(capsys, files, argv))


@FAST
@given(site=st.tuples(*[st.floats(allow_nan=True, allow_infinity=True, width=32)] * 3))
def test_any_site(capsys, files, site):
    text = ",".join(repr(value) for value in site)
    argv = ["natural", text, "--source", SOURCE, *SPAN]
    status, out, err = run(capsys, files, argv)
    check_outcome(status, out, err)
    lat, lon, height = site
    # Antenna bounds the height (about -12 km to +100 km); well inside must
    # work, far outside or off the map must be refused.
    if -90 <= lat <= 90 and -180 <= lon <= 360 and -10e3 <= height <= 90e3:
        assert status == 0, (text, err)
    if not (-90 <= lat <= 90 and -180 <= lon <= 360 and abs(height) < 1e6):
        assert status == 1, text


BAD_VALUES = {
    "--step": ["0", "nan", "-1s", "1e-9 s", "abc", "10 parsec", "inf"],
    "--start": ["2023-02-30", "yesterday", "1900-01-01"],
    "--min-elevation": ["nan", "100", "1 parsec", "-inf"],
    "--frame": ["altaz", "hadec", "nonsense"],
    "--polarization": ["XX", "LCP"],
    "--catalogue": ["{EMPTY}", "{GARBAGE}", "{DIR}", "{MISSING}"],
    "--mount": ["FOO"],
    "--focus": ["FOO"],
    "-o": ["{DIR}", "x.txt", "/nonexistent/x.ecsv"],
}


@FAST
@given(command=st.sampled_from(sorted(TIMED)),
       bad=st.dictionaries(st.sampled_from(sorted(BAD_VALUES)), st.just(None), min_size=1),
       data=st.data())
def test_combinations_of_bad_values(capsys, files, command, bad, data):
    argv = list(TIMED[command])
    refused = False
    for option in bad:
        if option == "--frame" and "satellite" in command:
            continue  # no --frame with a satellite: not a bad value but a bad option
        value = data.draw(st.sampled_from(BAD_VALUES[option]), label=option)
        argv += [option, value] if option == "-o" or value in files else [f"{option}={value}"]
        # An LCP receiver is legal for a natural source, not for an RCP satellite (and
        # faraday has no --polarization).
        refused |= not (option == "--polarization" and value == "LCP"
                        and command in ("natural", "baseline"))
    status, out, err = run(capsys, files, argv)
    check_outcome(status, out, err)
    assert (status != 0) == refused, argv


# Real processes ------------------------------------------------------------------------------


def feedrot(*argv, **kwargs):
    return subprocess.run([sys.executable, "-m", "astropy_feedrot", *argv], capture_output=True,
                          text=True, **kwargs)


@pytest.mark.parametrize("argv", [
    ["natural", "EFLSBERG", "--source", SOURCE, *SPAN, "--frame", "altaz"],
    ["natural", "EFLSBERG", "--source", SOURCE, *SPAN, "--polarization", "XX"],
    ["demo", "--step", "1ms"],
])
def test_process_without_traceback(argv):
    result = feedrot(*argv)
    assert result.returncode in (1, 2) and result.stdout == ""
    assert result.stderr.startswith("feedrot: error: ") and result.stderr.count("\n") == 1
    assert "Traceback" not in result.stderr


def test_closed_standard_output_is_quiet():
    # feedrot stations | head -0: the reader has gone before anything is written.
    process = subprocess.Popen([sys.executable, "-m", "astropy_feedrot", "stations"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    process.stdout.close()
    _, err = process.communicate(timeout=120)
    assert process.returncode == 1
    assert err == b""


@pytest.mark.parametrize("when", ["computing", "writing"])
def test_interrupted_run_leaves_files_as_they_were(capsys, tmp_path, monkeypatch, when):
    # Ctrl-C (KeyboardInterrupt) while the table is computed, or after half of the new
    # table is in its temporary file: raised at that point, not sent after a delay, so
    # the test does not depend on how fast the machine is.
    output = tmp_path / "out.ecsv"
    output.write_bytes(b"old table")
    argv = ["natural", "EFLSBERG", "--source", SOURCE, "--start", "2023-01-01", "--stop",
            "2023-01-01T02:00", "--step", "10min", "-o", str(output), "--overwrite"]

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    def half_written(table, fmt, step=None):
        def write(name):
            with open(name, "wb") as handle:
                handle.write(b"# %ECSV 1.0\n# ---\n")
            assert os.path.exists(name)
            raise KeyboardInterrupt
        return write

    if when == "computing":
        monkeypatch.setattr(astropy_feedrot.cli.tables, "feed_rotation_table", interrupted)
    else:
        monkeypatch.setattr(astropy_feedrot.cli.common, "table_writer", half_written)
    status = main(argv)
    _, err = capsys.readouterr()
    assert status == 130 and err == "feedrot: interrupted\n"
    assert [p.name for p in tmp_path.iterdir()] == ["out.ecsv"]
    assert output.read_bytes() == b"old table"


def test_a_good_run_still_works(capsys, files):
    status, out, err = run(capsys, files, NATURAL)
    assert status == 0 and err == ""
    assert len(Table.read(out, format="ascii.ecsv")) == 5
