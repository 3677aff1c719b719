# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""SGP4 at many epochs: evaluated at nodes and interpolated, within 0.1 mm.

SGP4 costs about a microsecond per satellite and epoch. An orbit is smooth on
the scale of a minute, so for dense epochs (a day at 1 s) `propagate` evaluates
SGP4 at nodes a fixed spacing apart, only around the epochs, and interpolates
the positions with a sliding eight-point Lagrange polynomial (degree 7, each
epoch in the central interval of its window, evaluated by Horner's rule). The
velocities SGP4 gives are not the derivative of its positions (they differ by
millimetres per second), so they are not used: a cubic Hermite interpolation
through them would be centimetres off.

The interpolation error is kept below `TOLERANCE` (0.1 mm) in two steps:

* the node spacing of each satellite is a power of two seconds (1 s to
  1024 s) from its elements, by the bound of the Lagrange remainder,
  ``h^8 |r^(8)| 6.5625^2 / 8!``, with ``|r^(8)| ~ r_p w_p^8`` at perigee
  (radius ``r_p``, angular rate ``w_p``);
* every window is checked on the nodes themselves: the eighth difference of
  nine nodes around it estimates ``h^8 r^(8)``. The epochs of windows whose
  estimate exceeds the tolerance (SGP4 is not smooth everywhere: it clamps
  the eccentricity of drag-decaying orbits, for instance) are computed with
  SGP4 directly; if they are more than a quarter of a satellite's epochs, its
  spacing is halved and the satellite done again.

Epochs are also computed with SGP4 directly where interpolation would not pay
(fewer than two epochs per node) and where it could hide a failure: an epoch
whose window holds a node where SGP4 fails, or whose interpolated position is
within 1 km of SGP4's Earth radius (SGP4 reports a decayed satellite there).
Error codes are therefore those of SGP4 at every epoch.
"""

import numpy as np

from ..core.extras import install_hint

__all__ = ["propagate", "TOLERANCE", "POINTS", "SGP4_MISSING"]

#: Interpolation error aimed at, in metres: a tenth of the 1 mm promised.
TOLERANCE = 1e-4

#: Nodes in the sliding Lagrange window (degree ``POINTS - 1``).
POINTS = 8

# Largest |prod_j (u - j)| for j = 0..7 and u in the central interval [3, 4],
# over 8!: the remainder of the Lagrange polynomial is this times h^8 r^(8).
_REMAINDER = 6.5625**2 / 40320

# Monomial coefficients, in the fraction of the cell [0, 1), of the polynomial
# through the nodes at -3 ... 4 (the cell's Lagrange window): c = _MONOMIAL @ y.
_MONOMIAL = np.linalg.inv(np.arange(-3.0, 5.0)[:, np.newaxis] ** np.arange(POINTS))

# Coefficients of the eighth difference: sum_j c_j y_j = h^8 y^(8) + O(h^10).
_EIGHTH = np.array([1.0, -8.0, 28.0, -56.0, 70.0, -56.0, 28.0, -8.0, 1.0])

# Largest fraction of the epochs in windows that fail the check with which a
# spacing is kept (SGP4 directly there); beyond it the spacing is halved.
_ROUGH = 0.25

# Offsets of the nodes kept for an epoch in the cell [k, k + 1): k - 4 to k + 4
# (the Lagrange window k - 3 to k + 4, and one more node for the check).
_OFFSETS = np.arange(-4, 5)

# Node spacings: powers of two seconds, from 1 s to 1024 s.
_SHORTEST, _LONGEST = 1.0, 1024.0

_DAY = 86400.0


#: What to do when the optional sgp4 package is missing.
SGP4_MISSING = ("TLE orbits need the sgp4 package, of the 'all' extra: "
                + install_hint("all", "sgp4"))


def _sgp4_array():
    """sgp4's ``SatrecArray`` (an optional dependency, imported when first needed)."""
    try:
        from sgp4.api import SatrecArray
    except ImportError:  # exercised by tests/cli/test_cli_extras.py, without sgp4
        raise ImportError(SGP4_MISSING) from None
    return SatrecArray


def node_spacing(satrec):
    """Node spacing (s) for one element set, from its elements.

    Parameters
    ----------
    satrec : ``sgp4.api.Satrec``
        An initialized element set.

    Returns
    -------
    float
        A power of two seconds between 1 s and 1024 s, such that the bound of
        the eight-point Lagrange remainder at perigee is below `TOLERANCE`.

    Examples
    --------
    >>> from sgp4.api import Satrec
    >>> from astropy_feedrot.transmitters.propagation import node_spacing
    >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
    >>> node_spacing(Satrec.twoline2rv(*GPS_SVN76_TLE))  # a GPS orbit: 8.5 minutes
    512.0
    """
    n = satrec.no_kozai / 60.0  # rad/s
    e = min(max(float(satrec.ecco), 0.0), 0.99)
    rate = n * np.sqrt((1 + e) / (1 - e) ** 3)  # angular rate at perigee
    perigee = satrec.a * satrec.radiusearthkm * 1e3 * (1 - e)  # m
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        h = (TOLERANCE / (_REMAINDER * perigee * rate**8)) ** (1 / 8)
    if not np.isfinite(h):
        return _SHORTEST
    return float(2.0 ** np.clip(np.floor(np.log2(h)), np.log2(_SHORTEST), np.log2(_LONGEST)))


def _direct(satrecs, jd1, jd2):
    error, r, _ = _sgp4_array()(list(satrecs)).sgp4(jd1, jd2)
    return np.asarray(error), np.asarray(r, dtype=float) * 1e3


def _interpolate(node_r, first, fraction, chunk=16384):
    """Interpolated positions (T, S, 3) from node positions (K, S, 3).

    The epoch in the cell between nodes ``first + 3`` and ``first + 4`` (in
    the fraction ``fraction`` of it) takes the polynomial through nodes
    ``first`` to ``first + 7``, evaluated by Horner's rule from its monomial
    coefficients.
    """
    nodes = node_r.reshape(node_r.shape[0], -1)  # (K, C)
    starts = np.arange(max(nodes.shape[0] - POINTS + 1, 0))
    windows = nodes[starts[:, np.newaxis] + np.arange(POINTS)]  # (W, 8, C)
    rows = nodes.shape[1] >= 48  # many satellites: gather rows; few: gather columns
    coefficients = np.einsum("kj,wjc->kwc" if rows else "kj,wjc->kcw", _MONOMIAL, windows)
    coefficients = np.ascontiguousarray(coefficients)
    out = np.empty((first.size, nodes.shape[1]) if rows else (nodes.shape[1], first.size))
    for a in range(0, first.size, chunk):  # blocks that stay in the cache
        b = min(a + chunk, first.size)
        index = first[a:b]
        f = fraction[a:b, np.newaxis] if rows else fraction[a:b]
        block = out[a:b] if rows else out[:, a:b]
        axis = 0 if rows else 1
        np.take(coefficients[-1], index, axis=axis, out=block)
        for k in range(POINTS - 2, -1, -1):
            block *= f
            block += np.take(coefficients[k], index, axis=axis)
    if not rows:
        out = out.T
    return out.reshape((first.size,) + node_r.shape[1:])


def _at_nodes(satrecs, jd1, jd2, spacing):
    """SGP4 interpolated from nodes ``spacing`` seconds apart.

    Returns None if that does not pay (fewer than two epochs per node), else
    ``(accurate, error, position)``: which satellites have at most a fraction
    `_ROUGH` of their epochs in windows that fail the check of the eighth
    differences, and for those SGP4's error codes (S, T) and positions
    (T, S, 3) in metres, from SGP4 directly in the windows that fail (the
    other satellites' values are meaningless).
    """
    n = jd1.size
    start = np.floor(np.min(jd1 + jd2) - 0.5) + 0.5  # a midnight before the first epoch
    x = ((jd1 - start) + jd2) * (_DAY / spacing)
    cell = np.floor(x)
    fraction = x - cell
    cell = cell.astype(np.int64)
    cells = np.unique(cell)
    if (cells.size + 8) * 2 > n:
        return None
    nodes = np.unique(cells[:, np.newaxis] + _OFFSETS)
    if nodes.size * 2 > n:
        return None
    first = np.searchsorted(nodes, cell + _OFFSETS[0])  # index of node cell - 4
    node_error, node_r = _direct(satrecs, np.full(nodes.size, start),
                                 nodes * (spacing / _DAY))
    node_r[node_error != 0] = np.nan  # SGP4 leaves its last numbers there
    node_r = np.ascontiguousarray(np.moveaxis(node_r, 0, 1))  # (K, S, 3)
    # Check: the eighth difference of the nodes first ... first + 8 of each window.
    count = nodes.size - _OFFSETS.size + 1
    eighth = sum(c * node_r[j:j + count] for j, c in enumerate(_EIGHTH))
    with np.errstate(invalid="ignore"):  # NaN at failed nodes: done directly below
        rough = np.einsum("wsc,wsc->ws", eighth, eighth) > (TOLERANCE / _REMAINDER) ** 2
    direct = rough[first]  # (T, S)
    accurate = np.mean(direct, axis=0) <= _ROUGH
    position = _interpolate(node_r, first + 1, fraction)
    # SGP4 directly wherever a window holds a failed node, or near the Earth's surface.
    failed = np.zeros((nodes.size + 1, len(satrecs)), dtype=np.int64)
    np.cumsum(node_error.T != 0, axis=0, out=failed[1:])
    direct |= failed[first + _OFFSETS.size] > failed[first]
    low = (np.array([s.radiusearthkm for s in satrecs]) * 1e3 + 1e3) ** 2
    with np.errstate(invalid="ignore"):
        direct |= ~(np.einsum("tsc,tsc->ts", position, position) > low)
    error = np.zeros((len(satrecs), n), dtype=node_error.dtype)
    for i in np.flatnonzero(np.any(direct, axis=0) & accurate):
        where = np.flatnonzero(direct[:, i])
        e, r = _direct([satrecs[i]], jd1[where], jd2[where])
        error[i, where], position[where, i] = e[0], r[0]
    return accurate, error, position


def propagate(satrecs, jd1, jd2, interpolate=True):
    """SGP4 positions of several element sets at the same epochs.

    Parameters
    ----------
    satrecs : sequence of ``sgp4.api.Satrec``
        Initialized element sets.
    jd1, jd2 : ndarray, shape (T,)
        The epochs as two-part Julian dates in UTC (C-contiguous float64), as
        SGP4 takes them.
    interpolate : bool, optional
        Whether dense epochs may be interpolated from nodes (default); False
        evaluates SGP4 at every epoch.

    Returns
    -------
    error : ndarray of int, shape (S, T)
        SGP4's error code at each epoch (0: none).
    position : ndarray, shape (S, T, 3)
        TEME positions in metres, within `TOLERANCE` of SGP4 evaluated at
        each epoch; meaningless where ``error`` is not 0. (A view of an array
        laid out epoch by epoch.)

    Notes
    -----
    Dense epochs (two or more per node) are interpolated from nodes (see the
    module's description); sparse ones, and epochs that are not finite, are
    evaluated directly, with one SGP4 call for all element sets.

    Examples
    --------
    >>> import numpy as np
    >>> from sgp4.api import Satrec
    >>> from astropy_feedrot.transmitters.propagation import propagate
    >>> from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
    >>> gps = Satrec.twoline2rv(*GPS_SVN76_TLE)
    >>> jd2 = np.arange(86400) / 86400.0  # one day at 1 s
    >>> error, r = propagate([gps], np.full(jd2.size, 2459969.5), jd2)
    >>> _, exact, _ = gps.sgp4_array(np.full(jd2.size, 2459969.5), jd2)
    >>> bool(np.max(np.abs(r[0] - np.asarray(exact) * 1e3)) < 1e-3)  # metres
    True
    """
    satrecs = list(satrecs)
    jd1 = np.ascontiguousarray(jd1, dtype=float)
    jd2 = np.ascontiguousarray(jd2, dtype=float)
    if not interpolate or jd1.size < 2 * POINTS or not np.all(np.isfinite(jd1 + jd2)):
        return _direct(satrecs, jd1, jd2)
    error = np.zeros((len(satrecs), jd1.size), dtype=np.int64)
    position = np.empty((jd1.size, len(satrecs), 3))  # epochs first: faster to fill
    todo = {}
    for i, satrec in enumerate(satrecs):
        todo.setdefault(node_spacing(satrec), []).append(i)
    direct = []
    while todo:
        spacing = max(todo)
        members = todo.pop(spacing)
        result = _at_nodes([satrecs[i] for i in members], jd1, jd2, spacing)
        if result is None:
            direct += members
            continue
        accurate, e, r = result
        if len(members) == len(satrecs) and np.all(accurate):
            error, position = e, r  # all in one go: no copy
            break
        done = [i for i, ok in zip(members, accurate) if ok]
        error[done], position[:, done] = e[accurate], r[:, accurate]
        for i in (i for i, ok in zip(members, accurate) if not ok):
            if spacing > _SHORTEST:
                todo.setdefault(spacing / 2, []).append(i)
            else:
                direct.append(i)
    if direct:
        direct.sort()
        e, r = _direct([satrecs[i] for i in direct], jd1, jd2)
        error[direct], position[:, direct] = e, np.moveaxis(r, 0, 1)
    return error, np.moveaxis(position, 0, 1)
