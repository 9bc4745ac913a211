"""Isentropic orifice flow with choking (Abaqus *FLUID EXCHANGE PROPERTY, TYPE=ORIFICE).

Scalar pure functions compiled by numba (``@njit``), which the engine's kernel and Python call alike; the law object
:class:`OrificeLaw` and the registry's :data:`LAW` (scene keys, lowering, the engine kernel :func:`orifice_kernel`).
Called from Python the functions take floats (ints are cast) and return a float.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from cavity.isentropic import choked_flow_factor, critical_pressure_ratio
from exchange.engine.layout import LAW_SIGNATURE, StateColumn, side

from .discharge import CD_KEYS, cd_breakpoints, cd_of_values, cd_value, discharge_coefficient, lowered_cd, lowers_cd, pressure_kinks
from .spec import LawSpec

__all__ = ["critical_pressure_ratio", "orifice_mass_flow", "choked_flow_factor", "is_choked", "LINEAR_BELOW",
           "OrificeLaw", "orifice_kernel", "LAW"]

#: Relative pressure difference (p_up − p_down)/p_up below which the orifice law's square root is replaced by a
#: C¹ quadratic through the origin. At 1 bar this is 10 Pa, a jet velocity of about 4 m/s, where a vent of a few
#: centimetres is near laminar flow anyway. It keeps the law Lipschitz at Δp = 0, so two cavities equalise
#: exponentially instead of landing on Δp = 0 in finite time and chattering across it.
LINEAR_BELOW = 1e-4


def is_choked(p_up: float, p_down: float, gamma: float) -> bool:
    """True when the downstream pressure is at or below the critical pressure [-].

    Parameters
    ----------
    p_up, p_down : float
        Upstream and downstream absolute pressures [Pa].
    gamma : float
        Ratio of specific heats of the upstream gas [-].

    Examples
    --------
    >>> is_choked(2.0e5, 1.0e5, 1.4), is_choked(1.5e5, 1.0e5, 1.4)
    (True, False)
    """
    return p_down <= p_up * critical_pressure_ratio(gamma)


@njit(cache=True)
def orifice_mass_flow(p_up: float, T_up: float, p_down: float, R: float, gamma: float,
                      area: float, Cd: float = 1.0) -> float:
    r"""Mass flow rate through an isentropic orifice, choked below the critical pressure [kg/s].

    .. math::

        \dot m = C_d A \frac{p_e}{\sqrt{R T_e}}
                 \sqrt{\frac{2\gamma}{\gamma-1}\left(q^{2/\gamma} - q^{(\gamma+1)/\gamma}\right)},
        \quad q = \frac{\max(p_{down},\, p_c)}{p_e},
        \quad p_c = p_e \left(\frac{2}{\gamma+1}\right)^{\gamma/(\gamma-1)}

    Parameters
    ----------
    p_up, T_up : float
        Upstream (cavity) absolute pressure p_e [Pa] and temperature T_e [K].
    p_down : float
        Downstream absolute pressure [Pa].
    R, gamma : float
        Specific gas constant [J/(kg K)] and ratio of specific heats at T_up [-] of the upstream gas.
    area, Cd : float
        Orifice area A [m^2] (>= 0) and discharge coefficient [-].

    Returns
    -------
    float
        Mass flow from upstream to downstream [kg/s]; 0 when p_down >= p_up (the law never reverses: callers
        that allow two-way flow swap the arguments).

    Notes
    -----
    The bracket is evaluated as q^(2/γ)·(1 − q^((γ−1)/γ)) (full precision as q → 1). Below Δp/p_e =
    :data:`LINEAR_BELOW` its square root is the quadratic a·s + b·s² (s = Δp/p_e) matching its value and slope
    there, so the law is C¹ and linear in Δp at Δp → 0; above, the law is exact.

    References
    ----------
    Abaqus Analysis User's Guide 11.5.3 "Fluid exchange definition" (ORIFICE).

    Examples
    --------
    Air at 2 bar, 300 K, into 1 bar (choked), 1 cm^2, Cd = 1:

    >>> f = lambda p_up, p_down: orifice_mass_flow(p_up, 300.0, p_down, 287.0, 1.4, 1.0e-4)
    >>> round(f(2.0e5, 1.0e5), 6), f(1.0e5, 1.0e5)
    (0.046671, 0.0)

    Near Δp = 0 the flow is linear in Δp (C¹ join at Δp/p = 1e-4):

    >>> round(f(1.0e5 + 0.02, 1.0e5) / f(1.0e5 + 0.01, 1.0e5), 3)
    1.999
    """
    if p_down >= p_up or area <= 0.0:
        return 0.0
    s = (p_up - p_down) / p_up
    if s >= LINEAR_BELOW:
        root = _root_bracket(max(p_down / p_up, critical_pressure_ratio(gamma)), gamma)
    else:  # a s + b s^2 matching value and slope of the exact root at s = d = LINEAR_BELOW
        d, f, fp = LINEAR_BELOW, _root_bracket(1.0 - LINEAR_BELOW, gamma), _root_bracket_slope(LINEAR_BELOW, gamma)
        root = s * ((2.0 * f - fp * d) / d + s * (fp * d - f) / (d * d))
    return Cd * area * p_up / math.sqrt(R * T_up) * math.sqrt(2.0 * gamma / (gamma - 1.0)) * root


@njit(cache=True)
def _root_bracket(q: float, gamma: float) -> float:
    """sqrt(q^(2/γ) − q^((γ+1)/γ)) = sqrt(q^(2/γ)·(1 − q^((γ−1)/γ))); expm1 keeps precision near q = 1."""
    return math.sqrt(q ** (2.0 / gamma) * -math.expm1(math.log(q) * (gamma - 1.0) / gamma))


@njit(cache=True)
def _root_bracket_slope(s: float, gamma: float) -> float:
    """d/ds of :func:`_root_bracket` at q = 1 − s (analytic)."""
    q = 1.0 - s
    g = q ** (2.0 / gamma) - q ** ((gamma + 1.0) / gamma)
    dg_dq = (2.0 / gamma) * q ** (2.0 / gamma - 1.0) - ((gamma + 1.0) / gamma) * q ** (1.0 / gamma)
    return -dg_dq / (2.0 * math.sqrt(g))


@dataclass(frozen=True)
class OrificeLaw:
    """Abaqus ORIFICE (pneumatic only): :func:`orifice_mass_flow`.

    ``discharge_coefficient``: Cd [-], a constant or a :class:`~exchange.laws.discharge.DischargeTable` of upstream
    pressure or time.
    """

    discharge_coefficient: object = 1.0
    pneumatic = True
    prescribed = False
    join_below = LINEAR_BELOW  # the law changes form at |Δp|/p = LINEAR_BELOW: a switch there

    def mass_flow(self, up, p_down, area, t):
        cd = discharge_coefficient(self.discharge_coefficient, up.p, t)
        return orifice_mass_flow(up.p, up.T, p_down, up.R, up.gamma, area, cd)

    @property
    def breakpoints(self) -> tuple:
        return cd_breakpoints(self.discharge_coefficient)


@njit(LAW_SIGNATURE, cache=True)
def orifice_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The engine's orifice flow from side u [kg/s]: :func:`orifice_mass_flow` with the upstream gas and
    :func:`~exchange.laws.discharge.cd_value`."""
    P, T, R, G = StateColumn.P, StateColumn.T, StateColumn.R, StateColumn.GAMMA
    return orifice_mass_flow(side(st, amb, u, P), side(st, amb, u, T), p_down, side(st, amb, u, R),
                             side(st, amb, u, G), area, cd_value(lf, li, tx, ty, ti, st, amb, u, t))


LAW = LawSpec(names=("orifice",), law=OrificeLaw, kernel=orifice_kernel, keys=CD_KEYS,
              build=lambda name, values, read_table: OrificeLaw(cd_of_values(values)),
              lower=lambda law, tables: lowered_cd(law.discharge_coefficient, tables),
              kinks=lambda law: pressure_kinks(law.discharge_coefficient),
              lowers=lambda law: lowers_cd(law.discharge_coefficient))
