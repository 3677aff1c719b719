# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The ``feedrot`` command line.

``feedrot natural``, ``feedrot satellite`` and ``feedrot baseline`` tabulate
feed rotation over a span of time (ECSV on standard output or to a file, and
optionally a figure); ``feedrot demo`` runs the paper's Section 4.1 simulation
on embedded data; ``feedrot stations`` lists the station catalogue. Errors are
one line on standard error and a non-zero exit status.
"""

import argparse
import os
import re
import sys
import warnings
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation, SkyCoord
from astropy.time import Time

from .antenna import Antenna
from .attitude import NominalAttitude, QuaternionAttitude
from .eop import iers_context
from .io import FileFormatError, read_tle
from .labels import mount_from_label
from .orbits import SP3Orbit, TLEOrbit
from .satellite import Satellite
from .stations import FOCUS_NAMES, default_catalogue, focus_from_name, read_catalogue
from .tables import baseline_table, feed_rotation_table

__all__ = ["main", "CommandError"]

#: Most epochs one command may compute.
MAX_EPOCHS = 10_000_000

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
  feedrot satellite FD-VLBA --sp3 igs.sp3 --sat G05 --orbex igs.obx -o g05.ecsv""",
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

_SITE = re.compile(r"^\s*([-+]?\d+(?:\.\d*)?),\s*([-+]?\d+(?:\.\d*)?),\s*([-+]?\d+(?:\.\d*)?)\s*$")


class CommandError(Exception):
    """A problem with the command's input, reported on one line."""


def _quantity(text, unit, what):
    """A positive quantity from text like '30s', '10 min' or '1575.42MHz'."""
    try:
        value = u.Quantity(text)
    except (TypeError, ValueError):
        raise CommandError(f"{what}: cannot read {text!r} as a number with a unit "
                           f"(e.g. 30s, 10min)") from None
    if value.unit == u.dimensionless_unscaled:
        value = value.value * unit
    try:
        value = value.to(unit)
    except u.UnitConversionError:
        raise CommandError(f"{what}: {text!r} is not in a unit of {unit.physical_type}") from None
    if not np.isfinite(value) or value <= 0:
        raise CommandError(f"{what} must be positive, got {text!r}")
    return value


def _time(text, what):
    if text.strip().lower() == "now":
        return Time.now()
    try:
        return Time(text.strip(), scale="utc")
    except (ValueError, TypeError):
        raise CommandError(f"{what}: cannot read {text!r} as a time; use ISO format, e.g. "
                           "2023-01-25T18:00 (UTC)") from None


def _times(args, default=None):
    start = _time(args.start, "--start") if args.start else None
    stop = _time(args.stop, "--stop") if args.stop else None
    if (start is None or stop is None) and default is not None:
        start = default[0] if start is None else start
        stop = default[1] if stop is None else stop
    if start is None or stop is None:
        raise CommandError("give the span of time with --start and --stop")
    step = _quantity(args.step, u.s, "--step")
    if stop < start:
        raise CommandError(f"--stop ({stop.isot}) is before --start ({start.isot})")
    count = int(np.floor(((stop - start).to(u.s) / step).decompose().value * (1 + 1e-12))) + 1
    if count > MAX_EPOCHS:
        raise CommandError(f"{count} epochs from --start to --stop at --step {args.step}; "
                           f"at most {MAX_EPOCHS} per run")
    return start + np.arange(count) * step


def _catalogue(args):
    if getattr(args, "catalogue", None):
        try:
            return read_catalogue(args.catalogue)
        except FileNotFoundError:
            raise CommandError(f"--catalogue: no such file {args.catalogue!r}") from None
    return default_catalogue()


