"""Real-gas equation of state: a CoolProp HEOS fluid evaluated at (density, temperature), state from (ρ, u).

The Helmholtz-energy equations of state behind CoolProp's ``HEOS`` backend are explicit in (ρ, T): an update
with ``DmassT_INPUTS`` evaluates them directly (no flash), in about 3 µs on the reference machine (measured in
``docs/realgas.md``), and p, u, h, s, c and cv are then getters of 0.1 µs. The state of a rigid cavity
of mass m, internal energy U and volume V is found by Newton's method on T at fixed ρ = m/V:

    u(ρ, T) = U/m,     ∂u/∂T|ρ = cv > 0,

started from the previous temperature, so 2–3 updates per state. Nothing is interpolated: the pressure is
HEOS's to the Newton tolerance (|Δu| ≤ 1e-13·|u| + 1e-9 J/kg, a pressure error far below 1e-10 relative).
CoolProp's tabular backends (``BICUBIC&HEOS``, ``TTSE&HEOS``) were measured and rejected: they do not accept
(ρ, T) or (ρ, u) inputs and their (p, h) tables were off by up to 2e-2 in p near the critical region
(``docs/realgas.md``), far from the 1e-6 the issue asks.

Energies are shifted by a constant per fluid (:attr:`RealFluid.offset`) so that the ideal-gas limit of u and h
equals that of the scene's ideal-gas species of the same fluid (a CoolProp cp0 fit): gas can then flow between
an ideal-gas region (ambient) and a real-gas cavity with one enthalpy reference.
"""
from __future__ import annotations

import math

__all__ = ["RealFluid", "IdealGasFluid", "FluidPoint", "temperature_from_energy", "isentrope_temperature", "IDEAL_LIMIT_DENSITY",
           "MetastableFluid",
           "RealGasSolveError"]


class RealGasSolveError(ArithmeticError):
    """Newton's method found no temperature for the given density and energy (or entropy)."""


#: Newton stops when the step is below this fraction of T [-] (quadratic convergence: one step more is exact).
NEWTON_RTOL = 1e-13
NEWTON_MAX = 50
#: Density [kg/m^3] at which the ideal-gas limit is taken for the energy offset (non-ideality ~1e-9).
IDEAL_LIMIT_DENSITY = 1e-6


class FluidPoint(tuple):
    """(p [Pa], u [J/kg], h [J/kg], s [J/(kg K)], c [m/s], cv [J/(kg K)]) at one (ρ, T)."""

    __slots__ = ()
    p = property(lambda self: self[0])
    u = property(lambda self: self[1])
    h = property(lambda self: self[2])
    s = property(lambda self: self[3])
    c = property(lambda self: self[4])
    cv = property(lambda self: self[5])


