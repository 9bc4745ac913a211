"""Isentropic flow of an ideal gas: the choked mass-flow factor, shared by orifices (:mod:`exchange.orifice`) and
inflators characterised through their exit orifice (:mod:`cavity.inflator_orifice`)."""
from __future__ import annotations

import math

from numba import njit

__all__ = ["choked_flow_factor"]


@njit(cache=True, inline="always")
def choked_flow_factor(gamma: float) -> float:
    r"""The dimensionless choked mass-flow factor C* / Cd [-].

    .. math:: C^* = \sqrt{\gamma}\left(\frac{2}{\gamma + 1}\right)^{(\gamma+1)/(2(\gamma-1))}

    so that the choked flow is :math:`\dot m = C_d A\,p_e\,C^*/\sqrt{R T_e}` (Anderson, *Modern Compressible
    Flow*, 3rd ed., eq. 5.21; ../shared/PHYSICS.md).

    Parameters
    ----------
    gamma : float
        Ratio of specific heats [-], > 1.

    Examples
    --------
    >>> round(choked_flow_factor(1.4), 6)
    0.684731
    """
    return math.sqrt(gamma) * (2.0 / (gamma + 1.0)) ** ((gamma + 1.0) / (2.0 * (gamma - 1.0)))
