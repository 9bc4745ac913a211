"""Real-gas equation of state: a CoolProp HEOS fluid evaluated at (density, temperature), state from (ρ, u).

The Helmholtz-energy equations of state behind CoolProp's ``HEOS`` backend are explicit in (ρ, T): an update
with ``DmassT_INPUTS`` evaluates them directly (no flash), in about 3 µs on the reference machine (measured in
``docs/realgas.md``), and p, u, h, s, c and cv are then getters of 0.1 µs. The state of a rigid cavity
of mass m, internal energy U and volume V is found by Newton's method on T at fixed ρ = m/V:

    u(ρ, T) = U/m,     ∂u/∂T|ρ = cv > 0,

started from a first-order prediction off the previous state (:meth:`RealFluid.state`). Each evaluation also
takes CoolProp's analytic ∂p and ∂c (:meth:`RealFluid.jet`); once a Newton step is below 1e-7·T it is taken
without another evaluation, the point being the Taylor step of the last (:func:`shifted`): mostly one update per
state. Nothing is interpolated: the pressure is HEOS's to the quadratic remainder, ~1e-14 relative.
CoolProp's tabular backends (``BICUBIC&HEOS``, ``TTSE&HEOS``) were measured and rejected: they do not accept
(ρ, T) or (ρ, u) inputs and their (p, h) tables were off by up to 2e-2 in p near the critical region
(``docs/realgas.md``), far from the 1e-6 the issue asks.

Energies are shifted by a constant per fluid (:attr:`RealFluid.offset`) so that the ideal-gas limit of u and h
equals that of the scene's ideal-gas species of the same fluid (a CoolProp cp0 fit): gas can then flow between
an ideal-gas region (ambient) and a real-gas cavity with one enthalpy reference.
"""
from __future__ import annotations

import math
from functools import partial

from .realgas_mixture import (IdealHeatCapacitySlope, MixtureTransport, density_at_pressure, entropy_correction,
                              heos_state, is_mixture, mixture_jet)

__all__ = ["RealFluid", "IdealGasFluid", "FluidPoint", "temperature_from_energy", "isentrope_temperature", "IDEAL_LIMIT_DENSITY",
           "shifted", "TAYLOR_BELOW",
           "MetastableFluid",
           "RealGasSolveError"]


