# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Real files of the field's programs, read and written right.

The files are under tests/data/real/ (README.md there: source, commit,
licence; trim_fits_rows.py made the trims, verbatim subsets of the rows).
Every correction is compared with an independent computation: the feed
rotation of each antenna from `Antenna.feed_rotation`, the antennas built
here from the file's own ``STABXYZ`` and the sources from its ``SOURCE``
table, read with astropy alone.
"""

import os
import re
import stat
from pathlib import Path

import astropy.units as u
import numpy as np
import pytest
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.io import fits
from astropy.time import Time

from astropy_feedrot import AltAzMount, Antenna
from astropy_feedrot.antennas.receptors import Receptors
from astropy_feedrot.cli import main
from astropy_feedrot.visibilities import (
    FITSFormatError,
    check_output_format,
    correct_file,
    correct_fitsidi,
    file_kind,
    fitsidi_antennas,
    read_antennas,
    read_uvdata,
    write_uvdata,
)

REAL = Path(__file__).parent.parent / "data" / "real"
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


def test_single_polarization_emerlin_antennas():
    # e-MERLIN's LL file names both receptors (R, L at 0 deg) in its ANTENNA table.
    antennas = fitsidi_antennas(EMERLIN)
    assert [antennas[n].name for n in sorted(antennas)] == ["Mk2", "Kn", "De", "Pi", "Da",
                                                            "Cm"]
    assert all(a.receptors == Receptors("RL", [0, 0] * u.deg) for a in antennas.values())


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


# --- UVFITS of AIPS and HOPS through pyuvdata ------------------------------------------

AIPS = Path(__file__).parent.parent / "data" / "uvdata" / "mojave.uvfits"  # pyuvdata's, AIPS


def _pyuvdata_phases(source, output):
    """Per product: the phase (deg) of corrected / original averaged over channels, per
    row; and Phi1 - Phi2, Phi1 + Phi2 (deg) from Antenna.feed_rotation of alt-az
    antennas at the input's positions (as pyuvdata reads them) and its phase centre."""
    before, after = read_uvdata(source), read_uvdata(output)
    assert np.array_equal(before.time_array, after.time_array)
    assert np.array_equal(before.ant_1_array, after.ant_1_array)
    telescope = before.telescope
    xyz = telescope.antenna_positions + np.array(
        [c.to_value(u.m) for c in (telescope.location.x, telescope.location.y,
                                   telescope.location.z)])
    entry = before.phase_center_catalog[0]
    target = SkyCoord(entry["cat_lon"] * u.rad, entry["cat_lat"] * u.rad)
    when = Time(before.time_array, format="jd", scale="utc")
    phi = {n: Antenna(EarthLocation.from_geocentric(*p, unit=u.m), AltAzMount())
           .feed_rotation(target, when).deg for n, p in zip(telescope.antenna_numbers, xyz)}
    rows = np.arange(before.Nblts)
    phi1 = np.choose(np.searchsorted(telescope.antenna_numbers, before.ant_1_array),
                     [phi[n] for n in telescope.antenna_numbers])
    phi2 = np.choose(np.searchsorted(telescope.antenna_numbers, before.ant_2_array),
                     [phi[n] for n in telescope.antenna_numbers])
    assert phi1.shape == rows.shape
    phases = {}
    for k, code in enumerate(before.polarization_array):
        a = before.data_array[..., k].reshape(before.Nblts, -1)
        b = after.data_array[..., k].reshape(before.Nblts, -1)
        live = np.abs(a) > 0
        ratio = np.where(live, b / np.where(live, a, 1), 0).sum(axis=1)
        phases[int(code)] = np.where(live.any(axis=1), np.angle(ratio, deg=True), np.nan)
    return phases, phi1 - phi2, phi1 + phi2


