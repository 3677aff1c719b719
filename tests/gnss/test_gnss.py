# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""RINEX observation files in and out, and the wind-up correction of their carrier phases."""

import gzip
import os

import gnss_reference as ref
import numpy as np
import pytest
from astropy import units as u
from astropy.time import Time

from astropy_feedrot import OrbitWarning
from astropy_feedrot.gnss import (
    RinexReader,
    RinexWriter,
    correct_rinex,
    read_rinex_header,
    receiver_axes,
)
from astropy_feedrot.gnss.synthetic import constellation, write_rinex, write_sp3
from astropy_feedrot.io import FileFormatError
from astropy_feedrot.transmitters.orbits import Orbit

START = Time("2023-01-25T00:00:19", scale="tai")  # 00:00 GPS time
GGAO = np.array([1130730.179, -4831245.954, 3994228.241])  # the paper's Table 3
TYPES = {"G": ("C1C", "L1C", "L2W", "S1C"), "E": ("C1C", "L1C", "L5Q", "S1C"),
         "R": ("C1C", "L1C", "S1C"), "C": ("C2I", "L2I", "L7I")}
TYPES_2 = {"*": ("C1", "L1", "L2", "P2", "S1", "S2", "L5")}  # two lines per satellite
COUNTS = {"G": 5, "E": 4, "R": 4}


@pytest.fixture(scope="module")
def orbits():
    return constellation(START, COUNTS)


@pytest.fixture(scope="module")
def sp3(tmp_path_factory, orbits):
    path = tmp_path_factory.mktemp("sp3") / "sim.sp3"
    write_sp3(path, orbits, START, 17)  # four hours at 15 min
    return path


def _rinex(path, version="3.04", epochs=60, **kwargs):
    types = TYPES_2 if version.startswith("2") else TYPES
    sats = kwargs.pop("sats", list(constellation(START, COUNTS)))
    write_rinex(path, version, types, sats, kwargs.pop("start", START + 3600 * u.s), epochs,
                30.0, **kwargs)
    return path


def _phases(path):
    """{(epoch index, prn): [L values]} and the record lines, read back."""
    values = {}
    with RinexReader(path) as reader:
        header = reader.header
        t = -1
        for record in reader:
            if not record.observations:
                continue
            t += 1
            for i, sat in enumerate(record.satellites):
                values[t, sat] = [record.value(i, line, col)
                                  for line, col, _ in header.phase_fields(sat[0])]
    return values


def _without_phases(path):
    """Every line of a file with its carrier-phase values blanked (flags kept)."""
    with RinexReader(path) as reader:
        header = reader.header
        lines = list(header.lines)
        for record in reader:
            if record.observations:
                for i, sat in enumerate(record.satellites):
                    for line, col, _ in header.phase_fields(sat[0]):
                        if record.value(i, line, col) is not None:
                            record.set_value(i, line, col, 0.0)
            lines += record.lines
    return lines


# -- reading and writing -----------------------------------------------------------------


@pytest.mark.parametrize("version", ["2.11", "3.04", "4.01"])
def test_headers(tmp_path, version):
    path = _rinex(tmp_path / "a.rnx", version, epochs=2, zero_direction=12.5)
    header = read_rinex_header(path)
    assert header.version == version
    assert header.major == int(version[0])
    np.testing.assert_allclose(header.position, GGAO)  # as written
    assert header.zero_direction == 12.5
    assert header.interval == 30.0
    assert header.time_system == "GPS"
    assert header.first_obs == (2023, 1, 25, 1, 0, 0.0)
    if version == "2.11":
        assert header.obs_types["G"] == TYPES_2["*"] == header.obs_types["R"]
        assert header.record_lines("G") == 2
        assert header.phase_fields("G") == [(0, 16, "L1"), (0, 32, "L2"), (1, 16, "L5")]
    else:
        assert header.obs_types == {k: TYPES[k] for k in "GER"}
        assert header.phase_fields("R") == [(0, 19, "L1C")]


@pytest.mark.parametrize("version", ["2.11", "3.04", "4.01"])
@pytest.mark.parametrize("suffix", [".rnx", ".rnx.gz"])
def test_round_trip_keeps_every_byte(tmp_path, version, suffix):
    sats = list(constellation(START, {"G": 8, "R": 4, "E": 2}))  # 14: two PRN lines in 2.11
    source = _rinex(tmp_path / "a.rnx", version, epochs=5, sats=sats, lli={(2, "G03"): 1},
                    events={3: ["RECEIVER RESET"]}, missing={(1, "E02")})
    target = tmp_path / f"b{suffix}"
    with RinexReader(source) as reader, RinexWriter(target) as writer:
        writer.write_header(reader.header, "a comment")
        for record in reader:
            writer.write_record(record)
    opener = gzip.open if suffix.endswith(".gz") else open
    with open(source, "rb") as fh:
        original = fh.read().splitlines(keepends=True)
    with opener(target, "rb") as fh:
        written = fh.read().splitlines(keepends=True)
    end = next(i for i, line in enumerate(original) if b"END OF HEADER" in line)
    assert written[end] == b"a comment".ljust(60) + b"COMMENT".ljust(20) + b"\n"  # 80 columns
    assert written[:end] + written[end + 1:] == original


