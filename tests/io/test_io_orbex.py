# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reading attitude quaternions from ORBEX files: values, convention, errors, size."""

import io
import pathlib
import re

import numpy as np
import pytest
from astropy import units as u
from astropy.time import Time
from helpers import SOURCE_KINDS, read_as

import astropy_feedrot.data
from astropy_feedrot.io import FileFormatError, ORBEXData, read_orbex, read_sp3

DATA = pathlib.Path(__file__).parent.parent / "data"
SAMPLES = pathlib.Path(astropy_feedrot.data.__file__).parent
SAMPLE = SAMPLES / "sample.obx"

# Values written in astropy_feedrot/data/sample.obx, lines 31, 35 and 38 (G01) and 33, 40 (E11).
G01_Q = np.array([
    [0.0354798739664723, 0.1940762630681236, -0.7303810881827204, -0.6539258739963278],
    [0.0349994571923225, 0.1941937123721343, -0.7315566977199617, -0.6526014389291800],
    [0.0345134652465047, 0.1943038205746366, -0.7327313967052089, -0.6512753229696420],
])
E11_Q = np.array([
    [0.1023897587176709, 0.0865495357288828, -0.9515516775321279, -0.2767217377811969],
    [0.0999118535413060, 0.0857486811743025, -0.9514769703480135, -0.2781301136090336],
])


def sample_lines():
    return SAMPLE.read_text().splitlines()


def write_modified(tmp_path, changes, name="bad.obx"):
    """Copy the sample with 1-based lines replaced (str) or deleted (None)."""
    lines = sample_lines()
    for lineno in sorted(changes, reverse=True):
        if changes[lineno] is None:
            del lines[lineno - 1]
        else:
            lines[lineno - 1] = changes[lineno]
    out = tmp_path / name
    out.write_text("\n".join(lines) + "\n")
    return out


def same_instant(a, b, tol=1 * u.ns):
    return bool(np.all(np.abs((a - b).to(u.s)) < tol))


def rotation_matrix(q):
    """R(q) with (0, r_B) = q (0, r_T) q*, i.e. r_B = R(q) r_T (Hamilton product)."""
    q0, q1, q2, q3 = q
    return np.array([
        [1 - 2 * (q2**2 + q3**2), 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
        [2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1**2 + q3**2), 2 * (q2 * q3 - q0 * q1)],
        [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), 1 - 2 * (q1**2 + q2**2)],
    ])


# --- the sample -------------------------------------------------------------------


def test_sample_header():
    data = read_orbex(SAMPLE)
    assert isinstance(data, ORBEXData)
    assert data.version == "0.09"  # line 1
    assert data.time_system == "GPS"  # line 10
    assert data.frame == "IGS20 ECEF"  # lines 14-15
    assert data.satellites == ("G01", "G05", "E11")
    assert repr(data) == (
        "<ORBEXData version='0.09' time_system='GPS' frame='IGS20 ECEF' 3 satellites, 8 records>"
    )


def test_sample_quaternions_as_written():
    data = read_orbex(SAMPLE)
    times, q = data.attitude["G01"]
    assert q.shape == (3, 4)
    np.testing.assert_array_equal(q, G01_Q)
    times, q = data.attitude["E11"]
    np.testing.assert_array_equal(q, E11_Q)
    # The sample holds unit quaternions.
    for sat in data.satellites:
        np.testing.assert_allclose(np.linalg.norm(data.attitude[sat][1], axis=1), 1.0,
                                   rtol=0, atol=1e-15)


def test_sample_epochs():
    data = read_orbex(SAMPLE)
    times, _ = data.attitude["G01"]
    assert times.shape == (3,)
    assert times.scale == "tai"
    # Lines 30, 34, 37: GPS 00:00:00, 00:00:30, 00:01:00 on 2023-01-25; GPS - UTC = 18 s.
    expected = Time("2023-01-24T23:59:42", scale="utc") + [0, 30, 60] * u.s
    assert same_instant(times, expected)
    assert times[1].utc.isot == "2023-01-25T00:00:12.000"
    # E11 has no record at 00:00:30 (lines 34-36).
    times, _ = data.attitude["E11"]
    assert same_instant(times, Time("2023-01-24T23:59:42", scale="utc") + [0, 60] * u.s)


def test_arrays_are_read_only():
    _, q = read_orbex(SAMPLE).attitude["G01"]
    with pytest.raises(ValueError, match="read-only"):
        q[0, 0] = 1.0


