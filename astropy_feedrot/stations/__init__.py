# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The station catalogue and the mount labels of other software.

`catalogue` reads the catalogue of stations that ships with the package and
makes `~astropy_feedrot.Antenna` objects from it; `focus_names` names the
foci of its ``focus`` column; `labels` turns the mount labels of other
software (FITS-IDI ``MNTSTA`` codes, Measurement Set ``MOUNT`` strings,
VEX and CASA names) into this package's mounts and foci and back, with
the tables and their sources in `label_tables`.

Everything public of `catalogue` is importable from here.

May import: ``core``, ``io``, ``earth``, ``antennas``, ``transmitters``,
``ionosphere``, ``engine``.
"""

from .catalogue import (
    FOCUS_NAMES,
    MAX_VELOCITY,
    StationCatalogue,
    default_catalogue,
    focus_from_name,
    get_antenna,
    get_network,
    networks,
    read_catalogue,
)

__all__ = ["MAX_VELOCITY", "StationCatalogue", "default_catalogue", "read_catalogue",
           "get_antenna", "get_network", "networks", "focus_from_name", "FOCUS_NAMES"]
