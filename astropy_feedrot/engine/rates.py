# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rates of the feed rotation, :math:`d\\Phi/dt`, on plain arrays.

The feed rotation is a function of the line of sight :math:`\\hat{s}` and of
the dipoles at both ends (Eq 7). For a natural source only :math:`\\hat{s}`
moves in the Earth-fixed ITRS, and every closed form of the package (Eq 13 for
any fixed axis, Eqs 38-39 for Nasmyth and beam-waveguide foci, Eq 33 for a
stationary crossed dipole) is an ``atan2`` of simple functions of
:math:`\\hat{s}`, so the chain rule,

.. math::

    \\frac{d}{dt}\\,\\mathrm{atan2}(y, x) = \\frac{x\\,\\dot{y} - y\\,\\dot{x}}{x^2 + y^2},

gives the rate exactly from :math:`\\dot{\\hat{s}}` (`source_direction_rate`).
Where the phase is not a closed form (a `~astropy_feedrot.MirrorTrain`, a
satellite whose attitude moves its dipoles), the rate is a centred difference:
along the line of sight's motion for a function of :math:`\\hat{s}`
(`directional_rate`), or in time for any callable (`difference_rate`).

Everything is in radians, seconds and metres, on arrays of shape ``(..., 3)``
in ITRS, as in `astropy_feedrot.core.kernel`; the rates are NaN where the angle is
NaN (a source within 0.2 mas of a fixed axis or of the celestial pole, see
`~astropy_feedrot.core.kernel.DEGENERATE_NORM`), without a warning: the front-ends
warn once per call.
"""

import warnings

import numpy as np
from astropy import constants, units as u

from ..core.exceptions import warn_caller
from ..core.kernel import DEGENERATE_NORM, NORTH_POLE, dot, wrap_phase
from ..earth.eop import iers_context
from ..earth.epochs import as_epochs
from ..earth.frames import as_time, fill_masked

__all__ = [
    "EARTH_ROTATION_ANGLE_RATE",
    "DIFFERENCE_STEP",
    "DIRECTIONAL_STEP",
    "atan2_rate",
    "celestial_pole",
    "source_direction_rate",
    "horizontal_rate",
    "wu_phase_rate",
    "fixed_axis_rate",
    "stationary_rate",
    "directional_rate",
    "difference_rate",
]

#: The rate of the Earth rotation angle (IAU 2000, ERFA ``era00``),
#: :math:`2\\pi \\times 1.00273781191135448` per day of UT1, in rad/s. Per SI
#: second it is smaller by the excess length of day over 86400 s (about
#: 1e-8 of it, a few 1e-13 rad/s), which is neglected.
EARTH_ROTATION_ANGLE_RATE = 2 * np.pi * 1.00273781191135448 / 86400.0

#: Default step of `difference_rate`, in seconds (see its Notes).
DIFFERENCE_STEP = 0.01

#: Default step of `directional_rate`, in radians along the line of sight's
#: motion (see its Notes).
DIRECTIONAL_STEP = 3e-7

_C = constants.c.to_value(u.m / u.s)
_GM_SUN = constants.GM_sun.to_value(u.m**3 / u.s**2)


def _vectors(value, name):
    """``value`` as a float array whose last axis has length 3."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be an array of 3-vectors, got "
                        f"{type(value).__name__}") from None
    if array.ndim == 0 or array.shape[-1] != 3:
        raise ValueError(f"{name} must have a last axis of length 3 (x, y, z), got shape "
                         f"{array.shape}")
    return array


def _local(local):
    """``local`` as an (east, north, up) triple of 3-vector arrays."""
    try:
        east, north, up = local
    except (TypeError, ValueError):
        raise TypeError(
            "local must be a LocalFrame (east, north, up), e.g. Antenna.local_frame or "
            f"astropy_feedrot.earth.frames.local_frame(location), got {type(local).__name__}"
        ) from None
    return (_vectors(east, "local.east"), _vectors(north, "local.north"),
            _vectors(up, "local.up"))


def _rate(num, den, num_rate, den_rate, defined):
    """The chain rule for ``atan2(num, den)``; NaN where not ``defined``."""
    with np.errstate(invalid="ignore", divide="ignore"):
        rate = (den * num_rate - num * den_rate) / (num * num + den * den)
    return np.where(defined, rate, np.nan)


