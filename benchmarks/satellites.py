# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Benchmark: satellites through the grid and the object API.

Three measurements, all in the same run:

* SGP4 for 32 GPS-like satellites (6 orbital planes, 20200 km altitude,
  inclination 55 deg) over one day at 1 s (86400 epochs): evaluated at every
  epoch, and at nodes and interpolated (the default), with the largest
  position difference between the two;
* the grid: the feed rotation of those satellites (nominal attitude) at the
  GNSS antenna DBR205 and the alt-az telescope FD-VLBA (Table 1 of the paper)
  with `astropy_feedrot.engine.grid.feed_rotation_grid`, then the rotation delay
  FD-VLBA minus DBR205 at L1; target: the grid under 3 s;
* the object API: ``Antenna.feed_rotation(satellite, times)`` for 3 antennas
  (DBR205, FD-VLBA, WETTZ13S) and GPS SVN 76 at 20000 epochs (1 s), against
  the grid for the same work; target: at most 1.5 times the grid's time.

Each time is the best of ``--repeat`` runs (the machine may be shared). A
profile (cProfile) of one run of each shows how the time splits between Earth
orientation, the Sun, SGP4, the TEME to ITRS rotation, the attitude and the
rest. PASS/FAIL lines close the output; with ``--strict`` the exit status is 1 if
one fails.

Run from the repository root with::

    python benchmarks/satellites.py

Needs ``sgp4`` (``pip install astropy_feedrot[bench]``); runs offline on the
Earth orientation tables bundled with astropy.
"""

import argparse
import cProfile
import os
import pstats
import resource
import sys
import time

import numpy as np
from astropy import units as u
from astropy.time import Time
from sgp4.api import Satrec

from astropy_feedrot import Satellite, TLEOrbit
from astropy_feedrot.applied.simulations import gps_svn76
from astropy_feedrot.earth.eop import iers_context
from astropy_feedrot.earth.orientation import clear_orientation_cache
from astropy_feedrot.engine.grid import feed_rotation_grid, rotation_delay_grid
from astropy_feedrot.stations.catalogue import get_antenna
from astropy_feedrot.transmitters.propagation import propagate

DATE = Time("2023-01-25T00:00:00", scale="utc")
L1 = 1575.42 * u.MHz

#: Satellites per orbital plane: 32 in 6 planes.
SLOTS = (6, 6, 5, 5, 5, 5)

#: Targets.
GRID_SECONDS = 3.0
OBJECT_OVER_GRID = 1.5
PROMISE_M = 1e-3

#: Where the time goes: (label, module file, function names), summed as
#: cumulative times of the profile.
PARTS = [
    ("Earth orientation (EarthOrientation)", "earth.py", ("__init__",)),
    ("the Sun", "attitude.py", ("interpolated_sun_position", "sun_position")),
    ("SGP4 (nodes + interpolation)", "propagation.py", ("propagate",)),
    ("TEME -> ITRS rotation", "earth.py", ("teme_to_itrs",)),
    ("nominal attitude (Eqs 26-27)", "attitude.py", ("nominal_dipoles",)),
]


def constellation(epoch=DATE, slots=SLOTS):
    """GPS-like satellites: circular orbits, 20200 km, 55 deg, nominal attitude."""
    satellites = []
    for plane, count in enumerate(slots):
        for slot in range(count):
            orbit = TLEOrbit.from_elements(
                epoch, inclination=55 * u.deg, raan=plane * 360 / len(slots) * u.deg,
                altitude=20200 * u.km,
                mean_anomaly=(slot * 360 / count + plane * 15) % 360 * u.deg,
                satnum=90000 + 10 * plane + slot)
            satellites.append(Satellite(orbit, name=f"P{plane}S{slot}"))
    return satellites


def peak_rss_mb():
    """Peak resident memory of this process (Linux reports kilobytes)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def best_of(repeat, function):
    """The smallest wall time of ``repeat`` calls, and the last result."""
    best = np.inf
    for _ in range(repeat):
        clear_orientation_cache()  # every run from nothing, as a first call
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def breakdown(function):
    """Fractions of the profiled time of ``function()`` spent in each of PARTS."""
    profile = cProfile.Profile()
    profile.enable()
    function()
    profile.disable()
    stats = pstats.Stats(profile).stats
    total = sum(tt for (_, _, _), (_, _, tt, _, _) in stats.items())
    rows = []
    for label, filename, names in PARTS:
        spent = sum(ct for (path, _, name), (_, _, _, ct, _) in stats.items()
                    if os.path.basename(path) == filename and name in names
                    and "astropy_feedrot" in path)
        rows.append((label, spent / total))
    rows.append(("everything else (receivers, phases, checks)",
                 1 - sum(fraction for _, fraction in rows)))
    return rows


