# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Outputs are never lost: exclusive create, all or none, checked before any work."""

import os
import re
from pathlib import Path

import pytest
from fitsidi_writer import write_fitsidi

import astropy_feedrot.cli.common
import astropy_feedrot.cli.data
import astropy_feedrot.visibilities.files
import astropy_feedrot.visibilities.fitsidi as fitsidi
from astropy_feedrot.cli import main
from astropy_feedrot.core.outputs import CommandError, publish, write_files
from astropy_feedrot.data import sample_file
from astropy_feedrot.visibilities import correct_file

VLA = sample_file("vla_day2_8chan.uvfits")
NATURAL = ["natural", "EFLSBERG", "--source", "13h31m08.29s +30d30m33.0s", "--start", "2023-01-01",
           "--stop", "2023-01-01T01:00", "--step", "20min"]


# --- publish -------------------------------------------------------------------------------


def test_publish_file_is_an_exclusive_create(tmp_path):
    (tmp_path / "a.tmp").write_text("mine")
    (tmp_path / "out.txt").write_text("theirs")
    with pytest.raises(FileExistsError, match=r"out\.txt' exists \(made by another program "
                       r"while this one ran\?\); nothing was replaced$"):
        publish(tmp_path / "a.tmp", tmp_path / "out.txt")
    assert (tmp_path / "out.txt").read_text() == "theirs"
    publish(tmp_path / "a.tmp", tmp_path / "out.txt", overwrite=True)
    assert (tmp_path / "out.txt").read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt"]


def test_publish_file_without_hard_links(tmp_path, monkeypatch):
    # A file system without hard links (FAT, some network mounts): os.link fails with
    # EPERM, and the name is reserved with O_EXCL instead.
    def no_links(*args):
        raise PermissionError(1, "Operation not permitted")

    monkeypatch.setattr(os, "link", no_links)
    (tmp_path / "a.tmp").write_text("mine")
    publish(tmp_path / "a.tmp", tmp_path / "out.txt")
    assert (tmp_path / "out.txt").read_text() == "mine"
    (tmp_path / "b.tmp").write_text("second")
    with pytest.raises(FileExistsError, match="nothing was replaced"):
        publish(tmp_path / "b.tmp", tmp_path / "out.txt")
    assert (tmp_path / "out.txt").read_text() == "mine"


def test_publish_directory(tmp_path):
    # A Measurement Set is a directory.
    for name, text in (("a", "first"), ("b", "second")):
        (tmp_path / name).mkdir()
        (tmp_path / name / "table.dat").write_text(text)
    publish(tmp_path / "a", tmp_path / "out.ms")
    with pytest.raises(FileExistsError, match="nothing was replaced"):
        publish(tmp_path / "b", tmp_path / "out.ms")
    assert (tmp_path / "out.ms" / "table.dat").read_text() == "first"
    publish(tmp_path / "b", tmp_path / "out.ms", overwrite=True)
    assert (tmp_path / "out.ms" / "table.dat").read_text() == "second"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.ms"]


# --- write_files ---------------------------------------------------------------------------


def test_write_files_refuses_a_file_made_meanwhile_all_or_none(tmp_path):
    one, two = tmp_path / "one.txt", tmp_path / "two.txt"

    def meanwhile():  # another program writes two.txt while this one runs
        two.write_text("theirs")

    with pytest.raises(CommandError, match=r"two\.txt' exists \(made by another program while "
                       r"this one ran\?\); nothing was replaced; add --overwrite to replace "
                       r"it$"):
        write_files([(one, lambda name: Path(name).write_text("1")),
                     (two, lambda name: Path(name).write_text("2"))], then=meanwhile)
    # one.txt, published first, is taken back: all or none, and nothing left behind.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["two.txt"]
    assert two.read_text() == "theirs"


def test_two_runs_into_one_output_do_not_both_succeed(tmp_path, capsys, monkeypatch):
    # The second run starts and finishes while the first is writing its table: the
    # second's table is kept and the first fails (it used to replace it silently).
    output = tmp_path / "out.ecsv"
    argv = NATURAL + ["-o", str(output)]
    writer = astropy_feedrot.cli.common.table_writer
    runs = []

    def racing_writer(table, fmt, step=None):
        write = writer(table, fmt, step)
        if not runs:
            runs.append(None)
            runs[0] = main(argv)  # the other run, from start to end
            table.meta["run"] = "first"
        return write

    monkeypatch.setattr(astropy_feedrot.cli.common, "table_writer", racing_writer)
    status = main(argv)
    err = capsys.readouterr().err
    assert runs == [0] and status == 1
    # The other run's line of success, then this one's error.
    assert re.fullmatch(r"feedrot: .*out\.ecsv: 4 rows of the feed rotation of .*\n"
                        r"feedrot: error: .*out\.ecsv' exists \(made by another program while "
                        r"this one ran\?\); nothing was replaced; add --overwrite to replace "
                        r"it\n", err), err
    assert "first" not in output.read_text()
    assert [p.name for p in tmp_path.iterdir()] == ["out.ecsv"]