def atan2_rate(y, x, y_rate, x_rate):
    """Rate of ``atan2(y, x)`` from the rates of its arguments.

    Parameters
    ----------
    y, x : array-like
        The arguments of ``atan2``.
    y_rate, x_rate : array-like
        Their time derivatives.

    Returns
    -------
    ndarray
        :math:`(x\\dot{y} - y\\dot{x}) / (x^2 + y^2)`, broadcast; NaN where
        :math:`\\sqrt{x^2 + y^2}` is below
        `~astropy_feedrot.core.kernel.DEGENERATE_NORM` (the angle is undefined).

    Examples
    --------
    A point moving on a circle of radius 2 at 0.5 rad/s, at 30 deg:

    >>> import numpy as np
    >>> from astropy_feedrot.engine.rates import atan2_rate
    >>> a = np.radians(30)
    >>> float(atan2_rate(2 * np.sin(a), 2 * np.cos(a),
    ...                  np.cos(a), -np.sin(a)))  # doctest: +FLOAT_CMP
    0.5
    """
    y, x, y_rate, x_rate = (np.asarray(v, dtype=float) for v in (y, x, y_rate, x_rate))
    return _rate(y, x, y_rate, x_rate, np.hypot(y, x) >= DEGENERATE_NORM)


def celestial_pole(obstime):
    """The Celestial Intermediate Pole in ITRS: the axis the Earth turns about.

    Parameters
    ----------
    obstime : `~astropy.time.Time` or `~astropy_feedrot.Epochs`
        Epoch(s); masked epochs give NaN.

    Returns
    -------
    ndarray, shape obstime.shape + (3,)
        The unit vector of the CIP in ITRS
        (`~astropy_feedrot.Epochs.celestial_pole`), from the polar motion of the IERS
        tables bundled with astropy (ERFA ``pom00``, the same values astropy's
        transformation to ITRS uses, inside
        `~astropy_feedrot.earth.eop.iers_context`). It lies within about 0.5 arcsec
        of the ITRS :math:`z` axis, `~astropy_feedrot.core.kernel.NORTH_POLE`.

    Raises
    ------
    TypeError
        If ``obstime`` is not a time.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot.engine.rates import celestial_pole
    >>> pole = celestial_pole(Time("2023-01-25T20:00"))
    >>> offset = np.degrees(np.arccos(pole[2])) * 3600  # arcsec from the ITRS z axis
    >>> round(float(offset), 2)
    0.23
    """
    return as_epochs(obstime).celestial_pole()


