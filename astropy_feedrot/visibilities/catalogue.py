# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Receptors from the station catalogue, for antennas a file gives none.

An antenna of a visibility file is matched to a station of the catalogue
(:doc:`/stations`) in two ways, the second only where the first finds no
station:

* by name: the station of the antenna's name (or alias) within
  `CATALOGUE_TOLERANCE` of the antenna (the VLBA's ``FD``, ``PT``);
* by position: the one station with receptors within `PAD_TOLERANCE` of
  the antenna, whatever the antenna's name. Connected arrays name their
  antennas for themselves or for their pads in their own way (the VLA's
  ``W09``, ``E18``, ``N72``; the catalogue's ``VLA_W9``...), or not at all
  (pyuvdata names the antennas of a Miriad file by their numbers);
* by the file's telescope: where neither finds a station, the receptors
  that every station of the telescope's network (or of the telescope's
  name) states, all alike, for an antenna within `ARRAY_TOLERANCE` of one
  of them. Miriad records the ATCA's antennas at positions that are not
  their pads' (antenna 1 at the array's reference pad, heights at sea
  level: :doc:`/correcting`), but every ATCA pad states the same feeds.

`catalogue_receptors` gives each antenna the receptors of its station and
says which antennas it matched, how, and why not the others.

`catalogue_mounts` compares each antenna's mount and focus with those of the
catalogue's station within `CATALOGUE_TOLERANCE` of it (the station of its
name, else the nearest), warns once where they differ, and with
``mounts='catalogue'`` takes the catalogue's: many writers put a placeholder
in the mount code (HOPS and pyuvdata before 3.2 write ``MNTSTA`` 0 for
every antenna, Nasmyth ones included).
"""

import functools
from typing import NamedTuple

import numpy as np
from astropy import units as u

from ..antennas.focus import CassegrainFocus
from ..core.choices import MOUNTS
from ..core.exceptions import CatalogueMountWarning, CatalogueReceptorsWarning, warn_caller
from ..engine.antenna import Antenna
from ..stations.catalogue import StationCatalogue, default_catalogue, read_catalogue
from ..stations.labels import mount_from_label
from .receptors import with_receptors
from .unusable import UnusableAntenna

__all__ = ["catalogue_receptors", "catalogue_mounts", "catalogue_stations", "StationMatch",
           "MOUNTS", "CATALOGUE_TOLERANCE", "PAD_TOLERANCE", "ARRAY_TOLERANCE"]

#: Largest distance between an antenna of a file and the catalogue's station of
#: its name for the station to lend the antenna its receptors
#: (`catalogue_receptors`): the station itself, not a neighbour (pads of an
#: array lie tens of metres apart, the telescopes of an observatory hundreds;
#: a file and the catalogue agree on a station to well under a metre).
CATALOGUE_TOLERANCE = 100 * u.m

#: Largest distance between an antenna that no station's name matches and
#: the station with receptors that lends it them by position
#: (`catalogue_receptors`). A third of the closest spacing of two catalogue
#: stations with receptors (the ATCA's pads, 15.3 m apart; the VLA's at least
#: 39.9 m), so that one antenna never lies this close to two pads; ten times
#: the distance of the VLA Measurement Set's antennas from the catalogue's
#: pads (0.42 to 0.45 m) and beyond the 3.4 m by which SCHED's ATCA pads,
#: reckoned from W104, depart over 6 km from the layout a Miriad file of the
#: ATCA records (:doc:`/correcting`).
PAD_TOLERANCE = 5 * u.m

#: Largest distance between an antenna matched by the file's telescope and the
#: nearest station of that telescope (`catalogue_receptors`): the antenna
#: belongs to that observatory (the VLA's arms reach 21 km from its centre),
#: not to another that a mislabelled file would name.
ARRAY_TOLERANCE = 50 * u.km


def _as_catalogue(catalogue):
    if catalogue is None:
        return default_catalogue()
    return catalogue if isinstance(catalogue, StationCatalogue) else read_catalogue(catalogue)


def _xyz(location):
    """Geocentric metres of an EarthLocation, shape (3,)."""
    return np.array([getattr(location, c).to_value(u.m) for c in "xyz"])


def _text(receptors):
    """Receptors as ``--feeds`` writes them: ``'R:0,L:0'``."""
    return ",".join(f"{t}:{a:g}" for t, a in zip(receptors.types, receptors.angles.value))


def _station_of(antenna, catalogue, tolerance):
    """The catalogue's station of an antenna's name, and None; or None and why not."""
    if not antenna.name:
        return None, "it has no name"
    stations = catalogue.stations_named(antenna.name)
    if not stations:
        return None, "its name is not in the catalogue"
    xyz = _xyz(antenna.location)
    distance = {station: float(np.linalg.norm(xyz - _xyz(catalogue.location(station))))
                for station in stations}
    near = [station for station in stations if distance[station] <= tolerance.to_value(u.m)]
    limit = f"{tolerance.to_value(u.m):g} m"
    if len(near) != 1:
        far = ", ".join(f"{station} {distance[station]:.1f} m away" for station in stations)
        return None, (f"the catalogue's {far}, beyond {limit}" if not near else
                      f"it names {', '.join(near)}, all within {limit}")
    return near[0], None


class _Stations:
    """The catalogue's stations that state receptors: names, positions and receptors."""

    def __init__(self, catalogue):
        self.names, xyz, self.receptors = [], [], []
        for name in catalogue.names:
            receptors, _ = catalogue.receptors(name)
            if receptors is not None:
                self.names.append(name)
                xyz.append(_xyz(catalogue.location(name)))
                self.receptors.append(receptors)
        self.xyz = np.reshape(xyz, (-1, 3))

    def near(self, antenna, tolerance):
        """The station with receptors near an antenna and its distance (m), or None and why."""
        limit = f"{tolerance.to_value(u.m):g} m"
        if not self.names:
            return None, "no station of the catalogue states receptors"
        distance = np.linalg.norm(self.xyz - _xyz(antenna.location), axis=-1)
        order = np.argsort(distance, kind="stable")
        near = [k for k in order if distance[k] <= tolerance.to_value(u.m)]
        if not near:
            k = order[0]
            return None, (f"no station within {limit} states receptors (nearest: "
                          f"{self.names[k]}, {distance[k]:.1f} m)")
        if len({_text(self.receptors[k]) for k in near}) > 1:
            return None, (f"stations with different receptors lie within {limit}: "
                          + ", ".join(f"{self.names[k]} ({_text(self.receptors[k])}, "
                                      f"{distance[k]:.1f} m)" for k in near))
        return near[0], float(distance[near[0]])


