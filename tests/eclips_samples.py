# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Samples of Kouba's ``eclips`` routine (Orekit's test data) and the package's yaw on them.

The files (``tests/data/gnss/eclips``, see its README) hold, one line per
epoch, the GPS week and milliseconds, the PRN, the block, the SVN, the
satellite's ITRF position (m) and inertial velocity on ITRF axes (m/s), the
Sun's ITRF position (m), the beta angle and the Sun-Earth-satellite angle
(deg), then the nominal body x axis and yaw and the x axis and yaw of
``eclips`` (Orekit's ``driverEclips.f`` writes them; Orekit's
``GenerateBaseSamples.java`` rotates the inertial velocity to ITRF without
adding the Earth's rotation).
"""

from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.time import Time

from astropy_feedrot import ModelAttitude
from astropy_feedrot.engine.grid import wind_up
from astropy_feedrot.gnss import receiver_axes
from astropy_feedrot.transmitters.orbits import Orbit
from astropy_feedrot.transmitters.yaw_models import EARTH_ROTATION

DATA = Path(__file__).parent / "data" / "gnss" / "eclips"

#: eclips block names (Orekit's files) -> the IGS metadata's.
BLOCKS = {"BLOCK-IIR-A": "GPS-IIR-A", "BLOCK-IIR-B": "GPS-IIR-B", "BLOCK-IIR-M": "GPS-IIR-M",
          "BLOCK-IIF": "GPS-IIF", "GALILEO-1": "GAL-1", "GALILEO-2": "GAL-2",
          "GLONASS-M": "GLO-M", "BEIDOU-2M": "BDS-2M", "BEIDOU-2I": "BDS-2I",
          # Orekit's driver of eclips has no branch for GLONASS-K1: the routine ran its
          # GLONASS-M law (every PRN of 33-64) on it; so do we.
          "GLONASS-K1": "GLO-M"}

#: A new event (a new block of lines) after a gap this long (s), as Orekit's test.
EVENT_GAP = 14400.0

#: Threshold (deg) of a departure from nominal yaw that makes an epoch "in a turn".
TURNING = 0.01


def read_eclips(name):
    """The lines of one file as arrays, split into events (one satellite, no gap)."""
    rows = [line.split() for line in (DATA / name).read_text(encoding="utf-8").splitlines()
            if line.strip() and not line.startswith("#")]
    seconds = np.array([int(r[1]) * 604800.0 + float(r[2]) / 1000.0 for r in rows])
    numbers = np.array([[float(x) for x in r[6:25]] for r in rows])
    prn = np.array([r[3] for r in rows])
    block = np.array([r[4] for r in rows])
    new = np.ones(len(rows), dtype=bool)
    new[1:] = (prn[1:] != prn[:-1]) | (np.diff(seconds) > EVENT_GAP)
    starts = np.flatnonzero(new)
    events = []
    for first, last in zip(starts, list(starts[1:]) + [len(rows)]):
        part = slice(first, last)
        position = numbers[part, 0:3]
        inertial = numbers[part, 3:6]
        events.append({
            "prn": prn[first], "block": BLOCKS[block[first]],
            "time": Time(seconds[part], format="gps"),
            "position": position,
            "velocity": inertial - np.cross([0.0, 0.0, EARTH_ROTATION], position),
            "sun": numbers[part, 6:9],
            "beta": numbers[part, 9],
            "x_nominal": numbers[part, 11:14],
            "x_eclips": numbers[part, 15:18],
        })
    return events


class SampledOrbit(Orbit):
    """Cubic Hermite interpolation of positions and Earth-fixed velocities of a file.

    Only BeiDou's mode switch (the beta angle at the last orbit quadrature)
    evaluates it; every other input is the file's own.
    """

    def __init__(self, time, position, velocity):
        self.seconds = (time - time[0]).sec
        self.start = time[0]
        self.position_samples = position
        self.velocity_samples = velocity
        self.coverage = (time[0], time[-1])

    def position(self, obstime, orientation=None):
        t = np.atleast_1d((obstime - self.start).sec)
        i = np.clip(np.searchsorted(self.seconds, t) - 1, 0, len(self.seconds) - 2)
        h = (self.seconds[i + 1] - self.seconds[i])[:, np.newaxis]
        s = ((t - self.seconds[i]) / h[:, 0])[:, np.newaxis]
        p0, p1 = self.position_samples[i], self.position_samples[i + 1]
        v0, v1 = self.velocity_samples[i] * h, self.velocity_samples[i + 1] * h
        value = ((2 * s**3 - 3 * s**2 + 1) * p0 + (s**3 - 2 * s**2 + s) * v0
                 + (-2 * s**3 + 3 * s**2) * p1 + (s**3 - s**2) * v1)
        return value.reshape(np.shape(obstime) + (3,))


def signed_angle(a, b, axis):
    """Angle (rad) from ``a`` to ``b`` about ``axis`` (unit vectors, shape (..., 3))."""
    return np.arctan2(np.sum(np.cross(a, b) * axis, axis=-1), np.sum(a * b, axis=-1))


def compare(name, replace=None):
    """The package's yaw against eclips's, epoch by epoch, for every event of a file.

    ``replace`` maps a block to the one whose law is used instead.

    Returns
    -------
    dict of ndarray
        ``difference``: yaw difference (deg, the package's minus eclips's, about
        nadir, in (-180, 180]); ``turning``: epochs where eclips or the package
        departs from nominal yaw by more than `TURNING`; ``windup``: the
        difference of the wind-up (cycles) a receiver sees with the two
        attitudes; ``beta`` (deg) and ``ours_nominal``/``eclips_nominal``
        (whether each follows the nominal yaw).
    """
    out = {k: [] for k in ("difference", "turning", "windup", "beta", "ours_nominal",
                           "eclips_nominal", "block")}
    for event in read_eclips(name):
        time, position, sun = event["time"], event["position"], event["sun"]
        orbit = SampledOrbit(time, position, event["velocity"])
        model = ModelAttitude(orbit, (replace or {}).get(event["block"], event["block"]))
        aligned, transverse = model.sun_and_dipoles(time, position, sun,
                                                    velocity=event["velocity"])
        yaw, nominal = model.yaw(time, position, sun, velocity=event["velocity"])
        nadir = -position / np.linalg.norm(position, axis=-1, keepdims=True)
        # eclips's x axis of the orbit-normal mode is the velocity itself, a little
        # off the plane normal to nadir in an eccentric orbit: its projection.
        x = event["x_eclips"] - np.sum(event["x_eclips"] * nadir, -1)[:, np.newaxis] * nadir
        x /= np.linalg.norm(x, axis=-1, keepdims=True)
        x_nominal = event["x_nominal"] / np.linalg.norm(event["x_nominal"], axis=-1,
                                                        keepdims=True)
        difference = np.degrees(signed_angle(x, aligned, nadir))
        eclips_off = np.abs(np.degrees(signed_angle(x_nominal, x, nadir))) > TURNING
        ours_off = np.abs((yaw - nominal).wrap_at(180 * u.deg).deg) > TURNING
        # The wind-up each attitude gives a receiver 30 deg (geocentric) off the
        # satellite's nadir, across the track (one receiver per epoch).
        side = np.cross(nadir, event["velocity"])
        side /= np.linalg.norm(side, axis=-1, keepdims=True)
        up = -nadir * np.cos(np.radians(30.0)) + side * np.sin(np.radians(30.0))
        sites = up * 6378137.0
        axes = np.stack([receiver_axes(site) for site in sites])
        phases = []
        for a, t in ((aligned, transverse), (x, np.cross(nadir, x))):
            grid = wind_up(sites, axes, np.ones(len(sites), dtype=bool),
                           position[:, np.newaxis], a[:, np.newaxis], t[:, np.newaxis])
            phases.append(np.diagonal(grid[:, :, 0]))
        windup = np.angle(np.exp(1j * (phases[0] - phases[1]))) / (2 * np.pi)
        for key, value in (("difference", difference), ("turning", eclips_off | ours_off),
                           ("windup", windup), ("beta", event["beta"]),
                           ("ours_nominal", ~ours_off), ("eclips_nominal", ~eclips_off),
                           ("block", np.full(len(time), event["block"]))):
            out[key].append(value)
    return {k: np.concatenate(v) for k, v in out.items()}
