"""Ideal-gas species: molar mass and the polynomial molar heat capacity, with its analytic integrals.

c̃p(T) = a + bT + cT² + dT³ + e/T² + fT⁴  [J/(mol K)]  (Abaqus *CAPACITY, TYPE=POLYNOMIAL; f is Radioss's T⁴ term).
The molar enthalpy and internal energy integrate it analytically (reference: the antiderivative's zero; any
constant offset cancels from every energy balance because species are conserved).
"""
from __future__ import annotations

import bisect
import functools
import math
import re
from dataclasses import dataclass

import numpy as np

from .tolerances import R_UNIVERSAL

__all__ = ["Species", "heat_capacity_polynomial", "enthalpy_polynomial", "molar_heat_capacity", "molar_enthalpy", "molar_internal_energy", "species_from_coolprop",
           "fit_species_from_coolprop", "species_record", "builtin_species", "BUILTIN_COOLPROP_NAMES",
           "coolprop_fluid_name", "coolprop_fluid_names"]

N_COEFFICIENTS = 6


def heat_capacity_polynomial(a, b, c, d, e, f, T):
    r"""Isobaric heat capacity of the polynomial model [J/K per the coefficients' amount, e.g. J/(mol K)].

    .. math:: \tilde c_p(T) = a + bT + cT^2 + dT^3 + e/T^2 + fT^4

    The one definition of the law: :func:`molar_heat_capacity`, :class:`cavity.gas.Mixture` and the compiled
    path (:func:`cavity.gas_rows.row_cp`, the same function compiled by numba) all evaluate it.

    Parameters
    ----------
    a, b, c, d, e, f : float
        a [J/(mol K)], b [J/(mol K²)], c [J/(mol K³)], d [J/(mol K⁴)], e [J K/mol], f [J/(mol K⁵)] (or the same
        per any amount of gas: totals over a mixture's moles).
    T : float
        Temperature [K].

    References
    ----------
    Abaqus Analysis User's Guide, "Fluid cavity definition", *CAPACITY, TYPE=POLYNOMIAL (f: Radioss's T⁴ term).

    Examples
    --------
    Air (Abaqus verification deck) at 300 K:

    >>> round(heat_capacity_polynomial(28.110, 1.967e-3, 4.802e-6, -1.966e-9, 0.0, 0.0, 300.0), 4)
    29.0792
    """
    return a + T * (b + T * (c + T * (d + T * f))) + e / (T * T)


def enthalpy_polynomial(a, b, c, d, e, f, T):
    r"""Enthalpy, the antiderivative of :func:`heat_capacity_polynomial` [J per the coefficients' amount].

    .. math:: \tilde h(T) = aT + bT^2/2 + cT^3/3 + dT^4/4 - e/T + fT^5/5

    Reference: the antiderivative's zero (constant offsets per temperature range are added by the callers, so that
    H is continuous across ranges). The one definition, as :func:`heat_capacity_polynomial`.

    Examples
    --------
    With constant cp the enthalpy is a·T:

    >>> enthalpy_polynomial(29.0, 0.0, 0.0, 0.0, 0.0, 0.0, 300.0)
    8700.0
    """
    return T * (a + T * (b / 2.0 + T * (c / 3.0 + T * (d / 4.0 + T * f / 5.0)))) - e / T


def molar_heat_capacity(coefficients, T: float) -> float:
    """Molar isobaric heat capacity [J/(mol K)] of the coefficients (a, b, c, d, e, f) at T [K]
    (:func:`heat_capacity_polynomial`).

    >>> round(molar_heat_capacity((28.110, 1.967e-3, 4.802e-6, -1.966e-9, 0.0, 0.0), 300.0), 4)
    29.0792
    """
    return heat_capacity_polynomial(*coefficients, T)


def molar_enthalpy(coefficients, T: float) -> float:
    """Molar enthalpy [J/mol] of the coefficients (a, b, c, d, e, f) at T [K] (:func:`enthalpy_polynomial`).

    >>> molar_enthalpy((29.0, 0, 0, 0, 0, 0), 300.0)
    8700.0
    """
    return enthalpy_polynomial(*coefficients, T)


