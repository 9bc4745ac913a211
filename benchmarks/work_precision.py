"""Work-precision of ventsim's integrator against scipy, fixed-step explicit schemes and Cantera.

Cases (cases/verification/*.toml and cases/airbag_vented.toml) and their references:

- blowdown_choked, blowdown_isothermal, fill_constant, compression_mesh: closed forms (../shared/PHYSICS.md);
- blowdown_subsonic: the quadrature of t(p) in tests/closed_forms.py at 121 times;
- airbag_vented: converged reference, the scene's integrator at rtol 1e-12, checked against Radau at 1e-12
  (the difference is printed; it bounds the reference's own error).

Methods, each over a ladder of tolerances (rtol 1e-3 ... 1e-12, atol = rtol/100 × each unknown's scale):

- ``ventsim M``: cavity.integration.integrate with scipy method M (DOP853 is the default): stops at table
  breakpoints, switch functions for choking and flow reversal located on the dense output;
- ``scipy M``: one plain solve_ivp call over the run on the same right-hand side (no stops, no switches);
- ``fixed Euler`` / ``fixed Heun``: forward Euler and Heun (2nd order) at fixed steps t_end/N, as explicit FE
  codes advance the gas with the structure's step (N up to 1e5, i.e. a 0.8 µs step for the 80 ms airbag);
- ``Cantera ReactorNet`` (optional): CVODES on the same gas and laws (blowdowns, fill, compression).

For each run: the wall time of the solve (best of a few; building the model and evaluating the error are not
timed), right-hand-side calls, steps, the largest relative error in the pressure on the evaluation grid (the
scene's output times), and the relative error in the peak pressure (when the peak is not the initial state;
for the airbag the peak is refined on a fine window around the reference peak time).

Prints the full table, a summary (the cheapest run of each method reaching 1e-6 and 1e-9) and the data behind the
recommended default; writes ``work_precision.png`` (error against wall time, log-log, one panel per case),
``work_precision.csv`` (every run) and ``summary.txt`` into ``--out``.

Requires: numpy, scipy, matplotlib; Cantera optional (pip install "ventsim[bench]").

Usage::

    python benchmarks/work_precision.py [--out out/benchmarks] [--quick] [--cases airbag_vented ...]
"""
from __future__ import annotations

import argparse
import csv
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402

import _common as C  # noqa: E402
import _peers as P  # noqa: E402

RTOLS = tuple(10.0 ** -k for k in range(3, 13))
QUICK_RTOLS = (1e-3, 1e-6, 1e-9)
EULER_STEPS = (100, 300, 1000, 3000, 10_000, 30_000, 100_000)
HEUN_STEPS = (100, 300, 1000, 3000, 10_000, 30_000)
COMPILED_STEPS = (100, 300, 1000, 3000, 10_000, 30_000, 100_000, 300_000, 1_000_000, 3_000_000)
QUICK_STEPS = (100, 1000)
QUICK_COMPILED_STEPS = (1000, 100_000, 1_000_000)
TARGETS = (1e-6, 1e-9)
DEFAULT = "ventsim DOP853"  # the default integrator: compiled DOP853
SCIPY_DOP853 = "ventsim DOP853 (scipy)"


def run_case(case, rtols, euler_steps, heun_steps, log, compiled_steps=COMPILED_STEPS) -> list:
    runs = []
    default = case.scene.solver.method
    methods = [default] + [m for m in C.SCIPY_METHODS if m != default]
    C.warm_up(case)
    for m in methods:
        for rtol in rtols:
            if case.reference_rtol is not None and m == default and rtol == case.reference_rtol:
                runs.append(C.Run(case.name, f"ventsim {m}", f"{rtol:.0e}", math.nan, 0, 0, math.nan, None,
                                  note="is the reference"))
                continue
            runs.append(C.run_ventsim(case, m, rtol, label=f"ventsim {m}"))
    runs += [C.run_ventsim(case, "DOP853", rtol, label=SCIPY_DOP853, integrator="scipy") for rtol in rtols]
    paths = sorted({r.extra.get("path", "?") for r in runs if r.method == DEFAULT and r.extra})
    log(f"  ventsim integrator done ({len(runs)} runs; default path: {', '.join(paths)})")
    for m in methods:
        for rtol in rtols:
            runs.append(C.run_plain_scipy(case, m, rtol))
    log("  plain solve_ivp done")
    runs += [P.run_fixed_step(case, n, "euler") for n in euler_steps]
    runs += [P.run_fixed_step(case, n, "heun") for n in heun_steps]
    runs += [P.run_fixed_compiled(case, n, "euler") for n in compiled_steps]
    runs += [P.run_fixed_compiled(case, n, "heun") for n in compiled_steps if n <= 1_000_000]
    log("  fixed steps done")
    if P.CANTERA is not None and case.name in P.CANTERA_CASES:
        runs += [P.run_cantera(case, rtol) for rtol in rtols]
        log("  Cantera done")
    return runs


