r"""Loading and unloading gap laws after the PVRC gasket tightness constants G_b, a, G_s.

The Pressure Vessel Research Council's room-temperature tightness test (ROTT) describes a gasket by the
tightness parameter T_p, a dimensionless inverse leak rate,

.. math:: T_p = \frac{P}{P^*}\left(\frac{L^*_{RM}}{L_{RM}}\right)^{1/2},

with P the gauge pressure, P* = 1 atm (101325 Pa), L_RM the helium mass leak rate per unit gasket outside diameter
and L*_RM = 1 mg/s for a 150 mm gasket (T_p = 1 is 1 mg/s of helium through a 150 mm gasket at 1 atm). On first
loading the gasket stress S follows S = G_b·T_p^a (part A of the test); unloading from the largest stress S_max
(tightness T_pmax) follows the straight line in log S–log T_p through (T_pmax, S_max) and (1, G_s) (part B):
S = G_s·T_p^{a_s}, a_s = ln(S_max/G_s)/ln(T_pmax). Sources: Payne, Bazergui & Leon, "New gasket factors — a
proposed procedure", ASME PVP 98-2 (1985); Bickford, *Gaskets and Gasketed Joints* (1998), ch. 4; the constants of
commercial gaskets are published by their makers (e.g. Flexitallic's gasket design manual).

**From tightness to a gap.** At a fixed pressure the leak rate scales as T_p^−2, and through a seal face of given
geometry the viscous leak scales as h³ (:mod:`exchange.seal.reynolds`), so the channel height scales as
T_p^(−2/3): h = h_1·T_p^(−2/3), where h_1 is the uniform gap that leaks the reference rate (T_p = 1) through the
tested gasket (:func:`pvrc_reference_gap`). The PVRC scaling L ∝ P² at fixed T_p and the film's L ∝ P1² − P2² agree
to (1 + 2·P_a/P), 7 % at the 2.8 MPa of the test; h_1 is taken in that high-pressure limit.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from exchange.seal.gap_laws import _positive, _shaped, as_pressure

__all__ = ["loading_tightness", "unloading_tightness", "tightness_gap", "pvrc_reference_gap", "pvrc_leak_rate", "PVRCGap",
           "P_STAR", "REFERENCE_LEAK_PER_DIAMETER"]

#: Reference gauge pressure of the tightness parameter, 1 atm [Pa].
P_STAR = 101325.0
#: Reference helium mass leak rate per unit outside diameter: 1 mg/s for a 150 mm gasket [kg/(s·m)].
REFERENCE_LEAK_PER_DIAMETER = 1e-6 / 0.150


def loading_tightness(S, Gb, a):
    r"""Tightness parameter on first loading [-].

    .. math:: T_p = (S/G_b)^{1/a}

    ``S`` gasket (contact) stress [Pa], ``Gb`` [Pa] the stress at T_p = 1, ``a`` [-] the slope (PVRC part A).

    >>> round(loading_tightness(4 * 6.0e6, 6.0e6, 0.5), 12)
    16.0
    """
    return _shaped((as_pressure(S) / Gb) ** (1.0 / a), S)


def unloading_tightness(S, S_max, Gb, a, Gs):
    r"""Tightness parameter on unloading from the largest stress ``S_max`` [-] (PVRC part B).

    .. math:: T_p = (S/G_s)^{1/a_s}, \quad a_s = \frac{\ln(S_{max}/G_s)}{\ln T_{pmax}},
              \quad T_{pmax} = (S_{max}/G_b)^{1/a}

    At S = S_max it equals :func:`loading_tightness`; below, it falls more slowly (the seated gasket keeps part of
    its tightness) down to T_p = 1 at S = G_s. Where S >= S_max, or the gasket was never loaded beyond T_p = 1 or
    beyond G_s, the loading curve holds.

    >>> Gb, a, Gs = 6.0e6, 0.5, 1e5
    >>> round(unloading_tightness(24e6, 24e6, Gb, a, Gs), 9), round(unloading_tightness(Gs, 24e6, Gb, a, Gs), 9)
    (16.0, 1.0)
    >>> unloading_tightness(12e6, 24e6, Gb, a, Gs) > loading_tightness(12e6, Gb, a)
    True
    """
    S_arr, top = as_pressure(S), np.maximum(as_pressure(S_max), as_pressure(S))
    t_max = (top / Gb) ** (1.0 / a)
    hysteretic = (top > Gb) & (top > Gs) & (S_arr < top)
    with np.errstate(divide="ignore", invalid="ignore"):
        a_s = np.log(np.where(hysteretic, top / Gs, 2.0)) / np.log(np.where(hysteretic, t_max, 2.0))
        unloading = (S_arr / Gs) ** (1.0 / a_s)
    return _shaped(np.where(hysteretic, unloading, (S_arr / Gb) ** (1.0 / a)), S)


def tightness_gap(Tp, h1, h_max=math.inf):
    r"""Channel height of a gasket of tightness ``Tp`` [m]: h = min(h_1·T_p^(−2/3), h_max) (module notes).

    >>> tightness_gap(8.0, 4e-6), tightness_gap(0.0, 4e-6, h_max=1e-5)
    (1e-06, 1e-05)
    """
    t = np.asarray(Tp, dtype=float)
    with np.errstate(divide="ignore"):
        h = np.minimum(h1 * t ** (-2.0 / 3.0), h_max)
    return _shaped(h, Tp)


def pvrc_leak_rate(Tp, pressure, outer_diameter):
    r"""Helium mass leak rate [kg/s] of a gasket of tightness ``Tp`` at gauge ``pressure`` [Pa] (PVRC definition).

    .. math:: L = L^*_{RM}\, D_o \left(\frac{P}{P^*}\right)^2 T_p^{-2}

    >>> float(pvrc_leak_rate(1.0, 101325.0, 0.150))  # the reference: 1 mg/s
    1e-06
    """
    return REFERENCE_LEAK_PER_DIAMETER * outer_diameter * (pressure / P_STAR) ** 2 / np.asarray(Tp, float) ** 2


def pvrc_reference_gap(outer_diameter, inner_diameter, viscosity, gas_constant, temperature):
    r"""Uniform gap h_1 [m] through which a gasket ring leaks helium at T_p = 1 (high-pressure limit).

    .. math:: h_1^3 = \frac{24\,\mu R T\, L^*\,\ln(r_o/r_i)}{2\pi\,P^{*2}},
              \qquad L^* = L^*_{RM}\, D_o

    from the annulus film law ṁ = π h³ (p1² − p2²)/(12 μ R T ln(r_o/r_i)) with p1² − p2² → P² and the PVRC
    scaling L = L*·(P/P*)²/T_p². ``outer_diameter``, ``inner_diameter`` [m] of the tested ring, ``viscosity`` μ
    [Pa s] and ``gas_constant`` R [J/(kg K)] of helium, ``temperature`` T [K].

    >>> round(pvrc_reference_gap(0.150, 0.114, 1.96e-5, 2077.0, 293.15) * 1e6, 3)  # 150 mm x 114 mm ring
    10.681
    """
    leak = REFERENCE_LEAK_PER_DIAMETER * outer_diameter
    cube = 24.0 * viscosity * gas_constant * temperature * leak * math.log(outer_diameter / inner_diameter)
    return (cube / (2.0 * math.pi * P_STAR ** 2)) ** (1.0 / 3.0)


@dataclass(frozen=True)
class PVRCGap:
    """Hysteretic gap law of a gasket with PVRC constants ``Gb`` [Pa], ``a`` [-], ``Gs`` [Pa], reference gap
    ``h1`` [m] (:func:`pvrc_reference_gap`) and cap ``h_max`` [m] at vanishing stress.

    :meth:`gap` takes the contact pressure and, for unloading, the largest contact pressure the node has carried.

    >>> law = PVRCGap(Gb=6.0e6, a=0.5, Gs=1e5, h1=4e-6, h_max=20e-6)
    >>> law.gap(24e6), law.gap(12e6, 24e6) < law.gap(12e6)
    (1e-06, True)
    """

    Gb: float
    a: float
    Gs: float
    h1: float
    h_max: float = math.inf

    def __post_init__(self):
        for name in ("Gb", "a", "Gs", "h1"):
            _positive(name, getattr(self, name))
        _positive("h_max [m]", self.h_max, allow_inf=True)

    def gap(self, p, p_max=None):
        """Channel height [m] at contact pressure ``p`` [Pa], on the loading curve unless ``p_max`` [Pa] > p."""
        if p_max is None:
            tightness = loading_tightness(p, self.Gb, self.a)
        else:
            tightness = unloading_tightness(p, p_max, self.Gb, self.a, self.Gs)
        return tightness_gap(tightness, self.h1, self.h_max)

    def closing_pressure(self):
        """A power law never closes: inf."""
        return math.inf

    def breakpoints(self):
        """The stress where the cap h_max ends on loading [Pa] (none without a cap)."""
        if not math.isfinite(self.h_max):
            return ()
        return (self.Gb * (self.h1 / self.h_max) ** (1.5 * self.a),)
