"""Checks of a scene that involve several keys at once: names that refer to each other, per-type required keys,
files that must exist, combinations that cannot be simulated. Each failure is a one-line SceneError."""
from __future__ import annotations

from cavity.tables import TableError

from cases.scene import law_keys
from cases.scene.errors import SceneError
from cases.scene.schema import unknown_name
from cases.scene.tables_io import read_table

__all__ = ["check_cross_references", "require_file"]


def require_file(scene, name: str, path, where: str) -> None:
    """A file a scene names (if it names one) exists and is a file, relative to the scene's folder."""
    if not name:
        return
    target = scene.base / name
    if target.is_dir():
        raise SceneError(path, where, f"{name!r} is a directory, not a file")
    if not target.is_file():
        raise SceneError(path, where, f"file {name!r} does not exist")


def check_cross_references(scene: Scene, path) -> None:
    """Keys that refer to other things (cavity names, volume sources, per-type inflator keys) agree."""
    names = [c.name for c in scene.cavity]
    if not names:
        raise SceneError(path, "cavity", "a scene needs at least one [[cavity]]")
    for i, c in enumerate(scene.cavity):
        where = f"cavity[{i}]"
        given = [k for k in ("volume", "volume_table", "mesh", "mesh_series") if getattr(c, k)]
        if len(given) != 1:
            raise SceneError(path, where, "give exactly one of volume, volume_table, mesh, mesh_series "
                                          f"(got {given or 'none'})")
        if c.mesh_scale_table and not c.mesh:
            raise SceneError(path, f"{where}.mesh_scale_table", "needs `mesh`")
        if c.mesh_series and c.wrapped_by:
            raise SceneError(path, f"{where}.wrapped_by", "a mesh series already gives every node's position")
        for f in ("volume_table", "mesh", "mesh_scale_table", "mesh_series"):
            require_file(scene, getattr(c, f), path, f"{where}.{f}")
        if c.volume_table:
            _require(read_table(scene.base / c.volume_table, path, f"{where}.volume_table", "volume [m^3]"),
                     path, f"{where}.volume_table", positive=True)
        if c.energy == "heat_loss" and not (c.heat_transfer_coefficient and c.heat_transfer_area):
            raise SceneError(path, f"{where}.energy", "heat_loss needs heat_transfer_coefficient and "
                                                      "heat_transfer_area > 0")
        for j, inf in enumerate(c.inflator):
            _check_inflator(inf, path, f"{where}.inflator[{j}]")
        if c.fluid == "hydraulic":
            for k in ("density", "bulk_modulus"):
                if not getattr(c, k) > 0:
                    raise SceneError(path, f"{where}.{k}", "required (> 0) for a hydraulic cavity")
            if c.inflator or c.energy != "adiabatic" or c.wrapped_by:
                raise SceneError(path, where, "a hydraulic cavity has no inflators, energy model or wrapping")
            require_file(scene, c.temperature_table, path, f"{where}.temperature_table")
    _check_bodies(scene, path)
    for i, e in enumerate(scene.exchange):
        for side, value in (("from", e.from_), ("to", e.to)):
            if value not in names and not (side == "to" and value == "ambient"):
                raise unknown_name(path, f"exchange[{i}].{side}", "cavity", value, names + ["ambient"])
        if e.from_ == e.to:
            raise SceneError(path, f"exchange[{i}].to", "an exchange joins two different sides")
        _check_exchange(scene, e, path, f"exchange[{i}]")
        _check_hydraulic_exchange(scene, e, path, f"exchange[{i}]")





def _check_bodies(scene: Scene, path) -> None:
    names = [b.name for b in scene.body]
    for i, b in enumerate(scene.body):
        shapes = [k for k in ("mesh", "sphere", "box", "mesh_series") if getattr(b, k)]
        if len(shapes) != 1:
            raise SceneError(path, f"body[{i}]", "give exactly one of mesh, sphere, box, mesh_series "
                                                 f"(got {shapes or 'none'})")
        for k in ("mesh", "mesh_series"):
            require_file(scene, getattr(b, k), path, f"body[{i}].{k}")
        if b.mesh_series and (b.mass or b.velocity or b.displacement_table or b.rotation_table or
                              b.vertex_trajectory):
            raise SceneError(path, f"body[{i}].mesh_series", "a mesh series is the body's whole motion")
        if b.displacement_table:
            read_table(scene.base / b.displacement_table, path, f"body[{i}].displacement_table", "displacement [m]")
        if b.mass and (b.velocity or b.displacement_table or b.rotation_table or b.vertex_trajectory):
            raise SceneError(path, f"body[{i}].mass", "a dynamic body (mass > 0) has no prescribed motion")
        if b.vertex_trajectory and (b.velocity or b.displacement_table or b.rotation_table):
            raise SceneError(path, f"body[{i}].vertex_trajectory", "replaces velocity, displacement and rotation")
        for k in ("rotation_table", "vertex_trajectory"):
            require_file(scene, getattr(b, k), path, f"body[{i}].{k}")
        forces = ("spring_stiffness", "spring_preload", "pressure_area", "pressure_cavity")
        given = [k for k in forces if getattr(b, k)]
        if given and not b.mass:
            raise SceneError(path, f"body[{i}].{given[0]}", "only a dynamic body (mass > 0) feels forces")
        if bool(b.pressure_area) != bool(b.pressure_cavity):
            raise SceneError(path, f"body[{i}].pressure_cavity", "give pressure_area and pressure_cavity together")
        cavities = [c.name for c in scene.cavity]
        if b.pressure_cavity and b.pressure_cavity not in cavities:
            raise unknown_name(path, f"body[{i}].pressure_cavity", "cavity", b.pressure_cavity, cavities)
    if sum(1 for b in scene.body if b.mass) > 1:
        raise SceneError(path, "body", "at most one dynamic body (mass > 0) per scene")
    if any(b.mass for b in scene.body):
        for i, b in enumerate(scene.body):
            if not b.mass and (b.velocity or b.displacement_table or b.rotation_table or b.vertex_trajectory):
                raise SceneError(path, f"body[{i}]", "with a dynamic body in the scene, the other bodies stay fixed")
    refs = [(f"cavity[{i}].wrapped_by", c.wrapped_by) for i, c in enumerate(scene.cavity)]
    refs += [(f"exchange[{i}].blocked_by", e.blocked_by) for i, e in enumerate(scene.exchange)]
    for where, used in refs:
        for n in used:
            if n not in names:
                raise unknown_name(path, where, "body", n, names)


