# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Output files that are never lost.

Every output of a command is checked before any work is done (its format,
its directory, an existing file needs permission to be replaced, never one of
the inputs, never two outputs in one file), then written to a temporary file
beside its target and moved into place once everything has been written
(`publish`): a failure anywhere leaves every existing file as it was and no
temporary file behind. Unless replacing was asked for, the move is an
exclusive create: of two runs writing the same new file at once, one wins and
the other fails, instead of both succeeding and one result silently
replacing the other. Used by the ``feedrot`` command line
(`astropy_feedrot.cli`).
"""

import contextlib
import importlib.util
import io
import os
import shutil
import stat
import tempfile
import warnings
from pathlib import Path

__all__ = ["CommandError", "TABLE_FORMATS", "same_file", "check_outputs", "table_format",
           "table_writer", "write_table_blocks", "BLOCK_ROWS", "new_file_mode", "publish",
           "write_files"]


class CommandError(Exception):
    """A problem with a command's input or outputs, reported on one line.

    Examples
    --------
    >>> from astropy_feedrot.core.outputs import CommandError
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
    >>> from astropy_feedrot.core.outputs import same_file
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
        The files to write (path None: not written) and the extensions each may have
        (None: any, for a file whose format the command decides, such as RINEX).
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
    >>> from astropy_feedrot.core.outputs import CommandError, check_outputs
    >>> here = tempfile.mkdtemp()
    >>> check_outputs([("-o", os.path.join(here, "t.ecsv"), (".ecsv",))], [], False)[0].name
    't.ecsv'
    >>> check_outputs([("-o", os.path.join(here, "t.txt"), (".ecsv",))], [], False)
    Traceback (most recent call last):
    ...
    astropy_feedrot.core.outputs.CommandError: -o: cannot tell a format from the extension of ...
    """
    resolved = []
    for what, text, extensions in outputs:
        if text is None:
            resolved.append(None)
            continue
        given = Path(text).expanduser()
        if given.is_dir():
            raise CommandError(f"{what}: {text!r} is a directory")
        if extensions is not None and given.suffix.lower() not in extensions:
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
    >>> from astropy_feedrot.core.outputs import table_format
    >>> table_format(Path("table.ECSV"))
    'ascii.ecsv'
    """
    fmt = TABLE_FORMATS[path.suffix.lower()]
    module = _FORMAT_NEEDS.get(fmt)
    if module is not None and importlib.util.find_spec(module) is None:
        raise CommandError(f"-o/--output: writing {path.suffix} files needs {module} "
                           f"(pip install {module})")
    return fmt


#: Rows of a text table formatted at a time by `write_table_blocks`: the steps of a
#: progress bar while a long table is written (ECSV: about 0.6 s each, of which the
#: header that each block repeats, then drops, takes under 1 %).
BLOCK_ROWS = 25_000

# Text formats that `write_table_blocks` writes in blocks of rows: one line per row.
_LINE_FORMATS = ("ascii.ecsv", "ascii.csv")


def _one_line_per_row(table):
    """Whether every row of ``table`` is written on one line (no string holds a newline)."""
    # numpy when a table is written, not when the module is imported: the command
    # line's parser (and so 'feedrot --help') imports this module.
    import numpy as np

    for name in table.colnames:
        column = table[name]
        kind = getattr(column, "dtype", np.dtype(float)).kind
        if kind == "O":
            return False
        if kind in "US":
            text = np.asarray(column).astype(str)
            if np.any(np.char.find(text, "\n") >= 0) or np.any(np.char.find(text, "\r") >= 0):
                return False
    return True


