"""Turn a validated Scene into the objects that compute: gas model, cavities, inflators, exchanges, network."""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from cavity.cavity import Cavity
from cavity.caution import VentsimWarning
from cavity.gas import GasModel
from cavity.hydraulic import HydraulicCavity
from cavity.tables import Table
from cavity.inflator import MassTemperatureInflator, TankTestInflator
from cavity.inflator_orifice import DualPressureInflator, PressureMassInflator
from cavity.integration import SolverOptions
from cavity.species import Species, builtin_species, species_from_coolprop
from cavity.volume import FixedVolume, MeshError, ScaledMeshVolume, SeriesVolume, TableVolume, closed_mesh_volume
from exchange.network.network import LEDGER_PER_CAVITY, LEDGER_PER_EXCHANGE, Network
from exchange.network.activation import Activation
from exchange.laws import registry
from exchange.network.vent import Ambient, Exchange

from cases.model.build_geometry import (Driver, build_bodies, build_contact, build_leak_area, build_wrapped_volume, cavity_mesh,
                             series_mesh)
from cases.scene.errors import SceneError
from cases.model.scene_network import BodyForces, SceneNetwork
from cases.scene.files import Scene
from cases.scene.validate import ensure_valid
from cases.scene.tables_io import read_table

__all__ = ["Model", "build_model", "unique_messages"]


@dataclass
class Model:
    """Everything needed to run a scene: the network, the solver options, the time axis, what was modelled."""

    scene: Scene
    network: Network
    options: SolverOptions
    output_times: np.ndarray
    modelled: dict
    geometry: dict | None = None
    warnings: list = field(default_factory=list)  # messages of the VentsimWarnings raised validating and building
    provenance: dict | None = None  # summary.json's "ventsim" entry, hashed once on the first run


