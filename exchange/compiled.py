"""Lowering a :class:`exchange.network.Network` to flat arrays for the compiled integrator.

:func:`lower` returns a :class:`CompiledNetwork` when every part of the network is of a supported kind, else
``None`` with the reason in :func:`unsupported_reason`; :func:`cavity.integration.integrate` then runs the Python
path. Supported: a plain ``Network`` or a scene network that lowers its geometry, ideal-gas mixtures with
piecewise cp polynomials, adiabatic, isothermal or heat-loss gas cavities, real-gas cavities (adiabatic, heat
loss or a wall) and hydraulic cavities (without inflators) with fixed, table or scaled-mesh volumes,
mass/temperature-table, tank-test, pressure-and-mass and dual-pressure inflators, exchanges to ambient (one- or
two-way) or between cavities with an orifice, fabric-leakage, Graefe, linear-resistance, leakage-table (mass or
volume rate), prescribed-flux (mass or volume) or bulk-viscosity law, a constant Cd or a Cd table of upstream
pressure or time, with an optional time window, amplitude table, pop pressure with hold time and DELTA LEAKAGE
AREA; any other law with ``mass_flow(up, p_down, area, t)`` (the real-gas nozzle, a user's law). A real-gas
cavity's equation of state and wall and the laws outside that list stay Python objects that the compiled kernels
call (:mod:`exchange.hosted`); the rest is compiled.

The arrays are described in :mod:`exchange.compiled_rhs`.
"""
from __future__ import annotations

import importlib.util
import logging
import math
import os
from dataclasses import dataclass, field

import numpy as np

from cavity.integration import NO_TEMPERATURE
from cavity.volume import FixedVolume, ScaledMeshVolume, TableVolume

from . import laws
from .compiled_contact import event_states, seat_arrays
from .compiled_inflators import INFLATOR_KINDS, lower_inflators, warn_clamped
from .discharge import DischargeTable
from .hosted import host_of, register
from .lowered_switches import switch_table
from .lowered_columns import (UNLOCKED, Tables, area_at_activation, law_parameters, law_tables,
                              liquid as liquid_columns, spline_entry)

__all__ = ["CompiledNetwork", "lower", "unsupported_reason"]

ENERGY = {"adiabatic": 0, "isothermal": 1, "heat_loss": 2}
REAL_GAS_ENERGY = {"adiabatic": 0, "heat_loss": 2, "wall": 3}  # ci[i, 1] of a real-gas cavity (3: hosted wall)
HOSTED_LAW = 7  # ``ei[j, 7]`` of a law the compiled path calls in Python (exchange.hosted)
#: law class of :mod:`exchange.laws` -> kind code in ``ei[:, 7]`` (:func:`exchange.compiled_rhs.law_flow`)
LAW_KINDS = {"OrificeLaw": 0, "FabricLeakageLaw": 1, "GraefeLaw": 2, "LinearResistanceLaw": 3, "LeakageTableLaw": 4,
             "FluxLaw": 5, "BulkViscosityLaw": 6}


