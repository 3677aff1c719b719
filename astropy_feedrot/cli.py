# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ``feedrot`` command line.

``feedrot natural``, ``feedrot satellite`` and ``feedrot baseline`` tabulate
feed rotation over a span of time (ECSV on standard output, or a file whose
format follows its extension, and optionally a figure); ``feedrot demo`` runs
the paper's Section 4.1 simulation on embedded data; ``feedrot stations``
lists the station catalogue (``--network``, ``--mount``); ``feedrot
coverage`` tabulates the range of feed rotation that candidate polarization
calibrators offer a network. ``feedrot antennas`` lists the antennas of a
visibility file as read, and ``feedrot correct`` writes a copy of a
visibility file with the feed rotation removed (see
`astropy_feedrot.visibility_files`).

Every error is one line on standard error and a non-zero exit status. No file
is lost: every output is checked before any work is done (format, directory,
an existing file needs ``--overwrite``, never one of the inputs, never the
table and the figure in one file), written to a temporary file beside its
target and renamed into place once everything has been written.
"""

import argparse
import contextlib
import math
import os
import re
import sys
import warnings
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord, frame_transform_graph
from astropy.time import Time

from . import plotting
from .antenna import Antenna
from .attitude import NominalAttitude, QuaternionAttitude
from .data import sample_file
from .eop import iers_context
from .io import FileFormatError, read_tle
from .labels import mount_from_label
from .orbits import SP3Orbit, TLEOrbit
from .outputs import (
    TABLE_FORMATS,
    CommandError,
    check_outputs,
    table_format,
    table_writer,
    write_files,
)
from .satellite import Satellite
from .simulations import gps_short_baseline
from .stations import FOCUS_NAMES, default_catalogue, focus_from_name, read_catalogue
from .tables import baseline_summary, baseline_table, feed_rotation_table

__all__ = ["main", "CommandError", "MAX_EPOCHS", "TABLE_FORMATS", "CELESTIAL_FRAMES"]

#: Most epochs one command may compute (about 1.6 GB and half a minute for
#: a natural source; a satellite with the nominal attitude is ten times slower).
MAX_EPOCHS = 1_000_000


#: Frames accepted by ``--frame``: celestial frames, whose coordinates need
#: no observing time or place (unlike altaz or hadec).
CELESTIAL_FRAMES = ("icrs", "fk5", "fk4", "fk4noeterms", "galactic", "supergalactic",
                    "barycentricmeanecliptic", "barycentrictrueecliptic")

_EXAMPLES = {
    "natural": """examples:
  feedrot natural YEBES40M --source "03h19m48.16s +41d30m42.1s" \\
      --start 2023-01-25T18:00 --stop 2023-01-26T06:00 --step 10min
  feedrot natural EFLSBERG --ra 12:29:06.7 --dec +02:03:09 --start 2024-03-01 \\
      --stop 2024-03-02 -o 3c273.ecsv --plot 3c273.png
  feedrot natural 40.5247,-3.0869,988 --mount NASR --source "187.27d 2.05d" \\
      --start 2024-03-01T20:00 --stop 2024-03-01T22:00 --step 1min""",
    "satellite": """examples:
  feedrot satellite DBR205 --tle gps.tle --sat 41328 \\
      --start 2023-01-25T06:00 --stop 2023-01-25T17:00 --step 30s --min-elevation 10
  feedrot satellite FD-VLBA --sp3 igs.sp3 --sat G05 --orbex igs.obx -o g05.fits""",
    "baseline": """examples:
  feedrot baseline DBR205 FD-VLBA --tle gps.tle --start 2023-01-25T06:00 \\
      --stop 2023-01-25T17:00 --frequency 1575.42MHz --min-elevation 10
  feedrot baseline EFLSBERG YEBES40M --source "03h19m48.16s +41d30m42.1s" \\
      --start 2023-01-25T18:00 --stop 2023-01-26T06:00 --frequency 8.4GHz""",
}

_ANTENNA_HELP = (
    "a station name of the catalogue (see 'feedrot stations'; case and punctuation do "
    "not matter) or a site 'LAT,LON,HEIGHT' in degrees, degrees and metres with "
    "--mount and --focus"
)

_SITE_FORMAT = "LAT,LON,HEIGHT in degrees, degrees and metres, e.g. 40.5247,-3.0869,988"


class _UsageError(Exception):
    """A command line that argparse cannot read."""


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line (no usage block).

    Options are never abbreviated: ``demo --output x`` is an unknown option,
    not ``--output-dir x``.
    """

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message):
        if "expected one argument" in message:
            message += " (write --option=VALUE for a value that starts with '-')"
        raise _UsageError(f"{message}; see '{self.prog} --help'")


