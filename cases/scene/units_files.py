"""Converted copies of the series and node files of a scene written in another unit system than SI
(:mod:`cases.scene.units`): a mesh series or vertex trajectory (.pvd, .xdmf/.xmf, .npz) with its times multiplied by
the system's unit of time and its coordinates by its unit of length, and a node CSV (x, y, z[, area]) with its
coordinates by the unit of length and its areas by its square. A copy keeps its format (and a .pvd's or .xdmf's
point-id arrays, which vouch for the node order), so reading it gives what reading an SI file would.

>>> import tempfile
>>> from cases.scene.unit_systems import unit_system
>>> folder = Path(tempfile.mkdtemp())
>>> _ = (folder / "n.csv").write_text("x,y,z,area\\n1000,0,5,2\\n")
>>> np.loadtxt(scaled_nodes(folder / "n.csv", folder / "si.csv", unit_system("mm-t-s"), "s.toml", "k"),
...            delimiter=",").tolist()
[1.0, 0.0, 0.005, 2e-06]
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from cases.scene.errors import SceneError

__all__ = ["scaled_series", "scaled_nodes"]


def scaled_series(source: Path, target: Path, system, path, where: str) -> Path:
    """Write the mesh series ``source`` in ``system`` as an SI copy ``target`` of the same format; return it.

    Times [system's time unit] become seconds, coordinates [its length unit] metres. A file that cannot be read is
    a SceneError naming the scene file ``path``, the key ``where`` and the file, as reading it in SI would be.
    """
    from cases.model.mesh_series_io import SeriesInvalid

    if not source.is_file():
        raise SceneError(path, where, f"file {str(source)!r} does not exist")
    try:
        if source.suffix.lower() == ".npz":
            return _scaled_npz(source, target, system)
        return _scaled_frames(source, target, system)
    except SeriesInvalid as exc:
        raise SceneError(path, where, f"{source}: {exc}") from None


def _scaled_npz(source: Path, target: Path, system) -> Path:
    """An .npz with every array kept and ``times`` and ``vertices`` scaled (faces are node indices)."""
    from cases.model.mesh_series_io import SeriesInvalid

    try:
        with np.load(source) as data:
            arrays = {name: data[name] for name in data.files}
    except (OSError, ValueError) as exc:
        raise SeriesInvalid(f"cannot read the .npz: {exc}") from None
    for name, factor in (("times", system.time), ("vertices", system.length)):
        if name in arrays and np.issubdtype(arrays[name].dtype, np.number):
            arrays[name] = np.asarray(arrays[name], dtype=float) * factor
    np.savez(target, **arrays)
    return target


def _scaled_frames(source: Path, target: Path, system) -> Path:
    """A .pvd or XDMF series read frame by frame, checked as a series, and written scaled in its own format."""
    from cases.model.mesh_series_checks import check_frames
    from cases.model.mesh_series_io import read_pvd, read_xdmf
    from cases.model.mesh_series_write import write_pvd, write_xdmf

    pvd = source.suffix.lower() == ".pvd"
    frames = read_pvd(source) if pvd else read_xdmf(source)
    check_frames(frames)  # a problem named in the user's file, before it is copied
    times = np.array([f.time for f in frames]) * system.time
    vertices = np.stack([f.points for f in frames]) * system.length
    names = [n for n in frames[0].ids if all(n in f.ids for f in frames)]
    ids = {n: np.stack([f.ids[n] for f in frames]) for n in names}
    if pvd:
        write_pvd(target, times, vertices, frames[0].faces, point_data=ids)
    else:
        write_xdmf(target, times, vertices, frames[0].faces, point_data=ids)
    return target


def scaled_nodes(source: Path, target: Path, system, path, where: str) -> Path:
    """Write the node CSV ``source`` (rows x, y, z [length unit] and optionally area [length unit²]; a header row
    and ``#`` comments allowed) as an SI copy ``target``; return it."""
    name = source.name
    if not source.is_file():
        raise SceneError(path, where, f"file {str(source)!r} does not exist")
    try:
        rows = np.genfromtxt(source, delimiter=",", comments="#", dtype=float)
    except (OSError, ValueError) as exc:
        raise SceneError(path, where, f"cannot read {name!r}: {exc}") from None
    rows = np.atleast_2d(rows)
    if rows.shape[0] and not np.all(np.isfinite(rows[0])):
        rows = rows[1:]  # a header row
    if rows.ndim != 2 or rows.shape[1] not in (3, 4) or not len(rows) or not np.all(np.isfinite(rows)):
        raise SceneError(path, where, f"{name!r}: expected rows of x, y, z [length] and optionally area "
                                      "[length^2], all finite numbers")
    factors = np.array([system.length] * 3 + [system.length ** 2])[:rows.shape[1]]
    np.savetxt(target, rows * factors, delimiter=",", fmt="%.17g")
    return target
