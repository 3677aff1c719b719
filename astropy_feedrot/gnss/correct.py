# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Carrier-phase wind-up removed from the phases of a RINEX observation file.

`correct_rinex` streams a RINEX file (`~astropy_feedrot.gnss.rinex`) in
blocks of epochs, computes the wind-up of every satellite of the block at
every epoch of it in one call of the engine (`astropy_feedrot.engine.grid.wind_up`:
orbits from SP3 files, transmitter attitude nominal or from ORBEX
quaternions, the receiver a crossed dipole turned by the header's antenna
zero direction), keeps it continuous along each satellite's arc and
subtracts it, in cycles, from every carrier phase (``L``) of the satellite.

Conventions
-----------
* The wind-up is the feed rotation of a right-hand circularly polarized
  (RHCP) receiver, the phase rotation of Eq 30 (Beyerle's crossed-dipole
  form) in cycles. It is the same number of cycles at every frequency of a
  circularly polarized signal (it is an angle, not a length), so the same
  value is subtracted from L1, L2, L5, E5b...: ``L_corrected = L - windup``,
  as Appendix D prescribes for RHCP ("subtract the feed rotation from the
  measured phase") and as RTKLIB and the IGS models apply it (with their
  own constants: see :doc:`/gnss`).
* An arc is a run of epochs of one satellite without a gap longer than
  ``max_gap`` (`~astropy_feedrot.gnss.arcs.Arcs`): the wind-up is kept
  continuous (Eq 9) through loss-of-lock flags, power failures and events,
  as RTKLIB keeps its ``phw``; an arc starts at the principal value, in
  [-0.5, 0.5) cycles, the same for every phase of the satellite.
