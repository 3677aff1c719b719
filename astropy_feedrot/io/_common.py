# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Shared pieces of the file readers: the error class, opening a source, time systems."""

import calendar
import contextlib
import gzip
import os
import re

import numpy as np
from astropy import units as u
from astropy.time import Time

__all__ = ["FileFormatError", "TIME_SYSTEMS"]

#: GNSS time systems understood by the readers: code -> (astropy scale of the
#: returned `~astropy.time.Time`, seconds to add to the file's clock reading to
#: get that scale, description). GPS, Galileo, QZSS and IRNSS system times run
#: 19 s behind TAI, BeiDou time 33 s behind TAI. ``GLO`` is "the GLONASS UTC
#: time system" of the SP3-c/SP3-d descriptions, whose time tags are UTC (RINEX
#: 3.04, Table 21: GLO = UTC), not Moscow time.
TIME_SYSTEMS = {
    "GPS": ("tai", 19.0, "GPS time = TAI - 19 s"),
    "GAL": ("tai", 19.0, "Galileo system time = TAI - 19 s"),
    "QZS": ("tai", 19.0, "QZSS time = TAI - 19 s"),
    "IRN": ("tai", 19.0, "IRNSS time = TAI - 19 s"),
    "BDT": ("tai", 33.0, "BeiDou time = TAI - 33 s"),
    "TAI": ("tai", 0.0, "International Atomic Time"),
    "TT": ("tt", 0.0, "Terrestrial Time"),
    "UTC": ("utc", 0.0, "Coordinated Universal Time"),
    "GLO": ("utc", 0.0, "GLONASS UTC time system, time tags in UTC"),
}

# Longest stretch of a line quoted in an error message.
_QUOTE = 90

#: A decimal number as GNSS files write it: digits, an optional point and an
#: optional exponent. Python's float() also reads 'nan', 'inf', '1_000' and
#: blanks around a number; none of them is a number of these formats.
DECIMAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_INTEGER = re.compile(r"\d+")


class FileFormatError(ValueError):
    """A file does not follow the format it is read as.

    The message names the file, the 1-based line number, what was found there
    and what was expected. The same facts are available as attributes.

    Parameters
    ----------
    filename : str
        Name of the file (``'<stream>'`` for an unnamed file object).
    lineno : int
        1-based line number.
    expected : str
        What the format requires at that line.
    found : str
        What the line holds (``None`` for the end of the file).

    Attributes
    ----------
    filename, lineno, expected, found
        As given.

    Examples
    --------
    >>> from astropy_feedrot.io import FileFormatError
    >>> err = FileFormatError("igs.sp3", 24, "a position record", "PG01 x")
    >>> print(err)
    igs.sp3, line 24: expected a position record, got 'PG01 x'
    >>> isinstance(err, ValueError)
    True
    """

    def __init__(self, filename, lineno, expected, found):
        self.filename = filename
        self.lineno = lineno
        self.expected = expected
        self.found = found
        if found is None:
            got = "end of file"
        else:
            text = found if len(found) <= _QUOTE else found[:_QUOTE] + "..."
            got = repr(text)
        super().__init__(f"{filename}, line {lineno}: expected {expected}, got {got}")

    def __reduce__(self):
        return (type(self), (self.filename, self.lineno, self.expected, self.found))


def _stream_lines(stream):
    """Lines of a file-like object without their line ends, decoding bytes."""
    while True:
        line = stream.readline()
        if not line:
            return
        if isinstance(line, bytes):
            line = line.decode("ascii", errors="replace")
        yield line.rstrip("\r\n")


def _file_lines(fh):
    for line in fh:
        yield line.rstrip("\r\n")


