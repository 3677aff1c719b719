# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The chunks of a FITS-IDI file and of a Measurement Set corrected on dask
workers: bit for bit the serial result (the reference is the package's own
serial run, itself checked against independent models in test_io_fitsidi.py
and test_ms.py)."""

import hashlib
import tarfile
from pathlib import Path

import numpy as np
import pytest
from astropy.io import fits
from astropy.time import Time

distributed = pytest.importorskip("distributed")
pytest.importorskip("casacore")

from casacore.tables import table  # noqa: E402
from faraday_model import faraday_fitsidi, faraday_ms, rm_table_mjd  # noqa: E402
from fitsidi_writer import write_fitsidi  # noqa: E402
from ms_model import fill_model, unpack  # noqa: E402

from astropy_feedrot import UncorrectedBaselinesWarning  # noqa: E402
from astropy_feedrot.cli import main  # noqa: E402
from astropy_feedrot.core.exceptions import DegenerateGeometryWarning  # noqa: E402
from astropy_feedrot.ionosphere import Ionosphere  # noqa: E402
from astropy_feedrot.visibilities import correct_fitsidi, correct_ms  # noqa: E402

# fitsidi_writer gives WETTZ13S a Nasmyth focus the catalogue does not (on purpose).
pytestmark = pytest.mark.filterwarnings(
    "ignore::astropy_feedrot.core.exceptions.CatalogueMountWarning")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        yield client


def sha(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_fitsidi_on_two_workers(tmp_path, client):
    source = tmp_path / "in.idifits"
    write_fitsidi(source, angles={0: (5.0, 95.0)}, n_times=12, n_freqid=2)
    correct_fitsidi(source, tmp_path / "serial.idifits", chunk_bytes=4096)
    correct_fitsidi(source, tmp_path / "dask.idifits", chunk_bytes=4096, client=client)
    assert sha(tmp_path / "serial.idifits") == sha(tmp_path / "dask.idifits")


def test_ms_on_two_workers(tmp_path, client):
    serial = unpack(tmp_path / "a")
    fill_model(serial)
    parallel = unpack(tmp_path / "b")
    fill_model(parallel)
    correct_ms(serial, chunk_rows=40)
    correct_ms(parallel, chunk_rows=40, client=client)
    with table(str(serial), ack=False) as a, table(str(parallel), ack=False) as b:
        np.testing.assert_array_equal(a.getcol("CORRECTED_DATA"), b.getcol("CORRECTED_DATA"))


def test_command_with_workers(tmp_path, capsys):
    ms = unpack(tmp_path)
    fill_model(ms)
    assert main(["correct", str(ms), "--in-place", "--workers", "2", "--quiet"]) == 0
    reference = unpack(tmp_path / "ref")
    fill_model(reference)
    correct_ms(reference)
    with table(str(ms), ack=False) as a, table(str(reference), ack=False) as b:
        np.testing.assert_array_equal(a.getcol("CORRECTED_DATA"), b.getcol("CORRECTED_DATA"))
    assert main(["correct", str(ms), "--in-place", "--workers", "2", "--dask",
                 "tcp://127.0.0.1:1", "--redo"]) == 1
    assert "--dask and --workers exclude each other" in capsys.readouterr().err
    assert main(["correct", str(ms), "--in-place", "--workers", "0", "--redo"]) == 1
    assert "--workers must be at least 1, got 0" in capsys.readouterr().err


@pytest.mark.parametrize("chunk_rows, data_column, corrected_column", [
    (7, "DATA", "CORRECTED_DATA"),    # chunks across the tiles of the column
    (13, "DATA", "DATA"),             # in place: the column read is the one written
])
def test_ms_workers_writing_rows_of_shared_tiles(tmp_path, client, chunk_rows, data_column,
                                                 corrected_column):
    # The workers write their chunks themselves under casacore's table lock; chunks of
    # a few rows share tiles of the output column with the chunks of the other worker,
    # and the result is still the serial one, bit for bit. The workers close the
    # table at the end: the set is not left locked.
    serial = unpack(tmp_path / "a")
    fill_model(serial)
    parallel = unpack(tmp_path / "b")
    fill_model(parallel)
    columns = dict(data_column=data_column, corrected_column=corrected_column)
    correct_ms(serial, chunk_rows=chunk_rows, **columns)
    correct_ms(parallel, chunk_rows=chunk_rows, client=client, **columns)
    with table(str(serial), ack=False) as a, table(str(parallel), ack=False) as b:
        np.testing.assert_array_equal(a.getcol(corrected_column),
                                      b.getcol(corrected_column))
        assert "FEEDROT_PARTIAL" not in b.getcolkeywords(corrected_column)
    correct_ms(parallel, chunk_rows=chunk_rows, redo=True, **columns)  # not locked


def test_ms_in_place_interrupted_on_workers_goes_on_without_correcting_twice(
        tmp_path, client):
    # DATA corrected into itself on two workers, stopped (Ctrl-C) after the first chunk
    # given: the chunks the workers had taken cannot be stopped, so they are waited for
    # and recorded; the run started again corrects only the others, and the result is
    # the serial one, bit for bit (a chunk corrected twice would differ).
    from astropy_feedrot.visibilities import MSError

    serial = unpack(tmp_path / "a")
    fill_model(serial)
    parallel = unpack(tmp_path / "b")
    fill_model(parallel)
    columns = dict(data_column="DATA", corrected_column="DATA", chunk_rows=13)
    correct_ms(serial, **columns)

    def stop(done, total):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt, match="DATA is partly corrected; the first"):
        correct_ms(parallel, client=client, progress=stop, **columns)
    with table(str(parallel), ack=False, readonly=False) as t:
        partial = t.getcolkeywords("DATA")["FEEDROT_PARTIAL"]
        assert partial["chunks"] > 1  # beyond the one given: the chunks sent, waited for
        assert partial["chunks"] < -(-t.nrows() // 13)
        # Were a chunk's state unknown (its task not waited for), going on would be refused.
        t.putcolkeyword("DATA", "FEEDROT_PARTIAL", dict(partial, unknown=np.array([0])))
    with pytest.raises(MSError, match=r"chunks \[0\] \(of 13 rows, numbered from 0\) of "
                       "DATA may or may not be corrected .* restore DATA from a copy"):
        correct_ms(parallel, client=client, **columns)
    with table(str(parallel), ack=False, readonly=False) as t:
        t.putcolkeyword("DATA", "FEEDROT_PARTIAL", partial)
    correct_ms(parallel, client=client, **columns)
    with table(str(serial), ack=False) as a, table(str(parallel), ack=False) as b:
        assert a.getcol("DATA").tobytes() == b.getcol("DATA").tobytes()
        assert "FEEDROT_PARTIAL" not in b.getcolkeywords("DATA")


def test_ms_orbiting_antenna_on_two_workers(tmp_path, client):
    # The rows left out (baselines to an orbiting antenna) make the chunks' rows
    # non-contiguous: the workers read and write them a run of neighbours at a time
    # (casacore's selections need the lock under user locking), and this process
    # copies DATA into the left-out rows of CORRECTED_DATA.
    archive = Path(__file__).parent.parent / "data" / "uvdata" / \
        "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms.tar.gz"
    paths = []
    for name in ("serial", "workers"):
        with tarfile.open(archive) as tar:
            tar.extractall(tmp_path / name, filter="data")
        path = tmp_path / name / "day2_TDEM0003_10s_norx_1src_1spw_2ints.ms"
        with table(str(path / "ANTENNA"), readonly=False, ack=False) as antennas:
            antennas.putcell("MOUNT", 1, "SPACE-HALCA")
        paths.append(path)
    with pytest.warns(UncorrectedBaselinesWarning):
        correct_ms(paths[0], chunk_rows=50)
    with pytest.warns(UncorrectedBaselinesWarning):
        correct_ms(paths[1], chunk_rows=50, client=client)
    with table(str(paths[0]), ack=False) as serial, table(str(paths[1]), ack=False) as work:
        on = (work.getcol("ANTENNA1") == 1) | (work.getcol("ANTENNA2") == 1)
        assert 0 < on.sum() < on.size
        assert work.getcol("CORRECTED_DATA").tobytes() == \
            serial.getcol("CORRECTED_DATA").tobytes()
        assert work.getcol("CORRECTED_DATA")[on].tobytes() == work.getcol("DATA")[on].tobytes()


def test_faraday_on_two_workers(tmp_path, client):
    """With an ionosphere: the workers get the RM with the angles (no maps), and give the
    serial result bit for bit, for a Measurement Set and a FITS-IDI file."""
    serial, _, _, (start, stop) = faraday_ms(tmp_path / "a")
    parallel, _, _, _ = faraday_ms(tmp_path / "b")
    ionosphere = Ionosphere.from_rm(rm_table_mjd(start, stop))
    correct_ms(serial, chunk_rows=40, ionosphere=ionosphere)
    correct_ms(parallel, chunk_rows=40, client=client, ionosphere=ionosphere)
    with table(str(serial), ack=False) as a, table(str(parallel), ack=False) as b:
        np.testing.assert_array_equal(a.getcol("CORRECTED_DATA"), b.getcol("CORRECTED_DATA"))
    path, _, _, _ = faraday_fitsidi(tmp_path)
    ionosphere = Ionosphere.from_rm(rm_table_mjd(Time("2023-01-25T20:00").mjd,
                                                 Time("2023-01-26T02:00").mjd))
    for name, options in (("serial", {}), ("dask", {"client": client})):
        with pytest.warns(DegenerateGeometryWarning):  # 3C 84 below a horizon: NaN rows
            correct_fitsidi(path, tmp_path / f"{name}.idifits", chunk_bytes=4096,
                            ionosphere=ionosphere, **options)
    with fits.open(tmp_path / "serial.idifits") as a, fits.open(tmp_path / "dask.idifits") as b:
        np.testing.assert_array_equal(a["UV_DATA"].data["FLUX"], b["UV_DATA"].data["FLUX"])
