# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation, parallactic angle and carrier-phase wind-up.

A unified model of the phase rotation seen by radio telescopes of every mount
and focus type and by GNSS antennas, observing natural radio sources and
satellites (Skeens et al., "A unified model of feed rotation in radio
telescopes and GNSS antennas").

Everything a user calls is importable from here; the folders where it lives
(``earth``, ``antennas``, ``transmitters``, ``engine``, ``stations``,
``applied``..., see the architecture page of the documentation) stay
importable for those who want them. ``astropy_feedrot.visibilities``
(visibility files: FITS-IDI, UVFITS, Measurement Sets, pyuvdata's ``UVData``
objects), ``astropy_feedrot.gnss`` (RINEX observation files) and
``astropy_feedrot.ionosphere`` (Faraday rotation) are imported on their own,
as they need optional packages.
"""

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
from .applied.feed_rotation_tables import baseline_summary, baseline_table, feed_rotation_table
from .applied.planning import feed_rotation_coverage, rank_sources
from .applied.plotting import plot_baseline, plot_feed_rotation  # matplotlib is imported on use
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
from .core.version import version as __version__  # noqa: F401
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
from .transmitters.orbits import CoordinateOrbit, SP3Orbit, TLEOrbit
from .transmitters.quaternion_attitude import QuaternionAttitude
from .transmitters.satellite import LineOfSight, Satellite
from .transmitters.yaw_models import ModelAttitude

__all__ = [
    # Antennas, their mounts and foci
    "Antenna",
    "FeedRotationTerms",
    "AntennaAngles",
    "get_antenna",
    "read_catalogue",
    "StationCatalogue",
    "Mount",
    "FixedAxisMount",
    "AltAzMount",
    "EquatorialMount",
    "XYMount",
    "StationaryMount",
    "Focus",
    "PrimeFocus",
    "CassegrainFocus",
    "GregorianFocus",
    "NasmythFocus",
    "BeamWaveguideFocus",
    "MirrorTrain",
    "Rotator",
    "mount_from_label",
    "label_from_mount",
    # Transmitters
    "Satellite",
    "LineOfSight",
    "TLEOrbit",
    "SP3Orbit",
    "CoordinateOrbit",
    "NominalAttitude",
    "QuaternionAttitude",
    "ModelAttitude",
    "read_tle",
    "read_sp3",
    "read_orbex",
    # Many antennas and targets
    "feed_rotation_grid",
    "feed_rotation_grid_dask",
    "feed_rotation_rate_grid",
    "rotation_delay_grid",
    # Planning polarization calibration
    "feed_rotation_coverage",
    "rank_sources",
    # Continuity, corrections, tables and figures
    "unwrap",
    "rotation_delay",
    "RotationDelay",
    "correct_phase",
    "correct_visibilities",
    "correct_linear_visibilities",
    "rotation_matrix",
    "rr_minus_ll",
    "baseline_rr_ll",
    "feed_rotation_table",
    "baseline_table",
    "baseline_summary",
    "plot_feed_rotation",
    "plot_baseline",
    # Earth orientation, warnings and errors
    "earth_orientation_status",
    "Epochs",
    "conf",
    "DegenerateGeometryWarning",
    "StaleEarthOrientationWarning",
    "OrbitWarning",
    "CatalogueReceptorsWarning",
    "CatalogueMountWarning",
    "UncorrectedBaselinesWarning",
    "ReceptorAngleWarning",
    "ContinuityWarning",
    "FileFormatError",
]
