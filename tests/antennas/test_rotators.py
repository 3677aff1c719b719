# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Rotators, against the geometry of the dipole model written out here.

The reference of every test is built from vectors in this file: the line of
sight from astropy's topocentric ITRS frame, the local vertical from the
geodetic latitude and longitude, the receiver's effective dipole, its turn
about the line of sight by Rodrigues' formula, and its position angle against
the projected celestial pole (north through east, as the observer sees it).
"""

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import ITRS, EarthLocation, SkyCoord
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    DegenerateGeometryWarning,
    EquatorialMount,
    NasmythFocus,
    Rotator,
    StationaryMount,
    feed_rotation_grid,
)
from astropy_feedrot.antennas.rotators import rotation_angles, rotation_rates
from astropy_feedrot.applied.simulations import gps_svn76
from astropy_feedrot.engine.equations import Receivers, feed_rotation
from astropy_feedrot.engine.grid import receiver_arrays

SITE = EarthLocation.from_geodetic(12.8775 * u.deg, 49.1450 * u.deg, 670 * u.m)  # Wettzell
SOURCE = SkyCoord("03h19m48.16s +41d30m42.1s")  # 3C 84
START = Time("2023-01-25T16:00")
TRACK = START + np.arange(0, 14, 0.25) * u.hour
ROTATORS = [None, "fixed", "series", "sky"]


def rodrigues(v, k, angle):
    """``v`` turned right-handedly about the unit axis ``k`` by ``angle`` (radians)."""
    angle = np.asarray(angle)[..., np.newaxis]
    kv = np.sum(k * v, axis=-1, keepdims=True)
    return v * np.cos(angle) + np.cross(k, v) * np.sin(angle) + k * kv * (1 - np.cos(angle))


def sky_geometry(times, source=SOURCE, site=SITE):
    """Line of sight, local up and the pole, as ITRS unit vectors (independent of the package)."""
    itrs = source.transform_to(ITRS(obstime=times, location=site))
    s = itrs.cartesian.xyz.value.T
    s = s / np.linalg.norm(s, axis=-1, keepdims=True)
    lon, lat = site.lon.rad, site.lat.rad  # geodetic: the ellipsoid normal
    up = np.array([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)])
    pole = np.array([0.0, 0.0, 1.0])
    return s, np.broadcast_to(up, s.shape), np.broadcast_to(pole, s.shape)


def on_sky(v, s):
    return v - np.sum(v * s, axis=-1, keepdims=True) * s


def position_angle(r, s, pole):
    """Position angle of ``r`` on the sky at ``s``: from north through east (radians)."""
    north = on_sky(pole, s)
    north /= np.linalg.norm(north, axis=-1, keepdims=True)
    east = np.cross(pole, s)  # increasing right ascension
    east /= np.linalg.norm(east, axis=-1, keepdims=True)
    r = on_sky(r, s)
    return np.arctan2(np.sum(r * east, axis=-1), np.sum(r * north, axis=-1))


def elevation(s, up):
    return np.arcsin(np.sum(s * up, axis=-1))


def receiver_dipole(kind, s, up, pole):
    """The receiver's effective dipole of each antenna, before any rotator."""
    if kind == "altaz":  # Eq 10 with the vertical
        return on_sky(up, s)
    if kind == "equatorial":  # Eq 10 with the pole
        return on_sky(pole, s)
    # Nasmyth right: the Cassegrain dipole turned on the sky by the elevation
    # (Eq 38), counter-clockwise as the observer sees it (about -s).
    return rodrigues(on_sky(up, s), -s, elevation(s, up))


MOUNTS = {"altaz": (AltAzMount(), None), "equatorial": (EquatorialMount(), None),
          "nasmyth": (AltAzMount(), NasmythFocus("right"))}

RHO0 = 37.5 * u.deg
# A series that turns at a known rate, logged every hour and wrapped to [-180, 180):
# rho(t) = -20 deg + 9 deg/h (t - START), across the wrap at 180 deg.
SERIES_TIMES = START + np.arange(-8, 25) * u.hour
SERIES_ANGLES = (-20 + 9 * np.arange(-8, 25) + 180) % 360 * u.deg - 180 * u.deg


