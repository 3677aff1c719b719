# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""One default frame for every entry point that corrects or tabulates visibility data."""

import inspect
from pathlib import Path

from astropy_feedrot.cli import build_parser
from astropy_feedrot.visibilities import (
    correct_file,
    correct_fitsidi,
    correct_ms,
    correct_uvdata,
    feed_rotation_rows,
    feed_rotation_uvdata,
)


def test_every_entry_point_has_the_same_default_frame():
    # The CLI corrected in the apparent frame while the README's Python example passed
    # frame="icrs": one file, results 0.15 deg apart by entry point.
    defaults = {function.__name__: inspect.signature(function).parameters["frame"].default
                for function in (correct_uvdata, feed_rotation_uvdata, correct_fitsidi,
                                 correct_file, feed_rotation_rows, correct_ms)}
    correct = build_parser()._subparsers._group_actions[0].choices["correct"]
    defaults["feedrot correct"] = correct.get_default("frame")
    assert set(defaults.values()) == {"apparent"}, defaults


def test_readme_example_uses_the_default():
    readme = (Path(__file__).parent.parent.parent / "README.md").read_text()
    assert 'write_uvdata(correct_uvdata(uv), "vla_corrected.uvfits")' in readme
