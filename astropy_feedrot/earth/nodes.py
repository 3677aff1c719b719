# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Slow quantities on grids of nodes, and polynomials in time.

The tools with which `~astropy_feedrot.earth.orientation.EarthOrientation` computes a
quantity that changes over days (precession-nutation, the Earth's
ephemeris) a few times a day and interpolates it to many epochs: Lagrange
polynomials through equally spaced nodes (`lagrange_weights`, `combine`),
the `Series` that keeps the nodes already computed, pieces of polynomials at
Chebyshev points evaluated by Horner's rule (`chebyshev`, `monomials`,
`horner`), and ERFA evaluations split between two threads (`in_parallel`).
Plain numpy on floats; nothing here knows about time scales or frames.
"""

import functools
import hashlib
import math
import os
import pathlib
import tempfile
import threading

import erfa
import numpy as np
from astropy.config import get_cache_dir

from ..core.cache import KeptLast, helper_thread, on_helper_thread
from ..core.kernel import over_components

__all__ = ["Series", "lagrange_weights", "combine", "in_parallel", "chebyshev", "monomials",
           "horner", "unique_integers", "short_span_degree", "KeptSeries", "kept_path",
           "clear_kept_nodes", "PIECE_DEGREE", "PARALLEL_NODES", "SHORT_SPANS", "KEPT_ORIGIN",
           "KEPT_CHUNK", "RUN_EPOCHS", "MAX_RUNS"]

# With many instants in an interval of a grid, the interpolant is reduced there to
# a polynomial of this degree (Chebyshev points), below 1e-6 mas.
PIECE_DEGREE = 5


def lagrange_weights(xi, offsets):
    """Weights (P, n) of the Lagrange polynomials through nodes at integer ``offsets``.

    The barycentric form for consecutive integers: w_k = b_k / (xi - o_k),
    normalized, with b_k = (-1)**k binomial(n - 1, k).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import lagrange_weights
    >>> w = lagrange_weights(np.array([0.5]), np.array([-1.0, 0.0, 1.0, 2.0]))
    >>> float((w @ np.array([-1.0, 0.0, 1.0, 2.0]) ** 3)[0])  # a cubic is reproduced
    0.125
    """
    b = _barycentric(offsets.size)
    distance = xi[:, np.newaxis] - offsets
    with np.errstate(divide="ignore", invalid="ignore"):
        weights = b / distance
        weights /= weights.sum(axis=1, keepdims=True)
    if not np.isfinite(weights).all():  # an instant on a node: that node's value
        on_node = distance == 0
        rows = np.any(on_node, axis=1)
        weights[rows] = on_node[rows]
    return weights


@functools.lru_cache(maxsize=None)
def _barycentric(n):
    """The barycentric weights (-1)**k binomial(n - 1, k) of n consecutive integers."""
    b = np.array([(-1) ** k * math.comb(n - 1, k) for k in range(n)], dtype=float)
    b.flags.writeable = False
    return b


def unique_integers(values, low, inverse=True):
    """`numpy.unique` of integers held as floats, ``low`` their least, and the inverse.

    Through a table of the whole range where it is short (sparse epochs over
    years: a few thousand days), which costs a few array passes instead of a
    sort; the same result.

    Parameters
    ----------
    values : ndarray
        Whole numbers as floats (anything else goes to `numpy.unique`).
    low : float
        ``values.min()``.
    inverse : bool, optional
        Whether to return the index of each value among the distinct ones.

    Returns
    -------
    distinct : ndarray
        The distinct values, sorted.
    index : ndarray or None
        ``distinct[index] == values`` (None unless ``inverse``).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import unique_integers
    >>> unique_integers(np.array([7.0, 3.0, 7.0, 5.0]), 3.0)
    (array([3., 5., 7.]), array([2, 0, 2, 1]))
    """
    high = values.max()
    if not (np.isfinite(low) and np.isfinite(high)) or high - low >= 8 * values.size + 4096:
        if inverse:
            return np.unique(values, return_inverse=True)
        return np.unique(values), None
    index = (values - low).astype(np.intp)
    present = np.zeros(int(high - low) + 1, dtype=bool)
    present[index] = True
    distinct = np.flatnonzero(present) + low
    if not inverse:
        return distinct, None
    return distinct, (np.cumsum(present) - 1)[index]


def combine(values, start, weights):
    """Sum of ``weights[:, k]`` times ``values[start + k]`` (values (M, ...) -> (P, ...)).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import combine
    >>> values = np.arange(5.0)[:, np.newaxis]  # (M, 1)
    >>> combine(values, np.array([1]), np.array([[0.5, 0.5]]))
    array([[1.5]])
    """
    # One gather of every stencil and one contraction: a loop over the nodes
    # costs two numpy calls per node, which dominates for few instants.
    weights = weights.reshape(weights.shape[:2])  # (P, n), trailing axes of 1 dropped
    return _contract(weights, values[start[:, np.newaxis] + np.arange(weights.shape[1])])


def _contract(weights, stencils):
    """Sum over the nodes of weights (P, n) times the stencils' values (P, n, ...)."""
    return np.einsum("pn,pn...->p...", weights, stencils)


