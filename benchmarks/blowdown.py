"""Choked adiabatic blowdown: ventsim's default integrator against Cantera's ReactorNet, error vs wall time.

The case is cases/verification/blowdown_choked.toml: a rigid 60 L tank of constant-cp N2 (γ = 1.4) at
5 bar, 300 K, venting through a choked orifice Cd·A = 1e-4 m² into 1 bar for 0.5 s; it stays choked, so the
closed form p/p0 = [1 + (γ−1)/2 · t/τ]^(−2γ/(γ−1)) (tests/closed_forms.py) holds exactly.

ventsim runs twice: its default path (DOP853 compiled with numba, cavity.rk_compiled) and the same algorithm
through scipy's solve_ivp (SolverOptions.compiled = False). For every rtol from 1e-3 to 1e-12 the table gives:
the wall time of the solve (best of several runs; building
the model and evaluating the error are not timed); the same with the pressure at the scene's 501 output times
included (``ventsim run`` writes them to history.csv); the right-hand-side calls; and the largest relative
error in p on those times.

Cantera (optional) solves the same scene: an IdealGasReactor with the same constant-cp N2 (M = 0.0280134
kg/mol), a Valve whose pressure_function is ventsim's orifice law read from the reactor's phase; one
advance(t_end) for the solve, advance() to each output time for the error and the second timing. Its rows are
skipped when Cantera is not importable. The last lines compare the cheapest run of each that reaches 1e-6 and
1e-9 (ventsim's default against Cantera; ratio > 1: ventsim is slower), for both timings.

Requires: numpy, scipy; Cantera optional (pip install "ventsim[bench]").

Usage::

    python benchmarks/blowdown.py
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import _common as C  # noqa: E402
import _peers as P  # noqa: E402

RTOLS = tuple(10.0 ** -k for k in range(3, 13))
TARGETS = (1e-6, 1e-9)


def main() -> int:
    print(__doc__.split("\n")[0])
    print(f"machine: {C.machine()}")
    case = C.load_case("blowdown_choked")
    method = case.scene.solver.method
    print(f"case: {case.scene.path.relative_to(C.ROOT)}; reference: {case.reference}; "
          f"error on {len(case.times)} output times\n")
    C.warm_up(case)  # numba compilation or cache load, outside the timings (Cantera is warmed by its repeats)
    runs = [C.run_ventsim(case, method, rtol, label=f"ventsim ({method}, {i})", with_output=True, integrator=i)
            for i in ("compiled", "scipy") for rtol in RTOLS]
    if P.CANTERA is not None:
        runs += [P.run_cantera(case, rtol) for rtol in RTOLS]
    else:
        print("Cantera is not importable: its rows are skipped\n")
    print(table(runs))
    if P.CANTERA is None:
        return 0
    print()
    ours = [r for r in runs if r.method.startswith("ventsim") and "compiled" in r.method]
    theirs = [r for r in runs if r.method.startswith("Cantera")]
    for target in TARGETS:
        a, b = C.cheapest(ours, target), C.cheapest(theirs, target)
        if a is None or b is None:
            print(f"max error <= {target:.0e}: not reached by {'ventsim' if a is None else 'Cantera'}")
            continue
        a_out = min(r.extra["wall_with_output"] for r in ours if r.err_p <= target)
        b_out = min(r.extra["wall_with_output"] for r in theirs if r.err_p <= target)
        print(f"max error <= {target:.0e}: solve only: ventsim {a.wall * 1e3:.2f} ms (rtol {a.tol}, {a.rhs_calls} RHS)"
              f" vs Cantera {b.wall * 1e3:.2f} ms (rtol {b.tol}, {b.rhs_calls} RHS): ratio {a.wall / b.wall:.1f}; "
              f"with 501 outputs: {a_out * 1e3:.2f} vs {b_out * 1e3:.2f} ms: ratio {a_out / b_out:.1f}")
    return 0


def table(runs) -> str:
    head = ("method", "rtol", "wall ms", "with output ms", "RHS", "steps", "max err p")
    rows = [head]
    for r in runs:
        rows.append((r.method, r.tol, f"{r.wall * 1e3:.3f}", f"{r.extra.get('wall_with_output', math.nan) * 1e3:.3f}",
                     str(r.rhs_calls), str(r.steps), C.fmt_err(r.err_p)))
    widths = [max(len(row[i]) for row in rows) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in enumerate(zip(row, widths)))
             for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
