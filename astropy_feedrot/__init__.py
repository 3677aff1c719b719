# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation, parallactic angle and carrier-phase wind-up.

A unified model of the phase rotation seen by radio telescopes of every mount
and focus type and by GNSS antennas, observing natural radio sources and
satellites (Skeens et al., "A unified model of feed rotation in radio
telescopes and GNSS antennas").

This module is the package's one import surface: everything a user calls is
importable from here, and this is where to import it from. It is not a layer
of deprecated aliases: the names below are the public API, each living in a
module of the folders (``earth``, ``antennas``, ``transmitters``, ``engine``,
``stations``, ``applied``..., see the architecture page of the
documentation), which stay importable for those who want them. Each name is
imported from its home the first time it is used (a module ``__getattr__``,
PEP 562, as the scientific Python ecosystem's SPEC 1 describes), so
``import astropy_feedrot`` and the ``feedrot`` command line start without
importing astropy; ``dir(astropy_feedrot)``, ``from astropy_feedrot import
*``, static type checkers and the documentation see every name.
``astropy_feedrot.visibilities`` (visibility files: FITS-IDI, UVFITS,
Measurement Sets, pyuvdata's ``UVData`` objects), ``astropy_feedrot.gnss``
(RINEX observation files) and ``astropy_feedrot.ionosphere`` (Faraday
rotation) are imported on their own, as they need optional packages.
"""

import importlib
from typing import TYPE_CHECKING

from .core.version import version as __version__

#: Each public name and the module where it lives (relative to the package),
#: imported on first use.
_HOMES = {
    # Antennas, their mounts and foci
    "Antenna": ".engine.antenna",
    "FeedRotationTerms": ".engine.antenna",
    "AntennaAngles": ".engine.antenna",
    "get_antenna": ".stations.catalogue",
    "read_catalogue": ".stations.catalogue",
    "StationCatalogue": ".stations.catalogue",
    "Mount": ".antennas.mounts",
    "FixedAxisMount": ".antennas.mounts",
    "AltAzMount": ".antennas.mounts",
    "EquatorialMount": ".antennas.mounts",
    "XYMount": ".antennas.mounts",
    "StationaryMount": ".antennas.mounts",
    "Focus": ".antennas.focus",
    "PrimeFocus": ".antennas.focus",
    "CassegrainFocus": ".antennas.focus",
    "GregorianFocus": ".antennas.focus",
    "NasmythFocus": ".antennas.focus",
    "BeamWaveguideFocus": ".antennas.focus",
    "MirrorTrain": ".antennas.focus",
    "Rotator": ".antennas.rotators",
    "mount_from_label": ".stations.labels",
    "label_from_mount": ".stations.labels",
    # Transmitters
    "Satellite": ".transmitters.satellite",
    "LineOfSight": ".transmitters.satellite",
    "TLEOrbit": ".transmitters.tle_orbit",
    "SP3Orbit": ".transmitters.sp3_orbit",
    "CoordinateOrbit": ".transmitters.orbits",
    "NominalAttitude": ".transmitters.nominal_attitude",
    "QuaternionAttitude": ".transmitters.quaternion_attitude",
    "ModelAttitude": ".transmitters.yaw_models",
    "read_tle": ".io",
    "read_sp3": ".io",
    "read_orbex": ".io",
    # Many antennas and targets
    "feed_rotation_grid": ".engine.grid",
    "feed_rotation_grid_dask": ".engine.grid",
    "feed_rotation_rate_grid": ".engine.grid",
    "rotation_delay_grid": ".engine.grid",
    # Planning polarization calibration
    "feed_rotation_coverage": ".applied.planning",
    "rank_sources": ".applied.planning",
    # Continuity, corrections, tables and figures
    "unwrap": ".engine.continuity",
    "rotation_delay": ".engine.continuity",
    "RotationDelay": ".engine.continuity",
    "correct_phase": ".applied.correction",
    "correct_visibilities": ".applied.correction",
    "correct_linear_visibilities": ".applied.correction",
    "rotation_matrix": ".applied.correction",
    "rr_minus_ll": ".applied.rr_ll",
    "baseline_rr_ll": ".applied.rr_ll",
    "feed_rotation_table": ".applied.feed_rotation_tables",
    "baseline_table": ".applied.feed_rotation_tables",
    "baseline_summary": ".applied.feed_rotation_tables",
    "faraday_table": ".applied.faraday_tables",
    "plot_feed_rotation": ".applied.plotting",
    "plot_baseline": ".applied.plotting",
    "plot_faraday": ".applied.plotting",
    # Earth orientation, warnings and errors
    "earth_orientation_status": ".earth.eop",
    "Epochs": ".earth.epochs",
    "conf": ".core.config",
    "DegenerateGeometryWarning": ".core.exceptions",
    "StaleEarthOrientationWarning": ".core.exceptions",
    "OrbitWarning": ".core.exceptions",
    "CatalogueReceptorsWarning": ".core.exceptions",
    "CatalogueMountWarning": ".core.exceptions",
    "UncorrectedBaselinesWarning": ".core.exceptions",
    "ReceptorAngleWarning": ".core.exceptions",
    "ContinuityWarning": ".engine.continuity",
    "FileFormatError": ".io",
}

__all__ = list(_HOMES)

#: The folders of the package, imported on first use as attributes
#: (``astropy_feedrot.stations``) as well as by ``import``.
_SUBPACKAGES = ("core", "io", "earth", "antennas", "transmitters", "ionosphere", "engine",
                "stations", "applied", "visibilities", "gnss", "cli", "data")

if TYPE_CHECKING:  # the same names for static tools (tests/test_import_surface.py checks)
    from .antennas.focus import (
        BeamWaveguideFocus,
        CassegrainFocus,
        Focus,
        GregorianFocus,
        MirrorTrain,
        NasmythFocus,
        PrimeFocus,
    )
    from .antennas.mounts import (
        AltAzMount,
        EquatorialMount,
        FixedAxisMount,
        Mount,
        StationaryMount,
        XYMount,
    )
    from .antennas.rotators import Rotator
    from .applied.correction import (
        correct_linear_visibilities,
        correct_phase,
        correct_visibilities,
        rotation_matrix,
    )
    from .applied.faraday_tables import faraday_table
    from .applied.feed_rotation_tables import (
        baseline_summary,
        baseline_table,
        feed_rotation_table,
    )
    from .applied.planning import feed_rotation_coverage, rank_sources
    from .applied.plotting import plot_baseline, plot_faraday, plot_feed_rotation
    from .applied.rr_ll import baseline_rr_ll, rr_minus_ll
    from .core.config import conf
    from .core.exceptions import (
        CatalogueMountWarning,
        CatalogueReceptorsWarning,
        DegenerateGeometryWarning,
        OrbitWarning,
        ReceptorAngleWarning,
        StaleEarthOrientationWarning,
        UncorrectedBaselinesWarning,
    )
    from .earth.eop import earth_orientation_status
    from .earth.epochs import Epochs
    from .engine.antenna import Antenna, AntennaAngles, FeedRotationTerms
    from .engine.continuity import ContinuityWarning, RotationDelay, rotation_delay, unwrap
    from .engine.grid import (
        feed_rotation_grid,
        feed_rotation_grid_dask,
        feed_rotation_rate_grid,
        rotation_delay_grid,
    )
    from .io import FileFormatError, read_orbex, read_sp3, read_tle
    from .stations.catalogue import StationCatalogue, get_antenna, read_catalogue
    from .stations.labels import label_from_mount, mount_from_label
    from .transmitters.nominal_attitude import NominalAttitude
    from .transmitters.orbits import CoordinateOrbit
    from .transmitters.quaternion_attitude import QuaternionAttitude
    from .transmitters.satellite import LineOfSight, Satellite
    from .transmitters.sp3_orbit import SP3Orbit
    from .transmitters.tle_orbit import TLEOrbit
    from .transmitters.yaw_models import ModelAttitude


def __getattr__(name):
    """Import a public name (or a folder) from where it lives, once."""
    if name in _HOMES:
        value = getattr(importlib.import_module(_HOMES[name], __name__), name)
    elif name in _SUBPACKAGES:
        value = importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value  # the next use finds it without this function
    return value


def __dir__():
    return sorted({*__all__, *_SUBPACKAGES, "__version__"})
