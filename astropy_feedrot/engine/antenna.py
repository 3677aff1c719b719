# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""An antenna: a site, a mount, a focus and a rotator, and its feed rotation.

`Antenna` is the wind-up engine (`~astropy_feedrot.engine.equations`) for one antenna:
it turns a target and epochs into lines of sight, lets the engine pick and
evaluate the equation its mount and focus call for, and returns angles.
"""

from typing import NamedTuple

import numpy as np
from astropy import units as u
from astropy.coordinates import Angle

from ..antennas.focus import CassegrainFocus, as_focus
from ..antennas.mounts import as_mount
from ..antennas.receptors import Receptors
from ..antennas.rotators import as_rotator
from ..core import kernel
from ..earth.eop import iers_context
from ..earth.epochs import as_epochs
from ..earth.frames import (
    VERTICALS,
    as_elevation_limit,
    as_location,
    check_station_xyz,
    horizontal,
    local_frame,
    location_xyz,
    source_direction,
)
from ..ionosphere.faraday import faraday_rotation, polarization_rotation
from ..transmitters.satellite import Satellite
from . import equations, rates

__all__ = ["Antenna", "FeedRotationTerms", "AntennaAngles"]


class FeedRotationTerms(NamedTuple):
    """The feed rotation split into transmitter and receiver terms (Eq 20).

    Attributes
    ----------
    transmitter : `~astropy.coordinates.Angle`
        :math:`\\Phi_\\mathrm{tx}` (Eq 21): the transmitter's effective dipole
        measured from the projected north celestial pole; 0 for a natural
        source.
    receiver : `~astropy.coordinates.Angle`
        :math:`\\Phi_\\mathrm{rx}` (Eq 22 and the focus terms): the receiver's
        feed measured from the same reference, i.e. its feed rotation for a
        natural source in the same direction.
    total : `~astropy.coordinates.Angle`
        Their sum, wrapped to (-180, 180] deg: the effective-dipole (Wu) form of
        the feed rotation (Eq 7).

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> terms = get_antenna("WETTZ13S").feed_rotation_terms(
    ...     SkyCoord("03h19m48.16s +41d30m42.1s"), Time("2023-01-25T22:00"))
    >>> float(abs(terms.transmitter.deg)) < 1e-9  # a natural source
    True
    """

    transmitter: Angle
    receiver: Angle
    total: Angle


class AntennaAngles(NamedTuple):
    """Every angle of an antenna observing a target, from one line of sight.

    Attributes
    ----------
    azimuth, elevation : `~astropy.coordinates.Angle`
        As `Antenna.altaz`.
    parallactic_angle : `~astropy.coordinates.Angle`
        As `Antenna.parallactic_angle` (Eq 15).
    transmitter, receiver : `~astropy.coordinates.Angle`
        The terms of `Antenna.feed_rotation_terms` (Eqs 21, 22).
    total : `~astropy.coordinates.Angle`
        As `Antenna.feed_rotation`.

    Examples
    --------
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> angles = get_antenna("WETTZ13S").angles(SkyCoord("03h19m48.16s +41d30m42.1s"),
    ...                                         Time("2023-01-25T22:00"))
    >>> angles._fields
    ('azimuth', 'elevation', 'parallactic_angle', 'transmitter', 'receiver', 'total')
    """

    azimuth: Angle
    elevation: Angle
    parallactic_angle: Angle
    transmitter: Angle
    receiver: Angle
    total: Angle


class _Sight(NamedTuple):
    """A line of sight: the direction, the transmitter's dipoles or None, and the
    angle of a 'series' rotator at its epochs (shape (..., 1)) or None."""

    s: np.ndarray
    aligned: np.ndarray
    transverse: np.ndarray
    rotation: np.ndarray = None


def _to_angle(radians):
    """Radians to an `~astropy.coordinates.Angle` in degrees; 0-d becomes scalar."""
    degrees = np.degrees(radians)
    return Angle(degrees[()] if degrees.ndim == 0 else degrees, u.deg, copy=False)


class Antenna:
    """A receiving antenna: where it is, how it is mounted, where its feed sits.

    Parameters
    ----------
    location : `~astropy.coordinates.EarthLocation`
        The antenna's reference point: a single site on the Earth, with a
        geodetic height between -12 and +100 km (see
        `~astropy_feedrot.earth.frames.STATION_HEIGHTS`).
    mount : `~astropy_feedrot.antennas.mounts.Mount`
        `AltAzMount`, `EquatorialMount`, `XYMount`, `FixedAxisMount` or
        `StationaryMount`.
    focus : `~astropy_feedrot.antennas.focus.Focus`, optional
        Where the feed sits: `CassegrainFocus` (default), `PrimeFocus`,
        `GregorianFocus`, `NasmythFocus`, `BeamWaveguideFocus` or a
        `MirrorTrain`. A `StationaryMount` takes only the conventional ones,
        which add nothing.
    name : str, optional
        A label (e.g. the station name).
    vertical : {'geodetic', 'geocentric'}, optional
        Definition of the local vertical (the alt-az axis, the GNSS boresight,
        the reference of azimuth and elevation). ``'geodetic'`` (default) is
        the ellipsoid normal, which a levelled antenna follows; ``'geocentric'``
        is :math:`r_\\mathrm{ant}/|r_\\mathrm{ant}|` as printed in Eq 28.
        CASA and casacore compute parallactic angles with the geocentric
        vertical (their ``AZEL`` frame); pass ``'geocentric'`` to reproduce
        them (see :doc:`/correcting`).
    receptors : `~astropy_feedrot.antennas.receptors.Receptors`, optional
        The receptors of the feed and their angles in the antenna, as
        visibility files give them; used to correct visibilities (see
        `~astropy_feedrot.applied.correction.correct_receptor_visibilities`). They
        do not change `feed_rotation`, which is that of the antenna's
        reference direction.
    rotator : `~astropy_feedrot.Rotator`, optional
        A rotator that turns the feed about the line of sight (beyond the
        paper): ``Rotator('sky')`` keeps the feed at a fixed angle on the sky
        (ASKAP's polarization axis), ``Rotator('fixed', angle)`` adds a
        constant, ``Rotator('series', times=..., angles=...)`` follows a log.
        Only a mount that tracks takes one. See :doc:`/rotators`.

    Raises
    ------
    TypeError
        If an argument is not of the expected kind.
    ValueError
        If ``location`` is not a single site, has a NaN or infinite
        coordinate, or is not an Earth station (the geocentre, coordinates in
        km read as m, a height beyond 100 km), for an unknown ``vertical``,
        if ``focus`` does not fit ``mount``, or for a rotator on a mount that
        does not track.

    Examples
    --------
    The parallactic angle of 3C 84 seen from the Wettzell 13 m telescope:

    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation, SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot import Antenna, AltAzMount
    >>> wettzell = EarthLocation.from_geocentric(4075659.180, 931824.551,
    ...                                          4801516.102, unit=u.m)
    >>> antenna = Antenna(wettzell, AltAzMount(), name="WETTZ13S")
    >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
    >>> antenna.feed_rotation(source, Time("2023-01-25T20:00"))  # doctest: +FLOAT_CMP
    <Angle 59.12271470 deg>
    """

    def __init__(self, location, mount, focus=None, name=None, vertical="geodetic",
                 receptors=None, rotator=None):
        self.location = as_location(location)
        if not self.location.isscalar:
            raise ValueError(
                f"an Antenna has one location, got an array of shape {self.location.shape}; "
                "make one Antenna per site"
            )
        self._xyz = xyz = location_xyz(self.location)
        check_station_xyz(xyz, "location")
        self.mount = as_mount(mount)
        self.focus = CassegrainFocus() if focus is None else as_focus(focus)
        if vertical not in VERTICALS:
            raise ValueError(f"vertical must be one of {VERTICALS}, got {vertical!r}")
        self.vertical = vertical
        self.name = name
        if receptors is not None and not isinstance(receptors, Receptors):
            raise TypeError(f"receptors must be a Receptors object (e.g. Receptors('RL')), "
                            f"got {type(receptors).__name__}")
        self.receptors = receptors
        self.rotator = as_rotator(rotator)
        self._local = local_frame(self.location, vertical=vertical)
        if self.mount.tracks:
            self.focus.check_mount(self.mount, self._local)
        # The engine's description of this one receiver (raises for optics or a
        # rotator on a mount that does not track).
        self._receivers = equations.Receivers.from_mounts(
            xyz[np.newaxis], np.stack(self._local)[np.newaxis], [self.mount], [self.focus],
            [self.rotator])

    def __repr__(self):
        label = f"{self.name!r}, " if self.name else ""
        x, y, z = location_xyz(self.location)
        return (
            f"<Antenna {label}({x:.3f}, {y:.3f}, {z:.3f}) m, {self.mount!r}, {self.focus!r}"
            + ("" if self.rotator is None else f", {self.rotator!r}")
            + ("" if self.receptors is None else f", {self.receptors!r}") + ">"
        )

    @property
    def local_frame(self):
        """East, north and up unit vectors of the site in ITRS.

        Returns
        -------
        `~astropy_feedrot.earth.frames.LocalFrame`
        """
        return self._local

    def _line_of_sight(self, target, obstime, series=True):
        """Direction, the transmitter's dipoles (None for a natural source) and the angle
        of a 'series' rotator (None without one, or without ``series``)."""
        if isinstance(target, Satellite):
            los = target.line_of_sight(self.location, obstime)
            sight = _Sight(los.s, los.aligned, los.transverse)
        else:
            sight = _Sight(source_direction(target, self.location, obstime), None, None)
        if series and self.rotator is not None and self.rotator.mode == "series":
            angle = self.rotator.radians_at(obstime)
            sight = sight._replace(rotation=np.broadcast_to(
                angle, sight.s.shape[:-1])[..., np.newaxis])
        return sight

    def _series_rotation(self, los):
        """The rotation to give the engine: 0 when a 'series' rotator is left out."""
        if los.rotation is None and self._receivers.series_index.size:
            return np.zeros(los.s.shape[:-1] + (1,))
        return los.rotation

    def _wind_up(self, los, form="beyerle", limit=None, terms=False):
        """The engine on the line of sight: feed rotation (or its terms) and ``below``.

        One antenna and one target per epoch: the engine's (..., A, S) axes are
        1 long and dropped again.
        """
        s = los.s[..., np.newaxis, np.newaxis, :]
        aligned = transverse = None
        if los.aligned is not None:
            aligned = los.aligned[..., np.newaxis, :]
            transverse = los.transverse[..., np.newaxis, :]
        rotation = self._series_rotation(los)
        if terms:
            *out, below = equations.feed_rotation_terms(self._receivers, s, aligned, transverse,
                                                        min_sine=equations.min_sine(limit),
                                                        rotation=rotation)
        else:
            *out, below = equations.feed_rotation(self._receivers, s, aligned, transverse,
                                                  form=form, min_sine=equations.min_sine(limit),
                                                  rotation=rotation)
        return [phase[..., 0, 0] for phase in out] + [None if below is None
                                                      else below[..., 0, 0]]

    def _describe(self):
        """The receiver, for warnings: mount, focus and rotator."""
        rotator = "" if self.rotator is None else f" and {self.rotator!r}"
        return f"{self.mount!r} with {self.focus!r}{rotator}"

    def _finish(self, phase, s, below=None, what="feed rotation"):
        """One warning about degenerate epochs; an Angle."""
        count = int(np.count_nonzero(equations.degenerate(phase, s, below)))
        equations.warn_degenerate(count, np.size(phase), what, "epochs", self._describe())
        return _to_angle(phase)

    @iers_context()  # one check of the Earth-orientation tables per call
    def feed_rotation(self, target, obstime, polarization=None, form=None,
                      min_elevation=None):
        """Feed rotation of the antenna observing a target.

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
            Natural source(s) in any celestial frame, or a satellite. A
            proper motion or radial velocity is applied from the coordinate's
            ``obstime`` (its catalogue epoch) to each epoch of observation
            (see `~astropy_feedrot.earth.frames.at_epochs`).
        obstime : `~astropy.time.Time` or `~astropy_feedrot.Epochs`
            Epoch(s) of observation (UTC scale or any other). Masked epochs
            give NaN, without a warning.
        polarization : {'RCP', 'LCP'}, optional
            Hand of the receiver: RCP by default for a natural source, the
            satellite's hand for a satellite. The LCP feed rotation is the
            negative of the RCP one (Sec. 3, Appendix D).
        form : {'beyerle', 'wu'}, optional
            For a `StationaryMount` seeing a satellite: the full crossed-dipole
            form (Eq 30, default) or the effective-dipole form (Eq 31). The two
            are identical for tracking antennas and natural sources.
        min_elevation : `~astropy.units.Quantity`, optional
            Return NaN (without warning) where the target is lower than this
            above the antenna's horizon: one angle in [-90, 90] deg. By
            default angles are computed for every epoch, below the horizon
            too.

        Returns
        -------
        `~astropy.coordinates.Angle`
            The feed rotation :math:`\\Phi` in degrees, in (-180, 180], with the
            broadcast shape of ``target`` and ``obstime`` (a scalar for scalar
            inputs); NaN where undefined. The value for ``polarization='LCP'``
            is the negative of the RCP one, so the returned angle is always
            *subtracted* from phases measured in that hand (Appendix D: RCP
            subtract :math:`\\Phi`, LCP add it).
            `~astropy_feedrot.applied.correction.correct_phase` takes the RCP value and
            the hand instead. For a continuous series see
            `~astropy_feedrot.unwrap`.

        Raises
        ------
        TypeError
            If ``target`` is not a coordinate, ``obstime`` not a time (plain
            numbers, a `~astropy.time.TimeDelta`), or ``min_elevation`` a
            plain number.
        ValueError
            For an unknown ``polarization`` or ``form``, a receiver hand that
            differs from a satellite's, a frame without data, a moving target
            without an epoch, shapes of ``target`` and ``obstime`` that do
            not broadcast, or a ``min_elevation`` that is NaN, not a single
            value or outside [-90, 90] deg.
        astropy.units.UnitsError
            If ``min_elevation`` is not an angle.

        Warns
        -----
        DegenerateGeometryWarning
            Once, with the count, if some epochs are degenerate.

        Notes
        -----
        For a natural source the transmitter's effective dipole is the
        projected celestial pole (Eq 11), and the feed rotation is the
        receiver term alone: Eq 13 for a fixed-axis mount (the parallactic
        angle Eq 15 for alt-az, 0 for equatorial), Eq 33 for a stationary
        crossed dipole, Eqs 38-39 for Nasmyth and beam-waveguide foci, and
        Eqs 42-45 for a `MirrorTrain`. For a satellite the transmitter's
        effective dipole (Eq 8) comes from its attitude; a telescope gives
        Eqs 35, 40 and 41, and a `MirrorTrain` traces that dipole through its
        mirrors. A `Rotator` then turns the receiver's effective dipole about
        the line of sight: :math:`\\Phi + \\rho` (``'fixed'``, ``'series'``),
        or :math:`\\rho_0` plus the transmitter term (``'sky'``); see
        :doc:`/rotators`.

        Examples
        --------
        The Yebes 40 m telescope (Nasmyth, right-handed third mirror) sees a
        feed rotation of parallactic angle plus elevation:

        >>> import astropy.units as u
        >>> from astropy.coordinates import EarthLocation, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Antenna, AltAzMount, NasmythFocus
        >>> yebes = EarthLocation.from_geodetic(-3.0869 * u.deg, 40.5247 * u.deg, 988 * u.m)
        >>> antenna = Antenna(yebes, AltAzMount(), NasmythFocus("right"))
        >>> times = Time("2023-01-25T20:00") + [0, 2, 4] * u.hour
        >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
        >>> antenna.feed_rotation(source, times)  # doctest: +FLOAT_CMP
        <Angle [174.60305791, 136.86281049, 103.27155036] deg>
        """
        obstime = as_epochs(obstime)  # converted once, handed down
        sign = equations.receiver_sign(target, polarization)
        limit = as_elevation_limit(min_elevation)
        form = equations.check_form(form)
        los = self._line_of_sight(target, obstime)
        phase, below = self._wind_up(los, form, limit)
        return self._finish(sign * phase, los.s, below)

    @iers_context()  # one check of the Earth-orientation tables per call
    def feed_rotation_terms(self, target, obstime, polarization=None, min_elevation=None):
        """The feed rotation split into a transmitter and a receiver term (Eqs 20-22).

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
            Natural source(s) or a satellite, as for `feed_rotation`.
        obstime : `~astropy.time.Time` or `~astropy_feedrot.Epochs`
            Epoch(s) of observation; masked epochs give NaN.
        polarization : {'RCP', 'LCP'}, optional
            As for `feed_rotation`; LCP flips the signs of both terms.
        min_elevation : `~astropy.units.Quantity`, optional
            As for `feed_rotation`.

        Returns
        -------
        FeedRotationTerms
            Named tuple ``(transmitter, receiver, total)`` of
            `~astropy.coordinates.Angle` in degrees; ``transmitter + receiver``
            equals ``total`` modulo 360 deg.

        Raises
        ------
        TypeError, ValueError, astropy.units.UnitsError
            As for `feed_rotation`.

        Notes
        -----
        The split is exact for the effective-dipole form (Eq 7). For a
        `StationaryMount` seeing a satellite, `feed_rotation` uses the
        crossed-dipole form (Eq 30) by default, which differs from ``total``
        by the receiver's cross-hand response (a few mrad for GNSS satellites).

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import EarthLocation
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Antenna, AltAzMount, Satellite, TLEOrbit
        >>> gps = Satellite(TLEOrbit(
        ...     "1 41328U 16007A   23024.39332179  .00000015  00000-0  00000+0 0  9995",
        ...     "2 41328  54.9577 138.7050 0066950 231.2234 128.1638  2.00560135 51012"))
        >>> fd = EarthLocation.from_geocentric(-1324009.454, -5332181.955, 3231962.369, u.m)
        >>> terms = Antenna(fd, AltAzMount()).feed_rotation_terms(gps, Time("2023-01-25T11:00"))
        >>> terms.total  # doctest: +FLOAT_CMP
        <Angle 41.41117014 deg>
        >>> sum_of_terms = terms.transmitter + terms.receiver
        >>> (sum_of_terms - terms.total).wrap_at(180 * u.deg)  # doctest: +FLOAT_CMP
        <Angle 0. deg>
        """
        obstime = as_epochs(obstime)  # converted once, handed down
        sign = equations.receiver_sign(target, polarization)
        limit = as_elevation_limit(min_elevation)
        return self._terms(self._line_of_sight(target, obstime), sign, limit)

    def _terms(self, los, sign, limit):
        transmitter, receiver, below = self._wind_up(los, limit=limit, terms=True)
        transmitter = self._finish(sign * transmitter, los.s, below, "transmitter term")
        receiver = self._finish(sign * receiver, los.s, below, "receiver term")
        total = kernel.wrap_phase(transmitter.rad + receiver.rad)
        return FeedRotationTerms(transmitter, receiver, _to_angle(total))

    @iers_context()  # one check of the Earth-orientation tables per call
    def parallactic_angle(self, target, obstime):
        """Parallactic angle of a target at the antenna's site (Eq 15).

        The feed rotation of an alt-az antenna with a conventional focus, and
        the first term of the Nasmyth and beam-waveguide forms. Positive west of
        the meridian, as ERFA's ``hd2pa``.

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
            Natural source(s) or a satellite, as for `feed_rotation`.
        obstime : `~astropy.time.Time` or `~astropy_feedrot.Epochs`
            Epoch(s) of observation; masked epochs give NaN.

        Returns
        -------
        `~astropy.coordinates.Angle`
            :math:`\\Psi` in degrees, broadcast shape of the inputs; NaN at the
            zenith and at the pole.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import EarthLocation, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Antenna, EquatorialMount
        >>> site = EarthLocation.from_geodetic(-3.0869 * u.deg, 40.5247 * u.deg, 988 * u.m)
        >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
        >>> antenna = Antenna(site, EquatorialMount())
        >>> antenna.parallactic_angle(source, Time("2023-01-25T22:00"))  # doctest: +FLOAT_CMP
        <Angle 77.88951063 deg>
        """
        obstime = as_epochs(obstime)  # converted once, handed down
        return self._parallactic_angle(self._line_of_sight(target, obstime).s)

    def _parallactic_angle(self, s):
        return self._finish(equations.parallactic_angle(s, self._local.up), s,
                            what="parallactic angle")

    @iers_context()  # one check of the Earth-orientation tables per call
    def altaz(self, target, obstime):
        """Azimuth and elevation of a target above the antenna's horizon.

        Azimuth from north through east, elevation above the plane normal to
        the antenna's vertical; no refraction.

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
            Natural source(s) or a satellite, as for `feed_rotation`.
        obstime : `~astropy.time.Time` or `~astropy_feedrot.Epochs`
            Epoch(s) of observation; masked epochs give NaN.

        Returns
        -------
        azimuth, elevation : `~astropy.coordinates.Angle`
            In degrees, broadcast shape of the inputs; azimuth in [0, 360).

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import EarthLocation, SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Antenna, AltAzMount
        >>> site = EarthLocation.from_geodetic(-3.0869 * u.deg, 40.5247 * u.deg, 988 * u.m)
        >>> az, el = Antenna(site, AltAzMount()).altaz(
        ...     SkyCoord("03h19m48.16s +41d30m42.1s"), Time("2023-01-25T22:00"))
        >>> round(float(el.deg), 3)
        58.973
        """
        obstime = as_epochs(obstime)  # converted once, handed down
        return self._altaz(self._line_of_sight(target, obstime).s)

    def _altaz(self, s):
        az, el = horizontal(s, self._local)
        return _to_angle(az), _to_angle(el)

    @iers_context()  # one check of the Earth-orientation tables per call
    def angles(self, target, obstime, polarization=None, form=None, min_elevation=None):
        """Every angle of the antenna observing a target, from one line of sight.

        The orbit is propagated (or the source's direction computed) once for
        all of them: what `~astropy_feedrot.applied.feed_rotation_tables.feed_rotation_table`
        tabulates.

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
            Natural source(s) or a satellite, as for `feed_rotation`.
        obstime : `~astropy.time.Time` or `~astropy_feedrot.Epochs`
            Epoch(s) of observation; masked epochs give NaN.
        polarization, form, min_elevation : optional
            As for `feed_rotation`; ``min_elevation`` masks the terms and the
            total, not the azimuth, elevation and parallactic angle.

        Returns
        -------
        AntennaAngles
            Named tuple ``(azimuth, elevation, parallactic_angle, transmitter,
            receiver, total)`` of `~astropy.coordinates.Angle` in degrees,
            each equal to what `altaz`, `parallactic_angle`,
            `feed_rotation_terms` and `feed_rotation` return.

        Raises
        ------
        TypeError, ValueError, astropy.units.UnitsError
            As for `feed_rotation`.

        Warns
        -----
        DegenerateGeometryWarning
            Once per angle that is undefined at some epochs.

        Examples
        --------
        >>> import numpy as np
        >>> import astropy.units as u
        >>> from astropy.coordinates import SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import NasmythFocus
        >>> from astropy_feedrot.stations.catalogue import get_antenna
        >>> yebes = get_antenna("YEBES40M", focus=NasmythFocus("right"))
        >>> times = Time("2023-01-25T20:00") + [0, 2] * u.hour
        >>> angles = yebes.angles(SkyCoord("03h19m48.16s +41d30m42.1s"), times)
        >>> difference = angles.total - angles.parallactic_angle - angles.elevation
        >>> bool(np.abs(difference.wrap_at(180 * u.deg).deg).max() < 1e-9)  # Eq 38
        True
        """
        obstime = as_epochs(obstime)  # converted once, handed down
        sign = equations.receiver_sign(target, polarization)
        limit = as_elevation_limit(min_elevation)
        form = equations.check_form(form)
        los = self._line_of_sight(target, obstime)
        azimuth, elevation = self._altaz(los.s)
        terms = self._terms(los, sign, limit)
        phase, below = self._wind_up(los, form, limit)
        return AntennaAngles(azimuth, elevation, self._parallactic_angle(los.s),
                             terms.transmitter, terms.receiver,
                             self._finish(sign * phase, los.s, below))

    @iers_context()  # one check of the Earth-orientation tables per call
    def rotation_measure(self, target, obstime, ionosphere):
        """Rotation measure of the ionosphere along the line of sight (rad m^-2).

        ``ionosphere`` is an `~astropy_feedrot.ionosphere.Ionosphere` (IONEX
        maps, or a table of rotation measures, looked up under this
        antenna's ``name``); NaN where the target is below the horizon. A
        source seen at intrinsic angle chi0 appears at chi0 + RM lambda^2
        (see :doc:`/ionosphere`).

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import SkyCoord
        >>> from astropy.table import QTable
        >>> from astropy.time import Time
        >>> from astropy_feedrot import get_antenna
        >>> from astropy_feedrot.ionosphere import Ionosphere
        >>> rm = QTable({"time": Time(["2024-06-01T20:00", "2024-06-01T22:00"]),
        ...              "rm": [1.0, 3.0] * u.rad / u.m**2})  # one series for every antenna
        >>> effelsberg, t = get_antenna("EFLSBERG"), Time("2024-06-01T21:00")
        >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
        >>> effelsberg.rotation_measure(source, t, Ionosphere.from_rm(rm))  # doctest: +FLOAT_CMP
        <Quantity 2. rad / m2>
        """
        return ionosphere.rotation_measure(self.location, target, as_epochs(obstime).time,
                                           antenna=self.name)

    def faraday_rotation(self, target, obstime, frequency, ionosphere):
        """Faraday rotation RM (c/nu)^2 of the wave's plane on the sky, per frequency.

        `rotation_measure` times the squared wavelength of each ``frequency``
        (epochs first, frequency last): the angle by which the ionosphere
        turns the polarization plane, positive from north through east.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import SkyCoord
        >>> from astropy.table import QTable
        >>> from astropy.time import Time
        >>> from astropy_feedrot import get_antenna
        >>> from astropy_feedrot.ionosphere import Ionosphere
        >>> rm = QTable({"time": Time(["2024-06-01T20:00", "2024-06-01T22:00"]),
        ...              "rm": [1.0, 3.0] * u.rad / u.m**2})  # one series for every antenna
        >>> effelsberg, t = get_antenna("EFLSBERG"), Time("2024-06-01T21:00")
        >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
        >>> effelsberg.faraday_rotation(source, t, [1.4, 5] * u.GHz,
        ...                             Ionosphere.from_rm(rm))  # doctest: +FLOAT_CMP
        <Angle [5.25457945, 0.41195902] deg>
        """
        return faraday_rotation(self.rotation_measure(target, obstime, ionosphere), frequency)

    def polarization_rotation(self, target, obstime, frequency, ionosphere=None, **kwargs):
        """The one angle a correction needs: feed rotation minus Faraday rotation.

        psi = Phi - RM lambda^2 enters a correction exactly as the feed
        rotation does (removing it leaves the source's intrinsic angle);
        without ``ionosphere`` it is the feed rotation, repeated over the
        frequencies (epochs first, frequency last). ``kwargs`` go to
        `feed_rotation`; for an LCP receiver both terms change sign.

        Examples
        --------
        >>> import astropy.units as u
        >>> from astropy.coordinates import SkyCoord
        >>> from astropy.table import QTable
        >>> from astropy.time import Time
        >>> from astropy_feedrot import get_antenna
        >>> from astropy_feedrot.ionosphere import Ionosphere
        >>> rm = QTable({"time": Time(["2024-06-01T20:00", "2024-06-01T22:00"]),
        ...              "rm": [1.0, 3.0] * u.rad / u.m**2})  # one series for every antenna
        >>> effelsberg, t = get_antenna("EFLSBERG"), Time("2024-06-01T21:00")
        >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
        >>> psi = effelsberg.polarization_rotation(source, t, [1.4, 5] * u.GHz,
        ...                                        Ionosphere.from_rm(rm))
        >>> phi = effelsberg.feed_rotation(source, t)
        >>> (phi - psi).to(u.deg)  # doctest: +FLOAT_CMP
        <Angle [5.25457945, 0.41195902] deg>
        """
        phi = self.feed_rotation(target, obstime, **kwargs)
        rm = 0 * u.rad / u.m**2 if ionosphere is None else \
            self.rotation_measure(target, obstime, ionosphere)
        # The Faraday rotation changes sign with the hand, as the feed rotation does.
        sign = equations.receiver_sign(target, kwargs.get("polarization"))
        return polarization_rotation(phi, sign * rm, frequency)

    @iers_context()  # one check of the Earth-orientation tables per call
    def feed_rotation_rate(self, target, obstime, polarization=None, form=None,
                           min_elevation=None):
        """Rate of the feed rotation of the antenna observing a target.

        Correlator models interpolate the feed rotation between their
        polynomial nodes, and solution intervals of a calibration must be
        short compared with the time the feed rotation takes to turn; both
        need its rate.

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord` or `~astropy_feedrot.Satellite`
            Natural source(s) or a satellite, as for `feed_rotation`.
        obstime : `~astropy.time.Time` or `~astropy_feedrot.Epochs`
            Epoch(s) of observation; masked epochs give NaN.
        polarization, form, min_elevation : optional
            As for `feed_rotation` (NaN below ``min_elevation``).

        Returns
        -------
        `~astropy.units.Quantity`
            :math:`d\\Phi/dt` in deg/s, with the broadcast shape of ``target``
            and ``obstime`` (a scalar for scalar inputs); the rate of the
            angle `feed_rotation` returns (so negated for LCP). NaN where the
            feed rotation is undefined.

        Raises
        ------
        TypeError, ValueError, astropy.units.UnitsError
            As for `feed_rotation`.

        Warns
        -----
        DegenerateGeometryWarning
            Once, with the count, if some epochs are degenerate.

        Notes
        -----
        For a natural source the rate is analytic
        (`~astropy_feedrot.engine.equations.feed_rotation_rate`): the line of sight
        turns about the celestial pole with the Earth, with the rates of the
        diurnal and annual aberration
        (`~astropy_feedrot.engine.rates.source_direction_rate`), and the chain rule
        goes through Eq 13, Eq 33 and the focus terms (Eqs 38, 39); mirror
        trains are differentiated along the motion of the line of sight. A
        ``'fixed'`` rotator changes nothing, a ``'sky'`` rotator gives 0 for a
        natural source, and a ``'series'`` rotator adds its rate
        (`Rotator.rate <astropy_feedrot.Rotator.rate>`). For
        a satellite, whose attitude turns its dipoles, it is a centred
        difference of `feed_rotation` over 0.02 s
        (`~astropy_feedrot.engine.rates.difference_rate`; one-sided within 0.01 s of
        the ends of an SP3 file). Both agree with a
        centred difference of the rigorous path to better than 1e-9 rad/s
        away from the singular directions (see :doc:`/rates`).

        Examples
        --------
        An alt-az telescope's feed rotation (the parallactic angle) turns
        fastest near the meridian, at :math:`-\\omega\\cos\\phi\\cos A/\\cos E`:

        >>> import astropy.units as u
        >>> from astropy.coordinates import SkyCoord
        >>> from astropy.time import Time
        >>> from astropy_feedrot import get_antenna
        >>> antenna = get_antenna("WETTZ13S")
        >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
        >>> rate = antenna.feed_rotation_rate(source, Time("2023-01-25T18:30"))
        >>> rate.unit
        Unit("deg / s")
        """
        obstime = as_epochs(obstime)  # converted once, handed down
        sign = equations.receiver_sign(target, polarization)
        limit = as_elevation_limit(min_elevation)
        form = equations.check_form(form)
        series = self._receivers.series_index.size > 0
        if isinstance(target, Satellite):
            def phase(epochs):
                # A 'series' rotator's rate is added below, from its own series.
                los = self._line_of_sight(target, epochs, series=False)
                return self._finish(sign * self._wind_up(los, form)[0], los.s)

            rate = rates.difference_rate(phase, obstime, span=target.orbit.coverage)
            if series:
                rate = rate + sign * self.rotator.rate(obstime)
            if limit is not None:
                below = self._below(self._line_of_sight(target, obstime).s, limit)
                rate = np.where(below, np.nan, rate)
            return self._rate(rate)
        s = source_direction(target, self.location, obstime)
        # The pole and the Sun (for the rate of the annual aberration) of the epochs.
        s_rate = rates.source_direction_rate(s, obstime.celestial_pole(), self._xyz,
                                             obstime.sun_position())
        rotation_rate = None
        if series:
            rotation_rate = np.broadcast_to(self.rotator.rate(obstime),
                                            s.shape[:-1])[..., np.newaxis]
        rate = sign * equations.feed_rotation_rate(
            self._receivers, s[..., np.newaxis, np.newaxis, :],
            s_rate[..., np.newaxis, np.newaxis, :], rotation_rate)[..., 0, 0]
        below = None if limit is None else self._below(s, limit)
        count = int(np.count_nonzero(equations.degenerate(rate, s, below)))
        equations.warn_degenerate(count, np.size(rate), "feed rotation rate", "epochs",
                                  self._describe())
        if below is not None:
            rate = np.where(below, np.nan, rate)
        return self._rate(rate)

    def _below(self, s, limit):
        """Where the lines of sight ``s`` are below the elevation ``limit`` (radians)."""
        return kernel.dot(s, self._local.up) < equations.min_sine(limit)

    @staticmethod
    def _rate(radians_per_second):
        rate = np.asarray(radians_per_second, dtype=float)
        return u.Quantity(rate[()] if rate.ndim == 0 else rate, u.rad / u.s).to(u.deg / u.s)
