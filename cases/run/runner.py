"""Run a scene: build the model, integrate it, and reduce the trajectory to a history and a summary."""
from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field, replace

import numpy as np

from cavity.caution import VentsimWarning
from cavity.integration import SolverError, Trajectory, integrate
from exchange.network.network import LEDGER_PER_CAVITY, LEDGER_PER_EXCHANGE

from cases.model.build import Model, build_model, unique_messages
from cases.model.build_leak import blockage_rule
from cases.results.contact_results import contact_summary, nodal_history
from cases.results.readback import cavity_summary, history_columns, history_rows
from cases.results.body_outputs import body_columns
from cases.results.seal_outputs import seal_columns
from cases.scene.errors import SceneError
from cases.results.history_outputs import engineering_columns
from cases.run.provenance import provenance
from cases.scene.files import Scene, load_scene
from cases.results.species_range import species_range_warnings

__all__ = ["Results", "RunError", "run", "run_scene", "history_columns"]


@dataclass
class Results:
    """A finished run: the sampled history (columns with units), the summary, and the raw trajectory."""

    model: Model
    trajectory: Trajectory
    columns: list
    history: np.ndarray
    summary: dict = field(default_factory=dict)
    contact: dict | None = None  # per-node CPRESS and status at the output times (contact.npz)

    def column(self, name: str) -> np.ndarray:
        """One history column by its name without the unit, e.g. ``"tank.pressure"``."""
        for i, c in enumerate(self.columns):
            if c.split(" [")[0] == name:
                return self.history[:, i]
        raise KeyError(f"no column {name!r}; columns: {', '.join(self.columns)}")


def mass_balance(model: Model, y0, y1) -> dict:
    """Per cavity: initial + inflow − outflow − final, and its size relative to the mass handled [kg]."""
    net = model.network
    out = {}
    base = net.ledger_offset + LEDGER_PER_EXCHANGE * len(net.exchanges)
    for i, (cav, k) in enumerate(zip(net.cavities, net.offsets)):
        ns = len(cav.initial_masses)
        m0, m1 = float(np.sum(y0[k:k + ns])), float(np.sum(y1[k:k + ns]))
        inflow = float(y1[base + LEDGER_PER_CAVITY * i])
        net_exchange = 0.0
        for j, ex in enumerate(net.exchanges):
            m_ex = float(y1[net.ledger_offset + LEDGER_PER_EXCHANGE * j])
            net_exchange += (-m_ex if ex.upstream == i else 0.0) + (m_ex if ex.downstream == i else 0.0)
        err = m0 + inflow + net_exchange - m1
        out[cav.name] = {"initial [kg]": m0, "inflow [kg]": inflow, "exchanged in [kg]": net_exchange,
                         "final [kg]": m1, "imbalance [kg]": err,
                         "relative imbalance [-]": abs(err) / max(m0 + inflow, abs(net_exchange), 1e-300)}
    return out


class RunError(SceneError, SolverError):
    """A run that started but could not finish (the integrator stopped: step budget, step size, wall time, no
    temperature for an internal energy); ``partial`` holds the Results up to where it stopped, or None. It is a
    SceneError (one line for the user) and a SolverError (what the integrator raised)."""

    def __init__(self, file, message: str, partial=None, where: str = ""):
        super().__init__(file, where, message)
        self.partial = partial


def _budget_key(message: str) -> str:
    """The scene key of the budget a stopped run ran out of (``limits.wall``, ``limits.steps``), or ''."""
    if "more than max_wall" in message:
        return "limits.wall"
    return "limits.steps" if message.startswith("more than ") and " steps before " in message else ""


def strict_scene(scene: Scene) -> Scene:
    """The scene with ``[blockage] strict = true``."""
    return replace(scene, blockage=replace(scene.blockage, strict=True))


def run(model: Model, *, progress: bool = False, max_wall: float | None = None) -> Results:
    """Integrate a built model and reduce it; ``max_wall`` [s] overrides the scene's ``limits.wall``.

    The VentsimWarnings of building and running are in ``summary["warnings"]``. A run the integrator cannot
    finish raises :class:`RunError` (one line: what went wrong and the state), holding the partial results.
    """
    options = model.options if not max_wall else replace(model.options, max_wall=float(max_wall))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", VentsimWarning)
        try:
            results = _run(model, options, progress)
        except SolverError as exc:
            partial = _partial(model, options, exc)
            raise RunError(model.scene.path if model.scene._path else "<scene built in Python>",
                           f"the run stopped: {exc}", partial, _budget_key(str(exc))) from None
    messages = unique_messages(model.warnings + [w for w in caught if issubclass(w.category, VentsimWarning)]
                               + species_range_warnings(model, results.history, results.columns))
    if messages:
        results.summary["warnings"] = messages
    return results


def _partial(model: Model, options, exc) -> Results | None:
    """The results up to where a failed run stopped (history rows at the output times before it), or None."""
    traj = getattr(exc, "trajectory", None)
    if traj is None or not traj.segments:
        return None
    try:
        times = model.output_times[model.output_times <= traj.t_final]
        history = history_rows(model, traj, times) if times.size else np.empty((0, len(history_columns(model))))
    except Exception:  # noqa: BLE001 - what was integrated may not even be readable; report the failure alone
        return None
    summary = {"title": model.scene.title, "scene": str(model.scene.path), "error": str(exc),
               "stopped at [s]": traj.t_final, "solver": {"method": options.method, "rtol": options.rtol,
                                                          **traj.stats}, "warnings": list(model.warnings)}
    return Results(model, traj, history_columns(model), history, summary, None)


