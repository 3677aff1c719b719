# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Benchmark: a GNSS network of 500 stations and 100 satellites, one day at 30 s.

500 stationary crossed dipoles (GNSS antennas) on a Fibonacci grid over the
globe at 100 m height observe 100 GPS-like satellites (10 planes of 10,
20200 km, inclination 55 deg, nominal attitude) at 2880 epochs: 144 million
feed rotations, NaN below 10 deg elevation, written as float32 chunk by chunk
(576 MB on disk) so that no process holds the whole grid. Three ways:

``distributed``
    `~astropy_feedrot.engine.grid.feed_rotation_grid_dask` on a ``dask.distributed``
    ``LocalCluster`` (2 worker processes, 1 thread each, glibc tuned as in
    `WORKER_MALLOC`), written with ``dask.array.to_npy_stack``.
``threads``
    The same dask array on dask's threaded scheduler (2 threads, one process).
``numpy``
    `~astropy_feedrot.engine.grid.feed_rotation_grid` on slices of epochs, each
    written into a ``.npy`` file opened as a memory map.

Each mode runs in a fresh process; the peak resident memory is the largest
sum of the RSS of that process and all its children (the cluster's nanny and
worker processes), sampled every 20 ms with psutil. Finally the three outputs
are compared chunk by chunk. Run with::

    python benchmarks/network.py            # all three modes
    python benchmarks/network.py --mode distributed

With ``--natural`` it measures instead what a network gains from being a
network: 30 antennas of the station catalogue x 100 natural sources (a
golden-spiral sky) x 2880 epochs (one day at 30 s), computed by
`~astropy_feedrot.engine.grid.feed_rotation_grid` (one `~astropy_feedrot.Epochs`
and one Earth orientation for all), by
`~astropy_feedrot.engine.grid.feed_rotation_grid_dask` (threads) and by a loop over
`Antenna.feed_rotation <astropy_feedrot.Antenna.feed_rotation>`, each in a
fresh process, the three taking turns for ``--rounds`` rounds (best of
``--repeats`` calls in each; the largest peak memory above the process's
memory before the call), and prints the two ratios of the targets: the loop's
time over the grid's (target: at least 3) and the grid's peak memory over the
loop's (target: at most 1); ``--strict`` exits with status 1 if one is
missed::

    python benchmarks/network.py --natural --strict

Needs ``sgp4``, ``dask[array]``, ``distributed`` and ``psutil``
(``pip install astropy_feedrot[bench]``).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np
import psutil
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.time import Time

from astropy_feedrot import Antenna, Satellite, StationaryMount, TLEOrbit
from astropy_feedrot.engine.grid import feed_rotation_grid, feed_rotation_grid_dask

DATE = Time("2023-01-25T00:00:00", scale="utc")
MODES = ("distributed", "threads", "numpy")
MIN_ELEVATION = 10 * u.deg

#: glibc settings of the worker processes. Dask's nanny exports
#: MALLOC_TRIM_THRESHOLD_=65536, which also pins glibc's mmap threshold at
#: 128 kB: every temporary array of a block (a few MB) is then mapped and
#: unmapped afresh and page faults double the compute time. These let glibc
#: reuse them (workers still return memory above 128 MB of free heap).
WORKER_MALLOC = {"MALLOC_TRIM_THRESHOLD_": 2**27, "MALLOC_MMAP_THRESHOLD_": 2**26}


def fibonacci_sites(n, height=100 * u.m):
    """``n`` sites spread evenly over the globe (a golden-spiral grid)."""
    i = np.arange(n) + 0.5
    latitude = np.arcsin(1 - 2 * i / n) * u.rad
    longitude = (np.mod(np.pi * (1 + 5**0.5) * i, 2 * np.pi) - np.pi) * u.rad
    return EarthLocation.from_geodetic(longitude, latitude, height)


def network(n_stations):
    return [Antenna(site, StationaryMount(), name=f"GNSS{k:03d}")
            for k, site in enumerate(fibonacci_sites(n_stations))]


