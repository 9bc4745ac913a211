"""Normal contact mechanics: pressure-overclosure laws, contact damping and CPRESS.

Small frozen dataclasses and the laws by law object after Abaqus Analysis User's Guide 37.1.2 ("Contact
pressure-overclosure relationships") and 37.1.3 ("Contact damping"); each formula is written once, as a numba
kernel of :mod:`exchange.contact.laws` (which the engine calls too), and these functions pick it by law object
(:func:`law_vector`: a law, its damping and its seat as the kernels' parameter vector). Scenes evaluate the same kernels on the nodes of a seat (:mod:`cases.model.seat_contact`, ``[[contact]]``
tables, docs/contact.md).

Sign conventions (SI throughout):

* ``h`` overclosure [m]: positive = penetration, negative = clearance ``c = -h``.
* ``v_rel`` relative normal velocity [m/s] = dh/dt: positive when the surfaces approach.
* Pressures [Pa] are positive in compression (pushing the surfaces apart).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Union

import numpy as np

from .laws import CRITICAL, EXPLICIT, HARD, LINEAR, NO_DAMPING, SOFTENED, STANDARD, SeatLaw, damping_of, seat_node
from .laws import critical_damping_coefficient as _critical_damping_coefficient
from .laws import damping_coefficient as _damping_coefficient
from .laws import penalty_pressure, penalty_stiffness, softened_pressure, softened_stiffness

__all__ = [
    "Hard", "LinearPenalty", "Softened", "ContactDamping", "DEFAULT_CRITICAL_FRACTION",
    "overclosure_pressure", "contact_stiffness", "hard_contact_pressure", "damping_coefficient",
    "damping_pressure", "critical_damping_coefficient", "default_critical_fraction", "cpress",
    "law_vector",
]

#: Abaqus/Explicit default critical damping fraction for penalty and softened contact [-].
DEFAULT_CRITICAL_FRACTION = 0.03


@dataclass(frozen=True)
class Hard:
    """Kinematic ("hard") contact: no penetration, no tension; pressure is a Lagrange multiplier."""


@dataclass(frozen=True)
class LinearPenalty:
    """Linear pressure-overclosure p = k·h for h > 0. ``stiffness`` [Pa/m] > 0."""

    stiffness: float

    def __post_init__(self):
        if not self.stiffness > 0.0:
            raise ValueError(f"penalty stiffness must be > 0 Pa/m, got {self.stiffness!r}")


@dataclass(frozen=True)
class Softened:
    """Exponential softened contact: zero pressure at clearance ``c0`` [m] > 0, ``p0`` [Pa] at zero clearance."""

    c0: float
    p0: float

    def __post_init__(self):
        if not (self.c0 > 0.0 and self.p0 > 0.0):
            raise ValueError(f"softened contact needs c0 > 0 and p0 > 0, got c0={self.c0!r}, p0={self.p0!r}")


Law = Union[Hard, LinearPenalty, Softened]


@dataclass(frozen=True)
class ContactDamping:
    """Viscous contact damping (Abaqus *CONTACT DAMPING, DEFINITION=DAMPING COEFFICIENT).

    Parameters
    ----------
    mu0 : float
        Damping coefficient [Pa·s/m] (pressure per relative velocity; force per velocity [N·s/m] for node-based
        surfaces, where "pressure" means force throughout this module).
    c0 : float
        Clearance at which damping vanishes [m] (``"standard"`` style only), >= 0.
    eta : float
        Fraction of ``c0`` up to which the full ``mu0`` acts [-], 0 <= eta < 1 (``"standard"`` style only).
    style : {"standard", "explicit"}
        ``"standard"``: clearance-dependent bilinear rule; ``"explicit"``: constant ``mu0`` while closed, 0 otherwise.
    tangent_fraction : float or None
        Tangential/normal damping ratio [-]; None picks the Abaqus default (0 Standard, 1.0 Explicit). Stored for
        completeness: tangential damping is not computed in this module.
    """

    mu0: float
    c0: float = 0.0
    eta: float = 0.0
    style: str = "standard"
    tangent_fraction: Optional[float] = None

    def __post_init__(self):
        if self.style not in ("standard", "explicit"):
            raise ValueError(f"style must be 'standard' or 'explicit', got {self.style!r}")
        if self.mu0 < 0.0 or self.c0 < 0.0 or not 0.0 <= self.eta < 1.0:
            raise ValueError(f"need mu0 >= 0, c0 >= 0, 0 <= eta < 1; got {self.mu0}, {self.c0}, {self.eta}")

    @property
    def tangent(self) -> float:
        """Effective tangent fraction [-] (default 0 for Standard, 1.0 for Explicit).

        >>> ContactDamping(1.0).tangent, ContactDamping(1.0, style="explicit").tangent
        (0.0, 1.0)
        """
        if self.tangent_fraction is not None:
            return float(self.tangent_fraction)
        return 0.0 if self.style == "standard" else 1.0


def overclosure_pressure(h: float, law: Law) -> float:
    r"""Elastic contact pressure for an overclosure ``h`` [Pa].

    .. math::
        p_{\text{penalty}} = k\,\max(h, 0), \qquad
        p_{\text{softened}} = \begin{cases} 0 & h \le -c_0 \\
        \dfrac{p_0}{e - 1}\left(\dfrac{h}{c_0} + 1\right)\left(e^{h/c_0 + 1} - 1\right) & h > -c_0 \end{cases}

    Parameters
    ----------
    h : float
        Overclosure [m], positive = penetration.
    law : LinearPenalty or Softened
        ``Hard`` raises: its pressure is a constraint reaction, see :func:`hard_contact_pressure`.

    Notes
    -----
    The softened law gives p = p0 at h = 0 and p = 0 with zero slope at h = -c0, so it is C¹ at first touch.
    Abaqus/Explicit also caps its stiffness at a maximum k_max; not modelled here.

    References
    ----------
    Abaqus Analysis User's Guide 37.1.2, "Exponential pressure-overclosure relationship" (*SURFACE BEHAVIOR,
    PRESSURE-OVERCLOSURE=EXPONENTIAL: data c0 "clearance at which the contact pressure is zero", p0 "pressure at
    zero clearance"); PRESSURE-OVERCLOSURE=LINEAR: "slope of the pressure-overclosure curve".

    Examples
    --------
    >>> overclosure_pressure(1e-4, LinearPenalty(1e9)), overclosure_pressure(-1e-4, LinearPenalty(1e9))
    (100000.0, 0.0)
    >>> law = Softened(c0=1e-3, p0=1e5)
    >>> overclosure_pressure(0.0, law), overclosure_pressure(-1e-3, law), round(overclosure_pressure(1e-3, law))
    (100000.0, 0.0, 743656)
    """
    if isinstance(law, LinearPenalty):
        return penalty_pressure(float(h), law.stiffness)
    if isinstance(law, Softened):
        return softened_pressure(float(h), law.c0, law.p0)
    if isinstance(law, Hard):
        raise TypeError("hard contact has no pressure-overclosure function: its pressure is the constraint "
                        "reaction (use hard_contact_pressure or pass the multiplier to cpress)")
    raise TypeError(f"unknown contact law {law!r}")


def contact_stiffness(h: float, law: Law) -> float:
    r"""Tangent contact stiffness dp/dh [Pa/m] (multiply by the nodal area for k_c in N/m).

    .. math:: \frac{dp}{dh}\Big|_{\text{softened}} = \frac{p_0}{c_0 (e - 1)}\left[(e^{x} - 1) + x e^{x}\right],
        \quad x = h/c_0 + 1

    Examples
    --------
    >>> contact_stiffness(1e-4, LinearPenalty(1e9)), contact_stiffness(-1e-4, LinearPenalty(1e9))
    (1000000000.0, 0.0)
    >>> round(contact_stiffness(0.0, Softened(c0=1e-3, p0=1e5)) / 1e8, 6)  # (e - 1 + e)/(e - 1) * p0/c0
    2.581977
    """
    if isinstance(law, LinearPenalty):
        return penalty_stiffness(float(h), law.stiffness)
    if isinstance(law, Softened):
        return softened_stiffness(float(h), law.c0, law.p0)
    if isinstance(law, Hard):
        raise TypeError("hard contact has infinite stiffness")
    raise TypeError(f"unknown contact law {law!r}")


def hard_contact_pressure(force: float, area: float) -> float:
    r"""Contact pressure of a rigid flat body statically pressed on a flat seat by hard contact [Pa].

    .. math:: p = F / A

    Parameters
    ----------
    force : float
        Net normal force pressing the body on the seat [N], >= 0 (contact transmits no tension).
    area : float
        Contact area [m²] > 0. For a nodal seat mesh each node carries F·A_i/A, so CPRESS_i = F/A at every node.

    Notes
    -----
    Hard contact is kinematic: the pressure is the Lagrange multiplier of the no-penetration constraint, which for
    a static rigid body is fixed by equilibrium alone.

    Examples
    --------
    >>> hard_contact_pressure(100.0, 1e-4)
    1000000.0
    """
    if force < 0.0 or not area > 0.0:
        raise ValueError(f"need force >= 0 N and area > 0 m², got {force!r}, {area!r}")
    return force / area


def damping_coefficient(clearance: float, mu0: float, c0: float, eta: float = 0.0) -> float:
    r"""Clearance-dependent damping coefficient of Abaqus/Standard [Pa·s/m].

    .. math:: \mu(c) = \begin{cases} \mu_0 & c \le \eta c_0 \\
        \mu_0 \dfrac{c_0 - c}{(1 - \eta) c_0} & \eta c_0 < c < c_0 \\ 0 & c \ge c_0 \end{cases}

    Parameters
    ----------
    clearance : float
        Clearance c = -h [m]; c <= 0 (closed) gives mu0.
    mu0 : float
        Damping coefficient at small clearance [Pa·s/m].
    c0 : float
        Clearance at which damping vanishes [m]; c0 = 0 means damping only while closed.
    eta : float
        Fraction of c0 with constant damping [-], 0 <= eta < 1 (eta = 0: linear from c = 0 to c0).

    References
    ----------
    Abaqus Analysis User's Guide 37.1.3, "Contact damping" (*CONTACT DAMPING, data: mu0, c0, eta).

    Examples
    --------
    >>> [damping_coefficient(c, 10.0, 1e-3, 0.2) for c in (0.0, 2e-4, 6e-4, 1e-3)]
    [10.0, 10.0, 5.0, 0.0]
    """
    return _damping_coefficient(float(clearance), float(mu0), float(c0), float(eta))


def damping_pressure(v_rel: float, clearance: float, rule: ContactDamping) -> float:
    r"""Viscous damping pressure opposing the relative normal velocity [Pa].

    .. math:: p_v = \mu(c)\, v_{rel}

    with μ(c) from :func:`damping_coefficient` (style ``"standard"``) or μ = μ0 for c <= 0 and 0 otherwise (style
    ``"explicit"``). Positive when approaching (pushes apart), negative when separating (resists opening).

    Examples
    --------
    >>> rule = ContactDamping(mu0=100.0, c0=1e-3, eta=0.5)
    >>> damping_pressure(2.0, 0.0, rule), damping_pressure(-2.0, 7.5e-4, rule), damping_pressure(2.0, 2e-3, rule)
    (200.0, -100.0, 0.0)
    >>> damping_pressure(2.0, 1e-4, ContactDamping(100.0, style="explicit"))
    0.0
    """
    mu, _ = damping_of(float(clearance), clearance <= 0.0, law_vector(Hard(), rule))
    return mu * v_rel


def critical_damping_coefficient(fraction: float, mass: float, stiffness: float) -> float:
    r"""Damping coefficient [N·s/m] for a critical damping fraction (Abaqus/Explicit).

    .. math:: c = \xi \sqrt{4 m k_c}, \qquad f = c\, v_{rel}

    Parameters
    ----------
    fraction : float
        Critical damping fraction ξ [-] (Abaqus default 0.03, see :func:`default_critical_fraction`).
    mass : float
        Nodal mass m [kg] > 0.
    stiffness : float
        Nodal contact stiffness k_c [N/m] > 0 and finite; hard (kinematic) contact has none and raises.

    Notes
    -----
    ξ = 1 is the critical damping of the oscillator m ẍ + c ẋ + k x = 0. Divide by the nodal area to get mu0 in
    Pa·s/m.

    References
    ----------
    Abaqus Keywords Reference, *CONTACT DAMPING, DEFINITION=CRITICAL DAMPING FRACTION.

    Examples
    --------
    >>> critical_damping_coefficient(0.03, 1.0, 1e6)
    60.0
    """
    if not (math.isfinite(stiffness) and stiffness > 0.0):
        raise ValueError("critical damping fraction needs a finite contact stiffness > 0 N/m; "
                         "it is not available for hard (kinematic) contact")
    if fraction < 0.0 or not mass > 0.0:
        raise ValueError(f"need fraction >= 0 and mass > 0 kg, got {fraction!r}, {mass!r}")
    return _critical_damping_coefficient(float(fraction), float(mass), float(stiffness))


def default_critical_fraction(law: Law) -> float:
    """Abaqus/Explicit default critical damping fraction for ``law`` [-]: 0.03; hard contact raises.

    >>> default_critical_fraction(LinearPenalty(1e9)), default_critical_fraction(Softened(1e-3, 1e5))
    (0.03, 0.03)
    """
    if isinstance(law, Hard):
        raise ValueError("critical damping fraction is not available for hard (kinematic) contact")
    return DEFAULT_CRITICAL_FRACTION


def cpress(h: float, v_rel: float, law: Law, damping: Optional[ContactDamping] = None,
           multiplier: float = 0.0) -> tuple[float, str]:
    r"""CPRESS at one slave node and its status ``"closed"``, ``"VD"`` or ``"open"``.

    .. math:: \text{closed: } p = p_e(h) + p_v, \qquad \text{VD: } p = p_v = \mu(c)\,v_{rel},
        \qquad \text{open: } p = 0

    Parameters
    ----------
    h : float
        Overclosure [m]. Closed when h >= 0 (hard, penalty) or h > -c0 (softened).
    v_rel : float
        Relative normal velocity dh/dt [m/s], positive approaching.
    law : Hard, LinearPenalty or Softened
        Pressure-overclosure law.
    damping : ContactDamping or None
        Viscous damping; None = undamped.
    multiplier : float
        Constraint pressure [Pa] of a closed hard-contact node (e.g. :func:`hard_contact_pressure`); ignored for
        the other laws.

    Notes
    -----
    The closed pressure includes the viscous part, so it may be negative while separating (damping resists
    opening). An open node reports "VD" while it lies within the damping clearance (nonzero μ(c)).

    Examples
    --------
    >>> law, rule = LinearPenalty(1e9), ContactDamping(mu0=1e4, c0=1e-3)
    >>> cpress(1e-4, 0.0, law, rule), cpress(-5e-4, -2.0, law, rule), cpress(-2e-3, 1.0, law, rule)
    ((100000.0, 'closed'), (-10000.0, 'VD'), (0.0, 'open'))
    >>> cpress(0.0, 0.0, Hard(), multiplier=hard_contact_pressure(50.0, 1e-4))
    (500000.0, 'closed')
    """
    p, closed, within = seat_node(-float(h), float(v_rel), 1.0, law_vector(law, damping))
    if closed:
        return p + (multiplier if isinstance(law, Hard) else 0.0), "closed"
    return (p, "VD") if within else (0.0, "open")


def law_vector(law: Law, damping: Optional[ContactDamping] = None, critical_fraction: Optional[float] = None,
               mass: float = 0.0, seat_area: float = 1.0, size: float = 0.0) -> np.ndarray:
    """The parameter vector of :mod:`exchange.contact.laws` (:class:`~exchange.contact.laws.SeatLaw`) of a
    pressure-overclosure law, its damping (or a critical damping fraction, with the body's mass [kg], the reachable
    seat area [m²] it shares) and the seat's size [m] (hard contact's touch tolerance is :data:`~exchange.contact.
    laws.TOUCH` of it).

    >>> law_vector(LinearPenalty(1e9), ContactDamping(10.0, c0=1e-3)).tolist()[:6]
    [1.0, 1000000000.0, 0.0, 1.0, 10.0, 0.001]
    """
    vec = np.zeros(len(SeatLaw))
    if isinstance(law, LinearPenalty):
        vec[SeatLaw.KIND], vec[SeatLaw.STIFFNESS] = LINEAR, law.stiffness
    elif isinstance(law, Softened):
        vec[SeatLaw.KIND], vec[SeatLaw.STIFFNESS], vec[SeatLaw.P0] = SOFTENED, law.c0, law.p0
    else:
        vec[SeatLaw.KIND] = HARD
    if critical_fraction is not None:
        vec[SeatLaw.DAMPING], vec[SeatLaw.CRITICAL_FRACTION] = CRITICAL, critical_fraction
    elif damping is not None:
        vec[SeatLaw.DAMPING] = STANDARD if damping.style == "standard" else EXPLICIT
        vec[SeatLaw.MU0], vec[SeatLaw.DAMPING_C0], vec[SeatLaw.ETA] = damping.mu0, damping.c0, damping.eta
    else:
        vec[SeatLaw.DAMPING] = NO_DAMPING
    vec[SeatLaw.BODY_MASS], vec[SeatLaw.SEAT_AREA], vec[SeatLaw.SEAT_SIZE] = mass, seat_area, size
    return vec
