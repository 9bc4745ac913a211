"""Run a compiled kernel over row chunks in threads (the kernels release the GIL).

The tree queries are compiled with ``nogil=True``; large queries are split into one
contiguous chunk per core and run in a small thread pool. This avoids numba's
parallel threading layers, whose worker threads spin after each call: on a 2-core
machine that cost milliseconds per call and slowed the caller's own numpy work.

>>> map_rows(lambda rows: rows.stop - rows.start, 10)
[10]
>>> map_rows(lambda rows: (rows.start, rows.stop), 20, min_rows=5, workers=2)
[(0, 10), (10, 20)]
"""

import os
from concurrent.futures import ThreadPoolExecutor

__all__ = ["MIN_ROWS", "map_rows"]

MIN_ROWS = 4096
"""Queries smaller than this run in the calling thread (thread start-up would dominate)."""

_pools = {}


def _pool(workers):
    if workers not in _pools:
        _pools[workers] = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="blockage")
    return _pools[workers]


def map_rows(function, n_rows, min_rows=MIN_ROWS, workers=None):
    """``[function(rows) for rows in chunks]`` with the chunks run in threads.

    Parameters
    ----------
    function : callable
        Takes a ``slice`` of rows and returns that chunk's result.
    n_rows : int
        Number of rows.
    min_rows : int
        Fewest rows per chunk.
    workers : int, optional
        Threads (default: the number of usable cores).

    Returns
    -------
    results : list
        One result per chunk, in row order.
    """
    if workers is None:
        workers = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    chunks = max(1, min(int(workers), n_rows // max(min_rows, 1)))
    if chunks == 1:
        return [function(slice(0, n_rows))]
    bounds = [n_rows * k // chunks for k in range(chunks + 1)]
    slices = [slice(bounds[k], bounds[k + 1]) for k in range(chunks)]
    return list(_pool(chunks).map(function, slices))
