# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Tables on standard output: aligned and rounded for a person on a terminal, ECSV
(or CSV) for a program on a pipe.

A person reading a table of feed rotation needs its units and the digits the
physics supports, not the 17 significant digits of a float64: angles to
0.001 deg (in their unit: 1.7e-5 rad, 2.8e-6 cycle), their rates to 1e-6 of
their unit per second, times to the second. A program reading the output of
``feedrot ... | ...`` needs every digit, which ECSV keeps. So the table
commands print the rounded, aligned view when standard output is a terminal
and ECSV when it is not, and ``--format text|ecsv|csv`` chooses either way.
Files written with ``-o`` always keep every digit.
"""

import math
import sys

from astropy import units as u
from astropy.time import Time

from ..core.outputs import write_table_blocks

__all__ = ["TEXT_ANGLE", "TEXT_ROTATION_MEASURE", "output_format", "for_people", "print_table"]

#: The resolution of angles in the text view.
TEXT_ANGLE = 0.001 * u.deg

#: The resolution of rotation measures in the text view: what IONEX maps support (their
#: 0.1 TECU is a few 0.001 rad/m2), 0.003 deg of Faraday rotation at 1.4 GHz.
TEXT_ROTATION_MEASURE = 0.001 * u.rad / u.m**2


def output_format(chosen, stream=None):
    """The format of a table on ``stream`` (standard output): ``chosen``, else text on a
    terminal and ECSV on anything else.

    Parameters
    ----------
    chosen : str or None
        ``--format``: one of `~astropy_feedrot.cli.parser.FORMATS`, or None.
    stream : file-like, optional
        Where the table goes (default ``sys.stdout``).

    Returns
    -------
    str

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.cli.views import output_format
    >>> output_format(None, io.StringIO()), output_format("text", io.StringIO())
    ('ecsv', 'text')
    """
    if chosen is not None:
        return chosen
    stream = sys.stdout if stream is None else stream
    isatty = getattr(stream, "isatty", None)
    return "text" if isatty is not None and isatty() else "ecsv"


def _decimals(unit):
    """Decimals that show `TEXT_ANGLE` in ``unit`` (an angle, or an angle per second), or
    `TEXT_ROTATION_MEASURE`, or None for a unit that is none of these."""
    for resolution, per, extra in ((TEXT_ANGLE, u.dimensionless_unscaled, 0),
                                   (TEXT_ANGLE, u.s, 3),
                                   (TEXT_ROTATION_MEASURE, u.dimensionless_unscaled, 0)):
        try:
            step = (resolution / per).to_value(unit)
        except u.UnitConversionError:
            continue
        return max(0, math.ceil(-math.log10(step))) + extra
    return None


def for_people(table):
    """A copy of ``table`` whose columns print with the digits the physics supports.

    Angle columns to 0.001 deg in their unit, angle rates to 1e-6 of their unit
    per second, rotation measures to 0.001 rad/m2; times as ISO UTC to the
    second; other numbers with six significant digits; exact zeros stay 0.

    Parameters
    ----------
    table : `~astropy.table.Table`

    Returns
    -------
    `~astropy.table.Table`
        The same values; only the print formats differ.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.table import Table
    >>> from astropy_feedrot.cli.views import for_people
    >>> table = for_people(Table({"angle": [12.3456789123] * u.deg,
    ...                           "rate": [0.00012345678] * u.deg / u.s}))
    >>> print("\\n".join(table.pformat()))  # doctest: +NORMALIZE_WHITESPACE
    angle    rate
     deg   deg / s
    ------ --------
    12.346 0.000123
    """
    view = table.copy(copy_data=False)
    for name in view.colnames:
        column = view[name]
        if isinstance(column, Time):
            view[name] = Time(column, format="isot", scale="utc", precision=0)
            continue
        if getattr(column, "dtype", None) is None or column.dtype.kind != "f":
            continue
        unit = getattr(column, "unit", None)
        decimals = _decimals(unit) if unit is not None else None
        column.info.format = f".{decimals}f" if decimals is not None else ".6g"
    return view


def print_table(table, form, stream=None, step=None):
    """Print ``table`` on ``stream`` (standard output) as ``form``: text, ecsv or csv.

    Parameters
    ----------
    table : `~astropy.table.Table`
    form : {'text', 'ecsv', 'csv'}
        See `output_format`.
    stream : file-like, optional
    step : callable, optional
        Called as ``step(rows)`` as rows are printed: after each block of
        ECSV or CSV (`~astropy_feedrot.core.outputs.write_table_blocks`),
        once for the text view.

    Examples
    --------
    >>> import astropy.units as u
    >>> from astropy.table import Table
    >>> from astropy_feedrot.cli.views import print_table
    >>> print_table(Table({"total": [1.23456789] * u.deg}), "text")
    ... # doctest: +NORMALIZE_WHITESPACE
    total
     deg
    -----
    1.235
    """
    stream = sys.stdout if stream is None else stream
    if form == "text":
        print("\n".join(for_people(table).pformat(max_lines=-1, max_width=-1)), file=stream)
        if step is not None:
            step(len(table))
    else:
        write_table_blocks(table, f"ascii.{form}", stream, step)