@dataclass
class CompiledNetwork:
    """A network as arrays, with its switch functions (kinds of :func:`exchange.lowered_switches.switch_table`) and their labels."""

    model: tuple
    kinds: np.ndarray
    exchanges: np.ndarray
    labels: list
    T_initial: np.ndarray
    network: object
    host: int = -1  # its id in exchange.hosted (−1: no hosted parts)
    _modes: dict = field(default_factory=dict, repr=False)
    _run_modes: list = field(default_factory=list, repr=False)

    def run(self, y0, t0: float, stops, rtol: float, atol, max_step: float, max_steps: int, near: float,
            deadline: float = math.inf):
        """One call of :func:`exchange.compiled_solver.solve` from the network's current discrete state; returns
        its tuple (see there) with the segment table cut to 5 columns, the last an index for
        :meth:`segment_mode`."""
        from .compiled_solver import solve

        _announce_compilation(solve)
        model, net = self.model, self.network
        model[16][:] = self.T_initial  # Newton's first guesses, as Network.reset()
        if self.host >= 0:
            host_of(self.host).error = None
        self.load_discrete_state()
        y0 = np.asarray(y0, dtype=float)
        if not (type(atol) is np.ndarray and atol.shape == y0.shape and atol.dtype == np.float64):
            atol = np.broadcast_to(np.asarray(atol, dtype=float), y0.shape).copy()
        out = solve(model, self.kinds, self.exchanges, y0, float(t0), np.array(stops, dtype=float), float(rtol),
                    atol, float(max_step), int(max_steps), float(near), float(deadline))
        model[7][:, 9] = UNLOCKED  # outputs read the volume splines on the pieces that hold s
        warn_clamped(net, model[9])
        segs = out[4]
        self._run_modes = [self._mode(row) for row in segs.tolist()]
        if getattr(net, "contact", None) is not None:
            net.log_contact_events(event_states(out, self.labels, self._run_modes))
        table = segs[:, :5].copy()
        table[:, 4] = np.arange(len(segs))
        return out[:4] + (table,) + out[5:]

    def solve_ivp_system(self, near: float):
        """This network as the system scipy's other methods integrate (:class:`exchange.lowered_system.
        LoweredSystem`), from the network's current discrete state."""
        from .lowered_system import LoweredSystem

        return LoweredSystem(self, near)

    def arm(self, t0: float, y0) -> list:
        """From the network's discrete state, every pop vent already above its pop pressure at t0 starts its hold
        (or pops) now, as if its pressure had just crossed it, and every exchange whose downstream cavity is
        already at its close pressure closes; the network takes the new state. Returns their switch labels (for
        the event log)."""
        from .compiled_modes import on_event
        from .compiled_solver import switches

        self.load_discrete_state()
        M, labels, value = self.model, [], np.empty(1)
        y0 = np.ascontiguousarray(y0, dtype=float)
        for q in np.flatnonzero((self.kinds == 4) | (self.kinds == 17)):
            j = int(self.exchanges[q])
            if M[21][j] != (1 if self.kinds[q] == 17 else 0) or not math.isnan(M[22][j]):
                continue
            switches(M, self.kinds[q:q + 1], self.exchanges[q:q + 1], float(t0), y0, math.inf, value)
            reached = value[0] >= 0.0 if self.kinds[q] == 17 else value[0] > 0.0
            if reached:
                on_event(M, int(self.kinds[q]), j, float(t0), y0.copy(), math.inf)
                labels.append(self.labels[q])
        if labels:
            self.network.restore(self.current_mode(t0))
        return labels

    def current_mode(self, t_min: float):
        """The network's snapshot of the discrete state now in the model arrays, for a segment from t_min [s]."""
        from .compiled_modes import record_segment

        M = self.model
        row = np.empty((1, 6 + 3 * M[21].size))
        code = sum(1 << j for j, e in enumerate(M[20].tolist()) if e)
        record_segment(M, row, 0, 0, 0, float(t_min), float(t_min), code)
        return self._mode(row[0])

    def failure(self) -> str:
        """Why the latest right-hand side failed: a hosted part's exception (:mod:`exchange.hosted`), else no
        temperature for a cavity's internal energy."""
        error = host_of(self.host).error if self.host >= 0 else None
        return NO_TEMPERATURE if error is None else f"{type(error).__name__}: {error}"

    def load_discrete_state(self) -> None:
        """Copy the network's discrete state into the model arrays: equalised flags, open flags (0 a pop vent not
        popped, 1 open, 2 closed at its close pressure), hold starts, the area intervals of the dynamic body,
        whether hard contact holds it (compiled_body), no volume-spline piece held, and each pop vent's area at
        activation (DELTA LEAKAGE AREA; for one opened by time on an area that follows the dynamic body, NaN until
        it opens)."""
        model, net = self.model, self.network
        eq, op, hold = model[20], model[21], model[22]
        model[23][:] = [i if i is not None else 0 for i in getattr(net, "intervals", [0] * len(net.exchanges))]
        model[25][1] = float(bool(getattr(net, "held", False)))
        model[7][:, 9] = UNLOCKED  # no spline piece held: the segment start locks one (compiled_modes.lock_pieces)
        for j in range(len(net.exchanges)):
            pop_vent = model[12][j, 6] == 1
            eq[j] = net.equalised[j]
            op[j] = 2 if net.closed[j] else 0 if pop_vent and not net.popped[j] else 1
            hold[j] = math.nan if net.holding_since[j] is None else net.holding_since[j]
            if pop_vent:
                model[13][j, 9] = net.area_at_activation[j] or 0.0
            elif model[12][j, 14] and model[12][j, 10] == 2:  # set at the open time (compiled_rhs.exchange_area)
                model[13][j, 9] = math.nan if net.area_at_activation[j] is None else net.area_at_activation[j]

    def _mode(self, row) -> tuple:
        """The network's snapshot (``Network.snapshot()``) from a row of the solver's segment table: code
        (bits: equalised exchanges), then per exchange its open flag (:meth:`load_discrete_state`), then per
        exchange the hold start (NaN: none), the dynamic body's area intervals, held on its seat."""
        ne, code = len(self.network.exchanges), int(row[4])
        popped = tuple(bool(self.model[12][j, 6] == 1 and row[5 + j] >= 1) for j in range(ne))
        closed = tuple(bool(row[5 + j] == 2) for j in range(ne))
        holding = tuple(None if math.isnan(h) else h for h in row[5 + ne:5 + 2 * ne])
        intervals = tuple(int(i) for i in row[5 + 2 * ne:5 + 3 * ne])
        held = bool(row[5 + 3 * ne])
        key = (code, popped, closed, holding, intervals, row[2], held)
        if key not in self._modes:
            areas = self._areas_at_activation(popped, row[2])
            mode = (popped, holding, areas, tuple(bool(code >> j & 1) for j in range(ne)), closed)
            wrap = getattr(self.network, "wrap_mode", None)
            self._modes[key] = wrap(mode, intervals, held) if wrap is not None else mode
        return self._modes[key]

    def _areas_at_activation(self, popped, t_min) -> tuple:
        """``Network.area_at_activation`` in a segment starting at t_min: a popped vent's area at its pop; the
        area at the open time of a DELTA LEAKAGE AREA opened by time once a segment starts at or after it
        (:func:`exchange.compiled_segment.begin_segment` sets it there); else None."""
        ei, ef, out = self.model[12], self.model[13], []
        for j, ex in enumerate(self.network.exchanges):
            act = ex.activation
            if popped[j]:
                out.append(float(ef[j, 9]))
            elif ei[j, 14] and ei[j, 6] == 0 and t_min >= act.open_time:
                out.append(float(ef[j, 9]))
            else:
                out.append(None)
        return tuple(out)

    def segment_mode(self, code) -> tuple:
        """The network's snapshot during segment ``code`` of the latest :meth:`run`."""
        return self._run_modes[int(code)]


