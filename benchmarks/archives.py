# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Benchmark: an archive of Measurement Sets on dask.distributed, and MSv4 processing sets.

Two questions, each answered by ratios measured in the same run (this machine's speed
swings within minutes; nothing here is a timed test):

* **Many files** (`astropy_feedrot.visibilities.correct_files`, ``feedrot correct
  A.ms B.ms ... --in-place``): ``--files`` Measurement Sets of ``--gib`` GiB each
  (the VLA set of the tests, grown as ``benchmarks/correct.py`` grows it), corrected
  in place

  - one after the other in this process (no workers: the serial reference);
  - on a scheduler that is already running with ``--workers`` worker processes,
    given by its address (``--dask ADDRESS``), one task per file;
  - with ``--workers N`` on the command line, which starts its own local cluster
    (its start is part of the time: on an archive of hundreds of files it is paid
    once).

  Target: the running scheduler at least 1.6x faster than serial, and every output
  column bit for bit the serial one. The serial run and the run on the cluster go in
  turn, ``--rounds`` times, and their medians are compared: on this machine the time of
  the same serial run swings by 2-3x between minutes (the disk).

* **MSv4** (`astropy_feedrot.visibilities.correct_processing_set`): the same set
  converted by xradio, corrected into its store with dask's synchronous scheduler (one
  core), against `correct_ms` on the Measurement Set (one core). Target: at most 1.3x.

Peak memory beyond the data read: the peak resident memory of this process during the
serial run and during the MSv4 run, and of each worker during the run on the cluster
(their ``ru_maxrss`` before and after), printed with the chunk sizes (32 MiB of DATA for
a Measurement Set, one dask chunk of ``VISIBILITY`` for MSv4). Target: at most about
two chunks per worker, plus the buffers casacore and zarr keep.

Runs offline; ``python benchmarks/archives.py --help`` for the options. Needs the
``bench`` and ``msv4`` extras.
"""

import astropy.utils.data
from astropy.utils import iers

iers.conf.auto_download = False
astropy.utils.data.conf.allow_internet = False

import argparse  # noqa: E402
import logging  # noqa: E402
import os  # noqa: E402
import platform  # noqa: E402
import resource  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from correct import _PeakRSS, _ms, _settle  # noqa: E402 (benchmarks/correct.py)

import astropy_feedrot  # noqa: E402
from astropy_feedrot.visibilities import (  # noqa: E402
    correct_files,
    correct_ms,
    correct_processing_set,
)

MIB = 2**20
_CHUNK = 32 * MIB  # the data column read at once by correct_ms


def _copies(master, directory, count, prefix):
    return [Path(shutil.copytree(master, Path(directory) / f"{prefix}{k}.ms"))
            for k in range(count)]


def _column(path):
    from casacore.tables import table

    with table(str(path), ack=False) as t:
        return t.getcol("CORRECTED_DATA")


def _worker_peak():
    """A worker's peak resident memory so far (Linux: ru_maxrss in KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def _worker_now():
    """A worker's resident memory now."""
    import psutil

    return psutil.Process().memory_info().rss


def _serial(master, directory, files, prefix):
    paths = _copies(master, directory, files, prefix)
    _settle()
    with _PeakRSS() as peak:
        start = time.perf_counter()
        table = correct_files(paths)
        seconds = time.perf_counter() - start
    assert table["outcome"].tolist() == ["corrected"] * files, table
    return seconds, peak.extra, paths


def _on_cluster(master, directory, files, prefix, client):
    paths = _copies(master, directory, files, prefix)
    before = client.run(_worker_now)
    _settle()
    start = time.perf_counter()
    table = correct_files(paths, client=client)
    seconds = time.perf_counter() - start
    after = client.run(_worker_peak)
    assert table["outcome"].tolist() == ["corrected"] * files, table
    # The peak during the run (the high-water mark) above the level before it.
    return seconds, max(after[w] - before[w] for w in after), paths