def _antenna(text, args):
    site = _SITE.match(text)
    catalogue = _catalogue(args)
    if site is None:
        if args.mount or args.focus:
            raise CommandError(f"--mount and --focus go with a site LAT,LON,HEIGHT, not with the "
                               f"catalogue station {text!r}")
        return catalogue.get_antenna(text.strip())
    lat, lon, height = (float(v) for v in site.groups())
    if not -90 <= lat <= 90:
        raise CommandError(f"latitude {lat} of site {text.strip()!r} is not in [-90, 90] deg; "
                           "the order is LAT,LON,HEIGHT")
    location = EarthLocation.from_geodetic(lon * u.deg, lat * u.deg, height * u.m)
    mount, focus = mount_from_label(args.mount or "AZEL", "geodetic")
    if args.focus:
        focus = focus_from_name(args.focus, "--focus")
    return Antenna(location, mount, focus, name=f"site {text.strip()}")


def _natural_target(args):
    frame = args.frame
    if args.source is not None:
        if args.ra is not None or args.dec is not None:
            raise CommandError("give the source either with --source or with --ra and --dec")
        for kwargs in ({}, {"unit": (u.hourangle, u.deg)}):
            try:
                return SkyCoord(args.source, frame=frame, **kwargs)
            except (ValueError, TypeError, u.UnitsError):
                continue
        raise CommandError(f"--source: cannot read {args.source!r} as coordinates (e.g. "
                           "'03h19m48.16s +41d30m42.1s' or '49.95d 41.51d'); looking up "
                           "names needs the internet, give the coordinates instead")
    if args.ra is None or args.dec is None:
        raise CommandError("give the source with --source, or with both --ra and --dec")
    plain = re.fullmatch(r"\s*[-+]?\d+(\.\d*)?\s*", args.ra) is not None
    ra_unit = u.deg if plain else u.hourangle
    try:
        return SkyCoord(args.ra, args.dec, unit=(ra_unit, u.deg), frame=frame)
    except (ValueError, TypeError, u.UnitsError) as error:
        raise CommandError(f"--ra/--dec: cannot read {args.ra!r} {args.dec!r} as coordinates "
                           f"({error}); e.g. --ra 03:19:48.16 --dec +41:30:42.1 (hours, "
                           "degrees) or --ra 49.95 --dec 41.51 (degrees)") from None


def _read_path(path, what):
    if not Path(path).is_file():
        raise CommandError(f"{what}: no such file {path!r}")
    return path


def _satellite(args):
    polarization = args.polarization or "RCP"
    if args.tle is not None:
        if args.sp3 is not None or args.orbex is not None:
            raise CommandError("--tle goes alone; --sp3 (with --orbex) is the other orbit source")
        records = read_tle(_read_path(args.tle, "--tle"))
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
        return Satellite(orbit, polarization=polarization, name=record.name), None
    if args.sp3 is None:
        raise CommandError("give the satellite's orbit with --tle FILE or --sp3 FILE --sat NAME")
    if args.sat is None:
        raise CommandError("--sp3 needs --sat, the satellite's SP3 name (e.g. G05)")
    name = args.sat.strip()
    orbit = SP3Orbit(_read_path(args.sp3, "--sp3"), name, points=args.points)
    if args.orbex is not None:
        attitude = QuaternionAttitude.from_orbex(_read_path(args.orbex, "--orbex"), name)
    else:
        attitude = NominalAttitude()
    satellite = Satellite(orbit, attitude, polarization=polarization, name=name)
    return satellite, (orbit.epochs[0], orbit.epochs[-1])


def _target(args):
    if getattr(args, "tle", None) is not None or getattr(args, "sp3", None) is not None:
        return _satellite(args)
    return _natural_target(args), None


def _check_output(path, what):
    if path is None:
        return
    parent = Path(path).expanduser().resolve().parent
    if not parent.is_dir():
        raise CommandError(f"{what}: cannot write {path!r}: directory {str(parent)!r} does "
                           "not exist")
    if Path(path).is_dir():
        raise CommandError(f"{what}: {path!r} is a directory")
    if not os.access(parent, os.W_OK) or (Path(path).exists() and not os.access(path, os.W_OK)):
        raise CommandError(f"{what}: cannot write {path!r}: permission denied")


def _check_plot(path):
    if path is None:
        return
    _check_output(path, "--plot")
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise CommandError('--plot needs matplotlib: pip install "astropy_feedrot[all]"') from None


