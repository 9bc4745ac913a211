"""The results of a run as a Python user wants them: a DataFrame history, a summary dict, a plot, files."""
from __future__ import annotations

import difflib
from pathlib import Path

import numpy as np

__all__ = ["Results", "run", "UnknownColumn"]


class UnknownColumn(KeyError):
    """A history column that a run does not have; ``str()`` is one line with the closest names."""

    def __str__(self) -> str:
        return str(self.args[0])


def _bare(name: str) -> str:
    """A column's name without its unit: ``"bag.pressure [Pa]"`` -> ``"bag.pressure"``."""
    return name.split(" [")[0].strip()


def resolve(columns, name) -> int:
    """The index of the history column ``name``, given with its unit (``"bag.pressure [Pa]"``) or without it
    (``"bag.pressure"``); :class:`UnknownColumn` naming the closest columns otherwise.

    >>> resolve(["time [s]", "bag.pressure [Pa]"], "bag.pressure")
    1
    >>> resolve(["time [s]", "bag.pressure [Pa]"], "bag.presure [Pa]")
    Traceback (most recent call last):
    ...
    ventsim.results.UnknownColumn: no history column 'bag.presure [Pa]' (did you mean 'bag.pressure [Pa]'?); columns: time [s], bag.pressure [Pa]
    """
    if not isinstance(name, str):
        raise UnknownColumn(f"a history column is named by a string such as 'bag.pressure', got {name!r}")
    columns = list(columns)
    if name in columns:
        return columns.index(name)
    bare = [_bare(c) for c in columns]
    if _bare(name) in bare:
        i = bare.index(_bare(name))
        if " [" not in name:
            return i
        raise UnknownColumn(f"history column {bare[i]!r} is in {columns[i][len(bare[i]):].strip()}, not in "
                            f"{name[len(_bare(name)):].strip()}: name it {columns[i]!r} or {bare[i]!r}")
    close = difflib.get_close_matches(name, columns, n=3, cutoff=0.6) or [
        columns[bare.index(c)] for c in difflib.get_close_matches(_bare(name), bare, n=3, cutoff=0.6)]
    hint = f" (did you mean {' or '.join(map(repr, close))}?)" if close else ""
    raise UnknownColumn(f"no history column {name!r}{hint}; columns: {', '.join(columns)}")


class Results:
    """A finished run.

    Attributes
    ----------
    history : pandas.DataFrame
        One row per output time; the columns of ``history.csv`` with their units in the names
        (``"time [s]"``, ``"tank.pressure [Pa]"``, ``"tank.gauge_pressure [Pa]"``, ``"vent.area [m^2]"``, ...).
    summary : dict
        What ``summary.json`` holds (peaks, final state, mass balance, solver statistics, provenance).
    scene : ventsim.Scene
        The scene that ran.
    raw : cases.run.runner.Results
        The runner's results (model, trajectory with dense output, history array).
    """

    def __init__(self, scene, raw):
        self.scene, self.raw = scene, raw
        self._history = None

    @property
    def history(self):
        if self._history is None:
            import pandas as pd

            self._history = pd.DataFrame(self.raw.history, columns=list(self.raw.columns))
        return self._history

    @property
    def summary(self) -> dict:
        return self.raw.summary

    def __getitem__(self, column: str):
        """A history column as a NumPy array, by its full name (``"bag.pressure [Pa]"``) or without the unit
        (``"bag.pressure"``); an unknown name raises :class:`UnknownColumn` (a KeyError) naming the closest."""
        return self.raw.history[:, resolve(self.raw.columns, column)].copy()

    def at(self, t: float, column: str) -> float:
        """The history column ``column`` (any name ``results[...]`` takes: ``"bag.pressure [Pa]"``,
        ``"vent.mass_flow"``, ``"headform.displacement"``) at any time t [s] in the run, read from the solver's
        dense output as the history rows are, not interpolated between them."""
        index = resolve(self.raw.columns, column)
        traj = self.raw.trajectory
        if isinstance(t, bool) or not isinstance(t, (int, float, np.floating)) or not 0.0 <= t <= traj.t_final:
            raise ValueError(f"t = {t!r} s is outside the run: give a time from 0 to {traj.t_final:.9g} s")
        return float(self._row(float(t))[index])

    def _row(self, t: float) -> np.ndarray:
        """Every history column at time ``t``, computed as the runner computes the output rows."""
        from cases.results.body_outputs import body_columns
        from cases.results.history_outputs import engineering_columns
        from cases.results.readback import history_columns, history_rows

        model, traj = self.raw.model, self.raw.trajectory
        rows = history_rows(model, traj, np.array([t]))
        columns, rows = engineering_columns(model, traj, history_columns(model), rows)
        bodies = body_columns(model, traj, rows[:, 0], set(columns))
        if bodies:
            rows = np.column_stack([rows] + [values for _, values in bodies])
        return rows[0]

    def plot(self, path=None):
        """The history figure (pressure, gauge pressure, temperature, flows, vent area, ... against time):
        a ``matplotlib.figure.Figure``; also written to ``path`` (PNG) when given."""
        from cases.results.output import history_figure, plot_history

        if path is not None:
            plot_history(Path(path), self.raw.columns, self.raw.history, self.scene.title)
        return history_figure(self.raw.columns, self.raw.history, self.scene.title)

    def to_vtk(self, folder) -> list:
        """Write the VTK series (every surface of the scene, ``.vtp`` frames and a ``.pvd``) into ``folder``;
        returns the ``.pvd`` paths (empty when the scene has no geometry)."""
        from cases.results.pictures import write_vtk

        return write_vtk(self.raw, Path(folder))

    def save(self, folder, *, render: bool = False) -> dict:
        """Write history.csv, summary.json, history.png (and with ``render`` the pictures and the VTK series)
        into ``folder``, as ``ventsim run`` does; returns ``{kind: path}``."""
        from cases.results.output import write_results

        paths = write_results(self.raw, Path(folder))
        if render:
            from cases.results.pictures import write_pictures

            pics = write_pictures(self.raw, Path(folder))
            paths.update({f"{k} {i}": p for k, v in pics.items() for i, p in enumerate(v)})
        return paths

    def __repr__(self) -> str:
        cav = ", ".join(f"{n} peak {c['peak pressure [Pa]']:.6g} Pa" for n, c in self.summary["cavities"].items())
        return f"Results({self.scene.title or str(self.scene.path)!r}: {cav})"


def run(scene, *, progress: bool = False, strict: bool = False) -> Results:
    """Build and integrate a scene; ``scene`` is a :class:`ventsim.Scene`, a TOML path or a scene dict.
    ``strict``: a leakage node whose contact intervals cannot be certified stops the run with an error (as the
    scene's ``[blockage] strict = true``); otherwise it is a warning naming the nodes and the area·time at stake.

    >>> import ventsim
    >>> r = ventsim.run("cases/verification/fill_constant.toml")
    >>> r.history.columns[:3].tolist()
    ['time [s]', 'tank.pressure [Pa]', 'tank.gauge_pressure [Pa]']
    """
    from cases.model.build import build_model
    from cases.run.runner import run as run_model

    from .scene import Scene, load

    if isinstance(scene, dict):
        scene = Scene(scene)
    elif not isinstance(scene, Scene):
        scene = load(scene)
    spec = scene.spec
    if strict:
        from cases.run.runner import strict_scene

        spec = strict_scene(spec)
    return Results(scene, run_model(build_model(spec), progress=progress))
