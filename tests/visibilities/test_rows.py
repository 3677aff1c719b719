# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Feed rotation of the rows of a visibility table, and the north of a frame.

References: ERFA's ``hd2pa`` on astropy's HADec (the parallactic angle of an
alt-az Cassegrain antenna), and ERFA's ``atci13`` and ``pas`` for the
position angle of a catalogue north in the apparent frame.
"""

import warnings

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import FK4, AltAz, HADec, SkyCoord
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time

from astropy_feedrot import DegenerateGeometryWarning
from astropy_feedrot.stations.catalogue import get_antenna
from astropy_feedrot.visibilities.rows import (
    distinct_epochs,
    feed_rotation_rows,
    frame_position_angle,
)

ANTENNAS = {3: get_antenna("FD-VLBA"), 7: get_antenna("WETTZ13S"), 9: get_antenna("GGAO12M")}
SOURCE = SkyCoord("03h19m48.16s +41d30m42.1s")
TIMES = Time("2023-01-25T20:00") + np.arange(0, 6, 0.5) * u.hour


def parallactic(antenna, source, times):
    """erfa.hd2pa from astropy's HADec at the antenna (alt-az Cassegrain)."""
    hadec = source.transform_to(HADec(obstime=times, location=antenna.location))
    lat = antenna.location.to_geodetic().lat
    return erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, lat.rad) * u.rad


def test_rows_pick_each_antennas_parallactic_angle():
    # Every baseline of three antennas at every epoch, in a shuffled order.
    pairs = [(3, 7), (3, 9), (7, 9), (9, 3)]
    ant1 = np.repeat([p[0] for p in pairs], TIMES.size)
    ant2 = np.repeat([p[1] for p in pairs], TIMES.size)
    times = TIMES[np.tile(np.arange(TIMES.size), len(pairs))]
    order = np.random.default_rng(0).permutation(ant1.size)
    ant1, ant2, times = ant1[order], ant2[order], times[order]
    rows = feed_rotation_rows(ANTENNAS, ant1, ant2, times, SOURCE)
    for column, numbers in ((0, ant1), (1, ant2)):
        for number, antenna in ANTENNAS.items():
            where = numbers == number
            assert_quantity_allclose(rows[where, column],
                                     parallactic(antenna, SOURCE, times[where]),
                                     atol=1 * u.mas)


def test_several_sources_and_a_moving_one():
    other = SkyCoord("12h29m06.7s +02d03m09s")
    ant1, ant2 = np.full(TIMES.size, 3), np.full(TIMES.size, 7)
    index = np.where(np.arange(TIMES.size) % 2, "a", "b")
    sources = {"a": SOURCE, "b": other}
    rows = feed_rotation_rows(ANTENNAS, ant1, ant2, TIMES, sources, index)
    for key, coord in sources.items():
        where = index == key
        assert_quantity_allclose(rows[where, 0], parallactic(ANTENNAS[3], coord, TIMES[where]),
                                 atol=1 * u.mas)

    # A moving source: the same source given as a function of the epochs.
    def track(epochs):
        return SkyCoord(np.full(epochs.shape, SOURCE.ra.deg) * u.deg,
                        np.full(epochs.shape, SOURCE.dec.deg) * u.deg)

    moving = feed_rotation_rows(ANTENNAS, ant1, ant2, TIMES, track)
    assert_quantity_allclose(moving, feed_rotation_rows(ANTENNAS, ant1, ant2, TIMES, SOURCE),
                             atol=1 * u.mas)


def test_a_direction_fixed_in_the_local_frame():
    # A drift scan at azimuth 30 deg, elevation 50 deg: its parallactic angle
    # follows from the spherical triangle (ERFA hd2pa after ae2hd).
    site = ANTENNAS[3]

    def drift(epochs):
        return SkyCoord(AltAz(az=np.full(epochs.shape, 30.0) * u.deg,
                              alt=np.full(epochs.shape, 50.0) * u.deg,
                              obstime=epochs, location=site.location))

    rows = feed_rotation_rows(ANTENNAS, [3, 3], [7, 7], TIMES[:2], drift)
    lat = site.location.to_geodetic().lat.rad
    ha, dec = erfa.ae2hd(np.radians(30.0), np.radians(50.0), lat)
    assert_quantity_allclose(rows[:, 0], [erfa.hd2pa(ha, dec, lat)] * 2 * u.rad,
                             atol=0.1 * u.arcsec)


def test_zenith_rows_are_nan_with_one_warning():
    site = ANTENNAS[3]

    def zenith(epochs):
        return SkyCoord(AltAz(az=np.zeros(epochs.shape) * u.deg,
                              alt=np.full(epochs.shape, 90.0) * u.deg,
                              obstime=epochs, location=site.location))

    with pytest.warns(DegenerateGeometryWarning, match="undefined in 3 of 3 rows") as record:
        rows = feed_rotation_rows(ANTENNAS, [3, 3, 3], [7, 7, 7], TIMES[:3], zenith)
    assert len(record) == 1
    assert np.all(np.isnan(rows[:, 0])) and np.all(np.isfinite(rows[:, 1]))