def _one_line(text):
    """``text`` on one line: its lines joined with '; '."""
    return "; ".join(" ".join(line.split()) for line in str(text).splitlines() if line.strip())


# Values ------------------------------------------------------------------------------------


def _quantity(text, unit, what):
    """A positive, finite quantity from text like '30s', '10 min' or '1575.42MHz'."""
    try:
        value = u.Quantity(text)
    except (TypeError, ValueError):
        raise CommandError(f"{what}: cannot read {text!r} as a number with a unit "
                           f"(e.g. {'30s, 10min' if unit == u.s else '1575.42MHz, 8.4GHz'})"
                           ) from None
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


def _min_elevation(args):
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


def _time(text, what, now):
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


def _times(args, default=None):
    """The epochs from --start to --stop at --step, at most `MAX_EPOCHS`."""
    now = Time.now()  # one 'now' for both ends: --start now --stop now is one epoch
    now.format = "isot"
    start = _time(args.start, "--start", now) if args.start else None
    stop = _time(args.stop, "--stop", now) if args.stop else None
    if default is not None:
        start = default[0] if start is None else start
        stop = default[1] if stop is None else stop
    if start is None or stop is None:
        raise CommandError("give the span of time with --start and --stop")
    step = _quantity(args.step, u.s, "--step")
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


def _site(text):
    """(lat, lon, height) of a site 'LAT,LON,HEIGHT', or None for a station name."""
    if "," not in text:
        return None
    parts = text.split(",")
    try:
        values = [float(part) for part in parts]
    except ValueError:
        values = []
    if len(values) != 3:
        raise CommandError(f"site {text.strip()!r}: expected {_SITE_FORMAT}")
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


def _antenna(text, args, catalogue):
    site = _site(text)
    if site is None:
        if args.mount is not None or args.focus is not None:
            raise CommandError(f"--mount and --focus go with a site LAT,LON,HEIGHT, not with the "
                               f"catalogue station {text!r}")
        return catalogue.get_antenna(text.strip())
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
        raise CommandError(f"site {text.strip()!r}: {_one_line(error)}") from None


def _natural_target(args):
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
                reason = _one_line(error)
                continue
            return _one_source(coord, "--source", args.source)
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
                           f"({_one_line(error)}); e.g. --ra 03:19:48.16 --dec +41:30:42.1 "
                           "(hours, degrees) or --ra 49.95 --dec 41.51 (degrees)") from None
    return _one_source(coord, "--ra/--dec", f"{args.ra} {args.dec}")


def _one_source(coord, what, text):
    if not coord.isscalar:
        raise CommandError(f"{what}: give one source, got {text!r}")
    spherical = coord.spherical
    if not (np.isfinite(spherical.lon) and np.isfinite(spherical.lat)):
        raise CommandError(f"{what}: the coordinates {text!r} are not finite")
    return coord


def _read_path(path, what):
    """``path`` if it names a readable file."""
    given = Path(path).expanduser()
    if given.is_dir():
        raise CommandError(f"{what}: {path!r} is a directory, not a file")
    if not given.is_file():
        raise CommandError(f"{what}: no such file {path!r}")
    if not os.access(given, os.R_OK):
        raise CommandError(f"{what}: cannot read {path!r}: permission denied")
    return str(given)


def _read(reader, path, what, *args, **kwargs):
    """``reader(path, ...)``, naming the option in the errors of a file that does not read."""
    try:
        return reader(_read_path(path, what), *args, **kwargs)
    except UnicodeDecodeError:
        raise CommandError(f"{what}: {path!r} is not a text file") from None
    except (FileFormatError, ValueError) as error:
        message = _one_line(error)
        raise CommandError(message if str(path) in message else f"{what}: {message}") from None


def _catalogue(args):
    if getattr(args, "catalogue", None):
        return _read(read_catalogue, args.catalogue, "--catalogue")
    return default_catalogue()


_SATELLITE_OPTIONS = ("tle", "sp3", "sat", "orbex", "points", "satellite_polarization")
_NATURAL_OPTIONS = ("source", "ra", "dec", "frame")


def _given(args, names):
    return ["--" + name.replace("_", "-") for name in names
            if getattr(args, name, None) is not None]