def _telescope_receptors(telescope, catalogue):
    """The receptors every station of a telescope states alike, its stations' positions
    and a label; or None, None and why not."""
    name = str(telescope).strip()
    try:
        names = catalogue.network_names(name)
        label = f"network {name}"
    except ValueError:
        names = catalogue.stations_named(name)
        label = f"station {', '.join(names)}"
    if not names:
        return None, None, f"the catalogue has no network or station {name!r}"
    stated, silent = {}, []
    for station in names:
        receptors, source = catalogue.receptors(station)
        if receptors is None:
            silent.append(station)
        else:
            stated.setdefault(_text(receptors), []).append((station, (receptors, source)))
    if silent:  # what some stations state says nothing of the others'
        return None, None, (f"{len(silent)} of the {len(names)} stations of the telescope "
                            f"{name!r} ({label}) state no receptors")
    if len(stated) != 1:
        return None, None, (f"the stations of the telescope {name!r} state different "
                            f"receptors ({', '.join(stated)})")
    stations = next(iter(stated.values()))
    xyz = np.array([_xyz(catalogue.location(station)) for station, _ in stations])
    return stations[0][1], xyz, label


def catalogue_receptors(antennas, catalogue=None, *, numbers=None,
                        tolerance=CATALOGUE_TOLERANCE, pad_tolerance=PAD_TOLERANCE,
                        telescope=None, array_tolerance=ARRAY_TOLERANCE):
    """The antennas, given the station catalogue's receptors where they have none.

    An antenna without receptors takes those the catalogue states for the
    station of its name (`~astropy_feedrot.stations.StationCatalogue.stations_named`;
    of the stations a shared name stands for, the one near the antenna) if
    the antenna lies within ``tolerance`` of it: a name alone could be
    another telescope's. Where its name gives no station (no name, a name
    the catalogue does not hold, stations of that name all farther than
    ``tolerance`` or several within it), the antenna takes the receptors of
    the station with receptors within ``pad_tolerance`` of it, the pad it
    stands on (the VLA's ``W09`` on ``VLA_W9``); if stations with
    different receptors lie that close, none. Where that finds none either,
    and the file names its ``telescope``, the antenna takes the receptors
    that every station of that network (or of that name) states alike, if
    it lies within ``array_tolerance`` of one of them.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna}``, as read from a file.
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, str, path-like or False, optional
        The catalogue (default: the embedded one; a path: an ECSV file to
        read); False for none (the antennas are returned as they are).
    numbers : iterable of int, optional
        Only these antennas (those the data use); default all.
    tolerance : `~astropy.units.Quantity`, optional
        Largest distance between an antenna and the station of its name
        (`CATALOGUE_TOLERANCE`).
    pad_tolerance : `~astropy.units.Quantity`, optional
        Largest distance between an antenna that no station's name matches
        and the station it takes its receptors from (`PAD_TOLERANCE`).
    telescope : str, optional
        The file's telescope (pyuvdata's ``telescope.name``, FITS-IDI's
        ``TELESCOP``), e.g. ``'ATCA'``.
    array_tolerance : `~astropy.units.Quantity`, optional
        Largest distance between an antenna matched by ``telescope`` and the
        nearest of that telescope's stations (`ARRAY_TOLERANCE`).

    Returns
    -------
    antennas : dict
        A new ``{antenna number: Antenna}``.
    note : str
        What the catalogue gave and to which antennas it gave nothing, and
        why, for the message of an antenna left without receptors; empty if
        no antenna lacked them or ``catalogue`` is False.

    Raises
    ------
    TypeError, ValueError, FileNotFoundError
        For a catalogue that cannot be read, as
        `~astropy_feedrot.stations.read_catalogue`.

    Warns
    -----
    CatalogueReceptorsWarning
        Once, if some antennas were given receptors: which, as which
        stations (``by position`` and the distance for those matched by
        position), and the source the catalogue cites.

    Examples
    --------
    The VLBA's Fort Davis antenna as a file without receptors gives it, and
    a VLA antenna named as the VLA names it, ``W09``, standing on the
    catalogue's pad ``VLA_W9``:

    >>> import warnings
    >>> from astropy_feedrot import Antenna, get_antenna
    >>> from astropy_feedrot.visibilities import catalogue_receptors
    >>> fd, w9 = get_antenna("FD-VLBA"), get_antenna("VLA_W9")
    >>> bare = {1: Antenna(fd.location, fd.mount, name="FD"),
    ...         2: Antenna(w9.location, w9.mount, name="W09")}
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     antennas, note = catalogue_receptors(bare)
    >>> antennas[1].receptors, antennas[2].receptors, note
    (Receptors('RL', [0.0, 0.0] * u.deg), Receptors('RL', [0.0, 0.0] * u.deg), '')
    >>> print(str(caught[0].message)[:75])
    receptors from the station catalogue for antennas the file gives none: 1 (F
    >>> "2 (W09 as VLA_W9 by position, 0.00 m)" in str(caught[0].message)
    True
    """
    if catalogue is False:
        return dict(antennas), ""
    wanted = None if numbers is None else {int(n) for n in numbers}
    lacking = [n for n, antenna in antennas.items() if isinstance(antenna, Antenna)
               and antenna.receptors is None and (wanted is None or int(n) in wanted)]
    if not lacking:
        return dict(antennas), ""
    catalogue = _as_catalogue(catalogue)
    given, refused, cited, stations, array = {}, {}, {}, None, None
    for number in lacking:
        antenna = antennas[number]
        name = str(antenna.name).strip() if antenna.name else "no name"
        station, why = _station_of(antenna, catalogue, tolerance)
        how = ""
        if station is None:
            stations = stations if stations is not None else _Stations(catalogue)
            k, found = stations.near(antenna, pad_tolerance)
            if k is None:
                why = f"{why}, and {found}"
            else:
                station, why, how = stations.names[k], None, f" by position, {found:.2f} m"
        if station is None and telescope:
            if array is None:
                array = _telescope_receptors(telescope, catalogue)
            stated, xyz, label = array
            if stated is None:
                why = f"{why}, and {label}"
            else:
                distance = float(np.min(np.linalg.norm(xyz - _xyz(antenna.location), axis=-1)))
                if distance > array_tolerance.to_value(u.m):
                    why = (f"{why}, and it lies {distance / 1e3:.1f} km from the nearest "
                           f"station of the telescope {telescope!r}, beyond "
                           f"{array_tolerance.to(u.km).value:g} km")
                else:
                    receptors, source = stated
                    given[number], why = receptors, None
                    cited.setdefault((_text(receptors), source), []).append(
                        f"{number} ({name} by the telescope {str(telescope).strip()}, "
                        f"{label}: every station states these)")
        if station is not None:
            receptors, source = catalogue.receptors(station)
            if receptors is None:
                why = f"the catalogue's {station} states no receptors"
            else:
                given[number] = receptors
                cited.setdefault((_text(receptors), source), []).append(
                    f"{number} ({name} as {station}{how})")
        if why is not None:
            refused[number] = f"{number} ({name}: {why})"
    if cited:
        warn_caller("receptors from the station catalogue for antennas the file gives none: "
                    + "; ".join(f"{', '.join(labels)}: {text} ({source})"
                                for (text, source), labels in cited.items())
                    + "; give feeds= (--feeds) to choose others", CatalogueReceptorsWarning)
    note = ""
    if refused:
        found = ", ".join(label for labels in cited.values() for label in labels)
        note = (f"the station catalogue gave receptors to antennas {found or 'none'}, "
                f"not to {'; '.join(refused[n] for n in sorted(refused)[:10])}"
                + (f" and {len(refused) - 10} more" if len(refused) > 10 else ""))
    return with_receptors(antennas, given), note


