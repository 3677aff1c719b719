# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Deprecated: this module moved to `astropy_feedrot.visibilities.files`.

Importing it warns (`DeprecationWarning`) and gives the same names; it goes
in the next release.
"""

import warnings

# The visibility files now live in one subpackage; this alias keeps the old
# import path working for one release.
from .visibilities.files import *  # noqa: F401,F403
from .visibilities.files import __all__  # noqa: F401

_OLD, _NEW = "astropy_feedrot.visibility_files", "astropy_feedrot.visibilities.files"
warnings.warn(f"{_OLD} moved to {_NEW}; the old import path goes in the next release",
              DeprecationWarning, stacklevel=2)
