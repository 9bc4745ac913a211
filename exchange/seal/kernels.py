r"""The seal law's right-hand-side kernels (numba, small, cached): what the engine evaluates per call.

* :func:`curve_conductance` — K(q) [m³] of a :class:`~exchange.seal.conductance.ConductanceCurve` from its arrays
  (binary search on the knots, one cubic Hermite piece; 0 on the sealed side of the closure load);
* :func:`seal_mass_flow` — the film's mass flow from the conductance, the two pressures and the gas:

.. math:: \dot m = \frac{K\,(p_{up}^2 - p_{down}^2) + 12\, c\, K_2\,(p_{up} - p_{down})}{24\,\mu R T}

  (c = λ·p the slip constant, K_2 the film conductance with k = h² (slip superposed, exact for a uniform gap);
  c = 0 without slip). Positive from "up" to "down"; antisymmetric, so either side may be the higher.

Plain ``@njit(cache=True)`` calls (no ``inline``): they compile once, in about a second, and link into a caller.
"""
from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["hermite", "curve_conductance", "seal_mass_flow"]


@njit(cache=True)
def hermite(q, qa, qb, ka, kb, sa, sb):
    """Cubic Hermite interpolant on [qa, qb] with end values ka, kb and slopes sa, sb, at q.

    >>> hermite(0.5, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0)
    0.5
    """
    w = qb - qa
    t = (q - qa) / w
    t2 = t * t
    t3 = t2 * t
    return (2.0 * t3 - 3.0 * t2 + 1.0) * ka + (t3 - 2.0 * t2 + t) * w * sa + (3.0 * t2 - 2.0 * t3) * kb + \
        (t3 - t2) * w * sb


@njit(cache=True)
def curve_conductance(q, knots, values, slopes, closure, direction):
    """K(q) [m³]: the tabulated curve at load ``q``, held at its end value outside the knots on the open side,
    0 where direction·(q − closure) >= 0, never negative.

    >>> knots, values, slopes = np.array([0.0, 1.0]), np.array([2.0, 1.0]), np.array([-1.0, -1.0])
    >>> curve_conductance(0.5, knots, values, slopes, 1.0, 1.0), curve_conductance(1.0, knots, values, slopes, 1.0, 1.0)
    (1.5, 0.0)
    """
    if direction * (q - closure) >= 0.0:
        return 0.0
    n = knots.shape[0]
    x = min(max(q, knots[0]), knots[n - 1])
    i = min(max(np.searchsorted(knots, x, side="right") - 1, 0), n - 2)
    k = hermite(x, knots[i], knots[i + 1], values[i], values[i + 1], slopes[i], slopes[i + 1])
    return k if k > 0.0 else 0.0


@njit(cache=True)
def seal_mass_flow(conductance, slip_conductance, p_up, p_down, temperature, viscosity, gas_constant, slip):
    """Mass flow through the seal film [kg/s] (module formula); ``slip`` = c = λ·p [Pa m] (0: no slip).

    >>> K = 2 * np.pi * 5e-6 ** 3 / np.log(2.0)
    >>> round(seal_mass_flow(K, 0.0, 3e5, 1e5, 293.15, 1.76e-5, 296.8, 0.0) * 1e6, 6)
    2.466475
    """
    drive = conductance * (p_up * p_up - p_down * p_down) + 12.0 * slip * slip_conductance * (p_up - p_down)
    return drive / (24.0 * viscosity * gas_constant * temperature)
