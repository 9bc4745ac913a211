"""Write a mesh series (for tests, and for users converting their output): ParaView .pvd, XDMF, .npz.

All three keep float64 coordinates and times exactly, so reading a written series back gives identical arrays.

- :func:`write_pvd`: a ParaView collection ``name.pvd`` and one frame file per time in the folder ``name/``:
  ``.vtp`` PolyData written with pyvista (VTK), or ``.vtu`` unstructured grids written with meshio.
- :func:`write_xdmf`: an XDMF 3 temporal collection, data inline as text (17 significant digits, no HDF5
  needed): every step has its own <Geometry>; the <Topology> is in the first step and included by the others.
- :func:`write_npz`: arrays ``times``, ``vertices``, ``faces``.

``point_data`` maps a name to a (k, n) or (k, n, c) array: frame i gets ``array[i]`` (e.g. node ids).
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

__all__ = ["write_pvd", "write_xdmf", "write_npz"]

XDMF_CELL = {3: ("Triangle", 4), 4: ("Quadrilateral", 5)}  # XDMF topology name, and its code in a Mixed topology


def _arrays(times, vertices, faces):
    times, vertices, faces = np.asarray(times, float), np.asarray(vertices, float), np.asarray(faces, np.int64)
    if times.ndim != 1 or vertices.shape != (len(times),) + vertices.shape[1:2] + (3,) or faces.ndim != 2 \
            or faces.shape[1] not in (3, 4):
        raise ValueError(f"expected times (k,), vertices (k, n, 3), faces (m, 3|4); got {times.shape}, "
                         f"{vertices.shape}, {faces.shape}")
    return times, vertices, faces


def _runs(faces):
    """Faces as meshio cell blocks, one per run of equal sizes (the order of the faces is kept)."""
    sizes = (faces >= 0).sum(axis=1)
    cuts = np.flatnonzero(np.diff(sizes)) + 1
    return [({3: "triangle", 4: "quad"}[int(sizes[lo])], faces[lo:hi, :sizes[lo]])
            for lo, hi in zip(np.r_[0, cuts], np.r_[cuts, len(sizes)]) if hi > lo]


def _frame_data(point_data, i):
    return {name: np.asarray(values)[i] for name, values in (point_data or {}).items()}


def write_pvd(path, times, vertices, faces, *, frame_format: str = "vtp", point_data=None) -> list:
    """Write ``path`` (.pvd) and its frames ``<stem>/<stem>_0000.<frame_format>``; return the frame paths.

    ``frame_format`` is "vtp" (pyvista.PolyData) or "vtu" (meshio).
    """
    times, vertices, faces = _arrays(times, vertices, faces)
    if frame_format not in ("vtp", "vtu"):
        raise ValueError(f"frame_format must be 'vtp' or 'vtu', got {frame_format!r}")
    path = Path(path)
    folder = path.parent / path.stem
    folder.mkdir(parents=True, exist_ok=True)
    files = [folder / f"{path.stem}_{i:04d}.{frame_format}" for i in range(len(times))]
    if frame_format == "vtp":
        import pyvista

        sizes = (faces >= 0).sum(axis=1)
        flat = np.column_stack([sizes, faces]).ravel()
        flat = flat[flat >= 0]
        for i, file in enumerate(files):
            mesh = pyvista.PolyData(vertices[i], faces=flat)
            for name, values in _frame_data(point_data, i).items():
                mesh.point_data[name] = values
            mesh.save(file, binary=True)
    else:
        import meshio

        cells = _runs(faces)
        for i, file in enumerate(files):
            meshio.write_points_cells(file, vertices[i], cells, point_data=_frame_data(point_data, i))
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    collection = ET.SubElement(root, "Collection")
    for t, file in zip(times, files):
        ET.SubElement(collection, "DataSet", timestep=repr(float(t)), group="", part="0",
                      file=file.relative_to(path.parent).as_posix())
    _write_xml(root, path)
    return files


def _write_xml(root, path) -> None:
    ET.indent(root)
    ET.ElementTree(root).write(path, encoding="utf-8", xml_declaration=True)


def _data_item(parent, values) -> None:
    a = np.asarray(values)
    number = ("Int", "8") if np.issubdtype(a.dtype, np.integer) else ("Float", "8")
    item = ET.SubElement(parent, "DataItem", Dimensions=" ".join(map(str, a.shape)), NumberType=number[0],
                         Precision=number[1], Format="XML")
    flat = a.astype(np.int64 if number[0] == "Int" else float).ravel().tolist()
    item.text = " ".join(map(repr, flat))


def _topology(grid, faces) -> None:
    sizes = (faces >= 0).sum(axis=1)
    if len(set(sizes.tolist())) <= 1:
        k = int(sizes[0]) if len(sizes) else faces.shape[1]
        topology = ET.SubElement(grid, "Topology", TopologyType=XDMF_CELL[k][0], NumberOfElements=str(len(faces)))
        _data_item(topology, faces[:, :k])
        return
    flat = np.column_stack([np.where(sizes == 3, XDMF_CELL[3][1], XDMF_CELL[4][1]), faces]).ravel()
    topology = ET.SubElement(grid, "Topology", TopologyType="Mixed", NumberOfElements=str(len(faces)))
    _data_item(topology, flat[flat >= 0])


def write_xdmf(path, times, vertices, faces, *, point_data=None) -> Path:
    """Write an XDMF 3 temporal collection of the frames to ``path`` (.xdmf); return the path."""
    times, vertices, faces = _arrays(times, vertices, faces)
    path = Path(path)
    root = ET.Element("Xdmf", {"Version": "3.0", "xmlns:xi": "http://www.w3.org/2001/XInclude"})
    collection = ET.SubElement(ET.SubElement(root, "Domain"), "Grid", Name="mesh_series", GridType="Collection",
                               CollectionType="Temporal")
    for i, t in enumerate(times):
        grid = ET.SubElement(collection, "Grid", Name=f"frame_{i}", GridType="Uniform")
        ET.SubElement(grid, "Time", Value=repr(float(t)))
        if i == 0:
            _topology(grid, faces)
        else:
            ET.SubElement(grid, "xi:include", xpointer="xpointer(//Grid[@Name='frame_0']/Topology)")
        _data_item(ET.SubElement(grid, "Geometry", GeometryType="XYZ"), vertices[i])
        for name, values in _frame_data(point_data, i).items():
            kind = "Scalar" if values.ndim == 1 else "Vector"
            _data_item(ET.SubElement(grid, "Attribute", Name=name, AttributeType=kind, Center="Node"), values)
    _write_xml(root, path)
    return path


def write_npz(path, times, vertices, faces) -> Path:
    """Write arrays ``times`` (k,) [s], ``vertices`` (k, n, 3) [m] and ``faces`` (m, 3|4) to ``path``."""
    times, vertices, faces = _arrays(times, vertices, faces)
    path = Path(path)
    np.savez(path, times=times, vertices=vertices, faces=faces)
    return path
