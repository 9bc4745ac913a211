"""A cavity volume orders of magnitude too large for its own scene: what the run would do to the cavity's gas.

A cavity given by ``volume`` (or a constant ``volume_table``) holds m = p·V/(R·T) of gas. Over a time t_ref its
inflators add m_in and its vents, all taken as open (also pop and blocked vents), relieve it with the time constant
τ = V/(Cd·A·c₀) (Cd 0.6, c₀ = √(1.4·R_air·T)). The response

    r = max(m_in / m, t_ref / τ)

is the share of its gas the run can change; both terms are inversely proportional to V, so a volume in litres
taken for m³ divides r by 1000, in mm³ by 1e9.

- **Inflated by tables** (every inflator a ``mass_temperature`` with a ``mass_flow`` table): m_in is the tables'
  whole mass and t_ref the later of ``time.end`` and the tables' end, so neither shrinks in a short preview. Below
  :data:`MIN_RESPONSE` (3e-3; the library's least r is 0.082, ``benchmarks/volume_responses.py``) the volume is
  taken for a unit mistake at any size.
- **Otherwise** (vents only, or an inflator at a constant rate): t_ref is ``time.end`` alone, and a preview of a
  run is as short against τ as a volume 1000 times too large: only a cavity of :data:`MIN_VENTED_VOLUME` (1 m³) or
  more is judged, against :data:`MIN_UNTIMED_RESPONSE` (1e-3).

The error is one line naming the file, the key, the value, what it was compared with and the override. A cavity is
not judged when a flow it sees cannot be bounded before the run: an inflator type other than
``mass_temperature``, a vent of another law than ``orifice`` or ``fabric_leakage``, a flux table, an exchange with
another cavity, or a volume table whose volume itself changes by more than MIN_RESPONSE.

>>> round(response(held=0.07, added=0.07, area=1.26e-3, volume=0.06, temperature=300.0, end=0.1), 3)
1.0
>>> response(held=70.0, added=0.07, area=1.26e-3, volume=60.0, temperature=300.0, end=0.1) < MIN_RESPONSE
True
"""
from __future__ import annotations

import math

from cavity.tables import Table

__all__ = ["MIN_RESPONSE", "MIN_UNTIMED_RESPONSE", "MIN_VENTED_VOLUME", "response", "check_responses"]

#: Least share of its gas a cavity inflated by tables may change over t_ref without an override [-].
MIN_RESPONSE = 3e-3
#: The same for a cavity without inflator tables (t_ref = time.end), judged from MIN_VENTED_VOLUME [m^3] up.
MIN_UNTIMED_RESPONSE, MIN_VENTED_VOLUME = 1e-3, 1.0
#: Discharge coefficient of the vents' time constant [-], and air's gas constant [J/(kg K)].
CD, R_AIR = 0.6, 287.05
#: Molar masses [kg/mol] of the common gases, for the held mass (other species: those of [[species]], else air).
MOLAR = {"air": 0.028965, "N2": 0.0280134, "O2": 0.0319988, "CO2": 0.0440095, "H2": 0.00201588, "He": 0.0040026,
         "Ar": 0.039948, "H2O": 0.01801528, "CH4": 0.0160425, "CO": 0.0280101}
_VENT_LAWS = ("orifice", "fabric_leakage")


def response(*, held: float, added: float, area: float, volume: float, temperature: float, end: float) -> float:
    """max(added / held, end / τ) with τ = volume / (CD·area·√(1.4·R_AIR·temperature)): the share of a cavity's gas
    [-] its inflators (``added`` of ``held`` [kg]) or its vents (``area`` [m²]) can change in ``end`` [s]."""
    vented = end * CD * area * math.sqrt(1.4 * R_AIR * temperature) / volume if area else 0.0
    return max(added / held if held > 0 else 0.0, vented)


