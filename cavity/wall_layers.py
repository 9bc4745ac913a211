"""Conduction through a vessel wall in layers: the 1-D heat equation across the thickness, by finite volumes.

The wall (thickness L, conductivity k, heat capacity m_w c_w, inner area A_i, outer area A_o) is cut into N layers
of equal thickness Δx = L/N; the area through the wall varies linearly from A_i to A_o (a thin cylinder or
sphere wall, exact for a slab). Layer j holds one temperature T_j at its centre and the heat capacity of its
volume; neighbouring layers exchange k·A(x)·(T_j − T_{j+1})/Δx through their interface; the gas reaches the inner
layer through the convective film in series with the half layer, h_i A_i and k A_i/(Δx/2), the ambient the outer
one likewise:

    C_j dT_j/dt = G_{j−1}(T_{j−1} − T_j) − G_j(T_j − T_{j+1}),   G_j = k·A(x_{j+1})/Δx
    Q_in = (T_gas − T_1) / (1/(h_i A_i) + Δx/(2 k A_i)),   Q_out = (T_N − T_amb) / (1/(h_o A_o) + Δx/(2 k A_o))

This is the standard finite-volume (method-of-lines) discretisation of the heat equation (Patankar, *Numerical
Heat Transfer and Fluid Flow*, 1980, ch. 4); it converges to the exact solution at second order in Δx. With
N = 1 the wall is lumped: one temperature and no conduction resistance (:class:`cavity.wall.Wall`).
"""
from __future__ import annotations

__all__ = ["layer_capacities", "layer_conductances", "surface_conductance", "layer_temperature_rates"]


def _area(inner_area: float, outer_area: float, fraction: float) -> float:
    return inner_area + (outer_area - inner_area) * fraction


def layer_capacities(thermal_mass: float, inner_area: float, outer_area: float, layers: int) -> tuple:
    r"""Heat capacity of each layer, inner to outer [J/K]: m_w c_w shared in proportion to the layers' volumes.

    .. math:: C_j = m_w c_w \frac{A(x_j) + A(x_{j+1})}{\sum_i A(x_i) + A(x_{i+1})}

    Examples
    --------
    >>> layer_capacities(100.0, 1.0, 3.0, 2)
    (37.5, 62.5)
    """
    if layers == 1:  # the lumped wall holds it all (exactly: no rounding through the weights)
        return (thermal_mass,)
    weights = [_area(inner_area, outer_area, j / layers) + _area(inner_area, outer_area, (j + 1) / layers)
               for j in range(layers)]
    total = sum(weights)
    return tuple(thermal_mass * w / total for w in weights)


def layer_conductances(conductivity: float, thickness: float, inner_area: float, outer_area: float,
                       layers: int) -> tuple:
    r"""Conductance between the centres of layers j and j+1, j = 1 … N−1 [W/K].

    .. math:: G_j = \frac{k\,A(x_{j+1})}{\Delta x},\quad \Delta x = L/N

    Parameters
    ----------
    conductivity : float
        k [W/(m K)].
    thickness : float
        L [m].
    inner_area, outer_area : float
        A_i, A_o [m^2].
    layers : int
        N.

    Examples
    --------
    >>> layer_conductances(50.0, 0.01, 1.0, 1.0, 2)
    (10000.0,)
    """
    dx = thickness / layers
    return tuple(conductivity * _area(inner_area, outer_area, (j + 1) / layers) / dx for j in range(layers - 1))


def surface_conductance(h: float, area: float, conductivity: float, half_thickness: float) -> float:
    r"""Conductance from a fluid to the centre of the wall's surface layer [W/K]: the film in series with the half
    layer (no half layer when ``half_thickness`` is 0: a lumped wall).

    .. math:: G_s = \left(\frac{1}{h A} + \frac{\Delta x/2}{k A}\right)^{-1}

    Examples
    --------
    >>> surface_conductance(100.0, 2.0, 50.0, 0.0), surface_conductance(100.0, 2.0, 50.0, 0.005)
    (200.0, 198.01980198019803)
    >>> surface_conductance(0.0, 2.0, 50.0, 0.005)
    0.0
    """
    film = h * area
    if film <= 0.0:
        return 0.0
    if half_thickness <= 0.0:
        return film
    return 1.0 / (1.0 / film + half_thickness / (conductivity * area))


def layer_temperature_rates(temperatures, q_in: float, q_out: float, capacities, conductances) -> tuple:
    r"""dT_j/dt of the layers [K/s], with Q_in [W] entering the inner layer and Q_out [W] leaving the outer one.

    .. math:: C_j \frac{dT_j}{dt} = \delta_{j1} Q_{in} − \delta_{jN} Q_{out}
              + G_{j−1}(T_{j−1} − T_j) − G_j(T_j − T_{j+1})

    The conduction terms cancel in the sum: Σ C_j dT_j/dt = Q_in − Q_out exactly (to round-off), which closes the
    wall's energy books.

    Examples
    --------
    >>> layer_temperature_rates((300.0, 290.0), 100.0, 0.0, (10.0, 10.0), (5.0,))
    (5.0, 5.0)
    """
    n = len(temperatures)
    flux = [conductances[j] * (temperatures[j] - temperatures[j + 1]) for j in range(n - 1)]
    rates = []
    for j in range(n):
        q = (q_in if j == 0 else flux[j - 1]) - (q_out if j == n - 1 else flux[j])
        rates.append(q / capacities[j])
    return tuple(rates)
