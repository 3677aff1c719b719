# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Deprecated: this module moved to `astropy_feedrot.visibilities.antenna_tables`.

Importing it warns (`DeprecationWarning`) and gives the same names; it goes
in the next release.
"""

import warnings

# The visibility files now live in one subpackage; this alias keeps the old
# import path working for one release.
from ..visibilities.antenna_tables import *  # noqa: F401,F403
from ..visibilities.antenna_tables import __all__  # noqa: F401

_OLD, _NEW = "astropy_feedrot.io.antenna_tables", "astropy_feedrot.visibilities.antenna_tables"
warnings.warn(f"{_OLD} moved to {_NEW}; the old import path goes in the next release",
              DeprecationWarning, stacklevel=2)
