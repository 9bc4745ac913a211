"""Build the leakage area of a blocked exchange along θ: its surface, how its nodes and blockers move, the
certified crossings and the incremental area track."""
from __future__ import annotations

import numpy as np

import blockage

from .area_track import AreaTrack, node_weights
from .crossings import RESOLUTION, certified_crossings
from .errors import SceneError
from .gaps import DeformingPlacement, GapField, NodePath, RigidPlacement
from .scene_network import GeometricArea

__all__ = ["build_leak_area", "placement_of", "leak_surface", "blockage_rule"]

#: Gaps are exact up to this many contact tolerances (at least CUTOFF_EXTENT of the surface's size) [-].
CUTOFF_TOLERANCES = 8.0
CUTOFF_EXTENT = 0.02


def leak_surface(scene, j, cavity_meshes):
    """(LeakageSurface, the cavity spec it was cut from or None) of exchange j."""
    e, where = scene.exchange[j], f"exchange[{j}]"
    if e.leakage_surface:
        try:
            return blockage.LeakageSurface.read(scene.base / e.leakage_surface), None
        except Exception as exc:
            raise SceneError(scene.path, f"{where}.leakage_surface", f"cannot read {e.leakage_surface!r}: {exc}") \
                from None
    mesh = cavity_meshes[e.from_]
    lo, hi = np.array(e.leakage_box[:3]), np.array(e.leakage_box[3:])
    try:
        surface = blockage.LeakageSurface.from_region(mesh, box=(lo, hi))
    except ValueError as exc:
        raise SceneError(scene.path, f"{where}.leakage_box", str(exc)) from None
    return surface, next(c for c in scene.cavity if c.name == e.from_)


def placement_of(driver, name, open_depth=0.0):
    """The gap placement (:mod:`cases.gaps`) of body ``name`` along the driver's θ."""
    body, blocker = driver.bodies[name]
    if body.deforming:
        copy = blockage.Blocker(body.mesh)
        return DeformingPlacement(copy, (body.motion.times, body.motion.vertices), open_depth)
    if driver.dynamic is not None:
        if body is driver.dynamic:
            return RigidPlacement(blocker, body.axis, velocity=1.0, open_depth=open_depth)  # θ = s
        return RigidPlacement(blocker, body.axis, open_depth=open_depth)  # held where it starts
    m = body.motion
    return RigidPlacement(blocker, body.axis, displacement=m.table, velocity=m.velocity, angle=m.rotation_table,
                          rotation_axis=m.rotation_axis, centre=m.rotation_centre, open_depth=open_depth)


def _node_path(scene, surface, cavity, lo, hi):
    """How the leakage nodes move: with the cavity mesh's scale table when cut from a scaled cavity."""
    x0 = np.asarray(surface.vertices, dtype=float)
    if cavity is not None and cavity.mesh_scale_table:
        from .tables_io import read_table

        i = [c.name for c in scene.cavity].index(cavity.name)
        scale = read_table(scene.base / cavity.mesh_scale_table, scene.path, f"cavity[{i}].mesh_scale_table",
                           "scale [-]")
        return NodePath(x0, scale=scale)
    return NodePath(x0)


def _knots(driver, path, lo, hi):
    pts = set(driver.breakpoints) if driver.dynamic is None else set()
    if path.scale is not None:
        pts |= set(path.scale.breakpoints)
    return np.array([lo] + sorted(p for p in pts if lo < p < hi) + [hi])


def build_leak_area(scene, j, cavity_meshes: dict, driver):
    """(GeometricArea, (surface, positions)) of exchange j, or (None, None) when it has a plain area."""
    e = scene.exchange[j]
    if not (e.leakage_surface or e.leakage_box):
        return None, None
    surface, cavity = leak_surface(scene, j, cavity_meshes)
    tol = e.contact_tolerance or 1e-300
    path = _node_path(scene, surface, cavity, driver.lo, driver.hi)
    depth = float(getattr(e, "penetration_depth", 0.0) or 0.0)
    field = GapField(path, [placement_of(driver, n, depth) for n in e.blocked_by], tol,
                     max(CUTOFF_TOLERANCES * tol, CUTOFF_EXTENT * float(np.linalg.norm(np.ptp(surface.vertices, 0)))))
    knots = _knots(driver, path, driver.lo, driver.hi)
    found = certified_crossings(field.excess, len(surface.vertices), knots, field.speed(knots))
    weights = node_weights(surface.face_areas, surface.faces, surface.face_sizes, len(surface.vertices))
    track = AreaTrack.build(weights, surface.total_area, found, driver.lo, driver.hi,
                            effective_area=e.effective_area or None, permeability=e.permeability, scale=path.scale)

    def positions(theta, nodes=None):
        idx = np.arange(len(surface.vertices)) if nodes is None else np.asarray(nodes)
        return path.positions(np.full(len(idx), float(theta)), idx)

    return GeometricArea(track, driver.dynamic is None), (surface, positions)


def blockage_rule(scene, j) -> dict:
    """What the blockage of exchange j models, for summary.json."""
    e = scene.exchange[j]
    return {"rule": "a leakage node is active when its signed distance to a blocking surface is <= the contact "
                    "tolerance; nodes inside a closed blocker are active at any depth"
                    + (f", and nodes behind an open blocker up to {e.penetration_depth} m"
                       if getattr(e, "penetration_depth", 0.0) else "")
                    + "; each face loses A_e*N_c/N_e",
            "tolerance [m]": e.contact_tolerance,
            "side test": "angle-weighted pseudonormal at the closest point (Baerentzen & Aanaes 2005)",
            "guarantee": f"every contact and release lasting at least {RESOLUTION:g} of the run (or of the "
                         "body's travel) is found and timed to machine precision (Lipschitz bound on the gap, "
                         "bisection, regula falsi)"}
