"""Normal-contact laws as numba kernels, each written once: pressure-overclosure, contact damping, and the seat's
nodal pressures and force on a rigid body (used by :mod:`exchange.contact`, :mod:`cases.model.seat_contact` and the
engine, :mod:`exchange.engine.body`).

After Abaqus Analysis User's Guide 37.1.2 ("Contact pressure-overclosure relationships") and 37.1.3 ("Contact
damping"); ``docs/contact.md``. Sign conventions (SI): overclosure h [m] > 0 is penetration, clearance c = −h;
the relative normal velocity v_rel = dh/dt [m/s] > 0 while approaching; pressures [Pa] > 0 in compression.

A seat is a table of nodes (``nodes`` (n, 4): g0 [m] the gap at s = 0, σ = ±1 its side, A [m²] the tributary
area, 1 if the body can reach the node) and a parameter vector (``law`` (:data:`SEAT_PARAMETERS`)); the body
translates by s [m] along its axis with speed v [m/s], node i has gap g_i = g0_i + σ_i·s, overclosure −g_i and
approach speed −σ_i·v, and the seat pushes the body along σ_i·axis with A_i·p_i.
"""
from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
from numba import njit

__all__ = ["Overclosure", "Damping", "SeatLaw", "SeatNode", "HARD", "LINEAR", "SOFTENED", "NO_DAMPING", "STANDARD", "EXPLICIT", "CRITICAL", "SEAT_PARAMETERS",
           "TOUCH", "penalty_pressure", "penalty_stiffness", "softened_pressure", "softened_stiffness",
           "damping_coefficient", "critical_damping_coefficient", "damping_of", "seat_node", "seat_force", "seat_nodal",
           "held_side"]

class Overclosure(IntEnum):
    """Pressure-overclosure law of a seat."""
    HARD = 0
    LINEAR = 1
    SOFTENED = 2


class Damping(IntEnum):
    """Contact damping definition of a seat."""
    NONE = 0
    STANDARD = 1  # Abaqus/Standard: μ(clearance)
    EXPLICIT = 2  # μ0 while closed
    CRITICAL = 3  # a critical damping fraction


HARD, LINEAR, SOFTENED = Overclosure.HARD, Overclosure.LINEAR, Overclosure.SOFTENED
NO_DAMPING, STANDARD, EXPLICIT, CRITICAL = Damping.NONE, Damping.STANDARD, Damping.EXPLICIT, Damping.CRITICAL


class SeatLaw(IntEnum):
    """Entries of a seat's parameter vector ``law``."""
    KIND = 0  # Overclosure
    STIFFNESS = 1  # linear: k [Pa/m]; softened: c0 [m]
    P0 = 2  # softened: p0 [Pa]
    DAMPING = 3  # Damping
    MU0 = 4  # [Pa s/m]
    DAMPING_C0 = 5  # [m]
    ETA = 6  # [-]
    CRITICAL_FRACTION = 7  # [-]
    BODY_MASS = 8  # [kg]
    SEAT_AREA = 9  # reachable seat area [m^2]
    SEAT_SIZE = 10  # [m]


class SeatNode(IntEnum):
    """Columns of a seat's node table ``nodes``."""
    GAP = 0  # g0 [m]
    SIDE = 1  # σ = ±1
    AREA = 2  # tributary area [m^2]
    REACH = 3  # 1 if the body can reach it


#: The entries of a seat's parameter vector, in words.
SEAT_PARAMETERS = ("law", "stiffness or c0 [m]", "p0 [Pa]", "damping", "mu0 [Pa s/m]", "damping c0 [m]", "eta",
                   "critical fraction", "body mass [kg]", "reachable seat area [m^2]", "seat size [m]")
#: A hard-contact node within this fraction of the seat size of the body counts as closed.
TOUCH = 1e-7


