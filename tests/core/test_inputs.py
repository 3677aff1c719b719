# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""One coercion step for targets: what it refuses, and the one rule for Earth-bound frames."""

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import (
    FK4,
    GCRS,
    ICRS,
    ITRS,
    AltAz,
    CartesianRepresentation,
    EarthLocation,
    HADec,
    SkyCoord,
)
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    CoordinateOrbit,
    NominalAttitude,
    Satellite,
    feed_rotation_grid,
)
from astropy_feedrot.core.inputs import as_skycoord

SITE = EarthLocation.from_geodetic(6.88 * u.deg, 50.52 * u.deg, 416 * u.m)  # Effelsberg
ANTENNA = Antenna(SITE, AltAzMount())
TIMES = Time("2023-01-25T20:00") + [0, 1, 2] * u.hour


@pytest.mark.parametrize("frame", [AltAz, HADec])
def test_observed_frame_without_obstime_is_refused(frame):
    # It was taken at J2000; astropy itself refuses to transform it.
    name = frame.__name__
    if frame is AltAz:
        target = SkyCoord(AltAz(az=30 * u.deg, alt=40 * u.deg, location=SITE))
    else:
        target = SkyCoord(HADec(ha=1 * u.hourangle, dec=40 * u.deg, location=SITE))
    with pytest.raises(ValueError, match=rf"^target is in {name} without an obstime: the "
                       rf"{name} of a direction changes with time \(astropy refuses to "
                       r"transform it too\); give .*ICRS \(fixed in the sky\) or ITRS \(fixed "
                       r"on the Earth\)$"):
        ANTENNA.feed_rotation(target, TIMES)


def test_altaz_at_other_epochs_is_ambiguous_and_refused():
    target = SkyCoord(AltAz(az=30 * u.deg, alt=40 * u.deg, location=SITE, obstime=TIMES[0]))
    with pytest.raises(ValueError, match=r"^target is in AltAz at obstime "
                       r"2023-01-25T20:00:00\.000, not at the epochs of observation "
                       r"\(2023-01-25T20:00:00\.000 \.\.\. 2023-01-25T22:00:00\.000, shape "
                       r"\(3,\)\): .* ambiguous; give target\.icrs for a direction fixed in the "
                       r"sky, target\.itrs for one fixed on the Earth$"):
        ANTENNA.feed_rotation(target, TIMES)


def test_altaz_at_the_epochs_is_the_direction_astropy_gives():
    # Reference: astropy's own transformation of the same AltAz directions to ICRS, each
    # at its epoch (the two readings, fixed on the Earth or in the sky, agree there).
    target = SkyCoord(AltAz(az=[30, 200, 300] * u.deg, alt=[40, 60, 20] * u.deg,
                            location=SITE, obstime=TIMES))
    icrs = target.transform_to(ICRS())
    assert_quantity_allclose(ANTENNA.feed_rotation(target, TIMES),
                             ANTENNA.feed_rotation(icrs, TIMES), atol=1e-6 * u.deg)


@pytest.mark.parametrize("make", [
    lambda: SkyCoord(GCRS(CartesianRepresentation(3000, 0, 0, unit=u.km), obstime=TIMES[0])),
    lambda: SkyCoord(ITRS(CartesianRepresentation(0, 0, 3000, unit=u.km), obstime=TIMES[0])),
])
def test_geocentric_position_inside_the_earth_is_refused(make):
    with pytest.raises(ValueError, match=r"^target in (GCRS|ITRS) is 3000 km from the "
                       r"geocentre, inside the Earth; a position needs its distance from the "
                       r"geocentre \(kilometres given as metres\?\), a direction no distance "
                       r"at all$"):
        ANTENNA.feed_rotation(make(), TIMES)


def test_geocentric_positions_outside_the_earth_and_directions_pass():
    for target in (SkyCoord(GCRS(CartesianRepresentation(26000, 0, 0, unit=u.km),
                                 obstime=TIMES[0])),
                   SkyCoord(GCRS(ra=10 * u.deg, dec=20 * u.deg, obstime=TIMES[0]))):
        assert as_skycoord(target) is target


def test_array_target_inside_the_earth_names_the_element():
    xyz = CartesianRepresentation([26000, 6000], [0, 0], [0, 0], unit=u.km)
    with pytest.raises(ValueError, match=r"^target\[1\] in GCRS is 6000 km from the geocentre"):
        as_skycoord(SkyCoord(GCRS(xyz, obstime=TIMES[0])))


def test_satellite_inside_the_earth_is_refused_in_the_object_api():
    # The docs promise it; an orbit 1,000 km from the geocentre gave angles.
    orbit = CoordinateOrbit(SkyCoord(ITRS(x=1000e3 * u.m, y=0 * u.m, z=0 * u.m,
                                          obstime=TIMES[0])))
    satellite = Satellite(orbit, NominalAttitude(), name="LOW")
    match = (r"^the orbit of (LOW) puts it 1000 km from the geocentre, inside the Earth, "
             r"at 3 of 3 epochs; orbit positions are geocentric, in metres \(kilometres given "
             r"as metres\?\)$")
    with pytest.raises(ValueError, match=match):
        ANTENNA.feed_rotation(satellite, TIMES)
    with pytest.raises(ValueError, match=match):
        feed_rotation_grid([ANTENNA], [satellite], TIMES)


def test_fk4_target_with_proper_motion():
    # It raised astropy's NotImplementedError from deep inside (apply_space_motion in a
    # frame with explicit time dependence). Reference: astropy's own transformation of
    # the same FK4 target, with its motion, to ICRS.
    target = SkyCoord(ra=10 * u.deg, dec=20 * u.deg, pm_ra_cosdec=500 * u.mas / u.yr,
                      pm_dec=300 * u.mas / u.yr, frame=FK4, obstime=Time("B1950"))
    angles = ANTENNA.feed_rotation(target, TIMES)
    assert_quantity_allclose(angles, ANTENNA.feed_rotation(target.icrs, TIMES),
                             atol=1e-9 * u.deg)
    # The motion is applied: 73 years at 0.58 arcsec/yr move it by 42 arcsec.
    static = SkyCoord(ra=10 * u.deg, dec=20 * u.deg, frame=FK4)
    assert np.all(np.abs(angles - ANTENNA.feed_rotation(static, TIMES)) > 1e-4 * u.deg)
