# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Benchmark: feed rotation of an alt-az telescope observing a natural source.

One antenna (WETTZ13S, alt-az Cassegrain, so its feed rotation is the
parallactic angle), one source (3C 84) and N epochs 1 s apart from
2023-01-25T00:00 UTC. For each N the time per epoch, from `~astropy.time.Time`
and `~astropy.coordinates.SkyCoord` inputs to angles, of

* ``fast``: ``antenna.feed_rotation(source, times)`` (the default fast path);
* ``rigorous``: the same with ``astropy_feedrot.conf.fast_path = False``
  (astropy's topocentric ITRS transformation at every epoch);
* ``astroplan``: ``Observer(location=...).parallactic_angle(times, source)``;
* ``astropy+hd2pa``: ``source.transform_to(HADec(...))`` and ``erfa.hd2pa``;

their ratios to the fast path, and the largest angle differences against the
rigorous path. The targets of the fast path are checked on the N = 1e6 row
(or the largest N run) and printed as PASS/FAIL lines; the exit status is 1
if one fails.

Everything runs offline on the Earth orientation tables bundled with astropy.

Run ``python benchmarks/natural.py --help`` for the options.
"""

# Offline before anything else imports astropy's IERS machinery.
from astropy.utils import iers
import astropy.utils.data

iers.conf.auto_download = False
astropy.utils.data.conf.allow_internet = False

import argparse  # noqa: E402
import gc  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402
import platform  # noqa: E402
import resource  # noqa: E402
import socket  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import astropy  # noqa: E402
import astropy.units as u  # noqa: E402
import erfa  # noqa: E402
import numpy as np  # noqa: E402
from astropy.coordinates import HADec, SkyCoord  # noqa: E402
from astropy.time import Time  # noqa: E402

import astropy_feedrot  # noqa: E402
from astropy_feedrot.stations import get_antenna  # noqa: E402


def _refuse_network(*args, **kwargs):
    raise OSError("the benchmark runs offline: no network connections")


# A hard guarantee that nothing waits on the network.
socket.socket.connect = _refuse_network
socket.socket.connect_ex = _refuse_network
socket.create_connection = _refuse_network

# Importing astroplan calls its download_IERS_A(): with downloads disabled this
# only instantiates astropy's IERS_Auto class. Should it fail, astroplan warns
# (OldEarthOrientationDataWarning) and replaces Time._get_delta_ut1_utc by a
# zero UT1 - UTC for every Time in the process; the original is put back so
# that the other paths are not affected.
_DELTA_UT1_UTC = Time._get_delta_ut1_utc
with warnings.catch_warnings():
    warnings.filterwarnings("ignore", message="For best precision", module="astroplan")
    try:
        import astroplan
        from astroplan import Observer
    except ImportError:  # pragma: no cover - astroplan is in the "bench" extra
        astroplan = Observer = None
ASTROPLAN_PATCHED_UT1 = Time._get_delta_ut1_utc is not _DELTA_UT1_UTC
Time._get_delta_ut1_utc = _DELTA_UT1_UTC

START = "2023-01-25T00:00"
SOURCE_RA, SOURCE_DEC = "03h19m48.16s", "+41d30m42.1s"  # 3C 84
STATION = "WETTZ13S"
PATHS = ("fast", "rigorous", "astroplan", "astropy+hd2pa")
COMPARED = ("fast", "astroplan", "astropy+hd2pa")
# The paths that --max-slow may cap (astroplan only when slower than this).
ALWAYS_SLOW = ("rigorous", "astropy+hd2pa")
SLOW_US = 10.0
TARGET_FAST_US = 1.5
TARGET_RATIO = 80.0
TARGET_MAS = 0.1
WARMUP_EPOCHS = 64
MAS_PER_DEG = 3.6e6


# --------------------------------------------------------------------------
# The four computations: inputs (a SkyCoord and a Time) to angles.

def run_fast(antenna, source, times):
    return antenna.feed_rotation(source, times)


def run_rigorous(antenna, source, times):
    with astropy_feedrot.conf.set_temp("fast_path", False):
        return antenna.feed_rotation(source, times)


def run_astroplan(antenna, source, times):
    return Observer(location=antenna.location).parallactic_angle(times, source)


def run_astropy(antenna, source, times):
    location = antenna.location
    hadec = source.transform_to(HADec(obstime=times, location=location))
    return erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, location.lat.rad) * u.rad


RUNNERS = {"fast": run_fast, "rigorous": run_rigorous, "astroplan": run_astroplan,
           "astropy+hd2pa": run_astropy}


def degrees(angle):
    """Angles of any of the runners as a float64 array in degrees."""
    return np.asarray(u.Quantity(angle).to_value(u.deg), dtype=float).ravel()


def max_difference_mas(a, b):
    """Largest absolute difference, wrapped to +-180 deg, in mas."""
    d = (a - b + 180.0) % 360.0 - 180.0
    return float(np.nanmax(np.abs(d))) * MAS_PER_DEG


class Inputs:
    """Fresh `Time` and `SkyCoord` objects for every call, so that no run
    profits from the scale conversions astropy caches on a `Time`."""

    def __init__(self, n):
        start = Time(START, scale="utc")
        seconds = np.arange(n, dtype=float)
        # Exact sums of whole days and fractions: jd1 + jd2 is the epoch.
        self.jd1 = np.full(n, start.jd1)
        self.jd2 = start.jd2 + seconds / 86400.0

    def make(self, step=1):
        times = Time(self.jd1[::step], self.jd2[::step], format="jd", scale="utc")
        source = SkyCoord(SOURCE_RA, SOURCE_DEC, frame="icrs")
        return source, times


def measure(runner, antenna, inputs, repeats, budget):
    """Best time of up to ``repeats`` calls (stopping once ``budget`` s are spent)."""
    best, spent, result = math.inf, 0.0, None
    for _ in range(repeats):
        source, times = inputs.make()
        result = None
        gc.collect()
        t0 = time.perf_counter()
        result = runner(antenna, source, times)
        elapsed = time.perf_counter() - t0
        best, spent = min(best, elapsed), spent + elapsed
        if spent >= budget:
            break
    return best, degrees(result)


# --------------------------------------------------------------------------
# Output.

def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def print_environment():
    try:
        import astropy_iers_data
        iers_data = astropy_iers_data.__version__
    except ImportError:
        iers_data = "not installed"
    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:
        usable = os.cpu_count()
    print("Feed rotation of a natural source: astropy_feedrot against astroplan and astropy")
    print()
    print(f"python            {platform.python_version()} ({platform.python_implementation()})")
    print(f"numpy             {np.__version__}")
    print(f"astropy           {astropy.__version__}"
          f"  (IERS auto_download {iers.conf.auto_download}, allow_internet "
          f"{astropy.utils.data.conf.allow_internet}, astropy-iers-data {iers_data})")
    print(f"erfa              pyerfa {erfa.__version__}, ERFA {erfa.version.erfa_version}")
    print(f"astroplan         {astroplan.__version__ if astroplan else 'not installed'}")
    print(f"astropy_feedrot   {astropy_feedrot.__version__}"
          f"  (fast_path_step {astropy_feedrot.conf.fast_path_step} min)")
    print(f"platform          {platform.platform()}")
    print(f"CPU               {cpu_model()}; {os.cpu_count()} CPUs, {usable} usable")
    if ASTROPLAN_PATCHED_UT1:
        print("note              astroplan replaced Time._get_delta_ut1_utc on import "
              "(no IERS table); the original was restored")
    print()


def fmt_n(n):
    exponent = math.log10(n)
    return f"1e{int(exponent)}" if exponent.is_integer() else str(n)


def fmt_value(value, estimated, digits):
    if value is None or not math.isfinite(value):
        return "-"
    return f"{value:.{digits}f}" + ("*" if estimated else "")


def fmt_mas(value):
    if value is None or not math.isfinite(value):
        return "-"
    if value < 1e-3:
        return f"{value:.1e}"
    return f"{value:.5f}" if value < 1 else f"{value:.2f}" if value < 1e4 else f"{value:.0f}"


def print_tables(rows, args, stride_used):
    paths = [p for p in PATHS if any(p in row["us"] for row in rows)]
    ratios = [p for p in paths if p != "fast"]
    columns = paths + [p.split("+")[0] + "/fast" for p in ratios]
    widths = [max(len(c) + 2, 10) for c in columns]
    print(f"Time per epoch (us): best of up to {args.repeats} runs within {args.budget:g} s "
          "per path and N, all transformations included")
    print(f"{'N':>8}" + "".join(f"{c:>{w}}" for c, w in zip(columns, widths)))
    for row in rows:
        cells = [fmt_value(row["us"].get(p), p in row["estimated"], 2) for p in paths]
        for p in ratios:
            value = row["us"].get(p)
            ratio = value / row["us"]["fast"] if value is not None else None
            digits = 2 if ratio is not None and ratio < 10 else 1
            cells.append(fmt_value(ratio, p in row["estimated"], digits))
        print(f"{fmt_n(row['n']):>8}" + "".join(f"{c:>{w}}" for c, w in zip(cells, widths)))
    if any(row["estimated"] for row in rows):
        source = max(row["n"] for row in rows if row["n"] <= args.max_slow)
        print(f"* not run at this N (--max-slow {fmt_n(args.max_slow)}): time per epoch "
              f"taken from N = {fmt_n(source)}")
    print()

    print("Largest |difference| against the rigorous path (mas, wrapped to +-180 deg)")
    print(f"{'N':>8}{'epochs compared':>17}" + "".join(f"{p:>15}" for p in COMPARED))
    for row in rows:
        line = f"{fmt_n(row['n']):>8}{row['compared']:>16}" + ("+" if row["sub"] else " ")
        for p in COMPARED:
            line += f"{fmt_mas(row['mas'].get(p)):>15}"
        print(line)
    if stride_used:
        print(f"+ N above --max-slow: the rigorous path (and each path not run) computed at "
              f"every {args.stride}th epoch,\n  compared with the same epochs of the full runs")
    print()


def check_targets(row):
    us, mas = row["us"], row["mas"]
    fast = us["fast"]
    star = {p: "*" if p in row["estimated"] else "" for p in PATHS}
    checks = [
        (fast <= TARGET_FAST_US,
         f"fast path <= {TARGET_FAST_US} us/epoch: {fast:.3f} us"),
        (us["rigorous"] / fast >= TARGET_RATIO,
         f"rigorous/fast >= {TARGET_RATIO:g}: {us['rigorous'] / fast:.1f}{star['rigorous']}"),
    ]
    if "astroplan" in us:
        checks.append((fast <= us["astroplan"],
                       f"fast no slower than astroplan: {fast:.3f} us vs "
                       f"{us['astroplan']:.3f}{star['astroplan']} us"))
    checks.append((mas["fast"] <= TARGET_MAS,
                   f"fast within {TARGET_MAS} mas of rigorous: {fmt_mas(mas['fast'])} mas"
                   + (" (subsample)" if row["sub"] else "")))
    print(f"Targets of the fast path (N = {fmt_n(row['n'])} row)")
    for ok, text in checks:
        print(f"  {'PASS' if ok else 'FAIL'}  {text}")
    return all(ok for ok, _ in checks)


# --------------------------------------------------------------------------

def parse_sizes(text):
    sizes = sorted({int(float(s)) for s in text.split(",") if s.strip()})
    if not sizes or sizes[0] < 16:
        raise argparse.ArgumentTypeError("sizes must be at least 16 epochs")
    return sizes


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", type=parse_sizes, default=parse_sizes("1e3,1e4,1e5,1e6"),
                        help="comma-separated numbers of epochs (default 1e3,1e4,1e5,1e6)")
    parser.add_argument("--max-slow", type=lambda s: int(float(s)), default=10**6,
                        help="largest N at which the slow paths (rigorous, astropy+hd2pa, and "
                             f"astroplan if slower than {SLOW_US:g} us/epoch) are run; above "
                             "it their time per epoch is taken from the largest N run and the "
                             "accuracy comes from a subsample (default 1e6: run everything)")
    parser.add_argument("--stride", type=int, default=100,
                        help="subsample step of the accuracy comparison above --max-slow "
                             "(default 100)")
    parser.add_argument("--repeats", type=int, default=5,
                        help="largest number of timed runs per path and N (default 5)")
    parser.add_argument("--budget", type=float, default=2.0,
                        help="stop repeating a path once this many seconds are spent "
                             "(default 2)")
    args = parser.parse_args(argv)
    if args.max_slow < args.sizes[0]:
        parser.error("--max-slow must be at least the smallest of --sizes")
    if args.stride < 1 or args.repeats < 1:
        parser.error("--stride and --repeats must be positive")
    return args


def main(argv=None):
    args = parse_args(argv)
    if hasattr(sys.stdout, "reconfigure"):
        sys.stdout.reconfigure(line_buffering=True)
    print_environment()
    wall = time.perf_counter()

    antenna = get_antenna(STATION)
    paths = [p for p in PATHS if p != "astroplan" or Observer is not None]
    print(f"Antenna {antenna.name}: {antenna.mount!r}, {antenna.focus!r} at "
          f"lat {antenna.location.lat.deg:.4f} deg, lon {antenna.location.lon.deg:.4f} deg")
    print(f"Source 3C 84, ICRS {SOURCE_RA} {SOURCE_DEC}; epochs 1 s apart from {START} UTC")
    print("  fast           antenna.feed_rotation(source, times)")
    print("  rigorous       the same within conf.set_temp('fast_path', False)")
    print("  astroplan      Observer(location=antenna.location).parallactic_angle(times, source)")
    print("  astropy+hd2pa  source.transform_to(HADec(obstime=times, location=...)), "
          "erfa.hd2pa(ha, dec, lat)")
    print()

    # Warm up imports, transformation graphs and caches.
    warm = Inputs(WARMUP_EPOCHS)
    for p in paths:
        RUNNERS[p](antenna, *warm.make())

    rows, per_epoch, slow, stride_used = [], {}, set(ALWAYS_SLOW), False
    for n in args.sizes:
        inputs = Inputs(n)
        row = {"n": n, "us": {}, "mas": {}, "estimated": set(), "sub": False}
        results = {}
        for p in paths:
            if p in slow and n > args.max_slow:
                row["us"][p] = per_epoch[p]
                row["estimated"].add(p)
                continue
            best, results[p] = measure(RUNNERS[p], antenna, inputs, args.repeats, args.budget)
            row["us"][p] = per_epoch[p] = best / n * 1e6
            if p == "astroplan" and per_epoch[p] > SLOW_US:
                slow.add(p)
        if "rigorous" in results:
            reference = results["rigorous"]
            compare = {p: results[p] for p in COMPARED if p in results}
            row["compared"] = n
        else:
            # Subsample: the rigorous path (and any capped path) at every stride-th epoch.
            row["sub"] = stride_used = True
            source, times = inputs.make(args.stride)
            reference = degrees(run_rigorous(antenna, source, times))
            compare = {}
            for p in COMPARED:
                if p in results:
                    compare[p] = results[p][::args.stride]
                elif p in paths:
                    compare[p] = degrees(RUNNERS[p](antenna, *inputs.make(args.stride)))
            row["compared"] = reference.size
        for p, values in compare.items():
            row["mas"][p] = max_difference_mas(values, reference)
        del results, compare, reference
        rows.append(row)
        measured = ", ".join(f"{p} {row['us'][p]:.2f}" for p in paths
                             if p not in row["estimated"])
        print(f"  N = {fmt_n(n)} done ({measured} us/epoch)")
    print()

    print_tables(rows, args, stride_used)
    target_rows = [row for row in rows if row["n"] == 10**6] or rows[-1:]
    ok = check_targets(target_rows[0])
    print()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"Total run time {time.perf_counter() - wall:.0f} s; peak memory {peak:.0f} MB")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
