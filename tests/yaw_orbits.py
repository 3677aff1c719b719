# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Orbits placed at a chosen beta angle, for the tests of the yaw models."""

import numpy as np
from astropy import units as u
from astropy.coordinates import get_sun
from astropy.time import Time

from astropy_feedrot import TLEOrbit
from astropy_feedrot.transmitters.attitude_interface import sun_position
from astropy_feedrot.transmitters.yaw_models import orbit_angles

EPOCH = Time("2023-01-25T00:00:00", scale="utc")


def beta_of(orbit, times):
    position = orbit.position(times)
    velocity = (orbit.position(times + 0.5 * u.s) - orbit.position(times - 0.5 * u.s))
    return orbit_angles(position, velocity, sun_position(times))


def orbit_at_beta(beta_deg, inclination=55.0, revolutions=2.0056):
    """A circular orbit whose beta angle at EPOCH is ``beta_deg`` (to 0.01 deg)."""
    def make(raan):
        return TLEOrbit.from_elements(EPOCH, inclination=inclination * u.deg, raan=raan * u.deg,
                                      mean_motion=revolutions * u.cycle / u.day)

    def beta(raan):
        return np.degrees(beta_of(make(raan), EPOCH)[0])

    # First guess from the Sun's celestial direction: n . s = sin(beta) with the
    # orbit normal n = (sin i sin raan, -sin i cos raan, cos i); then secant steps on
    # the beta angle of the propagated orbit.
    sun = get_sun(EPOCH).cartesian.xyz.value
    sun = sun / np.linalg.norm(sun)
    i = np.radians(inclination)
    amplitude = np.sin(i) * np.hypot(sun[0], sun[1])
    phase = np.arctan2(-sun[1], sun[0])  # sin(raan) sx - cos(raan) sy = A sin(raan + phase)
    target = (np.sin(np.radians(beta_deg)) - np.cos(i) * sun[2]) / amplitude
    first = np.degrees(np.arcsin(np.clip(target, -1, 1)) - phase)
    a, b = first, first + 0.5
    fa, fb = beta(a) - beta_deg, beta(b) - beta_deg
    for _ in range(6):
        if abs(fb) < 1e-4 or fb == fa:
            break
        a, b, fa = b, b - fb * (b - a) / (fb - fa), fb
        fb = beta(b) - beta_deg
    return make(b)


def noon(orbit, around=EPOCH, period=43082.0):
    """The first orbit noon (mu = 180 deg) after ``around``, to 1 s."""
    times = around + np.arange(0, period, 60.0) * u.s
    mu = beta_of(orbit, times)[1]
    k = int(np.argmin(np.abs(np.abs(mu) - np.pi)))
    fine = times[k] + np.arange(-120, 121, 1.0) * u.s
    mu = beta_of(orbit, fine)[1]
    return fine[int(np.argmin(np.abs(np.abs(mu) - np.pi)))]
