"""The whole integration of a lowered network in one numba call: DOP853 steps, stops, switches, event restarts.

Mirrors :func:`cavity.integration.integrate` with ``method="DOP853"`` step for step: one piece per segment
between stops (scipy's DOP853 with dense output: same initial step, error norm, step-size rule), the switch
functions watched away from their current sign (:func:`exchange.engine.segment.directions`), an event located by
Brent's method on the step's dense output (``solve_ivp``'s ``brentq`` with xtol = rtol = 4·eps), the state at the
event integrated to it from the start of the step, the step budget counted on every accepted step and switches that
keep firing at one instant stopped. ``M`` is the lowered model (:mod:`exchange.engine.layout`).
"""
from __future__ import annotations

import math
import time

import numpy as np
from numba import njit, objmode

from cavity.rk_compiled import (A, A_EXTRA, B, C, C_EXTRA, ERROR_EXPONENT, MIN_FACTOR, N_STAGES, RECORD, SAFETY,
                                Status, dense_eval, dense_F, error_norm, initial_h0, initial_step, step_factor)

from .arrays import copy_into
from .layout import segment_blocks
from .modes import on_event, record_segment
from .rhs import rhs
from .segment import begin_segment, directions
from .switches import switches

__all__ = ["solve", "piece", "root_on_step", "clock"]

OK, STEP_BUDGET, STEP_TOO_SMALL, RHS_FAILED, NOT_FINITE, STALLED, WALL_BUDGET = (
    Status.OK, Status.STEP_BUDGET, Status.STEP_TOO_SMALL, Status.RHS_FAILED, Status.NOT_FINITE, Status.STALLED,
    Status.WALL_BUDGET)
WALL_CHECK_EVERY = 1024  # steps between two looks at the clock (an object-mode call of ~1 µs)
MAX_EVENTS_AT_ONE_TIME = 20  # cavity.integration.MAX_EVENTS_AT_ONE_TIME
NO_BUDGET = 1 << 62  # the tail to an event is not budgeted (as in cavity.integration)
EPS4 = 4.0 * np.finfo(np.float64).eps


@njit(cache=True)
def clock():
    """time.perf_counter() [s], from compiled code."""
    with objmode(now="float64"):
        now = time.perf_counter()
    return now


@njit(cache=True)
def _grow(buf, need):
    if need <= buf.shape[0]:
        return buf
    new = np.empty((max(need, 2 * buf.shape[0]), buf.shape[1]))
    for i in range(buf.shape[0]):
        copy_into(new[i], buf[i])
    return new


@njit(cache=True)
def _record(buf, cnt, t, h, t_new, y, F):
    """Append a step record (cavity.rk_compiled layout); returns the buffer (grown if needed)."""
    n = y.size
    buf = _grow(buf, cnt[0] + 1)
    rec = buf[cnt[0]]
    rec[0], rec[1], rec[2] = t, h, t_new
    copy_into(rec[RECORD:], y)
    copy_into(rec[RECORD + n:], F.ravel())
    cnt[0] += 1
    return buf


@njit(cache=True)
def _switch_on_step(M, one, rec, n, t, seg_end, ybuf, value):
    dense_eval(rec, n, t, ybuf)
    switches(M, one, t, ybuf, seg_end, value)
    return value[0]


@njit(cache=True)
def root_on_step(M, q, rec, n, xa, xb, seg_end):
    """Root of switch q along one step's dense output by Brent's method (scipy ``brentq``, xtol = rtol = 4 eps)."""
    ybuf, one, ov = np.empty(n), np.full(1, q, np.int64), np.empty(1)
    xpre, xcur = xa, xb
    fpre = _switch_on_step(M, one, rec, n, xpre, seg_end, ybuf, ov)
    fcur = _switch_on_step(M, one, rec, n, xcur, seg_end, ybuf, ov)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    xblk, fblk, spre, scur = 0.0, 0.0, 0.0, 0.0
    for _ in range(100):
        if fpre != 0.0 and fcur != 0.0 and (math.copysign(1.0, fpre) != math.copysign(1.0, fcur)):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (EPS4 + EPS4 * abs(xcur)) / 2.0
        sbis = (xblk - xcur) / 2.0
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre, scur = sbis, sbis
        else:
            spre, scur = sbis, sbis
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = _switch_on_step(M, one, rec, n, xcur, seg_end, ybuf, ov)
    return xcur


@njit(cache=True)
def _combination(y, h, weights, K, count, out):
    """out = y + h·Σ_{r < count} weights[r]·K[r] (a Runge–Kutta stage state, summed in scipy's order)."""
    for i in range(y.size):
        acc = 0.0
        for r in range(count):
            acc += weights[r] * K[r, i]
        out[i] = y[i] + h * acc


@njit(cache=True)
def _stages(M, t, y, h, K, ytmp, y_new, seg_end, stats):
    """The 12 stages and the new state of one DOP853 step; K[12] = f(t + h, y_new). False if the RHS failed."""
    for s in range(1, N_STAGES):
        _combination(y, h, A[s], K, s, ytmp)
        stats[0] += 1
        if not rhs(M, t + C[s] * h, ytmp, K[s], seg_end):
            return False
    _combination(y, h, B, K, N_STAGES, y_new)
    stats[0] += 1
    return rhs(M, t + h, y_new, K[N_STAGES], seg_end)


