"""Bounding-volume hierarchy over boxes: built once, refitted when the geometry moves.

The tree is an implicit complete binary tree over leaves of ``leaf_size`` primitives.
Its order is made top-down: at each level every node's range of primitives is
sorted along the longest axis of its centres and cut in the middle (a median
split, one vectorised ``lexsort`` per level), which gives tighter boxes than a
Morton order. Boxes are then one compiled pass (no Python loop over primitives):

* node ``1`` is the root, node ``k`` has children ``2k`` and ``2k + 1``;
* nodes ``slots .. 2*slots - 1`` are leaves, leaf ``j`` holding the sorted
  primitives ``j*leaf_size .. (j+1)*leaf_size - 1`` (empty leaves have an empty box
  ``lo = +inf, hi = -inf`` that every query prunes).

Moving the primitives keeps the order and only recomputes the boxes
(:func:`node_boxes`), which is exact for any motion and stays a good tree for rigid
motion. Leaf boxes are inflated by a margin (``TOL.box_margin_rel`` of the
coordinate scale) so that round-off can only add candidates, never lose one.

For triangles, :func:`face_arrays` also packs, in tree order, the vertices, the
degeneracy flags and a per-face bound (centroid, unit normal, radius): every point
``x`` of a face lies in its plane within ``radius`` of its centroid ``c``, so with
``h = n.(p - c)`` and in-plane offset ``w = (p - c) - h n``::

    |p - x|^2 >= h^2 + max(|w| - radius, 0)^2

which lets the query skip the exact kernel for most faces of a visited leaf.

>>> import numpy as np
>>> lo = np.array([[0.0, 0, 0], [5, 5, 5], [1, 0, 0]])
>>> tree = build_tree(lo, lo + 1.0, leaf_size=1)
>>> tree.slots, tree.order.tolist()
(4, [0, 2, 1])
>>> tree.boxes[1].tolist()
[0.0, 0.0, 0.0, 6.0, 6.0, 6.0]
"""

from dataclasses import dataclass

import numpy as np

from blockage._jit import njit
from blockage.triangle_distance import is_degenerate

__all__ = ["LEAF_SIZE", "Tree", "build_tree", "face_arrays", "morton_codes", "node_boxes", "tree_layout"]

LEAF_SIZE = 8
"""Primitives per leaf: 8 balances box tests against per-face bounds."""

_MORTON_BITS = 21


@dataclass(frozen=True)
class Tree:
    """An implicit BVH (see the module docstring).

    Attributes
    ----------
    order : (m,) int
        Primitive index of each sorted position.
    slots : int
        Number of leaf slots, a power of two; leaves are nodes ``slots..2*slots-1``.
    leaf_size : int
        Primitives per leaf.
    boxes : (2 * slots, 6) float
        Inflated box ``lo, hi`` of each node [m] (row 0 repeats the root), the
        two children of a node side by side in memory.
    """

    order: np.ndarray
    slots: int
    leaf_size: int
    boxes: np.ndarray


def _spread_bits(x):
    """Insert two zero bits between the low 21 bits of each uint64."""
    x = x & np.uint64(0x1FFFFF)
    for shift, mask in ((32, 0x1F00000000FFFF), (16, 0x1F0000FF0000FF), (8, 0x100F00F00F00F00F),
                        (4, 0x10C30C30C30C30C3), (2, 0x1249249249249249)):
        x = (x | (x << np.uint64(shift))) & np.uint64(mask)
    return x


def morton_codes(centers):
    """Morton (Z-order) code of each point on a cubic 2^21 grid over their bounding box.

    The grid has the same cell size along the three axes (the largest extent
    over 2^21 cells), so a flat cloud is split mostly across its plane, which
    keeps the boxes of the tree compact.

    Parameters
    ----------
    centers : (m, 3) float
        Points [m].

    Returns
    -------
    codes : (m,) uint64

    >>> morton_codes(np.array([[0.0, 0, 0], [1, 1, 1], [1, 0, 0]])).tolist()
    [0, 9223372036854775807, 1317624576693539401]
    """
    lo = centers.min(axis=0)
    extent = max(float((centers.max(axis=0) - lo).max()), np.finfo(float).tiny)
    cells = (centers - lo) / extent * ((1 << _MORTON_BITS) - 1)
    q = np.clip(cells, 0, (1 << _MORTON_BITS) - 1).astype(np.uint64)
    return _spread_bits(q[:, 0]) | (_spread_bits(q[:, 1]) << np.uint64(1)) | (
        _spread_bits(q[:, 2]) << np.uint64(2))


