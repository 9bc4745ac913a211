"""The compressible Reynolds film on a seal mesh against closed forms (exchange.seal.reynolds, .film, .chart).

Closed forms (radial flow, derived in docs/seals.md):
* uniform gap h on an annulus r_i..r_o: K = 2π h³/ln(r_o/r_i), ṁ = π h³ (p1² − p2²)/(12 μ R T ln(r_o/r_i));
* gap linear in r, h = a + b·r: K = 2π / ∫ dr/(r h³) with
  ∫ dr/(r (a + b r)³) = [ln(r/(a + b r)) + a/(a + b r) + a²/(2 (a + b r)²)] / a³;
* a sector of the ring closed over its whole width: the open sector's radial flow meets the closed sides with
  no flux, so K = (open angle / 2π) · the annulus's K;
* uniform gap with first-order slip: ṁ = K [h³(p1² − p2²) + 12 c h² (p1 − p2)] / (24 μ R T h³), c = λ·p.
"""
import math

import numpy as np
import pytest

from exchange.seal.film import seal_film
from exchange.seal.meshes import annulus_delaunay, annulus_mesh
from exchange.seal.percolation import is_sealed
from exchange.seal.reynolds import film_conductance, film_mass_flow
from exchange.seal.viscosity import mean_free_path

RI, RO = 0.010, 0.016


def annulus_K(h):
    return 2.0 * math.pi * h ** 3 / math.log(RO / RI)


def tilted(vertices, centre=(0.3, -0.2, 0.05)):
    """Rotate a z = 0 mesh into an oblique plane and move it: the chart must find the plane and the centre."""
    a, b = 0.4, 1.1
    rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    rz = np.array([[math.cos(b), -math.sin(b), 0], [math.sin(b), math.cos(b), 0], [0, 0, 1]])
    return vertices @ (rz @ rx).T + np.asarray(centre)


@pytest.mark.parametrize("triangles", [False, True])
@pytest.mark.parametrize("n_radial, n_angular", [(1, 3), (2, 12), (6, 72)])
def test_uniform_gap_annulus_is_exact(triangles, n_radial, n_angular):
    v, f = annulus_mesh(RI, RO, n_radial, n_angular, triangles=triangles)
    film = seal_film(tilted(v), f)
    assert film.chart == "polar"
    h = 7e-6
    K, solution = film_conductance(film, np.full(film.n_nodes, h))
    assert K == pytest.approx(annulus_K(h), rel=1e-9, abs=0)
    assert abs(solution.inflow - solution.outflow) <= 1e-12 * solution.inflow


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_uniform_gap_unstructured_triangles_are_exact(seed):
    v, f, inner, outer = annulus_delaunay(RI, RO, 48, 900, seed=seed)
    film = seal_film(v, f, high=inner, low=outer)
    K, _ = film_conductance(film, np.full(film.n_nodes, 3e-6))
    assert K == pytest.approx(annulus_K(3e-6), rel=1e-9, abs=0)


def test_mass_flow_matches_the_annulus_formula_both_ways():
    v, f = annulus_mesh(RI, RO, 4, 40, triangles=True)
    film = seal_film(v, f)
    h, p1, p2, T, mu, R = 4e-6, 5.0e5, 1.01325e5, 300.0, 1.79e-5, 296.8
    exact = math.pi * h ** 3 * (p1 ** 2 - p2 ** 2) / (12 * mu * R * T * math.log(RO / RI))
    m, solution = film_mass_flow(film, np.full(film.n_nodes, h), p1, p2, T, mu, R)
    assert m == pytest.approx(exact, rel=1e-9)
    back, _ = film_mass_flow(film, np.full(film.n_nodes, h), p2, p1, T, mu, R)
    assert back == pytest.approx(-exact, rel=1e-9)
    assert np.nanmax(np.sqrt(solution.u)) == pytest.approx(p1) and np.nanmin(np.sqrt(solution.u)) == pytest.approx(p2)


