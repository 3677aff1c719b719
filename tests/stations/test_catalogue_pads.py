# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The station catalogue's receptors for antennas matched by position, on their pads.

The real case is the VLA Measurement Set of pyuvdata's test data
(``tests/data/uvdata``, written by CASA's importuvfits): its ANTENNA table
names the antennas ``1``...``28`` on stations ``W09``, ``E02``..., pyuvdata
names them by their stations, and neither is the catalogue's name of the pad
(``VLA_W9``). Its positions and the catalogue's pads (SCHED's
``locations.dat``, "VLA antenna data Sep. 28, 2011") are independent
sources; its FEED table gives R and L at 0 deg, which the catalogue must give
back. The ATCA's antennas (``CA01``...``CA06``) are placed on the pads of its
6C configuration (W0, W10, W113, W140, W182, W392).
"""

import io
import os
import re
import tarfile
import warnings

import numpy as np
import pytest
import uvdata_model as model
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord

from astropy_feedrot import AltAzMount, Antenna, CatalogueReceptorsWarning, get_antenna
from astropy_feedrot.antennas.receptors import Receptors
from astropy_feedrot.cli import main
from astropy_feedrot.stations.catalogue import default_catalogue, read_catalogue
from astropy_feedrot.visibilities import (
    CATALOGUE_TOLERANCE,
    PAD_TOLERANCE,
    catalogue_receptors,
    correct_uvdata,
    ms_antennas,
    read_uvdata,
)

DATA = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data", "uvdata")
VLA_MS = "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms.tar.gz"
ATCA_6C = ["AT_W0", "AT_W10", "AT_W113", "AT_W140", "AT_W182", "AT_W392"]
# Miriad's cat/observatories.dat (catalogue/sources/miriad): "atca evector 45.0",
# the X feed 45 deg from the vertical, Y 90 deg on.
ATCA_RECEPTORS = Receptors("XY", [45, 135] * u.deg)
# A few centimetres off each pad, as a file's positions are.
JITTER = np.array([[0.03, -0.02, 0.04], [-0.05, 0.01, 0.02], [0.02, 0.04, -0.03],
                   [0.0, -0.06, 0.01], [0.04, 0.03, 0.05], [-0.02, -0.03, -0.04]])


def xyz(location):
    return np.array([getattr(location, c).to_value(u.m) for c in "xyz"])


def at(station, offset=(0.0, 0.0, 0.0), name=None, north=0.0):
    """An antenna without receptors at a station, moved by offset (m, geocentric) and north."""
    place = get_antenna(station).location
    lat, lon = place.lat.rad, place.lon.rad
    to_north = np.array([-np.sin(lat) * np.cos(lon), -np.sin(lat) * np.sin(lon), np.cos(lat)])
    position = xyz(place) + np.asarray(offset) + north * to_north
    return Antenna(EarthLocation.from_geocentric(*position, unit=u.m), AltAzMount(), name=name)


def given(antennas, **kwargs):
    """catalogue_receptors, and the text of its warning (empty if none)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out, note = catalogue_receptors(antennas, **kwargs)
    messages = [str(w.message) for w in caught if w.category is CatalogueReceptorsWarning]
    assert len(messages) <= 1
    return out, note, messages[0] if messages else ""


@pytest.fixture(scope="module")
def vla_ms(tmp_path_factory):
    pytest.importorskip("casacore")
    tmp = tmp_path_factory.mktemp("vla")
    with tarfile.open(os.path.join(DATA, VLA_MS)) as tf:
        top = tf.getnames()[0].split("/")[0]
        tf.extractall(tmp, filter="data")
    return tmp / top


# --- the tolerance ----------------------------------------------------------------


def test_pad_tolerance_keeps_the_catalogues_stations_apart():
    # Stations with receptors closer than three times the tolerance: only the
    # VLA's reference point and the pad N1 (0.87 m apart, both R:0,L:0), so an
    # antenna within 5 m of one pad is more than 10 m from every other.
    catalogue = default_catalogue()
    names = [n for n in catalogue.names if catalogue.receptors(n)[0] is not None]
    places = np.array([xyz(catalogue.location(n)) for n in names])
    distance = np.linalg.norm(places[:, None] - places[None], axis=-1)
    close = {tuple(sorted((names[i], names[j]))) for i, j in zip(*np.nonzero(
        distance < 3 * PAD_TOLERANCE.to_value(u.m))) if i != j}
    assert close == {("VLA", "VLA_N1")}
    assert catalogue.receptors("VLA")[0] == catalogue.receptors("VLA_N1")[0]
    assert PAD_TOLERANCE == 5 * u.m and CATALOGUE_TOLERANCE == 100 * u.m


