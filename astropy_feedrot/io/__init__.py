# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Readers of GNSS orbit and attitude product files.

* `read_sp3` reads SP3 precise orbit files (SP3-c and SP3-d, also SP3-a/b):
  Earth-fixed satellite positions and clock corrections.
* `read_orbex` reads the attitude quaternions (``ATT`` records) of ORBEX
  files.
* `read_satellite_metadata` reads the IGS satellite metadata SINEX file
  (satellite blocks, PRN assignments).
* `read_tle` reads the element sets of two- and three-line element files;
  `check_tle_line` and `check_tle_pair` check element lines field by field.

Visibility files (FITS-IDI, UVFITS, Measurement Sets...) are read and
corrected by `astropy_feedrot.visibilities`.

Epochs come back as astropy `~astropy.time.Time`, converted from the file's
GNSS time system; files that break their format raise `FileFormatError`,
whose message names the file and the line.

May import: ``core``.

Examples
--------
>>> import io
>>> from astropy_feedrot.io import read_orbex
>>> text = '''%=ORBEX  0.09
... %%
... +FILE/DESCRIPTION
...  TIME_SYSTEM         GPS
...  COORD_SYSTEM        IGS20
...  FRAME_TYPE          ECEF
... -FILE/DESCRIPTION
... +EPHEMERIS/DATA
... ## 2023 01 25 00 00  0.000000000000   1
...  ATT G01              4  1.0000000000000000  0.0000000000000000  0.0000000000000000  0.0
... -EPHEMERIS/DATA
... %END_ORBEX
... '''
>>> read_orbex(io.StringIO(text)).satellites
('G01',)
"""

from ._common import TIME_SYSTEMS, FileFormatError, check_epoch, epochs_to_time
from .orbex import ORBEXData, read_orbex
from .sinex import SatelliteMetadata, read_satellite_metadata
from .sp3 import SP3Data, read_sp3
from .tle import TLE, check_tle_line, check_tle_pair, read_tle


__all__ = [
    "read_sp3",
    "read_orbex",
    "read_tle",
    "read_satellite_metadata",
    "SatelliteMetadata",
    "SP3Data",
    "ORBEXData",
    "TLE",
    "check_tle_line",
    "check_tle_pair",
    "FileFormatError",
    "TIME_SYSTEMS",
    "check_epoch",
    "epochs_to_time",
]