def _wrapped(angle):
    return np.abs((np.asarray(angle) + 180) % 360 - 180)


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:The telescope frame is set to")
# HOPS writes MNTSTA 0 for the EHT's Nasmyth stations (tests/visibilities/test_real_antennas.py).
@pytest.mark.filterwarnings("ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")
@pytest.mark.parametrize("path", [AIPS, HOPS], ids=["aips", "hops"])
def test_uvfits_output_of_aips_and_hops(path, tmp_path):
    # pyuvdata 3.2 gives J2000 entries of AIPS files (EQUINOX 2000, read as ICRS) no
    # epoch, and write_uvfits failed on it: "float() argument must be ... not
    # 'NoneType'". Its array centre (ARRAYX/Y/Z 0: the mean of the antennas, inside
    # the Earth) was written where pyuvdata cannot read it back.
    out = correct_file(path, tmp_path / "out.uvfits", redo=True)
    with fits.open(out) as hdus:
        assert hdus[0].header["EPOCH"] == 2000.0
    phases, minus, plus = _pyuvdata_phases(path, out)
    live = np.isfinite(phases[-1])
    assert live.sum() > 100
    # pyuvdata holds what UVFITS stores, the conjugate of <v1 v2*> (as FITS-IDI): R
    # turns by exp(-i Phi), so removing the rotation multiplies RR by
    # exp(-i (Phi1 - Phi2)) and LL by exp(+i (Phi1 - Phi2)); float32 data.
    assert _wrapped(phases[-1][live] + minus[live]).max() < 1e-4
    assert _wrapped(phases[-2][live] - minus[live]).max() < 1e-4
    # RL by exp(-i (Phi1 + Phi2)), LR by exp(+i (Phi1 + Phi2)): the HOPS file gives R
    # 0 and L 90 deg, and both receptors turn with the first one's angle (CASA's rule,
    # Receptors.sky_angles); with L's own 90 deg, RL and LR were 90 deg off (45 deg
    # of EVPA).
    cross = np.isfinite(phases[-3]) & np.isfinite(phases[-4])
    assert cross.sum() > 100
    assert _wrapped(phases[-3][cross] + plus[cross]).max() < 1e-4
    assert _wrapped(phases[-4][cross] - plus[cross]).max() < 1e-4


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:The telescope frame is set to")
def test_write_uvdata_leaves_the_data_as_they_were(tmp_path):
    uv = read_uvdata(AIPS)
    location, positions = uv.telescope.location, uv.telescope.antenna_positions.copy()
    write_uvdata(uv, tmp_path / "x.fits", kind="uvfits")
    assert uv.phase_center_catalog[0]["cat_epoch"] is None
    assert uv.telescope.location == location
    assert np.array_equal(uv.telescope.antenna_positions, positions)
    again = read_uvdata(tmp_path / "x.fits", file_type="uvfits")
    # The antennas where they were (the array centre moved to the surface below).
    xyz = [t.antenna_positions + np.array([c.to_value(u.m) for c in (
        t.location.x, t.location.y, t.location.z)]) for t in (uv.telescope, again.telescope)]
    assert np.abs(xyz[0] - xyz[1]).max() < 1e-3
    with pytest.raises(ValueError, match=r"kind must be one of \('uvfits', 'uvh5', 'ms', "
                                         r"'miriad'\).*got 'fits-idi'"):
        write_uvdata(uv, tmp_path / "y.fits", kind="fits-idi")


# --- names: by content, never by name alone ----------------------------------------------


@pytest.mark.parametrize("kind, output, written", [
    ("fits-idi", "x.IDI1", "fits-idi"),
    ("fits-idi", "x.idi12", "fits-idi"),
    ("fits-idi", "x.FITS", "fits-idi"),
    ("fits-idi", "x.idifits", "fits-idi"),
    ("fits-idi", "x.fts", "fits-idi"),
    ("uvfits", "x.fits", "uvfits"),
    ("uvfits", "x.FIT", "uvfits"),
    ("uvfits", "x.uvf", "uvfits"),
    ("uvfits", "x.UVFITS", "uvfits"),
    ("uvfits", "x.uvh5", "uvh5"),
    ("ms", "x.uvfits", "uvfits"),
    ("uvh5", "x.ms", "ms"),
    ("miriad", "x.uv", "miriad"),
])
def test_output_kind(kind, output, written):
    assert check_output_format(kind, output) == written


@pytest.mark.parametrize("kind, output, match", [
    ("fits-idi", "x.uvfits", r"a FITS-IDI input is corrected into a FITS-IDI copy"),
    ("fits-idi", "x.IDI", None),
    ("fits-idi", "x.txt", r"give the output one of the extensions .idifits"),
    ("uvfits", "x.IDI1", r"'x.IDI1': .idi1 names a FITS-IDI file, but a uvfits input is "
                         r"written by pyuvdata, which writes no FITS-IDI; use one of "
                         r"\.uvfits, \.uvf"),
    ("uvh5", "x.fits", r"'x.fits': .fits is used by both FITS-IDI and UVFITS; a uvh5 input "
                       r"is written as UVFITS with \.uvfits \(or \.uvf\)"),
    ("ms", "x.dat", r"cannot tell a format from the extension of 'x.dat'"),
])
def test_output_kind_refused(kind, output, match):
    if match is None:
        assert check_output_format(kind, output) == "fits-idi"
        return
    with pytest.raises(ValueError, match=match):
        check_output_format(kind, output)


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:The telescope frame is set to")
def test_names_by_content_in_and_out(tmp_path, capsys):
    # AIPS names UVFITS *.fits (and *.FITS); the EVN archive FITS-IDI *.IDI1: read by
    # content, written in the input's kind where the extension is FITS's.
    uvfits = tmp_path / "MOJAVE.FITS"
    uvfits.write_bytes(AIPS.read_bytes())
    idi = tmp_path / "n09q2.fits"
    idi.write_bytes(SFXC.read_bytes())
    assert file_kind(uvfits) == "uvfits" and file_kind(idi) == "fits-idi"
    assert len(read_antennas(uvfits)[0]) == 10
    out = correct_file(uvfits, tmp_path / "out.fits", redo=True)
    assert file_kind(out) == "uvfits"
    assert main(["correct", str(idi), "-o", str(tmp_path / "x.IDI1"), "--quiet"]) == 0
    assert main(["correct", str(uvfits), "-o", str(tmp_path / "x.uvf"), "--quiet",
                 "--redo"]) == 0
    assert file_kind(tmp_path / "x.IDI1") == "fits-idi"
    assert file_kind(tmp_path / "x.uvf") == "uvfits"
    capsys.readouterr()


