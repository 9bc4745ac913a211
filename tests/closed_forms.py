"""Closed-form and quadrature references for the verification cases (../shared/PHYSICS.md)."""
from __future__ import annotations

import math

from scipy.integrate import quad
from scipy.optimize import brentq

from exchange.orifice import choked_flow_factor, orifice_mass_flow

R_U = 8.314462618


def blowdown_tau(V, Cd, A, gamma, R, T0):
    """τ = V / (Cd·A·C*·√(R T0)) with C* the choked flow factor (√γ included) [s]."""
    return V / (Cd * A * choked_flow_factor(gamma) * math.sqrt(R * T0))


def choked_adiabatic_pressure(t, p0, tau, gamma):
    """p/p0 = [1 + (γ−1)/2 · t/τ]^(−2γ/(γ−1))."""
    return p0 * (1.0 + 0.5 * (gamma - 1.0) * t / tau) ** (-2.0 * gamma / (gamma - 1.0))


def choked_adiabatic_temperature(t, T0, tau, gamma):
    return T0 * (1.0 + 0.5 * (gamma - 1.0) * t / tau) ** -2.0


def isothermal_choked_pressure(t, p0, tau):
    return p0 * math.exp(-t / tau)


def adiabatic_blowdown_pressure(t, p0, T0, V, Cd, A, gamma, R, p_amb):
    """p(t) of an adiabatic rigid-tank blowdown through choked and subsonic flow, by quadrature.

    The gas left in the tank expands isentropically: T = T0 (p/p0)^((γ−1)/γ), ρ = ρ0 (p/p0)^(1/γ), so
    dp/dt = −γ p ṁ(p) / (V ρ(p)) and t(p) = ∫_p^{p0} V ρ(p') / (γ p' ṁ(p')) dp'.
    """
    rho0 = p0 / (R * T0)

    def dt_dp(p):
        T = T0 * (p / p0) ** ((gamma - 1.0) / gamma)
        rho = rho0 * (p / p0) ** (1.0 / gamma)
        return V * rho / (gamma * p * orifice_mass_flow(p, T, p_amb, R, gamma, A, Cd))

    def elapsed(p):
        pc = p_amb / ((2.0 / (gamma + 1.0)) ** (gamma / (gamma - 1.0)))  # upstream pressure at the choke limit
        pts = [x for x in (pc,) if p < x < p0]
        return quad(dt_dp, p, p0, points=pts or None, epsabs=0.0, epsrel=1e-13, limit=200)[0]

    if t == 0.0:
        return p0
    return brentq(lambda p: elapsed(p) - t, p_amb * (1 + 1e-9), p0, xtol=1e-300, rtol=1e-15, maxiter=200)


def fill_pressure(t, p0, gamma, R, mdot, T_in, V):
    """Rigid adiabatic fill at constant ṁ and T_in, same constant-cp gas: p = p0 + γ R ṁ T_in t / V."""
    return p0 + gamma * R * mdot * T_in * t / V
