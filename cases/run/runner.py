"""Run a scene: build the model, integrate it, and reduce the trajectory to a history and a summary."""
from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import minimize_scalar

from cavity.caution import VentsimWarning
from cavity.integration import SolverError, Trajectory, integrate
from exchange.network import LEDGER_PER_CAVITY, LEDGER_PER_EXCHANGE

from cases.model.build import Model, build_model, unique_messages
from cases.model.build_leak import blockage_rule
from cases.results.contact_results import contact_columns, contact_row, contact_summary, nodal_history
from cases.results.body_outputs import body_columns
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


def history_columns(model: Model) -> list:
    cols = ["time [s]"]
    for c in model.network.cavities:
        cols += [f"{c.name}.pressure [Pa]", f"{c.name}.temperature [K]", f"{c.name}.mass [kg]",
                 f"{c.name}.volume [m^3]"]
    for e in model.network.exchanges:
        cols += [f"{e.name}.mass_flow [kg/s]", f"{e.name}.area [m^2]"]
    cols += [f"{c.name}.wall_temperature [K]" for c in model.network.cavities if getattr(c, "wall", None)]
    cols += [f"{c.name}.outer_wall_temperature [K]" for c in model.network.cavities if _layered(c)]
    return cols + contact_columns(model)


def quantities(model: Model, t: float, y, mode=None) -> list:
    """One history row at (t, y), in the discrete state ``mode`` (vents popped or not) in force then."""
    net = model.network
    net.restore(mode)
    states = net.states(t, y)
    row = [t]
    for s in states:
        row += [s.pressure, s.temperature, s.mass if s.mixture is None else s.mixture.mass, s.volume]
    for j, (mdot, _) in enumerate(net.exchange_flows(t, states)):
        row += [mdot, net.exchange_area(j, t)]
    row += [s.wall_temperature for c, s in zip(net.cavities, states) if getattr(c, "wall", None)]
    row += [s.outer_wall_temperature for c, s in zip(net.cavities, states) if _layered(c)]
    return row + contact_row(model, t, y)


def _layered(cavity) -> bool:
    """A real-gas cavity whose wall conducts in layers (its outer layer's temperature is a column too)."""
    return getattr(getattr(cavity, "wall", None), "layers", 1) > 1


def pressure_at(model: Model, traj: Trajectory, i: int, t: float) -> float:
    return model.network.states(t, traj(t))[i].pressure


def peak_candidates(traj: Trajectory) -> np.ndarray:
    """Times where a pressure peak is looked for [s]: every step end, segment start and the final time."""
    return np.unique(np.concatenate([traj.step_times, [s.t_min for s in traj.segments], [traj.t_final]]))


def refine_peak(ts: np.ndarray, ps: np.ndarray, pressure) -> tuple[float, float]:
    """Largest pressure [Pa] and its time [s]: the largest of ``ps`` at ``ts``, refined between its neighbours
    by a bounded scalar search on ``pressure(t)`` [Pa]."""
    k = int(np.argmax(ps))
    best = (float(ps[k]), float(ts[k]))
    lo, hi = ts[max(k - 1, 0)], ts[min(k + 1, len(ts) - 1)]
    if hi > lo:
        res = minimize_scalar(lambda t: -pressure(t), bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-14 * max(1.0, hi)})
        if -res.fun > best[0]:
            best = (float(-res.fun), float(res.x))
    return best


def peak_pressure(model: Model, traj: Trajectory, i: int) -> tuple[float, float]:
    """Largest pressure of cavity i and its time, refined on the dense output (independent of output times)."""
    ts = peak_candidates(traj)
    ps = np.array([model.network.states(t, y)[i].pressure for t, y in zip(ts, traj.sample(ts))])
    return refine_peak(ts, ps, lambda t: pressure_at(model, traj, i, t))


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


def compiled_readback(model: Model, traj: Trajectory):
    """When ``traj`` ran on the compiled path: ``read(times) -> rows or None``, its history at ``times`` [s]
    (columns of :func:`history_columns`) in one compiled call (:mod:`exchange.compiled_history`), with
    ``read.peaks(ts)``, :func:`exchange.compiled_peak.peaks` over the candidate times ``ts``; else None."""
    if traj.path != "compiled" or contact_columns(model):
        return None
    fast = model.network.compiled_solver()
    if fast is None or fast.host >= 0:  # hosted parts (a real-gas wall's columns): row by row
        return None
    from exchange.compiled_history import equalised_per_segment, history
    from exchange.compiled_peak import peaks

    eqs = equalised_per_segment(traj.modes, len(model.network.exchanges))

    def read(times):
        return history(fast, traj, times, eqs)

    read.peaks = lambda ts: peaks(fast, traj, ts)
    return read