# --- feedrot correct -----------------------------------------------------------------------


@pytest.fixture
def idi(tmp_path):
    path = tmp_path / "experiment.idifits"
    write_fitsidi(path, angles={0: (12.0, 102.0)})
    return path


@pytest.mark.parametrize("name, match", [
    ("out.uvfits", r"'.*out\.uvfits': a FITS-IDI input is corrected into a FITS-IDI copy "
                   r"\(there is no conversion to other formats\); give the output one of the "
                   r"extensions \.idifits, \.fitsidi, \.idi, \.fits, \.fit, \.fts or \.idiN "
                   r"\(\.IDI1\)$"),
    ("out.txt", r"'.*out\.txt': a FITS-IDI input is corrected into a FITS-IDI copy"),
])
def test_correct_fitsidi_output_format_checked_first(idi, tmp_path, capsys, monkeypatch, name,
                                                     match):
    # The FITS-IDI input was written, as FITS-IDI, into out.uvfits or out.txt.
    monkeypatch.setattr(astropy_feedrot.cli.data, "correct_file", None)  # no work is done
    assert main(["correct", str(idi), "-o", str(tmp_path / name)]) == 1
    err = capsys.readouterr().err
    assert re.match(r"feedrot: error: -o/--output: " + match, err.rstrip("\n")), err
    assert not (tmp_path / name).exists()


def test_correct_uvfits_output_format_checked_first(tmp_path, capsys, monkeypatch):
    # Refused only after the whole input was read, before.
    monkeypatch.setattr(astropy_feedrot.cli.data, "correct_file", None)  # no work is done
    assert main(["correct", str(VLA), "-o", str(tmp_path / "out.txt")]) == 1
    assert capsys.readouterr().err == (
        f"feedrot: error: -o/--output: cannot tell a format from the extension of "
        f"'{tmp_path / 'out.txt'}'; use one of .uvfits, .uvf, .uvh5, .h5, .hdf5, .ms, .uv, "
        ".miriad, .fits\n")


def test_two_corrections_into_one_output_do_not_both_succeed(idi, tmp_path, capsys,
                                                             monkeypatch):
    output = tmp_path / "out.idifits"
    argv = ["correct", str(idi), "-o", str(output), "--quiet"]
    correct = astropy_feedrot.cli.data.correct_file
    runs = []

    def racing(*args, **kwargs):
        if not runs:
            runs.append(None)
            runs[0] = main(argv)  # the other run, from start to end
        return correct(*args, **kwargs)

    monkeypatch.setattr(astropy_feedrot.cli.data, "correct_file", racing)
    status = main(argv)
    err = capsys.readouterr().err
    assert runs == [0] and status == 1
    assert "exists (made by another program while this one ran?); nothing was replaced" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["experiment.idifits", "out.idifits"]


# --- the library's writers ---------------------------------------------------------------


# fitsidi_writer gives WETTZ13S a Nasmyth focus the catalogue does not (on purpose).
@pytest.mark.filterwarnings("ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")
def test_correct_fitsidi_never_replaces_a_file_made_meanwhile(idi, tmp_path, monkeypatch):
    # The output is checked first (it does not exist), then appears while the copy is
    # corrected: the corrected copy is not published over it.
    output = tmp_path / "out.idifits"
    copy = fitsidi.copy_around

    def copy_and_race(*args, **kwargs):
        shift = copy(*args, **kwargs)
        output.write_text("theirs")
        return shift

    monkeypatch.setattr(fitsidi, "copy_around", copy_and_race)
    with pytest.raises(FileExistsError, match="made by another program while this one ran"):
        fitsidi.correct_fitsidi(idi, output)
    assert output.read_text() == "theirs"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["experiment.idifits", "out.idifits"]


@pytest.mark.parametrize("name", ["out.uvfits", "out.txt"])
def test_correct_file_refuses_a_fitsidi_output_of_another_format(idi, tmp_path, name):
    # correct_file wrote FITS-IDI into out.uvfits (and out.txt).
    with pytest.raises(ValueError, match=rf"'.*{name}': a FITS-IDI input is corrected into a "
                       "FITS-IDI copy"):
        correct_file(idi, tmp_path / name)
    assert not (tmp_path / name).exists()


def test_correct_file_checks_the_output_before_reading(tmp_path, monkeypatch):
    monkeypatch.setattr(astropy_feedrot.visibilities.files, "read_uvdata", None)  # never reached
    with pytest.raises(ValueError, match=r"cannot tell a format from the extension of "
                       r"'.*out\.txt'; use one of \.uvfits, \.uvf, \.uvh5"):
        correct_file(VLA, tmp_path / "out.txt")