class StationMatch(NamedTuple):
    """The catalogue's station of an antenna of a file (`catalogue_stations`).

    Attributes
    ----------
    station : str
        The station's name in the catalogue.
    distance : float
        Its distance from the antenna, in m.
    mount, focus
        The catalogue's mount and focus of the station.
    agrees : bool
        Whether the file gives the antenna the same mount and an equivalent
        focus (prime, Cassegrain and Gregorian foci are alike); False where
        the file's mount has no model.

    Examples
    --------
    >>> from astropy_feedrot import AltAzMount, CassegrainFocus
    >>> from astropy_feedrot.visibilities import StationMatch
    >>> StationMatch("FD-VLBA", 0.0, AltAzMount(), CassegrainFocus(), True).station
    'FD-VLBA'
    """

    station: str
    distance: float
    mount: object
    focus: object
    agrees: bool


def _same_optics(mount, focus, other_mount, other_focus):
    """Whether two mounts and foci give the same feed rotation."""
    if mount is None or mount != other_mount:
        return False
    focus = CassegrainFocus() if focus is None else focus
    other_focus = CassegrainFocus() if other_focus is None else other_focus
    if focus.closed_form is not None and other_focus.closed_form is not None:
        return tuple(focus.closed_form) == tuple(other_focus.closed_form)
    return focus == other_focus


