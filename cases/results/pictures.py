"""Pictures of a finished run: per blocked exchange, PNGs at chosen times, a GIF over the run and a view of the
whole scene; a VTK series of every surface (:mod:`cases.results.surfaces`).

Defaults keep the cost of ``ventsim run --render`` low: one plotter per kind of picture, reused for all its frames
(:class:`cases.results.render_plotter.FramePlotter`), a GIF of :data:`GIF_FRAMES` frames at :data:`GIF_SIZE`.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from cases.results.leak_state import leak_state, theta_at
from cases.results.surfaces import blocked_exchanges, body_vertices, cavity_vertices, contact_arrays, scene_surfaces

__all__ = ["frames_for", "write_pictures", "write_vtk", "default_times", "blocked_exchanges", "GIF_FRAMES",
           "GIF_SIZE", "PNG_SIZE"]

GIF_FRAMES = 12
"""Frames of the GIF (and of the VTK series) over a run."""
GIF_SIZE = (400, 300)
"""Size of the GIF's 3-D view [px] (the colour-bar strip is added to its width)."""
PNG_SIZE = (800, 600)
"""Size of a PNG's 3-D view [px]."""


def frame_at(results, j: int, t: float, *, whole_scene: bool = False):
    """The render Frame of exchange j at time t (blockage from :func:`cases.results.leak_state.leak_state`); with
    ``whole_scene`` the cavity surfaces are its context."""
    from cases.results.render import Frame

    model = results.model
    spec, net = model.scene.exchange[j], model.network
    state = leak_state(model, results.trajectory, j, t)
    th = theta_at(model, results.trajectory, t)
    bodies = tuple((body_vertices(model, n, th), model.geometry["bodies"][n][0].mesh.faces) for n in spec.blocked_by)
    context = ()
    if whole_scene:
        context = tuple((cavity_vertices(model, i, th), model.geometry["meshes"][c.name].faces)
                        for i, c in enumerate(model.scene.cavity) if c.name in model.geometry["meshes"])
    net.restore(results.trajectory.mode_at(t))
    p = net.states(t, results.trajectory(t))[net.exchanges[j].upstream].pressure
    cpress, status = contact_arrays(results, j, t)
    return Frame(t, p, state.surface.vertices, state.surface.faces, state.face_fraction, state.active,
                 state.distances, bodies, context, cpress=cpress, contact_status=status, label=frame_label(model, j))


def frame_label(model, j: int) -> str:
    """The first title line of exchange j's pictures: ``"<scene>: exchange <name>, p of cavity <name>"`` (the scene
    file's name, else its title)."""
    scene, net = model.scene, model.network
    up = net.exchanges[j].upstream
    name = Path(scene._path).stem if getattr(scene, "_path", "") else (scene.title or "scene")
    cavity = net.cavities[up].name if up is not None and 0 <= up < len(net.cavities) else "ambient"
    return f"{name}: exchange {net.exchanges[j].name}, p of cavity {cavity}"


def frames_for(results, j: int, times) -> list:
    return [frame_at(results, j, float(t)) for t in times]


def default_times(results, j: int) -> list:
    """Before any blockage (t = 0) and when the leakage area is smallest; for a contact seat, at the largest
    lift of its first opening."""
    name = results.model.network.exchanges[j].name
    info = results.summary.get("blockage", {}).get(name, {})
    t_min = info.get("minimum leakage area time [s]")
    t_end = results.model.scene.time.end
    times = [0.0] + ([min(t_min + 1e-9, t_end)] if t_min else [])
    contact = results.model.geometry.get("contact")
    if contact is not None and contact.exchange == j:  # a seat: also at the largest lift of its first opening
        c = results.summary["contact"][contact.name]
        lifts = c["lift-off times [s]"]
        if lifts:
            seats = [t for t in c["reseat times [s]"] if t > lifts[0]]
            ts = np.linspace(lifts[0], seats[0] if seats else t_end, 201)
            lift = np.abs(results.trajectory.sample(ts)[:, results.model.network.body_offset])
            times.append(float(ts[int(np.argmax(lift))]))
    return times


def write_vtk(results, folder: Path, times=None) -> list:
    """The VTK series of every surface at ``times`` [s] (default :data:`GIF_FRAMES` times over the run) into
    ``folder``; returns the ``.pvd`` paths (per surface, then the whole scene's), [] without geometry."""
    from cases.results.render_vtk import write_surface_series

    if results.model.geometry is None:
        return []
    if times is None:
        times = np.linspace(0.0, results.model.scene.time.end, GIF_FRAMES)
    return write_surface_series([scene_surfaces(results, float(t)) for t in times], folder)


def _scene_view(results, j: int, t: float, path: Path, plotter) -> Path:
    """The whole scene at t: the cavity translucent, the bodies, the leakage surface by blocked fraction."""
    from cases.results.render import save_png, camera_for
    from cases.results.render_style import CAVITY_OPACITY

    frame = frame_at(results, j, t, whole_scene=True)
    image = plotter.image(frame, camera_for(frame, include_context=True), context_opacity=CAVITY_OPACITY)
    return save_png(image, path)


def write_pictures(results, out: Path, *, times=None, animation_frames: int = GIF_FRAMES) -> dict:
    """PNGs (annotated: time, pressure, colour bar, scale bar), a whole-scene PNG, a GIF for every blocked
    exchange and the VTK series of every surface; returns {kind: [paths]}."""
    from cases.results.render import save_png, camera_for, render_animation
    from cases.results.render_plotter import FramePlotter

    out, written = Path(out), {"png": [], "scene": [], "gif": [], "pvd": []}
    t_end = results.model.scene.time.end
    movie_times = np.linspace(0.0, t_end, animation_frames)
    for j in blocked_exchanges(results):
        name = results.model.network.exchanges[j].name
        movie = frames_for(results, j, movie_times)
        camera = camera_for(movie[0])
        picture_times = times if times is not None else default_times(results, j)
        with FramePlotter(camera, PNG_SIZE, annotated=True) as plotter:
            for t in picture_times:
                path = out / f"{name}_t{1e3 * t:08.3f}ms.png"
                written["png"].append(save_png(plotter.image(frame_at(results, j, t)), path))
            t_scene = picture_times[-1]
            written["scene"].append(_scene_view(results, j, t_scene, out / f"scene_{name}_t{1e3 * t_scene:08.3f}ms.png",
                                                plotter))
        written["gif"].append(render_animation(movie, out / f"{name}.gif", camera=camera, window_size=GIF_SIZE,
                                               annotated=True))
    written["pvd"] = write_vtk(results, out / "vtk", movie_times)
    return written
