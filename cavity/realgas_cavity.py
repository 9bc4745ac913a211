"""A cavity (a stored-gas tank, a test vessel) whose gas follows a real-gas equation of state.

Unknowns: the species masses [kg] (one species carries the fluid), the internal energy U [J] and, with a wall,
the wall temperatures T_1 … T_N [K] of its N layers (one when lumped, inner to outer) and the heat the wall gave
to the ambient ∫Q_out dt [J] (a ledger entry: it closes the wall's books, Σ C_j (T_j − T_j0) = ∫Q_in − ∫Q_out,
to round-off). The gas balance is the one of
:mod:`cavity.cavity`:

    dU/dt = Σ ṁ_in h_in − Σ ṁ_out h_out − p dV/dt − Q,

with Q = h_c A (T − T_amb) (``heat_loss``) or Q = Q_in to the wall (``wall``, :mod:`cavity.wall`). The state is
(ρ, u) = (m/V, U/m) → T by Newton on the equation of state, then p, h, c (:mod:`cavity.realgas`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .caution import caution
from .cavity import Cavity

__all__ = ["RealGasCavity", "RealGasState", "REAL_GAS_ENERGY_MODELS"]

REAL_GAS_ENERGY_MODELS = ("adiabatic", "heat_loss", "wall")


class _RealMixture:
    """The few mixture quantities the network and outputs read: mass [kg], an effective gas constant
    p/(ρT) [J/(kg K)] and, as γ, the isentropic exponent κ = ρc²/p [-] (used by laws that are not real-gas)."""

    __slots__ = ("mass", "gas_constant", "kappa", "moles")

    def __init__(self, mass, gas_constant, kappa, moles):
        self.mass, self.gas_constant, self.kappa, self.moles = mass, gas_constant, kappa, moles

    def gamma(self, T: float) -> float:
        return self.kappa


@dataclass(frozen=True)
class RealGasCavity(Cavity):
    """Definition of a real-gas cavity: a :class:`cavity.cavity.Cavity` (``energy`` ``"adiabatic"``,
    ``"heat_loss"`` or ``"wall"``) whose gas is ``fluid``.

    Attributes (beyond Cavity's)
    ----------------------------
    fluid : cavity.realgas.RealFluid
    species_index : int
        The scene species that is this fluid (the only non-zero entry of ``initial_masses``).
    wall : cavity.wall.Wall or None
        energy ``"wall"``.
    """

    fluid: object = None
    species_index: int = 0
    wall: object = None
    kind = "realgas"

    @property
    def n_unknowns(self) -> int:
        return len(self.initial_masses) + (2 + self.wall.layers if self.wall is not None else 1)

    @property
    def n_coupled(self) -> int:
        """The leading unknowns the right-hand side depends on: masses, U and the wall temperatures (not the
        heat to ambient, a ledger entry)."""
        return len(self.initial_masses) + (1 + self.wall.layers if self.wall is not None else 1)

    def initial_unknowns(self, gas=None) -> np.ndarray:
        m = np.asarray(self.initial_masses, dtype=float)
        V = max(self.total_volume(0.0), self.minimum_volume)
        total = float(m.sum())
        U = total * self.fluid.at(total / V, self.initial_temperature).u
        extra = [U] + ([self.wall.initial_temperature] * self.wall.layers + [0.0] if self.wall is not None else [])
        return np.append(m, extra)

    def state(self, t: float, unknowns, T_guess: float) -> "RealGasState":
        """The state at t from this cavity's slice of the unknowns (masses clipped at 0 for the equation of
        state)."""
        ns = len(self.initial_masses)
        if ns == 1:  # (np.maximum on one entry costs as much as the rest of this method's bookkeeping)
            m = float(unknowns[0])
            m = m if m > 0.0 else 0.0
            masses = np.array((m,))
        else:
            masses = np.maximum(unknowns[:ns], 0.0)
            m = float(masses.sum())
        V = self.volume(t) + self.added_volume
        V_eos = V if V > self.minimum_volume else self.minimum_volume
        rate = self.volume.rate(t) if V > self.minimum_volume else 0.0
        fluid = self.fluid
        rho = m / V_eos
        T, pt = fluid.state(rho, float(unknowns[ns]) / m, T_guess) if m > 0.0 else (T_guess, None)
        if T < fluid.caution_below:
            _caution_condensable(self.name, fluid)
        p = pt[0] if pt is not None else 0.0
        kappa = rho * pt[4] ** 2 / p if pt is not None else 1.4
        R = p / (rho * T) if pt is not None else 1.0
        mix = _RealMixture(m, R, kappa, m / fluid.molar_mass)
        s = RealGasState(masses, mix, T, V, rate, p, rho, pt[2] if pt is not None else 0.0, fluid)
        if self.wall is not None:  # its heat flows: wall_heat, called by the right-hand side only
            s.wall_temperature = float(unknowns[ns + 1])
            s.outer_wall_temperature = float(unknowns[ns + self.wall.layers])
            s.wall_layers = tuple(unknowns[ns + 1:ns + 1 + self.wall.layers].tolist())
        else:
            s.heat_out = self.heat_loss(T)  # Cavity's h_c·A·(T − T_amb), 0 unless heat_loss
        return s


    @property
    def has_inflow_convection(self) -> bool:
        """The wall's inner coefficient depends on the inflow (a forced-convection term)."""
        return self.wall is not None and not self.wall.inner_h and self.wall.jet_diameter > 0.0

    def wall_heat(self, s: "RealGasState", inflow: float) -> None:
        """Set the wall's heat flows of state ``s`` with ``inflow`` [kg/s] entering the cavity: ``s.heat_out``
        (gas → wall [W]) and ``s.extra_rates`` (dT_j/dt of the layers [K/s], wall → ambient [W])."""
        wall = self.wall
        q_in, q_out = wall.heat_flows(self.fluid, s.pressure, s.temperature, s.wall_temperature, inflow,
                                      s.outer_wall_temperature) if s.mixture.mass > 0.0 else (0.0, 0.0)
        s.heat_out, s.extra_rates = q_in, wall.layer_rates(s.wall_layers, q_in, q_out) + (q_out,)


def _caution_condensable(name: str, fluid) -> None:
    caution(f"cavity {name}: the {fluid.name} mixture is below the critical temperature of {fluid.caution_component} "
            f"({fluid.caution_below:.1f} K): it is evaluated as a gas (phase imposed; only the initial state is "
            "checked to be single-phase), condensation is not modelled: where its temperature history falls below that, "
            "treat the results as an ideal-vapour estimate")


@dataclass(slots=True)
class RealGasState:
    """The state of a real-gas cavity at one instant.

    ``heat_out``: heat leaving the gas [W]; ``extra_rates``: d/dt of the unknowns after U (wall temperatures
    [K/s], heat to ambient [W]); ``wall_temperature``, ``outer_wall_temperature`` [K]: the inner and outer
    layers' (the same when lumped; NaN without a wall); ``wall_layers``: every layer's [K]."""

    masses: np.ndarray
    mixture: _RealMixture
    temperature: float
    volume: float
    volume_rate: float
    pressure: float
    density: float
    specific_enthalpy: float
    fluid: object
    heat_out: float = 0.0
    extra_rates: tuple = ()
    wall_temperature: float = math.nan
    outer_wall_temperature: float = math.nan
    wall_layers: tuple = ()
