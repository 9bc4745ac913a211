"""Pictures of a finished run: per blocked exchange, PNGs at chosen times, a GIF over the run, a VTK series."""
from __future__ import annotations

from pathlib import Path

import numpy as np

import blockage

__all__ = ["frames_for", "write_pictures", "default_times"]


def theta_at(results, t: float) -> float:
    """The geometry parameter at time t: t itself, or the dynamic body's displacement."""
    net, driver = results.model.network, results.model.geometry["driver"]
    return t if driver.dynamic is None else float(results.trajectory(t)[net.body_offset])


def frame_at(results, j: int, t: float):
    """The render Frame of exchange j at time t."""
    from .render import Frame

    model = results.model
    geo, spec, net = model.geometry, model.scene.exchange[j], model.network
    surface, positions = geo["surfaces"][j]
    th = theta_at(results, t)
    leak = surface.with_vertices(positions(th, None))
    placed = geo["driver"].placed(spec.blocked_by)(th)
    tol = spec.contact_tolerance
    res = blockage.evaluate(leak, placed, tol, cutoff=4 * tol, permeability=spec.permeability)  # distances
    active = net.areas[j].track.active_at(th)  # the active set the solver used (cases.area_track)
    counts = blockage.areas.active_counts(active, leak.faces, leak.face_sizes)
    fraction = counts / np.asarray(leak.face_sizes, dtype=float)
    bodies = tuple((geo["bodies"][n][0].vertices_at(th), geo["bodies"][n][0].mesh.faces) for n in spec.blocked_by)
    net.restore(results.trajectory.mode_at(t))
    y = results.trajectory(t)
    p = net.states(t, y)[net.exchanges[j].upstream].pressure
    cpress = status = None
    contact = geo.get("contact")
    if contact is not None and contact.exchange == j:
        from .contact_results import nodal_state

        cpress, status, _ = nodal_state(net, t, y)
    return Frame(t, p, leak.vertices, leak.faces, np.clip(fraction, 0.0, 1.0), active,
                 res.distances, bodies, cpress=cpress, contact_status=status)


def frames_for(results, j: int, times) -> list:
    return [frame_at(results, j, float(t)) for t in times]


def blocked_exchanges(results) -> list:
    geo = results.model.geometry
    if geo is None:
        return []
    return [j for j, ga in enumerate(geo["areas"]) if ga is not None and geo["surfaces"][j][0] is not None]


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


def write_pictures(results, out: Path, *, times=None, animation_frames: int = 30) -> dict:
    """PNGs, a GIF and a VTK series for every blocked exchange of a run; returns {kind: [paths]}."""
    from .render import camera_for, render_animation, render_frame, write_vtk_series

    out, written = Path(out), {"png": [], "gif": [], "pvd": []}
    t_end = results.model.scene.time.end
    for j in blocked_exchanges(results):
        name = results.model.network.exchanges[j].name
        movie = frames_for(results, j, np.linspace(0.0, t_end, animation_frames))
        camera = camera_for(movie[0])
        for t in (times if times is not None else default_times(results, j)):
            path = out / f"{name}_t{1e3 * t:08.3f}ms.png"
            written["png"].append(render_frame(frame_at(results, j, t), path, camera=camera))
        written["gif"].append(render_animation(movie, out / f"{name}.gif", camera=camera))
        written["pvd"].append(write_vtk_series(movie, out / "vtk", stem=name))
    return written
