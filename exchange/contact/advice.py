"""Starting values for contact damping: μ0 from a run's peaks, or from a column's buckling load and the time
increment (Abaqus Analysis User's Guide 37.1.3, "Contact damping": damping to suppress chatter)."""
from __future__ import annotations

import math

__all__ = ["suggest_mu0", "suggest_mu0_euler_column"]


def suggest_mu0(peak_pressure: float, peak_velocity: float, fraction: float = 0.01) -> float:
    r"""A starting damping coefficient from a run's peak contact pressure and peak approach speed [Pa·s/m].

    .. math:: \mu_0 = \phi\, \frac{P_{peak}}{|v|_{peak}}

    so that at the fastest approach the viscous pressure is only a fraction φ of the largest contact pressure:
    enough to damp chatter, too small to change the load carried. Raise φ if the contact still chatters; the
    result should not depend on it. This is the pressure analogue of :func:`suggest_mu0_euler_column`, which sizes
    μ0 from a stiffness and the time increment instead.

    Examples
    --------
    >>> suggest_mu0(2e6, 4.0)
    5000.0
    """
    if not (peak_pressure > 0.0 and peak_velocity != 0.0 and fraction > 0.0):
        raise ValueError("need peak_pressure > 0, peak_velocity != 0 and fraction > 0")
    return fraction * peak_pressure / abs(peak_velocity)


def suggest_mu0_euler_column(dt: float, length: float, load: float, critical_load: float) -> float:
    r"""Starting damping coefficient for a column loaded beyond buckling [N·s/m] (Euler buckling of a pinned
    column, Timoshenko & Gere, *Theory of Elastic Stability*, ch. 2).

    .. math:: \mu_0 \approx \Delta t\,\frac{\pi^2}{2 l}\,(P - P_{crit})

    The first sine mode w = a·sin(πx/l) of a pinned column under axial load P has generalized stiffness
    (P_crit − P)·π²/(2l), negative past buckling. A dashpot μ0 = Δt·|k| gives the unstable mode a growth time of
    one increment Δt, so the snap-through is resolved instead of jumping.

    Examples
    --------
    >>> round(suggest_mu0_euler_column(1e-3, 1.0, 1200.0, 1000.0), 6)
    0.98696
    """
    if not (dt > 0.0 and length > 0.0):
        raise ValueError("need dt > 0 s and length > 0 m")
    return dt * math.pi ** 2 / (2.0 * length) * abs(load - critical_load)
