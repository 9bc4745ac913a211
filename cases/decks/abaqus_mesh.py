"""The mesh of an Abaqus deck: *NODE, *ELEMENT, *NSET, *ELSET, *SURFACE (Abaqus Keywords Reference, those
sections), parsed here and not by meshio (meshio ends the process on element types it does not know, M3D4R).

Only surface-like elements carry a cavity, a leakage surface or a rigid blocker: shells S3/S3R/S4/S4R (and
S4R5, STRI3, second-order S6/S8R by their corner nodes), membranes M3D3/M3D4/M3D4R (M3D6/M3D8/M3D8R/M3D9 by their
corners), surface elements SFM3D3/SFM3D4/SFM3D4R (SFM3D6/SFM3D8/SFM3D8R), rigid R3D3/R3D4. Other element types
(solids, beams, connectors) are kept by number, and so are surfaces on their faces: they become an error only
when ventsim needs that surface (a cavity boundary, a leakage surface, a blocker).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from cases.decks.deck_io import deck_error

__all__ = ["Mesh", "Surface", "read_mesh", "SURFACE_ELEMENTS", "face_nodes"]

#: element type -> (number of nodes, number of corner nodes, listed first)
SURFACE_ELEMENTS = {**{t: (3, 3) for t in ("S3", "S3R", "S3RS", "STRI3", "M3D3", "SFM3D3", "R3D3")},
                    **{t: (4, 4) for t in ("S4", "S4R", "S4RS", "S4R5", "M3D4", "M3D4R", "SFM3D4", "SFM3D4R", "R3D4")},
                    **{t: (6, 3) for t in ("S6", "STRI65", "M3D6", "SFM3D6")},
                    **{t: (8, 4) for t in ("S8R", "S8R5", "M3D8", "M3D8R", "SFM3D8", "SFM3D8R")},
                    "S9R5": (9, 4), "M3D9": (9, 4), "M3D9R": (9, 4)}


@dataclass
class Surface:
    """An element-based surface (faces: element id, side SPOS / SNEG / None, line) or a node-based one (nodes:
    node id, area, line)."""

    name: str
    kind: str  # ELEMENT or NODE
    faces: list = field(default_factory=list)
    nodes: list = field(default_factory=list)
    file: str = ""
    line: int = 0


@dataclass
class Mesh:
    nodes: dict = field(default_factory=dict)  # id -> (x, y, z) in deck units
    elements: dict = field(default_factory=dict)  # id -> node ids (surface elements)
    element_type: dict = field(default_factory=dict)  # id -> type
    other: dict = field(default_factory=dict)  # id -> (type, file, line) of element types ventsim cannot use
    other_types: dict = field(default_factory=dict)  # type -> (file, line) of its first *ELEMENT
    nsets: dict = field(default_factory=dict)
    elsets: dict = field(default_factory=dict)
    surfaces: dict = field(default_factory=dict)


def _int(kw, text, d):
    try:
        value = float(text)
    except ValueError:
        raise kw.error(f"expected an integer, got {text!r}", d.line) from None
    if value != int(value):
        raise kw.error(f"expected an integer, got {text!r}", d.line)
    return int(value)


def _float(kw, text, d):
    try:
        return float(text) if text else 0.0
    except ValueError:
        raise kw.error(f"expected a number, got {text!r}", d.line) from None


def _node(mesh, kw):
    if (kw.label("SYSTEM") or "R") != "R":
        raise kw.error(f"SYSTEM={kw.label('SYSTEM')}: ventsim reads rectangular coordinates (SYSTEM=R) only")
    ids = []
    for d in kw.data:
        if len(d.fields) < 2:
            raise kw.error(f"expected 'node, x, y, z', got {', '.join(d.fields)!r}", d.line)
        nid = _int(kw, d.fields[0], d)
        xyz = [_float(kw, f, d) for f in d.fields[1:4]]
        mesh.nodes[nid] = tuple(xyz + [0.0] * (3 - len(xyz)))
        ids.append(nid)
    if kw.label("NSET"):
        mesh.nsets.setdefault(kw.label("NSET"), []).extend(ids)


def _joined(kw):
    """Element data lines with continuation lines (a line ending with a comma) joined."""
    rows, pending = [], None
    for d in kw.data:
        fields = d.fields if pending is None else pending[0] + d.fields
        start = d if pending is None else pending[1]
        if fields and fields[-1] == "":
            pending = (fields[:-1], start)
            continue
        rows.append((fields, start))
        pending = None
    if pending is not None:
        rows.append(pending)
    return rows


def _element(mesh, kw):
    etype = kw.label("TYPE", required=True)
    n, corners = SURFACE_ELEMENTS.get(etype, (None, None))
    ids = []
    for fields, d in _joined(kw):
        eid = _int(kw, fields[0], d)
        nodes = [_int(kw, f, d) for f in fields[1:] if f]
        if n is None:
            mesh.other[eid] = (etype, d.file, d.line)
            mesh.other_types.setdefault(etype, (kw.file, kw.line))
        else:
            if len(nodes) != n:
                raise kw.error(f"element {eid} of type {etype} needs {n} nodes, got {len(nodes)}", d.line)
            mesh.elements[eid], mesh.element_type[eid] = tuple(nodes[:corners]), etype
        ids.append(eid)
    if kw.label("ELSET"):
        mesh.elsets.setdefault(kw.label("ELSET"), []).extend(ids)


def _set(mesh, kw, which):
    name = kw.label(which, required=True)
    sets = mesh.nsets if which == "NSET" else mesh.elsets
    members = sets.setdefault(name, [])
    for d in kw.data:
        fields = [f for f in d.fields if f]
        if kw.param("GENERATE"):
            if len(fields) not in (2, 3):
                raise kw.error(f"GENERATE expects 'first, last[, increment]', got {', '.join(d.fields)!r}", d.line)
            a, b, step = (_int(kw, f, d) for f in (fields + ["1"])[:3])
            if step <= 0 or b < a:
                raise kw.error(f"GENERATE: bad range {a}, {b}, {step}", d.line)
            members.extend(range(a, b + 1, step))
            continue
        for f in fields:
            if f.upper() in sets:
                members.extend(sets[f.upper()])
            else:
                try:
                    members.append(int(float(f)))
                except ValueError:
                    raise kw.error(f"{f!r} is neither a number nor a defined {which.lower()}", d.line) from None
    if which == "NSET" and kw.label("ELSET"):
        for e in mesh.elsets.get(kw.label("ELSET"), []):
            members.extend(mesh.elements.get(e, ()))


def _surface(mesh, kw):
    name = kw.label("NAME", required=True)
    kind = (kw.label("TYPE") or "ELEMENT")
    if kind not in ("ELEMENT", "NODE"):
        raise kw.error(f"TYPE={kind} is not supported (ELEMENT or NODE)")
    surf = Surface(name, kind, file=kw.file, line=kw.line)
    for d in kw.data:
        label = d.fields[0].upper()
        side = d.fields[1].upper() if len(d.fields) > 1 and d.fields[1] else None
        if kind == "NODE":  # data: node or node set, the area of each node (default 1.0)
            try:
                weight = float(d.fields[1]) if len(d.fields) > 1 and d.fields[1] else 1.0
            except ValueError:
                raise kw.error(f"expected the node area, got {d.fields[1]!r}", d.line) from None
            nodes = mesh.nsets[label] if label in mesh.nsets else [_int(kw, label, d)]
            surf.nodes.extend((n, weight, d.line) for n in nodes)
            continue
        elems = mesh.elsets[label] if label in mesh.elsets else [_int(kw, label, d)]
        for e in elems:
            if e not in mesh.elements and e not in mesh.other:
                raise kw.error(f"{label}: no element {e}", d.line)
            surf.faces.append((e, side, d.line))
    mesh.surfaces[name] = surf


def read_mesh(blocks) -> Mesh:
    """The mesh of the keyword blocks (``*NODE``, ``*ELEMENT``, ``*NSET``, ``*ELSET``, ``*SURFACE``)."""
    mesh = Mesh()
    for kw in blocks:
        if kw.name == "NODE":
            _node(mesh, kw)
        elif kw.name == "ELEMENT":
            _element(mesh, kw)
        elif kw.name in ("NSET", "ELSET"):
            _set(mesh, kw, kw.name)
        elif kw.name == "SURFACE":
            _surface(mesh, kw)
        if kw.name in ("NSET", "ELSET", "NODE", "ELEMENT"):  # a set holds each member once, in first-use order
            for sets in (mesh.nsets, mesh.elsets):
                for name in [kw.label(p) for p in ("NSET", "ELSET") if kw.label(p) in sets]:
                    sets[name] = list(dict.fromkeys(sets[name]))
    return mesh


def face_nodes(mesh: Mesh, surface: Surface, *, outward: bool, file="", line=0) -> list:
    """The node ids of each face of an element surface; ``outward`` orients them away from the cavity (Abaqus
    cavity surfaces point inward, so an SPOS face is reversed)."""
    if surface.kind != "ELEMENT":
        raise deck_error(file or surface.file, line or surface.line, "SURFACE",
                         f"{surface.name} is node-based; ventsim needs an element-based surface here")
    faces = []
    for e, side, dline in surface.faces:
        if side not in (None, "SPOS", "SNEG"):
            raise deck_error(surface.file, dline, "SURFACE", f"{surface.name}: face {side} of element {e}: "
                             "ventsim reads shell, membrane and surface-element faces (SPOS, SNEG) only")
        if e in mesh.other:
            etype, efile, eline = mesh.other[e]
            raise deck_error(surface.file, dline, "SURFACE", f"{surface.name}: element {e} ({etype}, {efile} "
                             f"line {eline}) is not a shell, membrane, surface or rigid element")
        nodes = mesh.elements[e]
        missing = [n for n in nodes if n not in mesh.nodes]
        if missing:
            raise deck_error(surface.file, dline, "SURFACE", f"element {e} uses undefined node {missing[0]}")
        if outward and side is None:
            raise deck_error(surface.file, dline, "SURFACE", f"{surface.name}: a cavity boundary needs a side "
                                                             f"(SPOS or SNEG) for element {e}")
        reverse = outward and side == "SPOS"
        faces.append(tuple(reversed(nodes)) if reverse else tuple(nodes))
    return faces
