"""A scene's unit system (``[units] system``): every dimensional value, table and mesh of a scene written in
mm-t-s or mm-kg-ms is converted to SI once, at load, by the factors of :mod:`cases.scene.unit_systems` (the deck
importer's). Temperatures are absolute kelvin in every system and are not converted.

Scalars and vectors are converted by the unit each key declares (``key(doc, unit)``); tables by their abscissa
(time, or pressure for a Cd table of pressure) and ordinate; the files a scene names (CSV tables, single meshes,
mesh series and vertex trajectories (``.pvd``, ``.xdmf``, ``.npz``: times and coordinates), node CSVs (coordinates
and areas)) are written converted into a private folder and the scene points at the copies
(:mod:`cases.scene.units_files`). A d3plot has its own ``[fe_run] units``.
"""
from __future__ import annotations

import atexit
import shutil
import tempfile
from dataclasses import dataclass, fields, is_dataclass, replace
from pathlib import Path

import numpy as np

from cavity.tables import Table

from cases.scene.errors import SceneError
from cases.scene.schema import key, toml_name
from cases.scene.unit_systems import SYSTEMS, exponents
from cases.scene.units_files import scaled_nodes, scaled_series

__all__ = ["UnitsSpec", "to_si", "UNIT_SYSTEMS"]

UNIT_SYSTEMS = tuple(SYSTEMS)


@dataclass(frozen=True, kw_only=True)
class UnitsSpec:
    system: str = key("unit system of every dimensional value, table and mesh of the scene: 'SI' (m, kg, s; Pa, "
                      "N, J), 'mm-t-s' (mm, tonne, s; MPa, N, mJ) or 'mm-kg-ms' (mm, kg, ms; GPa, kN, J); "
                      "temperatures are absolute [K] in every system; converted to SI at load", default="SI",
                      choices=UNIT_SYSTEMS)
    check: bool = key("plausibility checks of the dimensional values (an absolute pressure below 1 kPa, a "
                      "temperature below 150 K, areas, volumes and meshes orders of magnitude off for the scene): "
                      "false turns them all off", default=True)
    unchecked: tuple = key("keys exempt from the plausibility checks, as their error names them "
                           "(['cavity[0].pressure'])", default=())
    _given: str = ""  # set by the loader: the system the file was written in (the values held are SI)

    @property
    def given(self) -> str:
        """The unit system the scene was written in ('' when it was SI); its values are held in SI."""
        return self._given


#: Keys whose unit is not a plain product of SI symbols, or is left alone: (spec class name, key) -> exponents.
_SPECIAL = {("SpeciesSpec", "cp"): (2, 1, -2)}  # J/(mol K), J/(mol K^2), ...: each coefficient like energy
#: Spec classes whose numbers are not in the scene's system (work budgets; the FE run's own units).
_SKIP = ("LimitsSpec", "FeRunSpec", "UnitsSpec")
#: File keys converted by a copy: (spec class name, key) -> ((x exponents), (y exponents)) of a 2-column CSV, or
#: "mesh" for a single mesh.
_FILES = {("CavitySpec", "mesh"): "mesh", ("BodySpec", "mesh"): "mesh", ("ExchangeSpec", "leakage_surface"): "mesh",
          ("ContactSpec", "seat_mesh"): "mesh",
          ("CavitySpec", "volume_table"): ((0, 0, 1), (3, 0, 0)),
          ("CavitySpec", "mesh_scale_table"): ((0, 0, 1), (0, 0, 0)),
          ("CavitySpec", "temperature_table"): ((0, 0, 1), (0, 0, 0)),
          ("BodySpec", "displacement_table"): ((0, 0, 1), (1, 0, 0)),
          ("BodySpec", "rotation_table"): ((0, 0, 1), (0, 0, 0))}
_SERIES_KEYS = {("CavitySpec", "mesh_series"), ("BodySpec", "mesh_series"), ("BodySpec", "vertex_trajectory")}
_NODES_KEYS = {("ExchangeSpec", "leakage_nodes")}
_SERIES = (".pvd", ".xdmf", ".xmf", ".npz")
_FLUX = {"mass_flux": (-2, 1, -1), "volume_flux": (1, 0, -1), "mass_rate_leakage": (-2, 1, -1),
         "volume_rate_leakage": (1, 0, -1)}
_FOLDER: list = []


def _folder() -> Path:
    """The private folder of converted files (one per process, removed at exit)."""
    if not _FOLDER:
        _FOLDER.append(Path(tempfile.mkdtemp(prefix="ventsim-units-")))
        atexit.register(shutil.rmtree, _FOLDER[0], True)
    return _FOLDER[0]