def test_crlf_and_event_records_kept(tmp_path):
    source = _rinex(tmp_path / "a.rnx", epochs=3, events={1: ["ANTENNA CHANGED"]})
    text = source.read_bytes().replace(b"\n", b"\r\n")
    source.write_bytes(text)
    target = tmp_path / "b.rnx"
    with RinexReader(source) as reader, RinexWriter(target) as writer:
        writer.write_header(reader.header)
        records = list(reader)
        for record in records:
            writer.write_record(record)
    assert target.read_bytes() == text
    assert [r.flag for r in records] == [0, 4, 0, 0]


def test_hatanaka_input(tmp_path):
    hatanaka = pytest.importorskip("hatanaka")
    source = _rinex(tmp_path / "a.rnx", epochs=20, lli={(5, "G01"): 1})
    compact = tmp_path / "a.crx"
    compact.write_bytes(hatanaka.rnx2crx(source.read_bytes()))
    assert _phases(compact) == _phases(source)
    zipped = tmp_path / "a.crx.gz"
    zipped.write_bytes(gzip.compress(compact.read_bytes()))
    with RinexReader(zipped) as reader:
        lines = list(reader.header.lines) + [line for record in reader for line in record.lines]
    assert "".join(lines).encode("latin-1") == source.read_bytes()


# -- the correction ------------------------------------------------------------------------


def _reference(orbits, times, zero_direction=0.0):
    """Wu's wind-up (cycles, wrapped) from the independent implementation, (T, S)."""
    names = list(orbits)
    position = Orbit.positions([orbits[n] for n in names], times)
    sun = ref.sun_itrs(times)
    x_s, y_s = ref.nominal_axes(position, sun[np.newaxis])
    x_r, y_r = ref.receiver_dipoles(GGAO, zero_direction)
    return names, ref.wu_windup(GGAO, position, x_s, y_s, x_r, y_r).T / (2 * np.pi)


@pytest.mark.parametrize("version", ["2.11", "3.04", "4.01"])
def test_correction_against_independent_wu(tmp_path, sp3, version):
    orbits = constellation(START, COUNTS)  # GPS, Galileo and GLONASS
    source = _rinex(tmp_path / "a.rnx", version, epochs=120, zero_direction=30.0)
    report = correct_rinex(source, tmp_path / "b.rnx", sp3, form="wu")
    assert report.epochs == 120 and report.arcs == len(orbits)
    before, after = _phases(source), _phases(tmp_path / "b.rnx")
    times = START + 3600 * u.s + np.arange(120) * 30 * u.s
    names, expected = _reference(orbits, times, zero_direction=30.0)
    removed = np.array([[before[t, s][0] - after[t, s][0] for s in names] for t in range(120)])
    # Every frequency loses the same number of cycles.
    for (t, s), values in before.items():
        np.testing.assert_allclose(np.subtract(values, after[t, s]), removed[t, names.index(s)],
                                   atol=1.5e-3)
    # The removed wind-up is Wu's (same dipoles) up to the F14.3 rounding and the
    # SP3 interpolation of the orbits (10-point Lagrange at 15 min: far below).
    difference = (removed - expected + 0.5) % 1 - 0.5
    assert np.max(np.abs(difference)) < 1.1e-3  # cycles
    # Each arc starts at the principal value and stays continuous (Eq 9).
    assert np.all(np.abs(removed[0]) <= 0.5 + 1e-3)
    assert np.max(np.abs(np.diff(removed, axis=0))) < 0.25


def test_beyerle_form_within_hundredth_of_a_degree(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=40)
    correct_rinex(source, tmp_path / "wu.rnx", sp3, form="wu")
    correct_rinex(source, tmp_path / "beyerle.rnx", sp3)
    wu, beyerle = _phases(tmp_path / "wu.rnx"), _phases(tmp_path / "beyerle.rnx")
    difference = np.concatenate([np.subtract(wu[k], beyerle[k]) for k in wu])
    assert np.max(np.abs(difference)) <= 0.001 + 0.01 / 360 + 1e-9  # rounding + 0.01 deg