def source_direction_rate(s, pole=NORTH_POLE, site=None, sun=None):
    """Rate of the direction of a natural source in the Earth-fixed ITRS.

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Apparent unit direction(s) of the source in ITRS
        (`~astropy_feedrot.earth.frames.source_direction`).
    pole : array-like, shape (..., 3), optional
        The axis the Earth turns about, the CIP (`celestial_pole`). The ITRS
        :math:`z` axis by default.
    site : array-like, shape (..., 3), optional
        Geocentric ITRS position of the observer in metres
        (`~astropy_feedrot.earth.frames.location_xyz`), for the rate of the diurnal
        aberration. Left out if None.
    sun : array-like, shape (..., 3), optional
        Geocentric ITRS position of the Sun in metres
        (`~astropy_feedrot.transmitters.nominal_attitude.sun_position`), for the rate of the annual
        aberration. Left out if None.

    Returns
    -------
    ndarray, shape (..., 3)
        :math:`d\\hat{s}/dt` in rad/s (per second of time), perpendicular to
        ``s``.

    Raises
    ------
    TypeError, ValueError
        If an argument is not an array of 3-vectors.

    Notes
    -----
    A direction fixed on the celestial sphere turns in the Earth-fixed frame
    as :math:`\\dot{\\hat{s}} = -\\omega\\,\\hat{p} \\times \\hat{s}`, with
    :math:`\\omega` = `EARTH_ROTATION_ANGLE_RATE` and :math:`\\hat{p}` the CIP.
    The apparent direction also carries the aberration of the observer's
    velocity :math:`v`, :math:`\\hat{s} \\approx \\hat{s}_0 + P v / c`, whose
    rate is :math:`P a / c` with the observer's acceleration :math:`a`: the
    centripetal :math:`-\\omega^2 (r - (r\\cdot\\hat{p})\\hat{p})` of the site
    and the Earth's fall towards the Sun,
    :math:`GM_\\odot\\, r_\\odot / |r_\\odot|^3`. Together,

    .. math::

        \\dot{\\hat{s}} = -\\omega\\,\\hat{p} \\times \\hat{s} + P\\,a / c.

    The sizes of the terms, i.e. the error in :math:`\\dot{\\hat{s}}` when
    one is left out (measured against a centred difference of astropy's
    transformation over 2023 and in 2030):

    ==========================================  ================================
    term left out                               :math:`|\\delta\\dot{\\hat{s}}|` (rad/s)
    ==========================================  ================================
    polar motion (ITRS :math:`z` for the CIP)   :math:`\\omega` x 0.2-0.5 arcsec,
                                                0.8-1.8e-10
    diurnal aberration (``site``)               1.1e-10 cos(latitude)
    annual aberration (``sun``)                 2.0e-11
    precession-nutation (always left out)       2.5-6.6e-12
    ==========================================  ================================

    The last is the motion of the CIP on the sky (precession 3e-12 rad/s,
    the fortnightly and semi-annual nutation up to 3e-12 rad/s each), whose
    rate would need the precession-nutation matrix at two epochs.

    A feed rotation divides these by the sine of the angle between the line
    of sight and the nearest singular direction (a fixed axis, the celestial
    pole). With all three arguments the rates of `fixed_axis_rate` for an
    alt-az mount agree with a centred difference of astropy's
    transformation to 4e-10 rad/s at 1 deg from the zenith, 8e-11 rad/s at
    5 deg and 2e-11 rad/s at 20 deg; with the ITRS :math:`z` alone, to
    1e-8, 2e-9 and 6e-10 rad/s.

    Examples
    --------
    A source on the celestial equator turns at the Earth's rotation rate,
    westwards:

    >>> from astropy_feedrot.engine.rates import EARTH_ROTATION_ANGLE_RATE, source_direction_rate
    >>> source_direction_rate([1.0, 0.0, 0.0]) / EARTH_ROTATION_ANGLE_RATE + 0.0
    array([ 0., -1.,  0.])
    """
    s = _vectors(s, "s")
    pole = _vectors(pole, "pole")
    rate = -EARTH_ROTATION_ANGLE_RATE * np.cross(pole, s)
    acceleration = np.zeros(3)
    if site is not None:
        site = _vectors(site, "site")
        axial = dot(site, pole)[..., np.newaxis] * pole
        acceleration = acceleration - EARTH_ROTATION_ANGLE_RATE**2 * (site - axial)
    if sun is not None:
        sun = _vectors(sun, "sun")
        distance = np.sqrt(dot(sun, sun))[..., np.newaxis]
        acceleration = acceleration + _GM_SUN * sun / distance**3
    if site is None and sun is None:
        return rate
    aberration = acceleration - dot(acceleration, s)[..., np.newaxis] * s
    return rate + aberration / _C


def horizontal_rate(s, s_rate, local):
    """Rates of the azimuth and elevation of a moving line of sight.

    Parameters
    ----------
    s : array-like, shape (..., 3)
        Unit direction(s) in ITRS.
    s_rate : array-like, shape (..., 3)
        Their rate (`source_direction_rate` for a natural source), rad/s.
    local : `~astropy_feedrot.earth.frames.LocalFrame`
        East, north and up vectors of the site.

    Returns
    -------
    azimuth_rate, elevation_rate : ndarray, shape (...)
        :math:`\\dot{A}` and :math:`\\dot{E}` in rad/s, for the angles of
        `~astropy_feedrot.earth.frames.horizontal`; NaN within 0.2 mas of the
        zenith and the nadir, where the azimuth is undefined.

    Raises
    ------
    TypeError, ValueError
        If an argument is not an array of 3-vectors or ``local`` not a frame.

    Notes
    -----
    With :math:`A = \\mathrm{atan2}(\\hat{s}\\cdot\\hat{e}, \\hat{s}\\cdot
    \\hat{n})` and :math:`\\sin E = \\hat{s}\\cdot\\hat{u}`,
    :math:`\\dot{E} = \\dot{\\hat{s}}\\cdot\\hat{u} / \\cos E`. For a natural
    source (:math:`\\dot{\\hat{s}} = -\\omega \\hat{z} \\times \\hat{s}`) at
    latitude :math:`\\phi` these are the classical
    :math:`\\dot{A} = \\omega(\\sin\\phi - \\cos\\phi\\cos A\\tan E)` and
    :math:`\\dot{E} = \\omega\\cos\\phi\\sin A`.

    Examples
    --------
    A source rising due east at the equator climbs at the rotation rate,
    15.04 deg per hour:

    >>> import numpy as np
    >>> from astropy_feedrot.earth.frames import LocalFrame
    >>> from astropy_feedrot.engine.rates import horizontal_rate, source_direction_rate
    >>> enu = LocalFrame(east=np.array([0.0, 1, 0]), north=np.array([0.0, 0, 1]),
    ...                  up=np.array([1.0, 0, 0]))
    >>> s = np.array([0.0, 1, 0])
    >>> rates = horizontal_rate(s, source_direction_rate(s), enu)
    >>> np.degrees(rates) * 3600  # deg/h  # doctest: +FLOAT_CMP
    array([ 0.        , 15.04106718])
    """
    s = _vectors(s, "s")
    s_rate = _vectors(s_rate, "s_rate")
    east, north, up = _local(local)
    x, y = dot(s, north), dot(s, east)
    cos_elevation = np.hypot(x, y)
    defined = cos_elevation >= DEGENERATE_NORM
    azimuth_rate = _rate(y, x, dot(s_rate, east), dot(s_rate, north), defined)
    with np.errstate(invalid="ignore", divide="ignore"):
        elevation_rate = np.where(defined, dot(s_rate, up) / cos_elevation, np.nan)
    return azimuth_rate, elevation_rate


