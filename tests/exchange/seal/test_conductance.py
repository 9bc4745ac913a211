"""The seal's conductance along a load path (exchange.seal.conductance, .load_paths, .channel).

Closed forms: a flat flange parallel to a flat ring gives every node the same channel h(s), so the film is a
uniform annulus and K(s) = 2π h(s)³/ln(r_o/r_i); it closes where every node closes at once,
s* = g0 − g_c (g_c the closing clearance: −p_c/k for penalty contact, 0 for softened contact without a gap law).
A tilted flange closes the ring progressively; its closure load is checked against a brute-force scan.
"""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from exchange.contact.laws import softened_pressure
from exchange.seal.conductance import closure_load, conductance_curve
from exchange.seal.film import seal_film
from exchange.seal.gap_laws import ExponentialGap, NoGap, PerssonGap, TableGap
from exchange.seal.hysteresis import PVRCGap
from exchange.seal.load_paths import DisplacementPath, ReactionPath
from exchange.seal.meshes import annulus_mesh, flat_flange_seat
from exchange.seal.percolation import element_coefficients, leak_path_nodes
from exchange.seal.reynolds import film_conductance

RI, RO = 0.020, 0.025


def law(kind, a=0.0, b=0.0, size=RO):
    return np.array([float(kind), a, b, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, size])


@pytest.fixture(scope="module")
def film():
    return seal_film(*annulus_mesh(RI, RO, 6, 96))


def annulus_K(h):
    return 2.0 * math.pi * np.asarray(h) ** 3 / math.log(RO / RI)


def assert_within_tolerance(curve, q, exact, rtol, lower, upper, factor=10.0):
    """|curve − K| <= factor·(rtol·K + atol + qtol·|K'|) with the build's default atol and qtol (the midpoint
    test estimates the error of each piece; it is not a bound, hence the factor)."""
    k = exact(q)
    slope = (exact(q + 1e-6 * (upper - lower)) - exact(q - 1e-6 * (upper - lower))) / (2e-6 * (upper - lower))
    atol, qtol = rtol * 1e-3 * curve.values.max(), rtol * (upper - lower)
    error = np.abs(curve(q) - k)
    bound = factor * (rtol * k + atol + qtol * np.abs(slope))
    assert np.all(error <= bound), np.max(error / bound)


def test_flat_flange_penalty_exponential_gap(film):
    g0, k, gap = 1e-6, 1e13, ExponentialGap(h0=4e-6, p0=5e6, u_c=0.5e-6)
    path = DisplacementPath(flat_flange_seat(film.vertices, film.areas, g0), law(1, k), gap)
    curve = conductance_curve(film, path, -3e-6, 6e-6, rtol=1e-6)
    assert curve.closure == g0 + gap.closing_pressure() / k  # every node closes at once: exact

    def exact(s):
        return annulus_K(np.maximum(g0 - s, 0.0) + gap.gap(k * np.maximum(s - g0, 0.0)))
    assert_within_tolerance(curve, np.linspace(-3e-6, curve.closure, 301)[1:-1], exact, 1e-6, -3e-6, 6e-6)
    assert curve(curve.closure) == 0.0 and curve(curve.closure + 1e-9) == 0.0
    assert curve(np.nextafter(curve.closure, -1.0)) > 0.0 or curve(curve.closure - 1e-15) >= 0.0
    assert np.all(np.diff(curve(np.linspace(-3e-6, 6e-6, 2001))) <= 0.0)  # monotone


def test_flat_flange_softened_contact_closes_at_zero_clearance(film):
    g0, c0, p0 = 2e-6, 1e-6, 1e6
    path = DisplacementPath(flat_flange_seat(film.vertices, film.areas, g0), law(2, c0, p0), NoGap())
    curve = conductance_curve(film, path, 0.0, 5e-6, rtol=1e-7)
    assert curve.closure == g0
    assert_within_tolerance(curve, np.linspace(0.0, g0, 200, endpoint=False)[1:], lambda s: annulus_K(g0 - s),
                            1e-7, 0.0, 5e-6)


