# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""What the commands of ``feedrot`` share when they run: reading values, sites,
stations, sources and times from the command line, and the checked output files
of a table and its figure (the options themselves are in `astropy_feedrot.cli.parser`)."""

import math
import os
import re
import sys
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord, frame_transform_graph
from astropy.time import Time

from ..applied import plotting
from ..core.extras import install_hint
from ..core.outputs import (
    TABLE_FORMATS,
    CommandError,
    check_outputs,
    table_format,
    table_writer,
    write_files,
)
from ..data import sample_file
from ..engine.antenna import Antenna
from ..io import FileFormatError
from ..stations.catalogue import default_catalogue, focus_from_name, read_catalogue
from ..stations.labels import mount_from_label
from .shared import CELESTIAL_FRAMES, MAX_EPOCHS, PHASE_UNIT_NAMES, SITE_FORMAT, one_line
from .views import output_format, print_table

__all__ = [
    "parse_quantity", "elevation_limit", "parse_time", "time_span", "parse_site",
    "parse_antenna", "catalogue_antenna", "natural_target", "one_source", "read_path",
    "read_input", "station_catalogue", "input_files", "figure_types", "drawer",
    "table_outputs", "write_table", "show_progress", "wrote", "PHASE_UNITS", "in_units",
]

# Values ------------------------------------------------------------------------------------


def parse_quantity(text, unit, what):
    """A positive, finite quantity from text like '30s', '10 min' or '1575.42MHz'."""
    try:
        value = u.Quantity(text)
    except (TypeError, ValueError):
        example = {"time": "30s, 10min", "length": "450km"}.get(str(unit.physical_type),
                                                                "1575.42MHz, 8.4GHz")
        raise CommandError(f"{what}: cannot read {text!r} as a number with a unit "
                           f"(e.g. {example})") from None
    if value.unit == u.dimensionless_unscaled:
        value = value.value * unit
    try:
        value = value.to(unit)
    except u.UnitConversionError:
        raise CommandError(f"{what}: {text!r} is not in a unit of {unit.physical_type}") from None
    if not value.isscalar:
        raise CommandError(f"{what}: give one value, got {text!r}")
    if not np.isfinite(value) or value <= 0:
        raise CommandError(f"{what} must be positive and finite, got {text!r}")
    return value


def elevation_limit(args):
    if args.min_elevation is None:
        return None
    try:
        value = u.Quantity(args.min_elevation)
    except (TypeError, ValueError):
        raise CommandError(f"--min-elevation: cannot read {args.min_elevation!r} as an angle "
                           "(e.g. 10, 10deg)") from None
    value = value.value * u.deg if value.unit == u.dimensionless_unscaled else value
    try:
        value = value.to(u.deg)
    except u.UnitConversionError:
        raise CommandError(f"--min-elevation: {args.min_elevation!r} is not an angle") from None
    if not value.isscalar or not -90 <= value.value <= 90:
        raise CommandError(f"--min-elevation must be one angle within [-90, 90] deg, got "
                           f"{args.min_elevation!r}")
    return value


def parse_time(text, what, now):
    if text.strip().lower() == "now":
        return now
    try:
        time = Time(text.strip(), scale="utc")
    except (ValueError, TypeError):
        raise CommandError(f"{what}: cannot read {text!r} as a time; use ISO format, e.g. "
                           "2023-01-25T18:00 (UTC), or 'now'") from None
    if not time.isscalar:
        raise CommandError(f"{what}: give one time, got {text!r}")
    time.format = "isot"
    return time


def time_span(args, default=None):
    """The epochs from --start to --stop at --step, at most `MAX_EPOCHS`."""
    now = Time.now()  # one 'now' for both ends: --start now --stop now is one epoch
    now.format = "isot"
    start = parse_time(args.start, "--start", now) if args.start else None
    stop = parse_time(args.stop, "--stop", now) if args.stop else None
    if default is not None:
        start = default[0] if start is None else start
        stop = default[1] if stop is None else stop
    if start is None or stop is None:
        raise CommandError("give the span of time with --start and --stop")
    step = parse_quantity(args.step, u.s, "--step")
    if stop < start:
        raise CommandError(f"--stop ({stop.utc.isot}) is before --start ({start.utc.isot})")
    steps = (stop - start).to_value(u.s) / step.to_value(u.s)
    if not steps < MAX_EPOCHS:
        raise CommandError(f"--step {args.step} gives {steps + 1:.3g} epochs from --start to "
                           f"--stop, more than the {MAX_EPOCHS} of one run; use a larger "
                           "--step or a shorter span")
    count = math.floor(steps * (1 + 1e-12)) + 1
    times = start + np.arange(count) * step
    times.format = "isot"
    return times


def parse_site(text):
    """(lat, lon, height) of a site 'LAT,LON,HEIGHT', or None for a station name."""
    if "," not in text:
        return None
    parts = text.split(",")
    try:
        values = [float(part) for part in parts]
    except ValueError:
        values = []
    if len(values) != 3:
        raise CommandError(f"site {text.strip()!r}: expected {SITE_FORMAT}")
    lat, lon, height = values
    if not all(math.isfinite(value) for value in values):
        raise CommandError(f"site {text.strip()!r}: LAT, LON and HEIGHT must be finite "
                           "numbers")
    if not -90 <= lat <= 90:
        raise CommandError(f"latitude {lat:g} of site {text.strip()!r} is not in [-90, 90] deg; "
                           "the order is LAT,LON,HEIGHT")
    if not -180 <= lon <= 360:
        raise CommandError(f"longitude {lon:g} of site {text.strip()!r} is not in [-180, 360] "
                           "deg; the order is LAT,LON,HEIGHT")
    return lat, lon, height


def catalogue_antenna(catalogue, text):
    """The station ``NAME`` or ``NAME@NETWORK`` of a catalogue, its errors in the CLI's words.

    ``NAME@NETWORK`` chooses among stations that share a name (``KP@EHT``).
    """
    name, _, network = text.strip().partition("@")
    try:
        return catalogue.get_antenna(name.strip(), network=network.strip() or None)
    except ValueError as error:
        # The library suggests get_antenna('KP', network='EHT'); here that is KP@EHT.
        message = re.sub(r"get_antenna\('([^']*)', network='([^']*)'\)", r"\1@\2",
                         str(error))
        raise CommandError(message) from None


def parse_antenna(text, args, catalogue):
    site = parse_site(text)
    if site is None:
        if args.mount is not None or args.focus is not None:
            raise CommandError(f"--mount and --focus go with a site LAT,LON,HEIGHT, not with the "
                               f"catalogue station {text!r}")
        return catalogue_antenna(catalogue, text)
    lat, lon, height = site
    location = EarthLocation.from_geodetic(lon * u.deg, lat * u.deg, height * u.m)
    try:
        mount, focus = mount_from_label("AZEL" if args.mount is None else args.mount,
                                        "geodetic")
    except ValueError as error:
        raise CommandError(f"--mount: {error}") from None
    if args.focus:
        focus = focus_from_name(args.focus, "--focus")
    # One name per place, however the numbers are written (40 and 40.0).
    name = "site " + ",".join(format(value, ".15g") for value in site)
    try:
        return Antenna(location, mount, focus, name=name)
    except ValueError as error:
        raise CommandError(f"site {text.strip()!r}: {one_line(error)}") from None


def natural_target(args):
    frame = "icrs" if args.frame is None else args.frame.strip().lower()
    if frame not in CELESTIAL_FRAMES:
        known = frame_transform_graph.lookup_name(frame) is not None
        raise CommandError(
            f"--frame {args.frame!r}: "
            + ("a frame tied to an observing time or place; " if known else
               "unknown frame; ")
            + "give the coordinates in a celestial frame: " + ", ".join(CELESTIAL_FRAMES))
    if args.source is not None:
        if args.ra is not None or args.dec is not None:
            raise CommandError("give the source either with --source or with --ra and --dec")
        for kwargs in ({}, {"unit": (u.hourangle, u.deg)}):
            try:
                with np.errstate(all="ignore"):  # absurd numbers: refused below, not warned
                    coord = SkyCoord(args.source, frame=frame, **kwargs)
            except (ValueError, TypeError, u.UnitsError) as error:
                reason = one_line(error)
                continue
            return one_source(coord, "--source", args.source)
        raise CommandError(f"--source: cannot read {args.source!r} as coordinates ({reason}); "
                           "write e.g. '03h19m48.16s +41d30m42.1s' or '49.95d 41.51d'; looking "
                           "up names needs the internet, give the coordinates instead")
    if args.ra is None or args.dec is None:
        raise CommandError("give the source with --source, or with both --ra and --dec")
    plain = re.fullmatch(r"\s*[-+]?\d+(\.\d*)?\s*", args.ra) is not None
    ra_unit = u.deg if plain else u.hourangle
    try:
        with np.errstate(all="ignore"):  # absurd numbers: refused below, not warned
            coord = SkyCoord(args.ra, args.dec, unit=(ra_unit, u.deg), frame=frame)
    except (ValueError, TypeError, u.UnitsError) as error:
        raise CommandError(f"--ra/--dec: cannot read {args.ra!r} {args.dec!r} as coordinates "
                           f"({one_line(error)}); e.g. --ra 03:19:48.16 --dec +41:30:42.1 "
                           "(hours, degrees) or --ra 49.95 --dec 41.51 (degrees)") from None
    return one_source(coord, "--ra/--dec", f"{args.ra} {args.dec}")


def one_source(coord, what, text):
    if not coord.isscalar:
        raise CommandError(f"{what}: give one source, got {text!r}")
    spherical = coord.spherical
    if not (np.isfinite(spherical.lon) and np.isfinite(spherical.lat)):
        raise CommandError(f"{what}: the coordinates {text!r} are not finite")
    return coord


def read_path(path, what):
    """``path`` if it names a readable file."""
    given = Path(path).expanduser()
    if given.is_dir():
        raise CommandError(f"{what}: {path!r} is a directory, not a file")
    if not given.is_file():
        raise CommandError(f"{what}: no such file {path!r}")
    if not os.access(given, os.R_OK):
        raise CommandError(f"{what}: cannot read {path!r}: permission denied")
    return str(given)


def read_input(reader, path, what, *args, **kwargs):
    """``reader(path, ...)``, naming the option in the errors of a file that does not read."""
    try:
        return reader(read_path(path, what), *args, **kwargs)
    except UnicodeDecodeError:
        raise CommandError(f"{what}: {path!r} is not a text file") from None
    except (FileFormatError, ValueError) as error:
        message = one_line(error)
        raise CommandError(message if str(path) in message else f"{what}: {message}") from None


def station_catalogue(args):
    if getattr(args, "catalogue", None):
        return read_input(read_catalogue, args.catalogue, "--catalogue")
    return default_catalogue()


# Output files -----------------------------------------------------------------------------


def input_files(args):
    """(option, path) of every file the command reads."""
    inputs = [(f"--{name.replace('_', '-')}", getattr(args, name))
              for name in ("tle", "sp3", "orbex", "catalogue", "rm_table")
              if getattr(args, name, None) is not None]
    inputs += [("--ionex", path) for path in getattr(args, "ionex", None) or ()]
    if getattr(args, "catalogue", None) is None:
        inputs.append(("embedded station catalogue", str(sample_file("stations.ecsv"))))
    return inputs


def figure_types():
    try:
        from matplotlib.figure import Figure
    except ImportError:
        raise CommandError(f"--plot needs matplotlib: {install_hint('all', 'matplotlib')}"
                           ) from None
    return ["." + name for name in Figure().canvas.get_supported_filetypes()]


def drawer(table, kind, path):
    def write(name):
        import matplotlib.pyplot as plt  # optional: checked by figure_types

        try:
            plt.close(getattr(plotting, f"plot_{kind}")(table, name))
        except (RuntimeError, ValueError, OSError) as error:
            # e.g. a .pgf figure without LaTeX
            raise CommandError(f"--plot: cannot draw {str(path)!r}: {one_line(error)}") from None
    return write


def table_outputs(args):
    """The checked table and figure paths of a table command (None: not written)."""
    types = figure_types() if args.plot is not None else ()
    paths = check_outputs([("-o/--output", args.output, tuple(TABLE_FORMATS)),
                           ("--plot", args.plot, types)],
                          input_files(args), args.overwrite)
    if paths[0] is not None:
        table_format(paths[0])
    return paths


def write_table(table, paths, kind, overwrite=False, form=None, step=None):
    """Write ``table`` to ``paths`` (table, figure), or print it: as ``form``
    (`~astropy_feedrot.cli.views.output_format`) when no table file is given;
    ``step(rows)`` is called as rows are written or printed."""
    output, figure = paths
    files = []
    if output is not None:
        files.append((output, table_writer(table, table_format(output), step)))
    if figure is not None:
        files.append((figure, drawer(table, kind, figure)))
    then = None if output is not None else (
        lambda: print_table(table, output_format(form), step=step))
    write_files(files, then, overwrite=overwrite)


def show_progress(args, stream=None):
    """Whether a command draws a progress bar: when standard error is a terminal, and
    unless the table is printed as text on the terminal (its lines show the progress).

    ``args.output`` and ``args.format`` are those of the table commands; for
    ``args`` without them (or None) the bar is drawn whenever standard error
    is a terminal.
    """
    stream = sys.stderr if stream is None else stream
    isatty = getattr(stream, "isatty", None)
    if isatty is None or not isatty():
        return False
    printed = hasattr(args, "output") and args.output is None
    return not (printed and output_format(getattr(args, "format", None)) == "text")


def wrote(paths, what):
    """The summary line of a table command on success, on standard error: each file
    written (named as given), and what the table holds."""
    named = [str(path) for path in paths if path is not None]
    if named:
        print(f"feedrot: {' and '.join(named)}: {what}", file=sys.stderr)


#: Units of ``--units``: a phase in cycles, radians or degrees.
PHASE_UNITS = dict(zip(PHASE_UNIT_NAMES, (u.cycle, u.rad, u.deg)))


def in_units(table, units, columns):
    """Convert the angle (and angle-rate) columns of a table to the unit of ``--units``."""
    unit = PHASE_UNITS[units]
    for name in columns:
        if name in table.colnames:
            quantity = u.Quantity(table[name])
            target = unit / u.s if quantity.unit.is_equivalent(u.deg / u.s) else unit
            table[name] = quantity.to(target)
    return table
