# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reproduce the satellite simulations of Section 4 of the paper.

Run with ``python examples/paper_section4.py [OUTPUT_DIRECTORY]``. Prints a
summary of both simulations and writes their tables as ECSV files; with
matplotlib installed it also draws figures like the paper's Figs 10-12.
"""

import sys
from pathlib import Path

import numpy as np
from astropy import units as u

from astropy_feedrot.simulations import genesis_long_baseline, gps_short_baseline


def summarize(table, antennas):
    visible = table["both_visible"]
    times = table["time"][visible]
    print(f"{table.meta['satellite']} over {' and '.join(antennas)}")
    print(f"  both above {table.meta['min_elevation']}: {visible.sum()} epochs, "
          f"{times[0].isot} to {times[-1].isot}")
    for name in antennas:
        tx = table[f"{name}_transmitter"][visible]
        rx = table[f"{name}_receiver"][visible]
        cont = table[f"{name}_continuous"][visible]
        print(f"  {name}: receiver term {np.nanmin(rx):.1f} to {np.nanmax(rx):.1f}, "
              f"transmitter term {np.nanmin(tx):.1f} to {np.nanmax(tx):.1f}, "
              f"continuous total spans {np.nanmax(cont) - np.nanmin(cont):.1f}")
    a, b = antennas
    dtx = ((table[f"{b}_transmitter"] - table[f"{a}_transmitter"] + 180 * u.deg)
           % (360 * u.deg) - 180 * u.deg)[visible]
    print(f"  difference of the transmitter terms: up to {np.nanmax(np.abs(dtx)):.4f}")
    delay = table["rotation_delay"][visible]
    print(f"  rotation delay ({table.meta['frequency']}): {np.nanmin(delay):.1f} to "
          f"{np.nanmax(delay):.1f} (span {np.nanmax(delay) - np.nanmin(delay):.1f}); "
          f"ambiguity {table.meta['ambiguity']}")


def plot(table, antennas, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = (table["time"] - table["time"][0]).to_value(u.hour)
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for ax, name in zip(axes[:2], antennas):
        for term in ("transmitter", "receiver", "continuous"):
            ax.plot(t, table[f"{name}_{term}"], label=term)
        ax.set_ylabel(f"{name} [deg]")
        ax.legend(loc="best")
    axes[2].plot(t, table["rotation_delay"])
    axes[2].set_ylabel("rotation delay [ps]")
    axes[2].set_xlabel(f"hours since {table['time'][0].isot} UTC")
    fig.suptitle(table.meta["satellite"])
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(directory="."):
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    cases = [
        (gps_short_baseline(), ("DBR205", "FD-VLBA"), "section4_1_gps"),
        (genesis_long_baseline(), ("GGAO12M", "WETTZ13S"), "section4_2_genesis"),
    ]
    for table, antennas, stem in cases:
        summarize(table, antennas)
        table.write(directory / f"{stem}.ecsv", overwrite=True)
        try:
            plot(table, antennas, directory / f"{stem}.png")
        except ImportError:
            print("  (install matplotlib for the figure)")


if __name__ == "__main__":
    main(*sys.argv[1:])