def _optics(mount, focus):
    """A mount and focus, for messages."""
    if mount is None:
        return "no model"
    return f"{mount!r} {CassegrainFocus() if focus is None else focus!r}"


def check_mounts_option(mounts):
    """``mounts`` checked: one of `MOUNTS`.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.catalogue import check_mounts_option
    >>> check_mounts_option("catalogue")
    'catalogue'
    """
    if mounts not in MOUNTS:
        raise ValueError(f"mounts must be one of {MOUNTS}, got {mounts!r}")
    return mounts


@functools.lru_cache(maxsize=8)
def _positions(catalogue):
    """The catalogue's stations' geocentric positions (m), (N, 3), in its order."""
    return np.array([_xyz(catalogue.location(name)) for name in catalogue.names])


def _closed_form_of(catalogue, station):
    """The focus a station's mount code names (the closed form of traced mirrors)."""
    row = catalogue.names.index(station)
    code = str(catalogue.table["mount"][row])
    return mount_from_label(code, "geodetic")[1]


def catalogue_stations(antennas, catalogue=None, *, tolerance=CATALOGUE_TOLERANCE,
                       pad_tolerance=PAD_TOLERANCE):
    """The catalogue's station of each antenna of a file, within ``tolerance``.

    An antenna's station is the station of its name (or alias) within
    ``tolerance`` of it; else the station nearest to it within ``tolerance``
    if no station with another mount or focus lies within ``tolerance`` too
    (an observatory with several telescopes), or if it lies within
    ``pad_tolerance`` (the antenna's own pad). Orbiting antennas have none
    (the position a file gives them is that of a tracking station, or
    nothing).

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna or UnusableAntenna}``.
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, str, path-like or False, optional
        The catalogue (default: the embedded one); False for none.
    tolerance : `~astropy.units.Quantity`, optional
        Largest distance between an antenna and its station
        (`CATALOGUE_TOLERANCE`).
    pad_tolerance : `~astropy.units.Quantity`, optional
        Distance within which the nearest station is the antenna's whatever
        other stations lie within ``tolerance`` (`PAD_TOLERANCE`).

    Returns
    -------
    dict
        ``{antenna number: StationMatch}`` for the antennas with a station.

    Examples
    --------
    The EHT's APEX as a file with ``MNTSTA`` 0 gives it (a plain alt-az
    mount), where the catalogue has a right-handed Nasmyth focus:

    >>> from astropy_feedrot import AltAzMount, Antenna, get_antenna
    >>> from astropy_feedrot.visibilities import catalogue_stations
    >>> ap = Antenna(get_antenna("APEX").location, AltAzMount(), name="AP")
    >>> match = catalogue_stations({2: ap})[2]
    >>> match.station, match.focus, match.agrees
    ('APEX', NasmythFocus(handedness='right'), False)
    """
    if catalogue is False:
        return {}
    catalogue = _as_catalogue(catalogue)
    xyz = _positions(catalogue)
    limit = tolerance.to_value(u.m)
    known = {}

    def station_antenna(name):
        if name not in known:
            known[name] = catalogue.get_antenna(name)
        return known[name]

    def optics(row):
        """A station's mount and focus, as comparable values."""
        antenna = station_antenna(catalogue.names[row])
        return (antenna.mount, antenna.focus)

    out = {}
    for number, antenna in antennas.items():
        if isinstance(antenna, UnusableAntenna) and antenna.problem == "orbiting":
            continue
        station, _ = _station_of(antenna, catalogue, tolerance)
        here = _xyz(antenna.location)
        if station is None:
            distance = np.linalg.norm(xyz - here, axis=-1)
            near = np.flatnonzero(distance <= limit)
            if not near.size:
                continue
            nearest = int(near[np.argmin(distance[near])])
            # By position alone, the station must be the only one that near, or all
            # those that near alike (the ATA's dishes lie within 100 m of both the ATA
            # and the old Hat Creek equatorial antenna), unless it is the antenna's pad.
            if distance[nearest] > pad_tolerance.to_value(u.m) and len(
                    {optics(int(k)) for k in near}) > 1:
                continue
            station = catalogue.names[nearest]
        found = station_antenna(station)
        distance = float(np.linalg.norm(_xyz(found.location) - here))
        focus = found.focus
        if focus.closed_form is None:
            # Mirrors traced one by one (YEBES40M, WARK30M): a file can only give the
            # closed form its mount code names (NASR, BWG), to which they reduce.
            focus = _closed_form_of(catalogue, station)
        out[number] = StationMatch(station, distance, found.mount, found.focus,
                                   _same_optics(antenna.mount, antenna.focus, found.mount,
                                                focus))
    return out


