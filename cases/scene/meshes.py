"""Checks of the mesh files a scene names, before anything is built from them: readable, with faces, finite
coordinates, within ``limits.mesh_faces``; a cavity mesh made of closed shells each of positive volume and
joined to no other shell at a single vertex (a bowtie); and a warning when the size is implausible for metres.

A mesh is loaded once per (file, modification time) for these checks.
"""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

from cavity.caution import caution

from cases.scene.errors import SceneError

__all__ = ["check_meshes", "mesh_facts", "MILLIMETRE_VOLUME", "MILLIMETRE_EXTENT"]

#: A cavity larger than this [m^3], or any mesh wider than MILLIMETRE_EXTENT [m], is probably not in metres.
MILLIMETRE_VOLUME = 100.0
MILLIMETRE_EXTENT = 50.0


@lru_cache(maxsize=64)
def _facts(path: str, mtime_ns: int, size: int) -> dict:
    """Faces, coordinates, shells and volumes of mesh file ``path`` (as trimesh reads it, vertices merged)."""
    import trimesh

    try:
        mesh = trimesh.load(path, force="mesh", process=False)
    except Exception as exc:  # trimesh raises many types for unreadable files
        return {"error": f"cannot read mesh: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}"}
    faces = np.asarray(getattr(mesh, "faces", np.empty((0, 3))), dtype=np.int64).reshape(-1, 3)
    vertices = np.asarray(getattr(mesh, "vertices", np.empty((0, 3))), dtype=float).reshape(-1, 3)
    facts = {"faces": len(faces), "error": None}
    if not len(faces):
        return facts
    wrong = np.flatnonzero(np.any((faces < 0) | (faces >= len(vertices)), axis=1))
    if wrong.size:
        k = int(wrong[0])
        return {**facts, "error": f"face {k} indexes vertices {faces[k].tolist()} but the mesh has {len(vertices)} "
                                  f"vertices (0 to {len(vertices) - 1}): the file is corrupt or truncated"}
    bad = np.flatnonzero(~np.all(np.isfinite(vertices), axis=1))
    if bad.size:
        facts["nonfinite"] = int(bad[0])
        return facts
    mesh.merge_vertices()  # as trimesh.load(process=True) does, so that shells are told by shared vertices
    faces, vertices = np.asarray(mesh.faces, dtype=np.int64), np.asarray(mesh.vertices, dtype=float)
    used = vertices[faces.ravel()]
    facts["extent"] = float(np.linalg.norm(np.ptp(used, axis=0)))
    facts["box"] = (used.min(axis=0).tolist(), used.max(axis=0).tolist())
    labels = trimesh.graph.connected_component_labels(mesh.face_adjacency, node_count=len(faces))
    shells = int(labels.max()) + 1
    pairs = np.unique(faces.ravel() * shells + np.repeat(labels, 3))  # (vertex, shell) pairs, each once
    shared = np.flatnonzero(np.bincount(pairs // shells) > 1)
    facts["bowtie"] = int(shared[0]) if shared.size else None
    tri = vertices[faces]
    signed = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])) / 6.0
    facts["shell_volumes"] = np.bincount(labels, weights=signed).tolist()
    facts["volume"] = float(signed.sum())
    facts["area"] = float(0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1).sum())
    return facts


def mesh_facts(path: Path) -> dict:
    """The facts of a mesh file (cached while the file is unchanged)."""
    st = Path(path).stat()
    return _facts(str(path), st.st_mtime_ns, st.st_size)


#: Mesh series (.pvd, .xdmf, .npz) are checked frame by frame by cases.model.mesh_series_checks, not here.
SERIES_SUFFIXES = (".pvd", ".xdmf", ".xmf", ".npz")


def _mesh_files(scene):
    """(key, file name, is a cavity) of every single mesh file the scene names."""
    for kind, key, closed in (("cavity", "mesh", True), ("body", "mesh", False),
                              ("exchange", "leakage_surface", False), ("contact", "seat_mesh", False)):
        for i, item in enumerate(getattr(scene, kind)):
            name = getattr(item, key)
            if name and not str(name).lower().endswith(SERIES_SUFFIXES) and not _d3plot(name):
                yield f"{kind}[{i}].{key}", name, closed