def _satellite(args):
    hand = args.satellite_polarization or "RCP"
    if args.polarization is not None and args.polarization != hand:
        # The rule of Antenna.feed_rotation: a receiver hears its own hand only.
        raise CommandError(
            f"an {args.polarization} receiver (--polarization {args.polarization}) does not "
            f"receive the {hand} signal of the satellite; leave --polarization unset or give "
            f"--polarization {hand} (--satellite-polarization sets the satellite's hand, "
            "RCP by default as for GNSS)")
    if args.tle is not None:
        for option in ("sp3", "orbex", "points"):
            if getattr(args, option) is not None:
                raise CommandError(f"--{option} goes with --sp3; --tle is the other orbit source")
        records = _read(read_tle, args.tle, "--tle")
        if args.sat is not None:
            chosen = [r for r in records
                      if args.sat.strip().upper() in (r.name.upper(), r.catalog_number)]
            if not chosen:
                raise CommandError(f"--sat {args.sat!r} is not in {args.tle}; it has "
                                   + ", ".join(f"{r.name} ({r.catalog_number})" for r in records))
        elif len(records) > 1:
            raise CommandError(f"{args.tle} has {len(records)} satellites; choose one with --sat "
                               "(name or catalogue number)")
        else:
            chosen = records
        record = chosen[0]
        orbit = TLEOrbit(record.line1, record.line2, name=record.name)
        return Satellite(orbit, polarization=hand, name=record.name), None
    if args.sp3 is None:
        raise CommandError("give the satellite's orbit with --tle FILE or --sp3 FILE --sat NAME")
    if args.sat is None:
        raise CommandError("--sp3 needs --sat, the satellite's SP3 name (e.g. G05)")
    name = args.sat.strip()
    points = 10 if args.points is None else args.points
    if points < 2:
        raise CommandError(f"--points must be at least 2 (epochs of the interpolation window), "
                           f"got {points}")
    orbit = _read(SP3Orbit, args.sp3, "--sp3", name, points=points)
    if args.orbex is not None:
        attitude = _read(QuaternionAttitude.from_orbex, args.orbex, "--orbex", name)
    else:
        attitude = NominalAttitude()
    satellite = Satellite(orbit, attitude, polarization=hand, name=name)
    return satellite, (orbit.epochs[0].utc, orbit.epochs[-1].utc)


def _target(args):
    """The target (a SkyCoord or a Satellite) and the default span of time (or None)."""
    satellite, natural = _given(args, _SATELLITE_OPTIONS), _given(args, _NATURAL_OPTIONS)
    if satellite and natural:
        raise CommandError(f"give one target: a natural source or a satellite, not both "
                           f"({', '.join(natural)} and {', '.join(satellite)})")
    if satellite:
        return _satellite(args)
    return _natural_target(args), None


# Output files -------------------------------------------------------------------------------


def _inputs(args):
    """(option, path) of every file the command reads."""
    inputs = [(f"--{name}", getattr(args, name)) for name in ("tle", "sp3", "orbex", "catalogue")
              if getattr(args, name, None) is not None]
    if getattr(args, "catalogue", None) is None:
        inputs.append(("embedded station catalogue", str(sample_file("stations.ecsv"))))
    return inputs


def _figure_types():
    try:
        from matplotlib.figure import Figure
    except ImportError:
        raise CommandError('--plot needs matplotlib: pip install "astropy_feedrot[all]"') from None
    return ["." + name for name in Figure().canvas.get_supported_filetypes()]


def _draw(table, kind, path):
    def write(name):
        import matplotlib.pyplot as plt  # optional: checked by _figure_types

        try:
            plt.close(getattr(plotting, f"plot_{kind}")(table, name))
        except (RuntimeError, ValueError, OSError) as error:
            # e.g. a .pgf figure without LaTeX
            raise CommandError(f"--plot: cannot draw {str(path)!r}: {_one_line(error)}") from None
    return write


def _outputs(args):
    """The checked table and figure paths of a table command (None: not written)."""
    figure_types = _figure_types() if args.plot is not None else ()
    paths = check_outputs([("-o/--output", args.output, tuple(TABLE_FORMATS)),
                           ("--plot", args.plot, figure_types)],
                          _inputs(args), args.overwrite)
    if paths[0] is not None:
        table_format(paths[0])
    return paths


def _write(table, paths, kind):
    output, figure = paths
    files = []
    if output is not None:
        files.append((output, table_writer(table, table_format(output))))
    if figure is not None:
        files.append((figure, _draw(table, kind, figure)))
    then = None if output is not None else (lambda: table.write(sys.stdout, format="ascii.ecsv"))
    write_files(files, then)


