"""How the cost of a blocked vent grows with its size: airbag_impactor with its vent panel refined.

Requires: the ventsim package. Run: python benchmarks/vent_scaling.py [--levels 0 1 2 3] [--dynamic]
The cushion's vent panel (its faces inside the vent box) is cut out and subdivided k times (×4 faces each time:
about 1k, 4k, 16k, 64k vent faces) and given as the exchange's leakage surface; the cushion itself is unchanged. For each size it prints the build time (the whole model, and the crossing search + area track of the
vent within it), the solve time, the end-to-end time (load + build + solve + history), the crossings found, and
the solver's events and restarts. Same process, same machine load for all rows.
"""
import argparse
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np
import trimesh

from cases.model.build import build_model
from cases.run.library import HERE
from cases.run.runner import run
from cases.scene.files import load_scene
import cases.model.build_leak as build_leak

BOX = (np.array([-0.12, -0.12, 0.05]), np.array([0.12, 0.12, 0.2]))


def refined_case(folder: Path, level: int, dynamic: bool) -> Path:
    """Copy the case into ``folder`` with the vent panel's faces subdivided ``level`` times."""
    name = "airbag_impactor_dynamic.toml" if dynamic else "airbag_impactor.toml"
    for sub in ("data", "meshes"):
        shutil.copytree(HERE / sub, folder / sub, dirs_exist_ok=True)
    mesh = trimesh.load(HERE / "meshes" / "cushion.ply", process=True)
    inside = np.all(np.all((mesh.vertices[mesh.faces] >= BOX[0]) & (mesh.vertices[mesh.faces] <= BOX[1]), axis=2),
                    axis=1)
    vent = mesh.submesh([np.flatnonzero(inside)], append=True)
    for _ in range(level):
        vent = vent.subdivide()
    vent.export(folder / "meshes" / "vent.ply")
    text = (HERE / name).read_text().replace("leakage_box = [-0.12, -0.12, 0.05, 0.12, 0.12, 0.2]",
                                             'leakage_surface = "meshes/vent.ply"')
    (folder / name).write_text(text)
    return folder / name


def measure(path: Path):
    timings = {"track": 0.0}
    original = build_leak.certified_crossings

    def timed_crossings(*args, **kwargs):
        t0 = time.perf_counter()
        out = original(*args, **kwargs)
        timings["track"] += time.perf_counter() - t0
        return out

    build_leak.certified_crossings = timed_crossings
    try:
        t0 = time.perf_counter()
        model = build_model(load_scene(path))
        t1 = time.perf_counter()
        results = run(model)
        t2 = time.perf_counter()
    finally:
        build_leak.certified_crossings = original
    surface, _ = model.geometry["surfaces"][0]
    track = model.network.areas[0].track
    st = results.summary["solver"]
    return (len(surface.faces), len(surface.vertices), t1 - t0, timings["track"], st["wall time [s]"], t2 - t0,
            len(track.crossings), st["events"], st["restarts"])


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2, 3])
    ap.add_argument("--dynamic", action="store_true", help="the dynamic headform instead of the prescribed one")
    args = ap.parse_args()
    print(f"{'vent faces':>10} {'nodes':>7} {'build [s]':>10} {'crossings [s]':>14} {'solve [s]':>10} "
          f"{'end to end [s]':>15} {'crossings':>10} {'events':>7} {'restarts':>9}")
    for level in args.levels:
        with tempfile.TemporaryDirectory() as tmp:
            row = measure(refined_case(Path(tmp), level, args.dynamic))
        print(f"{row[0]:>10} {row[1]:>7} {row[2]:>10.2f} {row[3]:>14.2f} {row[4]:>10.2f} {row[5]:>15.2f} "
              f"{row[6]:>10} {row[7]:>7} {row[8]:>9}", flush=True)


if __name__ == "__main__":
    main()
