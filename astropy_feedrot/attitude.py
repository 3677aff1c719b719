# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Transmitter attitude: the satellite antenna's dipoles in the Earth-fixed frame.

`NominalAttitude` points the antenna at the Earth's centre and keeps the solar
panels towards the Sun (Eqs 26-27). `QuaternionAttitude` takes measured
attitude quaternions, such as those of IGS ORBEX files (Eqs 24-25).
"""

import os

import numpy as np
from astropy import units as u
from astropy.coordinates import (
    GCRS,
    ITRS,
    CartesianRepresentation,
    get_body_barycentric,
)

from . import kernel
from .eop import iers_context
from .exceptions import DegenerateGeometryWarning, warn_caller
from .frames import as_time
from .io import read_orbex
from .orbits import check_orientation

__all__ = [
    "Attitude",
    "NominalAttitude",
    "QuaternionAttitude",
    "nominal_dipoles",
    "sun_position",
    "interpolated_sun_position",
    "slerp",
]

#: Relative tolerance on the norm of attitude quaternions: within it they are
#: normalized, beyond it they are rejected.
QUATERNION_NORM_TOLERANCE = 1e-3


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
    >>> from astropy_feedrot.attitude import Attitude
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
        orientation : `~astropy_feedrot.earth.EarthOrientation`, optional
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
        orientation : `~astropy_feedrot.earth.EarthOrientation`, optional
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
            `~astropy_feedrot.earth.EarthOrientation`.
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
        >>> from astropy_feedrot.attitude import Attitude
        >>> from astropy_feedrot.earth import EarthOrientation
        >>> from astropy_feedrot.orbits import Orbit
        >>> from astropy_feedrot.simulations import GPS_SVN76_TLE
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
        sun = _sun(obstime, orientation)
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
        _warn_undefined_count(count, nan.size)
        return aligned, transverse


#: Epochs per block of `Attitude.dipoles_many`.
_EPOCHS = 4096


def _sun(obstime, orientation):
    """The Sun (ITRS metres, obstime.shape + (3,)): from the orientation's nodes if given."""
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
    >>> from astropy_feedrot.attitude import sun_position
    >>> au = np.linalg.norm(sun_position(Time("2023-01-25"))) / 1.495978707e11
    >>> round(float(au), 3)
    0.984
    """
    obstime = as_time(obstime)
    if obstime.size == 0:  # nothing to compute (astropy 6.0 fails on empty epochs)
        return np.empty(obstime.shape + (3,))
    with iers_context(obstime):
        itrs = _sun_gcrs(obstime).transform_to(ITRS(obstime=obstime))
    return np.moveaxis(itrs.cartesian.xyz.to_value(u.m), 0, -1)


def _sun_gcrs(obstime):
    """The Sun's geocentric position in GCRS (ERFA's ``epv00``)."""
    with iers_context(obstime):
        sun = get_body_barycentric("sun", obstime, ephemeris="builtin")
        earth = get_body_barycentric("earth", obstime, ephemeris="builtin")
    return GCRS(CartesianRepresentation((sun - earth).xyz), obstime=obstime)


def interpolated_sun_position(orientation):
    """Geocentric ITRS position of the Sun at many epochs, at the cost of a few.

    The Sun's position changes slowly in the celestial frames: ERFA's
    ``epv00`` is evaluated once a day and interpolated, and the Earth's
    rotation is applied at every epoch (see
    `~astropy_feedrot.earth.EarthOrientation.sun_position`).

    Parameters
    ----------
    orientation : `~astropy_feedrot.earth.EarthOrientation`
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
    >>> from astropy_feedrot.attitude import interpolated_sun_position, sun_position
    >>> from astropy_feedrot.earth import EarthOrientation
    >>> times = Time("2023-01-25") + np.arange(0, 86400, 60) * u.s
    >>> sun = interpolated_sun_position(EarthOrientation(times))
    >>> exact = sun_position(times[::100])
    >>> sine = np.linalg.norm(np.cross(sun[::100], exact), axis=-1)
    >>> bool(np.all(sine / np.linalg.norm(exact, axis=-1) ** 2 < 1e-12))  # radians
    True
    """
    return orientation.sun_position()


def nominal_dipoles(position, sun):
    """Transmitter dipoles of the nominal attitude from plain arrays (Eqs 26, 27).

    Parameters
    ----------
    position : array-like, shape (..., 3)
        Geocentric ITRS positions of satellites (any length unit).
    sun : array-like, shape (..., 3)
        Geocentric ITRS position of the Sun, same unit, broadcastable with
        ``position`` (e.g. shape (T, 1, 3) for (T, S, 3) positions: the Sun
        once per epoch for all satellites).

    Returns
    -------
    aligned, transverse : ndarray, shape (..., 3)
        :math:`\\hat{t}^a` and :math:`\\hat{t}^t`: the boresight points at the
        geocentre, the transverse dipole is perpendicular to it and to the
        direction of the Sun, the aligned dipole completes the right-handed
        set. NaN (without a warning) where the Sun, the satellite and the
        geocentre are aligned: where the sine of the angle between the
        boresight and the direction of the Sun is below
        `~astropy_feedrot.kernel.DEGENERATE_NORM`.

    Notes
    -----
    With the boresight :math:`\\hat{b} = -\\vec{r}/r` and the direction to the
    Sun along :math:`\\vec{r}_\\odot - \\vec{r}`, the transverse dipole is along
    :math:`\\hat{b} \\times (\\vec{r}_\\odot - \\vec{r}) \\propto
    \\vec{r}_\\odot \\times \\vec{r}` and the aligned dipole is
    :math:`\\hat{t}^t \\times \\hat{b}`; both are computed component by
    component.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.attitude import nominal_dipoles
    >>> aligned, transverse = nominal_dipoles([2.6e7, 0.0, 0.0], [0.0, 1.5e11, 0.0])
    >>> transverse  # doctest: +FLOAT_CMP
    array([ 0.,  0., -1.])
    >>> aligned  # doctest: +FLOAT_CMP
    array([0., 1., 0.])
    """
    position = np.asarray(position, dtype=float)
    sun = np.asarray(sun, dtype=float)
    shape = np.broadcast_shapes(position.shape, sun.shape)
    size = int(np.prod(shape[:-1]))
    if len(shape) < 2 or size <= _BLOCK:
        return _nominal_block(position, sun, shape)
    # Blocks along the first axis that stay in the cache (3x faster on 1e6 vectors).
    aligned = np.empty(shape)
    transverse = np.empty(shape)
    position = np.broadcast_to(position, shape)
    sun = np.broadcast_to(sun, shape)
    rows = max(1, _BLOCK * shape[0] // size)
    for a in range(0, shape[0], rows):
        block = slice(a, a + rows)
        aligned[block], transverse[block] = _nominal_block(position[block], sun[block],
                                                           position[block].shape)
    return aligned, transverse


#: Vectors per block of `nominal_dipoles`.
_BLOCK = 16384


def _nominal_block(position, sun, shape):
    """`nominal_dipoles` on arrays that broadcast to ``shape``."""
    px, py, pz = (position[..., i] for i in range(3))
    sx, sy, sz = (sun[..., i] for i in range(3))
    transverse = np.empty(shape)
    aligned = np.empty(shape)
    with np.errstate(invalid="ignore", divide="ignore"):
        cx = sy * pz - sz * py  # sun x position: along the transverse dipole
        cy = sz * px - sx * pz
        cz = sx * py - sy * px
        pp = px * px + py * py + pz * pz
        dd = (sx - px) ** 2 + (sy - py) ** 2 + (sz - pz) ** 2
        cc = cx * cx + cy * cy + cz * cz
        # |b x unit(sun - r)|^2 = cc / (pp dd): degenerate below DEGENERATE_NORM.
        scale = np.where(cc < kernel.DEGENERATE_NORM**2 * pp * dd, np.nan, 1 / np.sqrt(cc))
        tx = np.multiply(cx, scale, out=transverse[..., 0])
        ty = np.multiply(cy, scale, out=transverse[..., 1])
        tz = np.multiply(cz, scale, out=transverse[..., 2])
        inverse = 1 / np.sqrt(pp)  # aligned = t x b = (r x t) / r
        np.multiply(py * tz - pz * ty, inverse, out=aligned[..., 0])
        np.multiply(pz * tx - px * tz, inverse, out=aligned[..., 1])
        np.multiply(px * ty - py * tx, inverse, out=aligned[..., 2])
    return aligned, transverse


def _undefined(transverse, position):
    """Where `nominal_dipoles` is NaN for a finite position."""
    return np.isnan(transverse[..., 0]) & np.all(np.isfinite(position), axis=-1)


def _warn_nominal_undefined(transverse, position):
    """One warning for the epochs where `nominal_dipoles` is NaN for a finite position."""
    bad = _undefined(transverse, position)
    _warn_undefined_count(np.count_nonzero(bad), bad.size)


def _warn_undefined_count(count, epochs):
    """One warning for ``count`` epochs (of ``epochs``) where the nominal attitude is NaN."""
    if count:
        warn_caller(
            f"nominal attitude undefined at {count} of {epochs} epochs, "
            "where the Sun, the satellite and the Earth's centre are aligned; NaN is "
            "returned there",
            DegenerateGeometryWarning,
        )


class NominalAttitude(Attitude):
    """Nadir pointing with the solar panels towards the Sun (Eqs 26, 27).

    The boresight points at the geocentre, the transverse dipole is
    perpendicular to the boresight and to the direction of the Sun, and the
    aligned dipole completes the right-handed set (Montenbruck et al. 2015).

    Notes
    -----
    When the Sun, the satellite and the geocentre are aligned (the Sun behind
    or in front of the satellite, within ~0.2 mas) the transverse dipole is
    undefined: those epochs are NaN and one
    `~astropy_feedrot.DegenerateGeometryWarning` is emitted.

    The Sun is `sun_position` at each epoch, or, given an
    `~astropy_feedrot.earth.EarthOrientation` of the epochs,
    `interpolated_sun_position` (within 1e-10 rad in direction).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot import NominalAttitude
    >>> aligned, transverse = NominalAttitude().dipoles(Time("2023-01-25"),
    ...                                                 np.array([2.6e7, 0.0, 0.0]))
    >>> float(aligned @ transverse)  # doctest: +FLOAT_CMP
    0.0
    """

    needs_sun = True

    def __repr__(self):
        return "NominalAttitude()"

    def dipoles(self, obstime, position, orientation=None):
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        position = np.asarray(position, dtype=float)
        aligned, transverse = self.sun_dipoles(position, _sun(obstime, orientation))
        _warn_nominal_undefined(transverse, position)
        return aligned, transverse

    def sun_dipoles(self, position, sun):
        """Eqs 26-27 from the satellite's and the Sun's positions (`nominal_dipoles`).

        Parameters
        ----------
        position, sun : ndarray, shape (..., 3)
            Geocentric ITRS positions in metres, broadcastable.

        Returns
        -------
        aligned, transverse : ndarray, shape (..., 3)
            NaN, without a warning, where the Sun, the satellite and the
            geocentre are aligned.

        Examples
        --------
        >>> from astropy_feedrot import NominalAttitude
        >>> aligned, transverse = NominalAttitude().sun_dipoles([2.6e7, 0, 0], [0, 1.5e11, 0])
        >>> aligned  # doctest: +FLOAT_CMP
        array([0., 1., 0.])
        """
        return nominal_dipoles(position, sun)


def _quaternion_rows(q):
    """First and second rows of the rotation matrix of unit quaternions (Eqs 24, 25)."""
    q0, q1, q2, q3 = np.moveaxis(q, -1, 0)
    row1 = np.stack(
        [q0**2 + q1**2 - q2**2 - q3**2, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)], axis=-1)
    row2 = np.stack(
        [2 * (q1 * q2 + q0 * q3), q0**2 - q1**2 + q2**2 - q3**2, 2 * (q2 * q3 - q0 * q1)], axis=-1)
    return row1, row2


def slerp(q1, q2, fraction):
    """Spherical linear interpolation between unit quaternions.

    Parameters
    ----------
    q1, q2 : ndarray, shape (..., 4)
        Unit quaternions (scalar first) at the start and end of the interval.
    fraction : ndarray, shape (...)
        Position in the interval, 0 at ``q1`` and 1 at ``q2``.

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions along the shorter arc (``q2`` and ``-q2`` are the same
        rotation).

    Examples
    --------
    Halfway between no rotation and a quarter turn about z is an eighth turn:

    >>> import numpy as np
    >>> from astropy_feedrot.attitude import slerp
    >>> quarter = np.array([np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)])
    >>> slerp(np.array([1.0, 0, 0, 0]), quarter, 0.5)  # doctest: +FLOAT_CMP
    array([0.92387953, 0.        , 0.        , 0.38268343])
    """
    q1 = np.asarray(q1, dtype=float)
    q2 = np.asarray(q2, dtype=float)
    fraction = np.asarray(fraction, dtype=float)[..., np.newaxis]
    cos = np.sum(q1 * q2, axis=-1, keepdims=True)
    q2 = np.where(cos < 0, -q2, q2)
    cos = np.abs(cos)
    angle = np.arccos(np.clip(cos, -1.0, 1.0))
    sin = np.sin(angle)
    small = sin < 1e-9
    with np.errstate(invalid="ignore", divide="ignore"):
        w1 = np.where(small, 1 - fraction, np.sin((1 - fraction) * angle) / sin)
        w2 = np.where(small, fraction, np.sin(fraction * angle) / sin)
    out = w1 * q1 + w2 * q2
    return out / np.linalg.norm(out, axis=-1, keepdims=True)


class QuaternionAttitude(Attitude):
    """Attitude from tabulated quaternions, interpolated in time (Eqs 24, 25).

    Parameters
    ----------
    obstime : `~astropy.time.Time`, shape (N,)
        Increasing epochs of the quaternions.
    quaternions : array-like, shape (N, 4)
        Quaternions, scalar first :math:`(q_0, q_1, q_2, q_3)`.
    convention : {'earth_to_body', 'body_to_earth'}, optional
        What the quaternions rotate. ``'earth_to_body'`` (default, the form
        Eqs 24-25 need): a vector's Earth-fixed components go to body
        components, so the first and second rows of the rotation matrix are
        the body x (aligned) and y (transverse) axes in the Earth-fixed frame.
        ``'body_to_earth'`` quaternions are conjugated first.
    frame : {'itrs', 'gcrs'}, optional
        The reference frame the quaternions refer to: Earth-fixed (default) or
        celestial (the body axes are then rotated to ITRS at each epoch).

    Raises
    ------
    ValueError
        If shapes do not match, an epoch is masked, a quaternion is not
        finite, epochs do not increase strictly, a quaternion's norm is off by more
        than 0.1 % (smaller errors are normalized away), or for an unknown
        ``convention``/``frame``.

    Notes
    -----
    Between epochs the rotation is interpolated spherically (`slerp`);
    outside the tabulated epochs an error names the coverage.

    Examples
    --------
    A satellite whose body axes coincide with ITRS at the first epoch and have
    turned a quarter turn about z one minute later:

    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot import QuaternionAttitude
    >>> t = Time("2023-01-25T00:00") + [0, 1] * u.min
    >>> q = [[1, 0, 0, 0], [np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)]]
    >>> aligned, transverse = QuaternionAttitude(t, q).dipoles(t[0] + 30 * u.s, [2.6e7, 0, 0])
    >>> aligned  # doctest: +FLOAT_CMP
    array([ 0.70710678, -0.70710678,  0.        ])
    """

    CONVENTIONS = ("earth_to_body", "body_to_earth")
    FRAMES = ("itrs", "gcrs")

    def __init__(self, obstime, quaternions, convention="earth_to_body", frame="itrs"):
        if convention not in self.CONVENTIONS:
            raise ValueError(f"convention must be one of {self.CONVENTIONS}, got {convention!r}")
        if frame not in self.FRAMES:
            raise ValueError(f"frame must be one of {self.FRAMES}, got {frame!r}")
        obstime = as_time(obstime)
        q = np.array(quaternions, dtype=float)
        if obstime.ndim != 1 or q.shape != (len(obstime), 4):
            raise ValueError(
                f"need one quaternion (4 numbers) per epoch: obstime has shape "
                f"{obstime.shape}, quaternions {q.shape}"
            )
        if len(obstime) < 1:
            raise ValueError("need at least one epoch")
        finite = np.all(np.isfinite(q), axis=-1)
        if not np.all(finite):
            i = int(np.argmin(finite))
            raise ValueError(f"quaternion {i} at {obstime[i].isot} is not finite: {q[i]}")
        masked = np.asarray(obstime.mask) if obstime.masked else np.zeros(len(obstime), bool)
        if np.any(masked):
            raise ValueError(f"quaternion epochs must all be given: epoch {int(np.argmax(masked))} "
                             "is masked")
        seconds = np.asarray((obstime - obstime[0]).to_value(u.s), dtype=float)
        step = np.diff(seconds)
        if np.any(step <= 0):
            i = int(np.argmax(step <= 0))
            raise ValueError(
                f"quaternion epochs must increase strictly: epoch {i + 1} "
                f"({obstime[i + 1].isot}) is not after epoch {i} ({obstime[i].isot})"
            )
        norm = np.linalg.norm(q, axis=-1)
        off = np.abs(norm - 1) > QUATERNION_NORM_TOLERANCE
        if np.any(off):
            i = int(np.argmax(off))
            raise ValueError(
                f"quaternion {i} at {obstime[i].isot} has norm {norm[i]:.6g}; attitude "
                f"quaternions must be unit (within {QUATERNION_NORM_TOLERANCE:g})"
            )
        q = q / norm[:, np.newaxis]
        if convention == "body_to_earth":
            q = q * np.array([1.0, -1.0, -1.0, -1.0])
        self.epochs = obstime
        self.quaternions = q
        self.convention = convention
        self.frame = frame
        self._seconds = seconds

    def __repr__(self):
        return (
            f"<QuaternionAttitude {len(self.epochs)} epochs {self.epochs[0].isot} to "
            f"{self.epochs[-1].isot}, frame={self.frame!r}>"
        )

    @classmethod
    def from_orbex(cls, source, satellite, frame=None):
        """Read the attitude of one satellite from an IGS ORBEX file.

        Parameters
        ----------
        source : str, path-like or file object
            An ORBEX file with ``ATT`` records.
        satellite : str
            The satellite's ID, e.g. ``'G05'``.
        frame : {'itrs', 'gcrs'}, optional
            The frame the quaternions refer to, needed only when the file does
            not say it (no ``FRAME_TYPE``); if given for a file that does, it
            must agree (``ECEF`` is ``'itrs'``, ``ECI`` is ``'gcrs'``).

        Returns
        -------
        QuaternionAttitude

        Raises
        ------
        astropy_feedrot.io.FileFormatError
            If the file is malformed (naming the line and what was expected):
            among others a ``FRAME_TYPE`` other than ``ECEF`` or ``ECI``,
            quaternions that are not finite, epochs out of order or repeated.
        ValueError
            If ``satellite`` has no attitude in the file (listing those that
            do), the file gives no ``FRAME_TYPE`` and ``frame`` is not given,
            ``frame`` contradicts the file, or a quaternion of the satellite
            is not a unit quaternion (naming the file, satellite and epoch).

        Notes
        -----
        ORBEX quaternions rotate the file's reference frame into the satellite
        body frame, :math:`(0, r_B) = q\\,(0, r_T)\\,q^*` (the
        ``'earth_to_body'`` convention); a file whose ``FRAME_TYPE`` is ``ECI``
        refers to a celestial frame, rotated here to ITRS.

        Examples
        --------
        >>> from astropy.time import Time
        >>> from astropy_feedrot import QuaternionAttitude
        >>> from astropy_feedrot.data import sample_file
        >>> attitude = QuaternionAttitude.from_orbex(sample_file("sample.obx"), "G01")
        >>> attitude.frame
        'itrs'
        """
        if frame is not None and frame not in cls.FRAMES:
            raise ValueError(f"frame must be one of {cls.FRAMES} or None, got {frame!r}")
        data = read_orbex(source)
        name = _source_name(source)
        if satellite not in data.attitude:
            raise ValueError(
                f"satellite {satellite!r} has no attitude in the ORBEX file; it has "
                f"{', '.join(data.satellites)}"
            )
        if data.frame_type is None:
            if frame is None:
                raise ValueError(
                    f"{name}: the ORBEX file does not give FRAME_TYPE (ECEF or ECI) in its "
                    "+FILE/DESCRIPTION block, so the frame of its quaternions is unknown; "
                    "pass frame='itrs' (Earth-fixed) or frame='gcrs' (celestial)"
                )
        else:
            from_file = _ORBEX_FRAMES[data.frame_type]
            if frame is not None and frame != from_file:
                raise ValueError(
                    f"{name}: frame={frame!r} contradicts the file's FRAME_TYPE "
                    f"{data.frame_type} ({from_file!r}); leave frame out"
                )
            frame = from_file
        times, quaternions = data.attitude[satellite]
        try:
            return cls(times, quaternions, convention="earth_to_body", frame=frame)
        except ValueError as error:
            raise ValueError(f"{name}: ATT records of {satellite}: {error}") from None

    def quaternion(self, obstime):
        """Interpolated unit quaternions at the given epochs.

        Parameters
        ----------
        obstime : `~astropy.time.Time`

        Returns
        -------
        ndarray, shape obstime.shape + (4,)

        Raises
        ------
        ValueError
            If a time lies outside the tabulated epochs.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.time import Time
        >>> from astropy_feedrot import QuaternionAttitude
        >>> t = Time("2023-01-25T00:00") + [0, 1] * u.min
        >>> QuaternionAttitude(t, [[1, 0, 0, 0], [1, 0, 0, 0]]).quaternion(t[0])
        array([1., 0., 0., 0.])
        """
        obstime = as_time(obstime)
        x = np.atleast_1d((obstime - self.epochs[0]).to_value(u.s)).ravel()
        tol = 1e-6
        if np.any((x < -tol) | (x > self._seconds[-1] + tol)):
            raise ValueError(
                f"times outside the coverage of the attitude quaternions: "
                f"{self.epochs[0].isot} to {self.epochs[-1].isot} {self.epochs.scale.upper()}"
            )
        if len(self._seconds) == 1:
            q = np.broadcast_to(self.quaternions[0], x.shape + (4,))
        else:
            i = np.clip(np.searchsorted(self._seconds, x, side="right") - 1, 0,
                        len(self._seconds) - 2)
            span = self._seconds[i + 1] - self._seconds[i]
            q = slerp(self.quaternions[i], self.quaternions[i + 1], (x - self._seconds[i]) / span)
        return q.reshape(obstime.shape + (4,))

    def dipoles(self, obstime, position, orientation=None):
        # The tabulated axes are rotated exactly (astropy) when celestial: no
        # interpolated Earth orientation needed.
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        aligned, transverse = _quaternion_rows(self.quaternion(obstime))
        if self.frame == "gcrs":
            aligned, transverse = (_gcrs_to_itrs_direction(v, obstime)
                                   for v in (aligned, transverse))
        shape = np.broadcast_shapes(aligned.shape, np.shape(position))
        return np.broadcast_to(aligned, shape), np.broadcast_to(transverse, shape)


#: The frame of `QuaternionAttitude` for each ORBEX ``FRAME_TYPE``.
_ORBEX_FRAMES = {"ECEF": "itrs", "ECI": "gcrs"}


def _source_name(source):
    """The name of a file given as a path or a file object, for messages."""
    if isinstance(source, (str, os.PathLike)):
        return os.fsdecode(os.fspath(source))
    name = getattr(source, "name", None)
    return name if isinstance(name, str) and name else "<stream>"


def _gcrs_to_itrs_direction(vector, obstime):
    """Rotate geocentric celestial (GCRS) directions to ITRS."""
    rep = CartesianRepresentation(np.moveaxis(vector, -1, 0) * u.one)
    with iers_context(obstime):
        itrs = GCRS(rep, obstime=obstime).transform_to(ITRS(obstime=obstime))
    return np.moveaxis(itrs.cartesian.xyz.value, 0, -1)
