"""VTK series of a run's surfaces for ParaView, meshio and pyvista: one ``.vtu`` per surface and frame plus a
``.pvd`` collection per surface and one for the whole scene.

The files are VTK XML unstructured grids (``.vtu``, triangles and quads) because meshio reads those and not
``.vtp`` polydata. The surfaces of a run and their arrays are listed in :mod:`cases.results.surfaces`; a leakage
surface alone (:func:`write_vtk_series` of render Frames) carries

- cell data ``blocked_fraction`` (float64): per-face ``A_eb / A_e`` in [0, 1];
- point data ``active`` (uint8): 1 for an active blockage node, else 0;
- point data ``gap`` (float64) [m]: distance to the nearest blocking face, ``NaN`` where the node is beyond
  the detection cutoff (``inf`` in the frame), so that ParaView's colour range stays finite;
- on a contact seat (issue 7), point data ``CPRESS`` (float64) [Pa]: contact pressure of closed nodes, viscous
  damping pressure of open nodes within the damping clearance, else 0; and ``status`` (uint8): 0 open,
  1 closed, 2 VD.

The ``.pvd`` file lists the ``.vtu`` files (relative paths) with their time in seconds, so ParaView's time
slider shows the run's time. Every file is written under a temporary name and renamed into place.

The files are written by :func:`cases.results.vtu.write_vtu` (NumPy only); pyvista is imported by :func:`leak_polydata`
only, for rendering.
"""
from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from cases.results.output import atomic_path
from cases.results.vtu import write_vtu

__all__ = ["frame_arrays", "leak_polydata", "polygon_cells", "write_pvd", "write_vtk_series", "write_surface_series"]


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
    frame : cases.results.render.Frame
        Uses ``leak_vertices (n, 3)``, ``leak_faces (m, 3|4)``, ``blocked_fraction (m,)``,
        ``active_nodes (n,)`` and ``gaps (n,)``.
    """
    import pyvista as pv

    mesh = pv.PolyData(np.asarray(frame.leak_vertices, dtype=np.float64), faces=polygon_cells(frame.leak_faces))
    points, cells = frame_arrays(frame)
    for name, values in points.items():
        mesh.point_data[name] = values
    for name, values in cells.items():
        mesh.cell_data[name] = values
    return mesh


def write_pvd(path, entries):
    """Write a ParaView collection file atomically.

    Parameters
    ----------
    path : path-like
        The ``.pvd`` file.
    entries : iterable of (float, str) or (float, str, int)
        ``(time [s], file name relative to the .pvd's folder[, part])``; parts are the surfaces of one time.
    """
    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    for entry in entries:
        time, name, part = entry if len(entry) == 3 else (*entry, 0)
        lines.append(f'    <DataSet timestep="{float(time)!r}" group="" part="{part}" file={quoteattr(str(name))}/>')
    lines += ["  </Collection>", "</VTKFile>", ""]
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text("\n".join(lines), encoding="utf-8")
    return path


def write_vtk_series(frames, folder, stem="leakage"):
    """Write ``folder/stem_0000.vtu, ...`` (one per frame) and ``folder/stem.pvd`` indexing them by time.

    Parameters
    ----------
    frames : sequence of cases.results.render.Frame
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
        name = f"{stem}_{index:0{width}d}.vtu"
        _save(folder / name, frame.leak_vertices, frame.leak_faces, *frame_arrays(frame), {"time": frame.time})
        entries.append((frame.time, name))
    return write_pvd(folder / f"{stem}.pvd", entries)


def frame_arrays(frame) -> tuple[dict, dict]:
    """(point data, cell data) of a render Frame's leakage surface: the arrays listed in the module docstring."""
    gaps = np.asarray(frame.gaps, dtype=np.float64)
    points = {"active": np.asarray(frame.active_nodes, dtype=bool).astype(np.uint8),
              "gap": np.where(np.isfinite(gaps), gaps, np.nan)}
    if getattr(frame, "cpress", None) is not None:
        points.update(CPRESS=np.asarray(frame.cpress, dtype=np.float64),
                      status=np.asarray(frame.contact_status, dtype=np.uint8))
    return points, {"blocked_fraction": np.asarray(frame.blocked_fraction, dtype=np.float64)}


def _save(path: Path, vertices, faces, point_data, cell_data, field_data) -> None:
    with atomic_path(path) as tmp:
        write_vtu(tmp, vertices, faces, point_data, cell_data, field_data)


def write_surface_series(series, folder, stem="scene") -> list:
    """Write a run's surfaces over time: ``folder/<surface>_0000.vtu, ...``, one ``folder/<surface>.pvd`` each
    and ``folder/<stem>.pvd`` with every surface as a part (open this one in ParaView for the whole scene).

    Parameters
    ----------
    series : sequence of sequence of Surface
        Per time, the surfaces (:func:`cases.results.surfaces.scene_surfaces`), the same names at every time.

    Returns
    -------
    list of pathlib.Path
        The per-surface ``.pvd`` files, then the scene's.
    """
    series = [list(s) for s in series]
    if not series:
        raise ValueError("write_surface_series needs at least one time")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    width = max(4, len(str(len(series) - 1)))
    per_surface, scene = {}, []
    for index, surfaces in enumerate(series):
        for part, surface in enumerate(surfaces):
            name = f"{surface.name}_{index:0{width}d}.vtu"
            _save(folder / name, surface.vertices, surface.faces, surface.point_data, surface.cell_data,
                  surface.field_data)
            t = float(surface.field_data["time"])
            per_surface.setdefault(surface.name, []).append((t, name))
            scene.append((t, name, part))
    paths = [write_pvd(folder / f"{name}.pvd", entries) for name, entries in per_surface.items()]
    return paths + [write_pvd(folder / f"{stem}.pvd", scene)]
