"""Naive-vs-fast pairs for the one engine (used by the tests of the compiled engine).

- Integrators: the compiled DOP853 (one numba call, :mod:`exchange.engine.solver`) against scipy's DOP853 stepping
  the same lowered network (:mod:`exchange.engine.system`): two implementations of the stepping, the event
  location and the restarts, the same kernels.
- Read-back: the history in one compiled call (:func:`cases.results.readback.history_rows`: compiled dense
  output, discrete state per segment as arrays) against rows built one by one from ``Trajectory.sample`` and the
  point kernels in each segment's loaded mode (:mod:`exchange.readback.values`), and the compiled peak search against
  scipy's bounded search.
- Right-hand side: the compiled one against :func:`reference_rhs`, assembled here from the cavities' and
  exchanges' Python objects (mixtures, volume models, inflators, flow laws, activation rules and the area tracks
  of the blockage geometry): the bookkeeping written a second time, naively, as a test oracle.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from cases.results.contact_results import contact_columns, contact_rows
from cases.results.readback import cavity_peaks, cavity_summary, history_columns, history_rows, refine_peak
from cavity.integration import integrate
from cavity.tolerances import R_UNIVERSAL
from exchange.engine.rhs import rhs as compiled_rhs
from exchange.network.network import LEDGER_PER_CAVITY, LEDGER_PER_EXCHANGE
from exchange.readback.values import cavity_states, exchange_values, load_mode
from exchange.network.vent import GasPoint
from cavity.hydraulic import hydraulic_pressure

__all__ = ["compiled_dop853", "scipy_dop853", "both_integrators", "pointwise_history", "assert_same_history",
           "assert_same_on_both_integrators", "reference_rhs", "assert_rhs_matches_reference", "pressures"]


def compiled_dop853(model, options=None):
    net = model.network
    return integrate(net, net.initial_state(), 0.0, model.scene.time.end, options or model.options)


def scipy_dop853(model, options=None):
    """scipy's ``solve_ivp`` DOP853 stepping the lowered network (right-hand side, switches, switch actions)."""
    options = replace(options or model.options, method="DOP853", integrator="scipy")
    net = model.network
    traj = integrate(net, net.initial_state(), 0.0, model.scene.time.end, options)
    assert traj.path == "compiled, solve_ivp"
    return traj


def both_integrators(model, options=None):
    """(compiled DOP853 trajectory, scipy DOP853 trajectory) of a model."""
    fast = compiled_dop853(model, options)
    assert fast.path == "compiled"
    return fast, scipy_dop853(model, options)


def pressures(model, traj, times):
    return np.array([[s.pressure for s in model.network.states(t, y)] for t, y in zip(times, traj.sample(times))])


def pointwise_history(model, traj, times) -> np.ndarray:
    """History rows built one by one: each segment's dense output (``DenseSteps`` or scipy's), its mode loaded,
    the point kernels."""
    net = model.network
    fast, rows = net.engine(), []
    walls = [k + len(c.initial_masses) + 1 for c, k in zip(net.cavities, net.offsets) if getattr(c, "wall", None)]
    walls += [k + len(c.initial_masses) + c.wall.layers for c, k in zip(net.cavities, net.offsets)
              if getattr(c, "wall", None) is not None and c.wall.layers > 1]
    for t in times:
        y = traj.segments[traj.segment_index(t)](t)  # the segment's own dense output, not the compiled sampler
        load_mode(fast, traj.mode_at(t))
        row = [t]
        for s in cavity_states(fast, t, y):
            row += [s.pressure, s.temperature, s.mass, s.volume]
        for mdot, area in zip(*exchange_values(fast, t, y)):
            row += [mdot, area]
        for cav in net.cavities:  # the inflators' own Python methods: the engine's kernel against them
            for inf in cav.inflators:
                row += [inf.mass_flow(t), inf.temperature(t)]
        rows.append(row + [y[k] for k in walls])
    load_mode(fast, traj.modes[-1])
    out = np.array(rows)
    if contact_columns(model):
        out = np.column_stack([out, contact_rows(model, traj, times)])
    return out


