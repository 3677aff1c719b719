# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The wind-up correction on a real station file.

ESBC00DNK (a Septentrio PolaRx5 of SDFE, Denmark) on 2020-06-25, RINEX 3.05 from
georust/rinex's test resources, trimmed to nine satellites and four hours by
tests/data/real/make_esbc.py, with the same day's GRG (CNES/CLS) MGEX final orbits at
15 minutes, which end at 23:45. The file has 218 epochs where only R04's L3Q has its
loss-of-lock bit set (its other four phases not), among them 12:11:30, where R04's
continuous wind-up passes +0.5 cycle: before, the arc restarted there and
L1C/L1P/L2C/L2P, unflagged, jumped by one cycle.
"""

import gzip
import pathlib

import gnss_reference as ref
import numpy as np
import pytest
from astropy import units as u
from astropy.time import Time

from astropy_feedrot import OrbitWarning
from astropy_feedrot.gnss import RinexReader, correct_rinex
from astropy_feedrot.io import FileFormatError

REAL = pathlib.Path(__file__).parent.parent / "data" / "real"
OBS = REAL / "ESBC00DNK_R_20201770000_01D_30S_MO.trim.rnx.gz"
SP3 = REAL / "GRG0MGXFIN_20201770000_01D_15M_ORB.SP3.gz"
ESBC = np.array([3582105.2910, 532589.7313, 5232754.8054])  # APPROX POSITION XYZ

EXTRAPOLATED = ("29 epochs (2020-06-25T23:45:49.000 to 2020-06-25T23:59:49.000 TAI) lie up to "
                "900 s (one SP3 interval) outside the SP3 files (2020-06-25T00:00:19.000 to "
                "2020-06-25T23:45:19.000): their orbits are extrapolated, as RTKLIB does; give "
                "GRG0MGXFIN_20201780000_01D_15M_ORB.SP3 to interpolate them")
UNTOUCHED = "phases left untouched: C06: not in the SP3 files; J01: not in the SP3 files"


def _read(path):
    """Per (epoch, prn): {code: (value, lli)} of the L fields; and every line with L blanked."""
    phases, lines = {}, []
    with RinexReader(path) as reader:
        lines.extend(reader.header.lines)
        for record in reader:
            if record.observations:
                fields = reader.header
                for i, sat in enumerate(record.satellites):
                    got = {}
                    for line, col, code in fields.phase_fields(sat[0]):
                        got[code] = (record.value(i, line, col), record.lli(i, line, col))
                        if got[code][0] is not None:
                            record.set_value(i, line, col, 0.0)
                    phases[record.epoch, sat] = got
            lines.extend(record.lines)
    return phases, lines


@pytest.fixture(scope="module")
def corrected(tmp_path_factory):
    out = tmp_path_factory.mktemp("esbc") / "esbc.rnx"
    with pytest.warns(OrbitWarning) as caught:
        report = correct_rinex(OBS, out, SP3, table=True)
    assert [str(w.message) for w in caught] == [EXTRAPOLATED, UNTOUCHED]
    return report, _read(OBS), _read(out)


def test_counts(corrected):
    report, (before, _), _ = corrected
    assert (report.epochs, report.untouched_epochs, report.extrapolated_epochs) == (452, 0, 29)
    # An arc per run of a satellite with an orbit without a gap over 300 s, counted here
    # from the epochs where the file has its L values.
    runs = 0
    for prn in {p for _, p in before} - {"C06", "J01"}:
        t = np.array(sorted(e[3] * 3600 + e[4] * 60 + e[5] for e, p in before if p == prn
                            and any(v is not None for v, _ in before[e, p].values())))
        runs += 1 + int(np.count_nonzero(np.diff(t) > 300))
    assert report.arcs == runs == 9
    assert set(report.untouched) == {"C06", "J01"}


def test_no_step_in_any_phase(corrected):
    """Each satellite's correction is one continuous series, whatever its LLI flags.

    For every satellite: at every epoch, every phase loses the same number of cycles
    (up to the F14.3 rounding); from one epoch to the next (30 s), the correction changes
    by less than 0.02 cycle within a window, the flagged epochs included: no whole-cycle
    step in any phase, flagged or not.
    """
    _, (before, _), (after, _) = corrected
    flagged_steps = 0
    for prn in sorted({p for _, p in before}):
        epochs = sorted(e for e, p in before if p == prn)
        series, flags = [], []
        for epoch in epochs:
            removed = [before[epoch, prn][c][0] - after[epoch, prn][c][0]
                       for c in before[epoch, prn] if before[epoch, prn][c][0] is not None]
            if not removed:
                continue
            assert np.ptp(removed) <= 1.5e-3, (prn, epoch)
            series.append((epoch, np.mean(removed)))
            flags.append(any(lli & 1 for _, lli in before[epoch, prn].values()))
        if prn in ("C06", "J01"):  # no orbit: untouched
            assert all(abs(v) < 1e-9 for _, v in series)
            continue
        t = np.array([e[3] * 3600 + e[4] * 60 + e[5] for e, _ in series])
        v = np.array([v for _, v in series])
        same_window = np.diff(t) <= 30.5
        assert np.max(np.abs(np.diff(v)[same_window])) < 0.02, prn
        flagged_steps += int(np.count_nonzero(np.array(flags[1:]) & same_window))
    assert flagged_steps > 50  # R04, R12, E05 and E26's flagged epochs were crossed


def test_r04_at_12_11_30(corrected):
    """R04 at 12:11:30: only L3Q flagged; every phase loses the continuous wind-up, past 0.5."""
    _, (before, _), (after, _) = corrected
    epoch = (2020, 6, 25, 12, 11, 30.0)
    assert {c: lli & 1 for c, (_, lli) in before[epoch, "R04"].items()} == {
        "L1C": 0, "L1P": 0, "L2C": 0, "L2P": 0, "L3Q": 1}
    previous = (2020, 6, 25, 12, 11, 0.0)  # L3Q not tracked: blank
    assert before[previous, "R04"]["L3Q"][0] is None
    then = [before[previous, "R04"][c][0] - after[previous, "R04"][c][0]
            for c in ("L1C", "L1P", "L2C", "L2P")]
    now = [before[epoch, "R04"][c][0] - after[epoch, "R04"][c][0]
           for c in ("L1C", "L1P", "L2C", "L2P", "L3Q")]
    # The continuous wind-up goes on past +0.5 cycle (0.4998 -> 0.5004, as the table gives
    # it), not back to -0.4996; F14.3 rounding of the values aside.
    assert np.all((np.array(then) > 0.4985) & (np.array(then) < 0.5005))
    assert np.all((np.array(now) > 0.4995) & (np.array(now) < 0.5015))


def test_only_phases_change(corrected):
    """Every byte but the L values is kept: headers (plus two COMMENT lines), records, flags."""
    _, (_, original), (_, written) = corrected
    end = next(i for i, line in enumerate(original) if "END OF HEADER" in line)
    assert written[end:end + 2] == [
        "astropy_feedrot: L - WIND-UP (CYCLES, RHCP, NOMINAL YAW)    COMMENT             \n",
        "WIND-UP REMOVED FROM 6371 PHASES OF 7 SATELLITES            COMMENT             \n"]
    assert written[:end] + written[end + 2:] == original


def _sp3_positions(times, prn):
    """Positions of ``prn`` at ``times`` from the SP3 file, by a degree-9 polynomial fit
    (numpy) to the ten nearest epochs: independent of the package's Lagrange windows."""
    epochs, xyz = [], []
    with gzip.open(SP3, "rt") as fh:
        for line in fh:
            if line.startswith("*  "):
                f = line.split()
                epochs.append(Time(f"{f[1]}-{int(f[2]):02d}-{int(f[3]):02d}T{int(f[4]):02d}:"
                                   f"{int(f[5]):02d}:00", scale="tai") + 19 * u.s)
            elif line.startswith("P" + prn):
                xyz.append([float(v) * 1e3 for v in line[4:46].split()])
    t0 = epochs[0]
    seconds = np.array([(e - t0).sec for e in epochs])
    xyz = np.array(xyz)
    out = []
    for x in (times - t0).sec:
        k = np.clip(np.searchsorted(seconds, x) - 5, 0, len(seconds) - 10)
        s = seconds[k:k + 10]
        out.append([np.polynomial.Polynomial.fit(s, xyz[k:k + 10, c], 9)(x) for c in range(3)])
    return np.array(out)


