"""Abaqus fluid exchanges -> [[exchange]] tables (Abaqus Keywords Reference: *FLUID EXCHANGE, *FLUID EXCHANGE
PROPERTY, *FLUID EXCHANGE ACTIVATION).

*FLUID EXCHANGE: NAME, PROPERTY, SURFACE and/or EFFECTIVE AREA; data line: first cavity's reference node and an
optional second one (none: the environment). Area: the surface's area, or EFFECTIVE AREA (default 1.0 without a
surface); with both, the surface only carries the blockage and the effective area is reduced in proportion.
*FLUID EXCHANGE PROPERTY data lines per TYPE: ORIFICE and FABRIC LEAKAGE — discharge coefficient (optionally
against absolute pressure); MASS RATE LEAKAGE / VOLUME RATE LEAKAGE — |flow per area|, |Δp| (first row 0, 0);
MASS FLUX / VOLUME FLUX — flow per area; BULK VISCOSITY — viscous and hydrodynamic resistance coefficients.
*FLUID EXCHANGE ACTIVATION (step data): an exchange flows only once activated; BLOCKAGE=YES, DELTA LEAKAGE AREA,
OUTFLOW ONLY, AMPLITUDE.
"""
from __future__ import annotations

from cases.decks.abaqus_fluid import floats, ref_node

__all__ = ["read_exchange", "exchange_entries", "LAWS"]

LAWS = {"ORIFICE": "orifice", "FABRIC LEAKAGE": "fabric_leakage", "MASS RATE LEAKAGE": "mass_rate_leakage",
        "VOLUME RATE LEAKAGE": "volume_rate_leakage", "MASS FLUX": "mass_flux", "VOLUME FLUX": "volume_flux",
        "BULK VISCOSITY": "bulk_viscosity"}


def read_exchange(deck, kw):
    if kw.name == "FLUID EXCHANGE PROPERTY":
        kind = kw.label("TYPE", required=True)
        if kind not in LAWS:
            raise kw.error(f"TYPE={kind}: ventsim reads {', '.join(LAWS)}")
        rows = [floats(kw, d, 1, "property data") for d in kw.data]
        if not rows:
            raise kw.error(f"TYPE={kind}: missing data line")
        deck.exchange_props[kw.label("NAME", required=True)] = (kw, kind, rows)
    elif kw.name == "FLUID EXCHANGE":
        kw.label("NAME", required=True)
        kw.label("PROPERTY", required=True)
        if not kw.data or not kw.data[0].fields[0]:
            raise kw.error("missing data line (reference node of the first cavity[, of the second])")
        deck.exchanges.append(kw)
    elif kw.name == "FLUID EXCHANGE ACTIVATION":
        for d in kw.data:
            for name in filter(None, d.fields):
                deck.exchange_activation[name.upper()] = kw


def _law_keys(deck, pkw, kind, rows, name):
    law = LAWS[kind]
    keys = {"law": law}
    if kind in ("ORIFICE", "FABRIC LEAKAGE"):
        if len(rows) == 1:
            keys["discharge_coefficient"] = rows[0][0]
        else:
            if any(len(r) > 2 and any(r[2:]) for r in rows):
                raise pkw.error("discharge coefficient against temperature or field variables is not supported")
            keys["discharge_coefficient"] = deck.table_file(
                f"{name}_cd", [deck.si(r[1], "pressure") for r in rows], [r[0] for r in rows],
                "pressure [Pa],discharge coefficient [-]")
            keys["discharge_coefficient_of"] = "pressure"
    elif kind in ("MASS RATE LEAKAGE", "VOLUME RATE LEAKAGE"):
        if any(len(r) < 2 for r in rows) or any(len(r) > 2 and any(r[2:]) for r in rows):
            raise pkw.error("expected rows 'flow per area, |dp|' (no pressure or temperature dependence)")
        q = "mass_flux" if kind.startswith("MASS") else "volume_flux"
        unit = "kg/(s m^2)" if q == "mass_flux" else "m^3/(s m^2)"
        keys["leakage_table"] = deck.table_file(f"{name}_leakage", [deck.si(r[1], "pressure") for r in rows],
                                                [deck.si(r[0], q) for r in rows], f"|dp| [Pa],flow per area [{unit}]")
    elif kind in ("MASS FLUX", "VOLUME FLUX"):
        keys["flux"] = deck.si(rows[0][0], "mass_flux" if kind == "MASS FLUX" else "volume_flux")
    else:
        c_v, c_h = (rows[0] + [0.0])[:2]
        if len(rows) > 1:
            raise pkw.error("ventsim reads one row of resistance coefficients (no pressure dependence)")
        keys.update(viscous_resistance=deck.si(c_v, "viscous_resistance"), hydrodynamic_resistance=c_h)
    return keys


