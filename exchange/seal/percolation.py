"""Leak paths through a seal film: which elements conduct, and whether any conducting path joins the edges.

An element conducts with k_e = G²·H, G and H the geometric and harmonic means of its nodes' gaps: for two nodes
this is 2 h_a² h_b²/(h_a + h_b), the exact conductance ∫ ds / ∫ ds/h³ of a slot whose gap varies linearly between
them; it is h³ for a uniform gap, second-order accurate for a smooth one (10× smaller error than the harmonic
mean of h³ on a ring whose gap varies 4.5× across, tests/exchange/test_seal_film.py), and exactly 0 when one
node's channel is closed, tending to 0 continuously (as h^(1+2/N)) as it closes. The leak path exists if a connected set of
conducting elements joins a node of the pressurised edge to a node of the outer edge: the connected components
of the graph "two nodes share a conducting element" (scipy.sparse.csgraph) decide it exactly, in integers, with no
threshold. A ring of closed nodes all around the seal therefore leaks exactly nothing.
"""
from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from exchange.seal.surface import element_pairs

__all__ = ["series_coefficient", "element_coefficients", "leak_path_nodes", "is_sealed"]


def series_coefficient(h, power=3):
    """(m,) element coefficients of element gaps ``h`` (m, N) [m]: k_e = G²·H [m³] for ``power`` 3 (module
    notes), G² [m²] for ``power`` 2 (the slip term's h², exact for a linear 1-D slot: ∫ds/∫ds/h² = h_a·h_b).

    >>> series_coefficient(np.array([[1.0, 1.5], [2.0, 2.0], [1.0, 0.0]])).round(12).tolist()
    [1.8, 8.0, 0.0]
    >>> series_coefficient(np.array([[1.0, 1.5]]), power=2).round(12).tolist()
    [1.5]
    """
    if power not in (2, 3):
        raise ValueError(f"power must be 2 or 3, got {power!r}")
    open_ = np.all(h > 0.0, axis=1)
    safe = np.where(h > 0.0, h, 1.0)
    n = h.shape[1]
    k = np.exp(2.0 * np.mean(np.log(safe), axis=1))
    if power == 3:
        k = k * n / np.sum(1.0 / safe, axis=1)
    return np.where(open_, k, 0.0)


def element_coefficients(film, gaps, power=3):
    """(k_tri (mt,), k_quad (mq,)) [m³]: :func:`series_coefficient` of every element, 0 if a node is closed.

    >>> from exchange.seal.film import seal_film
    >>> from exchange.seal.meshes import annulus_mesh
    >>> film = seal_film(*annulus_mesh(0.01, 0.02, 2, 8))
    >>> h = np.full(film.n_nodes, 2e-6)
    >>> float(element_coefficients(film, h)[1][0])
    8e-18
    """
    h = np.asarray(gaps, dtype=float)
    if h.shape != (film.n_nodes,) or np.any(h < 0.0) or not np.isfinite(h).all():
        raise ValueError(f"gaps must be {film.n_nodes} finite numbers >= 0 [m], one per node")
    return series_coefficient(h[film.triangles], power), series_coefficient(h[film.quads], power)


def leak_path_nodes(film, k_tri, k_quad):
    """(through, high_side, low_side): (n,) bool masks of the nodes on a conducting path joining both edges, and
    of the nodes connected to the pressurised edge only or to the outer edge only."""
    pairs = element_pairs(film.triangles[k_tri > 0.0], film.quads[k_quad > 0.0])
    n = film.n_nodes
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    count, labels = connected_components(graph, directed=False)
    touches_high = np.zeros(count, bool)
    touches_low = np.zeros(count, bool)
    touches_high[labels[film.high]] = True
    touches_low[labels[film.low]] = True
    both = touches_high & touches_low
    return both[labels], (touches_high & ~both)[labels], (touches_low & ~both)[labels]


def is_sealed(film, gaps):
    """True when no conducting path joins the pressurised edge to the outer edge (exact).

    >>> from exchange.seal.film import seal_film
    >>> from exchange.seal.meshes import annulus_mesh
    >>> film = seal_film(*annulus_mesh(0.01, 0.02, 2, 8))
    >>> h = np.full(film.n_nodes, 1e-6)
    >>> is_sealed(film, h), is_sealed(film, np.where(np.arange(film.n_nodes) // 8 == 1, 0.0, h))
    (False, True)
    """
    through, _, _ = leak_path_nodes(film, *element_coefficients(film, gaps))
    return not through.any()
