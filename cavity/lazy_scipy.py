"""scipy's functions that ventsim's common path does not need, imported on first use.

``scipy.integrate`` costs about half a second of CPU to import (it loads quadrature, special functions and
optimisation too), and a scene on the compiled DOP853 path never calls it; the wrappers here import it when a
scipy method actually runs.
"""
from __future__ import annotations

__all__ = ["solve_ivp"]


def solve_ivp(*args, **kwargs):
    """``scipy.integrate.solve_ivp(*args, **kwargs)``, importing scipy.integrate on the first call."""
    from scipy.integrate import solve_ivp as scipy_solve_ivp

    return scipy_solve_ivp(*args, **kwargs)
