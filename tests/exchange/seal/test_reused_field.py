"""A field tried first in the film solve (the neighbouring load's) is kept only where it solves the system to
round-off."""
import numpy as np

import exchange.seal.reynolds as reynolds
from exchange.seal.film import seal_film
from exchange.seal.meshes import annulus_mesh
from exchange.seal.reynolds import film_conductance


def _film():
    return seal_film(*annulus_mesh(0.01, 0.02, 6, 48))


def test_a_field_of_scaled_coefficients_is_kept_and_gives_the_flux(monkeypatch):
    """Every gap × 1.7: the same field; kept without a factorisation, the flux equals the direct one to 1e-14."""
    film = _film()
    h = 1e-6 * (1.0 + 0.5 * np.random.default_rng(5).random(film.n_nodes))
    _, first = film_conductance(film, h)
    direct, _ = film_conductance(film, 1.7 * h)
    calls = []
    solve = reynolds._solve
    monkeypatch.setattr(reynolds, "_solve", lambda *a: calls.append(1) or solve(*a))
    reused, solution = film_conductance(film, 1.7 * h, guess=first.u)
    assert calls == [] and abs(reused / direct - 1.0) <= 1e-14
    assert abs(solution.inflow / solution.outflow - 1.0) <= 1e-12


def test_a_field_of_another_gap_is_refused():
    """A field of a different gap shape (a tilted flange) fails the residual test: the direct solve's result, bit
    for bit; a field with nodes off the old leak path (nan) too."""
    film = _film()
    rng = np.random.default_rng(6)
    h = 1e-6 * (1.0 + rng.random(film.n_nodes))
    _, other = film_conductance(film, 1e-6 * (1.0 + 1e-6 * rng.random(film.n_nodes)))
    direct, d = film_conductance(film, h)
    for guess in (other.u, np.full(film.n_nodes, np.nan)):
        flux, s = film_conductance(film, h, guess=guess)
        assert flux == direct and np.array_equal(s.u, d.u, equal_nan=True)
