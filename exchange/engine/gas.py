"""Each cavity's state at (t, y) on the engine: its volume, then its gas (an ideal-gas mixture's temperature from its
internal energy, a hydraulic fluid's pressure from its density, a real-gas cavity's state from CoolProp in Python)
and the flow-law view the exchanges read (``M.state``, columns :class:`~exchange.engine.layout.StateColumn`)."""
from __future__ import annotations

import math

from numba import njit

from cavity.gas_rows import mixture_row, range_of, row_cp, row_enthalpy, temperature
from cavity.hydraulic import hydraulic_pressure
from cavity.tolerances import R_UNIVERSAL as R_U

from .arrays import copy_into
from .hosted import hosted_state
from .layout import LAW_LOAD, BodyColumn, CavityFloat, CavityInt, Energy, ExchangeInt, Fluid, StateColumn, VolumeKind
from .tables import spline_piece_value, spline_value, table_slope, table_value

__all__ = ["states", "volume_of", "eos_volume"]

P, T, RHO, R, GAMMA, H, V, DV, MASS, FR = (StateColumn.P, StateColumn.T, StateColumn.RHO, StateColumn.R,
                                          StateColumn.GAMMA, StateColumn.H, StateColumn.V, StateColumn.DV,
                                          StateColumn.MASS, StateColumn.FRACTIONS)


@njit(cache=True)
def volume_of(M, i, t, y):
    """(V, dV/dt) of cavity i's geometric volume [m^3, m^3/s]: fixed, a table of time, a scaled mesh (s(t)³·V_mesh),
    or a volume wrapped around prescribed bodies (a cubic spline of time) or around the dynamic body (of its
    displacement, on the piece the segment holds: dV/dt = dV/ds·v)."""
    ci, cf, tx, ty, ti = M.cavity_int, M.cavity_float, M.table_x, M.table_y, M.table_index
    kind = ci[i, CavityInt.VOLUME]
    if kind == VolumeKind.FIXED:
        return cf[i, CavityFloat.VOLUME], 0.0
    k = ci[i, CavityInt.VOLUME_TABLE]
    if kind == VolumeKind.SPLINE_OF_TIME:
        return spline_value(tx, ty, ti, k, t)
    if kind == VolumeKind.SPLINE_OF_BODY:
        b = ci[i, CavityInt.BODY_OFFSET]
        value, slope = spline_piece_value(tx, ty, ti, k, y[b], ci[i, CavityInt.PIECE])
        return value, slope * y[b + 1]
    if kind == VolumeKind.TABLE:
        return table_value(tx, ty, ti, k, t), table_slope(tx, ty, ti, k, t)
    s = table_value(tx, ty, ti, k, t)
    mesh = cf[i, CavityFloat.VOLUME]
    return s * s * s * mesh, 3.0 * s * s * table_slope(tx, ty, ti, k, t) * mesh


@njit(cache=True)
def eos_volume(M, i, t, y):
    """(V, V_eos, dV/dt) of cavity i [m^3, m^3, m^3/s]: its geometric volume plus the added volume, the volume of the
    equation of state (:func:`cavity.volume.effective_volume`: at least the minimum volume), and the rate of change,
    none while held at the minimum."""
    Vg, rate = volume_of(M, i, t, y)
    Vt = Vg + M.cavity_float[i, CavityFloat.ADDED_VOLUME]
    floor = M.cavity_float[i, CavityFloat.MINIMUM_VOLUME]
    if Vt > floor:
        return Vt, Vt, rate
    return Vt, floor, 0.0


@njit(cache=True)
def _liquid_state(M, i, t, y):
    """Row i of the state scratch of a hydraulic cavity (:class:`cavity.hydraulic.HydraulicCavity`; its flow-law
    view: R and γ NaN, h 0, one "species"): mass, volume, T(t) from its table, ρ_ref(T) = ρ_0·exp(−α(T − T_0)),
    p from :func:`cavity.hydraulic.hydraulic_pressure` (−inf when empty)."""
    ci, cf, st = M.cavity_int, M.cavity_float, M.state
    k = ci[i, CavityInt.OFFSET]
    m = y[k] if y[k] > 0.0 else 0.0
    Vt, V_eos, rate = eos_volume(M, i, t, y)
    Tl = table_value(M.table_x, M.table_y, M.table_index, ci[i, CavityInt.TEMPERATURE_TABLE], t)
    rho_ref = cf[i, CavityFloat.REFERENCE_DENSITY] * math.exp(
        -cf[i, CavityFloat.THERMAL_EXPANSION] * (Tl - cf[i, CavityFloat.REFERENCE_TEMPERATURE]))
    rho = m / V_eos
    p = hydraulic_pressure(rho, rho_ref, cf[i, CavityFloat.BULK_MODULUS], cf[i, CavityFloat.REFERENCE_PRESSURE]) \
        if rho > 0 else -math.inf
    st[i, P], st[i, T], st[i, RHO], st[i, R], st[i, GAMMA], st[i, H] = p, Tl, rho, math.nan, math.nan, 0.0
    st[i, V], st[i, DV], st[i, MASS] = Vt, rate, m
    st[i, FR:] = 0.0
    st[i, FR] = 1.0


