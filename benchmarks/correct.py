# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Benchmark: correcting a visibility data set of more than 1 GiB.

Three paths, each on a data set built here (only the layout matters for the
speed):

* ``correct_uvdata``: a pyuvdata ``UVData`` of at least ``--gib`` GiB of
  ``data_array`` (complex64; four circular products, 64 channels), corrected
  in place (``inplace=True``, in chunks) and into a copy (``inplace=False``);
* ``correct_fitsidi``: a FITS-IDI file of at least ``--gib`` GiB (DiFX-like
  tables from ``tests/fitsidi_writer.py``, its UV_DATA rows repeated over
  later epochs), corrected into a new file through a memory map, in one
  process and on ``--workers`` dask workers;
* ``correct_ms``: a Measurement Set of at least ``--gib`` GiB of ``DATA``
  (the VLA set of the tests, 19 antennas, 64 channels, four products, its
  rows doubled until large enough and spread over 10 s epochs), corrected in
  place into ``CORRECTED_DATA``, in one process and on ``--workers`` dask
  workers; and with the ionosphere's Faraday rotation (CODE's IONEX maps
  that spinifex ships, the set's epochs moved into them), against the same
  correction without (target: at most 1.5x).

Besides the extra heap, the peak extra resident memory of the process during
each call is sampled (psutil, every 10 ms): it counts casacore's buffers
too. The floor of ``correct_ms`` is what any in-place correction must do,
measured in the same run: read ``DATA`` in the same chunks, multiply it by a
per-row, per-product phase factor (as fast as numpy does it) and write
``CORRECTED_DATA``. Targets (PASS/FAIL): the Measurement Set in place at most
2x that floor, FITS-IDI at most 4x a copy of the file, peak extra memory
under 300 MiB whatever the size, and two dask workers in at most 0.7x the
serial time. One process and the dask workers are timed in turn,
``--rounds`` times each (after a first run of the workers apart), and their
medians compared: this machine's speed swings within minutes.

For each: the wall time, the time per visibility, the largest extra heap
memory (``tracemalloc``: numpy registers its buffers there) and the peak
resident memory of the process; and, measured in the same run, the time of
the least any correction must do, as a ratio:

* for ``correct_uvdata``: one complex multiplication of ``data_array`` in
  place (``numpy``), and ``UVData.copy`` for the copy;
* for ``correct_fitsidi``: copying the file (``shutil.copyfile``), which the
  output needs anyway.

PASS/FAIL lines check the memory bounds the package promises: in place, the
extra heap stays below a quarter of ``data_array``; a FITS-IDI file is
corrected with less than 64 MiB of extra heap, whatever its size (it is
corrected in chunks of 16 MiB through a memory map). With ``--strict``
the exit status is 1 if one fails. Runs offline. ``python
benchmarks/correct.py --help`` for the options.
"""

import astropy.utils.data

# Offline before anything else imports astropy's IERS machinery.
from astropy.utils import iers

iers.conf.auto_download = False
astropy.utils.data.conf.allow_internet = False

import argparse  # noqa: E402
import gc  # noqa: E402
import os  # noqa: E402
import platform  # noqa: E402
import resource  # noqa: E402
import shutil  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402

import astropy.units as u  # noqa: E402
import numpy as np  # noqa: E402
from astropy.io import fits  # noqa: E402
from astropy.time import Time  # noqa: E402

import astropy_feedrot  # noqa: E402
from astropy_feedrot.visibilities import correct_fitsidi  # noqa: E402

GIB = 2 ** 30
HERE = Path(__file__).resolve().parent


def _peak_rss():
    """The process's peak resident memory so far, in bytes (Linux: ru_maxrss in KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def _settle():
    """Write out what earlier runs left in the page cache (and collect garbage), so that
    no run pays for the write-back of another."""
    gc.collect()
    if hasattr(os, "sync"):
        os.sync()


def _measure(function, *args, **kwargs):
    """(seconds, result) of a call."""
    _settle()
    start = time.perf_counter()
    result = function(*args, **kwargs)
    return time.perf_counter() - start, result


def _traced(function, *args, **kwargs):
    gc.collect()
    tracemalloc.start()
    try:
        function(*args, **kwargs)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return peak


