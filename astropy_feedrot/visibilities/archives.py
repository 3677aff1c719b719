# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Many visibility files corrected in one run: one task per file on dask.distributed.

An archive (a survey, an observatory's sets, a session's FITS-IDI files) is
corrected by `correct_files`: each file is one task, on the workers of a
dask.distributed client (a local cluster, or the user's scheduler: SLURM,
Kubernetes and dask-jobqueue clusters alike) or one after the other in this
process. One file that cannot be corrected does not stop the others: each
file's outcome is a row of the table returned,

* ``corrected``: written (its output named);
* ``skipped``: corrected by an earlier run (a copy in the output directory,
  a Measurement Set's column or a processing set's data group that holds
  this correction already), so that a run stopped half way goes on where it
  stopped when started again;
* ``refused``: the correction refuses the file, saying why (an aperture
  array, a mount without a model, data corrected already...);
* ``failed``: anything else went wrong (the error, with its type).

A file refused or failed is left as it was: a copy is written beside its
target and moved into place only when finished, and a Measurement Set
corrected in place keeps its data column (its output column records the
rows done, `~astropy_feedrot.visibilities.correct_ms`). MSv4 processing
sets are corrected in this process, their dask graph computed on the
client's workers.
"""
import os
import time
import warnings
from pathlib import Path

from astropy.table import Table

from ..core.progress import progress_steps
from .correction import OPTIONS, Correction
from .files import correct_file  # noqa: F401 (every adapter registered)
from .history import AlreadyCorrected
from .kinds import existing_path, file_kind

__all__ = ["correct_files", "OUTCOMES"]

#: The outcomes of a file in `correct_files`, as its table gives them.
OUTCOMES = ("corrected", "skipped", "refused", "failed")

#: Options of a Measurement Set corrected in place (or copied as one) only.
_COLUMN_OPTIONS = ("data_column", "corrected_column", "overwrite_column")


def _one_line(error):
    return " ".join(str(error).split())


def correct_one(correction, path, target, options):
    """One file's outcome: a dict with ``outcome``, ``output``, ``reason``, ``warnings``
    and ``seconds``; never raises but for an interrupt (what a task of `correct_files`
    runs).

    Examples
    --------
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import Correction
    >>> from astropy_feedrot.visibilities.archives import correct_one
    >>> correct_one(Correction(), sample_file("vla_day2_8chan.uvfits"), None, {})["outcome"]
    'refused'
    """
    start = time.perf_counter()
    outcome, output, reason = "corrected", "", ""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            # Absolute, as every format's adapter does not give it alike.
            output = os.path.abspath(correction.correct(path, target, **options))
        except AlreadyCorrected as error:
            outcome, reason = "skipped", _one_line(error)
        except (ValueError, ImportError) as error:  # the package's refusals are ValueErrors
            outcome, reason = "refused", _one_line(error)
        except Exception as error:  # noqa: BLE001 - one file's failure is its row
            outcome, reason = "failed", f"{type(error).__name__}: {_one_line(error)}"
    notes = list(dict.fromkeys(f"{w.category.__name__}: {_one_line(w.message)}"
                               for w in caught))
    return dict(outcome=outcome, output=output, reason=reason, warnings=notes,
                seconds=time.perf_counter() - start)


def _targets(paths, output_dir, overwrite):
    """The output of each input (None: in place), and the inputs skipped as done."""
    if output_dir is None:
        return [None] * len(paths), {}
    output_dir = Path(output_dir)
    names = {}
    for path in paths:
        names.setdefault(path.name, []).append(str(path))
    twice = {name: found for name, found in names.items() if len(found) > 1}
    if twice:
        name, found = next(iter(twice.items()))
        raise ValueError(f"the inputs {', '.join(map(repr, found))} would all be written as "
                         f"{str(output_dir / name)!r}: correct them into different output "
                         "directories")
    if output_dir.exists() and not output_dir.is_dir():
        raise ValueError(f"the output directory {str(output_dir)!r} is a file")
    targets = [output_dir / path.name for path in paths]
    for path, target in zip(paths, targets):
        if target.resolve() == path.resolve():
            raise ValueError(f"{str(path)!r} would be written onto itself: give another "
                             "output directory")
    done = {k: f"{str(t)!r} exists (an earlier run's output); overwrite=True (--overwrite) "
               "writes it again" for k, t in enumerate(targets) if t.exists() and not overwrite}
    return targets, done


def _kinds(paths):
    """Each input's kind, or the reason it has none (its row fails)."""
    kinds = []
    for path in paths:
        try:
            kinds.append((file_kind(path), None))
        except (OSError, ValueError) as error:
            kinds.append((None, f"{type(error).__name__}: {_one_line(error)}"))
    return kinds