# --- header cards that cannot be read ---------------------------------------------------


def _corrupt(source, target, keyword, value):
    """A copy of ``source`` whose first card ``keyword`` reads ``value`` (no quotes)."""
    data = bytearray(source.read_bytes())
    start = data.find(keyword.ljust(8).encode("ascii") + b"=")
    assert start >= 0 and start % 80 == 0
    data[start:start + 80] = f"{keyword:<8}= {value}".ljust(80).encode("ascii")
    target.write_bytes(bytes(data))
    return target


@pytest.mark.parametrize("source, keyword, value, table", [
    (AIPS, "EQUINOX", "2.0OOE+03", r"PRIMARY \(HDU 0\) header"),
    (SFXC, "NO_CHAN", "16.0.0", r"ARRAY_GEOMETRY \(HDU 1\) header"),
])
def test_unreadable_header_card_named(tmp_path, capsys, source, keyword, value, table):
    bad = _corrupt(source, tmp_path / f"bad{source.suffix}", keyword, value)
    match = (rf"bad{re.escape(source.suffix)}, table {table}: expected a readable value in "
             rf"the card {keyword} \(correct or remove the card in a copy, e\.g\. with "
             rf"astropy: hdul\.verify\('fix'\)\), got '{keyword} *= {re.escape(value)}'")
    with pytest.raises(FITSFormatError, match=match):
        correct_file(bad, tmp_path / f"out{source.suffix}")
    with pytest.raises(FITSFormatError, match=match):
        read_antennas(bad)
    if source == SFXC:
        with pytest.raises(FITSFormatError, match=match):
            correct_fitsidi(bad, tmp_path / "out.IDI1")
    assert main(["correct", str(bad), "-o", str(tmp_path / f"o{source.suffix}")]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and re.match("feedrot: error: INPUT: .*" + match, err), err
    assert sorted(p.name for p in tmp_path.iterdir()) == [bad.name]


# --- modes of new files ----------------------------------------------------------------


@pytest.fixture
def umask():
    old = os.umask(0o027)
    try:
        yield 0o640  # 0o666 & ~0o027
    finally:
        os.umask(old)


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:The telescope frame is set to")
@pytest.mark.filterwarnings("ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")
def test_new_files_get_the_umask_mode(tmp_path, umask, capsys):
    # mkstemp made corrected FITS-IDI copies 0600 whatever the umask.
    made = [correct_fitsidi(SFXC, tmp_path / "a.IDI1"),
            correct_file(SFXC, tmp_path / "b.idifits"),
            correct_file(HOPS, tmp_path / "c.uvfits"),
            correct_file(HOPS, tmp_path / "d.uvh5")]
    for name, source in (("e.IDI1", SFXC), ("f.uvfits", HOPS)):
        assert main(["correct", str(source), "-o", str(tmp_path / name), "--quiet"]) == 0
        made.append(tmp_path / name)
    capsys.readouterr()
    modes = {Path(p).name: stat.S_IMODE(os.stat(p).st_mode) for p in made}
    assert modes == dict.fromkeys(modes, umask), {k: oct(v) for k, v in modes.items()}


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
def test_new_measurement_sets_get_the_umask_mode(tmp_path, umask):
    # The casacore copy of a Measurement Set: directories 0750, files 0640 under 027.
    pytest.importorskip("casacore")
    from ms_model import unpack  # needs casacore

    out = correct_file(unpack(tmp_path / "in"), tmp_path / "out.ms")
    paths = [out, *Path(out).rglob("*")]
    modes = {stat.S_IMODE(p.stat().st_mode) for p in paths if p.is_file()}
    dirs = {stat.S_IMODE(p.stat().st_mode) for p in paths if p.is_dir()}
    assert modes == {umask} and dirs == {umask | 0o110}, (modes, dirs)
