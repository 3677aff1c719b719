# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Every example of every ``--help`` runs as printed; ``feedrot --version``."""

import contextlib
import importlib.util
import io
import shlex
import shutil
import tarfile
from pathlib import Path

import pytest
from astropy import units as u
from astropy.table import QTable
from astropy.time import Time
from fitsidi_writer import write_fitsidi

from astropy_feedrot import __version__
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
from astropy_feedrot.cli import main
from astropy_feedrot.data import sample_file

DATA = Path(__file__).parent.parent / "data" / "uvdata"
COMMANDS = ["", "natural", "satellite", "baseline", "faraday", "demo", "stations", "coverage",
            "antennas", "correct", "rinex", "samples"]


def help_of(command):
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit) as stop:
        main(([command] if command else []) + ["--help"])
    assert stop.value.code == 0
    return out.getvalue()


def printed_examples():
    """(command, line) for every example line of every --help, as printed."""
    found = []
    for command in COMMANDS:
        text = help_of(command)
        assert "examples:\n" in text, command
        section = text.split("examples:\n", 1)[1]
        for line in section.splitlines():
            if not line.startswith("  feedrot"):
                break
            found.append((command or "feedrot", line.strip()))
    return found


EXAMPLES = printed_examples()


def test_examples_are_whole_lines():
    # Three examples of 'feedrot --help' ended in a backslash: pasted, they joined.
    assert len(EXAMPLES) >= 20
    for _, line in EXAMPLES:
        assert not line.endswith("\\"), line


def _add_model(ms):
    """A MODEL_DATA column (a sky model, as CASA's ft or setjy would leave): the DATA."""
    try:
        from casacore.tables import makecoldesc, maketabdesc, table
    except ImportError:  # the Measurement Set examples say so themselves
        return
    with table(str(ms), readonly=False, ack=False) as t:
        description = t.getcoldesc("DATA")
        description.pop("keywords", None)
        t.addcols(maketabdesc(makecoldesc("MODEL_DATA", description)),
                  {"TYPE": "TiledShapeStMan", "NAME": "TiledMODEL", "SPEC": {}})
        t.putcol("MODEL_DATA", t.getcol("DATA"))


@pytest.fixture
def files(tmp_path, monkeypatch):
    """The files the examples name, made from the samples, in the working directory."""
    (tmp_path / "gps.tle").write_text("GPS SVN 76\n" + "\n".join(GPS_SVN76_TLE) + "\n")
    shutil.copy(sample_file("sample.sp3"), tmp_path / "igs.sp3")
    shutil.copy(sample_file("vla_day2_8chan.uvfits"), tmp_path / "vla.uvfits")
    shutil.copy(sample_file("stations.ecsv"), tmp_path / "mine.ecsv")
    shutil.copy(sample_file("gnss_sample.rnx"), tmp_path / "obs.rnx")
    shutil.copy(sample_file("gnss_sample.sp3"), tmp_path / "gnss.sp3")
    write_fitsidi(tmp_path / "experiment.idifits", angles={0: (12.0, 102.0)})
    with tarfile.open(DATA / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms.tar.gz") as archive:
        archive.extractall(tmp_path, filter="data")
    (tmp_path / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms").rename(tmp_path / "vla.ms")
    _add_model(tmp_path / "vla.ms")
    # feedrot faraday: the IONEX files spinifex ships (where it is installed) and a table
    # of rotation measures for Effelsberg.
    if importlib.util.find_spec("spinifex") is not None:
        from astropy_feedrot.ionosphere import sample_ionex

        for path in sample_ionex("codg00[89]0.20i.Z"):
            shutil.copy(path, tmp_path / path.name)
    QTable({"time": Time(["2024-06-01T00:00", "2024-06-02T00:00"]),
            "rm": [0.5, 1.5] * u.rad / u.m**2,
            "antenna": ["EFLSBERG"] * 2}).write(tmp_path / "rm.ecsv")
    # feedrot correct --rm-table: one series of rotation measures for every antenna of vla.ms.
    QTable({"time": Time(["2009-01-01T00:00", "2020-01-01T00:00"]),
            "rm": [2.0, 2.0] * u.rad / u.m**2}).write(tmp_path / "vla_rm.ecsv")
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.mark.parametrize("command, line", EXAMPLES, ids=[line for _, line in EXAMPLES])
def test_every_help_example_runs_as_printed(files, capsys, command, line):
    if "--ionex" in line and importlib.util.find_spec("spinifex") is None:
        pytest.skip("IONEX maps need spinifex: python -m pip install -e '.[ionosphere]'")
    argv = shlex.split(line)
    assert argv[0] == "feedrot"
    status = main(argv[1:])
    err = capsys.readouterr().err
    assert status == 0, err


def test_version(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out == f"feedrot {__version__}\n"
