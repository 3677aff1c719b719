# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""A user's own rotation measures: a table of RM per epoch, and per antenna if it says so.

For RM that come from elsewhere (ALBUS, an h5parm of spinifex or RMextract, a
GPS receiver at the site): an astropy table with columns ``time``
(`~astropy.time.Time`), ``rm`` (rad m^-2) and, optionally, ``antenna``
(names). Without ``antenna``, one series serves every antenna. Each series is
interpolated linearly in time and never extrapolated.
"""

import numpy as np
from astropy import units as u
from astropy.table import Table
from astropy.time import Time

from .errors import IonosphereError
from .ionex import describe_epochs

__all__ = ["RMTable", "RM_UNIT"]

#: The unit of rotation measures.
RM_UNIT = u.rad / u.m**2


class RMTable:
    """Series of rotation measures, one per antenna or one for all.

    Parameters
    ----------
    table : `~astropy.table.QTable` or `~astropy.table.Table`
        Columns ``time`` (`~astropy.time.Time`), ``rm`` (a quantity in
        rad m^-2, or a column with that unit) and optionally ``antenna``
        (str). Rows in any order.

    Raises
    ------
    TypeError
        If ``table`` is not an astropy table, ``time`` not a Time column, or
        ``rm`` plain numbers.
    astropy.units.UnitsError
        If ``rm`` is not in units of rad m^-2.
    ValueError
        If a column is missing, or an antenna (or the one series) has two
        rows at the same epoch.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.table import QTable
    >>> from astropy.time import Time
    >>> from astropy_feedrot.ionosphere.rm_table import RMTable
    >>> rms = RMTable(QTable({"time": Time(["2024-06-01T00:00", "2024-06-01T01:00"]),
    ...                       "rm": [1.0, 2.0] * u.rad / u.m**2}))
    >>> rms.rm(None, Time(["2024-06-01T00:30"]).mjd)
    array([1.5])
    """

    def __init__(self, table):
        if not isinstance(table, Table):
            raise TypeError(
                f"table must be an astropy QTable (or Table) with columns 'time', 'rm' and "
                f"optionally 'antenna', got {type(table).__name__}")
        missing = [name for name in ("time", "rm") if name not in table.colnames]
        if missing:
            raise ValueError(
                f"table lacks column(s) {', '.join(repr(m) for m in missing)}; it has "
                f"{', '.join(repr(c) for c in table.colnames) or 'none'}: give 'time' (Time), "
                "'rm' (rad / m2) and optionally 'antenna' (names)")
        time = table["time"]
        if not isinstance(time, Time):
            raise TypeError(
                f"table column 'time' must be an astropy Time, got {type(time).__name__}; "
                "e.g. QTable({'time': Time([...]), 'rm': [...] * u.rad / u.m**2})")
        rm = table["rm"]
        unit = getattr(rm, "unit", None)
        if unit is None:
            raise TypeError(
                "table column 'rm' has no unit; give it in rad / m2, "
                "e.g. values * u.rad / u.m**2")
        try:
            values = u.Quantity(rm, unit, copy=False).to_value(
                RM_UNIT, equivalencies=u.dimensionless_angles())
        except u.UnitConversionError:
            raise u.UnitsError(
                f"table column 'rm' must be a rotation measure in rad / m2, got "
                f"{u.Unit(unit).to_string()}; e.g. values * u.rad / u.m**2") from None
        mjd = np.asarray(time.utc.mjd, dtype=float).ravel()
        values = np.asarray(values, dtype=float).ravel()
        if "antenna" in table.colnames:
            names = np.array([str(name).strip() for name in table["antenna"]])
        else:
            names = np.full(mjd.shape, None, dtype=object)
        self.series = {}
        for name in dict.fromkeys(names.tolist()):  # one series per antenna the table names
            rows = names == name
            order = np.argsort(mjd[rows], kind="stable")
            epochs, rms = mjd[rows][order], values[rows][order]
            repeated = epochs[1:][np.diff(epochs) == 0]
            if repeated.size:
                who = "" if name is None else f"antenna {name!r} "
                raise ValueError(
                    f"table gives {who}two rotation measures at {describe_epochs(repeated)} "
                    "UTC; keep one row per epoch")
            self.series[name] = (epochs, rms)
        self.per_antenna = "antenna" in table.colnames

    @property
    def names(self):
        """The antennas the table names (empty if one series serves all)."""
        return [name for name in self.series if name is not None]

    def series_of(self, name):
        """The epochs (UTC MJD) and RM (rad m^-2) that serve antenna ``name``."""
        if not self.per_antenna:
            return self.series[None]
        if name is None:
            raise ValueError(
                f"the table gives rotation measures per antenna ({', '.join(self.names)}): "
                "say which with antenna=<name>, one per location")
        key = str(name).strip()
        if key not in self.series:
            folded = [known for known in self.names if known.lower() == key.lower()]
            if len(folded) != 1:
                raise IonosphereError(
                    f"the table of rotation measures has no antenna {name!r}; it has "
                    f"{', '.join(self.names)}: add its rows, or name one of those")
            key = folded[0]
        return self.series[key]

    def describe_coverage(self, name):
        """The span of antenna ``name``'s series, in words."""
        epochs, _ = self.series_of(name)
        return describe_epochs(epochs).replace(" ... ", " to ")

    def rm(self, name, mjd):
        """Rotation measures of antenna ``name`` at epochs ``mjd`` (UTC MJD), linear in time.

        Raises
        ------
        IonosphereError
            If some epochs lie outside the antenna's series.
        """
        epochs, rms = self.series_of(name)
        mjd = np.asarray(mjd, dtype=float)
        outside = (mjd < epochs[0]) | (mjd > epochs[-1])
        if np.any(outside):
            who = "" if name is None or not self.per_antenna else f" of antenna {name!r}"
            raise IonosphereError(
                f"{np.count_nonzero(outside)} of {mjd.size} epochs "
                f"({describe_epochs(mjd[outside])} UTC) lie outside the table of rotation "
                f"measures{who}, which covers {self.describe_coverage(name)} UTC; "
                "give rows that cover the epochs observed (the table is not extrapolated)")
        if epochs.size == 1:
            return np.full(mjd.shape, rms[0])
        return np.interp(mjd, epochs, rms)
