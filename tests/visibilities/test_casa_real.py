# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The correction of a real FITS-IDI file against CASA's own.

The file is the VLBA hardware correlator's FITS-IDI sample of the NASA GSFC
FITS registry (10 stations, RR/LL/RL/LR; tests/data/real/README.md), trimmed
to the tables CASA reads. CASA imports it (``importfitsidi``) and removes the
parallactic angle (``applycal(parang=True)``); the package corrects the same
data twice over, once as a FITS-IDI file (`correct_fitsidi`, the copy then
imported by CASA) and once as the Measurement Set CASA wrote (`correct_ms`).
Every visibility of every product is compared with CASA's, in phase, with
CASA's conventions (geocentric vertical, pole of date). The tolerance,
0.001 deg, is the one documented in docs/correcting.rst.
"""

import shutil
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("casacore")

from casa_offline import SKIP_WITHOUT_CASA, check_casa_starts, run_casa  # noqa: E402
from casacore.tables import table  # noqa: E402

from astropy_feedrot.visibilities import correct_fitsidi, correct_ms  # noqa: E402

pytestmark = SKIP_WITHOUT_CASA

BL146 = Path(__file__).parent.parent / "data" / "real" / "BL146_1.trim.fits"
CASA_CONVENTION = {"convention": "casa"}  # vertical="geocentric", pole="casa"


def _visibilities(ms, column):
    """The cross-correlations of ``column`` with a non-zero amplitude, and their mask."""
    with table(str(ms), ack=False) as t:
        values = t.getcol(column)
        cross = t.getcol("ANTENNA1") != t.getcol("ANTENNA2")
    return values, cross[:, None, None] & (np.abs(values) > 0)


@pytest.fixture(scope="module")
def imported(tmp_path_factory):
    """The file imported by CASA, with CASA's CORRECTED_DATA, and a pristine copy."""
    home = tmp_path_factory.mktemp("casa_bl146")
    check_casa_starts(home)
    ms = home / "casa.ms"
    run_casa(home, "importfitsidi", BL146, ms)
    pristine = home / "pristine.ms"
    shutil.copytree(ms, pristine)
    run_casa(home, "applycal", ms)
    casa, keep = _visibilities(ms, "CORRECTED_DATA")
    data, _ = _visibilities(pristine, "DATA")
    return home, pristine, casa, data, keep


def _phase_difference(ours, casa, keep):
    """|arg(ours / casa)| in degrees, for each kept visibility."""
    return np.abs(np.angle(ours[keep] / casa[keep], deg=True))


def test_real_fitsidi_file_as_casa_corrects_it(imported, tmp_path):
    home, _, casa, data, keep = imported
    # CASA's correction is large on this file (tens of degrees), so the
    # agreement below is not that of two near-identities.
    assert np.median(_phase_difference(data, casa, keep)) > 10
    corrected = tmp_path / "ours.fits"
    correct_fitsidi(BL146, corrected, **CASA_CONVENTION)
    ms = tmp_path / "ours.ms"
    run_casa(home, "importfitsidi", corrected, ms)
    ours, ours_keep = _visibilities(ms, "DATA")
    np.testing.assert_array_equal(ours_keep, keep)
    delta = _phase_difference(ours, casa, keep)
    print(f"FITS-IDI: median {np.median(delta) * 3600:.3f}\", max {delta.max() * 3600:.3f}\"")
    assert delta.max() < 0.001
    # The amplitudes are those of the file: a rotation only.
    np.testing.assert_allclose(np.abs(ours[keep]), np.abs(casa[keep]), rtol=1e-6)


def test_real_measurement_set_written_by_casa(imported, tmp_path):
    _, pristine, casa, _, keep = imported
    ms = tmp_path / "ours.ms"
    shutil.copytree(pristine, ms)
    correct_ms(ms, **CASA_CONVENTION)
    ours, _ = _visibilities(ms, "CORRECTED_DATA")
    delta = _phase_difference(ours, casa, keep)
    print(f"Measurement Set: median {np.median(delta) * 3600:.3f}\", "
          f"max {delta.max() * 3600:.3f}\"")
    assert delta.max() < 0.001
