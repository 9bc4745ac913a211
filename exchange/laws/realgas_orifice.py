"""Isentropic nozzle with a real-gas equation of state: choke point where the velocity equals the speed of sound.

From the stagnation (cavity) state (ρ0, T0) with enthalpy h0 and entropy s0, the gas expands along the isentrope
s = s0 to the throat; there, by energy conservation, v = √(2(h0 − h)) and the mass flux is G = ρ·v. Along the
isentrope dh = dp/ρ and dp = c²·dρ, so

    dG/dp|s = (v² − c²)/(c²·v),

which vanishes where v = c: the flux is largest (choked) at that throat pressure p*, and for p_down ≤ p* the
throat stays at p*. The isentrope is followed exactly: at any density ρ its temperature is the root of
s(ρ, T) = s0 (:func:`cavity.realgas.isentrope_temperature`), so h(ρ) and c(ρ) are those of the equation of state,
with no integration error. For an ideal gas of constant γ this is the law of :mod:`exchange.laws.orifice`
(tested to 1e-12), including its C¹ quadratic below Δp/p = :data:`exchange.laws.orifice.LINEAR_BELOW`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from cavity.realgas import TAYLOR_BELOW, RealGasSolveError, isentrope_temperature, shifted
from .discharge import discharge_coefficient
from .orifice import LINEAR_BELOW, orifice_mass_flow
from exchange.network.vent import GasPoint

__all__ = ["real_gas_critical_state", "real_gas_mass_flux", "RealGasOrificeLaw", "RealGasPoint", "real_gas_point"]

#: Newton iterations on the choke condition and the throat pressure (at most).
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


def _throat_newton(fluid, rho0, s0, rho, T, residual) -> tuple:
    r"""(ρ, T, FluidPoint, jet) of the throat: Newton's method in (ρ, T) on s(ρ, T) = s0 and
    ``residual(point, jet) -> (F, ∂F/∂ρ|T, ∂F/∂T|ρ)`` = 0, from (ρ, T); both unknowns together, one
    evaluation of the equation of state and its derivatives per iteration. A step below :data:`TAYLOR_BELOW` of ρ and T is
    taken without another evaluation (the point is the Taylor step of the last, exact to ~1e-14). Steps keep ρ
    between half its value and the midpoint to ρ0, and T above half its value. Also returns the last Jacobian
    (J11, J12, J21, J22) of (s, F) in (ρ, T), for :func:`_predicted`."""
    for _ in range(ITERATION_MAX):
        jet = fluid.jet(rho, T, True)
        pt, dT, dR = jet
        F1, F2, J21, J22 = pt[3] - s0, *residual(pt, jet)
        J11, J12 = dR[3], dT[3]
        det = J11 * J22 - J12 * J21
        d_rho, d_T = (J12 * F2 - F1 * J22) / det, (J21 * F1 - J11 * F2) / det
        if abs(d_rho) <= TAYLOR_BELOW * rho and abs(d_T) <= TAYLOR_BELOW * T:
            return rho + d_rho, T + d_T, shifted(jet, d_T, d_rho), jet, (J11, J12, J21, J22)
        rho_n = min(max(rho + d_rho, 0.5 * rho), 0.5 * (rho + rho0))
        T = max(T + d_T * (rho_n - rho) / d_rho if d_rho else T + d_T, 0.5 * T)
        rho = rho_n
    raise RealGasSolveError(f"{getattr(fluid, 'name', fluid)}: no throat state from rho0 = {rho0!r} kg/m^3 "
                            f"(last rho = {rho!r}, T = {T!r})")


def _predicted(last, rho0, ds0, dF) -> tuple | None:
    """(ρ, T) of the throat after the stagnation entropy changed by ds0 and the target of F by dF since the
    throat ``last`` = (ρ, T, s0, target, (J11, J12, J21, J22)): the implicit-function step J⁻¹·(ds0, dF)
    (s − s0 = 0 and F = target fix the throat, so J·dx = (ds0, dF)), exact to first order; None if it leaves
    0 < ρ < ρ0, T > 0."""
    rho, T, _, _, (J11, J12, J21, J22) = last
    det = J11 * J22 - J12 * J21
    rho, T = rho + (J22 * ds0 - J12 * dF) / det, T + (J11 * dF - J21 * ds0) / det
    return (rho, T) if 0.0 < rho < rho0 and T > 0.0 else None


def _sonic_point(fluid, rho0, T0, st0):
    """(ρ*, T*, FluidPoint) where 2(h0 − h) = c² on the isentrope of st0 (:func:`real_gas_critical_state`):
    :func:`_throat_newton` with F = 2(h0 − h) − c², ∂F/∂x = −2(∂h/∂x + c ∂c/∂x)."""
    h0, s0 = st0[2], st0[3]
    last = getattr(fluid, "last_choke", None)  # (ρ*/ρ0, T*/T0, p*/p0, the throat for _predicted)
    guess = _predicted(last[3], rho0, s0 - last[3][2], 2.0 * (last[3][3] - h0)) if last is not None else None
    if guess is not None:  # F = 2(h0 − h) − c² = 0: a change of h0 is one of −2·h0 in the target
        rho, T = guess
    elif last is None:
        kappa = rho0 * st0[4] ** 2 / st0[0]
        rho = rho0 * (2.0 / (kappa + 1.0)) ** (1.0 / (kappa - 1.0))
        T = _march(fluid, rho0, T0, s0, rho)[0]
    else:
        rho, T = rho0 * last[0], T0 * last[1]

    def choke(pt, jet):
        c, (_, a, b) = pt[4], jet
        return 2.0 * (h0 - pt[2]) - c * c, -2.0 * (b[2] + c * b[4]), -2.0 * (a[2] + c * a[4])

    rho, T, pt, _, J = _throat_newton(fluid, rho0, s0, rho, T, choke)
    return rho, T, pt, (rho, T, s0, h0, J)


def real_gas_critical_state(fluid, rho0: float, T0: float) -> tuple:
    r"""The choked throat of an isentropic nozzle fed from the stagnation state (ρ0, T0).

    Solves :math:`2(h_0 - h) = c^2` and :math:`s = s_0` by Newton's method in (ρ, T) together
    (:func:`_throat_newton`), started from the previous call's throat moved to first order by the change of
    (s0, h0) (:func:`_predicted`, kept on ``fluid``: an integrator asks for nearby states), or on the first call
    from the ideal-gas value :math:`\rho^* = \rho_0 (2/(\kappa+1))^{1/(\kappa-1)}` with the isentropic exponent
    κ = ρ0·c0²/p0, walked down the isentrope. The last Newton step, below 1e-7 of ρ and T, is taken as a Taylor
    step (ρ*, T* exact to ~1e-14; G*, stationary there, to round-off), so the start may change ρ* in its 14th
    digit.

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
    st0 = _stagnation(fluid, rho0, T0)[0]
    h0 = st0[2]
    rho_b, T_b, pb, throat = _sonic_point(fluid, rho0, T0, st0)
    v = math.sqrt(max(2.0 * (h0 - pb[2]), 0.0))
    fluid.last_choke = (rho_b / rho0, T_b / T0, pb[0] / st0[0], throat)
    return pb[0], rho_b * v, rho_b, T_b


