"""A Jacobian by forward differences over the unknowns a right-hand side depends on (for LSODA's stiff mode)."""
from __future__ import annotations

import numpy as np

__all__ = ["coupled_jacobian", "jacobian_option", "IMPLICIT"]

#: Methods that use a Jacobian (LSODA in its stiff mode).
IMPLICIT = ("LSODA", "BDF", "Radau")


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