def series_angle(times):
    return np.radians(-20 + 9 * (times - START).to_value(u.hour))


def make_rotator(mode):
    if mode is None:
        return None
    if mode == "series":
        return Rotator("series", times=SERIES_TIMES, angles=SERIES_ANGLES)
    return Rotator(mode, RHO0)


def antenna(kind, mode):
    mount, focus = MOUNTS[kind]
    return Antenna(SITE, mount, focus, rotator=make_rotator(mode), name=f"{kind}-{mode}")


def expected_phase(kind, mode, times):
    """The position angle of the turned dipole (radians)."""
    s, up, pole = sky_geometry(times)
    r = receiver_dipole(kind, s, up, pole)
    if mode == "fixed":
        r = rodrigues(r, -s, RHO0.to_value(u.rad))
    elif mode == "series":
        r = rodrigues(r, -s, series_angle(times))
    elif mode == "sky":  # the rotator undoes the dipole's angle and adds rho0
        r = rodrigues(r, -s, RHO0.to_value(u.rad) - position_angle(r, s, pole))
    return position_angle(r, s, pole)


def wrapped_difference(a, b):
    return (u.Quantity(a) - u.Quantity(b) + 180 * u.deg) % (360 * u.deg) - 180 * u.deg


@pytest.mark.parametrize("kind", list(MOUNTS))
@pytest.mark.parametrize("mode", ROTATORS)
def test_rotated_dipole(kind, mode):
    # The position angle of the explicitly turned dipole (Rodrigues) is the feed rotation.
    times = TRACK[::4]
    phi = antenna(kind, mode).feed_rotation(SOURCE, times)
    expected = expected_phase(kind, mode, times) * u.rad
    # 1e-6 deg: astropy's topocentric direction against the package's fast path.
    assert_quantity_allclose(wrapped_difference(phi, expected), 0 * u.deg, atol=1e-6 * u.deg)


@pytest.mark.parametrize("kind", list(MOUNTS))
def test_the_sign_turns_north_towards_east(kind):
    # A small positive rho moves the dipole towards the east (by hand: d PA = +rho).
    times = TRACK[10]
    s, up, pole = sky_geometry(times)
    r = receiver_dipole(kind, s, up, pole)
    east = np.cross(pole, s)
    turned = rodrigues(r, -s, 1e-3)
    north = on_sky(pole, s)
    north_before = np.dot(r, north) / np.linalg.norm(north)
    # The component along east grows with the component along north (first order).
    growth = (np.dot(turned - r, east) / np.linalg.norm(east)) / 1e-3
    assert growth == pytest.approx(north_before, abs=1e-3)
    rotated = Antenna(SITE, *MOUNTS[kind], rotator=Rotator("fixed", 1 * u.deg))
    plain = Antenna(SITE, *MOUNTS[kind])
    assert_quantity_allclose(wrapped_difference(rotated.feed_rotation(SOURCE, times),
                                                plain.feed_rotation(SOURCE, times)),
                             1 * u.deg, atol=1e-12 * u.deg)


@pytest.mark.parametrize("kind", list(MOUNTS))
def test_sky_mode_is_constant_over_a_long_track(kind):
    # 20 days every 10 minutes: the feed keeps rho0 on the sky (the identity of the mode).
    times = START + np.arange(0, 20 * 24 * 6) * 10 * u.min
    phi = antenna(kind, "sky").feed_rotation(SOURCE, times)
    assert np.all(np.abs(phi - RHO0) < 1e-9 * u.deg)
    rate = antenna(kind, "sky").feed_rotation_rate(SOURCE, times[:50])
    assert np.all(rate == 0)


def test_lcp_is_the_negative():
    times = TRACK[::7]
    for mode in ROTATORS[1:]:
        a = antenna("nasmyth", mode)
        assert_quantity_allclose(a.feed_rotation(SOURCE, times, "LCP"),
                                 -a.feed_rotation(SOURCE, times), atol=1e-12 * u.deg)


