# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""EarthOrientation, the epochs object, against ERFA and astropy at every epoch.

References: ERFA's ``era00`` and ``gmst82`` at astropy's UT1, astropy's CIRS to
ITRS transformation, `astropy_feedrot.transmitters.nominal_attitude.sun_position` (astropy's
ephemeris and frames), and the structure of the package's own source files.
"""

import pathlib

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import CIRS, ITRS, CartesianRepresentation, EarthLocation, SkyCoord
from astropy.time import Time
from helpers import SITES
from hypothesis import given, strategies as st

import astropy_feedrot
from astropy_feedrot import conf
from astropy_feedrot.earth.frames import source_direction
from astropy_feedrot.earth.orientation import EarthOrientation
from astropy_feedrot.transmitters.attitude_interface import interpolated_sun_position, sun_position

PACKAGE = pathlib.Path(astropy_feedrot.__file__).parent


def series(start, step, count):
    return Time(start, scale="utc") + np.arange(count) * step


#: Epochs that take each road through EarthOrientation: dense ones (polynomial
#: cells), hourly ones (daily ERFA nodes), a few (ERFA at the epochs), sparse
#: ones over years, a leap second, and other time scales.
EPOCHS = {
    "dense": series("2023-01-25T00:00", 7 * u.s, 6000),
    "hourly": series("2022-06-01T00:00", 1 * u.hour, 2000),
    "few": series("2023-01-25T00:00", 1 * u.min, 3),
    "scalar": Time("2023-01-25T17:31:07.25"),
    "sparse": Time("2012-01-01") + np.sort(np.random.default_rng(2).uniform(0, 3650, 50)) * u.day,
    # Not at 00:00:00.0 after the leap second: astropy's Time arithmetic gives that
    # epoch as jd2 = 0.5 - 2e-16, where astropy's UT1 jumps 1 s ahead (UT1 - UTC of
    # the new day with TAI - UTC of the old one) and falls back half a second later.
    "leap second": series("2016-12-31T23:59:00.25", 0.5 * u.s, 240),
    "tt": series("2023-01-25T00:00", 9 * u.s, 3000).tt,
    "tdb": series("2023-01-25T00:00", 9 * u.s, 3000).tdb,
}


def angle_between(a, b):
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


def wrapped(a):
    return np.angle(np.exp(1j * a))


@pytest.mark.parametrize("name", list(EPOCHS))
def test_rotation_angles_against_erfa(name):
    # Reference: ERFA at astropy's UT1 of each epoch.
    times = EPOCHS[name]
    orientation = EarthOrientation(times)
    ut1 = times.ravel().ut1
    assert orientation.era.shape == (times.size,)
    assert np.abs(wrapped(orientation.era - erfa.era00(ut1.jd1, ut1.jd2))).max() < 1e-12
    assert np.abs(wrapped(orientation.gmst82 - erfa.gmst82(ut1.jd1, ut1.jd2))).max() < 1e-12


@pytest.mark.parametrize("name", list(EPOCHS))
def test_cirs_to_itrs_against_astropy(name):
    # Reference: astropy's CIRS -> ITRS transformation (geocentric), at every epoch.
    times = EPOCHS[name].ravel()
    rng = np.random.default_rng(7)
    cirs = rng.normal(size=(times.size, 3)) * 7.0e6
    rep = CartesianRepresentation(np.moveaxis(cirs, -1, 0) * u.m)
    reference = CIRS(rep, obstime=times).transform_to(ITRS(obstime=times))
    reference = np.moveaxis(reference.cartesian.xyz.to_value(u.m), 0, -1)
    result = EarthOrientation(times).cirs_to_itrs(cirs)
    assert np.abs(result - reference).max() < 1e-5  # 10 um at 20 000 km: 1e-4 mas


@pytest.mark.parametrize("name", list(EPOCHS))
def test_sun_against_sun_position(name):
    # Reference: attitude.sun_position, astropy's ephemeris and frames at every epoch.
    times = EPOCHS[name]
    sun = interpolated_sun_position(EarthOrientation(times))
    exact = sun_position(times).reshape(-1, 3)
    assert sun.shape == exact.shape
    assert angle_between(sun, exact).max() < 1e-11
    assert np.abs(np.linalg.norm(sun, axis=-1) / np.linalg.norm(exact, axis=-1) - 1).max() < (
        1e-11)


@pytest.mark.parametrize("name", ["dense", "hourly", "few", "sparse"])
def test_interpolate_reproduces_polynomials(name):
    # The nodes are TT instants and interpolate() is exact for polynomials of low degree.
    orientation = EarthOrientation(EPOCHS[name])
    nodes = orientation.nodes
    assert nodes.scale == "tt"
    days = (nodes - nodes[0]).jd
    values = np.stack([days, days ** 2, np.ones_like(days)], axis=-1)
    epochs = (orientation.obstime.ravel() - nodes[0]).jd
    expected = np.stack([epochs, epochs ** 2, np.ones_like(epochs)], axis=-1)
    assert np.allclose(orientation.interpolate(values), expected, rtol=0, atol=1e-9)
    assert np.allclose(orientation.interpolate(values[np.newaxis])[0], expected, atol=1e-9)


def test_nodes_are_few():
    # One day of 1-s epochs needs sixteen evaluations of the nutation series
    # (one 16-node polynomial); sparse epochs never more than there are epochs.
    assert EarthOrientation(series("2023-01-25T00:00", 1 * u.s, 86400)).nodes.size == 16
    sparse = EPOCHS["sparse"]
    assert EarthOrientation(sparse).nodes.size == sparse.size


def test_step_is_accepted_and_changes_nothing():
    # conf.fast_path_step and step no longer set the accuracy.
    times = series("2023-01-25T00:00", 61 * u.s, 2000)
    source = SkyCoord(ra=80 * u.deg, dec=-10 * u.deg)
    reference = EarthOrientation(times).source_directions(source, SITES["YEBES"])
    for step in (1 * u.s, 60 * u.min, 3 * u.day):
        result = EarthOrientation(times, step=step).source_directions(source, SITES["YEBES"])
        assert np.array_equal(result, reference)
    with conf.set_temp("fast_path_step", 60):
        assert np.array_equal(source_direction(source, SITES["YEBES"], times), reference)


@pytest.mark.parametrize("step, error", [(0 * u.min, "step must be positive"),
                                         (-1 * u.min, "step must be positive")])
def test_bad_step(step, error):
    with pytest.raises(ValueError, match=error):
        EarthOrientation(Time("2023-01-25") + np.arange(3) * u.min, step=step)


def test_bad_inputs():
    times = Time("2023-01-25") + np.arange(3) * u.min
    with pytest.raises(TypeError, match="obstime must be an astropy Time"):
        EarthOrientation([59969.0, 59970.0])
    orientation = EarthOrientation(times)
    sites = EarthLocation.from_geodetic([0, 10] * u.deg, [40, 50] * u.deg)
    source = SkyCoord(ra=10 * u.deg, dec=20 * u.deg)
    with pytest.raises(ValueError, match="location must be a single site"):
        orientation.source_directions(source, sites)
    with pytest.raises(TypeError, match="location must be an astropy EarthLocation"):
        orientation.source_directions(source, "Yebes")
    with pytest.raises(TypeError, match="target must be an astropy SkyCoord"):
        orientation.source_directions("3C 84", SITES["YEBES"])


def test_shapes_of_targets_and_epochs():
    times = (Time("2023-01-25") + np.arange(12) * u.hour).reshape(3, 4)
    orientation = EarthOrientation(times)
    sources = SkyCoord(ra=[[10, 20], [30, 40]] * u.deg, dec=[[0, 10], [20, 30]] * u.deg)
    s = orientation.source_directions(sources, SITES["YEBES"])
    assert s.shape == (2, 2, 12, 3)
    assert orientation.sun_position().shape == (12, 3)
    assert orientation.era.shape == (12,)


def test_orientation_of_is_shared_and_follows_the_tables():
    from astropy.utils import iers

    from astropy_feedrot.earth.orientation import orientation_of

    times = Time("2023-01-25") + np.arange(50) * 10 * u.min
    first = orientation_of(times)
    assert orientation_of(times.copy()) is first  # the same epochs: one object
    assert orientation_of(times + 1 * u.s) is not first
    # Another IERS table (UT1 - UTC shifted by 0.5 s) is another orientation,
    # whose Earth rotation angle leads by 0.5 s of rotation (the ERA's rate,
    # 7.292e-5 rad/s: ERFA era00).
    shifted = iers.IERS_Auto.open().copy()
    shifted["UT1_UTC"] = shifted["UT1_UTC"] + 0.5 * u.s
    with iers.earth_orientation_table.set(shifted):
        other = orientation_of(Time(times.jd1, times.jd2, format="jd", scale="utc"))
        assert other is not first
    lead = np.angle(np.exp(1j * (other.era - first.era)))
    assert np.allclose(lead, 0.5 * 7.2921151467e-5, rtol=1e-6)
    masked = times.copy()
    masked[3] = np.ma.masked
    assert orientation_of(masked) is not orientation_of(masked)  # never cached


def test_day_tables_are_kept_and_follow_the_tables():
    # The tables of a set of days are kept between calls; they are those a new
    # computation gives, and another IERS table gives others (UT1 - UTC shifted
    # by 0.5 s: the ERA at midnight leads by 0.5 s of rotation, ERFA era00).
    from astropy.utils import iers

    from astropy_feedrot.earth import utc_days as instants

    times = Time("2023-01-25T03:00") + np.arange(5) * u.h
    instants._DAY_TABLES.clear()
    first = instants.UtcDays(times)
    kept = instants.UtcDays(times)
    assert kept.era0 is first.era0  # from the cache
    fresh = instants._day_tables(first.ref1, first.ref2, first.days)
    for name, value in fresh.items():
        assert np.array_equal(getattr(kept, name), value), name
    assert not kept.era0.flags.writeable
    shifted = iers.IERS_Auto.open().copy()
    shifted["UT1_UTC"] = shifted["UT1_UTC"] + 0.5 * u.s
    with iers.earth_orientation_table.set(shifted):
        other = instants.UtcDays(times)
    lead = np.angle(np.exp(1j * (other.era0 - first.era0)))
    assert np.allclose(lead, 0.5 * 7.2921151467e-5, rtol=1e-6)


def test_series_in_one_interval_as_in_several():
    # Instants within one day take the path without sorting; each value is the
    # same Lagrange polynomial through the same nodes as when instants of
    # another day come with them, bit for bit.
    from astropy_feedrot.earth.orientation import EarthOrientation

    times = Time("2023-01-25T03:00") + np.arange(4) * u.h
    orientation = EarthOrientation(times)
    tt = orientation._at_epochs().tt
    for series in (orientation._cip, orientation._velocity):
        alone = series.at(tt)
        together = series.at(np.concatenate([tt, tt[:1] + 3.0]))[:tt.size]
        assert np.array_equal(alone, together)


@pytest.mark.parametrize("span", [200.0, 3652.0])  # within a year; over ten years
def test_sparse_stencils_read_directly_as_through_distinct_nodes(span):
    # Sparse instants in time order take their stencils straight from the kept
    # table; out of order they go through the distinct intervals and nodes.
    # The same nodes and weights: the same bits, and the same as each alone.
    from astropy_feedrot.earth.orientation import EarthOrientation

    rng = np.random.default_rng(2)
    times = Time("2013-01-01T00:00") + np.sort(rng.uniform(0, span, 100)) * u.day
    orientation = EarthOrientation(times)
    tt = orientation._at_epochs().tt
    order = rng.permutation(tt.size)
    for series in (orientation._cip, orientation._velocity, orientation._position):
        x = tt + series.shift  # node spacing: a day
        assert series._direct(x, np.floor(x), np.floor(x).min()) is not None
        assert series._direct(x[order], np.floor(x[order]), np.floor(x).min()) is None
        direct = series.at(tt)
        through_nodes = np.empty_like(direct)
        through_nodes[order] = series.at(tt[order])
        assert np.array_equal(direct, through_nodes)
        pairs = np.concatenate([series.at(tt[k:k + 2])[:1] for k in range(0, tt.size - 1, 9)])
        assert np.array_equal(direct[0:tt.size - 1:9], pairs)


def test_kept_nodes_in_one_chunk_as_across_chunks():
    # Nodes of one year are read from its chunk alone; across a year's end the
    # same values come from both chunks.
    from astropy_feedrot.earth.nodes import KEPT_CHUNK
    from astropy_feedrot.earth.orientation import EarthOrientation

    series = EarthOrientation(Time(["2023-01-25T03:00"]))._cip
    needed = np.arange(5 * KEPT_CHUNK - 8, 5 * KEPT_CHUNK + 8)
    both = series.nodes(needed)
    assert np.array_equal(series.nodes(needed[:8]), both[:8])
    assert np.array_equal(series.nodes(needed[8:]), both[8:])
    # Nodes over three consecutive years come from one table of them, sorted or not.
    spread = np.arange(4 * KEPT_CHUNK - 5, 7 * KEPT_CHUNK + 5, 97)
    one_by_one = np.concatenate([series.nodes(spread[k:k + 1]) for k in range(spread.size)])
    assert np.array_equal(series.nodes(spread), one_by_one)
    assert np.array_equal(series.nodes(spread[::-1]), one_by_one[::-1])


@given(st.lists(st.integers(-10**6, 10**6), min_size=1, max_size=300),
       st.integers(0, 5))
def test_unique_integers_is_numpys_unique(values, spread):
    # The table of the range (short spans) and the sort (long ones) give
    # numpy's unique values and inverse, whatever the spread of the values.
    from astropy_feedrot.earth.nodes import unique_integers

    values = np.asarray(values, dtype=float) // 10**spread
    distinct, inverse = unique_integers(values, values.min())
    expected, expected_inverse = np.unique(values, return_inverse=True)
    assert np.array_equal(distinct, expected)
    assert np.array_equal(inverse, expected_inverse.reshape(-1))
    assert np.array_equal(unique_integers(values, values.min(), inverse=False)[0], expected)
    with_nan = np.append(values, np.nan)  # not integers: numpy's unique
    distinct, inverse = unique_integers(with_nan, with_nan.min())
    expected, expected_inverse = np.unique(with_nan, return_inverse=True)
    assert np.array_equal(distinct, expected, equal_nan=True)
    assert np.array_equal(inverse, expected_inverse.reshape(-1))


@pytest.mark.parametrize("sources", [1, 3])
@pytest.mark.parametrize("runs", [False, True])
def test_horner_in_blocks_is_horner_at_once(sources, runs):
    # Many epochs are evaluated a block at a time (in the cache), or a run of one
    # cell at a time: the same arithmetic per epoch, so the same bits as all
    # epochs at once.
    from astropy_feedrot.earth.nodes import HORNER_BLOCK, horner

    rng = np.random.default_rng(5)
    cells, n = 50, 3 * HORNER_BLOCK + 17
    slot = rng.integers(0, cells, n)
    if runs:  # runs of one cell, each longer than RUN_EPOCHS
        slot = np.sort(slot)
    coefficients = rng.normal(size=(9, sources, cells, 3))
    x = rng.uniform(-1, 1, n)
    # Horner written out over all epochs at once, x broadcast over the components.
    expected = coefficients[-1][:, slot]
    for k in range(coefficients.shape[0] - 2, -1, -1):
        expected = expected * x[:, np.newaxis] + coefficients[k][:, slot]
    assert np.array_equal(horner(coefficients, slot, x), expected)
