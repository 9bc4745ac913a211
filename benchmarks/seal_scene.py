"""The flange scene with a fine seal ring: CPU seconds to build (the seal's conductance curve) and to run 1 s of
physical time on the engine, by the ring's node count.

The scene is cases/seal_flange.toml with its gasket face replaced by a structured ring of quads (r = 40..50 mm) of
the node counts below, and ``time.end`` = 1 s (filled until the seal leaks and the flange lifts). The engine's
kernels are compiled and cached first (one run of the library scene, not counted). Figures are CPU seconds of this
process (``time.process_time``): "build" is ``build_model`` (mesh, seat rays, seal film and conductance curve),
"run" the integration with its history and seal columns, "picture" the gap picture.

Run: python benchmarks/seal_scene.py [--nodes 480 5120 20480]
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


def measure(nodes: int, folder: Path) -> dict:
    from cases.results.seal_outputs import write_seal_pictures

    scene = load_scene(ROOT / "cases" / "seal_flange.toml")
    seal = replace(scene.exchange[0], leakage_surface=str(ring_file(folder, nodes)))
    scene = replace(scene, exchange=(seal,) + scene.exchange[1:], time=replace(scene.time, end=1.0))
    start = time.process_time()
    model = build_model(scene)
    built = time.process_time()
    results = run(model)
    ran = time.process_time()
    write_seal_pictures(results, folder)
    drawn = time.process_time()
    curve = seal_models(model)[0].law.curve
    events = [label for _, label in results.trajectory.events if label.startswith("seal:")]
    return {"nodes": nodes, "build": built - start, "run": ran - built, "picture": drawn - ran,
            "solves": curve.solves, "knots": len(curve.knots), "steps": results.summary["solver"].get("steps", 0),
            "events": ",".join(events)}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nodes", type=int, nargs="+", default=sorted(SHAPES), choices=sorted(SHAPES))
    args = ap.parse_args()
    run(build_model(load_scene(ROOT / "cases" / "seal_flange.toml")))  # compile and cache, not counted
    print("| seal nodes | build [s CPU] | run 1 s [s CPU] | build + run | picture | Reynolds solves | knots | steps "
          "| seal events |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.nodes:
            r = measure(n, Path(tmp))
            print(f"| {r['nodes']} | {r['build']:.2f} | {r['run']:.2f} | {r['build'] + r['run']:.2f} | "
                  f"{r['picture']:.2f} | {r['solves']} | {r['knots']} | {r['steps']} | {r['events']} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
