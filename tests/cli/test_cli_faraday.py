# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot faraday``: RM, Faraday and feed rotation per station and epoch, from IONEX
maps or a table of rotation measures; values, files, figures and refusals."""

import shutil
import subprocess
import sys
import warnings

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import SkyCoord
from astropy.table import QTable, Table
from astropy.time import Time
from helpers import import_or_skip

from astropy_feedrot.cli import main
from astropy_feedrot.core.exceptions import DegenerateGeometryWarning
from astropy_feedrot.ionosphere import Ionosphere
from astropy_feedrot.stations.catalogue import get_antenna

CRAB = "05h34m31.94s +22d00m52.2s"
# CODE's maps of 2020 January 8 and 9 are among the IONEX files spinifex ships; the
# Crab is above Effelsberg's and Yebes' horizon from about 15:30 to 06:00 UTC.
IONEX_SPAN = ["--start", "2020-01-08T17:00", "--stop", "2020-01-09T07:00", "--step", "1h"]
SOURCE = "03h19m48.16s +41d30m42.1s"  # 3C 84
RM_SPAN = ["--start", "2024-06-01T06:00", "--stop", "2024-06-01T22:00", "--step", "2h"]
FREQUENCIES = ["--frequency", "150MHz", "--frequency", "1.4GHz"]


def run(capsys, *argv):
    status = main([str(arg) for arg in argv])
    out, err = capsys.readouterr()
    return status, out, err


def assert_one_line_error(status, out, err, match, code=1):
    assert status == code, err
    assert out == ""
    assert err.startswith("feedrot: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err and "internal error" not in err, err
    assert match in err, err


@pytest.fixture(scope="module")
def ionex(tmp_path_factory):
    """CODE's IONEX files of 2020 January 8 and 9, copied where the test may name them."""
    import_or_skip("spinifex", "ionosphere", "FEEDROT_REQUIRE_SPINIFEX")
    from astropy_feedrot.ionosphere import sample_ionex

    root = tmp_path_factory.mktemp("ionex")
    return [shutil.copy(path, root) for path in sample_ionex("codg00[89]0.20i.Z")]


@pytest.fixture(scope="module")
def rm_table(tmp_path_factory):
    """A table of rotation measures per station, as a user would write it (ECSV)."""
    path = tmp_path_factory.mktemp("rm") / "rm.ecsv"
    QTable({"time": Time(["2024-06-01T00:00", "2024-06-02T00:00"] * 2),
            "rm": [0.5, 2.5, -1.0, 1.0] * u.rad / u.m**2,
            "antenna": ["EFLSBERG", "EFLSBERG", "YEBES40M", "YEBES40M"]}).write(path)
    return path


def compare_with_antennas(table, source, ionosphere, frequencies):
    """Each column against the Antenna methods for the same inputs (one station at a time,
    another path through the package than the table's one call for all stations)."""
    times = Time(table["time"][::2])
    for index, name in enumerate(["EFLSBERG", "YEBES40M"]):
        rows = table[index::2]
        assert list(rows["antenna"]) == [name] * len(rows)
        antenna = get_antenna(name)
        up = antenna.altaz(source, times)[1] > 0 * u.deg
        with warnings.catch_warnings():  # NaN below the horizon, said once per call
            warnings.simplefilter("ignore", DegenerateGeometryWarning)
            rm = antenna.rotation_measure(source, times, ionosphere)
            chi = antenna.faraday_rotation(source, times, frequencies, ionosphere)
        # ECSV keeps every digit: equal to rounding of the text.
        assert np.allclose(rows["rm"], rm.to_value(u.rad / u.m**2), rtol=1e-14, atol=0,
                           equal_nan=True)
        phi = antenna.feed_rotation(source, times, min_elevation=0 * u.deg)
        assert np.allclose(rows["feed_rotation"], phi.to_value(u.deg), rtol=0, atol=1e-12,
                           equal_nan=True)
        for k, label in enumerate(["150MHz", "1.4GHz"]):
            assert np.allclose(rows[f"chi_{label}"], chi[:, k].to_value(u.deg), rtol=1e-14,
                               atol=0, equal_nan=True)
            assert np.allclose(rows[f"psi_{label}"],
                               phi.to_value(u.deg) - chi[:, k].to_value(u.deg),
                               rtol=0, atol=1e-12, equal_nan=True)
        # NaN exactly where the source is below the horizon.
        assert np.array_equal(np.isnan(rows["rm"]), ~up)


