# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""A catalogue of antennas: positions, mounts and focus types by name.

The embedded catalogue holds the antennas of the paper. Positions of DBR205
and FD-VLBA are its Table 1 and of GGAO12M and WETTZ13S its Table 3; those of
EFLSBERG, PARKES, WARK12M and YEBES40M are the GSFC VLBI global solution 2019d
(ITRF2014 frame, epoch 2020 Jan 1) and that of WARK30M a GSFC position from the
session AUA025, all as listed, with their velocities, in the station catalogue
``catalogs/locations.dat`` of the VLBI scheduling program SCHED (version
2025Jan31). Mounts are written as the geodetic station-catalogue codes (see
`astropy_feedrot.labels`), and YEBES40M and WARK30M carry the paper's mirror
trains (Appendix C).

A catalogue of one's own is an ECSV file with the same columns; only
``name``, ``x``, ``y``, ``z`` and ``mount`` are required.
"""

import difflib
import functools
import re

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.table import Table
from astropy.time import Time

from .antenna import Antenna
from .data import sample_file
from .focus import (
    BeamWaveguideFocus,
    CassegrainFocus,
    GregorianFocus,
    MirrorTrain,
    NasmythFocus,
    PrimeFocus,
)
from .labels import mount_from_label

__all__ = [
    "StationCatalogue",
    "default_catalogue",
    "read_catalogue",
    "get_antenna",
    "focus_from_name",
    "FOCUS_NAMES",
]

#: Columns every catalogue must have.
REQUIRED_COLUMNS = ("name", "x", "y", "z", "mount")

#: Values of the ``focus`` column and the focus each stands for.
FOCUS_NAMES = {
    "": None,
    "prime": PrimeFocus,
    "cassegrain": CassegrainFocus,
    "gregorian": GregorianFocus,
    "nasmyth-right": functools.partial(NasmythFocus, "right"),
    "nasmyth-left": functools.partial(NasmythFocus, "left"),
    "bwg-right": functools.partial(BeamWaveguideFocus, "right"),
    "bwg-left": functools.partial(BeamWaveguideFocus, "left"),
    "yebes40m-S": functools.partial(MirrorTrain.yebes40m, "S"),
    "yebes40m-C": functools.partial(MirrorTrain.yebes40m, "C"),
    "yebes40m-X": functools.partial(MirrorTrain.yebes40m, "X"),
    "wark30m": MirrorTrain.wark30m,
}

# A geocentric distance outside this range is not a position on the Earth's
# surface in metres (the lowest and highest points are about 6352 and
# 6384 km from the geocentre).
_RADIUS_RANGE = (6.30e6, 6.45e6)


def _key(name):
    """Case-, space- and punctuation-insensitive form of a station name."""
    return re.sub(r"[^0-9A-Z]", "", str(name).upper())


def focus_from_name(value, where="focus"):
    """The focus named by a value of the catalogue's ``focus`` column.

    Parameters
    ----------
    value : str or None
        One of `FOCUS_NAMES` (case-insensitive); empty or None for none.
    where : str, optional
        What to name in an error message.

    Returns
    -------
    `~astropy_feedrot.focus.Focus` or None

    Raises
    ------
    ValueError
        For an unknown name (listing the known ones).

    Examples
    --------
    >>> from astropy_feedrot.stations import focus_from_name
    >>> focus_from_name("nasmyth-right")
    NasmythFocus(handedness='right')
    """
    value = "" if value is None or np.ma.is_masked(value) else str(value).strip()
    for known, make in FOCUS_NAMES.items():
        if value.lower() == known.lower():
            return None if make is None else make()
    choices = ", ".join(k for k in FOCUS_NAMES if k)
    raise ValueError(f"{where}: unknown focus {value!r}; expected one of {choices}, or empty")


class StationCatalogue:
    """A table of antennas by name, as read from an ECSV file.

    Parameters
    ----------
    table : `~astropy.table.Table`
        Columns ``name`` (str), ``x``, ``y``, ``z`` (ITRF geocentric
        coordinates, with a length unit) and ``mount`` (a geodetic
        station-catalogue code: ``AZEL``, ``EQUA``, ``X-YN``, ``X-YE``,
        ``NASR``, ``NASL``, ``BWG``, ``GNSS``). Optional: ``aliases``
        (comma-separated other names), ``focus`` (one of `FOCUS_NAMES`;
        empty for the mount's default), ``vx``, ``vy``, ``vz`` (velocity unit) with
        ``epoch`` (MJD of the position) and ``source`` (a citation).
    origin : str, optional
        Where the table came from, for error messages.

    Raises
    ------
    ValueError
        For a missing column, an unknown mount code or focus, a duplicated
        name, or a position that is not on the Earth's surface (e.g. in km).
    astropy.units.UnitsError
        For coordinates or velocities without compatible units.

    Examples
    --------
    >>> from astropy_feedrot.stations import default_catalogue
    >>> catalogue = default_catalogue()
    >>> "YEBES40M" in catalogue
    True
    >>> catalogue.get_antenna("Effelsberg")  # doctest: +ELLIPSIS
    <Antenna 'EFLSBERG', (4033947.152, ...) m, AltAzMount(), GregorianFocus()>
    """

    def __init__(self, table, origin=None):
        self._origin = origin or "station catalogue"
        missing = [c for c in REQUIRED_COLUMNS if c not in table.colnames]
        if missing:
            raise ValueError(f"{self._origin}: missing column(s) {', '.join(missing)}; a "
                             f"catalogue needs {', '.join(REQUIRED_COLUMNS)}")
        table = Table(table, copy=True)
        self._xyz = self._quantity(table, ("x", "y", "z"), u.m)
        if all(c in table.colnames for c in ("vx", "vy", "vz")):
            self._velocity = self._quantity(table, ("vx", "vy", "vz"), u.m / u.yr)
        else:
            self._velocity = np.zeros((len(table), 3)) * u.m / u.yr
        epoch = table["epoch"] if "epoch" in table.colnames else np.full(len(table), np.nan)
        self._epoch = np.ma.filled(np.ma.asarray(epoch, dtype=float), np.nan)
        radius = np.linalg.norm(self._xyz.to_value(u.m), axis=-1)
        self._table = table
        self._index = {}
        for row, name in enumerate(table["name"]):
            where = f"{self._origin}, station {name}"
            if not _RADIUS_RANGE[0] <= radius[row] <= _RADIUS_RANGE[1]:
                raise ValueError(f"{where}: position is {radius[row]:.0f} m from the "
                                 "geocentre; expected ITRF coordinates on the Earth's "
                                 "surface (check the unit of x, y, z)")
            if np.any(self._velocity[row].value != 0) and np.isnan(self._epoch[row]):
                raise ValueError(f"{where}: a velocity needs the epoch (MJD) of the position")
            self._mount_and_focus(row)
            for label in [name, *self._aliases(row)]:
                if _key(label) in self._index and self._index[_key(label)] != row:
                    other = table["name"][self._index[_key(label)]]
                    raise ValueError(f"{where}: the name {label.strip()!r} is also used by "
                                     f"station {other}")
                self._index[_key(label)] = row

    def _quantity(self, table, columns, unit):
        values = []
        for column in columns:
            col = table[column]
            if col.unit is None:
                raise u.UnitsError(f"{self._origin}: column {column!r} has no unit; "
                                   f"give it one convertible to {unit}")
            try:
                values.append(u.Quantity(col).to(unit))
            except u.UnitConversionError:
                raise u.UnitsError(f"{self._origin}: column {column!r} is in {col.unit}, "
                                   f"which is not convertible to {unit}") from None
        return u.Quantity(values).T

    def _mount_and_focus(self, row):
        where = f"{self._origin}, station {self._table['name'][row]}"
        code = str(self._table["mount"][row]).strip()
        try:
            mount, focus = mount_from_label(code, "geodetic")
        except ValueError as error:
            raise ValueError(f"{where}: {error}") from None
        if "focus" in self._table.colnames:
            named = focus_from_name(self._table["focus"][row], where)
            focus = named if named is not None else focus
        return mount, focus

    @classmethod
    def read(cls, source):
        """Read a catalogue from an ECSV file.

        Parameters
        ----------
        source : str, path-like or file object
            The file.

        Returns
        -------
        `StationCatalogue`

        Raises
        ------
        FileNotFoundError
            If there is no such file.
        ValueError
            If the file is not a valid catalogue (see `StationCatalogue`).

        Examples
        --------
        >>> from astropy_feedrot.data import sample_file
        >>> from astropy_feedrot.stations import StationCatalogue
        >>> len(StationCatalogue.read(sample_file("stations.ecsv")))
        9
        """
        origin = str(getattr(source, "name", source) if hasattr(source, "read") else source)
        if hasattr(source, "read"):
            origin = origin if isinstance(getattr(source, "name", None), str) else "<stream>"
            source = source.read()
            source = source.decode() if isinstance(source, bytes) else source
        try:
            table = Table.read(source, format="ascii.ecsv")
        except (FileNotFoundError, IsADirectoryError, PermissionError):
            raise
        except Exception as error:  # astropy raises several kinds for bad ECSV
            raise ValueError(f"{origin}: not a readable ECSV table ({error})") from None
        return cls(table, origin=origin)

    def __len__(self):
        return len(self._table)

    def __contains__(self, name):
        return _key(name) in self._index

    def __repr__(self):
        return f"<StationCatalogue of {len(self)} antennas: {', '.join(self.names)}>"

    @property
    def names(self):
        """list of str: The station names, in catalogue order."""
        return [str(name) for name in self._table["name"]]

    @property
    def table(self):
        """`~astropy.table.Table`: A copy of the catalogue's table."""
        return self._table.copy()

    def _row(self, name):
        if not isinstance(name, str):
            raise TypeError(f"an antenna name must be a str, got {type(name).__name__}")
        if _key(name) in self._index:
            return self._index[_key(name)]
        labels = {}
        for row, station in enumerate(self.names):
            for label in [station, *self._aliases(row)]:
                labels.setdefault(label.upper(), station)
        close = difflib.get_close_matches(name.strip().upper(), list(labels), n=5, cutoff=0.6)
        close = list(dict.fromkeys(labels[label] for label in close))
        hint = f"; did you mean {' or '.join(close)}?" if close else "."
        raise ValueError(f"unknown antenna {name!r} in {self._origin}{hint} Known antennas: "
                         f"{', '.join(self.names)}")

    def _aliases(self, row):
        if "aliases" not in self._table.colnames or np.ma.is_masked(self._table["aliases"][row]):
            return []
        return [a.strip() for a in str(self._table["aliases"][row]).split(",") if a.strip()]

    def location(self, name, epoch=None):
        """The position of an antenna, moved to an epoch with its velocity.

        Parameters
        ----------
        name : str
            Station name or alias (case and punctuation do not matter).
        epoch : `~astropy.time.Time` or str, optional
            Epoch of the position; by default the catalogue's reference epoch
            (the velocity is not applied).

        Returns
        -------
        `~astropy.coordinates.EarthLocation`

        Raises
        ------
        ValueError
            For an unknown name (close matches are suggested).

        Examples
        --------
        >>> from astropy_feedrot.stations import default_catalogue
        >>> loc = default_catalogue().location("WARK12M", epoch="2030-01-01")
        >>> loc.z  # doctest: +FLOAT_CMP
        <Quantity -3767192.27540999 m>
        """
        row = self._row(name)
        xyz = self._xyz[row]
        if epoch is not None and not np.isnan(self._epoch[row]):
            # A position epoch needs no leap seconds: read strings as TT.
            epoch = epoch if isinstance(epoch, Time) else Time(epoch, scale="tt")
            if not epoch.isscalar:
                raise ValueError("epoch must be a single time")
            years = (epoch - Time(self._epoch[row], format="mjd", scale="tt")).to(u.yr)
            xyz = xyz + self._velocity[row] * years
        return EarthLocation.from_geocentric(*xyz)

    def get_antenna(self, name, epoch=None, focus=None):
        """The `~astropy_feedrot.Antenna` of a catalogue entry.

        Parameters
        ----------
        name : str
            Station name or alias (case and punctuation do not matter).
        epoch : `~astropy.time.Time` or str, optional
            Epoch of the position (see `location`).
        focus : `~astropy_feedrot.focus.Focus`, optional
            Replaces the catalogue's focus (e.g. ``NasmythFocus("right")``
            instead of YEBES40M's traced mirror train).

        Returns
        -------
        `~astropy_feedrot.Antenna`

        Raises
        ------
        ValueError
            For an unknown name (close matches are suggested).

        Examples
        --------
        >>> from astropy_feedrot.stations import default_catalogue
        >>> default_catalogue().get_antenna("WARK30M").mount
        AltAzMount()
        """
        row = self._row(name)
        mount, catalogue_focus = self._mount_and_focus(row)
        return Antenna(self.location(name, epoch), mount,
                       focus if focus is not None else catalogue_focus,
                       name=str(self._table["name"][row]))


@functools.lru_cache(maxsize=1)
def default_catalogue():
    """The embedded catalogue of the paper's antennas.

    Returns
    -------
    `StationCatalogue`

    Examples
    --------
    >>> from astropy_feedrot.stations import default_catalogue
    >>> default_catalogue().names  # doctest: +NORMALIZE_WHITESPACE
    ['DBR205', 'FD-VLBA', 'GGAO12M', 'WETTZ13S', 'YEBES40M', 'WARK30M', 'WARK12M',
     'EFLSBERG', 'PARKES']
    """
    table = Table.read(sample_file("stations.ecsv"), format="ascii.ecsv")
    return StationCatalogue(table, origin="the embedded station catalogue")


def read_catalogue(source):
    """Read a station catalogue of one's own (ECSV, same columns as the embedded one).

    Parameters
    ----------
    source : str, path-like or file object
        The ECSV file.

    Returns
    -------
    `StationCatalogue`

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.stations import read_catalogue
    >>> text = '''# %ECSV 1.0
    ... # ---
    ... # datatype:
    ... # - {name: name, datatype: string}
    ... # - {name: x, unit: m, datatype: float64}
    ... # - {name: y, unit: m, datatype: float64}
    ... # - {name: z, unit: m, datatype: float64}
    ... # - {name: mount, datatype: string}
    ... name x y z mount
    ... MYDISH 4075539.5 931735.6 4801629.6 AZEL
    ... '''
    >>> read_catalogue(io.StringIO(text)).get_antenna("mydish").mount
    AltAzMount()
    """
    return StationCatalogue.read(source)


def get_antenna(name, catalogue=None, epoch=None, focus=None):
    """An `~astropy_feedrot.Antenna` by name, from the embedded catalogue or one's own.

    Parameters
    ----------
    name : str
        Station name or alias, e.g. ``"YEBES40M"``, ``"Effelsberg"``,
        ``"fd-vlba"``.
    catalogue : `StationCatalogue` or str or path-like, optional
        A catalogue, or an ECSV file to read one from (default: the embedded
        catalogue of the paper's antennas).
    epoch : `~astropy.time.Time` or str, optional
        Epoch at which to place the antenna with its catalogue velocity.
    focus : `~astropy_feedrot.focus.Focus`, optional
        Replaces the catalogue's focus.

    Returns
    -------
    `~astropy_feedrot.Antenna`

    Raises
    ------
    ValueError
        For an unknown name, with the close matches.

    Examples
    --------
    >>> from astropy_feedrot.stations import get_antenna
    >>> get_antenna("YEBES40M").focus
    MirrorTrain(<4 mirrors>, feed_rotates=True, name='YEBES40M X')
    """
    if catalogue is None:
        catalogue = default_catalogue()
    elif not isinstance(catalogue, StationCatalogue):
        catalogue = read_catalogue(catalogue)
    return catalogue.get_antenna(name, epoch=epoch, focus=focus)
