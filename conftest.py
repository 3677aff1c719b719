# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Collection: the deprecated aliases of moved modules warn on import (their
tests import them on purpose, tests/test_deprecated_paths.py)."""

collect_ignore = [
    "astropy_feedrot/io/fitsidi.py",
    "astropy_feedrot/io/uvfits.py",
    "astropy_feedrot/io/antenna_tables.py",
    "astropy_feedrot/rows.py",
    "astropy_feedrot/uvdata.py",
    "astropy_feedrot/visibility_files.py",
]
