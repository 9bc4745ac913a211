"""What the Abaqus and LS-DYNA readers share: the one-line deck error, *INCLUDE resolution, the deck's text,
the "ignored" line, and the area of polygon faces."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from cases.scene.errors import SceneError

__all__ = ["deck_error", "include_target", "deck_lines", "ignored_line", "faces_area"]


def deck_error(file, line: int, keyword: str, message: str) -> SceneError:
    """The one-line error for a deck: ``deck.inp: line 12: *FLUID CAVITY: message``."""
    return SceneError(file, f"line {line}", f"*{keyword}: {message}" if keyword else message)


def deck_lines(path: Path) -> list:
    """The lines of a deck file (SceneError naming the file if it cannot be read)."""
    try:
        return path.read_text(errors="replace").splitlines()
    except OSError as exc:
        raise SceneError(path, "", f"cannot read the deck: {exc.strerror or exc}") from None


def include_target(path: Path, line: int, name: str, stack: tuple) -> Path:
    """The file an *INCLUDE at ``path`` line ``line`` names, relative to ``path`` (must exist, no cycle)."""
    target = (path.parent / name).resolve()
    if not target.is_file():
        raise deck_error(path, line, "INCLUDE", f"the file {name!r} does not exist")
    if target in stack:
        raise deck_error(path, line, "INCLUDE", f"{name!r} includes itself")
    return target


def ignored_line(name: str, file, line: int, main: Path, why: str = "") -> str:
    """``ignored: *NAME (line N)`` (``other.inp line N`` inside an included file), with an optional reason."""
    where = f"line {line}" if Path(file) == Path(main) else f"{Path(file).name} line {line}"
    return f"ignored: *{name} ({where}){': ' + why if why else ''}"


def faces_area(faces, coordinates) -> float:
    """Σ area of polygon faces (node ids), each split into a fan of triangles [m^2].

    coordinates : mapping node id -> (x, y, z) [m]

    >>> faces_area([(1, 2, 3, 4)], {1: (0, 0, 0), 2: (2, 0, 0), 3: (2, 1, 0), 4: (0, 1, 0)})
    2.0
    """
    total = 0.0
    for f in faces:
        p = np.array([coordinates[n] for n in f], dtype=float)
        for k in range(1, len(f) - 1):
            total += 0.5 * float(np.linalg.norm(np.cross(p[k] - p[0], p[k + 1] - p[0])))
    return total
