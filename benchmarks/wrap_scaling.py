"""How the cost of a wrapped cushion grows with its mesh: airbag_impactor with the cushion refined around its vent.

Requires: the ventsim package. Run: python benchmarks/wrap_scaling.py [--levels 1 2 3 4] [--dynamic] [--volume-only]
[--sampled] (--sampled: the 401-sample spline, as before the exact volume)
The cushion's faces inside the vent box are subdivided k times (×4 faces each time: about 4k, 16k, 64k, 256k vent
faces), the faces around them split to match (the mesh stays closed and conforming), and the case is run end to end
in a fresh process per size (after a warm-up run): load, build (the wrapped volume and the vent's blockage track),
solve. Each row gives
the cushion and vent faces, the wrapped volume's own CPU time, its exact knots and fitted knots and error bound, the
whole run's CPU time and peak resident memory; the last column is the local growth exponent of the end-to-end CPU
time, log(cpu ratio)/log(vent faces ratio), against the previous row.
"""
import argparse
import json
import math
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

BOX = (np.array([-0.12, -0.12, 0.05]), np.array([0.12, 0.12, 0.2]))


def refine_inside(vertices, faces, lo, hi, levels: int):
    """Subdivide the faces whose nodes all lie in the box [lo, hi] ``levels`` times (each into 4 by its edge
    midpoints) and split their neighbours on the shared edges so that the mesh stays conforming:
    (vertices (n, 3), faces (m, 3), number of faces inside the box)."""
    v, f = np.asarray(vertices, dtype=float), np.asarray(faces, dtype=np.int64)
    for _ in range(levels):
        inside = np.all(np.all((v[f] >= lo) & (v[f] <= hi), axis=2), axis=1)
        e = np.sort(f[inside][:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        edges = np.unique(e, axis=0)
        mid_id = len(v) + np.arange(len(edges))
        v = np.vstack([v, 0.5 * (v[edges[:, 0]] + v[edges[:, 1]])])
        key = edges[:, 0] * len(v) + edges[:, 1]
        order = np.argsort(key)
        key, mid_id = key[order], mid_id[order]

        def mid(a, b):
            k = np.minimum(a, b) * len(v) + np.maximum(a, b)
            i = np.clip(np.searchsorted(key, k), 0, len(key) - 1)
            return np.where(key[i] == k, mid_id[i], -1)

        a, b, c = f[:, 0], f[:, 1], f[:, 2]
        m = np.stack([mid(a, b), mid(b, c), mid(c, a)], axis=1)  # midpoints of edges ab, bc, ca (−1: unsplit)
        out = [f[np.all(m < 0, axis=1)]]
        full = np.all(m >= 0, axis=1)
        x, y, z, mab, mbc, mca = a[full], b[full], c[full], m[full, 0], m[full, 1], m[full, 2]
        out += [np.c_[x, mab, mca], np.c_[mab, y, mbc], np.c_[mca, mbc, z], np.c_[mab, mbc, mca]]
        for r in range(3):  # rotate so the split edges come first, then split 1 or 2 edges
            ar, br_, cr = np.roll(f, -r, axis=1).T
            mr = np.roll(m, -r, axis=1)
            one = (mr[:, 0] >= 0) & (mr[:, 1] < 0) & (mr[:, 2] < 0)
            out += [np.c_[ar[one], mr[one, 0], cr[one]], np.c_[mr[one, 0], br_[one], cr[one]]]
            two = (mr[:, 0] >= 0) & (mr[:, 1] >= 0) & (mr[:, 2] < 0)
            out += [np.c_[ar[two], mr[two, 0], cr[two]], np.c_[mr[two, 0], br_[two], mr[two, 1]],
                    np.c_[mr[two, 0], mr[two, 1], cr[two]]]
        f = np.concatenate(out)
    inside = np.all(np.all((v[f] >= lo) & (v[f] <= hi), axis=2), axis=1)
    return v, f, int(inside.sum())


def refined_case(folder: Path, level: int, dynamic: bool) -> Path:
    """Copy airbag_impactor(_dynamic) into ``folder`` with its cushion refined ``level`` times around the vent."""
    import trimesh

    from cases.run.library import HERE

    name = "airbag_impactor_dynamic.toml" if dynamic else "airbag_impactor.toml"
    for sub in ("data", "meshes"):
        shutil.copytree(HERE / sub, folder / sub, dirs_exist_ok=True)
    mesh = trimesh.load(HERE / "meshes" / "cushion.ply", process=True)
    v, f, _ = refine_inside(mesh.vertices, mesh.faces, BOX[0], BOX[1], level)
    trimesh.Trimesh(v, f, process=False).export(folder / "meshes" / "cushion.ply")
    shutil.copy(HERE / name, folder / name)
    return folder / name


def one(path: str, volume_only: bool, sampled: bool) -> dict:
    """Run one case in this process; its figures."""
    import os

    os.environ["VENTSIM_CACHE_DIR"] = ""  # compute the fit, not read the one an earlier run kept
    import cases.model.wrapped_volume as wv

    wv.EXACT_TRANSLATION = not sampled
    from cases.model.build import build_model
    from cases.run.runner import run
    from cases.scene.files import load_scene

    spent = {"volume": 0.0}
    original = wv.wrapped_volume

    def timed(*args, **kwargs):
        t0 = time.process_time()
        out = original(*args, **kwargs)
        spent["volume"] += time.process_time() - t0
        return out

    wv.wrapped_volume = timed
    import cases.model.build_geometry as bg
    bg.wrapped_volume = timed
    t0 = time.process_time()
    model = build_model(load_scene(Path(path)))
    if not volume_only:
        run(model)
    cpu = time.process_time() - t0
    vol = model.network.cavities[0].volume
    fit = next(iter(wv._FITS.values()), (None,))[0]
    bound = vol.bound if vol.bound == vol.bound else 0.0  # nan (sampled): no bound
    mesh_faces = len(model.geometry["surfaces"][0][0].faces)
    return {"cpu": cpu, "volume": spent["volume"], "rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
            "knots": len(vol.spline.x), "bound": bound, "fit_knots": len(fit.knots) if fit else 0,
            "vent": mesh_faces}


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--levels", type=int, nargs="+", default=[1, 2, 3, 4])
    ap.add_argument("--dynamic", action="store_true", help="the dynamic headform instead of the prescribed one")
    ap.add_argument("--volume-only", action="store_true", help="build the model only (no solve)")
    ap.add_argument("--sampled", action="store_true", help="the 401-sample spline instead of the exact volume")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        print(json.dumps(one(args.child, args.volume_only, args.sampled)))
        return
    print(f"{'cushion faces':>13} {'vent faces':>10} {'volume cpu [s]':>14} {'fit knots':>9} {'bound [m^3]':>11} "
          f"{'end to end cpu [s]':>18} {'peak RSS [MiB]':>14} {'exponent':>8}")
    with tempfile.TemporaryDirectory() as tmp:  # warm-up: numba's caches loaded or compiled, not in any row
        subprocess.run([sys.executable, __file__, "--child", str(refined_case(Path(tmp), 0, args.dynamic))],
                       capture_output=True, check=True)
    last = None
    for level in args.levels:
        with tempfile.TemporaryDirectory() as tmp:
            path = refined_case(Path(tmp), level, args.dynamic)
            import trimesh

            faces = len(trimesh.load(Path(tmp) / "meshes" / "cushion.ply", process=False).faces)
            cmd = ([sys.executable, __file__, "--child", str(path)] + (["--volume-only"] if args.volume_only else [])
                   + (["--sampled"] if args.sampled else []))
            row = json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout.splitlines()[-1])
        rate = "" if last is None else f"{math.log(row['cpu'] / last['cpu']) / math.log(row['vent'] / last['vent']):.2f}"
        print(f"{faces:>13} {row['vent']:>10} {row['volume']:>14.2f} {row['fit_knots']:>9} {row['bound']:>11.2e} "
              f"{row['cpu']:>18.2f} {row['rss']:>14.0f} {rate:>8}", flush=True)
        last = row


if __name__ == "__main__":
    main()