def constellation(n_planes, per_plane):
    satellites = []
    for plane in range(n_planes):
        for slot in range(per_plane):
            orbit = TLEOrbit.from_elements(
                DATE, inclination=55 * u.deg, raan=plane * 360 / n_planes * u.deg,
                altitude=20200 * u.km,
                mean_anomaly=(slot * 360 / per_plane + plane * 360 / n_planes / per_plane)
                * u.deg, satnum=80000 + 100 * plane + slot)
            satellites.append(Satellite(orbit, name=f"P{plane:02d}S{slot:02d}"))
    return satellites


class PeakMemory:
    """Largest summed RSS of this process and its children, sampled in a thread."""

    def __init__(self, interval=0.02):
        self.interval = interval
        self.peak = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _sample(self):
        me = psutil.Process()
        total = me.memory_info().rss
        for child in me.children(recursive=True):
            try:
                total += child.memory_info().rss
            except psutil.Error:
                pass
        self.peak = max(self.peak, total)

    def _run(self):
        while not self._stop.is_set():
            self._sample()
            self._stop.wait(self.interval)

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()
        self._sample()


def run_mode(mode, args):
    """Compute and write the grid one way; return timings and memory."""
    import dask
    import dask.array as da

    result = {"mode": mode}
    with PeakMemory() as memory:
        start = time.perf_counter()
        antennas = network(args.stations)
        satellites = constellation(args.planes, args.per_plane)
        times = DATE + np.arange(0, args.hours * 3600, args.step) * u.s
        setup = time.perf_counter()
        path = os.path.join(args.output, mode)
        if mode == "numpy":
            from numpy.lib.format import open_memmap

            out = open_memmap(path + ".npy", mode="w+", dtype=np.float32,
                              shape=(times.size, len(antennas), len(satellites)))
            for first in range(0, times.size, args.slice):
                epochs = slice(first, first + args.slice)
                out[epochs] = feed_rotation_grid(antennas, satellites, times[epochs],
                                                 min_elevation=MIN_ELEVATION).value
            out.flush()
            del out
            result["compute"] = time.perf_counter() - setup
            result["chunks"] = -(-times.size // args.slice)
        else:
            lazy = feed_rotation_grid_dask(antennas, satellites, times,
                                           min_elevation=MIN_ELEVATION, chunks=args.chunk)
            result["chunks"] = len(lazy.chunks[0])
            graph = time.perf_counter()
            result["prepare"] = graph - setup
            if mode == "distributed":
                from distributed import Client, LocalCluster

                environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ"))
                if not args.default_malloc:
                    environ.update(WORKER_MALLOC)
                with dask.config.set({"distributed.nanny.pre-spawn-environ": environ}), \
                        LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     dashboard_address=":0") as cluster, Client(cluster):
                    started = time.perf_counter()
                    result["cluster_start"] = started - graph
                    da.to_npy_stack(path, lazy.astype(np.float32), axis=0)
                    result["compute"] = time.perf_counter() - started
            else:
                with dask.config.set(scheduler="threads", num_workers=2):
                    da.to_npy_stack(path, lazy.astype(np.float32), axis=0)
                    result["compute"] = time.perf_counter() - graph
        done = time.perf_counter()
    result.update(setup=setup - start, total=done - start, peak_rss_mb=memory.peak / 2**20,
                  grid=[times.size, len(antennas), len(satellites)])
    return result


def compare(output):
    """Largest difference between the outputs of the modes, read chunk by chunk."""
    import dask.array as da

    present = [m for m in MODES if os.path.exists(os.path.join(output, m))
               or os.path.exists(os.path.join(output, m + ".npy"))]
    arrays = {m: (np.load(os.path.join(output, m + ".npy"), mmap_mode="r") if m == "numpy"
                  else da.from_npy_stack(os.path.join(output, m), mmap_mode="r"))
              for m in present}
    lines = []
    reference = present[0]
    for other in present[1:]:
        worst, nan_mismatch, visible = 0.0, 0, 0
        a, b = arrays[reference], arrays[other]
        step = 240
        for first in range(0, a.shape[0], step):
            x = np.asarray(a[first:first + step])
            y = np.asarray(b[first:first + step])
            nan_mismatch += int(np.count_nonzero(np.isnan(x) != np.isnan(y)))
            visible += int(np.count_nonzero(np.isfinite(x)))
            d = np.abs(x - y)
            worst = max(worst, float(np.nanmax(d, initial=0.0)))
        lines.append(f"{reference} vs {other}: max |difference| {worst:.3g} deg, NaN "
                     f"mismatches {nan_mismatch} ({visible} values above "
                     f"{MIN_ELEVATION:.0f})")
    return lines


