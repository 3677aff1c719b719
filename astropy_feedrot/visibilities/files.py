# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Visibility files of every kind: their antennas, and a corrected copy.

The one entry point for files of every format (`~astropy_feedrot.visibilities.FILE_KINDS`),
used by ``feedrot antennas`` and ``feedrot correct``:

* FITS-IDI files are read and corrected with astropy alone
  (`~astropy_feedrot.visibilities.fitsidi_antennas`,
  `~astropy_feedrot.visibilities.correct_fitsidi`), in chunks;
* UVFITS antenna tables are read with astropy alone
  (`~astropy_feedrot.visibilities.uvfits_antennas`);
* everything pyuvdata reads (UVFITS, uvh5, Measurement Sets through
  python-casacore, Miriad, SMA Mir) is corrected through
  `astropy_feedrot.visibilities.uvdata` and written in the format of the
  output's extension; a Measurement Set is corrected in place by
  `~astropy_feedrot.visibilities.correct_ms`, and into a new Measurement Set
  (``.ms``) by copying it with casacore (`~astropy_feedrot.visibilities.ms_tables.copy_ms`)
  and correcting the copy in place: every column and subtable as the input's,
  whatever pyuvdata would make of it.
"""

import contextlib

import numpy as np
from astropy.table import Table

from ..antennas.focus import CassegrainFocus
from ..stations.labels import label_from_mount
from .antenna_tables import writing_program
from .catalogue import CATALOGUE_TOLERANCE, catalogue_stations, check_mounts_option
from .correction import Correction, adapter_of
from .fitsidi import fitsidi_antennas
from .kinds import file_kind
from .ms_antennas import ms_antennas
from .msv4 import processing_set_antennas, read_processing_set
from .unusable import UnusableAntenna
from .uvdata import antennas_from_uvdata
from .uvdata_adapter import uvdata_telescopes  # noqa: F401 (registers its adapters)
from .uvdata_files import PYUVDATA_TYPES, read_uvdata
from .uvfits import uvfits_antennas

__all__ = ["read_antennas", "file_telescopes", "antenna_table", "correct_file"]


def file_telescopes(path, kind=None):
    """The telescope names a visibility file gives, of any kind of `FILE_KINDS`, read
    without its data: as the adapter of its kind reads them
    (`~astropy_feedrot.visibilities.correction.adapter_of`).

    ``TELESCOP`` and ``ARRNAM`` of FITS-IDI and UVFITS files, ``TELESCOPE_NAME`` of
    a Measurement Set's ``OBSERVATION`` rows, pyuvdata's ``telescope.name`` of the
    other kinds (their metadata read, not their data), the antenna tables' of an
    MSv4 processing set.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities.files import file_telescopes
    >>> file_telescopes(sample_file("vla_sim.ms"))
    ['VLA']
    """
    return adapter_of(file_kind(path) if kind is None else kind).telescopes(path)


def _processing_set_antennas(path, vertical):
    """The antennas of every partition, numbered by their names' first appearance."""
    antennas = {}
    for name, partition in read_processing_set(path).children.items():
        found, names, _ = processing_set_antennas(partition, vertical=vertical,
                                                  where=f"{str(path)!r}, partition {name!r}")
        for index, antenna in found.items():
            antennas.setdefault(names[index], antenna)
    return dict(enumerate(antennas.values()))


def read_antennas(path, *, vertical="geodetic", mounts="file", catalogue=None):
    """The antennas of a visibility file.

    Parameters
    ----------
    path : str or path-like
        A visibility file of any kind of `FILE_KINDS`.
    vertical : {'geodetic', 'geocentric'}, optional
        The local vertical of the antennas (see `~astropy_feedrot.Antenna`;
        ``'geocentric'`` reproduces CASA).
    mounts : {'file', 'catalogue'}, optional
        Whose mount and focus an antenna within
        `~astropy_feedrot.visibilities.CATALOGUE_TOLERANCE` of a station of
        the catalogue takes where the two differ: the file's (default) or
        the catalogue's (`~astropy_feedrot.visibilities.catalogue_mounts`).
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, path or False, optional
        The station catalogue the mounts are compared with (default: the
        embedded one); False for none.

    Returns
    -------
    antennas : dict
        ``{antenna number: Antenna}``, with names, mounts, foci and
        receptors; an antenna that cannot be described (an orbiting
        antenna, a mount with no model, receptors that cannot be used) is an
        `~astropy_feedrot.visibilities.UnusableAntenna` saying why.
    software : str
        The label convention of the file (one of
        `~astropy_feedrot.stations.labels.SOFTWARE`), in which `antenna_table`
        writes the labels back.

    Raises
    ------
    FileNotFoundError, ValueError
        As `file_kind` and the readers; ImportError if a pyuvdata format
        is read without pyuvdata.

    Warns
    -----
    CatalogueMountWarning
        Once, naming them, if the mounts or foci of some antennas differ
        from those of their stations in the catalogue.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import read_antennas
    >>> antennas, software = read_antennas(sample_file("vla_day2_8chan.uvfits"))
    >>> len(antennas), software
    (19, 'fits-idi:casacore')
    """
    check_mounts_option(mounts)
    kind = file_kind(path)
    if kind == "fits-idi":
        antennas = fitsidi_antennas(path, vertical=vertical, unusable="keep")
        software = writing_program(path)[1]
    elif kind == "uvfits":
        antennas = uvfits_antennas(path, vertical=vertical, unusable="keep")
        software = writing_program(path)[1]
    elif kind == "ms":
        antennas, software = ms_antennas(path, vertical=vertical, unusable="keep"), "casacore"
    elif kind == "msv4":
        antennas, software = _processing_set_antennas(path, vertical), "casacore"
    else:
        uv = read_uvdata(path, read_data=False, file_type=PYUVDATA_TYPES[kind])
        antennas = antennas_from_uvdata(uv, vertical=vertical, unusable="keep")
        software = "pyuvdata"
    # The step every correction takes: the same reasons as feedrot correct gives.
    correction = Correction(vertical=vertical, mounts=mounts, catalogue=catalogue)
    return correction.resolve(antennas, file_telescopes(path, kind), str(path)), software


