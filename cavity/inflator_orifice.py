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

import numpy as np
from numba import njit

from .caution import caution
from .gas import Mixture
from .gas_rows import rows_gamma
from .tolerances import R_UNIVERSAL
from .inflator import quadrature_mass, scheduled_breakpoints, table_mass
from .isentropic import choked_flow_factor

__all__ = ["PressureMassInflator", "DualPressureInflator", "choked_inflator_temperature",
           "dual_pressure_mass_flow", "pressure_mass_state", "dual_pressure_state", "clamped_message"]

#: Fixed-point iterations for γ(T_i) and the bounds kept on T_i [K].
GAMMA_ITERATIONS = 8
T_LOW, T_HIGH = 50.0, 1.0e4
T_BOUNDS = (T_LOW, T_HIGH)
T_START = 1000.0  # first guess of the fixed point [K]


@njit(cache=True, inline="always")
def choked_inflator_temperature(mdot: float, p_inflator: float, area: float, Cd: float, R: float,
                                gamma: float) -> float:
    r"""Inflator gas temperature from a choked orifice's mass flow and upstream pressure [K].

    .. math:: T_i = \frac{1}{R}\left(\frac{C_d A\, p_i\, C^*(\gamma)}{\dot m}\right)^2

    ``mdot`` [kg/s], ``p_inflator`` [Pa], ``area`` [m^2], ``Cd`` [-], ``R`` [J/(kg K)], ``gamma`` [-]: the choked
    orifice law ṁ = Cd·A·p_i·C*/√(R·T_i) solved for T_i (Abaqus Analysis User's Guide, "Fluid inflator
    definition", PRESSURE AND MASS).

    Examples
    --------
    The inverse of the choked orifice law: 0.0467 kg/s of air (R = 287, γ = 1.4) through 1 cm² at 2 bar is 300 K.

    >>> round(choked_inflator_temperature(0.046671171212124, 2.0e5, 1.0e-4, 1.0, 287.0, 1.4), 6)
    300.0
    """
    return (Cd * area * p_inflator * choked_flow_factor(gamma) / mdot) ** 2 / R


@njit(cache=True, inline="always")
def dual_pressure_mass_flow(p_inflator: float, tank_pressure_rate: float, tank_volume: float, area: float,
                            Cd: float, gamma: float) -> float:
    r"""Inflator mass flow from its pressure and a tank-test pressure rate [kg/s].

    .. math:: \dot m = \frac{\gamma\,(C_d A\, p_i\, C^*(\gamma))^2}{V\,\dot p_t}

    ``p_inflator`` [Pa], ``tank_pressure_rate`` [Pa/s], ``tank_volume`` [m^3], ``area`` [m^2], ``Cd`` [-]: the
    choked orifice law and the rigid adiabatic tank ṁ = V·ṗ_t/(γ·R·T_i) with T_i eliminated (Abaqus Analysis
    User's Guide, "Fluid inflator definition", DUAL PRESSURE; ../shared/PHYSICS.md).

    Examples
    --------
    >>> round(dual_pressure_mass_flow(2.0e5, 1.0e6, 0.06, 1.0e-4, 1.0, 1.4), 8)
    0.004376
    """
    return gamma * (Cd * area * p_inflator * choked_flow_factor(gamma)) ** 2 / (tank_volume * tank_pressure_rate)


@njit(cache=True, inline="always")
def _bounded(T: float) -> float:
    return min(max(T, T_LOW), T_HIGH)


@njit(cache=True)
def pressure_mass_state(mdot, p_inflator, area, Cd, rows, breaks, moles, mass):
    r"""(T_i [K], clamped) of a PRESSURE AND MASS inflator from its table values ṁ [kg/s] and p_i [Pa].

    .. math:: T_{k+1} = \mathrm{clip}\left(\frac{1}{R}\left(\frac{C_d A\,p_i\,C^*(\gamma(T_k))}{\dot m}
              \right)^2,\ 50,\ 10^4\right),\quad T_0 = 1000\ \mathrm{K}

    :data:`GAMMA_ITERATIONS` steps of the fixed point of :func:`choked_inflator_temperature` with γ(T) of the
    inflator gas (``moles`` [mol] and ``mass`` [kg] of it, coefficient rows ``rows`` (nr, 7) split at ``breaks``
    [K], as :class:`cavity.gas.Mixture`); ``clamped`` is True when the last iterate was held at a bound of
    :data:`T_BOUNDS`. No flow or no pressure gives (50 K, False). Source: Abaqus Analysis User's Guide, "Fluid
    inflator definition", PRESSURE AND MASS.

    Examples
    --------
    Nitrogen at constant cp (γ = 1.4, R = 296.9): the temperature at which a choked orifice of 1 cm² passes
    0.0467 kg/s at 2 bar.

    >>> import numpy as np
    >>> n2 = np.array([[3.5 * 8.314462618 / 0.028, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])  # rows of 1 kg
    >>> T, clamped = pressure_mass_state(0.0467, 2.0e5, 1.0e-4, 1.0, n2, np.zeros(0), 1.0 / 0.028, 1.0)
    >>> round(T, 3), clamped
    (289.595, False)
    """
    if mdot <= 0.0 or p_inflator <= 0.0:
        return T_LOW, False
    R = moles * R_UNIVERSAL / mass
    T, raw = T_START, T_START
    for _ in range(GAMMA_ITERATIONS):
        raw = choked_inflator_temperature(mdot, p_inflator, area, Cd, R, rows_gamma(rows, breaks, moles, T))
        T = _bounded(raw)
    return T, raw != T