def molar_internal_energy(coefficients, T: float) -> float:
    r"""Molar internal energy of an ideal gas, :math:`\tilde u = \tilde h - R_u T` [J/mol].

    >>> round(molar_internal_energy((29.0, 0, 0, 0, 0, 0), 300.0), 6)
    6205.661215
    """
    return molar_enthalpy(coefficients, T) - R_UNIVERSAL * T


@dataclass(frozen=True)
class Species:
    """One ideal-gas species with a piecewise-polynomial molar heat capacity.

    Attributes
    ----------
    name : str
        Name used in scene files.
    molar_mass : float
        Molar mass M [kg/mol], > 0.
    cp_coefficients : tuple of 6 float
        Polynomial coefficients (a, b, c, d, e, f) of the molar heat capacity (see :func:`molar_heat_capacity`);
        fewer than 6 are padded with zeros. Used on the whole temperature axis unless ``breaks`` is given.
    breaks : tuple of float
        Interior temperatures [K] where the polynomial changes (empty for one polynomial).
    pieces : tuple of tuples
        With ``breaks``: len(breaks) + 1 coefficient 6-tuples, one per range; ``cp_coefficients`` is then piece 0.
    source : str
        Where the data came from (a scene, a built-in, a CoolProp fit and its error).
    valid_range : (float, float)
        Temperatures [K] between which the data hold (a CoolProp fit's range; (0, inf): not known). A run that
        leaves it gets a warning (``cases.results.species_range``).

    Examples
    --------
    >>> s = Species("N2", 0.028, (29.1,))
    >>> round(s.gas_constant, 3), round(s.gamma(300.0), 4)
    (296.945, 1.4000)
    """

    name: str
    molar_mass: float
    cp_coefficients: tuple[float, ...]
    source: str = "user"
    breaks: tuple[float, ...] = ()
    pieces: tuple[tuple[float, ...], ...] = ()
    valid_range: tuple[float, float] = (0.0, math.inf)

    def __post_init__(self):
        pieces = self.pieces or (self.cp_coefficients,)
        if len(pieces) != len(self.breaks) + 1:
            raise ValueError(f"species {self.name!r}: {len(self.breaks)} breaks need {len(self.breaks) + 1} pieces")
        if any(b1 <= b0 for b0, b1 in zip(self.breaks[:-1], self.breaks[1:])):
            raise ValueError(f"species {self.name!r}: breaks must be strictly increasing temperatures [K]")
        padded = tuple(_padded(self.name, p) for p in pieces)
        if not (math.isfinite(self.molar_mass) and self.molar_mass > 0.0):
            raise ValueError(f"species {self.name!r}: molar mass must be > 0 [kg/mol], got {self.molar_mass!r}")
        object.__setattr__(self, "pieces", padded)
        object.__setattr__(self, "cp_coefficients", padded[0])
        object.__setattr__(self, "breaks", tuple(float(b) for b in self.breaks))
        if self.molar_cp(300.0) <= R_UNIVERSAL:
            raise ValueError(f"species {self.name!r}: cp(300 K) must exceed R = {R_UNIVERSAL} J/(mol K) "
                             "so that cv > 0")

    def piece(self, T: float) -> tuple[float, ...]:
        """The coefficient 6-tuple in force at T."""
        return self.pieces[bisect.bisect_right(self.breaks, T)]

    def molar_cp(self, T: float) -> float:
        """Molar heat capacity at constant pressure [J/(mol K)]."""
        return molar_heat_capacity(self.piece(T), T)

    @property
    def gas_constant(self) -> float:
        """Specific gas constant R_u/M [J/(kg K)]."""
        return R_UNIVERSAL / self.molar_mass

    def gamma(self, T: float) -> float:
        """Ratio of specific heats cp/cv at T [-]."""
        cp = self.molar_cp(T)
        return cp / (cp - R_UNIVERSAL)


def _padded(name: str, coefficients) -> tuple[float, ...]:
    coeffs = tuple(float(v) for v in coefficients)
    if not 1 <= len(coeffs) <= N_COEFFICIENTS:
        raise ValueError(f"species {name!r}: expected 1 to 6 cp coefficients (a, b, c, d, e, f), got {len(coeffs)}")
    if not all(math.isfinite(v) for v in coeffs):
        raise ValueError(f"species {name!r}: cp coefficients must be finite, got {coeffs}")
    return coeffs + (0.0,) * (N_COEFFICIENTS - len(coeffs))