def test_softened_contact_with_a_gap_law_closes_at_the_root_of_the_law(film):
    g0, c0, p0, gap = 1e-6, 1e-6, 1e6, ExponentialGap(h0=3e-6, p0=2e6, u_c=0.3e-6)
    path = DisplacementPath(flat_flange_seat(film.vertices, film.areas, g0), law(2, c0, p0), gap)
    s_star = closure_load(film, path.closing(), path.direction)
    overclosure = s_star - g0
    assert softened_pressure(overclosure, c0, p0) == pytest.approx(gap.closing_pressure(), rel=1e-14)


def test_hard_contact_reaction_path(film):
    gap = PerssonGap(u0=0.5e-6, p_star=2e8, u_c=1e-6, h_max=6e-6)
    nodes = flat_flange_seat(film.vertices, film.areas, 0.0)
    path = ReactionPath(nodes, law(0), gap, s_seat=0.0)
    assert path.contact.all()
    area = film.areas.sum()
    curve = conductance_curve(film, path, 0.0, 5e6, rtol=1e-6)
    assert curve.closure == pytest.approx(gap.closing_pressure() * area, rel=1e-15)
    force = np.linspace(0.0, curve.closure, 101)[1:-1]
    assert_within_tolerance(curve, force, lambda f: annulus_K(gap.gap(f / area)), 1e-6, 0.0, 5e6)


def test_tilted_flange_closure_matches_a_brute_force_scan(film):
    gap = TableGap((0.0, 5e6, 2e7), (3e-6, 1e-6, 0.0))
    path = DisplacementPath(flat_flange_seat(film.vertices, film.areas, 1e-6, slope=2e-5), law(1, 1e13), gap)
    closing = path.closing()
    s_star = closure_load(film, closing, path.direction)
    for s in np.unique(closing):  # naive: test every distinct closing load in turn
        closed = closing <= s
        gaps = np.where(closed, 0.0, 1.0)
        if not leak_path_nodes(film, *element_coefficients(film, gaps))[0].any():
            break
    assert s_star == s
    assert film_conductance(film, path.heights(s_star))[0] == 0.0
    assert film_conductance(film, path.heights(np.nextafter(s_star, -1.0)))[0] >= 0.0


def test_tilted_flange_curve_matches_direct_solves(film):
    gap = PerssonGap(u0=1e-6, p_star=1e8, u_c=2e-6, h_max=10e-6)
    path = DisplacementPath(flat_flange_seat(film.vertices, film.areas, 1e-6, slope=1e-5), law(1, 1e13), gap)
    curve = conductance_curve(film, path, -4e-6, 6e-6, rtol=1e-4)
    s = np.random.default_rng(0).uniform(-4e-6, curve.closure, 30)

    def direct(q):
        return np.array([film_conductance(film, path.heights(x))[0] for x in np.atleast_1d(q)])
    assert_within_tolerance(curve, s, direct, 1e-4, -4e-6, 6e-6)
    assert curve.solves < 200


def test_pvrc_unloading_is_tighter_than_loading(film):
    gap = PVRCGap(Gb=2e6, a=0.3, Gs=2e4, h1=8e-6, h_max=30e-6)
    seat = flat_flange_seat(film.vertices, film.areas, 0.0)
    loading = DisplacementPath(seat, law(1, 1e13), gap)
    unloading = DisplacementPath(seat, law(1, 1e13), gap, loaded_to=3e-6)
    k_load = conductance_curve(film, loading, 0.0, 3e-6, rtol=1e-5)
    k_unload = conductance_curve(film, unloading, 0.0, 3e-6, rtol=1e-5)
    assert k_unload(3e-6) == pytest.approx(k_load(3e-6), rel=1e-5)
    s = np.linspace(0.5e-6, 2.5e-6, 9)
    assert np.all(k_unload(s) < k_load(s))


