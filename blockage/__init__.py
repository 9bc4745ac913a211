"""Contact blockage of leakage surfaces: exact node-to-face proximity and obstruction areas.

Geometry only (no gas). A leakage-surface node is active when its exact float64
distance to the nearest blocking face is ``<= tolerance``; each element is blocked
over ``A_e * N_c / N_e``; the leakage area is the total minus the obstruction (or an
effective area reduced in proportion). See ``docs/blockage.md``.

Public API
----------
evaluate(leak, blockers, tolerance, *, effective_area=None, edge_contact=False, permeability=0.0, cutoff=None)
evaluate_nodes(points, blockers, tolerance, *, cutoff=None)
Blocker(mesh).distances(points, cutoff, transform=None, exclude_vertices=None)
LeakageSurface(vertices, faces) and its constructors (from_trimesh, from_faces, from_region, from_meshio,
from_pyvista, read)
"""

from blockage.api import BlockageResult, NodeBlockageResult, evaluate, evaluate_nodes, leakage_surface
from blockage.blocker import Blocker, Proximity
from blockage.surfaces import LeakageSurface
from blockage.tolerance import TOL, Tolerances

__all__ = [
    "TOL",
    "BlockageResult",
    "Blocker",
    "LeakageSurface",
    "NodeBlockageResult",
    "Proximity",
    "Tolerances",
    "evaluate",
    "evaluate_nodes",
    "leakage_surface",
]