# Commands -----------------------------------------------------------------------------------


def _run_single(args):
    paths = _outputs(args)
    catalogue = _catalogue(args)
    antenna = _antenna(args.antenna, args, catalogue)
    min_elevation = _min_elevation(args)
    target, span = _target(args)
    times = _times(args, default=span)
    table = feed_rotation_table(antenna, target, times, polarization=args.polarization,
                                min_elevation=min_elevation)
    _write(table, paths, "feed_rotation")
    return 0


def _run_natural(args):
    return _run_single(args)


def _run_satellite(args):
    if args.tle is None and args.sp3 is None:
        raise CommandError("give the satellite's orbit with --tle FILE or --sp3 FILE --sat NAME")
    return _run_single(args)


def _run_baseline(args):
    paths = _outputs(args)
    frequency = _quantity(args.frequency, u.MHz, "--frequency")
    catalogue = _catalogue(args)
    first, second = (_antenna(name, args, catalogue) for name in args.antennas)
    min_elevation = _min_elevation(args)
    target, span = _target(args)
    times = _times(args, default=span)
    table = baseline_table(first, second, target, times, frequency,
                           polarization=args.polarization, min_elevation=min_elevation)
    _write(table, paths, "baseline")
    return 0


def _run_antennas(args):
    from .visibility_files import antenna_table, read_antennas

    paths = check_outputs([("-o/--output", args.output, tuple(TABLE_FORMATS))],
                          [("FILE", args.file)], args.overwrite)
    antennas, software = read_antennas(args.file, vertical=args.vertical)
    table = antenna_table(antennas, software)
    table.meta["file"] = str(args.file)
    table.meta["labels"] = software
    files = [] if paths[0] is None else [(paths[0], table_writer(table,
                                                                 table_format(paths[0])))]
    then = None if files else (lambda: table.write(sys.stdout, format="ascii.ecsv"))
    write_files(files, then)
    return 0


def _run_correct(args):
    from .visibility_files import correct_file

    try:
        correct_file(args.input, args.output, frame=args.frame, vertical=args.vertical,
                     overwrite=args.overwrite, progress=not args.quiet and sys.stderr.isatty())
    except FileExistsError as error:
        raise CommandError(f"-o/--output: {_one_line(error)}") from None
    except ImportError as error:
        raise CommandError(_one_line(error)) from None
    return 0


def _run_coverage(args):
    from . import planning, stations  # the planning layer sits above this module's imports

    figure_types = _figure_types() if args.plot is not None else ()
    paths = check_outputs([("-o/--output", args.output, tuple(TABLE_FORMATS)),
                           ("--plot", args.plot, figure_types)],
                          _inputs(args), args.overwrite)
    if paths[0] is not None:
        table_format(paths[0])
    antennas = {}
    for text in args.stations:
        name = text.strip()
        found = None
        if hasattr(stations, "get_network"):  # a network name expands to its stations
            try:
                found = list(stations.get_network(name))
            except (KeyError, ValueError):
                found = None
        if found is None:
            found = [stations.get_antenna(name)]
        for antenna in found:
            antennas.setdefault(antenna.name, antenna)
    sources = {}
    for text in args.source:
        name, equals, where = text.partition("=")
        name, where = name.strip(), where.strip()
        if not equals or not name or not where:
            raise CommandError(f"--source {text!r}: write NAME=COORDINATES, e.g. "
                               "'3C84=03h19m48.16s +41d30m42.1s'; names are not looked up")
        if name in sources:
            raise CommandError(f"--source: the name {name!r} is given twice")
        for kwargs in ({}, {"unit": (u.hourangle, u.deg)}):
            try:
                with np.errstate(all="ignore"):
                    coord = SkyCoord(where, frame="icrs", **kwargs)
            except (ValueError, TypeError, u.UnitsError) as error:
                reason = _one_line(error)
                continue
            sources[name] = _one_source(coord, f"--source {name}", where)
            break
        else:
            raise CommandError(f"--source {name}: cannot read {where!r} as coordinates "
                               f"({reason}); write e.g. '03h19m48.16s +41d30m42.1s'")
    times = _times(args)
    if times.size < 2:
        raise CommandError("--stop must be after --start by at least one --step")
    min_elevation = _min_elevation(args)
    min_elevation = 10 * u.deg if min_elevation is None else min_elevation
    step = _quantity(args.step, u.s, "--step")
    table, epochs, continuous = planning.feed_rotation_coverage(
        list(antennas.values()), sources, times[0], times[-1], step, min_elevation,
        tracks=True)
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
            import matplotlib.pyplot as plt  # optional: checked by _figure_types

            try:
                plt.close(planning.plot_coverage(table, epochs, continuous, name))
            except (RuntimeError, ValueError, OSError) as error:
                raise CommandError(f"--plot: cannot draw {str(paths[1])!r}: "
                                   f"{_one_line(error)}") from None
        files.append((paths[1], draw))
    write_files(files)
    print(f"Feed rotation above {min_elevation} from {epochs[0].isot} to {epochs[-1].isot} "
          f"every {args.step}:")
    print("\n".join(table.pformat(max_lines=-1, max_width=-1)))
    print("\nSources ranked by the range of their worst station:")
    print("\n".join(ranking.pformat(max_lines=-1, max_width=-1)))
    for option, path in zip(("table", "figure"), paths):
        if path is not None:
            print(f"{option}: {path}")
    return 0


