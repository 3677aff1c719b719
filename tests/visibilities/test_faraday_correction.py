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

import shutil

import numpy as np
import pytest
from astropy import constants as const
from astropy import units as u
from astropy.io import fits
from astropy.table import QTable
from astropy.time import Time

from astropy_feedrot.core.exceptions import DegenerateGeometryWarning
from astropy_feedrot.ionosphere import Ionosphere, IonosphereError

casacore = pytest.importorskip("casacore")

import ms_model  # noqa: E402
from casacore.tables import table  # noqa: E402
from fitsidi_writer import write_fitsidi  # noqa: E402

from astropy_feedrot.visibilities import correct_fitsidi, correct_ms, correct_uvdata  # noqa: E402
from astropy_feedrot.visibilities.history import CorrectionRefused  # noqa: E402

# The models write some stations with other mounts than the catalogue's on purpose
# (tested in test_real_antennas.py).
pytestmark = pytest.mark.filterwarnings(
    "ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")

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


# --- FITS-IDI ------------------------------------------------------------------------


def faraday_fitsidi(where, products=("RR", "LL", "RL", "LR")):
    """A FITS-IDI file of fitsidi_writer (4 VLBI stations, 2 bands of 4 channels), its
    frequencies set to 1.0-1.3 and 1.5-1.8 GHz, the source's EVPA chi0 + RM lambda^2 per
    channel; the channels' frequencies (band, channel) and the gains."""
    parts = []
    for evpa, polarized in ((0.0, 0.0), (0.0, 0.1), (45.0, 0.1)):  # I, +Q, +U
        path = where / f"part{len(parts)}.idifits"
        info = write_fitsidi(path, products=products, evpa=evpa, polarized=polarized,
                             n_band=2, n_chan=4)
        with fits.open(path) as hdul:
            flux = hdul["UV_DATA"].data["FLUX"].reshape(len(info["rows"]), 1, 1, 2, 4,
                                                        len(products), 2)
            parts.append(flux[..., 0] + 1j * flux[..., 1].astype(float))
    bandfreq, width, reference = np.array([0.0, 0.5e9]), 0.1e9, 1.0e9
    frequency = reference + bandfreq[:, None] + np.arange(4)[None, :] * width  # REF_PIXL 1
    chi = np.radians(CHI0 + np.degrees(RM * (C / frequency) ** 2))[None, None, None, :, :, None]
    data = parts[0] + np.cos(2 * chi) * (parts[1] - parts[0]) \
        + np.sin(2 * chi) * (parts[2] - parts[0])
    path = where / "faraday.idifits"
    shutil.copy(where / "part2.idifits", path)
    with fits.open(path, mode="update") as hdul:
        uv = hdul["UV_DATA"]
        flux = np.stack([data.real, data.imag], axis=-1).astype(np.float32)
        uv.data["FLUX"][:] = flux.reshape(len(uv.data), -1)
        uv.header["REF_FREQ"] = reference
        uv.header["CRVAL3"], uv.header["CDELT3"] = reference, width
        hdul["FREQUENCY"].data["BANDFREQ"][:] = bandfreq
        hdul["FREQUENCY"].data["CH_WIDTH"][:] = width
    gain = 1.0 + 0.1 * np.arange(4)[None, :] + 0.01 * np.arange(2)[:, None]
    return path, frequency, gain, info


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


def faraday_uvdata(pols, feeds, angles, rm=RM):
    """A UVData set of four VLA-like antennas (uvdata_model), 16 channels at 1-2 GHz, the
    source's EVPA chi0 + RM lambda^2 per channel; its channel frequencies."""
    pytest.importorskip("pyuvdata")
    import uvdata_model as model
    from astropy.coordinates import EarthLocation, SkyCoord
    from pyuvdata import Telescope, UVData
    from pyuvdata.utils import ECEF_from_ENU

    vla = EarthLocation.from_geodetic(-107.6184 * u.deg, 34.0790 * u.deg, 2124 * u.m)
    source = SkyCoord(150 * u.deg, 30 * u.deg)
    enu = np.array([[0.0, 0, 0], [300.0, 0, 0], [0, 500.0, 0], [-200.0, -400.0, 0]])
    positions = ECEF_from_ENU(enu, center_loc=vla) - np.array(
        [vla.x.to_value(u.m), vla.y.to_value(u.m), vla.z.to_value(u.m)])
    telescope = Telescope.new(name="TESTARRAY", instrument="TESTARRAY", location=vla,
                              antenna_positions=positions,
                              antenna_names=["A0", "A1", "A2", "A3"],
                              antenna_numbers=[0, 1, 2, 3], feed_array=feeds,
                              feed_angle=np.radians(angles), mount_type="alt-az")
    frequency = np.linspace(1.0e9, 2.0e9, 16)
    centre = {0: dict(cat_name="SRC", cat_type="sidereal", cat_lon=source.ra.rad,
                      cat_lat=source.dec.rad, cat_frame="icrs", cat_epoch=2000.0)}
    with pytest.warns(UserWarning, match="Recalculating uvw_array"):
        uv = UVData.new(freq_array=frequency, polarization_array=pols,
                        channel_width=np.full(16, 62.5e6),
                        times=2460000.75 + np.arange(4) * 1800.0 / 86400,
                        telescope=telescope, antpairs=[(0, 1), (0, 2), (1, 3), (2, 3)],
                        do_blt_outer=True, empty=True, phase_center_catalog=centre)
    parts = []
    for stokes in ((1.0, 0.0, 0.0, 0.05), (1.0, 0.1, 0.0, 0.05), (1.0, 0.0, 0.1, 0.05)):
        model.inject(uv, stokes, lambda times: source, "alt-az")
        parts.append(uv.data_array.copy())
    chi = np.radians(CHI0 + np.degrees(rm * (C / frequency) ** 2))[None, :, None]
    uv.data_array = parts[0] + np.cos(2 * chi) * (parts[1] - parts[0]) \
        + np.sin(2 * chi) * (parts[2] - parts[0])
    return uv


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
