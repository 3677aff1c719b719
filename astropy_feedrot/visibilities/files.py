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
import os
import re
import shutil
import tempfile
import warnings
from pathlib import Path

import numpy as np
from astropy.table import Table

from ..antennas.focus import CassegrainFocus
from ..core.outputs import publish, same_file
from ..core.progress import check_progress, progress_steps
from ..ionosphere import IonosphereError
from ..stations.labels import label_from_mount
from .antenna_tables import fits_telescopes, writing_program
from .catalogue import (
    CATALOGUE_TOLERANCE,
    catalogue_stations,
    check_mounts_option,
)
from .fitsidi import correct_fitsidi, fitsidi_antennas
from .history import CorrectionRefused, check_history
from .kinds import existing_path, file_kind
from .ms import correct_ms
from .ms_antennas import ms_antennas, ms_telescopes
from .msv4 import processing_set_antennas, read_processing_set
from .ms_tables import MSError, check_column_history, column_records, copy_ms
from .poles import convention_options
from .resolve import refuse_aperture_array, resolve_antennas
from .unusable import UnusableAntenna
from .uvdata import antennas_from_uvdata, correct_uvdata
from .uvdata_files import PYUVDATA_TYPES, read_uvdata, write_uvdata
from .uvfits import uvfits_antennas

__all__ = ["read_antennas", "file_telescopes", "antenna_table", "correct_file",
           "FITSIDI_EXTENSIONS", "OUTPUT_EXTENSIONS", "check_output_format"]

#: The kind of output each extension names (lower case; ``.idi`` followed by
#: digits, the EVN archive's ``.IDI1``, is FITS-IDI too). ``None``: the FITS
#: extensions that FITS-IDI and UVFITS files both use, whose kind is the input's.
OUTPUT_EXTENSIONS = {
    ".idifits": "fits-idi", ".fitsidi": "fits-idi", ".idi": "fits-idi",
    ".fits": None, ".fit": None, ".fts": None,
    ".uvfits": "uvfits", ".uvf": "uvfits",
    ".uvh5": "uvh5", ".h5": "uvh5", ".hdf5": "uvh5",
    ".ms": "ms", ".uv": "miriad", ".miriad": "miriad",
}

#: Extensions of a FITS-IDI output (a FITS-IDI input is corrected into
#: FITS-IDI), and ``.idi`` followed by digits (``.IDI1``), in any case.
FITSIDI_EXTENSIONS = tuple(e for e, k in OUTPUT_EXTENSIONS.items() if k in ("fits-idi", None))

_NUMBERED_IDI = re.compile(r"\.idi[0-9]+")


def file_telescopes(path, kind=None):
    """The telescope names a visibility file gives, of any kind of `FILE_KINDS`.

    ``TELESCOP`` and ``ARRNAM`` of FITS-IDI and UVFITS files, ``TELESCOPE_NAME`` of
    a Measurement Set's ``OBSERVATION`` rows, pyuvdata's ``telescope.name`` of the
    other kinds (their metadata read, not their data).

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities.files import file_telescopes
    >>> file_telescopes(sample_file("vla_sim.ms"))
    ['VLA']
    """
    kind = file_kind(path) if kind is None else kind
    if kind in ("fits-idi", "uvfits"):
        return fits_telescopes(path)
    if kind == "ms":
        return ms_telescopes(path)
    if kind == "msv4":
        return sorted({t for partition in read_processing_set(path).children.values()
                       for t in processing_set_antennas(partition)[2]})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's complaints come with the data's read
        uv = read_uvdata(path, read_data=False, file_type=PYUVDATA_TYPES[kind])
    return [uv.telescope.name] if uv.telescope.name else []


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
    telescope = file_telescopes(path, kind)
    antennas = resolve_antennas(antennas, telescope=telescope, mounts=mounts,
                                catalogue=catalogue, where=str(path))
    return antennas, software


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


