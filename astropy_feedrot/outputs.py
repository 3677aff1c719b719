# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Output files that are never lost.

Every output of a command is checked before any work is done (its format,
its directory, an existing file needs permission to be replaced, never one of
the inputs, never two outputs in one file), then written to a temporary file
beside its target and renamed into place once everything has been written:
a failure anywhere leaves every existing file as it was and no temporary file
behind. Used by the ``feedrot`` command line (`astropy_feedrot.cli`).
"""

import contextlib
import importlib.util
import os
import stat
import tempfile
import warnings
from pathlib import Path

from astropy.io.fits.verify import VerifyWarning

__all__ = ["CommandError", "TABLE_FORMATS", "same_file", "check_outputs", "table_format",
           "table_writer", "new_file_mode", "write_files"]


class CommandError(Exception):
    """A problem with a command's input or outputs, reported on one line.

    Examples
    --------
    >>> from astropy_feedrot.outputs import CommandError
    >>> str(CommandError("-o/--output: 'x.ecsv' exists"))
    "-o/--output: 'x.ecsv' exists"
    """


#: Formats of ``-o/--output`` by file extension: the format `astropy.table.Table.write`
#: itself identifies from each extension. ECSV, FITS and HDF5 keep units, the
#: time scale and the header; CSV and HTML keep the values only (degrees, ps, UTC).
TABLE_FORMATS = {
    ".ecsv": "ascii.ecsv",
    ".csv": "ascii.csv",
    ".fits": "fits",
    ".fit": "fits",
    ".fts": "fits",
    ".hdf5": "hdf5",
    ".h5": "hdf5",
    ".html": "ascii.html",
}

#: The modules each table format needs beyond astropy.
_FORMAT_NEEDS = {"hdf5": "h5py"}


def same_file(path, other):
    """Whether two paths name one file (the same path, or links to one file).

    Parameters
    ----------
    path, other : str or path-like

    Returns
    -------
    bool
        False if either does not exist (and the paths differ).

    Examples
    --------
    >>> from astropy_feedrot.outputs import same_file
    >>> same_file("/nonexistent/a", "/nonexistent/a"), same_file("/nonexistent/a", "/b")
    (True, False)
    """
    if path == other:
        return True
    try:
        return os.path.samefile(path, other)
    except OSError:
        return False


def check_outputs(outputs, inputs, overwrite, hint="choose another name"):
    """Resolved paths of the outputs, each checked before any work is done.

    Parameters
    ----------
    outputs : list of (option, path, extensions)
        The files to write (path None: not written) and the extensions each may have.
    inputs : list of (option, path)
        Files the command reads: never overwritten.
    overwrite : bool
        Whether an existing output may be replaced.
    hint : str
        What else to do about an existing output.

    Returns
    -------
    list of `pathlib.Path` or None
        The resolved path of each output (symbolic links followed), None
        where the output is not written.

    Raises
    ------
    CommandError
        For an output that is a directory, has an extension not in its list,
        is one of the inputs or another output, lies in a missing or
        unwritable directory, or exists without ``overwrite``.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy_feedrot.outputs import CommandError, check_outputs
    >>> here = tempfile.mkdtemp()
    >>> check_outputs([("-o", os.path.join(here, "t.ecsv"), (".ecsv",))], [], False)[0].name
    't.ecsv'
    >>> check_outputs([("-o", os.path.join(here, "t.txt"), (".ecsv",))], [], False)
    Traceback (most recent call last):
    ...
    astropy_feedrot.outputs.CommandError: -o: cannot tell a format from the extension of ...
    """
    resolved = []
    for what, text, extensions in outputs:
        if text is None:
            resolved.append(None)
            continue
        given = Path(text).expanduser()
        if given.is_dir():
            raise CommandError(f"{what}: {text!r} is a directory")
        if given.suffix.lower() not in extensions:
            raise CommandError(f"{what}: cannot tell a format from the extension of {text!r}; "
                               f"use one of {', '.join(extensions)}")
        # Through symbolic links: the file that would change.
        path = given.resolve()
        for option, source in inputs:
            if same_file(path, Path(source).expanduser().resolve()):
                raise CommandError(f"{what}: {text!r} is the {option} input, which is never "
                                   f"overwritten; {hint}")
        for option, other in zip((o[0] for o in outputs), resolved):
            if other is not None and same_file(path, other):
                raise CommandError(f"{what} and {option} name the same file {text!r}; each "
                                   "needs its own")
        if not path.parent.is_dir():
            raise CommandError(f"{what}: cannot write {text!r}: directory "
                               f"{str(path.parent)!r} does not exist")
        if path.exists():
            if not path.is_file():
                raise CommandError(f"{what}: {text!r} is not a regular file")
            if not overwrite:
                raise CommandError(f"{what}: {text!r} exists; add --overwrite to replace it, or "
                                   f"{hint}")
            if not os.access(path, os.W_OK):
                raise CommandError(f"{what}: cannot write {text!r}: permission denied")
        if not os.access(path.parent, os.W_OK | os.X_OK):
            raise CommandError(f"{what}: cannot write {text!r}: permission denied in "
                               f"{str(path.parent)!r}")
        resolved.append(path)
    return resolved


def table_format(path):
    """The astropy format of a table file, checking that its writer is installed.

    Parameters
    ----------
    path : `pathlib.Path`
        A file name whose extension is in `TABLE_FORMATS`.

    Returns
    -------
    str
        The format name for `astropy.table.Table.write`.

    Raises
    ------
    CommandError
        If the format needs a module that is not installed (h5py for HDF5).

    Examples
    --------
    >>> from pathlib import Path
    >>> from astropy_feedrot.outputs import table_format
    >>> table_format(Path("table.ECSV"))
    'ascii.ecsv'
    """
    fmt = TABLE_FORMATS[path.suffix.lower()]
    module = _FORMAT_NEEDS.get(fmt)
    if module is not None and importlib.util.find_spec(module) is None:
        raise CommandError(f"-o/--output: writing {path.suffix} files needs {module} "
                           f"(pip install {module})")
    return fmt


def table_writer(table, fmt):
    """A function that writes ``table`` in format ``fmt`` to a file name, for `write_files`.

    Parameters
    ----------
    table : `~astropy.table.Table`
    fmt : str
        A value of `TABLE_FORMATS`.

    Returns
    -------
    callable
        ``write(name)``; HDF5 tables go to the path ``feedrot`` with their
        metadata, and long FITS keywords become HIERARCH cards silently.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy.table import Table
    >>> from astropy_feedrot.outputs import table_writer
    >>> name = os.path.join(tempfile.mkdtemp(), "t.ecsv")
    >>> table_writer(Table({"a": [1, 2]}), "ascii.ecsv")(name)
    >>> len(Table.read(name))
    2
    """

    def write(name):
        options = {"path": "feedrot", "serialize_meta": True} if fmt == "hdf5" else {}
        with warnings.catch_warnings():
            # Header keywords longer than 8 characters are written as HIERARCH cards.
            warnings.filterwarnings("ignore", "Keyword name", VerifyWarning)
            table.write(name, format=fmt, overwrite=True, **options)
    return write


def new_file_mode(path):
    """The permission bits a file written at ``path`` should get.

    Parameters
    ----------
    path : `pathlib.Path`

    Returns
    -------
    int
        Those of the existing file, or those of a new file under the umask.

    Examples
    --------
    >>> from pathlib import Path
    >>> from astropy_feedrot.outputs import new_file_mode
    >>> new_file_mode(Path("/nonexistent/file")) & 0o600
    384
    """
    if path.exists():
        return stat.S_IMODE(path.stat().st_mode)
    umask = os.umask(0o022)
    os.umask(umask)
    return 0o666 & ~umask


def write_files(files, then=None):
    """Write files safely: each to a temporary file beside it, all renamed at the end.

    Parameters
    ----------
    files : list of (Path, callable)
        Each target and a function writing its content to a given file name.
    then : callable, optional
        Called once every file is written, before any is renamed.

    Notes
    -----
    A failure anywhere leaves every existing file as it was and no temporary
    file behind. Permissions of a replaced file are kept.

    Examples
    --------
    >>> import os, tempfile
    >>> from pathlib import Path
    >>> from astropy_feedrot.outputs import write_files
    >>> target = Path(tempfile.mkdtemp()) / "out.txt"
    >>> write_files([(target, lambda name: Path(name).write_text("done"))])
    >>> target.read_text(), sorted(os.listdir(target.parent))
    ('done', ['out.txt'])
    """
    temporaries = []
    try:
        for path, write in files:
            handle, name = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem[:64]}.",
                                            suffix=f".tmp{path.suffix}")
            os.close(handle)
            temporaries.append(name)
            write(name)
            os.chmod(name, new_file_mode(path))
        if then is not None:
            then()
        for name, (path, _) in zip(temporaries, files):
            os.replace(name, path)
    finally:
        for name in temporaries:
            with contextlib.suppress(FileNotFoundError):
                os.remove(name)
