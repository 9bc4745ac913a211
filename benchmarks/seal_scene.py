"""The flange scene with a fine seal ring: CPU seconds to build (the seal's conductance curve) and to run 1 s of
physical time on the engine, by the ring's node count.

The scene is cases/seal_flange.toml with its gasket face replaced by a structured ring of quads (r = 40..50 mm) of
the node counts below, and ``time.end`` = 1 s (filled until the seal leaks and the flange lifts). The engine's
kernels are compiled and cached first (one run of the library scene, not counted). Figures are CPU seconds of this
process (``time.process_time``): "build" is ``build_model`` (mesh, seat rays, seal film and conductance curve),
"run" the integration with its history, contact and seal outputs (of which the integration alone), "picture"
the gap picture.

``--figures DIR`` also runs the library scene and draws its history (``seal_flange.png``: vessel pressure with
p_onset and p_lift, leak rate, minimum and mean channel height, contact-area fraction) and its gap picture at the
largest leak (``seal_flange_gap.png``), and prints the onset pressure against the formula.

``--compare-solver`` also builds each curve factorising every solve afresh (SuperLU's ordering, default
supernodes, no reused field) and prints how far the two curves differ.

``--no-reuse`` factorises every Reynolds solve (the cost of a seal whose gap field changes shape with the load).

Run: python benchmarks/seal_scene.py [--nodes 480 5120 20480] [--seal-rtol 1e-4] [--no-merge] [--no-reuse]
[--compare-solver] [--figures DIR]
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from cases.model.build import build_model  # noqa: E402
from cases.model.build_seal import seal_models  # noqa: E402
from cases.run.runner import run  # noqa: E402
from cases.scene.files import load_scene  # noqa: E402
from exchange.seal.meshes import annulus_mesh  # noqa: E402

#: (radial element rows, elements around) for a node count
SHAPES = {480: (4, 96), 5120: (9, 512), 20480: (19, 1024)}


def ring_file(folder: Path, nodes: int) -> Path:
    rows, around = SHAPES[nodes]
    v, f = annulus_mesh(0.04, 0.05, rows, around)
    path = folder / f"ring_{nodes}.obj"
    lines = ["v %r %r %r" % tuple(map(float, x)) for x in v] + ["f %d %d %d %d" % tuple(q + 1) for q in f]
    path.write_text("\n".join(lines) + "\n")
    return path


def figures(folder: Path) -> None:
    """The library scene's history and gap picture into ``folder``; prints its onset against the formula."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from cases.results.seal_outputs import write_seal_pictures
    from exchange.seal.flange import leak_onset_pressure, lift_off_pressure

    model = build_model(load_scene(ROOT / "cases" / "seal_flange.toml"))
    results = run(model)
    body, contact = model.scene.body[0], model.network.contact
    p_c = seal_models(model)[0].law.setup.gap.closing_pressure()
    onset = leak_onset_pressure(body.spring_preload, contact.seat_area, body.pressure_area, p_c)
    lift = lift_off_pressure(body.spring_preload, body.pressure_area)
    t_open = next(t for t, label in results.trajectory.events if label == "seal:kink0")
    p_open = model.network.states(t_open, results.trajectory(t_open))[0].pressure
    print(f"onset: run {p_open:.2f} Pa at t = {t_open:.6f} s, formula {onset:.2f} Pa "
          f"({p_open / onset - 1:+.2e}); lift-off formula {lift:.2f} Pa")
    t = results.history[:, 0]
    fig, ax = plt.subplots(4, 1, figsize=(7, 8), sharex=True)
    ax[0].plot(t, results.column("vessel.pressure") / 1e6, color="k")
    for p, label in ((onset, "p_onset"), (lift, "p_lift")):
        ax[0].axhline(p / 1e6, ls="--", lw=0.8, color="tab:red")
        ax[0].text(0.02, p / 1e6, label, va="bottom", fontsize=8, color="tab:red")
    ax[0].set_ylabel("vessel p [MPa]")
    ax[1].semilogy(t, np.maximum(results.column("seal.mass_flow") * 1e3, 1e-12))
    ax[1].set_ylabel("leak [g/s]")
    ax[1].set_ylim(1e-8, None)
    ax[2].plot(t, results.column("seal.min_gap") * 1e6, label="min")
    ax[2].plot(t, results.column("seal.mean_gap") * 1e6, "--", label="mean")
    ax[2].set_ylabel("channel h [µm]")
    ax[2].legend(fontsize=8)
    ax[3].plot(t, results.column("seal.contact_fraction"))
    ax[3].set_ylabel("contact fraction")
    ax[3].set_xlabel("time [s]")
    fig.suptitle("seal_flange: filled until the seal leaks and the flange lifts, then vented", fontsize=10)
    fig.tight_layout()
    fig.savefig(folder / "seal_flange.png", dpi=90)
    (picture,) = write_seal_pictures(results, folder)
    picture.replace(folder / "seal_flange_gap.png")


