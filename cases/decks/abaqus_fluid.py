"""Abaqus fluid keywords -> scene cavities, species and inflators.

Sections of the Abaqus Keywords Reference (2017) read here: *PHYSICAL CONSTANTS, *FLUID BEHAVIOR with
*MOLECULAR WEIGHT, *CAPACITY (TYPE=POLYNOMIAL), *FLUID DENSITY, *FLUID BULK MODULUS, *FLUID EXPANSION;
*FLUID CAVITY; *INITIAL CONDITIONS (TYPE=FLUID PRESSURE, TYPE=TEMPERATURE); *FLUID INFLATOR, *FLUID INFLATOR
PROPERTY (TEMPERATURE AND MASS, TANK TEST, PRESSURE AND MASS, DUAL PRESSURE: inflation time first, then the two
tabulated quantities in that order), *FLUID INFLATOR MIXTURE, *FLUID INFLATOR ACTIVATION; *AMPLITUDE.

Pressures: Abaqus's cavity pressure is relative to the cavity's AMBIENT PRESSURE (the ideal gas law is
p + p_A = ρ R (θ − θ_Z), Analysis User's Guide "Fluid cavity definition"); the scene's are absolute.
"""
from __future__ import annotations

from cases.decks.conversions import R_U, hydraulic_density

__all__ = ["read_behaviors", "read_initial", "cavity_entry", "species_entries", "floats", "ref_node", "R_U"]


def floats(kw, d, n_min=1, what="value"):
    """The numbers of data line ``d`` (blank fields are 0, as Abaqus reads them)."""
    out = []
    for f in d.fields:
        try:
            out.append(float(f) if f else 0.0)
        except ValueError:
            raise kw.error(f"expected a number for the {what}, got {f!r}", d.line) from None
    if len([f for f in d.fields if f]) < n_min:
        raise kw.error(f"expected at least {n_min} number(s) ({what}), got {', '.join(d.fields)!r}", d.line)
    return out


def _one_line(kw, n_min, what):
    if not kw.data:
        raise kw.error(f"missing data line ({what})")
    if len(kw.data) > 1:
        raise kw.error(f"{len(kw.data)} data lines: ventsim reads constant values only ({what}; no temperature "
                       "or field-variable dependence)", kw.data[1].line)
    return floats(kw, kw.data[0], n_min, what)


def read_behaviors(deck, kw, parent):
    """Handle *FLUID BEHAVIOR and its sub-options; returns the new parent behaviour name (or ``parent``)."""
    if kw.name == "FLUID BEHAVIOR":
        name = kw.label("NAME", required=True)
        deck.behaviors[name] = {"kw": kw}
        return name
    if parent is None:
        raise kw.error("must follow *FLUID BEHAVIOR")
    b = deck.behaviors[parent]
    if kw.name == "MOLECULAR WEIGHT":
        b["M"] = _one_line(kw, 1, "molecular weight")[0]
    elif kw.name == "CAPACITY":
        kind = kw.label("TYPE") or "TABULAR"
        if kind != "POLYNOMIAL":
            raise kw.error(f"TYPE={kind}: ventsim reads TYPE=POLYNOMIAL (a, b, c, d, e) only")
        b["cp"] = (_one_line(kw, 1, "cp polynomial a, b, c, d, e") + [0.0] * 5)[:5]
    elif kw.name == "FLUID DENSITY":
        b["density"] = _one_line(kw, 1, "reference density")[0]
        b["p_ref"] = kw.number("REFERENCE PRESSURE", 0.0)
    elif kw.name == "FLUID BULK MODULUS":
        b["K"] = _one_line(kw, 1, "bulk modulus")[0]
    elif kw.name == "FLUID EXPANSION":
        b["alpha"] = _one_line(kw, 1, "expansion coefficient")[0]
    return parent


def _node_or_set(deck, kw, text, d):
    if text.upper() in deck.mesh.nsets:
        return list(deck.mesh.nsets[text.upper()])
    try:
        return [int(float(text))]
    except ValueError:
        raise kw.error(f"{text!r} is neither a node number nor a node set", d.line) from None


def read_initial(deck, kw):
    """*INITIAL CONDITIONS, TYPE=FLUID PRESSURE / TEMPERATURE on nodes; other types are structural (ignored)."""
    kind = kw.label("TYPE")
    if kind not in ("FLUID PRESSURE", "TEMPERATURE"):
        return False
    store = deck.initial_pressure if kind == "FLUID PRESSURE" else deck.initial_temperature
    for d in kw.data:
        if len(d.fields) < 2:
            raise kw.error(f"expected 'node or node set, value', got {', '.join(d.fields)!r}", d.line)
        value = floats(kw, type(d)(d.fields[1:2], d.file, d.line), 1, "initial value")[0]
        for n in _node_or_set(deck, kw, d.fields[0], d):
            store[n] = (value, kw.line)
    return True


