"""Write the meshes and tables of the blockage library cases (run from the repository root):
seal_vent_nodes (node-based seal), vent_bar_edge (edge contact) and bag_unfold (self-contact)."""
from pathlib import Path

import numpy as np
import trimesh

import blockage
from cases.model.area_track import node_weights

HERE = Path(__file__).resolve().parent


def seal_nodes():
    """The seal's leak-path nodes with their share of the path's area (Σ A_e/N_e): the node-based twin of
    seal_vent, whose blocked area equals the element-based one."""
    leak = blockage.LeakageSurface.read(HERE / "seal_leak.obj")
    w = node_weights(leak.face_areas, leak.faces, leak.face_sizes, len(leak.vertices))
    rows = "".join(f"{x!r},{y!r},{z!r},{a!r}\n" for (x, y, z), a in zip(leak.vertices.tolist(), w.tolist()))
    (HERE.parent / "data" / "seal_leak_nodes.csv").write_text("x [m],y [m],z [m],area [m^2]\n" + rows)


def edge_vent():
    """A coarse vent, 4 x 4 quads of 10 mm in z = 0: a thin bar lying between its node columns touches only its
    edges."""
    xs = np.linspace(-0.02, 0.02, 5)
    lines = [f"v {float(x)!r} {float(y)!r} 0.0" for y in xs for x in xs]
    lines += [f"f {j * 5 + i + 1} {j * 5 + i + 2} {(j + 1) * 5 + i + 2} {(j + 1) * 5 + i + 1}"
              for j in range(4) for i in range(4)]
    (HERE / "edge_vent.obj").write_text("\n".join(lines) + "\n")


def bag_series():
    """A flat bag, 100 x 100 mm, 1 mm high, unfolding to 40 mm: its closed surface frame by frame (.npz)."""
    box = trimesh.creation.box(extents=(0.1, 0.1, 1.0))
    box.apply_translation((0.0, 0.0, 0.5))
    box = box.subdivide().subdivide().subdivide()
    times = np.array([0.0, 0.005, 0.0075, 0.01, 0.0125, 0.015, 0.02, 0.04])  # no edge grows 4x in one frame
    heights = np.array([0.001, 0.0015, 0.003, 0.006, 0.012, 0.024, 0.04, 0.04])
    frames = np.repeat(box.vertices[None], len(times), axis=0)
    frames[:, :, 2] *= heights[:, None]
    np.savez(HERE / "bag_unfold.npz", times=times, vertices=frames, faces=np.asarray(box.faces))


if __name__ == "__main__":
    seal_nodes()
    edge_vent()
    bag_series()
