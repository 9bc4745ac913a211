"""Contact results of a run: history columns, CPRESS per seat node, and the contact part of summary.json.

CPRESS follows Abaqus: the contact pressure of a closed node (the law's pressure plus damping, or for a held hard
contact the reaction shared by the closed nodes), the viscous damping pressure of an open node within the damping
clearance (status "VD"), 0 otherwise. A hard-contact impact is an impulse, not a pressure: it is reported by its
speed, not in CPRESS.
"""
from __future__ import annotations

import math
import time

import numpy as np

from cavity.integration import SolverError
from exchange.contact import suggest_mu0
from exchange.readback.values import body_values, load_mode
from cases.model.seat_contact import STATUS_CODES

__all__ = ["contact_columns", "contact_rows", "nodal_history", "contact_summary", "nodal_state"]


def contact_columns(model) -> list:
    c = getattr(model.network, "contact", None)
    if c is None:
        return []
    return [f"{c.body}.displacement [m]", f"{c.body}.velocity [m/s]", f"{c.name}.force [N]",
            f"{c.name}.max_cpress [Pa]"]


def nodal_state(fast, t, y):
    """(CPRESS per node, status per node, seat force on the body [N]) at (t, y) in the discrete state loaded in
    ``fast``, the network's :class:`exchange.engine.engine.Engine` (:func:`exchange.readback.values.load_mode`)."""
    net = fast.network
    c, k = net.contact, net.body_offset
    reaction = body_values(fast, t, y)[2] if net.held else 0.0
    p, status = c.nodal(y[k], y[k + 1], reaction)
    force = reaction * c.held_sigma(y[k]) if net.held else c.force(y[k], y[k + 1])
    return p, status, force


def _nodal_states(model, traj, times, deadline: float = math.inf):
    """(t, y, CPRESS, status, seat force) at each of ``times``, each in the mode of its segment; stops with a
    SolverError once ``time.perf_counter()`` passes ``deadline``."""
    fast = model.network.compiled_solver()
    ys, loaded = traj.sample(times), None
    for r, (t, y) in enumerate(zip(times, ys)):
        if r % 256 == 255 and time.perf_counter() > deadline:
            raise SolverError(f"out of wall time (max_wall) writing history rows: {r} of {len(times)} done; "
                              "raise time.output_interval")
        mode = traj.mode_at(t)
        if mode is not loaded:
            load_mode(fast, mode)
            loaded = mode
        yield (t, y) + nodal_state(fast, t, y)
    load_mode(fast, traj.modes[-1])


def contact_rows(model, traj, times, deadline: float = math.inf) -> np.ndarray:
    """The contact columns (:func:`contact_columns`) at ``times`` [s], (k, 4)."""
    k = model.network.body_offset
    return np.array([[y[k], y[k + 1], force, float(p.max())]
                     for t, y, p, _, force in _nodal_states(model, traj, times, deadline)]).reshape(-1, 4)


def nodal_history(model, traj, times) -> dict:
    """CPRESS [Pa] and status codes per seat node at ``times`` (k, n), with the seat's nodes and areas."""
    c = model.network.contact
    cp, st = np.zeros((len(times), len(c.nodes))), np.zeros((len(times), len(c.nodes)), dtype=np.uint8)
    for i, (_, _, p, status, _) in enumerate(_nodal_states(model, traj, times)):
        cp[i], st[i] = p, status
    return {"time": np.asarray(times, dtype=float), "cpress": cp, "status": st, "nodes": c.nodes,
            "faces": c.faces, "nodal_area": c.areas,
            "status_codes": np.array(list(STATUS_CODES), dtype="U6")}


def contact_summary(model, traj) -> dict:
    """Peak CPRESS, reseats and lift-offs, opening pressures against the preload's prediction, suggested μ0."""
    net = model.network
    c, k = net.contact, net.body_offset
    ts = np.unique(np.concatenate([traj.step_times, [t for t, _ in traj.events], [traj.t_final]]))
    peak, peak_t, peak_node, vd_peak, speed = 0.0, 0.0, -1, 0.0, 0.0
    for t, y, p, status, _ in _nodal_states(model, traj, ts):
        i = int(np.argmax(p))
        if p[i] > peak:
            peak, peak_t, peak_node = float(p[i]), float(t), i
        vd = p[status == STATUS_CODES["VD"]]
        vd_peak = max(vd_peak, float(np.abs(vd).max()) if vd.size else 0.0)
        speed = max(speed, abs(float(y[k + 1])))
    log = list(net.contact_log)
    impacts = [e for e in log if e[1] in ("impact", "touch")]
    lifts = [e for e in log if e[1] in ("lift-off", "separate")]
    out = {"body": c.body, "seat nodes": int(len(c.nodes)), "seat area [m^2]": c.seat_area,
           "peak CPRESS [Pa]": peak, "peak CPRESS time [s]": peak_t, "peak CPRESS node": peak_node,
           "peak viscous (VD) pressure [Pa]": vd_peak, "peak body speed [m/s]": speed,
           "reseats": len(impacts), "lift-offs": len(lifts),
           "reseat times [s]": [e[0] for e in impacts], "impact speeds [m/s]": [e[2] for e in impacts],
           "lift-off times [s]": [e[0] for e in lifts],
           "suggested_mu0 [Pa s/m]": suggest_mu0(peak, speed) if peak > 0 and speed > 0 else None,
           "suggested_mu0 rule": "0.01 * peak CPRESS / peak body speed (exchange.contact.suggest_mu0)",
           "nodal CPRESS": "contact.npz: time (k,), cpress (k, n) [Pa], status (k, n) 0 open 1 closed 2 VD"}
    f = net.forces
    if f.cavity is not None and lifts:
        m = net.body.motion
        predicted = net.ambient.pressure + (f.preload - m.mass * m.gravity) / f.area
        opened = [e[3] for e in lifts]
        out["opening pressure predicted [Pa]"] = predicted
        out["opening pressures [Pa]"] = opened
        out["opening pressure max relative error [-]"] = max(abs(p - predicted) / predicted for p in opened)
    return out
