# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""A catalogue of antennas: positions, mounts and focus types by name.

The embedded catalogue holds the stations of the VLBI networks (VLBA, EVN and
e-MERLIN, IVS and VGOS, KVN, VERA and the EAVN, the LBA, the GMVA, the EHT, the
DSN), the pads of the VLA and the ATCA, and reference positions of connected
arrays, built by ``catalogue/build_stations.py`` from public station files (the
catalogues of the VLBI scheduling program SCHED, the EVN observation planner,
casacore's tables, eht-imaging's EHT array files, astropy-data's sites,
pyuvdata's known telescopes, DiFX's antenna table, the IVS antenna-info file;
see :doc:`/stations`) and checked against every other source that holds each
station. Each row gives the source of its position, mount and focus; a focus
that no source gives is marked "assumed" with the reason. The paper's antennas come first,
with the positions of its Tables 1 and 3 (DBR205, FD-VLBA, GGAO12M, WETTZ13S),
its mounts and focus types, and the mirror trains of YEBES40M and WARK30M
(Appendix C). Mounts are written as the geodetic station-catalogue codes (see
`astropy_feedrot.stations.labels`).

Names resolve without regard to case, spaces or punctuation: IVS eight-character
names, two-letter VLBI codes, EHT codes, DSN ``DSS-NN`` names and observatory
names. A name that several stations share (``KP``, ``Ap``...) is refused as
ambiguous, naming them and their networks, unless a ``network`` chooses one
(``get_antenna("KP", network="EHT")``). An unknown name is answered with the
nearest five names.

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

from ..antennas.receptors import Receptors
from ..antennas.rotators import Rotator
from ..data import sample_file
from ..earth.frames import check_station_xyz
from ..engine.antenna import Antenna
from .focus_names import FOCUS_NAMES, focus_from_name
from .labels import mount_from_label

__all__ = [
    "MAX_VELOCITY",
    "StationCatalogue",
    "default_catalogue",
    "read_catalogue",
    "get_antenna",
    "get_network",
    "networks",
    "focus_from_name",
    "FOCUS_NAMES",
]

#: Columns every catalogue must have.
REQUIRED_COLUMNS = ("name", "x", "y", "z", "mount")

#: Largest station velocity a catalogue may give. Tectonic plates move by
#: less than 0.2 m/yr (the fastest, near the Tonga trench, about 0.24 m/yr),
#: and the linear velocities of geodetic catalogues are those of the plates;
#: a speed above 1 m/yr is a unit error (mm/yr labelled m/yr gives about
#: 20 m/yr, m/s instead of m/yr thousands of km/yr), which would move a
#: station off the Earth.
MAX_VELOCITY = 1 * u.m / u.yr


def _epoch(epoch):
    """One unmasked epoch; strings are read as TT (a position epoch needs no leap seconds)."""
    if not isinstance(epoch, Time):
        try:
            epoch = Time(epoch, scale="tt")
        except Exception:  # astropy raises several kinds for what it cannot read
            raise TypeError(f"epoch must be an astropy Time or an ISO string that Time() "
                            f"reads (e.g. '2030-01-01'), got {type(epoch).__name__} "
                            f"{epoch!r}") from None
    if not epoch.isscalar:
        raise ValueError(f"epoch must be a single time, got shape {epoch.shape}")
    if epoch.masked and epoch.mask:
        raise ValueError("epoch is masked; give the epoch at which to place the station")
    return epoch