def _run_stations(args):
    catalogue = _catalogue(args)
    table = catalogue.table
    keep = np.ones(len(table), dtype=bool)
    if args.network is not None:
        try:
            names = set(catalogue.network_names(args.network))
        except ValueError as error:
            raise CommandError(f"--network: {_one_line(error)}") from None
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


def _run_demo(args):
    directory = Path(args.output_dir).expanduser()
    if not directory.is_dir():
        raise CommandError(f"--output-dir: {args.output_dir!r} is not a directory")
    step = _quantity(args.step, u.s, "--step")
    steps = (11 * u.hour / step).decompose().value
    if not steps < MAX_EPOCHS:
        raise CommandError(f"--step {args.step} gives {steps + 1:.3g} epochs over the 11 hours "
                           f"of the demo, more than the {MAX_EPOCHS} of one run; use a larger "
                           "--step")
    try:
        figure_types = _figure_types()
    except CommandError:
        figure_types = None
    names = [("table", directory / "feedrot_demo.ecsv", (".ecsv",))]
    if figure_types is not None:
        names.append(("figure", directory / "feedrot_demo.png", figure_types))
    paths = check_outputs([("--output-dir", str(path), types) for _, path, types in names], [],
                          args.overwrite, hint="choose another --output-dir")
    table = gps_short_baseline(step=step)
    summary = baseline_summary(table)
    files = [(paths[0], table_writer(table, "ascii.ecsv"))]
    if figure_types is not None:
        files.append((paths[1], _draw(table, "baseline", paths[1])))
    write_files(files)
    print("Section 4.1 of the paper: GPS SVN 76 over the GNSS antenna DBR205 and the")
    print("alt-az telescope FD-VLBA, 73 m apart, on 2023-01-25 (embedded element set, Table 2).")
    print(summary)
    print(f"table:  {names[0][1]}")
    if figure_types is not None:
        print(f"figure: {names[1][1]}")
    else:
        print('figure: skipped (pip install "astropy_feedrot[all]" for matplotlib)')
    return 0


# Parser -------------------------------------------------------------------------------------


def _add_time_options(parser, required=True):
    group = parser.add_argument_group("time")
    group.add_argument("--start", metavar="TIME",
                       help="first epoch, ISO UTC (e.g. 2023-01-25T18:00) or 'now'"
                       + ("" if required else "; default: start of the SP3 file"))
    group.add_argument("--stop", metavar="TIME", help="last epoch (included if on the step)"
                       + ("" if required else "; default: end of the SP3 file"))
    group.add_argument("--step", metavar="DURATION", default="10min",
                       help="sampling interval with a unit (30s, 10min, 1h; default 10min; a "
                       f"plain number is seconds); at most {MAX_EPOCHS} epochs per run")


def _add_natural_options(parser):
    group = parser.add_argument_group("natural source (coordinates are parsed offline)")
    group.add_argument("--source", metavar="COORD",
                       help="coordinates in one string, e.g. '03h19m48.16s +41d30m42.1s'")
    group.add_argument("--ra", metavar="RA", help="right ascension: hours if sexagesimal "
                       "(03:19:48.16, 3h19m48s), degrees if a plain number")
    group.add_argument("--dec", metavar="DEC", help="declination in degrees (+41:30:42.1, 41.51)")
    group.add_argument("--frame", metavar="FRAME",
                       help="celestial frame of the coordinates (default icrs): "
                       + ", ".join(CELESTIAL_FRAMES))


