"""Leakage surfaces: triangles and quads, built once, moved cheaply.

A :class:`LeakageSurface` holds the vertices and the elements (``N_e`` = 3 or 4
nodes) of an element-based leakage surface, with their areas. It is made from a
whole mesh, from a selection of the faces of a cavity surface (by index, by a box
or sphere region, or by a named group of a file format that has groups), from a
meshio or pyvista mesh, or from a file. A node-based leakage surface is just an
array of points (:func:`blockage.evaluate_nodes`).

When the surface is a selection of a cavity surface it remembers that surface
(``source``) and the id there of each of its vertices (``source_vertices``): if the
same surface also blocks, faces sharing a node with the query node are excluded
(self-contact).

>>> import numpy as np
>>> quad = LeakageSurface([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
>>> quad.face_sizes.tolist(), quad.total_area
([4], 1.0)
>>> mixed = LeakageSurface([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]],
...                        [[0, 1, 2, 3], [1, 4, 2]])
>>> mixed.faces.tolist(), mixed.face_areas.tolist()
([[0, 1, 2, 3], [1, 4, 2, -1]], [1.0, 0.5])
"""

import numpy as np

from blockage import areas, edges
from blockage.sources import source_link
from blockage.validation import as_faces, as_indices, as_points, as_transform

__all__ = ["LeakageSurface"]


def _polygons(faces, n_vertices):
    """Faces as an (m, k) int64 array padded with -1, and the size of each face."""
    if not isinstance(faces, np.ndarray):
        rows = [list(face) for face in faces]
        if len({len(row) for row in rows}) > 1:
            return _mixed_polygons(rows, n_vertices)
        faces = np.asarray(rows) if rows else np.zeros((0, 3), np.int64)
    array = np.asarray(faces)
    if array.ndim != 2 or array.shape[1] not in (3, 4):
        raise ValueError(f"faces must have shape (m, 3) or (m, 4), or be a list of 3- and 4-node faces; "
                         f"got shape {array.shape}")
    if array.shape[1] == 4 and array.size and np.issubdtype(array.dtype, np.integer) and (array[:, 3] < 0).any():
        return _mixed_polygons([list(row[:3]) if row[3] < 0 else list(row) for row in array], n_vertices)
    array = as_faces(array, n_vertices)
    return array, np.full(len(array), array.shape[1], dtype=np.int64)


def _mixed_polygons(rows, n_vertices):
    """Mixed triangles and quads as an (m, 4) array padded with -1."""
    bad = [len(row) for row in rows if len(row) not in (3, 4)]
    if bad:
        raise ValueError(f"faces must have 3 or 4 vertices each, found a face with {bad[0]}")
    sizes = np.array([len(row) for row in rows], dtype=np.int64)
    padded = as_faces(np.array([row + row[:1] * (4 - len(row)) for row in rows]).reshape(-1, 4), n_vertices)
    return np.where(np.arange(4)[None, :] < sizes[:, None], padded, -1), sizes