def _key(name):
    """Case-, space- and punctuation-insensitive form of a station name."""
    return re.sub(r"[^0-9A-Z]", "", str(name).upper())


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
        ``epoch`` (MJD of the position), ``networks`` (comma-separated network
        names, see `get_network`), ``rotator`` (a mode of
        `~astropy_feedrot.antennas.rotators.Rotator`, ``'sky'`` or ``'fixed'``, or empty
        for none), ``feed_offset`` (an angle unit: the feed's constant angle in
        the cabin, such as eht-imaging's ``FR_OFFSET``; a fixed rotator at that
        angle, or the angle of the ``rotator`` column's mode), ``receptors``
        (``'R:0,L:0'``, ``'X:45,Y:135'``: the text of
        `~astropy_feedrot.Receptors.from_text`; empty where no source states
        them), ``source`` or ``position_source``, ``mount_source``,
        ``focus_source``, ``rotator_source`` and ``receptors_source``
        (citations). Other columns are kept and ignored.
    origin : str, optional
        Where the table came from, for error messages.

    Raises
    ------
    ValueError
        For a missing column, an unknown mount code or focus, a duplicated
        name, a missing (masked) or non-finite coordinate, a position that is
        not an Earth station (e.g. in km; see
        `~astropy_feedrot.earth.frames.check_station_xyz`), a velocity faster than
        `MAX_VELOCITY` (a unit error) or given for some axes only, or an
        epoch that is not an MJD number.
    astropy.units.UnitsError
        For coordinates or velocities without compatible units.

    Examples
    --------
    >>> from astropy_feedrot.stations.catalogue import default_catalogue
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
        self._xyz, missing = self._quantity(table, ("x", "y", "z"), u.m)
        self._check_missing(table, ("x", "y", "z"), missing, np.any(missing, axis=-1))
        if all(c in table.colnames for c in ("vx", "vy", "vz")):
            self._velocity, missing = self._quantity(table, ("vx", "vy", "vz"), u.m / u.yr)
            # A row without any velocity has no velocity model; half of one is an error.
            self._check_missing(table, ("vx", "vy", "vz"), missing,
                                np.any(missing, axis=-1) & ~np.all(missing, axis=-1))
            self._velocity[np.all(missing, axis=-1)] = 0
        else:
            self._velocity = np.zeros((len(table), 3)) * u.m / u.yr
        self._epoch = self._epochs(table)
        speed = np.linalg.norm(self._velocity.to_value(u.m / u.yr), axis=-1)
        self._table = table
        self._index = {}
        for row, name in enumerate(table["name"]):
            where = f"{self._origin}, station {name}"
            check_station_xyz(self._xyz[row].to_value(u.m), f"{where}: position")
            if not speed[row] <= MAX_VELOCITY.to_value(u.m / u.yr):  # NaN too
                raise ValueError(
                    f"{where}: velocity is {speed[row]:.4g} m/yr; station velocities are "
                    f"below {MAX_VELOCITY.to_value(u.m / u.yr):g} m/yr (plate motions, "
                    "< 0.2 m/yr): check the unit of vx, vy, vz (mm/yr labelled m/yr? m/s "
                    "instead of m/yr?)"
                )
            if np.any(self._velocity[row].value != 0) and np.isnan(self._epoch[row]):
                raise ValueError(f"{where}: a velocity needs the epoch (MJD) of the position")
            self._mount_and_focus(row)
            self._receptors(row)
            if _key(name) in self._index:
                other = table["name"][self._index[_key(name)]]
                raise ValueError(f"{where}: the name {str(name).strip()!r} is also used by "
                                 f"station {other}")
            self._index[_key(name)] = row
        # Aliases come second: one that is another station's name is an error;
        # one shared by several stations (a two-letter code used twice) is
        # ambiguous and refused when it is looked up.
        self._ambiguous = {}
        for row, name in enumerate(table["name"]):
            for label in self._aliases(row):
                key = _key(label)
                if key in self._ambiguous:
                    self._ambiguous[key].append(row)
                elif key not in self._index:
                    self._index[key] = row
                elif self._index[key] != row:
                    other = self._index[key]
                    if _key(table["name"][other]) == key:
                        raise ValueError(f"{self._origin}, station {name}: the name "
                                         f"{label.strip()!r} is also used by station "
                                         f"{table['name'][other]}")
                    self._ambiguous[key] = [other, row]
                    del self._index[key]

    def _quantity(self, table, columns, unit):
        """Columns as a (rows, 3) Quantity in ``unit``, and where values are missing."""
        values, missing = [], []
        for column in columns:
            col = table[column]
            if col.unit is None:
                raise u.UnitsError(f"{self._origin}: column {column!r} has no unit; "
                                   f"give it one convertible to {unit}")
            try:
                data = np.asarray(np.ma.getdata(col), dtype=float)
            except (TypeError, ValueError):
                raise ValueError(f"{self._origin}: column {column!r} must hold numbers, "
                                 f"got {col.dtype}") from None
            try:
                values.append(u.Quantity(data, col.unit).to(unit))
            except u.UnitConversionError:
                raise u.UnitsError(f"{self._origin}: column {column!r} is in {col.unit}, "
                                   f"which is not convertible to {unit}") from None
            missing.append(np.ma.getmaskarray(col))
        return u.Quantity(values).T, np.stack(missing, axis=-1)

    def _check_missing(self, table, columns, missing, refused):
        """ValueError naming the first station in ``refused`` with a missing value."""
        rows = np.flatnonzero(refused)
        if rows.size:
            row = rows[0]
            empty = [c for c, gone in zip(columns, missing[row]) if gone]
            raise ValueError(f"{self._origin}, station {table['name'][row]}: no value in "
                             f"column(s) {', '.join(empty)}; every station needs "
                             f"{', '.join(columns)}")

    def _epochs(self, table):
        """The ``epoch`` column as MJD floats, NaN where missing (no velocity model)."""
        if "epoch" not in table.colnames:
            return np.full(len(table), np.nan)
        column = table["epoch"]
        try:
            epoch = np.asarray(np.ma.getdata(column), dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"{self._origin}: column 'epoch' must hold MJD numbers, got "
                             f"{column.dtype}") from None
        epoch = np.where(np.ma.getmaskarray(column), np.nan, epoch)
        if np.any(np.isinf(epoch)):
            row = int(np.flatnonzero(np.isinf(epoch))[0])
            raise ValueError(f"{self._origin}, station {table['name'][row]}: epoch is "
                             f"{epoch[row]}; give the MJD of the position (or nan for none)")
        return epoch

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
        >>> from astropy_feedrot.stations.catalogue import StationCatalogue
        >>> len(StationCatalogue.read(sample_file("stations.ecsv"))) >= 90
        True
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

    def stations_named(self, name):
        """The stations a name or alias stands for: one, several (a shared name) or none.

        Parameters
        ----------
        name : str
            Station name or alias (case and punctuation do not matter).

        Returns
        -------
        list of str
            The stations' names, in catalogue order.

        Examples
        --------
        >>> from astropy_feedrot.stations.catalogue import default_catalogue
        >>> default_catalogue().stations_named("kp")
        ['KP-VLBA', 'KP12']
        >>> default_catalogue().stations_named("nowhere")
        []
        """
        key = _key(name)
        rows = [self._index[key]] if key in self._index else self._ambiguous.get(key, [])
        return [self.names[row] for row in sorted(rows)]

    def receptors(self, name, network=None):
        """The receptors of a station, and the source that states them.

        Parameters
        ----------
        name, network : str
            As `get_antenna`.

        Returns
        -------
        receptors : `~astropy_feedrot.Receptors` or None
            None where the catalogue states none.
        source : str
            The ``receptors_source`` column (empty with no receptors).

        Raises
        ------
        TypeError, ValueError
            As `get_antenna`.

        Examples
        --------
        >>> from astropy_feedrot.stations.catalogue import default_catalogue
        >>> default_catalogue().receptors("FD-VLBA")[0]
        Receptors('RL', [0.0, 0.0] * u.deg)
        """
        row = self._row(name, network)
        receptors, source = self._receptors(row), ""
        if receptors is not None and "receptors_source" in self._table.colnames:
            source = self._table["receptors_source"][row]
        return receptors, "" if np.ma.is_masked(source) else str(source).strip()

    def _row(self, name, network=None):
        if not isinstance(name, str):
            raise TypeError(f"an antenna name must be a str, got {type(name).__name__}")
        key = _key(name)
        candidates = ([self._index[key]] if key in self._index
                      else list(self._ambiguous.get(key, [])))
        if network is not None:
            members = set(self.network_names(network))
            in_network = [row for row in candidates if self.names[row] in members]
            if len(in_network) == 1:
                return in_network[0]
            if candidates and not in_network:
                raise ValueError(
                    f"antenna {name!r} ({' or '.join(self._described(r) for r in candidates)}) "
                    f"is not a station of the network {network!r} in {self._origin}; give "
                    "another network, or none")
        if len(candidates) == 1:
            return candidates[0]
        if candidates:
            # A network that holds exactly one of them chooses it.
            choosers = [n for r in reversed(candidates) for n in self._networks(r)
                        if sum(n in self._networks(c) for c in candidates) == 1]
            how = (f", or the network, e.g. get_antenna({name!r}, network={choosers[0]!r})"
                   if choosers else "")
            raise ValueError(
                f"ambiguous antenna name {name!r} in {self._origin}: it names "
                f"{' and '.join(self._described(r) for r in candidates)}; give one of those "
                f"names{how}")
        labels = {}
        for row, station in enumerate(self.names):
            for label in [station, *self._aliases(row)]:
                labels.setdefault(_key(label), station)
        close = difflib.get_close_matches(key, list(labels), n=20, cutoff=0.0)
        nearest = list(dict.fromkeys(labels[label] for label in close))[:5]
        raise ValueError(f"unknown antenna {name!r} in {self._origin}; the nearest names: "
                         f"{', '.join(nearest)}")

    def _described(self, row):
        """A station's name with its networks, for messages."""
        networks = ", ".join(self._networks(row))
        return f"{self.names[row]} ({networks})" if networks else self.names[row]

    def networks(self):
        """The networks named in the catalogue's ``networks`` column.

        Returns
        -------
        list of str
            Sorted, case as written in the catalogue; empty if the catalogue
            has no ``networks`` column.

        Examples
        --------
        >>> from astropy_feedrot.stations.catalogue import default_catalogue
        >>> "VLBA" in default_catalogue().networks()
        True
        """
        found = {}
        for row in range(len(self)):
            for network in self._networks(row):
                found.setdefault(network.upper(), network)
        return sorted(found.values(), key=str.upper)

    def network_names(self, network):
        """The names of the stations of a network, in catalogue order.

        Parameters
        ----------
        network : str
            A network of `networks` (case-insensitive), e.g. ``"VLBA"``,
            ``"EVN"``, ``"EHT"``.

        Returns
        -------
        list of str

        Raises
        ------
        TypeError
            If ``network`` is not a str.
        ValueError
            For an unknown network (the message suggests close matches and
            lists the known ones).

        Examples
        --------
        >>> from astropy_feedrot.stations.catalogue import default_catalogue
        >>> len(default_catalogue().network_names("vlba")) >= 10
        True
        """
        if not isinstance(network, str):
            raise TypeError(f"a network name must be a str, got {type(network).__name__}")
        known = self.networks()
        wanted = network.strip().upper()
        names = [self.names[row] for row in range(len(self))
                 if wanted in (n.upper() for n in self._networks(row))]
        if not names:
            close = difflib.get_close_matches(wanted, [k.upper() for k in known], n=3,
                                              cutoff=0.5)
            close = [k for k in known if k.upper() in close]
            hint = f"; did you mean {' or '.join(close)}?" if close else "."
            raise ValueError(f"unknown network {network!r} in {self._origin}{hint} Known "
                             f"networks: {', '.join(known) or 'none'}")
        return names

    def get_network(self, network, epoch=None):
        """The `~astropy_feedrot.Antenna` of each station of a network.

        Parameters
        ----------
        network : str
            A network of `networks` (case-insensitive).
        epoch : `~astropy.time.Time` or str, optional
            Epoch of the positions (see `location`).

        Returns
        -------
        list of `~astropy_feedrot.Antenna`

        Raises
        ------
        TypeError, ValueError
            As `network_names` and `get_antenna`.

        Examples
        --------
        >>> from astropy_feedrot.stations.catalogue import default_catalogue
        >>> [a.name for a in default_catalogue().get_network("KVN")]
        ['KVNPC', 'KVNTN', 'KVNUS', 'KVNYS']
        """
        return [self.get_antenna(name, epoch=epoch) for name in self.network_names(network)]

    def _networks(self, row):
        if "networks" not in self._table.colnames or \
                np.ma.is_masked(self._table["networks"][row]):
            return []
        return [n.strip() for n in str(self._table["networks"][row]).split(",") if n.strip()]

    def _aliases(self, row):
        if "aliases" not in self._table.colnames or np.ma.is_masked(self._table["aliases"][row]):
            return []
        return [a.strip() for a in str(self._table["aliases"][row]).split(",") if a.strip()]

    def location(self, name, epoch=None, network=None):
        """The position of an antenna, moved to an epoch with its velocity.

        Parameters
        ----------
        name : str
            Station name or alias (case and punctuation do not matter).
        epoch : `~astropy.time.Time` or str, optional
            Epoch of the position; by default the catalogue's reference epoch
            (the velocity is not applied).
        network : str, optional
            A network of `networks` that chooses among the stations sharing
            ``name`` (e.g. ``"KP"`` is KP-VLBA in the VLBA and KP12 in the EHT).

        Returns
        -------
        `~astropy.coordinates.EarthLocation`

        Raises
        ------
        TypeError
            If ``epoch`` is not a time.
        ValueError
            For an unknown name (the nearest five names are given), a name
            that several stations share (they are named, with their
            networks) and no ``network`` that chooses one, an unknown
            network, an ``epoch`` that is masked or not a single time, or one
            so far from the catalogue's that the velocity moves the station
            off the Earth.

        Examples
        --------
        >>> from astropy_feedrot.stations.catalogue import default_catalogue
        >>> loc = default_catalogue().location("WARK12M", epoch="2030-01-01")
        >>> loc.z  # doctest: +FLOAT_CMP
        <Quantity -3767192.27540999 m>
        """
        row = self._row(name, network)
        xyz = self._xyz[row]
        if epoch is not None:
            epoch = _epoch(epoch)
        if epoch is not None and not np.isnan(self._epoch[row]):
            years = (epoch - Time(self._epoch[row], format="mjd", scale="tt")).to(u.yr)
            xyz = xyz + self._velocity[row] * years
            check_station_xyz(xyz.to_value(u.m),
                              f"{self._origin}, station {self.names[row]}: position at "
                              f"{epoch.isot}")
        return EarthLocation.from_geocentric(*xyz)

    def get_antenna(self, name, epoch=None, focus=None, network=None):
        """The `~astropy_feedrot.Antenna` of a catalogue entry.

        Parameters
        ----------
        name : str
            Station name or alias (case and punctuation do not matter).
        epoch : `~astropy.time.Time` or str, optional
            Epoch of the position (see `location`).
        focus : `~astropy_feedrot.antennas.focus.Focus`, optional
            Replaces the catalogue's focus (e.g. ``NasmythFocus("right")``
            instead of YEBES40M's traced mirror train).
        network : str, optional
            Chooses among stations that share ``name`` (see `location`).

        Returns
        -------
        `~astropy_feedrot.Antenna`
            With the catalogue's receptors where it states them (see
            `receptors`).

        Raises
        ------
        TypeError, ValueError
            As `location`, and for a ``focus`` that is not a focus or does
            not fit the mount.

        Examples
        --------
        >>> from astropy_feedrot.stations.catalogue import default_catalogue
        >>> default_catalogue().get_antenna("WARK30M").mount
        AltAzMount()
        >>> default_catalogue().get_antenna("KP", network="EHT").name
        'KP12'
        """
        row = self._row(name, network)
        mount, catalogue_focus = self._mount_and_focus(row)
        return Antenna(self.location(self.names[row], epoch), mount,
                       focus if focus is not None else catalogue_focus,
                       name=str(self._table["name"][row]), rotator=self._rotator(row),
                       receptors=self._receptors(row))

    def _receptors(self, row):
        """The Receptors of a row's ``receptors`` column, or None where it is empty."""
        text = self._table["receptors"][row] if "receptors" in self._table.colnames else ""
        if np.ma.is_masked(text) or not str(text).strip():
            return None
        try:
            return Receptors.from_text(str(text).strip())
        except ValueError as error:
            raise ValueError(f"{self._origin}, station {self.names[row]}: {error}") from None

    def _rotator(self, row):
        """The Rotator of a row's ``rotator`` and ``feed_offset`` columns, or None.

        A feed offset without a rotator is a feed fixed in the cabin at that
        angle: a ``'fixed'`` rotator (eht-imaging adds its ``FR_OFFSET`` the
        same way, ``fr_par * PA + fr_elev * El + fr_off``).
        """
        mode = ""
        if "rotator" in self._table.colnames:
            mode = str(self._table["rotator"][row]).strip().lower()
        mode = "" if mode in ("--", "none") else mode
        if mode not in ("", "sky", "fixed"):
            raise ValueError(f"{self._origin}: rotator of {self._table['name'][row]!r} must be "
                             f"'sky', 'fixed' or empty, got {mode!r}")
        offset = 0 * u.deg
        if "feed_offset" in self._table.colnames:
            column = self._table["feed_offset"]
            if column.unit is None or column.unit.physical_type != "angle":
                raise ValueError(f"{self._origin}: the feed_offset column needs an angle unit "
                                 f"(deg), got {column.unit}")
            value = column[row]
            if not np.ma.is_masked(value) and np.isfinite(value):
                offset = (float(value) * column.unit).to(u.deg)
        if mode == "":
            return None if offset == 0 else Rotator("fixed", offset)
        return Rotator(mode, offset)


@functools.lru_cache(maxsize=1)
def default_catalogue():
    """The embedded station catalogue.

    Returns
    -------
    `StationCatalogue`

    Examples
    --------
    >>> from astropy_feedrot.stations.catalogue import default_catalogue
    >>> default_catalogue().names[:9]  # doctest: +NORMALIZE_WHITESPACE
    ['DBR205', 'FD-VLBA', 'GGAO12M', 'WETTZ13S', 'YEBES40M', 'WARK30M', 'WARK12M',
     'EFLSBERG', 'PARKES']
    """
    table = Table.read(sample_file("stations.ecsv"), format="ascii.ecsv")
    return StationCatalogue(table, origin="the embedded station catalogue")


def networks(catalogue=None):
    """The networks of the embedded catalogue (or of one's own).

    Parameters
    ----------
    catalogue : `StationCatalogue` or str or path-like, optional
        A catalogue, or an ECSV file to read one from (default: the embedded one).

    Returns
    -------
    list of str

    Examples
    --------
    >>> from astropy_feedrot.stations.catalogue import networks
    >>> {"EVN", "VLBA", "EHT"} <= set(networks())
    True
    """
    return _as_catalogue(catalogue).networks()


def get_network(network, catalogue=None, epoch=None):
    """The `~astropy_feedrot.Antenna` of each station of a network.

    Parameters
    ----------
    network : str
        A network name, e.g. ``"VLBA"``, ``"EVN"``, ``"EHT"`` (see `networks`;
        case-insensitive).
    catalogue : `StationCatalogue` or str or path-like, optional
        A catalogue, or an ECSV file to read one from (default: the embedded one).
    epoch : `~astropy.time.Time` or str, optional
        Epoch at which to place the antennas with their catalogue velocities.

    Returns
    -------
    list of `~astropy_feedrot.Antenna`

    Raises
    ------
    TypeError, ValueError
        For an unknown network (with close matches and the known networks).

    Examples
    --------
    >>> from astropy_feedrot.stations.catalogue import get_network
    >>> len(get_network("VLBA")) >= 10
    True
    """
    return _as_catalogue(catalogue).get_network(network, epoch=epoch)


def _as_catalogue(catalogue):
    if catalogue is None:
        return default_catalogue()
    if isinstance(catalogue, StationCatalogue):
        return catalogue
    return read_catalogue(catalogue)


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
    >>> from astropy_feedrot.stations.catalogue import read_catalogue
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


def get_antenna(name, catalogue=None, epoch=None, focus=None, network=None):
    """An `~astropy_feedrot.Antenna` by name, from the embedded catalogue or one's own.

    Parameters
    ----------
    name : str
        Station name or alias, e.g. ``"YEBES40M"``, ``"Effelsberg"``,
        ``"fd-vlba"``.
    catalogue : `StationCatalogue` or str or path-like, optional
        A catalogue, or an ECSV file to read one from (default: the embedded
        catalogue).
    epoch : `~astropy.time.Time` or str, optional
        Epoch at which to place the antenna with its catalogue velocity.
    focus : `~astropy_feedrot.antennas.focus.Focus`, optional
        Replaces the catalogue's focus.
    network : str, optional
        Chooses among the stations that share ``name``: ``"KP"`` is refused
        as ambiguous (KP-VLBA, KP12), ``get_antenna("KP", network="EHT")``
        is the EHT's 12 m antenna.

    Returns
    -------
    `~astropy_feedrot.Antenna`

    Raises
    ------
    TypeError, ValueError
        For an unknown name (with the nearest five names), an ambiguous
        name (naming the stations and how to choose), an unknown network,
        and as `StationCatalogue.get_antenna` and `read_catalogue`.

    Examples
    --------
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> get_antenna("YEBES40M").focus
    MirrorTrain(<4 mirrors>, feed_rotates=True, name='YEBES40M X')
    """
    return _as_catalogue(catalogue).get_antenna(name, epoch=epoch, focus=focus, network=network)
