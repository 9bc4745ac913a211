"""The lowest kernels of the compiled path: tables (piecewise linear, steps, cubic splines), volumes and the
columns of the state scratch (the gas's rows: :mod:`cavity.gas_rows`); shared by :mod:`exchange.compiled_rhs`
and :mod:`exchange.compiled_sources` (array layout: :mod:`exchange.compiled_rhs`).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from cavity.tables import interpolate, interpolation_slope
from cavity.tolerances import R_UNIVERSAL as R_U

from .lowered_columns import UNLOCKED

P, TT, RHO, RG, GAM, H, V, DV, MASS, FR = 0, 1, 2, 3, 4, 5, 6, 7, 8, 9  # columns of the state scratch


@njit(cache=True, inline="always")
def table_value(tx, ty, ti, k, x):
    """Table k at x: :func:`cavity.tables.interpolate` on its rows (``ti[k]``: first row, rows, linear ends)."""
    s, n = ti[k, 0], ti[k, 1]
    return interpolate(tx[s:s + n], ty[s:s + n], ti[k, 2] != 0, x)


@njit(cache=True, inline="always")
def table_slope(tx, ty, ti, k, x):
    """dy/dx of table k at x: :func:`cavity.tables.interpolation_slope` on its rows."""
    s, n = ti[k, 0], ti[k, 1]
    return interpolation_slope(tx[s:s + n], ty[s:s + n], ti[k, 2] != 0, x)


@njit(cache=True, inline="always")
def step_value(tx, ty, ti, k, x):
    """Step table k at x: ty[i] for tx[i] <= x < tx[i+1] (right limit at a step; tx[0] is -inf)
    (:meth:`cases.model.area_track.AreaTrack.area_in` on a fixed surface)."""
    s, n = ti[k, 0], ti[k, 1]
    i = np.searchsorted(tx[s:s + n], x, side="right") - 1
    return ty[s + max(i, 0)]


@njit(cache=True, inline="always")
def spline_value(tx, ty, ti, k, x):
    """(value, slope) of the cubic spline k at x: knots in table k, coefficients (4 per piece, highest power
    first, as scipy's PPoly) in table k + 1; held at its ends, slope 0 outside (:class:`cases.model.wrapped_volume.
    WrappedVolume`)."""
    s, n, c = ti[k, 0], ti[k, 1], ti[k + 1, 0]
    inside = tx[s] <= x <= tx[s + n - 1]
    x = min(max(x, tx[s]), tx[s + n - 1])
    i = min(max(np.searchsorted(tx[s:s + n], x, side="right") - 1, 0), n - 2)
    value, slope = _cubic(ty, c + 4 * i, x - tx[s + i])
    return value, slope if inside else 0.0


@njit(cache=True, inline="always")
def _cubic(ty, q, d):
    """(value, slope) of the cubic piece whose coefficients (highest power first) start at ty[q], d past its knot."""
    return ((ty[q] * d + ty[q + 1]) * d + ty[q + 2]) * d + ty[q + 3], (3.0 * ty[q] * d + 2.0 * ty[q + 1]) * d + ty[q + 2]


@njit(cache=True, inline="always")
def spline_piece_value(tx, ty, ti, k, x, p):
    """(value, slope) of the cubic spline k at x on its piece p held over the whole segment, extended beyond the
    piece's knots by one piece width (farther, as :func:`spline_value`: the extended cubic may leave the data
    there) (−1: below the first knot, the value there and slope 0; n − 1: above the last; UNLOCKED: on the
    piece holding x, :func:`spline_value`). The switches at the piece's knots end the segment, so a step never
    straddles a knot's jump in the third derivative (:func:`exchange.compiled_modes.lock_pieces`)."""
    if p == UNLOCKED:
        return spline_value(tx, ty, ti, k, x)
    s, n, c = ti[k, 0], ti[k, 1], ti[k + 1, 0]
    if p < 0 or p >= n - 1:  # held at the end knot
        return spline_value(tx, ty, ti, k, tx[s] if p < 0 else tx[s + n - 1])[0], 0.0
    w = tx[s + p + 1] - tx[s + p]
    if x < tx[s + p] - w or x > tx[s + p + 1] + w:  # a trial stage far off (a step to be rejected or cut)
        return spline_value(tx, ty, ti, k, x)
    return _cubic(ty, c + 4 * p, x - tx[s + p])


@njit(cache=True, inline="always")
def side(st, amb, i, c):
    """Column c of the gas point of cavity i, or of ambient (i < 0)."""
    return amb[c] if i < 0 else st[i, c]


@njit(cache=True, inline="always")
def volume_of(ci, cf, tx, ty, ti, i, t, y):
    """(V, dV/dt) of cavity i's geometric volume [m^3, m^3/s] (FixedVolume, TableVolume, ScaledMeshVolume, a
    volume wrapped around prescribed bodies: a cubic spline of time, kind 3, or around the dynamic body: of its
    displacement, kind 4)."""
    kind = ci[i, 2]
    if kind == 0:
        return cf[i, 5], 0.0
    k = ci[i, 3]
    if kind == 3:
        return spline_value(tx, ty, ti, k, t)
    if kind == 4:  # a spline of the dynamic body's displacement y[ci[i, 6]] on its held piece: dV/dt = dV/ds·v
        value, slope = spline_piece_value(tx, ty, ti, k, y[ci[i, 6]], ci[i, 9])
        return value, slope * y[ci[i, 6] + 1]
    if kind == 1:
        return table_value(tx, ty, ti, k, t), table_slope(tx, ty, ti, k, t)
    s = table_value(tx, ty, ti, k, t)
    return s * s * s * cf[i, 5], 3.0 * s * s * table_slope(tx, ty, ti, k, t) * cf[i, 5]


@njit(cache=True, inline="always")
def eos_volume(ci, cf, tx, ty, ti, i, t, y):
    """(V, V_eos, dV/dt) of cavity i [m^3, m^3, m^3/s]: its geometric volume plus the added volume, the volume of
    the equation of state (:func:`cavity.volume.effective_volume`: at least the minimum volume), and the rate of
    change, none while held at the minimum."""
    Vg, rate = volume_of(ci, cf, tx, ty, ti, i, t, y)
    Vt = Vg + cf[i, 1]
    if Vt > cf[i, 2]:
        return Vt, Vt, rate
    return Vt, cf[i, 2], 0.0
