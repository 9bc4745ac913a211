"""One engine against the previous one: every library case on this engine and on the previous Python engine, at
the same rtol, in the same run.

This engine: the compiled DOP853 (the default) and scipy's DOP853 stepping the same compiled kernels
(``integrator = "scipy"``). The previous engine, the Python right-hand side that ran every scene with bodies before
issue 16, is not on main any more: it is measured from the last commit that had it (``--baseline``, default
c378c91), exported with ``git archive`` into a temporary folder and run there in a child process
(``compiled=False``, its own code and numba cache; its first run compiles the laws it calls, outside the timings).
``--no-baseline`` skips it.

Timed is ``cases.run.runner.run`` (the integration and the history read-back; the model is built once, outside),
best of ``--repeat`` after a warm-up. "difference": the largest relative difference of the scipy-integrator run
and of the previous engine's run from the compiled run over every history column (scaled by the column's peak).

``--ladder``: wall time against error instead, per case and engine, on the rtol ladder 1e-4 … 1e-10 (absolute
tolerances scaled with rtol, as a scene's defaults are); the error is the largest relative difference (as above)
from this engine's run at rtol 1e-12 with steps of at most t_end/4000.

Run: python benchmarks/engine.py [--repeat 5] [--cases airbag_impactor airbag_impactor_dynamic] [--ladder]
     [--baseline REV | --no-baseline]
"""
import argparse
import json
import os
import subprocess
import sys
import tarfile
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.run.runner import run
from cases.scene.files import load_scene

ROOT = Path(__file__).resolve().parents[1]
BASELINE = "c378c91"  # the last commit with the Python right-hand side (compiled=False)
LADDER = (1e-4, 1e-6, 1e-8, 1e-10)

#: run in the previous engine's tree: best wall time and history of each case on its Python path, as JSON
PREVIOUS = r"""
import json, sys, time
from dataclasses import replace
from cases.model.build import build_model
from cases.run.library import CASES, HERE
from cases.run.runner import run
from cases.scene.files import load_scene
repeat, rtols, out = int(sys.argv[1]), json.loads(sys.argv[2]), {}
for name in sys.argv[3:]:
    model, out[name] = build_model(load_scene(HERE / CASES[name])), {}
    for rtol in rtols or [model.options.rtol]:
        o = model.options
        m = replace(model, options=replace(o, rtol=rtol, atol=o.atol * rtol / o.rtol, compiled=False))
        r, best = run(m), float("inf")
        for _ in range(repeat):
            t0 = time.perf_counter(); r = run(m); best = min(best, time.perf_counter() - t0)
        out[name][repr(rtol)] = {"wall": best, "path": r.summary["solver"]["path"],
                                 "rhs": r.summary["solver"]["rhs_calls"], "history": r.history.tolist()}
print(json.dumps(out))
"""


def best(model, repeat: int, **options):
    m = replace(model, options=replace(model.options, **options))
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


def previous_engine(rev: str, names, repeat: int, rtols=()) -> dict:
    """{case: {repr(rtol): {"wall", "path", "rhs", "history"}}} of the previous engine at ``rev`` (see the module
    docstring), at each of ``rtols`` (none: the scene's own)."""
    with tempfile.TemporaryDirectory(prefix="ventsim-previous-") as tmp:
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", "--format=tar", rev], capture_output=True,
                                 check=True).stdout
        tar_path = Path(tmp) / "tree.tar"
        tar_path.write_bytes(archive)
        with tarfile.open(tar_path) as tar:
            tar.extractall(tmp, filter="data")
        out = subprocess.run([sys.executable, "-c", PREVIOUS, str(repeat), json.dumps(list(rtols)), *names], cwd=tmp,
                             env={**os.environ, "PYTHONPATH": tmp}, capture_output=True, text=True,
                             check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def ladder(names, repeat: int, previous: dict) -> None:
    """Wall time [s] and error against an rtol-1e-12 reference, per case, rtol and engine."""
    print(f"{'case':<26} {'rtol':>7} {'compiled [s]':>12} {'error':>9} {'scipy [s]':>10} {'error':>9} "
          f"{'previous [s]':>12} {'error':>9} {'speed-up':>8}")
    for name in names:
        model = build_model(load_scene(HERE / CASES[name]))
        o = model.options  # absolute tolerances scale with rtol, as a scene's defaults do (atol = rtol/100 × scale)
        at = lambda rtol: replace(model, options=replace(o, rtol=rtol, atol=o.atol * rtol / o.rtol))  # noqa: E731
        # rtol 1e-12 alone is not a safe reference: DOP853's error estimate can vanish by accident on one step,
        # which is then accepted ~1e4 times less accurate than asked (seen on bag_unfold); steps of at most
        # t_end/4000 make such a step short enough not to matter
        reference = run(replace(model, options=replace(at(1e-12).options, max_step=model.scene.time.end / 4000)))
        for rtol in LADDER:
            fast, fres = best(at(rtol), repeat)
            slow, sres = best(at(rtol), repeat, integrator="scipy")
            prev = previous.get(name, {}).get(repr(rtol))
            cells = ["-", "-", "-"] if prev is None else [
                f"{prev['wall']:.4f}", f"{difference(prev['history'], reference.history):.1e}",
                f"{prev['wall'] / fast:.1f}x"]
            print(f"{name:<26} {rtol:>7.0e} {fast:>12.4f} {difference(fres.history, reference.history):>9.1e} "
                  f"{slow:>10.4f} {difference(sres.history, reference.history):>9.1e} {cells[0]:>12} {cells[1]:>9} "
                  f"{cells[2]:>8}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--cases", nargs="+", default=list(CASES))
    ap.add_argument("--ladder", action="store_true", help="wall time against error on the rtol ladder")
    ap.add_argument("--baseline", default=BASELINE, help="git revision of the previous engine")
    ap.add_argument("--no-baseline", action="store_true", help="skip the previous engine")
    args = ap.parse_args()
    rtols = LADDER if args.ladder else ()
    previous = {} if args.no_baseline else previous_engine(args.baseline, args.cases, args.repeat, rtols)
    print(f"previous engine: {'skipped' if args.no_baseline else args.baseline + ' (Python right-hand side)'}")
    if args.ladder:
        return ladder(args.cases, args.repeat, previous)
    print(f"{'case':<26} {'rtol':>7} {'compiled [s]':>12} {'scipy [s]':>10} {'previous [s]':>12} {'speed-up':>8} "
          f"{'RHS calls':>10} {'diff scipy':>10} {'diff prev':>10}")
    for name in args.cases:
        model = build_model(load_scene(HERE / CASES[name]))
        fast, res = best(model, args.repeat)
        slow, sres = best(model, args.repeat, integrator="scipy")
        prev = next(iter(previous.get(name, {}).values()), None)
        cells = ["-", "-", "-"] if prev is None else [
            f"{prev['wall']:.4f}", f"{prev['wall'] / fast:.1f}x", f"{difference(prev['history'], res.history):.1e}"]
        print(f"{name:<26} {model.options.rtol:>7.0e} {fast:>12.4f} {slow:>10.4f} {cells[0]:>12} {cells[1]:>8} "
              f"{res.summary['solver']['rhs_calls']:>10} {difference(sres.history, res.history):>10.1e} "
              f"{cells[2]:>10}")


if __name__ == "__main__":
    main()
