# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""pyuvdata front-end: antennas, feed rotation and correction of UVData objects.

References: an independent voltage-level model (tests/uvdata_model.py: ERFA's
hd2pa on astropy HADec, astropy AltAz, projected dipoles), ERFA's atci13 and
pas for the ICRS north, pyuvdata's own phase_center_frame_pa, and casacore's
parallactic angle (TaQL mscal.pa1) on a real VLA Measurement Set.
"""

import os
import sys
import tarfile
import tracemalloc
import warnings

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.time import Time

pyuvdata = pytest.importorskip("pyuvdata")

import uvdata_model as model  # noqa: E402
from pyuvdata import Telescope, UVData  # noqa: E402
from pyuvdata.utils import ECEF_from_ENU  # noqa: E402

from astropy_feedrot import Antenna, DegenerateGeometryWarning, StationaryMount  # noqa: E402
from astropy_feedrot.antennas.receptors import Receptors  # noqa: E402

# uvdata_model places its antennas near the VLA's pads with other mounts and foci
# on purpose; that a file's mounts differing from the catalogue's are named is
# tested in tests/visibilities/test_real_antennas.py.
pytestmark = pytest.mark.filterwarnings(
    "ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")
from astropy_feedrot.visibilities import (  # noqa: E402
    HISTORY_MARK,
    antennas_from_uvdata,
    correct_uvdata,
    feed_rotation_uvdata,
    read_uvdata,
    write_uvdata,
)

DATA = os.path.join(os.path.dirname(os.path.dirname(__file__)), "data", "uvdata")
VLA = EarthLocation.from_geodetic(-107.6184 * u.deg, 34.0790 * u.deg, 2124 * u.m)
T0 = 2460000.75  # 2023-02-25 06:00 UTC
SOURCE = SkyCoord(150 * u.deg, 30 * u.deg)  # transits near 10:40 UTC at the VLA
CIRCULAR = ["rr", "ll", "rl", "lr"]
LINEAR = ["xx", "xy", "yx", "yy"]


def make_uv(feeds, angles, mount, pols, catalog=None, ntimes=4, nfreqs=1, antpairs=None,
            step=1800.0):
    enu = np.array([[0.0, 0, 0], [300.0, 0, 0], [0, 500.0, 0], [-200.0, -400.0, 0]])
    antpos = ECEF_from_ENU(enu, center_loc=VLA) - np.array(
        [VLA.x.to_value(u.m), VLA.y.to_value(u.m), VLA.z.to_value(u.m)])
    tel = Telescope.new(name="TESTARRAY", instrument="TESTARRAY", location=VLA,
                        antenna_positions=antpos, antenna_names=["A0", "A1", "A2", "A3"],
                        antenna_numbers=[0, 1, 2, 3], feed_array=feeds,
                        feed_angle=np.radians(angles), mount_type=mount)
    antpairs = antpairs or [(0, 1), (0, 2), (1, 3), (2, 3), (3, 0)]
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "Recalculating uvw_array")
        return UVData.new(freq_array=1.4e9 + np.arange(nfreqs) * 1e6, polarization_array=pols,
                          channel_width=np.full(nfreqs, 1e6),
                          times=T0 + np.arange(ntimes) * step / 86400, telescope=tel,
                          antpairs=antpairs, do_blt_outer=True, empty=True,
                          phase_center_catalog=catalog)


def sidereal(coord=SOURCE, frame="icrs", epoch=2000.0):
    return {0: dict(cat_name="SRC", cat_type="sidereal", cat_lon=coord.spherical.lon.rad,
                    cat_lat=coord.spherical.lat.rad, cat_frame=frame, cat_epoch=epoch)}


STOKES = model.stokes_from_evpa(0.3, 25.0, v=0.05)


def fixed(coord):
    return lambda times: coord


# --- antennas --------------------------------------------------------------------


def test_antennas_from_uvdata_synthetic():
    uv = make_uv(["x", "y"], [90, 0], "alt-az+nasmyth-r", LINEAR)
    antennas = antennas_from_uvdata(uv)
    assert sorted(antennas) == [0, 1, 2, 3]
    a = antennas[1]
    assert a.name == "A1" and a.receptors == Receptors("XY", [90, 0] * u.deg)
    assert repr(a.focus) == "NasmythFocus(handedness='right')"
    # Absolute position = telescope location + ECEF offset (pyuvdata's own ENU back).
    xyz = np.array([a.location.x.value, a.location.y.value, a.location.z.value])
    expected = uv.telescope.antenna_positions[1] + np.array(
        [VLA.x.value, VLA.y.value, VLA.z.value])
    assert np.allclose(xyz, expected, atol=1e-6)
    assert antennas_from_uvdata(uv, vertical="geocentric")[1].vertical == "geocentric"


def test_fixed_feed_angle_is_alpha_plus_90():
    # pyuvdata: fixed antennas have feed angle 0 = north, 90 = east; StationaryMount's
    # reference dipole is east. Geometry: at the zenith, the sky position angle of a
    # horizontal dipole at azimuth f is f minus the azimuth of the projected pole
    # (model.projected_dipole_pa), which must equal Phi + alpha.
    uv = make_uv(["x", "y"], [0, 90], "fixed", LINEAR)
    antenna = antennas_from_uvdata(uv)[0]
    assert isinstance(antenna.mount, StationaryMount)
    assert antenna.receptors == Receptors("XY", [-90, 0] * u.deg)
    times = Time(T0, format="jd") + np.arange(3) * u.hour
    zenith = SkyCoord(model.AltAz(az=np.zeros(3) * u.deg, alt=np.full(3, 90) * u.deg,
                                  obstime=times, location=antenna.location))
    phi = antenna.feed_rotation(zenith, times)
    for f, letter in ((0.0, "X"), (90.0, "Y")):
        geometry = model.projected_dipole_pa(zenith, antenna.location, times, f)
        got = (phi + antenna.receptors.angle(letter)).wrap_at(180 * u.deg)
        assert np.allclose(got.rad, geometry, atol=np.radians(1 / 3600))


@pytest.mark.parametrize("el", [90.0, 60.0, 35.0])
def test_fixed_dipoles_off_zenith_against_projection(el):
    # Drift scan of fixed dipoles: each dipole's own projection (not a rigid rotation).
    catalog = {0: dict(cat_name="DRIFT", cat_type="driftscan", cat_lon=np.radians(120.0),
                       cat_lat=np.radians(el))}
    uv = make_uv(["x", "y"], [30, 120], "fixed", LINEAR, catalog=catalog)
    theta = feed_rotation_uvdata(uv)
    times = Time(uv.time_array, format="jd")
    for row in (0, 7):
        k = uv.ant_1_array[row]
        loc = EarthLocation.from_geocentric(
            *(uv.telescope.antenna_positions[k] + [VLA.x.value, VLA.y.value, VLA.z.value]),
            unit=u.m)
        source = SkyCoord(model.AltAz(az=120 * u.deg, alt=el * u.deg, obstime=times[row],
                                      location=VLA))
        expected = model.projected_dipole_pa(source, loc, times[row:row + 1], 30.0)
        assert abs(theta[row, 0].wrap_at(180 * u.deg).rad - expected[0]) < np.radians(0.5 / 3600)


# --- feed rotation --------------------------------------------------------------


def test_feed_rotation_uvdata_against_erfa_hd2pa():
    uv = make_uv(["r", "l"], [10, 10], "alt-az", CIRCULAR, catalog=sidereal())
    theta = feed_rotation_uvdata(uv)
    times = Time(uv.time_array, format="jd")
    for row in range(uv.Nblts):
        for col, ants in enumerate((uv.ant_1_array, uv.ant_2_array)):
            k = ants[row]
            loc = EarthLocation.from_geocentric(
                *(uv.telescope.antenna_positions[k] + [VLA.x.value, VLA.y.value, VLA.z.value]),
                unit=u.m)
            pa = model.parallactic_angle(SOURCE, loc, times[row:row + 1])[0]
            # ERFA hd2pa on astropy HADec, plus the receptor angle of R (10 deg).
            assert abs((theta[row, col] - (pa * u.rad + 10 * u.deg)).wrap_at(180 * u.deg)) \
                < 5 * u.mas


@pytest.mark.parametrize("dec", [-30.0, 30.0, 60.0])
def test_icrs_frame_against_pyuvdata_frame_pa(dec):
    # pyuvdata's phase_center_frame_pa: the PA of the catalogue north in the apparent
    # frame by a 0.5 deg finite difference; it differs from ERFA by 3e-4 deg at dec +-30
    # and 2e-3 deg at dec 60 (measured), so the tolerance is 3e-3 deg.
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR,
                 catalog=sidereal(SkyCoord(150 * u.deg, dec * u.deg)))
    apparent = feed_rotation_uvdata(uv)
    icrs = feed_rotation_uvdata(uv, frame="icrs")
    delta = (apparent - icrs)[:, 0].to_value(u.deg)
    assert np.allclose(delta, np.degrees(uv.phase_center_frame_pa), atol=3e-3)


def test_unprojected_alt_az_is_nan_with_one_warning():
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR)
    with pytest.warns(DegenerateGeometryWarning, match=r"undefined in 20 of 20") as record:
        theta = feed_rotation_uvdata(uv)
    assert len(record) == 1 and np.all(np.isnan(theta))


def test_ephemeris_outside_its_span_is_refused():
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR, catalog=ephem_catalog())
    entry = uv.phase_center_catalog[0]
    entry["cat_times"] = entry["cat_times"] + 0.1  # now starts after the first epoch
    with pytest.raises(ValueError, match="ephemeris of phase centre 'BODY' covers"):
        feed_rotation_uvdata(uv)


# --- correction, against the voltage model ---------------------------------------------


def ephem_catalog():
    times = T0 + np.array([-0.05, 0.05, 0.1, 0.2])
    lon = np.radians(359.9 + 0.1 * np.arange(4))  # crosses RA 0: unwrapping needed
    return {0: dict(cat_name="BODY", cat_type="ephem", cat_frame="icrs", cat_epoch=2000.0,
                    cat_times=times, cat_lon=lon, cat_lat=np.radians(30 + 0.05 * np.arange(4)))}


def ephem_source(times):
    from scipy.interpolate import make_interp_spline  # cubic, 4 points (as pyuvdata)

    cat = ephem_catalog()[0]
    ra = make_interp_spline(cat["cat_times"], np.unwrap(cat["cat_lon"]), k=3)(times.jd)
    dec = make_interp_spline(cat["cat_times"], cat["cat_lat"], k=3)(times.jd)
    return SkyCoord(ra * u.rad, dec * u.rad)


CASES = {
    "sidereal-icrs": (sidereal(), fixed(SOURCE)),
    "sidereal-fk4": (sidereal(SOURCE.fk4, "fk4", 1950.0), fixed(SOURCE)),
    "ephem": (ephem_catalog(), ephem_source),
    "driftscan": ({0: dict(cat_name="D", cat_type="driftscan", cat_lon=np.radians(200.0),
                           cat_lat=np.radians(50.0))},
                  lambda t: SkyCoord(model.AltAz(az=np.full(t.shape, 200) * u.deg,
                                                 alt=np.full(t.shape, 50) * u.deg,
                                                 obstime=t, location=VLA))),
}

FEEDS = {
    "circular": (["r", "l"], [0, 0], CIRCULAR),
    "circular-subset": (["r", "l"], [5, 5], ["lr", "rl"]),
    "linear-ata": (["x", "y"], [90, 0], ["yx", "xx", "yy", "xy"]),
    "linear-sma": (["x", "y"], [45, -45], LINEAR),
    "linear-alma": (["y", "x"], [80, -10], ["xy", "yy", "xx", "yx"]),
}


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("feeds", sorted(FEEDS))
@pytest.mark.parametrize("mount", ["alt-az", "alt-az+nasmyth-l"])
def test_correct_uvdata_recovers_the_source(case, feeds, mount):
    catalog, source = CASES[case]
    feed, angles, pols = FEEDS[feeds]
    uv = make_uv(feed, angles, mount, pols, catalog=catalog)
    model.inject(uv, STOKES, source, mount)
    before = uv.data_array.copy()
    out = correct_uvdata(uv)
    assert np.array_equal(uv.data_array, before)  # uv untouched
    expected = model.sky_data(uv, STOKES)
    assert np.allclose(out.data_array[:, 0, :], expected, atol=1e-6)
    if "rl" in pols or "xx" in pols:
        assert np.allclose(model.evpa(out), 25.0, atol=0.01)
    assert HISTORY_MARK in out.history and HISTORY_MARK not in uv.history


@pytest.mark.parametrize("feeds", ["circular", "linear-ata"])
def test_correct_uvdata_icrs_frame(feeds):
    # EVPA given in ICRS; in the apparent frame it is chi + delta, delta the PA of the
    # ICRS north there (ERFA: atci13 of the source and of a point 1 arcsec north; pas).
    feed, angles, pols = FEEDS[feeds]
    uv = make_uv(feed, angles, "alt-az", pols, catalog=sidereal())
    offset = np.radians(1 / 3600)

    def stokes(times):
        t = times.tt
        r, d = SOURCE.ra.rad, SOURCE.dec.rad
        r1, d1, _ = erfa.atci13(r, d, 0, 0, 0, 0, t.jd1, t.jd2)
        r2, d2, _ = erfa.atci13(r, d + offset, 0, 0, 0, 0, t.jd1, t.jd2)
        return model.stokes_from_evpa(0.3, 25.0 + np.degrees(erfa.pas(r1, d1, r2, d2)))

    model.inject(uv, stokes, fixed(SOURCE), "alt-az")
    out = correct_uvdata(uv, frame="icrs")
    assert np.allclose(model.evpa(out), 25.0, atol=0.01)
    assert "frame=icrs" in out.history


def test_correct_uvdata_unprojected_fixed_dipoles():
    uv = make_uv(["x", "y"], [90, 0], "fixed", LINEAR)
    model.inject(uv, STOKES, lambda t: SkyCoord(model.AltAz(
        az=np.zeros(t.shape) * u.deg, alt=np.full(t.shape, 90) * u.deg, obstime=t,
        location=VLA)), "fixed")
    out = correct_uvdata(uv, inplace=True)
    assert out is uv
    assert np.allclose(model.evpa(out), 25.0, atol=0.01)
    assert np.allclose(uv.telescope.feed_angle, [[0, np.pi / 2]] * 4)  # x north, y east


def test_feed_angle_after_correction_and_twice_refused():
    uv = make_uv(["y", "x"], [80, -10], "alt-az", LINEAR, catalog=sidereal())
    out = correct_uvdata(uv)
    assert np.allclose(out.telescope.feed_angle, [[np.pi / 2, 0.0]] * 4)  # y east, x north
    with pytest.raises(ValueError, match="removed already"):
        correct_uvdata(out)


def test_inplace_chunks_use_little_memory():
    uv = make_uv(["x", "y"], [90, 0], "alt-az", LINEAR, catalog=sidereal(), ntimes=20,
                 nfreqs=256, step=60.0)
    uv.data_array[:] = 1.0
    reference = correct_uvdata(uv)
    calls = []
    correct_uvdata(uv.copy(), inplace=True, progress=lambda done, total: calls.append(total))
    assert len(calls) > 1
    tracemalloc.start()
    start = tracemalloc.get_traced_memory()[0]
    correct_uvdata(uv, inplace=True)
    peak = tracemalloc.get_traced_memory()[1] - start
    tracemalloc.stop()
    assert peak < uv.data_array.nbytes / 4, (peak, uv.data_array.nbytes)
    assert np.array_equal(uv.data_array, reference.data_array)


def test_autocorrelations():
    uv = make_uv(["x", "y"], [90, 0], "alt-az", LINEAR, catalog=sidereal(),
                 antpairs=[(0, 0), (0, 1), (1, 1)])
    model.inject(uv, STOKES, fixed(SOURCE), "alt-az")
    out = correct_uvdata(uv)
    auto = out.ant_1_array == out.ant_2_array
    xx = list(out.polarization_array).index(-5)
    assert np.all(out.data_array[auto, :, xx].imag == 0)
    assert np.allclose(model.evpa(out), 25.0, atol=0.01)
    # Circular autos: RR unchanged, RL turned (by twice the feed rotation).
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR, catalog=sidereal(),
                 antpairs=[(0, 0), (1, 1)])
    model.inject(uv, STOKES, fixed(SOURCE), "alt-az")
    out = correct_uvdata(uv)
    assert np.allclose(out.data_array[:, :, 0], uv.data_array[:, :, 0])
    assert not np.allclose(out.data_array[:, :, 2], uv.data_array[:, :, 2])


def test_nan_rows_are_flagged_with_one_warning():
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR)
    uv.data_array[:] = 1.0
    with pytest.warns(DegenerateGeometryWarning, match="undefined in 20 of 20.*flagged") as rec:
        out = correct_uvdata(uv)
    assert len(rec) == 1
    assert np.all(np.isnan(out.data_array)) and np.all(out.flag_array)


def test_progress_bar(capsys):
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR, catalog=sidereal())
    correct_uvdata(uv, progress=True)
    before = uv.data_array.copy()
    with pytest.raises(TypeError, match="progress must be True, False or a callable"):
        correct_uvdata(uv, inplace=True, progress="yes")
    np.testing.assert_array_equal(uv.data_array, before)  # refused before any change


# --- bad input -------------------------------------------------------------------------


def test_not_uvdata():
    with pytest.raises(TypeError, match="must be a pyuvdata UVData"):
        correct_uvdata(np.zeros(3))
    with pytest.raises(TypeError, match="must be a pyuvdata UVData"):
        antennas_from_uvdata("file.uvfits")


def test_missing_mount_type():
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR, catalog=sidereal())
    uv.telescope.mount_type = None
    with pytest.raises(ValueError, match="do not say how the antennas are mounted"):
        antennas_from_uvdata(uv)


def test_phased_mount():
    uv = make_uv(["x", "y"], [90, 0], "phased", LINEAR, catalog=sidereal())
    with pytest.raises(ValueError,
                       match=r"antennas? 0 \(A0\).*: .*phased.*set uv.telescope.mount_type"):
        correct_uvdata(uv)


def test_stokes_and_parallel_hands_refused():
    uv = make_uv(["x", "y"], [90, 0], "alt-az", ["pI", "pQ"], catalog=sidereal())
    with pytest.raises(ValueError, match="Stokes or pseudo-Stokes.*before forming"):
        correct_uvdata(uv)
    uv = make_uv(["x", "y"], [90, 0], "alt-az", ["xx", "yy"], catalog=sidereal())
    with pytest.raises(ValueError, match="XX, XY, YX and YY.*feed_rotation_uvdata"):
        correct_uvdata(uv)


def test_other_bad_input():
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR, catalog=sidereal())
    with pytest.raises(ValueError, match="vertical must be one of"):
        antennas_from_uvdata(uv, vertical="up")
    with pytest.raises(TypeError, match="antennas must be a mapping"):
        feed_rotation_uvdata(uv, antennas=[1, 2])
    with pytest.raises(ValueError, match="antennas lacks"):
        feed_rotation_uvdata(uv, antennas={0: antennas_from_uvdata(uv)[0]})
    plain = {k: Antenna(a.location, a.mount) for k, a in antennas_from_uvdata(uv).items()}
    with pytest.raises(ValueError, match="has no receptors"):
        feed_rotation_uvdata(uv, antennas=plain)


def test_unknown_extension(tmp_path):
    uv = make_uv(["r", "l"], [0, 0], "alt-az", CIRCULAR, catalog=sidereal())
    with pytest.raises(ValueError, match="cannot tell the format of 'x.fits'"):
        write_uvdata(uv, tmp_path / "x.fits")
    write_uvdata(uv, tmp_path / "x.uvh5")
    with pytest.raises(FileExistsError, match="overwrite=True"):
        write_uvdata(uv, tmp_path / "x.uvh5")
    write_uvdata(uv, tmp_path / "x.uvh5", overwrite=True)
    with pytest.raises(FileNotFoundError, match="no file or directory"):
        read_uvdata(tmp_path / "nothing.uvh5")


def test_missing_pyuvdata(monkeypatch):
    monkeypatch.setitem(sys.modules, "pyuvdata", None)
    with pytest.raises(ImportError, match=r"python -m pip install pyuvdata \(or, in a clone of "
                       r"astropy_feedrot, python -m pip install -e '\.\[uvdata\]'\)"):
        correct_uvdata(object())


# --- real files -------------------------------------------------------------------------


def untar(name, tmp_path):
    with tarfile.open(os.path.join(DATA, name)) as tf:
        top = tf.getnames()[0].split("/")[0]
        tf.extractall(tmp_path, filter="data")
    return str(tmp_path / top)


def read(path):
    with warnings.catch_warnings():
        # pyuvdata's complaints about the files (uvw mismatches, missing sites...).
        warnings.simplefilter("ignore")
        return read_uvdata(path)


@pytest.fixture(scope="module")
def real(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("uvdata")
    return {
        "vla_uvfits": read(os.path.join(DATA, "day2_TDEM0003_10s_norx_1src_1spw_2ints.uvfits")),
        "vla_ms_path": untar("day2_TDEM0003_10s_norx_1src_1spw_2ints.ms.tar.gz", tmp),
        "alma": read(untar("X5707_1spw_1scan_10chan_1time_1bl_noatm.ms.tar.gz", tmp)),
        "ata": read(os.path.join(DATA, "ata.LoA.C0352.uvh5_60647_62965_9760406_3c286_0001.uvh5")),
        "sma": read(untar("sma_test_corrchunk1.mir.tar.gz", tmp)),
        "vlba": read(os.path.join(DATA, "mojave.uvfits")),
        "paper": read(os.path.join(DATA, "zen.2456865.60537.xy.uvcRREAAM.uvfits")),
        "lwa": read(untar("lwasv_cor_58342_05_00_14.ms.tar.gz", tmp)),
    }


@pytest.mark.parametrize("name, kind, receptors", [
    ("vla_uvfits", "AltAzMount", Receptors("RL", [0, 0] * u.deg)),  # POLTYB blank
    ("alma", "AltAzMount", Receptors("XY", [-10, 80] * u.deg)),
    ("ata", "AltAzMount", Receptors("XY", [90, 0] * u.deg)),
    ("sma", "AltAzMount", Receptors("XY", [45, -45] * u.deg)),
    ("vlba", "AltAzMount", Receptors("RL", [0, 0] * u.deg)),
    ("paper", "StationaryMount", Receptors("XY", [0, -90] * u.deg)),
    ("lwa", "AltAzMount", None),
])
def test_antennas_of_real_files(real, name, kind, receptors):
    if name == "lwa":  # RECEPTOR_ANGLE 0 for both dipoles: parallel, refused
        with pytest.raises(ValueError, match="parallel.*set uv.telescope.feed_angle"):
            antennas_from_uvdata(real[name])
        return
    antennas = antennas_from_uvdata(real[name])
    a = next(iter(antennas.values()))
    assert type(a.mount).__name__ == kind
    assert a.receptors.types == receptors.types
    assert np.allclose(a.receptors.angles.value, receptors.angles.value, atol=1e-4)


def test_vla_ms_against_casacore(real):
    tables = pytest.importorskip("casacore.tables")
    path = real["vla_ms_path"]
    uv = read(path)
    t = tables.taql(f"select TIME, ANTENNA1, ANTENNA2, mscal.pa1() as PA1, "
                    f"mscal.pa2() as PA2 from '{path}'")
    casa = {(round(float(tm), 3), int(a1), int(a2)): (p1, p2) for tm, a1, a2, p1, p2 in zip(
        t.getcol("TIME"), t.getcol("ANTENNA1"), t.getcol("ANTENNA2"), t.getcol("PA1"),
        t.getcol("PA2"))}
    t.close()
    mjd_s = np.round(Time(uv.time_array, format="jd").mjd * 86400, 3)
    geocentric = feed_rotation_uvdata(uv, vertical="geocentric").to_value(u.rad)
    geodetic = feed_rotation_uvdata(uv).to_value(u.rad)
    keys = zip(mjd_s, uv.ant_1_array, uv.ant_2_array)
    ref = np.array([casa[(m, a1, a2)] for m, a1, a2 in keys])
    wrap = lambda x: np.degrees(np.angle(np.exp(1j * x))) * 3600  # noqa: E731
    diff_geocentric = np.abs(wrap(geocentric - ref))
    diff_geodetic = np.abs(wrap(geodetic - ref))
    cross = uv.ant_1_array != uv.ant_2_array
    print("casacore vs geocentric max", diff_geocentric[cross].max(), "arcsec;",
          "vs geodetic", diff_geodetic[cross].min(), diff_geodetic[cross].max())
    # casacore (AZEL: geocentric vertical) and astropy/ERFA differ by a few tenths of an
    # arcsec in hour angle and declination: 0.52 arcsec measured. The geodetic vertical
    # moves the parallactic angle by 260-263 arcsec here.
    assert diff_geocentric.max() < 0.6
    assert 250 < diff_geodetic[cross].min() and diff_geodetic[cross].max() < 275


def test_correct_real_files_round_trip(real, tmp_path):
    for name, ext in (("vla_uvfits", ".uvfits"), ("ata", ".uvh5"), ("vlba", ".uvh5")):
        uv = real[name]
        # mojave.uvfits: AIPS removed the parallactic angle already (CLCOR PANG, then
        # SPLIT); tests/visibilities/test_history.py holds the refusal.
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DegenerateGeometryWarning)
            out = correct_uvdata(uv, redo=name == "vlba")
        path = tmp_path / (name + ext)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            write_uvdata(out, path)
        back = read(path)
        assert HISTORY_MARK.replace(" ", "") in back.history.replace(" ", "").replace("\n", "")
        assert np.allclose(back.data_array, out.data_array, equal_nan=True, rtol=1e-6)
        with pytest.raises(ValueError, match="removed already"):
            correct_uvdata(back)
    for name in ("alma", "sma"):  # XX and YY only
        with pytest.raises(ValueError, match="XX, XY, YX and YY"):
            correct_uvdata(real[name])
        assert feed_rotation_uvdata(real[name]).shape == (real[name].Nblts, 2)


def test_lwa_nan_file(real):
    uv = real["lwa"].copy()
    uv.telescope.feed_angle[:, 1] = np.pi / 2  # the file gives both dipoles angle 0
    # LWA-SV is an aperture array, refused as such (test_aperture_arrays.py); its NaN
    # visibilities under another name:
    uv.telescope.name = "TEST"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegenerateGeometryWarning)
        out = correct_uvdata(uv)
    assert np.isnan(out.data_array).sum() >= np.isnan(uv.data_array).sum()
