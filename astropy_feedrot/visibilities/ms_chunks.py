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

import numpy as np

from ..core.cache import heap_keeps_chunks, release_thread_buffer, thread_buffer
from ..core.extras import install_hint
from .faraday import correct_rows
from .tasks import in_order, task_groups, worker_count

__all__ = ["Block", "Progress", "rows_of", "RECORD_SECONDS", "locked", "results",
           "tables"]

_EXTRA = install_hint("ms", "python-casacore")

# With dask workers, the progress keyword is written at most this often (seconds): each
# write takes the table's lock, and the workers then read the table's state again.
RECORD_SECONDS = 1.0

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
    """One chunk of rows and where its receptors' position angles are; picklable, for
    dask.

    ``rows`` are the rows (a `range` where they follow each other: it pickles
    small). The position angles (deg) of the two antennas of row ``k`` are
    ``table[place1[k]]`` and ``table[place2[k]]``
    (`~astropy_feedrot.visibilities.receptors.ReceptorAngleTable`: each distinct
    time, source and antenna once, sent to each dask worker once). ``index`` is
    the chunk's place in the run (the progress keyword counts chunks). With an
    ionosphere, ``table`` has a third column, the rotation measure (rad m^-2)
    of each antenna's line of sight, and ``lambda2`` the squared wavelengths
    (m^2) of the chunk's channels: the angles are then taken per channel
    (`~astropy_feedrot.visibilities.faraday.correct_rows`).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.visibilities.ms_chunks import Block
    >>> table = np.array([[10.0, -10.0], [20.0, -20.0]])
    >>> block = Block(range(3), ["RR", "LL"], table, np.array([0, 1, 1]), np.zeros(3, int))
    >>> block.table[block.place1][:, 0]
    array([10., 20., 20.])
    """

    def __init__(self, rows, products, table, place1, place2, index=0, lambda2=None):
        self.rows, self.products, self.table = rows, products, table
        self.place1, self.place2, self.index = place1, place2, index
        self.lambda2 = lambda2

    def sent(self):
        """The block without its angle table (a dask task takes that apart)."""
        return Block(self.rows, self.products, None, self.place1, self.place2, self.index,
                     self.lambda2)


def rows_of(rows):
    """Rows as a `Block` keeps them: a `range` where they follow each other.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.visibilities.ms_chunks import rows_of
    >>> rows_of(np.array([4, 5, 6])), rows_of(np.array([1, 3]))
    (range(4, 7), array([1, 3]))
    """
    if rows.size and rows[-1] - rows[0] + 1 == rows.size:
        return range(int(rows[0]), int(rows[-1]) + 1)
    return rows


