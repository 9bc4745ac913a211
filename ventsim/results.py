"""The results of a run as a Python user wants them: a DataFrame history, a summary dict, a plot, files."""
from __future__ import annotations

from pathlib import Path

__all__ = ["Results", "run"]


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
        """A history column as a NumPy array, by its full name or its name without the unit."""
        if column in self.history.columns:
            return self.history[column].to_numpy()
        return self.raw.column(column)

    def at(self, t: float, quantity: str) -> float:
        """``quantity`` (``"pressure"``, ``"temperature"``, ``"mass"``, ``"volume"``) of the cavity named
        ``"cavity.quantity"`` at any time t [s] on the solver's dense output, not only at the output times."""
        cavity, what = quantity.split(".")
        net, traj = self.raw.model.network, self.raw.trajectory
        i = [c.name for c in net.cavities].index(cavity)
        net.restore(traj.mode_at(t))
        return float(getattr(net.states(t, traj(t))[i], what))

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