def _d3plot(name) -> bool:
    """An LS-DYNA d3plot (a mesh series checked by cases.model.mesh_series_d3plot)."""
    from cases.model.mesh_series_d3plot import is_d3plot

    return is_d3plot(name)


def check_meshes(scene, path) -> None:
    """Every mesh of ``scene``: SceneError on a mesh that cannot be used, a warning on implausible units."""
    for where, name, closed in _mesh_files(scene):
        file = scene.base / name
        if file.is_dir():
            raise SceneError(path, where, f"{name!r} is a directory, not a mesh file")
        if not file.is_file():
            raise SceneError(path, where, f"file {name!r} does not exist")
        f = mesh_facts(file)
        if f["error"]:
            raise SceneError(path, where, f"{name!r}: {f['error']}")
        if not f["faces"]:
            raise SceneError(path, where, f"{name!r} has no faces")
        if f["faces"] > scene.limits.mesh_faces:
            raise SceneError(path, where, f"{name!r} has {f['faces']} faces, more than limits.mesh_faces = "
                                          f"{scene.limits.mesh_faces}")
        if "nonfinite" in f:
            raise SceneError(path, where, f"{name!r}: vertex {f['nonfinite']} has a non-finite coordinate")
        if closed:
            _check_shells(f, path, where, name)
            _check_wrapping(scene, f, path, where)
        _check_units(f, where, name, closed)


def _check_shells(f: dict, path, where: str, name: str) -> None:
    if f["bowtie"] is not None:
        raise SceneError(path, where, f"{name!r}: vertex {f['bowtie']} joins two shells at a single point (a "
                                      "bowtie): separate them or merge them along an edge")
    vols = f["shell_volumes"]
    for k, v in enumerate(vols):
        if v < 0 and len(vols) > 1:
            raise SceneError(path, where, f"{name!r}: shell {k + 1} of {len(vols)} encloses {v:.3g} m^3: its "
                                          "normals point inwards (inside out); flip it")


def _check_wrapping(scene, f: dict, path, where: str) -> None:
    """A sphere or box body that wraps the cavity must not enclose all of its mesh at t = 0 (every node would be
    placed on the body: no volume is left)."""
    i = int(where.split("[")[1].split("]")[0])
    lo, hi = (np.asarray(v) for v in f["box"])
    corners = np.array([[(lo, hi)[k >> d & 1][d] for d in range(3)] for k in range(8)])
    for b in scene.body:
        if b.name not in scene.cavity[i].wrapped_by:
            continue
        if b.sphere:
            inside = np.all(np.linalg.norm(corners - np.asarray(b.sphere[:3]), axis=1) <= b.sphere[3])
        elif b.box:
            c, half = np.asarray(b.box[:3]), 0.5 * np.asarray(b.box[3:])
            inside = np.all(np.abs(corners - c) <= half)
        else:
            continue
        if inside:
            raise SceneError(path, where, f"body {b.name!r}, which the cavity wraps, encloses its whole mesh at t = 0: "
                                          "no volume would be left (check the body's size and position)")


def _check_units(f: dict, where: str, name: str, closed: bool) -> None:
    volume, extent = abs(f.get("volume", 0.0)), f.get("extent", 0.0)
    if (closed and volume > MILLIMETRE_VOLUME) or extent > MILLIMETRE_EXTENT:
        size = f"encloses {volume:.6g} m^3, " if closed else ""
        caution(f"{where}: {name!r} {size}spans {extent:.6g} m: coordinates look like millimetres (x 1e-3: "
                f"{extent * 1e-3:.3g} m); a mesh must be in the scene's units: set [units] system = 'mm-t-s' or "
                "'mm-kg-ms', or scale the mesh by 1e-3")
