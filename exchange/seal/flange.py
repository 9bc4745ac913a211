r"""A bolted flange on a gasket holding a pressurised vessel: when its seal leaks and when it lifts.

A rigid flange held on a gasket ring of area A_g by a preload F_b (bolts) closes a vessel whose gauge pressure
p − p_a pushes it off over the area A_p inside the seal. While it rests on the gasket (hard contact) the
gasket's contact pressure is what the preload leaves,

.. math:: p_{contact} = \frac{F_b - (p - p_a) A_p}{A_g},

uniform over a flat flange and ring. The seal's channel opens when p_contact falls below the gap law's closing
pressure p_c (:meth:`~exchange.seal.gap_laws.ExponentialGap.closing_pressure`), so the leak starts at

.. math:: p_{onset} = p_a + \frac{F_b - p_c A_g}{A_p},

and the flange lifts off the gasket when the contact pressure reaches 0, at p_lift = p_a + F_b/A_p. A gap law
that never closes leaks at every pressure (p_onset = −inf: the leak only grows as p rises). Static balance of a
rigid flange; its weight and any spring are part of F_b.
"""
from __future__ import annotations

import math

__all__ = ["gasket_contact_pressure", "leak_onset_pressure", "lift_off_pressure"]


def gasket_contact_pressure(pressure, preload, gasket_area, pressure_area, ambient=101325.0):
    """Contact pressure on the gasket [Pa] of a flange preloaded with ``preload`` [N] at vessel ``pressure`` [Pa]
    (``gasket_area``, ``pressure_area`` [m²]; negative: the flange has lifted).

    >>> gasket_contact_pressure(201325.0, 2e4, 1e-3, 0.01)
    19000000.0
    """
    return (preload - (pressure - ambient) * pressure_area) / gasket_area


def leak_onset_pressure(preload, gasket_area, pressure_area, closing_pressure, ambient=101325.0):
    """Vessel pressure [Pa] at which the gasket's channel opens (module formula; −inf if it never closes).

    >>> leak_onset_pressure(2e4, 1e-3, 0.01, 1.0e7)
    1101325.0
    """
    if not math.isfinite(closing_pressure):
        return -math.inf
    return ambient + (preload - closing_pressure * gasket_area) / pressure_area


def lift_off_pressure(preload, pressure_area, ambient=101325.0):
    """Vessel pressure [Pa] at which the flange leaves the gasket: p_a + F_b/A_p.

    >>> lift_off_pressure(2e4, 0.01)
    2101325.0
    """
    return ambient + preload / pressure_area
