# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Ionospheric Faraday rotation: rotation measure along each line of sight.

What it holds: `Ionosphere`, the rotation measure (RM) along the line of
sight from a site to a target at given epochs, from IONEX global ionosphere
maps and the IGRF geomagnetic field through spinifex (the optional extra
``ionosphere``), or from a user's own table of RM per antenna and epoch;
`faraday_rotation`, the rotation RM * lambda^2 of the wave's plane of
polarization; `polarization_rotation`, the feed rotation minus it, the one
angle a correction needs; `sample_ionex`, the real IONEX files spinifex ships. spinifex
is imported lazily, on the first use of IONEX maps: nothing here downloads,
and importing this package does not import spinifex.

The front-ends (``Antenna.rotation_measure``, the corrections) call
`Ionosphere` with an antenna's ``location`` and ``name``; this subpackage
never imports them.

May import: ``core``, ``earth``.
"""

from .errors import IonosphereError
from .faraday import faraday_rotation, polarization_rotation
from .ionex import sample_ionex
from .ionosphere import Ionosphere

__all__ = ["Ionosphere", "IonosphereError", "faraday_rotation", "polarization_rotation",
           "sample_ionex"]
