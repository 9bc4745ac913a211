"""Contact results of a run: history columns, CPRESS per seat node, and the contact part of summary.json.

CPRESS follows Abaqus: the contact pressure of a closed node (the law's pressure plus damping, or for a held hard
contact the reaction shared by the closed nodes), the viscous damping pressure of an open node within the damping
clearance (status "VD"), 0 otherwise. A hard-contact impact is an impulse, not a pressure: it is reported by its
speed, not in CPRESS.
"""
from __future__ import annotations

import numpy as np

from exchange.contact import suggest_mu0
from cases.model.seat_contact import STATUS_CODES

__all__ = ["contact_columns", "contact_row", "nodal_history", "contact_summary", "nodal_state"]


def contact_columns(model) -> list:
    c = getattr(model.network, "contact", None)
    if c is None:
        return []
    return [f"{c.body}.displacement [m]", f"{c.body}.velocity [m/s]", f"{c.name}.force [N]",
            f"{c.name}.max_cpress [Pa]"]


def nodal_state(net, t, y):
    """(CPRESS per node, status per node, seat force on the body [N]) in the network's current mode."""
    c, k = net.contact, net.body_offset
    reaction = net.reaction(t, y) if net.held else 0.0
    p, status = c.nodal(y[k], y[k + 1], reaction)
    force = reaction * net.contact.held_sigma(y[k]) if net.held else c.force(y[k], y[k + 1])
    return p, status, force


def contact_row(model, t, y) -> list:
    """The contact columns at (t, y); the network's mode must already be restored."""
    net = model.network
    if getattr(net, "contact", None) is None:
        return []
    p, _, force = nodal_state(net, t, y)
    k = net.body_offset
    return [y[k], y[k + 1], force, float(p.max())]


def nodal_history(model, traj, times) -> dict:
    """CPRESS [Pa] and status codes per seat node at ``times`` (k, n), with the seat's nodes and areas."""
    net = model.network
    c = net.contact
    ys = traj.sample(times)
    cp, st = np.zeros((len(times), len(c.nodes))), np.zeros((len(times), len(c.nodes)), dtype=np.uint8)
    for i, (t, y) in enumerate(zip(times, ys)):
        net.restore(traj.mode_at(t))
        cp[i], st[i], _ = nodal_state(net, t, y)
    net.restore(traj.modes[-1])
    return {"time": np.asarray(times, dtype=float), "cpress": cp, "status": st, "nodes": c.nodes,
            "faces": c.faces, "nodal_area": c.areas,
            "status_codes": np.array(list(STATUS_CODES), dtype="U6")}


def contact_summary(model, traj) -> dict:
    """Peak CPRESS, reseats and lift-offs, opening pressures against the preload's prediction, suggested μ0."""
    net = model.network
    c, k = net.contact, net.body_offset
    ts = np.unique(np.concatenate([traj.step_times, [t for t, _ in traj.events], [traj.t_final]]))
    ys = traj.sample(ts)
    peak, peak_t, peak_node, vd_peak, speed = 0.0, 0.0, -1, 0.0, 0.0
    for t, y in zip(ts, ys):
        net.restore(traj.mode_at(t))
        p, status, _ = nodal_state(net, t, y)
        i = int(np.argmax(p))
        if p[i] > peak:
            peak, peak_t, peak_node = float(p[i]), float(t), i
        vd = p[status == STATUS_CODES["VD"]]
        vd_peak = max(vd_peak, float(np.abs(vd).max()) if vd.size else 0.0)
        speed = max(speed, abs(float(y[k + 1])))
    net.restore(traj.modes[-1])
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
