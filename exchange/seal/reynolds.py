r"""Isothermal laminar gas flow through a seal film: the compressible Reynolds equation on the seal mesh.

For a gas of viscosity μ, gas constant R and temperature T in a gap h(x) between two surfaces at rest (thin film,
no inertia, isothermal), the mass flux per unit width is

.. math:: \mathbf q = -\frac{\rho h^3}{12\mu}\nabla p = -\frac{h^3}{24\mu R T}\nabla(p^2),
          \qquad \rho = \frac{p}{RT},

and mass conservation ∇·q = 0 makes u = p² solve the linear equation ∇·(h³∇u) = 0, with u = p1² on the
pressurised edge, p2² on the outer edge and no flux across the other boundaries and the closed (contact) region.
The mass flow is ṁ = K (p1² − p2²)/(24 μ R T), with the film's conductance K [m³] the flux of h³∇u for a unit
difference of u; for a uniform gap on an annulus r_i..r_o, K = 2π h³/ln(r_o/r_i), so
ṁ = π h³ (p1² − p2²)/(12 μ R T ln(r_o/r_i)). Sources: Reynolds, Phil. Trans. R. Soc. 177 (1886) 157; the gas
form, e.g. Gross, *Gas Film Lubrication* (1962), ch. 2; Hamrock, *Fundamentals of Fluid Film Lubrication*, ch. 7.

**Slip.** For micron gaps the first-order (Maxwell) slip condition multiplies the Poiseuille flux by
(1 + 6 Kn), Kn = λ/h (Burgdorfer, J. Basic Eng. 81 (1959) 94), with the mean free path λ = (μ/p)·√(πRT/2)
(:func:`exchange.seal.viscosity.mean_free_path`). Then k = h³(1 + 6λ/h) depends on p, and the equation is solved
by fixed-point iteration on the element pressures. For a uniform gap it is exact:
ṁ = K [(p1² − p2²) + 12 c (p1 − p2)/h]/(24 μ R T), c = λ·p.

**Discretisation.** Linear triangles and bilinear quads in a chart of the surface (:mod:`exchange.seal.chart`),
one coefficient per element (:func:`exchange.seal.percolation.element_coefficients`), a direct sparse solve
(scipy.sparse.linalg.splu, in a minimum-degree order computed once per film) on the nodes of the conducting paths
that join the edges. The inflow and the
outflow are the reactions of the assembled operator at the edge nodes; they balance to the solver's round-off.
"""
from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np
from scipy.sparse import csr_matrix, diags
from scipy.sparse.linalg import splu

from exchange.seal.percolation import element_coefficients, leak_path_nodes
from exchange.seal.viscosity import mean_free_path

__all__ = ["FilmSolution", "solve_film", "film_conductance", "film_mass_flow", "element_energies",
           "SLIP_RTOL", "SLIP_MAX_ITERATIONS", "GUESS_TOL"]

#: Relative change of the mass flow below which the slip iteration stops [-].
SLIP_RTOL = 1e-13
#: Iterations before the slip iteration is declared failed [-].
SLIP_MAX_ITERATIONS = 100
#: Componentwise backward error at which a guessed field is kept instead of a direct solve [-].
GUESS_TOL = 1e-14


@dataclass(frozen=True, eq=False)
class FilmSolution:
    """Solution of ∇·(k∇u) = 0 on a seal film.

    Attributes
    ----------
    flux : float
        Flux of k∇u from the pressurised edge to the outer edge [m³ × unit of u], from the Dirichlet energy:
        flux = Σ_e k_e u_eᵀK_e u_e / (u_high − u_low) (>= 0 for u_high > u_low; its round-off error is quadratic
        in the solve's, so it stays accurate where a nearly closed element carries the whole flow).
    inflow, outflow : float
        The same flux as the reactions of the operator at the pressurised and the outer edge nodes (they balance
        to round-off: mass conservation).
    u : (n,) float
        Nodal u (nan on nodes joined to neither edge by a conducting path).
    k_tri, k_quad : (mt,), (mq,) float
        Element coefficients [m³] used.
    sealed : bool
        True when no conducting path joins the edges (inflow = outflow = 0 exactly).
    """

    flux: float
    inflow: float
    outflow: float
    u: np.ndarray
    k_tri: np.ndarray
    k_quad: np.ndarray
    sealed: bool