def antenna_table(antennas, software=None, *, catalogue=None):
    """The antennas as a table: number, name, position, label, mount, focus, receptors,
    the catalogue's station and what prevents a correction.

    Parameters
    ----------
    antennas : dict
        ``{antenna number: Antenna or UnusableAntenna}``.
    software : str, optional
        A convention of `~astropy_feedrot.stations.labels.SOFTWARE`: adds the column
        ``label``, the mount label of each antenna in that convention (empty
        where the convention has none; the file's own label for an
        antenna that cannot be described).
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, path or False, optional
        Adds the catalogue's station of each antenna
        (`~astropy_feedrot.visibilities.catalogue_stations`): the embedded
        catalogue by default, another, or False for none.

    Returns
    -------
    `~astropy.table.Table`
        One row per antenna, ordered by number: ``number``, ``name``, ``x``,
        ``y``, ``z`` (ITRF, m), [``label``], ``mount``, ``focus``,
        ``receptors`` (letters, e.g. ``RL``), ``receptor_angles`` (deg),
        [``station``, ``station_distance`` (m), ``station_mount``,
        ``station_focus``: the catalogue's station within
        `~astropy_feedrot.visibilities.CATALOGUE_TOLERANCE` and its mount
        and focus, empty where there is none] and ``problem``: empty, or
        why the antenna cannot be corrected as the file gives it (an
        orbiting antenna, a mount without a model, receptors that cannot be
        used), or that its mount or focus differs from the catalogue's.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import antenna_table, read_antennas
    >>> table = antenna_table(*read_antennas(sample_file("vla_day2_8chan.uvfits")))
    >>> [list(map(str, table[c][:3])) for c in ("name", "label", "receptors")]
    [['W09', 'E02', 'E09'], ['0', '0', '0'], ['RL', 'RL', 'RL']]
    >>> str(table["mount"][0]), str(table["focus"][0])
    ('AltAzMount()', 'CassegrainFocus()')
    >>> str(table["station"][0]), str(table["problem"][0])
    ('VLA_W9', '')

    (casacore wrote a blank ``POLTYB`` for this file: the second receptor
    is completed from the first, `~astropy_feedrot.antennas.receptors.Receptors.paired`.)
    """
    numbers = sorted(antennas)
    matches = catalogue_stations(antennas, catalogue)
    rows = []
    for number in numbers:
        antenna = antennas[number]
        x, y, z = (getattr(antenna.location, c).to_value("m") for c in "xyz")
        receptors = antenna.receptors
        row = dict(number=number, name=antenna.name or "", x=x, y=y, z=z)
        unusable = isinstance(antenna, UnusableAntenna)
        if software is not None:
            row["label"] = ""
            if unusable and antenna.mount is None:
                row["label"] = "" if antenna.label is None else str(antenna.label)
            else:
                with contextlib.suppress(ValueError):
                    row["label"] = str(label_from_mount(antenna.mount, antenna.focus,
                                                        software))
        row.update(mount="" if antenna.mount is None else repr(antenna.mount),
                   focus="" if antenna.mount is None else repr(antenna.focus or
                                                               CassegrainFocus()),
                   receptors="" if receptors is None else receptors.types,
                   receptor_angles=" ".join(f"{a:g}" for a in receptors.angles.value)
                   if receptors is not None else "")
        problem = antenna.reason if unusable else ""
        if catalogue is not False:
            match = matches.get(number)
            row.update(station="" if match is None else match.station,
                       station_distance=np.nan if match is None else match.distance,
                       station_mount="" if match is None else repr(match.mount),
                       station_focus="" if match is None else repr(match.focus))
            if match is not None and not match.agrees and not unusable:
                problem = (f"the file's mount and focus differ from the catalogue's "
                           f"{match.station}: --mounts catalogue takes the catalogue's")
        row["problem"] = problem
        rows.append(row)
    table = Table(rows=rows) if rows else Table(names=["number", "name", "x", "y", "z"])
    for column in ("x", "y", "z", "station_distance"):
        if column in table.colnames:
            table[column].unit = "m"
            table[column].format = ".4f" if column != "station_distance" else ".1f"
    if "receptor_angles" in table.colnames:
        table["receptor_angles"].description = "angles of the receptors in the antenna (deg)"
    if "station" in table.colnames:
        table["station"].description = ("the station catalogue's station within "
                                        f"{CATALOGUE_TOLERANCE:g}")
    if "problem" in table.colnames:
        table["problem"].description = "why the antenna cannot be corrected as the file gives it"
    return table