def assert_same_history(model, traj, times=None, rtol=1e-12):
    """The history read back in one compiled call equals the pointwise one column by column (``rtol`` of each
    column's largest magnitude), and the compiled peak search scipy's bounded search; returns the rows."""
    times = np.asarray(model.output_times if times is None else times, dtype=float)
    fast, slow = history_rows(model, traj, times), pointwise_history(model, traj, times)
    columns = history_columns(model)
    assert fast.shape == slow.shape == (times.size, len(columns))
    for k, name in enumerate(columns):
        scale = np.max(np.abs(slow[:, k]))
        np.testing.assert_allclose(fast[:, k], slow[:, k], rtol=rtol, atol=rtol * scale, err_msg=name)
    net = model.network
    ts = np.unique(np.concatenate([traj.step_times, [s.t_min for s in traj.segments], [traj.t_final]]))
    ps = pressures(model, traj, ts)
    for i, (p, tp) in enumerate(cavity_peaks(model, traj)):
        ref = refine_peak(ts, ps[:, i], lambda t: net.states(t, traj(t))[i].pressure)
        # the time of a flat maximum moves as √(2 ε p / |p''|): for airbag_impactor's peak (p 2.6e5 Pa,
        # p'' ≈ -8e8 Pa/s², at 35 ms) that is 4e-10 s, 1.1e-8 of the time; 1e-7 leaves 9x
        assert p == pytest.approx(ref[0], rel=1e-12) and tp == pytest.approx(ref[1], rel=1e-7)
    cavity_summary(model, traj, traj(model.scene.time.end))
    return fast


def assert_same_on_both_integrators(model, events_expected=None, rtol=1e-12, steps=2, event_rtol=1e-12):
    """Both integrators: the same event labels, event times and discrete states to ``event_rtol``, the same steps
    (± ``steps``), and the same history column by column (``rtol`` of each column's largest magnitude). Returns
    the compiled trajectory."""
    fast_traj, slow_traj = both_integrators(model)
    labels = [label for _, label in slow_traj.events]
    assert [label for _, label in fast_traj.events] == labels
    if events_expected is not None:
        assert [label for label in labels if label.split(":")[1].startswith("pop")] == events_expected
    np.testing.assert_allclose([t for t, _ in fast_traj.events], [t for t, _ in slow_traj.events], rtol=event_rtol)
    # steps may part by one or two where the solution is a polynomial in t (a closed vent while the inflow is
    # constant): the error estimate is then round-off (docs/benchmarks.md, section 1)
    assert abs(fast_traj.stats["steps"] - slow_traj.stats["steps"]) <= steps
    assert len(fast_traj.modes) == len(slow_traj.modes)
    for f, s in zip(fast_traj.modes, slow_traj.modes):
        assert (f.popped, f.area_at_activation, f.equalised) == (s.popped, s.area_at_activation, s.equalised)
        assert [h is None for h in f.holding_since] == [h is None for h in s.holding_since]
        np.testing.assert_allclose([h for h in f.holding_since if h is not None],
                                   [h for h in s.holding_since if h is not None], rtol=event_rtol)
    # at an event time the two agree to the last bit, both read the same side of the switch; where round-off
    # parts them (by ~1e-16 s) a row at one integrator's event time would read the two sides of it
    same = [t for (t, _), (tf, _) in zip(slow_traj.events, fast_traj.events) if t == tf]
    times = np.union1d(np.asarray(model.output_times), same)
    fast, slow = history_rows(model, fast_traj, times), history_rows(model, slow_traj, times)
    for k, name in enumerate(history_columns(model)):
        scale = np.max(np.abs(slow[:, k]))
        np.testing.assert_allclose(fast[:, k], slow[:, k], rtol=rtol, atol=rtol * scale, err_msg=name)
    return fast_traj


# ---- the right-hand side assembled naively from the Python objects

def _gas_point(net, cav, t, y, k):
    """(GasPoint, p [Pa], T [K], dV/dt [m^3/s]) of a cavity from its unknowns (masses clipped at 0)."""
    V = cav.volume(t) + cav.added_volume
    V_eos = max(V, cav.minimum_volume)
    rate = cav.volume.rate(t) if V > cav.minimum_volume else 0.0
    if getattr(cav, "kind", "gas") == "hydraulic":
        m = max(float(y[k]), 0.0)
        T = cav.temperature(t)
        rho_ref = cav.reference_density * math.exp(-cav.thermal_expansion * (T - cav.reference_temperature))
        p = hydraulic_pressure(m / V_eos, rho_ref, cav.bulk_modulus, cav.reference_pressure) if m > 0 else -math.inf
        return GasPoint(p, T, m / V_eos, math.nan, math.nan, 0.0, np.ones(1)), p, T, rate
    ns = len(cav.initial_masses)
    masses = np.maximum(y[k:k + ns], 0.0)
    mix = net.gas.mixture(masses)
    T = cav.initial_temperature if cav.isothermal else mix.temperature(float(y[k + ns]), cav.initial_temperature)
    p = mix.moles * R_UNIVERSAL * T / V_eos
    point = GasPoint(p, T, mix.mass / V, mix.gas_constant, mix.gamma(T), mix.enthalpy(T) / mix.mass,
                     masses / mix.mass)
    return point, p, T, rate


