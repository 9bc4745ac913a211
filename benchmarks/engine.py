"""One engine against the previous one: every library case solved on the compiled path and on the Python
(``solve_ivp``) path at the same rtol, in the same run.

Timed is ``cases.run.runner.run`` (the integration and the history read-back; the model is built once, outside),
best of ``--repeat`` after a warm-up that pays for numba's loading. The error column is the compiled run's largest
relative difference from the Python run over every history column (scaled by the column's peak), so the ratio is
at equal results. Cases that do not lower run on the Python path only ("python" in the path column, no ratio).

``--ladder``: wall time against error instead, per case and per path, on the rtol ladder 1e-4 … 1e-10; the
error is the largest relative difference (as above) from a reference run at rtol 1e-12 with steps of at most
t_end/4000 (compiled where the case lowers), each time the fastest of ``--repeat`` runs.

Run: python benchmarks/engine.py [--repeat 5] [--cases airbag_impactor airbag_impactor_dynamic] [--ladder]
"""
import argparse
import time
from dataclasses import replace

import numpy as np

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.run.runner import run
from cases.scene.files import load_scene


def best(model, compiled: bool, repeat: int):
    m = replace(model, options=replace(model.options, compiled=compiled))
    results = run(m)  # warm-up
    wall = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        results = run(m)
        wall.append(time.perf_counter() - t0)
    return min(wall), results


def difference(a, b) -> float:
    """max over columns of max|a − b| / max|b| (a, b: history arrays of the same scene, rows by time)."""
    worst = 0.0
    for x, y in zip(np.asarray(a, float).T, np.asarray(b, float).T):
        scale = np.max(np.abs(y))
        if scale > 0.0:
            worst = max(worst, float(np.max(np.abs(x - y)) / scale))
    return worst


LADDER = (1e-4, 1e-6, 1e-8, 1e-10)


def ladder(names, repeat: int) -> None:
    """Wall time [s] and error against an rtol-1e-12 reference, per case, rtol and path."""
    print(f"{'case':<26} {'rtol':>7} {'compiled [s]':>12} {'error':>9} {'python [s]':>11} {'error':>9} {'ratio':>7}")
    for name in names:
        model = build_model(load_scene(HERE / CASES[name]))
        lowers = model.network.compiled_solver() is not None and model.options.method == "DOP853"
        at = lambda rtol: replace(model, options=replace(model.options, rtol=rtol))  # noqa: E731
        # rtol 1e-12 alone is not a safe reference: DOP853's error estimate can vanish by accident on one step,
        # which is then accepted ~1e4 times less accurate than asked (seen on bag_unfold); steps of at most
        # t_end/4000 make such a step short enough not to matter
        ref_options = replace(at(1e-12).options, compiled=lowers, max_step=model.scene.time.end / 4000)
        reference = run(replace(model, options=ref_options)).history
        for rtol in LADDER:
            slow, res = best(at(rtol), False, repeat)
            cells = ["-", "-"]
            if lowers:
                fast, fres = best(at(rtol), True, repeat)
                cells = [f"{fast:.4f}", f"{difference(fres.history, reference):.1e}"]
            ratio = f"{slow / fast:>6.1f}x" if lowers else "-"
            print(f"{name:<26} {rtol:>7.0e} {cells[0]:>12} {cells[1]:>9} {slow:>11.4f} "
                  f"{difference(res.history, reference):>9.1e} {ratio:>7}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--cases", nargs="+", default=list(CASES))
    ap.add_argument("--ladder", action="store_true", help="wall time against error on the rtol ladder")
    args = ap.parse_args()
    if args.ladder:
        return ladder(args.cases, args.repeat)
    print(f"{'case':<26} {'rtol':>7} {'path':>9} {'compiled [s]':>12} {'python [s]':>11} {'ratio':>7} "
          f"{'RHS calls':>10} {'difference':>10}")
    for name in args.cases:
        model = build_model(load_scene(HERE / CASES[name]))
        slow, ref = best(model, False, args.repeat)
        fast_ok = model.network.compiled_solver() is not None and model.options.method == "DOP853"
        if not fast_ok:
            print(f"{name:<26} {model.options.rtol:>7.0e} {'python':>9} {'-':>12} {slow:>11.4f} {'-':>7} "
                  f"{ref.summary['solver']['rhs_calls']:>10} {'-':>10}")
            continue
        fast, res = best(model, True, args.repeat)
        print(f"{name:<26} {model.options.rtol:>7.0e} {res.summary['solver']['path']:>9} {fast:>12.4f} "
              f"{slow:>11.4f} {slow / fast:>6.1f}x {res.summary['solver']['rhs_calls']:>10} "
              f"{difference(res.history, ref.history):>10.1e}")


if __name__ == "__main__":
    main()
