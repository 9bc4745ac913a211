"""Prescribed flux (Abaqus *FLUID EXCHANGE PROPERTY, TYPE=MASS FLUX / VOLUME FLUX).

The flow is prescribed per unit area and scaled by the exchange area and an amplitude (the *FLUID EXCHANGE
ACTIVATION amplitude multiplier). Unlike the pressure-driven laws it is signed: positive flows from the primary
cavity to the secondary cavity (or the environment), negative flows into the primary cavity. This follows the
Abaqus VUFLUIDEXCH convention ("a positive mass flow rate indicates flow from the primary fluid cavity to the
secondary fluid cavity") and the fluid exchange guide ("the flow can either be into or out of the primary cavity";
gas flowing in takes the instantaneous properties of the primary cavity's gas).

Pure arithmetic: the functions are numba kernels (the engine's kernel :func:`flux_kernel` calls them; from Python
they accept floats or numpy arrays alike).
"""
from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

from numba import njit

from exchange.engine.layout import LAW_SIGNATURE, StateColumn
from exchange.engine.tables import table_value

from .spec import LawKey, LawSpec

__all__ = ["mass_flux_mass_flow", "volume_flux_mass_flow", "FluxLaw", "flux_kernel", "LAW"]


@njit(cache=True)
def mass_flux_mass_flow(mass_flux, area, amplitude=1.0):
    r"""Mass flow from a prescribed mass flux [kg/s].

    .. math:: \dot m = a(t)\, q_m\, A

    Parameters
    ----------
    mass_flux : float or ndarray
        Prescribed mass flow per unit area q_m [kg/(s m^2)]; positive out of the primary cavity.
    area : float or ndarray
        Exchange (effective) area A [m^2], >= 0.
    amplitude : float or ndarray
        Amplitude multiplier a(t) [-] evaluated by the caller at the current time.

    Returns
    -------
    float or ndarray
        Signed mass flow [kg/s], positive from the primary cavity to the secondary cavity or environment.

    References
    ----------
    Abaqus Keywords Reference, *FLUID EXCHANGE PROPERTY, TYPE=MASS FLUX ("mass flow rate per unit area").

    Examples
    --------
    >>> mass_flux_mass_flow(0.5, 0.02, amplitude=0.25)
    0.0025
    """
    return amplitude * mass_flux * area


@njit(cache=True)
def volume_flux_mass_flow(volume_flux, area, rho, amplitude=1.0):
    r"""Mass flow from a prescribed volume flux [kg/s].

    .. math:: \dot m = a(t)\, \rho\, q_v\, A

    Parameters
    ----------
    volume_flux : float or ndarray
        Prescribed volume flow per unit area q_v [m^3/(s m^2)] (a velocity, [m/s]); positive out of the primary
        cavity.
    area : float or ndarray
        Exchange (effective) area A [m^2], >= 0.
    rho : float or ndarray
        Density of the primary cavity's gas [kg/m^3]; Abaqus uses the primary cavity's properties whichever the
        direction of the flow.
    amplitude : float or ndarray
        Amplitude multiplier a(t) [-].

    Returns
    -------
    float or ndarray
        Signed mass flow [kg/s], positive from the primary cavity to the secondary cavity or environment.

    Examples
    --------
    >>> round(volume_flux_mass_flow(2.0, 0.01, 1.2, amplitude=-0.5), 12)
    -0.012
    """
    return amplitude * rho * volume_flux * area


@dataclass(frozen=True)
class FluxLaw:
    """Abaqus MASS FLUX / VOLUME FLUX: a prescribed flow per unit area, signed, times an amplitude table of time.

    ``kind`` is ``"mass"`` [kg/(s m^2)] or ``"volume"`` [m^3/(s m^2)] (times the density of the first cavity).
    """

    kind: str
    flux: float
    amplitude: object = None  # cavity.tables.Table of time, or None
    pneumatic = False
    prescribed = True

    def mass_flow(self, up, p_down, area, t):
        a = self.amplitude(t) if self.amplitude is not None else 1.0
        if self.kind == "mass":
            return mass_flux_mass_flow(self.flux, area, a)
        return volume_flux_mass_flow(self.flux, area, up.rho, a)

    @property
    def breakpoints(self) -> tuple:
        """Times where the amplitude kinks [s] (the integrator stops there)."""
        return tuple(self.amplitude.breakpoints) if self.amplitude is not None else ()


class FluxFloat(IntEnum):
    FLUX = 0  # per unit area
    VOLUME = 1  # 1: a volume flux (times the first cavity's density)


class FluxInt(IntEnum):
    AMPLITUDE = 0  # its amplitude table of time, −1: none


@njit(LAW_SIGNATURE, cache=True)
def flux_kernel(lf, li, tx, ty, ti, st, amb, u, p_down, area, t):
    """The engine's prescribed flux [kg/s], signed, from the exchange's first cavity u."""
    k = li[FluxInt.AMPLITUDE]
    a = table_value(tx, ty, ti, k, t) if k >= 0 else 1.0
    if lf[FluxFloat.VOLUME] == 1.0:
        return volume_flux_mass_flow(lf[FluxFloat.FLUX], area, st[u, StateColumn.RHO], a)
    return mass_flux_mass_flow(lf[FluxFloat.FLUX], area, a)


def _lower(law, tables) -> tuple:
    amplitude = tables.add(law.amplitude) if law.amplitude is not None else -1
    return (float(law.flux), float(law.kind == "volume")), (amplitude,)


LAW = LawSpec(names=("mass_flux", "volume_flux"), law=FluxLaw, kernel=flux_kernel,
              keys=(LawKey("flux", "mass_flux [kg/(s m^2)] / volume_flux [m^3/(s m^2)]: prescribed flow per area, "
                           "signed, positive from `from` to `to`", default=0.0, check="finite"),
                    LawKey("flux_amplitude", "mass_flux / volume_flux: multiplier, a number or CSV (time [s], [-])",
                           default=None, kind="table")),
              build=lambda name, values, read_table: FluxLaw(name.split("_")[0], values["flux"],
                                                             values["flux_amplitude"]),
              lower=_lower)
