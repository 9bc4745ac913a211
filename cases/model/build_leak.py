"""Build the leakage area of a blocked exchange along θ: its surface, how its nodes and blockers move, the
certified crossings and the incremental area track."""
from __future__ import annotations

import time

import numpy as np

import blockage
from cavity.caution import caution

from cases.model.area_track import AreaTrack, node_weights
from cases.model.crossings import RESOLUTION, SearchBudget, certified_crossings
from cases.model.chord_crossings import chord_solver
from cases.model.exact_crossings import behind_open_sheet, exact_solver
from cases.scene.errors import SceneError
from cases.model.mesh_series import is_series, read_mesh_series
from cases.model.gaps import DeformingPlacement, GapField, NodePath, RigidPlacement, SelfPlacement
from cases.model.scene_network import GeometricArea

__all__ = ["build_leak_area", "placement_of", "leak_surface", "blockage_rule"]

#: Gaps are exact up to this many contact tolerances (at least CUTOFF_EXTENT of the surface's size) [-].
CUTOFF_TOLERANCES = 8.0
CUTOFF_EXTENT = 0.02
#: Crossings of a prescribed motion closer than GROUP_WINDOW·√rtol of the run share one switch
#: (:meth:`cases.model.area_track.AreaTrack.grouped`: blocked area·time kept exact, flow changed to second order).
GROUP_WINDOW = 0.0


def leak_surface(scene, j, cavity_meshes):
    """(LeakageSurface, the cavity spec it was cut from or None, its own (times, vertices) or None) of exchange j;
    a leakage_surface given as a mesh series (.pvd, .xdmf, .npz) moves on its own."""
    e, where = scene.exchange[j], f"exchange[{j}]"
    if e.leakage_surface and is_series(e.leakage_surface):
        series = read_mesh_series(scene.base / e.leakage_surface, where=f"{where}.leakage_surface",
                                  scene_path=scene.path, parts=e.parts, units=scene.fe_run.units)
        return blockage.LeakageSurface(series.vertices[0], series.faces), None, (series.times, series.vertices)
    if e.leakage_surface:
        try:
            return blockage.LeakageSurface.read(scene.base / e.leakage_surface), None, None
        except Exception as exc:
            raise SceneError(scene.path, f"{where}.leakage_surface", f"cannot read {e.leakage_surface!r}: {exc}") \
                from None
    mesh = cavity_meshes[e.from_]
    lo, hi = np.array(e.leakage_box[:3]), np.array(e.leakage_box[3:])
    try:
        surface = blockage.LeakageSurface.from_region(mesh, box=(lo, hi))
    except ValueError as exc:
        raise SceneError(scene.path, f"{where}.leakage_box", str(exc)) from None
    return surface, next(c for c in scene.cavity if c.name == e.from_), None


def placement_of(driver, name, open_depth=0.0):
    """The gap placement (:mod:`cases.model.gaps`) of body ``name`` along the driver's θ."""
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


def _node_path(scene, surface, cavity, series):
    """How the leakage nodes move: with the cavity mesh's scale table or its mesh series when cut from it."""
    x0 = np.asarray(surface.vertices, dtype=float)
    if cavity is not None and cavity.name in series:
        times, vertices = series[cavity.name]
        return NodePath(x0, trajectory=(times, vertices[:, surface.source_vertices]))
    if cavity is not None and cavity.mesh_scale_table:
        from cases.scene.tables_io import read_table

        i = [c.name for c in scene.cavity].index(cavity.name)
        scale = read_table(scene.base / cavity.mesh_scale_table, scene.path, f"cavity[{i}].mesh_scale_table",
                           "scale [-]")
        return NodePath(x0, scale=scale)
    return NodePath(x0)


def read_nodes(scene, j):
    """(x (n, 3) [m], area (n,) [m^2] or None) of a node-based leakage surface (CSV: x, y, z[, area])."""
    e, key = scene.exchange[j], f"exchange[{j}].leakage_nodes"
    try:
        rows = np.genfromtxt(scene.base / e.leakage_nodes, delimiter=",", comments="#", dtype=float)
    except (OSError, ValueError) as exc:
        raise SceneError(scene.path, key, f"cannot read {e.leakage_nodes!r}: {exc}") from None
    rows = np.atleast_2d(rows)
    if rows.shape[0] and not np.all(np.isfinite(rows[0])):
        rows = rows[1:]  # a header row
    if rows.ndim != 2 or rows.shape[1] not in (3, 4) or not len(rows) or not np.all(np.isfinite(rows)):
        raise SceneError(scene.path, key, f"{e.leakage_nodes!r}: expected rows of x, y, z [m] and optionally "
                                          "area [m^2], all finite numbers")
    if rows.shape[1] == 4 and not np.all(rows[:, 3] >= 0):
        raise SceneError(scene.path, key, f"{e.leakage_nodes!r}: node areas must be >= 0 [m^2]")
    return rows[:, :3].copy(), (rows[:, 3].copy() if rows.shape[1] == 4 else None)


