"""The lowered model: every array the compiled engine reads and writes, by name, its columns, and (from
:mod:`exchange.engine.kinds`) every kind it tests.

A network lowers (:mod:`exchange.engine.lower`) to one :class:`Model`, a numba StructRef: kernels receive it as one
pointer (a call costs what a call with two scalars costs, whatever the model holds) and read its fields by name,
``M.exchange_float[j, ExchangeFloat.AREA]``. The same numpy arrays are kept on the Python side as a
:class:`ModelArrays` (written in place by both sides: the discrete state, the state scratch). Columns of the 2-D
fields are the IntEnums below; kinds are IntEnums with predicates (:func:`is_kink`, :func:`is_body_switch`), never
ranges of integers. Nothing outside this module indexes the model by position.

The flow laws are not compiled into the engine: ``M.laws`` holds one function per law kind (the registry's kernels,
:mod:`exchange.laws.registry`, all of signature :data:`LAW_SIGNATURE`), called through their address. Adding a law
compiles that law's kernel and nothing else.
"""
from __future__ import annotations

import warnings
from enum import IntEnum
from typing import NamedTuple

import numpy as np
from numba import njit, types
from numba.core.errors import NumbaExperimentalFeatureWarning
from numba.experimental import structref

from cavity.rk_compiled import Status
from exchange.contact.laws import SeatLaw, SeatNode

from .kinds import (SWITCH_LABELS, AreaKind, Energy, Fluid, InflatorKind, KinkVariable, OpenState, SwitchKind,
                    VolumeKind, flags_of, is_body_switch, is_kink, is_seat_switch, one_way_direction, open_state_of)

__all__ = ["Model", "ModelArrays", "new_model", "LAW_SIGNATURE", "LAW_SLOTS", "TableColumn", "CavityInt",
           "CavityFloat", "InflatorInt", "InflatorFloat", "ExchangeInt", "ExchangeFloat", "StateColumn",
           "AmbientColumn", "BodyColumn", "SeatState", "SeatNode", "SeatLaw", "KinkColumn", "SamplingColumn", "SegmentColumn", "segment_blocks", "Energy", "Fluid", "VolumeKind",
           "AreaKind", "InflatorKind", "OpenState", "open_state_of", "flags_of", "SwitchKind", "KinkVariable", "Status", "SWITCH_LABELS",
           "side", "is_kink", "is_body_switch", "is_seat_switch", "one_way_direction", "UNLOCKED", "KNOT_SLACK", "LAW_LOAD"]


class TableColumn(IntEnum):
    """Columns of ``table_index``: one row per table of the concatenated ``table_x``, ``table_y``."""
    START = 0  # its first row
    ROWS = 1  # its number of rows
    LINEAR = 2  # 1: linear extrapolation beyond its ends, 0: held


class CavityInt(IntEnum):
    """Columns of ``cavity_int``."""
    OFFSET = 0  # its first unknown (species masses, then U)
    ENERGY = 1  # Energy
    VOLUME = 2  # VolumeKind
    VOLUME_TABLE = 3  # the volume's table (or the spline's knots), −1: none
    LEDGER = 4  # its first ledger unknown (exchange.network)
    SPECIES = 5  # number of species
    BODY_OFFSET = 6  # the dynamic body's first unknown (VolumeKind.SPLINE_OF_BODY), −1: none
    FLUID = 7  # Fluid
    TEMPERATURE_TABLE = 8  # a hydraulic cavity's T(t), −1: none
    HOST = 9  # a real-gas cavity's host id (exchange.engine.hosted), −1: none
    PIECE = 10  # the volume spline's piece held during the segment (UNLOCKED: the piece holding s)


class CavityFloat(IntEnum):
    """Columns of ``cavity_float``."""
    T0 = 0  # initial temperature [K]
    ADDED_VOLUME = 1  # [m^3]
    MINIMUM_VOLUME = 2  # [m^3]
    HEAT_TRANSFER = 3  # h_c·A [W/K]
    AMBIENT_TEMPERATURE = 4  # [K]
    VOLUME = 5  # fixed volume, or the mesh volume a scale table scales [m^3]
    REFERENCE_DENSITY = 6  # hydraulic: ρ_0 [kg/m^3]
    BULK_MODULUS = 7  # hydraulic: K [Pa]
    REFERENCE_PRESSURE = 8  # hydraulic [Pa]
    REFERENCE_TEMPERATURE = 9  # hydraulic [K]
    THERMAL_EXPANSION = 10  # hydraulic: α [1/K]