def wu_phase_rate(s, s_rate, r, t, r_rate=None, t_rate=None):
    """Rate of the effective-dipole form of the wind-up (Eq 7).

    Parameters
    ----------
    s, s_rate : array-like, shape (..., 3)
        Unit line of sight and its rate (rad/s).
    r, t : array-like, shape (..., 3)
        The vectors given to `~astropy_feedrot.core.kernel.wu_phase`: receiver and
        transmitter effective dipoles, or any vectors whose projections
        perpendicular to ``s`` are those dipoles (a fixed axis, the pole).
    r_rate, t_rate : array-like, shape (..., 3), optional
        Their rates; zero (fixed vectors) if None.

    Returns
    -------
    ndarray, shape (...)
        :math:`d\\Phi/dt` in rad/s for :math:`\\Phi` =
        ``wu_phase(s, r, t)``, NaN where that is NaN.

    Raises
    ------
    TypeError, ValueError
        If an argument is not an array of 3-vectors.

    Notes
    -----
    Components along :math:`\\hat{s}` drop out of the triple product, so
    :math:`\\Phi = \\mathrm{atan2}(y, x)` with :math:`y = \\hat{s}\\cdot(r
    \\times t)` and :math:`x = r\\cdot t - (r\\cdot\\hat{s})(t\\cdot\\hat{s})`,
    whose rates follow from the product rule.

    Examples
    --------
    The feed rotation of an equatorial mount (``r`` the pole) does not change:

    >>> from astropy_feedrot.core.kernel import NORTH_POLE
    >>> from astropy_feedrot.engine.rates import source_direction_rate, wu_phase_rate
    >>> s = [0.6, 0.0, 0.8]
    >>> float(wu_phase_rate(s, source_direction_rate(s), NORTH_POLE, NORTH_POLE))
    0.0
    """
    s = _vectors(s, "s")
    s_rate = _vectors(s_rate, "s_rate")
    r = _vectors(r, "r")
    t = _vectors(t, "t")
    r_rate = np.zeros(3) if r_rate is None else _vectors(r_rate, "r_rate")
    t_rate = np.zeros(3) if t_rate is None else _vectors(t_rate, "t_rate")
    rs, ts = dot(r, s), dot(t, s)
    rt = np.cross(r, t)
    y = dot(s, rt)
    x = dot(r, t) - rs * ts
    y_rate = dot(s_rate, rt) + dot(s, np.cross(r_rate, t)) + dot(s, np.cross(r, t_rate))
    rs_rate = dot(r_rate, s) + dot(r, s_rate)
    ts_rate = dot(t_rate, s) + dot(t, s_rate)
    x_rate = dot(r_rate, t) + dot(r, t_rate) - rs_rate * ts - rs * ts_rate
    # As wu_phase: undefined where either projection on the sky is degenerate.
    defined = ((dot(r, r) - rs * rs >= DEGENERATE_NORM**2)
               & (dot(t, t) - ts * ts >= DEGENERATE_NORM**2))
    return _rate(y, x, y_rate, x_rate, defined)