def _check_exchange(scene: Scene, e: ExchangeSpec, path, where: str) -> None:
    for k in law_keys.required(e.law):
        if not getattr(e, k):
            raise SceneError(path, f"{where}.{k}", f"required (non-zero) for law {e.law!r}")
    for k in law_keys.of_kind("file"):
        require_file(scene, getattr(e, k.name), path, f"{where}.{k.name}")
    sources = [k for k in ("leakage_surface", "leakage_box", "leakage_nodes") if getattr(e, k)]
    geometric = bool(sources)
    if len(sources) > 1:
        raise SceneError(path, f"{where}.{sources[1]}", "give one of leakage_surface, leakage_box, leakage_nodes")
    for k in ("leakage_surface", "leakage_nodes"):
        require_file(scene, getattr(e, k), path, f"{where}.{k}")
    cavity = next((c for c in scene.cavity if c.name == e.from_), None)
    if e.leakage_box and cavity is not None and not (cavity.mesh or cavity.mesh_series):
        raise SceneError(path, f"{where}.leakage_box", "selects faces of the `from` cavity's mesh: it has none")
    if e.self_contact and not e.leakage_box:
        raise SceneError(path, f"{where}.self_contact", "needs leakage_box (a part of the cavity's own surface)")
    if (e.self_contact or e.edge_contact) and not e.contact_tolerance > 0:
        raise SceneError(path, f"{where}.contact_tolerance", "expected a tolerance > 0 [m]")
    if e.edge_contact and e.leakage_nodes:
        raise SceneError(path, f"{where}.edge_contact", "a node-based leakage surface has no edges")
    if e.blocked_by and not geometric:
        raise SceneError(path, f"{where}.blocked_by", "needs leakage_surface or leakage_box")
    if geometric and e.area:
        raise SceneError(path, f"{where}.area", "the area comes from the leakage surface: use effective_area")
    if not geometric and not e.area > 0:
        raise SceneError(path, f"{where}.area", "expected a flow area > 0 [m^2]")
    if e.close_time and e.close_time <= e.open_time:
        raise SceneError(path, f"{where}.close_time", f"must be later than open_time ({e.open_time} s)")
    if e.pop_hold_time and not e.pop_pressure:
        raise SceneError(path, f"{where}.pop_hold_time", "needs pop_pressure")
    if e.close_pressure and e.to == "ambient":
        raise SceneError(path, f"{where}.close_pressure", "needs a `to` cavity (the pressure it closes at is that "
                         "cavity's); to stop a vent to ambient use close_time")



def _check_hydraulic_exchange(scene: Scene, e: ExchangeSpec, path, where: str) -> None:
    fluids = {c.name: c.fluid for c in scene.cavity}
    sides = [fluids[e.from_], fluids.get(e.to, "gas")]
    if "hydraulic" not in sides:
        return
    if e.to != "ambient" and len(set(sides)) > 1:
        raise SceneError(path, f"{where}.to", "an exchange cannot join a gas cavity and a hydraulic cavity")
    if law_keys.gas_only(e.law):
        usable = ", ".join(n for n in law_keys.names() if not law_keys.gas_only(n))
        raise SceneError(path, f"{where}.law", f"{e.law!r} is for gases; a hydraulic cavity uses one of {usable}")
    if e.two_way:
        raise SceneError(path, f"{where}.two_way", "ambient gas cannot flow into a hydraulic cavity")


def _check_inflator(inf: InflatorSpec, path, where: str) -> None:
    needed = {"mass_temperature": ("mass_flow", "temperature"), "tank_test": ("tank_pressure", "tank_volume",
                                                                            "temperature"),
              "pressure_mass": ("inflator_pressure", "mass_flow", "orifice_area"),
              "dual_pressure": ("inflator_pressure", "tank_pressure", "tank_volume", "orifice_area")}[inf.type]
    for k in needed:
        if not getattr(inf, k):
            raise SceneError(path, f"{where}.{k}", f"required for an inflator of type {inf.type!r}")
    if inf.temperature is not None:
        _require(inf.temperature, path, f"{where}.temperature", positive=True)
    if inf.mass_flow is not None:
        _require(inf.mass_flow, path, f"{where}.mass_flow", minimum=0.0)


def _require(table, path, where, **bounds):
    """Check a table's values against ``bounds`` (see Table.require), as a SceneError."""
    try:
        table.require(**bounds)
    except TableError as exc:
        raise SceneError(path, where, str(exc)) from None
