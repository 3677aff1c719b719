# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reproduce the satellite simulations of Section 4 of the paper.

Run with ``python examples/paper_section4.py [OUTPUT_DIRECTORY]``. Prints a
summary of both simulations and writes their tables as ECSV files; with
matplotlib installed it also draws figures like the paper's Figs 10-12.
(``feedrot demo`` runs the first of them.)
"""

import sys
from pathlib import Path

from astropy_feedrot.applied.feed_rotation_tables import baseline_summary
from astropy_feedrot.applied.simulations import genesis_long_baseline, gps_short_baseline


def main(directory="."):
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    cases = [
        (gps_short_baseline(), "section4_1_gps"),
        (genesis_long_baseline(), "section4_2_genesis"),
    ]
    for table, stem in cases:
        print(baseline_summary(table))
        table.write(directory / f"{stem}.ecsv", overwrite=True)
        try:
            from astropy_feedrot.applied.plotting import plot_baseline

            plot_baseline(table, directory / f"{stem}.png")
        except ImportError:
            print('  (pip install "astropy_feedrot[all]" for the figures)')


if __name__ == "__main__":
    main(*sys.argv[1:])
