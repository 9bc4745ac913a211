"""LS-DYNA control volumes -> [[species]], [[cavity]], [[exchange]] (see cases/decks/lsdyna.py for the cards).

LS-DYNA Keyword User's Manual: *AIRBAG (common card 1: SID SIDTYP RBID VSCA PSCA VINI MWD SPSF), *AIRBAG_SIMPLE_
AIRBAG_MODEL, *AIRBAG_WANG_NEFSKE, *AIRBAG_INTERACTION, *MAT_FABRIC (FLC, FAC, ELA, FVOPT).
"""
from __future__ import annotations

from cases.decks.conversions import constant_cp_species
from cases.decks.deck_io import faces_area
from cases.decks.lsdyna_cards import W10, fields, refuse
from cases.decks.lsdyna_hybrid import hybrid_gas
from cases.decks.write_scene import obj_text

__all__ = ["bag_entries"]



def _faces(deck, kw, sid, sidtyp):
    if sidtyp == 1:
        if sid not in deck.part_sets:
            raise kw.error(f"SID {sid}: no *SET_PART_LIST {sid}")
        pids = set(deck.part_sets[sid])
        faces = [(pid, nodes) for pid, nodes in deck.shells.values() if pid in pids]
    elif sidtyp in (0, None):
        if sid not in deck.segment_sets:
            raise kw.error(f"SID {sid}: no *SET_SEGMENT {sid}")
        faces = [(None, s if len(s) == 3 or s[3] != s[2] else s[:3]) for s in deck.segment_sets[sid]]
    else:
        raise kw.error(f"SIDTYP={sidtyp}: expected 0 (segment set) or 1 (part set)")
    if not faces:
        raise kw.error(f"SID {sid} (SIDTYP {sidtyp or 0}): the set has no shell elements or segments")
    for _, f in faces:
        for n in f:
            if n not in deck.nodes:
                raise kw.error(f"SID {sid}: a segment uses undefined node {n}")
    return faces


def _area(deck, faces):
    return faces_area(faces, {n: [deck.si(c, "length") for c in deck.nodes[n]] for f in faces for n in f})


def _id_cards(kw):
    """(id, cards): the _ID option puts the bag's id (and a title) on a card of its own before card 1."""
    if kw.name.endswith("_ID"):
        return fields(kw, kw.cards[0], (10, 70), "is")[0], kw.cards[1:]
    return None, kw.cards


def _mesh(deck, kw, name, faces):
    import trimesh

    from cavity.volume import MeshError, closed_mesh_volume

    xyz = {n: tuple(deck.si(c, "length") for c in deck.nodes[n]) for _, f in faces for n in f}
    file = f"{deck.stem}/{name}.obj"
    deck.files[file] = obj_text([f for _, f in faces], xyz, f"{name}: from {deck.path.name}")
    mesh = trimesh.load(trimesh.util.wrap_as_stream(deck.files[file]), file_type="obj", force="mesh")
    try:
        closed_mesh_volume(mesh, name=f"the bag surface of {kw.name}")
    except MeshError as exc:
        raise kw.error(str(exc)) from None
    return file


def _wang_nefske(kw, cards):
    """Gas, inflator curves, vents and ambient of card 2-4 of *AIRBAG_WANG_NEFSKE / card 2 of the simple model."""
    if kw.name.startswith("AIRBAG_SIMPLE"):
        cv, cp, t, lcid, mu, a, pe, ro = fields(kw, cards[1], W10, "fffiffff")
        return dict(cv=cv, cp=cp, t=t, lct=None, lcmt=lcid, vents=[("vent", mu, a)], pe=pe, ro=ro, ppop=None,
                    iabt=None)
    cv, cp, t, lct, lcmt, tvol, lcdt, iabt = fields(kw, cards[1], W10, "fffiifif")
    refuse(kw, cards[1], ("TVOL", "LCDT"), (tvol, lcdt))
    c23, lcc23, a23, lca23, cp23, lccp23, ap23, lcap23 = fields(kw, cards[2], W10, "fififif" + "i")
    refuse(kw, cards[2], ("LCC23", "LCA23", "LCCP23", "LCAP23"), (lcc23, lca23, lccp23, lcap23))
    pe, ro, gc, lcefr, pover, ppop, opt, knkdn = fields(kw, cards[3], W10, "fffiffii")
    refuse(kw, cards[3], ("LCEFR", "POVER", "OPT", "KNKDN"), (lcefr, pover, opt, knkdn))
    return dict(cv=cv, cp=cp, t=t, lct=lct, lcmt=lcmt, vents=[("vent", c23, a23), ("porosity", cp23, ap23)], pe=pe,
                ro=ro, ppop=ppop, iabt=iabt)


