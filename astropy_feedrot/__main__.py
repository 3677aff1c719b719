# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""``python -m astropy_feedrot``: the ``feedrot`` command line."""

import sys

from .cli import main

sys.exit(main())
