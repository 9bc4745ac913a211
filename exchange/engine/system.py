"""The lowered network as the system :func:`cavity.integration.integrate` steps with scipy's other methods.

LSODA, Radau, BDF, RK45 and RK23 run through ``solve_ivp`` segment by segment; what they integrate and watch is the
engine's, the same kernels the compiled DOP853 (:func:`exchange.engine.solver.solve`) calls: the right-hand side
(:func:`exchange.engine.rhs.rhs`), the switch functions (:func:`exchange.engine.switches.switches`), which of them
are watched and in which direction (:func:`exchange.engine.segment.directions`), the segment start
(:func:`exchange.engine.segment.begin_segment`: equalised exchanges, the dynamic body's area intervals and spline
pieces) and what a switch does (:func:`exchange.engine.modes.on_event`). The discrete state lives in the model, as on
the compiled DOP853; the network's snapshot of it per segment comes from :meth:`exchange.engine.engine.Engine.
current_mode`.
"""
from __future__ import annotations

import math

import numpy as np

from .inflators import warn_clamped
from .modes import on_event
from .rhs import rhs
from .segment import begin_segment, directions
from .switches import switches

__all__ = ["LoweredSystem"]


class LoweredSystem:
    """An :class:`exchange.engine.engine.Engine` as an ``integrate`` system (see there for the protocol).

    ``near``: a switch this close to zero at a segment start is watched against its trend (as
    :func:`cavity.integration._directions`)."""

    path = "compiled, solve_ivp"

    def __init__(self, fast, near: float):
        self.fast, self.network, self.near = fast, fast.network, float(near)
        self.breakpoints = self.network.breakpoints
        self.coupled_unknowns = getattr(self.network, "coupled_unknowns", None)
        self._seg = (0.0, math.inf)  # start and end of the current segment [s]
        self._last = (-1, math.nan, 0.0)  # switch index, time and direction of the latest event
        self._watch = (np.empty(0, np.int64), np.empty(0))
        self._cache = (None, None)
        fast.load_discrete_state()

    def arm(self, t0: float, y0) -> list:
        """Pop vents already above their pop pressure at the start (:meth:`Engine.arm`)."""
        return self.fast.arm(t0, y0)

    def begin_segment(self, t0: float, t1: float, y0) -> None:
        """Segment start on the compiled kernels: the equalised modes, then the watched switches and directions."""
        M = self.fast.model
        y0 = np.ascontiguousarray(y0, dtype=float)
        self._seg = (float(t0), float(t1))
        begin_segment(M, float(t0), y0, float(t1))
        q, t, d = self._last
        self._watch = directions(M, float(t0), y0, float(t1), int(q), float(t), float(d), self.near)
        self._cache = (None, None)

    def rhs(self, t: float, y) -> np.ndarray:
        """d(unknowns)/dt on the compiled right-hand side in the current discrete state."""
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty_like(y)
        if not rhs(self.fast.model, float(t), y, out, self._seg[1]):
            raise ArithmeticError(f"at t = {t:.9g} s: {self.fast.failure()}")
        warn_clamped(self.network, self.fast.arrays.inflator_int)
        return out

    def _values(self, t: float, y) -> np.ndarray:
        """Every watched switch at (t, y), in one compiled call (states solved once), kept for the next call."""
        y = np.ascontiguousarray(y, dtype=float)
        key = (float(t), y.tobytes())
        if self._cache[0] != key:
            wq = self._watch[0]
            vals = np.empty(wq.size)
            switches(self.fast.model, wq, float(t), y, self._seg[1], vals)
            self._cache = (key, vals)
        return self._cache[1]

    def events(self) -> list:
        """The watched switch functions of this segment, each with its ``label`` and ``direction``."""
        out = []
        for i, (q, d) in enumerate(zip(*self._watch)):
            def g(t, y, i=i):
                return self._values(t, y)[i]

            g.label, g.direction, g.index = self.fast.labels[int(q)], float(d), i
            out.append(g)
        return out

    def on_event(self, t: float, y, label: str) -> np.ndarray:
        """Apply the switch ``label`` that fired at t (it may set the body's state in ``y``, an impact)."""
        wq, wd = self._watch
        i = next(i for i, q in enumerate(wq) if self.fast.labels[int(q)] == label)
        q = int(wq[i])
        y = np.array(y, dtype=float)
        before, mode = y.copy(), self.snapshot()
        on_event(self.fast.model, q, float(t), y, self._seg[1])
        self._last = (q, float(t), float(wd[i]))
        if getattr(self.network, "contact", None) is not None:
            self.network.log_contact_events([(float(t), label, before, y.copy(), mode)])
        return y

    def snapshot(self):
        """The network's discrete state during the current segment (:meth:`Engine.current_mode`)."""
        return self.fast.current_mode(self._seg[0])

    def describe(self, t: float, y) -> str:
        return self.network.describe(t, y)