# --- the VLA's Measurement Set --------------------------------------------------------


def test_vla_ms_antennas_take_their_feed_receptors_by_position(vla_ms):
    antennas = ms_antennas(vla_ms)
    bare = {n: Antenna(a.location, a.mount, a.focus, name=a.name) for n, a in antennas.items()}
    out, note, message = given(bare)
    assert note == ""
    assert len(antennas) == 19
    for number, antenna in antennas.items():
        assert antenna.receptors == Receptors("RL", [0, 0] * u.deg)  # its FEED table
        assert out[number].receptors == antenna.receptors
    assert message.startswith("receptors from the station catalogue for antennas the file "
                              "gives none: 0 (1 as VLA_W9 by position, 0.43 m), 1 (2 as VLA_E2 "
                              "by position, 0.42 m)")
    assert "11 (12 as VLA_E8 by position, 0.43 m)" in message  # SCHED's VLA1 pad
    assert "27 (28 as VLA-N8 by position, 0.44 m)" in message  # a geodetic station
    assert "7 (8 as VLA_N1 by position, 0.42 m)" in message  # not VLA, 1.28 m away
    # The MS's antennas and SCHED's pads agree to 0.42-0.45 m (0.40 m of it vertical).
    distances = [float(d) for d in re.findall(r"by position, (\d\.\d\d) m", message)]
    assert len(distances) == 19 and 0.41 <= min(distances) <= max(distances) <= 0.45


def test_vla_ms_through_pyuvdata_corrected_from_the_catalogue(vla_ms):
    pytest.importorskip("pyuvdata")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's complaints about the file
        uv = read_uvdata(vla_ms)
    assert list(uv.telescope.antenna_names[:3]) == ["W09", "E02", "E09"]
    stripped = uv.copy()
    stripped.telescope.feed_array = stripped.telescope.feed_angle = None
    stripped.telescope.Nfeeds = None
    with pytest.warns(CatalogueReceptorsWarning, match=r"0 \(W09 as VLA_W9 by position, "
                      r"0\.43 m\), 1 \(E02 as VLA_E2 by position, 0\.42 m\)"):
        from_catalogue = correct_uvdata(stripped)
    as_written = correct_uvdata(uv)
    np.testing.assert_array_equal(from_catalogue.data_array, as_written.data_array)
    assert np.nanmax(np.abs(from_catalogue.data_array - uv.data_array)) > 0  # it did turn


# --- the ATCA's pads ----------------------------------------------------------------


def test_atca_antennas_on_their_pads():
    antennas = {k + 1: at(pad, JITTER[k], name=f"CA0{k + 1}") for k, pad in enumerate(ATCA_6C)}
    out, note, message = given(antennas)
    assert note == ""
    assert all(out[n].receptors == ATCA_RECEPTORS for n in antennas)
    labels = ", ".join(f"{k + 1} (CA0{k + 1} as {pad} by position, "
                       f"{np.linalg.norm(JITTER[k]):.2f} m)" for k, pad in enumerate(ATCA_6C))
    assert message.startswith("receptors from the station catalogue for antennas the file "
                              f"gives none: {labels}: X:45,Y:135 (Miriad cat/observatories.dat")
    # Antennas without a name are matched the same way.
    out, _, message = given({3: at("AT_W104", JITTER[0])})
    assert out[3].receptors == ATCA_RECEPTORS
    assert "3 (no name as AT_W104 by position, 0.05 m)" in message


def test_an_antenna_10_m_from_any_pad_gets_nothing():
    antennas = {1: at("AT_W0", name="CA01"), 7: at("AT_W104", name="CA07", north=10.0)}
    out, note, message = given(antennas)
    assert out[7].receptors is None
    assert note == ("the station catalogue gave receptors to antennas 1 (CA01 as AT_W0 by "
                    "position, 0.00 m), not to 7 (CA07: its name is not in the catalogue, and "
                    "no station within 5 m states receptors (nearest: AT_W104, 10.0 m))")
    # A larger tolerance reaches it; catalogue=False gives nothing at all.
    out, _, message = given(antennas, pad_tolerance=11 * u.m)
    assert out[7].receptors == ATCA_RECEPTORS and "7 (CA07 as AT_W104 by position, 10.00 m)" \
        in message
    assert catalogue_receptors(antennas, False) == (antennas, "")


def test_a_name_match_comes_first():
    # "ATCA" names AT_W104 (its alias), 30.6 m away: the name wins over the pad
    # AT_W106 the antenna stands on; both state the same receptors.
    out, note, message = given({1: at("AT_W106", name="ATCA")})
    assert out[1].receptors == ATCA_RECEPTORS and note == ""
    assert "1 (ATCA as AT_W104)" in message and "by position" not in message


