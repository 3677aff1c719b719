# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""IONEX global ionosphere maps, read by spinifex from local files only.

spinifex (the optional extra ``ionosphere``) reads and interpolates the maps:
this module chooses which of the user's files serves each epoch, checks that
every epoch is covered, and never lets spinifex look for a file elsewhere
(its own entry points download missing days from the analysis centres; the
functions used here, ``read_ionex`` and ``interpolate_ionex``, only read the
paths given).

A file is read by its name, as spinifex does: ``.gz`` gzip, ``.Z`` Unix
compress (LZW, through ``unlzw-cython``), anything else plain text. One file
per UTC day; a file whose maps run to the next midnight takes the first map
of the next day's file there when that file is given too (spinifex's removal
of midnight jumps), and its own last map otherwise.
"""

import contextlib
import importlib
import logging
import os
import pathlib
import types
import warnings

import numpy as np
from astropy.time import Time

from ..core.extras import install_hint
from .errors import IonosphereError

__all__ = ["IonexMaps", "sample_ionex", "spinifex_modules", "quiet_spinifex",
           "describe_epochs"]

__doctest_requires__ = {("sample_ionex", "IonexMaps", "IonexMaps.*"): ["spinifex"]}

# The first bytes of compressed files, to refuse a name that hides its compression.
_MAGIC = {b"\x1f\x8b": ".gz", b"\x1f\x9d": ".Z"}

_SPINIFEX = None


def spinifex_modules():
    """The parts of spinifex used here, imported on first use.

    spinifex's import calls ``logging.captureWarnings(True)``, which would turn
    every warning of the process into a log record: the previous
    ``warnings.showwarning`` is put back.

    Returns
    -------
    `types.SimpleNamespace`
        ``read_ionex``, ``interpolate_ionex``, ``IPP`` (the pierce points its
        field model reads), ``magnetic_models`` (IGRF through ppigrf, whose
        coefficients ship in its wheel) and ``version``.

    Raises
    ------
    ImportError
        If spinifex is not installed, with the command that installs it.

    Examples
    --------
    >>> from astropy_feedrot.ionosphere.ionex import spinifex_modules
    >>> spinifex_modules().version >= "2.0"  # doctest: +SKIP
    True
    """
    global _SPINIFEX
    if _SPINIFEX is None:
        shown = warnings.showwarning
        try:
            spinifex = importlib.import_module("spinifex")
            geometry = importlib.import_module("spinifex.geometry")
            parser = importlib.import_module("spinifex.ionospheric.ionex_parser")
            manipulation = importlib.import_module("spinifex.ionospheric.ionex_manipulation")
            magnetic = importlib.import_module("spinifex.magnetic")
        except ImportError as error:
            raise ImportError(
                f"rotation measures from IONEX maps need spinifex ({error}): "
                f"{install_hint('ionosphere', 'spinifex')}") from None
        finally:
            warnings.showwarning = shown
        _SPINIFEX = types.SimpleNamespace(
            read_ionex=parser.read_ionex,
            interpolate_ionex=manipulation.interpolate_ionex,
            IPP=geometry.IPP,
            magnetic_models=magnetic.magnetic_models,
            version=spinifex.__version__,
            package_dir=pathlib.Path(spinifex.__file__).parent,
        )
    return _SPINIFEX


@contextlib.contextmanager
def quiet_spinifex():
    """Keep spinifex's INFO messages (one per step of every call) off the terminal.

    Its logger is set to WARNING inside the context and restored on exit.

    Examples
    --------
    >>> import logging
    >>> from astropy_feedrot.ionosphere.ionex import quiet_spinifex
    >>> with quiet_spinifex():
    ...     logging.getLogger("spinifex").level == logging.WARNING
    True
    """
    logger = logging.getLogger("spinifex")
    level = logger.level
    logger.setLevel(max(level, logging.WARNING))
    try:
        yield
    finally:
        logger.setLevel(level)


def sample_ionex(pattern="*"):
    """The real IONEX files that spinifex ships with its tests.

    Parameters
    ----------
    pattern : str, optional
        A glob pattern on the file names, e.g. ``'codg00[89]0.20i.Z'``: CODE
        maps of 2020 January 8 and 9 (hourly, 5 x 2.5 deg); ``'esag*'``: ESA's
        of 2020 January 8 to 10 (2 h); ``'uqrg*'``: UPC's of 2019 April 25 and
        26 (15 min); ``'IGS0OPSFIN*'``: IGS's of 2024 December 14 (gzip, 2 h);
        ``'casg0010.99i.Z'``: 1999 January 1, maps from 01:00 to 23:00 only.

    Returns
    -------
    list of `pathlib.Path`
        The matching files, sorted by name.

    Raises
    ------
    ImportError
        If spinifex is not installed.
    IonosphereError
        If no shipped IONEX file matches ``pattern`` (the message lists them).

    Examples
    --------
    >>> from astropy_feedrot.ionosphere import sample_ionex
    >>> [path.name for path in sample_ionex("codg*")]
    ['codg0080.20i.Z', 'codg0090.20i.Z']
    """
    folder = spinifex_modules().package_dir / "data" / "tests"
    shipped = sorted(path for path in folder.iterdir() if _is_ionex_name(path.name))
    found = [path for path in shipped if path.match(pattern)]
    if not found:
        raise IonosphereError(
            f"no IONEX file that spinifex ships matches {pattern!r}; they are "
            f"{', '.join(path.name for path in shipped)}")
    return found


def _is_ionex_name(name):
    """Whether a file name is an IONEX file's (old 'codg0080.20i' or new '...GIM.INX')."""
    stem = name.lower().removesuffix(".gz").removesuffix(".z")
    return stem.endswith(".inx") or (len(stem) > 4 and stem[-4] == "." and stem[-1] == "i")


