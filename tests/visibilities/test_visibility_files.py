# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Visibility files of every kind: detection, antennas, corrected copies, and the
``feedrot antennas`` and ``feedrot correct`` commands.

The FITS-IDI files are written by ``fitsidi_writer`` with a polarized source
injected through a voltage-level model (receptor rows from their definitions,
feed rotation from ERFA's hd2pa on astropy's HADec); the corrected products
must come back as that model's sky-fixed products.
"""

import hashlib
import tarfile
from pathlib import Path

import numpy as np
import pytest
from astropy.io import fits
from astropy.table import Table
from fitsidi_writer import write_fitsidi

from astropy_feedrot.cli import main
from astropy_feedrot.data import sample_file
from astropy_feedrot.visibilities import (
    FILE_KINDS,
    antenna_table,
    correct_file,
    file_kind,
    read_antennas,
)

DATA = Path(__file__).parent.parent / "data" / "uvdata"
VLA = sample_file("vla_day2_8chan.uvfits")


def digest(path):
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def untar(name, where):
    with tarfile.open(DATA / name) as archive:
        top = archive.getnames()[0].split("/")[0]
        archive.extractall(where, filter="data")
    return where / top


# fitsidi_writer gives WETTZ13S a left-handed Nasmyth focus to exercise that closed
# form; that it differs from the catalogue's is tested in tests/visibilities/test_real_antennas.py.
MOUNT_WARNING = "ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning"
pytestmark = pytest.mark.filterwarnings(MOUNT_WARNING)


@pytest.fixture
def idi(tmp_path):
    path = tmp_path / "experiment.idifits"
    model = write_fitsidi(path, angles={0: (12.0, 102.0)})
    return path, model


def corrected(path, model):
    """Products (rows, bands, channels, products) in the <v1 v2*> convention, without
    the writer's channel gains (as tests/visibilities/test_io_fitsidi.py reads them)."""
    with fits.open(path) as hdus:
        flux = np.asarray(hdus["UV_DATA"].data["FLUX"], dtype=float)
    flux = flux.reshape(len(model["rows"]), model["n_band"], model["n_chan"],
                        len(model["products"]), 2)
    gain = (1.0 + 0.1 * np.arange(model["n_chan"])[None, :]
            + 0.01 * np.arange(model["n_band"])[:, None])
    return (flux[..., 0] + 1j * flux[..., 1]).conj() / gain[None, :, :, None]


def test_kinds(tmp_path, idi):
    assert file_kind(VLA) == "uvfits"
    assert file_kind(DATA / "ata.LoA.C0352.uvh5_60647_62965_9760406_3c286_0001.uvh5") == "uvh5"
    assert file_kind(idi[0]) == "fits-idi"
    assert file_kind(untar("lwasv_cor_58342_05_00_14.ms.tar.gz", tmp_path)) == "ms"
    assert file_kind(untar("sma_test_corrchunk1.mir.tar.gz", tmp_path)) == "mir"
    assert set(FILE_KINDS) == {"fits-idi", "uvfits", "uvh5", "ms", "miriad", "mir", "msv4"}


