# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Real files of the field's programs, read and written right (issue 26).

The files are under tests/data/real/ (README.md there: source, commit,
licence; trim_fits_rows.py made the trims, verbatim subsets of the rows).
Every correction is compared with an independent computation: the feed
rotation of each antenna from `Antenna.feed_rotation`, the antennas built
here from the file's own ``STABXYZ`` and the sources from its ``SOURCE``
table, read with astropy alone.
"""

from pathlib import Path

import astropy.units as u
import numpy as np
import pytest
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.io import fits
from astropy.time import Time

from astropy_feedrot import AltAzMount, Antenna
from astropy_feedrot.receptors import Receptors
from astropy_feedrot.visibilities import correct_fitsidi, fitsidi_antennas

REAL = Path(__file__).parent / "data" / "real"
SFXC = REAL / "n09q2_1_1-shortened.trim.IDI1"  # EVN/SFXC, LL, POLTYA 'l', POLTYB '?'
EMERLIN = REAL / "emerlin_multiuv.trim.IDI1"  # e-MERLIN, LL, two UV_DATA tables
HOPS = REAL / "hops_3600_OJ287.trim.uvfits"  # EHT 2017, HOPS UVFITS


def _raw_hdus(path):
    """[(name, header bytes, data bytes, record dtype or None)] of a FITS file."""
    out = []
    with fits.open(path) as hdus, open(path, "rb") as raw:
        for index, hdu in enumerate(hdus):
            info = hdus.fileinfo(index)
            raw.seek(info["hdrLoc"])
            header = raw.read(info["datLoc"] - info["hdrLoc"])
            data = raw.read(info["datSpan"])
            dtype = hdu.columns.dtype.newbyteorder(">") if hdu.name == "UV_DATA" else None
            out.append((hdu.name, header, data, dtype))
    return out


def _cards(header):
    """The cards of a header's bytes before END."""
    cards = [header[k:k + 80] for k in range(0, len(header), 80)]
    return cards[:[c.rstrip() for c in cards].index(b"END")]


def assert_only_flux_changed(original, corrected):
    """Every byte of ``corrected`` is that of ``original`` but UV_DATA's FLUX and one
    HISTORY card of the primary header."""
    before, after = _raw_hdus(original), _raw_hdus(corrected)
    assert [h[0] for h in before] == [h[0] for h in after]
    cards0, cards1 = (_cards(h[0][1]) for h in (before, after))
    assert cards1[:len(cards0)] == cards0  # the input's cards as they lie
    assert cards1[len(cards0):] and all(c.startswith(b"HISTORY ") for c in cards1[len(cards0):])
    for (name, h0, d0, dtype), (_, h1, d1, _) in zip(before[1:], after[1:]):
        assert h0 == h1, name
        if dtype is None:
            assert d0 == d1, name
            continue
        rows0 = np.frombuffer(d0[:len(d0) // dtype.itemsize * dtype.itemsize], dtype)
        rows1 = np.frombuffer(d1[:len(rows0) * dtype.itemsize], dtype)
        for field in dtype.names:
            if field != "FLUX":
                assert rows0[field].tobytes() == rows1[field].tobytes(), (name, field)
        assert d0[rows0.nbytes:] == d1[rows1.nbytes:]


def independent_phase(path, index):
    """Phi1 - Phi2 (deg) of every row of UV_DATA extension ``index``: Antenna.feed_rotation
    of alt-az antennas at the file's STABXYZ, the source of its SOURCE table (J2000)."""
    with fits.open(path) as hdus:
        geometry, table, rows = hdus["ARRAY_GEOMETRY"].data, hdus["SOURCE"].data, \
            hdus[index].data
        antennas = {int(n): Antenna(EarthLocation.from_geocentric(*xyz, unit=u.m),
                                    AltAzMount())
                    for n, xyz in zip(geometry["NOSTA"], geometry["STABXYZ"])}
        sources = {int(k): SkyCoord(ra * u.deg, dec * u.deg) for k, ra, dec in
                   zip(table["SOURCE_ID"], table["RAEPO"], table["DECEPO"])}
        baseline = rows["BASELINE"].astype(int)
        a1, a2 = baseline // 256, baseline % 256
        when = Time(rows["DATE"] + rows["TIME"], format="jd", scale="utc")
        source = np.asarray(rows["SOURCE"] if "SOURCE" in rows.names else rows["SOURCE_ID"])
    phi = {}
    for n, antenna in antennas.items():
        for k, target in sources.items():
            here = source == k
            phi[n, k] = np.full(len(a1), np.nan)
            phi[n, k][here] = antenna.feed_rotation(target, when[here]).deg
    phi1 = np.choose(np.searchsorted(sorted(antennas), a1), [np.nansum(
        [phi[n, k] for k in sources], axis=0) for n in sorted(antennas)])
    phi2 = np.choose(np.searchsorted(sorted(antennas), a2), [np.nansum(
        [phi[n, k] for k in sources], axis=0) for n in sorted(antennas)])
    return phi1 - phi2, a1 != a2


def flux_phase(path, index):
    """The phase (deg) of each FLUX value of UV_DATA extension ``index``, and its
    modulus."""
    with fits.open(path) as hdus:
        flux = np.asarray(hdus[index].data["FLUX"], float)
        size = hdus[index].header["MAXIS1"]
    flux = flux.reshape(len(flux), -1, size)
    vis = flux[..., 0] + 1j * flux[..., 1]
    return vis


def test_single_polarization_sfxc_antennas():
    # POLTYA 'l', POLTYB '?' at every antenna: L, with the R of the pair completed
    # at the same angle (Receptors.paired), as CASA's importfitsidi keeps 'L', '?'.
    antennas = fitsidi_antennas(SFXC)
    assert [antennas[n].name for n in (1, 2, 3)] == ["EB", "ON", "NT"]
    assert all(a.receptors == Receptors("LR", [0, 0] * u.deg) for a in antennas.values())


@pytest.mark.parametrize("path", [SFXC, EMERLIN], ids=["sfxc", "emerlin"])
def test_single_polarization_fitsidi_corrected(path, tmp_path):
    out = correct_fitsidi(path, tmp_path / "out.IDI1")
    assert_only_flux_changed(path, out)
    with fits.open(path) as hdus:
        tables = [k for k, hdu in enumerate(hdus) if hdu.name == "UV_DATA"]
    checked = 0
    for index in tables:
        before, after = flux_phase(path, index), flux_phase(out, index)
        delta, cross = independent_phase(path, index)
        # LL: the L voltage turns by exp(+i Phi); FITS-IDI stores the conjugate of
        # <v1 v2*>, so removing the rotation multiplies the stored LL by
        # exp(+i (Phi1 - Phi2)) (autocorrelations unchanged).
        expected = before * np.exp(1j * np.radians(delta))[:, None]
        live = np.abs(before) > 0
        assert live[cross].sum() > 100
        np.testing.assert_allclose(after[live], expected[live], rtol=2e-6, atol=0)
        assert np.array_equal(after[~cross], before[~cross])
        checked += live[cross].sum()
    print(f"{path.name}: {checked} values of baselines checked")
