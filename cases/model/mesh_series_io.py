"""Read the frames of a mesh series: a ParaView series (.pvd of .vtu/.vtp), an XDMF time series, or an .npz.

Each reader returns a list of :class:`Frame` (time, points, surface faces, point-id arrays, file) and checks
nothing across frames: :mod:`cases.model.mesh_series_checks` does that. A problem inside one file raises
:class:`SeriesInvalid` with a message naming the frame; :func:`cases.model.mesh_series.read_mesh_series` turns it into a
:class:`cases.scene.errors.SceneError`.

Only surface cells are taken: triangles, quads and polygons of 3 or 4 nodes. Vertex, line and volume cells next to
them are ignored (a volume mesh exported with its boundary faces gives its boundary); a frame without any surface
cell, or with quadratic surface cells, polygons of more than 4 nodes or triangle strips, is an error.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["Frame", "SeriesInvalid", "read_pvd", "read_xdmf", "read_npz", "surface_faces", "frame_label",
           "ID_NAMES", "DISPLACEMENT_NAMES"]

#: Point-data arrays taken as node ids (compared case-insensitively); any other integer, one-component point
#: array whose values are all different is taken as ids too.
ID_NAMES = ("vtkOriginalPointIds", "GlobalNodeId", "GlobalNodeIds", "node_id", "node_ids", "NodeId", "NodeIds",
            "PointIds", "point_ids", "ids", "id")
#: XDMF point-data vectors taken as the displacement from the mesh's points when a step has no Geometry of its own.
DISPLACEMENT_NAMES = ("displacement", "displacements", "Displacement", "disp", "u", "U")
SURFACE = {"triangle": 3, "quad": 4}
NOT_SURFACE = ("vertex", "line", "tetra", "hexa", "wedge", "pyramid", "penta", "polyhedron")


class SeriesInvalid(Exception):
    """A mesh series that cannot be used; the message is one line naming the frame."""


@dataclass
class Frame:
    """One frame as read: time [s], points (n, 3) [m], faces (m, 3|4) padded with -1, ids {name: (n,) int}."""

    time: float
    points: np.ndarray
    faces: np.ndarray
    ids: dict = field(default_factory=dict)
    file: str = ""


def frame_label(index: int, frame: Frame) -> str:
    """'frame 3 (t = 0.003 s, body/body_0003.vtp)': how errors name a frame."""
    return f"frame {index} (t = {frame.time:.9g} s{', ' + frame.file if frame.file else ''})"


def surface_faces(cells, what: str) -> np.ndarray:
    """Surface faces from (cell type, (m, k) ids) blocks in file order: (m, 3), (m, 4), or (m, 4) padded -1."""
    blocks, others = [], {}
    for kind, data in cells:
        data = np.asarray(data)
        if kind in SURFACE or (kind == "polygon" and data.shape[1] in (3, 4)):
            blocks.append(data.astype(np.int64).reshape(len(data), -1))
        elif kind == "polygon" or kind.startswith(("triangle", "quad")):
            cells = f"polygon cells of {data.shape[1]} nodes" if kind == "polygon" else f"{kind} cells"
            raise SeriesInvalid(f"{what}: {len(data)} {cells}: only linear triangles and quads (3 or 4 nodes) are "
                                f"taken")
        elif kind.startswith(NOT_SURFACE):
            others[kind] = others.get(kind, 0) + len(data)
        else:
            raise SeriesInvalid(f"{what}: cell type {kind!r} is not supported (triangles and quads are)")
    if not blocks:
        found = ", ".join(f"{n} {k}" for k, n in others.items()) or "no cells"
        raise SeriesInvalid(f"{what}: no surface cells (triangle, quad, or polygon of 3 or 4 nodes); found {found}")
    return _padded(blocks)


def _padded(blocks) -> np.ndarray:
    widths = {b.shape[1] for b in blocks}
    if len(widths) == 1:
        return np.concatenate(blocks)
    return np.concatenate([np.pad(b, ((0, 0), (0, 4 - b.shape[1])), constant_values=-1) for b in blocks])


def _ids(point_data: dict, n: int) -> dict:
    """The point-id arrays among ``point_data``: named ones (ID_NAMES), or integer ones with distinct values."""
    names = {s.lower() for s in ID_NAMES}
    out = {}
    for name, values in point_data.items():
        a = np.asarray(values)
        if a.ndim == 2 and a.shape[1] == 1:
            a = a[:, 0]
        if a.shape != (n,) or not np.issubdtype(a.dtype, np.integer):
            continue
        if name.lower() in names or len(np.unique(a)) == n:
            out[name] = a.astype(np.int64)
    return out


def _read_vtk_file(file: Path):
    """(points, cells, point_data) of a .vtu/.vtk (meshio, falling back to pyvista) or a .vtp (pyvista)."""
    if file.suffix.lower() != ".vtp":
        import meshio

        try:
            m = meshio.read(file)
            return m.points, [(c.type, c.data) for c in m.cells], dict(m.point_data)
        except Exception:  # meshio raises many types (and some VTU compressors it does not know): try VTK
            pass
    import pyvista

    mesh = pyvista.read(file)
    data = {name: np.asarray(mesh.point_data[name]) for name in mesh.point_data.keys()}
    if isinstance(mesh, pyvista.PolyData):
        if mesh.n_strips:
            raise SeriesInvalid(f"{mesh.n_strips} triangle strips: write polygons (pyvista: mesh.triangulate())")
        return np.asarray(mesh.points), _polydata_cells(mesh), data
    m = pyvista.to_meshio(mesh)
    return m.points, [(c.type, c.data) for c in m.cells], data


def _polydata_cells(mesh):
    """Polygons of a pyvista.PolyData as one (type, ids) block per run of equal sizes (order kept)."""
    from pyvista import convert_array

    polys = mesh.GetPolys()
    offsets = np.asarray(convert_array(polys.GetOffsetsArray()), dtype=np.int64)
    conn = np.asarray(convert_array(polys.GetConnectivityArray()), dtype=np.int64)
    sizes = np.diff(offsets)
    cuts = np.flatnonzero(np.diff(sizes)) + 1
    blocks = []
    for lo, hi in zip(np.r_[0, cuts], np.r_[cuts, len(sizes)]):
        k = int(sizes[lo])
        blocks.append(("polygon", conn[offsets[lo]:offsets[hi]].reshape(hi - lo, k)))
    others = (("line", mesh.n_lines), ("vertex", mesh.n_verts))
    return blocks + [(kind, np.zeros((n, 0), np.int64)) for kind, n in others if n]


def _pvd_entries(path: Path):
    """[(time, file)] of the DataSet entries of a ParaView collection, in file order."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise SeriesInvalid(f"cannot read the ParaView series: {exc}") from None
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        raise SeriesInvalid('not a ParaView series: expected <VTKFile type="Collection">')
    sets = root.findall("./Collection/DataSet")
    if not sets:
        raise SeriesInvalid("no <DataSet> entries in its <Collection>")
    parts = sorted({ds.get("part", "0") for ds in sets})
    if len(parts) > 1:
        raise SeriesInvalid(f"DataSets of several parts ({', '.join(parts)}): one surface a series; merge the parts "
                            f"or write one series per part")
    entries = []
    for j, ds in enumerate(sets):
        file, stamp = ds.get("file"), ds.get("timestep")
        if not file or stamp is None:
            raise SeriesInvalid(f"DataSet {j} needs both 'timestep' and 'file' attributes, got {dict(ds.attrib)}")
        try:
            entries.append((float(stamp), file))
        except ValueError:
            raise SeriesInvalid(f"DataSet {j} ({file}): timestep {stamp!r} is not a number") from None
    return entries


