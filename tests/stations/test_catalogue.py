# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The embedded station catalogue: provenance, networks, names, positions and its build."""

import importlib.util
import io
import re
import subprocess
import sys
from contextlib import redirect_stdout
from pathlib import Path

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import AltAz, HADec, SkyCoord
from astropy.table import Table
from astropy.time import Time

from astropy_feedrot import AltAzMount, CassegrainFocus, NasmythFocus
from astropy_feedrot.cli import main as cli_main
from astropy_feedrot.data import sample_file
from astropy_feedrot.stations.catalogue import (
    default_catalogue,
    get_antenna,
    get_network,
    networks,
    read_catalogue,
)
from astropy_feedrot.stations.labels import label_from_mount, mount_from_label

ROOT = Path(__file__).resolve().parent.parent.parent
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
    ("DSN", {"DSS14", "TIDBIN64", "DSS63"}),
    # SCHED locations.dat's pads; pyuvdata's known telescopes.
    ("VLA", {"VLA", "VLA_E1", "VLA_W72", "VLA_N72", "VLA-N8"}),
    ("ATCA", {"AT_W104", "AT_N2", "AT_W392"}),
    ("ATA", {"ATA"}), ("HERA", {"HERA"}), ("MWA", {"MWA"}), ("OVRO-LWA", {"OVRO-LWA"}),
    ("VGOS", {"GGAO12M", "WETTZ13S", "ISHIOKA", "RAEGSMAR", "RAEGYEB", "ONSA13NE", "NYALE13S",
              "WETTZ13N", "HOBART12", "KATH12M", "YARRA12M", "WESTFORD",
              # sked's position.cat (with DiFX's antenna_db), or a single source.
              "KOKEE12M", "MACGO12M", "ONSA13SW", "NYALE13N", "SESHAN13", "TIANMA13",
              "BADRT13V", "ZELRT13V"}),
    # simms's MeerKAT layout: the 64 dishes, and SCHED's MEERKAT.
    ("MeerKAT", {"MEERKAT", *(f"M{i:03d}" for i in range(64))}),
    ("GMVA", {"EFLSBERG", "PICOVEL"}),
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
def test_positions_on_the_surface(row):
    name = str(TABLE["name"][row])
    geodetic = default_catalogue().location(name).to_geodetic()
    # Telescope sites lie between the shore and the Chajnantor plateau (ALMA ~ 5 km).
    assert -100 * u.m < geodetic.height < 6 * u.km


def _build_module(monkeypatch):
    monkeypatch.syspath_prepend(str(BUILD.parent))  # its sibling module readers.py
    spec = importlib.util.spec_from_file_location("build_stations", BUILD)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_crosscheck_of_the_embedded_file(monkeypatch):
    # The build's own cross-check, run on the embedded file: each position
    # against every other source that holds the station (the files of
    # catalogue/sources), both moved to 2020.0.
    pytest.importorskip("casacore", reason="casadata's tables are read with python-casacore")
    build = _build_module(monkeypatch)
    sources = build.load_sources()
    counted = 0
    for row in ROWS:
        refs = [r for r in _text(row, "crosschecks").split(",") if r]
        xyz = [float(TABLE[c][row]) for c in "xyz"]
        vel = [float(TABLE[f"v{c}"][row]) for c in "xyz"]
        checks = build.crosscheck(str(TABLE["name"][row]), xyz, vel, float(TABLE["epoch"][row]),
                                  build.is_geodetic(_text(row, "position_source")), refs,
                                  sources)
        failed = [c for c in checks if c["status"] == "FAIL"]
        assert failed == [], (TABLE["name"][row], failed)
        for check in checks:
            if check["status"] == "ok":
                assert check["distance"] <= build.TOLERANCES[check["kind"]][0]
        counted += len(checks)
        measured = [c["distance"] for c in checks if c["status"] != "reference point"]
        if measured:
            assert TABLE["largest_difference"][row] == pytest.approx(max(measured), abs=1e-3)
    assert counted > 400


def test_tolerances():
    # 1 m between VLBI solutions, 50 m where a position comes from an
    # observatory or a compiled list; nothing else.
    text = (ROOT / "catalogue" / "crosscheck.txt").read_text()
    assert "geodetic     1.0 m" in text and "compiled    50.0 m" in text


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


