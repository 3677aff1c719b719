# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Benchmark: feed rotation of a natural source at every number of epochs and span.

One antenna (WETTZ13S, alt-az Cassegrain, so its feed rotation is the
parallactic angle) and one source (3C 84), in the sampling regimes of
radio astronomy and geodesy: per call (N = 1, 2, 5, 10, 16, 100, 1000 epochs
a minute apart), 100 epochs at random over ten years, 1 h for a year, and
the dense regimes (1 s for a day, 1 min for a week, 2.6 s for 30 days, 30 s
for a year). For each, the time per epoch, from `~astropy.time.Time` and
`~astropy.coordinates.SkyCoord` inputs to angles, of

* ``fast``: ``antenna.feed_rotation(source, times)``, cold: the Earth
  orientations of earlier calls forgotten before each call
  (`~astropy_feedrot.earth.orientation.clear_orientation_cache`); what depends on nothing
  but the day, the site and the IERS tables (the nodes of the slow series,
  `~astropy_feedrot.earth.nodes.KeptSeries`, the IERS arrays, the site's position)
  stays, as in any process after its first call at those dates;
* ``warm``: the same call again at the same epochs (fresh objects, caches kept);
* ``rigorous``: the same with ``astropy_feedrot.conf.fast_path = False``
  (astropy's topocentric ITRS transformation at every epoch);
* ``astroplan``: ``Observer(location=...).parallactic_angle(times, source)``;
* ``astropy+hd2pa``: ``source.transform_to(HADec(...))`` and ``erfa.hd2pa``;
* ``erfa``: ERFA called directly from the `~astropy.time.Time` (``atco13``
  with astropy's UT1 - UTC and polar motion, then ``hd2pa``);
* ``casacore``: python-casacore measures (the parallactic angle as CASA
  computes it: position angle of the pole in ``AZEL``), one epoch per
  ``do_frame``, as its API goes;
* ``skyfield``: Skyfield's apparent position of a ``Star`` (JPL de421 and the
  IERS finals with polar motion, both from ``skyfield-data``, offline) in its
  ``itrs`` frame, and Eq 15 against the Earth-fixed pole and the geodetic
  vertical: the pole ours measures from (Skyfield's ``hadec()`` measures from
  the celestial intermediate pole, polar motion over cos(el) away);

their ratios to the fast path, the largest angle differences against the
rigorous path, the first call of a fresh process (beyond the import), and
PASS/FAIL lines for the targets:

* one epoch per call: at most casacore's time; 10 epochs: at most half of
  ERFA's; 100 and 1,000 epochs: at most astroplan's;
* 100 epochs over ten years: at most 20 us per epoch; 1 h for a year: at most
  1 us per epoch; the dense regimes (1 s for a day, 2.6 s for 30 days, 30 s
  for a year): at most 0.25 us per epoch; 1 min for a week: at most
  astroplan's time;
* the first call in a fresh process: at most 0.1 s beyond the import;
* no regime slower than the rigorous path, cold or warm;
* every regime within 0.1 mas of the rigorous path.

Times are the best of repeated runs, the paths of a regime taking turns so
that a slow spell of a shared machine falls on all of them alike (compare
the ratios of one run; the load average is printed at the start and the end).
With ``--strict`` the exit status is 1 if a target is missed. Everything runs
offline on the Earth orientation tables bundled with astropy. Run
``python benchmarks/natural.py --help`` for the options.
"""

import astropy.utils.data

# Offline before anything else imports astropy's IERS machinery.
from astropy.utils import iers

iers.conf.auto_download = False
astropy.utils.data.conf.allow_internet = False

import argparse  # noqa: E402
import gc  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402
import platform  # noqa: E402
import resource  # noqa: E402
import socket  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import astropy  # noqa: E402
import astropy.units as u  # noqa: E402
import erfa  # noqa: E402
import numpy as np  # noqa: E402
from astropy.coordinates import HADec, SkyCoord  # noqa: E402
from astropy.coordinates.builtin_frames.utils import get_polar_motion  # noqa: E402
from astropy.time import Time  # noqa: E402

import astropy_feedrot  # noqa: E402
from astropy_feedrot.earth.eop import iers_context  # noqa: E402
from astropy_feedrot.earth.orientation import clear_orientation_cache  # noqa: E402
from astropy_feedrot.engine.antenna import Antenna  # noqa: E402
from astropy_feedrot.engine.equations import parallactic_angle  # noqa: E402
from astropy_feedrot.stations.catalogue import get_antenna  # noqa: E402


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
try:  # python-casacore is in the "bench" extra
    import casacore
    from casacore.measures import measures
    from casacore.quanta import quantity
    casacore_version = getattr(casacore, "__version__", "installed")
except ImportError:  # pragma: no cover
    measures = quantity = casacore_version = None
Time._get_delta_ut1_utc = _DELTA_UT1_UTC

try:  # skyfield and skyfield-data (JPL's de421 and the IERS finals, offline) are in "bench"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # skyfield-data's "has expired": dates here are older
        import skyfield
        import skyfield_data
        from skyfield.api import Loader, Star, wgs84
        from skyfield.data import iers as skyfield_iers
        from skyfield.framelib import itrs as skyfield_itrs
except ImportError:  # pragma: no cover
    skyfield = None

SOURCE_RA, SOURCE_DEC = "03h19m48.16s", "+41d30m42.1s"  # 3C 84
STATION = "WETTZ13S"
PATHS = ("fast", "warm", "rigorous", "astroplan", "astropy+hd2pa", "erfa", "casacore",
         "skyfield")
# Compared with the rigorous path for accuracy. casacore is compared with the
# rigorous path of the same antenna with vertical="geocentric" instead: its
# AZEL frame is topocentric with the geocentric vertical (AZELGEO would be the
# geodetic one), which moves the angle by up to ~0.8 deg near the zenith at
# Wettzell; what remains (under an arcsecond) is polar motion, which CASA
# leaves out, and the Earth orientation tables that python-casacore's wheel
# ships (older than astropy's).
# Skyfield gives its apparent direction in ITRS (its polar motion installed from
# the IERS finals of skyfield-data); the angle is then Eq 15 against the same
# Earth-fixed pole and geodetic vertical as ours (its hadec() would measure
# from the celestial intermediate pole instead).
COMPARED = ("fast", "warm", "astroplan", "astropy+hd2pa", "erfa", "skyfield")
# The paths that --max-slow caps.
SLOW = ("rigorous", "astropy+hd2pa", "erfa", "casacore", "skyfield")
# Paths computed one epoch per call of the peer (capped harder, --max-loop).
LOOPED = ("casacore",)
WARMUP_EPOCHS = 64
MAS_PER_DEG = 3.6e6
DAY = 86400.0

# Targets of the fast path (time per epoch, us, or ratios to a peer's time).
TARGET_SPARSE_US = 20.0       # 100 epochs over 10 years
TARGET_HOURLY_US = 1.0        # 1 h for a year
TARGET_DENSE_US = 0.25        # 1 s for a day ... 30 s for a year
TARGET_ERFA_RATIO = 0.5       # 10 epochs: at most half of ERFA's time
TARGET_FIRST_CALL_S = 0.1     # first call of a fresh process, beyond the import
TARGET_MAS = 0.1


class Regime:
    """A sampling: ``count`` epochs ``step`` seconds apart from ``start`` (UTC),
    or, with ``seed``, at random over ``span`` days. ``target`` names the
    regime's target: a peer ("casacore", "erfa", "astroplan") or a time per
    epoch ("sparse", "hourly", "dense")."""

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
        if self.count == 1:
            times = times[0]  # one epoch per call: a scalar Time, as callers pass it
        return SkyCoord(SOURCE_RA, SOURCE_DEC, frame="icrs"), times


REGIMES = [
    Regime("N = 1", 1, 60.0, target="casacore"),
    Regime("N = 2", 2, 60.0),
    Regime("N = 5", 5, 60.0),
    Regime("N = 10", 10, 60.0, target="erfa"),
    Regime("N = 16", 16, 60.0),
    Regime("N = 100", 100, 60.0, target="astroplan"),
    Regime("N = 1000", 1000, 60.0, target="astroplan"),
    Regime("100 over 10 years", 100, start="2013-01-01T00:00", span=3652.0, seed=1,
           target="sparse"),
    Regime("1 h x 1 year", 8760, 3600.0, start="2023-01-01T00:00", target="hourly"),
    Regime("1 s x 1 day", 86400, 1.0, target="dense"),
    Regime("1 min x 1 week", 10080, 60.0, target="astroplan"),
    Regime("2.6 s x 30 days", 1000000, 2.592, target="dense"),
    Regime("30 s x 1 year", 1051200, 30.0, start="2023-01-01T00:00", target="dense"),
]


# --------------------------------------------------------------------------
# The computations: inputs (a SkyCoord and a Time) to angles.

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


def run_erfa(antenna, source, times):
    """ERFA from a Time: atco13 (ICRS to observed, no refraction) and hd2pa."""
    location = antenna.location
    lon, lat, height = location.to_geodetic("WGS84")
    utc = times.utc
    with iers_context(times):
        dut1 = utc.delta_ut1_utc
        xp, yp = get_polar_motion(utc)
    _, _, hob, dob, _, _ = erfa.atco13(
        source.ra.rad, source.dec.rad, 0.0, 0.0, 0.0, 0.0, utc.jd1, utc.jd2, dut1,
        lon.rad, lat.rad, height.to_value(u.m), xp, yp, 0.0, 0.0, 0.0, 0.0)
    return erfa.hd2pa(hob, dob, lat.rad) * u.rad


_CASACORE = {}


def run_casacore(antenna, source, times):
    """casacore measures: the position angle of the pole in AZEL, one epoch per frame."""
    dm = _CASACORE.get("measures")
    if dm is None:
        dm = _CASACORE["measures"] = measures()
    x, y, z = (c.to_value(u.m) for c in antenna.location.to_geocentric())
    dm.do_frame(dm.position("itrf", f"{x}m", f"{y}m", f"{z}m"))
    direction = dm.direction("J2000", f"{source.ra.deg}deg", f"{source.dec.deg}deg")
    pole = dm.direction("HADEC", "0deg", "90deg")
    mjd = np.atleast_1d(times.utc.mjd)
    out = np.empty(mjd.shape)
    for k, day in enumerate(mjd):
        dm.do_frame(dm.epoch("utc", quantity(day, "d")))
        out[k] = dm.posangle(dm.measure(direction, "AZEL"),
                             dm.measure(pole, "AZEL")).get_value("rad")
    return out * u.rad


_SKYFIELD = {}


def _skyfield():
    """Skyfield's timescale (with polar motion) and JPL de421, from skyfield-data, once."""
    if not _SKYFIELD:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # skyfield-data's "has expired"
            load = Loader(skyfield_data.get_skyfield_data_path())
            ts = load.timescale(builtin=True)
            with load.open("finals2000A.all") as f:
                finals = skyfield_iers.parse_x_y_dut1_from_finals_all(f)
            skyfield_iers.install_polar_motion_table(ts, finals)
            _SKYFIELD.update(ts=ts, earth=load("de421.bsp")["earth"])
    return _SKYFIELD["ts"], _SKYFIELD["earth"]


def run_skyfield(antenna, source, times):
    """Skyfield: the apparent position in ITRS, then Eq 15 (z pole, geodetic vertical)."""
    ts, earth = _skyfield()
    lon, lat, height = antenna.location.to_geodetic("WGS84")
    site = earth + wgs84.latlon(lat.deg, lon.deg, elevation_m=height.to_value(u.m))
    star = Star(ra_hours=source.ra.hour, dec_degrees=source.dec.deg)
    apparent = site.at(ts.from_astropy(times)).observe(star).apparent()
    s = np.moveaxis(apparent.frame_xyz(skyfield_itrs).au, 0, -1)
    s = s / np.linalg.norm(s, axis=-1, keepdims=True)
    return parallactic_angle(s, antenna.local_frame.up) * u.rad


RUNNERS = {"fast": run_fast, "warm": run_fast, "rigorous": run_rigorous,
           "astroplan": run_astroplan, "astropy+hd2pa": run_astropy, "erfa": run_erfa,
           "casacore": run_casacore, "skyfield": run_skyfield}


def degrees(angle):
    """Angles of any of the runners as a float64 array in degrees."""
    return np.asarray(u.Quantity(angle).to_value(u.deg), dtype=float).ravel()


def max_difference_mas(a, b):
    """Largest absolute difference, wrapped to +-180 deg, in mas."""
    d = (a - b + 180.0) % 360.0 - 180.0
    return float(np.nanmax(np.abs(d))) * MAS_PER_DEG


def measure(paths, antenna, regime, steps, repeats, budget):
    """Best time per epoch (us) of each path, and its result: up to ``repeats`` rounds.

    In each round every path takes one sample in turn, so that a slow spell
    of the shared machine falls on all paths alike instead of on the one
    measured then; a path stops once it has spent ``budget`` s. A sample is
    one call, or, for fewer than 1000 epochs, the mean of as many calls as
    make 1000 epochs (timer resolution). ``fast`` clears the package's caches
    before every call (cold); ``warm`` computes the same epochs once first and
    keeps them. ``steps[path]`` thins the epochs of the slow paths.
    """
    best = {p: math.inf for p in paths}
    spent = {p: 0.0 for p in paths}
    results = {}
    if "warm" in paths:
        RUNNERS["warm"](antenna, *regime.make(steps["warm"]))
    for _ in range(repeats):
        for path in paths:
            if spent[path] >= budget:
                continue
            runner = RUNNERS[path]
            calls = max(1, 1000 // regime.count) if path not in LOOPED else 1
            inputs = [regime.make(steps[path]) for _ in range(calls)]
            count = np.size(inputs[0][1])
            gc.collect()
            elapsed = 0.0
            for source, times in inputs:
                if path == "fast":
                    clear_orientation_cache()  # every call from nothing, as a first call
                t0 = time.perf_counter()
                results[path] = runner(antenna, source, times)
                elapsed += time.perf_counter() - t0
            best[path] = min(best[path], elapsed / calls / count * 1e6)
            spent[path] += elapsed
    return best, {p: degrees(r) for p, r in results.items()}


FIRST_CALL = """
import time
t0 = time.perf_counter()
import astropy_feedrot
from astropy.coordinates import SkyCoord
from astropy.time import Time
antenna = astropy_feedrot.get_antenna({station!r})
source = SkyCoord({ra!r}, {dec!r})
times = Time("2023-01-25T20:00")
t1 = time.perf_counter()
antenna.feed_rotation(source, times)
t2 = time.perf_counter()
print(t1 - t0, t2 - t1)
"""


def first_call(repeats=3):
    """Import time and first-call time (s) of fresh processes: the best of ``repeats``."""
    code = FIRST_CALL.format(station=STATION, ra=SOURCE_RA, dec=SOURCE_DEC)
    runs = []
    for _ in range(repeats):
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             check=True)
        runs.append(tuple(float(v) for v in out.stdout.split()))
    return min(r[0] for r in runs), min(r[1] for r in runs)


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


def load_average():
    return " ".join(f"{x:.1f}" for x in os.getloadavg())


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
    print("Feed rotation of a natural source: astropy_feedrot against its peers")
    print()
    print(f"python            {platform.python_version()} ({platform.python_implementation()})")
    print(f"numpy             {np.__version__}")
    print(f"astropy           {astropy.__version__}"
          f"  (IERS auto_download {iers.conf.auto_download}, allow_internet "
          f"{astropy.utils.data.conf.allow_internet}, astropy-iers-data {iers_data})")
    print(f"erfa              pyerfa {erfa.__version__}, ERFA {erfa.version.erfa_version}")
    print(f"astroplan         {astroplan.__version__ if astroplan else 'not installed'}")
    print(f"casacore          {casacore_version or 'not installed'}")
    skyfield_text = (f"{skyfield.__version__} (de421 from skyfield-data)" if skyfield
                     else "not installed")
    print(f"skyfield          {skyfield_text}")
    print(f"astropy_feedrot   {astropy_feedrot.__version__} "
          f"({os.path.dirname(astropy_feedrot.__file__)})")
    print(f"platform          {platform.platform()}")
    print(f"CPU               {cpu_model()}; {os.cpu_count()} CPUs, {usable} usable; "
          f"load average {load_average()} at the start")
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
    ratios = [p for p in paths if p not in ("fast", "warm")]
    width = max(len(row["name"]) for row in rows) + 2
    columns = paths + [p.split("+")[0] + "/fast" for p in ratios]
    widths = [max(len(c) + 2, 10) for c in columns]
    print(f"Time per epoch (us): best of up to {args.repeats} samples within "
          f"{args.budget:g} s per path and regime, the paths taking turns, all "
          "transformations included")
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
        print(f"* run on every k-th epoch (at most --max-slow {args.max_slow:g} epochs, "
              f"--max-loop {args.max_loop:g} for casacore); the time per epoch there is "
              "extrapolated to the full series")
    print()
    compared = [p for p in COMPARED + ("casacore",) if any(p in row["mas"] for row in rows)]
    print("Largest |difference| against the rigorous path (mas, wrapped to +-180 deg; "
          "casacore against it with vertical='geocentric', at its epochs)")
    print(f"{'regime':<{width}}{'compared':>9}" + "".join(f"{p:>15}" for p in compared))
    for row in rows:
        line = f"{row['name']:<{width}}{row['compared']:>9}"
        line += "".join(f"{fmt_mas(row['mas'].get(p)):>15}" for p in compared)
        print(line + ("  (every %dth epoch)" % row["stride"] if row["stride"] > 1 else ""))
    print()


def check_targets(rows, first):
    """The PASS/FAIL lines; True if all pass."""
    checks = []
    for row in rows:
        us, fast, target, name = row["us"], row["us"]["fast"], row["target"], row["name"]
        if target in ("casacore", "astroplan") and target in us:
            checks.append((fast <= us[target], f"{name}: fast {fast:.2f} us/epoch <= "
                                               f"{target} {us[target]:.2f}"))
        elif target == "erfa" and "erfa" in us:
            checks.append((fast <= TARGET_ERFA_RATIO * us["erfa"],
                           f"{name}: fast {fast:.2f} us/epoch <= {TARGET_ERFA_RATIO:g} x "
                           f"erfa {us['erfa']:.2f}"))
        elif target in ("sparse", "hourly", "dense"):
            limit = {"sparse": TARGET_SPARSE_US, "hourly": TARGET_HOURLY_US,
                     "dense": TARGET_DENSE_US}[target]
            checks.append((fast <= limit, f"{name}: fast {fast:.3f} <= {limit:g} us/epoch"))
    if first is not None:
        checks.append((first <= TARGET_FIRST_CALL_S,
                       f"first call of a fresh process: {first:.3f} <= "
                       f"{TARGET_FIRST_CALL_S:g} s beyond the import"))
    for path in ("fast", "warm"):
        slower = [row["name"] for row in rows if row["us"][path] > row["us"]["rigorous"]]
        worst = min(rows, key=lambda row: row["us"]["rigorous"] / row["us"][path])
        checks.append((not slower,
                       f"{path} no slower than rigorous in every regime: "
                       + (f"slower in {', '.join(slower)}" if slower else
                          f"smallest ratio {worst['us']['rigorous'] / worst['us'][path]:.2f} "
                          f"({worst['name']})")))
    far = [row["name"] for row in rows
           if not max(row["mas"]["fast"], row["mas"]["warm"]) <= TARGET_MAS]
    largest = max(rows, key=lambda row: max(row["mas"]["fast"], row["mas"]["warm"]))
    worst_mas = max(largest["mas"]["fast"], largest["mas"]["warm"])
    checks.append((not far,
                   f"fast and warm within {TARGET_MAS} mas of rigorous in every regime: "
                   + (f"not in {', '.join(far)}" if far else
                      f"largest {fmt_mas(worst_mas)} mas ({largest['name']})")))
    print("Targets")
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
                             "astropy+hd2pa, erfa, skyfield) run; larger regimes run them on every "
                             "k-th epoch and extrapolate the time per epoch (default 2e6: "
                             "everything; 1e5 makes the run a few times shorter)")
    parser.add_argument("--max-loop", type=lambda s: int(float(s)), default=2000,
                        help="the same for casacore, which takes one epoch per call "
                             "(default 2000)")
    parser.add_argument("--repeats", type=int, default=5,
                        help="largest number of timed samples per path and regime (default 5)")
    parser.add_argument("--strict", action="store_true",
                        help="exit with status 1 if a target is missed (default: report only)")
    parser.add_argument("--budget", type=float, default=2.0,
                        help="stop repeating a path once this many seconds are spent "
                             "(default 2)")
    parser.add_argument("--no-first-call", action="store_true",
                        help="do not time the first call of fresh processes")
    args = parser.parse_args(argv)
    if args.max_slow < 1 or args.max_loop < 1 or args.repeats < 1:
        parser.error("--max-slow, --max-loop and --repeats must be positive")
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
    paths = [p for p in PATHS if (p != "astroplan" or Observer is not None)
             and (p != "casacore" or measures is not None)
             and (p != "skyfield" or skyfield is not None)]
    print(f"Antenna {antenna.name}: {antenna.mount!r}, {antenna.focus!r} at "
          f"lat {antenna.location.lat.deg:.4f} deg, lon {antenna.location.lon.deg:.4f} deg")
    print(f"Source 3C 84, ICRS {SOURCE_RA} {SOURCE_DEC}")
    print("  fast           antenna.feed_rotation(source, times), caches cleared (cold)")
    print("  warm           the same, the epochs computed once before (caches kept)")
    print("  rigorous       the same within conf.set_temp('fast_path', False)")
    print("  astroplan      Observer(location=antenna.location).parallactic_angle(times, source)")
    print("  astropy+hd2pa  source.transform_to(HADec(obstime=times, location=...)), "
          "erfa.hd2pa(ha, dec, lat)")
    print("  erfa           erfa.atco13 from the Time (astropy's UT1 - UTC and polar motion), "
          "erfa.hd2pa")
    print("  casacore       measures: posangle of the pole in AZEL, one do_frame per epoch")
    print("  skyfield       site.at(t).observe(Star).apparent() in ITRS (de421, polar motion), "
          "Eq 15 against the Earth-fixed pole")
    print()

    first = None
    if not args.no_first_call:
        imported, first = first_call()
        print(f"First call of a fresh process: {first:.3f} s (import and inputs {imported:.2f} s)")
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
        loop_stride = max(1, math.ceil(regime.count / args.max_loop))
        row["stride"] = stride
        steps = {p: loop_stride if p in LOOPED else stride if p in SLOW else 1 for p in paths}
        row["us"], results = measure(paths, antenna, regime, steps, args.repeats, args.budget)
        row["estimated"] = {p for p in paths if steps[p] > 1}
        reference = results["rigorous"]
        row["compared"] = reference.size
        for p in COMPARED:
            if p in results:
                values = results[p] if p in SLOW else results[p][::stride]
                row["mas"][p] = max_difference_mas(values, reference)
        if "casacore" in results:
            geocentric = Antenna(antenna.location, antenna.mount, antenna.focus,
                                 vertical="geocentric")
            row["mas"]["casacore"] = max_difference_mas(
                results["casacore"],
                degrees(run_rigorous(geocentric, *regime.make(loop_stride))))
        rows.append(row)
        measured = ", ".join(f"{p} {row['us'][p]:.2f}" for p in paths)
        print(f"  {regime.name}: {measured} us/epoch")
        del results, reference
    print()

    print_tables(rows, args)
    ok = check_targets(rows, first)
    print()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"Total run time {time.perf_counter() - wall:.0f} s; peak memory {peak:.0f} MB; "
          f"load average {load_average()} at the end")
    return 1 if args.strict and not ok else 0


if __name__ == "__main__":
    sys.exit(main())
