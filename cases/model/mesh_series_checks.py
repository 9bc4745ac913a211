"""Checks of a mesh series across its frames: times, connectivity, finite coordinates, node order, reference mesh.

Every check raises :class:`cases.model.mesh_series_io.SeriesInvalid` with one line naming the frame (index, time and,
for a .pvd, the frame's file) and what differs.

Node order. A frame whose nodes are listed in another order than the previous frame's describes another surface
with the same connectivity: it must be refused, not interpolated. Two tests, the first that applies:

1. **Point ids.** When a frame and the one before it both carry a point-id array (one of
   :data:`cases.model.mesh_series_io.ID_NAMES`, e.g. ``vtkOriginalPointIds`` or ``GlobalNodeId``, or any integer
   one-component point array whose values are all different), the arrays must be identical.
2. **Geometry.** Otherwise two rules, both invariant under rigid motion and uniform scaling:

   a. *Edge lengths*: every edge of the faces keeps its length within a factor :data:`EDGE_RATIO` (4) between
      consecutive frames, ``1/4 <= L_e(k) / L_e(k-1) <= 4`` (lengths below 1e-9 of the mesh size count as
      equal). Fabric and solids strain far less than 4x between two outputs; a permuted frame joins nodes that
      are far apart. This catches any node moved far from its neighbours, even a single swap.
   b. *Neighbourhoods*: the one-ring of a node (the node and its edge neighbours) is mapped from frame k-1 to
      frame k by the best affine map (least squares); its misfit is the largest distance of a ring node from its
      fitted place, relative to the ring's radius (:func:`ring_misfit`). Every affine motion (translation,
      rotation, any stretch or shear) has misfit 0 and a smooth bending a small one; the median over the nodes
      (about :data:`RING_SAMPLE` of them) must stay at most :data:`RING_MISFIT` (0.25). Random permutations give
      medians of 0.27-0.84 even on an 8-node box or a 42-node icosphere, where rule (a) sees nothing; a strong
      bending of a 42-node sphere in one frame interval gives 0.15.

   c. *Orientation*: a motion cannot reflect: the affine maps of the 3-D rings (not flat: smallest principal
      second moment at least 1e-2 of the largest) must not have a negative determinant for more of them than a
      positive one. This catches a box whose vertex order is reversed (a point reflection).

   Not detectable from geometry: a permutation that is a symmetry of the mesh (it is a rigid motion), and a
   swap of two neighbouring nodes on a fine mesh (only their rings change, the median does not): give point ids
   or a reference mesh for those.

Reference mesh. When the caller has the mesh the series belongs to (the body's or cavity's mesh at t = 0), frame 0
must coincide with it node by node within ``reference_rtol`` (1e-5) of the mesh's size (the diagonal of its
bounding box): this catches a series (or an .npz trajectory) written in another vertex order than the mesh.
"""
from __future__ import annotations

import math

import numpy as np

from blockage.edges import surface_edges

from cases.model.mesh_series_io import ID_NAMES, SeriesInvalid, frame_label

__all__ = ["check_frames", "ring_misfit", "EDGE_RATIO", "RING_MISFIT", "REFERENCE_RTOL"]

#: Largest factor by which an edge may grow or shrink between two consecutive frames without point ids.
EDGE_RATIO = 4.0
#: Largest median one-ring affine misfit between two consecutive frames without point ids (see ring_misfit).
RING_MISFIT = 0.25
#: The misfit is evaluated on about this many nodes (every ceil(n / RING_SAMPLE)-th): its median is what counts.
RING_SAMPLE = 2000
#: Default tolerance of frame 0 against a reference mesh, relative to the mesh's bounding-box diagonal.
REFERENCE_RTOL = 1e-5
SAME_MESH = "every frame must have the nodes and connectivity of frame 0"
SAME_ORDER = "every frame must list the nodes in the order of frame 0"


def check_frames(frames, reference_vertices=None, reference_rtol: float = REFERENCE_RTOL) -> None:
    """Raise SeriesInvalid on the first problem of ``frames`` (a list of mesh_series_io.Frame)."""
    if len(frames) < 2:
        raise SeriesInvalid(f"{len(frames)} frame{'' if frames else 's'}: a mesh series needs at least 2 (for a fixed "
                            f"surface, give a mesh)")
    _check_times(frames)
    first = frames[0]
    _check_faces(first.faces, len(first.points), frame_label(0, first))
    for i, frame in enumerate(frames):
        _check_same_mesh(i, frame, first)
    if reference_vertices is not None:
        _check_reference(first, reference_vertices, reference_rtol)
    edges = surface_edges(first.faces, (first.faces >= 0).sum(axis=1))
    rings, lengths = None, _lengths(first.points, edges)
    for i in range(1, len(frames)):
        before, lengths = lengths, _lengths(frames[i].points, edges)
        if not _same_ids(frames, i):
            _check_edges(frames, i, edges, before, lengths)
            rings = _rings(edges, len(first.points)) if rings is None else rings
            _check_rings(frames, i, rings)


