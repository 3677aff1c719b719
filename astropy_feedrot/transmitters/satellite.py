# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""A transmitting satellite: an orbit, an attitude and a circular polarization."""

import warnings

import numpy as np

from ..core import kernel
from ..core.exceptions import warn_caller
from ..core.inputs import MIN_GEOCENTRIC_DISTANCE
from ..core.polarization import polarization_sign
from ..earth.eop import iers_context
from ..earth.epochs import as_epochs
from ..earth.frames import as_location, fill_masked, location_xyz
from .attitude_interface import Attitude
from .nominal_attitude import NominalAttitude
from .orbits import as_orbit, check_orientation

__all__ = ["Satellite", "LineOfSight", "check_transmitter_positions"]


class LineOfSight:
    """The geometry of one receiver seeing one transmitter, as Earth-fixed vectors.

    Attributes
    ----------
    s : ndarray, shape (..., 3)
        Source unit vector, receiver to transmitter (Eq 2).
    aligned, transverse : ndarray, shape (..., 3)
        The transmitter's dipoles, or None for a natural source.
    t : ndarray, shape (..., 3)
        The transmitter's effective dipole (Eq 8; Eq 11 for a natural source).

    Examples
    --------
    A natural source at the ITRS x axis: its effective dipole is the projected
    celestial pole.

    >>> import numpy as np
    >>> from astropy_feedrot import LineOfSight
    >>> LineOfSight(np.array([1.0, 0.0, 0.0])).t
    array([0., 0., 1.])
    """

    def __init__(self, s, aligned=None, transverse=None):
        self.s = s
        self.aligned = aligned
        self.transverse = transverse

    @property
    def t(self):
        """The transmitter's effective dipole (Eq 8; Eq 11 for a natural source)."""
        return kernel.transmitter_dipole(self.s, self.aligned, self.transverse)


