# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Arcs of a satellite's wind-up, and the orbit files a RINEX file is missing.

`Arcs` keeps each satellite's wind-up continuous (Eq 9) from one epoch to
the next, across blocks of epochs, as RTKLIB keeps its ``phw`` (windupcorr
in rtkcmn.c): the accumulated value carries on through loss-of-lock flags,
power failures and events, because it is geometry, not a measurement; only
after a gap longer than ``max_gap`` does a new arc start at the principal
value, the same for every signal of the satellite (the wind-up is one value
per satellite), so no phase ever gets a step that another phase of the same
satellite lacks.

`orbit_file_name` names the SP3 file of a day, after the IGS long names.
"""

import re

import numpy as np
from astropy.time import Time

__all__ = ["Arcs", "orbit_file_name"]

#: The fraction of the sampling interval by which a gap may exceed ``max_gap``
#: and still belong to the arc: epoch times carry rounding (a 30 s step reads
#: 30.000000001 s), and a gap of one more missing epoch exceeds it by a whole interval.
GAP_TOLERANCE = 0.5

# IGS long product names (IGS "Guidelines for long product filenames", 2017), e.g.
# GRG0MGXFIN_20201770000_01D_15M_ORB.SP3.gz: centre, year, day of year, hour, minute.
_LONG_NAME = re.compile(r"^(?P<head>[A-Z0-9]{10}_)(?P<date>\d{11})(?P<tail>_\d\d[A-Z]_\d\d[A-Z]_"
                        r"ORB\.SP3)", re.IGNORECASE)


class Arcs:
    """Continuous wind-up along each satellite's arcs, across blocks of epochs.

    Parameters
    ----------
    max_gap : float
        Seconds: a satellite's gap longer than this starts a new arc.
    interval : float, optional
        The sampling interval (s; the RINEX header's ``INTERVAL``). Without
        it, the smallest step between epochs of the first block is used.

    Attributes
    ----------
    arcs : int
        Arcs started so far.

    Examples
    --------
    A wind-up turning by 0.3 cycle per epoch, unwrapped along one arc:

    >>> import numpy as np
    >>> from astropy_feedrot.gnss.arcs import Arcs
    >>> arcs = Arcs(max_gap=30.0, interval=30.0)
    >>> t = np.arange(5) * 30.0
    >>> wrapped = (0.3 * np.arange(5) + 0.5) % 1 - 0.5
    >>> arcs.apply(np.array(["G01"] * 5, dtype=object), t, wrapped)  # doctest: +FLOAT_CMP
    array([0. , 0.3, 0.6, 0.9, 1.2])
    >>> arcs.arcs
    1
    """

    def __init__(self, max_gap, interval=None):
        self.max_gap = float(max_gap)
        self.interval = interval
        self.last = {}  # prn -> (seconds, wrapped cycles, whole cycles)
        self.arcs = 0

    def tolerance(self, seconds):
        """Seconds by which a gap may exceed ``max_gap`` (a fraction of the interval)."""
        if not self.interval:  # unknown: the smallest step seen (kept once there is one)
            steps = np.diff(np.unique(np.round(seconds, 6)))
            self.interval = float(steps.min()) if steps.size else None
        return GAP_TOLERANCE * (self.interval or 0.0) + 1e-6

    def apply(self, prns, seconds, wrapped):
        """Continuous wind-up (cycles) of rows given in time order per PRN.

        Parameters
        ----------
        prns : ndarray of object, shape (R,)
            The satellite of each row.
        seconds : ndarray, shape (R,)
            Its time (s, on one scale for the whole file).
        wrapped : ndarray, shape (R,)
            Its wind-up in cycles, in [-0.5, 0.5).

        Returns
        -------
        ndarray, shape (R,)
            ``wrapped`` plus the whole cycles that keep each arc continuous.
        """
        order = np.lexsort((seconds, prns))
        p, t, w = prns[order], seconds[order], wrapped[order]
        first = np.r_[True, p[1:] != p[:-1]]
        prev_t = np.r_[np.nan, t[:-1]]
        prev_w = np.r_[np.nan, w[:-1]]
        carried = np.zeros(len(p))
        for k in np.flatnonzero(first):  # one per satellite: its state from the last block
            state = self.last.get(p[k])
            if state is None:
                prev_t[k], prev_w[k] = -np.inf, np.nan
            else:
                prev_t[k], prev_w[k], carried[k] = state
        limit = self.max_gap + self.tolerance(seconds)
        new = (t - prev_t > limit) | np.isnan(prev_w)
        step = np.where(new, 0.0, np.rint(prev_w - w) + np.where(first, carried, 0.0))
        start = new | first
        total = np.cumsum(step)
        begin = np.maximum.accumulate(np.where(start, np.arange(len(p)), 0))
        whole = total - total[begin] + step[begin]
        self.arcs += int(np.count_nonzero(new))
        last = np.r_[p[1:] != p[:-1], True] if len(p) else np.zeros(0, bool)
        for k in np.flatnonzero(last):
            self.last[p[k]] = (t[k], w[k], whole[k])
        out = np.empty(len(p))
        out[order] = w + whole
        return out


def orbit_file_name(names, day):
    """The name of the SP3 file of ``day``, after the names of the files given.

    Parameters
    ----------
    names : sequence of str
        The SP3 files given (paths or names).
    day : `~astropy.time.Time`
        A time in the day missing, on the scale whose calendar names the
        files (GPS time for IGS products: TAI - 19 s written as TAI).

    Returns
    -------
    str
        The IGS long name of that day's file of the same product if a name
        given is one (``GRG0MGXFIN_20201780000_01D_15M_ORB.SP3``), else the
        pattern of any product's (``*_20201780000_01D_*_ORB.SP3``).

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy_feedrot.gnss.arcs import orbit_file_name
    >>> orbit_file_name(["/data/GRG0MGXFIN_20201770000_01D_15M_ORB.SP3.gz"],
    ...                 Time("2020-06-26T00:00:00"))
    'GRG0MGXFIN_20201780000_01D_15M_ORB.SP3'
    >>> orbit_file_name(["orbits.sp3"], Time("2020-06-26T00:00:00"))
    '*_20201780000_01D_*_ORB.SP3'
    """
    date = Time(day).strftime("%Y%j") + "0000"
    for name in names:
        match = _LONG_NAME.match(str(name).replace("\\", "/").rsplit("/", 1)[-1])
        if match and match["tail"].upper().startswith("_01D"):
            return f"{match['head']}{date}{match['tail']}"
    return f"*_{date}_01D_*_ORB.SP3"