#: Temperatures [K] a CoolProp species is fitted on (and valid in) by default.
COOLPROP_RANGE = (100.0, 3000.0)

#: Species names resolved through CoolProp when a scene names them without data.
BUILTIN_COOLPROP_NAMES = {"N2": "Nitrogen", "O2": "Oxygen", "CO2": "CarbonDioxide", "He": "Helium", "Ar": "Argon",
                          "H2O": "Water", "H2": "Hydrogen", "Air": "Air"}


@functools.lru_cache(maxsize=1)
def coolprop_fluid_names() -> tuple:
    """CoolProp's fluid names and their aliases."""
    import CoolProp.CoolProp as CP

    names = CP.get_global_param_string("FluidsList").split(",")
    return tuple(names + [a for n in names for a in CP.get_fluid_param_string(n, "aliases").split(",") if a])


@functools.lru_cache(maxsize=None)
def coolprop_fluid_name(name: str) -> str:
    """CoolProp's fluid for a species ``name``: a built-in short name (``N2`` → ``Nitrogen``), a fluid name or
    alias CoolProp knows (``CH4``, ``Propane``), or a chemical formula exactly one CoolProp fluid has (``C2H6`` →
    ``Ethane``; ``C4H10``, two butanes, is not resolved); else ``name`` unchanged (CoolProp's error names it)."""
    if name in BUILTIN_COOLPROP_NAMES:
        return BUILTIN_COOLPROP_NAMES[name]
    import CoolProp.CoolProp as CP

    if name in coolprop_fluid_names():
        return name
    fluids = CP.get_global_param_string("FluidsList").split(",")
    same = [f for f in fluids if _formula(CP.get_fluid_param_string(f, "formula")) == name]
    return same[0] if len(same) == 1 else name


def _formula(coolprop_formula: str) -> str:
    """A CoolProp formula as written by hand: ``C_{2}H_{6}`` → ``C2H6``, ``C_{1}H_{4}`` → ``CH4``."""
    return re.sub(r"_\{(\d+)\}", lambda m: "" if m.group(1) == "1" else m.group(1), coolprop_formula)


#: Abaqus verification-deck air (../shared/PHYSICS.md): M and cp polynomial.
ABAQUS_AIR = Species("air", 0.0289, (28.110, 1.967e-3, 4.802e-6, -1.966e-9, 0.0), source="Abaqus verification deck")


def species_from_coolprop(name: str, *, label: str | None = None, t_range: tuple[float, float] | None = None,
                          width: float = 100.0) -> Species:
    """:func:`fit_species_from_coolprop`, looked up first in the fit cache (:mod:`cavity.species_fits`: shipped
    fits of the built-in species, then the user cache), which a fresh fit fills; equal to a fresh fit bit for bit on
    the machine that cached it, elsewhere in cp(T) to round-off (another LAPACK orders the least squares otherwise)."""
    from . import species_fits

    fluid = coolprop_fluid_name(name)
    key = coolprop_fit_key(fluid, t_range, width)
    record = species_fits.lookup(key)
    if record is None:
        species = fit_species_from_coolprop(name, label=label, t_range=t_range, width=width)
        species_fits.store(key, species_record(species))
        return species
    return Species(label or name, record["molar_mass"], tuple(record["pieces"][0]), source=record["source"],
                   breaks=tuple(record["breaks"]), pieces=tuple(tuple(p) for p in record["pieces"]),
                   valid_range=tuple(record["valid_range"]))


def coolprop_fit_key(fluid: str, t_range, width: float) -> str:
    """The fit cache's key of a fit: fluid, range (the default made explicit), piece width and target error, so
    that a fit made by other rules is never taken for this one.

    >>> coolprop_fit_key("Nitrogen", None, 100.0)
    'Nitrogen|100.0-3000.0|100.0|rtol 1e-07'
    """
    from .species_fits import fit_key

    return f"{fit_key(fluid, t_range or COOLPROP_RANGE, width)}|rtol {FIT_RTOL!r}"