@pytest.mark.parametrize("ra, dec", [(90, 0), (0, 0), (45, 60), (200, -80), (310, 30)])
def test_frame_position_angle_against_erfa(ra, dec):
    # ERFA: ICRS to CIRS (atci13: light deflection, aberration, precession-nutation)
    # of the source and of a point 1 arcsec north of it; then the position angle (pas).
    t = Time("2026-11-22T03:00")
    offset = np.radians(1 / 3600)
    r, d = np.radians(ra), np.radians(dec)
    r1, d1, _ = erfa.atci13(r, d, 0, 0, 0, 0, t.tt.jd1, t.tt.jd2)
    r2, d2, _ = erfa.atci13(r, d + offset, 0, 0, 0, 0, t.tt.jd1, t.tt.jd2)
    expected = erfa.pas(r1, d1, r2, d2) * u.rad
    got = frame_position_angle(SkyCoord(ra * u.deg, dec * u.deg), t)
    assert_quantity_allclose(got, expected, atol=1 * u.mas)


def test_frame_position_angle_of_other_frames():
    t = Time("2026-11-22T03:00")
    source = SkyCoord(90 * u.deg, 20 * u.deg)
    icrs = frame_position_angle(source, t, "icrs")
    # FK5 J2000 differs from ICRS by tens of mas; FK4 B1950 by half a century of
    # precession (about 0.28 deg at RA 6 h, sec(dec) times 20 arcsec a year).
    assert abs(frame_position_angle(source, t, "fk5") - icrs) < 0.1 * u.arcsec
    fk4 = frame_position_angle(source, t, FK4(equinox="B1950"))
    assert 0.25 * u.deg < abs(fk4 - icrs) < 0.35 * u.deg
    # 'catalogue' is the source's own frame.
    assert_quantity_allclose(frame_position_angle(source.transform_to(FK4(equinox="B1950")),
                                                  t, "catalogue"), fk4, atol=1 * u.mas)


def test_rows_in_the_icrs_frame_subtract_its_angle():
    apparent = feed_rotation_rows(ANTENNAS, [3, 3], [7, 7], TIMES[:2], SOURCE)
    icrs = feed_rotation_rows(ANTENNAS, [3, 3], [7, 7], TIMES[:2], SOURCE, frame="icrs")
    delta = frame_position_angle(SOURCE, TIMES[:2], "icrs")
    assert_quantity_allclose(apparent - icrs, np.stack([delta, delta], axis=1), atol=1e-9 * u.deg)


def test_masked_epochs_and_no_rows():
    # A masked epoch gives NaN in its row, without a warning (as everywhere in
    # the package); a table without rows gives an empty result.
    times = TIMES[:3].copy()
    times[1] = np.ma.masked
    rows = feed_rotation_rows(ANTENNAS, [3, 3, 3], [7, 7, 7], times, SOURCE)
    assert np.all(np.isnan(rows[1])) and np.all(np.isfinite(rows[[0, 2]]))
    assert_quantity_allclose(rows[[0, 2], 0], parallactic(ANTENNAS[3], SOURCE, TIMES[[0, 2]]),
                             atol=1 * u.mas)
    empty = feed_rotation_rows(ANTENNAS, [], [], Time([], format="mjd"), SOURCE)
    assert empty.shape == (0, 2)


def test_distinct_epochs_compare_both_parts():
    t = Time(60000.0, np.array([0.25, 0.0, 0.25, 0.5]), format="mjd")
    epochs, index = distinct_epochs(t)
    assert epochs.size == 3 and list(index) == [1, 0, 1, 2]
    # The same instant written with its parts split differently is one epoch.
    same = Time([2460000.5, 2460000.0], [0.25, 0.75], format="jd")
    assert distinct_epochs(same)[0].size == 1
    with pytest.raises(ValueError, match="must be 1-d"):
        distinct_epochs(Time([[60000.0]], format="mjd"))


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(antennas=[1, 2]), TypeError, "mapping"),
    (dict(antennas={3: "FD", 7: "WZ"}), TypeError, r"antennas\[3\] must be an Antenna"),
    (dict(antenna2=[7, 4]), ValueError, r"antenna numbers \[4\]"),
    (dict(antenna2=[7]), ValueError, "one value per row"),
    (dict(antenna1=[3.5, 3]), ValueError, r"antenna1 must be whole antenna numbers"),
    (dict(antenna2=[np.nan, 7]), ValueError, r"antenna2 must be whole antenna numbers"),
    (dict(antenna1=["3", "3"]), ValueError, r"antenna1 must be whole antenna numbers"),
    (dict(sources={"a": SOURCE}), ValueError, "source_index must give"),
    (dict(source_index=["a", "a"]), TypeError, "must be a mapping"),
    (dict(sources={"a": SOURCE}, source_index=["a", "b"]), ValueError, r"source keys \['b'\]"),
    (dict(sources={"a": SOURCE}, source_index=["a"]), ValueError, "one key per row"),
    (dict(sources=SkyCoord([1, 2] * u.deg, [3, 4] * u.deg)), ValueError, "one direction"),
    (dict(sources=lambda e: SOURCE), ValueError, "gave positions of shape"),
    (dict(frame="nowhere"), ValueError, "unknown frame"),
    (dict(frame="altaz"), ValueError, "Earth-bound"),
    (dict(frame=3), TypeError, "frame must be a name"),
])
def test_errors(kwargs, error, match):
    arguments = dict(antennas=ANTENNAS, antenna1=[3, 3], antenna2=[7, 7], obstime=TIMES[:2],
                     sources=SOURCE)
    arguments.update(kwargs)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(error, match=match):
            feed_rotation_rows(**arguments)