class Satellite:
    """A satellite transmitting a circularly polarized signal.

    Usable as the ``target`` of `~astropy_feedrot.Antenna.feed_rotation`.

    Parameters
    ----------
    orbit : `~astropy_feedrot.transmitters.orbits.Orbit` or `~astropy.coordinates.SkyCoord`
        Where the satellite is: a `TLEOrbit`, an `SP3Orbit`, or positions
        with a distance.
    attitude : `~astropy_feedrot.transmitters.nominal_attitude.Attitude`, optional
        How its antenna is oriented: `NominalAttitude` (default) or
        `QuaternionAttitude`.
    polarization : {'RCP', 'LCP'}, optional
        The hand it transmits (GNSS: RCP; GENESIS may be LCP).
    name : str, optional

    Raises
    ------
    TypeError
        If ``orbit`` or ``attitude`` is of the wrong kind.
    ValueError
        For an unknown ``polarization``.

    Notes
    -----
    The line of sight is the plain difference of Earth-fixed positions
    (Eq 2), at the reception time; the light time (~0.07 s for a GNSS
    satellite) moves the direction by less than an arcsecond and is neglected,
    as in the paper.

    Examples
    --------
    >>> from astropy_feedrot import Satellite, TLEOrbit
    >>> gps = Satellite(TLEOrbit(
    ...     "1 41328U 16007A   23024.39332179  .00000015  00000-0  00000+0 0  9995",
    ...     "2 41328  54.9577 138.7050 0066950 231.2234 128.1638  2.00560135 51012"),
    ...     name="GPS SVN 76")
    >>> gps
    <Satellite 'GPS SVN 76' TLEOrbit, NominalAttitude(), RCP>
    """

    def __init__(self, orbit, attitude=None, polarization="RCP", name=None):
        self.orbit = as_orbit(orbit)
        if attitude is None:
            attitude = NominalAttitude()
        if isinstance(attitude, type):
            raise TypeError(f"attitude must be an instance; did you mean {attitude.__name__}()?")
        if not isinstance(attitude, Attitude):
            raise TypeError(
                "attitude must be a NominalAttitude or QuaternionAttitude instance, got "
                f"{type(attitude).__name__}"
            )
        self.attitude = attitude
        self.sign = polarization_sign(polarization)
        self.polarization = "RCP" if self.sign > 0 else "LCP"
        self.name = name
        # The last positions and dipoles, for other antennas at the same epochs.
        self._transmitter = None

    def __repr__(self):
        label = f"{self.name!r} " if self.name else ""
        return (f"<Satellite {label}{type(self.orbit).__name__}, {self.attitude!r}, "
                f"{self.polarization}>")

    def receiver_sign(self, polarization):
        """The sign of the feed rotation for a receiver of hand ``polarization``.

        Parameters
        ----------
        polarization : {'RCP', 'LCP'} or None
            The receiver's hand; None for the satellite's own.

        Returns
        -------
        int
            +1 for RCP, -1 for LCP.

        Raises
        ------
        ValueError
            If the receiver's hand is not the satellite's: it does not receive
            this signal.

        Examples
        --------
        >>> from astropy_feedrot import Satellite, TLEOrbit
        >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
        >>> Satellite(TLEOrbit(*GPS_SVN76_TLE)).receiver_sign(None)
        1
        """
        if polarization is None:
            return self.sign
        sign = polarization_sign(polarization)
        if sign != self.sign:
            raise ValueError(
                f"an {'RCP' if sign > 0 else 'LCP'} receiver does not receive the "
                f"{self.polarization} signal of {self!r}; use "
                f"polarization={self.polarization!r} (or leave it unset)"
            )
        return sign

    @iers_context()  # one check of the Earth-orientation tables per call
    def position(self, obstime, orientation=None):
        """Geocentric ITRS position in metres (see `Orbit.position`).

        Parameters
        ----------
        obstime : `~astropy.time.Time`
            Epoch(s); masked epochs give NaN.
        orientation : `~astropy_feedrot.earth.orientation.EarthOrientation`, optional
            Earth orientation at exactly these epochs (built from the
            epochs with masked ones filled as
            `~astropy_feedrot.earth.frames.fill_masked` does), if one is at hand.

        Returns
        -------
        ndarray, shape obstime.shape + (3,)

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import ITRS, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Satellite
        >>> sat = Satellite(SkyCoord(ITRS(x=2.6e7 * u.m, y=0 * u.m, z=0 * u.m,
        ...                               representation_type="cartesian")))
        >>> sat.position(Time("2023-01-25"))  # doctest: +FLOAT_CMP
        array([26000000.,        0.,        0.])
        """
        filled, masked = fill_masked(obstime)
        check_orientation(orientation, filled)
        return self._position(filled, masked, orientation)

    def _position(self, filled, masked, orientation):
        """Positions at the filled epochs, NaN at the masked ones."""
        if masked is not None and masked.all():
            return np.full(filled.shape + (3,), np.nan)
        if filled.size == 0:  # nothing to compute (astropy 6.0 fails on empty epochs)
            return np.empty(filled.shape + (3,))
        position = np.asarray(self.orbit.position(filled, orientation), dtype=float)
        check_transmitter_positions(position, self.name or type(self.orbit).__name__)
        if masked is not None:
            position = np.where(masked[..., np.newaxis], np.nan, position)
        return position

    @iers_context()  # one check of the Earth-orientation tables per call
    def line_of_sight(self, location, obstime):
        """Source vector and transmitter dipoles seen from a site.

        Parameters
        ----------
        location : `~astropy.coordinates.EarthLocation`
            The receiver's site.
        obstime : `~astropy.time.Time`
            Epoch(s). Masked epochs give NaN vectors (which give NaN angles
            without a warning).

        Returns
        -------
        LineOfSight

        Notes
        -----
        Where the fast path applies (`~astropy_feedrot.earth.orientation.fast_path_applies`) one
        `~astropy_feedrot.earth.orientation.EarthOrientation` of the epochs serves the
        orbit (TEME to ITRS, for orbits with ``uses_orientation``) and the
        attitude (the Sun, interpolated from its nodes, for models with
        ``needs_sun``); it is built only if one of them uses it.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import EarthLocation, ITRS, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Satellite
        >>> sat = Satellite(SkyCoord(ITRS(x=2.6e7 * u.m, y=0 * u.m, z=0 * u.m,
        ...                               representation_type="cartesian")))
        >>> site = EarthLocation.from_geocentric(6.378e6, 0, 0, unit=u.m)
        >>> sat.line_of_sight(site, Time("2023-01-25")).s
        array([1., 0., 0.])
        """
        location = as_location(location)
        epochs = as_epochs(obstime)
        filled, masked = epochs.filled, epochs.mask
        if masked is not None and masked.all():
            s = np.full(filled.shape + (3,), np.nan)
            return LineOfSight(s, s, s)
        if filled.size == 0:  # nothing to compute (astropy 6.0 fails on empty epochs)
            s = np.empty(filled.shape + (3,))
            return LineOfSight(s, s, s)
        orientation = None
        if self.orbit.uses_orientation or self.attitude.needs_sun:
            orientation = _earth_orientation(epochs)
        position, aligned, transverse = self._transmitter_at(filled, masked, orientation)
        s = kernel.unit(position - location_xyz(location))
        if masked is not None:
            aligned = np.where(masked[..., np.newaxis], np.nan, aligned)
            transverse = np.where(masked[..., np.newaxis], np.nan, transverse)
        return LineOfSight(s, aligned, transverse)

    def _transmitter_at(self, filled, masked, orientation):
        """Positions and dipoles at the epochs, shared by the antennas that ask in turn.

        With an Earth orientation (`~astropy_feedrot.earth.orientation.orientation_of`
        gives one object per set of epochs and IERS table) the last result is
        kept; another antenna at the same epochs reuses it, and the warnings
        of the orbit and the attitude are given again, as a new computation
        would give them. Copies are returned, so the kept arrays stay as
        computed.
        """
        key = (orientation, self.orbit, self.attitude)
        kept = self._transmitter
        if orientation is None or kept is None or any(a is not b for a, b in zip(kept[0], key)) \
                or not np.array_equal(kept[1], masked if masked is not None else False):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                position = self._position(filled, masked, orientation)
                aligned, transverse = (v[0] for v in Attitude.dipoles_many(
                    [self.attitude], filled, position[np.newaxis], orientation))
            said = [(str(w.message), w.category) for w in caught]
            kept = (key, masked if masked is not None else False, position, aligned,
                    transverse, said)
            if orientation is not None:
                self._transmitter = kept
        for message, category in kept[5]:
            warn_caller(message, category)
        return tuple(np.array(v) for v in kept[2:5])


