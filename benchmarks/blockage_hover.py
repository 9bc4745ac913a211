"""Contacts whose gap stays inside the tolerance: a thin blade sliding over a vent, and brief contacts at any gap.

Requires: the ventsim package. Run: python benchmarks/blockage_hover.py
Prints the blade's blocked area·time against the exact per-node reference (each node's contact interval from the
box's geometry), the build and run CPU time of its 1 s run with 20,001 output rows, and the timing error of a
contact lasting 1e-6 of the run at gaps from 0 to just under the tolerance, and a blade turning over a node inside
the tolerance (chords). Figures quoted in docs/blockage.md.
"""
import math
import tempfile
import time
from pathlib import Path

import numpy as np

from cases.model.build import build_model
from cases.run.runner import run
from tests.test_blockage_exact import TOL, blade_reference, blade_scene
from tests.test_blockage_over_time import _node_weights, grid_vent, track_blocked_area_time


def blade(folder, n=10):
    grid_vent(folder / "vent.obj", n=n)
    gap = 18e-6
    t0 = time.process_time()
    model = build_model(blade_scene(folder, gap, 1e-4))
    t1 = time.process_time()
    results = run(model)
    t2 = time.process_time()
    track = model.network.areas[0].track
    surface, _ = model.geometry["surfaces"][0]
    vertices = model.geometry["bodies"]["blade"][1].vertices
    box, gap = vertices[:, 0], float(vertices[:, 2].min())  # the gap the float vertices give
    t_in, t_out = blade_reference(surface.vertices[:, 0], box.min(), box.max(), gap, 1.0)
    reference = float(np.sum(_node_weights(surface) * (t_out - t_in)))
    error = abs(track_blocked_area_time(track, 1.0) - reference) / reference
    rows = len(results.column("time"))
    blocked_rows = int(np.count_nonzero(results.column("vent.area") < 1e-4 * (1 - 1e-12)))
    print(f"blade over a {n}x{n} quad vent: blocked area*time relative error {error:.2e}, {rows} rows "
          f"({blocked_rows} with blockage), uncertified intervals {track.source.unresolved}, "
          f"build {t1 - t0:.2f} s CPU, run {t2 - t1:.2f} s CPU")


def brief(folder):
    (folder / "node.csv").write_text("x,y,z\n0.01,0.01,0.0\n")
    print(f"{'gap / tolerance':>16} {'contact [s]':>12} {'entry error':>12} {'exit error':>12}")
    for gap in (0.0, 0.6 * TOL, TOL * (1 - 1e-6), TOL * (1 - 1e-12)):
        speed = (2e-6 + 2 * math.sqrt(TOL ** 2 - gap ** 2)) / 1e-6
        model = build_model(blade_scene(folder, gap, 2e-6, speed, nodes="node.csv"))
        found = model.network.areas[0].track.source
        vertices = model.geometry["bodies"]["blade"][1].vertices
        box, actual = vertices[:, 0], float(vertices[:, 2].min())  # the gap the float vertices give
        t_in, t_out = blade_reference(0.01, box.min(), box.max(), actual, speed)
        err = np.abs(found.theta - [t_in, t_out]) if len(found.theta) == 2 else [np.inf, np.inf]
        print(f"{gap / TOL:>16.12f} {t_out - t_in:>12.3e} {err[0]:>12.1e} {err[1]:>12.1e}")


def rotating(folder):
    from tests.test_blockage_exact import rotating_blade

    t0 = time.process_time()
    model = build_model(rotating_blade(folder))
    t1 = time.process_time()
    found = model.network.areas[0].track.source
    gap = float(model.geometry["bodies"]["blade"][1].vertices[:, 2].min())
    half = math.asin((0.03 + math.sqrt(TOL ** 2 - gap ** 2)) / math.hypot(0.05, 0.05)) / math.radians(90.0)
    err = np.abs(found.theta - [0.5 - half, 0.5 + half])
    print(f"rotating blade: contact {2 * half:.4f} s, entry error {err[0]:.1e}, exit error {err[1]:.1e}, "
          f"uncertain {float(found.uncertain.sum()):.1e} s, build {t1 - t0:.2f} s CPU")


if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as tmp:
        blade(Path(tmp))
        brief(Path(tmp))
        rotating(Path(tmp))
