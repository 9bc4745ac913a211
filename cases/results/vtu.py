"""A VTK XML unstructured-grid file (``.vtu``) of a polygon surface, written with NumPy alone.

The format (VTK file formats, "Serial XML formats", UnstructuredGrid): XML whose ``DataArray`` elements hold their
values inline as ``format="binary"``: base64 of the block's size in bytes (UInt64) followed by the little-endian
values (meshio reads this form; it does not read raw appended data). Cells
are VTK_TRIANGLE (5) and VTK_QUAD (9). ParaView, pyvista (``pyvista.read``) and meshio (``meshio.read``) read it;
writing it this way needs no VTK import and costs about a millisecond for the airbag scene's surfaces.
"""
from __future__ import annotations

import base64
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

__all__ = ["write_vtu", "VTK_TYPES"]

VTK_TYPES = {np.dtype("float64"): "Float64", np.dtype("float32"): "Float32", np.dtype("int64"): "Int64",
             np.dtype("int32"): "Int32", np.dtype("uint8"): "UInt8", np.dtype("int8"): "Int8"}


def _cells(faces) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(connectivity, offsets, types) of (m, 3|4) faces, -1 padded."""
    faces = np.asarray(faces, dtype=np.int64)
    valid = faces >= 0
    sizes = valid.sum(axis=1)
    if (sizes < 3).any() or (sizes > 4).any():
        raise ValueError("every face needs 3 or 4 vertices (only the 4th column may be -1)")
    return faces[valid], np.cumsum(sizes).astype(np.int64), np.where(sizes == 3, 5, 9).astype(np.uint8)


def _array(name, values, field: bool = False) -> str:
    """One ``DataArray`` element with its values inline (base64 of size and data)."""
    values = np.asarray(values)
    if values.dtype == bool:
        values = values.astype(np.uint8)
    if values.dtype not in VTK_TYPES:
        values = values.astype(np.float64)
    kind = VTK_TYPES[values.dtype]
    data = np.ascontiguousarray(values, dtype=values.dtype.newbyteorder("<")).tobytes()
    text = base64.b64encode(np.array(len(data), dtype="<u8").tobytes() + data).decode()
    components = "" if values.ndim == 1 else f' NumberOfComponents="{values.shape[1]}"'  # VTK's default: 1
    return (f'<DataArray type="{kind}"' + (f" Name={quoteattr(name)}" if name else "") + components
            + (f' NumberOfTuples="{len(values)}"' if field else "")
            + f' format="binary">{text}</DataArray>')


def write_vtu(path, vertices, faces, point_data=None, cell_data=None, field_data=None) -> Path:
    """Write a surface with its data as a ``.vtu`` file.

    Parameters
    ----------
    path : path-like
        The file (written as given; wrap in :func:`cases.results.output.atomic_path` for an atomic write).
    vertices : (n, 3) float
        [m]
    faces : (m, 3) or (m, 4) int
        Triangles and quads, -1 padded.
    point_data, cell_data : dict of str -> (n,) / (m,) or (n, k) / (m, k) arrays
    field_data : dict of str -> float or 1-D array

    >>> import meshio, tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     f = write_vtu(os.path.join(d, "x.vtu"), [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]],
    ...                   {"active": np.array([1, 0, 0, 1], np.uint8)}, {"blocked_fraction": [0.5]}, {"time": 0.25})
    ...     m = meshio.read(f)
    >>> m.cells[0].type, m.point_data["active"].tolist(), m.cell_data["blocked_fraction"][0].tolist()
    ('quad', [1, 0, 0, 1], [0.5])
    >>> m.field_data["time"].ravel().tolist()
    [0.25]
    """
    vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    connectivity, offsets, types = _cells(faces)
    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">',
             "<UnstructuredGrid>"]
    if field_data:
        lines += ["<FieldData>"] + [_array(k, np.atleast_1d(np.asarray(v, dtype=np.float64)), field=True)
                                    for k, v in field_data.items()] + ["</FieldData>"]
    lines.append(f'<Piece NumberOfPoints="{len(vertices)}" NumberOfCells="{len(types)}">')
    lines += ["<PointData>"] + [_array(k, v) for k, v in (point_data or {}).items()] + ["</PointData>"]
    lines += ["<CellData>"] + [_array(k, v) for k, v in (cell_data or {}).items()] + ["</CellData>"]
    lines += ["<Points>", _array("", vertices), "</Points>", "<Cells>", _array("connectivity", connectivity),
              _array("offsets", offsets), _array("types", types), "</Cells>", "</Piece>", "</UnstructuredGrid>",
              "</VTKFile>", ""]
    path = Path(path)
    path.write_text("\n".join(lines), encoding="ascii")
    return path
