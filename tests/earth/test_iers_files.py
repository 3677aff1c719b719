# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The IERS tables astropy ships, read by their fixed columns: the same bits as
astropy's own reader (its CDS table reader and ``IERS_Auto``'s combination of
Bulletins A and B and the C04 series), and clear errors on damaged files."""

from pathlib import Path

import numpy as np
import pytest
from astropy import units as u
from astropy.utils import iers

from astropy_feedrot.earth import eop
from astropy_feedrot.earth.iers_files import (
    COMBINES_OFFLINE,
    bundled_arrays,
    c04_arrays,
    combined_arrays,
    read_eopc04,
    read_finals2000a,
)
from astropy_feedrot.io import FileFormatError


def _columns(table):
    mjd = table["MJD"].to_value(u.day)
    return (mjd, u.Quantity(table["UT1_UTC"]).to_value(u.s),
            u.Quantity(table["PM_x"]).to_value(u.rad), u.Quantity(table["PM_y"]).to_value(u.rad),
            float(table.meta.get("predictive_mjd", mjd[-1] + 1)))


@pytest.fixture(scope="module")
def astropys():
    """astropy's own combination of the bundled files, read by astropy's reader."""
    with iers.conf.set_temp("auto_download", False):
        return _columns(iers.IERS_Auto.read(iers.IERS_A_FILE))


@pytest.fixture
def offline():
    """The table astropy's IERS_Auto serves offline, read afresh by astropy."""
    with iers.conf.set_temp("auto_download", False):
        kept, iers.IERS_Auto.iers_table = iers.IERS_Auto.iers_table, None
        try:
            yield _columns(iers.IERS_Auto.open())
        finally:
            iers.IERS_Auto.iers_table = kept


def _same(ours, astropys):
    for mine, theirs in zip(ours[:4], astropys[:4]):
        np.testing.assert_array_equal(mine, theirs)
    assert ours[4] == astropys[4]


def test_bundled_tables_bit_for_bit_astropys(astropys):
    _same(combined_arrays(iers.IERS_A_FILE, iers.IERS_B_FILE), astropys)


def test_the_table_astropy_serves_offline(offline):
    # Astropy 7 combines A and B offline; astropy 6 serves B alone.
    _same(bundled_arrays(), offline)
    assert (offline[0][0] == 37665.0) != COMBINES_OFFLINE  # C04 starts in 1962


def test_c04_alone_is_astropys_iers_b():
    with iers.conf.set_temp("auto_download", False):
        _same(c04_arrays(iers.IERS_B_FILE), _columns(iers.IERS_B.open(iers.IERS_B_FILE)))


def test_c04_columns_are_astropys():
    with iers.conf.set_temp("auto_download", False):
        table = iers.IERS_B.open(iers.IERS_B_FILE)
    c04 = read_eopc04(iers.IERS_B_FILE)
    np.testing.assert_array_equal(c04.mjd, table["MJD"].to_value(u.day))
    np.testing.assert_array_equal(c04.ut1_utc, table["UT1_UTC"].to_value(u.s))
    np.testing.assert_array_equal(c04.pm_x, table["PM_x"].to_value(u.arcsec))


def test_lines_of_other_lengths_read_alike(astropys, tmp_path):
    # Trailing blanks stripped and Windows line ends: the line-by-line path.
    lines = Path(iers.IERS_A_FILE).read_bytes().splitlines()
    finals = tmp_path / "finals2000A.all"
    finals.write_bytes(b"".join(line.rstrip() + b"\r\n" for line in lines))
    _same(combined_arrays(finals, iers.IERS_B_FILE), astropys)


def test_blank_bulletin_b_is_nan():
    a, b, pm_flags, ut1_flags = read_finals2000a(iers.IERS_A_FILE)
    # Bulletin B stops long before the predictions end; astropy's masked values.
    assert np.isnan(b.ut1_utc[-1]) and np.isfinite(b.ut1_utc[0])
    assert set(np.unique(pm_flags)) <= {b"I", b"P", b""}


def _damaged(tmp_path, line, first, text):
    lines = Path(iers.IERS_A_FILE).read_bytes().splitlines(keepends=True)
    lines[line - 1] = lines[line - 1][:first - 1] + text + lines[line - 1][first - 1 + len(text):]
    path = tmp_path / "finals2000A.all"
    path.write_bytes(b"".join(lines))
    return path


def test_a_field_that_is_not_a_number(tmp_path):
    path = _damaged(tmp_path, 7, 59, b"0.8x84178 ")
    with pytest.raises(FileFormatError, match=r"line 7: expected a number for UT1_UTC_A "
                       r"\(columns 59-68\), got '0.8x84178'"):
        read_finals2000a(path)


def test_a_line_too_long(tmp_path):
    path = _damaged(tmp_path, 3, 186, b"99")
    with pytest.raises(FileFormatError, match="line 3: expected a line of at most 185 characters"):
        read_finals2000a(path)


def test_an_empty_file(tmp_path):
    path = tmp_path / "eopc04.1962-now"
    path.write_bytes(b"# only a comment\n")
    with pytest.raises(FileFormatError, match="line 1: expected lines of numbers, got end of file"):
        read_eopc04(path)


def test_c04_days_that_do_not_match(tmp_path):
    lines = Path(iers.IERS_B_FILE).read_bytes().splitlines(keepends=True)
    # The C04 series with a day missing from 1974: its days no longer match.
    day = next(k for k, line in enumerate(lines) if line.startswith(b"1974   1   1"))
    path = tmp_path / "eopc04.1962-now"
    path.write_bytes(b"".join(lines[:day] + lines[day + 1:]))
    with pytest.raises(FileFormatError, match="expected the days of the Bulletin B values"):
        combined_arrays(iers.IERS_A_FILE, path)


def test_astropys_reader_where_the_columns_do_not_parse(monkeypatch, offline):
    # eop falls back on astropy's own reader (the same arrays, slower).
    def damaged():
        raise FileFormatError("finals2000A.all", 1, "a number", "x")

    monkeypatch.setattr(eop, "bundled_arrays", damaged)
    with iers.conf.set_temp("auto_download", False):
        _same(eop._bundled_arrays(), offline)
