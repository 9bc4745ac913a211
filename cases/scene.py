"""Scene files: TOML validated once into frozen dataclasses (what to simulate, not how it is computed).

Every key's unit and meaning is declared next to it (``key(doc, unit)``); ``docs/scenes.md`` documents the
format. :func:`load_scene` turns any problem into a one-line :class:`SceneError` naming the file and the key.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, replace
from pathlib import Path

from cavity.integration import METHODS
from cavity.tables import TableError

from .errors import SceneError
from .schema import key, parse, suggest
from .tables_io import read_table, table_or_constant

__all__ = ["Scene", "BodySpec", "TimeSpec", "SolverSpec", "AmbientSpec", "SpeciesSpec", "CavitySpec", "InflatorSpec",
           "ExchangeSpec", "load_scene", "ENERGY_MODELS", "LAWS", "INFLATOR_TYPES"]

ENERGY_MODELS = ("adiabatic", "isothermal", "heat_loss")
LAWS = ("orifice", "fabric_leakage", "graefe", "mass_rate_leakage", "volume_rate_leakage", "mass_flux",
        "volume_flux", "bulk_viscosity", "linear_resistance")
INFLATOR_TYPES = ("mass_temperature", "tank_test", "pressure_mass", "dual_pressure")


@dataclass(frozen=True, kw_only=True)
class TimeSpec:
    end: float = key("end time of the run", "s", check="positive")
    output_interval: float = key("interval between rows of history.csv (0: end/500); does not affect the "
                                 "solution", "s", default=0.0, check="nonnegative")


@dataclass(frozen=True, kw_only=True)
class SolverSpec:
    method: str = key("scipy solve_ivp method", default="DOP853", choices=METHODS)
    rtol: float = key("relative tolerance", default=1e-8, check="positive")
    atol: float = key("absolute tolerance as a fraction of each unknown's scale (initial plus inflated mass, "
                      "and the matching energy); 0: rtol/100", default=0.0, check="nonnegative")
    max_step: float = key("largest step (0: unlimited)", "s", default=0.0, check="nonnegative")


@dataclass(frozen=True, kw_only=True)
class AmbientSpec:
    pressure: float = key("ambient pressure", "Pa", default=101325.0, check="positive")
    temperature: float = key("ambient temperature", "K", default=293.15, check="positive")
    gas: dict = key("composition {species = fraction}", default={"air": 1.0})
    gas_by_mole: bool = key("fractions in `gas` are molar, not by mass", default=False)


@dataclass(frozen=True, kw_only=True)
class SpeciesSpec:
    name: str = key("name used in `gas` tables")
    molar_mass: float = key("molar mass", "kg/mol", default=0.0, check="nonnegative")
    cp: tuple = key("molar cp polynomial a, b, c, d, e (, f): a + bT + cT² + dT³ + e/T² (+ fT⁴)",
                    "J/(mol K), J/(mol K²), ...", default=())
    coolprop: str = key("CoolProp fluid name; cp0(T) fitted once at load (instead of molar_mass and cp)",
                        default="")


@dataclass(frozen=True, kw_only=True)
class InflatorSpec:
    name: str = key("inflator name")
    type: str = key("inflator type", choices=INFLATOR_TYPES)
    temperature: object = key("mass_temperature, tank_test: inflator gas temperature, a number or a CSV table "
                              "(time [s], T [K])", "K", default=None)
    mass_flow: object = key("mass_temperature: CSV table (time [s], mass flow [kg/s]) or a number", "kg/s",
                            default=None)
    tank_pressure: object = key("tank_test: CSV table (time [s], tank pressure [Pa])", "Pa", default=None)
    tank_volume: float = key("tank_test, dual_pressure: tank volume", "m^3", default=0.0, check="nonnegative")
    inflator_pressure: object = key("pressure_mass, dual_pressure: CSV (time [s], inflator pressure [Pa])", "Pa",
                                    default=None)
    orifice_area: float = key("pressure_mass, dual_pressure: inflator orifice area", "m^2", default=0.0,
                              check="nonnegative")
    discharge_coefficient: float = key("pressure_mass, dual_pressure: inflator orifice Cd", default=1.0,
                                       check="positive")
    gas: dict = key("inflator gas composition {species = fraction}", default={"N2": 1.0})
    gas_by_mole: bool = key("fractions in `gas` are molar", default=False)
    start: float = key("activation time; tables are relative to it", "s", default=0.0, check="nonnegative")
    scale: float = key("multiplier on the mass flow", default=1.0, check="nonnegative")


@dataclass(frozen=True, kw_only=True)
class CavitySpec:
    name: str = key("cavity name (column prefix in history.csv)")
    pressure: float = key("initial pressure", "Pa", check="positive")
    temperature: float = key("initial temperature (constant when isothermal)", "K", check="positive")
    gas: dict = key("initial composition {species = fraction}", default={"air": 1.0})
    gas_by_mole: bool = key("fractions in `gas` are molar", default=False)
    energy: str = key("energy model", default="adiabatic", choices=ENERGY_MODELS)
    volume: float = key("rigid volume (give one of volume, volume_table, mesh)", "m^3", default=0.0,
                        check="nonnegative")
    volume_table: str = key("CSV table (time [s], volume [m^3])", default="")
    mesh: str = key("closed triangle mesh file (any format trimesh reads), coordinates in metres", default="")
    mesh_scale_table: str = key("CSV table (time [s], uniform scale factor [-]) applied to `mesh`", default="")
    added_volume: float = key("volume added to the geometric volume", "m^3", default=0.0, check="nonnegative")
    minimum_volume: float = key("volume used in the equation of state when V falls below it", "m^3",
                                default=0.0, check="nonnegative")
    heat_transfer_coefficient: float = key("heat_loss: h_c", "W/(m^2 K)", default=0.0, check="nonnegative")
    heat_transfer_area: float = key("heat_loss: area A", "m^2", default=0.0, check="nonnegative")
    inflator: tuple = key("inflators ([[cavity.inflator]] tables)", default=())
    wrapped_by: tuple = key("bodies whose surface the cavity mesh's nodes are placed on where they would "
                            "penetrate (the cushion wraps the impactor)", default=())
    fluid: str = key("what fills the cavity", default="gas", choices=("gas", "hydraulic"))
    density: float = key("hydraulic: density at the initial pressure and temperature", "kg/m^3", default=0.0,
                         check="nonnegative")
    bulk_modulus: float = key("hydraulic: bulk modulus K in p = p0 + K·ln(ρ/ρ_ref)", "Pa", default=0.0,
                              check="nonnegative")
    thermal_expansion: float = key("hydraulic: volumetric expansion α, ρ_ref(T) = ρ·exp(−α(T − T0))", "1/K",
                                   default=0.0, check="nonnegative")
    temperature_table: str = key("hydraulic: CSV (time [s], liquid temperature [K]); default: constant "
                                 "`temperature`", default="")


@dataclass(frozen=True, kw_only=True)
class ExchangeSpec:
    name: str = key("exchange name (column prefix in history.csv)")
    from_: str = key("first (upstream) cavity", toml="from")
    to: str = key("second cavity, or 'ambient'", default="ambient")
    law: str = key("flow law", default="orifice", choices=LAWS)
    area: float = key("flow area", "m^2", check="nonnegative", default=0.0)
    discharge_coefficient: object = key("orifice, fabric_leakage: Cd, a number or a CSV table of "
                                        "`discharge_coefficient_of`", default=1.0)
    discharge_coefficient_of: str = key("abscissa of a Cd table: upstream pressure [Pa] or time [s]",
                                        default="pressure", choices=("pressure", "time"))
    open_fraction: float = key("fabric_leakage: open (porous) fraction of the area", default=1.0, check="fraction")
    flc: float = key("graefe: leakage coefficient FLC", default=1.0, check="nonnegative")
    fac: float = key("graefe: area coefficient FAC", default=1.0, check="nonnegative")
    leakage_table: str = key("mass_rate_leakage / volume_rate_leakage: CSV (|Δp| [Pa], flow per area "
                             "[kg/(s m^2)] or [m^3/(s m^2)]); first row 0, 0", default="")
    leakage_table_extrapolation: str = key("beyond the last row", default="linear", choices=("linear", "constant"))
    flux: float = key("mass_flux [kg/(s m^2)] / volume_flux [m^3/(s m^2)]: prescribed flow per area, signed, "
                      "positive from `from` to `to`", default=0.0, check="finite")
    flux_amplitude: object = key("mass_flux / volume_flux: multiplier, a number or CSV (time [s], [-])",
                                 default=None)
    viscous_resistance: float = key("bulk_viscosity: c_v in Δp = c_v·v + c_h·ρ·v|v|", "Pa s/m", default=0.0,
                                    check="nonnegative")
    hydrodynamic_resistance: float = key("bulk_viscosity: c_h", default=0.0, check="nonnegative")
    conductance: float = key("linear_resistance: ṁ = G·A·Δp", "kg/(s Pa m^2)", default=0.0, check="nonnegative")
    two_way: bool = key("to ambient: let ambient gas flow back in when the cavity is below ambient",
                        default=False)
    open_time: float = key("activation: closed before this time", "s", default=0.0, check="nonnegative")
    close_time: float = key("activation: closed from this time (0: never)", "s", default=0.0,
                            check="nonnegative")
    pop_pressure: float = key("activation: opens once p_from − p_to exceeds this (and stays open); "
                              "0: no pop condition", "Pa", default=0.0, check="nonnegative")
    pop_hold_time: float = key("activation: how long p_from − p_to must stay above pop_pressure", "s",
                               default=0.0, check="nonnegative")
    amplitude: object = key("activation: area multiplier, a number or CSV (time [s], [-])", default=None)
    delta_area: bool = key("activation: current leakage area minus the area at activation (Abaqus DELTA "
                           "LEAKAGE AREA)", default=False)
    leakage_surface: str = key("leakage surface mesh file (triangles or quads, metres); the area is then its "
                               "unblocked area", default="")
    leakage_box: tuple = key("or: the faces of the `from` cavity's mesh inside this box: xmin, ymin, zmin, "
                             "xmax, ymax, zmax", "m", default=())
    blocked_by: tuple = key("bodies that block the leakage surface", default=())
    contact_tolerance: float = key("a leakage node is blocked when its gap to a body is <= this", "m",
                                   default=0.0, check="nonnegative")
    effective_area: float = key("with a leakage surface: area = effective_area·(1 − obstruction/total)", "m^2",
                                default=0.0, check="nonnegative")
    permeability: float = key("fraction of the blocked area that still leaks (Radioss Bvent)", default=0.0,
                              check="fraction")


@dataclass(frozen=True, kw_only=True)
class BodySpec:
    name: str = key("body name (named by `blocked_by` and `wrapped_by`)")
    mesh: str = key("body surface mesh file (metres; convex if it wraps a cavity)", default="")
    sphere: tuple = key("a sphere instead of a mesh: centre x, y, z and radius", "m", default=())
    sphere_subdivisions: int = key("icosphere subdivisions of `sphere` (4: 5120 faces)", default=4)
    box: tuple = key("a box instead of a mesh: centre x, y, z and extents lx, ly, lz", "m", default=())
    axis: tuple = key("direction of motion (normalised)", default=(0.0, 0.0, -1.0))
    velocity: float = key("prescribed constant speed along `axis`", "m/s", default=0.0, check="finite")
    displacement_table: str = key("prescribed CSV (time [s], displacement along axis [m])", default="")
    rotation_table: str = key("prescribed CSV (time [s], angle [deg]) about rotation_axis through rotation_centre",
                              default="")
    rotation_axis: tuple = key("axis of rotation_table", default=(0.0, 0.0, 1.0))
    rotation_centre: tuple = key("a point on the rotation axis", "m", default=(0.0, 0.0, 0.0))
    vertex_trajectory: str = key("prescribed .npz with 'times' (k,) [s] and 'vertices' (k, n, 3) [m] for the "
                                 "mesh's n vertices (e.g. from a finite-element run)", default="")
    mass: float = key("dynamic body: mass (0: prescribed motion)", "kg", default=0.0, check="nonnegative")
    initial_velocity: float = key("dynamic body: initial speed along `axis`", "m/s", default=0.0, check="finite")
    gravity: float = key("dynamic body: acceleration along `axis`", "m/s^2", default=0.0, check="finite")


@dataclass(frozen=True, kw_only=True)
class Scene:
    title: str = key("what the scene is", default="")
    time: TimeSpec = key("[time] table")
    solver: SolverSpec = key("[solver] table", default=SolverSpec())
    ambient: AmbientSpec = key("[ambient] table", default=AmbientSpec())
    species: tuple = key("[[species]] tables: user gas data", default=())
    cavity: tuple = key("[[cavity]] tables")
    exchange: tuple = key("[[exchange]] tables", default=())
    body: tuple = key("[[body]] tables: rigid bodies that block vents and wrap cavities", default=())
    _path: str = ""

    @property
    def path(self) -> Path:
        """The scene file."""
        return Path(self._path)

    @property
    def base(self) -> Path:
        """The folder relative file names are read from."""
        return self.path.parent


def load_scene(path) -> Scene:
    """Read and validate a scene file; every table it names is read and checked too."""
    path = Path(path)
    if not path.is_file():
        raise SceneError(path, "", "scene file does not exist")
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(path, "", f"not valid TOML: {exc}") from None
    return scene_from_dict(data, path)


def scene_from_dict(data: dict, path) -> Scene:
    """Validate an already-parsed scene (the TOML's dict); ``path`` anchors relative file names."""
    path = Path(path)
    base = path.parent

    def many(spec_cls, nested=None):
        def convert(value, where):
            if not isinstance(value, list):
                raise SceneError(path, where, "expected a list of tables ([[...]])")
            items = tuple(parse(spec_cls, v, path, f"{where}[{i}]", nested=nested) for i, v in enumerate(value))
            names = [getattr(it, "name") for it in items]
            dup = next((n for n in names if names.count(n) > 1), None)
            if dup is not None:
                raise SceneError(path, where, f"the name {dup!r} is used twice")
            return items
        return convert

    def composition(value, where):
        if not isinstance(value, dict) or not value:
            raise SceneError(path, where, "expected a table {species = fraction}")
        for k, v in value.items():
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v >= 0):
                raise SceneError(path, f"{where}.{k}", f"expected a fraction >= 0, got {v!r}")
        if sum(value.values()) <= 0:
            raise SceneError(path, where, "fractions sum to zero")
        return dict(value)

    def table(name):
        return lambda v, where: None if v is None else table_or_constant(v, base, path, where, name)

    def vector(n):
        def convert(v, where):
            if (not isinstance(v, list) or len(v) != n
                    or not all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in v)):
                raise SceneError(path, where, f"expected a list of {n} finite numbers, got {v!r}")
            return tuple(float(x) for x in v)
        return convert

    def names_list(v, where):
        if not isinstance(v, list) or not all(isinstance(x, str) for x in v):
            raise SceneError(path, where, f"expected a list of body names, got {v!r}")
        return tuple(v)

    def number_or_table(name):
        def convert(v, where):
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                if not (math.isfinite(v) and v > 0):
                    raise SceneError(path, where, f"expected a number > 0, got {v!r}")
                return float(v)
            return table_or_constant(v, base, path, where, name)
        return convert

    inflator_nested = {"gas": composition, "temperature": table("temperature [K]"),
                       "mass_flow": table("mass flow [kg/s]"), "tank_pressure": table("tank pressure [Pa]"),
                       "inflator_pressure": table("inflator pressure [Pa]")}
    cavity_nested = {"gas": composition, "inflator": many(InflatorSpec, inflator_nested), "wrapped_by": names_list}
    scene = parse(Scene, data, path, "", nested={
        "time": lambda v, w: parse(TimeSpec, v, path, w),
        "solver": lambda v, w: parse(SolverSpec, v, path, w),
        "ambient": lambda v, w: parse(AmbientSpec, v, path, w, nested={"gas": composition}),
        "species": many(SpeciesSpec, {"cp": lambda v, w: tuple(v)}),
        "cavity": many(CavitySpec, cavity_nested),
        "body": many(BodySpec, {"sphere": vector(4), "box": vector(6), "axis": vector(3),
                                "rotation_axis": vector(3), "rotation_centre": vector(3)}),
        "exchange": many(ExchangeSpec, {"leakage_box": vector(6), "blocked_by": names_list,"discharge_coefficient": number_or_table("discharge coefficient [-]"),
                                        "flux_amplitude": table("flux amplitude [-]"),
                                        "amplitude": table("area amplitude [-]")}),
    })
    scene = replace(scene, _path=str(path))
    _check_cross_references(scene, path)
    return scene


