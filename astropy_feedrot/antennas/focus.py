# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Focus types: what the optics between the sky and the feed add to the feed rotation.

Conventional foci (prime, Cassegrain, Gregorian) add nothing (Eq 13). A full
Nasmyth focus adds the elevation (Eq 38) and a beam-waveguide focus the
elevation and the azimuth (Eq 39), with a sign fixed by the handedness of the
third mirror. A `MirrorTrain` traces the wave's effective dipole through any
sequence of mirrors (Eqs 42-45) and reproduces those closed forms.

A focus declares what it adds through `Focus.closed_form`: the multiples of
the elevation and the azimuth, evaluated by `closed_form_phase`, or None for
optics traced mirror by mirror in `Focus.receiver_phase`. The
`~astropy_feedrot.engine.equations` reads that declaration; a new focus type plugs in
there once, and every front-end has it.
"""

import numpy as np

from ..core import kernel
from ..earth.frames import horizontal
from .mounts import AltAzMount, FixedAxisMount

__all__ = [
    "Focus",
    "PrimeFocus",
    "CassegrainFocus",
    "GregorianFocus",
    "NasmythFocus",
    "BeamWaveguideFocus",
    "MirrorTrain",
    "as_focus",
    "closed_form_phase",
]

HANDEDNESS = ("right", "left")

# Tolerance on the orthonormality of user-given feed dipoles.
_ORTHONORMAL_TOL = 1e-6


class Focus:
    """Base class of focus types.

    A focus turns the effective dipole :math:`t` of the arriving wave into the
    phase measured at the feed of a tracking antenna. A subclass says what it
    adds through `closed_form`; only a focus without a closed form (None)
    overrides `receiver_phase`, to trace its optics. A subclass that defines
    its own `receiver_phase` and no `closed_form` has none: its phase is
    always computed by its `receiver_phase`.

    Examples
    --------
    A focus whose beam leaves the telescope down its azimuth axis into a room
    fixed to the ground (the beam-waveguide form, Eq 39, right-handed):

    >>> from astropy_feedrot import Focus
    >>> class CoudeFocus(Focus):
    ...     closed_form = (1, -1)
    >>> CoudeFocus().closed_form
    (1, -1)
    """

    #: Multiples :math:`(m_E, m_A)` of the elevation and the azimuth that the
    #: focus adds to the feed rotation of its mount, :math:`\Phi = \Phi_{13}
    #: + m_E E + m_A A` (Eqs 13, 38, 39): (0, 0) for a prime, Cassegrain or
    #: Gregorian focus, (+-1, 0) for a right/left Nasmyth focus, (+-1, -+1) for
    #: a right/left beam waveguide. None for optics traced mirror by mirror
    #: (`MirrorTrain`), whose `receiver_phase` does the tracing.
    closed_form = (0, 0)

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        # Its own receiver_phase and no closed form of its own: it computes its phase.
        if "receiver_phase" in vars(cls) and "closed_form" not in vars(cls):
            cls.closed_form = None

    def __eq__(self, other):
        return type(self) is type(other) and self._key() == other._key()

    def __hash__(self):
        return hash((type(self), self._key()))

    def _key(self):
        return ()

    def __repr__(self):
        return f"{type(self).__name__}()"

    def check_mount(self, mount, local):
        """Raise if this focus cannot be used with ``mount``.

        Parameters
        ----------
        mount : `~astropy_feedrot.antennas.mounts.Mount`
            The mount of the antenna.
        local : `~astropy_feedrot.earth.frames.LocalFrame`
            East, north and up vectors of the site.

        Raises
        ------
        ValueError
            If the combination is not defined.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot import CassegrainFocus, EquatorialMount
        >>> from astropy_feedrot.earth.frames import LocalFrame
        >>> CassegrainFocus().check_mount(EquatorialMount(), LocalFrame(*np.eye(3)))
        """

    def receiver_phase(self, s, t, axis, local):
        """Phase at the feed of the arriving effective dipole, in radians.

        A focus with a `closed_form` evaluates it here
        (`closed_form_phase`); one without overrides this method to trace its
        optics, and `~astropy_feedrot.engine.equations` calls it for that focus only.

        Parameters
        ----------
        s : ndarray, shape (..., 3)
            Source unit vectors in ITRS.
        t : ndarray, shape (..., 3)
            Effective dipole of the arriving wave (Eq 8; :math:`P\\hat{z}` for a
            natural source, Eq 11).
        axis : ndarray, shape (..., 3)
            Fixed-axis unit vector of the mount in ITRS.
        local : `~astropy_feedrot.earth.frames.LocalFrame`
            East, north and up vectors of the site.

        Returns
        -------
        ndarray, shape (...)
            The feed rotation :math:`\\Phi` (RCP), NaN where undefined.

        Examples
        --------
        An alt-az telescope with a Cassegrain focus measures the parallactic
        angle; here a source due west at latitude 45 deg (local frame):

        >>> import numpy as np
        >>> from astropy_feedrot import CassegrainFocus
        >>> from astropy_feedrot.earth.frames import LocalFrame
        >>> from astropy_feedrot.core.kernel import project
        >>> enu = LocalFrame(*np.eye(3))
        >>> s = np.array([-1.0, 0.0, 0.0])
        >>> t = project([0.0, np.sqrt(0.5), np.sqrt(0.5)], s)
        >>> phi = CassegrainFocus().receiver_phase(s, t, enu.up, enu)
        >>> float(np.degrees(phi))  # doctest: +FLOAT_CMP
        45.0
        """
        form = self.closed_form
        if form is None:
            raise NotImplementedError(
                f"{self!r} has no closed form (closed_form is None), so it must trace its "
                "optics: override receiver_phase(s, t, axis, local)"
            )
        return closed_form_phase(s, t, axis, local, *form)


def closed_form_phase(s, t, axis, local, elevation_multiple=0, azimuth_multiple=0):
    """Feed rotation of a tracking antenna whose focus has a closed form (Eqs 13, 38, 39).

    Parameters
    ----------
    s : ndarray, shape (..., 3)
        Source unit vectors in ITRS.
    t : ndarray, shape (..., 3), or None
        Effective dipole of the arriving wave (Eq 8); None for a natural
        source, whose dipole is the projected pole :math:`P\\hat{z}` (Eq 11).
    axis : ndarray, shape (..., 3)
        Fixed-axis unit vector of the mount in ITRS.
    local : `~astropy_feedrot.earth.frames.LocalFrame`
        East, north and up vectors of the site (of shape (..., 3)).
    elevation_multiple, azimuth_multiple : float or ndarray, optional
        The multiples :math:`(m_E, m_A)` of `Focus.closed_form`, broadcast
        with the shape (...).

    Returns
    -------
    ndarray, shape (...)
        :math:`\\Phi = \\mathrm{atan2}(\\hat{s}\\cdot(\\hat{a}\\times t),\\;
        \\hat{a}\\cdot t) + m_E E + m_A A` in radians (RCP), wrapped to
        :math:`(-\\pi, \\pi]`: Eq 13 with the fixed axis :math:`\\hat{a}` (Eq 7
        with a satellite's dipole, Eq 35), plus the terms of the optics (Eqs
        38-41). NaN where undefined.

    Examples
    --------
    A right-handed Nasmyth focus adds the elevation (Eq 38): 45 deg here.

    >>> import numpy as np
    >>> from astropy_feedrot.antennas.focus import closed_form_phase
    >>> from astropy_feedrot.earth.frames import LocalFrame
    >>> from astropy_feedrot.core.kernel import project
    >>> enu = LocalFrame(*np.eye(3))
    >>> s = np.array([-1.0, 0.0, 1.0]) / np.sqrt(2)  # west, 45 deg high
    >>> t = project([0.0, 0.0, 1.0], s)  # a pole at the zenith: Psi = 0
    >>> float(np.degrees(closed_form_phase(s, t, enu.up, enu, 1, 0)))  # doctest: +FLOAT_CMP
    45.0
    """
    if t is None:
        phase = kernel.receiver_term(s, axis)  # Eq 13
    else:
        phase = kernel.wu_phase(s, axis, t)  # Eqs 7, 35
    if np.any(elevation_multiple) or np.any(azimuth_multiple):
        azimuth, elevation = horizontal(s, local)
        phase = kernel.wrap_phase(phase + elevation_multiple * elevation
                                  + azimuth_multiple * azimuth)
    return phase


class PrimeFocus(Focus):
    """Feed at the prime focus: no term beyond the mount's (Eq 13).

    Examples
    --------
    >>> from astropy_feedrot import PrimeFocus
    >>> PrimeFocus()
    PrimeFocus()
    """


class CassegrainFocus(Focus):
    """Feed at a Cassegrain focus: no term beyond the mount's (Eq 13).

    Examples
    --------
    >>> from astropy_feedrot import CassegrainFocus
    >>> CassegrainFocus() == CassegrainFocus()
    True
    """


class GregorianFocus(Focus):
    """Feed at a Gregorian focus: no term beyond the mount's (Eq 13).

    Examples
    --------
    >>> from astropy_feedrot import GregorianFocus
    >>> GregorianFocus()
    GregorianFocus()
    """


class _HandedFocus(Focus):
    """A closed-form focus of an alt-az antenna with a handed third mirror."""

    def __init__(self, handedness):
        if handedness not in HANDEDNESS:
            raise ValueError(
                f"{type(self).__name__} handedness must be one of {HANDEDNESS}, "
                f"got {handedness!r}"
            )
        self._handedness = handedness

    @property
    def handedness(self):
        """``'right'`` or ``'left'``: the handedness of the third mirror."""
        return self._handedness

    @property
    def sign(self):
        """+1 for a right-handed, -1 for a left-handed third mirror."""
        return 1 if self._handedness == "right" else -1

    def _key(self):
        return (self._handedness,)

    def __repr__(self):
        return f"{type(self).__name__}(handedness={self._handedness!r})"

    def check_mount(self, mount, local):
        if not isinstance(mount, AltAzMount):
            raise ValueError(
                f"{type(self).__name__} is defined for an AltAzMount (its extra terms "
                f"are elevation and azimuth), not for {mount!r}; describe other optics "
                "with a MirrorTrain"
            )


class NasmythFocus(_HandedFocus):
    """Full Nasmyth focus of an alt-az antenna (Eq 38).

    The feed sits in a cabin that turns in azimuth but not in elevation; the
    feed rotation is :math:`\\Psi + E` for a right-handed third mirror and
    :math:`\\Psi - E` for a left-handed one (:math:`E` the elevation), as in
    casacore, HOPS and PolConvert.

    Parameters
    ----------
    handedness : {'right', 'left'}
        Handedness of the reflection at the third mirror (YEBES40M: right).

    Raises
    ------
    ValueError
        For another ``handedness``.

    Examples
    --------
    >>> from astropy_feedrot import NasmythFocus
    >>> NasmythFocus("right").sign
    1
    """

    @property
    def closed_form(self):
        """``(sign, 0)``: plus or minus the elevation (Eq 38)."""
        return (self.sign, 0)


class BeamWaveguideFocus(_HandedFocus):
    """Beam-waveguide focus of an alt-az antenna (Eq 39).

    The feed is fixed to the ground; the feed rotation is
    :math:`\\Psi + E - A` for a right-handed third mirror and
    :math:`\\Psi - E + A` for a left-handed one (:math:`A` the azimuth from
    north through east), as casacore's ``BWG-R`` and ``BWG-L``.

    Parameters
    ----------
    handedness : {'right', 'left'}
        Handedness of the reflection at the third mirror (WARK30M: right).

    Raises
    ------
    ValueError
        For another ``handedness``.

    Examples
    --------
    >>> from astropy_feedrot import BeamWaveguideFocus
    >>> BeamWaveguideFocus("left")
    BeamWaveguideFocus(handedness='left')
    """

    @property
    def closed_form(self):
        """``(sign, -sign)``: plus or minus elevation minus azimuth (Eq 39)."""
        return (self.sign, -self.sign)


def _as_vectors(values, name):
    try:
        array = np.array(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numbers, got {values!r}") from None
    if array.ndim == 1:
        array = array[np.newaxis]
    if array.ndim != 2 or array.shape[-1] != 3 or len(array) == 0:
        raise ValueError(f"{name} must be one or more 3-vectors, got shape {np.shape(values)}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite, got {values!r}")
    return array


def _split(v):
    """The three components of vectors (..., 3)."""
    return v[..., 0], v[..., 1], v[..., 2]


def _components_dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _components_cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _components_unit(v):
    """``v / |v|``, NaN where ``|v|`` is degenerate (as `~astropy_feedrot.core.kernel.unit`)."""
    norm = np.sqrt(_components_dot(v, v))
    with np.errstate(invalid="ignore", divide="ignore"):
        norm = np.where(norm < kernel.DEGENERATE_NORM, np.nan, norm)
    return tuple(c / norm for c in v)


class MirrorTrain(Focus):
    """A feed behind a train of mirrors, traced reflection by reflection (Eqs 42-45).

    The wave arrives along :math:`\\hat{k}_1 = -\\hat{s}` after the primary and
    secondary mirrors (whose two phase flips cancel, Appendix C.1). Each
    further wave vector defines one more mirror (its normal by Eq 42), at which
    the effective dipole is reflected with a phase flip (Eqs 43, 44). The phase
    is then read by the feed's dipoles with Eq 45. After an odd number of
    mirrors the correlator relabels the hands, and the angle is negated
    (Sec. 3.2), not shifted by 180 deg.

    Wave vectors and feed dipoles are given in the antenna's local frame of
    Eq C15, :math:`(\\hat{\\xi}, \\hat{\\eta}, \\hat{u})`: :math:`\\hat{u}` the
    fixed axis of the mount (the local vertical of an alt-az mount),
    :math:`\\hat{\\xi}` the direction of the source projected on the plane
    perpendicular to it, and :math:`\\hat{\\eta} = \\hat{u} \\times
    \\hat{\\xi}`.

    Parameters
    ----------
    wave_vectors : array-like, shape (N, 3)
        :math:`\\hat{k}_2, \\ldots, \\hat{k}_{N+1}` in
        :math:`(\\hat{\\xi}, \\hat{\\eta}, \\hat{u})` components (normalized
        here); the last one is the wave entering the feed. ``N`` is the number
        of mirrors after the secondary.
    feed_aligned, feed_transverse : array-like of 3 floats
        The feed's aligned and transverse dipoles: an orthonormal pair with
        ``feed_aligned x feed_transverse`` (the boresight) along
        :math:`-\\hat{k}_{N+1}`. In :math:`(\\hat{\\xi}, \\hat{\\eta},
        \\hat{u})` components if ``feed_rotates``, else in east-north-up ones.
    feed_rotates : bool, optional
        True (default) if the feed turns with the antenna in azimuth (Nasmyth
        cabin); False if it is fixed to the ground (beam waveguide), in which
        case the last wave vector must lie along the fixed axis.
    name : str, optional
        A label for the train.

    Raises
    ------
    ValueError
        If a wave vector is zero or two consecutive ones are equal (no mirror
        between them), if the feed dipoles are not an orthonormal,
        right-handed pair facing the last wave vector, or if a ground-fixed feed
        does not receive the beam along the fixed axis.

    Notes
    -----
    The traced angle equals the closed forms up to a constant that depends on
    which feed dipole is called aligned: the ready-made
    `yebes40m` trains trace to :math:`\\Psi + E + c` (Nasmyth right, Eq 38)
    and `wark30m` to :math:`\\Psi + E - A + c` (beam waveguide right,
    Eq 39), with the constants :math:`c` given in their docstrings. A
    constant is absorbed by the clock in phase analyses.

    Examples
    --------
    The simplest Nasmyth focus: one tertiary mirror sends the beam along the
    elevation axis to the telescope's right (:math:`-\\hat{\\eta}`, as
    :math:`\\hat{\\eta} = \\hat{u} \\times \\hat{\\xi}` points to its left), into a
    feed that faces it. One reflection is odd, so the angle is negated; the
    result is the right-handed Nasmyth form :math:`\\Psi + E` plus 180 deg.

    >>> from astropy_feedrot import MirrorTrain
    >>> train = MirrorTrain([[0, -1, 0]], feed_aligned=[0, 0, 1], feed_transverse=[1, 0, 0])
    >>> train.reflections
    1
    >>> train
    MirrorTrain(<1 mirrors>, feed_rotates=True)
    """

    #: No closed form: the mirrors are traced (`receiver_phase`).
    closed_form = None

    def __init__(self, wave_vectors, feed_aligned, feed_transverse, feed_rotates=True, name=None):
        k = _as_vectors(wave_vectors, "wave_vectors")
        norms = np.linalg.norm(k, axis=-1)
        if np.any(norms == 0):
            raise ValueError(f"wave vector {int(np.argmin(norms)) + 2} has zero length")
        k = k / norms[:, np.newaxis]
        for i in range(len(k) - 1):
            if np.allclose(k[i], k[i + 1], atol=1e-12):
                raise ValueError(
                    f"wave vectors k_{i + 2} and k_{i + 3} are equal: there is no mirror "
                    "between them"
                )
        fa = _as_vectors(feed_aligned, "feed_aligned")
        ft = _as_vectors(feed_transverse, "feed_transverse")
        if fa.shape != (1, 3) or ft.shape != (1, 3):
            raise ValueError("feed_aligned and feed_transverse must each be one 3-vector")
        fa, ft = fa[0], ft[0]
        for label, v in (("feed_aligned", fa), ("feed_transverse", ft)):
            if abs(np.linalg.norm(v) - 1) > _ORTHONORMAL_TOL:
                raise ValueError(
                    f"{label} must be a unit vector, got length {np.linalg.norm(v):.9g}"
                )
        if abs(fa @ ft) > _ORTHONORMAL_TOL:
            raise ValueError(
                f"feed dipoles must be orthogonal, got feed_aligned . feed_transverse = "
                f"{fa @ ft:.3g}"
            )
        k_out = k[-1]
        boresight = np.cross(fa, ft)
        if not feed_rotates:
            if abs(abs(k_out[2]) - 1) > _ORTHONORMAL_TOL:
                raise ValueError(
                    "a feed fixed to the ground must receive the beam along the fixed "
                    f"axis, i.e. a last wave vector (0, 0, +-1); got {k_out}"
                )
        elif np.linalg.norm(boresight + k_out) > _ORTHONORMAL_TOL:
            raise ValueError(
                "the feed must face the arriving wave: feed_aligned x feed_transverse "
                f"= {boresight} must equal -k_out = {-k_out + 0.0} (a right-handed triad with "
                "the boresight against the last wave vector)"
            )
        for array in (k, fa, ft):
            array.flags.writeable = False
        self._k = k
        self._fa = fa
        self._ft = ft
        self._rotates = bool(feed_rotates)
        self.name = name

    @property
    def wave_vectors(self):
        """The unit wave vectors after the secondary mirror, shape (N, 3)."""
        return self._k

    @property
    def feed_aligned(self):
        """The feed's aligned dipole (local or east-north-up components)."""
        return self._fa

    @property
    def feed_transverse(self):
        """The feed's transverse dipole (local or east-north-up components)."""
        return self._ft

    @property
    def feed_rotates(self):
        """Whether the feed turns with the antenna in azimuth."""
        return self._rotates

    @property
    def reflections(self):
        """Number of mirrors traced (after the secondary)."""
        return len(self._k)

    def _key(self):
        return (self._k.tobytes(), self._fa.tobytes(), self._ft.tobytes(), self._rotates)

    def __repr__(self):
        label = f", name={self.name!r}" if self.name else ""
        return (
            f"MirrorTrain(<{self.reflections} mirrors>, feed_rotates={self._rotates}{label})"
        )

    def check_mount(self, mount, local):
        if not isinstance(mount, FixedAxisMount):
            raise ValueError(
                f"a MirrorTrain needs a steerable mount with a fixed axis, not {mount!r}"
            )
        if not self._rotates:
            axis = mount.fixed_axis(local)
            boresight = sum(c * v for c, v in zip(np.cross(self._fa, self._ft), local))
            if np.linalg.norm(boresight + self._k[-1][2] * axis) > _ORTHONORMAL_TOL:
                raise ValueError(
                    "the ground-fixed feed must face the arriving wave: feed_aligned x "
                    "feed_transverse (east-north-up) must point along -k_out, i.e. "
                    f"{'down' if self._k[-1][2] > 0 else 'up'} the fixed axis of {mount!r}"
                )

    def receiver_phase(self, s, t, axis, local):
        """Phase at the feed, traced through the mirrors (Eqs 42-45).

        The waves after the first mirror are fixed in the frame
        :math:`(\\hat{\\xi}, \\hat{\\eta}, \\hat{u})`, so the reflections
        after the first are one constant matrix and, for a feed that turns
        with the antenna, the read-out of Eq 45 two constant vectors; only the
        first mirror (between :math:`-\\hat{s}` and :math:`\\hat{k}_2`) is
        computed at each line of sight. This is the same trace as the kernel's
        `~astropy_feedrot.core.kernel.trace_dipole` and
        `~astropy_feedrot.core.kernel.feed_phase` wave by wave, to rounding.

        Parameters
        ----------
        s, t, axis, local
            As for `Focus.receiver_phase`.

        Returns
        -------
        ndarray, shape (...)
            The feed rotation (RCP) in radians; negated after an odd number
            of mirrors (Sec. 3.2). NaN where undefined.

        Examples
        --------
        The one-mirror Nasmyth train of the class example, for a source due
        west at 45 deg elevation seen from a pole at the zenith: the
        right-handed Nasmyth form (45 deg) plus 180 deg.

        >>> import numpy as np
        >>> from astropy_feedrot import MirrorTrain
        >>> from astropy_feedrot.earth.frames import LocalFrame
        >>> from astropy_feedrot.core.kernel import project
        >>> enu = LocalFrame(*np.eye(3))
        >>> train = MirrorTrain([[0, -1, 0]], feed_aligned=[0, 0, 1],
        ...                     feed_transverse=[1, 0, 0])
        >>> s = np.array([-1.0, 0.0, 1.0]) / np.sqrt(2)
        >>> phi = train.receiver_phase(s, project([0.0, 0, 1], s), enu.up, enu)
        >>> float(np.degrees(phi))  # doctest: +FLOAT_CMP
        -135.0
        """
        s, t = (_split(np.asarray(v, dtype=float)) for v in (s, t))
        return self.receiver_phase_from_components(s, t, axis, local)

    def receiver_phase_from_components(self, s, t, axis, local):
        """`receiver_phase` with the lines of sight and dipoles given by components.

        Parameters
        ----------
        s, t : tuple of 3 ndarray, each shape (...)
            The x, y and z components (ITRS) of the unit lines of sight and of
            the arriving effective dipoles.
        axis : array-like, shape (3,)
            The mount's fixed axis.
        local : `~astropy_feedrot.earth.frames.LocalFrame`
            The site's east, north and up.

        Returns
        -------
        ndarray, shape (...)
            As `receiver_phase`.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot import MirrorTrain
        >>> from astropy_feedrot.earth.frames import LocalFrame
        >>> enu = LocalFrame(*np.eye(3))
        >>> train = MirrorTrain([[0, -1, 0]], feed_aligned=[0, 0, 1],
        ...                     feed_transverse=[1, 0, 0])
        >>> r = np.sqrt(0.5)
        >>> phi = train.receiver_phase_from_components((-r, 0.0, r), (r, 0.0, r), enu.up, enu)
        >>> float(np.degrees(phi))  # doctest: +FLOAT_CMP
        -135.0
        """
        axis = np.asarray(axis, dtype=float)
        # The frame (xi, eta, u) at each line of sight; the waves after the first
        # mirror are fixed in it, so every mirror but the first is one constant
        # matrix (`_fixed_mirrors`), and Eq 45 two constant vectors.
        u = tuple(axis[..., i] for i in range(3))
        eta = _components_unit(_components_cross(u, s))
        xi = _components_cross(eta, u)
        frame = (xi, eta, u)
        s_f = [_components_dot(s, c) for c in frame]
        t_f = [_components_dot(t, c) for c in frame]
        # The first mirror, between -s and k_2 (Eqs 42-44): q = 2 (t.n) n / |n|^2 - t.
        k = self._k[0]
        n = [k[i] + s_f[i] for i in range(3)]
        nn = _components_dot(n, n)
        with np.errstate(invalid="ignore", divide="ignore"):
            scale = 2.0 * _components_dot(t_f, n) / np.where(
                nn < kernel.DEGENERATE_NORM**2, np.nan, nn)
        q = [scale * n[i] - t_f[i] for i in range(3)]
        if self._rotates:
            a, b = self._read_out
            num, den = _components_dot(q, a), _components_dot(q, b)
        else:  # the feed's dipoles are fixed in east-north-up: in (xi, eta, u) here
            m = self._fixed_mirrors
            q = [m[i, 0] * q[0] + m[i, 1] * q[1] + m[i, 2] * q[2] for i in range(3)]
            k_out = self._k[-1]
            enu = [_split(d[0] * local.east + d[1] * local.north + d[2] * local.up)
                   for d in (self._fa, self._ft)]
            ra, rt = ([_components_dot(d, c) for c in frame] for d in enu)
            kq = _components_cross(k_out, q)
            num = _components_dot(ra, kq) + _components_dot(rt, q)
            den = _components_dot(ra, q) - _components_dot(rt, kq)
        defined = _components_dot(q, q) >= kernel.DEGENERATE_NORM**2
        with np.errstate(invalid="ignore"):
            phi = np.where(defined, np.arctan2(num, den), np.nan)
        return -phi if self.reflections % 2 else phi

    @property
    def _fixed_mirrors(self):
        """The mirrors after the first as one matrix in (xi, eta, u) (Eqs 42-44)."""
        m = np.eye(3)
        for k_in, k_out in zip(self._k[:-1], self._k[1:]):
            n = (k_out - k_in) / np.linalg.norm(k_out - k_in)
            m = -(np.eye(3) - 2.0 * np.outer(n, n)) @ m
        return m

    @property
    def _read_out(self):
        """Eq 45 for a feed turning with the antenna: ``(a, b)`` with the phase
        ``atan2(q1 . a, q1 . b)`` of the dipole ``q1`` after the first mirror."""
        m, k_out = self._fixed_mirrors, self._k[-1]
        # r_a . (k x q) + r_t . q = q . (r_a x k + r_t); r_a . q - r_t . (k x q) likewise
        a = np.cross(self._fa, k_out) + self._ft
        b = self._fa - np.cross(self._ft, k_out)
        return m.T @ a, m.T @ b

    @classmethod
    def yebes40m(cls, band="X"):
        """The full Nasmyth optics of the Yebes 40 m telescope (Appendix C.1).

        Parameters
        ----------
        band : {'X', 'S', 'C'}
            ``'S'`` and ``'C'``: feeds behind mirrors M3-M5 (three reflections,
            Eqs C16-C17, :math:`\\alpha = 51.15^\\circ`); ``'X'``: the feed behind
            the dichroic mirror M6 (four reflections, :math:`\\beta =
            53.87^\\circ`), with the transverse dipole
            :math:`\\hat{u}\\cos\\beta - \\hat{\\xi}\\sin\\beta` (Eq C18 as
            printed has :math:`\\hat{\\eta}`, which is not orthogonal to the
            wave).

        Returns
        -------
        MirrorTrain

        Raises
        ------
        ValueError
            For another band.

        Notes
        -----
        All three bands trace to :math:`\\Psi + E + 90^\\circ` (Nasmyth right,
        Eq 38, plus a constant quarter turn set by the choice of aligned
        dipole), to better than 1e-9 rad over the sky.

        Examples
        --------
        >>> from astropy_feedrot import MirrorTrain
        >>> MirrorTrain.yebes40m("S").reflections
        3
        """
        bands = ("X", "S", "C")
        if band not in bands:
            raise ValueError(f"YEBES40M band must be one of {bands}, got {band!r}")
        alpha = np.radians(51.15)
        beta = np.radians(53.87)
        waves = [[0, -1, 0], [-1, 0, 0], [np.cos(alpha), 0, -np.sin(alpha)]]
        if band == "X":
            waves.append([-np.cos(beta), 0, -np.sin(beta)])
            aligned, transverse = [0, 1, 0], [-np.sin(beta), 0, np.cos(beta)]
        else:
            aligned, transverse = [0, -1, 0], [np.sin(alpha), 0, np.cos(alpha)]
        return cls(waves, aligned, transverse, feed_rotates=True, name=f"YEBES40M {band}")

    @classmethod
    def wark30m(cls):
        """The slanted beam waveguide of the Warkworth 30 m telescope (Appendix C.2).

        Four mirrors after the secondary (Eq C19), the last sending the beam
        down the azimuth axis to a feed fixed to the ground with its aligned
        dipole east and transverse dipole north (Eq C20).

        Returns
        -------
        MirrorTrain

        Notes
        -----
        Traces to :math:`\\Psi + E - A + c` (beam waveguide right, Eq 39) with
        the constant :math:`c = 2\\arctan(2500/9500) - 180^\\circ \\approx
        -150.51^\\circ`, set by the slant of the third wave vector, to better
        than 1e-9 rad over the sky.

        Examples
        --------
        >>> from astropy_feedrot import MirrorTrain
        >>> MirrorTrain.wark30m().feed_rotates
        False
        """
        waves = [[0, -1, 0], [-2500, 0, -9500], [0, 1, 0], [0, 0, -1]]
        return cls(waves, [1, 0, 0], [0, 1, 0], feed_rotates=False, name="WARK30M")


def as_focus(focus, name="focus"):
    """Check that a value is a focus instance.

    Parameters
    ----------
    focus : object
        The value to check.
    name : str, optional
        How to call it in error messages.

    Returns
    -------
    Focus
        ``focus`` itself.

    Raises
    ------
    TypeError
        If ``focus`` is a focus class rather than an instance, or not a
        `Focus` at all.

    Examples
    --------
    >>> from astropy_feedrot.antennas.focus import NasmythFocus, as_focus
    >>> as_focus(NasmythFocus("right"))
    NasmythFocus(handedness='right')
    """
    if isinstance(focus, type) and issubclass(focus, Focus):
        raise TypeError(f"{name} must be an instance; did you mean {focus.__name__}()?")
    if not isinstance(focus, Focus):
        raise TypeError(
            f"{name} must be a Focus instance (e.g. CassegrainFocus(), NasmythFocus('right')), "
            f"got {type(focus).__name__}"
        )
    return focus