#: Throat/stagnation pressure ratio above which h0 − h is integrated (∫ c²/ρ dρ along the isentrope) instead of
#: differenced: there h0 − h is under 1 % of h and the difference would lose more than two digits.
QUADRATURE_ABOVE = 0.99
#: Gauss–Lobatto's 4-point rule on [−1, 1] (exact to degree 5): the end nodes are the throat and the stagnation
#: state, already known; two interior evaluations.
_LOBATTO4 = ((-1.0, 1.0 / 6.0), (-0.4472135954999579, 5.0 / 6.0), (0.4472135954999579, 5.0 / 6.0), (1.0, 1.0 / 6.0))


def _stagnation(fluid, rho0, T0) -> tuple:
    """The jet (:meth:`cavity.realgas.RealFluid.jet`, with density derivatives) of the stagnation state, kept
    for the last (ρ0, T0): the flux, its choke point and the choke switch ask for the same state."""
    kept = getattr(fluid, "_stagnation", None)
    if kept is not None and kept[0] == rho0 and kept[1] == T0:
        return kept[2]
    jet = fluid.jet(rho0, T0, True)
    try:
        fluid._stagnation = (rho0, T0, jet)
    except AttributeError:  # a fluid that keeps nothing
        pass
    return jet


def _isentrope_slope(jet) -> float:
    """dT/dρ along the isentrope [K m^3/kg] at a jet's point: −(∂s/∂ρ|T)/(∂s/∂T|ρ)."""
    return -jet[2][3] / jet[1][3]


