# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Orbits from IGS SP3 precise-orbit files, interpolated with sliding Lagrange polynomials.

`SP3Orbit` is one satellite of an SP3 file; `lagrange_interpolate` is the
interpolation, in stretches without gaps.
"""

import numpy as np
from astropy import units as u

from ..core.exceptions import OrbitWarning, warn_caller
from ..earth.frames import as_time
from ..io import SP3Data, read_sp3
from .orbit_interface import Orbit, check_orientation

__all__ = ["SP3Orbit", "lagrange_interpolate", "points_needed", "MAX_EXTRAPOLATION",
           "POSITION_TOLERANCE"]

#: The longest extrapolation (s) before the first or after the last epoch of an SP3
#: file: RTKLIB's MAXDTE (pephpos in preceph.c).
MAX_EXTRAPOLATION = 900.0

#: The interpolation error (m) that `points_needed` allows. A position error turns the
#: line of sight and the nominal yaw by about its size over the distance, amplified near
#: the noon and midnight turns; 10 m keeps the wind-up within 1e-4 cycle with a margin
#: (tests/gnss/test_gnss_arcs.py measures it against the exact orbits).
POSITION_TOLERANCE = 10.0

_GM_EARTH = 3.986004418e14  # m3/s2, IERS Conventions 2010
_OMEGA_EARTH = 7.292115e-5  # rad/s


class SP3Orbit(Orbit):
    """An orbit from an IGS SP3 precise-orbit file, interpolated in time.

    Parameters
    ----------
    source : str, path-like, file object or `~astropy_feedrot.io.SP3Data`
        An SP3-c or SP3-d file, or its contents (several days joined by
        `~astropy_feedrot.io.sp3.join_sp3`, for instance).
    satellite : str
        The satellite's SP3 name, e.g. ``'G05'``.
    points : int, optional
        Number of consecutive epochs of the sliding window of the Lagrange
        interpolating polynomial (default 10, i.e. degree 9, the usual choice
        for 5- and 15-minute IGS orbits).
    extrapolate : float or `~astropy.units.Quantity`, optional
        Seconds before the first and after the last epoch of the file where
        positions are extrapolated (default 0: none; at most 900).

    Attributes
    ----------
    satellite, points : str, int
        As given.
    epochs : `~astropy.time.Time`
        The epochs of the file.
    interval : `~astropy.units.Quantity`
        The epoch interval of the file's header.
    spans : `~astropy.time.Time`, shape (K, 2)
        Start and end of each stretch where positions are interpolated:
        ``points`` or more consecutive epochs at the file's interval, all
        with a valid position of the satellite.

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        If the file is malformed (naming the line and what was expected).
    TypeError
        If ``points`` is not an integer (2.5 would be cut to 2 otherwise).
    ValueError
        If ``satellite`` is not in the file (listing those that are), the
        file has fewer epochs than ``points``, or the satellite has nowhere
        ``points`` consecutive valid epochs.

    Warns
    -----
    `~astropy_feedrot.OrbitWarning`
        From `position`, once per call, when some times fall in a hole.

    Notes
    -----
    Positions are interpolated coordinate by coordinate with a polynomial
    through ``points`` consecutive epochs around each requested time (a
    centred window, shifted at the ends of a stretch). Times outside the
    file's epochs raise an error.

    With ``extrapolate``, times up to that many seconds before the first or
    after the last epoch (at most ``MAX_EXTRAPOLATION``, 900 s, as RTKLIB's
    ``MAXDTE``) get the polynomial of the window at that end, evaluated
    outside it; its error grows as ``(omega h)**points`` (see
    `points_needed`): metres for 10 points and one 15-minute interval.

    The window is made only of consecutive epochs at the interval of the
    file's header where the satellite has a valid position. A hole is any
    break in that: epochs the file skips, an epoch without a record of the
    satellite, a position marked bad or absent (0.000000 for x, y and z). A
    requested time that cannot be given such a window (in a hole, or in a
    stretch of fewer than ``points`` valid epochs between holes) gets NaN,
    and each call warns once (`~astropy_feedrot.OrbitWarning`) with the
    number of such times: no position is ever interpolated across a hole.
    Within a stretch, times near a hole use a window shifted away from it, as
    at the ends of the file. (In a file in UTC or GLONASS time, a leap second
    between two epochs breaks the interval too, and makes a hole.)

    Examples
    --------
    The sample file has four 15-minute epochs, enough for a cubic:

    >>> import numpy as np
    >>> from astropy.time import Time
    >>> from astropy_feedrot import SP3Orbit
    >>> from astropy_feedrot.data import sample_file
    >>> orbit = SP3Orbit(sample_file("sample.sp3"), "G01", points=4)
    >>> xyz = orbit.position(Time("2023-01-25T00:20:00", scale="tai"))
    >>> round(float(np.linalg.norm(xyz)) / 1e3)  # km from the geocentre
    26560
    >>> orbit.spans.isot
    array([['2023-01-25T00:00:19.000', '2023-01-25T00:45:19.000']], dtype='<U23')
    """

    def __init__(self, source, satellite, points=10, extrapolate=0.0):
        data = source if isinstance(source, SP3Data) else read_sp3(source)
        if satellite not in data.positions:
            raise ValueError(
                f"satellite {satellite!r} is not in the SP3 file; it has "
                f"{', '.join(data.satellites)}"
            )
        if isinstance(points, bool) or not isinstance(points, (int, np.integer)):
            raise TypeError(f"points must be a whole number of epochs (int), got {points!r}")
        points = int(points)
        if points < 2:
            raise ValueError(f"points must be at least 2, got {points}")
        if len(data.epochs) < points:
            raise ValueError(
                f"the SP3 file has {len(data.epochs)} epochs, fewer than the {points} "
                "points of the interpolation window"
            )
        self.satellite = satellite
        self.points = points
        self.epochs = data.epochs
        self.interval = data.interval * u.s
        self.coordinate_system = data.coordinate_system
        self._t0 = data.epochs[0]
        self._seconds = (data.epochs - self._t0).to_value(u.s)
        self._xyz = data.positions[satellite]
        self._run_start, self._run_end = _stretches(self._seconds, self._xyz, data.interval)
        long_enough = self._run_end - self._run_start + 1 >= points
        if not np.any(long_enough):
            raise ValueError(
                f"{satellite} has no {points} consecutive epochs at the {data.interval:g} s "
                "interval of the SP3 file with a valid position, as the interpolation window "
                f"needs (its longest stretch has {np.max(self._run_end - self._run_start) + 1}); "
                "give fewer points or a file without holes"
            )
        self._usable = long_enough
        extrapolate = u.Quantity(extrapolate, u.s).to_value(u.s)
        if not 0 <= extrapolate <= MAX_EXTRAPOLATION:
            raise ValueError(f"extrapolate must be 0 to {MAX_EXTRAPOLATION:g} s, got "
                             f"{float(extrapolate)!r} s")
        self.extrapolate = extrapolate * u.s

    def __repr__(self):
        return (
            f"<SP3Orbit {self.satellite} {self.coordinate_system}, {len(self.epochs)} epochs "
            f"{self.epochs[0].isot} to {self.epochs[-1].isot}>"
        )

    @property
    def spans(self):
        """`~astropy.time.Time`, shape (K, 2): where positions are interpolated."""
        start = self._run_start[self._usable]
        end = self._run_end[self._usable]
        return self.epochs[np.stack([start, end], axis=-1)]

    @property
    def coverage(self):
        """(start, stop): the first and last epochs of the file, outside which
        `position` raises."""
        return self.epochs[0], self.epochs[-1]

    def position(self, obstime, orientation=None):
        # The file's positions are Earth-fixed already: no Earth orientation needed.
        obstime = as_time(obstime)
        check_orientation(orientation, obstime)
        x = np.atleast_1d((obstime - self._t0).to_value(u.s)).ravel()
        tol = 1e-6
        margin = tol + self.extrapolate.to_value(u.s)
        outside = (x < self._seconds[0] - margin) | (x > self._seconds[-1] + margin)
        if np.any(outside):
            beyond = f" (extrapolated up to {self.extrapolate.to_value(u.s):g} s beyond)" \
                if margin > tol else ""
            raise ValueError(
                f"times outside the coverage of the SP3 orbit of {self.satellite}: "
                f"{self.epochs[0].isot} to {self.epochs[-1].isot} {self.epochs.scale.upper()}"
                + beyond
            )
        run = _stretch_of(self._seconds, self._run_start, self._run_end, x, tol)
        # Beyond the first or last epoch (extrapolate): the stretch ending there, as RTKLIB
        # extrapolates the polynomial of its end window (pephpos, up to 900 s).
        for node, side in ((0, x < self._seconds[0] - tol),
                           (len(self._seconds) - 1, x > self._seconds[-1] + tol)):
            if np.any(side):
                k = np.searchsorted(self._run_start, node, side="right") - 1
                run[side] = k if self._run_start[k] <= node <= self._run_end[k] else -1
        ok = run >= 0
        ok[ok] = self._usable[run[ok]]
        out = np.full(x.shape + (3,), np.nan)
        if np.any(ok):
            first = self._run_start[run[ok]]
            last = self._run_end[run[ok]]
            start = np.searchsorted(self._seconds, x[ok]) - self.points // 2
            start = np.clip(start, first, last - self.points + 1)
            out[ok] = _lagrange(self._seconds, self._xyz, x[ok], start, self.points)
        if not np.all(ok):
            bad = np.flatnonzero(~ok)
            first_bad = (self._t0 + x[bad[0]] * u.s).isot
            warn_caller(
                f"{bad.size} of {x.size} times fall in holes of the SP3 orbit of "
                f"{self.satellite} (the first at {first_bad} {self.epochs.scale.upper()}), "
                f"where no {self.points} consecutive epochs at the {self.interval.value:g} s "
                "interval have valid positions: skipped epochs, missing records or positions "
                "marked bad; NaN is returned there (SP3Orbit.spans lists where positions are "
                "interpolated)",
                OrbitWarning,
            )
        return out.reshape(obstime.shape + (3,))


def _stretches(seconds, xyz, interval, tol=1e-3):
    """First and last index of each stretch of consecutive valid epochs at the interval.

    An epoch without a valid position is a stretch of its own, never usable
    (its length is counted as 0 by making its last index precede its first).
    """
    valid = np.all(np.isfinite(xyz), axis=-1)
    step = np.abs(np.diff(seconds) - interval) < tol
    link = valid[:-1] & valid[1:] & step
    starts = np.flatnonzero(np.r_[True, ~link])
    ends = np.r_[starts[1:] - 1, len(seconds) - 1]
    ends = np.where(valid[starts], ends, starts - 1)
    return starts, ends


def _stretch_of(seconds, run_start, run_end, x, tol):
    """Index of the stretch each time lies in, -1 in a hole."""
    node = np.clip(np.searchsorted(seconds, x - tol, side="left"), 0, len(seconds) - 1)
    # The last node at or before x (up to tol), and the stretch holding it.
    node = np.where(seconds[node] > x + tol, node - 1, node)
    node = np.clip(node, 0, len(seconds) - 1)
    run = np.searchsorted(run_start, node, side="right") - 1
    at_node = np.abs(seconds[node] - x) <= tol
    next_in_run = (node + 1 <= run_end[run])
    inside = (node <= run_end[run]) & (at_node | next_in_run)
    return np.where(inside, run, -1)


def lagrange_interpolate(x, y, x_new, points):
    """Sliding-window Lagrange interpolation of tabulated values.

    Parameters
    ----------
    x : ndarray, shape (N,)
        Increasing abscissae of the table.
    y : ndarray, shape (N, ...)
        Tabulated values.
    x_new : ndarray, shape (M,)
        Where to interpolate (within ``x[0]..x[-1]``).
    points : int
        Window length: the polynomial goes through the ``points`` table
        entries nearest to each ``x_new``.

    Returns
    -------
    ndarray, shape (M, ...)
        Interpolated values; NaN where the window holds a NaN.

    Notes
    -----
    The window is chosen by position in the table only: this function does
    not know about holes in it. `SP3Orbit` chooses windows that avoid them.

    Examples
    --------
    A cubic is reproduced exactly by a 4-point window:

    >>> import numpy as np
    >>> from astropy_feedrot.transmitters.orbits import lagrange_interpolate
    >>> x = np.arange(10.0)
    >>> float(lagrange_interpolate(x, x**3, np.array([4.5]), 4)[0])
    91.125
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    x_new = np.asarray(x_new, dtype=float)
    n = len(x)
    start = np.searchsorted(x, x_new) - points // 2
    start = np.clip(start, 0, n - points)
    return _lagrange(x, y, x_new, start, points)