def test_ionex_values_against_the_antenna(capsys, ionex):
    status, out, err = run(capsys, "faraday", "EFLSBERG", "YEBES40M", "--source", CRAB,
                           *IONEX_SPAN, "--ionex", *ionex, *FREQUENCIES)
    assert status == 0 and err == "", err
    table = Table.read(out, format="ascii.ecsv")
    assert table.colnames == ["time", "antenna", "elevation", "rm", "chi_150MHz", "chi_1.4GHz",
                              "feed_rotation", "psi_150MHz", "psi_1.4GHz"]
    assert len(table) == 2 * 15
    # The Crab sets at both stations between 05:00 and 06:00: NaN at 06:00 and 07:00.
    assert np.isnan(table["rm"][-4:]).all() and np.isfinite(table["rm"][:-4]).all()
    assert np.isfinite(table["elevation"]).all()
    compare_with_antennas(table, SkyCoord(CRAB), Ionosphere.from_ionex(ionex),
                          [150, 1400] * u.MHz)
    assert [name.rsplit("/", 1)[-1] for name in table.meta["ionex"]] == [
        "codg0080.20i.Z", "codg0090.20i.Z"]


def test_rm_table_values_against_the_antenna(capsys, rm_table):
    status, out, err = run(capsys, "faraday", "EFLSBERG", "YEBES40M", "--source", SOURCE,
                           *RM_SPAN, "--rm-table", rm_table, *FREQUENCIES)
    assert status == 0 and err == "", err
    table = Table.read(out, format="ascii.ecsv")
    compare_with_antennas(table, SkyCoord(SOURCE), Ionosphere.from_rm(QTable.read(rm_table)),
                          [150, 1400] * u.MHz)
    # 08:00 at Effelsberg: 0.5 + 2 * 8 / 24 rad/m2 by linear interpolation of the table.
    assert np.isclose(table["rm"][2], 0.5 + 2 * 8 / 24, rtol=1e-12)


def test_ecsv_file_round_trip_with_units(capsys, tmp_path, rm_table):
    path = tmp_path / "faraday.ecsv"
    status, out, err = run(capsys, "faraday", "EFLSBERG", "YEBES40M", "--source", SOURCE,
                           *RM_SPAN, "--rm-table", rm_table, *FREQUENCIES, "-o", path)
    # The one summary line on success: the file, as named, and what it holds.
    assert status == 0 and out == ""
    assert err == (f"feedrot: {path}: 18 rows of the rotation measure, Faraday and feed "
                   f"rotation of EFLSBERG, YEBES40M observing {SOURCE} (icrs) at 150MHz, "
                   "1.4GHz\n")
    table = QTable.read(path)
    assert isinstance(table["time"], Time) and table["time"].scale == "utc"
    assert table["rm"].unit == u.rad / u.m**2
    for name in ("elevation", "chi_150MHz", "chi_1.4GHz", "feed_rotation", "psi_150MHz",
                 "psi_1.4GHz"):
        assert table[name].unit == u.deg, name
    assert table.meta["frequencies"] == ["150.0 MHz", "1400.0 MHz"]
    assert table.meta["antennas"] == ["EFLSBERG", "YEBES40M"]
    # The same numbers as on standard output.
    _, out, _ = run(capsys, "faraday", "EFLSBERG", "YEBES40M", "--source", SOURCE, *RM_SPAN,
                    "--rm-table", rm_table, *FREQUENCIES)
    printed = Table.read(out, format="ascii.ecsv")
    assert np.array_equal(printed["psi_150MHz"], table["psi_150MHz"].value, equal_nan=True)


