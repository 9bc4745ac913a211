"""What a lowered network's exchanges and inputs deliver, as numba kernels: the flow of each exchange law (with
its discharge coefficient), prescribed fluxes, inflator mass flows, the state of a hydraulic cavity, and the
switches at a table law's kinks (array layout: :mod:`exchange.compiled_rhs`).

The laws themselves are the numba kernels of their own modules, which Python calls too: nothing here
restates a law.
"""
from __future__ import annotations

import math

from numba import njit

from cavity.hydraulic import hydraulic_pressure
from cavity.gas_rows import rows_gamma
from cavity.inflator import tank_test_mass_flow
from cavity.inflator_orifice import dual_pressure_state, pressure_mass_state

from .bulk_viscosity import bulk_viscosity_mass_flow, linear_resistance_mass_flow
from .fabric import fabric_leakage_mass_flow, graefe_mass_flow
from .compiled_hosted import hosted_flow
from .compiled_tables import (DV, FR, GAM, H, MASS, RG, RHO, TT, R_U, P, V, side, table_slope, table_value,
                              eos_volume)
from .flux import mass_flux_mass_flow, volume_flux_mass_flow
from .leakage_table import tabulated_leakage_mass_flow
from .orifice import orifice_mass_flow


@njit(cache=True, inline="always")
def liquid_state(ci, cf, tx, ty, ti, i, t, y, st):
    """Row i of ``st`` for a hydraulic cavity (:class:`cavity.hydraulic.HydraulicCavity`; its flow-law view: R and
    γ NaN, h 0, one "species"): mass, volume, T(t) from table ``ci[i, 8]``, ρ_ref(T) = ρ_0·exp(−α(T − T_0)),
    p from :func:`cavity.hydraulic.hydraulic_pressure` (−inf when empty)."""
    k = ci[i, 0]
    m = y[k] if y[k] > 0.0 else 0.0
    Vt, V_eos, rate = eos_volume(ci, cf, tx, ty, ti, i, t, y)
    T = table_value(tx, ty, ti, ci[i, 8], t)
    rho_ref = cf[i, 6] * math.exp(-cf[i, 10] * (T - cf[i, 9]))
    rho = m / V_eos
    p = hydraulic_pressure(rho, rho_ref, cf[i, 7], cf[i, 8]) if rho > 0 else -math.inf
    st[i, P], st[i, TT], st[i, RHO], st[i, RG], st[i, GAM], st[i, H] = p, T, rho, math.nan, math.nan, 0.0
    st[i, V], st[i, DV], st[i, MASS] = Vt, rate, m
    st[i, FR:] = 0.0
    st[i, FR] = 1.0


@njit(cache=True, inline="always")
def law_cd(ei, ef, tx, ty, ti, st, amb, j, u, t):
    """Discharge coefficient [-] of exchange j's law with side u upstream (``_cd`` of :mod:`exchange.laws`): the
    constant ``ef[j, 1]``, or the table ``ei[j, 12]`` of the upstream pressure (``ei[j, 13]`` 0) or of time (1)."""
    k = ei[j, 12]
    if k < 0:
        return ef[j, 1]
    return table_value(tx, ty, ti, k, side(st, amb, u, P) if ei[j, 13] == 0 else t)


@njit(cache=True, inline="always")
def law_flow(ei, ef, tx, ty, ti, st, amb, j, u, p_down, area, t):
    """Mass flow [kg/s] of exchange j's pressure-driven law from side u (cavity, or ambient if < 0) into p_down
    [Pa], >= 0 (``law.mass_flow`` of :mod:`exchange.laws`; kinds in :data:`exchange.compiled.LAW_KINDS`)."""
    kind, p_up = ei[j, 7], side(st, amb, u, P)
    dp = p_up - p_down
    if kind == 7:  # a law in Python (exchange.hosted): its object, host ei[j, 11]
        return hosted_flow(ei[j, 11], j, u, p_down, area, t, st)
    if kind == 2:  # GraefeLaw
        return graefe_mass_flow(p_up, p_down, side(st, amb, u, RHO), area, ef[j, 6], ef[j, 7])
    if kind == 3:  # LinearResistanceLaw
        return linear_resistance_mass_flow(dp, ef[j, 6] * area) if dp > 0 else 0.0
    if kind == 4:  # LeakageTableLaw: rows in table ei[j, 11], volume flag ef[j, 6], held last value ef[j, 7]
        k = ei[j, 11]
        s, n = ti[k, 0], ti[k, 1]
        return tabulated_leakage_mass_flow(dp, area, side(st, amb, u, RHO), tx[s:s + n], ty[s:s + n],
                                           ef[j, 7] == 1.0, ef[j, 6] == 1.0)
    if kind == 6:  # BulkViscosityLaw
        return bulk_viscosity_mass_flow(dp, side(st, amb, u, RHO), area, ef[j, 6], ef[j, 7]) if dp > 0 else 0.0
    cd = law_cd(ei, ef, tx, ty, ti, st, amb, j, u, t)
    if kind == 1:  # FabricLeakageLaw
        return fabric_leakage_mass_flow(p_up, side(st, amb, u, TT), p_down, side(st, amb, u, RG),
                                        side(st, amb, u, GAM), area, cd, ef[j, 6])
    return orifice_mass_flow(p_up, side(st, amb, u, TT), p_down, side(st, amb, u, RG), side(st, amb, u, GAM), area,
                             cd)


