# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The antenna tables of FITS-IDI and UVFITS files, and who wrote them.

Both formats describe the antennas in a binary table: ``ARRAY_GEOMETRY``
(positions and ``MNTSTA``) and ``ANTENNA`` (receptors) in FITS-IDI, ``AIPS
AN`` (both) in UVFITS. `read_antennas` turns them into
`~astropy_feedrot.Antenna` objects; `writing_program` finds the program that
wrote the file, which decides what the ``MNTSTA`` codes 6 and 7 mean
(`astropy_feedrot.stations.labels`). :doc:`/fitsidi` gives the conventions and their
sources.
"""

import os
from typing import NamedTuple

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.io import fits

from ..antennas.receptors import Receptors
from ..engine.antenna import Antenna
from ..io import FileFormatError
from ..stations.labels import SOFTWARE, is_orbiting, mount_from_label
from .unusable import UnusableAntenna, check_unusable, orbiting_reason

__all__ = ["FITSFormatError", "WritingProgram", "writing_program", "read_antennas",
           "fits_telescopes",
           "open_fits", "FORMATS"]

#: The file formats and the table that holds their antennas' positions.
FORMATS = {"fits-idi": "ARRAY_GEOMETRY", "uvfits": "AIPS AN"}

# Codes 0-5 mean the same to every writer (alt-az, equatorial, orbiting,
# X-Y east-west, Nasmyth right and left); 6 and up do not.
_COMMON_CODES = (0, 1, 2, 3, 4, 5)

# FRAME values read as the terrestrial frame (ITRF): casacore writes 'ITRF',
# DiFX 'GEOCENTRIC', pyuvdata 'ITRF'.
_FRAMES = ("ITRF", "GEOCENTRIC", "ITRS")


class FITSFormatError(FileFormatError):
    """A FITS file does not follow the format it is read as.

    The message names the file, the table (extension) and, where it applies,
    the column or keyword, what was found and what was expected.

    Parameters
    ----------
    filename : str
        Name of the file.
    table : str
        The extension (``'UV_DATA'``, ``'AIPS AN'``, ``'primary header'``...).
    expected : str
        What the format requires.
    found : str or None
        What the file holds (None when it is missing).
    column : str, optional
        The column or keyword.

    Attributes
    ----------
    filename, table, column, expected, found
        As given; ``lineno`` is None.

    Examples
    --------
    >>> from astropy_feedrot.io import FileFormatError
    >>> from astropy_feedrot.visibilities import FITSFormatError
    >>> err = FITSFormatError("exp.idifits", "UV_DATA", "an integer column", "1E",
    ...                       column="BASELINE")
    >>> print(err)
    exp.idifits, table UV_DATA, column BASELINE: expected an integer column, got '1E'
    >>> isinstance(err, FileFormatError)
    True
    """

    def __init__(self, filename, table, expected, found, column=None):
        self.filename = filename
        self.table = table
        self.column = column
        self.expected = expected
        self.found = found
        self.lineno = None
        where = f"{filename}, table {table}" + (f", column {column}" if column else "")
        got = "nothing" if found is None else repr(found)
        ValueError.__init__(self, f"{where}: expected {expected}, got {got}")

    def __reduce__(self):
        return (type(self), (self.filename, self.table, self.expected, self.found,
                             self.column))


class WritingProgram(NamedTuple):
    """The program that wrote a FITS-IDI or UVFITS file, as its headers tell.

    Attributes
    ----------
    program : str
        ``'casacore'`` (CASA ``exportuvfits``), ``'difx'``, ``'pyuvdata'``,
        ``'aips'`` or ``'unknown'``.
    software : str or None
        The `~astropy_feedrot.stations.labels.SOFTWARE` convention of its ``MNTSTA``
        codes, or None when the headers do not tell it.
    codes : tuple of int or None
        Without ``software``, the codes that can still be read (those that
        mean the same to every writer); None when ``software`` is known.
    reason : str
        How the program was recognised and, without ``software``, what to
        pass as ``software=``.

    Examples
    --------
    >>> from astropy_feedrot.visibilities import WritingProgram
    >>> WritingProgram("difx", "fits-idi:difx", None, "CORRELAT = 'DIFX'").software
    'fits-idi:difx'
    """

    program: str
    software: object
    codes: object
    reason: str


def open_fits(path):
    """Open a FITS file for reading, memory-mapped.

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    `~astropy.io.fits.HDUList`
        Opened read-only with ``memmap=True``; close it (or use ``with``).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    FITSFormatError
        If the file is not a FITS file.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy.io import fits
    >>> from astropy_feedrot.visibilities import open_fits
    >>> path = os.path.join(tempfile.mkdtemp(), "empty.fits")
    >>> fits.PrimaryHDU().writeto(path)
    >>> with open_fits(path) as hdul:
    ...     len(hdul)
    1
    """
    name = os.fspath(path)
    if not os.path.isfile(name):
        raise FileNotFoundError(f"no such file: {name!r}")
    try:
        hdul = fits.open(name, mode="readonly", memmap=True, lazy_load_hdus=False)
    except OSError as error:
        raise FITSFormatError(name, "primary header", "a FITS file", str(error)) from None
    return hdul


def _kind(hdul, name):
    """'fits-idi' or 'uvfits', from the tables the file holds."""
    names = {hdu.name for hdu in hdul}
    if "ARRAY_GEOMETRY" in names:
        return "fits-idi"
    if "AIPS AN" in names:
        return "uvfits"
    raise FITSFormatError(name, "ARRAY_GEOMETRY", "an ARRAY_GEOMETRY table (FITS-IDI) or an "
                          "'AIPS AN' table (UVFITS)", f"only {sorted(names)}")


def _history(header):
    """The HISTORY cards of a header as one string (cards joined without breaks)."""
    return "".join(str(card) for card in header.get("HISTORY", []))


def _text(header, key):
    return str(header.get(key, "")).strip()


def _tables(hdul, name, extname):
    """The extensions ``extname`` (one per array); FITSFormatError if there is none."""
    found = [hdu for hdu in hdul if hdu.name == extname]
    if not found:
        raise FITSFormatError(name, extname, f"the {extname} table", None)
    for hdu in found:
        if not isinstance(hdu, fits.BinTableHDU):
            raise FITSFormatError(name, extname, "a binary table", type(hdu).__name__)
    return found


def _table(hdul, name, extname):
    """The one extension ``extname``; FITSFormatError if missing or repeated."""
    found = _tables(hdul, name, extname)
    if len(found) > 1:
        raise FITSFormatError(name, extname, f"one {extname} table (several arrays or "
                              "subarrays are not supported; split the file)",
                              f"{len(found)} tables")
    return found[0]


def _codes(tables):
    """The MNTSTA codes of all antenna tables."""
    codes = set()
    for hdu in tables:
        if "MNTSTA" in hdu.columns.names:
            codes |= {int(c) for c in np.ravel(hdu.data["MNTSTA"])}
    return codes


def _column(hdu, name, column, table=None):
    table = table or hdu.name
    if column not in hdu.columns.names:
        raise FITSFormatError(name, table, f"a {column} column", None, column=column)
    return hdu.data[column]


def _detect(hdul, name, kind):
    """WritingProgram of an open file."""
    primary = hdul[0].header
    # FITS-IDI holds one ARRAY_GEOMETRY table per array (EXTVER, AIPS Memo 114).
    tables = (_tables(hdul, name, FORMATS[kind]) if kind == "fits-idi"
              else [_table(hdul, name, FORMATS[kind])])
    history = _history(primary)
    origin = _text(primary, "ORIGIN")
    correlator = _text(primary, "CORRELAT").upper()
    if origin.lower().startswith("casacore"):
        codes = _codes(tables)
        base = f"ORIGIN = {origin!r} (casacore's MSFitsOutput, e.g. CASA exportuvfits)"
        if max(codes, default=0) >= 8:
            return WritingProgram("casacore", "fits-idi:casacore", None,
                                  base + "; MNTSTA 8 or 9 occurs, which only casacore 3.7 "
                                  "and later write")
        if max(codes, default=0) <= 3:
            return WritingProgram("casacore", "fits-idi:casacore", None,
                                  base + "; MNTSTA 0-3 only, which mean the same in every "
                                  "casacore version")
        return WritingProgram(
            "casacore", None, _COMMON_CODES,
            base + "; casacore does not write its version, and its codes 6 and 7 mean "
            "beam waveguides from 3.7 on but BIZARRE and SPACE-HALCA/unknown in 3.2-3.6 "
            "(before 3.2, 4 was BIZARRE): pass software='fits-idi:casacore' (3.7 or later), "
            "'fits-idi:casacore<3.7' (3.2-3.6) or 'fits-idi:casacore<3.2' (2.0-3.1)")
    if correlator == "DIFX" or "CORRELATOR = 'DIFX'" in history.upper():
        return WritingProgram("difx", "fits-idi:difx", None,
                              "CORRELAT = 'DIFX' (difx2fits)")
    if "pyuvdata" in history.lower() or any("HASMNT" in t.header for t in tables):
        if all(t.header.get("HASMNT", False) for t in tables):
            return WritingProgram("pyuvdata", "fits-idi:pyuvdata", None,
                                  "HISTORY names pyuvdata and HASMNT = T")
        return WritingProgram(
            "pyuvdata", None, (),
            "HISTORY names pyuvdata but HASMNT is not true: pyuvdata before 3.2, or "
            "without known mounts, wrote MNTSTA 0 (and POLAA 90, POLAB 0) for every "
            "antenna as placeholders; pass software='fits-idi:pyuvdata' only if you know "
            "the codes are right")
    program = "aips" if "AIPS" in origin.upper() or "RELEASE =" in history.upper() \
        else "unknown"
    what = "AIPS" if program == "aips" else "an unrecognised program"
    return WritingProgram(
        program, None, _COMMON_CODES,
        f"written by {what}: codes 0-5 mean the same to every writer, but 6 and 7 mean beam "
        "waveguides to casacore 3.7 and later, XYNS and other to DiFX, phased and fixed to "
        "pyuvdata; pass software='fits-idi:casacore', 'fits-idi:difx' or "
        "'fits-idi:pyuvdata'")


def writing_program(path):
    """The program that wrote a FITS-IDI or UVFITS file, and its ``MNTSTA`` convention.

    Parameters
    ----------
    path : str or os.PathLike
        A FITS-IDI file (with an ``ARRAY_GEOMETRY`` table) or a UVFITS file
        (with an ``AIPS AN`` table).

    Returns
    -------
    WritingProgram
        The program, the label convention of its ``MNTSTA`` codes (None if
        the headers do not tell it), the codes readable without it, and how
        it was recognised.

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    FITSFormatError
        If the file is not FITS, or has no (or several) antenna tables.

    Notes
    -----
    In this order: ``ORIGIN`` beginning with ``casacore`` (casacore's
    ``MSFitsOutput``, CASA ``exportuvfits``; the version is not written, so
    it is taken from the codes only when they settle it: an 8 or 9 means 3.7
    or later, codes 0-3 only mean the same in every version); ``CORRELAT =
    'DIFX'`` (difx2fits); a HISTORY card naming pyuvdata, or the ``HASMNT``
    keyword of pyuvdata 3.2 and later (without ``HASMNT = T`` the codes are
    placeholders and none is read); ``ORIGIN`` naming AIPS or an AIPS
    ``RELEASE`` HISTORY card; otherwise unknown. AIPS and unknown writers
    keep codes 0-5, which every writer agrees on.

    Examples
    --------
    >>> import os, tempfile
    >>> import numpy as np
    >>> from astropy.io import fits
    >>> from astropy_feedrot.visibilities import writing_program
    >>> primary = fits.PrimaryHDU()
    >>> primary.header["CORRELAT"] = "DIFX"
    >>> table = fits.BinTableHDU.from_columns(
    ...     [fits.Column("MNTSTA", "1J", array=np.array([0, 6]))], name="ARRAY_GEOMETRY")
    >>> path = os.path.join(tempfile.mkdtemp(), "difx.idifits")
    >>> fits.HDUList([primary, table]).writeto(path)
    >>> writing_program(path)[:3]
    ('difx', 'fits-idi:difx', None)
    """
    name = os.fspath(path)
    with open_fits(name) as hdul:
        return _detect(hdul, name, _kind(hdul, name))


def _where(hdu, count):
    """The name of an antenna table in messages (with its EXTVER among several)."""
    if count > 1:
        return f"{hdu.name} (EXTVER {hdu.header.get('EXTVER', '?')})"
    return hdu.name


def _positions(hdu, name, program):
    """Absolute ITRF positions (N, 3) in m from STABXYZ and the array centre."""
    table = hdu.name
    header = hdu.header
    stab = np.asarray(_column(hdu, name, "STABXYZ"), dtype=float)
    if stab.ndim != 2 or stab.shape[1] != 3:
        raise FITSFormatError(name, table, "3 numbers per antenna", f"shape {stab.shape}",
                              column="STABXYZ")
    centre = []
    for key in ("ARRAYX", "ARRAYY", "ARRAYZ"):
        if key not in header:
            raise FITSFormatError(name, table, f"the keyword {key} (the array centre)", None,
                                  column=key)
        try:
            centre.append(float(header[key]))
        except (TypeError, ValueError):
            raise FITSFormatError(name, table, "a number", str(header[key]),
                                  column=key) from None
    centre = np.array(centre)
    if not np.all(np.isfinite(centre)):
        raise FITSFormatError(name, table, "a finite array centre", str(list(centre)),
                              column="ARRAYX")
    frame = _text(header, "FRAME").upper()
    if frame and set(frame) == {"?"} and np.all(centre == 0):
        frame = ""  # AIPS writes '?????' for an unset frame
    if frame and frame not in _FRAMES:
        raise FITSFormatError(name, table, f"FRAME one of {_FRAMES} (Earth-fixed positions "
                              "in m); positions in another frame or on another body are "
                              "not supported", frame, column="FRAME")
    if not frame and _text(header, "ARRNAM").upper() == "VLA":
        raise FITSFormatError(name, table, "a FRAME keyword: without one, a VLA file may "
                              "hold the old VLA (MODCOMP) frame that casacore rotates by the "
                              "VLA longitude", None, column="FRAME")
    hand = _text(header, "XYZHAND").upper()
    if hand not in ("", "RIGHT", "LEFT"):
        raise FITSFormatError(name, table, "XYZHAND 'RIGHT' or 'LEFT'", hand,
                              column="XYZHAND")
    if np.all(centre == 0):
        xyz = stab.copy()
    elif program == "pyuvdata":
        # pyuvdata (uvfits.py, rotECEF_from_ECEF): STABXYZ = Rz(-lon) (r - centre).
        lon = np.arctan2(centre[1], centre[0])
        c, s = np.cos(lon), np.sin(lon)
        xyz = centre + np.column_stack([c * stab[:, 0] - s * stab[:, 1],
                                        s * stab[:, 0] + c * stab[:, 1], stab[:, 2]])
    else:
        raise FITSFormatError(
            name, table, "ARRAYX = ARRAYY = ARRAYZ = 0 (absolute STABXYZ): with a non-zero "
            "array centre, STABXYZ is relative to it either in ITRF axes (casacore reads "
            "centre + STABXYZ) or in axes rotated to the array's longitude (AIPS memo 117, "
            "pyuvdata), and this file does not say which", str(list(centre)),
            column="ARRAYX")
    if hand == "LEFT":
        # A left-handed triad: casacore (MSFitsInput.cc) negates y.
        xyz[:, 1] = -xyz[:, 1]
    return xyz


def _letter(value):
    if isinstance(value, bytes):
        value = value.decode("ascii", "replace")
    return str(value).strip().upper()


def _receptor_rows(hdu, name, numbers_column, problems=None):
    """{antenna number: Receptors} from POLTYA/POLAA/POLTYB/POLAB rows; with a dict
    ``problems``, receptors that cannot be used (parallel, unknown types) go there as
    {number: reason} instead of raising."""
    table = hdu.name
    data = hdu.data
    columns = hdu.columns.names
    for column in ("POLTYA", "POLAA"):
        if column not in columns:
            raise FITSFormatError(name, table, f"a {column} column", None, column=column)
    numbers = np.asarray(_column(hdu, name, numbers_column)).astype(int)
    seen = {}
    for row, number in enumerate(numbers):
        number = int(number)
        types = _letter(data["POLTYA"][row])
        angles = [np.ravel(np.asarray(data["POLAA"][row], dtype=float))]
        # A blank or '?' POLTYB (casacore's UVFITS, SFXC's single-polarization
        # FITS-IDI) is completed from POLTYA (Receptors.paired) below.
        if "POLTYB" in columns and _letter(data["POLTYB"][row]) not in ("", "?"):
            types += _letter(data["POLTYB"][row])
            if "POLAB" not in columns:
                raise FITSFormatError(name, table, "a POLAB column with POLTYB", None,
                                      column="POLAB")
            angles.append(np.ravel(np.asarray(data["POLAB"][row], dtype=float)))
        for k, values in enumerate(angles):
            column = "POLAA" if k == 0 else "POLAB"
            if values.size == 0 or not np.all(np.isfinite(values)):
                raise FITSFormatError(name, table, "finite receptor angles (degrees)",
                                      str(values.tolist()), column=column)
            if np.ptp(values) > 1e-9:
                raise ValueError(
                    f"{name}, table {table}, column {column}: antenna {number} has receptor "
                    f"angles {values.tolist()} deg that differ between bands; one angle per "
                    "receptor is supported: give the antennas' receptors yourself "
                    "(Antenna(..., receptors=Receptors(...)))")
        key = (types, tuple(float(values[0]) for values in angles))
        if number in seen and seen[number] != key:
            raise ValueError(
                f"{name}, table {table}: antenna {number} has receptors {seen[number]} in "
                f"one row and {key} in another (rows per time or FREQID); one set per "
                "antenna is supported: give the antennas' receptors yourself")
        seen[number] = key
    out = {}
    for number, (types, angles) in seen.items():
        try:
            out[number] = (Receptors.paired(types, angles[0] * u.deg) if len(types) == 1
                           else Receptors(types, list(angles) * u.deg))
        except ValueError as error:
            if problems is None:
                raise ValueError(f"{name}, table {table}: antenna {number}: {error}") from None
            problems[number] = (f"table {table}: {error}; give its receptors (feeds=, "
                                "--feeds X,Y)")
    return out


def _check_software(software):
    if software is None:
        return None
    conventions = [s for s in SOFTWARE if s.startswith("fits-idi:")]
    if not isinstance(software, str) or software.strip().lower() not in conventions:
        raise ValueError(f"software must be a MNTSTA convention, one of {conventions}, or "
                         f"None to detect it; got {software!r}")
    return software.strip().lower()


def fits_telescopes(path):
    """The telescope names of a FITS-IDI or UVFITS file: the primary header's
    ``TELESCOP`` and every antenna table's ``ARRNAM``, those that are not empty.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities.antenna_tables import fits_telescopes
    >>> fits_telescopes(sample_file("vla_day2_8chan.uvfits"))
    ['EVLA']
    """
    name = os.fspath(path)
    with open_fits(name) as hdul:
        found = [_text(hdul[0].header, "TELESCOP")]
        found += [_text(hdu.header, "ARRNAM") for hdu in hdul[1:]
                  if hdu.name in ("ARRAY_GEOMETRY", "AIPS AN")]
    return list(dict.fromkeys(t for t in found if t))


def read_antennas(path, kind, *, vertical="geodetic", software=None, unusable="raise"):
    """The antennas of a FITS-IDI or UVFITS file.

    `~astropy_feedrot.visibilities.fitsidi_antennas` and
    `~astropy_feedrot.visibilities.uvfits_antennas` call this with their ``kind``.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    kind : {'fits-idi', 'uvfits'}
        Its format.
    vertical : {'geodetic', 'geocentric'}, optional
        Passed to each `~astropy_feedrot.Antenna`.
    software : str, optional
        The ``MNTSTA`` convention (a ``fits-idi:*`` name of
        `~astropy_feedrot.stations.labels.SOFTWARE`); by default that of the program
        that wrote the file (`writing_program`).
    unusable : {'raise', 'keep'}, optional
        What to do with an antenna that cannot be described: its ``MNTSTA``
        code has no model (orbiting, phased, other) or cannot be read, or
        its receptors cannot be used (linear ones at one angle): raise
        (default), or keep it as an
        `~astropy_feedrot.visibilities.UnusableAntenna` with the reason.

    Returns
    -------
    dict
        ``{antenna number: Antenna}`` (or `~astropy_feedrot.visibilities.UnusableAntenna`
        with ``unusable='keep'``).

    Raises
    ------
    FITSFormatError
        For missing tables, columns or keywords, and values the format does
        not allow (non-finite positions, a frame other than ITRF).
    ValueError
        For an unknown ``kind`` or ``software``; a ``MNTSTA`` code whose
        meaning the file does not settle, or with no model (the message
        names the antenna and the ``software=`` to pass); receptor angles
        that vary between bands or rows; an antenna off the Earth.

    Examples
    --------
    See `~astropy_feedrot.visibilities.fitsidi_antennas`.

    >>> from astropy_feedrot.visibilities.antenna_tables import FORMATS
    >>> FORMATS["uvfits"]
    'AIPS AN'
    """
    if kind not in FORMATS:
        raise ValueError(f"kind must be one of {tuple(FORMATS)}, got {kind!r}")
    software = _check_software(software)
    keep = check_unusable(unusable) == "keep"
    problems = {} if keep else None
    name = os.fspath(path)
    with open_fits(name) as hdul:
        geometries = (_tables(hdul, name, FORMATS[kind]) if kind == "fits-idi"
                      else [_table(hdul, name, FORMATS[kind])])
        program = _detect(hdul, name, kind)
        numbers, names, codes, xyz, where = [], [], [], [], []
        for geometry in geometries:
            numbers += np.asarray(_column(geometry, name, "NOSTA")).astype(int).tolist()
            # Names end at the first NUL (casacore pads with NUL and garbage).
            names += [(n.decode("ascii", "replace") if isinstance(n, bytes) else str(n))
                      .split("\x00")[0].strip() for n in _column(geometry, name, "ANNAME")]
            codes += np.asarray(_column(geometry, name, "MNTSTA")).tolist()
            xyz += list(_positions(geometry, name, program.program))
            where += [_where(geometry, len(geometries))] * (len(numbers) - len(where))
        xyz = np.array(xyz, dtype=float).reshape(-1, 3)
        table = where[0] if where else FORMATS[kind]
        if len(set(numbers)) != len(numbers):
            repeated = sorted({n for n in numbers if numbers.count(n) > 1})
            raise FITSFormatError(name, table, "one row per antenna number (antenna numbers "
                                  "are shared by all arrays of a file)",
                                  f"numbers {repeated} repeated", column="NOSTA")
        bad = ~np.all(np.isfinite(xyz), axis=1)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise FITSFormatError(name, where[k], f"finite positions (antenna "
                                  f"{numbers[k]}, {names[k]})", str(xyz[k].tolist()),
                                  column="STABXYZ")
        if kind == "fits-idi":
            receptors = _receptor_rows(_table(hdul, name, "ANTENNA"), name, "ANTENNA_NO",
                                       problems)
        else:
            receptors = _receptor_rows(geometry, name, "NOSTA", problems)
    convention = software or program.software
    antennas = {}
    for number, label, code, position, table in zip(numbers, names, codes, xyz, where):
        where = f"{name}, table {table}, antenna {number} ({label})"
        location = EarthLocation.from_geocentric(*position, unit=u.m)
        problem, reason = None, None
        if convention is None and int(code) not in program.codes:
            problem, reason = "mount", f"MNTSTA {int(code)} cannot be read: {program.reason}"
        else:
            try:
                mount, focus = mount_from_label(int(code), convention or "fits-idi:casacore")
            except ValueError as error:
                if not keep:
                    raise ValueError(f"{where}: {error}") from None
                problem, reason = "mount", str(error)
                if is_orbiting(int(code), convention or "fits-idi:casacore"):
                    problem, reason = "orbiting", orbiting_reason(f"MNTSTA {int(code)}")
        if problem is not None and not keep:
            raise ValueError(f"{where}: {reason}")
        if problem is not None:
            antennas[number] = UnusableAntenna(
                location, label, problem, reason, label=int(code), vertical=vertical,
                receptors=receptors.get(number), receptors_problem=problems.get(number))
            continue
        if keep and number in problems:
            antennas[number] = UnusableAntenna(
                location, label, "receptors", problems[number], label=int(code),
                mount=mount, focus=focus, vertical=vertical)
            continue
        try:
            antennas[number] = Antenna(location, mount, focus, name=label, vertical=vertical,
                                       receptors=receptors.get(number))
        except ValueError as error:
            raise ValueError(f"{where}: {error}") from None
    return antennas
