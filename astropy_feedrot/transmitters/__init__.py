# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Satellites: where they are and how their antennas point.

Orbits (`orbit_interface`, the interface; `orbits`, positions the user
has and the choice among sources; `sp3_orbit`, `tle_orbit`, and
`propagation`, SGP4 at nodes), attitudes (`attitude_interface`, the
interface and the Sun; `nominal_attitude`, Eqs 26-27; `quaternion_attitude`,
Eqs 24-25; `yaw_models`, the GNSS yaw laws beyond nominal) and the
`~astropy_feedrot.Satellite` that joins an orbit and an attitude
(`satellite`).

May import: ``core``, ``io``, ``earth``.
"""
