# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""MSv4 processing sets: the correction equals correct_ms on the same data, converted
by xradio's own convert_msv2_to_processing_set, and touches nothing but what it adds.

Independent reference: `correct_ms` on the Measurement Set v2 the processing set was
converted from (itself checked against CASA's applycal in test_casa.py); the rows of
the two are matched by time and antenna names, not by any code of the adapter.
"""
import hashlib
import logging
import os
import shutil
from pathlib import Path

import astropy.units as u
import numpy as np
import pytest
from astropy.table import QTable
from astropy.time import Time

from helpers import import_or_skip

xradio_ms = import_or_skip("xradio.measurement_set", "msv4", "FEEDROT_REQUIRE_XRADIO")

from casacore.tables import table  # noqa: E402
from ms_model import make_linear, set_feed  # noqa: E402

from astropy_feedrot.cli import main  # noqa: E402
from astropy_feedrot.core.exceptions import UncorrectedBaselinesWarning  # noqa: E402
from astropy_feedrot.data import sample_file  # noqa: E402
from astropy_feedrot.ionosphere import Ionosphere  # noqa: E402
from astropy_feedrot.visibilities import (  # noqa: E402
    MSv4Error,
    correct_file,
    correct_ms,
    correct_processing_set,
    file_kind,
    read_antennas,
)
from astropy_feedrot.visibilities.faraday import ionosphere_text  # noqa: E402
from astropy_feedrot.visibilities.history import CorrectionRefused  # noqa: E402

logging.getLogger("toolviper").setLevel(logging.WARNING)

# xradio's conversion stores strings in a data type zarr 3 calls unstable, and
# consolidates the metadata (not in zarr 3's specification).
pytestmark = [
    pytest.mark.filterwarnings("ignore:The data type .* does not have a Zarr V3 specification"),
    pytest.mark.filterwarnings("ignore:Consolidated metadata is currently not part"),
]


def _convert(ms, store, **options):
    xradio_ms.convert_msv2_to_processing_set(str(ms), str(store), **options)
    return store


def _set_column(ms, name, column, values):
    with table(str(ms / name), readonly=False, ack=False) as t:
        for row, value in enumerate(values):
            t.putcell(column, row, value)


def _sets(where, kind):
    """A copy of the package's VLA sample (circular, two spectral windows), made linear
    with X and Y swapped and X at -90 deg, or with Nasmyth and beam-waveguide mounts;
    and its processing set."""
    ms = shutil.copytree(sample_file("vla_sim.ms"), where / f"{kind}.ms")
    if kind == "linear":
        make_linear(ms, {"default": [-90.0, 0.0]})
        with table(str(ms / "POLARIZATION"), ack=False) as t:  # both windows linear
            rows = t.nrows()
        _set_column(ms, "POLARIZATION", "CORR_TYPE",
                    [np.array([9, 10, 11, 12], dtype=np.int32)] * rows)
        for antenna in range(4):  # Y listed first, at 0; X at -90 (MeerKAT-like)
            set_feed(ms, antenna, "YX", [0.0, -90.0])
    elif kind == "nasmyth":
        _set_column(ms, "ANTENNA", "MOUNT", ["ALT-AZ+NASMYTH-R", "ALT-AZ+BWG-L",
                                             "ALT-AZ+NASMYTH-L", "ALT-AZ"])
    return ms, _convert(ms, where / f"{kind}.ps.zarr")


def _rows(ms, column):
    with table(str(ms), ack=False) as t:
        values = [t.getcell(column, r) for r in range(t.nrows())]
        time, a1, a2 = t.getcol("TIME"), t.getcol("ANTENNA1"), t.getcol("ANTENNA2")
    with table(str(ms / "ANTENNA"), ack=False) as t:
        names = [f"{n}_{s}" for n, s in zip(t.getcol("NAME"), t.getcol("STATION"))]
    return values, time, a1, a2, names


def _largest_difference(ms, column, tree, variable):
    """max |MSv2 - MSv4| / max |MSv2| over every time-baseline of every partition."""
    values, time, a1, a2, names = _rows(ms, column)
    worst, count = 0.0, 0
    for partition in tree.children.values():
        v4 = partition[variable].values
        seconds = Time(partition["time"].values, format="unix", scale="utc").mjd * 86400
        first = [names.index(str(n)) for n in partition["baseline_antenna1_name"].values]
        second = [names.index(str(n)) for n in partition["baseline_antenna2_name"].values]
        for t, mjd_s in enumerate(seconds):
            for b, (p, q) in enumerate(zip(first, second)):
                rows = np.flatnonzero((np.abs(time - mjd_s) < 1e-3) & (a1 == p) & (a2 == q))
                errors = [np.abs(values[r] - v4[t, b]).max() / np.abs(values[r]).max()
                          for r in rows if values[r].shape == v4[t, b].shape]
                assert errors, "every time-baseline of MSv4 is a row of the MS"
                worst, count = max(worst, min(errors)), count + 1
    assert count == len(values)  # every row compared
    return worst


@pytest.mark.parametrize("kind", ["circular", "linear", "nasmyth"])
def test_equals_correct_ms(tmp_path, kind):
    ms, store = _sets(tmp_path, kind)
    options = dict(catalogue=False) if kind == "nasmyth" else {}
    tree = correct_processing_set(store, write=False, **options)
    correct_ms(ms, **options)
    assert _largest_difference(ms, "CORRECTED_DATA", tree, "VISIBILITY_CORRECTED") < 1e-6


def test_many_chunks_equal_correct_ms(tmp_path):
    """Stored in chunks of 7 times and one channel (with its ionosphere's Faraday
    rotation, whose lambda^2 follows the channel chunks): the same numbers."""
    ms = shutil.copytree(sample_file("vla_sim.ms"), tmp_path / "chunks.ms")
    store = _convert(ms, tmp_path / "chunks.ps.zarr",
                     main_chunksize={"time": 7, "frequency": 1})
    with table(str(ms), ack=False) as t:
        seconds = t.getcol("TIME")
    ionosphere = Ionosphere.from_rm(QTable({
        "time": Time(np.array([seconds.min() - 60, seconds.max() + 60]) / 86400,
                     format="mjd", scale="utc"),
        "rm": [2.0, 9.0] * u.rad / u.m**2}))
    tree = correct_processing_set(store, write=False, ionosphere=ionosphere)
    visibility = tree["chunks_0"]["VISIBILITY_CORRECTED"]
    assert len(visibility.chunks[0]) > 1 and len(visibility.chunks[2]) > 1
    correct_ms(ms, ionosphere=ionosphere)
    assert _largest_difference(ms, "CORRECTED_DATA", tree, "VISIBILITY_CORRECTED") < 1e-6


def test_nasmyth_mounts_reach_the_antennas(tmp_path):
    """The mounts of the Nasmyth set are read as such (else the set would test nothing
    beyond the circular one)."""
    _, store = _sets(tmp_path, "nasmyth")
    antennas, _ = read_antennas(store, catalogue=False)
    foci = sorted(type(a.focus).__name__ for a in antennas.values())
    assert foci == ["BeamWaveguideFocus", "CassegrainFocus", "NasmythFocus", "NasmythFocus"]


def test_casa_convention_and_frame_equal_correct_ms(tmp_path):
    ms, store = _sets(tmp_path, "circular")
    options = dict(convention="casa", frame="icrs")
    tree = correct_processing_set(store, write=False, **options)
    correct_ms(ms, **options)
    assert _largest_difference(ms, "CORRECTED_DATA", tree, "VISIBILITY_CORRECTED") < 1e-6


def test_apply_equals_correct_ms(tmp_path):
    """--apply: the model group corrupted, as correct_ms corrupts MODEL_DATA."""
    ms, store = _sets(tmp_path, "circular")
    tree = correct_processing_set(store, direction="apply", write=False)
    assert tree["circular_0"].attrs["data_groups"]["model_corrupted"]["correlated_data"] == \
        "VISIBILITY_MODEL_CORRUPTED"
    correct_ms(ms, direction="apply", data_column="MODEL_DATA",
               corrected_column="CORRECTED_DATA")
    assert _largest_difference(ms, "CORRECTED_DATA", tree, "VISIBILITY_MODEL_CORRUPTED") < 1e-6


def test_faraday_equals_correct_ms(tmp_path):
    """With an ionosphere (rotation measures per antenna): the same per-channel angles."""
    ms, store = _sets(tmp_path, "circular")
    with table(str(ms), ack=False) as t:
        seconds = t.getcol("TIME")
    with table(str(ms / "ANTENNA"), ack=False) as t:
        # The MS's names and the processing set's (xradio: NAME_STATION).
        names = list(t.getcol("NAME"))
        names += [f"{n}_{s}" for n, s in zip(names, t.getcol("STATION"))]
    times = Time(np.array([seconds.min() - 60, seconds.max() + 60]) / 86400, format="mjd",
                 scale="utc")
    rows = QTable({"time": Time(np.concatenate([times.mjd] * len(names)), format="mjd"),
                   "rm": np.repeat(np.arange(len(names)) % 4 + 1.0, 2) * 3 * u.rad / u.m**2,
                   "antenna": np.repeat(names, 2)})
    ionosphere = Ionosphere.from_rm(rows)
    tree = correct_processing_set(store, write=False, ionosphere=ionosphere)
    description = tree["circular_0"].attrs["data_groups"]["corrected"]["description"]
    assert description.endswith(ionosphere_text(ionosphere)), description
    correct_ms(ms, ionosphere=ionosphere)
    assert _largest_difference(ms, "CORRECTED_DATA", tree, "VISIBILITY_CORRECTED") < 1e-6
    # The Faraday term is there: without it the two differ.
    plain = correct_processing_set(store, write=False)
    assert _largest_difference(ms, "CORRECTED_DATA", plain, "VISIBILITY_CORRECTED") > 1e-3


def _chunk_files(store, variable):
    return [p for p in (store / "circular_0" / variable).rglob("*") if p.is_file()
            and p.name != "zarr.json"]


def test_lazy_reads_no_visibility(tmp_path):
    """The graph is built without reading a visibility: with VISIBILITY's chunks gone
    from the store, the correction is still made, and only computing it fails."""
    _, store = _sets(tmp_path, "circular")
    for path in _chunk_files(store, "VISIBILITY"):
        path.unlink()
    tree = correct_processing_set(store, write=False)
    corrected = tree["circular_0"]["VISIBILITY_CORRECTED"]
    assert corrected.chunks is not None
    values = corrected.values  # zarr fills missing chunks with the fill value
    assert not np.any(values)


def _digests(store):
    return {str(p.relative_to(store)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in store.rglob("*") if p.is_file()}


def test_written_into_the_store_alone(tmp_path):
    """Only the new arrays are written; every chunk that was there is byte for byte
    the same; a second run is refused, --redo computes it again."""
    ms, store = _sets(tmp_path, "circular")
    before = _digests(store)
    tree = correct_processing_set(store)
    after = _digests(store)
    changed = {k for k in before if after[k] != before[k]}
    # Metadata only: the partitions' zarr.json (data_groups) and the consolidated root.
    assert changed == {"zarr.json", "circular_0/zarr.json", "circular_1/zarr.json"}
    added = set(after) - set(before)
    assert added and all("/VISIBILITY_CORRECTED/" in k for k in added)
    correct_ms(ms)
    assert _largest_difference(ms, "CORRECTED_DATA", tree, "VISIBILITY_CORRECTED") < 1e-6
    reopened = xradio_ms.open_processing_set(str(store))
    group = reopened["circular_0"].attrs["data_groups"]["corrected"]
    assert group["description"].startswith("Feed rotation removed by astropy_feedrot")
    assert group["flag"] == "FLAG" and group["weight"] == "WEIGHT"
    with pytest.raises(CorrectionRefused, match="holds this correction already.*redo=True"):
        correct_processing_set(store)
    correct_processing_set(store, redo=True)
    assert {k for k, v in _digests(store).items() if before.get(k, v) != v} == changed


def test_foreign_group_refused(tmp_path):
    """A 'corrected' group another program wrote (CASA's CORRECTED_DATA) is left alone."""
    _, store = _sets(tmp_path, "circular")
    tree = xradio_ms.open_processing_set(str(store))
    for partition in tree.children.values():
        groups = dict(partition.attrs["data_groups"])
        groups["corrected"] = dict(groups["base"], description="from CASA's CORRECTED_DATA")
        partition.attrs["data_groups"] = groups
    with pytest.raises(CorrectionRefused, match="did not write .*CASA's CORRECTED_DATA.*"
                       "new_group="):
        correct_processing_set(tree)
    # Into a group of another name; or from the corrected group itself.
    done = correct_processing_set(tree, new_group="feedrot")
    group = done["circular_0"].attrs["data_groups"]["feedrot"]
    assert group["correlated_data"] == "VISIBILITY_FEEDROT" and "VISIBILITY_FEEDROT" in \
        done["circular_0"]
    again = correct_processing_set(tree, data_group="corrected", new_group="twice")
    assert "VISIBILITY -> VISIBILITY_TWICE" in \
        again["circular_0"].attrs["data_groups"]["twice"]["description"]
    with pytest.raises(ValueError, match="new_group 'base' is the data group read"):
        correct_processing_set(tree, new_group="base")
    with pytest.raises(ValueError, match="new_group must be a name of letters"):
        correct_processing_set(tree, new_group="feed rot")


def test_a_set_casa_wrote(tmp_path):
    """CASA's simulator wrote this set, with a CORRECTED_DATA of its own (xradio makes it
    the group 'corrected'): corrected into a group of another name, the same numbers as
    correct_ms into a column of another name."""
    import tarfile

    with tarfile.open(Path(__file__).parent.parent / "data" / "real" /
                      "casa_sim_vla_2spw.ms.tar.gz") as archive:
        archive.extractall(tmp_path, filter="data")
    ms = tmp_path / "casa_sim_vla_2spw.ms"
    store = _convert(ms, tmp_path / "casa.ps.zarr")
    with pytest.raises(CorrectionRefused, match="data group 'corrected' that this package"):
        correct_processing_set(store)
    tree = correct_processing_set(store, new_group="feedrot")
    correct_ms(ms, corrected_column="FEEDROT_DATA")
    assert _largest_difference(ms, "FEEDROT_DATA", tree, "VISIBILITY_FEEDROT") < 1e-6


def test_refusals(tmp_path):
    _, store = _sets(tmp_path, "circular")
    with pytest.raises(MSv4Error, match="is not an MSv4 processing set"):
        correct_processing_set(sample_file("vla_sim.ms"))
    with pytest.raises(TypeError, match="ps must be an xarray DataTree or the path"):
        correct_processing_set(42)
    tree = xradio_ms.open_processing_set(str(store))
    for partition in tree.children.values():
        groups = dict(partition.attrs["data_groups"])
        groups.pop("model")
        partition.attrs["data_groups"] = groups
    with pytest.raises(MSv4Error, match=r"has no data group 'model' \(it has \['base'\]\)"):
        correct_processing_set(tree, direction="apply")
    with pytest.raises(ValueError, match="direction"):
        correct_processing_set(tree, direction="sideways")
    empty = tree.copy()
    for name in list(empty.children):
        del empty[name]
    with pytest.raises(MSv4Error, match="holds no MSv4 partition"):
        correct_processing_set(empty)
    # A moving field (an ephemeris: the field table on a time axis): refused, not taken
    # for a fixed source.
    moving = xradio_ms.open_processing_set(str(store))
    fields = moving["circular_0"]["field_and_source_base_xds"].to_dataset()
    moving["circular_0"]["field_and_source_base_xds"] = \
        fields.expand_dims(time_ephemeris=[1.675e9, 1.676e9])
    with pytest.raises(MSv4Error, match=r"moving field .*time_ephemeris.*correct_ms"):
        correct_processing_set(moving)
    # A partition of single-dish spectra (here one relabelled): named, left as it is.
    mixed = xradio_ms.open_processing_set(str(store))
    mixed["circular_1"].attrs = dict(mixed["circular_1"].attrs, type="spectrum")
    with pytest.warns(UncorrectedBaselinesWarning, match=r"single-dish spectra \['circular_1'\]"):
        done = correct_processing_set(mixed)
    assert "VISIBILITY_CORRECTED" in done["circular_0"] and \
        "VISIBILITY_CORRECTED" not in done["circular_1"]
    with pytest.raises(ValueError, match="corrected in place, as a new data group"):
        correct_file(store, tmp_path / "copy.uvh5")


def test_aperture_array_refused(tmp_path):
    """An MWA set converted to MSv4 (OBSERVATION's TELESCOPE_NAME MWA, MOUNT ALT-AZ):
    refused with the reason every format gives."""
    ms = shutil.copytree(sample_file("vla_sim.ms"), tmp_path / "mwa.ms")
    with table(str(ms / "OBSERVATION"), readonly=False, ack=False) as t:
        t.putcell("TELESCOPE_NAME", 0, "MWA")
    store = _convert(ms, tmp_path / "mwa.ps.zarr")
    before = _digests(store)
    with pytest.raises(MSv4Error, match=r"antennas cannot be corrected: .*the telescope 'MWA' "
                       r"is an aperture array \(the Murchison Widefield Array\)"):
        correct_processing_set(store)
    assert _digests(store) == before


def test_command_line(tmp_path, capsys):
    ms, store = _sets(tmp_path, "circular")
    assert file_kind(store) == "msv4"
    assert main(["correct", str(store)]) == 0
    err = capsys.readouterr().err
    assert "in place, data group base -> corrected (VISIBILITY_CORRECTED)" in err
    assert main(["correct", str(store), "--in-place"]) == 1
    assert "--redo" in capsys.readouterr().err
    assert main(["correct", str(store), "--in-place", "--redo", "--quiet"]) == 0
    assert main(["correct", str(store), "--column", "X", "--redo"]) == 1
    assert "--column is for Measurement Sets v2" in capsys.readouterr().err
    assert main(["correct", str(store), "-o", str(tmp_path / "x.uvh5")]) == 1
    assert "corrected in place" in capsys.readouterr().err
    assert main(["antennas", str(store)]) == 0
    assert "A0_P" in capsys.readouterr().out
    assert main(["correct", str(store), "--group", "feedrot", "--quiet"]) == 0
    assert "VISIBILITY_FEEDROT" in xradio_ms.open_processing_set(str(store))["circular_0"]
    assert main(["correct", str(store), "--group", "base"]) == 1
    assert "--group 'base' is the data group read" in capsys.readouterr().err
    assert main(["correct", str(ms), "--in-place", "--group", "feedrot"]) == 1
    assert "--group is for one MSv4 processing set" in capsys.readouterr().err
    correct_ms(ms)
    tree = xradio_ms.open_processing_set(str(store))
    assert _largest_difference(ms, "CORRECTED_DATA", tree, "VISIBILITY_CORRECTED") < 1e-6


def test_on_dask_distributed(tmp_path):
    """The lazy graph runs on a dask.distributed cluster as on dask's threads."""
    distributed = pytest.importorskip("distributed")
    ms, store = _sets(tmp_path, "circular")
    tree = correct_processing_set(store, write=False)
    serial = {name: p["VISIBILITY_CORRECTED"].values for name, p in tree.children.items()}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster):
        correct_processing_set(store)
    reopened = xradio_ms.open_processing_set(str(store))
    for name, values in serial.items():
        assert np.array_equal(reopened[name]["VISIBILITY_CORRECTED"].values, values)
    assert os.path.isdir(Path(store) / "circular_0" / "VISIBILITY_CORRECTED")


def test_quiet_on_xradio_stores(tmp_path):
    """Reading, correcting and writing a store xradio wrote warns nothing (zarr 3's
    warnings on xradio's own layout are not the user's to act on)."""
    import warnings

    _, store = _sets(tmp_path, "circular")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        correct_processing_set(store)
    assert [str(w.message) for w in caught] == []
