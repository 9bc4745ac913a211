"""The dynamic body on the engine: its equation of motion, its seat contact's force, the hard contact's reaction,
the seat's switches (SEAT: lift-off and impact; SEAT_KINK: a kink of the force) and what they do.

The equation of motion and the seat's modes of :mod:`cases.model.scene_network` (its module docstring), on the laws
of :mod:`exchange.contact.laws` (the kernels the outputs call too): m·dv/dt = m·g + F_gas + F_spring + F_contact
along the body's axis, F_gas = (p − p_amb)·dV/ds of the cavity it intrudes into + (p − p_amb)·A of its pressure
cavity, F_spring = −(preload + k·s). While hard contact holds it on the seat, s and v are frozen and the contact
force is the reaction balancing the others.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from exchange.contact.laws import HARD, SeatLaw, SeatNode, held_side, seat_force

from .gas import states
from .layout import AmbientColumn, BodyColumn, CavityInt, SeatState, StateColumn, SwitchKind
from .tables import spline_piece_value

__all__ = ["gas_force", "body_force", "body_rhs", "is_held", "contact_force", "reaction", "seat_switch",
           "seat_event", "seat_watched", "lifting_side", "has_body"]

B = BodyColumn


@njit(cache=True)
def has_body(M):
    return M.body[B.OFFSET] >= 0.0


@njit(cache=True)
def gas_force(M, y):
    """Force of the gas on the dynamic body along its axis [N], on the states in ``M.state``: (p − p_amb)·dV/ds of
    the cavity it intrudes into (dV/ds < 0 while intruding) + (p − p_amb)·A of its pressure cavity."""
    bd, st, ci = M.body, M.state, M.cavity_int
    s = y[int(bd[B.OFFSET])]
    p_amb = M.ambient[AmbientColumn.P]
    force = 0.0
    pushed, other = int(bd[B.PUSHED]), int(bd[B.PRESSURE_CAVITY])
    if pushed >= 0:
        slope = spline_piece_value(M.table_x, M.table_y, M.table_index, ci[pushed, CavityInt.VOLUME_TABLE], s,
                                   ci[pushed, CavityInt.PIECE])[1]
        force += (st[pushed, StateColumn.P] - p_amb) * slope
    if other >= 0:
        force += (st[other, StateColumn.P] - p_amb) * bd[B.PRESSURE_AREA]
    return force


@njit(cache=True)
def body_force(M, y):
    """Force on the dynamic body along its axis from the gas and the spring [N]: :func:`gas_force` − preload −
    k·s."""
    bd = M.body
    return gas_force(M, y) - bd[B.PRELOAD] - bd[B.STIFFNESS] * y[int(bd[B.OFFSET])]


@njit(cache=True)
def is_held(M):
    """Hard contact holds the body on its seat now (s and v frozen)."""
    return M.seat_state[SeatState.HELD] != 0.0


@njit(cache=True)
def contact_force(M, y):
    """Force of the seat on the free body along its axis [N] (:func:`exchange.contact.laws.seat_force`); 0 without
    contact."""
    if M.seat_state[SeatState.HAS] == 0.0:
        return 0.0
    k = int(M.body[B.OFFSET])
    return seat_force(y[k], y[k + 1], M.seat_nodes, M.seat_law)


@njit(cache=True)
def body_rhs(M, y, dy):
    """ds/dt = v, dv/dt = g + F/m of the free dynamic body, F = :func:`body_force` + :func:`contact_force`."""
    bd = M.body
    k = int(bd[B.OFFSET])
    force = body_force(M, y) + contact_force(M, y)
    dy[k] = y[k + 1]
    dy[k + 1] = bd[B.GRAVITY] + force / bd[B.MASS]


@njit(cache=True)
def reaction(M, y):
    """Hard contact held: the seat's reaction F_c [N] (> 0 compressive) balancing the other forces at rest, on the
    states in ``M.state``: −σ_held·(F_gas + F_spring + m·g)."""
    bd = M.body
    net = body_force(M, y) + bd[B.MASS] * bd[B.GRAVITY]
    return -held_side(y[int(bd[B.OFFSET])], M.seat_nodes, M.seat_law) * net


@njit(cache=True)
def seat_switch(M, kind, j, y):
    """SEAT: F_c/F_scale while held (fires at lift-off), −g_min/L while free (fires at impact); SEAT_KINK:
    (s − s_j)/L on kink j. L is the seat size [m]; the states in ``M.state`` are current."""
    nodes = M.seat_nodes
    s, size = y[int(M.body[B.OFFSET])], M.seat_law[SeatLaw.SEAT_SIZE]
    if kind == SwitchKind.SEAT_KINK:
        return (s - M.seat_kinks[j]) / size
    if is_held(M):
        return reaction(M, y) / M.seat_state[SeatState.FORCE_SCALE]
    g_min = math.inf
    for i in range(nodes.shape[0]):
        if nodes[i, SeatNode.REACH] != 0.0:
            g_min = min(g_min, nodes[i, SeatNode.GAP] + nodes[i, SeatNode.SIDE] * s)
    return -g_min / size


@njit(cache=True)
def lifting_side(M, y):
    """σ when the free body rests on its hard seat (v = 0 exactly, a closed node), else 0: its turning-point switch
    is then watched for the return, direction −σ (its acceleration there is zero to round-off, so a probe of v = 0
    would take its direction from a rounding error)."""
    k = int(M.body[B.OFFSET])
    if M.seat_state[SeatState.HAS] == 0.0 or int(M.seat_law[SeatLaw.KIND]) != HARD or is_held(M) \
            or y[k + 1] != 0.0:
        return 0.0
    return held_side(y[k], M.seat_nodes, M.seat_law)


@njit(cache=True)
def seat_watched(M, kind):
    """The body's switch exists in the current discrete state: the turning point and the kinks of a hard contact
    only while the body is free."""
    if kind == SwitchKind.TURN:
        return not is_held(M)
    if kind == SwitchKind.SEAT_KINK:
        return not (is_held(M) and int(M.seat_law[SeatLaw.KIND]) == HARD)
    return True


@njit(cache=True)
def seat_event(M, t, y, seg_end):
    """The seat switch fired at t: lift-off frees the body; an impact of the approaching body sets s to the
    touching position and v to 0 in ``y`` (perfectly plastic kinematic contact) and holds it if the reaction is
    compressive."""
    nodes = M.seat_nodes
    if is_held(M):
        M.seat_state[SeatState.HELD] = 0.0
        return
    k = int(M.body[B.OFFSET])
    first, g_min = -1, math.inf
    for i in range(nodes.shape[0]):
        g = nodes[i, SeatNode.GAP] + nodes[i, SeatNode.SIDE] * y[k]
        if nodes[i, SeatNode.REACH] != 0.0 and g < g_min:
            first, g_min = i, g
    if first < 0 or -nodes[first, SeatNode.SIDE] * y[k + 1] <= 0.0:  # not approaching: the gap has just opened
        return
    y[k], y[k + 1] = -nodes[first, SeatNode.GAP] / nodes[first, SeatNode.SIDE], 0.0
    states(M, np.nextafter(seg_end, -np.inf) if t >= seg_end else t, y)
    M.seat_state[SeatState.HELD] = 1.0 if reaction(M, y) > 0.0 else 0.0
