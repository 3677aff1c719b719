# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Simulated data sets behind an ionosphere, for the tests of the Faraday correction.

The voltage-level models of the other tests (``ms_model``, ``fitsidi_writer``,
``uvdata_model``: receptor rows from their definitions, the feed rotation from
ERFA's hd2pa) for a source whose observed EVPA runs as chi0 + RM lambda^2
across the channels. The models are linear in the source's Stokes
parameters, so the data of each channel are made from three runs of a model
(I; I + P along Q; I + P along U) combined with cos 2 chi(nu) and
sin 2 chi(nu): the Faraday rotation enters as a turn of the source's plane of
polarization on the sky (the same for every antenna), independent of how the
package turns the receptors. Nothing here calls astropy_feedrot.
"""

import shutil

import ms_model
import numpy as np
import pytest
from astropy import constants as const
from astropy import units as u
from astropy.io import fits
from astropy.table import QTable
from astropy.time import Time
from casacore.tables import table
from fitsidi_writer import write_fitsidi

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
    per channel; the time span (MJD, days)."""
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


def rm_table_mjd(start, stop, rm=RM, antennas=None):
    """As `rm_table`, for a span in MJD (days)."""
    times = Time([start - 0.01, stop + 0.01], format="mjd", scale="utc")
    if antennas is None:
        return QTable({"time": times, "rm": [rm, rm] * u.rad / u.m**2})
    names = [name for name in antennas for _ in range(2)]
    return QTable({"time": Time(np.tile(times.mjd, len(antennas)), format="mjd", scale="utc"),
                   "rm": np.full(len(names), rm) * u.rad / u.m**2, "antenna": names})


def faraday_fitsidi(where, products=("RR", "LL", "RL", "LR"), n_freqid=1):
    """A FITS-IDI file of fitsidi_writer (4 VLBI stations, 2 bands of 4 channels), its
    frequencies set to 1.0-1.3 and 1.5-1.8 GHz, the source's EVPA chi0 + RM lambda^2 per
    channel; the channels' frequencies (band, channel) and the gains. With ``n_freqid``,
    the rows take turns through as many setups (FREQID), all of those frequencies."""
    parts = []
    for evpa, polarized in ((0.0, 0.0), (0.0, 0.1), (45.0, 0.1)):  # I, +Q, +U
        path = where / f"part{len(parts)}.idifits"
        info = write_fitsidi(path, products=products, evpa=evpa, polarized=polarized,
                             n_band=2, n_chan=4, n_freqid=n_freqid)
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
