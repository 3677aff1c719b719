# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The TLE file reader."""

import gzip
import io

import pytest

from astropy_feedrot import TLEOrbit
from astropy_feedrot.applied.simulations import GPS_SVN76_TLE
from astropy_feedrot.io import FileFormatError, read_tle

# Table 2 of the paper (GPS SVN 76) and the ISS element set of the CelesTrak
# documentation of the format (catalogue number 25544).
LINE1, LINE2 = GPS_SVN76_TLE
ISS = ("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927",
       "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537")


def test_two_and_three_line_forms_mixed():
    text = f"{LINE1}\n{LINE2}\n\nISS (ZARYA)\n{ISS[0]}\n{ISS[1]}\n"
    records = read_tle(io.StringIO(text))
    assert [(r.name, r.catalog_number) for r in records] == [
        ("41328", "41328"), ("ISS (ZARYA)", "25544")]
    assert records[1].line2 == ISS[1]
    # The records make valid orbits (checksums verified there).
    assert TLEOrbit(records[1].line1, records[1].line2).epoch.utc.iso.startswith("2008-09-20")


def test_space_track_3le_title_and_gzip(tmp_path):
    path = tmp_path / "gps.tle.gz"
    with gzip.open(path, "wt") as fh:
        fh.write(f"0 GPS SVN 76 (3LE)\r\n{LINE1}\r\n{LINE2}\r\n")
    (record,) = read_tle(path)
    assert record.name == "GPS SVN 76 (3LE)"
    assert (record.line1, record.line2) == GPS_SVN76_TLE


@pytest.mark.parametrize("text, match", [
    (f"{LINE1}\n", r"line 2: expected line 2 of the element set begun on line 1, got end of file"),
    (f"{LINE1}\nGPS\n{LINE2}\n", r"line 2: expected line 2 of an element set"),
    (f"GPS\n{LINE2}\n", r"line 2: expected a title or line 1 before line 2"),
    ("\n\n", r"expected at least one element set, got end of file"),
])
def test_malformed_files(text, match):
    with pytest.raises(FileFormatError, match=match):
        read_tle(io.StringIO(text))


def test_source_of_the_wrong_kind():
    with pytest.raises(TypeError, match="source must be a path"):
        read_tle(42)