@njit(cache=True, inline="always")
def prescribed_flow(ei, ef, tx, ty, ti, st, j, area, t):
    """Signed mass flow [kg/s] of exchange j's prescribed flux (:class:`exchange.laws.FluxLaw`, kind 5): flux
    ``ef[j, 6]`` per unit area, a volume flux when ``ef[j, 7]`` is 1 (times the first cavity's density), times the
    amplitude table ``ei[j, 11]`` of time (−1: none)."""
    a = table_value(tx, ty, ti, ei[j, 11], t) if ei[j, 11] >= 0 else 1.0
    if ef[j, 7] == 1.0:
        return volume_flux_mass_flow(ef[j, 6], area, st[ei[j, 0], RHO], a)
    return mass_flux_mass_flow(ef[j, 6], area, a)


@njit(cache=True, inline="always")
def inflator_flow(ii, if_, irows, breaks, tx, ty, ti, q, t):
    """(ṁ [kg/s], T_i [K]) of inflator q at t >= its start (``mass_flow`` and ``temperature`` of its class), by
    kind ``ii[q, 3]`` (:data:`exchange.compiled_inflators.INFLATOR_KINDS`): 0 the scaled mass-flow table and the
    temperature table (:class:`~cavity.inflator.MassTemperatureInflator`); 1 :func:`cavity.inflator.
    tank_test_mass_flow` on the slope of the tank-pressure table, none while it falls
    (:class:`~cavity.inflator.TankTestInflator`); 2 the mass-flow table and T_i of
    :func:`cavity.inflator_orifice.pressure_mass_state` (PRESSURE AND MASS); 3 both from
    :func:`cavity.inflator_orifice.dual_pressure_state` (DUAL PRESSURE); 4 the slope of the delivered-mass table
    of a real-gas tank (:class:`~cavity.inflator_realgas.RealGasTankTestInflator`, its tank states solved through
    HEOS at load) and the temperature table. A temperature held at a bound raises
    ``ii[q, 4]`` (warned after the run by :func:`exchange.compiled_inflators.warn_clamped`)."""
    x, scale, kind = t - if_[q, 0], if_[q, 1], ii[q, 3]
    c = if_.shape[1] - 4  # tank volume, gas moles, orifice area, Cd
    mass, moles = if_[q, 2], if_[q, c + 1]
    if kind == 0:
        return scale * table_value(tx, ty, ti, ii[q, 1], x), table_value(tx, ty, ti, ii[q, 2], x)
    if kind == 4:
        return scale * table_slope(tx, ty, ti, ii[q, 1], x), table_value(tx, ty, ti, ii[q, 2], x)
    if kind == 1:
        T = table_value(tx, ty, ti, ii[q, 2], x)
        rate = table_slope(tx, ty, ti, ii[q, 1], x)
        if rate <= 0.0:
            return 0.0, T
        g = rows_gamma(irows[q], breaks, moles, T)
        return scale * tank_test_mass_flow(if_[q, c], rate, g, moles * R_U / mass, T), T
    p = table_value(tx, ty, ti, ii[q, 2], x)
    if kind == 2:
        mdot = table_value(tx, ty, ti, ii[q, 1], x)
        T, clamped = pressure_mass_state(mdot, p, if_[q, c + 2], if_[q, c + 3], irows[q], breaks, moles, mass)
    else:
        mdot, T, clamped = dual_pressure_state(p, table_slope(tx, ty, ti, ii[q, 1], x), if_[q, c], if_[q, c + 2],
                                               if_[q, c + 3], irows[q], breaks, moles, mass)
    if clamped:
        ii[q, 4] = 1
    return scale * mdot, T


@njit(cache=True)
def kink_value(kind, code, ei, tx, ti, st, amb):
    """Switch at a law's kink (:func:`exchange.law_kinks.kink_switches`): row r of exchange j's Cd table of
    pressure (kind 11), (max(p_a, p_b) − x_r)/x_r, or of its leakage table (kind 12), (|p_a − p_b| − Δp_r)/Δp_r;
    ``code`` is j + ne·(r + 1) (:func:`exchange.lowered_switches.switch_table`)."""
    ne = ei.shape[0]
    j, r = code % ne, code // ne - 1
    pa, pb = st[ei[j, 0], P], side(st, amb, ei[j, 1], P)
    if kind == 11:
        x = tx[ti[ei[j, 12], 0] + r]
        return (max(pa, pb) - x) / x
    d = tx[ti[ei[j, 11], 0] + r]
    return (abs(pa - pb) - d) / d