def _check_cross_references(scene: Scene, path) -> None:
    """Keys that refer to other things (cavity names, volume sources, per-type inflator keys) agree."""
    names = [c.name for c in scene.cavity]
    if not names:
        raise SceneError(path, "cavity", "a scene needs at least one [[cavity]]")
    for i, c in enumerate(scene.cavity):
        where = f"cavity[{i}]"
        given = [k for k in ("volume", "volume_table", "mesh") if getattr(c, k)]
        if len(given) != 1:
            raise SceneError(path, where, f"give exactly one of volume, volume_table, mesh (got {given or 'none'})")
        if c.mesh_scale_table and not c.mesh:
            raise SceneError(path, f"{where}.mesh_scale_table", "needs `mesh`")
        for f in ("volume_table", "mesh", "mesh_scale_table"):
            if getattr(c, f) and not (scene.base / getattr(c, f)).is_file():
                raise SceneError(path, f"{where}.{f}", f"file {getattr(c, f)!r} does not exist")
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
            if c.temperature_table and not (scene.base / c.temperature_table).is_file():
                raise SceneError(path, f"{where}.temperature_table", f"file {c.temperature_table!r} does not exist")
    _check_bodies(scene, path)
    for i, e in enumerate(scene.exchange):
        for side, value in (("from", e.from_), ("to", e.to)):
            if value not in names and not (side == "to" and value == "ambient"):
                raise SceneError(path, f"exchange[{i}].{side}", f"no cavity named {value!r}"
                                                                f"{suggest(value, names + ['ambient'])}")
        if e.from_ == e.to:
            raise SceneError(path, f"exchange[{i}].to", "an exchange joins two different sides")
        _check_exchange(scene, e, path, f"exchange[{i}]")
        _check_hydraulic_exchange(scene, e, path, f"exchange[{i}]")


