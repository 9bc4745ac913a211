"""Abaqus contact blockage and rigid-body motion -> [[body]] tables and an exchange's blocked_by.

Keywords Reference sections: *SURFACE INTERACTION with *BLOCKAGE (the surfaces a *CONTACT PROPERTY ASSIGNMENT
pairs through it can block a leakage surface, Analysis User's Guide "Contact blockage") and *SURFACE BEHAVIOR
(PRESSURE-OVERCLOSURE: the clearance c0 of EXPONENTIAL, or of the first zero-pressure row of TABULAR, is the
distance at which ventsim flags a leakage node; HARD and LINEAR flag it at contact, gap 0); *RIGID BODY
(REF NODE, ELSET) and *BOUNDARY (TYPE=DISPLACEMENT or VELOCITY, AMPLITUDE; data: node or set, first and last
degree of freedom, magnitude) on its reference node as prescribed translation.
"""
from __future__ import annotations

import math

from cases.decks.abaqus_fluid import floats

__all__ = ["read_contact", "blockers"]


def read_contact(deck, kw, parent):
    """Store contact and rigid-body keywords; returns the *SURFACE INTERACTION a sub-option would follow."""
    if kw.name == "SURFACE INTERACTION":
        name = kw.label("NAME", required=True)
        deck.interactions[name] = {"kw": kw, "blockage": None, "tolerance": 0.0}
        return name
    if kw.name in ("BLOCKAGE", "SURFACE BEHAVIOR"):
        if parent is None:
            raise kw.error("must follow *SURFACE INTERACTION")
        if kw.name == "BLOCKAGE":
            deck.interactions[parent]["blockage"] = kw
        else:
            deck.interactions[parent]["tolerance"] = _clearance(deck, kw)
        return parent
    if kw.name == "CONTACT PROPERTY ASSIGNMENT":
        for d in kw.data:
            if len(d.fields) < 3 or not all(d.fields[:3]):
                raise kw.error("expected 'surface 1, surface 2, interaction property' (ventsim needs both surfaces "
                               "named)", d.line)
            deck.assignments.append((d.fields[0].upper(), d.fields[1].upper(), d.fields[2].upper(), kw, d.line))
    elif kw.name == "RIGID BODY":
        node, elset = kw.param("REF NODE"), kw.label("ELSET")
        if elset is None or elset not in deck.mesh.elsets:
            raise kw.error("ventsim reads rigid bodies given by ELSET= (a defined element set)")
        from cases.decks.abaqus_fluid import ref_node
        deck.rigid_bodies.append((ref_node(deck, kw), set(deck.mesh.elsets[elset]), kw))
    elif kw.name == "BOUNDARY":
        _boundary(deck, kw)
    return None


def _clearance(deck, kw):
    law = kw.label("PRESSURE-OVERCLOSURE") or "HARD"
    if law == "EXPONENTIAL":
        if not kw.data:
            raise kw.error("EXPONENTIAL needs a data line 'clearance, pressure at zero clearance'")
        return deck.si(floats(kw, kw.data[0], 2, "clearance, pressure")[0], "length")
    if law == "TABULAR":
        rows = [floats(kw, d, 2, "pressure, overclosure") for d in kw.data]
        return deck.si(max(0.0, -rows[0][1]), "length") if rows else 0.0
    if law not in ("HARD", "LINEAR"):
        raise kw.error(f"PRESSURE-OVERCLOSURE={law}: ventsim reads HARD, LINEAR, EXPONENTIAL, TABULAR")
    return 0.0


def _boundary(deck, kw):
    kind = kw.label("TYPE") or "DISPLACEMENT"
    for d in kw.data:
        target = d.fields[0].upper()
        nodes = deck.mesh.nsets.get(target) or ([int(float(target))] if target.replace(".", "").isdigit() else [])
        if len(d.fields) < 2 or not d.fields[1] or not d.fields[1].replace(".", "").isdigit():
            for n in nodes:  # ENCASTRE, PINNED, XSYMM, ...: fixed
                deck.boundaries.setdefault(n, {}).update({dof: ("DISPLACEMENT", 0.0, None, kw, d.line)
                                                          for dof in range(1, 7)})
            continue
        v = floats(kw, d.__class__(d.fields[1:], d.file, d.line), 1, "first dof, last dof, magnitude")
        first, last = int(v[0]), int(v[1]) if len(v) > 1 and v[1] else int(v[0])
        magnitude = v[2] if len(v) > 2 else 0.0
        for n in nodes:
            for dof in range(first, last + 1):
                deck.boundaries.setdefault(n, {})[dof] = (kind, magnitude, kw.label("AMPLITUDE"), kw, d.line)


