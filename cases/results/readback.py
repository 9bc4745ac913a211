"""A run read back from its trajectory: the history rows at the output times, each cavity's peak pressure and its
final state, on the engine's kernels (:mod:`exchange.readback.history`, :mod:`exchange.readback.peaks`,
:mod:`exchange.readback.values`)."""
from __future__ import annotations

import math
import warnings

import numpy as np

from cavity.caution import VentsimWarning
from cavity.integration import Trajectory
from exchange.readback.history import history
from exchange.readback.peaks import EDGE_PROBE, peaks
from exchange.readback.values import cavity_states

from cases.results.contact_results import contact_columns, contact_rows

__all__ = ["history_columns", "history_rows", "peak_candidates", "refine_peak", "cavity_peaks", "cavity_summary"]


def history_columns(model) -> list:
    """Names (with units) of the history columns: time, per cavity p, T, m, V, per exchange flow and area, per
    inflator its mass flow and temperature, each real-gas wall's inner (and, layered, outer) temperature, then the
    contact columns (the row layout of :class:`exchange.readback.history.HistoryLayout`)."""
    cols = ["time [s]"]
    for c in model.network.cavities:
        cols += [f"{c.name}.pressure [Pa]", f"{c.name}.temperature [K]", f"{c.name}.mass [kg]",
                 f"{c.name}.volume [m^3]"]
    for e in model.network.exchanges:
        cols += [f"{e.name}.mass_flow [kg/s]", f"{e.name}.area [m^2]"]
    for c in model.network.cavities:
        for inf in c.inflators:
            cols += [f"{c.name}.{inf.name}.mass_flow [kg/s]", f"{c.name}.{inf.name}.temperature [K]"]
    return cols + [name for name, _ in _wall_columns(model.network)] + contact_columns(model)


def _wall_columns(net) -> list:
    """[(column, unknown)] of each real-gas wall: the inner layer's temperature, then the outer layer's when the
    wall conducts in layers."""
    inner, outer = [], []
    for cav, k in zip(net.cavities, net.offsets):
        wall = getattr(cav, "wall", None)
        if wall is not None:
            ns = len(cav.initial_masses)
            inner.append((f"{cav.name}.wall_temperature [K]", k + ns + 1))
            if wall.layers > 1:
                outer.append((f"{cav.name}.outer_wall_temperature [K]", k + ns + wall.layers))
    return inner + outer


def history_rows(model, traj: Trajectory, times, deadline: float = math.inf) -> np.ndarray:
    """The history at ``times`` [s] (columns of :func:`history_columns`): one compiled call
    (:func:`exchange.readback.history.history`), then the contact columns (stopping with a SolverError once
    ``time.perf_counter()`` passes ``deadline``). A temperature that could not be solved at an output time is
    warned about (the row holds the previous row's)."""
    fast = model.network.compiled_solver()
    ycols = [k for _, k in _wall_columns(model.network)]
    ok, rows = history(fast, traj, times, ycols)
    if not ok:
        warnings.warn(VentsimWarning("history: a cavity temperature could not be solved at some output time (the "
                                     "row holds its first guess): check the history around sharp events, and rerun with a smaller "
                                     "solver.rtol or time.output_interval to resolve them"))
    contact = contact_rows(model, traj, rows[:, 0], deadline) if contact_columns(model) else None
    return rows if contact is None else np.column_stack([rows, contact])


def peak_candidates(traj: Trajectory) -> np.ndarray:
    """Times where a pressure peak is looked for [s]: every step end, segment start and the final time."""
    return np.unique(np.concatenate([traj.step_times, [s.t_min for s in traj.segments], [traj.t_final]]))


def refine_peak(ts: np.ndarray, ps: np.ndarray, pressure) -> tuple[float, float]:
    """Largest pressure [Pa] and its time [s]: the largest of ``ps`` at ``ts``, refined between its neighbours
    by a bounded scalar search on ``pressure(t)`` [Pa]; at the first or last of ``ts`` only when the pressure a
    fraction ``EDGE_PROBE`` of the step inside is larger, else that end is the peak (one evaluation instead of the
    search's ~60 golden sections towards the bound) (:func:`exchange.readback.peaks.peak_pressures` does the
    same search compiled on the compiled DOP853's records)."""
    k = int(np.argmax(ps))
    best = (float(ps[k]), float(ts[k]))
    lo, hi = ts[max(k - 1, 0)], ts[min(k + 1, len(ts) - 1)]
    if hi > lo and k in (0, len(ts) - 1):  # at an end (a discharge, a filling): searched only if p rises inside
        if not pressure(ts[k] + (EDGE_PROBE if k == 0 else -EDGE_PROBE) * (hi - lo)) > best[0]:
            return best
    if hi > lo:
        from scipy.optimize import minimize_scalar

        res = minimize_scalar(lambda t: -pressure(t), bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-14 * max(1.0, hi)})
        if -res.fun > best[0]:
            best = (float(-res.fun), float(res.x))
    return best


def cavity_peaks(model, traj: Trajectory) -> list:
    """[(peak pressure [Pa], its time [s])] per cavity, located on the dense output."""
    fast, ts = model.network.compiled_solver(), peak_candidates(traj)
    found = peaks(fast, traj, ts)
    if found is not None:
        return found
    ps = np.array([[s.pressure for s in cavity_states(fast, t, y)] for t, y in zip(ts, traj.sample(ts))])
    return [refine_peak(ts, ps[:, i], lambda t, i=i: cavity_states(fast, t, traj(t))[i].pressure)
            for i in range(ps.shape[1])]


def cavity_summary(model, traj: Trajectory, y1) -> dict:
    """Per cavity: peak pressure [Pa] and its time [s], final pressure [Pa], temperature [K] and mass [kg]."""
    net, t_end = model.network, model.scene.time.end
    finals = cavity_states(net.compiled_solver(), t_end, y1)
    out = {}
    for cav, (p, tp), s in zip(net.cavities, cavity_peaks(model, traj), finals):
        out[cav.name] = {"peak pressure [Pa]": p, "peak pressure time [s]": tp, "final pressure [Pa]": s.pressure,
                         "final temperature [K]": s.temperature, "final mass [kg]": s.mass}
    return out

