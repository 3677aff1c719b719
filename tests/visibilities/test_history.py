# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Never correct twice: the records of AIPS and CASA read beside the package's own mark.

The AIPS records are those of a real file, pyuvdata's ``mojave.uvfits``
(tests/data/uvdata/README.md): its HISTORY cards record ``CLCOR OPCODE =
'PANG'`` with ``CLPARM(1) = 1`` ("Parallactic angle correction APPLIED") on
CL table 4, from which CL table 6 descends, and then ``SPLIT GAINUSE = 6``:
the visibilities carry AIPS's correction. The CASA records are the rows CASA
6.7's ``applycal`` writes into a Measurement Set's HISTORY (``ORIGIN`` the
task, ``MESSAGE`` ``taskname=applycal`` and one ``name = value`` row per
parameter), as tests/visibilities/test_casa_history.py makes them with CASA itself.
"""

import warnings
from pathlib import Path

import numpy as np
import pytest
from astropy.io import fits

from astropy_feedrot.cli import main
from astropy_feedrot.visibilities import CorrectionRefused, correct_file, correct_fitsidi
from astropy_feedrot.visibilities.history import (
    aips_records,
    check_history,
    compose,
    ms_column_history,
)

DATA = Path(__file__).parent.parent / "data" / "uvdata"
MOJAVE = DATA / "mojave.uvfits"

PANG = ("CLCOR   OPCODE = 'PANG' / Operation code",
        "CLCOR   CLPARM(1)=  1. / Parallactic angle correction APPLIED")
UNPANG = ("CLCOR   OPCODE = 'PANG' / Operation code",
          "CLCOR   CLPARM(1)= -1. / Parallactic angle correction REMOVED")


def mojave_history():
    with fits.open(MOJAVE) as hdul:
        return [str(card) for card in hdul[0].header["HISTORY"]]


# --- AIPS -----------------------------------------------------------------------------------


def test_mojave_history_records_aips_pang_then_split():
    cards = mojave_history()
    records = aips_records("\n".join(cards))
    # One PANG record, in the cards as AIPS wrote them.
    assert len(records) == 1
    at, direction, record = records[0]
    assert direction == "remove"
    assert record == ("AIPS CLCOR OPCODE = 'PANG', CLPARM(1) = 1. (Parallactic angle "
                      "correction APPLIED), applied to the visibilities by SPLIT GAINUSE = 6")
    split = cards.index("SPLIT GAINUSE =  6 / CL table")
    assert cards.index(PANG[0]) < cards.index(PANG[1]) < split
    # The cards run together (no line ends) give the same record's direction.
    assert [d for _, d, _ in aips_records("".join(cards))] == ["remove"]


def test_aips_records_of_every_kind():
    assert aips_records("FITLD OUTNAME='X'\nAPCAL OPCODE= CALI") == []
    # A PANG correction taken out again (CLPARM(1) < 0): the last record says undone.
    records = aips_records("\n".join(PANG + UNPANG))
    assert [d for _, d, _ in records] == ["remove", "apply"]
    assert "REMOVED" in records[1][2]
    # In a CL table only, not yet applied to the visibilities: no SPLIT named.
    assert aips_records("\n".join(PANG))[0][2].endswith("(Parallactic angle correction "
                                                        "APPLIED)")
    assert [r for _, _, r in aips_records("VLBAPANG / parallactic angle")] == ["AIPS VLBAPANG"]
    # SPLIT with GAINUSE = 0 (no calibration applied) is not named.
    assert "SPLIT" not in aips_records("\n".join(PANG + ("SPLIT GAINUSE =  0 / CL",)))[0][2]


@pytest.mark.parametrize("cards, refused", [
    (PANG, True),
    (PANG + UNPANG, False),
    (("VLBAPANG",), True),
    (PANG + ("Feed rotation applied by astropy_feedrot 0.2: UV_DATA",), False),
    (("Feed rotation applied by astropy_feedrot 0.2: UV_DATA",) + PANG, True),
])
def test_check_history_takes_the_last_record(cards, refused):
    text = "\n".join(cards)
    if refused:
        with pytest.raises(CorrectionRefused, match=r"^x: the feed rotation was removed "
                           r"already \(the history records AIPS .*\); correcting again would "
                           r"remove it twice: pass redo=True to correct all the same$"):
            check_history(text, "remove", "x")
    else:
        check_history(text, "remove", "x")
    check_history(text, "remove", "x", redo=True)
    check_history(text, "apply", "x") if refused else None


def test_compose():
    assert [compose(s, d) for s in (None, "remove", "apply") for d in ("remove", "apply")] == \
        ["remove", "apply", "remove", None, None, "apply"]


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:The telescope frame is set to")
def test_mojave_is_refused_unless_redo(tmp_path):
    out = tmp_path / "mojave_corrected.uvh5"  # (UVFITS output of AIPS files: another fix)
    with pytest.raises(CorrectionRefused, match=r"mojave.uvfits.*: the feed rotation was "
                       r"removed already \(the history records AIPS CLCOR OPCODE = 'PANG', "
                       r"CLPARM\(1\) = 1\. \(Parallactic angle correction APPLIED\), applied "
                       r"to the visibilities by SPLIT GAINUSE = 6\); correcting again would "
                       r"remove it twice: pass redo=True to correct all the same$"):
        correct_file(MOJAVE, out)
    assert not out.exists() and list(tmp_path.iterdir()) == []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's, on writing this AIPS file
        assert correct_file(MOJAVE, out, redo=True) == out


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:The telescope frame is set to")
def test_mojave_refused_on_the_command_line(tmp_path, capsys):
    out = tmp_path / "out.uvh5"
    assert main(["correct", str(MOJAVE), "-o", str(out), "--quiet"]) == 1
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.startswith("feedrot: error")]
    assert len(lines) == 1, err
    assert "CLCOR OPCODE = 'PANG'" in lines[0] and lines[0].endswith(
        "pass --redo to correct all the same")
    assert "redo=True" not in err
    assert not out.exists()
    assert main(["correct", str(MOJAVE), "-o", str(out), "--quiet", "--redo"]) == 0
    assert out.exists()


# fitsidi_writer gives WETTZ13S a Nasmyth focus the catalogue does not (on purpose).
@pytest.mark.filterwarnings("ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")
def test_fitsidi_with_aips_history(tmp_path):
    from fitsidi_writer import write_fitsidi

    source = tmp_path / "aips.idifits"
    write_fitsidi(source)
    with fits.open(source, mode="update") as hdul:
        for card in PANG + ("SPLIT GAINUSE =  2 / CL table",):
            hdul[0].header.add_history(card)
    with pytest.raises(CorrectionRefused, match=r"HISTORY of the primary header\): the feed "
                       r"rotation was removed already \(the history records AIPS CLCOR "
                       r"OPCODE = 'PANG', .* applied to the visibilities by SPLIT GAINUSE = 2"):
        correct_fitsidi(source, tmp_path / "out.idifits")
    assert not (tmp_path / "out.idifits").exists()
    correct_fitsidi(source, tmp_path / "out.idifits", redo=True)
    # Taken out again by AIPS: corrected without redo.
    with fits.open(source, mode="update") as hdul:
        for card in UNPANG:
            hdul[0].header.add_history(card)
    correct_fitsidi(source, tmp_path / "again.idifits")


# --- CASA (HISTORY rows of a Measurement Set) ------------------------------------------------


def applycal_rows(parang):
    names = [("vis", '"x.ms"'), ("gaintable", "[]"), ("parang", str(parang)),
             ("applymode", '"calflag"')]
    return ([("applycal", "ms", "taskname=applycal"),
             ("applycal", "ms", "version: 6.7.0-31 CASAtools:v1.0.0")] +
            [("applycal", "ms", f"{name:<12}= {value}") for name, value in names])


def test_casa_applycal_rows():
    records = ms_column_history(applycal_rows(True))
    assert records["CORRECTED_DATA"].state == "remove"
    assert records["CORRECTED_DATA"].writer == "CASA applycal"
    assert records["CORRECTED_DATA"].record == "CASA applycal(parang=True)"
    assert "DATA" not in records
    records = ms_column_history(applycal_rows(False))
    assert records["CORRECTED_DATA"].state is None
    assert records["CORRECTED_DATA"].writer == "CASA applycal"
    # split(datacolumn="corrected") makes CORRECTED_DATA the DATA of a new set.
    split = [("split", "ms", "taskname=split"), ("split", "ms", 'datacolumn  = "corrected"')]
    records = ms_column_history(applycal_rows(True) + split)
    assert records["DATA"].state == "remove" and "CORRECTED_DATA" not in records
    assert records["DATA"].record == ("CASA applycal(parang=True), then CASA split"
                                      "(datacolumn='corrected')")
    records = ms_column_history(applycal_rows(True) + split[:1] +
                                [("split", "ms", 'datacolumn  = "data"')])
    assert records["DATA"].state is None


def test_package_rows_in_a_measurement_set():
    mark = ("Feed rotation removed by astropy_feedrot 0.2: DATA -> CORRECTED_DATA, receptors "
            "fixed on the sky (frame=apparent, vertical=geodetic)")
    rows = [("astropy_feedrot.visibilities.correct_ms", "astropy_feedrot", mark)]
    record = ms_column_history(rows)["CORRECTED_DATA"]
    assert (record.state, record.writer, record.source, record.direction) == \
        ("remove", "astropy_feedrot", "DATA", "remove")
    # CASA's applycal afterwards: CASA wrote the column last.
    record = ms_column_history(rows + applycal_rows(False))["CORRECTED_DATA"]
    assert record.writer == "CASA applycal" and record.state is None
    # The mark written by pyuvdata into a set it wrote: DATA holds the correction.
    rows = [("pyuvdata", "pyuvdata", "Read/written with pyuvdata. " + mark)]
    assert ms_column_history(rows)["DATA"].state == "remove"
    assert np.all([r.writer is None for r in ms_column_history(rows).values()])


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:The telescope frame is set to")
def test_mojave_record_is_true_a_second_correction_spreads_the_phases():
    # The reason for the refusal, measured on the file itself: AIPS's calibration left
    # the parallel hands of this compact source in phase (|sum V| / sum |V| over the
    # unflagged cross-correlations: 0.990 for RR and LL); removing the parallactic angle
    # again turns RR and LL by the difference of the two antennas' angles, which spreads
    # them (0.864 and 0.876).
    from astropy_feedrot.visibilities import correct_uvdata, read_uvdata

    uv = read_uvdata(MOJAVE)

    def coherence(data, product):
        k = list(data.polarization_array).index(product)
        cross = data.ant_1_array != data.ant_2_array
        values = data.data_array[cross, :, k][~data.flag_array[cross, :, k]]
        return abs(values.sum()) / abs(values).sum()

    twice = correct_uvdata(uv, redo=True)
    for product in (-1, -2):  # RR, LL
        assert coherence(uv, product) > 0.985
        assert coherence(twice, product) < 0.88
