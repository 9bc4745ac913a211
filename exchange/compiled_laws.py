"""The flow laws of :mod:`exchange.orifice` and :mod:`exchange.fabric` as numba kernels, for the compiled path.

Each kernel mirrors its pure Python function line by line (same branches, same operation order), so the two agree
to round-off; ``tests/test_compiled.py`` checks every pair over a grid of inputs to 1e-13.
"""
from __future__ import annotations

import math

from numba import njit

__all__ = ["critical_pressure_ratio", "orifice_mass_flow", "fabric_leakage_mass_flow",
           "graefe_mass_flow"]

LINEAR_BELOW = 1e-4  # exchange.orifice.LINEAR_BELOW


@njit(cache=True, inline="always")
def critical_pressure_ratio(gamma):
    """(2/(γ+1))^(γ/(γ−1)) [-] (:func:`exchange.orifice.critical_pressure_ratio`)."""
    return (2.0 / (gamma + 1.0)) ** (gamma / (gamma - 1.0))


@njit(cache=True, inline="always")
def _root_bracket(q, gamma):
    return math.sqrt(q ** (2.0 / gamma) * -math.expm1(math.log(q) * (gamma - 1.0) / gamma))


@njit(cache=True, inline="always")
def _root_bracket_slope(s, gamma):
    q = 1.0 - s
    g = q ** (2.0 / gamma) - q ** ((gamma + 1.0) / gamma)
    dg_dq = (2.0 / gamma) * q ** (2.0 / gamma - 1.0) - ((gamma + 1.0) / gamma) * q ** (1.0 / gamma)
    return -dg_dq / (2.0 * math.sqrt(g))


@njit(cache=True, inline="always")
def orifice_mass_flow(p_up, T_up, p_down, R, gamma, area, Cd):
    """Isentropic orifice flow with choking [kg/s] (:func:`exchange.orifice.orifice_mass_flow`, same C¹
    quadratic below Δp/p = 1e-4)."""
    if p_down >= p_up or area <= 0.0:
        return 0.0
    s = (p_up - p_down) / p_up
    if s >= LINEAR_BELOW:
        root = _root_bracket(max(p_down / p_up, critical_pressure_ratio(gamma)), gamma)
    else:
        d = LINEAR_BELOW
        f, fp = _root_bracket(1.0 - d, gamma), _root_bracket_slope(d, gamma)
        root = s * ((2.0 * f - fp * d) / d + s * (fp * d - f) / (d * d))
    return Cd * area * p_up / math.sqrt(R * T_up) * math.sqrt(2.0 * gamma / (gamma - 1.0)) * root


@njit(cache=True, inline="always")
def fabric_leakage_mass_flow(p_up, T_up, p_down, R, gamma, area, Cd, open_fraction):
    """Orifice law on the fabric's open area [kg/s] (:func:`exchange.fabric.fabric_leakage_mass_flow`)."""
    return orifice_mass_flow(p_up, T_up, p_down, R, gamma, area * open_fraction, Cd)


@njit(cache=True, inline="always")
def graefe_mass_flow(p_up, p_down, rho_up, area, FLC, FAC):
    """FLC·FAC·A·sqrt(2 ρ Δp) [kg/s] (:func:`exchange.fabric.graefe_mass_flow`)."""
    dp = p_up - p_down
    if dp <= 0.0 or area <= 0.0:
        return 0.0
    return FLC * FAC * area * math.sqrt(2.0 * rho_up * dp)