def _area_keys(deck, kw, act, cavity_surface):
    """Area keys: area, or leakage_surface (+ effective_area, blocked_by, contact_tolerance) with blockage."""
    surface, eff = kw.label("SURFACE"), kw.number("EFFECTIVE AREA")
    blockage = (act.label("BLOCKAGE") or "NO") == "YES"
    if surface is None:
        return {"area": deck.si(1.0 if eff is None else eff, "area")}
    if surface not in deck.mesh.surfaces:
        raise kw.error(f"SURFACE={surface}: no *SURFACE of that name{deck.suggest(surface, deck.mesh.surfaces)}")
    if deck.mesh.surfaces[surface].kind == "NODE":
        return _node_area_keys(deck, kw, surface, eff, deck.blockers(surface, cavity_surface, act) if blockage else ())
    faces = deck.faces(surface, kw, outward=False)
    blockers = deck.blockers(surface, cavity_surface, act) if blockage else ()
    if not blockers:
        if blockage:
            deck.notes.append(f"exchange {kw.label('NAME')}: BLOCKAGE=YES but no *CONTACT PROPERTY ASSIGNMENT with "
                              f"*BLOCKAGE pairs {surface} with a rigid surface: nothing blocks it")
        return {"area": deck.si(eff, "area") if eff is not None else deck.surface_area(faces)}
    keys = {"leakage_surface": deck.mesh_file(f"{kw.label('NAME').lower()}_leak", faces)}
    if eff is not None:
        keys["effective_area"] = deck.si(eff, "area")
    keys["blocked_by"] = [b for b, _ in blockers]
    keys["contact_tolerance"] = max(tol for _, tol in blockers)
    if deck.edge_contact:
        keys["edge_contact"] = True
    return keys


def _node_area_keys(deck, kw, surface, eff, blockers):
    """A node-based leakage surface: area EFFECTIVE AREA or the sum of its node areas; with blockers a
    ``leakage_nodes`` CSV (x, y, z, area per node), the blocked fraction being the active nodes' share."""
    nodes = list({n: (n, w, line) for n, w, line in reversed(deck.mesh.surfaces[surface].nodes)}.values())[::-1]
    for n, _, line in nodes:
        if n not in deck.mesh.nodes:
            raise deck.mesh_error(surface, line, f"{surface}: no node {n}")
    area = deck.si(eff, "area") if eff is not None else sum(deck.si(w, "area") for _, w, _ in nodes)
    if not blockers:
        return {"area": area}
    name = f"{deck.stem}/{kw.label('NAME').lower()}_leak_nodes.csv"
    deck.files[name] = "x [m],y [m],z [m],area [m^2]\n" + "".join(
        ",".join(repr(deck.si(c, "length")) for c in deck.mesh.nodes[n]) + f",{deck.si(w, 'area')!r}\n"
        for n, w, _ in nodes)
    keys = {"leakage_nodes": name, "blocked_by": [b for b, _ in blockers],
            "contact_tolerance": max(tol for _, tol in blockers)}
    if eff is not None:
        keys["effective_area"] = area
    return keys


def _activation_keys(deck, act, kw, between_cavities):
    keys = {}
    if act.param("OUTFLOW ONLY") and between_cavities:
        raise act.error(f"OUTFLOW ONLY between two cavities ({kw.label('NAME')}): the scene format lets flow "
                        "between cavities follow the pressure difference both ways")
    if act.param("DELTA LEAKAGE AREA") is not None:
        ratio = act.number("DELTA LEAKAGE AREA")
        if ratio != 1.0:
            raise act.error(f"DELTA LEAKAGE AREA={ratio}: ventsim leaks from the start of the step (ratio 1.0) only")
        keys["delta_area"] = True
    if act.label("AMPLITUDE"):
        t, a = deck.amplitude(act.label("AMPLITUDE"), act)
        keys["amplitude"] = deck.table_file(f"{kw.label('NAME').lower()}_amplitude", [deck.si(x, "time") for x in t],
                                            a, "time [s],area multiplier [-]")
    return keys


def exchange_entries(deck, cavities: dict, cavity_surfaces: dict) -> list:
    """[[exchange]] tables of the activated exchanges (``cavities``: reference node -> cavity entry)."""
    out = []
    for kw in deck.exchanges:
        name = kw.label("NAME")
        if name not in deck.exchange_activation:
            deck.notes.append(f"exchange {name} is never activated (*FLUID EXCHANGE ACTIVATION): no flow, as in Abaqus")
            continue
        d = kw.data[0]
        nodes = [ref_node(deck, kw, text=f, line=d.line) for f in d.fields[:2] if f]
        for n in nodes:
            if n not in cavities:
                raise kw.error(f"node {n} is the reference node of no *FLUID CAVITY", d.line)
        prop = kw.label("PROPERTY")
        if prop not in deck.exchange_props:
            raise kw.error(f"PROPERTY={prop}: no *FLUID EXCHANGE PROPERTY of that name"
                           f"{deck.suggest(prop, deck.exchange_props)}")
        pkw, kind, rows = deck.exchange_props[prop]
        act = deck.exchange_activation[name]
        entry = {"name": name.lower(), "from": cavities[nodes[0]]["name"],
                 "to": cavities[nodes[1]]["name"] if len(nodes) > 1 else "ambient"}
        entry.update(_law_keys(deck, pkw, kind, rows, name.lower()))
        entry.update(_area_keys(deck, kw, act, cavity_surfaces.get(nodes[0])))
        entry.update(_activation_keys(deck, act, kw, len(nodes) > 1))
        out.append(entry)
    return out
