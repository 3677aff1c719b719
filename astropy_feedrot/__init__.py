# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation, parallactic angle and carrier-phase wind-up.

A unified model of the phase rotation seen by radio telescopes of every mount
and focus type and by GNSS antennas, observing natural radio sources and
satellites (Skeens et al., "A unified model of feed rotation in radio
telescopes and GNSS antennas").
"""

from .antenna import Antenna, FeedRotationTerms
from .attitude import NominalAttitude, QuaternionAttitude
from .config import conf
from .continuity import ContinuityWarning, RotationDelay, rotation_delay, unwrap
from .exceptions import DegenerateGeometryWarning, OrbitWarning, StaleEarthOrientationWarning
from .focus import (
    BeamWaveguideFocus,
    CassegrainFocus,
    Focus,
    GregorianFocus,
    MirrorTrain,
    NasmythFocus,
    PrimeFocus,
)
from .orbits import CoordinateOrbit, SP3Orbit, TLEOrbit
from .satellite import LineOfSight, Satellite
from .mounts import (
    AltAzMount,
    EquatorialMount,
    FixedAxisMount,
    Mount,
    StationaryMount,
    XYMount,
)

try:
    from ._version import version as __version__
except ImportError:  # pragma: no cover - running from a source tree without a build
    __version__ = "unknown"

__all__ = [
    "Antenna",
    "FeedRotationTerms",
    "Satellite",
    "LineOfSight",
    "TLEOrbit",
    "SP3Orbit",
    "CoordinateOrbit",
    "NominalAttitude",
    "QuaternionAttitude",
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
    "unwrap",
    "rotation_delay",
    "RotationDelay",
    "DegenerateGeometryWarning",
    "StaleEarthOrientationWarning",
    "OrbitWarning",
    "ContinuityWarning",
    "conf",
]