class _PeakRSS:
    """The peak resident memory of this process above its level at the start (psutil)."""

    def __enter__(self):
        import threading

        import psutil

        self.process = psutil.Process()
        self.start = self.peak = self.process.memory_info().rss
        self.running = True

        def sample():
            while self.running:
                self.peak = max(self.peak, self.process.memory_info().rss)
                time.sleep(0.01)

        self.thread = threading.Thread(target=sample, daemon=True)
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.running = False
        self.thread.join()
        self.extra = self.peak - self.start


def _rss(function, *args, **kwargs):
    """(seconds, peak extra resident bytes) of a call."""
    _settle()
    with _PeakRSS() as peak:
        start = time.perf_counter()
        function(*args, **kwargs)
        seconds = time.perf_counter() - start
    return seconds, peak.extra


def _client(workers):
    import distributed

    cluster = distributed.LocalCluster(n_workers=workers, threads_per_worker=1,
                                       dashboard_address=":0")
    client = distributed.Client(cluster)
    # Start-up apart: the workers import the package (and astropy's tables) first.
    client.run(lambda: __import__("astropy_feedrot.visibilities"))
    return cluster, client


def _line(name, seconds, count, heap=None, ratio=None, reference=""):
    text = f"{name:<34s} {seconds:9.2f} s  {seconds / count * 1e9:8.2f} ns/visibility"
    if heap is not None:
        text += f"  extra heap {heap / 2**20:9.1f} MiB"
    if ratio is not None:
        text += f"  {ratio:6.2f}x {reference}"
    print(text)


# --- pyuvdata ----------------------------------------------------------------------------


def _uvdata(gib):
    """A UVData of at least ``gib`` GiB: VLBA antennas, 64 channels, RR LL RL LR."""
    from pyuvdata import Telescope, UVData

    from astropy_feedrot.stations.catalogue import get_antenna

    names = ["BR-VLBA", "FD-VLBA", "HN-VLBA", "KP-VLBA", "LA-VLBA", "MK-VLBA", "NL-VLBA",
             "OV-VLBA", "PIETOWN", "SC-VLBA"]
    available = []
    for name in names:
        try:
            available.append(get_antenna(name))
        except (KeyError, ValueError):
            continue
    if len(available) < 4:  # the embedded catalogue: fall back on the paper's antennas
        available = [get_antenna(n) for n in ("FD-VLBA", "EFLSBERG", "WETTZ13S", "GGAO12M",
                                              "YEBES40M")]
    xyz = np.array([[a.location.x.to_value(u.m), a.location.y.to_value(u.m),
                     a.location.z.to_value(u.m)] for a in available])
    centre = astropy.coordinates.EarthLocation.from_geocentric(*xyz.mean(axis=0), u.m)
    n_ant = len(available)
    n_freq, n_pol = 64, 4
    n_bl = n_ant * (n_ant - 1) // 2
    per_time = n_bl * n_freq * n_pol * 8
    n_times = int(np.ceil(gib * GIB / per_time))
    telescope = Telescope.new(
        name="VLBA-like", location=centre,
        antenna_positions={i: p - xyz.mean(axis=0) for i, p in enumerate(xyz)},
        antenna_names=[a.name for a in available], instrument="VLBA-like",
        mount_type=["alt-az"] * n_ant, feed_array=[["r", "l"]] * n_ant,
        feed_angle=np.zeros((n_ant, 2)))
    times = Time("2023-01-25T20:00") + np.arange(n_times) * 2 * u.s
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        uv = UVData.new(freq_array=8.4e9 + np.arange(n_freq) * 0.5e6,
                        polarization_array=[-1, -2, -3, -4], times=times.jd,
                        telescope=telescope, antpairs=[(i, j) for i in range(n_ant)
                                                       for j in range(i + 1, n_ant)],
                        phase_center_catalog={0: dict(cat_name="3C84", cat_type="sidereal",
                                                      cat_lon=np.radians(49.9506671),
                                                      cat_lat=np.radians(41.5116961),
                                                      cat_frame="icrs", cat_epoch=2000.0)},
                        data_array=None, do_blt_outer=True, empty=True)
    uv.data_array = np.ones(uv.data_array.shape, dtype=np.complex64)
    return uv


