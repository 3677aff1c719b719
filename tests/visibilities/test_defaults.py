# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""One default frame for every entry point that corrects or tabulates visibility data."""

import inspect
from pathlib import Path

from astropy_feedrot.cli import build_parser
from astropy_feedrot.visibilities import (
    Correction,
    correct_file,
    correct_files,
    correct_fitsidi,
    correct_ms,
    correct_processing_set,
    correct_uvdata,
    feed_rotation_rows,
    feed_rotation_uvdata,
)

CORRECTIONS = (correct_uvdata, correct_fitsidi, correct_file, correct_ms,
               correct_processing_set, correct_files)


def test_the_corrections_take_the_options_of_one_correction():
    """No correction has options of its own: each takes a Correction or its options, so
    that one default (and one check) serves them all."""
    for function in CORRECTIONS:
        parameters = inspect.signature(function).parameters
        assert not set(parameters) & {"frame", "direction", "vertical", "pole", "convention",
                                      "feeds", "mounts", "catalogue", "ionosphere", "redo"}
        assert parameters["correction"].default is None
        assert any(p.kind is p.VAR_KEYWORD for p in parameters.values()), function


def test_every_entry_point_has_the_same_default_frame():
    # The CLI corrected in the apparent frame while the README's Python example passed
    # frame="icrs": one file, results 0.15 deg apart by entry point.
    defaults = {function.__name__: inspect.signature(function).parameters["frame"].default
                for function in (feed_rotation_uvdata, feed_rotation_rows)}
    defaults["Correction"] = inspect.signature(Correction).parameters["frame"].default
    correct = build_parser()._subparsers._group_actions[0].choices["correct"]
    defaults["feedrot correct"] = correct.get_default("frame")
    assert set(defaults.values()) == {"apparent"}, defaults


def test_readme_example_uses_the_default():
    readme = (Path(__file__).parent.parent.parent / "README.md").read_text()
    assert 'write_uvdata(correct_uvdata(uv), "vla_corrected.uvfits")' in readme
