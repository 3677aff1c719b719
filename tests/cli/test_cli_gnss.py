# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot rinex``."""

import numpy as np
import pytest
from astropy import units as u
from astropy.table import QTable

from astropy_feedrot.cli import main
from astropy_feedrot.data import sample_file

RNX = str(sample_file("gnss_sample.rnx"))
SP3 = str(sample_file("gnss_sample.sp3"))


def test_rinex_writes_corrected_copy_and_table(tmp_path, capsys):
    out, table = tmp_path / "out.rnx", tmp_path / "windup.ecsv"
    assert main(["rinex", RNX, "--sp3", SP3, "-o", str(out), "--table", str(table)]) == 0
    assert ("1920 carrier phases of 640 observations at 40 epochs corrected, 16 arcs, "
            "0 epochs untouched\n") in capsys.readouterr().err
    windup = QTable.read(table)
    assert len(windup) == 640 and windup["windup"].unit == u.cycle
    assert list(windup["prn"][:3]) == ["G01", "G02", "G03"]
    assert main(["rinex", RNX, "--sp3", SP3, "-o", str(tmp_path / "deg.rnx"), "--table",
                 str(tmp_path / "deg.ecsv"), "--units", "deg"]) == 0
    degrees = QTable.read(tmp_path / "deg.ecsv")["windup"]
    # 1 cycle = 360 deg (the unit's definition).
    np.testing.assert_allclose(degrees.to_value(u.deg), windup["windup"].value * 360)
    assert (tmp_path / "deg.rnx").read_bytes() == out.read_bytes()


@pytest.mark.parametrize("argv, match", [
    (["-o", "{tmp}/a.crx"], "names a Compact RINEX"),
    (["-o", RNX], "is the OBS input, which is never overwritten"),
    (["-o", "{tmp}/a.rnx", "--attitude", "orbex"], "--attitude orbex needs --orbex"),
    (["-o", "{tmp}/a.rnx", "--orbex", "x.obx", "--attitude", "nominal"],
     "--orbex goes with --attitude orbex"),
    (["-o", "{tmp}/a.rnx", "--position", "1,2"], "--position: expected X,Y,Z"),
    (["-o", "{tmp}/a.rnx", "--table", "{tmp}/t.txt"], "--table: cannot tell a format"),
    (["-o", "{tmp}/a.rnx", "--orbex", "{tmp}/none.obx"], "--orbex: no such file '"),
    # --points 1 used to exit 0 with every satellite untouched; 2 is 4.6e-3 cycle off.
    (["-o", "{tmp}/a.rnx", "--points", "1"], "points=1 is too few for SP3 orbits at 900 s"),
    (["-o", "{tmp}/a.rnx", "--points", "2"], "needs at least 7 points (default 10)"),
])
def test_rinex_errors(tmp_path, capsys, argv, match):
    argv = [a.format(tmp=tmp_path) for a in argv]
    assert main(["rinex", RNX, "--sp3", SP3] + argv) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and match in err
    assert not (tmp_path / "a.rnx").exists()


def test_rinex_output_exists(tmp_path, capsys):
    (tmp_path / "a.rnx").write_text("keep")
    assert main(["rinex", RNX, "--sp3", SP3, "-o", str(tmp_path / "a.rnx")]) == 1
    # Checked before any work, in the command line's words (not the API's overwrite=True).
    assert "a.rnx' exists; add --overwrite to replace it" in capsys.readouterr().err
    assert (tmp_path / "a.rnx").read_text() == "keep"
    assert main(["rinex", RNX, "--sp3", SP3, "-o", str(tmp_path / "b.ecsv"),
                 "--table", str(tmp_path / "b.ecsv")]) == 1
    assert "name the same file" in capsys.readouterr().err
    assert not (tmp_path / "b.ecsv").exists()


# -- satellite commands: every satellite of an SP3 file, units, default interpolation ---------


def _table(capsys, *argv):
    assert main(list(argv)) == 0
    out, err = capsys.readouterr()
    return QTable.read(out, format="ascii.ecsv"), err


def test_every_satellite_of_an_sp3_file(capsys):
    table, err = _table(capsys, "satellite", "GGAO12M", "--sp3", SP3, "--step", "1h")
    assert err == ""
    assert table.colnames[:3] == ["time", "prn", "azimuth"]
    np.testing.assert_array_equal(table["windup"], table["continuous"])
    assert len(table) == 4 * 16  # 00:00 to 03:00, 16 satellites, by epoch then PRN
    assert list(table["prn"][:2]) == ["G01", "G02"] and table["time"][15] == table["time"][0]
    single, _ = _table(capsys, "satellite", "GGAO12M", "--sp3", SP3, "--sat", "E02", "--step",
                       "1h")
    rows = table[table["prn"] == "E02"]
    np.testing.assert_array_equal(rows["total"], single["total"])  # the same computation


