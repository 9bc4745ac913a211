"""A small TOML writer for tests that edit scene data (the standard library reads TOML but does not write it)."""
from __future__ import annotations

import json
import math

__all__ = ["dumps"]


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{json.dumps(str(k))} = {_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v).__name__} as TOML")


def _tables_of(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def _section(lines: list, header: str, table: dict, array: bool) -> None:
    lines.append(f"[[{header}]]" if array else f"[{header}]")
    nested = {k: v for k, v in table.items() if _tables_of(v)}
    for k, v in table.items():
        if k not in nested:
            lines.append(f"{json.dumps(str(k))} = {_value(v)}")
    for k, items in nested.items():
        for item in items:
            _section(lines, f"{header}.{json.dumps(str(k))}", item, True)


def dumps(data: dict) -> str:
    """TOML text of ``data`` (dicts, lists of dicts as arrays of tables, scalars, lists, inline dicts).

    >>> import tomllib
    >>> d = {"title": "x", "time": {"end": 0.1}, "cavity": [{"name": "a", "gas": {"N2": 1.0},
    ...      "inflator": [{"name": "i"}]}]}
    >>> tomllib.loads(dumps(d)) == d
    True
    """
    lines = []
    for k, v in data.items():
        if not isinstance(v, dict) and not _tables_of(v):
            lines.append(f"{json.dumps(str(k))} = {_value(v)}")
    for k, v in data.items():
        if isinstance(v, dict):
            _section(lines, json.dumps(str(k)), v, False)
        elif _tables_of(v):
            for item in v:
                _section(lines, json.dumps(str(k)), item, True)
    return "\n".join(lines) + "\n"
