# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The receivers of the wind-up engine: what each antenna declares, read once.

`Receivers` turns the mounts, foci and rotators of A antennas (or the plain
arrays of `ReceiverArrays`) into arrays: stations, local axes, fixed axes,
dipoles, focus terms, and the groups of receivers that share an equation
(stationary crossed dipoles, fixed-axis mounts with a closed-form focus,
mirror trains traced, rotators). `~astropy_feedrot.engine.equations` evaluates the
feed rotation from them.
"""

from typing import NamedTuple

import numpy as np

from ..antennas.focus import CassegrainFocus, as_focus
from ..antennas.mounts import as_mount
from ..antennas.rotators import as_rotator
from ..earth.frames import LocalFrame

__all__ = ["ReceiverArrays", "Receivers"]


class ReceiverArrays(NamedTuple):
    """The receiving antennas of a grid as plain arrays (the inputs of `grid.wind_up`).

    Attributes
    ----------
    station_xyz : ndarray, shape (A, 3)
        Geocentric ITRS positions in metres.
    station_axes : ndarray, shape (A, 3, 3)
        East, north and up unit vectors of each site in ITRS (rows). A
        stationary crossed dipole has its aligned dipole east and its
        transverse dipole north (Eq 28).
    stationary : ndarray of bool, shape (A,)
        True for a crossed dipole fixed to the ground, False for a tracking
        antenna.
    fixed_axis : ndarray, shape (A, 3)
        The fixed axis of each tracking mount in ITRS (Eq 10; ignored for a
        stationary one).
    focus_terms : ndarray, shape (A, 2)
        Multiples of the elevation and the azimuth a focus adds: (0, 0) for a
        prime, Cassegrain or Gregorian focus, (+-1, 0) for a right/left
        Nasmyth focus (Eq 38), (+-1, -+1) for a right/left beam waveguide
        (Eq 39).

    Examples
    --------
    >>> from astropy_feedrot.engine.grid import receiver_arrays
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> arrays = receiver_arrays([get_antenna("DBR205"), get_antenna("FD-VLBA")])
    >>> arrays.stationary.tolist()
    [True, False]
    """

    station_xyz: np.ndarray
    station_axes: np.ndarray
    stationary: np.ndarray
    fixed_axis: np.ndarray
    focus_terms: np.ndarray


def _closed_form(focus):
    """The closed form of a focus as two floats, or None; TypeError/ValueError if malformed."""
    form = focus.closed_form
    if form is None:
        return None
    try:
        multiples = tuple(float(value) for value in form)
    except (TypeError, ValueError):
        raise TypeError(f"{focus!r}.closed_form must be None or two numbers (the multiples of "
                        f"elevation and azimuth), got {form!r}") from None
    if len(multiples) != 2 or not all(np.isfinite(multiples)):
        raise ValueError(f"{focus!r}.closed_form must be None or two finite numbers (the "
                         f"multiples of elevation and azimuth), got {form!r}")
    return multiples


def _unit_vector(value, what):
    vector = np.asarray(value, dtype=float)
    if vector.shape != (3,) or not np.all(np.isfinite(vector)):
        raise ValueError(f"{what} must be three finite numbers, got {value!r}")
    return vector


class Receivers:
    """The receivers of A antennas, sorted by the equation each one needs.

    Build it from the mounts and foci of the antennas with `from_mounts`, or
    from plain arrays with `from_arrays`.

    Parameters
    ----------
    station_xyz : ndarray, shape (A, 3)
        Geocentric ITRS positions in metres.
    station_axes : ndarray, shape (A, 3, 3)
        East, north and up unit vectors of each site in ITRS (rows).
    stationary : ndarray of bool, shape (A,)
        True for a receiver that does not track (crossed dipoles fixed to the
        ground), False for a tracking one.
    dipoles : ndarray, shape (A, 2, 3)
        Aligned and transverse dipoles of the stationary receivers in ITRS
        (ignored for the others).
    fixed_axis : ndarray, shape (A, 3)
        Fixed axis of the tracking mounts in ITRS (ignored for the others).
    focus_terms : ndarray, shape (A, 2)
        Multiples of elevation and azimuth of each tracking receiver's focus
        (`Focus.closed_form <astropy_feedrot.Focus.closed_form>`; ignored for
        the traced ones).
    traced : dict, optional
        ``{index: focus}`` for tracking receivers whose focus has no closed
        form: the engine calls ``focus.receiver_phase`` for them.
    rotators : dict, optional
        ``{index: rotator}`` for tracking receivers with a
        `~astropy_feedrot.Rotator`.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot import AltAzMount, NasmythFocus, StationaryMount
    >>> from astropy_feedrot.engine.equations import Receivers
    >>> enu = np.eye(3)[np.newaxis].repeat(2, axis=0)
    >>> xyz = np.array([[0.0, 0, 6.4e6], [0.0, 0, 6.4e6]])
    >>> rx = Receivers.from_mounts(xyz, enu, [StationaryMount(), AltAzMount()],
    ...                            [None, NasmythFocus("left")])
    >>> rx.stationary.tolist(), rx.focus_terms.tolist()
    ([True, False], [[0.0, 0.0], [-1.0, 0.0]])
    """

    def __init__(self, station_xyz, station_axes, stationary, dipoles, fixed_axis, focus_terms,
                 traced=None, rotators=None):
        self.station_xyz = np.asarray(station_xyz, dtype=float)
        self.station_axes = np.asarray(station_axes, dtype=float)
        self.stationary = np.asarray(stationary, dtype=bool)
        self.dipoles = np.asarray(dipoles, dtype=float)
        self.fixed_axis = np.asarray(fixed_axis, dtype=float)
        self.focus_terms = np.asarray(focus_terms, dtype=float)
        self.traced = dict(traced or {})
        tracking = ~self.stationary
        tracking[list(self.traced)] = False
        terms = np.any(self.focus_terms != 0, axis=-1)
        # The groups of receivers that share an equation.
        self.stationary_index = np.flatnonzero(self.stationary)
        self.plain_index = np.flatnonzero(tracking & ~terms)
        self.focus_index = np.flatnonzero(tracking & terms)
        self.traced_index = np.array(sorted(self.traced), dtype=int)
        # Rotators: their angles (radians, 0 for 'series' and none) and modes.
        self.rotators = dict(rotators or {})
        self.rotator_angle = np.zeros(len(self.station_xyz))
        modes = {"sky": [], "fixed": [], "series": []}
        for i, rotator in sorted(self.rotators.items()):
            if self.stationary[i]:
                raise ValueError(f"receiver {i} does not track: a rotator turns the feed of a "
                                 "tracking antenna, and a stationary crossed dipole has none")
            modes[rotator.mode].append(i)
            if rotator.mode != "series":
                self.rotator_angle[i] = rotator.radians
        self.sky_index, self.fixed_index, self.series_index = (
            np.array(modes[mode], dtype=int) for mode in ("sky", "fixed", "series"))

    def __len__(self):
        return len(self.station_xyz)

    def __repr__(self):
        return (f"<Receivers: {len(self)} antennas, {self.stationary_index.size} stationary, "
                f"{self.plain_index.size + self.focus_index.size} closed-form, "
                f"{self.traced_index.size} traced, {len(self.rotators)} with rotators>")

    @classmethod
    def from_mounts(cls, station_xyz, station_axes, mounts, foci, rotators=None):
        """The receivers of antennas from their sites, mounts, foci and rotators.

        Parameters
        ----------
        station_xyz : array-like, shape (A, 3)
            Geocentric ITRS positions in metres.
        station_axes : array-like, shape (A, 3, 3)
            East, north and up unit vectors of each site in ITRS (rows).
        mounts : sequence of `~astropy_feedrot.antennas.mounts.Mount`
            A mount that tracks gives ``fixed_axis(local)``; one that does not
            gives ``dipoles(local)``.
        foci : sequence of `~astropy_feedrot.antennas.focus.Focus` or None
            Each focus's ``closed_form``, or its ``receiver_phase`` if that is
            None; None is a Cassegrain focus.
        rotators : sequence of `~astropy_feedrot.Rotator` or None, optional
            One per antenna (None: no rotator); only tracking mounts take one.

        Returns
        -------
        Receivers

        Raises
        ------
        TypeError
            If a mount or focus is not one, a tracking mount has no
            ``fixed_axis`` (or a stationary one no ``dipoles``), or a
            ``closed_form`` is not two numbers.
        ValueError
            If a mount that does not track has a focus that adds terms or a
            rotator, or a closed form or an axis is not finite.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot import AltAzMount, MirrorTrain
        >>> from astropy_feedrot.engine.equations import Receivers
        >>> rx = Receivers.from_mounts([[0.0, 0, 6.4e6]], [np.eye(3)], [AltAzMount()],
        ...                            [MirrorTrain.wark30m()])
        >>> rx.traced_index.tolist()
        [0]
        """
        xyz = np.asarray(station_xyz, dtype=float)
        axes = np.asarray(station_axes, dtype=float)
        n = len(xyz)
        stationary = np.zeros(n, dtype=bool)
        dipoles = np.full((n, 2, 3), np.nan)
        fixed_axis = np.full((n, 3), np.nan)
        terms = np.zeros((n, 2))
        traced = {}
        turned = {}
        rotators = [None] * n if rotators is None else list(rotators)
        for i, (mount, focus, rotator) in enumerate(zip(mounts, foci, rotators)):
            rotator = as_rotator(rotator)
            mount = as_mount(mount)
            focus = CassegrainFocus() if focus is None else as_focus(focus)
            local = LocalFrame(*axes[i])
            form = _closed_form(focus)
            if mount.tracks:
                if not callable(getattr(mount, "fixed_axis", None)):
                    raise TypeError(f"{mount!r} tracks but has no fixed_axis(local): a tracking "
                                    "mount turns about an axis fixed to the ground (see "
                                    "FixedAxisMount)")
                fixed_axis[i] = _unit_vector(mount.fixed_axis(local),
                                             f"the fixed axis of {mount!r}")
                if form is None:
                    traced[i] = focus
                else:
                    terms[i] = form
                if rotator is not None:
                    turned[i] = rotator
                continue
            if rotator is not None:
                raise ValueError(f"a {type(mount).__name__} does not track: a rotator turns the "
                                 "feed of a tracking antenna about the line of sight; give "
                                 "rotator=None")
            if form != (0.0, 0.0):
                raise ValueError(f"a {type(mount).__name__} has no optics to add terms; "
                                 f"{focus!r} needs a steerable mount")
            if not callable(getattr(mount, "dipoles", None)):
                raise TypeError(f"{mount!r} does not track but has no dipoles(local): a "
                                "stationary mount gives its aligned and transverse dipoles "
                                "(see StationaryMount)")
            aligned, transverse = mount.dipoles(local)[:2]
            stationary[i] = True
            dipoles[i] = (_unit_vector(aligned, f"the aligned dipole of {mount!r}"),
                          _unit_vector(transverse, f"the transverse dipole of {mount!r}"))
        return cls(xyz, axes, stationary, dipoles, fixed_axis, terms, traced, turned)

    @classmethod
    def from_arrays(cls, arrays):
        """The receivers described by plain arrays.

        Parameters
        ----------
        arrays : ReceiverArrays
            Checked arrays; a stationary receiver has its aligned dipole east
            and its transverse dipole north (Eq 28).

        Returns
        -------
        Receivers

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot.engine.equations import ReceiverArrays, Receivers
        >>> rx = Receivers.from_arrays(ReceiverArrays(
        ...     np.array([[6.4e6, 0, 0]]), np.eye(3)[np.newaxis], np.array([True]),
        ...     np.array([[0.0, 0, 1]]), np.zeros((1, 2))))
        >>> rx.dipoles[0, 1]
        array([0., 1., 0.])
        """
        axes = np.asarray(arrays.station_axes, dtype=float)
        return cls(arrays.station_xyz, axes, arrays.stationary, axes[:, :2],
                   arrays.fixed_axis, arrays.focus_terms)

    def as_arrays(self):
        """The receivers as `ReceiverArrays`, or None if some have no such description.

        Traced foci, rotators, and stationary dipoles other than east and
        north, have none.

        Returns
        -------
        ReceiverArrays or None

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot import AltAzMount, BeamWaveguideFocus
        >>> from astropy_feedrot.engine.equations import Receivers
        >>> rx = Receivers.from_mounts([[0.0, 0, 6.4e6]], [np.eye(3)], [AltAzMount()],
        ...                            [BeamWaveguideFocus("left")])
        >>> rx.as_arrays().focus_terms
        array([[-1.,  1.]])
        """
        if self.traced or self.rotators or not np.array_equal(
                self.dipoles[self.stationary], self.station_axes[self.stationary, :2]):
            return None
        fixed_axis = np.where(self.stationary[:, np.newaxis], self.station_axes[:, 2],
                              self.fixed_axis)
        return ReceiverArrays(self.station_xyz, self.station_axes, self.stationary, fixed_axis,
                              self.focus_terms)

    def unrepresentable(self):
        """Indices of the receivers that `as_arrays` cannot describe.

        Returns
        -------
        ndarray of int

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot import AltAzMount, MirrorTrain
        >>> from astropy_feedrot.engine.equations import Receivers
        >>> Receivers.from_mounts([[0.0, 0, 6.4e6]], [np.eye(3)], [AltAzMount()],
        ...                       [MirrorTrain.wark30m()]).unrepresentable().tolist()
        [0]
        """
        other = np.any(self.dipoles != self.station_axes[:, :2], axis=(1, 2)) & self.stationary
        other[self.traced_index] = True
        other[list(self.rotators)] = True
        return np.flatnonzero(other)