def to_si(scene, path):
    """``scene`` (a Scene whose values are in ``scene.units.system``) with every value in SI; the same scene when it
    is SI already."""
    system = scene.units.system
    if system == "SI" or scene.units.given:
        return scene
    conv = _Converter(SYSTEMS[system], path, scene.base)
    out = conv.spec(scene, "")
    return replace(out, units=replace(scene.units, system="SI", _given=system))


class _Converter:
    def __init__(self, system, path, base: Path):
        self.system, self.path, self.base = system, path, base

    def spec(self, obj, where: str):
        cls = type(obj).__name__
        if cls in _SKIP:
            return obj
        changes = {}
        for f in fields(obj):
            if not f.init or f.name.startswith("_"):
                continue
            here = f"{where}.{toml_name(f)}" if where else toml_name(f)
            value = getattr(obj, f.name)
            new = self.value(obj, cls, f, value, here)
            if new is not value:
                changes[f.name] = new
        return replace(obj, **changes) if changes else obj

    def value(self, obj, cls: str, f, value, where: str):
        if is_dataclass(value) and not isinstance(value, Table):
            return self.spec(value, where)
        if isinstance(value, tuple) and value and all(is_dataclass(v) and not isinstance(v, Table) for v in value):
            return tuple(self.spec(v, f"{where}[{i}]") for i, v in enumerate(value))
        if (cls, f.name) in _FILES or (cls, f.name) in _SERIES_KEYS | _NODES_KEYS or f.name == "leakage_table":
            return self.file(obj, cls, f.name, value, where)
        exps = _SPECIAL.get((cls, f.name)) or exponents(f.metadata.get("unit", "-"))
        if f.name == "flux":
            exps = _FLUX.get(getattr(obj, "law", ""), (0, 0, 0))
        if exps is None:
            return value
        factor = self.system.scale(exps)
        if isinstance(value, Table):
            return self.table(obj, f.name, value, factor)
        if isinstance(value, bool) or factor == 1.0:
            return value
        if isinstance(value, float):
            return value * factor
        if isinstance(value, tuple) and value and all(isinstance(v, float) for v in value):
            return tuple(v * factor for v in value)
        return value

    def table(self, obj, name: str, table: Table, factor: float) -> Table:
        of_pressure = name == "discharge_coefficient" and getattr(obj, "discharge_coefficient_of", "") == "pressure"
        fx = self.system.scale((-1, 1, -2) if of_pressure else (0, 0, 1))
        return replace(table, x=tuple(x * fx for x in table.x), y=tuple(y * factor for y in table.y))

    def file(self, obj, cls: str, name: str, value, where: str):
        if not value:
            return value
        from cases.model.mesh_series_d3plot import is_d3plot

        source = self.base / value
        if is_d3plot(value):
            return value  # converted by [fe_run] units
        kind = _FILES.get((cls, name))
        if name == "leakage_table":
            kind = ((-1, 1, -2), _FLUX.get(getattr(obj, "law", ""), (0, 0, 0)))
        target = _folder() / f"{abs(hash((str(self.path), where, str(source)))):x}_{Path(value).name}"
        if str(value).lower().endswith(_SERIES):
            return str(scaled_series(source, target, self.system, self.path, where))
        if (cls, name) in _SERIES_KEYS:
            return value  # not a series format: the reader names the formats it takes
        if (cls, name) in _NODES_KEYS:
            return str(scaled_nodes(source, target, self.system, self.path, where))
        if kind == "mesh":
            _scaled_mesh(source, target.with_suffix(".ply"), self.system.length, self.path, where)
            return str(target.with_suffix(".ply"))
        from cases.scene.tables_io import read_table

        t = read_table(source, self.path, where, name)
        fx, fy = self.system.scale(kind[0]), self.system.scale(kind[1])
        np.savetxt(target, np.column_stack([np.asarray(t.x) * fx, np.asarray(t.y) * fy]), delimiter=",",
                   fmt="%.17g")
        return str(target)


def _scaled_mesh(source: Path, target: Path, factor: float, path, where: str) -> None:
    """The mesh file ``source`` with its coordinates times ``factor``, written as a PLY file ``target``."""
    import trimesh

    from cases.scene.ply import write_ply

    if not source.is_file():
        raise SceneError(path, where, f"file {str(source)!r} does not exist")
    try:
        mesh = trimesh.load(source, force="mesh", process=False)
    except Exception as exc:  # noqa: BLE001 - trimesh raises many types for unreadable files
        raise SceneError(path, where, f"cannot read mesh {str(source)!r}: {exc}") from None
    write_ply(target, np.asarray(mesh.vertices, dtype=float) * factor, np.asarray(mesh.faces))