def build_model(scene: Scene) -> Model:
    """Validate ``scene`` (:func:`cases.scene.validate.ensure_valid`, also for a scene built in Python) and build
    its model; the warnings given meanwhile are kept in ``Model.warnings``."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", VentsimWarning)
        early = ensure_valid(scene)
        model = _build(scene)
    model.warnings = unique_messages(early + [w for w in caught if issubclass(w.category, VentsimWarning)])
    return model


def unique_messages(caught) -> list:
    """The distinct messages of warnings (or strings), in order."""
    return list(dict.fromkeys(str(getattr(w, "message", w)) for w in caught))


def _build(scene: Scene) -> Model:
    gas = GasModel(_species(scene))
    amb = scene.ambient
    y_amb = gas.mass_fractions(amb.gas, molar=amb.gas_by_mole)
    ambient = Ambient(amb.pressure, amb.temperature, tuple(y_amb), gas.mixture(y_amb))
    t_end = scene.time.end
    geometric = bool(scene.body) or any(e.leakage_surface or e.leakage_box or e.leakage_nodes
                                        for e in scene.exchange) or any(c.mesh_series for c in scene.cavity)
    geo = _geometry(scene, t_end) if geometric else None
    cavities = tuple(_cavity(scene, gas, i, geo) for i in range(len(scene.cavity)))
    names = [c.name for c in cavities]
    exchanges = tuple(_exchange(scene, i, names) for i in range(len(scene.exchange)))
    if any(c.fluid == "real_gas" for c in scene.cavity):
        from cases.model.build_realgas import real_gas_laws

        exchanges = real_gas_laws(exchanges, cavities)
    if geo is None:
        network = Network(gas, cavities, exchanges, ambient)
    else:
        network = _scene_network(scene, gas, cavities, exchanges, ambient, geo)
    if any(e.law == "seal" for e in scene.exchange):
        from cases.model.build_seal import finish_seals

        finish_seals(scene, network, geo)
    dt = scene.time.output_interval or t_end / 500.0
    n = max(2, int(math.floor(t_end / dt + 1e-9)) + 1)
    grid = np.linspace(0.0, (n - 1) * dt, n)
    times = np.append(grid[grid < t_end - 1e-9 * dt], t_end)  # no second row a rounding error before/after t_end
    s = scene.solver
    options = SolverOptions(method=s.method, rtol=s.rtol, atol=(s.atol or s.rtol / 100) * _scales(network, t_end),
                            max_step=s.max_step or math.inf, max_steps=scene.limits.steps,
                            max_wall=scene.limits.wall or math.inf, integrator=s.integrator)
    modelled = _modelled(scene, cavities)
    if geo is not None and geo.get("seals"):
        from cases.results.seal_outputs import seal_summary

        modelled["seals"] = seal_summary(geo["seals"])
    return Model(scene, network, options, times, modelled, geo)


def _species(scene: Scene) -> tuple:
    """Species named anywhere in the scene, from [[species]] or built in (CoolProp fit, or Abaqus air)."""
    declared = {}
    for i, sp in enumerate(scene.species):
        where = f"species[{i}]"
        if sp.coolprop:
            try:
                declared[sp.name] = species_from_coolprop(sp.coolprop, label=sp.name)
            except ValueError as exc:
                raise SceneError(scene.path, f"{where}.coolprop", str(exc)) from None
        else:
            if not sp.molar_mass or not sp.cp:
                raise SceneError(scene.path, where, "give molar_mass [kg/mol] and cp [J/(mol K)...], or coolprop")
            try:
                declared[sp.name] = Species(sp.name, sp.molar_mass, tuple(sp.cp), source=f"{scene.path.name}")
            except (ValueError, TypeError) as exc:
                raise SceneError(scene.path, f"{where}.cp", str(exc)) from None
    used = {}
    for where, comp in _compositions(scene):
        for name in comp:
            used.setdefault(name, where)
    out = []
    for name, where in used.items():
        if name in declared:
            out.append(declared[name])
            continue
        try:
            out.append(builtin_species(name))
        except ValueError:
            raise SceneError(scene.path, f"{where}.{name}", f"unknown species {name!r}: declare it in [[species]] "
                                                            "(molar_mass and cp, or a CoolProp name)") from None
    return tuple(out)


def _compositions(scene: Scene):
    yield "ambient.gas", scene.ambient.gas
    for i, c in enumerate(scene.cavity):
        yield f"cavity[{i}].gas", c.gas
        for j, inf in enumerate(c.inflator):
            yield f"cavity[{i}].inflator[{j}].gas", inf.gas


def _volume(scene: Scene, i: int):
    c, where = scene.cavity[i], f"cavity[{i}]"
    if c.volume:
        return FixedVolume(c.volume)
    if c.volume_table:
        return TableVolume(read_table(scene.base / c.volume_table, scene.path, f"{where}.volume_table",
                                      "volume [m^3]"))
    import trimesh

    try:
        mesh = trimesh.load(scene.base / c.mesh, force="mesh", process=True)
        v = closed_mesh_volume(mesh, name=c.mesh)
    except MeshError as exc:
        raise SceneError(scene.path, f"{where}.mesh", str(exc)) from None
    except Exception as exc:  # trimesh raises many types for unreadable files
        raise SceneError(scene.path, f"{where}.mesh", f"cannot read mesh {c.mesh!r}: {exc}") from None
    if not c.mesh_scale_table:
        return FixedVolume(v)
    scale = read_table(scene.base / c.mesh_scale_table, scene.path, f"{where}.mesh_scale_table", "scale [-]")
    return ScaledMeshVolume(v, scale)


def _geometry(scene: Scene, t_end: float) -> dict:
    """Bodies, the θ driver, wrapped volumes and blocked areas of a scene with geometry."""
    bodies = build_bodies(scene)
    series = {c.name: series_mesh(scene, c.mesh_series, f"cavity[{i}].mesh_series", c.parts)
              for i, c in enumerate(scene.cavity) if c.mesh_series}
    meshes = {c.name: cavity_mesh(scene, i) for i, c in enumerate(scene.cavity) if c.mesh and not c.mesh_series}
    meshes.update({name: mesh for name, (_, mesh) in series.items()})
    extent = max([float(np.linalg.norm(m.extents)) for m in meshes.values()]
                 + [float(np.linalg.norm(b.mesh.extents)) for b, _ in bodies.values()] + [1e-3])
    driver = Driver(bodies, t_end, extent)
    volumes = {c.name: build_wrapped_volume(scene, i, meshes[c.name], driver)
               for i, c in enumerate(scene.cavity) if c.wrapped_by}
    for name, (s, mesh) in series.items():
        _closed(scene, name, mesh)
        volumes[name] = SeriesVolume.of(s.times, s.vertices, s.triangles())
    moving = {name: (s.times, s.vertices) for name, (s, _) in series.items()}
    areas, surfaces = zip(*[build_leak_area(scene, j, meshes, driver, moving)
                            for j in range(len(scene.exchange))]) if scene.exchange else ((), ())
    return {"bodies": bodies, "driver": driver, "volumes": volumes, "areas": areas, "surfaces": surfaces,
            "meshes": meshes}


def _closed(scene, name, mesh) -> None:
    """Frame 0 of a cavity's mesh series must bound a volume."""
    i = [c.name for c in scene.cavity].index(name)
    try:
        closed_mesh_volume(mesh, name=scene.cavity[i].mesh_series)
    except MeshError as exc:
        raise SceneError(scene.path, f"cavity[{i}].mesh_series", f"frame 0: {exc}") from None


