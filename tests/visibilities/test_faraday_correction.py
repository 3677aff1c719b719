# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ionospheric Faraday rotation removed (and applied) with the feed rotation.

The data (tests/faraday_model.py): the voltage-level models of the other
tests for a source whose observed EVPA runs as chi0 + RM lambda^2 across the
channels, the Faraday rotation entering as a turn of the source's plane of
polarization on the sky, independent of how the package turns the receptors.
The corrected EVPA must be chi0 at every channel, and applying the rotation
to the corrected data must give the data back.
"""

import warnings

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import SkyCoord
from astropy.io import fits
from astropy.table import QTable
from astropy.time import Time

from helpers import import_or_skip

from astropy_feedrot import get_antenna
from astropy_feedrot.antennas.receptors import Receptors
from astropy_feedrot.core.exceptions import DegenerateGeometryWarning
from astropy_feedrot.ionosphere import Ionosphere, IonosphereError, sample_ionex

casacore = pytest.importorskip("casacore")

from casacore.tables import table  # noqa: E402
from faraday_model import (  # noqa: E402
    C,
    CHI0,
    FREQUENCIES,
    RM,
    evpa_circular,
    evpa_linear,
    faraday_fitsidi,
    faraday_ms,
    faraday_uvdata,
    rm_table_mjd,
)

from astropy_feedrot.visibilities import (  # noqa: E402
    ReceptorAngleTable,
    correct_fitsidi,
    correct_ms,
    correct_uvdata,
    with_receptors,
)
from astropy_feedrot.visibilities.history import CorrectionRefused  # noqa: E402

# The models write some stations with other mounts than the catalogue's on purpose
# (tested in test_real_antennas.py).
pytestmark = pytest.mark.filterwarnings(
    "ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")


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
    # The input back to 1e-6 of its largest value (measured: 7e-8, single precision).
    assert np.max(np.abs(back - data)) < 1e-6 * np.max(np.abs(data))
    # A second removal is refused, as without an ionosphere.
    with pytest.raises(CorrectionRefused, match="removed already"):
        correct_ms(ms, ionosphere=ionosphere)


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


# --- FITS-IDI ------------------------------------------------------------------------


@pytest.mark.parametrize("products", [("RR", "LL", "RL", "LR"), ("XX", "YY", "XY", "YX")])
def test_fitsidi_rows_of_two_setups(tmp_path, products):
    # Rows taking turns through two FREQIDs (lambda^2 per row: the angles per channel,
    # not the one-pass circular path): the EVPA still the intrinsic one at every channel,
    # and the same numbers as the file of one setup (its one pass for circular feeds).
    ionosphere = Ionosphere.from_rm(rm_table_mjd(Time("2023-01-25T20:00").mjd,
                                                 Time("2023-01-26T02:00").mjd))
    results = []
    for setups in (1, 2):
        where = tmp_path / f"setups{setups}"
        where.mkdir()
        path, frequency, gain, info = faraday_fitsidi(where, products, n_freqid=setups)
        with fits.open(path) as hdul:
            assert set(hdul["UV_DATA"].data["FREQID"]) == set(range(1, setups + 1))
        out = where / "corrected.idifits"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DegenerateGeometryWarning)  # below a horizon
            correct_fitsidi(path, out, ionosphere=ionosphere)
        with fits.open(out) as hdul:
            flux = hdul["UV_DATA"].data["FLUX"].reshape(-1, 1, 1, 2, 4, len(products), 2)
        results.append(np.conj(flux[..., 0] + 1j * flux[..., 1].astype(float))[:, 0, 0]
                       / gain[..., None])
    vis = results[1]
    up = np.isfinite(vis).all(axis=(1, 2, 3))
    evpa = (evpa_circular if products[0] == "RR" else evpa_linear)(vis[up], list(products))
    assert np.max(np.abs(evpa - CHI0)) < 0.01  # model: chi0 at every channel
    np.testing.assert_allclose(vis[up], results[0][up], rtol=0, atol=2e-6)


@pytest.mark.parametrize("products", [("RR", "LL", "RL", "LR"), ("XX", "YY", "XY", "YX")])
def test_fitsidi_evpa_flat_and_round_trip(tmp_path, products):
    path, frequency, gain, info = faraday_fitsidi(tmp_path, products)
    ionosphere = Ionosphere.from_rm(rm_table_mjd(Time("2023-01-25T20:00").mjd,
                                                 Time("2023-01-26T02:00").mjd))
    out = tmp_path / "corrected.idifits"
    # 3C 84 is below the horizon of one station at three epochs (its feed rotation is
    # defined, its line of sight through the ionosphere not): those rows are NaN.
    with pytest.warns(DegenerateGeometryWarning, match="below the antenna's horizon"), \
            pytest.warns(DegenerateGeometryWarning, match="undefined in 12 of 60 rows"):
        correct_fitsidi(path, out, ionosphere=ionosphere)
    with fits.open(out) as hdul:
        flux = hdul["UV_DATA"].data["FLUX"].reshape(-1, 1, 1, 2, 4, len(products), 2)
        history = "\n".join(str(card) for card in hdul[0].header["HISTORY"])
    vis = np.conj(flux[..., 0] + 1j * flux[..., 1].astype(float))[:, 0, 0] / gain[..., None]
    up = np.isfinite(vis).all(axis=(1, 2, 3))
    evpa = (evpa_circular if products[0] == "RR" else evpa_linear)(vis[up], list(products))
    # The intrinsic EVPA at every channel of both bands (measured: 3e-5 deg).
    assert np.max(np.abs(evpa - CHI0)) < 0.01
    assert "ionospheric Faraday rotation" in history
    back = tmp_path / "back.idifits"
    with pytest.warns(DegenerateGeometryWarning):
        correct_fitsidi(out, back, ionosphere=ionosphere, direction="apply")
    with fits.open(path) as original, fits.open(back) as again:
        before = original["UV_DATA"].data["FLUX"][up]
        after = again["UV_DATA"].data["FLUX"][up]
        assert np.max(np.abs(after - before)) < 1e-6 * np.max(np.abs(before))
    with pytest.raises(ValueError, match="already"):
        correct_fitsidi(out, tmp_path / "twice.idifits", ionosphere=ionosphere)


# --- pyuvdata --------------------------------------------------------------------------


@pytest.mark.parametrize("pols, feeds, angles",
                         [(["rr", "ll", "rl", "lr"], ["r", "l"], [0.0, 0.0]),
                          (["xx", "xy", "yx", "yy"], ["x", "y"], [0.0, 90.0])])
def test_uvdata_evpa_flat_and_round_trip(pols, feeds, angles):
    from astropy_feedrot.visibilities.uvdata import PRODUCT_CODES

    uv = faraday_uvdata(pols, [feeds] * 4, [angles] * 4)
    ionosphere = Ionosphere.from_rm(rm_table_mjd(uv.time_array.min() - 2400000.5,
                                                 uv.time_array.max() - 2400000.5))
    out = correct_uvdata(uv, ionosphere=ionosphere)
    names = [PRODUCT_CODES[c] for c in out.polarization_array]
    vis = np.conj(out.data_array)  # pyuvdata stores the conjugate of <v1 v2*>
    evpa = (evpa_circular if names[0] == "RR" else evpa_linear)(vis, names)
    # The intrinsic EVPA at every channel (measured: 1e-13 deg, double precision).
    assert np.max(np.abs(evpa - CHI0)) < 0.01
    assert "ionospheric Faraday rotation" in out.history
    back = correct_uvdata(out, ionosphere=ionosphere, direction="apply")
    assert np.max(np.abs(back.data_array - uv.data_array)) < 1e-6
    with pytest.raises(ValueError, match="already"):
        correct_uvdata(out, ionosphere=ionosphere)


def test_uvdata_rm_per_antenna_round_trip():
    """Different RM at each antenna: removing and applying give the data back, and the
    corrected RR of a baseline loses the differential rotation."""
    uv = faraday_uvdata(["rr", "ll", "rl", "lr"], [["r", "l"]] * 4, [[0.0, 0.0]] * 4, rm=0.0)
    start, stop = uv.time_array.min() - 2400000.5, uv.time_array.max() - 2400000.5
    table = QTable({"time": Time(np.repeat([start - 0.01, stop + 0.01], 4), format="mjd"),
                    "rm": np.tile([1.0, -2.0, 0.5, 4.0], 2) * u.rad / u.m**2,
                    "antenna": ["A0", "A1", "A2", "A3"] * 2})
    ionosphere = Ionosphere.from_rm(table)
    corrupted = correct_uvdata(correct_uvdata(uv), ionosphere=ionosphere, direction="apply",
                               redo=True)
    again = correct_uvdata(corrupted, ionosphere=ionosphere, redo=True)
    assert np.max(np.abs(again.data_array - correct_uvdata(uv).data_array)) < 1e-12


# --- real IONEX maps -------------------------------------------------------------------


def test_rm_of_every_row_is_the_ionospheres_on_real_ionex_maps():
    """The RM a correction uses for each row's antennas (looked up as the chunks look
    them up) equals Ionosphere.rotation_measure for those antennas and epochs, on CODE's
    IONEX maps of 2020 January 8 and 9 that spinifex ships."""
    import_or_skip("spinifex", "ionosphere", "FEEDROT_REQUIRE_SPINIFEX")
    ionosphere = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
    antennas = with_receptors({1: get_antenna("EFLSBERG"), 2: get_antenna("YEBES40M"),
                               3: get_antenna("WETTZ13S")}, Receptors("RL", [0, 0] * u.deg))
    crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    # Every 10 s for 3 h, each epoch on the three baselines (the Crab is up at all three).
    epochs = Time("2020-01-08T20:00") + np.repeat(np.arange(0, 3 * 3600, 10), 3) * u.s
    pairs = np.tile([[1, 2], [1, 3], [2, 3]], (epochs.size // 3, 1))
    source = np.zeros(epochs.size, int)
    table = ReceptorAngleTable(antennas, epochs.jd, source, pairs[:, 0], pairs[:, 1],
                               {0: crab}, lambda t: Time(t, format="jd"), products=["RR"],
                               ionosphere=ionosphere)
    rm1 = table.rm[table.places(epochs.jd, source, pairs[:, 0])]
    rm2 = table.rm[table.places(epochs.jd, source, pairs[:, 1])]
    sites = [antennas[n] for n in (1, 2, 3)]
    expected = ionosphere.rotation_measure(
        np.concatenate([a.location.reshape(1) for a in sites]), crab, epochs,
        antenna=[a.name for a in sites]).to_value(u.rad / u.m**2)  # (epochs, 3)
    rows = np.arange(epochs.size)
    assert np.all(np.isfinite(rm1)) and np.all(rm1 > 0)  # a winter night: 0.3-0.6 rad/m2
    # The same numbers but for the rows' times, kept as float Julian dates as a file keeps
    # them (20 us apart from the Time asked; measured: 5e-10 rad/m2, 1.3e-9 relative).
    np.testing.assert_allclose(rm1, expected[rows, pairs[:, 0] - 1], rtol=1e-8, atol=0)
    np.testing.assert_allclose(rm2, expected[rows, pairs[:, 1] - 1], rtol=1e-8, atol=0)


def test_history_names_the_ionex_files():
    from astropy_feedrot.visibilities.faraday import ionosphere_text

    import_or_skip("spinifex", "ionosphere", "FEEDROT_REQUIRE_SPINIFEX")
    text = ionosphere_text(Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z")), " ")
    assert text == (" and the ionospheric Faraday rotation (RM lambda^2 per channel) from the "
                    "IONEX files codg0080.20i.Z, codg0090.20i.Z (shell at 450 km, IGRF through "
                    "spinifex)")
    assert ionosphere_text(None, " ") == ""


def test_not_an_ionosphere_refused():
    # Before the files are looked at.
    for correct in (correct_ms, lambda path, **kw: correct_fitsidi(path, "out.idifits", **kw)):
        with pytest.raises(TypeError, match=r"ionosphere must be an Ionosphere \(Ionosphere"):
            correct("missing", ionosphere="codg0080.20i.Z")
