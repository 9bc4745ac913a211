"""A compact piecewise cubic for the exact wrapped volume, with a proven error bound.

The exact ΔV(s) = V(s) − V0 (:mod:`cases.model.wrap_exact`) has a knot wherever the contact set or a node's
nearest body plane changes: far too many to stop the integrator at. Where a node switches to another body plane
its closest point jumps, and so does V (the definition's own discontinuity, which no smooth representation
follows): each such jump is first spread linearly over a small ``width`` after it (:func:`smoothed_jumps`, error
computed exactly). The continuous result is replaced by its cubic Hermite interpolant on knots chosen among
its own knots: each piece takes the values at its ends and the one-sided slopes there, so on a stretch without an
exact knot it is the exact cubic. Starting from the ends of the range and of the contact, a piece is split at
the exact knot nearest its middle while

- its largest distance to the target exceeds ``tol`` [m^3] (found exactly: on every exact piece under it the
  difference is a cubic, largest at an end or where its derivative vanishes), or
- the piece's slope (a quadratic) leaves the range of its end slopes by more than ``ring`` [m^2] beyond what the
  exact slope does inside it: the ringing of a global spline near first contact.

Each piece depends only on data at its two ends (no global solve), so nothing rings beyond a piece, and before
first contact the representation is constant with slope exactly 0.
"""
from __future__ import annotations

import numpy as np
from scipy.interpolate import PPoly

__all__ = ["HermiteFit", "hermite_fit", "fit_wrap", "smoothed_jumps", "in_time", "excursion", "overshoot"]


class HermiteFit:
    """ΔV(s) [m^3] as a continuous piecewise cubic: ``knots`` [m], ``values`` [m^3] at them, ``start`` and
    ``end`` [m^2] the slope of each piece at its first and last knot; ``bound`` [m^3] the largest distance to the
    exact ΔV on [knots[0], knots[-1]], ``smoothing`` [m^3] the part of it due to spreading its jumps."""

    def __init__(self, knots, values, start, end, bound, smoothing=0.0):
        self.knots, self.values, self.start, self.end = knots, values, start, end
        self.bound, self.smoothing = bound, smoothing

    def ppoly(self, offset: float = 0.0) -> PPoly:
        """scipy PPoly of ``offset`` + ΔV(s) (coefficients highest power first, per piece)."""
        return PPoly(_hermite(np.diff(self.knots), self.values[:-1] + offset, self.values[1:] + offset,
                              self.start, self.end), self.knots)


def _hermite(h, y0, y1, d0, d1):
    """(4, n) coefficients, highest power first, of the cubics with values y0, y1 and slopes d0, d1 at the ends
    of intervals of widths h."""
    m = (y1 - y0) / h
    return np.stack([(d0 + d1 - 2.0 * m) / h ** 2, (3.0 * m - 2.0 * d0 - d1) / h, d0, y0])


def _knot_data(exact, s):
    """(ΔV, left-limit slope, right-limit slope) at s (ΔV continuous there: the mean of its limits)."""
    vl, dl = exact.value(s, side="left")
    vr, dr = exact.value(s, side="right")
    return 0.5 * (vl + vr), dl, dr


