# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The module paths that moved to astropy_feedrot.visibilities still import, for one
release, with a DeprecationWarning that names the new place."""

import importlib
import sys

import pytest

import astropy_feedrot.visibilities as visibilities

MOVED = [
    ("astropy_feedrot.visibility_files", "astropy_feedrot.visibilities.files", "correct_file"),
    ("astropy_feedrot.uvdata", "astropy_feedrot.visibilities.uvdata", "correct_uvdata"),
    ("astropy_feedrot.rows", "astropy_feedrot.visibilities.rows", "feed_rotation_rows"),
    ("astropy_feedrot.io.fitsidi", "astropy_feedrot.visibilities.fitsidi", "correct_fitsidi"),
    ("astropy_feedrot.io.uvfits", "astropy_feedrot.visibilities.uvfits", "uvfits_antennas"),
    ("astropy_feedrot.io.antenna_tables", "astropy_feedrot.visibilities.antenna_tables",
     "writing_program"),
]


@pytest.mark.parametrize("old, new, name", MOVED)
def test_old_module_paths(old, new, name):
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=f"{old} moved to {new}"):
        module = importlib.import_module(old)
    assert getattr(module, name) is getattr(visibilities, name)


@pytest.mark.parametrize("name", ["fitsidi_antennas", "uvfits_antennas", "correct_fitsidi",
                                  "writing_program", "WritingProgram", "open_fits",
                                  "FITSFormatError"])
def test_old_names_in_io(name):
    import astropy_feedrot.io as io

    with pytest.warns(DeprecationWarning, match=f"astropy_feedrot.io.{name} moved to "
                                                f"astropy_feedrot.visibilities"):
        value = getattr(io, name)
    assert value is getattr(visibilities, name)
    with pytest.raises(AttributeError, match="has no attribute 'nothing'"):
        io.nothing  # noqa: B018