@njit(cache=True)
def penalty_pressure(h, stiffness):
    r"""Linear (penalty) pressure-overclosure law [Pa].

    .. math:: p = k\,\max(h, 0)

    ``h`` overclosure [m], ``stiffness`` k [Pa/m] > 0. Abaqus Analysis User's Guide 37.1.2,
    *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR ("slope of the pressure-overclosure curve").

    >>> penalty_pressure(1e-4, 1e9), penalty_pressure(-1e-4, 1e9)
    (100000.0, 0.0)
    """
    return stiffness * h if h > 0.0 else 0.0


@njit(cache=True)
def penalty_stiffness(h, stiffness):
    """dp/dh of :func:`penalty_pressure` [Pa/m]: k while penetrating, 0 open.

    >>> penalty_stiffness(1e-4, 1e9), penalty_stiffness(-1e-4, 1e9)
    (1000000000.0, 0.0)
    """
    return stiffness if h > 0.0 else 0.0


@njit(cache=True)
def softened_pressure(h, c0, p0):
    r"""Exponential (softened) pressure-overclosure law [Pa].

    .. math:: p = \begin{cases} 0 & h \le -c_0 \\
        \dfrac{p_0}{e - 1}\,x\,(e^{x} - 1), \quad x = \dfrac{h}{c_0} + 1 & h > -c_0 \end{cases}

    ``h`` overclosure [m] (−inf: never touching), ``c0`` clearance [m] > 0 at which the pressure is zero, ``p0``
    pressure [Pa] > 0 at zero clearance. p(0) = p0 and p(−c0) = 0 with zero slope (C¹ at first touch); the
    Abaqus/Explicit stiffness cap k_max is not modelled. Abaqus Analysis User's Guide 37.1.2, *SURFACE BEHAVIOR,
    PRESSURE-OVERCLOSURE=EXPONENTIAL (data c0, p0; checked by its end conditions, docs/contact.md).

    >>> softened_pressure(0.0, 1e-3, 1e5), softened_pressure(-1e-3, 1e-3, 1e5), round(softened_pressure(1e-3, 1e-3, 1e5))
    (100000.0, 0.0, 743656)
    """
    x = h / c0 + 1.0
    return p0 / (math.e - 1.0) * x * math.expm1(x) if x > 0.0 else 0.0


@njit(cache=True)
def softened_stiffness(h, c0, p0):
    r"""dp/dh of :func:`softened_pressure` [Pa/m].

    .. math:: \frac{dp}{dh} = \frac{p_0}{c_0 (e - 1)}\left[(e^{x} - 1) + x e^{x}\right], \quad x = h/c_0 + 1

    >>> round(softened_stiffness(0.0, 1e-3, 1e5) / 1e8, 6)  # (e - 1 + e)/(e - 1) * p0/c0
    2.581977
    """
    x = h / c0 + 1.0
    return p0 / (c0 * (math.e - 1.0)) * (math.expm1(x) + x * math.exp(x)) if x > 0.0 else 0.0


@njit(cache=True)
def damping_coefficient(clearance, mu0, c0, eta):
    r"""Clearance-dependent viscous damping coefficient of Abaqus/Standard [Pa·s/m].

    .. math:: \mu(c) = \begin{cases} \mu_0 & c \le \eta c_0 \\
        \mu_0 \dfrac{c_0 - c}{(1 - \eta) c_0} & \eta c_0 < c < c_0 \\ 0 & c \ge c_0 \end{cases}

    ``clearance`` c = −h [m] (c <= 0: closed), ``mu0`` [Pa·s/m] (N·s/m for node-based surfaces), ``c0`` [m] the
    clearance at which damping vanishes (0: damping only while closed), ``eta`` [-] in [0, 1): the fraction of c0
    with the full μ0 (0: linear from c = 0 to c0). The damping pressure is μ(c)·v_rel. Abaqus Analysis User's
    Guide 37.1.3, "Contact damping" (*CONTACT DAMPING, data mu0, c0, eta).

    >>> [damping_coefficient(c, 10.0, 1e-3, 0.2) for c in (0.0, 2e-4, 6e-4, 1e-3)]
    [10.0, 10.0, 5.0, 0.0]
    """
    if clearance <= eta * c0:
        return mu0
    if clearance >= c0:
        return 0.0
    return mu0 * (c0 - clearance) / ((1.0 - eta) * c0)