class RealGasSolveError(ArithmeticError):
    """Newton's method found no temperature for the given density and energy (or entropy)."""


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

    def __init__(self, coolprop_name: str, ideal_enthalpy=None, reference_temperature: float = 300.0,
                 mass_fractions=None):
        import CoolProp.CoolProp as CP

        self.name = coolprop_name
        self.mass_fractions = tuple(mass_fractions) if mass_fractions is not None else (1.0,)
        self._state = heos_state(coolprop_name, self.mass_fractions)
        self._film = heos_state(coolprop_name, self.mass_fractions)
        self._DT, self._PT = CP.DmassT_INPUTS, CP.PT_INPUTS
        self._keys = _derivative_keys(CP)
        self._jet_of = _jet
        self.molar_mass = self._state.molar_mass()
        self.mixture = is_mixture(coolprop_name)
        #: [K] below which a state of a mixture is cautioned (the highest critical temperature of its components;
        #: 0 for a pure fluid, whose two-phase states :meth:`at` refuses).
        self.caution_below, self.caution_component = 0.0, ""
        if self.mixture:
            self.caution_below, self.caution_component = max(
                (CP.PropsSI("Tcrit", name), name) for name in coolprop_name.split("&"))  # cavity.realgas_mixture: the c derivatives CoolProp refuses for a mixture
            self._jet_of = partial(mixture_jet, IdealHeatCapacitySlope(coolprop_name.split("&"),
                                                                       self._state.get_mole_fractions(),
                                                                       self.molar_mass))
            self.entropy_correction = entropy_correction(self._state)
            self.at = self._mixture_at
            self._film_rho, self._transport = None, MixtureTransport(coolprop_name.split("&"),
                                                                     self._state.get_mole_fractions())
        self.offset = 0.0
        if ideal_enthalpy is not None:
            Tr = reference_temperature
            self._state.update(self._DT, IDEAL_LIMIT_DENSITY, Tr)
            self.offset = ideal_enthalpy(Tr) - self._state.hmass()
        self.metastable = MetastableFluid(self)
        self._anchor = None  # (ρ, u, T, ∂u/∂ρ|T, cv) of the last :meth:`state`

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

    def _mixture_at(self, rho: float, T: float) -> FluidPoint:
        """:meth:`at` of a mixture: no two-phase test (its phase is imposed as gas), and the entropy made
        consistent with p and u (:func:`cavity.realgas_mixture.entropy_correction`)."""
        st = self._state
        st.update(self._DT, rho, T)
        off = self.offset
        return FluidPoint((st.p(), st.umass() + off, st.hmass() + off,
                           st.smass() + self.entropy_correction * math.log(rho), st.speed_sound(), st.cvmass()))

    def jet(self, rho: float, T: float, density_too: bool = False) -> tuple:
        """:meth:`at` and the partial derivatives of its fields: ``(point, d/dT at fixed ρ, d/dρ at fixed T or
        None)`` (:func:`_jet`: two or four of CoolProp's analytic derivatives, 0.15 µs each)."""
        return self._jet_of(self._state, self.at(rho, T), rho, T, self._keys, density_too)

    def state(self, rho: float, u: float, T_guess: float) -> tuple:
        """(T [K], FluidPoint) at density ρ [kg/m^3] and specific energy u [J/kg]: :func:`temperature_from_energy`
        started from the first-order prediction off the previous call, T_a + (u − u_a − ∂u/∂ρ|T·(ρ − ρ_a))/cv
        (an integrator asks for nearby states: one evaluation and a Taylor step, mostly), else from T_guess."""
        a = self._anchor
        if a is not None:
            guess = a[2] + (u - a[1] - a[3] * (rho - a[0])) / a[4]
            T_guess = guess if 0.5 * T_guess < guess < 2.0 * T_guess else T_guess
        try:
            T, pt, (last, dT, _) = _newton(self, rho, u, T_guess, 1)
        except RealGasSolveError:
            self._anchor = None
            return self._state_from_above(rho, u, T_guess)
        # ∂u/∂ρ|T = (p − T ∂p/∂T|ρ)/ρ² (from (∂u/∂v)_T = T(∂p/∂T)_v − p)
        self._anchor = (rho, u, T, (last[0] - T * dT[0]) / (rho * rho), last[5])
        return T, pt

    def _state_from_above(self, rho: float, u: float, T_guess: float) -> tuple:
        """(T, FluidPoint) when Newton's iterates entered the two-phase dome from a guess far below the state (a
        restart after a failure, a jump): Newton again from above the critical temperature, where no dome is, so
        that the iterates come down to a single-phase state from the gas side (u rises with T at fixed ρ, cv > 0);
        RealGasSolveError (two-phase) when the state itself is inside the dome."""
        try:
            T_top = 1.5 * self._state.T_critical()
        except ValueError:  # a mixture: CoolProp has no single critical point (its phase is imposed anyway)
            T_top = 2.0 * T_guess
        return _newton(self, rho, u, max(T_guess, T_top), 1)[:2]

    def density(self, p: float, T: float) -> float:
        """Density [kg/m^3] at pressure p [Pa] and temperature T [K] (a CoolProp flash, for initial states)."""
        self._film.update(self._PT, p, T)
        rho = self._film.rhomass()
        if self.mixture:  # the flash's density to the last digit of p(ρ, T)
            rho = density_at_pressure(self._film, p, T, rho)
        return rho

    def temperature(self, rho: float, u: float, T_guess: float) -> float:
        """The temperature [K] of :func:`temperature_from_energy` of this fluid."""
        return temperature_from_energy(self, rho, u, T_guess)[0]

    def film_properties(self, p: float, T: float) -> tuple:
        """(ρ [kg/m^3], cp [J/(kg K)], μ [Pa s], k [W/(m K)], β [1/K]) at p [Pa], T [K], for convection
        correlations (:mod:`cavity.wall`)."""
        st = self._film
        if self.mixture:  # Newton on ρ from the last film state: a mixture's (p, T) flash costs ~40 µs
            last = self._film_rho
            self._film_rho = density_at_pressure(st, p, T, last[0] * (p / last[1]) * (last[2] / T) if last
                                                 else p / (st.gas_constant() / self.molar_mass * T)), p, T
            return (st.rhomass(), st.cpmass(), *self._transport(st.rhomolar(), T),
                    st.isobaric_expansion_coefficient())
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
        self._state = heos_state(fluid.name, fluid.mass_fractions, gas_phase=True)
        self._DT = CP.DmassT_INPUTS
        self._keys, self._jet_of = fluid._keys, fluid._jet_of
        self.last_choke = self.last_throat = None  # warm starts of exchange.realgas_orifice

    def jet(self, rho: float, T: float, density_too: bool = False) -> tuple:
        """:meth:`RealFluid.jet` on the metastable continuation."""
        return self._jet_of(self._state, self.at(rho, T), rho, T, self._keys, density_too)

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
        off, s = self._fluid.offset, st.smass()
        if self._fluid.mixture:
            s += self._fluid.entropy_correction * math.log(rho)
        return FluidPoint((st.p(), st.umass() + off, st.hmass() + off, s, c, st.cvmass()))


