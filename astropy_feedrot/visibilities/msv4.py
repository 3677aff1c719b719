# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""MSv4 processing sets (xradio): the feed rotation removed lazily, as a new data group.

A processing set is a tree of partitions, each one MSv4 (an
`xarray.DataTree` whose ``VISIBILITY`` has the dimensions ``time``,
``baseline_id``, ``frequency``, ``polarization``, with its ``antenna_xds``
and ``field_and_source_xds``). `correct_processing_set` adds to every
partition a data group (``corrected``) whose ``VISIBILITY_CORRECTED`` is
the ``base`` group's ``VISIBILITY`` with the feed rotation removed, as
`~astropy_feedrot.visibilities.correct_ms` removes it from a Measurement
Set v2; its flags, weights, UVW and field and source table are the base
group's. Nothing is read but the coordinates and the antenna and field
tables: the new variable is a dask array that any scheduler computes (dask's
threads, a dask.distributed cluster, Ray's dask scheduler). Given a store
on disk, only the new arrays are written into it; every array that was
there stays as it was.

The steps are the pipeline's (:doc:`/correcting`): the antennas are
resolved once (`~astropy_feedrot.visibilities.resolve.resolve_antennas`:
aperture arrays, the catalogue's mounts, the given receptors), the angles
computed once per epoch and antenna (`~astropy_feedrot.visibilities.
receptor_position_angles`), and each block of visibilities turned with
`~astropy_feedrot.applied.correction.correct_receptor_visibilities`.

xradio is optional (the ``msv4`` extra: ``python -m pip install
"astropy_feedrot[msv4]"``), imported when a function here is called.
"""
import contextlib
import datetime
import os
import warnings
from pathlib import Path

import numpy as np
from astropy import units as u
from astropy.coordinates import FK5, ICRS, EarthLocation, SkyCoord
from astropy.time import Time

from ..applied.correction import correct_receptor_visibilities
from ..core.exceptions import (
    DegenerateGeometryWarning,
    UncorrectedBaselinesWarning,
    warn_caller,
)
from .correction import Correction, refuse_column_options, register_adapter
from .faraday import lambda_squared, rotation_measure_rows
from .history import APPLY_MARK, HISTORY_MARK, AlreadyCorrected, CorrectionRefused
from .kinds import check_output_format, is_processing_set
from .ms_antennas import describe_antenna
from .receptors import receptor_position_angles, warn_unusual_angles
from .unusable import usable_antennas, warn_skipped

# The examples need xradio (the msv4 extra).
__doctest_requires__ = {("correct_processing_set", "read_processing_set"): ["xradio"]}

__all__ = ["correct_processing_set", "correct_processing_set_file", "processing_set_antennas",
           "processing_set_telescopes", "read_processing_set", "data_groups", "GROUPS",
           "MSv4Error"]

#: Per direction: the data group read, the data group added and its variable.
GROUPS = {"remove": ("base", "corrected", "VISIBILITY_CORRECTED"),
          "apply": ("model", "model_corrupted", "VISIBILITY_MODEL_CORRUPTED")}


def data_groups(direction, data_group=None, new_group=None):
    """The data group read, the data group added and its variable (``VISIBILITY_`` and
    the group's name in capitals, as xradio names ``corrected`` and ``model``'s).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.msv4 import data_groups
    >>> data_groups("remove")
    ('base', 'corrected', 'VISIBILITY_CORRECTED')
    >>> data_groups("remove", "corrected", "feedrot")
    ('corrected', 'feedrot', 'VISIBILITY_FEEDROT')
    """
    source, new, _ = GROUPS[direction]
    source = source if data_group is None else str(data_group)
    new = new if new_group is None else str(new_group)
    if not new.isidentifier():
        raise ValueError(f"new_group must be a name of letters, digits and underscores, got "
                         f"{new!r}")
    if new == source:
        raise ValueError(f"new_group {new!r} is the data group read: the correction goes "
                         "into a data group of its own")
    return source, new, f"VISIBILITY_{new.upper()}"


_FRAMES = {"icrs": ICRS(), "fk5": FK5(equinox="J2000")}


class MSv4Error(ValueError):
    """A processing set that cannot be corrected as it is (the message says why)."""


def read_processing_set(path):
    """A processing set on disk, opened lazily with xradio's ``open_processing_set``.

    Raises
    ------
    ImportError
        Without xradio, naming the extra to install.
    MSv4Error
        If ``path`` is not a processing set.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities.msv4 import read_processing_set
    >>> read_processing_set(sample_file("vla_sim.ms"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    astropy_feedrot.visibilities.msv4.MSv4Error: '...vla_sim.ms' is not an MSv4 processing set ...
    """
    if not is_processing_set(path):
        raise MSv4Error(f"{str(path)!r} is not an MSv4 processing set (a zarr store "
                        "whose root is of type 'processing_set')")
    try:
        from xradio.measurement_set import open_processing_set  # optional dependency
    except ImportError:
        raise ImportError("MSv4 processing sets need xradio: python -m pip install "
                          '"astropy_feedrot[msv4]"') from None
    with _zarr_quiet():
        return open_processing_set(str(path))


@contextlib.contextmanager
def _zarr_quiet():
    """Without zarr 3's warnings on the stores xradio writes: their consolidated metadata
    and their strings (neither in zarr 3's specification yet; the user can do nothing)."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Consolidated metadata is currently not")
        warnings.filterwarnings("ignore", message="The data type .* does not have a Zarr V3")
        yield


def _partitions(tree, where):
    """The partitions of visibilities; those of single-dish spectra are named in a
    warning and left as they are (a feed rotation per antenna, not per baseline)."""
    nodes = [(name, node) for name, node in tree.children.items()
             if node.attrs.get("type") == "visibility"]
    spectra = [name for name, node in tree.children.items()
               if node.attrs.get("type") == "spectrum"]
    if spectra:
        warn_caller(f"{where}: the partitions of single-dish spectra {spectra} are left as "
                    "they are: only visibilities are corrected", UncorrectedBaselinesWarning)
    if not nodes:
        raise MSv4Error(f"{where} holds no MSv4 partition of visibilities (no child of type "
                        "'visibility')")
    return nodes


def _values(variable):
    return np.asarray(variable.values)


def processing_set_antennas(partition, *, vertical="geodetic", where="the partition"):
    """The antennas of one MSv4 partition, from its ``antenna_xds``.

    Parameters
    ----------
    partition : `xarray.DataTree`
        One MSv4 of a processing set.
    vertical : {'geodetic', 'geocentric'}, optional
        As `~astropy_feedrot.Antenna`.
    where : str, optional
        The partition, for the messages.

    Returns
    -------
    antennas : dict
        ``{index in antenna_name: Antenna or UnusableAntenna}``, each with
        the receptors of ``polarization_type`` and ``ANTENNA_RECEPTOR_ANGLE``
        and the mount of ``mount`` (xradio's labels, which are casacore's in
        lower case).
    names : list of str
        The antenna names, in the order of the indices.
    telescopes : list of str
        The telescope names (``telescope_name``, ``overall_telescope_name``).

    Raises
    ------
    MSv4Error
        For positions that are not geocentric ITRS in metres.

    Examples
    --------
    See `correct_processing_set`.
    """
    antenna = partition["antenna_xds"].to_dataset()
    position = antenna["ANTENNA_POSITION"]
    frame = str(position.attrs.get("frame", "ITRS")).upper()
    system = str(position.attrs.get("coordinate_system", "geocentric")).lower()
    units = position.attrs.get("units", "m")
    units = units[0] if isinstance(units, (list, tuple)) else units
    if frame not in ("ITRS", "ITRF") or system != "geocentric":
        raise MSv4Error(f"{where}: ANTENNA_POSITION is {system} {frame}, not geocentric "
                        "ITRS; convert the positions first")
    xyz = (_values(position) * u.Unit(units)).to_value(u.m)
    names = [str(n) for n in _values(antenna["antenna_name"])]
    mounts = _values(antenna["mount"]) if "mount" in antenna else [""] * len(names)
    types = _values(antenna["polarization_type"]) if "polarization_type" in antenna \
        else None
    angles = np.degrees(_values(antenna["ANTENNA_RECEPTOR_ANGLE"])) \
        if "ANTENNA_RECEPTOR_ANGLE" in antenna else None
    antennas = {}
    for index, name in enumerate(names):
        found = set()
        if types is not None:
            letters = "".join(str(t).strip().upper() for t in np.atleast_1d(types[index]))
            alpha = np.zeros(len(letters)) if angles is None else np.atleast_1d(angles[index])
            found = {(letters, tuple(np.round(alpha[:len(letters)], 9)))}
        antennas[index] = describe_antenna(
            EarthLocation.from_geocentric(*xyz[index], unit=u.m), name,
            str(mounts[index]).upper(), found, vertical=vertical, keep=True,
            where=f"{where}, antenna_xds, antenna {name}")
    return antennas, names, _telescopes(antenna)


def _telescopes(antenna):
    """The telescope names of an ``antenna_xds`` (``telescope_name``,
    ``overall_telescope_name``)."""
    telescopes = [str(t) for t in np.unique(_values(antenna["telescope_name"]))] \
        if "telescope_name" in antenna.coords else []
    overall = antenna.attrs.get("overall_telescope_name")
    return list(dict.fromkeys(t for t in [*telescopes, overall] if t))


def _sources(partition, group, where):
    """{field index: SkyCoord or moving field} and the field index of each time."""
    table = partition[group["field_and_source"]].to_dataset()
    direction = table["FIELD_PHASE_CENTER_DIRECTION"]
    frame_name = str(direction.attrs.get("frame", "icrs")).lower()
    if frame_name not in _FRAMES:
        raise MSv4Error(f"{where}: FIELD_PHASE_CENTER_DIRECTION is in frame {frame_name!r}; "
                        f"the frames read are {sorted(_FRAMES)}")
    frame = _FRAMES[frame_name]
    values = (_values(direction) * u.Unit(direction.attrs.get("units", "rad"))).to_value(u.rad)
    moving = sorted({str(d) for name in ("FIELD_PHASE_CENTER_DIRECTION", "SOURCE_DIRECTION")
                     if name in table for d in table[name].dims if str(d).startswith("time")})
    if moving:
        # xradio's ephemeris fields (JPL-Horizons tables: SOURCE_DIRECTION on
        # time_ephemeris, the phase centre relative to it): not read yet; refused
        # rather than corrected as a fixed source.
        raise MSv4Error(f"{where}: {group['field_and_source']} describes a moving field (its "
                        f"dimensions {moving}); ephemeris fields are not corrected in MSv4 "
                        "yet: correct the Measurement Set v2 it came from with correct_ms "
                        "(it reads CASA's ephemeris tables), or convert that")
    fields = [str(f) for f in np.atleast_1d(_values(partition["field_name"]))]
    names = [str(n) for n in np.atleast_1d(_values(table["field_name"]))]
    values = values.reshape(len(names), 2)
    sources = {k: SkyCoord(values[k, 0] * u.rad, values[k, 1] * u.rad, frame=frame)
               for k in range(len(names))}
    missing = sorted(set(fields) - set(names))
    if missing:
        raise MSv4Error(f"{where}: the times use fields {missing} that "
                        f"{group['field_and_source']} lacks")
    index = {name: k for k, name in enumerate(names)}
    return sources, np.array([index[f] for f in fields])


def _times(partition, where):
    time = partition["time"]
    scale = str(time.attrs.get("scale", "utc")).lower()
    form = str(time.attrs.get("format", "unix")).lower()
    if form not in ("unix", "unix_tai"):
        raise MSv4Error(f"{where}: time is in format {form!r}; 'unix' is read")
    return Time(_values(time), format=form, scale=scale)


def _group(partition, name, where):
    groups = partition.attrs.get("data_groups", {})
    if name not in groups:
        raise MSv4Error(f"{where} has no data group {name!r} (it has {sorted(groups)})")
    return groups[name]


def _refuse_again(partition, new, direction, redo, where):
    """Refuse to write a data group that exists, unless ``redo`` and it is ours."""
    groups = partition.attrs.get("data_groups", {})
    if new not in groups:
        return
    description = str(groups[new].get("description", ""))
    mark = HISTORY_MARK if direction == "remove" else APPLY_MARK
    if not description.startswith(mark):
        raise CorrectionRefused(f"{where} has a data group {new!r} that this package did "
                                f"not write ({description!r}); it is left as it is: give "
                                "the correction a data group of another name (new_group=, "
                                "--group NAME)")
    if not redo:
        raise AlreadyCorrected(f"{where}: its data group {new!r} holds this correction "
                               f"already ({description}); pass <<redo>> to compute it again")


def _angle_table(partition, source, antennas, names, products, frame, where,
                 ionosphere=None):
    """Receptor position angles (deg) and, with an ionosphere, the rotation measure
    (rad/m^2) per (time, antenna), shape (T, A, 3); the antennas of each baseline; the
    orbiting antennas."""
    first = [names.index(str(n)) for n in _values(partition["baseline_antenna1_name"])]
    second = [names.index(str(n)) for n in _values(partition["baseline_antenna2_name"])]
    used = np.unique(first + second)
    usable, skip = usable_antennas(antennas, used, where)
    ground = np.array([n for n in used.tolist() if n in usable], int)
    times = _times(partition, where)
    sources, field = _sources(partition, source, where)
    theta = np.full((times.size, len(names), 3), np.nan)
    theta[..., 2] = 0.0
    if ground.size:
        rows = np.tile(ground, times.size)
        epochs = times[np.repeat(np.arange(times.size), ground.size)]
        field = np.repeat(field, ground.size)
        theta_rows, _ = receptor_position_angles(
            usable, rows, rows, epochs, sources, field, products=products, frame=frame,
            where=where, hint="give them with feeds=")
        theta[:, ground, :2] = theta_rows.reshape(times.size, ground.size, 2)
        if ionosphere is not None:
            rm = rotation_measure_rows(ionosphere, usable, rows, epochs, sources, field, where)
            theta[:, ground, 2] = rm.reshape(times.size, ground.size)
    warn_unusual_angles({n: usable[n] for n in ground.tolist()}, where)
    return theta, np.array(first), np.array(second), skip


def _correct_block(visibilities, table1, table2, lambda2=None, *, products, direction):
    """One block: the angles of both antennas (deg) and their RM (rad/m^2) along the
    last axis of ``table1``, ``table2``; lambda^2 (m^2) of the block's channels."""
    theta1, theta2 = table1[..., :2], table2[..., :2]
    if lambda2 is not None:  # theta - RM lambda^2, per channel (faraday.faraday_angles)
        theta1 = theta1 - np.degrees(table1[..., 2:] * lambda2[..., None])
        theta2 = theta2 - np.degrees(table2[..., 2:] * lambda2[..., None])
    out = np.empty_like(visibilities)
    with np.errstate(invalid="ignore"):  # NaN angles give NaN, counted beforehand
        correct_receptor_visibilities(visibilities, theta1 * u.deg, theta2 * u.deg, products,
                                      out=out, direction=direction)
    return out


def _corrected(partition, source, theta, first, second, skip, products, direction,
               faraday):
    import xarray as xr  # with xradio

    data = partition[source["correlated_data"]]
    # The variable's own chunks (its coordinates may be chunked otherwise).
    chunks = data.variable.chunksizes if data.variable.chunks is not None else None
    table = xr.DataArray(theta, dims=("time", "feedrot_antenna", "feedrot_angle"))
    if chunks:
        table = table.chunk({"time": chunks["time"]})
    theta1 = table.isel(feedrot_antenna=xr.DataArray(first, dims="baseline_id"))
    theta2 = table.isel(feedrot_antenna=xr.DataArray(second, dims="baseline_id"))
    inputs = [data.variable, theta1.variable, theta2.variable]
    core = [["polarization"], ["feedrot_angle"], ["feedrot_angle"]]
    if faraday:
        frequency = partition["frequency"]
        lambda2 = xr.DataArray(lambda_squared(_values(frequency) * u.Unit(
            frequency.attrs.get("units", "Hz"))), dims="frequency")
        if chunks:
            lambda2 = lambda2.chunk({"frequency": chunks["frequency"]})
        inputs.append(lambda2.variable)
        core.append([])
    corrected = xr.apply_ufunc(
        _correct_block, *inputs, input_core_dims=core,
        output_core_dims=[["polarization"]], dask="parallelized",
        output_dtypes=[data.dtype], kwargs=dict(products=products, direction=direction))
    corrected = corrected.transpose(*data.dims)
    if skip:  # baselines to an orbiting antenna: as they were
        names = [i for i in range(len(first))
                 if first[i] in skip or second[i] in skip]
        keep = xr.DataArray(np.isin(np.arange(len(first)), names), dims="baseline_id")
        corrected = xr.where(keep, data.variable, corrected)
    return xr.DataArray(corrected, dims=data.dims, attrs=dict(data.attrs))


def _check_products(products, where):
    try:
        # Receptors at right angles: only the products are checked here.
        correct_receptor_visibilities(np.zeros((1, len(products)), complex), [0, 90] * u.deg,
                                      [0, 90] * u.deg, products)
    except ValueError as error:
        raise MSv4Error(f"{where}: {error}") from None


def _partition(name, partition, correction, groups, where):
    """The partition with its new data group (a new tree; the input is left as it is)."""
    direction, frame = correction.direction, correction.frame
    source_name, new_name, variable = groups
    where = f"{where}, partition {name!r}"
    source = _group(partition, source_name, where)
    _refuse_again(partition, new_name, direction, correction.redo, where)
    products = [str(p).upper() for p in _values(partition["polarization"])]
    _check_products(products, where)
    antennas, names, telescopes = processing_set_antennas(
        partition, vertical=correction.vertical, where=where)
    every = antennas = correction.resolve(antennas, telescopes, where)
    try:
        with correction.pole_context():
            theta, first, second, skip = _angle_table(partition, source, antennas, names,
                                                      products, frame, where,
                                                      correction.ionosphere)
    except ValueError as error:
        raise MSv4Error(str(error)) from None
    partition = partition.copy()
    bad = np.isnan(theta).any(-1)
    undefined = int(np.count_nonzero(bad[:, first] | bad[:, second])) - \
        int(np.count_nonzero(np.isin(first, skip) | np.isin(second, skip))) * bad.shape[0]
    partition[variable] = _corrected(partition, source, theta, first, second, skip,
                                     products, direction, correction.ionosphere is not None)
    what = f"{source['correlated_data']} -> {variable}"
    if skip:
        what += f" (not the baselines to the orbiting antennas {', '.join(names[n] for n in skip)})"
    description = correction.history(what) + correction.ionosphere_text(" ") + \
        ("" if correction.pole == "itrs" else f" (pole={correction.pole})")
    group = {key: value for key, value in source.items()
             if key not in ("correlated_data", "description", "date")}
    group.update(correlated_data=variable, description=description,
                 date=datetime.datetime.now(datetime.timezone.utc).isoformat())
    partition.attrs = dict(partition.attrs,
                           data_groups={**partition.attrs["data_groups"], new_name: group})
    rows = bad.shape[0] * len(first)
    warn_skipped(every, skip, int(np.count_nonzero(np.isin(first, skip) |
                                                   np.isin(second, skip))) * bad.shape[0],
                 rows, where)
    return partition, max(undefined, 0), rows


def correct_processing_set(ps, *, data_group=None, new_group=None, write=None, correction=None,
                           **options):
    """Remove (or apply) the feed rotation of an MSv4 processing set, lazily.

    Parameters
    ----------
    ps : `xarray.DataTree` or path-like
        A processing set as xradio's ``open_processing_set`` gives it, or the
        path of one (a ``.ps.zarr`` store).
    data_group : str, optional
        The data group read (default: ``base``; with ``direction='apply'``,
        ``model``); e.g. ``corrected`` for data CASA calibrated.
    new_group : str, optional
        The data group added (default: ``corrected``; with
        ``direction='apply'``, ``model_corrupted``), its variable
        ``VISIBILITY_`` and its name in capitals: another name where the set
        has a ``corrected`` group already (an MSv2's ``CORRECTED_DATA``).
    write : bool, optional
        For a path: write the new variables into the store (default True);
        every array that was there stays as it was, and the partitions'
        ``data_groups`` attributes gain the new group, with the history
        line as its description. Ignored for a tree.
    correction : `~astropy_feedrot.visibilities.Correction`, optional
        The correction's options (direction, frame, convention, vertical,
        pole, feeds, mounts, catalogue, ionosphere, redo), made once...
    **options
        ...or given here, as `~astropy_feedrot.visibilities.Correction`
        takes them. ``direction='remove'`` (default) reads the data group
        ``base`` (``VISIBILITY``) and adds ``corrected``
        (``VISIBILITY_CORRECTED``); ``'apply'`` reads ``model``
        (``VISIBILITY_MODEL``, sky-fixed receptors) and adds
        ``model_corrupted`` (``VISIBILITY_MODEL_CORRUPTED``), as the turning
        receptors see it (`GROUPS`). ``feeds`` are keyed by antenna index
        or name; ``redo`` computes a data group this package wrote again.
        With an ionosphere, each receptor's angle becomes :math:`\\theta -
        \\mathrm{RM}\\,\\lambda^2` per channel, and the group's description
        names the IONEX files.

    Returns
    -------
    `xarray.DataTree`
        The processing set with the new data group in every partition: a new
        tree whose new variables are dask arrays (nothing computed) when
        ``ps`` is a tree or ``write`` is False; the store reopened after
        writing otherwise.

    Raises
    ------
    ImportError
        Without xradio (the ``msv4`` extra).
    MSv4Error
        For a tree that holds no partition, a partition without the data
        group read, positions that are not geocentric ITRS, fields in an
        unknown frame, ephemeris fields (moving sources, not read yet),
        linear products without all four, antennas that cannot be corrected
        (each named with its reason: an aperture array, a mount without a
        model, receptors that cannot be used); nothing is written then.
    IonosphereError
        If ``ionosphere`` does not cover the epochs of the data, or its
        table of rotation measures lacks an antenna (named).
    CorrectionRefused
        (a ValueError) If a partition has the new data group already
        (unless ``redo`` and this package wrote it).

    Warns
    -----
    DegenerateGeometryWarning
        Once, with the count, if the feed rotation is undefined for some
        time-baselines (an alt-az antenna at the zenith): they are NaN.
    UncorrectedBaselinesWarning
        Once per partition, if some baselines reach an orbiting antenna:
        they are left as they are.

    Notes
    -----
    Each partition's angles are computed once per epoch and antenna (a
    small table); each dask block of visibilities then takes the angles of
    its times and baselines. MSv4 follows the MSv2 convention
    :math:`\\langle v_1 v_2^* \\rangle`.

    Examples
    --------
    The package's VLA sample converted by xradio, corrected lazily (nothing
    written), then into its store:

    >>> import logging, tempfile, pathlib, warnings
    >>> from xradio.measurement_set import convert_msv2_to_processing_set
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import correct_processing_set
    >>> logging.getLogger("toolviper").setLevel(logging.WARNING)
    >>> store = pathlib.Path(tempfile.mkdtemp()) / "vla.ps.zarr"
    >>> ms = str(sample_file("vla_sim.ms"))
    >>> with warnings.catch_warnings():  # zarr's, on the strings xradio stores
    ...     warnings.simplefilter("ignore")
    ...     convert_msv2_to_processing_set(ms, str(store))  # doctest: +IGNORE_OUTPUT
    >>> ps = correct_processing_set(store, write=False)
    >>> sorted(ps["vla_sim_0"].attrs["data_groups"])
    ['base', 'corrected', 'model']
    >>> ps["vla_sim_0"]["VISIBILITY_CORRECTED"].chunks is not None  # a dask array
    True
    >>> ps = correct_processing_set(store)  # written into the store
    >>> ps["vla_sim_0"].attrs["data_groups"]["corrected"]["correlated_data"]
    'VISIBILITY_CORRECTED'
    """
    correction = Correction.of(correction, **options)
    path = None
    if isinstance(ps, (str, os.PathLike)):
        path = Path(ps)
        tree = read_processing_set(path)
        where = repr(str(path))
    elif hasattr(ps, "children") and hasattr(ps, "attrs"):
        tree, where = ps, "the processing set"
    else:
        raise TypeError(f"ps must be an xarray DataTree or the path of a processing set, "
                        f"got {type(ps).__name__}")
    groups = data_groups(correction.direction, data_group, new_group)
    done, undefined, rows = {}, 0, 0
    for name, partition in _partitions(tree, where):
        done[name], bad, count = _partition(name, partition, correction, groups, where)
        undefined, rows = undefined + bad, rows + count
    if undefined:
        warn_caller(f"the feed rotation is undefined for {undefined} of {rows} "
                    "time-baselines (an alt-az antenna pointing at the zenith): their "
                    f"{groups[2]} is NaN", DegenerateGeometryWarning)
    out = tree.copy()
    for name, partition in done.items():
        out[name] = partition
    if path is None or write is False:
        return out
    _write(path, out, done, groups[2], groups[0])
    return read_processing_set(path)


def _encoding(source, data):
    """How the new variable is stored: as the variable it came from (its codecs; xradio's
    Blosc LZ4 writes several times faster than zarr's default), in its dask chunks."""
    kept = {key: source.encoding[key] for key in ("compressors", "filters", "serializer")
            if key in source.encoding}
    if data.chunks:
        kept["chunks"] = tuple(c[0] for c in data.chunks)
    return kept


def _write(path, tree, names, variable, source_group):
    """The new variable and the ``data_groups`` attributes of each partition, into the
    store; the consolidated metadata made anew."""
    import zarr  # with xradio

    for name in names:
        data = tree[name][variable]
        dataset = data.to_dataset(name=variable).drop_vars(list(data.coords))
        # xarray writes the dataset's attributes as the group's: all of them, with the
        # data group added.
        dataset.attrs = dict(tree[name].attrs)
        group = zarr.open_group(str(path), path=name, mode="r")
        source = tree[name].attrs["data_groups"][source_group]["correlated_data"]
        encoding = {} if variable in group else \
            {variable: _encoding(tree[name][source], data)}
        with _zarr_quiet():
            dataset.to_zarr(str(path), group=name, mode="a", consolidated=False,
                            encoding=encoding)
    with _zarr_quiet():  # the store came with consolidated metadata: made anew, as it was
        zarr.consolidate_metadata(str(path))


def processing_set_telescopes(path):
    """The telescope names of a processing set's partitions (their antenna tables).

    Examples
    --------
    See `correct_processing_set`.
    """
    return sorted({t for partition in read_processing_set(path).children.values()
                   for t in _telescopes(partition["antenna_xds"].to_dataset())})


def correct_processing_set_file(correction, source, output, *, overwrite=False,
                                progress=False, client=None, data_group=None, new_group=None,
                                **columns):
    """The adapter of MSv4 processing sets (`~astropy_feedrot.visibilities.correction`):
    in place only, the graph computed on the active dask scheduler (the client's).

    Examples
    --------
    See `correct_processing_set`.
    """
    refuse_column_options(**columns)
    if output is not None:
        check_output_format("msv4", output)  # says: in place
    correct_processing_set(source, data_group=data_group, new_group=new_group, write=True,
                           correction=correction)
    return Path(source)


register_adapter(["msv4"], correct_processing_set_file, processing_set_telescopes)
