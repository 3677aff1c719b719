# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The grammar of ``feedrot``: every command, its arguments, options, help and examples.

The parser is built from plain constants (here and in
`astropy_feedrot.core.choices`) without importing astropy, numpy or the
modules that do the work: ``feedrot --version`` and ``feedrot --help`` start
in a tenth of a second instead of a second. Each command runs from the module
of its family (``tables``, ``faraday``, ``demo``, ``stations``, ``coverage``,
``data``, ``rinex``, ``samples``), named in `COMMANDS` and imported only when the
command runs (`astropy_feedrot.cli.running.run_command`). The constants and
helpers the commands share with the parser are `astropy_feedrot.cli.shared`'s: no
command imports the parser.
"""

import argparse

from ..core.choices import ATTITUDES, CONVENTIONS, FOCI, MOUNTS, POLES
from ..core.outputs import TABLE_FORMATS
from ..core.version import version
from .samples import run_samples
from .shared import (
    ANTENNA_HELP,
    CELESTIAL_FRAMES,
    FORMATS,
    MAX_EPOCHS,
    MOUNTS_HELP,
    NEAR_LIMIT,
    PHASE_UNIT_NAMES,
    SITE_FORMAT,
    UsageError,
)

__all__ = [
    "build_parser", "EXAMPLES", "MAX_EPOCHS", "CELESTIAL_FRAMES", "ANTENNA_HELP", "SITE_FORMAT",
    "FORMATS", "PHASE_UNIT_NAMES", "NEAR_LIMIT", "MOUNTS_HELP", "UsageError", "Parser",
    "COMMANDS", "examples", "add_units_option", "add_time_options", "add_natural_options",
    "add_common_options",
]


#: The examples of each command, one command line each: its ``--help`` prints them as
#: they are (and ``feedrot --help`` one or two of each); tests/cli/test_cli_examples.py runs
#: each in an empty directory. Files are the shipped samples, named as 'feedrot samples NAME'
#: prints them (a Measurement Set corrected in place is a copy of the sample); a comment
#: names an optional package an example needs and its extra.
_SGP4 = "   # sgp4: the all extra"
_PLOT = "   # matplotlib: the all extra"
_MS = "   # python-casacore: the ms extra"
_UVDATA = "   # pyuvdata: the uvdata extra"
_TLE = '"$(feedrot samples gps.tle)"'
_SP3 = '"$(feedrot samples sample.sp3)"'
_IONEX = '"$(feedrot samples codg0080.20i.Z)" "$(feedrot samples codg0090.20i.Z)"'
_UVFITS = '"$(feedrot samples vla_day2_8chan.uvfits)"'
_IDI = '"$(feedrot samples difx_k08161.idifits)"'
_MS_SAMPLE = '"$(feedrot samples vla_sim.ms)"'
_MS_COPY = '"$(feedrot samples vla_sim.ms --copy)"'
_GNSS = ('"$(feedrot samples gnss_sample.rnx)" --sp3 "$(feedrot samples gnss_sample.sp3)"')
EXAMPLES = {
    "natural": [
        'feedrot natural YEBES40M --source "03h19m48.16s +41d30m42.1s" '
        "--start 2023-01-25T18:00 --stop 2023-01-26T06:00 --step 10min",
        "feedrot natural EFLSBERG --ra 12:29:06.7 --dec +02:03:09 --start 2024-03-01 "
        "--stop 2024-03-02 -o 3c273.ecsv --plot 3c273.png" + _PLOT,
        'feedrot natural 40.5247,-3.0869,988 --mount NASR --source "187.27d 2.05d" '
        "--start 2024-03-01T20:00 --stop 2024-03-01T22:00 --step 1min",
    ],
    "satellite": [
        f"feedrot satellite DBR205 --tle {_TLE} --sat 41328 --start 2023-01-25T06:00 "
        "--stop 2023-01-25T17:00 --step 30s --min-elevation 10" + _SGP4,
        f"feedrot satellite FD-VLBA --sp3 {_SP3} --sat G01 --points 4 -o g01.fits",
        f"feedrot satellite GGAO12M --sp3 {_SP3} --points 4 --step 30s --units cycles "
        "-o all.ecsv",
    ],
    "baseline": [
        f"feedrot baseline DBR205 FD-VLBA --tle {_TLE} --sat 41328 --start 2023-01-25T06:00 "
        "--stop 2023-01-25T17:00 --frequency 1575.42MHz --min-elevation 10" + _SGP4,
        'feedrot baseline EFLSBERG YEBES40M --source "03h19m48.16s +41d30m42.1s" '
        "--start 2023-01-25T18:00 --stop 2023-01-26T06:00 --frequency 8.4GHz",
    ],
    "faraday": [
        'feedrot faraday EFLSBERG YEBES40M --source "05h34m31.94s +22d00m52.2s" '
        "--start 2020-01-08T16:00 --stop 2020-01-09T06:00 --step 30min "
        f"--ionex {_IONEX} --frequency 1.4GHz --frequency 5GHz"
        "   # spinifex: the ionosphere extra",
        'feedrot faraday WSTRBORK --source "05h34m31.94s +22d00m52.2s" --start 2020-01-08T20:00 '
        f"--stop 2020-01-09T02:00 --step 10min --ionex {_IONEX} "
        "--frequency 150MHz --min-elevation 20 -o crab.ecsv --plot crab.png"
        "   # spinifex, matplotlib: the ionosphere and all extras",
        'feedrot faraday EFLSBERG --source "03h19m48.16s +41d30m42.1s" --start 2024-06-01T08:00 '
        '--stop 2024-06-01T10:00 --step 10min --rm-table "$(feedrot samples rm_effelsberg.ecsv)" '
        "--frequency 1.4GHz",
    ],
    "demo": ["feedrot demo   # sgp4 (matplotlib for the figure): the all extra",
             "feedrot demo --step 30s --overwrite" + _SGP4,
             "feedrot demo --output-dir results" + _SGP4],
    "stations": ["feedrot stations",
                 "feedrot stations YEBES40M",
                 "feedrot stations 'EF*'",
                 "feedrot stations --network VLBA",
                 "feedrot stations --mount NASR",
                 "feedrot stations --near -3.09,40.52",
                 "feedrot stations --network EHT -o eht.ecsv"],
    "coverage": [
        "feedrot coverage --stations EFLSBERG YEBES40M WETTZ13S "
        "--source '3C84=03h19m48.16s +41d30m42.1s' --source '3C286=13h31m08.29s +30d30m33.0s' "
        "--start 2024-03-01T00:00 --stop 2024-03-02T00:00 --plot tracks.png" + _PLOT,
        "feedrot coverage --stations VLBA --source '03h19m48.16s +41d30m42.1s' "
        "--start 2024-03-01 --stop 2024-03-02",
    ],
    "antennas": [f"feedrot antennas {_IDI}",
                 f"feedrot antennas {_MS_SAMPLE} -o antennas.ecsv" + _MS,
                 f"feedrot antennas {_UVFITS} --mounts catalogue"],
    "correct": [f"feedrot correct {_UVFITS} -o vla_corrected.uvfits" + _UVDATA,
                f"feedrot correct {_IDI} -o corrected.idifits --frame icrs",
                f"feedrot correct {_MS_SAMPLE} -o vla_corrected.ms --vertical geocentric" + _MS,
                f"feedrot correct {_MS_COPY} --in-place" + _MS,
                f"feedrot correct {_MS_COPY} --in-place --column MODEL_DATA --apply" + _MS,
                f"feedrot correct {_UVFITS} -o vla_given.uvfits --feeds R,L" + _UVDATA,
                f"feedrot correct {_UVFITS} -o vla_catalogue.uvfits --mounts catalogue"
                + _UVDATA,
                f"feedrot correct {_MS_COPY} --in-place --convention casa --workers 2"
                "   # python-casacore, dask: the ms and dask extras",
                f"feedrot correct {_MS_COPY} --overwrite --in-place "
                '--rm-table "$(feedrot samples rm_constant.ecsv)"' + _MS],
    "rinex": [f"feedrot rinex {_GNSS} -o corrected.rnx",
              f"feedrot rinex {_GNSS} -o out.rnx --table windup.ecsv --units deg"],
    "samples": ["feedrot samples",
                "feedrot samples gnss_sample.sp3",
                f"feedrot antennas {_IDI}",
                f"feedrot correct {_MS_COPY} --in-place" + _MS],
}


# Parsers and shared options ----------------------------------------------------------------


def examples(commands):
    """The ``--help`` epilog listing example commands, each whole on one line.

    (A command continued with a trailing backslash cannot be copied from a
    list of several: pasted, the lines join into one.)
    """
    for command in commands:
        if "\n" in command or command.rstrip().endswith("\\"):
            raise ValueError(f"an example must be one line: {command!r}")
    return "examples:\n" + "\n".join(f"  {command}" for command in commands)


class Parser(argparse.ArgumentParser):
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
        raise UsageError(f"{message}; see '{self.prog} --help'")


def add_units_option(parser, default):
    """Add ``--units cycles|rad|deg``: the unit of phase columns."""
    parser.add_argument("--units", choices=PHASE_UNIT_NAMES, default=default,
                        help=f"unit of the feed rotation (wind-up) columns: cycles, rad or deg "
                        f"(default {default}; azimuth and elevation stay in deg)")


def add_time_options(parser, required=True):
    group = parser.add_argument_group("time")
    group.add_argument("--start", metavar="TIME",
                       help="first epoch, ISO UTC (e.g. 2023-01-25T18:00) or 'now'"
                       + ("" if required else "; default: start of the SP3 file"))
    group.add_argument("--stop", metavar="TIME", help="last epoch (included if on the step)"
                       + ("" if required else "; default: end of the SP3 file"))
    group.add_argument("--step", metavar="DURATION", default="10min",
                       help="sampling interval with a unit (30s, 10min, 1h; default 10min; a "
                       f"plain number is seconds); at most {MAX_EPOCHS} epochs per run")


def add_natural_options(parser):
    group = parser.add_argument_group("natural source (coordinates are parsed offline)")
    group.add_argument("--source", metavar="COORD",
                       help="coordinates in one string, e.g. '03h19m48.16s +41d30m42.1s'")
    group.add_argument("--ra", metavar="RA", help="right ascension: hours if sexagesimal "
                       "(03:19:48.16, 3h19m48s), degrees if a plain number")
    group.add_argument("--dec", metavar="DEC", help="declination in degrees (+41:30:42.1, 41.51)")
    group.add_argument("--frame", metavar="FRAME",
                       help="celestial frame of the coordinates (default icrs): "
                       + ", ".join(CELESTIAL_FRAMES))


def add_common_options(parser, polarization=True,
                       min_elevation="NaN below this elevation (degrees, or with a unit); the "
                       "continuous series restarts after such gaps"):
    """Add the antenna and output options: ``--polarization`` unless ``polarization`` is
    False, ``--min-elevation`` with the help ``min_elevation``."""
    group = parser.add_argument_group("antenna and output")
    group.add_argument("--mount", metavar="CODE", help="mount of a LAT,LON,HEIGHT site: AZEL "
                       "(default), EQUA, X-YN, X-YE, NASR, NASL, BWG, GNSS")
    group.add_argument("--focus", metavar="NAME",
                       help="focus of a LAT,LON,HEIGHT site: " + ", ".join(FOCI))
    group.add_argument("--catalogue", metavar="FILE",
                       help="an ECSV station catalogue of one's own instead of the embedded one")
    if polarization:
        group.add_argument("--polarization", choices=("RCP", "LCP"), type=str.upper,
                           help="hand of the receiver (default: the satellite's hand; RCP for "
                           "a natural source); a satellite is heard by a receiver of its own "
                           "hand only")
    group.add_argument("--min-elevation", metavar="ANGLE", help=min_elevation)
    group.add_argument("-o", "--output", metavar="FILE",
                       help="write the table here instead of standard output, in the format of "
                       "its extension: " + ", ".join(TABLE_FORMATS))
    group.add_argument("--format", choices=FORMATS,
                       help="the table on standard output: text (aligned, 0.001 deg; the "
                       "default on a terminal), ecsv (every digit; the default on a pipe) or "
                       "csv")
    group.add_argument("--plot", metavar="FILE.png", help="also draw the table (needs "
                       "matplotlib; .png, .pdf, .svg...)")
    group.add_argument("--overwrite", action="store_true",
                       help="replace an existing output file (never an input)")


def build_parser():
    """The argument parser of ``feedrot``, with every command.

    Returns
    -------
    argparse.ArgumentParser
        Each command's parser sets ``run``, the function that runs it.
    """
    parser = Parser(
        prog="feedrot",
        description="Feed rotation (parallactic angle, carrier-phase wind-up) of radio "
        "telescopes and GNSS antennas, as tables: time, azimuth, elevation, parallactic "
        "angle, transmitter and receiver terms, total and continuous total (degrees), and "
        "the rate of the feed rotation (deg/s).",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=examples(EXAMPLES["demo"][:1] + EXAMPLES["stations"][:1]
                        + [EXAMPLES[name][0] for name in ("natural", "satellite", "baseline",
                                                          "faraday")]
                        + [EXAMPLES["coverage"][1], EXAMPLES["antennas"][0],
                           EXAMPLES["correct"][0], EXAMPLES["rinex"][0]])
        + "\n\n'feedrot COMMAND --help' shows each command's options and more examples; "
        "'feedrot samples' lists the sample files shipped with the package, which the "
        "examples name.",
    )
    parser.add_argument("--version", action="version", version=f"feedrot {version}",
                        help="show the version of astropy_feedrot and exit")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    for add in (_add_tables, _add_faraday, _add_demo, _add_stations, _add_coverage, _add_files,
                _add_rinex, _add_samples):
        add(commands)
    return parser


# The commands -----------------------------------------------------------------------------


def _add_satellite_options(parser):
    group = parser.add_argument_group("satellite")
    group.add_argument("--tle", metavar="FILE", help="two- or three-line element file")
    group.add_argument("--sp3", metavar="FILE", help="IGS SP3 orbit file (nominal attitude "
                       "unless --orbex)")
    group.add_argument("--sat", metavar="NAME", help="satellite: SP3 name (G05), or TLE name or "
                       "catalogue number when the file has several; without it, every "
                       "satellite of an SP3 file (one row per epoch and satellite, column prn)")
    group.add_argument("--orbex", metavar="FILE", help="ORBEX attitude quaternions (with --sp3)")
    group.add_argument("--points", metavar="N", type=int,
                       help="epochs of the SP3 interpolation window (default 10, or all epochs "
                       "of a shorter file)")
    group.add_argument("--satellite-polarization", choices=("RCP", "LCP"), type=str.upper,
                       help="hand the satellite transmits (default RCP, as GNSS satellites)")


def _add_tables(commands):
    """``natural``, ``satellite`` and ``baseline``: tables of feed rotation."""
    natural = commands.add_parser(
        "natural", help="a natural radio source seen by one antenna",
        description="Feed rotation of one antenna observing a natural radio source.",
        epilog=examples(EXAMPLES["natural"]), formatter_class=argparse.RawDescriptionHelpFormatter)
    natural.add_argument("antenna", metavar="ANTENNA", help=ANTENNA_HELP)
    add_natural_options(natural)
    add_time_options(natural)
    add_common_options(natural)

    satellite = commands.add_parser(
        "satellite", help="a satellite seen by one antenna",
        description="Feed rotation (wind-up) of one antenna observing a satellite, split into "
        "transmitter and receiver terms.",
        epilog=examples(EXAMPLES["satellite"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    satellite.add_argument("antenna", metavar="ANTENNA", help=ANTENNA_HELP)
    _add_satellite_options(satellite)
    add_units_option(satellite, "deg")
    add_time_options(satellite, required=False)
    add_common_options(satellite)

    baseline = commands.add_parser(
        "baseline", help="both antennas of a baseline and the rotation delay",
        description="Feed rotation at both ends of a baseline and the rotation delay "
        "(antenna 2 minus antenna 1) at a frequency. The target is a natural source "
        "(--source or --ra/--dec) or a satellite (--tle or --sp3).",
        epilog=examples(EXAMPLES["baseline"]), formatter_class=argparse.RawDescriptionHelpFormatter)
    baseline.add_argument("antennas", metavar="ANTENNA", nargs=2, help=ANTENNA_HELP)
    baseline.add_argument("--frequency", required=True, metavar="FREQ",
                          help="observing frequency with a unit (1575.42MHz; plain: MHz)")
    add_natural_options(baseline)
    _add_satellite_options(baseline)
    add_units_option(baseline, "deg")
    add_time_options(baseline, required=False)
    add_common_options(baseline)


def _add_faraday(commands):
    faraday = commands.add_parser(
        "faraday", help="ionospheric Faraday rotation beside the feed rotation, per station",
        description="Per station and epoch: the elevation, the ionosphere's rotation measure "
        "RM along the line of sight (rad/m2), the Faraday rotation chi = RM lambda^2 at each "
        "--frequency (deg, positive from north through east), the feed rotation Phi and "
        "psi = Phi - chi (deg), the angle a correction removes. NaN below the horizon (or "
        "--min-elevation).",
        epilog=examples(EXAMPLES["faraday"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    faraday.add_argument("stations", metavar="STATION", nargs="+", help=ANTENNA_HELP)
    add_natural_options(faraday)
    add_time_options(faraday)
    group = faraday.add_argument_group("ionosphere and frequency")
    group.add_argument("--ionex", metavar="FILE", nargs="+",
                       help="IONEX global ionosphere maps, one file per UTC day (plain, .gz or "
                       ".Z), read through spinifex with the IGRF field (needs the extra "
                       "'ionosphere'); nothing is downloaded")
    group.add_argument("--rm-table", metavar="FILE",
                       help="your own rotation measures instead: a table (ECSV) with columns "
                       "time, rm (rad / m2) and optionally antenna (station names)")
    _add_ionex_height(group)
    group.add_argument("--frequency", metavar="FREQ", action="append", required=True,
                       help="observing frequency with a unit (1.4GHz, 150MHz; plain: MHz); "
                       "repeat it for several: one chi and one psi column each")
    add_common_options(faraday, polarization=False,
                       min_elevation="every value but the elevation NaN below this elevation "
                       "(degrees, or with a unit; from 0 to 90; default: the horizon)")


def _add_ionex_height(group):
    group.add_argument("--ionex-height", metavar="HEIGHT",
                       help="height of the ionosphere's thin shell for --ionex, with a unit "
                       "(350km; plain: km; default 450 km, the height the IONEX maps of "
                       "CODE, ESA, IGS and UPC state)")


def _add_demo(commands):
    demo = commands.add_parser(
        "demo", help="the paper's Section 4.1 simulation, on embedded data",
        description="GPS SVN 76 over the GNSS antenna DBR205 and the telescope FD-VLBA "
        "(Sec. 4.1 of the paper): prints a summary and writes feedrot_demo.ecsv and "
        "feedrot_demo.png (like Figs 10-11).",
        epilog=examples(EXAMPLES["demo"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    demo.add_argument("--output-dir", default=".", metavar="DIR",
                      help="where to write the table and figure (default: here); made if "
                      "it does not exist")
    demo.add_argument("--step", default="60s", metavar="DURATION",
                      help="sampling interval (default 60s)")
    demo.add_argument("--overwrite", action="store_true",
                      help="replace feedrot_demo.ecsv and feedrot_demo.png if they exist")


def _add_stations(commands):
    stations = commands.add_parser(
        "stations", help="list, search or show the station catalogue",
        description="List the station catalogue one station a line (name, networks, mount, "
        "focus, aliases), search it, or show one station in full with the source of each "
        "value. With -o, every column of the chosen stations in the format of the file's "
        "extension; piped, ECSV (or --format).",
        epilog=examples(EXAMPLES["stations"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    stations.add_argument("pattern", nargs="?", metavar="NAME",
                          help="a station (its name or an alias: shown in full), or a pattern "
                               "of names ('EF*', or a part of a name: 'yebes'), case-insensitive")
    stations.add_argument("--catalogue", metavar="FILE", help="an ECSV catalogue of one's own")
    stations.add_argument("--network", metavar="NAME",
                          help="only the stations of a network (VLBA, EVN, EHT...; "
                               "case-insensitive)")
    stations.add_argument("--mount", metavar="CODE",
                          help="only the stations with this geodetic mount code (AZEL, EQUA, "
                               "X-YE, X-YN, NASR, NASL, BWG, GNSS)")
    stations.add_argument("--near", metavar="LON,LAT",
                          help=f"the stations nearest a place (degrees east, north), nearest "
                               f"first, with their distance (km); {NEAR_LIMIT} unless --limit")
    stations.add_argument("--limit", metavar="N", type=int, help="at most N stations")
    stations.add_argument("--format", choices=FORMATS,
                          help="text (aligned, the default on a terminal), ecsv (the default "
                               "on a pipe) or csv")
    stations.add_argument("-o", "--output", metavar="FILE",
                          help="write every column of the chosen stations here, in the format "
                               "of its extension: " + ", ".join(TABLE_FORMATS))
    stations.add_argument("--overwrite", action="store_true",
                          help="replace an existing output file (never an input)")


def _add_coverage(commands):
    coverage = commands.add_parser(
        "coverage", help="the range of feed rotation of candidate polarization calibrators",
        description="For every station and source, the range of continuous feed rotation "
        "while the source is above the elevation limit, the time above it, and the sources "
        "ranked by their worst station (a polarization calibrator needs a wide range at "
        "every station). Names of networks expand to their stations where the catalogue "
        "knows them.",
        epilog=examples(EXAMPLES["coverage"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    coverage.add_argument("--stations", nargs="+", required=True, metavar="NAME",
                          help="station names of the catalogue (or names of networks; "
                               "NAME@NETWORK for a name two stations share, e.g. KP@EHT)")
    coverage.add_argument("--source", action="append", required=True, metavar="[NAME=]COORD",
                          help="a source's coordinates (ICRS), named or not, e.g. "
                          "'3C84=03h19m48.16s +41d30m42.1s' or '03h19m48.16s +41d30m42.1s'; "
                          "repeat for more")
    add_time_options(coverage)
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


def _add_files(commands):
    """``antennas`` and ``correct``: visibility files."""
    antennas = commands.add_parser(
        "antennas", help="the antennas of a visibility file, as read",
        description="The antennas of a visibility file (FITS-IDI, UVFITS, uvh5, Measurement "
        "Set, Miriad, SMA Mir) as read for the correction: number, name, ITRF position, "
        "mount label (in the file's convention), mount, focus, receptors and their angles, "
        "the station catalogue's station within 100 m with its mount and focus, and what "
        "keeps an antenna from being corrected as the file gives it (an orbiting antenna, a "
        "mount without a model, receptors that cannot be used, a mount that differs from "
        "the catalogue's).",
        epilog=examples(EXAMPLES["antennas"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    antennas.add_argument("file", metavar="FILE", help="a visibility file or directory")
    antennas.add_argument("--vertical", choices=("geodetic", "geocentric"), default="geodetic",
                          help="the local vertical (geocentric reproduces CASA)")
    antennas.add_argument("--mounts", choices=MOUNTS, default="file", help=MOUNTS_HELP)
    antennas.add_argument("-o", "--output", metavar="FILE",
                          help="write the table here (format of its extension) instead of "
                          "standard output")
    antennas.add_argument("--overwrite", action="store_true",
                          help="replace an existing output file")

    correct = commands.add_parser(
        "correct", help="remove (or apply) the feed rotation of a visibility file",
        description="Remove the feed rotation from every visibility (or, with --apply, "
        "apply it to a model): into a copy, FITS-IDI to FITS-IDI (a chunk at a time), a "
        "Measurement Set to .ms as a casacore copy corrected as --in-place would, and every "
        "format pyuvdata reads to the format of the output's extension (.uvfits, .uvh5, "
        ".ms; .fits is the input's kind), the input never modified; or a Measurement Set "
        "in place (--in-place), from one column into another (python-casacore), every other "
        "column left as it was. Data whose history says they were corrected already (by "
        "feedrot, AIPS CLCOR PANG or CASA applycal parang=True) are refused without --redo, "
        "and columns feedrot did not write without --overwrite-column.",
        epilog=examples(EXAMPLES["correct"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    correct.add_argument("input", metavar="INPUT", nargs="+",
                         help="a visibility file or directory; several (an archive) are "
                         "corrected one task per file, each file's outcome in one table at "
                         "the end, into -o OUTDIR/ or --in-place")
    correct.add_argument("-o", "--output", metavar="OUTPUT",
                         help="the corrected copy (not with --in-place); for several inputs, "
                         "or ending in /, a directory that takes each input's copy under its "
                         "own name (made if missing; copies an earlier run left there are "
                         "skipped unless --overwrite)")
    correct.add_argument("--in-place", action="store_true",
                         help="correct a Measurement Set in place: read --data-column, write "
                         "--column; an MSv4 processing set (.ps.zarr) is always corrected in "
                         "place, into the data group 'corrected' (--apply: 'model_corrupted')")
    correct.add_argument("--data-column", metavar="COLUMN",
                         help="Measurement Sets: the column read (default DATA; with --apply, "
                         "--column itself: a model corrupted in place)")
    correct.add_argument("--column", metavar="COLUMN",
                         help="Measurement Sets (--in-place, or -o OUTPUT.ms: a casacore copy "
                         "corrected in place): the visibility column written, created if "
                         "missing (default CORRECTED_DATA)")
    correct.add_argument("--data-group", metavar="NAME",
                         help="MSv4 processing sets: the data group read (default base; with "
                         "--apply, model), e.g. corrected for data CASA calibrated")
    correct.add_argument("--group", metavar="NAME",
                         help="MSv4 processing sets: the data group written, its variable "
                         "VISIBILITY_NAME (default corrected; with --apply, model_corrupted): "
                         "another name where the set has a corrected group already")
    correct.add_argument("--overwrite-column", action="store_true",
                         help="write into an existing column that feedrot did not write "
                         "(MODEL_DATA, a CORRECTED_DATA that CASA filled): its values are "
                         "replaced")
    correct.add_argument("--apply", action="store_true",
                         help="apply the feed rotation (corrupt a sky model) instead of "
                         "removing it")
    correct.add_argument("--feeds", metavar="R,L|X,Y",
                         help="receptors for antennas the file gives none (ATCA Miriad, old "
                         "UVFITS) or unusable ones (linear dipoles both at angle 0, as LWA and "
                         "PAPER Measurement Sets give): two letters with optional angles in "
                         "degrees, e.g. X:0,Y:90; without it, antennas without receptors take "
                         "the station catalogue's where it states them: for the station of "
                         "their name within 100 m, else for the pad within 5 m, else for every "
                         "station of the file's telescope alike (said in a warning); antennas "
                         "with unusable ones are refused, named")
    correct.add_argument("--mounts", choices=MOUNTS, default="file", help=MOUNTS_HELP)
    correct.add_argument("--redo", action="store_true",
                         help="correct data whose history says they were corrected in the "
                         "same direction already (by feedrot, by AIPS CLCOR PANG, by CASA "
                         "applycal parang=True), or recompute a column that holds this "
                         "correction already")
    correct.add_argument("--frame", default="apparent", choices=("apparent",) + CELESTIAL_FRAMES,
                         help="north of the corrected polarization angles: the pole of date "
                         "(default, as in Python, CASA and AIPS) or a catalogue frame such "
                         "as icrs")
    correct.add_argument("--convention", choices=tuple(CONVENTIONS), default="rigorous",
                         help="rigorous (default: the geodetic vertical and the Earth-fixed "
                         "pole) or casa (CASA's applycal(parang=True): the geocentric vertical "
                         "and the pole of date); --vertical and --pole replace its choices")
    correct.add_argument("--vertical", choices=("geodetic", "geocentric"),
                         help="the local vertical (default: the convention's; geocentric "
                         "reproduces CASA)")
    correct.add_argument("--pole", choices=POLES,
                         help="the pole of the parallactic angle: the Earth-fixed z axis with "
                         "polar motion or CASA's, without (default: the convention's)")
    ionosphere = correct.add_argument_group(
        "ionospheric Faraday rotation (removed, or with --apply applied, with the feed "
        "rotation: per antenna, epoch and channel)")
    ionosphere.add_argument("--ionex", metavar="FILE", nargs="+",
                            help="IONEX global ionosphere maps covering the observation, one "
                            "file per UTC day (plain, .gz or .Z), read through spinifex with "
                            "the IGRF field (needs the extra 'ionosphere'); nothing is "
                            "downloaded; the HISTORY names them")
    ionosphere.add_argument("--rm-table", metavar="FILE",
                            help="your own rotation measures instead: a table (ECSV) with "
                            "columns time, rm (rad / m2) and optionally antenna (the file's "
                            "antenna names; without it one series serves every antenna)")
    _add_ionex_height(ionosphere)
    correct.add_argument("--dask", metavar="SCHEDULER",
                         help="correct on the workers of this dask.distributed scheduler (its "
                         "address): the chunks of one Measurement Set or FITS-IDI file, one "
                         "task per file for several, a processing set's graph")
    correct.add_argument("--workers", type=int, metavar="N",
                         help="the same on a local dask cluster of N worker processes")
    correct.add_argument("--overwrite", action="store_true",
                         help="replace an existing output (never the input)")
    correct.add_argument("--quiet", action="store_true",
                         help="no progress bar, and no summary line on success")


def _add_rinex(commands):
    rinex = commands.add_parser(
        "rinex", help="a copy of a RINEX observation file with the phase wind-up removed",
        description="Write a copy of a RINEX observation file (2.11, 3.0x, 4.0x; plain, gzip "
        "or Hatanaka-compressed) with the carrier-phase wind-up of every satellite (GPS, "
        "GLONASS, Galileo, BeiDou, QZSS, NavIC; PRNs as G05, E11) subtracted from every "
        "carrier phase (L) of it: the RHCP wind-up in cycles, the same at every frequency "
        "(L_corrected = L - windup), continuous along each satellite's arc through loss-of-"
        "lock flags (a new arc only after a gap longer than --max-gap), the receiver turned "
        "by the header's ANTENNA: ZERODIR AZI (and by events that change it). Every other "
        "byte of the file is kept; two COMMENT lines say what was applied. Epochs up to one "
        "SP3 interval (900 s at most) beyond the SP3 files get extrapolated orbits; further "
        "ones, and satellites without an orbit or attitude, are left untouched and counted.",
        epilog=examples(EXAMPLES["rinex"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    rinex.add_argument("obs", metavar="OBS", help="the RINEX observation file")
    rinex.add_argument("--sp3", nargs="+", required=True, metavar="SP3",
                       help="SP3 orbit files covering the observations (days are joined)")
    rinex.add_argument("--orbex", nargs="+", metavar="OBX",
                       help="ORBEX attitude files (then --attitude orbex is the default)")
    rinex.add_argument("--attitude", choices=ATTITUDES,
                       help="transmitter attitude: nominal yaw steering (default without "
                       "--orbex), the yaw model of each satellite's block through noon and "
                       "midnight turns and shadows, or the ORBEX quaternions")
    rinex.add_argument("--metadata", metavar="SNX",
                       help="IGS satellite metadata SINEX file for --attitude model (default: "
                       "the shipped copy, release 2404)")
    rinex.add_argument("-o", "--output", required=True, metavar="OUT",
                       help="the corrected copy (.gz: gzip-compressed); never the input")
    rinex.add_argument("--max-gap", default="300s", metavar="DURATION",
                       help="a longer gap starts a new arc (default 300s; compared with a "
                       "tolerance of half the sampling interval)")
    rinex.add_argument("--points", type=int, metavar="N",
                       help="points of the orbit interpolation (default 10); fewer than the "
                       "orbits' sampling needs for 1e-4 cycle (7 at 15 min, 5 at 5 min for "
                       "GPS) are refused")
    rinex.add_argument("--position", metavar="X,Y,Z",
                       help="the antenna's ITRS position in metres (default APPROX POSITION "
                       "XYZ of the header)")
    rinex.add_argument("--form", choices=("beyerle", "wu"), default="beyerle",
                       help="wind-up form: Eq 30 crossed dipoles (default) or Eq 31 effective "
                       "dipoles (as RTKLIB)")
    rinex.add_argument("--table", metavar="FILE",
                       help="also write the wind-up removed, one row per epoch and satellite "
                       "(time, prn, windup), in the format of the extension")
    add_units_option(rinex, "cycles")
    rinex.add_argument("--overwrite", action="store_true",
                       help="replace existing outputs (never the input)")


def _add_samples(commands):
    samples = commands.add_parser(
        "samples", help="the sample files shipped with the package, and where they lie",
        description="List the sample files shipped with the package (orbits, attitude, "
        "observations, the station catalogue, visibility files) with what each is, print "
        "the path of one to give to another command, or copy one here to change it.",
        epilog=examples(EXAMPLES["samples"]),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    samples.add_argument("name", nargs="?", metavar="NAME", help="a sample file: its path")
    samples.add_argument("--copy", action="store_true",
                         help="copy the sample into the current directory (under its name) "
                         "and print the copy's path, to change it (correct it in place)")
    samples.add_argument("--overwrite", action="store_true",
                         help="with --copy, replace a file or folder of that name here")
    samples.set_defaults(run=run_samples, light=True)  # run without astropy


# The commands: each runs from its family's module, imported when it runs (and astropy
# with it) by astropy_feedrot.cli.running.run_command, which finds it here by its name
# (args.command, the subparsers' dest).

#: Each command's module of `astropy_feedrot.cli` and the function that runs it.
COMMANDS = {
    "natural": ("tables", "run_natural"),
    "satellite": ("tables", "run_satellite"),
    "baseline": ("tables", "run_baseline"),
    "faraday": ("faraday", "run_faraday"),
    "demo": ("demo", "run_demo"),
    "stations": ("stations", "run_stations"),
    "coverage": ("coverage", "run_coverage"),
    "antennas": ("data", "run_antennas"),
    "correct": ("data", "run_correct"),
    "rinex": ("rinex", "run_rinex"),
}