def test_only_phases_change(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=30, lli={(4, "G02"): 1},
                    events={6: ["ANTENNA CHANGED"]}, missing={(3, "R01")})
    report = correct_rinex(source, tmp_path / "b.rnx", sp3)
    original, corrected = _without_phases(source), _without_phases(tmp_path / "b.rnx")
    end = next(i for i, line in enumerate(original) if "END OF HEADER" in line)
    # Two COMMENT lines, 80 columns, saying what was done.
    assert corrected[end:end + 2] == [
        "astropy_feedrot: L - WIND-UP (CYCLES, RHCP, NOMINAL YAW)    COMMENT             \n",
        "WIND-UP REMOVED FROM 659 PHASES OF 13 SATELLITES            COMMENT             \n"]
    assert corrected[:end] + corrected[end + 2:] == original
    assert report.phases == 30 * (5 * 2 + 4 * 2 + 4 * 1) - 1  # R01 missing once


def test_loss_of_lock_keeps_the_arc(tmp_path, sp3):
    """A loss-of-lock flag does not restart the wind-up (it used to).

    The wind-up is geometry, not a measurement: RTKLIB carries its phw through
    every flag (windupcorr, rtkcmn.c). Restarting at the principal value put a
    whole-cycle step into the satellite's unflagged phases whenever the
    accumulated wind-up had drifted past half a cycle.
    """
    flagged = _rinex(tmp_path / "a.rnx", epochs=240, lli={(120, "G02", "L2W"): 1})
    report = correct_rinex(flagged, tmp_path / "b.rnx", sp3)
    plain = _rinex(tmp_path / "c.rnx", epochs=240)
    continuous = correct_rinex(plain, tmp_path / "d.rnx", sp3)
    assert report.arcs == continuous.arcs == 13
    before, after = _phases(flagged), _phases(tmp_path / "b.rnx")
    removed = np.array([[b - a for b, a in zip(before[t, "G02"], after[t, "G02"])]
                        for t in range(240)])
    # The same value from both phases (L1C unflagged, L2W flagged) at every epoch ...
    np.testing.assert_allclose(removed[:, 0], removed[:, 1], atol=1.5e-3)  # F14.3 rounding
    # ... and the same as without the flag: no step anywhere.
    plain_before, plain_after = _phases(plain), _phases(tmp_path / "d.rnx")
    removed_plain = np.array([plain_before[t, "G02"][0] - plain_after[t, "G02"][0]
                              for t in range(240)])
    np.testing.assert_allclose(removed[:, 0], removed_plain, atol=1e-9)
    assert np.all(np.abs(np.diff(removed[:, 0])) < 0.25)


def test_flagged_epoch_past_half_a_cycle(tmp_path, sp3):
    """The flagged-epoch geometry of ESBC R04, reproduced with the synthetic orbits.

    The wind-up of one satellite is followed past +0.5 cycle (or -0.5) and one
    of its phases is flagged there: every phase of the satellite keeps the
    continuous value (RTKLIB's behaviour), none gets a one-cycle step.
    """
    plain = _rinex(tmp_path / "plain.rnx", epochs=420, start=START + 1800 * u.s)
    report = correct_rinex(plain, tmp_path / "plain_out.rnx", sp3, table=True)
    rows = report.windup
    # The satellite and epoch where the continuous wind-up is furthest past half a cycle.
    prn, k = max(((p, int(np.argmax(np.abs(rows["windup"][rows["prn"] == p].value))))
                  for p in sorted(set(rows["prn"]))),
                 key=lambda pk: np.abs(rows["windup"][rows["prn"] == pk[0]].value[pk[1]]))
    series = rows["windup"][rows["prn"] == prn].value
    assert abs(series[k]) > 0.5  # past the principal value: a restart would step here
    code = TYPES[prn[0]][2] if prn[0] in "GE" else TYPES[prn[0]][1]
    flagged = _rinex(tmp_path / "flagged.rnx", epochs=420, start=START + 1800 * u.s,
                     lli={(k, prn, code): 1})
    again = correct_rinex(flagged, tmp_path / "flagged_out.rnx", sp3, table=True)
    np.testing.assert_array_equal(again.windup["windup"], rows["windup"])
    assert again.arcs == report.arcs


def test_gap_starts_a_new_arc(tmp_path, sp3):
    missing = {(t, "E01") for t in range(50, 70)}  # 10 minutes without E01
    source = _rinex(tmp_path / "a.rnx", epochs=100, missing=missing)
    assert correct_rinex(source, tmp_path / "b.rnx", sp3).arcs == 13 + 1
    assert correct_rinex(source, tmp_path / "c.rnx", sp3, max_gap=1 * u.h).arcs == 13


