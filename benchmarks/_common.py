"""Shared pieces of the integrator benchmarks: cases, references, runners and error measures.

Every runner returns a :class:`Run`: wall time of the solve only (scene loading, model building and the
evaluation of the error are not timed), right-hand-side calls, steps, and the pressure of cavity 0 on the case's
evaluation grid. Errors are relative: ``max |p/p_ref - 1|`` over the grid, and ``|peak/peak_ref - 1|`` where the
peak is not the initial state.

Runners
-------
- :func:`run_ventsim`: ``cavity.integration.integrate`` (stops at table breakpoints, choking and reversal
  switches, dense output), any scipy method.
- :func:`run_plain_scipy`: one ``scipy.integrate.solve_ivp`` call on the same right-hand side, no stops, no switches.

The peers (fixed-step explicit schemes, Cantera) are in :mod:`_peers`.
"""
from __future__ import annotations

import math
import os
import platform
import sys
import time
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # tests.closed_forms holds the references
    sys.path.insert(0, str(ROOT))

from cases.model.build import build_model
from cases.results.readback import cavity_peaks, history_rows
from cases.scene.files import load_scene
from cavity.integration import SolverError, integrate


VERIFICATION = ROOT / "cases" / "verification"

R_U = 8.314462618
M_N2 = 0.0280134
CP_N2 = 29.100619163  # [J/(mol K)], constant, as in the verification scenes
R_N2 = R_U / M_N2
GAMMA = CP_N2 / (CP_N2 - R_U)

#: The cases: name -> scene file.
CASE_FILES = {
    "blowdown_choked": VERIFICATION / "blowdown_choked.toml",
    "blowdown_isothermal": VERIFICATION / "blowdown_isothermal.toml",
    "blowdown_subsonic": VERIFICATION / "blowdown_subsonic.toml",
    "fill_constant": VERIFICATION / "fill_constant.toml",
    "compression_mesh": VERIFICATION / "compression_mesh.toml",
    "airbag_vented": ROOT / "cases" / "airbag_vented.toml",
}

#: Scipy methods compared (ventsim's default first).
SCIPY_METHODS = ("DOP853", "RK45", "LSODA", "Radau", "BDF")


@dataclass
class Case:
    """A scene, its built model, and the reference pressure of cavity 0 on an evaluation grid."""

    name: str
    scene: object
    model: object
    times: np.ndarray  # evaluation grid [s]
    p_ref: np.ndarray  # reference pressure on `grid` (times, then the peak window) [Pa]
    peak_ref: float | None  # reference peak pressure [Pa]; None when the peak is the initial state
    peak_window: np.ndarray = None  # fine grid around the reference peak (interior peaks), evaluated too
    reference: str = ""  # what the reference is
    reference_check: str = ""  # how it was checked (converged references)
    peak_time: float | None = None  # [s] of the reference peak (converged references)
    reference_rtol: float | None = None  # rtol of a converged reference (that run is the reference itself)

    @property
    def t_end(self) -> float:
        return self.scene.time.end

    @property
    def grid(self) -> np.ndarray:
        """All times where a run's pressure is evaluated (grid, then the peak window)."""
        return self.times if self.peak_window is None else np.concatenate([self.times, self.peak_window])


@dataclass
class Run:
    case: str
    method: str
    tol: str  # rtol, or the fixed step
    wall: float  # [s], solve only (best of the repeats)
    rhs_calls: int
    steps: int
    err_p: float  # max relative error in p over the grid
    err_peak: float | None  # relative error in the peak pressure (None: peak is the initial state)
    note: str = ""
    extra: dict = field(default_factory=dict)


def machine() -> str:
    """One line describing this machine and the software versions."""
    import scipy

    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        import cantera

        ct = f", Cantera {cantera.__version__}"
    except ImportError:  # pragma: no cover - optional
        ct = ", Cantera not installed"
    try:
        import numba

        nb = f", numba {numba.__version__}"
    except ImportError:  # pragma: no cover - numba is a dependency
        nb = ", numba not installed"
    return (f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}, numpy {np.__version__}, "
            f"scipy {scipy.__version__}{nb}{ct}")


