# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reader of two-line element (TLE) files, as distributed by CelesTrak and Space-Track."""

from typing import NamedTuple

from ._common import FileFormatError, open_lines

__all__ = ["TLE", "read_tle"]


class TLE(NamedTuple):
    """One element set of a TLE file.

    Attributes
    ----------
    name : str
        The title line of the three-line form, or the catalogue number of the
        two-line form.
    line1, line2 : str
        The two element lines (checked later by `~astropy_feedrot.TLEOrbit`).

    Examples
    --------
    >>> from astropy_feedrot.io import TLE
    >>> from astropy_feedrot.simulations import GPS_SVN76_TLE
    >>> TLE("GPS SVN 76", *GPS_SVN76_TLE).catalog_number
    '41328'
    """

    name: str
    line1: str
    line2: str

    @property
    def catalog_number(self):
        """str: The satellite catalogue number (columns 3-7 of line 1)."""
        return self.line1[2:7].strip()


def _is_element_line(line, number):
    return len(line) >= 2 and line[0] == str(number) and line[1] == " "


def read_tle(source):
    """Read the element sets of a TLE file (two- or three-line form, mixed).

    Parameters
    ----------
    source : str, path-like or file object
        The file (``.gz`` is decompressed).

    Returns
    -------
    list of `TLE`
        In file order.

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        If a line 1 is not followed by a line 2, a line 2 comes without a
        line 1, or the file holds no element set.

    Notes
    -----
    A title line (three-line form) is any line before a line 1 that is not an
    element line itself; the leading zero and blank of Space-Track's 3LE
    title lines are removed.
    Blank lines are skipped. Checksums and field layout are checked when the
    element set is turned into a `~astropy_feedrot.TLEOrbit`.

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.io import read_tle
    >>> from astropy_feedrot.simulations import GPS_SVN76_TLE
    >>> text = "GPS SVN 76\\n" + "\\n".join(GPS_SVN76_TLE) + "\\n"
    >>> [(tle.name, tle.catalog_number) for tle in read_tle(io.StringIO(text))]
    [('GPS SVN 76', '41328')]
    """
    records = []
    with open_lines(source) as (filename, lines):
        title = None
        pending = None  # (lineno, line 1)
        lineno = 0
        for lineno, raw in enumerate(lines, start=1):
            line = raw.rstrip()
            if not line.strip():
                continue
            if pending is not None:
                if not _is_element_line(line, 2):
                    raise FileFormatError(filename, lineno, "line 2 of an element set "
                                          "(starting '2 ')", line)
                name = title if title is not None else pending[1][2:7].strip()
                records.append(TLE(name, pending[1], line))
                title, pending = None, None
            elif _is_element_line(line, 1):
                pending = (lineno, line)
            elif _is_element_line(line, 2):
                raise FileFormatError(filename, lineno, "a title or line 1 before line 2", line)
            else:
                title = line[2:].strip() if line.startswith("0 ") else line.strip()
        if pending is not None:
            raise FileFormatError(filename, lineno + 1, "line 2 of the element set begun on "
                                  f"line {pending[0]}", None)
        if not records:
            raise FileFormatError(filename, lineno + 1, "at least one element set", None)
    return records
