"""Integration of a cavity system: between discontinuities, restarted after each one.

The model is not known here: a system gives a right-hand side, the times where its inputs have kinks
(table breakpoints, start times: known in advance), and state events (a vent popping, a node touching) found by
root finding on the dense output. The solver integrates up to each breakpoint or event and restarts after it,
so no step ever straddles a discontinuity.

A cavity network lowers itself to arrays (``compiled_solver()``: :class:`exchange.engine.engine.Engine`), and
one engine runs it: with DOP853 (the default) the whole integration is one numba call (:mod:`cavity.rk_compiled`,
``exchange.engine.solver``: the same steps, switches and restarts as solve_ivp's DOP853, except that a trial step
whose stage finds no gas state is retried shorter where solve_ivp stops); with scipy's other methods (LSODA, Radau,
BDF, RK45, RK23) ``solve_ivp`` steps the same compiled right-hand side, switch functions and switch actions
(:mod:`exchange.lowered_system`), segment by segment. A network that does not lower is refused with the reason.
Any other system (a plain object with ``rhs``, ``events``...) runs through ``solve_ivp`` as it is.
``Trajectory.path`` says which ran.
"""
from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass

import numpy as np
from .lazy_scipy import solve_ivp

from .jacobian import EXPLICIT_METHODS, jacobian_option, stiffness_advice
from .trajectory import Trajectory
from .progress import ProgressBar

__all__ = ["SolverOptions", "Trajectory", "SolverError", "integrate", "METHODS", "stiffness_advice"]

#: Events allowed at one instant before the run is declared stuck (chattering switches).
MAX_EVENTS_AT_ONE_TIME = 20
#: A switch function closer to zero than this times rtol at a restart is judged by its trend, not its sign.
SWITCH_NEAR_ZERO_PER_RTOL = 100.0

METHODS = ("RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA")


class SolverError(RuntimeError):
    """The integrator failed; the message names the time and the state where it stopped.

    ``trajectory`` holds what was integrated before (a :class:`Trajectory`, or None when nothing was)."""

    trajectory = None


@dataclass(frozen=True)
class SolverOptions:
    """How to integrate.

    Attributes
    ----------
    method : str
        One of scipy's ``solve_ivp`` methods (:data:`METHODS`).
    rtol : float
        Relative tolerance [-].
    atol : float or (n,) float
        Absolute tolerance per unknown, in the unknowns' units (kg, J, ...).
    max_step : float
        Largest step [s].
    max_steps : int
        Steps after which the run is declared stuck (no hang on a stiff or chattering scene).
    max_wall : float
        Wall time [s] after which the run is stopped (scipy's methods: checked every step; the compiled DOP853
        looks at the clock every 1,024 steps).
    integrator : str
        ``"compiled"`` (default): DOP853 runs as one numba call; ``"scipy"``: ``solve_ivp`` steps the same compiled
        right-hand side and switches with DOP853 too (a second implementation of the stepping and the event
        location, to cross-check a run). The other methods always step through ``solve_ivp``.
    """

    method: str = "DOP853"
    rtol: float = 1e-6
    atol: object = 1e-12
    max_step: float = math.inf
    max_steps: int = 2_000_000
    max_wall: float = math.inf
    integrator: str = "compiled"

    def __post_init__(self):
        if self.method not in METHODS:
            raise ValueError(f"solver method must be one of {', '.join(METHODS)}; got {self.method!r}")
        if not (0.0 < self.rtol < 1.0):
            raise ValueError(f"rtol must be in (0, 1), got {self.rtol!r}")
        if self.integrator not in ("compiled", "scipy"):
            raise ValueError(f"integrator must be 'compiled' or 'scipy'; got {self.integrator!r}")
        if not self.max_wall > 0:
            raise ValueError(f"max_wall must be > 0 [s], got {self.max_wall!r}")


