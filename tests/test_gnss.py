# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""RINEX observation files in and out, and the wind-up correction of their carrier phases."""

import gzip
import os

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
from astropy_feedrot.orbits import Orbit

import gnss_reference as ref

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
    assert written[end] == b"a comment".ljust(60) + b"COMMENT\n"
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
    assert corrected[end].startswith("L - WIND-UP (CYCLES, RHCP, NOMINAL ATTITUDE)")
    assert corrected[:end] + corrected[end + 1:] == original
    assert report.phases == 30 * (5 * 2 + 4 * 2 + 4 * 1) - 1  # R01 missing once


def test_new_arc_at_loss_of_lock(tmp_path, sp3):
    source = _rinex(tmp_path / "a.rnx", epochs=240, lli={(120, "G02"): 1})
    report = correct_rinex(source, tmp_path / "b.rnx", sp3)
    assert report.arcs == 13 + 1
    before, after = _phases(source), _phases(tmp_path / "b.rnx")
    removed = np.array([before[t, "G02"][0] - after[t, "G02"][0] for t in range(240)])
    whole = np.rint(removed)
    # Without the flag, the arc would run on continuously (Eq 9); the flag
    # restarts it at the principal value, in [-0.5, 0.5] cycles.
    assert abs(removed[120]) <= 0.5005
    steps = np.diff(removed)
    assert np.all(np.abs(np.delete(steps, 119)) < 0.25)
    continuous = correct_rinex(_rinex(tmp_path / "c.rnx", epochs=240), tmp_path / "d.rnx", sp3)
    assert continuous.arcs == 13
    plain = _phases(tmp_path / "c.rnx")
    after_plain = _phases(tmp_path / "d.rnx")
    removed_plain = np.array([plain[t, "G02"][0] - after_plain[t, "G02"][0]
                              for t in range(240)])
    # Same wind-up modulo whole cycles: the arcs differ by an integer only.
    offset = removed[120:] - removed_plain[120:]
    np.testing.assert_allclose(offset, np.rint(offset[0]), atol=2e-3)
    np.testing.assert_allclose(removed[:120], removed_plain[:120], atol=1e-9)
    assert whole.dtype == float


def test_gap_starts_a_new_arc(tmp_path, sp3):
    missing = {(t, "E01") for t in range(50, 70)}  # 10 minutes without E01
    source = _rinex(tmp_path / "a.rnx", epochs=100, missing=missing)
    assert correct_rinex(source, tmp_path / "b.rnx", sp3).arcs == 13 + 1
    assert correct_rinex(source, tmp_path / "c.rnx", sp3, max_gap=1 * u.h).arcs == 13


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

    source = _rinex(tmp_path / "a.rnx", epochs=3, sats=["G01", "G05", "E11"], start=START)
    with pytest.warns(OrbitWarning, match=r"E11: .*holes of the orbit"):
        report = correct_rinex(source, tmp_path / "b.rnx", sample_file("sample.sp3"),
                               orbex=sample_file("sample.obx"), points=2)
    # E11 has no two consecutive valid epochs at the start of the file: untouched.
    assert report.phases == 3 * (2 + 2)
    assert report.untouched == {"E11": "3 epochs in holes of the orbit, outside the attitude "
                                       "or with degenerate geometry"}


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
    source = _rinex(tmp_path / "a.rnx", epochs=10, start=START + 5 * u.h)
    with pytest.raises(ValueError, match=r"the SP3 files cover 2023-01-25T00:00:19.000 to "
                                         r"2023-01-25T04:00:19.000 TAI, but .* has observations "
                                         r"at 2023-01-25T05:00:19.000 TAI \(line 12\); give the "
                                         r"SP3 files"):
        correct_rinex(source, tmp_path / "b.rnx", sp3)
    assert not (tmp_path / "b.rnx").exists()


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
    from astropy_feedrot.yaw_models import orbit_angles
    from astropy_feedrot.attitude import sun_position

    named = make(START, {"G": 5, "E": 4, "R": 4, "C": 1})
    named["C59"] = named.pop("C01")
    path = tmp_path / "named.sp3"
    write_sp3(path, named, START, 17)
    source = _rinex(tmp_path / "a.rnx", epochs=120, sats=list(named))
    with pytest.warns(OrbitWarning, match=r"C59: no yaw model for its block BDS-3G"):
        report = correct_rinex(source, tmp_path / "model.rnx", path, attitude="model")
    assert list(report.untouched) == ["C59"]
    correct_rinex(source, tmp_path / "nominal.rnx", path)
    model, nominal = _phases(tmp_path / "model.rnx"), _phases(tmp_path / "nominal.rnx")
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
