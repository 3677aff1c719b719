# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""CASA's own parallactic angle correction recognised: applycal(parang=True) and
split(datacolumn="corrected") run by CASA (casa_offline.py, offline) on the
CASA-made set with two spectral windows of tests/data/real (casa_sim.py
``simulate vla2``).

What is checked: the HISTORY rows CASA writes are read (CORRECTED_DATA is not
overwritten without overwrite_column, nor corrected again, and neither is
the DATA of a set split from it); and, asked to replace CASA's
CORRECTED_DATA, the correction of both windows agrees with CASA's own
(the EVPA of RL, row by row; the reference is CASA's output, the tolerance
that of docs/correcting.rst).
"""

import shutil
import tarfile
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("casacore")

from casa_offline import SKIP_WITHOUT_CASA, check_casa_starts, run_casa  # noqa: E402
from casacore.tables import table  # noqa: E402

from astropy_feedrot.cli import main  # noqa: E402
from astropy_feedrot.visibilities import CorrectionRefused, correct_ms  # noqa: E402

pytestmark = SKIP_WITHOUT_CASA

REAL = Path(__file__).parent.parent / "data" / "real"


def by_window(ms, name):
    with table(str(ms), ack=False) as t:
        return [t.query(f"DATA_DESC_ID=={dd}").getcol(name) for dd in (0, 1)]


@pytest.fixture(scope="module")
def applied(tmp_path_factory):
    """(home, a set CASA's applycal(parang=True) corrected, CASA's CORRECTED_DATA)."""
    home = tmp_path_factory.mktemp("casa_history")
    check_casa_starts(home)
    with tarfile.open(REAL / "casa_sim_vla_2spw.ms.tar.gz") as archive:
        archive.extractall(home, filter="data")
    ms = home / "casa_sim_vla_2spw.ms"
    run_casa(home, "applycal", ms)
    return home, ms, by_window(ms, "CORRECTED_DATA")


def test_casa_corrected_data_recognised(applied, tmp_path, capsys):
    _, source, _ = applied
    ms = tmp_path / "applied.ms"
    shutil.copytree(source, ms)
    with pytest.raises(CorrectionRefused, match=r"column 'CORRECTED_DATA' exists and was "
                       r"written by CASA applycal \(CASA applycal\(parang=True\)\); writing "
                       r"DATA corrected into it would replace its values: pass "
                       r"overwrite_column=True"):
        correct_ms(ms)
    with pytest.raises(CorrectionRefused, match=r"\(HISTORY of CORRECTED_DATA\): the feed "
                       r"rotation was removed already \(the history records CASA applycal"
                       r"\(parang=True\)\); correcting again would remove it twice: pass "
                       r"redo=True to correct all the same$"):
        correct_ms(ms, data_column="CORRECTED_DATA", corrected_column="AGAIN")
    assert main(["correct", str(ms), "--in-place", "--data-column", "CORRECTED_DATA",
                 "--column", "AGAIN", "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.endswith("pass --redo to correct all the same\n")
    with table(str(ms), ack=False) as t:
        assert "AGAIN" not in t.colnames()


def test_split_from_casa_corrected_data_recognised(applied):
    home, source, _ = applied
    out = home / "split.ms"
    run_casa(home, "split", source, out)
    with pytest.raises(CorrectionRefused, match=r"\(HISTORY of DATA\): the feed rotation was "
                       r"removed already \(the history records CASA applycal\(parang=True\), "
                       r"then CASA split\(datacolumn='corrected'\)\)"):
        correct_ms(out)
    with table(str(out), ack=False) as t:
        assert "CORRECTED_DATA" not in t.colnames()


def evpa(values):
    """EVPA (deg) of a point source from circular products (IAU; RL = Q + iU)."""
    return np.degrees(np.angle(values[..., 1])) / 2


def test_replaced_when_asked_agrees_with_casa(applied, tmp_path):
    _, source, casa = applied
    ms = tmp_path / "ours.ms"
    shutil.copytree(source, ms)
    correct_ms(ms, vertical="geocentric", pole="casa", overwrite_column=True)
    for window, (ours, theirs) in enumerate(zip(by_window(ms, "CORRECTED_DATA"), casa)):
        delta = evpa(ours) - evpa(theirs)
        delta = np.abs((delta + 90) % 180 - 90) * 3600
        print(f"window {window}: max {delta.max():.3f}\"")
        assert delta.max() < 3.6  # 0.001 deg, docs/correcting.rst