"""

import os
import shutil
import tempfile
import warnings
from pathlib import Path
from typing import NamedTuple

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.table import QTable
from astropy.time import Time

from ..core.choices import ATTITUDES
from ..core.exceptions import DegenerateGeometryWarning, OrbitWarning, warn_caller
from ..core.outputs import same_file, write_files
from ..core.progress import check_progress, progress_steps
from ..earth.frames import check_station_xyz, local_frame
from ..earth.orientation import EarthOrientation
from ..engine.equations import check_form
from ..engine.grid import wind_up
from ..io import SatelliteMetadata, read_orbex, read_satellite_metadata
from ..io.sp3 import join_sp3
from ..transmitters.attitude_interface import Attitude, interpolated_sun_position
from ..transmitters.nominal_attitude import NominalAttitude
from ..transmitters.orbits import Orbit, SP3Orbit
from ..transmitters.quaternion_attitude import QuaternionAttitude
from ..transmitters.sp3_orbit import MAX_EXTRAPOLATION, points_needed
from ..transmitters.yaw_models import LAWS, ModelAttitude, default_metadata
from .arcs import Arcs, orbit_file_name
from .rinex import RinexReader, record_times
from .rinex_header import SYSTEMS
from .streams import RinexWriter

__all__ = ["ATTITUDES", "RinexCorrection", "correct_rinex", "receiver_axes", "join_orbex"]

#: Data epochs per block: the working memory of a block is about 1 kB per
#: observation line (2880 epochs of 40 satellites: about 120 MB at most).
BLOCK_EPOCHS = 2880

_TWO_PI = 2 * np.pi


class RinexCorrection(NamedTuple):
    """What `correct_rinex` did.

    Attributes
    ----------
    output : pathlib.Path
        The file written.
    epochs : int
        Observation epochs (flags 0 and 1) in the file.
    observations : int
        Satellite observation records (one satellite at one epoch).
    phases : int
        Carrier-phase values changed.
    arcs : int
        Satellite arcs along which the wind-up was kept continuous.
    untouched : dict of str to str
        Satellites (some of) whose phases were left as they were, and why.
    windup : `~astropy.table.QTable` or None
        With ``table=True``: columns ``time`` (`~astropy.time.Time`), ``prn``
        and ``windup`` (`~astropy.units.Quantity` in cycles, as removed), one
        row per epoch and satellite in the order of the file.
    untouched_epochs : int
        Epochs outside the SP3 files (beyond what is extrapolated), whose
        phases were left as they were.
    extrapolated_epochs : int
        Epochs up to one SP3 interval (at most 900 s) outside the SP3 files,
        whose orbits were extrapolated.

    Examples
    --------
    >>> from astropy_feedrot.gnss import RinexCorrection
    >>> RinexCorrection("out.rnx", 2, 6, 12, 3, {}).phases
    12
    """

    output: Path
    epochs: int
    observations: int
    phases: int
    arcs: int
    untouched: dict
    windup: QTable = None
    untouched_epochs: int = 0
    extrapolated_epochs: int = 0


def receiver_axes(xyz, zero_direction=0.0):
    """East, north and up of a GNSS antenna turned by its zero direction, in ITRS.

    Parameters
    ----------
    xyz : array-like, shape (3,)
        The antenna's geocentric ITRS position in metres.
    zero_direction : float, optional
        Azimuth of the antenna's zero direction (its north mark), in degrees
        from north through east (RINEX ``ANTENNA: ZERODIR AZI``).

    Returns
    -------
    ndarray, shape (3, 3)
        Rows: the antenna's aligned dipole (its "east"), transverse dipole
        (its "north", along the zero direction) and up (the geodetic
        vertical), as ``station_axes`` of `~astropy_feedrot.engine.grid.wind_up`.

    Examples
    --------
    >>> import numpy as np
    >>> from astropy_feedrot.gnss import receiver_axes
    >>> axes = receiver_axes([6378137.0, 0, 0], 90.0)  # zero direction east
    >>> axes[1]  # doctest: +FLOAT_CMP
    array([0., 1., 0.])
    """
    xyz = check_station_xyz(np.asarray(xyz, dtype=float), "the antenna position")
    east, north, up = local_frame(EarthLocation.from_geocentric(*xyz, unit=u.m))
    azimuth = np.radians(float(zero_direction))
    c, s = np.cos(azimuth), np.sin(azimuth)
    return np.stack([c * east - s * north, c * north + s * east, up])


def join_orbex(sources, frame=None):
    """The attitude quaternions of several ORBEX files, joined per satellite.

    Parameters
    ----------
    sources : sequence of str, path-like or file object
        ORBEX files (one per day, for instance).
    frame : {'itrs', 'gcrs'}, optional
        For files that do not give their ``FRAME_TYPE``
        (see `~astropy_feedrot.QuaternionAttitude.from_orbex`).

    Returns
    -------
    dict of str to `~astropy_feedrot.QuaternionAttitude`
        One attitude per satellite with ``ATT`` records; an epoch given by
        two files is taken from the first.

    Raises
    ------
    ValueError
        If a file gives no frame and ``frame`` is not given, or the files
        refer to different frames.

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.gnss import join_orbex
    >>> sorted(join_orbex([sample_file("sample.obx")]))
    ['E11', 'G01', 'G05']
    """
    frames = {"ECEF": "itrs", "ECI": "gcrs"}
    found = {}
    chosen = frame
    for source in sources:
        data = read_orbex(source)
        this = frames.get(data.frame_type, frame)
        if this is None:
            raise ValueError(f"{source}: the ORBEX file does not give FRAME_TYPE; pass "
                             "frame='itrs' (Earth-fixed) or frame='gcrs' (celestial)")
        if chosen is not None and this != chosen:
            raise ValueError(f"the ORBEX files refer to different frames ({chosen!r} and "
                             f"{this!r}); give files of one series")
        chosen = this
        for sat, (times, quaternions) in data.attitude.items():
            found.setdefault(sat, []).append((times, np.asarray(quaternions)))
    attitudes = {}
    for sat, parts in found.items():
        times = parts[0][0]
        seconds = [np.asarray((t - times[0]).sec) for t, _ in parts]
        every = np.concatenate(seconds)
        q = np.concatenate([q for _, q in parts])
        order = np.argsort(every, kind="stable")
        keep = np.r_[True, np.diff(every[order]) > 1e-6]
        pick = order[keep]
        attitudes[sat] = QuaternionAttitude(times[0] + every[pick] * u.s, q[pick],
                                            frame=chosen)
    return attitudes


class _Satellites:
    """The orbit and attitude of each PRN, made on first use; why a PRN has none.

    Under ``attitude='model'``, a PRN whose block has no yaw law (or that the
    metadata does not know) gets nominal yaw, and is listed in ``nominal``.
    """

    def __init__(self, sp3, orbex, attitude, points, metadata=None, extrapolate=0.0):
        self.metadata = metadata
        self.sp3 = sp3
        self.orbex = orbex
        self.attitude = attitude
        self.points = points
        self.extrapolate = extrapolate
        self.models = {}
        self.why = {}
        self.nominal = {}

    def get(self, prn):
        if prn in self.models:
            return self.models[prn]
        model = None
        if prn not in self.sp3.positions:
            self.why[prn] = "not in the SP3 files"
        elif self.attitude == "orbex" and prn not in self.orbex:
            self.why[prn] = "no attitude in the ORBEX files"
        else:
            try:
                orbit = SP3Orbit(self.sp3, prn, points=self.points,
                                 extrapolate=self.extrapolate)
            except ValueError as error:
                self.why[prn] = f"no usable orbit ({error})"
            else:
                model = (orbit, self.attitude_of(prn, orbit))
        self.models[prn] = model
        return model

    def attitude_of(self, prn, orbit):
        if self.attitude == "nominal":
            return NominalAttitude()
        if self.attitude == "orbex":
            return self.orbex[prn]
        try:
            block = self.metadata.block(prn, self.sp3.epochs[0])
        except ValueError:
            self.nominal[prn] = "not in the satellite metadata on that date"
            return NominalAttitude()
        if block not in LAWS:
            self.nominal[prn] = f"block {block}"
            return NominalAttitude()
        return ModelAttitude.from_metadata(orbit, prn, self.sp3.epochs[0], self.metadata)


def _dipoles(attitudes, times, positions, orientation):
    """Dipoles (S, T, 3) of the satellites; NaN outside an attitude's coverage."""
    nominal = [i for i, a in enumerate(attitudes) if a.needs_sun]
    aligned = np.full(positions.shape, np.nan)
    transverse = np.full(positions.shape, np.nan)
    if nominal:
        a, t = Attitude.dipoles_many([attitudes[i] for i in nominal], times, positions[nominal],
                                     orientation)
        aligned[nominal], transverse[nominal] = a, t
    models = [i for i, a in enumerate(attitudes) if isinstance(a, ModelAttitude)]
    if models:
        sun = interpolated_sun_position(orientation)  # once for every modelled satellite
        for i in models:
            aligned[i], transverse[i] = attitudes[i].sun_and_dipoles(times, positions[i], sun)
    for i, attitude in enumerate(attitudes):
        if attitude.needs_sun or i in models:
            continue
        first, last = attitude.epochs[0], attitude.epochs[-1]
        inside = ((times - first).sec >= -1e-6) & ((last - times).sec >= -1e-6)
        if np.any(inside):
            a, t = attitude.dipoles(times[inside], positions[i, inside])
            aligned[i, inside], transverse[i, inside] = a, t
    return aligned, transverse


