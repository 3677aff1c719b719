# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The names that options of the package take, as plain constants.

The modules that act on a choice import it from here, and so does the
command line's parser (`astropy_feedrot.cli.parser`), which is built without
importing astropy or numpy: ``feedrot --help`` starts in a tenth of a
second. This module imports nothing.

Examples
--------
>>> from astropy_feedrot.core.choices import CONVENTIONS
>>> CONVENTIONS["casa"]
('geocentric', 'casa')
"""

__all__ = ["POLES", "CONVENTIONS", "MOUNTS", "ATTITUDES", "FOCI"]

#: The poles offered: ``'itrs'`` (Earth-fixed z, with polar motion; default)
#: and ``'casa'`` (no polar motion, as CASA); see
#: `astropy_feedrot.visibilities.poles.pole_context`.
POLES = ("itrs", "casa")

#: The conventions of a correction, as the vertical and the pole they choose:
#: ``'rigorous'`` (the package's: the geodetic vertical, the Earth-fixed pole;
#: the default) and ``'casa'`` (CASA's ``applycal(parang=True)``: the
#: geocentric vertical, no polar motion). Circular receptors turn with the
#: first receptor's angle in both, as in CASA.
CONVENTIONS = {"rigorous": ("geodetic", "itrs"), "casa": ("geocentric", "casa")}

#: Whose mounts and foci a correction of a visibility file uses: the file's
#: (``'file'``, the default) or, for antennas within
#: `~astropy_feedrot.visibilities.catalogue.CATALOGUE_TOLERANCE` of a station,
#: the station catalogue's (``'catalogue'``); see
#: `astropy_feedrot.visibilities.catalogue.catalogue_mounts`.
MOUNTS = ("file", "catalogue")

#: The transmitter attitudes `astropy_feedrot.gnss.correct_rinex` offers.
ATTITUDES = ("nominal", "model", "orbex")

#: The names of the foci of the station catalogue's ``focus`` column (and of
#: ``feedrot --focus``); `astropy_feedrot.stations.FOCUS_NAMES` gives the focus
#: each stands for, the empty name for none.
FOCI = ("prime", "cassegrain", "gregorian", "nasmyth-right", "nasmyth-left", "bwg-right",
        "bwg-left", "yebes40m-S", "yebes40m-C", "yebes40m-X", "wark30m")