def _enthalpy_drop(fluid, rho0, T0, stag, rho_t, T_t, throat, c_t):
    r"""h0 − h(ρ_t) = ∫ c²/ρ dρ from ρ_t to ρ0 along the isentrope s0 (dh = dp/ρ, dp = c² dρ), by 4-point
    Gauss–Lobatto quadrature [J/kg] (the interval is short, p_t ≥ 0.99 p0, and the integrand smooth: the rule's
    error, ~(Δρ/ρ)^6/10^5, is below 1e-14). The end nodes are the throat (speed of sound c_t) and the stagnation
    state; each interior node's temperature starts from the cubic Hermite interpolant of T(ρ) with the
    isentrope's slopes at both ends (the ``stag`` and ``throat`` jets): one evaluation each, mostly."""
    s0, d = stag[0][3], rho0 - rho_t
    m_t, m_0 = _isentrope_slope(throat) * d, _isentrope_slope(stag) * d
    half, mid = 0.5 * d, 0.5 * (rho0 + rho_t)
    total = (c_t * c_t / rho_t + stag[0][4] ** 2 / rho0) / 6.0
    for x, w in _LOBATTO4[1:3]:
        rho, z = mid + half * x, 0.5 * (1.0 + x)  # z from 0 (throat) to 1 (stagnation)
        guess = ((2 * z ** 3 - 3 * z * z + 1) * T_t + (z ** 3 - 2 * z * z + z) * m_t + (3 * z * z - 2 * z ** 3) * T0
                 + (z ** 3 - z * z) * m_0)
        pt = isentrope_temperature(fluid, rho, s0, guess)[1]
        total += w * pt[4] ** 2 / rho
    return half * total


def _subsonic_guess(fluid, rho0, T0, st0, p_t) -> tuple:
    """(ρ, T) to start the throat at p_t from: the previous subsonic throat moved by :func:`_predicted`, else
    ρ0·(p_t/p0)^(1/κ0) and T between T0 and the last T* (or walked down the isentrope on a first call)."""
    q, last = p_t / st0[0], getattr(fluid, "last_throat", None)
    guess = _predicted(last, rho0, st0[3] - last[2], p_t - last[3]) if last is not None else None
    if guess is not None:
        return guess
    rho = rho0 * q ** (st0[0] / (rho0 * st0[4] ** 2))
    choke = getattr(fluid, "last_choke", None)
    if choke is not None:
        return rho, T0 * (1.0 - (1.0 - choke[1]) * (1.0 - q) / (1.0 - choke[2]))
    return rho, _march(fluid, rho0, T0, st0[3], rho)[0]