@pytest.mark.parametrize("name, stations", [
    # Two-letter codes that SCHED, casadata and eht-imaging give two stations.
    ("Ap", "ALGOPARK.*APEX"), ("KP", "KP-VLBA.*KP12"), ("Go", "DSS13.*DSS15"),
    ("On", "ONSALA60.*ONSALA85"), ("YK", "YELLOWKN.*YLOW7296"), ("Jb", "JB_Mk_2.*JODLMKI"),
    ("Ti", "DSS34.*DSS36.*TIDBIN64"), ("Ro", "DSS54.*DSS63.*DSS65A"),
    # The planner's [Kitt Peak] is the VLBA antenna, SCHED's KITTPEAK the 12 m.
    ("Kitt Peak", "KP-VLBA.*KP12"),
])
def test_shared_names_are_refused(name, stations):
    with pytest.raises(ValueError, match=rf"ambiguous antenna name {name!r} in the embedded "
                       rf"station catalogue: it names {stations}[^;]*; give one of those names"):
        get_antenna(name)


def test_every_station_name_resolves_to_itself():
    for row in ROWS:
        assert get_antenna(str(TABLE["name"][row])).name == TABLE["name"][row]


@pytest.mark.parametrize("name, network, expected", [
    ("KP", "EHT", "KP12"), ("KP", "VLBA", "KP-VLBA"), ("Ap", "EHT", "APEX"),
    ("Ap", "IVS", "ALGOPARK"), ("kp", "eht", "KP12"), ("EFLSBERG", "EVN", "EFLSBERG"),
])
def test_network_chooses_among_shared_names(name, network, expected):
    assert get_antenna(name, network=network).name == expected
    assert default_catalogue().location(name, network=network) == \
        default_catalogue().location(expected)


def test_network_context_errors():
    with pytest.raises(ValueError, match=r"ambiguous antenna name 'KP'.*e\.g\. "
                       r"get_antenna\('KP', network='EHT'\)"):
        get_antenna("KP")
    with pytest.raises(ValueError, match=r"antenna 'KP' \(KP-VLBA \(.*\) or KP12 \(EHT\)\) "
                       r"is not a station of the network 'KVN'"):
        get_antenna("KP", network="KVN")
    with pytest.raises(ValueError, match=r"unknown network 'EHTT'"):
        get_antenna("KP", network="EHTT")


@pytest.mark.parametrize("name, expected", [
    # Codes and names of the sources the catalogue cites, and common names.
    ("GBT", "GBT-VLBA"), ("EB", "EFLSBERG"), ("Effelsberg", "EFLSBERG"),
    ("Robledo 70", "DSS63"), ("Ro7", "DSS63"), ("DSS-63", "DSS63"), ("DSS-14", "DSS14"),
    ("DSS-43", "TIDBIN64"), ("DSS43", "TIDBIN64"), ("Robledo 34", "DSS65A"),
    ("GLT", "GREENLAND"), ("SPT", "SPT"), ("SMA", "SMA"), ("PV", "PICOVEL"),
    ("Kitt Peak 12m", "KP12"), ("ARO 12m", "KP12"), ("TIDBIN64", "TIDBIN64"),
])
def test_source_names_resolve(name, expected):
    assert get_antenna(name).name == expected


def test_apex_position_and_focus():
    # eht-imaging arrays/EHT2025.txt (an independent file, read here
    # directly): APEX at 2225039.53 -5441197.63 -2479303.36; FR_ELEV_ANGLE +1.
    eht = _eht_file()
    apex = get_antenna("APEX")
    distance = np.linalg.norm(np.subtract(
        [apex.location.x.to_value(u.m), apex.location.y.to_value(u.m),
         apex.location.z.to_value(u.m)], eht["APEX"][:3]))
    assert distance < 50
    lat = apex.location.to_geodetic().lat.deg
    assert abs(lat - (-23.0058)) < 0.001  # not the planner's -22.9942
    assert apex.focus == NasmythFocus("right") and eht["APEX"][3] == 1


