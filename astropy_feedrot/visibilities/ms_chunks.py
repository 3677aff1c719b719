# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Chunks of a Measurement Set's rows, corrected and written by this process or by
dask workers.

In one process the main table is held with casacore's permanent lock and each
chunk is read, corrected and written in turn. With a dask
client, each worker opens the table once per run with casacore's user locks
(``usernoread``: reading needs no lock, and other processes write other
rows), reads and corrects its chunks, and writes each under the table's write
lock (`locked`), which also makes casacore write out what it holds and the
next holder read the table's state again; the process that asked records
them in order (`results`). The threads of one process take the lock in turn.
"""

import contextlib
import threading
import time
import uuid

import astropy.units as u
import numpy as np

from ..correction import correct_receptor_visibilities
from ..kept import release_thread_buffer, thread_buffer

__all__ = ["Block", "locked", "results", "tables"]

_EXTRA = "pip install 'astropy_feedrot[ms]'"

# One holder of casacore's lock at a time among this process's threads (casacore's
# lock belongs to the process: two threads would release each other's).
_PROCESS_LOCK = threading.RLock()


def tables():
    """casacore.tables, or an ImportError naming the extra.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.ms_chunks import tables
    >>> tables().__name__
    'casacore.tables'
    """
    try:
        from casacore import tables  # optional: only Measurement Sets need it
    except ImportError:
        raise ImportError(f"Measurement Sets need python-casacore: {_EXTRA}") from None
    return tables


@contextlib.contextmanager
def locked(table, shared):
    """casacore's write lock on a table opened ``shared``, released (and the table
    written out) after; nothing for a table this process holds for good.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.ms_chunks import locked
    >>> with locked(None, False):  # a table held with the permanent lock
    ...     pass
    """
    if not shared:
        yield
        return
    # table.lock() retries once a second; a writer holds it for one chunk.
    with _PROCESS_LOCK:
        _acquire(table)
        try:
            yield
        finally:
            table.unlock()


def _acquire(table):
    while True:
        with contextlib.suppress(RuntimeError):
            table.lock(write=True, nattempts=1)
        if table.haslock(write=True):
            break
        time.sleep(0.001)


class Block:
    """One chunk of rows and its receptors' position angles; picklable, for dask.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.visibilities.ms_chunks import Block
    >>> Block(np.arange(3), ["RR", "LL"], np.zeros((3, 2)), np.zeros((3, 2))).rows
    array([0, 1, 2])
    """

    def __init__(self, rows, products, theta1, theta2):
        self.rows, self.products, self.theta1, self.theta2 = rows, products, theta1, theta2


def _corrected(data, block, direction):
    """``data`` (rows, channels, products) corrected in place; the NaN rows."""
    theta1, theta2 = block.theta1, block.theta2
    # One angle pair per row, for every channel.
    correct_receptor_visibilities(data, theta1[:, None, :] * u.deg, theta2[:, None, :] * u.deg,
                                  block.products, out=data, direction=direction)
    bad = np.isnan(theta1).any(axis=1) | np.isnan(theta2).any(axis=1)
    if bad.any():
        data[bad] = np.nan
    return int(np.count_nonzero(bad))


_VALUE_TYPES = {"complex": np.complex64, "dcomplex": np.complex128}


def _read(table, column, start, n):
    """Rows of a column of one cell shape, read into the buffer this thread keeps
    (`~astropy_feedrot.kept.thread_buffer`: a new 32 MiB array for each chunk took a
    tenth of a second to fault in here)."""
    dtype = _VALUE_TYPES.get(table.getcoldesc(column).get("valueType"), np.complex64)
    data = thread_buffer(dtype, (n,) + tuple(np.shape(table.getcell(column, start))))
    table.getcolnp(column, data, start, n)
    return data


@contextlib.contextmanager
def _selection(table, rows):
    """(table, start, count) of the rows: the table itself for a contiguous range, else a
    selection of them (a reference table)."""
    if rows[-1] - rows[0] + 1 == rows.size:
        yield table, int(rows[0]), int(rows.size)
        return
    with contextlib.closing(table.selectrows(rows.tolist())) as selection:
        yield selection, 0, int(rows.size)


# This worker process's handle on the Measurement Set of the current run (a dask
# task opens it once per run, not once per chunk).
_WORKER = {"run": None, "table": None}


def _worker_table(path, run):
    if _WORKER["run"] != run:
        if _WORKER["table"] is not None:
            _WORKER["table"].close()
        _WORKER.update(run=None, table=None)
        table = tables().table(str(path), readonly=False, ack=False,
                               lockoptions={"option": "usernoread"})
        _WORKER.update(run=run, table=table)
    return _WORKER["table"]


def _release_worker(run):
    """Close the handle of a finished run (run on every worker)."""
    with _PROCESS_LOCK:
        if _WORKER["run"] == run and _WORKER["table"] is not None:
            _WORKER["table"].close()
            _WORKER.update(run=None, table=None)


def _remote_block(path, data_column, corrected_column, block, direction, run):
    """A dask task: read a chunk (no lock: other processes write other rows), correct
    it, and write it under casacore's write lock; the NaN rows."""
    with _PROCESS_LOCK:
        table = _worker_table(path, run)
        with _selection(table, block.rows) as (selection, start, n):
            data = _read(selection, data_column, start, n)
    bad = _corrected(data, block, direction)
    with locked(table, True), _selection(table, block.rows) as (selection, start, n):
        selection.putcol(corrected_column, data, start, n)
    return bad


def _here(table, block, columns, direction):
    """Read, correct and write a `Block` in this process (the table held); the NaN rows."""
    data_column, corrected_column = columns
    with _selection(table, block.rows) as (selection, start, n):
        data = _read(selection, data_column, start, n)
        bad = _corrected(data, block, direction)
        selection.putcol(corrected_column, data, start, n)
    return bad


def results(work, table, path, columns, direction, client=None):
    """(block, NaN rows) in order, each chunk written: here, in ``table`` (opened with
    casacore's permanent lock), or with ``client`` on its dask workers (``table``
    opened shared), two per worker going.

    Parameters
    ----------
    work : iterable of `Block`
        The chunks, in order.
    table : casacore table
        The Measurement Set's main table, as this process holds it.
    path : str or path-like
        Its path (the workers open it).
    columns : (str, str)
        The column read and the column written.
    direction : {'remove', 'apply'}
        As in `~astropy_feedrot.visibilities.correct_ms`.
    client : `dask.distributed.Client`, optional
        Where the chunks are corrected.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.ms_chunks import results
    >>> list(results([], None, None, ("DATA", "CORRECTED_DATA"), "remove"))  # no chunks
    []
    """
    if client is None:
        try:
            for block in work:
                yield block, _here(table, block, columns, direction)
        finally:
            release_thread_buffer()  # this process keeps no chunk after the run
        return
    run = uuid.uuid4().hex  # under which the workers keep the table open
    ahead = 2 * max(1, len(client.scheduler_info().get("workers", {})))
    blocks, pending = iter(work), []
    try:
        while True:
            while len(pending) < ahead:
                block = next(blocks, None)
                if block is None:
                    break
                pending.append((block, client.submit(_remote_block, path, *columns, block,
                                                     direction, run, pure=False)))
            if not pending:
                return
            done, future = pending.pop(0)
            yield done, future.result()
    finally:
        for _, future in pending:  # interrupted: the rows after the last done are redone
            future.cancel()
        with contextlib.suppress(Exception):
            client.run(_release_worker, run)
