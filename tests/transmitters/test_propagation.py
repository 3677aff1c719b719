# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""SGP4 evaluated at nodes and interpolated, against SGP4 at every epoch.

Reference: the ``sgp4`` package's ``Satrec.sgp4_array`` called directly at
each epoch, on element sets read by ``Satrec.twoline2rv`` from the same two
lines (independent of the package's propagation). The promise: positions
within 1 mm everywhere, SGP4's own error codes at every epoch.
"""

import numpy as np
import pytest
from astropy import units as u
from astropy.time import Time
from sgp4.api import Satrec

from astropy_feedrot import OrbitWarning, TLEOrbit, conf
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
from astropy_feedrot.transmitters.orbits import propagate_tles
from astropy_feedrot.transmitters.propagation import TOLERANCE, node_spacing, propagate

#: The promise of the interpolation, in metres.
PROMISE = 1e-3

DATE = Time("2023-01-25T00:00:00", scale="utc")
DAY_AT_1S = DATE + np.arange(86400) * u.s


def orbit(kind):
    """Element sets of each regime (hypothetical except GPS SVN 76, Table 2 of the paper)."""
    if kind == "MEO (GPS SVN 76)":
        return TLEOrbit(*GPS_SVN76_TLE)
    if kind == "LEO (ISS-like)":
        return TLEOrbit.from_elements(DATE, inclination=51.64 * u.deg, raan=208.9 * u.deg,
                                      altitude=418 * u.km, eccentricity=0.0005,
                                      argument_of_perigee=282 * u.deg, mean_anomaly=171 * u.deg,
                                      bstar=3.0e-4)
    if kind == "LEO (GENESIS, 6000 km)":
        return TLEOrbit.from_elements(DATE, inclination=97 * u.deg, raan=30 * u.deg,
                                      altitude=6000 * u.km)
    if kind == "HEO (Molniya-like)":
        return TLEOrbit.from_elements(DATE, inclination=63.4 * u.deg, raan=226 * u.deg,
                                      mean_motion=2.006 * u.cycle / u.day, eccentricity=0.714,
                                      argument_of_perigee=280 * u.deg, mean_anomaly=13 * u.deg)
    if kind == "GEO":
        return TLEOrbit.from_elements(DATE, inclination=0.05 * u.deg, raan=80 * u.deg,
                                      mean_motion=1.0027 * u.cycle / u.day)
    raise AssertionError(kind)


KINDS = ["MEO (GPS SVN 76)", "LEO (ISS-like)", "LEO (GENESIS, 6000 km)", "HEO (Molniya-like)",
         "GEO"]


def direct(orbits, obstime):
    """Error codes (S, N) and TEME positions (S, N, 3) in metres, SGP4 at each epoch."""
    utc = obstime.utc
    jd1 = np.ascontiguousarray(utc.jd1, dtype=float).ravel()
    jd2 = np.ascontiguousarray(utc.jd2, dtype=float).ravel()
    errors, positions = [], []
    for o in orbits:
        e, r, _ = Satrec.twoline2rv(o.line1, o.line2).sgp4_array(jd1, jd2)
        errors.append(e)
        positions.append(np.asarray(r) * 1e3)
    return np.array(errors), np.array(positions)


def satrec(o):
    return Satrec.twoline2rv(o.line1, o.line2)


def split(obstime):
    utc = obstime.utc
    return (np.ascontiguousarray(utc.jd1, dtype=float).ravel(),
            np.ascontiguousarray(utc.jd2, dtype=float).ravel())


@pytest.mark.parametrize("kind", KINDS)
def test_dense_epochs_within_a_millimetre(kind):
    o = orbit(kind)
    jd1, jd2 = split(DAY_AT_1S)
    error, r = propagate([satrec(o)], jd1, jd2)
    reference_error, reference = direct([o], DAY_AT_1S)
    assert np.all(error == 0) and np.all(reference_error == 0)
    difference = np.linalg.norm(r - reference, axis=-1)
    assert difference.max() < PROMISE
    # Interpolated indeed (SGP4 at every epoch would agree to the last bit).
    assert np.count_nonzero(difference) > 0.9 * difference.size


def test_node_spacing_follows_the_orbit():
    # Powers of two seconds; shorter for faster (lower, more eccentric) orbits.
    spacing = {kind: node_spacing(satrec(orbit(kind))) for kind in KINDS}
    for h in spacing.values():
        assert 1 <= h <= 1024 and np.log2(h) == int(np.log2(h))
    assert spacing["LEO (ISS-like)"] < spacing["LEO (GENESIS, 6000 km)"]
    assert spacing["LEO (GENESIS, 6000 km)"] < spacing["MEO (GPS SVN 76)"]
    assert spacing["MEO (GPS SVN 76)"] <= spacing["GEO"]
    assert spacing["HEO (Molniya-like)"] < spacing["MEO (GPS SVN 76)"]
    # The Lagrange remainder bound (6.5625^2 / 8!) h^8 a n^8 of a circular
    # orbit of radius a and mean motion n, at the ISS-like spacing: below 0.1 mm.
    iss = satrec(orbit("LEO (ISS-like)"))
    n = iss.no_kozai / 60
    a = iss.a * iss.radiusearthkm * 1e3
    assert 6.5625**2 / 40320 * (spacing["LEO (ISS-like)"] * n) ** 8 * a < TOLERANCE


def test_sparse_epochs_are_sgp4_itself():
    # Two epochs a day: nodes would outnumber epochs, so SGP4 runs at each.
    times = DATE + np.arange(0, 10, 0.5) * u.day
    orbits = [orbit(kind) for kind in KINDS]
    error, r = propagate([satrec(o) for o in orbits], *split(times))
    reference_error, reference = direct(orbits, times)
    assert np.array_equal(error, reference_error)
    assert np.array_equal(r, reference)


def test_irregular_unsorted_and_multidimensional_epochs():
    # Bursts of dense epochs, isolated epochs, duplicates and disorder, in a 2-d Time.
    rng = np.random.default_rng(11)
    seconds = np.concatenate([rng.uniform(0, 3600, 3000), 7200 + np.arange(0, 600, 0.25),
                              rng.uniform(0, 5 * 86400, 40), [100.0, 100.0, 50000.0, 7200.0]])
    rng.shuffle(seconds)
    times = (DATE + seconds * u.s).reshape(-1, 4)
    orbits = [orbit("MEO (GPS SVN 76)"), orbit("LEO (ISS-like)")]
    r = propagate_tles(orbits, times)
    assert r.shape == (2,) + times.shape + (3,)
    _, reference = direct(orbits, times)
    difference = np.linalg.norm(r.reshape(2, -1, 3) - reference, axis=-1)
    assert difference.max() < PROMISE


def test_fast_path_off_is_sgp4_at_every_epoch():
    times = DAY_AT_1S[:7200]
    orbits = [orbit("MEO (GPS SVN 76)")]
    with conf.set_temp("fast_path", False):
        r = propagate_tles(orbits, times)
    assert np.array_equal(r, direct(orbits, times)[1])


def test_leap_second():
    # One hour at 1 s across 2016-12-31T23:59:60 UTC. SGP4 reads the two-part
    # Julian date as a uniform scale; so does the interpolation.
    o = TLEOrbit.from_elements(Time("2016-12-31T12:00"), inclination=55 * u.deg,
                               raan=10 * u.deg, altitude=20200 * u.km)
    times = Time("2016-12-31T23:30:00", scale="utc") + np.arange(3600) * u.s
    assert "23:59:60" in "".join(times.iso)
    r = propagate_tles([o], times)
    reference = direct([o], times)[1]
    assert np.linalg.norm(r - reference, axis=-1).max() < PROMISE


def decaying(altitude, bstar):
    return TLEOrbit.from_elements(DATE, inclination=97 * u.deg, raan=30 * u.deg,
                                  altitude=altitude * u.km, bstar=bstar, name="FALLING")


@pytest.mark.parametrize("altitude, bstar, seconds", [
    (200, 0.01, 86400),  # decays after 23 h, comes back for 15 min, then for good
    (150, 0.05, 3000),   # decays after 21 min (SGP4 error 6)
])
def test_failures_at_the_epochs_of_sgp4(altitude, bstar, seconds):
    o = decaying(altitude, bstar)
    times = o.epoch + np.arange(seconds) * u.s
    error, r = propagate([satrec(o)], *split(times))
    reference_error, reference = direct([o], times)
    assert np.any(reference_error != 0) and np.any(reference_error == 0)
    assert np.array_equal(error, reference_error)
    ok = reference_error == 0
    assert np.linalg.norm(r[ok] - reference[ok], axis=-1).max() < PROMISE
    # Through propagate_tles: NaN exactly there, and one warning with the count.
    count = np.count_nonzero(reference_error)
    with pytest.warns(OrbitWarning, match=rf"^SGP4 fails at {count} of {seconds} epochs "
                      r"\(FALLING: ") as caught:
        teme = propagate_tles([o], times)
    assert len(caught) == 1
    assert np.array_equal(np.isnan(teme[..., 0]), ~ok)


def test_failed_positions_never_interpolated():
    # The reentry-and-back of the 200 km orbit: around it, every epoch is SGP4's own.
    o = decaying(200, 0.01)
    times = o.epoch + np.arange(82000, 86400) * u.s
    error, r = propagate([satrec(o)], *split(times))
    reference_error, reference = direct([o], times)
    assert np.array_equal(error, reference_error)
    changes = np.flatnonzero(np.diff(reference_error[0].astype(int)))
    assert changes.size >= 2
    near = np.zeros(times.shape, dtype=bool)
    for i in changes:
        near[max(i - 100, 0):i + 100] = True
    near &= reference_error[0] == 0
    assert np.array_equal(r[0, near], reference[0, near])


def test_not_finite_epochs_go_to_sgp4():
    jd1, jd2 = split(DAY_AT_1S[:1000])
    jd2 = jd2.copy()
    jd2[5] = np.nan
    error, r = propagate([satrec(orbit("GEO"))], jd1, jd2)
    assert np.all(np.isnan(r[0, 5])) and np.all(np.isfinite(r[0, :5]))