def integrate(system, y0, t0: float, t1: float, options: SolverOptions, *, progress: bool = False) -> Trajectory:
    """Integrate ``system`` from t0 to t1, stopping at its breakpoints and events.

    Parameters
    ----------
    system : object
        Has ``rhs(t, y) -> (n,) float``, ``breakpoints`` (iterable of times [s]), ``events() -> list`` of
        scipy event functions (``terminal`` set, ``direction`` as needed) valid for the current discrete state,
        ``on_event(t, y, index) -> (n,) float`` which applies the switch of event ``index`` (and may change what
        ``events()`` returns), and ``describe(t, y) -> str`` for error messages. Optional:
        ``arm(t0, y0) -> labels`` (switches already past their threshold at the start, applied then and logged),
        ``begin_segment(t0, t1, y0)``, ``snapshot()``/``restore(mode)`` (its discrete state per segment) and
        ``compiled_solver()`` (None, or an object whose ``run`` integrates the whole span compiled: see
        :func:`_integrate_compiled`).
    y0 : (n,) float
        Initial unknowns.
    options : SolverOptions
    progress : bool
        Show a progress bar on stderr when the run takes more than a second.
    """
    stops = sorted({float(b) for b in system.breakpoints if t0 < b < t1} | {t1})
    fast = _compiled_system(system, options)
    compiled = options.method == "DOP853" and options.integrator == "compiled"
    if fast is not None and not compiled:  # scipy's method on the compiled engine
        network, system = system, fast.solve_ivp_system(SWITCH_NEAR_ZERO_PER_RTOL * options.rtol)
    y0 = np.asarray(y0, dtype=float)
    arm = getattr(fast if fast is not None else system, "arm", None)
    armed = [(float(t0), label) for label in arm(t0, y0)] if arm is not None else []
    start = _time.perf_counter()
    if fast is not None and compiled:
        traj = _integrate_compiled(system, fast, y0, t0, stops, options)
        traj.events[:0] = armed
        traj.stats["events"] += len(armed)
        if _time.perf_counter() - start > options.max_wall:
            exc = SolverError(f"the run took {_time.perf_counter() - start:.3g} s, more than max_wall = "
                              f"{options.max_wall:g} s")
            exc.trajectory = traj
            raise exc
        return traj
    path = getattr(system, "path", "python")
    traj = Trajectory(deadline=start + options.max_wall, events=armed, path=path)
    traj.stats.update(events=len(armed), path=path)
    bar = ProgressBar(t1 - t0, desc="ventsim", unit="s", enabled=progress)
    t, y = float(t0), np.asarray(y0, dtype=float)
    try:
        for stop in stops:
            while t < stop:
                t, y = _advance(system, t, y, stop, options, traj)
                bar.update_to(t - t0)
        bar.close(complete=True)
    except SolverError as exc:
        exc.trajectory = traj if traj.segments else None
        raise
    finally:
        bar.close()
    if fast is not None and traj.modes:  # the discrete state at the end, as the compiled DOP853 leaves it
        network.restore(traj.modes[-1])
        fast.load_discrete_state()
    return traj


def _compiled_system(system, options):
    """The network lowered for the compiled engine (``compiled_solver()``), None for a system that does not lower
    itself; a SolverError for a network that cannot be lowered, with the reason."""
    lower = getattr(system, "compiled_solver", None)
    if lower is None:
        return None
    fast = lower()
    if fast is None:
        raise SolverError(f"the engine cannot run {type(system).__name__}: "
                          f"{getattr(system, 'compiled_unsupported', lambda: 'no compiled_solver()')()}")
    return fast


_RTOL_FLOOR = 100 * float(np.finfo(float).eps)  # scipy's smallest rtol


def _compiled_advice(system, fast, traj, rtol: float, t: float, y, t_end: float, method: str) -> str:
    """:func:`stiffness_advice` for a failed compiled run, on its right-hand side in the discrete state where it
    stopped."""
    try:
        if traj is not None and traj.modes and hasattr(system, "restore"):
            system.restore(traj.modes[-1])
        rhs_system = fast.solve_ivp_system(SWITCH_NEAR_ZERO_PER_RTOL * rtol)
    except Exception:  # noqa: BLE001 - only a hint depends on it
        return ""
    return stiffness_advice(method, rhs_system, t, y, t_end)