def test_text_view_rounds_to_what_the_physics_supports(capsys, rm_table):
    status, out, err = run(capsys, "faraday", "EFLSBERG", "--source", SOURCE, *RM_SPAN,
                           "--rm-table", rm_table, "--frequency", "1.4GHz", "--format", "text")
    assert status == 0, err
    lines = out.splitlines()
    assert lines[0].split() == ["time", "antenna", "elevation", "rm", "chi_1.4GHz",
                                "feed_rotation", "psi_1.4GHz"]
    assert lines[1].split() == ["deg", "rad", "/", "m2", "deg", "deg", "deg"]
    first = lines[3].split()
    assert first[0] == "2024-06-01T06:00:00" and first[1] == "EFLSBERG"
    # 0.001 deg for angles, 0.001 rad/m2 for the RM: three decimals each.
    assert all(len(value.split(".")[1]) == 3 for value in first[2:]), first
    # 08:00: 0.5 + 2 * 8 / 24 = 1.1666... rad/m2 (the table's linear interpolation).
    assert lines[4].split()[3] == "1.167"


def test_plot(capsys, tmp_path, rm_table):
    pytest.importorskip("matplotlib")
    figure, table = tmp_path / "faraday.png", tmp_path / "faraday.csv"
    status, out, err = run(capsys, "faraday", "EFLSBERG", "YEBES40M", "--source", SOURCE,
                           *RM_SPAN, "--rm-table", rm_table, *FREQUENCIES, "-o", table,
                           "--plot", figure)
    assert status == 0 and err.startswith(f"feedrot: {table} and {figure}: 18 rows "), err
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert Table.read(table, format="ascii.csv").colnames[3] == "rm"


def test_inputs_are_never_overwritten(capsys, rm_table):
    before = rm_table.read_bytes()
    status, out, err = run(capsys, "faraday", "EFLSBERG", "--source", SOURCE, *RM_SPAN,
                           "--rm-table", rm_table, "--frequency", "1GHz", "-o", rm_table,
                           "--overwrite")
    assert_one_line_error(status, out, err, "is the --rm-table input, which is never "
                                            "overwritten")
    assert rm_table.read_bytes() == before


def test_ionex_input_is_never_overwritten(capsys, ionex, tmp_path):
    copy = shutil.copy(ionex[0], tmp_path / "codg0080.20i.ecsv")  # named like a table
    status, out, err = run(capsys, "faraday", "EFLSBERG", "--source", CRAB, *IONEX_SPAN,
                           "--ionex", copy, "--frequency", "1GHz", "-o", copy, "--overwrite")
    assert_one_line_error(status, out, err, "is the --ionex input, which is never overwritten")


@pytest.fixture
def bad_tables(tmp_path):
    paths = {}
    paths["no_unit"] = tmp_path / "no_unit.ecsv"
    QTable({"time": Time(["2024-06-01T00:00", "2024-06-02T00:00"]),
            "rm": [1.0, 2.0]}).write(paths["no_unit"])
    paths["other"] = tmp_path / "other.ecsv"
    QTable({"time": Time(["2024-06-01T00:00", "2024-06-02T00:00"]),
            "rm": [1.0, 2.0] * u.rad / u.m**2, "antenna": ["X", "Y"]}).write(paths["other"])
    paths["garbage"] = tmp_path / "garbage.ecsv"
    paths["garbage"].write_bytes(bytes(range(256)) * 4)
    paths["strings"] = tmp_path / "strings.csv"
    paths["strings"].write_text("time,rm\nyesterday,1\n")
    return paths


