"""Blockage of a leakage surface by blocking surfaces: the entry points.

A leakage-surface node is an *active blockage node* when its exact distance to the
nearest blocking face is ``<= tolerance`` (node-to-face contact) or, with
``edge_contact=True``, when one of its edges lies within the tolerance of a
blocking feature edge. The areas then follow :mod:`blockage.areas`.

>>> import trimesh
>>> vent = LeakageSurface([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
>>> plate = trimesh.Trimesh([[-1.0, -1, 0.001], [0.5, -1, 0.001], [0.5, 2, 0.001], [-1, 2, 0.001]],
...                         [[0, 1, 2], [0, 2, 3]])
>>> result = evaluate(vent, [plate], tolerance=0.002)
>>> result.active_nodes.tolist(), result.obstruction_area, result.leak_area
([True, False, False, True], 0.5, 0.5)
>>> evaluate(vent, [plate], 0.002, effective_area=1e-4).leak_area
5e-05
"""

import weakref
from dataclasses import dataclass

import numpy as np

from blockage import areas, edges, sides
from blockage.blocker import Blocker, Proximity
from blockage.surfaces import LeakageSurface
from blockage.validation import as_cutoff, as_points, as_tolerance, as_transform

__all__ = ["BlockageResult", "NodeBlockageResult", "evaluate", "evaluate_nodes", "leakage_surface",
           "placed_blockers"]


@dataclass(frozen=True)
class BlockageResult:
    """Blockage of an element-based leakage surface.

    Attributes
    ----------
    active_nodes : (n,) bool
        Active blockage nodes, one per leakage-surface vertex.
    distances : (n,) float
        Exact distance to the nearest blocking face [m] (``inf`` beyond the
        cutoff, which defaults to the tolerance).
    closest_points : (n, 3) float
        Closest blocking point [m] (NaN beyond the cutoff).
    face_active_count : (m,) int
        ``N_c`` of each element.
    face_blocked_area : (m,) float
        ``A_e N_c / N_e`` [m^2].
    total_area, obstruction_area, leak_area : float
        [m^2]
    tolerance : float
        Contact tolerance used [m].
    """

    active_nodes: np.ndarray
    distances: np.ndarray
    closest_points: np.ndarray
    face_active_count: np.ndarray
    face_blocked_area: np.ndarray
    total_area: float
    obstruction_area: float
    leak_area: float
    tolerance: float

    @property
    def gaps(self):
        """(n,) float: ``distance - tolerance`` [m]; ``<= 0`` in contact."""
        return self.distances - self.tolerance

    @property
    def blocked_fraction(self):
        """Obstruction area / total area (0 for an empty surface)."""
        return self.obstruction_area / self.total_area if self.total_area > 0.0 else 0.0


@dataclass(frozen=True)
class NodeBlockageResult:
    """Blockage of a node-based leakage surface.

    Attributes
    ----------
    active_nodes : (n,) bool
    distances : (n,) float
        [m], ``inf`` beyond the cutoff.
    closest_points : (n, 3) float
        [m]
    blocked_fraction : float
        Active nodes / all nodes.
    """

    active_nodes: np.ndarray
    distances: np.ndarray
    closest_points: np.ndarray
    blocked_fraction: float


class _MeshCache:
    """Objects derived from a trimesh, rebuilt when its faces change, updated when its vertices move."""

    def __init__(self, build, update):
        self._build, self._update, self._entries = build, update, {}

    def __call__(self, mesh):
        key = id(mesh)
        vertices, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces)
        entry = self._entries.get(key)
        if entry is not None and entry["ref"]() is mesh and np.array_equal(entry["faces"], faces):
            if not np.array_equal(entry["vertices"], vertices):
                entry["value"] = self._update(entry["value"], vertices)
                entry["vertices"] = vertices.copy()
            return entry["value"]
        value = self._build(mesh)
        entries = self._entries

        def forget(ref, key=key):
            if key in entries and entries[key]["ref"] is ref:
                del entries[key]

        self._entries[key] = {"ref": weakref.ref(mesh, forget), "vertices": vertices.copy(),
                              "faces": faces.copy(), "value": value}
        return value


_blocker_cache = _MeshCache(Blocker, lambda blocker, vertices: blocker.refit(vertices))
_surface_cache = _MeshCache(LeakageSurface.from_trimesh, lambda surface, vertices: surface.with_vertices(vertices))


def _is_mesh(obj):
    return hasattr(obj, "vertices") and hasattr(obj, "faces")