def _check_output(source, output, overwrite):
    if isinstance(output, (str, os.PathLike)):
        path = Path(output).expanduser()
    else:
        raise TypeError(f"output must be a path, got {type(output).__name__}")
    if isinstance(source, (str, os.PathLike)) and same_file(path.resolve(),
                                                            Path(source).expanduser().resolve()):
        raise ValueError(f"output {str(output)!r} is the input file, which is never "
                         "overwritten; choose another name")
    if path.is_dir():
        raise ValueError(f"output {str(output)!r} is a directory; give a file name")
    if path.exists() and not overwrite:
        raise FileExistsError(f"output {str(output)!r} exists; pass overwrite=True to "
                              "replace it, or choose another name")
    if not path.resolve().parent.is_dir():
        raise FileNotFoundError(f"cannot write {str(output)!r}: directory "
                                f"{str(path.resolve().parent)!r} does not exist")
    return path.resolve()


def _as_list(value, what):
    if value is None:
        return []
    if isinstance(value, (str, os.PathLike)) or hasattr(value, "readline"):
        return [value]
    value = list(value)
    return value


def correct_rinex(source, output, sp3, *, orbex=None, attitude=None, max_gap=300 * u.s,
                  points=None, position=None, form="beyerle", metadata=None, table=False,
                  overwrite=False, progress=False):
    """Write a copy of a RINEX observation file with the carrier-phase wind-up removed.

    Parameters
    ----------
    source : str, path-like or file object
        The RINEX observation file (2.11, 3.0x or 4.0x; plain, gzip or
        Hatanaka-compressed).
    output : str or path-like
        The file to write (gzip-compressed if its name ends in ``.gz``);
        never the input. Written to a temporary file beside it and renamed
        into place at the end: an error leaves no file behind.
    sp3 : str, path-like, file object or a sequence of them
        SP3 orbit files covering the observations (several days are joined).
    orbex : str, path-like, file object or a sequence of them, optional
        ORBEX attitude files; with them the attitude defaults to ``'orbex'``.
    attitude : {'nominal', 'model', 'orbex'}, optional
        The transmitter attitude: nominal yaw steering (Eqs 26-27, default
        without ``orbex``), the yaw-attitude model of each satellite's block
        through noon and midnight turns and shadows
        (`~astropy_feedrot.ModelAttitude`; satellites of blocks without a
        model get nominal yaw, named in one warning), or the ORBEX quaternions.
    max_gap : `~astropy.units.Quantity`, optional
        A satellite's gap longer than this (plus half the sampling interval,
        for the rounding of epoch times) starts a new arc (default 300 s).
    points : int, optional
        Points of the Lagrange interpolation of the orbits (default 10).
        Fewer than the orbits' sampling needs for 1e-4 cycle
        (`~astropy_feedrot.transmitters.sp3_orbit.points_needed`: 7 at 15 minutes for
        GPS) are refused.
    position : array-like, shape (3,), optional
        The antenna's ITRS position in metres, if the header has no ``APPROX
        POSITION XYZ`` (or to override the header's; an event giving a new
        position moves the antenna from there on).
    form : {'beyerle', 'wu'}, optional
        The crossed-dipole form of Eq 30 (Beyerle 2009, default) or the
        effective-dipole form of Eq 31 (Wu et al. 1993, as RTKLIB and the IGS
        analysis centres use it); they differ by up to ~0.01 deg for a
        receiver whose boresight (up) is not along the line of sight.
    metadata : str, path-like or `~astropy_feedrot.io.SatelliteMetadata`, optional
        The IGS satellite metadata SINEX file giving each PRN's block for
        ``attitude='model'`` (default: the shipped copy, release 2404).
    table : bool, optional
        Also return the wind-up removed, one row per epoch and satellite
        (``RinexCorrection.windup``; its memory grows with the file).
    overwrite : bool, optional
        Whether an existing ``output`` may be replaced.
    progress : bool or callable, optional
        True shows astropy's `~astropy.utils.console.ProgressBar` (on
        standard error, when it is a terminal) over the bytes of ``source``
        read, moved after each block of epochs is corrected and written; a
        callable is called as ``progress(done, total)`` then (bytes).
        Nothing for a ``source`` given as a file object.

    Returns
    -------
    `RinexCorrection`

    Raises
    ------
    astropy_feedrot.io.FileFormatError
        For a RINEX file that breaks its format (a file cut short, a wrong
        version line, a satellite of a system whose observation types the
        header does not declare, ...), or an SP3/ORBEX file that breaks
        its own.
    ValueError
        If ``output`` is the input, ``points`` is too few for the orbits'
        sampling (or more than their epochs), the header has no position
        and ``position`` is not given, the file gives ``ANTENNA: ZERODIR
        XYZ``, or for an unknown ``attitude``.
    TypeError
        If ``points`` is not an integer, or ``progress`` neither a bool nor
        a callable.
    FileExistsError
        If ``output`` exists and ``overwrite`` is False.

    Warns
    -----
    `~astropy_feedrot.OrbitWarning`
        Once, listing the satellites whose phases were left untouched (all
        or some of them) and why: not in the SP3 files, no ORBEX attitude,
        epochs in holes of an orbit or outside the attitude's coverage,
        degenerate geometry. Once for epochs whose orbits were extrapolated
        (up to one SP3 interval, at most 900 s, outside the SP3 files, as
        RTKLIB does), once for epochs further out, left untouched, each
        naming the missing day's file; once naming the satellites given
        nominal yaw under ``attitude='model'``.

    Notes
    -----
    Every line of the file is written as read except the ``L`` values that
    are corrected (their loss-of-lock and signal-strength flags are kept;
    blank and ``0.000`` values are missing, kept) and two ``COMMENT`` lines
    added before ``END OF HEADER``. The wind-up is that of an RHCP receiver
    in cycles, subtracted from every carrier phase of a satellite (the same
    number of cycles at every frequency); an arc starts at its principal
    value in [-0.5, 0.5) cycles and stays continuous (Eq 9) through
    loss-of-lock flags and events, as RTKLIB keeps its ``phw``, until a gap
    longer than ``max_gap``. Events of flags 3 and 4 that give new
    observation types, ``APPROX POSITION XYZ`` or ``ANTENNA: ZERODIR AZI``
    apply from the next epoch on. The epochs are read and corrected in blocks
    of `BLOCK_EPOCHS`, each with one call of the wind-up engine for all its
    epochs and satellites, so memory stays bounded for any file length.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.gnss import correct_rinex
    >>> out = os.path.join(tempfile.mkdtemp(), "corrected.rnx")
    >>> report = correct_rinex(sample_file("gnss_sample.rnx"), out,
    ...                        sample_file("gnss_sample.sp3"))
    >>> report.epochs, report.phases, report.arcs, report.untouched
    (40, 1920, 16, {})
    """
    if attitude is None:
        attitude = "orbex" if orbex is not None else "nominal"
    check_progress(progress)
    form = check_form(form)
    if attitude not in ATTITUDES:
        raise ValueError(f"attitude must be one of {ATTITUDES}, got {attitude!r}")
    orbex_files = _as_list(orbex, "orbex")
    if attitude == "orbex" and not orbex_files:
        raise ValueError("attitude='orbex' needs the ORBEX files: pass orbex=")
    sp3_files = _as_list(sp3, "sp3")
    max_gap = u.Quantity(max_gap, u.s).to_value(u.s)
    path = _check_output(source, output, overwrite)
    orbits = join_sp3(sp3_files)
    points = _check_points(points, orbits)
    margin = min(orbits.interval, MAX_EXTRAPOLATION)
    attitudes = join_orbex(orbex_files) if attitude == "orbex" else {}
    if attitude == "model":
        if metadata is None:
            metadata = default_metadata()
        elif not isinstance(metadata, SatelliteMetadata):
            metadata = read_satellite_metadata(metadata)
    satellites = _Satellites(orbits, attitudes, attitude, points, metadata, margin)
    report = {}

    def write(name):
        with RinexReader(source) as reader, tempfile.TemporaryFile(
                "w+", encoding="latin-1", newline="", dir=path.parent) as body:
            header = reader.header
            xyz = header.position if position is None else np.asarray(position, dtype=float)
            if xyz is None:
                raise ValueError(f"{reader.name}: the header gives no APPROX POSITION XYZ; "
                                 "pass the antenna's position (position=[x, y, z] in metres)")
            state = _Block(header, xyz, orbits, satellites, Arcs(max_gap, header.interval),
                           form, margin, reader.name)
            state.rows = [] if table else None
            out = RinexWriter(body)
            size = reader.size
            with progress_steps(progress if size is not None else False, size or 0) as step:
                read = 0  # bytes of the file behind the blocks written

                def moved(now):
                    nonlocal read
                    if now is not None and now > read:
                        step(now - read)
                        read = now

                block, epochs = [], 0
                for record in reader:
                    block.append(record)
                    epochs += record.observations
                    if epochs >= BLOCK_EPOCHS or reader.header is not state.header:
                        state.correct(block)
                        for done in block:
                            out.write_record(done)
                        block, epochs = [], 0
                        state.use(reader.header)
                        moved(reader.bytes_read())
                state.correct(block)
                for done in block:
                    out.write_record(done)
                moved(size)
            body.seek(0)
            with RinexWriter(name) as writer:
                writer.write_header(header, _comments(attitude, state.totals))
                shutil.copyfileobj(body, writer.file, 1 << 20)
        report.update(state.totals)
        report["rows"] = state.rows

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OrbitWarning)
        warnings.simplefilter("ignore", DegenerateGeometryWarning)
        write_files([(path, write)], overwrite=overwrite)
    _warn(report, satellites, orbits, sp3_files, margin)
    untouched = dict(satellites.why)
    for prn, count in report["gaps"].items():
        untouched.setdefault(prn, f"{count} epochs in holes of the orbit, outside the attitude "
                             "or with degenerate geometry")
    if untouched:
        listed = "; ".join(f"{prn}: {why}" for prn, why in sorted(untouched.items()))
        warn_caller(f"phases left untouched: {listed}", OrbitWarning)
    windup = None
    if table:
        rows = report["rows"]
        if rows:
            times = Time(np.concatenate([r[0] for r in rows]),
                         np.concatenate([r[1] for r in rows]), format="jd", scale="tai")
            times.format = "isot"
            prns = np.concatenate([r[2] for r in rows]).astype(str)
            cycles = np.concatenate([r[3] for r in rows])
        else:
            times, prns, cycles = Time([], format="jd", scale="tai"), np.array([], str), []
        windup = QTable({"time": times, "prn": prns, "windup": np.asarray(cycles) * u.cycle})
        windup.meta.update({"file": str(getattr(source, "name", source)), "attitude": attitude,
                            "form": form, "polarization": "RCP"})
    return RinexCorrection(path, report["epochs"], report["observations"], report["phases"],
                           report["arcs"], untouched, windup, report["outside"][0],
                           report["extrapolated"][0])


