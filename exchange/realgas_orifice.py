"""Isentropic nozzle with a real-gas equation of state: choke point where the velocity equals the speed of sound.

From the stagnation (cavity) state (ρ0, T0) with enthalpy h0 and entropy s0, the gas expands along the isentrope
s = s0 to the throat; there, by energy conservation, v = √(2(h0 − h)) and the mass flux is G = ρ·v. Along the
isentrope dh = dp/ρ and dp = c²·dρ, so

    dG/dp|s = (v² − c²)/(c²·v),

which vanishes where v = c: the flux is largest (choked) at that throat pressure p*, and for p_down ≤ p* the
throat stays at p*. The isentrope is followed exactly: at any density ρ its temperature is the root of
s(ρ, T) = s0 (:func:`cavity.realgas.isentrope_temperature`), so h(ρ) and c(ρ) are those of the equation of state,
with no integration error. For an ideal gas of constant γ this is the law of :mod:`exchange.orifice`
(tested to 1e-12), including its C¹ quadratic below Δp/p = :data:`exchange.orifice.LINEAR_BELOW`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from cavity.realgas import isentrope_temperature
from .discharge import PRESSURE, DischargeTable
from .orifice import LINEAR_BELOW, orifice_mass_flow
from .vent import GasPoint

__all__ = ["real_gas_critical_state", "real_gas_mass_flux", "RealGasOrificeLaw", "RealGasPoint", "real_gas_point"]

#: Newton iterations on the choke condition and the throat pressure stop when the density step is below this
#: fraction [-].
ITERATION_RTOL = 1e-13
ITERATION_MAX = 40


_throat = isentrope_temperature  # (T, FluidPoint) on the isentrope s0 at density rho
#: Density steps of the first walk down an isentrope (no previous choke point to start from).
MARCH_STEPS = 8


def _march(fluid, rho0, T0, s0, rho):
    """(T, FluidPoint) on the isentrope s0 at rho, walked down from (rho0, T0) in :data:`MARCH_STEPS` geometric
    density steps, each Newton started from the last: it keeps to the isentrope's branch where a far guess could
    find a root of s(ρ, T) = s0 on the equation of state's unphysical continuation (dense fluids)."""
    T, ratio = T0, (rho / rho0) ** (1.0 / MARCH_STEPS)
    for k in range(1, MARCH_STEPS + 1):
        T, pt = _throat(fluid, rho0 * ratio ** k, s0, T)
    return T, pt


def _sonic_point(fluid, rho0, T0, st0):
    """(ρ*, T*, FluidPoint) where 2(h0 − h) = c² on the isentrope of st0: :func:`real_gas_critical_state`'s
    Newton search, f(ρ) = 2(h0 − h) − c² with df/dρ|s = −2Γc²/ρ (dh = c²dρ/ρ; d(c²)/dρ|s = 2(Γ − 1)c²/ρ, Γ the
    fundamental derivative of gas dynamics)."""
    h0, s0 = st0[2], st0[3]
    last = getattr(fluid, "last_choke", None)  # (ρ*/ρ0, T*/T0, p*/p0) of the previous call: a warm start
    if last is None:
        kappa = rho0 * st0[4] ** 2 / st0[0]
        last = ((2.0 / (kappa + 1.0)) ** (1.0 / (kappa - 1.0)),)
    rho = rho0 * last[0]
    T, pt = _throat(fluid, rho, s0, T0 * last[1]) if len(last) > 2 else _march(fluid, rho0, T0, s0, rho)
    for _ in range(ITERATION_MAX):
        c2 = pt[4] ** 2
        f = 2.0 * (h0 - pt[2]) - c2
        # below 1e-12 c², f is at the level of the isentrope's Newton tolerance: ρ is the root to ~4e-13 and
        # G = ρv, stationary there, exact to ~1e-25
        if abs(f) <= 1e-12 * c2:
            break
        rho_n = rho + f * rho / (2.0 * c2 * fluid.fundamental_derivative())  # Γ at (ρ, T): the last at() call
        rho_n = min(max(rho_n, 0.5 * rho), 0.5 * (rho + rho0))  # stay between the start and the cavity
        done = abs(rho_n - rho) <= ITERATION_RTOL * rho
        rho = rho_n
        T, pt = _throat(fluid, rho, s0, T)
        if done:
            break
    return rho, T, pt