def _add_satellite_options(parser):
    group = parser.add_argument_group("satellite")
    group.add_argument("--tle", metavar="FILE", help="two- or three-line element file")
    group.add_argument("--sp3", metavar="FILE", help="IGS SP3 orbit file (nominal attitude "
                       "unless --orbex)")
    group.add_argument("--sat", metavar="NAME", help="satellite: SP3 name (G05), or TLE name or "
                       "catalogue number when the file has several")
    group.add_argument("--orbex", metavar="FILE", help="ORBEX attitude quaternions (with --sp3)")
    group.add_argument("--points", metavar="N", type=int,
                       help="epochs of the SP3 interpolation window (default 10)")
    group.add_argument("--satellite-polarization", choices=("RCP", "LCP"), type=str.upper,
                       help="hand the satellite transmits (default RCP, as GNSS satellites)")


def _add_common_options(parser):
    group = parser.add_argument_group("antenna and output")
    group.add_argument("--mount", metavar="CODE", help="mount of a LAT,LON,HEIGHT site: AZEL "
                       "(default), EQUA, X-YN, X-YE, NASR, NASL, BWG, GNSS")
    group.add_argument("--focus", metavar="NAME",
                       help="focus of a LAT,LON,HEIGHT site: " + ", ".join(
                           k for k in FOCUS_NAMES if k))
    group.add_argument("--catalogue", metavar="FILE",
                       help="an ECSV station catalogue of one's own instead of the embedded one")
    group.add_argument("--polarization", choices=("RCP", "LCP"), type=str.upper,
                       help="hand of the receiver (default: the satellite's hand; RCP for a "
                       "natural source); a satellite is heard by a receiver of its own hand only")
    group.add_argument("--min-elevation", metavar="ANGLE",
                       help="NaN below this elevation (degrees, or with a unit); the continuous "
                       "series restarts after such gaps")
    group.add_argument("-o", "--output", metavar="FILE",
                       help="write the table here instead of standard output, in the format of "
                       "its extension: " + ", ".join(TABLE_FORMATS))
    group.add_argument("--plot", metavar="FILE.png", help="also draw the table (needs "
                       "matplotlib; .png, .pdf, .svg...)")
    group.add_argument("--overwrite", action="store_true",
                       help="replace an existing output file (never an input)")


