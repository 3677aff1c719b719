# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Benchmark: a GPS-like constellation over a short baseline, one day at 1 s.

32 satellites (6 orbital planes, 20200 km altitude, inclination 55 deg,
nominal attitude) seen by the GNSS antenna DBR205 and the alt-az telescope
FD-VLBA (Table 1 of the paper) at 86400 epochs: the feed rotation of every
antenna for every satellite above 10 deg, and the rotation delay FD-VLBA minus
DBR205 at L1 (1575.42 MHz). Prints the wall time of each stage and the peak
memory of the process.

Run with::

    python benchmarks/satellites.py

Needs ``sgp4`` and ``psutil`` (``pip install astropy_feedrot[bench]``).
"""

import argparse
import resource
import time

import numpy as np
from astropy import units as u
from astropy.time import Time

from astropy_feedrot import Satellite, TLEOrbit
from astropy_feedrot.eop import iers_context
from astropy_feedrot.grid import feed_rotation_grid, rotation_delay_grid
from astropy_feedrot.stations import get_antenna

DATE = Time("2023-01-25T00:00:00", scale="utc")
L1 = 1575.42 * u.MHz

#: Satellites per orbital plane: 32 in 6 planes.
SLOTS = (6, 6, 5, 5, 5, 5)


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


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--step", type=float, default=1.0, help="sampling interval in s")
    parser.add_argument("--hours", type=float, default=24.0, help="length of the series")
    parser.add_argument("--no-check", action="store_true",
                        help="skip the comparison with Antenna.feed_rotation")
    args = parser.parse_args(argv)

    start = time.perf_counter()
    antennas = [get_antenna("DBR205"), get_antenna("FD-VLBA")]
    satellites = constellation()
    times = DATE + np.arange(0, args.hours * 3600, args.step) * u.s
    with iers_context():
        DATE.ut1  # astropy reads its IERS tables once per process (about 2 s)
    setup = time.perf_counter()

    phi = feed_rotation_grid(antennas, satellites, times, min_elevation=10 * u.deg)
    grid = time.perf_counter()
    delay, ambiguity = rotation_delay_grid(phi, L1, (0, 1))
    done = time.perf_counter()

    visible = np.isfinite(delay)
    print(f"grid: {times.size} epochs x {len(antennas)} antennas x {len(satellites)} "
          f"satellites = {phi.size} feed rotations ({np.count_nonzero(np.isfinite(phi))} above "
          f"10 deg)")
    print(f"setup (antennas, elements, IERS tables): {setup - start:5.2f} s")
    print(f"feed_rotation_grid:                      {grid - setup:5.2f} s")
    print(f"rotation_delay_grid (L1):                {done - grid:5.2f} s")
    print(f"total wall time:                         {done - start:5.2f} s")
    print(f"peak memory (max RSS):                   {peak_rss_mb():5.0f} MB")
    print(f"rotation delay: {np.count_nonzero(np.any(visible, axis=0))} satellites seen by "
          f"both, |delay| up to {np.nanmax(np.abs(delay)):.1f} "
          f"(ambiguity {ambiguity:.1f})")

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
        print(f"check: max |grid - Antenna.feed_rotation| = {worst:.2e} deg "
              f"({phi[sample].size} samples)")


if __name__ == "__main__":
    main()
