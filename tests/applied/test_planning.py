# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Planning polarization calibration: the range of feed rotation a source offers."""

import erfa
import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import AltAz, EarthLocation, HADec, SkyCoord
from astropy.table import Table
from astropy.tests.helper import assert_quantity_allclose
from astropy.time import Time

from astropy_feedrot import (
    AltAzMount,
    Antenna,
    ContinuityWarning,
    EquatorialMount,
    Rotator,
    feed_rotation_coverage,
    rank_sources,
)
from astropy_feedrot.stations.catalogue import get_antenna

VLA = EarthLocation.from_geodetic(-107.6184 * u.deg, 34.0789 * u.deg, 2124 * u.m)
SOURCES = {"3C84": SkyCoord("03h19m48.16s +41d30m42.1s"),
           "3C286": SkyCoord("13h31m08.29s +30d30m33.0s"),
           "NEARPOLE": SkyCoord("02h31m49.1s +86d15m51s"),
           "SOUTH": SkyCoord("05h00m00s -60d00m00s")}
DAY = Time("2024-03-01T00:00")


def test_a_zenith_transit_sweeps_180_degrees():
    # A source whose apparent declination is the site's latitude passes the zenith at
    # transit: the parallactic angle (Eq 16 with delta = phi) is atan2(cos(h/2),
    # sin(phi) sin(h/2)) for h > 0, from 90 deg at transit down to its value at setting,
    # and the mirror image before transit; it jumps by 180 deg at transit. Sampled at
    # +-(step/2) of hour angle dh around transit, the continuous series crosses the jump
    # the short way and spans 180 deg - 2 x, with 90 deg - x = Psi(dh/2), i.e.
    # x = atan(sin(phi) tan(dh/4)): 0.035 deg for a step of 1 minute at the VLA.
    transit = Time("2024-03-01T06:00")
    zenith = SkyCoord(HADec(ha=0 * u.hourangle, dec=VLA.lat, obstime=transit, location=VLA))
    source = SkyCoord(zenith.icrs.ra, zenith.icrs.dec)
    step = 1 * u.min
    start = transit - 12 * u.hour + step / 2  # no epoch at transit itself
    with pytest.warns(ContinuityWarning, match="consecutive steps exceed"):
        table = feed_rotation_coverage([Antenna(VLA, AltAzMount(), name="VLA")],
                                       {"zenith": source}, start, start + 24 * u.hour, step,
                                       min_elevation=0 * u.deg)
    dh = (step * 1.00273781191135 * 15 * u.deg / u.hour).to(u.rad)  # hour angle of a step
    x = np.arctan(np.sin(VLA.lat) * np.tan(dh / 4))
    assert_quantity_allclose(table["range"].quantity[0], 180 * u.deg - 2 * x,
                             atol=0.002 * u.deg)
    assert table["max"][0] == pytest.approx(-table["min"][0], abs=0.01)
    # Above the horizon for 2 acos(-tan(phi) tan(delta)) of hour angle (no refraction).
    hours = 2 * np.degrees(np.arccos(-np.tan(VLA.lat.rad) ** 2)) / (15 * 1.00273781191135)
    assert table["hours"].quantity[0].to_value(u.hour) == pytest.approx(hours, abs=2 / 60)
    assert table["epochs"][0] == round(table["hours"][0] * 60)


def test_a_source_near_the_pole():
    # Eq 17: an equatorial mount has no feed rotation, whatever the source. For an alt-az
    # mount, the direction from a source 3.7 deg from the pole to the pole turns once a
    # sidereal day, while the direction to the zenith (56 deg from the pole) swings by
    # asin(sin 3.7 deg / sin 56 deg) = 4.5 deg at most: the parallactic angle winds by
    # 360 deg a sidereal day, 363.5 deg over 145 epochs 10 min apart.
    antennas = [Antenna(VLA, EquatorialMount(), name="EQ"), Antenna(VLA, AltAzMount(), name="AZ")]
    table = feed_rotation_coverage(antennas, {"NEARPOLE": SOURCES["NEARPOLE"]}, DAY,
                                   DAY + 1 * u.day, 10 * u.min)
    assert table["range"][0] == pytest.approx(0, abs=1e-9)
    assert list(table["epochs"]) == [145, 145]
    turned = 24 * u.hour * 1.00273781191135 * 15 * u.deg / u.hour
    assert table["range"][1] == pytest.approx(turned.to_value(u.deg), abs=2 * 4.5)