def _multiples(multiples):
    try:
        a, b = (float(m) for m in multiples)
    except (TypeError, ValueError):
        raise ValueError(
            "multiples must be two numbers (of the elevation and of the azimuth), e.g. "
            f"(0, 0) Cassegrain, (1, 0) Nasmyth right, (1, -1) beam waveguide right; got "
            f"{multiples!r}"
        ) from None
    if not (np.isfinite(a) and np.isfinite(b)):
        raise ValueError(f"multiples must be finite, got {multiples!r}")
    return a, b


def fixed_axis_rate(s, s_rate, axis, local=None, multiples=(0, 0)):
    """Feed rotation rate of a fixed-axis mount with a closed-form focus.

    Parameters
    ----------
    s, s_rate : array-like, shape (..., 3)
        Unit line of sight in ITRS and its rate in rad/s (for a natural
        source, `source_direction_rate`).
    axis : array-like, shape (..., 3)
        Fixed-axis unit vector of the mount in ITRS
        (`~astropy_feedrot.FixedAxisMount.fixed_axis`): the local vertical
        (alt-az), the pole (equatorial), north or east (X-Y), any other.
    local : `~astropy_feedrot.earth.frames.LocalFrame`, optional
        East, north and up vectors of the site; needed only for non-zero
        ``multiples``.
    multiples : tuple of 2 float, optional
        :math:`(a, b)` of :math:`\\Phi = \\Phi_{13} + a E + b A`: Cassegrain,
        prime and Gregorian (0, 0), Nasmyth right (1, 0) and left (-1, 0),
        beam waveguide right (1, -1) and left (-1, 1) (Eqs 38, 39).

    Returns
    -------
    ndarray, shape (...)
        :math:`d\\Phi/dt` in rad/s of the feed rotation of a natural source
        (RCP; the LCP rate is its negative); NaN where the angle is NaN (the
        source along the axis or at the celestial pole) and, with a non-zero
        multiple, at the zenith.

    Raises
    ------
    TypeError, ValueError
        If an argument is not an array of 3-vectors, ``multiples`` not two
        finite numbers, or ``local`` missing for non-zero ``multiples``.

    Notes
    -----
    :math:`\\Phi_{13}` is Eq 13, ``wu_phase(s, axis, z)``; its rate is
    `wu_phase_rate` with fixed vectors, and the focus adds
    :math:`a\\dot{E} + b\\dot{A}` (`horizontal_rate`). For an alt-az mount and
    :math:`\\dot{\\hat{s}} = -\\omega\\hat{z}\\times\\hat{s}` this is the
    classical rate of the parallactic angle,
    :math:`\\dot{\\Psi} = -\\omega\\cos\\phi\\cos A / \\cos E`, which grows
    without bound towards the zenith; an equatorial mount gives 0.

    Examples
    --------
    The parallactic angle of a source transiting 10 deg south of the zenith
    at latitude 45 deg, in a local frame where ITRS :math:`z` is the pole:

    >>> import numpy as np
    >>> from astropy_feedrot.earth.frames import LocalFrame
    >>> from astropy_feedrot.engine.rates import fixed_axis_rate, source_direction_rate
    >>> lat = np.radians(45)
    >>> local = LocalFrame(east=np.array([0.0, 1, 0]),
    ...                    north=np.array([-np.sin(lat), 0, np.cos(lat)]),
    ...                    up=np.array([np.cos(lat), 0, np.sin(lat)]))
    >>> z = np.radians(10)
    >>> s = np.cos(z) * local.up - np.sin(z) * local.north
    >>> rate = fixed_axis_rate(s, source_direction_rate(s), local.up)
    >>> float(np.degrees(rate) * 3600)  # deg/h  # doctest: +FLOAT_CMP
    61.24821314693
    >>> from astropy_feedrot.engine.rates import EARTH_ROTATION_ANGLE_RATE as omega
    >>> float(np.degrees(omega * np.cos(lat) / np.cos(np.pi / 2 - z)) * 3600)  # doctest: +FLOAT_CMP
    61.24821314693
    """
    a, b = _multiples(multiples)
    rate = wu_phase_rate(s, s_rate, axis, NORTH_POLE)
    if a == 0 and b == 0:
        return rate
    if local is None:
        raise ValueError(f"multiples {multiples!r} add the elevation or the azimuth: give "
                         "the site's local frame (local=Antenna.local_frame)")
    azimuth_rate, elevation_rate = horizontal_rate(s, s_rate, local)
    if a != 0:
        rate = rate + a * elevation_rate
    if b != 0:
        rate = rate + b * azimuth_rate
    return rate