NATURAL_WAYS = ("grid", "loop", "dask")


def natural_run(way, n_antennas, n_sources, n_epochs, repeats):
    """One way of computing the natural-source grid, in this (fresh) process."""
    import resource
    import warnings

    from astropy.coordinates import SkyCoord, golden_spiral_grid

    from astropy_feedrot.earth.orientation import clear_orientation_cache
    from astropy_feedrot.stations.catalogue import default_catalogue

    catalogue = default_catalogue()
    antennas = []
    for name in catalogue.names:
        antenna = catalogue.get_antenna(name)
        if antenna.mount.tracks:
            antennas.append(antenna)
        if len(antennas) == n_antennas:
            break
    sky = golden_spiral_grid(n_sources)
    sources = SkyCoord(sky.lon, sky.lat, frame="icrs")
    times = DATE + np.arange(n_epochs) * 30 * u.s
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    best = np.inf
    for _ in range(repeats):
        clear_orientation_cache()
        start = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # degenerate points: counted, not timed
            if way == "grid":
                out = feed_rotation_grid(antennas, sources, times)
            elif way == "dask":
                out = feed_rotation_grid_dask(antennas, sources, times).compute(
                    scheduler="threads")
            else:
                column = sources[:, np.newaxis]
                out = [antenna.feed_rotation(column, times) for antenna in antennas]
        best = min(best, time.perf_counter() - start)
        del out
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return {"way": way, "seconds": best, "peak_mb": peak - before,
            "grid": [n_epochs, len(antennas), n_sources]}


