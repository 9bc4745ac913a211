"""Tank-test inflators read through a real-gas tank: the mass delivered from the tank pressure with HEOS.

The Abaqus TANK TEST formula ṁ = V·ṗ/(γ·R·T_in) (:func:`cavity.inflator.tank_test_mass_flow`) assumes one
constant-cp ideal gas in the tank. With a real-gas tank the same two balances of a rigid adiabatic tank are
solved with the equation of state instead: between two rows of the pressure table (t_{i−1}, t_i) the tank's mass
and energy change by Δm and Δm·h_in, and

    p_EOS(ρ = m_i/V, u = (U_{i−1} + (m_i − m_{i−1})·h_in)/m_i) = p_i,

solved for m_i by the secant method (h_in: the inflator gas's enthalpy at the interval's mid-time temperature, in
its ideal-gas limit: the gas leaves the inflator at a pressure the test does not record). The delivered mass
m_i − m_0 is then a piecewise-linear table of time, and ṁ its slope, constant between rows as in the ideal
formula. For an ideal gas of constant cp this is the ideal formula exactly (U = cv·p·V/R, so
cv·V·Δp/R = Δm·cp·T_in). A falling tank pressure delivers nothing: the tank is taken to lose heat at constant
mass down to the table's pressure (the ideal formula counts every rise from the row before it, likewise).
"""
from __future__ import annotations

from dataclasses import dataclass

from .inflator import TankTestInflator
from .realgas import IDEAL_LIMIT_DENSITY, temperature_from_energy
from .tables import Table

__all__ = ["real_gas_tank_masses", "RealGasTankTestInflator"]

SECANT_RTOL = 1e-14


def _pressure(fluid, V, m, U, T_guess):
    T, pt = temperature_from_energy(fluid, m / V, U / m, T_guess)
    return pt[0], T


def _temperature_at_pressure(fluid, rho, p_target, T):
    """T [K] at which ``fluid`` at density rho has pressure p_target (secant from T)."""
    T_a, f_a = T, fluid.at(rho, T)[0] - p_target
    T_b = T * (1.0 + 1e-3)
    f_b = fluid.at(rho, T_b)[0] - p_target
    for _ in range(60):
        if f_b == f_a or abs(T_b - T_a) <= SECANT_RTOL * T_b:
            break
        T_a, f_a, T_b = T_b, f_b, T_b - f_b * (T_b - T_a) / (f_b - f_a)
        f_b = fluid.at(rho, T_b)[0] - p_target
    return T_b


def real_gas_tank_masses(fluid, tank_volume: float, times, pressures, tank_temperature: float,
                         inflator_temperature) -> tuple:
    r"""Mass in a rigid adiabatic real-gas tank [kg] at each row of a tank-test pressure table.

    Parameters
    ----------
    fluid : cavity.realgas.RealFluid (or IdealGasFluid)
        The gas in the tank and from the inflator.
    tank_volume : float
        V [m^3].
    times, pressures : sequence of float
        The tank pressure table: t [s], p [Pa].
    tank_temperature : float
        Initial tank temperature [K] (at pressures[0]).
    inflator_temperature : callable
        T_in(t) [K] of the inflator gas.

    Returns
    -------
    tuple of float
        m_i [kg], non-decreasing.

    Examples
    --------
    The ideal formula for an ideal gas (N2, γ = 1.4, T_in = 800 K), 60 L tank from 1 to 2 bar:

    >>> from cavity.realgas import IdealGasFluid
    >>> m = real_gas_tank_masses(IdealGasFluid(296.8, 1.4), 0.06, (0.0, 0.01), (1e5, 2e5), 300.0, lambda t: 800.0)
    >>> round((m[1] - m[0]) / (0.06 * 1e5 / (1.4 * 296.8 * 800.0)), 12)
    1.0
    """
    p0 = pressures[0]
    rho = fluid.density(p0, tank_temperature) if hasattr(fluid, "density") else p0 / (fluid.R * tank_temperature)
    m = rho * tank_volume
    U = m * fluid.at(rho, tank_temperature)[1]
    T, p, out = tank_temperature, p0, [m]
    for (t0, t1), p_i in zip(zip(times[:-1], times[1:]), pressures[1:]):
        if p_i <= p:  # no flow; the tank lost heat at constant mass, down to p_i (what the ideal formula assumes)
            T = _temperature_at_pressure(fluid, m / tank_volume, p_i, T)
            U, p = m * fluid.at(m / tank_volume, T)[1], p_i
            out.append(m)
            continue
        T_in = inflator_temperature(0.5 * (t0 + t1))
        h = fluid.at(IDEAL_LIMIT_DENSITY, T_in)[2]
        m_a, f_a = m, p - p_i
        m_b = m * (1.0 + (p_i - p) / p)
        f_b, T_b = _pressure(fluid, tank_volume, m_b, U + (m_b - m) * h, T)
        f_b -= p_i
        for _ in range(60):
            if f_b == f_a or abs(m_b - m_a) <= SECANT_RTOL * m_b:
                break
            m_a, f_a, m_b = m_b, f_b, m_b - f_b * (m_b - m_a) / (f_b - f_a)
            f_b, T_b = _pressure(fluid, tank_volume, m_b, U + (m_b - m) * h, T_b)
            f_b -= p_i
        U, m, p, T = U + (m_b - m) * h, m_b, p_i, T_b
        out.append(m)
    return tuple(out)


@dataclass(frozen=True)
class RealGasTankTestInflator(TankTestInflator):
    """A :class:`cavity.inflator.TankTestInflator` whose tank holds a real gas: ṁ is the slope of ``delivered``
    (m_i − m_0 of :func:`real_gas_tank_masses` against the pressure table's times [kg]), times ``scale``."""

    delivered: Table = None

    def mass_flow(self, t: float) -> float:
        if t < self.start:
            return 0.0
        return self.scale * self.delivered.slope(t - self.start)

    def mass_between(self, t0: float, t1: float) -> float:
        """Exact mass delivered over [t0, t1] [kg]."""
        a, b = max(t0, self.start) - self.start, t1 - self.start
        return self.scale * (self.delivered(b) - self.delivered(a)) if b > a else 0.0