@njit(cache=True)
def dual_pressure_state(p_inflator, tank_pressure_rate, tank_volume, area, Cd, rows, breaks, moles, mass):
    r"""(ṁ [kg/s], T_i [K], clamped) of a DUAL PRESSURE inflator from p_i [Pa] and the tank pressure's rate ṗ_t
    [Pa/s].

    .. math:: \dot m_k = \frac{\gamma_k (C_d A\,p_i\,C^*(\gamma_k))^2}{V\dot p_t},\quad
              T_{k+1} = \mathrm{clip}\left(\frac{V\dot p_t}{\gamma_k R\,\dot m_k},\ 50,\ 10^4\right),\quad
              \gamma_k = \gamma(T_k),\ T_0 = 1000\ \mathrm{K}

    :data:`GAMMA_ITERATIONS` steps (:func:`dual_pressure_mass_flow` and the tank relation of
    :func:`cavity.inflator.tank_test_mass_flow`), the gas as in :func:`pressure_mass_state`; ``clamped`` when the
    last T was held at a bound. A falling tank pressure or no inflator pressure gives (0, 50 K, False). Source:
    Abaqus Analysis User's Guide, "Fluid inflator definition", DUAL PRESSURE.

    Examples
    --------
    Nitrogen at constant cp (γ = 1.4) made to give 0.5 kg/s at 600 K through 0.2 cm² (Cd 0.9) into a 60 L tank:
    p_i = ṁ·√(R·T)/(Cd·A·C*), ṗ_t = γ·R·T·ṁ/V; the law recovers both.

    >>> import numpy as np
    >>> n2 = np.array([[3.5 * 8.314462618 / 0.028, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])  # rows of 1 kg
    >>> mdot, T, clamped = dual_pressure_state(17123436.2634, 2078615.6545, 0.06, 2e-5, 0.9, n2, np.zeros(0),
    ...                                        1 / 0.028, 1.0)
    >>> round(mdot, 9), round(T, 6), clamped
    (0.5, 600.0, False)
    """
    if tank_pressure_rate <= 0.0 or p_inflator <= 0.0:
        return 0.0, T_LOW, False
    R = moles * R_UNIVERSAL / mass
    T, raw, mdot = T_START, T_START, 0.0
    for _ in range(GAMMA_ITERATIONS):
        g = rows_gamma(rows, breaks, moles, T)
        mdot = dual_pressure_mass_flow(p_inflator, tank_pressure_rate, tank_volume, area, Cd, g)
        raw = tank_volume * tank_pressure_rate / (g * R * mdot)
        T = _bounded(raw)
    return mdot, T, raw != T


def clamped_message(name: str) -> str:
    """The warning given when an orifice inflator's temperature was held at a bound of :data:`T_BOUNDS`."""
    return (f"inflator {name!r}: the gas temperature from the orifice relation left [{T_BOUNDS[0]:g}, "
            f"{T_BOUNDS[1]:g}] K and was held at the bound: check its pressure and mass flow tables")


class _GasArrays:
    """The inflator gas as the arrays of its laws (``rows`` (nr, 7), ``breaks``), made once at construction."""

    def __post_init__(self):
        object.__setattr__(self, "_rows", np.array(self.gas.rows, dtype=float).reshape(-1, 7))
        object.__setattr__(self, "_breaks", np.array(self.gas.breaks, dtype=float))

    def _gas(self) -> tuple:
        return self._rows, self._breaks, float(self.gas.moles), float(self.gas.mass)


@dataclass(frozen=True)
class PressureMassInflator(_GasArrays):
    """PRESSURE AND MASS: tables p_i(t) [Pa] and ṁ(t) [kg/s], orifice area [m^2] and Cd [-]; T_i(t) from
    :func:`pressure_mass_state` (the law the compiled path calls too)."""

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
        T, clamped = pressure_mass_state(self.mass_flow_table(t - self.start), self.pressure_table(t - self.start),
                                         self.area, self.discharge_coefficient, *self._gas())
        if clamped:
            caution(clamped_message(self.name))
        return T

    @property
    def breakpoints(self) -> tuple:
        return scheduled_breakpoints(self.start, self.pressure_table, self.mass_flow_table)

    def mass_between(self, t0: float, t1: float) -> float:
        return table_mass(self.mass_flow_table, self.start, self.scale, t0, t1)


@dataclass(frozen=True)
class DualPressureInflator(_GasArrays):
    """DUAL PRESSURE: tables p_i(t) and tank pressure p_t(t) [Pa], tank volume [m^3], orifice area, Cd; ṁ and T_i
    from :func:`dual_pressure_state` (the law the compiled path calls too)."""

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
        mdot, T, clamped = dual_pressure_state(self.pressure_table(t - self.start),
                                               self.tank_pressure_table.slope(t - self.start), self.tank_volume,
                                               self.area, self.discharge_coefficient, *self._gas())
        if clamped:
            caution(clamped_message(self.name))
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
