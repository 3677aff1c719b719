# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""GNSS observation files: RINEX in, wind-up-corrected RINEX out.

* `RinexReader` streams the header and the epoch records of RINEX
  observation files (2.11, 3.0x, 4.0x; gzip and Hatanaka-compressed), and
  `RinexWriter` writes them back, changing nothing but the carrier phases a
  caller sets (`~astropy_feedrot.gnss.rinex`, `~astropy_feedrot.gnss.streams`).
* `correct_rinex` removes the carrier-phase wind-up of every satellite from
  every carrier phase of a file, given SP3 orbits and, optionally, ORBEX
  attitude (`~astropy_feedrot.gnss.correct`).

See :doc:`/gnss`.

May import: ``core``, ``io``, ``earth``, ``antennas``, ``transmitters``,
``ionosphere``, ``engine``, ``stations``, ``applied``.
"""

from .correct import ATTITUDES, RinexCorrection, correct_rinex, join_orbex, receiver_axes
from .rinex import EpochRecord, RinexReader, read_rinex_header
from .rinex_header import SYSTEMS, RinexHeader
from .streams import RinexWriter, comment_line

__all__ = [
    "correct_rinex",
    "RinexCorrection",
    "ATTITUDES",
    "receiver_axes",
    "join_orbex",
    "RinexReader",
    "RinexWriter",
    "RinexHeader",
    "EpochRecord",
    "read_rinex_header",
    "comment_line",
    "SYSTEMS",
]
