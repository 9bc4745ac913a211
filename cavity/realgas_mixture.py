"""Real-gas mixtures of fixed composition: CoolProp HEOS mixture states and the derivatives CoolProp lacks.

CoolProp's HEOS backend evaluates a mixture (GERG-2008-style departure functions, ``"Nitrogen&Argon"``) at
(ρ, T) like a pure fluid, with two differences measured on the reference machine (``docs/realgas.md``):

- an update runs a phase-stability analysis first, ~10 ms; with the phase imposed as gas
  (``specify_phase(iphase_gas)``) it is 3–7 µs. States of a mixture are therefore always evaluated as gas, and
  a cavity's initial state is checked once, without the imposed phase, to be single-phase
  (:func:`check_single_phase`);
- the derivatives of c (and of cv) are refused (CoolProp has no third derivative of the mixture's ideal-gas
  Helmholtz energy). :func:`mixture_jet` forms them from ∂p, ∂²p, the residual Helmholtz energy's third
  τ-derivative and the ideal-gas cv0'(T) of the components (:class:`IdealHeatCapacitySlope`).

Transport properties of a mixture are CoolProp's own estimates at the mixture's T and molar density ρ̃:
μ = exp(Σ x_i ln μ_i(T, ρ̃)) and k = Σ x_i k_i(T, ρ̃) (mole-fraction-weighted; checked against the pure fluids'
in ``tests/realgas/test_realgas_mixture.py``).
"""
from __future__ import annotations

import math

__all__ = ["heos_state", "is_mixture", "IdealHeatCapacitySlope", "MixtureTransport", "entropy_correction", "mixture_jet", "density_at_pressure",
           "check_single_phase", "SLOPE_NODE_SPACING"]

#: Spacing [K] of the temperature nodes at which the components' cv0'(T) is evaluated (linear between).
SLOPE_NODE_SPACING = 0.5


def is_mixture(coolprop_name: str) -> bool:
    """True for a CoolProp mixture name (components joined by ``&``).

    >>> is_mixture("Nitrogen&Argon"), is_mixture("Nitrogen")
    (True, False)
    """
    return "&" in coolprop_name


def heos_state(coolprop_name: str, mass_fractions=None, gas_phase: bool = False):
    """A CoolProp ``AbstractState("HEOS", name)``; for a mixture with its ``mass_fractions`` set and, with
    ``gas_phase`` (always for a mixture), its phase imposed as gas."""
    import CoolProp.CoolProp as CP

    st = CP.AbstractState("HEOS", coolprop_name)
    if is_mixture(coolprop_name):
        st.set_mass_fractions(list(mass_fractions))
    if gas_phase or is_mixture(coolprop_name):
        st.specify_phase(CP.iphase_gas)
    return st


class IdealHeatCapacitySlope:
    r"""d cv0/dT [J/(kg K²)] of a mixture's ideal-gas part, from its components.

    .. math:: \frac{dc_{v0}}{dT} = \frac{1}{M}\sum_i x_i\,\frac{R_i\,\tau_i^2}{T}\left(2\alpha^0_{i,\tau\tau}
              + \tau_i\,\alpha^0_{i,\tau\tau\tau}\right),\quad \tau_i = T_{r,i}/T

    (M the mixture's molar mass, R_i [J/(mol K)] the gas constant of component i's equation of state, as CoolProp
    forms a mixture's cv0 = Σ x_i c̃_v0,i/M, c̃_v0,i = −R_i τ_i² α⁰_i,ττ; they differ from each other by up to 6e-6).
    Evaluated exactly at nodes :data:`SLOPE_NODE_SPACING` apart, filled as they are first needed, and linear
    between: cv0' only enters the derivatives of c (Newton slopes and the 1e-7 Taylor steps), where its interpolation error, below 1e-5
    relative, moves c by less than 1e-13 relative.

    Examples
    --------
    >>> slope = IdealHeatCapacitySlope(("Nitrogen", "Argon"), (0.8, 0.2), 0.0304)
    >>> round(slope(300.0) * 1e3, 2)  # N2's 4.9e-4 J/(mol K²) (vibration) · 0.8 / M; Ar's cv0 is constant
    12.81
    """

    def __init__(self, components, mole_fractions, molar_mass: float):
        import CoolProp.CoolProp as CP

        self._pure = [CP.AbstractState("HEOS", name) for name in components]
        self._xR = tuple(x * st.gas_constant() / molar_mass for x, st in zip(mole_fractions, self._pure))
        self._DT = CP.DmolarT_INPUTS
        self._nodes = {}

    def exact(self, T: float) -> float:
        """The slope at T [K], evaluated (one update per component)."""
        total = 0.0
        for st, xR in zip(self._pure, self._xR):
            st.update(self._DT, 1e-3, T)
            tau = st.T_reducing() / T
            total += xR * tau * tau * (2.0 * st.d2alpha0_dTau2() + tau * st.d3alpha0_dTau3())
        return total / T

    def __call__(self, T: float) -> float:
        z = T / SLOPE_NODE_SPACING
        k = math.floor(z)
        nodes = self._nodes
        a = nodes.get(k)
        if a is None:
            a = nodes[k] = self.exact(k * SLOPE_NODE_SPACING)
        b = nodes.get(k + 1)
        if b is None:
            b = nodes[k + 1] = self.exact((k + 1) * SLOPE_NODE_SPACING)
        return a + (z - k) * (b - a)


