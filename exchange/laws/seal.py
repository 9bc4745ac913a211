r"""A seal that leaks by contact pressure, loaded by the dynamic body: the law object, its kernel and scene keys.

The seal's mass flow is the compressible Reynolds film through its interface (docs/seals.md) with the film
conductance K(s) of the flange's displacement s tabulated once at load (:mod:`exchange.seal.conductance`):

.. math:: \dot m = \frac{K(s)\,(p_{up}^2 - p_{down}^2) + 12\, c\, K_2(s)\,(p_{up} - p_{down})}{24\,\mu(T) R T}

(:func:`exchange.seal.kernels.seal_mass_flow`; c = μ·√(πRT/2) the slip constant λ·p and K_2 the conductance with
k = h², only with slip). T, R and p_up are the upstream side's; μ(T) is a table of the gas's viscosity built once
(CoolProp or Sutherland). The engine writes s into the law's floats before every evaluation
(:func:`exchange.engine.gas.states`, ``ExchangeInt.BODY_LOAD``), and stops at the closure displacement s* (K = 0 on
its sealed side: the ring closed all around leaks exactly 0) and at the ends of the tabulated range (beyond them K
is held): they are the law's kinks in the body's displacement.

Limits: laminar, isothermal film at the upstream temperature, no inertia (docs/seals.md).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum

import numpy as np
from numba import njit

from exchange.engine.layout import LAW_LOAD, LAW_SIGNATURE, KinkVariable, StateColumn, TableColumn, side
from exchange.engine.tables import table_value
from exchange.seal.kernels import curve_conductance, seal_mass_flow
from exchange.seal.spec import SealSetup

from .spec import LawKey, LawSpec

__all__ = ["SealLaw", "SealSetup", "seal_kernel", "LAW", "GAP_LAWS", "VISCOSITY_MODELS"]

GAP_LAWS = ("exponential", "persson", "table", "pvrc", "none")
VISCOSITY_MODELS = ("sutherland", "coolprop")


@dataclass(frozen=True, eq=False)
class SealLaw:
    """A seal on the dynamic body's displacement: the conductance curve ``curve``
    (:class:`exchange.seal.conductance.ConductanceCurve`, None until the seal surface and the flange are known),
    ``slip_values`` K_2 at its knots [m²] (None: no slip), the viscosity table (``temperatures`` [K],
    ``viscosities`` [Pa s]) and ``load`` [m]: the displacement Python's :meth:`mass_flow` evaluates at (the engine
    writes the body's own)."""

    setup: SealSetup
    curve: object = None
    slip_values: object = None
    temperatures: tuple = ()
    viscosities: tuple = ()
    load: float = 0.0
    pneumatic = False
    prescribed = False
    body_load = True

    def viscosity(self, T):
        """μ(T) [Pa s] from the table (linear, held beyond its ends)."""
        return float(np.interp(T, self.temperatures, self.viscosities))

    def conductance(self, s):
        """(K [m³], K_2 [m²]) at displacement ``s`` [m]."""
        c = self.curve
        k = curve_conductance(float(s), c.knots, c.values, c.slopes, float(c.closure), float(c.direction))
        k2 = 0.0 if self.slip_values is None or k == 0.0 else float(np.interp(s, c.knots, self.slip_values))
        return k, k2

    def mass_flow(self, up, p_down, area, t):
        """Mass flow [kg/s] from ``up`` into ``p_down`` [Pa] at displacement :attr:`load` (``area`` unused)."""
        if self.curve is None:
            raise ValueError("a seal's conductance curve is built with its flange (cases.model.build_seal)")
        k, k2 = self.conductance(self.load)
        if k == 0.0 or up.p <= p_down:
            return 0.0
        mu = self.viscosity(up.T)
        slip = mu * math.sqrt(0.5 * math.pi * up.R * up.T) if self.slip_values is not None else 0.0
        return seal_mass_flow(k, k2, up.p, p_down, up.T, mu, up.R, slip)


class SealFloat(IntEnum):
    LOAD = LAW_LOAD  # the body's displacement s [m], written by the engine
    CLOSURE = 1  # s* [m] (±inf: never closes)
    DIRECTION = 2  # +1: sealed for s >= s*, −1: for s <= s*


class SealInt(IntEnum):
    CURVE = 0  # table: knots [m], K [m³]
    SLOPES = 1  # table: knots [m], dK/ds [m²]
    VISCOSITY = 2  # table: T [K], μ [Pa s]
    SLIP = 3  # table: knots [m], K_2 [m²]; −1: no slip


@njit(LAW_SIGNATURE, cache=True)
def seal_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The engine's seal flow from side u [kg/s], >= 0 (module formula)."""
    k = li[SealInt.CURVE]
    a, n = ti[k, TableColumn.START], ti[k, TableColumn.ROWS]
    b = ti[li[SealInt.SLOPES], TableColumn.START]
    s = lf[SealFloat.LOAD]
    K = curve_conductance(s, tx[a:a + n], ty[a:a + n], ty[b:b + n], lf[SealFloat.CLOSURE], lf[SealFloat.DIRECTION])
    p_up = side(st, amb, u, StateColumn.P)
    if K == 0.0 or p_up <= p_down:
        return 0.0
    T, R = side(st, amb, u, StateColumn.T), side(st, amb, u, StateColumn.R)
    mu = table_value(tx, ty, ti, li[SealInt.VISCOSITY], T)
    K2, slip = 0.0, 0.0
    if li[SealInt.SLIP] >= 0:
        K2 = table_value(tx, ty, ti, li[SealInt.SLIP], s)
        slip = mu * math.sqrt(0.5 * math.pi * R * T)
    return seal_mass_flow(K, K2, p_up, p_down, T, mu, R, slip)