# ---------------------------------------------------------------------------------------------------------
# models and options


def options_for(model, method: str, rtol: float):
    """The model's solver options with another method and rtol; atol = rtol/100 × each unknown's scale.

    Mirrors ``cases.model.build`` (docs/scenes.md: absolute tolerances are atol, default rtol/100, times each unknown's
    scale); the scales are recovered from the options the scene was built with.
    """
    s = model.scene.solver
    scales = np.asarray(model.options.atol, dtype=float) / (s.atol or s.rtol / 100.0)
    return replace(model.options, method=method, rtol=rtol, atol=(rtol / 100.0) * scales)


def fresh_state(model) -> np.ndarray:
    """Initial unknowns; also puts the network back in its t = 0 discrete state."""
    net = model.network
    y0 = net.initial_state()
    if hasattr(net, "reset"):
        net.reset()
    return y0


def engine_rhs(model, y0):
    """The engine's compiled right-hand side as a Python callable f(t, y), in the t = 0 discrete state with no
    segment end (inputs read at t itself): what a loop outside the engine (fixed steps, one solve_ivp call
    without stops) integrates."""
    system = model.network.engine().solve_ivp_system(0.0)
    system.begin_segment(0.0, math.inf, y0)
    return system.rhs


def pressures(model, times, ys, cavity: int = 0) -> np.ndarray:
    """Pressure of ``cavity`` at ``times`` from the unknowns ``ys`` (len(times), n)."""
    net = model.network
    return np.array([net.states(t, y)[cavity].pressure for t, y in zip(times, ys)])


def best_of(fn, budget: float = 0.25, max_reps: int = 5, fast_reps: int = 30):
    """Call ``fn()`` until ``max_reps`` calls (``fast_reps`` when a call takes under 2 ms: sub-millisecond runs
    jitter by ±20 %) or ``budget`` seconds; (smallest wall time [s], last result)."""
    best, spent, reps, result = math.inf, 0.0, 0, None
    while reps < (fast_reps if best < 2e-3 else max_reps) and (reps == 0 or spent < budget):
        t0 = time.perf_counter()
        result = fn()
        dt = time.perf_counter() - t0
        best, spent, reps = min(best, dt), spent + dt, reps + 1
    return best, result


# ---------------------------------------------------------------------------------------------------------
# references


def load_case(name: str, *, reference_rtol: float = 1e-12) -> Case:
    """Build a case and its reference pressure (closed form, quadrature, or a converged run)."""
    scene = load_scene(CASE_FILES[name])
    model = build_model(scene)
    out_t = np.asarray(model.output_times, dtype=float)
    if name == "blowdown_choked":
        from tests import closed_forms as cf

        tau = cf.blowdown_tau(0.06, 1.0, 1e-4, GAMMA, R_N2, 300.0)
        p = np.array([cf.choked_adiabatic_pressure(t, 5e5, tau, GAMMA) for t in out_t])
        return Case(name, scene, model, out_t, p, None, reference="closed form (PHYSICS.md)")
    if name == "blowdown_isothermal":
        from tests import closed_forms as cf

        tau = cf.blowdown_tau(0.06, 1.0, 1e-4, GAMMA, R_N2, 300.0)
        p = np.array([cf.isothermal_choked_pressure(t, 5e5, tau) for t in out_t])
        return Case(name, scene, model, out_t, p, None, reference="closed form p0·exp(-t/τ)")
    if name == "blowdown_subsonic":
        from tests import closed_forms as cf

        times = np.linspace(0.0, scene.time.end, 121)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            p = np.array([cf.adiabatic_blowdown_pressure(t, 3e5, 300.0, 0.06, 1.0, 1e-4, GAMMA, R_N2, 1e5)
                          for t in times])
        return Case(name, scene, model, times, p, None, reference="quadrature of t(p) (121 times)")
    if name == "fill_constant":
        from tests import closed_forms as cf

        p = np.array([cf.fill_pressure(t, 1e5, GAMMA, R_N2, 0.5, 600.0, 0.06) for t in out_t])
        return Case(name, scene, model, out_t, p, float(p[-1]), reference="closed form p0 + γRṁT_in·t/V")
    if name == "compression_mesh":
        cav = model.network.cavities[0]
        V = np.array([cav.total_volume(t) for t in out_t])
        p = 1.2e5 * (V[0] / V) ** GAMMA
        return Case(name, scene, model, out_t, p, float(p.max()), reference="closed form p·V^γ = const")
    if name == "airbag_vented":
        return _converged_case(name, scene, model, out_t, reference_rtol)
    raise KeyError(name)