def _check_output(source, output, overwrite):
    """The resolved output path, refused if it is the input or exists without overwrite."""
    target = Path(os.fspath(output)).expanduser()
    resolved = target.resolve()
    if same_file(resolved, source.resolve()):
        raise ValueError(f"the output {str(target)!r} is the input; the input is never "
                         "modified: choose another name")
    if target.exists() and not overwrite:
        raise FileExistsError(f"{str(target)!r} exists; pass overwrite=True (--overwrite) to "
                              "replace it")
    if not resolved.parent.is_dir():
        raise FileNotFoundError(f"cannot write {str(target)!r}: directory "
                                f"{str(resolved.parent)!r} does not exist")
    return resolved


def check_output_format(kind, output):
    """The kind of file `correct_file` writes for an input of ``kind`` into ``output``.

    The output's kind follows its extension where the extension names one
    kind (`OUTPUT_EXTENSIONS`: ``.uvfits``/``.uvf``, ``.uvh5``, ``.ms``,
    ``.IDI1``, ``.idifits``...), and the input's kind where it names two:
    ``.fits`` (and ``.fit``, ``.fts``, any case) is FITS-IDI for a FITS-IDI
    input, UVFITS for a UVFITS input. A FITS-IDI input is always corrected
    into FITS-IDI (there is no conversion); other inputs are written by
    pyuvdata, which writes no FITS-IDI.

    Parameters
    ----------
    kind : str
        The input's kind, one of `~astropy_feedrot.visibilities.FILE_KINDS`
        (`~astropy_feedrot.visibilities.file_kind`: by content, whatever
        its name).
    output : str or path-like
        The output's name.

    Returns
    -------
    str
        The output's kind: ``'fits-idi'``, ``'uvfits'``, ``'uvh5'``,
        ``'ms'`` or ``'miriad'``.

    Raises
    ------
    ValueError
        For an extension that names no kind, another kind than FITS-IDI for
        a FITS-IDI input, FITS-IDI for another input, or ``.fits`` for an
        input that is not FITS; the message lists the extensions to use.

    Examples
    --------
    >>> from astropy_feedrot.visibilities import check_output_format
    >>> check_output_format("uvfits", "out.uvh5")
    'uvh5'
    >>> check_output_format("uvfits", "out.FITS"), check_output_format("fits-idi", "x.IDI1")
    ('uvfits', 'fits-idi')
    >>> check_output_format("fits-idi", "out.uvfits")
    Traceback (most recent call last):
    ...
    ValueError: 'out.uvfits': a FITS-IDI input is corrected into a FITS-IDI copy ...
    """
    text = os.fspath(output)
    extension = Path(text.rstrip("/" + os.sep)).suffix.lower()
    if _NUMBERED_IDI.fullmatch(extension):
        named = "fits-idi"
    else:
        named = OUTPUT_EXTENSIONS.get(extension, "unknown")
    pyuvdata = ", ".join(e for e, k in OUTPUT_EXTENSIONS.items() if k not in ("fits-idi", None))
    if kind == "msv4":
        raise ValueError(f"{text!r}: an MSv4 processing set is corrected in place, as a new "
                         "data group beside its data (correct_processing_set; feedrot correct "
                         "PS.ps.zarr --in-place), not into a copy")
    if kind == "fits-idi":
        if named in ("fits-idi", None):
            return "fits-idi"
        raise ValueError(f"{text!r}: a FITS-IDI input is corrected into a FITS-IDI copy "
                         "(there is no conversion to other formats); give the output one "
                         f"of the extensions {', '.join(FITSIDI_EXTENSIONS)} or .idiN "
                         "(.IDI1)")
    if named == "fits-idi":
        raise ValueError(f"{text!r}: {extension} names a FITS-IDI file, but a {kind} input "
                         "is written by pyuvdata, which writes no FITS-IDI; use one of "
                         f"{pyuvdata}")
    if named is None:
        if kind == "uvfits":
            return "uvfits"
        raise ValueError(f"{text!r}: {extension} is used by both FITS-IDI and UVFITS; a "
                         f"{kind} input is written as UVFITS with .uvfits (or .uvf), or use "
                         f"one of {pyuvdata}")
    if named == "unknown":
        raise ValueError(f"cannot tell a format from the extension of {text!r}; use one of "
                         f"{pyuvdata}" + (", .fits" if kind == "uvfits" else ""))
    return named