def catalogue_mounts(antennas, mounts="file", catalogue=None, *, numbers=None,
                     tolerance=CATALOGUE_TOLERANCE, where="the file"):
    """The antennas with the file's or the catalogue's mounts, and where they differ.

    Each antenna is compared with its station in the catalogue
    (`catalogue_stations`: the station of its name within ``tolerance``, else
    the nearest within ``tolerance``). Where the mounts or foci differ, one
    warning names every such antenna with both; ``mounts`` chooses which is
    used. An antenna whose mount label has no model (an empty or unknown
    ``MOUNT``, an unreadable ``MNTSTA`` code) takes its station's mount with
    ``mounts='catalogue'``; with ``'file'`` it stays unusable, its reason
    naming the station.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna or UnusableAntenna}``, as read from a file.
    mounts : {'file', 'catalogue'}, optional
        Whose mount and focus to use where they differ (`MOUNTS`).
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, str, path-like or False, optional
        The catalogue (default: the embedded one); False for none (the
        antennas are returned as they are).
    numbers : iterable of int, optional
        Only these antennas (those the data use); default all.
    tolerance : `~astropy.units.Quantity`, optional
        Largest distance between an antenna and its station.
    where : str, optional
        The file, for the messages.

    Returns
    -------
    antennas : dict
        A new ``{antenna number: Antenna or UnusableAntenna}``.
    matches : dict
        ``{antenna number: StationMatch}`` (`catalogue_stations`).

    Raises
    ------
    ValueError
        For a ``mounts`` not in `MOUNTS`.

    Warns
    -----
    CatalogueMountWarning
        Once, if the file's mount or focus of some antennas differs from
        their station's: which, both, and which was used.

    Examples
    --------
    >>> import warnings
    >>> from astropy_feedrot import AltAzMount, Antenna, get_antenna
    >>> from astropy_feedrot.visibilities import catalogue_mounts
    >>> ap = Antenna(get_antenna("APEX").location, AltAzMount(), name="AP")
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     antennas, matches = catalogue_mounts({2: ap}, "catalogue")
    >>> antennas[2].focus
    NasmythFocus(handedness='right')
    >>> print(caught[0].message)  # doctest: +ELLIPSIS
    the file: the station catalogue's mounts are used where they differ from the file's: ...
    """
    mounts = check_mounts_option(mounts)
    wanted = None if numbers is None else {int(n) for n in numbers}
    chosen = {n: a for n, a in antennas.items() if wanted is None or int(n) in wanted}
    matches = catalogue_stations(chosen, catalogue, tolerance=tolerance)
    out = dict(antennas)
    differ = []
    for number, match in matches.items():
        antenna = antennas[number]
        if match.agrees:
            continue
        station = f"the catalogue's {match.station}, {match.distance:.1f} m away"
        if isinstance(antenna, UnusableAntenna) and antenna.problem == "mount":
            if mounts == "catalogue":
                out[number] = antenna.with_mount(match.mount, match.focus)
                differ.append(f"{_name(number, antenna)}: file {antenna.reason}; "
                              f"{match.station} ({match.distance:.1f} m) "
                              f"{_optics(match.mount, match.focus)}")
            else:
                out[number] = UnusableAntenna(
                    antenna.location, antenna.name, "mount",
                    f"{antenna.reason}; {station}, has {_optics(match.mount, match.focus)}: "
                    "pass mounts='catalogue' (--mounts catalogue) to use it",
                    label=antenna.label, vertical=antenna.vertical, rotator=antenna.rotator,
                    receptors=antenna.receptors, receptors_problem=antenna.receptors_problem)
            continue
        if antenna.mount is None:
            continue
        differ.append(f"{_name(number, antenna)}: file {_optics(antenna.mount, antenna.focus)}"
                      f", {match.station} ({match.distance:.1f} m) "
                      f"{_optics(match.mount, match.focus)}")
        if mounts == "catalogue":
            out[number] = _with_optics(antenna, match.mount, match.focus)
    if differ:
        limit = f"{tolerance.to_value(u.m):g} m"
        if mounts == "catalogue":
            head = "the station catalogue's mounts are used where they differ from the file's"
            tail = "pass mounts='file' (--mounts file) to use the file's"
        else:
            head = (f"the file's mounts differ from those of the station catalogue's stations "
                    f"within {limit}")
            tail = ("the file's are used: pass mounts='catalogue' (--mounts catalogue) to use "
                    "the catalogue's")
        warn_caller(f"{where}: {head}: {'; '.join(differ)}; {tail}", CatalogueMountWarning)
    return out, matches


def _name(number, antenna):
    return f"antenna {number} ({antenna.name})" if antenna.name else f"antenna {number}"


def _with_optics(antenna, mount, focus):
    """``antenna`` (an Antenna, or an UnusableAntenna of problem 'receptors') with
    another mount and focus."""
    if isinstance(antenna, UnusableAntenna):
        return UnusableAntenna(antenna.location, antenna.name, antenna.problem,
                               antenna.reason, label=antenna.label, mount=mount, focus=focus,
                               vertical=antenna.vertical, rotator=antenna.rotator)
    return Antenna(antenna.location, mount, focus, name=antenna.name,
                   vertical=antenna.vertical, receptors=antenna.receptors,
                   rotator=antenna.rotator)