class RealFluid:
    """A CoolProp HEOS pure or pseudo-pure fluid, evaluated at (ρ, T).

    Parameters
    ----------
    coolprop_name : str
        CoolProp fluid (``"Nitrogen"``, ``"Air"``, ``"Helium"``, ``"Hydrogen"``, ``"CarbonDioxide"``).
    ideal_enthalpy : callable or None
        ``h_ideal(T) -> J/kg`` of the scene's ideal-gas species of this fluid; the offset makes HEOS's ideal-gas
        limit equal it at ``reference_temperature``. None: no offset (HEOS's own reference state).
    reference_temperature : float
        [K].

    Examples
    --------
    >>> f = RealFluid("Nitrogen")
    >>> pt = f.at(100.0, 300.0)
    >>> round(pt.p / 1e5, 4), round(f.temperature(100.0, pt.u, 250.0), 10)
    (89.2492, 300.0)
    """

    def __init__(self, coolprop_name: str, ideal_enthalpy=None, reference_temperature: float = 300.0):
        import CoolProp.CoolProp as CP

        self.name = coolprop_name
        self._state = CP.AbstractState("HEOS", coolprop_name)
        self._film = CP.AbstractState("HEOS", coolprop_name)
        self._DT, self._PT = CP.DmassT_INPUTS, CP.PT_INPUTS
        self.molar_mass = self._state.molar_mass()
        self.offset = 0.0
        if ideal_enthalpy is not None:
            Tr = reference_temperature
            self._state.update(self._DT, IDEAL_LIMIT_DENSITY, Tr)
            self.offset = ideal_enthalpy(Tr) - self._state.hmass()
        self.metastable = MetastableFluid(self)

    def __repr__(self) -> str:
        return f"RealFluid({self.name!r}, offset={self.offset!r})"

    def at(self, rho: float, T: float) -> FluidPoint:
        """The fluid at density ρ [kg/m^3] and temperature T [K] (energies include :attr:`offset`)."""
        st = self._state
        st.update(self._DT, rho, T)
        off = self.offset
        try:
            c = st.speed_sound()
        except ValueError:
            raise RealGasSolveError(f"{self.name} at rho = {rho!r} kg/m^3, T = {T!r} K is two-phase: a real-gas "
                                    "cavity holds a single-phase fluid") from None
        return FluidPoint((st.p(), st.umass() + off, st.hmass() + off, st.smass(), c, st.cvmass()))

    def density(self, p: float, T: float) -> float:
        """Density [kg/m^3] at pressure p [Pa] and temperature T [K] (a CoolProp flash, for initial states)."""
        self._film.update(self._PT, p, T)
        return self._film.rhomass()

    def temperature(self, rho: float, u: float, T_guess: float) -> float:
        """The temperature [K] of :func:`temperature_from_energy` of this fluid."""
        return temperature_from_energy(self, rho, u, T_guess)[0]

    def film_properties(self, p: float, T: float) -> tuple:
        """(ρ [kg/m^3], cp [J/(kg K)], μ [Pa s], k [W/(m K)], β [1/K]) at p [Pa], T [K], for convection
        correlations (:mod:`cavity.wall`)."""
        st = self._film
        st.update(self._PT, p, T)
        return st.rhomass(), st.cpmass(), st.viscosity(), st.conductivity(), st.isobaric_expansion_coefficient()


class MetastableFluid:
    """The same fluid with its phase imposed as gas: (ρ, T) states past the saturation line are the equation of
    state's metastable (supersaturated) continuation instead of a two-phase mixture, identical to
    :meth:`RealFluid.at` wherever the fluid is single-phase. Used for the expansion to an orifice's throat, which
    is taken as frozen: a gas crossing the saturation line in the microseconds of its passage does not condense
    (supersaturated nozzle flow, as in steam nozzles up to the Wilson line). The cavity's own state is never
    metastable (:meth:`RealFluid.at` refuses two-phase states)."""

    def __init__(self, fluid: RealFluid):
        import CoolProp.CoolProp as CP

        self.name, self._fluid = fluid.name, fluid
        self._state = CP.AbstractState("HEOS", fluid.name)
        self._state.specify_phase(CP.iphase_gas)
        self._DT = CP.DmassT_INPUTS
        self.last_choke = None

    def fundamental_derivative(self) -> float:
        """Γ = 1 + (ρ/c)(∂c/∂ρ)_s [-] at the state of the last :meth:`at` call."""
        return self._state.fundamental_derivative_of_gas_dynamics()

    def at(self, rho: float, T: float) -> FluidPoint:
        """:meth:`RealFluid.at`, continued past the saturation line."""
        st = self._state
        try:
            st.update(self._DT, rho, T)
            c = st.speed_sound()
        except ValueError as exc:
            raise RealGasSolveError(f"{self.name}: the expansion to the throat reaches rho = {rho!r} kg/m^3, T = {T!r} K "
                                    f"where the equation of state fails ({exc}): flashing (two-phase) orifice flow "
                                    "is not modelled") from None
        off = self._fluid.offset
        return FluidPoint((st.p(), st.umass() + off, st.hmass() + off, st.smass(), c, st.cvmass()))


