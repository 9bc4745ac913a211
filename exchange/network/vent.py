"""Exchanges: a flow law, an area, and the two sides it connects (a cavity and ambient, or two cavities).

The sign convention: a positive mass flow goes from ``upstream`` to ``downstream`` as named in the scene. Gas
always carries the composition and specific enthalpy of the side it leaves.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .activation import Activation
from cavity.isentropic import critical_pressure_ratio
from exchange.laws.orifice import OrificeLaw

__all__ = ["GasPoint", "Ambient", "OrificeLaw", "Exchange"]  # OrificeLaw re-exported from .laws.orifice


@dataclass(frozen=True)
class GasPoint:
    """What a flow law needs to know of the gas on one side.

    Attributes: pressure p [Pa], temperature T [K], density rho [kg/m^3], specific gas constant R [J/(kg K)],
    ratio of specific heats gamma [-], specific enthalpy h [J/kg], mass fractions (ns,) [-].
    """

    p: float
    T: float
    rho: float
    R: float
    gamma: float
    h: float
    mass_fractions: object

    def choke_ratio(self) -> float:
        """Throat/upstream pressure ratio below which an orifice fed from this gas is choked [-]."""
        return critical_pressure_ratio(self.gamma)


@dataclass(frozen=True)
class Ambient:
    """The environment: an infinite reservoir at pressure [Pa] and temperature [K] with a gas composition."""

    pressure: float
    temperature: float
    mass_fractions: tuple
    gas: object  # cavity.gas.Mixture of 1 kg of ambient gas

    def point(self) -> GasPoint:
        g, T = self.gas, self.temperature
        R = g.gas_constant
        return GasPoint(self.pressure, T, self.pressure / (R * T), R, g.gamma(T), g.enthalpy(T) / g.mass,
                        np.asarray(self.mass_fractions, dtype=float))


@dataclass(frozen=True)
class Exchange:
    """A fluid exchange between cavity ``upstream`` and cavity ``downstream`` (None: ambient).

    Attributes
    ----------
    name : str
    upstream : int
        Index of the first cavity.
    downstream : int or None
        Index of the second cavity, or None for the environment.
    law : object
        Has ``mass_flow(up: GasPoint, p_down, area, t) -> float`` (>= 0, never reversing).
    area : float
        Flow area [m^2].
    two_way : bool
        To ambient: also let ambient gas flow in when the cavity pressure is below ambient. Between
        cavities flow always follows the pressure difference.
    activation : Activation or None
        Time window, pop pressure, amplitude, delta area (None: always open).
    """

    name: str
    upstream: int
    downstream: int | None
    law: object
    area: float
    two_way: bool = False
    activation: Activation | None = None