def _flux_at_pressure(fluid, rho0, T0, stag, p_t):
    """(G, dG/dp) at throat pressure p_t >= p* on the isentrope of the ``stag`` jet: :func:`_throat_newton` with
    F = p − p_t."""
    st0 = stag[0]
    rho, T = _subsonic_guess(fluid, rho0, T0, st0, p_t)
    rho, T, pt, jet, J = _throat_newton(fluid, rho0, st0[3], rho, T,
                                        lambda pt, jet: (pt[0] - p_t, jet[2][0], jet[1][0]))
    c2 = pt[4] ** 2
    fluid.last_throat = (rho, T, st0[3], p_t, J)
    if p_t < QUADRATURE_ABOVE * st0[0]:
        drop = st0[2] - pt[2]
    else:
        drop = _enthalpy_drop(fluid, rho0, T0, stag, rho, T, jet, pt[4])
    v2 = 2.0 * drop
    v = math.sqrt(max(v2, 0.0))
    return rho * v, (v2 - c2) / (c2 * v) if v > 0.0 else math.inf


def real_gas_mass_flux(fluid, rho0: float, T0: float, p_down: float) -> float:
    r"""Mass flux through an isentropic real-gas nozzle [kg/(s m^2)], choked below the critical pressure.

    .. math::

        G = \rho_t \sqrt{2\,(h_0 - h(\rho_t))},\quad s(\rho_t, T_t) = s_0,\quad
        p_t = \max(p_{down},\, p^*)

    with p* from :func:`real_gas_critical_state`. When the previous call's p*/p0 puts p_down above the choke
    point, the throat at p_down is computed first and kept if its velocity is below the speed of sound there
    (dG/dp ≤ 0: then p_down ≥ p*, the isentrope crossing v = c once), saving the choke search. Below a relative
    pressure difference s = Δp/p0 of
    :data:`exchange.laws.orifice.LINEAR_BELOW` the flux is the quadratic a·s + b·s² matching G and dG/ds at s = 1e-4
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
    stag = _stagnation(fluid, rho0, T0)
    p0 = stag[0][0]
    if p_down >= p0:
        return 0.0
    s = (p0 - p_down) / p0
    if s < LINEAR_BELOW:
        d = LINEAR_BELOW
        f, dGdp = _flux_at_pressure(fluid, rho0, T0, stag, p0 * (1.0 - d))
        fp = -p0 * dGdp
        return s * ((2.0 * f - fp * d) / d + s * (fp * d - f) / (d * d))
    last = getattr(fluid, "last_choke", None)
    if last is not None and p_down > last[2] * p0:  # likely subsonic: a throat at p_down with v <= c proves it
        G, dGdp = _flux_at_pressure(fluid, rho0, T0, stag, p_down)
        if dGdp <= 0.0:
            return G
    p_star, G_star, _, _ = real_gas_critical_state(fluid, rho0, T0)
    if p_down <= p_star:
        return G_star
    return _flux_at_pressure(fluid, rho0, T0, stag, p_down)[0]


@dataclass(frozen=True)
class RealGasOrificeLaw:
    """The orifice law (:class:`exchange.laws.orifice.OrificeLaw`) with the upstream cavity's real-gas equation of state.

    ``mass_flow(up, p_down, area, t) = Cd·A·G`` with G from :func:`real_gas_mass_flux` when the upstream gas point
    carries a fluid (``up.fluid``, a real-gas cavity), else the ideal law (gas flowing back in from ambient).
    """

    discharge_coefficient: object = 1.0
    pneumatic = True
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        cd = discharge_coefficient(self.discharge_coefficient, up.p, t)
        fluid = getattr(up, "fluid", None)
        if fluid is None:
            return orifice_mass_flow(up.p, up.T, p_down, up.R, up.gamma, area, cd)
        return cd * area * real_gas_mass_flux(fluid, up.rho, up.T, p_down)


@dataclass(frozen=True)
class RealGasPoint(GasPoint):
    """A :class:`exchange.network.vent.GasPoint` of a real-gas cavity: also its fluid (equation of state); R is p/(ρT)
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
