# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The progress of correct_rinex: the bytes of the file read, block by block."""

import gzip
import io
import shutil

import pytest
from astropy import units as u
from astropy.time import Time

from astropy_feedrot.data import sample_file
from astropy_feedrot.gnss import RinexReader, correct, correct_rinex
from astropy_feedrot.gnss.synthetic import constellation, write_rinex, write_sp3

RNX = sample_file("gnss_sample.rnx")  # 40 epochs
SP3 = sample_file("gnss_sample.sp3")
START = Time("2023-01-25T00:00:19", scale="tai")  # 00:00 GPS time
TYPES = {"G": ("C1C", "L1C", "L2W", "S1C"), "E": ("C1C", "L1C", "L5Q", "S1C")}


@pytest.fixture(scope="module")
def long_file(tmp_path_factory):
    """(RINEX, SP3): 900 epochs at 1 s of 8 satellites, about 0.6 MB: longer than the
    buffer of the file read (so that the bytes read move as the records are)."""
    here = tmp_path_factory.mktemp("long")
    orbits = constellation(START, {"G": 5, "E": 3})
    write_sp3(here / "sim.sp3", orbits, START, 9)  # two hours at 15 min
    write_rinex(here / "obs.rnx", "3.04", TYPES, list(orbits), START + 600 * u.s, 900, 1.0)
    return here / "obs.rnx", here / "sim.sp3"


@pytest.mark.parametrize("compressed", [False, True])
def test_progress_counts_the_bytes_read_after_each_block(tmp_path, monkeypatch, long_file,
                                                         compressed):
    rnx, sp3 = long_file
    source = tmp_path / ("obs.rnx.gz" if compressed else "obs.rnx")
    if compressed:
        source.write_bytes(gzip.compress(rnx.read_bytes()))
    else:
        shutil.copy(rnx, source)
    # Blocks of 100 epochs.
    monkeypatch.setattr(correct, "BLOCK_EPOCHS", 100)
    calls = []
    correct_rinex(source, tmp_path / "bar.rnx", sp3,
                  progress=lambda done, total: calls.append((done, total)))
    size = source.stat().st_size
    # After several of the nine blocks, then at the end (gzip reads the 60 kB of this
    # compressed file at once: its blocks are those of the decompressor).
    assert len(calls) >= (1 if compressed else 4), calls
    assert all(total == size for _, total in calls)
    done = [d for d, _ in calls]
    assert done == sorted(set(done)) and done[-1] == size
    # The same bytes written with and without progress.
    correct_rinex(source, tmp_path / "plain.rnx", sp3)
    assert (tmp_path / "bar.rnx").read_bytes() == (tmp_path / "plain.rnx").read_bytes()


def test_no_progress_for_a_file_object(tmp_path):
    calls = []
    with open(RNX, "rb") as handle:
        correct_rinex(handle, tmp_path / "out.rnx", SP3,
                      progress=lambda done, total: calls.append((done, total)))
    assert calls == []


def test_a_bad_progress_is_refused_before_anything_is_read(tmp_path):
    with pytest.raises(TypeError, match=r"progress must be True, False or a callable "
                                        r"\(done, total\), got int"):
        correct_rinex(RNX, tmp_path / "out.rnx", SP3, progress=1)
    assert list(tmp_path.iterdir()) == []


def test_the_reader_follows_the_file():
    with RinexReader(RNX) as reader:
        assert reader.size == RNX.stat().st_size
        first = reader.bytes_read()
        records = list(reader)
        assert 0 < first <= reader.bytes_read() == reader.size
    assert len(records) == 40
    with RinexReader(io.StringIO(RNX.read_text())) as reader:
        assert reader.size is None and reader.bytes_read() is None
