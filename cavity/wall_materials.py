"""A vessel wall of several materials: the 1-D heat equation across a liner and its shells, by finite volumes.

A Type III vessel is an aluminium liner wound with carbon-fibre composite, a Type IV a polymer liner wound the
same way: the wall is a stack of materials, inner to outer, each with its thickness t_m, conductivity k_m,
density ρ_m and specific heat c_m, and cut into N_m cells of thickness Δx_m = t_m/N_m (faces fall on the material
interfaces). The area through the wall varies linearly from A_i to A_o across the whole thickness (exact for a
slab, a thin-shell approximation for a cylinder, as :mod:`cavity.wall_layers`). Cell j holds one temperature and
the heat capacity of its volume, C_j = ρ_j c_j Δx_j (A(x_j) + A(x_{j+1}))/2; two neighbouring cells exchange heat
through the two half cells in series (the harmonic mean of Patankar's eq. 4.9), at the area of their common face:

    G_{j,j+1} = A_f / (Δx_j/(2 k_j) + Δx_{j+1}/(2 k_{j+1}))

The gas reaches the first cell through its film in series with the first half cell, the ambient the last cell
likewise (:func:`cavity.wall_layers.surface_conductance`). The scheme is second order in the cell size, within a
material and across an interface (the interface is a face), and exact at steady state for a slab: the steady
heat flux through the stack is ΔT/(1/h_i + Σ t_m/k_m + 1/h_o) for any N_m (tests/realgas/test_wall_materials.py).

Reference: S. V. Patankar, *Numerical Heat Transfer and Fluid Flow*, Hemisphere, 1980, §4.2-3 (interface
conductivity); a composite wall's series resistance: Incropera & DeWitt, *Fundamentals of Heat and Mass
Transfer*, §3.1.3.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["WallMaterial", "interface_conductance", "series_resistance", "cell_thicknesses", "layered_capacities",
           "layered_conductances"]


@dataclass(frozen=True)
class WallMaterial:
    """One material of a wall, inner to outer.

    Attributes
    ----------
    thickness : float
        t [m], > 0.
    conductivity : float
        k [W/(m K)], > 0.
    density : float
        ρ [kg/m^3], > 0.
    heat_capacity : float
        c [J/(kg K)], > 0.
    layers : int
        N >= 1 cells across this material.
    name : str
        What it is ("liner", "CFRP").
    """

    thickness: float
    conductivity: float
    density: float
    heat_capacity: float
    layers: int = 1
    name: str = ""

    def __post_init__(self):
        if not (self.thickness > 0 and self.conductivity > 0 and self.density > 0 and self.heat_capacity > 0
                and self.layers >= 1):
            raise ValueError(f"wall material {self.name!r}: thickness, conductivity, density and heat_capacity "
                             f"must be > 0 and layers >= 1 (got {self.thickness!r}, {self.conductivity!r}, "
                             f"{self.density!r}, {self.heat_capacity!r}, {self.layers!r})")


def interface_conductance(area: float, dx_a: float, k_a: float, dx_b: float, k_b: float) -> float:
    r"""Conductance between the centres of two adjacent cells through their common face [W/K].

    .. math:: G = \frac{A_f}{\Delta x_a/(2 k_a) + \Delta x_b/(2 k_b)}

    The two half cells conduct in series; for one material it is k A_f/Δx. This is the harmonic mean of the two
    conductivities that Patankar (1980, eq. 4.9) shows to carry the exact flux across a material interface.

    Parameters
    ----------
    area : float
        A_f, the face's area [m^2].
    dx_a, dx_b : float
        Thicknesses of the two cells [m].
    k_a, k_b : float
        Their conductivities [W/(m K)].

    Examples
    --------
    1 mm aluminium (237 W/(m K)) against 2 mm composite (0.5 W/(m K)), 1 m²: the composite's half cell dominates.

    >>> round(interface_conductance(1.0, 1e-3, 237.0, 2e-3, 0.5), 2)
    499.47
    >>> interface_conductance(2.0, 0.01, 50.0, 0.01, 50.0)
    10000.0
    """
    return area / (0.5 * dx_a / k_a + 0.5 * dx_b / k_b)


def series_resistance(h_inner: float, h_outer: float, thicknesses, conductivities) -> float:
    r"""Resistance of unit area of a plane composite wall between two fluids [m^2 K/W].

    .. math:: R'' = \frac{1}{h_i} + \sum_m \frac{t_m}{k_m} + \frac{1}{h_o}

    The steady heat flux through the wall is ΔT/R'' (Incropera & DeWitt, eq. 3.19).

    Parameters
    ----------
    h_inner, h_outer : float
        Film coefficients [W/(m^2 K)], > 0.
    thicknesses, conductivities : sequence of float
        t_m [m] and k_m [W/(m K)] of the materials.

    Examples
    --------
    A 5 mm aluminium liner and a 20 mm composite shell between films of 100 and 8 W/(m² K):

    >>> round(series_resistance(100.0, 8.0, (0.005, 0.020), (237.0, 0.5)), 6)
    0.175021
    """
    return 1.0 / h_inner + sum(t / k for t, k in zip(thicknesses, conductivities)) + 1.0 / h_outer


def cell_thicknesses(materials) -> tuple:
    """(Δx [m], k [W/(m K)], ρc [J/(m^3 K)]) of every cell, inner to outer.

    Examples
    --------
    >>> cell_thicknesses((WallMaterial(0.002, 200.0, 2700.0, 900.0, 2), WallMaterial(0.01, 0.5, 1500.0, 1000.0)))
    ((0.001, 200.0, 2430000.0), (0.001, 200.0, 2430000.0), (0.01, 0.5, 1500000.0))
    """
    return tuple((m.thickness / m.layers, m.conductivity, m.density * m.heat_capacity)
                 for m in materials for _ in range(m.layers))


def _faces(cells) -> list:
    """Positions of the cell faces from the inner surface [m], n + 1 of them."""
    x = [0.0]
    for dx, _, _ in cells:
        x.append(x[-1] + dx)
    return x


def layered_capacities(materials, inner_area: float, outer_area: float) -> tuple:
    r"""Heat capacity of every cell, inner to outer [J/K].

    .. math:: C_j = \rho_j c_j\,\Delta x_j\,\frac{A(x_j) + A(x_{j+1})}{2},\quad
              A(x) = A_i + (A_o - A_i)\,x/L

    Examples
    --------
    >>> layered_capacities((WallMaterial(0.01, 1.0, 1000.0, 1000.0, 2),), 1.0, 3.0)
    (7500.0, 12500.0)
    """
    cells = cell_thicknesses(materials)
    x = _faces(cells)
    total = x[-1]

    def area(s):
        return inner_area + (outer_area - inner_area) * (s / total)

    return tuple(rc * dx * 0.5 * (area(x[j]) + area(x[j + 1])) for j, (dx, _, rc) in enumerate(cells))


def layered_conductances(materials, inner_area: float, outer_area: float) -> tuple:
    """Conductance between the centres of cells j and j+1 [W/K] (:func:`interface_conductance` at the area of
    their common face), j = 1 … N−1.

    Examples
    --------
    >>> layered_conductances((WallMaterial(0.02, 50.0, 7800.0, 500.0, 2),), 1.0, 1.0)
    (5000.0,)
    """
    cells = cell_thicknesses(materials)
    x = _faces(cells)
    total = x[-1]
    out = []
    for j in range(len(cells) - 1):
        face = inner_area + (outer_area - inner_area) * (x[j + 1] / total)
        out.append(interface_conductance(face, cells[j][0], cells[j][1], cells[j + 1][0], cells[j + 1][1]))
    return tuple(out)