def measure(nodes: int, folder: Path, rtol: float) -> dict:
    from cases.results.seal_outputs import write_seal_pictures

    scene = load_scene(ROOT / "cases" / "seal_flange.toml")
    seal = replace(scene.exchange[0], leakage_surface=str(ring_file(folder, nodes)), seal_rtol=rtol)
    scene = replace(scene, exchange=(seal,) + scene.exchange[1:], time=replace(scene.time, end=1.0))
    import cases.run.runner as runner

    spent = []

    def timed(*args, **kwargs):  # the integration's own CPU
        begin = time.process_time()
        out = integrate(*args, **kwargs)
        spent.append(time.process_time() - begin)
        return out

    import exchange.seal.reynolds as reynolds
    factorised = []

    def counted(*args):  # the direct solves (the others reused a neighbouring field)
        factorised.append(1)
        return solve(*args)

    integrate, runner.integrate = runner.integrate, timed
    solve, reynolds._solve = reynolds._solve, counted
    start = time.process_time()
    model = build_model(scene)
    built = time.process_time()
    reynolds._solve = solve
    results = run(model)
    ran = time.process_time()
    write_seal_pictures(results, folder)
    drawn = time.process_time()
    runner.integrate = integrate
    curve = seal_models(model)[0].law.curve
    events = [label for _, label in results.trajectory.events if label.startswith("seal:")]
    return {"nodes": nodes, "build": built - start, "run": ran - built, "picture": drawn - ran,
            "integration": spent[0],
            "solves": curve.solves, "factorised": len(factorised), "knots": len(curve.knots), "steps": results.summary["solver"].get("steps", 0),
            "events": ",".join(events)}


def compare_solver(nodes: int, folder: Path, rtol: float) -> None:
    """Print the largest relative difference of the curve (values, slopes) built as the scene does (the film's
    elimination order, neighbouring fields reused) against one factorised afresh at every solve with SuperLU's own
    ordering and default supernodes."""
    from scipy.sparse.linalg import splu

    import exchange.seal.reynolds as reynolds
    from exchange.seal.setup import piecewise_curve

    scene = load_scene(ROOT / "cases" / "seal_flange.toml")
    seal = replace(scene.exchange[0], leakage_surface=str(ring_file(folder, nodes)), seal_rtol=rtol)
    model = build_model(replace(scene, exchange=(seal,) + scene.exchange[1:]))
    seal_model = seal_models(model)[0]
    film, path, law = seal_model.film, seal_model.path, seal_model.law
    rank, solve, accepted = reynolds._elimination_rank, reynolds._solve, reynolds._accepted
    reynolds._elimination_rank = lambda f: np.arange(f.n_nodes)
    reynolds._accepted = lambda *args: None
    reynolds._solve = lambda a, b: splu(a, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                                        options={"SymmetricMode": True}).solve(b)
    try:
        other = piecewise_curve(film, path, model.network.contact.thresholds(), law.setup.s_min, law.setup.s_max,
                                rtol)
    finally:
        reynolds._elimination_rank, reynolds._solve, reynolds._accepted = rank, solve, accepted
    c = law.curve
    same = np.array_equal(c.knots, other.knots)
    dv = np.max(np.abs(c.values - other.values) / np.maximum(np.abs(other.values), 1e-300)) if same else np.nan
    ds = np.max(np.abs(c.slopes - other.slopes) / np.maximum(np.abs(other.slopes), 1e-300)) if same else np.nan
    print(f"{nodes} nodes, seal_rtol {rtol:g}: same knots {same}; values differ by {dv:.1e}, slopes by {ds:.1e} "
          "(relative, largest)")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nodes", type=int, nargs="+", default=sorted(SHAPES), choices=sorted(SHAPES))
    ap.add_argument("--seal-rtol", type=float, default=1e-4, help="the seal curve's tolerance (the scene's: 1e-4)")
    ap.add_argument("--figures", type=Path, default=None, help="draw the library scene's figures into this folder")
    ap.add_argument("--no-merge", action="store_true", help="sum the seat force over every node (no merged rows)")
    ap.add_argument("--no-reuse", action="store_true",
                    help="factorise every Reynolds solve (no field reused: the cost of a film whose field changes)")
    ap.add_argument("--compare-solver", action="store_true",
                    help="also compare the curve with one factorised afresh at every solve")
    args = ap.parse_args()
    if args.no_reuse:
        import exchange.seal.reynolds as reynolds
        reynolds._accepted = lambda *unused: None
    if args.no_merge:
        import cases.model.seat_contact as seat_contact
        seat_contact.MERGE_ABOVE = 10 ** 12
    run(build_model(load_scene(ROOT / "cases" / "seal_flange.toml")))  # compile and cache, not counted
    print("| seal nodes | build [s CPU] | run 1 s [s CPU] | of which integration [s CPU] | build + run | picture "
          "| Reynolds solves | factorised | knots | steps | seal events |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.nodes:
            r = measure(n, Path(tmp), args.seal_rtol)
            print(f"| {r['nodes']} | {r['build']:.2f} | {r['run']:.2f} | {r['integration']:.2f} | "
                  f"{r['build'] + r['run']:.2f} | {r['picture']:.2f} | {r['solves']} | {r['factorised']} | {r['knots']} | {r['steps']} | {r['events']} |", flush=True)
        if args.compare_solver:
            for n in args.nodes:
                compare_solver(n, Path(tmp), args.seal_rtol)
    if args.figures is not None:
        figures(args.figures)
    return 0


if __name__ == "__main__":
    sys.exit(main())
