# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The foci of the station catalogue's ``focus`` column, by name.

Public as ``astropy_feedrot.stations.FOCUS_NAMES`` and
`astropy_feedrot.stations.focus_from_name`; the command line's ``--focus``
takes the same names.
"""

import functools

import numpy as np

from ..antennas.focus import (
    BeamWaveguideFocus,
    CassegrainFocus,
    GregorianFocus,
    MirrorTrain,
    NasmythFocus,
    PrimeFocus,
)

__all__ = []  # public through astropy_feedrot.stations.catalogue, which documents them


#: Values of the ``focus`` column and the focus each stands for.
FOCUS_NAMES = {
    "": None,
    "prime": PrimeFocus,
    "cassegrain": CassegrainFocus,
    "gregorian": GregorianFocus,
    "nasmyth-right": functools.partial(NasmythFocus, "right"),
    "nasmyth-left": functools.partial(NasmythFocus, "left"),
    "bwg-right": functools.partial(BeamWaveguideFocus, "right"),
    "bwg-left": functools.partial(BeamWaveguideFocus, "left"),
    "yebes40m-S": functools.partial(MirrorTrain.yebes40m, "S"),
    "yebes40m-C": functools.partial(MirrorTrain.yebes40m, "C"),
    "yebes40m-X": functools.partial(MirrorTrain.yebes40m, "X"),
    "wark30m": MirrorTrain.wark30m,
}


def focus_from_name(value, where="focus"):
    """The focus named by a value of the catalogue's ``focus`` column.

    Parameters
    ----------
    value : str or None
        One of `FOCUS_NAMES` (case-insensitive); empty or None for none.
    where : str, optional
        What to name in an error message.

    Returns
    -------
    `~astropy_feedrot.antennas.focus.Focus` or None

    Raises
    ------
    ValueError
        For an unknown name (listing the known ones).

    Examples
    --------
    >>> from astropy_feedrot.stations.catalogue import focus_from_name
    >>> focus_from_name("nasmyth-right")
    NasmythFocus(handedness='right')
    """
    value = "" if value is None or np.ma.is_masked(value) else str(value).strip()
    for known, make in FOCUS_NAMES.items():
        if value.lower() == known.lower():
            return None if make is None else make()
    choices = ", ".join(k for k in FOCUS_NAMES if k)
    raise ValueError(f"{where}: unknown focus {value!r}; expected one of {choices}, or empty")
