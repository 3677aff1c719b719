# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Antenna mounts: how the feed of a receiver is oriented in the Earth-fixed frame.

A steerable telescope keeps its boresight on the source and turns about a
*fixed axis* (Eq 10): its feed rotation for a natural source is the angle, on
the plane of the sky, from the projected fixed axis to the projected north
celestial pole (Eq 13). A `StationaryMount` is a crossed dipole that never
moves (a GNSS antenna, Eqs 28-29).

A mount declares what it is, and `~astropy_feedrot.engine.equations` picks the
equation: a mount that ``tracks`` gives its ``fixed_axis(local)``; one that
does not gives its ``dipoles(local)``.
"""

import numpy as np

__all__ = [
    "Mount",
    "FixedAxisMount",
    "AltAzMount",
    "EquatorialMount",
    "XYMount",
    "StationaryMount",
    "as_mount",
]


class Mount:
    """Base class of antenna mounts.

    Subclasses describe how the receiving feed is oriented; they hold no site
    and no time, and are immutable. A subclass that tracks (``tracks =
    True``, the default) defines ``fixed_axis(local)``, the unit vector its
    first axis keeps fixed to the ground (as `FixedAxisMount`); one that
    does not track defines ``dipoles(local)``, its aligned, transverse and
    boresight unit vectors (as `StationaryMount`). That is all
    `~astropy_feedrot.engine.equations` needs to give it every feed rotation.

    Examples
    --------
    >>> from astropy_feedrot import AltAzMount, Mount, StationaryMount
    >>> isinstance(AltAzMount(), Mount), AltAzMount().tracks, StationaryMount().tracks
    (True, True, False)
    """

    #: Whether the antenna points its boresight at the source.
    tracks = True

    def __eq__(self, other):
        return type(self) is type(other) and self._key() == other._key()

    def __hash__(self):
        return hash((type(self), self._key()))

    def _key(self):
        return ()

    def __repr__(self):
        return f"{type(self).__name__}()"


class FixedAxisMount(Mount):
    """A steerable mount whose first axis is fixed to the ground (Eq 10).

    Parameters
    ----------
    axis : array-like of 3 floats
        Direction of the fixed axis (any length but zero; it is normalized).
    frame : {'itrs', 'enu'}, optional
        Whether ``axis`` is given in geocentric ITRS components (default) or in
        the local east-north-up components of the antenna's site.

    Raises
    ------
    ValueError
        If ``axis`` is not three finite numbers of non-zero length, or for an
        unknown ``frame``.

    Notes
    -----
    The feed rotation of a natural source is Eq 13 with the fixed-axis vector
    :math:`\\hat{a}`: :math:`\\Phi = \\mathrm{atan2}(\\hat{a}^T S_\\times^T
    \\hat{z},\\; \\hat{a}^T P \\hat{z})`. It is undefined (NaN) when the source
    lies along the axis.

    Examples
    --------
    A mount whose fixed axis is horizontal and points north-east:

    >>> from astropy_feedrot import FixedAxisMount
    >>> FixedAxisMount([1.0, 1.0, 0.0], frame="enu")
    FixedAxisMount([0.70710678, 0.70710678, 0.        ], frame='enu')
    """

    FRAMES = ("itrs", "enu")

    def __init__(self, axis, frame="itrs"):
        if frame not in self.FRAMES:
            raise ValueError(f"frame must be one of {self.FRAMES}, got {frame!r}")
        try:
            vector = np.array(axis, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"axis must be three numbers, got {axis!r}") from None
        if vector.shape != (3,) or not np.all(np.isfinite(vector)):
            raise ValueError(f"axis must be three finite numbers, got {axis!r}")
        norm = np.linalg.norm(vector)
        if norm == 0:
            raise ValueError("axis must have a non-zero length")
        vector = vector / norm
        vector.flags.writeable = False
        self._axis = vector
        self._frame = frame

    @property
    def axis(self):
        """The unit fixed-axis vector, in the components of `frame`."""
        return self._axis

    @property
    def frame(self):
        """``'itrs'`` or ``'enu'``: the components `axis` is given in."""
        return self._frame

    def _key(self):
        return (tuple(self._axis), self._frame)

    def __repr__(self):
        return f"{type(self).__name__}({np.array_repr(self._axis)[6:-1]}, frame={self._frame!r})"

    def fixed_axis(self, local):
        """The fixed-axis unit vector :math:`\\hat{a}` in ITRS at a site.

        Parameters
        ----------
        local : `~astropy_feedrot.earth.frames.LocalFrame`
            East, north and up vectors of the site.

        Returns
        -------
        ndarray, shape (..., 3)

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot import FixedAxisMount
        >>> from astropy_feedrot.earth.frames import LocalFrame
        >>> enu = LocalFrame(*np.eye(3))
        >>> FixedAxisMount([0, 0, 1.0], frame="enu").fixed_axis(enu)
        array([0., 0., 1.])
        """
        if self._frame == "itrs":
            return self._axis
        e, n, up = local
        return self._axis[0] * e + self._axis[1] * n + self._axis[2] * up


class AltAzMount(FixedAxisMount):
    """Azimuth-elevation (alt-az) mount: the fixed axis is the local vertical (Eq 14).

    Its feed rotation for a natural source is the parallactic angle
    :math:`\\Psi` (Eq 15), positive west of the meridian as in ERFA's
    ``hd2pa``.

    Examples
    --------
    >>> from astropy_feedrot import AltAzMount
    >>> AltAzMount()
    AltAzMount()
    """

    def __init__(self):
        super().__init__([0.0, 0.0, 1.0], frame="enu")

    def fixed_axis(self, local):
        return local.up

    def __repr__(self):
        return "AltAzMount()"


class EquatorialMount(FixedAxisMount):
    """Equatorial (polar) mount: the fixed axis is the celestial pole (Eq 17).

    The feed does not rotate for a natural source: the feed rotation is 0,
    and undefined (NaN) for a source at the pole.

    Examples
    --------
    >>> from astropy_feedrot import EquatorialMount
    >>> EquatorialMount().axis
    array([0., 0., 1.])
    """

    def __init__(self):
        super().__init__([0.0, 0.0, 1.0], frame="itrs")

    def __repr__(self):
        return "EquatorialMount()"


class XYMount(FixedAxisMount):
    """X-Y mount: the fixed (X) axis is horizontal, north-south or east-west (Eqs 18, 19).

    Parameters
    ----------
    axis : {'north', 'east'}
        Direction of the fixed X axis: ``'north'`` for a north-south axis
        (VEX ``x:yns``, :math:`\\hat{a} = \\hat{n}`), ``'east'`` for an
        east-west one (VEX ``x:yew``, :math:`\\hat{a} = \\hat{e}`).

    Raises
    ------
    ValueError
        For another ``axis``.

    Notes
    -----
    With the local apparent hour angle :math:`h` (positive west),
    declination :math:`\\delta` and geodetic latitude :math:`\\phi`,
    spherical trigonometry on Eq 13 gives, for :math:`\\cos\\delta > 0`,

    .. math::

        \\Phi_\\mathrm{XY\\text{-}N} &= \\mathrm{atan2}(-\\sin\\phi\\sin h,\\;
            \\cos\\phi\\cos\\delta + \\sin\\phi\\sin\\delta\\cos h), \\\\
        \\Phi_\\mathrm{XY\\text{-}E} &= \\mathrm{atan2}(\\cos h,\\; \\sin\\delta\\sin h).

    (Write :math:`\\hat{s} = \\cos\\delta\\cos h\\,\\hat{m} - \\cos\\delta\\sin h
    \\,\\hat{e} + \\sin\\delta\\,\\hat{z}` with :math:`\\hat{m}` the equator on
    the meridian, and :math:`\\hat{n} = -\\sin\\phi\\,\\hat{m} +
    \\cos\\phi\\,\\hat{z}`.) The north-south form is the parallactic angle
    of a site at latitude :math:`\\phi - 90^\\circ`, plus 180 deg; the east-west
    form does not depend on latitude. The feed rotation is undefined where
    the source lies on the X axis (the horizon's north/south or east/west
    point).

    Examples
    --------
    >>> from astropy_feedrot import XYMount
    >>> XYMount("east")
    XYMount(axis='east')
    """

    AXES = ("north", "east")

    def __init__(self, axis):
        if axis not in self.AXES:
            raise ValueError(f"XYMount axis must be one of {self.AXES}, got {axis!r}")
        enu = [0.0, 1.0, 0.0] if axis == "north" else [1.0, 0.0, 0.0]
        super().__init__(enu, frame="enu")
        self._direction = axis

    @property
    def direction(self):
        """``'north'`` or ``'east'``: the direction of the fixed X axis."""
        return self._direction

    def __repr__(self):
        return f"XYMount(axis={self._direction!r})"


class StationaryMount(Mount):
    """A crossed dipole fixed to the ground, pointing up (Eqs 28, 29, 33).

    The receiver of a GNSS antenna (and of LOFAR-like dipole arrays): aligned
    dipole east, transverse dipole north, boresight up. Its feed rotation for a
    natural source is Eq 33; it does not track, so the Wu form (Eq 7) and the
    crossed-dipole form of Beyerle (Eq 5) differ for a transmitter that does
    not face it.

    Examples
    --------
    >>> from astropy_feedrot import StationaryMount
    >>> StationaryMount()
    StationaryMount()
    """

    tracks = False

    def dipoles(self, local):
        """Aligned, transverse and boresight unit vectors in ITRS (Eq 28).

        Parameters
        ----------
        local : `~astropy_feedrot.earth.frames.LocalFrame`
            East, north and up vectors of the site.

        Returns
        -------
        tuple of ndarray
            ``(east, north, up)``.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot import StationaryMount
        >>> from astropy_feedrot.earth.frames import LocalFrame
        >>> StationaryMount().dipoles(LocalFrame(*np.eye(3)))[1]
        array([0., 1., 0.])
        """
        return local.east, local.north, local.up


def as_mount(mount, name="mount"):
    """Check that a value is a mount instance.

    Parameters
    ----------
    mount : object
        The value to check.
    name : str, optional
        How to call it in error messages.

    Returns
    -------
    Mount
        ``mount`` itself.

    Raises
    ------
    TypeError
        If ``mount`` is a mount class rather than an instance, or not a
        `Mount` at all.

    Examples
    --------
    >>> from astropy_feedrot.antennas.mounts import AltAzMount, as_mount
    >>> as_mount(AltAzMount())
    AltAzMount()
    """
    if isinstance(mount, type) and issubclass(mount, Mount):
        raise TypeError(f"{name} must be an instance; did you mean {mount.__name__}()?")
    if not isinstance(mount, Mount):
        raise TypeError(
            f"{name} must be a Mount instance (e.g. AltAzMount(), StationaryMount()), got "
            f"{type(mount).__name__}"
        )
    return mount
