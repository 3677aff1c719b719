# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""The chunks of a correction grouped into dask tasks.

A dask task costs some milliseconds of the calling process's time and of the
worker's besides its work. A task of up to `TASK_CHUNKS` chunks, read,
corrected and written one after the other, pays that once for all of them,
with no more memory than one chunk. Towards the end of a run the tasks shrink
to one chunk each, so that the workers finish together.
"""

__all__ = ["TASK_CHUNKS", "task_groups", "worker_count", "in_order"]

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


def worker_count(client):
    """The workers of a dask client (at least one).

    Examples
    --------
    >>> from astropy_feedrot.visibilities.tasks import worker_count
    >>> class Client:  # what dask's Client.scheduler_info gives, in part
    ...     def scheduler_info(self):
    ...         return {"workers": {"tcp://a": {}, "tcp://b": {}}}
    >>> worker_count(Client())
    2
    """
    return max(1, len(client.scheduler_info().get("workers", {})))


def in_order(groups, submit, workers, pending):
    """(group, result) of each task in the order of ``groups``, two tasks per worker
    submitted ahead.

    A task stays in ``pending`` until its result is in: a caller stopped while
    it waits finds there every task submitted and not given (a task that has
    started cannot be stopped: it may be waited for).

    Parameters
    ----------
    groups : iterable
        The tasks' items (`task_groups`).
    submit : callable
        ``submit(group)`` gives the task's future.
    workers : int
        The dask workers.
    pending : list
        Filled with the (group, future) submitted and not yet given.

    Yields
    ------
    (group, result)

    Examples
    --------
    >>> from concurrent.futures import ThreadPoolExecutor
    >>> from astropy_feedrot.visibilities.tasks import in_order
    >>> with ThreadPoolExecutor(2) as pool:
    ...     list(in_order([[1, 2], [3]], lambda group: pool.submit(sum, group), 1, []))
    [([1, 2], 3), ([3], 3)]
    """
    groups = iter(groups)
    while True:
        while len(pending) < 2 * workers:
            group = next(groups, None)
            if group is None:
                break
            pending.append((group, submit(group)))
        if not pending:
            return
        group, future = pending[0]
        result = future.result()
        del pending[0]
        yield group, result