class Progress:
    """Which chunks of a run are written: the value of the output column's keyword
    ``FEEDROT_PARTIAL`` until the run ends.

    The first ``chunks`` chunks are written, and those numbered in ``also``
    (chunks run on dask workers end in any order); those in ``unknown`` may
    or may not be (a worker's task that was not waited for).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.ms_chunks import Progress
    >>> progress = Progress("DATA -> CORRECTED_DATA", "remove", 100)
    >>> progress.count_rows([100, 100, 100, 50])
    >>> progress.add(0); progress.add(2)
    >>> progress.chunks, sorted(progress.also), progress.done
    (1, [2], 200)
    >>> progress.add(1)
    >>> progress.chunks, progress.also, progress.to_do(4)
    (3, set(), [3])
    """

    def __init__(self, what, direction, chunk_rows, chunks=0, also=(), unknown=()):
        self.what, self.direction, self.chunk_rows = what, direction, int(chunk_rows)
        self.chunks, self.also, self.unknown = int(chunks), set(also), set(unknown)
        self.sizes = []
        self._written = time.monotonic()

    @classmethod
    def resumed(cls, keyword, what, direction):
        """The progress recorded in the keyword of an interrupted run."""
        return cls(what, direction, keyword["chunk_rows"], keyword["chunks"],
                   np.ravel(keyword.get("also", [])).astype(int).tolist(),
                   np.ravel(keyword.get("unknown", [])).astype(int).tolist())

    def count_rows(self, sizes):
        """The number of rows of each chunk of the run."""
        self.sizes = list(sizes)

    def to_do(self, n):
        """The numbers of the chunks still to write, of ``n``."""
        return [k for k in range(self.chunks, n) if k not in self.also]

    def add(self, index, known=True):
        """Chunk ``index`` written (``known`` false: perhaps written)."""
        if not known:
            self.unknown.add(index)
            return
        self.unknown.discard(index)
        self.also.add(index)
        while self.chunks in self.also:
            self.also.discard(self.chunks)
            self.chunks += 1

    @property
    def done(self):
        """The rows written."""
        return sum(self.sizes[:self.chunks]) + sum(self.sizes[k] for k in self.also)

    def keyword(self):
        """The keyword's value now (and the time it is written)."""
        self._written = time.monotonic()
        value = {"what": self.what, "direction": self.direction, "done": self.done,
                 "chunks": self.chunks, "chunk_rows": self.chunk_rows}
        for name in ("also", "unknown"):
            if getattr(self, name):
                value[name] = np.array(sorted(getattr(self, name)), dtype=np.int64)
        return value

    def since_written(self):
        """Seconds since the keyword's value was last taken."""
        return time.monotonic() - self._written

    def unknown_text(self, column):
        """What the chunks of unknown state mean for ``column``."""
        return (f"chunks {sorted(self.unknown)} (of {self.chunk_rows} rows, numbered from 0) "
                f"of {column} may or may not be corrected (a worker's task was not waited "
                "for)")

    def interrupted(self, path, total, data_column, corrected_column):
        """The message of an interrupted run."""
        same = data_column == corrected_column
        also = f" and chunks {sorted(self.also)} (numbered from 0)" if self.also else ""
        text = (f"{str(path)!r}: interrupted after {self.done} of {total} rows; "
                f"{data_column} {'is partly corrected' if same else 'is intact'}; the first "
                f"{self.chunks} chunks of {self.chunk_rows} rows of {corrected_column}{also} "
                f"(keyword FEEDROT_PARTIAL) are corrected, the others not")
        if same and self.unknown:
            return (f"{text}, but {self.unknown_text(corrected_column)}: the correction "
                    f"cannot go on from there; restore {data_column} from a copy")
        return f"{text}: run the same correction again to finish"


def _corrected(data, block, direction):
    """``data`` (rows, channels, products) corrected in place; the NaN rows."""
    table = block.table
    angles, rm = (table, None) if block.lambda2 is None else (table[:, :2], table[:, 2])
    bad = correct_rows(data, angles, rm, block.place1, block.place2, block.products,
                       lambda2=block.lambda2, direction=direction)
    if bad.any():
        data[bad] = np.nan
    return int(np.count_nonzero(bad))


_VALUE_TYPES = {"complex": np.complex64, "dcomplex": np.complex128}


def _read(table, column, start, n=None):
    """Rows of a column of one cell shape, read into the buffer this thread keeps
    (`~astropy_feedrot.core.cache.thread_buffer`: a new 32 MiB array for each chunk took a
    tenth of a second to fault in here): ``n`` rows from ``start``, or the runs
    ``start`` [(first row, count), ...] one after the other."""
    runs = [(start, n)] if n is not None else start
    dtype = _VALUE_TYPES.get(table.getcoldesc(column).get("valueType"), np.complex64)
    data = thread_buffer(dtype, (sum(count for _, count in runs),) +
                         tuple(np.shape(table.getcell(column, runs[0][0]))))
    at = 0
    for first, count in runs:
        table.getcolnp(column, data[at:at + count], first, count)
        at += count
    return data


@contextlib.contextmanager
def _selection(table, rows):
    """(table, start, count) of the rows: the table itself for a contiguous range, else a
    selection of them (a reference table)."""
    n = len(rows)
    if rows[-1] - rows[0] + 1 == n:
        yield table, int(rows[0]), n
        return
    with contextlib.closing(table.selectrows(np.asarray(rows).tolist())) as selection:
        yield selection, 0, n


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


def _start_worker(path, run):
    """Open the table for a run and keep chunk-sized blocks in the heap (run on every
    worker)."""
    with _PROCESS_LOCK:
        _worker_table(path, run)
    heap_keeps_chunks()