def _converged_case(name, scene, model, out_t, rtol):
    """Reference = the default integrator at ``rtol``, checked against Radau at the same rtol."""
    def solve(method):
        y0 = fresh_state(model)
        traj = integrate(model.network, y0, 0.0, scene.time.end, options_for(model, method, rtol))
        p = pressures(model, out_t, traj.sample(out_t))
        peak, t_peak = cavity_peaks(model, traj)[0]
        return traj, p, peak, t_peak

    traj, p, peak, t_peak = solve(scene.solver.method)
    _, p2, peak2, _ = solve("Radau")
    diff = float(np.max(np.abs(p2 / p - 1.0)))
    dpeak = abs(peak2 / peak - 1.0)
    dt = out_t[1] - out_t[0]
    window = np.linspace(max(0.0, t_peak - 2 * dt), min(scene.time.end, t_peak + 2 * dt), 201)
    p_window = pressures(model, window, traj.sample(window))
    return Case(name, scene, model, out_t, np.concatenate([p, p_window]), peak, peak_window=window,
                reference=f"{scene.solver.method} through ventsim's integrator at rtol {rtol:g}",
                reference_check=f"Radau at rtol {rtol:g} differs by {diff:.1e} in p (max), {dpeak:.1e} in peak",
                peak_time=t_peak, reference_rtol=rtol)


def errors(case: Case, p: np.ndarray) -> tuple[float, float | None]:
    """(max relative error in p over the grid, relative error in peak pressure) of pressures ``p`` on case.grid."""
    ref = case.p_ref
    p = np.asarray(p, dtype=float)
    if not np.all(np.isfinite(p)):
        return math.inf, (math.inf if case.peak_ref is not None else None)
    err_p = float(np.max(np.abs(p / ref - 1.0)))
    if case.peak_ref is None:
        return err_p, None
    if case.peak_window is None:  # the peak is on the grid (a table breakpoint or the end): its largest sample
        return err_p, abs(float(np.max(p)) / case.peak_ref - 1.0)
    return err_p, abs(_refined_max(case.grid, p) / case.peak_ref - 1.0)


def _refined_max(times, p) -> float:
    """Largest value of samples p(times), refined by the vertex of the parabola through the top three samples."""
    order = np.argsort(times, kind="stable")
    t, v = np.asarray(times)[order], np.asarray(p)[order]
    k = int(np.argmax(v))
    if 0 < k < len(v) - 1:
        t0, t1, t2 = t[k - 1:k + 2]
        f0, f1, f2 = v[k - 1:k + 2]
        if t1 - t0 == t2 - t1:  # equal spacing: the vertex value of the interpolating parabola
            denom = f0 - 2 * f1 + f2
            if denom < 0:
                return float(f1 - (f2 - f0) ** 2 / (8 * denom))
    return float(v[k])


# ---------------------------------------------------------------------------------------------------------
# runners


def warm_up(case: Case) -> None:
    """Run the case once through ventsim's default path (numba compilation or cache load, outside any timing)."""
    integrate(case.model.network, fresh_state(case.model), 0.0, case.t_end, options_for(case.model, "DOP853", 1e-6))