def linear_gap_K(h_i, h_o):
    b = (h_o - h_i) / (RO - RI)
    a = h_i - b * RI

    def primitive(r):
        w = a + b * r
        return (math.log(r / w) + a / w + a * a / (2 * w * w)) / a ** 3
    return 2.0 * math.pi / (primitive(RO) - primitive(RI))


@pytest.mark.parametrize("triangles", [False, True])
@pytest.mark.parametrize("chart", ["polar", "local"])
def test_linear_gap_converges_at_second_order(triangles, chart):
    h_i, h_o = 2e-6, 9e-6
    exact = linear_gap_K(h_i, h_o)
    errors = []
    for n in (4, 8, 16, 32):
        v, f = annulus_mesh(RI, RO, n, 6 * n, triangles=triangles)
        film = seal_film(v, f, chart=chart)
        r = np.hypot(v[:, 0], v[:, 1])
        K, solution = film_conductance(film, h_i + (h_o - h_i) * (r - RI) / (RO - RI))
        assert abs(solution.inflow - solution.outflow) <= 1e-12 * K
        errors.append(abs(K / exact - 1.0))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert errors[-1] < 1e-3
    assert np.all(rates > 1.8), (errors, rates)


def test_random_gap_conserves_mass():
    v, f, inner, outer = annulus_delaunay(RI, RO, 40, 600, seed=3)
    film = seal_film(v, f, high=inner, low=outer)
    h = np.random.default_rng(1).uniform(1e-7, 8e-6, film.n_nodes)
    m, solution = film_mass_flow(film, h, 3e5, 1e5, 293.15, 1.76e-5, 296.8)
    assert m > 0.0 and abs(solution.inflow - solution.outflow) <= 1e-12 * solution.inflow
    assert solution.flux == pytest.approx(solution.inflow, rel=1e-10)  # Dirichlet energy = edge reactions


@pytest.mark.parametrize("triangles", [False, True])
@pytest.mark.parametrize("closed", [(0, 0), (5, 13), (30, 64)])
def test_closed_sector_leaks_through_the_open_sectors(triangles, closed):
    n_angular, (ja, jb) = 72, closed
    v, f = annulus_mesh(RI, RO, 5, n_angular, triangles=triangles)
    film = seal_film(v, f)
    j = np.arange(film.n_nodes) % n_angular
    h = np.where((j >= ja) & (j <= jb), 0.0, 5e-6)
    K, _ = film_conductance(film, h)
    open_columns = n_angular - (jb - ja + 2)  # element columns touching no closed node
    assert K == pytest.approx(annulus_K(5e-6) * open_columns / n_angular, rel=1e-9)


@pytest.mark.parametrize("triangles", [False, True])
def test_one_open_column_carries_its_share(triangles):
    n_angular = 40
    v, f = annulus_mesh(RI, RO, 4, n_angular, triangles=triangles)
    film = seal_film(v, f)
    j = np.arange(film.n_nodes) % n_angular
    h = np.where((j == 10) | (j == 11), 2e-6, 0.0)
    K, _ = film_conductance(film, h)
    assert K == pytest.approx(annulus_K(2e-6) / n_angular, rel=1e-9)


@pytest.mark.parametrize("triangles", [False, True])
def test_a_ring_closed_all_around_leaks_exactly_nothing(triangles):
    v, f = annulus_mesh(RI, RO, 6, 48, triangles=triangles)
    film = seal_film(v, f)
    ring = np.arange(film.n_nodes) // 48 == 3
    h = np.where(ring, 0.0, 5e-6)
    K, solution = film_conductance(film, h)
    assert K == 0.0 and solution.sealed and is_sealed(film, h)
    m, _ = film_mass_flow(film, h, 1e7, 1e5, 300.0, 1.8e-5, 287.0, slip=True)
    assert m == 0.0
    h[3 * 48 + 17] = h[3 * 48 + 18] = 1e-12  # two neighbours barely open: one element column is a leak path
    assert not is_sealed(film, h)
    assert film_conductance(film, h)[0] > 0.0


