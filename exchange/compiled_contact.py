"""The seat contact's side of the compiled path that runs in Python: its arrays for the model tuple, and the
states around each event of a run, from which the network rebuilds its contact log (:mod:`exchange.compiled_body`
holds the kernels)."""
from __future__ import annotations

import numpy as np

from cavity.rk_compiled import RECORD, DenseSteps

__all__ = ["seat_arrays", "event_states"]


def seat_arrays(seat) -> tuple:
    """``M[25]``, ``M[26]``, ``M[27]`` from a network's lowered contact (``lowered_geometry()["contact"]``: the
    head vector, the node table, the kink displacements) or None (no contact: zeros)."""
    if seat is None:
        seat = np.zeros(3 + 11), np.zeros((0, 4)), np.zeros(0)
    return tuple(np.ascontiguousarray(a, dtype=float) for a in seat)


def event_states(out, labels, modes) -> list:
    """(t, label, state just before, state just after, mode before) of every event of a
    :meth:`CompiledNetwork.run`'s ``out``, with the switch ``labels`` and the segment ``modes``.

    The segment ending at an event is the last one ending at its time before one starting there (the piece
    holding the event may be followed by the tail integrated to it); the state before is the dense output at
    its end, the state after is the next segment's first step record (or the final state)."""
    recs, segs, evs, y_end = out[3], out[4], out[5], out[2]
    n, pre, found = y_end.size, 0, []
    for te, q, _ in evs.tolist():
        while not (segs[pre, 3] == te and (pre + 1 == len(segs) or segs[pre + 1, 2] == te)):
            pre += 1
        first, end, t_min = int(segs[pre, 0]), int(segs[pre, 1]), segs[pre, 2]
        before = DenseSteps(recs[first:end], t_min, te)(te)
        after = recs[int(segs[pre + 1, 0]), RECORD:RECORD + n] if pre + 1 < len(segs) else y_end
        found.append((te, labels[int(q)], before, np.array(after), modes[pre]))
        pre += 1
    return found
