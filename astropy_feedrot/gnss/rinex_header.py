# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The header of a RINEX observation file, and the layout of its records.

`RinexHeader` holds what `~astropy_feedrot.gnss.rinex.RinexReader` reads of
a header (version, system, position, zero direction, observation types,
interval, time system) and says where a satellite's carrier phases lie in
its records; the constants give the layout of the records (RINEX 2.11, 3.05,
4.01: see `astropy_feedrot.gnss.rinex`). The reader, which fills it, is in
`~astropy_feedrot.gnss.rinex`; this module reads nothing.
"""

import dataclasses

import numpy as np

__all__ = ["SYSTEMS", "DEFAULT_TIME_SYSTEM", "VERSIONS", "FIELD", "VALUE_WIDTH", "PER_LINE_2",
           "RinexHeader"]

#: The satellite systems of RINEX: code -> name.
SYSTEMS = {"G": "GPS", "R": "GLONASS", "E": "Galileo", "C": "BeiDou", "J": "QZSS",
           "I": "NavIC", "S": "SBAS"}

#: The time system of a file whose ``TIME OF FIRST OBS`` leaves it blank, by the
#: satellite system of the first line (RINEX 3.05, section 6.2).
DEFAULT_TIME_SYSTEM = {"G": "GPS", "M": "GPS", " ": "GPS", "R": "GLO", "E": "GAL",
                       "C": "BDT", "J": "QZS", "I": "IRN", "S": "GPS"}

#: The versions read: 2.10-2.11, 3.00-3.05, 4.00-4.02.
VERSIONS = ("2.10", "2.11", "2.12", "3.00", "3.01", "3.02", "3.03", "3.04", "3.05",
            "4.00", "4.01", "4.02")

#: Width of one observation field: F14.3, LLI, SSI.
FIELD = 16
#: Width of its value (F14.3).
VALUE_WIDTH = 14

#: Observations per line of a RINEX 2 satellite record.
PER_LINE_2 = 5


@dataclasses.dataclass(frozen=True, eq=False)
class RinexHeader:
    """The header of a RINEX observation file, as read by `RinexReader`.

    Attributes
    ----------
    name : str
        The file's name (``'<stream>'`` for an unnamed stream).
    version : str
        As written in columns 1-9 of the first line, e.g. ``'3.04'``.
    major : int
        2, 3 or 4.
    system : str
        Satellite system of the file (column 41): ``'G'``, ``'R'``, ``'E'``,
        ``'C'``, ``'J'``, ``'I'``, ``'S'`` or ``'M'`` (mixed).
    lines : tuple of str
        Every line of the header with its line end, ``END OF HEADER`` last.
    position : ndarray, shape (3,), or None
        ``APPROX POSITION XYZ`` in metres (ITRS); None if absent or zero.
    zero_direction : float
        ``ANTENNA: ZERODIR AZI``: azimuth of the antenna's zero direction
        in degrees from north through east; 0 if the header does not give it.
    obs_types : dict of str to tuple of str
        Observation types per satellite system (RINEX 2: the same tuple, e.g.
        ``('C1', 'L1', 'L2')``, under every system code; RINEX 3 and 4: e.g.
        ``{'G': ('C1C', 'L1C', ...), 'E': (...)}``).
    interval : float or None
        ``INTERVAL`` in seconds, None if absent.
    time_system : str
        The time system of the epochs (a key of
        `~astropy_feedrot.io.TIME_SYSTEMS`): ``TIME OF FIRST OBS`` columns
        49-51, or the system's own when blank.
    first_obs, last_obs : tuple or None
        ``TIME OF FIRST OBS`` and ``TIME OF LAST OBS`` as ``(year, month,
        day, hour, minute, second)``; None if absent.

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.gnss import RinexReader
    >>> text = '''     3.04           OBSERVATION DATA    M                   RINEX VERSION / TYPE
    ...   1130730.1790 -4831245.9540  3994228.2410                  APPROX POSITION XYZ
    ...         90.0000                                             ANTENNA: ZERODIR AZI
    ... G    2 C1C L1C                                              SYS / # / OBS TYPES
    ...   2023    01    25    00    00    0.0000000     GPS         TIME OF FIRST OBS
    ...                                                             END OF HEADER
    ... '''
    >>> with RinexReader(io.StringIO(text)) as reader:
    ...     header = reader.header
    >>> header.version, header.obs_types, header.zero_direction, header.time_system
    ('3.04', {'G': ('C1C', 'L1C')}, 90.0, 'GPS')
    """

    name: str
    version: str
    major: int
    system: str
    lines: tuple
    position: np.ndarray = None
    zero_direction: float = 0.0
    obs_types: dict = dataclasses.field(default_factory=dict)
    interval: float = None
    time_system: str = "GPS"
    first_obs: tuple = None
    last_obs: tuple = None

    def phase_fields(self, system):
        """Where the carrier phases (``L`` types) of a system's satellites are.

        Parameters
        ----------
        system : str
            A satellite system code, e.g. ``'G'``.

        Returns
        -------
        list of (int, int, str)
            For each ``L`` observation type of the system: the line of the
            satellite's record it is on (0 for the first), the column where
            its 14-character value starts (0-based) and the type.

        Raises
        ------
        KeyError
            If the header declares no observation types for ``system``.

        Examples
        --------
        >>> from astropy_feedrot.gnss import RinexHeader
        >>> header = RinexHeader("x", "3.04", 3, "G", (), obs_types={"G": ("C1C", "L1C")})
        >>> header.phase_fields("G")
        [(0, 19, 'L1C')]
        """
        types = self.obs_types[system]
        if self.major == 2:
            return [(k // PER_LINE_2, FIELD * (k % PER_LINE_2), code)
                    for k, code in enumerate(types) if code.startswith("L")]
        return [(0, 3 + FIELD * k, code) for k, code in enumerate(types) if code.startswith("L")]

    def record_lines(self, system):
        """Number of lines of one satellite's observations (1 in RINEX 3 and 4).

        Examples
        --------
        >>> from astropy_feedrot.gnss import RinexHeader
        >>> header = RinexHeader("x", "2.11", 2, "G", (), obs_types={"G": ("C1", "L1") * 4})
        >>> header.record_lines("G")
        2
        """
        if self.major > 2:
            return 1
        return max(1, -(-len(self.obs_types[system]) // PER_LINE_2))

    @property
    def line_end(self):
        """The line end of the header's first line (``'\\n'`` or ``'\\r\\n'``)."""
        first = self.lines[0] if self.lines else "\n"
        return "\r\n" if first.endswith("\r\n") else "\n"
