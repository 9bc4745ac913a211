"""Write what a deck becomes: the scene TOML and the meshes (OBJ) and tables (CSV) it names.

Numbers are written with ``repr`` so that reading the files back gives the same floats bit for bit: the scene
loaded from the written TOML is the scene the deck gave.
"""
from __future__ import annotations

import json
from pathlib import Path

__all__ = ["obj_text", "csv_text", "toml_text", "write_imported"]


def obj_text(faces, coordinates, header: str = "") -> str:
    """A Wavefront OBJ of ``faces`` (tuples of node ids) on the nodes they use, in order of first use.

    coordinates : mapping node id -> (x, y, z) [m]
    """
    order, index = [], {}
    for face in faces:
        for n in face:
            if n not in index:
                index[n] = len(order) + 1
                order.append(n)
    lines = [f"# {header}"] if header else []
    lines += ["v " + " ".join(repr(float(c)) for c in coordinates[n]) for n in order]
    lines += ["f " + " ".join(str(index[n]) for n in face) for face in faces]
    return "\n".join(lines) + "\n"


def csv_text(x, y, header: str) -> str:
    """Two columns with a header row, every value written exactly."""
    return header + "\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(x, y))


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def _key(k: str) -> str:
    return k if k.replace("_", "").replace("-", "").isalnum() else json.dumps(k)


def _is_tables(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def _table(lines, name, table):
    for k, v in table.items():
        if not _is_tables(v):
            lines.append(f"{_key(k)} = {_value(v)}")
    for k, v in table.items():
        if _is_tables(v):
            for item in v:
                lines.append("")
                lines.append(f"[[{name}.{k}]]")
                _table(lines, f"{name}.{k}", item)


def toml_text(data: dict, comment: str = "") -> str:
    """The TOML of a scene dict: top-level dicts are tables, lists of dicts arrays of tables (nested ones too),
    other dicts inline tables (gas compositions)."""
    lines = [f"# {line}" for line in comment.splitlines()]
    for k, v in data.items():
        if not isinstance(v, dict) and not _is_tables(v):
            lines.append(f"{_key(k)} = {_value(v)}")
    for k, v in data.items():
        if isinstance(v, dict):
            lines += ["", f"[{k}]"]
            _table(lines, k, v)
        elif _is_tables(v):
            for item in v:
                lines += ["", f"[[{k}]]"]
                _table(lines, k, item)
    return "\n".join(lines) + "\n"


def write_imported(imported, toml_path) -> Path:
    """Write ``imported.files`` beside ``toml_path`` and the scene TOML itself; returns the TOML path."""
    toml_path = Path(toml_path)
    for name, text in imported.files.items():
        target = toml_path.parent / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text)
    toml_path.parent.mkdir(parents=True, exist_ok=True)
    toml_path.write_text(toml_text(imported.data, imported.comment()))
    return toml_path