def test_smt_and_sma_focus_from_eht_imaging():
    eht = _eht_file()
    # FR_ELEV_ANGLE +1 for SMT (right Nasmyth), -1 for SMA (left Nasmyth) with
    # FR_OFFSET 45 deg; 0 for JCMT, ALMA (no Nasmyth).
    assert eht["SMT"][3] == 1 and get_antenna("SMT").focus == NasmythFocus("right")
    assert eht["SMA"][3] == -1 and get_antenna("SMA").focus == NasmythFocus("left")
    row = list(TABLE["name"]).index("SMA")
    assert TABLE["feed_offset"][row] == eht["SMA"][4] == 45
    for name in ("JCMT", "ALMA"):
        assert eht[name][3] == 0 and get_antenna(name).focus == CassegrainFocus()


# The EHT codes of eht-imaging's arrays/EHT2025.txt with FR_PAR_ANGLE 1 (the rows
# whose feed rotation the file states; FR_PAR_ANGLE 0 marks rows without one).
EHT_FEEDS = {"PV": "PICOVEL", "SMT": "SMT", "SMA": "SMA", "LMT": "LMT", "ALMA": "ALMA",
             "APEX": "APEX", "JCMT": "JCMT"}


@pytest.mark.parametrize("code", sorted(EHT_FEEDS))
def test_eht_feed_rotation_is_eht_imaging_formula(code):
    # eht-imaging's feed rotation: FR_PAR * PA + FR_ELEV * El + FR_OFFSET, with
    # the coefficients read from its array file; PA from ERFA's hd2pa on
    # astropy's HADec, El from astropy's AltAz (independent of the package's
    # engine). The SMA's 45 deg offset is applied by get_antenna (a fixed rotator).
    fr_par, fr_elev, fr_off = _eht_coefficients()[code]
    assert fr_par == 1
    antenna = get_antenna(EHT_FEEDS[code])
    source = SkyCoord("12h30m49.42s +12d23m28.0s")  # M87
    times = Time("2025-04-10T00:00") + np.arange(0, 24, 0.5) * u.hour
    hadec = source.transform_to(HADec(obstime=times, location=antenna.location))
    altaz = source.transform_to(AltAz(obstime=times, location=antenna.location))
    up = altaz.alt > 5 * u.deg
    assert up.any()
    lat = antenna.location.to_geodetic().lat.to_value(u.rad)
    pa = np.rad2deg(erfa.hd2pa(hadec.ha.to_value(u.rad), hadec.dec.to_value(u.rad), lat))
    expected = fr_par * pa + fr_elev * altaz.alt.deg + fr_off
    got = antenna.feed_rotation(source, times).deg
    difference = (got - expected + 180) % 360 - 180
    assert np.max(np.abs(difference[up])) < 1e-6  # deg


def _eht_coefficients():
    rows = {}
    path = ROOT / "catalogue" / "sources" / "eht-imaging" / "EHT2025.txt"
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            parts = line.split()
            rows[parts[0]] = tuple(float(v) for v in parts[6:9])
    return rows


def test_robledo_70_is_dss63():
    # SCHED stations.dat: DSS63 is "Madrid 70m"; DSS65A the 34 m, 534 m away.
    dss63, dss65 = get_antenna("Robledo 70"), get_antenna("DSS65A")
    assert dss63.name == "DSS63"
    apart = np.linalg.norm([(getattr(dss63.location, c) - getattr(dss65.location, c))
                            .to_value(u.m) for c in "xyz"])
    assert 450 < apart < 600


def test_kitt_peak_12m_is_not_the_vlba_antenna():
    # SCHED locations.dat KP12 ("From Bob Phillips 28 Apr 1997") and KP-VLBA: 402 m apart.
    kp12, kp25 = get_antenna("KP", network="EHT"), get_antenna("KP", network="VLBA")
    apart = np.linalg.norm([(getattr(kp12.location, c) - getattr(kp25.location, c))
                            .to_value(u.m) for c in "xyz"])
    assert 390 < apart < 410


def _eht_file():
    rows = {}
    path = ROOT / "catalogue" / "sources" / "eht-imaging" / "EHT2025.txt"
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            parts = line.split()
            rows[parts[0]] = [float(v) for v in parts[1:4]] + [float(parts[7]),
                                                               float(parts[8])]
    return rows


