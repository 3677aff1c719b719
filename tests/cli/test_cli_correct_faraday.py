# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot correct --rm-table / --ionex``: the ionospheric Faraday rotation removed (and,
with --apply, applied) with the feed rotation, from the command line; its refusals.

The data: tests/faraday_model.py (a simulated VLA set whose EVPA runs as
chi0 + RM lambda^2 across 1-2 GHz).
"""

import subprocess
import sys

import numpy as np
import pytest
from astropy.time import Time

from astropy_feedrot.cli import main

casacore = pytest.importorskip("casacore")

from casacore.tables import table  # noqa: E402
from faraday_model import CHI0, evpa_circular, faraday_ms, rm_table_mjd  # noqa: E402

pytestmark = pytest.mark.filterwarnings(
    "ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")


def run(capsys, *argv):
    status = main([str(arg) for arg in argv])
    out, err = capsys.readouterr()
    return status, out, err


def write_rm_table(path, start, stop, **kwargs):
    """The table a user writes: ECSV, columns time (ISO, UTC), rm (rad / m2)."""
    table_ = rm_table_mjd(start, stop, **kwargs)
    table_["time"] = Time(table_["time"], format="mjd").isot
    table_.write(path, format="ascii.ecsv")
    return path


def test_rm_table_in_place_and_apply_back(tmp_path, capsys):
    ms, products, gain, (start, stop) = faraday_ms(tmp_path)
    rm = write_rm_table(tmp_path / "rm.ecsv", start, stop)
    with table(str(ms), ack=False) as main_table:
        data = main_table.getcol("DATA")
    status, out, err = run(capsys, "correct", ms, "--in-place", "--rm-table", rm)
    assert status == 0, err
    assert "feed rotation and ionospheric Faraday rotation removed" in err
    with table(str(ms), ack=False) as main_table:
        corrected = main_table.getcol("CORRECTED_DATA") / gain
    # The intrinsic EVPA at every channel (the same figure as correct_ms: 3e-6 deg).
    assert np.max(np.abs(evpa_circular(corrected, products) - CHI0)) < 0.01
    status, out, err = run(capsys, "correct", ms, "--in-place", "--apply", "--rm-table", rm,
                           "--data-column", "CORRECTED_DATA", "--column", "BACK")
    assert status == 0, err
    with table(str(ms), ack=False) as main_table:
        back = main_table.getcol("BACK")
    assert np.max(np.abs(back - data)) < 1e-6 * np.max(np.abs(data))


def test_rm_table_not_covering_one_line_before_writing(tmp_path, capsys):
    ms, _, _, (start, stop) = faraday_ms(tmp_path)
    rm = write_rm_table(tmp_path / "rm.ecsv", stop + 1, stop + 2)
    out_ms = tmp_path / "out.ms"
    status, out, err = run(capsys, "correct", ms, "-o", out_ms, "--rm-table", rm)
    assert status == 1 and out == ""
    assert err.startswith("feedrot: error: --rm-table: ") and err.count("\n") == 1, err
    assert "outside the table of rotation measures" in err and str(ms) in err
    assert not out_ms.exists()


def test_rm_table_lacking_an_antenna_names_it(tmp_path, capsys):
    ms, _, _, (start, stop) = faraday_ms(tmp_path)
    rm = write_rm_table(tmp_path / "rm.ecsv", start, stop, antennas=["1", "2", "3"])
    status, out, err = run(capsys, "correct", ms, "--in-place", "--rm-table", rm)
    assert status == 1 and err.count("\n") == 1, err
    assert "has no antenna '4'; it has 1, 2, 3" in err
    with table(str(ms), ack=False) as main_table:
        assert "CORRECTED_DATA" not in main_table.colnames()


def test_ionex_with_its_height(tmp_path, capsys):
    # Reference: correct_ms with Ionosphere.from_ionex(height=350 km) on a copy of the set;
    # the command's --ionex-height reaches the maps' shell, and HISTORY says so.
    import shutil

    from helpers import import_or_skip

    import_or_skip("spinifex", "ionosphere", "FEEDROT_REQUIRE_SPINIFEX")
    import astropy.units as u

    from astropy_feedrot.ionosphere import Ionosphere, sample_ionex
    from astropy_feedrot.visibilities import correct_ms

    ms, _, _, _ = faraday_ms(tmp_path)
    with table(str(ms), readonly=False, ack=False) as main_table:  # into CODE's maps
        time_ = main_table.getcol("TIME")
        main_table.putcol("TIME", time_ - time_[0] + Time("2020-01-08T10:00").mjd * 86400)
    reference = shutil.copytree(ms, tmp_path / "reference.ms")
    files = sample_ionex("codg00[89]0.20i.Z")
    status, out, err = run(capsys, "correct", ms, "--in-place", "--ionex", *files,
                           "--ionex-height", "350km")
    assert status == 0, err
    correct_ms(reference, ionosphere=Ionosphere.from_ionex(files, height=350 * u.km))
    with table(str(ms), ack=False) as ours, table(str(reference), ack=False) as theirs:
        np.testing.assert_array_equal(ours.getcol("CORRECTED_DATA"),
                                      theirs.getcol("CORRECTED_DATA"))
    with table(str(ms / "HISTORY"), ack=False) as history:
        assert "(shell at 350 km, IGRF through spinifex)" in history.getcol("MESSAGE")[-1]
    status, out, err = run(capsys, "correct", ms, "--in-place", "--redo", "--ionex", *files,
                           "--ionex-height", "25000km")
    assert status == 1 and err.count("\n") == 1, err
    assert err.startswith("feedrot: error: --ionex-height: height of the ionosphere's thin "
                          "shell must be one value from 50 km to 20000 km, got 25000.0 km"), err


def test_ionex_and_rm_table_exclude_each_other(tmp_path, capsys):
    ms, _, _, (start, stop) = faraday_ms(tmp_path)
    rm = write_rm_table(tmp_path / "rm.ecsv", start, stop)
    status, out, err = run(capsys, "correct", ms, "--in-place", "--rm-table", rm,
                           "--ionex", tmp_path / "codg0080.20i")
    assert status == 1 and "not both" in err and err.count("\n") == 1


def test_ionex_without_spinifex_gives_the_install_hint(tmp_path):
    ionex = tmp_path / "codg0080.20i"
    ionex.write_text("not read\n")
    code = ("import sys; sys.modules['spinifex'] = None; "
            "from astropy_feedrot.cli import main; "
            f"sys.exit(main(['correct', 'x.ms', '--in-place', '--ionex', {str(ionex)!r}]))")
    # Read before the input: the missing extra is said first.
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 1 and result.stdout == ""
    assert result.stderr.count("\n") == 1, result.stderr
    assert "need spinifex" in result.stderr and "[ionosphere]" in result.stderr