def write_table_blocks(table, fmt, stream, step=None):
    """Write ``table`` as ``fmt`` to an open text ``stream``, `BLOCK_ROWS` rows at a time.

    The text is the same, byte for byte, as ``table.write(stream, format=fmt)``
    writes: the header of the first block, then the rows of every block (each
    value is formatted on its own). Formats other than ECSV and CSV, and
    tables whose strings hold line breaks, are written in one block.

    Parameters
    ----------
    table : `~astropy.table.Table`
    fmt : str
        A value of `TABLE_FORMATS` that writes text (``ascii.ecsv``,
        ``ascii.csv``, ``ascii.html``).
    stream : file-like
        Open for writing text.
    step : callable, optional
        Called as ``step(rows)`` after each block
        (`~astropy_feedrot.core.progress.progress_steps`).

    Raises
    ------
    RuntimeError
        If a block's header differs from the first block's (which would
        make the blocks differ from the table written at once); nothing
        the package writes does.

    Examples
    --------
    >>> import io
    >>> import numpy as np
    >>> from astropy.table import Table
    >>> from astropy_feedrot.core.outputs import write_table_blocks
    >>> table = Table({"a": np.arange(60_000.0)})
    >>> whole, blocks, steps = io.StringIO(), io.StringIO(), []
    >>> table.write(whole, format="ascii.ecsv")
    >>> write_table_blocks(table, "ascii.ecsv", blocks, steps.append)
    >>> blocks.getvalue() == whole.getvalue(), steps
    (True, [25000, 25000, 10000])
    """
    step = (lambda rows: None) if step is None else step
    rows = len(table)
    if fmt not in _LINE_FORMATS or rows <= BLOCK_ROWS or not _one_line_per_row(table):
        table.write(stream, format=fmt)
        step(rows)
        return
    header = None
    for start in range(0, rows, BLOCK_ROWS):
        block = table[start:start + BLOCK_ROWS]
        text = io.StringIO()
        block.write(text, format=fmt)
        # The writer joins its lines with os.linesep and ends with one: header lines,
        # then one line per row.
        lines = text.getvalue().split(os.linesep)
        count = len(lines) - 1 - len(block)
        if header is None:
            header = lines[:count]
        elif lines[:count] != header:
            raise RuntimeError(f"the {fmt} header of rows {start} to {start + len(block)} "
                               "differs from that of the first rows; write the table at once "
                               "(Table.write)")
        stream.write(os.linesep.join(lines if start == 0 else lines[count:]))
        step(len(block))