@pytest.mark.parametrize("missing, arcs", [(0, 13), (1, 13 + 1), (2, 13 + 1)])
def test_max_gap_of_one_interval(tmp_path, sp3, missing, arcs):
    """--max-gap equal to the sampling interval: consecutive epochs never start an arc.

    Epoch times carry rounding (30 s steps read as 29.999999 or 30.000001 s);
    the gap is compared with max_gap plus half the interval, so a step of one
    interval is always within it and one missing epoch (60 s) never is.
    """
    gone = {(t, "G03") for t in range(100, 100 + missing)}
    source = _rinex(tmp_path / "a.rnx", epochs=200, missing=gone)
    report = correct_rinex(source, tmp_path / "b.rnx", sp3, max_gap=30 * u.s)
    assert report.arcs == arcs


def test_sp3_day_boundary_and_blocks(tmp_path, orbits, sp3, monkeypatch):
    """Two SP3 files split at 02:00 give what one file gives, across blocks of epochs."""
    first, second = tmp_path / "day1.sp3", tmp_path / "day2.sp3"
    write_sp3(first, orbits, START, 9)  # 00:00 to 02:00
    write_sp3(second, orbits, START + 9 * 900 * u.s, 8)  # 02:15 to 04:00
    source = _rinex(tmp_path / "a.rnx", epochs=240, start=START + 5400 * u.s)  # 01:30-03:30
    one = correct_rinex(source, tmp_path / "one.rnx", sp3)
    monkeypatch.setattr("astropy_feedrot.gnss.correct.BLOCK_EPOCHS", 7)
    two = correct_rinex(source, tmp_path / "two.rnx", [second, first])
    assert one.arcs == two.arcs == 13
    assert (tmp_path / "one.rnx").read_bytes() == (tmp_path / "two.rnx").read_bytes()


def test_zero_direction_turns_the_receiver():
    # Independent: the rotated east and north of gnss_reference.
    axes = receiver_axes(GGAO, 30.0)
    east, north = ref.receiver_dipoles(GGAO, 30.0)
    np.testing.assert_allclose(axes[0], east, atol=1e-12)
    np.testing.assert_allclose(axes[1], north, atol=1e-12)


def test_orbex_attitude(tmp_path):
    from astropy_feedrot.data import sample_file

    named = constellation(START, {"G": 5, "E": 11})  # G01, G05, E11 of sample.obx among them
    path = tmp_path / "sim.sp3"
    write_sp3(path, {p: named[p] for p in ("G01", "G05", "E11")}, START - 3600 * u.s, 12)
    source = _rinex(tmp_path / "a.rnx", epochs=4, sats=["G01", "G05", "E11"], start=START)
    with pytest.warns(OrbitWarning, match=r"^phases left untouched: E11: 1 epochs in holes of "
                                          r"the orbit, outside the attitude"):
        report = correct_rinex(source, tmp_path / "b.rnx", path,
                               orbex=sample_file("sample.obx"))
    # sample.obx covers 00:00 to 00:01: the fourth epoch (00:01:30) is outside it.
    assert report.phases == 3 * 3 * 2
    assert set(report.untouched) == {"E11", "G01", "G05"}


def test_points_refused_before_any_work(tmp_path, sp3):
    """Too few interpolation points for the orbit's sampling are refused."""
    from astropy_feedrot.data import sample_file

    source = _rinex(tmp_path / "a.rnx", epochs=3, sats=["G01", "G05"], start=START)
    for points in (1, 2, 6):
        with pytest.raises(ValueError, match=rf"points={points} is too few for SP3 orbits at "
                                             r"900 s: interpolating them within 1e-4 cycle of "
                                             r"wind-up needs at least 7 points"):
            correct_rinex(source, tmp_path / "b.rnx", sp3, points=points)
    with pytest.raises(ValueError, match=r"points=30 exceeds the 17 epochs of the SP3 files"):
        correct_rinex(source, tmp_path / "b.rnx", sp3, points=30)
    with pytest.raises(TypeError, match=r"points must be a whole number of epochs \(int\)"):
        correct_rinex(source, tmp_path / "b.rnx", sp3, points=7.5)
    # The shipped four-epoch sample cannot be interpolated well at 15 minutes.
    with pytest.raises(ValueError, match=r"the SP3 files have 4 epochs at 900 s; interpolating "
                                         r"their orbits within 1e-4 cycle of wind-up needs 7 "
                                         r"points: give SP3 files of a longer span"):
        correct_rinex(source, tmp_path / "b.rnx", sample_file("sample.sp3"))
    assert not (tmp_path / "b.rnx").exists()


