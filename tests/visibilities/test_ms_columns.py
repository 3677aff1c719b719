# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Never overwrite what is not ours: the columns correct_ms reads and writes, and
Measurement Sets corrected into a casacore copy (-o OUTPUT.ms).

The set is the VLA's (CASA's importuvfits), its data a polarized point source
from the voltage-level model of ``ms_model``; the sky model put into
MODEL_DATA, and the CASA HISTORY rows of an ``applycal(parang=True)``, are
made here as CASA would leave them (tests/visibilities/test_casa_history.py makes them
with CASA itself).
"""

import hashlib
import tarfile
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("casacore")

from casacore.tables import makecoldesc, maketabdesc, table  # noqa: E402
from ms_model import fill_model, unpack  # noqa: E402

from astropy_feedrot.cli import main  # noqa: E402
from astropy_feedrot.visibilities import CorrectionRefused, correct_file, correct_ms  # noqa: E402
from astropy_feedrot.visibilities.ms_tables import copy_ms  # noqa: E402


def digests(ms):
    return {str(p.relative_to(ms)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(ms.rglob("*")) if p.is_file() and p.name != "table.lock"}


def column(ms, name):
    with table(str(ms), ack=False) as t:
        return t.getcol(name)


def add_column(ms, name, values=None, like="DATA", comment=None):
    """A column as CASA adds one (the description of ``like``), filled with ``values``."""
    with table(str(ms), readonly=False, ack=False) as t:
        description = t.getcoldesc(like)
        description.pop("keywords", None)
        if comment is not None:
            description["comment"] = comment
        t.addcols(maketabdesc(makecoldesc(name, description)),
                  {"TYPE": "TiledShapeStMan", "NAME": f"Tiled{name}", "SPEC": {}})
        if values is not None:
            t.putcol(name, values)


def add_casa_history(ms, parang=True):
    """The HISTORY rows CASA 6.7's applycal writes (ORIGIN the task, one parameter a row)."""
    rows = ["taskname=applycal", "version: 6.7.0-31 CASAtools:v1.0.0", f'vis         = "{ms}"',
            "gaintable   = []", f"parang      = {parang}", 'applymode   = "calflag"']
    with table(str(ms / "HISTORY"), readonly=False, ack=False) as history:
        start = history.nrows()
        history.addrows(len(rows))
        for k, message in enumerate(rows):
            history.putcell("MESSAGE", start + k, message)
            history.putcell("ORIGIN", start + k, "applycal")
            history.putcell("APPLICATION", start + k, "ms")
            history.putcell("PRIORITY", start + k, "NORMAL")


@pytest.fixture
def vla(tmp_path):
    ms = unpack(tmp_path)
    return ms, fill_model(ms)


def unchanged(ms, call, match, error=CorrectionRefused):
    """``call`` refused with one line matching ``match``; nothing written."""
    before = digests(ms)
    with pytest.raises(error, match=match) as info:
        call()
    assert "\n" not in str(info.value)
    assert digests(ms) == before
    return info.value


# --- columns that are not ours -------------------------------------------------------------


def test_model_data_not_written_by_us_needs_overwrite_column(vla, tmp_path):
    ms, _ = vla
    model = column(ms, "DATA") * np.complex64(0.5 + 0.25j)  # a sky model, not the data
    add_column(ms, "MODEL_DATA", model, comment="The model data column")
    error = unchanged(ms, lambda: correct_ms(ms, corrected_column="MODEL_DATA"),
                      r"column 'MODEL_DATA' exists and was not written by astropy_feedrot "
                      r"\(its description: 'The model data column'\); writing DATA corrected "
                      r"into it would replace its values: pass overwrite_column=True to "
                      r"replace them, or write another column \(corrected_column=\)$")
    assert error.command_line().endswith("pass --overwrite-column to replace them, or write "
                                         "another column (--column)")
    np.testing.assert_array_equal(column(ms, "MODEL_DATA"), model)
    # Asked for: the same values as the correction into a new column, bit for bit.
    twin = unpack(tmp_path / "twin")
    fill_model(twin)
    correct_ms(twin)
    correct_ms(ms, corrected_column="MODEL_DATA", overwrite_column=True)
    np.testing.assert_array_equal(column(ms, "MODEL_DATA"), column(twin, "CORRECTED_DATA"))


