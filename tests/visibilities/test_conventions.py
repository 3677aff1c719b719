# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""convention='casa' is every choice CASA makes, and nothing else: the same bits
as vertical='geocentric', pole='casa' in every correction (its agreement with
CASA itself: tests/visibilities/test_casa.py, tests/visibilities/test_casa_real.py)."""

import shutil
from pathlib import Path

import numpy as np
import pytest

from astropy_feedrot.visibilities import correct_fitsidi
from astropy_feedrot.visibilities.poles import CONVENTIONS, convention_options

BL146 = Path(__file__).parent.parent / "data" / "real" / "BL146_1.trim.fits"


@pytest.mark.parametrize("convention, vertical, pole, expected", [
    ("rigorous", None, None, ("geodetic", "itrs")),
    ("casa", None, None, ("geocentric", "casa")),
    ("casa", "geodetic", None, ("geodetic", "casa")),  # given explicitly: replaces
    ("rigorous", None, "casa", ("geodetic", "casa")),
])
def test_convention_options(convention, vertical, pole, expected):
    assert convention_options(convention, vertical, pole) == expected


def test_conventions_are_the_documented_pairs():
    assert CONVENTIONS == {"rigorous": ("geodetic", "itrs"), "casa": ("geocentric", "casa")}


def test_an_unknown_convention():
    with pytest.raises(ValueError, match=r"convention must be one of \('rigorous', 'casa'\).* "
                       r"got 'aips'"):
        convention_options("aips")


def _flux(path):
    from astropy.io import fits

    with fits.open(path) as hdul:
        return np.array(hdul["UV_DATA"].data["FLUX"])


def test_casa_convention_is_its_two_options_bit_for_bit(tmp_path):
    correct_fitsidi(BL146, tmp_path / "convention.fits", convention="casa")
    correct_fitsidi(BL146, tmp_path / "options.fits", vertical="geocentric", pole="casa")
    correct_fitsidi(BL146, tmp_path / "rigorous.fits")
    convention, options = _flux(tmp_path / "convention.fits"), _flux(tmp_path / "options.fits")
    np.testing.assert_array_equal(convention, options)
    assert not np.array_equal(convention, _flux(tmp_path / "rigorous.fits"))


def test_an_unknown_convention_writes_nothing(tmp_path):
    with pytest.raises(ValueError, match="convention must be one of"):
        correct_fitsidi(BL146, tmp_path / "out.fits", convention="aips")
    assert not any(tmp_path.iterdir())


def test_ms_and_uvdata_take_the_convention(tmp_path):
    pytest.importorskip("casacore")
    pytest.importorskip("pyuvdata")
    from casacore.tables import table

    from astropy_feedrot.data import sample_file
    from astropy_feedrot.visibilities import correct_file, correct_ms, read_uvdata

    source = sample_file("vla_day2_8chan.uvfits")
    with pytest.warns(Warning):  # pyuvdata's uvw complaint about the sample
        correct_file(source, tmp_path / "a.uvh5", convention="casa")
        correct_file(source, tmp_path / "b.uvh5", vertical="geocentric", pole="casa")
        uvs = [read_uvdata(tmp_path / name) for name in ("a.uvh5", "b.uvh5")]
    np.testing.assert_array_equal(uvs[0].data_array, uvs[1].data_array)
    ms = tmp_path / "vla.ms"
    with pytest.warns(Warning):
        read_uvdata(source).write_ms(str(ms))
    twin = tmp_path / "twin.ms"
    shutil.copytree(ms, twin)
    correct_ms(ms, convention="casa")
    correct_ms(twin, vertical="geocentric", pole="casa")
    with table(str(ms), ack=False) as a, table(str(twin), ack=False) as b:
        np.testing.assert_array_equal(a.getcol("CORRECTED_DATA"), b.getcol("CORRECTED_DATA"))
