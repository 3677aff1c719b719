# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The station catalogue's receptors, and their use for files that give none.

The VLBA file (``mojave.uvfits``, written by AIPS: R and L at POLAA = POLAB =
0) is read by pyuvdata and stripped of its feeds, as pyuvdata reads a Miriad
file; corrected with the catalogue's receptors it must equal the same data
corrected with ``--feeds R,L``, and the file as written.
"""

import io
import math
import os
import warnings

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation

from astropy_feedrot import AltAzMount, Antenna, CatalogueReceptorsWarning, get_antenna
from astropy_feedrot.antennas.receptors import Receptors
from astropy_feedrot.stations.catalogue import default_catalogue, read_catalogue
from astropy_feedrot.visibilities import (
    CATALOGUE_TOLERANCE,
    catalogue_receptors,
    parse_feeds,
    read_antennas,
)

DATA = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data", "uvdata")
MOJAVE = os.path.join(DATA, "mojave.uvfits")
VLBA_NAMES = ["BR-VLBA", "FD-VLBA", "HN-VLBA", "KP-VLBA", "LA-VLBA", "MK-VLBA", "NL-VLBA",
              "OV-VLBA", "PIETOWN", "SC-VLBA"]


# --- the catalogue's column ---------------------------------------------------------


def test_the_column_is_read_and_every_value_cites_its_source():
    table = default_catalogue().table
    stated = [row for row in table if row["receptors"]]
    assert len(stated) == 131  # 10 VLBA + the VLA and its 72 pads + 45 ATCA + ATA, OVRO-LWA, MWA
    assert all(row["receptors_source"] for row in stated)
    assert not any(row["receptors_source"] for row in table if not row["receptors"])


@pytest.mark.parametrize("name", VLBA_NAMES)
def test_vlba_receptors_are_those_aips_wrote(name):
    # mojave.uvfits (AIPS): POLTYA R, POLTYB L, POLAA = POLAB = 0 at every VLBA station.
    written = {a.name.strip(): a.receptors for a in read_antennas(MOJAVE)[0].values()}
    code = {"PIETOWN": "PT"}.get(name, name[:2])
    assert get_antenna(name).receptors == written[code] == Receptors("RL", [0, 0] * u.deg)


@pytest.mark.parametrize("name", ["AT_W104", "ATCA", "AT_N2"])
def test_atca_receptors_are_miriads(name):
    # Miriad cat/observatories.dat: atca evector 45 deg (the X feed from the
    # vertical); Y 90 deg on.
    receptors, source = default_catalogue().receptors(name)
    assert get_antenna(name).receptors == receptors == Receptors("XY", [45, 135] * u.deg)
    assert "evector 45" in source and "not at 7 mm" in source


def test_pyuvdata_arrays_as_pyuvdata_gives_them():
    # pyuvdata's KNOWN_TELESCOPES (the installed package, read here by pyuvdata
    # itself): ATA x at pi/2, y at 0 on alt-az antennas; OVRO-LWA and MWA the
    # same azimuths on dipoles fixed to the ground, which the catalogue counts
    # from the east dipole (as antennas_from_uvdata reads PAPER's file).
    telescopes = pytest.importorskip("pyuvdata.telescopes")
    for name, offset in (("ATA", 0.0), ("OVRO-LWA", -90.0), ("MWA", -90.0)):
        known = telescopes.KNOWN_TELESCOPES[name]
        expected = Receptors("".join(known["feed_array"]),
                             [math.degrees(a) + offset for a in known["feed_angle"]] * u.deg)
        assert get_antenna(name).receptors == expected


def test_stations_without_a_statement_have_none():
    for name in ("EFLSBERG", "ALMA", "M000", "YEBES40M"):
        assert get_antenna(name).receptors is None
        assert default_catalogue().receptors(name) == (None, "")


CATALOGUE = """# %ECSV 1.0
# ---
# datatype:
# - {{name: name, datatype: string}}
# - {{name: x, unit: m, datatype: float64}}
# - {{name: y, unit: m, datatype: float64}}
# - {{name: z, unit: m, datatype: float64}}
# - {{name: mount, datatype: string}}
# - {{name: receptors, datatype: string}}
name x y z mount receptors
MYDISH 4075539.5 931735.6 4801629.6 AZEL {receptors}
"""


def test_a_catalogue_of_ones_own_with_receptors():
    mine = read_catalogue(io.StringIO(CATALOGUE.format(receptors="X:10,Y:100")))
    assert mine.get_antenna("mydish").receptors == Receptors("XY", [10, 100] * u.deg)
    assert mine.receptors("mydish") == (Receptors("XY", [10, 100] * u.deg), "")
    with pytest.raises(ValueError, match=r"<stream>, station MYDISH: receptors 'Q,L': unknown "
                                         r"receptor 'Q'"):
        read_catalogue(io.StringIO(CATALOGUE.format(receptors="Q,L")))


def test_stations_named():
    catalogue = default_catalogue()
    assert catalogue.stations_named("KP") == ["KP-VLBA", "KP12"]
    assert catalogue.stations_named("pt") == ["PIETOWN"]
    assert catalogue.stations_named("nowhere") == []


# --- antennas without receptors -------------------------------------------------------


def bare(name, offset_m=0.0, station=None):
    """An antenna at a station's position (moved north-ish by offset_m), without receptors."""
    place = get_antenna(station or name).location
    xyz = [place.x.to_value(u.m), place.y.to_value(u.m), place.z.to_value(u.m) + offset_m]
    return Antenna(EarthLocation.from_geocentric(*xyz, unit=u.m), AltAzMount(), name=name)