def leakage_surface(leak):
    """``leak`` as a :class:`LeakageSurface` (a trimesh is converted once and cached)."""
    if isinstance(leak, LeakageSurface):
        return leak
    if _is_mesh(leak):
        return _surface_cache(leak)
    raise ValueError(f"leak must be a trimesh.Trimesh or a blockage.LeakageSurface, got {type(leak).__name__}")


def _placed(item):
    """One blocker as ``(Blocker, transform or None)``."""
    transform = None
    if isinstance(item, tuple):
        if len(item) != 2:
            raise ValueError("a blocker pair must be (mesh or Blocker, 4x4 transform)")
        item, transform = item[0], as_transform(item[1])
    if isinstance(item, Blocker):
        return item, transform
    if _is_mesh(item):
        return _blocker_cache(item), transform
    raise ValueError("blockers must be trimesh.Trimesh, blockage.Blocker or (mesh, 4x4 transform) pairs, "
                     f"got {type(item).__name__}")


def placed_blockers(blockers):
    """A sequence of blockers as ``[(Blocker, transform or None), ...]``.

    Accepts a single mesh or :class:`Blocker`, or a sequence of meshes, Blockers
    and ``(mesh or Blocker, transform)`` pairs. Blockers are cached per mesh.
    """
    if blockers is None:
        raise ValueError("blockers must be a sequence (possibly empty) of meshes or Blockers, got None")
    if isinstance(blockers, Blocker) or _is_mesh(blockers):
        blockers = [blockers]
    return [_placed(item) for item in blockers]


def _self_ids(surface, blocker, ids):
    """Blocker vertex ids of the query nodes when the blocker is the leak's own surface."""
    if surface.source is not None and blocker.source is surface.source and surface.source_vertices is not None:
        return surface.source_vertices[ids]
    return None


def nearest_blocking(points, placed, cutoff, surface=None):
    """Nearest blocking face over all blockers.

    Parameters
    ----------
    points : (n, 3) float
        Query points [m].
    placed : list of (Blocker, transform or None)
    cutoff : float
        Search radius [m].
    surface : LeakageSurface, optional
        Whose vertices ``points`` are (enables self-contact exclusion).

    Returns
    -------
    proximity : Proximity
        ``faces`` holds the face index in the winning blocker.
    """
    n = len(points)
    best = Proximity(np.full(n, np.inf), np.full((n, 3), np.nan), np.full(n, -1, np.int64))
    for blocker, transform in placed:
        exclude = _self_ids(surface, blocker, np.arange(n)) if surface is not None else None
        found = blocker.distances(points, cutoff, transform, exclude)
        closer = found.distances < best.distances
        best = Proximity(np.where(closer, found.distances, best.distances),
                         np.where(closer[:, None], found.closest_points, best.closest_points),
                         np.where(closer, found.faces, best.faces))
    return best


def edge_distances(surface, placed, cutoff):
    """(e,) float: distance of each leakage edge to the nearest blocking feature edge [m]."""
    ends = surface.vertices[surface.edges]
    distances = np.full(len(ends), np.inf)
    for blocker, transform in placed:
        exclude = _self_ids(surface, blocker, surface.edges)
        distances = np.minimum(distances, blocker.edge_distances(ends[:, 0], ends[:, 1], cutoff, transform,
                                                                 exclude))
    return distances


def penetrated(points, placed, surface=None, open_depth=0.0) -> np.ndarray:
    """(n,) bool: points inside a closed blocker, or behind an open one's interior within ``open_depth`` [m]
    (:mod:`blockage.sides`); a blocker that is the leak's own surface (self-contact) is skipped."""
    inside = np.zeros(len(points), dtype=bool)
    for blocker, transform in placed:
        if surface is not None and surface.source is not None and blocker.source is surface.source:
            continue
        inside |= sides.penetrating(blocker, points, transform, open_depth)
    return inside


def _open_depth(penetration) -> float:
    """Depth [m] behind an open blocker that counts as contact (``penetration`` given as a number)."""
    return 0.0 if isinstance(penetration, bool) else as_cutoff(penetration)


def _check_options(effective_area, permeability):
    if effective_area is not None:
        effective_area = as_tolerance(effective_area, "effective_area")
    try:
        permeability = float(permeability)
    except (TypeError, ValueError):
        permeability = np.nan
    if not 0.0 <= permeability <= 1.0:
        raise ValueError(f"permeability must be a fraction in [0, 1] (Radioss Bvent), got {permeability!r}")
    return effective_area, permeability