#: Spans of instants (days) short enough for one polynomial through ERFA at the
#: Chebyshev points of the span, and its degree. The bound on the error of
#: degree d over a span L is max|f^(d+1)| (L/2)^(d+1) / (2^d (d+1)!), with the
#: derivatives of the fastest terms of each series: for X and Y the nutation's
#: 13.7- and 9.1-day terms (0.095" and 0.012", sum of A w^n), for the Earth's
#: velocity the monthly wobble about the Earth-Moon barycentre (12.6 m/s at
#: 27.3 days). Degree 2 up to 0.02 day, 4 up to 0.25 day and 6 up to a day keep
#: X, Y and s below 1e-14 rad and the velocity below 1e-8 m/s (1e-13 rad of
#: aberration): as the grids of nodes, or better, at 3 to 7 evaluations.
SHORT_SPANS = ((0.02, 2), (0.25, 4), (1.0, 6))


def short_span_degree(span):
    """The degree of the one polynomial for instants spanning ``span`` days, or None.

    Parameters
    ----------
    span : float
        Days from the first instant to the last.

    Returns
    -------
    int or None
        From `SHORT_SPANS`; None for spans longer than a day (grids of nodes
        serve those).

    Examples
    --------
    >>> from astropy_feedrot.earth.nodes import short_span_degree
    >>> short_span_degree(10 / 1440), short_span_degree(0.7), short_span_degree(3.0)
    (2, 6, None)
    """
    for longest, degree in SHORT_SPANS:
        if span <= longest:
            return degree
    return None


#: Nodes from which `in_parallel` splits an ERFA evaluation between threads.
PARALLEL_NODES = 64


def in_parallel(evaluate, tt1, tt2):
    """``evaluate(tt1, tt2)`` on halves of the nodes in two threads, where there are many.

    pyerfa's functions release the GIL, so the nutation series and the
    ephemeris of long sparse series (a year of hourly epochs needs a few
    hundred nodes) take half the time on two cores.

    Examples
    --------
    >>> import erfa
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import in_parallel
    >>> tt2 = np.arange(100.0)
    >>> era = in_parallel(lambda a, b: erfa.era00(a, b), 2460000.5, tt2)
    >>> bool(np.array_equal(era, erfa.era00(2460000.5, tt2)))
    True
    """
    if tt2.size < PARALLEL_NODES or on_helper_thread():
        return evaluate(tt1, tt2)
    half = tt2.size // 2
    first = helper_thread().submit(evaluate, tt1, tt2[:half])
    second = evaluate(tt1, tt2[half:])
    return np.concatenate([first.result(), second])


