# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The kinds of visibility file, told from their content, and who reads each."""

import json
import os
import re
import warnings
from pathlib import Path

from astropy.io import fits

from ..core.outputs import same_file

from .antenna_tables import FITSFormatError

__all__ = ["FILE_KINDS", "file_kind", "existing_path", "check_header_cards",
           "is_processing_set", "OUTPUT_EXTENSIONS", "FITSIDI_EXTENSIONS", "check_output_format",
           "check_output_path"]

#: The kinds of visibility file recognised, and the module of
#: `astropy_feedrot.visibilities` that reads and corrects each (with the
#: library it needs).
FILE_KINDS = {
    "fits-idi": "fitsidi (astropy, in chunks)",
    "uvfits": "uvfits for antennas (astropy), uvdata for visibilities (pyuvdata)",
    "uvh5": "uvdata (pyuvdata)",
    "ms": "ms (python-casacore, in place) or uvdata (pyuvdata, a copy)",
    "miriad": "uvdata (pyuvdata)",
    "mir": "uvdata (pyuvdata)",
    "msv4": "msv4 (xradio, a new data group, in place)",
}

#: The kind of output each extension names (lower case; ``.idi`` followed by
#: digits, the EVN archive's ``.IDI1``, is FITS-IDI too). ``None``: the FITS
#: extensions that FITS-IDI and UVFITS files both use, whose kind is the input's.
OUTPUT_EXTENSIONS = {
    ".idifits": "fits-idi", ".fitsidi": "fits-idi", ".idi": "fits-idi",
    ".fits": None, ".fit": None, ".fts": None,
    ".uvfits": "uvfits", ".uvf": "uvfits",
    ".uvh5": "uvh5", ".h5": "uvh5", ".hdf5": "uvh5",
    ".ms": "ms", ".uv": "miriad", ".miriad": "miriad",
}

#: Extensions of a FITS-IDI output (a FITS-IDI input is corrected into
#: FITS-IDI), and ``.idi`` followed by digits (``.IDI1``), in any case.
FITSIDI_EXTENSIONS = tuple(e for e, k in OUTPUT_EXTENSIONS.items() if k in ("fits-idi", None))

_NUMBERED_IDI = re.compile(r"\.idi[0-9]+")

_HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"

# What astropy.io.fits warns on opening a FITS file that ends early.
_CUT_SHORT = ("truncated", "Header size is not multiple of 2880")


def existing_path(path, what="file"):
    """``path`` as a `~pathlib.Path` (``~`` expanded), or FileNotFoundError.

    Parameters
    ----------
    path : str or path-like
        A file or directory.
    what : str, optional
        What it is, for the message.

    Returns
    -------
    pathlib.Path

    Examples
    --------
    >>> from astropy_feedrot.visibilities import existing_path
    >>> existing_path("/no/such/file.ms", "Measurement Set")
    Traceback (most recent call last):
    ...
    FileNotFoundError: no such Measurement Set: '/no/such/file.ms'
    """
    path = Path(os.fspath(path)).expanduser()
    if not path.exists():
        raise FileNotFoundError(f"no such {what}: {str(path)!r}")
    return path


def check_header_cards(hdus, path):
    """Refuse a FITS file with a header card astropy cannot parse, naming the card.

    Parameters
    ----------
    hdus : `~astropy.io.fits.HDUList`
        The open file.
    path : str or path-like
        Its name, for the message.

    Raises
    ------
    FITSFormatError
        For the first card whose value cannot be read (e.g. ``EQUINOX =
        2.0OOE+03``), with the card as written and what to do: a one-line
        message instead of the ``VerifyError`` astropy raises where the
        value is first used.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from astropy.io import fits
    >>> from astropy_feedrot.visibilities import check_header_cards
    >>> path = Path(tempfile.mkdtemp()) / "bad.fits"
    >>> fits.PrimaryHDU(header=fits.Header({"EQUINOX": 2000.0})).writeto(path)
    >>> data = path.read_bytes().replace(b"EQUINOX =               2000.0",
    ...                                  b"EQUINOX =            2.0OOE+03")
    >>> _ = path.write_bytes(data)
    >>> with fits.open(path) as hdus:
    ...     check_header_cards(hdus, "bad.fits")
    Traceback (most recent call last):
    ...
    astropy_feedrot.visibilities.antenna_tables.FITSFormatError: bad.fits, table PRIMARY ...
    """
    for index, hdu in enumerate(hdus):
        for card in hdu.header.cards:
            try:
                card.value  # parsed here: astropy reads a card's value when first used
            except (fits.VerifyError, ValueError):
                raise FITSFormatError(
                    os.fspath(path), f"{hdu.name or index} (HDU {index}) header",
                    f"a readable value in the card {card.keyword} (correct or remove the "
                    "card in a copy, e.g. with astropy: hdul.verify('fix'))",
                    _as_written(hdu, path, card.keyword)) from None


