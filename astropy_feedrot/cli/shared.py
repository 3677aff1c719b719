# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""What the parser and the commands share: limits, choices, help texts and the one-line
form of a message.

Plain Python, imported by the parser (which starts without astropy) and by every
command's module; it imports nothing of the command line, so that no command imports
the parser and the parser reaches the commands through its table only
(`astropy_feedrot.cli.parser.COMMANDS`).
"""

__all__ = ["MAX_EPOCHS", "CELESTIAL_FRAMES", "ANTENNA_HELP", "SITE_FORMAT", "FORMATS",
           "PHASE_UNIT_NAMES", "NEAR_LIMIT", "MOUNTS_HELP", "UsageError", "one_line"]

#: Most epochs one command may compute (about 1.6 GB and half a minute for
#: a natural source; a satellite with the nominal attitude is ten times slower).
MAX_EPOCHS = 1_000_000


#: Frames accepted by ``--frame``: celestial frames, whose coordinates need
#: no observing time or place (unlike altaz or hadec).
CELESTIAL_FRAMES = ("icrs", "fk5", "fk4", "fk4noeterms", "galactic", "supergalactic",
                    "barycentricmeanecliptic", "barycentrictrueecliptic")


#: The help of an antenna argument.
ANTENNA_HELP = (
    "a station name of the catalogue (see 'feedrot stations'; case and punctuation do "
    "not matter; NAME@NETWORK for a name two stations share, e.g. KP@EHT) or a site "
    "'LAT,LON,HEIGHT' in degrees, degrees and metres with --mount and --focus"
)


#: How a site is written.
SITE_FORMAT = "LAT,LON,HEIGHT in degrees, degrees and metres, e.g. 40.5247,-3.0869,988"


#: What ``--format`` takes: the table on standard output
#: (`astropy_feedrot.cli.views.output_format`).
FORMATS = ("text", "ecsv", "csv")


#: What ``--units`` takes: a phase in cycles, radians or degrees
#: (`astropy_feedrot.cli.common.PHASE_UNITS` gives their units).
PHASE_UNIT_NAMES = ("cycles", "rad", "deg")


#: Stations ``feedrot stations --near`` lists unless ``--limit`` says otherwise.
NEAR_LIMIT = 10


#: The help of ``--mounts``.
MOUNTS_HELP = ("whose mount and focus an antenna within 100 m of a station of the catalogue "
               "takes where the two differ (said in a warning): the file's (default; many "
               "writers put MNTSTA 0, alt-az, for every antenna) or the catalogue's, which "
               "also gives its mount to an antenna whose MOUNT is empty or unknown")


class UsageError(Exception):
    """A command line that argparse cannot read."""


def one_line(text):
    """``text`` on one line: its lines joined with '; '.

    Examples
    --------
    >>> from astropy_feedrot.cli.shared import one_line
    >>> one_line("no such file\\n  try again")
    'no such file; try again'
    """
    return "; ".join(" ".join(line.split()) for line in str(text).splitlines() if line.strip())
