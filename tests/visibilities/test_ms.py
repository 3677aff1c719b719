# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Measurement Sets corrected in place (correct_ms) and their refusals.

The MS is the VLA's, as CASA's importuvfits wrote it, with its data replaced
by a polarized point source from the voltage-level model of ``ms_model``
(ERFA hd2pa on astropy's HADec, receptor rows from their definitions),
independent of the package: the corrected products must be that model's
sky-fixed products.
"""

import hashlib
import os
import subprocess
import sys
import textwrap

import astropy.units as u
import numpy as np
import pytest

pytest.importorskip("casacore")

from casacore.tables import table  # noqa: E402
from ms_model import fill_model, make_linear, set_feed, unpack  # noqa: E402

from astropy_feedrot.antennas.receptors import Receptors  # noqa: E402
from astropy_feedrot.cli import main  # noqa: E402
from astropy_feedrot.core.exceptions import DegenerateGeometryWarning  # noqa: E402
from astropy_feedrot.visibilities import (  # noqa: E402
    APPLY_MARK,
    HISTORY_MARK,
    CorrectionRefused,
    MSError,
    correct_ms,
    ms_antennas,
    parse_feeds,
)

LINEAR = {"default": (-10.0, 80.0), 3: (15.0, 105.0), 7: (-30.0, 62.0)}


def digests(ms):
    return {str(p.relative_to(ms)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(ms.rglob("*")) if p.is_file() and p.name != "table.lock"}


def column(ms, name):
    with table(str(ms), ack=False) as t:
        return t.getcol(name)


@pytest.fixture
def circular(tmp_path):
    ms = unpack(tmp_path)
    return ms, fill_model(ms)


@pytest.fixture
def linear(tmp_path):
    ms = unpack(tmp_path)
    make_linear(ms, LINEAR)
    return ms, fill_model(ms)


def corrected(ms, model, name="CORRECTED_DATA"):
    return column(ms, name) / model["gain"]


@pytest.mark.parametrize("kind", ["circular", "linear"])
@pytest.mark.parametrize("chunk_rows", [None, 50])
def test_corrected_in_place(request, kind, chunk_rows):
    ms, model = request.getfixturevalue(kind)
    before = digests(ms)
    assert correct_ms(ms, chunk_rows=chunk_rows) == ms
    got = corrected(ms, model)
    # Reference: the sky-fixed products of the voltage-level model.
    np.testing.assert_allclose(got, np.broadcast_to(model["expected"][:, None, :], got.shape),
                               rtol=0, atol=2e-6)
    after = digests(ms)
    changed = {k for k in before if before[k] != after.get(k)}
    # Only the table description (a new column), HISTORY, and new files change.
    assert changed <= {"table.dat", "HISTORY/table.f0"}, changed
    new = set(after) - set(before)
    assert new and all(name.startswith("table.f") for name in new)
    with table(str(ms / "HISTORY"), ack=False) as history:
        assert history.getcell("MESSAGE", history.nrows() - 1).startswith(HISTORY_MARK)
        assert history.getcell("APPLICATION", history.nrows() - 1) == "astropy_feedrot"


@pytest.mark.filterwarnings("ignore:The uvw_array does not match")
def test_reread_with_pyuvdata(circular):
    pytest.importorskip("pyuvdata")
    from astropy_feedrot.visibilities import read_uvdata

    ms, model = circular
    correct_ms(ms)
    uv = read_uvdata(ms, data_column="CORRECTED_DATA")
    values = column(ms, "CORRECTED_DATA")
    # pyuvdata holds the conjugate of the MS's <v1 v2*>, rows in the MS order
    # (one spectral window: data_array is (Nblts, Nfreqs, Npols)).
    with table(str(ms), ack=False) as t:
        flagged = t.getcol("FLAG_ROW")
    assert uv.data_array.shape == values.shape
    order = [uv.polarization_array.tolist().index(c) for c in (-1, -3, -4, -2)]
    np.testing.assert_allclose(uv.data_array[..., order][~flagged],
                               values.conj()[~flagged], rtol=0, atol=1e-7)


@pytest.mark.parametrize("kind", ["circular", "linear"])
def test_apply_then_remove_gives_the_input_back(request, kind):
    ms, model = request.getfixturevalue(kind)
    correct_ms(ms)
    # The model's sky-fixed products, turned forward, are the data again
    # (identity: apply is the inverse of remove).
    correct_ms(ms, data_column="CORRECTED_DATA", corrected_column="MODEL_DATA",
               direction="apply")
    np.testing.assert_allclose(column(ms, "MODEL_DATA"), column(ms, "DATA"), rtol=0,
                               atol=1e-6)
    with table(str(ms / "HISTORY"), ack=False) as history:
        assert history.getcell("MESSAGE", history.nrows() - 1).startswith(APPLY_MARK)


def test_apply_in_place_on_a_model_column(circular):
    ms, model = circular
    correct_ms(ms)  # CORRECTED_DATA holds the sky
    correct_ms(ms, data_column="CORRECTED_DATA", corrected_column="CORRECTED_DATA",
               direction="apply")
    np.testing.assert_allclose(column(ms, "CORRECTED_DATA"), column(ms, "DATA"), rtol=0,
                               atol=1e-6)


def test_twice_is_refused_unless_asked(circular):
    ms, _ = circular
    correct_ms(ms)
    before = digests(ms)
    # DATA -> CORRECTED_DATA again would recompute the same values.
    with pytest.raises(CorrectionRefused, match=r"CORRECTED_DATA holds DATA with the feed "
                       r"rotation removed already \(the history records 'Feed rotation "
                       r"removed by astropy_feedrot' \(DATA -> CORRECTED_DATA\)\); the same "
                       r"correction again would only compute it anew: pass redo=True to do "
                       r"so$"):
        correct_ms(ms)
    # CORRECTED_DATA corrected again would be corrected twice.
    with pytest.raises(CorrectionRefused, match=r"\(HISTORY of CORRECTED_DATA\): the feed "
                       r"rotation was removed already .*correcting again would remove it "
                       r"twice: pass redo=True to correct all the same$"):
        correct_ms(ms, data_column="CORRECTED_DATA", corrected_column="OTHER")
    assert digests(ms) == before
    correct_ms(ms, redo=True)


def test_antennas_and_receptors(tmp_path):
    ms = unpack(tmp_path)
    antennas = ms_antennas(ms)
    # importuvfits left rows at the geocentre for antenna numbers the UVFITS file skips.
    assert len(antennas) == 19 and all(a.receptors == Receptors("RL", [0, 0] * u.deg)
                                       for a in antennas.values())
    make_linear(ms, LINEAR)
    antennas = ms_antennas(ms)
    assert antennas[3].receptors == Receptors("XY", [15.0, 105.0] * u.deg)


def test_receptors_per_spectral_window_and_time(linear, tmp_path):
    # Two FEED rows for antenna 3 (one per half of the observation): each row
    # of data takes the receptors of its time.
    ms, _ = linear
    with table(str(ms), ack=False) as t:
        times = np.unique(t.getcol("TIME"))
    with table(str(ms / "FEED"), readonly=False, ack=False) as feed:
        row = [k for k in range(feed.nrows()) if feed.getcell("ANTENNA_ID", k) == 3][0]
        feed.putcell("TIME", row, times[0])
        feed.putcell("INTERVAL", row, 1.0)
        feed.copyrows(feed, startrowin=row, nrow=1)
        last = feed.nrows() - 1
        feed.putcell("TIME", last, times[1])
        feed.putcell("RECEPTOR_ANGLE", last, np.radians([25.0, 115.0]))
    assert ms_antennas(ms)[3].receptors is None  # two sets
    model = fill_model(ms)
    correct_ms(ms)
    got = corrected(ms, model)
    np.testing.assert_allclose(got, np.broadcast_to(model["expected"][:, None, :], got.shape),
                               rtol=0, atol=2e-6)


def test_one_receptor_named_completed_from_it(circular):
    # CASA's importfitsidi of a single-polarization file (SFXC, POLTYB '?') writes
    # POLARIZATION_TYPE ['R', '?'] (FitsIDItoMS.cc): the pair is completed from the
    # first receptor (Receptors.paired), whatever angle the '?' receptor has.
    ms, model = circular
    for antenna in range(28):
        set_feed(ms, antenna, "R?", (0.0, 37.0))
    assert ms_antennas(ms)[1].receptors == Receptors("RL", [0, 0] * u.deg)
    correct_ms(ms)
    got = corrected(ms, model)
    np.testing.assert_allclose(got, np.broadcast_to(model["expected"][:, None, :], got.shape),
                               rtol=0, atol=2e-6)


def test_feeds_given_by_the_user(tmp_path):
    ms = unpack(tmp_path)
    make_linear(ms, {"default": (0.0, 90.0)})
    model = fill_model(ms)
    set_feed(ms, 7, "RL", (0.0, 0.0))  # wrong in the file
    with pytest.raises(MSError, match=r"antenna 7 \(.*\) has circular receptors 'RL' but the "
                                      r"data hold linear products.*PolConvert"):
        correct_ms(ms)
    correct_ms(ms, feeds=parse_feeds("X:0,Y:90"))
    got = corrected(ms, model)
    np.testing.assert_allclose(got, np.broadcast_to(model["expected"][:, None, :], got.shape),
                               rtol=0, atol=2e-6)


# --- bad input: one line, nothing modified ------------------------------------------------


def _unchanged(ms, call, error, match):
    before = digests(ms)
    with pytest.raises(error, match=match) as info:
        call()
    assert "\n" not in str(info.value)
    assert digests(ms) == before


def test_no_data_column(circular):
    ms, _ = circular
    _unchanged(ms, lambda: correct_ms(ms, data_column="MODEL_DATA"), MSError,
               r"has no column 'MODEL_DATA' \(its visibility columns: \['DATA'\]\); choose one "
               r"with data_column=$")


def test_rows_of_a_feed_id_that_feed_lacks(circular):
    # Antenna 2 has one FEED row (feed 0); three rows of data say feed 1.
    ms, _ = circular
    with table(str(ms), readonly=False, ack=False) as t:
        rows = np.flatnonzero(t.getcol("ANTENNA1") == 2)[:3]
        for row in rows.tolist():
            t.putcell("FEED1", row, 1)
    _unchanged(ms, lambda: correct_ms(ms), MSError,
               r"antenna 2 has no FEED row for the FEED1/FEED2 ids \[0, 1\]")


def test_no_feed_rows_for_an_antenna(circular):
    ms, _ = circular
    with table(str(ms / "FEED"), readonly=False, ack=False) as feed:
        feed.removerows([k for k in range(feed.nrows()) if feed.getcell("ANTENNA_ID", k) == 2])
    _unchanged(ms, lambda: correct_ms(ms), MSError,
               r"antenna 2 \(.*\) has no receptors: it has no FEED rows; add them to FEED, "
               r"or give them \(feeds=, --feeds R,L\)")


def test_mixed_circular_and_linear_on_one_baseline(circular):
    ms, _ = circular
    set_feed(ms, 6, "XY", (0.0, 90.0))
    _unchanged(ms, lambda: correct_ms(ms), MSError,
               r"antenna 6 \(.*\) has linear receptors 'XY' but the data hold circular "
               r"products.*PolConvert")


def test_read_only(circular):
    ms, _ = circular
    if os.geteuid() == 0:
        pytest.skip("root writes read-only files")
    modes = {p: p.stat().st_mode for p in [ms, *ms.glob("table.*")]}
    try:
        for p in modes:
            p.chmod(modes[p] & ~0o222)
        _unchanged(ms, lambda: correct_ms(ms), MSError, "is read-only")
    finally:
        for p, mode in modes.items():
            p.chmod(mode)


def test_read_only_as_root_too(circular, monkeypatch):
    # os.access says what the process may write; as root the files' modes
    # do not stop it, so the check is made to see a read-only file here.
    ms, _ = circular
    real = os.access
    monkeypatch.setattr(os, "access", lambda p, mode: False if mode == os.W_OK and str(
        p).endswith("table.dat") else real(p, mode))
    _unchanged(ms, lambda: correct_ms(ms), MSError,
               r"is read-only \(.*table.dat' cannot be written\)")


def test_locked_by_another_process(circular):
    ms, _ = circular
    # The other process holds the lock until it is told to stop (its standard
    # input closed), however long the check takes, not for a fixed time.
    holder = subprocess.Popen([sys.executable, "-c", textwrap.dedent(f"""
        import sys
        from casacore.tables import table
        t = table({str(ms)!r}, readonly=False, ack=False, lockoptions="permanent")
        print("locked", flush=True)
        sys.stdin.read()
        """)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "locked"
        _unchanged(ms, lambda: correct_ms(ms), MSError,
                   "is locked by another process .*close it there")
    finally:
        holder.stdin.close()
        holder.wait(timeout=60)
        holder.stdout.close()


def test_interrupted_run_keeps_the_input_and_resumes(circular, tmp_path):
    ms, model = circular
    data = column(ms, "DATA")
    # Ctrl-C at a known point, not at a time: after its third chunk the run
    # sends itself SIGINT, which Python raises at the next instruction of the
    # progress callback (never in a destructor, where it would be dropped).
    script = textwrap.dedent(f"""
        import os, signal, sys
        from astropy_feedrot.visibilities import correct_ms
        def interrupt(done, total):
            print(done, flush=True)
            if done == 3:
                os.kill(os.getpid(), signal.SIGINT)
        try:
            correct_ms({str(ms)!r}, chunk_rows=20, progress=interrupt)
        except KeyboardInterrupt as error:
            print("INTERRUPTED", error, flush=True)
            sys.exit(3)
        """)
    run = subprocess.run([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True,
                         timeout=600)
    out = run.stdout
    assert run.returncode == 3
    assert "INTERRUPTED" in out and "DATA is intact" in out and "FEEDROT_PARTIAL" in out
    np.testing.assert_array_equal(column(ms, "DATA"), data)
    with table(str(ms), ack=False) as t:
        done = t.getcolkeywords("CORRECTED_DATA")["FEEDROT_PARTIAL"]["done"]
    assert 0 < done < len(data)
    # Run again: it goes on from there, and the result is that of one run.
    correct_ms(ms, chunk_rows=20)
    got = corrected(ms, model)
    np.testing.assert_allclose(got, np.broadcast_to(model["expected"][:, None, :], got.shape),
                               rtol=0, atol=2e-6)
    with table(str(ms), ack=False) as t:
        assert "FEEDROT_PARTIAL" not in t.getcolkeywords("CORRECTED_DATA")


def test_not_a_measurement_set(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such Measurement Set"):
        correct_ms(tmp_path / "missing.ms")
    (tmp_path / "empty.ms").mkdir()
    with pytest.raises(ValueError, match="is a directory but not a Measurement Set"):
        correct_ms(tmp_path / "empty.ms")


def test_bad_options(circular):
    ms, _ = circular
    with pytest.raises(ValueError, match="direction must be one of"):
        correct_ms(ms, direction="forward")
    with pytest.raises(ValueError, match="chunk_rows must be a positive number of rows, got 0"):
        correct_ms(ms, chunk_rows=0)


# --- the command line ----------------------------------------------------------------------


def test_command_in_place(circular, capsys):
    ms, model = circular
    assert main(["antennas", str(ms)]) == 0
    out = capsys.readouterr().out
    assert "casacore" in out and "AltAzMount()" in out
    assert main(["correct", str(ms), "--in-place", "--quiet"]) == 0
    got = corrected(ms, model)
    np.testing.assert_allclose(got, np.broadcast_to(model["expected"][:, None, :], got.shape),
                               rtol=0, atol=2e-6)
    assert main(["correct", str(ms), "--in-place", "--quiet"]) == 1
    err = capsys.readouterr().err
    # One line, in the command line's words.
    assert err.count("\n") == 1 and err.endswith("pass --redo to do so\n"), err
    assert "redo=True" not in err
    assert main(["correct", str(ms), "--in-place", "--data-column", "CORRECTED_DATA",
                 "--column", "MODEL_DATA", "--apply", "--quiet"]) == 0
    np.testing.assert_allclose(column(ms, "MODEL_DATA"), column(ms, "DATA"), rtol=0,
                               atol=1e-6)
    assert main(["correct", str(ms), "--in-place", "-o", "x.ms"]) == 1
    assert "exclude each other" in capsys.readouterr().err
    assert main(["correct", str(ms)]) == 1
    assert "--in-place" in capsys.readouterr().err
    assert main(["correct", str(ms), "--in-place", "--feeds", "Q,L"]) == 1
    assert "--feeds: feeds 'Q,L': unknown receptor 'Q'" in capsys.readouterr().err


def test_degenerate_rows_warn_once(circular, monkeypatch):
    # A field at the zenith of the VLA at the first epoch: the alt-az antennas
    # have no feed rotation there; those rows are NaN, with one warning.
    from astropy.coordinates import AltAz, EarthLocation, SkyCoord
    from astropy.time import Time

    ms, _ = circular
    with table(str(ms), ack=False) as t:
        first = t.getcol("TIME")[0]
    with table(str(ms / "ANTENNA"), ack=False) as ant:
        xyz = ant.getcell("POSITION", 0)
    site = EarthLocation.from_geocentric(*xyz, unit=u.m)
    when = Time(first / 86400, format="mjd", scale="utc")
    zenith = SkyCoord(AltAz(az=0 * u.deg, alt=90 * u.deg, obstime=when,
                            location=site)).transform_to("fk5")
    with table(str(ms / "FIELD"), readonly=False, ack=False) as field:
        field.putcell("PHASE_DIR", 0, np.array([[zenith.ra.rad, zenith.dec.rad]]))
    with pytest.warns(DegenerateGeometryWarning, match=r"undefined in \d+ of 306 rows"):
        correct_ms(ms)
    assert np.isnan(column(ms, "CORRECTED_DATA")).any()


def test_several_data_descriptions_interleaved(tmp_path):
    # Odd rows in a second data description (same window and products): rows of
    # one description are not contiguous; the result is that of one description.
    plain = unpack(tmp_path / "a")
    model = fill_model(plain)
    split = unpack(tmp_path / "b")
    fill_model(split)
    with table(str(split / "DATA_DESCRIPTION"), readonly=False, ack=False) as dd:
        dd.copyrows(dd, nrow=1)
    with table(str(split), readonly=False, ack=False) as t:
        ddid = t.getcol("DATA_DESC_ID")
        ddid[1::2] = 1
        t.putcol("DATA_DESC_ID", ddid)
    correct_ms(plain, chunk_rows=50)
    correct_ms(split, chunk_rows=50)
    np.testing.assert_array_equal(column(split, "CORRECTED_DATA"),
                                  column(plain, "CORRECTED_DATA"))
    got = corrected(split, model)
    np.testing.assert_allclose(got, np.broadcast_to(model["expected"][:, None, :], got.shape),
                               rtol=0, atol=2e-6)


def _ephemeris_field(ms, mjd, ra_deg, dec_deg):
    """FIELD 0 follows a CASA ephemeris table FIELD/EPHEM0_SRC.tab (MJD, RA, DEC in deg)."""
    from casacore.tables import makescacoldesc, maketabdesc

    description = maketabdesc([makescacoldesc("MJD", 0.0), makescacoldesc("RA", 0.0),
                               makescacoldesc("DEC", 0.0)])
    with table(str(ms / "FIELD" / "EPHEM0_SRC.tab"), description, nrow=len(mjd),
               ack=False) as eph:
        eph.putcol("MJD", np.asarray(mjd, float))
        eph.putcol("RA", np.asarray(ra_deg, float))
        eph.putcol("DEC", np.asarray(dec_deg, float))
        eph.putkeyword("posrefsys", "ICRF/ICRS")
    with table(str(ms / "FIELD"), readonly=False, ack=False) as field:
        if "EPHEMERIS_ID" not in field.colnames():
            field.addcols(maketabdesc(makescacoldesc("EPHEMERIS_ID", -1)))
        field.putcell("EPHEMERIS_ID", 0, 0)
        field.putcell("PHASE_DIR", 0, np.zeros((1, 2)))  # the offset from the ephemeris


def test_ephemeris_field(tmp_path):
    # A "moving" source whose ephemeris stays at the field's position (ICRS):
    # the same result as the fixed ICRS field; outside the ephemeris, refused.
    from astropy.coordinates import FK5, SkyCoord

    fixed = unpack(tmp_path / "a")
    fill_model(fixed)
    moving = unpack(tmp_path / "b")
    fill_model(moving)
    with table(str(fixed / "FIELD"), ack=False) as field:
        ra, dec = field.getcell("PHASE_DIR", 0)[0]
    icrs = SkyCoord(ra * u.rad, dec * u.rad, frame=FK5(equinox="J2000")).icrs
    with table(str(fixed / "FIELD"), readonly=False, ack=False) as field:
        field.putcell("PHASE_DIR", 0, np.array([[icrs.ra.rad, icrs.dec.rad]]))
    field_info = {"type": "direction", "Ref": "ICRS"}
    with table(str(fixed / "FIELD"), readonly=False, ack=False) as field:
        keywords = field.getcolkeywords("PHASE_DIR")
        keywords["MEASINFO"] = field_info
        field.putcolkeywords("PHASE_DIR", keywords)
    with table(str(moving), ack=False) as t:
        times = t.getcol("TIME") / 86400
    mjd = [times.min() - 0.01, times.max() + 0.01]
    _ephemeris_field(moving, mjd, [icrs.ra.deg] * 2, [icrs.dec.deg] * 2)
    correct_ms(fixed)
    correct_ms(moving)
    np.testing.assert_allclose(column(moving, "CORRECTED_DATA"), column(fixed, "CORRECTED_DATA"),
                               rtol=0, atol=1e-6)
    short = unpack(tmp_path / "c")
    _ephemeris_field(short, [times.min() - 1, times.min() - 0.5], [icrs.ra.deg] * 2,
                     [icrs.dec.deg] * 2)
    with pytest.raises(MSError, match=r"the ephemeris of field .* covers MJD .* give an "
                                      "ephemeris that spans the observation"):
        correct_ms(short)