def bench_uvdata(gib, results):
    from astropy_feedrot.visibilities import correct_uvdata

    print(f"\ncorrect_uvdata: building a UVData of at least {gib} GiB ...", flush=True)
    uv = _uvdata(gib)
    size = uv.data_array.nbytes
    count = uv.data_array.size
    print(f"  {uv.Nants_data} antennas, {uv.Nbls} baselines, {uv.Ntimes} epochs, "
          f"{uv.Nfreqs} channels, {uv.Npols} products: {uv.Nblts} baseline-times, "
          f"data_array {size / GIB:.2f} GiB ({count / 1e6:.0f} M visibilities)")
    floor, _ = _measure(np.multiply, uv.data_array, np.complex64(1j), out=uv.data_array)
    copy_time, copied = _measure(uv.copy)
    del copied
    seconds, _ = _measure(correct_uvdata, uv, inplace=True)
    uv.history = uv.history.split("Feed rotation removed")[0]  # allow a second run
    heap = _traced(correct_uvdata, uv, inplace=True)
    uv.history = uv.history.split("Feed rotation removed")[0]
    _line("numpy: one complex multiply", floor, count)
    _line("correct_uvdata(inplace=True)", seconds, count, heap, seconds / floor, "the multiply")
    copy_seconds, out = _measure(correct_uvdata, uv, inplace=False)
    del out
    _line("UVData.copy", copy_time, count)
    _line("correct_uvdata(inplace=False)", copy_seconds, count, None,
          copy_seconds / (copy_time + floor), "copy + multiply")
    results.append(("in place: extra heap below a quarter of data_array",
                    heap < size / 4, f"{heap / 2**20:.0f} MiB < {size / 4 / 2**20:.0f} MiB"))
    print(f"  peak resident memory of the process so far: {_peak_rss() / GIB:.2f} GiB")


# --- FITS-IDI -----------------------------------------------------------------------------


def _fitsidi(path, gib):
    """A FITS-IDI file of at least ``gib`` GiB: a small written file's rows repeated."""
    sys.path.insert(0, str(HERE.parent / "tests"))
    from fitsidi_writer import write_fitsidi

    seed = path.with_name("seed.idifits")
    n_band, n_chan = 8, 64
    write_fitsidi(seed, n_times=4, step_minutes=0.05, n_band=n_band, n_chan=n_chan,
                  autocorrelations=False)
    with fits.open(seed) as hdus:
        tables = [hdu.copy() for hdu in hdus]
    uv = tables[-1]
    rows = uv.data
    span = 4 * 3.0 / 86400  # four epochs 3 s apart, in days
    repeats = int(np.ceil(gib * GIB / (rows.itemsize * len(rows))))
    big = np.empty(len(rows) * repeats, dtype=rows.dtype)
    for k in range(repeats):
        block = big[k * len(rows):(k + 1) * len(rows)]
        block[...] = rows.base if hasattr(rows, "base") and rows.base is not None else rows
        block["TIME"] += k * span
    tables[-1] = fits.BinTableHDU(big, header=uv.header, name="UV_DATA")
    fits.HDUList(tables).writeto(path, overwrite=True)
    seed.unlink()
    return len(big), len(big) * n_band * n_chan * 4


def _in_turn(paths, rounds):
    """{name: median seconds} of calls taken in turn, ``rounds`` times (this machine's
    speed swings within minutes: a slow spell then hits every path alike)."""
    times = {name: [] for name in paths}
    for _ in range(rounds):
        for name, call in paths.items():
            seconds, _ = _measure(call)
            times[name].append(seconds)
    for name, values in times.items():
        print(f"  {name}: " + ", ".join(f"{v:.2f}" for v in values) + " s")
    return {name: float(np.median(values)) for name, values in times.items()}


