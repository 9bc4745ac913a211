"""Build the meshes of the case library (run: python cases/meshes/make_meshes.py); the outputs are committed.

* ``cushion.ply``: a closed ellipsoidal cushion, semi-axes 0.30 x 0.30 x 0.15 m (about 57 L), 20,480 triangles
  (icosphere of 5 subdivisions, scaled); its vent panel is selected by a box in the scene.
* ``seal_chamber.ply``: a closed cylindrical chamber (radius 40 mm, height 30 mm) whose top disc has a leak
  path ring selected by a box in the scene.
* ``seal_leak.obj``: an annular leak path of quads (inner radius 10 mm, outer 20 mm) in the plane z = 0.
* ``relief_seat.obj``: the annular seat of the relief valve (inner radius 5 mm, outer 6 mm, 48 x 2 quads) in the
  plane z = 0; the poppet (a box in the scene) rests on it.
* ``seal_flange.ply``: a 60 x 60 x 5 mm flange plate tilted by 0.1° about y, its lower face 1 mm above the leak
  path at x = 0, so that it closes the path progressively as it comes down.
"""
import math
from pathlib import Path

import numpy as np
import trimesh

HERE = Path(__file__).resolve().parent


def cushion() -> trimesh.Trimesh:
    m = trimesh.creation.icosphere(subdivisions=5, radius=1.0)
    m.apply_scale((0.30, 0.30, 0.15))
    return m


def annulus_quads(r_in=0.010, r_out=0.020, n_theta=48, n_r=4):
    """Vertices and quads of a flat annulus in z = 0 (counter-clockwise seen from +z)."""
    radii = np.linspace(r_in, r_out, n_r + 1)
    theta = np.linspace(0.0, 2 * np.pi, n_theta, endpoint=False)
    v = np.array([[r * np.cos(t), r * np.sin(t), 0.0] for r in radii for t in theta])
    q = []
    for i in range(n_r):
        for j in range(n_theta):
            a, b = i * n_theta + j, i * n_theta + (j + 1) % n_theta
            q.append([a, b, b + n_theta, a + n_theta])
    return v, np.array(q)


def write_obj(path: Path, vertices, quads):
    lines = [f"v {x:.17g} {y:.17g} {z:.17g}" for x, y, z in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in q) for q in quads]
    path.write_text("\n".join(lines) + "\n")


def main():
    cushion().export(HERE / "cushion.ply")
    chamber = trimesh.creation.cylinder(radius=0.04, height=0.03, sections=64)
    chamber.apply_translation((0, 0, -0.015))  # top disc at z = 0
    chamber.export(HERE / "seal_chamber.ply")
    write_obj(HERE / "seal_leak.obj", *annulus_quads())
    write_obj(HERE / "relief_seat.obj", *annulus_quads(0.005, 0.006, 48, 2))
    flange = trimesh.creation.box(extents=(0.06, 0.06, 0.005))
    tilt = math.radians(0.1)
    flange.apply_transform(trimesh.transformations.rotation_matrix(-tilt, (0, 1, 0)))
    flange.apply_translation((0.0, 0.0, 0.001 + 0.0025 / math.cos(tilt)))
    flange.export(HERE / "seal_flange.ply")


if __name__ == "__main__":
    main()
