r"""A seal's conductance as a function of its load, built once so the engine evaluates it in O(1).

Along a load path (:mod:`exchange.seal.load_paths`: the flange's displacement s, or a held hard contact's
reaction F) the film conductance K(q) [m³] (:func:`exchange.seal.reynolds.film_conductance`) is continuous and
monotone (every channel narrows as the seal tightens, and K grows with every element coefficient by Dirichlet's
principle). It is tabulated as a monotone piecewise-cubic Hermite curve:

* **values and exact slopes** at each knot: dK/dq = Σ_e (dK/dk_e)(dk_e/dq) with dK/dk_e = the element's Dirichlet
  energy of the solved field (no extra solve), dk_e/dh_i from the element coefficient, dh_i/dq by a central difference
  of the (cheap) nodal heights;
* **adaptive knots**: an interval is split until the Hermite interpolant from its ends matches a Reynolds solve
  at its midpoint within rtol·K + atol (the midpoint then becomes a knot, so the final curve is finer than the
  tested one); Fritsch–Carlson limited slopes keep every piece monotone and K >= 0;
* **the closure load q\***, exact: each node's channel closes at a load known in closed form (or by a root solve
  to round-off) (:meth:`~exchange.seal.load_paths.DisplacementPath.closing`); sorting them and bisecting on how
  many are closed with the exact leak-path test (:func:`exchange.seal.percolation.leak_path_nodes`) gives the
  load at which the closed region first separates the edges. Beyond it K = 0 exactly; it is the event at which
  the engine stops the leak and the event of re-opening.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from exchange.seal.kernels import curve_conductance, hermite
from exchange.seal.percolation import element_coefficients, leak_path_nodes
from exchange.seal.reynolds import element_energies, film_conductance

__all__ = ["ConductanceCurve", "conductance_curve", "closure_load", "CURVE_RTOL", "MAX_SOLVES"]

#: Default relative tolerance of the tabulated conductance [-].
CURVE_RTOL = 1e-4
#: Reynolds solves one curve may spend before the build stops with an error.
MAX_SOLVES = 400


def closure_load(film, closing, direction):
    """The load q* [unit of q] at which the closed nodes first separate the pressurised edge from the outer edge.

    ``closing`` (n,) the load at which each node closes (±inf: never), ``direction`` +1 if nodes close as the load
    grows, −1 as it falls. Returns ``direction·inf`` if the seal never closes.

    >>> from exchange.seal.film import seal_film
    >>> from exchange.seal.meshes import annulus_mesh
    >>> film = seal_film(*annulus_mesh(0.01, 0.02, 2, 8))
    >>> closing = np.where(np.arange(24) // 8 == 1, np.arange(24) * 1.0, np.inf)  # middle ring closes at 8..15
    >>> closure_load(film, closing, 1.0)  # node 15, alone between closed 14 and 8, conducts through no element
    14.0
    """
    order = np.argsort(direction * closing, kind="stable")
    finite = int(np.isfinite(closing).sum())

    def sealed(k):
        gaps = np.ones(film.n_nodes)
        gaps[order[:k]] = 0.0
        return not leak_path_nodes(film, *element_coefficients(film, gaps))[0].any()

    if finite == 0 or not sealed(finite):
        return direction * math.inf
    lo, hi = 0, finite  # sealed(hi) holds, sealed(lo) does not (an all-open film leaks)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if sealed(mid) else (mid, hi)
    return float(closing[order[hi - 1]])


def _limited(ka, kb, sa, sb, w):
    """Fritsch–Carlson slopes keeping the cubic monotone between ka and kb (Fritsch & Carlson, SIAM J. Numer.
    Anal. 17 (1980) 238)."""
    secant = (kb - ka) / w
    if secant == 0.0:
        return 0.0, 0.0
    a, b = max(sa / secant, 0.0), max(sb / secant, 0.0)
    r = math.hypot(a, b)
    if r > 3.0:
        a, b = 3.0 * a / r, 3.0 * b / r
    return a * secant, b * secant


@dataclass(frozen=True, eq=False)
class ConductanceCurve:
    """Tabulated film conductance K(q) [m³] along a load path.

    Attributes
    ----------
    knots, values, slopes : (m,) float
        Increasing loads, K [m³] and dK/dq there (monotone-limited).
    closure : float
        The closure load q* (±inf if the seal does not close); K = 0 on the sealed side of it.
    direction : float
        +1: sealed for q >= closure; −1: sealed for q <= closure.
    solves : int
        Reynolds solves spent building the curve.
    error_estimate : float
        Largest midpoint difference accepted while refining [m³].

    Outside [knots[0], knots[-1]] on the open side K is held at the end value (the range was the caller's).
    """

    knots: np.ndarray
    values: np.ndarray
    slopes: np.ndarray
    closure: float
    direction: float
    solves: int
    error_estimate: float

    def __call__(self, q):
        """K [m³] at load(s) ``q`` (the engine's kernel :func:`exchange.seal.kernels.curve_conductance`)."""
        values = [curve_conductance(float(x), self.knots, self.values, self.slopes, self.closure, self.direction)
                  for x in np.ravel(q)]
        return float(values[0]) if np.ndim(q) == 0 else np.array(values).reshape(np.shape(q))

    def arrays(self):
        """The arrays the engine's kernel takes: knots, values, slopes [and closure, direction as floats]."""
        return {"knots": self.knots, "values": self.values, "slopes": self.slopes,
                "closure": float(self.closure), "direction": float(self.direction)}


def _sample(film, path, q, step, power, guess=None):
    """(K, dK/dq) at load q, and the solved field (None if sealed); ``guess`` a field tried first."""
    h = path.heights(q)
    k_cond, solution = film_conductance(film, h, power, guess)
    if solution.sealed:
        return (0.0, 0.0), None
    dh = (path.heights(q + step) - path.heights(q - step)) / (2.0 * step)
    slope = 0.0
    for elements, k, energy in zip((film.triangles, film.quads), (solution.k_tri, solution.k_quad),
                                   element_energies(film, solution)):
        if len(elements) == 0:
            continue
        he, n = h[elements], elements.shape[1]
        with np.errstate(divide="ignore", invalid="ignore"):
            harmonic = n / np.sum(1.0 / he, axis=1)
            dk = k[:, None] * (2.0 / (n * he) + (power - 2) * harmonic[:, None] / (n * he * he))  # d(G²H)/dh_i
        slope += float(np.sum(energy * np.sum(np.where(k[:, None] > 0.0, dk, 0.0) * dh[elements], axis=1)))
    return (k_cond, slope), solution.u


def conductance_curve(film, path, lower, upper, rtol=CURVE_RTOL, atol=None, qtol=None, max_solves=MAX_SOLVES,
                      power=3):
    """Build the :class:`ConductanceCurve` of ``film`` along ``path`` for loads in [``lower``, ``upper``].

    A piece is accepted when its midpoint error is within rtol·|K| + atol + qtol·|dK/dq|: ``rtol`` [-], ``atol``
    [m³] (default rtol·1e-3·max K) and ``qtol`` [unit of q] (default rtol·(upper − lower)), a tolerance on
    the load itself: a feature narrower than qtol (a node's first touch under a steep gap law) is smeared over
    qtol instead of being resolved. ``max_solves`` stops a runaway build with an error.
    """
    if not upper > lower:
        raise ValueError(f"the load range must have upper > lower, got [{lower!r}, {upper!r}]")
    closing = path.closing()
    q_star = closure_load(film, closing, path.direction)
    lo, hi = (lower, min(upper, q_star)) if path.direction > 0 else (max(lower, q_star), upper)
    if hi <= lo:  # sealed over the whole range
        return ConductanceCurve(np.array([lower, upper]), np.zeros(2), np.zeros(2), q_star, path.direction, 0, 0.0)
    step = 1e-7 * (hi - lo)
    samples, solves, field = {}, 0, None

    def sample(q):  # the last field solved is tried first: kept only where it solves the new system to round-off
        nonlocal solves, field
        if q not in samples:
            if q == q_star:
                samples[q] = (0.0, 0.0)
            else:
                samples[q], u = _sample(film, path, q, min(step, abs(q - q_star) / 2), power, field)
                field, solves = (field if u is None else u), solves + 1
        return samples[q]

    grid = list(np.linspace(lo, hi, 5))
    k_max = max(abs(sample(q)[0]) for q in grid)
    atol = rtol * 1e-3 * k_max if atol is None else atol
    qtol = rtol * (upper - lower) if qtol is None else qtol
    todo, knots, worst = list(zip(grid[:-1], grid[1:])), set(grid), 0.0
    while todo:
        a, b = todo.pop()
        (ka, sa), (kb, sb) = sample(a), sample(b)
        la, lb = _limited(ka, kb, sa, sb, b - a)
        m = 0.5 * (a + b)
        if not a < m < b:
            continue
        if solves >= max_solves:
            raise RuntimeError(f"the conductance curve needs more than {max_solves} Reynolds solves for rtol "
                               f"{rtol:g}: loosen rtol/atol or narrow the load range [{lower:g}, {upper:g}]")
        km, sm = sample(m)
        error = abs(hermite(m, a, b, ka, kb, la, lb) - km)
        knots.add(m)
        if error <= rtol * abs(km) + atol + qtol * abs(sm):
            worst = max(worst, error)
        else:
            todo.extend([(a, m), (m, b)])
    q = np.array(sorted(knots))
    values = np.array([sample(x)[0] for x in q])
    slopes = np.array([sample(x)[1] for x in q])
    for i in range(len(q) - 1):
        la, lb = _limited(values[i], values[i + 1], slopes[i], slopes[i + 1], q[i + 1] - q[i])
        slopes[i] = la if abs(la) < abs(slopes[i]) else slopes[i]
        slopes[i + 1] = lb if abs(lb) < abs(slopes[i + 1]) else slopes[i + 1]
    return ConductanceCurve(q, values, slopes, q_star, path.direction, solves, worst)
