# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reader of two-line element (TLE) files, as distributed by CelesTrak and Space-Track.

The two element lines have fixed columns (CelesTrak, "NORAD Two-Line Element
Set Format"); every field that SGP4 uses is checked here, because the
propagator's own parser reads garbage (letters, a missing decimal point,
blanks inside a number) as some number without a word.
"""

import calendar
import re
from typing import NamedTuple

from ._common import FileFormatError, open_lines

__all__ = ["TLE", "read_tle", "check_tle_line", "check_tle_pair", "tle_checksum"]

# One element line: (first column, last column (1-based, inclusive), name,
# pattern of the field, what it must hold). Blank separator columns are
# checked separately.
_CATALOG = (r"( *[0-9]+|[A-HJ-NP-Z][0-9]{4})", "a catalogue number (digits, or a letter and "
            "four digits)")
_ANGLE = r" *[0-9]{1,3}\.[0-9]{4}"
_FIELDS = {
    1: (
        (3, 7, "catalogue number", *_CATALOG),
        (8, 8, "classification", r"[A-Z ]", "a letter such as U"),
        (19, 20, "epoch year", r"[0-9]{2}", "two digits"),
        (21, 32, "epoch day", r" *[0-9]{1,3}\.[0-9]{8}", "a day of the year 'ddd.dddddddd'"),
        (34, 43, "first derivative of the mean motion", r"[ +-]\.[0-9]{8}",
         "a signed fraction such as ' .00000015'"),
        (45, 52, "second derivative of the mean motion", r"[ +-][0-9]{5}[+-][0-9]",
         "an assumed-decimal number such as ' 00000-0'"),
        (54, 61, "BSTAR drag term", r"[ +-][0-9]{5}[+-][0-9]",
         "an assumed-decimal number such as '-11606-4'"),
        (63, 63, "ephemeris type", r"[0-9 ]", "a digit"),
        (65, 68, "element set number", r" *[0-9]+", "a number"),
    ),
    2: (
        (3, 7, "catalogue number", *_CATALOG),
        (9, 16, "inclination", _ANGLE, "degrees 'ddd.dddd'"),
        (18, 25, "right ascension of the ascending node", _ANGLE, "degrees 'ddd.dddd'"),
        (27, 33, "eccentricity", r"[0-9]{7}", "seven digits (assumed leading decimal point)"),
        (35, 42, "argument of perigee", _ANGLE, "degrees 'ddd.dddd'"),
        (44, 51, "mean anomaly", _ANGLE, "degrees 'ddd.dddd'"),
        (53, 63, "mean motion", r" *[0-9]{1,2}\.[0-9]{8}", "revolutions per day 'dd.dddddddd'"),
        (64, 68, "revolution number", r" *[0-9]+", "a number"),
    ),
}
_BLANKS = {1: (2, 9, 18, 33, 44, 53, 62, 64), 2: (2, 8, 17, 26, 34, 43, 52)}
# Largest value of the angles of line 2 (degrees); 360.0000 is what 359.99996 rounds to.
_ANGLE_LIMITS = {"inclination": 180.0, "right ascension of the ascending node": 360.0,
                 "argument of perigee": 360.0, "mean anomaly": 360.0}


class TLE(NamedTuple):
    """One element set of a TLE file.

    Attributes
    ----------
    name : str
        The title line of the three-line form, or the catalogue number of the
        two-line form.
    line1, line2 : str
        The two element lines, checked field by field (`check_tle_pair`).

    Examples
    --------
    >>> from astropy_feedrot.io import TLE
    >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
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


def tle_checksum(line):
    """The checksum of a TLE line: the sum of its digits, minus signs counting 1, modulo 10.

    Parameters
    ----------
    line : str
        An element line; columns 1-68 are summed.

    Returns
    -------
    int

    Examples
    --------
    >>> from astropy_feedrot.io.tle import tle_checksum
    >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
    >>> tle_checksum(GPS_SVN76_TLE[0]), GPS_SVN76_TLE[0][68]
    (5, '5')
    """
    return sum(int(c) if c.isdigit() else c == "-" for c in line[:68]) % 10


def _line_problem(line, number):
    """What is wrong with an element line, or None.

    Returns ``(tail, expected)``: ``tail`` completes the message
    "TLE line <number> ...", ``expected`` the "expected ..." of a
    `FileFormatError`.
    """
    if len(line) != 69:
        return (f"must have 69 characters, got {len(line)}: {line!r}",
                f"line {number} of an element set, 69 characters long (got {len(line)})")
    if line[0] != str(number) or line[1] != " ":
        return (f"must start with '{number} ', got {line[:2]!r}",
                f"line {number} of an element set, starting '{number} '")
    for column in _BLANKS[number]:
        if line[column - 1] != " ":
            what = f"a blank in column {column}, between two fields"
            return f"must have {what}, got {line[column - 1]!r}: {line!r}", what
    for first, last, name, pattern, form in _FIELDS[number]:
        field = line[first - 1:last]
        what = f"the {name} in columns {first}-{last} as {form}"
        if not re.fullmatch(pattern, field):
            return f"must have {what}, got {field!r}: {line!r}", what
        limit = _ANGLE_LIMITS.get(name)
        if limit is not None and float(field) > limit:
            what = f"the {name} in columns {first}-{last} at most {limit:g} degrees"
            return f"must have {what}, got {field!r}: {line!r}", what
    if number == 1:
        year = int(line[18:20])
        year += 1900 if year >= 57 else 2000
        days = 366 if calendar.isleap(year) else 365
        if not 1.0 <= float(line[20:32]) < days + 1:
            what = f"an epoch day in columns 21-32 from 1 to {days + 1} (excluded) in {year}"
            return f"must have {what}, got {line[20:32]!r}: {line!r}", what
    elif float(line[52:63]) <= 0.0:
        what = "a mean motion in columns 53-63 above zero"
        return f"must have {what}, got {line[52:63]!r}: {line!r}", what
    checksum = tle_checksum(line)
    if not line[68].isdigit() or int(line[68]) != checksum:
        return (f"checksum: expected {checksum} in column 69, got {line[68]!r}: {line!r}",
                f"the checksum {checksum} in column 69 (got {line[68]!r})")
    return None


