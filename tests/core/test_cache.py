# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""What the package keeps between calls (astropy_feedrot.core.cache): the last few values,
tied to what they were computed from, and each thread's buffer."""

import threading

import numpy as np

from astropy_feedrot.core.cache import KeptLast, release_thread_buffer, thread_buffer


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

    from astropy_feedrot.core.cache import helper_thread, on_helper_thread
    from astropy_feedrot.earth.nodes import PARALLEL_NODES, in_parallel

    tt2 = np.arange(4.0 * PARALLEL_NODES)
    expected = erfa.era00(2460000.5, tt2)  # ERFA at every node, directly
    assert not on_helper_thread()
    assert np.array_equal(in_parallel(erfa.era00, 2460000.5, tt2), expected)
    nested = helper_thread().submit(in_parallel, erfa.era00, 2460000.5, tt2)
    assert np.array_equal(nested.result(timeout=60), expected)


# glibc's struct mallinfo2 (malloc.h, glibc 2.33+): hblkhd is the memory in mapped blocks.
_MALLINFO = """
import ctypes, sys
import numpy as np
from astropy_feedrot.core.cache import heap_keeps_chunks

class Info(ctypes.Structure):
    _fields_ = [(name, ctypes.c_size_t) for name in (
        "arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks",
        "fordblks", "keepcost")]

libc = ctypes.CDLL(None)
libc.mallinfo2.restype = Info
mapped = lambda: libc.mallinfo2().hblkhd
size = 8 * 2**20
a = np.ones(size, np.uint8)
start = mapped()
b = np.ones(size, np.uint8)
print(mapped() - start >= size)  # mapped: the environment keeps the threshold at 128 KiB
print(heap_keeps_chunks())
c = np.ones(size, np.uint8)
print(mapped() - start >= 2 * size)  # from the heap now
print(heap_keeps_chunks(False))
d = np.ones(size, np.uint8)
print(mapped() - start >= 2 * size)  # mapped again
"""


def test_the_heap_keeps_chunks_for_a_run_and_gives_them_back_after():
    # A process started as dask starts its workers (MALLOC_TRIM_THRESHOLD_=65536); glibc's
    # own count of mapped blocks says where each 8 MiB array came from.
    import ctypes
    import os
    import subprocess
    import sys

    import pytest

    if not hasattr(ctypes.CDLL(None), "mallinfo2"):
        pytest.skip("needs glibc 2.33 or later (mallinfo2)")
    env = dict(os.environ, MALLOC_TRIM_THRESHOLD_="65536")
    out = subprocess.run([sys.executable, "-c", _MALLINFO], env=env, capture_output=True,
                         text=True, check=True).stdout.split()
    assert out == ["True", "True", "False", "True", "True"]


def test_without_the_environment_glibc_is_left_to_adapt(monkeypatch):
    from astropy_feedrot.core.cache import heap_keeps_chunks

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    monkeypatch.delenv("MALLOC_MMAP_THRESHOLD_", raising=False)
    assert heap_keeps_chunks() is False
    assert heap_keeps_chunks(False) is False


def test_an_unreadable_threshold_in_the_environment_gives_glibcs_default(monkeypatch):
    from astropy_feedrot.core import cache as kept

    monkeypatch.setenv("MALLOC_MMAP_THRESHOLD_", "lots")
    assert kept._environment_value("MALLOC_MMAP_THRESHOLD_") == 128 * 1024
    monkeypatch.setattr(kept, "_glibc", lambda: None)  # not glibc: nothing to set
    assert kept.heap_keeps_chunks() is False
