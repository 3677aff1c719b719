# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""An independent wind-up for the GNSS tests: Wu et al. (1993) as written in the IGS literature.

Nothing of astropy_feedrot's geometry is used: the geometric Sun from
ERFA's ``epv00`` (astropy's ``get_body_barycentric``, Sun minus Earth, the
ephemeris the package uses too: the apparent Sun, 20.8" away, moves the
wind-up near noon turns by up to 0.1 deg) rotated from GCRS to ITRS by
astropy, the nominal yaw-steering axes of Kouba (2009, GPS Solutions 13,
1-12, eqs 1-3), the local east and north from the geodetic latitude and
longitude, and Wu's formula with the receiver dipoles east (x) and north (y):

    D_s = x_s - k (k . x_s) - k x y_s,    D_r = x_r - k (k . x_r) + k x y_r,
    dphi = sign(k . (D_s x D_r)) arccos(D_s . D_r / |D_s| |D_r|),

with k the unit vector from the satellite to the receiver.
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import GCRS, ITRS, CartesianRepresentation, EarthLocation
from astropy.coordinates import get_body_barycentric


def sun_itrs(times):
    geocentric = (get_body_barycentric("sun", times, ephemeris="builtin")
                  - get_body_barycentric("earth", times, ephemeris="builtin"))
    sun = GCRS(CartesianRepresentation(geocentric.xyz), obstime=times).transform_to(
        ITRS(obstime=times))
    return np.moveaxis(sun.cartesian.xyz.to_value(u.m), 0, -1)


def nominal_axes(position, sun):
    z = -position / np.linalg.norm(position, axis=-1, keepdims=True)
    e = sun - position
    e /= np.linalg.norm(e, axis=-1, keepdims=True)
    y = np.cross(z, e)
    y /= np.linalg.norm(y, axis=-1, keepdims=True)
    x = np.cross(y, z)
    return x, y


def receiver_dipoles(xyz, zero_direction=0.0):
    location = EarthLocation.from_geocentric(*xyz, unit=u.m)
    lat = location.geodetic.lat.to_value(u.rad)
    lon = location.geodetic.lon.to_value(u.rad)
    east = np.array([-np.sin(lon), np.cos(lon), 0.0])
    north = np.array([-np.sin(lat) * np.cos(lon), -np.sin(lat) * np.sin(lon), np.cos(lat)])
    a = np.radians(zero_direction)
    return np.cos(a) * east - np.sin(a) * north, np.cos(a) * north + np.sin(a) * east


def wu_windup(receiver, position, x_s, y_s, x_r, y_r):
    """Wu's wind-up in radians for satellites at ``position`` (..., 3)."""
    k = receiver - position
    k /= np.linalg.norm(k, axis=-1, keepdims=True)

    def dot(a, b):
        return np.sum(a * b, axis=-1, keepdims=True)

    d_s = x_s - k * dot(k, x_s) - np.cross(k, y_s)
    d_r = x_r - k * dot(k, x_r) + np.cross(k, y_r)
    cos = dot(d_s, d_r)[..., 0] / (np.linalg.norm(d_s, axis=-1) * np.linalg.norm(d_r, axis=-1))
    sign = np.sign(dot(k, np.cross(d_s, d_r))[..., 0])
    return sign * np.arccos(np.clip(cos, -1, 1))