@pytest.mark.parametrize("extra, match", [
    ([], "give the ionosphere with --ionex FILE [FILE ...] (IONEX maps, one file per UTC day) "
     "or --rm-table FILE (a table of rotation measures)"),
    (["--rm-table", "{no_unit}"], "--rm-table: '"),
    (["--rm-table", "{no_unit}"], "table column 'rm' has no unit; give it in rad / m2"),
    (["--rm-table", "{other}"], "EFLSBERG"),
    (["--rm-table", "{garbage}"], "--rm-table: cannot read"),
    (["--rm-table", "{strings}"], "--rm-table: column 'time' of"),
    (["--rm-table", "/nonexistent/rm.ecsv"], "--rm-table: no such file '/nonexistent/rm.ecsv'"),
    (["--ionex", "/nonexistent/codg0080.20i.Z"],
     "--ionex: no such file '/nonexistent/codg0080.20i.Z'"),
    (["--rm-table", "{no_unit}", "--ionex", "{no_unit}"], "not both"),
    (["--rm-table", "{other}", "--min-elevation=-5"],
     "--min-elevation must be from 0 to 90 deg here, got '-5': the rotation measure is "
     "undefined below the horizon"),
    (["--rm-table", "{other}", "--frequency", "1400MHz"],
     "frequency 1.4GHz is given twice; give each frequency once"),
    (["--rm-table", "{other}", "--frequency", "10m"],
     "--frequency: '10m' is not in a unit of frequency"),
])
def test_refusals(capsys, bad_tables, extra, match):
    extra = [str(bad_tables[arg[1:-1]]) if arg.startswith("{") else arg for arg in extra]
    status, out, err = run(capsys, "faraday", "EFLSBERG", "--source", SOURCE, *RM_SPAN,
                           "--frequency", "1.4GHz", *extra)
    assert_one_line_error(status, out, err, match)


def test_refusals_of_the_command_line(capsys, rm_table):
    base = ["faraday", "EFLSBERG", "--source", SOURCE, *RM_SPAN, "--rm-table", rm_table]
    assert_one_line_error(*run(capsys, *base), "the following arguments are required: "
                          "--frequency", code=2)
    assert_one_line_error(*run(capsys, *base, "--frequency", "1GHz", "--polarization", "LCP"),
                          "unrecognized arguments: --polarization LCP", code=2)
    assert_one_line_error(*run(capsys, *base[:1], "--source", SOURCE, *RM_SPAN, "--rm-table",
                               rm_table, "--frequency", "1GHz"),
                          "the following arguments are required: STATION", code=2)
    assert_one_line_error(*run(capsys, "faraday", "EFLSBERG", "EFLSBERG", *base[2:],
                               "--frequency", "1GHz"),
                          "antenna 'EFLSBERG' is given twice; give each station once")
    # A station the table does not list, and epochs outside it: named, with the option.
    assert_one_line_error(*run(capsys, "faraday", "WSTRBORK", *base[2:], "--frequency", "1GHz"),
                          "--rm-table: the table of rotation measures has no antenna 'WB_RT1'; "
                          "it has EFLSBERG, YEBES40M")
    assert_one_line_error(*run(capsys, "faraday", "EFLSBERG", "--source", SOURCE, "--start",
                               "2024-06-03", "--stop", "2024-06-03T01:00", "--rm-table",
                               rm_table, "--frequency", "1GHz"), "--rm-table: ")


def test_epochs_outside_the_maps(capsys, ionex):
    status, out, err = run(capsys, "faraday", "EFLSBERG", "--source", CRAB, "--start",
                           "2020-01-10T12:00", "--stop", "2020-01-10T13:00", "--ionex", *ionex,
                           "--frequency", "1GHz")
    assert_one_line_error(status, out, err, "--ionex: ")
    assert "2020-01-08" in err and "2020-01-10" in err


