# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Satellite orbits: Earth-fixed (ITRS) positions at any time.

Three sources of positions: a two-line element set propagated with SGP4
(`TLEOrbit`), an IGS SP3 precise-orbit file interpolated with sliding-window
Lagrange polynomials (`SP3Orbit`), and positions the user already has as a
`~astropy.coordinates.SkyCoord` (`CoordinateOrbit`).

Every orbit gives its positions one orbit at a time (`Orbit.position`) or many
orbits together (`Orbit.positions`: one SGP4 call for all element sets); both
take an optional `~astropy_feedrot.earth.orientation.EarthOrientation` of the epochs, so
that several consumers of the same epochs share one.
"""

import numpy as np
from astropy import units as u
from astropy.coordinates import ITRS, SkyCoord

from ..earth.eop import iers_context
from ..earth.frames import as_time, location_xyz
from .orbit_interface import Orbit, check_orientation
from .sp3_orbit import SP3Orbit, lagrange_interpolate
from .tle_orbit import TLEOrbit, propagate_tles, teme_to_itrs

__all__ = ["Orbit", "TLEOrbit", "SP3Orbit", "CoordinateOrbit", "as_orbit", "propagate_tles",
           "check_orientation", "lagrange_interpolate", "teme_to_itrs"]


class CoordinateOrbit(Orbit):
    """Positions the user already has, as a `~astropy.coordinates.SkyCoord`.

    Parameters
    ----------
    coord : `~astropy.coordinates.SkyCoord`
        Satellite position(s) with a distance, in any frame astropy can
        transform to ITRS. Positions in ITRS are used as they are; those in
        other frames are transformed to ITRS at the requested times (their
        shape must broadcast with them).

    Raises
    ------
    TypeError
        If ``coord`` is not a coordinate.
    ValueError
        If ``coord`` has no distance.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import ITRS, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot import CoordinateOrbit
    >>> where = SkyCoord(ITRS(x=2.6e7 * u.m, y=0 * u.m, z=0 * u.m,
    ...                       representation_type="cartesian"))
    >>> CoordinateOrbit(where).position(Time("2023-01-25"))  # doctest: +FLOAT_CMP
    array([26000000.,        0.,        0.])
    """

    def __init__(self, coord):
        if not isinstance(coord, SkyCoord):
            raise TypeError(f"coord must be a SkyCoord, got {type(coord).__name__}")
        if coord.cartesian.x.unit.physical_type != "length":
            raise ValueError(
                "a satellite position needs a distance; this SkyCoord is a direction only"
            )
        self.coord = coord

    def __repr__(self):
        return f"<CoordinateOrbit shape={self.coord.shape} frame={self.coord.frame.name}>"

    def position(self, obstime, orientation=None):
        # Positions in celestial frames go through astropy's transformation at
        # each epoch (exact, whatever the frame): no interpolated orientation.
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        coord = self.coord
        if not isinstance(coord.frame, ITRS):
            with iers_context(obstime):
                coord = coord.transform_to(ITRS(obstime=obstime))
        xyz = np.moveaxis(coord.cartesian.xyz.to_value(u.m), 0, -1)
        if coord.frame.location is not None:
            xyz = xyz + location_xyz(coord.frame.location)
        shape = np.broadcast_shapes(xyz.shape[:-1], obstime.shape)
        return np.broadcast_to(xyz, shape + (3,))


def as_orbit(orbit):
    """Coerce an orbit-like object to an `Orbit`.

    Parameters
    ----------
    orbit : `Orbit` or `~astropy.coordinates.SkyCoord`
        An orbit, or satellite positions with a distance.

    Returns
    -------
    `Orbit`

    Raises
    ------
    TypeError
        For anything else.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import ITRS, SkyCoord
    >>> from astropy_feedrot.transmitters.orbits import as_orbit
    >>> as_orbit(SkyCoord(ITRS(x=2.6e7 * u.m, y=0 * u.m, z=0 * u.m,
    ...                        representation_type="cartesian")))
    <CoordinateOrbit shape=() frame=itrs>
    """
    if isinstance(orbit, Orbit):
        return orbit
    if isinstance(orbit, SkyCoord):
        return CoordinateOrbit(orbit)
    raise TypeError(
        f"orbit must be a TLEOrbit, SP3Orbit, CoordinateOrbit or a SkyCoord with a "
        f"distance, got {type(orbit).__name__}"
    )