def test_catalogue_receptors_by_name_and_position():
    antennas = {1: bare("FD"), 2: bare("KP", station="KP-VLBA"),
                3: bare("XX", offset_m=10.0, station="LA-VLBA"),
                4: bare("LA", offset_m=150.0), 5: bare("EFLSBERG"),
                6: Antenna(get_antenna("BR-VLBA").location, AltAzMount(), name="BR",
                           receptors=Receptors("RL", [10, 10] * u.deg))}
    with pytest.warns(CatalogueReceptorsWarning, match=r"1 \(FD as FD-VLBA\), 2 \(KP as "
                      r"KP-VLBA\): R:0,L:0 \(VLBA Observational Status Summary 2018A"):
        given, note = catalogue_receptors(antennas)
    assert given[1].receptors == given[2].receptors == Receptors("RL", [0, 0] * u.deg)
    assert given[6].receptors == Receptors("RL", [10, 10] * u.deg)  # the file's own wins
    assert [given[n].receptors for n in (3, 4, 5)] == [None] * 3
    # An unknown name 10 m from any station, and a known one too far from it,
    # are matched by position neither: no station with receptors within 5 m.
    assert note == ("the station catalogue gave receptors to antennas 1 (FD as FD-VLBA), 2 (KP "
                    "as KP-VLBA), not to 3 (XX: its name is not in the catalogue, and no "
                    "station within 5 m states receptors (nearest: LA-VLBA, 10.0 m)); 4 (LA: "
                    "the catalogue's LA-VLBA 150.0 m away, beyond 100 m, and no station within "
                    "5 m states receptors (nearest: LA-VLBA, 150.0 m)); 5 (EFLSBERG: the "
                    "catalogue's EFLSBERG states no receptors)")
    # Only the antennas asked for; none from catalogue=False.
    assert catalogue_receptors(antennas, numbers=[3, 6]) == (
        antennas, "the station catalogue gave receptors to antennas none, not to 3 (XX: its "
                  "name is not in the catalogue, and no station within 5 m states receptors "
                  "(nearest: LA-VLBA, 10.0 m))")
    assert catalogue_receptors(antennas, False) == (antennas, "")
    assert CATALOGUE_TOLERANCE == 100 * u.m


def test_a_shared_name_far_from_both_stations():
    far = bare("KP", offset_m=5000.0, station="KP-VLBA")
    _, note = catalogue_receptors({1: far})
    assert note.endswith(r"not to 1 (KP: the catalogue's KP-VLBA 5000.0 m away, KP12 "
                         f"{far_from('KP12', far):.1f} m away, beyond 100 m, and no station "
                         "within 5 m states receptors (nearest: KP-VLBA, 5000.0 m))")


def far_from(station, antenna):
    a, b = get_antenna(station).location, antenna.location
    return float(np.sqrt(sum((getattr(a, c) - getattr(b, c)).to_value(u.m) ** 2 for c in "xyz")))


# --- files without receptors ---------------------------------------------------------------


pyuvdata = pytest.importorskip("pyuvdata")
from astropy_feedrot.cli import main  # noqa: E402
from astropy_feedrot.visibilities import correct_file, correct_uvdata, read_uvdata  # noqa: E402