def correct_file(path, output, *, overwrite=False, progress=False, client=None,
                 data_column=None, corrected_column="CORRECTED_DATA", overwrite_column=False,
                 correction=None, **options):
    """Write a copy of a visibility file with the feed rotation removed.

    Parameters
    ----------
    path : str or path-like
        The input, of any kind of `FILE_KINDS`; never modified.
    output : str or path-like
        Where to write. A FITS-IDI input gives a FITS-IDI output; a
        Measurement Set written as ``.ms`` is a casacore copy of the input
        corrected in place (`~astropy_feedrot.visibilities.correct_ms`,
        ``data_column`` into ``corrected_column``); any other input is
        written by pyuvdata in the format its extension names (``.uvfits``,
        ``.uvh5``, ``.ms``...; ``.fits`` is UVFITS for a UVFITS input):
        `~astropy_feedrot.visibilities.check_output_format`. An MSv4
        processing set is corrected in place only
        (`~astropy_feedrot.visibilities.correct_processing_set`).
    overwrite : bool, optional
        Replace an existing output (never the input).
    progress : bool or callable, optional
        Show a progress bar (astropy's `~astropy.utils.console.ProgressBar`,
        on standard error when it is a terminal), or call
        ``progress(done, total)``: over the chunks of a FITS-IDI file or a
        Measurement Set corrected as a Measurement Set, read and corrected
        a chunk at a time; for a file pyuvdata reads, in bytes of the input
        counted three times: read (at once), corrected (a chunk at a time)
        and written (at once), so that the bar is drawn before the read.
    client : `dask.distributed.Client`, optional
        For FITS-IDI and Measurement Sets, correct the chunks of rows on its
        workers.
    data_column, corrected_column, overwrite_column : optional
        For a Measurement Set copied into a Measurement Set: as in
        `~astropy_feedrot.visibilities.correct_ms` (the copy's
        ``corrected_column`` holds the correction; ``DATA`` and every
        other column are the input's).
    correction : `~astropy_feedrot.visibilities.Correction`, optional
        The correction's options (direction, frame, convention, vertical,
        pole, feeds, mounts, catalogue, ionosphere, redo), made once...
    **options
        ...or given here, as `~astropy_feedrot.visibilities.Correction`
        takes them.

    Returns
    -------
    pathlib.Path
        The output written.

    Raises
    ------
    FileNotFoundError, FileExistsError, ValueError
        For a missing input, an existing output without ``overwrite``, the
        input as output, an aperture array's data (before anything else is
        read), or data that cannot be corrected (see
        `~astropy_feedrot.visibilities.correct_uvdata` and
        `~astropy_feedrot.visibilities.correct_fitsidi`); an antenna
        without receptors is named, with what the station catalogue found.

    Warns
    -----
    CatalogueReceptorsWarning
        Once, naming the antennas, their stations and the source, if some
        took their receptors from the station catalogue.
    CatalogueMountWarning
        Once, naming them with both, if the file's mount or focus of some
        antennas differs from their catalogue station's.
    UncorrectedBaselinesWarning
        Once, if some rows are on baselines to an orbiting antenna: they
        are left as they were, the others corrected.

    Notes
    -----
    `Correction.correct <astropy_feedrot.visibilities.Correction.correct>`
    with an output: the adapter of the input's kind writes a temporary file
    (or directory) beside the output and renames it into place at the end,
    so that an interrupted run leaves no partial output and an existing
    output as it was.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import correct_file
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "corrected.uvfits"
    >>> correct_file(sample_file("vla_day2_8chan.uvfits"), out).name  # doctest: +IGNORE_WARNINGS
    'corrected.uvfits'
    """
    if output is None:
        raise TypeError("correct_file writes a copy: give its output (correct_ms and "
                        "correct_processing_set correct in place)")
    return Correction.of(correction, **options).correct(
        path, output, overwrite=overwrite, progress=progress, client=client,
        data_column=data_column, corrected_column=corrected_column,
        overwrite_column=overwrite_column)
