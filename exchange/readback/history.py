"""The history of a run, read back in one numba call from its states at the output times.

The states come from ``Trajectory.sample`` (the compiled DOP853's step records in one compiled call,
:func:`cavity.rk_compiled.dense_samples`, or solve_ivp's dense output); :func:`history_rows` then evaluates every
cavity's state, each exchange's flow and area and each inflator's flow and temperature at every output time with
the kernels the right-hand side runs (:func:`exchange.engine.gas.states`, :func:`exchange.engine.flows.
exchange_flow`, :func:`~exchange.engine.flows.exchange_area`, :func:`exchange.engine.inflators.inflator_flow`):
nothing is written twice. Each output time is read in the discrete state of its segment (the last starting at or
before it: the right limit at a switch).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from exchange.engine.arrays import copy_into
from exchange.engine.flows import exchange_area, exchange_flow
from exchange.engine.gas import reset_temperature_guesses, states
from exchange.engine.inflators import inflator_flow
from exchange.engine.layout import ExchangeInt, InflatorFloat, StateColumn, open_state_of

__all__ = ["HistoryLayout", "history_rows", "history", "segment_states"]


@dataclass(frozen=True)
class HistoryLayout:
    """Where each quantity sits in a row of :func:`history_rows`: time, then per cavity pressure [Pa], temperature
    [K], mass [kg] and volume [m^3], then per exchange mass flow [kg/s] (first side → second) and flow area [m^2],
    then per inflator mass flow [kg/s] and gas temperature [K], then the unknowns asked for as they are."""

    cavities: int
    exchanges: int
    inflators: int

    @property
    def exchange_start(self) -> int:
        return 1 + 4 * self.cavities

    @property
    def inflator_start(self) -> int:
        return self.exchange_start + 2 * self.exchanges

    @property
    def width(self) -> int:
        return self.inflator_start + 2 * self.inflators


@njit(cache=True)
def history_rows(M, ys, idx, eqs, ops, ivs, times, ycols):
    """(ok, rows) at ``times`` [s] from the states ``ys`` (len(times), n) there, each row in the discrete state of
    segment ``idx[r]``: ``eqs``, ``ops`` and ``ivs`` (segments, exchanges) the equalised flags, open states and the
    dynamic body's area intervals of each segment (:func:`segment_states`). ok is False when a temperature solve
    failed (that row then holds the first guess). The model's discrete state is restored afterwards; Newton's first
    guesses start from the cavities' initial temperatures."""
    nc, ne, ni = M.cavity_int.shape[0], M.exchange_int.shape[0], M.inflator_int.shape[0]
    saved = (M.equalised.copy(), M.open_state.copy(), M.interval.copy())
    reset_temperature_guesses(M)
    e0 = 1 + 4 * nc
    i0 = e0 + 2 * ne
    width = i0 + 2 * ni
    out = np.empty((times.size, width + ycols.size))
    st, ok, loaded = M.state, True, -1
    for r in range(times.size):
        t, y, i = times[r], ys[r], idx[r]
        if i != loaded:  # the discrete state of the row's segment
            _load_discrete_state(M, eqs[i], ops[i], ivs[i])
            loaded = i
        ok &= states(M, t, y)
        out[r, 0] = t
        for c in range(nc):
            out[r, 1 + 4 * c], out[r, 2 + 4 * c] = st[c, StateColumn.P], st[c, StateColumn.T]
            out[r, 3 + 4 * c], out[r, 4 + 4 * c] = st[c, StateColumn.MASS], st[c, StateColumn.V]
        for j in range(ne):
            out[r, e0 + 2 * j] = exchange_flow(M, j, t)
            out[r, e0 + 2 * j + 1] = exchange_area(M, j, t)
        for q in range(ni):
            mdot, T_in = inflator_flow(M, q, t)
            out[r, i0 + 2 * q] = mdot if t >= M.inflator_float[q, InflatorFloat.START] else 0.0
            out[r, i0 + 2 * q + 1] = T_in
        for c in range(ycols.size):
            out[r, width + c] = y[ycols[c]]
    _load_discrete_state(M, saved[0], saved[1], saved[2])
    return ok, out


@njit(cache=True)
def _load_discrete_state(M, equalised, open_state, interval):
    """The model's equalised flags, open states and the dynamic body's area intervals."""
    copy_into(M.equalised, equalised)
    copy_into(M.open_state, open_state)
    copy_into(M.interval, interval)


def segment_states(modes, pop_vents) -> tuple:
    """(equalised flags, open states, area intervals), each (segments, exchanges) int, of each segment's
    :class:`~exchange.network.DiscreteState` (None: the initial state)."""
    ne = len(pop_vents)
    eqs = np.zeros((len(modes), ne), dtype=np.int64)
    ops = np.zeros((len(modes), ne), dtype=np.int64)
    ivs = np.zeros((len(modes), ne), dtype=np.int64)
    for i, mode in enumerate(modes):
        for j in range(ne):
            if mode is None:  # the initial state
                ops[i, j] = open_state_of(pop_vents[j], False, False)
                continue
            eqs[i, j] = mode.equalised[j]
            ops[i, j] = open_state_of(pop_vents[j], mode.popped[j], mode.closed[j])
            ivs[i, j] = mode.intervals[j] if mode.intervals[j] is not None else 0
    return eqs, ops, ivs


def history(engine, traj, times, ycols=()) -> tuple:
    """(ok, rows) of a trajectory at ``times`` [s] on a network's engine (:func:`history_rows`; ``ycols``: unknowns
    appended as columns)."""
    times = np.ascontiguousarray(times, dtype=float)
    ys = np.ascontiguousarray(traj.sample(times))
    idx = np.asarray(traj.segment_index(times), dtype=np.int64).reshape(-1)
    engine.unlock_pieces()
    eqs, ops, ivs = segment_states(traj.modes, engine.arrays.exchange_int[:, ExchangeInt.POP] == 1)
    return history_rows(engine.model, ys, idx, eqs, ops, ivs, times, np.asarray(ycols, dtype=np.int64))