def blockage_result(surface, active, proximity, tolerance, effective_area=None, permeability=0.0):
    """Assemble a :class:`BlockageResult` from the active nodes (the area laws).

    Parameters
    ----------
    surface : LeakageSurface
    active : (n,) bool
        Active blockage nodes.
    proximity : Proximity
        Distances and closest points of the nodes.
    tolerance : float
        [m]
    effective_area : float, optional
        [m^2]
    permeability : float
        Radioss Bvent.
    """
    counts = areas.active_counts(active, surface.faces, surface.face_sizes)
    blocked = areas.blocked_face_areas(surface.face_areas, counts, surface.face_sizes)
    obstruction = areas.obstruction_area(blocked)
    return BlockageResult(active, proximity.distances, proximity.closest_points, counts, blocked,
                          surface.total_area, obstruction,
                          areas.leak_area(surface.total_area, obstruction, effective_area, permeability), tolerance)


def evaluate(leak, blockers, tolerance, *, effective_area=None, edge_contact=False, permeability=0.0,
             cutoff=None, penetration=True):
    """Active blockage nodes and leakage area of an element-based leakage surface.

    Parameters
    ----------
    leak : trimesh.Trimesh or LeakageSurface
        The leakage surface (triangles, or triangles and quads).
    blockers : sequence of trimesh.Trimesh, Blocker or (mesh or Blocker, 4x4 transform)
        Blocking surfaces, open or closed; the leak's own cavity surface may be
        one of them (self-contact: faces sharing the query node are ignored).
        Trees are built once per mesh and refitted when its vertices move.
    tolerance : float
        Contact tolerance [m]; a node is active when its distance is ``<=`` it.
    effective_area : float, optional
        Effective leakage area [m^2]; the result is then
        ``effective_area * (1 - obstruction / total)``.
    edge_contact : bool
        Also make active both nodes of every leakage edge within the tolerance
        of a blocking feature edge (boundary, non-manifold or sharp edge).
    permeability : float
        Fraction of the blocked area that still leaks (Radioss Bvent), default 0.
    cutoff : float, optional
        Report exact distances up to this radius [m] (default: the tolerance;
        ``np.inf`` for all nodes, slower).
    penetration : bool or float
        True (default): nodes inside a closed blocker are active at any depth;
        a float [m]: also nodes behind an open blocker's interior (against the
        pseudonormal of their closest point) up to that depth; False: the
        distance rule only.

    Returns
    -------
    result : BlockageResult
    """
    surface = leakage_surface(leak)
    tolerance = as_tolerance(tolerance)
    effective_area, permeability = _check_options(effective_area, permeability)
    cutoff = tolerance if cutoff is None else max(as_cutoff(cutoff), tolerance)
    placed = placed_blockers(blockers)
    proximity = nearest_blocking(surface.vertices, placed, cutoff, surface)
    active = proximity.distances <= tolerance
    if penetration:
        far = np.flatnonzero(~active)
        active[far[penetrated(surface.vertices[far], placed, surface, _open_depth(penetration))]] = True
    if edge_contact and len(surface.edges):
        active |= edges.edge_active_nodes(surface.edges, edge_distances(surface, placed, tolerance), tolerance,
                                          len(surface.vertices))
    return blockage_result(surface, active, proximity, tolerance, effective_area, permeability)


def evaluate_nodes(points, blockers, tolerance, *, cutoff=None, penetration=True):
    """Active nodes and blocked fraction of a node-based leakage surface.

    Parameters
    ----------
    points : (n, 3) float
        The nodes [m].
    blockers : sequence of trimesh.Trimesh, Blocker or (mesh or Blocker, 4x4 transform)
    tolerance : float
        Contact tolerance [m].
    cutoff : float, optional
        Report exact distances up to this radius [m] (default: the tolerance).
    penetration : bool or float
        As for :func:`evaluate`.

    Returns
    -------
    result : NodeBlockageResult
        ``blocked_fraction`` = active nodes / all nodes.

    >>> import trimesh
    >>> wall = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    >>> evaluate_nodes([[0.0, 0, 0.5005], [0, 0, 0.6], [0, 0, 0.7], [0.5, 0.5, 0.5]], [wall], 0.001).blocked_fraction
    0.5
    """
    points = as_points(points)
    tolerance = as_tolerance(tolerance)
    cutoff = tolerance if cutoff is None else max(as_cutoff(cutoff), tolerance)
    placed = placed_blockers(blockers)
    proximity = nearest_blocking(points, placed, cutoff)
    active = proximity.distances <= tolerance
    if penetration:
        far = np.flatnonzero(~active)
        active[far[penetrated(points[far], placed, None, _open_depth(penetration))]] = True
    return NodeBlockageResult(active, proximity.distances, proximity.closest_points, areas.blocked_fraction(active))
