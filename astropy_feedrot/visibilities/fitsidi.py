# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""FITS-IDI files: their antennas, and the feed rotation removed from their data.

* `fitsidi_antennas` reads the ``ARRAY_GEOMETRY`` and ``ANTENNA`` tables into
  `~astropy_feedrot.Antenna` objects (positions, mounts, receptors).
* `correct_fitsidi` writes a copy of a file whose ``UV_DATA`` visibilities
  have the feed rotation of both antennas removed, row by row, a chunk at a time
  so that files larger than memory work.

:doc:`/fitsidi` gives the conventions (visibility conjugation, time, baseline
and Stokes codes) and their sources.
"""

import contextlib
import os
import tempfile
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import FK4, ICRS, SkyCoord
from astropy.time import Time

from ..antennas.receptors import PRODUCT_CODES, basis_of
from ..core.cache import heap_keeps_chunks, release_thread_buffer, thread_buffer
from ..core.exceptions import DegenerateGeometryWarning, warn_caller
from ..core.outputs import new_file_mode, publish, same_file
from ..core.progress import progress_steps
from .antenna_tables import FITSFormatError, fits_telescopes, open_fits, read_antennas
from .catalogue import catalogue_receptors
from .correction import Correction, refuse_column_options, register_adapter
from .fits_bytes import copy_around, header_with_history
from .faraday import correct_rows, fitsidi_lambda_squared, rows_lambda_squared
from .kinds import check_header_cards
from .receptors import ReceptorAngleTable, warn_unusual_angles, with_receptors
from .tasks import in_order, task_groups, worker_count
from .unusable import UnusableAntenna, usable_antennas, warn_skipped

__all__ = ["fitsidi_antennas", "correct_fitsidi", "correct_fitsidi_file", "STOKES_CODES"]

#: The polarization codes of the ``STOKES`` axis (FITS-IDI, UVFITS, casacore,
#: pyuvdata and DiFX agree) that can be corrected:
#: `~astropy_feedrot.antennas.receptors.PRODUCT_CODES`.
STOKES_CODES = PRODUCT_CODES

# Time systems of the TIMSYS keyword, as astropy scales (AIPS says IAT for TAI).
_TIME_SCALES = {"UTC": "utc", "IAT": "tai", "TAI": "tai", "TT": "tt"}

# Bytes of UV_DATA rows corrected at once.
_CHUNK_BYTES = 16 * 2**20

_FLOAT_FORMATS = ("E", "D")


def fitsidi_antennas(path, *, vertical="geodetic", software=None, unusable="raise"):
    """The antennas of a FITS-IDI file.

    Parameters
    ----------
    path : str or os.PathLike
        The FITS-IDI file.
    vertical : {'geodetic', 'geocentric'}, optional
        The local vertical of each `~astropy_feedrot.Antenna`; CASA uses the
        geocentric one.
    software : str, optional
        Whose ``MNTSTA`` convention: ``'fits-idi:difx'``,
        ``'fits-idi:casacore'`` (3.7 and later), ``'fits-idi:casacore<3.7'``,
        ``'fits-idi:casacore<3.2'`` or ``'fits-idi:pyuvdata'``. By default the
        convention of the program that wrote the file
        (`~astropy_feedrot.visibilities.writing_program`).
    unusable : {'raise', 'keep'}, optional
        Raise for an antenna that cannot be described (default), or keep it
        as an `~astropy_feedrot.visibilities.UnusableAntenna` (see
        `~astropy_feedrot.visibilities.antenna_tables.read_antennas`).

    Returns
    -------
    dict
        ``{antenna number: Antenna}``: ``NOSTA``, ``ANNAME``, ``STABXYZ``
        (with ``ARRAYX/Y/Z``, ``FRAME`` and ``XYZHAND``) and ``MNTSTA`` from
        ``ARRAY_GEOMETRY``; receptors (``POLTYA``, ``POLAA``, ``POLTYB``,
        ``POLAB``, one angle per receptor) from ``ANTENNA``.

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    FITSFormatError
        If a table, column or keyword is missing or malformed (non-finite
        positions, a frame other than ITRF, a non-zero array centre from a
        writer other than pyuvdata).
    ValueError
        For a ``MNTSTA`` code whose meaning depends on a writer the file
        does not reveal (6 and up; the message says which ``software=`` to
        pass), a code with no feed-rotation model, receptor angles that
        differ between bands or between rows of one antenna, or a position
        off the Earth; the message names the antenna.

    Examples
    --------
    A DiFX-like file with the VLBA antennas at Pie Town and Los Alamos
    (positions from the package's station list):

    >>> import os, tempfile
    >>> from astropy.io import fits
    >>> from astropy_feedrot.visibilities import fitsidi_antennas
    >>> primary = fits.PrimaryHDU()
    >>> primary.header["CORRELAT"] = "DIFX"
    >>> geometry = fits.BinTableHDU.from_columns([
    ...     fits.Column("ANNAME", "8A", array=["PT", "LA"]),
    ...     fits.Column("STABXYZ", "3D", array=[[-1640953.9, -5014816.0, 3575411.8],
    ...                                         [-1449752.6, -4975298.6, 3709123.8]]),
    ...     fits.Column("NOSTA", "1J", array=[1, 2]),
    ...     fits.Column("MNTSTA", "1J", array=[0, 6])], name="ARRAY_GEOMETRY")
    >>> geometry.header.update(ARRAYX=0.0, ARRAYY=0.0, ARRAYZ=0.0, FRAME="GEOCENTRIC")
    >>> antenna = fits.BinTableHDU.from_columns([
    ...     fits.Column("ANTENNA_NO", "1J", array=[1, 2]),
    ...     fits.Column("POLTYA", "1A", array=["R", "R"]),
    ...     fits.Column("POLAA", "2E", array=[[0, 0], [0, 0]]),
    ...     fits.Column("POLTYB", "1A", array=["L", "L"]),
    ...     fits.Column("POLAB", "2E", array=[[0, 0], [0, 0]])], name="ANTENNA")
    >>> path = os.path.join(tempfile.mkdtemp(), "vlba.idifits")
    >>> fits.HDUList([primary, geometry, antenna]).writeto(path)
    >>> antennas = fitsidi_antennas(path)
    >>> antennas[2].name, antennas[2].mount  # DiFX's 6 is XYNS
    ('LA', XYMount(axis='north'))
    """
    return read_antennas(path, "fits-idi", vertical=vertical, software=software,
                         unusable=unusable)


# --- the layout of UV_DATA ---------------------------------------------------------


def _key(header, key, name, table, kind=float):
    if key not in header:
        raise FITSFormatError(name, table, f"the keyword {key}", None, column=key)
    try:
        return kind(header[key])
    except (TypeError, ValueError):
        raise FITSFormatError(name, table, f"a {kind.__name__} for {key}", str(header[key]),
                              column=key) from None


def _record_dtype(hdu, name):
    """The big-endian record dtype of a binary table's rows, as stored."""
    dtype = hdu.columns.dtype.newbyteorder(">")
    if dtype.itemsize != hdu.header["NAXIS1"]:
        raise FITSFormatError(name, hdu.name, f"rows of {dtype.itemsize} bytes from the "
                              "columns", f"NAXIS1 = {hdu.header['NAXIS1']}")
    return dtype


def _flux_layout(hdu, name):
    """Products, per-row FLUX shape (numpy order), STOKES numpy axis, complex length."""
    header, table = hdu.header, hdu.name
    if "FLUX" not in hdu.columns.names:
        raise FITSFormatError(name, table, "a FLUX column", None, column="FLUX")
    column = hdu.columns["FLUX"]
    if column.format.format not in _FLOAT_FORMATS:
        raise FITSFormatError(name, table, "floating-point visibilities (E or D)",
                              str(column.format), column="FLUX")
    if column.bscale not in (None, 1) or column.bzero not in (None, 0):
        raise FITSFormatError(name, table, "unscaled visibilities (no TSCAL/TZERO)",
                              f"TSCAL {column.bscale}, TZERO {column.bzero}", column="FLUX")
    naxes = _key(header, "MAXIS", name, table, int)
    dims = [_key(header, f"MAXIS{k}", name, table, int) for k in range(1, naxes + 1)]
    types = [str(header.get(f"CTYPE{k}", "")).strip().upper() for k in range(1, naxes + 1)]
    if int(np.prod(dims)) != column.format.repeat:
        raise FITSFormatError(name, table, f"FLUX of {int(np.prod(dims))} numbers per row "
                              f"(MAXIS1..{naxes} = {dims})", str(column.format),
                              column="FLUX")
    if types[0] != "COMPLEX" or dims[0] not in (2, 3):
        raise FITSFormatError(name, table, "axis 1 COMPLEX of length 2 (real, imaginary) or "
                              "3 (real, imaginary, weight)",
                              f"{types[0] or 'no CTYPE1'} of length {dims[0]}",
                              column="CTYPE1")
    if "STOKES" not in types:
        raise FITSFormatError(name, table, "a STOKES axis", str(types), column="CTYPE")
    k = types.index("STOKES") + 1
    crval = _key(header, f"CRVAL{k}", name, table)
    cdelt = _key(header, f"CDELT{k}", name, table)
    crpix = _key(header, f"CRPIX{k}", name, table) if f"CRPIX{k}" in header else 1.0
    codes = crval + cdelt * (np.arange(dims[k - 1]) + 1 - crpix)
    if not np.allclose(codes, np.round(codes)):
        raise FITSFormatError(name, table, "integer polarization codes", str(codes.tolist()),
                              column=f"CRVAL{k}")
    codes = np.round(codes).astype(int).tolist()
    unknown = [c for c in codes if c not in STOKES_CODES]
    if unknown:
        raise ValueError(
            f"{name}, table {table}: polarization codes {unknown} are not correlation "
            f"products of receptors (the codes are {STOKES_CODES}); Stokes parameters "
            "(codes 1-4) cannot be corrected per visibility: rotate Q and U by twice the "
            "feed rotation instead")
    products = [STOKES_CODES[c] for c in codes]
    shape = tuple(reversed(dims))
    return products, shape, naxes - k, dims[0]


def _int_column(records, plan, column):
    bscale, bzero = plan.scales[column]
    values = np.asarray(records[column], dtype=float)
    if bscale not in (None, 1) or bzero not in (None, 0):
        values = values * (bscale or 1) + (bzero or 0)
    return values


def _time_scale(hdul, name):
    """The astropy scale of the file's times (TIMESYS/TIMSYS of ARRAY_GEOMETRY)."""
    for table in ("ARRAY_GEOMETRY", "UV_DATA"):
        header = hdul[table].header if table in hdul else {}
        for key in ("TIMESYS", "TIMSYS"):
            if key in header:
                system = str(header[key]).strip().upper()
                if system not in _TIME_SCALES:
                    raise FITSFormatError(name, table, f"a time system of "
                                          f"{tuple(_TIME_SCALES)}", system, column=key)
                return _TIME_SCALES[system]
    raise FITSFormatError(name, "ARRAY_GEOMETRY", "a TIMSYS keyword (the time system)", None,
                          column="TIMSYS")


def _sky(ra, dec, equinox, pmra, pmdec, epoch, where):
    """A source position from the SOURCE table."""
    label = equinox.strip().upper()
    if label in ("J2000", "J2000.0", "2000", "2000.0"):
        frame = ICRS()
    elif label in ("B1950", "B1950.0", "1950", "1950.0"):
        frame = FK4(equinox="B1950")
    else:
        raise ValueError(f"{where}: equinox {equinox!r} is not supported (J2000 or B1950)")
    if pmra or pmdec:
        # PMRA is the rate of RA (deg/day), so the motion on the sky is
        # PMRA cos(DEC).
        year = epoch if epoch and np.isfinite(epoch) else 2000.0
        return SkyCoord(ra * u.deg, dec * u.deg, frame=frame,
                        pm_ra_cosdec=pmra * np.cos(np.radians(dec)) * u.deg / u.day,
                        pm_dec=pmdec * u.deg / u.day, obstime=Time(year, format="jyear"))
    return SkyCoord(ra * u.deg, dec * u.deg, frame=frame)


def _sources(hdul, name):
    """{source id: SkyCoord} from the SOURCE table."""
    if "SOURCE" not in hdul:
        raise FITSFormatError(name, "SOURCE", "a SOURCE table", None)
    hdu = hdul["SOURCE"]
    columns = hdu.columns.names
    id_column = "SOURCE_ID" if "SOURCE_ID" in columns else "ID_NO."
    for column in (id_column, "RAEPO", "DECEPO"):
        if column not in columns:
            raise FITSFormatError(name, "SOURCE", f"a {column} column", None, column=column)
    data = hdu.data
    equinox = [str(e.decode() if isinstance(e, bytes) else e) for e in data["EQUINOX"]] \
        if "EQUINOX" in columns else None
    if equinox is None and "EPOCH" in columns:
        equinox = [f"J{float(e):.1f}" for e in data["EPOCH"]]
    if equinox is None:
        raise FITSFormatError(name, "SOURCE", "an EQUINOX (or EPOCH) column", None,
                              column="EQUINOX")
    zeros = np.zeros(len(data))
    pmra = np.asarray(data["PMRA"], float) if "PMRA" in columns else zeros
    pmdec = np.asarray(data["PMDEC"], float) if "PMDEC" in columns else zeros
    epoch = np.asarray(data["EPOCH"], float) if "EPOCH" in columns else zeros
    table = {}
    for row in range(len(data)):
        key = int(data[id_column][row])
        ra, dec = float(data["RAEPO"][row]), float(data["DECEPO"][row])
        if not (np.isfinite(ra) and np.isfinite(dec) and -90 <= dec <= 90):
            label = data["SOURCE"][row] if "SOURCE" in columns else ""
            label = (label.decode("ascii", "replace") if isinstance(label, bytes)
                     else str(label)).strip()
            raise FITSFormatError(name, "SOURCE", f"finite RAEPO and DECEPO (degrees) for "
                                  f"source {key}{f' ({label})' if label else ''}",
                                  f"{ra}, {dec}", column="RAEPO")
        entry = (ra, dec, equinox[row].strip().upper(), float(pmra[row]), float(pmdec[row]))
        if key in table and table[key][0] != entry:
            raise FITSFormatError(name, "SOURCE", f"one position per source {key}",
                                  f"{table[key][0][:2]} and {entry[:2]}", column=id_column)
        table[key] = (entry, float(epoch[row]))
    where = f"{name}, table SOURCE"
    return {key: _sky(*entry, epoch, where) for key, (entry, epoch) in table.items()}


def _history(header):
    return "\n".join(str(card) for card in header.get("HISTORY", []))


class _Plan:
    """What correcting one UV_DATA table needs."""

    def __init__(self, hdul, index, name):
        hdu = hdul[index]
        self.index = index
        self.table = f"UV_DATA (extension {index})"
        self.dtype = _record_dtype(hdu, name)
        self.rows = int(hdu.header["NAXIS2"])
        self.offset = int(hdul.fileinfo(index)["datLoc"])
        needed = self.rows * self.dtype.itemsize
        available = os.path.getsize(hdul.filename()) - self.offset
        if available < needed:
            raise FITSFormatError(name, self.table, f"{needed} bytes of rows (NAXIS2 = "
                                  f"{self.rows})", f"{max(available, 0)} bytes: the file is "
                                  "cut short", None)
        self.products, self.shape, self.stokes_axis, self.complex = _flux_layout(hdu, name)
        if basis_of(self.products) == "linear":  # also refuses mixed products
            missing = [p for p in ("XX", "XY", "YX", "YY") if p not in self.products]
            if missing:
                raise ValueError(
                    f"{name}, table UV_DATA: linear products {self.products} lack {missing}: "
                    "the feed rotation of linear feeds mixes XX, XY, YX and YY, so it "
                    "cannot be removed visibility by visibility without all four. With "
                    "parallel hands only, rotate Stokes Q and U by twice the feed rotation "
                    "after imaging (feed_rotation_rows gives the angles of every row)")
        columns = hdu.columns.names
        for column in ("BASELINE", "DATE", "TIME"):
            if column not in columns:
                raise FITSFormatError(name, "UV_DATA", f"a {column} column", None,
                                      column=column)
        self.source_column = next((c for c in ("SOURCE_ID", "SOURCE") if c in columns), None)
        self.weight_column = "WEIGHT" if "WEIGHT" in columns else None
        # Plain values only: a plan goes to dask workers.
        self.scales = {c.name: (c.bscale, c.bzero) for c in hdu.columns}
        # Antennas whose rows are left as they are (orbiting), and how many rows.
        self.skip, self.skipped_rows = (), 0
        # With an ionosphere: the FREQID column and {FREQID: lambda^2 of the samples}.
        self.freqid, self.faraday = None, None


def _rows_of(plan, records, name):
    """Antennas, times (jd1, jd2) and source ids of a chunk of rows."""
    baseline = _int_column(records, plan, "BASELINE")
    if not np.all(np.isfinite(baseline)):
        raise FITSFormatError(name, "UV_DATA", "finite baseline numbers", "NaN",
                              column="BASELINE")
    baseline = np.floor(baseline).astype(np.int64)
    a1, a2 = baseline // 256, baseline % 256
    bad = (a1 < 1) | (a1 > 255) | (a2 < 1)
    if bad.any():
        raise FITSFormatError(name, "UV_DATA", "BASELINE = 256 * antenna1 + antenna2 with "
                              "antennas 1-255 (no larger antenna numbers are defined for "
                              "FITS-IDI)", str(int(baseline[bad][0])), column="BASELINE")
    date = _int_column(records, plan, "DATE")
    time = _int_column(records, plan, "TIME")
    if plan.source_column is None:
        source = None
    else:
        source = _int_column(records, plan, plan.source_column).astype(int)
    return a1, a2, date, time, source


def _row_sources(plan, records, sources, name):
    """Antennas, Julian dates (one float) and source ids of rows, the ids checked."""
    a1, a2, date, time, source = _rows_of(plan, records, name)
    if source is None:
        if len(sources) != 1:
            raise FITSFormatError(name, "UV_DATA", "a SOURCE_ID (or SOURCE) column when the "
                                  "SOURCE table has several sources", None,
                                  column="SOURCE_ID")
        source = np.full(len(a1), next(iter(sources)))
    missing = sorted(set(np.unique(source).tolist()) - set(sources))
    if missing:
        raise FITSFormatError(name, "UV_DATA", "source ids of the SOURCE table "
                              f"{sorted(sources)}", str(missing), column=plan.source_column)
    return a1, a2, date + time, source


def _angle_table(path, plan, antennas, sources, scale, frame, name, per_chunk, note="",
                 ionosphere=None):
    """The receptors' position angles of every row of one UV_DATA table, computed once
    per distinct epoch, source and antenna (the rows' few metadata bytes are read, a
    chunk mapped at a time)."""
    parts = []
    for start in range(0, plan.rows, per_chunk):
        stop = min(start + per_chunk, plan.rows)
        records = np.memmap(path, dtype=plan.dtype, mode="r",
                            offset=plan.offset + start * plan.dtype.itemsize,
                            shape=(stop - start,))
        try:
            parts.append(_row_sources(plan, records, sources, name))
        finally:
            del records
    a1, a2, jd, source = (np.concatenate(values) for values in zip(*parts))
    # Rows on baselines to an orbiting antenna are left as they are (plan.skip).
    antennas, skipped = usable_antennas(antennas, np.concatenate([a1, a2]),
                                        f"{name}, table UV_DATA")
    plan.skip = tuple(skipped)
    if skipped:
        kept = ~(np.isin(a1, skipped) | np.isin(a2, skipped))
        plan.skipped_rows = int(np.count_nonzero(~kept))
        a1, a2, jd, source = a1[kept], a2[kept], jd[kept], source[kept]
        if not a1.size:
            return None
    return ReceptorAngleTable(
        antennas, jd, source, a1, a2, sources, lambda t: Time(t, format="jd", scale=scale),
        products=plan.products, frame=frame, where=f"{name}, table UV_DATA",
        hint="the ANTENNA table has no row for it; give the feeds (feeds=Receptors(...), "
             "or --feeds R,L on the command line)" + (f"; {note}" if note else ""),
        ionosphere=ionosphere)


def _correct_chunk(records, plan, table, sources, name, direction):
    """Correct the FLUX of a chunk of records in place, but the rows on baselines to
    the antennas ``plan.skip``; the number of NaN rows."""
    if plan.skip:
        a1, a2 = _rows_of(plan, records, name)[:2]
        kept = ~(np.isin(a1, plan.skip) | np.isin(a2, plan.skip))
        if not kept.all():
            if not kept.any():
                return 0
            rows = records[kept]  # a copy, corrected and put back
            count = _correct_rows(rows, plan, table, sources, name, direction)
            records[kept] = rows
            return count
    return _correct_rows(records, plan, table, sources, name, direction)


def _correct_rows(records, plan, table, sources, name, direction):
    """Correct the FLUX of records in place; the number of NaN rows."""
    a1, a2, jd, source = _row_sources(plan, records, sources, name)
    n = len(a1)
    # Corrected where they lie, in the file's byte order (the rows are this thread's
    # own buffer): numpy's loops swap the bytes of a block at a time in the cache,
    # in the precision stored, and the chunk is neither copied nor swapped.
    flux = records["FLUX"].reshape((n,) + plan.shape)
    if plan.complex == 2:
        # (real, imaginary) pairs are complex numbers as they lie, corrected in place
        # (E: complex64, D: complex128).
        vis = flux.view(np.dtype(f">c{2 * flux.dtype.itemsize}"))[..., 0]
    else:
        vis = np.empty(flux.shape[:-1], dtype=np.result_type(flux.dtype, np.complex64))
        vis.real, vis.imag = flux[..., 0], flux[..., 1]
    axis = plan.stokes_axis + 1
    moved = np.moveaxis(vis, axis, -1)
    freqid = None if plan.freqid is None else _int_column(records, plan, plan.freqid)
    lambda2, per_row = (None, False) if plan.faraday is None else \
        rows_lambda_squared(plan.faraday, freqid)
    bad = correct_rows(moved, table.table, table.rm, table.places(jd, source, a1),
                       table.places(jd, source, a2), plan.products, lambda2=lambda2,
                       per_row=per_row, conjugate=True, direction=direction)
    if plan.complex != 2:
        flux[..., 0], flux[..., 1] = vis.real, vis.imag
    if bad.any():
        flux[bad, ..., 0:2] = np.nan
        if plan.complex == 3:
            flux[bad, ..., 2] = 0.0
        elif plan.weight_column:
            weights = records[plan.weight_column]
            weights[bad] = 0
    return int(np.count_nonzero(bad))


def _chunk_task(source, target, plan, start, stop, shift, table, sources, name, direction):
    """Correct rows [start, stop) of one UV_DATA table: read from ``source``, corrected
    in memory, written to the same rows of ``target``, ``shift`` bytes further (its
    primary header is longer); the number of NaN rows. A dask task too: chunks are
    disjoint byte ranges of the output."""
    offset = plan.offset + start * plan.dtype.itemsize
    # In a buffer this thread keeps for its next chunks (kept.thread_buffer).
    records = thread_buffer(plan.dtype, (stop - start,))
    with open(source, "rb") as fin:
        fin.seek(offset)
        if fin.readinto(records.view(np.uint8)) != records.nbytes:
            raise FITSFormatError(name, plan.table, f"{records.nbytes} bytes of rows from "
                                  f"byte {offset}", "fewer: the file changed while it was "
                                  "read", None)
    count = _correct_chunk(records, plan, table, sources, name, direction)
    with open(target, "r+b") as fout:
        fout.seek(offset + shift)
        fout.write(records.view(np.uint8))
    return count


def _chunk_run(source, target, items, shift, table, sources, name, direction):
    """A dask task: chunks (plan, start, stop) of one UV_DATA table in turn; their NaN
    rows."""
    return [_chunk_task(source, target, plan, start, stop, shift, table, sources, name,
                        direction) for plan, start, stop in items]


def _chunks(work, client, source, target, shift, tables, sources, name, direction):
    """The NaN rows of each chunk, corrected here or, with a client, on dask workers
    (two tasks of a few chunks, `~astropy_feedrot.visibilities.tasks.task_groups`, per
    worker at a time; the angle tables sent to each worker once)."""
    if client is None:
        try:
            for plan, start, stop in work:
                yield _chunk_task(source, target, plan, start, stop, shift,
                                  tables[plan.index], sources, name, direction)
        finally:
            release_thread_buffer()  # this process keeps no chunk after the run
        return
    tables = {k: client.scatter(table, broadcast=True) for k, table in tables.items()}
    sources = client.scatter(sources, broadcast=True)
    workers = worker_count(client)

    def submit(group):
        return client.submit(_chunk_run, source, target, group, shift,
                             tables[group[0][0].index], sources, name, direction, pure=False)

    client.run(heap_keeps_chunks)
    try:
        groups = task_groups(work, len(work), workers, key=lambda item: item[0].index)
        for _, counts in in_order(groups, submit, workers, []):
            yield from counts
    finally:
        with contextlib.suppress(Exception):
            client.run(heap_keeps_chunks, False)


def _check_paths(path, output, overwrite):
    source = os.fspath(path)
    target = os.fspath(output)
    if not os.path.isfile(source):
        raise FileNotFoundError(f"no such file: {source!r}")
    if same_file(Path(source).resolve(), Path(target).resolve()):
        raise ValueError(f"output {target!r} is the input file; write the corrected copy to "
                         "another path (the input is never modified)")
    if os.path.isdir(target):
        raise IsADirectoryError(f"output {target!r} is a directory; give a file name")
    if os.path.exists(target) and not overwrite:
        raise FileExistsError(f"output {target!r} exists; pass overwrite=True to replace it")
    with open(source, "rb") as fh:
        if fh.read(6) != b"SIMPLE":
            raise FITSFormatError(source, "primary header", "an uncompressed FITS file "
                                  "(beginning with SIMPLE)", None)
    return source, target


def _read_header(correction, source):
    """The UV_DATA tables, time scale, sources, end of the primary header and telescope
    of a file, its history asked first."""
    with open_fits(source) as hdul:
        check_header_cards(hdul, source)
        primary = hdul[0].header
        correction.check_history(_history(primary), f"{source} (HISTORY of the primary "
                                 "header)")
        indices = [k for k, hdu in enumerate(hdul) if hdu.name == "UV_DATA"]
        if not indices:
            raise FITSFormatError(source, "UV_DATA", "a UV_DATA table", None)
        return (indices, _time_scale(hdul, source), _sources(hdul, source),
                int(hdul.fileinfo(0)["datLoc"]), str(primary.get("TELESCOP", "")).strip())


def _antennas(correction, source, software, telescope):
    """Every antenna, resolved, with the receptors the user or the catalogue gives;
    what the catalogue's receptors note says."""
    antennas = correction.resolve(
        fitsidi_antennas(source, vertical=correction.vertical, software=software,
                         unusable="keep"), fits_telescopes(source), source)
    ground = {n: a for n, a in antennas.items() if not isinstance(a, UnusableAntenna)}
    if correction.feeds is not None:
        ground = with_receptors(ground, correction.feeds)
    ground, note = catalogue_receptors(ground, correction.catalogue, telescope=telescope)
    antennas.update(ground)
    warn_unusual_angles(ground, source)
    return antennas, note


def _temporary(target):
    """A new file beside ``target``, with the mode of a new file (or of the one it
    replaces)."""
    directory = os.path.dirname(os.path.abspath(target))
    handle, temporary = tempfile.mkstemp(dir=directory, prefix=f".{os.path.basename(target)}.",
                                         suffix=".part")
    os.close(handle)
    # mkstemp makes the file 0600: the copy gets the mode of a new file under the umask
    # (or of the file it replaces), as every other output.
    os.chmod(temporary, new_file_mode(Path(target)))
    return temporary


def _write_copy(correction, source, temporary, new_header, header_end, indices, described,
                chunk_bytes, progress, client):
    """Everything but the rows copied byte for byte, then the rows corrected a chunk at a
    time into their places; the plans and the NaN rows."""
    antennas, note, sources, scale = described
    with open_fits(source) as hdul:
        plans = [_Plan(hdul, index, source) for index in indices]
        for plan in plans if correction.ionosphere is not None else ():
            plan.freqid, plan.faraday = fitsidi_lambda_squared(hdul, plan.index, source)
    shift = copy_around(source, temporary, new_header, header_end,
                        [(plan.offset, plan.offset + plan.rows * plan.dtype.itemsize)
                         for plan in plans])
    work = []
    for plan in plans:
        per_chunk = max(1, chunk_bytes // max(plan.dtype.itemsize, 1))
        work += [(plan, start, min(start + per_chunk, plan.rows))
                 for start in range(0, plan.rows, per_chunk)]
    with correction.pole_context():
        tables = {plan.index: _angle_table(source, plan, antennas, sources, scale,
                                           correction.frame, source,
                                           max(1, chunk_bytes // plan.dtype.itemsize),
                                           note, correction.ionosphere)
                  for plan in plans if plan.rows}
    nan_rows = 0
    with progress_steps(progress, len(work)) as step:
        for count in _chunks(work, client, source, temporary, shift, tables, sources,
                             source, correction.direction):
            nan_rows += count
            step()
    return plans, nan_rows


def correct_fitsidi_file(correction, source, output, *, overwrite=False, progress=False,
                         client=None, **columns):
    """The adapter of FITS-IDI files (`~astropy_feedrot.visibilities.correction`): a
    corrected copy, never in place.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import Correction
    >>> from astropy_feedrot.visibilities.fitsidi import correct_fitsidi_file
    >>> correct_fitsidi_file(Correction(), sample_file("difx_k08161.idifits"), None)
    Traceback (most recent call last):
    ...
    ValueError: a FITS-IDI file is corrected into a copy, never in place: give the output
    """
    refuse_column_options(**columns)
    if output is None:
        raise ValueError("a FITS-IDI file is corrected into a copy, never in place: give the "
                         "output")
    return Path(correct_fitsidi(source, output, overwrite=overwrite, progress=progress,
                                client=client, correction=correction))


def correct_fitsidi(path, output, *, overwrite=False, progress=False, software=None,
                    chunk_bytes=None, client=None, correction=None, **options):
    """Write a copy of a FITS-IDI file with the feed rotation removed from its visibilities.

    Each row of each ``UV_DATA`` table (a baseline, a time, a source) has
    the feed rotation of both its antennas, plus their receptor angles
    (``POLAA``, ``POLAB``), removed from ``FLUX``: the output holds the
    visibilities of receptors fixed on the sky. The input is not modified.

    Parameters
    ----------
    path : str or os.PathLike
        The FITS-IDI file.
    output : str or os.PathLike
        The file to write (not the input).
    overwrite : bool, optional
        Replace ``output`` if it exists.
    progress : bool or callable, optional
        True shows astropy's `~astropy.utils.console.ProgressBar` over the
        chunks of rows; a callable is called as ``progress(done, total)``
        after each chunk.
    software : str, optional
        The ``MNTSTA`` convention, as in `fitsidi_antennas`.
    chunk_bytes : int, optional
        Bytes of rows corrected at once (default 16 MiB): the memory used
        is a few times this, whatever the size of the file.
    client : `dask.distributed.Client`, optional
        Correct the chunks on its workers (each maps and writes its own rows
        of the copy); the output is bit for bit the serial one.
    correction : `~astropy_feedrot.visibilities.Correction`, optional
        The correction's options (direction, frame, convention, vertical,
        pole, feeds, mounts, catalogue, ionosphere, redo), made once...
    **options
        ...or given here, as `~astropy_feedrot.visibilities.Correction`
        takes them. Antennas that neither the file nor ``feeds`` give
        receptors take the catalogue's (by name, else by position, else by
        the primary header's ``TELESCOP``); ``mounts`` compares ``MNTSTA``
        with it.

    Returns
    -------
    str
        The path of the output.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    FileExistsError
        If ``output`` exists and ``overwrite`` is False.
    FITSFormatError
        For a file that is not uncompressed FITS-IDI or lacks what the
        correction needs (tables, columns, keywords, time system, source
        positions, valid baselines).
    ValueError, IonosphereError
        As every correction (`~astropy_feedrot.visibilities.Correction`);
        and if ``output`` is the input, for Stokes parameters instead of
        correlation products, linear products without all four, receptors of
        the other basis or missing, and everything `fitsidi_antennas` refuses
        but orbiting antennas.

    Warns
    -----
    DegenerateGeometryWarning, CatalogueMountWarning, UncorrectedBaselinesWarning
        As every correction (`~astropy_feedrot.visibilities.Correction`):
        rows whose feed rotation is undefined get a NaN ``FLUX`` and weight
        0; rows on baselines to an orbiting antenna (``MNTSTA`` 2) are left
        byte for byte as they were.

    Notes
    -----
    The input is copied to a temporary file beside ``output``, with one
    HISTORY card added to the primary header, all but the ``UV_DATA`` rows;
    these are read ``chunk_bytes`` at a time, corrected in memory and
    written to their place in the copy, which is then renamed to
    ``output``. Everything but ``FLUX`` (and the
    weights of NaN rows) is byte for byte the input. FITS-IDI stores the
    complex conjugate of :math:`\\langle v_1 v_2^* \\rangle` (casacore's
    ``FitsIDItoMS.cc`` and DiFX's ``fitsUV.c``, see :doc:`/fitsidi`), so the
    correction is made with ``conjugate=True``.

    Examples
    --------
    See :doc:`/fitsidi` for a complete file. The marker written to the
    primary header:

    >>> from astropy_feedrot.visibilities import HISTORY_MARK
    >>> HISTORY_MARK
    'Feed rotation removed by astropy_feedrot'
    """
    correction = Correction.of(correction, **options)
    source, target = _check_paths(path, output, overwrite)
    chunk_bytes = _CHUNK_BYTES if chunk_bytes is None else int(chunk_bytes)
    if chunk_bytes < 1:
        raise ValueError(f"chunk_bytes must be positive, got {chunk_bytes}")
    indices, scale, sources, header_end, telescope = _read_header(correction, source)
    antennas, note = _antennas(correction, source, software, telescope)
    new_header = header_with_history(source, header_end, correction.history(
        "UV_DATA FLUX, the feed rotation and receptor angles (POLAA, POLAB) of "
        "both antennas of every row" + correction.ionosphere_text(" ")))
    temporary = _temporary(target)
    try:
        plans, nan_rows = _write_copy(correction, source, temporary, new_header, header_end,
                                      indices, (antennas, note, sources, scale),
                                      chunk_bytes, progress, client)
        publish(temporary, target, overwrite=overwrite)  # exclusive without overwrite
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise
    total_rows = sum(plan.rows for plan in plans)
    if nan_rows:
        warn_caller(f"the feed rotation is undefined in {nan_rows} of {total_rows} rows (an "
                    "alt-az antenna pointing at the zenith, or an equatorial one at the "
                    "pole): their FLUX is NaN and their weight 0", DegenerateGeometryWarning)
    warn_skipped(antennas, sorted({n for plan in plans for n in plan.skip}),
                 sum(plan.skipped_rows for plan in plans), total_rows, source)
    return target


register_adapter(["fits-idi"], correct_fitsidi_file, fits_telescopes)
