# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The files pyuvdata reads and writes, read and written without downloading anything.

`read_uvdata` reads any file pyuvdata knows (UVFITS, uvh5, Measurement Sets,
Miriad, Mir) with internet access off; `write_uvdata` writes a
`~pyuvdata.UVData` object in the format its file name (or ``kind``) names,
beside the target and published in one step, with what UVFITS needs of AIPS
and HOPS data. The feed rotation of the data is
`~astropy_feedrot.visibilities.uvdata`. pyuvdata is an optional dependency
(the ``uvdata`` extra), imported when a function here is called.
"""

import contextlib
import os
import shutil
import tempfile
import warnings

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation

from ..core.extras import install_hint
from ..core.outputs import publish
from ..earth.eop import iers_context

__all__ = ["read_uvdata", "write_uvdata", "WRITERS", "PYUVDATA_TYPES", "UVDATA_EXTRA",
           "pyuvdata_module", "check_uvdata", "offline_sites"]

__doctest_requires__ = {("*",): ["pyuvdata"]}

#: Writers by file name extension (lower case), used by `write_uvdata`.
WRITERS = {
    ".uvfits": "write_uvfits",
    ".uvf": "write_uvfits",
    ".uvh5": "write_uvh5",
    ".h5": "write_uvh5",
    ".hdf5": "write_uvh5",
    ".ms": "write_ms",
    ".uv": "write_miriad",
    ".miriad": "write_miriad",
}

# Writers by kind of file (`write_uvdata`'s ``kind``).
_KIND_WRITERS = {"uvfits": "write_uvfits", "uvh5": "write_uvh5", "ms": "write_ms",
                 "miriad": "write_miriad"}

#: pyuvdata's ``file_type`` of each kind of `~astropy_feedrot.visibilities.FILE_KINDS`
#: it reads: files are read as their content says, whatever their names.
PYUVDATA_TYPES = {"uvfits": "uvfits", "uvh5": "uvh5", "ms": "ms", "miriad": "miriad",
                  "mir": "mir"}

# The epoch of catalogue frames whose entries pyuvdata leaves without one (AIPS
# and HOPS UVFITS: EQUINOX 2000 read as ICRS), which its write_uvfits needs.
_FRAME_EPOCHS = {"icrs": 2000.0, "fk5": 2000.0, "fk4": 1950.0}

#: How to install pyuvdata with the package.
UVDATA_EXTRA = install_hint("uvdata", "pyuvdata")


def pyuvdata_module():
    """The pyuvdata module, or an ImportError naming the extra.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.uvdata_files import pyuvdata_module
    >>> pyuvdata_module().__name__
    'pyuvdata'
    """
    try:
        import pyuvdata
    except ImportError:
        raise ImportError(f"astropy_feedrot.visibilities needs pyuvdata for this: "
                          f"{UVDATA_EXTRA}") from None
    return pyuvdata


def check_uvdata(uv):
    """A TypeError unless ``uv`` is a `~pyuvdata.UVData` object (pyuvdata imported).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.uvdata_files import check_uvdata
    >>> check_uvdata("data.uvfits")
    Traceback (most recent call last):
    ...
    TypeError: uv must be a pyuvdata UVData object (e.g. from read_uvdata), got str
    """
    pyuvdata = pyuvdata_module()
    if not isinstance(uv, pyuvdata.UVData):
        raise TypeError(f"uv must be a pyuvdata UVData object (e.g. from read_uvdata), got "
                        f"{type(uv).__name__}")


# --- files --------------------------------------------------------------------------


@contextlib.contextmanager
def offline_sites():
    """While in it: no download, IERS from astropy's bundled tables, no site registry
    from the web.

    pyuvdata asks astropy for its site names (which downloads ``sites.json``)
    when a file has no telescope location. Offline, astropy cannot fall back
    on a bundled list, so a registry with no real site stands in for it while
    the file is read; pyuvdata then takes the location from its own table of
    known telescopes, or from the antenna positions.
    """
    from astropy.coordinates.sites import SiteRegistry
    from astropy.utils.data import conf as data_conf

    with data_conf.set_temp("allow_internet", False), iers_context():
        try:
            with warnings.catch_warnings():
                # astropy 6.0 falls back on its built-in list, with this warning.
                warnings.filterwarnings("ignore", "Could not access the main site list")
                EarthLocation.get_site_names()
        except OSError:  # URLError: not cached and no internet
            previous = EarthLocation._site_registry
            registry = SiteRegistry()
            # An empty registry is falsy, and astropy would try to download again.
            registry.add_site(["astropy_feedrot offline"], EarthLocation.from_geocentric(
                6378137.0, 0.0, 0.0, unit=u.m))
            EarthLocation._site_registry = registry
            try:
                yield
            finally:
                EarthLocation._site_registry = previous
        else:
            yield


def read_uvdata(path, **kwargs):
    """Read a visibility file with pyuvdata, without downloading anything.

    Parameters
    ----------
    path : str or path-like
        Any file or directory `pyuvdata.UVData.from_file` reads (UVFITS,
        uvh5, Measurement Set, Miriad, Mir...).
    **kwargs
        Passed to `pyuvdata.UVData.from_file` (e.g. ``file_type``).

    Returns
    -------
    `~pyuvdata.UVData`

    Raises
    ------
    ImportError
        If pyuvdata is not installed.
    FileNotFoundError
        If ``path`` does not exist.

    Notes
    -----
    pyuvdata looks up astropy's registry of sites when a file carries no
    telescope location (Measurement Sets not written by pyuvdata, Mir), and
    astropy downloads that registry. Here internet access is off while the
    file is read; the registry then holds no site, and pyuvdata uses its own
    table of known telescopes or the mean antenna position. Earth
    orientation comes from astropy's bundled IERS tables.

    Examples
    --------
    >>> import os, tempfile
    >>> import numpy as np
    >>> import astropy.units as u
    >>> from astropy.coordinates import EarthLocation
    >>> from pyuvdata import Telescope, UVData
    >>> from astropy_feedrot.visibilities.uvdata_files import read_uvdata, write_uvdata
    >>> site = EarthLocation.from_geodetic(-107.6184 * u.deg, 34.0790 * u.deg, 2124 * u.m)
    >>> tel = Telescope.new(name="TEST", instrument="TEST", location=site,
    ...                     antenna_positions={0: [0.0, 0, 0], 1: [100.0, 0, 0]},
    ...                     feed_array=["r", "l"], feed_angle=[0.0, 0.0],
    ...                     mount_type="alt-az")
    >>> uv = UVData.new(freq_array=np.array([1.4e9]), channel_width=np.array([1e6]),
    ...                 polarization_array=["rr", "ll"], times=np.array([2460000.9]),
    ...                 integration_time=np.array([10.0]), telescope=tel,
    ...                 antpairs=[(0, 1)], do_blt_outer=True,
    ...                 empty=True)  # doctest: +IGNORE_WARNINGS
    >>> path = os.path.join(tempfile.mkdtemp(), "test.uvh5")
    >>> write_uvdata(uv, path)
    >>> read_uvdata(path).telescope.mount_type.tolist()
    ['alt-az', 'alt-az']
    """
    pyuvdata = pyuvdata_module()
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(f"no file or directory {path!r}")
    with offline_sites():
        return pyuvdata.UVData.from_file(path, **kwargs)


# The distances from the geocentre (m) at which pyuvdata reads a UVFITS file's array
# centre (ARRAYX/Y/Z); pyuvdata puts the centre of VLBI files, whose ARRAYX/Y/Z are
# 0, at the mean of their antennas, deep inside the Earth, and writes it there.
_SURFACE = (6.35e6, 6.39e6)


@contextlib.contextmanager
def _ready_for_uvfits(uv):
    """While pyuvdata writes UVFITS: phase centres of J2000 (ICRS, FK5) or B1950 (FK4)
    frames without an epoch given it (their EPOCH card), and an array centre off the
    Earth's surface moved onto it (the ellipsoid below it), the antennas' offsets from it
    changed so that their positions stay the same; both restored afterwards."""
    missing = [(entry, _FRAME_EPOCHS[entry.get("cat_frame")])
               for entry in (uv.phase_center_catalog or {}).values()
               if entry.get("cat_epoch") is None and entry.get("cat_frame") in _FRAME_EPOCHS]
    telescope = uv.telescope
    location, offsets = telescope.location, telescope.antenna_positions
    if isinstance(location, EarthLocation):
        centre = np.array([c.to_value(u.m) for c in (location.x, location.y, location.z)])
        if not _SURFACE[0] <= np.linalg.norm(centre) <= _SURFACE[1]:
            surface = EarthLocation.from_geodetic(location.lon, location.lat, 0.0)
            below = np.array([c.to_value(u.m) for c in (surface.x, surface.y, surface.z)])
            telescope.location = surface
            telescope.antenna_positions = offsets + (centre - below)
    for entry, epoch in missing:
        entry["cat_epoch"] = epoch
    try:
        yield
    finally:
        for entry, _ in missing:
            entry["cat_epoch"] = None
        telescope.location, telescope.antenna_positions = location, offsets


def write_uvdata(uv, path, overwrite=False, kind=None):
    """Write a `~pyuvdata.UVData` object, in the format its file name's extension names.

    Parameters
    ----------
    uv : `~pyuvdata.UVData`
        The data.
    path : str or path-like
        The file (or directory, for a Measurement Set or Miriad data) to
        write; its extension chooses the writer (`WRITERS`): ``.uvfits``,
        ``.uvh5``/``.h5``/``.hdf5``, ``.ms``, ``.uv``/``.miriad``.
    overwrite : bool, optional
        Replace an existing file (default False).
    kind : {'uvfits', 'uvh5', 'ms', 'miriad'}, optional
        The format, whatever the extension (e.g. UVFITS named ``.fits``;
        `~astropy_feedrot.visibilities.check_output_format` tells it).

    Raises
    ------
    ImportError
        If pyuvdata is not installed.
    TypeError
        If ``uv`` is not a `~pyuvdata.UVData` object.
    ValueError
        For an extension without a writer, or an unknown ``kind``.
    FileExistsError
        If ``path`` exists and ``overwrite`` is False.

    Notes
    -----
    UVFITS needs the epoch of each phase centre's coordinates; pyuvdata
    leaves none for J2000 entries of AIPS and HOPS files (read as ICRS), and
    they are written with ``EPOCH = 2000`` (B1950 for FK4). The array centre
    of a VLBI file (``ARRAYX/Y/Z`` = 0, which pyuvdata puts at the mean of the
    antennas, inside the Earth) is written on the ellipsoid below that
    point, with the antennas where they were: pyuvdata reads back no centre
    off the surface. ``uv`` is left as it was.

    Examples
    --------
    >>> import os, tempfile
    >>> from pyuvdata import UVData
    >>> from astropy_feedrot.visibilities.uvdata_files import write_uvdata
    >>> write_uvdata(UVData(), os.path.join(tempfile.mkdtemp(), "out.fits"))
    Traceback (most recent call last):
    ...
    ValueError: cannot tell the format of 'out.fits' from its extension '.fits'; ...
    """
    check_uvdata(uv)
    path = os.fspath(path)
    extension = os.path.splitext(path.rstrip("/" + os.sep))[1].lower()
    if kind is not None:
        if kind not in _KIND_WRITERS:
            raise ValueError(f"kind must be one of {tuple(_KIND_WRITERS)} (pyuvdata writes "
                             f"no other), got {kind!r}")
        method = _KIND_WRITERS[kind]
    elif extension in WRITERS:
        method = WRITERS[extension]
    else:
        raise ValueError(f"cannot tell the format of {os.path.basename(path)!r} from its "
                         f"extension {extension!r}; use one of {', '.join(WRITERS)} (or "
                         "give kind=)")
    if os.path.exists(path) and not overwrite:
        raise FileExistsError(f"{path!r} exists; pass overwrite=True to replace it")
    writer = getattr(uv, method)
    # Written beside the target and published in one step: exclusively unless overwrite,
    # so that a file made meanwhile by another program is never replaced.
    name = os.path.basename(path.rstrip("/" + os.sep))
    work = tempfile.mkdtemp(dir=os.path.dirname(os.path.abspath(path)), prefix=f".{name}.")
    try:
        temporary = os.path.join(work, name)
        with offline_sites():
            if method == "write_uvfits":
                with _ready_for_uvfits(uv):
                    writer(temporary)
            else:
                writer(temporary, clobber=True)
        publish(temporary, path, overwrite=overwrite)
    finally:
        shutil.rmtree(work, ignore_errors=True)
