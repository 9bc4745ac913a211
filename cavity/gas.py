"""Ideal-gas mixtures tracked by mass per species: pressure, temperature from internal energy, γ, R.

A :class:`GasModel` holds the species of a scene on one common set of temperature ranges. For given species
masses, :meth:`GasModel.mixture` sums the per-species polynomial coefficients weighted by moles once, so the
mixture's U(T), cv(T) and cp(T) are single polynomials per range, evaluated in scalar arithmetic inside the ODE
right-hand side. Temperature is recovered from internal energy by Newton's method on the analytic U(T).
"""
from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field

import numpy as np

from .species import Species, molar_enthalpy, molar_heat_capacity
from .tolerances import R_UNIVERSAL, TOL

__all__ = ["GasModel", "Mixture", "TemperatureSolveError"]


class TemperatureSolveError(ArithmeticError):
    """Newton's method could not recover a positive temperature from the internal energy."""


@dataclass(frozen=True)
class Mixture:
    """Thermodynamic polynomial of a fixed amount of mixture: totals over species, per temperature range.

    Attributes
    ----------
    moles : float
        Total amount n [mol].
    mass : float
        Total mass m [kg].
    breaks : tuple of float
        Interior temperatures [K] of the ranges.
    rows : list of 7-lists
        Per range: mole-weighted sums of (a, b, c, d, e, f) and the enthalpy offset [J] that makes H continuous.
    """

    moles: float
    mass: float
    breaks: tuple
    rows: list

    def _row(self, T):
        return self.rows[bisect.bisect_right(self.breaks, T)] if self.breaks else self.rows[0]

    def enthalpy(self, T: float) -> float:
        """Total enthalpy H(T) [J] (reference: the polynomial antiderivative of the first range)."""
        r = self._row(T)
        return molar_enthalpy(r[:6], T) + r[6]

    def internal_energy(self, T: float) -> float:
        """Total internal energy U(T) = H(T) − n·R_u·T [J]."""
        return self.enthalpy(T) - self.moles * R_UNIVERSAL * T

    def heat_capacity_p(self, T: float) -> float:
        """Total isobaric heat capacity Cp(T) [J/K]."""
        return molar_heat_capacity(self._row(T)[:6], T)

    def heat_capacity_v(self, T: float) -> float:
        """Total isochoric heat capacity Cv(T) = Cp − n·R_u [J/K]."""
        return self.heat_capacity_p(T) - self.moles * R_UNIVERSAL

    def gamma(self, T: float) -> float:
        """Ratio of specific heats cp/cv [-]."""
        cp = self.heat_capacity_p(T)
        return cp / (cp - self.moles * R_UNIVERSAL)

    @property
    def gas_constant(self) -> float:
        """Specific gas constant R = n·R_u/m [J/(kg K)]."""
        return self.moles * R_UNIVERSAL / self.mass

    def temperature(self, U: float, T_guess: float) -> float:
        """Temperature [K] whose internal energy is U [J], by Newton's method on the analytic U(T).

        U(T) is strictly increasing (Cv > 0), so Newton converges from any positive guess in a few steps;
        steps are kept above :attr:`Tolerances.temperature_floor`.
        """
        T = T_guess
        for _ in range(TOL.newton_max_iterations):
            step = (self.internal_energy(T) - U) / self.heat_capacity_v(T)
            T_new = T - step
            if T_new < TOL.temperature_floor:
                T_new = 0.5 * (T + TOL.temperature_floor)
            if abs(T_new - T) <= TOL.newton_rtol * T_new:
                return T_new
            T = T_new
        raise TemperatureSolveError(f"no temperature found for U = {U!r} J, n = {self.moles!r} mol "
                                    f"(last T = {T!r} K)")


@dataclass(frozen=True)
class GasModel:
    """The species of a scene on one common set of temperature ranges.

    Parameters
    ----------
    species : tuple of Species
        Every species any cavity, inflator or ambient uses; masses are arrays in this order.

    Examples
    --------
    >>> from cavity.species import Species
    >>> g = GasModel((Species("N2", 0.028, (29.1,)),))
    >>> mix = g.mixture([0.028])
    >>> round(mix.internal_energy(300.0), 6), round(mix.temperature(mix.internal_energy(300.0), 1000.0), 12)
    (6235.661215, 300.0)
    """

    species: tuple[Species, ...]
    molar_masses: np.ndarray = field(init=False, repr=False, compare=False)
    breaks: tuple = field(init=False, repr=False, compare=False)
    _table: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        if not self.species:
            raise ValueError("a gas model needs at least one species")
        names = [s.name for s in self.species]
        if len(set(names)) != len(names):
            raise ValueError(f"species names must be unique, got {names}")
        breaks = tuple(sorted({b for s in self.species for b in s.breaks}))
        table = np.array([_species_rows(s, breaks) for s in self.species])  # (ns, nr, 7), per mole
        object.__setattr__(self, "species", tuple(self.species))
        object.__setattr__(self, "breaks", breaks)
        object.__setattr__(self, "_table", table.reshape(len(self.species), -1))
        object.__setattr__(self, "molar_masses", np.array([s.molar_mass for s in self.species]))

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.species)

    def index(self, name: str) -> int:
        return self.names.index(name)

    def mixture(self, masses) -> Mixture:
        """The mixture polynomial of species masses ``masses`` [kg], shape (ns,)."""
        masses = np.asarray(masses, dtype=float)
        n = masses / self.molar_masses
        rows = (n @ self._table).reshape(-1, 7).tolist()
        return Mixture(float(n.sum()), float(masses.sum()), self.breaks, rows)

    def mass_fractions(self, fractions: dict, *, molar: bool = False) -> np.ndarray:
        """Mass fractions (ns,) from a {species: fraction} mapping given by mass or by mole; normalised."""
        y = np.zeros(len(self.species))
        for name, value in fractions.items():
            y[self.index(name)] = value
        if molar:
            y = y * self.molar_masses
        total = y.sum()
        if not total > 0.0:
            raise ValueError(f"gas composition {fractions} has no positive fraction")
        return y / total

    def masses_at(self, mass_fractions, p: float, T: float, V: float) -> np.ndarray:
        """Species masses [kg] of a gas of mass fractions ``mass_fractions`` at p [Pa], T [K] filling V [m^3]."""
        y = np.asarray(mass_fractions, dtype=float)
        moles_per_kg = float(np.sum(y / self.molar_masses))
        total = p * V / (R_UNIVERSAL * T * moles_per_kg)
        return y * total


def _species_rows(species: Species, breaks: tuple) -> list:
    """Per-mole coefficient rows (a..f, H offset) of one species on the common ranges ``breaks``."""
    rows, offset = [], 0.0
    edges = (None,) + breaks
    for i, lo in enumerate(edges):
        coef = species.piece(lo if i else (breaks[0] - 1.0 if breaks else 300.0))
        if i:
            prev = rows[-1]
            offset = molar_enthalpy(prev[:6], lo) + prev[6] - molar_enthalpy(coef, lo)
        rows.append(list(coef) + [offset])
    return rows
