"""A lowered network's values at one (t, y) in the discrete state its model holds: each exchange's flow and area,
the dynamic body's gas force, acceleration and seat reaction.

These are the kernels the right-hand side runs (:func:`exchange.engine.gas.states`, :func:`exchange.engine.flows.
exchange_flow`, :func:`~exchange.engine.flows.exchange_area`, :func:`exchange.engine.body.gas_force`,
:func:`exchange.engine.body.reaction`, :func:`exchange.engine.rhs.rhs`) called once for a point, for results and the
Python API (:mod:`exchange.readback.values`); nothing is restated. Inputs are read at t itself (no segment end: the
right limit at a table break).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from exchange.engine.body import body_force, gas_force, reaction
from exchange.engine.flows import exchange_area, exchange_flow
from exchange.engine.gas import states
from exchange.engine.layout import BodyColumn
from exchange.engine.rhs import rhs

__all__ = ["point_exchanges", "point_body"]


@njit(cache=True)
def point_exchanges(M, t, y, flows, areas):
    """Each exchange's signed mass flow [kg/s] (first side → second) into ``flows`` and flow area [m^2] into
    ``areas`` at (t, y); False when a temperature solve failed."""
    ok = states(M, t, y)
    for j in range(M.exchange_int.shape[0]):
        flows[j] = exchange_flow(M, j, t)
        areas[j] = exchange_area(M, j, t)
    return ok


@njit(cache=True)
def point_body(M, t, y, out):
    """The dynamic body at (t, y): ``out[0]`` the gas force along its axis [N], ``out[1]`` its acceleration [m/s^2]
    (the right-hand side's dv/dt: 0 while held on its seat), ``out[2]`` the reaction [N] a hard seat holding it at
    rest would give (> 0 compressive; 0 without a closed node), ``out[3]`` the gas and spring force on it [N] (no
    gravity, no contact). False when a temperature solve failed."""
    dy = np.empty_like(y)
    ok = rhs(M, t, y, dy, math.inf)
    ok = states(M, t, y) and ok
    out[0] = gas_force(M, y)
    out[1] = dy[int(M.body[BodyColumn.OFFSET]) + 1]
    out[2] = reaction(M, y)
    out[3] = body_force(M, y)
    return ok