def test_closure_of_a_slowly_loaded_flange_is_an_event(film):
    """A rigid 1 L vessel of nitrogen leaks through the seal while a flange is pressed down as s = s0 + a t²:
    the leak stops exactly when s(t) reaches s*, an event located to 1e-10 of the run."""
    g0, k, gap = 1e-6, 1e13, ExponentialGap(h0=4e-6, p0=5e6, u_c=0.5e-6)
    path = DisplacementPath(flat_flange_seat(film.vertices, film.areas, g0), law(1, k), gap)
    curve = conductance_curve(film, path, -1e-6, 4e-6, rtol=1e-6)
    s0, a, t_end = -1e-6, 2e-6, 2.0
    V, R, T, mu, p_amb = 1e-3, 296.8, 293.15, 1.76e-5, 1e5

    def rhs(t, y):
        p = y[0] * R * T / V
        return [-curve(s0 + a * t * t) * (p * p - p_amb * p_amb) / (24 * mu * R * T)]

    def closes(t, y):
        return s0 + a * t * t - curve.closure
    closes.terminal = True
    m0 = 5e5 * V / (R * T)
    run = solve_ivp(rhs, (0.0, t_end), [m0], method="DOP853", rtol=1e-10, atol=1e-16, events=closes)
    t_star = math.sqrt((curve.closure - s0) / a)
    assert abs(run.t_events[0][0] - t_star) <= 1e-10 * t_end
    assert run.y_events[0][0][0] < m0  # it leaked until then, and nothing after: K = 0 beyond s*
    assert curve(s0 + a * t_end ** 2) == 0.0


def test_engine_kernels_give_the_film_mass_flow_with_slip(film):
    """K and the slip conductance K_2 tabulated, then the engine's kernel: exact for a uniform gap."""
    from exchange.seal.kernels import seal_mass_flow
    from exchange.seal.reynolds import film_mass_flow
    from exchange.seal.viscosity import mean_free_path
    g0, k, gap = 0.2e-6, 1e13, ExponentialGap(h0=0.5e-6, p0=5e6, u_c=0.05e-6)
    path = DisplacementPath(flat_flange_seat(film.vertices, film.areas, g0), law(1, k), gap)
    k3 = conductance_curve(film, path, 0.0, 2e-6, rtol=1e-7)
    k2 = conductance_curve(film, path, 0.0, 2e-6, rtol=1e-7, power=2)
    assert k2.closure == k3.closure
    T, mu, R, p1, p2 = 293.15, 1.76e-5, 296.8, 3e5, 1e5
    c = mean_free_path(1.0, T, mu, R)
    for s in (0.0, 0.1e-6, 0.5e-6):
        expected, _ = film_mass_flow(film, path.heights(s), p1, p2, T, mu, R, slip=True)
        kernel = seal_mass_flow(k3(s), k2(s), p1, p2, T, mu, R, c)
        assert kernel == pytest.approx(expected, rel=1e-5)
        assert seal_mass_flow(k3(s), k2(s), p2, p1, T, mu, R, c) == pytest.approx(-kernel, rel=1e-12)


def test_leak_onset_of_a_preloaded_flange_is_where_the_reaction_path_opens(film):
    """The held flange's reaction F = F_b − (p − p_a)·A_p: the seal opens exactly at p_onset."""
    from exchange.seal.flange import leak_onset_pressure
    gap = ExponentialGap(h0=4e-6, p0=5e6, u_c=0.5e-6)
    path = ReactionPath(flat_flange_seat(film.vertices, film.areas, 0.0), law(0), gap, s_seat=0.0)
    curve = conductance_curve(film, path, 0.0, 2e5, rtol=1e-5)
    preload, a_p, p_a = 1.5e5, math.pi * RI ** 2, 101325.0
    onset = leak_onset_pressure(preload, path.contact_area, a_p, gap.closing_pressure(), p_a)

    def reaction(p):
        return preload - (p - p_a) * a_p
    assert reaction(onset) == pytest.approx(curve.closure, rel=1e-12)
    assert curve(reaction(onset * (1 - 1e-9))) == 0.0 and curve(reaction(onset * (1 + 1e-9))) > 0.0
