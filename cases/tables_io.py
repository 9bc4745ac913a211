"""Read the CSV tables a scene names (two numeric columns, an optional header row) into validated Tables."""
from __future__ import annotations

import csv
import math
from pathlib import Path

from cavity.tables import Table, TableError

from .errors import SceneError

__all__ = ["read_table", "table_or_constant"]


def read_table(path: Path, file, where: str, name: str, columns: int = 2) -> Table:
    """The piecewise-linear table in CSV file ``path`` (first column x, second y).

    A first row that is not numeric is taken as a header. Raises :class:`SceneError` naming the scene file,
    the key and the CSV row on a missing file, a non-numeric or NaN cell, or x not strictly increasing.
    """
    if not path.is_file():
        raise SceneError(file, where, f"table file {str(path)!r} does not exist")
    rows = []
    with path.open(newline="") as fh:
        for lineno, row in enumerate(csv.reader(fh), start=1):
            cells = [c.strip() for c in row if c.strip()]
            if not cells or cells[0].startswith("#"):
                continue
            try:
                values = [float(c) for c in cells]
            except ValueError:
                if not rows and lineno == 1:
                    continue  # header
                raise SceneError(file, where, f"{path.name} line {lineno}: expected {columns} numbers, "
                                              f"got {row!r}") from None
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
    """A Table from a CSV file name, or a constant table from a number."""
    if isinstance(value, bool):
        raise SceneError(file, where, f"expected a number or a CSV file name, got {value!r}")
    if isinstance(value, (int, float)):
        if not math.isfinite(value):
            raise SceneError(file, where, f"expected a finite number, got {value!r}")
        return Table((0.0,), (float(value),), name=name)
    if isinstance(value, str):
        return read_table(base / value, file, where, name)
    raise SceneError(file, where, f"expected a number or a CSV file name, got {value!r}")