def check_tle_line(line, number):
    """Check one line of a two-line element set, field by field.

    Parameters
    ----------
    line : str
        The line; trailing blanks are ignored.
    number : {1, 2}
        Which line of the element set it is.

    Returns
    -------
    str
        The line without trailing blanks.

    Raises
    ------
    TypeError
        If ``line`` is not a str.
    ValueError
        If the line is not 69 characters long, does not start with its
        number, has a character in a blank column, a field that does not
        read as its format requires (letters in a number, a missing decimal
        point, blanks in the eccentricity...), an angle out of range, an
        epoch day its year does not have, a mean motion of zero, or a wrong
        checksum. The message names the line, the field, its columns and what
        was found. A correct checksum does not make a field valid.

    Examples
    --------
    >>> from astropy_feedrot.io.tle import check_tle_line
    >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
    >>> line2 = GPS_SVN76_TLE[1]
    >>> check_tle_line(line2, 2) == line2
    True
    >>> bad = line2[:8] + " 54.95x7" + line2[16:]
    >>> try:
    ...     check_tle_line(bad, 2)
    ... except ValueError as error:
    ...     print(error)  # doctest: +ELLIPSIS
    TLE line 2 must have the inclination in columns 9-16 as degrees 'ddd.dddd', got ' 54.95x7': ...
    """
    if number not in (1, 2):
        raise ValueError(f"number must be 1 or 2, got {number!r}")
    if not isinstance(line, str):
        raise TypeError(f"TLE line {number} must be a str, got {type(line).__name__}")
    line = line.rstrip()
    problem = _line_problem(line, number)
    if problem is not None:
        raise ValueError(f"TLE line {number} {problem[0]}")
    return line


def check_tle_pair(line1, line2):
    """Check both lines of an element set and that they describe the same satellite.

    Parameters
    ----------
    line1, line2 : str
        The two element lines.

    Returns
    -------
    line1, line2 : str
        Without trailing blanks.

    Raises
    ------
    TypeError
        If a line is not a str.
    ValueError
        As `check_tle_line`, or if the catalogue numbers of the two lines
        differ.

    Examples
    --------
    >>> from astropy_feedrot.io.tle import check_tle_pair
    >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
    >>> check_tle_pair(*GPS_SVN76_TLE) == GPS_SVN76_TLE
    True
    """
    line1 = check_tle_line(line1, 1)
    line2 = check_tle_line(line2, 2)
    if line1[2:7] != line2[2:7]:
        raise ValueError(
            f"TLE lines describe different satellites: {line1[2:7]!r} and {line2[2:7]!r}")
    return line1, line2


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
        line 1, the file holds no element set, or an element line breaks the
        format (`check_tle_line`: length, blank columns, a field that does not
        read, a checksum) or the two lines of a set name different satellites.

    Notes
    -----
    A title line (three-line form) is any line before a line 1 that is not an
    element line itself; the leading zero and blank of Space-Track's 3LE
    title lines are removed. Blank lines are skipped; trailing blanks of the
    element lines are ignored.

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.io import read_tle
    >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
    >>> text = "GPS SVN 76\\n" + "\\n".join(GPS_SVN76_TLE) + "\\n"
    >>> [(tle.name, tle.catalog_number) for tle in read_tle(io.StringIO(text))]
    [('GPS SVN 76', '41328')]
    """
    records = []
    with open_lines(source) as (filename, lines):
        title = None
        previous = (0, "")  # the last title line: (lineno, line)
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
                _check_in_file(filename, lineno, line, 2)
                if line[2:7] != pending[1][2:7]:
                    raise FileFormatError(
                        filename, lineno, f"line 2 of the element set of catalogue number "
                        f"{pending[1][2:7].strip()!r} begun on line {pending[0]}", line)
                name = title if title is not None else pending[1][2:7].strip()
                records.append(TLE(name, pending[1], line))
                title, pending = None, None
            elif _is_element_line(line, 1):
                _check_in_file(filename, lineno, line, 1)
                pending = (lineno, line)
            elif _is_element_line(line, 2):
                if title is not None and previous[1][:1] == "1" and len(previous[1]) == 69:
                    # A line 1 broken in its first columns, read as a title.
                    _check_in_file(filename, *previous, 1)
                raise FileFormatError(filename, lineno, "a title or line 1 before line 2", line)
            else:
                title = line[2:].strip() if line.startswith("0 ") else line.strip()
                previous = (lineno, line)
        if pending is not None:
            raise FileFormatError(filename, lineno + 1, "line 2 of the element set begun on "
                                  f"line {pending[0]}", None)
        if not records:
            raise FileFormatError(filename, lineno + 1, "at least one element set", None)
    return records


def _check_in_file(filename, lineno, line, number):
    problem = _line_problem(line, number)
    if problem is not None:
        raise FileFormatError(filename, lineno, problem[1], line)
