"""Prescribed flux (Abaqus *FLUID EXCHANGE PROPERTY, TYPE=MASS FLUX / VOLUME FLUX).

The flow is prescribed per unit area and scaled by the exchange area and an amplitude (the *FLUID EXCHANGE
ACTIVATION amplitude multiplier). Unlike the pressure-driven laws it is signed: positive flows from the primary
cavity to the secondary cavity (or the environment), negative flows into the primary cavity. This follows the
Abaqus VUFLUIDEXCH convention ("a positive mass flow rate indicates flow from the primary fluid cavity to the
secondary fluid cavity") and the fluid exchange guide ("the flow can either be into or out of the primary cavity";
gas flowing in takes the instantaneous properties of the primary cavity's gas).

Pure arithmetic: the functions are numba kernels (the compiled right-hand side inlines them; from Python they accept
floats or numpy arrays alike).
"""
from __future__ import annotations

from numba import njit

__all__ = ["mass_flux_mass_flow", "volume_flux_mass_flow"]


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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
