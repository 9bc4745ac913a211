"""The discrete state of each segment of a run on the engine, read back from its segment table as the network's
:class:`~exchange.network.discrete_state.DiscreteState`."""
from __future__ import annotations

import numpy as np

from exchange.network.discrete_state import DiscreteState

from .layout import ExchangeFloat, ExchangeInt, SegmentColumn, flags_of, segment_blocks

__all__ = ["modes_of"]


def modes_of(engine, segs) -> list:
    """The network's DiscreteState of each row of an engine's segment table (:func:`exchange.engine.modes.
    record_segment`), one object per distinct state (kept in ``engine.modes``)."""
    ne = len(engine.network.exchanges)
    opened, hold, interval, held, _ = (int(c) for c in segment_blocks(ne))
    pop_vents, by_body = engine.pop_vents, engine.by_body
    bits_c, t_c = int(SegmentColumn.EQUALISED), int(SegmentColumn.T_MIN)
    out = []
    for row in np.asarray(segs).tolist():
        bits = int(row[bits_c])
        flags = [flags_of(int(state), pop_vents[j]) for j, state in enumerate(row[opened:opened + ne])]
        popped, closed = tuple(f[0] for f in flags), tuple(f[1] for f in flags)
        holding = tuple(None if h != h else h for h in row[hold:hold + ne])
        intervals = tuple(int(i) if b else None for i, b in zip(row[interval:interval + ne], by_body))
        key = (bits, popped, closed, holding, intervals, row[t_c], bool(row[held]))
        mode = engine.modes.get(key)
        if mode is None:
            mode = engine.modes[key] = DiscreteState(
                popped, holding, _areas_at_activation(engine, popped, key[5]),
                tuple(bool(bits >> j & 1) for j in range(ne)), closed, intervals, key[6])
        out.append(mode)
    return out


def _areas_at_activation(engine, popped, t_min) -> tuple:
    """``Network.area_at_activation`` in a segment starting at t_min: a popped vent's area at its pop; the area
    at the open time of a DELTA LEAKAGE AREA opened by time once a segment starts at or after it
    (:func:`exchange.engine.segment.begin_segment` sets it there); else None."""
    ei, ef, out = engine.arrays.exchange_int, engine.arrays.exchange_float, []
    for j, ex in enumerate(engine.network.exchanges):
        base = float(ef[j, ExchangeFloat.AREA_AT_ACTIVATION])
        if popped[j]:
            out.append(base)
        elif ei[j, ExchangeInt.DELTA_AREA] and ei[j, ExchangeInt.POP] == 0 and t_min >= ex.activation.open_time:
            out.append(base)
        else:
            out.append(None)
    return tuple(out)