def _derivative_keys(CP) -> tuple:
    """CoolProp's keys of p, c, ρ and T."""
    return CP.iP, CP.ispeed_sound, CP.iDmass, CP.iT


def _jet(st, pt, rho, T, keys, density_too: bool) -> tuple:
    r"""(pt, ∂/∂T|ρ, ∂/∂ρ|T or None) of the fields (p, u, h, s, c, cv) of ``pt``, the FluidPoint of CoolProp
    state ``st`` at (ρ, T): CoolProp's ∂p and ∂c, the rest by thermodynamic identities,

    .. math:: u_T = c_v,\ h_T = c_v + p_T/\rho,\ s_T = c_v/T,\ u_\rho = (p - T p_T)/\rho^2,\
              h_\rho = u_\rho + p_\rho/\rho - p/\rho^2,\ s_\rho = -p_T/\rho^2

    (Maxwell's (∂s/∂v)_T = (∂p/∂T)_v); cv is held (its derivatives are not needed: it is only a Newton slope)."""
    iP, iC, iD, iT = keys
    d = st.first_partial_deriv
    p, cv = pt[0], pt[5]
    p_T = d(iP, iT, iD)
    dT = (p_T, cv, cv + p_T / rho, cv / T, d(iC, iT, iD), 0.0)
    if not density_too:
        return pt, dT, None
    p_rho, r2 = d(iP, iD, iT), rho * rho
    u_rho = (p - T * p_T) / r2
    return pt, dT, (p_rho, u_rho, u_rho + p_rho / rho - p / r2, -p_T / r2, d(iC, iD, iT), 0.0)


def shifted(jet: tuple, d_T: float, d_rho: float = 0.0) -> FluidPoint:
    """The first-order Taylor step of a :meth:`RealFluid.jet` by d_T [K] and d_ρ [kg/m^3]: exact to
    O(d_T² + d_ρ²) (used after a Newton step too small to need another evaluation: below 1e-7 relative, the
    remainder is ~1e-14 relative), except cv, held at the evaluated point's (first order: a Newton slope only).

    Examples
    --------
    >>> g = IdealGasFluid(287.0, 1.4)
    >>> round(shifted(g.jet(1.2, 300.0), 1e-5).p / g.at(1.2, 300.0 + 1e-5).p - 1.0, 15)
    0.0
    """
    (p, u, h, s, c, cv), a, b = jet
    if b is None:
        return FluidPoint((p + d_T * a[0], u + d_T * a[1], h + d_T * a[2], s + d_T * a[3], c + d_T * a[4],
                           cv + d_T * a[5]))
    return FluidPoint((p + d_T * a[0] + d_rho * b[0], u + d_T * a[1] + d_rho * b[1], h + d_T * a[2] + d_rho * b[2],
                       s + d_T * a[3] + d_rho * b[3], c + d_T * a[4] + d_rho * b[4], cv + d_T * a[5] + d_rho * b[5]))


