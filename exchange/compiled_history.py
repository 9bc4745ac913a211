"""The history of a run, read back in one numba call from its states at the output times.

The states come from ``Trajectory.sample`` (the compiled DOP853's step records in one compiled call,
:func:`cavity.rk_compiled.dense_samples`, or solve_ivp's dense output); :func:`history_rows` then evaluates the
cavity states, each exchange's flow and area at every output time with the kernels the right-hand side uses
(:func:`exchange.compiled_rhs.states`, :func:`~exchange.compiled_rhs.exchange_flow`,
:func:`~exchange.compiled_rhs.exchange_area`): no physics is written twice.

- the segment of time t: the last segment starting at or before t (right limit at a switch),
  ``Trajectory.segment_index``;
- the discrete state of a segment: of its mode the equalised flags (``mode[3]``), the popped flags (``mode[0]``)
  and the dynamic body's area intervals act, passed per segment as ``eqs``, ``ops`` (0 while a pop vent is
  shut) and ``ivs``; a DELTA LEAKAGE AREA's area at activation is set once per run (``ef[:, 9]``) and acts only
  while its exchange is open;
- the row: the columns of :func:`cases.results.readback.history_columns`, time [s], then per cavity pressure
  [Pa], temperature [K], mass [kg], volume [m^3], then per exchange mass flow [kg/s] (up → down) and flow area
  [m^2], then the unknowns asked for (a real-gas wall's temperatures [K]).
"""
from __future__ import annotations

import numpy as np
from numba import njit


from .compiled_rhs import MASS, P, TT, V, exchange_area, exchange_flow, states
from .lowered_columns import UNLOCKED

__all__ = ["history_rows", "row_width", "equalised_per_segment", "opened_per_segment", "samples", "history"]


def row_width(n_cavities: int, n_exchanges: int) -> int:
    """Columns of a history row: time, 4 per cavity, 2 per exchange."""
    return 1 + 4 * n_cavities + 2 * n_exchanges


@njit(cache=True)
def history_rows(M, ys, idx, eqs, ops, ivs, times, ycols):
    """History rows at ``times`` [s] from the states ``ys`` (len(times), n) there, each in the discrete state of
    segment ``idx[r]``.

    ``M``: the model tuple of :class:`exchange.compiled.CompiledNetwork`; ``eqs`` (segments, exchanges) int: 1 where
    an exchange is equalised (held closed) during the segment; ``ops`` (segments, exchanges) int: 0 where a pop
    vent has not popped during the segment (:func:`opened_per_segment`); ``ivs`` (segments, exchanges) int: the
    dynamic body's area interval (:func:`intervals_per_segment`); ``ycols``: unknowns appended as they are (a
    real-gas wall's temperatures). Returns (ok, rows (len(times), width + len(ycols))); ok is False when a
    temperature solve failed (that row then holds the first guess). The model's scratch is not touched: the Newton
    first guesses start at the cavities' initial temperatures.
    """
    rows, breaks, linear, Mm, tx, ty, ti, ci, cf, ii, if_, irows, ei, ef, amb, ledger, T_guess, st, n, row, eq = M[:21]
    nc, ne = ci.shape[0], ei.shape[0]
    guess, eq_now, op_now = cf[:, 0].copy(), np.empty(ne, np.int64), np.empty(ne, np.int64)
    iv_now = np.empty(ne, np.int64)
    st_, n_, row_ = np.empty_like(st), np.empty_like(n), np.empty_like(row)
    width = 1 + 4 * nc + 2 * ne
    out = np.empty((times.size, width + ycols.size))
    ok = True
    for r in range(times.size):
        t, y, i = times[r], ys[r], idx[r]
        eq_now[:] = eqs[i]
        op_now[:] = ops[i]
        iv_now[:] = ivs[i]
        ok &= states(rows, breaks, linear, Mm, tx, ty, ti, ci, cf, t, y, guess, st_, n_, row_)
        out[r, 0] = t
        for c in range(nc):
            out[r, 1 + 4 * c], out[r, 2 + 4 * c] = st_[c, P], st_[c, TT]
            out[r, 3 + 4 * c], out[r, 4 + 4 * c] = st_[c, MASS], st_[c, V]
        base = 1 + 4 * nc
        for j in range(ne):
            out[r, base + 2 * j] = exchange_flow(ei, ef, eq_now, op_now, iv_now, tx, ty, ti, st_, amb, j, t)
            out[r, base + 2 * j + 1] = exchange_area(ei, ef, op_now, iv_now, tx, ty, ti, j, t)
        for c in range(ycols.size):
            out[r, width + c] = y[ycols[c]]
    return ok, out


def _network_mode(mode):
    """The plain network's part of a segment's mode (a scene network wraps it: (mode, intervals, held))."""
    return mode[0] if mode is not None and len(mode) == 3 else mode


def equalised_per_segment(modes, n_exchanges: int) -> np.ndarray:
    """(segments, exchanges) int: the equalised flags (``mode[3]``) of each segment's discrete state."""
    eqs = np.zeros((len(modes), n_exchanges), dtype=np.int64)
    for i, mode in enumerate(modes):
        mode = _network_mode(mode)
        if mode is not None and len(mode) > 3:
            eqs[i] = mode[3]
    return eqs


def intervals_per_segment(modes, n_exchanges: int) -> np.ndarray:
    """(segments, exchanges) int: the dynamic body's area interval of each exchange in each segment (0: none)."""
    ivs = np.zeros((len(modes), n_exchanges), dtype=np.int64)
    for i, mode in enumerate(modes):
        if mode is not None and len(mode) == 3:
            ivs[i] = [k if k is not None else 0 for k in mode[1]]
    return ivs


def opened_per_segment(modes, pop_vents) -> np.ndarray:
    """(segments, exchanges) int: 0 where exchange j is a pop vent (``pop_vents[j]``) not popped (``mode[0]``)
    during the segment, 2 where it has closed at its close pressure (``mode[4]``), else 1."""
    ops = np.ones((len(modes), len(pop_vents)), dtype=np.int64)
    for i, mode in enumerate(modes):
        mode = _network_mode(mode)
        for j, pop in enumerate(pop_vents):
            if mode is not None and len(mode) > 4 and mode[4][j]:
                ops[i, j] = 2
            elif pop and not (mode is not None and mode[0][j]):
                ops[i, j] = 0
    return ops


def samples(traj, times) -> tuple[np.ndarray, np.ndarray]:
    """(states (len(times), n), segment index per time) of a trajectory at ``times`` [s] (``Trajectory.sample``:
    from the compiled DOP853's records in one call, else from solve_ivp's dense output)."""
    times = np.ascontiguousarray(times, dtype=float)
    return traj.sample(times), np.asarray(traj.segment_index(times), dtype=np.int64).reshape(-1)


def history(fast, traj, times, ycols=()) -> tuple[bool, np.ndarray]:
    """(ok, history rows) of a trajectory at ``times`` [s] (see :func:`history_rows`; ``ycols``: unknowns
    appended as columns)."""
    times = np.ascontiguousarray(times, dtype=float)
    ne = len(fast.network.exchanges)
    ys, idx = samples(traj, times)
    fast.model[7][:, 9] = UNLOCKED  # volume splines on the pieces that hold s
    eqs = equalised_per_segment(traj.modes, ne)
    ops = opened_per_segment(traj.modes, fast.model[12][:, 6])
    ivs = intervals_per_segment(traj.modes, ne)
    return history_rows(fast.model, np.ascontiguousarray(ys), idx, eqs, ops, ivs, times,
                        np.asarray(ycols, dtype=np.int64))