@njit(cache=True)
def _dense_stages(M, t, y, h, K, ytmp, seg_end, stats):
    """The three extra stages of DOP853's dense output, into K[13..15]. False if the RHS failed."""
    for e in range(3):
        s = N_STAGES + 1 + e
        _combination(y, h, A_EXTRA[e], K, s, ytmp)
        stats[0] += 1
        if not rhs(M, t + C_EXTRA[e] * h, ytmp, K[s], seg_end):
            return False
    return True


@njit(cache=True)
def _step(M, t, y, f, h_abs, min_step, t_bound, K, ytmp, y_new, rtol, atol, seg_end, stats):
    """One accepted DOP853 step from (t, y) with f = f(t, y), trying |h| = h_abs first (scipy ``RungeKutta.
    _step_impl``): returns (status, h, t_new, next |h|); y_new and K hold the step. A failed stage (no gas state)
    retries the step ``MIN_FACTOR`` shorter, to the minimum step (then RHS_FAILED); scipy's would stop."""
    n = y.size
    scale = np.empty(n)
    rejected = failed = False
    while True:
        if h_abs < min_step:
            return (RHS_FAILED if failed else STEP_TOO_SMALL), 0.0, t, h_abs
        t_new = min(t + h_abs, t_bound)
        h = t_new - t
        h_abs = abs(h)
        copy_into(K[0], f)
        failed = not _stages(M, t, y, h, K, ytmp, y_new, seg_end, stats)
        if failed:  # a stage left the states the gas can take (a trial step too long): retry shorter
            h_abs *= MIN_FACTOR
            rejected = True
            continue
        for i in range(n):
            scale[i] = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
        err = error_norm(K, h, scale)
        if err < 1.0:
            return OK, h, t_new, h_abs * step_factor(err, rejected)
        h_abs *= max(MIN_FACTOR, SAFETY * err ** ERROR_EXPONENT)
        rejected = True


@njit(cache=True)
def first_crossing(M, wq, wd, g, gnew, rec, n, t, t_new, seg_end):
    """(index into wq, time) of the earliest watched switch crossing in its direction over the step [t, t_new]
    (scipy ``find_active_events`` and ``handle_events``), or (−1, t_new)."""
    first, t_ev = -1, t_new
    for q in range(wq.size):
        up = g[q] <= 0.0 and gnew[q] >= 0.0
        down = g[q] >= 0.0 and gnew[q] <= 0.0
        if (up and wd[q] > 0) or (down and wd[q] < 0):
            root = root_on_step(M, wq[q], rec, n, t, t_new, seg_end)
            if first < 0 or root < t_ev:
                first, t_ev = q, root
    return first, t_ev


@njit(cache=True)
def piece(M, wq, wd, t0, y0, t_bound, seg_end, rtol, atol, max_step, max_steps, stats, buf, cnt, deadline):
    """DOP853 from (t0, y0) to t_bound watching switches wq for crossings in directions wd.

    Returns (status, t_end, y_end, watched index that fired or −1, t_k, y_k, buf): at an event, t_end is its time,
    y_end the dense state there, (t_k, y_k) the start of the step that holds it.
    """
    n = y0.size
    K, F = np.empty((16, n)), np.empty((7, n))
    ytmp, y_new, y_old = np.empty(n), np.empty(n), np.empty(n)
    y, f = y0.copy(), np.empty(n)
    nw = wq.size
    g, gnew = np.empty(nw), np.empty(nw)
    stats[0] += 2
    if not rhs(M, t0, y, f, seg_end):
        return RHS_FAILED, t0, y, -1, t0, y, buf
    h0 = initial_h0(y, f, t_bound - t0, rtol, atol)
    for i in range(n):
        ytmp[i] = y[i] + h0 * f[i]
    if not rhs(M, t0 + h0, ytmp, K[1], seg_end):
        return RHS_FAILED, t0, y, -1, t0, y, buf
    h_abs = initial_step(y, f, K[1], h0, t_bound - t0, max_step, rtol, atol)
    if nw:
        switches(M, wq, t0, y, seg_end, g)
    t = t0
    while True:
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        h_abs = max_step if h_abs > max_step else (min_step if h_abs < min_step else h_abs)
        status, h, t_new, h_abs = _step(M, t, y, f, h_abs, min_step, t_bound, K, ytmp, y_new, rtol, atol, seg_end,
                                        stats)
        if status != OK:
            return status, t, y, -1, t, y, buf
        if not _dense_stages(M, t, y, h, K, ytmp, seg_end, stats):
            return RHS_FAILED, t, y, -1, t, y, buf
        dense_F(K, h, y, y_new, K[N_STAGES], F)
        buf = _record(buf, cnt, t, h, t_new, y, F)
        rec = buf[cnt[0] - 1]
        stats[1] += 1
        if stats[1] > max_steps:
            return STEP_BUDGET, t_new, y_new, -1, t, y, buf
        if stats[1] % WALL_CHECK_EVERY == 0 and deadline < math.inf and clock() > deadline:
            return WALL_BUDGET, t_new, y_new, -1, t, y, buf
        for i in range(n):
            if not math.isfinite(y_new[i]):
                return NOT_FINITE, t_new, y_new, -1, t, y, buf
        if nw:
            switches(M, wq, t_new, y_new, seg_end, gnew)
            first, t_ev = first_crossing(M, wq, wd, g, gnew, rec, n, t, t_new, seg_end)
            if first >= 0:
                rec[2] = t_ev
                y_ev = np.empty(n)
                dense_eval(rec, n, t_ev, y_ev)
                return OK, t_ev, y_ev, first, t, y, buf
            copy_into(g, gnew)
        copy_into(y_old, y)
        copy_into(y, y_new)
        copy_into(f, K[N_STAGES])
        t = t_new
        if t >= t_bound:
            return OK, t, y, -1, t, y_old, buf


