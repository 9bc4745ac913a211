"""Sweep designs: dotted keys into a scene's TOML data, their values, and the variants a design makes.

A key addresses the parsed TOML (before validation), with lists of tables addressed by their ``name`` or by
index: ``time.end``, ``exchange.vent.area``, ``exchange[0].area``, ``cavity.cushion.inflator.inflator.scale``,
``ambient.gas.N2``, ``species.N2.cp[0]``. :func:`resolve_key` checks a key against the scene and its schema once,
up front (an unknown key fails with suggestions); :func:`apply_variant` writes values into a copy of the data.

Values (``--vary KEY=VALUES``) are comma lists of scalars and ranges: ``0.5,0.6,0.7``, ``linspace(a,b,n)``,
``geomspace(a,b,n)``; for a Latin hypercube, ``lo:hi`` (or any numeric list: its minimum and maximum).

>>> parse_values("0.5,linspace(1,2,3),true,DOP853")
[0.5, 1.0, 1.5, 2.0, True, 'DOP853']
>>> full_design({"a": [1, 2], "b": ["x", "y"]})
[{'a': 1, 'b': 'x'}, {'a': 1, 'b': 'y'}, {'a': 2, 'b': 'x'}, {'a': 2, 'b': 'y'}]
>>> variant_id({"a": 1}) == variant_id({"a": 1.0})
True
"""
from __future__ import annotations

import copy
import csv
import hashlib
import itertools
import json
import math
import re
from dataclasses import fields
from functools import cache
from pathlib import Path

import numpy as np

from cases.scene.errors import SceneError, SweepError
from cases.scene.schema import suggest, toml_name
from cases.sweep.folder import DESIGNS

__all__ = ["SweepError", "DESIGNS", "parse_values", "parse_vary", "parse_scalar", "full_design", "list_design",
           "lhs_design", "read_variants", "make_design", "resolve_key", "apply_variant", "variant_id",
           "canonical"]

_RANGES = {"linspace": np.linspace, "geomspace": np.geomspace}


# ---------------------------------------------------------------------------------------------------- values

def parse_scalar(text: str):
    """A TOML-like scalar from text: bool, int, float, or a string (quotes optional).

    >>> [parse_scalar(s) for s in ("3", "2.5e-4", "false", "'a,b'", "orifice")]
    [3, 0.00025, False, 'a,b', 'orifice']
    """
    t = text.strip()
    if len(t) >= 2 and t[0] == t[-1] and t[0] in "'\"":
        return t[1:-1]
    if t in ("true", "false"):
        return t == "true"
    for kind in (int, float):
        try:
            return kind(t)
        except ValueError:
            pass
    return t


def _split_top(text: str) -> list:
    """Split on commas outside parentheses and quotes."""
    parts, depth, quote, cur = [], 0, "", ""
    for ch in text:
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        cur += ch
    return parts + [cur]


def parse_values(text: str, key: str = "") -> list:
    """The values of one ``--vary`` (comma list, ``linspace(a,b,n)``, ``geomspace(a,b,n)``)."""
    out = []
    for item in _split_top(text):
        item = item.strip()
        if not item:
            raise SweepError(f"--vary {key}={text}: empty value")
        m = re.fullmatch(r"(\w+)\((.*)\)", item)
        if m and m.group(1) in _RANGES:
            try:
                a, b, n = (float(v) for v in m.group(2).split(","))
                if n != int(n) or n < 1:
                    raise ValueError
                out += [float(v) for v in _RANGES[m.group(1)](a, b, int(n))]
            except ValueError:
                raise SweepError(f"--vary {key}={text}: expected {m.group(1)}(start,stop,count), got {item!r}") \
                    from None
            continue
        out.append(parse_scalar(item))
    return out


def parse_vary(items) -> dict:
    """``["KEY=VALUES", ...]`` -> {key: values text}, keys in the order given."""
    out = {}
    for item in items or ():
        key, eq, text = item.partition("=")
        if not eq or not key.strip() or not text.strip():
            raise SweepError(f"--vary {item!r}: expected KEY=VALUES, e.g. exchange.vent.area=1e-4,2e-4")
        if key.strip() in out:
            raise SweepError(f"--vary {key.strip()}: given twice")
        out[key.strip()] = text.strip()
    return out


def _as_values(key: str, values) -> list:
    """Values given as text (CLI syntax) or as a sequence (API)."""
    vals = parse_values(values, key) if isinstance(values, str) else [_plain(v) for v in values]
    if not vals:
        raise SweepError(f"--vary {key}: no values")
    return vals


def _plain(v):
    return v.item() if isinstance(v, np.generic) else v


# ---------------------------------------------------------------------------------------------------- designs

def full_design(vary: dict) -> list:
    """Every combination (full factorial), the last key varying fastest."""
    keys = list(vary)
    return [dict(zip(keys, combo)) for combo in itertools.product(*(vary[k] for k in keys))]