def run_ventsim(case: Case, method: str, rtol: float, label: str | None = None, with_output: bool = False,
                integrator: str = "compiled") -> Run:
    """ventsim's integrator (breakpoints, switch functions, dense output) with a scipy method.

    ``integrator``: SolverOptions.integrator ("compiled": DOP853 in one numba call; "scipy": solve_ivp steps the
    engine's kernels). ``extra["path"]`` says which ran.

    With ``with_output``, ``extra["wall_with_output"]`` is the wall time of the solve plus the history (every
    column of history.csv) at every time of the grid, built as ``ventsim run`` builds it (one compiled call).
    """
    model, grid = case.model, case.grid
    opts = replace(options_for(model, method, rtol), integrator=integrator)

    def solve():
        y0 = fresh_state(model)
        return integrate(model.network, y0, 0.0, case.t_end, opts)

    try:
        wall, traj = best_of(solve)
    except SolverError as exc:
        return Run(case.name, label or f"ventsim {method}", f"{rtol:.0e}", math.nan, 0, 0, math.inf, None,
                   note=f"failed: {exc}"[:120])
    extra = {"events": traj.stats["events"], "restarts": traj.stats["restarts"], "path": traj.path}
    if with_output:
        def solve_and_sample():  # the whole history at the grid, as ventsim run builds it (compiled read-back)
            tr = solve()
            return history_rows(model, tr, grid)

        extra["wall_with_output"], _ = best_of(solve_and_sample)
    p = pressures(model, grid, traj.sample(grid))
    err_p, err_peak = errors(case, p)
    st = traj.stats
    return Run(case.name, label or f"ventsim {method}", f"{rtol:.0e}", wall, st["rhs_calls"], st["steps"], err_p,
               err_peak, extra=extra)


def run_plain_scipy(case: Case, method: str, rtol: float) -> Run:
    """One solve_ivp call over the whole run on the engine's right-hand side: no stops, no switches."""
    model, grid = case.model, case.grid
    opts = options_for(model, method, rtol)

    def solve():
        y0 = fresh_state(model)
        return solve_ivp(engine_rhs(model, y0), (0.0, case.t_end), y0, method=method, rtol=rtol, atol=opts.atol,
                         dense_output=True)

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            wall, sol = best_of(solve)
    except (ArithmeticError, ValueError) as exc:
        return Run(case.name, f"scipy {method}", f"{rtol:.0e}", math.nan, 0, 0, math.inf, None,
                   note=f"failed: {exc}"[:120])
    if sol.status != 0:
        return Run(case.name, f"scipy {method}", f"{rtol:.0e}", wall, sol.nfev, len(sol.t) - 1, math.inf, None,
                   note=f"failed: {sol.message}"[:120])
    p = pressures(model, grid, sol.sol(grid).T)
    err_p, err_peak = errors(case, p)
    return Run(case.name, f"scipy {method}", f"{rtol:.0e}", wall, sol.nfev, len(sol.t) - 1, err_p, err_peak)


def cheapest(runs, target: float, key: str = "err_p"):
    """The fastest run whose error ``key`` is at most ``target`` (None if none reaches it)."""
    ok = [r for r in runs if getattr(r, key) is not None and getattr(r, key) <= target and math.isfinite(r.wall)]
    return min(ok, key=lambda r: r.wall) if ok else None


def fmt_err(e) -> str:
    if e is None or (isinstance(e, float) and math.isnan(e)):
        return "-"
    return "inf" if not math.isfinite(e) else f"{e:.1e}"


def format_table(runs, columns=("case", "method", "tol", "wall ms", "RHS", "steps", "max err p", "err peak")) -> str:
    rows = [columns]
    for r in runs:
        rows.append((r.case, r.method, r.tol, "-" if not math.isfinite(r.wall) else f"{r.wall * 1e3:.2f}",
                     str(r.rhs_calls), str(r.steps), fmt_err(r.err_p), fmt_err(r.err_peak))[:len(columns)]
                    + ((r.note,) if r.note else ()))
    widths = [max(len(row[i]) for row in rows if i < len(row)) for i in range(len(columns))]
    lines = []
    for k, row in enumerate(rows):
        cells = [c.ljust(w) if i < 2 else c.rjust(w) for i, (c, w) in enumerate(zip(row, widths))]
        lines.append("  ".join(cells) + (f"  {row[len(columns)]}" if len(row) > len(columns) else ""))
        if k == 0:
            lines.append("  ".join("-" * w for w in widths))
    return "\n".join(lines)
