# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Reading SP3-c and SP3-d orbit files: values, missing data, time systems, errors."""

import io
import pathlib
import re

import numpy as np
import pytest
from astropy import units as u
from astropy.time import Time
from helpers import SOURCE_KINDS, SP3_DESCRIPTORS, read_as

import astropy_feedrot.data
from astropy_feedrot import OrbitWarning, SP3Orbit
from astropy_feedrot.io import FileFormatError, SP3Data, read_sp3
from astropy_feedrot.io.sp3 import implausible_positions

DATA = pathlib.Path(__file__).parent.parent / "data"
SAMPLES = pathlib.Path(astropy_feedrot.data.__file__).parent
SAMPLE = SAMPLES / "sample.sp3"
SAMPLE_D = DATA / "sample_d.sp3"


def sample_lines(path=SAMPLE):
    return path.read_text().splitlines()


def write_modified(tmp_path, changes, name="bad.sp3", path=SAMPLE):
    """Copy a sample with 1-based lines replaced (str) or deleted (None)."""
    lines = sample_lines(path)
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


# --- the SP3-c sample -------------------------------------------------------------


def test_sample_header():
    data = read_sp3(SAMPLE)
    assert isinstance(data, SP3Data)
    assert data.version == "c"  # line 1 '#c'
    assert data.time_system == "GPS"  # line 13, columns 10-12
    assert data.coordinate_system == "IGS20"  # line 1, columns 47-51
    assert data.satellites == ("G01", "G05", "E11")  # line 3
    assert repr(data) == (
        "<SP3Data version='c' time_system='GPS' coordinate_system='IGS20' "
        "3 satellites, 4 epochs>"
    )


def test_sample_epochs_gps_to_utc():
    data = read_sp3(SAMPLE)
    assert data.epochs.shape == (4,)
    assert data.epochs.scale == "tai"
    # Line 23: GPS 2023-01-25 00:00:00; GPS - UTC = 18 s in 2023.
    assert same_instant(data.epochs[0], Time("2023-01-24T23:59:42", scale="utc"))
    assert data.epochs[0].utc.isot == "2023-01-24T23:59:42.000"
    # Lines 27, 30, 34: 15-minute steps.
    assert np.allclose((data.epochs[1:] - data.epochs[:-1]).to_value(u.s), 900.0, atol=1e-6)


def test_sample_positions_and_clock():
    data = read_sp3(SAMPLE)
    # Values written in astropy_feedrot/data/sample.sp3 line 24 (km and microseconds).
    np.testing.assert_allclose(
        data.positions["G01"][0], [5364995.752, -25736687.425, 3778007.538], rtol=0, atol=1e-6
    )
    assert data.clock["G01"][0] == pytest.approx(-89.426574e-6, rel=1e-12)
    # Line 37: E11 at 00:45.
    np.testing.assert_allclose(
        data.positions["E11"][3], [1175372.818, -19329064.429, 22386731.942], rtol=0, atol=1e-6
    )
    assert data.clock["E11"][3] == pytest.approx(-623.001081e-6, rel=1e-12)
    # GPS orbits: 26,560 km from the geocentre.
    radius = np.linalg.norm(data.positions["G01"], axis=1)
    np.testing.assert_allclose(radius, 26560e3, atol=1.0)
    for sat in data.satellites:
        assert data.positions[sat].shape == (4, 3)
        assert data.clock[sat].shape == (4,)


def test_missing_record_is_nan():
    data = read_sp3(SAMPLE)
    # Lines 27-29: the epoch 00:15 has no E11 record.
    assert np.all(np.isnan(data.positions["E11"][1]))
    assert np.isnan(data.clock["E11"][1])
    assert np.all(np.isfinite(data.positions["G01"]))


def test_bad_clock_is_nan():
    data = read_sp3(SAMPLE)
    # Line 33: E11 clock 999999.999999, position valid.
    assert np.isnan(data.clock["E11"][2])
    np.testing.assert_allclose(
        data.positions["E11"][2], [-532402.999, -18162488.511, 23366654.834], rtol=0, atol=1e-6
    )


