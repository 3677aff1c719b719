# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The diurnal aberration: geocentric apparent directions moved to sites.

What the apparent direction of a source fixed in a celestial frame owes to
the site is small: the diurnal aberration (the site's velocity
:math:`\\Omega\\,\\hat{z}\\times\\vec{r}`, at most 465 m/s, moves it by up to
0.32"), the parallax of the light deflection (below 1e-4 mas) and, for
sources with a distance, the parallax. So a network computes the geocentric
apparent directions once per epoch
(`~astropy_feedrot.earth.orientation.EarthOrientation.source_directions` with
no site) and each site adds its diurnal aberration:

.. math::

    \\hat{s}_\\mathrm{site} = \\hat{s}\\,(1 - k) + (1 - k_V/2)\\,\\vec{\\beta}
    + (k/2)\\,\\vec{V}, \\qquad k = \\hat{s}\\cdot\\vec{\\beta},\\;
    k_V = \\hat{s}\\cdot\\vec{V},\\;
    \\vec{\\beta} = \\Omega\\,(\\hat{z}\\times\\vec{r}_\\mathrm{site}) / c,

with :math:`\\vec{V}` the geocentre's barycentric velocity in units of c
(`~astropy_feedrot.earth.orientation.EarthOrientation.geocentre_velocity`): the change of
ERFA's relativistic aberration (``ab``) from :math:`\\vec{V}` to
:math:`\\vec{V} + \\vec{\\beta}`, to first order in :math:`\\beta` and
:math:`\\beta V` (the first order alone is off by up to 0.006 mas; this form
by 1e-4 mas, of unit length to 1e-12). The axis of :math:`\\Omega` is taken
as the Earth-fixed :math:`\\hat{z}` rather than the celestial pole (below
1e-12 rad).
"""

import erfa
import numpy as np
from astropy.coordinates import ICRS

from ..core.inputs import as_skycoord
from .orientation import distance_less, fast_path_applies, orientation_of
from .utc_days import OMEGA

__all__ = ["diurnal_beta", "topocentric", "network_directions", "network_applies"]


def diurnal_beta(xyz):
    """The velocity of a site from the Earth's rotation, in units of c, in ITRS.

    Parameters
    ----------
    xyz : array-like, shape (..., 3)
        Geocentric ITRS positions in metres.

    Returns
    -------
    ndarray, shape (..., 3)
        :math:`\\Omega\\,(\\hat{z}\\times\\vec{r}) / c`, with :math:`\\Omega`
        the rate of the Earth rotation angle (ERFA's value).

    Examples
    --------
    >>> from astropy_feedrot.earth.diurnal import diurnal_beta
    >>> beta = diurnal_beta([6378137.0, 0.0, 0.0])  # on the equator
    >>> float(beta[1] * 299792458.0)  # m/s  # doctest: +FLOAT_CMP
    465.1013911634
    """
    xyz = np.asarray(xyz, dtype=float)
    beta = np.zeros(xyz.shape)
    beta[..., 0] = -xyz[..., 1]
    beta[..., 1] = xyz[..., 0]
    return beta * (OMEGA / erfa.CMPS)


def topocentric(geocentric, xyz, velocity):
    """Geocentric apparent directions moved to a site by its diurnal aberration.

    Parameters
    ----------
    geocentric : ndarray, shape (..., 3)
        Apparent unit vectors seen from the geocentre, in ITRS.
    xyz : array-like, shape (..., 3)
        The site's geocentric ITRS position in metres (or several sites',
        broadcast with ``geocentric``).
    velocity : ndarray, shape (..., 3)
        The geocentre's barycentric velocity in ITRS, in units of c
        (broadcast with ``geocentric``).

    Returns
    -------
    ndarray, shape (..., 3)
        :math:`\\hat{s}(1 - k) + (1 - k_V/2)\\vec{\\beta} + (k/2)\\vec{V}`
        (see the module's description), normalized (its length is 1 to
        1e-12, which moves the elevation by microradians within an arcsecond
        of the zenith).

    Examples
    --------
    A source at the zenith of a site on the equator moves by its speed over
    c, 465 m/s (0.32"), towards the east:

    >>> import numpy as np
    >>> from astropy_feedrot.earth.diurnal import topocentric
    >>> s = topocentric(np.array([1.0, 0.0, 0.0]), [6378137.0, 0, 0], np.zeros(3))
    >>> float(np.degrees(s[1]) * 3600)  # arcsec  # doctest: +FLOAT_CMP
    0.32000134
    """
    beta = diurnal_beta(xyz)
    k = geocentric[..., 0] * beta[..., 0] + geocentric[..., 1] * beta[..., 1]  # no z
    g = 1.0 - 0.5 * np.einsum("...i,...i->...", geocentric, velocity)
    s = (geocentric * (1.0 - k)[..., np.newaxis] + g[..., np.newaxis] * beta
         + (0.5 * k)[..., np.newaxis] * velocity)
    s /= np.sqrt(np.einsum("...i,...i->...", s, s))[..., np.newaxis]  # 1e-12 from unit
    return s


def network_applies(target, obstime):
    """Whether `network_directions` serves a target at these epochs.

    Where the package's fast path serves them
    (`~astropy_feedrot.earth.orientation.fast_path_applies`: ``conf.fast_path``
    on, a frame fixed on the sky, no space motion) for one direction without
    distance (the network's directions are geocentric: no parallax). Else
    each site takes `~astropy_feedrot.earth.frames.source_direction`.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.diurnal import network_applies
    >>> t = Time(["2023-01-25T00:00", "2023-01-25T01:00"])
    >>> network_applies(SkyCoord("03h19m48s +41d30m42s"), t)
    True
    >>> network_applies(SkyCoord("03h19m48s +41d30m42s", distance=1 * u.pc), t)
    False
    """
    target = as_skycoord(target)
    return (target.isscalar and distance_less(target.data)
            and fast_path_applies(target, obstime))


def network_directions(target, xyz, obstime):
    """Apparent topocentric directions of one fixed target from many sites at once.

    Parameters
    ----------
    target : `~astropy.coordinates.SkyCoord`
        One direction fixed in a celestial frame, without distance or space
        motion (`network_applies`).
    xyz : `~numpy.ndarray`, shape (L, 3)
        Geocentric ITRS positions of the sites in metres.
    obstime : `~astropy.time.Time`
        The epochs, 1-D (T,).

    Returns
    -------
    `~numpy.ndarray`, shape (T, L, 3)
        Unit vectors from each site towards the target in ITRS: astropy's
        ``target.transform_to(ITRS(obstime=..., location=site))`` to 0.001
        mas (4e-4 mas measured at Effelsberg and Yebes), with the geocentric
        part computed once for every site.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import ITRS, EarthLocation, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.diurnal import network_directions
    >>> sites = EarthLocation.from_geodetic([6.88, -3.09] * u.deg, [50.52, 40.52] * u.deg)
    >>> crab = SkyCoord("05h34m31.94s +22d00m52.2s")
    >>> times = Time("2020-01-08T20:00") + np.arange(3) * u.h
    >>> xyz = np.stack([sites.x, sites.y, sites.z], axis=-1).to_value(u.m)
    >>> s = network_directions(crab, xyz, times)
    >>> s.shape
    (3, 2, 3)
    >>> astropy = crab.transform_to(ITRS(obstime=times, location=sites[1])).cartesian
    >>> mas = np.linalg.norm(s[:, 1] - astropy.xyz.value.T, axis=-1) * 206264806.2
    >>> bool(np.all(mas < 0.001))
    True
    """
    target = as_skycoord(target)
    orientation = orientation_of(obstime)
    icrs = target if isinstance(target.frame, ICRS) else target.icrs
    geocentric = orientation.source_directions(icrs, None).reshape(-1, 1, 3)
    velocity = orientation.geocentre_velocity().reshape(-1, 1, 3)
    return topocentric(geocentric, np.asarray(xyz, dtype=float), velocity)
