"""The states around each event of a compiled run, from which a network rebuilds its contact log."""
from __future__ import annotations

import numpy as np

from cavity.rk_compiled import RECORD, DenseSteps

from .layout import SegmentColumn

__all__ = ["event_states"]


def event_states(out, labels, modes) -> list:
    """(t, label, state just before, state just after, discrete state before) of every event of an
    :meth:`exchange.engine.engine.Engine.run`'s ``out`` (before its segment table is cut), with the switch ``labels``
    and the segments' ``modes``.

    The segment ending at an event is the last one ending at its time before one starting there (the piece holding
    the event may be followed by the tail integrated to it); the state before is the dense output at its end, the
    state after is the next segment's first step record (or the final state)."""
    recs, segs, evs, y_end = out[3], out[4], out[5], out[2]
    n, pre, found = y_end.size, 0, []
    first_c, end_c, lo_c, hi_c = SegmentColumn.FIRST, SegmentColumn.END, SegmentColumn.T_MIN, SegmentColumn.T_MAX
    for te, q, _ in evs.tolist():
        while not (segs[pre, hi_c] == te and (pre + 1 == len(segs) or segs[pre + 1, lo_c] == te)):
            pre += 1
        first, end, t_min = int(segs[pre, first_c]), int(segs[pre, end_c]), segs[pre, lo_c]
        before = DenseSteps(recs[first:end], t_min, te)(te)
        after = recs[int(segs[pre + 1, first_c]), RECORD:RECORD + n] if pre + 1 < len(segs) else y_end
        found.append((te, labels[int(q)], before, np.array(after), modes[pre]))
        pre += 1
    return found
