# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""What the package keeps between calls (astropy_feedrot.kept): the last few values,
tied to what they were computed from, and each thread's buffer."""

import threading

import numpy as np

from astropy_feedrot.kept import KeptLast, release_thread_buffer, thread_buffer


def test_the_least_recently_used_goes_first():
    kept = KeptLast(2)
    kept.put("a", 1)
    kept.put("b", 2)
    assert kept.get("a") == 1  # "a" used last: "b" is the oldest
    kept.put("c", 3)
    assert (kept.get("a"), kept.get("b"), kept.get("c")) == (1, None, 3)
    assert len(kept) == 2
    kept.clear()
    assert len(kept) == 0 and kept.get("a") is None


def test_a_value_is_found_only_with_what_it_was_computed_from():
    # Tags are compared by identity: an equal but other table is another table.
    first, other = [1.0], [1.0]
    kept = KeptLast(4)
    kept.put("k", "from first", tag=first)
    assert kept.get("k", tag=first) == "from first"
    assert kept.get("k", tag=other) is None
    assert kept.get("k") is None


def test_each_thread_has_its_own_buffer_which_grows():
    release_thread_buffer()
    small = thread_buffer(np.float64, (4,))
    large = thread_buffer(np.complex64, (3, 5))
    assert large.shape == (3, 5) and large.dtype == np.complex64
    assert not np.shares_memory(small, large)  # grown: a new buffer
    again = thread_buffer(np.float64, (2,))
    assert np.shares_memory(again, large)
    seen = []
    worker = threading.Thread(target=lambda: seen.append(thread_buffer(np.float64, (2,))))
    worker.start()
    worker.join()
    assert not np.shares_memory(seen[0], again)
    release_thread_buffer()
    assert not np.shares_memory(thread_buffer(np.float64, (2,)), again)


def test_in_parallel_on_the_helper_thread_runs_in_turn():
    # Work on the helper thread that splits itself in two must not wait for
    # its own thread (a deadlock): it runs both halves itself, same values.
    import erfa

    from astropy_feedrot.kept import helper_thread, on_helper_thread
    from astropy_feedrot.series import PARALLEL_NODES, in_parallel

    tt2 = np.arange(4.0 * PARALLEL_NODES)
    expected = erfa.era00(2460000.5, tt2)  # ERFA at every node, directly
    assert not on_helper_thread()
    assert np.array_equal(in_parallel(erfa.era00, 2460000.5, tt2), expected)
    nested = helper_thread().submit(in_parallel, erfa.era00, 2460000.5, tt2)
    assert np.array_equal(nested.result(timeout=60), expected)