def test_casa_corrected_data_is_neither_overwritten_nor_corrected_again(vla):
    ms, model = vla
    # CASA's applycal(parang=True) filled CORRECTED_DATA (here: our own reference
    # correction, written as CASA would, under CASA's name).
    twin = ms.parent / "twin"
    twin.mkdir()
    reference = unpack(twin)
    fill_model(reference)
    correct_ms(reference)
    add_column(ms, "CORRECTED_DATA", column(reference, "CORRECTED_DATA"),
               comment="The corrected data column")
    add_casa_history(ms, parang=True)
    unchanged(ms, lambda: correct_ms(ms),
              r"column 'CORRECTED_DATA' exists and was written by CASA applycal \(CASA "
              r"applycal\(parang=True\)\); writing DATA corrected into it would replace its "
              r"values: pass overwrite_column=True")
    unchanged(ms, lambda: correct_ms(ms, data_column="CORRECTED_DATA",
                                     corrected_column="OURS"),
              r"\(HISTORY of CORRECTED_DATA\): the feed rotation was removed already \(the "
              r"history records CASA applycal\(parang=True\)\); correcting again would remove "
              r"it twice: pass redo=True to correct all the same$")
    # Applying it (undoing CASA's) is allowed, and gives DATA back (apply inverts remove).
    correct_ms(ms, data_column="CORRECTED_DATA", corrected_column="UNDONE", direction="apply")
    np.testing.assert_allclose(column(ms, "UNDONE"), column(ms, "DATA"), rtol=0, atol=1e-6)


