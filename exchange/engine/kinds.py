"""Every kind the engine tests, as an IntEnum, with the predicates that group them (re-exported by
:mod:`exchange.engine.layout`, the model's layout): energy models, fluids, volumes, areas, inflators, an exchange's
open state, the laws' kink variables and the switches with their labels in the event log."""
from __future__ import annotations

from enum import IntEnum

from numba import njit

__all__ = ["Energy", "Fluid", "VolumeKind", "AreaKind", "InflatorKind", "OpenState", "open_state_of", "flags_of",
           "KinkVariable", "SwitchKind", "SWITCH_LABELS", "is_kink", "is_body_switch", "is_seat_switch",
           "one_way_direction"]


class Energy(IntEnum):
    """How a cavity's energy is modelled (``CavityInt.ENERGY``)."""
    ADIABATIC = 0
    ISOTHERMAL = 1  # also a hydraulic cavity: no energy unknown
    HEAT_LOSS = 2  # h_c·A·(T − T_amb)
    WALL = 3  # a real-gas cavity's wall (hosted)


class Fluid(IntEnum):
    GAS = 0  # ideal-gas mixture of cp(T) polynomials
    HYDRAULIC = 1
    REAL_GAS = 2  # CoolProp (hosted)


class VolumeKind(IntEnum):
    FIXED = 0
    TABLE = 1  # V(t) table
    SCALED_MESH = 2  # mesh volume × s(t)³
    SPLINE_OF_TIME = 3  # wrapped around prescribed bodies
    SPLINE_OF_BODY = 4  # wrapped around the dynamic body: of its displacement


class AreaKind(IntEnum):
    CONSTANT = 0
    STEPS_OF_TIME = 1  # a blocked leakage area with prescribed motion
    STEPS_OF_BODY = 2  # blocked by the dynamic body: per interval of its displacement
    MOVING_SURFACE = 3  # a leakage surface on a vertex trajectory (blockage.moving_area)
    SAMPLED_OF_BODY = 4  # an FE rule's area of the dynamic body's displacement, sampled at its time steps (sampled.py)


class InflatorKind(IntEnum):
    MASS_TEMPERATURE = 0
    TANK_TEST = 1
    PRESSURE_MASS = 2
    DUAL_PRESSURE = 3
    REAL_GAS_TANK_TEST = 4


class OpenState(IntEnum):
    """``open_state`` of an exchange."""
    SHUT = 0  # a pop vent that has not popped
    OPEN = 1
    CLOSED = 2  # closed for good at its close pressure


def open_state_of(pop_vent: bool, popped: bool, closed: bool) -> int:
    """An exchange's OpenState from the network's flags: closed for good, a pop vent not popped yet, or open."""
    return OpenState.CLOSED if closed else OpenState.SHUT if pop_vent and not popped else OpenState.OPEN


def flags_of(state: int, pop_vent: bool) -> tuple:
    """(popped, closed) of an exchange in OpenState ``state``: the inverse of :func:`open_state_of`."""
    return bool(pop_vent and state != OpenState.SHUT), state == OpenState.CLOSED


class KinkVariable(IntEnum):
    UPSTREAM_PRESSURE = 0  # max(p_a, p_b): a row of a Cd table of pressure
    PRESSURE_DIFFERENCE = 1  # |p_a − p_b|: a row of a leakage table
    BODY_DISPLACEMENT = 2  # the dynamic body's displacement s [m] (ExchangeInt.BODY_LOAD): a seal's closure, its range


class SwitchKind(IntEnum):
    """The switch functions the engine watches (exchange.engine.switches)."""
    CHOKE = 0  # the orifice law's choke, where its second derivative jumps
    JOIN = 1  # the orifice law's C¹ join at |Δp|/p = LINEAR_BELOW
    REVERSAL = 2  # a one-way exchange's Δp reaching 0
    EQUALISE = 3  # |Δp|/p falling below EQUALISED_BELOW
    RELEASE = 4  # |Δp|/p rising above RELEASED_ABOVE
    LAW_KINK = 5  # a row of a law's table (kink_int, kink_x)
    POP = 6  # Δp reaching the pop pressure
    POP_DROP = 7  # Δp falling back below it during the hold
    POP_HOLD = 8  # the hold's end (a function of time)
    CLOSE = 9  # the downstream cavity reaching the close pressure
    TURN = 10  # the dynamic body's turning point
    CROSSING_UP = 11  # its displacement reaching the crossing above its area interval
    CROSSING_DOWN = 12  # ... below
    KNOT_UP = 13  # the knot above the held piece of the pushed cavity's volume spline
    KNOT_DOWN = 14  # ... below
    SEAT = 15  # hard contact: lift-off while held, impact while free
    SEAT_KINK = 16  # a kink of the seat's force
    SAMPLE = 17  # an FE rule's sampled flags coming into use at their cycle (a function of time)


#: The label of each switch kind in the event log (``<exchange>:<label>``; a law kink's ``kink<row>``, a seat kink's
#: ``kink-<i>``).
SWITCH_LABELS = {SwitchKind.CHOKE: "choke", SwitchKind.JOIN: "join", SwitchKind.REVERSAL: "reversal",
                 SwitchKind.EQUALISE: "equalise", SwitchKind.RELEASE: "release", SwitchKind.LAW_KINK: "kink",
                 SwitchKind.POP: "pop", SwitchKind.POP_DROP: "pop-drop", SwitchKind.POP_HOLD: "pop-hold",
                 SwitchKind.CLOSE: "close", SwitchKind.TURN: "turn", SwitchKind.CROSSING_UP: "contact-up",
                 SwitchKind.CROSSING_DOWN: "contact-down", SwitchKind.KNOT_UP: "knot-up",
                 SwitchKind.KNOT_DOWN: "knot-down", SwitchKind.SEAT: "seat", SwitchKind.SEAT_KINK: "kink-",
                 SwitchKind.SAMPLE: "sample"}


@njit(cache=True)
def is_kink(kind):
    """A switch at a kink of the right-hand side in the state: its event changes neither the state nor the
    function (choke, join, reversal, a law's table row)."""
    return kind == SwitchKind.CHOKE or kind == SwitchKind.JOIN or kind == SwitchKind.REVERSAL \
        or kind == SwitchKind.LAW_KINK


@njit(cache=True)
def is_body_switch(kind):
    """A switch of the dynamic body: its turning point, area crossings, volume-spline knots and seat."""
    return kind == SwitchKind.TURN or kind == SwitchKind.CROSSING_UP or kind == SwitchKind.CROSSING_DOWN \
        or kind == SwitchKind.KNOT_UP or kind == SwitchKind.KNOT_DOWN or is_seat_switch(kind)


@njit(cache=True)
def is_seat_switch(kind):
    return kind == SwitchKind.SEAT or kind == SwitchKind.SEAT_KINK


@njit(cache=True)
def one_way_direction(kind):
    """+1 or −1 for a switch the body's displacement can cross in one direction only (it leaves its interval or
    spline piece through that end) or time crosses (an FE rule's sample), 0 for the others."""
    if kind == SwitchKind.CROSSING_UP or kind == SwitchKind.KNOT_UP or kind == SwitchKind.SAMPLE:
        return 1.0
    if kind == SwitchKind.CROSSING_DOWN or kind == SwitchKind.KNOT_DOWN:
        return -1.0
    return 0.0