def stationary_rate(s, s_rate, local):
    """Feed rotation rate of a stationary crossed dipole for a natural source (Eq 33).

    Parameters
    ----------
    s, s_rate : array-like, shape (..., 3)
        Unit line of sight in ITRS and its rate in rad/s.
    local : `~astropy_feedrot.earth.frames.LocalFrame`
        East, north and up vectors of the site: the aligned, transverse and
        boresight directions of the antenna (Eq 28).

    Returns
    -------
    ndarray, shape (...)
        :math:`d\\Phi/dt` in rad/s (RCP), NaN where Eq 33 is NaN.

    Raises
    ------
    TypeError, ValueError
        If an argument is not an array of 3-vectors or ``local`` not a frame.

    Notes
    -----
    The receiver's effective dipole :math:`r = P\\hat{e} - \\hat{s}\\times
    \\hat{n}` (Eq 8) moves with the line of sight:
    :math:`\\dot{r} = -(\\hat{e}\\cdot\\dot{\\hat{s}})\\hat{s} -
    (\\hat{e}\\cdot\\hat{s})\\dot{\\hat{s}} - \\dot{\\hat{s}}\\times\\hat{n}`;
    the rate is then `wu_phase_rate` with the fixed pole.

    Examples
    --------
    Unlike the parallactic angle, Eq 33 is regular at the zenith: the
    effective dipole is twice the east vector there (Eq A1), and the angle
    turns with the sky about the vertical, at :math:`-\\omega\\sin\\phi`.
    Here at latitude 45 deg:

    >>> import numpy as np
    >>> from astropy_feedrot.earth.frames import LocalFrame
    >>> from astropy_feedrot.engine.rates import source_direction_rate, stationary_rate
    >>> lat = np.radians(45)
    >>> local = LocalFrame(east=np.array([0.0, 1, 0]),
    ...                    north=np.array([-np.sin(lat), 0, np.cos(lat)]),
    ...                    up=np.array([np.cos(lat), 0, np.sin(lat)]))
    >>> s = local.up
    >>> rate = stationary_rate(s, source_direction_rate(s), local)
    >>> float(np.degrees(rate) * 3600)  # deg/h  # doctest: +FLOAT_CMP
    -10.63564059832
    """
    s = _vectors(s, "s")
    s_rate = _vectors(s_rate, "s_rate")
    east, north, _ = _local(local)
    es = dot(east, s)[..., np.newaxis]
    r = east - es * s - np.cross(s, north)
    r_rate = -dot(east, s_rate)[..., np.newaxis] * s - es * s_rate - np.cross(s_rate, north)
    return wu_phase_rate(s, s_rate, r, NORTH_POLE, r_rate=r_rate)