def _integrate_compiled(system, fast, y0, t0, stops, options) -> Trajectory:
    """Run the compiled DOP853 path (the system's ``compiled_solver().run``) and wrap its records."""
    rtol = max(options.rtol, _RTOL_FLOOR)
    try:
        status, t, y, recs, segs, evs, st = fast.run(y0, t0, stops, rtol, options.atol, options.max_step,
                                                     options.max_steps, SWITCH_NEAR_ZERO_PER_RTOL * rtol,
                                                     _time.perf_counter() + options.max_wall)
    except (ArithmeticError, ValueError) as exc:  # numba raises as Python would (a step size divided to zero)
        raise SolverError(f"the compiled DOP853 failed ({type(exc).__name__}: {exc}) from t = {t0:.9g} s; "
                          f"{system.describe(t0, np.asarray(y0, dtype=float))}; inputs this extreme (a rate "
                          f"or an area many orders too large?) stop it") from None
    if status:  # the messages scipy's methods give
        state = system.describe(t, y)
        traj = _compiled_trajectory(system, fast, t0, recs, segs, evs, st) if len(segs) else None
        stiff = _compiled_advice(system, fast, traj, rtol, t, y, stops[-1], options.method) if status < 3 else ""
        exc = SolverError({1: f"more than {options.max_steps} steps before t = {t:.9g} s; {state}{stiff}",
                           2: f"DOP853 stopped at t = {t:.9g} s: Required step size is less than spacing between "
                              f"numbers.; {state}{stiff}",
                           3: f"the right-hand side failed near t = {t:.9g} s ({_failure(fast)}); {state}",
                           4: f"non-finite state at t = {t:.9g} s; {state}",
                           5: f"switches keep firing at t = {t:.9g} s without progress; {state}",
                           6: f"more than max_wall = {options.max_wall:g} s of wall time before t = {t:.9g} s; "
                              f"{state}"}[status])
        exc.trajectory = traj
        raise exc
    return _compiled_trajectory(system, fast, t0, recs, segs, evs, st)


#: Why a compiled right-hand side failed when the lowered system does not say (``failure()``).
NO_TEMPERATURE = "no temperature found for a cavity's internal energy"


def _failure(fast) -> str:
    """Why the compiled right-hand side failed (the lowered system's ``failure()``, if it says)."""
    failure = getattr(fast, "failure", None)
    return failure() if failure is not None else NO_TEMPERATURE


def _compiled_trajectory(system, fast, t0, recs, segs, evs, st) -> Trajectory:
    """The Trajectory of the compiled solver's records and segment table."""
    from .rk_compiled import DenseSteps

    traj = Trajectory(path="compiled", compiled_records=(recs, segs))
    for first, end, t_min, t_max, code in segs.tolist():
        traj.segments.append(DenseSteps(recs[int(first):int(end)], t_min, t_max))
        traj.modes.append(fast.segment_mode(code))
    if traj.modes and system.snapshot() != traj.modes[-1]:
        system.restore(traj.modes[-1])  # the discrete state at the end
    traj.step_times = [float(t0)] + recs[:, 2].tolist()
    labels = fast.labels
    traj.events = [(te, labels[int(q)]) for te, q, _ in evs.tolist()]
    rhs_calls, steps, restarts, events = st.tolist()
    traj.stats.update(steps=steps, rhs_calls=rhs_calls, restarts=restarts, events=events, path="compiled")
    if events:
        te, q, d = evs[-1].tolist()
        if segs[-1, 3] == te:
            traj.last_event = (labels[int(q)], te, d)
    return traj


