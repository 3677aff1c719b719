# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""RINEX body events, missing and malformed values, broken compressed input."""

import gzip
import io

import numpy as np
import pytest
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.time import Time

from astropy_feedrot.gnss import RinexReader, correct_rinex
from astropy_feedrot.gnss.synthetic import constellation, write_rinex, write_sp3
from astropy_feedrot.io import FileFormatError

START = Time("2023-01-25T00:00:19", scale="tai")  # 00:00 GPS time
COUNTS = {"G": 4}


@pytest.fixture(scope="module")
def sp3(tmp_path_factory):
    path = tmp_path_factory.mktemp("sp3") / "sim.sp3"
    write_sp3(path, constellation(START, COUNTS), START, 17)
    return path


def _lines(path):
    return path.read_text().splitlines(keepends=True)


def _rnx(tmp_path, version="3.04", epochs=6, name="a.rnx", **kwargs):
    types = {"G": ("C1C", "L1C", "L2W", "S1C")} if version[0] != "2" else {"*": ("C1", "L1")}
    path = tmp_path / name
    write_rinex(path, version, types, list(constellation(START, COUNTS)), START + 3600 * u.s,
                epochs, 30.0, **kwargs)
    return path


def _epoch_index(lines, k):
    """Index of the line of the k-th epoch record (RINEX 3)."""
    return [i for i, line in enumerate(lines) if line.startswith("> ")][k]


def _phase(path, prn, code):
    out = []
    with RinexReader(path) as reader:
        for record in reader:
            if record.observations and prn in record.satellites:
                i = record.satellites.index(prn)
                fields = [f for f in reader.header.phase_fields(prn[0]) if f[2] == code]
                out.append(record.value(i, *fields[0][:2]) if fields else None)
    return out


def test_zero_phase_is_missing(tmp_path, sp3):
    """RINEX writes a phase not measured as 0.000 (or blank): kept as it is, not corrected."""
    path = _rnx(tmp_path)
    lines = _lines(path)
    k = _epoch_index(lines, 2) + 1  # G01 at the third epoch
    lines[k] = lines[k][:19] + f"{0.0:14.3f}" + lines[k][33:]
    path.write_text("".join(lines))
    report = correct_rinex(path, tmp_path / "b.rnx", sp3)
    assert report.phases == 6 * 4 * 2 - 1
    assert _lines(tmp_path / "b.rnx")[k + 2][19:33] == "         0.000"  # two COMMENT lines


@pytest.mark.parametrize("field", ["**************", "   12345.6x789", "           nan"])
def test_unreadable_phase(tmp_path, sp3, field):
    path = _rnx(tmp_path)
    lines = _lines(path)
    k = _epoch_index(lines, 3) + 2  # G02 at the fourth epoch
    lines[k] = lines[k][:35] + field + lines[k][49:]
    path.write_text("".join(lines))
    with pytest.raises(FileFormatError, match=rf"a.rnx, line {k + 1}: expected a carrier phase "
                                              r"L2W of G02 as an F14.3 number in columns 36-49 "
                                              r"\(blank or 0.000 if missing\), got 'G02"):
        correct_rinex(path, tmp_path / "b.rnx", sp3)
    assert not (tmp_path / "b.rnx").exists()


