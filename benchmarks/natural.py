# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Benchmark: feed rotation of a natural source in every sampling regime.

One antenna (WETTZ13S, alt-az Cassegrain, so its feed rotation is the
parallactic angle) and one source (3C 84), in the sampling regimes of
radio astronomy and geodesy: 1 s for a day, 1 min for a week, 2.6 s for 30
days (a million epochs), 30 s for a year, 1 h for a year; single epochs and a
few (N = 1, 2, 5, 10, 16, 100, one minute apart); and 100 epochs at random
over ten years. For each, the time per epoch, from `~astropy.time.Time` and
`~astropy.coordinates.SkyCoord` inputs to angles, of

* ``fast``: ``antenna.feed_rotation(source, times)`` (the default fast path,
  `astropy_feedrot.earth.EarthOrientation`);
* ``rigorous``: the same with ``astropy_feedrot.conf.fast_path = False``
  (astropy's topocentric ITRS transformation at every epoch);
* ``astroplan``: ``Observer(location=...).parallactic_angle(times, source)``;
* ``astropy+hd2pa``: ``source.transform_to(HADec(...))`` and ``erfa.hd2pa``;

their ratios to the fast path, the largest angle differences against the
rigorous path, and PASS/FAIL lines for the targets of the fast path:

* the first four regimes in at most astroplan's time, and at most 0.4 us per
  epoch at a million epochs;
* 1 h for a year in at most 3 us per epoch, at least 20 times faster than the
  rigorous path;
* no regime, number of epochs or span slower than the rigorous path;
* every regime within 0.1 mas of the rigorous path.

With ``--strict`` the exit status is 1 if one fails. Everything runs offline on the Earth
orientation tables bundled with astropy. Run ``python benchmarks/natural.py
--help`` for the options.
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
from astropy_feedrot.earth import clear_orientation_cache  # noqa: E402
from astropy_feedrot.eop import iers_context  # noqa: E402
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

SOURCE_RA, SOURCE_DEC = "03h19m48.16s", "+41d30m42.1s"  # 3C 84
STATION = "WETTZ13S"
PATHS = ("fast", "rigorous", "astroplan", "astropy+hd2pa")
COMPARED = ("fast", "astroplan", "astropy+hd2pa")
# The paths that --max-slow caps.
SLOW = ("rigorous", "astropy+hd2pa")
WARMUP_EPOCHS = 64
MAS_PER_DEG = 3.6e6
DAY = 86400.0

# Targets of the fast path.
TARGET_ASTROPLAN_RATIO = 1.0   # first four regimes: at most astroplan's time
TARGET_MILLION_US = 0.4        # at a million epochs
TARGET_HOURLY_US = 3.0         # 1 h for a year
TARGET_HOURLY_RATIO = 20.0     # rigorous / fast, 1 h for a year
TARGET_MAS = 0.1


class Regime:
    """A sampling: ``count`` epochs ``step`` seconds apart from ``start`` (UTC),
    or, with ``seed``, at random over ``span`` days."""

    def __init__(self, name, count, step=None, start="2023-01-25T00:00", span=None,
                 seed=None, target=None):
        self.name, self.count, self.step, self.target = name, count, step, target
        begin = Time(start, scale="utc")
        if seed is None:
            offsets = np.arange(count, dtype=float) * step / DAY
        else:
            offsets = np.sort(np.random.default_rng(seed).uniform(0, span, count))
        # Exact sums of whole days and fractions: jd1 + jd2 is the epoch.
        whole = np.floor(offsets)
        self.jd1 = begin.jd1 + whole
        self.jd2 = begin.jd2 + (offsets - whole)

    def make(self, stride=1):
        """Fresh Time and SkyCoord objects for every call, so that no run
        profits from the scale conversions astropy caches on a Time."""
        times = Time(self.jd1[::stride], self.jd2[::stride], format="jd", scale="utc")
        return SkyCoord(SOURCE_RA, SOURCE_DEC, frame="icrs"), times


REGIMES = [
    Regime("1 s x 1 day", 86400, 1.0, target="astroplan"),
    Regime("1 min x 1 week", 10080, 60.0, target="astroplan"),
    Regime("2.6 s x 30 days", 1000000, 2.592, target="astroplan"),
    Regime("30 s x 1 year", 1051200, 30.0, start="2023-01-01T00:00", target="astroplan"),
    Regime("1 h x 1 year", 8760, 3600.0, start="2023-01-01T00:00", target="hourly"),
] + [Regime(f"N = {n}", n, 60.0) for n in (1, 2, 5, 10, 16, 100)] + [
    Regime("100 over 10 years", 100, start="2013-01-01T00:00", span=3652.0, seed=1),
]


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


def measure(runner, antenna, regime, stride, repeats, budget):
    """Best time per epoch (us) of up to ``repeats`` calls within ``budget`` s, and the result."""
    best, spent, result, count = math.inf, 0.0, None, 0
    for _ in range(repeats):
        source, times = regime.make(stride)
        count = times.size
        result = None
        clear_orientation_cache()  # every run from nothing, as a first call
        gc.collect()
        t0 = time.perf_counter()
        result = runner(antenna, source, times)
        elapsed = time.perf_counter() - t0
        best, spent = min(best, elapsed), spent + elapsed
        if spent >= budget:
            break
    return best / count * 1e6, degrees(result)


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
    print(f"astropy_feedrot   {astropy_feedrot.__version__} "
          f"({os.path.dirname(astropy_feedrot.__file__)})")
    print(f"platform          {platform.platform()}")
    print(f"CPU               {cpu_model()}; {os.cpu_count()} CPUs, {usable} usable; "
          f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())} at the start")
    if ASTROPLAN_PATCHED_UT1:
        print("note              astroplan replaced Time._get_delta_ut1_utc on import "
              "(no IERS table); the original was restored")
    print()