def bench_fitsidi(gib, results, directory, workers=0, rounds=3):
    path = Path(directory) / "big.idifits"
    print(f"\ncorrect_fitsidi: writing a FITS-IDI file of at least {gib} GiB ...", flush=True)
    n_rows, count = _fitsidi(path, gib)
    size = path.stat().st_size
    print(f"  {n_rows} rows, {size / GIB:.2f} GiB, {count / 1e6:.0f} M visibilities")
    copy = path.with_name("copy.idifits")
    copy_time, _ = _measure(shutil.copyfile, path, copy)
    copy.unlink()
    out = path.with_name("corrected.idifits")
    seconds, rss = _rss(correct_fitsidi, path, out)
    out.unlink()
    heap = _traced(correct_fitsidi, path, out)
    out.unlink()
    parallel = None
    if workers:
        cluster, client = _client(workers)
        try:
            correct_fitsidi(path, out, client=client)  # the workers' first run apart
            out.unlink()

            def serial():
                correct_fitsidi(path, out)
                out.unlink()

            def dask():
                correct_fitsidi(path, out, client=client)
                out.unlink()

            median = _in_turn({"one process": serial, f"{workers} dask workers": dask},
                              rounds)
            seconds, parallel = median["one process"], median[f"{workers} dask workers"]
        finally:
            client.close()
            cluster.close()
    _line("shutil.copyfile", copy_time, count)
    _line("correct_fitsidi", seconds, count, heap, seconds / copy_time, "the copy")
    print(f"  {seconds / (size / GIB):.2f} s/GiB; peak extra resident memory "
          f"{rss / 2**20:.0f} MiB (the mapped pages of the file count while touched)")
    results.append(("FITS-IDI: extra heap below 64 MiB, whatever the file's size",
                    heap < 64 * 2**20, f"{heap / 2**20:.0f} MiB for {size / GIB:.2f} GiB"))
    results.append(("FITS-IDI: at most 4x a copy of the file", seconds <= 4 * copy_time,
                    f"{seconds / copy_time:.2f}x"))
    if parallel is not None:
        _line(f"correct_fitsidi, {workers} dask workers", parallel, count, None,
              parallel / seconds, "one process")
        results.append((f"FITS-IDI: {workers} dask workers at most 0.7x one process "
                        f"(medians of {rounds} runs in turn)", parallel <= 0.7 * seconds,
                        f"{parallel / seconds:.2f}x"))
    print(f"  peak resident memory of the process so far: {_peak_rss() / GIB:.2f} GiB "
          "(the memory-mapped file's pages count while they are touched)")
    path.unlink()


# --- Measurement Sets ---------------------------------------------------------------------