class InflatorInt(IntEnum):
    """Columns of ``inflator_int``."""
    CAVITY = 0
    FIRST_TABLE = 1  # mass flow, tank pressure or delivered mass (InflatorKind)
    SECOND_TABLE = 2  # temperature or inflator pressure
    KIND = 3  # InflatorKind
    CLAMPED = 4  # raised once its temperature was held at a bound (warned after the run)


class InflatorFloat(IntEnum):
    """Columns of ``inflator_float``; the gas's mass fractions follow from FRACTIONS."""
    START = 0  # [s]
    SCALE = 1  # [-]
    GAS_MASS = 2  # mass of the gas its rows describe [kg]
    TANK_VOLUME = 3  # [m^3]
    MOLES = 4  # moles of the gas its rows describe [mol]
    ORIFICE_AREA = 5  # [m^2]
    CD = 6  # [-]
    FRACTIONS = 7


class ExchangeInt(IntEnum):
    """Columns of ``exchange_int``."""
    UP = 0  # first cavity
    DOWN = 1  # second cavity, −1: ambient
    TWO_WAY = 2  # to ambient: ambient gas may flow back
    AMPLITUDE = 3  # area multiplier table of time, −1: none
    WINDOW = 4  # has a time window (open time, close time)
    EQUALISE = 5  # has an equalised mode (exchange.network.equalised)
    POP = 6  # has a pop pressure
    LAW = 7  # slot of its law in ``laws`` (exchange.laws.registry)
    AREA_TABLE = 8  # its area's step table (AreaKind), −1: the constant AREA
    SCALE_TABLE = 9  # its mesh scale table of time (area × s²), −1: none
    AREA = 10  # AreaKind
    DELTA_AREA = 11  # DELTA LEAKAGE AREA
    PRESCRIBED = 12  # a prescribed flow: signed, from UP, whatever the pressures
    BODY_LOAD = 13  # 1: its law reads the dynamic body's displacement s [m] in law_float column LAW_LOAD


class ExchangeFloat(IntEnum):
    """Columns of ``exchange_float``."""
    AREA = 0  # [m^2]
    OPEN_TIME = 1  # [s]
    CLOSE_TIME = 2  # [s]
    POP_PRESSURE = 3  # [Pa]
    HOLD_TIME = 4  # [s]
    SWITCH_SCALE = 5  # length scale of its area crossings [m]
    AREA_AT_ACTIVATION = 6  # DELTA LEAKAGE AREA's base [m^2] (NaN: set when it opens)
    CLOSE_PRESSURE = 7  # of the downstream cavity [Pa], 0: none
    JOIN_BELOW = 8  # |Δp|/p where its law changes form (the orifice law's C¹ join: a switch), 0: none


class StateColumn(IntEnum):
    """Columns of the state scratch ``state`` (a cavity's state and flow-law view); mass fractions from
    FRACTIONS."""
    P = 0  # [Pa]
    T = 1  # [K]
    RHO = 2  # [kg/m^3]
    R = 3  # [J/(kg K)]
    GAMMA = 4  # [-]
    H = 5  # specific enthalpy [J/kg]
    V = 6  # [m^3]
    DV = 7  # dV/dt [m^3/s]
    MASS = 8  # [kg]
    FRACTIONS = 9


class AmbientColumn(IntEnum):
    """Entries of ``ambient`` (its flow-law view; mass fractions from FRACTIONS). The first six are those of
    StateColumn, so a side reads ambient and a cavity alike."""
    P = 0
    T = 1
    RHO = 2
    R = 3
    GAMMA = 4
    H = 5
    FRACTIONS = 6


class BodyColumn(IntEnum):
    """Entries of ``body``, the dynamic body (OFFSET −1: none)."""
    OFFSET = 0  # its first unknown (s, then v)
    MASS = 1  # [kg]
    GRAVITY = 2  # along its axis [m/s^2]
    PUSHED = 3  # the cavity it intrudes into, −1: none
    PRESSURE_CAVITY = 4  # the cavity whose gauge pressure pushes it on PRESSURE_AREA, −1: none
    PRESSURE_AREA = 5  # [m^2]
    STIFFNESS = 6  # spring [N/m]
    PRELOAD = 7  # [N]
    SPEED_SCALE = 8  # of its turning-point switch [m/s]
    SLACK = 9  # of its area intervals' re-derivation [m]


class SeatState(IntEnum):
    """Entries of ``seat_state``."""
    HAS = 0  # the body has a seat contact
    HELD = 1  # hard contact holds it on the seat now (the discrete state)
    FORCE_SCALE = 2  # of the lift-off switch [N]


class KinkColumn(IntEnum):
    """Columns of ``kink_int`` (its abscissa in ``kink_x``)."""
    EXCHANGE = 0
    VARIABLE = 1  # KinkVariable