def test_every_satellite_is_not_plotted(tmp_path, capsys):
    assert main(["satellite", "GGAO12M", "--sp3", SP3, "--plot", str(tmp_path / "a.png")]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--plot draws one satellite; choose it with --sat" in err
    assert not (tmp_path / "a.png").exists()


def test_default_interpolation_on_the_shipped_sample(capsys):
    # sample.sp3 has 4 epochs: the window defaults to all of them (a cubic); G05 and E11
    # have no 4 consecutive valid epochs and are left out with one warning.
    table, err = _table(capsys, "satellite", "GGAO12M", "--sp3", str(sample_file("sample.sp3")),
                        "--step", "15min")
    assert set(table["prn"]) == {"G01"} and len(table) == 4
    assert err.count("\n") == 1 and "left out: G05 (G05 has no 4 consecutive epochs" in err


@pytest.mark.parametrize("command", ["satellite", "baseline"])
def test_units(capsys, command):
    second = ["WETTZ13S", "--frequency", "1575.42MHz"] if command == "baseline" else []
    argv = [command, "GGAO12M"] + second + ["--sp3", SP3, "--sat", "G03", "--step", "1h"]
    degrees, _ = _table(capsys, *argv)
    cycles, _ = _table(capsys, *argv, "--units", "cycles")
    radians, _ = _table(capsys, *argv, "--units", "rad")
    prefix = "GGAO12M_" if command == "baseline" else ""
    for name in ("total", "continuous", "transmitter", "parallactic_angle") + (
            ("windup",) if command == "satellite" else ()):
        column = prefix + name
        assert cycles[column].unit == u.cycle and radians[column].unit == u.rad
        # 1 cycle = 2 pi rad = 360 deg (the units' definitions).
        np.testing.assert_allclose(cycles[column].value * 360, degrees[column].value)
        np.testing.assert_allclose(radians[column].value, np.radians(degrees[column].value))
    assert cycles[prefix + "rate"].unit == u.cycle / u.s
    assert cycles[prefix + "elevation"].unit == u.deg


def test_rinex_model_attitude(tmp_path, capsys):
    out = tmp_path / "out.rnx"
    assert main(["rinex", RNX, "--sp3", SP3, "-o", str(out), "--attitude", "model"]) == 0
    assert "16 arcs" in capsys.readouterr().err
    assert "astropy_feedrot: L - WIND-UP (CYCLES, RHCP, YAW MODELS)" in out.read_text()
    assert main(["rinex", RNX, "--sp3", SP3, "-o", str(tmp_path / "x.rnx"),
                 "--metadata", str(sample_file("igs_satellite_metadata.snx"))]) == 1
    assert "--metadata goes with --attitude model" in capsys.readouterr().err


def test_rinex_summary_counts(tmp_path, capsys):
    """The summary line counts arcs, untouched epochs and satellites, singular or plural."""
    from astropy.time import Time

    from astropy_feedrot.gnss.synthetic import write_rinex

    obs = tmp_path / "obs.rnx"
    write_rinex(obs, "3.04", {"G": ("C1C", "L1C")}, ["G01", "G31"],
                Time("2023-01-25T02:55:19", scale="tai"), 2, 30.0)
    assert main(["rinex", str(obs), "--sp3", SP3, "-o", str(tmp_path / "a.rnx")]) == 0
    err = capsys.readouterr().err
    assert "G31: not in the SP3 files" in err
    assert err.endswith("2 carrier phases of 4 observations at 2 epochs corrected, 1 arc, "
                        "0 epochs untouched, 1 satellite untouched\n")


def test_satellite_with_too_few_points_says_so(tmp_path, capsys):
    # gnss_sample.sp3: 13 epochs at 15 min. Two points (a straight line between
    # epochs) put a GNSS orbit kilometres off (45 km here): the SP3 orbit itself,
    # interpolated through 2 and 10 points, half an interval after an epoch.
    from astropy.time import Time

    from astropy_feedrot.io import read_sp3
    from astropy_feedrot.transmitters.orbits import SP3Orbit
    from astropy_feedrot.transmitters.sp3_orbit import points_needed

    data = read_sp3(SP3)
    when = data.epochs[6] + 450 * u.s
    coarse, fine = (SP3Orbit(data, "G01", points=n).position(Time([when]))
                    for n in (2, 10))
    assert np.linalg.norm(np.asarray(coarse) - np.asarray(fine)) > 100  # metres
    needed = min(points_needed(data.interval), len(data.epochs))
    argv = ["satellite", "GGAO12M", "--sp3", SP3, "--sat", "G01", "--step", "15min",
            "-o", str(tmp_path / "g01.ecsv")]
    assert main(argv + ["--points", "2"]) == 0
    err = capsys.readouterr().err
    # The warning, then the summary line.
    assert err.count("\n") == 2 and err.startswith(
        "feedrot: warning: --points 2 at the SP3 file's 900 s interval: its positions may be "
        f"off by more than 10 m between epochs; --points {needed} keeps them within")
    assert main(argv + ["--points", str(needed), "--overwrite"]) == 0
    assert capsys.readouterr().err.startswith(f"feedrot: {tmp_path / 'g01.ecsv'}: ")