@pytest.mark.parametrize("kind", list(MOUNTS))
def test_rates(kind):
    times = TRACK[::9]
    plain = antenna(kind, None).feed_rotation_rate(SOURCE, times)
    fixed = antenna(kind, "fixed").feed_rotation_rate(SOURCE, times)
    series = antenna(kind, "series").feed_rotation_rate(SOURCE, times)
    assert np.array_equal(fixed, plain)
    # The series turns at 9 deg/h (its closed form above).
    assert_quantity_allclose(series - plain, 9 * u.deg / u.hour, rtol=1e-9)


def test_series_interpolates_the_continuous_angles():
    # Across +-180 deg the series is made continuous before interpolating.
    log = Rotator("series", times=START + [0, 1] * u.hour, angles=[170, -170] * u.deg)
    assert_quantity_allclose(log.angle_at(START + 30 * u.min), 180 * u.deg)
    assert_quantity_allclose(log.rate(START + 30 * u.min), np.radians(20) / 3600,
                             rtol=1e-9)
    masked = START + [0, 10] * u.min
    masked[1] = np.ma.masked
    assert np.isnan(log.radians_at(masked)[1])


def test_satellites_sky_mode_keeps_the_receiver_term():
    # For a satellite the receiver term is rho0 and the total is the transmitter term + rho0.
    times = Time("2023-01-25T09:00") + np.arange(0, 5, 0.5) * u.hour
    a = Antenna(SITE, AltAzMount(), rotator=Rotator("sky", RHO0))
    terms = a.feed_rotation_terms(gps_svn76(), times)
    assert_quantity_allclose(terms.receiver, RHO0, atol=1e-9 * u.deg)
    assert_quantity_allclose(wrapped_difference(terms.total, terms.transmitter + RHO0),
                             0 * u.deg, atol=1e-9 * u.deg)
    series = Antenna(SITE, AltAzMount(), rotator=make_rotator("series"))
    plain = Antenna(SITE, AltAzMount())
    assert_quantity_allclose(series.feed_rotation_rate(gps_svn76(), times)
                             - plain.feed_rotation_rate(gps_svn76(), times),
                             9 * u.deg / u.hour, rtol=1e-6)


def test_grid_and_tables_apply_the_rotators():
    antennas = [antenna(kind, mode) for kind in MOUNTS for mode in ROTATORS]
    grid = feed_rotation_grid(antennas, SOURCE, TRACK)
    for i, a in enumerate(antennas):
        assert_quantity_allclose(wrapped_difference(grid[:, i, 0],
                                                    a.feed_rotation(SOURCE, TRACK)),
                                 0 * u.deg, atol=1e-9 * u.deg)


def test_degenerate_epochs_and_the_zenith():
    # At the zenith of an alt-az mount Eq 13 is undefined, and a fixed rotator keeps it so;
    # the sky mode holds the feed at rho0 there too (an ideal rotator). Latitude 45 deg.
    c = np.sqrt(0.5)
    enu = [[0.0, 1, 0], [-c, 0, c], [c, 0, c]]
    rx = Receivers.from_mounts([[4.5e6, 0, 4.5e6]] * 2, [enu] * 2, [AltAzMount()] * 2,
                               [None] * 2, [Rotator("fixed", RHO0), Rotator("sky", RHO0)])
    phase, _ = feed_rotation(rx, np.array([[[c, 0, c]]]))
    assert np.isnan(phase[0, 0])
    assert np.degrees(phase[1, 0]) == pytest.approx(RHO0.value, abs=1e-12)
    obs = Time("2023-01-25T18:00")
    pole = SkyCoord(ITRS(x=0, y=0, z=1, representation_type="cartesian", obstime=obs))
    with pytest.warns(DegenerateGeometryWarning, match="Rotator"):
        Antenna(SITE, AltAzMount(), rotator=Rotator("sky", RHO0)).feed_rotation(pole, obs)


def test_repr():
    a = Antenna(SITE, AltAzMount(), rotator=Rotator("sky", 10 * u.deg), name="X")
    assert repr(a).endswith("CassegrainFocus(), Rotator('sky', 10 deg)>")
    assert repr(make_rotator("series")).startswith("Rotator('series', 33 epochs, 2023-01-25T08:00")
    assert Rotator("sky", 10 * u.deg) == Rotator("sky", 10 * u.deg)
    assert Rotator("sky") != Rotator("fixed")


