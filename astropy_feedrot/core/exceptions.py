# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Warnings and errors of astropy_feedrot."""

import contextlib
import os
import sys
import warnings

from astropy.utils.exceptions import AstropyUserWarning

__all__ = ["DegenerateGeometryWarning", "OrbitWarning", "StaleEarthOrientationWarning",
           "CatalogueReceptorsWarning", "CatalogueMountWarning", "UncorrectedBaselinesWarning",
           "ReceptorAngleWarning", "warn_caller"]

_PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep


def warn_caller(message, category):
    """Warn, pointing at the first line outside this package.

    The package's warnings name the user's line that called it, however deep
    in the package they arise and whatever decorators or contexts lie between.

    Parameters
    ----------
    message : str
        The text of the warning.
    category : type
        A subclass of `Warning`.

    Examples
    --------
    >>> import warnings
    >>> from astropy_feedrot.core.exceptions import DegenerateGeometryWarning, warn_caller
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_caller("2 of 10 epochs undefined", DegenerateGeometryWarning)
    >>> "exceptions.py" in caught[0].filename
    False
    """
    frame, level = sys._getframe(1), 2
    while frame is not None and (frame.f_code.co_filename.startswith(_PACKAGE_DIR)
                                 or frame.f_code.co_filename == contextlib.__file__):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)


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


class OrbitWarning(AstropyUserWarning):
    """An orbit gives no position, or a degraded one, at some of the requested epochs.

    Raised once per call, saying how many epochs are affected and why: epochs
    in a hole of an SP3 file (NaN there), epochs where SGP4 fails on an element
    set (NaN there), or epochs too far from the epoch of an element set for
    SGP4 to be trusted (positions returned, accuracy degraded).

    Examples
    --------
    >>> import warnings
    >>> from astropy_feedrot import OrbitWarning
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warnings.warn("3 of 10 epochs fall in holes of the SP3 file", OrbitWarning)
    >>> caught[0].category.__name__
    'OrbitWarning'
    """


class StaleEarthOrientationWarning(AstropyUserWarning):
    """The Earth-orientation tables do not cover the epochs well; computed anyway.

    Emitted once per call when the epochs lie beyond the measured values of
    tables that are more than 30 days old, past the end of their predictions,
    or before their start. The message says how old the tables are, how far
    the epochs lie beyond them, the likely UT1 error and its effect on hour
    and parallactic angles, and how to refresh the tables (see
    `astropy_feedrot.earth.eop.earth_orientation_status`).

    Examples
    --------
    >>> from astropy_feedrot import StaleEarthOrientationWarning
    >>> issubclass(StaleEarthOrientationWarning, UserWarning)
    True
    """


class CatalogueReceptorsWarning(AstropyUserWarning):
    """Receptors a visibility file lacks were taken from the station catalogue.

    Emitted once per correction, naming the antennas, the catalogue's
    stations they were matched to (by name, within
    `~astropy_feedrot.visibilities.CATALOGUE_TOLERANCE` of their position;
    or by position alone, within
    `~astropy_feedrot.visibilities.PAD_TOLERANCE`, with the distance), the
    receptors and the source the catalogue cites. Information, not a
    fault: give the feeds yourself (``feeds=``, ``--feeds``) to silence it.

    Examples
    --------
    >>> from astropy_feedrot import CatalogueReceptorsWarning
    >>> issubclass(CatalogueReceptorsWarning, UserWarning)
    True
    """


class CatalogueMountWarning(AstropyUserWarning):
    """A visibility file and the station catalogue describe an antenna differently.

    Emitted once per call, naming each antenna of the file that lies within
    `~astropy_feedrot.visibilities.CATALOGUE_TOLERANCE` of a catalogue
    station whose mount or focus differs from the file's (``MNTSTA`` 0, the
    placeholder of many writers, for a Nasmyth station; a casacore
    ``'ALT-AZ'`` for a beam waveguide), with both; and which of the two was
    used (``mounts='file'``, the default, or ``'catalogue'``; ``--mounts``).

    Examples
    --------
    >>> from astropy_feedrot import CatalogueMountWarning
    >>> issubclass(CatalogueMountWarning, UserWarning)
    True
    """


class UncorrectedBaselinesWarning(AstropyUserWarning):
    """Some baselines of a visibility file were left as they were.

    Emitted once per correction, naming the antennas (orbiting antennas,
    whose feed turns with a spacecraft whose attitude the file does not give)
    and counting the rows left untouched; the other baselines are corrected.

    Examples
    --------
    >>> from astropy_feedrot import UncorrectedBaselinesWarning
    >>> issubclass(UncorrectedBaselinesWarning, UserWarning)
    True
    """


class ReceptorAngleWarning(AstropyUserWarning):
    """A file gives the two receptors of circular feeds unusual angles.

    Emitted once per correction, naming the antennas, when the angle of the
    second circular receptor differs from the first's by other than 0 or 90
    deg (`~astropy_feedrot.antennas.receptors.CIRCULAR_OFFSETS`). Both receptors then
    turn with the first's angle, as CASA turns them
    (`~astropy_feedrot.antennas.receptors.Receptors.sky_angles`): the second angle is ignored.
    Give the feeds yourself (``feeds=``, ``--feeds``) if the file is wrong.

    Examples
    --------
    >>> from astropy_feedrot import ReceptorAngleWarning
    >>> issubclass(ReceptorAngleWarning, UserWarning)
    True
    """
