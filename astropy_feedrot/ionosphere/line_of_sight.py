# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rotation measure along one site's line of sight through a thin-shell ionosphere.

Everything physical comes from spinifex, in the steps of its own
``get_rm_from_skycoord``: the pierce point of the line of sight through a
shell at ``height`` above a spherical Earth of radius 6371 km and its slant
factor (``get_ipp_from_skycoord``), the vertical TEC of the IONEX maps there
(``interpolate_ionex``), and the IGRF field at the pierce point projected on
the line of sight (``magnetic_models.ppigrf``). Only the height differs from
spinifex's ``get_rm_from_skycoord``, which fixes it at 450 km for IONEX maps.

Sign: spinifex's line of sight points from the site to the source, and its
factor is negative, so a field pointing towards the observer gives a positive
RM, the astronomers' convention (a source of intrinsic angle chi0 is seen at
chi0 + RM lambda^2, angles from north through east).
"""

import numpy as np
from astropy import units as u

from .ionex import quiet_spinifex, spinifex_modules

__all__ = ["RM_PER_TECU_NANOTESLA", "rm_along_line_of_sight"]

__doctest_requires__ = {("rm_along_line_of_sight",): ["spinifex"]}

#: Rotation measure in rad m^-2 of 1 TECU (1e16 electrons m^-2) along a field of
#: 1 nT along the line of sight from the site to the source: spinifex's factor
#: (``spinifex.get_rm``), e^3 / (8 pi^2 eps0 m_e^2 c^3) = 2.63e-13 rad m^-2 per
#: (electron m^-2 T) rounded to 2.62e-6, negative because a field pointing away
#: from the observer gives a negative RM.
RM_PER_TECU_NANOTESLA = -2.62e-6


def rm_along_line_of_sight(maps, location, target, times, height):
    """Rotation measure and elevation along one site's lines of sight.

    Parameters
    ----------
    maps : `~astropy_feedrot.ionosphere.ionex.IonexMaps`
        The IONEX maps; every epoch must be covered (checked).
    location : `~astropy.coordinates.EarthLocation`
        One site (scalar).
    target : `~astropy.coordinates.SkyCoord`
        The source: scalar, or of the shape of ``times``.
    times : `~astropy.time.Time`
        Epochs, 1-D, UTC.
    height : `~astropy.units.Quantity`
        Height of the thin shell above the spherical Earth.

    Returns
    -------
    rm : `~numpy.ndarray`
        RM in rad m^-2, shape of ``times``; computed below the horizon too
        (the line continued through the Earth).
    elevation : `~numpy.ndarray`
        The target's elevation in radians (spinifex's AltAz, no refraction).

    Raises
    ------
    IonosphereError
        If some epochs lie outside the maps.

    Examples
    --------
    >>> import numpy as np, astropy.units as u
    >>> from astropy.coordinates import EarthLocation, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.ionosphere import sample_ionex
    >>> from astropy_feedrot.ionosphere.ionex import IonexMaps
    >>> from astropy_feedrot.ionosphere.line_of_sight import rm_along_line_of_sight
    >>> maps = IonexMaps(sample_ionex("codg*"))
    >>> wsrt = EarthLocation.from_geodetic(6.60 * u.deg, 52.91 * u.deg, 16 * u.m)
    >>> crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    >>> epochs = Time(["2020-01-08T22:00", "2020-01-09T10:00"])
    >>> rm, elevation = rm_along_line_of_sight(maps, wsrt, crab, epochs, 450 * u.km)
    >>> rm  # doctest: +FLOAT_CMP
    array([0.31617066, 0.27793539])
    >>> np.degrees(elevation)  # below the horizon at 10:00  # doctest: +FLOAT_CMP
    array([ 59.1128087 , -15.05805744])
    """
    sp = spinifex_modules()
    index = maps.file_index(times.mjd)
    with quiet_spinifex():
        ipp = sp.get_ipp_from_skycoord(loc=location, times=times, source=target,
                                       height_array=u.Quantity([height.to_value(u.km)], u.km))
        tec = maps.vertical_tec(ipp.lon.to_value(u.deg)[:, 0], ipp.lat.to_value(u.deg)[:, 0],
                                times, index)
        field = sp.magnetic_models.ppigrf(ipp=ipp).magnetic_field.to_value(u.nT)[:, 0]
    rm = RM_PER_TECU_NANOTESLA * tec * field * ipp.airmass[:, 0]
    return rm, np.asarray(ipp.altaz.alt.to_value(u.rad), dtype=float).reshape(rm.shape)