def species_record(species: Species) -> dict:
    """The JSON-able fit of a species (molar mass, breaks, pieces, source, valid range) as the fit cache stores
    it."""
    return {"molar_mass": species.molar_mass, "breaks": list(species.breaks),
            "pieces": [list(p) for p in species.pieces], "source": species.source,
            "valid_range": list(species.valid_range)}


def fit_species_from_coolprop(name: str, *, label: str | None = None, t_range: tuple[float, float] | None = None,
                              width: float = 100.0) -> Species:
    """A species whose cp is a piecewise cubic least-squares fit of CoolProp's ideal-gas cp0(T), made once at load.

    The range ``t_range`` (default: :data:`COOLPROP_RANGE`, 100 K to 3000 K, or from the fluid's lowest data
    temperature if cp0 cannot be evaluated at 100 K) is cut into pieces of about ``width`` kelvin, each fitted
    by a cubic in T on 12 samples; beyond the range cp is held at its end values and ``valid_range`` says so
    (a run that goes there is warned). The ideal-gas cp0 is CoolProp's analytic ideal-gas part, defined below the
    fluid's triple point too. The maximum relative error of the fit (on points between the samples) is recorded
    in ``source``: below 1e-6 for N2, O2, CO2, H2O, Ar, He, H2 and Air (tests/test_gas.py). CoolProp is never
    called while integrating.

    Parameters
    ----------
    name : str
        CoolProp fluid name (``"Nitrogen"``), alias or formula (``"N2"``, ``"C2H6"``: :func:`coolprop_fluid_name`).
    """
    import CoolProp.CoolProp as CP

    fluid = coolprop_fluid_name(name)
    try:
        state = CP.AbstractState("HEOS", fluid)
    except ValueError as exc:
        raise ValueError(f"species {name!r}: CoolProp does not know the fluid {fluid!r} ({exc})") from None

    def cp0(T):
        state.update(CP.DmolarT_INPUTS, 1e-6, T)
        return state.cp0molar()

    lo, hi = t_range or COOLPROP_RANGE
    try:
        cp0(lo)
    except ValueError:
        lo = state.Tmin()
    pieces, edges, err = [(cp0(lo),)], [float(lo)], 0.0
    for t0, t1 in zip(np.linspace(lo, hi, max(1, int(round((hi - lo) / width))) + 1)[:-1],
                      np.linspace(lo, hi, max(1, int(round((hi - lo) / width))) + 1)[1:]):
        for coef, e, t_end in _cubic_pieces(cp0, float(t0), float(t1)):
            pieces.append(coef)
            edges.append(t_end)
            err = max(err, e)
    pieces.append((cp0(hi),))
    source = f"CoolProp {fluid} cp0, cubic pieces on [{lo:.0f}, {hi:.0f}] K, max rel error {err:.1e}"
    return Species(label or name, state.molar_mass(), pieces[0], source=source,
                   breaks=tuple(edges), pieces=tuple(pieces), valid_range=(float(lo), float(hi)))


#: Target relative error of a CoolProp fit piece; a piece above it is split in two (down to MIN_PIECE kelvin).
FIT_RTOL, MIN_PIECE = 1e-7, 2.0


def _cubic_pieces(cp0, t0: float, t1: float) -> list:
    """[(coefficients, max relative error, piece end)] of cubic least-squares fits of ``cp0`` over [t0, t1] on 12
    samples each, halving a piece whose error (between the samples) exceeds :data:`FIT_RTOL`."""
    T = np.linspace(t0, t1, 12)
    coef = np.polynomial.polynomial.polyfit(T, [cp0(t) for t in T], 3)
    mid = 0.5 * (T[:-1] + T[1:])
    err = max(abs(np.polynomial.polynomial.polyval(t, coef) / cp0(t) - 1.0) for t in mid)
    if err <= FIT_RTOL or t1 - t0 <= MIN_PIECE:
        return [(tuple(coef), err, t1)]
    half = 0.5 * (t0 + t1)
    return _cubic_pieces(cp0, t0, half) + _cubic_pieces(cp0, half, t1)


def builtin_species(name: str) -> Species:
    """A species known by name: ``"air"`` (Abaqus deck data) or a CoolProp fluid (fitted at load)."""
    if name.lower() == "air" and name != "Air":
        return ABAQUS_AIR
    return species_from_coolprop(name, label=name)