def print_breakdown(title, rows):
    print(f"  {title}:")
    for label, fraction in rows:
        print(f"    {label:46s} {100 * fraction:5.1f} %")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--step", type=float, default=1.0, help="sampling interval in s")
    parser.add_argument("--hours", type=float, default=24.0, help="length of the series")
    parser.add_argument("--epochs", type=int, default=20000,
                        help="epochs of the object-API comparison")
    parser.add_argument("--repeat", type=int, default=2, help="runs of each timing")
    parser.add_argument("--no-check", action="store_true",
                        help="skip the comparison with Antenna.feed_rotation")
    parser.add_argument("--no-profile", action="store_true", help="skip the profiles")
    parser.add_argument("--strict", action="store_true",
                        help="exit with status 1 if a target is missed (default: report only)")
    args = parser.parse_args(argv)

    start = time.perf_counter()
    antennas = [get_antenna("DBR205"), get_antenna("FD-VLBA")]
    satellites = constellation()
    times = DATE + np.arange(0, args.hours * 3600, args.step) * u.s
    with iers_context():
        DATE.ut1  # astropy reads its IERS tables once per process (about 2 s)
    setup = time.perf_counter() - start
    print(f"setup (antennas, elements, IERS tables): {setup:6.2f} s")
    results = []

    # --- SGP4: every epoch against nodes ----------------------------------------
    satrecs = [Satrec.twoline2rv(sat.orbit.line1, sat.orbit.line2) for sat in satellites]
    jd1 = np.ascontiguousarray(times.utc.jd1, dtype=float)
    jd2 = np.ascontiguousarray(times.utc.jd2, dtype=float)
    direct_s, (_, exact) = best_of(1, lambda: propagate(satrecs, jd1, jd2, interpolate=False))
    nodes_s, (_, fast) = best_of(args.repeat, lambda: propagate(satrecs, jd1, jd2))
    worst = float(np.max(np.linalg.norm(fast - exact, axis=-1)))
    n = len(satrecs) * times.size
    print(f"\nSGP4, {len(satrecs)} satellites x {times.size} epochs:")
    print(f"  at every epoch:              {direct_s:6.2f} s ({1e6 * direct_s / n:.3f} us each)")
    print(f"  at nodes, interpolated:      {nodes_s:6.2f} s ({1e6 * nodes_s / n:.3f} us each; "
          f"{direct_s / nodes_s:.0f}x faster)")
    print(f"  largest position difference: {1e3 * worst:.3f} mm")
    results.append((f"interpolated SGP4 within 1 mm of SGP4 ({1e3 * worst:.3f} mm)",
                    worst < PROMISE_M))

    # --- the grid ------------------------------------------------------------------
    grid_s, phi = best_of(args.repeat, lambda: feed_rotation_grid(
        antennas, satellites, times, min_elevation=10 * u.deg))
    delay_start = time.perf_counter()
    delay, ambiguity = rotation_delay_grid(phi, L1, (0, 1))
    delay_s = time.perf_counter() - delay_start
    visible = np.isfinite(delay)
    print(f"\ngrid: {times.size} epochs x {len(antennas)} antennas x {len(satellites)} "
          f"satellites = {phi.size} feed rotations ({np.count_nonzero(np.isfinite(phi))} above "
          f"10 deg)")
    print(f"  feed_rotation_grid:          {grid_s:6.2f} s (best of {args.repeat})")
    print(f"  rotation_delay_grid (L1):    {delay_s:6.2f} s")
    print(f"  rotation delay: {np.count_nonzero(np.any(visible, axis=0))} satellites seen by "
          f"both, |delay| up to {np.nanmax(np.abs(delay)):.1f} (ambiguity {ambiguity:.1f})")
    results.append((f"grid, one day at 1 s x 32 satellites x 2 antennas, under "
                    f"{GRID_SECONDS:g} s ({grid_s:.2f} s)", grid_s < GRID_SECONDS))

    # --- the object API against the grid ----------------------------------------------
    three = antennas + [get_antenna("WETTZ13S")]
    gps = gps_svn76()
    series = DATE + np.arange(args.epochs) * u.s
    feed_rotation_grid(three, [gps], series[:100])  # warm up both paths
    [antenna.feed_rotation(gps, series[:100]) for antenna in three]
    one_grid_s, small = best_of(args.repeat + 1, lambda: feed_rotation_grid(three, [gps], series))
    object_s, each = best_of(args.repeat + 1,
                             lambda: [antenna.feed_rotation(gps, series) for antenna in three])
    agree = max(float(np.nanmax(np.abs((small[:, i, 0] - each[i]).wrap_at(180 * u.deg).deg)))
                for i in range(len(three)))
    ratio = object_s / one_grid_s
    print(f"\nobject API: {len(three)} antennas x 1 satellite x {series.size} epochs")
    print(f"  feed_rotation_grid:          {1e3 * one_grid_s:6.1f} ms")
    print(f"  Antenna.feed_rotation x {len(three)}:   {1e3 * object_s:6.1f} ms "
          f"({ratio:.2f}x the grid)")
    print(f"  largest difference:          {agree:.1e} deg")
    results.append((f"object API within {OBJECT_OVER_GRID:g}x the grid ({ratio:.2f}x)",
                    ratio <= OBJECT_OVER_GRID))

    if not args.no_profile:
        print("\nwhere the time goes (cProfile, fractions of the profiled time):")
        print_breakdown(f"object API, {len(three)} antennas x {series.size} epochs",
                        breakdown(lambda: [a.feed_rotation(gps, series) for a in three]))
        print_breakdown(f"grid, {len(antennas)} antennas x {len(satellites)} satellites x "
                        f"{times.size} epochs",
                        breakdown(lambda: feed_rotation_grid(antennas, satellites, times,
                                                             min_elevation=10 * u.deg)))

    if not args.no_check:
        # Every 10 min, each pair against Antenna.feed_rotation (not timed).
        sample = slice(None, None, max(1, int(600 / args.step)))
        worst = 0.0
        for i, antenna in enumerate(antennas):
            for j, satellite in enumerate(satellites):
                reference = antenna.feed_rotation(satellite, times[sample],
                                                  min_elevation=10 * u.deg)
                difference = (phi[sample, i, j] - reference).wrap_at(180 * u.deg)
                worst = max(worst, float(np.nanmax(np.abs(difference.deg), initial=0)))
        print(f"\ncheck: max |grid - Antenna.feed_rotation| = {worst:.2e} deg "
              f"({phi[sample].size} samples)")

    print(f"\npeak memory (max RSS): {peak_rss_mb():.0f} MB")
    print()
    for label, passed in results:
        print(f"{'PASS' if passed else 'FAIL'}: {label}")
    return 1 if args.strict and not all(passed for _, passed in results) else 0


if __name__ == "__main__":
    sys.exit(main())
