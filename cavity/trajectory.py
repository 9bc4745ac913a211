"""The solution of an integration: a chain of dense-output segments, the discrete state in force on each, the
solver's statistics and the event log (what :func:`cavity.integration.integrate` returns)."""
from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Trajectory"]


@dataclass
class Trajectory:
    """The solution as a chain of dense-output segments, with the solver's statistics and the event log."""

    segments: list = field(default_factory=list)
    modes: list = field(default_factory=list)  # the system's discrete state during each segment
    step_times: list = field(default_factory=list)
    events: list = field(default_factory=list)
    stats: dict = field(default_factory=lambda: {"steps": 0, "rhs_calls": 0, "jacobians": 0, "lu_decompositions": 0,
                                                 "restarts": 0, "events": 0, "path": "python"})
    last_event: tuple | None = None  # (label, time, direction) of the switch that ended the last segment
    deadline: float = math.inf  # time.perf_counter() after which the run stops (SolverOptions.max_wall)
    stalls: int = 0  # events in a row at the same time
    path: str = "python"  # which integrator ran: "compiled" (cavity.rk_compiled), "compiled, solve_ivp" (scipy's
    #: methods on the engine's kernels) or "python" (solve_ivp on a plain Python system)
    #: compiled path: (step records, segment table) of the compiled solver, read back by exchange.readback.history
    compiled_records: tuple | None = field(default=None, repr=False)

    def __call__(self, t: float) -> np.ndarray:
        """State at time t (right limit at a breakpoint)."""
        return self.segments[int(self.segment_index(t))](t)

    def mode_at(self, t: float):
        """The discrete state (``system.snapshot()``) in force at time t (right limit at a switch)."""
        return self.modes[int(self.segment_index(t))]

    def segment_index(self, t):
        """The segment holding t (a time or an array): the last starting at or before t, clipped."""
        if len(self.__dict__.get("_starts", ())) != len(self.segments):
            self._starts = np.array([s.t_min for s in self.segments])
            self._start_list = self._starts.tolist()
        if np.ndim(t) == 0:
            return min(max(bisect.bisect_right(self._start_list, t) - 1, 0), len(self.segments) - 1)
        return np.clip(np.searchsorted(self._starts, t, side="right") - 1, 0, len(self.segments) - 1)

    def sample(self, times) -> np.ndarray:
        """States at ``times`` (sorted), shape (len(times), n): from the compiled DOP853's records in one compiled
        call (:func:`cavity.rk_compiled.dense_samples`), else segment by segment."""
        times = np.asarray(times, dtype=float)
        if self.compiled_records is not None and len(self.compiled_records[1]) == len(self.segments):
            from .rk_compiled import dense_samples

            recs, segs = self.compiled_records
            return dense_samples(recs, segs, np.ascontiguousarray(times.reshape(-1)))[0]
        idx = self.segment_index(times)
        out = np.empty((times.size, self.segments[0](self.segments[0].t_min).size))
        for i in np.unique(idx):
            sel = idx == i
            out[sel] = self.segments[i](times[sel]).T
        return out

    @property
    def t_final(self) -> float:
        return self.segments[-1].t_max
