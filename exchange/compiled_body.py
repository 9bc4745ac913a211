"""The dynamic body on the compiled path: its equation of motion, its seat contact's force, the hard contact's
reaction, the seat's switches (kind 13 the seat, kind 14 a kink of the force) and what they do.

The equation of motion and the seat's modes of :mod:`cases.model.scene_network` (its module docstring), on the laws
of :mod:`exchange.contact_laws` (the kernels the outputs call too). Arrays of the model tuple
(:func:`exchange.compiled.lower`):

- ``M[25]`` (3 + 11,) float: 1 if the body has a contact (else 0), 1 while hard contact holds the body on the
  seat (the discrete state), the force scale of the seat switch [N], then the seat's law vector
  (:data:`exchange.contact_laws.SEAT_PARAMETERS`);
- ``M[26]`` (n, 4) the seat's node table (g0 [m], σ, area [m²], reachable);
- ``M[27]`` (k,) the displacements [m] at which the force has a kink (:meth:`cases.model.seat_contact.SeatContact.
  thresholds`).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .compiled_rhs import states
from .compiled_tables import P, spline_piece_value
from .contact_laws import HARD, held_side, seat_force

__all__ = ["gas_force", "body_force", "body_rhs", "HAS", "HELD", "SCALE", "LAW", "is_held", "contact_force",
           "reaction", "seat_switch", "seat_event", "seat_watched", "lifting_side"]

HAS, HELD, SCALE, LAW = 0, 1, 2, 3  # entries of M[25]; the law vector starts at LAW


@njit(cache=True, inline="always")
def gas_force(y, ci, tx, ty, ti, st, amb, bd):
    """Force of the gas on the dynamic body along its axis [N] (:meth:`cases.model.scene_network.SceneNetwork.
    gas_force`): (p − p_amb)·dV/ds of the cavity it intrudes into (dV/ds < 0 while intruding) + (p − p_amb)·A of
    its pressure cavity. ``bd``: offset, mass, gravity, pushed cavity (−1), pressure cavity (−1), pressure area,
    stiffness, preload (:func:`exchange.compiled.lower`)."""
    s = y[int(bd[0])]
    force = 0.0
    pushed, other = int(bd[3]), int(bd[4])
    if pushed >= 0:
        force += (st[pushed, P] - amb[0]) * spline_piece_value(tx, ty, ti, ci[pushed, 3], s, ci[pushed, 9])[1]
    if other >= 0:
        force += (st[other, P] - amb[0]) * bd[5]
    return force


@njit(cache=True, inline="always")
def body_force(y, ci, tx, ty, ti, st, amb, bd):
    """Force on the dynamic body along its axis from the gas and the spring [N]: :func:`gas_force` − preload −
    k·s."""
    return gas_force(y, ci, tx, ty, ti, st, amb, bd) - bd[7] - bd[6] * y[int(bd[0])]


@njit(cache=True)
def body_rhs(y, dy, ci, tx, ty, ti, st, amb, bd, contact):
    """ds/dt = v, dv/dt = g + F/m of the dynamic body:
    F = :func:`body_force` + ``contact`` (the seat's force [N], :func:`contact_force`)."""
    k = int(bd[0])
    force = body_force(y, ci, tx, ty, ti, st, amb, bd) + contact
    dy[k] = y[k + 1]
    dy[k + 1] = bd[2] + force / bd[1]


@njit(cache=True, inline="always")
def is_held(M):
    """Hard contact holds the body on its seat now (s and v frozen)."""
    return M[25][HELD] != 0.0


@njit(cache=True, inline="always")
def contact_force(M, y):
    """Force of the seat on the free body along its axis [N] (:meth:`cases.model.seat_contact.SeatContact.force`);
    0 without contact."""
    sp = M[25]
    if sp[HAS] == 0.0:
        return 0.0
    k = int(M[24][0])
    return seat_force(y[k], y[k + 1], M[26], sp[LAW:])


@njit(cache=True)
def reaction(M, y):
    """Hard contact held: the seat's reaction F_c [N] (> 0 compressive) balancing the other forces at rest, on the
    states in ``M[17]``: −σ_held·(F_gas + F_spring + m·g)."""
    bd = M[24]
    k = int(bd[0])
    net = body_force(y, M[7], M[4], M[5], M[6], M[17], M[14], bd) + bd[1] * bd[2]
    return -held_side(y[k], M[26], M[25][LAW:]) * net


@njit(cache=True)
def seat_switch(M, kind, j, y):
    """Kind 13: F_c/F_scale while held (fires at lift-off), −g_min/L while free (fires at impact);
    kind 14: (s − s_j)/L on kink j. L is the seat size [m]; the states in ``M[17]`` are current."""
    sp, nodes = M[25], M[26]
    s, size = y[int(M[24][0])], sp[LAW + 10]
    if kind == 14:
        return (s - M[27][j]) / size
    if sp[HELD] != 0.0:
        return reaction(M, y) / sp[SCALE]
    g_min = math.inf
    for i in range(nodes.shape[0]):
        if nodes[i, 3] != 0.0:
            g_min = min(g_min, nodes[i, 0] + nodes[i, 1] * s)
    return -g_min / size


@njit(cache=True)
def lifting_side(M, y):
    """σ when the free body rests on its hard seat (v = 0 exactly, a closed node), else 0: its turning-point
    switch is then watched for the return, direction −σ (its acceleration there is zero to round-off, so a probe of
    v = 0 would take its direction from a rounding error)."""
    sp = M[25]
    k = int(M[24][0])
    if sp[HAS] == 0.0 or int(sp[LAW]) != HARD or sp[HELD] != 0.0 or y[k + 1] != 0.0:
        return 0.0
    return held_side(y[k], M[26], sp[LAW:])


@njit(cache=True)
def seat_watched(M, kind):
    """The switch exists in the current discrete state: the
    turning point (kind 10) and the kinks of a hard contact (14) only while the body is free."""
    held = M[25][HELD] != 0.0
    if kind == 10:
        return not held
    if kind == 14:
        return not (held and int(M[25][LAW]) == HARD)
    return True


@njit(cache=True)
def seat_event(M, kind, t, y, seg_end):
    """A seat switch fired at t: lift-off frees the body; an
    impact of the approaching body sets s to the touching position and v to 0 in ``y`` (perfectly plastic
    kinematic contact) and holds it if the reaction is compressive. A kink changes nothing."""
    sp, nodes = M[25], M[26]
    if kind != 13:
        return
    if sp[HELD] != 0.0:
        sp[HELD] = 0.0
        return
    k = int(M[24][0])
    first, g_min = -1, math.inf
    for i in range(nodes.shape[0]):
        g = nodes[i, 0] + nodes[i, 1] * y[k]
        if nodes[i, 3] != 0.0 and g < g_min:
            first, g_min = i, g
    if first < 0 or -nodes[first, 1] * y[k + 1] <= 0.0:  # not approaching: the gap has just opened
        return
    y[k], y[k + 1] = -nodes[first, 0] / nodes[first, 1], 0.0
    t_in = np.nextafter(seg_end, -np.inf) if t >= seg_end else t
    rows, breaks, linear, Mm, tx, ty, ti, ci, cf = M[:9]
    states(rows, breaks, linear, Mm, tx, ty, ti, ci, cf, t_in, y, M[16], M[17], M[18], M[19])
    sp[HELD] = 1.0 if reaction(M, y) > 0.0 else 0.0