def _announce_compilation(kernel) -> None:
    """Log (logger ``ventsim``, level INFO: ``ventsim run`` prints it) that numba is about to compile ``kernel``
    when this process has not compiled it and its on-disk cache is missing (the first run after installing)."""
    if kernel.signatures:
        return
    cache = getattr(getattr(kernel, "_cache", None), "_cache_file", None)
    index = getattr(cache, "_index_path", None)
    if index is None or not os.path.exists(index):
        logging.getLogger("ventsim").info(
            "compiling the compiled network path with numba: the first run after installing takes about a minute "
            "of CPU, then it is cached (%s)", os.path.dirname(index) if index else "no cache")


def unsupported_reason(net) -> str | None:
    """Why ``net`` cannot be lowered (None: it can)."""
    if importlib.util.find_spec("numba") is None:
        return "numba is not installed"
    geometry = getattr(net, "lowered_geometry", None)
    if not net.is_plain() and geometry is None:
        return f"{type(net).__name__} is not a plain Network"
    if geometry is not None and isinstance(geometry(), str):
        return geometry()
    for cav in net.cavities:
        kind = getattr(cav, "kind", "gas")
        if kind == "hydraulic" and cav.inflators:
            return f"cavity {cav.name}: a hydraulic cavity with inflators"
        if kind not in ("gas", "hydraulic", "realgas") or (kind == "gas" and cav.energy not in ENERGY) \
                or (kind == "realgas" and cav.energy not in REAL_GAS_ENERGY):
            return f"cavity {cav.name}: kind or energy model"
        if not isinstance(cav.volume, (FixedVolume, TableVolume, ScaledMeshVolume)) and not _splined(net, cav):
            return f"cavity {cav.name}: volume model {type(cav.volume).__name__}"
        for inf in cav.inflators:
            if type(inf) not in INFLATOR_KINDS or tuple(inf.gas.breaks) != tuple(net.gas.breaks):
                return f"inflator {inf.name}: {type(inf).__name__}"
    for ex in net.exchanges:
        if _is_hosted(ex.law) and not callable(getattr(ex.law, "mass_flow", None)):
            return f"exchange {ex.name}: law {type(ex.law).__name__} has no mass_flow(up, p_down, area, t)"
    return None


