"""Graefe–Krummheuer–Siejak fabric porosity (OpenRadioss Iform_ps = 3): the pure law, its object and its kernel.

Incompressible Bernoulli outflow through the effective porous area at the cavity's density; one-directional (0 when
``p_down >= p_up``; two-way flow evaluates it again with the sides swapped).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum

from numba import njit

from exchange.engine.layout import LAW_SIGNATURE, StateColumn, side

from .spec import LawKey, LawSpec

__all__ = ["graefe_velocity", "graefe_mass_flow", "GraefeLaw", "graefe_kernel", "LAW"]


def graefe_velocity(p_up: float, p_down: float, rho_up: float) -> float:
    r"""Gas velocity through the fabric in the Graefe porosity formulation [m/s].

    .. math:: u = \sqrt{\frac{2\,\max(p_e - p_{down}, 0)}{\rho_e}}

    Parameters
    ----------
    p_up, p_down : float
        Upstream and downstream absolute pressures [Pa].
    rho_up : float
        Upstream (cavity) gas density ρ_e [kg/m^3], > 0.

    Returns
    -------
    float
        Velocity [m/s]; 0 when ``p_down >= p_up``.

    Examples
    --------
    >>> graefe_velocity(1.015e5, 1.0e5, 1.2)
    50.0
    """
    dp = p_up - p_down
    if dp <= 0.0:
        return 0.0
    return math.sqrt(2.0 * dp / rho_up)


@njit(cache=True)
def graefe_mass_flow(p_up: float, p_down: float, rho_up: float, area: float,
                     FLC: float = 1.0, FAC: float = 1.0) -> float:
    r"""Graefe–Krummheuer–Siejak fabric leakage, as OpenRadioss implements it (Iform_ps = 3) [kg/s].

    .. math:: \dot m = \rho_e\, u\, A_{eff} = FLC \cdot FAC \cdot A\,\sqrt{2 \rho_e \max(p_e - p_{down}, 0)}

    Parameters
    ----------
    p_up, p_down : float
        Upstream and downstream absolute pressures [Pa].
    rho_up : float
        Upstream (cavity) gas density [kg/m^3].
    area : float
        Fabric area A [m^2], >= 0.
    FLC, FAC : float
        Fabric leakage and area coefficients [-] (LS-DYNA *MAT_FABRIC FLC, FAC; Radioss /LEAK/MAT LC, AC). Their
        product is the effective open fraction of the fabric.

    Returns
    -------
    float
        Outflow [kg/s]; 0 when ``p_down >= p_up`` (the caller swaps the cavities for two-way flow).

    Notes
    -----
    Incompressible Bernoulli outflow through the effective porous area, evaluated at the cavity density. It is
    continuous at Δp = 0 but behaves like sqrt(Δp) there (infinite slope), like the orifice law.

    Source status: the form is read from OpenRadioss ``airbagb1.F`` (branch IFVENT == 3, labelled "GRAEFE POROSITY
    FORMULATION" in ``hm_read_monvol_type5.F``); there the stability cap ``VMAX`` on u is a time-step device and
    is not reproduced. LS-DYNA *MAT_FABRIC FVOPT = 3/4 cites "Graefe, Krummheuer and Siejak [1990]" for its
    leakage formulas, but the LS-DYNA equation and the original paper were not available, so agreement with
    LS-DYNA is not confirmed. OpenRadioss /LEAK/MAT Ileakage = 2 is not this law: it is the effective-area factor
    LC(t)·AC(P) that multiplies whichever velocity law the surface uses.

    References
    ----------
    Graefe, Krummheuer and Siejak (1990), as cited by LS-DYNA *MAT_FABRIC FVOPT = 3/4 (not read).
    OpenRadioss engine/source/airbag/airbagb1.F.

    Examples
    --------
    Δp = 1500 Pa, ρ = 1.2 kg/m^3: u = 50 m/s, ρu = 60 kg/(s m^2); 0.01 m^2 with FLC·FAC = 0.1:

    >>> round(graefe_mass_flow(1.015e5, 1.0e5, 1.2, 0.01, FLC=0.5, FAC=0.2), 12)
    0.06
    """
    dp = p_up - p_down
    if dp <= 0.0 or area <= 0.0:
        return 0.0
    return FLC * FAC * area * math.sqrt(2.0 * rho_up * dp)


@dataclass(frozen=True)
class GraefeLaw:
    """Graefe–Krummheuer–Siejak porosity (OpenRadioss Iform_ps = 3): :func:`graefe_mass_flow`."""

    flc: float = 1.0
    fac: float = 1.0
    pneumatic = False
    prescribed = False

    def mass_flow(self, up, p_down, area, t):
        return graefe_mass_flow(up.p, p_down, up.rho, area, self.flc, self.fac)


class GraefeFloat(IntEnum):
    FLC = 0
    FAC = 1


@njit(LAW_SIGNATURE, cache=True)
def graefe_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The engine's Graefe flow from side u [kg/s]: :func:`graefe_mass_flow`."""
    return graefe_mass_flow(side(st, amb, u, StateColumn.P), p_down, side(st, amb, u, StateColumn.RHO), area,
                            lf[GraefeFloat.FLC], lf[GraefeFloat.FAC])


LAW = LawSpec(names=("graefe",), law=GraefeLaw, kernel=graefe_kernel,
              keys=(LawKey("flc", "graefe: leakage coefficient FLC", default=1.0, check="nonnegative"),
                    LawKey("fac", "graefe: area coefficient FAC", default=1.0, check="nonnegative")),
              build=lambda name, values, read_table: GraefeLaw(values["flc"], values["fac"]),
              lower=lambda law, tables: ((float(law.flc), float(law.fac)), ()))