def test_convention_statement():
    data = read_orbex(SAMPLE)
    assert data.quaternion_convention == (
        "rotation from the terrestrial frame (ECEF) to the satellite body frame, "
        "(0, r_body) = q (0, r_ECEF) q*"
    )


def test_convention_with_the_orbit():
    # The sample attitude is nominal yaw steering: with r_B = R(q) r_T, the third row of
    # R(q) (the body z axis, the antenna axis) points from the satellite to the Earth's
    # centre, at the positions of astropy_feedrot/data/sample.sp3 (lines 24-26, the same epoch).
    orbit = read_sp3(SAMPLES / "sample.sp3")
    attitude = read_orbex(SAMPLE)
    assert same_instant(orbit.epochs[0], attitude.attitude["G01"][0][0])
    for sat in ("G01", "G05", "E11"):
        matrix = rotation_matrix(attitude.attitude[sat][1][0])
        np.testing.assert_allclose(matrix @ matrix.T, np.eye(3), rtol=0, atol=1e-14)
        r = orbit.positions[sat][0]
        np.testing.assert_allclose(matrix[2], -r / np.linalg.norm(r), rtol=0, atol=1e-9)
        # The conjugate reading (columns as body axes) is not the nominal attitude.
        assert not np.allclose(matrix[:, 2], -r / np.linalg.norm(r), atol=1e-3)


INLINE = """%=ORBEX  0.09
%%
+FILE/DESCRIPTION
 DESCRIPTION         EXAMPLE GPS + LEO ORBIT
 TIME_SYSTEM         {time_system}
 COORD_SYSTEM        IGS20
 FRAME_TYPE          {frame_type}
 LIST_OF_REC_TYPES   POS VEL CLK ATT
 ORBIT_XYZ_UNITS     METERS
 ORBIT_VEL_UNITS     METERS/SEC
 SVCLK_UNITS         MICROSECOND
-FILE/DESCRIPTION
+SATELLITE/ID_AND_DESCRIPTION
 G02    GPS BLOCK IIR-B
 L06    LEO
-SATELLITE/ID_AND_DESCRIPTION
+EPHEMERIS/DATA
*REC ID_    FLAGS_    N ________X_(m)___ ________Y_(m)___ ________Z_(m)___
## 2023 01 25  0  0  0.000000000000  2
 POS G02              3     4049646.6140    25594715.4960    -5815946.7980
 VEL G02              3        -353.5783         821.0842        2972.7179
 CLK G02              1      -39.2268190
 POS L06    EP  M     3     1781848.9098     5968846.1797    -2704551.4098
 ATT L06              4  2.0000000000000000  0.0000000000000000  0.0000000000000000  0.0
## 2023 01 25  0  0  1.000000000000  2
 POS G02              3     4049200.1234    25594900.5678    -5813000.9876

 ATT L06              4 -0.5066930256001020 -0.2289786888002010  0.7772033941001450 -0.29
 ATT G02              4  0.7071067811865476  0.0  0.0  0.7071067811865476
-EPHEMERIS/DATA
%END_ORBEX
"""


def inline(time_system="GPS", frame_type="ECEF"):
    return io.StringIO(INLINE.format(time_system=time_system, frame_type=frame_type))


def test_other_records_are_skipped():
    data = read_orbex(inline())
    assert data.satellites == ("L06", "G02")
    times, q = data.attitude["L06"]
    assert len(times) == 2
    # Returned as written: no normalisation (2, 0, 0, 0), no sign flip (negative q0).
    np.testing.assert_array_equal(
        q, [[2.0, 0.0, 0.0, 0.0], [-0.5066930256001020, -0.2289786888002010,
                                   0.7772033941001450, -0.29]])
    times, q = data.attitude["G02"]
    assert same_instant(times, Time("2023-01-24T23:59:43", scale="utc"))


def test_celestial_frame_type():
    data = read_orbex(inline(frame_type="ECI"))
    assert data.frame == "IGS20 ECI"
    assert data.quaternion_convention == (
        "rotation from the celestial frame (ECI) to the satellite body frame, "
        "(0, r_body) = q (0, r_ECI) q*"
    )


def test_missing_frame_type():
    text = SAMPLE.read_text().replace(" FRAME_TYPE          ECEF\n", "")
    data = read_orbex(io.StringIO(text))
    assert data.frame == "IGS20"
    assert "reference frame of the file (FRAME_TYPE not given)" in data.quaternion_convention


