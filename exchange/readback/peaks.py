"""The peak pressure of each cavity of a run on the compiled path, found in one numba call.

The search of :func:`cases.results.readback.cavity_peaks` on the compiled DOP853's records (the largest pressure at
every step end and segment start, refined between its neighbours by scipy's bounded scalar search,
``minimize_scalar(method="bounded")``, ported line by line in :func:`bounded_minimum_of_minus_p`) on the engine's
cavity states (:func:`exchange.engine.gas.states`): a search of ~25–60 pressure evaluations costs ~1 µs instead of
~0.5 ms through Python. Pressure does not depend on the discrete state, so no mode is needed.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from cavity.rk_compiled import RECORD, dense_state, segment_of
from exchange.engine.arrays import copy_into
from exchange.engine.gas import reset_temperature_guesses, states
from exchange.engine.layout import StateColumn

__all__ = ["pressure_at", "bounded_minimum_of_minus_p", "peak_pressures", "peaks"]

SQRT_EPS = math.sqrt(2.2e-16)  # as scipy's _minimize_scalar_bounded
GOLDEN_MEAN = 0.5 * (3.0 - math.sqrt(5.0))
MAXITER = 500
# a largest value at the record's first or last time is refined only if p is larger this fraction of the step inside
EDGE_PROBE = 1e-7


@njit(cache=True)
def pressure_at(M, recs, segs, c, t, y):
    """Pressure [Pa] of cavity c at t [s] on the dense output (``y`` scratch); NaN when the temperature solve
    fails."""
    dense_state(recs, segs, segment_of(segs, t), t, y)
    if not states(M, t, y):
        return math.nan
    return M.state[c, StateColumn.P]


@njit(cache=True)
def _step(a, b, xf, xm, nfc, fulc, fx, fnfc, ffulc, e, rat, tol1, tol2):
    """(e, rat) of the next trial point xf + rat: a parabolic step through the three best points when it is
    acceptable, else a golden-section step (scipy ``_minimize_scalar_bounded``, inner part)."""
    golden = True
    if abs(e) > tol1:
        golden = False
        r = (xf - nfc) * (fx - ffulc)
        q = (xf - fulc) * (fx - fnfc)
        p = (xf - fulc) * q - (xf - nfc) * r
        q = 2.0 * (q - r)
        if q > 0.0:
            p = -p
        q = abs(q)
        r = e
        e = rat
        if abs(p) < abs(0.5 * q * r) and p > q * (a - xf) and p < q * (b - xf):
            rat = (p + 0.0) / q
            x = xf + rat
            if (x - a) < tol2 or (b - x) < tol2:
                rat = tol1 * (np.sign(xm - xf) + (1.0 if xm - xf == 0 else 0.0))
        else:
            golden = True
    if golden:
        e = a - xf if xf >= xm else b - xf
        rat = GOLDEN_MEAN * e
    return e, rat


@njit(cache=True)
def bounded_minimum_of_minus_p(M, recs, segs, c, x1, x2, xatol, y):
    """(max p [Pa], its t [s]) of cavity c on [x1, x2] [s]: scipy's ``_minimize_scalar_bounded`` (Brent's
    golden-section and parabolic search, maxiter 500) on −p(t), line by line."""
    a, b = x1, x2
    fulc = a + GOLDEN_MEAN * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    fx = -pressure_at(M, recs, segs, c, xf, y)
    num = 1
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = SQRT_EPS * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    while abs(xf - xm) > (tol2 - 0.5 * (b - a)):
        e, rat = _step(a, b, xf, xm, nfc, fulc, fx, fnfc, ffulc, e, rat, tol1, tol2)
        x = xf + (np.sign(rat) + (1.0 if rat == 0 else 0.0)) * max(abs(rat), tol1)
        fu = -pressure_at(M, recs, segs, c, x, y)
        num += 1
        if fu <= fx:
            if x >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = x, fu
        else:
            if x < xf:
                a = x
            else:
                b = x
            if fu <= fnfc or nfc == xf:
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = x, fu
            elif fu <= ffulc or fulc == xf or fulc == nfc:
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = SQRT_EPS * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= MAXITER:
            break
    return -fx, xf


@njit(cache=True)
def peak_pressures(M, recs, segs, ts):
    """(ok, (nc, 2) array of [peak pressure [Pa], its time [s]]) per cavity: the largest pressure at the
    candidate times ``ts`` [s] (sorted), refined between its neighbours as
    :func:`cases.results.readback.refine_peak` does (an end only if the pressure rises inside)."""
    nc, m = M.cavity_int.shape[0], ts.size
    y = np.empty((recs.shape[1] - RECORD) // 8)
    reset_temperature_guesses(M)
    ps = np.empty((m, nc))
    ok = True
    for r in range(m):
        ok &= not math.isnan(pressure_at(M, recs, segs, 0, ts[r], y))
        copy_into(ps[r], M.state[:, StateColumn.P])
    out = np.empty((nc, 2))
    for c in range(nc):
        k = np.argmax(ps[:, c])
        out[c, 0], out[c, 1] = ps[k, c], ts[k]
        lo, hi = ts[max(k - 1, 0)], ts[min(k + 1, m - 1)]
        if hi > lo and (k == 0 or k == m - 1):  # at an end: searched only if the pressure rises into the record
            t_in = ts[k] + (EDGE_PROBE if k == 0 else -EDGE_PROBE) * (hi - lo)
            if not pressure_at(M, recs, segs, c, t_in, y) > out[c, 0]:
                continue
        if hi > lo:
            p, t = bounded_minimum_of_minus_p(M, recs, segs, c, lo, hi, 1e-14 * max(1.0, hi), y)
            if p > out[c, 0]:
                out[c, 0], out[c, 1] = p, t
    for c in range(nc):
        ok &= not math.isnan(out[c, 0])
    return ok, out


def peaks(engine, traj, ts) -> list | None:
    """[(peak pressure [Pa], its time [s])] per cavity of a compiled trajectory over the candidate times ``ts``
    [s], or None when it did not run compiled or a temperature solve failed (then search in Python)."""
    recs = getattr(traj, "compiled_records", None)
    if engine is None or traj.path != "compiled" or recs is None:
        return None
    engine.unlock_pieces()  # volume splines on the pieces that hold s
    ok, out = peak_pressures(engine.model, recs[0], recs[1], np.ascontiguousarray(ts, dtype=float))
    return [(float(p), float(t)) for p, t in out] if ok else None
