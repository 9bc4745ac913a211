"""VTK series of a run's leakage surface for ParaView: one ``.vtp`` per frame plus a ``.pvd`` collection.

Each ``.vtp`` is the leakage surface at that time (polygons: triangles and quads) with

- cell data ``blocked_fraction`` (float64): per-face ``A_eb / A_e`` in [0, 1];
- point data ``active`` (uint8): 1 for an active blockage node, else 0;
- point data ``gap`` (float64) [m]: distance to the nearest blocking face minus the contact tolerance,
  ``NaN`` where the node is beyond the detection cutoff (``inf`` in the frame), so that ParaView's colour
  range stays finite;
- on a contact seat (issue 7), point data ``CPRESS`` (float64) [Pa]: contact pressure of closed nodes, viscous
  damping pressure of open nodes within the damping clearance, else 0; and ``status`` (uint8): 0 open,
  1 closed, 2 VD (the names are in the field data ``status_names``).

The ``.pvd`` file lists the ``.vtp`` files (relative paths) with their time in seconds, so ParaView's time
slider shows the run's time. Every file is written under a temporary name and renamed into place.

pyvista is imported inside the functions only (rendering and VTK output are optional parts of ventsim).
"""
from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from cases.output import atomic_path

__all__ = ["leak_polydata", "polygon_cells", "write_pvd", "write_vtk_series"]


def polygon_cells(faces):
    """VTK's flat cell array ``[n0, i, j, k, n1, ...]`` for (m, 3|4) faces padded with -1.

    Parameters
    ----------
    faces : (m, 3) or (m, 4) int
        Triangles and quads; a triangle in a 4-column array has ``-1`` in its last column.

    Returns
    -------
    cells : (m + sum of sizes,) int64

    >>> polygon_cells(np.array([[0, 1, 2, 3], [1, 4, 2, -1]])).tolist()
    [4, 0, 1, 2, 3, 3, 1, 4, 2]
    """
    faces = np.asarray(faces, dtype=np.int64)
    if faces.ndim != 2 or faces.shape[1] not in (3, 4):
        raise ValueError(f"faces must have shape (m, 3) or (m, 4), got {faces.shape}")
    valid = faces >= 0
    sizes = valid.sum(axis=1)
    if (sizes < 3).any():
        raise ValueError("every face needs at least 3 vertices (only the 4th column may be -1)")
    rows = np.concatenate([sizes[:, None], faces], axis=1)
    keep = np.concatenate([np.ones((len(faces), 1), dtype=bool), valid], axis=1)
    return rows[keep]


def leak_polydata(frame):
    """The frame's leakage surface as a ``pyvista.PolyData`` with the arrays listed in the module docstring.

    Parameters
    ----------
    frame : cases.render.Frame
        Uses ``leak_vertices (n, 3)``, ``leak_faces (m, 3|4)``, ``blocked_fraction (m,)``,
        ``active_nodes (n,)`` and ``gaps (n,)``.
    """
    import pyvista as pv

    vertices = np.asarray(frame.leak_vertices, dtype=np.float64)
    mesh = pv.PolyData(vertices, faces=polygon_cells(frame.leak_faces))
    mesh.cell_data["blocked_fraction"] = np.asarray(frame.blocked_fraction, dtype=np.float64)
    mesh.point_data["active"] = np.asarray(frame.active_nodes, dtype=bool).astype(np.uint8)
    gaps = np.asarray(frame.gaps, dtype=np.float64)
    mesh.point_data["gap"] = np.where(np.isfinite(gaps), gaps, np.nan)
    if getattr(frame, "cpress", None) is not None:
        mesh.point_data["CPRESS"] = np.asarray(frame.cpress, dtype=np.float64)
        mesh.point_data["status"] = np.asarray(frame.contact_status, dtype=np.uint8)
        mesh.field_data["status_names"] = np.array(["open", "closed", "VD"])
    return mesh


def write_pvd(path, entries):
    """Write a ParaView collection file atomically.

    Parameters
    ----------
    path : path-like
        The ``.pvd`` file.
    entries : iterable of (float, str)
        ``(time [s], file name relative to the .pvd's folder)``.
    """
    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    for time, name in entries:
        lines.append(f'    <DataSet timestep="{float(time)!r}" group="" part="0" file={quoteattr(str(name))}/>')
    lines += ["  </Collection>", "</VTKFile>", ""]
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text("\n".join(lines), encoding="utf-8")
    return path


def write_vtk_series(frames, folder, stem="leakage"):
    """Write ``folder/stem_0000.vtp, ...`` (one per frame) and ``folder/stem.pvd`` indexing them by time.

    Parameters
    ----------
    frames : sequence of cases.render.Frame
        In time order.
    folder : path-like
        Created if missing.
    stem : str
        File-name stem.

    Returns
    -------
    pathlib.Path
        The ``.pvd`` file (open it in ParaView: File > Open, then Apply; the time slider steps the frames).
    """
    frames = list(frames)
    if not frames:
        raise ValueError("write_vtk_series needs at least one frame")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    width = max(4, len(str(len(frames) - 1)))
    entries = []
    for index, frame in enumerate(frames):
        name = f"{stem}_{index:0{width}d}.vtp"
        with atomic_path(folder / name) as tmp:
            leak_polydata(frame).save(tmp, binary=True)
        entries.append((frame.time, name))
    return write_pvd(folder / f"{stem}.pvd", entries)