def _parser():
    parser = _Parser(
        prog="feedrot",
        description="Feed rotation (parallactic angle, carrier-phase wind-up) of radio "
        "telescopes and GNSS antennas, as tables: time, azimuth, elevation, parallactic "
        "angle, transmitter and receiver terms, total and continuous total (degrees), and "
        "the rate of the feed rotation (deg/s).",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="examples:\n  feedrot demo\n  feedrot stations\n"
        + "\n".join(text.split("\n", 2)[1] for text in _EXAMPLES.values())
        + "\n  feedrot antennas vla.uvfits\n  feedrot correct vla.uvfits -o corrected.uvfits"
        + "\n\n'feedrot COMMAND --help' shows each command's options and more examples.",
    )
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")

    natural = commands.add_parser(
        "natural", help="a natural radio source seen by one antenna",
        description="Feed rotation of one antenna observing a natural radio source.",
        epilog=_EXAMPLES["natural"], formatter_class=argparse.RawDescriptionHelpFormatter)
    natural.add_argument("antenna", metavar="ANTENNA", help=_ANTENNA_HELP)
    _add_natural_options(natural)
    _add_time_options(natural)
    _add_common_options(natural)
    natural.set_defaults(run=_run_natural)

    satellite = commands.add_parser(
        "satellite", help="a satellite seen by one antenna",
        description="Feed rotation (wind-up) of one antenna observing a satellite, split into "
        "transmitter and receiver terms.",
        epilog=_EXAMPLES["satellite"], formatter_class=argparse.RawDescriptionHelpFormatter)
    satellite.add_argument("antenna", metavar="ANTENNA", help=_ANTENNA_HELP)
    _add_satellite_options(satellite)
    _add_time_options(satellite, required=False)
    _add_common_options(satellite)
    satellite.set_defaults(run=_run_satellite)

    baseline = commands.add_parser(
        "baseline", help="both antennas of a baseline and the rotation delay",
        description="Feed rotation at both ends of a baseline and the rotation delay "
        "(antenna 2 minus antenna 1) at a frequency. The target is a natural source "
        "(--source or --ra/--dec) or a satellite (--tle or --sp3).",
        epilog=_EXAMPLES["baseline"], formatter_class=argparse.RawDescriptionHelpFormatter)
    baseline.add_argument("antennas", metavar="ANTENNA", nargs=2, help=_ANTENNA_HELP)
    baseline.add_argument("--frequency", required=True, metavar="FREQ",
                          help="observing frequency with a unit (1575.42MHz; plain: MHz)")
    _add_natural_options(baseline)
    _add_satellite_options(baseline)
    _add_time_options(baseline, required=False)
    _add_common_options(baseline)
    baseline.set_defaults(run=_run_baseline)

    demo = commands.add_parser(
        "demo", help="the paper's Section 4.1 simulation, on embedded data",
        description="GPS SVN 76 over the GNSS antenna DBR205 and the telescope FD-VLBA "
        "(Sec. 4.1 of the paper): prints a summary and writes feedrot_demo.ecsv and "
        "feedrot_demo.png (like Figs 10-11).",
        epilog="example:\n  feedrot demo --output-dir results --step 30s",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    demo.add_argument("--output-dir", default=".", metavar="DIR",
                      help="where to write the table and figure (default: here)")
    demo.add_argument("--step", default="60s", metavar="DURATION",
                      help="sampling interval (default 60s)")
    demo.add_argument("--overwrite", action="store_true",
                      help="replace feedrot_demo.ecsv and feedrot_demo.png if they exist")
    demo.set_defaults(run=_run_demo)

    stations = commands.add_parser(
        "stations", help="list the station catalogue",
        description="Print the station catalogue (names, ITRF positions, mounts, focus types, "
        "sources) as ECSV, all of it or the stations of one network or mount.",
        epilog="examples:\n  feedrot stations --network VLBA\n  feedrot stations --mount NASR\n"
        "  feedrot stations --catalogue mine.ecsv",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    stations.add_argument("--catalogue", metavar="FILE", help="an ECSV catalogue of one's own")
    stations.add_argument("--network", metavar="NAME",
                          help="only the stations of a network (VLBA, EVN, EHT...; "
                               "case-insensitive)")
    stations.add_argument("--mount", metavar="CODE",
                          help="only the stations with this geodetic mount code (AZEL, EQUA, "
                               "X-YE, X-YN, NASR, NASL, BWG, GNSS)")
    stations.set_defaults(run=_run_stations)

    coverage = commands.add_parser(
        "coverage", help="the range of feed rotation of candidate polarization calibrators",
        description="For every station and source, the range of continuous feed rotation "
        "while the source is above the elevation limit, the time above it, and the sources "
        "ranked by their worst station (a polarization calibrator needs a wide range at "
        "every station). Names of networks expand to their stations where the catalogue "
        "knows them.",
        epilog="examples:\n  feedrot coverage --stations EFLSBERG YEBES40M WETTZ13S \\\n"
        "      --source '3C84=03h19m48.16s +41d30m42.1s' \\\n"
        "      --source '3C286=13h31m08.29s +30d30m33.0s' \\\n"
        "      --start 2024-03-01T00:00 --stop 2024-03-02T00:00 --plot tracks.png",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    coverage.add_argument("--stations", nargs="+", required=True, metavar="NAME",
                          help="station names of the catalogue (or names of networks)")
    coverage.add_argument("--source", action="append", required=True, metavar="NAME=COORD",
                          help="a source and its coordinates (ICRS), e.g. "
                          "'3C84=03h19m48.16s +41d30m42.1s'; repeat for more")
    _add_time_options(coverage)
    coverage.add_argument("--min-elevation", metavar="ANGLE",
                          help="elevation limit (degrees, or with a unit; default 10)")
    coverage.add_argument("-o", "--output", metavar="FILE",
                          help="also write the table here, in the format of its extension: "
                          + ", ".join(TABLE_FORMATS))
    coverage.add_argument("--plot", metavar="FILE.png",
                          help="draw the tracks: one panel per source, one line per station "
                          "(needs matplotlib)")
    coverage.add_argument("--overwrite", action="store_true",
                          help="replace existing output files")
    coverage.set_defaults(run=_run_coverage)

    antennas = commands.add_parser(
        "antennas", help="the antennas of a visibility file, as read",
        description="The antennas of a visibility file (FITS-IDI, UVFITS, uvh5, Measurement "
        "Set, Miriad, SMA Mir) as read for the correction: number, name, ITRF position, "
        "mount label (in the file's convention), mount, focus, receptors and their angles.",
        epilog="examples:\n  feedrot antennas experiment.idifits\n"
        "  feedrot antennas vla.ms -o antennas.ecsv",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    antennas.add_argument("file", metavar="FILE", help="a visibility file or directory")
    antennas.add_argument("--vertical", choices=("geodetic", "geocentric"), default="geodetic",
                          help="the local vertical (geocentric reproduces CASA)")
    antennas.add_argument("-o", "--output", metavar="FILE",
                          help="write the table here (format of its extension) instead of "
                          "standard output")
    antennas.add_argument("--overwrite", action="store_true",
                          help="replace an existing output file")
    antennas.set_defaults(run=_run_antennas)

    correct = commands.add_parser(
        "correct", help="a copy of a visibility file with the feed rotation removed",
        description="Write a copy of a visibility file with the feed rotation removed from "
        "every visibility: FITS-IDI to FITS-IDI (memory-mapped), and every format pyuvdata "
        "reads to the format of the output's extension (.uvfits, .uvh5, .ms). The input is "
        "never modified.",
        epilog="examples:\n  feedrot correct vla.uvfits -o vla_corrected.uvfits\n"
        "  feedrot correct experiment.idifits -o corrected.idifits --frame icrs\n"
        "  feedrot correct alma.ms -o alma_corrected.ms --vertical geocentric",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    correct.add_argument("input", metavar="INPUT", help="a visibility file or directory")
    correct.add_argument("-o", "--output", required=True, metavar="OUTPUT",
                         help="the corrected copy")
    correct.add_argument("--frame", default="apparent", choices=("apparent",) + CELESTIAL_FRAMES,
                         help="north of the corrected polarization angles: the apparent pole "
                         "of date (default) or a catalogue frame such as icrs")
    correct.add_argument("--vertical", choices=("geodetic", "geocentric"), default="geodetic",
                         help="the local vertical (geocentric reproduces CASA)")
    correct.add_argument("--overwrite", action="store_true",
                         help="replace an existing output (never the input)")
    correct.add_argument("--quiet", action="store_true", help="no progress bar")
    correct.set_defaults(run=_run_correct)
    return parser


def _protect_sites(argv):
    # A southern or western site such as -33.0,148.26,415 would look like an
    # option to argparse; a leading space keeps it positional.
    return [f" {arg}" if arg.startswith("-") and not arg.startswith("--") and arg.count(",") == 2
            else arg for arg in argv]


def _show_warning(message, category, filename, lineno, file=None, line=None):
    print(f"feedrot: warning: {_one_line(message)}", file=sys.stderr)


def _run(args):
    """Run a parsed command: its exit status, and any error as one line on stderr."""
    try:
        status = args.run(args)
        sys.stdout.flush()
        return status
    except (CommandError, FileFormatError, ValueError, TypeError, KeyError, OSError,
            u.UnitsError) as error:
        if isinstance(error, BrokenPipeError):
            # The reader of standard output has gone (feedrot ... | head): stop quietly.
            with contextlib.suppress(OSError, ValueError):
                os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            return 1
        message = error.args[0] if isinstance(error, KeyError) and error.args else error
        print(f"feedrot: error: {_one_line(message)}", file=sys.stderr)
        return 1
    except MemoryError:
        print("feedrot: error: out of memory; use fewer epochs (a larger --step or a shorter "
              "span)", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("feedrot: interrupted", file=sys.stderr)
        return 130
    except Exception as error:
        print(f"feedrot: error: internal error ({type(error).__name__}: {_one_line(error)}); "
              "please report it with the command line", file=sys.stderr)
        return 1


def main(argv=None):
    """Run the ``feedrot`` command line.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status: 0 on success, 1 for bad input or a failed
        computation, 2 for a command line that does not parse, 130 when
        interrupted. Every error is one line on standard error.

    Examples
    --------
    >>> from astropy_feedrot.cli import main
    >>> main(["natural", "EFLSBERG", "--source", "03h19m48.16s +41d30m42.1s",
    ...       "--start", "2023-01-25T18:00", "--stop", "2023-01-25T19:00",
    ...       "--step", "1h"])  # doctest: +ELLIPSIS
    # %ECSV 1.0
    ...
    0
    """
    parser = _parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        args = parser.parse_args(_protect_sites(argv))
    except _UsageError as error:
        print(f"feedrot: error: {_one_line(error)}", file=sys.stderr)
        return 2
    if not hasattr(args, "run"):
        parser.print_help()
        return 2
    # One Earth-orientation context for the whole run: at most one warning
    # (one line) about stale tables, however many computations it makes.
    with warnings.catch_warnings():
        warnings.simplefilter("default")
        warnings.showwarning = _show_warning
        with iers_context():
            return _run(args)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