def ref_node(deck, kw, param="REF NODE", text=None, line=None):
    """The node a parameter (or a data field ``text``) names: a node number or a set of exactly one node."""
    text = kw.param(param) if text is None else text
    if not isinstance(text, str) or not text:
        raise kw.error(f"missing required parameter {param}=", line)
    if text.upper() in deck.mesh.nsets:
        nodes = sorted(set(deck.mesh.nsets[text.upper()]))
    else:
        try:
            nodes = [int(float(text))]
        except ValueError:
            raise kw.error(f"{text!r} is neither a node number nor a node set", line) from None
    if len(nodes) != 1:
        raise kw.error(f"{text}: expected one reference node, the set has {len(nodes)}", line)
    return nodes[0]


def _composition(deck, kw):
    """(gas table, by mole, kind) of a cavity: its BEHAVIOR, or MIXTURE data lines 'behavior, fraction'."""
    if kw.label("BEHAVIOR"):
        name = kw.label("BEHAVIOR")
        if name not in deck.behaviors:
            raise kw.error(f"BEHAVIOR={name}: no *FLUID BEHAVIOR of that name{deck.suggest(name, deck.behaviors)}")
        deck.used_species.add(name)
        return {name.lower(): 1.0}, False, deck.behavior_kind(name, kw)
    mix = kw.label("MIXTURE")
    if mix is None:
        raise kw.error("needs BEHAVIOR= or MIXTURE=")
    if mix not in ("MASS FRACTION", "MOLAR FRACTION", "YES"):
        raise kw.error(f"MIXTURE={mix}: expected MASS FRACTION or MOLAR FRACTION")
    gas = {}
    for d in kw.data:
        if d.fields and d.fields[0].upper() in deck.behaviors:
            name = d.fields[0].upper()
            if deck.behavior_kind(name, kw) != "gas":
                raise kw.error(f"{name} is not an ideal gas (a mixture needs *MOLECULAR WEIGHT and *CAPACITY)",
                               d.line)
            gas[name.lower()] = floats(kw, type(d)(d.fields[1:], d.file, d.line), 1, "fraction")[0]
            deck.used_species.add(name)
        elif d.fields and d.fields[0] and not d.fields[0].replace(".", "").replace("-", "").isdigit():
            raise kw.error(f"{d.fields[0]!r}: no *FLUID BEHAVIOR of that name"
                           f"{deck.suggest(d.fields[0].upper(), deck.behaviors)}", d.line)
    if not gas:
        raise kw.error("MIXTURE: no data line 'fluid behavior, fraction'")
    return gas, mix == "MOLAR FRACTION", "gas"


def cavity_entry(deck, kw, volume_entry):
    """The [[cavity]] table of a *FLUID CAVITY; ``volume_entry(kw)`` gives its mesh or volume keys."""
    name = kw.label("NAME", required=True).lower()
    node = ref_node(deck, kw)
    gas, by_mole, kind = _composition(deck, kw)
    p_amb = kw.number("AMBIENT PRESSURE", 0.0)
    gauge, _ = deck.initial_pressure.get(node, (0.0, 0))
    if node in deck.initial_temperature or kind == "gas":
        temperature = deck.kelvin(deck.initial_temperature.get(node, (0.0, 0))[0], kw)  # Abaqus default θ = 0
    else:
        temperature = 293.15
        deck.notes.append(f"cavity {name}: no initial TEMPERATURE on the reference node: the liquid is at 293.15 K "
                          "(used only with *FLUID EXPANSION)")
    entry = {"name": name, "pressure": deck.si(gauge + p_amb, "pressure"), "temperature": temperature}
    if kind == "gas":
        entry.update(gas=gas, gas_by_mole=by_mole, energy="adiabatic" if kw.param("ADIABATIC") else "isothermal")
    entry.update(volume_entry(kw))
    if kw.number("MINIMUM VOLUME"):
        entry["minimum_volume"] = deck.si(kw.number("MINIMUM VOLUME"), "volume")
    if kind == "hydraulic":
        b = deck.behaviors[next(iter(gas)).upper()]
        K, dp = b["K"], gauge - b.get("p_ref", 0.0)
        if not (K > 0 and b["density"] > 0):
            raise b["kw"].error(f"{next(iter(gas)).upper()}: the density and the bulk modulus must be > 0")
        try:
            rho = hydraulic_density(b["density"], gauge, b.get("p_ref", 0.0), K)
        except OverflowError:
            raise kw.error(f"the initial pressure is {dp / K:.3g} bulk moduli above the reference: the density "
                           "overflows") from None
        entry.update(fluid="hydraulic", density=deck.si(rho, "density"), bulk_modulus=deck.si(K, "pressure"))
        if b.get("alpha"):
            entry["thermal_expansion"] = b["alpha"]
    return node, entry, (p_amb, kw.number("AMBIENT TEMPERATURE"))


def species_entries(deck) -> list:
    """[[species]] tables of the ideal-gas behaviours used, with M and cp scaled by R_u / R_deck so that the
    specific gas constant and specific heats are those of the deck."""
    out = []
    for name in sorted(deck.used_species):
        b = deck.behaviors[name]
        if deck.behavior_kind(name, b["kw"]) != "gas":
            continue
        scale = deck.gas_constant_scale(b["kw"])
        M = deck.si(b["M"], "mass") * scale
        cp = [deck.si(c, "molar_heat") * scale for c in b["cp"]]
        while len(cp) > 1 and cp[-1] == 0.0:
            cp.pop()
        out.append({"name": name.lower(), "molar_mass": M, "cp": cp})
    return out
