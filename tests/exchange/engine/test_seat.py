"""Seat contact on the engine, its compiled DOP853 against scipy's DOP853 stepping the same kernels: the relief
valves, seat variants.

The two integrators run the same algorithm on the same contact kernels (exchange/contact/laws.py,
exchange/engine/body.py); they differ only by round-off (sums in another order), which moves step sizes where
the error estimate is itself round-off (a constant-rate fill). So the events must be the same, in the same order,
and the histories must agree to the solver's tolerance, converging together as rtol shrinks.
"""
import copy
import dataclasses
from pathlib import Path

import numpy as np
import pytest

from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import load_scene, read_scene_data, scene_from_dict
from tests.test_contact_scenes import poppet_scene

CASES = Path(__file__).resolve().parents[3] / "cases"


def both(scene, rtol=None):
    """(compiled DOP853, scipy DOP853) Results of one scene."""
    out = []
    for integrator in ("compiled", "scipy"):
        model = build_model(scene)
        if rtol is not None:
            o = model.options
            model.options = dataclasses.replace(o, rtol=rtol, atol=o.atol * rtol / o.rtol)
        model.options = dataclasses.replace(model.options, integrator=integrator)
        out.append(run(model))
    return out


def peak_relative(a, b) -> np.ndarray:
    """Largest difference per history column over the column's peak."""
    return np.abs(a.history - b.history).max(axis=0) / np.maximum(np.abs(b.history).max(axis=0), 1e-300)


def assert_same_run(fast, slow, history_tol, time_tol=1e-9):
    assert fast.summary["solver"]["path"] == "compiled" and slow.summary["solver"]["path"] == "compiled, solve_ivp"
    ef, es = fast.summary["solver"]["event log"], slow.summary["solver"]["event log"]
    assert [label for _, label in ef] == [label for _, label in es]
    assert max((abs(a[0] - b[0]) for a, b in zip(ef, es)), default=0.0) <= time_tol
    assert fast.columns == slow.columns
    assert peak_relative(fast, slow).max() <= history_tol
    cf, cs = fast.summary["contact"]["seat"], slow.summary["contact"]["seat"]
    for key in ("reseats", "lift-offs", "seat nodes"):
        assert cf[key] == cs[key]
    assert np.array_equal(fast.contact["status"], slow.contact["status"])
    peak = max(np.abs(slow.contact["cpress"]).max(), 1e-300)
    assert np.abs(fast.contact["cpress"] - slow.contact["cpress"]).max() <= history_tol * peak
    return cf, cs


@pytest.mark.parametrize("name", ["relief_valve", "relief_valve_undamped"])
def test_relief_valves_have_the_same_events_and_history_on_both_integrators(name):
    """At the case's rtol 1e-9: same 97–107 events (observed times within 4e-11 s), histories within 1e-6 of
    each column's peak (observed 6e-8, the poppet's 25 µm lift being the most sensitive column), every opening
    at the preload's pressure."""
    fast, slow = both(load_scene(CASES / f"{name}.toml"))
    cf, cs = assert_same_run(fast, slow, 1e-6)
    assert cf["lift-offs"] >= 19
    assert cf["opening pressure max relative error [-]"] <= 1e-12
    assert np.allclose(cf["impact speeds [m/s]"], cs["impact speeds [m/s]"], rtol=1e-6)
    assert fast.summary["solver"]["steps"] == pytest.approx(slow.summary["solver"]["steps"], abs=10)  # 500 vs 507


def test_the_two_integrators_converge_together_as_rtol_shrinks():
    """The difference is the solver's tolerance, not the model: at rtol 1e-12 the relief valve's histories agree
    to 1e-9 of each peak (observed 3e-10; 6e-8 at 1e-9)."""
    data = copy.deepcopy(read_scene_data(CASES / "relief_valve.toml"))
    data["time"]["end"] = 0.1
    fast, slow = both(scene_from_dict(data, CASES / "relief_valve.toml"), rtol=1e-12)
    assert_same_run(fast, slow, 1e-9, time_tol=1e-11)


