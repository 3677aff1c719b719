# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""FITS-IDI: the antenna tables and correct_fitsidi.

References: the files are written by ``fitsidi_writer`` with a polarized
point source injected through a voltage-level model written from the
definitions (feed rotation from ERFA's hd2pa on astropy's HADec, plus or
minus astropy's elevation for Nasmyth antennas; the ICRS north from ERFA's
atci13 and pas), independent of the package. The EVPA recovered must be the
one injected; the mount codes are those of the programs' sources (DiFX
``fitsAG.c``/``difx_input.h``, casacore ``MSFitsOutput.cc``).
"""

import hashlib
import os
import warnings

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import ICRS, AltAz, EarthLocation, SkyCoord
from astropy.io import fits
from fitsidi_writer import START, STATIONS, station_xyz, write_fitsidi

from astropy_feedrot import AltAzMount, NasmythFocus, XYMount
from astropy_feedrot.antennas.receptors import Receptors
from astropy_feedrot.core.exceptions import (
    CatalogueReceptorsWarning,
    DegenerateGeometryWarning,
    ReceptorAngleWarning,
)
from astropy_feedrot.io import FileFormatError
from astropy_feedrot.visibilities import (
    HISTORY_MARK,
    FITSFormatError,
    correct_fitsidi,
    fitsidi_antennas,
    writing_program,
)

# The writer gives WETTZ13S a left-handed Nasmyth focus to exercise that closed form
# (fitsidi_writer.STATIONS); that it differs from the catalogue's is tested in
# tests/visibilities/test_real_antennas.py.
pytestmark = pytest.mark.filterwarnings(
    "ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")

# R and L at one angle or 90 deg apart, as files give them (Receptors.sky_angles).
CIRCULAR_ANGLES = {0: (5.0, 95.0), 2: (12.0, 12.0)}
LINEAR_ANGLES = {0: (15.0, 105.0), 1: (-30.0, 62.0), 3: (0.0, 90.0)}


def sha(path):
    with open(path, "rb") as fh:
        return hashlib.sha256(fh.read()).hexdigest()


def flux(path, info, complex_length=2):
    n_rows = len(info["rows"])
    with fits.open(path) as hdul:
        f = np.array(hdul["UV_DATA"].data["FLUX"], dtype=float)
    f = f.reshape(n_rows, 1, 1, info["n_band"], info["n_chan"], len(info["products"]),
                  complex_length)
    return f


def corrected_products(path, info, complex_length=2):
    f = flux(path, info, complex_length)
    # Undo FITS-IDI's conjugation and the channel gains of the writer.
    vis = (f[..., 0] + 1j * f[..., 1]).conj()[:, 0, 0]
    gain = 1.0 + 0.1 * np.arange(info["n_chan"])[None, :] + 0.01 * np.arange(
        info["n_band"])[:, None]
    return vis / gain[None, :, :, None]


def evpa(products, values):
    """EVPA (deg) from corrected products: chi = arg(RL)/2 (RL = (Q + iU)/2) or
    atan2(U, Q)/2 with Q = XX - YY, U = Re(XY + YX) (the writer's definitions)."""
    values = np.asarray(values)
    if "RL" in products:
        return np.degrees(np.angle(values[..., products.index("RL")])) / 2
    q = values[..., products.index("XX")] - values[..., products.index("YY")]
    u_ = values[..., products.index("XY")] + values[..., products.index("YX")]
    return np.degrees(np.arctan2(u_.real, q.real)) / 2


def run(tmp_path, name="in.idifits", **kwargs):
    source = tmp_path / name
    info = write_fitsidi(source, **kwargs)
    return source, info


# ------------------------------------------------------------------ round trips


@pytest.mark.parametrize("frame", ["apparent", "icrs"])
@pytest.mark.parametrize("products", [
    ("RR", "LL", "RL", "LR"),     # DiFX order, CDELT -1
    ("LR", "RL", "LL", "RR"),     # CDELT +1
    ("RR", "LL"),                 # parallel hands only
    ("LL", "RR"),
])
def test_circular_round_trip(tmp_path, products, frame):
    source, info = run(tmp_path, products=products, angles=CIRCULAR_ANGLES, frame=frame)
    before = sha(source)
    output = tmp_path / "out.idifits"
    assert correct_fitsidi(source, output, frame=frame) == os.fspath(output)
    assert sha(source) == before
    got = corrected_products(output, info)
    expected = info["expected"][:, None, None, :]
    np.testing.assert_allclose(got, np.broadcast_to(expected, got.shape), atol=2e-6)
    if "RL" in products:
        chi = evpa(list(products), got)
        assert np.max(np.abs(chi - info["evpa"])) < 0.01


def test_unusual_circular_angles_warn_once_and_use_the_first(tmp_path):
    # R 5, L -7 deg and R 12, L 3 deg: neither one angle nor 90 deg apart. Both
    # receptors turn with the first's angle, as CASA's applycal does (test_casa.py),
    # and as the voltage model of fitsidi_writer turns them.
    source, info = run(tmp_path, angles={0: (5.0, -7.0), 2: (12.0, 3.0)})
    output = tmp_path / "out.idifits"
    with pytest.warns(ReceptorAngleWarning) as caught:
        correct_fitsidi(source, output)
    caught = [w for w in caught if w.category is ReceptorAngleWarning]
    assert len(caught) == 1
    assert str(caught[0].message) == (
        f"{source}: circular receptors neither at one angle nor 90 deg apart (the usual "
        "offsets) at 2 antennas: antenna 1 (FD-VLBA): R 5, L -7 deg; antenna 3 (YEBES40M): "
        "R 12, L 3 deg; both receptors of each turn with the first one's angle, as in CASA "
        "(the second angle is ignored); give the feeds (feeds=, --feeds) if the file's "
        "angles are wrong")
    got = corrected_products(output, info)
    expected = info["expected"][:, None, None, :]
    np.testing.assert_allclose(got, np.broadcast_to(expected, got.shape), atol=2e-6)


@pytest.mark.parametrize("frame", ["apparent", "icrs"])
@pytest.mark.parametrize("products", [("XX", "YY", "XY", "YX"), ("YX", "XY", "YY", "XX")])
def test_linear_round_trip(tmp_path, products, frame):
    source, info = run(tmp_path, products=products, angles=LINEAR_ANGLES, frame=frame)
    output = tmp_path / "out.idifits"
    correct_fitsidi(source, output, frame=frame)
    got = corrected_products(output, info)
    expected = info["expected"][:, None, None, :]
    np.testing.assert_allclose(got, np.broadcast_to(expected, got.shape), atol=2e-6)
    chi = evpa(list(products), got)
    assert np.max(np.abs(chi - info["evpa"])) < 0.01


@pytest.mark.parametrize("products", [("RR", "LL", "RL", "LR"), ("LR", "RL", "LL", "RR"),
                                      ("XX", "YY", "XY", "YX"), ("YX", "XY", "YY", "XX")])
def test_difx_file_with_two_arrays_and_two_setups(tmp_path, products):
    # As difx2fits writes it (fitsHeader.c, fitsAG.c, fitsAN.c, fitsUV.c): a
    # primary header with NAXIS = 0, GROUPS = T, GCOUNT = PCOUNT = 0 (astropy
    # opens it as random groups), ORBPARM/POLCALA/POLCALB/GATEID columns of
    # length 0, a WEIGHT column; here also two arrays (two ARRAY_GEOMETRY
    # tables) and two frequency setups (ANTENNA rows per FREQID).
    angles = LINEAR_ANGLES if products[0][0] in "XY" else CIRCULAR_ANGLES
    source, info = run(tmp_path, products=products, angles=angles, n_arrays=2, n_freqid=2)
    with fits.open(source) as hdul:
        assert hdul[0].header["GROUPS"] and hdul[0].header["GCOUNT"] == 0
        assert [h.header["EXTVER"] for h in hdul if h.name == "ARRAY_GEOMETRY"] == [1, 2]
        assert hdul["UV_DATA"].columns["GATEID"].format == "0J"
        assert set(hdul["UV_DATA"].data["FREQID"]) == {1, 2}
    assert sorted(fitsidi_antennas(source)) == [1, 2, 3, 4]
    output = tmp_path / "out.idifits"
    correct_fitsidi(source, output)
    got = corrected_products(output, info)
    expected = info["expected"][:, None, None, :]
    # Reference: the writer's voltage-level model (ERFA hd2pa on astropy's HADec).
    np.testing.assert_allclose(got, np.broadcast_to(expected, got.shape), atol=2e-6)
    assert np.max(np.abs(evpa(list(products), got) - info["evpa"])) < 0.01
    with fits.open(source) as a, fits.open(output) as b:
        np.testing.assert_array_equal(a["UV_DATA"].data["WEIGHT"], b["UV_DATA"].data["WEIGHT"])


def test_an_antenna_number_in_two_arrays_is_refused(tmp_path):
    source, _ = run(tmp_path, n_arrays=2)

    def edit(hdul):
        second = [h for h in hdul if h.name == "ARRAY_GEOMETRY"][1]
        second.data["NOSTA"][0] = 1

    bad = rewrite(source, tmp_path / "bad.idifits", edit)
    with pytest.raises(FITSFormatError, match=r"ARRAY_GEOMETRY \(EXTVER 1\), column NOSTA: "
                                              r"expected one row per antenna number .*\[1\]"):
        fitsidi_antennas(bad)


def test_without_correction_the_evpa_wanders(tmp_path):
    # The injected data are not trivially right: before correction RL turns
    # with the feed rotation (tens of degrees over the track).
    source, info = run(tmp_path, angles=CIRCULAR_ANGLES)
    got = corrected_products(source, info)
    assert np.ptp(evpa(info["products"], got)) > 20


def test_linear_parallel_hands_are_refused(tmp_path):
    source, _ = run(tmp_path, products=("XX", "YY"))
    with pytest.raises(ValueError, match=r"lack \['XY', 'YX'\].*rotate Stokes Q and U.*"
                                         r"feed_rotation_rows"):
        correct_fitsidi(source, tmp_path / "out.idifits")
    assert not (tmp_path / "out.idifits").exists()


def test_weight_in_the_complex_axis_and_crpix(tmp_path):
    source, info = run(tmp_path, complex_length=3, crpix=3.0, angles=CIRCULAR_ANGLES)
    output = tmp_path / "out.idifits"
    correct_fitsidi(source, output)
    got = corrected_products(output, info, complex_length=3)
    np.testing.assert_allclose(got, np.broadcast_to(info["expected"][:, None, None, :],
                                                    got.shape), atol=2e-6)
    np.testing.assert_array_equal(flux(output, info, 3)[..., 2], 1.0)


def test_output_differs_only_in_flux_and_history(tmp_path):
    source, _ = run(tmp_path, angles=CIRCULAR_ANGLES)
    output = tmp_path / "out.idifits"
    correct_fitsidi(source, output)
    with fits.open(source) as a, fits.open(output) as b:
        assert len(a) == len(b)
        history = [str(h) for h in b[0].header["HISTORY"]]
        assert HISTORY_MARK in "".join(history)
        before = [str(h) for h in a[0].header["HISTORY"]]
        assert before == history[:len(before)] and len(history) > len(before)
        for key in a[0].header:
            if key != "HISTORY":
                assert a[0].header[key] == b[0].header[key]
        for ha, hb in zip(a[1:], b[1:]):
            assert ha.header == hb.header
            for name in ha.columns.names:
                if ha.name == "UV_DATA" and name == "FLUX":
                    assert not np.array_equal(ha.data[name], hb.data[name])
                else:
                    np.testing.assert_array_equal(ha.data[name], hb.data[name])


def test_chunks_give_the_same_file(tmp_path):
    source, _ = run(tmp_path, angles=CIRCULAR_ANGLES)
    correct_fitsidi(source, tmp_path / "one.idifits")
    calls = []
    with fits.open(source) as hdul:
        row_bytes = hdul["UV_DATA"].header["NAXIS1"]
        n_rows = hdul["UV_DATA"].header["NAXIS2"]
    correct_fitsidi(source, tmp_path / "many.idifits", chunk_bytes=7 * row_bytes,
                    progress=lambda done, total: calls.append((done, total)))
    assert sha(tmp_path / "one.idifits") == sha(tmp_path / "many.idifits")
    chunks = -(-n_rows // 7)
    assert calls == [(k, chunks) for k in range(1, chunks + 1)]


def test_progress_bar(tmp_path, capsys):
    source, _ = run(tmp_path)
    correct_fitsidi(source, tmp_path / "out.idifits", progress=True)
    with pytest.raises(TypeError, match="progress must be True, False or a callable"):
        correct_fitsidi(source, tmp_path / "out2.idifits", progress="yes")


def test_multi_source_rows_use_their_source(tmp_path):
    # Two sources 90 deg apart in RA: a file with both, and each row must be
    # corrected with its own (checked by the round trip above); swapping the
    # SOURCE ids in the table breaks it.
    source, info = run(tmp_path, angles=CIRCULAR_ANGLES)
    with fits.open(source) as hdul:
        hdul["SOURCE"].data["SOURCE_ID"] = hdul["SOURCE"].data["SOURCE_ID"][::-1]
        hdul.writeto(tmp_path / "swapped.idifits")
    correct_fitsidi(tmp_path / "swapped.idifits", tmp_path / "out.idifits")
    got = corrected_products(tmp_path / "out.idifits", info)
    assert np.max(np.abs(evpa(info["products"], got) - info["evpa"])) > 1


def test_degenerate_rows_are_nan_with_zero_weight(tmp_path):
    # A source at the zenith of FD-VLBA at the first epoch: its alt-az feed
    # rotation is undefined (hd2pa's 0/0).
    fd = EarthLocation.from_geocentric(*station_xyz("FD-VLBA"), unit=u.m)
    zenith = SkyCoord(alt=90 * u.deg, az=0 * u.deg, frame=AltAz(obstime=START, location=fd))
    icrs = zenith.transform_to(ICRS())
    sources = [(1, "ZENITH", float(icrs.ra.deg), float(icrs.dec.deg))]
    source = tmp_path / "in.idifits"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # hd2pa in the writer
        info = write_fitsidi(source, sources=sources, n_times=2)
    output = tmp_path / "out.idifits"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        correct_fitsidi(source, output)
    degenerate = [w for w in caught if issubclass(w.category, DegenerateGeometryWarning)]
    if not degenerate:
        pytest.skip("the zenith direction did not give an exactly degenerate geometry")
    assert len(degenerate) == 1 and "rows" in str(degenerate[0].message)
    f = flux(output, info)
    with fits.open(output) as hdul:
        weight = np.array(hdul["UV_DATA"].data["WEIGHT"])
    bad = np.isnan(f[..., 0]).reshape(len(f), -1).any(axis=1)
    assert bad.any() and np.all(weight[bad] == 0) and np.all(weight[~bad] == 1)


# ------------------------------------------------------------------ refusals


def test_already_corrected_is_refused(tmp_path):
    source, _ = run(tmp_path)
    correct_fitsidi(source, tmp_path / "out.idifits")
    with pytest.raises(ValueError, match=r"removed already .*would remove it twice: pass "
                                         r"redo=True to correct all the same$"):
        correct_fitsidi(tmp_path / "out.idifits", tmp_path / "again.idifits")
    assert not (tmp_path / "again.idifits").exists()
    correct_fitsidi(tmp_path / "out.idifits", tmp_path / "again.idifits", redo=True)
    # The capitals of releases before 0.2 are recognised too.
    old = rewrite(source, tmp_path / "old.idifits", lambda hdul: hdul[0].header.add_history(
        "FEED ROTATION REMOVED by astropy_feedrot 0.1: UV_DATA FLUX corrected"))
    with pytest.raises(ValueError, match="removed already"):
        correct_fitsidi(old, tmp_path / "old_again.idifits")


@pytest.mark.parametrize("products, angles", [(("RR", "LL", "RL", "LR"), CIRCULAR_ANGLES),
                                              (("XX", "YY", "XY", "YX"), LINEAR_ANGLES)])
def test_apply_then_remove_gives_the_input_back(tmp_path, products, angles):
    # Identity: applying the feed rotation inverts removing it, row by row.
    source, info = run(tmp_path, products=products, angles=angles, n_freqid=2)
    removed = tmp_path / "removed.idifits"
    correct_fitsidi(source, removed)
    applied = tmp_path / "applied.idifits"
    correct_fitsidi(removed, applied, direction="apply")
    with fits.open(source) as a, fits.open(applied) as b:
        np.testing.assert_allclose(b["UV_DATA"].data["FLUX"], a["UV_DATA"].data["FLUX"],
                                   rtol=0, atol=1e-6)
        assert "Feed rotation applied by astropy_feedrot" in "".join(
            str(h) for h in b[0].header["HISTORY"])
    # Applied to the sky-fixed products, the forward direction gives what the
    # writer's model measured (its voltage-level model, ERFA hd2pa).
    with pytest.raises(ValueError, match="applied already"):
        correct_fitsidi(applied, tmp_path / "twice.idifits", direction="apply")
    with pytest.raises(ValueError, match="direction must be one of"):
        correct_fitsidi(source, tmp_path / "x.idifits", direction="forward")


def _double_precision(source, target):
    """A copy of a FITS-IDI file with FLUX stored in double precision (format D)."""
    with fits.open(source) as hdul:
        hdu = hdul["UV_DATA"]
        values = np.asarray(hdu.data["FLUX"], dtype=np.float64)
        columns = [fits.Column("FLUX", f"{values.shape[1]}D", unit=c.unit, array=values)
                   if c.name == "FLUX" else c for c in hdu.columns]
        hdul["UV_DATA"] = fits.BinTableHDU.from_columns(columns, header=hdu.header,
                                                        name="UV_DATA")
        hdul.writeto(target)


@pytest.mark.parametrize("products, angles, complex_length", [
    (("RR", "LL", "RL", "LR"), CIRCULAR_ANGLES, 2),
    (("RR", "LL", "RL", "LR"), CIRCULAR_ANGLES, 3),
    (("XX", "YY", "XY", "YX"), LINEAR_ANGLES, 2)])
def test_double_precision_flux_is_corrected_in_double_precision(
        tmp_path, products, angles, complex_length):
    # FLUX in format D is corrected as complex128: removing then applying gives
    # the input back to double-precision rounding (single precision would leave
    # 1e-7), and it agrees with the same file in format E to the latter's
    # precision (the tests above check E against the writer's model).
    source, info = run(tmp_path, products=products, angles=angles,
                       complex_length=complex_length)
    double = tmp_path / "double.idifits"
    _double_precision(source, double)
    removed, applied = tmp_path / "removed.idifits", tmp_path / "applied.idifits"
    correct_fitsidi(double, removed)
    correct_fitsidi(removed, applied, direction="apply")
    single = tmp_path / "single.idifits"
    correct_fitsidi(source, single)
    with fits.open(double) as a, fits.open(applied) as b, fits.open(removed) as r, \
            fits.open(single) as e:
        assert r["UV_DATA"].columns["FLUX"].format.format == "D"
        np.testing.assert_allclose(b["UV_DATA"].data["FLUX"], a["UV_DATA"].data["FLUX"],
                                   rtol=0, atol=1e-13)
        np.testing.assert_allclose(r["UV_DATA"].data["FLUX"], e["UV_DATA"].data["FLUX"],
                                   rtol=0, atol=2e-6)


def test_paths(tmp_path):
    source, _ = run(tmp_path)
    output = tmp_path / "out.idifits"
    output.write_bytes(b"x")
    with pytest.raises(FileExistsError, match="overwrite=True"):
        correct_fitsidi(source, output)
    correct_fitsidi(source, output, overwrite=True)
    with pytest.raises(ValueError, match="is the input file"):
        correct_fitsidi(source, source, overwrite=True)
    os.link(source, tmp_path / "hard.idifits")
    with pytest.raises(ValueError, match="is the input file"):
        correct_fitsidi(source, tmp_path / "hard.idifits", overwrite=True)
    with pytest.raises(FileNotFoundError, match="no such file"):
        correct_fitsidi(tmp_path / "none.idifits", tmp_path / "x.idifits")
    with pytest.raises(IsADirectoryError, match="is a directory"):
        correct_fitsidi(source, tmp_path, overwrite=True)
    with pytest.raises(ValueError, match="chunk_bytes must be positive"):
        correct_fitsidi(source, tmp_path / "y.idifits", chunk_bytes=0)
    (tmp_path / "z.gz").write_bytes(b"\x1f\x8b" + b"\0" * 100)
    with pytest.raises(FITSFormatError, match="uncompressed FITS"):
        correct_fitsidi(tmp_path / "z.gz", tmp_path / "y.idifits")
    # Nothing is left behind by the refusals.
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []


def rewrite(source, target, edit):
    with fits.open(source) as hdul:
        edit(hdul)
        hdul.writeto(target, overwrite=True)
    return target


def _drop_column(table, column):
    def edit(hdul):
        hdu = hdul[table]
        columns = [c for c in hdu.columns if c.name != column]
        new = fits.BinTableHDU.from_columns(columns, header=hdu.header, name=table)
        hdul[table] = new
    return edit


def _set(table, **keys):
    def edit(hdul):
        for key, value in keys.items():
            if value is None:
                del hdul[table].header[key]
            else:
                hdul[table].header[key] = value
    return edit


def _set_data(table, column, value):
    def edit(hdul):
        hdul[table].data[column][0] = value
    return edit


def _remove(table):
    def edit(hdul):
        del hdul[table]
    return edit


@pytest.mark.parametrize("edit, error, match", [
    (_remove("UV_DATA"), FITSFormatError, "table UV_DATA: expected a UV_DATA table"),
    (_remove("SOURCE"), FITSFormatError, "table SOURCE: expected a SOURCE table"),
    (_remove("ANTENNA"), FITSFormatError, "table ANTENNA: expected the ANTENNA table"),
    (_drop_column("UV_DATA", "BASELINE"), FITSFormatError, "column BASELINE"),
    (_drop_column("UV_DATA", "FLUX"), FITSFormatError, "column FLUX: expected a FLUX column"),
    (_drop_column("SOURCE", "RAEPO"), FITSFormatError, "column RAEPO"),
    (_drop_column("SOURCE", "EQUINOX"), None, None),  # EPOCH is used instead
    (_set("UV_DATA", CTYPE1="FOO"), FITSFormatError, "axis 1 COMPLEX"),
    (_set("UV_DATA", MAXIS3=4), FITSFormatError, r"FLUX of \d+ numbers per row"),
    (_set("UV_DATA", MAXIS=None), FITSFormatError, "the keyword MAXIS"),
    (_set("UV_DATA", CTYPE2="FOO"), FITSFormatError, "a STOKES axis"),
    (_set("UV_DATA", CDELT2=-0.5), FITSFormatError, "integer polarization codes"),
    (_set("UV_DATA", CRVAL2=1.0, CDELT2=1.0), ValueError, r"codes \[1, 2, 3, 4\] are not "
     r"correlation products.*rotate Q and U"),
    (_set("ARRAY_GEOMETRY", TIMSYS="GPS", TIMESYS=None), FITSFormatError,
     "column TIMSYS: expected a time system"),
    (_set("ARRAY_GEOMETRY", TIMSYS=None, TIMESYS=None), FITSFormatError,
     "a TIMSYS keyword"),
    (_set_data("UV_DATA", "BASELINE", 5), FITSFormatError,
     r"BASELINE = 256 \* antenna1 \+ antenna2.*got '5'"),
    (_set_data("UV_DATA", "SOURCE", 9), FITSFormatError, r"source ids of the SOURCE table"),
    (_set_data("SOURCE", "DECEPO", np.nan), FITSFormatError, "finite RAEPO and DECEPO"),
    (_set_data("SOURCE", "EQUINOX", "B1900"), ValueError, "equinox 'B1900' is not supported"),
    (_set_data("ANTENNA", "POLTYA", "X"), ValueError, "mixes circular"),
])
def test_malformed_files(tmp_path, edit, error, match):
    source, _ = run(tmp_path)
    bad = rewrite(source, tmp_path / "bad.idifits", edit)
    if error is None:
        correct_fitsidi(bad, tmp_path / "out.idifits")
        return
    with pytest.raises(error, match=match):
        correct_fitsidi(bad, tmp_path / "out.idifits")
    assert not (tmp_path / "out.idifits").exists()


def test_receptors_of_the_other_basis(tmp_path):
    source, _ = run(tmp_path)

    def edit(hdul):
        hdul["ANTENNA"].data["POLTYA"][1] = "X"
        hdul["ANTENNA"].data["POLTYB"][1] = "Y"
        hdul["ANTENNA"].data["POLAB"][1] = [90.0, 90.0]
    bad = rewrite(source, tmp_path / "bad.idifits", edit)
    with pytest.raises(ValueError, match=r"antenna 2 \(EFLSBERG\) has linear receptors.*"
                                         "PolConvert"):
        correct_fitsidi(bad, tmp_path / "out.idifits")


def test_a_single_source_without_a_source_column(tmp_path):
    source, info = run(tmp_path, sources=[(1, "3C84", 49.9506671, 41.5116961)],
                       angles=CIRCULAR_ANGLES)
    bad = rewrite(source, tmp_path / "nosrc.idifits", _drop_column("UV_DATA", "SOURCE"))
    correct_fitsidi(bad, tmp_path / "out.idifits")
    got = corrected_products(tmp_path / "out.idifits", info)
    assert np.max(np.abs(evpa(info["products"], got) - info["evpa"])) < 0.01
    two, _ = run(tmp_path, name="two.idifits")
    bad = rewrite(two, tmp_path / "nosrc2.idifits", _drop_column("UV_DATA", "SOURCE"))
    with pytest.raises(FITSFormatError, match="a SOURCE_ID .* several sources"):
        correct_fitsidi(bad, tmp_path / "out2.idifits")


# ------------------------------------------------------------------ antennas


def test_difx_antennas(tmp_path):
    source, _ = run(tmp_path, angles=CIRCULAR_ANGLES, mntsta=[0, 6, 4, 5])
    assert writing_program(source)[:2] == ("difx", "fits-idi:difx")
    antennas = fitsidi_antennas(source)
    assert sorted(antennas) == [1, 2, 3, 4]
    # DiFX's enum AntennaMountType: 6 = XYNS, 4/5 = Nasmyth R/L.
    assert antennas[2].mount == XYMount("north")
    assert antennas[3].focus == NasmythFocus("right")
    assert antennas[4].focus == NasmythFocus("left")
    assert antennas[1].mount == AltAzMount() and antennas[1].name == "FD-VLBA"
    assert antennas[1].receptors == Receptors("RL", [5.0, 95.0] * u.deg)
    # The positions are the catalogue's (the writer wrote them absolute).
    xyz = antennas[1].location.get_itrs().cartesian.xyz.to_value(u.m)
    np.testing.assert_allclose(xyz, [-1324009.454, -5332181.955, 3231962.369], atol=1e-6)
    assert fitsidi_antennas(source, vertical="geocentric")[1].vertical == "geocentric"


def test_software_overrides_detection(tmp_path):
    source, _ = run(tmp_path, mntsta=[0, 6, 0, 0])
    antennas = fitsidi_antennas(source, software="fits-idi:casacore")
    assert antennas[2].focus.__class__.__name__ == "BeamWaveguideFocus"
    with pytest.raises(ValueError, match="antenna 2 .*phased"):
        fitsidi_antennas(source, software="fits-idi:pyuvdata")
    with pytest.raises(ValueError, match="software must be a MNTSTA convention"):
        fitsidi_antennas(source, software="casacore")


@pytest.mark.parametrize("program, codes, expected", [
    ("casacore", [0, 1, 0, 3], ("casacore", "fits-idi:casacore")),
    ("casacore", [0, 9, 6, 0], ("casacore", "fits-idi:casacore")),
    ("casacore", [0, 4, 6, 0], ("casacore", None)),
    ("unknown", [0, 0, 0, 0], ("unknown", None)),
])
def test_writing_program_of_idi_files(tmp_path, program, codes, expected):
    source, _ = run(tmp_path, program=program, mntsta=codes)
    assert writing_program(source)[:2] == expected


def test_ambiguous_codes_are_refused_with_the_software_to_pass(tmp_path):
    source, _ = run(tmp_path, program="unknown", mntsta=[0, 4, 6, 0])
    with pytest.raises(ValueError, match=r"antenna 3 \(YEBES40M\): MNTSTA 6 cannot be read: "
                                         r"written by an unrecognised program.*software="):
        fitsidi_antennas(source)
    with pytest.raises(ValueError, match=r"MNTSTA 6 cannot be read"):
        correct_fitsidi(source, tmp_path / "out.idifits")
    assert fitsidi_antennas(source, software="fits-idi:difx")[3].mount == XYMount("north")


@pytest.mark.parametrize("edit, error, match", [
    (_remove("ARRAY_GEOMETRY"), FITSFormatError,
     "table ARRAY_GEOMETRY: expected the ARRAY_GEOMETRY table"),
    (_drop_column("ARRAY_GEOMETRY", "MNTSTA"), FITSFormatError, "column MNTSTA"),
    (_drop_column("ARRAY_GEOMETRY", "STABXYZ"), FITSFormatError, "column STABXYZ"),
    (_drop_column("ANTENNA", "POLAA"), FITSFormatError, "column POLAA"),
    (_set("ARRAY_GEOMETRY", ARRAYX=None), FITSFormatError, "column ARRAYX: expected the "
     "keyword ARRAYX"),
    (_set("ARRAY_GEOMETRY", ARRAYX=1000.0), FITSFormatError, "ARRAYX = ARRAYY = ARRAYZ = 0"),
    (_set("ARRAY_GEOMETRY", FRAME="MCMF"), FITSFormatError, "column FRAME.*'MCMF'"),
    (_set("ARRAY_GEOMETRY", XYZHAND="UP"), FITSFormatError, "XYZHAND 'RIGHT' or 'LEFT'"),
    (_set_data("ARRAY_GEOMETRY", "STABXYZ", [np.nan, 0, 0]), FITSFormatError,
     r"finite positions \(antenna 1, FD-VLBA\)"),
    (_set_data("ARRAY_GEOMETRY", "STABXYZ", [1.0, 2.0, 3.0]), ValueError,
     r"antenna 1 \(FD-VLBA\):.*"),
    (_set_data("ARRAY_GEOMETRY", "NOSTA", 2), FITSFormatError, "one row per antenna number"),
    (_set_data("ARRAY_GEOMETRY", "MNTSTA", 2), ValueError,
     r"antenna 1 \(FD-VLBA\): 2 \(fits-idi:difx\) has no feed-rotation model"),
    (_set_data("ANTENNA", "POLAA", [1.0, 2.0]), ValueError,
     "antenna 1 has receptor angles .* differ between bands"),
    (_set_data("ANTENNA", "POLAA", [np.nan, np.nan]), FITSFormatError,
     "finite receptor angles"),
    (_set_data("ANTENNA", "POLTYA", "Q"), ValueError, r"antenna 1: receptor types"),
])
def test_antenna_errors(tmp_path, edit, error, match):
    source, _ = run(tmp_path)
    bad = rewrite(source, tmp_path / "bad.idifits", edit)
    with pytest.raises(error, match=match):
        fitsidi_antennas(bad)


def test_receptors_varying_between_rows_are_refused(tmp_path):
    source, _ = run(tmp_path)

    def edit(hdul):
        hdu = hdul["ANTENNA"]
        rows = np.concatenate([hdu.data, hdu.data[:1]])
        new = fits.BinTableHDU(data=rows, header=hdu.header, name="ANTENNA")
        new.data["POLAA"][-1] = [10.0, 10.0]
        new.data["FREQID"][-1] = 2
        hdul["ANTENNA"] = new
    bad = rewrite(source, tmp_path / "bad.idifits", edit)
    with pytest.raises(ValueError, match="antenna 1 has receptors .* in one row and .* in "
                                         "another"):
        fitsidi_antennas(bad)


def test_left_handed_xyz_and_errors_are_file_format_errors(tmp_path):
    source, _ = run(tmp_path)

    # XYZHAND = 'LEFT': casacore negates y (MSFitsInput.cc).
    def edit(hdul):
        hdul["ARRAY_GEOMETRY"].header["XYZHAND"] = "LEFT"
        hdul["ARRAY_GEOMETRY"].data["STABXYZ"][:, 1] *= -1
    flipped = rewrite(source, tmp_path / "left.idifits", edit)
    a, b = fitsidi_antennas(source), fitsidi_antennas(flipped)
    for k in a:
        np.testing.assert_allclose(a[k].location.get_itrs().cartesian.xyz.to_value(u.m),
                                   b[k].location.get_itrs().cartesian.xyz.to_value(u.m))
    assert issubclass(FITSFormatError, FileFormatError)


def test_not_a_fits_file(tmp_path):
    path = tmp_path / "text.idifits"
    path.write_text("SIMPLE but not FITS\n")
    with pytest.raises(FITSFormatError, match="expected a FITS file"):
        fitsidi_antennas(path)
    with pytest.raises(FileNotFoundError, match="no such file"):
        writing_program(tmp_path / "missing.fits")


def test_stations_used_by_the_writer_are_in_the_catalogue():
    assert [name for name, _, _ in STATIONS] == ["FD-VLBA", "EFLSBERG", "YEBES40M", "WETTZ13S"]


def test_receptors_from_the_catalogue_where_the_antenna_table_has_none(tmp_path):
    # Antenna 1 (FD-VLBA) loses its ANTENNA rows: the station catalogue gives
    # it R and L at 0 deg (VLBA Observational Status Summary), the receptors of
    # the writer's model, and says so once; with catalogue=False it has none.
    source, info = run(tmp_path)

    def edit(hdul):
        table = hdul["ANTENNA"]
        keep = table.data["ANTENNA_NO"] != 1
        hdul["ANTENNA"] = fits.BinTableHDU(table.data[keep], header=table.header,
                                           name="ANTENNA")

    bad = rewrite(source, tmp_path / "nofeed.idifits", edit)
    with pytest.raises(ValueError, match=r"antenna 1 \(FD-VLBA\) has no receptors: .*--feeds "
                                         r"R,L on the command line\)$"):
        correct_fitsidi(bad, tmp_path / "out.idifits", catalogue=False)
    with pytest.warns(CatalogueReceptorsWarning, match=r"^receptors from the station catalogue "
                      r"for antennas the file gives none: 1 \(FD-VLBA as FD-VLBA\): R:0,L:0 "
                      r"\(VLBA Observational Status Summary"):
        correct_fitsidi(bad, tmp_path / "out.idifits")
    got = corrected_products(tmp_path / "out.idifits", info)
    np.testing.assert_allclose(got, np.broadcast_to(info["expected"][:, None, None, :],
                                                    got.shape), atol=2e-6)


def test_feeds_given_where_the_antenna_table_has_none(tmp_path):
    # Antenna 2 (EFLSBERG) loses its ANTENNA rows, as a file without receptors
    # (the ATCA Miriad case): refused, naming --feeds; given, the result is the
    # writer's model (its receptors are R and L at 0 deg).
    source, info = run(tmp_path, angles=CIRCULAR_ANGLES)

    def edit(hdul):
        table = hdul["ANTENNA"]
        keep = table.data["ANTENNA_NO"] != 2
        hdul["ANTENNA"] = fits.BinTableHDU(table.data[keep], header=table.header,
                                           name="ANTENNA")

    bad = rewrite(source, tmp_path / "nofeed.idifits", edit)
    with pytest.raises(ValueError, match=r"antenna 2 \(EFLSBERG\) has no receptors: the "
                                         r"ANTENNA table has no row for it; give the feeds .*"
                                         r"--feeds R,L"):
        correct_fitsidi(bad, tmp_path / "out.idifits")
    assert not (tmp_path / "out.idifits").exists()
    correct_fitsidi(bad, tmp_path / "out.idifits",
                    feeds={"EFLSBERG": Receptors("RL", [0, 0] * u.deg)})
    got = corrected_products(tmp_path / "out.idifits", info)
    np.testing.assert_allclose(got, np.broadcast_to(info["expected"][:, None, None, :],
                                                    got.shape), atol=2e-6)


def test_the_calling_thread_keeps_no_chunk_after_a_run(tmp_path):
    # The chunks are read into a buffer the thread keeps between chunks
    # (kept.thread_buffer); after the run the calling thread lets it go, as
    # correct_ms does, so that no chunk-sized buffer stays alive.
    from astropy_feedrot.core import cache as kept

    source, _ = run(tmp_path)
    kept.thread_buffer(np.uint8, (16,))  # a buffer from before the run
    correct_fitsidi(source, tmp_path / "out.idifits")
    assert getattr(kept._BUFFERS, "bytes", None) is None