def list_design(vary: dict) -> list:
    """The i-th value of every key together (lists of equal length; a single value is repeated)."""
    n = max(len(v) for v in vary.values())
    bad = {k: len(v) for k, v in vary.items() if len(v) not in (1, n)}
    if bad:
        raise SweepError(f"--design list: every key needs {n} values (or one); got {bad}")
    return [{k: v[i if len(v) > 1 else 0] for k, v in vary.items()} for i in range(n)]


def _bounds(key: str, text) -> tuple:
    if isinstance(text, str) and re.fullmatch(r"[^:,()]+:[^:,()]+", text.strip()):
        lo, hi = (parse_scalar(v) for v in text.split(":"))
        vals = [lo, hi]
    else:
        vals = _as_values(key, text)
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in vals):
        raise SweepError(f"--vary {key}: --design lhs needs numbers (lo:hi), got {text!r}")
    return float(min(vals)), float(max(vals))


def lhs_design(vary: dict, samples: int, seed: int = 0) -> list:
    """A Latin hypercube of ``samples`` points (scipy.stats.qmc, seeded) over each key's [lo, hi]."""
    from scipy.stats import qmc

    if not samples or samples < 1:
        raise SweepError("--design lhs needs --samples N (N >= 1)")
    bounds = {k: _bounds(k, v) for k, v in vary.items()}
    try:
        sampler = qmc.LatinHypercube(d=len(bounds), rng=seed)
    except TypeError:  # scipy < 1.15
        sampler = qmc.LatinHypercube(d=len(bounds), seed=seed)
    u = sampler.random(samples)
    return [{k: lo + float(u[i, j]) * (hi - lo) for j, (k, (lo, hi)) in enumerate(bounds.items())}
            for i in range(samples)]


def read_variants(path) -> list:
    """Variants from a CSV file: a header of keys, one variant per row; an empty cell keeps the scene's value."""
    path = Path(path)
    if not path.is_file():
        raise SweepError(f"--variants {path}: file does not exist")
    with path.open(newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and any(c.strip() for c in r) and not r[0].startswith("#")]
    if len(rows) < 2:
        raise SweepError(f"--variants {path}: expected a header of keys and at least one row")
    keys = [k.strip() for k in rows[0]]
    if len(set(keys)) != len(keys) or not all(keys):
        raise SweepError(f"--variants {path}: header needs distinct, non-empty keys, got {rows[0]}")
    out = []
    for n, row in enumerate(rows[1:], start=2):
        if len(row) != len(keys):
            raise SweepError(f"--variants {path}: row {n} has {len(row)} cells, the header {len(keys)}")
        out.append({k: parse_scalar(c) for k, c in zip(keys, row) if c.strip()})
    return out


def make_design(vary=None, design: str = "full", *, samples=None, seed: int = 0, variants=None) -> list:
    """The variants ({key: value}) of a sweep: ``vary`` {key: values or text} by ``design``, or ``variants``
    (a CSV file or a list of dicts). Repeated variants are kept once."""
    if bool(vary) == (variants is not None):
        raise SweepError("give either --vary KEY=VALUES (one or more) or --variants FILE.csv")
    if design not in DESIGNS:
        raise SweepError(f"--design {design!r}: expected one of {', '.join(DESIGNS)}{suggest(design, DESIGNS)}")
    if variants is not None:
        rows = read_variants(variants) if isinstance(variants, (str, Path)) else [dict(v) for v in variants]
    elif design == "lhs":
        rows = lhs_design(vary, samples, seed)
    else:
        values = {k: _as_values(k, v) for k, v in vary.items()}
        for k, vals in values.items():
            if any(isinstance(v, str) and re.fullmatch(r"[-+.\deE]+:[-+.\deE]+", v) for v in vals):
                raise SweepError(f"--vary {k}: lo:hi ranges are for --design lhs; use linspace(lo,hi,n)")
        rows = full_design(values) if design == "full" else list_design(values)
    unique = {}
    for r in rows:
        unique.setdefault(variant_id(r), r)
    return list(unique.values())


def canonical(inputs: dict) -> str:
    """The inputs as canonical JSON (sorted keys, numbers as floats): what a variant's id is a hash of."""
    def norm(v):
        v = _plain(v)
        return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v
    return json.dumps({k: norm(v) for k, v in sorted(inputs.items())}, separators=(",", ":"), sort_keys=True)


def variant_id(inputs: dict) -> str:
    """A stable 12-hex-digit id of a variant's inputs (the same values give the same id in every run)."""
    return hashlib.sha256(canonical(inputs).encode()).hexdigest()[:12]


# ---------------------------------------------------------------------------------------------------- keys

@cache
def _schema() -> dict:
    """Schema path (``"cavity.inflator"``) -> (spec class, is a list of tables), from the key reference."""
    from cases.scene.docs import SECTIONS  # imports the scene specs (and the solver): only when keys are resolved

    return {prefix.rstrip("."): (cls, title.startswith("[[")) for title, cls, prefix in SECTIONS}


