# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Which pole the parallactic angle is measured from: the package's or CASA's.

The package measures feed rotation in the Earth-fixed frame of the paper's
Appendix D: the pole is the ITRS ``z`` axis and the source direction comes
from astropy's celestial-to-terrestrial transformation with polar motion
(``pole="itrs"``, the default). CASA (casacore's ``MSDerivedValues``, which
``applycal(parang=True)`` uses) leaves polar motion out: its pole is the
celestial intermediate pole and its antennas sit on the ITRS positions as if
the two frames' axes coincided. ``pole="casa"`` reproduces that by computing
with zero polar motion; the two differ by the polar motion (a few tenths of
an arcsecond) over the cosine of the elevation. :doc:`/correcting` gives the
numbers measured against CASA.
"""

import contextlib

from astropy.utils import iers

from ..core.choices import CONVENTIONS, POLES

__all__ = ["POLES", "CONVENTIONS", "pole_context", "convention_options"]

# The polar-motion columns of astropy's IERS tables.
_PM_COLUMNS = ("PM_x", "PM_y", "PM_x_A", "PM_y_A", "PM_X_B", "PM_Y_B")


@contextlib.contextmanager
def pole_context(pole="itrs"):
    """Context in which the feed rotation is measured from ``pole``.

    Parameters
    ----------
    pole : {'itrs', 'casa'}
        ``'itrs'`` changes nothing; ``'casa'`` sets polar motion to zero in
        astropy's Earth-orientation table for the duration of the context.

    Raises
    ------
    ValueError
        For another ``pole``.

    Examples
    --------
    >>> from astropy.time import Time
    >>> from astropy.coordinates.builtin_frames.utils import get_polar_motion
    >>> from astropy_feedrot.visibilities.poles import pole_context
    >>> with pole_context("casa"):
    ...     xp, yp = get_polar_motion(Time("2023-01-25"))
    >>> float(xp), float(yp)
    (0.0, 0.0)
    """
    if pole not in POLES:
        raise ValueError(f"pole must be one of {POLES} ('itrs': the Earth-fixed z axis, with "
                         f"polar motion; 'casa': no polar motion, as CASA), got {pole!r}")
    if pole == "itrs":
        yield
        return
    table = iers.earth_orientation_table.get().copy()
    for column in _PM_COLUMNS:
        if column in table.colnames:
            table[column] = 0 * table[column]
    with iers.earth_orientation_table.set(table):
        yield


def convention_options(convention="rigorous", vertical=None, pole=None):
    """The vertical and the pole of a correction: a convention's, unless given.

    Parameters
    ----------
    convention : {'rigorous', 'casa'}, optional
        One of `CONVENTIONS` (default ``'rigorous'``).
    vertical : {'geodetic', 'geocentric'}, optional
        Given explicitly, it replaces the convention's.
    pole : {'itrs', 'casa'}, optional
        Given explicitly, it replaces the convention's.

    Returns
    -------
    vertical, pole : str

    Raises
    ------
    ValueError
        For another ``convention``.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.poles import convention_options
    >>> convention_options("casa")
    ('geocentric', 'casa')
    >>> convention_options("rigorous", pole="casa")
    ('geodetic', 'casa')
    """
    if convention not in CONVENTIONS:
        raise ValueError(f"convention must be one of {tuple(CONVENTIONS)} ('rigorous': the "
                         "geodetic vertical and the Earth-fixed pole; 'casa': CASA's "
                         f"geocentric vertical and pole of date), got {convention!r}")
    default_vertical, default_pole = CONVENTIONS[convention]
    return (default_vertical if vertical is None else vertical,
            default_pole if pole is None else pole)
