# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""How much faster two processes do the plain work under a correction, on this machine.

The target of ``benchmarks/correct.py`` for dask (two workers in at most 0.7x
the time of one process) needs the machine to do the work under a correction
in parallel. This script measures that work without the package, casacore or
dask, in one process and in two processes that split it (alternate chunks of
32 MiB), for ``--gib`` GiB:

* ``memory``: a complex64 array multiplied in place, chunk by chunk, by a
  per-row, per-polarization phase (the floor's arithmetic);
* ``cached file``: a file already in the page cache read, multiplied and
  written back in place, chunk by chunk (a Measurement Set corrected in place,
  without casacore);
* ``new file``: a new file written, chunk by chunk (the output of
  ``correct_fitsidi``).

Each run starts after ``os.sync()``; the ratio two/one is printed for every
round::

    python benchmarks/io_scaling.py --gib 2 --rounds 3

Needs nothing beyond numpy.
"""

import argparse
import multiprocessing
import os
import tempfile
import time

import numpy as np

CHUNK = 32 * 2**20  # bytes


def _memory(index, n, size, path):
    rows = size // 8 // 256 // n  # 64 channels x 4 products of complex64 per row
    data = np.ones((rows, 64, 4), np.complex64)  # faulted in before the clock starts
    phase = np.exp(1j * np.linspace(0.0, 1.0, rows * 4)).astype(np.complex64)
    phase = phase.reshape(rows, 1, 4)
    step = CHUNK // data[0].nbytes
    yield
    for a in range(0, rows, step):
        data[a:a + step] *= phase[a:a + step]


def _cached_file(index, n, size, path):
    buffer = np.empty(CHUNK // 8, np.complex64)
    view = memoryview(buffer).cast("B")
    phase = np.complex64(np.exp(1e-3j))
    fd = os.open(path, os.O_RDWR)
    try:
        yield
        for k in range(index, size // CHUNK, n):
            os.preadv(fd, [view], k * CHUNK)
            buffer *= phase
            os.pwritev(fd, [view], k * CHUNK)
    finally:
        os.close(fd)


def _new_file(index, n, size, path):
    buffer = np.ones(CHUNK // 8, np.complex64)
    view = memoryview(buffer).cast("B")
    fd = os.open(path, os.O_RDWR)
    try:
        yield
        for k in range(index, size // CHUNK, n):
            os.pwritev(fd, [view], k * CHUNK)
    finally:
        os.close(fd)


WORKS = {"memory": _memory, "cached file": _cached_file, "new file": _new_file}


def _worker(name, index, n, size, path, ready, go, done):
    steps = WORKS[name](index, n, size, path)
    next(steps)  # set up, untimed
    ready.wait()
    go.wait()
    for _ in steps:
        pass
    done.put(index)


def _prepare(name, size, path):
    if os.path.exists(path):
        os.remove(path)
    if name == "cached file":
        block = np.ones(CHUNK // 8, np.complex64).tobytes()
        with open(path, "wb") as f:
            for _ in range(size // CHUNK):
                f.write(block)
    elif name == "new file":
        with open(path, "wb") as f:
            f.truncate(size)
    os.sync()  # nothing left to write out from earlier runs


def run(name, processes, size, path):
    """Seconds for ``processes`` processes to do the work ``name`` on ``size`` bytes."""
    _prepare(name, size, path)
    context = multiprocessing.get_context("spawn")
    ready, go = context.Barrier(processes + 1), context.Barrier(processes + 1)
    done = context.Queue()
    workers = [context.Process(target=_worker, args=(name, i, processes, size, path,
                                                     ready, go, done))
               for i in range(processes)]
    for w in workers:
        w.start()
    ready.wait()
    start = time.perf_counter()
    go.wait()
    for _ in workers:
        done.get()
    seconds = time.perf_counter() - start
    for w in workers:
        w.join()
    return seconds


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--gib", type=float, default=2.0, help="size in GiB (default 2)")
    parser.add_argument("--rounds", type=int, default=3, help="rounds (default 3)")
    parser.add_argument("--dir", default=None, help="where to write the files "
                        "(default: a temporary directory)")
    args = parser.parse_args(argv)
    size = max(1, int(args.gib * 2**30) // (2 * CHUNK)) * 2 * CHUNK
    print(f"{size / 2**30:.2f} GiB in chunks of {CHUNK // 2**20} MiB, "
          f"{os.cpu_count()} CPUs")
    with tempfile.TemporaryDirectory(dir=args.dir) as directory:
        path = os.path.join(directory, "scaling.bin")
        for name in WORKS:
            for _ in range(args.rounds):
                one = run(name, 1, size, path)
                two = run(name, 2, size, path)
                print(f"{name:>12}: one process {one:6.3f} s, two {two:6.3f} s, "
                      f"two/one {two / one:.2f}")
            if os.path.exists(path):
                os.remove(path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