def temperature_from_energy(fluid, rho: float, u: float, T_guess: float) -> tuple:
    r"""Temperature [K] at which ``fluid`` of density ρ has specific internal energy u, by Newton's method, and
    the fluid there (a :class:`FluidPoint`).

    .. math:: T_{k+1} = T_k - \frac{u(\rho, T_k) - u}{c_v(\rho, T_k)}

    Parameters
    ----------
    fluid : RealFluid (or anything with ``at(rho, T) -> FluidPoint``)
    rho : float
        Density [kg/m^3], > 0.
    u : float
        Specific internal energy [J/kg] (with the fluid's offset).
    T_guess : float
        Start [K] (the previous temperature).

    Notes
    -----
    u is strictly increasing in T at fixed ρ outside the two-phase dome (cv > 0), so the iteration converges
    from a nearby guess; steps are limited to halve T at most. It stops when the next step would be below
    1e-13·T and returns the last point evaluated.

    Examples
    --------
    >>> f = RealFluid("Helium")
    >>> round(temperature_from_energy(f, 30.0, f.at(30.0, 80.0).u, 300.0)[0], 9)
    80.0
    """
    T = T_guess
    for _ in range(NEWTON_MAX):
        pt = fluid.at(rho, T)
        step = (pt[1] - u) / pt[5]
        if abs(step) <= NEWTON_RTOL * T:
            return T, pt
        T = T - step if step < 0.5 * T else 0.5 * T
    raise RealGasSolveError(f"{getattr(fluid, 'name', fluid)}: no temperature for rho = {rho!r} kg/m^3, "
                            f"u = {u!r} J/kg (last T = {T!r} K)")


def isentrope_temperature(fluid, rho: float, s: float, T_guess: float) -> tuple:
    r"""Temperature [K] of ``fluid`` at density ρ on the isentrope of specific entropy s [J/(kg K)], and the
    fluid there (a :class:`FluidPoint`).

    .. math:: T_{k+1} = T_k - \frac{s(\rho, T_k) - s}{c_v(\rho, T_k)/T_k}

    (∂s/∂T|ρ = cv/T). It stops when the next step would be below 1e-13·T and returns the last point evaluated
    (its T is then exact to that level). Limits as :func:`temperature_from_energy`.

    Examples
    --------
    >>> f = RealFluid("Nitrogen")
    >>> s0 = f.at(300.0, 300.0).s
    >>> round(isentrope_temperature(f, 300.0, s0, 200.0)[0], 9)
    300.0
    """
    T = T_guess
    for _ in range(NEWTON_MAX):
        pt = fluid.at(rho, T)
        step = (pt[3] - s) * T / pt[5]
        if abs(step) <= NEWTON_RTOL * T:
            return T, pt
        T = T - step if step < 0.5 * T else 0.5 * T
    raise RealGasSolveError(f"{getattr(fluid, 'name', fluid)}: no isentrope temperature for rho = {rho!r} "
                            f"kg/m^3, s = {s!r} J/(kg K) (last T = {T!r} K)")


class IdealGasFluid:
    """An ideal gas of constant cp with the :class:`RealFluid` interface (for tests of the real-gas laws).

    Parameters: specific gas constant R [J/(kg K)], ratio of specific heats γ [-]. u = cv·T, h = cp·T,
    s = cv·ln T − R·ln ρ, c = √(γRT).

    Examples
    --------
    >>> g = IdealGasFluid(287.0, 1.4)
    >>> round(g.at(1.2, 300.0).p, 6)
    103320.0
    """

    def __init__(self, R: float, gamma: float):
        self.name, self.R, self.gamma = "ideal", R, gamma
        self.cv = R / (gamma - 1.0)
        self.offset = 0.0

    def fundamental_derivative(self) -> float:
        """Γ = (γ + 1)/2 [-] (constant for an ideal gas of constant cp)."""
        return 0.5 * (self.gamma + 1.0)

    def at(self, rho: float, T: float) -> FluidPoint:
        R, cv = self.R, self.cv
        return FluidPoint((rho * R * T, cv * T, (cv + R) * T, cv * math.log(T) - R * math.log(rho),
                           math.sqrt(self.gamma * R * T), cv))