def _inflator(deck, kw, name, g):
    if not g["lcmt"]:
        deck.notes.append(f"{name}: no mass flow curve (LCMT/LCID = 0): no inflator")
        return []
    t, m = deck.curve(kw, g["lcmt"], "LCMT", "time", "mass_flow")
    entry = {"name": "inflator", "type": "mass_temperature",
             "mass_flow": deck.table_file(f"{name}_mass_flow", t, m, "time [s],mass flow [kg/s]"),
             "gas": {f"{name}_gas": 1.0}}  # the bag's gas (the scene's default inflator gas is N2)
    if g["lct"]:  # the optional curve of the gas temperature takes precedence over the constant T
        tt, tv = deck.curve(kw, g["lct"], "LCT", "time", "dimensionless")
        entry["temperature"] = deck.table_file(f"{name}_temperature", tt, tv, "time [s],temperature [K]")
    elif g["t"]:
        entry["temperature"] = float(g["t"])
    else:
        raise kw.error("the inflator gas needs a temperature T or a curve LCT")
    return [entry]


def _fabric(deck, name, faces):
    out = []
    for pid in sorted({p for p, _ in faces if p is not None}):
        mid = deck.parts.get(pid, (None, ""))[0]
        if mid not in deck.fabrics:
            continue
        fkw, flc, fac, ela, fvopt = deck.fabrics[mid]
        if fvopt == 0:
            continue
        if fvopt > 4:
            raise fkw.error(f"FVOPT={fvopt}: ventsim reads 1-4 (Wang-Nefske, Graefe)")
        if fvopt % 2 == 0:
            deck.notes.append(f"part {pid}: FVOPT={fvopt} asks for blockage of the fabric leakage; the deck has no "
                              "blocking body for ventsim, the leakage is unblocked (ELA unused)")
        area = _area(deck, [f for p, f in faces if p == pid])
        flc, fac = flc or 1.0, fac or 1.0
        entry = {"name": f"{name}_fabric_{pid}", "from": name, "to": "ambient"}
        if fvopt <= 2:
            entry.update(law="orifice", area=fac * area, discharge_coefficient=flc)
        else:
            entry.update(law="graefe", area=area, flc=flc, fac=fac)
        out.append(entry)
    return out


def _constant_gas(deck, kw, cards, name):
    """([species], cavity state, vents, pop pressure) of the simple and Wang–Nefske models: one gas, constant cp."""
    g = _wang_nefske(kw, cards)
    r = deck.si(g["cp"] or 0.0, "specific_heat") - deck.si(g["cv"] or 0.0, "specific_heat")
    if not r > 0:
        raise kw.error(f"CP - CV = {r!r}: expected CP > CV > 0 (J/(kg K))", cards[1][1])
    M, cp_molar = constant_cp_species(deck.si(g["cp"], "specific_heat"), deck.si(g["cv"], "specific_heat"))
    pe, ro = deck.si(g["pe"] or 0.0, "pressure"), deck.si(g["ro"] or 0.0, "density")
    if not (pe > 0 and (ro > 0 or g["iabt"])):
        raise kw.error("PE and RO (ambient pressure and density) must be > 0")
    species = {"name": f"{name}_gas", "molar_mass": M, "cp": [cp_molar]}
    state = {"pressure": pe, "temperature": float(g["iabt"]) if g["iabt"] else pe / (ro * r),
             "gas": {species["name"]: 1.0}}
    inflators = _inflator(deck, kw, name, g)
    if inflators:
        state["inflator"] = inflators
    return [species], state, g["vents"], g["ppop"]