def history_rows(model: Model, traj: Trajectory, times, readback=None, deadline: float = math.inf) -> np.ndarray:
    """The history at ``times`` [s] (columns of :func:`history_columns`): one compiled call with a
    :func:`compiled_readback`, else (or if that fails) row by row with :func:`quantities`, stopping with a
    SolverError once ``time.perf_counter()`` passes ``deadline``."""
    rows = readback(times) if readback is not None else None
    if rows is not None:
        return rows
    ys = traj.sample(times)
    out = []
    for k, (t, y) in enumerate(zip(times, ys)):
        if k % 256 == 255 and time.perf_counter() > deadline:
            raise SolverError(f"out of wall time (max_wall) writing history rows: {k} of {len(times)} done; "
                              "raise time.output_interval")
        out.append(quantities(model, t, y, traj.mode_at(t)))
    return np.array(out)


def compiled_cavity_values(model: Model, traj: Trajectory, readback):
    """(peaks [(p [Pa], t [s])], finals [(p [Pa], T [K], m [kg])]) per cavity from a :func:`compiled_readback`,
    or None if it fails (as :func:`peak_pressure` and the cavity states at the end time)."""
    peaks, last = readback.peaks(peak_candidates(traj)), readback([model.scene.time.end])
    if peaks is None or last is None:
        return None
    return peaks, [tuple(float(v) for v in last[0, 1 + 4 * i:4 + 4 * i]) for i in range(len(model.network.cavities))]


def cavity_summary(model: Model, traj: Trajectory, y1, readback=None) -> dict:
    """Per cavity: peak pressure [Pa] and its time [s], final pressure [Pa], temperature [K] and mass [kg]."""
    net, t_end, out = model.network, model.scene.time.end, {}
    fast = compiled_cavity_values(model, traj, readback) if readback is not None else None
    for i, cav in enumerate(net.cavities):
        if fast is not None:
            (p, tp), (p1, T1, m1) = fast[0][i], fast[1][i]
        else:
            p, tp = peak_pressure(model, traj, i)
            s = net.states(t_end, y1)[i]
            p1, T1, m1 = s.pressure, s.temperature, s.mass if s.mixture is None else s.mixture.mass
        out[cav.name] = {"peak pressure [Pa]": p, "peak pressure time [s]": tp, "final pressure [Pa]": p1,
                         "final temperature [K]": T1, "final mass [kg]": m1}
    return out


class RunError(SceneError, SolverError):
    """A run that started but could not finish (the integrator stopped: step budget, step size, wall time, no
    temperature for an internal energy); ``partial`` holds the Results up to where it stopped, or None. It is a
    SceneError (one line for the user) and a SolverError (what the integrator raised)."""

    def __init__(self, file, message: str, partial=None):
        super().__init__(file, "", message)
        self.partial = partial


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
                           f"the run stopped: {exc}", partial) from None
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
    readback = compiled_readback(model, traj)
    history = history_rows(model, traj, model.output_times, readback, start + options.max_wall)
    net.restore(traj.modes[-1])
    y1 = traj(t_end)
    summary = {"title": model.scene.title, "scene": str(model.scene.path), "end time [s]": t_end,
               "cavities": cavity_summary(model, traj, y1, readback), "mass balance": mass_balance(model, y0, y1),
               "solver": {"method": model.options.method, "rtol": model.options.rtol, **traj.stats,
                          "wall time [s]": wall, "event log": [[t, label] for t, label in traj.events]},
               "modelled": model.modelled, "ventsim": provenance(model.scene)}
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
                if mode is not None and (not idx or mode[1][j] != idx[-1]):
                    times.append(float(seg.t_min))
                    idx.append(mode[1][j])
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


def run_scene(path_or_scene, *, progress: bool = False, max_wall: float | None = None) -> Results:
    """Load (if given a path), build and run a scene (``max_wall``: see :func:`run`)."""
    scene = path_or_scene if isinstance(path_or_scene, Scene) else load_scene(path_or_scene)
    return run(build_model(scene), progress=progress, max_wall=max_wall)
