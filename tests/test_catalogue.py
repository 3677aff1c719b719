# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The embedded station catalogue: provenance, networks, names, positions and its build."""

import importlib.util
import io
import re
import subprocess
import sys
from contextlib import redirect_stdout
from pathlib import Path

import numpy as np
import pytest
from astropy import units as u
from astropy.table import Table

from astropy_feedrot import AltAzMount, CassegrainFocus, NasmythFocus
from astropy_feedrot.cli import main as cli_main
from astropy_feedrot.data import sample_file
from astropy_feedrot.labels import label_from_mount, mount_from_label
from astropy_feedrot.stations import (
    default_catalogue,
    get_antenna,
    get_network,
    networks,
    read_catalogue,
)

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "catalogue" / "build_stations.py"
TABLE = Table.read(sample_file("stations.ecsv"), format="ascii.ecsv")
ROWS = list(range(len(TABLE)))


def _text(row, column):
    value = TABLE[column][row]
    return "" if np.ma.is_masked(value) else str(value)


def test_size_and_provenance():
    assert len(TABLE) >= 150
    for column in ("position_source", "mount_source", "focus_source"):
        # Every station says where each value comes from, or that it is
        # assumed and why.
        empty = [TABLE["name"][r] for r in ROWS if not _text(r, column).strip()]
        assert empty == [], (column, empty)
    assumed = [r for r in ROWS if _text(r, "focus_source").startswith("assumed")]
    for r in assumed:
        assert len(_text(r, "focus_source")) > len("assumed: ") + 10


@pytest.mark.parametrize("network, members", [
    # The ten VLBA antennas (SCHED stations.dat VLBA_xx; the EVN planner's VLBA).
    ("VLBA", {"BR-VLBA", "FD-VLBA", "HN-VLBA", "KP-VLBA", "LA-VLBA", "MK-VLBA", "NL-VLBA",
              "OV-VLBA", "PIETOWN", "SC-VLBA"}),
    ("KVN", {"KVNYS", "KVNUS", "KVNTN", "KVNPC"}),
    ("VERA", {"VERAMZSW", "VERAIRIK", "VERAOGSW", "VERAISGK"}),
    ("EVN", {"EFLSBERG", "YEBES40M", "ONSALA60", "TORUN"}),
    ("eMERLIN", {"DARNHALL", "KNOCKIN", "DEFFORD"}),
    ("LBA", {"PARKES", "MOPRA", "HOBART26", "CEDUNA"}),
    ("EHT", {"PICOVEL", "LMT", "ALMA"}),
    ("GMVA", {"EFLSBERG", "PICOVEL"}),
    ("VGOS", {"GGAO12M", "WETTZ13S"}),
    ("IVS", {"WETTZELL", "HOBART26", "KOKEE"}),
])
def test_networks_resolve(network, members):
    names = {antenna.name for antenna in get_network(network)}
    assert members <= names, members - names
    assert set(default_catalogue().network_names(network.lower())) == names
    assert network in networks()


@pytest.mark.parametrize("network", networks())
def test_every_network_resolves(network):
    assert len(get_network(network)) >= 1


def test_unknown_network():
    with pytest.raises(ValueError, match=r"unknown network 'VLBB' in the embedded station "
                       r"catalogue; did you mean .*VLBA.*\? Known networks: .*EVN"):
        get_network("VLBB")
    with pytest.raises(ValueError, match=r"unknown network 'ZZZ'.*\. Known networks: "):
        get_network("ZZZ")
    with pytest.raises(TypeError, match="a network name must be a str, got int"):
        get_network(3)


@pytest.mark.parametrize("row", ROWS)
def test_positions_on_the_surface_and_checked(row):
    name = str(TABLE["name"][row])
    geodetic = default_catalogue().location(name).to_geodetic()
    # Telescope sites lie between the shore and the Chajnantor plateau (ALMA ~ 5 km).
    assert -100 * u.m < geodetic.height < 6 * u.km
    kind = TABLE["check_kind"][row]
    if kind == "none":
        # The paper's antennas that no fetched catalogue lists keep the paper's position.
        assert TABLE["position_source"][row].startswith("paper")
    else:
        # Distance to a second, independent catalogue within the stated tolerance
        # of that kind of comparison (catalogue/crosscheck.txt).
        assert TABLE["check_distance"][row] <= TABLE["check_tolerance"][row]


@pytest.mark.parametrize("row", ROWS)
def test_mount_and_focus_round_trip_through_labels(row):
    code = _text(row, "mount")
    mount, focus = mount_from_label(code, "geodetic")
    antenna = get_antenna(str(TABLE["name"][row]))
    assert antenna.mount == mount
    if _text(row, "focus") in ("", "cassegrain", "prime", "gregorian") or code == "GNSS":
        assert label_from_mount(antenna.mount, antenna.focus, "geodetic") == code
    elif code in ("NASR", "NASL"):
        if isinstance(antenna.focus, NasmythFocus):
            assert label_from_mount(antenna.mount, antenna.focus, "geodetic") == code
    assert label_from_mount(mount, focus, "geodetic") == code