# -- bad input ---------------------------------------------------------------------------


def test_cut_short(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=10)
    lines = source.read_text().splitlines(keepends=True)
    source.write_text("".join(lines[:-3]))
    with pytest.raises(FileFormatError, match=r"line \d+: expected 13 satellites announced .* "
                                              r"\(the file is cut short\), got end of file"):
        correct_rinex(source, tmp_path / "b.rnx", sp3)
    assert sorted(os.listdir(tmp_path)) == ["a.rnx"]


def test_header_cut_short(tmp_path):
    source = _rinex(tmp_path / "a.rnx", epochs=1)
    source.write_text("".join(source.read_text().splitlines(keepends=True)[:5]))
    with pytest.raises(FileFormatError, match="expected 'END OF HEADER' .*cut short"):
        read_rinex_header(source)


@pytest.mark.parametrize("first, match", [
    ("     5.00           OBSERVATION DATA    G", "a version .* of 2.10, 2.11"),
    ("     3.04           NAVIGATION DATA     G", "an observation file"),
    ("     3.04           OBSERVATION DATA    G       SOMETHING ELSE", "RINEX VERSION / TYPE"),
])
def test_wrong_version_line(tmp_path, first, match):
    source = _rinex(tmp_path / "a.rnx", epochs=1)
    lines = source.read_text().splitlines(keepends=True)
    label = "RINEX VERSION / TYPE" if "ELSE" not in first else "RINEX VERSION/TYPE"
    lines[0] = f"{first:<60}{label}\n" if "ELSE" not in first else f"{first[:60]}{label}\n"
    source.write_text("".join(lines))
    with pytest.raises(FileFormatError, match=match):
        read_rinex_header(source)


def test_undeclared_system(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=2)
    text = source.read_text().replace("R01  ", "C01  ", 1)
    source.write_text(text)
    with pytest.raises(FileFormatError, match=r"a satellite of a system whose observation "
                                              r"types the header declares \(G, E, R\), got 'C01"):
        correct_rinex(source, tmp_path / "b.rnx", sp3)


def test_more_observations_than_declared(tmp_path):
    source = _rinex(tmp_path / "a.rnx", epochs=2)
    lines = source.read_text().splitlines(keepends=True)
    k = next(i for i, line in enumerate(lines) if line.startswith("R02"))
    lines[k] = lines[k].rstrip("\n") + "  20000000.000 7\n"
    source.write_text("".join(lines))
    with RinexReader(source) as reader:
        with pytest.raises(FileFormatError, match=r"at most 3 observations of R02 \(the types "
                                                  r"the header declares for system R: C1C L1C S1C"):
            list(reader)


def test_sp3_not_covering(tmp_path, sp3):
    """Epochs beyond the SP3 files: extrapolated up to one interval, untouched beyond.

    RTKLIB extrapolates precise orbits up to 900 s (MAXDTE, pephpos); further
    out the epochs are left as read and counted, never the whole file refused.
    """
    source = _rinex(tmp_path / "a.rnx", epochs=62, start=START + 3.75 * u.h)  # 03:45-04:15:30
    with pytest.warns(OrbitWarning) as caught:
        report = correct_rinex(source, tmp_path / "b.rnx", sp3)
    messages = [str(w.message) for w in caught]
    assert len(messages) == 2
    assert messages[0] == (
        "30 epochs (2023-01-25T04:00:49.000 to 2023-01-25T04:15:19.000 TAI) lie up to 900 s "
        "(one SP3 interval) outside the SP3 files (2023-01-25T00:00:19.000 to "
        "2023-01-25T04:00:19.000): their orbits are extrapolated, as RTKLIB does; give "
        "*_20230250000_01D_*_ORB.SP3 to interpolate them")
    assert messages[1].startswith(
        "1 epochs (2023-01-25T04:15:49.000 to 2023-01-25T04:15:49.000 TAI) lie more than 900 s "
        "outside the SP3 files")
    assert messages[1].endswith("their phases are left untouched; give "
                                "*_20230250000_01D_*_ORB.SP3")
    assert report.untouched_epochs == 1 and report.extrapolated_epochs == 30
    before, after = _phases(source), _phases(tmp_path / "b.rnx")
    assert all(before[61, s] == after[61, s] for s in constellation(START, COUNTS))
    assert all(before[60, s] != after[60, s] for s in constellation(START, COUNTS))
    # The extrapolated wind-up against the same orbits in a longer file (interpolated).
    longer = tmp_path / "longer.sp3"
    write_sp3(longer, constellation(START, COUNTS), START, 19)
    correct_rinex(source, tmp_path / "c.rnx", longer)
    reference = _phases(tmp_path / "c.rnx")
    diff = np.concatenate([np.subtract(after[t, s], reference[t, s]) for t in range(31, 61)
                           for s in constellation(START, COUNTS)])
    assert np.max(np.abs(diff)) <= 2e-3  # F14.3 rounding of the two files
    # A file wholly outside: every epoch untouched, the file still written.
    late = _rinex(tmp_path / "late.rnx", epochs=10, start=START + 5 * u.h)
    with pytest.warns(OrbitWarning, match=r"^10 epochs \(2023-01-25T05:00:19.000 to "
                                          r"2023-01-25T05:04:49.000 TAI\) lie more than 900 s"):
        report = correct_rinex(late, tmp_path / "d.rnx", sp3)
    assert report.phases == 0 and report.untouched_epochs == 10
    assert "NO PHASE CORRECTED" in (tmp_path / "d.rnx").read_text()


