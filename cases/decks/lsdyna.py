"""An LS-DYNA control-volume airbag deck -> the scene dict a TOML file gives.

Card layouts of the LS-DYNA Keyword User's Manual (Vol. I): *NODE (8, 16, 16, 16 characters), *ELEMENT_SHELL
(EID PID N1..N4, 8 characters each; N3 = N4 is a triangle), *PART (a title card, then PID SECID MID ...),
*SET_PART_LIST, *SET_SEGMENT, *DEFINE_CURVE (LCID SIDR SFA SFO OFFA OFFO, then abscissa/ordinate pairs of 20
characters; value = SFA·(a + OFFA), SFO·(o + OFFO)), *MAT_FABRIC (card 3: AOPT FLC FAC ELA LNRC FORM FVOPT),
*AIRBAG_SIMPLE_AIRBAG_MODEL (card 1: SID SIDTYP RBID VSCA PSCA VINI MWD SPSF; card 2: CV CP T LCID MU A PE RO),
*AIRBAG_WANG_NEFSKE (card 2: CV CP T LCT LCMT TVOL LCDT IABT; card 3: C23 LCC23 A23 LCA23 CP23 LCCP23 AP23
LCAP23; card 4: PE RO GC LCEFR POVER PPOP OPT KNKDN), *AIRBAG_INTERACTION (AB1 AB2 AREA SF PID LCID IFLOW),
*AIRBAG_HYBRID (cases/decks/lsdyna_hybrid.py), *CONTROL_TERMINATION (ENDTIM), *DATABASE_ABSTAT (DT).

The bag gas is one ideal gas of constant cp, cv (J/(kg K)): molar mass M = R_u/(cp − cv), molar cp = cp·M. The
bag starts at the ambient PE and T = PE/(RO·(cp − cv)) (or IABT). Vents and fabric porosity are the isentropic
orifice law (the Wang–Nefske velocity law, docs/exchange_laws.md): vent C23·A23, porosity CP23·AP23, *MAT_FABRIC
FVOPT 1/2 Cd = FLC on FAC·(part area), FVOPT 3/4 the Graefe law with FLC, FAC; PPOP is the vent's pop pressure.
"""
from __future__ import annotations

from pathlib import Path

from cases.scene.errors import SceneError
from cases.decks.imported import Imported
from cases.decks.deck_io import ignored_line
from cases.decks.lsdyna_bags import bag_entries
from cases.decks.lsdyna_cards import W10, fields, read_dyna
from cases.decks.units import unit_system
from cases.decks.write_scene import csv_text

__all__ = ["read_lsdyna"]

MAPPED = {"KEYWORD", "TITLE", "END", "PARAMETER", "NODE", "ELEMENT_SHELL", "PART", "SET_PART_LIST", "SET_PART",
          "SET_SEGMENT",
          "DEFINE_CURVE", "DEFINE_CURVE_TITLE", "MAT_FABRIC", "MAT_034", "CONTROL_TERMINATION", "DATABASE_ABSTAT",
          "AIRBAG_INTERACTION"}
BAGS = {"AIRBAG_SIMPLE_AIRBAG_MODEL", "AIRBAG_WANG_NEFSKE", "AIRBAG_HYBRID"}


class DynaDeck:
    def __init__(self, path, units):
        self.path, self.units, self.stem = path, unit_system(units), path.stem
        self.nodes, self.shells, self.parts, self.part_sets, self.segment_sets = {}, {}, {}, {}, {}
        self.curves, self.fabrics, self.bags, self.interactions = {}, {}, [], []
        self.files, self.notes, self.ignored = {}, [], {}
        self.end, self.dt, self.title = None, None, ""

    def si(self, v, q):
        return self.units.si(v, q)

    def table_file(self, stem, x, y, header):
        name = f"{self.stem}/{stem}.csv"
        self.files[name] = csv_text(x, y, header)
        return name

    def curve(self, kw, lcid, what, xq, yq):
        if lcid not in self.curves:
            raise kw.error(f"{what}: no *DEFINE_CURVE {lcid}")
        x, y = self.curves[lcid]
        return [self.si(v, xq) for v in x], [self.si(v, yq) for v in y]


def _sets(deck, kw):
    cards = kw.cards[1:] if kw.name.endswith("_TITLE") else kw.cards
    if not cards:
        raise kw.error("missing the set card (SID ...)")
    sid = fields(kw, cards[0], W10, "i")[0]
    if kw.name.startswith("SET_SEGMENT"):
        deck.segment_sets[sid] = [tuple(n for n in fields(kw, c, W10, "iiii") if n) for c in cards[1:]]
    else:
        deck.part_sets[sid] = [p for c in cards[1:] for p in fields(kw, c, W10, "iiiiiiii") if p]