def _min_elevation(args):
    if args.min_elevation is None:
        return None
    try:
        value = u.Quantity(args.min_elevation)
    except (TypeError, ValueError):
        raise CommandError(f"--min-elevation: cannot read {args.min_elevation!r}") from None
    value = value.value * u.deg if value.unit == u.dimensionless_unscaled else value
    try:
        value = value.to(u.deg)
    except u.UnitConversionError:
        raise CommandError(f"--min-elevation: {args.min_elevation!r} is not an angle") from None
    if not -90 <= value.value <= 90:
        raise CommandError(f"--min-elevation must be within [-90, 90] deg, got "
                           f"{args.min_elevation!r}")
    return value


def _write(table, args, kind):
    if args.output:
        table.write(args.output, format="ascii.ecsv", overwrite=True)
    else:
        table.write(sys.stdout, format="ascii.ecsv")
    if args.plot:
        import matplotlib.pyplot as plt

        from . import plotting

        plt.close(getattr(plotting, f"plot_{kind}")(table, args.plot))


def _run_single(args):
    _check_output(args.output, "-o/--output")
    _check_plot(args.plot)
    antenna = _antenna(args.antenna, args)
    target, span = _target(args)
    table = feed_rotation_table(antenna, target, _times(args, default=span),
                                polarization=args.polarization,
                                min_elevation=_min_elevation(args))
    _write(table, args, "feed_rotation")
    return 0


def _run_natural(args):
    args.tle = args.sp3 = None
    return _run_single(args)


def _run_satellite(args):
    if args.tle is None and args.sp3 is None:
        raise CommandError("give the satellite's orbit with --tle FILE or --sp3 FILE --sat NAME")
    return _run_single(args)


def _run_baseline(args):
    _check_output(args.output, "-o/--output")
    _check_plot(args.plot)
    frequency = _quantity(args.frequency, u.MHz, "--frequency")
    first, second = (_antenna(name, args) for name in args.antennas)
    target, span = _target(args)
    table = baseline_table(first, second, target, _times(args, default=span), frequency,
                           polarization=args.polarization, min_elevation=_min_elevation(args))
    _write(table, args, "baseline")
    return 0


def _run_stations(args):
    catalogue = _catalogue(args)
    table = catalogue.table
    keep = [c for c in ("name", "aliases", "x", "y", "z", "mount", "focus", "source")
            if c in table.colnames]
    table[keep].write(sys.stdout, format="ascii.ecsv")
    return 0


def _run_demo(args):
    from .simulations import gps_short_baseline
    from .tables import baseline_summary

    directory = Path(args.output_dir)
    if not directory.is_dir():
        raise CommandError(f"--output-dir: {args.output_dir!r} is not a directory")
    table_path = directory / "feedrot_demo.ecsv"
    figure_path = directory / "feedrot_demo.png"
    _check_output(table_path, "--output-dir")
    step = _quantity(args.step, u.s, "--step")
    table = gps_short_baseline(step=step)
    print("Section 4.1 of the paper: GPS SVN 76 over the GNSS antenna DBR205 and the")
    print("alt-az telescope FD-VLBA, 73 m apart, on 2023-01-25 (embedded element set, Table 2).")
    print(baseline_summary(table))
    table.write(table_path, format="ascii.ecsv", overwrite=True)
    print(f"table:  {table_path}")
    try:
        from .plotting import plot_baseline

        import matplotlib.pyplot as plt

        plt.close(plot_baseline(table, figure_path))
        print(f"figure: {figure_path}")
    except ImportError:
        print('figure: skipped (pip install "astropy_feedrot[all]" for matplotlib)')
    return 0


def _add_time_options(parser, required=True):
    group = parser.add_argument_group("time")
    group.add_argument("--start", metavar="TIME",
                       help="first epoch, ISO UTC (e.g. 2023-01-25T18:00) or 'now'"
                       + ("" if required else "; default: start of the SP3 file"))
    group.add_argument("--stop", metavar="TIME", help="last epoch (included if on the step)"
                       + ("" if required else "; default: end of the SP3 file"))
    group.add_argument("--step", metavar="DURATION", default="10min",
                       help="sampling interval with a unit (30s, 10min, 1h; default 10min; a "
                       "plain number is seconds)")


