"""A lowered network's values at one (t, y) in the discrete state its model arrays hold: the cavity states, each
exchange's flow and area, the dynamic body's gas force, acceleration and seat reaction.

These are the kernels the right-hand side runs (:func:`exchange.compiled_rhs.states`,
:func:`~exchange.compiled_rhs.exchange_flow`, :func:`~exchange.compiled_rhs.exchange_area`,
:func:`exchange.compiled_body.gas_force`, :func:`exchange.compiled_body.reaction`, :func:`exchange.compiled_kernels.rhs`)
called once for a point, for results and the Python API (:mod:`exchange.point_values`); nothing is restated.
Inputs are read at t itself (no segment end: the right limit at a table break).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .compiled_body import body_force, gas_force, reaction
from .compiled_rhs import exchange_area, exchange_flow, states
from .compiled_kernels import rhs

__all__ = ["point_states", "point_exchanges", "point_body"]


@njit(cache=True)
def point_states(M, t, y):
    """Fill the state scratch ``M[17]`` (:mod:`exchange.compiled_rhs` columns) at (t, y); False when a temperature
    solve failed (the row then holds the first guess)."""
    rows, breaks, linear, Mm, tx, ty, ti, ci, cf = M[:9]
    return states(rows, breaks, linear, Mm, tx, ty, ti, ci, cf, t, y, M[16], M[17], M[18], M[19])


@njit(cache=True)
def point_exchanges(M, t, y, flows, areas):
    """Each exchange's signed mass flow [kg/s] (up → down) into ``flows`` and flow area [m^2] into ``areas`` at
    (t, y); False when a temperature solve failed."""
    ok = point_states(M, t, y)
    ei, ef, tx, ty, ti, amb = M[12], M[13], M[4], M[5], M[6], M[14]
    for j in range(ei.shape[0]):
        flows[j] = exchange_flow(ei, ef, M[20], M[21], M[23], tx, ty, ti, M[17], amb, j, t)
        areas[j] = exchange_area(ei, ef, M[21], M[23], tx, ty, ti, j, t)
    return ok


@njit(cache=True)
def point_body(M, t, y, out):
    """The dynamic body at (t, y): ``out[0]`` the gas force along its axis [N] ((p − p_amb)·dV/ds of the cavity it
    intrudes into + (p − p_amb)·A of its pressure cavity), ``out[1]`` its acceleration [m/s^2] (the right-hand
    side's dv/dt: 0 while held on its seat), ``out[2]`` the reaction [N] a hard seat holding it at rest would give
    (> 0 compressive; 0 without a closed node), ``out[3]`` the gas and spring force on it [N] (no gravity, no
    contact). False when a temperature solve failed."""
    dy = np.empty_like(y)
    ok = rhs(M, t, y, dy, math.inf)
    ok = point_states(M, t, y) and ok
    out[0] = gas_force(y, M[7], M[4], M[5], M[6], M[17], M[14], M[24])
    out[1] = dy[int(M[24][0]) + 1]
    out[2] = reaction(M, y)
    out[3] = body_force(y, M[7], M[4], M[5], M[6], M[17], M[14], M[24])
    return ok
