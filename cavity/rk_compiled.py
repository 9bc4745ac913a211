"""Dormand–Prince 8(5,3) (DOP853) pieces compiled with numba, and the dense output of a chain of its steps.

The model-specific loop that calls a right-hand side lives with the model (``exchange.engine.solver``); this
module holds what does not depend on it: the tableau, scipy's error norm and step-size rule, scipy's initial
step, the 7th-order dense output and :class:`DenseSteps`, the Python view of the recorded steps that
:class:`cavity.integration.Trajectory` holds as a segment. Everything mirrors ``scipy.integrate.DOP853``
(Hairer, Nørsett & Wanner, *Solving ODEs I*, II.4 and II.10), so a compiled run takes the same steps as
``solve_ivp(method="DOP853")`` up to round-off.

Step record layout (one row per accepted step, ``3 + 8 n`` floats): t_old [s], h [s], t_rec [s] (the step's
end, or the event time that truncated it), y_old (n), F (7, n) (scipy's ``Dop853DenseOutput.F``).
"""
from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
from numba import njit

from .dop853_tableau import tableau

_d = tableau()

__all__ = ["Status", "A", "B", "C", "E3", "E5", "D", "A_EXTRA", "C_EXTRA", "N_STAGES", "DenseSteps", "error_norm",
           "initial_h0", "initial_step", "dense_F", "dense_eval", "step_factor", "SAFETY", "MIN_FACTOR",
           "MAX_FACTOR", "segment_of", "dense_state", "dense_samples"]

N_STAGES = _d.N_STAGES  # 12
A = np.ascontiguousarray(_d.A[:N_STAGES, :N_STAGES])
B = np.ascontiguousarray(_d.A[N_STAGES, :N_STAGES])
C = np.ascontiguousarray(_d.C[:N_STAGES])
E3 = np.ascontiguousarray(_d.E3)
E5 = np.ascontiguousarray(_d.E5)
D = np.ascontiguousarray(_d.D)
A_EXTRA = np.ascontiguousarray(_d.A[N_STAGES + 1:])
C_EXTRA = np.ascontiguousarray(_d.C[N_STAGES + 1:])
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0


class Status(IntEnum):
    """How a compiled integration ended."""
    OK = 0
    STEP_BUDGET = 1  # more steps than allowed
    STEP_TOO_SMALL = 2  # the step size fell below the spacing of floating-point numbers
    RHS_FAILED = 3  # the right-hand side failed (no gas state, a hosted part's exception)
    NOT_FINITE = 4  # a non-finite state
    STALLED = 5  # switches kept firing at one instant
    WALL_BUDGET = 6  # more wall time than allowed


ERROR_EXPONENT = -1.0 / 8.0  # −1/(error estimator order + 1)
RECORD = 3  # floats before y_old in a step record


@njit(cache=True)
def rms_norm(v, scale):
    """sqrt(mean((v/scale)²)) [-] (scipy's ``norm(v / scale)``)."""
    s = 0.0
    for i in range(v.size):
        q = v[i] / scale[i]
        s += q * q
    return math.sqrt(s / v.size)


@njit(cache=True)
def error_norm(K, h, scale):
    """DOP853's error norm of a step of size h from its stages K (13, n) (scipy ``_estimate_error_norm``)."""
    n = scale.size
    e5, e3 = 0.0, 0.0
    for i in range(n):
        a5, a3 = 0.0, 0.0
        for s in range(13):
            a5 += K[s, i] * E5[s]
            a3 += K[s, i] * E3[s]
        a5 /= scale[i]
        a3 /= scale[i]
        e5 += a5 * a5
        e3 += a3 * a3
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@njit(cache=True)
def step_factor(err, rejected_before):
    """Factor on |h| after an accepted step of error norm err < 1 (scipy's rule)."""
    if err == 0.0:
        factor = MAX_FACTOR
    else:
        factor = min(MAX_FACTOR, SAFETY * err ** ERROR_EXPONENT)
    if rejected_before:
        factor = min(1.0, factor)
    return factor


@njit(cache=True)
def initial_step(y0, f0, f1, h0, t_span, max_step, rtol, atol):
    """scipy's ``select_initial_step`` second half: given h0 and f1 = f(t0 + h0, y0 + h0 f0), the first |h|."""
    n = y0.size
    d1, d2 = 0.0, 0.0
    for i in range(n):
        sc = atol[i] + abs(y0[i]) * rtol
        d1 += (f0[i] / sc) ** 2
        d2 += ((f1[i] - f0[i]) / sc) ** 2
    d1 = math.sqrt(d1 / n)
    d2 = math.sqrt(d2 / n) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, t_span, max_step)


@njit(cache=True)
def initial_h0(y0, f0, t_span, rtol, atol):
    """scipy's ``select_initial_step`` first half: the trial step h0 [s]."""
    n = y0.size
    d0, d1 = 0.0, 0.0
    for i in range(n):
        sc = atol[i] + abs(y0[i]) * rtol
        d0 += (y0[i] / sc) ** 2
        d1 += (f0[i] / sc) ** 2
    d0 = math.sqrt(d0 / n)
    d1 = math.sqrt(d1 / n)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    return min(h0, t_span)


