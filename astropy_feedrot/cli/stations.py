# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot stations``: the station catalogue, all of it or one network or mount."""

import argparse
import sys

import numpy as np

from ..outputs import CommandError
from .common import examples, one_line, station_catalogue

__all__ = ["register"]


def _run_stations(args):
    catalogue = station_catalogue(args)
    table = catalogue.table
    keep = np.ones(len(table), dtype=bool)
    if args.network is not None:
        try:
            names = set(catalogue.network_names(args.network))
        except ValueError as error:
            raise CommandError(f"--network: {one_line(error)}") from None
        keep &= np.isin(np.asarray(table["name"], dtype=str), list(names))
    if args.mount is not None:
        codes = [str(code).strip().upper() for code in table["mount"]]
        wanted = args.mount.strip().upper()
        if wanted not in codes:
            known = ", ".join(sorted(set(codes)))
            raise CommandError(f"--mount: no station has the mount code {args.mount!r}; the "
                               f"catalogue's codes are {known}")
        keep &= np.array([code == wanted for code in codes], dtype=bool)
    columns = [c for c in ("name", "aliases", "networks", "x", "y", "z", "mount", "focus",
                           "source", "position_source", "mount_source", "focus_source")
               if c in table.colnames]
    table[columns][keep].write(sys.stdout, format="ascii.ecsv")
    return 0


def register(commands):
    """Add ``stations`` to the subparsers ``commands``."""
    stations = commands.add_parser(
        "stations", help="list the station catalogue",
        description="Print the station catalogue (names, ITRF positions, mounts, focus types, "
        "sources) as ECSV, all of it or the stations of one network or mount.",
        epilog=examples(["feedrot stations --network VLBA", "feedrot stations --mount NASR",
                         "feedrot stations --catalogue mine.ecsv"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    stations.add_argument("--catalogue", metavar="FILE", help="an ECSV catalogue of one's own")
    stations.add_argument("--network", metavar="NAME",
                          help="only the stations of a network (VLBA, EVN, EHT...; "
                               "case-insensitive)")
    stations.add_argument("--mount", metavar="CODE",
                          help="only the stations with this geodetic mount code (AZEL, EQUA, "
                               "X-YE, X-YN, NASR, NASL, BWG, GNSS)")
    stations.set_defaults(run=_run_stations)
