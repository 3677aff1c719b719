# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""UVFITS antenna tables, as casacore, pyuvdata and AIPS write them.

References: the tables are written by ``fitsidi_writer.write_uvfits_an`` from
the writers' code (casacore ``MSFitsOutput.cc``: ORIGIN 'casacore', ARRAYX/Y/Z
= 0, absolute STABXYZ; pyuvdata ``uvfits.py``: HISTORY 'pyuvdata version',
HASMNT, STABXYZ rotated by the array longitude about the array centre). The
positions must come back as the catalogue's, the mounts as the writers'
codes mean them (casacore ``MSFitsOutput.cc`` per version, pyuvdata
``utils/antenna.py``).
"""

from pathlib import Path

import numpy as np
import pytest
from astropy import units as u
from fitsidi_writer import station_xyz, write_uvfits_an

from astropy_feedrot import AltAzMount, BeamWaveguideFocus, StationaryMount
from astropy_feedrot.antennas.receptors import Receptors
from astropy_feedrot.visibilities import FITSFormatError, uvfits_antennas, writing_program

VLA_CENTRE = [-1601185.4, -5041977.5, 3554875.9]


def xyz_of(antenna):
    return antenna.location.get_itrs().cartesian.xyz.to_value(u.m)


def test_casacore_37_reads_6_as_beam_waveguide(tmp_path):
    path = tmp_path / "c.uvfits"
    # A 9 occurs (SPACE-HALCA/unknown in 3.7 and later only), so the era is known.
    write_uvfits_an(path, program="casacore", mntsta=(6, 9, 0),
                    stations=("FD-VLBA", "EFLSBERG", "WETTZ13S"),
                    pola=((0, 0), (0, 0), (0, 0)))
    assert writing_program(path)[:2] == ("casacore", "fits-idi:casacore")
    with pytest.raises(ValueError, match=r"antenna 2 \(EFLSBERG\): 9 .*SPACE-HALCA"):
        uvfits_antennas(path)


def test_casacore_beam_waveguide_with_software(tmp_path):
    path = tmp_path / "c.uvfits"
    write_uvfits_an(path, program="casacore", mntsta=(6, 0))
    antennas = uvfits_antennas(path, software="fits-idi:casacore")
    assert antennas[1].mount == AltAzMount()
    assert antennas[1].focus == BeamWaveguideFocus("right")


def test_casacore_of_unknown_era_refuses_6(tmp_path):
    path = tmp_path / "c.uvfits"
    write_uvfits_an(path, program="casacore", mntsta=(6, 4))
    program = writing_program(path)
    assert program.program == "casacore" and program.software is None
    with pytest.raises(ValueError, match=r"antenna 1 \(FD-VLBA\): MNTSTA 6 cannot be read.*"
                                         r"'fits-idi:casacore<3.7' \(3.2-3.6\)"):
        uvfits_antennas(path)
    # casacore 3.2-3.6: 6 is BIZARRE, never a beam waveguide.
    with pytest.raises(ValueError, match="'BIZARRE' mount, not for a beam waveguide"):
        uvfits_antennas(path, software="fits-idi:casacore<3.7")


def test_casacore_absolute_positions_and_receptors(tmp_path):
    path = tmp_path / "c.uvfits"
    write_uvfits_an(path, program="casacore", mntsta=(0, 0), pola=((3.0, -4.0), (0.0, 0.0)))
    antennas = uvfits_antennas(path)
    np.testing.assert_allclose(xyz_of(antennas[1]), station_xyz("FD-VLBA"), atol=1e-6)
    assert antennas[1].receptors == Receptors("RL", [3.0, -4.0] * u.deg)
    assert antennas[2].name == "EFLSBERG"


def test_pyuvdata_rotated_positions_and_fixed_mount(tmp_path):
    path = tmp_path / "p.uvfits"
    stations = ("FD-VLBA", "EFLSBERG")
    write_uvfits_an(path, program="pyuvdata", mntsta=(7, 0), centre=VLA_CENTRE,
                    polty=("X", "Y"), pola=((90.0, 0.0), (45.0, -45.0)), stations=stations)
    assert writing_program(path)[:2] == ("pyuvdata", "fits-idi:pyuvdata")
    antennas = uvfits_antennas(path)
    # pyuvdata's ECEF_from_rotECEF undoes the rotation the writer applied.
    for k, name in enumerate(stations, start=1):
        np.testing.assert_allclose(xyz_of(antennas[k]), station_xyz(name), atol=1e-6)
    assert antennas[1].mount == StationaryMount()  # pyuvdata 7 = 'fixed'
    assert antennas[2].receptors == Receptors("XY", [45.0, -45.0] * u.deg)


def test_pyuvdata_without_hasmnt_is_refused(tmp_path):
    path = tmp_path / "p.uvfits"
    write_uvfits_an(path, program="pyuvdata", mntsta=(0, 0), centre=VLA_CENTRE, hasmnt=None)
    assert writing_program(path)[:3] == ("pyuvdata", None, ())
    with pytest.raises(ValueError, match="MNTSTA 0 cannot be read: .*placeholders"):
        uvfits_antennas(path)
    assert uvfits_antennas(path, software="fits-idi:pyuvdata")[1].mount == AltAzMount()


@pytest.mark.parametrize("program", ["aips", "unknown"])
def test_aips_and_unknown_writers(tmp_path, program):
    path = tmp_path / "a.uvfits"
    write_uvfits_an(path, program=program, mntsta=(0, 5))
    assert writing_program(path)[:3] == (program, None, (0, 1, 2, 3, 4, 5))
    assert uvfits_antennas(path)[2].focus.handedness == "left"
    write_uvfits_an(path, program=program, mntsta=(0, 6))
    with pytest.raises(ValueError, match="MNTSTA 6 cannot be read.*'fits-idi:difx'"):
        uvfits_antennas(path)


@pytest.mark.parametrize("kwargs, match", [
    (dict(centre=VLA_CENTRE, program="casacore"), "ARRAYX = ARRAYY = ARRAYZ = 0"),
    (dict(frame="MCMF"), "column FRAME"),
    (dict(frame=None, telescope="VLA"), "without one, a VLA file"),
    (dict(xyzhand="SIDEWAYS"), "XYZHAND"),
    (dict(extra_an={"ARRAYY": "abc"}), "column ARRAYY: expected a number"),
])
def test_position_errors(tmp_path, kwargs, match):
    path = tmp_path / "bad.uvfits"
    write_uvfits_an(path, **kwargs)
    with pytest.raises(FITSFormatError, match=match):
        uvfits_antennas(path)


def test_receptor_errors(tmp_path):
    path = tmp_path / "bad.uvfits"
    write_uvfits_an(path, polty=("X", "Y"), pola=((0.0, 0.0), (0.0, 90.0)))
    with pytest.raises(ValueError, match=r"antenna 1: the linear receptors 'XY' are parallel"):
        uvfits_antennas(path)


def test_no_antenna_table(tmp_path):
    from astropy.io import fits

    path = tmp_path / "empty.uvfits"
    fits.PrimaryHDU().writeto(path)
    with pytest.raises(FITSFormatError, match="an ARRAY_GEOMETRY table .* or an 'AIPS AN'"):
        writing_program(path)
    with pytest.raises(FITSFormatError, match="table AIPS AN: expected the AIPS AN table"):
        uvfits_antennas(path)


def test_bad_arguments(tmp_path):
    path = tmp_path / "c.uvfits"
    write_uvfits_an(path)
    with pytest.raises(ValueError, match="vertical"):
        uvfits_antennas(path, vertical="up")
    with pytest.raises(ValueError, match="software must be a MNTSTA convention"):
        uvfits_antennas(path, software=3)


# ------------------------------------------------------------------ real files

DATA = Path(__file__).parent.parent / "data" / "uvdata"


def test_real_aips_vlba_file():
    # tests/data/uvdata/README.md: AIPS-written VLBA file from pyuvdata's test data.
    path = DATA / "mojave.uvfits"
    assert writing_program(path).program == "aips"
    antennas = uvfits_antennas(path)
    names = [a.name for a in antennas.values()]
    assert names == ["BR", "FD", "HN", "KP", "LA", "MK", "NL", "OV", "PT", "SC"]
    assert all(a.mount == AltAzMount() and a.receptors == Receptors("RL") for a in
               antennas.values())
    # Fort Davis within 1 m of the paper's Table 1 position (different epochs
    # and solutions, 2006 against the paper's).
    fd = antennas[names.index("FD") + 1]
    assert np.linalg.norm(xyz_of(fd) - station_xyz("FD-VLBA")) < 1.0


def test_real_casacore_evla_file():
    # tests/data/uvdata/README.md: CASA exportuvfits of EVLA data.
    path = DATA / "day2_TDEM0003_10s_norx_1src_1spw_2ints.uvfits"
    assert writing_program(path)[:2] == ("casacore", "fits-idi:casacore")
    antennas = uvfits_antennas(path)
    assert len(antennas) == 19
    assert antennas[1].name == "W09"
    # An empty POLTYB: completed from POLTYA (Receptors.paired), as pyuvdata reads it.
    assert antennas[1].receptors == Receptors("RL", [0, 0] * u.deg)
    # The VLA's antennas lie within 25 km of its centre (the VLA_CENTRE above).
    assert all(np.linalg.norm(xyz_of(a) - VLA_CENTRE) < 25e3 for a in antennas.values())
