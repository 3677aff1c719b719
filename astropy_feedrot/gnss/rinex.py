# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""RINEX observation files: a streaming reader, and a writer that changes carrier phases only.

The formats are those of the IGS/RTCM RINEX working group: RINEX 2.11
(Gurtner and Estey 2007), 3.05 (2020) and 4.01 (2023). What this module
relies on:

* the header: 80-column lines whose label is in columns 61-80, the first one
  ``RINEX VERSION / TYPE`` (version in columns 1-9, file type ``O`` in column
  21, satellite system in column 41), the last one ``END OF HEADER``;
  ``APPROX POSITION XYZ``, ``ANTENNA: ZERODIR AZI``, ``INTERVAL``, ``TIME OF
  FIRST OBS`` (with the time system in columns 49-51) and the observation
  types: ``# / TYPES OF OBSERV`` (2.11, one list for all systems) or ``SYS /
  # / OBS TYPES`` (3 and 4, one list per system);
* the epoch records: in RINEX 3 and 4 a line ``> yyyy mm dd hh mm ss.sssssss
  f nnn``, then one line per satellite: its PRN and one 16-column field per
  observation type (a value F14.3, the loss-of-lock indicator, LLI, and the
  signal strength, SSI); in RINEX 2.11 the epoch line ``yy mm dd hh mm
  ss.sssssss f nnn`` with up to 12 PRNs (continued on further lines), then
  each satellite's observations five fields to a line. Epoch flags 0 and 1
  are observations, 2 to 5 announce ``nnn`` header lines (events, which are
  passed on as they are), 6 announces cycle-slip records (kept as they are).
  The header lines of events of flags 3 (new site occupation) and 4 (header
  information) that give observation types, ``APPROX POSITION XYZ`` or
  ``ANTENNA: ZERODIR AZI`` replace the reader's ``header`` from
  there on (its ``lines`` stay the file's header);
* a phase value blank or ``0.000`` is missing; one that is not a number
  (``**************``, an overflow) is a `~astropy_feedrot.io.FileFormatError`
  naming the line.

Nothing is held beyond one epoch record: the reader yields `EpochRecord`
objects from a stream, and `RinexWriter` writes them back, so a file of a day
at 1 s is read and written in bounded memory. Every line is kept byte for
byte (read as Latin-1, with its own line end) except the carrier-phase
fields a caller changes with `EpochRecord.set_value`, and the one
``COMMENT`` line `RinexWriter.write_header` adds.

Compressed files: gzip (``.gz``, recognised by its content) is read and
written with the standard library; Hatanaka-compressed files (Compact RINEX,
``.crx`` or ``.YYd``, recognised by their ``CRINEX VERS   / TYPE`` first
line) are read through the ``crx2rnx`` program of the optional `hatanaka
<https://pypi.org/project/hatanaka/>`_ package (the ``gnss`` extra: ``python
-m pip install hatanaka``), streamed through a pipe.
"""

import contextlib
import dataclasses
import os
import zlib

import numpy as np

from ..io import TIME_SYSTEMS, FileFormatError, check_epoch, epochs_to_time
from .rinex_header import (
    DEFAULT_TIME_SYSTEM,
    FIELD,
    PER_LINE_2,
    SYSTEMS,
    VALUE_WIDTH,
    VERSIONS,
    RinexHeader,
)
from .streams import open_rinex_lines, source_name

__all__ = [
    "EpochRecord",
    "RinexReader",
    "read_rinex_header",
    "record_times",
]


class EpochRecord:
    """One epoch record of a RINEX observation file, with its lines as read.

    Attributes
    ----------
    lineno : int
        1-based line number of the epoch line in the (decompressed) file.
    lines : list of str
        The record's lines, each with its line end: the epoch line (and its
        continuation lines in RINEX 2), then the satellites' observations or
        the event's header lines.
    flag : int or None
        The epoch flag: 0 (OK), 1 (power failure since the previous epoch),
        2-5 (events), 6 (cycle slips); None for a blank line, which is kept
        as a record of its own so that it is written back.
    epoch : tuple or None
        ``(year, month, day, hour, minute, second)``; None for an event that
        gives no time.
    satellites : list of str
        The PRNs (``'G05'``) of a record of flag 0, 1 or 6; empty otherwise.
    starts : list of int
        For each satellite, the index in ``lines`` of its first line.

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.gnss import RinexReader
    >>> text = '''     3.04           OBSERVATION DATA    G                   RINEX VERSION / TYPE
    ... G    2 C1C L1C                                              SYS / # / OBS TYPES
    ...                                                             END OF HEADER
    ... > 2023 01 25 00 00  0.0000000  0  1
    ... G05  20000000.000 7 105100000.12317
    ... '''
    >>> with RinexReader(io.StringIO(text)) as reader:
    ...     record = next(iter(reader))
    >>> record.satellites, record.flag, record.epoch
    (['G05'], 0, (2023, 1, 25, 0, 0, 0.0))
    >>> record.value(0, 0, 19), record.lli(0, 0, 19)
    (105100000.123, 1)
    >>> record.set_value(0, 0, 19, 105100000.0)
    >>> record.lines[1]
    'G05  20000000.000 7 105100000.00017\\n'
    """

    __slots__ = ("lineno", "lines", "flag", "epoch", "satellites", "starts")

    def __init__(self, lineno, lines, flag, epoch, satellites=(), starts=()):
        self.lineno = lineno
        self.lines = lines
        self.flag = flag
        self.epoch = epoch
        self.satellites = list(satellites)
        self.starts = list(starts)

    def __repr__(self):
        return (f"<EpochRecord line {self.lineno} flag {self.flag} {self.epoch} "
                f"{len(self.satellites)} satellites>")

    @property
    def observations(self):
        """Whether the record holds observations (epoch flag 0 or 1)."""
        return self.flag in (0, 1)

    def _field(self, i, line, col):
        text = self.lines[self.starts[i] + line]
        return text.rstrip("\r\n")[col:col + FIELD]

    def value(self, i, line, col):
        """The value of the field at ``col`` of line ``line`` of satellite ``i``; None if blank.

        Examples
        --------
        See `EpochRecord`.
        """
        field = self._field(i, line, col)[:VALUE_WIDTH]
        return float(field) if field.strip() else None

    def lli(self, i, line, col):
        """The loss-of-lock indicator of a field (0 when blank).

        Examples
        --------
        See `EpochRecord`.
        """
        flag = self._field(i, line, col)[VALUE_WIDTH:VALUE_WIDTH + 1]
        return int(flag) if flag.strip() else 0

    def phases(self, i, fields, name="<stream>"):
        """The values of fields of satellite ``i`` and whether one has lost lock.

        Parameters
        ----------
        i : int
            The satellite's index in `satellites`.
        fields : list of (int, int, str)
            As `RinexHeader.phase_fields` gives them.
        name : str, optional
            The file's name, for the message of an unreadable value.

        Returns
        -------
        values : list of float or None
            None where a field is missing: blank, or ``0.000`` (RINEX's
            spelling of a phase not measured).
        lost : bool
            Whether bit 0 of a field's loss-of-lock indicator is set.

        Raises
        ------
        astropy_feedrot.io.FileFormatError
            If a value is not an F14.3 number (an overflow written as
            ``**************``, for instance), naming the file and line.

        Examples
        --------
        See `subtract`.
        """
        values, lost = [], False
        start = self.starts[i]
        for line, col, code in fields:
            text = self.lines[start + line]
            field = text[col:col + VALUE_WIDTH]
            value = None
            if field.strip():
                try:
                    value = float(field)
                except ValueError:
                    value = np.nan
                if not np.isfinite(value):
                    raise FileFormatError(
                        name, self.lineno + start + line,
                        f"a carrier phase {code} of {self.satellites[i]} as an F14.3 number "
                        f"in columns {col + 1}-{col + VALUE_WIDTH} (blank or 0.000 if missing)",
                        text.rstrip("\r\n"))
                if value == 0.0:
                    value = None
            values.append(value)
            flag = text[col + VALUE_WIDTH:col + VALUE_WIDTH + 1]
            if flag.isdigit() and int(flag) & 1:
                lost = True
        return values, lost

    def subtract(self, i, fields, values, amount):
        """Subtract ``amount`` from the non-blank ``values`` read by `phases` (F14.3).

        Returns
        -------
        int
            The number of fields changed.

        Raises
        ------
        ValueError
            If a new value does not fit in 14 characters.

        Examples
        --------
        >>> from astropy_feedrot.gnss.rinex import EpochRecord
        >>> record = EpochRecord(1, ["> epoch\\n", "G05  20000000.000 7 105100000.12317\\n"], 0,
        ...                      (2023, 1, 25, 0, 0, 0.0), ["G05"], [1])
        >>> fields = [(0, 19, "L1C")]
        >>> values, lost = record.phases(0, fields)
        >>> values, lost
        ([105100000.123], True)
        >>> record.subtract(0, fields, values, 0.25)
        1
        >>> record.lines[1]
        'G05  20000000.000 7 105099999.87317\\n'
        """
        start = self.starts[i]
        changed = 0
        for (line, col, _), value in zip(fields, values):
            if value is None:
                continue
            new = f"{value - amount:14.3f}"
            if len(new) != VALUE_WIDTH:
                raise ValueError(f"{value - amount!r} does not fit the 14 characters (F14.3) of "
                                 f"a RINEX observation (satellite {self.satellites[i]}, epoch "
                                 f"{self.epoch})")
            text = self.lines[start + line]
            self.lines[start + line] = text[:col] + new + text[col + VALUE_WIDTH:]
            changed += 1
        return changed

    def set_value(self, i, line, col, value):
        """Replace a field's value (F14.3), keeping every other character of the line.

        Raises
        ------
        ValueError
            If the value does not fit in 14 characters.

        Examples
        --------
        See `EpochRecord`.
        """
        k = self.starts[i] + line
        text = self.lines[k]
        new = f"{value:14.3f}"
        if len(new) != VALUE_WIDTH:
            raise ValueError(f"{value!r} does not fit the 14 characters (F14.3) of a RINEX "
                             f"observation (satellite {self.satellites[i]}, epoch {self.epoch})")
        self.lines[k] = text[:col] + new + text[col + VALUE_WIDTH:]


class RinexReader:
    """Stream the epoch records of a RINEX observation file (2.11, 3.0x, 4.0x).

    Parameters
    ----------
    source : str, path-like or file object
        A path (plain, gzip or Hatanaka-compressed, recognised by content) or
        an open file object (text, or bytes of a plain file).

    Attributes
    ----------
    header : `RinexHeader`
        Read on opening.

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        On opening, for a header that is not a RINEX observation header (a
        wrong version line, no ``END OF HEADER``, a malformed observation
        types record); while iterating, for a record that breaks the format
        (naming the line): a file cut short inside a record, a satellite of
        a system whose observation types the header does not declare, more
        observations than declared, a malformed epoch line.
    ImportError
        For a Hatanaka-compressed file without the optional hatanaka package.

    Notes
    -----
    Use it as a context manager; iterating yields `EpochRecord` objects one
    at a time, so memory does not grow with the file.

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.gnss import RinexReader
    >>> text = '''     2.11           OBSERVATION DATA    G (GPS)             RINEX VERSION / TYPE
    ...      2    C1    L1                                          # / TYPES OF OBSERV
    ...                                                             END OF HEADER
    ...  23  1 25  0  0  0.0000000  0  2G05G07
    ...   20000000.000   105100000.123 7
    ...   21000000.000   110300000.456 7
    ... '''
    >>> with RinexReader(io.StringIO(text)) as reader:
    ...     records = list(reader)
    >>> reader.header.version, records[0].satellites
    ('2.11', ['G05', 'G07'])
    """

    def __init__(self, source, *, name=None):
        self.name = name or source_name(source)
        self._stack = contextlib.ExitStack()
        self._pipe = None
        self._file = None
        try:
            if isinstance(source, (str, os.PathLike)):
                # Opened here, so that `bytes_read` can follow the file as it is read.
                source = self._file = self._stack.enter_context(open(source, "rb"))
            self._lines, self._pipe = open_rinex_lines(source, self._stack, self.name)
            self.lineno = 0
            self.header = self._read_header()
        except BaseException:
            self.close()
            raise

    # -- opening ---------------------------------------------------------------------

    def close(self):
        """Close the file (and stop ``crx2rnx``)."""
        self._stack.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def size(self):
        """Bytes of the file as stored (compressed if it is), or None if a file object was
        given."""
        return None if self._file is None else os.fstat(self._file.fileno()).st_size

    def bytes_read(self):
        """Bytes of the file as stored read so far (at most `size`), or None if a file
        object was given.

        The records come a buffer behind (for Compact RINEX, also the pipe to
        ``crx2rnx``): a measure of progress, not a place in the file.
        """
        return None if self._file is None else min(self._file.tell(), self.size)

    # -- lines -------------------------------------------------------------------------

    def _read(self):
        """The next line, or None at the end; a broken compressed stream is a FileFormatError."""
        try:
            return next(self._lines, None)
        except (EOFError, OSError, zlib.error) as error:
            raise FileFormatError(self.name, self.lineno + 1, "a complete compressed file "
                                  "(gzip or Compact RINEX) that decompresses",
                                  f"{type(error).__name__}: {error}") from None

    def _next(self, expected):
        line = self._read()
        if line is None:
            if self._pipe is not None:
                self._pipe.check(self.lineno + 1)
            raise FileFormatError(self.name, self.lineno + 1, expected
                                  + " (the file is cut short)", None)
        self.lineno += 1
        return line

    def _error(self, expected, line, lineno=None):
        return FileFormatError(self.name, lineno or self.lineno, expected,
                               line.rstrip("\r\n"))

    # -- header ------------------------------------------------------------------------

    def _read_header(self):
        first = self._next("the 'RINEX VERSION / TYPE' line")
        version = first[:9].strip()
        if first[60:80].strip() != "RINEX VERSION / TYPE" or version not in VERSIONS:
            raise self._error(
                "'RINEX VERSION / TYPE' in columns 61-80 and a version (columns 1-9) of "
                f"{', '.join(VERSIONS)}", first)
        if first[20:21] != "O":
            raise self._error("an observation file ('O' in column 21 of the first line)",
                              first)
        major = int(version[0])
        system = first[40:41].upper() or "G"
        system = "G" if system == " " else system
        lines = [first]
        fields = {"obs_types": {}}
        pending = None  # (system, count, types) of a types record being continued
        while True:
            line = self._next("'END OF HEADER'")
            lines.append(line)
            label = line[60:80].strip()
            if label == "END OF HEADER":
                break
            if label in ("SYS / # / OBS TYPES", "# / TYPES OF OBSERV"):
                pending = self._obs_types(line, label, pending, fields["obs_types"], system)
            elif label == "APPROX POSITION XYZ":
                xyz = self._numbers(line, 3, 14, "three coordinates (3F14.4)")
                fields["position"] = None if not np.any(xyz) else xyz
            elif label == "ANTENNA: ZERODIR AZI":
                fields["zero_direction"] = float(self._numbers(line, 1, 14, "an azimuth "
                                                               "(F14.4, degrees)")[0])
            elif label == "ANTENNA: ZERODIR XYZ":
                self._zero_xyz(line)
            elif label == "INTERVAL":
                fields["interval"] = float(self._numbers(line, 1, 10, "F10.3 seconds")[0])
            elif label in ("TIME OF FIRST OBS", "TIME OF LAST OBS"):
                key = "first_obs" if label == "TIME OF FIRST OBS" else "last_obs"
                code = line[48:51].strip()
                if key == "first_obs" and code:
                    if code not in TIME_SYSTEMS:
                        raise self._error(f"a time system of {', '.join(TIME_SYSTEMS)} in "
                                          "columns 49-51", line)
                    fields["time_system"] = code
                fields[key] = self._calendar(line[:43].split(), line,
                                             fields.get("time_system", "UTC"))
        if pending is not None and len(pending[2]) < pending[1]:
            raise self._error(f"{pending[1]} observation types ({len(pending[2])} given)",
                              lines[-2], self.lineno - 1)
        if not fields["obs_types"]:
            raise self._error("a header declaring its observation types ('SYS / # / OBS "
                              "TYPES' or '# / TYPES OF OBSERV') before 'END OF HEADER'", line)
        fields.setdefault("time_system", DEFAULT_TIME_SYSTEM.get(system, "GPS"))
        return RinexHeader(self.name, version, major, system, tuple(lines), **fields)

    def _numbers(self, line, count, width, what, lineno=None):
        try:
            return np.array([float(line[i * width:(i + 1) * width]) for i in range(count)])
        except ValueError:
            raise self._error(what, line, lineno) from None

    def _zero_xyz(self, line, lineno=None):
        xyz = self._numbers(line, 3, 14, "three components (3F14.4)", lineno)
        if np.any(xyz):
            raise ValueError(
                f"{self.name}, line {lineno or self.lineno}: ANTENNA: ZERODIR XYZ gives the zero "
                "direction of a vehicle's antenna in the vehicle's body frame, which needs its "
                "attitude; only fixed antennas (ANTENNA: ZERODIR AZI) are corrected")

    def _header_change(self, record):
        """Apply the header records of an event (flags 3 and 4) to `header`.

        New observation types (``# / TYPES OF OBSERV``, ``SYS / # / OBS
        TYPES``) change how the following records are read; a new ``APPROX
        POSITION XYZ`` or ``ANTENNA: ZERODIR AZI`` changes the receiver of the
        wind-up from the next epoch on.
        """
        changes, obs_types, pending = {}, None, None
        header = self.header
        for k, line in enumerate(record.lines[1:], start=1):
            label = line[60:80].strip()
            lineno = record.lineno + k
            if label in ("SYS / # / OBS TYPES", "# / TYPES OF OBSERV"):
                if obs_types is None:
                    obs_types = dict(header.obs_types)
                pending = self._obs_types(line, label, pending, obs_types, header.system, lineno)
            elif label == "APPROX POSITION XYZ":
                xyz = self._numbers(line, 3, 14, "three coordinates (3F14.4)", lineno)
                changes["position"] = None if not np.any(xyz) else xyz
            elif label == "ANTENNA: ZERODIR AZI":
                changes["zero_direction"] = float(self._numbers(
                    line, 1, 14, "an azimuth (F14.4, degrees)", lineno)[0])
            elif label == "ANTENNA: ZERODIR XYZ":
                self._zero_xyz(line, lineno)
        if pending is not None and len(pending[2]) < pending[1]:
            raise self._error(f"{pending[1]} observation types ({len(pending[2])} given) in the "
                              f"event record of line {record.lineno}", record.lines[-1])
        if obs_types is not None:
            changes["obs_types"] = obs_types
        if changes:
            self.header = dataclasses.replace(header, **changes)

    def _calendar(self, fields, line, time_system):
        epoch = check_epoch(fields, time_system)
        if epoch is None:
            raise self._error("a date and time 'yyyy mm dd hh mm ss.sssssss'", line)
        return epoch

    def _obs_types(self, line, label, pending, obs_types, file_system, lineno=None):
        if label == "# / TYPES OF OBSERV":
            if pending is None or len(pending[2]) >= pending[1]:
                count = line[:6].strip()
                if not count.isdigit():
                    raise self._error("the number of observation types in columns 1-6", line,
                                      lineno)
                pending = (None, int(count), [])
            pending[2].extend(line[6:60].split())
            if len(pending[2]) >= pending[1]:
                types = tuple(pending[2][:pending[1]])
                for code in "GRESJIC":
                    obs_types[code] = types
            return pending
        head = line[:6]
        if head.strip() == "":  # continuation line
            if pending is None:
                raise self._error("a system code and a number of types in columns 1-6", line,
                                  lineno)
        else:
            code, count = head[0], head[3:6].strip()
            if code not in SYSTEMS or not count.isdigit():
                raise self._error("a system code (G, R, E, C, J, I, S) in column 1 and a "
                                  "number of types in columns 4-6", line, lineno)
            pending = (code, int(count), [])
        pending[2].extend(line[7:60].split())
        if len(pending[2]) >= pending[1]:
            obs_types[pending[0]] = tuple(pending[2][:pending[1]])
        return pending

    # -- epoch records ---------------------------------------------------------------

    def __iter__(self):
        header = self.header
        parse = self._record_3 if header.major > 2 else self._record_2
        while True:
            line = self._read()
            if line is None:
                if self._pipe is not None:
                    self._pipe.check(self.lineno + 1)
                return
            self.lineno += 1
            if not line.strip():  # a blank line (at the end): kept as it is
                yield EpochRecord(self.lineno, [line], None, None)
                continue
            yield parse(line)

    def _satellites_2(self, record):
        """Read the observation lines of ``record.satellites`` (RINEX 2, flags 0, 1, 6)."""
        header = self.header
        for sat in record.satellites:
            system = sat[0]
            if system not in header.obs_types:
                raise self._error(f"a satellite of a system whose observation types the "
                                  f"header declares ({', '.join(header.obs_types)})",
                                  f"{sat} in the epoch record", record.lineno)
            types = header.obs_types[system]
            record.starts.append(len(record.lines))
            for k in range(header.record_lines(system)):
                line = self._next(f"observations of {sat} ({len(record.satellites)} "
                                  f"satellites announced by the epoch line {record.lineno})")
                width = FIELD * min(PER_LINE_2, len(types) - PER_LINE_2 * k)
                if len(line.rstrip()) > width:
                    raise self._error(f"at most {len(types)} observations of {sat} (the "
                                      f"types the header declares for system {system}: "
                                      f"{' '.join(types)})", line)
                record.lines.append(line)

    def _events(self, record, count):
        for _ in range(count):
            record.lines.append(self._next(f"{count} header lines of the event record "
                                           f"of line {record.lineno}"))

    def _record_3(self, line):
        lineno = self.lineno
        if line[:1] != ">" or len(line.rstrip()) < 35:
            raise self._error("an epoch line '> yyyy mm dd hh mm ss.sssssss f nnn'", line)
        flag, count = line[31:32], line[32:35].strip()
        if not flag.isdigit() or int(flag) > 6 or not count.isdigit():
            raise self._error("an epoch flag 0-6 in column 32 and a count in columns 33-35",
                              line)
        flag, count = int(flag), int(count)
        epoch = None
        if line[2:29].strip():
            epoch = self._calendar(line[2:29].split(), line, self.header.time_system)
        elif flag < 2 or flag == 6:
            raise self._error("the epoch's date and time", line)
        record = EpochRecord(lineno, [line], flag, epoch)
        if flag in (2, 3, 4, 5):
            self._events(record, count)
            if flag in (3, 4):
                self._header_change(record)
            return record
        sats = []
        for _ in range(count):
            peek = self._next(f"{count} satellites announced by the epoch line {lineno}")
            sats.append(peek)
        # Satellites are on their own lines: read them back as records.
        for text in sats:
            sat = text[:3].replace(" ", "0")
            if sat[0] not in SYSTEMS or not sat[1:].isdigit():
                raise self._error("a satellite's observations starting with its PRN (G05)",
                                  text)
            record.satellites.append(sat)
        record.lines.extend(sats)
        record.starts = list(range(1, count + 1))
        header = self.header
        for i, (sat, text) in enumerate(zip(record.satellites, sats)):
            system = sat[0]
            if system not in header.obs_types:
                raise self._error("a satellite of a system whose observation types the header "
                                  f"declares ({', '.join(header.obs_types)})", text,
                                  lineno + 1 + i)
            width = 3 + FIELD * len(header.obs_types[system])
            if len(text.rstrip()) > width:
                raise self._error(f"at most {len(header.obs_types[system])} observations of "
                                  f"{sat} (the types the header declares for system {system}: "
                                  f"{' '.join(header.obs_types[system])})", text, lineno + 1 + i)
        return record

    def _record_2(self, line):
        lineno = self.lineno
        flag, count = line[28:29], line[29:32].strip()
        if not flag.isdigit() or int(flag) > 6 or not count.isdigit():
            raise self._error("an epoch line ' yy mm dd hh mm ss.sssssss  f nnn' with an epoch "
                              "flag 0-6 in column 29 and a count in columns 30-32", line)
        flag, count = int(flag), int(count)
        epoch = None
        if line[:26].strip():
            fields = line[:26].split()
            if len(fields) != 6 or not fields[0].isdigit():
                raise self._error("an epoch line ' yy mm dd hh mm ss.sssssss  f nnn'", line)
            year = int(fields[0])
            fields[0] = str(year + (2000 if year < 80 else 1900) if year < 100 else year)
            epoch = self._calendar(fields, line, self.header.time_system)
        elif flag < 2 or flag == 6:
            raise self._error("the epoch's date and time", line)
        record = EpochRecord(lineno, [line], flag, epoch)
        if flag in (2, 3, 4, 5):
            self._events(record, count)
            if flag in (3, 4):
                self._header_change(record)
            return record
        prns = line[32:68]
        for k in range(12, count, 12):
            more = self._next(f"the continuation of the {count} satellites of the epoch line "
                              f"{lineno}")
            record.lines.append(more)
            prns += more[32:68]
        default = self.header.system if self.header.system in SYSTEMS else "G"
        for k in range(count):
            prn = prns[3 * k:3 * k + 3]
            code = prn[0] if prn[0] != " " else default
            number = prn[1:].strip()
            if code not in SYSTEMS or not number.isdigit():
                raise self._error(f"{count} satellites (A1,I2 each) from column 33", line,
                                  lineno)
            record.satellites.append(f"{code}{int(number):02d}")
        self._satellites_2(record)
        return record


def read_rinex_header(source):
    """The header of a RINEX observation file (its records are not read).

    Parameters
    ----------
    source : str, path-like or file object
        As for `RinexReader`.

    Returns
    -------
    `RinexHeader`

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        As `RinexReader`.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.gnss import read_rinex_header
    >>> header = read_rinex_header(sample_file("gnss_sample.rnx"))
    >>> header.version, sorted(header.obs_types)
    ('3.04', ['C', 'E', 'G', 'R'])
    """
    with RinexReader(source) as reader:
        return reader.header


def record_times(records, time_system):
    """The epochs of records as one `~astropy.time.Time` (TAI or UTC, as `epochs_to_time`).

    Examples
    --------
    >>> from astropy_feedrot.gnss.rinex import EpochRecord, record_times
    >>> record_times([EpochRecord(1, [], 0, (2023, 1, 25, 0, 0, 0.0))], "GPS").isot
    array(['2023-01-25T00:00:19.000'], dtype='<U23')
    """
    return epochs_to_time([record.epoch for record in records], time_system)
