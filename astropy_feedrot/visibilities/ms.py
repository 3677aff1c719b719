# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Measurement Sets, corrected in place with python-casacore.

* `~astropy_feedrot.visibilities.ms_antennas` (module
  `~astropy_feedrot.visibilities.ms_antennas`) reads the ``ANTENNA`` table
  and the receptors of the ``FEED`` table.
* `correct_ms` writes the feed rotation removed from (or applied to) one data
  column into another column of the same Measurement Set, in chunks of rows,
  creating the output column as CASA does when it is missing, and records
  what it did in the ``HISTORY`` table.

The receptors come from ``FEED`` row by row (``POLARIZATION_TYPE``,
``RECEPTOR_ANGLE``, for the antenna, feed, spectral window and time of each
visibility row), the sources from ``FIELD`` (``PHASE_DIR`` with its
reference frame and polynomial, ephemeris tables of moving sources) and the
products from ``POLARIZATION`` (``CORR_TYPE``), per data description.
python-casacore is an optional dependency, of the ``ms`` extra (``python -m
pip install python-casacore``), imported on first use.
"""

import contextlib
import fcntl
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import FK4, FK5, ICRS, SkyCoord
from astropy.time import Time

from ..antennas.receptors import basis_of
from ..core.exceptions import DegenerateGeometryWarning, warn_caller
from ..core.outputs import publish
from ..core.progress import progress_steps
from ..ionosphere import IonosphereError
from .correction import Correction, refuse_column_options, register_adapter
from .history import CorrectionRefused
from .kinds import check_output_format, check_output_path
from .faraday import ms_lambda_squared
from .ms_antennas import FeedReceptors, cell_text, ms_antennas, ms_path, ms_telescopes, subtable
from .ms_chunks import RECORD_SECONDS, Block, Progress, locked, results, rows_of, tables as _tables
from .ms_tables import (
    OWN_COLUMN,
    MSError,
    check_column_history,
    check_columns,
    column_records,
    copy_ms,
)
from .receptors import ReceptorAngleTable, warn_unusual_angles
from .unusable import warn_skipped
from .uvdata_adapter import correct_uvdata_file

__all__ = ["correct_ms", "correct_ms_file", "CORR_TYPES", "MSError"]

#: The casacore ``Stokes`` codes of ``CORR_TYPE`` that are correlations of
#: receptors (casacore ``Stokes.h``).
CORR_TYPES = {5: "RR", 6: "RL", 7: "LR", 8: "LL", 9: "XX", 10: "XY", 11: "YX", 12: "YY"}

# Bytes of the data column read at once.
_CHUNK_BYTES = 32 * 2**20

# The keyword of the output column that records an unfinished run.
_PARTIAL = "FEEDROT_PARTIAL"

# PHASE_DIR reference frames read as celestial coordinates.
_FRAMES = {"J2000": lambda: FK5(equinox="J2000"), "ICRS": ICRS,
           "B1950": lambda: FK4(equinox="B1950"), "B1950_VLA": lambda: FK4(equinox="B1950")}


@contextlib.contextmanager
def _open(path, *, write=False, shared=False):
    """The main table; ``shared``: written by other processes too (casacore user locks,
    taken by `~astropy_feedrot.visibilities.ms_chunks.locked` around each write)."""
    tables = _tables()
    locking = {"option": "usernoread"} if shared else "permanent" if write else "auto"
    table = tables.table(str(path), readonly=not write, ack=False, lockoptions=locking)
    try:
        yield table
    finally:
        table.close()


# --- fields ------------------------------------------------------------------------------


class _EphemerisField:
    """A moving source: a CASA ephemeris table (MJD, RA, DEC) plus PHASE_DIR offsets."""

    def __init__(self, table_path, offset, name):
        tables = _tables()
        with contextlib.closing(tables.table(str(table_path), ack=False)) as table:
            self.mjd = np.asarray(table.getcol("MJD"), float)
            self.ra = np.unwrap(np.radians(np.asarray(table.getcol("RA"), float)))
            self.dec = np.radians(np.asarray(table.getcol("DEC"), float))
            frame = str(table.getkeywords().get("posrefsys", "ICRF/ICRS")).upper()
        self.frame = FK5(equinox="J2000") if "J2000" in frame and "ICRS" not in frame else ICRS()
        self.offset = offset
        self.name = name

    def __call__(self, epochs):
        mjd = epochs.utc.mjd
        outside = (mjd < self.mjd[0] - 1e-9) | (mjd > self.mjd[-1] + 1e-9)
        if np.any(outside):
            raise MSError(f"the ephemeris of field {self.name!r} covers MJD {self.mjd[0]:.5f} "
                          f"to {self.mjd[-1]:.5f} but the data reach {mjd[outside][0]:.5f}; "
                          "give an ephemeris that spans the observation")
        ra = np.interp(mjd, self.mjd, self.ra) + self.offset[0]
        dec = np.interp(mjd, self.mjd, self.dec) + self.offset[1]
        return SkyCoord(ra * u.rad, dec * u.rad, frame=self.frame)


class _PolynomialField:
    """A field whose PHASE_DIR is a polynomial in time (NUM_POLY > 0)."""

    def __init__(self, coefficients, origin, frame, name):
        self.coefficients, self.origin, self.frame, self.name = coefficients, origin, frame, name

    def __call__(self, epochs):
        dt = epochs.utc.mjd * 86400.0 - self.origin
        powers = dt[:, None] ** np.arange(len(self.coefficients))[None, :]
        ra, dec = (powers @ self.coefficients).T
        return SkyCoord(ra * u.rad, dec * u.rad, frame=self.frame)


def _fields(path):
    """{FIELD row: source} from PHASE_DIR and the ephemeris tables."""
    with contextlib.closing(subtable(path, "FIELD")) as table:
        columns = table.colnames()
        info = table.getcolkeywords("PHASE_DIR").get("MEASINFO", {})
        codes = dict(zip(info.get("TabRefCodes", []), info.get("TabRefTypes", [])))
        variable = info.get("VarRefCol")
        fields = {}
        for k in range(table.nrows()):
            name = cell_text(table.getcell("NAME", k))
            where = f"{str(path)!r}, table FIELD, field {k} ({name})"
            ref = codes.get(int(table.getcell(variable, k)), "?") if variable \
                else str(info.get("Ref", "J2000"))
            direction = np.asarray(table.getcell("PHASE_DIR", k), float).reshape(-1, 2)
            if not np.all(np.isfinite(direction)):
                raise MSError(f"{where}: PHASE_DIR is {direction.tolist()} rad, not numbers: "
                              "every angle of its rows would be NaN; give the field's "
                              "direction")
            ephemeris = int(table.getcell("EPHEMERIS_ID", k)) if "EPHEMERIS_ID" in columns \
                else -1
            if ephemeris >= 0:
                found = sorted((path / "FIELD").glob(f"EPHEM{ephemeris}_*.tab"))
                if not found:
                    raise MSError(f"{where}: EPHEMERIS_ID {ephemeris} but no table "
                                  f"FIELD/EPHEM{ephemeris}_*.tab")
                fields[k] = _EphemerisField(found[0], direction[0], name)
                continue
            if ref not in _FRAMES:
                raise MSError(f"{where}: PHASE_DIR in {ref}; the fields must be in "
                              f"{sorted(_FRAMES)} or have an ephemeris table")
            frame = _FRAMES[ref]()
            if len(direction) > 1 and np.any(direction[1:] != 0):
                fields[k] = _PolynomialField(direction, float(table.getcell("TIME", k)),
                                             frame, name)
            else:
                fields[k] = SkyCoord(direction[0, 0] * u.rad, direction[0, 1] * u.rad,
                                     frame=frame)
    return fields


def _descriptions(path):
    """{DATA_DESC_ID: (spectral window, products)}."""
    with contextlib.closing(subtable(path, "POLARIZATION")) as table:
        corr = [np.asarray(table.getcell("CORR_TYPE", k)).tolist() for k in range(table.nrows())]
    with contextlib.closing(subtable(path, "DATA_DESCRIPTION")) as table:
        spw = table.getcol("SPECTRAL_WINDOW_ID").tolist()
        pol = table.getcol("POLARIZATION_ID").tolist()
    out = {}
    for dd, (s, p) in enumerate(zip(spw, pol)):
        codes = corr[p]
        unknown = [c for c in codes if c not in CORR_TYPES]
        if unknown:
            raise MSError(f"{str(path)!r}: data description {dd} holds CORR_TYPE {codes}, "
                          f"with {unknown} not correlations of receptors (RR=5 ... YY=12); "
                          "Stokes data cannot be corrected per visibility")
        products = [CORR_TYPES[c] for c in codes]
        try:
            basis_of(products)
        except ValueError:
            raise MSError(f"{str(path)!r}: data description {dd} mixes circular and linear "
                          f"products {products}") from None
        out[dd] = (s, products)
    return out


# --- writing -------------------------------------------------------------------------------


def _check_writable(path):
    """MSError unless the Measurement Set can be written and no other process holds it."""
    blocked = [p for p in [path, *path.glob("table.*")] if not os.access(p, os.W_OK)]
    if blocked:
        raise MSError(f"{str(path)!r} is read-only ({str(blocked[0])!r} cannot be written): "
                      "make it writable, or correct a writable copy")
    lock = path / "table.lock"
    if lock.exists():
        handle = os.open(lock, os.O_RDWR)
        try:
            # casacore locks table.lock with fcntl; a lock held elsewhere is refused
            # here at once instead of waiting for it.
            fcntl.lockf(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            raise MSError(f"{str(path)!r} is locked by another process (casacore's "
                          "table.lock): close it there (CASA, casabrowser, a Python "
                          "session) and try again") from None
        else:
            fcntl.lockf(handle, fcntl.LOCK_UN)
        finally:
            os.close(handle)


def _add_column(table, source, name):
    """Add ``name`` like ``source`` (description, tiled storage of its own), as CASA does."""
    tables = _tables()
    description = table.getcoldesc(source)
    description.pop("keywords", None)
    description["comment"] = f"{name} {OWN_COLUMN} from {source}"
    info = table.getdminfo(source)
    group = f"Tiled{name}"
    dminfo = {"TYPE": info["TYPE"] if info["TYPE"].startswith("Tiled") else "TiledShapeStMan",
              "NAME": group, "SPEC": {}}
    if "DEFAULTTILESHAPE" in info.get("SPEC", {}):
        dminfo["SPEC"]["DEFAULTTILESHAPE"] = info["SPEC"]["DEFAULTTILESHAPE"]
    description["dataManagerGroup"] = group
    description["dataManagerType"] = dminfo["TYPE"]
    table.addcols(tables.maketabdesc(tables.makecoldesc(name, description)), dminfo)


def _copy_rows(table, rows, source, target, step):
    """Copy the cells of column ``source`` into ``target`` at ``rows`` (sorted), a run of
    neighbouring rows at a time, at most ``step`` rows at once (casacore's selections
    of rows cannot be written under user locking)."""
    for part in np.split(rows, np.flatnonzero(np.diff(rows) != 1) + 1):
        for start in range(int(part[0]), int(part[-1]) + 1, step):
            count = min(step, int(part[-1]) + 1 - start)
            table.putcol(target, table.getcol(source, start, count), start, count)


def _add_history(path, message):
    tables = _tables()
    with contextlib.closing(tables.table(str(path / "HISTORY"), readonly=False,
                                         ack=False)) as table:
        row = table.nrows()
        table.addrows(1)
        now = Time.now().utc.mjd * 86400.0
        table.putcell("TIME", row, now)
        table.putcell("OBSERVATION_ID", row, 0)
        table.putcell("MESSAGE", row, message)
        table.putcell("PRIORITY", row, "NORMAL")
        table.putcell("ORIGIN", row, "astropy_feedrot.visibilities.correct_ms")
        table.putcell("OBJECT_ID", row, 0)
        table.putcell("APPLICATION", row, "astropy_feedrot")
        table.putcell("CLI_COMMAND", row, [""])
        table.putcell("APP_PARAMS", row, [""])


def _chunk_rows(table, column, chunk_rows):
    if chunk_rows is not None:
        chunk_rows = int(chunk_rows)
        if chunk_rows < 1:
            raise ValueError(f"chunk_rows must be a positive number of rows, got {chunk_rows}")
        return chunk_rows
    if table.nrows() == 0:
        return 1
    cell = np.asarray(table.getcell(column, 0))
    return max(1, _CHUNK_BYTES // max(cell.nbytes, 1))


def _meta(table):
    """The columns that say what each row is, for all rows (a few bytes per row)."""
    return {name: table.getcol(name) for name in ("TIME", "ANTENNA1", "ANTENNA2", "FEED1",
                                                  "FEED2", "FIELD_ID", "DATA_DESC_ID")}


def _plan(correction, path, meta, feeds, skipped):
    """Per data description: rows, products, the virtual antennas of each row (not the
    rows ``skipped``, a mask, left as they are), their angles and, with an ionosphere,
    the lambda^2 of the channels (else None).

    Everything is checked here, before anything is written.
    """
    channels = None if correction.ionosphere is None else ms_lambda_squared(path, _tables())
    descriptions, fields = _descriptions(path), _fields(path)
    ddid = meta["DATA_DESC_ID"]
    missing = sorted(set(np.unique(meta["FIELD_ID"]).tolist()) - set(fields))
    if missing:
        raise MSError(f"{str(path)!r}: rows use FIELD_ID {missing} that the FIELD table lacks")
    plans = []
    for dd in np.unique(ddid).tolist():
        if dd not in descriptions:
            raise MSError(f"{str(path)!r}: rows use DATA_DESC_ID {dd} that the "
                          "DATA_DESCRIPTION table lacks")
        spw, products = descriptions[dd]
        rows = np.flatnonzero((ddid == dd) & ~skipped)
        if not rows.size:
            continue
        epochs = meta["TIME"][rows]
        k1 = feeds.keys(feeds.antennas, meta["ANTENNA1"][rows], meta["FEED1"][rows], spw,
                        epochs)
        k2 = feeds.keys(feeds.antennas, meta["ANTENNA2"][rows], meta["FEED2"][rows], spw,
                        epochs)
        feeds.check(np.concatenate([k1, k2]), products, dd)
        if basis_of(products) == "linear":
            lacking = sorted(set(("XX", "XY", "YX", "YY")) - set(products))
            if lacking:
                raise MSError(f"{str(path)!r}: data description {dd} holds the linear "
                              f"products {products} only, without {lacking}: the feed "
                              "rotation of linear feeds mixes all four, so it cannot be "
                              "removed visibility by visibility; rotate Stokes Q + iU by "
                              "twice the feed rotation after imaging instead")
        with correction.pole_context():
            angles = ReceptorAngleTable(
                feeds.virtual, epochs, meta["FIELD_ID"][rows], k1, k2, fields,
                lambda t: Time(t / 86400.0, format="mjd", scale="utc"), products=products,
                frame=correction.frame, where=str(path), ionosphere=correction.ionosphere)
        plans.append((rows, products, k1, k2, angles,
                      None if channels is None else channels[spw]))
    return plans


def _start(correction, path, columns, overwrite_column, chunk_rows):
    """The run's record of progress (a new one, or an interrupted run's), the columns
    checked, the history asked; and the columns that say what each row is."""
    data_column, corrected_column = columns
    what = f"{data_column} -> {corrected_column}"
    records = column_records(path)
    with _open(path) as table:
        partial = None
        if isinstance(corrected_column, str) and corrected_column in table.colnames():
            partial = table.getcolkeywords(corrected_column).get(_PARTIAL)
        resuming = partial is not None and partial.get("what") == what \
            and partial.get("direction") == correction.direction
        meta = _meta(table)
        firsts = np.unique(meta["DATA_DESC_ID"], return_index=True)[1].tolist()
        check_columns(table, path, data_column, corrected_column, records, firsts,
                      overwrite_column=overwrite_column, resuming=resuming)
        step_rows = _chunk_rows(table, data_column, chunk_rows)
    if not resuming:
        check_column_history(path, records, data_column, corrected_column,
                             correction.direction, correction.redo)
        return Progress(what, correction.direction, step_rows), meta
    # Go on with the chunks of the interrupted run.
    progress_record = Progress.resumed(partial, what, correction.direction)
    if progress_record.unknown and data_column == corrected_column:
        raise MSError(f"{str(path)!r}: an interrupted run left "
                      f"{progress_record.unknown_text(data_column)}; the correction "
                      f"cannot go on from there: restore {data_column} from a copy")
    return progress_record, meta


def _antennas(correction, path, meta):
    """Every antenna of the set as the correction resolves it; those the rows use that
    can be corrected; the orbiting ones, and the mask of the rows they leave alone."""
    where = repr(str(path))
    every = correction.resolve(ms_antennas(path, vertical=correction.vertical,
                                           unusable="keep"), ms_telescopes(path), where)
    used = np.unique(np.concatenate([meta["ANTENNA1"], meta["ANTENNA2"]]))
    antennas, skip = correction.usable(every, used, where, error=MSError)
    skipped = np.isin(meta["ANTENNA1"], skip) | np.isin(meta["ANTENNA2"], skip)
    return every, antennas, skip, skipped


def _blocks(meta, chunking, to_do):
    for index in to_do:
        rows, products, k1, k2, angles, lambda2 = chunking[index]
        epochs, field = meta["TIME"][rows], meta["FIELD_ID"][rows]
        yield Block(rows_of(rows), products, angles.packed,
                    angles.places(epochs, field, k1), angles.places(epochs, field, k2),
                    index, lambda2)


def _write(path, columns, direction, meta, chunking, progress_record, progress, client):
    """Each chunk to do corrected and written (here, or by the client's workers), the
    record of progress kept in the output column's keyword; the rows that came out NaN."""
    data_column, corrected_column = columns
    to_do = progress_record.to_do(len(chunking))
    shared = client is not None  # the workers write their chunks themselves
    late, nan_rows = [], 0
    with _open(path, write=True, shared=shared) as table:
        if corrected_column not in table.colnames():
            with locked(table, shared):
                _add_column(table, data_column, corrected_column)

        def record():
            with locked(table, shared):
                table.putcolkeyword(corrected_column, _PARTIAL, progress_record.keyword())

        # Marked before any row is written: a run killed outright is seen as partial.
        record()
        stream = results(_blocks(meta, chunking, to_do), table, path, columns, direction,
                         client, late, len(to_do))
        try:
            with progress_steps(progress, len(to_do)) as step:
                for block, bad in stream:
                    nan_rows += bad
                    progress_record.add(block.index)
                    # Shared: taking the table's lock costs the workers a reread of it.
                    if not shared or progress_record.since_written() >= RECORD_SECONDS:
                        record()
                    step()
        except BaseException as error:
            stream.close()  # waits for the chunks already sent to workers: into late
            for block, bad in late:
                progress_record.add(block.index, known=bad is not None)
            record()
            with locked(table, shared):
                table.flush()
            message = progress_record.interrupted(path, meta["TIME"].size, data_column,
                                                  corrected_column)
            if isinstance(error, KeyboardInterrupt):
                raise KeyboardInterrupt(message) from None
            if isinstance(error, Exception):
                raise MSError(f"{message} ({type(error).__name__}: {error})") from error
            raise
    return nan_rows


def _finish(path, columns, skipped, step_rows):
    """The rows left alone copied into the output column (when it is another), and the
    record of progress removed: the run is whole."""
    data_column, corrected_column = columns
    with _open(path, write=True) as table:
        if skipped.any() and corrected_column != data_column:
            _copy_rows(table, np.flatnonzero(skipped), data_column, corrected_column,
                       step_rows)
        table.removecolkeyword(corrected_column, _PARTIAL)


def correct_ms(ms, *, data_column=None, corrected_column="CORRECTED_DATA", chunk_rows=None,
               progress=False, client=None, overwrite_column=False, correction=None,
               **options):
    """Remove (or apply) the feed rotation of a Measurement Set's data, in place.

    Reads ``data_column`` in chunks of rows and writes the result into
    ``corrected_column`` of the same Measurement Set; every other column and
    table is left as it was, but for one row added to ``HISTORY``.

    Parameters
    ----------
    ms : str or path-like
        The Measurement Set.
    data_column : str, optional
        The column read: ``'DATA'`` to remove the feed rotation,
        ``corrected_column`` itself to apply it (a model, e.g.
        ``'MODEL_DATA'``, corrupted in place), unless given.
    corrected_column : str, optional
        The column written (``'CORRECTED_DATA'``), a visibility column of
        the type and cell shape of ``data_column``; created when missing, as
        CASA creates it (the description of ``data_column``, tiled storage of
        its own). It may be ``data_column`` itself. An existing column that
        this package did not write (a ``MODEL_DATA``, a ``CORRECTED_DATA``
        that CASA filled) is written only with ``overwrite_column``.
    chunk_rows : int, optional
        Rows read at once (default: 32 MiB of the data column); the extra
        memory is about twice a chunk, plus some 60 bytes per row for the
        columns that say what each row is (time, antennas, feeds, field, data
        description).
    progress : bool or callable, optional
        True shows astropy's progress bar; a callable is called as
        ``progress(done, total)`` after each chunk.
    client : `dask.distributed.Client`, optional
        Correct the chunks on its workers, a few chunks to a task: each
        worker reads, corrects and writes its chunks itself, under casacore's
        table lock (taken for the writing of one chunk at a time), and this
        process records them in order. The result is bit for bit the serial
        one. On Ctrl-C the chunks the workers have taken are waited for
        (a running task cannot be stopped) and recorded.
    overwrite_column : bool, optional
        Write into an existing ``corrected_column`` that this package did
        not write (its values are replaced).

    correction : `~astropy_feedrot.visibilities.Correction`, optional
        The correction's options (direction, frame, convention, vertical,
        pole, feeds, mounts, catalogue, ionosphere, redo), made once...
    **options
        ...or given here, as `~astropy_feedrot.visibilities.Correction`
        takes them. ``feeds`` replace the receptors of ``FEED``; with an
        ionosphere, lambda^2 comes from ``CHAN_FREQ`` of each row's
        spectral window and ``HISTORY`` names the IONEX files.

    Returns
    -------
    pathlib.Path
        The Measurement Set.

    Raises
    ------
    ImportError
        Without python-casacore.
    FileNotFoundError, MSError
        For a path that is not a Measurement Set, a missing ``data_column``,
        an antenna without ``FEED`` rows, receptors of the other basis than
        the products (a circular-linear baseline), Stokes products, a set
        that is read-only or locked by another process, or a correction of a
        column into itself whose interrupted run left chunks in an unknown
        state; nothing is written then.
    CorrectionRefused
        (a ValueError) For a correction the ``HISTORY`` says was made
        already (unless ``redo``), and for columns that cannot be read or
        written as asked (`~astropy_feedrot.visibilities.ms_tables.check_columns`):
        an output column that is no visibility column like ``data_column``
        (``UVW``, ``FLAG``, a name that is no column name), or one this
        package did not write (unless ``overwrite_column``); nothing is
        written then.
    MSError, IonosphereError
        As every correction (`~astropy_feedrot.visibilities.Correction`:
        an aperture array, antennas named with their reasons, an ionosphere
        that does not cover the data); nothing is written then.

    Warns
    -----
    DegenerateGeometryWarning, CatalogueMountWarning, UncorrectedBaselinesWarning
        As every correction (`~astropy_feedrot.visibilities.Correction`):
        rows whose feed rotation is undefined are NaN; rows on baselines to
        an orbiting antenna (``MOUNT`` ``'SPACE-HALCA'``, ``'ORBITING'``)
        are copied from ``data_column``.

    Notes
    -----
    The visibilities of a Measurement Set are :math:`\\langle v_1 v_2^*
    \\rangle` (casacore), corrected with
    `~astropy_feedrot.applied.correction.correct_receptor_visibilities`. Each chunk
    is written as soon as it is corrected, and the output column's keyword
    ``FEEDROT_PARTIAL`` records the rows done until the end. If the run is
    interrupted (Ctrl-C, an error), ``data_column`` is intact unless it is
    the output column; the message says which rows of the output are
    corrected, and running the same call again goes on from there.

    Examples
    --------
    >>> import tarfile, tempfile, pathlib
    >>> from astropy_feedrot.visibilities import correct_ms
    >>> where = pathlib.Path(tempfile.mkdtemp())
    >>> with tarfile.open("tests/data/uvdata/day2_TDEM0003_10s_norx_1src_1spw_2ints"
    ...                   ".ms.tar.gz") as archive:
    ...     archive.extractall(where, filter="data")
    >>> correct_ms(where / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms").name
    'day2_TDEM0003_10s_norx_1src_1spw_2ints.ms'
    """
    correction = Correction.of(correction, **options)
    if data_column is None:
        data_column = "DATA" if correction.direction == "remove" else corrected_column
    columns = (data_column, corrected_column)
    path = ms_path(ms)
    _tables()
    # Before casacore opens anything: it would wait for another process's lock.
    _check_writable(path)
    progress_record, meta = _start(correction, path, columns, overwrite_column, chunk_rows)
    every, antennas, skip, skipped = _antennas(correction, path, meta)
    feed_table = FeedReceptors(path, antennas, correction.feeds)
    plans = _plan(correction, path, meta, feed_table, skipped)
    warn_unusual_angles({feed_table.number[k]: antenna
                         for k, antenna in feed_table.virtual.items()}, str(path))
    step_rows = progress_record.chunk_rows
    chunking = [(rows[k:k + step_rows], products, k1[k:k + step_rows], k2[k:k + step_rows],
                 angles, lambda2) for rows, products, k1, k2, angles, lambda2 in plans
                for k in range(0, rows.size, step_rows)]
    progress_record.count_rows([item[0].size for item in chunking])
    nan_rows = _write(path, columns, correction.direction, meta, chunking, progress_record,
                      progress, client)
    _finish(path, columns, skipped, step_rows)
    _add_history(path, correction.history(" -> ".join(columns)) +
                 correction.ionosphere_text(" ") +
                 ("" if correction.pole == "itrs" else f" (pole={correction.pole})") +
                 (f" (not the baselines to the orbiting antennas "
                  f"{', '.join(map(str, skip))})" if skip else ""))
    total = meta["TIME"].size
    warn_skipped(every, skip, int(np.count_nonzero(skipped)), total, repr(str(path)))
    if nan_rows:
        warn_caller(f"the feed rotation is undefined in {nan_rows} of {total} rows (an "
                    "alt-az antenna pointing at the zenith): their output is NaN",
                    DegenerateGeometryWarning)
    return path


def _copy_corrected(correction, source, target, overwrite, options):
    """A casacore copy of the set beside ``target``, corrected in place, then moved
    onto ``target``; errors name the input, not the copy."""
    work = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}."))
    try:
        temporary = copy_ms(source, work / target.name)
        try:
            correct_ms(temporary, correction=correction, **options)
        except CorrectionRefused as error:  # named as the input, not the copy
            raise type(error)(error.template.replace(str(temporary), str(source))) from None
        except (MSError, IonosphereError) as error:
            raise type(error)(str(error).replace(str(temporary), str(source))) from None
        except KeyboardInterrupt:
            raise KeyboardInterrupt(f"{str(target)!r} was not written (the copy being "
                                    "corrected is removed)") from None
        publish(temporary, target, overwrite=overwrite)
    finally:
        with contextlib.suppress(OSError):
            shutil.rmtree(work)
    return target