LAW_KEYS = {"mass_rate_leakage": ("leakage_table",), "volume_rate_leakage": ("leakage_table",),
            "bulk_viscosity": ("viscous_resistance",), "linear_resistance": ("conductance",)}


def _check_bodies(scene: Scene, path) -> None:
    names = [b.name for b in scene.body]
    for i, b in enumerate(scene.body):
        shapes = [k for k in ("mesh", "sphere", "box") if getattr(b, k)]
        if len(shapes) != 1:
            raise SceneError(path, f"body[{i}]", f"give exactly one of mesh, sphere, box (got {shapes or 'none'})")
        if b.mesh and not (scene.base / b.mesh).is_file():
            raise SceneError(path, f"body[{i}].mesh", f"file {b.mesh!r} does not exist")
        if b.displacement_table:
            read_table(scene.base / b.displacement_table, path, f"body[{i}].displacement_table", "displacement [m]")
        if b.mass and (b.velocity or b.displacement_table or b.rotation_table or b.vertex_trajectory):
            raise SceneError(path, f"body[{i}].mass", "a dynamic body (mass > 0) has no prescribed motion")
        if b.vertex_trajectory and (b.velocity or b.displacement_table or b.rotation_table):
            raise SceneError(path, f"body[{i}].vertex_trajectory", "replaces velocity, displacement and rotation")
        for k in ("rotation_table", "vertex_trajectory"):
            if getattr(b, k) and not (scene.base / getattr(b, k)).is_file():
                raise SceneError(path, f"body[{i}].{k}", f"file {getattr(b, k)!r} does not exist")
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
                raise SceneError(path, where, f"no body named {n!r}{suggest(n, names)}")


