"""The discrete state of a cavity network and its switches: choking, flow reversal, the equalised mode of a
two-way exchange, the orifice law's C¹ join, table kinks and pop vents (with hold), and what each switch does."""
from __future__ import annotations

import math

import numpy as np

from .activation import arm_pop_vents
from .equalised import EQUALISED_BELOW, RELEASED_ABOVE
from .law_kinks import kink_switches
from .orifice import LINEAR_BELOW
from .vent import GasPoint

__all__ = ["NetworkSwitches", "gas_point"]

_LIQUID = np.ones(1)


def _labelled(func, label):
    func.label = label
    return func


def gas_point(state) -> GasPoint:
    """The flow-law view of a cavity state (a liquid has no R, γ or enthalpy: NaN, NaN, 0)."""
    if getattr(state, "fluid", None) is not None:  # real gas
        from .realgas_orifice import real_gas_point

        return real_gas_point(state)
    mix, T = state.mixture, state.temperature
    if mix is None:  # hydraulic
        return GasPoint(state.pressure, T, state.density, math.nan, math.nan, 0.0, _LIQUID)
    if mix.mass <= 0.0:
        return GasPoint(state.pressure, T, 0.0, 1.0, 1.4, 0.0, state.masses)
    return GasPoint(state.pressure, T, state.density, mix.gas_constant, mix.gamma(T), state.specific_enthalpy,
                    state.masses / mix.mass)


class NetworkSwitches:
    """The switch functions and discrete state of :class:`exchange.network.Network` (mixed into it): which
    switches are watched, and what firing each one does. Uses the network's ``exchanges``, ``cavities``,
    ``ambient``, ``states``, ``input_time`` and ``base_area``."""

    def snapshot(self) -> tuple:
        """The discrete state (for reading results back on a segment)."""
        return (tuple(self.popped), tuple(self.holding_since), tuple(self.area_at_activation),
                tuple(self.equalised))

    def restore(self, mode) -> None:
        if mode is not None:
            self.popped, self.holding_since, self.area_at_activation = (list(m) for m in mode[:3])
            self.equalised = list(mode[3]) if len(mode) > 3 else [False] * len(self.exchanges)

    def can_equalise(self, index: int) -> bool:
        """Exchange ``index`` has an equalised mode: a pneumatic law between two gas cavities, or two-way to
        ambient."""
        ex = self.exchanges[index]
        if ex.law.prescribed or not ex.law.pneumatic or not (ex.two_way or ex.downstream is not None):
            return False
        return all(getattr(self.cavities[i], "kind", "gas") == "gas" for i in (ex.upstream, ex.downstream)
                   if i is not None)

    def events(self) -> list:
        """Switch functions valid in the current discrete state.

        Per exchange: choking (p_low − p_crit, pneumatic laws), because the orifice law's second derivative jumps
        where flow chokes; for an outflow-only vent, Δp = 0, where its flow stops (a kink). A two-way pneumatic
        exchange has no switch at Δp = 0 (its laws are C¹ there; a switch would fire on every overshoot of the
        sliding state) but an equalised mode: "equalise" fires when |Δp|/p falls to :data:`EQUALISED_BELOW` and
        holds it closed, "release" when it rises to :data:`RELEASED_ABOVE` and opens it again; and, for a vent
        with a pop pressure not yet open, the pop crossing, or while holding, the drop below it and the end of
        the hold time. The orifice law (and fabric leakage, which uses it) changes form at |Δp|/p =
        :data:`~exchange.orifice.LINEAR_BELOW` (a C¹ join): "join" stops the integrator there too, so that no
        step and no dense output straddles it. A table law stops at its rows in the same way ("kink<row>":
        :func:`exchange.law_kinks.kink_switches`).
        """
        out = []
        for j, ex in enumerate(self.exchanges):
            if not ex.law.prescribed:
                if ex.law.pneumatic:
                    out.append(_labelled(lambda t, y, j=j: self._choke_switch(t, y, j), f"{ex.name}:choke"))
                if getattr(ex.law, "orifice_join", False):
                    out.append(_labelled(lambda t, y, j=j: self._dp_relative(t, y, j) / LINEAR_BELOW - 1.0,
                                         f"{ex.name}:join"))
                if ex.downstream is None and not ex.two_way:  # one-way: the flow stops at Δp = 0 (a kink)
                    out.append(_labelled(lambda t, y, j=j: self._dp_switch(t, y, j), f"{ex.name}:reversal"))
                elif self.can_equalise(j):  # two-way: held closed once equalised, opened when driven apart
                    kind, level = ("release", RELEASED_ABOVE) if self.equalised[j] else ("equalise", EQUALISED_BELOW)
                    out.append(_labelled(lambda t, y, j=j, c=level: self._dp_relative(t, y, j) / c - 1.0,
                                         f"{ex.name}:{kind}"))
                out += kink_switches(self, j)  # rows of a Cd table of pressure or of a leakage table
            act = ex.activation
            if act is None or act.pop_pressure is None or self.popped[j]:
                continue
            if self.holding_since[j] is None:
                out.append(_labelled(lambda t, y, j=j: self._pop_switch(t, y, j), f"{ex.name}:pop"))
            else:
                out.append(_labelled(lambda t, y, j=j: self._pop_switch(t, y, j), f"{ex.name}:pop-drop"))
                due = self.holding_since[j] + act.hold_time
                out.append(_labelled(lambda t, y, due=due, h=act.hold_time: (t - due) / h, f"{ex.name}:pop-hold"))
        return out

    def _pressures(self, t, y, j):
        ex = self.exchanges[j]
        states = self.states(self.input_time(t), y)
        pa = states[ex.upstream].pressure
        pb = self.ambient.pressure if ex.downstream is None else states[ex.downstream].pressure
        return states, pa, pb

    def _dp_relative(self, t, y, j) -> float:
        """|p_a − p_b| / max(p_a, p_b) of exchange j [-]."""
        _, pa, pb = self._pressures(t, y, j)
        return abs(pa - pb) / max(pa, pb)

    def _dp_switch(self, t, y, j):
        _, pa, pb = self._pressures(t, y, j)
        return (pa - pb) / max(pa, pb)

    def _choke_switch(self, t, y, j):
        ex = self.exchanges[j]
        states, pa, pb = self._pressures(t, y, j)
        if pa >= pb:
            hi, lo, point = pa, pb, gas_point(states[ex.upstream])
        else:
            hi, lo = pb, pa
            point = self._ambient_point if ex.downstream is None else gas_point(states[ex.downstream])
        return (lo - point.choke_ratio() * hi) / hi

    def _pop_switch(self, t, y, j):
        _, pa, pb = self._pressures(t, y, j)
        pop = self.exchanges[j].activation.pop_pressure
        return (pa - pb - pop) / max(pop, pb)

    def on_event(self, t, y, label):
        """Apply a switch: a pop crossing starts the hold (or opens at once), a drop re-arms, a hold end opens."""
        name, _, kind = label.rpartition(":")
        j = next((k for k, ex in enumerate(self.exchanges) if ex.name == name), None)
        if j is not None and kind in ("equalise", "release"):
            self.equalised[j] = kind == "equalise"
            return y
        if j is None or not kind.startswith("pop"):
            return y
        act = self.exchanges[j].activation
        if kind == "pop" and act.hold_time > 0.0:
            self.holding_since[j] = t
        elif kind == "pop-drop":
            self.holding_since[j] = None
        else:
            self.popped[j] = True
            self.area_at_activation[j] = self.base_area(j, t)
        return y

    arm = arm_pop_vents  # see there