@contextlib.contextmanager
def open_lines(source):
    """Open ``source`` and yield ``(name, lines)``.

    ``source`` is a path (str or `os.PathLike`; ``.gz`` files are decompressed)
    or an open file object with ``readline`` (text or binary). ``lines``
    iterates over the lines without their line ends; ``name`` is the path, the
    file object's ``name``, or ``'<stream>'``.
    """
    if isinstance(source, (str, os.PathLike)):
        name = os.fspath(source)
        if isinstance(name, bytes):
            name = os.fsdecode(name)
        opener = gzip.open if name.endswith(".gz") else open
        with opener(name, "rt", encoding="ascii", errors="replace") as fh:
            yield name, _file_lines(fh)
    elif hasattr(source, "readline"):
        name = getattr(source, "name", None)
        name = name if isinstance(name, str) and name else "<stream>"
        yield name, _stream_lines(source)
    else:
        raise TypeError(
            "source must be a path (str or os.PathLike) or a file object with a "
            f"readline method, got {type(source).__name__}"
        )


def known_time_systems():
    """The known time-system codes as one string, for error messages."""
    return ", ".join(TIME_SYSTEMS)


def check_epoch(fields, time_system):
    """Check and convert six calendar fields; return a tuple or None if invalid.

    ``fields`` start with strings ``year month day hour minute second``: five
    unsigned integers and a decimal number. A second of 60 (a leap second) is
    accepted only for UTC-based time systems.

    Examples
    --------
    >>> from astropy_feedrot.io import check_epoch
    >>> check_epoch("2016 12 31 23 59 60.0".split(), "UTC")
    (2016, 12, 31, 23, 59, 60.0)
    >>> check_epoch("2016 12 31 23 59 60.0".split(), "GPS") is None  # no leap second
    True
    """
    if len(fields) < 6 or not all(_INTEGER.fullmatch(f) for f in fields[:5]):
        return None
    if not DECIMAL.fullmatch(fields[5]):
        return None
    year, month, day, hour, minute = (int(f) for f in fields[:5])
    second = float(fields[5])
    if not (1 <= month <= 12 and 0 <= hour <= 23 and 0 <= minute <= 59):
        return None
    if not 1 <= day <= calendar.monthrange(year, month)[1]:
        return None
    top = 61.0 if TIME_SYSTEMS[time_system][0] == "utc" else 60.0
    if not 0.0 <= second < top:
        return None
    return (year, month, day, hour, minute, second)


def epochs_to_time(epochs, time_system):
    """Turn calendar readings of a GNSS clock into an astropy `~astropy.time.Time`.

    Parameters
    ----------
    epochs : sequence of tuple
        ``(year, month, day, hour, minute, second)`` as read in the file.
    time_system : str
        One of `TIME_SYSTEMS`.

    Returns
    -------
    `~astropy.time.Time`, shape (N,)
        Scale ``'tai'`` for the atomic system times (GPS, GAL, QZS, IRN, BDT,
        TAI, TT), ``'utc'`` for UTC and GLO; format ``'isot'``.

    Examples
    --------
    >>> from astropy_feedrot.io import epochs_to_time
    >>> epochs_to_time([(2023, 1, 25, 0, 0, 0.0)], "GPS").isot  # GPS = TAI - 19 s
    array(['2023-01-25T00:00:19.000'], dtype='<U23')
    """
    scale, offset, _ = TIME_SYSTEMS[time_system]
    arr = np.array(epochs, dtype=float).reshape(-1, 6)
    keys = ("year", "month", "day", "hour", "minute")
    ymdhms = {key: arr[:, i].astype(int) for i, key in enumerate(keys)}
    ymdhms["second"] = arr[:, 5]
    t = Time(ymdhms, format="ymdhms", scale=scale)
    if scale == "tt":
        t = t.tai
    if offset:
        t = t + offset * u.s
    t.format = "isot"
    return t


def readonly(array):
    """Mark a numpy array read-only and return it."""
    array.flags.writeable = False
    return array


def first_duplicate(epoch_index, sat_index, nsat):
    """Position (in record order) of the first repeated (epoch, satellite) pair, or None."""
    if len(epoch_index) < 2:
        return None
    key = np.asarray(epoch_index, dtype=np.int64) * nsat + np.asarray(sat_index, dtype=np.int64)
    order = np.argsort(key, kind="stable")
    same = key[order][1:] == key[order][:-1]
    if not same.any():
        return None
    return int(np.min(order[1:][same]))