class SamplingColumn(IntEnum):
    """Columns of ``sampling``, one row per exchange whose area is an FE rule's flags sampled from the dynamic body
    (AreaKind.SAMPLED_OF_BODY, :mod:`exchange.engine.sampled`); after QUEUE come the pending samples, two columns
    each: the sample time t_k [s] and the area interval its flags give (used from t_k + lag·step on)."""
    STEP = 0  # the explicit time step [s]
    LAG = 1  # cycles between a sample and its use
    CURRENT = 2  # the area interval holding the body's displacement now (the crossings switches move it)
    COUNT = 3  # pending samples
    QUEUE = 4


class SegmentColumn(IntEnum):
    """Columns of the engine's segment table (one row per segment: :func:`exchange.engine.modes.record_segment`);
    after EQUALISED come, per exchange, its open state, then its hold start [s], then the dynamic body's area
    interval, then one column: 1 while the body is held on its seat (:func:`segment_blocks`)."""
    FIRST = 0  # its first step record
    END = 1  # one past its last step record
    T_MIN = 2  # [s]
    T_MAX = 3  # [s]
    EQUALISED = 4  # bit j: exchange j equalised (held closed)
    BLOCKS = 5


@njit(cache=True)
def segment_blocks(ne):
    """(open states, hold starts, intervals, held, width) columns of a segment row with ne exchanges."""
    b = SegmentColumn.BLOCKS
    return b, b + ne, b + 2 * ne, b + 3 * ne, b + 3 * ne + 1


@njit(cache=True)
def side(st, amb, i, column):
    """Entry ``column`` (StateColumn, AmbientColumn: the first six agree) of the flow-law view of side i: cavity
    i's row of the state scratch ``st``, or ambient ``amb`` when i < 0."""
    return amb[column] if i < 0 else st[i, column]


#: The law_float column into which :func:`exchange.engine.gas.states` writes the dynamic body's displacement s [m]
#: for an exchange whose law reads it (``ExchangeInt.BODY_LOAD``, a seal's load).
LAW_LOAD = 0

#: ``CavityInt.PIECE`` of a volume spline evaluated on the piece holding x (no piece held).
UNLOCKED = -2
#: At a segment start the piece of a volume spline of the dynamic body's displacement is the one holding s nudged by
#: this fraction of the spline's span along the body's motion (after a knot switch s lies on the knot, to round-off).
KNOT_SLACK = 1e-9

# First-class functions (the law slots) are experimental in numba since 0.49 and stable in use here: tested on every
# library scene and by a law registered from outside the package.
warnings.filterwarnings("ignore", message="First-class function type feature is experimental",
                        category=NumbaExperimentalFeatureWarning)

#: Law kernels: ``(law floats (LF,), law ints (LI,), table_x, table_y, table_index, state, ambient, upstream side u
#: (−1: ambient), p_down [Pa], area [m^2], t [s]) -> mass flow [kg/s]`` (exchange.laws.registry).
LAW_SIGNATURE = types.float64(types.float64[::1], types.int64[::1], types.float64[::1], types.float64[::1],
                              types.int64[:, ::1], types.float64[:, ::1], types.float64[::1], types.int64,
                              types.float64, types.float64, types.float64)
#: Slots of ``laws``: the registry's laws fill the first, the rest hold the registry's no-flow kernel. A fixed count
#: keeps the model's type (and every compiled kernel) the same whatever laws are registered.
LAW_SLOTS = 16