class MixtureTransport:
    r"""Viscosity [Pa s] and conductivity [W/(m K)] of a mixture by CoolProp's own mixing rule for HEOS mixtures,

    .. math:: \mu = \exp\Big(\sum_i x_i \ln \mu_i(T, \tilde\rho)\Big),\qquad k = \sum_i x_i\,k_i(T, \tilde\rho)

    (x_i mole fractions, μ_i and k_i the pure fluids' transport models at the mixture's temperature and molar
    density ρ̃), evaluated on pure-fluid states (gas phase imposed): the same numbers as the mixture state's own
    ``viscosity()`` and ``conductivity()`` (tested to 1e-12) at ~15 µs for two components instead of ~800 µs.
    A mole-fraction-weighted estimate, not a mixture transport model: for components of very different molar
    mass (He/Ar) it can be off by tens of per cent against kinetic-theory rules (Wilke's).
    """

    def __init__(self, components, mole_fractions):
        import CoolProp.CoolProp as CP

        self._pure = [heos_state(name, gas_phase=True) for name in components]
        self._x = tuple(mole_fractions)
        self._DT = CP.DmolarT_INPUTS

    def __call__(self, rho_molar: float, T: float) -> tuple:
        """(μ [Pa s], k [W/(m K)]) at molar density [mol/m^3] and temperature [K]."""
        log_mu = k = 0.0
        for st, x in zip(self._pure, self._x):
            st.update(self._DT, rho_molar, T)
            log_mu += x * math.log(st.viscosity())
            k += x * st.conductivity()
        return math.exp(log_mu), k


def entropy_correction(st) -> float:
    r"""C [J/(kg K)] such that s = ``smass()`` + C·ln ρ is the entropy of the CoolProp HEOS mixture state ``st``
    consistent with its own u, p and analytic derivatives (T ds = du − p dρ/ρ², ∂s/∂ρ|T = −∂p/∂T|ρ/ρ²).

    .. math:: C = \frac{\sum_i x_i R_i - R}{M}

    CoolProp's ``smass()`` of a mixture carries the ideal-gas term −R_i ln δ of each component with that
    component's own gas constant R_i (8.31451 J/(mol K) for N2, Ar, CO2), while its pressure, energy and every
    derivative use the mixture's R (8.314462618 J/(mol K)): the value's ρ-derivative differs from the analytic one
    by (Σ x_i R_i − R)/(Mρ), 5.7e-6 of the ideal term, enough to break an isentropic expansion's entropy balance
    at 1e-6. With C the two agree to the differences' own round-off (``tests/realgas/test_realgas_mixture.py``).

    Examples
    --------
    >>> st = heos_state("Nitrogen&Argon", (0.7372, 0.2628))
    >>> round(entropy_correction(st) * 1e3, 3)
    1.558
    """
    import CoolProp.CoolProp as CP

    R_bar = sum(x * CP.AbstractState("HEOS", name).gas_constant()
                for name, x in zip(st.fluid_names(), st.get_mole_fractions()))
    return (R_bar - st.gas_constant()) / st.molar_mass()


