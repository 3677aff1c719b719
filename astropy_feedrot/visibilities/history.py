# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""What the history of visibility data says was done to the feed rotation.

Each correction by this package adds one line to the data's history (the
``HISTORY`` cards of a FITS-IDI primary header, pyuvdata's ``history``, a
row of a Measurement Set's ``HISTORY`` table) that begins with
`HISTORY_MARK` or `APPLY_MARK`. Other programs leave their own records of
the same correction, read here too:

* AIPS: ``CLCOR`` with ``OPCODE = 'PANG'`` (the parallactic angle correction
  put into a CL table, ``CLPARM(1) > 0``, or taken out, ``CLPARM(1) < 0``;
  the procedure ``VLBAPANG`` runs it), found in the ``HISTORY`` cards of
  UVFITS and FITS-IDI files, with the ``SPLIT`` that applied the CL table to
  the visibilities when there is one (`aips_records`);
* CASA: ``applycal`` with ``parang = True`` in a Measurement Set's
  ``HISTORY`` table (read by `~astropy_feedrot.visibilities.correct_ms`).

A second correction in the same direction would turn the receptors twice
and is refused unless asked for (`CorrectionRefused`); the opposite
direction undoes the first and is allowed.
"""

import re

from ..applied.correction import DIRECTIONS
from ..core.version import version as __version__

__all__ = ["HISTORY_MARK", "APPLY_MARK", "DIRECTIONS", "history_entry", "last_direction",
           "check_history", "check_direction", "CorrectionRefused", "AlreadyCorrected",
           "OPTION_WORDS", "aips_records", "history_records", "compose", "refusal", "ColumnRecord",
           "ms_column_history"]

#: The first words of the history line of data whose feed rotation was removed.
HISTORY_MARK = "Feed rotation removed by astropy_feedrot"

#: The first words of the history line of data whose feed rotation was applied.
APPLY_MARK = "Feed rotation applied by astropy_feedrot"

_MARKS = {"remove": HISTORY_MARK, "apply": APPLY_MARK}

# The words of releases before 0.2 (pyuvdata data; FITS-IDI wrote
# HISTORY_MARK in capitals, which the comparison without case finds).
_OLD_MARKS = {"remove": ("Feed rotation removed with astropy_feedrot",)}

_DONE = {"remove": "removed", "apply": "applied"}

#: The options a refusal names: ``{placeholder: (the API's words, the command line's)}``.
OPTION_WORDS = {
    "redo": ("redo=True", "--redo"),
    "overwrite_column": ("overwrite_column=True", "--overwrite-column"),
    "corrected_column": ("corrected_column=", "--column"),
    "data_column": ("data_column=", "--data-column"),
}

# AIPS: CLCOR ... OPCODE = 'PANG', then CLPARM(1) = value / comment (AIPS writes
# "Parallactic angle correction APPLIED" for CLPARM(1) > 0).
_PANG = re.compile(r"(?-i:(?P<task>[A-Z][A-Z0-9]{1,7}))\s+OPCODE\s*=\s*'\s*PANG\s*'", re.IGNORECASE)
_CLPARM = re.compile(r"CLPARM\s*\(\s*1\s*\)\s*=\s*(?P<value>[-+]?(?:\d+\.?\d*|\.\d+)"
                     r"(?:[EeDd][-+]?\d+)?)(?P<comment>[^\n]{0,80})", re.IGNORECASE)
_VLBAPANG = re.compile(r"\bVLBAPANG\b", re.IGNORECASE)
_APPLIED_BY = re.compile(r"(?P<task>SPLIT|SPLAT)\b[^\n]{0,60}?"
                         r"(?:GAINUSE|DOCAL)\s*=\s*(?P<value>[-+]?\d+)", re.IGNORECASE)


class CorrectionRefused(ValueError):
    """A correction refused unless an option says otherwise: one line saying why, naming
    the option as the caller spells it.

    ``str(error)`` names the options in the API's words (``redo=True``);
    `command_line` gives the same message in the command line's
    (``--redo``), `OPTION_WORDS`.

    Parameters
    ----------
    template : str
        The message, with ``<<redo>>``, ``<<overwrite_column>>``... where
        the options go.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import CorrectionRefused
    >>> error = CorrectionRefused("x.ms: done already; pass <<redo>> to do it again")
    >>> str(error)
    'x.ms: done already; pass redo=True to do it again'
    >>> error.command_line()
    'x.ms: done already; pass --redo to do it again'
    """

    def __init__(self, template):
        self.template = str(template)
        super().__init__(self._words(0))

    def _words(self, which):
        text = self.template
        for name, words in OPTION_WORDS.items():
            text = text.replace(f"<<{name}>>", words[which])
        return text

    def command_line(self):
        """The message in the words of the command line."""
        return self._words(1)

    def __reduce__(self):
        return type(self), (self.template,)


class AlreadyCorrected(CorrectionRefused):
    """The refusal of a correction whose output holds exactly this correction already
    (this package's, in the same direction, from the same data): running it again would
    only compute it anew. A run over many files skips such a file
    (`~astropy_feedrot.visibilities.correct_files`).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import AlreadyCorrected, CorrectionRefused
    >>> issubclass(AlreadyCorrected, CorrectionRefused)
    True
    """


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


def compose(state, direction):
    """The state of data in ``state`` (None, 'remove', 'apply') after a correction.

    Parameters
    ----------
    state : {None, 'remove', 'apply'}
        What was done to the data before (None: nothing, or undone).
    direction : {'remove', 'apply'}
        The correction made.

    Returns
    -------
    {None, 'remove', 'apply'}
        One direction undoes the other; twice the same stays that direction
        (the history says no more).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import compose
    >>> compose(None, "remove"), compose("remove", "apply")
    ('remove', None)
    """
    return None if state is not None and state != direction else direction


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


def _own_records(text):
    """(position, direction, record) of this package's marks in ``text``."""
    squeezed = _squeeze(text)
    found = []
    for direction in DIRECTIONS:
        for mark in (_MARKS[direction],) + _OLD_MARKS.get(direction, ()):
            key = _squeeze(mark)
            at = squeezed.find(key)
            while at >= 0:
                found.append((at, direction, f"{mark!r}"))
                at = squeezed.find(key, at + 1)
    return found


def aips_records(text):
    """The parallactic angle corrections that AIPS recorded in a history.

    Parameters
    ----------
    text : str
        The ``HISTORY`` cards of a UVFITS or FITS-IDI file, one a line (or
        run together).

    Returns
    -------
    list of (int, str, str)
        ``(position in text, direction, record)`` in order: ``'remove'``
        for ``OPCODE = 'PANG'`` with ``CLPARM(1) > 0`` (or without a value
        read) and ``VLBAPANG``, ``'apply'`` for ``CLPARM(1) < 0`` (AIPS
        takes the correction out again); ``record`` quotes the cards, and
        names the ``SPLIT`` (or other task applying a CL table) that
        followed.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import aips_records
    >>> cards = ("CLCOR   OPCODE = 'PANG' / Operation code\\n"
    ...          "CLCOR   CLPARM(1)=  1. / Parallactic angle correction APPLIED\\n"
    ...          "SPLIT GAINUSE =  6 / CL table")
    >>> [(direction, record) for _, direction, record in aips_records(cards)]
    ... # doctest: +NORMALIZE_WHITESPACE
    [('remove', "AIPS CLCOR OPCODE = 'PANG', CLPARM(1) = 1. (Parallactic angle correction
      APPLIED), applied to the visibilities by SPLIT GAINUSE = 6")]
    """
    text = str(text)
    found = []
    for match in _PANG.finditer(text):
        task = match.group("task").upper()
        parameter = _CLPARM.search(text, match.end(), match.end() + 300)
        record = f"AIPS {task} OPCODE = 'PANG'"
        direction = "remove"
        if parameter is not None:
            value = float(parameter.group("value").upper().replace("D", "E"))
            comment = parameter.group("comment").strip(" /")
            if value < 0 or "REMOVED" in comment.upper():
                direction = "apply"
            record += f", CLPARM(1) = {parameter.group('value')}"
            if comment:
                record += f" ({comment})"
        found.append((match.start(), direction, record))
    for match in _VLBAPANG.finditer(text):
        found.append((match.start(), "remove", "AIPS VLBAPANG"))
    found.sort()
    out = []
    for k, (at, direction, record) in enumerate(found):
        stop = found[k + 1][0] if k + 1 < len(found) else len(text)
        applied = [m for m in _APPLIED_BY.finditer(text, at, stop) if int(m.group("value")) > 0]
        if applied:
            m = applied[0]
            record += (f", applied to the visibilities by {m.group('task').upper()} "
                       f"{' '.join(m.group(0)[len(m.group('task')):].split())}")
        out.append((at, direction, record))
    return out


def history_records(text):
    """Every record of a feed rotation correction in a history, in order.

    Parameters
    ----------
    text : str
        The history.

    Returns
    -------
    list of (str, str)
        ``(direction, record)``: this package's marks and AIPS's records
        (`aips_records`).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import history_records
    >>> history_records("Feed rotation removed by astropy_feedrot 0.2")
    [('remove', "'Feed rotation removed by astropy_feedrot'")]
    """
    text = str(text)
    # Positions of the package's marks are in the text without spaces; map them back.
    keep = [k for k, c in enumerate(text) if not c.isspace()]
    own = [(keep[at] if at < len(keep) else len(text), d, r) for at, d, r in _own_records(text)]
    return [(d, r) for _, d, r in sorted(own + aips_records(text))]


def last_direction(text, what=None):
    """The direction of the last correction a history records, or None.

    Parameters
    ----------
    text : str
        The history.
    what : str, optional
        Only lines that name this (e.g. the output column of a
        Measurement Set) count; only the package's own marks are read then.

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
    if what is None:
        records = history_records(text)
        return records[-1][0] if records else None
    lines = [line for line in str(text).splitlines() if _squeeze(what) in _squeeze(line)]
    best, at = None, (-1, -1)
    for number, line in enumerate(lines):
        for found, direction, _ in _own_records(line):
            if (number, found) > at:
                best, at = direction, (number, found)
    return best


def refusal(where, direction, record, *, recompute=None):
    """The refusal of a correction the history says was made (`CorrectionRefused`).

    Parameters
    ----------
    where : str
        The data, for the message.
    direction : {'remove', 'apply'}
        The correction asked for, made already.
    record : str
        The record found.
    recompute : str, optional
        The correction would only write again what its output holds (a
        Measurement Set's ``DATA -> CORRECTED_DATA`` run again), rather than
        correct corrected data a second time: says so (e.g.
        ``'CORRECTED_DATA holds DATA'``).

    Returns
    -------
    CorrectionRefused
        An `AlreadyCorrected` with ``recompute``.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import refusal
    >>> str(refusal("x.uvfits", "remove", "AIPS CLCOR OPCODE = 'PANG'"))  # doctest: +ELLIPSIS
    "x.uvfits: the feed rotation was removed already (the history records AIPS CLCOR ..."
    >>> print(refusal("x.ms", "remove", "a mark", recompute="CORRECTED_DATA holds DATA"))
    ... # doctest: +NORMALIZE_WHITESPACE
    x.ms: CORRECTED_DATA holds DATA with the feed rotation removed already (the history
    records a mark); the same correction again would only compute it anew: pass redo=True
    to do so
    """
    done = _DONE[check_direction(direction)]
    if recompute:
        return AlreadyCorrected(
            f"{where}: {recompute} with the feed rotation {done} already (the history "
            f"records {record}); the same correction again would only compute it anew: "
            "pass <<redo>> to do so")
    verb = direction if direction == "apply" else "remove"
    return CorrectionRefused(
        f"{where}: the feed rotation was {done} already (the history records {record}); "
        f"correcting again would {verb} it twice: pass <<redo>> to correct all the same")


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
    CorrectionRefused
        If the last correction recorded (this package's, or AIPS's
        parallactic angle correction, `aips_records`) was in the same
        direction and ``redo`` is False.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import check_history
    >>> check_history("Feed rotation applied by astropy_feedrot", "remove", "x.ms")
    >>> check_history("Feed rotation removed by astropy_feedrot", "remove", "x.ms")
    Traceback (most recent call last):
    ...
    astropy_feedrot...CorrectionRefused: x.ms: the feed rotation was removed already ...
    """
    direction = check_direction(direction)
    if redo:
        return
    if what is None:
        records = history_records(text)
        if records and records[-1][0] == direction:
            raise refusal(where, direction, records[-1][1])
    elif last_direction(text, what) == direction:
        raise refusal(where, direction, repr(_MARKS[direction]))


# --- Measurement Sets: what each column holds -------------------------------------------

# CASA tasks that write a whole new Measurement Set from one of its columns.
_CASA_COPIES = ("split", "mstransform", "cvel", "cvel2", "partition", "oldsplit")
_PARAMETER = re.compile(r"^\s*(?P<name>\w+)\s*=\s*(?P<value>.*?)\s*$")
_WHAT = re.compile(r"astropy_feedrot\s+\S+\s*:\s*(?P<source>[^\s,]+)\s*->\s*"
                   r"(?P<target>[^\s,]+)")


class ColumnRecord:
    """What a Measurement Set's ``HISTORY`` says one column holds.

    Attributes
    ----------
    state : {None, 'remove', 'apply'}
        The feed rotation correction its values carry.
    record : str or None
        The record that says so (for messages).
    writer : str or None
        Who wrote the column last: ``'astropy_feedrot'``, ``'CASA applycal'``...
        (None: the history does not say).
    source, direction : str or None
        For a column this package wrote: its input column and direction.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import ColumnRecord
    >>> ColumnRecord().state is None
    True
    """

    def __init__(self, state=None, record=None, writer=None, source=None, direction=None):
        self.state, self.record, self.writer = state, record, writer
        self.source, self.direction = source, direction

    def __repr__(self):
        return (f"ColumnRecord(state={self.state!r}, record={self.record!r}, "
                f"writer={self.writer!r})")


def _casa_task(name, parameters, columns):
    """Apply one CASA task's record to ``columns``."""
    data = columns.get("DATA", ColumnRecord())
    if name == "applycal":
        parang = parameters.get("parang", "False").strip("'\"") == "True"
        if parang:
            columns["CORRECTED_DATA"] = ColumnRecord(
                compose(data.state, "remove"), "CASA applycal(parang=True)", "CASA applycal")
        else:
            columns["CORRECTED_DATA"] = ColumnRecord(data.state, data.record, "CASA applycal")
    elif name == "clearcal":
        columns["CORRECTED_DATA"] = ColumnRecord(data.state, data.record, "CASA clearcal")
        columns["MODEL_DATA"] = ColumnRecord(None, None, "CASA clearcal")
    elif name in ("setjy", "ft", "delmod"):
        columns["MODEL_DATA"] = ColumnRecord(None, None, f"CASA {name}")
    elif name in _CASA_COPIES and "datacolumn" in parameters:
        chosen = parameters["datacolumn"].strip("'\" ").lower()
        source = {"corrected": "CORRECTED_DATA", "model": "MODEL_DATA",
                  "data": "DATA"}.get(chosen)
        if source is not None:
            moved = columns.get(source, ColumnRecord())
            columns.clear()
            columns["DATA"] = ColumnRecord(moved.state, moved.record and
                                           f"{moved.record}, then CASA {name}(datacolumn="
                                           f"{chosen!r})", None)


def ms_column_history(rows):
    """What each column of a Measurement Set holds, from its ``HISTORY`` table.

    Parameters
    ----------
    rows : iterable of (str, str, str)
        ``(ORIGIN, APPLICATION, MESSAGE)`` of each row, in order.

    Returns
    -------
    dict
        ``{column: ColumnRecord}`` for the columns the history speaks of:
        this package's corrections (``DATA -> CORRECTED_DATA``...), CASA's
        ``applycal`` (``CORRECTED_DATA``, with the parallactic angle removed
        when ``parang = True``), ``clearcal``, ``setjy``/``ft``
        (``MODEL_DATA``), and the tasks that copy one column into the
        ``DATA`` of a new set (``split``, ``mstransform``... with their
        ``datacolumn``); AIPS's records (`aips_records`, in the history of
        an imported UVFITS file) concern ``DATA``.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import ms_column_history
    >>> rows = [("applycal", "ms", "taskname=applycal"),
    ...         ("applycal", "ms", "parang      = True")]
    >>> ms_column_history(rows)["CORRECTED_DATA"].record
    'CASA applycal(parang=True)'
    """
    rows = [(str(o).strip(), str(a).strip(), str(m)) for o, a, m in rows]
    columns = {}
    imported = [r for r in aips_records("\n".join(m for _, _, m in rows))]
    if imported and imported[-1][1] == "remove":
        columns["DATA"] = ColumnRecord("remove", imported[-1][2])
    task, parameters = None, {}

    def finish():
        if task is not None:
            _casa_task(task, parameters, columns)

    for origin, application, message in rows:
        own = _own_records(message)
        if own and application != "astropy_feedrot":
            # Data corrected here, then written into DATA by another program (pyuvdata).
            direction = max(own)[1]
            columns["DATA"] = ColumnRecord(direction, f"{_MARKS[direction]!r} (then written "
                                           f"by {application or origin or 'another program'})")
            continue
        if own:
            finish()
            task, parameters = None, {}
            what = _WHAT.search(message)
            if what is None:
                continue
            direction = min(own)[1]
            source, target = what.group("source"), what.group("target")
            before = columns.get(source, ColumnRecord())
            # A column corrected in place stays whose it was (a model turned is a model).
            writer = before.writer if source == target else "astropy_feedrot"
            columns[target] = ColumnRecord(compose(before.state, direction),
                                           repr(_MARKS[direction]) + f" ({source} -> {target})",
                                           writer, source, direction)
            continue
        if message.strip().startswith("taskname="):
            finish()
            task, parameters = message.strip()[len("taskname="):].strip(), {}
            continue
        if task is not None and origin == task:
            parameter = _PARAMETER.match(message)
            if parameter:
                parameters[parameter.group("name")] = parameter.group("value")
            continue
        finish()
        task, parameters = None, {}
    finish()
    return columns