def test_unknown_station_gives_the_nearest_five():
    with pytest.raises(ValueError, match=r"unknown antenna 'EFFELSBURG' in the embedded station "
                       r"catalogue; the nearest names: EFLSBERG, [^,]+, [^,]+, [^,]+, [^,]+$"):
        get_antenna("EFFELSBURG")


def test_ambiguous_alias_in_a_users_catalogue():
    table = Table({"name": ["A", "B"], "aliases": ["XX", "XX,b2"],
                   "x": [4075539.5, 4075540.5] * u.m, "y": [931735.6, 931735.6] * u.m,
                   "z": [4801629.6, 4801629.6] * u.m, "mount": ["AZEL", "AZEL"]})
    path = io.StringIO()
    table.write(path, format="ascii.ecsv")
    catalogue = read_catalogue(io.StringIO(path.getvalue()))
    assert catalogue.get_antenna("b2").name == "B"
    with pytest.raises(ValueError, match=r"ambiguous antenna name 'xx'.*it names A and B; give one "
                       r"of those names$"):
        catalogue.get_antenna("xx")
    assert catalogue.networks() == []
    with pytest.raises(ValueError, match=r"unknown network 'VLBA'.*Known networks: none"):
        catalogue.get_network("VLBA")


@pytest.mark.parametrize("name, code", [
    # IVS antenna-info (Nothnagel) MO_EQUA, MO_XYNO, MO_RICH; SCHED's 2005f file
    # and casadata's copy say 'altz' for all of them.
    ("HATCREEK", "EQUA"), ("MARPOINT", "EQUA"), ("NRAO85_1", "EQUA"), ("NRAO85_3", "EQUA"),
    ("HRAS_085", "EQUA"), ("KAUAI", "X-YN"), ("MOJAVE12", "X-YN"), ("SANTIA12", "X-YN"),
    ("RICHMOND", "RICH"), ("HOBART26", "X-YE"), ("ONSALA85", "EQUA"), ("HARTRAO", "EQUA"),
])
def test_polar_and_xy_mounts(name, code):
    assert TABLE["mount"][list(TABLE["name"]).index(name)] == code
    assert get_antenna(name).mount == mount_from_label(code, "geodetic")[0]


def test_prime_focus_from_antenna_info():
    # antenna-info FO_PRIM for WESTFORD and PARKES (the paper: prime focus too).
    from astropy_feedrot import PrimeFocus
    assert get_antenna("WESTFORD").focus == PrimeFocus()
    assert get_antenna("PARKES").focus == PrimeFocus()


def test_connected_arrays_of_pyuvdata():
    # pyuvdata 3.2.8 KNOWN_TELESCOPES mount_type: 'alt-az' (ATA), 'fixed' (HERA,
    # OVRO-LWA), 'phased' (MWA, whose dipoles are fixed to the ground).
    from astropy_feedrot import StationaryMount
    assert get_antenna("ATA").mount == AltAzMount()
    for name in ("HERA", "OVRO-LWA", "MWA"):
        assert isinstance(get_antenna(name).mount, StationaryMount)


