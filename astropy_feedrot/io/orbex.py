# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reader of satellite attitude quaternions from ORBEX files.

ORBEX, the orbit exchange format of the IGS (J. Loyer, S. Banville, J. Geng,
S. Strasser, "ORBEX: The Orbit Exchange Format", version 0.09), is built of
blocks opened by ``+NAME`` and closed by ``-NAME`` lines, after a first line
``%=ORBEX <version>`` and up to a last line ``%END_ORBEX``. This reader uses

* the ``+FILE/DESCRIPTION`` block: ``TIME_SYSTEM`` (``GPS``, ``GAL``, ...),
  ``COORD_SYSTEM`` (the terrestrial frame, one word, e.g. ``IGS20``) and
  ``FRAME_TYPE``, exactly ``ECEF`` or ``ECI``; each given once (or repeated
  with the same value);
* the ``+EPHEMERIS/DATA`` block: epoch lines
  ``## yyyy mm dd hh mm ss.ssssssssssss n``, each later than the one before,
  and, for each of them, records ``' <TYPE> <sat> ... N <N values>'``. Only
  ``ATT`` records (``N = 4``, four finite numbers) are read; positions,
  velocities and clocks (``POS``, ``VEL``, ``CLK``, ``PCS``, ...) and
  comment lines ``*`` are skipped.

What the reader refuses, with a `FileFormatError` naming the line: a
``FRAME_TYPE`` other than ``ECEF`` or ``ECI`` (``ecef``, ``ITRF``,
``ECEF J2000``...), a ``COORD_SYSTEM`` that is not one word, a description
field given twice with different values, an epoch line that repeats or
precedes the one before it, an ``ATT`` record with a number that does not
read or is not finite (``nan``, ``inf``, ``1e999``), a second ``ATT`` record
of a satellite at one epoch; besides the breaks of the layout above. A file
without ``FRAME_TYPE`` is read (`ORBEXData.frame_type` is None), but
`~astropy_feedrot.QuaternionAttitude.from_orbex` then needs to be told the
frame.

Quaternion convention
---------------------
An ``ATT`` record holds the attitude quaternion ``q = (q0, q1, q2, q3)``,
scalar ``q0`` first. The ORBEX description defines it as the rotation from
the reference frame of the file to the satellite body frame; the reference
frame is the terrestrial frame of ``COORD_SYSTEM`` when ``FRAME_TYPE`` is
``ECEF`` (the usual case for GNSS attitude products) and a celestial frame
when it is ``ECI``. Attitude files in this format state the relation in a
comment above their ``ATT`` records as ``(0,B) = q.(0,T).trans(q)``, with
``T`` and ``B`` the coordinates of a vector in the terrestrial and body
frames and ``trans(q)`` the conjugate ``q* = (q0, -q1, -q2, -q3)``. With the
Hamilton product this is

    (0, r_B) = q (0, r_T) q*,   that is   r_B = R(q) r_T,

    R(q) = [[1 - 2(q2² + q3²),  2(q1 q2 - q0 q3),  2(q1 q3 + q0 q2)],
            [2(q1 q2 + q0 q3),  1 - 2(q1² + q3²),  2(q2 q3 - q0 q1)],
            [2(q1 q3 - q0 q2),  2(q2 q3 + q0 q1),  1 - 2(q1² + q2²)]]

for a unit quaternion. So ``q`` transforms coordinates from the reference
frame to the body frame (a passive rotation), the rows of ``R(q)`` are the
body axes ``x_B``, ``y_B``, ``z_B`` expressed in the reference frame, and
body coordinates go back to the reference frame with ``R(q).T``, the matrix
of ``q*``. This reading was checked on the ``ATT`` records of an attitude
file of the IGS analysis centre CNES/CLS (2018-10-21, GPS, GLONASS and
Galileo satellites in yaw steering): the rows of ``R(q)`` give body ``y``
axes perpendicular to the Sun to 1e-4 and the Sun on the ``+x`` side, as the
nominal attitude requires; the columns of ``R(q)`` (the conjugate reading)
do not.