def test_the_range_agrees_with_erfa_hd2pa():
    # An ordinary source over one pass, against ERFA's parallactic angle of astropy's HADec
    # and astropy's AltAz elevation, unwrapped by numpy (independent of the package).
    antenna = get_antenna("WETTZ13S")
    start, stop, step = Time("2023-01-25T14:00"), Time("2023-01-26T06:00"), 5 * u.min
    table = feed_rotation_coverage([antenna], {"3C84": SOURCES["3C84"]}, start, stop, step)
    times = start + np.arange(int(16 * 12) + 1) * step
    hadec = SOURCES["3C84"].transform_to(HADec(obstime=times, location=antenna.location))
    altaz = SOURCES["3C84"].transform_to(AltAz(obstime=times, location=antenna.location))
    above = altaz.alt >= 10 * u.deg
    runs = np.flatnonzero(np.diff(above.astype(int)))
    assert len(runs) <= 2  # one pass in the span
    pa = erfa.hd2pa(hadec.ha.rad, hadec.dec.rad, antenna.location.lat.rad)
    continuous = np.degrees(np.unwrap(pa[above]))
    assert table["epochs"][0] == above.sum()
    assert table["range"][0] == pytest.approx(continuous.max() - continuous.min(), abs=1e-5)
    assert table["min"][0] == pytest.approx(continuous.min(), abs=1e-5)


def test_targets_in_every_form_and_a_sky_rotator():
    site = get_antenna("WETTZ13S").location
    antennas = [get_antenna("WETTZ13S"),
                Antenna(site, AltAzMount(), rotator=Rotator("sky"), name="SKY")]
    pick = {name: SOURCES[name] for name in ("3C84", "3C286")}
    args = (DAY, DAY + 12 * u.hour, 20 * u.min)
    by_dict = feed_rotation_coverage(antennas, pick, *args)
    by_pairs = feed_rotation_coverage(antennas, list(pick.items()), *args)
    by_coord = feed_rotation_coverage(antennas, SkyCoord(list(pick.values())), *args,
                                      names=list(pick))
    for table in (by_pairs, by_coord):
        assert np.allclose(table["range"], by_dict["range"], rtol=0, atol=1e-9)
        assert list(table["target"]) == list(by_dict["target"])
    assert list(by_dict["antenna"]) == ["WETTZ13S", "WETTZ13S", "SKY", "SKY"]
    # A feed that tracks the sky keeps one angle: no range.
    assert np.all(np.abs(by_dict["range"][2:]) < 1e-9)
    unnamed = feed_rotation_coverage(antennas[:1], SkyCoord(list(pick.values())), *args)
    assert unnamed["target"][0].startswith("03h19m48.2s")