def _scene_network(scene, gas, cavities, exchanges, ambient, geo):
    driver = geo["driver"]
    body, pushed, slope, forces, contact = None, None, None, BodyForces(), None
    if driver.dynamic is not None:
        body = driver.dynamic
        spec = next(b for b in scene.body if b.name == body.name)
        names = [c.name for c in scene.cavity]
        forces = BodyForces(spec.spring_stiffness, spec.spring_preload,
                            names.index(spec.pressure_cavity) if spec.pressure_cavity else None, spec.pressure_area)
        pushed = next((i for i, c in enumerate(scene.cavity) if body.name in c.wrapped_by), None)
        contact = build_contact(scene, geo, body)
        if pushed is None and forces.cavity is None and contact is None:
            raise SceneError(scene.path, "body", f"the dynamic body {body.name!r} wraps no cavity, has no "
                                                 "pressure_area and no contact: nothing pushes it")
        if pushed is not None:
            slope = geo["volumes"][scene.cavity[pushed].name].slope
    geo["contact"] = contact
    return SceneNetwork(gas, cavities, exchanges, ambient, areas=tuple(geo["areas"]), body=body, pushed=pushed,
                        volume_slope=slope, body_state=driver.state, forces=forces, contact=contact)


def _hydraulic(scene: Scene, i: int, volume) -> HydraulicCavity:
    c = scene.cavity[i]
    T = (read_table(scene.base / c.temperature_table, scene.path, f"cavity[{i}].temperature_table",
                    "temperature [K]") if c.temperature_table else Table((0.0,), (c.temperature,)))
    V0 = max(volume(0.0) + c.added_volume, c.minimum_volume)
    return HydraulicCavity(c.name, volume, c.density * V0, c.density, c.bulk_modulus, c.pressure, c.temperature, T,
                           c.thermal_expansion, c.added_volume, c.minimum_volume)


def _cavity(scene: Scene, gas: GasModel, i: int, geo=None):
    c = scene.cavity[i]
    volume = geo["volumes"][c.name] if geo and c.name in geo["volumes"] else _volume(scene, i)
    if c.fluid == "hydraulic":
        return _hydraulic(scene, i, volume)
    if c.fluid == "real_gas":
        from cases.model.build_realgas import real_gas_cavity

        return real_gas_cavity(scene, gas, i, volume, tuple(_inflator(gas, inf, scene) for inf in c.inflator))
    y = gas.mass_fractions(c.gas, molar=c.gas_by_mole)
    V0 = max(volume(0.0) + c.added_volume, c.minimum_volume)
    masses = gas.masses_at(y, c.pressure, c.temperature, V0)
    inflators = tuple(_inflator(gas, inf, scene) for inf in c.inflator)
    return Cavity(c.name, volume, tuple(masses), c.temperature, c.energy, c.added_volume, c.minimum_volume,
                  c.heat_transfer_coefficient, c.heat_transfer_area, scene.ambient.temperature, inflators)