def test_zero_position_is_nan():
    data = read_sp3(SAMPLE)
    # Line 36: G05 position 0.000000 0.000000 0.000000, clock valid.
    assert np.all(np.isnan(data.positions["G05"][3]))
    assert data.clock["G05"][3] == pytest.approx(412.120141e-6, rel=1e-12)


def test_position_999999_is_nan():
    # 999999.999999 is the format's bad/absent value; read as km it would put the
    # satellite 1.7e9 m out. Line 24 is G01's first record.
    lines = sample_lines()
    lines[23] = "PG01 999999.999999 999999.999999 999999.999999    -89.426574"
    data = read_sp3(io.StringIO("\n".join(lines) + "\n"))
    assert np.all(np.isnan(data.positions["G01"][0]))
    assert np.all(np.isfinite(data.positions["G01"][1:3]))


def test_position_inside_the_earth_is_nan_with_a_warning():
    # 3,000 km from the geocentre: no satellite orbits there (the radius check needs no
    # neighbouring epochs, so it works on the four-epoch sample).
    lines = sample_lines()
    lines[23] = "PG01   3000.000000      0.000000      0.000000    -89.426574"
    with pytest.warns(OrbitWarning, match=r"^sample\.sp3: 1 position record\(s\) no orbit can "
                      r"have \(the first: G01 on line 24, 3000 km from the geocentre, .*treated "
                      r"as missing \(NaN\), never interpolated$"):
        data = read_sp3(write_lines(lines, "sample.sp3"))
    assert np.all(np.isnan(data.positions["G01"][0]))


def write_lines(lines, name):
    stream = io.StringIO("\n".join(lines) + "\n")
    stream.name = name
    return stream


@pytest.mark.parametrize("seconds, km", [(300.0, 1000.0), (900.0, 1000.0), (300.0, 10.0)])
def test_single_record_jump_of_a_gnss_orbit(seconds, km):
    # A 12-hour circular orbit sampled like IGS files (5 and 15 minutes), one record
    # moved along x: the fourth difference of the neighbours gives it away (a 10 km jump
    # too at 5 minutes, where the allowance for a smooth GPS orbit is 5 km).
    t = np.arange(30) * seconds
    angle = 2 * np.pi * t / 43082.0
    xyz = 26.56e6 * np.stack([np.cos(angle), np.sin(angle), 0 * t], axis=-1)
    assert not np.any(implausible_positions(["G01"], xyz[np.newaxis], t, seconds))
    for k in (0, 1, 13, 28, 29):
        moved = xyz.copy()
        moved[k, 0] += km * 1e3
        bad = implausible_positions(["G01"], moved[np.newaxis], t, seconds)
        assert np.flatnonzero(bad[0]).tolist() == [k]


def test_arrays_are_read_only():
    data = read_sp3(SAMPLE)
    with pytest.raises(ValueError, match="read-only"):
        data.positions["G01"][0, 0] = 0.0
    with pytest.raises(ValueError, match="read-only"):
        data.clock["G01"][0] = 0.0


# --- SP3-d ----------------------------------------------------------------------


def test_sp3d_sample():
    data = read_sp3(SAMPLE_D)
    assert data.version == "d"
    assert data.time_system == "GPS"
    assert data.coordinate_system == "IGS20"
    assert data.satellites == ("G01", "G05", "E11", "R09", "C20", "J03")
    assert len(data.epochs) == 2
    assert same_instant(data.epochs[1], Time("2023-01-24T23:59:42", scale="utc") + 5 * u.min)
    # Line 48: R09 at 00:05; velocity (V) and correlation (EP, EV) records skipped.
    np.testing.assert_allclose(
        data.positions["R09"][1], [8551038.751, -14143704.668, -19431815.523], rtol=0, atol=1e-6
    )
    assert data.clock["R09"][1] == pytest.approx(35.870121e-6, rel=1e-12)
    # Line 50: flags in columns 75-80 do not disturb the values.
    np.testing.assert_allclose(
        data.positions["C20"][1], [-13290563.727, 17871911.317, 16803740.706], rtol=0, atol=1e-6
    )
    # Lines 37 and 52: J03 clock 999999.999999 at both epochs.
    assert np.all(np.isnan(data.clock["J03"]))
    assert np.all(np.isfinite(data.positions["J03"]))
    # J03 is a QZSS satellite in inclined geosynchronous orbit: 42,164 km.
    np.testing.assert_allclose(np.linalg.norm(data.positions["J03"], axis=1), 42164e3, atol=1.0)


