# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``feedrot faraday``: the ionosphere's rotation measure, its Faraday rotation and the
feed rotation of stations over a span of time, for planning polarimetry.

The ionosphere comes from IONEX maps (``--ionex``, through spinifex, the extra
``ionosphere``) or from a table of rotation measures (``--rm-table``); the
table is `~astropy_feedrot.applied.faraday_tables.faraday_table`.
"""

from astropy import units as u
from astropy.table import QTable
from astropy.time import Time

from ..applied.faraday_tables import faraday_table
from ..core.outputs import CommandError
from ..core.progress import progress_steps
from ..ionosphere import Ionosphere, IonosphereError
from ..ionosphere.ionosphere import DEFAULT_HEIGHT
from .common import (
    elevation_limit,
    natural_target,
    parse_antenna,
    parse_quantity,
    read_path,
    show_progress,
    station_catalogue,
    table_outputs,
    time_span,
    write_table,
    wrote,
)
from .shared import one_line

__all__ = ["run_faraday", "ionosphere_option"]

_IONOSPHERE_HINT = ("give the ionosphere with --ionex FILE [FILE ...] (IONEX maps, one file per "
                    "UTC day) or --rm-table FILE (a table of rotation measures)")


def _read_rm_table(path):
    """A table of rotation measures, as `~astropy_feedrot.ionosphere.Ionosphere.from_rm`
    takes it, read from ``path`` in the format astropy identifies (ECSV keeps units)."""
    path = read_path(path, "--rm-table")
    try:
        table = QTable.read(path)
    except Exception as error:  # astropy's readers raise many kinds: any is a bad file
        raise CommandError(
            f"--rm-table: cannot read {path!r} as a table ({one_line(error)}); write it as "
            "ECSV with columns time, rm (rad / m2) and optionally antenna") from None
    if "time" in table.colnames and not isinstance(table["time"], Time):
        try:  # ISO strings (a CSV, or an ECSV written without a Time column)
            table["time"] = Time(list(table["time"]), scale="utc")
        except (ValueError, TypeError):
            raise CommandError(f"--rm-table: column 'time' of {path!r} is not ISO times "
                               f"(UTC), e.g. 2024-06-01T08:00") from None
    try:
        return Ionosphere.from_rm(table)
    except (TypeError, ValueError, u.UnitsError) as error:
        raise CommandError(f"--rm-table: {path!r}: {one_line(error)}") from None


def ionosphere_option(args):
    """The `Ionosphere` of ``--ionex`` or ``--rm-table``, and the option that gave it
    (also for ``feedrot correct``)."""
    if (args.ionex is None) == (args.rm_table is None):
        raise CommandError(_IONOSPHERE_HINT + ("" if args.ionex is None else ", not both"))
    if args.ionex_height is not None and args.ionex is None:
        raise CommandError("--ionex-height is the height of the IONEX maps' shell: give it "
                           "with --ionex (a table of rotation measures has no height)")
    if args.rm_table is not None:
        return _read_rm_table(args.rm_table), "--rm-table"
    paths = [read_path(path, "--ionex") for path in args.ionex]
    height = DEFAULT_HEIGHT if args.ionex_height is None else \
        parse_quantity(args.ionex_height, u.km, "--ionex-height")
    try:
        return Ionosphere.from_ionex(paths, height=height), "--ionex"
    except IonosphereError as error:
        raise CommandError(f"--ionex: {one_line(error)}") from None
    except ValueError as error:  # the height out of range
        raise CommandError(f"--ionex-height: {one_line(error)}") from None


def run_faraday(args):
    """Run ``feedrot faraday`` (its grammar: `astropy_feedrot.cli.parser`)."""
    paths = table_outputs(args)
    frequencies = u.Quantity([parse_quantity(text, u.MHz, "--frequency")
                              for text in args.frequency])
    catalogue = station_catalogue(args)
    antennas = [parse_antenna(name, args, catalogue) for name in args.stations]
    min_elevation = elevation_limit(args)
    if min_elevation is not None and min_elevation < 0 * u.deg:
        raise CommandError(f"--min-elevation must be from 0 to 90 deg here, got "
                           f"{args.min_elevation!r}: the rotation measure is undefined below "
                           "the horizon")
    target = natural_target(args)
    times = time_span(args)
    ionosphere, option = ionosphere_option(args)
    # One bar over the rows written: drawn at once (the table is computed at 0 %).
    with progress_steps(show_progress(args), times.size * len(antennas)) as step:
        try:
            table = faraday_table(antennas, target, times, ionosphere, frequencies,
                                  min_elevation=min_elevation)
        except IonosphereError as error:  # epochs outside the maps, a station not listed
            raise CommandError(f"{option}: {one_line(error)}") from None
        write_table(table, paths, "faraday", overwrite=args.overwrite, form=args.format,
                    step=step)
    count = len(table)
    wrote([args.output, args.plot], f"{count} row{'' if count == 1 else 's'} of the rotation "
          f"measure, Faraday and feed rotation of {', '.join(table.meta['antennas'])} "
          f"observing {table.meta['target']} at {', '.join(table.meta['labels'])}")
    return 0