@njit(cache=True)
def critical_damping_coefficient(fraction, mass, stiffness):
    r"""Damping coefficient for a critical damping fraction (Abaqus/Explicit) [N·s/m].

    .. math:: c = \xi \sqrt{4 m k_c}, \qquad f = c\, v_{rel}

    ``fraction`` ξ [-] (Abaqus default 0.03), ``mass`` m [kg] (nodal), ``stiffness`` k_c [N/m] (nodal contact
    stiffness, area times dp/dh). ξ = 1 is critical damping of m·ẍ + c·ẋ + k·x = 0. Abaqus Keywords Reference,
    *CONTACT DAMPING, DEFINITION=CRITICAL DAMPING FRACTION.

    >>> critical_damping_coefficient(0.03, 1.0, 1e6)
    60.0
    """
    return fraction * math.sqrt(4.0 * mass * stiffness)


@njit(cache=True)
def damping_of(clearance, closed, law):
    r"""(μ [Pa·s/m], within the damping clearance) of a node of clearance ``clearance`` [m] (its gap; a closed
    node's is >= 0), closed or not, under the seat's damping ``law`` (:class:`SeatLaw`; not the critical fraction,
    which needs the node's stiffness: :func:`seat_node`): explicit μ0 while closed with zero clearance; standard
    :func:`damping_coefficient` of the clearance, an open node within c0 being "VD"; none.

    >>> law = np.zeros(11); law[SeatLaw.DAMPING], law[SeatLaw.MU0], law[SeatLaw.DAMPING_C0] = STANDARD, 10.0, 1e-3
    >>> damping_of(5e-4, False, law)
    (5.0, True)
    """
    damping = int(law[SeatLaw.DAMPING])
    if damping == EXPLICIT:
        return (law[SeatLaw.MU0] if closed and clearance <= 0.0 else 0.0), False
    if damping == STANDARD:
        mu = damping_coefficient(clearance, law[SeatLaw.MU0], law[SeatLaw.DAMPING_C0], law[SeatLaw.ETA])
        return mu, (not closed and clearance < law[SeatLaw.DAMPING_C0])
    return 0.0, False


@njit(cache=True, inline="always")  # called per seat node in every right-hand side: a call there costs 1.2x
def seat_node(g, v_rel, area, law):
    r"""(pressure [Pa], closed, within the damping clearance) of one seat node with gap ``g`` [m] (overclosure
    −g), approach speed ``v_rel`` [m/s] and tributary area ``area`` [m²]; ``law`` the seat's parameters
    (:class:`SeatLaw`). Hard contact gives its damping only (its elastic part is the reaction). The CPRESS of
    Abaqus at a slave node: closed p = p_e(h) + p_v, VD (open within the damping clearance) p = p_v, open 0.

    .. math:: p = p_e(-g) + \mu\,v_{rel}

    Closed: g <= TOUCH·size (hard), g <= 0 (linear), g < c0 (softened). μ: critical fraction
    ξ·√(4·m_i·k_i)/A_i with m_i = m·A_i/A_seat, k_i = A_i·dp/dh while closed; otherwise :func:`damping_of`.

    >>> law = np.array([1.0, 1e9, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
    >>> seat_node(-1e-4, 0.5, 1.0, law)
    (100000.0, True, False)
    """
    kind = int(law[SeatLaw.KIND])
    k_or_c0, p0 = law[SeatLaw.STIFFNESS], law[SeatLaw.P0]
    if kind == HARD:
        closed, p = g <= TOUCH * law[SeatLaw.SEAT_SIZE], 0.0
    elif kind == LINEAR:
        closed, p = g <= 0.0, penalty_pressure(-g, k_or_c0)
    else:
        closed, p = g < k_or_c0, softened_pressure(-g, k_or_c0, p0) if math.isfinite(g) else 0.0
    within = False
    if int(law[SeatLaw.DAMPING]) == CRITICAL:
        if closed:
            k = penalty_stiffness(-g, k_or_c0) if kind == LINEAR else softened_stiffness(-g, k_or_c0, p0)
            nodal_mass = law[SeatLaw.BODY_MASS] * area / law[SeatLaw.SEAT_AREA]
            mu = critical_damping_coefficient(law[SeatLaw.CRITICAL_FRACTION], nodal_mass, area * k) / area
            p += mu * v_rel
    elif int(law[SeatLaw.DAMPING]) != NO_DAMPING:
        mu, within = damping_of(max(g, 0.0) if closed else g, closed, law)
        p += mu * v_rel
    return p, closed, within


