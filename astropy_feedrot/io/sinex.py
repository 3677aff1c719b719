# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reader of the IGS satellite metadata SINEX file.

The file is described in P. Steigenberger and O. Montenbruck, "IGS Satellite
Metadata File Description", version 1.10 (2024), doi:10.57677/metadata-sinex.
The reader relies on its blocks (``+NAME`` ... ``-NAME``, comment lines
starting with ``*``):

* ``SATELLITE/IDENTIFIER``: SVN (columns 2-5), COSPAR ID, catalogue number,
  block (columns 24-38), comment;
* ``SATELLITE/PRN``: SVN, valid from and to (``YYYY:DDD:SSSSS``, columns
  7-20 and 22-35; ``0000:000:00000`` open), PRN (columns 37-39);
* ``SATELLITE/YAW_BIAS_RATE`` where present (files of some analysis
  software, not the IGS file): SVN, validity, yaw bias code (``U``, ``P``,
  ``N``, ``Y``...) and maximum yaw rate in deg/s.

Other blocks are skipped. A copy of the IGS file is shipped
(`~astropy_feedrot.data`).
"""

import dataclasses

import numpy as np
from astropy.time import Time

from ._common import FileFormatError, open_lines

__all__ = ["SatelliteMetadata", "read_satellite_metadata"]

_OPEN = "0000:000:00000"


def _sinex_time(text, name, lineno, line):
    """``YYYY:DDD:SSSSS`` (or ``YY:DDD:SSSSS``) as a UTC-free day count: MJD float, None if open."""
    text = text.strip()
    if text in (_OPEN, "00:000:00000"):
        return None
    parts = text.split(":")
    try:
        year, day, seconds = int(parts[0]), int(parts[1]), int(parts[2])
    except (ValueError, IndexError):
        raise FileFormatError(name, lineno, "a time YYYY:DDD:SSSSS", line) from None
    if year < 100:
        year += 1900 if year > 50 else 2000
    if not (1 <= day <= 366 and 0 <= seconds <= 86400):
        raise FileFormatError(name, lineno, "a time YYYY:DDD:SSSSS (day 1-366, seconds "
                              "0-86400)", line)
    start = Time(f"{year}-01-01T00:00:00", scale="utc").mjd
    return start + day - 1 + seconds / 86400


@dataclasses.dataclass(frozen=True, eq=False, repr=False)
class SatelliteMetadata:
    """Contents of an IGS satellite metadata SINEX file (the blocks used here).

    Attributes
    ----------
    name : str
        The file's name.
    description : str
        ``DESCRIPTION`` of the ``FILE/REFERENCE`` block (the release).
    blocks : dict of str to str
        Satellite block of each SVN, e.g. ``{'G063': 'GPS-IIF'}``.
    prns : list of (str, float, float, str)
        ``(svn, start, end, prn)``: the SVN carried the PRN from ``start``
        to ``end`` (MJD; ``inf`` when still valid).
    yaw : list of (str, float, float, str, float)
        ``(svn, start, end, bias code, max yaw rate in deg/s)`` from a
        ``SATELLITE/YAW_BIAS_RATE`` block; empty if the file has none.

    Examples
    --------
    >>> from astropy_feedrot.io import read_satellite_metadata
    >>> from astropy_feedrot.data import sample_file
    >>> metadata = read_satellite_metadata(sample_file("igs_satellite_metadata.snx"))
    >>> metadata
    <SatelliteMetadata 'IGS satellite meta data of GNSS satellites, release 2404', 291 SVNs>
    """

    name: str
    description: str
    blocks: dict
    prns: list
    yaw: list = dataclasses.field(default_factory=list)

    def __repr__(self):
        return f"<SatelliteMetadata {self.description!r}, {len(self.blocks)} SVNs>"

    def svn(self, prn, obstime):
        """The SVN that carried a PRN at an epoch.

        Parameters
        ----------
        prn : str
            E.g. ``'G05'``.
        obstime : `~astropy.time.Time`
            A scalar epoch.

        Returns
        -------
        str

        Raises
        ------
        ValueError
            If no SVN carried the PRN then (naming the file).

        Examples
        --------
        >>> from astropy.time import Time
        >>> from astropy_feedrot.io import read_satellite_metadata
        >>> from astropy_feedrot.data import sample_file
        >>> metadata = read_satellite_metadata(sample_file("igs_satellite_metadata.snx"))
        >>> metadata.svn("G05", Time("2023-01-25"))
        'G050'
        """
        mjd = Time(obstime).utc.mjd
        for svn, start, end, carried in self.prns:
            if carried == prn and start <= mjd < end:
                return svn
        raise ValueError(f"{self.name}: no satellite carried PRN {prn!r} on "
                         f"{Time(obstime).utc.isot[:10]} (SATELLITE/PRN); check the PRN or "
                         "use a newer metadata file")

    def block(self, prn, obstime):
        """The block of the satellite that carried a PRN at an epoch (``'GPS-IIR-M'``...).

        Examples
        --------
        >>> from astropy.time import Time
        >>> from astropy_feedrot.io import read_satellite_metadata
        >>> from astropy_feedrot.data import sample_file
        >>> metadata = read_satellite_metadata(sample_file("igs_satellite_metadata.snx"))
        >>> metadata.block("G05", Time("2023-01-25")), metadata.block("E11", Time("2023-01-25"))
        ('GPS-IIR-M', 'GAL-1')
        """
        svn = self.svn(prn, obstime)
        if svn not in self.blocks:
            raise ValueError(f"{self.name}: SVN {svn} (PRN {prn}) has no block in "
                             "SATELLITE/IDENTIFIER")
        return self.blocks[svn]

    def yaw_rate(self, prn, obstime):
        """``(bias code, max yaw rate in deg/s)`` of a PRN's satellite, or None without the block.

        Examples
        --------
        >>> from astropy.time import Time
        >>> from astropy_feedrot.io import read_satellite_metadata
        >>> from astropy_feedrot.data import sample_file
        >>> metadata = read_satellite_metadata(sample_file("igs_satellite_metadata.snx"))
        >>> metadata.yaw_rate("G05", Time("2023-01-25")) is None  # not in the IGS file
        True
        """
        svn = self.svn(prn, obstime)
        mjd = Time(obstime).utc.mjd
        for number, start, end, bias, rate in self.yaw:
            if number == svn and start <= mjd < end:
                return bias, rate
        return None


def read_satellite_metadata(source):
    """Read an IGS satellite metadata SINEX file.

    Parameters
    ----------
    source : str, path-like or file object
        The file (``.gz`` is decompressed).

    Returns
    -------
    `SatelliteMetadata`

    Raises
    ------
    FileFormatError
        If the first line is not a SINEX header (``%=SNX``), a block is not
        closed, a line of a block read here is malformed, or the file has no
        ``SATELLITE/IDENTIFIER`` or ``SATELLITE/PRN`` block.

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.io import read_satellite_metadata
    >>> text = '''%=SNX 2.02 DLR 26:035:25117 DLR 78:053:00000 00:000:00000 P 00000 0
    ... +SATELLITE/IDENTIFIER
    ... *SVN_ COSPAR ID SatCat Block__________ Comment__________________________________
    ...  G063 2011-036A  37753 GPS-IIF         Launched 2011-07-16; NAVSTAR 66
    ... -SATELLITE/IDENTIFIER
    ... +SATELLITE/PRN
    ...  G063 2011:197:00000 0000:000:00000 G01
    ... -SATELLITE/PRN
    ... %ENDSNX
    ... '''
    >>> read_satellite_metadata(io.StringIO(text)).blocks
    {'G063': 'GPS-IIF'}
    """
    with open_lines(source) as (name, lines):
        blocks, prns, yaw = {}, [], []
        description = ""
        block = None
        lineno = 0
        for lineno, line in enumerate(lines, start=1):
            if lineno == 1:
                if not line.startswith("%=SNX"):
                    raise FileFormatError(name, 1, "a SINEX header line '%=SNX ...'", line)
                continue
            if not line or line.startswith("*"):
                continue
            if line.startswith("+"):
                if block is not None:
                    raise FileFormatError(name, lineno, f"'-{block}' before a new block", line)
                block = line[1:].strip()
                continue
            if line.startswith("-"):
                if line[1:].strip() != block:
                    raise FileFormatError(name, lineno, f"'-{block}'", line)
                block = None
                continue
            if line.startswith("%ENDSNX"):
                break
            if block == "FILE/REFERENCE" and line[1:19].strip() == "DESCRIPTION":
                description = line[20:].strip()
            elif block == "SATELLITE/IDENTIFIER":
                svn = line[1:5]
                label = line[23:38].strip()
                if not svn.strip() or not label:
                    raise FileFormatError(name, lineno, "' SVN COSPAR SatCat Block' (SVN in "
                                          "columns 2-5, block in columns 24-38)", line)
                blocks[svn] = label
            elif block == "SATELLITE/PRN":
                start = _sinex_time(line[6:20], name, lineno, line)
                end = _sinex_time(line[21:35], name, lineno, line)
                prn = line[36:39].strip()
                if len(prn) != 3 or start is None:
                    raise FileFormatError(name, lineno, "' SVN start end PRN' (PRN in columns "
                                          "37-39)", line)
                prns.append((line[1:5], start, np.inf if end is None else end, prn))
            elif block == "SATELLITE/YAW_BIAS_RATE":
                start = _sinex_time(line[6:20], name, lineno, line)
                end = _sinex_time(line[21:35], name, lineno, line)
                fields = line[35:].split()
                try:
                    bias, rate = fields[0], float(fields[1])
                except (IndexError, ValueError):
                    raise FileFormatError(name, lineno, "' SVN start end bias rate'",
                                          line) from None
                yaw.append((line[1:5], start or -np.inf, np.inf if end is None else end,
                            bias, rate))
        if block is not None:
            raise FileFormatError(name, lineno + 1, f"'-{block}' (the file is cut short)", None)
        for needed, found in (("SATELLITE/IDENTIFIER", blocks), ("SATELLITE/PRN", prns)):
            if not found:
                raise FileFormatError(name, lineno + 1, f"a {needed} block", None)
    return SatelliteMetadata(name, description, blocks, prns, yaw)
