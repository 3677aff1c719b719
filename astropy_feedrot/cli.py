# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ``feedrot`` command line."""

import argparse
import sys

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.table import Table
from astropy.time import Time

from .antenna import Antenna
from .kernel import unwrap_phase
from .mounts import AltAzMount, StationaryMount

__all__ = ["main"]

# Positions of the paper's Tables 1 and 3 (ITRF, metres).
_PAPER_ANTENNAS = {
    "DBR205": ((-1324070.478, -5332176.001, 3231921.799), StationaryMount()),
    "FD-VLBA": ((-1324009.454, -5332181.955, 3231962.369), AltAzMount()),
    "GGAO12M": ((1130730.179, -4831245.954, 3994228.241), AltAzMount()),
    "WETTZ13S": ((4075659.180, 931824.551, 4801516.102), AltAzMount()),
}


def demo_table():
    """Feed rotation of 3C 84 over one day for the paper's antennas.

    Returns
    -------
    `~astropy.table.Table`
        One row per 30 min on 2023-01-25 (the date of the paper's
        simulations); for each antenna its elevation and continuous feed
        rotation.

    Examples
    --------
    >>> from astropy_feedrot.cli import demo_table
    >>> demo_table()["time"].shape
    (48,)
    """
    times = Time("2023-01-25T00:00:00", scale="utc") + np.arange(48) * 30 * u.min
    source = SkyCoord("03h19m48.16s +41d30m42.1s", frame="icrs")
    table = Table({"time": times})
    table.meta["source"] = "3C 84 (ICRS 03h19m48.16s +41d30m42.1s)"
    for name, (xyz, mount) in _PAPER_ANTENNAS.items():
        antenna = Antenna(EarthLocation.from_geocentric(*xyz, unit=u.m), mount, name=name)
        _, elevation = antenna.altaz(source, times)
        phi = antenna.feed_rotation(source, times)
        table[f"{name}_elevation"] = elevation.deg * u.deg
        table[f"{name}_feed_rotation"] = np.degrees(unwrap_phase(phi.rad)) * u.deg
    return table


def _demo(args):
    table = demo_table()
    for column in table.colnames[1:]:
        table[column].info.format = ".4f"
    table.write(sys.stdout, format="ascii.ecsv")
    return 0


def _parser():
    parser = argparse.ArgumentParser(
        prog="feedrot",
        description="Feed rotation (parallactic angle, carrier-phase wind-up) of radio "
        "telescopes and GNSS antennas.",
        epilog="Example: feedrot demo > demo.ecsv",
    )
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    demo = commands.add_parser(
        "demo",
        help="feed rotation of 3C 84 for the paper's antennas, on embedded data",
        description="Print, as an ECSV table, the elevation and continuous feed rotation "
        "of 3C 84 over 2023-01-25 for the antennas of Tables 1 and 3 of the paper.",
    )
    demo.set_defaults(run=_demo)
    return parser


def main(argv=None):
    """Run the ``feedrot`` command line.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status.

    Examples
    --------
    >>> from astropy_feedrot.cli import main
    >>> main(["demo"])  # doctest: +ELLIPSIS
    # %ECSV 1.0
    ...
    0
    """
    from astropy.utils import iers

    args = _parser().parse_args(argv)
    if not hasattr(args, "run"):
        _parser().print_help()
        return 2
    with iers.conf.set_temp("auto_download", False):
        return args.run(args)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