def summary(cases, runs) -> str:
    """Per case and method: the cheapest run reaching each target (max error in p, and in the peak)."""
    lines = []
    methods = list(dict.fromkeys(r.method for r in runs))
    head = ["case", "method"] + [f"{k} <= {t:.0e}" for t in TARGETS for k in ("p", "peak")]
    rows = [head]
    for case in cases:
        mine = [r for r in runs if r.case == case.name]
        for m in methods:
            rm = [r for r in mine if r.method == m]
            if not rm:
                continue
            cells = [case.name, m]
            for t in TARGETS:
                for key in ("err_p", "err_peak"):
                    if case.peak_ref is None and key == "err_peak":
                        cells.append("-")
                        continue
                    best = C.cheapest(rm, t, key)
                    cells.append("not reached" if best is None else f"{best.wall * 1e3:.2f} ms @ {best.tol}")
            rows.append(cells)
    widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
    for k, r in enumerate(rows):
        lines.append("  ".join(c.ljust(w) if i < 2 else c.rjust(w) for i, (c, w) in enumerate(zip(r, widths))))
        if k == 0:
            lines.append("  ".join("-" * w for w in widths))
    return "\n".join(lines)


def _err(r) -> float:
    """The error a run is judged by: max relative error in p, and in the peak where there is one."""
    return max(r.err_p, r.err_peak if r.err_peak is not None else 0.0)


def _cheapest(runs, target):
    ok = [r for r in runs if math.isfinite(r.wall) and _err(r) <= target]
    return min(ok, key=lambda r: r.wall) if ok else None


def acceptance(runs) -> str:
    """Issue 6's acceptance figures from this run: the default against Cantera on the blowdown and fill cases,
    and against fixed-step explicit schemes on the airbag, each at equal error (max relative error in p and in
    the peak pressure <= target; the cheapest run of each method that reaches it)."""
    out = ["Default (compiled DOP853) against Cantera ReactorNet at equal error; ratio = ventsim / Cantera "
           "(<= 1: ventsim at least as fast):"]
    for name in ("blowdown_choked", "blowdown_isothermal", "blowdown_subsonic", "fill_constant"):
        mine = [r for r in runs if r.case == name]
        if not mine:
            out.append(f"  {name:20s} not run (--cases)")
            continue
        for target in TARGETS:
            a = _cheapest([r for r in mine if r.method == DEFAULT], target)
            b = _cheapest([r for r in mine if r.method == "Cantera ReactorNet"], target)
            if a is None or b is None:
                out.append(f"  {name:20s} <= {target:.0e}: not reached by "
                           f"{'ventsim' if a is None else 'Cantera (or Cantera not installed)'}")
                continue
            out.append(f"  {name:20s} <= {target:.0e}: ventsim {a.wall * 1e3:7.3f} ms (rtol {a.tol}, err "
                       f"{_err(a):.1e}) / Cantera {b.wall * 1e3:7.3f} ms (rtol {b.tol}, err {_err(b):.1e}) "
                       f"= {a.wall / b.wall:5.2f}")
    out.append("Default against fixed-step explicit schemes on airbag_vented at equal error in the peak pressure "
               "(fixed steps on the same compiled right-hand side, in a compiled and in a Python loop); ratio = fixed / ventsim "
               "(>= 100 required):")
    mine = [r for r in runs if r.case == "airbag_vented" and r.err_peak is not None]
    for target in TARGETS if mine else ():
        a = C.cheapest([r for r in mine if r.method == DEFAULT], target, "err_peak")
        for m in ("fixed Euler (compiled)", "fixed Heun (compiled)", "fixed Euler", "fixed Heun"):
            b = C.cheapest([r for r in mine if r.method == m], target, "err_peak")
            if a is None or b is None:
                best = min((r for r in mine if r.method == m), key=lambda r: r.err_peak, default=None)
                got = "" if best is None else f" (best: {best.err_peak:.1e} at {best.tol}, {best.wall:.2f} s)"
                out.append(f"  peak <= {target:.0e}: {m} not reached{got}")
                continue
            out.append(f"  peak <= {target:.0e}: {m} {b.wall * 1e3:8.1f} ms ({b.tol}, err {b.err_peak:.1e}) / "
                       f"ventsim {a.wall * 1e3:.3f} ms (rtol {a.tol}, err {a.err_peak:.1e}) = {b.wall / a.wall:6.0f}x")
    return "\n".join(out)