@pytest.mark.parametrize("prn", ["G05", "E05", "R04"])
def test_against_independent_wu(prn, tmp_path):
    """Wu's wind-up (gnss_reference: Kouba's nominal yaw, astropy's Sun, east/north
    dipoles) from positions fitted to the SP3 records by numpy, every 10 minutes."""
    with pytest.warns(OrbitWarning):
        report = correct_rinex(OBS, tmp_path / "wu.rnx", SP3, form="wu", table=True)
    rows = report.windup[report.windup["prn"] == prn]
    pick = rows[::20]
    times = pick["time"]
    position = _sp3_positions(times, prn)
    x_s, y_s = ref.nominal_axes(position, ref.sun_itrs(times))
    x_r, y_r = ref.receiver_dipoles(ESBC)
    expected = ref.wu_windup(ESBC, position, x_s, y_s, x_r, y_r) / (2 * np.pi)
    difference = (pick["windup"].value - expected + 0.5) % 1 - 0.5
    assert len(pick) >= 10 and np.max(np.abs(difference)) < 1e-4


def test_model_attitude_nominal_for_glonass_k1b(tmp_path):
    """R09 (GLONASS-K1B) has no yaw law: nominal yaw, named in one warning."""
    with pytest.warns(OrbitWarning) as caught:
        report = correct_rinex(OBS, tmp_path / "m.rnx", SP3, attitude="model")
    messages = [str(w.message) for w in caught]
    assert messages == ["no yaw model for R09 (block GLO-K1B): nominal yaw used for them",
                        EXTRAPOLATED, UNTOUCHED]
    assert "R09" not in report.untouched and report.phases == 6371