def fmt_value(value, estimated, digits=2):
    if value is None or not math.isfinite(value):
        return "-"
    text = f"{value:.{digits}f}" if value < 1000 else f"{value:.0f}"
    return text + ("*" if estimated else "")


def fmt_mas(value):
    if value is None or not math.isfinite(value):
        return "-"
    if value < 1e-3:
        return f"{value:.1e}"
    return f"{value:.4f}" if value < 1 else f"{value:.2f}" if value < 1e4 else f"{value:.0f}"


def print_tables(rows, args):
    paths = [p for p in PATHS if any(p in row["us"] for row in rows)]
    ratios = [p for p in paths if p != "fast"]
    width = max(len(row["name"]) for row in rows) + 2
    columns = paths + [p.split("+")[0] + "/fast" for p in ratios]
    widths = [max(len(c) + 2, 10) for c in columns]
    print(f"Time per epoch (us): best of up to {args.repeats} runs within {args.budget:g} s "
          "per path and regime, all transformations included")
    print(f"{'regime':<{width}}{'epochs':>9}"
          + "".join(f"{c:>{w}}" for c, w in zip(columns, widths)))
    for row in rows:
        cells = [fmt_value(row["us"].get(p), p in row["estimated"]) for p in paths]
        for p in ratios:
            value = row["us"].get(p)
            ratio = value / row["us"]["fast"] if value is not None else None
            cells.append(fmt_value(ratio, p in row["estimated"], 2 if ratio and ratio < 10 else 1))
        print(f"{row['name']:<{width}}{row['count']:>9}"
              + "".join(f"{c:>{w}}" for c, w in zip(cells, widths)))
    if any(row["estimated"] for row in rows):
        print(f"* above --max-slow {args.max_slow:g} epochs: run on every k-th epoch (at most "
              f"{args.max_slow:g}); the time per epoch there is extrapolated to the full series")
    print()
    print("Largest |difference| against the rigorous path (mas, wrapped to +-180 deg)")
    print(f"{'regime':<{width}}{'compared':>9}" + "".join(f"{p:>15}" for p in COMPARED))
    for row in rows:
        line = f"{row['name']:<{width}}{row['compared']:>9}"
        line += "".join(f"{fmt_mas(row['mas'].get(p)):>15}" for p in COMPARED)
        print(line + ("  (every %dth epoch)" % row["stride"] if row["stride"] > 1 else ""))
    print()


def check_targets(rows):
    """The PASS/FAIL lines; True if all pass."""
    checks = []
    star = {True: "*", False: ""}
    for row in rows:
        us, fast = row["us"], row["us"]["fast"]
        if row["target"] == "astroplan" and "astroplan" in us:
            checks.append((fast <= TARGET_ASTROPLAN_RATIO * us["astroplan"],
                           f"{row['name']}: fast {fast:.3f} us/epoch <= "
                           f"{TARGET_ASTROPLAN_RATIO:g} x astroplan {us['astroplan']:.3f}"))
        if row["count"] >= 10**6:
            checks.append((fast <= TARGET_MILLION_US,
                           f"{row['name']}: fast {fast:.3f} <= {TARGET_MILLION_US} us/epoch "
                           f"at {row['count']} epochs"))
        if row["target"] == "hourly":
            ratio = us["rigorous"] / fast
            checks.append((fast <= TARGET_HOURLY_US,
                           f"{row['name']}: fast {fast:.2f} <= {TARGET_HOURLY_US} us/epoch"))
            checks.append((ratio >= TARGET_HOURLY_RATIO,
                           f"{row['name']}: rigorous/fast {ratio:.1f}"
                           f"{star['rigorous' in row['estimated']]} >= {TARGET_HOURLY_RATIO:g}"))
    slower = [row["name"] for row in rows if row["us"]["fast"] > row["us"]["rigorous"]]
    worst = min(rows, key=lambda row: row["us"]["rigorous"] / row["us"]["fast"])
    checks.append((not slower,
                   "fast no slower than rigorous in every regime: "
                   + (f"slower in {', '.join(slower)}" if slower else
                      f"smallest ratio {worst['us']['rigorous'] / worst['us']['fast']:.2f} "
                      f"({worst['name']})")))
    far = [row["name"] for row in rows if not row["mas"]["fast"] <= TARGET_MAS]
    largest = max(rows, key=lambda row: row["mas"]["fast"])
    checks.append((not far,
                   f"fast within {TARGET_MAS} mas of rigorous in every regime: "
                   + (f"not in {', '.join(far)}" if far else
                      f"largest {fmt_mas(largest['mas']['fast'])} mas ({largest['name']})")))
    print("Targets of the fast path")
    for ok, text in checks:
        print(f"  {'PASS' if ok else 'FAIL'}  {text}")
    return all(ok for ok, _ in checks)


