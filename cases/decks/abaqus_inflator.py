"""Abaqus inflators -> [[cavity.inflator]] tables (Abaqus Keywords Reference: *FLUID INFLATOR, *FLUID INFLATOR
PROPERTY, *FLUID INFLATOR MIXTURE, *FLUID INFLATOR ACTIVATION; Analysis User's Guide "Inflator definition").

*FLUID INFLATOR PROPERTY data lines: inflation time, then per TYPE (Abaqus Scripting Reference,
FluidInflatorProperty, "table data"): TEMPERATURE AND MASS — gas temperature, mass flow rate; TANK TEST — gas
temperature, tank pressure (TANK VOLUME=); PRESSURE AND MASS — inflator pressure, mass flow rate (EFFECTIVE AREA=,
DISCHARGE COEFFICIENT=); DUAL PRESSURE — inflator pressure, tank pressure (all three parameters). An inflator
flows only once *FLUID INFLATOR ACTIVATION names it; the inflation time is the integral of its INFLATION TIME
AMPLITUDE (a step from 0 to 1: a delay); MASS FLOW AMPLITUDE multiplies a prescribed flow (a constant here; ignored
for TANK TEST and DUAL PRESSURE, as in Abaqus).
"""
from __future__ import annotations

from cases.decks.abaqus_fluid import floats, ref_node

__all__ = ["read_inflator", "inflator_entries"]

#: TYPE -> (scene type, (second column key, quantity), (third column key, quantity))
TYPES = {"TEMPERATURE AND MASS": ("mass_temperature", ("temperature", "temperature"), ("mass_flow", "mass_flow")),
         "TANK TEST": ("tank_test", ("temperature", "temperature"), ("tank_pressure", "pressure")),
         "PRESSURE AND MASS": ("pressure_mass", ("inflator_pressure", "pressure"), ("mass_flow", "mass_flow")),
         "DUAL PRESSURE": ("dual_pressure", ("inflator_pressure", "pressure"), ("tank_pressure", "pressure"))}


def read_inflator(deck, kw, parent):
    """Store *FLUID INFLATOR [PROPERTY | MIXTURE | ACTIVATION]; returns the property a MIXTURE would follow."""
    if kw.name == "FLUID INFLATOR PROPERTY":
        kind = kw.label("TYPE", required=True)
        if kind not in TYPES:
            raise kw.error(f"TYPE={kind}: expected one of {', '.join(TYPES)}")
        rows = [floats(kw, d, 3, "inflation time and two values") for d in kw.data]
        if not rows:
            raise kw.error("no data lines (inflation time, two tabulated values)")
        deck.inflator_props[kw.label("NAME", required=True)] = {"kw": kw, "type": kind, "rows": rows}
        return kw.label("NAME")
    if kw.name == "FLUID INFLATOR MIXTURE":
        if parent is None:
            raise kw.error("must follow *FLUID INFLATOR PROPERTY")
        deck.inflator_props[parent]["mixture"] = kw
        return parent
    if kw.name == "FLUID INFLATOR":
        if not kw.data:
            raise kw.error("missing data line (the fluid cavity's reference node)")
        node = ref_node(deck, kw, text=kw.data[0].fields[0], line=kw.data[0].line)
        deck.inflators.append((kw, node))
    elif kw.name == "FLUID INFLATOR ACTIVATION":
        for d in kw.data:
            for name in filter(None, d.fields):
                deck.inflator_activation[name.upper()] = kw
    return None