def tree_layout(centers, leaf_size=LEAF_SIZE):
    """Median-split order of the primitives and the number of leaf slots.

    Parameters
    ----------
    centers : (m, 3) float
        Primitive centres [m], ``m >= 1``.
    leaf_size : int
        Primitives per leaf.

    Returns
    -------
    order : (m,) int
    slots : int
        Smallest power of two with ``slots * leaf_size >= m``.
    """
    centers = np.asarray(centers, dtype=np.float64)
    m = len(centers)
    slots = 1 << max(int(-(-m // leaf_size) - 1).bit_length(), 0)
    order, rows = np.arange(m), np.arange(m)
    span = slots * leaf_size
    while span > leaf_size:
        sorted_centers = centers[order]
        starts = np.arange(0, m, span)
        extent = np.maximum.reduceat(sorted_centers, starts) - np.minimum.reduceat(sorted_centers, starts)
        segment = rows // span
        key = sorted_centers[rows, np.argmax(extent, axis=1)[segment]]
        order = order[np.lexsort((key, segment))]
        span //= 2
    return order, slots


@njit(nogil=True)
def node_boxes(lo, hi, slots, leaf_size, margin):
    """Boxes of all nodes from the boxes of the sorted primitives.

    Parameters
    ----------
    lo, hi : (m, 3) float
        Primitive boxes in tree order [m].
    slots, leaf_size : int
        Tree shape (see :class:`Tree`).
    margin : float
        Inflation of every leaf box on every side [m].

    Returns
    -------
    boxes : (2 * slots, 6) float
        ``lo, hi`` of each node [m].
    """
    m = lo.shape[0]
    boxes = np.empty((2 * slots, 6))
    for leaf in range(slots):
        node = slots + leaf
        for k in range(3):
            boxes[node, k], boxes[node, k + 3] = np.inf, -np.inf
        for i in range(leaf * leaf_size, min((leaf + 1) * leaf_size, m)):
            for k in range(3):
                boxes[node, k] = min(boxes[node, k], lo[i, k] - margin)
                boxes[node, k + 3] = max(boxes[node, k + 3], hi[i, k] + margin)
    for node in range(slots - 1, 0, -1):
        for k in range(3):
            boxes[node, k] = min(boxes[2 * node, k], boxes[2 * node + 1, k])
            boxes[node, k + 3] = max(boxes[2 * node, k + 3], boxes[2 * node + 1, k + 3])
    for k in range(6):
        boxes[0, k] = boxes[1, k]
    return boxes


@njit(nogil=True)
def face_arrays(vertices, faces, sin2):
    """Per-face arrays in the given (tree) order, in one pass.

    Parameters
    ----------
    vertices : (n, 3) float
        Vertex positions [m].
    faces : (m, 3) int
        Triangles in tree order.
    sin2 : float
        ``TOL.degenerate_sin2``.

    Returns
    -------
    tri : (m, 9) float
        ``a, b, c`` of each face [m].
    degenerate : (m,) bool
        :func:`blockage.triangle_distance.is_degenerate` of each face.
    bounds : (m, 8) float
        ``cx, cy, cz, nx, ny, nz, radius, 0`` (``n = 0`` for degenerate faces).
    lo, hi : (m, 3) float
        Bounding box of each face [m].
    """
    m = faces.shape[0]
    tri, degenerate = np.empty((m, 9)), np.empty(m, np.bool_)
    bounds, lo, hi = np.zeros((m, 8)), np.empty((m, 3)), np.empty((m, 3))
    for f in range(m):
        t = tri[f]
        for j in range(3):
            for k in range(3):
                t[3 * j + k] = vertices[faces[f, j], k]
        degenerate[f] = is_degenerate(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8], sin2)
        for k in range(3):
            lo[f, k] = min(t[k], t[3 + k], t[6 + k])
            hi[f, k] = max(t[k], t[3 + k], t[6 + k])
            bounds[f, k] = (t[k] + t[3 + k] + t[6 + k]) / 3.0
        _plane_and_radius(t, bounds[f], degenerate[f])
    return tri, degenerate, bounds, lo, hi


@njit
def _plane_and_radius(t, bound, degenerate):
    """Unit normal (zero if degenerate) and circumscribing radius about the centroid."""
    ux, uy, uz = t[3] - t[0], t[4] - t[1], t[5] - t[2]
    vx, vy, vz = t[6] - t[0], t[7] - t[1], t[8] - t[2]
    nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    length = np.sqrt(nx * nx + ny * ny + nz * nz)
    if not degenerate and length > 0.0:
        bound[3], bound[4], bound[5] = nx / length, ny / length, nz / length
    radius_sq = 0.0
    for j in range(3):
        dx, dy, dz = t[3 * j] - bound[0], t[3 * j + 1] - bound[1], t[3 * j + 2] - bound[2]
        radius_sq = max(radius_sq, dx * dx + dy * dy + dz * dz)
    bound[6] = np.sqrt(radius_sq)


def build_tree(lo, hi, leaf_size=LEAF_SIZE, margin=0.0):
    """Build the tree over primitive boxes.

    Parameters
    ----------
    lo, hi : (m, 3) float
        Bounding box of each primitive [m], ``m >= 1``.
    leaf_size : int
        Primitives per leaf.
    margin : float
        Inflation of every leaf box [m].

    Returns
    -------
    tree : Tree
    """
    lo = np.asarray(lo, dtype=np.float64)
    hi = np.asarray(hi, dtype=np.float64)
    order, slots = tree_layout(0.5 * (lo + hi), leaf_size)
    boxes = node_boxes(np.ascontiguousarray(lo[order]), np.ascontiguousarray(hi[order]), slots, leaf_size,
                       float(margin))
    return Tree(order, slots, leaf_size, boxes)
