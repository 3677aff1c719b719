# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The one Correction: its options checked once, the adapters found by kind, and every
format's function a short call of it (the same result given a Correction or its
options)."""
import filecmp
import shutil

import numpy as np
import pytest
from astropy.coordinates import ICRS

from astropy_feedrot.data import sample_file
from astropy_feedrot.visibilities import (
    Correction,
    correct_file,
    correct_fitsidi,
    correct_ms,
)
from astropy_feedrot.visibilities.correction import OPTIONS, adapter_of, refuse_column_options

IDI = sample_file("difx_k08161.idifits")


@pytest.mark.parametrize("options, error, match", [
    (dict(vertical="up"), ValueError, "vertical must be one of"),
    (dict(pole="north"), ValueError, "pole must be one of"),
    (dict(direction="sideways"), ValueError, "direction"),
    (dict(mounts="both"), ValueError, "mounts"),
    (dict(convention="aips"), ValueError, "convention"),
    (dict(ionosphere=3.0), TypeError, "Ionosphere"),
])
def test_options_refused_when_made(options, error, match):
    with pytest.raises(error, match=match):
        Correction(**options)


def test_the_options_once():
    casa = Correction(convention="casa", pole="itrs")
    assert (casa.vertical, casa.pole) == ("geocentric", "itrs")  # pole given: it wins
    assert Correction.of(casa) is casa
    assert Correction.of(direction="apply").direction == "apply"
    with pytest.raises(TypeError, match=r"give the options \['frame'\] to the Correction"):
        Correction.of(casa, frame="icrs")
    with pytest.raises(TypeError, match="correction must be a Correction, got dict"):
        Correction.of({"frame": "icrs"})
    assert Correction(frame=ICRS()).frame_name == "icrs"
    assert set(OPTIONS) == set(Correction.__init__.__code__.co_varnames[1:len(OPTIONS) + 1])
    assert "frame='apparent'" in repr(Correction())


def test_adapters_by_kind():
    assert adapter_of("fits-idi").correct.__name__ == "correct_fitsidi_file"
    assert adapter_of("ms").correct.__name__ == "correct_ms_file"
    assert adapter_of("msv4").correct.__name__ == "correct_processing_set_file"
    for kind in ("uvfits", "uvh5", "miriad", "mir"):
        assert adapter_of(kind).correct.__name__ == "correct_uvdata_file"
    with pytest.raises(ValueError, match="no adapter corrects files of kind 'vex'"):
        adapter_of("vex")


def test_refusals_before_any_work(tmp_path):
    with pytest.raises(ValueError, match="corrected into a copy, never in place"):
        Correction().correct(IDI)
    with pytest.raises(TypeError, match="correct_file writes a copy: give its output"):
        correct_file(IDI, None)
    with pytest.raises(ValueError, match="FITS-IDI input is corrected into a FITS-IDI copy"):
        Correction().correct(IDI, tmp_path / "out.uvh5")
    with pytest.raises(ValueError, match="are for a Measurement Set written as a Measurement"):
        correct_file(IDI, tmp_path / "out.idifits", data_column="MODEL_DATA")
    with pytest.raises(ValueError, match="are for a Measurement Set"):
        refuse_column_options(overwrite_column=True)
    with pytest.raises(FileNotFoundError, match="does not exist"):
        Correction().correct(IDI, tmp_path / "nowhere" / "out.idifits")
    assert list(tmp_path.iterdir()) == []


def test_a_correction_or_its_options_give_the_same(tmp_path):
    """The same bytes from correct_fitsidi given the options, given a Correction, and
    from Correction.correct; the same column from correct_ms either way."""
    options = dict(direction="apply", frame="icrs", convention="casa")
    correction = Correction(**options)
    a = correct_fitsidi(IDI, tmp_path / "a.idifits", **options)
    b = correct_fitsidi(IDI, tmp_path / "b.idifits", correction=correction)
    c = correction.correct(IDI, tmp_path / "c.idifits")
    assert filecmp.cmp(a, b, shallow=False) and filecmp.cmp(a, c, shallow=False)
    tables = pytest.importorskip("casacore.tables")
    one = shutil.copytree(sample_file("vla_sim.ms"), tmp_path / "one.ms")
    two = shutil.copytree(sample_file("vla_sim.ms"), tmp_path / "two.ms")
    correct_ms(one, frame="icrs")
    Correction(frame="icrs").correct(two)
    with tables.table(str(one), ack=False) as t1, tables.table(str(two), ack=False) as t2:
        for row in range(t1.nrows()):
            assert np.array_equal(t1.getcell("CORRECTED_DATA", row),
                                  t2.getcell("CORRECTED_DATA", row))
