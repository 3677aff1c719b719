# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Measured attitude: quaternions (ORBEX files, Eqs 24-25), interpolated in time.

`QuaternionAttitude` takes attitude quaternions at epochs (or an IGS ORBEX
file) and gives the dipoles between them by spherical linear interpolation
(`slerp`).
"""

import os

import numpy as np
from astropy import units as u
from astropy.coordinates import GCRS, ITRS, CartesianRepresentation

from ..earth.eop import iers_context
from ..earth.frames import as_time
from ..io import read_orbex
from .attitude_interface import Attitude
from .orbits import check_orientation

__all__ = ["QuaternionAttitude", "slerp", "QUATERNION_NORM_TOLERANCE"]


#: Relative tolerance on the norm of attitude quaternions: within it they are
#: normalized, beyond it they are rejected.
QUATERNION_NORM_TOLERANCE = 1e-3


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
    >>> from astropy_feedrot.transmitters.quaternion_attitude import slerp
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
