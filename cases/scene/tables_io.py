"""Read the CSV tables a scene names (two numeric columns, an optional header row) into validated Tables."""
from __future__ import annotations

import csv
import math
import re
from pathlib import Path

from cavity.tables import Table, TableError

from cases.scene.errors import SceneError

__all__ = ["read_table", "read_text", "table_or_constant"]


#: A CSV number: Python's float() also takes '0_5', ' nan ', 'infinity', which a table must not.
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|[+-]?(nan|inf|infinity)", re.IGNORECASE)


def read_text(path: Path, file, where: str, what: str = "table file") -> str:
    """The text of a file a scene names, which must exist, be a file and be UTF-8; else a SceneError.

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "t.csv"
    >>> _ = p.write_bytes("t,y\\n0,1\\n".encode("utf-16"))
    >>> read_text(p, "s.toml", "x")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cases.scene.errors.SceneError: s.toml: x: table file '...t.csv' is not UTF-8 text (it looks like UTF-16): save it as UTF-8
    """
    path = Path(path)
    if path.is_dir():
        raise SceneError(file, where, f"{what} {str(path)!r} is a directory, not a file")
    if not path.is_file():
        raise SceneError(file, where, f"{what} {str(path)!r} does not exist")
    data = path.read_bytes()
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise SceneError(file, where, f"{what} {str(path)!r} is not UTF-8 text ({_guess_encoding(data, exc)}): "
                                      "save it as UTF-8") from None


def _guess_encoding(data: bytes, exc: UnicodeDecodeError) -> str:
    if data[:2] in (b"\xff\xfe", b"\xfe\xff") or (len(data) > 3 and data[1::2].count(0) > len(data) // 4):
        return "it looks like UTF-16"
    if b"\x00" in data:
        return "it looks like a binary file"
    return f"byte {data[exc.start]:#04x} at offset {exc.start}; Latin-1 or Windows-1252?"


def _numbers(cells: list):
    """The cells as floats, or None if one is not a plain number."""
    if not all(_NUMBER.fullmatch(c) for c in cells):
        return None
    return [float(c) for c in cells]


def read_table(path: Path, file, where: str, name: str, columns: int = 2) -> Table:
    """The piecewise-linear table in CSV file ``path`` (first column x, second y).

    Lines starting with ``#`` are comments; the first other row, if it is not numeric, is a header. Raises
    :class:`SceneError` naming the scene file, the key and the CSV row on a missing, non-UTF-8 or empty file, a
    cell that is not a plain number (``0_5``, ``1,5``), a NaN, or x not strictly increasing.
    """
    rows = []
    seen_row = False
    for lineno, row in enumerate(csv.reader(read_text(path, file, where).splitlines()), start=1):
        cells = [c.strip() for c in row if c.strip()]
        if not cells or cells[0].startswith("#"):
            continue
        values = _numbers(cells)
        if values is None:
            if not seen_row:
                seen_row = True
                continue  # header
            raise SceneError(file, where, f"{path.name} line {lineno}: expected {columns} numbers, got {row!r}")
        seen_row = True
        if len(values) != columns:
            raise SceneError(file, where, f"{path.name} line {lineno}: expected {columns} columns, "
                                          f"got {len(values)}")
        if not all(math.isfinite(v) for v in values):
            raise SceneError(file, where, f"{path.name} line {lineno}: NaN or infinite value {row!r}")
        rows.append(values)
    if not rows:
        raise SceneError(file, where, f"{path.name}: no numeric rows")
    try:
        return Table(tuple(r[0] for r in rows), tuple(r[1] for r in rows), name=f"{path.name} ({name})")
    except TableError as exc:
        raise SceneError(file, where, str(exc)) from None


def table_or_constant(value, base: Path, file, where: str, name: str) -> Table:
    """A Table from a CSV file name, a list of [x, y] rows, or a constant table from a number."""
    if isinstance(value, bool):
        raise SceneError(file, where, f"expected a number or a CSV file name, got {value!r}")
    if isinstance(value, (int, float)):
        if not math.isfinite(value):
            raise SceneError(file, where, f"expected a finite number, got {value!r}")
        return Table((0.0,), (float(value),), name=name)
    if isinstance(value, str) and value:
        return read_table(base / value, file, where, name)
    if isinstance(value, list) and value and all(isinstance(r, list) for r in value):
        return _rows_table(value, file, where, name)
    raise SceneError(file, where, f"expected a number, a CSV file name or a list of [x, y] rows, got {value!r}")


def _rows_table(rows: list, file, where: str, name: str) -> Table:
    """A table given in the scene as a list of [x, y] rows (``[[0.0, 0.1], [0.05, 0.2]]``)."""
    for k, r in enumerate(rows, start=1):
        if len(r) != 2 or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                                  for v in r):
            raise SceneError(file, where, f"row {k}: expected [x, y], two finite numbers, got {r!r}")
    try:
        return Table(tuple(float(r[0]) for r in rows), tuple(float(r[1]) for r in rows), name=name)
    except TableError as exc:
        raise SceneError(file, where, str(exc)) from None