def _area(net, j, t, mode):
    """Exchange j's flow area [m^2] at t in ``mode`` (a DiscreteState)."""
    ex, act = net.exchanges[j], net.exchanges[j].activation
    ga = net.areas[j] if getattr(net, "areas", None) else None
    area = ga.track(t) if ga is not None else ex.area  # the blockage geometry's area track (by time)
    if act is None:
        return area
    if not (act.open_time <= t < act.close_time) or (act.pop_pressure is not None and not mode.popped[j]) \
            or mode.closed[j]:
        return 0.0
    a = act.amplitude(t) if act.amplitude is not None else 1.0
    return a * (max(area - (mode.area_at_activation[j] or 0.0), 0.0) if act.delta_area else area)


def _flow(net, j, t, points, mode):
    ex = net.exchanges[j]
    area = _area(net, j, t, mode)
    if area <= 0.0 or mode.equalised[j]:
        return 0.0, None
    a = points[ex.upstream]
    b = net.ambient.point() if ex.downstream is None else points[ex.downstream]
    if ex.law.prescribed or a.p >= b.p:
        mdot = ex.law.mass_flow(a, b.p, area, t)
    elif ex.downstream is None and not ex.two_way:
        mdot = 0.0
    else:
        mdot = -ex.law.mass_flow(b, a.p, area, t)
    return mdot, (a if mdot >= 0.0 else b)


def reference_rhs(net, t, y, mode) -> np.ndarray:
    """d(unknowns)/dt of an ideal-gas or hydraulic network without a dynamic body, in ``mode``."""
    assert getattr(net, "body", None) is None
    dy = np.zeros_like(y)
    states = [_gas_point(net, c, t, y, k) for c, k in zip(net.cavities, net.offsets)]
    points = [s[0] for s in states]
    base = net.ledger_offset + LEDGER_PER_EXCHANGE * len(net.exchanges)
    for i, (cav, k, (point, p, T, rate)) in enumerate(zip(net.cavities, net.offsets, states)):
        ns, c = len(cav.initial_masses), base + LEDGER_PER_CAVITY * i
        for inf in cav.inflators:
            mdot = inf.mass_flow(t)
            hdot = mdot * inf.gas.enthalpy(inf.temperature(t)) / inf.gas.mass
            dy[k:k + ns] += mdot * np.asarray(inf.mass_fractions, dtype=float)
            dy[c] += mdot
            dy[c + 1] += hdot
            dy[k + ns] += 0.0 if cav.isothermal else hdot
        if not cav.isothermal and getattr(cav, "kind", "gas") == "gas":
            heat = cav.heat_loss(T)
            dy[k + ns] -= p * rate + heat
            dy[c + 2] += p * rate
            dy[c + 3] += heat
    for j, ex in enumerate(net.exchanges):
        mdot, carrier = _flow(net, j, t, points, mode)
        if mdot == 0.0:
            continue
        edot = mdot * carrier.h
        for i, sign in ((ex.upstream, -1.0), (ex.downstream, 1.0)):
            if i is None:
                continue
            cav, k = net.cavities[i], net.offsets[i]
            ns = len(cav.initial_masses)
            dy[k:k + ns] += sign * mdot * np.asarray(carrier.mass_fractions, dtype=float)
            if not cav.isothermal and getattr(cav, "kind", "gas") == "gas":
                dy[k + ns] += sign * edot
        e = net.ledger_offset + LEDGER_PER_EXCHANGE * j
        dy[e] += mdot
        dy[e + 1] += edot
    return dy


def assert_rhs_matches_reference(model, samples=31, traj=None):
    """The compiled right-hand side equals :func:`reference_rhs` at points of the compiled trajectory, in its
    discrete state there, to 1e-12 of each rate's largest magnitude over the samples (round-off near Δp = 0 makes
    a vent's flow ±1e-15 kg/s where the reference's is 0)."""
    net = model.network
    fast = net.engine()
    traj = traj or compiled_dop853(model)
    got, expected = [], []
    for t in np.linspace(0.0, model.scene.time.end, samples)[1:-1]:
        y = traj(t)
        mode = traj.mode_at(t)
        expected.append(reference_rhs(net, t, y, mode))
        load_mode(fast, mode)
        got.append(np.empty_like(y))
        assert compiled_rhs(fast.model, t, y, got[-1], math.inf)
    load_mode(fast, traj.modes[-1])
    got, expected = np.array(got), np.array(expected)
    scale = np.max(np.abs(expected), axis=0)
    assert np.all(np.abs(got - expected) <= 1e-12 * scale + 1e-300), (np.abs(got - expected) / scale).max(axis=0)
