"""History columns of the bodies: displacement, velocity, acceleration (and rotation), and the gas force on a
dynamic body — the primary result of a headform test.

A dynamic body moves along its axis: ``<body>.displacement [m]`` s, ``.velocity [m/s]`` v, ``.acceleration
[m/s^2]`` dv/dt from the compiled right-hand side at (t, y), i.e. the equation of motion
m·dv/dt = m·g + F_gas + F_spring + F_contact itself, and ``.gas_force [N]`` F_gas = (p − p_amb)·dV/ds of the cavity
it intrudes into plus (p − p_amb)·A of its pressure cavity. A prescribed rigid body gets s, ṡ and s̈ of its
displacement table (s̈ = 0 on each piece of a piecewise-linear table) and ``.rotation [deg]`` when it rotates.
"""
from __future__ import annotations

import numpy as np

from exchange.readback.values import body_values, load_mode

__all__ = ["body_columns"]


def _dynamic(model, trajectory, times) -> list:
    net = model.network
    fast, body, k = net.compiled_solver(), net.body, net.body_offset
    ys = trajectory.sample(times)
    s, v = ys[:, k].copy(), ys[:, k + 1].copy()
    a, f = np.empty(len(times)), np.empty(len(times))
    loaded = None
    for r, (t, y) in enumerate(zip(times, ys)):
        mode = trajectory.mode_at(t)
        if mode is not loaded:
            load_mode(fast, mode)
            loaded = mode
        f[r], a[r], _, _ = body_values(fast, t, y)
    if trajectory.modes:
        load_mode(fast, trajectory.modes[-1])
    name = body.name
    return [(f"{name}.displacement [m]", s), (f"{name}.velocity [m/s]", v), (f"{name}.acceleration [m/s^2]", a),
            (f"{name}.gas_force [N]", f)]


def _prescribed(body, times) -> list:
    m = body.motion
    out = []
    if getattr(m, "table", None) is not None or getattr(m, "velocity", 0.0):
        out += [(f"{body.name}.displacement [m]", np.array([m.displacement(t) for t in times])),
                (f"{body.name}.velocity [m/s]", np.array([m.speed(t) for t in times])),
                (f"{body.name}.acceleration [m/s^2]", np.zeros(len(times)))]
    if getattr(m, "rotation_table", None) is not None:
        out.append((f"{body.name}.rotation [deg]", np.array([m.rotation_table(t) for t in times])))
    return out


def body_columns(model, trajectory, times, present=()) -> list:
    """[(column, values)] of every body at ``times`` [s], leaving out columns already ``present``."""
    geo = model.geometry
    if geo is None or not geo.get("bodies"):
        return []
    out = []
    for body, _ in geo["bodies"].values():
        if body.dynamic:
            out += _dynamic(model, trajectory, times)
        elif not body.deforming:
            out += _prescribed(body, times)
    return [(name, values) for name, values in out if name not in present]
