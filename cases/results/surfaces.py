"""Every surface of a run's scene at a time t, with its data: what the VTK series holds and the pictures draw.

- ``cavity_<name>``: a cavity's mesh (wrapped around its bodies where they push into it); point data
  ``displacement`` [m] from the initial mesh; cell data ``pressure`` and ``gauge_pressure`` [Pa] (uniform: one
  pressure per cavity) and ``temperature`` [K];
- ``leakage_<exchange>``: a blocked exchange's leakage surface (:func:`cases.results.render_vtk.leak_polydata` arrays:
  cell ``blocked_fraction``, point ``active``, ``gap``, on a seat ``CPRESS`` and ``status``) and field data
  ``leak_area``, ``open_area`` [m^2] and ``exchange_blocked_fraction`` [-], all from :func:`cases.results.leak_state.leak_state`,
  the one definition of the vent area;
- ``body_<name>``: a body at its pose; point data ``displacement`` [m] from its initial position.

Every surface has field data ``time`` [s].
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cases.results.leak_state import leak_state, theta_at

__all__ = ["Surface", "blocked_exchanges", "body_vertices", "cavity_vertices", "contact_arrays", "scene_surfaces"]


@dataclass(frozen=True)
class Surface:
    """One named surface at one time: ``vertices (n, 3) [m]``, ``faces (m, 3|4)`` (-1 padded) and its arrays."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    point_data: dict = field(default_factory=dict)
    cell_data: dict = field(default_factory=dict)
    field_data: dict = field(default_factory=dict)


def body_vertices(model, name: str, theta: float) -> np.ndarray:
    """World coordinates [m] of body ``name``'s vertices at θ, placed as the blockage sees it."""
    body, _ = model.geometry["bodies"][name]
    if body.deforming:
        return body.vertices_at(theta)
    T = model.geometry["driver"].placement(name, theta)[1]
    return np.asarray(body.mesh.vertices) @ T[:3, :3].T + T[:3, 3]


def cavity_vertices(model, i: int, theta: float) -> np.ndarray:
    """Cavity i's mesh nodes at θ [m]: wrapped around its bodies when it has ``wrapped_by``."""
    spec = model.scene.cavity[i]
    mesh = model.geometry["meshes"][spec.name]
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    if not spec.wrapped_by:
        return vertices
    return model.geometry["driver"].wrapper(spec.wrapped_by).place(vertices, theta)


def blocked_exchanges(results) -> list:
    """Indices of the exchanges whose area comes from a blocked leakage surface."""
    geo = results.model.geometry
    if geo is None:
        return []
    return [j for j, ga in enumerate(geo["areas"]) if ga is not None and geo["surfaces"][j][0] is not None]


def contact_arrays(results, j: int, t: float):
    """(CPRESS (n,) [Pa], status (n,) uint8) of exchange j's seat nodes at t, or (None, None) if it is no seat."""
    contact = results.model.geometry.get("contact")
    if contact is None or contact.exchange != j:
        return None, None
    from cases.results.contact_results import nodal_state
    from exchange.readback.values import load_mode

    fast = results.model.network.engine()
    load_mode(fast, results.trajectory.mode_at(t))
    cpress, status, _ = nodal_state(fast, t, results.trajectory(t))
    return cpress, status


def _leak_arrays(results, j: int, t: float, state) -> tuple[dict, dict]:
    gaps = np.asarray(state.distances, dtype=np.float64)
    points = {"active": state.active.astype(np.uint8),
              "gap": np.where(np.isfinite(gaps), gaps, np.nan)}
    cpress, status = contact_arrays(results, j, t)
    if cpress is not None:
        points.update(CPRESS=np.asarray(cpress, dtype=np.float64), status=np.asarray(status, dtype=np.uint8))
    return points, {"blocked_fraction": state.face_fraction}


def _cavities(model, states, theta, t) -> list:
    out = []
    for i, spec in enumerate(model.scene.cavity):
        if spec.name not in model.geometry["meshes"]:
            continue
        mesh, s = model.geometry["meshes"][spec.name], states[i]
        v = cavity_vertices(model, i, theta)
        m = len(mesh.faces)
        out.append(Surface(f"cavity_{spec.name}", v, np.asarray(mesh.faces),
                           {"displacement": v - np.asarray(mesh.vertices)},
                           {"pressure": np.full(m, s.pressure),
                            "gauge_pressure": np.full(m, s.pressure - model.network.ambient.pressure),
                            "temperature": np.full(m, s.temperature)}, {"time": t}))
    return out


def scene_surfaces(results, t: float) -> list:
    """Every surface of the scene of ``results`` (a :class:`cases.run.runner.Results`) at time ``t`` [s]."""
    model, traj = results.model, results.trajectory
    theta = theta_at(model, traj, t)
    net = model.network
    net.restore(traj.mode_at(t))
    states = net.states(t, traj(t))
    out = _cavities(model, states, theta, t)
    for j in blocked_exchanges(results):
        state = leak_state(model, traj, j, t)
        points, cells = _leak_arrays(results, j, t, state)
        out.append(Surface(f"leakage_{net.exchanges[j].name}", np.asarray(state.surface.vertices),
                           np.asarray(state.surface.faces), points, cells,
                           {"time": t, "leak_area": state.leak_area, "open_area": state.open_area,
                            "exchange_blocked_fraction": state.blocked_fraction}))
    for name, (body, _) in model.geometry["bodies"].items():
        v = body_vertices(model, name, theta)
        out.append(Surface(f"body_{name}", v, np.asarray(body.mesh.faces),
                           {"displacement": v - np.asarray(body.mesh.vertices)}, {}, {"time": t}))
    return out