def natural(args):
    """Grid, dask and a loop over antennas in fresh processes; the ratios; True if met."""
    # The ways take turns, each in a fresh process, for --rounds rounds: a slow
    # spell of a shared machine falls on all of them alike. The best time of
    # each way, and its largest peak memory.
    results = {}
    for _ in range(args.rounds):
        for way in NATURAL_WAYS:
            completed = subprocess.run(
                [sys.executable, os.path.abspath(__file__), f"--natural-run={way}",
                 f"--antennas={args.antennas}", f"--sources={args.sources}",
                 f"--epochs={args.epochs}", f"--repeats={args.repeats}"],
                check=True, capture_output=True, text=True)
            run = json.loads(completed.stdout.strip().splitlines()[-1])
            if way in results:
                run["peak_mb"] = max(run["peak_mb"], results[way]["peak_mb"])
                run["seconds"] = min(run["seconds"], results[way]["seconds"])
            results[way] = run
    n_t, n_a, n_s = results["grid"]["grid"]
    print(f"natural sources: {n_t} epochs x {n_a} antennas x {n_s} sources "
          f"(load average {' '.join(f'{x:.1f}' for x in os.getloadavg())})")
    for way in NATURAL_WAYS:
        r = results[way]
        print(f"{way:>6}: {r['seconds']:6.2f} s (best of {args.repeats} x {args.rounds} "
              f"processes), peak memory {r['peak_mb']:6.0f} MB above the start")
    speed = results["loop"]["seconds"] / results["grid"]["seconds"]
    memory = results["grid"]["peak_mb"] / max(results["loop"]["peak_mb"], 1.0)
    dask = results["dask"]["seconds"] / results["grid"]["seconds"]
    checks = [(speed >= 3.0, f"loop / grid time {speed:.2f} >= 3"),
              (memory <= 1.0, f"grid / loop peak memory {memory:.2f} <= 1")]
    print(f"  dask (threads) / grid time {dask:.2f}: the dask path pays where the grid "
          "does not fit in memory, not here")
    for ok, text in checks:
        print(f"  {'PASS' if ok else 'FAIL'}  {text}")
    return all(ok for ok, _ in checks)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--natural", action="store_true",
                        help="natural sources: the grid against a loop over antennas")
    parser.add_argument("--natural-run", choices=NATURAL_WAYS, help=argparse.SUPPRESS)
    parser.add_argument("--antennas", type=int, default=30)
    parser.add_argument("--sources", type=int, default=100)
    parser.add_argument("--epochs", type=int, default=2880)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--rounds", type=int, default=3,
                        help="--natural: fresh processes per way, the ways taking turns "
                             "(default 3)")
    parser.add_argument("--strict", action="store_true",
                        help="with --natural: exit with status 1 if a target is missed")
    parser.add_argument("--mode", choices=MODES + ("all",), default="all")
    parser.add_argument("--stations", type=int, default=500)
    parser.add_argument("--planes", type=int, default=10)
    parser.add_argument("--per-plane", type=int, default=10)
    parser.add_argument("--hours", type=float, default=24.0)
    parser.add_argument("--step", type=float, default=30.0, help="sampling interval in s")
    parser.add_argument("--chunk", type=int, default=None,
                        help="epochs per dask chunk (default: about 2 million grid points)")
    parser.add_argument("--slice", type=int, default=240,
                        help="epochs per feed_rotation_grid call in the numpy mode")
    parser.add_argument("--output", default=None,
                        help="directory for the results (default: a temporary one)")
    parser.add_argument("--default-malloc", action="store_true",
                        help="keep dask's glibc settings in the workers (see WORKER_MALLOC)")
    parser.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)

    if args.natural_run:
        print(json.dumps(natural_run(args.natural_run, args.antennas, args.sources,
                                     args.epochs, args.repeats)))
        return 0
    if args.natural:
        ok = natural(args)
        return 1 if args.strict and not ok else 0

    if args.mode != "all":
        if args.output is None:
            raise SystemExit("--output is needed with --mode")
        result = run_mode(args.mode, args)
        if args.json:
            print(json.dumps(result))
        else:
            print(result)
        return

    with tempfile.TemporaryDirectory(prefix="feedrot-network-") as output:
        forwarded = [f"--stations={args.stations}", f"--planes={args.planes}",
                     f"--per-plane={args.per_plane}", f"--hours={args.hours}",
                     f"--step={args.step}", f"--slice={args.slice}", f"--output={output}"]
        if args.chunk:
            forwarded.append(f"--chunk={args.chunk}")
        if args.default_malloc:
            forwarded.append("--default-malloc")
        results = []
        for mode in MODES:
            completed = subprocess.run(
                [sys.executable, os.path.abspath(__file__), f"--mode={mode}", "--json",
                 *forwarded], check=True, capture_output=True, text=True)
            results.append(json.loads(completed.stdout.strip().splitlines()[-1]))
        n_t, n_a, n_s = results[0]["grid"]
        print(f"grid: {n_t} epochs x {n_a} stations x {n_s} satellites = "
              f"{n_t * n_a * n_s / 1e6:.0f} million feed rotations "
              f"(float32 on disk: {n_t * n_a * n_s * 4 / 2**20:.0f} MB)")
        for r in results:
            detail = (f"setup {r['setup']:.1f} s, "
                      + (f"prepare {r['prepare']:.1f} s, " if "prepare" in r else "")
                      + (f"cluster start {r['cluster_start']:.1f} s, "
                         if "cluster_start" in r else "")
                      + f"compute and write {r['compute']:.1f} s ({r['chunks']} "
                      + ("calls)" if r["mode"] == "numpy" else "chunks)"))
            print(f"{r['mode']:>11}: wall {r['total']:6.1f} s, peak RSS (process tree) "
                  f"{r['peak_rss_mb']:6.0f} MB  [{detail}]")
        for line in compare(output):
            print(line)


if __name__ == "__main__":
    sys.exit(main())
