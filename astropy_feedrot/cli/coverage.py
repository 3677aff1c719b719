# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot coverage``: the range of feed rotation that candidate polarization
calibrators offer the stations of a network."""

import numpy as np
from astropy import units as u
from astropy.coordinates import SkyCoord

from ..applied import planning
from ..core.outputs import (
    TABLE_FORMATS,
    CommandError,
    check_outputs,
    table_format,
    table_writer,
    write_files,
)
from ..stations import catalogue
from .common import (
    catalogue_antenna,
    elevation_limit,
    figure_types,
    input_files,
    one_source,
    parse_quantity,
    show_progress,
    time_span,
)
from .shared import one_line

__all__ = ["run_coverage"]


def run_coverage(args):
    types = figure_types() if args.plot is not None else ()
    paths = check_outputs([("-o/--output", args.output, tuple(TABLE_FORMATS)),
                           ("--plot", args.plot, types)],
                          input_files(args), args.overwrite)
    if paths[0] is not None:
        table_format(paths[0])
    antennas = {}
    for text in args.stations:
        name = text.strip()
        found = None
        if hasattr(catalogue, "get_network"):  # a network name expands to its stations
            try:
                found = list(catalogue.get_network(name))
            except (KeyError, ValueError):
                found = None
        if found is None:  # NAME@NETWORK chooses among stations sharing a name (KP@EHT)
            found = [catalogue_antenna(catalogue.default_catalogue(), name)]
        for antenna in found:
            antennas.setdefault(antenna.name, antenna)
    sources = {}
    for text in args.source:
        name, equals, where = text.partition("=")
        name, where = name.strip(), where.strip()
        if not equals:  # bare coordinates, as every other command takes: their own name
            name = where = text.strip()
        if not name or not where:
            raise CommandError(f"--source {text!r}: write COORDINATES or NAME=COORDINATES, "
                               "e.g. '3C84=03h19m48.16s +41d30m42.1s'; names are not looked up")
        if name in sources:
            raise CommandError(f"--source: the name {name!r} is given twice")
        for kwargs in ({}, {"unit": (u.hourangle, u.deg)}):
            try:
                with np.errstate(all="ignore"):
                    coord = SkyCoord(where, frame="icrs", **kwargs)
            except (ValueError, TypeError, u.UnitsError) as error:
                reason = one_line(error)
                continue
            sources[name] = one_source(coord, f"--source {name}", where)
            break
        else:
            raise CommandError(f"--source {name}: cannot read {where!r} as coordinates "
                               f"({reason}); write e.g. '03h19m48.16s +41d30m42.1s' or "
                               "'3C84=03h19m48.16s +41d30m42.1s' (names are not looked up)")
    times = time_span(args)
    if times.size < 2:
        raise CommandError("--stop must be after --start by at least one --step")
    min_elevation = elevation_limit(args)
    min_elevation = 10 * u.deg if min_elevation is None else min_elevation
    step = parse_quantity(args.step, u.s, "--step")
    # A bar whenever standard error is a terminal: the tables printed after it are short.
    table, epochs, continuous = planning.feed_rotation_coverage(
        list(antennas.values()), sources, times[0], times[-1], step, min_elevation,
        tracks=True, progress=show_progress(None))
    ranking = planning.rank_sources(table)
    for column in ("range", "min", "max", "hours"):
        table[column].info.format = ".2f"
    for column in ("worst_range", "best_range"):
        ranking[column].info.format = ".2f"
    files = []
    if paths[0] is not None:
        files.append((paths[0], table_writer(table, table_format(paths[0]))))
    if paths[1] is not None:
        def draw(name):
            import matplotlib.pyplot as plt  # optional: checked by figure_types

            try:
                plt.close(planning.plot_coverage(table, epochs, continuous, name))
            except (RuntimeError, ValueError, OSError) as error:
                raise CommandError(f"--plot: cannot draw {str(paths[1])!r}: "
                                   f"{one_line(error)}") from None
        files.append((paths[1], draw))
    write_files(files, overwrite=args.overwrite)
    print(f"Feed rotation above {min_elevation} from {epochs[0].isot} to {epochs[-1].isot} "
          f"every {args.step}:")
    print("\n".join(table.pformat(max_lines=-1, max_width=-1)))
    print("\nSources ranked by the range of their worst station:")
    print("\n".join(ranking.pformat(max_lines=-1, max_width=-1)))
    for option, path in zip(("table", "figure"), paths):
        if path is not None:
            print(f"{option}: {path}")
    return 0
