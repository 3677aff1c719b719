# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""What the file readers refuse: SP3, ORBEX and TLE files that are damaged or
ambiguous give a clear error (or NaN with one warning), never a silent number.

Explicit examples for each refusal, and property-based tests that mutate the
valid sample files (truncate, duplicate or swap blocks, inject NaN, inf or
garbage) and require either a `FileFormatError` naming the file and the line,
or the result of the unmutated file.
"""

import io
import pathlib
import re
import string
import warnings

import numpy as np
import pytest
from astropy import units as u
from astropy.time import Time
from helpers import SP3_DESCRIPTORS
from hypothesis import HealthCheck, given, settings, strategies as st

import astropy_feedrot.data
from astropy_feedrot import OrbitWarning, QuaternionAttitude, SP3Orbit, TLEOrbit
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
from astropy_feedrot.io import (
    FileFormatError,
    check_tle_line,
    check_tle_pair,
    read_orbex,
    read_sp3,
    read_tle,
)
from astropy_feedrot.transmitters.orbits import propagate_tles

SAMPLES = pathlib.Path(astropy_feedrot.data.__file__).parent
SP3_C = SAMPLES / "sample.sp3"
SP3_D = pathlib.Path(__file__).parent.parent / "data" / "sample_d.sp3"
OBX = SAMPLES / "sample.obx"

# A few examples each; the whole file runs in a few seconds.
FAST = settings(max_examples=40, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

# Tokens that are not numbers of these formats: non-finite, or garbage.
NOT_FINITE = ["nan", "NaN", "-nan", "inf", "-inf", "+inf", "Infinity", "1e999", "-1e999"]
GARBAGE = ["abc", "1.2.3", "--5.0", "5.0-", "0x1F", "1,5", "1_000.5", "12a.5", "?"]


def stream(text, name):
    """A text stream that the readers name ``name`` in their errors."""
    source = io.StringIO(text)
    source.name = name
    return source


def lines_of(path):
    return path.read_text().splitlines()


def joined(lines):
    return "\n".join(lines) + "\n"


def file_error(name):
    """The start of every FileFormatError message about the file ``name``."""
    return rf"^{re.escape(name)}, line \d+: expected "


# --- SP3 ---------------------------------------------------------------------------------


def read_sp3_text(text, name="sample.sp3"):
    return read_sp3(stream(text, name))


def same_sp3(a, b):
    assert (a.version, a.time_system, a.coordinate_system, a.satellites, a.interval,
            a.gaps) == (b.version, b.time_system, b.coordinate_system, b.satellites,
                        b.interval, b.gaps)
    assert np.all(np.abs((a.epochs - b.epochs).to_value(u.s)) < 1e-9)
    for sat in a.satellites:
        np.testing.assert_array_equal(a.positions[sat], b.positions[sat])
        np.testing.assert_array_equal(a.clock[sat], b.clock[sat])


def sp3_with(changes, path=SP3_C):
    """The sample with 1-based lines replaced (str), deleted (None) or expanded (list)."""
    lines = lines_of(path)
    for lineno in sorted(changes, reverse=True):
        new = changes[lineno]
        lines[lineno - 1:lineno] = [] if new is None else [new] if isinstance(new, str) else new
    return joined(lines)


def record(sat, x, y, z, clock):
    """A position record with fields written as given, each in its 14 columns."""
    return f"P{sat}{x:>14}{y:>14}{z:>14}{clock:>14}"


# sample.sp3: epoch lines 23 (00:00), 27 (00:15), 30 (00:30), 34 (00:45); EOF line 38.

def test_sp3_epoch_repeated():
    text = sp3_with({30: "*  2023  1 25  0 15  0.00000000"})
    with pytest.raises(FileFormatError, match=r"^sample\.sp3, line 30: expected an epoch later "
                       r"than the one on line 27 \(this one repeats it\)"):
        read_sp3_text(text)


def test_sp3_epochs_reversed():
    lines = lines_of(SP3_C)
    swapped = lines[:26] + lines[29:33] + lines[26:29] + lines[33:]  # 00:30 block before 00:15
    with pytest.raises(FileFormatError, match=r"^sample\.sp3, line 31: expected an epoch later "
                       r"than the one on line 27 \(epochs must increase; this one is earlier\)"):
        read_sp3_text(joined(swapped))


def test_sp3_epoch_off_the_interval():
    text = sp3_with({27: "*  2023  1 25  0 20  0.00000000"})
    with pytest.raises(FileFormatError, match=r"line 27: expected an epoch a whole number of "
                       r"900 s intervals \(line 2\) after the one on line 23 \(1200 s later\)"):
        read_sp3_text(text)


def test_sp3_gap_is_read_and_recorded():
    # The 00:15 epoch (lines 27-29) skipped: a gap of two intervals, allowed and recorded.
    data = read_sp3_text(sp3_with({27: None, 28: None, 29: None}))
    assert data.interval == 900.0
    assert len(data.epochs) == 3
    assert data.gaps == ((0, 1),)
    whole = read_sp3(SP3_C)
    assert whole.gaps == () and whole.interval == 900.0
    np.testing.assert_array_equal(data.positions["G01"][1:], whole.positions["G01"][2:])


def test_sp3_epoch_count_disagrees_with_line_1():
    # The last epoch cut off and EOF written after the rest: line 1 still says 4 epochs.
    # A warning, not a refusal: gnss_lib_py's trimmed test files are so, and
    # RTKLIB reads them.
    text = sp3_with({34: None, 35: None, 36: None, 37: None})
    with pytest.warns(OrbitWarning, match=r"^sample\.sp3: line 1 counts 4 epochs \(columns "
                      r"33-39\), but the file has 3 epoch lines \(a span of 3\); the epochs of "
                      r"the file are read"):
        data = read_sp3_text(text)
    assert len(data.epochs) == 3


@pytest.mark.parametrize("first, match", [
    ("#cP2023  1 25  0  0  0.00000000      x4 ORBIT IGS20 HLM  IGS",
     "the number of epochs in columns 33-39 of line 1"),
])
def test_sp3_line_1_epoch_count_unreadable(first, match):
    with pytest.raises(FileFormatError, match=r"line 1: expected " + match):
        read_sp3_text(sp3_with({1: first}))


@pytest.mark.parametrize("interval", ["   0.00000000", "  -900.0000000", "   900.0x00000",
                                      "           nan", "              "])
def test_sp3_interval_unreadable(interval):
    second = "## 2246 259200.00000000 " + f"{interval:>14}" + " 59969 0.0000000000000"
    with pytest.raises(FileFormatError, match=r"^sample\.sp3, line 2: expected the epoch "
                       r"interval in seconds, above zero, in columns 25-38 of line 2"):
        read_sp3_text(sp3_with({2: second}))


@pytest.mark.parametrize("field", range(4))
@pytest.mark.parametrize("token", NOT_FINITE)
def test_sp3_non_finite_numbers(field, token):
    values = ["5572.730146", "-25129.164480", "6550.066506", "-89.426262"]
    values[field] = token
    with pytest.raises(FileFormatError, match=r"^sample\.sp3, line 28: expected finite numbers "
                       r"in columns 5-60 \('nan' and 'inf' are not SP3 values: a bad or absent "
                       r"position is written 0\.000000, a bad or absent clock 999999\.999999\)"):
        read_sp3_text(sp3_with({28: record("G01", *values)}))


@pytest.mark.parametrize("field", range(4))
@pytest.mark.parametrize("token", GARBAGE + ["5.572730e3", "+5572.73"])
def test_sp3_numbers_that_are_not_fixed_point(field, token):
    values = ["5572.730146", "-25129.164480", "6550.066506", "-89.426262"]
    values[field] = token
    with pytest.raises(FileFormatError, match=r"^sample\.sp3, line 28: expected a position "
                       r"record 'P<sat> x y z clock' \(numbers in columns 5-60\)"):
        read_sp3_text(sp3_with({28: record("G01", *values)}))


@pytest.mark.parametrize("field", range(3))
def test_sp3_blank_coordinate(field):
    values = ["5572.730146", "-25129.164480", "6550.066506", "-89.426262"]
    values[field] = ""
    with pytest.raises(FileFormatError, match=r"line 28: expected a position record"):
        read_sp3_text(sp3_with({28: record("G01", *values)}))


def test_sp3_record_cut_inside_z():
    with pytest.raises(FileFormatError, match=r"^sample\.sp3, line 28: expected a position "
                       r"record .* x, y and z complete in columns 5-46, got 'PG01   5572"):
        read_sp3_text(sp3_with({28: "PG01   5572.730146 -25129.164480   6550.0"}))


def test_sp3_bad_or_absent_records_are_nan_never_zero():
    # Zero position (line 36), sentinel clock (line 33), no record (E11 at 00:15).
    data = read_sp3(SP3_C)
    assert np.all(np.isnan(data.positions["G05"][3]))
    assert np.isnan(data.clock["E11"][2])
    assert np.all(np.isnan(data.positions["E11"][1]))
    for sat in data.satellites:
        finite = np.isfinite(data.positions[sat])
        assert np.all(np.abs(data.positions[sat][finite]) > 0)


# --- SP3: property-based mutations of the samples ------------------------------------------


def epoch_blocks(lines, head="*", end=("EOF",)):
    """(first, stop) line indices of each epoch block: the epoch line and its records."""
    starts = [i for i, line in enumerate(lines) if line.startswith(head)]
    stop = next(i for i, line in enumerate(lines) if line.startswith(end))
    return [(a, b) for a, b in zip(starts, starts[1:] + [stop])]


def sp3_outcome(text, reference, name="sample.sp3"):
    """Either a FileFormatError naming the file and a line, or the reference result."""
    try:
        data = read_sp3_text(text, name)
    except FileFormatError as error:
        assert re.match(file_error(name), str(error)), str(error)
        return "error"
    same_sp3(data, reference)
    return "same"


SP3_SAMPLES = pytest.mark.parametrize("path", [SP3_C, SP3_D], ids=["sp3c", "sp3d"])


@SP3_SAMPLES
@FAST
@given(data=st.data())
def test_sp3_truncated_anywhere(path, data):
    text = path.read_text()
    cut = text[:data.draw(st.integers(0, len(text) - 1), label="cut")]
    outcome = sp3_outcome(cut, read_sp3(path))
    assert outcome == ("same" if cut.rstrip() == text.rstrip() else "error")


@SP3_SAMPLES
@FAST
@given(data=st.data())
def test_sp3_block_duplicated(path, data):
    lines = lines_of(path)
    first = data.draw(st.integers(0, len(lines) - 1), label="first")
    size = data.draw(st.integers(1, 6), label="size")
    block = lines[first:first + size]
    mutated = lines[:first + size] + block + lines[first + size:]
    sp3_outcome(joined(mutated), read_sp3(path))


@SP3_SAMPLES
@FAST
@given(data=st.data())
def test_sp3_epoch_blocks_swapped(path, data):
    lines = lines_of(path)
    blocks = epoch_blocks(lines)
    i, j = sorted(data.draw(st.lists(st.integers(0, len(blocks) - 1), min_size=2, max_size=2,
                                     unique=True), label="blocks"))
    (a0, a1), (b0, b1) = blocks[i], blocks[j]
    mutated = lines[:a0] + lines[b0:b1] + lines[a1:b0] + lines[a0:a1] + lines[b1:]
    assert sp3_outcome(joined(mutated), read_sp3(path)) == "error"


@SP3_SAMPLES
@FAST
@given(data=st.data())
def test_sp3_records_shuffled_within_an_epoch(path, data):
    lines = lines_of(path)
    a, b = data.draw(st.sampled_from(epoch_blocks(lines)), label="block")
    records = data.draw(st.permutations(lines[a + 1:b]), label="order")
    mutated = lines[:a + 1] + list(records) + lines[b:]
    assert sp3_outcome(joined(mutated), read_sp3(path)) == "same"


@SP3_SAMPLES
@FAST
@given(data=st.data())
def test_sp3_bad_token_in_a_number(path, data):
    lines = lines_of(path)
    rows = [i for i, line in enumerate(lines) if line.startswith("P")]
    row = data.draw(st.sampled_from(rows), label="row")
    field = data.draw(st.integers(0, 3), label="field")
    token = data.draw(st.sampled_from(NOT_FINITE + GARBAGE), label="token")
    line = lines[row].ljust(60)
    start = 4 + 14 * field
    lines[row] = line[:start] + f"{token:>14}" + line[start + 14:]
    assert sp3_outcome(joined(lines), read_sp3(path)) == "error"


@SP3_SAMPLES
@FAST
@given(data=st.data())
def test_sp3_digit_replaced_by_a_non_digit(path, data):
    lines = lines_of(path)
    rows = [i for i, line in enumerate(lines) if line.startswith("P")]
    row = data.draw(st.sampled_from(rows), label="row")
    digits = [k for k in range(4, min(60, len(lines[row]))) if lines[row][k].isdigit()]
    k = data.draw(st.sampled_from(digits), label="column")
    char = data.draw(st.sampled_from(string.ascii_letters + "!#$%&*/:;<=>?@[]^_{|}~.,"),
                     label="char")
    lines[row] = lines[row][:k] + char + lines[row][k + 1:]
    assert sp3_outcome(joined(lines), read_sp3(path)) == "error"


@SP3_SAMPLES
@FAST
@given(data=st.data())
def test_sp3_bad_or_absent_position_999999_is_missing(path, data):
    # The format's bad/absent value 999999.999999 in any coordinate of any record: that
    # position is NaN (never a position 1e9 m out), everything else as read before.
    lines = lines_of(path)
    reference = read_sp3(path)
    rows = [i for i, line in enumerate(lines) if line.startswith("P")]
    row = data.draw(st.sampled_from(rows), label="row")
    fields = data.draw(st.lists(st.integers(0, 2), min_size=1, max_size=3, unique=True),
                       label="fields")
    line = lines[row].ljust(60)
    for field in fields:
        start = 4 + 14 * field
        line = line[:start] + f"{'999999.999999':>14}" + line[start + 14:]
    lines[row] = line
    epoch = sum(1 for text in lines[:row] if text.startswith("*")) - 1
    sat = lines[row][1:4]
    mutated = read_sp3_text(joined(lines))
    assert np.all(np.isnan(mutated.positions[sat][epoch]))
    for name in reference.satellites:
        expected = np.array(reference.positions[name])
        if name == sat:
            expected[epoch] = np.nan
        np.testing.assert_array_equal(mutated.positions[name], expected)
        np.testing.assert_array_equal(mutated.clock[name], reference.clock[name])


@FAST
@given(data=st.data())
def test_sp3_single_record_off_by_1000_km_or_more_is_dropped(data):
    # One record of G01 moved by 1,000 to 20,000 km in any direction, at any epoch
    # (the ends included): one OrbitWarning, that position NaN, the others untouched,
    # and SP3Orbit interpolates nothing through it (the closed-form circle to 1 mm).
    text = sp3_with_holes({})
    reference = read_sp3_text(text)
    epoch = data.draw(st.integers(0, N_EPOCHS - 1), label="epoch")
    size = data.draw(st.floats(1000.0, 20000.0), label="km")
    direction = np.array(data.draw(st.tuples(*[st.floats(-1, 1)] * 3).filter(
        lambda v: np.linalg.norm(v) > 0.1), label="direction"))
    shift = size * direction / np.linalg.norm(direction)
    lines = lines_of_text(text)
    row = [i for i, line in enumerate(lines) if line.startswith("PG01")][epoch]
    x, y, z = circle_km(epoch * INTERVAL, 0) + shift
    lines[row] = f"PG01{x:14.6f}{y:14.6f}{z:14.6f}{1.0:14.6f}"
    with pytest.warns(OrbitWarning) as caught:
        mutated = read_sp3_text(joined(lines))
    assert len(caught) == 1
    assert re.match(rf"sample\.sp3: 1 position record\(s\) no orbit can have \(the first: G01 "
                    rf"on line {row + 1}, ", str(caught[0].message))
    expected = np.array(reference.positions["G01"])
    expected[epoch] = np.nan
    np.testing.assert_array_equal(mutated.positions["G01"], expected)
    np.testing.assert_array_equal(mutated.positions["G02"], reference.positions["G02"])


def lines_of_text(text):
    return text.splitlines()


# --- SP3Orbit: holes ---------------------------------------------------------------------

INTERVAL = 300.0
N_EPOCHS = 40
RADIUS_KM = 26560.0
OMEGA = 2 * np.pi / 43082.0  # rad/s: a GNSS-like 12-hour orbit
OFFSET_KM = 1000.0  # added to x after each hole: crossing a hole cannot go unseen


def circle_km(seconds, segment):
    """The tabulated orbit: a circle in the x-y plane, shifted in x after each hole."""
    angle = OMEGA * seconds
    return np.stack([RADIUS_KM * np.cos(angle) + OFFSET_KM * segment,
                     RADIUS_KM * np.sin(angle), 0 * angle], axis=-1)


def sp3_with_holes(holes):
    """An SP3-d file of G01 and G02 at 5-minute epochs; ``holes`` maps an epoch index of
    G01 to 'missing' (no G01 record), 'zero' (0.000000 position) or 'skipped' (no epoch)."""
    present = [e for e in range(N_EPOCHS) if holes.get(e) != "skipped"]
    lines = [
        f"#dP2023  1 25  0  0  0.00000000 {len(present):7d} ORBIT IGS20 FIT  XYZ",
        f"## 2246 259200.00000000 {INTERVAL:14.8f} 59969 0.0000000000000",
        "+    2   G01G02" + "  0" * 15,
    ] + ["+        " + "  0" * 17] * 4 + ["++       " + "  5" * 17] * 5 + SP3_DESCRIPTORS + [
        "/* SYNTHETIC, WITH HOLES",
    ]
    for e in present:
        segment = sum(1 for h in holes if h < e)
        hour, rest = divmod(int(e * INTERVAL), 3600)
        minute, second = divmod(rest, 60)
        lines.append(f"*  2023  1 25 {hour:2d} {minute:2d} {second:11.8f}")
        if holes.get(e) == "zero":
            lines.append(record("G01", "0.000000", "0.000000", "0.000000", "1.000000"))
        elif holes.get(e) != "missing":
            x, y, z = circle_km(e * INTERVAL, segment)
            lines.append(f"PG01{x:14.6f}{y:14.6f}{z:14.6f}{1.0:14.6f}")
        x, y, z = circle_km(e * INTERVAL, 0)
        lines.append(f"PG02{y:14.6f}{x:14.6f}{z:14.6f}{2.0:14.6f}")
    lines.append("EOF")
    return joined(lines)


def expected_segments(holes, points):
    """Independently: (first, last) seconds of each run of >= points consecutive valid
    epochs at the interval, and the segment number (holes before it) of each run."""
    runs, current = [], []
    for e in range(N_EPOCHS):
        if e in holes:
            if current:
                runs.append(current)
            current = []
        else:
            current.append(e)
    if current:
        runs.append(current)
    return [(run[0] * INTERVAL, run[-1] * INTERVAL, sum(1 for h in holes if h < run[0]))
            for run in runs if len(run) >= points]


T0 = Time("2023-01-25T00:00:19", scale="tai")  # 00:00 GPS


def interpolate(holes, points, seconds):
    """SP3Orbit positions (km) at seconds after the first epoch, and the warnings given."""
    orbit = SP3Orbit(io.StringIO(sp3_with_holes(holes)), "G01", points=points)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        xyz = orbit.position(T0 + np.asarray(seconds) * u.s) / 1e3
    return orbit, xyz, caught


def test_sp3_orbit_without_holes_matches_the_circle():
    # Independent reference: the closed-form circle the file tabulates (to 1 mm).
    seconds = np.linspace(0, (N_EPOCHS - 1) * INTERVAL, 157)
    orbit, xyz, caught = interpolate({}, 10, seconds)
    assert caught == []
    np.testing.assert_allclose(xyz, circle_km(seconds, 0), rtol=0, atol=1e-5)
    assert orbit.interval == INTERVAL * u.s
    assert orbit.spans.shape == (1, 2)


@pytest.mark.parametrize("kind", ["missing", "zero", "skipped"])
def test_sp3_orbit_hole_gives_nan_and_one_warning(kind):
    # A hole at epoch 20 (6000 s): times between epochs 19 and 21 have no window of 10
    # consecutive valid epochs; times right beside the hole use windows shifted away.
    seconds = np.array([5700.0, 5850.0, 6000.0, 6150.0, 6300.0, 5600.0, 6400.0, 100.0])
    orbit, xyz, caught = interpolate({20: kind}, 10, seconds)
    assert np.all(np.isnan(xyz[1:4]))
    assert np.all(np.isfinite(xyz[[0, 4, 5, 6, 7]]))
    # Before the hole the circle, after it the circle shifted by OFFSET_KM (1 m tolerance:
    # a window across the hole would be off by hundreds of km).
    np.testing.assert_allclose(xyz[[0, 5, 7]], circle_km(seconds[[0, 5, 7]], 0), atol=1e-3)
    np.testing.assert_allclose(xyz[[4, 6]], circle_km(seconds[[4, 6]], 1), atol=1e-3)
    assert len(caught) == 1 and caught[0].category is OrbitWarning
    assert re.match(r"3 of 8 times fall in holes of the SP3 orbit of G01 \(the first at "
                    r"2023-01-25T01:37:49\.000 TAI\), where no 10 consecutive epochs at the "
                    r"300 s interval have valid positions", str(caught[0].message))
    np.testing.assert_allclose((orbit.spans - T0).to_value(u.s),
                               [[0, 5700], [6300, (N_EPOCHS - 1) * INTERVAL]])


def test_sp3_orbit_short_stretch_between_holes_is_nan_even_at_its_epochs():
    orbit, xyz, caught = interpolate({10: "missing", 15: "zero"}, 10, np.arange(11, 15) * 300.0)
    assert np.all(np.isnan(xyz)) and len(caught) == 1


def test_sp3_orbit_warning_is_an_error_when_asked():
    orbit = SP3Orbit(io.StringIO(sp3_with_holes({20: "skipped"})), "G01", points=10)
    with pytest.raises(OrbitWarning, match=r"1 of 1 times fall in holes"):
        orbit.position(T0 + 5900 * u.s)


def test_sp3_orbit_no_stretch_long_enough():
    holes = {e: "missing" for e in range(5, N_EPOCHS, 6)}
    with pytest.raises(ValueError, match=r"G01 has no 10 consecutive epochs at the 300 s "
                       r"interval of the SP3 file with a valid position, as the interpolation "
                       r"window needs \(its longest stretch has 5\); give fewer points"):
        SP3Orbit(io.StringIO(sp3_with_holes(holes)), "G01")


def test_sp3_orbit_sample_e11_has_holes():
    # E11 of the sample lacks 00:15: two stretches, of one and two epochs.
    with pytest.raises(ValueError, match=r"E11 has no 4 consecutive epochs .* longest "
                       r"stretch has 2"):
        SP3Orbit(SP3_C, "E11", points=4)
    orbit = SP3Orbit(SP3_C, "E11", points=2)
    with pytest.warns(OrbitWarning, match=r"1 of 2 times fall in holes"):
        xyz = orbit.position(T0 + [600, 2000] * u.s)
    assert np.all(np.isnan(xyz[0])) and np.all(np.isfinite(xyz[1]))


@FAST
@given(holes=st.dictionaries(st.integers(1, N_EPOCHS - 2),
                             st.sampled_from(["missing", "zero", "skipped"]), max_size=5),
       points=st.sampled_from([4, 6, 10]),
       seconds=st.lists(st.floats(0, (N_EPOCHS - 1) * INTERVAL), min_size=1, max_size=20))
def test_sp3_orbit_never_interpolates_across_a_hole(holes, points, seconds):
    segments = expected_segments(holes, points)
    if not segments:
        with pytest.raises(ValueError, match="has no .* consecutive epochs"):
            SP3Orbit(io.StringIO(sp3_with_holes(holes)), "G01", points=points)
        return
    seconds = np.array(seconds)
    orbit, xyz, caught = interpolate(holes, points, seconds)
    expected = np.full(xyz.shape, np.nan)
    for first, last, segment in segments:
        inside = (seconds >= first - 1e-6) & (seconds <= last + 1e-6)
        expected[inside] = circle_km(seconds[inside], segment)
    assert np.array_equal(np.isnan(xyz), np.isnan(expected))
    # Within 1 km of the right circle (a 4-point window is good to metres); a window
    # across a hole would mix circles 1000 km apart.
    np.testing.assert_allclose(xyz, expected, rtol=0, atol=1.0)
    assert len(caught) == (1 if np.any(np.isnan(expected)) else 0)
    assert all(w.category is OrbitWarning for w in caught)


# --- ORBEX ---------------------------------------------------------------------------------


def read_obx_text(text, name="sample.obx"):
    return read_orbex(stream(text, name))


def obx_with(changes):
    lines = lines_of(OBX)
    for lineno in sorted(changes, reverse=True):
        new = changes[lineno]
        lines[lineno - 1:lineno] = [] if new is None else [new] if isinstance(new, str) else new
    return joined(lines)


def same_orbex(a, b):
    assert (a.version, a.time_system, a.frame, a.frame_type, a.quaternion_convention) == (
        b.version, b.time_system, b.frame, b.frame_type, b.quaternion_convention)
    assert set(a.satellites) == set(b.satellites)
    for sat in a.satellites:
        (ta, qa), (tb, qb) = a.attitude[sat], b.attitude[sat]
        assert np.all(np.abs((ta - tb).to_value(u.s)) < 1e-9)
        np.testing.assert_array_equal(qa, qb)


# sample.obx: FRAME_TYPE line 15, COORD_SYSTEM 14, TIME_SYSTEM 10; epochs on lines 30, 34,
# 37 with ATT records 31-33, 35-36, 38-40.

@pytest.mark.parametrize("value", ["ecef", "Ecef", "ITRF", "ECEF J2000", "ECI/J2000", "EME2000",
                                   "ECEF*", ""])
def test_orbex_frame_type_must_be_exactly_ecef_or_eci(value):
    with pytest.raises(FileFormatError, match=r"^sample\.obx, line 15: expected a FRAME_TYPE, "
                       r"one of ECEF, ECI, got ' FRAME_TYPE"):
        read_obx_text(obx_with({15: f" FRAME_TYPE          {value}"}))


def test_orbex_frame_type_read_exactly():
    assert read_orbex(OBX).frame_type == "ECEF"
    eci = read_obx_text(obx_with({15: " FRAME_TYPE          ECI"}))
    assert eci.frame_type == "ECI" and eci.frame == "IGS20 ECI"
    assert read_obx_text(obx_with({15: None})).frame_type is None


@pytest.mark.parametrize("value", ["", "IGS 20"])
def test_orbex_coord_system_one_word(value):
    with pytest.raises(FileFormatError, match=r"line 14: expected a COORD_SYSTEM, one word such "
                       r"as IGS20"):
        read_obx_text(obx_with({14: f" COORD_SYSTEM        {value}"}))


@pytest.mark.parametrize("line, match", [
    (" FRAME_TYPE          ECI", r"line 16: expected a FRAME_TYPE, one of ECEF, ECI, the same as "
                                 r"on line 15 \(ECEF\), got ' FRAME_TYPE          ECI'"),
    (" TIME_SYSTEM         GAL", r"line 16: expected a TIME_SYSTEM, one of .*, the same as on "
                                 r"line 10 \(GPS\)"),
    (" COORD_SYSTEM        IGb14", r"line 16: expected a COORD_SYSTEM, one word such as IGS20, "
                                   r"the same as on line 14 \(IGS20\)"),
])
def test_orbex_description_field_given_twice(line, match):
    with pytest.raises(FileFormatError, match=r"^sample\.obx, " + match):
        read_obx_text(obx_with({15: [lines_of(OBX)[14], line]}))


def test_orbex_same_field_twice_with_the_same_value_is_fine():
    same_orbex(read_obx_text(obx_with({15: [lines_of(OBX)[14]] * 2})), read_orbex(OBX))


@pytest.mark.parametrize("component", range(4))
@pytest.mark.parametrize("token", NOT_FINITE)
def test_orbex_non_finite_quaternion(component, token):
    q = ["0.0349994571923225", "0.1941937123721343", "-0.7315566977199617", "-0.65260143892918"]
    q[component] = token
    line = " ATT G01              4 " + " ".join(q)
    with pytest.raises(FileFormatError, match=r"^sample\.obx, line 35: expected an ATT record "
                       r"' ATT <sat> 4 q0 q1 q2 q3' with four finite numbers \('nan' and 'inf' "
                       r"are not quaternion components\)"):
        read_obx_text(obx_with({35: line}))


def test_orbex_epoch_repeated():
    with pytest.raises(FileFormatError, match=r"^sample\.obx, line 34: expected an epoch later "
                       r"than the one on line 30 \(epochs must increase; this one repeats it\)"):
        read_obx_text(obx_with({34: "## 2023 01 25 00 00  0.000000000000   2"}))


def test_orbex_epochs_reversed():
    lines = lines_of(OBX)
    swapped = lines[:29] + lines[33:36] + lines[29:33] + lines[36:]  # 00:00:30 before 00:00
    with pytest.raises(FileFormatError, match=r"^sample\.obx, line 33: expected an epoch later "
                       r"than the one on line 30 \(epochs must increase; this one is earlier\)"):
        read_obx_text(joined(swapped))


def test_orbex_epoch_record_count_unreadable():
    with pytest.raises(FileFormatError, match=r"line 34: expected an epoch line"):
        read_obx_text(obx_with({34: "## 2023 01 25 00 00 30.000000000000   x"}))


def test_from_orbex_frame_from_the_file_or_the_caller():
    eci = obx_with({15: " FRAME_TYPE          ECI"})
    assert QuaternionAttitude.from_orbex(stream(eci, "eci.obx"), "G01").frame == "gcrs"
    assert QuaternionAttitude.from_orbex(OBX, "G01", frame="itrs").frame == "itrs"
    missing = obx_with({15: None})
    with pytest.raises(ValueError, match=r"^nofr\.obx: the ORBEX file does not give FRAME_TYPE "
                       r"\(ECEF or ECI\) in its \+FILE/DESCRIPTION block, so the frame of its "
                       r"quaternions is unknown; pass frame='itrs' \(Earth-fixed\) or "
                       r"frame='gcrs' \(celestial\)"):
        QuaternionAttitude.from_orbex(stream(missing, "nofr.obx"), "G01")
    given = QuaternionAttitude.from_orbex(stream(missing, "nofr.obx"), "G01", frame="gcrs")
    assert given.frame == "gcrs"
    with pytest.raises(ValueError, match=rf"^{re.escape(str(OBX))}: frame='gcrs' contradicts "
                       r"the file's FRAME_TYPE ECEF \('itrs'\); leave frame out"):
        QuaternionAttitude.from_orbex(OBX, "G01", frame="gcrs")
    with pytest.raises(ValueError, match=r"frame must be one of \('itrs', 'gcrs'\) or None, "
                       r"got 'ecef'"):
        QuaternionAttitude.from_orbex(OBX, "G01", frame="ecef")


def test_from_orbex_names_file_satellite_and_epoch_of_a_non_unit_quaternion():
    text = obx_with({35: " ATT G01              4  0.5 0.0 0.0 0.0"})
    with pytest.raises(ValueError, match=r"^bad\.obx: ATT records of G01: quaternion 1 at "
                       r"2023-01-25T00:00:49\.000 has norm 0\.5; attitude quaternions must be "
                       r"unit"):
        QuaternionAttitude.from_orbex(stream(text, "bad.obx"), "G01")


def test_quaternion_attitude_refuses_non_finite_values():
    t = Time("2023-01-25") + [0, 60] * u.s
    with pytest.raises(ValueError, match=r"quaternion 1 at 2023-01-25T00:01:00\.000 is not "
                       r"finite: \[nan  0\.  0\.  0\.\]"):
        QuaternionAttitude(t, [[1, 0, 0, 0], [np.nan, 0, 0, 0]])
    with pytest.raises(ValueError, match=r"quaternion 0 .* is not finite"):
        QuaternionAttitude(t, [[np.inf, 0, 0, 0], [1, 0, 0, 0]])
    with pytest.raises(ValueError, match=r"must increase strictly: epoch 1 "
                       r"\(2023-01-25T00:00:00\.000\) is not after epoch 0"):
        QuaternionAttitude(t[[0, 0]], [[1, 0, 0, 0], [1, 0, 0, 0]])
    masked = t.copy()
    masked[1] = np.ma.masked
    with pytest.raises(ValueError, match=r"quaternion epochs must all be given: epoch 1 is "
                       r"masked"):
        QuaternionAttitude(masked, [[1, 0, 0, 0], [1, 0, 0, 0]])


# --- ORBEX: property-based mutations of the sample -----------------------------------------


def obx_outcome(text, name="sample.obx"):
    try:
        data = read_obx_text(text, name)
    except FileFormatError as error:
        assert re.match(file_error(name), str(error)), str(error)
        return "error"
    same_orbex(data, read_orbex(OBX))
    return "same"


@FAST
@given(data=st.data())
def test_orbex_truncated_anywhere(data):
    text = OBX.read_text()
    cut = text[:data.draw(st.integers(0, len(text) - 1), label="cut")]
    assert obx_outcome(cut) == ("same" if cut.rstrip() == text.rstrip() else "error")


@FAST
@given(data=st.data())
def test_orbex_block_duplicated(data):
    lines = lines_of(OBX)
    first = data.draw(st.integers(0, len(lines) - 1), label="first")
    size = data.draw(st.integers(1, 5), label="size")
    mutated = lines[:first + size] + lines[first:first + size] + lines[first + size:]
    obx_outcome(joined(mutated))


@FAST
@given(data=st.data())
def test_orbex_epoch_blocks_swapped(data):
    lines = lines_of(OBX)
    blocks = epoch_blocks(lines, head="##", end=("-EPHEMERIS/DATA",))
    i, j = sorted(data.draw(st.lists(st.integers(0, len(blocks) - 1), min_size=2, max_size=2,
                                     unique=True), label="blocks"))
    (a0, a1), (b0, b1) = blocks[i], blocks[j]
    mutated = lines[:a0] + lines[b0:b1] + lines[a1:b0] + lines[a0:a1] + lines[b1:]
    assert obx_outcome(joined(mutated)) == "error"


@FAST
@given(data=st.data())
def test_orbex_records_shuffled_within_an_epoch(data):
    lines = lines_of(OBX)
    a, b = data.draw(st.sampled_from(epoch_blocks(lines, "##", ("-EPHEMERIS/DATA",))))
    records = data.draw(st.permutations(lines[a + 1:b]), label="order")
    assert obx_outcome(joined(lines[:a + 1] + list(records) + lines[b:])) == "same"


@FAST
@given(data=st.data())
def test_orbex_bad_token_in_a_quaternion(data):
    lines = lines_of(OBX)
    rows = [i for i, line in enumerate(lines) if line.startswith(" ATT ")]
    row = data.draw(st.sampled_from(rows), label="row")
    parts = lines[row].split()
    parts[3 + data.draw(st.integers(0, 3), label="component")] = data.draw(
        st.sampled_from(NOT_FINITE + GARBAGE), label="token")
    lines[row] = " " + " ".join(parts)
    assert obx_outcome(joined(lines)) == "error"


# --- TLE -----------------------------------------------------------------------------------

ISS = ("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
       "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")
LINE1, LINE2 = GPS_SVN76_TLE


def checksum(line):
    """The TLE checksum (CelesTrak: digits summed, '-' counts 1, modulo 10)."""
    return str(sum(int(c) if c.isdigit() else c == "-" for c in line[:68]) % 10)


def put(line, column, text):
    """Write ``text`` from 1-based ``column`` and make the checksum hold again."""
    line = line[:column - 1] + text + line[column - 1 + len(text):]
    return line[:68] + checksum(line)


@pytest.mark.parametrize("number, column, text, match", [
    (2, 9, " 54.95x7", r"the inclination in columns 9-16 as degrees 'ddd.dddd', got ' 54.95x7'"),
    (2, 9, "  549577", r"the inclination in columns 9-16 as degrees 'ddd.dddd', got '  549577'"),
    (2, 9, "181.0000", r"the inclination in columns 9-16 at most 180 degrees, got '181.0000'"),
    (2, 18, "138,7050", r"the right ascension of the ascending node in columns 18-25"),
    (2, 18, "360.5000", r"the right ascension of the ascending node in columns 18-25 at most 360"),
    (2, 27, "00 6950", r"the eccentricity in columns 27-33 as seven digits \(assumed leading "
                       r"decimal point\), got '00 6950'"),
    (2, 27, "0.06695", r"the eccentricity in columns 27-33"),
    (2, 27, "abcdefg", r"the eccentricity in columns 27-33"),
    (2, 35, "231.22x4", r"the argument of perigee in columns 35-42"),
    (2, 44, "128.16 8", r"the mean anomaly in columns 44-51"),
    (2, 53, " 2.0056x135", r"the mean motion in columns 53-63 as revolutions per day"),
    (2, 53, "   20056013", r"the mean motion in columns 53-63"),
    (2, 53, " 0.00000000", r"a mean motion in columns 53-63 above zero, got ' 0.00000000'"),
    (2, 17, "x", r"a blank in column 17, between two fields, got 'x'"),
    (2, 3, "4132x", r"the catalogue number in columns 3-7"),
    (1, 19, "2x", r"the epoch year in columns 19-20 as two digits"),
    (1, 21, "024.3933217x", r"the epoch day in columns 21-32"),
    (1, 21, "366.50000000", r"an epoch day in columns 21-32 from 1 to 366 \(excluded\) in 2023"),
    (1, 21, "000.50000000", r"an epoch day in columns 21-32 from 1 to 366"),
    (1, 34, " .0000001x", r"the first derivative of the mean motion in columns 34-43"),
    (1, 34, " 0.0000001", r"the first derivative of the mean motion in columns 34-43"),
    (1, 45, " 00000x0", r"the second derivative of the mean motion in columns 45-52"),
    (1, 54, " 0000e+0", r"the BSTAR drag term in columns 54-61"),
    (1, 54, "  1.5e-4", r"the BSTAR drag term in columns 54-61"),
    (1, 63, "x", r"the ephemeris type in columns 63-63"),
    (1, 65, " 9x9", r"the element set number in columns 65-68"),
    (1, 33, "x", r"a blank in column 33"),
])
def test_tle_field_that_does_not_read_with_a_valid_checksum(number, column, text, match):
    lines = [LINE1, LINE2]
    lines[number - 1] = put(lines[number - 1], column, text)
    assert lines[number - 1][68] == checksum(lines[number - 1])  # the checksum holds
    with pytest.raises(ValueError, match=rf"^TLE line {number} must have " + match):
        TLEOrbit(*lines)
    text_file = "GPS\n" + "\n".join(lines) + "\n"
    with pytest.raises(FileFormatError, match=rf"^gps\.tle, line {number + 1}: expected "
                       + match.replace("must have ", "").split(", got")[0]):
        read_tle(stream(text_file, "gps.tle"))


def test_tle_leap_year_day_366_is_fine():
    line1 = put(LINE1, 19, "24366.50000000")  # 2024 is a leap year
    assert TLEOrbit(line1, LINE2).epoch.utc.iso.startswith("2024-12-31 12:00")


def test_tle_check_functions():
    assert check_tle_pair(LINE1 + "  ", LINE2) == GPS_SVN76_TLE
    with pytest.raises(ValueError, match=r"number must be 1 or 2, got 3"):
        check_tle_line(LINE1, 3)
    with pytest.raises(TypeError, match=r"TLE line 2 must be a str, got NoneType"):
        check_tle_line(None, 2)
    with pytest.raises(ValueError, match=r"different satellites: '41328' and '25544'"):
        check_tle_pair(LINE1, ISS[1])


def test_read_tle_line_1_broken_in_its_first_columns():
    # '1x' is no element line: read as a title, it is named when its line 2 comes.
    text = f"GPS\n{put(LINE1, 2, 'x')}\n{LINE2}\n"
    with pytest.raises(FileFormatError, match=r"^sats\.tle, line 2: expected line 1 of an "
                       r"element set, starting '1 ', got '1x41328U"):
        read_tle(stream(text, "sats.tle"))


def test_read_tle_catalogue_numbers_differ():
    text = f"{LINE1}\n{ISS[1]}\n"
    with pytest.raises(FileFormatError, match=r"^sats\.tle, line 2: expected line 2 of the "
                       r"element set of catalogue number '41328' begun on line 1, got '2 25544"):
        read_tle(stream(text, "sats.tle"))


def test_read_tle_checksum_in_file():
    with pytest.raises(FileFormatError, match=r"^sats\.tle, line 3: expected the checksum 2 in "
                       r"column 69 \(got '3'\)"):
        read_tle(stream(f"GPS\n{LINE1}\n{LINE2[:-1]}3\n", "sats.tle"))


def test_sgp4_cannot_start():
    line2 = put(LINE2, 27, "9999999")
    with pytest.raises(ValueError, match=r"SGP4 cannot start from this element set: semilatus "
                       r"rectum is less than zero"):
        TLEOrbit(LINE1, line2)


def decaying():
    # A low orbit with a huge drag term: SGP4 gives up within a day (error 1/6).
    return TLEOrbit.from_elements(Time("2023-01-25"), inclination=97 * u.deg, raan=30 * u.deg,
                                  altitude=60 * u.km, bstar=0.5, name="FALLING")


def test_sgp4_failure_gives_nan_and_one_warning():
    orbit = decaying()
    t = Time("2023-01-25") + np.arange(0, 5, 0.5) * u.day
    with pytest.warns(OrbitWarning, match=r"^SGP4 fails at 9 of 10 epochs \(FALLING: 9 epochs, "
                      r"mean eccentricity is outside the range 0\.0 to 1\.0\); their positions "
                      r"are NaN") as caught:
        xyz = orbit.position(t)
    assert len(caught) == 1
    assert np.all(np.isfinite(xyz[0])) and np.all(np.isnan(xyz[1:]))


def test_old_element_set_warns_once():
    orbit = TLEOrbit(*GPS_SVN76_TLE, name="GPS SVN 76")  # epoch 2023-01-24.39
    orbit.position(orbit.epoch + [-29.9, 0, 29.9] * u.day)  # no warning (they are errors here)
    t = orbit.epoch + [0, 10, 31, 45, -40] * u.day
    with pytest.warns(OrbitWarning, match=r"^3 of 5 epochs lie more than 30 days from the epoch "
                      r"of their element set \(GPS SVN 76 \(epoch 2023-01-24\) up to 45\.0 days "
                      r"away\); SGP4 positions degrade") as caught:
        xyz = orbit.position(t)
    assert len(caught) == 1 and np.all(np.isfinite(xyz))
    orbit.max_age = 60 * u.day
    orbit.position(t)


def test_propagate_tles_needs_tle_orbits():
    with pytest.raises(TypeError, match=r"orbits\[1\] must be a TLEOrbit, got str"):
        propagate_tles([TLEOrbit(*GPS_SVN76_TLE), "ISS"], Time("2023-01-25"))


# ERFA calls UTC "dubious" before 1960 and decades ahead; the checks here do not depend on it.
@pytest.mark.filterwarnings("ignore::erfa.ErfaWarning")
@pytest.mark.parametrize("epoch", ["2057-01-01", "1956-12-31T23:59", "2100-06-01"])
def test_from_elements_epoch_beyond_the_two_digit_year(epoch):
    with pytest.raises(ValueError, match=r"epoch must be within 1957-2056, the years a TLE's "
                       r"two-digit year can hold \(57-99: 1957-1999, 00-56: 2000-2056\), got "
                       + epoch[:4]):
        TLEOrbit.from_elements(Time(epoch), inclination=55 * u.deg, raan=0 * u.deg,
                               altitude=20000 * u.km)


@pytest.mark.filterwarnings("ignore::erfa.ErfaWarning")
def test_from_elements_epoch_edges_of_the_two_digit_year():
    for epoch, year in (("1957-01-02", "57"), ("2056-06-01", "56")):
        orbit = TLEOrbit.from_elements(Time(epoch), inclination=55 * u.deg, raan=0 * u.deg,
                                       altitude=20000 * u.km)
        assert orbit.line1[18:20] == year
        assert orbit.epoch.utc.iso.startswith(epoch)


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(epoch=Time(["2023-01-25", "2023-01-26"])), ValueError,
     r"epoch must be one instant, got shape \(2,\)"),
    (dict(satnum=340000), ValueError, r"satnum must be within 0-339999, got 340000"),
    (dict(satnum=5.5), TypeError, r"satnum must be an integer, got float"),
    (dict(raan=np.nan * u.deg), ValueError, r"raan must be one finite angle, got nan deg"),
    (dict(mean_anomaly=[1, 2] * u.deg), ValueError, r"mean_anomaly must be one finite angle"),
    (dict(argument_of_perigee=np.inf * u.deg), ValueError, r"argument_of_perigee must be one"),
    (dict(bstar=np.inf), ValueError, r"bstar must be finite, got inf"),
    (dict(eccentricity=np.nan), ValueError, r"eccentricity must be in \[0, 1\), got nan"),
    (dict(altitude=None, mean_motion=150 * u.cycle / u.day), ValueError,
     r"mean_motion must be below 100 revolutions per day"),
    (dict(altitude=np.nan * u.km), ValueError, r"altitude must be positive, got nan km"),
])
def test_from_elements_refusals(kwargs, error, match):
    arguments = dict(epoch=Time("2023-01-25"), inclination=55 * u.deg, raan=0 * u.deg,
                     altitude=20000 * u.km)
    arguments.update(kwargs)
    epoch = arguments.pop("epoch")
    with pytest.raises(error, match=match):
        TLEOrbit.from_elements(epoch, **arguments)


def test_from_elements_wraps_angles():
    orbit = TLEOrbit.from_elements(Time("2023-01-25"), inclination=55 * u.deg, raan=-30 * u.deg,
                                   argument_of_perigee=400 * u.deg, mean_anomaly=-1 * u.deg,
                                   altitude=20000 * u.km, eccentricity=0.01, satnum=123456)
    assert orbit.line2[17:25] == "330.0000" and orbit.line2[34:42] == " 40.0000"
    assert orbit.line2[43:51] == "359.0000"
    assert orbit.line1[2:7] == "C3456"  # 123456 in the letter-and-four-digits form


# --- TLE: property-based mutations of a three-set file -------------------------------------


def tle_sets():
    genesis = TLEOrbit.from_elements(Time("2023-01-25"), inclination=97 * u.deg,
                                     raan=30 * u.deg, altitude=6000 * u.km)
    return [("GPS SVN 76", *GPS_SVN76_TLE), ("ISS (ZARYA)", *ISS),
            ("GENESIS", genesis.line1, genesis.line2)]


def tle_text(sets):
    return "".join(f"{name}\n{l1}\n{l2}\n" for name, l1, l2 in sets)


# 1-based columns, with the characters a column holds (a digit where a number needs one, the
# point, a blank between fields): in these columns any other character breaks the field
# (digits before the point may be blanks: there only a digit or a blank reads).
DIGITS = set(string.digits)
TLE_STRICT = {
    1: {**{c: {"."} for c in (24, 35)},
        **{c: DIGITS for c in [*range(25, 33), *range(36, 44), *range(46, 51), 52,
                               *range(55, 60), 61]},
        **{c: {"+", "-"} for c in (51, 60)},
        **{c: DIGITS | {" "} for c in (19, 20)},
        **{c: {" "} for c in (2, 9, 18, 33, 44, 53, 62, 64)}},
    2: {**{c: {"."} for c in (12, 21, 38, 47, 55)},
        **{c: DIGITS for c in [*range(13, 17), *range(22, 26), *range(27, 34),
                               *range(39, 43), *range(48, 52), *range(56, 64)]},
        **{c: DIGITS | {" "}
           for c in (9, 10, 11, 18, 19, 20, 35, 36, 37, 44, 45, 46, 53, 54)},
        **{c: {" "} for c in (2, 8, 17, 26, 34, 43, 52)}},
}
PRINTABLE = string.ascii_letters + string.digits + string.punctuation + " "


@FAST
@given(data=st.data())
def test_tle_field_broken_anywhere_with_a_valid_checksum(data):
    sets = tle_sets()
    k = data.draw(st.integers(0, len(sets) - 1), label="set")
    number = data.draw(st.sampled_from([1, 2]), label="line")
    line = sets[k][number]
    columns = [c for c, allowed in TLE_STRICT[number].items() if line[c - 1] in allowed]
    column = data.draw(st.sampled_from(columns), label="column")
    allowed = TLE_STRICT[number][column]
    char = data.draw(st.sampled_from([c for c in PRINTABLE if c not in allowed]), label="char")
    broken = put(line, column, char)
    sets[k] = sets[k][:number] + (broken,) + sets[k][number + 1:]
    with pytest.raises(ValueError, match=rf"^TLE line {number} must (have|start with) "):
        TLEOrbit(sets[k][1], sets[k][2])
    with pytest.raises(FileFormatError, match=rf"^sets\.tle, line {3 * k + 1 + number}: "):
        read_tle(stream(tle_text(sets), "sets.tle"))


@FAST
@given(data=st.data())
def test_tle_file_truncated_anywhere(data):
    sets = tle_sets()
    text = tle_text(sets)
    cut = text[:data.draw(st.integers(0, len(text) - 1), label="cut")]
    try:
        records = read_tle(stream(cut, "sets.tle"))
    except FileFormatError as error:
        assert re.match(file_error("sets.tle"), str(error)), str(error)
        return
    # Only whole element sets survive, exactly as they were.
    assert [tuple(r) for r in records] == sets[:len(records)]


# --- the warnings point at the caller ------------------------------------------------------


def test_orbit_warnings_name_the_calling_line():
    from astropy.coordinates import EarthLocation

    from astropy_feedrot import AltAzMount, Antenna, Satellite
    from astropy_feedrot.engine.grid import feed_rotation_grid

    t = Time("2023-01-25") + np.arange(0, 5, 0.5) * u.day
    with pytest.warns(OrbitWarning) as caught:
        decaying().position(t)
    assert [w.filename for w in caught] == [__file__]
    orbit = SP3Orbit(io.StringIO(sp3_with_holes({20: "missing"})), "G01")
    with pytest.warns(OrbitWarning) as caught:
        orbit.position(T0 + 6100 * u.s)
    assert [w.filename for w in caught] == [__file__]
    # The grid propagates element sets together, with the same warning.
    antenna = Antenna(EarthLocation.from_geodetic(0 * u.deg, 45 * u.deg), AltAzMount())
    with pytest.warns(OrbitWarning, match=r"SGP4 fails at 9 of 10 epochs") as caught:
        feed_rotation_grid([antenna], [Satellite(decaying())], t)
    assert [w.filename for w in caught if w.category is OrbitWarning] == [__file__]
