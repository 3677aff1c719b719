# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Where lines of sight pierce a thin ionospheric shell: pure numpy, every site at once.

The shell is a sphere of radius ``EARTH_RADIUS + height`` about the
geocentre, the model spinifex uses for IONEX maps (its ``get_ipp_from_itrs``
with a spherical Earth of 6371 km). A line of sight from the site ``r``
along the unit vector ``s`` meets it at ``r + alpha s`` with
``alpha = -r.s + sqrt((r.s)^2 - |r|^2 + (R + h)^2)``; its slant factor, the
ratio of the slant path through a thin layer to the vertical one, is
``(R + h) / (p.s)`` at the pierce point ``p``. Latitude and longitude are
spherical (geocentric), as the IONEX maps' grid is read there.

spinifex computes this for one site per call; here sites and epochs are
arrays, so that a network's pierce points take one pass (tested equal to
spinifex's to 1e-9 relative).
"""

from typing import NamedTuple

import numpy as np

from ..core.kernel import dot

__all__ = ["EARTH_RADIUS_KM", "PiercePoints", "pierce_points"]

#: Radius (km) of the spherical Earth under the shell: spinifex's ``R_EARTH_MEAN_KM``.
EARTH_RADIUS_KM = 6371.0


class PiercePoints(NamedTuple):
    """Pierce points of lines of sight through a thin shell (arrays of one shape).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.ionosphere.pierce_points import pierce_points
    >>> point = pierce_points(np.array([0, 6371.0, 0]), np.array([0, 1.0, 0]), 450.0)
    >>> point._fields
    ('lon', 'lat', 'radius', 'slant')
    >>> float(point.lon), float(point.radius)
    (90.0, 6821.0)
    """

    #: Geocentric longitude in degrees, from -180 to 180.
    lon: np.ndarray
    #: Geocentric (spherical) latitude in degrees.
    lat: np.ndarray
    #: Distance from the geocentre in km (the shell's radius).
    radius: np.ndarray
    #: Slant factor: slant over vertical path through the shell.
    slant: np.ndarray


def pierce_points(site_km, s, height_km):
    """Pierce points of lines of sight through a spherical shell about the geocentre.

    Parameters
    ----------
    site_km : `~numpy.ndarray`, shape (..., 3)
        Geocentric ITRS positions of the sites in km.
    s : `~numpy.ndarray`, shape (..., 3)
        Unit vectors from the sites towards the target (broadcast with
        ``site_km``), in ITRS.
    height_km : float
        Height of the shell above the spherical Earth (`EARTH_RADIUS_KM`).

    Returns
    -------
    PiercePoints
        Of the broadcast shape without the last axis. A line of sight into
        the ground (the target below the horizon) still meets the shell, on
        the far side of the Earth; callers mask those epochs.

    Examples
    --------
    Straight up from a site on the equator at 0 deg longitude, the pierce
    point is above the site, and the slant factor is 1:

    >>> import numpy as np
    >>> from astropy_feedrot.ionosphere.pierce_points import pierce_points
    >>> p = pierce_points(np.array([6371.0, 0, 0]), np.array([1.0, 0, 0]), 450.0)
    >>> float(p.lon), float(p.lat), float(p.radius), float(p.slant)
    (0.0, 0.0, 6821.0, 1.0)

    At 30 deg elevation the slant factor is the secant of the zenith angle at
    the shell, where sin z' = R cos(30 deg) / (R + h), less than 1 / sin(30 deg):

    >>> s = np.array([np.sin(np.radians(30)), np.cos(np.radians(30)), 0.0])
    >>> slant = pierce_points(np.array([6371.0, 0, 0]), s, 450.0).slant
    >>> sin_z = 6371.0 * np.cos(np.radians(30)) / 6821.0
    >>> bool(np.isclose(slant, 1 / np.sqrt(1 - sin_z**2), rtol=1e-12)), round(float(slant), 4)
    (True, 1.7008)
    """
    site_km, s = np.broadcast_arrays(np.asarray(site_km, float), np.asarray(s, float))
    shell = EARTH_RADIUS_KM + float(height_km)
    b = dot(site_km, s)
    alpha = -b + np.sqrt(b * b - (dot(site_km, site_km) - shell * shell))
    point = site_km + alpha[..., np.newaxis] * s
    x, y, z = np.moveaxis(point, -1, 0)
    radius = np.sqrt(x * x + y * y + z * z)
    lat = np.degrees(np.arcsin(np.clip(z / radius, -1.0, 1.0)))
    return PiercePoints(np.degrees(np.arctan2(y, x)), lat, radius, shell / dot(point, s))