def gas_constant(scene, gas: dict) -> float:
    """R [J/(kg K)] of a composition by mass (species of [[species]] or :data:`MOLAR`; air for the others)."""
    known = {sp.name: sp.molar_mass for sp in scene.species if sp.molar_mass}
    total = sum(gas.values()) or 1.0
    inverse = sum(w / total / (known.get(name) or MOLAR.get(name) or MOLAR["air"]) for name, w in gas.items())
    return 8.314462618 * inverse if inverse > 0 else R_AIR


def inflow(cav, end: float, integral) -> tuple | None:
    """(mass [kg] the inflators add, t_ref [s], inflated by tables) of a cavity; None when a type's mass is not
    known. Tables count whole and push t_ref to their end; a constant rate counts up to time.end."""
    total, t_ref, tables = 0.0, end, bool(cav.inflator)
    for inf in cav.inflator:
        if inf.type != "mass_temperature" or inf.mass_flow is None:
            return None
        table = isinstance(inf.mass_flow, Table)
        last = inf.mass_flow.x[-1] if table else 0.0
        total += inf.scale * integral(inf.mass_flow, max(end - inf.start, last))
        t_ref, tables = (max(t_ref, inf.start + last), tables) if table else (t_ref, False)
    return total, t_ref, tables


def vent_area(scene, name: str) -> float | None:
    """Total area [m²] of the cavity's vents, all open; None when one of its exchanges cannot be bounded."""
    area = 0.0
    for e in scene.exchange:
        if name not in (e.from_, e.to):
            continue
        if e.to != "ambient" or e.leakage_table or e.law not in _VENT_LAWS:
            return None
        area += e.effective_area or e.area
    return area


def check_responses(c, volumes: list, integral) -> None:
    """SceneError (through the checker ``c``) on a cavity whose run would change too little of its gas;
    ``volumes`` as plausible._volumes gives them, ``integral(rate, span)`` the mass of an inflator rate."""
    scene = c.scene
    for i, cav in enumerate(scene.cavity):
        where, v, _ = volumes[i]
        if cav.fluid not in ("gas", "real_gas") or not v or not where.endswith(("volume", "volume_table")):
            continue
        flow, area = inflow(cav, scene.time.end, integral), vent_area(scene, cav.name)
        if flow is None or area is None or not (flow[0] or area) or _table_varies(c, cav, i):
            continue
        added, t_ref, tables = flow
        least = MIN_RESPONSE if tables else MIN_UNTIMED_RESPONSE
        if not tables and v < MIN_VENTED_VOLUME:
            continue
        held = cav.pressure * v / (gas_constant(scene, cav.gas) * cav.temperature)
        r = response(held=held, added=added, area=area, volume=v, temperature=cav.temperature, end=t_ref)
        if r < least:
            _fail(c, where, v, r, held, added, area, t_ref, cav.temperature)


def _fail(c, where, v, r, held, added, area, t_ref, temperature) -> None:
    tau = v / (CD * area * math.sqrt(1.4 * R_AIR * temperature)) if area else math.inf
    vents = f"its vents ({area:.3g} m^2) would take {tau:.3g} s to relieve it" if area else "it has no vent"
    c.fail(where, f"{c.given(v, (3, 0, 0), 'm^3')} is orders of magnitude too large for its scene: in {t_ref:.3g} s "
                  f"(time.end or its inflator tables' end) the run would change at most {r:.2g} of its gas "
                  f"({held:.3g} kg; its inflators add {added:.3g} kg, {vents}): {_hint(c, v)}")


def _table_varies(c, cav, i: int) -> bool:
    """A volume table whose volume changes by more than MIN_RESPONSE: the cavity responds by its own motion."""
    if not cav.volume_table:
        return False
    from cases.scene.tables_io import read_table

    y = read_table(c.scene.base / cav.volume_table, c.path, f"cavity[{i}].volume_table", "volume_table").y
    return min(y) <= 0 or max(y) / min(y) - 1.0 > MIN_RESPONSE


def _hint(c, v: float) -> str:
    if c.system.name == "SI":
        return f"a volume in litres ({v:g} L = {v * 1e-3:.6g} m^3) or mm^3? Volumes are in m^3"
    return f"a volume in another unit than {c.system.name}'s (mm^3)?"