def _geometry(deck, kw):
    if kw.name == "NODE":
        for c in kw.cards:
            nid, x, y, z = fields(kw, c, (8, 16, 16, 16), "ifff")
            deck.nodes[nid] = (x or 0.0, y or 0.0, z or 0.0)
    elif kw.name.startswith("ELEMENT_SHELL"):
        if kw.name not in ("ELEMENT_SHELL", "ELEMENT_SHELL_THICKNESS", "ELEMENT_SHELL_BETA"):
            raise kw.error("ventsim reads *ELEMENT_SHELL, *ELEMENT_SHELL_THICKNESS and *ELEMENT_SHELL_BETA")
        step = 1 if kw.name == "ELEMENT_SHELL" else 2  # the options add a thickness card per element
        for c in kw.cards[::step]:
            eid, pid, *ns = fields(kw, c, (8,) * 6, "iiiiii")
            if None in ns[:3]:
                raise kw.error(f"element {eid}: expected EID PID N1 N2 N3 N4", c[1])
            deck.shells[eid] = (pid, tuple(ns[:3]) if ns[3] in (None, ns[2]) else tuple(ns))
    elif kw.name == "PART":
        for title, card in zip(kw.cards[0::2], kw.cards[1::2]):
            pid, _, mid = fields(kw, card, W10, "iii")
            deck.parts[pid] = (mid, title[2].strip())
    elif kw.name in ("SET_PART_LIST", "SET_PART", "SET_PART_LIST_TITLE", "SET_SEGMENT", "SET_SEGMENT_TITLE"):
        _sets(deck, kw)
    else:
        return False
    return True


def _curve(deck, kw):
    cards = kw.cards[1:] if kw.name.endswith("_TITLE") else kw.cards
    lcid, _, sfa, sfo, offa, offo = fields(kw, cards[0], W10, "iiffff")
    sfa, sfo = sfa or 1.0, sfo or 1.0
    pts = [fields(kw, c, (20, 20), "ff") for c in cards[1:]]
    deck.curves[lcid] = ([sfa * ((a or 0.0) + (offa or 0.0)) for a, _ in pts],
                         [sfo * ((o or 0.0) + (offo or 0.0)) for _, o in pts])


def _other(deck, kw):
    if kw.name in ("DEFINE_CURVE", "DEFINE_CURVE_TITLE"):
        _curve(deck, kw)
    elif kw.name in ("MAT_FABRIC", "MAT_034"):
        mid = fields(kw, kw.cards[0], W10, "i")[0]
        if len(kw.cards) < 3:
            raise kw.error("expected at least 3 cards (card 3: AOPT FLC FAC ELA LNRC FORM FVOPT)")
        _, flc, fac, ela, _, _, fvopt = fields(kw, kw.cards[2], W10, "fffffff")
        deck.fabrics[mid] = (kw, flc or 0.0, fac or 0.0, ela or 0.0, int(fvopt or 0))
    elif kw.name == "CONTROL_TERMINATION":
        deck.end = fields(kw, kw.cards[0], W10, "f")[0]
    elif kw.name == "DATABASE_ABSTAT":
        deck.dt = fields(kw, kw.cards[0], W10, "f")[0]
    elif kw.name == "AIRBAG_INTERACTION":
        deck.interactions += [(kw, c, fields(kw, c, W10, "iiffiii")) for c in kw.cards]
    elif kw.name == "TITLE" and kw.cards:
        deck.title = kw.cards[0][2].strip()


def _keyword(deck, kw):
    base = kw.name[:-3] if kw.name.endswith("_ID") else kw.name
    if base in BAGS:
        deck.bags.append((base, kw))
    elif base.startswith("AIRBAG_") and base != "AIRBAG_INTERACTION":
        raise kw.error("not supported: ventsim reads *AIRBAG_SIMPLE_AIRBAG_MODEL, *AIRBAG_WANG_NEFSKE, "
                       "*AIRBAG_HYBRID and *AIRBAG_INTERACTION")
    elif not (_geometry(deck, kw) or kw.name not in MAPPED and _ignore(deck, kw)):
        _other(deck, kw)


def read_lsdyna(path, units: str = "SI") -> Imported:
    """Read the LS-DYNA deck at ``path`` (values in ``units``) into an :class:`Imported` scene."""
    path = Path(path)
    deck = DynaDeck(path, units)
    for kw in read_dyna(path):
        try:
            _keyword(deck, kw)
        except IndexError:
            raise kw.error("missing cards (the LS-DYNA Keyword User's Manual gives this keyword's cards)") from None
    if not deck.bags:
        raise SceneError(path, "", "no *AIRBAG_SIMPLE_AIRBAG_MODEL, *AIRBAG_WANG_NEFSKE or *AIRBAG_HYBRID: nothing "
                                   "to simulate")
    if deck.end is None:
        raise SceneError(path, "", "no *CONTROL_TERMINATION (ENDTIM): the run has no end time")
    data = {"title": deck.title or f"imported from {path.name}", "time": {"end": deck.si(deck.end, "time")}}
    if deck.dt:
        data["time"]["output_interval"] = deck.si(deck.dt, "time")
    data.update(bag_entries(deck))
    return Imported(path.name, data, deck.files, list(deck.ignored.values()), deck.notes)


def _ignore(deck, kw):
    if kw.name not in deck.ignored:
        deck.ignored[kw.name] = ignored_line(kw.name, kw.file, kw.line, deck.path)
    return True
