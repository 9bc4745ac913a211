r"""Calibrate a gap law on a measured leak-rate-versus-contact-pressure curve.

A gasket or seal ring pressed uniformly with contact pressure p has a uniform channel h(p), so its film is a
uniform annulus and its leak follows the closed form of :mod:`exchange.seal.reynolds`,

.. math:: \dot m(p) = \frac{\pi\, h(p)^3 (p_1^2 - p_2^2)}{12\,\mu R T \ln(r_o/r_i)}
          \;\left(1 + \frac{12\,c}{h (p_1 + p_2)}\right)^{[slip]}, \qquad c = \lambda p,

:func:`annulus_mass_flow`. :func:`fit_gap_law` finds the (at most three) parameters of a gap law that make this
curve pass through measured (p, ṁ) points, by least squares on log ṁ (scipy.optimize.least_squares), and returns
the law and the largest factor between the model and the measurement.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares

from exchange.seal.viscosity import mean_free_path

__all__ = ["annulus_mass_flow", "fit_gap_law"]


def annulus_mass_flow(h, p1, p2, r_inner, r_outer, temperature, viscosity, gas_constant, slip=False):
    r"""Mass flow through a uniform gap ``h`` [m] on an annulus ``r_inner``..``r_outer`` [m] [kg/s].

    .. math:: \dot m = \frac{\pi h^3 (p_1^2 - p_2^2)}{12 \mu R T \ln(r_o/r_i)}

    ``p1``, ``p2`` absolute pressures [Pa] inside and outside, T [K], μ [Pa s], R [J/(kg K)]; with ``slip`` the
    first-order slip term 12·c·(p1 − p2)/h is added to p1² − p2² (c = λ·p, exact for a uniform gap).

    >>> float(round(annulus_mass_flow(5e-6, 3e5, 1e5, 0.01, 0.02, 293.15, 1.76e-5, 296.8) * 1e6, 6))
    2.466475
    """
    drive = p1 * p1 - p2 * p2
    if slip:
        drive = drive + 12.0 * mean_free_path(1.0, temperature, viscosity, gas_constant) * (p1 - p2) / np.asarray(h)
    return math.pi * np.asarray(h) ** 3 * drive / (12.0 * viscosity * gas_constant * temperature *
                                                   math.log(r_outer / r_inner))


def fit_gap_law(make_law, guess, pressures, leaks, flow):
    """Fit a gap law to measured leak rates.

    Parameters
    ----------
    make_law : callable
        ``make_law(*params)`` returns a gap law (e.g. :class:`~exchange.seal.gap_laws.ExponentialGap`).
    guess : sequence of float
        Positive starting parameters (at most 3; fitted in log space, so they stay positive).
    pressures, leaks : (k,) float
        Measured contact pressures [Pa] and leak rates [kg/s].
    flow : callable
        ``flow(h)`` the leak rate [kg/s] of the test ring with a uniform gap h [m] (e.g. a partial of
        :func:`annulus_mass_flow`).

    Returns
    -------
    (law, params, factor): the fitted law, its parameters and max over the points of max(ṁ/ṁ_meas, ṁ_meas/ṁ).
    """
    if len(guess) > 3:
        raise ValueError(f"at most three fitted parameters, got {len(guess)}")
    p, measured = np.asarray(pressures, float), np.asarray(leaks, float)

    def residual(x):
        model = flow(make_law(*np.exp(x)).gap(p))
        return np.log(np.maximum(model, 1e-300)) - np.log(measured)

    result = least_squares(residual, np.log(np.asarray(guess, float)), x_scale=1.0)
    params = np.exp(result.x)
    return make_law(*params), params, float(np.exp(np.max(np.abs(residual(result.x)))))
