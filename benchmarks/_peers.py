"""The peers of the integrator benchmarks: fixed-step explicit schemes (a Python loop and a compiled loop over the
engine's right-hand side) and
Cantera's ``ReactorNet``; each runner returns a :class:`_common.Run` like the ventsim runners of :mod:`_common`.

- :func:`run_fixed_step`: forward Euler or Heun at a fixed step, as explicit finite-element codes advance the gas
  with the structure's step (benchmark-only code; no error control), a Python loop calling the engine's compiled
  right-hand side; :func:`run_fixed_compiled` the same loop compiled (the fair baseline).
- :func:`run_cantera`: Cantera's ``ReactorNet`` (CVODES BDF) with a constant-cp N2 phase identical to the scenes'
  (custom element weight so that M = 0.0280134 kg/mol), a ``Valve`` whose ``pressure_function`` is the orifice
  law read from the upstream reactor, a ``MassFlowController`` for the inflator, a moving ``Wall`` for the volume
  history. Optional: :data:`CANTERA` is None when Cantera is not importable.
"""
from __future__ import annotations

import math
import time

import numpy as np

from _common import Case, Run, best_of, engine_rhs, errors, fresh_state, pressures
from exchange.laws.orifice import orifice_mass_flow

try:  # Cantera is a peer for benchmarks, not a dependency
    import cantera as CANTERA
except ImportError:  # pragma: no cover - optional
    CANTERA = None


def fixed_step(rhs, y0, t_end: float, n_steps: int, scheme: str = "euler") -> tuple[np.ndarray, np.ndarray]:
    """Integrate with ``n_steps`` equal steps of forward Euler or Heun (explicit trapezoidal, order 2).

    Returns (times (n+1,), states (n+1, len(y0))). No error control: the step is the user's (an explicit FE code
    uses its structural step, ~1 µs). Non-finite states stop the loop (the rest is NaN).
    """
    h = t_end / n_steps
    ys = np.full((n_steps + 1, len(y0)), np.nan)
    ys[0] = y = np.array(y0, dtype=float)
    for i in range(n_steps):
        t = i * h
        if scheme == "euler":
            y = y + h * rhs(t, y)
        else:
            k1 = rhs(t, y)
            k2 = rhs(t + h, y + h * k1)
            y = y + 0.5 * h * (k1 + k2)
        if not np.all(np.isfinite(y)):
            break
        ys[i + 1] = y
    return np.linspace(0.0, t_end, n_steps + 1), ys


def run_fixed_compiled(case: Case, n_steps: int, scheme: str = "euler") -> Run:
    """Forward Euler or Heun at t_end/n_steps on the compiled right-hand side (the one the default path uses):
    the fair fixed-step baseline. States on the grid by linear interpolation between steps, inside the loop."""
    from _fixed_compiled import fixed_step_compiled

    fast = case.model.network.compiled_solver()
    name = f"fixed {'Euler' if scheme == 'euler' else 'Heun'} (compiled)"
    dt = case.t_end / n_steps
    if fast is None:
        return Run(case.name, name, f"dt {dt:.1e}", math.nan, 0, 0, math.inf, None, note="not lowerable")
    order = np.argsort(case.grid, kind="stable")
    grid = case.grid[order]

    def solve():
        fast.arrays.temperature_guess[:] = fast.T_initial
        return fixed_step_compiled(fast.model, fresh_state(case.model), case.t_end, n_steps, scheme == "heun", grid)

    solve()  # compile outside the timing
    wall, yg = best_of(solve, budget=0.0 if n_steps > 20_000 else 0.25, max_reps=3)
    calls = n_steps * (1 if scheme == "euler" else 2)
    if not np.all(np.isfinite(yg)):
        return Run(case.name, name, f"dt {dt:.1e}", wall, calls, n_steps, math.inf, None, note="unstable")
    ys = np.empty_like(yg)
    ys[order] = yg
    err_p, err_peak = errors(case, pressures(case.model, case.grid, ys))
    return Run(case.name, name, f"dt {dt:.1e}", wall, calls, n_steps, err_p, err_peak)


def run_fixed_step(case: Case, n_steps: int, scheme: str = "euler") -> Run:
    """:func:`fixed_step` on the engine's right-hand side; states between steps by linear interpolation (below the
    scheme's error)."""
    model, grid = case.model, case.grid
    calls = n_steps * (1 if scheme == "euler" else 2)

    def solve():
        y0 = fresh_state(model)
        try:
            with np.errstate(all="ignore"):
                return fixed_step(engine_rhs(model, y0), y0, case.t_end, n_steps, scheme)
        except (ArithmeticError, ValueError) as exc:
            return exc

    wall, out = best_of(solve, budget=0.0 if n_steps > 2000 else 0.25, max_reps=3)
    name = "fixed Euler" if scheme == "euler" else "fixed Heun"
    dt = case.t_end / n_steps
    if isinstance(out, Exception) or not np.all(np.isfinite(out[1])):
        return Run(case.name, name, f"dt {dt:.1e}", wall, calls, n_steps, math.inf, None, note="unstable")
    ts, ys = out
    yg = np.column_stack([np.interp(grid, ts, ys[:, j]) for j in range(ys.shape[1])])
    try:
        p = pressures(model, grid, yg)
    except (ArithmeticError, ValueError):
        return Run(case.name, name, f"dt {dt:.1e}", wall, calls, n_steps, math.inf, None, note="unstable")
    err_p, err_peak = errors(case, p)
    return Run(case.name, name, f"dt {dt:.1e}", wall, calls, n_steps, err_p, err_peak)


