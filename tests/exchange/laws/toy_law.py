"""A flow law written outside the package, the way a user adds one: its pure law, its object, its engine kernel and
its registry spec (docs/architecture.md walks through the same steps)."""
from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

from numba import njit

from exchange.engine.layout import LAW_SIGNATURE, StateColumn, side
from exchange.laws.spec import LawKey, LawSpec


@njit(cache=True)
def power_law_mass_flow(dp, area, coefficient, exponent):
    r"""Leak of a power law in the pressure difference [kg/s] (a seal's or a valve's measured leak curve).

    .. math:: \dot m = C\,A\,\Delta p^{\,n}, \qquad \Delta p > 0

    ``dp`` p_up − p_down [Pa], ``area`` [m^2], ``coefficient`` C [kg/(s m^2 Pa^n)], ``exponent`` n [-].

    >>> power_law_mass_flow(100.0, 2.0, 1e-3, 0.5)
    0.02
    """
    return coefficient * area * dp ** exponent if dp > 0.0 else 0.0


@dataclass(frozen=True)
class PowerLawLeak:
    coefficient: float
    exponent: float = 1.0
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        return power_law_mass_flow(up.p - p_down, area, self.coefficient, self.exponent)


class PowerLawFloat(IntEnum):
    COEFFICIENT = 0
    EXPONENT = 1


@njit(LAW_SIGNATURE, cache=True)
def power_law_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    return power_law_mass_flow(side(st, amb, u, StateColumn.P) - p_down, area, lf[PowerLawFloat.COEFFICIENT],
                               lf[PowerLawFloat.EXPONENT])


LAW = LawSpec(names=("power_law",), law=PowerLawLeak, kernel=power_law_kernel,
              keys=(LawKey("leak_coefficient", "power_law: C in ṁ = C·A·Δp^n", "kg/(s m^2 Pa^n)", default=0.0),
                    LawKey("leak_exponent", "power_law: n", default=1.0)),
              build=lambda name, values, read_table: PowerLawLeak(values["leak_coefficient"],
                                                                  values["leak_exponent"]),
              lower=lambda law, tables: ((law.coefficient, law.exponent), ()))
