"""Plausibility of a scene's dimensional values (in SI, after :mod:`cases.scene.units`): the unit mistakes that
would otherwise run silently or for minutes, each a one-line :class:`SceneError` naming the file, the key, the
value and the likely mistake.

- an absolute pressure below 1 kPa (a pressure in bar or MPa, or a gauge pressure), or above 10 GPa (a pressure in
  Pa in an mm-t-s or mm-kg-ms scene);
- a gas temperature below 150 K (a temperature in °C) or above 10,000 K;
- an exchange or inflator orifice area larger than twice its cavity's mesh surface, or (a cavity given by its
  volume) a thousand times the surface of a sphere of that volume (an area in mm² or cm²);
- a cavity volume above 100 m³, or one whose run would change less than 0.3 % of its gas (its inflator tables'
  mass and its vents' time constant: :mod:`cases.scene.plausible_volume`) (litres or mm³);
- a mesh, a sphere, a box or a leakage box wider than 50 m, a cavity mesh enclosing more than 100 m³, a contact
  tolerance above 1 m (millimetres);
- a hydraulic cavity's bulk modulus outside 1e6 to 1e12 Pa or density outside 10 to 1e5 kg/m³ (another unit).

``[units] check = false`` turns them off; ``[units] unchecked = ["cavity[0].pressure"]`` exempts keys.
"""
from __future__ import annotations

import math

from cavity.tables import Table

from cases.scene.errors import SceneError
from cases.scene.plausible_volume import MIN_RESPONSE, check_responses
from cases.scene.unit_systems import SYSTEMS

__all__ = ["check_plausible", "gas_temperatures", "MIN_PRESSURE", "MIN_TEMPERATURE", "MAX_VOLUME", "MAX_EXTENT",
           "MIN_RESPONSE"]

#: Lowest absolute pressure [Pa], gas temperature [K], largest cavity volume [m^3] and mesh or body extent [m]
#: a scene may give without an explicit override.
MIN_PRESSURE, MIN_TEMPERATURE, MAX_VOLUME, MAX_EXTENT = 1e3, 150.0, 100.0, 50.0
MAX_TOLERANCE = 1.0
#: Highest absolute pressure [Pa] without override: 10 GPa, over ten times a hydraulic system's (700 MPa); the SI
#: value of a pressure written in Pa in an mm-t-s scene is a million times it (1 bar: 1e11 Pa).
MAX_PRESSURE = 1e10
#: Surface of a sphere of volume V is SPHERE·V^(2/3), the least surface that can enclose V.
SPHERE = (36.0 * math.pi) ** (1.0 / 3.0)
#: An area may be at most this many times its cavity's mesh surface, or the surface of a sphere of its volume (a
#: flat cavity, a seal's gap 1e-5 of its width, has 1000 times the sphere's surface).
MESH_AREA_FACTOR, SPHERE_AREA_FACTOR = 2.0, 1000.0
#: Highest gas temperature [K] and lowest molar mass [kg/mol] (atomic hydrogen: 1.008e-3) taken without override.
MAX_TEMPERATURE, MIN_MOLAR_MASS = 1e4, 1e-3


class _Checker:
    def __init__(self, scene, path):
        self.scene, self.path, self.units = scene, path, scene.units
        self.system = SYSTEMS.get(scene.units.given or "SI", SYSTEMS["SI"])

    def fail(self, where: str, message: str) -> None:
        if where in self.units.unchecked:
            return
        raise SceneError(self.path, where, f"{message}; if it is meant, add {where!r} to [units] unchecked (or "
                                           "set [units] check = false)")

    def given(self, value: float, exps: tuple, unit: str) -> str:
        """The value as the file gave it (in its unit system) and in SI."""
        if self.system.name == "SI":
            return f"{value:.6g} {unit}"
        return f"{value / self.system.scale(exps):.6g} in {self.system.name} ({value:.6g} {unit})"


def check_plausible(scene, path) -> None:
    """SceneError on the first implausible dimensional value of ``scene`` (see the module's list)."""
    if not scene.units.check:
        return
    c = _Checker(scene, path)
    _pressures(c)
    _temperatures(c)
    volumes = _volumes(c)
    _areas(c, volumes)
    check_responses(c, volumes, _integral)
    _lengths(c)
    _coefficients(c)
    _liquids(c)