def test_next_day_file_named(tmp_path, orbits):
    """A full day at 15 minutes ends at 23:45: the message names the next day's product."""
    day = tmp_path / "GRG0MGXFIN_20230250000_01D_15M_ORB.SP3"
    write_sp3(day, orbits, START + 20 * u.h, 16)  # 20:00 to 23:45 GPS
    source = _rinex(tmp_path / "a.rnx", epochs=40, start=START + 23.7 * u.h)  # to 00:01:30
    with pytest.warns(OrbitWarning) as caught:
        report = correct_rinex(source, tmp_path / "b.rnx", day)
    assert [str(w.message).rsplit(" give ", 1)[1] for w in caught] == [
        "GRG0MGXFIN_20230260000_01D_15M_ORB.SP3 to interpolate them",
        "GRG0MGXFIN_20230260000_01D_15M_ORB.SP3"]
    assert report.untouched_epochs == 3 and report.extrapolated_epochs == 30


def test_prn_absent_from_orbit(tmp_path, sp3):
    sats = ["G01", "G07", "E01", "C03"]
    source = _rinex(tmp_path / "a.rnx", epochs=4, sats=sats)
    with pytest.warns(OrbitWarning, match=r"^phases left untouched: C03: not in the SP3 "
                                          r"files; G07: not in the SP3 files$"):
        report = correct_rinex(source, tmp_path / "b.rnx", sp3)
    assert set(report.untouched) == {"G07", "C03"}
    before, after = _phases(source), _phases(tmp_path / "b.rnx")
    assert all(before[t, s] == after[t, s] for t in range(4) for s in ("G07", "C03"))
    assert all(before[t, "G01"] != after[t, "G01"] for t in range(4))


def test_output_is_input(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=2)
    text = source.read_bytes()
    with pytest.raises(ValueError, match="output .*a.rnx' is the input file, which is never "
                                         "overwritten; choose another name"):
        correct_rinex(source, tmp_path / "." / "a.rnx", sp3)
    assert source.read_bytes() == text


def test_output_exists(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=2)
    (tmp_path / "b.rnx").write_text("keep")
    with pytest.raises(FileExistsError, match="exists; pass overwrite=True"):
        correct_rinex(source, tmp_path / "b.rnx", sp3)
    assert (tmp_path / "b.rnx").read_text() == "keep"
    correct_rinex(source, tmp_path / "b.rnx", sp3, overwrite=True)
    assert (tmp_path / "b.rnx").read_text() != "keep"


def test_bad_options(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=2)
    with pytest.raises(ValueError, match=r"attitude must be one of \('nominal', 'model', "
                                         r"'orbex'\), got 'kouba'"):
        correct_rinex(source, tmp_path / "b.rnx", sp3, attitude="kouba")
    with pytest.raises(ValueError, match="attitude='orbex' needs the ORBEX files"):
        correct_rinex(source, tmp_path / "b.rnx", sp3, attitude="orbex")
    with pytest.raises(ValueError, match="form must be one of"):
        correct_rinex(source, tmp_path / "b.rnx", sp3, form="kouba")


