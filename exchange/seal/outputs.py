"""What a seal reports at a load: minimum and mean channel height, contact-area fraction, sealed or not, and a
picture of the gap field over the seal face with the contact region.
"""
from __future__ import annotations

import numpy as np

from exchange.seal.channel import contact_fraction

__all__ = ["seal_outputs", "gap_picture"]


def seal_outputs(film, path, q, closure):
    """Outputs of a seal at load ``q`` on ``path`` (``closure`` the curve's closure load).

    Returns a dict: "min_gap [m]", "mean_gap [m]" (area-weighted), "contact_fraction [-]" (area of the nodes in
    contact over the seal's area) and "sealed" (True on the sealed side of the closure load).

    >>> from exchange.seal.film import seal_film
    >>> from exchange.seal.meshes import annulus_mesh, flat_flange_seat
    >>> from exchange.seal.load_paths import DisplacementPath
    >>> from exchange.seal.gap_laws import NoGap
    >>> film = seal_film(*annulus_mesh(0.01, 0.02, 2, 8))
    >>> law = np.array([1.0, 1e12, 0, 0, 0, 0, 0, 0, 1.0, 1.0, 0.02])
    >>> path = DisplacementPath(flat_flange_seat(film.vertices, film.areas, 1e-6), law, NoGap())
    >>> out = seal_outputs(film, path, 0.25e-6, 1e-6)
    >>> round(out["mean_gap [m]"], 12), out["contact_fraction [-]"], out["sealed"]
    (7.5e-07, 0.0, False)
    """
    h = path.heights(q)
    return {"min_gap [m]": float(h.min()), "mean_gap [m]": float(np.sum(h * film.areas) / np.sum(film.areas)),
            "contact_fraction [-]": contact_fraction(path.in_contact(q), film.areas),
            "sealed": bool(path.direction * (q - closure) >= 0.0)}


def gap_picture(film, gaps, in_contact, path, title=""):
    """Write a PNG of the channel height over the seal face (its best-fit plane), the contact nodes as dots and
    the closed nodes (h = 0) in black. ``gaps`` (n,) [m], ``in_contact`` (n,) bool, ``path`` the file."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.tri import Triangulation

    from exchange.seal.chart import plane_frame

    _, _, e1, e2, _ = plane_frame(film.vertices, film.axis)
    xy = np.c_[film.vertices @ e1, film.vertices @ e2] * 1e3
    tris = np.concatenate([film.triangles, film.quads[:, [0, 1, 2]], film.quads[:, [0, 2, 3]]])
    fig, ax = plt.subplots(figsize=(5.5, 5))
    shade = ax.tripcolor(Triangulation(xy[:, 0], xy[:, 1], tris), np.asarray(gaps) * 1e6, shading="gouraud",
                         cmap="viridis")
    fig.colorbar(shade, ax=ax, label="channel height h [µm]")
    closed = np.asarray(gaps) == 0.0
    ax.plot(*xy[in_contact & ~closed].T, ".", color="white", ms=2, label="in contact")
    ax.plot(*xy[closed].T, ".", color="black", ms=3, label="closed (h = 0)")
    ax.set_aspect("equal")
    ax.set_xlabel("in-plane u [mm]")
    ax.set_ylabel("in-plane v [mm]")
    ax.set_title(title, fontsize=9)
    ax.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