def test_ionex_height(capsys, ionex):
    # Reference: Ionosphere.from_ionex(height=...) at the same epochs (the command's
    # height reaches the maps' shell; 350 km gives another RM than the default 450 km).
    argv = ["faraday", "EFLSBERG", "--source", CRAB, *IONEX_SPAN[:4], "--step", "3h",
            "--ionex", *ionex, "--frequency", "1GHz"]
    tables = {}
    for height, extra in ((350, ["--ionex-height", "350km"]), (450, []),
                          (600, ["--ionex-height", "600"])):  # plain: km
        status, out, err = run(capsys, *argv, *extra)
        assert status == 0 and err == "", err
        tables[height] = table = Table.read(out, format="ascii.ecsv")
        rm = Ionosphere.from_ionex(ionex, height=height * u.km).rotation_measure(
            get_antenna("EFLSBERG").location, SkyCoord(CRAB), Time(table["time"]))
        np.testing.assert_allclose(table["rm"], rm.value, rtol=1e-14, atol=0)
    assert np.all(tables[350]["rm"] != tables[450]["rm"])
    assert_one_line_error(*run(capsys, *argv, "--ionex-height", "30km"),
                          "--ionex-height: height of the ionosphere's thin shell must be one "
                          "value from 50 km to 20000 km, got 30.0 km")
    assert_one_line_error(*run(capsys, *argv, "--ionex-height", "3deg"),
                          "--ionex-height: '3deg' is not in a unit of length")
    assert_one_line_error(*run(capsys, *argv, "--ionex-height", "high"),
                          "--ionex-height: cannot read 'high' as a number with a unit "
                          "(e.g. 450km)")


def test_ionex_height_needs_ionex(capsys, rm_table):
    assert_one_line_error(*run(capsys, "faraday", "EFLSBERG", "--source", SOURCE, *RM_SPAN,
                               "--rm-table", rm_table, "--frequency", "1GHz",
                               "--ionex-height", "300km"),
                          "--ionex-height is the height of the IONEX maps' shell: give it "
                          "with --ionex")


def test_a_file_that_is_not_ionex(capsys, ionex, rm_table):
    status, out, err = run(capsys, "faraday", "EFLSBERG", "--source", CRAB, *IONEX_SPAN,
                           "--ionex", rm_table, "--frequency", "1GHz")
    assert_one_line_error(status, out, err, "--ionex: ")


def test_missing_spinifex_gives_the_install_hint(tmp_path):
    # A Python where spinifex cannot be imported (None in sys.modules blocks it).
    ionex = tmp_path / "codg0080.20i"
    ionex.write_text("not read\n")
    code = ("import sys; sys.modules['spinifex'] = None; "
            "from astropy_feedrot.cli import main; "
            f"sys.exit(main(['faraday', 'EFLSBERG', '--source', '{CRAB}', *{IONEX_SPAN!r}, "
            f"'--ionex', {str(ionex)!r}, '--frequency', '1.4GHz']))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 1 and result.stdout == ""
    assert result.stderr.count("\n") == 1, result.stderr
    assert result.stderr.startswith("feedrot: error: rotation measures from IONEX maps need "
                                    "spinifex")
    assert "python -m pip install spinifex" in result.stderr
    assert "[ionosphere]" in result.stderr


@pytest.mark.parametrize("extension", [".fits", ".hdf5"])
def test_fits_and_hdf5_keep_the_units(capsys, tmp_path, rm_table, extension):
    if extension == ".hdf5":
        pytest.importorskip("h5py")
    path = tmp_path / f"faraday{extension}"
    status, _, err = run(capsys, "faraday", "EFLSBERG", "--source", SOURCE, *RM_SPAN,
                         "--rm-table", rm_table, *FREQUENCIES, "-o", path)
    assert status == 0 and err.startswith(f"feedrot: {path}: 9 rows "), err
    table = QTable.read(path, **({"astropy_native": True} if extension == ".fits" else {}))
    assert isinstance(table["time"], Time)
    assert table["rm"].unit == u.rad / u.m**2 and table["psi_1.4GHz"].unit == u.deg
    # 06:00 at Effelsberg: 0.5 + 2 * 6 / 24 = 1 rad/m2.
    assert np.isclose(table["rm"][0].value, 1.0, rtol=1e-12)
