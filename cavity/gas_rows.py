"""An ideal-gas mixture's polynomial rows as numba kernels (one row of (a, b, c, d, e, f, H offset) per
temperature range, as :attr:`cavity.gas.Mixture.rows`): Cp, H, γ and T from U, for the compiled right-hand side,
the laws of :mod:`cavity.inflator_orifice` (γ(T) inside numba code) and :class:`cavity.gas.Mixture` itself. The
polynomials are :mod:`cavity.species`'s functions compiled, not copies."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .species import enthalpy_polynomial, heat_capacity_polynomial
from .tolerances import R_UNIVERSAL as R_U
from .tolerances import TOL

NEWTON_RTOL, NEWTON_MAX, T_FLOOR = TOL.newton_rtol, TOL.newton_max_iterations, TOL.temperature_floor

__all__ = ["range_of", "row_cp", "row_enthalpy", "mixture_row", "temperature", "rows_gamma"]


@njit(cache=True, inline="always")
def range_of(breaks, T):
    """Index of the temperature range holding T [K] (bisect_right on the interior breaks, as
    :meth:`cavity.gas.Mixture._range`)."""
    return np.searchsorted(breaks, T, side="right") if breaks.size else 0


_cp = njit(cache=True, inline="always")(heat_capacity_polynomial)
_h = njit(cache=True, inline="always")(enthalpy_polynomial)


@njit(cache=True, inline="always")
def row_cp(r, T):
    """Cp(T) [J/K] of a coefficient row (a, b, c, d, e, f, H offset): :func:`cavity.species.heat_capacity_polynomial`
    compiled, as :meth:`cavity.gas.Mixture.heat_capacity_p` evaluates it.

    Examples
    --------
    >>> import numpy as np
    >>> round(row_cp(np.array([28.11, 1.967e-3, 4.802e-6, -1.966e-9, 0.0, 0.0, 0.0]), 300.0), 4)
    29.0792
    """
    return _cp(r[0], r[1], r[2], r[3], r[4], r[5], T)


@njit(cache=True, inline="always")
def row_enthalpy(r, T):
    """H(T) [J] of a coefficient row: :func:`cavity.species.enthalpy_polynomial` plus the row's offset r[6]
    (:meth:`cavity.gas.Mixture.enthalpy`).

    >>> import numpy as np
    >>> row_enthalpy(np.array([29.0, 0.0, 0.0, 0.0, 0.0, 0.0, 100.0]), 300.0)
    8800.0
    """
    return _h(r[0], r[1], r[2], r[3], r[4], r[5], T) + r[6]


@njit(cache=True, inline="always")
def mixture_row(rows, n, i, out):
    """Mole-weighted row of range i (:meth:`cavity.gas.Mixture`'s rows): Σ n_s·rows[s, i] into out (7,)."""
    for c in range(7):
        out[c] = n[0] * rows[0, i, c]
    for s in range(1, n.size):
        if n[s] != 0.0:
            for c in range(7):
                out[c] += n[s] * rows[s, i, c]


@njit(cache=True, inline="always")
def temperature(rows, breaks, linear, n, nmol, U, T_guess, row):
    """T [K] with U(T) = U [J] of the mixture of ``n`` (ns,) [mol] of the species whose per-mole rows are ``rows``
    (ns, nr, 7) over the ranges split at ``breaks``; NaN if Newton's method fails. The one solver of it: the
    compiled right-hand side and :meth:`cavity.gas.Mixture.temperature` call this.

    Newton on the analytic U(T) = H(T) − nR_u·T with dU/dT = Cv; steps kept above ``TOL.temperature_floor`` and
    within a factor 2 of the last iterate (a polynomial cp such as the Abaqus air deck's turns negative far above
    its data, giving U(T) a second, spurious root an undamped step from a poor guess can land on). Where every
    species has a constant cp in the range (``linear[i]``) U is linear in T and the step lands on the root at once,
    returned when it lies in that range. ``row`` (7,) is scratch; on return it holds the row of the range of T
    (whose index is returned second).

    >>> import numpy as np
    >>> rows = np.array([[[29.1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]]])
    >>> T, i = temperature(rows, np.zeros(0), np.ones(1, np.int64), np.ones(1), 1.0, 29.1 * 300.0 - 8.314462618 * 300.0,
    ...                    1000.0, np.zeros(7))
    >>> round(T, 10), i
    (300.0, 0)
    """
    nR = nmol * R_U
    T = T_guess
    cur = -1
    for _ in range(NEWTON_MAX):
        i = range_of(breaks, T)
        if i != cur:
            mixture_row(rows, n, i, row)
            cur = i
        if linear[i]:
            T_new = (U - row[6]) / (row[0] - nR)
            if T_new >= T_FLOOR and range_of(breaks, T_new) == i:
                return T_new, cur
        else:
            U_T = row_enthalpy(row, T) - nR * T
            cv = row_cp(row, T) - nR
            T_new = min(max(T - (U_T - U) / cv, 0.5 * T), 2.0 * T)
        if T_new < T_FLOOR:
            T_new = 0.5 * (T + T_FLOOR)
        if abs(T_new - T) <= NEWTON_RTOL * T_new:
            return T_new, cur
        T = T_new
    return math.nan, cur


@njit(cache=True, inline="always")
def rows_gamma(rows, breaks, moles, T):
    r"""Ratio of specific heats γ(T) [-] of a gas of ``moles`` [mol] whose total coefficient rows are ``rows``
    (nr, 7) over the ranges split at ``breaks`` (nr − 1,) [K] (:meth:`cavity.gas.Mixture.gamma`).

    .. math:: \gamma = \frac{C_p(T)}{C_p(T) - n R_u}

    Examples
    --------
    One mole of a constant-cp diatomic gas (cp = 3.5 R_u):

    >>> import numpy as np
    >>> rows = np.array([[3.5 * 8.314462618, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    >>> round(rows_gamma(rows, np.zeros(0), 1.0, 500.0), 12)
    1.4
    """
    cp = row_cp(rows[range_of(breaks, T)], T)
    return cp / (cp - moles * R_U)
