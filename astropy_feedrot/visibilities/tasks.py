# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The chunks of a correction grouped into dask tasks.

A dask task costs some milliseconds of the calling process's time and of the
worker's besides its work. A task of up to `TASK_CHUNKS` chunks, read,
corrected and written one after the other, pays that once for all of them,
with no more memory than one chunk. Towards the end of a run the tasks shrink
to one chunk each, so that the workers finish together.
"""

__all__ = ["TASK_CHUNKS", "task_groups"]

TASK_CHUNKS = 4


def task_groups(items, count, workers, key=id):
    """Consecutive items in lists, each list one dask task.

    A list holds at most `TASK_CHUNKS` items, all of one ``key(item)`` (the
    chunks of one table), and fewer as the end nears: a task starting with
    ``left`` items to go takes ``left // (2 * workers)`` of them, at least one.

    Parameters
    ----------
    items : iterable
        The chunks, in order.
    count : int
        How many there are.
    workers : int
        The dask workers.
    key : callable, optional
        Items of different keys are never in one task.

    Yields
    ------
    list
        The items of one task, in order.

    Examples
    --------
    >>> from astropy_feedrot.visibilities.tasks import task_groups
    >>> [len(group) for group in task_groups(range(17), 17, 2, key=lambda item: 0)]
    [4, 3, 2, 2, 1, 1, 1, 1, 1, 1]
    """
    group, size, left = [], 0, count
    for item in items:
        if group and (len(group) >= size or key(item) != key(group[0])):
            yield group
            group = []
        if not group:  # a new task: its size from the items left
            size = max(1, min(TASK_CHUNKS, left // (2 * max(1, workers))))
        group.append(item)
        left -= 1
    if group:
        yield group
