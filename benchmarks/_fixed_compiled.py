"""Fixed-step forward Euler / Heun on the compiled network right-hand side (benchmark-only code).

The fair fixed-step baseline for the compiled DOP853 default: the same numba right-hand side
(``exchange.engine.rhs.rhs``), inputs read at t itself (no segment end), no error control, no stops at
table kinks. States at the (sorted) evaluation times are interpolated linearly between steps inside the loop,
so a million steps need no million-row history.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from exchange.engine.rhs import rhs


@njit(cache=True)
def fixed_step_compiled(M, y0, t_end, n_steps, heun, grid):
    """States (len(grid), n) at the sorted times ``grid`` of n_steps fixed steps of Euler (or Heun) [SI]."""
    n = y0.size
    h = t_end / n_steps
    y, y_new, k1, k2, ytmp = y0.copy(), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    out = np.full((grid.size, n), np.nan)
    g = 0
    while g < grid.size and grid[g] <= 0.0:
        out[g] = y
        g += 1
    for i in range(n_steps):
        t = i * h
        rhs(M, t, y, k1, math.inf)
        if heun:
            for j in range(n):
                ytmp[j] = y[j] + h * k1[j]
            rhs(M, t + h, ytmp, k2, math.inf)
            for j in range(n):
                y_new[j] = y[j] + 0.5 * h * (k1[j] + k2[j])
        else:
            for j in range(n):
                y_new[j] = y[j] + h * k1[j]
        t1 = (i + 1) * h
        while g < grid.size and grid[g] <= t1:
            w = (grid[g] - t) / h
            for j in range(n):
                out[g, j] = y[j] + w * (y_new[j] - y[j])
            g += 1
        y[:] = y_new
        if not np.isfinite(y[0]):
            return out
    while g < grid.size:  # times within round-off of t_end
        out[g] = y
        g += 1
    return out