_f1, _f2, _f3 = types.float64[::1], types.float64[:, ::1], types.float64[:, :, ::1]
_i1, _i2 = types.int64[::1], types.int64[:, ::1]
#: (name, numba type, meaning): the fields of the model, in order.
FIELDS = (
    ("gas_rows", _f3, "per-mole coefficient rows (a, b, c, d, e, f, H offset) per species and range (ns, nr, 7)"),
    ("gas_breaks", _f1, "temperature ranges' interior breaks [K] (nr − 1,)"),
    ("gas_linear", _i1, "1 where every species has a constant cp in the range (nr,)"),
    ("molar_masses", _f1, "[kg/mol] (ns,)"),
    ("table_x", _f1, "every table's abscissae, concatenated"),
    ("table_y", _f1, "every table's values, concatenated"),
    ("table_index", _i2, "one row per table (TableColumn)"),
    ("cavity_int", _i2, "(nc, CavityInt)"),
    ("cavity_float", _f2, "(nc, CavityFloat)"),
    ("inflator_int", _i2, "(ni, InflatorInt)"),
    ("inflator_float", _f2, "(ni, InflatorFloat + ns)"),
    ("inflator_rows", _f3, "total coefficient rows of each inflator's gas (ni, nr, 7)"),
    ("exchange_int", _i2, "(ne, ExchangeInt)"),
    ("exchange_float", _f2, "(ne, ExchangeFloat)"),
    ("law_int", _i2, "each exchange's law integers (ne, LAW_INTS), the law's own columns"),
    ("law_float", _f2, "each exchange's law parameters (ne, LAW_FLOATS), the law's own columns"),
    ("laws", types.UniTuple(types.FunctionType(LAW_SIGNATURE), LAW_SLOTS), "the law kernels by slot"),
    ("kink_int", _i2, "the laws' kinks (nk, KinkColumn)"),
    ("kink_x", _f1, "the abscissa of each kink [Pa] (nk,)"),
    ("ambient", _f1, "the environment's flow-law view (AmbientColumn + ns)"),
    ("ledger", types.int64, "first unknown of the exchanges' ledger"),
    ("temperature_guess", _f1, "Newton's first guesses [K] (nc,), scratch"),
    ("state", _f2, "each cavity's state (nc, StateColumn + ns), scratch"),
    ("moles", _f1, "(ns,) scratch"),
    ("row", _f1, "(7,) scratch"),
    ("equalised", _i1, "1 while an exchange is held closed (ne,)"),
    ("open_state", _i1, "OpenState (ne,)"),
    ("hold_start", _f1, "start of a pop vent's hold [s], NaN: not holding (ne,)"),
    ("interval", _i1, "the dynamic body's area interval of each exchange (ne,)"),
    ("sampling", _f2, "FE rules' sampled flags of the dynamic body (ne, SamplingColumn + 2 per pending sample)"),
    ("body", _f1, "the dynamic body (BodyColumn)"),
    ("seat_state", _f1, "(SeatState)"),
    ("seat_law", _f1, "the seat's law vector (SeatLaw)"),
    ("seat_nodes", _f2, "its node table (n, SeatNode)"),
    ("seat_kinks", _f1, "displacements where the seat's force kinks [m]"),
    ("switch_kind", _i1, "SwitchKind of every switch the engine may watch"),
    ("switch_target", _i1, "what each reads: the exchange, cavity, kink row or seat kink"),
)


@structref.register
class ModelType(types.StructRef):
    def preprocess_fields(self, fields):
        return tuple((name, types.unliteral(t)) for name, t in fields)


class Model(structref.StructRefProxy):
    """The lowered model as numba sees it (build it with :func:`new_model`; read it from Python through the
    :class:`ModelArrays` it was built from)."""


structref.define_boxing(ModelType, Model)
MODEL_TYPE = ModelType(tuple((name, t) for name, t, _ in FIELDS))

#: The model's arrays on the Python side, field for field (the same objects the Model holds).
ModelArrays = NamedTuple("ModelArrays", [(name, object) for name, _, _ in FIELDS])


@njit(cache=True)
def _new(gas_rows, gas_breaks, gas_linear, molar_masses, table_x, table_y, table_index, cavity_int, cavity_float,
         inflator_int, inflator_float, inflator_rows, exchange_int, exchange_float, law_int, law_float, laws,
         kink_int, kink_x, ambient, ledger, temperature_guess, state, moles, row, equalised, open_state, hold_start,
         interval, sampling, body, seat_state, seat_law, seat_nodes, seat_kinks, switch_kind, switch_target):
    m = structref.new(MODEL_TYPE)
    m.gas_rows, m.gas_breaks, m.gas_linear, m.molar_masses = gas_rows, gas_breaks, gas_linear, molar_masses
    m.table_x, m.table_y, m.table_index = table_x, table_y, table_index
    m.cavity_int, m.cavity_float = cavity_int, cavity_float
    m.inflator_int, m.inflator_float, m.inflator_rows = inflator_int, inflator_float, inflator_rows
    m.exchange_int, m.exchange_float, m.law_int, m.law_float, m.laws = exchange_int, exchange_float, law_int, \
        law_float, laws
    m.kink_int, m.kink_x, m.ambient, m.ledger = kink_int, kink_x, ambient, ledger
    m.temperature_guess, m.state, m.moles, m.row = temperature_guess, state, moles, row
    m.equalised, m.open_state, m.hold_start, m.interval = equalised, open_state, hold_start, interval
    m.sampling = sampling
    m.body, m.seat_state, m.seat_law, m.seat_nodes, m.seat_kinks = body, seat_state, seat_law, seat_nodes, seat_kinks
    m.switch_kind, m.switch_target = switch_kind, switch_target
    return m


def new_model(arrays: ModelArrays) -> Model:
    """The Model holding ``arrays`` (numpy arrays of the types of :data:`FIELDS`, C-contiguous; ``laws`` a tuple of
    :data:`LAW_SLOTS` kernels of :data:`LAW_SIGNATURE`)."""
    return _new(*arrays)
