r"""Gas viscosity μ(T) and mean free path for the seal film.

* :func:`coolprop_viscosity`: CoolProp's dilute-gas viscosity of a pure fluid or predefined mixture (the
  reference; CoolProp's transport correlations, e.g. Lemmon & Jacobsen, Int. J. Thermophys. 25 (2004) 21 for
  nitrogen, oxygen, argon and air).
* :func:`sutherland_viscosity`: Sutherland's law (Phil. Mag. 36 (1893) 507), cheap and compilable, with the
  constants of White, *Viscous Fluid Flow*, 3rd ed., Table 1-2 (:data:`SUTHERLAND`); within 1 % of CoolProp for
  air and nitrogen from 250 to 400 K (1.3 % for air at 500 K; tests/exchange/test_seal_film.py).
* :func:`mean_free_path`: λ = (μ/p)·√(πRT/2) (hard-sphere kinetic theory; e.g. Karniadakis, Beskok & Aluru,
  *Microflows and Nanoflows* (2005), sec. 1.2): 65 nm for air at 1 atm and 20 °C.
"""
from __future__ import annotations

import math

from numba import njit

__all__ = ["coolprop_viscosity", "sutherland_viscosity", "mean_free_path", "SUTHERLAND"]

#: Sutherland constants (μ_ref [Pa s], T_ref [K], S [K]) from White, Viscous Fluid Flow, Table 1-2.
SUTHERLAND = {"Air": (1.716e-5, 273.0, 111.0), "Nitrogen": (1.663e-5, 273.0, 107.0)}


def coolprop_viscosity(temperature, fluid, pressure=101325.0):
    """Viscosity of ``fluid`` (a CoolProp name, e.g. "Nitrogen", "Air", "Helium") at T [K] and p [Pa] [Pa s].

    >>> round(coolprop_viscosity(293.15, "Nitrogen") * 1e6, 2)
    17.58
    """
    from CoolProp.CoolProp import PropsSI

    return float(PropsSI("V", "T", float(temperature), "P", float(pressure), fluid))


@njit(cache=True)
def sutherland_viscosity(temperature, mu_ref, T_ref, S):
    r"""Sutherland's law [Pa s].

    .. math:: \mu = \mu_{ref}\left(\frac{T}{T_{ref}}\right)^{3/2}\frac{T_{ref} + S}{T + S}

    >>> round(sutherland_viscosity(293.15, *SUTHERLAND["Air"]) * 1e6, 3)
    18.142
    """
    return mu_ref * (temperature / T_ref) ** 1.5 * (T_ref + S) / (temperature + S)


def mean_free_path(pressure, temperature, viscosity, gas_constant):
    r"""Mean free path of a gas molecule [m].

    .. math:: \lambda = \frac{\mu}{p}\sqrt{\frac{\pi R T}{2}}

    >>> round(mean_free_path(101325.0, 293.15, 1.81e-5, 287.05) * 1e9, 1)
    65.0
    """
    return viscosity / pressure * math.sqrt(0.5 * math.pi * gas_constant * temperature)
