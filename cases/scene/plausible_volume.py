"""A cavity volume orders of magnitude too large for its own scene: what the run would do to the cavity's gas.

A cavity given by ``volume`` (or ``volume_table``) holds m = p·V/(R·T) of gas. By ``time.end`` its inflators add
m_in (their whole tables) and its vents, all taken as open (also pop and blocked vents), relieve it with the time
constant τ = V/(Cd·A·c₀) (Cd 0.6, c₀ = √(1.4·R·T)). The response

    r = max(m_in / m, time.end / τ)

is the share of its gas the run can change; both terms are inversely proportional to V. The library's least r is
0.082 (a 1 L tank vented 20 ms through 20 mm²; benchmarks/volume_responses.py prints them all); a volume in litres
taken for m³ divides it by 1000, in mm³ by 1e9. A cavity whose r is below :data:`MIN_RESPONSE` (3e-3, 27 times below
the library's least)
would hardly notice its own run: its volume is taken for a unit mistake, with one line naming the file, the key, the
value, what it was compared with and the override. An upper bound of r is what counts, so a cavity is not judged
when a flow it sees cannot be bounded before the run: an inflator type other than ``mass_temperature``, a vent of
another law than ``orifice`` or ``fabric_leakage``, a flux table, an exchange with another cavity, or a volume
table whose volume itself changes by more than the threshold.

>>> round(response(held=0.07, added=0.07, area=1.26e-3, volume=0.06, temperature=300.0, end=0.1), 3)
1.0
>>> response(held=70.0, added=0.07, area=1.26e-3, volume=60.0, temperature=300.0, end=0.1) < MIN_RESPONSE
True
"""
from __future__ import annotations

import math

from cavity.tables import Table

__all__ = ["MIN_RESPONSE", "response", "check_responses"]

#: Least share of its gas a cavity's run may change (inflated or vented) without an override [-].
MIN_RESPONSE = 3e-3
#: Discharge coefficient of the vents' time constant [-], and air's gas constant [J/(kg K)] for a gas not known here.
CD, R_AIR = 0.6, 287.05
#: Molar masses [kg/mol] of the common gases, for the held mass (other species: those of [[species]], else air).
MOLAR = {"air": 0.028965, "N2": 0.0280134, "O2": 0.0319988, "CO2": 0.0440095, "H2": 0.00201588, "He": 0.0040026,
         "Ar": 0.039948, "H2O": 0.01801528, "CH4": 0.0160425, "CO": 0.0280101}
_VENT_LAWS = ("orifice", "fabric_leakage")


def response(*, held: float, added: float, area: float, volume: float, temperature: float, end: float) -> float:
    """max(added / held, end / τ) with τ = volume / (CD·area·√(1.4·R_AIR·temperature)): the share of a cavity's gas
    [-] its inflators (``added`` of ``held`` [kg]) or its vents (``area`` [m²]) can change by ``end`` [s]."""
    vented = end * CD * area * math.sqrt(1.4 * R_AIR * temperature) / volume if area else 0.0
    return max(added / held if held > 0 else 0.0, vented)


def _gas_constant(scene, gas: dict) -> float:
    """R [J/(kg K)] of a composition by mass (species of [[species]] or :data:`MOLAR`; air for the others)."""
    known = {sp.name: sp.molar_mass for sp in scene.species if sp.molar_mass}
    total = sum(gas.values()) or 1.0
    inverse = sum(w / total / (known.get(name) or MOLAR.get(name) or MOLAR["air"]) for name, w in gas.items())
    return 8.314462618 * inverse if inverse > 0 else R_AIR


def _added(cav, end: float, integral) -> float | None:
    """Mass [kg] the inflators add by time.end (a table: all of it); None when a type's mass is not known."""
    total = 0.0
    for inf in cav.inflator:
        if inf.type != "mass_temperature" or inf.mass_flow is None:
            return None
        last = inf.mass_flow.x[-1] if isinstance(inf.mass_flow, Table) else 0.0
        total += inf.scale * integral(inf.mass_flow, max(end - inf.start, last))
    return total


def _vent_area(scene, name: str) -> float | None:
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
    """SceneError (through the checker ``c``) on a cavity whose run would change less than MIN_RESPONSE of its gas;
    ``volumes`` as plausible._volumes gives them, ``integral(rate, span)`` the mass of an inflator rate."""
    scene = c.scene
    end = scene.time.end
    for i, cav in enumerate(scene.cavity):
        where, v, _ = volumes[i]
        if cav.fluid not in ("gas", "real_gas") or not v or not where.endswith(("volume", "volume_table")):
            continue
        added, area = _added(cav, end, integral), _vent_area(scene, cav.name)
        if added is None or area is None or not (added or area) or _table_varies(c, cav, i):
            continue
        R = _gas_constant(scene, cav.gas)
        held = cav.pressure * v / (R * cav.temperature)
        r = response(held=held, added=added, area=area, volume=v, temperature=cav.temperature, end=end)
        if r >= MIN_RESPONSE:
            continue
        tau = v / (CD * area * math.sqrt(1.4 * R_AIR * cav.temperature)) if area else math.inf
        vents = f"its vents ({area:.3g} m^2) would take {tau:.3g} s to relieve it" if area else "it has no vent"
        c.fail(where, f"{c.given(v, (3, 0, 0), 'm^3')} is orders of magnitude too large for its scene: by time.end "
                      f"({end:.3g} s) the run would change at most {r:.2g} of its gas ({held:.3g} kg; its inflators "
                      f"add {added:.3g} kg, {vents}): {_hint(c, v)}")


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
