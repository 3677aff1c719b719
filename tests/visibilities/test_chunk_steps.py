# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The steps under a correction in chunks: the per-row multiplication, the lookup of each
row's position angles, the grouping of chunks into dask tasks and the record of the
chunks written. Each is compared with the plain numpy it replaces (np.multiply,
np.unique, np.searchsorted), bit for bit, or with the rule it states."""

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import SkyCoord
from astropy.time import Time
from hypothesis import given, settings, strategies as st

from astropy_feedrot import get_antenna
from astropy_feedrot.antennas.receptors import Receptors
from astropy_feedrot.applied.correction import _multiply
from astropy_feedrot.visibilities import receptors as receptors_module, with_receptors
from astropy_feedrot.visibilities.ms_chunks import Progress
from astropy_feedrot.visibilities.receptors import ReceptorAngleTable, _distinct
from astropy_feedrot.visibilities.tasks import TASK_CHUNKS, task_groups


def _random(shape, dtype, seed):
    rng = np.random.default_rng(seed)
    return (rng.standard_normal(shape) + 1j * rng.standard_normal(shape)).astype(dtype)


@pytest.mark.parametrize("dtype", [np.complex64, ">c8", np.complex128])
@pytest.mark.parametrize("shape", [(50, 64, 4), (7, 3, 16, 2), (300, 9, 1), (3, 2, 4)])
def test_multiply_is_numpys_multiply(dtype, shape):
    values = _random(shape, dtype, 1)
    factor = _random((shape[0],) + (1,) * (len(shape) - 2) + (shape[-1],), np.complex64
                     if np.dtype(dtype).itemsize == 8 else np.complex128, 2)
    expected = np.empty_like(values)
    np.multiply(values, factor, out=expected, casting="same_kind")
    out = np.empty_like(values)
    _multiply(values, factor, out)
    assert out.tobytes() == expected.tobytes()
    _multiply(values, factor, values)  # in place
    assert values.tobytes() == expected.tobytes()


def test_multiply_in_rows_of_records():
    # FITS-IDI rows: the visibilities of a row lie together, rows a record apart.
    records = np.zeros(40, dtype=[("TIME", ">f8"), ("FLUX", ">c8", (8, 16, 4))])
    records["FLUX"] = _random((40, 8, 16, 4), ">c8", 3)
    flux = records["FLUX"]
    factor = _random((40, 1, 1, 4), np.complex64, 4)
    expected = flux * factor
    _multiply(flux, factor, flux)
    assert np.array_equal(records["FLUX"], expected)
    assert not np.shares_memory(flux, expected)


def test_multiply_falls_back_where_the_factor_is_not_per_row():
    values = _random((20, 16, 4), np.complex64, 5)
    for factor in (_random((1, 1, 4), np.complex64, 6), _random((20, 16, 4), np.complex64, 7),
                   _random((20, 16, 1), np.complex64, 8)):
        out = np.empty_like(values)
        _multiply(values, factor, out)
        assert out.tobytes() == (values * factor).tobytes()
    columns = _random((16, 20, 4), np.complex64, 9).transpose(1, 0, 2)  # rows not contiguous
    factor = _random((20, 1, 4), np.complex64, 10)
    out = np.empty_like(columns)
    _multiply(columns, factor, out)
    assert out.tobytes() == (columns * factor).tobytes()


@settings(max_examples=60, deadline=None)
@given(st.lists(st.sampled_from([0.0, 1.5, 2.0, 2.5, -3.0, 7.25]), min_size=1, max_size=30),
       st.booleans())
def test_distinct_is_numpys_unique(values, in_order):
    values = np.array(sorted(values) if in_order else values)
    distinct, at = _distinct(values)
    expected, inverse = np.unique(values, return_inverse=True)
    assert np.array_equal(distinct, expected)
    assert np.array_equal(at, inverse.ravel())


@pytest.fixture(scope="module")
def antennas():
    names = ["FD-VLBA", "PIETOWN", "KP-VLBA", "LA-VLBA"]
    return with_receptors({k + 1: get_antenna(name) for k, name in enumerate(names)},
                          Receptors("RL", [0, 0] * u.deg))


@pytest.mark.parametrize("in_order", [True, False])
def test_the_grid_lookup_is_the_search(antennas, monkeypatch, in_order):
    # The same rows, their places found in the grid of (time, source, antenna) and by a
    # search of the sorted codes: the same places, the same angles.
    rng = np.random.default_rng(11)
    jd = np.repeat(2459970.3 + np.arange(40) / 24, 2)  # two baselines at each of 40 times
    key1 = np.tile([1, 1, 1, 2, 2, 3], 40)[:jd.size]
    key2 = np.tile([2, 3, 4, 3, 4, 4], 40)[:jd.size]
    source = np.repeat(rng.integers(0, 2, 40), 2)
    if not in_order:
        order = rng.permutation(jd.size)
        jd, key1, key2, source = jd[order], key1[order], key2[order], source[order]
    sources = {0: SkyCoord("3h19m48s +41d30m42s"), 1: SkyCoord("12h29m06s +2d03m09s")}

    def table():
        return ReceptorAngleTable(antennas, jd, source, key1, key2, sources,
                                  lambda t: Time(t, format="jd"), products=["RR", "LL"])

    lookup = table()  # a grid of 40 x 2 x 5 cells, fewer than LOOKUP_CELLS
    monkeypatch.setattr(receptors_module, "LOOKUP_CELLS", -1)
    search = table()  # more cells than twice the 80 rows: a search
    assert lookup.lookup is not None and search.lookup is None
    for keys in (key1, key2):
        places = lookup.places(jd, source, keys)
        assert places.dtype == np.int32
        assert np.array_equal(places, search.places(jd, source, keys))
        assert lookup(jd, source, keys).tobytes() == search(jd, source, keys).tobytes()
    assert np.array_equal(lookup.codes, search.codes)


def test_task_groups_keep_order_and_key_and_shrink_at_the_end():
    items = [("a", k) for k in range(23)] + [("b", k) for k in range(9)]
    groups = list(task_groups(iter(items), len(items), 2, key=lambda item: item[0]))
    assert [item for group in groups for item in group] == items
    assert all(len({item[0] for item in group}) == 1 for group in groups)
    assert max(len(group) for group in groups) == TASK_CHUNKS
    # The rule: a task starting with `left` items to go takes left // 4 (2 workers).
    left = len(items)
    for group in groups:
        assert len(group) <= max(1, min(TASK_CHUNKS, left // 4))
        left -= len(group)
    assert [len(group) for group in groups[-3:]] == [1, 1, 1]
    assert list(task_groups([], 0, 2)) == []


def test_progress_counts_chunks_written_out_of_order():
    progress = Progress("DATA -> CORRECTED_DATA", "remove", 10)
    progress.count_rows([10, 10, 10, 10, 5])
    for index in (1, 3):
        progress.add(index)
    progress.add(4, known=False)
    state = (progress.chunks, progress.also, progress.unknown, progress.done)
    assert state == (0, {1, 3}, {4}, 20)
    value = progress.keyword()
    assert value["chunks"] == 0 and list(value["also"]) == [1, 3]
    assert list(value["unknown"]) == [4]
    again = Progress.resumed(value, "DATA -> CORRECTED_DATA", "remove")
    assert again.to_do(5) == [0, 2, 4] and again.unknown == {4}
    progress.add(0)
    progress.add(2)
    progress.add(4)
    assert (progress.chunks, progress.also, progress.unknown) == (5, set(), set())
    assert set(progress.keyword()) == {"what", "direction", "done", "chunks", "chunk_rows"}


def test_progress_messages():
    progress = Progress("DATA -> DATA", "remove", 100)
    progress.count_rows([100, 100, 100])
    progress.add(0)
    progress.add(2)
    text = progress.interrupted("x.ms", 300, "DATA", "CORRECTED_DATA")
    assert "interrupted after 200 of 300 rows; DATA is intact; the first 1 chunks" in text
    assert "and chunks [2] (numbered from 0)" in text and "run the same correction" in text
    progress.add(1, known=False)
    text = progress.interrupted("x.ms", 300, "DATA", "DATA")
    assert "DATA is partly corrected" in text
    assert "chunks [1] (of 100 rows, numbered from 0) of DATA may or may not be" in text
    assert "restore DATA from a copy" in text