def _run(model: Model, options, progress: bool) -> Results:
    net = model.network
    y0 = net.initial_state()
    t_end = model.scene.time.end
    start = time.perf_counter()
    traj = integrate(net, y0, 0.0, t_end, options, progress=progress)
    wall = time.perf_counter() - start
    history = history_rows(model, traj, model.output_times, start + options.max_wall)
    net.restore(traj.modes[-1])
    y1 = traj(t_end)
    if model.provenance is None:  # the scene's hash costs more than a small scene's run: once per model
        model.provenance = provenance(model.scene)
    summary = {"title": model.scene.title, "scene": str(model.scene.path), "end time [s]": t_end,
               "cavities": cavity_summary(model, traj, y1), "mass balance": mass_balance(model, y0, y1),
               "solver": {"method": model.options.method, "rtol": model.options.rtol, **traj.stats,
                          "wall time [s]": wall, "event log": [[t, label] for t, label in traj.events]},
               "modelled": model.modelled, "ventsim": dict(model.provenance)}
    if model.geometry is not None:
        summary["blockage"] = blockage_summary(model, traj, history)
        if getattr(net, "body", None) is not None:
            summary["impactor"] = impactor_summary(model, traj)
    contact = None
    if getattr(net, "contact", None) is not None:
        summary["contact"] = {net.contact.name: contact_summary(model, traj)}
        contact = nodal_history(model, traj, model.output_times)
    columns, history = engineering_columns(model, traj, history_columns(model), history)
    bodies = body_columns(model, traj, history[:, 0], set(columns))
    if bodies:
        columns = columns + [name for name, _ in bodies]
        history = np.column_stack([history] + [values for _, values in bodies])
    seals = seal_columns(model, columns, history)
    if seals:
        columns = columns + [name for name, _ in seals]
        history = np.column_stack([history] + [values for _, values in seals])
    return Results(model, traj, columns, history, summary, contact)


def blockage_summary(model: Model, traj: Trajectory, history: np.ndarray) -> dict:
    """Per blocked exchange: time of first blockage, minimum leakage area and when (by time: over the run,
    :meth:`AreaTrack.smallest_area`, exact where areas are piecewise constant; by a body's pose: over the intervals
    the run used)."""
    out, t_end = {}, model.scene.time.end
    for j, ga in enumerate(model.network.areas):
        if ga is None:
            continue
        track, name = ga.track, model.network.exchanges[j].name
        if ga.by_time:
            starts = np.concatenate([[0.0], track.crossings])
            inside = starts <= t_end
            areas, times, actives = track.areas[inside], starts[inside], np.array(track.actives)[inside]
            smallest = track.smallest_area(0.0, t_end, history[:, 0])  # face areas that change inside intervals
        else:
            times, idx = [], []  # the interval each segment used (a switch or a re-derivation changed it)
            for seg, mode in zip(traj.segments, traj.modes):
                if mode is not None and (not idx or mode.intervals[j] != idx[-1]):
                    times.append(float(seg.t_min))
                    idx.append(mode.intervals[j])
            areas, actives = track.areas[idx], np.array(track.actives)[idx]
            times = np.array(times)
            k = int(np.argmin(areas))
            smallest = (float(areas[k]), float(times[k]))
        blocked = np.flatnonzero(np.asarray(actives) > 0)
        out[name] = {"first blockage time [s]": float(times[blocked[0]]) if blocked.size else None,
                     "minimum leakage area [m^2]": smallest[0], "minimum leakage area time [s]": smallest[1],
                     "total leakage surface area [m^2]": track.total_area, "area switches": len(times) - 1,
                     "crossings found": int(len(track.source.theta)) if track.source is not None else 0,
                     "gap evaluations": int(track.source.evaluations) if track.source is not None else 0,
                     **blockage_rule(model.scene, j)}
    return out


def impactor_summary(model: Model, traj: Trajectory) -> dict:
    """Energy the dynamic body gave up (peak and final), its deepest displacement and final speed."""
    net = model.network
    ts = np.unique(np.concatenate([traj.step_times, [traj.t_final]]))
    ys = traj.sample(ts)
    energy = np.array([net.impactor_energy(y) for y in ys])
    k = net.body_offset
    return {"body": net.body.name, "absorbed energy peak [J]": float(energy.max()),
            "absorbed energy final [J]": float(energy[-1]), "deepest displacement [m]": float(ys[:, k].max()),
            "deepest displacement time [s]": float(ts[int(np.argmax(ys[:, k]))]),
            "final speed [m/s]": float(ys[-1, k + 1])}


def run_scene(path_or_scene, *, progress: bool = False, max_wall: float | None = None, strict: bool = False) -> Results:
    """Load (if given a path), build and run a scene (``max_wall``: see :func:`run`; ``strict``: as the scene's
    ``[blockage] strict``, a contact interval that cannot be certified is an error)."""
    scene = path_or_scene if isinstance(path_or_scene, Scene) else load_scene(path_or_scene)
    if strict:
        scene = strict_scene(scene)
    return run(build_model(scene), progress=progress, max_wall=max_wall)