def bench_archive(master, directory, files, workers, gib, results, rounds):
    import distributed

    print(f"\n{files} Measurement Sets of {gib:g} GiB, in place; {rounds} rounds in turn, "
          "medians")
    serial, running, extra, extra_worker = [], [], 0, 0
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1,
                                  dashboard_address=None) as cluster:
        address = cluster.scheduler_address
        with distributed.Client(address) as client:
            client.run(lambda: __import__("astropy_feedrot.visibilities"))  # warm
            for k in range(rounds):
                seconds, peak, one = _serial(master, directory, files, f"serial{k}_")
                serial.append(seconds)
                extra = max(extra, peak)
                seconds, peak, other = _on_cluster(master, directory, files,
                                                   f"running{k}_", client)
                running.append(seconds)
                extra_worker = max(extra_worker, peak)
                if k == 0:
                    same = all(np.array_equal(_column(a), _column(b))
                               for a, b in zip(one, other))
                for path in one + other:
                    shutil.rmtree(path)
        t_serial, t_running = np.median(serial), np.median(running)
        ratio = t_serial / t_running
        results.append(("running scheduler >= 1.6x serial", ratio >= 1.6, f"{ratio:.2f}x"))
        results.append(("outputs bit for bit the serial ones", same, ""))
        print(f"  one process, one file after the other  {t_serial:8.2f} s   (rounds "
              f"{', '.join(f'{t:.2f}' for t in serial)}) peak extra RSS "
              f"{extra / MIB:7.1f} MiB ({_CHUNK // MIB} MiB chunks)")
        print(f"  --dask ADDRESS ({workers} workers running)     {t_running:8.2f} s   "
              f"{ratio:5.2f}x serial (rounds {', '.join(f'{t:.2f}' for t in running)}); "
              f"peak extra RSS of a worker {extra_worker / MIB:7.1f} MiB")
        print(f"  outputs bit for bit the serial ones: {same}")
        # The command line, on the same running scheduler and with a cluster of its own.
        command = _copies(master, directory, files, "command")
        _settle()
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "astropy_feedrot", "correct",
                        *map(str, command), "--in-place", "--quiet", "--dask", address],
                       check=True, stdout=subprocess.DEVNULL)
        t_command = time.perf_counter() - start
    print(f"  feedrot correct ... --dask ADDRESS       {t_command:8.2f} s   "
          f"{t_serial / t_command:5.2f}x serial (with the interpreter's start)")
    own = _copies(master, directory, files, "own")
    _settle()
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "astropy_feedrot", "correct", *map(str, own),
                    "--in-place", "--quiet", "--workers", str(workers)], check=True,
                   stdout=subprocess.DEVNULL)
    t_own = time.perf_counter() - start
    print(f"  feedrot correct ... --workers {workers}          {t_own:8.2f} s   "
          f"{t_serial / t_own:5.2f}x serial (starting its own cluster)")
    for path in command + own:
        shutil.rmtree(path)


def _zarr_floor(store):
    """What any correction of a processing set must do, with zarr alone: read each
    partition's VISIBILITY a chunk at a time, multiply it by a phase per time and
    baseline, and write it into a new array of the same codecs and chunks."""
    import zarr

    root = zarr.open_group(str(store), mode="r+")
    for name in list(root.group_keys()):
        source = root[name]["VISIBILITY"]
        target = root[name].create_array(
            "FLOOR", shape=source.shape, chunks=source.chunks, dtype=source.dtype,
            compressors=source.compressors, filters=source.filters,
            serializer=source.serializer, overwrite=True)
        step = source.chunks[0]
        for start in range(0, source.shape[0], step):
            block = source[start:start + step]
            # A phase of each time and baseline, as a correction's (a constant one would
            # leave the shipped pattern as compressible as it was, and the write cheaper).
            phase = np.exp(1j * np.linspace(0, 6, block.shape[0] * block.shape[1]))
            block *= phase.astype(source.dtype).reshape(block.shape[:2] + (1, 1))
            target[start:start + step] = block


