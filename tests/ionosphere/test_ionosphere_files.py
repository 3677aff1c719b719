# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""IONEX files: plain, gzip and Unix compress, coverage, and every refusal, offline."""

import gzip
import shutil
import socket
import subprocess
import sys

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.time import Time
from helpers import import_or_skip

import_or_skip("spinifex", "ionosphere", "FEEDROT_REQUIRE_SPINIFEX")

from unlzw_cython import unlzw  # noqa: E402  (a dependency of spinifex)

from astropy_feedrot.ionosphere import Ionosphere, IonosphereError, sample_ionex  # noqa: E402

WSRT = EarthLocation.from_geodetic(6.60 * u.deg, 52.91 * u.deg, 16 * u.m)
CRAB = SkyCoord("05h34m31.94s +22d00m52.2s")
# The Crab is above WSRT's horizon from 15:00 to 06:00 UTC in January.
EVENING = Time("2020-01-08T18:00") + np.arange(0, 4 * 3600, 600) * u.s


@pytest.fixture(autouse=True)
def no_network(monkeypatch):
    """Any attempt to open a connection fails the test: everything here is offline."""
    def refuse(*args, **kwargs):
        raise AssertionError(f"network access attempted: {args}")
    monkeypatch.setattr(socket.socket, "connect", refuse)
    monkeypatch.setattr(socket, "create_connection", refuse)


@pytest.fixture(scope="module")
def plain_text():
    """CODE's map of 2020 January 8, decompressed from the shipped .Z file."""
    return unlzw(sample_ionex("codg0080.20i.Z")[0].read_bytes())


def reference_rm():
    # Reference: the file spinifex ships (.Z), read by spinifex.
    return Ionosphere.from_ionex(sample_ionex("codg0080.20i.Z")).rotation_measure(
        WSRT, CRAB, EVENING)


def test_plain_and_gzip_files_give_the_same_numbers(tmp_path, plain_text):
    expected = reference_rm()
    plain = tmp_path / "codg0080.20i"
    plain.write_bytes(plain_text)
    packed = tmp_path / "codg0080.20i.gz"
    packed.write_bytes(gzip.compress(plain_text))
    for path in (plain, packed, str(packed)):
        rm = Ionosphere.from_ionex(path).rotation_measure(WSRT, CRAB, EVENING)
        np.testing.assert_array_equal(rm.value, expected.value)


def test_unix_compress_file_made_here(tmp_path, plain_text):
    ncompress = pytest.importorskip("ncompress")
    path = tmp_path / "CODG0080.20I.Z"
    path.write_bytes(ncompress.compress(plain_text))
    rm = Ionosphere.from_ionex([path]).rotation_measure(WSRT, CRAB, EVENING)
    np.testing.assert_array_equal(rm.value, reference_rm().value)


def test_compressed_file_without_its_suffix_is_refused(tmp_path, plain_text):
    path = tmp_path / "codg0080.20i"
    path.write_bytes(gzip.compress(plain_text))
    with pytest.raises(IonosphereError, match=r"codg0080.20i is compressed \(gzip\) but its "
                       r"name does not end in .gz; .* rename it to codg0080.20i.gz"):
        Ionosphere.from_ionex(path)
    shutil.copy(sample_ionex("codg0080.20i.Z")[0], path)
    with pytest.raises(IonosphereError, match=r"compressed \(Unix compress\) .* end in .Z"):
        Ionosphere.from_ionex(path)


def test_missing_and_foreign_files(tmp_path):
    with pytest.raises(FileNotFoundError, match="IONEX file .*nothing.20i does not exist"):
        Ionosphere.from_ionex(tmp_path / "nothing.20i")
    text = tmp_path / "notes.20i"
    text.write_text("not a map\n")
    with pytest.raises(IonosphereError, match=r"notes.20i could not be read as an IONEX file "
                       r"\(IonexError: Could not parse ionex header\)"):
        Ionosphere.from_ionex(text)
    with pytest.raises(IonosphereError, match="no IONEX file given"):
        Ionosphere.from_ionex([])


def test_two_files_for_one_day_are_refused():
    with pytest.raises(IonosphereError, match="two IONEX files start on 2020-01-08: "
                       "codg0080.20i.Z and esag0080.20i.Z; give one file per day"):
        Ionosphere.from_ionex(sample_ionex("codg0080.20i.Z") + sample_ionex("esag0080.20i.Z"))


def test_epochs_outside_the_maps():
    iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
    late = Time(["2020-01-09T22:00", "2020-01-10T00:30", "2020-01-10T01:00"])
    with pytest.raises(IonosphereError,
                       match=r"^2 of 3 epochs \(2020-01-10T00:30:00 ... 2020-01-10T01:00:00 UTC\) "
                             r"lie outside the IONEX maps, which cover 2020-01-08T00:00 to "
                             r"2020-01-10T00:00 \(codg0080.20i.Z, codg0090.20i.Z\); give the "
                             "IONEX files of the days observed too"):
        iono.rotation_measure(WSRT, CRAB, late)
    # the last midnight is covered by the last map of the last file
    assert np.isfinite(iono.rotation_measure(WSRT, CRAB, Time("2020-01-10T00:00")))


