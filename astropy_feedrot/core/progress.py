# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Progress of long corrections, as the caller asks for it.

`~astropy_feedrot.visibilities.correct_uvdata`,
`~astropy_feedrot.visibilities.correct_fitsidi` and
`~astropy_feedrot.visibilities.correct_ms` take ``progress=True`` (astropy's
`~astropy.utils.console.ProgressBar`), ``False`` or a callable
``progress(done, total)``; `progress_steps` turns that into one function to
call after each step.
"""

import contextlib
import sys

from astropy.utils.console import ProgressBar

__all__ = ["progress_steps"]


@contextlib.contextmanager
def progress_steps(progress, total):
    """A function to call after each of ``total`` steps, reporting as ``progress`` asks.

    Parameters
    ----------
    progress : bool, None or callable
        True: astropy's `~astropy.utils.console.ProgressBar` on standard
        output; False or None: nothing; a callable: called as
        ``progress(done, total)`` after each step.
    total : int
        The number of steps.

    Yields
    ------
    callable
        ``step()``, to call once a step is done.

    Raises
    ------
    TypeError
        For any other ``progress``.

    Examples
    --------
    >>> from astropy_feedrot.core.progress import progress_steps
    >>> calls = []
    >>> with progress_steps(lambda done, total: calls.append((done, total)), 2) as step:
    ...     step()
    ...     step()
    >>> calls
    [(1, 2), (2, 2)]
    """
    if progress is True:
        with ProgressBar(total, file=sys.stdout) as bar:
            yield bar.update
    elif callable(progress):
        done = 0

        def step():
            nonlocal done
            done += 1
            progress(done, total)

        yield step
    elif progress is False or progress is None:
        yield lambda: None
    else:
        raise TypeError(f"progress must be True, False or a callable (done, total), got "
                        f"{type(progress).__name__}")