@njit(cache=True)
def _gas_state(M, i, t, y):
    """Row i of the state scratch of an ideal-gas cavity: T from U by :func:`cavity.gas_rows.temperature` (or its
    fixed temperature when isothermal), p = nR_uT/V, and its flow-law view; False when the temperature solve
    failed (the first guess is then used)."""
    ci, st, n, row, guess = M.cavity_int, M.state, M.moles, M.row, M.temperature_guess
    rows, breaks = M.gas_rows, M.gas_breaks
    k, ns = ci[i, CavityInt.OFFSET], ci[i, CavityInt.SPECIES]
    ok = True
    m, nmol = 0.0, 0.0
    for s in range(ns):
        ms = y[k + s] if y[k + s] > 0.0 else 0.0
        st[i, FR + s] = ms
        n[s] = ms / M.molar_masses[s]
        m += ms
        nmol += n[s]
    if ci[i, CavityInt.ENERGY] == Energy.ISOTHERMAL:
        Tg = M.cavity_float[i, CavityFloat.T0]
        mixture_row(rows, n, range_of(breaks, Tg), row)
    elif nmol > 0.0:
        Tg, ri = temperature(rows, breaks, M.gas_linear, n, nmol, y[k + ns], guess[i], row)
        if not Tg == Tg:
            ok = False
            Tg = guess[i]
        if range_of(breaks, Tg) != ri:
            mixture_row(rows, n, range_of(breaks, Tg), row)
    else:
        Tg = guess[i]
        mixture_row(rows, n, range_of(breaks, Tg), row)
    guess[i] = Tg
    Vt, V_eos, rate = eos_volume(M, i, t, y)
    st[i, P], st[i, T], st[i, V], st[i, DV], st[i, MASS] = nmol * R_U * Tg / V_eos, Tg, Vt, rate, m
    if m > 0.0:
        cp = row_cp(row, Tg)
        st[i, RHO] = m / Vt
        st[i, R] = nmol * R_U / m
        st[i, GAMMA] = cp / (cp - nmol * R_U)
        st[i, H] = row_enthalpy(row, Tg) / m
        for s in range(ns):
            st[i, FR + s] /= m
    else:  # an empty cavity
        st[i, RHO], st[i, R], st[i, GAMMA], st[i, H] = 0.0, 1.0, 1.4, 0.0
    return ok


@njit(cache=True)
def body_loads(M, y):
    """Write the dynamic body's displacement s [m] into column LAW_LOAD of the law floats of every exchange whose
    law reads it (``ExchangeInt.BODY_LOAD``: a seal loaded by the body)."""
    k = int(M.body[BodyColumn.OFFSET])
    if k < 0:
        return
    for j in range(M.exchange_int.shape[0]):
        if M.exchange_int[j, ExchangeInt.BODY_LOAD] == 1:
            M.law_float[j, LAW_LOAD] = y[k]


@njit(cache=True)
def states(M, t, y):
    """Fill ``M.state`` with every cavity's state at (t, y), and the law floats of the laws that read the dynamic
    body's displacement (:func:`body_loads`); False when a temperature solve failed."""
    body_loads(M, y)
    ok = True
    for i in range(M.cavity_int.shape[0]):
        fluid = M.cavity_int[i, CavityInt.FLUID]
        if fluid == Fluid.HYDRAULIC:
            _liquid_state(M, i, t, y)
        elif fluid == Fluid.REAL_GAS:  # its equation of state in Python (exchange.engine.hosted)
            Tr = hosted_state(M.cavity_int[i, CavityInt.HOST], i, t, y, M.state, M.temperature_guess[i])
            if Tr == Tr:
                M.temperature_guess[i] = Tr
            else:
                ok = False
        else:
            ok = _gas_state(M, i, t, y) and ok
    return ok


@njit(cache=True)
def reset_temperature_guesses(M):
    """Newton's first guesses of the cavities' temperatures: their initial temperatures (a run's or a read-back's
    start)."""
    copy_into(M.temperature_guess, M.cavity_float[:, CavityFloat.T0])