@njit(cache=True)
def seat_force(s, v, nodes, law):
    """Force of the seat on the body along its axis [N]: Σ σ_i·A_i·p_i over the reachable nodes at displacement
    ``s`` [m] and speed ``v`` [m/s] (:func:`seat_node`; hard contact: its damping only).

    Summed with Neumaier's compensation: at rest on a stiff seat the force balances the others to round-off.

    >>> nodes = np.array([[0.0, -1.0, 0.5, 1.0], [0.0, -1.0, 0.5, 1.0]])  # two nodes touching, σ = −1
    >>> law = np.array([1.0, 1e9, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
    >>> seat_force(1e-4, 0.0, nodes, law)  # moved 0.1 mm into a 1e9 Pa/m seat: 1e5 Pa on 1 m², along −axis
    -100000.0
    """
    force, lost = 0.0, 0.0  # Neumaier's compensated sum: the force at rest on a stiff seat is a small difference
    for i in range(nodes.shape[0]):
        if nodes[i, SeatNode.REACH] != 0.0:
            sigma, area = nodes[i, SeatNode.SIDE], nodes[i, SeatNode.AREA]
            p, _, _ = seat_node(nodes[i, SeatNode.GAP] + sigma * s, -sigma * v, area, law)
            term = sigma * area * p
            total = force + term
            lost += (force - total) + term if abs(force) >= abs(term) else (term - total) + force
            force = total
    return force + lost


@njit(cache=True)
def held_side(s, nodes, law):
    """Side σ of the first closed reachable node at displacement ``s`` [m] (0 if none): hard contact pushes the
    body along σ·axis.

    >>> held_side(0.0, np.array([[0.0, -1.0, 1.0, 1.0]]), np.zeros(11))
    -1.0
    """
    for i in range(nodes.shape[0]):
        sigma = nodes[i, SeatNode.SIDE]
        if nodes[i, SeatNode.REACH] != 0.0 and \
                seat_node(nodes[i, SeatNode.GAP] + sigma * s, 0.0, nodes[i, SeatNode.AREA], law)[1]:
            return sigma
    return 0.0


@njit(cache=True)
def seat_nodal(s, v, reaction, nodes, law):
    """(CPRESS per node [Pa], status per node: 0 open, 1 closed, 2 VD) at (s [m], v [m/s]); ``reaction`` [N] is a
    held hard contact's force, shared by the closed nodes in proportion to their areas. Unreachable nodes and open
    nodes outside the damping clearance carry 0.

    >>> p, status = seat_nodal(0.0, 0.0, 2.0, np.array([[0.0, -1.0, 0.5, 1.0], [1.0, -1.0, 0.5, 1.0]]), np.zeros(11))
    >>> p.tolist(), status.tolist()
    ([4.0, 0.0], [1, 0])
    """
    n = nodes.shape[0]
    p, status = np.zeros(n), np.zeros(n, np.uint8)
    closed_area = 0.0
    for i in range(n):
        if nodes[i, SeatNode.REACH] != 0.0:
            sigma = nodes[i, SeatNode.SIDE]
            pi, closed, within = seat_node(nodes[i, SeatNode.GAP] + sigma * s, -sigma * v, nodes[i, SeatNode.AREA],
                                           law)
            if closed:
                p[i], status[i] = pi, 1
                closed_area += nodes[i, SeatNode.AREA]
            elif within:
                p[i], status[i] = pi, 2
    if int(law[SeatLaw.KIND]) == HARD and closed_area > 0.0:
        share = reaction / closed_area
        for i in range(n):
            if status[i] == 1:
                p[i] += share
    return p, status