def real_gas_critical_state(fluid, rho0: float, T0: float) -> tuple:
    r"""The choked throat of an isentropic nozzle fed from the stagnation state (ρ0, T0).

    Solves :math:`2(h_0 - h(\rho)) = c(\rho)^2` on the isentrope s = s0 by Newton's method in ρ, started from
    the previous call's ρ*/ρ0 and T*/T0 (kept on ``fluid``: an integrator asks for nearby states), or on the first
    call from the ideal-gas value :math:`\rho^* = \rho_0 (2/(\kappa+1))^{1/(\kappa-1)}` with the isentropic
    exponent κ = ρ0·c0²/p0. It stops when 2(h0 − h) − c² is below 1e-12·c² (the isentrope's own tolerance), so
    the start may change ρ* in its 13th digit and G* (stationary there) not at all.

    Parameters
    ----------
    fluid : cavity.realgas.RealFluid or IdealGasFluid
    rho0, T0 : float
        Stagnation density [kg/m^3] and temperature [K].

    Returns
    -------
    tuple
        (p* [Pa], G* [kg/(s m^2)], ρ* [kg/m^3], T* [K]).

    References
    ----------
    Any compressible-flow text for the sonic throat (e.g. Anderson, *Modern Compressible Flow*, §5.4); the real-gas
    form as in R. C. Johnson, "Calculations of real-gas effects in flow through critical-flow nozzles",
    J. Basic Eng. 86 (1964) 519–525.

    Examples
    --------
    >>> from cavity.realgas import IdealGasFluid
    >>> p, G, rho, T = real_gas_critical_state(IdealGasFluid(287.0, 1.4), 2.0e5 / (287.0 * 300.0), 300.0)
    >>> round(p / 2.0e5, 6), round(T / 300.0, 12)
    (0.528282, 0.833333333333)
    """
    fluid = getattr(fluid, "metastable", fluid)  # the expansion is frozen (cavity.realgas.MetastableFluid)
    st0 = fluid.at(rho0, T0)
    h0 = st0[2]
    rho_b, T_b, pb = _sonic_point(fluid, rho0, T0, st0)
    v = math.sqrt(max(2.0 * (h0 - pb[2]), 0.0))
    fluid.last_choke = (rho_b / rho0, T_b / T0, pb[0] / st0[0])
    return pb[0], rho_b * v, rho_b, T_b


#: Throat/stagnation pressure ratio above which h0 − h is integrated (∫ c²/ρ dρ along the isentrope) instead of
#: differenced: there h0 − h is under 1 % of h and the difference would lose more than two digits.
QUADRATURE_ABOVE = 0.99
_GAUSS3 = ((-0.7745966692414834, 5.0 / 9.0), (0.0, 8.0 / 9.0), (0.7745966692414834, 5.0 / 9.0))


def _enthalpy_drop(fluid, rho0, T0, s0, rho_t, T_t):
    r"""h0 − h(ρ_t) = ∫ c²/ρ dρ from ρ_t to ρ0 along the isentrope s0 (dh = dp/ρ, dp = c² dρ), by 3-point
    Gauss–Legendre quadrature [J/kg] (the interval is short, p_t ≥ 0.99 p0, and the integrand smooth: the rule's
    error, ~(Δρ/2ρ)^6, is below 1e-13)."""
    half, mid, total = 0.5 * (rho0 - rho_t), 0.5 * (rho0 + rho_t), 0.0
    for x, w in _GAUSS3:
        rho = mid + half * x
        pt = isentrope_temperature(fluid, rho, s0, T_t + (T0 - T_t) * (rho - rho_t) / (rho0 - rho_t))[1]
        total += w * pt[4] ** 2 / rho
    return half * total


def _flux_at_pressure(fluid, rho0, T0, st0, p_t):
    """(G, dG/dp) at throat pressure p_t >= p* on the isentrope of st0: Newton on p(ρ) = p_t, dp/dρ|s = c²."""
    h0, s0 = st0[2], st0[3]
    kappa = rho0 * st0[4] ** 2 / st0[0]
    rho = rho0 * (p_t / st0[0]) ** (1.0 / kappa)
    last = getattr(fluid, "last_choke", None)  # T between T0 and T* in proportion to p0 − p_t, or walk down
    if last is not None:
        T = T0 * (1.0 - (1.0 - last[1]) * (1.0 - p_t / st0[0]) / (1.0 - last[2]))
    else:
        T = _march(fluid, rho0, T0, s0, rho)[0]
    for _ in range(ITERATION_MAX):
        T, pt = _throat(fluid, rho, s0, T)
        step = (pt[0] - p_t) / pt[4] ** 2
        rho -= step
        if abs(step) <= ITERATION_RTOL * rho:
            break
    T, pt = _throat(fluid, rho, s0, T)
    T -= (pt[3] - s0) * T / pt[5]  # one Newton step more: h is differenced below, T must be exact, not 1e-13
    pt = fluid.at(rho, T)
    r, c2 = p_t - pt[0], pt[4] ** 2  # the Newton residual, removed to first order (dh = dp/ρ, dρ = dp/c²)
    drop = h0 - pt[2] if p_t < QUADRATURE_ABOVE * st0[0] else _enthalpy_drop(fluid, rho0, T0, s0, rho, T)
    v2 = 2.0 * drop - 2.0 * r / rho
    rho += r / c2
    v = math.sqrt(max(v2, 0.0))
    return rho * v, (v2 - c2) / (c2 * v) if v > 0.0 else math.inf


