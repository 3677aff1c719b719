# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The interface of transmitter attitudes, and the Sun they may need.

`Attitude` is what every attitude model implements: the satellite antenna's
dipoles in the Earth-fixed frame, one satellite or many at a time
(`Attitude.dipoles_many`, which gives the models that follow the Sun one Sun
from the epochs' Earth orientation).
"""

import numpy as np

from ..core.exceptions import DegenerateGeometryWarning, warn_caller
from ..earth.epochs import Epochs
from ..earth.frames import as_time
from .orbits import check_orientation

__all__ = ["Attitude", "sun_at", "sun_position", "interpolated_sun_position",
           "warn_undefined_count"]


class Attitude:
    """Base class of transmitter attitude models.

    A model implements `dipoles`. A model whose dipoles follow from the
    satellite's position and the Sun's alone (as `NominalAttitude`) sets
    `needs_sun` and implements `sun_dipoles`: drivers of many satellites
    (`dipoles_many`) then compute the Sun once for all of them.

    Attributes
    ----------
    needs_sun : bool
        Whether `sun_dipoles` gives the dipoles (False here).

    Examples
    --------
    >>> from astropy_feedrot import NominalAttitude, QuaternionAttitude
    >>> from astropy_feedrot.transmitters.attitude_interface import Attitude
    >>> issubclass(NominalAttitude, Attitude), issubclass(QuaternionAttitude, Attitude)
    (True, True)
    >>> NominalAttitude.needs_sun, Attitude.needs_sun
    (True, False)
    """

    needs_sun = False

    def dipoles(self, obstime, position, orientation=None):
        """Aligned and transverse dipole unit vectors of the transmitter in ITRS.

        Parameters
        ----------
        obstime : `~astropy.time.Time`
            Epoch(s).
        position : ndarray, shape (..., 3)
            Geocentric ITRS position(s) of the satellite in metres.
        orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`, optional
            Earth orientation at exactly these epochs (same shape), shared
            with other computations at the same epochs; models that need no
            Earth orientation ignore it.

        Returns
        -------
        aligned, transverse : ndarray, shape (..., 3)
            :math:`\\hat{t}^a` and :math:`\\hat{t}^t`; NaN where undefined.

        Examples
        --------
        A model's dipoles are orthogonal unit vectors (here the nominal
        attitude of a satellite 26,000 km from the geocentre):

        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot import NominalAttitude
        >>> aligned, transverse = NominalAttitude().dipoles(Time("2023-01-25"),
        ...                                                 np.array([2.6e7, 0.0, 0.0]))
        >>> bool(np.isclose(aligned @ aligned, 1) and abs(aligned @ transverse) < 1e-12)
        True
        """
        raise NotImplementedError  # pragma: no cover

    def sun_dipoles(self, position, sun):
        """Dipoles from the satellite's and the Sun's positions (models with `needs_sun`).

        Parameters
        ----------
        position : ndarray, shape (..., 3)
            Geocentric ITRS positions of the satellite in metres.
        sun : ndarray, shape (..., 3)
            Geocentric ITRS positions of the Sun in metres, broadcastable with
            ``position``.

        Returns
        -------
        aligned, transverse : ndarray, shape (..., 3)
            NaN, without a warning, where undefined (callers warn once).

        Raises
        ------
        NotImplementedError
            For models without `needs_sun`.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot import NominalAttitude
        >>> aligned, transverse = NominalAttitude().sun_dipoles(
        ...     np.array([2.6e7, 0.0, 0.0]), np.array([0.0, 1.5e11, 0.0]))
        >>> aligned.shape, bool(abs(aligned @ transverse) < 1e-12)
        ((3,), True)
        """
        raise NotImplementedError(f"{type(self).__name__} does not take its dipoles from the "
                                  "Sun (needs_sun is False); call dipoles()")

    @staticmethod
    def dipoles_many(attitudes, obstime, positions, orientation=None):
        """Dipoles of many satellites at the same epochs, with one Sun for all.

        Parameters
        ----------
        attitudes : sequence of `Attitude`
            One model per satellite (S of them).
        obstime : `~astropy.time.Time`
            The epochs.
        positions : array-like, shape (S,) + obstime.shape + (3,)
            Geocentric ITRS positions of the satellites in metres (each
            ``positions[i]`` may be any shape that broadcasts with
            ``obstime.shape + (3,)``).
        orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`, optional
            Earth orientation at exactly these epochs: the Sun of the models
            with `needs_sun` is then interpolated from its nodes
            (`interpolated_sun_position`, within 1e-10 rad of the exact
            Sun) rather than computed exactly at every epoch (`sun_position`).

        Returns
        -------
        aligned, transverse : ndarray, shape of ``positions``
            Unit vectors; NaN where undefined.

        Raises
        ------
        TypeError
            If an item is not an `Attitude`, or ``orientation`` is not an
            `~astropy_feedrot.earth.orientation.EarthOrientation`.
        ValueError
            If ``positions`` does not hold one array per attitude, or
            ``orientation`` is not for these epochs.

        Warns
        -----
        `~astropy_feedrot.DegenerateGeometryWarning`
            Once for all models with `needs_sun`, with the count of epochs
            where the Sun, a satellite and the geocentre are aligned; other
            models warn as their `dipoles` does.

        Notes
        -----
        Models with `needs_sun` are called as ``sun_dipoles(positions[i],
        sun)``, the others as ``dipoles(obstime, positions[i])``.

        Examples
        --------
        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import NominalAttitude, TLEOrbit
        >>> from astropy_feedrot.transmitters.attitude_interface import Attitude
        >>> from astropy_feedrot.earth.orientation import EarthOrientation
        >>> from astropy_feedrot.transmitters.orbits import Orbit
        >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
        >>> times = Time("2023-01-25") + np.arange(0, 3600, 60) * u.s
        >>> orientation = EarthOrientation(times)
        >>> orbits = [TLEOrbit(*GPS_SVN76_TLE)] * 2
        >>> positions = Orbit.positions(orbits, times, orientation)
        >>> aligned, transverse = Attitude.dipoles_many(
        ...     [NominalAttitude(), NominalAttitude()], times, positions, orientation)
        >>> aligned.shape
        (2, 60, 3)
        >>> bool(np.allclose(np.sum(aligned * transverse, axis=-1), 0))
        True
        """
        attitudes = list(attitudes)
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        for i, attitude in enumerate(attitudes):
            if not isinstance(attitude, Attitude):
                raise TypeError(f"attitudes[{i}] must be an Attitude, got "
                                f"{type(attitude).__name__}")
        positions = np.asarray(positions, dtype=float)
        if positions.ndim < 2 or len(positions) != len(attitudes):
            raise ValueError(f"positions must hold one array per attitude: shape "
                             f"({len(attitudes)}, ..., 3), got {positions.shape}")
        aligned = np.empty_like(positions)
        transverse = np.empty_like(positions)
        sunny = [i for i, attitude in enumerate(attitudes) if attitude.needs_sun]
        for i, attitude in enumerate(attitudes):
            if not attitude.needs_sun:
                aligned[i], transverse[i] = attitude.dipoles(obstime, positions[i])
        if not sunny:
            return aligned, transverse
        sun = sun_at(obstime, orientation)
        if positions.shape[1:] == sun.shape:
            # Blocks of epochs, all satellites in each: the positions, the Sun and
            # the dipoles of a block stay in the cache whatever the memory layout.
            sun = sun.reshape(-1, 3)
            flat = [a.reshape(len(attitudes), -1, 3) for a in (positions, aligned, transverse)]
            blocks = [slice(a, a + _EPOCHS) for a in range(0, len(sun), _EPOCHS)]
        else:  # positions[i] broadcast with the epochs: one call per satellite
            flat = (positions, aligned, transverse)
            blocks = [Ellipsis]
        where, a_out, t_out = flat
        for block in blocks:
            for i in sunny:
                a_out[i, block], t_out[i, block] = attitudes[i].sun_dipoles(where[i, block],
                                                                            sun[block])
        if len(sunny) < len(attitudes):
            transverse_sunny, positions = transverse[sunny], positions[sunny]
        else:
            transverse_sunny = transverse
        nan = np.isnan(transverse_sunny[..., 0])
        finite = np.all(np.isfinite(positions), axis=-1) if np.any(nan) else False
        count = np.count_nonzero(nan & finite)
        warn_undefined_count(count, nan.size)
        return aligned, transverse


#: Epochs per block of `Attitude.dipoles_many`.
_EPOCHS = 4096


def sun_at(obstime, orientation):
    """The Sun (ITRS metres, obstime.shape + (3,)), from the orientation's nodes if given.

    Parameters
    ----------
    obstime : `~astropy.time.Time`
        Epochs.
    orientation : `~astropy_feedrot.earth.orientation.EarthOrientation` or None
        Earth orientation at these epochs, or None for astropy's
        transformation at every epoch (`sun_position`).

    Returns
    -------
    ndarray, shape obstime.shape + (3,)

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.transmitters.attitude_interface import sun_at
    >>> from astropy_feedrot.earth.orientation import EarthOrientation
    >>> t = Time(["2023-01-25T00:00", "2023-01-25T12:00"])
    >>> fast, exact = sun_at(t, EarthOrientation(t)), sun_at(t, None)
    >>> bool(np.allclose(fast, exact, rtol=1e-11))  # nodes against astropy
    True
    """
    if orientation is None:
        return sun_position(obstime)
    return interpolated_sun_position(orientation).reshape(obstime.shape + (3,))


def sun_position(obstime):
    """Geocentric ITRS position of the Sun in metres.

    Parameters
    ----------
    obstime : `~astropy.time.Time`
        Epoch(s).

    Returns
    -------
    ndarray, shape obstime.shape + (3,)

    Notes
    -----
    From ERFA's built-in ephemeris (``epv00``, through astropy's
    ``get_body_barycentric``), expressed in GCRS and rotated to ITRS; good to
    a few arcseconds, far more than the attitude model needs.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.transmitters.attitude_interface import sun_position
    >>> au = np.linalg.norm(sun_position(Time("2023-01-25"))) / 1.495978707e11
    >>> round(float(au), 3)
    0.984
    """
    return Epochs(obstime).sun_position(exact=True)


def interpolated_sun_position(orientation):
    """Geocentric ITRS position of the Sun at many epochs, at the cost of a few.

    The Sun's position changes slowly in the celestial frames: ERFA's
    ``epv00`` is evaluated once a day and interpolated, and the Earth's
    rotation is applied at every epoch (see
    `~astropy_feedrot.earth.orientation.EarthOrientation.sun_position`).

    Parameters
    ----------
    orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`
        Earth orientation at the epochs.

    Returns
    -------
    ndarray, shape (N, 3)
        Metres, at the N flattened epochs of ``orientation``; within 1e-11 rad
        of `sun_position` in direction and 1e-11 in relative distance (about
        2e-13 for both).

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.transmitters.attitude_interface import (interpolated_sun_position,
    ...                                                              sun_position)
    >>> from astropy_feedrot.earth.orientation import EarthOrientation
    >>> times = Time("2023-01-25") + np.arange(0, 86400, 60) * u.s
    >>> sun = interpolated_sun_position(EarthOrientation(times))
    >>> exact = sun_position(times[::100])
    >>> sine = np.linalg.norm(np.cross(sun[::100], exact), axis=-1)
    >>> bool(np.all(sine / np.linalg.norm(exact, axis=-1) ** 2 < 1e-12))  # radians
    True
    """
    return orientation.sun_position()


def warn_undefined_count(count, epochs):
    """One warning for ``count`` epochs (of ``epochs``) where the nominal attitude is NaN.

    Parameters
    ----------
    count : int
        Epochs (satellite epochs) where the attitude is undefined; no warning
        if 0.
    epochs : int
        All of them.

    Warns
    -----
    DegenerateGeometryWarning
        If ``count`` is not 0.

    Examples
    --------
    >>> import warnings
    >>> from astropy_feedrot.transmitters.attitude_interface import warn_undefined_count
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_undefined_count(2, 100)
    >>> str(caught[0].message)[:39]
    'nominal attitude undefined at 2 of 100 '
    """
    if count:
        warn_caller(
            f"nominal attitude undefined at {count} of {epochs} epochs, "
            "where the Sun, the satellite and the Earth's centre are aligned; NaN is "
            "returned there",
            DegenerateGeometryWarning,
        )
