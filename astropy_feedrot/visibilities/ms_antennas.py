# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The antennas of a Measurement Set and the receptors of its ``FEED`` table.

* `ms_antennas` reads the ``ANTENNA`` table (``POSITION``, ``MOUNT`` through
  `astropy_feedrot.stations.labels`) and the receptors of the ``FEED`` table; an
  antenna that cannot be described (an orbiting one, an empty or unknown
  ``MOUNT``, receptors that are not a pair) is refused or kept as an
  `~astropy_feedrot.visibilities.UnusableAntenna`.
* `FeedReceptors` gives each visibility row the receptors of the ``FEED`` row
  of its antenna, feed, spectral window and time, as
  `~astropy_feedrot.visibilities.correct_ms` uses them.

python-casacore is imported on first use
(`~astropy_feedrot.visibilities.ms_chunks.tables`).
"""

import contextlib
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation

from ..antennas.receptors import Receptors
from ..engine.antenna import Antenna
from ..stations.labels import is_orbiting, mount_from_label
from .kinds import existing_path, file_kind
from .ms_chunks import tables as _tables
from .ms_tables import MSError
from .receptors import check_receptors, with_receptors
from .unusable import UnusableAntenna, check_unusable, orbiting_reason

__all__ = ["ms_antennas", "ms_telescopes", "describe_antenna", "FeedReceptors", "feed_rows",
           "ms_path", "subtable", "cell_text"]


def ms_path(ms):
    """The path of a Measurement Set, checked (MSError if it is not one)."""
    path = existing_path(ms, "Measurement Set")
    if not path.is_dir() or file_kind(path) != "ms":
        raise MSError(f"{str(path)!r} is not a Measurement Set (a directory with table.dat "
                      "and ANTENNA)")
    return path


def subtable(path, name):
    """A subtable of a Measurement Set, opened read-only (MSError if it has none)."""
    tables = _tables()
    if not (Path(path) / name).is_dir():
        raise MSError(f"{str(path)!r} has no {name} table")
    return tables.table(str(Path(path) / name), ack=False)


def cell_text(value):
    """A string cell as str."""
    return value.decode() if isinstance(value, bytes) else str(value)


def ms_telescopes(ms):
    """The telescope names of a Measurement Set's ``OBSERVATION`` rows, those that are not
    empty (none if it has no such table).

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities.ms_antennas import ms_telescopes
    >>> ms_telescopes(sample_file("vla_sim.ms"))
    ['VLA']
    """
    path = ms_path(ms)
    if not (path / "OBSERVATION").is_dir():
        return []
    with contextlib.closing(subtable(path, "OBSERVATION")) as table:
        if "TELESCOPE_NAME" not in table.colnames() or not table.nrows():
            return []
        names = [cell_text(n).strip() for n in table.getcol("TELESCOPE_NAME")]
    return list(dict.fromkeys(n for n in names if n))


def _positions(path):
    with contextlib.closing(subtable(path, "ANTENNA")) as table:
        xyz = np.asarray(table.getcol("POSITION"), dtype=float).reshape(-1, 3)
        reference = str(table.getcolkeywords("POSITION").get("MEASINFO", {}).get("Ref", "ITRF"))
        names = [cell_text(n) for n in table.getcol("NAME")]
        mounts = [cell_text(m).strip() for m in table.getcol("MOUNT")]
        flagged = np.asarray(table.getcol("FLAG_ROW"), bool) if "FLAG_ROW" in \
            table.colnames() else np.zeros(len(names), bool)
    if reference.upper() != "ITRF":
        raise MSError(f"{str(path)!r}, table ANTENNA: POSITION is in {reference}, not ITRF; "
                      "convert the positions to ITRF first")
    # Rows that hold no antenna (flagged, or at the geocentre as importuvfits
    # writes the numbers a UVFITS file skips) are left out.
    empty = flagged | np.all(xyz == 0, axis=1)
    return xyz, names, mounts, empty


def feed_rows(path):
    """FEED rows: antenna, feed, spw, start, stop (MJD s), types, angles (deg)."""
    with contextlib.closing(subtable(path, "FEED")) as table:
        n = table.nrows()
        rows = []
        for k in range(n):
            types = "".join(cell_text(t).strip().upper()
                            for t in table.getcell("POLARIZATION_TYPE", k))
            angles = np.degrees(np.asarray(table.getcell("RECEPTOR_ANGLE", k), float).ravel())
            mid, interval = float(table.getcell("TIME", k)), float(table.getcell("INTERVAL", k))
            half = np.inf if interval <= 0 else interval / 2
            rows.append((int(table.getcell("ANTENNA_ID", k)), int(table.getcell("FEED_ID", k)),
                         int(table.getcell("SPECTRAL_WINDOW_ID", k)), mid - half, mid + half,
                         types, tuple(np.round(angles[:len(types)], 9))))
    return rows


def _receptors(types, angles, where):
    try:
        if len(types.replace("?", "")) == 1 and types[0] != "?":
            # One receptor named ('L' and '?' of a single-polarization FITS-IDI
            # file imported by CASA): the pair, completed from it.
            return Receptors.paired(types[0], angles[0] * u.deg)
        return Receptors(types, list(angles) * u.deg)
    except ValueError as error:
        raise MSError(f"{where}: {error}") from None


def describe_antenna(location, name, label, receptor_sets, *, vertical="geodetic", keep=False,
                     where="the antenna"):
    """One antenna of a Measurement Set (v2 or v4) as its ``MOUNT`` and receptors give it.

    Parameters
    ----------
    location : `~astropy.coordinates.EarthLocation`
        Its position.
    name : str
        Its name.
    label : str
        Its ``MOUNT`` (casacore's labels, `~astropy_feedrot.stations.labels`).
    receptor_sets : set of tuple
        The ``(types, angles in deg)`` its feed rows give: one set gives its
        receptors, none or several leave them to each row.
    vertical : {'geodetic', 'geocentric'}, optional
        As `~astropy_feedrot.Antenna`.
    keep : bool, optional
        An antenna that cannot be described becomes an
        `~astropy_feedrot.visibilities.UnusableAntenna` (else MSError).
    where : str, optional
        The antenna, for the messages.

    Returns
    -------
    `~astropy_feedrot.Antenna` or `~astropy_feedrot.visibilities.UnusableAntenna`

    Examples
    --------
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.visibilities.ms_antennas import describe_antenna
    >>> site = get_antenna("VLA_W9").location
    >>> describe_antenna(site, "W9", "ALT-AZ", {("RL", (0.0, 0.0))}).receptors
    Receptors('RL', [0.0, 0.0] * u.deg)
    >>> describe_antenna(site, "W9", "", set(), keep=True).problem
    'mount'
    """
    label = str(label).strip()
    problem = mount = focus = None
    if not label:
        problem, reason = "mount", (
            "MOUNT is empty (casacore takes it for alt-az, but the writer did not say "
            "how the antenna is mounted): write its mount into the ANTENNA table, or "
            "pass mounts='catalogue' (--mounts catalogue) to take the station "
            "catalogue's")
    else:
        try:
            mount, focus = mount_from_label(label, "casacore")
        except ValueError as error:
            problem, reason = "mount", f"MOUNT {label!r}: {error}"
            if keep and is_orbiting(label, "casacore"):
                problem, reason = "orbiting", orbiting_reason(f"MOUNT {label!r}")
    receptors = receptors_problem = None
    if len(receptor_sets) == 1:
        try:
            receptors = _receptors(*next(iter(receptor_sets)), "table FEED")
        except MSError as error:
            receptors_problem = (f"{error}; give its receptors (feeds=, --feeds X,Y)")
    if not keep and (problem is not None or receptors_problem is not None):
        raise MSError(f"{where}: {reason if problem is not None else receptors_problem}")
    if problem is not None:
        return UnusableAntenna(location, name, problem, reason, label=label, vertical=vertical,
                               receptors=receptors, receptors_problem=receptors_problem)
    if receptors_problem is not None:
        return UnusableAntenna(location, name, "receptors", receptors_problem, label=label,
                               mount=mount, focus=focus, vertical=vertical)
    try:
        return Antenna(location, mount, focus, name=name, vertical=vertical,
                       receptors=receptors)
    except ValueError as error:
        raise MSError(f"{where}: {error}") from None


def ms_antennas(ms, *, vertical="geodetic", unusable="raise"):
    """The antennas of a Measurement Set, with their receptors.

    Parameters
    ----------
    ms : str or path-like
        The Measurement Set.
    vertical : {'geodetic', 'geocentric'}, optional
        The local vertical of each `~astropy_feedrot.Antenna`
        (``'geocentric'`` reproduces CASA).
    unusable : {'raise', 'keep'}, optional
        What to do with an antenna that cannot be described (an orbiting
        antenna, a ``MOUNT`` that is empty or has no model, receptors that
        cannot be used such as linear ones both at ``RECEPTOR_ANGLE`` 0):
        raise (default), or keep it as an
        `~astropy_feedrot.visibilities.UnusableAntenna` with the reason.

    Returns
    -------
    dict
        ``{ANTENNA row: Antenna}``: ``NAME``, ``POSITION`` (ITRF) and
        ``MOUNT`` (casacore's labels, `~astropy_feedrot.stations.labels`) of every
        row but those flagged or at the geocentre (placeholders); the
        receptors of the antenna's ``FEED`` rows when they all agree (None
        when it has none, or several sets: `correct_ms` then takes each
        row's own).

    Raises
    ------
    ImportError
        Without python-casacore.
    FileNotFoundError, MSError
        For a missing path or one that is not a Measurement Set, positions
        not in ITRF; with ``unusable='raise'``, an empty or unknown mount
        (casacore reads an empty ``MOUNT`` as alt-az; here it is refused,
        naming the antenna), an orbiting antenna, receptors that cannot be
        used.

    Examples
    --------
    >>> import tarfile, tempfile, pathlib
    >>> from astropy_feedrot.visibilities import ms_antennas
    >>> where = pathlib.Path(tempfile.mkdtemp())
    >>> with tarfile.open("tests/data/uvdata/X5707_1spw_1scan_10chan_1time_1bl_noatm"
    ...                   ".ms.tar.gz") as archive:
    ...     archive.extractall(where, filter="data")
    >>> antennas = ms_antennas(where / "X5707_1spw_1scan_10chan_1time_1bl_noatm.ms")
    >>> antennas[0].name, antennas[0].receptors
    ('DA41', Receptors('XY', [-10.0, 80.0] * u.deg))
    """
    path = ms_path(ms)
    xyz, names, mounts, empty = _positions(path)
    sets = {}
    for antenna, _, _, _, _, types, angles in feed_rows(path):
        sets.setdefault(antenna, set()).add((types, angles))
    keep = check_unusable(unusable) == "keep"
    antennas = {}
    for number, (position, name, label) in enumerate(zip(xyz, names, mounts)):
        if empty[number]:
            continue
        antennas[number] = describe_antenna(
            EarthLocation.from_geocentric(*position, unit=u.m), name, label,
            sets.get(number, set()), vertical=vertical, keep=keep,
            where=f"{str(path)!r}, table ANTENNA, antenna {number} ({name})")
    return antennas


class FeedReceptors:
    """The receptors of each row: virtual antennas, one per (antenna, receptor set)."""

    def __init__(self, path, antennas, feeds):
        self.path = path
        self.antennas = antennas
        self.rows = feed_rows(path)
        given = with_receptors(antennas, feeds, replace=True) if feeds is not None \
            else antennas
        self.virtual, self.key, self.number = {}, {}, {}
        self.by_antenna = {}
        for index, (antenna, _, _, _, _, types, angles) in enumerate(self.rows):
            if antenna not in antennas:
                continue
            self.by_antenna.setdefault(antenna, []).append(index)
        self.fallback = {}
        for number, antenna in given.items():
            if number not in self.by_antenna or feeds is not None:
                self.fallback[number] = self._virtual(number, antenna, antenna.receptors)

    def _virtual(self, number, antenna, receptors):
        described = None
        if receptors is not None:
            described = (receptors.types, tuple(receptors.angles.value))
        key = (number, described)
        if key not in self.key:
            k = len(self.key)
            self.key[key] = k
            self.number[k] = number
            self.virtual[k] = Antenna(antenna.location, antenna.mount, antenna.focus,
                                      name=antenna.name, vertical=antenna.vertical,
                                      receptors=receptors)
        return self.key[key]

    def _candidates(self, number, spw):
        """The FEED rows of antenna ``number`` that hold for spectral window ``spw``."""
        return [i for i in self.by_antenna.get(number, []) if self.rows[i][2] in (-1, spw)]

    def check(self, keys, products, dd):
        """MSError unless the receptors of the virtual antennas ``keys`` give ``products``."""
        for key in np.unique(keys).tolist():
            antenna = self.virtual[key]
            label = f"antenna {self.number[key]} ({antenna.name})"
            try:
                check_receptors(antenna.receptors, products, label, str(self.path),
                                "it has no FEED rows; add them to FEED, or give them "
                                "(feeds=, --feeds R,L)")
            except ValueError as error:
                raise MSError(f"{error} (data description {dd})") from None

    def keys(self, antennas, numbers, feed, spw, mjd_s):
        """The virtual antenna of each row (antenna ``numbers``, ``feed`` ids, times)."""
        distinct = np.unique(numbers).tolist()
        for number in distinct:
            if number not in antennas:
                raise MSError(f"{str(self.path)!r}: rows use antenna {number}, which the "
                              "ANTENNA table lacks (or holds as a flagged placeholder)")
        # Most antennas have one receptor set for the window, whatever the time: their
        # rows take it at once (a lookup by antenna number); the others are resolved
        # row by row below.
        size = max(distinct, default=-1) + 1
        lookup, feed_of = np.full(size, -1), np.full(size, -1)
        for number in distinct:
            if number in self.fallback:
                lookup[number] = self.fallback[number]
                continue
            candidates = self._candidates(number, spw)
            if len(candidates) == 1:
                _, feed_id, _, _, _, types, angles = self.rows[candidates[0]]
                where = f"{str(self.path)!r}, table FEED, row {candidates[0]}"
                lookup[number] = self._virtual(number, antennas[number],
                                               _receptors(types, angles, where))
                feed_of[number] = feed_id
        out = lookup[numbers]
        wanted = feed_of[numbers]
        out[(wanted >= 0) & (feed != wanted)] = -1
        for number in np.unique(numbers[out < 0]).tolist():
            rows = np.flatnonzero(numbers == number)
            candidates = self._candidates(number, spw)
            if not candidates:
                raise MSError(f"{str(self.path)!r}: antenna {number} "
                              f"({antennas[number].name}) has no FEED row for spectral "
                              f"window {spw}; its receptors are unknown: add them to FEED, or "
                              "give them (feeds=, --feeds R,L)")
            # The FEED row whose time range holds the row's time (else the nearest),
            # among those of the row's feed id.
            distance = np.full((len(candidates), rows.size), np.inf)
            for c, i in enumerate(candidates):
                _, feed_id, _, start, stop, _, _ = self.rows[i]
                t = mjd_s[rows]
                d = np.maximum(0.0, np.maximum(start - t, t - stop))
                distance[c] = np.where(feed[rows] == feed_id, d, np.inf)
            best = np.argmin(distance, axis=0)
            if np.isinf(distance[best, np.arange(rows.size)]).any():
                raise MSError(f"{str(self.path)!r}: antenna {number} has no FEED row for the "
                              f"FEED1/FEED2 ids {sorted(set(feed[rows].tolist()))}")
            for c, i in enumerate(candidates):
                _, _, _, _, _, types, angles = self.rows[i]
                where = f"{str(self.path)!r}, table FEED, row {i}"
                key = self._virtual(number, antennas[number], _receptors(types, angles, where))
                out[rows[best == c]] = key
        return out