def _check_points(points, orbits):
    """The interpolation points, refused before any work if too few for the orbits' sampling."""
    epochs = len(orbits.epochs)
    # The GNSS satellites' smallest radius (a LEO in the file is never a RINEX PRN).
    radii = [np.nanmin(np.linalg.norm(xyz, axis=-1)) for sat, xyz in orbits.positions.items()
             if sat[:1] in SYSTEMS and np.any(np.isfinite(xyz))]
    needed = points_needed(orbits.interval, min(radii) if radii else 20e6)
    if points is None:
        points = min(10, epochs)
        if points < needed:
            raise ValueError(f"the SP3 files have {epochs} epochs at {orbits.interval:g} s; "
                             f"interpolating their orbits within 1e-4 cycle of wind-up needs "
                             f"{needed} points: give SP3 files of a longer span")
        return max(points, needed)
    if isinstance(points, bool) or not isinstance(points, (int, np.integer)):
        raise TypeError(f"points must be a whole number of epochs (int), got {points!r}")
    if points < needed:
        raise ValueError(f"points={points} is too few for SP3 orbits at {orbits.interval:g} s: "
                         f"interpolating them within 1e-4 cycle of wind-up needs at least "
                         f"{needed} points (default 10)")
    if points > epochs:
        raise ValueError(f"points={points} exceeds the {epochs} epochs of the SP3 files; give "
                         f"{needed} to {epochs} points or SP3 files of a longer span")
    return int(points)