def _add_natural_options(parser):
    group = parser.add_argument_group("natural source (coordinates are parsed offline)")
    group.add_argument("--source", metavar="COORD",
                       help="coordinates in one string, e.g. '03h19m48.16s +41d30m42.1s'")
    group.add_argument("--ra", metavar="RA", help="right ascension: hours if sexagesimal "
                       "(03:19:48.16, 3h19m48s), degrees if a plain number")
    group.add_argument("--dec", metavar="DEC", help="declination in degrees (+41:30:42.1, 41.51)")
    group.add_argument("--frame", default="icrs",
                       help="celestial frame of the coordinates (default icrs; fk5, galactic...)")


def _add_satellite_options(parser):
    group = parser.add_argument_group("satellite")
    group.add_argument("--tle", metavar="FILE", help="two- or three-line element file")
    group.add_argument("--sp3", metavar="FILE", help="IGS SP3 orbit file (nominal attitude "
                       "unless --orbex)")
    group.add_argument("--sat", metavar="NAME", help="satellite: SP3 name (G05), or TLE name or "
                       "catalogue number when the file has several")
    group.add_argument("--orbex", metavar="FILE", help="ORBEX attitude quaternions (with --sp3)")
    group.add_argument("--points", metavar="N", type=int, default=10,
                       help="epochs of the SP3 interpolation window (default 10)")


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
                       help="hand of the receiver (default RCP; a satellite's own hand)")
    group.add_argument("--min-elevation", metavar="ANGLE",
                       help="NaN below this elevation (degrees, or with a unit); the continuous "
                       "series restarts after such gaps")
    group.add_argument("-o", "--output", metavar="FILE", help="write the ECSV table here "
                       "instead of standard output")
    group.add_argument("--plot", metavar="FILE.png", help="also draw the table (needs matplotlib)")


def _parser():
    parser = argparse.ArgumentParser(
        prog="feedrot",
        description="Feed rotation (parallactic angle, carrier-phase wind-up) of radio "
        "telescopes and GNSS antennas, as ECSV tables: time, azimuth, elevation, parallactic "
        "angle, transmitter and receiver terms, total and continuous total (degrees).",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="examples:\n  feedrot demo\n  feedrot stations\n"
        + "\n".join(text.split("\n", 2)[1] for text in _EXAMPLES.values())
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
    demo.set_defaults(run=_run_demo)

    stations = commands.add_parser(
        "stations", help="list the station catalogue",
        description="Print the station catalogue (names, ITRF positions, mounts, focus types, "
        "sources) as ECSV.", epilog="example:\n  feedrot stations --catalogue mine.ecsv",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    stations.add_argument("--catalogue", metavar="FILE", help="an ECSV catalogue of one's own")
    stations.set_defaults(run=_run_stations)
    return parser


def _protect_sites(argv):
    # A southern or western site such as -33.0,148.26,415 would look like an
    # option to argparse; a leading space keeps it positional.
    return [f" {arg}" if arg.startswith("-") and _SITE.match(arg) else arg for arg in argv]


def _show_warning(message, category, filename, lineno, file=None, line=None):
    print(f"feedrot: warning: {message}", file=sys.stderr)


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
        computation (one line on standard error), 2 for a usage error.

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
    args = parser.parse_args(_protect_sites(argv))
    if not hasattr(args, "run"):
        parser.print_help()
        return 2
    # One Earth-orientation context for the whole run: at most one warning
    # (one line) about stale tables, however many computations it makes.
    with warnings.catch_warnings():
        warnings.simplefilter("default")
        warnings.showwarning = _show_warning
        with iers_context():
            try:
                return args.run(args)
            except (CommandError, FileFormatError, ValueError, TypeError, KeyError, OSError,
                    u.UnitsError) as error:
                message = error.args[0] if isinstance(error, KeyError) and error.args else error
                print(f"feedrot: error: {message}", file=sys.stderr)
                return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