def _as_written(hdu, path, keyword):
    """The first card ``keyword`` of ``hdu``'s header as the file ``path`` has it
    (astropy's ``Card.image`` would show it repaired, with a warning)."""
    info = hdu.fileinfo()  # HDUList.fileinfo would render the header (and warn)
    if not info:
        return keyword
    try:
        with open(path, "rb") as handle:
            handle.seek(info["hdrLoc"])
            raw = handle.read(info["datLoc"] - info["hdrLoc"])
    except (OSError, TypeError):
        return keyword
    for start in range(0, len(raw), 80):
        card = raw[start:start + 80].decode("ascii", "replace")
        if card[:8].rstrip() == keyword:
            return card.rstrip()
    return keyword


def is_processing_set(path):
    """Whether ``path`` is an MSv4 processing set on disk: a zarr group whose root
    ``zarr.json`` says its type is ``processing_set`` (read as JSON, without xradio).

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities.kinds import is_processing_set
    >>> is_processing_set(sample_file("vla_sim.ms"))
    False
    """
    meta = Path(path) / "zarr.json"
    if not meta.is_file():
        return False
    try:
        attributes = json.loads(meta.read_text()).get("attributes", {})
    except (OSError, ValueError, AttributeError):
        return False
    return isinstance(attributes, dict) and attributes.get("type") == "processing_set"


def file_kind(path):
    """The kind of a visibility file, from its content.

    Parameters
    ----------
    path : str or path-like
        A file (FITS-IDI, UVFITS, uvh5) or a directory (Measurement Set,
        Miriad, SMA Mir, MSv4 processing set).

    Returns
    -------
    str
        One of `FILE_KINDS`.

    Notes
    -----
    A FITS file with a ``UV_DATA`` table is FITS-IDI, whatever its primary
    header says: FITS-IDI files (AIPS Memo 114, DiFX's difx2fits) write
    ``GROUPS = T`` with ``NAXIS = 0``, ``GCOUNT = 0`` and ``PCOUNT = 0``.
    UVFITS is a primary array of random groups (``GROUPS = T``, ``NAXIS1 =
    0`` and further axes).

    Raises
    ------
    FileNotFoundError
        If nothing is at ``path``.
    ValueError
        If the content is none of the known kinds, or a FITS file is cut
        short; a `FITSFormatError` (a ValueError) names a header card that
        cannot be read (`check_header_cards`).

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import file_kind
    >>> file_kind(sample_file("vla_day2_8chan.uvfits"))
    'uvfits'
    """
    path = existing_path(path)
    if path.is_dir():
        if (path / "table.dat").is_file() and (path / "ANTENNA").is_dir():
            return "ms"
        if (path / "visdata").is_file() and (path / "vartable").is_file():
            return "miriad"
        if (path / "in_read").is_file() and (path / "bl_read").is_file():
            return "mir"
        if is_processing_set(path):
            return "msv4"
        raise ValueError(f"{str(path)!r} is a directory but not a Measurement Set (table.dat "
                         "and ANTENNA), a Miriad data set (visdata), an SMA Mir data set "
                         "(in_read) nor an MSv4 processing set (zarr.json of type "
                         "'processing_set')")
    with open(path, "rb") as handle:
        start = handle.read(8)
    if start.startswith(_HDF5_SIGNATURE):
        return "uvh5"
    if start.startswith(b"SIMPLE"):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                with fits.open(path, memmap=True) as hdus:
                    header = hdus[0].header
                    # Random groups hold data: NAXIS1 = 0 and further axes.
                    # FITS-IDI (AIPS Memo 114, difx2fits) writes GROUPS = T
                    # too, but with NAXIS = 0 and GCOUNT = PCOUNT = 0.
                    groups = (bool(header.get("GROUPS", False))
                              and int(header.get("NAXIS", 0)) >= 2
                              and int(header.get("NAXIS1", -1)) == 0)
                    names = {hdu.name for hdu in hdus[1:]}
                    check_header_cards(hdus, path)
            except OSError as error:
                raise ValueError(f"{str(path)!r} cannot be read as FITS ({error}); the file "
                                 "may be cut short") from None
        for record in caught:
            if any(sign in str(record.message) for sign in _CUT_SHORT):
                raise ValueError(f"{str(path)!r} is cut short: {record.message}")
            warnings.warn_explicit(record.message, record.category, record.filename,
                                   record.lineno)
        if "UV_DATA" in names:
            return "fits-idi"
        if groups:
            return "uvfits"
        if "ARRAY_GEOMETRY" in names:
            raise ValueError(f"{str(path)!r} is a FITS-IDI file without a UV_DATA table; its "
                             f"extensions: {sorted(names)} (a FITS-IDI file cut short loses "
                             "its last tables)")
        raise ValueError(f"{str(path)!r} is a FITS file with neither random groups (UVFITS) "
                         f"nor a UV_DATA table (FITS-IDI); its extensions: {sorted(names)} "
                         "(a FITS-IDI file cut short loses its last tables)")
    raise ValueError(f"cannot tell the kind of {str(path)!r}: not FITS, HDF5 (uvh5), a "
                     "Measurement Set, Miriad nor SMA Mir")