def _pressures(c: _Checker) -> None:
    items = [("ambient.pressure", c.scene.ambient.pressure)]
    items += [(f"cavity[{i}].pressure", cav.pressure) for i, cav in enumerate(c.scene.cavity)]
    for where, p in items:
        if p < MIN_PRESSURE:
            c.fail(where, f"{c.given(p, (-1, 1, -2), 'Pa')} is below 1 kPa absolute: a pressure in bar ({p:g} bar = "
                          f"{p * 1e5:.6g} Pa) or MPa ({p * 1e6:.6g} Pa), or a gauge pressure? Pressures are absolute "
                          "[Pa]")
        if p > MAX_PRESSURE:
            unit = {"mm-t-s": "MPa", "mm-kg-ms": "GPa"}.get(c.system.name)
            why = (f"a pressure in Pa in a {c.system.name} scene, whose pressures are in {unit}?" if unit else
                   "a pressure in a unit smaller than Pa, or a typo?")
            c.fail(where, f"{c.given(p, (-1, 1, -2), 'Pa')} is above {MAX_PRESSURE:g} Pa, more than any gas or liquid "
                          f"here holds: {why}")


def gas_temperatures(scene) -> list:
    """(key, temperature [K]) of every gas temperature a scene gives: ambient, gas cavities, their inflators (a
    table's lowest value) and inflator tanks."""
    items = [("ambient.temperature", scene.ambient.temperature)]
    for i, cav in enumerate(scene.cavity):
        if cav.fluid != "gas":
            continue
        items.append((f"cavity[{i}].temperature", cav.temperature))
        for j, inf in enumerate(cav.inflator):
            T = inf.temperature
            if T is not None:
                items.append((f"cavity[{i}].inflator[{j}].temperature", min(T.y) if isinstance(T, Table) else T))
            if inf.tank_temperature:
                items.append((f"cavity[{i}].inflator[{j}].tank_temperature", inf.tank_temperature))
    return items


def _temperatures(c: _Checker) -> None:
    items = gas_temperatures(c.scene)
    for where, T in items:
        if T > MAX_TEMPERATURE:
            c.fail(where, f"{T:.6g} K is above {MAX_TEMPERATURE:g} K, hotter than any gas here: a typo?")
        if T < MIN_TEMPERATURE:
            c.fail(where, f"{T:.6g} K is below {MIN_TEMPERATURE:g} K: a temperature in °C ({T:g} °C = "
                          f"{T + 273.15:.6g} K)? Temperatures are absolute [K]")


def _volumes(c: _Checker) -> list:
    """Each cavity's initial volume [m^3] (None when it is not known before building), checked against
    MAX_VOLUME."""
    from cases.scene.meshes import SERIES_SUFFIXES, mesh_facts

    out = []
    for i, cav in enumerate(c.scene.cavity):
        where, v, surface = f"cavity[{i}].volume", cav.volume or None, None
        if cav.mesh and not str(cav.mesh).lower().endswith(SERIES_SUFFIXES) and (c.scene.base / cav.mesh).is_file():
            facts = mesh_facts(c.scene.base / cav.mesh)
            where, v = f"cavity[{i}].mesh", abs(facts.get("volume", 0.0)) or None
            surface = facts.get("area")
            if facts.get("extent", 0.0) > MAX_EXTENT or (v or 0.0) > MAX_VOLUME:
                c.fail(where, f"{cav.mesh!r} encloses {v or 0.0:.6g} m^3 and spans {facts.get('extent', 0.0):.6g} m: "
                              f"coordinates in millimetres (then it encloses {(v or 0.0) * 1e-9:.3g} m^3)? "
                              "Meshes are in the "
                              "scene's units (set [units] system = 'mm-t-s' or 'mm-kg-ms', or scale the mesh)")
        elif cav.volume_table and (c.scene.base / cav.volume_table).is_file():
            from cases.scene.tables_io import read_table

            where = f"cavity[{i}].volume_table"
            v = read_table(c.scene.base / cav.volume_table, c.path, where, "volume_table").y[0] or None
        elif v is not None and v > MAX_VOLUME:
            c.fail(where, f"{c.given(v, (3, 0, 0), 'm^3')} is above {MAX_VOLUME:g} m^3: a volume in litres ({v:g} L = "
                          f"{v * 1e-3:.6g} m^3) or mm^3? Volumes are in m^3")
        out.append((where, None if v is None else v + cav.added_volume, surface))
    return out


