"""Inflators characterised through their orifice (Abaqus *FLUID INFLATOR PROPERTY, PRESSURE AND MASS, DUAL PRESSURE).

Both assume the inflator's exit orifice (area A, discharge coefficient Cd) is choked, which holds while the
inflator pressure exceeds the cavity pressure by the critical ratio (≈ 1.9 for γ = 1.4), as it does for the
pressures of pyrotechnic and hybrid inflators (tens of MPa):

    ṁ = Cd·A·p_i·C*(γ)/√(R·T_i)    (choked orifice, C* = √γ·(2/(γ+1))^((γ+1)/(2(γ−1))))

PRESSURE AND MASS gives p_i(t) and ṁ(t), so T_i = (Cd·A·p_i·C*/ṁ)²/R. DUAL PRESSURE gives p_i(t) and a tank-test
pressure p_t(t) with the tank volume V, whose rigid adiabatic tank relation ṁ = V·ṗ_t/(γ·R·T_i) closes the pair:
ṁ = γ·(Cd·A·p_i·C*)²/(V·ṗ_t), T_i = V·ṗ_t/(γ·R·ṁ). γ depends on T_i and is found by fixed-point iteration.
"""
from __future__ import annotations

from dataclasses import dataclass

from .caution import caution
from .gas import Mixture
from .inflator import quadrature_mass, scheduled_breakpoints, table_mass

__all__ = ["PressureMassInflator", "DualPressureInflator", "choked_inflator_temperature",
           "dual_pressure_mass_flow"]

#: Fixed-point iterations for γ(T_i) and the bounds kept on T_i [K].
GAMMA_ITERATIONS = 8
T_BOUNDS = (50.0, 1.0e4)


def _choked_factor(gamma: float) -> float:
    return gamma ** 0.5 * (2.0 / (gamma + 1.0)) ** ((gamma + 1.0) / (2.0 * (gamma - 1.0)))


def choked_inflator_temperature(mdot: float, p_inflator: float, area: float, Cd: float, R: float,
                                gamma: float) -> float:
    r"""Inflator gas temperature from a choked orifice's mass flow and upstream pressure [K].

    .. math:: T_i = \frac{1}{R}\left(\frac{C_d A\, p_i\, C^*(\gamma)}{\dot m}\right)^2

    Examples
    --------
    The inverse of the choked orifice law: 0.0467 kg/s of air (R = 287, γ = 1.4) through 1 cm² at 2 bar is 300 K.

    >>> round(choked_inflator_temperature(0.046671171212124, 2.0e5, 1.0e-4, 1.0, 287.0, 1.4), 6)
    300.0
    """
    return (Cd * area * p_inflator * _choked_factor(gamma) / mdot) ** 2 / R


def dual_pressure_mass_flow(p_inflator: float, tank_pressure_rate: float, tank_volume: float, area: float,
                            Cd: float, gamma: float) -> float:
    r"""Inflator mass flow from its pressure and a tank-test pressure rate [kg/s].

    .. math:: \dot m = \frac{\gamma\,(C_d A\, p_i\, C^*(\gamma))^2}{V\,\dot p_t}

    Examples
    --------
    >>> round(dual_pressure_mass_flow(2.0e5, 1.0e6, 0.06, 1.0e-4, 1.0, 1.4), 8)
    0.004376
    """
    return gamma * (Cd * area * p_inflator * _choked_factor(gamma)) ** 2 / (tank_volume * tank_pressure_rate)


def _clamped(T: float, name: str = "", last: bool = False) -> float:
    """T held in :data:`T_BOUNDS` [K]; with ``last`` (the final iterate) a :class:`~cavity.caution.VentsimWarning`
    when it had to be."""
    if T_BOUNDS[0] <= T <= T_BOUNDS[1]:
        return T
    if last:
        caution(f"inflator {name!r}: the gas temperature from the orifice relation left [{T_BOUNDS[0]:g}, "
                f"{T_BOUNDS[1]:g}] K and was held at the bound: check its pressure and mass flow tables")
    return min(max(T, T_BOUNDS[0]), T_BOUNDS[1])


@dataclass(frozen=True)
class PressureMassInflator:
    """PRESSURE AND MASS: tables p_i(t) [Pa] and ṁ(t) [kg/s], orifice area [m^2] and Cd [-]."""

    name: str
    pressure_table: object
    mass_flow_table: object
    area: float
    discharge_coefficient: float
    mass_fractions: tuple
    gas: Mixture
    start: float = 0.0
    scale: float = 1.0

    def mass_flow(self, t: float) -> float:
        return self.scale * self.mass_flow_table(t - self.start) if t >= self.start else 0.0

    def temperature(self, t: float) -> float:
        mdot, p = self.mass_flow_table(t - self.start), self.pressure_table(t - self.start)
        if mdot <= 0.0 or p <= 0.0:
            return T_BOUNDS[0]
        T = 1000.0
        for k in range(GAMMA_ITERATIONS):
            T = _clamped(choked_inflator_temperature(mdot, p, self.area, self.discharge_coefficient,
                                                     self.gas.gas_constant, self.gas.gamma(T)),
                         self.name, k == GAMMA_ITERATIONS - 1)
        return T

    @property
    def breakpoints(self) -> tuple:
        return scheduled_breakpoints(self.start, self.pressure_table, self.mass_flow_table)

    def mass_between(self, t0: float, t1: float) -> float:
        return table_mass(self.mass_flow_table, self.start, self.scale, t0, t1)


@dataclass(frozen=True)
class DualPressureInflator:
    """DUAL PRESSURE: tables p_i(t) and tank pressure p_t(t) [Pa], tank volume [m^3], orifice area, Cd."""

    name: str
    pressure_table: object
    tank_pressure_table: object
    tank_volume: float
    area: float
    discharge_coefficient: float
    mass_fractions: tuple
    gas: Mixture
    start: float = 0.0
    scale: float = 1.0

    def _solve(self, t: float) -> tuple:
        """(ṁ, T_i) at t, unscaled."""
        rate, p = self.tank_pressure_table.slope(t - self.start), self.pressure_table(t - self.start)
        if rate <= 0.0 or p <= 0.0:
            return 0.0, T_BOUNDS[0]
        T, mdot = 1000.0, 0.0
        for k in range(GAMMA_ITERATIONS):
            g = self.gas.gamma(T)
            mdot = dual_pressure_mass_flow(p, rate, self.tank_volume, self.area, self.discharge_coefficient, g)
            T = _clamped(self.tank_volume * rate / (g * self.gas.gas_constant * mdot), self.name,
                         k == GAMMA_ITERATIONS - 1)
        return mdot, T

    def mass_flow(self, t: float) -> float:
        return self.scale * self._solve(t)[0] if t >= self.start else 0.0

    def temperature(self, t: float) -> float:
        return self._solve(t)[1]

    @property
    def breakpoints(self) -> tuple:
        return scheduled_breakpoints(self.start, self.pressure_table, self.tank_pressure_table)

    def mass_between(self, t0: float, t1: float) -> float:
        return quadrature_mass(self, t0, t1)