def _is_hosted(law) -> bool:
    """A law called in Python (:mod:`exchange.hosted`): not exactly a :data:`LAW_KINDS` class with a lowerable Cd."""
    name = type(law).__name__
    return not (name in LAW_KINDS and type(law) is getattr(laws, name, None)
                and isinstance(getattr(law, "discharge_coefficient", 1.0), (int, float, DischargeTable)))


def has_hosted_parts(net) -> bool:
    """A real-gas cavity or a law the compiled path calls in Python (:mod:`exchange.hosted`)."""
    return any(getattr(c, "kind", "gas") == "realgas" for c in net.cavities) \
        or any(_is_hosted(ex.law) for ex in net.exchanges)


def _geometry(net) -> dict:
    """The network's lowered geometry (``lowered_geometry()``: {"areas": {j: (steps x, y, scale table or None,
    by displacement, switch scale, moving-surface pack or None)}, "volumes": {cavity name: (knots, coefficients
    (4, pieces), by displacement)}, "body": the dynamic body's parameters or None}), or empty."""
    lowered = getattr(net, "lowered_geometry", None)
    return lowered() if lowered is not None else {"areas": {}, "volumes": {}}


def _splined(net, cav) -> bool:
    return cav.name in _geometry(net).get("volumes", {})


def _cavities(net, tables, host):
    ci, cf = [], []
    splines = _geometry(net).get("volumes", {})
    for cav, k, c in zip(net.cavities, net.offsets, net._ledger):
        vol = cav.volume
        kind = (4 if splines[cav.name][2] else 3) if cav.name in splines else 0 if isinstance(vol, FixedVolume) \
            else 1 if isinstance(vol, TableVolume) else 2
        tab = tables.add(vol.table) if kind == 1 else tables.add(vol.scale) if kind == 2 else \
            spline_entry(tables, *splines[cav.name][:2]) if kind >= 3 else -1
        size = vol.volume if kind == 0 else vol.mesh_volume if kind == 2 else 0.0
        liquid, real = (getattr(cav, "kind", "gas") == k for k in ("hydraulic", "realgas"))
        hA = 0.0 if liquid else cav.heat_transfer_coefficient * cav.heat_transfer_area
        energy = 1 if liquid else REAL_GAS_ENERGY[cav.energy] if real else ENERGY[cav.energy]
        ci.append((k, energy, kind, tab, c, len(cav.initial_masses),
                   int(_geometry(net)["body"][0]) if kind == 4 else -1, 2 if real else int(liquid),
                   tables.add(cav.temperature) if liquid else host if real else -1, UNLOCKED))
        cf.append((cav.initial_temperature, cav.added_volume, cav.minimum_volume, hA,
                   0.0 if liquid else cav.ambient_temperature, size) + liquid_columns(cav))
    return np.array(ci, dtype=np.int64).reshape(-1, 10), np.array(cf, dtype=float).reshape(-1, 11)


