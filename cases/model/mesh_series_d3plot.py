"""Mesh series from an LS-DYNA d3plot: the surface of chosen parts at every state of the run.

The d3plot family (``d3plot``, ``d3plot01``, ...) is read with lasso-python (``pip install 'ventsim[lsdyna]'``).
The parts chosen by their user ids give the surface: their shell elements (a 4-node shell whose third and fourth
nodes coincide is a triangle) and the outer faces of their solid elements (faces that no second solid of the
parts shares). The nodes these faces use keep the d3plot's order; every state's node coordinates (the d3plot
stores the current coordinates) make a frame at the state's time. Lengths and times are converted to SI with the
run's unit system (``[fe_run] units``). Each frame carries the LS-DYNA node ids, so the checks of
:mod:`cases.model.mesh_series_checks` apply as to any series; elements deleted during the run are kept (ventsim's
surfaces have a fixed topology).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from cases.model.mesh_series_io import Frame, SeriesInvalid

__all__ = ["is_d3plot", "read_d3plot", "HEXA_FACES"]

#: The six quad faces of an 8-node solid (LS-DYNA node order), outward for a positive-volume element.
HEXA_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))


def is_d3plot(path) -> bool:
    """A d3plot family's first file: named ``d3plot`` (any case, any prefix folder) or ``*.d3plot``.

    >>> is_d3plot("run/d3plot"), is_d3plot("run/crash.d3plot"), is_d3plot("run/d3plot.pvd")
    (True, True, False)
    """
    name = Path(path).name.lower()
    return name == "d3plot" or name.endswith(".d3plot")


def _load(path: Path):
    try:
        from lasso.dyna import ArrayType, D3plot
    except ImportError:
        raise SeriesInvalid("reading a d3plot needs lasso-python: pip install 'ventsim[lsdyna]' (or "
                            "'lasso-python')") from None
    try:
        return D3plot(str(path)), ArrayType
    except Exception as exc:  # noqa: BLE001 - a damaged or foreign binary: say which and why
        raise SeriesInvalid(f"not a readable d3plot: {exc}") from None


def _solid_faces(solids: np.ndarray) -> np.ndarray:
    """(f, 4) the faces of 8-node solids (degenerate wedges and tetrahedra included) that no other solid shares."""
    faces = solids[:, np.array(HEXA_FACES)].reshape(-1, 4)
    key = np.sort(faces, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    outer = faces[counts[inverse.ravel()] == 1]
    return np.array([f for f in outer if len(set(f.tolist())) >= 3], dtype=np.int64).reshape(-1, 4)


def _as_polygons(faces: np.ndarray) -> np.ndarray:
    """(m, 4) faces with repeated corners dropped: a triangle padded with -1, a quad as it is."""
    out = np.full((len(faces), 4), -1, dtype=np.int64)
    for k, f in enumerate(faces):
        unique = list(dict.fromkeys(f.tolist()))
        out[k, :len(unique)] = unique
    return out


def _part_faces(d3, A, parts) -> np.ndarray:
    """(m, 4) the selected parts' faces in the d3plot's node indices."""
    ids = np.asarray(d3.arrays.get(A.part_ids, np.zeros(0)), dtype=np.int64)
    known = sorted(int(i) for i in ids)
    missing = [p for p in parts if p not in known]
    if missing:
        raise SeriesInvalid(f"part {missing[0]} is not in this d3plot; its parts are {known}")
    wanted = np.flatnonzero(np.isin(ids, parts))
    blocks = []
    shells = d3.arrays.get(A.element_shell_node_indexes)
    if shells is not None and len(shells):
        sel = np.isin(np.asarray(d3.arrays[A.element_shell_part_indexes]), wanted)
        blocks.append(np.asarray(shells, dtype=np.int64)[sel])
    solids = d3.arrays.get(A.element_solid_node_indexes)
    if solids is not None and len(solids):
        sel = np.isin(np.asarray(d3.arrays[A.element_solid_part_indexes]), wanted)
        if sel.any():
            blocks.append(_solid_faces(np.asarray(solids, dtype=np.int64)[sel]))
    faces = np.concatenate(blocks) if blocks else np.zeros((0, 4), np.int64)
    if not len(faces):
        raise SeriesInvalid(f"parts {list(parts)} have no shell or solid elements: no surface to take")
    return _as_polygons(faces)


def read_d3plot(path, parts, units: str = "SI") -> list:
    """The frames (:class:`cases.model.mesh_series_io.Frame`) of the chosen parts of a d3plot, in SI."""
    from cases.decks.units import unit_system

    path = Path(path)
    parts = [int(p) for p in parts]
    if not parts:
        raise SeriesInvalid("a d3plot holds a whole model: name the parts of this surface (parts = [...])")
    d3, A = _load(path)
    faces = _part_faces(d3, A, parts)
    used = np.unique(faces[faces >= 0])
    local = np.full(int(used.max()) + 1, -1, dtype=np.int64)
    local[used] = np.arange(len(used))
    faces = np.where(faces >= 0, local[np.maximum(faces, 0)], -1)
    if np.all(faces[:, 3] < 0):
        faces = faces[:, :3]
    system = unit_system(units)
    times = np.asarray(d3.arrays[A.global_timesteps], dtype=float) * system.factor("time")
    coords = np.asarray(d3.arrays.get(A.node_displacement), dtype=float)
    if coords.ndim != 3 or len(coords) != len(times):
        raise SeriesInvalid(f"the d3plot has {len(times)} states but no node coordinates for them")
    ids = np.asarray(d3.arrays.get(A.node_ids, np.arange(1, coords.shape[1] + 1)), dtype=np.int64)[used]
    name = f"{path.name} parts {parts}"
    return [Frame(float(t), coords[k, used] * system.factor("length"), faces, {"node_id": ids}, name)
            for k, t in enumerate(times)]