def _inflator(gas: GasModel, inf, scene: Scene | None = None):
    y = gas.mass_fractions(inf.gas, molar=inf.gas_by_mole)
    mix = gas.mixture(y)  # 1 kg of inflator gas
    if inf.type == "tank_test" and inf.tank_gas == "real_gas":
        from cases.model.build_realgas import real_gas_tank_test

        return real_gas_tank_test(scene, gas, inf, tuple(y), mix)
    if inf.type == "mass_temperature":
        return MassTemperatureInflator(inf.name, inf.mass_flow, inf.temperature, tuple(y), mix, inf.start, inf.scale)
    if inf.type == "tank_test":
        return TankTestInflator(inf.name, inf.tank_pressure, inf.tank_volume, inf.temperature, tuple(y), mix,
                                inf.start, inf.scale)
    if inf.type == "pressure_mass":
        return PressureMassInflator(inf.name, inf.inflator_pressure, inf.mass_flow, inf.orifice_area,
                                    inf.discharge_coefficient, tuple(y), mix, inf.start, inf.scale)
    return DualPressureInflator(inf.name, inf.inflator_pressure, inf.tank_pressure, inf.tank_volume,
                                inf.orifice_area, inf.discharge_coefficient, tuple(y), mix, inf.start, inf.scale)


def _exchange(scene: Scene, i: int, names: list) -> Exchange:
    e, where = scene.exchange[i], f"exchange[{i}]"
    try:
        law = _law(scene, e, where)
    except ValueError as exc:
        raise SceneError(scene.path, f"{where}.{_law_key(e.law)}", str(exc)) from None
    pop = e.pop_pressure or None
    activation = None
    if e.open_time or e.close_time or pop or e.amplitude is not None or e.delta_area or e.close_pressure:
        activation = Activation(e.open_time, e.close_time or math.inf, pop, e.pop_hold_time, e.amplitude,
                                e.delta_area, e.close_pressure or None)
    return Exchange(e.name, names.index(e.from_), None if e.to == "ambient" else names.index(e.to), law, e.area,
                    e.two_way, activation)


def _law_key(law: str) -> str:
    """The scene key a law's construction error is about: its first key, else ``law``."""
    keys = registry.spec_of_name(law).keys
    return keys[0].name if keys else "law"


def _law(scene: Scene, e, where: str):
    """The flow-law object of an exchange spec: its registry entry built from the spec's values of the law's keys
    (:mod:`exchange.laws.registry`)."""
    spec = registry.spec_of_name(e.law)

    def table(key, what):
        return read_table(scene.base / getattr(e, key), scene.path, f"{where}.{key}", what)

    return spec.build(e.law, {k.name: getattr(e, k.name) for k in spec.keys}, table)


def _scales(network: Network, t_end: float) -> np.ndarray:
    """A magnitude for every unknown (kg for masses, J for energies), for absolute tolerances."""
    y0 = network.initial_state()
    scale = np.zeros_like(y0)
    mass_scales, energy_scales = [], []
    for cav, k in zip(network.cavities, network.offsets):
        ns = len(cav.initial_masses)
        inflated = sum(inf.mass_between(0.0, t_end) for inf in cav.inflators)
        m = float(np.sum(y0[k:k + ns])) + inflated
        h_in = max((inf.gas.enthalpy(inf.temperature(0.0)) for inf in cav.inflators), default=0.0)
        e = abs(y0[k + ns]) if not cav.isothermal else 0.0
        e = max(e, inflated * h_in, m * 1e5)
        scale[k:k + ns] = m
        if not cav.isothermal:
            scale[k + ns] = e
        wall = getattr(cav, "wall", None)
        if wall is not None:  # real gas with a wall: its layers' temperatures, heat to ambient
            scale[k + ns + 1:k + ns + 1 + wall.layers] = wall.initial_temperature
            scale[k + ns + 1 + wall.layers] = e
        mass_scales.append(m)
        energy_scales.append(e)
    if getattr(network, "body", None) is not None:
        k, v0 = network.body_offset, abs(network.body.motion.initial_velocity)
        scale[k:k + 2] = (max(v0 * t_end, 1e-3), max(v0, 1e-3))  # displacement [m], speed [m/s]
    m_all, e_all = max(mass_scales), max(energy_scales)
    j = network.ledger_offset
    for _ in network.exchanges:
        scale[j:j + LEDGER_PER_EXCHANGE] = (m_all, e_all)
        j += LEDGER_PER_EXCHANGE
    for m, e in zip(mass_scales, energy_scales):
        scale[j:j + LEDGER_PER_CAVITY] = (m, e, e, e)
        j += LEDGER_PER_CAVITY
    return scale