def _check_times(frames) -> None:
    for i, frame in enumerate(frames):
        if not math.isfinite(frame.time):
            raise SeriesInvalid(f"{frame_label(i, frame)}: the time is not finite")
        if i and not frame.time > frames[i - 1].time:
            raise SeriesInvalid(f"{frame_label(i, frame)}: not after frame {i - 1} (t = {frames[i - 1].time:.9g} s):"
                                f" frame times must increase strictly")


def _check_faces(faces, n: int, label: str) -> None:
    """Node ids within 0..n-1; -1 only as the padding of a triangle in a 4-column array."""
    allowed = np.zeros(faces.shape, bool)
    if faces.shape[1] == 4:
        allowed[:, 3] = faces[:, 3] == -1
    bad = np.flatnonzero((((faces < 0) & ~allowed) | (faces >= n)).any(axis=1))
    if bad.size:
        j = int(bad[0])
        raise SeriesInvalid(f"{label}: face {j} {_face(faces[j])} names a node outside 0..{n - 1} ({n} nodes)")


def _face(row) -> list:
    return [int(v) for v in row if v >= 0]


def _padded4(faces):
    return faces if faces.shape[1] == 4 else np.pad(faces, ((0, 0), (0, 1)), constant_values=-1)


def _check_same_mesh(i, frame, first) -> None:
    label = frame_label(i, frame)
    n0, n = len(first.points), len(frame.points)
    if n != n0:
        raise SeriesInvalid(f"{label}: {n} nodes, frame 0 has {n0}: {SAME_MESH}")
    if frame.faces is not first.faces:
        m0, m = len(first.faces), len(frame.faces)
        if m != m0:
            raise SeriesInvalid(f"{label}: {m} faces, frame 0 has {m0}: {SAME_MESH}")
        a, b = _padded4(frame.faces), _padded4(first.faces)
        differ = np.flatnonzero((a != b).any(axis=1))
        if differ.size:
            j = int(differ[0])
            raise SeriesInvalid(f"{label}: face {j} is {_face(a[j])}, in frame 0 {_face(b[j])} ({differ.size} faces "
                                f"differ): {SAME_MESH}")
    bad = np.flatnonzero(~np.isfinite(frame.points).all(axis=1))
    if bad.size:
        j = int(bad[0])
        raise SeriesInvalid(f"{label}: node {j} has a non-finite coordinate {frame.points[j].tolist()}")


def _same_ids(frames, i) -> bool:
    """True when frames i-1 and i share a point-id array and it is the same; SeriesInvalid when it differs."""
    prev, cur = frames[i - 1], frames[i]
    known = {s.lower() for s in ID_NAMES}
    compared = False
    for name, before in prev.ids.items():
        now = cur.ids.get(name)
        if now is None:
            if name.lower() in known:
                raise SeriesInvalid(f"{frame_label(i, cur)}: no point-id array {name!r}, which frame {i - 1} has")
            continue
        differ = np.flatnonzero(now != before)
        if differ.size:
            j = int(differ[0])
            what = ("nodes permuted" if np.array_equal(np.sort(now), np.sort(before))
                    else "other nodes (other ids)")
            raise SeriesInvalid(f"{frame_label(i, cur)}: {what} relative to frame {i - 1}: point id {name!r} is "
                                f"{now[j]} at node {j}, {before[j]} in frame {i - 1} ({differ.size} nodes differ): "
                                f"{SAME_ORDER}")
        compared = True
    return compared


def _lengths(points, edges) -> np.ndarray:
    d = points[edges[:, 0]] - points[edges[:, 1]]
    return np.sqrt(np.einsum("ij,ij->i", d, d))


def _check_edges(frames, i, edges, before, after) -> None:
    """Every edge within EDGE_RATIO of its length in the previous frame (a permuted frame scrambles edges)."""
    if not len(edges):
        return
    prev = frames[i - 1].points
    floor = 1e-9 * max(float(np.linalg.norm(np.ptp(prev, axis=0))), np.finfo(float).tiny)
    ratio = (after + floor) / (before + floor)
    bad = (ratio > EDGE_RATIO) | (ratio < 1.0 / EDGE_RATIO)
    if bad.any():
        j = int(np.argmax(np.abs(np.log(ratio))))
        u, v = edges[j]
        raise SeriesInvalid(
            f"{frame_label(i, frames[i])}: nodes permuted relative to frame {i - 1}? edge {u}-{v} changes length "
            f"{ratio[j]:.3g}x ({before[j]:.3g} m -> {after[j]:.3g} m) and {100.0 * bad.mean():.3g} % of the edges "
            f"more than {EDGE_RATIO:g}x (median ratio {np.median(ratio):.3g}): {SAME_ORDER} (rule: each edge within "
            f"1/{EDGE_RATIO:g} to {EDGE_RATIO:g} times its length in the previous frame)")


