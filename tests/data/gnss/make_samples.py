# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Make the synthetic GNSS samples shipped in astropy_feedrot/data.

Run from the repository root: ``python tests/data/gnss/make_samples.py``.
"""

from pathlib import Path

from astropy import units as u
from astropy.time import Time

from astropy_feedrot.gnss.synthetic import constellation, write_rinex, write_sp3

DATA = Path(__file__).resolve().parents[3] / "astropy_feedrot" / "data"
START = Time("2023-01-25T00:00:19", scale="tai")  # 00:00:00 GPS time
TYPES = {"G": ("C1C", "L1C", "L2W", "L5Q", "S1C"), "E": ("C1C", "L1C", "L5Q", "L7Q", "S1C"),
         "R": ("C1C", "L1C", "L2C", "L3Q", "S1C"), "C": ("C2I", "L2I", "L6I", "L7I", "S2I")}

if __name__ == "__main__":
    orbits = constellation(START, {"G": 6, "E": 4, "R": 3, "C": 3})
    write_sp3(DATA / "gnss_sample.sp3", orbits, START, 13, 900.0)
    write_rinex(DATA / "gnss_sample.rnx", "3.04", TYPES, list(orbits),
                START + 3600 * u.s, 40, 30.0, zero_direction=0.0)
