# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The satellite simulations of Section 4 of the paper, on embedded data.

`gps_short_baseline` is Sec. 4.1: GPS SVN 76 (Table 2 element set) over the
GNSS antenna DBR205 and the alt-az telescope FD-VLBA (Table 1), 73 m apart.
`genesis_long_baseline` is Sec. 4.2: a GENESIS-like orbit (circular, 6000 km,
inclination 97 deg, node 30 deg, LCP, nominal attitude) over the VGOS
telescopes GGAO12M and WETTZ13S (Table 3).
"""

import numpy as np
from astropy import units as u
from astropy.time import Time

from ..stations.catalogue import get_antenna
from ..transmitters.orbits import TLEOrbit
from ..transmitters.satellite import Satellite
from .feed_rotation_tables import baseline_table

__all__ = [
    "GPS_SVN76_TLE",
    "PAPER_ANTENNAS",
    "paper_antenna",
    "gps_svn76",
    "genesis",
    "gps_short_baseline",
    "genesis_long_baseline",
]

#: Table 2 of the paper: the element set of GPS SVN 76 for 2023-01-25.
GPS_SVN76_TLE = (
    "1 41328U 16007A   23024.39332179  .00000015  00000-0  00000+0 0  9995",
    "2 41328  54.9577 138.7050 0066950 231.2234 128.1638  2.00560135 51012",
)

#: The antennas of Tables 1 and 3 of the paper (entries of the station catalogue).
PAPER_ANTENNAS = ("DBR205", "FD-VLBA", "GGAO12M", "WETTZ13S")

#: The date of both simulations.
DATE = Time("2023-01-25T00:00:00", scale="utc")


def paper_antenna(name):
    """One of the antennas of Tables 1 and 3.

    Parameters
    ----------
    name : {'DBR205', 'FD-VLBA', 'GGAO12M', 'WETTZ13S'}

    Returns
    -------
    `~astropy_feedrot.Antenna`

    Raises
    ------
    ValueError
        For another name (listing these).

    Examples
    --------
    >>> from astropy_feedrot.applied.simulations import paper_antenna
    >>> paper_antenna("DBR205").mount
    StationaryMount()
    """
    if name not in PAPER_ANTENNAS:
        raise ValueError(f"name must be one of {', '.join(PAPER_ANTENNAS)}, got {name!r}")
    return get_antenna(name)


def gps_svn76():
    """GPS SVN 76 from the Table 2 element set, nominal attitude, RCP.

    Returns
    -------
    `~astropy_feedrot.Satellite`

    Examples
    --------
    >>> from astropy_feedrot.applied.simulations import gps_svn76
    >>> gps_svn76().polarization
    'RCP'
    """
    return Satellite(TLEOrbit(*GPS_SVN76_TLE, name="GPS SVN 76"), name="GPS SVN 76")


def genesis():
    """The GENESIS-like satellite of Sec. 4.2 (nominal attitude, LCP).

    Returns
    -------
    `~astropy_feedrot.Satellite`

    Examples
    --------
    >>> from astropy_feedrot.applied.simulations import genesis
    >>> genesis().polarization
    'LCP'
    """
    orbit = TLEOrbit.from_elements(DATE, inclination=97 * u.deg, raan=30 * u.deg,
                                   altitude=6000 * u.km, name="GENESIS")
    return Satellite(orbit, polarization="LCP", name="GENESIS")


def _baseline_table(antenna1, antenna2, satellite, times, frequency, min_elevation):
    table = baseline_table(antenna1, antenna2, satellite, times, frequency,
                           min_elevation=min_elevation)
    table.meta["satellite"] = satellite.name
    return table


def gps_short_baseline(step=60 * u.s, min_elevation=10 * u.deg):
    """Sec. 4.1: GPS SVN 76 over DBR205 (GNSS) and FD-VLBA (alt-az), L1.

    Parameters
    ----------
    step : `~astropy.units.Quantity`, optional
        Sampling interval over 06:00-17:00 UTC on 2023-01-25.
    min_elevation : `~astropy.units.Quantity`, optional
        Elevation limit for the continuous series and the delay.

    Returns
    -------
    `~astropy.table.Table`
        Per epoch and antenna: azimuth, elevation, transmitter and receiver
        terms (Eqs 21, 22), total feed rotation (wrapped and continuous),
        and the rotation delay FD-VLBA minus DBR205 at 1575.42 MHz (NaN when
        the satellite is below the limit at either antenna).

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.simulations import gps_short_baseline
    >>> table = gps_short_baseline(step=10 * u.min)
    >>> table.meta["ambiguity"]
    '634.7513678891978 ps'
    """
    times = DATE + 6 * u.hour + np.arange(0, (11 * u.hour / step).decompose().value + 1) * step
    return _baseline_table(paper_antenna("DBR205"), paper_antenna("FD-VLBA"), gps_svn76(),
                           times, 1575.42 * u.MHz, min_elevation)


def genesis_long_baseline(step=60 * u.s, min_elevation=10 * u.deg, frequency=8.4 * u.GHz):
    """Sec. 4.2: the GENESIS-like satellite over GGAO12M and WETTZ13S (LCP).

    Parameters
    ----------
    step : `~astropy.units.Quantity`, optional
        Sampling interval over the whole of 2023-01-25.
    min_elevation : `~astropy.units.Quantity`, optional
        Elevation limit for the continuous series and the delay.
    frequency : `~astropy.units.Quantity`, optional
        Frequency of the rotation delay (X band by default).

    Returns
    -------
    `~astropy.table.Table`
        As `gps_short_baseline`, WETTZ13S minus GGAO12M.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.simulations import genesis_long_baseline
    >>> table = genesis_long_baseline(step=10 * u.min)
    >>> int(table["both_visible"].sum()) > 0
    True
    """
    times = DATE + np.arange(0, (1 * u.day / step).decompose().value) * step
    return _baseline_table(paper_antenna("GGAO12M"), paper_antenna("WETTZ13S"), genesis(),
                           times, frequency, min_elevation)
