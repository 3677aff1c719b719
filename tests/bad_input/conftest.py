# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The bad-input suite, organised by public entry point: API, command line, readers."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
