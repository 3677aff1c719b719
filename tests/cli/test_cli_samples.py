# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot samples``: the shipped sample files, listed and found."""

import os

import pytest

from astropy_feedrot.cli import main
from astropy_feedrot.data import DESCRIPTIONS, SAMPLES, sample_file


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_list_says_what_each_is_and_where(capsys):
    status, out, err = run(capsys, "samples")
    lines = out.splitlines()
    assert status == 0 and err == ""
    assert [line.split()[0] for line in lines[:-1]] == list(SAMPLES)
    for name, line in zip(SAMPLES, lines):
        assert line.endswith(DESCRIPTIONS[name])
        path = sample_file(name)
        files = [path] if path.is_file() else [p for p in path.rglob("*") if p.is_file()]
        size = sum(f.stat().st_size for f in files) / 1024
        assert f"{size:.1f} KiB" in line
    assert lines[-1] == f"in {sample_file(SAMPLES[0]).parent}"


def test_a_path_to_give_another_command(capsys, tmp_path):
    paths = {}
    for name in ("gnss_sample.rnx", "gnss_sample.sp3"):
        status, out, _ = run(capsys, "samples", name)
        assert status == 0 and out == f"{sample_file(name)}\n"
        paths[name] = out.strip()
    # As a shell would: feedrot rinex "$(feedrot samples gnss_sample.rnx)" ...
    assert main(["rinex", paths["gnss_sample.rnx"], "--sp3", paths["gnss_sample.sp3"], "-o",
                 str(tmp_path / "corrected.rnx")]) == 0
    assert (tmp_path / "corrected.rnx").stat().st_size > 0


def test_an_unknown_sample(capsys):
    status, out, err = run(capsys, "samples", "gps.tl")
    assert status == 1 and out == ""
    assert err == ("feedrot: error: no sample file 'gps.tl'; 'feedrot samples' lists them: "
                   + ", ".join(SAMPLES) + "\n")


def test_the_measurement_set_is_listed_with_its_whole_size(capsys):
    # A Measurement Set is a directory: its size is that of its files (618 kB), not the
    # 4 kB of the directory entry.
    _, out, _ = run(capsys, "samples")
    (line,) = [line for line in out.splitlines() if line.startswith("vla_sim.ms ")]
    assert float(line.split()[1]) > 500


@pytest.mark.parametrize("name", ["gps.tle", "vla_sim.ms"])
def test_copy_here_to_change_it(capsys, tmp_path, monkeypatch, name):
    monkeypatch.chdir(tmp_path)
    source = sample_file(name)
    source_files = sorted(p.relative_to(source) for p in source.rglob("*")) if \
        source.is_dir() else []
    status, out, err = run(capsys, "samples", name, "--copy")
    assert status == 0 and err == "" and out == f"{name}\n"
    copy = tmp_path / name
    if source.is_dir():
        assert sorted(p.relative_to(copy) for p in copy.rglob("*")) == source_files
        assert (copy / "table.dat").read_bytes() == (source / "table.dat").read_bytes()
    else:
        assert copy.read_bytes() == source.read_bytes()
    # Again: refused, the copy (maybe changed) kept; --overwrite replaces it.
    status, out, err = run(capsys, "samples", name, "--copy")
    assert status == 1 and out == ""
    assert err == (f"feedrot: error: {name} exists in {tmp_path}; remove it, work on it as it "
                   "is, or pass --overwrite to replace it with the sample\n")
    assert run(capsys, "samples", name, "--copy", "--overwrite")[:2] == (0, f"{name}\n")


def test_copy_a_read_only_sample_gives_a_writable_copy(capsys, tmp_path, monkeypatch):
    # An installed package may be read-only; the copy is the user's to change.
    monkeypatch.chdir(tmp_path)
    assert run(capsys, "samples", "vla_sim.ms", "--copy")[0] == 0
    for path in (tmp_path / "vla_sim.ms").rglob("*"):
        assert os.access(path, os.W_OK), path


def test_copy_needs_a_name(capsys):
    status, out, err = run(capsys, "samples", "--copy")
    assert status == 1 and out == ""
    assert err == ("feedrot: error: --copy copies one sample: give its name ('feedrot samples' "
                   "lists them)\n")
