# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Many files in one run: one task per file on a real dask.distributed cluster (two
worker processes), each file's outcome in the table, a bad file that stops nothing and
is left as it was, and a second run that skips what the first did.

Reference: each file corrected alone, by correct_file or correct_ms in this process;
the run's outputs must be those bytes (FITS-IDI) or those values (Measurement Sets).
"""
import filecmp
import hashlib
import shutil
from pathlib import Path

import numpy as np
import pytest
from astropy.io import fits

from astropy_feedrot.cli import main
from astropy_feedrot.data import sample_file
from astropy_feedrot.visibilities import (
    OUTCOMES,
    correct_file,
    correct_files,
    correct_ms,
)

distributed = pytest.importorskip("distributed")
tables = pytest.importorskip("casacore.tables")


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1,
                                  dashboard_address=None) as cluster:
        yield cluster


def _digest(path):
    path = Path(path)
    files = [path] if path.is_file() else sorted(p for p in path.rglob("*") if p.is_file())
    return hashlib.sha256(b"".join(p.read_bytes() for p in files)).hexdigest()


def _archive(where):
    """Two FITS-IDI files, two Measurement Sets, a file that is no visibility file and an
    MWA set (an aperture array, refused)."""
    where.mkdir()
    shutil.copy(sample_file("difx_k08161.idifits"), where / "a.idifits")
    with fits.open(sample_file("difx_k08161.idifits")) as hdul:
        hdul[0].header["OBSERVER"] = "B"  # another file of the same session
        hdul.writeto(where / "b.idifits")
    shutil.copytree(sample_file("vla_sim.ms"), where / "c.ms")
    shutil.copytree(sample_file("vla_sim.ms"), where / "d.ms")
    (where / "e.idifits").write_bytes(b"SIMPLE  = this is not FITS")
    mwa = shutil.copytree(sample_file("vla_sim.ms"), where / "mwa.ms")
    with tables.table(str(mwa / "OBSERVATION"), readonly=False, ack=False) as t:
        t.putcell("TELESCOPE_NAME", 0, "MWA")
    return [where / n for n in ("a.idifits", "b.idifits", "c.ms", "d.ms", "e.idifits",
                                "mwa.ms")]


def _column(ms, name="CORRECTED_DATA"):
    with tables.table(str(ms), ack=False) as t:
        return [t.getcell(name, r) for r in range(t.nrows())]


def test_copies_on_a_cluster(tmp_path, cluster):
    paths = _archive(tmp_path / "in")
    before = {p.name: _digest(p) for p in paths}
    out = tmp_path / "out"
    with distributed.Client(cluster) as client:
        table = correct_files(paths, out, client=client)
    assert table["outcome"].tolist() == ["corrected"] * 4 + ["failed", "refused"]
    assert table.meta["outcomes"] == dict(zip(OUTCOMES, (4, 0, 1, 1)))
    assert "cannot be read as FITS" in table["reason"][4]
    # Each output named as one absolute path, whichever adapter wrote it.
    expected = [(out / p.name).absolute() for p in paths[:4]]
    assert [Path(o) for o in table["output"][:4]] == expected
    assert list(table["output"][4:]) == ["", ""]
    assert "'MWA' is an aperture array" in table["reason"][5]
    # The inputs are as they were; the bad ones have no output.
    assert {p.name: _digest(p) for p in paths} == before
    assert sorted(p.name for p in out.iterdir()) == ["a.idifits", "b.idifits", "c.ms", "d.ms"]
    # Each output is what the file corrected alone gives: the same bytes for FITS-IDI.
    for name in ("a.idifits", "b.idifits"):
        alone = correct_file(tmp_path / "in" / name, tmp_path / f"alone_{name}")
        assert filecmp.cmp(out / name, alone, shallow=False)
    alone = correct_file(tmp_path / "in" / "c.ms", tmp_path / "alone.ms")
    for a, b in zip(_column(out / "c.ms"), _column(alone)):
        assert np.array_equal(a, b)
    # A second run skips what the first did, and only tries the others again.
    with distributed.Client(cluster) as client:
        again = correct_files(paths, out, client=client)
    assert again["outcome"].tolist() == ["skipped"] * 4 + ["failed", "refused"]
    assert "exists (an earlier run's output)" in again["reason"][0]


def test_in_place_serial_then_resumed(tmp_path):
    paths = _archive(tmp_path / "in")
    ms = [p for p in paths if p.suffix == ".ms"]
    steps = []
    table = correct_files(ms, progress=lambda done, total: steps.append((done, total)))
    assert table["outcome"].tolist() == ["corrected", "corrected", "refused"]
    assert steps == [(1, 3), (2, 3), (3, 3)]  # the bar counts files
    reference = shutil.copytree(sample_file("vla_sim.ms"), tmp_path / "reference.ms")
    correct_ms(reference)
    for a, b in zip(_column(ms[0]), _column(reference)):
        assert np.array_equal(a, b)
    again = correct_files(ms)
    assert again["outcome"].tolist() == ["skipped", "skipped", "refused"]
    assert "holds DATA with the feed rotation removed already" in again["reason"][0]
    # In place, only Measurement Sets and processing sets.
    fitsidi = correct_files(paths[:1])
    assert fitsidi["outcome"].tolist() == ["refused"]
    assert "corrected into a copy, never in place" in fitsidi["reason"][0]


def test_warnings_in_the_table(tmp_path):
    """What a file's correction warns goes into its row (a worker's warnings would be
    lost): a Measurement Set whose mounts differ from the catalogue's."""
    ms = shutil.copytree(sample_file("vla_sim.ms"), tmp_path / "n.ms")
    with tables.table(str(ms / "ANTENNA"), readonly=False, ack=False) as t:
        t.putcell("MOUNT", 0, "ALT-AZ+NASMYTH-R")
    table = correct_files([ms])
    assert table["outcome"].tolist() == ["corrected"]
    assert "CatalogueMountWarning" in table["warnings"][0]