def _check_fixed_under_a_dynamic_body(scene, j, driver, path) -> None:
    """A dynamic body's blockage track is one of its displacement s; a leakage surface that moves in time (its
    cavity mesh's scale table or mesh series, or its own series) would make it one of (t, s) together, which is
    not tracked: such a scene is refused rather than run with the time table read at s."""
    if driver.dynamic is None or (path.scale is None and path.trajectory is None):
        return
    how = "scales with its cavity mesh's scale table" if path.scale is not None else "moves with a mesh series"
    raise SceneError(scene.path, f"exchange[{j}].blocked_by",
                     f"the leakage surface {how} (in time) and is blocked by a dynamic body, whose blockage is "
                     "tracked along its displacement only; give the body a prescribed motion (a motion table) "
                     "or keep the leakage surface's mesh fixed")


def _knots(driver, path, lo, hi):
    pts = set(driver.breakpoints) if driver.dynamic is None else set()
    if path.scale is not None:
        pts |= set(path.scale.breakpoints)
    if path.trajectory is not None:
        pts |= {float(t) for t in path.trajectory[0]}
    return np.array([lo] + sorted(p for p in pts if lo < p < hi) + [hi])


def _search(scene, j, field, n, knots, weights, unit):
    """The certified crossings of exchange j within the scene's wall budget. Node intervals the bound cannot settle
    are solved in closed form where the motion allows (:mod:`cases.model.exact_crossings`); any left are reported
    (which nodes, how much blocked area·θ is at stake) as a caution, or an error with ``[blockage] strict``."""
    wall = getattr(getattr(scene, "limits", None), "wall", 0.0) or np.inf
    try:
        exact, sheet = exact_solver(field, knots) or chord_solver(field, knots), behind_open_sheet(field)
        found = certified_crossings(field.excess, n, knots, field.speed(knots), deadline=time.perf_counter() + wall,
                                    exact=exact, exact_first=sheet)
    except SearchBudget as exc:
        raise SceneError(scene.path, f"exchange[{j}].blocked_by", f"the crossing search of the leakage surface "
                                                                  f"stopped at limits.wall = {wall:g} s ({exc}); "
                                                                  "raise limits.wall or coarsen the surface") from None
    messages = [uncertified_message(found, weights, unit)] if found.unresolved else []
    if sheet and exact is None:
        messages.append("a node slipping behind an open blocking sheet (penetration_depth) around its edge is judged "
                        "at the search's samples, not certified, for a rotating or deforming sheet")
    for message in messages:
        if getattr(getattr(scene, "blockage", None), "strict", False):
            raise SceneError(scene.path, f"exchange[{j}].blocked_by", f"{message}; [blockage] strict = true (or "
                                                                      "--strict) refuses it: give the body a rigid "
                                                                      "motion (translation and rotation tables)")
        caution(f"exchange {scene.exchange[j].name}: {message}")
    return found


def uncertified_message(found, weights, unit) -> str:
    """Which nodes' contact is not certified on which length of θ, and the blocked area·θ bound at stake."""
    who = np.flatnonzero(found.uncertain > 0)
    stake = float(np.dot(found.uncertain[who], weights[who]))
    names = ", ".join(str(int(i)) for i in who[:8]) + (", ..." if len(who) > 8 else "")
    return (f"the contact of {len(who)} leakage node(s) ({names}) is not certified on "
            f"{float(found.uncertain.sum()):.3g} {unit} of node intervals (a deforming blocker, or edge or self-"
            f"contact, whose gap stays near the tolerance): at most {stake:.3g} m^2*{unit} of blocked area*{unit} is at stake")


