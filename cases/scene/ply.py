"""A mesh written as a binary PLY file with double-precision vertices (for scenes built in Python and meshes
converted from a scene's unit system)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["write_ply"]


def write_ply(path: Path, vertices, faces) -> None:
    """A binary PLY with double-precision vertices (trimesh's own PLY export rounds them to float32).

    Parameters
    ----------
    vertices : (n, 3) float
        [m]
    faces : (m, 3) or (m, 4) int
    """
    v, f = np.asarray(vertices, "<f8"), np.asarray(faces, "<i4")
    header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(v)}\nproperty double x\n"
              f"property double y\nproperty double z\nelement face {len(f)}\n"
              "property list uchar int vertex_indices\nend_header\n")
    cells = np.zeros(len(f), dtype=[("n", "u1"), ("i", "<i4", (f.shape[1],))])
    cells["n"], cells["i"] = f.shape[1], f
    with open(path, "wb") as fh:
        fh.write(header.encode() + v.tobytes() + cells.tobytes())
