"""Build the moving geometry of a scene: bodies, wrapped cavity volumes, blocked leakage areas."""
from __future__ import annotations

import numpy as np

import blockage
from cavity.volume import closed_mesh_volume, MeshError

from cases.model.bodies import Body, DynamicMotion, PrescribedMotion, VertexTrajectory, unit
from cases.scene.errors import SceneError
from cases.model.build_leak import build_leak_area
from cases.model.wrapped_volume import Wrapper, wrapped_volume
from cases.model.scene_network import BodyState
from cases.scene.tables_io import read_table

__all__ = ["build_bodies", "Driver", "build_wrapped_volume", "build_leak_area", "load_mesh", "build_contact"]


def load_mesh(scene, file: str, where: str, process: bool = True):
    import trimesh

    try:
        return trimesh.load(scene.base / file, force="mesh", process=process)
    except Exception as exc:  # trimesh raises many types for unreadable files
        raise SceneError(scene.path, where, f"cannot read mesh {file!r}: {exc}") from None


def _body_mesh(scene, spec, where):
    import trimesh

    if spec.mesh:  # a vertex trajectory follows the file's own node order
        return load_mesh(scene, spec.mesh, f"{where}.mesh", process=not spec.vertex_trajectory)
    if spec.sphere:
        x, y, z, r = spec.sphere
        m = trimesh.creation.icosphere(subdivisions=spec.sphere_subdivisions, radius=r)
        m.apply_translation((x, y, z))
        return m
    x, y, z, lx, ly, lz = spec.box
    m = trimesh.creation.box(extents=(lx, ly, lz))
    m.apply_translation((x, y, z))
    return m


def _trajectory(scene, b, mesh, where) -> VertexTrajectory:
    """Vertex positions from an .npz file with arrays ``times`` (k,) [s] and ``vertices`` (k, n, 3) [m]; frame 0
    must be the mesh node by node (a trajectory in another vertex order is an error)."""
    from cases.model.mesh_series import read_mesh_series

    series = read_mesh_series(scene.base / b.vertex_trajectory, where=where, scene_path=scene.path,
                              reference_vertices=np.asarray(mesh.vertices), reference_faces=np.asarray(mesh.faces),
                              parts=b.parts, units=scene.fe_run.units)
    return VertexTrajectory(series.times, series.vertices)


def series_mesh(scene, file: str, where: str, parts=()):
    """(MeshSeries, trimesh of frame 0 in the series' own node order) of a mesh series (``parts``: of a d3plot)."""
    import trimesh

    from cases.model.mesh_series import read_mesh_series

    series = read_mesh_series(scene.base / file, where=where, scene_path=scene.path, parts=parts,
                              units=scene.fe_run.units)
    return series, trimesh.Trimesh(series.vertices[0], series.triangles(), process=False)


def build_bodies(scene) -> dict:
    """{name: (Body, Blocker)} for every [[body]]."""
    out = {}
    for i, b in enumerate(scene.body):
        where = f"body[{i}]"
        try:
            axis = unit(b.axis, f"{where}.axis")
        except ValueError as exc:
            raise SceneError(scene.path, f"{where}.axis", str(exc)) from None
        if b.mesh_series:
            motion, mesh = series_mesh(scene, b.mesh_series, f"{where}.mesh_series", b.parts)
            out[b.name] = (Body(b.name, mesh, axis, motion), blockage.Blocker(mesh))
            continue
        mesh = _body_mesh(scene, b, where)
        if b.mass:
            motion = DynamicMotion(b.mass, b.initial_velocity, b.gravity)
        elif b.vertex_trajectory:
            motion = _trajectory(scene, b, mesh, f"{where}.vertex_trajectory")
        else:
            table = (read_table(scene.base / b.displacement_table, scene.path, f"{where}.displacement_table",
                                "displacement [m]") if b.displacement_table else None)
            rot = (read_table(scene.base / b.rotation_table, scene.path, f"{where}.rotation_table", "angle [deg]")
                   if b.rotation_table else None)
            motion = PrescribedMotion(b.velocity, table, rot, unit(b.rotation_axis, f"{where}.rotation_axis"),
                                      tuple(b.rotation_centre))
        out[b.name] = (Body(b.name, mesh, axis, motion), blockage.Blocker(mesh))
    return out