def build_leak_area(scene, j, cavity_meshes: dict, driver, series=None):
    """(GeometricArea, (surface or None, positions)) of exchange j, or (None, None) when it has a plain area.

    ``series``: {cavity name: (times, vertices)} of cavities given as mesh series."""
    e = scene.exchange[j]
    if not (e.leakage_surface or e.leakage_box or e.leakage_nodes):
        return None, None
    tol = e.contact_tolerance or 1e-300
    options = {"effective_area": e.effective_area or None, "permeability": e.permeability}
    if e.leakage_nodes:
        surface, (x0, node_area) = None, read_nodes(scene, j)
        path = NodePath(x0)
        weights = node_area if node_area is not None else np.ones(len(x0))
        total = float(weights.sum())
    else:
        surface, cavity, own = leak_surface(scene, j, cavity_meshes)
        path = NodePath(surface.vertices, trajectory=own) if own is not None else \
            _node_path(scene, surface, cavity, series or {})
        weights = node_weights(surface.face_areas, surface.faces, surface.face_sizes, len(surface.vertices))
        total = surface.total_area
        options.update(scale=path.scale)
    _check_fixed_under_a_dynamic_body(scene, j, driver, path)
    depth = float(e.penetration_depth or 0.0)
    placements = [placement_of(driver, n, depth) for n in e.blocked_by]
    if e.self_contact:
        placements.append(SelfPlacement(blockage.Blocker(cavity_meshes[e.from_]), surface.source_vertices,
                                        path.scale, (series or {}).get(e.from_)))
    size = float(np.linalg.norm(np.ptp(path.x0, axis=0)))
    field = GapField(path, placements, tol, max(CUTOFF_TOLERANCES * tol, CUTOFF_EXTENT * size),
                     surface.edges if e.edge_contact else None)
    knots = _knots(driver, path, driver.lo, driver.hi)
    found = _search(scene, j, field, len(path.x0), knots, weights, "s" if driver.dynamic is None else "m")
    if scene.blockage.rule != "exact" and driver.dynamic is not None:  # the rule's area along s, sampled in time
        from cases.model.fe_dynamic import dynamic_fe_track                # by the engine

        track = dynamic_fe_track(scene, j, found, surface, path.x0, weights, driver, options)
    elif scene.blockage.rule != "exact":  # an FE code's rule: flags sampled at its time steps, used with its lag
        from cases.model.fe_sampling import fe_leak_track

        track = fe_leak_track(scene, j, found, surface, path, weights, driver, options)
    else:
        track = _exact_track(scene, found, surface, path, weights, total, driver, options)

    def positions(theta, nodes=None):
        idx = np.arange(len(path.x0)) if nodes is None else np.asarray(nodes)
        return path.positions(np.full(len(idx), float(theta)), idx)

    return GeometricArea(track, driver.dynamic is None), (surface, positions)


def _exact_track(scene, found, surface, path, weights, total, driver, options) -> AreaTrack:
    """The exact rule's track: every crossing a switch, face areas that change between frames on a trajectory."""
    track = AreaTrack.build(weights, total, found, driver.lo, driver.hi, **options)
    if surface is not None and path.trajectory is not None:  # face areas that change between frames
        track = track.on_trajectory(*path.trajectory, surface.faces, surface.face_sizes)
    elif driver.dynamic is None and GROUP_WINDOW > 0.0:  # clusters of crossings within √rtol share one restart
        track = track.grouped(GROUP_WINDOW * np.sqrt(scene.solver.rtol) * (driver.hi - driver.lo))
    return track


def blockage_rule(scene, j) -> dict:
    """What the blockage of exchange j models, for summary.json ("blockage")."""
    e = scene.exchange[j]
    surface = "node-based (active nodes / all, or their share of the area)" if e.leakage_nodes else \
        "element-based: each face loses A_e*N_c/N_e"
    rule = ("a leakage node is active when its distance to a blocking surface is <= the contact tolerance, or "
            "when it lies inside a closed blocker (any depth)")
    if e.penetration_depth:
        rule += f", or behind an open blocker's interior within {e.penetration_depth} m"
    if e.edge_contact:
        rule += "; both nodes of a leakage edge within the tolerance of a blocker's feature edge are active"
    if e.self_contact:
        rule += "; the cavity's own surface blocks too (faces sharing the node ignored)"
    return {"rule": rule, "surface": surface, "tolerance [m]": e.contact_tolerance,
            "side test": "angle-weighted pseudonormal at the closest point (Baerentzen & Aanaes 2005)",
            "guarantee": f"every contact and release lasting at least {RESOLUTION:g} of the searched range (the "
                         "run, or the body's travel) is found and timed to machine precision: Lipschitz bound on "
                         "the gap from the motion, bisection where it cannot exclude a crossing, regula falsi; "
                         "where the gap hovers near the tolerance on a translating blocker, every crossing in "
                         "closed form (segment against the tolerance offset of each face), of any length, and on a "
                         "rotating one by chords of certified deviation; what cannot be certified (deforming "
                         "blockers, edge or self-contact) is a warning naming its nodes",
            "area switches shared": f"crossings within {GROUP_WINDOW:g}*sqrt(rtol) of the run share one switch"
                                    if GROUP_WINDOW > 0 else "none: every crossing is a switch"}