def _tokens(key: str, path) -> list:
    """``"exchange[0].area"`` -> ``["exchange", 0, "area"]``."""
    out = []
    for part in key.split("."):
        m = re.fullmatch(r"([^\[\]]*)((?:\[\d+\])*)", part)
        if m is None or not (m.group(1) or (m.group(2) and out)):
            raise SceneError(path, key, "not a key: expected dotted names and [index], e.g. exchange.vent.area")
        if m.group(1):
            out.append(m.group(1))
        out += [int(i) for i in re.findall(r"\[(\d+)\]", m.group(2))]
    return out


def _pick(items: list, tok, path, key: str, what: str) -> int:
    """The index of a list item named ``tok`` (or at index ``tok``); ``what`` names the items in messages."""
    if isinstance(tok, int):
        if not 0 <= tok < len(items):
            raise SceneError(path, key, f"index {tok} out of range: {len(items)} {what}")
        return tok
    names = [it.get("name") for it in items if isinstance(it, dict)]
    if tok not in names:
        raise SceneError(path, key, f"no {what} named {tok!r}{suggest(tok, [str(n) for n in names])}; "
                                    f"names: {', '.join(map(str, names)) or 'none'}")
    return names.index(tok)


def resolve_key(data: dict, key: str, path) -> tuple:
    """The concrete steps (dict keys, list indices) of dotted ``key`` in the scene data ``data``.

    Checked against the scene's schema (unknown keys fail with suggestions) and its content (named list
    items must exist). A key the file does not set but the schema knows (a default) is allowed.
    """
    toks, steps = _tokens(key, path), []
    node, schema, kind = data, "", "table"  # kind: table | list | free (gas, cp) | value
    for n, tok in enumerate(toks):
        last = n == len(toks) - 1
        spec = _schema().get(schema, (None, False))[0]
        if kind == "list":
            idx = _pick(node if isinstance(node, list) else [], tok, path, key, f"[[{schema}]] table(s)")
            steps.append(idx)
            node, kind = node[idx], "table"
        elif kind == "value":
            raise SceneError(path, key, f"{_show(steps)} is a value, not a table")
        elif isinstance(node, list):  # a free list (cp)
            if not isinstance(tok, int):
                raise SceneError(path, key, f"{_show(steps)} is a list: address an item by [index]")
            steps.append(_pick(node, tok, path, key, f"value(s) in {_show(steps)}"))
            node, kind = node[tok], "value"
        else:
            node, schema, kind = _step_table(node, tok, spec if kind == "table" else None, schema, last,
                                             path, key, steps)
        if last and kind != "value":
            raise SceneError(path, key, f"{_show(steps)} holds {'a list' if kind == 'list' else 'a table'}: "
                                        "address one of its values")
    return tuple(steps)


def _step_table(node, tok, spec, schema: str, last: bool, path, key: str, steps: list):
    """One step into a table: check ``tok`` against the spec (if known), return (child, schema, kind)."""
    if isinstance(tok, int):
        raise SceneError(path, key, f"{_show(steps) or 'the scene'} is a table, not a list")
    present = node if isinstance(node, dict) else {}
    if spec is not None:
        known = [toml_name(f) for f in fields(spec) if f.init and not f.name.startswith("_")]
        if tok not in known:
            raise SceneError(path, key, f"unknown key {tok!r}{suggest(tok, known)}; known keys: "
                                        f"{', '.join(sorted(known))}")
    elif tok not in present and not last:
        raise SceneError(path, key, f"{_show(steps + [tok])} is not in the scene")
    steps.append(tok)
    child = present.get(tok)
    sub = f"{schema}.{tok}" if schema else tok
    if spec is not None and sub in _schema():
        is_list = _schema()[sub][1]
        if is_list and child is None and not last:
            raise SceneError(path, key, f"the scene has no [[{sub}]] tables")
        return child if child is not None else {}, sub, "list" if is_list else "table"
    if isinstance(child, list) and child and all(isinstance(c, dict) for c in child):
        return child, sub, "list"
    if isinstance(child, (dict, list)):
        return child, sub, "free"
    return child, sub, "value"


def _show(steps) -> str:
    return "".join(f"[{s}]" if isinstance(s, int) else (f".{s}" if i else s) for i, s in enumerate(steps))


def apply_variant(data: dict, steps: dict, inputs: dict) -> dict:
    """A deep copy of ``data`` with ``inputs`` {key: value} written at ``steps`` {key: resolved steps}."""
    out = copy.deepcopy(data)
    for k, value in inputs.items():
        node = out
        for s in steps[k][:-1]:
            if isinstance(s, str) and s not in node:
                node[s] = {}
            node = node[s]
        node[steps[k][-1]] = _plain(value)
    return out