def recommendation_data(cases, runs) -> str:
    """What the recommendation rests on: per candidate (ventsim's integrator with each method), its cost to reach
    a target relative to the fastest candidate of each case, and the largest rtol whose errors (p and peak) stay
    within a target on every case. Plain solve_ivp, fixed steps and Cantera are references, not candidates."""
    out = []
    methods = [m for m in dict.fromkeys(r.method for r in runs) if m.startswith("ventsim")]
    for target in TARGETS:
        out.append(f"cost to reach max error in p <= {target:.0e}, relative to the fastest candidate of each case "
                   f"(geometric mean and worst over the cases; 1.00 = always the fastest):")
        ratios = {m: [] for m in methods}
        missing = {m: [] for m in methods}
        for case in cases:
            mine = [r for r in runs if r.case == case.name and r.method in methods]
            best_any = C.cheapest(mine, target)
            for m in methods:
                b = C.cheapest([r for r in mine if r.method == m], target)
                if b is None or best_any is None:
                    missing[m].append(case.name)
                else:
                    ratios[m].append(b.wall / best_any.wall)

        def mean(m):
            return float(np.exp(np.mean(np.log(ratios[m])))) if ratios[m] else math.inf

        for m in sorted(methods, key=lambda m: (len(missing[m]), mean(m))):
            worst = max(ratios[m]) if ratios[m] else math.nan
            miss = f"; not reached on {', '.join(missing[m])}" if missing[m] else ""
            out.append(f"  {m:16s} mean x{mean(m):5.2f}  worst x{worst:5.2f}{miss}")
    out.append("")
    for m in methods:
        for target in TARGETS:
            ok = []
            for rtol_s in dict.fromkeys(r.tol for r in runs if r.method == m):
                sel = [r for r in runs if r.method == m and r.tol == rtol_s and r.note != "is the reference"]
                worst_p = max(r.err_p for r in sel)
                worst_peak = max((r.err_peak for r in sel if r.err_peak is not None), default=0.0)
                if len(sel) == len(cases) and max(worst_p, worst_peak) <= target:
                    ok.append((float(rtol_s), sum(r.wall for r in sel), max(worst_p, worst_peak)))
            if ok:
                rtol, wall, worst = max(ok)
                out.append(f"  {m}: largest rtol with max error in p and peak <= {target:.0e} on every case: "
                           f"{rtol:.0e} (worst error {worst:.1e}; all cases together {wall * 1e3:.1f} ms)")
            else:
                out.append(f"  {m}: no rtol reaches {target:.0e} on every case")
    default = cases[0].scene.solver.method if cases else "DOP853"
    for rtol_s in dict.fromkeys(r.tol for r in runs if r.method == f"ventsim {default}"):
        sel = [r for r in runs if r.method == f"ventsim {default}" and r.tol == rtol_s and r.note != "is the reference"]
        worst = max(max(r.err_p, r.err_peak or 0.0) for r in sel)
        per_case = ", ".join(f"{r.case} {r.wall * 1e3:.1f} ms" for r in sel)
        out.append(f"  ventsim {default} rtol {rtol_s}: worst error {worst:.1e}; {per_case}")
    return "\n".join(out)