def read_pvd(path: Path) -> list:
    """Frames of a ParaView series; frame files are relative to the .pvd's folder (or absolute)."""
    frames = []
    for i, (t, name) in enumerate(_pvd_entries(path)):
        label = frame_label(i, Frame(t, None, None, file=name))
        file = path.parent / name
        if file.suffix.lower() not in (".vtu", ".vtp", ".vtk"):
            raise SeriesInvalid(f"{label}: expected a .vtu, .vtp or .vtk frame file")
        if not file.is_file():
            raise SeriesInvalid(f"{label}: frame file {name} not found (in {path.parent})")
        try:
            points, cells, data = _read_vtk_file(file)
        except SeriesInvalid as exc:
            raise SeriesInvalid(f"{label}: {exc}") from None
        except Exception as exc:  # a corrupt frame file: meshio and VTK raise many types
            raise SeriesInvalid(f"{label}: cannot read {name}: {exc}") from None
        points = _points(points, label)
        frames.append(Frame(t, points, surface_faces(cells, label), _ids(data, len(points)), name))
    return frames


def _points(points, label) -> np.ndarray:
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] != 3:
        raise SeriesInvalid(f"{label}: points of shape {p.shape}, expected (n, 3)")
    return p


def _xdmf_child(grid, tag):
    found = [c for c in grid if c.tag == tag]
    return found[0] if found else None


def _xdmf_cells(reader, topology):
    """(type, ids) blocks of one XDMF <Topology>, as meshio reads them."""
    from meshio.xdmf.common import translate_mixed_cells, xdmf_to_meshio_type

    items = list(topology)
    data = reader._read_data_item(items[0])  # meshio's reader of XML, Binary and HDF data items
    kind = topology.get("Type") or topology.get("TopologyType")
    if kind == "Mixed":
        return [(c.type, c.data) for c in translate_mixed_cells(data.ravel())]
    if kind not in xdmf_to_meshio_type:
        raise SeriesInvalid(f"XDMF topology {kind!r} is not supported")
    return [(xdmf_to_meshio_type[kind], data.reshape(len(data), -1))]


