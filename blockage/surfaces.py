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
from blockage.polygons import polygons
from blockage.sources import source_link
from blockage.surface_readers import SurfaceReaders
from blockage.validation import as_indices, as_points, as_transform

__all__ = ["LeakageSurface"]


class LeakageSurface(SurfaceReaders):
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
        self.faces, self.face_sizes = polygons(faces, len(self.vertices))
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