def mixture_jet(slope, st, pt, rho: float, T: float, keys, density_too: bool) -> tuple:
    r"""The jet of :func:`cavity.realgas._jet` for a CoolProp mixture state ``st`` at (ρ, T): the same fields and
    identities, with ∂c from

    .. math:: c^2 = p_\rho + \frac{T p_T^2}{\rho^2 c_v},\quad
              \partial_T c^2 = p_{\rho T} + \frac{p_T^2 + 2 T p_T p_{TT}}{\rho^2 c_v}
              - \frac{T p_T^2\,c_{v,T}}{\rho^2 c_v^2},\quad
              \partial_\rho c^2 = p_{\rho\rho} + \frac{2 T p_T p_{\rho T}}{\rho^2 c_v}
              - \frac{2 T p_T^2}{\rho^3 c_v} - \frac{T p_T^2\,c_{v,\rho}}{\rho^2 c_v^2}

    with c_v,ρ = −T p_TT/ρ² (Maxwell) and c_v,T = cv0'(T) (``slope``, :class:`IdealHeatCapacitySlope`) plus the
    residual part (R/M)·τ²(2α^r_ττ + τ α^r_τττ)/T, τ = T_r/T. All second derivatives of p are CoolProp's."""
    iP, iC, iD, iT = keys
    d, d2 = st.first_partial_deriv, st.second_partial_deriv
    p, c, cv = pt[0], pt[4], pt[5]
    p_T, p_TT, p_rT = d(iP, iT, iD), d2(iP, iT, iD, iT, iD), d2(iP, iD, iT, iT, iD)
    tau = st.T_reducing() / T
    cv_T = slope(T) + st.gas_constant() / st.molar_mass() * tau * tau * (
        2.0 * st.d2alphar_dTau2() + tau * st.d3alphar_dTau3()) / T
    r2 = rho * rho
    a = T * p_T * p_T / (r2 * cv)
    c2_T = p_rT + (p_T * p_T + 2.0 * T * p_T * p_TT) / (r2 * cv) - a * cv_T / cv
    dT = (p_T, cv, cv + p_T / rho, cv / T, 0.5 * c2_T / c, 0.0)
    if not density_too:
        return pt, dT, None
    p_rho, p_rr = d(iP, iD, iT), d2(iP, iD, iT, iD, iT)
    c2_r = p_rr + 2.0 * T * p_T * p_rT / (r2 * cv) - 2.0 * a / rho + a * T * p_TT / (r2 * cv)
    u_rho = (p - T * p_T) / r2
    return pt, dT, (p_rho, u_rho, u_rho + p_rho / rho - p / r2, -p_T / r2, 0.5 * c2_r / c, 0.0)


def density_at_pressure(st, p: float, T: float, rho: float) -> float:
    r"""Density [kg/m^3] at which CoolProp state ``st`` has pressure p [Pa] at temperature T [K], by Newton's
    method from ρ (ρ ← ρ − (p(ρ, T) − p)/p_ρ) to 1e-13 relative; ``st`` is left at the result. (HEOS's own
    (p, T) flash of a mixture costs ~40 µs; this, from a nearby density, one or two 5 µs updates.)"""
    import CoolProp.CoolProp as CP

    DT, iP, iD, iT = CP.DmassT_INPUTS, CP.iP, CP.iDmass, CP.iT
    for _ in range(50):
        st.update(DT, rho, T)
        step = (st.p() - p) / st.first_partial_deriv(iP, iD, iT)
        rho_n = rho - step if step < 0.5 * rho else 0.5 * rho
        if abs(step) <= 1e-13 * rho:
            return rho
        rho = rho_n
    raise ArithmeticError(f"{'&'.join(st.fluid_names())}: no density for p = {p!r} Pa at T = {T!r} K")


def check_single_phase(coolprop_name: str, mass_fractions, rho: float, T: float) -> None:
    """Raise ValueError if the mixture at (ρ, T) is two-phase by CoolProp's own phase determination (a stability
    analysis, 13–15 ms: for initial states only)."""
    import CoolProp.CoolProp as CP

    st = CP.AbstractState("HEOS", coolprop_name)
    st.set_mass_fractions(list(mass_fractions))
    st.update(CP.DmassT_INPUTS, rho, T)
    if st.phase() == CP.iphase_twophase:
        raise ValueError(f"{coolprop_name} at rho = {rho:.6g} kg/m^3, T = {T:.6g} K is two-phase: a real-gas cavity "
                         "holds a single-phase fluid")
