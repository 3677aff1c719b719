# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""RINEX text streams: reading plain, gzip and Hatanaka-compressed files, and writing.

`open_rinex_lines` recognises gzip (by its magic bytes) and Compact RINEX
(by its ``CRINEX VERS   / TYPE`` first line, decompressed by the ``crx2rnx``
program of the optional hatanaka package through a pipe,
`CompactRinexPipe`), and gives the lines as Latin-1 text with their own line
ends, so that every byte can be written back as it was. `RinexWriter` writes
them (gzip-compressed for ``.gz`` names); `comment_line` makes the one header
line a correction adds.
"""

import contextlib
import gzip
import io
import os
import shutil
import subprocess
import threading
import zlib
from importlib.resources import files

from ..core.extras import install_hint
from ..io import FileFormatError

__all__ = ["source_name", "crx2rnx_program", "CompactRinexPipe", "open_rinex_lines",
           "RinexWriter", "comment_line"]

# Doctests that need the optional hatanaka (pytest-doctestplus).
__doctest_requires__ = {("crx2rnx_program", "CompactRinexPipe"): ["hatanaka"]}


def source_name(source):
    """The name of a path or file object, for messages.

    Examples
    --------
    >>> from astropy_feedrot.gnss.streams import source_name
    >>> source_name("obs.rnx")
    'obs.rnx'
    """
    if isinstance(source, (str, os.PathLike)):
        return os.fsdecode(os.fspath(source))
    name = getattr(source, "name", None)
    return name if isinstance(name, str) and name else "<stream>"


def crx2rnx_program():
    """Path of the ``crx2rnx`` program of the optional hatanaka package.

    Raises
    ------
    ImportError
        Without hatanaka, naming the extra that installs it.

    Examples
    --------
    >>> from astropy_feedrot.gnss.streams import crx2rnx_program
    >>> crx2rnx_program().endswith("crx2rnx")
    True
    """
    try:
        import hatanaka.bin  # optional dependency, imported on use
    except ImportError:
        raise ImportError("reading Hatanaka-compressed RINEX (Compact RINEX) needs the "
                          f"hatanaka package: {install_hint('gnss', 'hatanaka')}") from None
    program = files(hatanaka.bin).joinpath("crx2rnx.exe" if os.name == "nt" else "crx2rnx")
    return str(program)


class CompactRinexPipe:
    """Text lines of a Compact RINEX stream decompressed by ``crx2rnx`` through a pipe.

    Parameters
    ----------
    binary : file object
        The compressed stream (bytes), fed to ``crx2rnx`` by a thread.
    name : str
        The file's name, for messages.

    Attributes
    ----------
    text : io.TextIOWrapper
        The decompressed lines (Latin-1, line ends kept).

    Examples
    --------
    >>> import io
    >>> import hatanaka
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.gnss.streams import CompactRinexPipe
    >>> compact = hatanaka.rnx2crx(sample_file("gnss_sample.rnx").read_bytes())
    >>> pipe = CompactRinexPipe(io.BytesIO(compact), "sample.crx")
    >>> pipe.text.readline()[60:]
    'RINEX VERSION / TYPE\\n'
    >>> pipe.close()
    """

    def __init__(self, binary, name):
        self.name = name
        self.process = subprocess.Popen([crx2rnx_program(), "-"], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.error = []

        def feed():
            try:
                shutil.copyfileobj(binary, self.process.stdin, 1 << 20)
            except BrokenPipeError:  # crx2rnx stopped: its exit code tells why
                pass
            except (EOFError, OSError, zlib.error) as error:  # a truncated or broken .gz
                self.error.append(error)
                with contextlib.suppress(OSError):  # crx2rnx sees its input end
                    self.process.stdin.close()
            finally:
                with contextlib.suppress(OSError):
                    self.process.stdin.close()

        self.thread = threading.Thread(target=feed, daemon=True)
        self.thread.start()
        self.stderr = []
        self.err_thread = threading.Thread(
            target=lambda: self.stderr.append(self.process.stderr.read()), daemon=True)
        self.err_thread.start()
        self.text = io.TextIOWrapper(self.process.stdout, encoding="latin-1", newline="")

    def check(self, lineno=0):
        """Raise `~astropy_feedrot.io.FileFormatError` if crx2rnx failed (at the end of its output).

        ``lineno`` is the line of the decompressed file where the output ended.

        Examples
        --------
        See `CompactRinexPipe`.
        """
        code = self.process.wait()
        self.thread.join()
        self.err_thread.join()
        if self.error:
            error = self.error[0]
            raise FileFormatError(self.name, lineno, "a complete compressed file that "
                                  "decompresses",
                                  f"{type(error).__name__}: {error}")
        if code not in (0, 2):
            message = b"".join(self.stderr).decode("latin-1").strip().splitlines()
            raise FileFormatError(self.name, lineno, "a Compact RINEX (Hatanaka) file that crx2rnx "
                                  "decompresses", " ".join(message)[:200] or f"exit {code}")

    def close(self):
        """Stop ``crx2rnx`` if it still runs, and close the pipes.

        Examples
        --------
        See `CompactRinexPipe`.
        """
        if self.process.poll() is None:
            self.process.kill()
        self.process.wait()
        self.thread.join()
        self.err_thread.join()
        self.text.close()
        self.process.stderr.close()


def open_rinex_lines(source, stack, name):
    """Lines of a RINEX source (path or file object), decompressing as needed.

    Parameters
    ----------
    source : str, path-like or file object
        A path (plain, gzip or Compact RINEX, recognised by content), a
        text file object, or a binary one.
    stack : contextlib.ExitStack
        Receives what must be closed with the source.
    name : str
        The file's name, for messages.

    Returns
    -------
    lines : iterator of str
        Lines with their line ends.
    pipe : `CompactRinexPipe` or None
        The decompressing pipe of a Compact RINEX file, whose ``check``
        reports a failure of ``crx2rnx`` at the end.

    Raises
    ------
    TypeError
        If ``source`` is neither a path nor a file object.

    Examples
    --------
    >>> import contextlib, io
    >>> from astropy_feedrot.gnss.streams import open_rinex_lines
    >>> with contextlib.ExitStack() as stack:
    ...     lines, pipe = open_rinex_lines(io.BytesIO(b"a\\r\\nb\\n"), stack, "x")
    ...     list(lines), pipe
    (['a\\r\\n', 'b\\n'], None)
    """
    if isinstance(source, (str, os.PathLike)):
        binary = stack.enter_context(open(source, "rb"))
    elif hasattr(source, "read"):
        if isinstance(source.read(0), str):
            return iter(source.readline, ""), None
        binary = source
    else:
        raise TypeError("source must be a path (str or os.PathLike) or a file object, got "
                        f"{type(source).__name__}")
    binary = io.BufferedReader(binary) if not hasattr(binary, "peek") else binary
    if binary.peek(2)[:2] == b"\x1f\x8b":
        binary = stack.enter_context(gzip.GzipFile(fileobj=binary, mode="rb"))
        binary = io.BufferedReader(binary)
    try:
        start = binary.peek(80)
    except (EOFError, OSError, zlib.error) as error:  # a .gz cut short within its first block
        raise FileFormatError(name, 1, "a complete compressed file that decompresses",
                              f"{type(error).__name__}: {error}") from None
    if start[60:80].startswith(b"CRINEX VERS"):
        pipe = CompactRinexPipe(binary, name)
        stack.callback(pipe.close)
        return iter(pipe.text.readline, ""), pipe
    text = io.TextIOWrapper(binary, encoding="latin-1", newline="")
    stack.callback(text.detach)
    return iter(text.readline, ""), None


def comment_line(text, line_end="\n"):
    """A RINEX header ``COMMENT`` line (text in columns 1-60, the label padded to 80).

    Raises
    ------
    ValueError
        If ``text`` is longer than 60 characters.

    Examples
    --------
    >>> from astropy_feedrot.gnss import comment_line
    >>> len(comment_line("hello").rstrip("\\n")), comment_line("hello")[60:].rstrip()
    (80, 'COMMENT')
    """
    if len(text) > 60:
        raise ValueError(f"a RINEX comment holds 60 characters, got {len(text)}: {text!r}")
    return f"{text:<60}{'COMMENT':<20}{line_end}"


class RinexWriter:
    """Write a RINEX observation file line by line, as read (gzip for ``.gz`` names).

    Parameters
    ----------
    target : str, path-like or file object
        Where to write: a path (compressed with gzip if it ends in ``.gz``)
        or a text file object.

    Examples
    --------
    >>> import io
    >>> from astropy_feedrot.gnss import RinexReader, RinexWriter
    >>> text = '''     3.04           OBSERVATION DATA    G                   RINEX VERSION / TYPE
    ... G    1 L1C                                                  SYS / # / OBS TYPES
    ...                                                             END OF HEADER
    ... > 2023 01 25 00 00  0.0000000  0  1
    ... G05 105100000.123 7
    ... '''
    >>> out = io.StringIO()
    >>> with RinexReader(io.StringIO(text)) as reader, RinexWriter(out) as writer:
    ...     writer.write_header(reader.header, "example")
    ...     for record in reader:
    ...         writer.write_record(record)
    >>> print(out.getvalue().splitlines()[2])
    example                                                     COMMENT
    """

    def __init__(self, target):
        self._stack = contextlib.ExitStack()
        if isinstance(target, (str, os.PathLike)):
            name = os.fsdecode(os.fspath(target))
            if name.endswith(".gz"):
                binary = self._stack.enter_context(gzip.open(name, "wb", compresslevel=6))
            else:
                binary = self._stack.enter_context(open(name, "wb"))
            self._file = self._stack.enter_context(
                io.TextIOWrapper(binary, encoding="latin-1", newline=""))
        elif hasattr(target, "write"):
            self._file = target
        else:
            raise TypeError("target must be a path or a text file object, got "
                            f"{type(target).__name__}")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        """Flush and close the file (a file object given is left open)."""
        self._stack.close()

    @property
    def file(self):
        """The text file object written to."""
        return self._file

    def write_header(self, header, comment=None):
        """Write the header as read, with ``COMMENT`` lines before ``END OF HEADER``.

        Parameters
        ----------
        header : `RinexHeader`
        comment : str or list of str, optional
            The text of one comment line, or of several.

        Examples
        --------
        See `RinexWriter`.
        """
        lines = header.lines
        write = self._file.write
        for line in lines[:-1]:
            write(line)
        comments = [comment] if isinstance(comment, str) else comment or []
        for text in comments:
            write(comment_line(text, header.line_end))
        write(lines[-1])

    def write_record(self, record):
        """Write an epoch record's lines.

        Examples
        --------
        See `RinexWriter`.
        """
        self._file.writelines(record.lines)