def table_writer(table, fmt, step=None):
    """A function that writes ``table`` in format ``fmt`` to a file name, for `write_files`.

    Parameters
    ----------
    table : `~astropy.table.Table`
    fmt : str
        A value of `TABLE_FORMATS`.
    step : callable, optional
        Called as ``step(rows)`` as rows are written: after each block of
        an ECSV or CSV file (`write_table_blocks`), once for other formats.

    Returns
    -------
    callable
        ``write(name)``; HDF5 tables go to the path ``feedrot`` with their
        metadata, and long FITS keywords become HIERARCH cards silently.

    Examples
    --------
    >>> import os, tempfile
    >>> from astropy.table import Table
    >>> from astropy_feedrot.core.outputs import table_writer
    >>> name = os.path.join(tempfile.mkdtemp(), "t.ecsv")
    >>> table_writer(Table({"a": [1, 2]}), "ascii.ecsv")(name)
    >>> len(Table.read(name))
    2
    """

    def write(name):
        if fmt in _LINE_FORMATS:
            # As astropy opens a file it writes text to: no translation of line ends.
            with open(name, "w", newline="") as stream:
                write_table_blocks(table, fmt, stream, step)
            return
        # astropy when a table is written, not when the module is imported: the
        # command line's parser (and so 'feedrot --help') imports this module.
        from astropy.io.fits.verify import VerifyWarning

        options = {"path": "feedrot", "serialize_meta": True} if fmt == "hdf5" else {}
        with warnings.catch_warnings():
            # Header keywords longer than 8 characters are written as HIERARCH cards.
            warnings.filterwarnings("ignore", "Keyword name", VerifyWarning)
            table.write(name, format=fmt, overwrite=True, **options)
        if step is not None:
            step(len(table))
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
    >>> from astropy_feedrot.core.outputs import new_file_mode
    >>> new_file_mode(Path("/nonexistent/file")) & 0o600
    384
    """
    if path.exists():
        return stat.S_IMODE(path.stat().st_mode)
    umask = os.umask(0o022)
    os.umask(umask)
    return 0o666 & ~umask


def publish(temporary, target, overwrite=False):
    """Move a finished temporary file or directory onto its target in one step.

    Parameters
    ----------
    temporary : str or path-like
        The finished output, a file or a directory (a Measurement Set), in
        the directory of ``target`` (a move within one file system).
    target : str or path-like
        Where it goes.
    overwrite : bool, optional
        Whether an existing ``target`` may be replaced. If False (the
        default), ``target`` is created exclusively: if anything exists
        there, even made by another program since the outputs were checked,
        nothing is replaced.

    Raises
    ------
    FileExistsError
        If ``target`` exists and ``overwrite`` is False; ``temporary`` is
        then left for the caller to remove.

    Notes
    -----
    A file is published with a hard link (`os.link`, which refuses an
    existing name), or, on file systems without hard links, by creating the
    name with ``O_CREAT | O_EXCL`` and renaming onto it; a directory by
    creating the name with `os.mkdir` (which refuses an existing name) and
    renaming onto the empty directory. With ``overwrite``, a file is renamed
    over the target (`os.replace`) and an existing directory is moved aside
    first and removed once the new one is in place.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from astropy_feedrot.core.outputs import publish
    >>> here = Path(tempfile.mkdtemp())
    >>> (here / "a.tmp").write_text("first")
    5
    >>> publish(here / "a.tmp", here / "out.txt")
    >>> (here / "b.tmp").write_text("second")
    6
    >>> publish(here / "b.tmp", here / "out.txt")
    Traceback (most recent call last):
    ...
    FileExistsError: ... exists (made by another program while this one ran?); nothing was replaced
    >>> (here / "out.txt").read_text()
    'first'
    """
    temporary, target = Path(temporary), Path(target)
    exists = (f"{str(target)!r} exists (made by another program while this one ran?); "
              "nothing was replaced")
    if temporary.is_dir() and not temporary.is_symlink():
        if not overwrite:
            try:
                os.mkdir(target)
            except FileExistsError:
                raise FileExistsError(exists) from None
            try:
                os.replace(temporary, target)
            except BaseException:
                os.rmdir(target)
                raise
        elif target.is_dir() and not target.is_symlink():
            old = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}.old."))
            os.replace(target, old / target.name)
            try:
                os.replace(temporary, target)
            except BaseException:
                os.replace(old / target.name, target)
                raise
            finally:
                shutil.rmtree(old, ignore_errors=True)
        else:
            with contextlib.suppress(FileNotFoundError):
                os.remove(target)
            os.replace(temporary, target)
        return
    if overwrite:
        os.replace(temporary, target)
        return
    try:
        os.link(temporary, target)
    except FileExistsError:
        raise FileExistsError(exists) from None
    except OSError:
        # No hard links on this file system: reserve the name exclusively, then rename.
        try:
            handle = os.open(target, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600)
        except FileExistsError:
            raise FileExistsError(exists) from None
        os.close(handle)
        os.replace(temporary, target)
    else:
        os.remove(temporary)


def write_files(files, then=None, overwrite=False):
    """Write files safely: each to a temporary file beside it, all published at the end.

    Parameters
    ----------
    files : list of (Path, callable)
        Each target and a function writing its content to a given file name.
    then : callable, optional
        Called once every file is written, before any is published.
    overwrite : bool, optional
        Whether existing targets may be replaced; if False (the default), each
        target is created exclusively (`publish`).

    Raises
    ------
    CommandError
        If a target exists and ``overwrite`` is False (another program made
        it while this one ran): no target is then written.

    Notes
    -----
    A failure anywhere leaves every existing file as it was and no temporary
    file behind. Permissions of a replaced file are kept.

    Examples
    --------
    >>> import os, tempfile
    >>> from pathlib import Path
    >>> from astropy_feedrot.core.outputs import write_files
    >>> target = Path(tempfile.mkdtemp()) / "out.txt"
    >>> write_files([(target, lambda name: Path(name).write_text("done"))])
    >>> target.read_text(), sorted(os.listdir(target.parent))
    ('done', ['out.txt'])
    """
    temporaries = []
    published = []
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
            try:
                publish(name, path, overwrite=overwrite)
            except FileExistsError as error:
                # Take back the outputs of this run already in place: all or none.
                for done in published:
                    with contextlib.suppress(FileNotFoundError):
                        os.remove(done)
                raise CommandError(f"{error}; add --overwrite to replace it") from None
            published.append(path)
    finally:
        for name in temporaries:
            with contextlib.suppress(FileNotFoundError):
                os.remove(name)