# --------------------------------------------------------------------------

def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    names = [r.name for r in REGIMES]
    parser.add_argument("--regimes", default=None,
                        help="comma-separated regime numbers to run (1-based, in the order "
                             "of the table; default all): " + "; ".join(
                                 f"{k + 1} = {n}" for k, n in enumerate(names)))
    parser.add_argument("--max-slow", type=lambda s: int(float(s)), default=2 * 10**6,
                        help="largest number of epochs at which the slow paths (rigorous, "
                             "astropy+hd2pa) run; larger regimes run them on every k-th epoch "
                             "and extrapolate the time per epoch (default 2e6: everything; "
                             "1e5 makes the run a few times shorter)")
    parser.add_argument("--repeats", type=int, default=5,
                        help="largest number of timed runs per path and regime (default 5)")
    parser.add_argument("--strict", action="store_true",
                        help="exit with status 1 if a target is missed (default: report only)")
    parser.add_argument("--budget", type=float, default=2.0,
                        help="stop repeating a path once this many seconds are spent "
                             "(default 2)")
    args = parser.parse_args(argv)
    if args.max_slow < 1 or args.repeats < 1:
        parser.error("--max-slow and --repeats must be positive")
    if args.regimes:
        try:
            chosen = sorted({int(k) for k in args.regimes.split(",")})
        except ValueError:
            parser.error("--regimes takes numbers, e.g. 1,5,6")
        if chosen[0] < 1 or chosen[-1] > len(REGIMES):
            parser.error(f"--regimes must be within 1..{len(REGIMES)}")
        args.regimes = [REGIMES[k - 1] for k in chosen]
    else:
        args.regimes = REGIMES
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
    print(f"Source 3C 84, ICRS {SOURCE_RA} {SOURCE_DEC}")
    print("  fast           antenna.feed_rotation(source, times)")
    print("  rigorous       the same within conf.set_temp('fast_path', False)")
    print("  astroplan      Observer(location=antenna.location).parallactic_angle(times, source)")
    print("  astropy+hd2pa  source.transform_to(HADec(obstime=times, location=...)), "
          "erfa.hd2pa(ha, dec, lat)")
    print()

    # Warm up imports, transformation graphs, IERS tables and caches.
    warm = Regime("warm-up", WARMUP_EPOCHS, 60.0)
    with iers_context():
        Time("2023-01-25").ut1
    for p in paths:
        RUNNERS[p](antenna, *warm.make())

    rows = []
    for regime in args.regimes:
        row = {"name": regime.name, "count": regime.count, "target": regime.target,
               "us": {}, "mas": {}, "estimated": set()}
        stride = max(1, math.ceil(regime.count / args.max_slow))
        row["stride"] = stride
        results = {}
        for p in paths:
            step = stride if p in SLOW else 1
            row["us"][p], results[p] = measure(RUNNERS[p], antenna, regime, step,
                                               args.repeats, args.budget)
            if step > 1:
                row["estimated"].add(p)
        reference = results["rigorous"]
        row["compared"] = reference.size
        for p in COMPARED:
            if p in results:
                values = results[p] if p in SLOW else results[p][::stride]
                row["mas"][p] = max_difference_mas(values, reference)
        rows.append(row)
        measured = ", ".join(f"{p} {row['us'][p]:.2f}" for p in paths)
        print(f"  {regime.name}: {measured} us/epoch")
        del results, reference
    print()

    print_tables(rows, args)
    ok = check_targets(rows)
    print()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"Total run time {time.perf_counter() - wall:.0f} s; peak memory {peak:.0f} MB")
    return 1 if args.strict and not ok else 0


if __name__ == "__main__":
    sys.exit(main())