def relief_variant():
    """The relief valve with another preload (12 N) and damping (μ0 8e4 Pa·s/m, η 0.3 of a 0.2 mm clearance)."""
    data = copy.deepcopy(read_scene_data(CASES / "relief_valve.toml"))
    data["time"]["end"] = 0.1
    data["body"][0]["spring_preload"] = 12.0
    data["contact"][0].update(mu0=8e4, damping_clearance=2e-4, eta=0.3)
    return scene_from_dict(data, CASES / "relief_valve.toml")


def scene(data):
    return scene_from_dict(data, CASES / "test_scene.toml")


@pytest.mark.parametrize("variant, tol", [
    ("relief 12 N, mu0 8e4, eta 0.3", 1e-6),
    ("penalty drop, critical fraction 0.3", 1e-9),
    ("softened drop, standard damping", 1e-9),
    ("hard drop under gravity, explicit damping", 1e-9),
])
def test_seat_variants_are_the_same_on_both_integrators(variant, tol):
    """Every law and damping style through both integrators: same events (kinks, seat switches, impacts), same
    histories and CPRESS (observed 4e-9 of the peaks on the relief variant at rtol 1e-9; on the drops at 1e-10,
    ≤ 1.2e-12 on one machine and 3.4e-10 on another, whose numba and numpy round differently: the round-off moves
    a step size where the error estimate is itself round-off, so the bound is 10 rtol, not a round-off figure)."""
    drop = dict(preload=0.0, velocity=1.5, axis=(0.0, 0.0, -1.0), end=2.5e-3)
    sc = {
        "relief 12 N, mu0 8e4, eta 0.3": relief_variant,
        "penalty drop, critical fraction 0.3": lambda: scene(poppet_scene(
            {"pressure_overclosure": "linear", "stiffness": 1e10, "damping": "critical_fraction",
             "critical_fraction": 0.3}, **drop)),
        "softened drop, standard damping": lambda: scene(poppet_scene(
            {"pressure_overclosure": "exponential", "clearance": 2e-5, "pressure": 2e5, "damping": "coefficient",
             "mu0": 2e4, "damping_clearance": 4e-5, "eta": 0.25}, **drop)),
        "hard drop under gravity, explicit damping": lambda: scene(poppet_scene(
            {"pressure_overclosure": "hard", "damping": "coefficient", "mu0": 1e4, "style": "explicit"},
            preload=0.0, axis=(0.0, 0.0, -1.0), z=0.0035, end=0.03, body={"gravity": 9.81})),
    }[variant]()
    fast, slow = both(sc)
    cf, _ = assert_same_run(fast, slow, tol)
    assert fast.summary["solver"]["events"] >= 1
    if variant.startswith("hard"):
        assert cf["reseats"] == 1 and fast.column("poppet.velocity")[-1] == 0.0


def test_lsoda_runs_on_the_engine_for_a_seat_scene():
    """solve_ivp's LSODA on the engine (held mode in the engine's arrays) takes the compiled DOP853's events, and
    its history agrees to 1e-6 of each peak."""
    data = copy.deepcopy(read_scene_data(CASES / "relief_valve.toml"))
    data["time"]["end"] = 0.1
    sc = scene_from_dict(data, CASES / "relief_valve.toml")
    out = []
    for method in ("DOP853", "LSODA"):
        model = build_model(sc)
        model.options = dataclasses.replace(model.options, method=method)
        out.append(run(model))
    fast, other = out
    assert other.summary["solver"]["path"] == "compiled, solve_ivp"
    assert [lb for _, lb in other.summary["solver"]["event log"]] == [lb for _, lb in fast.summary["solver"]["event log"]]
    assert other.summary["contact"]["seat"]["lift-offs"] >= 3
    assert peak_relative(other, fast).max() <= 1e-6
