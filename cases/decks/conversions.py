"""The two relations the deck readers apply to the solvers' data (pure functions, SI units)."""
from __future__ import annotations

import math

__all__ = ["hydraulic_density", "constant_cp_species", "R_U"]

#: universal gas constant [J/(mol K)], as cavity.species uses it
R_U = 8.314462618


def hydraulic_density(rho_ref: float, p: float, p_ref: float, K: float) -> float:
    """Density of an Abaqus hydraulic fluid at pressure ``p``.

    .. math:: \\rho = \\rho_R \\exp\\left(\\frac{p - p_R}{K}\\right)

    Parameters: ``rho_ref`` reference density [kg/m^3] (*FLUID DENSITY) at the reference pressure ``p_ref``
    [Pa]; ``p`` [Pa]; ``K`` bulk modulus [Pa] (*FLUID BULK MODULUS). This is the law ventsim's hydraulic cavity
    integrates (p = p0 + K·ln(ρ/ρ0), docs/scenes.md), so the scene's ``density`` at the initial pressure follows
    from the deck's reference state. Source: Abaqus Analysis User's Guide, "Fluid cavity definition",
    hydraulic fluids (thermal expansion aside). Raises OverflowError for (p − p_R)/K beyond ~709.

    >>> hydraulic_density(1000.0, 1.0e6, 0.0, 2.2e9)
    1000.4546487759847
    """
    dp = p - p_ref
    return rho_ref * math.exp(dp / K) if dp else rho_ref


def constant_cp_species(cp: float, cv: float) -> tuple[float, float]:
    """(molar mass [kg/mol], molar cp [J/(mol K)]) of the ideal gas an LS-DYNA control volume gives by its
    specific heats ``cp``, ``cv`` [J/(kg K)].

    .. math:: M = \\frac{R_u}{c_p - c_v}, \\qquad \\tilde c_p = c_p M

    so that R = R_u/M = cp − cv and γ = cp/cv are the deck's exactly (LS-DYNA Keyword User's Manual,
    *AIRBAG_SIMPLE_AIRBAG_MODEL / *AIRBAG_WANG_NEFSKE: CV, CP). Air-like cp = 1005, cv = 718:

    >>> M, cp_molar = constant_cp_species(1005.0, 718.0)
    >>> round(M, 6), round(cp_molar / M, 9), round(R_U / M, 9)
    (0.02897, 1005.0, 287.0)
    """
    M = R_U / (cp - cv)
    return M, cp * M
