"""Where a run came from: the installed ventsim version and a hash of the validated scene (summary.json)."""
from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
from pathlib import Path

from cavity.tables import Table

__all__ = ["version", "scene_hash", "provenance"]

FILE_KEYS = ("mesh", "volume_table", "mesh_scale_table", "temperature_table", "leakage_table", "leakage_surface",
             "displacement_table", "rotation_table", "vertex_trajectory")
"""Scene keys whose value names a file: the hash covers the file's bytes, not its name."""


@functools.cache
def version() -> str:
    """The installed ventsim version (package metadata, from ``pyproject.toml``), or ``"0+unknown"``; read once a
    process (the lookup costs ~1 ms, as much as a small scene's whole run)."""
    from importlib.metadata import PackageNotFoundError, version as dist_version

    try:
        return dist_version("ventsim")
    except PackageNotFoundError:
        return "0+unknown"


def _file_digest(base: Path, name: str) -> str:
    path = base / name
    return "sha256:" + hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else f"missing:{name}"


def _canonical(value, base: Path, key: str = ""):
    """A JSON-able form of a validated scene value: tables by their rows, files by the hash of their bytes."""
    if isinstance(value, Table):
        return {"x": list(value.x), "y": list(value.y), "extrapolation": value.extrapolation}
    if dataclasses.is_dataclass(value):
        return {f.name: _canonical(getattr(value, f.name), base, f.name) for f in dataclasses.fields(value)
                if not f.name.startswith("_")}
    if isinstance(value, (list, tuple)):
        return [_canonical(v, base) for v in value]
    if isinstance(value, dict):
        return {str(k): _canonical(v, base) for k, v in sorted(value.items())}
    if isinstance(value, str) and key in FILE_KEYS and value:
        return _file_digest(base, value)
    if isinstance(value, float):
        return repr(value)
    return value


def scene_hash(scene) -> str:
    """SHA-256 of a validated :class:`cases.scene.files.Scene`: every value (floats exactly), every table's rows and
    the bytes of every file it names; not the file names or the scene file's path, so that the same scene
    built from TOML or from Python (``ventsim.Scene``) has the same hash."""
    text = json.dumps(_canonical(scene, scene.base), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def provenance(scene) -> dict:
    """``{"version": ..., "scene sha256": ...}`` for summary.json."""
    return {"version": version(), "scene sha256": scene_hash(scene)}