def _release_worker(run):
    """Close the handle of a finished run and give glibc's thresholds back (run on every
    worker)."""
    with _PROCESS_LOCK:
        if _WORKER["run"] == run and _WORKER["table"] is not None:
            _WORKER["table"].close()
            _WORKER.update(run=None, table=None)
    heap_keeps_chunks(False)


def _remote_blocks(path, data_column, corrected_column, blocks, table, direction, run):
    """A dask task: read each block (no lock: other processes write other rows),
    correct it with the angle ``table``, and write it under casacore's write lock; the
    NaN rows of each."""
    bad = []
    for block in blocks:
        block.table = table
        # Rows that do not follow each other (a data description's rows among
        # others', rows left out of a correction) are read and written a run of
        # neighbours at a time: casacore's selections of rows need the table's lock
        # under user locking, also to be read.
        runs = _runs(block.rows)
        with _PROCESS_LOCK:
            handle = _worker_table(path, run)
            data = _read(handle, data_column, runs)
        bad.append(_corrected(data, block, direction))
        with locked(handle, True):
            at = 0
            for start, n in runs:
                handle.putcol(corrected_column, data[at:at + n], start, n)
                at += n
    return bad


def _runs(rows):
    """(first row, count) of each run of neighbouring rows, in order."""
    if isinstance(rows, range):
        return [(rows.start, len(rows))]
    rows = np.asarray(rows)
    return [(int(part[0]), part.size) for part in
            np.split(rows, np.flatnonzero(np.diff(rows) != 1) + 1)]


def _here(table, block, columns, direction):
    """Read, correct and write a `Block` in this process (the table held); the NaN rows."""
    data_column, corrected_column = columns
    with _selection(table, block.rows) as (selection, start, n):
        data = _read(selection, data_column, start, n)
        bad = _corrected(data, block, direction)
        selection.putcol(corrected_column, data, start, n)
    return bad


def results(work, table, path, columns, direction, client=None, late=None, count=0):
    """(block, NaN rows) in order, each chunk written: here, in ``table`` (opened with
    casacore's permanent lock), or with ``client`` on its dask workers (``table``
    opened shared), two tasks per worker going.

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
        Where the chunks are corrected, a few at a time in each task
        (`~astropy_feedrot.visibilities.tasks.task_groups`).
    late : list, optional
        If the run stops early (an error, Ctrl-C, the generator closed), the
        chunks written by the workers and not yet given are waited for (a task
        that has started cannot be stopped, and it writes its rows): each is
        appended as ``(block, NaN rows)``, or ``(block, None)`` where its task
        failed or was not waited for (a second Ctrl-C): its rows may or may not
        have been written.
    count : int, optional
        The number of chunks in ``work`` (with ``client``: the tasks shrink
        towards the end).

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
    # Every worker opens the table now, while no process writes: opening reads the
    # table's files without a lock, and a column another worker is writing could be
    # read half written (a worker that joins later opens it at its first task).
    client.run(_start_worker, path, run)
    workers = worker_count(client)
    pending, angle_tables, given = [], {}, []

    def submit(group):
        key = id(group[0].table)
        if key not in angle_tables:  # each angle table to each worker once
            angle_tables[key] = client.scatter(group[0].table, broadcast=True)
        return client.submit(_remote_blocks, path, *columns, [block.sent() for block in group],
                             angle_tables[key], direction, run, pure=False)

    try:
        groups = task_groups(work, count, workers, key=lambda block: id(block.table))
        for group, bad in in_order(groups, submit, workers, pending):
            given = list(zip(group, bad))
            while given:
                yield given.pop(0)
    finally:
        if late is not None:
            late.extend(given)  # written, not yet given
        waiting = True
        for group, future in pending:
            bad = [None] * len(group)
            if waiting:
                try:
                    bad = future.result()
                except Exception:  # noqa: S110 - recorded as unknown below
                    pass
                except BaseException:  # a second Ctrl-C: stop waiting, the rest unknown
                    waiting = False
            if late is not None:
                late.extend(zip(group, bad))
        with contextlib.suppress(Exception):
            client.run(_release_worker, run)
