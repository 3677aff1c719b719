# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The adapter of the files pyuvdata reads (UVFITS, uvh5, Miriad, SMA Mir, and a
Measurement Set written in another format): read whole, corrected by
`~astropy_feedrot.visibilities.correct_uvdata`, written in the format the output's
extension names, beside it and moved into place at the end.

pyuvdata is an optional dependency (the ``uvdata`` extra), imported when a function
here is called.
"""
import contextlib
import os
import shutil
import tempfile
import warnings
from pathlib import Path

from ..core.outputs import publish
from ..core.progress import check_progress, progress_steps
from .antenna_tables import fits_telescopes
from .correction import refuse_column_options, register_adapter
from .kinds import check_output_format, check_output_path, file_kind
from .uvdata import correct_uvdata
from .uvdata_files import PYUVDATA_TYPES, read_uvdata, write_uvdata

__all__ = ["correct_uvdata_file", "uvdata_telescopes"]


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


def uvdata_telescopes(path):
    """The telescope name pyuvdata reads from a file's metadata (none if empty).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.uvdata_adapter import uvdata_telescopes
    >>> uvdata_telescopes("tests/data/uvdata/ata.LoA.C0352.uvh5_60647_62965_9760406_"
    ...                   "3c286_0001.uvh5")
    ['ATA']
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyuvdata's complaints come with the data's read
        uv = read_uvdata(path, read_data=False, file_type=PYUVDATA_TYPES[file_kind(path)])
    return [uv.telescope.name] if uv.telescope.name else []


def correct_uvdata_file(correction, source, output, *, overwrite=False, progress=False,
                        client=None, kind=None, **columns):
    """Correct a file pyuvdata reads into ``output`` (the adapter of these kinds).

    ``client`` is not used (pyuvdata reads and writes in one call each); ``kind`` is the
    input's, when known.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import Correction
    >>> from astropy_feedrot.visibilities.uvdata_adapter import correct_uvdata_file
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "copy.uvh5"
    >>> correct_uvdata_file(Correction(), sample_file("vla_day2_8chan.uvfits"),
    ...                     out).name  # doctest: +IGNORE_WARNINGS
    'copy.uvh5'
    """
    refuse_column_options(**columns)
    kind = file_kind(source) if kind is None else kind
    if output is None:
        raise ValueError(f"{str(source)!r} is a {kind} file: it is corrected into a copy; "
                         "give the output")
    written = check_output_format(kind, output)
    target = check_output_path(source, output, overwrite)
    size = _stored_size(source)
    # pyuvdata reads and writes in one call each: the bar is drawn before the read, and
    # counts the input's bytes three times (read, corrected chunk by chunk, written).
    with progress_steps(check_progress(progress), 3 * size) as step:
        uv = read_uvdata(source, file_type=PYUVDATA_TYPES[kind])
        step(size)
        correction.check_history(uv.history, str(source))  # the file named
        correct_uvdata(uv, inplace=True, progress=_share(step, size) if progress else False,
                       correction=correction)
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


register_adapter(["uvfits"], correct_uvdata_file, fits_telescopes)
register_adapter(["uvh5", "miriad", "mir"], correct_uvdata_file, uvdata_telescopes)
