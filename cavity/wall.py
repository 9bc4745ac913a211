"""A lumped vessel wall: one temperature, heated by the gas inside and cooled by the ambient outside.

    m_w c_w dT_w/dt = Q_in − Q_out,   Q_in = h_i A_i (T_gas − T_w),   Q_out = h_o A_o (T_w − T_amb)

The inner coefficient h_i is given, or from natural convection, Nu = C·Ra^n (Geankoplis, *Transport Processes
and Unit Operations*, 3rd ed., 1993, eq. 4.7-4 and Table 4.7-1, vertical planes and cylinders; or Morgan 1975 for
a horizontal cylinder on its diameter), with the gas
properties at the film temperature (T_gas + T_w)/2 and the gas pressure. The constants, the film temperature and
the characteristic length (the vessel's length when vertical, its diameter when horizontal) are those HydDown
uses (Andreasen, HydDown, J. Open Source Softw. 6 (2021) 3695), so the two can be compared case for case.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .wall_layers import layer_capacities, layer_conductances, layer_temperature_rates, surface_conductance
from .wall_materials import layered_capacities, layered_conductances

__all__ = ["Wall", "natural_convection_nusselt", "horizontal_cylinder_nusselt", "forced_inflow_nusselt", "rayleigh_number",
           "natural_convection_coefficient", "GRAVITY", "MORGAN_HORIZONTAL_CYLINDER"]

#: Standard gravity [m/s^2].
GRAVITY = 9.81


def natural_convection_nusselt(Ra: float) -> float:
    r"""Nusselt number of free convection on a vertical plane or cylinder [-].

    .. math::

        Nu = \begin{cases} 1.36\,Ra^{1/5} & Ra \le 10^4 \\ 0.59\,Ra^{1/4} & 10^4 < Ra < 10^9 \\
        0.13\,Ra^{1/3} & Ra \ge 10^9 \end{cases}

    Parameters
    ----------
    Ra : float
        Rayleigh number Gr·Pr [-], >= 0.

    Notes
    -----
    The exponent of the turbulent branch is 0.333 as in HydDown (Geankoplis gives 1/3; the difference is below
    1 % at Ra = 1e12).

    References
    ----------
    C. J. Geankoplis, *Transport Processes and Unit Operations*, 3rd ed., Prentice-Hall, 1993, Table 4.7-1.

    Examples
    --------
    >>> round(natural_convection_nusselt(1e6), 3), round(natural_convection_nusselt(1e10), 3)
    (18.657, 277.935)
    """
    if Ra >= 1e9:
        return 0.13 * Ra ** 0.333
    if Ra > 1e4:
        return 0.59 * Ra ** 0.25
    return 1.36 * Ra ** 0.20


#: Morgan (1975) for a long horizontal cylinder, Nu_D = C·Ra_D^n: (upper Ra_D of the range, C, n).
MORGAN_HORIZONTAL_CYLINDER = ((1e-2, 0.675, 0.058), (1e2, 1.02, 0.148), (1e4, 0.850, 0.188), (1e7, 0.480, 0.250),
                              (math.inf, 0.125, 0.333))


def horizontal_cylinder_nusselt(Ra: float) -> float:
    r"""Nusselt number of free convection around a long horizontal cylinder, on its diameter [-].

    .. math:: Nu_D = C\,Ra_D^{\,n},\quad (C, n) = (0.675, 0.058),\ (1.02, 0.148),\ (0.850, 0.188),\
              (0.480, 0.250),\ (0.125, 0.333)

    for Ra_D up to 1e-2, 1e2, 1e4, 1e7 and beyond (validated to 1e12).

    Parameters
    ----------
    Ra : float
        Rayleigh number on the diameter [-], >= 0.

    References
    ----------
    V. T. Morgan, "The overall convective heat transfer from smooth circular cylinders", Adv. Heat Transfer 11
    (1975) 199–264; Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, Table 9.1.

    Examples
    --------
    >>> round(horizontal_cylinder_nusselt(1e6), 4), round(horizontal_cylinder_nusselt(1e9), 3)
    (15.1789, 124.14)
    """
    for upper, C, n in MORGAN_HORIZONTAL_CYLINDER:
        if Ra <= upper:
            return C * Ra ** n
    return 0.0  # not reached


def forced_inflow_nusselt(Re: float) -> float:
    r"""Forced-convection part of the inner Nusselt number while gas flows into a vessel [-].

    .. math:: Nu_{forced} = 0.56\,Re^{0.67},\quad Re = \frac{4\,\dot m_{in}}{\pi\,d\,\mu}

    added to the free-convection Nusselt number over the same length (mixed convection).

    Parameters
    ----------
    Re : float
        Reynolds number of the inflow [-], >= 0.

    References
    ----------
    The forced term of Woodfield, Monde and Mitsutake, "Measurement of averaged heat transfer coefficients in
    high-pressure vessel during charging with hydrogen, nitrogen or argon gas", J. Therm. Sci. Technol. 2 (2007)
    180–191, in the form HydDown applies while filling (``transport.h_inside_mixed``: d = the vessel diameter).

    Examples
    --------
    >>> round(forced_inflow_nusselt(1e5), 3)
    1253.684
    """
    return 0.56 * Re ** 0.67


def rayleigh_number(L: float, dT: float, rho: float, cp: float, mu: float, k: float, beta: float,
                    g: float = GRAVITY) -> float:
    r"""Rayleigh number of free convection over a length L [-].

    .. math:: Ra = Gr\,Pr = \frac{g\,\beta\,|\Delta T|\,L^3 \rho^2}{\mu^2}\cdot\frac{c_p \mu}{k}

    Parameters
    ----------
    L : float
        Characteristic length [m].
    dT : float
        Wall − gas temperature difference [K].
    rho, cp, mu, k, beta : float
        Density [kg/m^3], isobaric heat capacity [J/(kg K)], viscosity [Pa s], conductivity [W/(m K)] and
        isobaric expansion coefficient [1/K] at the film temperature.
    g : float
        Gravity [m/s^2].

    Examples
    --------
    Air near 1 bar and 300 K, 10 K difference over 0.2 m:

    >>> round(rayleigh_number(0.2, 10.0, 1.16, 1007.0, 1.85e-5, 0.0263, 1 / 300.0) / 1e6, 3)
    7.285
    """
    return g * abs(beta) * abs(dT) * L ** 3 * rho * rho * cp / (mu * k)


def natural_convection_coefficient(L: float, T_gas: float, T_wall: float, props: tuple,
                                   orientation: str = "vertical", inflow: float = 0.0,
                                   jet_diameter: float = 0.0) -> float:
    r"""Free-convection heat transfer coefficient h = Nu·k/L [W/(m^2 K)].

    ``orientation`` ``"vertical"``: :func:`natural_convection_nusselt` over L (HydDown's choice for either
    orientation of a vessel); ``"horizontal"``: :func:`horizontal_cylinder_nusselt` over L = the diameter. With
    an ``inflow`` [kg/s] and a ``jet_diameter`` d [m], :func:`forced_inflow_nusselt` of Re = 4ṁ/(π d μ) is added.

    Parameters
    ----------
    L : float
        Characteristic length [m].
    T_gas, T_wall : float
        Gas and wall temperatures [K].
    props : tuple
        (ρ [kg/m^3], cp [J/(kg K)], μ [Pa s], k [W/(m K)], β [1/K]) at the film temperature.

    Examples
    --------
    >>> round(natural_convection_coefficient(0.2, 290.0, 300.0, (1.16, 1007.0, 1.85e-5, 0.0263, 1 / 300.0)), 4)
    4.0308
    """
    rho, cp, mu, k, beta = props
    Ra = rayleigh_number(L, T_wall - T_gas, rho, cp, mu, k, beta)
    nusselt = horizontal_cylinder_nusselt if orientation == "horizontal" else natural_convection_nusselt
    forced = forced_inflow_nusselt(4.0 * inflow / (math.pi * jet_diameter * mu)) if inflow > 0.0 and jet_diameter \
        else 0.0
    return (nusselt(Ra) + forced) * k / L


@dataclass(frozen=True)
class Wall:
    """A lumped wall around a cavity.

    Attributes
    ----------
    mass : float
        m_w [kg], > 0.
    heat_capacity : float
        c_w [J/(kg K)], > 0.
    inner_area, outer_area : float
        A_i, A_o [m^2].
    inner_h : float
        h_i [W/(m^2 K)]; 0: natural convection over ``length``.
    outer_h : float
        h_o [W/(m^2 K)].
    length : float
        Characteristic length of the inner convection [m].
    initial_temperature, ambient_temperature : float
        [K].
    orientation : str
        Correlation of the inner convection: ``"vertical"`` or ``"horizontal"`` (see
        :func:`natural_convection_coefficient`).
    jet_diameter : float
        d [m] of the forced term while gas flows in (0: none).
    layers : int
        N >= 1: 1 is lumped (one temperature, no conduction resistance); more conduct through the thickness
        (:mod:`cavity.wall_layers`), the first layer facing the gas, the last the ambient.
    conductivity, thickness : float
        k [W/(m K)] and L [m] of a layered wall (> 0 when ``layers`` > 1).
    materials : tuple of cavity.wall_materials.WallMaterial
        A wall of several materials, inner to outer (a liner and its shells), each in its own cells
        (:mod:`cavity.wall_materials`); then ``mass``, ``heat_capacity``, ``layers``, ``conductivity`` (the inner
        material's) and ``thickness`` (the whole wall's) are derived from them and the areas, and may be given as 0.
    """

    mass: float
    heat_capacity: float
    inner_area: float
    outer_area: float
    inner_h: float
    outer_h: float
    length: float
    initial_temperature: float
    ambient_temperature: float
    orientation: str = "vertical"
    jet_diameter: float = 0.0
    layers: int = 1
    conductivity: float = 0.0
    thickness: float = 0.0
    materials: tuple = ()

    def __post_init__(self):
        if self.materials:
            self._layer_materials()
            return
        if self.layers < 1 or (self.layers > 1 and not (self.conductivity > 0.0 and self.thickness > 0.0)):
            raise ValueError(f"a wall of {self.layers} layers needs layers >= 1, and conductivity > 0 and "
                             f"thickness > 0 when layered (got {self.conductivity!r}, {self.thickness!r})")
        half = 0.5 * self.thickness / self.layers if self.layers > 1 else 0.0
        object.__setattr__(self, "_layering", (
            layer_capacities(self.thermal_mass, self.inner_area, self.outer_area, self.layers),
            layer_conductances(self.conductivity, self.thickness, self.inner_area, self.outer_area, self.layers),
            surface_conductance(self.outer_h, self.outer_area, self.conductivity, half), half))

    def _layer_materials(self) -> None:
        """The cells of a wall of several materials, and the wall's derived mass, heat capacity, layers, inner
        conductivity and thickness."""
        first, last = self.materials[0], self.materials[-1]
        capacities = layered_capacities(self.materials, self.inner_area, self.outer_area)
        conductances = layered_conductances(self.materials, self.inner_area, self.outer_area)
        specific = [m.heat_capacity for m in self.materials for _ in range(m.layers)]
        mass = sum(C / c for C, c in zip(capacities, specific))
        for name, value in (("mass", mass), ("heat_capacity", sum(capacities) / mass), ("layers", len(capacities)),
                            ("conductivity", first.conductivity),
                            ("thickness", sum(m.thickness for m in self.materials))):
            object.__setattr__(self, name, value)
        half_out = 0.5 * last.thickness / last.layers
        object.__setattr__(self, "_layering", (
            capacities, conductances, surface_conductance(self.outer_h, self.outer_area, last.conductivity, half_out),
            0.5 * first.thickness / first.layers))

    @property
    def thermal_mass(self) -> float:
        """m_w·c_w [J/K]."""
        return self.mass * self.heat_capacity

    @property
    def capacities(self) -> tuple:
        """Heat capacity of each layer, inner to outer [J/K] (they sum to :attr:`thermal_mass`)."""
        return self._layering[0]

    def heat_flows(self, fluid, p: float, T_gas: float, T_wall: float, inflow: float = 0.0,
                   T_outer: float | None = None) -> tuple:
        """(Q_in gas → wall, Q_out wall → ambient) [W] with ``inflow`` [kg/s] entering the cavity, T_wall the
        inner layer's temperature and T_outer the outer layer's (default: T_wall) [K];
        ``fluid.film_properties(p, T)`` gives the gas properties for the correlation."""
        h_i = self.inner_h
        if not h_i and T_gas != T_wall:
            h_i = natural_convection_coefficient(self.length, T_gas, T_wall,
                                                 fluid.film_properties(p, 0.5 * (T_gas + T_wall)), self.orientation,
                                                 inflow, self.jet_diameter)
        g_in = surface_conductance(h_i, self.inner_area, self.conductivity, self._layering[3])
        outer = T_wall if T_outer is None else T_outer
        return g_in * (T_gas - T_wall), self._layering[2] * (outer - self.ambient_temperature)

    def layer_rates(self, temperatures, q_in: float, q_out: float) -> tuple:
        """dT_j/dt of the layers [K/s] (:func:`cavity.wall_layers.layer_temperature_rates`)."""
        return layer_temperature_rates(temperatures, q_in, q_out, self._layering[0], self._layering[1])
