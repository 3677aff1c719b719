# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Arcs of the wind-up and the interpolation points an orbit's sampling needs."""

import numpy as np
import pytest
from astropy import units as u
from astropy.time import Time

from astropy_feedrot.gnss import correct_rinex
from astropy_feedrot.gnss.arcs import Arcs, orbit_file_name
from astropy_feedrot.gnss.synthetic import constellation, write_rinex, write_sp3
from astropy_feedrot.transmitters.sp3_orbit import points_needed

START = Time("2023-01-25T00:00:19", scale="tai")  # 00:00 GPS time
COUNTS = {"G": 5, "E": 4, "R": 4}
TYPES = {"G": ("C1C", "L1C"), "E": ("C1C", "L1C"), "R": ("C1C", "L1C")}


def test_arcs_across_blocks_and_rounding():
    """One satellite turning 0.3 cycle per 30 s, given in three blocks with rounded times."""
    t = np.arange(12) * 30.0 + np.array([0, 1e-6, -1e-6] * 4)
    wrapped = (0.3 * np.arange(12) + 0.5) % 1 - 0.5
    prn = np.array(["G01"] * 4, dtype=object)
    arcs = Arcs(max_gap=30.0)  # the interval from the first block's steps
    out = np.concatenate([arcs.apply(prn, t[k:k + 4], wrapped[k:k + 4]) for k in (0, 4, 8)])
    np.testing.assert_allclose(out, 0.3 * np.arange(12), atol=1e-12)
    assert arcs.arcs == 1 and arcs.interval == pytest.approx(30.0, abs=1e-5)
    # One epoch missing (60 s): more than max_gap + half the interval, a new arc.
    later = arcs.apply(np.array(["G01"], dtype=object), np.array([390.0]), np.array([0.1]))
    assert arcs.arcs == 2 and later[0] == 0.1


def test_orbit_file_name_before_the_first_day():
    assert orbit_file_name(["COD0MGXFIN_20201770000_01D_05M_ORB.SP3"],
                           Time("2020-06-24T23:55:00", scale="tai")) == \
        "COD0MGXFIN_20201760000_01D_05M_ORB.SP3"
    # Not a daily product: the pattern of any.
    assert orbit_file_name(["ESA0OPSULT_20232320600_02D_15M_ORB.SP3"],
                           Time("2023-08-21T00:00:00", scale="tai")) == \
        "*_20232330000_01D_*_ORB.SP3"


def test_points_needed_rule():
    # GPS radius at 15 and 5 minutes (the error bound of the module: r (omega h)^n max|prod|/n!)
    assert points_needed(900.0, 26.56e6) == 7 and points_needed(300.0, 26.56e6) == 5
    assert points_needed(900.0 * u.s) == 8  # the fastest GNSS radius (20,000 km)
    assert points_needed(30.0) == 3
    # More points for finer tolerances, never fewer than 2.
    assert points_needed(900.0, tolerance=1e-3) > points_needed(900.0)
    assert points_needed(1.0) == 2


def test_points_needed_against_a_dense_reference(tmp_path):
    """The rule's points at 15 minutes keep the wind-up within 1e-4 cycle of orbits
    sampled every 30 s (interpolated with 10 points: exact to far below), over 4 hours of
    GPS, Galileo and GLONASS satellites.

    Measured here (max over 5460 rows): 2 points 1.0e-3 cycle, 3 points 4.3e-4, 4 points
    1.6e-5, 7 (the rule) 5e-8, 10 (the default) 2.4e-10. The rule keeps a margin of
    three points for these orbits: near noon and midnight turns of real files the
    sensitivity to a position error is higher (measured 4.6e-3 cycle for 2 points
    on a real day).
    """
    orbits = constellation(START, COUNTS)
    coarse, dense = tmp_path / "coarse.sp3", tmp_path / "dense.sp3"
    write_sp3(coarse, orbits, START, 17)  # 15 minutes
    write_sp3(dense, orbits, START, 481, interval=30.0)
    obs = tmp_path / "obs.rnx"
    write_rinex(obs, "3.04", TYPES, list(orbits), START + 600 * u.s, 420, 30.0)
    rule = points_needed(900.0, 25.5e6)  # GLONASS's radius, the smallest of the three
    assert rule == 7
    reference = correct_rinex(obs, tmp_path / "ref.rnx", dense, table=True).windup
    got = correct_rinex(obs, tmp_path / "got.rnx", coarse, points=rule, table=True).windup
    error = np.abs(got["windup"] - reference["windup"]).to_value(u.cycle)
    assert np.max(error) < 1e-4
    # The measured margin: the default 10 points are 1e-6 cycle off or better.
    default = correct_rinex(obs, tmp_path / "d.rnx", coarse, table=True).windup
    assert np.max(np.abs(default["windup"] - reference["windup"]).to_value(u.cycle)) < 1e-6


def test_arcs_interval_learnt_after_a_one_epoch_block():
    arcs = Arcs(max_gap=30.0)
    prn = np.array(["G01"], dtype=object)
    arcs.apply(prn, np.array([0.0]), np.array([0.1]))  # no step to learn the interval from
    assert arcs.interval is None
    arcs.apply(np.array(["G01"] * 3, dtype=object), np.array([30.000001, 60.0, 89.999999]),
               np.array([0.1, 0.1, 0.1]))
    assert arcs.arcs == 1 and arcs.interval == pytest.approx(30.0, abs=1e-5)