class Series:
    """A slow quantity from ERFA on a grid of TT, interpolated to instants.

    ``evaluate(tt1, tt2)`` returns an (M, C) array at M instants of TT.
    Values at the grid nodes are kept, so that instants asked for later reuse
    the nodes already computed.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(tt1, tt2)``: the quantity at M instants, shape (M, C).
    spacing : float
        Days between nodes.
    order : int
        Nodes per Lagrange polynomial.
    tt1, tt2 : float
        The two-part JD (TT) from which instants are counted in days.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import Series
    >>> cubic = Series(lambda a, b: ((b - 0.25) ** 3)[:, np.newaxis], 1.0, 8, 0.0, 0.0)
    >>> tt = np.linspace(0, 10, 50)
    >>> bool(np.allclose(cubic.at(tt)[:, 0], (tt - 0.25) ** 3))
    True
    """

    #: Days from the reference of the instants to node 0 of the grid.
    shift = 0.0

    def __init__(self, evaluate, spacing, order, tt1, tt2):
        self.evaluate, self.spacing, self.order = evaluate, spacing, order
        self.tt1, self.tt2 = tt1, tt2
        self.offsets = np.arange(order) - (order // 2 - 1)
        self._nodes = {}

    def plan(self, tt):
        """Grid nodes (integers, sorted) needed by instants at ``tt``, or None.

        None when there are no more instants than the nodes they would need:
        ERFA is then evaluated at the instants themselves.
        """
        if tt.size <= self.order:
            return None
        needed = np.unique(np.unique(np.floor((tt + self.shift) / self.spacing))[:, np.newaxis]
                           + self.offsets)
        return None if tt.size <= needed.size else needed

    def at(self, tt):
        """The quantity at instants ``tt`` (days from the reference), shape (P, C).

        From ERFA at the instants, the Lagrange polynomial through the grid
        nodes around each instant, or, with many instants per interval of the
        grid, that polynomial reduced to a Chebyshev interpolant of degree
        `PIECE_DEGREE` in each interval (below 1e-6 mas).
        """
        ready = self.nodes_ready(tt)
        if tt.size > 1 and not ready:
            low, high = float(tt.min()), float(tt.max())
            degree = short_span_degree(high - low)
            if degree is not None and tt.size > degree + 1:
                return self._over_span(tt, low, high, degree)
        if tt.size <= self.order and not ready:  # fewer instants than nodes
            return self.evaluate(self.tt1, self.tt2 + tt)
        x = (tt + self.shift) / self.spacing
        j = np.floor(x)
        low = j.min()
        if low == j.max():  # one interval (a few epochs, a scan): no sorting
            intervals, slot = j[:1], np.zeros(j.size, dtype=np.intp)
            needed = low + self.offsets
        else:
            if ready:
                direct = self._direct(x, j, low)
                if direct is not None:
                    return direct
            intervals, slot = unique_integers(j, low)
            needed, _ = unique_integers((intervals[:, np.newaxis] + self.offsets).ravel(),
                                        low + self.offsets[0], inverse=False)
        if tt.size <= needed.size and not ready:
            return self.evaluate(self.tt1, self.tt2 + tt)
        values = self.nodes(needed)
        # The nodes of a stencil are consecutive integers, hence consecutive in needed.
        first = np.searchsorted(needed, intervals + self.offsets[0])
        offsets = self.offsets.astype(float)
        if tt.size <= 2 * (PIECE_DEGREE + 1) * intervals.size:
            return combine(values, first[slot], lagrange_weights(x - j, offsets))
        points, inverse = chebyshev(PIECE_DEGREE)
        weights = lagrange_weights((points + 1) / 2, offsets)  # (K, order), every interval
        # The interpolant at the K Chebyshev points of each interval: (K, intervals, C).
        at_points = weights[:, 0, np.newaxis, np.newaxis] * values[first]
        for k in range(1, self.order):
            at_points += weights[:, k, np.newaxis, np.newaxis] * values[first + k]
        coefficients = monomials(inverse, at_points)[:, np.newaxis]
        return horner(coefficients, slot.reshape(-1), 2 * (x - j) - 1)[0]

    def _direct(self, x, j, low):
        """The Lagrange sums at sparse instants, their stencils read straight from the nodes.

        For instants in time order, mostly one per interval (per scan, sparse
        over years), when `stencils` serves them: the sums of `at`, with the
        same nodes and weights, without finding the distinct intervals and
        nodes first. None where `at` goes the other way.
        """
        steps = np.diff(j)
        if not np.all(steps >= 0):
            return None
        intervals = 1 + np.count_nonzero(steps)
        if j.size > 2 * (PIECE_DEGREE + 1) * intervals:  # the piecewise interpolants pay
            return None
        stencils = self.stencils(j, low)
        if stencils is None:
            return None
        return _contract(lagrange_weights(x - j, self.offsets.astype(float)), stencils)

    def stencils(self, j, low):
        """Values (P, order, C) at the nodes around each interval ``j``, or None.

        ``low`` is the least of ``j``. None here: the nodes of a plain
        series are computed for the instants that need them.
        """
        return None

    def _over_span(self, tt, low, high, degree):
        """ERFA at the Chebyshev points of the span of ``tt``, and the polynomial through them."""
        points, inverse = chebyshev(degree)
        half = (high - low) / 2
        if half == 0:  # one instant, many times
            value = self.evaluate(self.tt1, self.tt2 + np.array([low]))
            return np.repeat(value, tt.size, axis=0)
        values = self.evaluate(self.tt1, self.tt2 + (low + half * (points + 1)))  # (K, C)
        coefficients = monomials(inverse, values)  # (K, C)
        x = ((tt - low) / half - 1)[:, np.newaxis]
        out = np.broadcast_to(coefficients[-1], (tt.size, coefficients.shape[-1])).copy()
        for k in range(degree - 1, -1, -1):
            out *= x
            out += coefficients[k]
        return out

    def nodes_ready(self, tt):
        """Whether the nodes for instants ``tt`` cost nothing to compute (`KeptSeries`).

        Parameters
        ----------
        tt : ndarray
            Instants, days from the reference.

        Returns
        -------
        bool
            False here: a plain series computes its nodes.

        Examples
        --------
        >>> import numpy as np
        >>> from astropy_feedrot.earth.nodes import Series
        >>> Series(None, 1.0, 8, 2451545.0, 0.0).nodes_ready(np.zeros(3))
        False
        """
        return False

    def nodes(self, needed):
        """Values at grid nodes ``needed`` (integers), computing those not yet known."""
        missing = [j for j in needed.tolist() if j not in self._nodes]
        if missing:
            tt = np.array(missing) * self.spacing
            for j, row in zip(missing, in_parallel(self.evaluate, self.tt1, self.tt2 + tt)):
                self._nodes[j] = row
        return np.array([self._nodes[j] for j in needed.tolist()])


def chebyshev(degree):
    """Chebyshev points of the first kind in (-1, 1) and the monomial fit through them.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import chebyshev
    >>> points, inverse = chebyshev(2)
    >>> bool(np.allclose(inverse @ points ** 2, [0, 0, 1]))  # x**2 in monomials
    True
    """
    n = degree + 1
    points = np.cos(np.pi * (np.arange(n) + 0.5) / n)
    return points, np.linalg.inv(np.vander(points, n, increasing=True))


def monomials(inverse, values):
    """Monomial coefficients (K, ...) from values (K, ...) at the Chebyshev points.

    ``inverse`` is the inverse Vandermonde matrix of `chebyshev`; the sums run
    element by element (not through BLAS), so that each coefficient is the same
    whatever else is computed with it.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import chebyshev, monomials
    >>> points, inverse = chebyshev(3)
    >>> monomials(inverse, 1 + 2 * points).round(12) + 0.0  # 1 + 2x
    array([1., 2., 0., 0.])
    """
    out = inverse[:, 0].reshape((-1,) + (1,) * (values.ndim - 1)) * values[0]
    for j in range(1, values.shape[0]):
        out += inverse[:, j].reshape((-1,) + (1,) * (values.ndim - 1)) * values[j]
    return out


def horner(coefficients, slot, x):
    """Evaluate each epoch's cell polynomial: coefficients (m + 1, S, cells, 3) -> (S, N, 3).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import horner
    >>> coefficients = np.array([1.0, 2.0]).reshape(2, 1, 1, 1) * np.ones((2, 1, 1, 3))
    >>> horner(coefficients, np.array([0]), np.array([0.5]))  # 1 + 2 x at x = 0.5
    array([[[2., 2., 2.]]])
    """
    slot = np.asarray(slot)
    starts = np.flatnonzero(np.diff(slot)) + 1
    if slot.size >= RUN_EPOCHS * (starts.size + 1) and starts.size < MAX_RUNS:
        return _horner_by_runs(coefficients, slot, x, starts)
    n_s = coefficients.shape[1]
    block = max(256, HORNER_BLOCK // max(n_s, 1))
    if slot.size <= block:
        return _horner_block(coefficients, slot, x)
    # A block of epochs at a time, so that the sums stay in the cache between the
    # steps of the polynomial (each step over a million epochs went to memory).
    out = np.empty((n_s, slot.size) + coefficients.shape[3:])
    for a in range(0, slot.size, block):
        b = min(a + block, slot.size)
        out[:, a:b] = _horner_block(coefficients, slot[a:b], x[a:b])
    return out


def _horner_block(coefficients, slot, x):
    x = over_components(x, coefficients.shape[3])  # (N, 3): a long inner loop
    out = np.take(coefficients[-1], slot, axis=1)
    for k in range(coefficients.shape[0] - 2, -1, -1):
        out *= x
        out += np.take(coefficients[k], slot, axis=1)
    return out


#: Epochs (times sources) that `horner` evaluates at once: 16384 epochs of one
#: source are 400 kB of sums, which stay in the cache (the arithmetic, hence
#: every bit, is that of all epochs at once).
HORNER_BLOCK = 16384

#: Epochs per run of one cell from which `horner` takes a run's coefficients
#: once (broadcast) instead of gathering them for every epoch, and the most
#: runs it loops over. The arithmetic, hence every bit, is the same.
RUN_EPOCHS = 64
MAX_RUNS = 1024


def _horner_by_runs(coefficients, slot, x, starts):
    """`horner` for epochs in runs of one cell: no gather, the same arithmetic.

    Computed epoch-major, (N, S * 3), where each run is one contiguous block,
    and returned as (S, N, 3) in C order (what follows runs faster on it than
    the copy costs).
    """
    degree, n_s, cells, n_c = coefficients.shape
    flat = coefficients.transpose(0, 2, 1, 3).reshape(degree, cells, n_s * n_c)
    width = n_s * n_c
    out = np.empty((slot.size, width))
    bounds = np.concatenate([[0], starts, [slot.size]])
    for a, b in zip(bounds[:-1], bounds[1:]):
        cell = slot[a]
        # x over the components when they are few (a short inner loop otherwise).
        xs = over_components(x[a:b], width) if width <= 4 else x[a:b, np.newaxis]
        segment = out[a:b]
        segment[...] = flat[-1, cell]
        for k in range(degree - 2, -1, -1):
            segment *= xs
            segment += flat[k, cell]
    return np.ascontiguousarray(out.reshape(slot.size, n_s, n_c).transpose(1, 0, 2))


#: TT Julian date of node 0 of `KeptSeries` (2000-01-01T00:00 TT).
KEPT_ORIGIN = 2451544.5
#: Nodes (days) per file of `KeptSeries`.
KEPT_CHUNK = 366
# The chunks kept: within 1901-2098, where ERFA's ephemeris (epv00) is valid.
_KEPT_CHUNKS = range(-99, 99)
_KEPT = {}
# Runs of consecutive chunks as one table, for sparse epochs over years.
_KEPT_SPANS = KeptLast(8)
_KEPT_LOCK = threading.Lock()
# Set when a chunk could not be written: chunks not kept yet are then not
# computed (a year of nodes for a few epochs would be paid by every process).
_UNWRITABLE = False


def kept_path(name, chunk, evaluate=None):
    """The file of chunk ``chunk`` of the kept nodes of series ``name``.

    Parameters
    ----------
    name : str
        The series.
    chunk : int
        `KEPT_CHUNK` days from ``KEPT_ORIGIN + chunk * KEPT_CHUNK``.
    evaluate : callable, optional
        The function that computes the series: its code is part of the name,
        so that a changed function never reads the nodes of the old one.

    Returns
    -------
    pathlib.Path
        In astropy's cache directory, named after the series, the chunk, the
        versions of pyerfa and ERFA and the code that computed it.

    Examples
    --------
    >>> from astropy_feedrot.earth.nodes import kept_path
    >>> kept_path("cip", 23).name.startswith("cip-23-")
    True
    """
    stamp = [erfa.__version__, erfa.version.erfa_version, KEPT_ORIGIN, KEPT_CHUNK]
    code = getattr(evaluate, "__code__", None)
    if code is not None:
        stamp += [code.co_code, repr(code.co_consts), code.co_names]
    key = hashlib.blake2b(repr(stamp).encode(), digest_size=8).hexdigest()
    return pathlib.Path(get_cache_dir()) / "astropy_feedrot" / f"{name}-{chunk}-{key}.npy"


def clear_kept_nodes():
    """Forget the kept nodes held in memory (the files stay).

    Examples
    --------
    >>> from astropy_feedrot.earth.nodes import clear_kept_nodes
    >>> clear_kept_nodes()
    """
    with _KEPT_LOCK:
        _KEPT.clear()
    _KEPT_SPANS.clear()


class KeptSeries(Series):
    """A `Series` whose nodes are whole days of TT, computed once and kept.

    The values at the nodes of a slow quantity depend on nothing but the
    day: they are computed a year (`KEPT_CHUNK` days) at a time, kept in
    memory and in a file of astropy's cache directory (`kept_path`), and
    shared by every computation after, in this process and the next. A
    computation at sparse epochs (one a day, or fewer) then costs an
    interpolation per epoch instead of ERFA's series, and a year of hourly
    epochs needs no evaluation of its own. Where no file can be written, the
    nodes are kept in memory only. Nodes outside 1901-2098 are computed as a
    `Series` computes them.

    Parameters
    ----------
    name : str
        What the nodes are called in their files (one name per ``evaluate``).
    evaluate : callable
        ``evaluate(tt1, tt2)``: the quantity at M instants, shape (M, C).
    order : int
        Nodes per Lagrange polynomial.
    tt1, tt2 : float
        The two-part JD (TT) from which instants are counted in days.

    Examples
    --------
    >>> import erfa
    >>> import numpy as np
    >>> from astropy_feedrot.earth.nodes import KeptSeries
    >>> def era(tt1, tt2):  # a smooth stand-in for a slow series
    ...     return np.stack([np.sin(tt2 / 30.0), np.cos(tt2 / 30.0)], axis=-1)
    >>> series = KeptSeries("doctest-example", era, 12, 2451544.5, 8000.3)
    >>> tt = np.linspace(0, 40, 7)
    >>> bool(np.allclose(series.at(tt), era(2451544.5, 8000.3 + tt), atol=1e-12))
    True
    """

    def __init__(self, name, evaluate, order, tt1, tt2):
        super().__init__(evaluate, 1.0, order, tt1, tt2)
        self.name = name
        self.shift = (tt1 - KEPT_ORIGIN) + tt2

    def nodes_ready(self, tt):
        """Whether the kept nodes serve these instants (see `Series.nodes_ready`).

        Always, within the kept years, unless a chunk is missing and cannot be
        written: each instant's value is then the polynomial through the same
        nodes whatever other instants are computed with it (a file corrected
        in chunks is the file corrected at once, bit for bit).
        """
        if tt.size == 0:
            return False
        low = int(np.floor(float(tt.min()) + self.shift)) + int(self.offsets[0])
        high = int(np.floor(float(tt.max()) + self.shift)) + int(self.offsets[-1])
        chunks = range(low // KEPT_CHUNK, high // KEPT_CHUNK + 1)
        if not all(c in _KEPT_CHUNKS for c in chunks):
            return False
        if not _UNWRITABLE:
            return True
        with _KEPT_LOCK:
            missing = [c for c in chunks if (self.name, c) not in _KEPT]
        return all(kept_path(self.name, c, self.evaluate).exists() for c in missing)

    def nodes(self, needed):
        """Values at whole days ``needed`` (from `KEPT_ORIGIN`), from the kept chunks."""
        needed = np.asarray(needed, dtype=np.int64)
        which = needed // KEPT_CHUNK
        if which.size and which.min() == which.max():  # one chunk (one year)
            chunk = int(which[0])
            if chunk not in _KEPT_CHUNKS:
                return self._computed(needed)
            return self._chunk(chunk)[needed - chunk * KEPT_CHUNK]
        chunks = np.unique(which)
        if not all(int(c) in _KEPT_CHUNKS for c in chunks):
            return self._computed(needed)
        first, last = int(chunks[0]), int(chunks[-1])
        if chunks.size == last - first + 1:  # consecutive years: one gather from them all
            return self._years(first, last)[needed - first * KEPT_CHUNK]
        tables = {int(c): self._chunk(int(c)) for c in chunks}
        out = np.empty((needed.size, next(iter(tables.values())).shape[-1]))
        if np.all(which[1:] >= which[:-1]):  # sorted (as Series.at asks): runs of a chunk
            bounds = np.searchsorted(which, np.append(chunks, chunks[-1] + 1))
            for c, start, stop in zip(tables, bounds[:-1].tolist(), bounds[1:].tolist()):
                out[start:stop] = tables[c][needed[start:stop] - c * KEPT_CHUNK]
            return out
        for c, table in tables.items():
            here = which == c
            out[here] = table[needed[here] - c * KEPT_CHUNK]
        return out

    def stencils(self, j, low):
        """Values (P, order, C) at the kept nodes around each interval ``j``, or None.

        One gather from the kept table of the years they span; None outside
        the kept years (`nodes` computes those).
        """
        first = int(low) + int(self.offsets[0])
        last = int(j.max()) + int(self.offsets[-1])
        first_chunk, last_chunk = first // KEPT_CHUNK, last // KEPT_CHUNK
        if first_chunk not in _KEPT_CHUNKS or last_chunk not in _KEPT_CHUNKS:
            return None
        table = self._years(first_chunk, last_chunk)
        start = j.astype(np.int64) + (int(self.offsets[0]) - first_chunk * KEPT_CHUNK)
        return table[start[:, np.newaxis] + np.arange(self.order)]

    def _computed(self, needed):
        """Nodes outside the kept years, from ERFA (kept in this series only)."""
        missing = [j for j in needed.tolist() if j not in self._nodes]
        if missing:
            days = np.array(missing, dtype=float)
            for j, row in zip(missing, self.evaluate(KEPT_ORIGIN, days)):
                self._nodes[j] = row
        return np.array([self._nodes[j] for j in needed.tolist()])

    def _years(self, first, last):
        """The kept chunks ``first`` to ``last`` as one table (the last few kept)."""
        if first == last:  # one year: its chunk itself, not a copy
            return self._chunk(first)
        key = (self.name, first, last)
        table = _KEPT_SPANS.get(key)
        if table is None:
            table = np.concatenate([self._chunk(c) for c in range(first, last + 1)])
            table.flags.writeable = False
            _KEPT_SPANS.put(key, table)
        return table

    def _chunk(self, chunk):
        key = (self.name, chunk)
        with _KEPT_LOCK:
            table = _KEPT.get(key)
        if table is not None:
            return table
        path = kept_path(self.name, chunk, self.evaluate)
        try:
            table = np.load(path)
        except (OSError, ValueError):  # not kept yet, or unreadable: compute it
            table = None
        if table is None or table.ndim != 2 or len(table) != KEPT_CHUNK:
            days = chunk * KEPT_CHUNK + np.arange(KEPT_CHUNK, dtype=float)
            table = in_parallel(self.evaluate, KEPT_ORIGIN, days)
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
                with tempfile.NamedTemporaryFile(dir=path.parent, suffix=".npy",
                                                 delete=False) as f:
                    np.save(f, table)
                os.replace(f.name, path)  # whole or not at all
            except OSError:  # a read-only cache: this chunk in memory, no new ones
                global _UNWRITABLE
                _UNWRITABLE = True
        with _KEPT_LOCK:
            _KEPT[key] = table
        return table