def test_truncated_gzip(tmp_path, sp3):
    path = _rnx(tmp_path, epochs=200)
    data = gzip.compress(path.read_bytes())
    cut = tmp_path / "cut.rnx.gz"
    cut.write_bytes(data[:len(data) // 2])
    with pytest.raises(FileFormatError, match=r"cut.rnx.gz, line \d+: expected a complete "
                                              r"compressed file \(gzip or Compact RINEX\) that "
                                              r"decompresses, got 'EOFError: Compressed file "
                                              r"ended"):
        correct_rinex(cut, tmp_path / "b.rnx", sp3)
    assert not (tmp_path / "b.rnx").exists()


def test_truncated_compact_rinex_gzip(tmp_path, sp3):
    hatanaka = pytest.importorskip("hatanaka")
    path = _rnx(tmp_path, epochs=200)
    data = gzip.compress(hatanaka.rnx2crx(path.read_bytes()))
    cut = tmp_path / "cut.crx.gz"
    cut.write_bytes(data[:len(data) // 2])
    with pytest.raises(FileFormatError, match=r"cut.crx.gz, line 1: expected a complete "
                                              r"compressed file that decompresses, got "
                                              r"'EOFError"):
        correct_rinex(cut, tmp_path / "b.rnx", sp3)


def _event(lines, version="3"):
    """An event record of flag 4 (RINEX 3) holding header lines."""
    head = f">{'':30}4{len(lines):3d}\n" if version == "3" else f"{'':26}  4{len(lines):3d}\n"
    return [head] + [line if line.endswith("\n") else line + "\n" for line in lines]


def test_flag_4_new_observation_types_rinex_2(tmp_path, sp3):
    """A flag-4 event redefining # / TYPES OF OBSERV: the records after it are read by it.

    Before, the old list was kept: C1 and L1 swapped places, C1 was corrected
    and L1 not.
    """
    path = _rnx(tmp_path, version="2.11")
    lines = _lines(path)
    starts = [i for i, line in enumerate(lines) if line[28:29] == "0" and line[:3].strip()]
    k = starts[3]
    event = _event(["     2    L1    C1                                          "
                    "# / TYPES OF OBSERV"], version="2")
    body = lines[k + 1:]
    swapped = [line[16:32] + line[:16] + "\n" if len(line) > 17 else line for line in body]
    text = lines[:k] + event + [lines[k]] + swapped[:4]
    rest = lines[k + 5:]
    out = []
    for line in rest:  # every later satellite line swapped too
        out.append(line[16:32] + line[:16] + "\n" if line[28:29] != "0" else line)
    (tmp_path / "e.rnx").write_text("".join(text + out))
    report = correct_rinex(tmp_path / "e.rnx", tmp_path / "f.rnx", sp3)
    assert report.phases == 6 * 4
    before, after = _lines(tmp_path / "e.rnx"), _lines(tmp_path / "f.rnx")
    end = next(i for i, line in enumerate(before) if "END OF HEADER" in line)
    after = after[:end] + after[end + 2:]  # without the two COMMENT lines
    changed = [(a, b) for a, b in zip(before, after) if a != b]
    assert len(changed) == 6 * 4
    # The pseudoranges (C1, in columns 17-32 after the event) are kept byte for byte.
    assert all(a[16:] == b[16:] and a[:16] != b[:16] for a, b in changed[3 * 4:])


def test_flag_4_zero_direction_and_flag_3_position(tmp_path, sp3):
    """ANTENNA: ZERODIR AZI in an event turns the receiver from there on; flag 3 moves it."""
    path = _rnx(tmp_path, epochs=8)
    lines = _lines(path)
    k = _epoch_index(lines, 4)
    turn = _event(["       90.0000                                             "
                   " ANTENNA: ZERODIR AZI"])
    (tmp_path / "turned.rnx").write_text("".join(lines[:k] + turn + lines[k:]))
    plain = correct_rinex(path, tmp_path / "p.rnx", sp3, table=True)
    turned = correct_rinex(tmp_path / "turned.rnx", tmp_path / "t.rnx", sp3, table=True)
    a, b = plain.windup["windup"].value, turned.windup["windup"].value
    np.testing.assert_array_equal(a[:16], b[:16])
    # An antenna turned by 90 deg (east of north) changes the wind-up of an RHCP receiver by
    # a quarter cycle (Eq 30: the receiver dipoles turn by the azimuth), the same for every
    # satellite; carried on continuously (no new arc).
    np.testing.assert_allclose(np.abs(b[16:] - a[16:]), 0.25, atol=1e-9)
    assert turned.arcs == plain.arcs == 4
    # A new occupation (flag 3) with a position on the other side of the Earth.
    moved = [f">{'':30}3  1\n",
             f"{-1130730.179:14.4f}{4831245.954:14.4f}{-3994228.241:14.4f}{'':18}"
             "APPROX POSITION XYZ\n"]
    (tmp_path / "moved.rnx").write_text("".join(lines[:k] + moved + lines[k:]))
    again = correct_rinex(tmp_path / "moved.rnx", tmp_path / "m.rnx", sp3, table=True)
    c = again.windup["windup"].value
    np.testing.assert_array_equal(a[:16], c[:16])
    assert np.all(np.abs(c[16:] - a[16:]) > 1e-3)
    # Event records are written byte for byte.
    assert "".join(moved) in (tmp_path / "m.rnx").read_text()
    assert "".join(turn) in (tmp_path / "t.rnx").read_text()


def test_flag_4_new_obs_types_rinex_3(tmp_path, sp3):
    path = _rnx(tmp_path)
    lines = _lines(path)
    k = _epoch_index(lines, 3)
    event = _event(["G    2 L1C C1C                                              "
                    "SYS / # / OBS TYPES"])
    rest = []
    for line in lines[k:]:
        rest.append(line if line.startswith(">") else line[:3] + line[19:35] + line[3:19] + "\n")
    (tmp_path / "e.rnx").write_text("".join(lines[:k] + event + rest))
    report = correct_rinex(tmp_path / "e.rnx", tmp_path / "f.rnx", sp3)
    assert report.phases == 3 * 4 * 2 + 3 * 4


def test_zero_direction_xyz_refused(tmp_path, sp3):
    path = _rnx(tmp_path)
    lines = _lines(path)
    k = _epoch_index(lines, 2)
    event = _event(["        0.0000        1.0000        0.0000                  "
                    "ANTENNA: ZERODIR XYZ"])
    (tmp_path / "e.rnx").write_text("".join(lines[:k] + event + lines[k:]))
    with pytest.raises(ValueError, match=rf"e.rnx, line {k + 2}: ANTENNA: ZERODIR XYZ gives the "
                                         r"zero direction of a vehicle's antenna"):
        correct_rinex(tmp_path / "e.rnx", tmp_path / "f.rnx", sp3)


def test_event_flags_2_and_5_kept(tmp_path, sp3):
    path = _rnx(tmp_path)
    lines = _lines(path)
    k = _epoch_index(lines, 2)
    events = [f">{'':30}2  0\n", "> 2023 01 25 01 01 10.1234567  5  0\n"]
    (tmp_path / "e.rnx").write_text("".join(lines[:k] + events + lines[k:]))
    report = correct_rinex(tmp_path / "e.rnx", tmp_path / "f.rnx", sp3)
    assert report.phases == 6 * 4 * 2
    assert "".join(events) in (tmp_path / "f.rnx").read_text()


def test_stream_input(sp3, tmp_path):
    text = _rnx(tmp_path).read_text()
    report = correct_rinex(io.StringIO(text), tmp_path / "b.rnx", sp3)
    assert report.phases == 6 * 4 * 2


def test_position_given_survives_an_event_without_one(tmp_path, sp3):
    """position= overrides the header's; a later event that gives no position keeps it."""
    path = _rnx(tmp_path)  # the header's position: GGAO12M
    lines = _lines(path)
    k = _epoch_index(lines, 3)
    event = _event(["G    4 C1C L1C L2W S1C                                      "
                    "SYS / # / OBS TYPES"])
    (tmp_path / "e.rnx").write_text("".join(lines[:k] + event + lines[k:]))
    site = EarthLocation.from_geodetic(-70 * u.deg, 45 * u.deg, 0 * u.m)  # not the header's
    xyz = np.array(site.to_value(u.m).tolist())
    plain = correct_rinex(path, tmp_path / "p.rnx", sp3, position=xyz, table=True)
    again = correct_rinex(tmp_path / "e.rnx", tmp_path / "f.rnx", sp3, position=xyz, table=True)
    np.testing.assert_array_equal(plain.windup["windup"], again.windup["windup"])


def test_flag_4_more_types_rinex_2(tmp_path, sp3):
    """RINEX 2.11: an event raising the number of types from 2 to 6 (two lines per
    satellite from there on) is followed by the reader."""
    path = _rnx(tmp_path, version="2.11")
    lines = _lines(path)
    starts = [i for i, line in enumerate(lines) if line[28:29] == "0" and line[:3].strip()]
    k = starts[3]
    event = _event(["     6    C1    L1    L2    P2    S1    S2                  "
                    "# / TYPES OF OBSERV"], version="2")
    out = lines[:k] + event
    for i in starts[3:]:
        out.append(lines[i])
        for j in range(4):  # each satellite's one line becomes two
            one = lines[i + 1 + j].rstrip("\n")
            out += [one + f"{100000000.5:14.3f}  {20000000.0:14.3f}  {45.0:14.3f}  \n",
                    f"{46.0:14.3f}  \n"]
    (tmp_path / "e.rnx").write_text("".join(out))
    report = correct_rinex(tmp_path / "e.rnx", tmp_path / "f.rnx", sp3)
    assert report.phases == 3 * 4 + 3 * 4 * 2
