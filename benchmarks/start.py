# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""How fast a new user's first commands answer: fresh processes, empty caches.

Each sample runs in a new process whose home directory is a new empty
folder (``HOME`` and ``XDG_CACHE_HOME``), so that nothing kept by an earlier
run (astropy's cache, the package's kept Earth-orientation arrays and nodes)
is there: what a user sees on the first day. It times

* ``python -m astropy_feedrot --version``, ``--help`` and ``natural --help``
  (the ``feedrot`` command), whole, from start to exit: the parser is built
  without importing astropy (`astropy_feedrot.cli.parser`);
* ``import astropy_feedrot`` with the inputs of the README's example;
* the README's first feed rotation (24 epochs of YEBES40M on 3C 84) beyond
  the import, with an empty cache and then again in a second process that
  finds what the first kept.

Each figure is the best of ``--repeat`` samples (the machine may be shared:
the load average is printed). Targets: the three commands at most 0.3 s, the
first feed rotation at most 0.3 s beyond the import with an empty cache.
PASS/FAIL lines close the output; with ``--strict`` a missed target is an
exit status of 1. Run from the repository root: ``python benchmarks/start.py``.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

TARGET_COMMAND_S = 0.3
TARGET_FIRST_S = 0.3

FIRST = """
import time
t0 = time.perf_counter()
import numpy as np
import astropy.units as u
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.time import Time
from astropy_feedrot import AltAzMount, Antenna, NasmythFocus
site = EarthLocation.from_geodetic(-3.0869 * u.deg, 40.5247 * u.deg, 988 * u.m)
source = SkyCoord("03h19m48.16s +41d30m42.1s")
times = Time("2023-01-25T18:00") + np.arange(0, 12, 0.5) * u.hour
t1 = time.perf_counter()
antenna = Antenna(site, AltAzMount(), NasmythFocus("right"), name="YEBES40M")
antenna.feed_rotation(source, times)
t2 = time.perf_counter()
print(t1 - t0, t2 - t1)
"""


def _environment(home):
    cache = os.path.join(home, ".cache")
    os.makedirs(cache, exist_ok=True)
    return dict(os.environ, HOME=home, XDG_CACHE_HOME=cache, XDG_CONFIG_HOME=cache)


def command(args, repeat):
    """Best wall time (s) of ``python -m astropy_feedrot ARGS`` in fresh homes."""
    best = float("inf")
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as home:
            start = time.perf_counter()
            subprocess.run([sys.executable, "-m", "astropy_feedrot", *args], check=True,
                           capture_output=True, env=_environment(home))
            best = min(best, time.perf_counter() - start)
    return best


def first_feed_rotation(repeat):
    """Best (import, first call with an empty cache, first call with a kept cache), s."""
    runs = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as home:
            samples = []
            for _ in range(2):  # the same home: the second finds what the first kept
                out = subprocess.run([sys.executable, "-c", FIRST], check=True,
                                     capture_output=True, text=True, env=_environment(home))
                samples.append([float(value) for value in out.stdout.split()])
            runs.append((samples[0][0], samples[0][1], samples[1][1]))
    return tuple(min(run[k] for run in runs) for k in range(3))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3, help="samples of each (default 3)")
    parser.add_argument("--strict", action="store_true",
                        help="exit with status 1 if a target is missed")
    options = parser.parse_args(argv)
    print(f"Python {sys.version.split()[0]}, load average "
          f"{' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    version = command(["--version"], options.repeat)
    helped = command(["--help"], options.repeat)
    command_help = command(["natural", "--help"], options.repeat)
    imported, empty, kept = first_feed_rotation(options.repeat)
    print(f"feedrot --version: {version:.3f} s")
    print(f"feedrot --help: {helped:.3f} s")
    print(f"feedrot natural --help: {command_help:.3f} s")
    print(f"import and inputs: {imported:.3f} s")
    print(f"first feed rotation, empty cache: {empty:.3f} s beyond the import")
    print(f"first feed rotation, kept cache: {kept:.3f} s beyond the import")
    checks = [(f"feedrot --version {version:.3f} <= {TARGET_COMMAND_S} s",
               version <= TARGET_COMMAND_S),
              (f"feedrot --help {helped:.3f} <= {TARGET_COMMAND_S} s",
               helped <= TARGET_COMMAND_S),
              (f"feedrot natural --help {command_help:.3f} <= {TARGET_COMMAND_S} s",
               command_help <= TARGET_COMMAND_S),
              (f"first feed rotation, empty cache, {empty:.3f} <= {TARGET_FIRST_S} s",
               empty <= TARGET_FIRST_S)]
    for text, passed in checks:
        print(f"{'PASS' if passed else 'FAIL'}: {text}")
    print(f"load average at the end {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    return 1 if options.strict and not all(passed for _, passed in checks) else 0


if __name__ == "__main__":
    sys.exit(main())
