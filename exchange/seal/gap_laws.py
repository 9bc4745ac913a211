r"""Gap laws: the leak-channel height h [m] of a rough contact pressed with contact pressure p [Pa].

Each law is one pure, vectorised function of the contact pressure (scalar or array in, same shape out), with a
small frozen dataclass that checks its parameters once and gives the pressures where the law has a kink
(:meth:`breakpoints`) and the pressure at which the channel closes (:meth:`closing_pressure`, ``inf`` if never).

The channel closes *continuously*: every law returns exactly 0 at and beyond its closing pressure and tends to 0
as p approaches it from below, so a seal's conductance is a continuous function of the load and a closed
channel is decided by an exact zero, not by a small number (:mod:`exchange.seal.percolation`).

The percolation gap u_c [m] is the interfacial separation at which the non-contact region stops percolating
across the seal (the contact area fraction reaches about 0.42 for isotropic random roughness: Persson & Yang,
J. Phys.: Condens. Matter 20 (2008) 315011; Lorenz & Persson, Eur. Phys. J. E 31 (2010) 159). Only the part of
the separation above it carries flow: h = max(u(p) − u_c, 0).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["exponential_gap", "persson_gap", "table_gap", "power_gap", "ExponentialGap", "PerssonGap", "TableGap",
           "NoGap", "as_pressure"]


def as_pressure(p):
    """Contact pressure as a float array (negative values count as 0: an open contact carries no pressure)."""
    return np.maximum(np.asarray(p, dtype=float), 0.0)


def _shaped(values, p):
    return float(values) if np.ndim(p) == 0 else values


def exponential_gap(p, h0, p0, u_c=0.0):
    r"""Exponential gap law [m].

    .. math:: h(p) = \max\left(h_0\, e^{-p/p_0} - u_c,\ 0\right)

    Parameters
    ----------
    p : float or array
        Contact pressure [Pa] (negative counts as 0).
    h0 : float
        Gap at zero contact pressure [m] > 0.
    p0 : float
        Pressure scale [Pa] > 0: the gap falls by e each p0.
    u_c : float
        Percolation gap [m] >= 0 (0: the channel never closes).

    Notes
    -----
    The common engineering fit of a gap that narrows with load (the inverse of Persson's large-separation law
    p ∝ exp(−u/u0), read the other way round); closes at p_c = p0·ln(h0/u_c).

    Examples
    --------
    >>> exponential_gap(0.0, 10e-6, 1e6), round(exponential_gap(1e6, 10e-6, 1e6) * 1e6, 6)
    (1e-05, 3.678794)
    >>> round(exponential_gap(2e6, 10e-6, 1e6, u_c=1e-6) * 1e6, 6), exponential_gap(3e6, 10e-6, 1e6, u_c=1e-6)
    (0.353353, 0.0)
    """
    h = np.maximum(h0 * np.exp(-as_pressure(p) / p0) - u_c, 0.0)
    return _shaped(h, p)


def persson_gap(p, u0, p_star, u_c=0.0, h_max=math.inf):
    r"""Persson's logarithmic gap law, minus the percolation gap, smoothly capped at first touch [m].

    .. math:: h(p) = \max\left(u_0 \ln\frac{p^*}{p + p_t} - u_c,\ 0\right),
              \qquad p_t = p^*\, e^{-(h_{max} + u_c)/u_0}

    Parameters
    ----------
    p : float or array
        Contact pressure [Pa] (negative counts as 0).
    u0 : float
        Separation scale [m] > 0 (of the order of the rms roughness; Persson: u0 = γ·h_rms).
    p_star : float
        Pressure scale p* = β·E* [Pa] > 0 (E* the effective modulus, β from the roughness spectrum).
    u_c : float
        Percolation gap [m] >= 0: the channel closes at p_c = p*·exp(−u_c/u0) − p_t.
    h_max : float
        Channel height at zero pressure [m] > 0 (inf: Persson's law unmodified, infinite at p = 0).

    Notes
    -----
    Persson's contact mechanics gives the mean interfacial separation u = u0·ln(p*/p) for p ≪ p* (B. N. J.
    Persson, Phys. Rev. Lett. 99 (2007) 125502; J. Phys.: Condens. Matter 20 (2008) 315011). The logarithm diverges
    as p → 0; adding p_t (a few hundred pascals for typical parameters) keeps h finite and smooth there, equal to
    h_max at first touch, and changes h by u0·ln(1 + p_t/p), negligible where p ≫ p_t. The flow channel is the
    separation above the percolation gap (module notes).

    Examples
    --------
    >>> round(persson_gap(1e5, 1e-6, 1e8) * 1e6, 6)  # u0·ln(1000)
    6.907755
    >>> round(persson_gap(0.0, 1e-6, 1e8, h_max=20e-6), 15), persson_gap(2e7, 1e-6, 1e8, u_c=2e-6)
    (2e-05, 0.0)
    """
    q = as_pressure(p)
    p_t = p_star * math.exp(-(h_max + u_c) / u0) if math.isfinite(h_max) else 0.0
    with np.errstate(divide="ignore"):
        h = np.maximum(u0 * np.log(p_star / (q + p_t)) - u_c, 0.0)
    return _shaped(h, p)


def table_gap(p, pressures, gaps):
    """Tabulated gap law [m]: piecewise linear in p through (pressures[k], gaps[k]), constant beyond the ends.

    Parameters
    ----------
    p : float or array
        Contact pressure [Pa] (negative counts as 0).
    pressures : (k,) float
        Strictly increasing contact pressures [Pa], the first >= 0.
    gaps : (k,) float
        Non-increasing gaps [m] >= 0; a zero closes the channel from there on.

    Examples
    --------
    >>> table_gap([0.0, 5e5, 2e6], [0.0, 1e6], [4e-6, 0.0]).tolist()
    [4e-06, 2e-06, 0.0]
    """
    h = np.interp(as_pressure(p), pressures, gaps)
    return _shaped(h, p)


def power_gap(p, h_ref, p_ref, exponent, h_max=math.inf):
    r"""Power-law gap [m], the form a PVRC tightness law gives (:mod:`exchange.seal.hysteresis`).

    .. math:: h(p) = \min\left(h_{ref}\,(p/p_{ref})^{-n},\ h_{max}\right)

    ``h_ref`` [m] the gap at ``p_ref`` [Pa], ``exponent`` n > 0 [-], ``h_max`` [m] the cap at vanishing pressure.

    >>> power_gap(4e6, 1e-6, 1e6, 0.5), power_gap(0.0, 1e-6, 1e6, 0.5, h_max=5e-6)
    (5e-07, 5e-06)
    """
    q = as_pressure(p)
    with np.errstate(divide="ignore"):
        h = np.minimum(h_ref * (q / p_ref) ** (-exponent), h_max)
    return _shaped(h, p)


def _positive(name, value, allow_zero=False, allow_inf=False):
    ok = (value >= 0.0 if allow_zero else value > 0.0) and (allow_inf or math.isfinite(value))
    if not ok or math.isnan(value):
        raise ValueError(f"{name} must be {'>= 0' if allow_zero else '> 0'}, got {value!r}")


@dataclass(frozen=True)
class NoGap:
    """No roughness channel: the channel is the clearance alone (a softened contact law carries the roughness)."""

    def gap(self, p):
        """0 [m] at every pressure.

        >>> NoGap().gap([0.0, 1e6]).tolist()
        [0.0, 0.0]
        """
        return _shaped(np.zeros(np.shape(p)), p)

    def closing_pressure(self):
        return 0.0

    def breakpoints(self):
        return ()


@dataclass(frozen=True)
class ExponentialGap:
    """:func:`exponential_gap` with ``h0`` [m], ``p0`` [Pa] and percolation gap ``u_c`` [m]."""

    h0: float
    p0: float
    u_c: float = 0.0

    def __post_init__(self):
        _positive("h0 [m]", self.h0)
        _positive("p0 [Pa]", self.p0)
        _positive("u_c [m]", self.u_c, allow_zero=True)
        if self.u_c >= self.h0:
            raise ValueError(f"u_c must be < h0 = {self.h0!r} m, got {self.u_c!r}: the channel would never open")

    def gap(self, p):
        return exponential_gap(p, self.h0, self.p0, self.u_c)

    def closing_pressure(self):
        """p_c = p0·ln(h0/u_c) [Pa] (inf without a percolation gap).

        >>> round(ExponentialGap(10e-6, 1e6, 1e-6).closing_pressure())
        2302585
        """
        return self.p0 * math.log(self.h0 / self.u_c) if self.u_c > 0.0 else math.inf

    def breakpoints(self):
        pc = self.closing_pressure()
        return (pc,) if math.isfinite(pc) else ()


@dataclass(frozen=True)
class PerssonGap:
    """:func:`persson_gap` with ``u0`` [m], ``p_star`` [Pa], percolation gap ``u_c`` [m] and cap ``h_max`` [m]."""

    u0: float
    p_star: float
    u_c: float = 0.0
    h_max: float = math.inf

    def __post_init__(self):
        _positive("u0 [m]", self.u0)
        _positive("p_star [Pa]", self.p_star)
        _positive("u_c [m]", self.u_c, allow_zero=True)
        _positive("h_max [m]", self.h_max, allow_inf=True)

    def gap(self, p):
        return persson_gap(p, self.u0, self.p_star, self.u_c, self.h_max)

    def closing_pressure(self):
        """p_c = p*·exp(−u_c/u0) − p_t [Pa].

        >>> round(PerssonGap(1e-6, 1e8, 2e-6).closing_pressure())
        13533528
        """
        p_t = self.p_star * math.exp(-(self.h_max + self.u_c) / self.u0) if math.isfinite(self.h_max) else 0.0
        return self.p_star * math.exp(-self.u_c / self.u0) - p_t

    def breakpoints(self):
        """The closing pressure [Pa]."""
        return (self.closing_pressure(),)


@dataclass(frozen=True)
class TableGap:
    """:func:`table_gap` through ``pressures`` [Pa] and ``gaps`` [m] (tuples, checked once)."""

    pressures: tuple
    gaps: tuple

    def __post_init__(self):
        p, h = np.asarray(self.pressures, float), np.asarray(self.gaps, float)
        if p.ndim != 1 or p.shape != h.shape or len(p) < 2:
            raise ValueError(f"a gap table needs >= 2 rows of (pressure [Pa], gap [m]), got {p.shape} and {h.shape}")
        if not (np.isfinite(p).all() and np.isfinite(h).all()):
            raise ValueError("gap table entries must be finite numbers")
        if p[0] < 0.0 or np.any(np.diff(p) <= 0.0):
            raise ValueError(f"gap table pressures must start >= 0 Pa and increase strictly, got {p.tolist()}")
        if np.any(h < 0.0) or np.any(np.diff(h) > 0.0):
            raise ValueError(f"gap table gaps must be >= 0 m and non-increasing with pressure, got {h.tolist()}")
        object.__setattr__(self, "pressures", tuple(p.tolist()))
        object.__setattr__(self, "gaps", tuple(h.tolist()))

    def gap(self, p):
        return table_gap(p, self.pressures, self.gaps)

    def closing_pressure(self):
        """The first tabulated pressure with a zero gap [Pa] (inf if none).

        >>> TableGap((0.0, 1e6, 2e6), (4e-6, 1e-6, 0.0)).closing_pressure()
        2000000.0
        """
        zero = [p for p, h in zip(self.pressures, self.gaps) if h == 0.0]
        return zero[0] if zero else math.inf

    def breakpoints(self):
        return self.pressures
