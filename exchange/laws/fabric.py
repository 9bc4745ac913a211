"""Leakage through porous fabric: Abaqus FABRIC LEAKAGE, Wang–Nefske, Graefe–Krummheuer–Siejak, Anagonye–Wang.

Every law here is one-directional: ``p_up`` is the pressure of the cavity the gas leaves, and the flow is 0 when
``p_down >= p_up``. A caller that allows two-way flow evaluates the law a second time with the cavities swapped.

Scalar pure functions on floats (``math``); the fabric-leakage law is compiled by numba (``@njit``), the one
implementation that both the engine's kernel (:func:`fabric_kernel`) and Python call. The Graefe law is
:mod:`exchange.laws.graefe`.

What each source confirms (see ``docs/exchange_laws.md``):

- Abaqus *FLUID EXCHANGE PROPERTY: TYPE=FABRIC LEAKAGE and TYPE=ORIFICE share the same data lines, a discharge
  coefficient tabulated against pressure and temperature. The analysis guide's fabric equation itself was not
  readable here, so :func:`fabric_leakage_mass_flow` is the orifice law applied to the fabric's open area.
- OpenRadioss ``engine/source/airbag/airbagb1.F``: a porous surface flows through an effective area
  ``A_eff = sum(SVTFAC * Area)`` with either the isenthalpic law (Iform_ps = 1, the Wang–Nefske orifice law) or
  the "GRAEFE POROSITY FORMULATION" (Iform_ps = 3, ``u = sqrt(2 (P - Pext) / rho)``). SVTFAC comes from /LEAK/MAT
  Ileakage: 1 = LC*AC, 2 = LC(t)*AC(P), 3 = LC(t)*AC(P - Pext), 4 = LC(A/A0)*AC(Pext/P), 5 = Autoliv,
  6 = Anagonye–Wang (``porfor6.F``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum

from numba import njit

from exchange.engine.layout import LAW_SIGNATURE, StateColumn, side

from .discharge import (CD_KEYS, cd_breakpoints, cd_of_values, cd_value, discharge_coefficient, lowered_cd,
                        lowers_cd, pressure_kinks)
from .orifice import LINEAR_BELOW, orifice_mass_flow
from .spec import LawKey, LawSpec

__all__ = [
    "anagonye_wang_area_factor",
    "anagonye_wang_mass_flow",
    "fabric_leakage_mass_flow",
    "wang_nefske_mass_flow",
    "FabricLeakageLaw",
    "fabric_kernel",
    "LAW",
]


@njit(cache=True)
def fabric_leakage_mass_flow(p_up: float, T_up: float, p_down: float, R: float, gamma: float,
                             area: float, Cd: float = 1.0, open_fraction: float = 1.0) -> float:
    r"""Mass flow through porous fabric treated as an orifice of the fabric's open area [kg/s].

    .. math::

        \dot m = \dot m_{orifice}(p_e, T_e, p_{down};\; A_{eff} = \phi A,\; C_d)

    with :math:`\dot m_{orifice}` the isentropic orifice law of :func:`exchange.laws.orifice.orifice_mass_flow`
    (choked below the critical pressure ratio).

    Parameters
    ----------
    p_up, T_up : float
        Upstream (cavity) absolute pressure [Pa] and temperature [K].
    p_down : float
        Downstream absolute pressure [Pa].
    R, gamma : float
        Specific gas constant [J/(kg K)] and ratio of specific heats [-] of the upstream gas.
    area : float
        Fabric (leakage surface) area A [m^2], >= 0.
    Cd : float
        Discharge coefficient [-]; see :mod:`exchange.discharge` for a tabulated one.
    open_fraction : float
        Open (porous) fraction φ of the fabric area [-], in [0, 1].

    Returns
    -------
    float
        Mass flow from upstream to downstream [kg/s]; 0 when ``p_down >= p_up`` (never reverses: the caller
        swaps the cavities for two-way flow).

    Notes
    -----
    Source status: the Abaqus keyword reference confirms that TYPE=FABRIC LEAKAGE takes the same data as
    TYPE=ORIFICE (a discharge coefficient as a function of pressure and temperature). The exact fabric equation of
    the Abaqus Analysis User's Guide could not be confirmed; this form (orifice law on the open area) is our
    assumption and is exact for a fabric whose pores behave as short orifices.

    References
    ----------
    Abaqus Keywords Reference, *FLUID EXCHANGE PROPERTY, "Data lines for TYPE=FABRIC LEAKAGE or TYPE=ORIFICE".

    Examples
    --------
    Choked air at 2 bar, 300 K through 1 cm^2 of fabric, half of it open, Cd = 0.6: 0.3 times the ideal
    orifice value 0.046671 kg/s.

    >>> round(fabric_leakage_mass_flow(2.0e5, 300.0, 1.0e5, 287.0, 1.4, 1.0e-4, Cd=0.6, open_fraction=0.5), 7)
    0.0140014
    """
    return orifice_mass_flow(p_up, T_up, p_down, R, gamma, area * open_fraction, Cd)


def wang_nefske_mass_flow(p_up: float, T_up: float, p_down: float, R: float, gamma: float,
                          C23: float, A23: float, CP23: float = 0.0, AP23: float = 0.0) -> float:
    r"""Wang–Nefske vent plus fabric-porosity outflow (LS-DYNA *AIRBAG_WANG_NEFSKE) [kg/s].

    .. math::

        \dot m = (C_{23} A_{23} + C'_{23} A'_{23})\,\frac{p_e}{\sqrt{R T_e}}\, q^{1/\gamma}
                 \sqrt{\frac{2\gamma}{\gamma-1}\left(1 - q^{(\gamma-1)/\gamma}\right)},
        \quad q = \max\!\left(\frac{p_{down}}{p_e}, \left(\frac{2}{\gamma+1}\right)^{\gamma/(\gamma-1)}\right)

    which is the isentropic orifice law with the effective area :math:`C_{23}A_{23} + C'_{23}A'_{23}`.

    Parameters
    ----------
    p_up, T_up : float
        Upstream (bag) absolute pressure [Pa] and temperature [K].
    p_down : float
        Downstream (ambient) absolute pressure [Pa].
    R, gamma : float
        Specific gas constant [J/(kg K)] and ratio of specific heats [-] of the bag gas.
    C23, A23 : float
        Vent orifice coefficient [-] and vent orifice area [m^2].
    CP23, AP23 : float
        Orifice coefficient [-] and area [m^2] for leakage through the fabric (porosity).

    Returns
    -------
    float
        Outflow [kg/s]; 0 when ``p_down >= p_up`` (the caller swaps the cavities for two-way flow).

    Notes
    -----
    The vent and the fabric share one velocity law, so only the sum of the products C·A matters. The same law is
    OpenRadioss's isenthalpic venting (Iform = 1): ``u = sqrt(2 gamma/(gamma-1) P/rho (1 - q**((gamma-1)/gamma)))``
    at density ``rho q**(1/gamma)``, whose product reduces to the formula above (checked in the tests). The
    LS-DYNA theory-manual equation itself was not available here; the field meanings come from the LS-DYNA keyword
    documentation (C23, A23, CP23, AP23; FVOPT = 1/2 "Wang–Nefske formulas for venting through an orifice").

    References
    ----------
    Wang, J. T. and Nefske, D. J., "A new CAL3D airbag inflation model", SAE 880654 (1988), as cited (not read).
    LS-DYNA Keyword User's Manual, *AIRBAG_WANG_NEFSKE and *MAT_FABRIC (FVOPT).
    OpenRadioss, engine/source/airbag/airbagb1.F (isentropic outflow, IFVENT = 1).

    Examples
    --------
    A 1 cm^2 vent with C23 = 0.7 plus 2 cm^2 of fabric with CP23 = 0.5 is 1.7 cm^2 of ideal orifice:
    1.7 x 0.046671 kg/s for choked air at 2 bar, 300 K.

    >>> round(wang_nefske_mass_flow(2.0e5, 300.0, 1.0e5, 287.0, 1.4, 0.7, 1.0e-4, 0.5, 2.0e-4), 6)
    0.079341
    """
    effective_area = C23 * A23 + CP23 * AP23
    return orifice_mass_flow(p_up, T_up, p_down, R, gamma, effective_area)


def anagonye_wang_area_factor(area_ratio: float, p_up: float, p_down: float,
                              X0: float, X1: float, X2: float, X3: float) -> float:
    r"""Anagonye–Wang effective leakage-area factor of a stretched fabric [-] (Radioss /LEAK/MAT Ileakage = 6).

    .. math::

        f = \frac{X_0 + X_2\, r_p}{r_s} + X_1 + X_3\, r_p,
        \quad r_s = \max(A / A_0, 1), \quad r_p = \min(p_{down} / p_e, 1)

    The effective leakage area is :math:`f\,A`.

    Parameters
    ----------
    area_ratio : float
        Current over initial fabric area A/A_0 [-].
    p_up, p_down : float
        Cavity and external absolute pressures [Pa]. r_p = 1 when ``p_up <= 0``.
    X0, X1, X2, X3 : float
        Fitted leakage coefficients [-].

    Notes
    -----
    Transcribed from OpenRadioss ``porfor6.F`` (PORFOR6/PORFORM6, "ANAGONYE WANG EFFECTIVE LEAKAGE AREA
    FORMULATION"), where r_s is the element area ratio (or 1 + ε_xx + ε_yy + ε_xx ε_yy from membrane strains).
    The original Anagonye & Wang paper was not available here. No clamping is applied (as in OpenRadioss).

    Examples
    --------
    >>> round(anagonye_wang_area_factor(1.25, 2.0e5, 1.0e5, 0.01, 0.002, 0.005, 0.001), 12)
    0.0125
    """
    r_s = max(area_ratio, 1.0)
    r_p = min(p_down / p_up, 1.0) if p_up > 0.0 else 1.0
    return (X0 + X2 * r_p) / r_s + X1 + X3 * r_p


def anagonye_wang_mass_flow(p_up: float, T_up: float, p_down: float, R: float, gamma: float,
                            area: float, area0: float, X0: float, X1: float, X2: float, X3: float) -> float:
    r"""Fabric leakage with the Anagonye–Wang area factor and the isenthalpic (orifice) velocity law [kg/s].

    .. math:: \dot m = \dot m_{orifice}\big(p_e, T_e, p_{down};\; A_{eff} = \max(f, 0)\, A,\; C_d = 1\big)

    with f from :func:`anagonye_wang_area_factor` and A/A_0 = ``area / area0``.

    Parameters
    ----------
    p_up, T_up, p_down, R, gamma : float
        As in :func:`exchange.laws.orifice.orifice_mass_flow` [Pa, K, Pa, J/(kg K), -].
    area, area0 : float
        Current and initial fabric area [m^2]; ``area0`` > 0.
    X0, X1, X2, X3 : float
        Anagonye–Wang coefficients [-].

    Returns
    -------
    float
        Outflow [kg/s]; 0 when ``p_down >= p_up`` (the caller swaps the cavities for two-way flow).

    Notes
    -----
    OpenRadioss pairs the area factor with the velocity law chosen on the porous surface (Iform_ps); this function
    uses the isenthalpic one (Iform_ps = 1). For the Graefe velocity law multiply :func:`graefe_mass_flow` by the
    factor instead. A negative factor (possible with negative fitted coefficients) is taken as 0 so the
    law never reverses.

    Examples
    --------
    Choked air at 2 bar, 300 K; 1 cm^2 of fabric stretched 25 %; f = 0.0125 at r_p = 0.5 (see above):

    >>> round(anagonye_wang_mass_flow(2.0e5, 300.0, 1.0e5, 287.0, 1.4, 1.25e-4, 1.0e-4,
    ...                               0.01, 0.002, 0.005, 0.001) / 0.0466711712, 6)
    0.015625
    """
    factor = anagonye_wang_area_factor(area / area0, p_up, p_down, X0, X1, X2, X3)
    return orifice_mass_flow(p_up, T_up, p_down, R, gamma, max(factor, 0.0) * area)


@dataclass(frozen=True)
class FabricLeakageLaw:
    """Abaqus FABRIC LEAKAGE: :func:`fabric_leakage_mass_flow` on the open fraction of the area."""

    discharge_coefficient: object = 1.0
    open_fraction: float = 1.0
    pneumatic = True
    prescribed = False
    join_below = LINEAR_BELOW  # the orifice law's C¹ join at |Δp|/p = LINEAR_BELOW: a switch there

    def mass_flow(self, up, p_down, area, t):
        cd = discharge_coefficient(self.discharge_coefficient, up.p, t)
        return fabric_leakage_mass_flow(up.p, up.T, p_down, up.R, up.gamma, area, cd, self.open_fraction)

    @property
    def breakpoints(self) -> tuple:
        return cd_breakpoints(self.discharge_coefficient)


class FabricFloat(IntEnum):
    """``law_float`` entries after the Cd's."""
    OPEN_FRACTION = 1


@njit(LAW_SIGNATURE, cache=True)
def fabric_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The engine's fabric leakage from side u [kg/s]: :func:`fabric_leakage_mass_flow`."""
    P, T, R, G = StateColumn.P, StateColumn.T, StateColumn.R, StateColumn.GAMMA
    return fabric_leakage_mass_flow(side(st, amb, u, P), side(st, amb, u, T), p_down, side(st, amb, u, R),
                                    side(st, amb, u, G), area, cd_value(lf, li, tx, ty, ti, st, amb, u, t),
                                    lf[FabricFloat.OPEN_FRACTION])


def _lower(law, tables) -> tuple:
    floats, ints = lowered_cd(law.discharge_coefficient, tables)
    return floats + (float(law.open_fraction),), ints


LAW = LawSpec(names=("fabric_leakage",), law=FabricLeakageLaw, kernel=fabric_kernel,
              keys=CD_KEYS + (LawKey("open_fraction", "fabric_leakage: open (porous) fraction of the area",
                                     default=1.0, check="fraction"),),
              build=lambda name, values, read_table: FabricLeakageLaw(cd_of_values(values), values["open_fraction"]),
              lower=_lower, kinks=lambda law: pressure_kinks(law.discharge_coefficient),
              lowers=lambda law: lowers_cd(law.discharge_coefficient))