The quaternions are returned exactly as in the file: not normalised, not
conjugated, with the sign chosen by the file (``q`` and ``-q`` are the same
rotation).
"""

import dataclasses
import datetime
import re

import numpy as np

from ._common import (
    DECIMAL,
    TIME_SYSTEMS,
    FileFormatError,
    check_epoch,
    epochs_to_time,
    first_duplicate,
    known_time_systems,
    open_lines,
    readonly,
)

__all__ = ["ORBEXData", "read_orbex"]

_ATT_RECORD = "an ATT record ' ATT <sat> 4 q0 q1 q2 q3' with four numbers"
_FRAME_TYPES = ("ECEF", "ECI")
# Description fields the reader uses, and what each must hold.
_FIELDS = {
    "TIME_SYSTEM": "a TIME_SYSTEM, one of " + known_time_systems(),
    "COORD_SYSTEM": "a COORD_SYSTEM, one word such as IGS20",
    "FRAME_TYPE": "a FRAME_TYPE, one of " + ", ".join(_FRAME_TYPES),
}
_EPOCH_LINE = "an epoch line '## yyyy mm dd hh mm ss.ssssssssssss n' with a valid date and time"
# Any other data record: a blank, a three-character record type, a blank.
_OTHER_RECORD = re.compile(r" [A-Z][A-Z0-9]{2} ")


@dataclasses.dataclass(frozen=True, eq=False, repr=False)
class ORBEXData:
    """Attitude quaternions read from an ORBEX file.

    Returned by `read_orbex`. Arrays are read-only.

    Attributes
    ----------
    version : str
        Format version from the ``%=ORBEX`` line, e.g. ``'0.09'``.
    time_system : str
        Time system code from ``TIME_SYSTEM`` (``'GPS'``, ``'GAL'``, ...).
    frame : str
        ``COORD_SYSTEM`` and ``FRAME_TYPE`` of the file, e.g.
        ``'IGS20 ECEF'`` (whichever of the two the file gives).
    frame_type : str or None
        ``FRAME_TYPE`` of the file: ``'ECEF'`` (quaternions from the
        terrestrial frame), ``'ECI'`` (from a celestial frame), or None when
        the file does not give it.
    satellites : tuple of str
        IDs of the satellites with ``ATT`` records, in order of appearance.
    attitude : dict of str to (`~astropy.time.Time`, ndarray)
        For each satellite, the epochs of its ``ATT`` records, shape (M,),
        converted to TAI (atomic system times) or UTC (UTC and GLO), and the
        quaternions ``[q0, q1, q2, q3]`` (scalar first), shape (M, 4),
        exactly as written in the file.
    quaternion_convention : str
        What the quaternions rotate, from the ORBEX description (see
        `read_orbex`): the rotation from the file's reference frame to the
        satellite body frame, ``(0, r_B) = q (0, r_T) q*``.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.io import ORBEXData
    >>> t = Time(["2023-01-25T00:00:19"], scale="tai")
    >>> data = ORBEXData(
    ...     version="0.09", time_system="GPS", frame="IGS20 ECEF", satellites=("G01",),
    ...     attitude={"G01": (t, np.array([[1.0, 0.0, 0.0, 0.0]]))},
    ...     quaternion_convention="rotation from the terrestrial frame to the body frame")
    >>> data
    <ORBEXData version='0.09' time_system='GPS' frame='IGS20 ECEF' 1 satellite, 1 record>
    >>> times, quaternions = data.attitude["G01"]
    >>> quaternions.shape
    (1, 4)
    """

    version: str
    time_system: str
    frame: str
    satellites: tuple
    attitude: dict
    quaternion_convention: str
    frame_type: str = None

    def __repr__(self):
        nsat = len(self.satellites)
        nrec = sum(len(q) for _, q in self.attitude.values())
        return (
            f"<ORBEXData version={self.version!r} time_system={self.time_system!r} "
            f"frame={self.frame!r} {nsat} satellite{'' if nsat == 1 else 's'}, "
            f"{nrec} record{'' if nrec == 1 else 's'}>"
        )


def _convention(frame_type):
    """The quaternion convention in words, for the file's FRAME_TYPE."""
    if frame_type == "ECEF":
        ref, r = "the terrestrial frame (ECEF)", "r_ECEF"
    elif frame_type == "ECI":
        ref, r = "the celestial frame (ECI)", "r_ECI"
    else:
        given = repr(frame_type) if frame_type else "not given"
        ref, r = f"the reference frame of the file (FRAME_TYPE {given})", "r_ref"
    return f"rotation from {ref} to the satellite body frame, (0, r_body) = q (0, {r}) q*"


