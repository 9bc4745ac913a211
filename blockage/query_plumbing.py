"""Query plumbing shared by the blocker's face and edge searches: Morton ordering, exclusions, rigid frames."""

import numpy as np

from blockage import broadphase
from blockage.parallel import map_rows

__all__ = ["exclusions", "ordered_query", "to_local", "to_world"]

SORT_MIN = 2048
"""Queries of at least this many points are sorted in Morton order first."""


def ordered_query(run, queries, exclude, width, centers=None):
    """``run(queries, exclude)`` in Morton order and in threads, rows returned in input order.

    Queries of at least ``SORT_MIN`` rows are sorted by the Morton code of
    ``centers`` (default: the queries) so that neighbours share tree paths, then
    split into one chunk per core (:func:`blockage.parallel.map_rows`).
    """
    n = len(queries)
    if n < SORT_MIN:
        return run(np.ascontiguousarray(queries), np.ascontiguousarray(exclude))
    order = np.argsort(broadphase.morton_codes(queries if centers is None else centers), kind="stable")
    ordered, ids = np.ascontiguousarray(queries[order]), np.ascontiguousarray(exclude[order])
    raw = np.empty((n, width))
    raw[order] = np.concatenate(map_rows(lambda rows: run(ordered[rows], ids[rows]), n))
    return raw


def exclusions(exclude, n, width):
    """Exclusion ids as an (n, width) int64 array (-1 everywhere when None)."""
    if exclude is None:
        return np.full((n, width), -1, np.int64)
    array = np.asarray(exclude, dtype=np.int64).reshape(-1, width) if np.size(exclude) else np.zeros((0, width),
                                                                                                      np.int64)
    if array.shape != (n, width):
        raise ValueError(f"exclude_vertices must have {n} x {width} entries, got {np.shape(exclude)}")
    return np.ascontiguousarray(array)


def to_local(points, matrix):
    """Apply the inverse of a rigid transform: ``R^T (p - t)``."""
    return np.ascontiguousarray((points - matrix[:3, 3]) @ matrix[:3, :3])


def to_world(points, matrix):
    """Apply a rigid transform: ``R p + t``."""
    return points @ matrix[:3, :3].T + matrix[:3, 3]
