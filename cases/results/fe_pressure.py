"""The control-volume pressure history of a finite-element run, to draw over ventsim's.

LS-DYNA writes it in the ``abstat`` database: a binout file (read with lasso-python's ``Binout``: ``abstat/time``
and ``abstat/pressure``, one column per airbag) or the ASCII ``abstat`` file, whose state blocks start with a
header line naming ``time   airbag/cv #  volume   pressure ...`` and then hold one row per airbag: time, airbag
number, volume, pressure, internal energy, ... . The values are converted to SI with the run's unit system
(``[fe_run] units``).
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cases.scene.errors import SceneError

__all__ = ["FePressure", "read_abstat", "scene_fe_pressures"]


@dataclass(frozen=True)
class FePressure:
    """One airbag's pressure from the FE run: ``times`` (k,) [s], ``pressures`` (k,) [Pa], its ``number``."""

    number: int
    times: np.ndarray
    pressures: np.ndarray

    def peak(self) -> tuple:
        """(peak pressure [Pa], its time [s]) over the rows."""
        k = int(np.argmax(self.pressures))
        return float(self.pressures[k]), float(self.times[k])


def _ascii_abstat(path: Path) -> dict:
    """{airbag number: (times, pressures)} of an ASCII abstat file, in the file's units."""
    rows, in_block = [], False
    for line in path.read_text(errors="replace").splitlines():
        if "airbag/cv" in line and "pressure" in line:
            in_block = True
            continue
        tokens = line.split()
        if not in_block or len(tokens) < 4:
            continue
        try:
            rows.append((float(tokens[0]), int(tokens[1]), float(tokens[3])))
        except ValueError:
            in_block = False
    out = {}
    for t, n, p in rows:
        out.setdefault(n, ([], []))
        out[n][0].append(t)
        out[n][1].append(p)
    return {n: (np.array(ts), np.array(ps)) for n, (ts, ps) in out.items()}


def _binout_abstat(path: Path) -> dict:
    from lasso.dyna import Binout

    binout = Binout(str(path))
    if "abstat" not in binout.read():
        raise ValueError("no abstat database in this binout")
    t = np.asarray(binout.read("abstat", "time"), dtype=float)
    p = np.asarray(binout.read("abstat", "pressure"), dtype=float).reshape(len(t), -1)
    try:
        ids = [int(i) for i in np.ravel(binout.read("abstat", "ids"))]
    except Exception:  # noqa: BLE001 - older binouts number the airbags in order
        ids = list(range(1, p.shape[1] + 1))
    return {n: (t, p[:, k]) for k, n in enumerate(ids)}


def read_abstat(path, units: str = "SI", *, scene_path=None, where: str = "fe_run.abstat") -> dict:
    """{airbag number: :class:`FePressure`} in SI from a binout or an ASCII abstat file.

    A binout is recognised by lasso-python (``pip install ventsim[lsdyna]``); any other file is read as ASCII.
    Problems are one-line :class:`SceneError` naming the scene (or the file) and ``where``.
    """
    from cases.decks.units import unit_system

    path = Path(path)
    file = scene_path if scene_path is not None else path
    if not path.is_file():
        raise SceneError(file, where, f"{path}: file not found")
    system = unit_system(units)
    try:
        found = _ascii_abstat(path) if _is_text(path) else _binout_abstat(path)
    except ImportError:
        raise SceneError(file, where, f"{path}: reading a binout needs lasso-python (pip install "
                                      "'ventsim[lsdyna]'), or give the ASCII abstat file") from None
    except Exception as exc:  # noqa: BLE001 - a damaged binary file: say which and why
        raise SceneError(file, where, f"{path}: cannot read its abstat data: {exc}") from None
    if not found:
        raise SceneError(file, where, f"{path}: no airbag pressure rows found (expected abstat blocks headed "
                                      "'time  airbag/cv #  volume  pressure ...')")
    return {n: FePressure(n, t * system.factor("time"), p * system.factor("pressure")) for n, (t, p) in found.items()}


def _is_text(path: Path) -> bool:
    head = path.read_bytes()[:4096]
    return b"\0" not in head


def scene_fe_pressures(scene) -> dict:
    """{cavity name: FePressure} of a scene's [fe_run] abstat (airbags mapped by [fe_run] airbags, else the
    cavities in order), or {} when it names none."""
    run = scene.fe_run
    if not run.abstat:
        return {}
    found = read_abstat(scene.base / run.abstat, run.units, scene_path=scene.path)
    names = [c.name for c in scene.cavity]
    numbers = dict(run.airbags) or {name: i + 1 for i, name in enumerate(names)}
    return {name: found[n] for name, n in numbers.items() if n in found}
