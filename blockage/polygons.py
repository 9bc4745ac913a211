"""Faces of a leakage surface as one padded array: triangles and quads, mixed or not."""

import numpy as np

from blockage.validation import as_faces

__all__ = ["polygons"]


def polygons(faces, n_vertices):
    """Faces as an (m, k) int64 array padded with -1, and the size of each face."""
    if not isinstance(faces, np.ndarray):
        rows = [list(face) for face in faces]
        if len({len(row) for row in rows}) > 1:
            return _mixedpolygons(rows, n_vertices)
        faces = np.asarray(rows) if rows else np.zeros((0, 3), np.int64)
    array = np.asarray(faces)
    if array.ndim != 2 or array.shape[1] not in (3, 4):
        raise ValueError(f"faces must have shape (m, 3) or (m, 4), or be a list of 3- and 4-node faces; "
                         f"got shape {array.shape}")
    if array.shape[1] == 4 and array.size and np.issubdtype(array.dtype, np.integer) and (array[:, 3] < 0).any():
        return _mixedpolygons([list(row[:3]) if row[3] < 0 else list(row) for row in array], n_vertices)
    array = as_faces(array, n_vertices)
    return array, np.full(len(array), array.shape[1], dtype=np.int64)


def _mixedpolygons(rows, n_vertices):
    """Mixed triangles and quads as an (m, 4) array padded with -1."""
    bad = [len(row) for row in rows if len(row) not in (3, 4)]
    if bad:
        raise ValueError(f"faces must have 3 or 4 vertices each, found a face with {bad[0]}")
    sizes = np.array([len(row) for row in rows], dtype=np.int64)
    padded = as_faces(np.array([row + row[:1] * (4 - len(row)) for row in rows]).reshape(-1, 4), n_vertices)
    return np.where(np.arange(4)[None, :] < sizes[:, None], padded, -1), sizes