def test_eht_is_the_current_array():
    # eht-imaging arrays/EHT2025.txt without CARMA (closed in 2015): the
    # EHT's eleven stations.
    names = {a.name for a in get_network("EHT")}
    assert names == {"ALMA", "APEX", "GREENLAND", "JCMT", "KP12", "LMT", "NOEMA", "PICOVEL",
                     "SMA", "SMT", "SPT"}
    assert set(_eht_file()) - {"CARMA"} == {"ALMA", "APEX", "GLT", "JCMT", "KP", "LMT", "PDB",
                                            "PV", "SMA", "SMT", "SPT"}


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
    (("--mount", "NASP"), r"--mount: no station has the mount code 'NASP'; the catalogue's "
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


def test_cli_station_names(capsys):
    # feedrot natural NAME: an unknown name, a shared name, an unknown
    # network: one line each; NAME@NETWORK chooses.
    span = ["--source", "03h19m48.16s +41d30m42.1s", "--start", "2024-01-01T00:00",
            "--stop", "2024-01-01T01:00", "--step", "30min"]
    for name, match in [("EFFELSBURG", r"unknown antenna 'EFFELSBURG'.*nearest names: "
                                       r"EFLSBERG(, [^,]+){4}$"),
                        # in the command line's words: KP@EHT, not get_antenna(...)
                        ("KP", r"ambiguous antenna name 'KP'.*KP-VLBA.*KP12.*e\.g\. KP@EHT$"),
                        ("KP@EHTT", r"unknown network 'EHTT'")]:
        assert cli_main(["natural", name, *span]) != 0
        error = capsys.readouterr().err.strip().splitlines()
        assert len(error) == 1 and re.search(match, error[0]), error
    assert cli_main(["natural", "KP@EHT", *span]) == 0
    capsys.readouterr()


def test_build_script_is_importable(monkeypatch):
    module = _build_module(monkeypatch)
    assert set(module.TOLERANCES) == {"geodetic", "compiled"}
    # Every exception and reference point says why.
    for table in (module.EXCEPTIONS, module.REFERENCE_POINTS):
        for (station, tag), (limit, reason) in table.items():
            assert tag in module.SOURCE_TAGS and limit > 0 and len(reason) > 20


def test_build_fails_on_an_unexplained_disagreement(monkeypatch):
    pytest.importorskip("casacore", reason="casadata's tables are read with python-casacore")
    module = _build_module(monkeypatch)
    # Without its reason, the planner's APEX 1.29 km away fails the build.
    monkeypatch.delitem(module.EXCEPTIONS, ("APEX", "planner"))
    rows, *_ = module.build()
    failed = module.failures(rows)
    assert any(line.startswith("APEX: 1287.") and "planner:APEX" in line for line in failed)
    # A reason that no comparison needs fails it too (Effelsberg agrees with
    # the planner to 0.16 m).
    monkeypatch.setitem(module.EXCEPTIONS, ("EFLSBERG", "planner"), (5.0, "none needed"))
    assert "EFLSBERG: the listed reason for planner is not needed (no such difference)" in \
        module.failures(rows)


def test_every_alias_names_its_station_or_is_refused_naming_it():
    # Every code and name the sources give a station (the aliases column)
    # resolves to it, or is refused as shared, naming it among the others.
    catalogue = default_catalogue()
    for row in ROWS:
        name = str(TABLE["name"][row])
        for alias in filter(None, (a.strip() for a in _text(row, "aliases").split(","))):
            try:
                assert catalogue.get_antenna(alias).name == name, (alias, name)
            except ValueError as error:
                assert str(error).startswith(f"ambiguous antenna name {alias!r}")
                assert f" {name} (" in str(error) or str(error).endswith(f" {name}") or \
                    f" {name};" in str(error), (alias, name, str(error))


def test_spt_near_the_pole():
    # Closed form: at the pole the zenith is the celestial pole, so the
    # parallactic angle is 180 deg for every source; the catalogue's SPT (DiFX,
    # 1.16 km from the pole) and eht-imaging's (on the pole) agree to 0.02 deg.
    from astropy.coordinates import EarthLocation, SkyCoord
    from astropy.time import Time

    from astropy_feedrot import Antenna
    times = Time("2024-04-01T00:00") + np.arange(0, 24, 3) * u.hour
    source = SkyCoord("17h45m40s -29d00m28s")
    spt = get_antenna("SPT")
    on_pole = Antenna(EarthLocation.from_geocentric(*_eht_file()["SPT"][:3], unit=u.m),
                      AltAzMount())
    for antenna in (spt, on_pole):
        angle = antenna.feed_rotation(source, times).wrap_at(360 * u.deg)
        assert np.all(np.abs(angle.deg - 180) < 0.02)


def test_cli_coverage_station_names(capsys):
    # feedrot coverage --stations: NAME@NETWORK chooses; a shared name alone is
    # refused on one line.
    span = ["--source", "3C84=03h19m48.16s +41d30m42.1s", "--start", "2024-03-01T00:00",
            "--stop", "2024-03-01T06:00", "--step", "60min"]
    assert cli_main(["coverage", "--stations", "KP@EHT", "EFLSBERG", *span]) == 0
    assert "KP12" in capsys.readouterr().out
    assert cli_main(["coverage", "--stations", "KP", "EFLSBERG", *span]) != 0
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and "ambiguous antenna name 'KP'" in error[0], error
    assert error[0].endswith("e.g. KP@EHT"), error


def test_meerkat_dishes():
    # MeerKAT has 64 dishes, M000 to M063 (SARAO); its longest baseline is 8 km,
    # so every dish lies within 8 km of the catalogue's MEERKAT, and no two
    # 13.5 m dishes can stand closer than their diameter.
    dishes = [a for a in get_network("MeerKAT") if a.name != "MEERKAT"]
    assert sorted(a.name for a in dishes) == [f"M{i:03d}" for i in range(64)]
    xyz = np.array([[a.location.x.to_value(u.m), a.location.y.to_value(u.m),
                     a.location.z.to_value(u.m)] for a in dishes])
    centre = get_antenna("MEERKAT").location
    centre = np.array([centre.x.to_value(u.m), centre.y.to_value(u.m), centre.z.to_value(u.m)])
    assert np.all(np.linalg.norm(xyz - centre, axis=1) < 8000)
    separation = np.linalg.norm(xyz[:, None] - xyz[None], axis=2) + np.eye(64) * 1e9
    assert separation.min() > 13.5
    assert all(a.mount == AltAzMount() for a in dishes)
    assert get_antenna("m063").name == "M063"


def test_single_source_stations_say_why():
    # A station kept with one source is named, with its reason, in
    # crosscheck.txt and in its position_source (the docs page's column).
    text = (ROOT / "catalogue" / "crosscheck.txt").read_text()
    single = {"NOBEYA45", "NYALE13N", "BADRT13V", "ZELRT13V", *(f"M{i:03d}" for i in range(64))}
    for row in ROWS:
        name = str(TABLE["name"][row])
        if name in single:
            assert "; single source: " in _text(row, "position_source"), name
            listed = "\n  M000-M063  " if re.fullmatch(r"M0[0-6][0-9]", name) else \
                f"\n  {name} "
            assert listed in text, name
    assert {str(n) for n in TABLE["name"]} >= single


def test_nobeyama_45m_is_not_the_6m_antenna():
    # sked's NOBEYA45 is 2.6 m from its NOBEY_6M: not the 45 m dish, whose
    # centre no other antenna can stand within 22 m of. The catalogue's is
    # casacore's NRO, at the 45 m's latitude (35.9445 deg; the 6 m's 35.9409).
    nro = get_antenna("Nobeyama 45m")
    assert nro.name == "NOBEYA45" and get_antenna("NRO").name == "NOBEYA45"
    assert nro.location.to_geodetic().lat.deg == pytest.approx(35.9445, abs=2e-4)
    six = get_antenna("NOBEY_6M").location
    assert np.linalg.norm([(nro.location.x - six.x).to_value(u.m),
                           (nro.location.y - six.y).to_value(u.m),
                           (nro.location.z - six.z).to_value(u.m)]) > 22.5
    text = (ROOT / "catalogue" / "crosscheck.txt").read_text()
    assert re.search(r"NOBEYA45 +sked:NOBEYA45 +407\.\d+ m +\(exception\)", text)


@pytest.mark.parametrize("name, code, difx", [
    # sked's position.cat (GSFC 2020c or the observatory) against DiFX's
    # antenna_db, each within the 50 m of a compiled position (0.01 to 1.1 m).
    ("KOKEE12M", "K2", "Kokee 12"), ("MACGO12M", "Mg", "MacDonald"),
    ("ONSA13SW", "Ow", "Onsala 13SW"), ("SESHAN13", "S6", "Seshan 13m"),
    ("TIANMA13", "T1", "Tianma 13m"),
])
def test_vgos_antennas_from_sked(name, code, difx):
    row = list(TABLE["name"]).index(name)
    assert _text(row, "position_source").startswith("sked_catalogs (commit 5aa7e2a) position.cat")
    assert f"difx:{difx}" in _text(row, "crosschecks").split(",")
    assert TABLE["largest_difference"][row] < 1.1
    assert get_antenna(code).name == name
    assert "VGOS" in _text(row, "networks").split(",")
