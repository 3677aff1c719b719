# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Progress of long work, as the caller asks for it.

`~astropy_feedrot.visibilities.correct_uvdata`,
`~astropy_feedrot.visibilities.correct_fitsidi`,
`~astropy_feedrot.visibilities.correct_ms` and
`~astropy_feedrot.gnss.correct_rinex` take ``progress=True`` (astropy's
`~astropy.utils.console.ProgressBar` on standard error, drawn only when
standard error is a terminal), ``False`` or a callable
``progress(done, total)``; `progress_steps` turns that into one function to
call after each step, and the ``feedrot`` commands use it for their bars.
The work is counted in the units it is done in (chunks of rows, blocks of
epochs, bytes of a file read): a step may count several units, so that a
bar moves once per block, never once per epoch.
"""

import contextlib
import sys

from astropy.utils.console import ProgressBar

__all__ = ["progress_steps", "check_progress", "bar_drawn"]

# Bars being drawn on a terminal now (`bar_drawn`).
_drawn = 0


def bar_drawn():
    """Whether a progress bar is being drawn on standard error now: a message printed
    there meanwhile starts on a new line, not after the bar.

    Examples
    --------
    >>> from astropy_feedrot.core.progress import bar_drawn
    >>> bar_drawn()
    False
    """
    return _drawn > 0


def check_progress(progress):
    """``progress`` if it is one that `progress_steps` takes, else a TypeError.

    Examples
    --------
    >>> from astropy_feedrot.core.progress import check_progress
    >>> check_progress("yes")
    Traceback (most recent call last):
    ...
    TypeError: progress must be True, False or a callable (done, total), got str
    """
    if not (progress is True or progress is False or progress is None or callable(progress)):
        raise TypeError(f"progress must be True, False or a callable (done, total), got "
                        f"{type(progress).__name__}")
    return progress


@contextlib.contextmanager
def progress_steps(progress, total):
    """A function to call after each step of work ``total`` units long, reporting as
    ``progress`` asks.

    Parameters
    ----------
    progress : bool, None or callable
        True: astropy's `~astropy.utils.console.ProgressBar` on standard
        error (silent unless standard error is a terminal); False or None:
        nothing; a callable: called as ``progress(done, total)`` after each
        step, ``done`` counting the units done so far.
    total : int
        The units of work (steps, rows, bytes...).

    Yields
    ------
    callable
        ``step(count=1)``, to call once ``count`` more units are done.

    Raises
    ------
    TypeError
        For any other ``progress``.

    Examples
    --------
    >>> from astropy_feedrot.core.progress import progress_steps
    >>> calls = []
    >>> with progress_steps(lambda done, total: calls.append((done, total)), 5) as step:
    ...     step()
    ...     step(4)
    >>> calls
    [(1, 5), (5, 5)]
    """
    global _drawn
    check_progress(progress)
    if progress is True:
        drawn = int(sys.stderr.isatty())  # astropy's bar is silent elsewhere
        with ProgressBar(total, file=sys.stderr) as bar:
            _drawn += drawn
            try:
                yield _counter(lambda done, total: bar.update(done), total)
            finally:
                _drawn -= drawn
    elif callable(progress):
        yield _counter(progress, total)
    else:
        yield lambda count=1: None


def _counter(report, total):
    """``step(count=1)``: adds ``count`` to the units done and reports them."""
    done = 0

    def step(count=1):
        nonlocal done
        done += count
        report(done, total)
    return step