def _vents(deck, kw, name, vents, ppop):
    out = []
    for vent, cd, area in vents:
        if area and area < 0:
            raise kw.error(f"{vent} area {area} < 0 (an area curve): not supported")
        if area:
            e = {"name": f"{name}_{vent}", "from": name, "to": "ambient", "law": "orifice",
                 "area": deck.si(area, "area"), "discharge_coefficient": cd if cd is not None else 1.0}
            if vent == "vent" and ppop:
                e["pop_pressure"] = deck.si(ppop, "pressure")
            out.append(e)
    return out


def _bag(deck, base, kw, number):
    """(id, [species], cavity, exchanges) of one control volume."""
    bid, cards = _id_cards(kw)
    if len(cards) < (2 if base == "AIRBAG_SIMPLE_AIRBAG_MODEL" else 4):
        raise kw.error("missing cards (see the LS-DYNA Keyword User's Manual for this keyword)")
    sid, sidtyp, _, vsca, psca, vini, _, _ = fields(kw, cards[0], W10, "iiifffff")
    for n, v, ok in (("VSCA", vsca, 1.0), ("PSCA", psca, 1.0), ("VINI", vini, 0.0)):
        if v not in (None, ok):
            raise kw.error(f"{n} = {v}: ventsim reads {n} = {ok} only", cards[0][1])
    name = f"bag{bid if bid is not None else number}"
    faces = _faces(deck, kw, sid, sidtyp)
    gas = hybrid_gas if base == "AIRBAG_HYBRID" else _constant_gas
    species, state, vents, ppop = gas(deck, kw, cards, name)
    cavity = {"name": name, **{k: state[k] for k in ("pressure", "temperature", "gas")}, "energy": "adiabatic",
              "mesh": _mesh(deck, kw, name, faces)}
    if "inflator" in state:
        cavity["inflator"] = state["inflator"]
    exchanges = _vents(deck, kw, name, vents, ppop) + _fabric(deck, name, faces)
    return bid if bid is not None else number, species, cavity, exchanges


def _interactions(deck, ids):
    out = []
    for kw, card, (ab1, ab2, area, sf, pid, lcid, iflow) in deck.interactions:
        refuse(kw, card, ("PID", "LCID", "IFLOW"), (pid, lcid, iflow))
        for ab in (ab1, ab2):
            if ab not in ids:
                raise kw.error(f"no airbag {ab} (airbags: {', '.join(map(str, ids))})", card[1])
        out.append({"name": f"{ids[ab1]}_to_{ids[ab2]}", "from": ids[ab1], "to": ids[ab2], "law": "orifice",
                    "area": deck.si(area or 0.0, "area"), "discharge_coefficient": sf if sf else 1.0})
    return out


def bag_entries(deck) -> dict:
    """The scene tables of every control volume, their vents and interactions, and the ambient."""
    species, cavities, exchanges, ids = [], [], [], {}
    for number, (base, kw) in enumerate(deck.bags, start=1):
        try:
            bid, sp, cav, ex = _bag(deck, base, kw, number)
        except IndexError:
            raise kw.error("missing cards (the LS-DYNA Keyword User's Manual gives this keyword's cards)") from None
        ids[bid] = cav["name"]
        species += sp
        cavities.append(cav)
        exchanges += ex
    pressures = {c["pressure"] for c in cavities}
    if len(pressures) > 1:
        raise deck.bags[-1][1].error(f"airbags with different ambient pressures PE {sorted(pressures)}")
    first = cavities[0]
    ambient = {"pressure": first["pressure"], "temperature": first["temperature"], "gas": dict(first["gas"])}
    exchanges += _interactions(deck, ids)
    out = {"ambient": ambient, "species": species, "cavity": cavities}
    if exchanges:
        out["exchange"] = exchanges
    return out