def _errors(exact, k0, k1, y0, y1, d0, d1):
    """Largest |Hermite − exact| over each interval [k0, k1] (arrays), exactly: per exact piece under it the
    difference is a cubic, compared at the ends and its derivative's roots."""
    j0 = np.clip(exact.piece(k0, "right"), 0, len(exact.coef) - 1)
    j1 = np.clip(exact.piece(k1, "left"), 0, len(exact.coef) - 1)
    count = np.maximum(j1 - j0 + 1, 1)
    which = np.repeat(np.arange(len(k0)), count)
    j = j0[which] + np.arange(len(which)) - np.repeat(np.cumsum(count) - count, count)
    a = np.maximum(k0[which], exact.breaks[j])
    b = np.minimum(k1[which], exact.breaks[j + 1])
    h = (k1 - k0)[which]
    # Hermite in τ = s − k0 (coefficients lowest first), exact piece's cubic shifted to the same origin
    dd0, dd1 = d0[which], d1[which]
    H = _hermite(h, y0[which], y1[which], dd0, dd1)[::-1].T
    c = exact.coef[j] / exact.half ** np.arange(4)  # in powers of (s − mid)
    x = k0[which] - exact.mid
    E = np.stack([((c[:, 3] * x + c[:, 2]) * x + c[:, 1]) * x + c[:, 0],
                  (3.0 * c[:, 3] * x + 2.0 * c[:, 2]) * x + c[:, 1], 3.0 * c[:, 3] * x + c[:, 2], c[:, 3]], axis=1)
    D = E - H
    ta, tb = a - k0[which], b - k0[which]
    err = np.maximum(np.abs(_poly(D, ta)), np.abs(_poly(D, tb)))
    qa, qb, qc = 3.0 * D[:, 3], 2.0 * D[:, 2], D[:, 1]
    disc = np.sqrt(np.maximum(qb * qb - 4.0 * qa * qc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        for r in ((-qb + disc) / (2.0 * qa), (-qb - disc) / (2.0 * qa), -qc / qb):
            ok = np.isfinite(r) & (r > ta) & (r < tb)
            err = np.where(ok, np.maximum(err, np.abs(_poly(D, np.where(ok, r, 0.0)))), err)
    out = np.zeros(len(k0))
    np.maximum.at(out, which, err)
    return out


def _poly(c, t):
    return ((c[:, 3] * t + c[:, 2]) * t + c[:, 1]) * t + c[:, 0]



def overshoot(k0, k1, y0, y1, d0, d1):
    """How far each piece's slope leaves the range of its end slopes [m^2] (0 when monotone): on τ ∈ [0, 1] it
    is the quadratic q = d0 + (d1 − d0)τ + 6δτ(1 − τ), δ = m − (d0 + d1)/2, m the mean slope, whose extremum is
    at τ* = 1/2 + (d1 − d0)/(12δ)."""
    delta = (y1 - y0) / (k1 - k0) - 0.5 * (d0 + d1)
    with np.errstate(divide="ignore", invalid="ignore"):
        tau = 0.5 + (d1 - d0) / (12.0 * delta)
    inner = np.isfinite(tau) & (tau > 0.0) & (tau < 1.0)
    tau = np.where(inner, tau, 0.0)
    q = d0 + (d1 - d0) * tau + 6.0 * delta * tau * (1.0 - tau)
    out = np.maximum(q - np.maximum(d0, d1), np.minimum(d0, d1) - q)
    return np.where(inner, np.maximum(out, 0.0), 0.0)


def smoothed_jumps(exact, width: float):
    """(target, smoothing error [m^3]): ``exact`` with each jump of ΔV at b spread linearly over [b − w/2, b + w/2]
    (``width`` w [m], its start held at the first contact so that nothing moves before it): the staircase of
    jumps J becomes Σ j·clip((s − start)/(end − start), 0, 1), continuous. The error is the largest |J_w − J| (at
    the new knots or the jumps) plus the jumps too small to matter (rounding of the running sum), dropped."""
    br = exact.breaks
    vl, _ = exact.value(br, side="left")
    vr, _ = exact.value(br, side="right")
    jump = vr - vl
    jump[0] = jump[-1] = 0.0
    small = np.abs(jump) <= max(1e3 * exact.rounding, 1e-13 * float(np.max(np.abs(vr))))
    dropped = float(np.sum(np.abs(jump[small])))
    jump[small] = 0.0
    k = np.flatnonzero(jump)
    if not k.size:
        return exact, dropped
    moving = np.flatnonzero(np.any(exact.coef != 0.0, axis=1))
    b, j = br[k], jump[k]
    start, end = np.maximum(b - 0.5 * width, br[moving[0]]), b + 0.5 * width
    new = np.unique(np.clip(np.r_[br, start, end], br[0], br[-1]))
    mids = 0.5 * (new[:-1] + new[1:])
    stair = np.cumsum(jump)[np.searchsorted(br, mids, side="right") - 1]  # J on each new piece
    const, slope = _ramps(start, end, j, mids)
    coef = exact.coef[np.clip(exact.piece(mids), 0, len(exact.coef) - 1)].copy()
    coef[:, 0] += const + slope * exact.mid - stair
    coef[:, 1] += slope * exact.half
    target = type(exact)(new, coef, exact.mid, exact.half, exact.rounding)
    ends = np.r_[new[:-1], new[1:]]
    pj = np.r_[np.arange(len(mids)), np.arange(len(mids))]
    error = float(np.max(np.abs(const[pj] + slope[pj] * ends - stair[pj])))
    return target, error + dropped


def _ramps(start, end, j, s):
    """(a, c) with Σ j·clip((s − start)/(end − start), 0, 1) = a + c·s at each s (no ramp end strictly inside a
    piece holding s): the ramps ended count whole, those under way linearly."""
    rate = j / (end - start)
    by_start, by_end = np.argsort(start), np.argsort(end)
    started = np.searchsorted(start[by_start], s)  # start < s
    ended = np.searchsorted(end[by_end], s)  # end < s
    cum = lambda v, order: np.r_[0.0, np.cumsum(v[order])]  # noqa: E731
    whole = cum(j, by_end)[ended]
    slope = cum(rate, by_start)[started] - cum(rate, by_end)[ended]
    const = whole - (cum(rate * start, by_start)[started] - cum(rate * start, by_end)[ended])
    return const, slope


def excursion(slopes, br, k0, k1, d0, d1):
    """How far the exact slope's limits at the knots strictly inside each [k0, k1] (``slopes``: left and right
    limit at every exact knot, in order) leave the range of the piece's end slopes d0, d1 [m^2]: the geometry's
    own departure from monotone there (−inf where there is no knot inside: the piece is exact)."""
    i0, i1 = 2 * np.searchsorted(br, k0, "right"), 2 * np.searchsorted(br, k1, "left")
    idx = np.minimum(np.c_[i0, np.maximum(i1, i0 + 1)].ravel(), len(slopes))
    seq = np.r_[slopes, 0.0]
    hi = np.maximum.reduceat(seq, idx)[::2]
    lo = np.minimum.reduceat(seq, idx)[::2]
    out = np.maximum(np.maximum(hi - np.maximum(d0, d1), np.minimum(d0, d1) - lo), 0.0)
    return np.where(i1 > i0, out, -np.inf)


def _split_points(br, k0, k1, width):
    """The exact knot nearest the middle of each [k0, k1], at least ``width`` from its ends (nan if none)."""
    mid = 0.5 * (k0 + k1)
    q = np.clip(np.searchsorted(br, mid), 1, len(br) - 1)
    near = np.where(np.abs(br[q - 1] - mid) < np.abs(br[q] - mid), br[q - 1], br[q])
    return np.where((near > k0 + width) & (near < k1 - width), near, np.nan)


def hermite_fit(exact, tol: float, ring: float, max_knots: int = 20000) -> HermiteFit:
    """Adaptive :class:`HermiteFit` of a continuous ``exact`` (:class:`cases.model.wrap_exact.ExactWrap`) on its
    range: see the module; past ``max_knots`` the split stops and ``bound`` says what was reached."""
    br = exact.breaks
    moving = np.flatnonzero(np.any(exact.coef != 0.0, axis=1))
    knots = {float(br[0]), float(br[-1])}
    if moving.size:
        knots |= {float(br[moving[0]]), float(br[moving[-1] + 1])}
    knots = np.array(sorted(knots))
    slopes = np.c_[exact.value(br, side="left")[1], exact.value(br, side="right")[1]].ravel()
    todo = np.ones(len(knots) - 1, dtype=bool)
    errs = np.zeros(len(knots) - 1)
    while todo.any():
        y, dl, dr = _knot_data(exact, knots)
        i = np.flatnonzero(todo)
        k0, k1, y0, y1, d0, d1 = knots[i], knots[i + 1], y[i], y[i + 1], dr[i], dl[i + 1]
        errs[i] = _errors(exact, k0, k1, y0, y1, d0, d1)
        room = excursion(slopes, br, k0, k1, d0, d1)  # −inf: no exact knot inside, the piece is exact
        ringing = (room >= 0.0) & (overshoot(k0, k1, y0, y1, d0, d1) > ring + np.maximum(room, 0.0))
        bad = i[(errs[i] > tol) | ringing]
        near = _split_points(br, knots[bad], knots[bad + 1], 1e-9 * (br[-1] - br[0]))
        ok = np.isfinite(near)
        if not ok.any() or len(knots) + ok.sum() > max_knots:
            break
        split = np.zeros(len(knots) - 1, dtype=bool)
        split[bad[ok]] = True
        knots = np.sort(np.r_[knots, near[ok]])
        # each split interval becomes two new ones to check; the others keep their errors
        todo = np.repeat(split, np.where(split, 2, 1))
        errs = np.repeat(errs, np.where(split, 2, 1))
    y, dl, dr = _knot_data(exact, knots)
    return HermiteFit(knots, y, dr[:-1], dl[1:], float(errs.max(initial=0.0)) + exact.rounding)


def fit_wrap(exact, tol: float, ring: float, width: float, max_knots: int = 20000) -> HermiteFit:
    """The :class:`HermiteFit` of the exact ΔV with its jumps spread over ``width`` [m]
    (:func:`smoothed_jumps`); its ``bound`` [m^3] holds against the exact ΔV (fit error + smoothing error)."""
    target, smoothing = smoothed_jumps(exact, width)
    fit = hermite_fit(target, tol, ring, max_knots)
    fit.bound += smoothing
    fit.smoothing = smoothing
    return fit


def in_time(fit: HermiteFit, motion_times, displacement, lo: float, hi: float, offset: float) -> PPoly:
    """The fit composed with a piecewise-linear displacement s(t) on [lo, hi] (t [s], knots of s(t) among
    ``motion_times``): V(t) = offset + ΔV(s(t)) is a cubic between those knots and the times s(t) crosses a knot
    of the fit, and each such piece is exactly the Hermite interpolant of its end values and one-sided slopes (a
    cubic of a linear function is a cubic). Held (slope 0) where s(t) leaves the fit's range."""
    times = np.unique(np.r_[lo, hi, [t for t in motion_times if lo < t < hi]])
    s = np.array([displacement(t) for t in times])
    pieces = [times]
    for t0, t1, a, b in zip(times[:-1], times[1:], s[:-1], s[1:]):
        if a != b:
            k = fit.knots[(fit.knots > min(a, b)) & (fit.knots < max(a, b))]
            pieces.append(t0 + (k - a) * (t1 - t0) / (b - a))
    knots = np.unique(np.concatenate(pieces))
    knots = knots[np.r_[True, np.diff(knots) > 1e-12 * (hi - lo)]]
    knots[-1] = hi
    seg = np.clip(np.searchsorted(times, knots[:-1], side="right") - 1, 0, len(times) - 2)
    speed = np.diff(s) / np.diff(times)
    ends = [s[seg] + (e - times[seg]) * speed[seg] for e in (knots[:-1], knots[1:])]  # s(t) on each piece
    pp = fit.ppoly(offset)
    x0, x1 = fit.knots[0], fit.knots[-1]
    j = np.clip(np.searchsorted(fit.knots, 0.5 * (ends[0] + ends[1]), side="right") - 1, 0, len(fit.knots) - 2)
    inside = (np.minimum(ends[0], ends[1]) >= x0) & (np.maximum(ends[0], ends[1]) <= x1)
    y, d = [], []
    for e in ends:
        x = np.clip(e, x0, x1) - fit.knots[j]
        c = pp.c[:, j]
        y.append(((c[0] * x + c[1]) * x + c[2]) * x + c[3])
        d.append(np.where(inside, (3.0 * c[0] * x + 2.0 * c[1]) * x + c[2], 0.0) * speed[seg])
    return PPoly(_hermite(np.diff(knots), y[0], y[1], d[0], d[1]), knots)
