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
  ``correct_fitsidi``);
* ``measurement set`` (with python-casacore): the Measurement Set of
  ``benchmarks/correct.py``, ``DATA`` read, multiplied and written to
  ``CORRECTED_DATA`` through casacore chunk by chunk: one process holding
  the table, two writing each chunk under casacore's table lock (what
  ``correct_ms`` does in one process and on dask workers, without the
  package or dask).

The arithmetic is numpy's fastest (the phase repeated over the channels, as
the package multiplies). Each run starts after ``os.sync()``; the ratio
two/one is printed for every round::

    python benchmarks/io_scaling.py --gib 2 --rounds 3 [--only "measurement set"]

Needs nothing beyond numpy (python-casacore for the Measurement Set).
"""

import argparse
import multiprocessing
import os
import tempfile
import time

import numpy as np

CHUNK = 32 * 2**20  # bytes


def _multiply(data, phase):
    """``data *= phase`` (rows, 1, products) as fast as numpy does it: the phase
    repeated over the channels, 128 rows at a time."""
    for a in range(0, len(data), 128):
        data[a:a + 128] *= np.repeat(phase[a:a + 128], data.shape[1], axis=1)


def _memory(index, n, size, path):
    rows = size // 8 // 256 // n  # 64 channels x 4 products of complex64 per row
    data = np.ones((rows, 64, 4), np.complex64)  # faulted in before the clock starts
    phase = np.exp(1j * np.linspace(0.0, 1.0, rows * 4)).astype(np.complex64)
    phase = phase.reshape(rows, 1, 4)
    step = CHUNK // data[0].nbytes
    yield
    for a in range(0, rows, step):
        _multiply(data[a:a + step], phase[a:a + step])


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


def _measurement_set(index, n, size, path):
    from casacore.tables import table

    # As correct_ms: one process holds the table for good, two lock it for each write.
    shared = n > 1
    t = table(path, readonly=False, ack=False,
              lockoptions={"option": "usernoread"} if shared else "permanent")
    try:
        rows = t.nrows()
        shape = t.getcell("DATA", 0).shape
        step = CHUNK // (8 * int(np.prod(shape)))
        buffer = np.empty((step,) + shape, np.complex64)
        yield
        for a in range(index * step, rows, n * step):
            m = min(step, rows - a)
            data = buffer[:m]
            t.getcolnp("DATA", data, a, m)  # no lock: the others write another column
            phase = np.exp(1j * np.linspace(0, 1, m * shape[-1])).astype(np.complex64)
            _multiply(data, phase.reshape(m, 1, shape[-1]))
            while shared and not t.haslock(write=True):  # the write lock for each chunk
                try:
                    t.lock(write=True, nattempts=1)
                except RuntimeError:
                    time.sleep(0.001)
            t.putcol("CORRECTED_DATA", data, a, m)
            if shared:
                t.unlock()
    finally:
        t.close()


WORKS = {"memory": _memory, "cached file": _cached_file, "new file": _new_file,
         "measurement set": _measurement_set}


def _worker(name, index, n, size, path, ready, go, done):
    steps = WORKS[name](index, n, size, path)
    next(steps)  # set up, untimed
    ready.wait()
    go.wait()
    for _ in steps:
        pass
    done.put(index)


def _prepare(name, size, path):
    if name == "measurement set":  # built once (main): its columns are rewritten
        os.sync()
        return
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
    parser.add_argument("--only", choices=list(WORKS), help="one kind of work only")
    args = parser.parse_args(argv)
    size = max(1, int(args.gib * 2**30) // (2 * CHUNK)) * 2 * CHUNK
    print(f"{size / 2**30:.2f} GiB in chunks of {CHUNK // 2**20} MiB, "
          f"{os.cpu_count()} CPUs")
    with tempfile.TemporaryDirectory(dir=args.dir) as directory:
        for name in [args.only] if args.only else WORKS:
            path = os.path.join(directory, "scaling.bin")
            if name == "measurement set":
                path = _build_ms(directory, args.gib)
                if path is None:
                    print(f"{name:>15}: skipped (needs python-casacore)")
                    continue
            for _ in range(args.rounds):
                one = run(name, 1, size, path)
                two = run(name, 2, size, path)
                print(f"{name:>15}: one process {one:6.3f} s, two {two:6.3f} s, "
                      f"two/one {two / one:.2f}", flush=True)
            if os.path.isfile(path):
                os.remove(path)
    return 0


def _build_ms(directory, gib):
    """The Measurement Set of ``benchmarks/correct.py`` (``gib`` GiB of DATA), with a
    CORRECTED_DATA column; None without python-casacore."""
    try:
        from casacore.tables import makearrcoldesc, maketabdesc, table
    except ImportError:
        return None
    from correct import _ms  # this folder's benchmark builds it

    path, _, _, _ = _ms(directory, gib)
    with table(str(path), readonly=False, ack=False) as t:
        tiles = [dm["SPEC"]["DEFAULTTILESHAPE"] for dm in t.getdminfo().values()
                 if dm["COLUMNS"] == ["DATA"]][0]  # the tiles of DATA
        t.addcols(maketabdesc(makearrcoldesc("CORRECTED_DATA", 0j, valuetype="complex",
                                             shape=list(t.getcell("DATA", 0).shape))),
                  {"TYPE": "TiledShapeStMan", "NAME": "TiledCorrected",
                   "SPEC": {"DEFAULTTILESHAPE": list(tiles)}})
        zeros = np.zeros((65536,) + t.getcell("DATA", 0).shape, np.complex64)
        for a in range(0, t.nrows(), len(zeros)):  # written once: not a new file after
            m = min(len(zeros), t.nrows() - a)
            t.putcol("CORRECTED_DATA", zeros[:m], a, m)
    return str(path)


if __name__ == "__main__":
    raise SystemExit(main())
