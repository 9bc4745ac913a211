"""The lowered network's right-hand side and switch values on its model tuple ``M`` (:func:`exchange.compiled.lower`):
the network's rates (:func:`exchange.compiled_rhs.network_rhs`) with the dynamic body's equation of motion
(:func:`exchange.compiled_body.body_rhs`), and every switch kind of :mod:`exchange.compiled_modes` at (t, y)."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .compiled_body import body_rhs, contact_force, is_held
from .compiled_modes import body_switch
from .compiled_rhs import network_rhs, states, switch_value
from .compiled_sources import kink_value

__all__ = ["rhs", "switches"]


@njit(cache=True)
def rhs(M, t, y, out, seg_end):
    """Network right-hand side into out; False when a temperature solve failed."""
    rows, breaks, linear, Mm, tx, ty, ti, ci, cf, ii, if_, irows, ei, ef, amb, ledger, T_guess, st, n, row, eq = M[:21]
    ok = network_rhs(t, y, out, seg_end, rows, breaks, linear, Mm, tx, ty, ti, ci, cf, ii, if_, irows, ei, ef,
                     amb, ledger, T_guess, st, n, row, eq, M[21], M[23])
    if M[24][0] >= 0.0 and not is_held(M):
        body_rhs(y, out, ci, tx, ty, ti, st, amb, M[24], contact_force(M, y))
    return ok


@njit(cache=True)
def switches(M, kinds, js, t, y, seg_end, vals):
    """Values of switch functions (kinds, js) at (t, y), inputs read as the right-hand side reads them; the
    pop-hold switch (kind 6) is (t − due)/hold at the raw t, due = hold start + hold time."""
    rows, breaks, linear, Mm, tx, ty, ti, ci, cf, ii, if_, irows, ei, ef, amb, ledger, T_guess, st, n, row, eq = M[:21]
    t_in = np.nextafter(seg_end, -np.inf) if t >= seg_end else t
    states(rows, breaks, linear, Mm, tx, ty, ti, ci, cf, t_in, y, T_guess, st, n, row)
    for q in range(kinds.size):
        j = js[q]
        if kinds[q] == 11 or kinds[q] == 12:
            vals[q] = kink_value(kinds[q], j, ei, tx, ti, st, amb)
        elif kinds[q] == 17:
            vals[q] = switch_value(17, j, ci, ei, ef, st, amb)
        elif kinds[q] >= 8:  # the dynamic body and its seat
            vals[q] = body_switch(M, kinds[q], j, y)
        elif kinds[q] == 6:  # 1 (never watched) when not holding
            h = ef[j, 5]
            vals[q] = (t - (M[22][j] + h)) / h if h > 0.0 and not math.isnan(M[22][j]) else 1.0
        else:
            vals[q] = switch_value(kinds[q], j, ci, ei, ef, st, amb)
