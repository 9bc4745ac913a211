"""The one validation of a scene, however it was made: read from TOML (:func:`cases.scene.files.scene_from_dict`),
built from dataclasses in Python (``build_model`` calls :func:`validate_scene`), or a sweep variant.

It checks every key's type and range (:func:`cases.scene.schema.check_fields`), the values that are not scalars
(:mod:`cases.scene.values`), the keys that involve each other (:mod:`cases.scene.checks`,
:mod:`cases.scene.contact`), the meshes (:mod:`cases.scene.meshes`) and the work budgets of ``[limits]``
before any work starts. Every failure is one :class:`~cases.scene.errors.SceneError` line naming the file and key.
"""
from __future__ import annotations

import math
import warnings
import weakref
from dataclasses import fields, is_dataclass
from types import SimpleNamespace

from cavity.caution import VentsimWarning, caution
from cavity.tables import Table

from cases.scene import law_keys
from cases.scene.errors import SceneError
from cases.scene.schema import check_fields, toml_name
from cases.scene.checks import check_cross_references
from cases.scene.contact import check_contacts
from cases.scene.blockage_rule import check_blockage
from cases.scene.meshes import check_meshes
from cases.scene.plausible import check_plausible, gas_temperatures
from cases.scene.values import composition, cp_coefficients, names_list, table_value, vector
from cases.scene.tables_io import read_table

__all__ = ["validate_scene", "ensure_valid", "register_specs", "PYTHON_SCENE"]

#: Lowest gas temperature a scene may give [K], and the largest uniform scale of a cavity mesh [-].
MIN_GAS_TEMPERATURE = 10.0
MAX_MESH_SCALE = 1e3
#: The "file" named in errors about a scene built in Python (no scene file).
PYTHON_SCENE = "<scene built in Python>"
_VALID: dict = {}  # id(scene) -> (weakref, warnings) of the scenes validated (a frozen scene cannot change after)

#: The spec classes, by name, registered by :mod:`cases.scene.files` when it is imported (this module does not import it).
SPECS: dict = {}


def register_specs(**classes) -> None:
    """Tell the validation the spec classes (``Scene=Scene, TimeSpec=TimeSpec, ...``)."""
    SPECS.update(classes)


_SPEC_LISTS = {"species": "SpeciesSpec", "cavity": "CavitySpec", "exchange": "ExchangeSpec", "body": "BodySpec",
               "contact": "ContactSpec"}
_TABLE_FILES = {"cavity": ("volume_table", "mesh_scale_table", "temperature_table"),
                "exchange": tuple(k.name for k in law_keys.of_kind("file")),
                "body": ("displacement_table", "rotation_table")}


def ensure_valid(scene) -> list:
    """:func:`validate_scene` unless this very scene object passed it before; returns the warnings (messages) it
    gave."""
    known = _VALID.get(id(scene))
    if known is not None and known[0]() is scene:
        return list(known[1])
    return validate_scene(scene)


