"""An FE code's blockage rule with the dynamic body: flags sampled at the explicit code's cycles t_k = k·Δt from the
body's displacement s(t_k), used from cycle k + n on (AreaKind.SAMPLED_OF_BODY).

The rule's area is a step function of s (:mod:`cases.model.fe_dynamic`): interval i of its crossings c_1 < … < c_N
holds area A_i, and a last row (crossing +inf) the area with no flag (before cycle n a run has none). Two integers
per exchange follow it: the interval holding s *now* (``SamplingColumn.CURRENT``, moved by the crossing switches as
the exact rule's interval is) and the interval *in use* (``M.interval``, what the area reads and the segment table
records). A change of the current interval at θ is the state of cycle k = ⌈θ/Δt⌉ (the first cycle whose state
includes it, as :func:`cases.model.fe_sampling.sample_index`); its sample is queued and comes into use at
t_k + n·Δt through the SAMPLE switch (t − due)/Δt, a function of time. Between changes no sample differs from the
one before, so the run stops only where the rule's area changes: the flags at every t_k are those of s(t_k), up to
the solver's location of the crossings (as the exact rule's).

The queue holds at most n + 1 samples (their times are distinct cycles within the last n + 1); a later change at
or before a queued sample's time replaces its interval (the cycle sees the state after it).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .layout import AreaKind, BodyColumn, ExchangeInt, SamplingColumn, TableColumn

__all__ = ["is_sampled", "tracked_interval", "crossing_count", "move_tracked", "sample_time", "note_change",
           "apply_head", "apply_due", "sample_switch", "rederive_sampled", "reset_sampling", "sampling_rows"]

S = SamplingColumn


@njit(cache=True)
def is_sampled(M, j):
    return M.exchange_int[j, ExchangeInt.AREA] == AreaKind.SAMPLED_OF_BODY


@njit(cache=True)
def tracked_interval(M, j):
    """The area interval holding the body's displacement now: the sampled rule's current one, else the one in use."""
    return int(M.sampling[j, S.CURRENT]) if is_sampled(M, j) else M.interval[j]


@njit(cache=True)
def crossing_count(M, j):
    """N, the crossings of exchange j's area along s (a sampled rule's last row, +inf, is its flagless area)."""
    rows = M.table_index[M.exchange_int[j, ExchangeInt.AREA_TABLE], TableColumn.ROWS]
    return rows - 2 if is_sampled(M, j) else rows - 1


@njit(cache=True)
def sample_time(t, step):
    """t_k [s] of the first cycle k >= 0 with k·step >= t (robust to the rounding of t/step)."""
    k = math.ceil(t / step)
    if (k - 1) * step >= t:
        k -= 1
    if k * step < t:
        k += 1
    return max(k, 0) * step


@njit(cache=True)
def note_change(M, j, t):
    """The current interval of exchange j changed at t: the sample of the next cycle t_k >= t takes it (the last
    queued sample when it is at or after t, else a new one)."""
    row = M.sampling[j]
    count = int(row[S.COUNT])
    last = S.QUEUE + 2 * (count - 1)
    if count > 0 and row[last] >= t:
        row[last + 1] = row[S.CURRENT]
        return
    if S.QUEUE + 2 * count + 1 >= row.size:  # full (not reached: n + 1 samples at most): the oldest comes in now
        apply_head(M, j)
        count -= 1
    q = S.QUEUE + 2 * count
    row[q], row[q + 1] = sample_time(t, row[S.STEP]), row[S.CURRENT]
    row[S.COUNT] = count + 1


@njit(cache=True)
def apply_head(M, j):
    """The oldest queued sample of exchange j comes into use."""
    row = M.sampling[j]
    count = int(row[S.COUNT])
    if count == 0:
        return
    M.interval[j] = int(row[S.QUEUE + 1])
    for q in range(S.QUEUE, S.QUEUE + 2 * (count - 1)):
        row[q] = row[q + 2]
    row[S.COUNT] = count - 1


@njit(cache=True)
def _due(row):
    return row[S.QUEUE] + row[S.LAG] * row[S.STEP]


@njit(cache=True)
def apply_due(M, t):
    """Every queued sample due at or before t comes into use (a segment start)."""
    for j in range(M.interval.size):
        if is_sampled(M, j):
            while M.sampling[j, S.COUNT] > 0 and _due(M.sampling[j]) <= t:
                apply_head(M, j)


@njit(cache=True)
def sample_switch(M, j, t):
    """(t − due)/Δt of exchange j's oldest queued sample, due = t_k + n·Δt; 1 without one (not watched)."""
    row = M.sampling[j]
    if row[S.COUNT] == 0:
        return 1.0
    return (t - _due(row)) / row[S.STEP]