def real_gas_mass_flux(fluid, rho0: float, T0: float, p_down: float) -> float:
    r"""Mass flux through an isentropic real-gas nozzle [kg/(s m^2)], choked below the critical pressure.

    .. math::

        G = \rho_t \sqrt{2\,(h_0 - h(\rho_t))},\quad s(\rho_t, T_t) = s_0,\quad
        p_t = \max(p_{down},\, p^*)

    with p* from :func:`real_gas_critical_state`. When the previous call's p*/p0 puts p_down above the choke
    point, the throat at p_down is computed first and kept if its velocity is below the speed of sound there
    (dG/dp ≤ 0: then p_down ≥ p*, the isentrope crossing v = c once), saving the choke search. Below a relative pressure difference s = Δp/p0 of
    :data:`exchange.orifice.LINEAR_BELOW` the flux is the quadratic a·s + b·s² matching G and dG/ds at s = 1e-4
    (dG/ds = p0·(c² − v²)/(c²·v), exact), as the ideal law does.

    Parameters
    ----------
    fluid : cavity.realgas.RealFluid or IdealGasFluid
    rho0, T0 : float
        Upstream stagnation density [kg/m^3] and temperature [K].
    p_down : float
        Downstream pressure [Pa].

    Returns
    -------
    float
        G >= 0 [kg/(s m^2)]; 0 when p_down >= p0.

    Examples
    --------
    Equal to the ideal orifice law for an ideal gas (air, 2 bar into 1 bar):

    >>> from cavity.realgas import IdealGasFluid
    >>> round(real_gas_mass_flux(IdealGasFluid(287.0, 1.4), 2.0e5 / (287.0 * 300.0), 300.0, 1.0e5) * 1e-4, 6)
    0.046671
    """
    fluid = getattr(fluid, "metastable", fluid)  # the expansion is frozen (cavity.realgas.MetastableFluid)
    st0 = fluid.at(rho0, T0)
    p0 = st0[0]
    if p_down >= p0:
        return 0.0
    s = (p0 - p_down) / p0
    if s < LINEAR_BELOW:
        d = LINEAR_BELOW
        f, dGdp = _flux_at_pressure(fluid, rho0, T0, st0, p0 * (1.0 - d))
        fp = -p0 * dGdp
        return s * ((2.0 * f - fp * d) / d + s * (fp * d - f) / (d * d))
    last = getattr(fluid, "last_choke", None)
    if last is not None and p_down > last[2] * p0:  # likely subsonic: a throat at p_down with v <= c proves it
        G, dGdp = _flux_at_pressure(fluid, rho0, T0, st0, p_down)
        if dGdp <= 0.0:
            return G
    p_star, G_star, _, _ = real_gas_critical_state(fluid, rho0, T0)
    if p_down <= p_star:
        return G_star
    return _flux_at_pressure(fluid, rho0, T0, st0, p_down)[0]


@dataclass(frozen=True)
class RealGasOrificeLaw:
    """The orifice law (:class:`exchange.laws.OrificeLaw`) with the upstream cavity's real-gas equation of state.

    ``mass_flow(up, p_down, area, t) = Cd·A·G`` with G from :func:`real_gas_mass_flux` when the upstream gas point
    carries a fluid (``up.fluid``, a real-gas cavity), else the ideal law (gas flowing back in from ambient).
    """

    discharge_coefficient: object = 1.0
    pneumatic = True
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        cd = self.discharge_coefficient
        if isinstance(cd, DischargeTable):
            cd = cd(up.p) if cd.variable == PRESSURE else cd(t)
        fluid = getattr(up, "fluid", None)
        if fluid is None:
            return orifice_mass_flow(up.p, up.T, p_down, up.R, up.gamma, area, cd)
        return cd * area * real_gas_mass_flux(fluid, up.rho, up.T, p_down)


@dataclass(frozen=True)
class RealGasPoint(GasPoint):
    """A :class:`exchange.vent.GasPoint` of a real-gas cavity: also its fluid (equation of state); R is p/(ρT)
    and γ the isentropic exponent ρc²/p there."""

    fluid: object = None

    def choke_ratio(self) -> float:
        """p*/p0 of :func:`real_gas_critical_state` [-]."""
        return real_gas_critical_state(self.fluid, self.rho, self.T)[0] / self.p


def real_gas_point(state) -> RealGasPoint:
    """The flow-law view of a :class:`cavity.realgas_cavity.RealGasState`."""
    mix = state.mixture
    if mix.mass <= 0.0:
        return RealGasPoint(state.pressure, state.temperature, 0.0, 1.0, 1.4, 0.0, state.masses, state.fluid)
    return RealGasPoint(state.pressure, state.temperature, state.density, mix.gas_constant, mix.kappa,
                        state.specific_enthalpy, state.masses / mix.mass, state.fluid)