def test_no_position(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=2, position=(0.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="the header gives no APPROX POSITION XYZ; pass"):
        correct_rinex(source, tmp_path / "b.rnx", sp3)
    correct_rinex(source, tmp_path / "b.rnx", sp3, position=GGAO)


def test_model_attitude(tmp_path, sp3, orbits):
    # PRNs of 2023-01-25 in the IGS metadata: G05 GPS-IIR-M, G01 GPS-IIF... the synthetic
    # orbits carry them; C59 (BeiDou-3 GEO) has no model and is left untouched.
    from astropy_feedrot.gnss.synthetic import constellation as make
    from astropy_feedrot.transmitters.attitude_interface import sun_position
    from astropy_feedrot.transmitters.yaw_models import orbit_angles

    named = make(START, {"G": 5, "E": 4, "R": 4, "C": 1})
    named["C59"] = named.pop("C01")
    path = tmp_path / "named.sp3"
    write_sp3(path, named, START, 17)
    source = _rinex(tmp_path / "a.rnx", epochs=120, sats=list(named))
    # Satellites without a yaw law get nominal yaw, named in one warning.
    with pytest.warns(OrbitWarning, match=r"^no yaw model for C59 \(block BDS-3G\): nominal "
                                          r"yaw used for them$"):
        report = correct_rinex(source, tmp_path / "model.rnx", path, attitude="model")
    assert report.untouched == {}
    correct_rinex(source, tmp_path / "nominal.rnx", path)
    model, nominal = _phases(tmp_path / "model.rnx"), _phases(tmp_path / "nominal.rnx")
    assert all(model[t, "C59"] == nominal[t, "C59"] for t in range(120))
    times = START + 3600 * u.s + np.arange(120) * 30 * u.s
    sun = sun_position(times)
    for prn, orbit in named.items():
        if prn == "C59":
            continue
        position = orbit.position(times)
        velocity = orbit.position(times + 0.5 * u.s) - orbit.position(times - 0.5 * u.s)
        beta = np.degrees(orbit_angles(position, velocity, sun)[0])
        if np.min(np.abs(beta)) > 15:  # far from any turn: the model is nominal
            assert all(model[t, prn] == nominal[t, prn] for t in range(120)), prn


def test_model_attitude_nominal_for_qzss_and_glonass_k1b(tmp_path):
    """Under attitude='model', QZSS (J01-J03) and GLONASS-K1B (R09), which have no yaw law,
    get nominal yaw and are named in one warning (they were left untouched,
    9,714 phases of the real ESBC00DNK file)."""
    from astropy_feedrot.gnss.synthetic import constellation as make

    named = make(START, {"G": 3, "R": 4})
    for old, new in (("G01", "J01"), ("G02", "J02"), ("G03", "J03"), ("R04", "R09")):
        named[new] = named.pop(old)
    path = tmp_path / "named.sp3"
    write_sp3(path, named, START, 17)
    types = {"J": ("C1C", "L1C", "L2L"), "R": ("C1C", "L1C")}
    source = tmp_path / "a.rnx"
    write_rinex(source, "3.04", types, list(named), START + 3600 * u.s, 20, 30.0)
    with pytest.warns(OrbitWarning, match=r"^no yaw model for J01 \(block QZS-1\), J02 \(block "
                                          r"QZS-2I\), J03 \(block QZS-2I\), R09 \(block "
                                          r"GLO-K1B\): nominal yaw used for them$"):
        report = correct_rinex(source, tmp_path / "model.rnx", path, attitude="model")
    assert report.untouched == {} and report.phases == 20 * (3 * 2 + 4)
    correct_rinex(source, tmp_path / "nominal.rnx", path)
    model, nominal = _phases(tmp_path / "model.rnx"), _phases(tmp_path / "nominal.rnx")
    assert all(model[t, p] == nominal[t, p] for t in range(20) for p in ("J01", "J03", "R09"))


def test_join_orbex_and_sp3(tmp_path, orbits, sp3):
    from astropy_feedrot.data import sample_file
    from astropy_feedrot.gnss import join_orbex
    from astropy_feedrot.io import read_sp3
    from astropy_feedrot.io.sp3 import join_sp3

    one = join_orbex([sample_file("sample.obx")])
    two = join_orbex([sample_file("sample.obx"), sample_file("sample.obx")])
    assert sorted(one) == sorted(two) == ["E11", "G01", "G05"]
    np.testing.assert_array_equal(one["G05"].quaternions, two["G05"].quaternions)
    text = sample_file("sample.obx").read_text()
    eci = tmp_path / "eci.obx"
    eci.write_text(text.replace("FRAME_TYPE          ECEF", "FRAME_TYPE          ECI"))
    with pytest.raises(ValueError, match=r"the ORBEX files refer to different frames \('itrs' "
                                         r"and 'gcrs'\); give files of one series"):
        join_orbex([sample_file("sample.obx"), eci])
    coarse = tmp_path / "coarse.sp3"
    write_sp3(coarse, orbits, START, 5, interval=1800.0)
    with pytest.raises(ValueError, match=r"the SP3 files differ in interval: 900.0 and 1800.0; "
                                         "join files of one product series"):
        join_sp3([sp3, coarse])
    with pytest.raises(ValueError, match="sources is empty; give at least one SP3 file"):
        join_sp3([])
    assert len(join_sp3([sp3, read_sp3(sp3)]).epochs) == 17  # the same epochs once


def test_cycle_slip_records_kept(tmp_path, sp3):
    # Epoch flag 6 announces cycle-slip records in the observation format: kept as read.
    source = _rinex(tmp_path / "a.rnx", epochs=3)
    lines = source.read_text().splitlines(keepends=True)
    k = next(i for i, line in enumerate(lines) if line.startswith(">"))
    slip = lines[k].replace("  0 13", "  6  1", 1)
    lines[k + 14:k + 14] = [slip, "G01         0.000 1        1.000 1\n"]
    source.write_text("".join(lines))
    correct_rinex(source, tmp_path / "b.rnx", sp3)
    written = (tmp_path / "b.rnx").read_text()
    assert slip + "G01         0.000 1        1.000 1\n" in written


def test_hatanaka_file_broken(tmp_path, sp3):
    hatanaka = pytest.importorskip("hatanaka")
    source = _rinex(tmp_path / "a.rnx", epochs=20)
    compact = hatanaka.rnx2crx(source.read_bytes())
    broken = tmp_path / "a.crx"
    broken.write_bytes(compact[:len(compact) // 2] + b"&garbage\n" * 5)
    with pytest.raises(FileFormatError, match="Compact RINEX"):
        correct_rinex(broken, tmp_path / "b.rnx", sp3)
    assert not (tmp_path / "b.rnx").exists()


def test_glonass_only_rinex_2_in_utc(tmp_path, sp3, orbits):
    # A GLONASS file (system R): its epochs are UTC (GLO), the SP3 file's GPS time.
    glonass = {prn: orbit for prn, orbit in orbits.items() if prn[0] == "R"}
    source = tmp_path / "r.rnx"
    start = START + 3600 * u.s
    write_rinex(source, "2.11", {"R": ("C1", "L1", "L2")}, list(glonass), start, 20)
    text = source.read_text().replace("M (MIXED)", "R (GLO)  ")
    source.write_text(text.replace("     GPS         TIME", "     GLO         TIME"))
    header = read_rinex_header(source)
    assert header.system == "R" and header.time_system == "GLO"
    report = correct_rinex(source, tmp_path / "b.rnx", sp3, form="wu")
    assert report.arcs == 4
    # Read as UTC, the epochs are 18 s later than the GPS readings: the wind-up
    # removed is Wu's at those instants.
    times = start + (np.arange(20) * 30 + 18) * u.s
    names, expected = _reference(glonass, times)
    before, after = _phases(source), _phases(tmp_path / "b.rnx")
    removed = np.array([[before[t, s][0] - after[t, s][0] for s in names] for t in range(20)])
    assert np.max(np.abs((removed - expected + 0.5) % 1 - 0.5)) < 1.1e-3


def test_blank_lines_kept(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=3)
    source.write_text(source.read_text() + "\n\n")
    report = correct_rinex(source, tmp_path / "b.rnx", sp3)
    assert report.epochs == 3
    assert (tmp_path / "b.rnx").read_text().endswith("\n\n\n")


def test_rtklib_receiver_dipoles_are_a_quarter_cycle_away(tmp_path, sp3):
    # RTKLIB's receiver dipoles are north and west (PAPER-NOTES): ours (east, north)
    # turned by a zero direction of 270 deg. In Wu's form that turns the receiver's
    # effective dipole by exactly 90 deg about the line of sight (D' = -k x D), so the
    # wind-up differs by a constant quarter cycle; RTKLIB's constant is -0.25 cycle.
    plain = _rinex(tmp_path / "a.rnx", epochs=40, zero_direction=0.0)
    turned = _rinex(tmp_path / "b.rnx", epochs=40, zero_direction=270.0)
    correct_rinex(plain, tmp_path / "a2.rnx", sp3, form="wu")
    correct_rinex(turned, tmp_path / "b2.rnx", sp3, form="wu")
    a0, a1 = _phases(plain), _phases(tmp_path / "a2.rnx")
    b0, b1 = _phases(turned), _phases(tmp_path / "b2.rnx")
    difference = np.array([(b0[k][0] - b1[k][0]) - (a0[k][0] - a1[k][0]) for k in a0])
    difference = (difference + 0.5) % 1 - 0.5
    np.testing.assert_allclose(difference, -0.25, atol=1.1e-3)
