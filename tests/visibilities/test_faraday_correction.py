# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ionospheric Faraday rotation removed (and applied) with the feed rotation.

The data: the voltage-level models of the other tests (``ms_model``,
``uvdata_model``: receptor rows from their definitions, the feed rotation
from ERFA's hd2pa), for a source whose observed EVPA runs as
chi0 + RM lambda^2 across the channels. The models are linear in the
source's Stokes parameters, so the data of each channel are made from three
runs of a model (I; I + P along Q; I + P along U) combined with
cos 2 chi(nu) and sin 2 chi(nu): the Faraday rotation enters as a turn of the
source's plane of polarization on the sky, independent of how the package
turns the receptors. The corrected EVPA must be chi0 at every channel.
"""

import numpy as np
import pytest
from astropy import constants as const
from astropy import units as u
from astropy.table import QTable
from astropy.time import Time

from astropy_feedrot.ionosphere import Ionosphere, IonosphereError

casacore = pytest.importorskip("casacore")

import ms_model  # noqa: E402
from casacore.tables import table  # noqa: E402

from astropy_feedrot.visibilities import correct_ms  # noqa: E402
from astropy_feedrot.visibilities.history import CorrectionRefused  # noqa: E402

C = const.c.to_value(u.m / u.s)
RM = 3.0  # rad/m2: 15.5 deg at 1 GHz, 3.9 deg at 2 GHz
CHI0 = 33.0  # deg, ms_model.EVPA: the source's intrinsic EVPA
FREQUENCIES = np.linspace(1.0e9, 2.0e9, 64)  # the simulated set's 64 channels, Hz


def evpa_circular(vis, products):
    """EVPA (deg) from RL = Q + iU of receptors fixed on the sky (<v1 v2*>)."""
    return np.degrees(np.angle(vis[..., products.index("RL")])) / 2


def evpa_linear(vis, products):
    """EVPA (deg) from Q = (XX - YY) / 2, U = (XY + YX) / 2 (X north, Y east)."""
    q = (vis[..., products.index("XX")] - vis[..., products.index("YY")]).real
    uu = (vis[..., products.index("XY")] + vis[..., products.index("YX")]).real
    return np.degrees(np.arctan2(uu, q)) / 2


# --- Measurement Sets --------------------------------------------------------------


def faraday_ms(where, linear=False):
    """The VLA set of ms_model, its channels at 1-2 GHz, the source's EVPA chi0 + RM lambda^2
    per channel; the time span (MJD seconds)."""
    ms = ms_model.unpack(where)
    if linear:
        ms_model.make_linear(ms, {"default": [0.0, 90.0]})
    with table(str(ms / "SPECTRAL_WINDOW"), readonly=False, ack=False) as spw:
        spw.putcell("CHAN_FREQ", 0, FREQUENCIES)
    parts = []
    saved = ms_model.EVPA, ms_model.POLARIZED
    try:
        for evpa, polarized in ((0.0, 0.0), (0.0, 0.1), (45.0, 0.1)):  # I, +Q, +U
            ms_model.EVPA, ms_model.POLARIZED = evpa, polarized
            info = ms_model.fill_model(ms)
            with table(str(ms), ack=False) as main:
                parts.append(main.getcol("DATA").astype(complex))
    finally:
        ms_model.EVPA, ms_model.POLARIZED = saved
    chi = np.radians(CHI0 + np.degrees(RM * (C / FREQUENCIES) ** 2))[None, :, None]
    data = parts[0] + np.cos(2 * chi) * (parts[1] - parts[0]) \
        + np.sin(2 * chi) * (parts[2] - parts[0])
    with table(str(ms), readonly=False, ack=False) as main:
        main.putcol("DATA", data.astype(np.complex64))
        time = main.getcol("TIME")
    return ms, info["products"], info["gain"], (time.min() / 86400, time.max() / 86400)


@pytest.mark.parametrize("linear", [False, True])
def test_ms_evpa_flat_and_round_trip(tmp_path, linear):
    ms, products, gain, (start, stop) = faraday_ms(tmp_path, linear)
    evpa = evpa_linear if linear else evpa_circular
    with table(str(ms), ack=False) as main:
        data = main.getcol("DATA")
    # Before: the feed rotation removed only, the EVPA runs with lambda^2.
    correct_ms(ms, corrected_column="FEED_ONLY")
    with table(str(ms), ack=False) as main:
        feed_only = main.getcol("FEED_ONLY") / gain
    seen = evpa(feed_only, products)
    expected = CHI0 + np.degrees(RM * (C / FREQUENCIES) ** 2)
    assert np.allclose(seen, expected[None, :], atol=1e-3)
    ionosphere = Ionosphere.from_rm(rm_table_mjd(start, stop))
    correct_ms(ms, ionosphere=ionosphere)
    with table(str(ms), ack=False) as main:
        corrected = main.getcol("CORRECTED_DATA") / gain
    flat = evpa(corrected, products)
    print("EVPA max deviation (deg):", np.max(np.abs(flat - CHI0)))
    # The intrinsic EVPA at every channel and row, to 0.01 deg (measured: 2e-5 deg,
    # the single precision of the data).
    assert np.max(np.abs(flat - CHI0)) < 0.01
    with table(str(ms / "HISTORY"), ack=False) as history:
        message = history.getcol("MESSAGE")[-1]
    assert "ionospheric Faraday rotation" in message and "table of rotation measures" in message
    # Applied to the corrected data: the input back.
    correct_ms(ms, direction="apply", data_column="CORRECTED_DATA",
               corrected_column="MODEL_BACK", ionosphere=ionosphere)
    with table(str(ms), ack=False) as main:
        back = main.getcol("MODEL_BACK")
    print("round trip max |back - data| / max |data|:", np.max(np.abs(back - data)) / np.max(np.abs(data)))
    assert np.max(np.abs(back - data)) < 1e-6 * np.max(np.abs(data)) * 10
    # A second removal is refused, as without an ionosphere.
    with pytest.raises(CorrectionRefused, match="removed already"):
        correct_ms(ms, ionosphere=ionosphere)


def rm_table_mjd(start, stop, rm=RM, antennas=None):
    """As `rm_table`, for a span in MJD (days)."""
    times = Time([start - 0.01, stop + 0.01], format="mjd", scale="utc")
    if antennas is None:
        return QTable({"time": times, "rm": [rm, rm] * u.rad / u.m**2})
    names = [name for name in antennas for _ in range(2)]
    return QTable({"time": Time(np.tile(times.mjd, len(antennas)), format="mjd", scale="utc"),
                   "rm": np.full(len(names), rm) * u.rad / u.m**2, "antenna": names})


def test_ms_ionosphere_not_covering_refused_before_writing(tmp_path):
    ms, _, _, (start, stop) = faraday_ms(tmp_path)
    late = Ionosphere.from_rm(rm_table_mjd(stop + 1, stop + 2))
    with pytest.raises(IonosphereError, match="outside the table of rotation measures"):
        correct_ms(ms, ionosphere=late)
    with table(str(ms), ack=False) as main:
        assert "CORRECTED_DATA" not in main.colnames()  # nothing written


def test_ms_table_lacking_an_antenna_names_it(tmp_path):
    ms, _, _, (start, stop) = faraday_ms(tmp_path)
    with table(str(ms / "ANTENNA"), ack=False) as antennas:
        names = [n for n in antennas.getcol("NAME") if n]
    partial = Ionosphere.from_rm(rm_table_mjd(start, stop, antennas=names[:3]))
    with pytest.raises(IonosphereError, match="has no antenna '"):
        correct_ms(ms, ionosphere=partial)
