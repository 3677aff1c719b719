# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The progress of feed_rotation_coverage: the grid, each antenna, the series."""

import astropy.units as u
import numpy as np
import pytest
from astropy.coordinates import SkyCoord
from astropy.time import Time

from astropy_feedrot.applied.planning import feed_rotation_coverage
from astropy_feedrot.stations.catalogue import get_antenna

SOURCES = {"3C84": SkyCoord("03h19m48.16s +41d30m42.1s"),
           "3C286": SkyCoord("13h31m08.29s +30d30m33.0s")}
SPAN = (Time("2024-03-01T00:00"), Time("2024-03-02T00:00"), 30 * u.min)


def test_progress_steps_and_the_same_table():
    antennas = [get_antenna(name) for name in ("EFLSBERG", "YEBES40M", "WETTZ13S")]
    calls = []
    with_progress = feed_rotation_coverage(antennas, SOURCES, *SPAN,
                                           progress=lambda done, total: calls.append(
                                               (done, total)))
    # The grid, each of the three antennas, then the continuous series.
    assert calls == [(k, 5) for k in range(1, 6)]
    without = feed_rotation_coverage(antennas, SOURCES, *SPAN)
    for name in without.colnames:
        np.testing.assert_array_equal(with_progress[name], without[name])


def test_a_bad_progress_is_refused():
    with pytest.raises(TypeError, match=r"progress must be True, False or a callable "
                                        r"\(done, total\), got list"):
        feed_rotation_coverage([get_antenna("EFLSBERG")], SOURCES, *SPAN, progress=[])