def test_slip_on_a_uniform_gap_is_exact():
    v, f = annulus_mesh(RI, RO, 3, 30)
    film = seal_film(v, f)
    h, p1, p2, T, mu, R = 0.3e-6, 2.0e5, 1.0e5, 293.15, 1.81e-5, 287.05
    c = mean_free_path(1.0, T, mu, R)  # λ·p
    m, _ = film_mass_flow(film, np.full(film.n_nodes, h), p1, p2, T, mu, R, slip=True)
    exact = annulus_K(h) * ((p1 ** 2 - p2 ** 2) + 12.0 * c * (p1 - p2) / h) / (24 * mu * R * T)
    assert m == pytest.approx(exact, rel=1e-9)
    no_slip, _ = film_mass_flow(film, np.full(film.n_nodes, h), p1, p2, T, mu, R)
    assert m / no_slip == pytest.approx(1 + 6 * c / (0.5 * (p1 + p2)) / h, rel=1e-9)  # 1 + 6 Kn at the mean p


def test_edges_from_loops_and_node_sets():
    v, f = annulus_mesh(RI, RO, 2, 16)
    inward = seal_film(v, f, high="outer", low="inner")
    outward = seal_film(v, f)
    h = np.full(len(v), 2e-6)
    assert film_conductance(inward, h)[0] == pytest.approx(film_conductance(outward, h)[0], rel=1e-12)
    with pytest.raises(ValueError, match="exactly 2 boundary loops"):
        seal_film(v[:32], f[:16][np.all(f[:16] < 32, axis=1)] if False else np.array([[0, 1, 17, 16]]))
    with pytest.raises(ValueError, match="chart must be"):
        seal_film(v, f, chart="cartesian")
    with pytest.raises(ValueError, match="gaps must be"):
        film_conductance(outward, np.full(len(v), -1.0))


@pytest.mark.parametrize("fluid", ["Air", "Nitrogen"])
def test_sutherland_viscosity_is_within_one_percent_of_coolprop(fluid):
    from exchange.seal.viscosity import SUTHERLAND, coolprop_viscosity, sutherland_viscosity
    for T in np.linspace(250.0, 400.0, 7):  # air: 1.3 % at 500 K
        assert sutherland_viscosity(T, *SUTHERLAND[fluid]) == pytest.approx(coolprop_viscosity(T, fluid), rel=0.01)


def test_mean_free_path_of_air():
    from exchange.seal.viscosity import coolprop_viscosity
    lam = mean_free_path(101325.0, 293.15, coolprop_viscosity(293.15, "Air"), 287.05)
    assert 60e-9 < lam < 70e-9  # 65 nm; tabulated ≈ 68 nm (hard-sphere estimates differ by a few %)


@pytest.mark.parametrize("triangles", [False, True])
def test_conical_seal_face_converges_to_the_unrolled_annulus(triangles):
    """A cone z = r·tan α unrolls into a plane annular sector of angle 2π·cos α between slant radii r/cos α:
    K = 2π cos α h³ / ln(r_o/r_i). The local chart converges to it at second order."""
    alpha, h = math.radians(30.0), 3e-6
    exact = 2.0 * math.pi * math.cos(alpha) * h ** 3 / math.log(RO / RI)
    errors = []
    for n in (4, 8, 16):
        v, f = annulus_mesh(RI, RO, n, 12 * n, triangles=triangles)
        v[:, 2] = np.hypot(v[:, 0], v[:, 1]) * math.tan(alpha)
        film = seal_film(v, f)
        assert film.chart == "local"
        errors.append(abs(film_conductance(film, np.full(film.n_nodes, h))[0] / exact - 1.0))
    assert errors[-1] < 1e-3 and np.all(np.log2(np.array(errors[:-1]) / np.array(errors[1:])) > 1.8), errors


def test_degenerate_elements_are_named():
    v, f = annulus_mesh(RI, RO, 2, 16, triangles=True)
    v[20] = v[4]  # collapse: node 20 onto node 4 (same angle, inner row) makes its triangles flat
    with pytest.raises(ValueError, match="has no area|twisted"):
        seal_film(v, f, chart="local")
