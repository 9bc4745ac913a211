"""A linear resistance: a mass flow proportional to the pressure difference (a linear valve, Cantera's ``Valve``
with a constant coefficient): the pure law, its object and its kernel."""
from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

from numba import njit

from exchange.engine.layout import LAW_SIGNATURE, StateColumn, side

from .spec import LawKey, LawSpec

__all__ = ["linear_resistance_mass_flow", "LinearResistanceLaw", "linear_resistance_kernel", "LAW"]


@njit(cache=True)
def linear_resistance_mass_flow(dp, conductance):
    r"""Mass flow through a linear resistance [kg/s].

    .. math:: \dot m = G\, \Delta p

    Parameters
    ----------
    dp : float or ndarray
        p_1 − p_2 [Pa] (signed).
    conductance : float or ndarray
        G [kg/(s Pa)], >= 0.

    Notes
    -----
    Between two rigid isothermal ideal-gas tanks (p_i = m_i R T / V_i) this gives
    :math:`\Delta p(t) = \Delta p_0\, e^{-t/\tau}` with :math:`1/\tau = G R T (1/V_1 + 1/V_2)`
    (Cantera's ``test_valve2`` oracle for a linear valve).

    Examples
    --------
    >>> linear_resistance_mass_flow(-2000.0, 1.0e-6)
    -0.002
    """
    return conductance * dp


@dataclass(frozen=True)
class LinearResistanceLaw:
    """ṁ = G·A·Δp with a conductance per unit area G [kg/(s Pa m^2)], outflow only."""

    conductance: float
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        dp = up.p - p_down
        return linear_resistance_mass_flow(dp, self.conductance * area) if dp > 0 else 0.0


class LinearFloat(IntEnum):
    CONDUCTANCE = 0  # per unit area [kg/(s Pa m^2)]


@njit(LAW_SIGNATURE, cache=True)
def linear_resistance_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The engine's linear-resistance flow from side u [kg/s], >= 0."""
    dp = side(st, amb, u, StateColumn.P) - p_down
    return linear_resistance_mass_flow(dp, lf[LinearFloat.CONDUCTANCE] * area) if dp > 0 else 0.0


LAW = LawSpec(names=("linear_resistance",), law=LinearResistanceLaw, kernel=linear_resistance_kernel,
              keys=(LawKey("conductance", "linear_resistance: ṁ = G·A·Δp", "kg/(s Pa m^2)", default=0.0,
                           check="nonnegative"),),
              required={"linear_resistance": ("conductance",)},
              build=lambda name, values, read_table: LinearResistanceLaw(values["conductance"]),
              lower=lambda law, tables: ((float(law.conductance),), ()))
