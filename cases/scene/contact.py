"""Scene keys for contact between a dynamic body and a seat surface (issue 7): the [[contact]] table and its checks.

A contact joins the dynamic body (``body``) to the nodes of a fixed seat: the leakage surface of an exchange
(``seat``, so that the same nodes block the vent) or a mesh of its own (``seat_mesh``). ``docs/contact.md``
describes the laws; :mod:`exchange.contact` holds them.
"""
from __future__ import annotations

from dataclasses import dataclass

from cases.scene.errors import SceneError
from cases.scene.schema import key, unknown_name

__all__ = ["ContactSpec", "PRESSURE_OVERCLOSURES", "DAMPING_DEFINITIONS", "check_contacts"]

PRESSURE_OVERCLOSURES = ("hard", "linear", "exponential")
DAMPING_DEFINITIONS = ("none", "coefficient", "critical_fraction")


@dataclass(frozen=True, kw_only=True)
class ContactSpec:
    name: str = key("contact name (column prefix in history.csv, key in summary.json)")
    body: str = key("the dynamic body that touches the seat")
    seat: str = key("exchange whose leakage surface is the seat (its nodes carry CPRESS)", default="")
    seat_mesh: str = key("or: a seat mesh file of its own (triangles or quads, metres), fixed", default="")
    pressure_overclosure: str = key("hard (kinematic: the seat holds the body while the contact force is "
                                    "compressive), linear (penalty) or exponential (softened)", default="hard",
                                    choices=PRESSURE_OVERCLOSURES)
    stiffness: float = key("linear: penalty stiffness k in p = k·h", "Pa/m", default=0.0, check="nonnegative")
    clearance: float = key("exponential: clearance c0 at which the pressure is zero", "m", default=0.0,
                           check="nonnegative")
    pressure: float = key("exponential: pressure p0 at zero clearance", "Pa", default=0.0, check="nonnegative")
    damping: str = key("contact damping definition (Abaqus *CONTACT DAMPING)", default="none",
                       choices=DAMPING_DEFINITIONS)
    mu0: float = key("coefficient: damping coefficient μ0 (pressure per approach speed)", "Pa s/m", default=0.0,
                     check="nonnegative")
    damping_clearance: float = key("coefficient, standard style: clearance c0 at which damping vanishes",
                                   "m", default=0.0, check="nonnegative")
    eta: float = key("coefficient, standard style: fraction of damping_clearance with constant μ0 (0 <= η < 1)",
                     default=0.0, check="fraction")
    style: str = key("coefficient: standard (μ(c) bilinear in clearance, open nodes within c0 are 'VD') or "
                     "explicit (μ0 while closed only); critical_fraction is always explicit", default="standard",
                     choices=("standard", "explicit"))
    critical_fraction: float = key("critical_fraction: ξ in c = ξ·√(4·m·k_c) (Abaqus default 0.03); not "
                                   "available for hard contact", default=0.03, check="nonnegative")
    tangent_fraction: float = key("tangential/normal damping ratio (-1: Abaqus default, 0 standard, 1 "
                                  "explicit); stored and reported, tangential damping is not computed",
                                  default=-1.0, check="finite")


def check_contacts(scene, path, raw: dict) -> None:
    """Cross-key checks of every [[contact]]; ``raw`` is the TOML dict (to tell a given key from a default)."""
    bodies = {b.name: b for b in scene.body}
    exchanges = {e.name: e for e in scene.exchange}
    raw_contacts = raw.get("contact", [])
    used = set()
    for i, c in enumerate(scene.contact):
        where, given = f"contact[{i}]", set(raw_contacts[i])
        body = bodies.get(c.body)
        if body is None:
            raise unknown_name(path, f"{where}.body", "body", c.body, bodies)
        if not body.mass:
            raise SceneError(path, f"{where}.body", f"body {c.body!r} is not dynamic (mass > 0): a prescribed "
                                                    "body needs no contact force")
        if c.body in used:
            raise SceneError(path, f"{where}.body", f"body {c.body!r} already has a contact")
        used.add(c.body)
        _check_seat(scene, c, path, where, exchanges)
        _check_law(c, path, where, given)
        _check_damping(c, path, where, given)


def _check_seat(scene, c, path, where, exchanges) -> None:
    if bool(c.seat) == bool(c.seat_mesh):
        raise SceneError(path, where, "give exactly one of seat (an exchange with a leakage_surface) or seat_mesh")
    if c.seat:
        e = exchanges.get(c.seat)
        if e is None:
            raise unknown_name(path, f"{where}.seat", "exchange", c.seat, exchanges)
        if not e.leakage_surface:
            raise SceneError(path, f"{where}.seat", f"exchange {c.seat!r} has no leakage_surface (the seat must be "
                                                    "a fixed surface of its own)")
    else:
        from cases.scene.checks import require_file

        require_file(scene, c.seat_mesh, path, f"{where}.seat_mesh")


def _check_law(c, path, where, given) -> None:
    needed = {"hard": (), "linear": ("stiffness",), "exponential": ("clearance", "pressure")}
    for k in needed[c.pressure_overclosure]:
        if not getattr(c, k) > 0:
            raise SceneError(path, f"{where}.{k}", f"expected a number > 0 for pressure_overclosure = "
                                                   f"{c.pressure_overclosure!r}")
    for k in ("stiffness", "clearance", "pressure"):
        if k in given and k not in needed[c.pressure_overclosure]:
            raise SceneError(path, f"{where}.{k}", f"not used by pressure_overclosure = {c.pressure_overclosure!r}")


def _check_damping(c, path, where, given) -> None:
    keys = {"none": (), "coefficient": ("mu0", "damping_clearance", "eta", "style"),
            "critical_fraction": ("critical_fraction",)}
    for k in ("mu0", "damping_clearance", "eta", "style", "critical_fraction"):
        if k in given and k not in keys[c.damping]:
            raise SceneError(path, f"{where}.{k}", f"not used by damping = {c.damping!r}"
                                                   + ("" if c.damping != "none" else
                                                      " (set damping = 'coefficient' or 'critical_fraction')"))
    if c.damping == "critical_fraction" and c.pressure_overclosure == "hard":
        raise SceneError(path, f"{where}.damping", "a critical damping fraction is not available for hard "
                                                   "(kinematic) contact: it has no contact stiffness; use "
                                                   "damping = 'coefficient' or a linear/exponential law")
    if c.damping == "coefficient":
        if not c.mu0 > 0:
            raise SceneError(path, f"{where}.mu0", "expected a damping coefficient > 0 [Pa s/m]")
        if not c.eta < 1.0:
            raise SceneError(path, f"{where}.eta", f"expected 0 <= eta < 1, got {c.eta!r}")
        if c.style == "explicit" and ("damping_clearance" in given or "eta" in given):
            raise SceneError(path, f"{where}.style", "explicit-style damping acts while closed only: "
                                                     "damping_clearance and eta are standard-style keys")
    if c.tangent_fraction != -1.0 and c.tangent_fraction < 0:
        raise SceneError(path, f"{where}.tangent_fraction", "expected a ratio >= 0 (or -1 for the default)")
