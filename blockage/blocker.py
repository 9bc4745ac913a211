"""A blocking surface with its broad phase built once: exact distances on demand.

>>> import trimesh
>>> blocker = Blocker(trimesh.creation.box(extents=(2.0, 2.0, 2.0)))
>>> found = blocker.distances([[0.0, 0.0, 1.5], [0.0, 0.0, 9.0]], cutoff=1.0)
>>> found.distances.tolist()
[0.5, inf]
>>> found.closest_points[0].tolist()
[0.0, 0.0, 1.0]
>>> shift = np.eye(4); shift[2, 3] = 0.25          # the box moved up by 0.25 m
>>> blocker.distances([[0.0, 0.0, 1.5]], cutoff=1.0, transform=shift).distances.tolist()
[0.25]
"""

from typing import NamedTuple

import numpy as np

from blockage import broadphase, traversal
from blockage.feature_edges import FeatureEdgeQueries
from blockage.query_plumbing import exclusions, ordered_query, to_local, to_world
from blockage.sources import source_link
from blockage.tolerance import TOL
from blockage.validation import as_cutoff, as_faces, as_points, as_transform

__all__ = ["Blocker", "Proximity"]

class Proximity(NamedTuple):
    """Nearest blocking face of each query point.

    Attributes
    ----------
    distances : (n,) float
        Exact distance [m] where it is ``<= cutoff``, ``inf`` beyond.
    closest_points : (n, 3) float
        Closest point on the blocker [m] (world frame), NaN beyond the cutoff.
    faces : (n,) int
        Index of the nearest face, -1 beyond the cutoff.
    """

    distances: np.ndarray
    closest_points: np.ndarray
    faces: np.ndarray


def _mesh_arrays(mesh, faces):
    """Vertices and faces of a trimesh, or of explicit arrays."""
    if faces is None:
        if not hasattr(mesh, "vertices") or not hasattr(mesh, "faces"):
            raise ValueError("a blocker must be a trimesh.Trimesh or (vertices, faces) arrays, "
                             f"got {type(mesh).__name__}")
        mesh, faces = mesh.vertices, mesh.faces
    vertices = as_points(mesh, "blocker vertices", copy=True)  # the tree describes these, not the caller's
    faces = np.asarray(faces)
    if faces.size == 0:
        faces = np.zeros((0, 3), np.int64)
    return vertices, as_faces(faces, len(vertices), sizes=(3,), name="blocker faces")


class Blocker(FeatureEdgeQueries):
    """Blocking triangle surface with a bounding-volume hierarchy built once.

    Parameters
    ----------
    mesh : trimesh.Trimesh or (n, 3) float
        The surface, open or closed; or its vertices [m] when ``faces`` is given.
    faces : (m, 3) int, optional
        Triangles, when ``mesh`` is a vertex array.
    leaf_size : int
        Faces per leaf of the tree.

    Notes
    -----
    Rigid motion can be handled two ways: pass ``transform`` to the queries (the
    inverse transform is applied to the query points, nothing is rebuilt), or call
    :meth:`refit` with the moved vertices (the tree keeps its order and only its
    boxes are recomputed, which is exact for any motion).
    """

    def __init__(self, mesh, faces=None, *, leaf_size=broadphase.LEAF_SIZE):
        self._source = source_link(mesh if faces is None else None)
        self.vertices, self.faces = _mesh_arrays(mesh, faces)
        self._leaf_size = int(leaf_size)
        self._edge_tree = None
        self._edges = None
        self._build()

    @property
    def source(self):
        """The mesh this blocker was built from (held weakly), or None."""
        return self._source()

    def _margin(self):
        if len(self.vertices) == 0:
            return 0.0
        span = self.vertices.max(axis=0) - self.vertices.min(axis=0)
        return TOL.box_margin_rel * (np.abs(self.vertices).max() + np.sqrt(span @ span))

    def _build(self):
        self._tree = None
        if len(self.faces):
            order, slots = broadphase.tree_layout(self.vertices[self.faces].mean(axis=1), self._leaf_size)
            self._tree = broadphase.Tree(order, slots, self._leaf_size, np.zeros((2 * slots, 6)))
            self._sorted_faces = np.ascontiguousarray(self.faces[order])
        self._pack()

    def _pack(self):
        """Face arrays in tree order and node boxes for the current vertices."""
        self.margin = self._margin()
        if self._tree is None:
            return
        tree = self._tree
        (self._sorted_tri, self._sorted_degenerate, self._sorted_bounds, lo,
         hi) = broadphase.face_arrays(self.vertices, self._sorted_faces, TOL.degenerate_sin2)
        boxes = broadphase.node_boxes(lo, hi, tree.slots, tree.leaf_size, self.margin)
        self._tree = broadphase.Tree(tree.order, tree.slots, tree.leaf_size, boxes)

    def refit(self, vertices):
        """Move the vertices (same faces) and refit the tree boxes in place.

        Parameters
        ----------
        vertices : (n, 3) float
            New vertex positions [m], same count and order.

        Returns
        -------
        self : Blocker
        """
        vertices = as_points(vertices, "blocker vertices", copy=True)
        if vertices.shape != self.vertices.shape:
            raise ValueError(f"refit needs {self.vertices.shape} vertices, got {vertices.shape}")
        self.vertices = vertices
        self._pack()
        self._edge_tree = self._edges = None  # a deformation may change which edges are sharp
        return self

    def distances(self, points, cutoff=np.inf, transform=None, exclude_vertices=None):
        """Exact distance from each point to the nearest face, within a cutoff.

        Parameters
        ----------
        points : (n, 3) float
            Query points [m] (world frame).
        cutoff : float
            Search radius [m]; nodes farther than this get ``inf``.
        transform : (4, 4) float, optional
            Rigid transform placing the blocker in the world; its inverse is
            applied to the points, the tree is not rebuilt.
        exclude_vertices : (n,) int, optional
            For self-contact: blocker vertex id of each point (-1: none); faces
            incident to it are ignored for that point.

        Returns
        -------
        proximity : Proximity
        """
        points = as_points(points)
        cutoff = as_cutoff(cutoff)
        matrix = None if transform is None else as_transform(transform)
        local = points if matrix is None else to_local(points, matrix)
        exclude = exclusions(exclude_vertices, len(points), 1).ravel()
        n = len(points)
        if self._tree is None or n == 0:
            return Proximity(np.full(n, np.inf), np.full((n, 3), np.nan), np.full(n, -1, np.int64))
        raw = ordered_query(self._nearest_triangles((cutoff + self.margin) ** 2), local, exclude, 5)
        distances = np.sqrt(raw[:, 0])
        found = distances <= cutoff
        distances[~found] = np.inf
        closest = raw[:, 2:]
        closest[~found] = np.nan
        if matrix is not None:
            closest = to_world(closest, matrix)
        faces = self._tree.order[np.where(found, raw[:, 1], 0).astype(np.int64)]
        faces[~found] = -1
        return Proximity(distances, closest, faces)

    def _nearest_triangles(self, limit_sq):
        """The compiled nearest-face query as a function of (points, exclusions)."""
        tree = self._tree

        def run(points, exclude):
            return traversal.nearest_triangles(points, exclude, limit_sq, tree.boxes, tree.slots, tree.leaf_size,
                                               self._sorted_tri, self._sorted_degenerate, self._sorted_bounds,
                                               self._sorted_faces, self.margin)

        return run