def correct_ms_file(correction, source, output, *, overwrite=False, progress=False,
                    client=None, data_column=None, corrected_column="CORRECTED_DATA",
                    overwrite_column=False):
    """The adapter of Measurement Sets (`~astropy_feedrot.visibilities.correction`): in
    place (``output`` None), into a casacore copy (``.ms``: the copy corrected in place,
    ``data_column`` into ``corrected_column``), or through pyuvdata into the format the
    output's extension names.

    Examples
    --------
    >>> import shutil, tempfile, pathlib
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import Correction
    >>> from astropy_feedrot.visibilities.ms import correct_ms_file
    >>> where = pathlib.Path(tempfile.mkdtemp())
    >>> ms = shutil.copytree(sample_file("vla_sim.ms"), where / "vla.ms")
    >>> correct_ms_file(Correction(), ms, where / "copy.ms").name
    'copy.ms'
    """
    columns = dict(data_column=data_column, corrected_column=corrected_column,
                   overwrite_column=overwrite_column)
    if output is None:
        return correct_ms(source, progress=progress, client=client, correction=correction,
                          **columns)
    if check_output_format("ms", output) != "ms":
        refuse_column_options(**columns)
        # pyuvdata reads DATA: what the HISTORY says of it (CASA's too).
        check_column_history(source, column_records(source), "DATA", "DATA",
                             correction.direction, correction.redo)
        return correct_uvdata_file(correction, source, output, overwrite=overwrite,
                                   progress=progress, kind="ms")
    target = check_output_path(source, output, overwrite)
    return _copy_corrected(correction, source, target, overwrite,
                           dict(progress=progress, client=client, **columns))


register_adapter(["ms"], correct_ms_file, ms_telescopes)