def _ms(directory, gib):
    """A Measurement Set of at least ``gib`` GiB of DATA: the VLA set of the tests, its
    153 baselines repeated over 10 s epochs (rows added, the columns written in blocks)."""
    import tarfile

    from casacore.tables import table

    name = "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms"
    with tarfile.open(HERE.parent / "tests" / "data" / "uvdata" / f"{name}.tar.gz") as tar:
        tar.extractall(directory, filter="data")
    path = Path(directory) / name
    with table(str(path), readonly=False, ack=False) as t:
        cell = t.getcell("DATA", 0)
        first = t.getcol("TIME")
        one = first == first[0]  # the rows of the first epoch: one per baseline
        names = ("ANTENNA1", "ANTENNA2", "FEED1", "FEED2", "FIELD_ID", "DATA_DESC_ID")
        columns = {c: t.getcol(c)[one] for c in names}
        per_epoch = int(np.count_nonzero(one))
        epochs = int(np.ceil(gib * GIB / (cell.nbytes * per_epoch)))
        n = epochs * per_epoch
        t.addrows(n - t.nrows())
        phase = np.exp(1j * np.linspace(0, 6, cell.size)).astype(np.complex64)
        block_epochs = max(1, 65536 // per_epoch)
        for e in range(0, epochs, block_epochs):
            m = min(block_epochs, epochs - e)
            start, rows = e * per_epoch, m * per_epoch
            for column, values in columns.items():
                t.putcol(column, np.tile(values, m), start, rows)
            t.putcol("TIME", first[0] + np.repeat(np.arange(e, e + m), per_epoch) * 10.0,
                     start, rows)
            t.putcol("FLAG_ROW", np.zeros(rows, bool), start, rows)
            t.putcol("DATA", np.broadcast_to(phase.reshape(cell.shape),
                                             (rows,) + cell.shape).copy(), start, rows)
    return path, n, n * cell.size, n * cell.nbytes


def _floor(path, chunk_rows):
    """Read DATA in chunks into one buffer, multiply by a per-row, per-product phase, write
    CORRECTED_DATA."""
    from casacore.tables import table

    with table(str(path), readonly=False, ack=False) as t:
        n = t.nrows()
        # Read into one buffer (a new array per chunk would be faulted in afresh).
        buffer = np.empty((chunk_rows,) + t.getcell("DATA", 0).shape, dtype=np.complex64)
        for k in range(0, n, chunk_rows):
            m = min(chunk_rows, n - k)
            data = buffer[:m]
            t.getcolnp("DATA", data, k, m)
            phase = np.exp(1j * np.linspace(0, 1, m * data.shape[-1])).astype(np.complex64)
            phase = phase.reshape(m, 1, data.shape[-1])
            # As fast as numpy multiplies: the phase repeated over the channels, 128 rows
            # at a time (broadcast instead, numpy's inner loop is four products long).
            for a in range(0, m, 128):
                data[a:a + 128] *= np.repeat(phase[a:a + 128], data.shape[1], axis=1)
            t.putcol("CORRECTED_DATA", data, k, m)


def bench_ms(gib, results, directory, workers=0, rounds=3):
    from casacore.tables import table

    from astropy_feedrot.visibilities import correct_ms

    print(f"\ncorrect_ms: building a Measurement Set of at least {gib} GiB ...", flush=True)
    path, n_rows, count, size = _ms(directory, gib)
    with table(str(path), ack=False) as t:
        chunk_rows = max(1, 32 * 2**20 // t.getcell("DATA", 0).nbytes)
    print(f"  {n_rows} rows, DATA {size / GIB:.2f} GiB, {count / 1e6:.0f} M visibilities, "
          f"chunks of {chunk_rows} rows")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        seconds, rss = _rss(correct_ms, path)  # creates CORRECTED_DATA
        floor, _ = _measure(_floor, path, chunk_rows)
        seconds, rss = _rss(correct_ms, path, redo=True)  # the same work, column existing
        parallel = None
        if workers:
            cluster, client = _client(workers)
            try:
                correct_ms(path, redo=True, client=client)  # the workers' first run apart
                median = _in_turn({
                    "one process": lambda: correct_ms(path, redo=True),
                    f"{workers} dask workers": lambda: correct_ms(path, redo=True,
                                                                  client=client)}, rounds)
                seconds, parallel = median["one process"], median[f"{workers} dask workers"]
            finally:
                client.close()
                cluster.close()
    _line("floor: read, phase multiply, write", floor, count)
    _line("correct_ms (in place)", seconds, count, None, seconds / floor, "the floor")
    print(f"  {seconds / (size / GIB):.2f} s/GiB; peak extra resident memory "
          f"{rss / 2**20:.0f} MiB")
    results.append(("Measurement Set in place: at most 2x the floor", seconds <= 2 * floor,
                    f"{seconds / floor:.2f}x"))
    results.append(("Measurement Set: peak extra memory under 300 MiB", rss < 300 * 2**20,
                    f"{rss / 2**20:.0f} MiB for {size / GIB:.2f} GiB"))
    if parallel is not None:
        _line(f"correct_ms, {workers} dask workers", parallel, count, None,
              parallel / seconds, "one process")
        results.append((f"Measurement Set: {workers} dask workers at most 0.7x one process "
                        f"(medians of {rounds} runs in turn)", parallel <= 0.7 * seconds,
                        f"{parallel / seconds:.2f}x"))


def bench_ms_ionosphere(gib, results, directory, rounds=3):
    """The Measurement Set corrected with and without the ionosphere's Faraday rotation
    (CODE's IONEX maps of 2020 January 8 and 9 that spinifex ships; the set's epochs moved
    there), in turn: the extra cost of the RM on its 60 s grid per antenna and of the
    angles per channel."""
    import importlib.util

    from casacore.tables import table

    from astropy_feedrot.ionosphere import Ionosphere, sample_ionex
    from astropy_feedrot.visibilities import correct_ms

    if importlib.util.find_spec("spinifex") is None:
        print("\ncorrect_ms with an ionosphere: skipped (spinifex, the extra 'ionosphere', "
              "is not installed)")
        return
    print(f"\ncorrect_ms with an ionosphere: building a Measurement Set of at least {gib} "
          "GiB ...", flush=True)
    path, n_rows, count, size = _ms(directory, gib)
    with table(str(path), readonly=False, ack=False) as t:
        time_ = t.getcol("TIME")
        start = Time("2020-01-08T06:00", scale="utc").mjd * 86400.0
        t.putcol("TIME", time_ - time_[0] + start)
        hours = (time_[-1] - time_[0]) / 3600
    ionosphere = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
    print(f"  {n_rows} rows over {hours:.1f} h, DATA {size / GIB:.2f} GiB; {ionosphere!r}")
    # Two sources: the set's own (the fraction of antenna-epochs above the horizon is
    # printed: no RM is needed below it) and one always above it (dec +80 deg at the VLA).
    with table(str(path / "FIELD"), ack=False) as field:
        own = field.getcol("PHASE_DIR")
    for label, direction in (("its own source", None), ("a circumpolar source", 80.0)):
        if direction is not None:
            with table(str(path / "FIELD"), readonly=False, ack=False) as field:
                moved = own.copy()
                moved[..., 1] = np.radians(direction)
                for column in ("PHASE_DIR", "DELAY_DIR", "REFERENCE_DIR"):
                    field.putcol(column, moved)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a source below the horizon: NaN rows, said
            correct_ms(path, redo=True)  # creates CORRECTED_DATA
            up = _fraction_up(path, ionosphere)
            print(f"  {label}: above the horizon at {100 * up:.0f}% of antenna-epochs")
            median = _in_turn({
                "without": lambda: correct_ms(path, redo=True),
                "with the ionosphere": lambda: correct_ms(path, redo=True,
                                                          ionosphere=ionosphere)}, rounds)
        without, with_ = median["without"], median["with the ionosphere"]
        _line(f"correct_ms, {label}", without, count)
        _line("  ionosphere=(IONEX)", with_, count, None, with_ / without, "without")
        results.append((f"Measurement Set with an ionosphere (IONEX), {label}: at most 1.5x "
                        f"without (medians of {rounds} runs in turn)", with_ <= 1.5 * without,
                        f"{with_ / without:.2f}x ({with_:.2f} s against {without:.2f} s)"))


def _fraction_up(path, ionosphere):
    """The fraction of antenna-epochs at which the set's source is above the horizon."""
    from astropy.coordinates import AltAz, EarthLocation, SkyCoord
    from casacore.tables import table

    with table(str(path), ack=False) as t:
        epochs = np.unique(t.getcol("TIME"))
    with table(str(path / "FIELD"), ack=False) as field:
        ra, dec = field.getcol("PHASE_DIR")[0, 0]
    with table(str(path / "ANTENNA"), ack=False) as antennas:
        xyz = antennas.getcol("POSITION")
    sites = EarthLocation.from_geocentric(*xyz.T, unit=u.m)
    times = Time(epochs[::30] / 86400.0, format="mjd", scale="utc")
    source = SkyCoord(ra * u.rad, dec * u.rad)
    altitude = source.transform_to(AltAz(obstime=times[:, None], location=sites[None])).alt
    return float(np.mean(altitude > 0 * u.deg))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--gib", type=float, default=1.0,
                        help="size of each data set in GiB (default 1)")
    parser.add_argument("--only", choices=("uvdata", "fitsidi", "ms", "ionosphere"),
                        help="run one path only")
    parser.add_argument("--workers", type=int, default=2,
                        help="dask workers for the parallel runs (0: none; default 2)")
    parser.add_argument("--rounds", type=int, default=3,
                        help="runs of one process and of the dask workers, taken in turn; "
                        "their medians are compared (default 3)")
    parser.add_argument("--dir", default=None, help="where to write the FITS-IDI files "
                        "(default: a temporary directory)")
    parser.add_argument("--strict", action="store_true", help="exit 1 if a check fails")
    args = parser.parse_args(argv)
    print(f"astropy_feedrot {astropy_feedrot.__version__}, astropy {astropy.__version__}, "
          f"numpy {np.__version__}, Python {platform.python_version()}, "
          f"{os.cpu_count()} CPUs, {platform.machine()}")
    results = []
    if args.only in (None, "uvdata"):
        bench_uvdata(args.gib, results)
    if args.only in (None, "fitsidi"):
        with tempfile.TemporaryDirectory(dir=args.dir) as directory:
            bench_fitsidi(args.gib, results, directory, args.workers, args.rounds)
    if args.only in (None, "ms"):
        with tempfile.TemporaryDirectory(dir=args.dir) as directory:
            bench_ms(args.gib, results, directory, args.workers, args.rounds)
    if args.only in (None, "ionosphere"):
        with tempfile.TemporaryDirectory(dir=args.dir) as directory:
            bench_ms_ionosphere(args.gib, results, directory, args.rounds)
    print()
    for name, ok, detail in results:
        print(f"{'PASS' if ok else 'FAIL'}  {name}: {detail}")
    return 1 if args.strict and not all(ok for _, ok, _ in results) else 0


if __name__ == "__main__":
    sys.exit(main())
