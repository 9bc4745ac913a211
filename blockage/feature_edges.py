"""Feature-edge distances of a blocker (boundary, non-manifold and sharp edges): a mixin of
:class:`blockage.blocker.Blocker`, which supplies ``vertices``, ``faces``, ``margin``, ``_leaf_size``, ``_edges``
and ``_edge_tree``."""

import numpy as np

from blockage import broadphase, edges, traversal
from blockage.query_plumbing import exclusions, ordered_query, to_local
from blockage.validation import as_cutoff, as_points, as_transform

__all__ = ["FeatureEdgeQueries"]


class FeatureEdgeQueries:
    """Segment-to-feature-edge distances, with the edges' tree built on first use."""

    @property
    def feature_edges(self):
        """(e, 2) int: boundary, non-manifold and sharp edges (computed once)."""
        if self._edges is None:
            self._edges = edges.feature_edges(self.vertices, self.faces)
        return self._edges

    def edge_distances(self, starts, ends, cutoff=np.inf, transform=None, exclude_vertices=None):
        """Distance from each segment to the nearest feature edge, within a cutoff.

        Parameters
        ----------
        starts, ends : (n, 3) float
            Query segments [m] (world frame).
        cutoff : float
            Search radius [m]; farther segments get ``inf``.
        transform : (4, 4) float, optional
            Rigid transform placing the blocker in the world.
        exclude_vertices : (n, 2) int, optional
            Blocker vertex ids of the segment ends (self-contact, -1: none).

        Returns
        -------
        distances : (n,) float
            Exact segment-to-segment distance [m], ``inf`` beyond the cutoff.
        """
        starts, ends = as_points(starts, "starts"), as_points(ends, "ends")
        if starts.shape != ends.shape:
            raise ValueError(f"starts and ends must have the same shape, got {starts.shape} and {ends.shape}")
        cutoff = as_cutoff(cutoff)
        if transform is not None:
            matrix = as_transform(transform)
            starts, ends = to_local(starts, matrix), to_local(ends, matrix)
        exclude = exclusions(exclude_vertices, len(starts), 2)
        if len(self.feature_edges) == 0 or len(starts) == 0:
            return np.full(len(starts), np.inf)
        tree, segs, seg_vertices = self._feature_edge_tree()
        limit_sq = (cutoff + self.margin) ** 2

        def run(queries, ids):
            return traversal.nearest_segments(queries, ids, limit_sq, tree.boxes, tree.slots, tree.leaf_size,
                                              segs, seg_vertices)

        raw = ordered_query(run, np.hstack([starts, ends]), exclude, 2, centers=0.5 * (starts + ends))
        distances = np.sqrt(raw[:, 0])
        distances[distances > cutoff] = np.inf
        return distances

    def _feature_edge_tree(self):
        if self._edge_tree is None:
            ends = self.vertices[self.feature_edges]
            tree = broadphase.build_tree(ends.min(axis=1), ends.max(axis=1), self._leaf_size, self.margin)
            segs = np.ascontiguousarray(ends[tree.order].reshape(-1, 6))
            self._edge_tree = (tree, segs, np.ascontiguousarray(self.feature_edges[tree.order]))
        return self._edge_tree