@njit(cache=True)
def dense_F(K, h, y_old, y_new, f_new, F):
    """The 7 interpolation rows F (7, n) of a step (scipy ``DOP853._dense_output_impl``); K (16, n) complete."""
    n = y_old.size
    for i in range(n):
        dy = y_new[i] - y_old[i]
        F[0, i] = dy
        F[1, i] = h * K[0, i] - dy
        F[2, i] = 2.0 * dy - h * (f_new[i] + K[0, i])
        for r in range(4):
            acc = 0.0
            for s in range(16):
                acc += D[r, s] * K[s, i]
            F[3 + r, i] = h * acc


@njit(cache=True)
def dense_eval(rec, n, t, out):
    """State at t from one step record (scipy ``Dop853DenseOutput._call_impl``) into out (n,)."""
    t_old, h = rec[0], rec[1]
    x = (t - t_old) / h
    base = RECORD + n
    for i in range(n):
        acc = 0.0
        for k in range(7):
            acc += rec[base + (6 - k) * n + i]
            acc *= x if k % 2 == 0 else 1.0 - x
        out[i] = acc + rec[RECORD + i]


@njit(cache=True)
def segment_of(segs, t):
    """Index of the segment holding t [s]: the last whose start ``segs[:, 2]`` is ≤ t, clipped to the table
    (``np.searchsorted(starts, t, side="right") − 1`` as ``Trajectory.mode_at``)."""
    lo, hi = 0, segs.shape[0]
    while lo < hi:
        mid = (lo + hi) // 2
        if segs[mid, 2] <= t:
            lo = mid + 1
        else:
            hi = mid
    return min(max(lo - 1, 0), segs.shape[0] - 1)


@njit(cache=True)
def dense_state(recs, segs, i, t, y):
    """State at t [s] on segment i into y (n,): the step of :meth:`DenseSteps.__call__` (``searchsorted(ts, t,
    side="left") − 1`` on ts = [t_min, step ends...], clipped), then its dense output."""
    first, end = int(segs[i, 0]), int(segs[i, 1])
    lo, hi = first, end
    while lo < hi:
        mid = (lo + hi) // 2
        if recs[mid, 2] < t:
            lo = mid + 1
        else:
            hi = mid
    k = (1 if segs[i, 2] < t else 0) + (lo - first) - 1
    k = min(max(k, 0), end - first - 1)
    dense_eval(recs[first + k], y.size, t, y)


@njit(cache=True)
def dense_samples(recs, segs, times):
    """(states (len(times), n), segment index per time) of a compiled run's records at ``times`` [s] (sorted or
    not): the segment of each time (:func:`segment_of`), then its step's dense output (:func:`dense_state`)."""
    n_y = (recs.shape[1] - RECORD) // 8
    ys, idx = np.empty((times.size, n_y)), np.empty(times.size, np.int64)
    for r in range(times.size):
        idx[r] = segment_of(segs, times[r])
        dense_state(recs, segs, idx[r], times[r], ys[r])
    return ys, idx


class DenseSteps:
    """Dense output of a chain of recorded DOP853 steps over [t_min, t_max] (an ``OdeSolution`` look-alike).

    Parameters
    ----------
    records : (k, 3 + 8 n) float
        Step records (module docstring).
    t_min, t_max : float
        The segment's start and end [s] (the end may be an event time inside the last step).
    """

    def __init__(self, records: np.ndarray, t_min: float, t_max: float):
        self.t_min, self.t_max = float(t_min), float(t_max)
        self.records = records
        self.ts = None  # views of the records, made on the first call (most segments are never evaluated)

    def _views(self):
        records = self.records
        self.n = (records.shape[1] - RECORD) // 8
        self.t_old = records[:, 0]
        self.h = records[:, 1]
        self.ts = np.concatenate([[self.t_min], records[:, 2]])
        self.y_old = records[:, RECORD:RECORD + self.n]
        self.F = records[:, RECORD + self.n:].reshape(len(records), 7, self.n)

    def __call__(self, t):
        """y at t: (n,) for a scalar t, (n, m) for m times (the step holding t; the left one at a step end)."""
        if self.ts is None:
            self._views()
        scalar = np.ndim(t) == 0
        t = np.atleast_1d(np.asarray(t, dtype=float))
        k = np.clip(np.searchsorted(self.ts, t, side="left") - 1, 0, len(self.h) - 1)
        x = ((t - self.t_old[k]) / self.h[k])[:, None]
        y = np.zeros((t.size, self.n))
        for i, f in enumerate(self.F[k].transpose(1, 0, 2)[::-1]):
            y += f
            y *= x if i % 2 == 0 else 1.0 - x
        y += self.y_old[k]
        return y[0] if scalar else y.T
