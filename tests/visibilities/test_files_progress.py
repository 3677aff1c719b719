# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The progress of correct_file for the files pyuvdata reads: read, corrected, written."""

import warnings

import numpy as np
import pytest
from astropy.io import fits

from astropy_feedrot.data import sample_file
from astropy_feedrot.visibilities import correct_file

pytest.importorskip("pyuvdata")

UVFITS = sample_file("vla_day2_8chan.uvfits")


def _correct(path, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's uvw warning on this sample
        return correct_file(UVFITS, path, **kwargs)


def test_progress_counts_the_read_the_chunks_and_the_write(tmp_path):
    calls = []
    _correct(tmp_path / "bar.uvfits", progress=lambda done, total: calls.append((done, total)))
    size = UVFITS.stat().st_size
    done = [d for d, _ in calls]
    assert {total for _, total in calls} == {3 * size}
    # The read at once, then the chunks of the correction, then the write at once.
    assert done[0] == size and done[-2] == 2 * size and done[-1] == 3 * size
    assert len(done) > 3 and done == sorted(done)
    # The same visibilities with and without progress.
    _correct(tmp_path / "plain.uvfits")
    with fits.open(tmp_path / "bar.uvfits") as a, fits.open(tmp_path / "plain.uvfits") as b:
        np.testing.assert_array_equal(a[0].data["DATA"], b[0].data["DATA"])


def test_a_bad_progress_is_refused_before_anything_is_read(tmp_path):
    with pytest.raises(TypeError, match=r"progress must be True, False or a callable "
                                        r"\(done, total\), got str"):
        _correct(tmp_path / "out.uvfits", progress="yes")
    assert list(tmp_path.iterdir()) == []