@pytest.mark.parametrize("code, utc", [
    ("GPS", "2023-01-24T23:59:42"),
    ("GAL", "2023-01-24T23:59:42"),
    ("BDT", "2023-01-24T23:59:56"),
    ("TAI", "2023-01-24T23:59:23"),
    ("UTC", "2023-01-25T00:00:00"),
    ("GLO", "2023-01-25T00:00:00"),
])
def test_time_systems(code, utc):
    data = read_orbex(inline(time_system=code))
    assert data.time_system == code
    assert same_instant(data.attitude["L06"][0][0], Time(utc, scale="utc"))


# --- sources ----------------------------------------------------------------------


@pytest.mark.parametrize("kind", SOURCE_KINDS)
def test_sources(kind, tmp_path):
    data = read_as(kind, read_orbex, SAMPLE, tmp_path)
    assert data.satellites == ("G01", "G05", "E11")
    np.testing.assert_array_equal(data.attitude["G01"][1], G01_Q)


def test_error_names_open_file(tmp_path):
    path = write_modified(tmp_path, {31: " ATT G01              4  0.1  0.2  0.3"})
    with open(path) as fh, pytest.raises(FileFormatError, match=re.escape(f"{path}, line 31")):
        read_orbex(fh)


def test_error_names_stream():
    with pytest.raises(FileFormatError, match="^<stream>, line 1: expected an ORBEX version"):
        read_orbex(io.StringIO("%=SP3 0.09\n"))


def test_not_a_source():
    with pytest.raises(TypeError, match="source must be a path .* got list"):
        read_orbex([])


# --- errors --------------------------------------------------------------------------


def check_error(tmp_path, changes, match):
    path = write_modified(tmp_path, changes)
    with pytest.raises(FileFormatError, match=match) as info:
        read_orbex(path)
    assert str(path) in str(info.value)
    return info.value


def test_empty_file(tmp_path):
    path = tmp_path / "empty.obx"
    path.write_text("")
    with pytest.raises(FileFormatError,
                       match=r"empty\.obx, line 1: expected an ORBEX version line '%=ORBEX "
                       r"<version>' \(the file is empty\), got end of file"):
        read_orbex(path)


@pytest.mark.parametrize("first", ["%=ORBEX", "%=ORBEXX 0.09", "ORBEX 0.09", ""])
def test_garbled_version_line(tmp_path, first):
    err = check_error(tmp_path, {1: first},
                      r"bad\.obx, line 1: expected an ORBEX version line '%=ORBEX <version>'")
    assert err.lineno == 1


def test_no_ephemeris_data_block(tmp_path):
    lines = sample_lines()[:26]
    path = tmp_path / "bad.obx"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(FileFormatError,
                       match=r"bad\.obx, line 27: expected a '\+EPHEMERIS/DATA' block \(this "
                       r"ORBEX file has none\), got end of file"):
        read_orbex(path)


def test_unknown_time_system(tmp_path):
    check_error(tmp_path, {10: " TIME_SYSTEM         GLONASS"},
                r"bad\.obx, line 10: expected a TIME_SYSTEM, one of GPS, GAL, QZS, IRN, BDT, "
                r"TAI, TT, UTC, GLO, got ' TIME_SYSTEM         GLONASS'")


def test_missing_time_system(tmp_path):
    check_error(tmp_path, {10: None},
                r"bad\.obx, line 26: expected a TIME_SYSTEM line in the \+FILE/DESCRIPTION "
                r"block before the '\+EPHEMERIS/DATA' block, got '\+EPHEMERIS/DATA'")


@pytest.mark.parametrize("line", [
    "## 2023 01 25 00 00 3x.000000000000   2",
    "## 2023 01 32 00 00 30.000000000000   2",
    "## 2023 01 25 00 00",
])
def test_epoch_line_unparsable(tmp_path, line):
    check_error(tmp_path, {34: line},
                r"bad\.obx, line 34: expected an epoch line '## yyyy mm dd hh mm "
                r"ss.ssssssssssss n' with a valid date and time, got '" + re.escape(line))


