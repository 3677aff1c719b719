# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The epochs of a computation and everything that depends on them alone.

An `Epochs` is made once from a `~astropy.time.Time` (any shape, masked or
not, any scale) at the front of a computation and handed down: it owns the
masked epochs and the values that stand in for them (`fill_masked`), the
conversion to UTC, TT and UT1, the Earth's orientation (the rotation from the
celestial intermediate frame to ITRS and the celestial pole), the Sun, the
Earth's velocity, and the one choice of the package between evaluating the
slow series of Earth orientation at nodes and interpolating
(`~astropy_feedrot.earth.orientation.EarthOrientation`) or astropy's transformation at
every epoch (`uses_nodes`). Each of these is computed when first asked for
and kept, so that several antennas, sources or quantities at the same epochs
pay for them once. Every function of the package that takes ``obstime``
takes an `Epochs` too.
"""

import erfa
import numpy as np
from astropy import units as u
from astropy.coordinates import GCRS, ITRS, CartesianRepresentation, get_body_barycentric

from ..core.inputs import as_time
from .eop import iers_context, utc_earth_orientation
from .orientation import EarthOrientation, fast_path_applies, orientation_of

__all__ = ["Epochs", "as_epochs", "fill_masked"]


def fill_masked(obstime):
    """Split a possibly masked `~astropy.time.Time` into epochs to compute with and a mask.

    Masked epochs stand for missing data. The package computes nothing for
    them and returns NaN there (never a number, never a masked array): the
    geometry functions take the epochs returned here, where each masked epoch
    is replaced by the nearest earlier valid one (the first valid one for
    leading masked epochs), so that no orbit is asked for an epoch outside its
    span, and set their results to NaN where ``mask`` is True.

    Parameters
    ----------
    obstime : `~astropy.time.Time` or `Epochs`
        Epoch(s), masked or not (astropy >= 6 keeps the mask of a `Time`
        in ``Time.mask``; the values under the mask are meaningless).

    Returns
    -------
    filled : `~astropy.time.Time`
        Unmasked epochs of the same shape. Where every epoch is masked they
        are the values under the mask, which callers must not use.
    mask : ndarray of bool or None
        True at masked epochs, shape ``obstime.shape``; None if no epoch is
        masked.

    Raises
    ------
    TypeError
        If ``obstime`` is not a time (see `~astropy_feedrot.core.inputs.as_time`).

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.epochs import fill_masked
    >>> times = Time("2023-01-25T08:00") + [0, 1, 2] * u.hour
    >>> times[1] = np.ma.masked
    >>> filled, mask = fill_masked(times)
    >>> filled.isot.tolist(), mask.tolist()
    (['2023-01-25T08:00:00.000', '2023-01-25T08:00:00.000', '2023-01-25T10:00:00.000'], \
[False, True, False])
    """
    if isinstance(obstime, Epochs):
        return obstime.filled, obstime.mask
    obstime = as_time(obstime)
    if not obstime.masked:
        return obstime, None
    mask = np.array(obstime.mask, dtype=bool)
    plain = obstime.unmasked
    if not mask.any():
        return plain, None
    flat = mask.ravel()
    valid = np.flatnonzero(~flat)
    if not valid.size:
        return plain, mask
    index = np.maximum.accumulate(np.where(flat, -1, np.arange(flat.size)))
    index[index < 0] = valid[0]
    return plain.ravel()[index].reshape(mask.shape), mask


class Epochs:
    """Epochs of observation, and what depends on them alone, computed once.

    Parameters
    ----------
    obstime : `~astropy.time.Time` or `Epochs`
        The epochs: any shape, any scale, masked or not (masked epochs give
        NaN in every result of the package). An `Epochs` is returned as it is
        by `as_epochs`; ``Epochs(epochs)`` shares its time.

    Raises
    ------
    TypeError
        If ``obstime`` is not a time (see `~astropy_feedrot.core.inputs.as_time`).

    Notes
    -----
    Every function and method of the package that takes ``obstime`` takes an
    `Epochs` as well: make one to share the Earth orientation, the Sun and
    the time scales between calls at the same epochs (several antennas,
    sources, or the angle and its rate). Per-epoch arrays (`celestial_pole`,
    `sun_position`, `earth_velocity`) have the shape of the epochs plus a
    last axis of 3; NaN at masked epochs.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot import Epochs, get_antenna
    >>> epochs = Epochs(Time("2023-01-25T20:00") + np.arange(3) * u.hour)
    >>> source = SkyCoord("03h19m48.16s +41d30m42.1s")
    >>> a = get_antenna("WETTZ13S").feed_rotation(source, epochs)  # Earth orientation once,
    >>> b = get_antenna("ONSALA60").feed_rotation(source, epochs)  # used twice
    >>> epochs.shape, a.shape
    ((3,), (3,))
    """

    #: Marks objects `~astropy_feedrot.core.inputs.as_time` reads through ``epochs_time``.
    holds_epochs = True

    def __init__(self, obstime):
        if isinstance(obstime, Epochs):
            obstime = obstime.time
        self.time = as_time(obstime)
        self.filled, self.mask = fill_masked(self.time)
        self.shape = self.time.shape
        self.size = self.time.size
        self._orientation = None
        self._cache = {}

    @property
    def epochs_time(self):
        """`~astropy.time.Time`: The epochs as given (masked or not)."""
        return self.time

    @property
    def isscalar(self):
        """bool: Whether there is a single epoch of shape ()."""
        return self.time.isscalar

    @property
    def masked(self):
        """bool: Whether some epochs are masked."""
        return self.mask is not None

    def __len__(self):
        return len(self.time)

    def __repr__(self):
        masked = "" if self.mask is None else f", {int(self.mask.sum())} masked"
        if self.size == 0:
            return f"<Epochs shape {self.shape}>"
        low, high = self.filled.min(), self.filled.max()
        return (f"<Epochs shape {self.shape}{masked}, {low.utc.isot} to {high.utc.isot} "
                f"({self.time.scale})>")

    # --- the one choice --------------------------------------------------------

    def uses_nodes(self, target=None):
        """Whether Earth orientation comes from nodes and interpolation here.

        The package's one rule (`~astropy_feedrot.earth.orientation.fast_path_applies`),
        asked of these epochs: True where `orientation` serves (the default
        for sources fixed in a celestial frame, Earth rotation and the Sun),
        False where astropy's transformation runs at every epoch
        (``astropy_feedrot.conf.fast_path = False``, nearby or moving
        sources, shapes that do not pair every source with every epoch).

        Parameters
        ----------
        target : `~astropy.coordinates.SkyCoord` or None
            The sources, or None for Earth rotation alone.

        Returns
        -------
        bool

        Examples
        --------
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Epochs
        >>> Epochs(Time(["2023-01-25", "2023-01-26"])).uses_nodes()
        True
        """
        return fast_path_applies(target, self.filled)

    @property
    def orientation(self):
        """`~.orientation.EarthOrientation`: the orientation at the filled epochs.

        Made on first use and kept; for unmasked epochs it is also shared
        with other computations at the same epochs
        (`~astropy_feedrot.earth.orientation.orientation_of`).
        """
        if self._orientation is None:  # (each checks the tables for these epochs)
            if self.mask is None:
                self._orientation = orientation_of(self.filled)
            else:
                self._orientation = EarthOrientation(self.filled)
        return self._orientation

    # --- time scales ---------------------------------------------------------------

    def _scale(self, name):
        value = self._cache.get(name)
        if value is None:
            with iers_context(self.filled):
                value = getattr(self.filled, name)
            self._cache[name] = value
        return value

    @property
    def utc(self):
        """`~astropy.time.Time`: The filled epochs in UTC (converted once)."""
        return self._scale("utc")

    @property
    def tt(self):
        """`~astropy.time.Time`: The filled epochs in TT (converted once)."""
        return self._scale("tt")

    @property
    def ut1(self):
        """`~astropy.time.Time`: The filled epochs in UT1 (converted once)."""
        return self._scale("ut1")

    def _nan_where_masked(self, values):
        if self.mask is None:
            return values
        return np.where(self.mask[..., np.newaxis], np.nan, values)

    def _eop(self):
        """TT, UT1 and polar motion at every epoch (`~.eop.utc_earth_orientation`).
        """
        eop = self._cache.get("eop")
        if eop is None:
            utc = self.utc
            with iers_context(self.filled):
                eop = utc_earth_orientation(utc.jd1, utc.jd2)
            self._cache["eop"] = eop
        return eop

    # --- Earth orientation at every epoch -------------------------------------------

    def celestial_pole(self):
        """The Celestial Intermediate Pole in ITRS: the axis the Earth turns about.

        Returns
        -------
        ndarray, shape epochs.shape + (3,)
            Unit vectors, from the polar motion of the IERS tables as astropy
            interpolates them and the TIO locator s' (ERFA ``pom00``, ``sp00``);
            NaN at masked epochs.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Epochs
        >>> pole = Epochs(Time("2023-01-25T20:00")).celestial_pole()
        >>> round(float(np.degrees(np.arccos(pole[2])) * 3600), 2)  # arcsec from ITRS z
        0.23
        """
        pole = self._cache.get("pole")
        if pole is None:
            tt1, tt2, _, _, xp, yp = self._eop()
            sp = erfa.sp00(tt1, tt2)
            pole = self._nan_where_masked(erfa.pom00(xp, yp, sp)[..., :, 2])
            self._cache["pole"] = pole
        return pole

    def earth_rotation_angle(self):
        """The Earth rotation angle (rad, in [0, 2 pi)) at every epoch.

        Returns
        -------
        ndarray, shape epochs.shape
            ERFA ``era00`` of UT1; NaN at masked epochs.

        Examples
        --------
        >>> import erfa
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Epochs
        >>> t = Time("2023-01-25T20:00")
        >>> era = Epochs(t).earth_rotation_angle()
        >>> ut1 = t.ut1  # astropy's UT1, for comparison
        >>> float(era - erfa.era00(ut1.jd1, ut1.jd2))  # doctest: +FLOAT_CMP
        0.0
        """
        _, _, ut11, ut12, _, _ = self._eop()
        era = erfa.era00(ut11, ut12)
        return era if self.mask is None else np.where(self.mask, np.nan, era)

    def cirs_to_itrs(self, vectors):
        """Rotate CIRS vectors to ITRS at every epoch.

        Parameters
        ----------
        vectors : array-like, shape (..., N, 3)
            Vectors whose second-last axis runs over the N flattened epochs.

        Returns
        -------
        ndarray, shape (..., N, 3)
            As astropy's ``cirs_to_itrs_mat`` (see
            `~astropy_feedrot.earth.orientation.EarthOrientation.cirs_to_itrs`).

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Epochs
        >>> z = Epochs(Time(["2023-01-25T00:00"])).cirs_to_itrs([[0, 0, 1.0]])
        >>> bool(np.allclose(z, [0, 0, 1], atol=1e-5))
        True
        """
        return self.orientation.cirs_to_itrs(vectors)

    def teme_to_itrs(self, vectors):
        """Rotate TEME vectors (SGP4 output) to ITRS at every epoch.

        Parameters
        ----------
        vectors : array-like, shape (..., N, 3)
            Vectors whose second-last axis runs over the N flattened epochs.

        Returns
        -------
        ndarray, shape (..., N, 3)
            As astropy's ``teme_to_itrs_mat`` (see
            `~astropy_feedrot.earth.orientation.EarthOrientation.teme_to_itrs`).

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Epochs
        >>> r = Epochs(Time(["2023-01-25T00:00"])).teme_to_itrs([[7000.0, 0, 0]])
        >>> float(np.linalg.norm(r))  # doctest: +FLOAT_CMP
        7000.0
        """
        return self.orientation.teme_to_itrs(vectors)

    # --- the Sun and the Earth's motion ------------------------------------------

    def sun_position(self, exact=None):
        """Geocentric ITRS position of the Sun at every epoch, in metres.

        Parameters
        ----------
        exact : bool, optional
            True: astropy's transformation of ERFA's ``epv00`` at every epoch;
            False: `~astropy_feedrot.earth.orientation.EarthOrientation.sun_position`
            (within 2e-13 rad); None (default): as `uses_nodes` says.

        Returns
        -------
        ndarray, shape epochs.shape + (3,)
            NaN at masked epochs.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Epochs
        >>> sun = Epochs(Time("2023-01-25")).sun_position()
        >>> round(float(np.linalg.norm(sun) / 1.495978707e11), 3)  # au
        0.984
        """
        if exact is None:
            exact = not self.uses_nodes()
        key = ("sun", bool(exact))
        sun = self._cache.get(key)
        if sun is None:
            if self.size == 0:
                sun = np.empty(self.shape + (3,))
            elif exact:
                filled = self.filled
                with iers_context(filled):
                    body = get_body_barycentric("sun", filled, ephemeris="builtin")
                    earth = get_body_barycentric("earth", filled, ephemeris="builtin")
                    gcrs = GCRS(CartesianRepresentation((body - earth).xyz), obstime=filled)
                    itrs = gcrs.transform_to(ITRS(obstime=filled))
                sun = np.moveaxis(itrs.cartesian.xyz.to_value(u.m), 0, -1)
            else:
                sun = self.orientation.sun_position().reshape(self.shape + (3,))
            sun = self._nan_where_masked(sun)
            self._cache[key] = sun
        return sun

    def earth_velocity(self):
        """Barycentric velocity of the geocentre in GCRS, in m/s, at every epoch.

        Returns
        -------
        ndarray, shape epochs.shape + (3,)
            ERFA ``epv00`` at TDB = TT (the velocity of the annual
            aberration); NaN at masked epochs.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy.time import Time
        >>> from astropy_feedrot import Epochs
        >>> v = Epochs(Time("2023-01-25")).earth_velocity()
        >>> round(float(np.linalg.norm(v)) / 1e3, 1)  # km/s
        30.3
        """
        velocity = self._cache.get("velocity")
        if velocity is None:
            tt1, tt2, *_ = self._eop()
            _, barycentric = erfa.epv00(tt1, tt2)
            velocity = self._nan_where_masked(barycentric["v"] * (erfa.DAU / 86400.0))
            self._cache["velocity"] = velocity
        return velocity


def as_epochs(obstime):
    """An `Epochs` of ``obstime``: the same object if it is one already.

    Parameters
    ----------
    obstime : `~astropy.time.Time`, `Epochs` or what `~astropy.time.Time` reads
        The epochs.

    Returns
    -------
    Epochs

    Raises
    ------
    TypeError
        If ``obstime`` is not a time (see `~astropy_feedrot.core.inputs.as_time`).

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.earth.epochs import Epochs, as_epochs
    >>> epochs = Epochs(Time("2023-01-25"))
    >>> as_epochs(epochs) is epochs
    True
    """
    if isinstance(obstime, Epochs):
        return obstime
    return Epochs(obstime)
