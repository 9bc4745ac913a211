r"""Flow resistance with viscous (linear) and hydrodynamic (quadratic) terms (Abaqus TYPE=BULK VISCOSITY).

Abaqus defines this exchange by two data: a "viscous resistance coefficient" and a "hydrodynamic resistance
coefficient", tabulated against the *average* absolute pressure and temperature of the two sides (Abaqus Keywords
Reference, *FLUID EXCHANGE PROPERTY, data lines for TYPE=BULK VISCOSITY). The equation that combines them is in the
Analysis User's Guide, which could not be read here, so the form below is ours:

.. math:: \Delta p = c_v\, v + c_h\, \rho\, v |v|, \qquad v = \frac{\dot m}{\rho A}

- viscous term: a Darcy/Poiseuille-like drop proportional to the through-velocity, c_v [Pa s/m];
- hydrodynamic term: a dynamic-pressure loss, c_h [-] (c_h = 1/2 is one dynamic head, i.e. a loss coefficient
  K = 2 c_h).

The same two-term law is the classical Darcy–Forchheimer / "linear + quadratic" resistance. With c_h = 0 the mass
flow is exactly proportional to Δp (conductance ρA/c_v).

Unlike the orifice and fabric laws, these laws are odd in Δp: a negative Δp gives the opposite flow. A caller that
wants outflow only (Abaqus OUTFLOW ONLY, or exchange with the environment) clips the result at 0.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum

from numba import njit

from exchange.engine.layout import LAW_SIGNATURE, StateColumn, side

from .spec import LawKey, LawSpec

__all__ = [
    "bulk_viscosity_mass_flow",
    "bulk_viscosity_pressure_drop",
    "linear_resistance_conductance",
    "BulkViscosityLaw",
    "bulk_viscosity_kernel",
    "LAW",
]


@njit(cache=True)
def _check_coefficients(c_v: float, c_h: float) -> None:
    if c_v < 0.0 or c_h < 0.0:
        raise ValueError("bulk viscosity coefficients c_v, c_h must be >= 0")
    if c_v == 0.0 and c_h == 0.0:
        raise ValueError("bulk viscosity needs c_v > 0 or c_h > 0 (both zero is an infinite conductance)")


def bulk_viscosity_pressure_drop(mdot: float, rho: float, area: float, c_v: float, c_h: float) -> float:
    r"""Pressure drop across a viscous + hydrodynamic resistance for a given mass flow [Pa].

    .. math:: \Delta p = c_v\, v + c_h\, \rho\, v|v|, \qquad v = \dot m / (\rho A)

    Parameters
    ----------
    mdot : float
        Mass flow from side 1 to side 2 [kg/s] (signed).
    rho : float
        Density that converts mass flow to velocity [kg/m^3], > 0. Abaqus tabulates the coefficients against the
        average state of the two sides; the caller chooses (the upstream or the mean density).
    area : float
        Exchange area A [m^2], > 0.
    c_v : float
        Viscous resistance coefficient [Pa s/m], >= 0.
    c_h : float
        Hydrodynamic resistance coefficient [-], >= 0.

    Returns
    -------
    float
        p_1 − p_2 [Pa], with the sign of ``mdot``.

    Examples
    --------
    v = 0.12 / (1.2 x 0.01) = 10 m/s: 100 x 10 + 0.5 x 1.2 x 10^2 = 1060 Pa.

    >>> round(bulk_viscosity_pressure_drop(0.12, 1.2, 0.01, 100.0, 0.5), 9)
    1060.0
    """
    v = mdot / (rho * area)
    return c_v * v + c_h * rho * v * abs(v)


@njit(cache=True)
def bulk_viscosity_mass_flow(dp: float, rho: float, area: float, c_v: float, c_h: float) -> float:
    r"""Mass flow driven by a pressure difference through a viscous + hydrodynamic resistance [kg/s].

    Inverse of :func:`bulk_viscosity_pressure_drop`, in closed form:

    .. math::

        \dot m = \operatorname{sign}(\Delta p)\, \rho A\,
                 \frac{2|\Delta p|}{c_v + \sqrt{c_v^2 + 4 c_h \rho |\Delta p|}}

    (the root of :math:`c_h\rho v^2 + c_v v - |\Delta p| = 0` written without cancellation). For c_h = 0 it is
    evaluated as :math:`\rho A \Delta p / c_v`, exactly proportional to Δp.

    Parameters
    ----------
    dp : float
        p_1 − p_2 [Pa] (signed; the flow has its sign).
    rho, area, c_v, c_h : float
        As in :func:`bulk_viscosity_pressure_drop` [kg/m^3, m^2, Pa s/m, -].

    Returns
    -------
    float
        Mass flow from side 1 to side 2 [kg/s]; 0 when ``dp == 0``, ``area <= 0`` or ``rho <= 0``. Continuous in
        Δp; its slope at Δp = 0 is ρA/c_v (infinite only when c_v = 0).

    Raises
    ------
    ValueError
        If a coefficient is negative or both are zero.

    Examples
    --------
    >>> round(bulk_viscosity_mass_flow(1060.0, 1.2, 0.01, 100.0, 0.5), 12)
    0.12
    >>> round(bulk_viscosity_mass_flow(-500.0, 1.2, 0.01, 100.0, 0.0), 12)
    -0.06
    """
    _check_coefficients(c_v, c_h)
    if dp == 0.0 or area <= 0.0 or rho <= 0.0:
        return 0.0
    if c_h == 0.0:
        return rho * area * dp / c_v
    mag = abs(dp)
    speed = 2.0 * mag / (c_v + math.sqrt(c_v * c_v + 4.0 * c_h * rho * mag))
    return math.copysign(rho * area * speed, dp)


def linear_resistance_conductance(rho: float, area: float, c_v: float) -> float:
    r"""Mass-flow conductance of a purely viscous resistance [kg/(s Pa)].

    .. math:: G = \frac{\rho A}{c_v}

    so that ``bulk_viscosity_mass_flow(dp, rho, area, c_v, 0.0)`` equals
    :func:`exchange.laws.linear_resistance.linear_resistance_mass_flow` ``(dp, G)``.

    Examples
    --------
    >>> round(linear_resistance_conductance(1.2, 0.01, 100.0), 12)
    0.00012
    """
    if c_v <= 0.0:
        raise ValueError(f"a linear resistance needs c_v > 0, got {c_v}")
    return rho * area / c_v


@dataclass(frozen=True)
class BulkViscosityLaw:
    """BULK VISCOSITY: Δp = c_v·v + c_h·ρ·v|v| solved for ṁ (:func:`bulk_viscosity_mass_flow`), outflow only."""

    viscous: float
    hydrodynamic: float = 0.0
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        dp = up.p - p_down
        return bulk_viscosity_mass_flow(dp, up.rho, area, self.viscous, self.hydrodynamic) if dp > 0 else 0.0


class BulkFloat(IntEnum):
    VISCOUS = 0  # c_v [Pa s/m]
    HYDRODYNAMIC = 1  # c_h [-]


@njit(LAW_SIGNATURE, cache=True)
def bulk_viscosity_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The engine's bulk-viscosity flow from side u [kg/s], >= 0."""
    dp = side(st, amb, u, StateColumn.P) - p_down
    if dp <= 0.0:
        return 0.0
    return bulk_viscosity_mass_flow(dp, side(st, amb, u, StateColumn.RHO), area, lf[BulkFloat.VISCOUS],
                                    lf[BulkFloat.HYDRODYNAMIC])


LAW = LawSpec(names=("bulk_viscosity",), law=BulkViscosityLaw, kernel=bulk_viscosity_kernel,
              keys=(LawKey("viscous_resistance", "bulk_viscosity: c_v in Δp = c_v·v + c_h·ρ·v|v|", "Pa s/m",
                           default=0.0, check="nonnegative"),
                    LawKey("hydrodynamic_resistance", "bulk_viscosity: c_h", default=0.0, check="nonnegative")),
              required={"bulk_viscosity": ("viscous_resistance",)},
              build=lambda name, values, read_table: BulkViscosityLaw(values["viscous_resistance"],
                                                                      values["hydrodynamic_resistance"]),
              lower=lambda law, tables: ((float(law.viscous), float(law.hydrodynamic)), ()))