def _areas(c: _Checker, volumes: list) -> None:
    """An orifice cannot be larger than the whole surface of the cavity it leaves."""
    index = {cav.name: i for i, cav in enumerate(c.scene.cavity)}
    items = []
    for j, e in enumerate(c.scene.exchange):
        ends = [index[n] for n in (e.from_, e.to) if n in index]
        for k in ("area", "effective_area"):
            a = getattr(e, k)
            if a:
                items.append((f"exchange[{j}].{k}", a, ends))
    for i, cav in enumerate(c.scene.cavity):
        for j, inf in enumerate(cav.inflator):
            if inf.orifice_area:
                items.append((f"cavity[{i}].inflator[{j}].orifice_area", inf.orifice_area, [i]))
    for where, a, ends in items:
        known = [(volumes[i][1], volumes[i][2], c.scene.cavity[i].name) for i in ends if volumes[i][1]]
        if not known:
            continue
        v, surface, name = max(known, key=lambda k: (k[2] is not None, k[0]))
        if surface:  # a mesh: a vent is a hole in it (a fabric's leaking area at most all of it)
            bound, what = MESH_AREA_FACTOR * surface, f"{MESH_AREA_FACTOR:g} times the mesh surface of cavity {name!r}"
        else:  # a volume only: the least surface that holds it is a sphere's, a flat cavity has much more
            bound = SPHERE_AREA_FACTOR * SPHERE * v ** (2.0 / 3.0)
            what = f"{SPHERE_AREA_FACTOR:g} times the surface of a sphere of cavity {name!r}'s volume"
        if a > bound:
            c.fail(where, f"{c.given(a, (2, 0, 0), 'm^2')} is larger than {what} ({v:.3g} m^3; bound "
                          f"{bound:.3g} m^2): an "
                          f"area in mm^2 ({a:g} mm^2 = {a * 1e-6:.6g} m^2) or cm^2 ({a * 1e-4:.6g} m^2)? Areas are "
                          "in m^2")


def _integral(rate, span: float) -> float:
    """∫₀^span of a number or a Table (held beyond its ends) [kg]."""
    if not isinstance(rate, Table):
        return float(rate) * span
    xs = [x for x in rate.x if 0.0 < x < span]
    pts = [0.0] + xs + [span]
    return sum(0.5 * (rate(a) + rate(b)) * (b - a) for a, b in zip(pts[:-1], pts[1:]))


def _lengths(c: _Checker) -> None:
    from cases.scene.meshes import _mesh_files, mesh_facts

    for where, name, closed in _mesh_files(c.scene):
        extent = mesh_facts(c.scene.base / name).get("extent", 0.0) if not closed else 0.0
        if extent > MAX_EXTENT:
            c.fail(where, f"{name!r} spans {extent:.6g} m: coordinates in millimetres (x 1e-3: {extent * 1e-3:.3g} m)? "
                          "Meshes are in the scene's units (set [units] system = 'mm-t-s' or 'mm-kg-ms', or scale "
                          "the mesh)")
    for i, b in enumerate(c.scene.body):
        if b.sphere and 2 * b.sphere[3] > MAX_EXTENT:
            c.fail(f"body[{i}].sphere", f"radius {c.given(b.sphere[3], (1, 0, 0), 'm')} is wider than {MAX_EXTENT:g} "
                                        "m: millimetres? Lengths are in m")
        if b.box and max(b.box[3:]) > MAX_EXTENT:
            c.fail(f"body[{i}].box", f"extent {c.given(max(b.box[3:]), (1, 0, 0), 'm')} is wider than "
                                     f"{MAX_EXTENT:g} m: millimetres? Lengths are in m")
    for j, e in enumerate(c.scene.exchange):
        if e.leakage_box and max(e.leakage_box[3 + d] - e.leakage_box[d] for d in range(3)) > MAX_EXTENT:
            c.fail(f"exchange[{j}].leakage_box", f"spans more than {MAX_EXTENT:g} m: millimetres? Lengths are in m")
        if e.contact_tolerance > MAX_TOLERANCE:
            c.fail(f"exchange[{j}].contact_tolerance", f"{c.given(e.contact_tolerance, (1, 0, 0), 'm')} is above "
                                                       f"{MAX_TOLERANCE:g} m: millimetres? Lengths are in m")


