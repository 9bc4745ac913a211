"""The start of a segment on the compiled engine: the equalised exchanges, the dynamic body's area intervals and
volume-spline pieces, a DELTA LEAKAGE AREA opened by time on an area that follows the dynamic body, and which
switches are watched in which direction (``cavity.integration._directions``). Both integrators call these: the
compiled DOP853 (:func:`exchange.compiled_solver.solve`) and scipy's methods (:mod:`exchange.lowered_system`)."""
from __future__ import annotations

import numpy as np
from numba import njit

from .compiled_body import lifting_side
from .compiled_kernels import rhs, switches
from .compiled_modes import lock_pieces, rederive_intervals, watched
from .compiled_rhs import base_area

__all__ = ["begin_segment", "directions"]


@njit(cache=True, inline="always")
def _kink(kind):
    """A switch at a kink of the right-hand side in the state (choke, reversal, orifice join, a table row): its
    event changes neither the state nor the function."""
    return kind == 0 or kind == 1 or kind == 7 or kind == 11 or kind == 12


@njit(cache=True)
def directions(M, kinds, js, t, y, seg_end, last_q, last_t, last_dir, near):
    """(watched switch indices, their directions) at a segment start: away from each switch's current sign; the
    switch that has just fired for the opposite crossing; a switch within ``near`` of zero against its trend along
    the flow (not at all if it does not move). After a kink's switch fired (:func:`_kink`: a function of the state
    that the event leaves as it is), ``near`` grows to 4 times its value at the restart (at most 1e3·``near``): the
    state there is integrated afresh to the event time located on the step's dense output, and a low-order dense
    output (Radau's) leaves the fired switch up to ~1e3·rtol off zero; a twin that crossed at the same instant (two
    identical vents) has the same value and would otherwise fire again at once, in turn."""
    nsw, n = kinds.size, y.size
    vals, pvals = np.empty(nsw), np.empty(nsw)
    wq, wd = np.empty(nsw, np.int64), np.empty(nsw)
    switches(M, kinds, js, t, y, seg_end, vals)
    if last_q >= 0 and t == last_t and _kink(kinds[last_q]):
        near = max(near, min(4.0 * abs(vals[last_q]), 1e3 * near))
    probed, nw = False, 0
    for q in range(nsw):
        if not watched(M, kinds[q], js[q]):
            continue  # the switch of another discrete state
        if kinds[q] == 8 or kinds[q] == 9 or kinds[q] == 15 or kinds[q] == 16:  # it leaves through that end only
            d = 1.0 if kinds[q] == 8 or kinds[q] == 15 else -1.0
        elif kinds[q] == 10 and lifting_side(M, y) != 0.0:  # freed at rest on its seat: it can only return
            d = -lifting_side(M, y)
        elif q == last_q and t == last_t:
            d = -last_dir
        elif abs(vals[q]) > near:
            d = 1.0 if vals[q] < 0 else -1.0
        else:
            if not probed:
                dt = 1e-9 * max(abs(t), 1e-6)
                fp = np.empty(n)
                rhs(M, t, y, fp, seg_end)
                switches(M, kinds, js, t + dt, y + dt * fp, seg_end, pvals)
                probed = True
            trend = pvals[q] - vals[q]
            d = -1.0 if trend > 0 else (1.0 if trend < 0 else 0.0)
        if d != 0.0:
            wq[nw], wd[nw] = q, d
            nw += 1
    return wq[:nw], wd[:nw]


@njit(cache=True)
def begin_segment(M, kinds, js, t, y, seg_end):
    """Segment start from (t, y): re-derive the dynamic body's area intervals and lock its volume-spline pieces, set a
    DELTA LEAKAGE AREA opened by time once past its open time, and equalise (hold closed) the two-way exchanges
    whose sides agree to :data:`exchange.equalised.EQUALISED_BELOW` (their release switch watches for the network
    driving them apart); returns the mode bitmask (bit j: exchange j equalised)."""
    eq, ei = M[20], M[12]
    one_k, one_j, val = np.empty(1, np.int64), np.empty(1, np.int64), np.empty(1)
    if M[24][0] >= 0.0:
        rederive_intervals(M, y)
        lock_pieces(M, y)
    ef, iv, tx, ty, ti = M[13], M[23], M[4], M[5], M[6]
    for j in range(eq.size):  # a DELTA LEAKAGE AREA opened by time: its area at the open time, once past it
        if ei[j, 14] == 1 and ef[j, 9] != ef[j, 9] and t >= ef[j, 2]:
            ef[j, 9] = base_area(ei, ef, iv, tx, ty, ti, j, ef[j, 2])
    mode = 0
    for j in range(eq.size):
        if ei[j, 5] == 1 and eq[j] == 0:
            one_k[0], one_j[0] = 2, j
            switches(M, one_k, one_j, t, y, seg_end, val)
            if val[0] < 0.0:
                eq[j] = 1
        if eq[j] == 1:
            mode += 1 << j
    return mode
