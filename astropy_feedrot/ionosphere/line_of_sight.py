# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rotation measure along the lines of sight of sites through a thin-shell ionosphere.

The steps of spinifex's own ``get_rm_from_skycoord``, for every site and
epoch at once: the pierce point of each line of sight through a shell at
``height`` above a spherical Earth of radius 6371 km and its slant factor
(`~astropy_feedrot.ionosphere.pierce_points`, spinifex's geometry), the
vertical TEC of the IONEX maps there (spinifex's ``interpolate_ionex``), and
the IGRF field at the pierce point projected on the line of sight
(spinifex's ``magnetic_models.ppigrf``). spinifex takes one site per call and
reads the field model's coefficients anew in each; one call for the whole
network reads them once per day. Only the height differs from spinifex's
``get_rm_from_skycoord``, which fixes it at 450 km for IONEX maps.

Sign: spinifex's line of sight points from the site to the source, and its
factor is negative, so a field pointing towards the observer gives a positive
RM, the astronomers' convention (a source of intrinsic angle chi0 is seen at
chi0 + RM lambda^2, angles from north through east).
"""

import numpy as np
from astropy import units as u
from astropy.time import Time

from .ionex import quiet_spinifex, spinifex_modules
from .pierce_points import pierce_points

__all__ = ["RM_PER_TECU_NANOTESLA", "rm_along_lines_of_sight"]

__doctest_requires__ = {("rm_along_lines_of_sight",): ["spinifex"]}

#: Rotation measure in rad m^-2 of 1 TECU (1e16 electrons m^-2) along a field of
#: 1 nT along the line of sight from the site to the source: spinifex's factor
#: (``spinifex.get_rm``), e^3 / (8 pi^2 eps0 m_e^2 c^3) = 2.63e-13 rad m^-2 per
#: (electron m^-2 T) rounded to 2.62e-6, negative because a field pointing away
#: from the observer gives a negative RM.
RM_PER_TECU_NANOTESLA = -2.62e-6


def rm_along_lines_of_sight(maps, site_km, s, mjd, height):
    """Rotation measure along lines of sight from sites, at epochs.

    Parameters
    ----------
    maps : `~astropy_feedrot.ionosphere.ionex.IonexMaps`
        The IONEX maps; every epoch must be covered (checked).
    site_km : `~numpy.ndarray`, shape (..., 3)
        Geocentric ITRS positions of the sites in km.
    s : `~numpy.ndarray`, shape (..., 3)
        Apparent topocentric ITRS unit vectors from the sites towards the
        target (`~astropy_feedrot.earth.frames.source_direction`), broadcast
        with ``site_km``.
    mjd : `~numpy.ndarray`
        The epochs as UTC MJD, of the broadcast shape without the last axis.
    height : `~astropy.units.Quantity`
        Height of the thin shell above the spherical Earth.

    Returns
    -------
    `~numpy.ndarray`
        RM in rad m^-2, of the shape of ``mjd``; computed below the horizon
        too (the line continued through the Earth): callers mask those.

    Raises
    ------
    IonosphereError
        If some epochs lie outside the maps.

    Examples
    --------
    >>> import numpy as np, astropy.units as u
    >>> from astropy.coordinates import EarthLocation, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.frames import location_xyz, source_direction
    >>> from astropy_feedrot.ionosphere import sample_ionex
    >>> from astropy_feedrot.ionosphere.ionex import IonexMaps
    >>> from astropy_feedrot.ionosphere.line_of_sight import rm_along_lines_of_sight
    >>> maps = IonexMaps(sample_ionex("codg*"))
    >>> wsrt = EarthLocation.from_geodetic(6.60 * u.deg, 52.91 * u.deg, 16 * u.m)
    >>> epochs = Time(["2020-01-08T22:00", "2020-01-09T02:00"])
    >>> s = source_direction(SkyCoord("05h34m31.94s +22d00m52.2s"), wsrt, epochs)
    >>> rm_along_lines_of_sight(maps, location_xyz(wsrt) / 1e3, s, epochs.mjd,
    ...                         450 * u.km)  # doctest: +FLOAT_CMP
    array([0.31617066, 0.24714569])
    """
    sp = spinifex_modules()
    shape = np.shape(mjd)
    point = pierce_points(site_km, s, height.to_value(u.km))
    mjd = np.asarray(mjd, dtype=float).ravel()
    index = maps.file_index(mjd)
    times = Time(mjd, format="mjd", scale="utc")
    lon, lat = point.lon.ravel(), point.lat.ravel()
    # spinifex's pierce points, as its field model reads them (one shell: a last axis of 1)
    ipp = sp.IPP(lon=lon[:, np.newaxis] * u.deg, lat=lat[:, np.newaxis] * u.deg,
                 height=point.radius.reshape(-1, 1) * u.km, times=times,
                 los=np.broadcast_to(s, shape + (3,)).reshape(-1, 3),
                 airmass=point.slant.reshape(-1, 1), altaz=None, station_loc=None)
    with quiet_spinifex():
        tec = maps.vertical_tec(lon, lat, times, index)
        field = sp.magnetic_models.ppigrf(ipp=ipp).magnetic_field.to_value(u.nT)[:, 0]
    return (RM_PER_TECU_NANOTESLA * tec * field * point.slant.ravel()).reshape(shape)
