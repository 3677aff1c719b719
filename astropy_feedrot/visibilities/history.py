# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The one history mark of corrected visibility data, in every format.

Each correction adds one line to the data's history (the ``HISTORY`` cards
of a FITS-IDI primary header, pyuvdata's ``history``, a row of a
Measurement Set's ``HISTORY`` table) that begins with `HISTORY_MARK` or
`APPLY_MARK`. A second correction in the same direction would add the
rotation twice and is refused unless asked for; the opposite direction
undoes the first and is allowed.
"""

from .. import __version__
from ..correction import DIRECTIONS

__all__ = ["HISTORY_MARK", "APPLY_MARK", "DIRECTIONS", "history_entry", "last_direction",
           "check_history", "check_direction"]

#: The first words of the history line of data whose feed rotation was removed.
HISTORY_MARK = "Feed rotation removed by astropy_feedrot"

#: The first words of the history line of data whose feed rotation was applied.
APPLY_MARK = "Feed rotation applied by astropy_feedrot"

_MARKS = {"remove": HISTORY_MARK, "apply": APPLY_MARK}

# The words of releases before 0.2 (pyuvdata data; FITS-IDI wrote
# HISTORY_MARK in capitals, which the comparison without case finds).
_OLD_MARKS = {"remove": ("Feed rotation removed with astropy_feedrot",)}

_DONE = {"remove": "removed", "apply": "applied"}


def _squeeze(text):
    """Text without white space and case: FITS cards wrap lines anywhere."""
    return "".join(str(text).split()).casefold()


def check_direction(direction):
    """``direction`` if it is ``'remove'`` or ``'apply'``, else ValueError.

    Parameters
    ----------
    direction : str
        The direction asked for.

    Returns
    -------
    str

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import check_direction
    >>> check_direction("apply")
    'apply'
    """
    if direction not in DIRECTIONS:
        raise ValueError(f"direction must be one of {DIRECTIONS} (remove the feed rotation "
                         f"from measured data, or apply it to a model), got {direction!r}")
    return direction


def history_entry(direction, what, *, frame, vertical):
    """The history line of a correction.

    Parameters
    ----------
    direction : {'remove', 'apply'}
        What was done.
    what : str
        To which data (e.g. ``'UV_DATA FLUX'`` or ``'DATA -> CORRECTED_DATA'``).
    frame, vertical : str or frame
        The options of the correction.

    Returns
    -------
    str

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import history_entry
    >>> history_entry("remove", "DATA -> CORRECTED_DATA", frame="icrs",
    ...               vertical="geodetic").startswith("Feed rotation removed by astropy_feedrot")
    True
    """
    frame = frame if isinstance(frame, str) else getattr(frame, "name", type(frame).__name__)
    receptors = ("receptors fixed on the sky (R, L; X north, Y east)" if direction == "remove"
                 else "sky-fixed receptors turned to the antennas' receptors")
    return (f"{_MARKS[check_direction(direction)]} {__version__}: {what}, {receptors} "
            f"(frame={frame}, vertical={vertical})")


def last_direction(text, what=None):
    """The direction of the last correction a history records, or None.

    Parameters
    ----------
    text : str
        The history.
    what : str, optional
        Only lines that name this (e.g. the output column of a
        Measurement Set) count.

    Returns
    -------
    {'remove', 'apply'} or None

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import last_direction
    >>> last_direction("Feed rotation removed by astropy_feedrot 0.2: x. "
    ...                "Feed rotation applied by astropy_feedrot 0.2: x.")
    'apply'
    >>> last_direction("FEED ROTATION REMOVED BY ASTROPY_FEEDROT 0.1")
    'remove'
    """
    lines = [text] if what is None else [line for line in str(text).splitlines()
                                         if _squeeze(what) in _squeeze(line)]
    best, at = None, (-1, -1)
    for number, line in enumerate(lines):
        squeezed = _squeeze(line)
        for direction in DIRECTIONS:
            for mark in (_MARKS[direction],) + _OLD_MARKS.get(direction, ()):
                found = squeezed.rfind(_squeeze(mark))
                if found >= 0 and (number, found) > at:
                    best, at = direction, (number, found)
    return best


def check_history(text, direction, where, *, redo=False, what=None):
    """Refuse a correction that the history says was made already.

    Parameters
    ----------
    text : str
        The history of the data.
    direction : {'remove', 'apply'}
        The correction asked for.
    where : str
        The data, for the message.
    redo : bool, optional
        Allow it all the same.
    what : str, optional
        As in `last_direction`.

    Raises
    ------
    ValueError
        If the last correction recorded was in the same direction and
        ``redo`` is False.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import check_history
    >>> check_history("Feed rotation applied by astropy_feedrot", "remove", "x.ms")
    >>> check_history("Feed rotation removed by astropy_feedrot", "remove", "x.ms")
    Traceback (most recent call last):
    ...
    ValueError: x.ms: the history says the feed rotation was removed already ...
    """
    direction = check_direction(direction)
    if not redo and last_direction(text, what) == direction:
        verb = "removing" if direction == "remove" else "applying"
        effect = "add it back" if direction == "remove" else "turn the receptors twice"
        raise ValueError(f"{where}: the history says the feed rotation was {_DONE[direction]} "
                         f"already ({_MARKS[direction]!r}); {verb} it again would {effect}: "
                         "pass redo=True (--redo) if that is what you want")