def _comments(attitude, totals):
    """The COMMENT lines of the corrected file: what was done, and only that."""
    kind = {"nominal": "NOMINAL YAW", "model": "YAW MODELS", "orbex": "ORBEX ATTITUDE"}[attitude]
    corrected = len(totals["satellites"])
    if not totals["phases"]:
        return ["astropy_feedrot: NO PHASE CORRECTED (NO ORBIT OR ATTITUDE)"]
    sats = f"{corrected} SATELLITE{'' if corrected == 1 else 'S'}"
    return [f"astropy_feedrot: L - WIND-UP (CYCLES, RHCP, {kind})",
            f"WIND-UP REMOVED FROM {totals['phases']} PHASES OF {sats}"]


def _gps_day(time):
    """``time`` shifted to the GPS-time calendar (as TAI - 19 s), for file names."""
    return Time(time.tai.jd1, time.tai.jd2 - 19.0 / 86400, format="jd", scale="tai")


def _warn(report, satellites, orbits, sp3_files, margin):
    """The warnings of a correction: once each, after the file is written."""
    if satellites.nominal:
        listed = ", ".join(f"{prn} ({why})" for prn, why in sorted(satellites.nominal.items()))
        warn_caller(f"no yaw model for {listed}: nominal yaw used for them", OrbitWarning)
    names = [str(getattr(f, "name", f)) for f in sp3_files]
    first, last = orbits.epochs[0], orbits.epochs[-1]
    scale = first.scale.upper()
    for key, what in (("extrapolated", "extrapolated"), ("outside", "untouched")):
        count, (early, late), after = report[key]
        if not count:
            continue
        day = last + orbits.interval * u.s if after else first - orbits.interval * u.s
        missing = orbit_file_name(names, _gps_day(day))
        span = f"{count} epochs ({early.isot} to {late.isot} {scale})"
        if what == "extrapolated":
            warn_caller(f"{span} lie up to {margin:g} s (one SP3 interval) outside the SP3 "
                        f"files ({first.isot} to {last.isot}): their orbits are extrapolated, "
                        f"as RTKLIB does; give {missing} to interpolate them", OrbitWarning)
        else:
            warn_caller(f"{span} lie more than {margin:g} s outside the SP3 files "
                        f"({first.isot} to {last.isot}): their phases are left untouched; "
                        f"give {missing}", OrbitWarning)