def _read(name, lines):
    def error(lineno, expected, found):
        return FileFormatError(name, lineno, expected, found)

    lineno = 0
    line = None
    for line in lines:
        lineno = 1
        break
    version_expected = "an ORBEX version line '%=ORBEX <version>'"
    if lineno == 0:
        raise error(1, version_expected + " (the file is empty)", None)
    fields = line.split()
    if not line.startswith("%=ORBEX") or len(fields) < 2 or fields[0] != "%=ORBEX":
        raise error(1, version_expected, line)
    version = fields[1]

    # --- header blocks, up to +EPHEMERIS/DATA -----------------------------------
    description = {}
    where = {}
    in_description = False
    for lineno, line in enumerate(lines, start=2):
        if line.startswith("+EPHEMERIS/DATA"):
            break
        if line.startswith("+FILE/DESCRIPTION"):
            in_description = True
        elif line.startswith("-FILE/DESCRIPTION"):
            in_description = False
        elif in_description and line.startswith(" "):
            key, _, value = line.strip().partition(" ")
            value = value.strip()
            if key in _FIELDS and not _valid_field(key, value):
                raise error(lineno, _FIELDS[key], line)
            if key in _FIELDS and description.get(key, value) != value:
                raise error(lineno, f"{_FIELDS[key]}, the same as on line {where[key]} "
                            f"({description[key]})", line)
            description.setdefault(key, value)
            where.setdefault(key, lineno)
    else:
        raise error(lineno + 1, "a '+EPHEMERIS/DATA' block (this ORBEX file has none)", None)
    time_system = description.get("TIME_SYSTEM")
    if time_system is None:
        raise error(lineno, "a TIME_SYSTEM line in the +FILE/DESCRIPTION block before the "
                    "'+EPHEMERIS/DATA' block", line)

    # --- data block ---------------------------------------------------------------
    epochs = []
    index = {}
    ep_idx, sat_idx, linenos, quats = [], [], [], []
    current = -1
    epoch_line = None
    for lineno, line in enumerate(lines, start=lineno + 1):
        if line.startswith(" ATT "):
            parts = line.split()
            if len(parts) != 7 or parts[2] != "4":
                raise error(lineno, _ATT_RECORD, line)
            if current < 0:
                raise error(lineno, "an epoch line '## yyyy mm dd hh mm ss n' before the first "
                            "record", line)
            if not all(DECIMAL.fullmatch(p) for p in parts[3:]):
                lower = [p.lower().lstrip("+-") for p in parts[3:]]
                if not any(p.startswith(("nan", "inf")) for p in lower):
                    raise error(lineno, _ATT_RECORD, line)
                q = (np.nan,)
            else:
                q = (float(parts[3]), float(parts[4]), float(parts[5]), float(parts[6]))
            if not all(np.isfinite(q)):
                raise error(lineno, _ATT_RECORD.replace("four numbers", "four finite numbers")
                            + " ('nan' and 'inf' are not quaternion components)", line)
            k = index.setdefault(parts[1], len(index))
            ep_idx.append(current)
            sat_idx.append(k)
            linenos.append(lineno)
            quats.append(q)
        elif line.startswith("##"):
            fields = line[2:].split()
            epoch = check_epoch(fields, time_system) if len(fields) in (6, 7) else None
            if epoch is None or (len(fields) == 7 and not fields[6].isdigit()):
                raise error(lineno, _EPOCH_LINE, line)
            if epochs:
                step = _seconds_between(epochs[-1], epoch)
                if step <= 0:
                    how = "repeats it" if step == 0 else "is earlier"
                    raise error(lineno, f"an epoch later than the one on line {epoch_line} "
                                f"(epochs must increase; this one {how})", line)
            epochs.append(epoch)
            epoch_line = lineno
            current = len(epochs) - 1
        elif line.startswith("*") or not line.strip() or _OTHER_RECORD.match(line):
            continue
        elif line.startswith("-EPHEMERIS/DATA"):
            break
        else:
            raise error(lineno, f"{_EPOCH_LINE}, a record such as {_ATT_RECORD}, a comment "
                        "'*', or '-EPHEMERIS/DATA'", line)
    else:
        raise error(lineno + 1, "'-EPHEMERIS/DATA' closing the data block (the file seems "
                    "truncated)", None)

    for lineno, line in enumerate(lines, start=lineno + 1):
        if line.startswith("%END_ORBEX"):
            break
    else:
        raise error(lineno + 1, "the last line '%END_ORBEX' (the file seems truncated)", None)

    # --- arrays -----------------------------------------------------------------
    satellites = tuple(index)
    dup = first_duplicate(ep_idx, sat_idx, len(satellites))
    if dup is not None:
        raise error(linenos[dup], "one ATT record per satellite and epoch, not a second one for "
                    + satellites[sat_idx[dup]], "ATT " + satellites[sat_idx[dup]])
    times = epochs_to_time(epochs, time_system)
    q = np.array(quats, dtype=float).reshape(-1, 4)
    ep = np.array(ep_idx, dtype=np.intp)
    order = np.argsort(np.array(sat_idx, dtype=np.intp), kind="stable")
    counts = np.bincount(np.array(sat_idx, dtype=np.intp), minlength=len(satellites))
    attitude = {}
    for k, (sat, rows) in enumerate(zip(satellites, np.split(order, np.cumsum(counts)[:-1]))):
        attitude[sat] = (times[ep[rows]], readonly(q[rows]))
    frame_type = description.get("FRAME_TYPE", "")
    frame = " ".join(v for v in (description.get("COORD_SYSTEM", ""), frame_type) if v)
    return ORBEXData(
        version=version,
        time_system=time_system,
        frame=frame,
        satellites=satellites,
        attitude=attitude,
        quaternion_convention=_convention(frame_type),
        frame_type=frame_type or None,
    )


