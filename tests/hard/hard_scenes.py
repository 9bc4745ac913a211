"""Helpers of the hard cases: scenes built in code (tests/scenes.py pattern), run, and physical sanity checks."""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import scene_from_dict
from tests.scenes import tank

R_U = 8.314462618
M_N2, CP_N2 = 0.0280134, 29.100619163
R_N2 = R_U / M_N2
GAMMA = CP_N2 / (CP_N2 - R_U)
CV_N2 = (CP_N2 - R_U) / M_N2  # [J/(kg K)]
CPM_N2 = CP_N2 / M_N2  # [J/(kg K)]
P_AMB, T_AMB = 1.0e5, 300.0  # the ambient of tests.scenes.tank()

#: Tolerance of "monotone" on the history: the scenes run at rtol 1e-10 and the dense output between steps may
#: wobble at that level (measured 2e-12·p after a blowdown stops at ambient).
MONOTONE_RTOL = 1e-9

__all__ = ["MONOTONE_RTOL", "tank", "run_scene", "check_sane", "series", "R_N2", "GAMMA", "CV_N2", "CPM_N2",
           "P_AMB", "T_AMB"]


def run_scene(data: dict, folder: Path, **options):
    """Validate, build and run a scene dict; ``options`` replace fields of the solver options (e.g. max_steps)."""
    model = build_model(scene_from_dict(data, Path(folder) / "scene.toml"))
    if options:
        model.options = replace(model.options, **options)
    return run(model)


def series(r, cavity: str = "tank"):
    """(t, p, T, m) of a cavity from the history."""
    return (r.column("time"), r.column(f"{cavity}.pressure"), r.column(f"{cavity}.temperature"),
            r.column(f"{cavity}.mass"))


def check_sane(r, *, max_steps: int, cavity: str = "tank") -> None:
    """No NaN anywhere, mass >= 0, T > 0, p > 0, mass balance to round-off, and at most ``max_steps`` steps."""
    assert np.all(np.isfinite(r.history)), "NaN or infinite value in the history"
    t, p, T, m = series(r, cavity)
    assert np.all(m >= 0.0), f"negative mass {m.min()!r} kg"
    assert np.all(T > 0.0), f"non-positive temperature {T.min()!r} K"
    assert np.all(p > 0.0), f"non-positive pressure {p.min()!r} Pa"
    steps = r.summary["solver"]["steps"]
    assert steps <= max_steps, f"{steps} steps (bound {max_steps}); solver stats {r.summary['solver']}"
    for name, bal in r.summary["mass balance"].items():
        assert bal["relative imbalance [-]"] <= 1e-11, (name, bal)