def test_engine_rotation_helpers():
    rotators = [None, make_rotator("series"), Rotator("fixed")]
    angles = rotation_angles(rotators, TRACK[:3])
    assert angles.shape == (3, 3)
    assert_quantity_allclose(angles[:, 1], series_angle(TRACK[:3]), rtol=1e-12)
    assert rotation_rates(rotators[::2], TRACK[:3]) is None
    with pytest.raises(ValueError, match=r"have a 'series' rotator.*pass rotation"):
        rx = Receivers.from_mounts([SITE.get_itrs().cartesian.xyz.to_value(u.m)],
                                   [np.eye(3)], [AltAzMount()], [None], rotators[1:2])
        feed_rotation(rx, np.array([[[0.0, 0.6, 0.8]]]))
    with pytest.raises(ValueError, match=r"rotation must have shape \(\.\.\., 1\)"):
        feed_rotation(rx, np.array([[[0.0, 0.6, 0.8]]]), rotation=np.zeros((1, 2)))
    with pytest.raises(ValueError, match="has no closed form for wind_up.*Rotator"):
        receiver_arrays([antenna("altaz", "sky")])


@pytest.mark.parametrize("args, kwargs, error, match", [
    (("spin",), {}, ValueError, r"mode must be one of \('sky', 'fixed', 'series'\), got 'spin'"),
    ((None,), {}, ValueError, r"mode must be one of"),
    (("fixed", 30), {}, TypeError, r"angle must be an angle Quantity .* degrees or radians"),
    (("fixed", 30 * u.m), {}, u.UnitsError, r"angle must be an angle .* got a quantity in m"),
    (("fixed", [1, 2] * u.deg), {}, ValueError, r"angle must be one finite angle"),
    (("sky", np.nan * u.deg), {}, ValueError, r"angle must be one finite angle"),
    (("sky",), {"times": SERIES_TIMES}, ValueError, r"times and angles go with mode 'series'"),
    (("series", 3 * u.deg), {}, ValueError, r"give times= and angles= instead of angle"),
    (("series",), {"times": SERIES_TIMES}, ValueError, r"needs times= .* and angles="),
    (("series",), {"times": [1, 2], "angles": [1, 2] * u.deg}, TypeError,
     r"times must be an astropy Time array, got list"),
    (("series",), {"times": SERIES_TIMES[:2], "angles": [1, 2]}, TypeError,
     r"angles must be an angle Quantity array"),
    (("series",), {"times": SERIES_TIMES[:2], "angles": [1, 2] * u.s}, u.UnitsError,
     r"angles must be angles .* got a quantity in s"),
    (("series",), {"times": SERIES_TIMES[:2], "angles": [1, 2, 3] * u.deg}, ValueError,
     r"angles has shape \(3,\) but times has shape \(2,\)"),
    (("series",), {"times": SERIES_TIMES[:1], "angles": [1] * u.deg}, ValueError,
     r"at least two epochs, got shape \(1,\)"),
    (("series",), {"times": SERIES_TIMES[1::-1], "angles": [1, 2] * u.deg}, ValueError,
     r"times must increase strictly; sort"),
    (("series",), {"times": SERIES_TIMES[:2], "angles": [1, np.nan] * u.deg}, ValueError,
     r"angles must all be finite"),
])
def test_bad_rotators(args, kwargs, error, match):
    with pytest.raises(error, match=match):
        Rotator(*args, **kwargs)


def test_bad_uses():
    times = SERIES_TIMES[:2].copy()
    times[1] = np.ma.masked
    with pytest.raises(ValueError, match="times has masked epochs"):
        Rotator("series", times=times, angles=[1, 2] * u.deg)
    with pytest.raises(ValueError, match=r"1 epochs lie outside the rotator's series .* "
                                         "extend the series or restrict the epochs"):
        antenna("altaz", "series").feed_rotation(SOURCE, START + [0, 30] * u.hour)
    with pytest.raises(ValueError, match="a StationaryMount does not track: a rotator turns "
                                         "the feed of a tracking antenna"):
        Antenna(SITE, StationaryMount(), rotator=Rotator("sky"))
    with pytest.raises(TypeError, match=r"rotator must be a Rotator or None, got str; "
                                        r"write Rotator\('sky'\)"):
        Antenna(SITE, AltAzMount(), rotator="sky")