def _check_exchange(scene: Scene, e: ExchangeSpec, path, where: str) -> None:
    for k in LAW_KEYS.get(e.law, ()):
        if not getattr(e, k):
            raise SceneError(path, f"{where}.{k}", f"required for law {e.law!r}")
    if e.leakage_table and not (scene.base / e.leakage_table).is_file():
        raise SceneError(path, f"{where}.leakage_table", f"file {e.leakage_table!r} does not exist")
    if e.law in ("mass_flux", "volume_flux") and e.flux == 0.0:
        raise SceneError(path, f"{where}.flux", f"required (non-zero) for law {e.law!r}")
    geometric = bool(e.leakage_surface or e.leakage_box)
    if e.leakage_surface and e.leakage_box:
        raise SceneError(path, f"{where}.leakage_box", "give leakage_surface or leakage_box, not both")
    if e.leakage_surface and not (scene.base / e.leakage_surface).is_file():
        raise SceneError(path, f"{where}.leakage_surface", f"file {e.leakage_surface!r} does not exist")
    if e.leakage_box and not next(c for c in scene.cavity if c.name == e.from_).mesh:
        raise SceneError(path, f"{where}.leakage_box", "selects faces of the `from` cavity's mesh: it has none")
    if e.blocked_by and not geometric:
        raise SceneError(path, f"{where}.blocked_by", "needs leakage_surface or leakage_box")
    if geometric and e.blocked_by and not e.contact_tolerance > 0:
        raise SceneError(path, f"{where}.contact_tolerance", "expected a tolerance > 0 [m] with blocked_by")
    if geometric and e.area:
        raise SceneError(path, f"{where}.area", "the area comes from the leakage surface: use effective_area")
    if not geometric and not e.area > 0:
        raise SceneError(path, f"{where}.area", "expected a flow area > 0 [m^2]")
    if e.close_time and e.close_time <= e.open_time:
        raise SceneError(path, f"{where}.close_time", f"must be later than open_time ({e.open_time} s)")
    if e.pop_hold_time and not e.pop_pressure:
        raise SceneError(path, f"{where}.pop_hold_time", "needs pop_pressure")


PNEUMATIC_LAWS = ("orifice", "fabric_leakage")


def _check_hydraulic_exchange(scene: Scene, e: ExchangeSpec, path, where: str) -> None:
    fluids = {c.name: c.fluid for c in scene.cavity}
    sides = [fluids[e.from_], fluids.get(e.to, "gas")]
    if "hydraulic" not in sides:
        return
    if e.to != "ambient" and len(set(sides)) > 1:
        raise SceneError(path, f"{where}.to", "an exchange cannot join a gas cavity and a hydraulic cavity")
    if e.law in PNEUMATIC_LAWS:
        raise SceneError(path, f"{where}.law", f"{e.law!r} is for gases; a hydraulic cavity uses "
                                               "volume_rate_leakage, mass_rate_leakage, bulk_viscosity, "
                                               "linear_resistance or a flux")
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