def _assemble(film, k_tri, k_quad, used_tri, used_quad):
    """The film operator Σ_e k_e K_e over the used elements, on the film's fixed CSR pattern."""
    indptr, indices = film.pattern
    weights = np.concatenate([(np.where(used_tri, k_tri, 0.0)[:, None, None] * film.stiffness_tri).ravel(),
                              (np.where(used_quad, k_quad, 0.0)[:, None, None] * film.stiffness_quad).ravel()])
    slots = np.concatenate([film.slots_tri.ravel(), film.slots_quad.ravel()])
    data = np.bincount(slots, weights=weights, minlength=len(indices))
    n = film.n_nodes
    return csr_matrix((data, indices, indptr), shape=(n, n))


#: The elimination rank of each film's nodes (:func:`_elimination_rank`), computed once per film.
_RANKS = weakref.WeakKeyDictionary()


def _elimination_rank(film):
    """(n,) rank of every node in a fill-reducing elimination order of the film's interior system (−1 on the
    edges): SuperLU's minimum degree on AᵀA + A of the film's pattern, computed once per film. The pattern is fixed
    and only the coefficients change between solves, so each solve takes its free nodes in this order instead of
    ordering again (the order restricted to a subset stays fill-reducing)."""
    rank = _RANKS.get(film)
    if rank is None:
        indptr, indices = film.pattern
        interior = np.flatnonzero(~film.high & ~film.low)
        rank = np.full(film.n_nodes, -1)
        n = film.n_nodes
        pattern = csr_matrix((np.ones(len(indices)), indices, indptr), shape=(n, n))[interior][:, interior]
        # strictly diagonally dominant on the same pattern: the order depends on the pattern only
        spd = diags(2.0 * np.asarray(pattern.sum(axis=1)).ravel() + 2.0) - pattern
        rank[interior] = splu(spd.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                              options={"SymmetricMode": True}).perm_c if len(interior) else []
        _RANKS[film] = rank
    return rank


def _solve(matrix, rhs):
    """Direct sparse solve of the symmetric positive definite film system, its rows and columns already in
    elimination order (:func:`_elimination_rank`): SuperLU with symmetric (diagonal) pivoting and small
    supernodes (relax = panel size = 4: a film's supernodes are narrow; about 1.3× faster than the defaults on
    rings of 5k to 80k nodes, the same factors)."""
    if matrix.shape[0] == 1:
        return rhs / matrix.toarray().ravel()
    lu = splu(matrix, permc_spec="NATURAL", diag_pivot_thresh=0.0, relax=4, panel_size=4,
              options={"SymmetricMode": True})
    return lu.solve(rhs)


def _accepted(matrix, rhs, x):
    """``x`` if it solves matrix·x = rhs to a componentwise backward error of GUESS_TOL in every row
    (Oettli–Prager: |A x − b| <= tol·(|A| |x| + |b|), x then exactly solves a system whose entries differ by at
    most that relative amount, as a direct solve's do by round-off), else None."""
    if x is None or not np.isfinite(x).all():
        return None
    bound = abs(matrix) @ np.abs(x) + np.abs(rhs)
    return x if np.all(np.abs(matrix @ x - rhs) <= GUESS_TOL * bound) else None


def solve_film(film, k_tri, k_quad, u_high, u_low, guess=None):
    """Solve ∇·(k∇u) = 0 with u = ``u_high`` on the pressurised edge and ``u_low`` on the outer edge.

    ``k_tri``, ``k_quad`` element coefficients [m³] (:func:`exchange.seal.percolation.element_coefficients`);
    ``guess`` (n,) a field u tried first (e.g. the solution at a neighbouring load): kept where it solves this
    system to round-off (:func:`_accepted`; a film whose coefficients all scale by one factor has the same field),
    else the system is factorised. Returns a :class:`FilmSolution`.
    """
    through, high_side, low_side = leak_path_nodes(film, k_tri, k_quad)
    u = np.full(film.n_nodes, np.nan)
    u[high_side] = u_high
    u[low_side] = u_low
    if not through.any():
        return FilmSolution(0.0, 0.0, 0.0, u, k_tri, k_quad, True)
    used_tri = (k_tri > 0.0) & through[film.triangles[:, 0]]
    used_quad = (k_quad > 0.0) & through[film.quads[:, 0]]
    matrix = _assemble(film, k_tri, k_quad, used_tri, used_quad)
    fixed_high, fixed_low = through & film.high, through & film.low
    free = through & ~film.high & ~film.low
    u[fixed_high], u[fixed_low] = u_high, u_low
    if free.any():
        order = np.flatnonzero(free)
        order = order[np.argsort(_elimination_rank(film)[order], kind="stable")]
        rows = matrix[order]
        rhs = -(rows[:, fixed_high | fixed_low] @ u[fixed_high | fixed_low])
        a_ff = rows[:, order].tocsc()
        x = None if guess is None else _accepted(a_ff, rhs, np.asarray(guess, float)[order])
        u[order] = _solve(a_ff, rhs) if x is None else x
    field = np.where(through, u, 0.0)
    reaction = matrix @ field
    energy = float(np.sum(field * reaction))  # not a BLAS dot: its idle threads spin and cost CPU
    flux = energy / (u_high - u_low) if u_high != u_low else 0.0
    return FilmSolution(flux, float(reaction[fixed_high].sum()), float(-reaction[fixed_low].sum()), u, k_tri,
                        k_quad, False)