@njit(cache=True)
def _keep_piece(M, segs, nseg, status, first, end, t, t_end, mode):
    """(segments, count) with the accepted steps (records first..end, t to t_end) of the piece a run stopped in
    as one more segment, so that a failed run keeps them; not after a non-finite step (its record holds it)."""
    if status == NOT_FINITE or end <= first:
        return segs, nseg
    segs = _grow(segs, nseg + 1)
    record_segment(M, segs, nseg, first, end, t, t_end, mode)
    return segs, nseg + 1


@njit(cache=True)
def solve(M, y0, t0, stops, rtol, atol, max_step, max_steps, near, deadline):
    """Integrate from t0 through every stop (the last is the end), stopping with WALL_BUDGET once
    ``time.perf_counter()`` passes ``deadline`` (looked at every WALL_CHECK_EVERY steps).

    Returns (status, t, y, step records, segments (:func:`exchange.engine.modes.record_segment`), events (m, 3):
    time, switch, direction, stats [rhs calls, steps, restarts, events]).
    """
    n = y0.size
    buf, cnt = np.empty((64, RECORD + 8 * n)), np.zeros(1, np.int64)
    segs, evs = np.empty((16, segment_blocks(M.open_state.size)[4])), np.empty((16, 3))
    nseg, nev = 0, 0
    stats = np.zeros(4, np.int64)
    t, y = t0, y0.copy()
    last_q, last_t, last_dir, stalls = np.int64(-1), math.nan, 0.0, 0  # typed: one specialisation of its callees
    empty_i, empty_f = np.empty(0, np.int64), np.empty(0)
    for stop in stops:
        while t < stop:
            if max_steps - stats[1] <= 0:
                return STEP_BUDGET, t, y, buf[:cnt[0]], segs[:nseg], evs[:nev], stats
            mode = begin_segment(M, t, y, stop)
            wq, wd = directions(M, t, y, stop, last_q, last_t, last_dir, near)
            first = cnt[0]
            status, t_end, y_end, qw, t_k, y_k, buf = piece(M, wq, wd, t, y, stop, stop, rtol, atol, max_step,
                                                            max_steps, stats, buf, cnt, deadline)
            stats[2] += 1
            if status != OK:
                segs, nseg = _keep_piece(M, segs, nseg, status, first, cnt[0], t, t_end, mode)
                return status, t_end, y_end, buf[:cnt[0]], segs[:nseg], evs[:nev], stats
            segs = _grow(segs, nseg + 2)
            record_segment(M, segs, nseg, first, cnt[0], t, t_end, mode)
            nseg += 1
            if qw < 0:
                last_q = -1
            else:
                if t_end > t_k:  # the state at the event, integrated to it from the step's start
                    first = cnt[0]
                    status, _, y_end, _, _, _, buf = piece(M, empty_i, empty_f, t_k, y_k, t_end, stop, rtol, atol,
                                                           max_step, np.int64(NO_BUDGET), stats, buf, cnt, math.inf)
                    if status != OK:
                        return status, t_end, y_end, buf[:cnt[0]], segs[:nseg], evs[:nev], stats
                    record_segment(M, segs, nseg, first, cnt[0], t_k, t_end, mode)
                    nseg += 1
                q = wq[qw]
                on_event(M, q, t_end, y_end, stop)
                evs = _grow(evs, nev + 1)
                evs[nev, 0], evs[nev, 1], evs[nev, 2] = t_end, q, wd[qw]
                nev += 1
                stats[3] += 1
                if last_q >= 0 and last_t == t_end:
                    stalls += 1
                    if stalls > MAX_EVENTS_AT_ONE_TIME:
                        return STALLED, t_end, y_end, buf[:cnt[0]], segs[:nseg], evs[:nev], stats
                else:
                    stalls = 0
                last_q, last_t, last_dir = q, t_end, wd[qw]
            t, y = t_end, y_end
    return OK, t, y, buf[:cnt[0]], segs[:nseg], evs[:nev], stats