def _step(step, name, unit):
    if isinstance(step, u.Quantity):
        try:
            step = step.to_value(unit)
        except u.UnitConversionError:
            raise u.UnitsError(f"{name} must be in {unit}, got {step.unit}") from None
    if isinstance(step, bool) or not isinstance(step, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number ({unit}), got {type(step).__name__}")
    if not (np.isfinite(step) and step > 0):
        raise ValueError(f"{name} must be positive and finite, got {step!r}")
    return float(step)


def _callable(phase):
    if not callable(phase):
        raise TypeError(f"phase must be a callable returning angles, got "
                        f"{type(phase).__name__}")
    return phase


def _radians(angles):
    """A callable's result in radians (Quantity angles, or plain radians)."""
    if isinstance(angles, u.Quantity):
        if angles.unit.physical_type != "angle":
            raise u.UnitsError(f"phase must return angles, got a quantity in "
                               f"{angles.unit.to_string() or 'dimensionless units'}")
        return angles.to_value(u.rad)
    return np.asarray(angles, dtype=float)


def directional_rate(phase, s, s_rate, step=DIRECTIONAL_STEP):
    """Rate of any function of the line of sight, by a centred difference along its motion.

    For a natural source the feed rotation of every receiver is a function of
    :math:`\\hat{s}` alone (a `~astropy_feedrot.MirrorTrain`'s traced phase,
    for instance): its rate is the derivative along :math:`\\dot{\\hat{s}}`,
    computed here without any further transformation of coordinates.

    Parameters
    ----------
    phase : callable
        ``phase(s)`` -> angles in radians (or an angle
        `~astropy.units.Quantity`) for unit vectors ``s`` of shape (..., 3).
    s, s_rate : array-like, shape (..., 3)
        Unit line of sight in ITRS and its rate in rad/s.
    step : float, optional
        Half the difference interval in radians along the motion (default
        `DIRECTIONAL_STEP`).

    Returns
    -------
    ndarray, shape (...)
        :math:`|\\dot{\\hat{s}}|\\,(\\Phi(\\hat{s}_+) - \\Phi(\\hat{s}_-)) /
        2\\,\\mathrm{step}` in rad/s, the difference wrapped to
        :math:`(-\\pi, \\pi]`, with :math:`\\hat{s}_\\pm` the unit vectors of
        :math:`\\hat{s} \\pm \\mathrm{step}\\,\\dot{\\hat{s}} /
        |\\dot{\\hat{s}}|`; 0 where the line of sight does not move, NaN where
        either phase is NaN.

    Raises
    ------
    TypeError
        If ``phase`` is not callable or ``step`` not a number.
    ValueError
        If ``step`` is not positive and finite, or the vectors are malformed.
    astropy.units.UnitsError
        If ``phase`` returns a quantity that is not an angle.

    Notes
    -----
    The truncation error is :math:`\\mathrm{step}^2\\,|\\Phi'''|/6` and the
    rounding error about :math:`\\epsilon_\\Phi/\\mathrm{step}`, both in units
    of :math:`|\\dot{\\hat{s}}|`, with :math:`\\Phi'''` the third derivative
    along the motion (about :math:`1/\\sin^3\\theta` at an angle
    :math:`\\theta` from a singular direction) and :math:`\\epsilon_\\Phi
    \\approx 3 \\times 10^{-16}` rad the rounding of the angle. For a natural
    source (:math:`|\\dot{\\hat{s}}| \\le \\omega`) at the default step of
    3e-7 rad they add up to 1e-13 rad/s beyond 5 deg from a singular
    direction, 8e-13 rad/s at 1 deg and 3e-12 rad/s at 0.5 deg (measured on
    the mirror trains of Appendix C against the closed forms they trace to).

    Examples
    --------
    The parallactic angle as a function of the line of sight, against its
    analytic rate:

    >>> import numpy as np
    >>> from astropy_feedrot.earth.frames import LocalFrame
    >>> from astropy_feedrot.core.kernel import receiver_term
    >>> from astropy_feedrot.engine.rates import (directional_rate, fixed_axis_rate,
    ...                                    source_direction_rate)
    >>> enu = LocalFrame(*np.eye(3))
    >>> s = np.array([0.3, -0.5, 0.6]) / np.linalg.norm([0.3, -0.5, 0.6])
    >>> s_rate = source_direction_rate(s)
    >>> numeric = directional_rate(lambda v: receiver_term(v, enu.up), s, s_rate)
    >>> bool(abs(numeric - fixed_axis_rate(s, s_rate, enu.up)) < 1e-12)
    True
    """
    phase = _callable(phase)
    step = _step(step, "step", u.rad)
    s = _vectors(s, "s")
    s_rate = _vectors(s_rate, "s_rate")
    speed = np.sqrt(dot(s_rate, s_rate))
    with np.errstate(invalid="ignore", divide="ignore"):
        direction = np.where(speed[..., np.newaxis] > 0,
                             s_rate / speed[..., np.newaxis], 0.0)
    ahead = s + step * direction
    behind = s - step * direction
    ahead = ahead / np.sqrt(dot(ahead, ahead))[..., np.newaxis]
    behind = behind / np.sqrt(dot(behind, behind))[..., np.newaxis]
    change = wrap_phase(_radians(phase(ahead)) - _radians(phase(behind)))
    return speed * change / (2 * step)


def difference_rate(phase, obstime, step=DIFFERENCE_STEP, span=None):
    """Rate of any time-dependent angle, by a centred difference in time.

    The general path: for satellites (whose attitude turns the transmitter's
    dipoles), Beyerle's form (Eq 30) and anything else without a closed form,
    e.g. ``difference_rate(lambda t: antenna.feed_rotation(target, t), obstime)``.

    Parameters
    ----------
    phase : callable
        ``phase(obstime)`` -> angles, an angle `~astropy.units.Quantity` (such
        as the `~astropy.coordinates.Angle` of
        `~astropy_feedrot.Antenna.feed_rotation`) or plain radians.
    obstime : `~astropy.time.Time`
        Epoch(s) at which to take the rate. Masked epochs give NaN.
    step : float or `~astropy.units.Quantity`, optional
        Half the difference interval, in seconds (default `DIFFERENCE_STEP`).
    span : tuple of `~astropy.time.Time`, optional
        ``(start, stop)`` outside which ``phase`` cannot be evaluated (the
        coverage of an orbit file, `~astropy_feedrot.SP3Orbit.coverage`).
        Epochs within ``step`` of either end take a one-sided difference
        over ``step`` that stays inside (first order: an error of
        :math:`h|\\ddot\\Phi|/2`).

    Returns
    -------
    ndarray
        :math:`(\\Phi(t + h) - \\Phi(t - h)) / 2h` in rad/s, the difference of
        the angles wrapped to :math:`(-\\pi, \\pi]` (correct while the angle
        turns by less than half a turn in :math:`2h`: below 157 rad/s at the
        default step), with the shape ``phase`` returns.

    Raises
    ------
    TypeError
        If ``phase`` is not callable, ``obstime`` not a time or ``step`` not a
        number.
    ValueError
        If ``step`` is not positive and finite.
    astropy.units.UnitsError
        If ``step`` is not a time or ``phase`` returns a quantity that is not an
        angle.

    Warns
    -----
    Whatever ``phase`` warns, once per category, and one
    `~astropy_feedrot.StaleEarthOrientationWarning` for both evaluations.

    Notes
    -----
    The truncation error is :math:`h^2|\\Phi'''|/6` and the rounding error
    about :math:`\\epsilon_\\Phi/h`. For a natural source or a GNSS satellite
    the angle changes on a time scale :math:`\\sin\\theta/\\omega`, with
    :math:`\\theta` the angle from the nearest singular direction, so
    :math:`|\\Phi'''| \\approx |\\dot\\Phi|\\,(\\omega/\\sin\\theta)^2`:
    7e-8 rad/s^3 at 1 deg from the zenith of an alt-az mount, where
    :math:`h^2|\\Phi'''|/6` is 1e-12 rad/s at the default :math:`h` = 0.01 s.
    The angles of astropy's transformation scatter as if the epochs were
    rounded to about 2e-10 s, :math:`\\epsilon_\\Phi \\approx 2 \\times
    10^{-10}\\,\\mathrm{s} \\times |\\dot\\Phi|`: 5e-13 rad at 1 deg from the
    zenith, 5e-11 rad/s over :math:`h`. (Measured there against the analytic
    rate: 5e-10 rad/s at :math:`h` = 1 ms, 1e-10 rad/s from 3 to 30 ms,
    where the analytic model's own error dominates, 7e-10 rad/s at 0.3 s.)
    Satellites in low orbits turn faster (up to 0.02 rad/s overhead at
    400 km, a time scale of 1 s at 1 deg from an axis) and want a step of
    about 1 ms there.

    The two evaluations must come from one smooth function of time. The
    fast path's interpolated Earth orientation is (it gives the rates of the
    rigorous path to 3e-13 rad/s for natural sources, 2e-12 rad/s for GPS).

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.engine.rates import difference_rate
    >>> start = Time("2023-01-25T00:00")
    >>> def phase(t):  # an angle turning at 1 deg per minute
    ...     return ((t - start).to(u.min).value % 360 - 180) * u.deg
    >>> rate = difference_rate(phase, start + [10, 180] * u.min)
    >>> rate * 60 / np.radians(1.0)  # doctest: +FLOAT_CMP
    array([1., 1.])
    """
    phase = _callable(phase)
    step = _step(step, "step", u.s)
    obstime = as_time(obstime)
    forward = np.full(obstime.shape, step)
    backward = np.full(obstime.shape, -step)
    if span is not None:
        start, stop = (as_time(end) for end in span)
        filled, _ = fill_masked(obstime)
        backward[(filled - start).to_value(u.s) < step] = 0.0
        forward[(stop - filled).to_value(u.s) < step] = 0.0
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with iers_context(obstime):  # one check of the tables for both evaluations
            ahead = _radians(phase(obstime + forward * u.s))
            behind = _radians(phase(obstime + backward * u.s))
    seen = set()
    for warning in caught:  # each category once (the two evaluations warn alike)
        if warning.category not in seen:
            seen.add(warning.category)
            warn_caller(str(warning.message), warning.category)
    with np.errstate(invalid="ignore", divide="ignore"):  # a span shorter than the step
        return wrap_phase(ahead - behind) / (forward - backward)
