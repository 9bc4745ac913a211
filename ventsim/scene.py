"""A scene built from Python (dicts, lists, arrays, trimesh meshes) or read from a TOML file.

A Python scene is validated by the very code that validates a TOML file (:func:`cases.scene.files.scene_from_dict`):
every array becomes a CSV table and every mesh a PLY file (double precision) in a private folder, named after the
key that holds it, and the dict then goes through the loader like a parsed TOML file. An error is therefore the
same one-line :class:`cases.scene.errors.SceneError` naming the key.
"""
from __future__ import annotations

import copy
import dataclasses
import tempfile
from pathlib import Path

import numpy as np

from cases.scene.errors import SceneError
from cavity.tables import Table
from cases.scene.files import load_scene, read_scene_data, scene_from_dict
from cases.scene.ply import write_ply

__all__ = ["Scene", "load"]


def _is_mesh(value) -> bool:
    return hasattr(value, "vertices") and hasattr(value, "faces") and not isinstance(value, dict)


def _is_default(f, value) -> bool:
    """True when a dataclass field holds its default (left out, as a TOML file would)."""
    if f.default is not dataclasses.MISSING:
        default = f.default
    elif f.default_factory is not dataclasses.MISSING:
        default = f.default_factory()
    else:
        return False
    try:
        return type(value) is type(default) and bool(value == default)
    except ValueError:  # arrays
        return False


def _is_rows(value) -> bool:
    """A table given as a list of [x, y] rows of numbers (``[[0.0, 0.1], [0.05, 0.2]]``)."""
    return (isinstance(value, (list, tuple)) and len(value) > 0
            and all(isinstance(r, (list, tuple)) and len(r) == 2 and all(
                isinstance(x, (int, float, np.number)) and not isinstance(x, bool) for x in r) for r in value))


def _file_name(where: str, suffix: str) -> str:
    return "".join(c if c.isalnum() or c in "._-" else "_" for c in where).strip("_") + suffix


def _write_table(value, path: Path, where: str) -> None:
    rows = np.asarray(value, dtype=np.float64)
    if rows.ndim != 2 or rows.shape[1] != 2:
        raise SceneError("<python scene>", where, f"expected a table of shape (n, 2) (x, y), got shape {rows.shape}")
    np.savetxt(path, rows, delimiter=",", fmt="%.17g")


def _externalised(value, folder: Path, where: str):
    """``value`` with every array written as a CSV and every mesh as a PLY file in ``folder`` (absolute names)."""
    if _is_mesh(value):
        path = folder / _file_name(where, ".ply")
        write_ply(path, value.vertices, value.faces)
        return str(path)
    if hasattr(value, "to_numpy") and hasattr(value, "columns"):  # a pandas DataFrame of two columns
        value = value.to_numpy()
    if isinstance(value, Table):  # a validated table (from another scene's spec)
        value = np.column_stack([value.x, value.y])
    if _is_rows(value):  # a table as a list of [x, y] rows
        value = np.asarray(value, dtype=np.float64)
    if isinstance(value, np.ndarray) and value.ndim == 2:
        path = folder / _file_name(where, ".csv")
        _write_table(value, path, where)
        return str(path)
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        value = {f.metadata.get("toml") or f.name: getattr(value, f.name) for f in dataclasses.fields(value)
                 if not f.name.startswith("_") and not _is_default(f, getattr(value, f.name))}
    if isinstance(value, dict):
        return {k: _externalised(v, folder, f"{where}.{k}" if where else str(k)) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_externalised(v, folder, f"{where}[{i}]") for i, v in enumerate(value)]
    return value


class Scene:
    """A validated scene, ready for :func:`ventsim.run`.

    Parameters
    ----------
    data : dict, optional
        The scene as the dict a TOML file parses to (``{"time": {"end": 0.1}, "cavity": [...], ...}``). Any
        value may be a NumPy array of shape (n, 2) (a table: first column x, second y, in the key's units), a
        list of [x, y] rows, a pandas DataFrame of two columns, or a ``trimesh.Trimesh`` (a mesh, coordinates in metres) where the
        TOML file would name a CSV or mesh file. Strings name files relative to ``base``. Objects are taken by
        their fields: the spec dataclasses of a loaded scene (``ventsim.load(path).spec.cavity[0]``, with its
        tables) or any dataclass whose fields are scene keys.
    base : path-like, optional
        Folder that relative file names are read from (default: the current folder).
    name : str
        What error messages call the scene (default ``"<python scene>"``).
    **tables
        Top-level tables, merged into ``data`` (``Scene(time={"end": 0.1}, cavity=[...])``).

    Raises
    ------
    cases.scene.errors.SceneError
        One line naming the key and what was expected, exactly as for a TOML file.

    Examples
    --------
    >>> s = Scene(time={"end": 0.01}, cavity=[{"name": "tank", "pressure": 2e5, "temperature": 300.0,
    ...                                        "volume": 1e-3}])
    >>> s.title, s.spec.cavity[0].volume
    ('', 0.001)
    >>> Scene(time={"end": 0.01}, cavity=[{"name": "tank", "presure": 2e5}])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cases.scene.errors.SceneError: <python scene>: cavity[0].presure: unknown key (did you mean 'pressure'?); ...
    """

    def __init__(self, data: dict | None = None, /, *, base=None, name: str = "<python scene>", **tables):
        data = {**copy.copy(data or {}), **tables}
        self._folder = tempfile.TemporaryDirectory(prefix="ventsim-scene-")  # lives as long as the scene
        self.data = _externalised(data, Path(self._folder.name), "")
        try:
            self.spec = scene_from_dict(self.data, Path(base or ".").resolve() / name)
        except SceneError as exc:  # name the scene as the user did, not by its anchor path
            error = SceneError(name, "", str(exc)[len(exc.file) + 2:])
            error.where = exc.where
            raise error from None

    @classmethod
    def from_toml(cls, path) -> "Scene":
        """The scene of a TOML file (same as :func:`load`)."""
        scene = cls.__new__(cls)
        scene._folder, scene.data, scene.spec = None, read_scene_data(path), load_scene(path)
        return scene

    @property
    def title(self) -> str:
        return self.spec.title

    @property
    def path(self) -> Path:
        """The scene file (for a Python scene: ``base / name``, which need not exist)."""
        return self.spec.path

    @property
    def sha256(self) -> str:
        """The scene's hash (:func:`cases.run.provenance.scene_hash`), as written to summary.json."""
        from cases.run.provenance import scene_hash

        return scene_hash(self.spec)

    def __repr__(self) -> str:
        s = self.spec
        return (f"Scene({s.title or str(s.path)!r}: {len(s.cavity)} cavities, {len(s.exchange)} exchanges, "
                f"{len(s.body)} bodies, end {s.time.end:g} s)")


def load(path) -> Scene:
    """Read and validate a TOML scene file (every table and mesh it names is read and checked too).

    >>> import ventsim
    >>> ventsim.load("cases/verification/fill_constant.toml").spec.cavity[0].name
    'tank'
    """
    return Scene.from_toml(path)
