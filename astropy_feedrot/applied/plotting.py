# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Figures of the tables of `astropy_feedrot.applied.feed_rotation_tables` and
`astropy_feedrot.applied.faraday_tables` (needs matplotlib).

matplotlib is an optional dependency, of the ``all`` extra (``python -m pip
install matplotlib``).
The functions draw on a new pyplot figure and return it, so ``plt.show()``
and notebooks display it; close it with ``plt.close(fig)`` when drawing many.
"""

import numpy as np
from astropy import units as u

from ..core.extras import install_hint

__all__ = ["plot_feed_rotation", "plot_baseline", "plot_faraday", "line_styles",
           "unwrapped_degrees", "outside_legend", "pyplot"]

# The line styles after the ten colours of matplotlib's "tab10" cycle.
_LINESTYLES = ("-", "--", ":", "-.")


def pyplot():
    """matplotlib's pyplot, imported on use, or an ImportError naming the extra.

    Examples
    --------
    >>> from astropy_feedrot.applied.plotting import pyplot
    >>> pyplot().__name__
    'matplotlib.pyplot'
    """
    try:
        import matplotlib.pyplot as plt  # optional: imported on use
    except ImportError:
        raise ImportError(f"plotting needs matplotlib: {install_hint('all', 'matplotlib')}"
                          ) from None
    return plt


def line_styles(count):
    """A colour and a line style for each of ``count`` lines, no two alike up to 40.

    The ten colours of matplotlib's ``tab10`` cycle, solid; then the same
    colours dashed, dotted and dash-dotted: the eleventh station of a network
    shares the first one's colour but not its style.

    Parameters
    ----------
    count : int
        Number of lines.

    Returns
    -------
    list of (str, str)
        ``(colour, linestyle)`` pairs, colours as ``'#rrggbb'``.

    Examples
    --------
    >>> from astropy_feedrot.applied.plotting import line_styles
    >>> styles = line_styles(11)
    >>> styles[0][0] == styles[10][0], styles[0][1], styles[10][1]
    (True, '-', '--')
    """
    pyplot()  # matplotlib, or the ImportError that names the extra
    from matplotlib import colormaps, colors  # optional: imported on use

    palette = [colors.to_hex(colour) for colour in colormaps["tab10"].colors]
    return [(palette[k % len(palette)], _LINESTYLES[(k // len(palette)) % len(_LINESTYLES)])
            for k in range(count)]


def unwrapped_degrees(column):
    """Degrees of an angle column, unwrapped over each run of finite values.

    A wrapped angle that crosses +-180 deg (the receiver term of an antenna
    near a pole, say) is drawn as the continuous curve it is, not as a line
    jumping across the panel. Each run between NaN values (the target below
    the horizon) starts at its wrapped value.

    Parameters
    ----------
    column : `~astropy.units.Quantity` or `~astropy.table.Column`
        Angles.

    Returns
    -------
    numpy.ndarray
        Degrees, NaN where ``column`` is NaN.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.plotting import unwrapped_degrees
    >>> unwrapped_degrees([170, -170, -150, float("nan"), 170, -170] * u.deg)
    array([170., 190., 210.,  nan, 170., 190.])
    """
    values = np.array(u.Quantity(column).to_value(u.deg), dtype=float)
    finite = np.flatnonzero(np.isfinite(values))
    if finite.size == 0:
        return values
    runs = np.cumsum(np.diff(finite, prepend=finite[0] - 1) > 1)  # a new run after each gap
    steps = np.diff(values[finite], prepend=values[finite[0]])
    steps -= 360.0 * np.round(steps / 360.0)
    starts = np.flatnonzero(np.diff(runs, prepend=-1))
    steps[starts] = 0.0
    continuous = np.cumsum(steps)
    # Each run from its own first value.
    continuous += np.repeat(values[finite[starts]] - continuous[starts],
                            np.diff(np.append(starts, finite.size)))
    values[finite] = continuous
    return values


def outside_legend(ax, **options):
    """A legend to the right of ``ax``, outside the plotted tracks.

    Parameters
    ----------
    ax : `matplotlib.axes.Axes`
        The panel whose lines it lists.
    **options
        Passed on to `matplotlib.axes.Axes.legend`.

    Returns
    -------
    `matplotlib.legend.Legend`

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> from astropy_feedrot.applied.plotting import outside_legend
    >>> fig, ax = plt.subplots()
    >>> _ = ax.plot([0, 1], label="a")
    >>> outside_legend(ax).get_bbox_to_anchor() is not None
    True
    >>> plt.close(fig)
    """
    return ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                     **options)


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


def _has_transmitter(table, prefix=""):
    """Whether the target transmits: a satellite, not a natural source.

    Tables of `~astropy_feedrot.applied.feed_rotation_tables` say so in ``meta['natural']``; a
    table without it is judged by its transmitter term, which is zero (to
    rounding) for a natural source.
    """
    if "natural" in table.meta:
        return not table.meta["natural"]
    values = u.Quantity(table[f"{prefix}transmitter"]).to_value(u.deg)
    return bool(np.nanmax(np.abs(values), initial=0.0) > 1e-9)


def _draw_terms(ax, table, prefix=""):
    """The feed rotation of one antenna: the continuous total, and for a satellite its
    two terms (unwrapped) over it."""
    hours = _hours(table)[0]
    if not _has_transmitter(table, prefix):
        # A natural source: the feed rotation is the receiver term.
        ax.plot(hours, _degrees(table[f"{prefix}continuous"]), color="C1",
                label="feed rotation = receiver term (continuous)")
        return
    ax.plot(hours, _degrees(table[f"{prefix}continuous"]), color="0.6", linewidth=4,
            alpha=0.6, label="total (continuous)")
    ax.plot(hours, unwrapped_degrees(table[f"{prefix}transmitter"]), color="C0",
            label="transmitter term")
    ax.plot(hours, unwrapped_degrees(table[f"{prefix}receiver"]), color="C1", linestyle="--",
            label="receiver term")


def plot_feed_rotation(table, path=None):
    """Draw a `~astropy_feedrot.applied.feed_rotation_tables.feed_rotation_table`.

    Parameters
    ----------
    table : `~astropy.table.Table`
        A table with the columns of `~astropy_feedrot.feed_rotation_table`.
    path : str or path-like, optional
        Save the figure there (the format follows the extension).

    Returns
    -------
    `matplotlib.figure.Figure`
        Elevation on top; below, the continuous total feed rotation and, for
        a satellite, its transmitter and receiver terms (unwrapped), against
        hours since the first epoch; the legend to the right. A natural
        source has no transmitter term: its feed rotation is the receiver
        term, drawn once.

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
    >>> from astropy_feedrot.applied.plotting import plot_feed_rotation
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> from astropy_feedrot.applied.feed_rotation_tables import feed_rotation_table
    >>> times = Time("2023-01-25T12:00") + np.arange(0, 12, 0.5) * u.hour
    >>> table = feed_rotation_table(get_antenna("YEBES40M"),
    ...                             SkyCoord("03h19m48.16s +41d30m42.1s"), times)
    >>> fig = plot_feed_rotation(table)
    >>> len(fig.axes)
    2
    """
    columns = ("time", "elevation", "transmitter", "receiver", "continuous")
    missing = [c for c in columns if c not in table.colnames]
    if missing:
        raise KeyError(f"the table lacks column(s) {', '.join(missing)}; plot a "
                       "feed_rotation_table")
    plt = pyplot()
    hours, label = _hours(table)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True,
                                      gridspec_kw={"height_ratios": (1, 2)})
    top.plot(hours, _degrees(table["elevation"]), color="k")
    top.set_ylabel("elevation [deg]")
    _draw_terms(bottom, table)
    bottom.set_ylabel("feed rotation [deg]")
    bottom.set_xlabel(label)
    outside_legend(bottom)
    fig.suptitle(f"{table.meta.get('antenna', '')}: {table.meta.get('target', '')}")
    return _finish(fig, path)


def plot_baseline(table, path=None):
    """Draw a `~astropy_feedrot.baseline_table` like Figs 10-12 of the paper.

    Parameters
    ----------
    table : `~astropy.table.Table`
        A table with the columns of `~astropy_feedrot.applied.feed_rotation_tables.baseline_table`.
    path : str or path-like, optional
        Save the figure there.

    Returns
    -------
    `matplotlib.figure.Figure`
        One panel per antenna with the continuous total and, for a satellite,
        the transmitter and receiver terms (unwrapped); a last panel with the
        rotation delay.

    Raises
    ------
    ImportError
        Without matplotlib.
    KeyError
        If ``meta["antennas"]`` or a column is missing.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy_feedrot.applied.plotting import plot_baseline
    >>> from astropy_feedrot.applied.simulations import gps_short_baseline
    >>> fig = plot_baseline(gps_short_baseline(step=10 * u.min))
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['DBR205 [deg]', 'FD-VLBA [deg]', 'rotation delay [ps]']
    """
    antennas = table.meta.get("antennas")
    if not antennas or len(antennas) != 2:
        raise KeyError("the table's meta lacks the two 'antennas'; plot a baseline_table")
    plt = pyplot()
    hours, label = _hours(table)
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for ax, name in zip(axes[:2], antennas):
        _draw_terms(ax, table, f"{name}_")
        ax.set_ylabel(f"{name} [deg]")
        outside_legend(ax)
    delay = u.Quantity(table["rotation_delay"]).to_value(u.ps)
    axes[2].plot(hours, delay, color="k")
    axes[2].set_ylabel("rotation delay [ps]")
    axes[2].set_xlabel(label)
    visible = np.isfinite(delay)
    if visible.any():
        axes[0].set_xlim(hours[visible].min() - 0.25, hours[visible].max() + 0.25)
    fig.suptitle(f"{table.meta.get('target', '')}, {table.meta.get('frequency', '')}")
    return _finish(fig, path)


def _faraday_labels(table):
    """The stations and frequency labels of a
    `~astropy_feedrot.applied.faraday_tables.faraday_table`."""
    missing = [c for c in ("time", "antenna", "elevation", "rm", "feed_rotation")
               if c not in table.colnames]
    labels = table.meta.get("labels") or [name[4:] for name in table.colnames
                                          if name.startswith("chi_")]
    missing += [f"{kind}_{label}" for label in labels for kind in ("chi", "psi")
                if f"{kind}_{label}" not in table.colnames]
    if missing or not labels:
        raise KeyError(f"the table lacks column(s) {', '.join(missing) or 'chi_*, psi_*'}; "
                       "plot a faraday_table")
    names = list(table.meta.get("antennas") or dict.fromkeys(np.asarray(table["antenna"])))
    return names, labels


def plot_faraday(table, path=None):
    """Draw a `~astropy_feedrot.applied.faraday_tables.faraday_table`.

    Parameters
    ----------
    table : `~astropy.table.Table`
        A table with the columns of
        `~astropy_feedrot.applied.faraday_tables.faraday_table`.
    path : str or path-like, optional
        Save the figure there (the format follows the extension).

    Returns
    -------
    `matplotlib.figure.Figure`
        Against hours since the first epoch, one colour per station (the
        legend to the right of the top panel): the elevation; the rotation
        measure; the feed rotation Phi (unwrapped); then one panel per
        frequency with psi = Phi - chi (unwrapped) and, thin, the Faraday
        rotation chi = RM lambda^2.

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
    >>> from astropy.table import QTable
    >>> from astropy.time import Time
    >>> from astropy_feedrot.applied.faraday_tables import faraday_table
    >>> from astropy_feedrot.applied.plotting import plot_faraday
    >>> from astropy_feedrot.ionosphere import Ionosphere
    >>> from astropy_feedrot.stations.catalogue import get_antenna
    >>> rm = QTable({"time": Time(["2024-06-01T06:00", "2024-06-01T12:00"]),
    ...              "rm": [1.0, 3.0] * u.rad / u.m**2})
    >>> times = Time("2024-06-01T06:00") + np.arange(0, 6, 0.25) * u.hour
    >>> table = faraday_table([get_antenna("EFLSBERG"), get_antenna("YEBES40M")],
    ...                       SkyCoord("03h19m48.16s +41d30m42.1s"), times,
    ...                       Ionosphere.from_rm(rm), [150, 1400] * u.MHz)
    >>> fig = plot_faraday(table)
    >>> [ax.get_ylabel() for ax in fig.axes]  # doctest: +NORMALIZE_WHITESPACE
    ['elevation [deg]', 'RM [rad/m$^2$]', 'feed rotation [deg]', '150MHz [deg]',
     '1.4GHz [deg]']
    """
    names, labels = _faraday_labels(table)
    plt = pyplot()
    hours, label = _hours(table)
    count = 3 + len(labels)
    fig, axes = plt.subplots(count, 1, figsize=(8, 1.0 + 1.9 * count), sharex=True)
    stations = np.asarray(table["antenna"])
    for (colour, style), name in zip(line_styles(len(names)), names):
        rows = stations == name
        line = {"color": colour, "linestyle": style}
        axes[0].plot(hours[rows], _degrees(table["elevation"][rows]), label=name, **line)
        axes[1].plot(hours[rows], u.Quantity(table["rm"][rows]).to_value(u.rad / u.m**2),
                     **line)
        axes[2].plot(hours[rows], unwrapped_degrees(table["feed_rotation"][rows]), **line)
        for ax, frequency in zip(axes[3:], labels):
            ax.plot(hours[rows], unwrapped_degrees(table[f"psi_{frequency}"][rows]), **line)
            ax.plot(hours[rows], u.Quantity(table[f"chi_{frequency}"][rows]).to_value(u.deg),
                    linewidth=0.8, alpha=0.6, **line)
    axes[0].set_ylabel("elevation [deg]")
    axes[1].set_ylabel("RM [rad/m$^2$]")
    axes[2].set_ylabel("feed rotation [deg]")
    outside_legend(axes[0])
    for ax, frequency in zip(axes[3:], labels):
        ax.set_ylabel(f"{frequency} [deg]")
        ax.plot([], [], color="0.3", label=f"$\\psi = \\Phi - \\chi$ at {frequency}")
        ax.plot([], [], color="0.3", linewidth=0.8, alpha=0.6,
                label=f"$\\chi$ = RM $\\lambda^2$ at {frequency}")
        outside_legend(ax)
    axes[-1].set_xlabel(label)
    files = [str(name).replace("\\", "/").rsplit("/", 1)[-1]
             for name in table.meta.get("ionex") or ()]
    fig.suptitle(f"{table.meta.get('target', '')}; RM from "
                 + (", ".join(files) if files else "a table"))
    return _finish(fig, path)
