# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The antennas of real files: mounts against the station catalogue,
orbiting antennas, receptors that are not a pair, empty mounts, NaN sources.

The files are under tests/data/real/ (README.md there: source, commit, licence;
trim_fits_rows.py made the trims) and tests/data/uvdata/ (the LWA set). Each
number is checked against an independent computation: `Antenna.feed_rotation`
of antennas built here, astropy's AltAz elevation, the input's own bytes.
"""

import shutil
import tarfile
from pathlib import Path

import astropy.units as u
import numpy as np
import pytest
from astropy.coordinates import AltAz, EarthLocation, SkyCoord
from astropy.io import fits
from astropy.table import Table
from astropy.time import Time

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    CatalogueMountWarning,
    NasmythFocus,
    UncorrectedBaselinesWarning,
    get_antenna,
)
from astropy_feedrot.antennas.receptors import Receptors
from astropy_feedrot.cli import main
from astropy_feedrot.visibilities import (
    MSError,
    UnusableAntenna,
    antenna_table,
    catalogue_mounts,
    correct_file,
    correct_fitsidi,
    correct_ms,
    correct_uvdata,
    feed_rotation_rows,
    fitsidi_antennas,
    ms_antennas,
    read_antennas,
    read_uvdata,
    uvfits_antennas,
)

pytestmark = pytest.mark.filterwarnings(
    # pyuvdata's remarks on these files (uvw against the antenna positions...).
    "ignore::UserWarning:pyuvdata",
    "ignore:.*padding at the end of the file:astropy.utils.exceptions.AstropyUserWarning")

REAL = Path(__file__).parent.parent / "data" / "real"
UVDATA = Path(__file__).parent.parent / "data" / "uvdata"
EHT = REAL / "SR1_3C279_2017_101_hi.trim.uvfits"  # EHT 2017, HOPS, MNTSTA 0 everywhere
VSOP = REAL / "v050c.trim.fits"  # VSOP: HALCA (RZ, MNTSTA 2) with five VLBA antennas
LWA = UVDATA / "lwasv_cor_58342_05_00_14.ms.tar.gz"  # RECEPTOR_ANGLE [0, 0]
VLA_MS = UVDATA / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms.tar.gz"

# The EHT 2017 stations the catalogue knows (eht-imaging's array files): these four
# have Nasmyth foci; ALMA, JCMT and the SPT Cassegrain ones. SM and SR (the SMA and
# its reference antenna) lie 289 m from the catalogue's SMA and 163 m from JCMT: no
# station within 100 m.
NASMYTH = {2: ("AP", "APEX", "right"), 3: ("AZ", "SMT", "right"), 5: ("LM", "LMT", "left"),
           6: ("PV", "PICOVEL", "left")}
CASSEGRAIN = {1: "ALMA", 4: "JCMT", 8: "SPT"}
MOUNT_WARNING = (r"antenna 2 \(AP\): file AltAzMount\(\) CassegrainFocus\(\), APEX .*"
                 r"NasmythFocus\(handedness='right'\); antenna 3 \(AZ\): .*SMT.*; antenna 5 "
                 r"\(LM\): .*LMT.*'left'.*; antenna 6 \(PV\): .*PICOVEL")


def untar(archive, where):
    with tarfile.open(archive) as tar:
        top = tar.getnames()[0].split("/")[0]
        tar.extractall(where, filter="data")
    return where / top


# --- the file's mounts against the catalogue --------------------------------------------


def test_eht_stations_as_the_catalogue_knows_them():
    with pytest.warns(CatalogueMountWarning, match="the file's mounts differ.*" + MOUNT_WARNING
                      + ".*the file's are used: pass mounts='catalogue'"):
        antennas, software = read_antennas(EHT)
    # The default stays the file's: MNTSTA 0, alt-az with a Cassegrain focus.
    assert all(a.mount == AltAzMount() and a.focus.closed_form == (0, 0)
               for a in antennas.values())
    table = antenna_table(antennas, software)
    rows = {int(r["number"]): r for r in table}
    for number, (name, station, hand) in NASMYTH.items():
        assert rows[number]["name"] == name and rows[number]["station"] == station
        # The catalogue's own antenna, read independently of the matching.
        assert get_antenna(station).focus == NasmythFocus(hand)
        assert rows[number]["station_focus"] == repr(NasmythFocus(hand))
        assert rows[number]["station_distance"] < 5
        assert "differ from the catalogue's" in rows[number]["problem"]
    for number, station in CASSEGRAIN.items():
        assert rows[number]["station"] == station and rows[number]["problem"] == ""
    for number in (7, 9):  # SM, SR: no station within 100 m
        assert rows[number]["station"] == "" and rows[number]["problem"] == ""


def test_eht_mounts_from_the_catalogue():
    with pytest.warns(CatalogueMountWarning, match="the station catalogue's mounts are used "
                      "where they differ from the file's: " + MOUNT_WARNING):
        antennas, _ = read_antennas(EHT, mounts="catalogue")
    for number, (_, station, hand) in NASMYTH.items():
        assert antennas[number].focus == NasmythFocus(hand)
        assert antennas[number].mount == get_antenna(station).mount
        # The file's position, name and receptors stay.
        assert antennas[number].receptors.types == "RL"
    with pytest.raises(ValueError, match="mounts must be one of"):
        read_antennas(EHT, mounts="vex")


def test_command_antennas_shows_the_disagreement(capsys):
    assert main(["antennas", str(EHT)]) == 0
    out, err = capsys.readouterr()
    assert err.startswith("feedrot: warning: ") and "APEX" in err
    table = Table.read(out, format="ascii.ecsv")
    assert list(table["station_focus"][1:3]) == [repr(NasmythFocus("right"))] * 2
    assert list(table["focus"][1:3]) == ["CassegrainFocus()"] * 2
    assert main(["antennas", str(EHT), "--mounts", "catalogue"]) == 0
    table = Table.read(capsys.readouterr().out, format="ascii.ecsv")
    assert list(table["focus"][1:3]) == [repr(NasmythFocus("right"))] * 2


def test_correction_with_catalogue_mounts_against_feed_rotation(tmp_path):
    uv = read_uvdata(EHT)
    with pytest.warns(CatalogueMountWarning, match="the file's are used"):
        by_file = correct_uvdata(uv)
    with pytest.warns(CatalogueMountWarning, match="the station catalogue's mounts are used"):
        by_catalogue = correct_uvdata(uv, mounts="catalogue")
    # ALMA (1) - APEX (2): only APEX changes, from alt-az to right-handed Nasmyth.
    rows = np.flatnonzero((uv.ant_1_array == 1) & (uv.ant_2_array == 2))
    assert rows.size > 10
    times = Time(uv.time_array[rows], format="jd", scale="utc")
    source = SkyCoord(uv.phase_center_catalog[0]["cat_lon"] * u.rad,
                      uv.phase_center_catalog[0]["cat_lat"] * u.rad, frame="icrs")
    position = uv.telescope.location.get_itrs().cartesian.xyz.to_value(u.m) + \
        uv.telescope.antenna_positions[1]
    apex = EarthLocation.from_geocentric(*position, unit=u.m)
    # Independent: the feed rotation of the catalogue's APEX and of the file's one.
    nasmyth = Antenna(apex, get_antenna("APEX").mount, get_antenna("APEX").focus)
    plain = Antenna(apex, AltAzMount())
    delta = (nasmyth.feed_rotation(source, times) - plain.feed_rotation(source, times))
    # A right-handed Nasmyth focus adds the elevation (Eq 38): astropy's AltAz says it.
    elevation = source.transform_to(AltAz(obstime=times, location=apex)).alt
    np.testing.assert_allclose(delta.to_value(u.deg), elevation.to_value(u.deg), atol=3e-3)
    # RR (conjugate convention) is corrected by exp(-i(theta1 - theta2)): the catalogue's
    # APEX turns it by exp(+i delta) against the file's.
    rr = list(uv.polarization_array).index(-1)
    a, b = by_file.data_array[rows, :, rr], by_catalogue.data_array[rows, :, rr]
    good = np.abs(a) > 0
    turn = np.angle(b[good] / a[good], deg=True)
    expected = np.broadcast_to(delta.to_value(u.deg)[:, None], a.shape)[good]
    assert np.abs((turn - expected + 180) % 360 - 180).max() < 1e-4  # deg
    # The command line does the same (uvh5 output).
    out = tmp_path / "eht.uvh5"
    assert main(["correct", str(EHT), "-o", str(out), "--mounts", "catalogue", "--quiet"]) == 0
    np.testing.assert_array_equal(read_uvdata(out).data_array, by_catalogue.data_array)


def test_mounts_with_no_catalogue_are_the_files():
    antennas = uvfits_antennas(EHT)
    assert catalogue_mounts(antennas, "catalogue", catalogue=False) == (antennas, {})


# --- an orbiting antenna ---------------------------------------------------------------


def test_orbiting_antenna_is_listed(capsys):
    with pytest.raises(ValueError, match=r"antenna 5 \(RZ\): 2 .*orbiting antenna"):
        fitsidi_antennas(VSOP)
    antennas, _ = read_antennas(VSOP)
    halca = antennas[5]
    assert isinstance(halca, UnusableAntenna) and halca.problem == "orbiting"
    assert halca.name == "RZ" and "MNTSTA 2: an orbiting antenna" in halca.reason
    assert all(isinstance(antennas[n], Antenna) for n in (1, 2, 3, 4, 6))
    assert main(["antennas", str(VSOP)]) == 0
    table = Table.read(capsys.readouterr().out, format="ascii.ecsv")
    problem = dict(zip(table["name"], table["problem"]))
    assert "orbiting antenna" in problem["RZ"] and "leaves its baselines" in problem["RZ"]
    assert np.ma.is_masked(problem["BR"]) and table["station"][0] == "BR-VLBA"  # empty
    with pytest.raises(ValueError, match=r"antenna 5 \(RZ\) cannot be used: MNTSTA 2: an "
                       "orbiting antenna"):
        feed_rotation_rows(antennas, [1], [5], Time(["1999-04-01T20:00"]),
                           SkyCoord(153.767 * u.deg, 49.433 * u.deg))
    table = antenna_table(antennas, "fits-idi:difx")
    assert table["mount"][4] == "" and table["label"][4] == "2" and table["problem"][0] == ""


def _rows(path):
    with fits.open(path) as hdus:
        data = hdus["UV_DATA"].data
        geometry = hdus["ARRAY_GEOMETRY"].data
        source = hdus["SOURCE"].data
        return (np.array(data["BASELINE"]), np.array(data["DATE"]), np.array(data["TIME"]),
                np.array(data["FLUX"]), np.array(data).tobytes(), data.itemsize,
                {int(n): xyz for n, xyz in zip(geometry["NOSTA"], geometry["STABXYZ"])},
                SkyCoord(float(source["RAEPO"][0]) * u.deg,
                         float(source["DECEPO"][0]) * u.deg, frame="icrs"))


def test_orbiting_baselines_are_left_byte_for_byte(tmp_path):
    out = tmp_path / "v050c.fits"
    with pytest.warns(UncorrectedBaselinesWarning, match=r"rows on baselines to the orbiting "
                      r"antenna 5 \(RZ\) are left as they were.*ground baselines are "
                      "corrected"):
        correct_fitsidi(VSOP, out)
    baseline, date, time, flux, raw, size, xyz, source = _rows(VSOP)
    _, _, _, corrected, raw_out, _, _, _ = _rows(out)
    a1, a2 = baseline // 256, baseline % 256
    orbiting = (a1 == 5) | (a2 == 5)
    assert 0 < orbiting.sum() < orbiting.size
    for row in np.flatnonzero(orbiting):  # byte for byte
        assert raw[row * size:(row + 1) * size] == raw_out[row * size:(row + 1) * size]
    # The ground baselines: LL (the file's one product, receptor angles 0) corrected
    # by exp(+i (Phi1 - Phi2)) (the conjugate convention of FITS-IDI), Phi from
    # Antenna.feed_rotation of alt-az antennas at the file's positions.
    ground = np.flatnonzero(~orbiting & (a1 != a2))
    assert ground.size
    # ARRAY_GEOMETRY's TIMSYS is 'UTC' (UV_DATA's TIME column calls itself IAT).
    assert fits.getval(VSOP, "TIMSYS", "ARRAY_GEOMETRY") == "UTC"
    times = Time(date[ground] + time[ground], format="jd", scale="utc")
    phi = {n: Antenna(EarthLocation.from_geocentric(*xyz[n], unit=u.m), AltAzMount())
           for n in (1, 2, 3, 4, 6)}
    phi1 = np.array([phi[a].feed_rotation(source, t).to_value(u.rad)
                     for a, t in zip(a1[ground], times)])
    phi2 = np.array([phi[a].feed_rotation(source, t).to_value(u.rad)
                     for a, t in zip(a2[ground], times)])
    before = flux[ground].reshape(ground.size, -1, 2)
    after = corrected[ground].reshape(ground.size, -1, 2)
    v0 = before[..., 0] + 1j * before[..., 1]
    v1 = after[..., 0] + 1j * after[..., 1]
    expected = v0 * np.exp(1j * (phi1 - phi2))[:, None]
    assert np.abs(v1 - expected).max() <= 2e-6 * np.abs(v0).max()


# --- receptors that are not a pair (LWA: RECEPTOR_ANGLE [0, 0]) ------------------------


def _rename_telescope(ms, name):
    casacore = pytest.importorskip("casacore.tables")
    with casacore.table(str(ms / "OBSERVATION"), readonly=False, ack=False) as t:
        for row in range(t.nrows()):
            t.putcell("TELESCOPE_NAME", row, name)


def test_lwa_is_an_aperture_array_in_every_route(tmp_path, capsys):
    """LWASV (its OBSERVATION's TELESCOPE_NAME) is refused as an aperture array by
    every route, with its receptors given or not; feedrot antennas gives the reason."""
    ms = untar(LWA, tmp_path)
    antennas, _ = read_antennas(ms)
    assert all(a.problem == "aperture array" for a in antennas.values())
    assert main(["antennas", str(ms)]) == 0
    table = Table.read(capsys.readouterr().out, format="ascii.ecsv")
    assert all("'LWASV' is an aperture array" in p for p in table["problem"])
    feeds = Receptors("XY", [0, 90] * u.deg)
    reason = r"the telescope 'LWASV' is an aperture array \(a Long Wavelength Array station\)"
    with pytest.raises(MSError, match=r"4 antennas cannot be corrected: antennas 0 "
                       r"\(LWA001\), 1 \(LWA002\), 2 \(LWA003\), 3 \(LWA004\): " + reason):
        correct_ms(ms, feeds=feeds)
    with pytest.raises(ValueError, match=reason):
        correct_file(ms, tmp_path / "lwa.uvh5", feeds=feeds)
    assert main(["correct", str(ms), "-o", str(tmp_path / "lwa.uvh5"), "--feeds",
                 "X:0,Y:90"]) == 1
    assert "is an aperture array" in capsys.readouterr().err
    assert not (tmp_path / "lwa.uvh5").exists()


def test_lwa_receptors_listed_and_refused_then_given(tmp_path, capsys):
    """The same set under another telescope name: its receptors are what is wrong."""
    ms = untar(LWA, tmp_path)
    _rename_telescope(ms, "TEST")
    with pytest.raises(MSError, match=r"antenna 0 \(LWA001\): table FEED: the linear "
                       "receptors 'XY' are parallel"):
        ms_antennas(ms)
    antennas, _ = read_antennas(ms)
    assert all(isinstance(a, UnusableAntenna) and a.problem == "receptors"
               for a in antennas.values())
    assert antennas[0].mount == AltAzMount()
    assert main(["antennas", str(ms)]) == 0
    table = Table.read(capsys.readouterr().out, format="ascii.ecsv")
    assert all("parallel" in p and "--feeds" in p for p in table["problem"])
    before = shutil.copytree(ms, tmp_path / "before.ms")
    with pytest.raises(MSError, match=r"4 antennas cannot be corrected: antennas 0 "
                       r"\(LWA001\), 1 \(LWA002\), 2 \(LWA003\), 3 \(LWA004\): table FEED: "
                       "the linear receptors 'XY' are parallel"):
        correct_ms(ms)
    assert main(["correct", str(ms), "--in-place"]) == 1
    assert "cannot be corrected" in capsys.readouterr().err
    # Through pyuvdata too.
    with pytest.raises(ValueError, match=r"cannot be corrected: antennas 0 \(LWA001\), "
                       ".*: the linear receptors 'XY' are parallel"):
        correct_file(ms, tmp_path / "lwa.uvh5")
    # The feeds given: corrected.
    feeds = Receptors("XY", [0, 90] * u.deg)
    correct_ms(ms, feeds=feeds)
    assert main(["correct", str(before), "-o", str(tmp_path / "lwa.uvh5"), "--feeds",
                 "X:0,Y:90", "--quiet"]) == 0


# --- empty and unknown mounts, sources that are not numbers -------------------------------


def _set_cell(ms, table, column, row, value):
    casacore = pytest.importorskip("casacore.tables")
    with casacore.table(str(ms / table), readonly=False, ack=False) as t:
        t.putcell(column, row, value)


def test_empty_mount_is_refused_or_taken_from_the_catalogue(tmp_path):
    ms = untar(VLA_MS, tmp_path)
    _set_cell(ms, "ANTENNA", "MOUNT", 1, "")
    with pytest.raises(MSError, match=r"antenna 1 \(\w+\): MOUNT is empty .*--mounts "
                       "catalogue"):
        ms_antennas(ms)
    antennas, _ = read_antennas(ms)
    assert antennas[1].problem == "mount" and "VLA_" in antennas[1].reason
    with pytest.raises(MSError, match=r"1 antenna cannot be corrected: antenna 1 \(\w+\): "
                       "MOUNT is empty.*the catalogue's VLA_"):
        correct_ms(ms)
    # Into a copy: refused too (pyuvdata refuses the empty mount_type itself).
    with pytest.raises(ValueError, match="MOUNT is empty|mount_type has unacceptable values"):
        correct_file(ms, tmp_path / "vla.uvh5")
    with pytest.warns(CatalogueMountWarning, match=r"antenna 1 \(\w+\): file MOUNT is empty"):
        correct_ms(ms, mounts="catalogue")
    _set_cell(ms, "ANTENNA", "MOUNT", 1, "ALT-AX")
    with pytest.raises(MSError, match=r"antenna 1 \(\w+\): MOUNT 'ALT-AX': unknown casacore "
                       "mount label 'ALT-AX'"):
        ms_antennas(ms)


def test_nan_sources_are_refused_naming_them(tmp_path):
    ms = untar(VLA_MS, tmp_path)
    _set_cell(ms, "FIELD", "PHASE_DIR", 0, np.array([[np.nan, 0.5]]))
    with pytest.raises(MSError, match=r"field 0 \(\w+.*\): PHASE_DIR is \[\[nan, 0.5\]\] "
                       "rad, not numbers"):
        correct_ms(ms)
    uv = read_uvdata(EHT)
    uv.phase_center_catalog[0]["cat_lat"] = np.nan
    with pytest.raises(ValueError, match="phase centre '3C279' .*cat_lat nan, not a number"):
        correct_uvdata(uv, catalogue=False)
    with pytest.raises(ValueError, match="source 'x' has coordinates that are not numbers"):
        feed_rotation_rows({1: get_antenna("FD-VLBA")}, [1], [1], Time(["2023-01-01"]),
                           {"x": SkyCoord(np.nan * u.deg, 0 * u.deg)}, ["x"])


def test_orbiting_antenna_of_a_measurement_set(tmp_path):
    plain = untar(VLA_MS, tmp_path / "plain")
    ms = untar(VLA_MS, tmp_path / "orbiting")
    correct_ms(plain)
    _set_cell(ms, "ANTENNA", "MOUNT", 1, "SPACE-HALCA")
    with pytest.warns(UncorrectedBaselinesWarning, match=r"orbiting antenna 1 \(\w+\) are "
                      "left as they were"):
        correct_ms(ms)
    casacore = pytest.importorskip("casacore.tables")
    with casacore.table(str(ms), ack=False) as t, casacore.table(str(plain), ack=False) as p:
        on = (t.getcol("ANTENNA1") == 1) | (t.getcol("ANTENNA2") == 1)
        data, out = t.getcol("DATA"), t.getcol("CORRECTED_DATA")
        reference = p.getcol("CORRECTED_DATA")
    assert 0 < on.sum() < on.size
    # Baselines to the orbiting antenna: DATA as it was; the others as corrected
    # without it.
    assert data[on].tobytes() == out[on].tobytes()
    assert out[~on].tobytes() == reference[~on].tobytes()


def test_orbiting_antenna_through_pyuvdata():
    uv = read_uvdata(EHT)
    with pytest.warns(CatalogueMountWarning):
        reference = correct_uvdata(uv)
    uv.telescope.mount_type[1] = "orbiting"  # AP, antenna 2
    with pytest.warns(UncorrectedBaselinesWarning, match=r"orbiting antenna 2 \(AP\)"):
        with pytest.warns(CatalogueMountWarning):
            out = correct_uvdata(uv)
    on = (uv.ant_1_array == 2) | (uv.ant_2_array == 2)
    assert 0 < on.sum() < on.size
    assert out.data_array[on].tobytes() == uv.data_array[on].tobytes()
    assert out.data_array[~on].tobytes() == reference.data_array[~on].tobytes()
    assert out.telescope.feed_angle[1].tolist() == uv.telescope.feed_angle[1].tolist()
    assert "not the baselines to the orbiting antennas 2" in out.history.replace("\n", "")


def test_traced_mirrors_compare_as_their_closed_form():
    # WARK30M: a beam waveguide traced mirror by mirror (the catalogue's 'BWG'), so a
    # casacore 'ALT-AZ' differs; YEBES40M's mirrors reduce to a right-handed Nasmyth
    # focus (NASR), which a file's MNTSTA 4 says: alike.
    wark, yebes = get_antenna("WARK30M"), get_antenna("YEBES40M")
    antennas = {1: Antenna(wark.location, AltAzMount(), name="WARK30M"),
                2: Antenna(yebes.location, AltAzMount(), NasmythFocus("right"), name="YS")}
    with pytest.warns(CatalogueMountWarning, match=r"antenna 1 \(WARK30M\): file AltAzMount"
                      r"\(\) CassegrainFocus\(\), WARK30M \(0.0 m\) AltAzMount\(\) MirrorTrain"):
        chosen, matches = catalogue_mounts(antennas, "catalogue")
    assert not matches[1].agrees and matches[2].agrees
    assert chosen[1].focus == wark.focus and chosen[2].focus == NasmythFocus("right")