def _directions(system, events, t, y, last, near) -> list:
    """Crossing direction each switch function is watched for, away from its current sign.

    Switch functions are dimensionless and of order one. The function that has just fired is watched for the
    opposite crossing, so a root located a rounding error before the true crossing cannot fire again at the
    restart. A function with a ``direction`` attribute is watched that way. A function within ``near`` of zero (a twin of the one that fired, a tank exactly at ambient) is
    watched against its trend along the flow: if it is moving up it can only fire coming back down; if it does
    not move it is not watched in this segment (its kink is the segment's start).
    """
    dirs, slope_probe = [], None
    for g in events:
        label = getattr(g, "label", None)
        if getattr(g, "direction", None) is not None:  # the system knows which way it can cross
            dirs.append(g.direction)
            continue
        if last is not None and label is not None and label == last[0] and t == last[1]:
            dirs.append(-last[2])
            continue
        v = g(t, y)
        if abs(v) > near:
            dirs.append(1.0 if v < 0 else -1.0)
            continue
        if slope_probe is None:
            dt = 1e-9 * max(abs(t), 1e-6)
            slope_probe = (t + dt, y + dt * np.asarray(system.rhs(t, y)))
        trend = g(*slope_probe) - v
        dirs.append(-1.0 if trend > 0 else 1.0 if trend < 0 else None)  # None: not watched
    return dirs


def _watched(g, direction):
    def event(t, y):
        return g(t, y)

    event.terminal, event.direction = True, direction
    event.label = getattr(g, "label", "event")
    return event


def _step_budget(system, remaining: int, options, deadline: float, stop: float):
    """A never-firing event: scipy evaluates it once per accepted step, so it counts the steps of one solve and
    stops a segment that exceeds the run's step budget or its wall-time ``deadline`` (solve_ivp has neither)."""
    count, last = [0], [-math.inf]

    def budget(t, y):
        count[0] += 1
        last[0] = t
        if count[0] > remaining + 1:  # the first call is at the segment's start
            raise SolverError(f"more than {options.max_steps} steps before t = {t:.9g} s; {system.describe(t, y)}"
                              f"{stiffness_advice(options.method, system, t, y, stop)}")
        if _time.perf_counter() > deadline:
            raise SolverError(f"more than max_wall = {options.max_wall:g} s of wall time before t = {t:.9g} s; "
                              f"{system.describe(t, y)}")
        return 1.0

    budget.terminal, budget.direction, budget.label, budget.last_step = False, 0.0, "step budget", last
    return budget


def _keep_progress(system, t, y, t_ok: float, options, traj) -> None:
    """After a failure inside the segment from t: integrate it again to ``t_ok``, its last accepted step, and keep
    that in ``traj`` (solve_ivp returns nothing when the right-hand side raises); nothing if that fails too."""
    try:
        sol = _solve(system, t, t_ok, y, options, traj, []) if t_ok > t else None
    except (ArithmeticError, ValueError):
        return
    if sol is not None and sol.status == 0:
        _keep_segment(system, sol, traj)


def _solve(system, t, stop, y, options, traj, events):
    """One solve_ivp call of the system from (t, y) to stop with dense output, watching ``events``."""
    return solve_ivp(system.rhs, (t, stop), y, method=options.method, rtol=options.rtol, atol=options.atol,
                     max_step=options.max_step, dense_output=True, events=events,
                     **jacobian_option(system, options.method, system.rhs, traj.stats))


def _keep_segment(system, sol, traj) -> None:
    """Append a solve_ivp solution to ``traj``: its dense output, the discrete state it ran in, its step times."""
    traj.segments.append(sol.sol)
    traj.modes.append(system.snapshot() if hasattr(system, "snapshot") else None)
    traj.step_times.extend(sol.t[1:] if traj.step_times else sol.t)


