# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Figures of the tables of `astropy_feedrot.tables` (needs matplotlib).

matplotlib is an optional dependency: ``pip install "astropy_feedrot[all]"``.
The functions draw on a new pyplot figure and return it, so ``plt.show()``
and notebooks display it; close it with ``plt.close(fig)`` when drawing many.
"""

import numpy as np
from astropy import units as u

__all__ = ["plot_feed_rotation", "plot_baseline"]

_TERMS = (("transmitter", "transmitter term"), ("receiver", "receiver term"),
          ("continuous", "total (continuous)"))


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError:
        raise ImportError('plotting needs matplotlib: pip install "astropy_feedrot[all]"') from None
    return plt


def _degrees(column):
    """Degrees of a column, with NaN at the jumps of a wrapped angle (no vertical lines)."""
    values = np.array(u.Quantity(column).to_value(u.deg), dtype=float)
    values[1:][np.abs(np.diff(values)) > 180] = np.nan
    return values


def _hours(table):
    times = table["time"]
    return (times - times[0]).to_value(u.hour), f"hours since {times[0].utc.isot[:19]} UTC"


def _finish(fig, path):
    if path is not None:
        fig.savefig(path, dpi=100, bbox_inches="tight")
    return fig


def plot_feed_rotation(table, path=None):
    """Draw a `~astropy_feedrot.tables.feed_rotation_table`.

    Parameters
    ----------
    table : `~astropy.table.Table`
        A table with the columns of `~astropy_feedrot.tables.feed_rotation_table`.
    path : str or path-like, optional
        Save the figure there (the format follows the extension).

    Returns
    -------
    `matplotlib.figure.Figure`
        Elevation on top; transmitter, receiver and continuous total feed
        rotation below, against hours since the first epoch.

    Raises
    ------
    ImportError
        Without matplotlib.
    KeyError
        If a column is missing.

    Examples
    --------
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import SkyCoord
    >>> from astropy.time import Time
    >>> from astropy_feedrot.plotting import plot_feed_rotation
    >>> from astropy_feedrot.stations import get_antenna
    >>> from astropy_feedrot.tables import feed_rotation_table
    >>> times = Time("2023-01-25T12:00") + np.arange(0, 12, 0.5) * u.hour
    >>> table = feed_rotation_table(get_antenna("YEBES40M"),
    ...                             SkyCoord("03h19m48.16s +41d30m42.1s"), times)
    >>> fig = plot_feed_rotation(table)
    >>> len(fig.axes)
    2
    """
    missing = [c for c in ("time", "elevation", *(c for c, _ in _TERMS)) if c not in table.colnames]
    if missing:
        raise KeyError(f"the table lacks column(s) {', '.join(missing)}; plot a "
                       "feed_rotation_table")
    plt = _pyplot()
    hours, label = _hours(table)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True,
                                      gridspec_kw={"height_ratios": (1, 2)})
    top.plot(hours, _degrees(table["elevation"]), color="k")
    top.set_ylabel("elevation [deg]")
    for column, name in _TERMS:
        bottom.plot(hours, _degrees(table[column]), label=name)
    bottom.set_ylabel("feed rotation [deg]")
    bottom.set_xlabel(label)
    bottom.legend(loc="best")
    fig.suptitle(f"{table.meta.get('antenna', '')}: {table.meta.get('target', '')}")
    return _finish(fig, path)


def plot_baseline(table, path=None):
    """Draw a `~astropy_feedrot.tables.baseline_table` like Figs 10-12 of the paper.

    Parameters
    ----------
    table : `~astropy.table.Table`
        A table with the columns of `~astropy_feedrot.tables.baseline_table`.
    path : str or path-like, optional
        Save the figure there.

    Returns
    -------
    `matplotlib.figure.Figure`
        One panel per antenna with the transmitter and receiver terms and the
        continuous total; a last panel with the rotation delay.

    Raises
    ------
    ImportError
        Without matplotlib.
    KeyError
        If ``meta["antennas"]`` or a column is missing.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.plotting import plot_baseline
    >>> from astropy_feedrot.simulations import gps_short_baseline
    >>> fig = plot_baseline(gps_short_baseline(step=10 * u.min))
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['DBR205 [deg]', 'FD-VLBA [deg]', 'rotation delay [ps]']
    """
    antennas = table.meta.get("antennas")
    if not antennas or len(antennas) != 2:
        raise KeyError("the table's meta lacks the two 'antennas'; plot a baseline_table")
    plt = _pyplot()
    hours, label = _hours(table)
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for ax, name in zip(axes[:2], antennas):
        for column, term in _TERMS:
            ax.plot(hours, _degrees(table[f"{name}_{column}"]), label=term)
        ax.set_ylabel(f"{name} [deg]")
        ax.legend(loc="best")
    delay = u.Quantity(table["rotation_delay"]).to_value(u.ps)
    axes[2].plot(hours, delay, color="k")
    axes[2].set_ylabel("rotation delay [ps]")
    axes[2].set_xlabel(label)
    visible = np.isfinite(delay)
    if visible.any():
        axes[0].set_xlim(hours[visible].min() - 0.25, hours[visible].max() + 0.25)
    fig.suptitle(f"{table.meta.get('target', '')}, {table.meta.get('frequency', '')}")
    return _finish(fig, path)