#: Largest molar mass [kg/mol], molar cp at 300 K [J/(mol K)] and discharge coefficient [-] taken without override.
MAX_MOLAR_MASS, MAX_MOLAR_CP, MAX_CD = 1.0, 1000.0, 10.0


def _coefficients(c: _Checker) -> None:
    for i, sp in enumerate(c.scene.species):
        if 0.0 < sp.molar_mass < MIN_MOLAR_MASS:
            c.fail(f"species[{i}].molar_mass", f"{sp.molar_mass:.6g} kg/mol is below {MIN_MOLAR_MASS:g} kg/mol, "
                                               "lighter than a hydrogen atom: a typo?")
        if sp.molar_mass > MAX_MOLAR_MASS:
            c.fail(f"species[{i}].molar_mass", f"{sp.molar_mass:.6g} kg/mol is above {MAX_MOLAR_MASS:g} kg/mol: "
                                               f"in g/mol "
                                               f"({sp.molar_mass:g} g/mol = {sp.molar_mass * 1e-3:.6g} kg/mol)?")
        if sp.cp:
            a = tuple(sp.cp) + (0.0,) * (6 - len(sp.cp))
            T = 300.0
            cp = a[0] + a[1] * T + a[2] * T ** 2 + a[3] * T ** 3 + a[4] / T ** 2 + a[5] * T ** 4
            if not 0.0 < cp <= MAX_MOLAR_CP:
                c.fail(f"species[{i}].cp", f"gives cp = {cp:.6g} J/(mol K) at 300 K, expected 0 to {MAX_MOLAR_CP:g}: "
                                           "per kg instead of per mol (multiply by the molar mass), or a coefficient "
                                           "of the wrong power of T?")
    for j, e in enumerate(c.scene.exchange):
        cd = getattr(e, "discharge_coefficient", None)
        top = max(cd.y) if isinstance(cd, Table) else cd
        if isinstance(top, float) and top > MAX_CD:
            c.fail(f"exchange[{j}].discharge_coefficient", f"{top:.6g} is above {MAX_CD:g}: a discharge coefficient "
                                                           "is at most about 1 (the ideal flow)")


#: Liquid bulk modulus [Pa] (oil with entrained air ~1e7, water 2.2e9, diamond 4.4e11) and density [kg/m^3]
#: (liquid hydrogen 71, osmium 22,600) taken without override.
MIN_BULK_MODULUS, MAX_BULK_MODULUS, MIN_DENSITY, MAX_DENSITY = 1e6, 1e12, 10.0, 1e5


def _liquids(c: _Checker) -> None:
    """A hydraulic cavity's bulk modulus and density within the bounds above (a value in another unit: in the SI
    value of an mm-t-s scene, 2.2e9 written for water's bulk modulus is 2.2e15 Pa)."""
    name = c.system.name
    units = {"mm-t-s": ("MPa", "t/mm^3"), "mm-kg-ms": ("GPa", "kg/mm^3")}.get(name)
    for i, cav in enumerate(c.scene.cavity):
        if cav.fluid != "hydraulic":
            continue
        k, rho = cav.bulk_modulus, cav.density
        if k and not MIN_BULK_MODULUS <= k <= MAX_BULK_MODULUS:
            why = (f"a bulk modulus in Pa in a {name} scene, whose pressures are in {units[0]}?" if units else
                   f"a bulk modulus in MPa or GPa ({k:g} GPa = {k * 1e9:.6g} Pa)?" if k < MIN_BULK_MODULUS else
                   "a typo?")
            c.fail(f"cavity[{i}].bulk_modulus", f"{c.given(k, (-1, 1, -2), 'Pa')} is outside {MIN_BULK_MODULUS:g} to "
                                                f"{MAX_BULK_MODULUS:g} Pa (water: 2.2e9 Pa): {why}")
        if rho and not MIN_DENSITY <= rho <= MAX_DENSITY:
            why = (f"a density in kg/m^3 in a {name} scene, whose densities are in {units[1]}?" if units else
                   f"a density in g/cm^3 ({rho:g} g/cm^3 = {rho * 1e3:.6g} kg/m^3)?" if rho < MIN_DENSITY else
                   "a typo?")
            c.fail(f"cavity[{i}].density", f"{c.given(rho, (-3, 1, 0), 'kg/m^3')} is outside {MIN_DENSITY:g} to "
                                           f"{MAX_DENSITY:g} kg/m^3 (water: 1000): {why}")