def _state_at_event(system, sol, t_event, options, traj):
    """The state at an event time, integrated to it from the last accepted step rather than interpolated.

    The dense output of a long step is accurate to a lower order than the steps themselves; restarting from it
    would carry that interpolation error into everything after the event.
    """
    t_k, y_k = float(sol.t[-2]), sol.y[:, -2]
    if t_event <= t_k:
        return sol.y[:, -1]
    tail = solve_ivp(system.rhs, (t_k, t_event), y_k, method=options.method, rtol=options.rtol, atol=options.atol,
                     max_step=options.max_step, dense_output=True)
    traj.stats["rhs_calls"] += tail.nfev
    traj.stats["steps"] += len(tail.t) - 1
    traj.segments.append(tail.sol)
    traj.modes.append(traj.modes[-1])
    traj.step_times.extend(tail.t[1:])
    return tail.y[:, -1]


def _advance(system, t, y, stop, options, traj):
    """One solve_ivp call from t towards stop; returns where it ended (stop, or an event)."""
    if hasattr(system, "begin_segment"):
        system.begin_segment(t, stop, y)
    switches = system.events()
    try:
        dirs = _directions(system, switches, t, y, traj.last_event, SWITCH_NEAR_ZERO_PER_RTOL * options.rtol)
    except (ArithmeticError, ValueError) as exc:  # a switch function failed as the right-hand side can
        raise SolverError(f"a switch function failed at t = {t:.9g} s ({exc}); {system.describe(t, y)}") from None
    switches = [g for g, d in zip(switches, dirs) if d is not None]
    dirs = [d for d in dirs if d is not None]
    events = [_watched(g, d) for g, d in zip(switches, dirs)]
    remaining = options.max_steps - traj.stats["steps"]
    if remaining <= 0:
        raise SolverError(f"more than {options.max_steps} steps before t = {t:.9g} s; {system.describe(t, y)}")
    budget = _step_budget(system, remaining, options, traj.deadline, stop)
    try:
        sol = _solve(system, t, stop, y, options, traj, events + [budget])
    except (ArithmeticError, ValueError) as exc:
        _keep_progress(system, t, y, budget.last_step[0], options, traj)
        raise SolverError(f"the right-hand side failed in the segment from t = {t:.9g} s ({exc}); at the "
                          f"segment's start: {system.describe(t, y)}") from None
    if sol.status == -1:
        raise SolverError(f"{options.method} stopped at t = {sol.t[-1]:.9g} s: {sol.message}; "
                          f"{system.describe(sol.t[-1], sol.y[:, -1])}"
                          f"{stiffness_advice(options.method, system, sol.t[-1], sol.y[:, -1], stop)}")
    if not np.all(np.isfinite(sol.y[:, -1])):
        raise SolverError(f"non-finite state at t = {sol.t[-1]:.9g} s; {system.describe(sol.t[-1], sol.y[:, -1])}")
    st = traj.stats
    st["steps"] += len(sol.t) - 1
    st["rhs_calls"] += sol.nfev
    st["jacobians"] += sol.njev
    st["lu_decompositions"] += sol.nlu
    st["restarts"] += 1
    _keep_segment(system, sol, traj)
    t_end, y_end = float(sol.t[-1]), sol.y[:, -1]
    if sol.status != 1:
        traj.last_event = None
    else:
        index = next(i for i, te in enumerate(sol.t_events) if len(te))
        t_end = float(sol.t_events[index][0])
        y_end = _state_at_event(system, sol, t_end, options, traj)
        label = events[index].label
        traj.events.append((t_end, label))
        st["events"] += 1
        y_end = np.asarray(system.on_event(t_end, y_end, label), dtype=float)
        if traj.last_event is not None and traj.last_event[1] == t_end:
            traj.stalls += 1
            if traj.stalls > MAX_EVENTS_AT_ONE_TIME:
                raise SolverError(f"switches keep firing at t = {t_end:.9g} s without progress ({label}); "
                                  f"{system.describe(t_end, y_end)}")
        else:
            traj.stalls = 0
        traj.last_event = (label, t_end, dirs[index])
    return t_end, y_end
