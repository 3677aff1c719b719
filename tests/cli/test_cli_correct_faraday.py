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
