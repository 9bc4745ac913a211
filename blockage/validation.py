"""Input checks: every public entry point converts its arguments here.

Each function returns a clean float64/int64 array (or float) or raises a
``ValueError`` that names the argument and says what was expected.

>>> as_points([[0, 0, 0]]).dtype
dtype('float64')
>>> as_points([[0.0, float("nan"), 0.0]])
Traceback (most recent call last):
...
ValueError: points must be finite; found NaN or inf in 1 row(s), first at row 0
>>> as_tolerance(-1.0)
Traceback (most recent call last):
...
ValueError: tolerance must be a finite number >= 0 [m], got -1.0
"""

import numpy as np

from blockage.tolerance import TOL

__all__ = ["as_cutoff", "as_faces", "as_indices", "as_points", "as_tolerance", "as_transform"]


def as_points(points, name="points", copy=False):
    """``points`` as a finite (n, 3) float64 array (n may be 0); ``copy`` never shares memory."""
    try:
        array = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must be an (n, 3) array of numbers: {error}") from None
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"{name} must have shape (n, 3), got {array.shape}")
    if not np.isfinite(array).all():
        bad = ~np.isfinite(array).all(axis=1)
        raise ValueError(f"{name} must be finite; found NaN or inf in {int(bad.sum())} row(s), "
                         f"first at row {int(np.flatnonzero(bad)[0])}")
    return np.array(array, order="C", copy=True) if copy else np.ascontiguousarray(array)


def as_tolerance(value, name="tolerance"):
    """``value`` as a float >= 0 (a contact tolerance in metres)."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a finite number >= 0 [m], got {value!r}") from None
    if not np.isfinite(number) or number < 0.0:
        raise ValueError(f"{name} must be a finite number >= 0 [m], got {value!r}")
    return number


def as_cutoff(value, name="cutoff"):
    """``value`` as a float >= 0 or ``inf`` (a search radius in metres)."""
    number = np.inf if value is None else value
    try:
        number = float(number)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number >= 0 [m] or inf, got {value!r}") from None
    if np.isnan(number) or number < 0.0:
        raise ValueError(f"{name} must be a number >= 0 [m] or inf, got {value!r}")
    return number


def as_indices(indices, upper, name="face indices"):
    """``indices`` as an int64 array with every entry in ``[0, upper)``."""
    array = np.asarray(indices)
    if array.size == 0:
        return np.zeros(array.shape, dtype=np.int64)
    if not np.issubdtype(array.dtype, np.integer):
        if np.issubdtype(array.dtype, np.bool_):
            raise ValueError(f"{name} must be integers, got booleans (use np.flatnonzero)")
        rounded = np.asarray(array, dtype=np.float64)
        if not np.all(np.isfinite(rounded)) or np.any(rounded != np.round(rounded)):
            raise ValueError(f"{name} must be integers, got {array.dtype}")
    array = array.astype(np.int64)
    out = (array < 0) | (array >= upper)
    if out.any():
        raise ValueError(f"{name} must lie in [0, {upper}); found {int(array[out][0])} "
                         f"({int(out.sum())} out of range)")
    return array


def as_faces(faces, n_vertices, sizes=(3, 4), name="faces"):
    """``faces`` as an (m, k) int64 array with k in ``sizes`` and valid vertex ids."""
    array = np.asarray(faces)
    if array.ndim != 2 or array.shape[1] not in sizes:
        raise ValueError(f"{name} must have shape (m, k) with k in {sizes}, got {array.shape}")
    return as_indices(array, n_vertices, name=f"{name} (vertex indices)")


def as_transform(matrix, name="transform"):
    """``matrix`` as a 4x4 float64 rigid transform ``[[R, t], [0, 1]]`` (R orthogonal)."""
    array = np.asarray(matrix, dtype=np.float64)
    if array.shape != (4, 4) or not np.isfinite(array).all():
        raise ValueError(f"{name} must be a finite 4x4 homogeneous matrix, got shape {array.shape}")
    rotation = array[:3, :3]
    error = max(np.abs(rotation.T @ rotation - np.eye(3)).max(), np.abs(array[3] - [0, 0, 0, 1]).max())
    if error > TOL.rigid_rel:
        raise ValueError(f"{name} must be rigid (orthogonal rotation, last row 0 0 0 1); "
                         f"deviation {error:.3g} > {TOL.rigid_rel:g}")
    return array