# ---------------------------------------------------------------------------------------------------------
# Cantera

#: Constant-cp N2 exactly as in the scenes. The element weight is set so that M = 0.0280134 kg/mol (Cantera's
#: default N weight gives 0.028014, a 2e-5 offset in R). Reactors are built with clone=False from their own
#: Solution: clone=True rebuilds the phase with the default element weights (measured: p0 off by 2.1e-5).
CANTERA_N2_YAML = """
elements:
- symbol: N
  atomic-weight: 14.0067
phases:
- name: gas
  thermo: ideal-gas
  elements: [{elements: [N]}]
  species: [N2]
  state: {T: 300.0, P: 1.0e5}
species:
- name: N2
  composition: {N: 2}
  thermo: {model: constant-cp, T0: 300.0, h0: 0.0, s0: 0.0, cp0: 29100.619163}
"""

#: Cases Cantera can express with its stock objects.
CANTERA_CASES = ("blowdown_choked", "blowdown_isothermal", "blowdown_subsonic", "fill_constant", "compression_mesh")


def _ct_gas(T, P):
    g = CANTERA.Solution(yaml=CANTERA_N2_YAML)
    g.TP = T, P
    return g


def cantera_network(case_name: str, model=None):
    """(ReactorNet, reactor, objects to keep alive) for a case: see the module docstring."""
    ct = CANTERA
    if case_name.startswith("blowdown"):
        p0 = 3.0e5 if case_name == "blowdown_subsonic" else 5.0e5
        r = ct.IdealGasReactor(_ct_gas(300.0, p0), clone=False)
        r.volume = 0.06
        if case_name == "blowdown_isothermal":
            r.energy_enabled = False
        env = ct.Reservoir(_ct_gas(300.0, 1.0e5), clone=False)
        valve = ct.Valve(r, env)
        phase = r.phase
        R = ct.gas_constant / phase.mean_molecular_weight
        gamma = phase.cp_mass / phase.cv_mass

        def orifice(dp, phase=phase):  # Cd·A = 1e-4 m^2, into 1 bar; dp unused: the law needs p_up and T_up
            return orifice_mass_flow(phase.P, phase.T, 1.0e5, R, gamma, 1.0e-4, 1.0)

        valve.pressure_function = orifice
        return ct.ReactorNet([r]), r, (valve, env, orifice)
    if case_name == "fill_constant":
        r = ct.IdealGasReactor(_ct_gas(300.0, 1.0e5), clone=False)
        r.volume = 0.06
        inlet = ct.Reservoir(_ct_gas(600.0, 1.0e5), clone=False)
        mfc = ct.MassFlowController(inlet, r, mdot=0.5)
        return ct.ReactorNet([r]), r, (mfc, inlet)
    if case_name == "compression_mesh":
        vol = model.network.cavities[0].volume
        r = ct.IdealGasReactor(_ct_gas(300.0, 1.2e5), clone=False)
        r.volume = vol(0.0)
        env = ct.Reservoir(_ct_gas(300.0, 1.0e5), clone=False)
        wall = ct.Wall(r, env, A=1.0, velocity=lambda t: vol.rate(t))  # dV/dt of the left reactor = A·v
        return ct.ReactorNet([r]), r, (wall, env)
    raise KeyError(case_name)


def run_cantera(case: Case, rtol: float) -> Run:
    """Cantera ReactorNet at rtol (atol left at Cantera's default 1e-15).

    ``wall``: one ``advance(t_end)`` (the solve alone, like the other runners). The error comes from a second
    run that advances to every time of the grid and reads the pressure (CVODES interpolates); its wall time,
    outputs included, is ``extra["wall_with_output"]``. RHS calls count the finite-difference Jacobian's too.
    """
    grid = np.sort(case.grid)
    order = np.argsort(case.grid, kind="stable")

    def solve_only():
        net, r, _keep = cantera_network(case.name, case.model)
        net.rtol = rtol
        t0 = time.perf_counter()
        net.advance(case.t_end)
        return time.perf_counter() - t0, net.solver_stats

    def with_output():
        net, r, _keep = cantera_network(case.name, case.model)
        net.rtol = rtol
        phase = r.phase
        out = np.empty(len(grid))
        t0 = time.perf_counter()
        for i, t in enumerate(grid):
            if t > 0.0:
                net.advance(t)
            out[i] = phase.P
        return time.perf_counter() - t0, out

    wall = min(solve_only()[0] for _ in range(30))  # as many repeats as the sub-millisecond ventsim runs
    _, stats = solve_only()
    wall_out, out = min((with_output() for _ in range(3)), key=lambda r: r[0])
    p = np.empty(len(grid))
    p[order] = out
    err_p, err_peak = errors(case, p)
    calls = stats.get("rhs_evals", 0) + stats.get("lin_rhs_evals", 0)
    return Run(case.name, "Cantera ReactorNet", f"{rtol:.0e}", wall, calls, stats.get("steps", 0), err_p, err_peak,
               extra={"wall_with_output": wall_out})


# ---------------------------------------------------------------------------------------------------------
# tables
