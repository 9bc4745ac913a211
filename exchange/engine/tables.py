"""The model's tables: piecewise-linear tables, step tables and cubic splines, concatenated in ``table_x`` and
``table_y`` with one row of ``table_index`` each (:class:`~exchange.engine.layout.TableColumn`); the kernels that
read them and the builder that concatenates them at lowering."""
from __future__ import annotations

import numpy as np
from numba import njit

from cavity.tables import interpolate, interpolation_slope

from .layout import UNLOCKED, TableColumn

__all__ = ["Tables", "table_value", "table_slope", "step_value", "spline_value", "spline_piece_value"]

START, ROWS, LINEAR = TableColumn.START, TableColumn.ROWS, TableColumn.LINEAR


@njit(cache=True)
def table_value(tx, ty, ti, k, x):
    """Table k at x: :func:`cavity.tables.interpolate` on its rows."""
    s, n = ti[k, START], ti[k, ROWS]
    return interpolate(tx[s:s + n], ty[s:s + n], ti[k, LINEAR] != 0, x)


@njit(cache=True)
def table_slope(tx, ty, ti, k, x):
    """dy/dx of table k at x: :func:`cavity.tables.interpolation_slope` on its rows."""
    s, n = ti[k, START], ti[k, ROWS]
    return interpolation_slope(tx[s:s + n], ty[s:s + n], ti[k, LINEAR] != 0, x)


@njit(cache=True)
def step_value(tx, ty, ti, k, x):
    """Step table k at x: y[i] for x[i] <= x < x[i+1] (the right limit at a step; its first x is −inf)
    (:meth:`cases.model.area_track.AreaTrack.area_in` on a fixed surface)."""
    s, n = ti[k, START], ti[k, ROWS]
    i = np.searchsorted(tx[s:s + n], x, side="right") - 1
    return ty[s + max(i, 0)]


@njit(cache=True)
def _cubic(ty, q, d):
    """(value, slope) of the cubic piece whose coefficients (highest power first) start at ty[q], d past its knot."""
    return ((ty[q] * d + ty[q + 1]) * d + ty[q + 2]) * d + ty[q + 3], (3.0 * ty[q] * d + 2.0 * ty[q + 1]) * d + ty[q + 2]


@njit(cache=True)
def spline_value(tx, ty, ti, k, x):
    """(value, slope) of the cubic spline k at x: knots in table k, coefficients (4 per piece, highest power first,
    as scipy's PPoly) in table k + 1; held at its ends, slope 0 outside (:class:`cases.model.wrapped_volume.
    WrappedVolume`)."""
    s, n, c = ti[k, START], ti[k, ROWS], ti[k + 1, START]
    inside = tx[s] <= x <= tx[s + n - 1]
    x = min(max(x, tx[s]), tx[s + n - 1])
    i = min(max(np.searchsorted(tx[s:s + n], x, side="right") - 1, 0), n - 2)
    value, slope = _cubic(ty, c + 4 * i, x - tx[s + i])
    return value, slope if inside else 0.0


@njit(cache=True)
def spline_piece_value(tx, ty, ti, k, x, p):
    """(value, slope) of the cubic spline k at x on its piece p held over the whole segment, extended beyond the
    piece's knots by one piece width (farther, as :func:`spline_value`) (−1: below the first knot, the value there
    and slope 0; n − 1: above the last; UNLOCKED: on the piece holding x). The switches at the piece's knots end the
    segment, so a step never straddles a knot's jump in the third derivative (:func:`exchange.engine.modes.
    lock_pieces`)."""
    if p == UNLOCKED:
        return spline_value(tx, ty, ti, k, x)
    s, n, c = ti[k, START], ti[k, ROWS], ti[k + 1, START]
    if p < 0 or p >= n - 1:  # held at the end knot
        return spline_value(tx, ty, ti, k, tx[s] if p < 0 else tx[s + n - 1])[0], 0.0
    w = tx[s + p + 1] - tx[s + p]
    if x < tx[s + p] - w or x > tx[s + p + 1] + w:  # a trial stage far off (a step to be rejected or cut)
        return spline_value(tx, ty, ti, k, x)
    return _cubic(ty, c + 4 * p, x - tx[s + p])


class Tables:
    """The tables of a lowered network, concatenated as the model holds them."""

    def __init__(self):
        self.x, self.y, self.index, self.size = [], [], [], 0

    def add(self, table) -> int:
        """Append a table (``x``, ``y``, ``extrapolation``: "linear" or held); returns its index."""
        return self.add_arrays(table.x, table.y, table.extrapolation == "linear")

    def add_arrays(self, x, y, linear: bool = False) -> int:
        """Append raw rows (x and y of equal length: the steps of an area, the knots of a spline); returns its
        index."""
        x, y = np.asarray(x, dtype=float).ravel(), np.asarray(y, dtype=float).ravel()
        self.index.append((self.size, len(x), int(linear)))
        self.x.append(x)
        self.y.append(y)
        self.size += len(x)
        return len(self.index) - 1

    def add_spline(self, knots, coefficients) -> int:
        """A cubic spline: its knots (table k, values unused), then its coefficients (table k + 1, 4 per piece,
        highest power first); returns k."""
        knots, flat = np.asarray(knots, dtype=float), np.asarray(coefficients, dtype=float).T.ravel()
        k = self.add_arrays(knots, np.zeros(len(knots)))
        self.add_arrays(np.zeros(len(flat)), flat)
        return k

    def arrays(self) -> tuple:
        """(table_x, table_y, table_index) (one dummy table when empty)."""
        if not self.index:
            self.add_arrays((0.0,), (0.0,))
        return (np.concatenate(self.x), np.concatenate(self.y),
                np.ascontiguousarray(np.array(self.index, dtype=np.int64).reshape(-1, len(TableColumn))))
