"""The pictures of ``ventsim compare``: the rules' histories overlaid, the per-face difference of blocked fraction
to exact at the instant the leakage areas differ most (pyvista, off screen), and the convergence sweep."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from cases.results.output import atomic_path
from cases.results.render import save_png
from cases.run.area_integrals import breakpoints

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

__all__ = ["plot_histories", "worst_instant", "plot_face_difference", "plot_sweep"]


def _figure(rows: int, height: float = 2.4):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, height * rows))
    return fig, fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]


def plot_histories(path: Path, runs: list, fe_pressures: dict | None = None) -> None:
    """Per cavity its pressure, per blocked exchange its leakage area, one line per rule (the FE run's pressure
    dashed black when given)."""
    first = runs[0].results
    cavities = list(first.summary["cavities"])
    exchanges = [c.split(".area")[0] for c in first.columns if c.endswith(".area [m^2]")]
    fig, axes = _figure(len(cavities) + len(exchanges))
    for run in runs:
        r, label = run.results, run.rule + (f" ({run.step:g} s, lag {run.lag})" if run.step else "")
        t = r.column("time") * 1e3
        for ax, name in zip(axes, cavities):
            ax.plot(t, r.column(f"{name}.pressure") * 1e-3, label=label, lw=1)
        for ax, name in zip(axes[len(cavities):], exchanges):
            ax.plot(t, r.column(f"{name}.area") * 1e6, label=label, lw=1)
    for ax, name in zip(axes, cavities):
        fe = (fe_pressures or {}).get(name)
        if fe is not None:
            ax.plot(fe.times * 1e3, fe.pressures * 1e-3, "--", color="k", lw=1, label="FE run (abstat)")
        ax.set_ylabel(f"{name}\npressure [kPa]")
    for ax, name in zip(axes[len(cavities):], exchanges):
        ax.set_ylabel(f"{name}\narea [mm^2]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    axes[-1].set_xlabel("time [ms]")
    fig.suptitle(f"{first.model.scene.title or first.model.scene.path.name}: blockage rules", fontsize=10)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=100, format="png")


def worst_instant(track, exact, t_end: float) -> tuple:
    """(time [s], |A − A_exact| [m^2]) where two area tracks of an exchange differ most: both sides of every
    breakpoint and the middle of every piece."""
    pts = breakpoints([track, exact], 0.0, t_end)
    cand = np.unique(np.concatenate([pts, 0.5 * (pts[1:] + pts[:-1]), np.nextafter(pts, np.inf)]))
    cand = cand[(cand >= 0.0) & (cand <= t_end)]
    diff = np.array([abs(track(float(t)) - exact(float(t))) for t in cand])
    k = int(np.argmax(diff))
    return float(cand[k]), float(diff[k])


def plot_face_difference(path: Path, run, exact, j: int, t: float) -> None:
    """Exchange j's leakage surface at ``t`` coloured by its faces' blocked fraction under ``run.rule`` minus
    exact's (red: the rule blocks more), the blocking bodies translucent."""
    import pyvista as pv

    from cases.results.leak_state import leak_state, theta_at
    from cases.results.render_vtk import polygon_cells
    from cases.results.surfaces import body_vertices

    r, e = run.results, exact.results
    mine, ref = leak_state(r.model, r.trajectory, j, t), leak_state(e.model, e.trajectory, j, t)
    surface = pv.PolyData(np.asarray(mine.surface.vertices, dtype=float), faces=polygon_cells(mine.surface.faces))
    surface.cell_data["difference"] = np.asarray(mine.face_fraction) - np.asarray(ref.face_fraction)
    plotter = pv.Plotter(off_screen=True, window_size=(800, 600))
    plotter.add_mesh(surface, scalars="difference", cmap="coolwarm", clim=(-1.0, 1.0), show_edges=True,
                     scalar_bar_args={"title": f"blocked fraction, {run.rule} - exact [-]"})
    th = theta_at(r.model, r.trajectory, t)
    spec = r.model.scene.exchange[j]
    for name in spec.blocked_by:
        faces = np.asarray(r.model.geometry["bodies"][name][0].mesh.faces)
        body = pv.PolyData(np.asarray(body_vertices(r.model, name, th), dtype=float), faces=polygon_cells(faces))
        plotter.add_mesh(body, color="lightgrey", opacity=0.15)
    plotter.add_text(f"{spec.name}: {run.rule} (step {run.step:g} s, lag {run.lag}) - exact, t = {t * 1e3:.4g} ms",
                     font_size=10)
    normal = _view_direction(mine.surface)
    plotter.view_vector(normal, viewup=np.eye(3)[int(np.argmin(np.abs(normal)))])
    plotter.reset_camera(bounds=surface.bounds)  # the leakage surface fills the view, the bodies are clipped
    plotter.camera.zoom(0.9)
    try:
        save_png(plotter.screenshot(return_img=True), path)
    finally:
        plotter.close()


def _view_direction(surface) -> np.ndarray:
    """The leakage surface's mean normal (a view from in front of it), +z when it has none."""
    from cases.results.render import _face_normals

    n = _face_normals(surface.vertices, surface.faces).sum(axis=0)
    norm = np.linalg.norm(n)
    return n / norm if norm > 0 else np.array([0.0, 0.0, 1.0])


def plot_sweep(path: Path, rows: list) -> None:
    """Log-log: per rule, ∫|A − A_exact| dt and |Δ peak pressure| against the step, with a slope-1 guide."""
    fig, axes = _figure(2, 3.0)
    keys = ("|A - A_exact| area*time [m^2 s]",
            next((k for k in rows[0] if k.startswith("delta") and k.endswith("peak pressure [Pa]")), None))
    for ax, key in zip(axes, keys):
        if key is None:
            continue
        for rule in dict.fromkeys(r["rule"] for r in rows):
            pts = [(r["step [s]"], abs(r[key])) for r in rows if r["rule"] == rule and abs(r[key]) > 0]
            if pts:
                s, v = np.array(pts).T
                ax.loglog(s, v, "o-", label=rule)
                ax.loglog(s, v[0] * s / s[0], ":", color="grey", lw=0.8)
        ax.set_ylabel(key.replace("delta ", "|delta ").replace(" [", "| [", 1) if key.startswith("delta") else key,
                      fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    axes[-1].set_xlabel("step [s] (dotted: first order)")
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=100, format="png")
