"""Proximity benchmark: exact node-to-face distances against a ~200k-face wavy plane.

Blocker: a wavy plane of ~200k triangles (1 m square, amplitude 5 cm). Queries:
10k and 100k points in a thin shell (+-2 tolerances along the face normal), so
about half are within the tolerance of 1% of the bounding-box diagonal. Each method
answers "distance to the nearest face" with its tree built beforehand; the timed
region is the query only, after a warm-up call (which also compiles numba kernels).
Runs are interleaved and the median is printed, with each method's time divided by
``blockage``'s (ratio > 1: slower than blockage). ``blockage`` searches within the
tolerance (nodes beyond it get ``inf``), as the blockage test needs; the row
"blockage, no cutoff" computes the exact distance of every node, like the peers.

Exactness: on a random subsample of the queries, and on "boundary" nodes placed at
``tolerance * (1 +- 1e-12)`` from a face, each method's active set
(``distance <= tolerance``) is compared with the brute-force reference
(:mod:`blockage.reference`); the number of nodes classified differently is printed.

Requires: numpy, scipy, trimesh (with rtree), numba; libigl optional.

Usage::

    python benchmarks/proximity.py                 # full run (a few minutes)
    python benchmarks/proximity.py --quick         # 20k faces, 1 repeat
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import trimesh

import blockage
from blockage import reference

try:
    import igl
except ImportError:  # pragma: no cover - optional peer
    igl = None


def wavy_plane(n_faces, size=1.0, amplitude=0.05, waves=3):
    """Triangulated height field ``z = A sin(2 pi k x) cos(2 pi k y)`` with about ``n_faces`` faces."""
    m = int(np.sqrt(n_faces / 2)) + 1
    x = np.linspace(0.0, size, m)
    gx, gy = np.meshgrid(x, x, indexing="ij")
    gz = amplitude * np.sin(2 * np.pi * waves * gx / size) * np.cos(2 * np.pi * waves * gy / size)
    i, j = np.meshgrid(np.arange(m - 1), np.arange(m - 1), indexing="ij")
    a = (i * m + j).ravel()
    faces = np.concatenate([np.column_stack([a, a + m, a + m + 1]), np.column_stack([a, a + m + 1, a + 1])])
    return trimesh.Trimesh(np.column_stack([gx.ravel(), gy.ravel(), gz.ravel()]), faces, process=False)


def shell_points(mesh, n, thickness, seed):
    """Points on the surface moved along the face normal by U(-thickness, thickness)."""
    rng = np.random.default_rng(seed)
    points, face = trimesh.sample.sample_surface(mesh, n, seed=seed)
    return points + mesh.face_normals[face] * rng.uniform(-thickness, thickness, n)[:, None]


def boundary_points(mesh, tolerance, n, seed):
    """Points at tolerance * (1 +- 1e-12) above face interiors, on the convex side."""
    rng = np.random.default_rng(seed)
    faces = rng.integers(0, len(mesh.faces), n)
    weights = rng.dirichlet([1.0, 1.0, 1.0], n)
    base = np.einsum("ij,ijk->ik", weights, mesh.triangles[faces])
    scale = np.where(np.arange(n) % 2 == 0, 1.0 - 1e-12, 1.0 + 1e-12)
    return base + mesh.face_normals[faces] * (tolerance * scale)[:, None]


def methods(mesh, tolerance):
    """Name -> (setup seconds, query function returning distances)."""
    found = {}
    start = time.perf_counter()
    blocker = blockage.Blocker(mesh)
    found["blockage"] = (time.perf_counter() - start, lambda p: blocker.distances(p, tolerance).distances)
    found["blockage, no cutoff"] = (None, lambda p: blocker.distances(p, np.inf).distances)  # same tree
    start = time.perf_counter()
    mesh.triangles_tree  # noqa: B018 - builds trimesh's rtree
    found["trimesh closest_point"] = (time.perf_counter() - start,
                                      lambda p: trimesh.proximity.closest_point(mesh, p)[1])
    if igl is not None:
        vertices, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces, dtype=np.int64)
        start = time.perf_counter()
        tree = igl.AABB()
        tree.init(vertices, faces)
        found["igl AABB"] = (time.perf_counter() - start,
                             lambda p: np.sqrt(tree.squared_distance(vertices, faces, p)[0]))
    return found


def disagreements(query, points, truth, tolerance):
    """Nodes whose active flag differs from the reference, and the worst distance error within tolerance."""
    distances = query(points)
    active = distances <= tolerance
    inside = truth <= tolerance
    error = np.abs(distances[inside] - truth[inside]).max(initial=0.0)
    return int((active != inside).sum()), error


def compile_seconds():
    """First-call time in fresh processes: with an empty numba cache, then with it filled."""
    script = ("import time, numpy as np, trimesh; t = time.perf_counter(); import blockage; "
              "blockage.evaluate(trimesh.creation.box(), [trimesh.creation.icosphere(1)], 0.1, edge_contact=True); "
              "print(time.perf_counter() - t)")
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        runs = [float(subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True,
                                     check=True).stdout) for _ in range(2)]
    return runs


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--faces", type=int, default=200_000)
    parser.add_argument("--sizes", type=int, nargs="+", default=[10_000, 100_000])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--subsample", type=int, default=300, help="random queries checked by brute force")
    parser.add_argument("--boundary", type=int, default=200, help="nodes at tolerance*(1+-1e-12)")
    parser.add_argument("--quick", action="store_true", help="20k faces, 1 repeat")
    args = parser.parse_args(argv)
    if args.quick:
        args.faces, args.repeats = 20_000, 1

    mesh = wavy_plane(args.faces)
    tolerance = 0.01 * float(np.linalg.norm(mesh.extents))
    print(f"blocker: wavy plane, {len(mesh.faces):,} faces; tolerance {tolerance:.6g} m (1% of the diagonal); "
          f"queries in a shell of +-{2 * tolerance:.4g} m; cores: {os.cpu_count()}")
    found = methods(mesh, tolerance)
    for name, (setup, query) in found.items():
        query(shell_points(mesh, 100, 2 * tolerance, seed=99))  # warm-up: compile / load caches
        if setup is not None:
            print(f"  setup {name}: {setup:.3f} s")
    cold, warm = compile_seconds()
    print(f"  blockage first call in a fresh process: {cold:.2f} s with an empty numba cache (compile), "
          f"{warm:.2f} s with the cache filled")

    rows = {name: {} for name in found}
    for n in args.sizes:
        points = shell_points(mesh, n, 2 * tolerance, seed=n)
        times = {name: [] for name in found}
        for _ in range(args.repeats):
            for name, (_, query) in found.items():
                start = time.perf_counter()
                query(points)
                times[name].append(time.perf_counter() - start)
        for name in found:
            rows[name][n] = float(np.median(times[name]))

    rng = np.random.default_rng(7)
    sample = shell_points(mesh, args.subsample, 2 * tolerance, seed=12345)[rng.permutation(args.subsample)]
    edge = boundary_points(mesh, tolerance, args.boundary, seed=4321)
    start = time.perf_counter()
    truth_sample = reference.nearest_faces(sample, mesh.vertices, mesh.faces).distances
    truth_edge = reference.nearest_faces(edge, mesh.vertices, mesh.faces).distances
    print(f"  brute-force reference on {len(sample) + len(edge)} nodes: {time.perf_counter() - start:.1f} s")

    header = "| method | " + " | ".join(f"{n // 1000}k pts [s] | ratio" for n in args.sizes)
    print()
    print(header + " | disagree (random / boundary) | max error within tol [m] |")
    print("|" + "---|" * (2 + 2 * len(args.sizes) + 1))
    base = rows["blockage"]
    for name, (_, query) in found.items():
        cells = " | ".join(f"{rows[name][n]:.4g} | {rows[name][n] / base[n]:.2f}" for n in args.sizes)
        bad_random, err_random = disagreements(query, sample, truth_sample, tolerance)
        bad_edge, err_edge = disagreements(query, edge, truth_edge, tolerance)
        print(f"| {name} | {cells} | {bad_random} / {bad_edge} of {len(sample)} / {len(edge)} | "
              f"{max(err_random, err_edge):.2g} |")


if __name__ == "__main__":
    main()