def _mixture(deck, kw):
    """(gas, by mole) of a *FLUID INFLATOR MIXTURE whose fractions do not change with time."""
    n = int(kw.number("NUMBER SPECIES", 0) or 0)
    names = [f.upper() for d in kw.data for f in d.fields if f and not _is_number(f)]
    rows = [floats(kw, d, 1 + n, "time and fractions") for d in kw.data if d.fields and _is_number(d.fields[0])]
    if n <= 0 or len(names) != n:
        raise kw.error(f"NUMBER SPECIES={n} but {len(names)} species names")
    for name in names:
        if name not in deck.behaviors:
            raise kw.error(f"{name}: no *FLUID BEHAVIOR of that name{deck.suggest(name, deck.behaviors)}")
        deck.used_species.add(name)
    if not rows or any(r[1:1 + n] != rows[0][1:1 + n] for r in rows):
        raise kw.error("ventsim needs one constant composition (the same fractions on every line)")
    by_mole = (kw.label("TYPE") or "MASS FRACTION") == "MOLAR FRACTION"
    return {name.lower(): rows[0][1 + i] for i, name in enumerate(names)}, by_mole


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def _start(deck, act):
    """Inflation delay [deck time] from INFLATION TIME AMPLITUDE f: the inflation time is ∫₀ᵗ f dt (Analysis
    User's Guide, "Inflator definition"), f typically a step from 0 to 1 at deployment. A tabular f that is 0 up
    to t_a and 1 from t_b on gives ∫f = t − (t_a + t_b)/2 for t ≥ t_b: ventsim starts the inflator there."""
    name = act.label("INFLATION TIME AMPLITUDE")
    if name is None:
        return 0.0
    t, f = deck.amplitude(name, act, smooth_step=True)  # a symmetric smooth step integrates like the ramp
    zeros = [i for i, v in enumerate(f) if v == 0.0]
    ones = [i for i, v in enumerate(f) if v == 1.0]
    a = zeros[-1] if zeros else None
    b = ones[0] if ones else None
    ok = b is not None and ones == list(range(b, len(f))) and (a is None or (zeros == list(range(a + 1))
                                                                              and b == a + 1))
    if ok and a is not None and t[b] - t[a] > 1e-3 * deck.step_end(act):
        ok = False  # a slow ramp is not a delay
    if not ok:
        raise act.error(f"INFLATION TIME AMPLITUDE={name}: ventsim reads a step from 0 to 1 (0 up to t_a, 1 from "
                        "t_b = the next point on, t_b - t_a <= 0.001 x the step time)")
    if a is None:
        return 0.0
    if t[b] > t[a]:
        deck.notes.append(f"inflation time amplitude {name}: the ramp from {t[a]!r} to {t[b]!r} is read as a "
                          f"delay of {(t[a] + t[b]) / 2!r} (exact from {t[b]!r} on)")
    return 0.5 * (t[a] + t[b])


def _scale(deck, act):
    name = act.label("MASS FLOW AMPLITUDE")
    if name is None:
        return 1.0
    _, a = deck.amplitude(name, act)
    if any(v != a[0] for v in a):
        raise act.error(f"MASS FLOW AMPLITUDE={name}: ventsim reads a constant multiplier only")
    return a[0]


def _entry(deck, kw, prop, default_gas):
    scene_type, (k2, q2), (k3, q3) = TYPES[prop["type"]]
    pkw, rows, name = prop["kw"], prop["rows"], kw.label("NAME", required=True)
    entry = {"name": name.lower(), "type": scene_type}
    times = [deck.si(r[0], "time") for r in rows]
    for key, quantity, col in ((k2, q2, 1), (k3, q3, 2)):
        values = [deck.kelvin(r[col], pkw) if quantity == "temperature" else deck.si(r[col], quantity)
                  for r in rows]
        if quantity == "temperature" and all(v == values[0] for v in values):
            entry[key] = values[0]
        else:
            unit = {"temperature": "K", "pressure": "Pa", "mass_flow": "kg/s"}[quantity]
            entry[key] = deck.table_file(f"{name.lower()}_{key}", times, values, f"time [s],{key} [{unit}]")
    if scene_type in ("tank_test", "dual_pressure"):
        entry["tank_volume"] = deck.si(pkw.number("TANK VOLUME", 0.0), "volume")
    if scene_type in ("pressure_mass", "dual_pressure"):
        entry["orifice_area"] = deck.si(pkw.number("EFFECTIVE AREA", 0.0), "area")
        entry["discharge_coefficient"] = pkw.number("DISCHARGE COEFFICIENT", 1.0)
    entry["gas"], entry["gas_by_mole"] = _mixture(deck, prop["mixture"]) if "mixture" in prop else default_gas
    act = deck.inflator_activation[name]
    start, scale = _start(deck, act), _scale(deck, act)
    if scale != 1.0 and scene_type in ("tank_test", "dual_pressure"):
        deck.notes.append(f"inflator {name}: MASS FLOW AMPLITUDE is ignored for {prop['type']} (as in Abaqus)")
        scale = 1.0
    if start:
        entry["start"] = deck.si(start, "time")
    if scale != 1.0:
        entry["scale"] = scale
    return entry


def inflator_entries(deck, cavities: dict) -> None:
    """Add the activated inflators to their cavities' entries (``cavities``: reference node -> entry)."""
    for kw, node in deck.inflators:
        name = kw.label("NAME", required=True)
        prop_name = kw.label("PROPERTY", required=True)
        if prop_name not in deck.inflator_props:
            raise kw.error(f"PROPERTY={prop_name}: no *FLUID INFLATOR PROPERTY of that name"
                           f"{deck.suggest(prop_name, deck.inflator_props)}")
        if node not in cavities:
            raise kw.error(f"node {node} is the reference node of no *FLUID CAVITY", kw.data[0].line)
        if name not in deck.inflator_activation:
            deck.notes.append(f"inflator {name} is never activated (*FLUID INFLATOR ACTIVATION): no inflow, "
                              "as in Abaqus")
            continue
        cav = cavities[node]
        default = (dict(cav.get("gas", {"air": 1.0})), cav.get("gas_by_mole", False))
        cav.setdefault("inflator", []).append(_entry(deck, kw, deck.inflator_props[prop_name], default))
