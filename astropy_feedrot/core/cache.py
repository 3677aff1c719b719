# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""What the package keeps between calls: the last few results, and each thread's buffer.

`KeptLast` holds the last few values computed (sites' positions, Earth
orientations, day tables of Earth orientation, runs of years of kept nodes),
safe to share between threads; a value may be tied to the object it was
computed from (the IERS table in use), and is found only with that object.
`thread_buffer` gives each thread one buffer for the chunks of a long
correction, so that a new array for each chunk is not mapped and faulted in
afresh. `helper_thread` is the one worker thread the process keeps for work
split in two (numpy and pyerfa release the GIL). `heap_keeps_chunks` has
glibc's malloc keep chunk-sized blocks in the heap for the length of a run in
a process (a dask worker) whose environment tells it to give memory back at
once. Nothing here imports the rest of the package.
"""

import collections
import concurrent.futures
import ctypes
import os
import threading

import numpy as np

__all__ = ["KeptLast", "thread_buffer", "release_thread_buffer", "helper_thread",
           "on_helper_thread", "heap_keeps_chunks"]


class KeptLast:
    """The last ``size`` values used, by key, for every thread.

    Parameters
    ----------
    size : int
        How many values are kept; the least recently used goes first.

    Examples
    --------
    >>> from astropy_feedrot.core.cache import KeptLast
    >>> kept = KeptLast(2)
    >>> table = object()
    >>> kept.put("a", 1.0, tag=table)
    1.0
    >>> kept.get("a", tag=table), kept.get("a"), kept.get("b")
    (1.0, None, None)
    """

    def __init__(self, size):
        self.size = int(size)
        self._values = collections.OrderedDict()
        self._lock = threading.Lock()

    def get(self, key, tag=None):
        """The value kept for ``key`` and computed from ``tag`` (by identity), or None."""
        with self._lock:
            hit = self._values.get(key)
            if hit is None or hit[0] is not tag:
                return None
            self._values.move_to_end(key)
            return hit[1]

    def put(self, key, value, tag=None):
        """Keep ``value`` (and ``tag``, alive with it) for ``key``; return ``value``."""
        with self._lock:
            self._values[key] = (tag, value)
            self._values.move_to_end(key)
            while len(self._values) > self.size:
                self._values.popitem(last=False)
        return value

    def clear(self):
        """Forget every value."""
        with self._lock:
            self._values.clear()

    def __len__(self):
        return len(self._values)


_BUFFERS = threading.local()


def thread_buffer(dtype, shape):
    """An array of ``dtype`` and ``shape`` in a buffer this thread keeps for its next calls.

    The buffer grows to the largest array asked for; its contents are
    whatever the last user left. Chunks of a long correction reuse it: a new
    array of tens of MiB for each chunk would be mapped and faulted in afresh
    (dask's workers set glibc to return freed memory at once).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.core.cache import release_thread_buffer, thread_buffer
    >>> a = thread_buffer(np.complex64, (4, 2))
    >>> b = thread_buffer(np.complex64, (2, 2))
    >>> a.shape, np.shares_memory(a, b)
    ((4, 2), True)
    >>> release_thread_buffer()
    """
    dtype = np.dtype(dtype)
    nbytes = dtype.itemsize * int(np.prod(shape))
    buffer = getattr(_BUFFERS, "bytes", None)
    if buffer is None or buffer.size < nbytes:
        buffer = _BUFFERS.bytes = np.empty(nbytes, dtype=np.uint8)
    return buffer[:nbytes].view(dtype).reshape(shape)


def release_thread_buffer():
    """Let this thread's buffer go (at the end of a correction in the calling thread).

    Examples
    --------
    >>> from astropy_feedrot.core.cache import release_thread_buffer
    >>> release_thread_buffer()
    """
    vars(_BUFFERS).pop("bytes", None)


_HELPER = []
_HELPER_LOCK = threading.Lock()
_HELPER_NAME = "astropy_feedrot-helper"


def helper_thread():
    """The one worker thread the process keeps, started on first use.

    For work split in two, one half here and one in the calling thread
    (starting a thread costs about 2 ms). Work running on it must not wait
    for it again (`on_helper_thread` tells).

    Returns
    -------
    concurrent.futures.ThreadPoolExecutor
        With one worker.

    Examples
    --------
    >>> from astropy_feedrot.core.cache import helper_thread
    >>> helper_thread().submit(sum, [1, 2, 3]).result()
    6
    """
    with _HELPER_LOCK:
        if not _HELPER:
            _HELPER.append(concurrent.futures.ThreadPoolExecutor(
                max_workers=1, thread_name_prefix=_HELPER_NAME))
        return _HELPER[0]


def on_helper_thread():
    """Whether the calling thread is `helper_thread` (which must then do its work itself).

    Examples
    --------
    >>> from astropy_feedrot.core.cache import helper_thread, on_helper_thread
    >>> on_helper_thread(), helper_thread().submit(on_helper_thread).result()
    (False, True)
    """
    return threading.current_thread().name.startswith(_HELPER_NAME)


# glibc's mallopt parameters (malloc.h) and the environment variables that set them.
_MALLOPT = {"MALLOC_TRIM_THRESHOLD_": -1, "MALLOC_MMAP_THRESHOLD_": -3}
_GLIBC_DEFAULT = 128 * 1024  # both thresholds, when the environment does not set them
# While a run goes on: blocks up to 32 MiB (glibc's largest mmap threshold on 64-bit
# systems) come from the heap, and up to 256 MiB of freed heap stays there.
_RUN = {"MALLOC_TRIM_THRESHOLD_": 256 * 2**20, "MALLOC_MMAP_THRESHOLD_": 32 * 2**20}


def _glibc():
    try:
        libc = ctypes.CDLL(None)
        return libc.mallopt, libc.malloc_trim
    except (OSError, AttributeError):  # not glibc
        return None


def _environment_value(name):
    try:
        return int(os.environ.get(name, _GLIBC_DEFAULT))
    except ValueError:
        return _GLIBC_DEFAULT


def heap_keeps_chunks(keep=True):
    """During a run of chunks, let glibc's malloc keep chunk-sized blocks in the heap.

    dask's workers start with ``MALLOC_TRIM_THRESHOLD_=65536`` in their
    environment, so that freed memory goes back to the system at once. That
    also stops glibc from raising its mmap threshold as it does by default:
    every block of more than 128 KiB is then mapped afresh and faulted in
    page by page when used, and casacore's and numpy's chunk-sized
    temporaries did so for every chunk (a dask worker took twice the time
    of this process for the same chunks of a Measurement Set). With ``keep``
    true, blocks up to 32 MiB come from the heap and up to 256 MiB of freed
    heap is kept; ``keep=False`` gives back the values of the environment
    (glibc's defaults where it sets only one) and returns the free heap to
    the system. Nothing happens in a process whose environment sets neither
    threshold (glibc then adapts by itself) or that does not use glibc.

    Parameters
    ----------
    keep : bool, optional
        True when a run starts, False when it ends.

    Returns
    -------
    bool
        Whether glibc's thresholds were set.

    Examples
    --------
    >>> from astropy_feedrot.core.cache import heap_keeps_chunks
    >>> import os
    >>> heap_keeps_chunks() == ("MALLOC_TRIM_THRESHOLD_" in os.environ
    ...                         or "MALLOC_MMAP_THRESHOLD_" in os.environ)
    True
    >>> _ = heap_keeps_chunks(False)
    """
    if not any(name in os.environ for name in _MALLOPT):
        return False
    calls = _glibc()
    if calls is None:
        return False
    mallopt, malloc_trim = calls
    for name, parameter in _MALLOPT.items():
        mallopt(parameter, _RUN[name] if keep else _environment_value(name))
    if not keep:
        malloc_trim(0)
    return True