def _body_text(b) -> str:
    if b.mass:
        extra = (f", spring {b.spring_stiffness} N/m preloaded {b.spring_preload} N" if b.spring_stiffness or
                 b.spring_preload else "")
        extra += f", gauge pressure of {b.pressure_cavity!r} on {b.pressure_area} m^2" if b.pressure_area else ""
        return f"dynamic, mass {b.mass} kg, initial speed {b.initial_velocity} m/s, gravity {b.gravity} m/s^2{extra}"
    return "prescribed displacement table" if b.displacement_table else f"prescribed speed {b.velocity} m/s"


def _activation_text(e) -> str:
    parts = []
    if e.open_time or e.close_time:
        parts.append(f"open from {e.open_time} s" + (f" to {e.close_time} s" if e.close_time else ""))
    if e.pop_pressure:
        parts.append(f"pops at {e.pop_pressure} Pa" + (f" held {e.pop_hold_time} s" if e.pop_hold_time else ""))
    if e.close_pressure:
        parts.append(f"closes once {e.to} reaches {e.close_pressure} Pa")
    if e.amplitude is not None:
        parts.append("area amplitude table")
    if e.delta_area:
        parts.append("delta leakage area")
    return ", ".join(parts) or "always open"


def _modelled(scene: Scene, cavities) -> dict:
    """What this scene modelled (and therefore what it did not), for summary.json."""
    return {
        "cavities": {c.name: {"fluid": getattr(c, "kind", "gas"),
                              "energy": getattr(c, "energy", "isothermal liquid"), "volume": type(c.volume).__name__,
                              "inflators": [type(i).__name__ for i in c.inflators]} for c in cavities},
        "exchanges": {e.name: {"law": e.law, "from": e.from_, "to": e.to, "two_way": e.two_way,
                               "area": "leakage surface" if (e.leakage_surface or e.leakage_box) else "fixed",
                               "activation": _activation_text(e)} for e in scene.exchange},
        "gas": "ideal-gas mixture, species masses tracked" + ("; real gas (CoolProp HEOS) in " + ", ".join(
            c.name for c in cavities if getattr(c, "kind", "gas") == "realgas")
            if any(getattr(c, "kind", "gas") == "realgas" for c in cavities) else ""),
        "geometry": "none" if all(not c.mesh for c in scene.cavity) else "closed mesh volume"
                    + ("; cavity nodes wrapped around bodies" if any(c.wrapped_by for c in scene.cavity) else ""),
        "blockage": {e.name: f"leakage surface blocked by {list(e.blocked_by)}, tolerance {e.contact_tolerance} m"
                     for e in scene.exchange if e.blocked_by} or "not modelled",
        "bodies": {b.name: _body_text(b) for b in scene.body} or "none",
        "contact": {c.name: _contact_text(c) for c in scene.contact} or
                   "not modelled (bodies are rigid; cavity nodes are placed on them, no contact force model)",
    }


def _contact_text(c) -> str:
    law = {"hard": "hard (kinematic): held on the seat while the reaction is compressive, lift-off located as an "
                   "event at zero reaction, perfectly plastic impact",
           "linear": f"linear penalty, stiffness {c.stiffness} Pa/m",
           "exponential": f"softened exponential, p0 {c.pressure} Pa at zero clearance, zero at {c.clearance} m"}
    damping = {"none": "no damping",
               "coefficient": f"viscous damping mu0 {c.mu0} Pa s/m, {c.style} style"
                              + (f", clearance {c.damping_clearance} m, eta {c.eta}" if c.style == "standard" else ""),
               "critical_fraction": f"critical damping fraction {c.critical_fraction} (explicit style)"}
    tangent = c.tangent_fraction if c.tangent_fraction >= 0 else (1.0 if c.damping == "critical_fraction" or
                                                                   c.style == "explicit" else 0.0)
    seat = f"leakage surface of {c.seat!r}" if c.seat else f"mesh {c.seat_mesh!r}"
    return (f"{c.body!r} on {seat}: {law[c.pressure_overclosure]}; {damping[c.damping]}; tangent fraction "
            f"{tangent} (stored, no tangential forces); CPRESS per seat node in contact.npz")