@pytest.mark.parametrize("name, expected", [
    ("Effelsberg", "EFLSBERG"), ("EF", "EFLSBERG"), ("eflsberg", "EFLSBERG"),
    ("Ef", "EFLSBERG"), ("pico veleta", "PICOVEL"), ("PV", "PICOVEL"),
    ("Pie Town", "PIETOWN"), ("pt", "PIETOWN"), ("VLBA_PT", "PIETOWN"),
    ("onsala60", "ONSALA60"), ("Ky", "KVNYS"), ("kvn-ys", "KVNYS"),
])
def test_usual_names_resolve(name, expected):
    assert get_antenna(name).name == expected


def test_aliases_unique_or_ambiguous():
    catalogue = default_catalogue()
    # "Ap" is the two-letter code of Algonquin Park (SCHED) and of APEX (the
    # EVN planner): refused, naming both.
    with pytest.raises(ValueError, match=r"ambiguous antenna name 'Ap' in the embedded station "
                       r"catalogue: it is an alias of (ALGOPARK and APEX|APEX and ALGOPARK)"):
        catalogue.get_antenna("Ap")
    # Every other label names one station.
    for row in ROWS:
        assert get_antenna(str(TABLE["name"][row])).name == TABLE["name"][row]


def test_unknown_station_suggests():
    with pytest.raises(ValueError, match=r"unknown antenna 'EFFELSBURG'.*did you mean "
                       r".*EFLSBERG"):
        get_antenna("EFFELSBURG")


def test_ambiguous_alias_in_a_users_catalogue():
    table = Table({"name": ["A", "B"], "aliases": ["XX", "XX,b2"],
                   "x": [4075539.5, 4075540.5] * u.m, "y": [931735.6, 931735.6] * u.m,
                   "z": [4801629.6, 4801629.6] * u.m, "mount": ["AZEL", "AZEL"]})
    path = io.StringIO()
    table.write(path, format="ascii.ecsv")
    catalogue = read_catalogue(io.StringIO(path.getvalue()))
    assert catalogue.get_antenna("b2").name == "B"
    with pytest.raises(ValueError, match=r"ambiguous antenna name 'xx'.*alias of A and B"):
        catalogue.get_antenna("xx")
    assert catalogue.networks() == []
    with pytest.raises(ValueError, match=r"unknown network 'VLBA'.*Known networks: none"):
        catalogue.get_network("VLBA")


def test_nasmyth_from_eht_imaging():
    # eht-imaging EHT2017.txt: FR_ELEV_ANGLE = -1 for Pico Veleta and the LMT.
    assert get_antenna("PICOVEL").focus == NasmythFocus("left")
    assert get_antenna("LMT").focus == NasmythFocus("left")
    assert get_antenna("KVNYS").mount == AltAzMount()
    assert get_antenna("KVNYS").focus == CassegrainFocus()


def _run_cli(*args):
    out = io.StringIO()
    with redirect_stdout(out):
        code = cli_main(["stations", *args])
    return code, out.getvalue()


def test_cli_filters():
    code, text = _run_cli("--network", "kvn")
    assert code == 0
    table = Table.read(text, format="ascii.ecsv")
    assert set(table["name"]) == {"KVNYS", "KVNUS", "KVNTN", "KVNPC"}
    code, text = _run_cli("--mount", "nasl", "--network", "EHT")
    table = Table.read(text, format="ascii.ecsv")
    assert set(table["mount"]) == {"NASL"} and "PICOVEL" in table["name"]


@pytest.mark.parametrize("args, match", [
    (("--network", "VLBB"), r"--network: unknown network 'VLBB'.*did you mean"),
    (("--mount", "RICH"), r"--mount: no station has the mount code 'RICH'; the catalogue's "
                          r"codes are AZEL"),
])
def test_cli_filter_errors(args, match, capsys):
    assert cli_main(["stations", *args]) != 0
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1
    assert re.search(match, error[0])


def test_build_reproduces_the_committed_catalogue(tmp_path):
    pytest.importorskip("casacore", reason="the build reads casacore's Observatories table")
    output, report = tmp_path / "stations.ecsv", tmp_path / "crosscheck.txt"
    subprocess.run([sys.executable, str(BUILD), "--output", str(output),
                    "--report", str(report)], check=True, capture_output=True)
    assert output.read_text() == Path(sample_file("stations.ecsv")).read_text()
    assert report.read_text() == (ROOT / "catalogue" / "crosscheck.txt").read_text()


def test_build_script_is_importable():
    spec = importlib.util.spec_from_file_location("build_stations", BUILD)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert set(module.TOLERANCES) >= {"geodetic", "observatory"}