def _rings(edges, n: int, most: int = RING_SAMPLE) -> list:
    """One-rings (the node, then its edge neighbours) of every ceil(n / most)-th node of degree >= 3, as one
    (g, d + 1) index array per degree d."""
    both = np.concatenate([edges, edges[:, ::-1]])
    both = both[np.lexsort((both[:, 1], both[:, 0]))]
    degree = np.bincount(both[:, 0], minlength=n)
    start = np.concatenate([[0], np.cumsum(degree)[:-1]])
    sample = np.arange(0, n, max(1, -(-n // most)))
    groups = []
    for d in np.unique(degree[sample]):
        nodes = sample[degree[sample] == d]
        if d >= 3:
            groups.append(np.column_stack([nodes, both[start[nodes][:, None] + np.arange(d), 1]]))
    return groups


def ring_misfit(before, after, ring):
    """Misfit (g,) of the best affine map taking each ring of ``before`` to ``after`` (least squares), and the
    sign (g,) of that map's determinant for rings that are 3-D (0 for flat ones).

    The misfit is the largest distance of a ring node from its fitted position, relative to the ring's radius in
    ``after``: 0 for any affine motion (translation, rotation, stretch, shear), small for a smooth bending. A ring
    is 3-D when the smallest principal second moment of its points is at least 1e-2 of the largest.

    >>> import numpy as np
    >>> x = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0.5]])
    >>> ring = np.array([[0, 1, 2, 3, 4]])
    >>> misfit, sign = ring_misfit(x, x @ [[2.0, 1, 0], [0, 3, 0], [0, 0, 1]] + 7.0, ring)
    >>> misfit.round(12).tolist(), sign.tolist()
    ([0.0], [1.0])
    >>> ring_misfit(x, -x, ring)[1].tolist(), bool(ring_misfit(x, x[[0, 2, 1, 3, 4]], ring)[0][0] > 0.25)
    ([-1.0], True)
    """
    p, q = before[ring], after[ring]
    p, q = p - p.mean(axis=1, keepdims=True), q - q.mean(axis=1, keepdims=True)
    gram = np.einsum("gri,grj->gij", p, p)
    moments = np.linalg.eigvalsh(gram)
    gram += (1e-9 * moments[:, -1])[:, None, None] * np.eye(3)  # a flat ring has rank 2
    fit = np.linalg.solve(gram, np.einsum("gri,grj->gij", p, q))
    miss = np.linalg.norm(np.einsum("gri,gij->grj", p, fit) - q, axis=2).max(axis=1)
    size = np.linalg.norm(q, axis=2).max(axis=1)
    solid = moments[:, 0] >= 1e-2 * moments[:, -1]
    return (np.where(size > 0, miss / np.where(size > 0, size, 1.0), 0.0),
            np.where(solid, np.sign(np.linalg.det(fit)), 0.0))


def _check_rings(frames, i, rings) -> None:
    """The median one-ring affine misfit between frames i-1 and i at most RING_MISFIT, and no mirror image."""
    if not rings:
        return
    prev, cur = frames[i - 1].points, frames[i].points
    misfit, sign = (np.concatenate(parts) for parts in zip(*(ring_misfit(prev, cur, ring) for ring in rings)))
    median = float(np.median(misfit))
    start = f"{frame_label(i, frames[i])}: nodes permuted relative to frame {i - 1}?"
    if median > RING_MISFIT:
        raise SeriesInvalid(f"{start} the nodes' neighbourhoods do not follow any smooth motion (median affine "
                            f"misfit of the one-rings {median:.2g}, more than {RING_MISFIT:g}, over {len(misfit)} "
                            f"nodes): {SAME_ORDER}")
    if (sign < 0).sum() > (sign > 0).sum():
        raise SeriesInvalid(f"{start} it is the mirror image of frame {i - 1} ({int((sign < 0).sum())} of "
                            f"{int((sign != 0).sum())} 3-D neighbourhoods reflected; a motion cannot reflect): "
                            f"{SAME_ORDER}")


def _check_reference(frame, reference_vertices, rtol: float) -> None:
    """Frame 0 coincides with the reference mesh node by node, within rtol of its bounding-box diagonal."""
    ref = np.asarray(reference_vertices, dtype=float)
    label = frame_label(0, frame)
    if ref.shape != frame.points.shape:
        raise SeriesInvalid(f"{label}: {len(frame.points)} nodes, the reference mesh has {len(ref)} "
                            f"(shape {ref.shape}): the series must have the mesh's vertices, in its order")
    tol = rtol * float(np.linalg.norm(np.ptp(ref, axis=0)))
    dist = np.linalg.norm(frame.points - ref, axis=1)
    off = np.flatnonzero(dist > tol)
    if off.size:
        j = int(off[0])
        from scipy.spatial import cKDTree

        near, which = cKDTree(ref).query(frame.points)
        hint = (f"; it is the reference mesh with its vertices in another order (its vertex {j} is reference vertex "
                f"{which[j]}): write the series in the mesh's vertex order" if (near <= tol).all() else "")
        raise SeriesInvalid(f"{label} does not match the reference mesh: vertex {j} is {dist[j]:.3g} m from reference"
                            f" vertex {j} ({off.size} of {len(ref)} vertices off by more than {tol:.3g} m = {rtol:g} "
                            f"x the mesh size){hint}")
