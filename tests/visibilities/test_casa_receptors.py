# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Circular receptors at different angles, against CASA's own applycal(parang=True).

CASA's simulator observes a polarized point source with four VLA antennas
(circular feeds, tests/casa_sim.py); the FEED table's RECEPTOR_ANGLE is then
set to [a, a + 90] deg (the offset HOPS and pyuvdata write) or [a, b] with an
unusual offset. CASA turns both hands by the first receptor's angle: measured
here (and when the rule was chosen, 2026-11-27: RL moved by 40 deg for [20,
110] and [20, 50] alike against [0, 0]). The package's correct_ms must give
CASA's CORRECTED_DATA; with L's own angle it was 45 deg of EVPA away.
"""

import shutil

import numpy as np
import pytest

pytest.importorskip("casacore")

from casa_offline import SKIP_WITHOUT_CASA, check_casa_starts, run_casa  # noqa: E402
from casacore.tables import table  # noqa: E402

from astropy_feedrot.core.exceptions import ReceptorAngleWarning  # noqa: E402
from astropy_feedrot.visibilities import correct_ms  # noqa: E402

pytestmark = SKIP_WITHOUT_CASA


@pytest.fixture(scope="module")
def simulated(tmp_path_factory):
    home = tmp_path_factory.mktemp("casa_receptors")
    check_casa_starts(home)
    ms = home / "vla.ms"
    run_casa(home, "simulate", "vla", ms)
    return home, ms


def _corrected(ms):
    with table(str(ms), ack=False) as t:
        data = t.getcol("CORRECTED_DATA")[:, 0]
        cross = t.getcol("ANTENNA1") != t.getcol("ANTENNA2")
        keep = ~t.getcol("FLAG")[:, 0].any(axis=-1) & cross
    return data[keep]


@pytest.mark.parametrize("angles, unusual", [
    ([20.0, 110.0], False),   # the usual 90 deg offset (HOPS, pyuvdata)
    ([20.0, 50.0], True),     # unusual: warned, the first angle used as CASA does
    ([-35.0, -35.0], False),  # one angle (AIPS, DiFX, casacore)
])
def test_circular_receptor_angles_as_casa(simulated, tmp_path, angles, unusual):
    home, source = simulated
    casa, ours = tmp_path / "casa.ms", tmp_path / "ours.ms"
    shutil.copytree(source, casa)
    with table(str(casa / "FEED"), readonly=False, ack=False) as feed:
        feed.putcol("RECEPTOR_ANGLE", np.tile(np.radians(angles), (feed.nrows(), 1)))
    shutil.copytree(casa, ours)
    run_casa(home, "applycal", casa)
    options = dict(vertical="geocentric", pole="casa", overwrite_column=True)
    if unusual:
        with pytest.warns(ReceptorAngleWarning, match=r"at 4 antennas: antenna 0 \(A0\): R "
                          r"20, L 50 deg; .*both receptors of each turn with the first one's "
                          r"angle, as in CASA"):
            correct_ms(ours, **options)
    else:
        correct_ms(ours, **options)
    reference, got = _corrected(casa), _corrected(ours).astype(complex)
    assert len(reference) > 100
    # Every product's phase against CASA's (RR, RL, LR, LL); the RL phase is twice the
    # EVPA. 0.002 deg as tests/visibilities/test_casa.py (the same geometry, CASA's pole
    # and vertical).
    phase = np.degrees(np.angle(got / reference))
    print(f"{angles}: max |phase - CASA| {np.max(np.abs(phase)):.2e} deg")
    assert np.max(np.abs(phase)) < 2e-3
    np.testing.assert_allclose(np.abs(got), np.abs(reference), rtol=1e-5)
