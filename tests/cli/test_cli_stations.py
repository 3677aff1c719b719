# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot stations``: listed one a line on a terminal, searched, shown in full,
written to files; ECSV on a pipe as before."""

import sys

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.table import Table

from astropy_feedrot.cli import main
from astropy_feedrot.stations.catalogue import get_antenna


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_a_terminal_gets_one_station_a_line(capsys, monkeypatch):
    monkeypatch.setattr(sys.stdout, "isatty", lambda: True)
    status, out, err = run(capsys, "stations", "--network", "EHT")
    assert status == 0 and err == ""
    lines = out.splitlines()
    assert lines[0].split() == ["name", "networks", "mount", "focus", "aliases"]
    assert set(lines[1]) == {"-", " "}
    assert lines[-1] == "11 stations"
    rows = lines[2:-1]
    assert len(rows) == 11 and all(len(row) <= len(lines[1]) for row in rows)
    apex = next(row for row in rows if row.startswith("APEX "))
    assert apex.split()[:4] == ["APEX", "EHT", "NASR", "nasmyth-right"]


def test_a_pipe_gets_ecsv_unless_told(capsys):
    status, out, _ = run(capsys, "stations", "--mount", "NASR")
    table = Table.read(out, format="ascii.ecsv")
    assert status == 0 and set(table["mount"]) == {"NASR"} and "x" in table.colnames
    status, out, _ = run(capsys, "stations", "--mount", "NASR", "--format", "csv")
    assert out.startswith("name,") and Table.read(out, format="ascii.csv")["mount"][0] == "NASR"
    status, out, _ = run(capsys, "stations", "--mount", "NASR", "--format", "text")
    assert out.splitlines()[0].split()[0] == "name" and out.rstrip().endswith("stations")


def test_one_station_in_full_with_its_sources(capsys):
    status, out, _ = run(capsys, "stations", "yebes40m")  # any case
    assert status == 0
    fields = dict(line.split(": ", 1) for line in out.splitlines())
    fields = {key.strip(): value for key, value in fields.items()}
    assert fields["name"] == "YEBES40M" and fields["mount"] == "NASR"
    assert fields["mount_source"].startswith("paper Appendix C.1")
    assert "position_source" in fields
    # The position as the catalogue holds it (m, 4 decimals).
    xyz = u.Quantity(get_antenna("YEBES40M").location.geocentric).to_value(u.m)
    assert fields["x"] == f"{xyz[0]:.4f} m"


def test_patterns_search_names_and_aliases(capsys):
    status, out, _ = run(capsys, "stations", "EF*", "--format", "ecsv")
    assert list(Table.read(out, format="ascii.ecsv")["name"]) == ["EFLSBERG"]
    status, out, _ = run(capsys, "stations", "pico", "--format", "ecsv")  # a part of an alias
    assert "PICOVEL" in list(Table.read(out, format="ascii.ecsv")["name"])


def test_near_a_place_nearest_first(capsys):
    status, out, _ = run(capsys, "stations", "--near", "-3.09,40.52", "--limit", "4",
                         "--format", "ecsv")
    table = Table.read(out, format="ascii.ecsv")
    assert status == 0 and len(table) == 4
    distance = table["distance"].quantity.to_value(u.km)
    assert np.all(np.diff(distance) >= 0)
    assert {"YEBES40M", "YEBES", "RAEGYEB"} <= set(table["name"][:3])
    # Independently: the chord between the place and the first station (a
    # great circle of 1 km differs from its chord by far less than 0.1 km).
    place = EarthLocation.from_geodetic(-3.09 * u.deg, 40.52 * u.deg, 0 * u.m)
    first = get_antenna(str(table["name"][0])).location
    chord = np.linalg.norm(u.Quantity(first.geocentric).to_value(u.km)
                           - u.Quantity(place.geocentric).to_value(u.km))
    assert abs(chord - distance[0]) < 1.1  # the station's height is ~1 km


def test_write_every_column_to_a_file(capsys, tmp_path):
    output = tmp_path / "eht.csv"
    status, out, err = run(capsys, "stations", "--network", "EHT", "-o", str(output))
    assert status == 0 and out == ""
    assert err == f"feedrot: {output}: 11 stations of the catalogue\n"  # the file, as named
    table = Table.read(output, format="ascii.csv")
    assert len(table) == 11 and {"x", "mount_source", "focus_source"} <= set(table.colnames)
    status, _, err = run(capsys, "stations", "--network", "EHT", "-o", str(output))
    assert status == 1 and "--overwrite" in err
    assert run(capsys, "stations", "--network", "EHT", "-o", str(output), "--overwrite")[0] == 0


@pytest.mark.parametrize("argv, message", [
    (["NOWHERE*"], r"no station matches 'NOWHERE\*'; 'feedrot stations' lists them all"),
    (["--near", "40.5"], r"--near: expected LON,LAT in degrees \(e.g. -3.09,40.52\), got '40.5'"),
    (["--near", "10,95"], r"--near: latitude must lie in \[-90, 90\] deg"),
    (["--limit", "0"], r"--limit: expected a positive number of stations, got 0"),
    (["--mount", "ROUND"], r"--mount: no station has the mount code 'ROUND'"),
    (["-o", "stations.txt"], r"-o/--output: cannot tell a format"),
])
def test_errors_name_the_option(capsys, argv, message):
    import re

    status, out, err = run(capsys, "stations", *argv)
    assert status == 1 and out == ""
    assert re.search(message, err), err
    assert err.count("\n") == 1
