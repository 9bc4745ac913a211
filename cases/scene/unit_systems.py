"""Consistent unit systems: a scene's ``[units] system`` and a deck's ``--units``. Abaqus and LS-DYNA have no units,
the numbers are in whatever consistent system the analyst chose; a scene file may be written in one too. Every
value is multiplied by the factor of its quantity to give SI (temperatures are not converted: they are absolute
[K], or for a deck shifted by *PHYSICAL CONSTANTS, ABSOLUTE ZERO).

A system is the triple (length [m], mass [kg], time [s]); every other quantity's factor follows from its
dimension exponents. The three systems offered are the common consistent sets of crash and airbag analysis.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["UnitSystem", "SYSTEMS", "unit_system", "exponents"]

#: quantity -> exponents of (length, mass, time)
DIMENSIONS = {
    "length": (1, 0, 0), "area": (2, 0, 0), "volume": (3, 0, 0), "mass": (0, 1, 0), "time": (0, 0, 1),
    "velocity": (1, 0, -1), "pressure": (-1, 1, -2), "density": (-3, 1, 0), "mass_flow": (0, 1, -1),
    "mass_flux": (-2, 1, -1), "volume_flux": (1, 0, -1), "energy": (2, 1, -2),
    "specific_heat": (2, 0, -2),  # J/(kg K)
    "molar_mass": (0, 1, 0),  # mass per mol
    "molar_heat": (2, 1, -2),  # J/(mol K): energy per mol and kelvin
    "viscous_resistance": (-2, 1, -1),  # Pa s/m
    "bulk_modulus": (-1, 1, -2), "acceleration": (1, 0, -2), "inverse_temperature": (0, 0, 0),
    "dimensionless": (0, 0, 0),
}


@dataclass(frozen=True)
class UnitSystem:
    """A consistent unit system: the SI value of its unit of length, mass and time.

    >>> unit_system("mm-t-s").factor("pressure")  # N/mm^2 = MPa
    1000000.0
    >>> unit_system("mm-kg-ms").factor("pressure")  # kN/mm^2 = GPa
    1000000000.0
    """

    name: str
    length: float
    mass: float
    time: float

    def factor(self, quantity: str) -> float:
        """SI value of one deck unit of ``quantity`` (a key of ``DIMENSIONS``)."""
        a, b, c = DIMENSIONS[quantity]
        return self.length ** a * self.mass ** b * self.time ** c

    def scale(self, exps: tuple) -> float:
        """SI value of one unit of the quantity with (length, mass, time) exponents ``exps``."""
        return self.length ** exps[0] * self.mass ** exps[1] * self.time ** exps[2]

    def si(self, value: float, quantity: str) -> float:
        """``value`` in deck units converted to SI (exact for SI itself: the factor is 1.0)."""
        f = self.factor(quantity)
        return float(value) if f == 1.0 else float(value) * f


SYSTEMS = {
    "SI": UnitSystem("SI", 1.0, 1.0, 1.0),  # m, kg, s: N, Pa, J
    "mm-t-s": UnitSystem("mm-t-s", 1e-3, 1e3, 1.0),  # mm, tonne, s: N, MPa, mJ
    "mm-kg-ms": UnitSystem("mm-kg-ms", 1e-3, 1.0, 1e-3),  # mm, kg, ms: kN, GPa, J
}


def unit_system(name: str) -> UnitSystem:
    """The system called ``name`` (KeyError with the known names otherwise)."""
    try:
        return SYSTEMS[name]
    except KeyError:
        raise KeyError(f"unknown unit system {name!r}; known: {', '.join(SYSTEMS)}") from None


#: (length, mass, time) exponents of the symbols a scene key's unit is written with (temperature, mol: none).
_SYMBOLS = {"m": (1, 0, 0), "kg": (0, 1, 0), "s": (0, 0, 1), "Pa": (-1, 1, -2), "N": (1, 1, -2), "J": (2, 1, -2),
            "W": (2, 1, -3), "K": (0, 0, 0), "mol": (0, 0, 0), "deg": (0, 0, 0), "-": (0, 0, 0), "1": (0, 0, 0)}


def _product(text: str) -> tuple:
    """Exponents of a product of symbols such as ``"Pa s"`` or ``"s Pa m^2"``."""
    total = [0, 0, 0]
    for token in text.replace("(", " ").replace(")", " ").split():
        sym, _, power = token.partition("^")
        exps = _SYMBOLS[sym]
        for d in range(3):
            total[d] += exps[d] * int(power or 1)
    return tuple(total)


def exponents(unit: str) -> tuple | None:
    """(length, mass, time) exponents of a scene key's unit, or None when it is not a plain product of SI symbols.

    >>> exponents("W/(m^2 K)"), exponents("kg/(s Pa m^2)"), exponents("1/K"), exponents("J/(mol K), ...")
    ((0, 1, -3), (-1, 0, 1), (0, 0, 0), None)
    """
    num, _, den = unit.partition("/")
    try:
        a, b = _product(num), _product(den) if den else (0, 0, 0)
    except (KeyError, ValueError):
        return None
    return tuple(x - y for x, y in zip(a, b))
