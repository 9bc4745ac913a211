"""Piecewise-linear tables of one variable (inflator curves, volume histories, amplitudes).

A table is validated once when it is built; evaluation is a scalar binary search, cheap enough for an ODE
right-hand side. Breakpoints are exposed so the integrator can stop at each kink.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

__all__ = ["Table", "TableError", "interpolate", "interpolation_slope"]


@njit(cache=True, inline="always")
def interpolate(x, y, linear, t):
    """Piecewise-linear y(t) through the rows (x, y) (x strictly increasing), held constant beyond the first and
    last rows unless ``linear`` (then the end segments extend); the engine and :class:`Table` both call it.

    >>> interpolate(np.array([0.0, 1.0, 3.0]), np.array([0.0, 2.0, 2.0]), False, 0.5)
    1.0
    """
    n = x.size
    if n == 1:
        return y[0]
    if t <= x[0] and not linear:
        return y[0]
    if t >= x[n - 1] and not linear:
        return y[n - 1]
    i = min(max(np.searchsorted(x, t, side="right") - 1, 0), n - 2)
    w = (t - x[i]) / (x[i + 1] - x[i])
    return y[i] + w * (y[i + 1] - y[i])


@njit(cache=True, inline="always")
def interpolation_slope(x, y, linear, t):
    """dy/dt of :func:`interpolate` at t, taken from the right at a row (0 beyond the ends when held constant).

    >>> interpolation_slope(np.array([0.0, 1.0, 3.0]), np.array([0.0, 2.0, 2.0]), False, 1.0)
    0.0
    """
    n = x.size
    if n == 1 or (not linear and (t < x[0] or t >= x[n - 1])):
        return 0.0
    i = min(max(np.searchsorted(x, t, side="right") - 1, 0), n - 2)
    return (y[i + 1] - y[i]) / (x[i + 1] - x[i])


class TableError(ValueError):
    """A table whose data cannot define a piecewise-linear function; the message says which row and why."""


@dataclass(frozen=True)
class Table:
    """A piecewise-linear function y(x), held constant beyond its first and last rows.

    Parameters
    ----------
    x : (n,) float
        Abscissae, strictly increasing, finite (e.g. time [s] or pressure difference [Pa]).
    y : (n,) float
        Ordinates, finite.
    name : str
        What the table is (used in error messages), e.g. ``"mass flow [kg/s]"``.
    extrapolation : str
        ``"constant"`` (hold the end values) or ``"linear"`` (extend the end segments).

    Examples
    --------
    >>> t = Table((0.0, 1.0, 3.0), (0.0, 2.0, 2.0))
    >>> t(0.5), t(2.0), t(9.0), t.slope(0.5), t.slope(2.0)
    (1.0, 2.0, 2.0, 2.0, 0.0)
    """

    x: tuple[float, ...]
    y: tuple[float, ...]
    name: str = "table"
    extrapolation: str = "constant"
    _xa: np.ndarray = field(init=False, repr=False, compare=False)
    _ya: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        x = np.asarray(self.x, dtype=float).ravel()
        y = np.asarray(self.y, dtype=float).ravel()
        if x.size == 0:
            raise TableError(f"{self.name}: the table is empty; expected at least one row")
        if x.size != y.size:
            raise TableError(f"{self.name}: {x.size} abscissae but {y.size} ordinates")
        for label, arr in (("first", x), ("second", y)):
            bad = np.flatnonzero(~np.isfinite(arr))
            if bad.size:
                raise TableError(f"{self.name}: row {bad[0] + 1} has a non-finite value in the {label} column; "
                                 "expected finite numbers")
        steps = np.flatnonzero(np.diff(x) <= 0.0)
        if steps.size:
            i = steps[0] + 1
            what = "repeat the abscissa" if x[i] == x[i - 1] else "are not in strictly increasing order"
            raise TableError(f"{self.name}: rows {i} and {i + 1} {what} ({float(x[i - 1])!r} then {float(x[i])!r})")
        if self.extrapolation not in ("constant", "linear"):
            raise TableError(f"{self.name}: extrapolation must be 'constant' or 'linear', got {self.extrapolation!r}")
        object.__setattr__(self, "x", tuple(float(v) for v in x))
        object.__setattr__(self, "y", tuple(float(v) for v in y))
        object.__setattr__(self, "_xa", x.copy())
        object.__setattr__(self, "_ya", y.copy())

    def __call__(self, x: float) -> float:
        return float(interpolate(self._xa, self._ya, self.extrapolation == "linear", float(x)))

    def slope(self, x: float) -> float:
        """dy/dx at x, taken from the right at a breakpoint (0 beyond the ends when held constant)."""
        return float(interpolation_slope(self._xa, self._ya, self.extrapolation == "linear", float(x)))

    def integral(self, a: float, b: float) -> float:
        """Exact integral of the table from a to b (trapezoids on the pieces)."""
        if b < a:
            return -self.integral(b, a)
        knots = [a] + [v for v in self.x if a < v < b] + [b]
        return math.fsum(0.5 * (self(k0) + self(k1)) * (k1 - k0) for k0, k1 in zip(knots[:-1], knots[1:]))

    @property
    def breakpoints(self) -> tuple[float, ...]:
        """Abscissae where the slope may jump (all rows)."""
        return self.x

    def require(self, *, minimum: float | None = None, positive: bool = False) -> "Table":
        """Check the ordinates' range; returns self so it chains.

        >>> Table((0.0, 1.0), (1.0, -1.0), name="T [K]").require(positive=True)
        Traceback (most recent call last):
        ...
        cavity.tables.TableError: T [K]: row 2 has value -1.0; expected > 0
        """
        for i, v in enumerate(self.y):
            if positive and not v > 0.0:
                raise TableError(f"{self.name}: row {i + 1} has value {v!r}; expected > 0")
            if minimum is not None and v < minimum:
                raise TableError(f"{self.name}: row {i + 1} has value {v!r}; expected >= {minimum}")
        return self