#: A Newton step below this fraction of T (or ρ) is taken without another evaluation: the point is the Taylor
#: step of the last one (:func:`shifted`); the quadratic remainder is ~1e-14 relative.
TAYLOR_BELOW = 1e-7


def temperature_from_energy(fluid, rho: float, u: float, T_guess: float) -> tuple:
    r"""Temperature [K] at which ``fluid`` of density ρ has specific internal energy u, by Newton's method, and
    the fluid there (a :class:`FluidPoint`).

    .. math:: T_{k+1} = T_k - \frac{u(\rho, T_k) - u}{c_v(\rho, T_k)}

    Parameters
    ----------
    fluid : RealFluid (or anything with ``jet(rho, T)``, see :meth:`RealFluid.jet`)
    rho : float
        Density [kg/m^3], > 0.
    u : float
        Specific internal energy [J/kg] (with the fluid's offset).
    T_guess : float
        Start [K] (the previous temperature).

    Notes
    -----
    u is strictly increasing in T at fixed ρ outside the two-phase dome (cv > 0), so the iteration converges
    from a nearby guess; steps are limited to halve T at most. Once a step is below :data:`TAYLOR_BELOW`·T it
    is taken and the point is the Taylor step of the last evaluation (:func:`shifted`): T and the fields are then
    exact to ~1e-14 relative (the quadratic remainder, (∂cv/∂T)/(2cv)·step²).

    Examples
    --------
    >>> f = RealFluid("Helium")
    >>> round(temperature_from_energy(f, 30.0, f.at(30.0, 80.0).u, 300.0)[0], 9)
    80.0
    """
    return _newton(fluid, rho, u, T_guess, 1)[:2]


def isentrope_temperature(fluid, rho: float, s: float, T_guess: float) -> tuple:
    r"""Temperature [K] of ``fluid`` at density ρ on the isentrope of specific entropy s [J/(kg K)], and the
    fluid there (a :class:`FluidPoint`).

    .. math:: T_{k+1} = T_k - \frac{s(\rho, T_k) - s}{c_v(\rho, T_k)/T_k}

    (∂s/∂T|ρ = cv/T). Stopping, limits and accuracy as :func:`temperature_from_energy`.

    Examples
    --------
    >>> f = RealFluid("Nitrogen")
    >>> s0 = f.at(300.0, 300.0).s
    >>> round(isentrope_temperature(f, 300.0, s0, 200.0)[0], 9)
    300.0
    """
    return _newton(fluid, rho, s, T_guess, 3)[:2]


def _newton(fluid, rho: float, target: float, T: float, field: int) -> tuple:
    """(T, FluidPoint, jet of the last evaluation) where field ``field`` of the fluid at (ρ, T) equals
    ``target`` (1: u, 3: s; both increase with T at fixed ρ)."""
    for _ in range(NEWTON_MAX):
        jet = fluid.jet(rho, T)
        step = (jet[0][field] - target) / jet[1][field]
        if abs(step) <= TAYLOR_BELOW * T:
            return T - step, shifted(jet, -step), jet
        T = T - step if step < 0.5 * T else 0.5 * T
    what = "temperature" if field == 1 else "isentrope temperature"
    raise RealGasSolveError(f"{getattr(fluid, 'name', fluid)}: no {what} for rho = {rho!r} kg/m^3, "
                            f"{'u' if field == 1 else 's'} = {target!r} (last T = {T!r} K)")


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

    def jet(self, rho: float, T: float, density_too: bool = False) -> tuple:
        """:meth:`RealFluid.jet` in closed form."""
        pt, R, cv = self.at(rho, T), self.R, self.cv
        dT = (rho * R, cv, cv + R, cv / T, 0.5 * pt[4] / T, 0.0)
        return pt, dT, (R * T, 0.0, 0.0, -R / rho, 0.0, 0.0) if density_too else None