def bench_msv4(master, directory, gib, results):
    import dask
    from xradio.measurement_set import convert_msv2_to_processing_set

    print(f"\nMSv4 against correct_ms, one core, {gib:g} GiB")
    ms = Path(shutil.copytree(master, Path(directory) / "msv4_reference.ms"))
    store = Path(directory) / "msv4.ps.zarr"
    logging.getLogger("toolviper").setLevel(logging.WARNING)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        start = time.perf_counter()
        convert_msv2_to_processing_set(str(ms), str(store))
        print(f"  (xradio's conversion {time.perf_counter() - start:.1f} s, not timed below)")
    pristine = shutil.copytree(store, Path(directory) / "msv4_pristine.ps.zarr")
    _settle()
    with _PeakRSS() as peak_ms:
        start = time.perf_counter()
        correct_ms(ms)
        t_ms = time.perf_counter() - start
    with dask.config.set(scheduler="synchronous"):
        _settle()
        with _PeakRSS() as peak_v4:
            start = time.perf_counter()
            tree = correct_processing_set(store)
            t_v4 = time.perf_counter() - start
    chunk = max(np.prod([c[0] for c in p["VISIBILITY"].chunks]) * 8
                for p in tree.children.values())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _settle()
        start = time.perf_counter()
        _zarr_floor(store)
        t_floor = time.perf_counter() - start
    ratio = t_v4 / t_ms
    results.append(("MSv4 <= 1.3x correct_ms per core", ratio <= 1.3, f"{ratio:.2f}x"))
    print(f"  correct_ms                               {t_ms:8.2f} s   peak extra RSS "
          f"{peak_ms.extra / MIB:7.1f} MiB ({_CHUNK // MIB} MiB chunks)")
    print(f"  correct_processing_set (synchronous)     {t_v4:8.2f} s   {ratio:5.2f}x; peak "
          f"extra RSS {peak_v4.extra / MIB:7.1f} MiB ({chunk / MIB:.0f} MiB dask chunks)")
    print(f"  zarr alone: read, multiply, write        {t_floor:8.2f} s   the format's floor; "
          f"the correction {t_v4 / t_floor:5.2f}x it")
    with dask.config.set(scheduler="threads", num_workers=2):
        shutil.rmtree(store)
        shutil.copytree(pristine, store)
        _settle()
        start = time.perf_counter()
        correct_processing_set(store)
        t_threads = time.perf_counter() - start
    print(f"  correct_processing_set (2 threads)       {t_threads:8.2f} s   "
          f"{t_threads / t_ms:5.2f}x correct_ms (one core)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--files", type=int, default=8, help="Measurement Sets (8)")
    parser.add_argument("--gib", type=float, default=0.25, help="GiB of DATA each (0.25)")
    parser.add_argument("--workers", type=int, default=2, help="dask workers (2)")
    parser.add_argument("--rounds", type=int, default=3,
                        help="serial and cluster runs in turn, medians compared (3)")
    parser.add_argument("--only", choices=("archive", "msv4"))
    parser.add_argument("--strict", action="store_true", help="exit 1 if a target fails")
    args = parser.parse_args(argv)
    print(f"astropy_feedrot {astropy_feedrot.__version__}, Python {platform.python_version()}, "
          f"{os.cpu_count()} cores, load {os.getloadavg()[0]:.2f}")
    results = []
    with tempfile.TemporaryDirectory(dir=os.environ.get("FEEDROT_BENCH_DIR")) as directory:
        master, rows, visibilities, nbytes = _ms(directory, args.gib)
        print(f"one set: {rows} rows, {visibilities} visibilities, {nbytes / 2**30:.2f} GiB "
              "of DATA")
        if args.only in (None, "archive"):
            bench_archive(master, directory, args.files, args.workers, args.gib, results,
                          args.rounds)
        if args.only in (None, "msv4"):
            bench_msv4(master, directory, args.gib, results)
    print()
    for name, passed, value in results:
        print(f"{'PASS' if passed else 'FAIL'}: {name} {value}")
    return 1 if args.strict and not all(passed for _, passed, _ in results) else 0


if __name__ == "__main__":
    sys.exit(main())