def validate_scene(scene, raw: dict | None = None) -> list:
    """Check ``scene`` (a :class:`cases.scene.files.Scene`) in full; ``raw`` is its TOML dict when it came from a
    file (it tells a key that was given from a default). Returns the messages of the warnings it gave (the
    scene remembers them for ``build_model``)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", VentsimWarning)
        _validate(scene, raw)
    messages = list(dict.fromkeys(str(w.message) for w in caught if issubclass(w.category, VentsimWarning)))
    _VALID[id(scene)] = (weakref.ref(scene, lambda _, k=id(scene): _VALID.pop(k, None)), messages)
    return messages


def _validate(scene, raw) -> None:
    sc = SimpleNamespace(**SPECS)
    if not isinstance(scene, sc.Scene):
        raise SceneError(PYTHON_SCENE, "", f"expected a Scene, got {type(scene).__name__}")
    path = scene.path if scene._path else PYTHON_SCENE
    check_fields(scene, path, "")
    for name, cls in (("time", sc.TimeSpec), ("solver", sc.SolverSpec), ("ambient", sc.AmbientSpec),
                      ("limits", sc.LimitsSpec), ("blockage", sc.BlockageSpec), ("fe_run", sc.FeRunSpec),
                      ("units", sc.UnitsSpec)):
        _spec(getattr(scene, name), cls, path, name)
    for name, cls_name in _SPEC_LISTS.items():
        items = getattr(scene, name)
        if not isinstance(items, (tuple, list)):
            raise SceneError(path, name, f"expected a list of {cls_name} ([[{name}]] tables), got {items!r}")
        for i, item in enumerate(items):
            _spec(item, SPECS[cls_name], path, f"{name}[{i}]")
    _values(scene, path)
    if scene.units.system != "SI":
        raise SceneError(path, "units.system", f"a Scene made of spec dataclasses holds SI values, got "
                                               f"{scene.units.system!r}: give the unit system in the TOML file or "
                                               "to ventsim.Scene({..., 'units': {'system': ...}}), which convert")
    names_list(scene.units.unchecked, path, "units.unchecked", "key")
    _sanity(scene, path)
    check_cross_references(scene, path)
    if any(c.fluid == "real_gas" or c.energy == "wall" or any(i.tank_gas == "real_gas" for i in c.inflator)
           for c in scene.cavity):
        from cases.scene.realgas import check_real_gas

        check_real_gas(scene)
    check_contacts(scene, path, raw if raw is not None else _given(scene))
    check_blockage(scene, path)
    _budgets(scene, path)
    _held_tables(scene, path)
    check_meshes(scene, path)
    check_plausible(scene, path)


def _spec(obj, cls, path, where) -> None:
    if not isinstance(obj, cls):
        raise SceneError(path, where, f"expected a {cls.__name__}, got {type(obj).__name__}")
    check_fields(obj, path, where)
    for i, inf in enumerate(getattr(obj, "inflator", ()) if cls.__name__ == "CavitySpec" else ()):
        _spec(inf, SPECS["InflatorSpec"], path, f"{where}.inflator[{i}]")
    for i, m in enumerate(getattr(obj, "wall_materials", ()) if cls.__name__ == "CavitySpec" else ()):
        _spec(m, SPECS["WallMaterialSpec"], path, f"{where}.wall_materials[{i}]")


def _values(scene, path) -> None:
    """Compositions, vectors, name lists, cp coefficients and number-or-table values."""
    composition(scene.ambient.gas, path, "ambient.gas")
    for i, sp in enumerate(scene.species):
        if sp.cp:
            cp_coefficients(sp.cp, path, f"species[{i}].cp")
    for i, c in enumerate(scene.cavity):
        composition(c.gas, path, f"cavity[{i}].gas")
        names_list(c.wrapped_by, path, f"cavity[{i}].wrapped_by")
        for j, inf in enumerate(c.inflator):
            where = f"cavity[{i}].inflator[{j}]"
            composition(inf.gas, path, f"{where}.gas")
            for k in ("temperature", "mass_flow", "tank_pressure", "inflator_pressure"):
                table_value(getattr(inf, k), path, f"{where}.{k}")
    for i, b in enumerate(scene.body):
        where = f"body[{i}]"
        for k, n in (("sphere", 4), ("box", 6)):
            if getattr(b, k):
                vector(getattr(b, k), n, path, f"{where}.{k}")
        vector(b.axis, 3, path, f"{where}.axis", nonzero=True)
        vector(b.rotation_axis, 3, path, f"{where}.rotation_axis", nonzero=True)
        vector(b.rotation_centre, 3, path, f"{where}.rotation_centre")
    for i, e in enumerate(scene.exchange):
        where = f"exchange[{i}]"
        if e.leakage_box:
            vector(e.leakage_box, 6, path, f"{where}.leakage_box")
        names_list(e.blocked_by, path, f"{where}.blocked_by")
        for k in law_keys.of_kind("cd"):
            table_value(getattr(e, k.name), path, f"{where}.{k.name}", allow_none=False)
        for k in [k.name for k in law_keys.of_kind("table")] + ["amplitude"]:
            table_value(getattr(e, k), path, f"{where}.{k}")


def _positive_values(value, path, where, what) -> None:
    """A number or a Table whose values are all > 0 (``what``: '> 0') or >= 0."""
    ys = value.y if isinstance(value, Table) else (value,)
    for k, v in enumerate(ys):
        if not (v > 0 if what == "> 0" else v >= 0):
            row = f"row {k + 1} has {v!r}" if isinstance(value, Table) else f"got {v!r}"
            raise SceneError(path, where, f"{row}; expected {what}")


#: Smallest relative tolerance: 100 times the double machine epsilon (scipy's solve_ivp raises a smaller rtol to it).
MIN_RTOL = 100 * 2.220446049250313e-16


def _sanity(scene, path) -> None:
    """Ranges that involve one key but more than its sign."""
    s, t = scene.solver, scene.time
    if not MIN_RTOL <= s.rtol < 1.0:
        raise SceneError(path, "solver.rtol", f"expected a relative tolerance {MIN_RTOL:.3g} <= rtol < 1 (100 times "
                                              f"the machine epsilon: no step can be more accurate), got {s.rtol!r}")
    if not s.atol < 1.0:
        raise SceneError(path, "solver.atol", f"expected a fraction 0 <= atol < 1 of each unknown's scale, got "
                                              f"{s.atol!r}")
    if t.output_interval > t.end:
        raise SceneError(path, "time.output_interval", f"{t.output_interval!r} s is longer than time.end "
                                                       f"({t.end!r} s): no rows between t = 0 and the end")
    for i, c in enumerate(scene.cavity):
        if c.name == "ambient":
            raise SceneError(path, f"cavity[{i}].name", "'ambient' is reserved for the surroundings (exchange.to)")
    for name in ("cavity", "exchange", "body", "contact", "species"):
        for i, item in enumerate(getattr(scene, name)):
            if not item.name:
                raise SceneError(path, f"{name}[{i}].name", "expected a non-empty name")
    for i, e in enumerate(scene.exchange):
        for k in law_keys.of_kind("cd"):
            _positive_values(getattr(e, k.name), path, f"exchange[{i}].{k.name}", "> 0")
        if e.amplitude is not None:
            _positive_values(e.amplitude, path, f"exchange[{i}].amplitude", ">= 0")
        if e.effective_area is not None and not (e.leakage_surface or e.leakage_box or e.leakage_nodes):
            raise SceneError(path, f"exchange[{i}].effective_area", "needs leakage_surface, leakage_box or "
                                                                    "leakage_nodes (without one, give `area`)")
    _temperatures(scene, path)
    for i, b in enumerate(scene.body):
        if b.sphere and not b.sphere[3] > 0:
            raise SceneError(path, f"body[{i}].sphere", f"expected a radius > 0 [m], got {b.sphere[3]!r}")
        if b.box and not all(v > 0 for v in b.box[3:]):
            raise SceneError(path, f"body[{i}].box", f"expected extents lx, ly, lz > 0 [m], got {list(b.box[3:])}")


def _temperatures(scene, path) -> None:
    """Gas temperatures (ambient, gas cavities, inflator numbers and tables) of at least
    :data:`MIN_GAS_TEMPERATURE`: below it the ideal-gas energy solve has nothing to stand on."""
    low = gas_temperatures(scene)
    for where, T in low:
        if T < MIN_GAS_TEMPERATURE:
            raise SceneError(path, where, f"{T!r} K is below {MIN_GAS_TEMPERATURE:g} K, where no gas here is "
                                          "an ideal gas; temperatures are absolute [K]")


def _budgets(scene, path) -> None:
    """The work a scene asks for, against ``[limits]``: output rows, steps forced by max_step, table rows,
    sphere faces."""
    lim, t, s = scene.limits, scene.time, scene.solver
    dt = t.output_interval or t.end / 500.0
    rows = t.end / dt + 1 if dt > 0 else math.inf
    if rows > lim.output_rows:
        raise SceneError(path, "time.output_interval", f"{rows:.3g} rows of history.csv (time.end / "
                                                       f"output_interval) exceed limits.output_rows = "
                                                       f"{lim.output_rows}: raise the interval or the limit")
    if s.max_step and t.end / s.max_step > lim.steps:
        raise SceneError(path, "solver.max_step", f"time.end / max_step = {t.end / s.max_step:.3g} steps exceed "
                                                  f"limits.steps = {lim.steps}: raise max_step or the limit")
    for i, b in enumerate(scene.body):
        if b.sphere and 20 * 4 ** b.sphere_subdivisions > lim.mesh_faces:
            raise SceneError(path, f"body[{i}].sphere_subdivisions", f"{20 * 4 ** b.sphere_subdivisions} faces "
                                                                     f"exceed limits.mesh_faces = {lim.mesh_faces}")
    for where, table in _tables(scene, path):
        if len(table.x) > lim.table_rows:
            raise SceneError(path, where, f"{len(table.x)} rows exceed limits.table_rows = {lim.table_rows}: "
                                          "resample the table or raise the limit")
        if where.endswith(".mesh_scale_table") and not all(0 < v <= MAX_MESH_SCALE for v in table.y):
            raise SceneError(path, where, f"expected scale factors in (0, {MAX_MESH_SCALE:g}], got "
                                          f"{min(table.y)!r} to {max(table.y)!r}")


#: Tables of time whose last value is held to the end of the run (tank pressures are left out: held, they give
#: no flow, which is what a finished tank test means).
_TIME_TABLES = {"cavity": ("volume_table", "mesh_scale_table", "temperature_table"),
                "inflator": ("mass_flow", "temperature", "inflator_pressure"),
                "exchange": ("amplitude",) + tuple(k.name for k in law_keys.of_kind("table")),
                "body": ("displacement_table", "rotation_table")}


def _held_tables(scene, path) -> None:
    """A warning for every time table that ends before ``time.end`` with a non-zero last value (held constant
    from there, which a table's author rarely means)."""
    end = scene.time.end
    for where, table in _tables(scene, path):
        kind, key = where.rsplit(".", 1)
        kind = "inflator" if ".inflator[" in kind else kind.split("[")[0]
        if key not in _TIME_TABLES.get(kind, ()) or len(table.x) < 2:
            continue
        inflator = _inflator(scene, where) if kind == "inflator" else None
        start = inflator.start if inflator is not None else 0.0
        if key == "temperature" and _stops_by(inflator.mass_flow, table.x[-1]):
            continue  # the gas temperature after the inflator stopped flowing does not matter
        if start + table.x[-1] < end and table.y[-1] != 0.0:
            caution(f"{where}: the table ends at {start + table.x[-1]:.6g} s, before time.end = {end:.6g} s: its "
                    f"last value {table.y[-1]:.6g} is held from there; extend the table to time.end (or end it with 0) "
                    "if that is not meant")


def _inflator(scene, where: str):
    """The InflatorSpec at ``where`` (``cavity[i].inflator[j]...``)."""
    i, j = (int(part.split("]")[0]) for part in where.split("[")[1:3])
    return scene.cavity[i].inflator[j]


def _stops_by(mass_flow, t: float) -> bool:
    """A mass flow (a number or a Table) that is zero from ``t`` on (relative to the inflator's start)."""
    return isinstance(mass_flow, Table) and mass_flow.x[-1] <= t and mass_flow.y[-1] == 0.0 or mass_flow == 0.0


def _tables(scene, path):
    """(key, Table) of every table of the scene, given as a value or named as a CSV file."""
    for name in ("cavity", "exchange", "body"):
        for i, item in enumerate(getattr(scene, name)):
            where = f"{name}[{i}]"
            for f in fields(item):
                v = getattr(item, f.name)
                if isinstance(v, Table):
                    yield f"{where}.{toml_name(f)}", v
            for k in _TABLE_FILES[name]:
                if getattr(item, k):
                    yield f"{where}.{k}", read_table(scene.base / getattr(item, k), path, f"{where}.{k}", k,
                                                     columns=2)
            for j, inf in enumerate(getattr(item, "inflator", ())):
                for f in fields(inf):
                    v = getattr(inf, f.name)
                    if isinstance(v, Table):
                        yield f"{where}.inflator[{j}].{toml_name(f)}", v


def _given(scene) -> dict:
    """For a scene built in Python: the keys of each [[contact]] that differ from their defaults."""
    out = []
    for c in scene.contact:
        out.append({toml_name(f): 1 for f in fields(c) if f.init and is_dataclass(c)
                    and getattr(c, f.name) != f.default})
    return {"contact": out}
