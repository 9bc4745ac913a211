"""Parse TOML tables into frozen dataclasses, field by field, with units and 'did you mean' suggestions.

A spec class declares each key as a dataclass field whose metadata holds its unit and its documentation
(``key(...)``). :func:`parse` checks a TOML table against it: unknown keys are rejected with the closest known
names, missing required keys are named, and each value is checked for type (a bool is a bool, a text is a
text, a number is a finite number and not a bool), finiteness and sign. :func:`check_fields` runs the same
checks on a spec built directly in Python (no TOML), so that both ways in meet one validation.
"""
from __future__ import annotations

import difflib
import math
from dataclasses import MISSING, field, fields

from cases.scene.errors import SceneError

__all__ = ["key", "parse", "describe_spec", "suggest", "check_fields", "checked_number", "unknown_name"]


def key(doc: str, unit: str = "-", *, default=MISSING, check: str | None = None, choices=None, toml: str = "",
        bounds: tuple | None = None):
    """A scene key: its documentation, unit (``"Pa"``, ``"m^3"``, ``"-"``), default, and check.

    ``check`` is one of ``"finite"``, ``"positive"``, ``"nonnegative"``, ``"fraction"``; ``choices`` a tuple of allowed strings;
    ``toml`` the key's name in the file when it differs from the field name (``from`` is a Python keyword);
    ``bounds`` (lo, hi) an inclusive range for an integer key.
    """
    meta = {"doc": doc, "unit": unit, "check": check, "choices": choices, "toml": toml, "bounds": bounds}
    if isinstance(default, (list, dict)):
        return field(default_factory=lambda d=default: type(d)(d), metadata=meta)
    return field(default=default, metadata=meta)


def toml_name(f) -> str:
    return f.metadata.get("toml") or f.name


def suggest(name: str, known) -> str:
    """' (did you mean 'x'?)' for the closest known names, or ''.

    >>> suggest("presure", ["pressure", "temperature"])
    " (did you mean 'pressure'?)"
    """
    if not isinstance(name, str):
        return ""
    close = difflib.get_close_matches(name, [str(k) for k in known], n=2, cutoff=0.6)
    return f" (did you mean {' or '.join(repr(c) for c in close)}?)" if close else ""


def unknown_name(path, where: str, kind: str, value: str, known) -> SceneError:
    """The error for a reference to a ``kind`` (cavity, body, exchange) that the scene does not define, with the
    closest defined name as a suggestion."""
    return SceneError(path, where, f"no {kind} named {value!r}{suggest(value, known)}")


def parse(cls, table, file, where: str, *, nested: dict | None = None):
    """Build ``cls`` from the TOML table ``table``; raise :class:`SceneError` naming file and key on any problem.

    ``nested`` maps a field name to a function ``(value, where) -> object`` for sub-tables and lists of tables.
    """
    nested = nested or {}
    if not isinstance(table, dict):
        raise SceneError(file, where, f"expected a table of keys, got {type(table).__name__}")
    by_toml = {toml_name(f): f for f in fields(cls) if f.init and not f.name.startswith("_")}
    for name in table:
        if name not in by_toml:
            raise SceneError(file, f"{where}.{name}" if where else name,
                             f"unknown key{suggest(name, by_toml)}; known keys: {', '.join(sorted(by_toml))}")
    values = {}
    for tname, f in by_toml.items():
        here = f"{where}.{tname}" if where else tname
        if tname not in table:
            if f.default is MISSING and f.default_factory is MISSING:
                raise SceneError(file, here, f"missing required key ({f.metadata.get('doc', '')} "
                                             f"[{f.metadata.get('unit', '-')}])")
            continue
        value = table[tname]
        values[f.name] = nested[f.name](value, here) if f.name in nested else _checked(value, f, file, here)
    return cls(**values)


def _kind(f) -> str:
    """The declared type of a spec field: ``"str"``, ``"bool"``, ``"int"``, ``"float"`` or another annotation."""
    return f.type if isinstance(f.type, str) else getattr(f.type, "__name__", str(f.type))


def _checked(value, f, file, where):
    """``value`` for field ``f`` checked for type, choices, finiteness and range; raises SceneError."""
    meta, unit, kind = f.metadata, f.metadata.get("unit", "-"), _kind(f)
    if meta.get("choices") is not None:
        if not isinstance(value, str) or value not in meta["choices"]:
            raise SceneError(file, where, f"expected one of {', '.join(map(repr, meta['choices']))}, got {value!r}"
                             f"{suggest(value, meta['choices'])}")
        return value
    if kind == "str" and not isinstance(value, str):
        raise SceneError(file, where, f"expected a text string, got {value!r}")
    if kind == "bool" and not isinstance(value, bool):
        raise SceneError(file, where, f"expected true or false (a TOML boolean, no quotes), got {value!r}")
    if kind == "int":
        return _checked_int(value, meta.get("bounds"), file, where)
    check = meta.get("check")
    if check is None or (value is None and f.default is None):
        return value
    return checked_number(value, check, unit, file, where)


def _checked_int(value, bounds, file, where) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise SceneError(file, where, f"expected a whole number, got {value!r}")
    if bounds is not None and not bounds[0] <= value <= bounds[1]:
        raise SceneError(file, where, f"expected a whole number from {bounds[0]} to {bounds[1]}, got {value!r}")
    return value


def checked_number(value, check: str, unit: str, file, where) -> float:
    """``value`` as a float if it is a finite number meeting ``check`` (see :func:`key`); raises SceneError.

    >>> checked_number(2, "positive", "Pa", "s.toml", "x")
    2.0
    >>> checked_number(True, "finite", "-", "s.toml", "x")
    Traceback (most recent call last):
    ...
    cases.scene.errors.SceneError: s.toml: x: expected a number [-], got True
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError(file, where, f"expected a number [{unit}], got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise SceneError(file, where, f"expected a finite number [{unit}], got {value!r}")
    if check == "positive" and not value > 0:
        raise SceneError(file, where, f"expected a number > 0 [{unit}], got {value!r}")
    if check == "nonnegative" and not value >= 0:
        raise SceneError(file, where, f"expected a number >= 0 [{unit}], got {value!r}")
    if check == "fraction" and not 0 <= value <= 1:
        raise SceneError(file, where, f"expected a number in [0, 1] [{unit}], got {value!r}")
    return value


def check_fields(obj, file, where: str) -> None:
    """Run the per-key checks of :func:`parse` on a spec ``obj`` built in Python (its scalar fields: text,
    booleans, choices, numbers); sub-tables and lists are the caller's (see ``cases.scene_api``)."""
    for f in fields(obj):
        if not f.init or f.name.startswith("_"):
            continue
        kind, value = _kind(f), getattr(obj, f.name)
        here = f"{where}.{toml_name(f)}" if where else toml_name(f)
        if kind in ("str", "bool", "int", "float") or f.metadata.get("choices") is not None:
            _checked(value, f, file, here)


def describe_spec(cls, prefix: str = "") -> str:
    """A Markdown table of the keys of ``cls`` (key, unit, default, meaning), for docs/scenes.md."""
    rows = ["| key | unit | default | meaning |", "|---|---|---|---|"]
    for f in fields(cls):
        if not f.init or f.name.startswith("_"):
            continue
        default = "required" if f.default is MISSING and f.default_factory is MISSING else (
            repr(f.default) if f.default is not MISSING else repr(f.default_factory()))
        rows.append(f"| `{prefix}{toml_name(f)}` | {f.metadata.get('unit', '-')} | {default} | "
                    f"{f.metadata.get('doc', '')} |")
    return "\n".join(rows)
