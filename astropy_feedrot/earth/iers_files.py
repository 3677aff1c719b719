# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The IERS tables that astropy ships, read by their fixed columns.

Astropy reads its bundled Earth-orientation tables (``finals2000A.all``, the
IERS Bulletin A with its Bulletin B columns, and ``eopc04.1962-now``, the
EOP 20 C04 series, both from the ``astropy-iers-data`` package) with its
general CDS table reader, which takes about a second and a half. This module
reads the few columns the package needs straight from the byte columns the
files' ReadMe gives, in a few tens of milliseconds, and combines them as
astropy's ``IERS_Auto`` does:

* rows of ``finals2000A.all`` without a Bulletin A UT1 - UTC or polar-motion
  flag are left out;
* where ``finals2000A.all`` holds Bulletin B values, those of
  ``eopc04.1962-now`` replace them, day for day (astropy's
  ``IERS_Auto._substitute_iers_b``);
* UT1 - UTC and polar motion are Bulletin B's where it has them, else
  Bulletin A's;
* the predictions begin at the first row flagged ``P`` in either Bulletin A
  column.

The arrays are bit for bit those astropy's table gives
(``tests/earth/test_iers_files.py`` compares them); `bundled_arrays` is what
`astropy_feedrot.earth.eop.table_arrays` reads when astropy has no table loaded yet.
Astropy 6, offline, serves the IERS-B table alone (`COMBINES_OFFLINE`), and
so does `bundled_arrays` there.
Nothing here is used for a table a user set or astropy downloaded.
"""

from typing import NamedTuple

import astropy
import numpy as np
from astropy import units as u
from astropy.utils import iers
from astropy.utils.introspection import minversion

from ..io import FileFormatError

__all__ = ["EarthOrientationColumns", "read_finals2000a", "read_eopc04", "combined_arrays",
           "c04_arrays", "bundled_arrays", "COMBINES_OFFLINE"]

#: Whether astropy's ``IERS_Auto``, offline (``iers.conf.auto_download = False``),
#: combines the bundled IERS-A and IERS-B tables (astropy 7.0 and later) rather
#: than serving the IERS-B table alone (astropy 6; astropy pull request 16187).
COMBINES_OFFLINE = minversion(astropy, "7.0")


class EarthOrientationColumns(NamedTuple):
    """Days, UT1 - UTC and polar motion of an IERS table, in the table's units.

    Examples
    --------
    >>> from astropy.utils import iers
    >>> from astropy_feedrot.earth.iers_files import read_eopc04
    >>> columns = read_eopc04(iers.IERS_B_FILE)
    >>> float(columns.mjd[0])  # 1962-01-01
    37665.0
    """

    #: Modified Julian Date (UTC), days.
    mjd: np.ndarray
    #: UT1 - UTC, seconds.
    ut1_utc: np.ndarray
    #: Polar motion x and y, arcseconds.
    pm_x: np.ndarray
    pm_y: np.ndarray


def _lines(path, width, comment=None):
    """The lines of ``path`` as an (N, width) array of bytes (short lines padded with
    blanks), and their 1-based line numbers in the file."""
    with open(path, "rb") as stream:
        data = stream.read()
    start, skipped = 0, 0
    while comment is not None and data.startswith(comment, start) and b"\n" in data[start:]:
        start, skipped = data.index(b"\n", start) + 1, skipped + 1
    table = _same_length_lines(data[start:], width)
    if table is not None:  # the files as the IERS writes them: no loop over lines
        return table, np.arange(skipped + 1, skipped + 1 + len(table))
    return _any_lines(path, data, width, comment)


def _same_length_lines(data, width):
    """Lines of one length (``\\n`` ends, the last one too) as an (N, width) array, or
    None when the lines differ in length or hold more than blanks past ``width``."""
    length = data.find(b"\n") + 1
    if length < 2 or len(data) % length:
        return None
    table = np.frombuffer(data, dtype=np.uint8).reshape(-1, length)
    if not (table[:, -1] == ord("\n")).all() or (table[:, :-1] == ord("\n")).any():
        return None
    text = table[:, :-1].copy()
    text[text == ord("\r")] = ord(" ")
    if (text[:, width:] != ord(" ")).any():
        return None
    padded = np.full((len(table), width), ord(" "), dtype=np.uint8)
    padded[:, :min(width, length - 1)] = text[:, :width]
    return padded


def _any_lines(path, data, width, comment):
    lines = data.splitlines()
    numbers = [k + 1 for k, line in enumerate(lines)
               if line.strip() and not (comment is not None and line.startswith(comment))]
    lines = [lines[k - 1].rstrip() for k in numbers]
    if not lines:
        raise FileFormatError(str(path), 1, "lines of numbers", None)
    for number, line in zip(numbers, lines):
        if len(line) > width:
            raise FileFormatError(str(path), number, f"a line of at most {width} characters",
                                  line.decode("ascii", "replace"))
    table = np.array(lines, dtype=f"S{width}")  # numpy pads short lines with NUL bytes
    table = table.view(np.uint8).reshape(len(lines), width)
    table[table == 0] = ord(" ")
    return table, np.array(numbers)


def _field(table, first, last):
    """Bytes ``first`` to ``last`` (1-based, inclusive, as a ReadMe gives them) of every line."""
    return np.ascontiguousarray(table[:, first - 1:last]).view(f"S{last - first + 1}").ravel()


def _numbers(lines, first, last, path, label):
    """The numbers of a column; NaN where it is blank."""
    table, numbers = lines
    text = _field(table, first, last)
    text[(table[:, first - 1:last] == ord(" ")).all(axis=1)] = b"nan"
    try:
        return text.astype(float)
    except ValueError:
        bad = next(k for k, value in enumerate(text) if not _is_number(value))
        raise FileFormatError(str(path), int(numbers[bad]),
                              f"a number for {label} (columns {first}-{last})",
                              text[bad].strip().decode("ascii", "replace")) from None


def _is_number(text):
    try:
        float(text)
    except ValueError:
        return False
    return True


def read_finals2000a(path):
    """The Bulletin A and B columns of a ``finals2000A`` file.

    Parameters
    ----------
    path : str or os.PathLike
        A ``finals2000A.all`` (or ``.data``, ``.daily``) file.

    Returns
    -------
    a, b : EarthOrientationColumns
        Bulletin A's and Bulletin B's columns (NaN where blank), one row per
        line of the file.
    pm_flags, ut1_flags : numpy.ndarray
        The Bulletin A flags of polar motion and UT1 - UTC: ``b'I'`` (IERS),
        ``b'P'`` (prediction) or ``b''``.

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        A line longer than the format's 185 columns, or a field that is not a
        number.

    Examples
    --------
    >>> from astropy.utils import iers
    >>> from astropy_feedrot.earth.iers_files import read_finals2000a
    >>> a, b, pm_flags, ut1_flags = read_finals2000a(iers.IERS_A_FILE)
    >>> float(a.mjd[0]), bytes(ut1_flags[0])  # 1973-01-02, a measured value
    (41684.0, b'I')
    """
    table = _lines(path, 185)
    mjd = _numbers(table, 8, 15, path, "MJD")
    flags = table[0]
    a = EarthOrientationColumns(mjd, _numbers(table, 59, 68, path, "UT1_UTC_A"),
                                _numbers(table, 19, 27, path, "PM_x_A"),
                                _numbers(table, 38, 46, path, "PM_y_A"))
    b = EarthOrientationColumns(mjd, _numbers(table, 155, 165, path, "UT1_UTC_B"),
                                _numbers(table, 135, 144, path, "PM_X_B"),
                                _numbers(table, 145, 154, path, "PM_Y_B"))
    return a, b, np.char.strip(_field(flags, 17, 17)), np.char.strip(_field(flags, 58, 58))


def read_eopc04(path):
    """UT1 - UTC and polar motion of an EOP 20 C04 file (``eopc04.1962-now``).

    Parameters
    ----------
    path : str or os.PathLike
        The file; its comment lines (``#``) are skipped.

    Returns
    -------
    EarthOrientationColumns

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        A line longer than the format's 218 columns, or a field that is not a
        number.

    Examples
    --------
    >>> from astropy.utils import iers
    >>> from astropy_feedrot.earth.iers_files import read_eopc04
    >>> c04 = read_eopc04(iers.IERS_B_FILE)
    >>> float(c04.ut1_utc[0])  # 1962-01-01
    0.0326338
    """
    table = _lines(path, 218, comment=b"#")
    return EarthOrientationColumns(_numbers(table, 17, 26, path, "MJD"),
                                   _numbers(table, 51, 62, path, "UT1_UTC"),
                                   _numbers(table, 27, 38, path, "PM_x"),
                                   _numbers(table, 39, 50, path, "PM_y"))


def combined_arrays(finals, eopc04):
    """The Earth-orientation table astropy's ``IERS_Auto.read`` makes of two files, as arrays.

    Parameters
    ----------
    finals, eopc04 : str or os.PathLike
        A ``finals2000A.all`` and an ``eopc04.1962-now`` file (astropy's
        ``iers.IERS_A_FILE`` and ``iers.IERS_B_FILE``).

    Returns
    -------
    mjd, ut1_utc, xp, yp : numpy.ndarray
        Days (MJD, UTC), UT1 - UTC (s) and polar motion (rad).
    predictive_mjd : float
        The first day of predictions (the day after the table if none).

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        A file that does not follow its format, or C04 days that do not match
        the Bulletin B days of the finals file.

    Examples
    --------
    >>> from astropy.utils import iers
    >>> from astropy_feedrot.earth.iers_files import combined_arrays
    >>> mjd, ut1_utc, xp, yp, predictive = combined_arrays(iers.IERS_A_FILE, iers.IERS_B_FILE)
    >>> bool(mjd[0] < predictive <= mjd[-1] + 1)
    True
    """
    a, b, pm_flags, ut1_flags = read_finals2000a(finals)
    keep = np.isfinite(a.ut1_utc) & (pm_flags != b"")
    a = EarthOrientationColumns(*(column[keep] for column in a))
    b = EarthOrientationColumns(*(column[keep].copy() for column in b))
    pm_flags, ut1_flags = pm_flags[keep], ut1_flags[keep]
    has_b = np.isfinite(b.ut1_utc)
    if has_b.any():
        c04 = read_eopc04(eopc04)
        days = a.mjd[has_b]
        first, last = (np.searchsorted(c04.mjd, days[0], side="left"),
                       np.searchsorted(c04.mjd, days[-1], side="right"))
        count = last - first
        if count:
            if not np.allclose(a.mjd[:count], c04.mjd[first:last]):
                raise FileFormatError(str(eopc04), 1, f"the days of the Bulletin B values of "
                                      f"{finals}", f"MJD {c04.mjd[first]} to {c04.mjd[last - 1]}")
            for target, source in zip(b[1:], c04[1:]):
                target[:count] = source[first:last]
    ut1_utc = np.where(np.isnan(b.ut1_utc), a.ut1_utc, b.ut1_utc)
    no_b = np.isnan(b.pm_x) | np.isnan(b.pm_y)
    xp = (np.where(no_b, a.pm_x, b.pm_x) * u.arcsec).to_value(u.rad)
    yp = (np.where(no_b, a.pm_y, b.pm_y) * u.arcsec).to_value(u.rad)
    first_prediction = min(np.searchsorted(ut1_flags, b"P"), np.searchsorted(pm_flags, b"P"))
    predictive = (float(a.mjd[first_prediction]) if first_prediction < len(a.mjd)
                  else float(a.mjd[-1] + 1))
    return a.mjd, ut1_utc, xp, yp, predictive


def c04_arrays(eopc04):
    """The Earth-orientation table astropy's ``IERS_B`` makes of a C04 file, as arrays.

    Parameters
    ----------
    eopc04 : str or os.PathLike
        An ``eopc04.1962-now`` file (astropy's ``iers.IERS_B_FILE``).

    Returns
    -------
    mjd, ut1_utc, xp, yp : numpy.ndarray
        Days (MJD, UTC), UT1 - UTC (s) and polar motion (rad).
    predictive_mjd : float
        The day after the table (the series has no predictions).

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        A file that does not follow its format.

    Examples
    --------
    >>> from astropy.utils import iers
    >>> from astropy_feedrot.earth.iers_files import c04_arrays
    >>> mjd, ut1_utc, xp, yp, predictive = c04_arrays(iers.IERS_B_FILE)
    >>> bool(predictive == mjd[-1] + 1)
    True
    """
    c04 = read_eopc04(eopc04)
    return (c04.mjd, c04.ut1_utc, (c04.pm_x * u.arcsec).to_value(u.rad),
            (c04.pm_y * u.arcsec).to_value(u.rad), float(c04.mjd[-1] + 1))


def bundled_arrays():
    """The table astropy's ``IERS_Auto`` uses offline with the files astropy ships.

    `combined_arrays` of ``iers.IERS_A_FILE`` and ``iers.IERS_B_FILE`` with
    astropy 7.0 and later, `c04_arrays` of ``iers.IERS_B_FILE`` with astropy 6
    (`COMBINES_OFFLINE`).

    Returns
    -------
    mjd, ut1_utc, xp, yp, predictive_mjd
        As `combined_arrays` returns them.

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        A file that does not follow its format.

    Examples
    --------
    >>> from astropy_feedrot.earth.iers_files import bundled_arrays
    >>> mjd, ut1_utc, xp, yp, predictive = bundled_arrays()
    >>> bool(mjd[0] < predictive <= mjd[-1] + 1)
    True
    """
    if COMBINES_OFFLINE:
        return combined_arrays(iers.IERS_A_FILE, iers.IERS_B_FILE)
    return c04_arrays(iers.IERS_B_FILE)