def _lagrange(x, y, x_new, start, points):
    """Lagrange interpolation through the window ``start[m]:start[m] + points`` for each x_new."""
    window = start[:, np.newaxis] + np.arange(points)  # (M, points)
    xs = x[window]
    # Lagrange basis: w_j = prod_{k != j} (x_new - x_k) / (x_j - x_k)
    diff = x_new[:, np.newaxis] - xs  # (M, points)
    denom = xs[:, :, np.newaxis] - xs[:, np.newaxis, :]  # (M, points, points)
    eye = np.eye(points, dtype=bool)
    denom[:, eye] = 1.0
    numer = np.broadcast_to(diff[:, np.newaxis, :], denom.shape).copy()
    numer[:, eye] = 1.0
    weights = np.prod(numer / denom, axis=-1)  # (M, points)
    values = y[window]  # (M, points, ...)
    return np.einsum("mp,mp...->m...", weights, values)


def points_needed(interval, radius=20e6, tolerance=POSITION_TOLERANCE):
    """The fewest Lagrange points that interpolate an orbit sampled every ``interval`` well.

    Parameters
    ----------
    interval : float or `~astropy.units.Quantity`
        The epoch interval of the orbit file (s).
    radius : float, optional
        The smallest orbit radius of its satellites (m; default 20,000 km,
        below every GNSS orbit: the fastest).
    tolerance : float, optional
        The interpolation error allowed (m; default ``POSITION_TOLERANCE``, 10).

    Returns
    -------
    int
        The smallest ``n >= 2`` whose error bound is within ``tolerance``.

    Notes
    -----
    The rule: the error of a polynomial through ``n`` points ``h`` apart is
    at most ``|f^(n)| / n! * max |prod (t - t_k)|``. An Earth-fixed orbit of
    radius ``r`` turns at most at ``omega = sqrt(GM / r**3) + Omega_Earth``,
    so ``|f^(n)| <= r omega**n``; in the first or last interval of a window
    shifted to an end (the worst place inside a file) the product is at most
    ``h**n max_{0 <= s <= 1} |s (s - 1) ... (s - n + 1)|``.

    Examples
    --------
    >>> from astropy_feedrot.transmitters.sp3_orbit import points_needed
    >>> points_needed(900.0), points_needed(300.0), points_needed(30.0)
    (8, 5, 3)
    """
    h = u.Quantity(interval, u.s).to_value(u.s)
    omega = np.sqrt(_GM_EARTH / radius**3) + _OMEGA_EARTH
    s = np.linspace(0.0, 1.0, 201)
    product = np.ones_like(s)
    factorial = 1.0
    for n in range(1, 40):
        product = product * np.abs(s - (n - 1))
        factorial *= n
        if n >= 2 and radius * (omega * h) ** n * product.max() / factorial <= tolerance:
            return n
    return 40