ONE_SITE = """# %ECSV 1.0
# ---
# datatype:
# - {name: name, datatype: string}
# - {name: x, unit: m, datatype: float64}
# - {name: y, unit: m, datatype: float64}
# - {name: z, unit: m, datatype: float64}
# - {name: mount, datatype: string}
# - {name: receptors, datatype: string}
name x y z mount receptors
PADA 4075539.5 931735.6 4801629.6 AZEL R:0,L:0
PADB 4075539.5 931735.6 4801633.6 AZEL X:0,Y:90
PADC 4075539.5 931735.6 4801637.6 AZEL X:0,Y:90
DISH 4075539.5 931795.6 4801629.6 AZEL ""
"""


def test_stations_with_different_receptors_that_close_give_none():
    mine = read_catalogue(io.StringIO(ONE_SITE))
    between = Antenna(EarthLocation.from_geocentric(4075539.5, 931735.6, 4801631.6, unit=u.m),
                      AltAzMount(), name="A1")
    out, note, message = given({1: between}, catalogue=mine)
    assert out[1].receptors is None and message == ""
    assert note.endswith("not to 1 (A1: its name is not in the catalogue, and stations with "
                         "different receptors lie within 5 m: PADA (R:0,L:0, 2.0 m), PADB "
                         "(X:0,Y:90, 2.0 m))")
    # Stations with the same receptors: the nearest lends them.
    near_c = Antenna(EarthLocation.from_geocentric(4075539.5, 931735.6, 4801636.6, unit=u.m),
                     AltAzMount(), name="A2")
    out, note, message = given({2: near_c}, catalogue=mine)
    assert out[2].receptors == Receptors("XY", [0, 90] * u.deg)
    assert "2 (A2 as PADC by position, 1.00 m)" in message
    # A station without receptors lends none, however close.
    at_dish = Antenna(EarthLocation.from_geocentric(4075539.5, 931795.6, 4801629.6, unit=u.m),
                      AltAzMount(), name="A3")
    _, note, _ = given({3: at_dish}, catalogue=mine)
    assert note.endswith("no station within 5 m states receptors (nearest: PADA, 60.0 m))")
    # Its name found it: the station states none, and no position is tried.
    _, note, _ = given({3: Antenna(at_dish.location, AltAzMount(), name="DISH")},
                       catalogue=mine)
    assert note.endswith("not to 3 (DISH: the catalogue's DISH states no receptors)")


def test_a_catalogue_that_states_no_receptors():
    mine = read_catalogue(io.StringIO(ONE_SITE.replace("R:0,L:0", '""')
                                      .replace("X:0,Y:90", '""')))
    _, note, _ = given({1: at("AT_W0", name="CA01")}, catalogue=mine)
    assert note.endswith("not to 1 (CA01: its name is not in the catalogue, and no station of "
                         "the catalogue states receptors)")


# --- a Miriad file of the ATCA through the command line ------------------------------


# At the ATCA's meridian near 06:00 UTC on 2023-02-25 (local sidereal time 2.3 h).
ATCA_SOURCE = SkyCoord(35 * u.deg, -40 * u.deg)
STOKES = model.stokes_from_evpa(0.3, 25.0)


def atca_uv(north=0.0):
    """CA01..CA06 on the 6C pads (or ``north`` m north of them), X at 45 deg and Y at
    135 deg, a polarized source."""
    pyuvdata = pytest.importorskip("pyuvdata")  # optional: imported when the test runs
    centre = get_antenna("AT_W104").location
    positions = np.array([xyz(at(pad, north=north).location) for pad in ATCA_6C]) + JITTER
    tel = pyuvdata.Telescope.new(
        name="ATCA", instrument="ATCA", location=centre,
        antenna_positions=positions - xyz(centre),
        antenna_names=[f"CA0{k}" for k in range(1, 7)], antenna_numbers=list(range(1, 7)),
        feed_array=["x", "y"], feed_angle=np.radians([45, 135]), mount_type="alt-az")
    catalog = {0: dict(cat_name="SRC", cat_type="sidereal", cat_lon=ATCA_SOURCE.ra.rad,
                       cat_lat=ATCA_SOURCE.dec.rad, cat_frame="icrs", cat_epoch=2000.0)}
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "Recalculating uvw_array")
        uv = pyuvdata.UVData.new(
            freq_array=2.1e9 + np.arange(2) * 1e6, channel_width=np.full(2, 1e6),
            polarization_array=np.array([-5, -6, -7, -8]),  # ints: write_miriad needs them
            times=2460000.75 + np.arange(4) * 1800.0 / 86400, telescope=tel,
            antpairs=[(1, 2), (1, 6), (3, 5), (4, 6)], do_blt_outer=True, empty=True,
            phase_center_catalog=catalog)
    return model.inject(uv, STOKES, lambda times: ATCA_SOURCE, "alt-az")