@pytest.mark.parametrize("line", [
    " ATT G01              4  0.0349994571923221  0.1941937123721363 -0.7315566977199698",
    " ATT G01              3  0.0349994571923221  0.1941937123721363 -0.7315566977199698",
    " ATT G01              4  0.0349994571923221  0.1941937123721363 -0.7315566977199698 "
    "-0.6526014389291870 0.1",
    " ATT G01              5  0.0349994571923221  0.1941937123721363 -0.7315566977199698 "
    "-0.6526014389291870 0.1",
    " ATT 4  0.0349994571923221  0.1941937123721363 -0.7315566977199698 -0.6526014389291870",
])
def test_att_record_with_wrong_number_of_values(tmp_path, line):
    check_error(tmp_path, {35: line},
                r"bad\.obx, line 35: expected an ATT record ' ATT <sat> 4 q0 q1 q2 q3' with "
                r"four numbers, got ' ATT")


def test_att_record_with_unparsable_number(tmp_path):
    line = " ATT G01              4  0.0349994571923221  0.19419371237213e3x -0.73 -0.65"
    check_error(tmp_path, {35: line},
                r"bad\.obx, line 35: expected an ATT record .* four numbers, got ' ATT G01 ")


def test_att_record_before_first_epoch(tmp_path):
    check_error(tmp_path, {30: None},
                r"bad\.obx, line 30: expected an epoch line '## yyyy mm dd hh mm ss n' before "
                r"the first record")


def test_duplicate_att_record(tmp_path):
    lines = sample_lines()
    check_error(tmp_path, {36: lines[34]},
                r"bad\.obx, line 36: expected one ATT record per satellite and epoch, not a "
                r"second one for G01")


def test_garbage_in_data_block(tmp_path):
    check_error(tmp_path, {36: "ATT G05 4 0.1 0.2 0.3 0.4"},
                r"bad\.obx, line 36: expected an epoch line .* or '-EPHEMERIS/DATA', "
                r"got 'ATT G05 4 0.1 0.2 0.3 0.4'")


def test_truncated_data_block(tmp_path):
    lines = sample_lines()[:39]
    path = tmp_path / "bad.obx"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(FileFormatError,
                       match=r"bad\.obx, line 40: expected '-EPHEMERIS/DATA' closing the data "
                       r"block \(the file seems truncated\), got end of file"):
        read_orbex(path)


def test_missing_end_line(tmp_path):
    check_error(tmp_path, {43: None},
                r"bad\.obx, line 43: expected the last line '%END_ORBEX' \(the file seems "
                r"truncated\), got end of file")


# --- a day of 30-s attitude for 100 satellites ---------------------------------------------


def test_large_file(tmp_path):
    nepoch, sats = 2880, [f"{c}{n:02d}" for c in "GREC" for n in range(1, 26)]
    rng = np.random.default_rng(2023)
    q = rng.normal(size=(nepoch, len(sats), 4))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    q = np.round(q, 16)
    header = "\n".join([
        "%=ORBEX  0.09", "%%", "+FILE/DESCRIPTION", " TIME_SYSTEM         GPS",
        " COORD_SYSTEM        IGS20", " FRAME_TYPE          ECEF", " LIST_OF_REC_TYPES   ATT",
        "-FILE/DESCRIPTION", "+EPHEMERIS/DATA",
    ])
    record = "".join(f" ATT {sat}              4 %19.16f %19.16f %19.16f %19.16f\n" for sat in sats)
    path = tmp_path / "day.obx"
    with open(path, "w") as fh:
        fh.write(header + "\n")
        for e in range(nepoch):
            hour, rest = divmod(30 * e, 3600)
            minute, second = divmod(rest, 60)
            fh.write(f"## 2023 01 25 {hour:02d} {minute:02d} {second:2d}.000000000000 100\n")
            fh.write(record % tuple(q[e].ravel()))
        fh.write("-EPHEMERIS/DATA\n%END_ORBEX\n")

    data = read_orbex(path)
    assert data.satellites == tuple(sats)
    assert sum(len(data.attitude[sat][1]) for sat in sats) == 288000
    for k in (0, 37, 99):
        times, quats = data.attitude[sats[k]]
        assert times.shape == (nepoch,)
        np.testing.assert_allclose(quats, q[:, k], rtol=0, atol=1e-16)
    times = data.attitude["C25"][0]
    assert same_instant(times[-1], Time("2023-01-25T23:59:12", scale="utc"))
    assert np.allclose(np.diff(times.tai.mjd) * 86400, 30.0, atol=1e-6)