def read_xdmf(path: Path) -> list:
    """Frames of an XDMF temporal collection (meshio.xdmf.TimeSeriesReader).

    A step's points are its own <Geometry> if it has one, else the mesh's points plus a displacement point-data
    vector (DISPLACEMENT_NAMES), as meshio's TimeSeriesWriter and FEniCS write a moving mesh. A step's own
    <Topology> is read and compared with the first step's by the checks.
    """
    from meshio.xdmf import TimeSeriesReader

    try:
        reader = TimeSeriesReader(path)
    except Exception as exc:  # meshio raises ReadError, ParseError, KeyError ...
        raise SeriesInvalid(f"cannot read the XDMF time series: {exc!s} ({type(exc).__name__})") from None
    for item in reader.domain.iter("DataItem"):  # meshio opens raw binary files relative to the working folder
        if item.get("Format") == "Binary" and item.text and not Path(item.text.strip()).is_absolute():
            item.text = str(path.parent / item.text.strip())
    with reader:
        try:
            points0, _ = reader.read_points_cells()
            faces0 = surface_faces(_xdmf_cells(reader, _xdmf_child(reader.mesh_grid, "Topology")), "the mesh")
            return [_xdmf_frame(reader, k, points0, faces0) for k in range(reader.num_steps)]
        except ImportError as exc:
            raise SeriesInvalid(f"its data are in HDF5: install h5py to read them ({exc})") from None
        except SeriesInvalid:
            raise
        except Exception as exc:  # meshio's ReadError and numpy's shape errors on a malformed file
            raise SeriesInvalid(f"cannot read the XDMF time series: {exc!s} ({type(exc).__name__})") from None


def _xdmf_frame(reader, k, points0, faces0) -> Frame:
    t, point_data, _ = reader.read_data(k)
    label = frame_label(k, Frame(t, None, None))
    grid = reader.collection[k]
    if grid.get("GridType") == "Collection":
        raise SeriesInvalid(f"{label}: a spatial collection (several parts): one surface a series; merge the parts")
    topology, geometry = _xdmf_child(grid, "Topology"), _xdmf_child(grid, "Geometry")
    faces = faces0 if topology is None else surface_faces(_xdmf_cells(reader, topology), label)
    if geometry is not None:
        points = _points(reader._read_data_item(list(geometry)[0]), label)
    else:
        name = next((s for s in DISPLACEMENT_NAMES if s in point_data), None)
        if name is None:
            raise SeriesInvalid(f"{label}: no <Geometry> of its own and no displacement point data (one of "
                                f"{', '.join(DISPLACEMENT_NAMES)}): a mesh series gives the nodes' positions in "
                                f"every frame")
        points = _points(points0, label) + np.asarray(point_data[name], dtype=float).reshape(len(points0), -1)
    return Frame(t, points, faces, _ids(point_data, len(points)))


def read_npz(path: Path, reference_faces=None) -> list:
    """Frames of an .npz with ``times`` (k,), ``vertices`` (k, n, 3) and ``faces`` (m, 3|4) (or the reference's)."""
    try:
        with np.load(path) as data:
            arrays = {name: data[name] for name in data.files}
    except (OSError, ValueError) as exc:
        raise SeriesInvalid(f"cannot read the .npz: {exc}") from None
    for name in ("times", "vertices") + (() if reference_faces is not None else ("faces",)):
        if name not in arrays:
            raise SeriesInvalid(f"no array {name!r} (it has: {', '.join(sorted(arrays)) or 'none'}); expected "
                                f"times (k,) [s], vertices (k, n, 3) [m] and faces (m, 3) or (m, 4)")
    times, verts = np.asarray(arrays["times"], dtype=float), np.asarray(arrays["vertices"], dtype=float)
    if verts.ndim != 3 or verts.shape[2] != 3 or times.shape != (verts.shape[0],):
        raise SeriesInvalid(f"expected times (k,) and vertices (k, n, 3), got {times.shape} and {verts.shape}")
    faces = np.asarray(arrays["faces"] if "faces" in arrays else reference_faces)
    if faces.ndim != 2 or faces.shape[1] not in (3, 4) or not np.issubdtype(faces.dtype, np.integer):
        raise SeriesInvalid(f"faces must be integers of shape (m, 3) or (m, 4), got {faces.dtype} {faces.shape}")
    faces = faces.astype(np.int64)
    return [Frame(float(t), verts[i], faces) for i, t in enumerate(times)]