@pytest.fixture(scope="module")
def vlba():
    """mojave.uvfits as read, and the same without feeds (as pyuvdata reads Miriad files)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's complaints about the file's uvw and site
        uv = read_uvdata(MOJAVE)
    # AIPS removed the parallactic angle of these data (its CLCOR PANG record, which
    # refuses a second removal: tests/visibilities/test_history.py); the tests here are of the
    # receptors, so the record is left out and the data taken as raw.
    uv.history = "\n".join(line for line in uv.history.splitlines() if "PANG" not in line)
    stripped = uv.copy()
    stripped.telescope.feed_array = stripped.telescope.feed_angle = None
    stripped.telescope.Nfeeds = None
    return uv, stripped


def test_vlba_data_without_feeds_are_corrected_from_the_catalogue(vlba):
    uv, stripped = vlba
    with pytest.warns(CatalogueReceptorsWarning, match=r"4 \(KP as KP-VLBA\).*9 \(PT as "
                      r"PIETOWN\), 10 \(SC as SC-VLBA\): R:0,L:0"):
        from_catalogue = correct_uvdata(stripped)
    given = correct_uvdata(stripped, feeds=parse_feeds("R,L"))
    as_written = correct_uvdata(uv)
    np.testing.assert_array_equal(from_catalogue.data_array, given.data_array)
    np.testing.assert_array_equal(from_catalogue.data_array, as_written.data_array)
    assert np.nanmax(np.abs(from_catalogue.data_array - uv.data_array)) > 1  # it did turn


def test_feeds_given_win_over_the_catalogue(vlba):
    _, stripped = vlba
    turned = correct_uvdata(stripped, feeds=parse_feeds("R:10,L:10"))  # no warning
    plain = correct_uvdata(stripped, feeds=parse_feeds("R,L"))
    assert not np.allclose(turned.data_array, plain.data_array)


def renamed(uv, old, new):
    out = uv.copy()
    names = [str(n).strip() for n in out.telescope.antenna_names]
    names[names.index(old)] = new
    out.telescope.antenna_names = np.array(names)
    return out


def moved(uv, name, metres):
    out = uv.copy()
    names = [str(n).strip() for n in out.telescope.antenna_names]
    out.telescope.antenna_positions[names.index(name), 2] += metres
    return out


def test_an_unknown_name_is_matched_by_position_or_refused(vlba):
    uv, stripped = vlba
    # AIPS put LA 0.21 m from the catalogue's LA-VLBA: renamed, it is matched there.
    with pytest.warns(CatalogueReceptorsWarning, match=r"5 \(XX as LA-VLBA by position, "
                      r"0\.21 m\)"):
        renamed_data = correct_uvdata(renamed(stripped, "LA", "XX"))
    np.testing.assert_array_equal(renamed_data.data_array, correct_uvdata(uv).data_array)
    # Renamed and 10 m away from it, it takes the receptors that every station of
    # the data's telescope, the VLBA, states.
    far = renamed(moved(stripped, "LA", 10.0), "LA", "XX")
    with pytest.warns(CatalogueReceptorsWarning, match=r"5 \(XX by the telescope VLBA, "
                      r"network VLBA: every station states these\)"):
        telescope_data = correct_uvdata(far)
    np.testing.assert_allclose(telescope_data.data_array, correct_uvdata(uv).data_array,
                               atol=1e-4)  # 10 m further: a few microradians
    # With a telescope the catalogue does not know, it is refused, with what the
    # catalogue found.
    far.telescope.name = "ELSEWHERE"
    with pytest.warns(CatalogueReceptorsWarning), \
            pytest.raises(ValueError, match=r"antenna 5 \(XX\) has no receptors: the data give "
                          r"no telescope.feed_array/feed_angle.*--feeds R,L on the command "
                          r"line\); the station catalogue gave receptors to antennas 1 \(BR as "
                          r"BR-VLBA\), .*, not to 5 \(XX: its name is not in the catalogue, and "
                          r"no station within 5 m states receptors \(nearest: LA-VLBA, "
                          r"10\.\d m\), and the catalogue has no network or station "
                          r"'ELSEWHERE'\)$"):
        correct_uvdata(far)


def test_a_station_too_far_from_its_namesake_is_refused(vlba):
    _, stripped = vlba
    away = moved(stripped, "LA", 200.0)
    away.telescope.name = "ELSEWHERE"
    with pytest.warns(CatalogueReceptorsWarning), \
            pytest.raises(ValueError, match=r"antenna 5 \(LA *\) has no receptors: .*not to 5 "
                          r"\(LA: the catalogue's LA-VLBA 2\d\d\.\d m away, beyond 100 m, and no "
                          r"station within 5 m states receptors \(nearest: LA-VLBA, "
                          r"2\d\d\.\d m\), and the catalogue has no network or station "
                          r"'ELSEWHERE'\)$"):
        correct_uvdata(away)
    with pytest.raises(ValueError, match=r"antenna 1 \(BR *\) has no receptors: .*command line\)$"):
        correct_uvdata(stripped, catalogue=False)


def test_correct_file_and_the_command_line(vlba, tmp_path, capsys):
    _, stripped = vlba
    source = tmp_path / "bare.uvh5"
    with warnings.catch_warnings():
        # pyuvdata, writing and reading the file: its uvws do not match its positions.
        warnings.filterwarnings("ignore", message="The uvw_array does not match")
        stripped.write_uvh5(source)
        with pytest.warns(CatalogueReceptorsWarning, match="FD as FD-VLBA"):
            correct_file(source, tmp_path / "catalogue.uvh5")
        correct_file(source, tmp_path / "given.uvh5", feeds=parse_feeds("R,L"))
        assert main(["correct", str(source), "-o", str(tmp_path / "cli.uvh5"), "--quiet"]) == 0
    assert "feedrot: warning: receptors from the station catalogue for antennas the file " \
           "gives none: 1 (BR as BR-VLBA)" in capsys.readouterr().err
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's complaints about the file's uvw and site
        data = [read_uvdata(tmp_path / f"{name}.uvh5").data_array
                for name in ("catalogue", "given", "cli")]
    np.testing.assert_array_equal(data[0], data[1])
    np.testing.assert_array_equal(data[0], data[2])