def test_an_atca_miriad_file_corrected_from_the_catalogue(tmp_path, capsys):
    uv = atca_uv()
    expected = model.sky_data(uv, STOKES)
    uv.telescope.feed_array = uv.telescope.feed_angle = None  # as Miriad files have none
    uv.telescope.Nfeeds = None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata: default values it writes
        uv.write_miriad(tmp_path / "atca.uv")
    assert main(["correct", str(tmp_path / "atca.uv"), "-o", str(tmp_path / "out.uvfits"),
                 "--quiet"]) == 0
    assert main(["correct", str(tmp_path / "atca.uv"), "-o", str(tmp_path / "given.uvfits"),
                 "--feeds", "X:45,Y:135", "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "feedrot: warning: receptors from the station catalogue for antennas the file " \
           "gives none: 1 (CA01 as AT_W0 by position, 0.05 m), 2 (CA02 as AT_W10 by " \
           "position, 0.05 m)" in err
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out, feeds = (read_uvdata(tmp_path / name) for name in ("out.uvfits", "given.uvfits"))
    np.testing.assert_array_equal(out.data_array, feeds.data_array)
    # The independent model (tests/uvdata_model.py): X north, Y east on the sky.
    for channel in range(2):
        assert np.allclose(out.data_array[:, channel, :], expected, atol=1e-5)
    assert np.allclose(model.evpa(out), 25.0, atol=0.01)


# --- the file's telescope --------------------------------------------------------------


def test_antennas_off_their_pads_take_the_telescopes_receptors():
    # As in Miriad's files of the ATCA: numbers for names, positions that are not
    # the pads' (here 20 m north of the track). Every ATCA station states X 45,
    # Y 135 (Miriad's observatories.dat, catalogue/sources/miriad).
    antennas = {k: at(pad, name=str(k), north=20.0) for k, pad in enumerate(ATCA_6C)}
    out, note, message = given(antennas)
    assert note.startswith("the station catalogue gave receptors to antennas none")
    assert all(out[k].receptors is None for k in antennas)
    assert "no station within 5 m states receptors" in note
    out, note, message = given(antennas, telescope="ATCA")
    assert note == "" and all(out[k].receptors == ATCA_RECEPTORS for k in antennas)
    assert "0 (0 by the telescope ATCA, network ATCA: every station states these)" in message


def test_the_telescope_does_not_lend_what_it_cannot():
    far = {1: at("FD-VLBA", name="1", north=20.0)}  # not at the ATCA
    out, note, _ = given(far, telescope="ATCA")
    assert out[1].receptors is None
    assert re.search(r"it lies \d+\.\d km from the nearest station of the telescope 'ATCA', "
                     r"beyond 50 km", note)
    near = {1: at("AT_W104", name="1", north=20.0)}
    out, note, _ = given(near, telescope="NO SUCH ARRAY")
    assert out[1].receptors is None
    assert "the catalogue has no network or station 'NO SUCH ARRAY'" in note
    # The EHT: its stations state no receptors (none of the sources does), so
    # what one of them might state would say nothing of another's.
    smt = {1: at("SMT", name="1", north=20.0)}
    out, note, _ = given(smt, telescope="EHT")
    assert out[1].receptors is None
    assert re.search(r"\d+ of the \d+ stations of the telescope 'EHT' \(network EHT\) state "
                     r"no receptors", note)


def test_an_atca_miriad_file_off_its_pads_corrected_by_its_telescope(tmp_path, capsys):
    # The antennas 20 m from every pad (as Miriad's positions are, in other ways):
    # the file's telescope, ATCA, lends them its stations' receptors.
    uv = atca_uv(north=20.0)
    expected = model.sky_data(uv, STOKES)
    uv.telescope.feed_array = uv.telescope.feed_angle = None
    uv.telescope.Nfeeds = None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        uv.write_miriad(tmp_path / "atca.uv")
    assert main(["correct", str(tmp_path / "atca.uv"), "-o", str(tmp_path / "out.uvfits"),
                 "--quiet"]) == 0
    assert "1 (CA01 by the telescope ATCA, network ATCA: every station states these)" \
        in capsys.readouterr().err
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = read_uvdata(tmp_path / "out.uvfits")
    for channel in range(2):
        assert np.allclose(out.data_array[:, channel, :], expected, atol=1e-5)
    assert np.allclose(model.evpa(out), 25.0, atol=0.01)