def _valid_field(key, value):
    """Whether a description field the reader uses holds a valid value."""
    if key == "TIME_SYSTEM":
        return value in TIME_SYSTEMS
    if key == "FRAME_TYPE":
        return value in _FRAME_TYPES
    return bool(value) and len(value.split()) == 1


def _seconds_between(earlier, later):
    """Seconds from one calendar reading to another (leap seconds ignored, as the labels)."""
    days = (datetime.date(*later[:3]).toordinal() - datetime.date(*earlier[:3]).toordinal())
    return (days * 86400.0 + (later[3] - earlier[3]) * 3600.0 + (later[4] - earlier[4]) * 60.0
            + (later[5] - earlier[5]))


def read_orbex(source):
    r"""Read the attitude quaternions of an ORBEX file.

    Parameters
    ----------
    source : str, `os.PathLike` or file object
        Path of the file (``.gz`` files are decompressed), or an open file
        object with a ``readline`` method (text or binary).

    Returns
    -------
    `ORBEXData`
        For each satellite with ``ATT`` records, the epochs (astropy
        `~astropy.time.Time` in TAI or UTC) and the quaternions as written,
        scalar first.

    Raises
    ------
    FileFormatError
        If the file does not follow the ORBEX format; the message gives the
        file, the line, what was found and what was expected.
    TypeError
        If ``source`` is neither a path nor a file object.

    Notes
    -----
    In ORBEX an ``ATT`` quaternion ``q = (q0, q1, q2, q3)`` is the rotation
    from the file's reference frame (terrestrial for ``FRAME_TYPE ECEF``,
    celestial for ``ECI``) to the satellite body frame: with the Hamilton
    product, ``(0, r_B) = q (0, r_T) q*``, i.e. ``r_B = R(q) r_T`` where

    .. math::

        R(q) = \begin{pmatrix}
        1 - 2(q_2^2 + q_3^2) & 2(q_1 q_2 - q_0 q_3) & 2(q_1 q_3 + q_0 q_2) \\
        2(q_1 q_2 + q_0 q_3) & 1 - 2(q_1^2 + q_3^2) & 2(q_2 q_3 - q_0 q_1) \\
        2(q_1 q_3 - q_0 q_2) & 2(q_2 q_3 + q_0 q_1) & 1 - 2(q_1^2 + q_2^2)
        \end{pmatrix}.

    The rows of :math:`R(q)` are the body axes expressed in the reference
    frame. The reasoning, from the ORBEX description, is in the docstring of
    the module ``astropy_feedrot.io.orbex``.

    Examples
    --------
    Two epochs of one GPS satellite; the body axes are the rows of the
    rotation matrix of ``q``:

    >>> import io
    >>> import numpy as np
    >>> from astropy_feedrot.io import read_orbex
    >>> text = '''%=ORBEX  0.09
    ... %%
    ... +FILE/DESCRIPTION
    ...  DESCRIPTION         Example attitude
    ...  TIME_SYSTEM         GPS
    ...  COORD_SYSTEM        IGS20
    ...  FRAME_TYPE          ECEF
    ...  LIST_OF_REC_TYPES   ATT
    ... -FILE/DESCRIPTION
    ... +EPHEMERIS/DATA
    ... *REC ID_              N ___q0_(scalar)_ ___q1__x____ ___q2__y____ ___q3__z____
    ... ## 2023 01 25 00 00  0.000000000000   1
    ...  ATT G01              4  0.0354798740  0.1940762631 -0.7303810882 -0.6539258740
    ... ## 2023 01 25 00 00 30.000000000000   1
    ...  ATT G01              4  0.0349994572  0.1941937124 -0.7315566977 -0.6526014389
    ... -EPHEMERIS/DATA
    ... %END_ORBEX
    ... '''
    >>> data = read_orbex(io.StringIO(text))
    >>> data
    <ORBEXData version='0.09' time_system='GPS' frame='IGS20 ECEF' 1 satellite, 2 records>
    >>> times, q = data.attitude["G01"]
    >>> times.utc.isot
    array(['2023-01-24T23:59:42.000', '2023-01-25T00:00:12.000'], dtype='<U23')
    >>> print(data.quaternion_convention)  # doctest: +ELLIPSIS
    rotation from the terrestrial frame (ECEF) to the satellite body frame, ...
    >>> q0, q1, q2, q3 = q[0]
    >>> z_body = [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), 1 - 2 * (q1**2 + q2**2)]
    >>> np.round(z_body, 4)  # the antenna axis points to the Earth's centre
    array([-0.202 ,  0.969 , -0.1422])
    """
    with open_lines(source) as (name, lines):
        return _read(name, lines)