def element_energies(film, solution):
    """(e_tri (mt,), e_quad (mq,)): u_eᵀ K_e u_e of every element with unit coefficient (0 off the leak path).

    By the variational principle the conductance's sensitivity to an element coefficient is this energy:
    dK/dk_e = e_e for the unit-difference problem (Dirichlet's principle).
    """
    out = []
    for elements, stiffness in ((film.triangles, film.stiffness_tri), (film.quads, film.stiffness_quad)):
        ue = np.nan_to_num(solution.u[elements])
        out.append(np.einsum("mi,mij,mj->m", ue, stiffness, ue))
    return tuple(out)


def film_conductance(film, gaps, power=3, guess=None):
    """The film's conductance K [m³] for nodal gaps ``gaps`` (n,) [m], and its :class:`FilmSolution` (u from 1 on
    the pressurised edge to 0 on the outer edge); ``power`` 2 gives the slip conductance K_2 [m²] (k = h²);
    ``guess`` a field tried first (:func:`solve_film`).

    >>> from exchange.seal.film import seal_film
    >>> from exchange.seal.meshes import annulus_mesh
    >>> film = seal_film(*annulus_mesh(0.01, 0.02, 3, 24))
    >>> K, _ = film_conductance(film, np.full(film.n_nodes, 1e-5))
    >>> float(round(K / (2 * np.pi * 1e-15 / np.log(2.0)), 12))  # 2π h³ / ln(ro/ri)
    1.0
    """
    solution = solve_film(film, *element_coefficients(film, gaps, power), 1.0, 0.0, guess)
    return solution.flux, solution


def film_mass_flow(film, gaps, p_high, p_low, temperature, viscosity, gas_constant, slip=False):
    """Mass flow through the film from the pressurised edge to the outer edge [kg/s] (negative if p_low > p_high),
    and its :class:`FilmSolution` (u = p² [Pa²]).

    ``gaps`` (n,) [m]; ``p_high``, ``p_low`` absolute pressures [Pa]; ``temperature`` T [K] of the isothermal
    film; ``viscosity`` μ [Pa s]; ``gas_constant`` R [J/(kg K)]; ``slip``: first-order slip (module notes).

    >>> from exchange.seal.film import seal_film
    >>> from exchange.seal.meshes import annulus_mesh
    >>> film = seal_film(*annulus_mesh(0.01, 0.02, 3, 24))
    >>> m, _ = film_mass_flow(film, np.full(film.n_nodes, 5e-6), 3e5, 1e5, 293.15, 1.76e-5, 296.8)
    >>> exact = np.pi * 5e-6 ** 3 * (3e5 ** 2 - 1e5 ** 2) / (12 * 1.76e-5 * 296.8 * 293.15 * np.log(2.0))
    >>> float(round(m / exact, 12))
    1.0
    """
    scale = 24.0 * viscosity * gas_constant * temperature
    k3_tri, k3_quad = element_coefficients(film, gaps)
    solution = solve_film(film, k3_tri, k3_quad, p_high ** 2, p_low ** 2)
    if not slip or solution.sealed:
        return solution.flux / scale, solution
    pv = mean_free_path(1.0, temperature, viscosity, gas_constant)  # λ·p [Pa m]
    flow = solution.flux / scale
    for _ in range(SLIP_MAX_ITERATIONS):
        factors = []
        for elements, k3 in ((film.triangles, k3_tri), (film.quads, k3_quad)):
            p_e = np.nanmean(np.sqrt(np.abs(solution.u[elements])), axis=1) if len(elements) else np.zeros(0)
            h_e = np.cbrt(k3)
            with np.errstate(divide="ignore", invalid="ignore"):
                factors.append(np.where(k3 > 0.0, k3 * (1.0 + 6.0 * pv / (np.nan_to_num(p_e, nan=1.0) * h_e)), 0.0))
        solution = solve_film(film, factors[0], factors[1], p_high ** 2, p_low ** 2)
        new = solution.flux / scale
        if abs(new - flow) <= SLIP_RTOL * abs(new):
            return new, solution
        flow = new
    raise RuntimeError(f"the slip iteration did not converge in {SLIP_MAX_ITERATIONS} iterations")
