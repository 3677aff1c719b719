# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The whole rotation of the polarization plane per station and epoch, as an astropy QTable.

What ``feedrot faraday`` prints and `~astropy_feedrot.applied.plotting.plot_faraday`
draws: for each station and epoch the elevation, the ionosphere's rotation
measure along the line of sight, the Faraday rotation chi = RM lambda^2 at
each frequency, the feed rotation Phi, and psi = Phi - chi, the one angle that
enters a correction as the feed rotation does (see :doc:`/ionosphere`).
"""

import os
import warnings

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.table import QTable

from ..core.exceptions import DegenerateGeometryWarning
from ..earth.eop import iers_context
from ..earth.frames import as_elevation_limit, as_skycoord
from ..engine.antenna import Antenna
from ..ionosphere import Ionosphere, faraday_rotation, polarization_rotation
from ..transmitters.satellite import Satellite
from .feed_rotation_tables import check_times, target_name

__all__ = ["faraday_table", "frequency_label"]


def frequency_label(frequency):
    """A short name of one frequency for column names: ``'1.4GHz'``, ``'150MHz'``.

    GHz from 1 GHz up, MHz from 1 MHz, kHz below; six significant digits.

    Parameters
    ----------
    frequency : `~astropy.units.Quantity`
        One frequency (or wavelength).

    Returns
    -------
    str

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.faraday_tables import frequency_label
    >>> frequency_label(1.4 * u.GHz), frequency_label(150e6 * u.Hz), frequency_label(21 * u.cm)
    ('1.4GHz', '150MHz', '1.42758GHz')
    """
    hertz = u.Quantity(frequency).to_value(u.Hz, equivalencies=u.spectral())
    for unit in (u.GHz, u.MHz, u.kHz):
        if hertz >= unit.to(u.Hz) or unit is u.kHz:
            return f"{hertz / unit.to(u.Hz):.6g}{unit}"


def _antennas(antennas):
    antennas = [antennas] if isinstance(antennas, Antenna) else list(antennas)
    if not antennas:
        raise ValueError("give at least one antenna")
    names = []
    for antenna in antennas:
        if not isinstance(antenna, Antenna):
            raise TypeError(f"antennas must be Antenna objects, got {type(antenna).__name__}")
        name = antenna.name or repr(antenna)
        if name in names:
            raise ValueError(f"antenna {name!r} is given twice; give each station once")
        names.append(name)
    return antennas, names


def _frequencies(frequency):
    if isinstance(frequency, (list, tuple)) and frequency and all(
            isinstance(f, u.Quantity) for f in frequency):
        frequency = u.Quantity(frequency)  # [1400 * u.MHz, 5 * u.GHz]
    if not isinstance(frequency, u.Quantity):
        raise TypeError(f"frequency must be a Quantity (e.g. [1.4, 5] * u.GHz), got "
                        f"{type(frequency).__name__}")
    frequencies = np.atleast_1d(frequency)
    if frequencies.ndim != 1:
        raise ValueError(f"frequency must be one value or a one-dimensional list, got shape "
                         f"{frequency.shape}")
    faraday_rotation(0 * u.rad / u.m**2, frequencies)  # the unit and value checks, once
    labels = [frequency_label(f) for f in frequencies]
    repeated = sorted({label for label in labels if labels.count(label) > 1})
    if repeated:
        raise ValueError(f"frequency {repeated[0]} is given twice; give each frequency once")
    return frequencies, labels


@iers_context()  # one check of the Earth-orientation tables per call
def faraday_table(antennas, target, obstime, ionosphere, frequency, min_elevation=0 * u.deg):
    """Rotation measure, Faraday rotation, feed rotation and their difference per station.

    Parameters
    ----------
    antennas : `~astropy_feedrot.Antenna` or sequence of them
        The stations, each once (by name).
    target : `~astropy.coordinates.SkyCoord`
        One natural source (the ionosphere's rotation measure is for the
        lines of sight to a direction on the sky, not to a satellite).
    obstime : `~astropy.time.Time`
        Strictly increasing epochs (one-dimensional).
    ionosphere : `~astropy_feedrot.ionosphere.Ionosphere`
        IONEX maps (`~astropy_feedrot.ionosphere.Ionosphere.from_ionex`) or a
        table of rotation measures
        (`~astropy_feedrot.ionosphere.Ionosphere.from_rm`, looked up under
        each antenna's ``name``).
    frequency : `~astropy.units.Quantity`
        One frequency or several (one-dimensional), or wavelengths.
    min_elevation : `~astropy.units.Quantity`, optional
        Every value but the elevation is NaN below this elevation: the
        horizon (0 deg) by default, where the line of sight leaves the
        ionosphere through the Earth; from 0 to 90 deg.

    Returns
    -------
    `~astropy.table.QTable`
        One row per epoch and station (by epoch, then in the order of
        ``antennas``), with columns ``time``, ``antenna``, ``elevation``
        (deg), ``rm`` (rad m^-2), ``chi_<frequency>`` for each frequency
        (e.g. ``chi_1.4GHz``: RM lambda^2 in deg, positive from north
        through east, not wrapped), ``feed_rotation`` (deg, wrapped to
        (-180, 180], RCP as in `~astropy_feedrot.Antenna.feed_rotation`) and
        ``psi_<frequency>`` (feed rotation minus chi, deg, not wrapped). The
        ``meta`` records the antennas, target, frequencies (``labels``
        too), elevation limit and the ionosphere (with the names of its
        IONEX files).

    Raises
    ------
    TypeError
        If an antenna is not an `~astropy_feedrot.Antenna`, ``target`` is a
        satellite or not a coordinate, ``ionosphere`` is not an
        `~astropy_feedrot.ionosphere.Ionosphere`, or ``frequency`` not a
        Quantity.
    ValueError
        If ``obstime`` is not one-dimensional and increasing, an antenna or a
        frequency is given twice, ``target`` holds several sources, or
        ``min_elevation`` lies outside [0, 90] deg.
    astropy.units.UnitsError
        If ``frequency`` is not spectral or ``min_elevation`` not an angle.
    ~astropy_feedrot.ionosphere.IonosphereError
        If an epoch lies outside the maps (or the table), or the table does
        not list an antenna.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.table import QTable
    >>> from astropy.time import Time
    >>> from astropy_feedrot.applied.faraday_tables import faraday_table
    >>> from astropy_feedrot.ionosphere import Ionosphere
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> rm = QTable({"time": Time(["2024-06-01T08:00", "2024-06-01T10:00"] * 2),
    ...              "rm": [1.0, 3.0, 0.5, 1.5] * u.rad / u.m**2,
    ...              "antenna": ["EFLSBERG"] * 2 + ["YEBES40M"] * 2})
    >>> times = Time("2024-06-01T08:00") + np.arange(3) * u.hour
    >>> table = faraday_table([get_antenna("EFLSBERG"), get_antenna("YEBES40M")],
    ...                       SkyCoord("03h19m48.16s +41d30m42.1s"), times,
    ...                       Ionosphere.from_rm(rm), [1.4, 5] * u.GHz)
    >>> table.colnames  # doctest: +NORMALIZE_WHITESPACE
    ['time', 'antenna', 'elevation', 'rm', 'chi_1.4GHz', 'chi_5GHz', 'feed_rotation',
     'psi_1.4GHz', 'psi_5GHz']
    >>> table["rm"]  # doctest: +FLOAT_CMP
    <Quantity [1. , 0.5, 2. , 1. , 3. , 1.5] rad / m2>
    >>> table["chi_1.4GHz"][:2]  # doctest: +FLOAT_CMP
    <Quantity [2.62728972, 1.31364486] deg>
    """
    antennas, names = _antennas(antennas)
    if isinstance(target, Satellite):
        raise TypeError("target must be a natural source (a SkyCoord): the rotation measure "
                        "is computed along lines of sight to a direction on the sky")
    target = as_skycoord(target)
    if not target.isscalar and target.size != 1:
        raise ValueError(f"a table follows one target, got a coordinate of shape "
                         f"{target.shape}; make one table per source")
    target = target.reshape(())
    if not isinstance(ionosphere, Ionosphere):
        raise TypeError(f"ionosphere must be an Ionosphere (Ionosphere.from_ionex or "
                        f"Ionosphere.from_rm), got {type(ionosphere).__name__}")
    frequencies, labels = _frequencies(frequency)
    min_elevation = 0 * u.deg if min_elevation is None else min_elevation
    limit = as_elevation_limit(min_elevation)
    if limit < 0:
        raise ValueError(f"min_elevation must be from 0 to 90 deg, got {min_elevation}: the "
                         "rotation measure is undefined below the horizon")
    times = check_times(obstime)
    # The feed rotation and elevation of each station: one line of sight each.
    angles = [antenna.angles(target, times, min_elevation=min_elevation)
              for antenna in antennas]
    elevation = np.stack([a.elevation.to_value(u.deg) for a in angles], axis=-1)
    phi = np.stack([a.total.to_value(u.deg) for a in angles], axis=-1) << u.deg
    # Every station's rotation measure in one call (epochs x stations).
    locations = EarthLocation.from_geocentric(
        *(u.Quantity([getattr(a.location, c) for a in antennas]) for c in "xyz"))
    with warnings.catch_warnings():
        # Below the horizon: NaN, and the elevation column says why.
        warnings.simplefilter("ignore", DegenerateGeometryWarning)
        rm = ionosphere.rotation_measure(locations, target, times, antenna=names)
    below = ~(elevation >= np.degrees(limit))
    rm[below] = np.nan
    phi[below] = np.nan
    chi = faraday_rotation(rm, frequencies)
    psi = polarization_rotation(phi, rm, frequencies)
    rows = elevation.size
    count = len(antennas)
    table = QTable({"time": times[np.repeat(np.arange(len(times)), count)],
                    "antenna": np.tile(np.array(names), len(times)),
                    "elevation": elevation.reshape(rows) << u.deg,
                    "rm": rm.reshape(rows)})
    for k, label in enumerate(labels):
        table[f"chi_{label}"] = u.Quantity(chi[..., k].reshape(rows), u.deg)
    table["feed_rotation"] = phi.reshape(rows)
    for k, label in enumerate(labels):
        table[f"psi_{label}"] = u.Quantity(psi[..., k].reshape(rows), u.deg)
    table.meta.update(antennas=names, target=target_name(target),
                      frequencies=[str(f) for f in frequencies], labels=labels,
                      min_elevation=str(u.Quantity(min_elevation)),
                      # Short values: FITS cards of 80 characters hold them (astropy 6
                      # refuses a longer HIERARCH card); the files by name.
                      ionosphere=(f"IONEX maps, shell at {ionosphere.height.to_value(u.km):g} km"
                                  if ionosphere.files else "a table of rotation measures"),
                      ionex=[os.path.basename(str(path)) for path in ionosphere.files])
    return table
