"""Parts, assembly and instances of an Abaqus deck (Keywords Reference: *PART, *END PART, *ASSEMBLY, *INSTANCE,
*END INSTANCE, *END ASSEMBLY) flattened into top-level mesh keywords, as Abaqus itself does.

Each *INSTANCE, NAME=I, PART=P copies P's *NODE, *ELEMENT, *NSET, *ELSET and *SURFACE (and the mesh written
inside the instance itself) with node and element numbers shifted by the instance's offset and set and surface
names prefixed ``I.`` (the names the assembly and model levels use, e.g. ``I.VENT, SPOS``). The instance's
optional data lines move its nodes: a translation (x, y, z), then a rotation by an angle [degrees] about the axis
through points a and b (translation first). Assembly-level *NSET/*ELSET with INSTANCE=I number I's nodes and
elements; a label ``I.12`` anywhere else is node (or element) 12 of instance I.
"""
from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np

from cases.decks.abaqus_lexer import DataLine, Keyword

__all__ = ["flatten_parts"]

MESH = ("NODE", "ELEMENT", "NSET", "ELSET", "SURFACE")
#: node and element numbers of instance k start at OFFSET * (k + 1)
OFFSET = 10 ** 9
_LABEL = re.compile(r"^(?P<inst>[^.\s]+)\.(?P<num>\d+)$")


def _num(kw, text, d):
    try:
        return int(float(text))
    except ValueError:
        raise kw.error(f"expected a node or element number, got {text!r}", d.line) from None


def _relabel(kw, prefix, offset, sets):
    """A copy of mesh keyword ``kw`` in an instance's namespace."""
    params = dict(kw.params)
    for p in ("NSET", "ELSET", "NAME"):
        if isinstance(params.get(p), str):
            params[p] = f"{prefix}.{params[p]}"
    rows = []
    for d in kw.data:
        f = list(d.fields)
        if kw.name in ("NODE", "ELEMENT"):
            count = 1 if kw.name == "NODE" else len(f)
            f = [str(_num(kw, x, d) + offset) if i < count and x else x for i, x in enumerate(f)]
        elif kw.name in ("NSET", "ELSET"):
            if kw.param("GENERATE"):
                f = [str(_num(kw, x, d) + offset) if i < 2 and x else x for i, x in enumerate(f)]
            else:
                f = [f"{prefix}.{x}" if x.upper() in sets else (str(_num(kw, x, d) + offset) if x else x) for x in f]
        elif f and f[0]:  # SURFACE: an element set, an element number, or (TYPE=NODE) a node set / number
            f[0] = f"{prefix}.{f[0]}" if f[0].upper() in sets else str(_num(kw, f[0], d) + offset)
        rows.append(DataLine(tuple(f), d.file, d.line))
    return Keyword(kw.name, params, kw.file, kw.line, rows)


def _floats(kw, d):
    try:
        return [float(x) if x else 0.0 for x in d.fields]
    except ValueError:
        raise kw.error(f"expected numbers, got {', '.join(d.fields)!r}", d.line) from None


def _transform(kw):
    """The affine map of an *INSTANCE's data lines (translation, then rotation about a–b)."""
    lines = [_floats(kw, d) for d in kw.data]
    shift = np.array((lines[0] + [0.0] * 3)[:3]) if lines else np.zeros(3)
    rot = np.eye(3)
    if len(lines) > 1:
        r = (lines[1] + [0.0] * 7)[:7]
        a, b, angle = np.array(r[:3]), np.array(r[3:6]), math.radians(r[6])
        axis = b - a
        if np.linalg.norm(axis) == 0.0:
            raise kw.error("rotation axis: points a and b coincide", kw.data[1].line)
        k = axis / np.linalg.norm(axis)
        K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        rot = np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K
        return lambda x: rot @ (np.asarray(x) + shift - a) + a
    return lambda x: np.asarray(x) + shift


def _place_nodes(kw, move):
    rows = []
    for d in kw.data:
        xyz = _floats(kw, DataLine(d.fields[1:4], d.file, d.line))
        p = move((xyz + [0.0] * 3)[:3])
        rows.append(DataLine((d.fields[0], *(repr(float(c)) for c in p)), d.file, d.line))
    return replace(kw, data=rows)


def _set_names(blocks):
    return {kw.label(p) for kw in blocks for p in ("NSET", "ELSET", "NAME") if kw.name in MESH and kw.label(p)}


def _instance(kw, body, parts, k):
    name, part = kw.label("NAME", required=True), kw.label("PART")
    if part is not None and part not in parts:
        raise kw.error(f"PART={part}: no *PART of that name")
    blocks = (parts.get(part, []) if part else []) + body
    sets, offset, move = _set_names(blocks), OFFSET * (k + 1), _transform(kw)
    out = []
    for b in blocks:
        if b.name in MESH:
            b = _relabel(b, name, offset, sets)
            out.append(_place_nodes(b, move) if b.name == "NODE" else b)
    return name, offset, out


def _labels(kw, offsets):
    """``I.12`` -> node/element 12 of instance I, in parameters and data fields."""
    def fix(text):
        m = _LABEL.match(text) if isinstance(text, str) else None
        if m and m.group("inst").upper() in offsets:
            return str(offsets[m.group("inst").upper()] + int(m.group("num")))
        return text
    params = {k: fix(v) for k, v in kw.params.items()}
    data = [DataLine(tuple(fix(f) for f in d.fields), d.file, d.line) for d in kw.data]
    inst = kw.label("INSTANCE") if kw.name in ("NSET", "ELSET") else None
    if inst is not None:
        if inst not in offsets:
            raise kw.error(f"INSTANCE={inst}: no *INSTANCE of that name")
        data = [DataLine(tuple(str(int(float(f)) + offsets[inst]) if f and _LABEL.match(f) is None and
                               f.replace(".", "").isdigit() else (f"{inst}.{f}" if f else f) for f in d.fields),
                         d.file, d.line) for d in data]
        params.pop("INSTANCE")
    return Keyword(kw.name, params, kw.file, kw.line, data)


def flatten_parts(blocks) -> list:
    """The keyword blocks with parts and instances expanded (unchanged when the deck has none)."""
    if not any(kw.name in ("PART", "INSTANCE", "ASSEMBLY") for kw in blocks):
        return blocks
    parts, out, offsets = {}, [], {}
    current_part, instance, body = None, None, []
    for kw in blocks:
        if kw.name == "PART":
            current_part = kw.label("NAME", required=True)
            parts[current_part] = []
        elif kw.name == "END PART":
            current_part = None
        elif current_part is not None:
            parts[current_part].append(kw) if kw.name in MESH else out.append(kw)
        elif kw.name == "INSTANCE":
            instance, body = kw, []
        elif kw.name == "END INSTANCE":
            name, offset, copies = _instance(instance, body, parts, len(offsets))
            offsets[name] = offset
            out += copies
            instance = None
        elif instance is not None:
            body.append(kw) if kw.name in MESH else out.append(kw)
        elif kw.name not in ("ASSEMBLY", "END ASSEMBLY"):
            out.append(kw)
    return [_labels(kw, offsets) if offsets else kw for kw in out]