def plot(cases, runs, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colors = {"DOP853": "tab:blue", "RK45": "tab:orange", "LSODA": "tab:green", "Radau": "tab:red",
              "BDF": "tab:purple", "Euler": "0.45", "Heun": "tab:brown", "ReactorNet": "black",
              "(scipy)": "tab:cyan"}
    ncol = 3
    nrow = math.ceil(len(cases) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.2 * ncol, 4.2 * nrow), squeeze=False)
    for ax, case in zip(axes.flat, cases):
        mine = [r for r in runs if r.case == case.name]
        for m in dict.fromkeys(r.method for r in mine):
            pts = [(r.wall, max(r.err_p, 1e-16)) for r in mine  # in tolerance order
                   if r.method == m and math.isfinite(r.wall) and math.isfinite(r.err_p)]
            if not pts:
                continue
            key = m.split()[1] if m.endswith("(compiled)") else m.split()[-1]
            style = "-" if m.startswith("ventsim") else "--" if m.startswith("scipy") else ":"
            marker = ("o" if m.startswith("ventsim") else "x" if m.startswith("scipy")
                      else "^" if m.endswith("(compiled)") else "s")
            lw = 2.2 if m == f"ventsim {case.scene.solver.method}" else 1.0
            ax.loglog(*zip(*pts), style, marker=marker, ms=3.5, lw=lw, color=colors.get(key, "k"), label=m)
        ax.set_title(f"{case.name}", fontsize=10)
        ax.set_xlabel("wall time of the solve [s]")
        ax.set_ylabel("max relative error in p [-]")
        ax.grid(True, which="major", alpha=0.3)
        ax.axhline(1e-6, color="0.7", lw=0.8)
    for ax in list(axes.flat)[len(cases):]:
        ax.axis("off")
    handles, labels = [], []
    for ax in axes.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="lower center", ncol=6, fontsize=8, frameon=False)
    fig.suptitle("ventsim work-precision: error against wall time (solid: ventsim integrator, thick: the default; "
                 "dashed: plain solve_ivp; dotted: fixed step (triangles: on the compiled RHS) / Cantera)",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 0.96))
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp.png")
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    tmp.replace(path)


def write_csv(runs, path: Path) -> None:
    tmp = path.with_suffix(".tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "method", "tolerance", "wall [s]", "rhs calls", "steps", "max rel error p [-]",
                    "rel error peak [-]", "note"])
        for r in runs:
            w.writerow([r.case, r.method, r.tol, f"{r.wall:.6g}", r.rhs_calls, r.steps, f"{r.err_p:.6g}",
                        "" if r.err_peak is None else f"{r.err_peak:.6g}", r.note])
    tmp.replace(path)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="out/benchmarks", help="folder for the PNG, CSV and summary")
    ap.add_argument("--quick", action="store_true", help="three tolerances, two fixed steps (a smoke test)")
    ap.add_argument("--cases", nargs="*", default=list(C.CASE_FILES), choices=list(C.CASE_FILES))
    args = ap.parse_args(argv)
    out = Path(args.out)
    rtols = QUICK_RTOLS if args.quick else RTOLS
    euler = QUICK_STEPS if args.quick else EULER_STEPS
    heun = QUICK_STEPS if args.quick else HEUN_STEPS

    start = time.perf_counter()

    def log(msg):
        print(f"[{time.perf_counter() - start:6.1f} s] {msg}", file=sys.stderr, flush=True)

    header = [__doc__.split("\n")[0], f"machine: {C.machine()}",
              f"command: python benchmarks/work_precision.py{' --quick' if args.quick else ''} --out {args.out}"]
    print("\n".join(header))
    cases, runs = [], []
    for name in args.cases:
        log(f"{name}: reference")
        case = C.load_case(name)
        cases.append(case)
        print(f"\n{name}: reference = {case.reference}" + (f"; {case.reference_check}" if case.reference_check
                                                           else ""))
        runs += run_case(case, rtols, euler, heun, log, QUICK_COMPILED_STEPS if args.quick else COMPILED_STEPS)
    print()
    print(C.format_table(runs))
    text = ["", "Cheapest run reaching each target (wall time of the solve @ tolerance):", summary(cases, runs), "",
            acceptance(runs), "", "Data for the recommended default:", recommendation_data(cases, runs)]
    print("\n".join(text))
    out.mkdir(parents=True, exist_ok=True)
    write_csv(runs, out / "work_precision.csv")
    (out / "summary.txt").write_text("\n".join(header + text) + "\n")
    plot(cases, runs, out / "work_precision.png")
    log(f"wrote {out / 'work_precision.png'}, {out / 'work_precision.csv'}, {out / 'summary.txt'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
