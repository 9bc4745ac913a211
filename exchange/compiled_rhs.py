"""The network's right-hand side and switch functions compiled with numba, on the flat arrays of
:mod:`exchange.compiled`.

The flow laws are not copied here: the orifice, fabric-leakage and Graefe laws of :mod:`exchange.orifice` and
:mod:`exchange.fabric` are numba functions, inlined into this right-hand side and called as they are by Python.
The network's bookkeeping (states from (m, U), areas, transfers) follows :meth:`exchange.network.Network.rhs`
(named in each docstring) so that both paths give the same derivatives to round-off; ``tests/test_compiled.py``
pairs them. Scalar arithmetic only, SI units throughout. The helpers are inlined (``inline="always"``): numba links
separately compiled functions without inlining them, and a call passing a few arrays costs ~80 ns, as much as the
law itself (measured: the whole right-hand side 0.54 → 0.37 µs).

Array layout (built by :func:`exchange.compiled.lower`):

- gas: ``rows`` (ns, nr, 7) per-mole coefficients (a, b, c, d, e, f, H offset) per species and range,
  ``breaks`` (nr − 1,) [K], ``linear`` (nr,) 1 where every species has a constant cp, ``M`` (ns,) [kg/mol];
- tables: ``tx``, ``ty`` concatenated; ``ti`` (ntab, 3): first row, rows, 1 for linear extrapolation;
- cavities ``ci`` (nc, 6) int: offset, energy (0 adiabatic, 1 isothermal, 2 heat loss), volume kind (0 fixed,
  1 table, 2 scaled mesh, 3 cubic spline of time), volume table, ledger offset, species count; ``cf`` (nc, 6): T0 [K], added volume
  [m^3], minimum volume [m^3], h_c·A [W/K], T_amb [K], fixed or mesh volume [m^3];
- inflators ``ii`` (ni, 3) int: cavity, mass-flow table, temperature table; ``if_`` (ni, 3 + ns): start [s],
  scale [-], gas mass [kg], mass fractions; ``irows`` (ni, nr, 7) total coefficients of the inflator gas;
- exchanges ``ei`` (ne, 10) int: upstream, downstream (−1: ambient), two-way, amplitude table (−1: none),
  has a time window, has an equalised mode, has a pop pressure, law kind (:data:`exchange.compiled.LAW_KINDS`),
  geometric area step table (−1: the constant ``ef[:, 0]``), scale table of that area (−1: none); ``ef`` (ne, 8): area [m^2], Cd [-], open time [s], close time [s], pop pressure [Pa], hold time
  [s], law parameters (fabric: open fraction; Graefe: FLC, FAC; linear resistance: conductance);
  ``eq`` (ne,) int: 1 while held closed (equalised, :data:`exchange.equalised.EQUALISED_BELOW`); ``op`` (ne,)
  int: 0 while a pop vent has not popped (else 1); ``hold`` (ne,): the time its hold started [s] (NaN: not
  holding);
- ambient ``amb`` (6 + ns,): p [Pa], T [K], ρ [kg/m^3], R [J/(kg K)], γ [-], h [J/kg], mass fractions;
- state scratch ``st`` (nc, 9 + ns): p, T, ρ, R, γ, h, V, dV/dt, mass, mass fractions (filled by
  :func:`states`).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .fabric import fabric_leakage_mass_flow, graefe_mass_flow
from .orifice import LINEAR_BELOW, critical_pressure_ratio, orifice_mass_flow
from .equalised import EQUALISED_BELOW, RELEASED_ABOVE

R_U = 8.314462618  # cavity.tolerances.R_UNIVERSAL
NEWTON_RTOL = 1e-10  # cavity.tolerances.TOL.newton_rtol
NEWTON_MAX = 60
T_FLOOR = 1.0

P, TT, RHO, RG, GAM, H, V, DV, MASS, FR = 0, 1, 2, 3, 4, 5, 6, 7, 8, 9  # columns of the state scratch


@njit(cache=True, inline="always")
def table_value(tx, ty, ti, k, x):
    """:meth:`cavity.tables.Table.__call__` of table k at x (piecewise linear, constant or linear ends)."""
    s, n, lin = ti[k, 0], ti[k, 1], ti[k, 2]
    if n == 1:
        return ty[s]
    if x <= tx[s] and lin == 0:
        return ty[s]
    if x >= tx[s + n - 1] and lin == 0:
        return ty[s + n - 1]
    i = np.searchsorted(tx[s:s + n], x, side="right") - 1
    i = min(max(i, 0), n - 2) + s
    w = (x - tx[i]) / (tx[i + 1] - tx[i])
    return ty[i] + w * (ty[i + 1] - ty[i])


@njit(cache=True, inline="always")
def table_slope(tx, ty, ti, k, x):
    """:meth:`cavity.tables.Table.slope` of table k at x (from the right at a breakpoint)."""
    s, n, lin = ti[k, 0], ti[k, 1], ti[k, 2]
    if n == 1 or (lin == 0 and (x < tx[s] or x >= tx[s + n - 1])):
        return 0.0
    i = np.searchsorted(tx[s:s + n], x, side="right") - 1
    i = min(max(i, 0), n - 2) + s
    return (ty[i + 1] - ty[i]) / (tx[i + 1] - tx[i])


@njit(cache=True, inline="always")
def step_value(tx, ty, ti, k, x):
    """Step table k at x: ty[i] for tx[i] <= x < tx[i+1] (right limit at a step; tx[0] is -inf)
    (:meth:`cases.area_track.AreaTrack.area_in` on a fixed surface)."""
    s, n = ti[k, 0], ti[k, 1]
    i = np.searchsorted(tx[s:s + n], x, side="right") - 1
    return ty[s + max(i, 0)]


@njit(cache=True, inline="always")
def spline_value(tx, ty, ti, k, x):
    """(value, slope) of the cubic spline k at x: knots in table k, coefficients (4 per piece, highest power
    first, as scipy's PPoly) in table k + 1; held at its ends, slope 0 outside (:class:`cases.geometry.
    WrappedVolume`)."""
    s, n, c = ti[k, 0], ti[k, 1], ti[k + 1, 0]
    inside = tx[s] <= x <= tx[s + n - 1]
    x = min(max(x, tx[s]), tx[s + n - 1])
    i = min(max(np.searchsorted(tx[s:s + n], x, side="right") - 1, 0), n - 2)
    d = x - tx[s + i]
    q = c + 4 * i
    value = ((ty[q] * d + ty[q + 1]) * d + ty[q + 2]) * d + ty[q + 3]
    slope = (3.0 * ty[q] * d + 2.0 * ty[q + 1]) * d + ty[q + 2] if inside else 0.0
    return value, slope


@njit(cache=True, inline="always")
def range_of(breaks, T):
    """Index of the temperature range holding T [K] (bisect_right on the interior breaks)."""
    return np.searchsorted(breaks, T, side="right") if breaks.size else 0


@njit(cache=True, inline="always")
def mixture_row(rows, n, i, out):
    """Mole-weighted row of range i (:meth:`cavity.gas.Mixture._combined`): Σ n_s·rows[s, i] into out (7,)."""
    for c in range(7):
        out[c] = n[0] * rows[0, i, c]
    for s in range(1, n.size):
        if n[s] != 0.0:
            for c in range(7):
                out[c] += n[s] * rows[s, i, c]


@njit(cache=True, inline="always")
def row_enthalpy(r, T):
    """H(T) [J] of a coefficient row (:meth:`cavity.gas.Mixture.enthalpy`)."""
    return T * (r[0] + T * (r[1] / 2.0 + T * (r[2] / 3.0 + T * (r[3] / 4.0 + T * r[5] / 5.0)))) - r[4] / T + r[6]


@njit(cache=True, inline="always")
def row_cp(r, T):
    """Cp(T) [J/K] of a coefficient row (:meth:`cavity.gas.Mixture.heat_capacity_p`)."""
    return r[0] + T * (r[1] + T * (r[2] + T * (r[3] + T * r[5]))) + r[4] / (T * T)


@njit(cache=True, inline="always")
def temperature(rows, breaks, linear, n, nmol, U, T_guess, row):
    """T [K] with U(T) = U [J] by Newton (:meth:`cavity.gas.Mixture.temperature`); NaN if it fails.

    ``row`` (7,) is scratch; on return it holds the row of the range of T (index returned second).
    """
    nR = nmol * R_U
    T = T_guess
    cur = -1
    for _ in range(NEWTON_MAX):
        i = range_of(breaks, T)
        if i != cur:
            mixture_row(rows, n, i, row)
            cur = i
        if linear[i]:
            T_new = (U - row[6]) / (row[0] - nR)
            if T_new >= T_FLOOR and range_of(breaks, T_new) == i:
                return T_new, cur
        else:
            U_T = row_enthalpy(row, T) - nR * T
            cv = row_cp(row, T) - nR
            T_new = T - (U_T - U) / cv
        if T_new < T_FLOOR:
            T_new = 0.5 * (T + T_FLOOR)
        if abs(T_new - T) <= NEWTON_RTOL * T_new:
            return T_new, cur
        T = T_new
    return math.nan, cur


@njit(cache=True, inline="always")
def volume_of(ci, cf, tx, ty, ti, i, t, y):
    """(V, dV/dt) of cavity i's geometric volume [m^3, m^3/s] (FixedVolume, TableVolume, ScaledMeshVolume, a
    volume wrapped around prescribed bodies: a cubic spline of time, kind 3, or around the dynamic body: of its
    displacement, kind 4)."""
    kind = ci[i, 2]
    if kind == 0:
        return cf[i, 5], 0.0
    k = ci[i, 3]
    if kind == 3:
        return spline_value(tx, ty, ti, k, t)
    if kind == 4:  # a spline of the dynamic body's displacement y[ci[i, 6]]: dV/dt = dV/ds·v
        value, slope = spline_value(tx, ty, ti, k, y[ci[i, 6]])
        return value, slope * y[ci[i, 6] + 1]
    if kind == 1:
        return table_value(tx, ty, ti, k, t), table_slope(tx, ty, ti, k, t)
    s = table_value(tx, ty, ti, k, t)
    return s * s * s * cf[i, 5], 3.0 * s * s * table_slope(tx, ty, ti, k, t) * cf[i, 5]


@njit(cache=True, inline="always")
def states(rows, breaks, linear, M, tx, ty, ti, ci, cf, t, y, T_guess, st, n, row):
    """Fill ``st`` with every cavity's state at (t, y) (:meth:`cavity.cavity.CavityState.of` + ``gas_point``).

    Returns False when a temperature solve failed. ``n`` (ns,) and ``row`` (7,) are scratch.
    """
    ok = True
    for i in range(ci.shape[0]):
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
        Vg, rate = volume_of(ci, cf, tx, ty, ti, i, t, y)
        Vt = Vg + cf[i, 1]
        if Vt > cf[i, 2]:
            V_eos = Vt
        else:
            V_eos = cf[i, 2]
            rate = 0.0
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
        else:  # gas_point of an empty cavity
            st[i, RHO], st[i, RG], st[i, GAM], st[i, H] = 0.0, 1.0, 1.4, 0.0
    return ok


@njit(cache=True, inline="always")
def exchange_area(ei, ef, op, iv, tx, ty, ti, j, t):
    """Flow area [m^2] of exchange j at t (:func:`exchange.activation.activated_area` without delta area);
    ``op[j]`` is 0 while a pop vent has not popped; ``iv[j]`` the interval of the dynamic body's displacement
    that holds the area of an area kind 2 (``ei[j, 10]``)."""
    if ei[j, 4] == 1 and not (ef[j, 2] <= t < ef[j, 3]):
        return 0.0
    if op[j] == 0:
        return 0.0
    a = table_value(tx, ty, ti, ei[j, 3], t) if ei[j, 3] >= 0 else 1.0
    if ei[j, 10] == 2:
        base = ty[ti[ei[j, 8], 0] + iv[j]]
    elif ei[j, 8] >= 0:
        base = step_value(tx, ty, ti, ei[j, 8], t)
    else:
        base = ef[j, 0]
    if ei[j, 9] >= 0:  # the leakage surface scales with its cavity mesh: area × s²
        sc = table_value(tx, ty, ti, ei[j, 9], t)
        base *= sc * sc
    return a * base


@njit(cache=True, inline="always")
def side(st, amb, i, c):
    """Column c of the gas point of cavity i, or of ambient (i < 0)."""
    return amb[c] if i < 0 else st[i, c]


@njit(cache=True, inline="always")
def law_flow(ei, ef, st, amb, j, u, p_down, area):
    """Mass flow [kg/s] of exchange j's law from side u (cavity, or ambient if < 0) into p_down [Pa], >= 0
    (``law.mass_flow`` of :mod:`exchange.laws`; kinds in :data:`exchange.compiled.LAW_KINDS`)."""
    kind, p_up = ei[j, 7], side(st, amb, u, P)
    if kind == 2:  # GraefeLaw
        return graefe_mass_flow(p_up, p_down, side(st, amb, u, RHO), area, ef[j, 6], ef[j, 7])
    if kind == 3:  # LinearResistanceLaw
        dp = p_up - p_down
        return ef[j, 6] * area * dp if dp > 0 else 0.0
    if kind == 1:  # FabricLeakageLaw
        return fabric_leakage_mass_flow(p_up, side(st, amb, u, TT), p_down, side(st, amb, u, RG),
                                        side(st, amb, u, GAM), area, ef[j, 1], ef[j, 6])
    return orifice_mass_flow(p_up, side(st, amb, u, TT), p_down, side(st, amb, u, RG), side(st, amb, u, GAM), area,
                             ef[j, 1])


@njit(cache=True, inline="always")
def exchange_flow(ei, ef, eq, op, iv, tx, ty, ti, st, amb, j, t):
    """Signed mass flow [kg/s] of exchange j, up → down (:meth:`exchange.vent.Exchange.mass_flow`);
    0 while equalised or not popped."""
    area = exchange_area(ei, ef, op, iv, tx, ty, ti, j, t)
    if area <= 0.0 or eq[j] == 1:
        return 0.0
    a, b = ei[j, 0], ei[j, 1]
    pa, pb = side(st, amb, a, P), side(st, amb, b, P)
    if pa >= pb:
        return law_flow(ei, ef, st, amb, j, a, pb, area)
    if b < 0 and ei[j, 2] == 0:
        return 0.0
    return -law_flow(ei, ef, st, amb, j, b, pa, area)


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
    """d(unknowns)/dt into dy (:meth:`exchange.network.Network.rhs`); False if a temperature solve failed.

    ``seg_end``: inputs are read at its left limit when t reaches it (:meth:`Network.input_time`); ``ledger``:
    offset of the exchanges' ledger entries (each cavity's are ``ci[i, 4]``).
    """
    if t >= seg_end:
        t = np.nextafter(seg_end, -np.inf)
    ok = states(rows, breaks, linear, M, tx, ty, ti, ci, cf, t, y, T_guess, st, n, row)
    dy[:] = 0.0
    for q in range(ii.shape[0]):
        i, start = ii[q, 0], if_[q, 0]
        if t < start:
            continue
        mdot = if_[q, 1] * table_value(tx, ty, ti, ii[q, 1], t - start)
        if mdot != 0.0:
            T_in = table_value(tx, ty, ti, ii[q, 2], t - start)
            r = irows[q, range_of(breaks, T_in)]
            hdot = mdot * row_enthalpy(r, T_in) / if_[q, 2]
            k, ns, c = ci[i, 0], ci[i, 5], ci[i, 4]
            for s in range(ns):
                dy[k + s] += mdot * if_[q, 3 + s]
            dy[c] += mdot
            dy[c + 1] += hdot
            if ci[i, 1] != 1:
                dy[k + ns] += hdot
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
        src = ei[j, 0] if mdot >= 0.0 else ei[j, 1]
        edot = mdot * side(st, amb, src, H)
        _transfer(ci, dy, ei[j, 0], -mdot, -edot, st, amb, src)
        if ei[j, 1] >= 0:
            _transfer(ci, dy, ei[j, 1], mdot, edot, st, amb, src)
        e = ledger + 2 * j
        dy[e] += mdot
        dy[e + 1] += edot
    return ok


@njit(cache=True)
def body_rhs(y, dy, ci, tx, ty, ti, st, amb, bd):
    """ds/dt = v, dv/dt = g + F/m of the dynamic body (:meth:`cases.scene_network.SceneNetwork.rhs` with
    :meth:`~cases.scene_network.SceneNetwork.applied_force`): F = (p − p_amb)·dV/ds of the cavity it intrudes into
    + (p − p_amb)·A of its pressure cavity − preload − k·s. ``bd``: offset, mass, gravity, pushed cavity (−1),
    pressure cavity (−1), pressure area, stiffness, preload (:func:`exchange.compiled.lower`)."""
    k = int(bd[0])
    s, v = y[k], y[k + 1]
    force = 0.0
    pushed, other = int(bd[3]), int(bd[4])
    if pushed >= 0:
        force += (st[pushed, P] - amb[0]) * spline_value(tx, ty, ti, ci[pushed, 3], s)[1]
    if other >= 0:
        force += (st[other, P] - amb[0]) * bd[5]
    force -= bd[7] + bd[6] * s
    dy[k] = v
    dy[k + 1] = bd[2] + force / bd[1]


@njit(cache=True)
def switch_value(kind, j, ei, ef, st, amb):
    """Switch function of exchange j on the states in ``st`` (:meth:`Network._choke_switch`, kind 0,
    :meth:`Network._dp_switch`, kind 1, the equalise and release switches, kinds 2 and 3,
    :meth:`Network._pop_switch`, kinds 4 (pop) and 5 (pop-drop), the orifice join, kind 7) [-]. The pop-hold
    switch (kind 6) depends on time only: :func:`exchange.compiled_solver.switches`."""
    a, b = ei[j, 0], ei[j, 1]
    pa, pb = st[a, P], side(st, amb, b, P)
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
        return (pb - critical_pressure_ratio(st[a, GAM]) * pa) / pa
    return (pa - critical_pressure_ratio(side(st, amb, b, GAM)) * pb) / pb
