"""A lowered network on the engine: its model, switch labels and network, and what the integrators ask of it (a whole
compiled DOP853 run, the system scipy's methods step, the switches already past their threshold at the start, the
discrete state loaded into the model and read back per segment as the network's :class:`~exchange.network.
DiscreteState`)."""
from __future__ import annotations

import logging
import math
import os

import numpy as np

from cavity.integration import NO_TEMPERATURE
from exchange.network.discrete_state import DiscreteState

from .host import host_of
from .sampled import reset_sampling
from .segments import modes_of
from .inflators import warn_clamped
from .layout import (UNLOCKED, AreaKind, CavityInt, ExchangeFloat, ExchangeInt, OpenState, SeatState, SegmentColumn,
                     SwitchKind, open_state_of, segment_blocks)

__all__ = ["Engine"]

_SOLVE_READY = False  # whether this process has called the compiled solver (compiled or loaded it)


class Engine:
    """A network lowered onto the engine (:func:`exchange.engine.lower.lower`).

    ``model`` the numba Model, ``arrays`` its arrays on the Python side (:class:`~exchange.engine.layout.ModelArrays`),
    ``labels`` each switch's label, ``T_initial`` the cavities' initial temperatures [K], ``network`` the network,
    ``host`` its id in :mod:`exchange.engine.hosted` (−1: no hosted parts); ``pop_vents`` and ``by_body``
    per exchange whether it is a pop vent and whether its area follows the dynamic body."""

    def __init__(self, model, arrays, labels, T_initial, network, host: int = -1):
        self.model, self.arrays, self.labels, self.T_initial = model, arrays, labels, T_initial
        self.network, self.host = network, host
        self.modes, self._run_modes = {}, []  # modes: each distinct DiscreteState once
        # fixed by the lowering, found once: the switches arm() tests, each exchange's pop-vent and by-body flags
        kinds, ei = arrays.switch_kind, arrays.exchange_int
        self._armable = np.flatnonzero((kinds == SwitchKind.POP) | (kinds == SwitchKind.CLOSE)).tolist()
        self.pop_vents = (ei[:, ExchangeInt.POP] == 1).tolist()
        self.by_body = [int(k) in (AreaKind.STEPS_OF_BODY, AreaKind.SAMPLED_OF_BODY) for k in ei[:, ExchangeInt.AREA]]

    @property
    def kinds(self) -> np.ndarray:
        return self.arrays.switch_kind

    def run(self, y0, t0: float, stops, rtol: float, atol, max_step: float, max_steps: int, near: float,
            deadline: float = math.inf):
        """The whole integration in one call of :func:`exchange.engine.solver.solve` from the network's current
        discrete state; returns its tuple (see there), its segment table cut to five columns, the last an index for
        :meth:`segment_mode`."""
        from .solver import solve

        global _SOLVE_READY
        if not _SOLVE_READY:
            _announce_compilation(solve)
        a, net = self.arrays, self.network
        a.temperature_guess[:] = self.T_initial  # Newton's first guesses, as Network.reset()
        if self.host >= 0:
            host_of(self.host).error = None
        self.load_discrete_state()
        y0 = np.ascontiguousarray(y0, dtype=float)
        atol = np.array(np.broadcast_to(np.asarray(atol, dtype=float), y0.shape))  # writable: one specialisation
        out = solve(self.model, y0, float(t0), np.array(stops, dtype=float), float(rtol), atol, float(max_step),
                    int(max_steps), float(near), float(deadline))
        _SOLVE_READY = True
        self.unlock_pieces()
        warn_clamped(net, a.inflator_int)
        segs = out[4]
        self._run_modes = modes_of(self, segs)
        if getattr(net, "contact", None) is not None:
            from .events import event_states

            net.log_contact_events(event_states(out, self.labels, self._run_modes))
        table = segs[:, :SegmentColumn.EQUALISED + 1].copy()
        table[:, SegmentColumn.EQUALISED] = np.arange(len(segs))
        return out[:4] + (table,) + out[5:]

    def unlock_pieces(self) -> None:
        """Volume splines read on the piece that holds s (outputs, after a run)."""
        self.arrays.cavity_int[:, CavityInt.PIECE] = UNLOCKED

    def solve_ivp_system(self, near: float):
        """This network as the system scipy's other methods integrate (:class:`exchange.engine.system.
        LoweredSystem`), from the network's current discrete state."""
        from .system import LoweredSystem

        return LoweredSystem(self, near)

    def arm(self, t0: float, y0) -> list:
        """From the network's discrete state, every pop vent already above its pop pressure at t0 starts its hold (or
        pops) now, as if its pressure had just crossed it, and every exchange whose downstream cavity is already at
        its close pressure closes; the network takes the new state. Returns their switch labels (for the event
        log)."""
        if not self._armable:
            return []
        from .modes import on_event
        from .switches import switches

        self.load_discrete_state()
        a, labels, value = self.arrays, [], np.empty(1)
        y0 = np.ascontiguousarray(y0, dtype=float)
        for q in self._armable:
            j, close = int(a.switch_target[q]), a.switch_kind[q] == SwitchKind.CLOSE
            armed = OpenState.OPEN if close else OpenState.SHUT
            if a.open_state[j] != armed or not math.isnan(a.hold_start[j]):
                continue
            switches(self.model, np.array([q]), float(t0), y0, math.inf, value)
            if value[0] >= 0.0 if close else value[0] > 0.0:
                on_event(self.model, int(q), float(t0), y0.copy(), math.inf)
                labels.append(self.labels[q])
        if labels:
            self.network.restore(self.current_mode(t0))
        return labels

    def current_mode(self, t_min: float) -> DiscreteState:
        """The network's snapshot of the discrete state now in the model, for a segment from t_min [s]."""
        from .modes import record_segment

        row = np.empty((1, segment_blocks(self.arrays.open_state.size)[4]))
        bits = sum(1 << j for j, e in enumerate(self.arrays.equalised.tolist()) if e)
        record_segment(self.model, row, 0, 0, 0, float(t_min), float(t_min), bits)
        return modes_of(self, row)[0]

    def failure(self) -> str:
        """Why the latest right-hand side failed: a hosted part's exception (:mod:`exchange.engine.hosted`), else no
        temperature for a cavity's internal energy."""
        error = host_of(self.host).error if self.host >= 0 else None
        return NO_TEMPERATURE if error is None else f"{type(error).__name__}: {error}"

    def load_discrete_state(self) -> None:
        """Copy the network's discrete state into the model: equalised flags, open states, hold starts, the dynamic
        body's area intervals, whether hard contact holds it, no volume-spline piece held, and each pop vent's area
        at activation (DELTA LEAKAGE AREA; of one opened by time on an area that follows the dynamic body, NaN until
        it opens)."""
        a, net = self.arrays, self.network
        a.interval[:] = [i if i is not None else 0 for i in getattr(net, "intervals", [0] * len(net.exchanges))]
        a.seat_state[SeatState.HELD] = float(bool(getattr(net, "held", False)))
        reset_sampling(a)
        self.unlock_pieces()  # the segment start locks one (exchange.engine.modes.lock_pieces)
        ei, ef = a.exchange_int, a.exchange_float
        for j in range(len(net.exchanges)):
            pop_vent = self.pop_vents[j]
            a.equalised[j] = net.equalised[j]
            a.open_state[j] = open_state_of(pop_vent, net.popped[j], net.closed[j])
            a.hold_start[j] = math.nan if net.holding_since[j] is None else net.holding_since[j]
            base = net.area_at_activation[j]
            if pop_vent:
                ef[j, ExchangeFloat.AREA_AT_ACTIVATION] = base or 0.0
            elif ei[j, ExchangeInt.DELTA_AREA] and self.by_body[j]:
                ef[j, ExchangeFloat.AREA_AT_ACTIVATION] = math.nan if base is None else base

    def segment_mode(self, code) -> DiscreteState:
        """The network's discrete state during segment ``code`` of the latest :meth:`run`."""
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
            "compiling the engine with numba: about 45 s of CPU measured on this first run, then it is cached "
            "(%s)", os.path.dirname(index) if index else "no cache")
