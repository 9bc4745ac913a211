"""A uniform-pressure gas cavity: its definition and its unknowns (the engine derives its state and rates:
:func:`exchange.engine.gas.states`, :func:`exchange.engine.rhs.rhs`), and its heat loss.

Unknowns of one cavity: the mass of every species [kg] and, unless isothermal, the internal energy U [J].
Energy balance of the control volume (open system, moving boundary):

    dU/dt = Σ ṁ_in h_in − Σ ṁ_out h_out − p dV/dt − h_c A (T − T_amb)

with h the specific enthalpy of the gas that crosses the boundary (the inflator's at its temperature, the
upstream cavity's for an exchange). Isothermal cavities keep T fixed and carry no energy unknown
(Abaqus: an ideal-gas cavity is isothermal unless ADIABATIC is set).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from .gas import GasModel

__all__ = ["Cavity", "ENERGY_MODELS", "heat_loss"]

ENERGY_MODELS = ("adiabatic", "isothermal", "heat_loss")


@njit(cache=True)
def heat_loss(hA, T, T_ambient):
    r"""Heat a cavity loses to its surroundings [W] (Newton's law of cooling; Abaqus *FLUID CAVITY heat transfer
    through the cavity wall by a film coefficient).

    .. math:: \dot Q = h_c A\,(T - T_{amb})

    ``hA`` the heat-transfer coefficient times the area [W/K], T and T_ambient [K] (> 0 leaves the gas).

    >>> heat_loss(2.0, 350.0, 300.0)
    100.0
    """
    return hA * (T - T_ambient)


@dataclass(frozen=True)
class Cavity:
    """Definition of one gas cavity.

    Attributes
    ----------
    name : str
    volume : volume model
        ``FixedVolume``, ``TableVolume`` or ``ScaledMeshVolume`` (anything with ``__call__(t)``, ``rate(t)``,
        ``breakpoints``) [m^3].
    initial_masses : (ns,) float
        Initial mass of each species [kg].
    initial_temperature : float
        Initial (and, when isothermal, constant) temperature [K].
    energy : str
        ``"adiabatic"``, ``"isothermal"`` or ``"heat_loss"``.
    added_volume : float
        Volume added to the geometric volume [m^3].
    minimum_volume : float
        Volume used in the equation of state when the total falls below it [m^3].
    heat_transfer_coefficient : float
        h_c [W/(m^2 K)] (heat_loss only).
    heat_transfer_area : float
        A [m^2] (heat_loss only).
    ambient_temperature : float
        T_amb [K] for heat loss.
    inflators : tuple
        Inflator objects feeding this cavity.
    """

    name: str
    volume: object
    initial_masses: tuple
    initial_temperature: float
    energy: str = "adiabatic"
    added_volume: float = 0.0
    minimum_volume: float = 0.0
    heat_transfer_coefficient: float = 0.0
    heat_transfer_area: float = 0.0
    ambient_temperature: float = 293.15
    inflators: tuple = ()

    @property
    def isothermal(self) -> bool:
        return self.energy == "isothermal"

    @property
    def n_unknowns(self) -> int:
        return len(self.initial_masses) + (0 if self.isothermal else 1)

    def total_volume(self, t: float) -> float:
        """Geometric plus added volume [m^3]."""
        return self.volume(t) + self.added_volume

    def initial_unknowns(self, gas: GasModel) -> np.ndarray:
        m = np.asarray(self.initial_masses, dtype=float)
        if self.isothermal:
            return m.copy()
        return np.append(m, gas.mixture(m).internal_energy(self.initial_temperature))

    @property
    def breakpoints(self) -> tuple:
        return tuple(self.volume.breakpoints) + tuple(b for inf in self.inflators for b in inf.breakpoints)

    def heat_loss(self, T: float) -> float:
        """Heat flow out of the cavity h_c·A·(T − T_amb) [W]; 0 unless the energy model is heat_loss."""
        if self.energy != "heat_loss":
            return 0.0
        return heat_loss(self.heat_transfer_coefficient * self.heat_transfer_area, float(T),
                         self.ambient_temperature)
