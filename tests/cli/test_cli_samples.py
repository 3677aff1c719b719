# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot samples``: the shipped sample files, listed and found."""

import os

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
        size = os.path.getsize(sample_file(name)) / 1024
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
    status, out, err = run(capsys, "samples", "gps.tle")
    assert status == 1 and out == ""
    assert err == ("feedrot: error: no sample file 'gps.tle'; 'feedrot samples' lists them: "
                   + ", ".join(SAMPLES) + "\n")
