# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""`Ionosphere`: the rotation measure along the lines of sight of sites, at many epochs.

One object, two sources: IONEX maps with the IGRF field through spinifex
(`Ionosphere.from_ionex`), or the user's table of rotation measures
(`Ionosphere.from_rm`). One method, `Ionosphere.rotation_measure`, takes
sites, a target and epochs, as the package's front-ends have them; an
``Antenna`` passes its ``location`` and ``name``.

For many epochs the maps are evaluated on a coarse grid (every ``step``, 60 s
by default, per site) and interpolated linearly to the epochs asked; the
elevation is interpolated the same way to tell the epochs below the horizon.
Every site's lines of sight go through the maps and the field in one call.
"""

import numpy as np
from astropy import units as u
from astropy.time import Time

from ..core.exceptions import DegenerateGeometryWarning, warn_caller
from ..core.inputs import as_location, as_skycoord, as_time, broadcast_shape
from ..core.kernel import dot
from ..earth.diurnal import network_applies, network_directions
from ..earth.frames import local_frame, location_xyz, source_direction
from .ionex import IonexMaps
from .line_of_sight import rm_along_lines_of_sight
from .rm_table import RM_UNIT, RMTable
from .sampling import coarse_nodes, interpolate

__all__ = ["Ionosphere", "DEFAULT_HEIGHT", "DEFAULT_STEP"]

__doctest_requires__ = {("Ionosphere", "Ionosphere.*"): ["spinifex"]}

#: Height of the thin shell: spinifex's (and RMextract's) for IONEX maps, the
#: height the maps of CODE, ESA, IGS and UPC state (``HGT1``).
DEFAULT_HEIGHT = 450 * u.km

#: Spacing of the grid on which IONEX maps are evaluated before interpolation.
DEFAULT_STEP = 60 * u.s

#: Heights of a thin shell that make sense: above every site, below the plasmasphere's top.
_HEIGHTS = (50 * u.km, 20000 * u.km)

_SECONDS_PER_DAY = 86400.0


def _as_height(height):
    if not isinstance(height, u.Quantity):
        raise TypeError(f"height must be a length Quantity (e.g. 450 * u.km), got "
                        f"{type(height).__name__}")
    if height.unit.physical_type != "length":
        raise u.UnitsError(f"height must be a length (e.g. 450 * u.km), got a quantity in "
                           f"{height.unit.to_string() or 'dimensionless units'}")
    if not height.isscalar or not _HEIGHTS[0] <= height <= _HEIGHTS[1]:
        raise ValueError(
            f"height of the ionosphere's thin shell must be one value from "
            f"{_HEIGHTS[0]:g} to {_HEIGHTS[1]:g}, got {height}; 450 km is the usual one")
    return height.to(u.km)


def _as_step(step):
    if not isinstance(step, u.Quantity) or step.unit.physical_type != "time":
        raise u.UnitsError(f"step must be a time Quantity (e.g. 60 * u.s), got {step!r}")
    if not step.isscalar or not step >= 0 * u.s:
        raise ValueError(f"step must be one non-negative time (0 evaluates every epoch), "
                         f"got {step}")
    return step.to(u.s)


class Ionosphere:
    """Rotation measure of the ionosphere along lines of sight.

    Make one with `from_ionex` (IONEX maps and the IGRF field, through
    spinifex) or `from_rm` (a table of rotation measures), then ask
    `rotation_measure` for sites, a target and epochs.

    Examples
    --------
    >>> import numpy as np, astropy.units as u
    >>> from astropy.coordinates import EarthLocation, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.ionosphere import Ionosphere, sample_ionex
    >>> iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
    >>> iono
    <Ionosphere from 2 IONEX files, 2020-01-08T00:00 to 2020-01-10T00:00, shell at 450 km>
    >>> [path.name for path in iono.files]
    ['codg0080.20i.Z', 'codg0090.20i.Z']
    >>> wsrt = EarthLocation.from_geodetic(6.60 * u.deg, 52.91 * u.deg, 16 * u.m)
    >>> crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    >>> iono.rotation_measure(wsrt, crab, Time("2020-01-08T22:00"))  # doctest: +FLOAT_CMP
    <Quantity 0.31617066 rad / m2>
    """

    def __init__(self, *, maps=None, table=None, height=DEFAULT_HEIGHT, step=DEFAULT_STEP):
        if (maps is None) == (table is None):
            raise TypeError("make an Ionosphere with Ionosphere.from_ionex(paths) or "
                            "Ionosphere.from_rm(table)")
        self._maps = maps
        self._table = table
        self.height = _as_height(height)
        self.step = _as_step(step)

    @classmethod
    def from_ionex(cls, paths, height=DEFAULT_HEIGHT, step=DEFAULT_STEP):
        """An ionosphere from IONEX global ionosphere maps (CODE, ESA, IGS, UPC...).

        Parameters
        ----------
        paths : path-like or sequence of path-like
            IONEX files, one per UTC day, plain, gzip (``.gz``) or Unix
            compress (``.Z``), read from these paths only: nothing is
            downloaded. Give the day after the last one observed too if you
            have it: its first map then serves the last midnight, as in
            spinifex.
        height : `~astropy.units.Quantity`, optional
            Height of the thin shell where the line of sight pierces the
            ionosphere (450 km by default, as spinifex's
            ``get_rm_from_skycoord``), from 50 to 20000 km.
        step : `~astropy.units.Quantity`, optional
            Spacing of the grid of epochs (per site) on which the maps are
            evaluated before linear interpolation to the epochs asked; 60 s by
            default, 0 to evaluate every epoch.

        Returns
        -------
        `Ionosphere`

        Raises
        ------
        ImportError
            If spinifex (the extra ``ionosphere``) is not installed.
        FileNotFoundError
            If a file does not exist.
        IonosphereError
            If a file is not IONEX, is compressed but not named so, or two
            files start on the same day.
        TypeError, ValueError, astropy.units.UnitsError
            For a ``height`` or ``step`` that is not one length (time) in range.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy_feedrot.ionosphere import Ionosphere, sample_ionex
        >>> Ionosphere.from_ionex(sample_ionex("uqrg*"), height=350 * u.km).height
        <Quantity 350. km>
        """
        height = _as_height(height)
        step = _as_step(step)
        return cls(maps=IonexMaps(paths), height=height, step=step)

    @classmethod
    def from_rm(cls, table, step=DEFAULT_STEP):
        """An ionosphere from a table of rotation measures (ALBUS, an h5parm, your own).

        Parameters
        ----------
        table : `~astropy.table.QTable`
            Columns ``time`` (`~astropy.time.Time`), ``rm`` (rad m^-2) and,
            optionally, ``antenna`` (names as the antennas are called: in the
            station catalogue or the visibility file). Without ``antenna``
            one series serves every antenna. Interpolated linearly in time,
            never extrapolated.
        step : `~astropy.units.Quantity`, optional
            Spacing of the grid of epochs on which the target's elevation is
            computed (to find where it is below the horizon); 60 s by default.

        Returns
        -------
        `Ionosphere`

        Raises
        ------
        TypeError
            If ``table`` is not an astropy table, its ``time`` not a Time
            column, its ``rm`` plain numbers.
        astropy.units.UnitsError
            If ``rm`` is not in rad m^-2.
        ValueError
            If a column is missing or an antenna has two rows at one epoch.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.table import QTable
        >>> from astropy.time import Time
        >>> from astropy_feedrot.ionosphere import Ionosphere
        >>> table = QTable({"time": Time(["2024-06-01T00:00", "2024-06-01T02:00"] * 2),
        ...                 "rm": [1.0, 3.0, -0.5, 0.5] * u.rad / u.m**2,
        ...                 "antenna": ["EF", "EF", "WB", "WB"]})
        >>> Ionosphere.from_rm(table)
        <Ionosphere from a table of rotation measures for EF, WB>
        """
        return cls(table=RMTable(table), step=step)

    def __repr__(self):
        if self._table is not None:
            names = self._table.names
            which = f"for {', '.join(names)}" if names else "for every antenna"
            return f"<Ionosphere from a table of rotation measures {which}>"
        count = len(self._maps.paths)
        plural = "s" if count > 1 else ""
        return (f"<Ionosphere from {count} IONEX file{plural}, "
                f"{self._maps.describe_coverage()}, shell at {self.height.value:g} km>")

    @property
    def files(self):
        """The IONEX files read, sorted by day (empty for a table).

        For the history a correction writes.
        """
        return () if self._maps is None else self._maps.paths

    @property
    def coverage(self):
        """The spans of time the maps cover, ``(start, stop)`` pairs in UTC MJD.

        For a table, the union of its series' spans is not given: each
        antenna has its own (``None``).
        """
        return None if self._maps is None else self._maps.coverage()

    def rotation_measure(self, location, target, obstime, antenna=None):
        """Rotation measure along the lines of sight from sites to a target.

        Parameters
        ----------
        location : `~astropy.coordinates.EarthLocation`
            One site, or several (any shape ``L``).
        target : `~astropy.coordinates.SkyCoord`
            The source: one direction (evaluated on the coarse grid), or one
            per epoch (a shape that broadcasts with ``obstime``; then
            evaluated at every epoch).
        obstime : `~astropy.time.Time`
            Epochs of observation, any shape ``T`` (any time scale).
        antenna : str or sequence of str, optional
            The antennas' names, one per location (the shape of
            ``location``), for a table that gives rotation measures per
            antenna; not used by IONEX maps or a table of one series.

        Returns
        -------
        `~astropy.units.Quantity`
            RM in rad m^-2, of shape ``T + L`` (epochs first, sites last; the
            broadcast shape of ``target`` and ``obstime`` for ``T``): a
            scalar for one site and one epoch. NaN where the target is below
            a site's horizon (elevation < 0, no refraction). Positive when
            the field along the line of sight points towards the observer: a
            source of intrinsic angle chi0 is seen at chi0 + RM lambda^2.

        Raises
        ------
        IonosphereError
            If an epoch lies outside the maps (or the table), or the table
            does not name an antenna: the message gives the span covered.
        TypeError
            If ``location``, ``target`` or ``obstime`` is of the wrong kind.
        ValueError
            If shapes do not broadcast, ``antenna`` does not give one name per
            location, or the table is per antenna and no name is given.

        Warns
        -----
        DegenerateGeometryWarning
            Once, with the count, if the target is below the horizon of a
            site at some epochs (NaN there).

        Notes
        -----
        From IONEX maps, each site's RM is computed as spinifex's
        ``get_rm_from_skycoord`` does (a thin shell, the IGRF field at the
        pierce point) at the shell's ``height``. On the grid of 60 s the
        result differs from evaluating every epoch by at most 2e-4 rad m^-2
        with hourly maps and 1.1e-3 rad m^-2 with 15 min maps (rms 30 times
        less; 12 h at two sites, docs/ionosphere.rst), far below the maps'
        own uncertainty; ``step=10 * u.s`` gives 1e-4 rad m^-2.

        Examples
        --------
        >>> import numpy as np, astropy.units as u
        >>> from astropy.coordinates import EarthLocation, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot.ionosphere import Ionosphere, sample_ionex
        >>> iono = Ionosphere.from_ionex(sample_ionex("codg00[89]0.20i.Z"))
        >>> sites = EarthLocation.from_geodetic([6.60, -3.09] * u.deg, [52.91, 40.52] * u.deg)
        >>> epochs = Time("2020-01-08T20:00") + np.arange(3) * u.h
        >>> iono.rotation_measure(sites, SkyCoord("05h34m31.94s +22d00m52.2s"),
        ...                       epochs)  # doctest: +FLOAT_CMP
        <Quantity [[0.29062281, 0.4704625 ],
                   [0.33126959, 0.49879387],
                   [0.31617414, 0.47001266]] rad / m2>
        """
        location = as_location(location)
        time = as_time(obstime)
        target = as_skycoord(target, time)
        shape = broadcast_shape(target=target.shape, obstime=time.shape)
        sites = location.ravel() if location.shape else location.reshape((1,))
        names = self._names(antenna, location.shape, sites.size)
        fixed = target.isscalar
        if fixed:
            epochs = time.utc.ravel()  # a scalar target broadcasts to the epochs' shape
            directions = target
        else:
            epochs = np.broadcast_to(time, shape, subok=True).utc.ravel()
            directions = np.broadcast_to(target, shape, subok=True).ravel()
        mjd = np.asarray(epochs.mjd, dtype=float)
        if fixed:  # each distinct epoch once (a visibility file repeats them per baseline)
            unique, first, inverse = np.unique(mjd, return_index=True, return_inverse=True)
            base = epochs[first]
        else:
            unique, base, inverse = mjd, epochs, None
        grid = self._grid(unique) if fixed and self.step > 0 else None
        at = base if grid is None else grid[2]
        # The sites' apparent directions of the target (astropy's topocentric ITRS to
        # 0.001 mas): a fixed direction once for the network and each site's diurnal
        # aberration; else site by site. Then every site's pierce points at once.
        if fixed and network_applies(directions, at):
            s = network_directions(directions, location_xyz(sites), at)
        else:
            s = np.stack([source_direction(directions, site, at) for site in sites], axis=1)
        elevation = np.arcsin(np.clip(dot(s, local_frame(sites).up), -1.0, 1.0))
        if self._maps is not None:
            rm = self._rm_from_maps(sites, s, elevation, at, grid is not None)
            if grid is not None:
                rm = interpolate(grid[0], grid[1], rm)
        else:
            rm = np.column_stack([self._table.rm(name, unique) for name in names])
        if grid is not None:
            elevation = interpolate(grid[0], grid[1], elevation)
        if inverse is not None:
            rm, elevation = rm[inverse], elevation[inverse]
        values, below = rm, elevation < 0
        count = int(np.count_nonzero(below))
        if count:
            warn_caller(
                f"rotation measure is undefined at {count} of {below.size} epochs x sites, "
                "where the target is below the horizon (the line of sight crosses the "
                "Earth); NaN is returned there", DegenerateGeometryWarning)
        values[below] = np.nan
        return (values.reshape(shape + location.shape)) << RM_UNIT

    @staticmethod
    def _names(antenna, location_shape, count):
        if antenna is None:
            return [None] * count
        names = [antenna] if isinstance(antenna, str) else [str(name) for name in np.ravel(antenna)]
        if len(names) == 1 and count == 1:
            return names
        if np.shape(antenna) != location_shape:
            raise ValueError(
                f"antenna gives {len(names)} name(s) for locations of shape {location_shape}; "
                "give one name per location, in the same shape")
        return names

    def _rm_from_maps(self, sites, s, elevation, at, nodes):
        """RM (T, L) at the epochs ``at`` from the maps, NaN where it is not needed.

        Only lines of sight above the horizon are needed, and on the coarse
        grid (``nodes``) also those next to one above: the epochs between two
        nodes below the horizon are below it too.
        """
        mjd = np.asarray(at.utc.mjd, dtype=float)
        self._maps.file_index(mjd)  # every epoch covered, above the horizon or not
        needed = elevation >= 0
        if nodes:
            needed[1:] |= needed[:-1].copy()
            needed[:-1] |= elevation[1:] >= 0
        rm = np.full(elevation.shape, np.nan)
        if needed.any():
            epoch, site = np.nonzero(needed)
            rm[needed] = rm_along_lines_of_sight(self._maps, location_xyz(sites)[site] / 1e3,
                                                 s[needed], mjd[epoch], self.height)
        return rm

    def _grid(self, unique):
        """The coarse grid for sorted unique epochs (UTC MJD), or None to use the epochs.

        Returns the epochs in seconds from their first UTC midnight, the
        nodes in the same seconds and the nodes as a UTC `~astropy.time.Time`.
        """
        day = np.floor(unique[0])
        seconds = (unique - day) * _SECONDS_PER_DAY
        groups = None
        if self._maps is not None:  # no node in a gap between the maps' spans
            index = self._maps.file_index(unique)  # raises for epochs outside the maps
            starts = np.array([start for start, _ in self._maps.coverage()])
            groups = np.searchsorted(starts, self._maps.starts[index], side="right")
        nodes = coarse_nodes(seconds, self.step.to_value(u.s), groups)
        if nodes is seconds:
            return None
        return seconds, nodes, Time(day + nodes / _SECONDS_PER_DAY, format="mjd", scale="utc")