def test_ranking_by_the_worst_station():
    antennas = [get_antenna("WETTZ13S"), get_antenna("GGAO12M")]
    table = feed_rotation_coverage(antennas, SOURCES, DAY, DAY + 1 * u.day, 10 * u.min)
    south = table[table["target"] == "SOUTH"]
    assert np.all(np.isnan(south["range"])) and np.all(south["hours"] == 0)
    assert np.all(south["epochs"] == 0)
    ranked = rank_sources(table)
    worst = {name: np.min(table["range"][table["target"] == name]) for name in SOURCES}
    # Descending worst range; a source never seen comes last; the near-pole source winds
    # once a day everywhere (see test_a_source_near_the_pole) and comes first.
    assert list(ranked["target"]) == sorted(["3C84", "3C286", "NEARPOLE"],
                                            key=lambda n: -worst[n]) + ["SOUTH"]
    assert list(ranked["target"]) == ["NEARPOLE", "3C84", "3C286", "SOUTH"]
    assert list(ranked["rank"]) == [1, 2, 3, 4]
    assert list(ranked["stations_above"]) == [2, 2, 2, 0]
    for row in ranked[:3]:
        assert row["worst_range"] == pytest.approx(worst[row["target"]])
        mine = table[table["target"] == row["target"]]
        assert row["worst_antenna"] == mine["antenna"][np.argmin(mine["range"])]


@pytest.mark.parametrize("targets, kwargs, error, match", [
    ({"SOUTH": SOURCES["SOUTH"]}, {}, ValueError,
     r"no antenna sees any target above 10.0 deg from .* lower min_elevation"),
    ({}, {}, ValueError, "targets is empty; give at least one source"),
    ([], {}, ValueError, "targets is empty"),
    ("3C84", {}, TypeError, r"got the str '3C84'; names are not looked up \(no network\)"),
    ({"3C84": "03h19m48s +41d30m"}, {}, TypeError, r"target '3C84' must be a SkyCoord, got str"),
    ([("3C84", SOURCES["3C84"], 1)], {}, TypeError, r"sequence of \(name, SkyCoord\) pairs"),
    (5, {}, TypeError, r"targets must be a SkyCoord, a dict .* got int"),
    ([("A", SOURCES["3C84"]), ("A", SOURCES["3C286"])], {}, ValueError,
     "target names must differ; repeated: A"),
    ({"3C84": SOURCES["3C84"]}, {"step": 0 * u.min}, ValueError,
     "step must be one positive finite time, got 0.0 min"),
    ({"3C84": SOURCES["3C84"]}, {"step": -5 * u.min}, ValueError, "step must be one positive"),
    ({"3C84": SOURCES["3C84"]}, {"step": 10}, TypeError, r"step must be a time Quantity"),
    ({"3C84": SOURCES["3C84"]}, {"step": 10 * u.deg}, u.UnitsError,
     "step must be a time .* got a quantity in deg"),
    ({"3C84": SOURCES["3C84"]}, {"stop": DAY}, ValueError,
     r"stop \(2024-03-01T00:00:00.000\) must be after start"),
    ({"3C84": SOURCES["3C84"]}, {"stop": DAY - 1 * u.hour}, ValueError, "must be after start"),
    ({"3C84": SOURCES["3C84"]}, {"min_elevation": 10}, TypeError, "min_elevation"),
    ({"3C84": SOURCES["3C84"]}, {"names": ["x"]}, ValueError, "names goes with a SkyCoord"),
    (SkyCoord([SOURCES["3C84"], SOURCES["3C286"]]), {"names": ["x"]}, ValueError,
     "names holds 1 names for 2 targets"),
])
def test_bad_input(targets, kwargs, error, match):
    arguments = dict(start=DAY, stop=DAY + 12 * u.hour, step=30 * u.min)
    arguments.update(kwargs)
    with pytest.raises(error, match=match):
        feed_rotation_coverage([get_antenna("WETTZ13S")], targets, **arguments)


def test_bad_antennas_and_tables():
    with pytest.raises(TypeError, match="antennas"):
        feed_rotation_coverage(["WETTZ13S"], SOURCES, DAY, DAY + 1 * u.hour, 10 * u.min)
    with pytest.raises(TypeError, match="table must be an astropy Table from "
                                        "feed_rotation_coverage, got dict"):
        rank_sources({})
    with pytest.raises(ValueError, match="table is not from feed_rotation_coverage: it lacks "
                                         "range, epochs"):
        rank_sources(Table({"antenna": ["A"], "target": ["B"]}))
