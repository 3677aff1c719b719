# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Warnings and errors of astropy_feedrot."""

from astropy.utils.exceptions import AstropyUserWarning

__all__ = ["DegenerateGeometryWarning"]


class DegenerateGeometryWarning(AstropyUserWarning):
    """Some epochs have legal but degenerate geometry; their angles are NaN.

    Raised once per call, saying how many epochs are affected: a source at the
    zenith of an alt-az mount, at the pole of an equatorial mount or along any
    fixed axis, a natural source at the celestial pole.

    Examples
    --------
    >>> import warnings
    >>> from astropy_feedrot import DegenerateGeometryWarning
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warnings.warn("2 of 10 epochs undefined", DegenerateGeometryWarning)
    >>> caught[0].category.__name__
    'DegenerateGeometryWarning'
    """