def test_a_file_whose_maps_start_late():
    # CAS's map of 1999 January 1 runs from 01:00 to 23:00: nothing is extrapolated.
    iono = Ionosphere.from_ionex(sample_ionex("casg0010.99i.Z"))
    assert iono.coverage == [(Time("1999-01-01T01:00").mjd, Time("1999-01-01T23:00").mjd)]
    with pytest.raises(IonosphereError, match=r"1 of 2 epochs \(1999-01-01T00:30:00 UTC\) .* "
                       "cover 1999-01-01T01:00 to 1999-01-01T23:00"):
        iono.rotation_measure(WSRT, CRAB, Time(["1999-01-01T00:30", "1999-01-01T02:00"]))


def test_days_with_a_gap_between_them():
    both = Ionosphere.from_ionex(sample_ionex("codg0080.20i.Z") + sample_ionex("esag0100.20i.Z"))
    assert "2020-01-08T00:00 to 2020-01-09T00:00; 2020-01-10T00:00 to 2020-01-11T00:00" in \
        repr(both)
    epochs = Time(["2020-01-08T20:00", "2020-01-08T21:00", "2020-01-10T20:00",
                   "2020-01-10T21:00"])
    rm = both.rotation_measure(WSRT, CRAB, epochs)
    # Reference: each day's file alone on its own epochs (no node of the grid in the gap)
    first = Ionosphere.from_ionex(sample_ionex("codg0080.20i.Z"))
    third = Ionosphere.from_ionex(sample_ionex("esag0100.20i.Z"))
    np.testing.assert_allclose(rm.value[:2], first.rotation_measure(WSRT, CRAB, epochs[:2]).value,
                               rtol=1e-12)
    np.testing.assert_allclose(rm.value[2:], third.rotation_measure(WSRT, CRAB, epochs[2:]).value,
                               rtol=1e-12)
    with pytest.raises(IonosphereError, match=r"1 of 1 epochs \(2020-01-09T20:00:00 UTC\)"):
        both.rotation_measure(WSRT, CRAB, Time("2020-01-09T20:00"))


@pytest.mark.parametrize("height, error, message", [
    (450, TypeError, "height must be a length Quantity"),
    (450 * u.s, u.UnitsError, "height must be a length"),
    (10 * u.km, ValueError, "from 50 km to 20000 km, got 10.0 km"),
    ([300, 450] * u.km, ValueError, "must be one value"),
    (np.nan * u.km, ValueError, "got nan km"),
])
def test_bad_heights(height, error, message):
    with pytest.raises(error, match=message):
        Ionosphere.from_ionex(sample_ionex("codg0080.20i.Z"), height=height)


@pytest.mark.parametrize("step, error, message", [
    (60, u.UnitsError, "step must be a time Quantity"),
    (-1 * u.s, ValueError, "step must be one non-negative time"),
])
def test_bad_steps(step, error, message):
    with pytest.raises(error, match=message):
        Ionosphere.from_ionex(sample_ionex("codg0080.20i.Z"), step=step)


def test_sample_ionex():
    names = [path.name for path in sample_ionex()]
    assert "codg0080.20i.Z" in names and "IGS0OPSFIN_20243490000_01D_02H_GIM.INX.gz" in names
    assert "NeFull.2024169.gz" not in names and "test.ms.zip" not in names
    with pytest.raises(IonosphereError, match="no IONEX file that spinifex ships matches "
                       "'jplg\\*'; they are IGS0OPSFIN"):
        sample_ionex("jplg*")


def test_spinifex_stays_quiet(capfd):
    Ionosphere.from_ionex(sample_ionex("codg0080.20i.Z")).rotation_measure(WSRT, CRAB, EVENING)
    assert "INFO" not in capfd.readouterr().err


def test_missing_spinifex_names_the_extra():
    # A Python where spinifex cannot be imported (None in sys.modules blocks it).
    code = ("import sys; sys.modules['spinifex'] = None; "
            "from astropy_feedrot.ionosphere import Ionosphere; "
            "Ionosphere.from_ionex('codg0080.20i.Z')")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode != 0
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: rotation measures from IONEX maps need spinifex")
    assert "python -m pip install spinifex" in last and "[ionosphere]" in last


def test_warnings_are_not_turned_into_log_records():
    # spinifex's import calls logging.captureWarnings(True); the package undoes it.
    # (astropy's own logger replaces showwarning at its import: taken after it)
    code = ("import warnings; from astropy_feedrot.ionosphere.ionex import spinifex_modules; "
            "shown = warnings.showwarning; "
            "spinifex_modules(); print(warnings.showwarning is shown)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True)
    assert result.stdout.strip() == "True"