class _Block:
    """Correct blocks of epoch records, carrying the arcs from block to block."""

    def __init__(self, header, xyz, orbits, satellites, arcs, form, margin, name):
        self.form = form
        self.name = name
        self.orbits = orbits
        self.satellites = satellites
        self.arcs = arcs
        self.margin = margin
        self.xyz = np.asarray(xyz, dtype=float)
        self.header = None
        self.use(header)
        self.totals = {"epochs": 0, "observations": 0, "phases": 0, "arcs": 0, "gaps": {},
                       "satellites": set(), "outside": [0, (None, None), True],
                       "extrapolated": [0, (None, None), True]}
        self.rows = None
        self.first = orbits.epochs[0]
        self.span = (orbits.epochs[-1] - self.first).sec

    def use(self, header):
        """Take the header in effect from now on (events of flags 3 and 4 change it)."""
        if header is self.header:
            return
        if (self.header is not None and header.position is not None
                and header.position is not self.header.position):  # an event's new position
            self.xyz = header.position
        self.header = header
        self.axes = receiver_axes(self.xyz, header.zero_direction)
        self.fields = {code: header.phase_fields(code) for code in header.obs_types}

    def count(self, key, times, mask, after):
        """Count the epochs of ``mask`` under ``key``, keeping the first and last."""
        if not np.any(mask):
            return
        total = self.totals[key]
        chosen = times[mask]
        early, late = total[1]
        total[0] += int(np.count_nonzero(mask))
        total[1] = (chosen[0] if early is None else early, chosen[-1])
        total[2] = after

    def correct(self, block):
        data = [record for record in block if record.observations]
        if not data:
            return
        self.totals["epochs"] += len(data)
        self.totals["observations"] += sum(len(record.satellites) for record in data)
        times = record_times(data, self.header.time_system)
        seconds = np.asarray((times - self.first).sec, dtype=float)
        tol = 1e-6
        before, after = seconds < -tol, seconds > self.span + tol
        inside = (seconds >= -self.margin - tol) & (seconds <= self.span + self.margin + tol)
        self.count("outside", times, ~inside, bool(np.any(after & ~inside)))
        self.count("extrapolated", times, inside & (before | after), bool(np.any(after)))
        if not np.all(inside):
            data = [record for record, ok in zip(data, inside) if ok]
            times, seconds = times[inside], seconds[inside]
            if not data:
                return
        # Rows: one per satellite observation with an orbit and an attitude.
        prns = sorted({sat for record in data for sat in record.satellites})
        models = {prn: self.satellites.get(prn) for prn in prns}
        usable = [prn for prn in prns if models[prn] is not None]
        column = {prn: j for j, prn in enumerate(usable)}
        rows_t, rows_s, where = [], [], []
        for t, record in enumerate(data):
            for i, sat in enumerate(record.satellites):
                j = column.get(sat)
                if j is None:
                    continue
                fields = self.fields[sat[0]]
                values, _ = record.phases(i, fields, self.name)
                rows_t.append(t)
                rows_s.append(j)
                where.append((record, i, fields, values))
        if not usable or not rows_t:
            return
        orbits = [models[prn][0] for prn in usable]
        attitudes = [models[prn][1] for prn in usable]
        orientation = EarthOrientation(times)  # its Sun: 1e-13 rad from the exact one
        positions = Orbit.positions(orbits, times, orientation)
        aligned, transverse = _dipoles(attitudes, times, positions, orientation)
        phase = wind_up(self.xyz[np.newaxis], self.axes[np.newaxis], [True],
                        np.swapaxes(positions, 0, 1), np.swapaxes(aligned, 0, 1),
                        np.swapaxes(transverse, 0, 1), form=self.form)[:, 0, :]
        rows_t = np.asarray(rows_t)
        rows_s = np.asarray(rows_s)
        wrapped = phase[rows_t, rows_s] / _TWO_PI
        good = np.isfinite(wrapped)
        if not np.all(good):
            for j, count in zip(*np.unique(rows_s[~good], return_counts=True)):
                gaps = self.totals["gaps"]
                gaps[usable[j]] = gaps.get(usable[j], 0) + int(count)
        names = np.array(usable, dtype=object)[rows_s[good]]
        total = self.arcs.apply(names, seconds[rows_t[good]], wrapped[good])
        self.totals["arcs"] = self.arcs.arcs
        if self.rows is not None:
            tai = times.tai
            index = rows_t[good]  # rows are in the file's order
            self.rows.append((tai.jd1[index], tai.jd2[index], names, total))
        changed = 0
        kept = (w for w, g in zip(where, good) if g)
        done = self.totals["satellites"]
        for (record, i, fields, values), cycles in zip(kept, total):
            n = record.subtract(i, fields, values, cycles)
            if n:
                done.add(record.satellites[i])
            changed += n
        self.totals["phases"] += changed
