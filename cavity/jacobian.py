"""A Jacobian by forward differences over the unknowns a right-hand side depends on (for LSODA's stiff mode)."""
from __future__ import annotations

import numpy as np

__all__ = ["coupled_jacobian", "jacobian_option", "IMPLICIT", "stiffness_advice", "EXPLICIT_METHODS"]

#: Methods that use a Jacobian (LSODA in its stiff mode).
IMPLICIT = ("LSODA", "BDF", "Radau")
EXPLICIT_METHODS = ("RK23", "RK45", "DOP853")


def coupled_jacobian(system, stats: dict, rhs=None):
    """∂f/∂y of ``rhs`` (default ``system.rhs``) by forward differences over ``system.coupled_unknowns`` only,
    the unknowns the right-hand side depends on (the others, ledger integrals, have zero columns: exactly, not
    approximately); the right-hand sides it costs are added to ``stats["rhs_calls"]``. The step is
    √ε·max(|y_j|, 1e-6)."""
    cols = np.asarray(system.coupled_unknowns, dtype=int)
    f = system.rhs if rhs is None else rhs

    def jac(t, y):
        y = np.asarray(y, dtype=float)
        f0 = np.asarray(f(t, y))
        J = np.zeros((y.size, y.size))
        for j in cols:
            h = 1.4901161193847656e-08 * max(abs(y[j]), 1e-6)
            yj = y.copy()
            yj[j] += h
            J[:, j] = (np.asarray(f(t, yj)) - f0) / (yj[j] - y[j])
        stats["rhs_calls"] += 1 + cols.size
        return J

    return jac


def jacobian_option(system, method: str, rhs, stats: dict) -> dict:
    """solve_ivp's ``jac`` keyword: :func:`coupled_jacobian` of ``rhs`` (the system's Python right-hand side or
    its compiled one) for an implicit method when the system names its ``coupled_unknowns``; else none (the
    method differences all)."""
    if method in IMPLICIT and getattr(system, "coupled_unknowns", None) is not None:
        return {"jac": coupled_jacobian(system, stats, rhs)}
    return {}


#: An explicit method is told to switch to an implicit one only when the scene is stiff: the fastest time scale of
#: its Jacobian, 1/ρ, is shorter than the time left by this factor (DOP853's stability bound |h·λ| ≈ 6 then forces
#: more than ~1,700 steps where accuracy alone would need a few).
STIFF_RATIO = 1e4


def stiffness_advice(method: str, system=None, t: float = 0.0, y=None, t_end: float | None = None) -> str:
    """The advice appended to a step-budget or step-size failure of an explicit method: switch to an implicit
    method when the scene is stiff at (t, y) (spectral radius ρ of ∂f/∂y by differences,
    ρ·(t_end − t) > :data:`STIFF_RATIO`), else look for an input orders of magnitude off. Without a system to
    test, nothing.

    >>> stiffness_advice("Radau"), stiffness_advice("DOP853")
    ('', '')
    """
    if method not in EXPLICIT_METHODS or system is None or y is None or t_end is None:
        return ""
    rho = _spectral_radius(system, t, y)
    if rho is None:
        return ""
    left = max(t_end - t, 0.0)
    scale = f"{1.0 / rho:.3g} s" if rho > 0 else "none"
    if rho * left > STIFF_RATIO:
        return (f"; the scene is stiff here (its fastest time scale, {scale}, is {rho * left:.2g} times shorter than "
                f"the {left:.3g} s left) for the explicit method {method!r}: set [solver] method = 'Radau' "
                "(or 'LSODA')")
    return (f"; the scene is not stiff here (fastest time scale {scale}): an input orders of magnitude off (an area, "
            "a rate, a volume: check the units) or a discontinuity the scene does not declare is more likely")


def _spectral_radius(system, t: float, y) -> float | None:
    """Largest |eigenvalue| of the system's Jacobian at (t, y) by forward and backward differences of relative
    steps √ε and 1e-5 (a flow law with a kink at Δp = 0, a one-way vent, is stiff on one side and beyond the
    kink only), or None when it cannot be evaluated."""
    if not hasattr(system, "rhs"):
        return None
    y = np.asarray(y, dtype=float)
    cols = getattr(system, "coupled_unknowns", None)
    cols = range(y.size) if cols is None else cols
    rho = 0.0
    try:
        with np.errstate(all="ignore"):
            f0 = np.asarray(system.rhs(t, y))
            for step in (1.4901161193847656e-08, -1.4901161193847656e-08, 1e-5, -1e-5):
                J = np.zeros((y.size, y.size))
                for j in cols:
                    yj = y.copy()
                    yj[j] += step * max(abs(y[j]), 1e-300)
                    J[:, j] = (np.asarray(system.rhs(t, yj)) - f0) / (yj[j] - y[j])
                rho = max(rho, float(np.max(np.abs(np.linalg.eigvals(J)))) if J.size else 0.0)
    except Exception:  # noqa: BLE001 - the advice is a hint: a state the RHS cannot evaluate gives none
        return None
    return rho if np.isfinite(rho) else None