def test_trimmed_sp3_with_the_day_counted(tmp_path):
    """An SP3 trimmed to hours whose line 1 still counts 96 epochs (as gnss_lib_py's test
    files): read with a warning, as RTKLIB reads it; epochs beyond it are left untouched."""
    lines = gzip.open(SP3, "rt").read().splitlines(keepends=True)
    stars = [i for i, line in enumerate(lines) if line.startswith("*  ")]
    text = "".join(lines[:stars[0]] + lines[stars[40]:stars[60]] + ["EOF\n"])  # 10:00-14:45
    path = tmp_path / "trimmed.sp3"
    path.write_text(text)
    with pytest.warns(OrbitWarning) as caught:
        report = correct_rinex(OBS, tmp_path / "t.rnx", path)
    messages = [str(w.message) for w in caught]
    assert messages[0] == (f"{path}: line 1 counts 96 epochs (columns 33-39), but the file has "
                           "20 epoch lines (a span of 20); the epochs of the file are read (a "
                           "file trimmed, cut short or joined?)")
    assert messages[1] == (
        "90 epochs (2020-06-25T23:15:19.000 to 2020-06-25T23:59:49.000 TAI) lie more than "
        "900 s outside the SP3 files (2020-06-25T10:00:19.000 to 2020-06-25T14:45:19.000): "
        "their phases are left untouched; give *_20201770000_01D_*_ORB.SP3")
    assert messages[2] == UNTOUCHED
    assert report.untouched_epochs == 90 and report.epochs == 452


def test_truncated_compact_rinex(tmp_path):
    hatanaka = pytest.importorskip("hatanaka")
    compact = gzip.compress(hatanaka.rnx2crx(gzip.decompress(OBS.read_bytes())))
    cut = tmp_path / "ESBC.crx.gz"
    cut.write_bytes(compact[:len(compact) // 2])
    with pytest.raises(FileFormatError, match=r"ESBC.crx.gz, line \d+: expected a complete "
                                              r"compressed file that decompresses, got "
                                              r"'EOFError: Compressed file ended"):
        correct_rinex(cut, tmp_path / "b.rnx", SP3)
    assert not (tmp_path / "b.rnx").exists()


@pytest.mark.parametrize("name, counted, held", [
    ("COD0OPSRAP_20230730000_01D_05M_ORB.SP3", 289, 3),
    ("GFZ0MGXRAP_20201380000_01D_05M_ORB.SP3", 288, 3),
    ("grg21553.sp3", 288, 55),
])
def test_gnss_lib_py_trimmed_sp3(name, counted, held):
    """gnss_lib_py's test SP3 files, trimmed with line 1 still counting the day: read with
    one warning (they were refused before; RTKLIB reads them)."""
    from astropy_feedrot.io import read_sp3

    with pytest.warns(OrbitWarning, match=rf"{name}: line 1 counts {counted} epochs \(columns "
                                          rf"33-39\), but the file has {held} epoch lines"):
        data = read_sp3(REAL / name)
    assert len(data.epochs) == held


def test_correct_with_gnss_lib_py_orbits(tmp_path):
    """A RINEX file of 2021-04-28 19:00-19:30 GPS corrected with grg21553.sp3 (18:00-22:30 at
    5 minutes, line 1 counting 288 epochs): every phase corrected, as with a whole day."""
    from astropy_feedrot.gnss.synthetic import write_rinex

    obs = tmp_path / "obs.rnx"
    sats = ["G01", "G10", "R01", "R24"]
    write_rinex(obs, "3.04", {"G": ("C1C", "L1C", "L2W"), "R": ("C1C", "L1C")}, sats,
                Time("2021-04-28T19:00:19", scale="tai"), 60, 30.0, position=tuple(ESBC))
    with pytest.warns(OrbitWarning, match="grg21553.sp3: line 1 counts 288 epochs"):
        report = correct_rinex(obs, tmp_path / "out.rnx", REAL / "grg21553.sp3")
    assert report.phases == 60 * (2 * 2 + 2) and report.arcs == 4 and not report.untouched
