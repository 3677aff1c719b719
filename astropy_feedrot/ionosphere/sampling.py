# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Where to evaluate a slowly varying quantity: a coarse grid of epochs, then linear interpolation.

Pure numpy on epochs given as seconds. The rotation measure changes on the
time scale of the ionosphere maps (15 min to 2 h) and of the line of sight
(the Earth's rotation), so evaluating it every ``step`` seconds (60 s by
default) and interpolating linearly to the epochs asked costs one evaluation
per step and per antenna however many epochs there are. The nodes lie on
multiples of ``step`` counted from a UTC midnight, so that they include the
epochs of the maps (whole minutes) where the maps' time interpolation bends.
"""

import numpy as np

__all__ = ["coarse_nodes", "interpolate"]


def coarse_nodes(seconds, step, groups=None):
    """The epochs at which to evaluate, for ``seconds`` to be interpolated from them.

    Parameters
    ----------
    seconds : `~numpy.ndarray`
        Epochs, in seconds from a UTC midnight, 1-D, sorted and unique.
    step : float
        Spacing of the grid in seconds; 0 evaluates every epoch.
    groups : `~numpy.ndarray` of int, optional
        A label per epoch; the grid does not cross from one label to the next
        (e.g. an interval that the data cover, so that no node falls in a gap
        between two of them). One group by default.

    Returns
    -------
    `~numpy.ndarray`
        Sorted unique node epochs in seconds: in each group its first and
        last epoch and the multiples of ``step`` between them. They are the
        epochs themselves when there are no more epochs than that.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.ionosphere.sampling import coarse_nodes
    >>> coarse_nodes(np.arange(30.0, 200.0, 10.0), 60.0)
    array([ 30.,  60., 120., 180., 190.])
    >>> coarse_nodes(np.array([0.0, 100.0]), 60.0)
    array([  0., 100.])
    """
    seconds = np.asarray(seconds, dtype=float)
    if step <= 0 or seconds.size <= 2:
        return seconds
    groups = np.zeros(seconds.shape, dtype=int) if groups is None else np.asarray(groups)
    starts = np.flatnonzero(np.r_[True, groups[1:] != groups[:-1]])
    stops = np.r_[starts[1:], seconds.size] - 1
    pieces = []
    for first, last in zip(seconds[starts], seconds[stops]):  # one per covered interval
        inner = np.arange(np.floor(first / step) + 1, np.ceil(last / step)) * step
        pieces.append(np.r_[first, inner[(inner > first) & (inner < last)], last])
    nodes = np.unique(np.concatenate(pieces))
    return seconds if nodes.size >= seconds.size else nodes


def interpolate(seconds, nodes, values):
    """Values at ``seconds``, linear between the ``nodes``.

    Parameters
    ----------
    seconds : `~numpy.ndarray`
        Epochs in seconds, 1-D, within the span of ``nodes``.
    nodes : `~numpy.ndarray`
        Sorted node epochs in seconds, 1-D.
    values : `~numpy.ndarray`
        Values at ``nodes``: shape (nodes,) or (nodes, L), one series per column.

    Returns
    -------
    `~numpy.ndarray`
        Shape (seconds,) or (seconds, L).

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.ionosphere.sampling import interpolate
    >>> interpolate(np.array([15.0, 30.0]), np.array([0.0, 60.0]), np.array([0.0, 4.0]))
    array([1., 2.])
    >>> interpolate(np.array([30.0]), np.array([0.0, 60.0]), np.array([[0.0, 2.0], [4.0, 6.0]]))
    array([[2., 4.]])
    """
    seconds = np.asarray(seconds, dtype=float)
    values = np.asarray(values, dtype=float)
    if nodes.size == 1:
        return np.broadcast_to(values[0], seconds.shape + values.shape[1:]).copy()
    if values.ndim == 1:
        return np.interp(seconds, nodes, values)
    return np.column_stack([np.interp(seconds, nodes, column) for column in values.T])
