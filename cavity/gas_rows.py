"""Heat capacity of an ideal-gas mixture from its polynomial coefficient rows, as numba kernels (one row of
(a, b, c, d, e, f, H offset) per temperature range, as :attr:`cavity.gas.Mixture.rows`): used by the compiled
right-hand side and by the laws of :mod:`cavity.inflator_orifice`, which need γ(T) inside numba code."""
from __future__ import annotations

import numpy as np
from numba import njit

from .tolerances import R_UNIVERSAL as R_U

__all__ = ["range_of", "row_cp", "rows_gamma"]


@njit(cache=True, inline="always")
def range_of(breaks, T):
    """Index of the temperature range holding T [K] (bisect_right on the interior breaks, as
    :meth:`cavity.gas.Mixture._range`)."""
    return np.searchsorted(breaks, T, side="right") if breaks.size else 0


@njit(cache=True, inline="always")
def row_cp(r, T):
    r"""Cp(T) [J/K] of a coefficient row (:meth:`cavity.gas.Mixture.heat_capacity_p`).

    .. math:: C_p = a + bT + cT^2 + dT^3 + fT^4 + e/T^2

    Abaqus *CAPACITY, TYPE=POLYNOMIAL (Radioss adds f); ``r`` (7,) in J/(K) per the row's moles.

    Examples
    --------
    >>> import numpy as np
    >>> round(row_cp(np.array([28.11, 1.967e-3, 4.802e-6, -1.966e-9, 0.0, 0.0, 0.0]), 300.0), 4)
    29.0792
    """
    return r[0] + T * (r[1] + T * (r[2] + T * (r[3] + T * r[5]))) + r[4] / (T * T)


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
