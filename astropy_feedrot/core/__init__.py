# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The core: what every layer uses, and which imports nothing of the package.

The pure-numpy geometry kernel of the paper's equations (`kernel`), the
checks and coercions of a user's inputs (`inputs`), the package's warnings
and errors (`exceptions`), its configuration (`config`), the hands of
circular polarization (`polarization`), what is kept between calls
(`cache`), optional dependencies and their install hints (`extras`), output
files that are never lost (`outputs`) and progress reporting (`progress`).

May import: nothing of the package (``astropy_feedrot.data`` for data files
excepted).
"""
