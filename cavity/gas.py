"""Ideal-gas mixtures tracked by mass per species: pressure, temperature from internal energy, γ, R.

A :class:`GasModel` holds the species of a scene on one common set of temperature ranges. For given species
masses, :meth:`GasModel.mixture` sums the per-species polynomial coefficients weighted by moles (for a range
only when a temperature in it is asked for), so the mixture's U(T), cv(T) and cp(T) are single polynomials per
range, evaluated in scalar arithmetic inside the ODE right-hand side. Temperature is recovered from internal
energy by Newton's method on the analytic U(T) (one division where cp is constant).
"""
from __future__ import annotations

import bisect
from dataclasses import dataclass, field

import numpy as np

from .gas_rows import temperature as row_temperature
from .species import Species, enthalpy_polynomial, heat_capacity_polynomial, molar_enthalpy
from .tolerances import R_UNIVERSAL

__all__ = ["GasModel", "Mixture", "TemperatureSolveError"]


class TemperatureSolveError(ArithmeticError):
    """Newton's method could not recover a positive temperature from the internal energy."""


class Mixture:
    """Thermodynamic polynomial of a fixed amount of mixture: totals over species, per temperature range.

    Immutable by convention. Built by :meth:`GasModel.mixture`, a mixture computes the mole-weighted row of a
    temperature range only when a temperature in that range is asked for (and keeps the last one), so a scene
    with CoolProp species of ~20 ranges pays for one range per right-hand-side call, not for all of them.

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

    __slots__ = ("moles", "mass", "breaks", "_rows", "_moles_by_species", "_model", "_index", "_current")

    def __init__(self, moles: float, mass: float, breaks: tuple, rows: list | None = None, *,
                 _moles_by_species=None, _model=None):
        self.moles = moles
        self.mass = mass
        self.breaks = breaks
        self._rows = rows
        self._moles_by_species = _moles_by_species  # list (ns,) [mol], with _model: rows are computed lazily
        self._model = _model  # GasModel._per_range: per-range per-species rows; rows (ns, nr, 7), flags, breaks
        self._index = -1
        self._current = None

    def __repr__(self) -> str:
        return f"Mixture(moles={self.moles!r}, mass={self.mass!r}, breaks={self.breaks!r}, rows={self.rows!r})"

    def __eq__(self, other):
        if not isinstance(other, Mixture):
            return NotImplemented
        return (self.moles, self.mass, self.breaks, self.rows) == (other.moles, other.mass, other.breaks, other.rows)

    __hash__ = None  # rows are lists, as before: not hashable

    @property
    def rows(self) -> list:
        if self._rows is None:
            self._rows = [self._combined(i) for i in range(len(self.breaks) + 1)]
        return self._rows

    def _combined(self, i: int) -> list:
        """Mole-weighted row of range i from the per-species rows."""
        n = self._moles_by_species
        per_species = self._model[0][i]
        out = [n[0] * v for v in per_species[0]]
        for k in range(1, len(n)):
            nk = n[k]
            if nk:
                out = [o + nk * v for o, v in zip(out, per_species[k])]
        return out

    def _range(self, T: float) -> int:
        return bisect.bisect_right(self.breaks, T) if self.breaks else 0

    def _row_of_range(self, i: int) -> list:
        if i != self._index:
            self._current = self._rows[i] if self._rows is not None else self._combined(i)
            self._index = i
        return self._current

    def _row(self, T):
        return self._row_of_range(self._range(T))

    def enthalpy(self, T: float) -> float:
        """Total enthalpy H(T) [J] (reference: the polynomial antiderivative of the first range)."""
        a, b, c, d, e, f, off = self._row(T)
        return enthalpy_polynomial(a, b, c, d, e, f, T) + off

    def internal_energy(self, T: float) -> float:
        """Total internal energy U(T) = H(T) − n·R_u·T [J]."""
        return self.enthalpy(T) - self.moles * R_UNIVERSAL * T

    def heat_capacity_p(self, T: float) -> float:
        """Total isobaric heat capacity Cp(T) [J/K]."""
        a, b, c, d, e, f, _ = self._row(T)
        return heat_capacity_polynomial(a, b, c, d, e, f, T)

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
        """Temperature [K] whose internal energy is U [J], by Newton's method on the analytic U(T) from T_guess
        (:func:`cavity.gas_rows.temperature`, the solver the compiled path runs too).

        U(T) is strictly increasing (Cv > 0) over the data, so the damped Newton converges from any positive guess
        in a few steps; where cp is constant over a range the step lands on the root at once.
        """
        table, linear, breaks = self._model[1:]
        T, _ = row_temperature(table, breaks, linear, np.asarray(self._moles_by_species), self.moles, float(U),
                               float(T_guess), np.empty(7))
        if not T == T:
            raise TemperatureSolveError(f"no temperature found for U = {U!r} J, n = {self.moles!r} mol "
                                        f"(from T = {T_guess!r} K)")
        return T


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
    _per_range: tuple = field(init=False, repr=False, compare=False)
    _molar_mass_list: tuple = field(init=False, repr=False, compare=False)

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
        object.__setattr__(self, "molar_masses", np.array([s.molar_mass for s in self.species]))
        # Per range the per-species rows as Python floats (Mixture builds only the rows it needs); the rows as one
        # array, per range 1 where cp is constant for every species (b..f all zero: U linear in T), and the breaks
        # (the temperature solver, cavity.gas_rows.temperature, and the compiled path read these).
        per_range = [table[:, i, :].tolist() for i in range(table.shape[1])]
        linear = np.all(table[:, :, 1:6] == 0.0, axis=(0, 2)).astype(np.int64)
        object.__setattr__(self, "_per_range", (per_range, table, linear, np.array(breaks, dtype=float)))
        object.__setattr__(self, "_molar_mass_list", tuple(float(s.molar_mass) for s in self.species))

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.species)

    def index(self, name: str) -> int:
        return self.names.index(name)

    def mixture(self, masses) -> Mixture:
        """The mixture polynomial of species masses ``masses`` [kg], shape (ns,)."""
        m = masses.tolist() if type(masses) is np.ndarray else np.asarray(masses, dtype=float).tolist()
        if len(m) != len(self._molar_mass_list):
            raise ValueError(f"expected {len(self._molar_mass_list)} species masses, got {len(m)}")
        return self._mixture_of(m)

    def _mixture_of(self, m: list) -> Mixture:
        """:meth:`mixture` of a list of Python floats (no checks): the right-hand side's fast path."""
        n = [mk / Mk for mk, Mk in zip(m, self._molar_mass_list)]
        return Mixture(float(sum(n)), float(sum(m)), self.breaks, None, _moles_by_species=n, _model=self._per_range)

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