def check_transmitter_positions(xyz, label):
    """Refuse orbit positions inside the Earth.

    Parameters
    ----------
    xyz : ndarray, shape (..., 3)
        Geocentric ITRS positions in metres; NaN (missing) passes.
    label : str
        How to name the transmitter in the message.

    Raises
    ------
    ValueError
        If a position is closer to the geocentre than
        `~astropy_feedrot.core.inputs.MIN_GEOCENTRIC_DISTANCE` (6,300 km; the
        Earth's polar radius is 6,357 km): kilometres read as metres, or an
        orbit that is not one.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.transmitters.satellite import check_transmitter_positions
    >>> check_transmitter_positions(np.array([2.6e7, 0, 0]), "G01")
    >>> check_transmitter_positions(np.array([1.0e6, 0, 0]), "G01")
    Traceback (most recent call last):
    ...
    ValueError: the orbit of G01 puts it 1000 km from the geocentre, inside the Earth, ...
    """
    with np.errstate(invalid="ignore"):
        radius = np.sqrt(np.einsum("...i,...i->...", xyz, xyz))
        inside = radius < MIN_GEOCENTRIC_DISTANCE.to_value("m")  # False for NaN
    if np.any(inside):
        closest = float(np.min(radius[inside]))
        raise ValueError(
            f"the orbit of {label} puts it {closest / 1e3:.0f} km from the geocentre, inside "
            f"the Earth, at {np.count_nonzero(inside)} of {inside.size} epochs; orbit "
            "positions are geocentric, in metres (kilometres given as metres?)")


def _earth_orientation(epochs):
    """The Earth orientation of `~astropy_feedrot.Epochs` where it serves, else None."""
    return epochs.orientation if epochs.uses_nodes() else None