def _lower(law, tables):
    c = law.curve
    if c is None:
        raise ValueError("a seal needs its flange: a [[contact]] whose seat is the seal exchange")
    curve = tables.add_arrays(c.knots, c.values)
    slopes = tables.add_arrays(c.knots, c.slopes)
    viscosity = tables.add_arrays(law.temperatures, law.viscosities)
    slip = -1
    if law.slip_values is not None:  # K_2 is continuous: one row per distinct knot (a join's twin dropped)
        knots, first = np.unique(c.knots, return_index=True)
        slip = tables.add_arrays(knots, np.asarray(law.slip_values)[first])
    return (float(law.load), float(c.closure), float(c.direction)), (curve, slopes, viscosity, slip)


def _kinks(law):
    """Row 0: the closure displacement s* (the ring closes or re-opens); rows 1 and 2: the ends of the tabulated
    range (KinkVariable.BODY_DISPLACEMENT), each once."""
    c = law.curve
    if c is None:
        return ()
    out = []
    if math.isfinite(c.closure) and c.knots[0] <= c.closure <= c.knots[-1]:
        out.append((KinkVariable.BODY_DISPLACEMENT, float(c.closure), 0))
    for row, x in ((1, law.setup.s_min), (2, law.setup.s_max)):
        if x != c.closure:
            out.append((KinkVariable.BODY_DISPLACEMENT, float(x), row))
    return tuple(out)


def _build(name, values, read_table):
    from exchange.seal.setup import seal_setup

    return SealLaw(seal_setup(values, read_table))


KEYS = (
    LawKey("gap_law", "seal: the channel height under contact pressure p", default="exponential",
           choices=GAP_LAWS),
    LawKey("seal_pressurised_edge", "seal: the edge at the upstream pressure, 'inner' or 'outer' (the boundary "
           "loops of a ring) or a CSV file of node indices of the seal surface", default="inner"),
    LawKey("seal_outer_edge", "seal: the edge at the downstream pressure ('inner', 'outer' or a CSV of node "
           "indices)", default="outer"),
    LawKey("gap_h0", "seal, exponential: h = h0·exp(−p/p0) − u_c", "m", default=0.0, check="nonnegative"),
    LawKey("gap_p0", "seal, exponential: pressure scale p0", "Pa", default=0.0, check="nonnegative"),
    LawKey("gap_u0", "seal, persson: u = u0·ln(p*/p) − u_c", "m", default=0.0, check="nonnegative"),
    LawKey("gap_p_star", "seal, persson: p*", "Pa", default=0.0, check="nonnegative"),
    LawKey("gap_percolation", "seal, exponential and persson: percolation gap u_c where the channel closes",
           "m", default=0.0, check="nonnegative"),
    LawKey("gap_max", "seal, persson and pvrc: cap of the channel height at low pressure (0: none)", "m",
           default=0.0, check="nonnegative"),
    LawKey("gap_table", "seal, table: CSV (contact pressure [Pa], channel height [m]), non-increasing",
           kind="file", default=""),
    LawKey("pvrc_gb", "seal, pvrc: gasket constant G_b", "Pa", default=0.0, check="nonnegative"),
    LawKey("pvrc_a", "seal, pvrc: gasket constant a", default=0.0, check="nonnegative"),
    LawKey("pvrc_gs", "seal, pvrc: gasket constant G_s", "Pa", default=0.0, check="nonnegative"),
    LawKey("pvrc_h1", "seal, pvrc: channel height at tightness 1", "m", default=0.0, check="nonnegative"),
    LawKey("seal_loaded_to", "seal: the flange displacement reached at bolt-up before the run; the gap law "
           "unloads from the contact pressure there (pvrc hysteresis); 'nan': loading curve", "m",
           default=float("nan")),
    LawKey("seal_viscosity", "seal: gas viscosity μ (0: from seal_viscosity_model at the film temperature)",
           "Pa s", default=0.0, check="nonnegative"),
    LawKey("seal_viscosity_model", "seal: μ(T) from 'sutherland' (Air, Nitrogen) or 'coolprop' (any CoolProp "
           "fluid)", default="sutherland", choices=VISCOSITY_MODELS),
    LawKey("seal_gas", "seal: the gas for μ(T) (a CoolProp name; Sutherland knows Air and Nitrogen)",
           default="Nitrogen"),
    LawKey("seal_slip", "seal: first-order slip correction (Knudsen number of micron gaps)", default=False),
    LawKey("seal_displacement_min", "seal: the lowest flange displacement tabulated (beyond: K held, an event)",
           "m", default=0.0, check="finite"),
    LawKey("seal_displacement_max", "seal: the highest flange displacement tabulated", "m", default=0.0,
           check="finite"),
    LawKey("seal_rtol", "seal: relative tolerance of the tabulated conductance", default=1e-4, check="positive"),
)

LAW = LawSpec(names=("seal",), law=SealLaw, kernel=seal_kernel, keys=KEYS,
              required={"seal": ("seal_displacement_min", "seal_displacement_max")},
              build=_build, lower=_lower, kinks=_kinks, lowers=lambda law: law.curve is not None)