def correct_file(path, output, *, frame="apparent", vertical=None, overwrite=False,
                 progress=False, direction="remove", feeds=None, redo=False, pole=None,
                 client=None, catalogue=None, data_column=None,
                 corrected_column="CORRECTED_DATA", overwrite_column=False,
                 mounts="file", convention="rigorous", ionosphere=None):
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
        `~astropy_feedrot.visibilities.check_output_format`.
    frame : str, optional
        ``'apparent'`` (default) or a celestial frame such as ``'icrs'``:
        north of the corrected polarization angles (see
        `~astropy_feedrot.visibilities.frame_position_angle`).
    vertical : {'geodetic', 'geocentric'}, optional
        Default: the convention's.
        The local vertical (``'geocentric'`` reproduces CASA).
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
    direction : {'remove', 'apply'}, optional
        Remove the feed rotation (default), or apply it to a model.
    feeds : `~astropy_feedrot.Receptors` or mapping, optional
        Receptors for antennas the file gives none
        (`~astropy_feedrot.visibilities.with_receptors`).
    redo : bool, optional
        Correct data whose history says they were corrected in the same
        direction already.
    convention : {'rigorous', 'casa'}, optional
        The vertical and pole of `~astropy_feedrot.visibilities.poles.CONVENTIONS`:
        ``'rigorous'`` (default: geodetic, Earth-fixed pole) or ``'casa'``
        (CASA's applycal: geocentric, no polar motion); ``vertical`` and
        ``pole`` given explicitly replace its choices.
    pole : {'itrs', 'casa'}, optional
        Default: the convention's.
        The pole of the parallactic angle (`~astropy_feedrot.visibilities.poles`).
    client : `dask.distributed.Client`, optional
        For FITS-IDI and Measurement Sets, correct the chunks of rows on its
        workers.
    catalogue : `~astropy_feedrot.stations.StationCatalogue`, path or False, optional
        Where antennas that neither the file nor ``feeds`` give receptors
        take theirs: the station catalogue's receptors of the station of
        the antenna's name, if the antenna lies within
        `~astropy_feedrot.visibilities.CATALOGUE_TOLERANCE` of it, else of
        the station with receptors within
        `~astropy_feedrot.visibilities.PAD_TOLERANCE` of the antenna, else
        those every station of the file's telescope states alike, within
        `~astropy_feedrot.visibilities.ARRAY_TOLERANCE`
        (`~astropy_feedrot.visibilities.catalogue_receptors`). The embedded
        catalogue by default, another one, or False for none.
    data_column, corrected_column, overwrite_column : optional
        For a Measurement Set copied into a Measurement Set: as in
        `~astropy_feedrot.visibilities.correct_ms` (the copy's
        ``corrected_column`` holds the correction; ``DATA`` and every
        other column are the input's).
    mounts : {'file', 'catalogue'}, optional
        Whose mount and focus an antenna within
        `~astropy_feedrot.visibilities.CATALOGUE_TOLERANCE` of a station of
        ``catalogue`` takes where the two differ: the file's (default) or the
        catalogue's (`~astropy_feedrot.visibilities.catalogue_mounts`).
    ionosphere : `~astropy_feedrot.ionosphere.Ionosphere`, optional
        Remove (apply) the ionospheric Faraday rotation too, per antenna,
        epoch and channel, in the same pass (:doc:`/ionosphere`).

    Returns
    -------
    pathlib.Path
        The output written.

    Raises
    ------
    FileNotFoundError, FileExistsError, ValueError
        For a missing input, an existing output without ``overwrite``, the
        input as output, or data that cannot be corrected (see
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
    The output is written to a temporary file (or directory) beside it and
    renamed into place at the end: an interrupted run leaves no partial
    output and an existing output as it was.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import correct_file
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "corrected.uvfits"
    >>> correct_file(sample_file("vla_day2_8chan.uvfits"), out).name  # doctest: +IGNORE_WARNINGS
    'corrected.uvfits'
    """
    vertical, pole = convention_options(convention, vertical, pole)
    source = existing_path(path)
    kind = file_kind(source)
    written = check_output_format(kind, output)  # before any work
    copy = kind == "ms" and written == "ms"
    # The one refusal that needs no antenna: before any reader of the format.
    refuse_aperture_array(file_telescopes(source, kind), catalogue, where=str(source))
    columns = dict(data_column=data_column, corrected_column=corrected_column,
                   overwrite_column=overwrite_column)
    if not copy and (data_column is not None or overwrite_column or
                     corrected_column != "CORRECTED_DATA"):
        raise ValueError("data_column, corrected_column and overwrite_column are for a "
                         "Measurement Set written as a Measurement Set (.ms)")
    target = _check_output(source, output, overwrite)
    if copy:
        # The FEED table gives the receptors (feeds= replaces them); the catalogue is
        # only compared with the mounts.
        work = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}."))
        try:
            temporary = copy_ms(source, work / target.name)
            try:
                correct_ms(temporary, direction=direction, frame=frame, vertical=vertical,
                           progress=progress, feeds=feeds, redo=redo, pole=pole,
                           client=client, mounts=mounts, catalogue=catalogue,
                           ionosphere=ionosphere, **columns)
            except CorrectionRefused as error:  # named as the input, not the copy
                raise type(error)(error.template.replace(str(temporary), str(source))) \
                    from None
            except (MSError, IonosphereError) as error:
                raise type(error)(str(error).replace(str(temporary), str(source))) from None
            except KeyboardInterrupt:
                raise KeyboardInterrupt(f"{str(target)!r} was not written (the copy being "
                                        "corrected is removed)") from None
            publish(temporary, target, overwrite=overwrite)
        finally:
            with contextlib.suppress(OSError):
                shutil.rmtree(work)
        return target
    if kind == "fits-idi":
        correct_fitsidi(source, target, frame=frame, overwrite=overwrite, progress=progress,
                        vertical=vertical, direction=direction, feeds=feeds, redo=redo,
                        pole=pole, client=client, catalogue=catalogue, mounts=mounts,
                        ionosphere=ionosphere)
        return target

    if kind == "ms":  # pyuvdata reads DATA: what the HISTORY says of it (CASA's too)
        check_column_history(source, column_records(source), "DATA", "DATA", direction, redo)
    size = _stored_size(source)
    # pyuvdata reads and writes in one call each: the bar is drawn before the read, and
    # counts the input's bytes three times (read, corrected chunk by chunk, written).
    with progress_steps(check_progress(progress), 3 * size) as step:
        uv = read_uvdata(source, file_type=PYUVDATA_TYPES[kind])
        step(size)
        check_history(uv.history, direction, str(source), redo=redo)  # the file named
        correct_uvdata(uv, inplace=True, frame=frame, vertical=vertical,
                       progress=_share(step, size) if progress else False,
                       direction=direction, feeds=feeds, redo=redo, catalogue=catalogue,
                       mounts=mounts, pole=pole, ionosphere=ionosphere)
        work = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}."))
        try:
            temporary = work / target.name
            write_uvdata(uv, temporary, kind=written)
            step(size)
            publish(temporary, target, overwrite=overwrite)  # exclusive without overwrite
        finally:
            with contextlib.suppress(OSError):
                shutil.rmtree(work)
    return target


def _stored_size(path):
    """Bytes of a file, or of every file under a directory (a Measurement Set)."""
    path = Path(path)
    if not path.is_dir():
        return path.stat().st_size
    return sum(os.path.getsize(os.path.join(root, name))
               for root, _, names in os.walk(path) for name in names)


def _share(step, units):
    """A ``progress(done, total)`` of a part of the work that counts ``units`` of
    ``step``'s, in proportion."""
    given = 0

    def report(done, total):
        nonlocal given
        now = units * done // max(total, 1)
        step(now - given)
        given = now
    return report