def check_output_format(kind, output):
    """The kind of file `correct_file` writes for an input of ``kind`` into ``output``.

    The output's kind follows its extension where the extension names one
    kind (`OUTPUT_EXTENSIONS`: ``.uvfits``/``.uvf``, ``.uvh5``, ``.ms``,
    ``.IDI1``, ``.idifits``...), and the input's kind where it names two:
    ``.fits`` (and ``.fit``, ``.fts``, any case) is FITS-IDI for a FITS-IDI
    input, UVFITS for a UVFITS input. A FITS-IDI input is always corrected
    into FITS-IDI (there is no conversion); other inputs are written by
    pyuvdata, which writes no FITS-IDI.

    Parameters
    ----------
    kind : str
        The input's kind, one of `~astropy_feedrot.visibilities.FILE_KINDS`
        (`~astropy_feedrot.visibilities.file_kind`: by content, whatever
        its name).
    output : str or path-like
        The output's name.

    Returns
    -------
    str
        The output's kind: ``'fits-idi'``, ``'uvfits'``, ``'uvh5'``,
        ``'ms'`` or ``'miriad'``.

    Raises
    ------
    ValueError
        For an extension that names no kind, another kind than FITS-IDI for
        a FITS-IDI input, FITS-IDI for another input, or ``.fits`` for an
        input that is not FITS; the message lists the extensions to use.

    Examples
    --------
    >>> from astropy_feedrot.visibilities import check_output_format
    >>> check_output_format("uvfits", "out.uvh5")
    'uvh5'
    >>> check_output_format("uvfits", "out.FITS"), check_output_format("fits-idi", "x.IDI1")
    ('uvfits', 'fits-idi')
    >>> check_output_format("fits-idi", "out.uvfits")
    Traceback (most recent call last):
    ...
    ValueError: 'out.uvfits': a FITS-IDI input is corrected into a FITS-IDI copy ...
    """
    text = os.fspath(output)
    extension = Path(text.rstrip("/" + os.sep)).suffix.lower()
    if _NUMBERED_IDI.fullmatch(extension):
        named = "fits-idi"
    else:
        named = OUTPUT_EXTENSIONS.get(extension, "unknown")
    pyuvdata = ", ".join(e for e, k in OUTPUT_EXTENSIONS.items() if k not in ("fits-idi", None))
    if kind == "msv4":
        raise ValueError(f"{text!r}: an MSv4 processing set is corrected in place, as a new "
                         "data group beside its data (correct_processing_set; feedrot correct "
                         "PS.ps.zarr --in-place), not into a copy")
    if kind == "fits-idi":
        if named in ("fits-idi", None):
            return "fits-idi"
        raise ValueError(f"{text!r}: a FITS-IDI input is corrected into a FITS-IDI copy "
                         "(there is no conversion to other formats); give the output one "
                         f"of the extensions {', '.join(FITSIDI_EXTENSIONS)} or .idiN "
                         "(.IDI1)")
    if named == "fits-idi":
        raise ValueError(f"{text!r}: {extension} names a FITS-IDI file, but a {kind} input "
                         "is written by pyuvdata, which writes no FITS-IDI; use one of "
                         f"{pyuvdata}")
    if named is None:
        if kind == "uvfits":
            return "uvfits"
        raise ValueError(f"{text!r}: {extension} is used by both FITS-IDI and UVFITS; a "
                         f"{kind} input is written as UVFITS with .uvfits (or .uvf), or use "
                         f"one of {pyuvdata}")
    if named == "unknown":
        raise ValueError(f"cannot tell a format from the extension of {text!r}; use one of "
                         f"{pyuvdata}" + (", .fits" if kind == "uvfits" else ""))
    return named


def check_output_path(source, output, overwrite):
    """The output path (as given, ``~`` expanded), refused if it is the input, exists
    without ``overwrite`` or lies in no directory.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities.kinds import check_output_path
    >>> check_output_path(sample_file("vla_sim.ms"), "copy.ms", False).name
    'copy.ms'
    """
    target = Path(os.fspath(output)).expanduser()
    resolved = target.resolve()
    if same_file(resolved, source.resolve()):
        raise ValueError(f"the output {str(target)!r} is the input; the input is never "
                         "modified: choose another name")
    if target.exists() and not overwrite:
        raise FileExistsError(f"{str(target)!r} exists; pass overwrite=True (--overwrite) to "
                              "replace it")
    if not resolved.parent.is_dir():
        raise FileNotFoundError(f"cannot write {str(target)!r}: directory "
                                f"{str(resolved.parent)!r} does not exist")
    return resolved
