"""The network's right-hand side and switch functions compiled with numba, on the flat arrays of
:mod:`exchange.compiled`.

The flow laws are not copied here: the orifice, fabric-leakage and Graefe laws of :mod:`exchange.orifice` and
:mod:`exchange.fabric` are numba functions, inlined into this right-hand side and called as they are by Python.
The network's bookkeeping (states from (m, U), areas, transfers, the ledger) is written here once; the tests pair
it with a naive assembly from the Python objects (``tests/engine_pairs.py``). Scalar arithmetic only, SI units throughout. The helpers are inlined (``inline="always"``): numba links
separately compiled functions without inlining them, and a call passing a few arrays costs ~80 ns, as much as the
law itself (measured: the whole right-hand side 0.54 → 0.37 µs).

Array layout (built by :func:`exchange.compiled.lower`):

- gas: ``rows`` (ns, nr, 7) per-mole coefficients (a, b, c, d, e, f, H offset) per species and range,
  ``breaks`` (nr − 1,) [K], ``linear`` (nr,) 1 where every species has a constant cp, ``M`` (ns,) [kg/mol];
- tables: ``tx``, ``ty`` concatenated; ``ti`` (ntab, 3): first row, rows, 1 for linear extrapolation;
- cavities ``ci`` (nc, 10) int: offset, energy (0 adiabatic, 1 isothermal or hydraulic, 2 heat loss, 3 a real-gas
  cavity's wall, hosted), volume kind
  (0 fixed, 1 table, 2 scaled mesh, 3 cubic spline of time, 4 of the dynamic body's displacement), volume table,
  ledger offset, species count, the body's offset, 1 hydraulic or 2 real gas (hosted: :mod:`exchange.hosted`),
  temperature table of a hydraulic cavity or host id of a real-gas one, the volume spline's held piece;
  ``cf`` (nc, 11): T0 [K], added volume [m^3], minimum volume [m^3], h_c·A [W/K], T_amb [K], fixed or mesh volume
  [m^3], and of a hydraulic cavity reference density [kg/m^3], bulk modulus [Pa], reference pressure [Pa],
  reference temperature [K], thermal expansion [1/K];
- inflators ``ii`` (ni, 5) int: cavity, mass-flow (or tank-pressure) table, temperature (or inflator-pressure)
  table, kind (0 mass and temperature tables, 1 tank test, 2 pressure and mass, 3 dual pressure), 1 once its
  temperature was held at a bound; ``if_`` (ni, 7 + ns): start [s], scale [-], gas mass [kg], mass fractions,
  tank volume [m^3], gas moles [mol], orifice area [m^2], Cd [-]; ``irows`` (ni, nr, 7) total coefficients of the
  inflator gas;
- exchanges ``ei`` (ne, 15) int: upstream, downstream (−1: ambient), two-way, amplitude table (−1: none),
  has a time window, has an equalised mode, has a pop pressure, law kind (:data:`exchange.compiled.LAW_KINDS`;
  7 a law called in Python, :mod:`exchange.hosted`),
  geometric area step table (−1: the constant ``ef[:, 0]``), scale table of that area (−1: none), area kind
  (0 constant, 1 steps of time, 2 steps of the dynamic body's displacement, 3 a surface on a vertex trajectory),
  law table (leakage table rows or flux amplitude, −1: none; a hosted law's host id), Cd table (−1: the constant
  ``ef[:, 1]``), Cd abscissa (0 upstream pressure, 1 time), DELTA LEAKAGE AREA (1); ``ef`` (ne, 11): area [m^2], Cd
  [-], open time [s], close time [s], pop pressure [Pa], hold time [s], law parameters (fabric: open fraction;
  Graefe: FLC, FAC; linear resistance: conductance; leakage table: volume flag, held-last flag; flux: flux per area,
  volume flag; bulk viscosity: c_v, c_h; a hosted law: 1 if prescribed), switch scale, area at activation,
  close pressure [Pa] of the downstream cavity (0: none);
  ``eq`` (ne,) int: 1 while held closed (equalised, :data:`exchange.equalised.EQUALISED_BELOW`); ``op`` (ne,)
  int: 0 while a pop vent has not popped (else 1); ``hold`` (ne,): the time its hold started [s] (NaN: not
  holding);
- ambient ``amb`` (6 + ns,): p [Pa], T [K], ρ [kg/m^3], R [J/(kg K)], γ [-], h [J/kg], mass fractions;
- state scratch ``st`` (nc, 9 + ns): p, T, ρ, R, γ, h, V, dV/dt, mass, mass fractions (filled by
  :func:`states`).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from blockage.moving_area import moving_leak_area
from cavity.gas_rows import mixture_row, range_of, row_cp, row_enthalpy, temperature

from .activation import activated_area
from .compiled_hosted import add_wall_heat, choke_ratio_of, hosted_flow, hosted_state, inflow_scratch
from .compiled_sources import inflator_flow, law_flow, liquid_state, prescribed_flow
from .compiled_tables import (DV, FR, GAM, H, MASS, RG, RHO, TT, R_U, P, V, side, step_value,
                              table_value, eos_volume)
from .equalised import EQUALISED_BELOW, RELEASED_ABOVE
from .orifice import LINEAR_BELOW

@njit(cache=True, inline="always")
def states(rows, breaks, linear, M, tx, ty, ti, ci, cf, t, y, T_guess, st, n, row):
    """Fill ``st`` with every cavity's state at (t, y) and its flow-law view (ρ, R, γ, h, mass fractions).

    Returns False when a temperature solve failed. ``n`` (ns,) and ``row`` (7,) are scratch.
    """
    ok = True
    for i in range(ci.shape[0]):
        if ci[i, 7] == 1:
            liquid_state(ci, cf, tx, ty, ti, i, t, y, st)
            continue
        if ci[i, 7] == 2:  # a real-gas cavity: its equation of state in Python (exchange.hosted)
            T = hosted_state(ci[i, 8], i, t, y, st, T_guess[i])
            if T == T:
                T_guess[i] = T
            else:
                ok = False
            continue
        k, ns = ci[i, 0], ci[i, 5]
        m = 0.0
        nmol = 0.0
        for s in range(ns):
            ms = y[k + s] if y[k + s] > 0.0 else 0.0
            st[i, FR + s] = ms
            n[s] = ms / M[s]
            m += ms
            nmol += n[s]
        if ci[i, 1] == 1:
            T = cf[i, 0]
            ri = range_of(breaks, T)
            mixture_row(rows, n, ri, row)
        elif nmol > 0.0:
            T, ri = temperature(rows, breaks, linear, n, nmol, y[k + ns], T_guess[i], row)
            if not T == T:
                ok = False
                T = T_guess[i]
            if range_of(breaks, T) != ri:
                mixture_row(rows, n, range_of(breaks, T), row)
        else:
            T = T_guess[i]
            mixture_row(rows, n, range_of(breaks, T), row)
        T_guess[i] = T
        Vt, V_eos, rate = eos_volume(ci, cf, tx, ty, ti, i, t, y)
        p = nmol * R_U * T / V_eos
        st[i, P], st[i, TT], st[i, V], st[i, DV], st[i, MASS] = p, T, Vt, rate, m
        if m > 0.0:
            cp = row_cp(row, T)
            st[i, RHO] = m / Vt
            st[i, RG] = nmol * R_U / m
            st[i, GAM] = cp / (cp - nmol * R_U)
            st[i, H] = row_enthalpy(row, T) / m
            for s in range(ns):
                st[i, FR + s] /= m
        else:  # an empty cavity
            st[i, RHO], st[i, RG], st[i, GAM], st[i, H] = 0.0, 1.0, 1.4, 0.0
    return ok


@njit(cache=True, inline="always")
def exchange_area(ei, ef, op, iv, tx, ty, ti, j, t):
    """Flow area [m^2] of exchange j at t (:func:`exchange.activation.activated_area` of its base area):
    ``ei[j, 4]`` 1 with a time window ``ef[j, 2:4]``; ``op[j]`` 0 while a pop vent has not popped, 2 once closed at
    its close pressure (shut either way); ``ei[j, 3]``
    its amplitude table (−1: none); ``iv[j]`` the interval of the dynamic body's displacement that holds the area
    of an area kind 2 (``ei[j, 10]``); with DELTA LEAKAGE AREA (``ei[j, 14]``) the area at activation ``ef[j, 9]``
    (of one opened by time that follows the dynamic body, set at the first segment start past its open time:
    :func:`exchange.compiled_segment.begin_segment`)."""
    window = ei[j, 4] == 1
    a = table_value(tx, ty, ti, ei[j, 3], t) if ei[j, 3] >= 0 else 1.0
    return activated_area(base_area(ei, ef, iv, tx, ty, ti, j, t), t, ef[j, 2] if window else -np.inf,
                          ef[j, 3] if window else np.inf, op[j] != 1, a, ef[j, 9] if ei[j, 14] == 1 else 0.0)


@njit(cache=True, inline="always")
def base_area(ei, ef, iv, tx, ty, ti, j, t):
    """Leakage area of exchange j before activation rules [m^2] (:meth:`exchange.network.Network.base_area`):
    the constant ``ef[j, 0]``, a step table of time, or the area of the dynamic body's interval ``iv[j]``, times
    the square of its mesh scale; of a surface on a vertex trajectory (area kind 3) the step table gives the
    interval of the active set and the next table holds the pack of :func:`blockage.moving_area.moving_leak_area`
    (:meth:`cases.model.area_track.AreaTrack.area_in`)."""
    if ei[j, 10] == 3:
        k = ei[j, 8]
        s, n = ti[k + 1, 0], ti[k + 1, 1]
        return moving_leak_area(ty[s:s + n], int(step_value(tx, ty, ti, k, t)), t)
    if ei[j, 10] == 2:
        base = ty[ti[ei[j, 8], 0] + iv[j]]
    elif ei[j, 8] >= 0:
        base = step_value(tx, ty, ti, ei[j, 8], t)
    else:
        base = ef[j, 0]
    if ei[j, 9] >= 0:  # the leakage surface scales with its cavity mesh: area × s²
        sc = table_value(tx, ty, ti, ei[j, 9], t)
        base *= sc * sc
    return base


@njit(cache=True, inline="always")
def exchange_flow(ei, ef, eq, op, iv, tx, ty, ti, st, amb, j, t):
    """Signed mass flow [kg/s] of exchange j, up → down (:meth:`exchange.vent.Exchange.mass_flow`);
    0 while equalised or not popped."""
    area = exchange_area(ei, ef, op, iv, tx, ty, ti, j, t)
    if area <= 0.0 or eq[j] == 1:
        return 0.0
    if ei[j, 7] == 5:
        return prescribed_flow(ei, ef, tx, ty, ti, st, j, area, t)
    a, b = ei[j, 0], ei[j, 1]
    if ei[j, 7] == 7 and ef[j, 6] == 1.0:  # a prescribed law in Python: signed, from side a
        return hosted_flow(ei[j, 11], j, a, side(st, amb, b, P), area, t, st)
    pa, pb = side(st, amb, a, P), side(st, amb, b, P)
    if pa >= pb:
        return law_flow(ei, ef, tx, ty, ti, st, amb, j, a, pb, area, t)
    if b < 0 and ei[j, 2] == 0:
        return 0.0
    return -law_flow(ei, ef, tx, ty, ti, st, amb, j, b, pa, area, t)


@njit(cache=True, inline="always")
def _transfer(ci, dy, i, mdot, edot, st, amb, src):
    k, ns = ci[i, 0], ci[i, 5]
    for s in range(ns):
        dy[k + s] += mdot * (amb[6 + s] if src < 0 else st[src, FR + s])
    if ci[i, 1] != 1:
        dy[k + ns] += edot


@njit(cache=True)
def network_rhs(t, y, dy, seg_end, rows, breaks, linear, M, tx, ty, ti, ci, cf, ii, if_, irows, ei, ef, amb,
                ledger, T_guess, st, n, row, eq, op, iv):
    """d(unknowns)/dt into dy (layout: :mod:`exchange.network`); False if a temperature solve failed.

    ``seg_end``: inputs are read at its left limit when t reaches it (a step ending on a table break sees the
    piece it integrated over); ``ledger``: offset of the exchanges' ledger entries (a cavity's: ``ci[i, 4]``)."""
    if t >= seg_end:
        t = np.nextafter(seg_end, -np.inf)
    ok = states(rows, breaks, linear, M, tx, ty, ti, ci, cf, t, y, T_guess, st, n, row)
    dy[:] = 0.0
    inflow = inflow_scratch(ci)  # per cavity with a real-gas wall, the mass flowing in [kg/s]
    walls = inflow.size > 0
    for q in range(ii.shape[0]):
        i, start = ii[q, 0], if_[q, 0]
        if t < start:
            continue
        mdot, T_in = inflator_flow(ii, if_, irows, breaks, tx, ty, ti, q, t)
        if mdot != 0.0:
            r = irows[q, range_of(breaks, T_in)]
            hdot = mdot * row_enthalpy(r, T_in) / if_[q, 2]
            k, ns, c = ci[i, 0], ci[i, 5], ci[i, 4]
            for s in range(ns):
                dy[k + s] += mdot * if_[q, 3 + s]
            dy[c] += mdot
            dy[c + 1] += hdot
            if ci[i, 1] != 1:
                dy[k + ns] += hdot
            if walls:
                inflow[i] += mdot
    for i in range(ci.shape[0]):
        if ci[i, 1] != 1:
            work = st[i, P] * st[i, DV]
            heat = cf[i, 3] * (st[i, TT] - cf[i, 4]) if ci[i, 1] == 2 else 0.0
            k, ns, c = ci[i, 0], ci[i, 5], ci[i, 4]
            dy[k + ns] -= work + heat
            dy[c + 2] += work
            dy[c + 3] += heat
    for j in range(ei.shape[0]):
        mdot = exchange_flow(ei, ef, eq, op, iv, tx, ty, ti, st, amb, j, t)
        if mdot == 0.0:
            continue
        if not mdot == mdot:  # a hosted law failed
            ok = False
            continue
        if walls:
            into = ei[j, 1] if mdot > 0.0 else ei[j, 0]
            if into >= 0:
                inflow[into] += abs(mdot)
        src = ei[j, 0] if mdot >= 0.0 else ei[j, 1]
        edot = mdot * side(st, amb, src, H)
        _transfer(ci, dy, ei[j, 0], -mdot, -edot, st, amb, src)
        if ei[j, 1] >= 0:
            _transfer(ci, dy, ei[j, 1], mdot, edot, st, amb, src)
        e = ledger + 2 * j
        dy[e] += mdot
        dy[e + 1] += edot
    if walls:
        ok = add_wall_heat(ci, inflow, dy) and ok
    return ok


@njit(cache=True)
def switch_value(kind, j, ci, ei, ef, st, amb):
    """Switch function of exchange j on the states in ``st`` [-]: kind 0 choking (p_low − r*·p_high)/p_high, where
    the orifice law's second derivative jumps; kind 1 the one-way reversal Δp/p_max; kinds 2 and 3 the equalise and
    release levels of |Δp|/p_max (:mod:`exchange.equalised`); kinds 4 (pop) and 5 (pop-drop) (Δp − p_pop)/max(p_pop,
    p_b); kind 7 the orifice law's C¹ join at |Δp|/p = LINEAR_BELOW; kind 17 (p_b − p_close)/p_close, the
    downstream cavity reaching the exchange's close pressure. The pop-hold switch (kind 6) depends on time
    only: :func:`exchange.compiled_kernels.switches`."""
    a, b = ei[j, 0], ei[j, 1]
    pa, pb = st[a, P], side(st, amb, b, P)
    if kind == 17:
        return (pb - ef[j, 10]) / ef[j, 10]
    if kind == 1:
        return (pa - pb) / max(pa, pb)
    if kind == 7:
        return abs(pa - pb) / max(pa, pb) / LINEAR_BELOW - 1.0
    if kind == 2 or kind == 3:
        return abs(pa - pb) / max(pa, pb) / (EQUALISED_BELOW if kind == 2 else RELEASED_ABOVE) - 1.0
    if kind == 4 or kind == 5:
        pop = ef[j, 4]
        return (pa - pb - pop) / max(pop, pb)
    if pa >= pb:
        return (pb - choke_ratio_of(ci, st, amb, a) * pa) / pa
    return (pa - choke_ratio_of(ci, st, amb, b) * pb) / pb
