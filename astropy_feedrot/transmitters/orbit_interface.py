# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The interface of satellite orbits: Earth-fixed positions as a function of time.

`Orbit` is what every source of positions implements (`~astropy_feedrot.transmitters.orbits`
lists them); `check_orientation` checks an Earth orientation handed to one.
"""

import numpy as np

from ..earth.frames import as_time
from ..earth.orientation import EarthOrientation

__all__ = ["Orbit", "check_orientation"]


class Orbit:
    """Base class of orbits: Earth-fixed positions as a function of time.

    A subclass implements `position`. Orbits that are cheaper computed
    together (element sets: one SGP4 call) also implement the class method
    `batch_positions`, which `positions` calls once per class with all the
    orbits of that class.

    Attributes
    ----------
    uses_orientation : bool
        Whether `position` uses an `~astropy_feedrot.earth.orientation.EarthOrientation`
        when given one (class attribute: False here, True for `TLEOrbit`).
        Callers build one for their epochs only when some orbit (or attitude)
        will use it.
    coverage : tuple of `~astropy.time.Time` or None
        ``(start, stop)`` outside which `position` cannot give positions (an
        orbit file's span); None (here) where there is no such limit.

    Examples
    --------
    >>> from astropy_feedrot import CoordinateOrbit, SP3Orbit, TLEOrbit
    >>> from astropy_feedrot.transmitters.orbits import Orbit
    >>> all(issubclass(c, Orbit) for c in (TLEOrbit, SP3Orbit, CoordinateOrbit))
    True
    >>> TLEOrbit.uses_orientation, CoordinateOrbit.coverage
    (True, None)
    """

    uses_orientation = False
    coverage = None

    def position(self, obstime, orientation=None):
        """Geocentric ITRS position(s), in metres.

        Parameters
        ----------
        obstime : `~astropy.time.Time`
            Epoch(s).
        orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`, optional
            Earth orientation at exactly these epochs (same shape), shared
            with other computations at the same epochs; orbits that need no
            Earth rotation ignore it. By default the orbit makes its own when
            it needs one.

        Returns
        -------
        ndarray, shape obstime.shape + (3,)
            Cartesian ITRS coordinates in metres; NaN where the orbit cannot
            give a position.

        Examples
        --------
        GPS SVN 76 (the paper's Table 2) is some 26,600 km from the geocentre:

        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import TLEOrbit
        >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
        >>> xyz = TLEOrbit(*GPS_SVN76_TLE).position(Time("2023-01-25T12:00") + [0, 1] * u.h)
        >>> xyz.shape, bool(np.all(np.abs(np.linalg.norm(xyz, axis=-1) - 2.66e7) < 2e5))
        ((2, 3), True)
        """
        raise NotImplementedError  # pragma: no cover

    @classmethod
    def batch_positions(cls, orbits, obstime, orientation=None):
        """Positions of several orbits of this class at the same epochs.

        The default calls `position` for each orbit; a class whose orbits are
        cheaper together overrides it.

        Parameters
        ----------
        orbits : list of `Orbit`
            Orbits of this class.
        obstime : `~astropy.time.Time`
            Epochs, any shape.
        orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`, optional
            As for `position`.

        Returns
        -------
        ndarray, shape (len(orbits),) + obstime.shape + (3,)
            ITRS metres.

        Raises
        ------
        ValueError
            If an orbit does not give one position per epoch.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import ITRS, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import CoordinateOrbit
        >>> here = CoordinateOrbit(SkyCoord(ITRS(x=2.6e7 * u.m, y=0 * u.m, z=0 * u.m,
        ...                                      representation_type="cartesian")))
        >>> times = Time("2023-01-25") + [0, 1] * u.hour
        >>> CoordinateOrbit.batch_positions([here, here], times).shape
        (2, 2, 3)
        """
        out = np.empty((len(orbits),) + obstime.shape + (3,))
        for i, orbit in enumerate(orbits):
            xyz = np.asarray(orbit.position(obstime, orientation), dtype=float)
            if xyz.shape != obstime.shape + (3,):
                raise ValueError(
                    f"{orbit!r} gives positions of shape {xyz.shape} for obstime of shape "
                    f"{obstime.shape}; a batch of orbits needs one position per epoch")
            out[i] = xyz
        return out

    @staticmethod
    def positions(orbits, obstime, orientation=None):
        """Positions of many orbits at the same epochs, each class in one batch.

        Parameters
        ----------
        orbits : sequence of `Orbit`
            Orbits of any classes: element sets are propagated together (one
            SGP4 call), the others one by one.
        obstime : `~astropy.time.Time`
            Epochs, any shape.
        orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`, optional
            Earth orientation at exactly these epochs, shared by every orbit
            that needs one (element sets: the rotation from TEME to ITRS). By
            default each class makes its own when it needs one.

        Returns
        -------
        ndarray, shape (len(orbits),) + obstime.shape + (3,)
            Geocentric ITRS positions in metres; NaN where an orbit cannot
            give one (with that orbit's warning, once per class).

        Raises
        ------
        TypeError
            If an item is not an `Orbit`.
        ValueError
            If ``orientation`` is not for these epochs, or an orbit does not
            give one position per epoch (a `CoordinateOrbit` of several
            positions at one time, for instance).

        Examples
        --------
        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import TLEOrbit
        >>> from astropy_feedrot.transmitters.orbits import Orbit
        >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
        >>> gps = TLEOrbit(*GPS_SVN76_TLE)
        >>> genesis = TLEOrbit.from_elements(Time("2023-01-25"), inclination=97 * u.deg,
        ...                                  raan=30 * u.deg, altitude=6000 * u.km)
        >>> times = Time("2023-01-25") + np.arange(0, 3600, 60) * u.s
        >>> xyz = Orbit.positions([gps, genesis], times)
        >>> xyz.shape
        (2, 60, 3)
        >>> np.round(np.linalg.norm(xyz[:, 0], axis=-1) / 1e6, 1)  # thousands of km
        array([26.7, 12.4])
        """
        orbits = list(orbits)
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        kinds = {}
        for i, orbit in enumerate(orbits):
            if not isinstance(orbit, Orbit):
                raise TypeError(f"orbits[{i}] must be an Orbit, got {type(orbit).__name__}")
            kinds.setdefault(type(orbit), []).append(i)
        shape = (len(orbits),) + obstime.shape + (3,)
        if len(kinds) == 1:  # one class: its batch is the answer, without a copy
            (kind,) = kinds
            out = np.asarray(kind.batch_positions(orbits, obstime, orientation), dtype=float)
            if out.shape != shape:
                raise ValueError(f"{kind.__name__}.batch_positions gives shape {out.shape} "
                                 f"for {len(orbits)} orbits at epochs of shape "
                                 f"{obstime.shape}; it must give {shape}")
            return out
        out = np.empty(shape)
        for kind, members in kinds.items():
            out[members] = kind.batch_positions([orbits[i] for i in members], obstime,
                                                orientation)
        return out


def check_orientation(orientation, obstime):
    """Check that an Earth orientation is one for the given epochs.

    Parameters
    ----------
    orientation : `~astropy_feedrot.earth.orientation.EarthOrientation` or None
        None passes.
    obstime : `~astropy.time.Time`
        The epochs it must describe.

    Raises
    ------
    TypeError
        If ``orientation`` is neither None nor an
        `~astropy_feedrot.earth.orientation.EarthOrientation`.
    ValueError
        If its epochs have another shape than ``obstime``.

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.orientation import EarthOrientation
    >>> from astropy_feedrot.transmitters.orbits import check_orientation
    >>> times = Time(["2023-01-25T00:00", "2023-01-25T06:00"])
    >>> check_orientation(EarthOrientation(times), times)
    """
    if orientation is None:
        return
    if not isinstance(orientation, EarthOrientation):
        raise TypeError(f"orientation must be an EarthOrientation or None, got "
                        f"{type(orientation).__name__}")
    if orientation.shape != obstime.shape:
        raise ValueError(f"orientation is for epochs of shape {orientation.shape}, obstime has "
                         f"shape {obstime.shape}: build the EarthOrientation from these epochs")
