# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Without an optional dependency, the command line names the extra to install."""

import subprocess
import sys
import warnings

import pytest

import astropy_feedrot.cli.stations as stations_cli
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
from astropy_feedrot.cli import main
from astropy_feedrot.data import sample_file

# sys.modules[name] = None makes "import name" raise ImportError, as when the package
# is not installed; the run is a separate interpreter, so this one keeps sgp4.
WITHOUT_SGP4 = ("import sys; sys.modules['sgp4'] = sys.modules['sgp4.api'] = None; "
                "from astropy_feedrot.cli import main; sys.exit(main(sys.argv[1:]))")


@pytest.mark.parametrize("argv", [
    ["demo", "--output-dir", "{dir}"],
    ["satellite", "DBR205", "--tle", "{tle}", "--start", "2023-01-25T08:00",
     "--stop", "2023-01-25T09:00", "--step", "30min"],
])
def test_missing_sgp4_names_the_extra(tmp_path, argv):
    # It said "internal error (ImportError: ...); please report it".
    tle = tmp_path / "gps.tle"
    tle.write_text("GPS SVN 76\n" + "\n".join(GPS_SVN76_TLE) + "\n")
    argv = [a.format(dir=tmp_path, tle=tle) for a in argv]
    run = subprocess.run([sys.executable, "-c", WITHOUT_SGP4, *argv], capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 1
    assert run.stderr == (
        "feedrot: error: TLE orbits need the sgp4 package, of the 'all' extra: python -m pip "
        "install sgp4 (or, in a clone of astropy_feedrot, python -m pip install -e '.[all]')\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["gps.tle"]


def test_each_warning_printed_once(tmp_path, capsys):
    # pyuvdata warns that the uvw_array does not match on reading and again on
    # writing the VLA sample; the command line printed it twice.
    output = tmp_path / "out.uvfits"
    assert main(["correct", str(sample_file("vla_day2_8chan.uvfits")), "-o", str(output),
                 "--quiet"]) == 0
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == len(set(lines)), lines
    assert all(line.startswith("feedrot: warning: ") for line in lines)


def test_library_deprecations_are_not_printed(capsys, monkeypatch):
    # numpy 1.24 under astropy 6.0 warned "Passing (type, 1) or '1type' as a synonym of
    # type is deprecated" on every run; such messages are for the libraries' developers.
    catalogue = stations_cli.station_catalogue

    def deprecated(*args, **kwargs):
        warnings.warn("Passing (type, 1) or '1type' as a synonym of type is deprecated",
                      DeprecationWarning)
        return catalogue(*args, **kwargs)

    monkeypatch.setattr(stations_cli, "station_catalogue", deprecated)
    assert main(["stations", "--network", "VLBA"]) == 0
    assert capsys.readouterr().err == ""