class LeakageSurface:
    """Element-based leakage surface (triangles and quads).

    Parameters
    ----------
    vertices : (n, 3) float
        Node positions [m].
    faces : (m, 3) or (m, 4) int, or a list of 3- and 4-node faces
        Elements; a 4-column array may pad triangles with -1.
    source : trimesh.Trimesh, optional
        The cavity surface this was selected from (enables self-contact).
    source_vertices : (n,) int, optional
        Vertex id in ``source`` of each node.

    Attributes
    ----------
    vertices : (n, 3) float
    faces : (m, k) int
        ``k = 3`` when all faces are triangles, else 4 with triangles padded -1.
    face_sizes : (m,) int
        ``N_e`` of each face.
    face_areas : (m,) float
        ``A_e`` [m^2].
    total_area : float
        [m^2]
    """

    def __init__(self, vertices, faces, *, source=None, source_vertices=None):
        self.vertices = as_points(vertices, "leakage-surface vertices", copy=True)
        self.faces, self.face_sizes = _polygons(faces, len(self.vertices))
        self._source = source_link(source)
        self.source_vertices = None
        if source_vertices is not None:
            ids = as_indices(source_vertices, len(source.vertices) if source is not None else np.iinfo(np.int64).max,
                             name="source_vertices")
            if ids.shape != (len(self.vertices),):
                raise ValueError(f"source_vertices must have one id per vertex ({len(self.vertices)}), "
                                 f"got shape {ids.shape}")
            self.source_vertices = ids
        self.face_areas = areas.face_areas(self.vertices, self.faces, self.face_sizes)
        self.total_area = float(self.face_areas.sum())
        self._edges = None

    @property
    def source(self):
        """The cavity surface this was selected from (held weakly), or None."""
        return self._source()

    def __repr__(self):
        return (f"LeakageSurface({len(self.vertices)} nodes, {len(self.faces)} faces, "
                f"total_area={self.total_area:.6g} m^2)")

    @property
    def edges(self):
        """(e, 2) int: unique element edges (quad diagonals excluded)."""
        if self._edges is None:
            self._edges = edges.surface_edges(self.faces, self.face_sizes)
        return self._edges

    def with_vertices(self, vertices):
        """The same elements on moved nodes (cheap: topology is shared).

        Parameters
        ----------
        vertices : (n, 3) float
            New node positions [m], same count and order.
        """
        vertices = as_points(vertices, "leakage-surface vertices", copy=True)
        if vertices.shape != self.vertices.shape:
            raise ValueError(f"with_vertices needs {self.vertices.shape} vertices, got {vertices.shape}")
        moved = object.__new__(LeakageSurface)
        moved.__dict__.update(self.__dict__)
        moved.vertices = vertices
        moved.face_areas = areas.face_areas(vertices, self.faces, self.face_sizes)
        moved.total_area = float(moved.face_areas.sum())
        return moved

    def transformed(self, matrix):
        """The surface moved by a rigid 4x4 transform."""
        matrix = as_transform(matrix)
        return self.with_vertices(self.vertices @ matrix[:3, :3].T + matrix[:3, 3])

    @classmethod
    def from_trimesh(cls, mesh):
        """Every face of a trimesh (which stays its ``source``)."""
        return cls(mesh.vertices, mesh.faces, source=mesh, source_vertices=np.arange(len(mesh.vertices)))

    @classmethod
    def from_faces(cls, mesh, face_indices):
        """A selection of faces of a cavity surface.

        Parameters
        ----------
        mesh : trimesh.Trimesh
            The cavity surface (kept as ``source`` for self-contact).
        face_indices : (k,) int
            Selected faces.
        """
        chosen = as_indices(np.ravel(face_indices), len(mesh.faces), name="face indices")
        used, local = np.unique(np.asarray(mesh.faces)[chosen], return_inverse=True)
        return cls(np.asarray(mesh.vertices)[used], local.reshape(-1, 3), source=mesh, source_vertices=used)

    @classmethod
    def from_region(cls, mesh, *, box=None, sphere=None):
        """Faces of a cavity surface whose centroid lies in a box or a sphere.

        Parameters
        ----------
        mesh : trimesh.Trimesh
            The cavity surface.
        box : ((3,) float, (3,) float), optional
            Lower and upper corners [m] (inclusive).
        sphere : ((3,) float, float), optional
            Centre [m] and radius [m] (inclusive).
        """
        if (box is None) == (sphere is None):
            raise ValueError("from_region needs exactly one of box=(lo, hi) or sphere=(centre, radius)")
        centroids = np.asarray(mesh.vertices)[np.asarray(mesh.faces)].mean(axis=1)
        if box is not None:
            lo, hi = (as_points(np.reshape(x, (1, 3)), "box corner")[0] for x in box)
            inside = ((centroids >= lo) & (centroids <= hi)).all(axis=1)
        else:
            centre = as_points(np.reshape(sphere[0], (1, 3)), "sphere centre")[0]
            inside = np.linalg.norm(centroids - centre, axis=1) <= float(sphere[1])
        if not inside.any():
            raise ValueError("no face of the mesh has its centroid in the given region")
        return cls.from_faces(mesh, np.flatnonzero(inside))

    @classmethod
    def from_meshio(cls, mesh, group=None):
        """Triangles and quads of a meshio mesh, optionally only a named cell set.

        Higher-order cells (``triangle6``, ``quad8``, ``quad9``) use their corner
        nodes. Nodes not used by the selected faces are dropped.
        """
        if group is not None and group not in mesh.cell_sets:
            raise ValueError(f"group {group!r} not found; the file has {sorted(mesh.cell_sets)}")
        rows = []
        for block_index, block in enumerate(mesh.cells):
            corners = {"triangle": 3, "triangle6": 3, "quad": 4, "quad8": 4, "quad9": 4}.get(block.type)
            if corners is None:
                continue
            data = np.asarray(block.data)[:, :corners]
            if group is not None:
                data = data[np.asarray(mesh.cell_sets[group][block_index], dtype=np.int64)]
            rows.extend(list(row) for row in data)
        if not rows:
            raise ValueError("the mesh has no triangle or quad cells" + (f" in group {group!r}" if group else ""))
        points = np.asarray(mesh.points, dtype=np.float64)
        points = np.column_stack([points, np.zeros((len(points), 3 - points.shape[1]))]) if points.shape[1] < 3 else points
        return cls._compact(points, rows)

    @classmethod
    def from_pyvista(cls, polydata):
        """Triangles and quads of a ``pyvista.PolyData``."""
        rows = [list(face) for face in polydata.irregular_faces]
        return cls._compact(np.asarray(polydata.points, dtype=np.float64), rows)

    @classmethod
    def read(cls, path, group=None):
        """Read a file with meshio (keeps quads; ``group`` names a cell set)."""
        import meshio

        return cls.from_meshio(meshio.read(path), group=group)

    @classmethod
    def _compact(cls, points, rows):
        """Surface on the nodes that the faces use."""
        faces, sizes = _polygons(rows, len(points))
        used = np.unique(faces[faces >= 0])
        renumber = np.full(len(points), -1, np.int64)
        renumber[used] = np.arange(len(used))
        local = [list(renumber[face[:size]]) for face, size in zip(faces, sizes)]
        return cls(points[used], local)
