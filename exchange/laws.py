"""Flow-law objects: the pure functions of this package behind one interface the network calls.

Every law answers ``mass_flow(up, p_down, area, t) -> float``: the mass flow [kg/s] from the gas point ``up`` into
a region at pressure ``p_down`` through ``area`` [m^2] at time t, >= 0 and zero when p_down >= up.p (the network
swaps the sides for reverse flow). Prescribed-flux laws set ``prescribed = True`` and return a signed flow that
does not depend on the pressures.
"""
from __future__ import annotations

from dataclasses import dataclass

from .bulk_viscosity import bulk_viscosity_mass_flow, linear_resistance_mass_flow
from .discharge import PRESSURE, DischargeTable
from .fabric import fabric_leakage_mass_flow, graefe_mass_flow
from .flux import mass_flux_mass_flow, volume_flux_mass_flow
from .leakage_table import LeakageTable, leakage_table_mass_flow
from .orifice import orifice_mass_flow

__all__ = ["OrificeLaw", "FabricLeakageLaw", "GraefeLaw", "LeakageTableLaw", "FluxLaw", "BulkViscosityLaw",
           "LinearResistanceLaw", "LAW_NAMES"]


def _cd(cd, up, t) -> float:
    if isinstance(cd, DischargeTable):
        return cd(up.p) if cd.variable == PRESSURE else cd(t)
    return cd


def _cd_breakpoints(cd) -> tuple:
    """Times where a discharge coefficient of time kinks [s] (the integrator stops there)."""
    return cd.x if isinstance(cd, DischargeTable) and cd.variable != PRESSURE else ()


@dataclass(frozen=True)
class OrificeLaw:
    """Abaqus ORIFICE (pneumatic only): :func:`exchange.orifice.orifice_mass_flow`.

    ``discharge_coefficient``: Cd [-], a constant or a :class:`DischargeTable` of upstream pressure or time.
    """

    discharge_coefficient: object = 1.0
    pneumatic = True
    prescribed = False
    orifice_join = True  # the law changes form at Δp/p = LINEAR_BELOW: a switch there (exchange.lowered_switches)

    def mass_flow(self, up, p_down, area, t):
        return orifice_mass_flow(up.p, up.T, p_down, up.R, up.gamma, area, _cd(self.discharge_coefficient, up, t))

    @property
    def breakpoints(self) -> tuple:
        return _cd_breakpoints(self.discharge_coefficient)


@dataclass(frozen=True)
class FabricLeakageLaw:
    """Abaqus FABRIC LEAKAGE: :func:`exchange.fabric.fabric_leakage_mass_flow` on the open fraction of the area."""

    discharge_coefficient: object = 1.0
    open_fraction: float = 1.0
    pneumatic = True
    prescribed = False
    orifice_join = True

    def mass_flow(self, up, p_down, area, t):
        return fabric_leakage_mass_flow(up.p, up.T, p_down, up.R, up.gamma, area,
                                        _cd(self.discharge_coefficient, up, t), self.open_fraction)

    @property
    def breakpoints(self) -> tuple:
        return _cd_breakpoints(self.discharge_coefficient)


@dataclass(frozen=True)
class GraefeLaw:
    """Graefe–Krummheuer–Siejak porosity (OpenRadioss Iform_ps = 3): :func:`exchange.fabric.graefe_mass_flow`."""

    flc: float = 1.0
    fac: float = 1.0
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        return graefe_mass_flow(up.p, p_down, up.rho, area, self.flc, self.fac)


@dataclass(frozen=True)
class LeakageTableLaw:
    """Abaqus MASS RATE LEAKAGE / VOLUME RATE LEAKAGE: :func:`exchange.leakage_table.leakage_table_mass_flow`."""

    table: LeakageTable
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        return leakage_table_mass_flow(self.table, up.p - p_down, area, up.rho)


@dataclass(frozen=True)
class FluxLaw:
    """Abaqus MASS FLUX / VOLUME FLUX: a prescribed flow per unit area, signed, times an amplitude table of time.

    ``kind`` is ``"mass"`` [kg/(s m^2)] or ``"volume"`` [m^3/(s m^2)] (times the density of the first cavity).
    """

    kind: str
    flux: float
    amplitude: object = None  # cavity.tables.Table of time, or None
    pneumatic = False
    prescribed = True

    def mass_flow(self, up, p_down, area, t):
        a = self.amplitude(t) if self.amplitude is not None else 1.0
        if self.kind == "mass":
            return mass_flux_mass_flow(self.flux, area, a)
        return volume_flux_mass_flow(self.flux, area, up.rho, a)

    @property
    def breakpoints(self) -> tuple:
        """Times where the amplitude kinks [s] (the integrator stops there)."""
        return tuple(self.amplitude.breakpoints) if self.amplitude is not None else ()


@dataclass(frozen=True)
class BulkViscosityLaw:
    """BULK VISCOSITY: Δp = c_v·v + c_h·ρ·v|v| solved for ṁ (:func:`exchange.bulk_viscosity.bulk_viscosity_mass_flow`)."""

    viscous: float
    hydrodynamic: float = 0.0
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        dp = up.p - p_down
        return bulk_viscosity_mass_flow(dp, up.rho, area, self.viscous, self.hydrodynamic) if dp > 0 else 0.0


@dataclass(frozen=True)
class LinearResistanceLaw:
    """ṁ = G·A·Δp with a conductance per unit area G [kg/(s Pa m^2)] (a linear valve, Cantera's Valve with K)."""

    conductance: float
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        dp = up.p - p_down
        return linear_resistance_mass_flow(dp, self.conductance * area) if dp > 0 else 0.0


LAW_NAMES = ("orifice", "fabric_leakage", "graefe", "mass_rate_leakage", "volume_rate_leakage", "mass_flux",
             "volume_flux", "bulk_viscosity", "linear_resistance")