def test_apply_on_model_data_reads_model_data(vla, tmp_path, capsys):
    ms, _ = vla
    data = column(ms, "DATA")
    model = data * np.complex64(0.5 - 0.5j)  # a sky model unlike DATA
    add_column(ms, "MODEL_DATA", model, comment="The model data column")
    before = {name: column(ms, name) for name in ("DATA", "UVW", "FLAG")}
    assert main(["correct", str(ms), "--in-place", "--column", "MODEL_DATA", "--apply",
                 "--quiet"]) == 0
    for name, values in before.items():
        np.testing.assert_array_equal(column(ms, name), values)
    # The model, turned: removing the rotation again gives the model back (identity:
    # remove inverts apply); had DATA been read, it would give DATA.
    correct_ms(ms, data_column="MODEL_DATA", corrected_column="BACK")
    np.testing.assert_allclose(column(ms, "BACK"), model, rtol=0, atol=1e-6)
    assert np.abs(column(ms, "MODEL_DATA") - model).max() > 0.01
    # --data-column says otherwise: DATA into the (foreign) MODEL_DATA needs the option.
    assert main(["correct", str(ms), "--in-place", "--column", "MODEL_DATA", "--apply",
                 "--data-column", "DATA", "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "add --overwrite-column" not in err
    assert "pass --overwrite-column to replace them, or write another column (--column)" in err


@pytest.mark.parametrize("name, match", [
    ("UVW", r"column 'UVW' is not a visibility column like 'DATA' \(double with cells of "
            r"shape \(3,\) against \(64, 4\), not complex\); nothing was written: choose "
            r"another corrected_column= \(CORRECTED_DATA, or a new name\)$"),
    ("FLAG", r"column 'FLAG' is not a visibility column like 'DATA' \(boolean, not complex\)"),
    ("bad name;drop", r"'bad name;drop' is not a column name \(letters, digits and _, not "
                      r"starting with a digit\); choose another corrected_column=$"),
    ("1ST", r"'1ST' is not a column name"),
])
def test_columns_that_are_not_visibility_columns(vla, name, match):
    ms, _ = vla
    unchanged(ms, lambda: correct_ms(ms, corrected_column=name), match)
    with table(str(ms), ack=False) as t:
        assert name == "UVW" or name == "FLAG" or name not in t.colnames()
        assert "FEEDROT_PARTIAL" not in t.getcolkeywords("UVW")


def test_column_of_another_shape(vla):
    ms, _ = vla
    with table(str(ms), readonly=False, ack=False) as t:
        description = t.getcoldesc("DATA")
        description.pop("keywords", None)
        description["shape"] = np.array([1, 4])
        description["option"] = 4  # fixed shape
        t.addcols(maketabdesc(makecoldesc("NARROW", description)))
    unchanged(ms, lambda: correct_ms(ms, corrected_column="NARROW", overwrite_column=True),
              r"'NARROW' is not a visibility column like 'DATA' \(complex with cells of shape "
              r"\(1, 4\) against \(64, 4\), not complex\)")


def test_bad_columns_on_the_command_line(vla, capsys):
    ms, _ = vla
    before = digests(ms)
    for argv, message in (
            (["--column", "UVW"], "choose another --column (CORRECTED_DATA, or a new name)"),
            (["--column", "bad name;drop"], "'bad name;drop' is not a column name"),
            (["--data-column", "FLAG"], "column 'FLAG' holds boolean values, not complex "
                                        "visibilities (its visibility columns: ['DATA']); "
                                        "choose one with --data-column")):
        assert main(["correct", str(ms), "--in-place", "--quiet", *argv]) == 1
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and message in err, err
        assert "interrupted" not in err and "=" not in err.split("column", 1)[0]
    assert digests(ms) == before
    assert main(["correct", str(ms), "-o", str(ms.parent / "x.uvfits"), "--column", "X"]) == 1
    assert "--column is for a Measurement Set" in capsys.readouterr().err


def test_own_column_written_again(vla):
    # A column this package made is ours: written again without the option (from
    # another column), and its rerun from the same column refused as a recomputation.
    ms, _ = vla
    correct_ms(ms, corrected_column="OURS")
    with table(str(ms), ack=False) as t:
        assert "written by astropy_feedrot" in t.getcoldesc("OURS")["comment"]
    unchanged(ms, lambda: correct_ms(ms, corrected_column="OURS"),
              r"OURS holds DATA with the feed rotation removed already .*only compute it anew")
    correct_ms(ms, corrected_column="OURS", redo=True)
    correct_ms(ms, data_column="OURS", corrected_column="BACK", direction="apply")
    correct_ms(ms, corrected_column="BACK")  # BACK (ours) held OURS applied: now DATA removed
    np.testing.assert_array_equal(column(ms, "BACK"), column(ms, "OURS"))


# --- into a copy -----------------------------------------------------------------------------


def test_copy_then_corrected_equals_in_place(vla, tmp_path):
    ms, _ = vla
    twin = unpack(tmp_path / "twin")
    fill_model(twin)
    before = digests(ms)
    out = tmp_path / "copy.ms"
    assert correct_file(ms, out, vertical="geocentric") == out
    assert digests(ms) == before  # the input untouched
    correct_ms(twin, vertical="geocentric")
    with table(str(ms), ack=False) as source, table(str(out), ack=False) as copy, \
            table(str(twin), ack=False) as in_place:
        assert sorted(copy.colnames()) == sorted(source.colnames() + ["CORRECTED_DATA"])
        # Bit for bit the in-place result; every other column byte for byte the input's.
        assert copy.getcol("CORRECTED_DATA").tobytes() == \
            in_place.getcol("CORRECTED_DATA").tobytes()
        for name in source.colnames():
            if name != "FLAG_CATEGORY":
                assert copy.getcol(name).tobytes() == source.getcol(name).tobytes(), name
    for sub in ("ANTENNA", "FEED", "FIELD", "SPECTRAL_WINDOW", "POLARIZATION"):
        with table(str(ms / sub), ack=False) as a, table(str(out / sub), ack=False) as b:
            for name in a.colnames():
                if a.iscelldefined(name, 0):
                    assert np.array_equal(a.getcol(name), b.getcol(name)), (sub, name)
    # Refusals name the input, not the copy being corrected; nothing is left behind.
    add_column(ms, "MODEL_DATA", column(ms, "DATA"))
    with pytest.raises(CorrectionRefused, match=rf"^'{ms}': column 'MODEL_DATA' exists"):
        correct_file(ms, tmp_path / "model.ms", corrected_column="MODEL_DATA")
    assert not (tmp_path / "model.ms").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["copy.ms", "day2_TDEM0003_10s_"
                                                          "norx_1src_1spw_2ints.ms", "twin"]


def test_copy_on_the_command_line(vla, tmp_path, capsys):
    ms, _ = vla
    out = tmp_path / "out.ms"
    assert main(["correct", str(ms), "-o", str(out), "--quiet"]) == 0
    assert main(["correct", str(out), "-o", str(tmp_path / "again.ms"), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"'{out}': CORRECTED_DATA holds DATA" in err
    assert err.endswith("pass --redo to do so\n")
    assert main(["correct", str(out), "-o", str(tmp_path / "model.ms"), "--column", "MODEL",
                 "--quiet"]) == 0
    assert "MODEL" in table(str(tmp_path / "model.ms"), ack=False).colnames()


def test_copy_ms_is_casacores(vla, tmp_path):
    ms, _ = vla
    with table(str(ms), ack=False) as t, t.selectrows([0, 1, 2]) as selection:
        selection.copy(str(tmp_path / "three.ms"), deep=True).close()
    copy = copy_ms(tmp_path / "three.ms", tmp_path / "again.ms")
    with table(str(copy), ack=False) as t:
        assert t.nrows() == 3
    with pytest.raises(ValueError, match="a directory but not a Measurement Set"):
        correct_ms(tmp_path)


# --- a CASA-made set with two spectral windows (tests/data/real/README.md) -------------------

REAL = Path(__file__).parent.parent / "data" / "real"


def casa_two_windows(where):
    with tarfile.open(REAL / "casa_sim_vla_2spw.ms.tar.gz") as archive:
        archive.extractall(where, filter="data")
    return Path(where) / "casa_sim_vla_2spw.ms"


def by_window(ms, name):
    """``name`` per data description (the windows have 2 and 3 channels)."""
    with table(str(ms), ack=False) as t:
        return [t.query(f"DATA_DESC_ID=={dd}").getcol(name) for dd in (0, 1)]


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_two_windows_copied_and_corrected(tmp_path, capsys):
    source = casa_two_windows(tmp_path / "in")
    twin = casa_two_windows(tmp_path / "twin")
    before = digests(source)
    with table(str(source), ack=False) as t:
        columns = [c for c in t.colnames() if c != "FLAG_CATEGORY"]
        assert {"DATA", "MODEL_DATA", "CORRECTED_DATA"} <= set(columns)
        assert len(set(t.getcolshapestring("DATA"))) == 2  # [2, 4] and [3, 4]
    # pyuvdata cannot read this set (one time, two scans): what -o used before.
    pyuvdata = pytest.importorskip("pyuvdata")
    with pytest.raises(ValueError, match="SCAN_NUMBER appears to vary"):
        pyuvdata.UVData.from_file(str(source))
    out = tmp_path / "out.ms"
    # CASA's simulator left CORRECTED_DATA (a copy of DATA): replaced only when asked.
    assert main(["correct", str(source), "-o", str(out), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "pass --overwrite-column" in err and str(source) in err
    assert not out.exists()
    assert main(["correct", str(source), "-o", str(out), "--quiet", "--overwrite-column"]) == 0
    assert digests(source) == before
    assert main(["correct", str(twin), "--in-place", "--quiet", "--overwrite-column"]) == 0
    for name in columns:
        expected = by_window(twin if name == "CORRECTED_DATA" else source, name)
        for got, want in zip(by_window(out, name), expected):
            assert got.tobytes() == want.tobytes(), name
    # The correction did something: CORRECTED_DATA is no longer DATA.
    assert all(np.abs(c - d).max() > 0.01 for c, d in zip(by_window(out, "CORRECTED_DATA"),
                                                          by_window(out, "DATA")))


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
def test_data_split_from_casa_corrected_data_refused_into_any_format(vla, tmp_path):
    # split(datacolumn="corrected") after applycal(parang=True): DATA holds CASA's
    # correction, for the copy (.ms) and for pyuvdata's formats alike.
    ms, _ = vla
    add_casa_history(ms, parang=True)
    with table(str(ms / "HISTORY"), readonly=False, ack=False) as history:
        start = history.nrows()
        history.addrows(2)
        for k, message in enumerate(["taskname=split", 'datacolumn  = "corrected"']):
            history.putcell("MESSAGE", start + k, message)
            history.putcell("ORIGIN", start + k, "split")
    for name in ("out.ms", "out.uvh5"):
        with pytest.raises(CorrectionRefused, match=r"\(HISTORY of DATA\): the feed rotation "
                           r"was removed already \(the history records CASA applycal\(parang="
                           r"True\), then CASA split\(datacolumn='corrected'\)\)"):
            correct_file(ms, tmp_path / name)
        assert not (tmp_path / name).exists()
    pytest.importorskip("pyuvdata")
    correct_file(ms, tmp_path / "out.uvh5", redo=True)


def test_aips_history_imported_into_a_measurement_set(vla):
    # importuvfits of an AIPS file that SPLIT after CLCOR PANG: the cards in HISTORY.
    ms, _ = vla
    cards = ["CLCOR   OPCODE = 'PANG' / Operation code",
             "CLCOR   CLPARM(1)=  1. / Parallactic angle correction APPLIED",
             "SPLIT GAINUSE =  6 / CL table"]
    with table(str(ms / "HISTORY"), readonly=False, ack=False) as history:
        start = history.nrows()
        history.addrows(len(cards))
        for k, message in enumerate(cards):
            history.putcell("MESSAGE", start + k, message)
            history.putcell("ORIGIN", start + k, "importuvfits")
    unchanged(ms, lambda: correct_ms(ms), r"\(HISTORY of DATA\): the feed rotation was "
              r"removed already \(the history records AIPS CLCOR OPCODE = 'PANG'")
    correct_ms(ms, direction="apply", data_column="DATA")  # undoing AIPS's is allowed
