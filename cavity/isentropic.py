"""Isentropic flow of an ideal gas: the critical pressure ratio and the choked mass-flow factor, shared by orifices
(:mod:`exchange.laws.orifice`), the engine's choke switches and inflators characterised through their exit orifice
(:mod:`cavity.inflator_orifice`)."""
from __future__ import annotations

import math

from numba import njit

__all__ = ["choked_flow_factor", "critical_pressure_ratio"]


@njit(cache=True)
def choked_flow_factor(gamma: float) -> float:
    r"""The dimensionless choked mass-flow factor C* / Cd [-].

    .. math:: C^* = \sqrt{\gamma}\left(\frac{2}{\gamma + 1}\right)^{(\gamma+1)/(2(\gamma-1))}

    so that the choked flow is :math:`\dot m = C_d A\,p_e\,C^*/\sqrt{R T_e}` (Anderson, *Modern Compressible
    Flow*, 3rd ed., eq. 5.21).

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


@njit(cache=True)
def critical_pressure_ratio(gamma: float) -> float:
    r"""Downstream/upstream pressure ratio below which an isentropic orifice is choked [-].

    .. math:: \frac{p_c}{p_e} = \left(\frac{2}{\gamma + 1}\right)^{\gamma/(\gamma - 1)}

    Parameters
    ----------
    gamma : float
        Ratio of specific heats cp/cv of the upstream gas [-], > 1.

    Notes
    -----
    Isentropic expansion of an ideal gas to sonic speed at the throat.

    References
    ----------
    Abaqus Analysis User's Guide, "Fluid exchange definition", orifice flow; Anderson, *Modern Compressible Flow*, eq. 5.20.

    Examples
    --------
    >>> round(critical_pressure_ratio(1.4), 6)
    0.528282
    """
    return (2.0 / (gamma + 1.0)) ** (gamma / (gamma - 1.0))