def _exchanges(net, tables, host):
    ei, ef = [], []
    geometric = _geometry(net).get("areas", {})
    for j, ex in enumerate(net.exchanges):
        act = ex.activation
        amp = tables.add(act.amplitude) if act is not None and act.amplitude is not None else -1
        window = act is not None
        pop = window and act.pop_pressure is not None
        hosted = _is_hosted(ex.law)
        cd, p1, p2 = (1.0, float(bool(ex.law.prescribed)), 0.0) if hosted else law_parameters(ex.law)
        steps, scale, kind, switch_scale = -1, -1, 0, 1.0
        if j in geometric:
            x, y, scale_table, by_displacement, switch_scale, moving = geometric[j]
            steps = tables.add_arrays(np.concatenate([[-np.inf], x]), y if moving is None else np.arange(len(x) + 1.0))
            if moving is not None:  # a surface on a vertex trajectory: the steps give the interval, then its pack
                tables.add_arrays(np.zeros(len(moving)), moving)
            scale = tables.add(scale_table) if scale_table is not None else -1
            kind = 3 if moving is not None else 2 if by_displacement else 1
        law_table, cd_table, cd_variable = law_tables(ex.law, tables)
        ei.append((ex.upstream, -1 if ex.downstream is None else ex.downstream, int(bool(ex.two_way)), amp,
                   int(window), int(net.can_equalise(len(ei))), int(pop),
                   HOSTED_LAW if hosted else LAW_KINDS[type(ex.law).__name__], steps, scale, kind,
                   host if hosted else law_table, cd_table, cd_variable))
        ef.append((ex.area, cd, act.open_time if window else 0.0, act.close_time if window else math.inf,
                   act.pop_pressure if pop else 0.0, act.hold_time if pop else 0.0, p1, p2, switch_scale,
                   area_at_activation(net, j), (act.close_pressure or 0.0) if window else 0.0))
        ei[-1] += (int(window and act.delta_area),)
    return np.array(ei, dtype=np.int64).reshape(-1, 15), np.array(ef, dtype=float).reshape(-1, 11)


def _body(net) -> np.ndarray:
    """The dynamic body for :func:`exchange.compiled_body.body_rhs`: offset, mass, gravity, pushed cavity, pressure
    cavity, pressure area, stiffness, preload, turning-point speed scale, re-derivation slack [m]; offset −1:
    none."""
    body = _geometry(net).get("body")
    return np.array(body if body is not None else (-1.0,) + (0.0,) * 9, dtype=float)


_CACHE_CHECKED = []


def lower(net) -> CompiledNetwork | None:
    """The network as arrays for :func:`exchange.compiled_solver.solve`, or None if a part is not supported."""
    if unsupported_reason(net) is not None:
        return None
    if not _CACHE_CHECKED:  # once per process, before numba loads a cached kernel
        from .kernel_cache import purge_stale

        purge_stale()
        _CACHE_CHECKED.append(True)
    gas = net.gas
    _, rows, linear, breaks = gas._per_range  # rows (ns, nr, 7) per mole; int flags and breaks as Mixture's
    ns, nr = rows.shape[0], rows.shape[1]
    tables = Tables()
    host = register(net) if has_hosted_parts(net) else -1
    ci, cf = _cavities(net, tables, host)
    ii, ifl, irows = lower_inflators(net, tables, ns, nr)
    ei, ef = _exchanges(net, tables, host)
    tx, ty, ti = tables.arrays()
    a = net.ambient.point()
    amb = np.array([a.p, a.T, a.rho, a.R, a.gamma, a.h] + list(np.asarray(a.mass_fractions, dtype=float)))
    nc = len(net.cavities)
    T0 = np.array([c.initial_temperature for c in net.cavities], dtype=float)
    model = (rows, breaks, linear,
             np.asarray(gas.molar_masses, dtype=float), tx, ty, ti, ci, cf, ii, ifl, irows, ei, ef, amb,
             int(net.ledger_offset), T0.copy(), np.zeros((nc, 9 + ns)), np.zeros(ns), np.zeros(7),
             np.zeros(len(net.exchanges), dtype=np.int64), np.ones(len(net.exchanges), dtype=np.int64),
             np.full(len(net.exchanges), np.nan), np.zeros(len(net.exchanges), dtype=np.int64), _body(net)) \
        + seat_arrays(_geometry(net).get("contact"))
    kinds, js, labels = switch_table(net, _geometry(net))
    return CompiledNetwork(model, kinds, js, labels, T0, net, host)
