# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Aperture arrays are never corrected as dishes: every format refuses them with one
reason, whatever MOUNT, MNTSTA or mount_type says (the MWA's Birli writes ALT-AZ).

The files are real ones (the package's VLA samples, PAPER's UVFITS from pyuvdata's
test data) with the telescope name an aperture array's writer puts there.
"""
import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
from astropy.io import fits

from astropy_feedrot.cli import main
from astropy_feedrot.data import sample_file
from astropy_feedrot.stations.aperture_arrays import APERTURE_ARRAYS, aperture_array
from astropy_feedrot.stations.catalogue import default_catalogue
from astropy_feedrot.visibilities import (
    MSError,
    correct_file,
    correct_fitsidi,
    correct_ms,
    correct_uvdata,
    read_antennas,
    read_uvdata,
)
from astropy_feedrot.visibilities.resolve import mark_aperture_array, resolve_antennas

DATA = Path(__file__).parent.parent / "data" / "uvdata"
PAPER = DATA / "zen.2456865.60537.xy.uvcRREAAM.uvfits"
REASON = r"the telescope {!r} is an aperture array \({}\): its elements are fixed"


@pytest.mark.parametrize("name, description", [
    ("MWA", APERTURE_ARRAYS["MWA"]),
    ("mwa", APERTURE_ARRAYS["MWA"]),
    ("LOFAR", APERTURE_ARRAYS["LOFAR"]),
    ("LWA1", APERTURE_ARRAYS["LWA"]),
    ("LWA-SV", APERTURE_ARRAYS["LWA"]),
    ("OVRO_LWA", APERTURE_ARRAYS["OVROLWA"]),
    ("OVRO-LWA", APERTURE_ARRAYS["OVROLWA"]),
    ("HERA", APERTURE_ARRAYS["HERA"]),
    ("PAPER_SA", APERTURE_ARRAYS["PAPER"]),
    ("SKA-Low", APERTURE_ARRAYS["SKALOW"]),
    ("AAVS2", APERTURE_ARRAYS["AAVS"]),
    ("EDA2", APERTURE_ARRAYS["EDA"]),
    ("VLA", None), ("VLBA", None), ("ALMA", None), ("EVN", None), ("ATCA", None),
    ("MeerKAT", None), ("", None), (None, None),
])
def test_names(name, description):
    assert aperture_array(name, catalogue=False) == description


def test_catalogue_stations_fixed_to_the_ground():
    """A catalogue station whose mount is stationary (elements fixed to the ground)
    names an aperture array; a dish of the catalogue does not."""
    catalogue = default_catalogue()
    table = catalogue.table
    # A catalogue of its own: the MWA's row renamed, so that no name of the list matches.
    row = table[table["name"] == "MWA"]
    row["name"] = "TILES"
    path_table = row
    from astropy_feedrot.stations.catalogue import StationCatalogue
    own = StationCatalogue(path_table)
    assert aperture_array("TILES", catalogue=False) is None
    assert aperture_array("TILES", catalogue=own) == \
        "the catalogue's TILES, whose elements are fixed to the ground"
    assert aperture_array("EFLSBERG", catalogue=catalogue) is None


def test_mark_and_resolve_keep_the_other_arrays():
    from astropy_feedrot import get_antenna
    antennas = {0: get_antenna("VLA_W9"), 1: get_antenna("VLA_E18")}
    same, aperture = mark_aperture_array(antennas, ["VLA", ""])
    assert not aperture and same == antennas
    marked, aperture = mark_aperture_array(antennas, ["VLA", "HERA"])
    assert aperture and {a.problem for a in marked.values()} == {"aperture array"}
    assert marked[0].name == "VLA_W9" and marked[0].location == antennas[0].location
    resolved = resolve_antennas(antennas, telescope="HERA", mounts="catalogue")
    assert {a.problem for a in resolved.values()} == {"aperture array"}


def _ms_named(tmp_path, telescope, name="vla.ms"):
    casacore = pytest.importorskip("casacore.tables")
    ms = shutil.copytree(sample_file("vla_sim.ms"), tmp_path / name)
    with casacore.table(str(ms / "OBSERVATION"), readonly=False, ack=False) as t:
        for row in range(t.nrows()):
            t.putcell("TELESCOPE_NAME", row, telescope)
    return ms


def test_measurement_set_refused_in_every_route(tmp_path, capsys):
    """An MWA set as Birli writes it (MOUNT ALT-AZ, TELESCOPE_NAME MWA): refused in
    place, into a Measurement Set, into uvh5 and UVFITS, with the same reason; nothing
    is written."""
    ms = _ms_named(tmp_path, "MWA")
    reason = REASON.format("MWA", "the Murchison Widefield Array")
    antennas, _ = read_antennas(ms)
    assert {a.problem for a in antennas.values()} == {"aperture array"}
    with pytest.raises(MSError, match=r"4 antennas cannot be corrected: .*" + reason):
        correct_ms(ms)
    with pytest.raises(MSError, match=reason):
        correct_ms(ms, mounts="catalogue")
    for output in ("copy.ms", "copy.uvh5", "copy.uvfits"):
        with pytest.raises(ValueError, match=reason):
            correct_file(ms, tmp_path / output)
        assert not (tmp_path / output).exists()
    assert main(["correct", str(ms), "--in-place"]) == 1
    assert "is an aperture array" in capsys.readouterr().err
    assert main(["antennas", str(ms)]) == 0
    assert "'MWA' is an aperture array" in capsys.readouterr().out
    # Nothing was written: no CORRECTED_DATA column was added.
    casacore = pytest.importorskip("casacore.tables")
    with casacore.table(str(ms), ack=False) as t:
        assert "CORRECTED_DATA" not in t.colnames()


def test_fitsidi_refused(tmp_path):
    """A FITS-IDI file whose TELESCOP is LOFAR's: refused before anything is written."""
    source = tmp_path / "lofar.idifits"
    with fits.open(sample_file("difx_k08161.idifits")) as hdul:
        hdul[0].header["TELESCOP"] = "LOFAR"
        hdul.writeto(source)
    reason = REASON.format("LOFAR", "the Low-Frequency Array")
    with pytest.raises(ValueError, match=reason):
        correct_fitsidi(source, tmp_path / "out.idifits")
    with pytest.raises(ValueError, match=reason):
        correct_file(source, tmp_path / "out.idifits")
    assert not (tmp_path / "out.idifits").exists()
    assert [p.name for p in tmp_path.iterdir()] == ["lofar.idifits"]  # no partial copy
    antennas, _ = read_antennas(source)
    assert {a.problem for a in antennas.values()} == {"aperture array"}


def test_paper_uvfits_refused(tmp_path):
    """PAPER's own UVFITS (pyuvdata's test file, TELESCOP 'PAPER', mount_type fixed):
    refused as an aperture array, not corrected as stationary dipoles."""
    reason = REASON.format("PAPER", APERTURE_ARRAYS["PAPER"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's own complaints about the file
        antennas, _ = read_antennas(PAPER)
    assert {a.problem for a in antennas.values()} == {"aperture array"}
    with pytest.raises(ValueError, match=reason):
        correct_file(PAPER, tmp_path / "paper.uvh5")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's own complaints about the file
        uv = read_uvdata(PAPER)
    before = uv.data_array.copy()
    with pytest.raises(ValueError, match=reason):
        correct_uvdata(uv)
    assert np.array_equal(uv.data_array, before, equal_nan=True)
    uv.telescope.name = "HERA"
    with pytest.raises(ValueError, match=REASON.format("HERA", APERTURE_ARRAYS["HERA"])):
        correct_uvdata(uv)