def _motion(deck, ref, kw):
    """Scene motion keys of the rigid body with reference node ``ref``."""
    bcs = deck.boundaries.get(ref, {})
    for dof in (4, 5, 6):
        if dof in bcs and bcs[dof][1] != 0.0:
            raise bcs[dof][3].error(f"rotation of rigid body node {ref} (dof {dof}): ventsim prescribes "
                                    "translation only", bcs[dof][4])
    moving = {dof: bcs[dof] for dof in (1, 2, 3) if dof in bcs and bcs[dof][1] != 0.0}
    for tkw in deck.transforms:
        if moving and ref in deck.mesh.nsets.get(tkw.label("NSET") or "", ()):
            raise tkw.error(f"rigid body node {ref} moves along transformed directions: ventsim reads *BOUNDARY "
                            "in global axes")
    if not moving:
        if any(dof not in bcs for dof in (1, 2, 3)):
            deck.notes.append(f"rigid body of node {ref} ({kw.label('ELSET')}) has free translations: ventsim holds "
                              "it fixed (no contact forces)")
        return {}
    kinds = {b[0] for b in moving.values()}
    amps = {b[2] for b in moving.values()}
    first = next(iter(moving.values()))
    if len(kinds) > 1 or len(amps) > 1:
        raise first[3].error(f"node {ref}: all moving directions need the same TYPE and AMPLITUDE", first[4])
    vec = [moving[d][1] if d in moving else 0.0 for d in (1, 2, 3)]
    size = math.sqrt(sum(x * x for x in vec))
    axis = [x / size for x in vec]
    kind, amp = kinds.pop(), amps.pop()
    if kind == "VELOCITY":
        scale = 1.0
        if amp is not None:
            _, a = deck.amplitude(amp, first[3])
            if any(x != a[0] for x in a):
                raise first[3].error(f"TYPE=VELOCITY with AMPLITUDE={amp}: ventsim prescribes a constant speed; "
                                     "give TYPE=DISPLACEMENT with an amplitude instead", first[4])
            scale = a[0]
        return {"axis": axis, "velocity": deck.si(size * scale, "velocity")}
    t, a = deck.amplitude(amp, first[3]) if amp is not None else ([0.0], [1.0])
    table = deck.table_file(f"body_{ref}_displacement", [deck.si(x, "time") for x in t],
                            [deck.si(size * x, "length") for x in a], "time [s],displacement [m]")
    return {"axis": axis, "displacement_table": table}


def _body(deck, surface, kw, line):
    """The [[body]] of a blocking surface (made once), moving with the rigid body its elements belong to."""
    name = surface.lower()
    if name in deck.bodies:
        return name
    if surface not in deck.mesh.surfaces:
        raise kw.error(f"no *SURFACE named {surface}{deck.suggest(surface, deck.mesh.surfaces)}", line)
    faces = deck.faces(surface, kw, outward=False)
    elements = {e for e, _, _ in deck.mesh.surfaces[surface].faces}
    owner = [(ref, rkw) for ref, elset, rkw in deck.rigid_bodies if elements <= elset]
    if not owner:
        raise kw.error(f"{surface} blocks a leakage surface but is not part of a *RIGID BODY: ventsim's "
                       "blockers are rigid", line)
    entry = {"name": name, "mesh": deck.mesh_file(f"body_{name}", faces)}
    entry.update(_motion(deck, *owner[0]))
    deck.bodies[name] = entry
    return name


def blockers(deck, leak_surface, cavity_surface, act):
    """(body name, contact tolerance [m]) of the surfaces that can block ``leak_surface``."""
    out = []
    for s1, s2, prop, kw, line in deck.assignments:
        inter = deck.interactions.get(prop)
        if inter is None:
            raise kw.error(f"no *SURFACE INTERACTION named {prop}{deck.suggest(prop, deck.interactions)}", line)
        if inter["blockage"] is None:
            continue
        own = {leak_surface, cavity_surface} - {None}
        if s1 in own or s2 in own:
            other = s2 if s1 in own else s1
            out.append((_body(deck, other, kw, line), inter["tolerance"]))
    return out