class Driver:
    """What θ is: time (all bodies prescribed) or the dynamic body's displacement s."""

    def __init__(self, bodies: dict, t_end: float, extent: float):
        self.bodies = bodies
        dyn = [b for b, _ in bodies.values() if b.dynamic]
        self.dynamic = dyn[0] if dyn else None
        self.state = BodyState()
        self.lo, self.hi = (0.0, t_end) if self.dynamic is None else (-0.05 * extent, extent)

    def placement(self, name, theta):
        """(Blocker, 4x4) of body ``name`` at θ; a deforming body's Blocker is refitted (identity transform)."""
        body, blocker = self.bodies[name]
        if body.deforming:
            return blocker.refit(body.vertices_at(theta)), np.eye(4)
        if self.dynamic is not None and body is not self.dynamic:
            return blocker, body.transform(0.0)
        return blocker, body.transform(theta)

    def placed(self, names):
        return lambda theta: [self.placement(n, theta) for n in names]

    def wrapper(self, names) -> Wrapper:
        return Wrapper([self.bodies[n][0] for n in names], self.placed(names))

    @property
    def breakpoints(self):
        return tuple(b for body, _ in self.bodies.values() for b in body.motion.breakpoints)


def build_wrapped_volume(scene, i, mesh, driver: Driver):
    """The volume model of cavity i wrapped around its bodies."""
    c = scene.cavity[i]
    wrapper = driver.wrapper(c.wrapped_by)
    if driver.dynamic is None:
        return wrapped_volume(mesh, wrapper, driver.lo, driver.hi, lambda t: t, lambda t: 1.0, driver.breakpoints,
                              knots_in_time=True)
    if driver.dynamic.name not in c.wrapped_by:
        raise SceneError(scene.path, f"cavity[{i}].wrapped_by", "with a dynamic body, it must be among wrapped_by")
    st = driver.state
    return wrapped_volume(mesh, wrapper, driver.lo, driver.hi, lambda t: st.s, lambda t: st.v)


def cavity_mesh(scene, i):
    c = scene.cavity[i]
    mesh = load_mesh(scene, c.mesh, f"cavity[{i}].mesh")
    try:
        closed_mesh_volume(mesh, name=c.mesh)
    except MeshError as exc:
        raise SceneError(scene.path, f"cavity[{i}].mesh", str(exc)) from None
    return mesh


def _contact_law(c):
    from exchange.contact import ContactDamping, Hard, LinearPenalty, Softened

    law = {"hard": Hard, "linear": lambda: LinearPenalty(c.stiffness),
           "exponential": lambda: Softened(c.clearance, c.pressure)}[c.pressure_overclosure]()
    damping = None
    if c.damping == "coefficient":
        damping = ContactDamping(c.mu0, c.damping_clearance, c.eta, c.style,
                                 c.tangent_fraction if c.tangent_fraction >= 0 else None)
    return law, damping, (c.critical_fraction if c.damping == "critical_fraction" else None)


def build_contact(scene, geo, body):
    """The SeatContact of the dynamic body (None if it has no [[contact]])."""
    from cases.model.seat_contact import SeatContact, nodal_areas, ray_gaps

    found = [(i, c) for i, c in enumerate(scene.contact) if c.body == body.name]
    if not found:
        return None
    i, c = found[0]
    where = f"contact[{i}]"
    names = [e.name for e in scene.exchange]
    if c.seat:
        j = names.index(c.seat)
        surface = geo["surfaces"][j][0]
    else:
        j = None
        try:
            surface = blockage.LeakageSurface.read(scene.base / c.seat_mesh)
        except Exception as exc:
            raise SceneError(scene.path, f"{where}.seat_mesh", f"cannot read {c.seat_mesh!r}: {exc}") from None
    nodes = np.asarray(surface.vertices, dtype=float)
    tri = body.vertices_at(0.0)[np.asarray(body.mesh.faces)]
    axis = np.broadcast_to(np.asarray(body.axis, dtype=float), nodes.shape)
    up, down = ray_gaps(nodes, axis, tri), ray_gaps(nodes, -axis, tri)
    sigma = np.where(up <= down, 1.0, -1.0)
    g0 = np.minimum(up, down)
    if not np.isfinite(g0).any():
        raise SceneError(scene.path, where, f"no seat node faces body {body.name!r} along its axis: they never touch")
    law, damping, fraction = _contact_law(c)
    return SeatContact(c.name, body.name, law, damping, fraction, g0, sigma, nodal_areas(surface),
                       body.motion.mass, nodes, np.asarray(surface.faces), j)
