"""Hydraulic (liquid-filled) cavities: mass of liquid as the unknown, pressure from a bulk modulus.

Abaqus *FLUID BEHAVIOR, HYDRAULIC: the density follows from a reference density and a bulk modulus,

    ρ(p, T) = ρ_ref(T)·exp((p − p_ref)/K),   ρ_ref(T) = ρ_0·exp(−α (T − T_0)),

so p = p_ref + K·ln(ρ/ρ_ref(T)); for a closed cavity (constant mass) at constant T, p − p_0 = K·ln(V_0/V).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit


__all__ = ["HydraulicCavity", "hydraulic_pressure"]


@njit(cache=True, inline="always")
def hydraulic_pressure(density: float, reference_density: float, bulk_modulus: float,
                       reference_pressure: float) -> float:
    r"""Pressure of a liquid of constant bulk modulus [Pa].

    .. math:: p = p_{ref} + K \ln(\rho / \rho_{ref})

    Parameters
    ----------
    density : float
        Current density ρ [kg/m^3].
    reference_density : float
        Density ρ_ref at the reference pressure and the current temperature [kg/m^3].
    bulk_modulus : float
        K [Pa].
    reference_pressure : float
        p_ref [Pa].

    References
    ----------
    Abaqus Analysis User's Guide, "Fluid cavity definition", hydraulic fluids.

    Examples
    --------
    Oil (K = 1.5 GPa) compressed by 1 %:

    >>> round(hydraulic_pressure(870.0 / 0.99, 870.0, 1.5e9, 1.0e5) / 1e6, 4)
    15.1755
    """
    return reference_pressure + bulk_modulus * math.log(density / reference_density)


@dataclass(frozen=True)
class HydraulicCavity:
    """A liquid-filled cavity: volume model, reference density [kg/m^3] at ``reference_pressure`` [Pa] and
    ``reference_temperature`` [K], bulk modulus [Pa], volumetric thermal expansion [1/K], temperature T(t) [K]
    (a cavity.tables.Table), added and minimum volume [m^3]."""

    name: str
    volume: object
    initial_mass: float
    reference_density: float
    bulk_modulus: float
    reference_pressure: float
    reference_temperature: float
    temperature: object
    thermal_expansion: float = 0.0
    added_volume: float = 0.0
    minimum_volume: float = 0.0
    inflators: tuple = ()
    isothermal = True
    kind = "hydraulic"

    @property
    def initial_masses(self) -> tuple:
        return (self.initial_mass,)

    @property
    def initial_temperature(self) -> float:
        return self.temperature(0.0)

    @property
    def n_unknowns(self) -> int:
        return 1

    def initial_unknowns(self, gas=None) -> np.ndarray:
        return np.array([self.initial_mass])

    def total_volume(self, t: float) -> float:
        return self.volume(t) + self.added_volume

    @property
    def breakpoints(self) -> tuple:
        return tuple(self.volume.breakpoints) + tuple(self.temperature.breakpoints)

    def heat_loss(self, T: float) -> float:
        return 0.0