def test_sp3d_comment_lines_anywhere_in_header():
    lines = sample_lines(SAMPLE_D)
    # An extra comment between the '+' and the '++' lines, and before the epoch.
    lines.insert(7, "/* A COMMENT AMONG THE SATELLITE LINES")
    lines.insert(24, "/* ANOTHER JUST BEFORE THE FIRST EPOCH")
    data = read_sp3(io.StringIO("\n".join(lines) + "\n"))
    assert data.satellites == ("G01", "G05", "E11", "R09", "C20", "J03")
    assert data.clock["G01"][0] == pytest.approx(-89.426574e-6, rel=1e-12)


def make_sp3d(nsat, nepoch, interval=300.0):
    """An SP3-d file with more than 85 satellites (more than five '+' lines)."""
    systems = "GRECJ"
    sats = [f"{systems[k % 5]}{k // 5 + 1:02d}" for k in range(nsat)]
    nlines = max(5, -(-nsat // 17))
    ids = sats + ["  0"] * (17 * nlines - nsat)
    lines = [
        f"#dP2023  1 25  0  0  0.00000000 {nepoch:7d} ORBIT IGS20 FIT  XYZ",
        "## 2246 259200.00000000   300.00000000 59969 0.0000000000000",
    ]
    for k in range(nlines):
        head = f"+  {nsat:3d}   " if k == 0 else "+        "
        lines.append(head + "".join(ids[17 * k:17 * (k + 1)]))
    for k in range(nlines):
        lines.append("++       " + "  5" * 17)
    lines += SP3_DESCRIPTORS + ["/* SYNTHETIC"]
    angle = np.arange(nepoch)[:, None] * 1e-3 + np.arange(nsat)[None, :] * 0.05
    x = 26560.0 * np.cos(angle)
    y = 26560.0 * np.sin(angle)
    clk = np.arange(nsat)[None, :] * 1.5 + np.arange(nepoch)[:, None] * 1e-4
    for e in range(nepoch):
        seconds = e * interval
        hour, rest = divmod(seconds, 3600)
        minute, second = divmod(rest, 60)
        lines.append(f"*  2023  1 25 {int(hour):2d} {int(minute):2d} {second:11.8f}")
        for k, sat in enumerate(sats):
            lines.append(f"P{sat}{x[e, k]:14.6f}{y[e, k]:14.6f}{0.0:14.6f}{clk[e, k]:14.6f}")
    lines.append("EOF")
    return "\n".join(lines) + "\n", sats, x, y, clk


def test_sp3d_more_than_85_satellites_and_a_day(tmp_path):
    # A day at 5 min with 120 satellites: eight '+' lines, 34,560 records.
    text, sats, x, y, clk = make_sp3d(120, 288)
    path = tmp_path / "big.sp3"
    path.write_text(text)
    data = read_sp3(path)
    assert data.version == "d"
    assert data.satellites == tuple(sats)
    assert len(data.satellites) == 120
    assert len(data.epochs) == 288
    assert same_instant(data.epochs[-1] - data.epochs[0], 287 * 300 * u.s)
    for k in (0, 84, 85, 119):
        sat = sats[k]
        np.testing.assert_allclose(data.positions[sat][:, 0], x[:, k] * 1e3, rtol=0, atol=1e-3)
        np.testing.assert_allclose(data.positions[sat][:, 1], y[:, k] * 1e3, rtol=0, atol=1e-3)
        np.testing.assert_allclose(data.clock[sat], clk[:, k] * 1e-6, rtol=0, atol=1e-12)


def test_sp3d_first_satellite_of_the_sixth_plus_line():
    text, sats, x, y, clk = make_sp3d(86, 1)
    data = read_sp3(io.StringIO(text))
    assert data.satellites[85] == sats[85]
    assert data.positions[sats[85]][0, 0] == pytest.approx(x[0, 85] * 1e3, abs=1e-3)


# --- older versions ------------------------------------------------------------------


def test_sp3a_style_satellite_ids():
    lines = sample_lines()
    lines[0] = "#a" + lines[0][2:]
    lines[2] = "+    3     1G 5E11  0  0  0  0  0  0  0  0  0  0  0  0  0  0"
    lines[12] = "%c cc cc ccc ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc"
    lines = [
        "P  1" + line[4:] if line.startswith("PG01") else
        "PG 5" + line[4:] if line.startswith("PG05") else line
        for line in lines
    ]
    data = read_sp3(io.StringIO("\n".join(lines) + "\n"))
    assert data.version == "a"
    assert data.time_system == "GPS"  # left open ('ccc'), GPS for SP3-a/b
    assert data.satellites == ("G01", "G05", "E11")
    np.testing.assert_allclose(
        data.positions["G01"][0], [5364995.752, -25736687.425, 3778007.538], rtol=0, atol=1e-6
    )
    assert data.clock["G05"][1] == pytest.approx(412.122351e-6, rel=1e-12)


# --- sources ---------------------------------------------------------------------


@pytest.mark.parametrize("kind", SOURCE_KINDS)
def test_sources(kind, tmp_path):
    data = read_as(kind, read_sp3, SAMPLE, tmp_path)
    assert data.satellites == ("G01", "G05", "E11")
    assert data.clock["G01"][0] == pytest.approx(-89.426574e-6, rel=1e-12)


def test_crlf_line_ends():
    text = SAMPLE.read_text().replace("\n", "\r\n")
    data = read_sp3(io.BytesIO(text.encode()))
    assert data.clock["G05"][3] == pytest.approx(412.120141e-6, rel=1e-12)


def test_error_names_open_file(tmp_path):
    path = write_modified(tmp_path, {28: "PG01   abc"})
    with open(path) as fh, pytest.raises(FileFormatError, match=re.escape(f"{path}, line 28")):
        read_sp3(fh)


def test_error_names_stream():
    with pytest.raises(FileFormatError, match="^<stream>, line 1: "):
        read_sp3(io.StringIO("not an sp3 file\n"))


def test_not_a_source():
    with pytest.raises(TypeError, match="source must be a path .* got int"):
        read_sp3(42)


# --- time systems ------------------------------------------------------------------


def with_time_system(code):
    lines = sample_lines()
    lines[12] = lines[12][:9] + f"{code:3s}" + lines[12][12:]
    return io.StringIO("\n".join(lines) + "\n")


@pytest.mark.parametrize(
    "code, utc",
    [
        ("GPS", "2023-01-24T23:59:42"),  # TAI - 19 s
        ("GAL", "2023-01-24T23:59:42"),  # TAI - 19 s
        ("QZS", "2023-01-24T23:59:42"),  # TAI - 19 s
        ("IRN", "2023-01-24T23:59:42"),  # TAI - 19 s
        ("BDT", "2023-01-24T23:59:56"),  # TAI - 33 s
        ("TAI", "2023-01-24T23:59:23"),  # TAI - UTC = 37 s
        ("TT", "2023-01-24T23:58:50.816"),  # TT - TAI = 32.184 s
        ("UTC", "2023-01-25T00:00:00"),
        ("GLO", "2023-01-25T00:00:00"),  # the GLONASS UTC time system: UTC
    ],
)
def test_time_systems(code, utc):
    # The first epoch (line 23) reads 2023-01-25 00:00:00 in the file's time system.
    data = read_sp3(with_time_system(code))
    assert data.time_system == code.strip()
    assert same_instant(data.epochs[0], Time(utc, scale="utc"))
    assert data.epochs.scale in ("tai", "utc")


def test_glonass_time_is_utc_not_moscow():
    # SP3-c/d call GLO "the GLONASS UTC time system": time tags in UTC, not UTC + 3 h.
    glo = read_sp3(with_time_system("GLO")).epochs
    utc = read_sp3(with_time_system("UTC")).epochs
    assert same_instant(glo, utc)
    assert glo.scale == "utc"


def test_unknown_time_system(tmp_path):
    line = "%c M  cc XYZ ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc"
    path = write_modified(tmp_path, {13: line})
    with pytest.raises(FileFormatError,
                       match=r"bad\.sp3, line 13: expected a time system .* one of GPS, GAL, "
                       r"QZS, IRN, BDT, TAI, TT, UTC, GLO, got '%c M  cc XYZ"):
        read_sp3(path)


def test_placeholder_time_system_in_sp3c_is_an_error(tmp_path):
    line = "%c M  cc ccc ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc"
    path = write_modified(tmp_path, {13: line})
    with pytest.raises(FileFormatError, match=r"bad\.sp3, line 13: expected a time system"):
        read_sp3(path)


# --- errors ------------------------------------------------------------------------


def check_error(tmp_path, changes, match):
    path = write_modified(tmp_path, changes)
    with pytest.raises(FileFormatError, match=match) as info:
        read_sp3(path)
    assert str(path) in str(info.value)
    return info.value


def test_empty_file(tmp_path):
    path = tmp_path / "empty.sp3"
    path.write_text("")
    with pytest.raises(FileFormatError,
                       match=r"empty\.sp3, line 1: expected an SP3 version line .* "
                       r"\(the file is empty\), got end of file"):
        read_sp3(path)


@pytest.mark.parametrize("first", [
    "",
    "SP3 FILE",
    "#eP2023  1 25  0  0  0.00000000       4 ORBIT IGS20 HLM  IGS",
    "#cX2023  1 25  0  0  0.00000000       4 ORBIT IGS20 HLM  IGS",
])
def test_garbled_version_line(tmp_path, first):
    err = check_error(tmp_path, {1: first},
                      r"bad\.sp3, line 1: expected an SP3 version line '#c' or '#d'")
    assert err.lineno == 1
    assert err.found == first


def test_missing_second_header_line(tmp_path):
    check_error(tmp_path, {2: None}, r"bad\.sp3, line 2: expected the second header line '##")


def test_epoch_line_unparsable(tmp_path):
    check_error(tmp_path, {27: "*  2023  1 25  0 1x  0.00000000"},
                r"bad\.sp3, line 27: expected an epoch line '\*  yyyy mm dd hh mm ss.ssssssss' "
                r"with a valid date and time, got '\*  2023  1 25  0 1x  0.00000000'")


@pytest.mark.parametrize("line", [
    "*  2023 13 25  0 15  0.00000000",  # month 13
    "*  2023  2 30  0 15  0.00000000",  # 30 February
    "*  2023  1 25  0 15 60.00000000",  # second 60 in GPS time
    "*  2023  1 25  0 15",  # too short
])
def test_epoch_line_invalid_date(tmp_path, line):
    check_error(tmp_path, {27: line}, r"bad\.sp3, line 27: expected an epoch line")


def test_unparsable_number_in_record(tmp_path):
    bad = "PG01   5572.730146 -25129.1x4480   6550.066506    -89.426262"
    check_error(tmp_path, {28: bad},
                r"bad\.sp3, line 28: expected a position record 'P<sat> x y z clock' "
                r"\(numbers in columns 5-60\), got 'PG01   5572.730146 -25129.1x4480")


def test_unparsable_clock_in_record(tmp_path):
    bad = "PG01   5572.730146 -25129.164480   6550.066506    -89.42x262"
    check_error(tmp_path, {28: bad}, r"bad\.sp3, line 28: expected a position record")


def test_missing_clock_field_is_nan(tmp_path):
    path = write_modified(tmp_path, {28: "PG01   5572.730146 -25129.164480   6550.066506"})
    data = read_sp3(path)
    assert np.isnan(data.clock["G01"][1])
    assert data.positions["G01"][1, 0] == pytest.approx(5572730.146, abs=1e-6)


def test_record_for_satellite_not_in_header(tmp_path):
    bad = "PG07   5572.730146 -25129.164480   6550.066506    -89.426262"
    check_error(tmp_path, {28: bad},
                r"bad\.sp3, line 28: expected a record for one of the 3 satellites of the "
                r"header \(G01, G05, E11\), got 'PG07")


def test_duplicate_record(tmp_path):
    lines = sample_lines()
    check_error(tmp_path, {29: lines[27]},
                r"bad\.sp3, line 29: expected one record per satellite and epoch, not a "
                r"second one for G01")


def test_truncated_file_without_eof(tmp_path):
    check_error(tmp_path, {38: None},
                r"bad\.sp3, line 38: expected the last line 'EOF' \(the file seems "
                r"truncated\), got end of file")


def test_truncated_in_the_middle(tmp_path):
    lines = sample_lines()[:30]
    path = tmp_path / "bad.sp3"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(FileFormatError, match=r"bad\.sp3, line 31: expected the last line 'EOF'"):
        read_sp3(path)


def test_truncated_in_the_header(tmp_path):
    lines = sample_lines()[:12]
    path = tmp_path / "bad.sp3"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(FileFormatError,
                       match=r"bad\.sp3, line 13: expected more header lines or the first epoch "
                       r"line .* got end of file"):
        read_sp3(path)


def test_garbage_in_data_section(tmp_path):
    check_error(tmp_path, {31: "XG01 hello"},
                r"bad\.sp3, line 31: expected an epoch line .* or 'EOF', got 'XG01 hello'")


def test_record_in_header(tmp_path):
    bad = "PG01   5572.730146 -25129.164480   6550.066506    -89.426262"
    check_error(tmp_path, {19: bad}, r"bad\.sp3, line 19: expected a header line")


def test_satellite_count_disagrees_with_ids(tmp_path):
    check_error(tmp_path, {3: "+    4   G01G05E11  0  0  0  0  0  0  0  0  0  0  0  0  0  0"},
                r"bad\.sp3, line 23: expected 4 satellite IDs in the '\+' lines, as their "
                r"count says \(found 3\)")


def test_garbled_satellite_id_in_header(tmp_path):
    check_error(tmp_path, {3: "+    3   G01G?5E11  0  0  0  0  0  0  0  0  0  0  0  0  0  0"},
                r"bad\.sp3, line 3: expected satellite IDs such as 'G01'")


def test_garbled_satellite_count(tmp_path):
    check_error(tmp_path, {3: "+    x   G01G05E11  0  0  0  0  0  0  0  0  0  0  0  0  0  0"},
                r"bad\.sp3, line 3: expected the number of satellites")


def test_missing_time_system_line(tmp_path):
    check_error(tmp_path, {13: None, 14: None},
                r"bad\.sp3, line 21: expected a '%c' line with the time system before the "
                r"first epoch")


def test_error_is_a_value_error(tmp_path):
    err = check_error(tmp_path, {38: None}, "EOF")
    assert isinstance(err, ValueError)
    assert (err.filename, err.lineno, err.found) == (str(tmp_path / "bad.sp3"), 38, None)


def test_sp3_orbit_extrapolates_up_to_its_limit(tmp_path):
    """extrapolate: the end window's polynomial evaluated beyond the last epoch (as RTKLIB's
    pephpos, up to 900 s); further out, and beyond 900 s as an option, an error."""
    from astropy_feedrot.gnss.synthetic import constellation, write_sp3

    start = Time("2023-01-25T00:00:19", scale="tai")
    orbits = constellation(start, {"G": 1})
    write_sp3(tmp_path / "g.sp3", orbits, start, 12)  # 00:00 to 02:45
    data = read_sp3(tmp_path / "g.sp3")
    orbit = SP3Orbit(data, "G01", extrapolate=900 * u.s)
    after = data.epochs[-1] + [300, 900] * u.s
    # Independent: the SGP4 orbit the file was written from (10-point extrapolation over
    # one 15-minute interval: metres).
    error = np.linalg.norm(orbit.position(after) - orbits["G01"].position(after), axis=-1)
    assert np.all(error < 50.0)
    before = orbit.position(data.epochs[0] - 600 * u.s)
    assert np.linalg.norm(before - orbits["G01"].position(data.epochs[0] - 600 * u.s)) < 50.0
    with pytest.raises(ValueError, match=r"times outside the coverage of the SP3 orbit of G01: "
                                         r".* \(extrapolated up to 900 s beyond\)"):
        orbit.position(data.epochs[-1] + 901 * u.s)
    with pytest.raises(ValueError, match=r"extrapolate must be 0 to 900 s, got 1000.0 s"):
        SP3Orbit(data, "G01", extrapolate=1000 * u.s)