def test_refused_before_any_work(tmp_path):
    paths = _archive(tmp_path / "in")
    (tmp_path / "other").mkdir()
    twin = shutil.copy(paths[0], tmp_path / "other" / "a.idifits")
    with pytest.raises(ValueError, match="would all be written as .*a.idifits"):
        correct_files([paths[0], twin], tmp_path / "out")
    assert not (tmp_path / "out").exists()
    with pytest.raises(ValueError, match="is a file"):
        correct_files(paths[:1], paths[1])
    with pytest.raises(ValueError, match="onto itself"):
        correct_files(paths[:1], tmp_path / "in")
    with pytest.raises(ValueError, match="no input"):
        correct_files([], tmp_path / "out")
    with pytest.raises(TypeError, match=r"unexpected options \['colour'\]"):
        correct_files(paths[:1], tmp_path / "out", colour="red")


def test_command_line(tmp_path, cluster, capsys):
    paths = _archive(tmp_path / "in")
    out = tmp_path / "out"
    arguments = ["correct", *map(str, paths), "-o", f"{out}/", "--dask", cluster.scheduler_address]
    assert main(arguments) == 1  # one failed, one refused
    captured = capsys.readouterr()
    assert "6 files: 4 corrected, 0 skipped, 1 refused, 1 failed" in captured.err
    lines = captured.out.splitlines()
    assert lines[0].split()[:3] == ["path", "outcome", "seconds"]
    assert sum("corrected" in line for line in lines) == 4
    # Resumed: the good files skipped, exit 0 once the bad ones are left out.
    assert main(["correct", *map(str, paths[:4]), "-o", str(out), "--quiet"]) == 0
    captured = capsys.readouterr()
    assert captured.err == "" and captured.out.count("skipped") == 4
    # In place on two workers of a local cluster, the reasons in the command's words.
    assert main(["correct", str(paths[2]), str(paths[3]), "--in-place", "--workers", "2"]) == 0
    assert main(["correct", str(paths[2]), str(paths[3]), "--in-place"]) == 0
    assert "pass --redo" in capsys.readouterr().out
    assert main(["correct", str(paths[2]), str(paths[3])]) == 1
    assert "give -o/--output OUTDIR/" in capsys.readouterr().err
    assert main(["correct", str(paths[2]), str(paths[3]), "-o", str(out), "--in-place"]) == 1
    assert "exclude each other" in capsys.readouterr().err
