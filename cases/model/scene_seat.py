"""The dynamic body against its seat: its forces from the engine, its rest position and the log of impacts and
lift-offs of a :class:`cases.model.scene_network.SceneNetwork` (the contact laws are :mod:`exchange.contact.laws`,
the seat's switches and what they do :mod:`exchange.engine.body`)."""
from __future__ import annotations

import numpy as np

from exchange.readback.values import body_values

__all__ = ["body_forces", "rest_position", "log_contact_events"]


def body_forces(net, t, y) -> tuple:
    """(gas force, acceleration, reaction of a hard seat holding it at rest, gas and spring force) of the
    dynamic body at (t, y) [N, m/s^2, N, N], from the compiled engine (:func:`exchange.readback.values.
    body_values`) in the network's current discrete state."""
    engine = net.engine()
    engine.load_discrete_state()
    return body_values(engine, t, y)


def rest_position(net, y) -> float:
    """Displacement s [m] at which a body at rest on a penalty or softened seat is in static equilibrium.

    A body that starts at rest touching its seat while the other forces push it in (a preloaded poppet) starts
    at the overclosure that carries them, so it does not ring on the contact spring; otherwise 0. The root of
    the net force F(s) = F_applied(s) + m·g + F_seat(s, v=0) is bracketed by doubling steps into the seat and
    found by Brent's method to round-off.
    """
    k, m, c = net.body_offset, net.body.motion, net.contact
    sigma = c.held_sigma(0.0)  # the seat pushes the body along +sigma; 0: no closed node at s = 0
    y = np.array(y, dtype=float)

    def force(s):
        y[k] = s
        return body_forces(net, 0.0, y)[3] + m.mass * m.gravity + c.force(s, 0.0)

    if sigma == 0.0 or force(0.0) * sigma >= 0.0:
        return 0.0
    inside, step = 0.0, 1e-12 * c.size
    while force(-sigma * step) * sigma < 0.0:
        inside, step = step, 2.0 * step
        if step > c.size:
            raise ValueError(f"contact {c.name!r}: the seat cannot carry the forces pressing {c.body!r} into it "
                             f"within an overclosure of {c.size:.3g} m (stiffness too low?)")
    from scipy.optimize import brentq

    s0 = float(brentq(force, -sigma * inside, -sigma * step, xtol=1e-15 * c.size, rtol=4 * np.finfo(float).eps))
    force(s0)  # leaves the body state at s0
    return s0


def log_contact_events(net, events) -> None:
    """The contact log of a run, from its events: (t, label, state before, state after, mode before) each
    (:func:`exchange.engine.body.seat_event`: an impact sets s to the touching position and v to 0)."""
    k, c = net.body_offset, net.contact
    for t, label, before, after, mode in events:
        kind = label.rpartition(":")[2]
        if kind == "seat" and mode.held:
            net.contact_log.append((t, "lift-off", 0.0, _pressure(net, t, before)))
        elif kind == "seat":
            reach = np.flatnonzero(c.reach)
            i = reach[int(np.argmin(c.gaps(before[k])[reach]))]
            approach = -c.sigma[i] * before[k + 1]
            if approach > 0.0:
                net.contact_log.append((t, "impact", float(approach), _pressure(net, t, after)))
        elif kind.startswith("kink-"):
            _log_touch(net, t, before)


def _pressure(net, t, y) -> float:
    f = net.forces.cavity
    return float(net.states(t, y)[f].pressure) if f is not None else float("nan")


def _log_touch(net, t, y):
    """Penalty/softened contact: record first touch and full separation (the kinks where g_min = 0)."""
    k, c = net.body_offset, net.contact
    reach = np.flatnonzero(c.reach)
    i = reach[int(np.argmin(c.gaps(y[k])[reach]))]
    if abs(c.gaps(y[k])[i]) <= 1e-9 * c.size:
        approach = float(-c.sigma[i] * y[k + 1])
        net.contact_log.append((t, "touch" if approach > 0 else "separate", approach, _pressure(net, t, y)))
