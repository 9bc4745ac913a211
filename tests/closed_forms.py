"""Closed-form and quadrature references for the verification cases (../shared/PHYSICS.md)."""
from __future__ import annotations

import math

from scipy.integrate import quad
from scipy.optimize import brentq

from exchange.laws.orifice import choked_flow_factor, orifice_mass_flow

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


def two_layer_slab_mean(t, h, layer1, layer2, terms=60):
    """Mean of θ/θ_0 over a two-material slab (weighted by ρc), θ = T − T_f, initially uniform, whose face x = 0
    meets a fluid at T_f through h and whose face x = L1 + L2 is adiabatic; ``layer1``, ``layer2`` = (L [m],
    k [W/(m K)], ρc [J/(m^3 K)]).

    Separation of variables for composite media (Mikhailov and Özişik, *Unified Analysis and Solutions of Heat
    and Mass Diffusion*, 1984, ch. 5): θ = Σ c_n X_n(x) exp(−λ_n t), X = cos ω_1 x + h/(k_1 ω_1) sin ω_1 x in
    layer 1 (k_1 X' = h X at x = 0), X = C cos ω_2 (L − x) in layer 2 (adiabatic at L), ω_i = √(λ/α_i);
    temperature and flux continuous at L1 give the eigenvalue condition
    k_1 X'(L1) cos ω_2 L2 − k_2 ω_2 sin(ω_2 L2) X(L1) = 0. The X_n are orthogonal with weight ρc, so
    θ̄/θ_0 = Σ (∫ρc X_n)² / (∫ρc X_n² · ∫ρc) exp(−λ_n t); integrals by quadrature, roots by a scan and Brent's
    method in √λ.
    """
    (L1, k1, c1), (L2, k2, c2) = layer1, layer2
    a1, a2 = k1 / c1, k2 / c2

    def parts(beta):
        w1, w2 = beta / math.sqrt(a1), beta / math.sqrt(a2)
        X1 = math.cos(w1 * L1) + h / (k1 * w1) * math.sin(w1 * L1)
        dX1 = -w1 * math.sin(w1 * L1) + h / k1 * math.cos(w1 * L1)
        return w1, w2, X1, dX1

    def condition(beta):
        w1, w2, X1, dX1 = parts(beta)
        return k1 * dX1 * math.cos(w2 * L2) - k2 * w2 * math.sin(w2 * L2) * X1

    step = 0.02 * min(math.sqrt(a1) / L1, math.sqrt(a2) / L2)
    roots, b = [], step * 1e-3
    f = condition(b)
    while len(roots) < terms:
        b2 = b + step
        f2 = condition(b2)
        if f * f2 < 0:
            roots.append(brentq(condition, b, b2, xtol=1e-15, rtol=1e-15))
        b, f = b2, f2
    total = c1 * L1 + c2 * L2
    mean = 0.0
    for beta in roots:
        w1, w2, X1, dX1 = parts(beta)
        C = X1 / math.cos(w2 * L2) if abs(math.cos(w2 * L2)) > 0.1 else k1 * dX1 / (k2 * w2 * math.sin(w2 * L2))

        def X(x):
            if x <= L1:
                return math.cos(w1 * x) + h / (k1 * w1) * math.sin(w1 * x)
            return C * math.cos(w2 * (L1 + L2 - x))

        opts = dict(epsabs=0.0, epsrel=1e-10, limit=400)
        first = c1 * quad(X, 0.0, L1, **opts)[0] + c2 * quad(X, L1, L1 + L2, **opts)[0]
        square = (c1 * quad(lambda x: X(x) ** 2, 0.0, L1, **opts)[0]
                  + c2 * quad(lambda x: X(x) ** 2, L1, L1 + L2, **opts)[0])
        mean += first * first / (square * total) * math.exp(-beta * beta * t)
    return mean
