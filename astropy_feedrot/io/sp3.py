# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reader of SP3 precise orbit files (SP3-c and SP3-d, and the older SP3-a/b).

The format is described in S. Hilla, "The Extended Standard Product 3 Orbit
Format (SP3-c)" (NGS, 2010) and "(SP3-d)" (NGS, 2016). The reader relies on:

* line 1: ``#`` and the version letter in column 2, the number of epochs in
  columns 33-39, the coordinate system in columns 47-51;
* line 2: ``##`` and the epoch interval in seconds in columns 25-38;
* the ``+`` lines: the number of satellites in columns 4-6 of the first one
  and 17 three-character satellite IDs per line from column 10 (unused slots
  ``  0``). SP3-c has exactly five such lines (at most 85 satellites); SP3-d
  has as many as needed (up to 999 satellites);
* the first ``%c`` line: the time system in columns 10-12;
* comment lines ``/*`` (four in SP3-c, any number in SP3-d), skipped wherever
  they are in the header;
* epoch lines ``*  yyyy mm dd hh mm ss.ssssssss``, increasing by the
  interval of line 2 or by a whole number of intervals (a gap, recorded in
  `SP3Data.gaps`);
* position records ``P<sat>`` with x, y, z in km in columns 5-46 and the
  clock in microseconds in columns 47-60, fixed-point numbers (F14.6). A bad
  or absent position is written as 0.000000 for all three coordinates (or,
  by some writers, 999999.999999 as for the clock), a bad or absent clock as
  999999.999999; all become NaN here. Velocity (``V``) and correlation
  (``EP``, ``EV``) records are skipped;
* the last line ``EOF``.

What the reader refuses, with a `FileFormatError` naming the line: an epoch
that repeats or precedes the one before it, or lies off the grid of the
interval; a number that is not a fixed-point number, including
``nan`` and ``inf``; a record cut short inside a number; besides the breaks
of the layout above.

A number of epochs on line 1 that disagrees with the epoch lines (a file
trimmed to a few hours whose header still counts the day) is a warning
(`~astropy_feedrot.OrbitWarning`): the epochs of the file are read, as
RTKLIB reads them.

What the reader does not interpolate, with one `~astropy_feedrot.OrbitWarning`
per file: positions that no orbit around the Earth can have, which become
NaN (holes). A position is implausible when its distance from the geocentre
lies outside the band of its system (`RADIUS_LIMITS`; inside the Earth for
any satellite), or when it breaks the smoothness of the orbit: over five
consecutive epochs at the file's interval ``h``, the fourth difference of a
satellite's positions is at most about ``r (omega h)**4``, with ``omega``
the fastest angular rate of an orbit at radius ``r`` seen from the rotating
Earth (mean motion plus the Earth's rotation); the reader allows ten times
that, plus a metre: 400 km for GPS at 15-minute epochs, 5 km at 5-minute
epochs, which a single record 1,000 km (or 10 km) off exceeds. The record
that best explains the excess (least squares over the windows holding it)
is dropped, and the check repeats until every window is smooth. Files with fewer than five
consecutive epochs get the radius check only.

SP3-a files (satellite IDs as I3 numbers) and SP3-b files are read too; their
satellite IDs ``'  5'`` or ``'G 5'`` become ``'G05'`` and, when the ``%c`` line
leaves the time system open, it is GPS time.
"""

import dataclasses
import datetime
import re

import numpy as np
from astropy import units as u
from astropy.time import Time

from ..core.exceptions import OrbitWarning, warn_caller
from ._common import (
    TIME_SYSTEMS,
    FileFormatError,
    check_epoch,
    epochs_to_time,
    first_duplicate,
    known_time_systems,
    open_lines,
    readonly,
)

__all__ = ["SP3Data", "implausible_positions", "read_sp3", "join_sp3"]

#: Clock values at or above this (the format writes 999999.999999) are bad or absent;
#: so are positions with a coordinate of this size (km) or more.
BAD_CLOCK = 999999.0

#: Geocentric gravitational constant (m3/s2, IERS Conventions 2010, Table 1.1).
GM_EARTH = 3.986004418e14

#: The Earth's rotation rate (rad/s, IERS Conventions 2010, Table 1.1).
OMEGA_EARTH = 7.292115e-5

#: Plausible distance from the geocentre (m) by the system letter of the satellite ID.
#: GNSS orbits lie between 23,200 km (perigee of Galileo E14 and E18, the most eccentric)
#: and 45,300 km (apogee of the QZSS inclined orbits); any other satellite lies above
#: the Earth's equatorial radius plus 100 km and within 400,000 km (the Moon's distance).
RADIUS_LIMITS = {
    "G": (20e6, 35e6), "R": (20e6, 35e6), "E": (20e6, 35e6), "C": (20e6, 48e6),
    "J": (20e6, 48e6), "I": (20e6, 48e6), "S": (20e6, 48e6),
}
OTHER_RADIUS_LIMITS = (6.478e6, 4e8)

# Fourth differences over five consecutive epochs: the weights, and the margin (factor,
# metres) allowed above the bound r (omega h)**4 of a smooth orbit.
_D4 = np.array([1.0, -4.0, 6.0, -4.0, 1.0])
_D4_FACTOR = 10.0
_D4_FLOOR = 1.0

#: Two epochs closer than this (seconds) are the same; an epoch further than
#: this from a whole number of intervals after the previous one is off the grid.
EPOCH_TOLERANCE = 1e-5

_VERSIONS = "abcd"
_POSITION_RECORD = "a position record 'P<sat> x y z clock' (numbers in columns 5-60)"
# A fixed-point number as the format writes it (F14.6): no exponent, no 'nan' or 'inf'.
_FIXED = re.compile(r" *-?(\d+\.?\d*|\.\d+)")
_NOT_FINITE = ("finite numbers in columns 5-60 ('nan' and 'inf' are not SP3 values: a bad "
               "or absent position is written 0.000000, a bad or absent clock 999999.999999)")


@dataclasses.dataclass(frozen=True, eq=False, repr=False)
class SP3Data:
    """Contents of an SP3 orbit file.

    Returned by `read_sp3`. Arrays are read-only.

    Attributes
    ----------
    version : str
        Format version letter from line 1: ``'a'``, ``'b'``, ``'c'`` or ``'d'``.
    time_system : str
        Time system code of the file (``'GPS'``, ``'GAL'``, ``'UTC'``, ...).
    coordinate_system : str
        Coordinate system from line 1, e.g. ``'IGS20'``.
    satellites : tuple of str
        Satellite IDs in the order of the header, e.g. ``('G01', 'E11')``.
    epochs : `~astropy.time.Time`, shape (N,)
        The epoch lines of the file, converted from the file's time system to
        TAI (atomic system times) or UTC (UTC and GLO).
    positions : dict of str to ndarray, shape (N, 3)
        Earth-fixed position of each satellite in metres; NaN where the file
        has no record or marks the position bad.
    clock : dict of str to ndarray, shape (N,)
        Clock correction of each satellite in seconds; NaN where the file has
        no record or marks the clock bad.
    interval : float
        Epoch interval of the header (line 2), in seconds.
    gaps : tuple of (int, int)
        Where the file skips epochs: pairs ``(i, i + 1)`` of indices into
        ``epochs`` between which more than one interval passes.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.io import SP3Data
    >>> data = SP3Data(
    ...     version="d", time_system="GPS", coordinate_system="IGS20",
    ...     satellites=("G01",), epochs=Time(["2023-01-25T00:00:19"], scale="tai"),
    ...     positions={"G01": np.array([[5364995.752, -25736687.425, 3778007.538]])},
    ...     clock={"G01": np.array([-89.426574e-6])})
    >>> data
    <SP3Data version='d' time_system='GPS' coordinate_system='IGS20' 1 satellite, 1 epoch>
    >>> float(np.linalg.norm(data.positions["G01"][0]))  # doctest: +FLOAT_CMP
    26560000.0
    """

    version: str
    time_system: str
    coordinate_system: str
    satellites: tuple
    epochs: Time
    positions: dict
    clock: dict
    interval: float = None
    gaps: tuple = ()

    def __repr__(self):
        nsat = len(self.satellites)
        nep = len(self.epochs)
        return (
            f"<SP3Data version={self.version!r} time_system={self.time_system!r} "
            f"coordinate_system={self.coordinate_system!r} "
            f"{nsat} satellite{'' if nsat == 1 else 's'}, {nep} epoch{'' if nep == 1 else 's'}>"
        )


def _satellite_id(field):
    """Normalise a three-character SP3 satellite field; None if it is not one.

    ``'G01'`` stays; ``'G 1'``, ``' 01'`` and ``'  1'`` (SP3-a/b) become
    ``'G01'``; ``'  0'`` (an unused header slot) gives ``''``.
    """
    field = field.ljust(3)
    letter, number = field[0], field[1:]
    if letter.isdigit():
        letter, number = " ", field
    if letter == " ":
        letter = "G"
    elif not letter.isalpha():
        return None
    number = number.strip()
    if not number.isdigit():
        return None
    prn = int(number)
    if prn == 0:
        return ""
    return f"{letter}{prn:02d}"


class _Reader:
    """One pass over the lines of an SP3 file."""

    def __init__(self, name, lines):
        self.name = name
        self.lines = lines
        self.lineno = 0

    def error(self, expected, found, lineno=None):
        if lineno is None:
            # At the end of the file, the missing line would have been the next one.
            lineno = self.lineno + 1 if found is None else self.lineno
        return FileFormatError(self.name, lineno, expected, found)

    def next_line(self):
        for line in self.lines:
            self.lineno += 1
            return line
        return None

    def read(self):
        version, coordinate_system, nominal = self.read_first_lines()
        satellites, time_system, line = self.read_header(version)
        epochs, records = self.read_data(satellites, time_system, line)
        return self.build(version, time_system, coordinate_system, satellites, epochs, records,
                          nominal)

    # --- header ---------------------------------------------------------------

    def read_first_lines(self):
        first = self.next_line()
        expected = "an SP3 version line '#c' or '#d' (or '#a', '#b') with the first epoch"
        if first is None:
            raise self.error(expected + " (the file is empty)", None, lineno=1)
        if len(first) < 3 or first[0] != "#" or first[1] not in _VERSIONS:
            raise self.error(expected, first)
        if first[2] not in "PV":
            raise self.error(expected + ", with 'P' or 'V' in column 3", first)
        count = first[32:39]
        if not count.strip().isdigit():
            raise self.error("the number of epochs in columns 33-39 of line 1", first)
        coordinate_system = first[46:51].strip()
        second = self.next_line()
        if second is None or not second.startswith("##"):
            raise self.error("the second header line '## <GPS week> <seconds of week> ...'",
                             second)
        interval = second[24:38]
        if not _FIXED.fullmatch(interval) or not float(interval) > 0:
            raise self.error("the epoch interval in seconds, above zero, in columns 25-38 of "
                             "line 2", second)
        nominal = {"line": first, "epochs": int(count), "interval": float(interval)}
        return first[1], coordinate_system, nominal

    def read_header(self, version):
        ids = []
        nsat = None
        time_system = None
        while True:
            line = self.next_line()
            if line is None:
                raise self.error("more header lines or the first epoch line '*  yyyy mm dd ...'",
                                 None)
            if line.startswith("++"):
                continue
            if line.startswith("+"):
                if nsat is None:
                    try:
                        nsat = int(line[1:6])
                    except ValueError:
                        raise self.error("the number of satellites in columns 4-6 of the "
                                         "first '+' line", line) from None
                for k in range(9, 60, 3):
                    sat = _satellite_id(line[k:k + 3]) if line[k:k + 3].strip() else ""
                    if sat is None:
                        raise self.error("satellite IDs such as 'G01' in columns 10-60 of "
                                         "the '+' lines", line)
                    if sat:
                        ids.append(sat)
            elif line.startswith("%c"):
                if time_system is None:
                    time_system = self.parse_time_system(line, version)
            elif line.startswith(("%f", "%i", "/*", "%/*")):
                continue
            elif line.startswith("*"):
                break
            else:
                raise self.error("a header line ('+', '++', '%c', '%f', '%i', '/*') or the "
                                 "first epoch line '*  yyyy mm dd hh mm ss'", line)
        if nsat is None:
            raise self.error("the '+' lines listing the satellites before the first epoch", line)
        if len(ids) != nsat:
            raise self.error(f"{nsat} satellite IDs in the '+' lines, as their count says "
                             f"(found {len(ids)}), before the first epoch", line)
        if len(set(ids)) != len(ids):
            raise self.error("each satellite listed once in the '+' lines", line)
        if time_system is None:
            if version in "ab":
                time_system = "GPS"
            else:
                raise self.error("a '%c' line with the time system before the first epoch",
                                 line)
        return tuple(ids), time_system, line

    def parse_time_system(self, line, version):
        code = line[9:12].strip()
        if version in "ab" and code in ("", "ccc"):
            return "GPS"
        if code not in TIME_SYSTEMS:
            raise self.error("a time system in columns 10-12 of the first '%c' line, one of "
                             + known_time_systems(), line)
        return code

    # --- data -----------------------------------------------------------------

    def read_data(self, satellites, time_system, line):
        index = {sat: k for k, sat in enumerate(satellites)}
        epochs = []
        ep_idx, sat_idx, linenos, values = [], [], [], []
        epoch_expected = "an epoch line '*  yyyy mm dd hh mm ss.ssssssss'"
        while line is not None:
            head = line[:1]
            if head == "P":
                if not epochs:
                    raise self.error(epoch_expected + " before the first record", line)
                sat = _satellite_id(line[1:4])
                if not sat:
                    raise self.error(_POSITION_RECORD, line)
                k = index.get(sat)
                if k is None:
                    raise self.error(
                        f"a record for one of the {len(satellites)} satellites of the header "
                        f"({', '.join(satellites[:5])}{', ...' if len(satellites) > 5 else ''})",
                        line)
                ep_idx.append(len(epochs) - 1)
                sat_idx.append(k)
                linenos.append(self.lineno)
                values.append(self.parse_record(line))
            elif head == "*":
                fields = line[1:].split()
                epoch = check_epoch(fields, time_system) if len(fields) == 6 else None
                if epoch is None:
                    raise self.error(epoch_expected + " with a valid date and time", line)
                epochs.append((epoch, self.lineno, line))
            elif head == "V" or line.startswith(("EP", "EV", "/*")) or not line.strip():
                pass
            elif line.startswith("EOF"):
                return epochs, (ep_idx, sat_idx, linenos, values)
            else:
                raise self.error(f"{epoch_expected}, {_POSITION_RECORD}, a 'V', 'EP' or 'EV' "
                                 "record, or 'EOF'", line)
            line = self.next_line()
        raise self.error("the last line 'EOF' (the file seems truncated)", None)

    def parse_record(self, line):
        """x, y, z (km) and clock (microseconds, NaN if blank) of a position record."""
        if len(line) < 46:
            raise self.error(_POSITION_RECORD + ", x, y and z complete in columns 5-46", line)
        fields = [line[4:18], line[18:32], line[32:46]]
        clock = line[46:60]
        if clock.strip():
            fields.append(clock)
        for field in fields:
            if not _FIXED.fullmatch(field):
                text = field.strip().lower().lstrip("+-")
                if text.startswith(("nan", "inf")) or _is_overflow(field):
                    raise self.error(_NOT_FINITE, line)
                raise self.error(_POSITION_RECORD, line)
        x, y, z = (float(f) for f in fields[:3])
        return (x, y, z, float(clock) if clock.strip() else np.nan)

    def check_epochs(self, epochs, interval):
        """Seconds of each epoch after the first, checking the steps; return them and the gaps."""
        first = epochs[0][0]
        day0 = datetime.date(*first[:3]).toordinal()
        offsets = np.array([
            (datetime.date(*e[:3]).toordinal() - day0) * 86400.0
            + (e[3] - first[3]) * 3600.0 + (e[4] - first[4]) * 60.0 + (e[5] - first[5])
            for e, _, _ in epochs])
        steps = np.diff(offsets)
        multiples = np.round(steps / interval)
        off_grid = np.abs(steps - multiples * interval) > EPOCH_TOLERANCE
        bad = (steps <= EPOCH_TOLERANCE) | off_grid
        if np.any(bad):
            i = int(np.argmax(bad))
            _, previous, _ = epochs[i]
            _, lineno, line = epochs[i + 1]
            if steps[i] < -EPOCH_TOLERANCE:
                what = (f"an epoch later than the one on line {previous} (epochs must "
                        "increase; this one is earlier)")
            elif steps[i] <= EPOCH_TOLERANCE:
                what = (f"an epoch later than the one on line {previous} (this one repeats "
                        "it)")
            else:
                what = (f"an epoch a whole number of {interval:g} s intervals (line 2) after "
                        f"the one on line {previous} ({steps[i]:.8g} s later)")
            raise self.error(what, line, lineno=lineno)
        gaps = tuple((int(i), int(i) + 1) for i in np.flatnonzero(multiples > 1))
        return offsets, gaps

    def build(self, version, time_system, coordinate_system, satellites, epochs, records,
              nominal):
        ep_idx, sat_idx, linenos, values = records
        nsat, nep = len(satellites), len(epochs)
        offsets, gaps = self.check_epochs(epochs, nominal["interval"])
        span = int(round(offsets[-1] / nominal["interval"])) + 1
        if nominal["epochs"] not in (nep, span):
            # A trimmed file whose line 1 still counts the whole day: read as RTKLIB reads
            # it (readsp3b never checks the count), with one warning.
            warn_caller(
                f"{self.name}: line 1 counts {nominal['epochs']} epochs (columns 33-39), but "
                f"the file has {nep} epoch lines (a span of {span}); the epochs of the file "
                "are read (a file trimmed, cut short or joined?)", OrbitWarning)
        dup = first_duplicate(ep_idx, sat_idx, nsat)
        if dup is not None:
            raise self.error(f"one record per satellite and epoch, not a second one for "
                             f"{satellites[sat_idx[dup]]}", "P" + satellites[sat_idx[dup]],
                             lineno=linenos[dup])
        pos = np.full((nsat, nep, 3), np.nan)
        clk = np.full((nsat, nep), np.nan)
        if values:
            vals = np.array(values, dtype=float)
            xyz = vals[:, :3] * 1e3
            xyz[np.all(vals[:, :3] == 0.0, axis=1)] = np.nan
            xyz[np.any(np.abs(vals[:, :3]) >= BAD_CLOCK, axis=1)] = np.nan
            c = vals[:, 3]
            c = np.where(c >= BAD_CLOCK, np.nan, c * 1e-6)
            pos[sat_idx, ep_idx] = xyz
            clk[sat_idx, ep_idx] = c
            lines = np.zeros((nsat, nep), dtype=int)
            lines[sat_idx, ep_idx] = linenos
            self.drop_implausible(satellites, pos, offsets, nominal["interval"], lines)
        return SP3Data(
            version=version,
            time_system=time_system,
            coordinate_system=coordinate_system,
            satellites=satellites,
            epochs=epochs_to_time([e for e, _, _ in epochs], time_system),
            positions={sat: readonly(pos[k]) for k, sat in enumerate(satellites)},
            clock={sat: readonly(clk[k]) for k, sat in enumerate(satellites)},
            interval=nominal["interval"],
            gaps=gaps,
        )

    def drop_implausible(self, satellites, pos, offsets, interval, lines):
        """Set implausible positions to NaN (in place), warning once."""
        bad = implausible_positions(satellites, pos, offsets, interval)
        if not np.any(bad):
            return
        k, e = np.argwhere(bad)[0]
        r = np.linalg.norm(pos[k, e])
        pos[bad] = np.nan
        warn_caller(
            f"{self.name}: {np.count_nonzero(bad)} position record(s) no orbit can have (the "
            f"first: {satellites[k]} on line {lines[k, e]}, {r / 1e3:.0f} km from the "
            "geocentre, off the radius of its system or off the smooth path through its "
            "neighbours); they are treated as missing (NaN), never interpolated", OrbitWarning)


def implausible_positions(satellites, positions, seconds, interval):
    """Which positions of an SP3 file no orbit around the Earth can have.

    Parameters
    ----------
    satellites : sequence of str
        SP3 satellite IDs (``'G01'``...), whose letters choose the radius
        band of `RADIUS_LIMITS`.
    positions : ndarray, shape (len(satellites), N, 3)
        Earth-fixed positions in metres, NaN where missing.
    seconds : ndarray, shape (N,)
        Times of the epochs in seconds.
    interval : float
        The file's epoch interval in seconds.

    Returns
    -------
    ndarray of bool, shape (len(satellites), N)
        True where a position lies outside the radius band of its system, or
        is the record that breaks the smoothness of the orbit through five
        consecutive epochs (see the module's description).

    Examples
    --------
    A circular 12-hour orbit at 5-minute epochs, one record moved by 1,000 km:

    >>> import numpy as np
    >>> from astropy_feedrot.io.sp3 import implausible_positions
    >>> t = np.arange(20) * 300.0
    >>> angle = 2 * np.pi * t / 43082.0
    >>> xyz = 26.56e6 * np.stack([np.cos(angle), np.sin(angle), 0 * t], axis=-1)
    >>> xyz[7, 2] += 1e6
    >>> np.flatnonzero(implausible_positions(["G01"], xyz[np.newaxis], t, 300.0))
    array([7])
    """
    pos = np.asarray(positions, dtype=float)
    r = np.linalg.norm(pos, axis=-1)
    low = np.array([RADIUS_LIMITS.get(s[:1], OTHER_RADIUS_LIMITS)[0] for s in satellites])
    high = np.array([RADIUS_LIMITS.get(s[:1], OTHER_RADIUS_LIMITS)[1] for s in satellites])
    with np.errstate(invalid="ignore"):
        bad = (r < low[:, np.newaxis]) | (r > high[:, np.newaxis])
    nep = pos.shape[1]
    if nep < len(_D4):
        return bad
    steps = np.abs(np.diff(seconds) - interval) < EPOCH_TOLERANCE
    nwin = nep - len(_D4) + 1
    # Windows of five epochs one interval apart.
    on_grid = np.all([steps[k:k + nwin] for k in range(len(_D4) - 1)], axis=0)
    while True:
        valid = np.isfinite(r) & ~bad
        usable = on_grid & np.all([valid[:, k:k + nwin] for k in range(len(_D4))], axis=0)
        d4 = sum(c * np.where(valid[:, k:k + nwin, np.newaxis], pos[:, k:k + nwin], 0.0)
                 for k, c in enumerate(_D4))
        if not np.any(usable):
            return bad
        radii = np.stack([r[:, k:k + nwin] for k in range(len(_D4))])
        with np.errstate(invalid="ignore"):
            rmin = np.min(radii, axis=0)
            rmax = np.max(radii, axis=0)
        with np.errstate(invalid="ignore"):
            omega = np.sqrt(GM_EARTH / rmin**3) + OMEGA_EARTH
            limit = _D4_FACTOR * rmax * (omega * interval) ** 4 + _D4_FLOOR
            rough = usable & (np.linalg.norm(d4, axis=-1) > limit)
        if not np.any(rough):
            return bad
        # The record that best explains the rough windows, per satellite (least squares).
        score = np.zeros(pos.shape)
        weight = np.zeros(r.shape)
        for k, c in enumerate(_D4):
            score[:, k:k + nwin] += np.where(usable[..., np.newaxis], c * d4, 0.0)
            weight[:, k:k + nwin] += np.where(usable, c * c, 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            gain = np.where(weight > 0, np.sum(score**2, axis=-1) / weight, -1.0)
        sats = np.flatnonzero(np.any(rough, axis=1))
        bad[sats, np.argmax(gain[sats], axis=1)] = True


def _is_overflow(field):
    """Whether a field reads as a number too large for a float (e.g. '1e999')."""
    try:
        return not np.isfinite(float(field))
    except ValueError:
        return False


def read_sp3(source):
    """Read an SP3 precise orbit file (SP3-c or SP3-d; SP3-a/b too).

    Parameters
    ----------
    source : str, `os.PathLike` or file object
        Path of the file (``.gz`` files are decompressed), or an open file
        object with a ``readline`` method (text or binary).

    Returns
    -------
    `SP3Data`
        Satellites, epochs (as astropy `~astropy.time.Time` in TAI or UTC),
        Earth-fixed positions in metres and clock corrections in seconds, with
        NaN for missing or bad values.

    Raises
    ------
    FileFormatError
        If the file does not follow the SP3 format; the message gives the
        file, the line, what was found and what was expected.
    TypeError
        If ``source`` is neither a path nor a file object.

    Examples
    --------
    A one-epoch SP3-d file with two satellites, Galileo E11's clock marked bad:

    >>> import io
    >>> from astropy_feedrot.io import read_sp3
    >>> text = '''#dP2023  1 25  0  0  0.00000000       1 ORBIT IGS20 FIT  XYZ
    ... ## 2246 259200.00000000   300.00000000 59969 0.0000000000000
    ... +    2   G01E11  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... +          0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... +          0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... +          0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... +          0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... ++         6  7  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... ++         0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... ++         0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... ++         0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... ++         0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
    ... %c M  cc GPS ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc
    ... %c cc cc ccc ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc
    ... %f  1.2500000  1.025000000  0.00000000000  0.000000000000000
    ... %f  0.0000000  0.000000000  0.00000000000  0.000000000000000
    ... %i    0    0    0    0      0      0      0      0         0
    ... %i    0    0    0    0      0      0      0      0         0
    ... /* EXAMPLE
    ... *  2023  1 25  0  0  0.00000000
    ... PG01   5364.995752 -25736.687425   3778.007538    -89.426574
    ... PE11  -4349.957317 -16112.867737  24446.131895 999999.999999
    ... EOF
    ... '''
    >>> data = read_sp3(io.StringIO(text))
    >>> data
    <SP3Data version='d' time_system='GPS' coordinate_system='IGS20' 2 satellites, 1 epoch>
    >>> data.satellites
    ('G01', 'E11')
    >>> data.epochs.utc.isot  # GPS time was 18 s ahead of UTC in 2023
    array(['2023-01-24T23:59:42.000'], dtype='<U23')
    >>> data.positions["G01"]
    array([[  5364995.752, -25736687.425,   3778007.538]])
    >>> data.clock["G01"], data.clock["E11"]
    (array([-8.9426574e-05]), array([nan]))
    """
    with open_lines(source) as (name, lines):
        return _Reader(name, lines).read()


def join_sp3(sources):
    """Join the SP3 files of consecutive days (or any sequence of spans) into one.

    Parameters
    ----------
    sources : sequence of str, path-like, file object or `SP3Data`
        The files (read with `read_sp3`) or their contents, in any order.

    Returns
    -------
    `SP3Data`
        Epochs of all files in order, each once; satellites of all files (a
        satellite absent from a file is NaN at its epochs). Where two files
        give the same epoch, the first file with a valid position gives it.
        Holes between files are listed in ``gaps``.

    Raises
    ------
    ValueError
        If ``sources`` is empty, or the files differ in time system, in
        coordinate system or in epoch interval (naming both).

    Examples
    --------
    The sample file split in two and joined again:

    >>> import numpy as np
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.io import read_sp3
    >>> from astropy_feedrot.io.sp3 import SP3Data, join_sp3
    >>> whole = read_sp3(sample_file("sample.sp3"))
    >>> def part(i):
    ...     return SP3Data(whole.version, whole.time_system, whole.coordinate_system,
    ...                    whole.satellites, whole.epochs[i],
    ...                    {s: p[i] for s, p in whole.positions.items()},
    ...                    {s: c[i] for s, c in whole.clock.items()}, whole.interval)
    >>> joined = join_sp3([part(slice(2, 4)), part(slice(0, 3))])
    >>> len(joined.epochs), bool(np.array_equal(joined.positions["G01"], whole.positions["G01"]))
    (4, True)
    """
    datas = [s if isinstance(s, SP3Data) else read_sp3(s) for s in sources]
    if not datas:
        raise ValueError("sources is empty; give at least one SP3 file")
    first = datas[0]
    for data in datas[1:]:
        for what in ("time_system", "coordinate_system", "interval"):
            if getattr(data, what) != getattr(first, what):
                raise ValueError(f"the SP3 files differ in {what.replace('_', ' ')}: "
                                 f"{getattr(first, what)!r} and {getattr(data, what)!r}; "
                                 "join files of one product series")
    if len(datas) == 1:
        return first
    satellites = tuple(dict.fromkeys(s for data in datas for s in data.satellites))
    seconds = [np.asarray((data.epochs - first.epochs[0]).sec, dtype=float) for data in datas]
    every = np.concatenate(seconds)
    # One epoch per cluster of times closer than EPOCH_TOLERANCE.
    order = np.argsort(every, kind="stable")
    ordered = every[order]
    new = np.r_[True, np.diff(ordered) > EPOCH_TOLERANCE]
    unique = ordered[new]
    index = np.empty(len(every), dtype=int)
    index[order] = np.cumsum(new) - 1
    positions = {s: np.full((len(unique), 3), np.nan) for s in satellites}
    clock = {s: np.full(len(unique), np.nan) for s in satellites}
    offset = 0
    for data, secs in zip(datas, seconds):
        where = index[offset:offset + len(secs)]
        offset += len(secs)
        for s in data.satellites:
            xyz = data.positions[s]
            empty = np.isnan(positions[s][where, 0])
            positions[s][where[empty]] = xyz[empty]
            empty = np.isnan(clock[s][where])
            clock[s][where[empty]] = data.clock[s][empty]
    times = first.epochs[0] + unique * u.s
    times.format = "isot"
    step = np.diff(unique)
    gaps = tuple((i, i + 1) for i in np.flatnonzero(step > first.interval + EPOCH_TOLERANCE))
    return SP3Data(first.version, first.time_system, first.coordinate_system, satellites,
                   times, {s: readonly(p) for s, p in positions.items()},
                   {s: readonly(c) for s, c in clock.items()}, first.interval, gaps)