def describe_epochs(mjd):
    """The first and last of epochs given as UTC MJD, in ISO format, for messages."""
    mjd = np.sort(np.ravel(mjd))
    first = Time(mjd[0], format="mjd", scale="utc").isot[:19]
    if mjd.size == 1 or mjd[-1] == mjd[0]:
        return first
    return f"{first} ... {Time(mjd[-1], format='mjd', scale='utc').isot[:19]}"


def _span(start, stop):
    return (f"{Time(start, format='mjd', scale='utc').isot[:16]} to "
            f"{Time(stop, format='mjd', scale='utc').isot[:16]}")


class IonexMaps:
    """IONEX files, one per UTC day, read by spinifex and checked for coverage.

    Parameters
    ----------
    paths : path-like or sequence of path-like
        IONEX files (plain, ``.gz`` or ``.Z``), in any order, one per day.

    Raises
    ------
    FileNotFoundError
        If a file does not exist.
    IonosphereError
        If a file cannot be read as IONEX, is compressed but not named so,
        or two files start on the same day; if no file is given.
    ImportError
        If spinifex is not installed.

    Examples
    --------
    >>> from astropy_feedrot.ionosphere import sample_ionex
    >>> from astropy_feedrot.ionosphere.ionex import IonexMaps
    >>> IonexMaps(sample_ionex("codg*")).describe_coverage()
    '2020-01-08T00:00 to 2020-01-10T00:00'
    """

    def __init__(self, paths):
        if isinstance(paths, (str, os.PathLike)):
            paths = [paths]
        paths = [pathlib.Path(os.fspath(path)).expanduser().resolve() for path in paths]
        if not paths:
            raise IonosphereError("no IONEX file given; give one file per day observed, "
                                  "e.g. Ionosphere.from_ionex(['codg0080.20i.Z'])")
        sp = spinifex_modules()
        first = [self._read(sp, path) for path in paths]
        days = np.array([np.floor(maps.times.utc.mjd[0]) for maps in first])
        order = np.argsort(days, kind="stable")
        for a, b in zip(order[:-1], order[1:]):
            if days[a] == days[b]:
                raise IonosphereError(
                    f"two IONEX files start on {_span(days[a], days[a])[:10]}: "
                    f"{paths[a].name} and {paths[b].name}; give one file per day "
                    "(of one analysis centre)")
        self.paths = tuple(paths[i] for i in order)
        self.days = days[order]
        # The maps at the next midnight from the next day's file, where given (spinifex).
        self.maps = tuple(self._read(sp, path, self._next(day)) for path, day
                          in zip(self.paths, self.days))
        self.starts = np.array([maps.times.utc.mjd[0] for maps in self.maps])
        self.stops = np.array([maps.times.utc.mjd[-1] for maps in self.maps])

    def _next(self, day):
        """The file of the next day, or None."""
        match = np.flatnonzero(self.days == day + 1)
        return self.paths[match[0]] if match.size else None

    @staticmethod
    def _read(sp, path, next_path=None):
        if not path.is_file():
            raise FileNotFoundError(f"IONEX file {path} does not exist")
        with path.open("rb") as stream:
            magic = stream.read(2)
        expected = _MAGIC.get(magic)
        if expected is not None and path.suffix != expected:
            raise IonosphereError(
                f"{path.name} is compressed ({'gzip' if expected == '.gz' else 'Unix compress'}) "
                f"but its name does not end in {expected}; spinifex reads a file by its name: "
                f"rename it to {path.name}{expected}")
        try:
            with quiet_spinifex():
                return sp.read_ionex(path, next_path)
        except Exception as error:  # spinifex's reason, on one line
            reason = str(error).splitlines()[0] if str(error) else ""
            raise IonosphereError(
                f"{path.name} could not be read as an IONEX file ({type(error).__name__}: "
                f"{reason}); give IONEX global ionosphere maps (e.g. CODE's codgDDD0.YYi.Z)"
            ) from None

    def coverage(self):
        """The spans the files cover, as (start, stop) UTC MJD pairs, merged where they touch.

        Returns
        -------
        list of tuple of float
        """
        spans = []
        for start, stop in zip(self.starts, self.stops):
            if spans and start <= spans[-1][1] + 1e-9:
                spans[-1] = (spans[-1][0], max(spans[-1][1], stop))
            else:
                spans.append((start, stop))
        return spans

    def describe_coverage(self):
        """The covered spans in words, for messages."""
        return "; ".join(_span(start, stop) for start, stop in self.coverage())

    def file_index(self, mjd):
        """Which file serves each epoch: the latest one starting at or before it.

        At a midnight where one file ends and the next begins, the next one
        serves (as spinifex chooses a file by the epoch's UTC day).

        Parameters
        ----------
        mjd : `~numpy.ndarray`
            Epochs as UTC MJD, 1-D.

        Returns
        -------
        `~numpy.ndarray` of int

        Raises
        ------
        IonosphereError
            If some epochs lie outside every file's maps.
        """
        index = np.searchsorted(self.starts, mjd, side="right") - 1
        last = self.stops[np.maximum(index, 0)]
        inside = (index >= 0) & (mjd <= last + 1e-9)
        if not np.all(inside):
            outside = mjd[~inside]
            names = ", ".join(path.name for path in self.paths[:4])
            more = f" and {len(self.paths) - 4} more" if len(self.paths) > 4 else ""
            raise IonosphereError(
                f"{outside.size} of {mjd.size} epochs ({describe_epochs(outside)} UTC) lie "
                f"outside the IONEX maps, which cover {self.describe_coverage()} ({names}{more}); "
                "give the IONEX files of the days observed too (one per day)")
        return index

    def vertical_tec(self, lon, lat, times, index):
        """Vertical TEC (TECU) interpolated by spinifex at pierce points.

        Parameters
        ----------
        lon, lat : `~numpy.ndarray`
            Pierce points in degrees, 1-D.
        times : `~astropy.time.Time`
            Their epochs (UTC), 1-D.
        index : `~numpy.ndarray` of int
            The file serving each epoch (`file_index`).

        Returns
        -------
        `~numpy.ndarray`
            TEC in TECU; spinifex interpolates bilinearly in space and
            linearly in time between maps rotated with the Earth (its
            ``apply_earth_rotation=1``, method 3 of the IONEX description).
        """
        sp = spinifex_modules()
        tec = np.empty(lon.shape)
        for file in np.unique(index):  # one call per file (day), as spinifex groups them
            rows = index == file
            tec[rows] = sp.interpolate_ionex(self.maps[file], lon[rows], lat[rows],
                                             times[rows], apply_earth_rotation=1)
        return tec
