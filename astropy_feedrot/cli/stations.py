# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot stations``: the station catalogue, searched, one station a line or one in full.

On a terminal the stations are listed one a line (name, networks, mount,
focus, aliases), aligned; ``feedrot stations NAME`` shows one station in full,
with the source of each of its values. A pattern (``'EF*'``, ``yebes``),
``--network``, ``--mount`` and ``--near LON,LAT`` choose stations; ``-o FILE``
writes every column of the chosen stations in the format of the file's
extension, and on a pipe (standard output not a terminal) the listing is
ECSV unless ``--format`` says otherwise.
"""

import fnmatch
import sys

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.table import Table

from ..core.outputs import TABLE_FORMATS, CommandError, check_outputs
from .common import input_files, station_catalogue, write_table, wrote
from .shared import NEAR_LIMIT, one_line
from .views import output_format

__all__ = ["run_stations"]

#: The columns of the listing, one station a line.
LISTING = ("name", "networks", "mount", "focus", "aliases")


def _names(table):
    """Each station's name and aliases, upper case."""
    aliases = [str(alias) if alias is not np.ma.masked else "" for alias in table["aliases"]] \
        if "aliases" in table.colnames else [""] * len(table)
    return [[str(name).upper()] + [a.strip().upper() for a in alias.split(",") if a.strip()]
            for name, alias in zip(table["name"], aliases)]


def _matching(table, pattern):
    """The stations whose name or an alias matches ``pattern`` (a glob, or a part of a
    name if it has no wildcard), case-insensitive."""
    wanted = pattern.strip().upper()
    glob = any(c in wanted for c in "*?[")
    return np.array([any(fnmatch.fnmatchcase(name, wanted) if glob else wanted in name
                         for name in names) for names in _names(table)], dtype=bool)


def _exact(table, pattern):
    """Rows whose name or an alias is ``pattern`` exactly (case-insensitive)."""
    wanted = pattern.strip().upper()
    return [k for k, names in enumerate(_names(table)) if wanted in names]


def _near(text):
    try:
        lon, lat = (float(value) for value in text.split(","))
    except ValueError:
        raise CommandError(f"--near: expected LON,LAT in degrees (e.g. -3.09,40.52), got "
                           f"{text!r}") from None
    if not (-90 <= lat <= 90 and -360 <= lon <= 360):
        raise CommandError(f"--near: latitude must lie in [-90, 90] deg and longitude in "
                           f"[-360, 360] deg, got {text!r}")
    return lon, lat


def _distances_km(table, lon, lat):
    """Great-circle distances (km, on a sphere of the Earth's mean radius) from a place."""
    sites = EarthLocation.from_geocentric(table["x"], table["y"], table["z"], unit=u.m)
    lon2, lat2 = sites.lon.rad, sites.lat.rad
    lon1, lat1 = np.radians(lon), np.radians(lat)
    half = (np.sin((lat2 - lat1) / 2) ** 2
            + np.cos(lat1) * np.cos(lat2) * np.sin((lon2 - lon1) / 2) ** 2)
    return 2 * 6371.0 * np.arcsin(np.sqrt(np.clip(half, 0, 1)))


def _one_station(table, row):
    """Every value of one station, with its source, one a line."""
    record = table[row]
    width = max(len(name) for name in table.colnames)
    lines = []
    for name in table.colnames:
        value = record[name]
        if value is np.ma.masked or (isinstance(value, float) and np.isnan(value)):
            continue
        unit = table[name].unit
        text = f"{value:.4f}" if isinstance(value, (float, np.floating)) else str(value)
        lines.append(f"{name:>{width}}: {text}{f' {unit}' if unit else ''}")
    return "\n".join(lines)


def _selected(args, catalogue):
    table = catalogue.table
    keep = np.ones(len(table), dtype=bool)
    if args.pattern is not None:
        keep &= _matching(table, args.pattern)
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
    selected = Table(table[keep], masked=True)
    if args.near is not None:
        lon, lat = _near(args.near)
        selected["distance"] = np.round(_distances_km(selected, lon, lat), 1) * u.km
        selected.sort("distance")
        selected = selected[:args.limit if args.limit is not None else NEAR_LIMIT]
    elif args.limit is not None:
        selected = selected[:args.limit]
    return selected


def run_stations(args):
    if args.limit is not None and args.limit < 1:
        raise CommandError(f"--limit: expected a positive number of stations, got {args.limit}")
    output = check_outputs([("-o/--output", args.output, tuple(TABLE_FORMATS))],
                           input_files(args), args.overwrite)[0]
    catalogue = station_catalogue(args)
    only = [args.network, args.mount, args.near, args.limit, args.output, args.format]
    if args.pattern is not None and all(option is None for option in only):
        exact = _exact(catalogue.table, args.pattern)
        if len(exact) == 1:
            print(_one_station(catalogue.table, exact[0]))
            return 0
    selected = _selected(args, catalogue)
    if not len(selected):
        raise CommandError("no station matches" + (f" {args.pattern!r}" if args.pattern else "")
                           + "; 'feedrot stations' lists them all")
    if output is not None:
        write_table(selected, (output, None), "stations", overwrite=args.overwrite)
        count = len(selected)
        wrote([args.output], f"{count} station{'s' if count != 1 else ''} of the catalogue")
        return 0
    form = output_format(args.format)
    if form == "text":
        columns = [c for c in (*LISTING, "distance") if c in selected.colnames]
        listing = selected[columns]
        for name in LISTING:
            if name in listing.colnames:
                listing[name].format = "<"  # text left-aligned
        lines = listing.pformat(max_lines=-1, max_width=-1)
        print("\n".join(lines))
        count = len(selected)
        print(f"{count} station{'s' if count != 1 else ''}")
    else:
        selected.write(sys.stdout, format=f"ascii.{form}")
    return 0
