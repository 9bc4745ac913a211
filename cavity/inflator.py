"""Inflators: mass flow rate and gas temperature versus time (Abaqus *FLUID INFLATOR PROPERTY).

Each inflator answers ``mass_flow(t)`` [kg/s], ``temperature(t)`` [K] and ``breakpoints`` (absolute times where
its curves have kinks, which the integrator stops at). Time tables are relative to the inflator's start time.
"""
from __future__ import annotations

from dataclasses import dataclass

from numba import njit

from .gas import Mixture
from .tables import Table

__all__ = ["MassTemperatureInflator", "TankTestInflator", "tank_test_mass_flow"]


@njit(cache=True, inline="always")
def tank_test_mass_flow(tank_volume: float, tank_pressure_rate: float, gamma: float, R: float,
                        T_inflator: float) -> float:
    r"""Inflator mass flow inferred from a rigid adiabatic tank test [kg/s].

    .. math:: \dot m = \frac{V_{tank}\,\dot p_{tank}}{\gamma R T_{in}}

    from m·T = m0·T0 + γ·T_in·∫ṁ dt for a rigid adiabatic tank filled with one constant-cp gas.

    Parameters
    ----------
    tank_volume : float
        Tank volume [m^3].
    tank_pressure_rate : float
        Rate of rise of the tank pressure [Pa/s].
    gamma : float
        Ratio of specific heats of the inflator gas at T_in [-].
    R : float
        Specific gas constant of the inflator gas [J/(kg K)].
    T_inflator : float
        Inflator gas temperature [K].

    References
    ----------
    Abaqus Analysis User's Guide, "Fluid inflator definition", TANK TEST; ../shared/PHYSICS.md.

    Examples
    --------
    A 60 L tank whose pressure rises by 1 MPa/s, N2 (γ = 1.4, R = 296.8) at 800 K:

    >>> round(tank_test_mass_flow(0.06, 1.0e6, 1.4, 296.8, 800.0), 6)
    0.180497
    """
    return tank_volume * tank_pressure_rate / (gamma * R * T_inflator)


def scheduled_breakpoints(start: float, *tables) -> tuple:
    """Absolute times where an inflator's inputs may kink: its start and every row of its tables [s]."""
    return (start,) + tuple(start + x for table in tables for x in table.breakpoints)


def table_mass(table: Table, start: float, scale: float, t0: float, t1: float) -> float:
    """Exact mass [kg] a mass-flow table (relative to ``start``, times ``scale``) delivers over [t0, t1]."""
    a, b = max(t0, start) - start, t1 - start
    return scale * table.integral(a, b) if b > a else 0.0


def quadrature_mass(inflator, t0: float, t1: float) -> float:
    """Mass [kg] an inflator delivers over [t0, t1], by quadrature between its breakpoints."""
    from scipy.integrate import quad

    pts = sorted({t0, t1, *[b for b in inflator.breakpoints if t0 < b < t1]})
    return sum(quad(inflator.mass_flow, a, b)[0] for a, b in zip(pts[:-1], pts[1:]))


@dataclass(frozen=True)
class MassTemperatureInflator:
    """Inflator given by tables of mass flow rate ṁ(t) [kg/s] and gas temperature T(t) [K].

    Attributes
    ----------
    name : str
    mass_flow_table, temperature_table : Table
        Functions of the time since ``start`` [s]; zero flow before ``start``.
    mass_fractions : tuple of float
        Inflator gas composition by mass, in the scene's species order.
    gas : Mixture
        The mixture polynomial of 1 kg of inflator gas (enthalpy per kg, γ, R).
    start : float
        Activation time [s].
    scale : float
        Multiplier on the mass flow [-] (an activation amplitude).
    """

    name: str
    mass_flow_table: Table
    temperature_table: Table
    mass_fractions: tuple
    gas: Mixture
    start: float = 0.0
    scale: float = 1.0

    def mass_flow(self, t: float) -> float:
        return self.scale * self.mass_flow_table(t - self.start) if t >= self.start else 0.0

    def temperature(self, t: float) -> float:
        return self.temperature_table(t - self.start)

    @property
    def breakpoints(self) -> tuple:
        return scheduled_breakpoints(self.start, self.mass_flow_table, self.temperature_table)

    def mass_between(self, t0: float, t1: float) -> float:
        """Exact mass delivered over [t0, t1] [kg] (for scales and checks)."""
        return table_mass(self.mass_flow_table, self.start, self.scale, t0, t1)


@dataclass(frozen=True)
class TankTestInflator:
    """Inflator characterised by a tank test: tank pressure p(t) [Pa], tank volume [m^3], gas temperature T(t).

    The mass flow is :func:`tank_test_mass_flow` with ṗ the slope of the piecewise-linear pressure table
    (so ṁ is piecewise constant between table rows); a falling tank pressure gives no flow (ṁ is clipped at 0).
    """

    name: str
    tank_pressure_table: Table
    tank_volume: float
    temperature_table: Table
    mass_fractions: tuple
    gas: Mixture
    start: float = 0.0
    scale: float = 1.0

    def mass_flow(self, t: float) -> float:
        if t < self.start:
            return 0.0
        rate = self.tank_pressure_table.slope(t - self.start)
        if rate <= 0.0:
            return 0.0
        T = self.temperature(t)
        return self.scale * tank_test_mass_flow(self.tank_volume, rate, self.gas.gamma(T), self.gas.gas_constant, T)

    def temperature(self, t: float) -> float:
        return self.temperature_table(t - self.start)

    @property
    def breakpoints(self) -> tuple:
        return scheduled_breakpoints(self.start, self.tank_pressure_table, self.temperature_table)

    def mass_between(self, t0: float, t1: float) -> float:
        """Mass delivered over [t0, t1] [kg], by quadrature between breakpoints."""
        return quadrature_mass(self, t0, t1)
