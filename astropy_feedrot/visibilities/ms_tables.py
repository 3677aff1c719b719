# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The columns of a Measurement Set that a correction reads and writes, and copies of
a Measurement Set.

* `check_columns` refuses, before anything is written, an output column that
  is not a visibility column of the input's type and shape (``UVW``,
  ``FLAG``, a name that is no column name), and an existing column that
  this package did not write (``MODEL_DATA``, a ``CORRECTED_DATA`` that CASA
  filled) unless ``overwrite_column`` is given.
* `column_records` reads what the ``HISTORY`` table says each column holds,
  and `check_column_history` refuses a correction made already.
* `copy_ms` copies a Measurement Set with casacore's own table copy.

python-casacore is imported on first use
(`~astropy_feedrot.visibilities.ms_chunks.tables`).
"""

import contextlib
import re
from pathlib import Path

import numpy as np

from .history import CorrectionRefused, ms_column_history, refusal
from .ms_chunks import tables

__all__ = ["MSError", "ColumnRefused", "OWN_COLUMN", "VISIBILITY_TYPES", "check_columns",
           "column_is_ours", "copy_ms", "column_name", "column_records",
           "check_column_history"]

#: The words of the comment of a column this package created.
OWN_COLUMN = "written by astropy_feedrot"

#: casacore value types of visibility columns.
VISIBILITY_TYPES = ("complex", "dcomplex")

_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


class MSError(ValueError):
    """A Measurement Set cannot be corrected as asked: one line saying why and what to do.

    Examples
    --------
    >>> from astropy_feedrot.visibilities import MSError
    >>> issubclass(MSError, ValueError)
    True
    """


class ColumnRefused(CorrectionRefused, MSError):
    """A column of a Measurement Set that cannot be read or written as asked.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.ms_tables import ColumnRefused
    >>> str(ColumnRefused("x.ms: choose another <<corrected_column>>"))
    'x.ms: choose another corrected_column='
    """


def column_name(name, what, where):
    """``name`` if it can name a casacore column (a letter or ``_``, then letters, digits,
    ``_``), else `ColumnRefused`.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.ms_tables import column_name
    >>> column_name("CORRECTED_DATA", "<<corrected_column>>", "x.ms")
    'CORRECTED_DATA'
    """
    if not isinstance(name, str) or not _NAME.match(name):
        raise ColumnRefused(f"{where}: {name!r} is not a column name (letters, digits and _, "
                            f"not starting with a digit); choose another {what}")
    return name


def column_is_ours(table, column, record):
    """Whether ``column`` (existing) was written last by this package: its description
    says this package created it, and the ``HISTORY`` names no other writer since
    (``record``, a `~astropy_feedrot.visibilities.history.ColumnRecord` or None).

    Examples
    --------
    >>> import tarfile, tempfile, pathlib
    >>> from astropy_feedrot.visibilities.ms_chunks import tables
    >>> from astropy_feedrot.visibilities.ms_tables import column_is_ours
    >>> where = pathlib.Path(tempfile.mkdtemp())
    >>> with tarfile.open("tests/data/uvdata/day2_TDEM0003_10s_norx_1src_1spw_2ints"
    ...                   ".ms.tar.gz") as archive:
    ...     archive.extractall(where, filter="data")
    >>> with tables().table(str(where / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms"),
    ...                     ack=False) as table:
    ...     column_is_ours(table, "DATA", None)  # CASA's importuvfits wrote it
    False
    """
    if record is not None and record.writer is not None:
        return record.writer == "astropy_feedrot"
    return OWN_COLUMN in str(table.getcoldesc(column).get("comment", ""))


def _cell_shape(table, column, row):
    if not table.iscelldefined(column, row):
        return None
    return tuple(np.shape(table.getcell(column, row)))


def check_columns(table, path, data_column, corrected_column, records, firsts, *,
                  overwrite_column=False, resuming=False):
    """Refuse, before any write, columns that cannot be read or written as asked.

    Parameters
    ----------
    table : casacore table
        The main table.
    path : path-like
        The Measurement Set, for messages.
    data_column, corrected_column : str
        The column read and the column written.
    records : dict
        What the ``HISTORY`` says of each column
        (`~astropy_feedrot.visibilities.history.ms_column_history`).
    firsts : sequence of int
        A row of each data description (their shapes are compared).
    overwrite_column : bool, optional
        Allow writing into an existing column this package did not write.
    resuming : bool, optional
        The run goes on with an interrupted one into ``corrected_column``
        (which was allowed then).

    Raises
    ------
    MSError, ColumnRefused
        A missing or non-visibility ``data_column``; a ``corrected_column``
        that is no column name, not of the type and cell shape of
        ``data_column``, or that exists, is not ``data_column``, and was not
        written by this package, unless ``overwrite_column``.

    Examples
    --------
    >>> import tarfile, tempfile, pathlib
    >>> from astropy_feedrot.visibilities.ms_chunks import tables
    >>> from astropy_feedrot.visibilities.ms_tables import check_columns
    >>> where = pathlib.Path(tempfile.mkdtemp())
    >>> with tarfile.open("tests/data/uvdata/day2_TDEM0003_10s_norx_1src_1spw_2ints"
    ...                   ".ms.tar.gz") as archive:
    ...     archive.extractall(where, filter="data")
    >>> with tables().table(str(where / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms"),
    ...                     ack=False) as table:
    ...     check_columns(table, "vla.ms", "DATA", "CORRECTED_DATA", {}, [0])  # a new column
    ...     check_columns(table, "vla.ms", "DATA", "UVW", {}, [0])
    Traceback (most recent call last):
    ...
    astropy_feedrot...ColumnRefused: 'vla.ms': column 'UVW' is not a visibility column ...
    """
    where = repr(str(path))
    column_name(data_column, "<<data_column>>", where)
    column_name(corrected_column, "<<corrected_column>>", where)
    columns = table.colnames()
    visibility = [c for c in columns
                  if table.getcoldesc(c).get("valueType") in VISIBILITY_TYPES]
    if data_column not in columns:
        raise ColumnRefused(f"{where} has no column {data_column!r} (its visibility columns: "
                            f"{visibility}); choose one with <<data_column>>")
    described = table.getcoldesc(data_column)
    if described.get("valueType") not in VISIBILITY_TYPES:
        raise ColumnRefused(f"{where}: column {data_column!r} holds {described.get('valueType')}"
                            f" values, not complex visibilities (its visibility columns: "
                            f"{visibility}); choose one with <<data_column>>")
    if corrected_column not in columns or corrected_column == data_column:
        return
    target = table.getcoldesc(corrected_column)
    kind = target.get("valueType")
    shapes = [(_cell_shape(table, data_column, r), _cell_shape(table, corrected_column, r))
              for r in firsts]
    wrong = [(a, b) for a, b in shapes if a is not None and b is not None and a != b]
    if kind not in VISIBILITY_TYPES or wrong or ("ndim" in target and "ndim" in described and
                                                 target["ndim"] != described["ndim"]):
        shape = f" with cells of shape {wrong[0][1]} against {wrong[0][0]}" if wrong else ""
        raise ColumnRefused(f"{where}: column {corrected_column!r} is not a visibility column "
                            f"like {data_column!r} ({kind}{shape}, not "
                            f"{described.get('valueType')}); nothing was written: choose "
                            "another <<corrected_column>> (CORRECTED_DATA, or a new name)")
    record = records.get(corrected_column)
    if overwrite_column or resuming or column_is_ours(table, corrected_column, record):
        return
    if record is not None and record.writer is not None:
        who = f"was written by {record.writer}"
        if record.record:
            who += f" ({record.record})"
    else:
        comment = str(target.get("comment", "")).strip()
        who = "was not written by astropy_feedrot" + (f" (its description: {comment!r})"
                                                      if comment else "")
    raise ColumnRefused(f"{where}: column {corrected_column!r} exists and {who}; writing "
                        f"{data_column} corrected into it would replace its values: pass "
                        "<<overwrite_column>> to replace them, or write another column "
                        "(<<corrected_column>>)")


def copy_ms(source, target):
    """Copy a Measurement Set with casacore's table copy (every column and subtable).

    Parameters
    ----------
    source, target : path-like
        The Measurement Set and where its copy goes (must not exist).

    Returns
    -------
    pathlib.Path
        ``target``.

    Examples
    --------
    >>> import tarfile, tempfile, pathlib
    >>> from astropy_feedrot.visibilities.ms_tables import copy_ms
    >>> where = pathlib.Path(tempfile.mkdtemp())
    >>> with tarfile.open("tests/data/uvdata/day2_TDEM0003_10s_norx_1src_1spw_2ints"
    ...                   ".ms.tar.gz") as archive:
    ...     archive.extractall(where, filter="data")
    >>> copy_ms(where / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms", where / "copy.ms").name
    'copy.ms'
    """
    casacore = tables()
    target = Path(target)
    with contextlib.closing(casacore.table(str(source), ack=False)) as table:
        # deep: a reference table (a selection) becomes a plain one; plain tables are
        # copied as they are stored, subtables included.
        table.copy(str(target), deep=True).close()
    return target


def column_records(ms):
    """What the ``HISTORY`` table of a Measurement Set says each column holds.

    Parameters
    ----------
    ms : str or path-like
        The Measurement Set.

    Returns
    -------
    dict
        ``{column: ColumnRecord}``
        (`~astropy_feedrot.visibilities.history.ms_column_history`); empty
        without a ``HISTORY`` table.

    Examples
    --------
    >>> import tarfile, tempfile, pathlib
    >>> from astropy_feedrot.visibilities.ms_tables import column_records
    >>> where = pathlib.Path(tempfile.mkdtemp())
    >>> with tarfile.open("tests/data/uvdata/day2_TDEM0003_10s_norx_1src_1spw_2ints"
    ...                   ".ms.tar.gz") as archive:
    ...     archive.extractall(where, filter="data")
    >>> column_records(where / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms")  # importuvfits
    {}
    """
    path = Path(ms) / "HISTORY"
    if not path.is_dir():
        return {}
    with contextlib.closing(tables().table(str(path), ack=False)) as table:
        if table.nrows() == 0:
            return {}
        columns = [table.getcol(c) if c in table.colnames() else [""] * table.nrows()
                   for c in ("ORIGIN", "APPLICATION", "MESSAGE")]
    text = [[v.decode() if isinstance(v, bytes) else str(v) for v in c] for c in columns]
    return ms_column_history(zip(*text))


def check_column_history(path, records, data_column, corrected_column, direction, redo):
    """Refuse a correction of data the ``HISTORY`` says are corrected already (it would
    correct them twice), or the same correction into the same column again (a
    recomputation), unless ``redo``.

    Parameters
    ----------
    path : path-like
        The Measurement Set, for messages.
    records : dict
        `column_records` of it.
    data_column, corrected_column : str
        The column read and the column written.
    direction : {'remove', 'apply'}
        The correction asked for.
    redo : bool
        Allow it all the same.

    Raises
    ------
    CorrectionRefused

    Examples
    --------
    >>> from astropy_feedrot.visibilities.history import ColumnRecord
    >>> from astropy_feedrot.visibilities.ms_tables import check_column_history
    >>> records = {"CORRECTED_DATA": ColumnRecord("remove", "CASA applycal(parang=True)")}
    >>> check_column_history("x.ms", records, "DATA", "CORRECTED_DATA", "remove", False)
    >>> check_column_history("x.ms", records, "CORRECTED_DATA", "OURS", "remove", False)
    Traceback (most recent call last):
    ...
    astropy_feedrot...CorrectionRefused: 'x.ms' (HISTORY of CORRECTED_DATA): the feed ...
    """
    if redo:
        return
    source = records.get(data_column)
    if source is not None and source.state == direction:
        raise refusal(f"{str(path)!r} (HISTORY of {data_column})", direction, source.record)
    target = records.get(corrected_column)
    if corrected_column != data_column and target is not None and \
            target.writer == "astropy_feedrot" and target.source == data_column and \
            target.direction == direction:
        raise refusal(repr(str(path)), direction, target.record,
                      recompute=f"{corrected_column} holds {data_column}")
