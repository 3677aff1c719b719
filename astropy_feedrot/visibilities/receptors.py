# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The receptor step shared by every visibility format.

Rows of visibility data (time, antenna 1, antenna 2, source) become the sky
position angles of the receptors of both antennas:

.. math:: \\theta = \\Phi + \\alpha

with :math:`\\Phi` the feed rotation of the antenna
(`~astropy_feedrot.visibilities.feed_rotation_rows`) and :math:`\\alpha` the
angle of the receptor in the antenna (`~astropy_feedrot.Receptors`). A
linear dipole fixed to the ground (a `~astropy_feedrot.StationaryMount`)
does not turn rigidly: each of its dipoles has its own projection on the
sky. `receptor_position_angles` checks what the products need (receptors
known, one basis per baseline) and says which antenna lacks what.

`with_receptors` gives receptors to antennas whose file has none (ATCA
Miriad files, old UVFITS files): ``feedrot correct --feeds X,Y``; where
none are given, `~astropy_feedrot.visibilities.catalogue_receptors` takes
those of the station catalogue (`~astropy_feedrot.visibilities.catalogue`).
"""

import warnings

import numpy as np
from astropy import units as u
from astropy.time import Time

from ..antennas.mounts import FixedAxisMount
from ..antennas.receptors import RECEPTOR_TYPES, Receptors, basis_of
from ..core.exceptions import DegenerateGeometryWarning, ReceptorAngleWarning, warn_caller
from ..earth.frames import local_frame
from ..engine.antenna import Antenna
from .faraday import rotation_measure_rows
from .rows import feed_rotation_rows

__all__ = ["receptor_position_angles", "ReceptorAngleTable", "check_receptors", "with_receptors",
           "parse_feeds", "warn_unusual_angles"]

_POLCONVERT = ("a baseline between linear and circular feeds is not supported (convert one "
               "of them first, e.g. with PolConvert)")


def _dipole_antenna(antenna, alpha):
    """A stand-in whose feed rotation is the sky position angle of one fixed dipole.

    Eq 13 with a fixed vector :math:`\\hat{a}` is the position angle of the
    projection of :math:`\\hat{a}` on the plane of the sky: for a dipole fixed
    to the ground, its direction as the source sees it.
    """
    local = local_frame(antenna.location, vertical=antenna.vertical)
    aligned, transverse, _ = antenna.mount.dipoles(local)
    a = np.radians(alpha)
    # alpha grows from the aligned dipole away from the transverse one (east
    # toward south for StationaryMount), as position angles grow on the sky.
    axis = np.cos(a) * np.asarray(aligned) - np.sin(a) * np.asarray(transverse)
    return Antenna(antenna.location, FixedAxisMount(axis, frame="itrs"), name=antenna.name,
                   vertical=antenna.vertical)


def check_receptors(receptors, products, label, where="the data",
                    hint="give the antennas' receptors"):
    """Refuse receptors that cannot give the correlation products.

    Parameters
    ----------
    receptors : `~astropy_feedrot.antennas.receptors.Receptors` or None
        The receptors of one antenna.
    products : sequence of str
        The products of the data (``'RR'``, ``'XY'``...).
    label : str
        The antenna, for the message (``'antenna 3 (EA05)'``).
    where : str, optional
        The data, for the message.
    hint : str, optional
        What to do when ``receptors`` is None.

    Returns
    -------
    str
        The basis, ``'circular'`` or ``'linear'``.

    Raises
    ------
    ValueError
        If ``receptors`` is None, of the other basis than ``products`` (a
        baseline between a circular and a linear feed), or lacks a receptor
        the products need.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.antennas.receptors import Receptors
    >>> from astropy_feedrot.visibilities import check_receptors
    >>> check_receptors(Receptors("XY", [0, 90] * u.deg), ["RR", "LL"], "antenna 1", "x.ms")
    Traceback (most recent call last):
    ...
    ValueError: x.ms: antenna 1 has linear receptors 'XY' but the data hold circular ...
    """
    basis = basis_of(products)
    if receptors is None:
        raise ValueError(f"{where}: {label} has no receptors: {hint}")
    if receptors.basis != basis:
        raise ValueError(f"{where}: {label} has {receptors.basis} receptors "
                         f"{receptors.types!r} but the data hold {basis} products "
                         f"{list(products)}; {_POLCONVERT}")
    lacking = sorted(set("".join(products)) - set(receptors.types))
    if lacking:
        raise ValueError(f"{where}: {label} has receptors {receptors.types!r} but the "
                         f"products {list(products)} need {lacking}")
    return basis


def warn_unusual_angles(antennas, where="the data"):
    """Warn once, naming them, if antennas give their circular receptors unusual angles.

    Parameters
    ----------
    antennas : mapping or iterable
        ``{antenna number: Antenna}`` (or the antennas).
    where : str, optional
        The data, for the message.

    Returns
    -------
    list of str
        The antennas named (empty when none is unusual).

    Warns
    -----
    ReceptorAngleWarning
        When the second circular receptor of some antennas lies by other
        than 0 or 90 deg from the first
        (`~astropy_feedrot.antennas.receptors.Receptors.unusual_offset`): both receptors turn
        with the first's angle, as in CASA
        (`~astropy_feedrot.antennas.receptors.Receptors.sky_angles`).

    Examples
    --------
    >>> import warnings
    >>> import astropy.units as u
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.antennas.receptors import Receptors
    >>> from astropy_feedrot.visibilities import warn_unusual_angles, with_receptors
    >>> antennas = with_receptors({1: get_antenna("EFLSBERG")}, Receptors("RL", [20, 50] * u.deg))
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_unusual_angles(antennas, "x.idifits")
    ['antenna 1 (EFLSBERG): R 20, L 50 deg']
    >>> print(caught[0].message)  # doctest: +ELLIPSIS
    x.idifits: circular receptors neither at one angle nor 90 deg apart (the usual ...
    """
    items = antennas.items() if hasattr(antennas, "items") else enumerate(antennas)
    unusual = []
    for number, antenna in items:
        receptors = getattr(antenna, "receptors", None)
        if receptors is None or receptors.unusual_offset is None:
            continue
        label = f"antenna {number} ({antenna.name})" if antenna.name else f"antenna {number}"
        angles = ", ".join(f"{t} {a:g}" for t, a in zip(receptors.types,
                                                        receptors.angles.to_value(u.deg)))
        unusual.append(f"{label}: {angles} deg")
    if unusual:
        more = f"; and {len(unusual) - 10} more" if len(unusual) > 10 else ""
        listed = "; ".join(unusual[:10]) + more
        warn_caller(f"{where}: circular receptors neither at one angle nor 90 deg apart "
                    f"(the usual offsets) at {len(unusual)} antenna"
                    f"{'s' if len(unusual) > 1 else ''}: {listed}; both receptors of each "
                    "turn with the first one's angle, as in CASA (the second angle is "
                    "ignored); give the feeds (feeds=, --feeds) if the file's angles are "
                    "wrong", ReceptorAngleWarning)
    return unusual


def _check_antennas(antennas, used, products, where, hint):
    """The basis of the products, after checking every antenna used can give them."""
    basis = basis_of(products)
    missing = [int(n) for n in used if int(n) not in antennas]
    if missing:
        raise ValueError(f"{where}: the rows use antenna numbers {missing[:10]} that have no "
                         "antenna (no row in the antenna table)")
    for n in used:
        antenna = antennas[int(n)]
        if not isinstance(antenna, Antenna):
            raise TypeError(f"antennas[{int(n)}] must be an Antenna, got "
                            f"{type(antenna).__name__}")
        label = f"antenna {int(n)} ({antenna.name})" if antenna.name else f"antenna {int(n)}"
        check_receptors(antenna.receptors, products, label, where, hint)
    return basis


def receptor_position_angles(antennas, antenna1, antenna2, obstime, sources,
                             source_index=None, *, products, frame="apparent",
                             where="the data", hint="give the antennas' receptors"):
    """Sky position angles of the receptors of both antennas of every row.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna}``, each with `~astropy_feedrot.Receptors`.
    antenna1, antenna2 : array-like of int, shape (N,)
        The antennas of each row.
    obstime : `~astropy.time.Time`, shape (N,)
        The time of each row.
    sources : `~astropy.coordinates.SkyCoord` or mapping
        As in `~astropy_feedrot.visibilities.feed_rotation_rows`.
    source_index : array-like, optional
        The source of each row, as in
        `~astropy_feedrot.visibilities.feed_rotation_rows`.
    products : sequence of str
        The correlation products of the data (``'RR'``, ``'XY'``...): their
        basis decides the receptors needed.
    frame : str or frame, optional
        North of the position angles (``'apparent'``, the default, or a
        celestial frame such as ``'icrs'``).
    where : str, optional
        The data, for messages (a file name and table).
    hint : str, optional
        What to do when an antenna has no receptors, for the message.

    Returns
    -------
    theta1, theta2 : `~numpy.ndarray`, shape (N, 2)
        Position angles in degrees of the receptors of antenna 1 and 2 in
        the order ``(R, L)`` or ``(X, Y)``; NaN where the feed rotation is
        undefined (the caller counts and warns).

    Raises
    ------
    ValueError
        If an antenna has no antenna entry or no receptors, receptors of the
        other basis than the products (a circular-linear baseline), or lacks
        a receptor the products need; the message names the antenna.
    TypeError
        If an entry of ``antennas`` is not an `~astropy_feedrot.Antenna`.

    Examples
    --------
    Two VLBA antennas with R at 0 deg and L at 0 deg: both receptors turn
    with the parallactic angle.

    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.antennas.receptors import Receptors
    >>> from astropy_feedrot.visibilities import receptor_position_angles
    >>> import astropy.units as u
    >>> from astropy_feedrot.visibilities import with_receptors
    >>> feeds = Receptors("RL", [0, 0] * u.deg)
    >>> antennas = with_receptors({1: get_antenna("FD-VLBA"), 2: get_antenna("PIETOWN")},
    ...                           feeds)
    >>> t = Time(["2023-01-25T20:00", "2023-01-25T21:00"])
    >>> theta1, theta2 = receptor_position_angles(antennas, [1, 1], [2, 2], t,
    ...                                           SkyCoord("3h19m48s +41d30m42s"),
    ...                                           products=["RR", "LL"])
    >>> theta1.shape, bool(np.all(theta1[:, 0] == theta1[:, 1]))
    ((2, 2), True)
    """
    ant1 = np.asarray(antenna1, dtype=int)
    ant2 = np.asarray(antenna2, dtype=int)
    used = np.unique(np.concatenate([ant1, ant2]))
    basis = _check_antennas(antennas, used, products, where, hint)
    letters = RECEPTOR_TYPES[basis]
    # Virtual antennas: key 2n + k for receptor k of antenna n. Tracking mounts
    # (and circular feeds) turn rigidly, theta = Phi + alpha with one key 2n; a
    # linear dipole fixed to the ground has its own projection on the sky.
    virtual, keys, offsets = {}, {}, {}
    for n in used.tolist():
        antenna = antennas[n]
        # Circular receptors turn with the first one's angle (Receptors.sky_angles).
        types, angles = antenna.receptors.types, antenna.receptors.sky_angles.to_value(u.deg)
        alphas = [angles[types.index(letter)] if letter in types else 0.0
                  for letter in letters]
        if antenna.mount.tracks or basis == "circular":
            virtual[2 * n] = antenna
            keys[n] = (2 * n, 2 * n)
            offsets[n] = alphas
        else:
            virtual[2 * n] = _dipole_antenna(antenna, alphas[0])
            virtual[2 * n + 1] = _dipole_antenna(antenna, alphas[1])
            keys[n] = (2 * n, 2 * n + 1)
            offsets[n] = [0.0, 0.0]
    key = np.array([keys[n] for n in used.tolist()])  # (A, 2)
    offset = np.array([offsets[n] for n in used.tolist()])  # (A, 2)
    pos1, pos2 = np.searchsorted(used, ant1), np.searchsorted(used, ant2)
    n_rows = ant1.size
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegenerateGeometryWarning)
        if np.all(key[:, 0] == key[:, 1]):
            phi = feed_rotation_rows(virtual, key[pos1, 0], key[pos2, 0], obstime, sources,
                                     source_index, frame=frame).to_value(u.deg)
            phi = np.concatenate([phi, phi])
        else:
            index = None if source_index is None else np.tile(np.asarray(source_index), 2)
            phi = feed_rotation_rows(
                virtual, np.concatenate([key[pos1, 0], key[pos1, 1]]),
                np.concatenate([key[pos2, 0], key[pos2, 1]]), _tile(obstime), sources,
                index, frame=frame).to_value(u.deg)
    theta1 = np.stack([phi[:n_rows, 0], phi[n_rows:, 0]], axis=-1) + offset[pos1]
    theta2 = np.stack([phi[:n_rows, 1], phi[n_rows:, 1]], axis=-1) + offset[pos2]
    return theta1, theta2


class ReceptorAngleTable:
    """The receptors' position angles of many rows, computed once for each distinct
    (time, source, antenna) and looked up by rows.

    A visibility file repeats each epoch and source for every baseline, and is
    read in chunks: the angles are computed here for all the rows at once, at
    their distinct epochs (`receptor_position_angles`), and each chunk looks
    its rows up (`__call__`) instead of running the geometry again.

    Parameters
    ----------
    antennas : mapping
        ``{key: Antenna}`` with receptors.
    time : array-like of float, shape (N,)
        The time of each row, in any unit ``to_time`` understands.
    source : array-like of int, shape (N,)
        The source (key of ``sources``) of each row.
    key1, key2 : array-like of int, shape (N,)
        The antennas of each row.
    sources : mapping
        ``{source key: source}``, as `feed_rotation_rows` takes them.
    to_time : callable
        Turns an array of ``time`` values into a `~astropy.time.Time`.
    products, frame, where, hint
        As `receptor_position_angles`.
    ionosphere : `~astropy_feedrot.ionosphere.Ionosphere`, optional
        Also the rotation measure of each (time, source, antenna), in
        ``rm`` (rad m^-2; `~astropy_feedrot.visibilities.faraday`), computed
        here once as the angles are; None (default) leaves ``rm`` None.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.time import Time
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.antennas.receptors import Receptors
    >>> from astropy_feedrot.visibilities import ReceptorAngleTable, with_receptors
    >>> antennas = with_receptors({1: get_antenna("FD-VLBA"), 2: get_antenna("PIETOWN")},
    ...                           Receptors("RL", [0, 0] * u.deg))
    >>> jd = np.array([2459970.3, 2459970.3, 2459970.4])
    >>> table = ReceptorAngleTable(antennas, jd, [0, 0, 0], [1, 2, 1], [2, 1, 2],
    ...                            {0: SkyCoord("3h19m48s +41d30m42s")},
    ...                            lambda t: Time(t, format="jd"), products=["RR"])
    >>> theta = table(jd, np.zeros(3, int), np.array([1, 2, 1]))
    >>> theta.shape, bool(theta[0, 0] != theta[1, 0])
    ((3, 2), True)
    """

    def __init__(self, antennas, time, source, key1, key2, sources, to_time, *, products,
                 frame="apparent", where="the data", hint="give the antennas' receptors",
                 ionosphere=None):
        time, source = np.asarray(time, float), np.asarray(source)
        self.times, at = _distinct(time)
        self.sources = np.unique(source)
        self.n_keys = int(max(antennas)) + 1
        row = self._row_codes(at, source)
        code1, code2 = row + np.asarray(key1), row + np.asarray(key2)
        grid = self.times.size * self.sources.size * self.n_keys
        self.lookup = None
        if grid <= max(2 * time.size, LOOKUP_CELLS):
            # Every (time, source, antenna) is a place in a grid no larger than the
            # rows: the codes present are marked there, and a row's place is read
            # from it (no sort of the rows' codes, no search).
            seen = np.zeros(grid, bool)
            seen[code1] = True
            seen[code2] = True
            codes = np.flatnonzero(seen)
            self.lookup = (np.cumsum(seen, dtype=np.int64) - 1).astype(_place_type(codes.size))
        else:
            codes = np.unique(np.concatenate([code1, code2]))
        keys = codes % self.n_keys
        rest = codes // self.n_keys
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DegenerateGeometryWarning)
            self.table, _ = receptor_position_angles(
                antennas, keys, keys, to_time(self.times[rest // self.sources.size]),
                sources, self.sources[rest % self.sources.size], products=products,
                frame=frame, where=where, hint=hint)
        self.codes = codes
        # What a chunk's rows look up (dask workers are sent it once): the angles (deg),
        # shape (K, 2), and with an ionosphere the RM (rad m^-2) as a third column.
        self.rm, self.packed = None, self.table
        if ionosphere is not None:
            self.rm = rotation_measure_rows(
                ionosphere, antennas, keys, to_time(self.times[rest // self.sources.size]),
                sources, self.sources[rest % self.sources.size], where=where)
            self.packed = np.column_stack([self.table, self.rm])

    def _row_codes(self, at, source):
        """The code of antenna 0 in rows of times ``self.times[at]`` and ``source``."""
        return (at * self.sources.size + np.searchsorted(self.sources, source)) * self.n_keys

    def _codes(self, time, source, keys):
        return self._row_codes(np.searchsorted(self.times, time), source) + keys

    def __call__(self, time, source, keys):
        """The position angles (deg), shape (N, 2), of the receptors of antennas
        ``keys`` in rows of these times and sources (rows the table was made from)."""
        return self.table[self.places(time, source, keys)]

    def places(self, time, source, keys):
        """Where the position angles of those rows are in ``table`` (int32 where it is
        large enough: chunks sent to dask workers carry these, not the angles)."""
        codes = self._codes(np.asarray(time, float), np.asarray(source), np.asarray(keys))
        if self.lookup is not None:
            return self.lookup[codes]
        return np.searchsorted(self.codes, codes).astype(_place_type(self.codes.size))


# A ReceptorAngleTable finds rows' places by a lookup in the grid of (time, source,
# antenna) when the grid has at most this many cells or twice the rows; else by a search.
LOOKUP_CELLS = 2**16


def _place_type(n):
    """The integer type of places in a table of ``n`` rows."""
    return np.int32 if n < 2**31 else np.int64


def _distinct(values):
    """``np.unique(values, return_inverse=True)`` of an array of floats, without a sort
    or a search when it is sorted already (the rows of a visibility file mostly are)."""
    if values.size > 1 and np.all(values[1:] >= values[:-1]):
        new = np.concatenate([[True], values[1:] != values[:-1]])
        return values[new], np.cumsum(new) - 1
    distinct = np.unique(values)
    return distinct, np.searchsorted(distinct, values)


def _tile(obstime):
    """Two copies of a time array, end to end."""
    obstime = obstime if isinstance(obstime, Time) else Time(obstime)
    return obstime[np.tile(np.arange(obstime.size), 2)]


def _given(antenna, receptors):
    """``antenna`` with other receptors."""
    return Antenna(antenna.location, antenna.mount, antenna.focus, name=antenna.name,
                   vertical=antenna.vertical, receptors=receptors, rotator=antenna.rotator)


def parse_feeds(text):
    """Receptors from a command-line text: ``'R,L'``, ``'X,Y'`` or ``'X:45,Y:135'``.

    Parameters
    ----------
    text : str
        Two receptor letters separated by a comma, each optionally followed
        by ``:angle`` in degrees (default 0 for R, L and X, 90 for Y).

    Returns
    -------
    `~astropy_feedrot.Receptors`

    Raises
    ------
    ValueError
        For anything else, with the accepted forms.

    Examples
    --------
    >>> from astropy_feedrot.visibilities import parse_feeds
    >>> parse_feeds("X:45,Y:135")
    Receptors('XY', [45.0, 135.0] * u.deg)
    >>> parse_feeds("R,L").types
    'RL'
    """
    return Receptors.from_text(text, "feeds")


def with_receptors(antennas, receptors, *, replace=False):
    """The antennas, given ``receptors`` where they have none.

    Parameters
    ----------
    antennas : mapping
        ``{antenna number: Antenna}``.
    receptors : `~astropy_feedrot.Receptors` or mapping
        The receptors of every antenna, or ``{antenna number or name:
        Receptors}``.
    replace : bool, optional
        Replace the receptors an antenna has (default: keep them).

    Returns
    -------
    dict
        A new ``{antenna number: Antenna}``.

    Raises
    ------
    TypeError
        If ``receptors`` is neither.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot import get_antenna
    >>> from astropy_feedrot.antennas.receptors import Receptors
    >>> from astropy_feedrot.visibilities import with_receptors
    >>> antennas = with_receptors({1: get_antenna("EFLSBERG")}, Receptors("XY", [0, 90] * u.deg))
    >>> antennas[1].receptors.types
    'XY'
    """
    if isinstance(receptors, Receptors):
        def given(number, antenna):
            return receptors
    elif hasattr(receptors, "get"):
        def given(number, antenna):
            return receptors.get(number, receptors.get(antenna.name))
    else:
        raise TypeError(f"receptors must be Receptors or a mapping {{antenna: Receptors}}, "
                        f"got {type(receptors).__name__}")
    out = {}
    for number, antenna in antennas.items():
        new = given(number, antenna)
        if new is not None and (replace or antenna.receptors is None):
            antenna = _given(antenna, new)
        out[number] = antenna
    return out