@njit(cache=True)
def move_tracked(M, j, i, t):
    """The body's displacement has moved exchange j's area interval to i at t: the interval in use, or a sampled
    rule's current interval and its sample."""
    if is_sampled(M, j):
        M.sampling[j, S.CURRENT] = i
        note_change(M, j, t)
    else:
        M.interval[j] = i


@njit(cache=True)
def rederive_sampled(M, t, y):
    """The current interval of each sampled rule re-derived from the body's displacement when it lies outside by
    more than the slack (:func:`exchange.engine.modes.rederive_intervals`), then the samples due by t used."""
    bd, ei, tx, ti = M.body, M.exchange_int, M.table_x, M.table_index
    s, slack = y[int(bd[BodyColumn.OFFSET])], bd[BodyColumn.SLACK]
    for j in range(M.interval.size):
        if not is_sampled(M, j):
            continue
        start, n = ti[ei[j, ExchangeInt.AREA_TABLE], TableColumn.START], crossing_count(M, j)
        i = int(M.sampling[j, S.CURRENT])
        if (i > 0 and s < tx[start + i] - slack) or (i < n and s > tx[start + 1 + i] + slack):
            move_tracked(M, j, np.searchsorted(tx[start + 1:start + 1 + n], s, side="right"), t)
    apply_due(M, t)


def sampling_rows(geometry, ne: int) -> np.ndarray:
    """The model's ``sampling`` field: per exchange with a sampled rule (``AreaSteps.sampling`` = (step, lag)) its
    step and lag, room for lag + 1 samples (the widest lag sets the width)."""
    lags = [a.sampling[1] for a in geometry.areas.values() if a.sampling is not None]
    out = np.zeros((ne, S.QUEUE + 2 * (max(lags, default=0) + 2)))
    for j, area in geometry.areas.items():
        if area.sampling is not None:
            out[j, S.STEP], out[j, S.LAG] = area.sampling
    return out


def reset_sampling(arrays) -> None:
    """The run's start: each sampled rule's current interval is the one holding s = 0 (a segment start re-derives
    it), its cycle 0 queued when it has a lag (in use from n·Δt on; the network starts it flagless) and nothing
    queued otherwise (the network starts it on that interval)."""
    if not arrays.sampling[:, S.STEP].any():  # no sampled rule in this model
        return
    tx, ti = arrays.table_x, arrays.table_index
    for j in np.flatnonzero(arrays.exchange_int[:, ExchangeInt.AREA] == AreaKind.SAMPLED_OF_BODY):
        k = arrays.exchange_int[j, ExchangeInt.AREA_TABLE]
        start, n = ti[k, TableColumn.START], ti[k, TableColumn.ROWS] - 2
        row = arrays.sampling[j]
        row[S.CURRENT] = np.searchsorted(tx[start + 1:start + 1 + n], 0.0, side="right")
        row[S.COUNT:] = 0.0
        if row[S.LAG] > 0:
            row[S.QUEUE + 1], row[S.COUNT] = row[S.CURRENT], 1.0