def _run(correction, jobs, client, progress):
    """The outcome of each job (index, path, kind, target, options), in this process or
    on the client's workers, one task per file; MSv4 sets here (their graph on the
    client)."""
    results = {}
    with progress_steps(progress, len(jobs)) as step:
        here = [client is None or kind == "msv4" for _, _, kind, _, _ in jobs]
        local = [job for job, there in zip(jobs, here) if there]
        remote = [job for job, there in zip(jobs, here) if not there]
        futures = {}
        if remote:
            futures = {client.submit(correct_one, correction, path, target, options, pure=False,
                                     key=f"feedrot-correct-{index}-{os.getpid()}-"
                                     f"{time.monotonic_ns()}"): index
                       for index, path, kind, target, options in remote}
        for index, path, kind, target, options in local:
            results[index] = correct_one(correction, path, target, options)
            step()
        if futures:
            from distributed import as_completed  # with the client

            for future in as_completed(futures):
                try:
                    results[futures[future]] = future.result()
                except Exception as error:  # noqa: BLE001 - a worker lost, say
                    results[futures[future]] = dict(
                        outcome="failed", output="", warnings=[], seconds=0.0,
                        reason=f"{type(error).__name__}: {_one_line(error)}")
                step()
    return results


def correct_files(paths, output_dir=None, *, client=None, progress=False, overwrite=False,
                  correction=None, **options):
    """Correct many visibility files, one task per file; the outcome of each in a table.

    Parameters
    ----------
    paths : iterable of str or path-like
        The inputs, of any kind of `~astropy_feedrot.visibilities.FILE_KINDS`.
    output_dir : str or path-like, optional
        Where the corrected copies go, each under its input's name, in its
        input's format (created if missing). Without it, every input is
        corrected in place: Measurement Sets (``data_column`` into
        ``corrected_column``) and MSv4 processing sets (a new data group);
        other files are refused.
    client : `dask.distributed.Client`, optional
        Correct the files on its workers, one task per file (a processing
        set's graph runs on them too); without it, one after the other here.
    progress : bool or callable, optional
        Count the files done: astropy's progress bar (True), or
        ``progress(done, total)``.
    overwrite : bool, optional
        Write over copies an earlier run left in ``output_dir`` (else those
        files are skipped, as done).
    correction : `~astropy_feedrot.visibilities.Correction`, optional
        The correction's options, made once (checked before any file is
        touched)...
    **options
        ...or given here, as `~astropy_feedrot.visibilities.Correction`
        takes them; and for Measurement Sets ``data_column``,
        ``corrected_column``, ``overwrite_column``.

    Returns
    -------
    `~astropy.table.Table`
        One row per input, in the order given: ``path``, ``kind``,
        ``outcome`` (one of `OUTCOMES`), ``output``, ``reason`` (why it was
        skipped, refused or failed), ``warnings`` (what its correction
        warned, one line each, ``|`` between), ``seconds``.

    Raises
    ------
    ValueError
        Before any file is touched: two inputs of one name into one
        directory, an input as its own output, an output directory that is
        a file, or no input.
    TypeError
        For an option the corrections do not take.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from astropy_feedrot.data import sample_file
    >>> from astropy_feedrot.visibilities import correct_files
    >>> out = pathlib.Path(tempfile.mkdtemp())
    >>> table = correct_files([sample_file("difx_k08161.idifits"), "nowhere.ms"], out)
    >>> table["outcome"].tolist()
    ['corrected', 'failed']
    >>> correct_files([sample_file("difx_k08161.idifits")], out)["outcome"].tolist()
    ['skipped']
    """
    unknown = sorted(set(options) - set(OPTIONS) - set(_COLUMN_OPTIONS))
    if unknown:
        raise TypeError(f"correct_files() got unexpected options {unknown}")
    correction = Correction.of(correction, **{k: v for k, v in options.items()
                                              if k in OPTIONS})
    options = {k: v for k, v in options.items() if k in _COLUMN_OPTIONS}
    paths = [Path(os.fspath(p)) for p in paths]
    if not paths:
        raise ValueError("no input to correct")
    targets, done = _targets(paths, output_dir, overwrite)
    if output_dir is not None:
        Path(output_dir).mkdir(parents=True, exist_ok=True)
        options["overwrite"] = overwrite
    rows, jobs = [], []
    for index, (path, (kind, problem), target) in enumerate(zip(paths, _kinds(paths), targets)):
        rows.append(dict(path=str(path), kind=kind or "", output="", warnings=[],
                         seconds=0.0, outcome="failed" if problem else "skipped",
                         reason=problem or done.get(index, "")))
        if problem is None and index not in done:
            jobs.append((index, existing_path(path), kind, target, options))
    for index, result in _run(correction, jobs, client, progress).items():
        rows[index].update(result)
    table = Table(rows=[[row[k] for k in ("path", "kind", "outcome", "output", "reason")]
                        + [" | ".join(row["warnings"]), row["seconds"]] for row in rows],
                  names=("path", "kind", "outcome", "output", "reason", "warnings", "seconds"),
                  dtype=(str, str, str, str, str, str, float))
    table["seconds"].format = ".1f"
    table.meta["outcomes"] = {k: int((table["outcome"] == k).sum()) for k in OUTCOMES}
    return table
