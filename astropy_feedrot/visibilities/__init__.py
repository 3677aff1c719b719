# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Visibility data: files of every kind, their antennas, and the feed rotation
removed from (or applied to) their visibilities.

One module per format, on shared steps:

* `~astropy_feedrot.visibilities.kinds`: the kinds of file (`FILE_KINDS`,
  `file_kind`);
* `~astropy_feedrot.visibilities.rows`: rows (time, antenna 1, antenna 2,
  source) to the feed rotation of both antennas (`feed_rotation_rows`);
* `~astropy_feedrot.visibilities.receptors`: the receptor step, from feed
  rotation to the sky position angle of each receptor
  (`receptor_position_angles`), receptors given by the user
  (`with_receptors`, `parse_feeds`);
* `~astropy_feedrot.visibilities.catalogue`: receptors from the station
  catalogue for antennas a file gives none, matched by name or by position
  (`catalogue_receptors`), and the file's mounts against the catalogue's
  (`catalogue_mounts`, `catalogue_stations`);
* `~astropy_feedrot.visibilities.unusable`: antennas a file describes in a
  way that cannot be corrected (orbiting, a mount without a model,
  receptors that are not a pair), kept as `UnusableAntenna`;
* `~astropy_feedrot.visibilities.history`: the one history mark
  (`HISTORY_MARK`, `APPLY_MARK`), and the records of AIPS and CASA of the
  same correction, refused unless asked for (`CorrectionRefused`);
* formats: `~astropy_feedrot.visibilities.fitsidi` (FITS-IDI, astropy,
  in chunks), `~astropy_feedrot.visibilities.uvfits` (UVFITS antenna
  tables), `~astropy_feedrot.visibilities.ms` (Measurement Sets in place,
  python-casacore; `~astropy_feedrot.visibilities.ms_tables`: the columns
  it may write, and casacore copies; module ``ms_antennas``: its antennas
  and ``FEED`` receptors), `~astropy_feedrot.visibilities.uvdata` (everything
  pyuvdata reads); `~astropy_feedrot.visibilities.antenna_tables` holds the
  antenna tables FITS-IDI and UVFITS share;
* `~astropy_feedrot.visibilities.msv4`: MSv4 processing sets (xradio),
  corrected lazily into a new data group (`correct_processing_set`);
* `~astropy_feedrot.visibilities.resolve`: the antennas of a file resolved
  once, the same way for every format (aperture arrays, the catalogue's
  mounts, the receptors given);
* `~astropy_feedrot.visibilities.faraday`: the ionospheric Faraday rotation
  in a correction (the RM of each row's antennas, lambda^2 of each format's
  channels), beside the feed rotation;
* `~astropy_feedrot.visibilities.files`: any file, by its kind
  (`read_antennas`, `antenna_table`, `correct_file`), as ``feedrot
  antennas`` and ``feedrot correct`` use them;
* `~astropy_feedrot.visibilities.archives`: many files, one task per file
  on dask.distributed, each file's outcome in one table (`correct_files`).

pyuvdata and python-casacore are optional and imported on first use.

May import: ``core``, ``io``, ``earth``, ``antennas``, ``transmitters``,
``ionosphere``, ``engine``, ``stations``, ``applied``.
"""

from .archives import OUTCOMES, correct_files
from .antenna_tables import FITSFormatError, WritingProgram, open_fits, writing_program
from .catalogue import (
    ARRAY_TOLERANCE,
    CATALOGUE_TOLERANCE,
    MOUNTS,
    PAD_TOLERANCE,
    StationMatch,
    catalogue_mounts,
    catalogue_receptors,
    catalogue_stations,
)
from .correction import Correction
from .files import antenna_table, correct_file, read_antennas
from .fitsidi import STOKES_CODES, correct_fitsidi, fitsidi_antennas
from .history import APPLY_MARK, HISTORY_MARK, CorrectionRefused
from .kinds import (
    FILE_KINDS,
    FITSIDI_EXTENSIONS,
    OUTPUT_EXTENSIONS,
    check_header_cards,
    check_output_format,
    existing_path,
    file_kind,
)
from .ms import CORR_TYPES, MSError, correct_ms
from .ms_antennas import ms_antennas
from .msv4 import MSv4Error, correct_processing_set, processing_set_antennas
from .poles import POLES, pole_context
from .receptors import (
    ReceptorAngleTable,
    check_receptors,
    parse_feeds,
    receptor_position_angles,
    warn_unusual_angles,
    with_receptors,
)
from .rows import FRAMES, distinct_epochs, feed_rotation_rows, frame_position_angle
from .unusable import UnusableAntenna
from .uvdata import antennas_from_uvdata, correct_uvdata, feed_rotation_uvdata
from .uvdata_files import PYUVDATA_TYPES, WRITERS, read_uvdata, write_uvdata
from .uvfits import uvfits_antennas

__all__ = [
    "FILE_KINDS",
    "file_kind",
    "existing_path",
    "check_header_cards",
    "read_antennas",
    "antenna_table",
    "Correction",
    "correct_file",
    "correct_files",
    "OUTCOMES",
    "check_output_format",
    "OUTPUT_EXTENSIONS",
    "FITSIDI_EXTENSIONS",
    "feed_rotation_rows",
    "frame_position_angle",
    "distinct_epochs",
    "FRAMES",
    "POLES",
    "pole_context",
    "receptor_position_angles",
    "ReceptorAngleTable",
    "check_receptors",
    "with_receptors",
    "warn_unusual_angles",
    "parse_feeds",
    "catalogue_receptors",
    "catalogue_mounts",
    "catalogue_stations",
    "StationMatch",
    "MOUNTS",
    "UnusableAntenna",
    "CATALOGUE_TOLERANCE",
    "PAD_TOLERANCE",
    "ARRAY_TOLERANCE",
    "HISTORY_MARK",
    "APPLY_MARK",
    "CorrectionRefused",
    "fitsidi_antennas",
    "correct_fitsidi",
    "STOKES_CODES",
    "uvfits_antennas",
    "FITSFormatError",
    "WritingProgram",
    "writing_program",
    "open_fits",
    "ms_antennas",
    "correct_ms",
    "CORR_TYPES",
    "MSError",
    "correct_processing_set",
    "processing_set_antennas",
    "MSv4Error",
    "antennas_from_uvdata",
    "feed_rotation_uvdata",
    "correct_uvdata",
    "read_uvdata",
    "write_uvdata",
    "WRITERS",
    "PYUVDATA_TYPES",
]