def test_kinds_refused(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such file"):
        file_kind(tmp_path / "missing.uvfits")
    (tmp_path / "empty").mkdir()
    with pytest.raises(ValueError, match="is a directory but not a Measurement Set"):
        file_kind(tmp_path / "empty")
    text = tmp_path / "notes.txt"
    text.write_text("hello")
    with pytest.raises(ValueError, match="cannot tell the kind"):
        file_kind(text)
    image = tmp_path / "image.fits"
    fits.HDUList([fits.PrimaryHDU(np.zeros((2, 2)))]).writeto(image)
    with pytest.raises(ValueError, match="neither random groups"):
        file_kind(image)


def test_antennas_of_the_sample_as_read():
    # The sample is the VLA (casacore's UVFITS, MNTSTA 0, POLTYA R, POLAA 0).
    antennas, software = read_antennas(VLA)
    assert software == "fits-idi:casacore" and len(antennas) == 19
    table = antenna_table(antennas, software)
    assert list(table["label"]) == ["0"] * 19
    assert set(table["mount"]) == {"AltAzMount()"}
    assert table["x"].unit == "m"
    # A VLA pad lies some 2 km above the ellipsoid, at latitude 34 deg north.
    geodetic = antennas[1].location.to_geodetic()
    assert 2000 < geodetic.height.to_value("m") < 2200 and 33.9 < geodetic.lat.deg < 34.2


def test_fitsidi_file_is_corrected_and_input_kept(idi, tmp_path):
    path, model = idi
    before = digest(path)
    out = correct_file(path, tmp_path / "corrected.idifits", frame="apparent")
    assert digest(path) == before and file_kind(out) == "fits-idi"
    values = corrected(out, model)
    np.testing.assert_allclose(values, np.broadcast_to(model["expected"][:, None, None, :],
                                                       values.shape), atol=2e-6)


def test_outputs_refused(idi, tmp_path):
    path, _ = idi
    with pytest.raises(ValueError, match="is the input"):
        correct_file(path, path)
    existing = tmp_path / "exists.idifits"
    existing.write_bytes(b"x")
    with pytest.raises(FileExistsError, match="overwrite=True"):
        correct_file(path, existing)
    with pytest.raises(FileNotFoundError, match="does not exist"):
        correct_file(path, tmp_path / "nowhere" / "out.idifits")


def test_command_antennas(capsys, idi, tmp_path):
    assert main(["antennas", str(VLA)]) == 0
    out, err = capsys.readouterr()
    table = Table.read(out, format="ascii.ecsv")
    assert len(table) == 19 and err == "" and table.meta["labels"] == "fits-idi:casacore"
    output = tmp_path / "antennas.ecsv"
    assert main(["antennas", str(idi[0]), "-o", str(output)]) == 0
    assert "label" in Table.read(output).colnames
    # (After this file's warnings, one line per distinct warning.)
    assert capsys.readouterr().err.endswith(f"\nfeedrot: {output}: {len(Table.read(output))} "
                                            f"antennas of {idi[0]}, as read\n")
    assert main(["antennas", str(idi[0]), "-o", str(output)]) == 1
    assert "exists; add --overwrite" in capsys.readouterr().err


def test_command_correct_fitsidi(capsys, idi, tmp_path):
    path, model = idi
    output = tmp_path / "out.idifits"
    assert main(["correct", str(path), "-o", str(output), "--frame", "icrs", "--quiet"]) == 0
    err = capsys.readouterr().err
    assert output.exists() and err.count("\n") == 1 and "WETTZ13S" in err  # the mounts
    assert main(["correct", str(path), "-o", str(output)]) == 1
    assert "--overwrite" in capsys.readouterr().err
    assert main(["correct", str(path), "-o", str(path)]) == 1
    assert "never modified" in capsys.readouterr().err
    assert main(["correct", str(tmp_path / "missing.uvfits"), "-o", str(output)]) == 1
    assert "no such file" in capsys.readouterr().err


def test_commands_on_a_difx_file(capsys, tmp_path):
    # difx2fits' primary header (NAXIS = 0, GROUPS = T, GCOUNT = PCOUNT = 0),
    # two arrays and two frequency setups: recognised as FITS-IDI, not UVFITS.
    path = tmp_path / "difx.idifits"
    model = write_fitsidi(path, angles={0: (12.0, 102.0)}, n_arrays=2, n_freqid=2)
    assert file_kind(path) == "fits-idi"
    assert main(["antennas", str(path)]) == 0
    table = Table.read(capsys.readouterr().out, format="ascii.ecsv")
    assert list(table["name"]) == ["FD-VLBA", "EFLSBERG", "YEBES40M", "WETTZ13S"]
    assert table.meta["labels"] == "fits-idi:difx"
    output = tmp_path / "out.idifits"
    assert main(["correct", str(path), "-o", str(output), "--quiet"]) == 0
    values = corrected(output, model)
    # Reference: the writer's voltage-level model (ERFA hd2pa on astropy's HADec).
    np.testing.assert_allclose(values, np.broadcast_to(model["expected"][:, None, None, :],
                                                       values.shape), atol=2e-6)


# Through pyuvdata ----------------------------------------------------------------------------


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:Writing in the MS file that the units")
@pytest.mark.parametrize("name", ["corrected.uvfits", "corrected.uvh5", "corrected.ms"])
def test_uvfits_corrected_into_every_format(tmp_path, name):
    # The sample: real VLA data with RR, LL, RL, LR. The corrected copy, read
    # back, equals correct_uvdata on the input read directly.
    from astropy_feedrot.visibilities import correct_uvdata, read_uvdata

    before = digest(VLA)
    out = correct_file(VLA, tmp_path / name)
    assert digest(VLA) == before
    expected = correct_uvdata(read_uvdata(VLA))
    got = read_uvdata(out)
    got.reorder_pols(order=[list(got.polarization_array).index(p)
                            for p in expected.polarization_array])
    np.testing.assert_allclose(got.data_array, expected.data_array, rtol=1e-6, atol=1e-6)
    assert "Feedrotationremoved" in "".join(got.history.split())  # lines are wrapped
    # A second correction is refused: the history says it was done.
    with pytest.raises(ValueError, match="already"):
        correct_file(out, tmp_path / ("again" + Path(name).suffix))


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
@pytest.mark.filterwarnings("ignore:Writing in the MS file that the units")
def test_command_correct_uvfits_and_existing_directory(tmp_path, capsys):
    output = tmp_path / "vla.ms"
    assert main(["correct", str(VLA), "-o", str(output), "--quiet"]) == 0
    assert file_kind(output) == "ms"
    assert main(["correct", str(VLA), "-o", str(output), "--quiet"]) == 1
    assert "--overwrite" in capsys.readouterr().err
    assert main(["correct", str(VLA), "-o", str(output), "--quiet", "--overwrite"]) == 0
    assert file_kind(output) == "ms"
    assert [p.name for p in tmp_path.iterdir()] == ["vla.ms"]  # nothing left behind


def test_antennas_through_pyuvdata():
    # The ATA uvh5 file: pyuvdata fills alt-az and x = 90 deg, y = 0 for the ATA.
    antennas, software = read_antennas(
        DATA / "ata.LoA.C0352.uvh5_60647_62965_9760406_3c286_0001.uvh5")
    assert software == "pyuvdata"
    table = antenna_table(antennas, software)
    assert set(table["label"]) == {"alt-az"} and set(table["receptors"]) == {"XY"}
    assert set(table["receptor_angles"]) == {"90 0"}


def test_files_cut_short(idi, tmp_path):
    # A FITS-IDI file cut inside its first block, before its UV_DATA table, and
    # inside the rows of UV_DATA: each a clear error, never a corrected copy.
    path, _ = idi
    data = path.read_bytes()
    cut = tmp_path / "cut.idifits"
    cut.write_bytes(data[:100])
    with pytest.raises(ValueError, match="cannot be read as FITS .* may be cut short"):
        file_kind(cut)
    cut.write_bytes(data[:2 * 2880 + 10])
    with pytest.raises(ValueError, match="is cut short"):
        correct_file(cut, tmp_path / "out.idifits")
    with fits.open(path) as hdus:  # cut where UV_DATA starts: whole tables before it
        start = hdus.fileinfo(hdus.index_of("UV_DATA"))["hdrLoc"]
    cut.write_bytes(data[:start])
    with pytest.raises(ValueError, match="cut short loses its last tables"):
        file_kind(cut)
    cut.write_bytes(data[:-2880])
    with pytest.raises(ValueError, match="is cut short"):
        correct_file(cut, tmp_path / "out.idifits")
    assert not (tmp_path / "out.idifits").exists()


def test_correct_fitsidi_refuses_rows_cut_short(idi, tmp_path):
    from astropy_feedrot.visibilities import FITSFormatError, correct_fitsidi

    path, _ = idi
    cut = tmp_path / "cut.idifits"
    cut.write_bytes(path.read_bytes()[:-2880])
    with pytest.warns(UserWarning, match="truncated"):  # astropy's own word on reading
        with pytest.raises(FITSFormatError, match="UV_DATA .* the file is cut short"):
            correct_fitsidi(cut, tmp_path / "out.idifits")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cut.idifits", "experiment.idifits"]
