# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""A FITS file copied as its bytes lie: a new primary header, the rest around the rows.

`~astropy_feedrot.visibilities.fitsidi.correct_fitsidi` writes its copy in
two parts: everything but the visibility rows, copied byte for byte after a
primary header that gains HISTORY cards (`header_with_history`,
`copy_around`), and the corrected rows, which its chunks write into the gaps.
astropy is not asked to write the file: it would rewrite cards it reads (the
``NAXIS = 0`` of SFXC's random-groups header, for one).
"""

import os

from astropy.io import fits

from .antenna_tables import FITSFormatError

__all__ = ["header_with_history", "copy_around", "copy_range"]


def header_with_history(source, header_end, text):
    """The primary header of a file as its bytes lie, with HISTORY cards before its END card.

    Parameters
    ----------
    source : str
        The FITS file.
    header_end : int
        The byte where its primary header ends (a multiple of 2880).
    text : str
        The history, as many HISTORY cards as it takes.

    Returns
    -------
    bytes
        The new header, padded to a multiple of 2880 bytes.

    Raises
    ------
    FITSFormatError
        If the header has no END card.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy.io import fits
    >>> from astropy_feedrot.visibilities.fits_bytes import header_with_history
    >>> path = os.path.join(tempfile.mkdtemp(), "x.fits")
    >>> fits.PrimaryHDU().writeto(path)
    >>> header = header_with_history(path, 2880, "corrected")
    >>> len(header), fits.Header.fromstring(header.decode())["HISTORY"][0]
    (2880, 'corrected')
    """
    with open(source, "rb") as handle:
        raw = handle.read(header_end)
    cards = [raw[k:k + 80] for k in range(0, len(raw) - len(raw) % 80, 80)]
    end = next((k for k, card in enumerate(cards) if card.rstrip() == b"END"), None)
    if end is None:
        raise FITSFormatError(source, "primary header", "an END card", None)
    history = fits.Header()
    history.add_history(text)
    body = b"".join(cards[:end]) + history.tostring(endcard=False, padding=False).encode(
        "ascii") + cards[end]
    return body + b" " * (-len(body) % 2880)


def copy_around(source, target, header, header_end, rows):
    """Write a new primary header, then the bytes of a file after its own but its rows.

    Parameters
    ----------
    source, target : str
        The file, and its copy (which exists: it is opened to be written over).
    header : bytes
        The copy's primary header.
    header_end : int
        The byte where the source's primary header ends.
    rows : list of (int, int)
        Byte ranges of the source not copied (the rows the caller writes).

    Returns
    -------
    int
        How many bytes further everything lies in the copy.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy_feedrot.visibilities.fits_bytes import copy_around
    >>> folder = tempfile.mkdtemp()
    >>> source, target = os.path.join(folder, "a"), os.path.join(folder, "b")
    >>> with open(source, "wb") as f:
    ...     _ = f.write(b"HHabcdef")
    >>> open(target, "wb").close()
    >>> copy_around(source, target, b"NEWH", 2, [(4, 6)])
    2
    >>> with open(target, "rb") as f:
    ...     f.read()
    b'NEWHab\\x00\\x00ef'
    """
    size = os.path.getsize(source)
    shift = len(header) - header_end
    with open(source, "rb") as fin, open(target, "r+b") as fout:  # r+: the caller made it
        fout.write(header)
        position = header_end
        for begin, end in sorted(rows) + [(size, size)]:
            copy_range(fin, fout, position, begin, shift)
            position = max(position, end)
        fout.truncate(size + shift)  # the rows' bytes until the chunks write them
    return shift


def copy_range(fin, fout, begin, end, shift):
    """Bytes [begin, end) of one file to the same place in another, ``shift`` further.

    In the kernel where it can (``os.sendfile``, as `shutil.copyfile` does on
    Linux), else by reads and writes.

    Parameters
    ----------
    fin, fout : file
        Open binary files, read and written.
    begin, end : int
        The byte range of ``fin``.
    shift : int
        How many bytes further it goes in ``fout``.

    Raises
    ------
    OSError
        If ``fin`` ends before ``end``.

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.visibilities.fits_bytes import copy_range
    >>> fin, fout = io.BytesIO(b"abcdef"), io.BytesIO()
    >>> copy_range(fin, fout, 2, 5, 1)
    >>> fout.getvalue()
    b'\\x00\\x00\\x00cde'
    """
    fout.seek(begin + shift)
    fout.flush()
    offset = begin
    try:  # in the kernel where it can (Linux), as shutil.copyfile does
        while offset < end:
            sent = os.sendfile(fout.fileno(), fin.fileno(), offset, min(end - offset, 2**30))
            if sent == 0:
                break
            offset += sent
    except (AttributeError, OSError):  # io.UnsupportedOperation is an OSError
        pass
    if offset < end:  # elsewhere (or what sendfile left)
        fout.seek(offset + shift)
        fin.seek(offset)
        while offset < end:
            data = fin.read(min(end - offset, 16 * 2**20))
            if not data:
                raise OSError(f"{fin.name!r} ended at byte {offset}, before {end}")
            fout.write(data)
            offset += len(data)
        fout.flush()
