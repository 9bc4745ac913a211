"""Scene files: TOML validated once into frozen dataclasses (what to simulate, not how it is computed).

Every key's unit and meaning is declared next to it (``key(doc, unit)``); ``docs/scenes.md`` documents the
format. :func:`load_scene` turns any problem into a one-line :class:`SceneError` naming the file and the key.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, replace
from pathlib import Path
from types import SimpleNamespace

from cavity.integration import METHODS

from cases.scene import law_keys
from cases.scene.errors import SceneError
from cases.scene.schema import key, parse
from cases.scene.contact import ContactSpec
from cases.scene.blockage_rule import BlockageSpec, FeRunSpec, part_ids
from cases.scene.validate import register_specs, validate_scene
from cases.scene.values import composition as _composition, cp_coefficients, names_list as _names, vector as _vector
from cases.scene.tables_io import read_text, table_or_constant
from cases.scene.walls import WallMaterialSpec
from cases.scene.units import UnitsSpec, to_si

__all__ = ["read_scene_data", "Scene", "BodySpec", "TimeSpec", "SolverSpec", "AmbientSpec", "SpeciesSpec", "CavitySpec", "InflatorSpec",
           "ExchangeSpec", "ContactSpec", "LimitsSpec", "UnitsSpec", "load_scene", "ENERGY_MODELS", "LAWS", "INFLATOR_TYPES"]

ENERGY_MODELS = ("adiabatic", "isothermal", "heat_loss", "wall")
LAWS = law_keys.names()  # the law registry's (exchange.laws.registry)
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
    integrator: str = key("'compiled': DOP853 in one numba call; 'scipy': solve_ivp steps the same compiled "
                          "kernels with DOP853 too (a second implementation, to cross-check a run); the other "
                          "methods always step through solve_ivp", default="compiled", choices=("compiled", "scipy"))


@dataclass(frozen=True, kw_only=True)
class LimitsSpec:
    """Work budgets, checked before the work starts: exceeding one is a clear error, never a hang."""

    output_rows: int = key("most rows of history.csv (time.end / time.output_interval + 1)", default=1_000_000,
                           bounds=(2, 10 ** 9))
    table_rows: int = key("most rows of any CSV table", default=100_000, bounds=(1, 10 ** 9))
    mesh_faces: int = key("most faces of any mesh (a body's sphere: 20·4^subdivisions)", default=2_000_000,
                          bounds=(1, 10 ** 9))
    steps: int = key("most integration steps of a run (a stiff scene stops here with advice)", default=2_000_000,
                     bounds=(1, 10 ** 10))
    wall: float = key("most wall time of the integration and its history rows (0: unlimited; `ventsim run "
                      "--max-wall` overrides)", "s", default=3600.0, check="nonnegative")


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
    tank_gas: str = key("tank_test: the tank's gas, 'ideal' (ṁ = V·ṗ/(γ·R·T_in)) or 'real_gas' (CoolProp HEOS of "
                        "the inflator's `gas`, one species or a mixture of fixed composition, docs/realgas.md)",
                        default="ideal", choices=("ideal", "real_gas"))
    tank_temperature: float = key("tank_test with tank_gas = 'real_gas': initial tank temperature", "K",
                                  default=0.0, check="nonnegative")


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
    mesh_scale_table: str = key("CSV table (time [s], uniform scale factor [-]) applied to `mesh` (about the "
                                "origin; a leakage_box vent scales with it)", default="")
    mesh_series: str = key("the cavity surface as a series of closed meshes (.pvd, .xdmf or .npz), linear in "
                           "time between frames: exact volume; a leakage_box vent moves and stretches with it",
                           default="")
    parts: tuple = key("mesh_series from an LS-DYNA d3plot: the part ids of the surface", default=())
    added_volume: float = key("volume added to the geometric volume", "m^3", default=0.0, check="nonnegative")
    minimum_volume: float = key("volume used in the equation of state when V falls below it", "m^3",
                                default=0.0, check="nonnegative")
    heat_transfer_coefficient: float = key("heat_loss: h_c", "W/(m^2 K)", default=0.0, check="nonnegative")
    heat_transfer_area: float = key("heat_loss: area A", "m^2", default=0.0, check="nonnegative")
    inflator: tuple = key("inflators ([[cavity.inflator]] tables)", default=())
    wrapped_by: tuple = key("bodies whose surface the cavity mesh's nodes are placed on where they would "
                            "penetrate (the cushion wraps the impactor)", default=())
    fluid: str = key("what fills the cavity: an ideal gas, a liquid, or a real gas (CoolProp HEOS equation of "
                     "state of `gas`: one species, or a mixture of fixed composition by `gas_by_mole` mole or mass "
                     "fractions, docs/realgas.md)", default="gas",
                     choices=("gas", "hydraulic", "real_gas"))
    density: float = key("hydraulic: density at the initial pressure and temperature", "kg/m^3", default=0.0,
                         check="nonnegative")
    bulk_modulus: float = key("hydraulic: bulk modulus K in p = p0 + K·ln(ρ/ρ_ref)", "Pa", default=0.0,
                              check="nonnegative")
    thermal_expansion: float = key("hydraulic: volumetric expansion α, ρ_ref(T) = ρ·exp(−α(T − T0))", "1/K",
                                   default=0.0, check="nonnegative")
    temperature_table: str = key("hydraulic: CSV (time [s], liquid temperature [K]); default: constant "
                                 "`temperature`", default="")
    wall_mass: float = key("real_gas, energy = 'wall': mass of the lumped vessel wall", "kg", default=0.0,
                           check="nonnegative")
    wall_heat_capacity: float = key("wall: specific heat of the wall material", "J/(kg K)", default=0.0,
                                    check="nonnegative")
    wall_inner_area: float = key("wall: inner (wetted) area", "m^2", default=0.0, check="nonnegative")
    wall_outer_area: float = key("wall: outer area (0: wall_inner_area)", "m^2", default=0.0, check="nonnegative")
    wall_inner_h: float = key("wall: inner heat transfer coefficient (0: natural convection Nu = C·Ra^n over "
                              "wall_length, docs/realgas.md)", "W/(m^2 K)", default=0.0, check="nonnegative")
    wall_outer_h: float = key("wall: outer heat transfer coefficient to the ambient temperature (0: insulated)",
                              "W/(m^2 K)",
                              default=0.0, check="nonnegative")
    wall_length: float = key("wall: length of the natural-convection correlation (vessel length if vertical, "
                             "diameter if horizontal)", "m", default=0.0, check="nonnegative")
    wall_temperature: float = key("wall: initial wall temperature (0: the gas temperature)", "K", default=0.0,
                                  check="nonnegative")
    wall_orientation: str = key("wall: natural-convection correlation, 'vertical' (Geankoplis, vertical planes and "
                                "cylinders, over wall_length; HydDown's) or 'horizontal' (Morgan, horizontal "
                                "cylinder, wall_length = the diameter)", default="vertical",
                                choices=("vertical", "horizontal"))
    wall_jet_diameter: float = key("wall: diameter d in the Reynolds number 4·ṁ_in/(π·d·μ) of a forced-convection "
                                   "term 0.56·Re^0.67 added to the inner Nusselt number while gas flows in "
                                   "(HydDown's filling correlation, d = the vessel diameter); 0: none", "m",
                                   default=0.0, check="nonnegative")
    wall_layers: int = key("wall: layers through the thickness; 1: lumped (one temperature); more: 1-D conduction "
                           "with wall_conductivity and wall_thickness (docs/realgas.md)", default=1,
                           bounds=(1, 200))
    wall_conductivity: float = key("wall: thermal conductivity of the wall material (wall_layers > 1)", "W/(m K)",
                                   default=0.0, check="nonnegative")
    wall_thickness: float = key("wall: thickness (wall_layers > 1)", "m", default=0.0, check="nonnegative")
    wall_materials: tuple = key("wall: the materials through its thickness, inner to outer, each with its own "
                                "cells ([[cavity.wall_materials]]: a liner and a composite shell; replaces "
                                "wall_mass, wall_heat_capacity, wall_layers, wall_conductivity, wall_thickness)",
                                default=())


@dataclass(frozen=True, kw_only=True)
class _ExchangeHead:
    name: str = key("exchange name (column prefix in history.csv)")
    from_: str = key("first (upstream) cavity", toml="from")
    to: str = key("second cavity, or 'ambient'", default="ambient")
    law: str = key("flow law", default="orifice", choices=LAWS)
    area: float = key("flow area", "m^2", check="nonnegative", default=0.0)


@dataclass(frozen=True, kw_only=True)
class ExchangeSpec(law_keys.LawKeys, _ExchangeHead):  # the laws' keys (cases.scene.law_keys) after `area`
    two_way: bool = key("to ambient: let ambient gas flow back in when the cavity is below ambient",
                        default=False)
    open_time: float = key("activation: closed before this time", "s", default=0.0, check="nonnegative")
    close_time: float = key("activation: closed from this time (0: never)", "s", default=0.0,
                            check="nonnegative")
    pop_pressure: float = key("activation: opens once p_from − p_to exceeds this (and stays open); "
                              "0: no pop condition", "Pa", default=0.0, check="nonnegative")
    pop_hold_time: float = key("activation: how long p_from − p_to must stay above pop_pressure", "s",
                               default=0.0, check="nonnegative")
    close_pressure: float = key("activation: closes for good once the pressure of the `to` cavity reaches this (a "
                                "filling stopped at its target pressure); 0: never", "Pa", default=0.0,
                                check="nonnegative")
    amplitude: object = key("activation: area multiplier, a number or CSV (time [s], [-])", default=None)
    delta_area: bool = key("activation: current leakage area minus the area at activation (Abaqus DELTA "
                           "LEAKAGE AREA)", default=False)
    leakage_surface: str = key("leakage surface mesh file (triangles or quads, metres), or a mesh series "
                               "(.pvd, .xdmf, .npz, d3plot) moving on its own; its area is its unblocked area",
                               default="")
    parts: tuple = key("leakage_surface from an LS-DYNA d3plot: the part ids of the surface", default=())
    leakage_box: tuple = key("or: the faces of the `from` cavity's mesh inside this box: xmin, ymin, zmin, "
                             "xmax, ymax, zmax", "m", default=())
    blocked_by: tuple = key("bodies that block the leakage surface", default=())
    contact_tolerance: float = key("a leakage node is blocked when its gap to a body is <= this", "m",
                                   default=0.0, check="nonnegative")
    effective_area: float = key("with a leakage surface: area = effective_area·(1 − obstruction/total) "
                                "(omitted: the surface's own area)", "m^2", default=None, check="positive")
    permeability: float = key("fraction of the blocked area that still leaks (Radioss Bvent)", default=0.0,
                              check="fraction")
    leakage_nodes: str = key("or: a node-based leakage surface, CSV of x, y, z [m] and optionally area [m^2] per "
                             "node; blocked fraction = active nodes / all (or their share of the area)", default="")
    edge_contact: bool = key("also block both nodes of a leakage edge within the tolerance of a blocker's "
                             "feature edge (edge-to-edge contact)", default=False)
    self_contact: bool = key("the `from` cavity's own surface also blocks its leakage_box surface (faces "
                             "sharing the node are ignored)", default=False)
    penetration_depth: float = key("nodes behind an open blocking sheet count as in contact up to this depth "
                                   "(0: the distance rule only; inside a closed blocker: any depth)", "m",
                                   default=0.0, check="nonnegative")


@dataclass(frozen=True, kw_only=True)
class BodySpec:
    name: str = key("body name (named by `blocked_by` and `wrapped_by`)")
    mesh: str = key("body surface mesh file (metres; convex if it wraps a cavity)", default="")
    sphere: tuple = key("a sphere instead of a mesh: centre x, y, z and radius", "m", default=())
    sphere_subdivisions: int = key("icosphere subdivisions of `sphere` (4: 5120 faces)", default=4, bounds=(0, 9))
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
    mesh_series: str = key("prescribed series of the body's mesh (.pvd with .vtu/.vtp frames, .xdmf, or .npz "
                           "with 'times', 'vertices', 'faces', or d3plot), linear in time between frames", default="")
    parts: tuple = key("mesh_series from an LS-DYNA d3plot: the part ids of the body", default=())
    mass: float = key("dynamic body: mass (0: prescribed motion)", "kg", default=0.0, check="nonnegative")
    initial_velocity: float = key("dynamic body: initial speed along `axis`", "m/s", default=0.0, check="finite")
    gravity: float = key("dynamic body: acceleration along `axis`", "m/s^2", default=0.0, check="finite")
    spring_stiffness: float = key("dynamic body: spring stiffness k; spring force −(spring_preload + k·s) along "
                                  "`axis`", "N/m", default=0.0, check="nonnegative")
    spring_preload: float = key("dynamic body: spring force against `axis` at s = 0 (a poppet's preload)", "N",
                                default=0.0, check="nonnegative")
    pressure_area: float = key("dynamic body: area on which the gauge pressure of `pressure_cavity` pushes it "
                               "along `axis`", "m^2", default=0.0, check="nonnegative")
    pressure_cavity: str = key("dynamic body: the cavity whose gauge pressure acts on `pressure_area`",
                               default="")


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
    contact: tuple = key("[[contact]] tables: contact of the dynamic body with a seat surface (docs/contact.md)",
                         default=())
    limits: LimitsSpec = key("[limits] table: work budgets", default=LimitsSpec())
    blockage: BlockageSpec = key("[blockage] table: an FE code's blockage rule", default=BlockageSpec())
    fe_run: FeRunSpec = key("[fe_run] table: the FE run replayed (units, abstat)", default=FeRunSpec())
    units: UnitsSpec = key("[units] table: the scene's unit system and its plausibility checks",
                           default=UnitsSpec())
    _path: str = ""

    @property
    def path(self) -> Path:
        """The scene file."""
        return Path(self._path)

    @property
    def base(self) -> Path:
        """The folder relative file names are read from."""
        return self.path.parent


def read_scene_data(path) -> dict:
    """The parsed TOML of a scene file, before validation (SceneError if missing or not TOML)."""
    path = Path(path)
    try:
        return tomllib.loads(read_text(path, path, "", "scene file"))
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(path, "", f"not valid TOML: {exc}") from None


def load_scene(path) -> Scene:
    """Read and validate a scene file; every table it names is read and checked too."""
    return scene_from_dict(read_scene_data(path), Path(path))


def _converters(path: Path, base: Path) -> SimpleNamespace:
    """The value converters of a scene file at ``path`` (relative file names resolve against ``base``)."""

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
        return _composition(value, path, where)

    def table(name):
        return lambda v, where: None if v is None else table_or_constant(v, base, path, where, name)

    def vector(n, nonzero=False):
        return lambda v, where: _vector(v, n, path, where, nonzero=nonzero)

    def names_list(v, where):
        return _names(v, path, where)

    def number_or_table(name):
        def convert(v, where):
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                if not (math.isfinite(v) and v > 0):
                    raise SceneError(path, where, f"expected a number > 0, got {v!r}")
                return float(v)
            return table_or_constant(v, base, path, where, name)
        return convert

    return SimpleNamespace(many=many, composition=composition, table=table, vector=vector, names_list=names_list,
                           number_or_table=number_or_table)


def scene_from_dict(data: dict, path) -> Scene:
    """Validate an already-parsed scene (the TOML's dict); ``path`` anchors relative file names."""
    path = Path(path)
    c = _converters(path, path.parent)
    many, composition, table, vector = c.many, c.composition, c.table, c.vector
    names_list, number_or_table = c.names_list, c.number_or_table
    inflator_nested = {"gas": composition, "temperature": table("temperature [K]"),
                       "mass_flow": table("mass flow [kg/s]"), "tank_pressure": table("tank pressure [Pa]"),
                       "inflator_pressure": table("inflator pressure [Pa]")}
    cavity_nested = {"gas": composition, "inflator": many(InflatorSpec, inflator_nested), "wrapped_by": names_list,
                     "wall_materials": many(WallMaterialSpec)}
    scene = parse(Scene, data, path, "", nested={
        "time": lambda v, w: parse(TimeSpec, v, path, w),
        "solver": lambda v, w: parse(SolverSpec, v, path, w),
        "ambient": lambda v, w: parse(AmbientSpec, v, path, w, nested={"gas": composition}),
        "species": many(SpeciesSpec, {"cp": lambda v, w: cp_coefficients(v, path, w)}),
        "cavity": many(CavitySpec, {**cavity_nested, "parts": part_ids(path)}),
        "body": many(BodySpec, {"sphere": vector(4), "box": vector(6), "axis": vector(3, True), "parts": part_ids(path),
                                "rotation_axis": vector(3, True), "rotation_centre": vector(3)}),
        "contact": many(ContactSpec),
        "limits": lambda v, w: parse(LimitsSpec, v, path, w),
        "blockage": lambda v, w: parse(BlockageSpec, v, path, w),
        "fe_run": lambda v, w: parse(FeRunSpec, v, path, w),
        "units": lambda v, w: parse(UnitsSpec, v, path, w, nested={"unchecked": lambda u, x: _names(u, path, x, "key")}),
        "exchange": many(ExchangeSpec, {"leakage_box": vector(6), "blocked_by": names_list, "parts": part_ids(path),
                                        "amplitude": table("area amplitude [-]"),
                                        **{k.name: number_or_table(law_keys.label(k)) for k in law_keys.of_kind("cd")},
                                        **{k.name: table(law_keys.label(k)) for k in law_keys.of_kind("table")}}),
    })
    scene = to_si(replace(scene, _path=str(path)), path)
    validate_scene(scene, data)
    return scene


register_specs(Scene=Scene, TimeSpec=TimeSpec, SolverSpec=SolverSpec, AmbientSpec=AmbientSpec, LimitsSpec=LimitsSpec,
               SpeciesSpec=SpeciesSpec, CavitySpec=CavitySpec, InflatorSpec=InflatorSpec, ExchangeSpec=ExchangeSpec,
               BodySpec=BodySpec, ContactSpec=ContactSpec, WallMaterialSpec=WallMaterialSpec,
               BlockageSpec=BlockageSpec, FeRunSpec=FeRunSpec, UnitsSpec=UnitsSpec)
