# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The figures, drawn and read back: what they hold, not only that they draw.

Each test renders a figure (matplotlib's Agg canvas) and checks its lines,
their labels, colours and styles, the place of the legend and the titles.
"""

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import SkyCoord
from astropy.table import Table
from astropy.time import Time

pytest.importorskip("matplotlib")

import matplotlib  # noqa: E402

matplotlib.use("Agg")

from astropy_feedrot.applied.feed_rotation_tables import feed_rotation_table  # noqa: E402
from astropy_feedrot.applied.planning import feed_rotation_coverage, plot_coverage  # noqa: E402
from astropy_feedrot.applied.plotting import (  # noqa: E402
    line_styles,
    plot_baseline,
    plot_feed_rotation,
    unwrapped_degrees,
)
from astropy_feedrot.applied.simulations import gps_short_baseline  # noqa: E402
from astropy_feedrot.stations.catalogue import get_antenna, get_network  # noqa: E402

DAY = Time("2024-03-01T00:00") + np.arange(0, 24, 0.25) * u.hour


def _outside(fig, ax, legend):
    """Whether ``legend`` lies to the right of ``ax``, clear of its tracks."""
    fig.canvas.draw()
    return legend.get_window_extent().x0 >= ax.get_window_extent().x1


def _jumps(line):
    """The largest step (deg) between consecutive finite points of a drawn line."""
    y = np.asarray(line.get_ydata(), dtype=float)
    steps = np.abs(np.diff(y))
    return np.nanmax(steps, initial=0.0)


def test_line_styles_distinct_for_a_large_network():
    styles = line_styles(40)
    assert len(set(styles)) == 40
    # The 11th station: the first colour again, in another style.
    assert styles[10][0] == styles[0][0] and styles[10][1] != styles[0][1]


def test_unwrapped_degrees_follows_the_angle_across_180():
    wrapped = np.array([150, 179, -179, -150, np.nan, np.nan, 179, -179]) * u.deg
    np.testing.assert_allclose(unwrapped_degrees(wrapped),
                               [150, 179, 181, 210, np.nan, np.nan, 179, 181])
    # A closed form: a steadily turning angle, wrapped, comes back unwrapped.
    turning = np.linspace(-170, 900, 200)
    np.testing.assert_allclose(unwrapped_degrees(((turning + 180) % 360 - 180) * u.deg),
                               turning, atol=1e-9)
    assert np.isnan(unwrapped_degrees([np.nan, np.nan] * u.deg)).all()


@pytest.fixture(scope="module")
def eht_coverage():
    # 3C 279 (dec -6 deg), which the South Pole never sees above the limit (its
    # elevation there is 6 deg), and a source at dec +70 deg, which no southern
    # station sees: the EHT's eleven stations. (No source is above the limit at
    # both the South Pole and Greenland: the worst range of the whole network
    # is NaN for every target, which the titles printed as 'nan'.)
    sources = {"3C279": SkyCoord("12h56m11.17s -05d47m21.5s"),
               "NORTH": SkyCoord("06h00m00s +70d00m00s")}
    return feed_rotation_coverage(get_network("EHT"), sources, Time("2024-03-01"),
                                  Time("2024-03-02"), 30 * u.min, tracks=True)


def test_coverage_of_eleven_stations(eht_coverage):
    fig = plot_coverage(*eht_coverage)
    axes = fig.axes
    assert len(axes) == 2
    for ax in axes:
        looks = [(line.get_color(), line.get_linestyle()) for line in ax.get_lines()]
        assert len(looks) == 11 and len(set(looks)) == 11  # ALMA and SPT told apart
    legend = axes[0].get_legend()
    assert [text.get_text() for text in legend.get_texts()] == [
        "ALMA", "APEX", "GREENLAND", "JCMT", "KP12", "LMT", "NOEMA", "PICOVEL", "SMA", "SMT",
        "SPT"]
    assert _outside(fig, axes[0], legend)
    titles = [ax.get_title() for ax in axes]
    assert not any("nan" in title.lower() for title in titles)
    assert titles[0] == "3C279: never above the limit at SPT"
    assert titles[1].startswith("NORTH: never above the limit at ")
    assert titles[1].endswith(" other stations")  # the southern stations


def test_coverage_titles_of_seen_and_unseen_targets():
    sources = {"SOUTH": SkyCoord("00h00m00s -80d00m00s"),
               "3C84": SkyCoord("03h19m48.16s +41d30m42.1s")}
    result = feed_rotation_coverage([get_antenna("EFLSBERG"), get_antenna("YEBES40M")],
                                    sources, Time("2024-03-01"), Time("2024-03-02"),
                                    1 * u.hour, tracks=True)
    titles = [ax.get_title() for ax in plot_coverage(*result).axes]
    assert titles[0] == "SOUTH: never above the limit at any station"
    assert titles[1].startswith("3C84: worst range ") and titles[1].endswith(" deg (EFLSBERG)")


def test_natural_source_has_no_transmitter_line():
    # At the South Pole the feed rotation of an alt-az antenna stays near 180 deg
    # (the parallactic angle hardly changes there): the wrapped receiver term
    # flickers between +180 and -180 deg; the figure draws it without the jumps.
    table = feed_rotation_table(get_antenna("SPT"), SkyCoord("05h00m00s -60d00m00s"), DAY)
    assert table.meta["natural"] is True
    assert np.nanmax(np.abs(np.diff(table["receiver"].quantity.to_value(u.deg)))) > 300
    fig = plot_feed_rotation(table)
    top, bottom = fig.axes
    lines = bottom.get_lines()
    assert [line.get_label() for line in lines] == ["feed rotation = receiver term (continuous)"]
    assert _jumps(lines[0]) < 1
    assert _outside(fig, bottom, bottom.get_legend())


def test_satellite_terms_unwrapped_and_visible():
    table = gps_short_baseline(step=10 * u.min)
    assert table.meta["natural"] is False
    fig = plot_baseline(table)
    for ax, name in zip(fig.axes[:2], table.meta["antennas"]):
        lines = ax.get_lines()
        assert [line.get_label() for line in lines] == [
            "total (continuous)", "transmitter term", "receiver term"]
        total, transmitter, receiver = lines
        assert total.get_linewidth() > receiver.get_linewidth()  # not hidden under a term
        assert receiver.get_linestyle() != total.get_linestyle()
        for line in lines:
            assert _jumps(line) < 180
        assert _outside(fig, ax, ax.get_legend())
    # One antenna as a feed_rotation_table: the same three lines.
    name = table.meta["antennas"][0]
    single = Table({"time": table["time"],
                    **{column: table[f"{name}_{column}"]
                       for column in ("elevation", "transmitter", "receiver", "continuous")}})
    labels = [line.get_label() for line in plot_feed_rotation(single).axes[1].get_lines()]
    assert labels == ["total (continuous)", "transmitter term", "receiver term"]


def test_table_without_meta_judged_by_its_transmitter_term():
    table = feed_rotation_table(get_antenna("YEBES40M"), SkyCoord("03h19m48.16s +41d30m42.1s"),
                                DAY[:20])
    del table.meta["natural"]
    labels = [line.get_label() for line in plot_feed_rotation(table).axes[1].get_lines()]
    assert labels == ["feed rotation = receiver term (continuous)"]


def test_natural_transmitter_term_zero_where_defined_nan_below_the_limit():
    # Eq 21 is zero for a natural source; below the elevation limit every angle
    # of feed rotation is NaN, the transmitter term too (not a 0 for a source unseen).
    table = feed_rotation_table(get_antenna("YEBES40M"), SkyCoord("03h19m48.16s +41d30m42.1s"),
                                DAY, min_elevation=30 * u.deg)
    transmitter = table["transmitter"].quantity.to_value(u.deg)
    below = table["elevation"].quantity < 30 * u.deg
    assert below.any() and (~below).any()
    assert np.isnan(transmitter[below]).all()
    assert (transmitter[~below] == 0).all() and not np.signbit(transmitter[~below]).any()
