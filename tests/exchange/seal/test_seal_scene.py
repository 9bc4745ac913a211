"""The seal as a scene exchange on the engine (law = "seal"): the flange scene's leak onset against the static
formula, its mass balance, the rtol ladder, and the ring's closure under a flange loaded by a constant force
against the closed-form motion (free flight, then a harmonic oscillator on the penalty gasket)."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from cases.model.build import build_model
from cases.run.library import HERE
from cases.run.runner import run
from cases.scene.errors import SceneError
from cases.scene.files import load_scene, scene_from_dict
from exchange.seal.flange import leak_onset_pressure
from exchange.seal.gap_laws import ExponentialGap
from exchange.seal.meshes import annulus_mesh

FLANGE = HERE / "seal_flange.toml"


@pytest.fixture(scope="module")
def flange_run():
    model = build_model(load_scene(FLANGE))
    return model, run(model)


def _event_times(results, label):
    return [t for t, name in results.trajectory.events if name == label]


def test_flange_leak_onset_is_the_static_formula(flange_run):
    """The ring re-opens (event seal:kink0) where the flange's displacement reaches the closure displacement
    s* = −p_c/k (to 1e-12 of the seat size), at the pressure the static balance of the preload, the gasket's contact
    pressure p_c and the vessel's pressure gives, p_onset = p_a + (F_b − p_c·A_g)/A_p, corrected by the flange's
    inertia and the contact damping at that instant (to 1e-9); those two terms are < 3e-4 of p_onset."""
    model, results = flange_run
    net = model.network
    t = _event_times(results, "seal:kink0")[0]
    y = results.trajectory(t)
    k = net.body_offset
    law = net.exchanges[0].law
    contact, body = net.contact, model.scene.body[0]
    assert abs(y[k] - law.curve.closure) <= 1e-12 * contact.size
    p = net.states(t, y)[0].pressure
    gap = ExponentialGap(10e-6, 1e6, 0.5e-6)
    p_c, a_g = gap.closing_pressure(), contact.seat_area
    assert law.curve.closure == pytest.approx(-p_c / 5e10, rel=1e-12)
    onset = leak_onset_pressure(body.spring_preload, a_g, body.pressure_area, p_c, 101325.0)
    accel = net.body_forces(t, y)[1]
    dynamic = body.mass * accel - (contact.force(y[k], y[k + 1]) - p_c * a_g)
    assert p == pytest.approx(onset + dynamic / body.pressure_area, rel=1e-9)
    assert abs(p / onset - 1.0) < 3e-4
    assert results.column("seal.mass_flow")[results.history[:, 0] < t].max() == 0.0


def test_flange_closes_again_when_vented_and_balances_mass(flange_run):
    model, results = flange_run
    opened, closed = _event_times(results, "seal:kink0")
    assert opened < 1.0 < 1.2 < closed  # re-opens while filled, closes again while vented
    assert results.summary["mass balance"]["vessel"]["relative imbalance [-]"] <= 1e-12
    flow = results.column("seal.mass_flow")
    assert flow[results.history[:, 0] > closed].max() == 0.0  # closed all around: exactly no leak
    fraction = results.column("seal.contact_fraction")
    assert fraction.min() == 0.0 and fraction.max() == 1.0  # it lifted off the gasket and sat back
    assert results.summary["modelled"]["seals"]["seal"]["gap law"].startswith("exponential")


def test_flange_rtol_ladder_is_monotone():
    """The onset and closure times and the pressure history converge monotonically down the rtol ladder."""
    model = build_model(load_scene(FLANGE))
    model = replace(model, scene=model.scene)
    runs = [run(replace(model, options=replace(model.options, rtol=r, atol=model.options.atol * r / 1e-8)))
            for r in (1e-5, 1e-7, 1e-9, 1e-12)]
    times = [np.array(_event_times(r, "seal:kink0")) for r in runs]
    p = [r.column("vessel.pressure") for r in runs]
    event_errors = [float(np.max(np.abs(t - times[-1]))) for t in times[:-1]]
    pressure_errors = [float(np.max(np.abs(q - p[-1])) / p[-1].max()) for q in p[:-1]]
    assert all(b < a for a, b in zip(event_errors, event_errors[1:])), event_errors
    assert all(b < a for a, b in zip(pressure_errors, pressure_errors[1:])), pressure_errors


def _closing_scene(tmp_path, gap, d, force, mass, stiffness):
    v, f = annulus_mesh(0.04, 0.05, 2, 48)
    lines = ["v %r %r %r" % tuple(map(float, x)) for x in v] + ["f %d %d %d %d" % tuple(q + 1) for q in f]
    (tmp_path / "ring.obj").write_text("\n".join(lines) + "\n")
    return scene_from_dict({
        "time": {"end": 0.01, "output_interval": 1e-4}, "solver": {"rtol": 1e-12},
        "ambient": {"pressure": 101325.0, "temperature": 293.15, "gas": {"N2": 1.0}},
        "body": [{"name": "flange", "box": [0.0, 0.0, d + 0.005, 0.12, 0.12, 0.01], "axis": [0.0, 0.0, 1.0],
                  "mass": mass, "spring_preload": force}],
        "cavity": [{"name": "vessel", "pressure": 3e5, "temperature": 293.15, "gas": {"N2": 1.0}, "volume": 1e-3,
                    "energy": "isothermal"}],
        "exchange": [{"name": "seal", "from": "vessel", "law": "seal", "leakage_surface": "ring.obj",
                      "gap_law": "exponential", "gap_h0": gap.h0, "gap_p0": gap.p0, "gap_percolation": gap.u_c,
                      "seal_viscosity": 1.76e-5, "seal_displacement_min": -2e-4, "seal_displacement_max": 1e-4}],
        "contact": [{"name": "gasket", "body": "flange", "seat": "seal", "pressure_overclosure": "linear",
                     "stiffness": stiffness}]}, tmp_path / "closing.toml")


def test_ring_closure_time_is_the_closed_form_to_1e_10(tmp_path):
    """A flange pushed by a constant force F from a clearance d: free flight s = −F t²/(2m) until touch, then
    m x'' = F − K x (x the overclosure, K = k·A_g). The ring closes where every node carries p_c, x* = p_c/k, at
    τ* = (φ + asin((x* − a)/R))/ω after touch (a = F/K, b = v1/ω, R = √(a² + b²), φ = atan2(a, b))."""
    gap, d, force, mass, k = ExponentialGap(10e-6, 1e6, 0.5e-6), 2e-6, 1.0e4, 2.0, 5e10
    model = build_model(_closing_scene(tmp_path, gap, d, force, mass, k))
    results = run(model)
    t_event = _event_times(results, "seal:kink0")[0]  # undamped: it re-opens and closes again as it rings
    a_g = model.network.contact.seat_area
    K, t1 = k * a_g, math.sqrt(2.0 * d * mass / force)
    omega, v1 = math.sqrt(K / mass), force * t1 / mass
    a, b = force / K, v1 / omega
    x_star = gap.closing_pressure() / k
    tau = (math.atan2(a, b) + math.asin((x_star - a) / math.hypot(a, b))) / omega
    assert abs(t_event - (t1 + tau)) <= 1e-10 * model.scene.time.end
    flow = results.column("seal.mass_flow")
    t = results.history[:, 0]
    assert flow[0] > 0.0 and flow[(t > t_event) & (t < t_event + 1e-4)].max() == 0.0


def test_a_seal_without_its_flange_is_one_clear_error(tmp_path):
    scene = _closing_scene(tmp_path, ExponentialGap(10e-6, 1e6, 0.5e-6), 2e-6, 1e4, 2.0, 5e10)
    with pytest.raises(SceneError, match="needs its flange"):
        pushed = replace(scene.body[0], pressure_area=1e-3, pressure_cavity="vessel")
        build_model(replace(scene, contact=(), body=(pushed,)))
    hard = replace(scene, contact=(replace(scene.contact[0], pressure_overclosure="hard", stiffness=0.0),))
    with pytest.raises(SceneError, match="not 'hard'"):
        build_model(hard)
    no_h0 = replace(scene, exchange=(replace(scene.exchange[0], gap_h0=0.0),))
    with pytest.raises(SceneError, match=r"exchange\[0\]\.gap_law: gap_law = 'exponential': .*gap_h0"):
        build_model(no_h0)


def test_merged_seat_rows_give_the_same_force_and_the_path_state_its_parts():
    """The engine's merged seat (nodes of equal clearance and side in one row) gives the seat force of every node
    to round-off, with penalty contact and critical damping; a load path's state is its heights and contact."""
    from cases.model.seat_contact import merged_seat_rows
    from exchange.contact.laws import seat_force
    from exchange.seal.load_paths import DisplacementPath

    rng = np.random.default_rng(3)
    table = np.c_[rng.choice([0.0, 1e-6, 2e-6], 400), np.ones(400), rng.uniform(1e-6, 2e-6, 400), np.ones(400)]
    law = np.array([1.0, 5e10, 0.0, 3.0, 0.0, 0.0, 0.0, 0.5, 2.0, table[:, 2].sum(), 0.05])  # critical fraction 0.5
    merged = merged_seat_rows(table)
    assert merged.shape == (3, 4) and merged[:, 2].sum() == pytest.approx(table[:, 2].sum(), rel=1e-15)
    for s, v in ((-3e-6, 0.01), (-1.5e-6, -0.02), (0.5e-6, 0.0)):
        assert seat_force(s, v, merged, law) == pytest.approx(seat_force(s, v, table, law), rel=1e-13, abs=1e-12)
    path = DisplacementPath(table, law, ExponentialGap(10e-6, 1e6, 0.5e-6))
    for s in (-2e-4, -1.5e-6, 0.0, 3e-6):
        h, touching = path.state(s)
        assert np.array_equal(h, path.heights(s)) and np.array_equal(touching, path.in_contact(s))


def test_range_end_is_an_event_at_its_closed_form_time(tmp_path):
    """The flange leaves the tabulated range's upper end s_max = −1 µm in free flight s = −F t²/(2m): the event
    <seal>:kink2 fires at t = √(2 m |s_max| / F) to 1e-10 of the run."""
    scene = _closing_scene(tmp_path, ExponentialGap(10e-6, 1e6, 0.5e-6), 2e-6, 1.0e4, 2.0, 5e10)
    scene = replace(scene, exchange=(replace(scene.exchange[0], seal_displacement_max=-1e-6),))
    results = run(build_model(scene))
    t = _event_times(results, "seal:kink2")[0]
    assert abs(t - math.sqrt(2.0 * 2.0 * 1e-6 / 1.0e4)) <= 1e-10 * scene.time.end


@pytest.mark.parametrize("keys", [
    {"gap_law": "persson", "gap_u0": 1e-6, "gap_p_star": 1e8, "gap_percolation": 1e-6, "gap_max": 20e-6},
    {"gap_law": "table", "gap_table": "gap.csv"},
    {"gap_law": "pvrc", "pvrc_gb": 6e6, "pvrc_a": 0.5, "pvrc_gs": 1e5, "pvrc_h1": 4e-6, "gap_max": 20e-6,
     "seal_loaded_to": -1e-4, "seal_viscosity_model": "coolprop", "seal_slip": True},
])
def test_every_gap_law_builds_its_curve_in_a_scene(tmp_path, keys):
    """Each gap law from scene keys: the law's K(s) is the film conductance of the load path's channel heights at
    the flange's displacements (within the curve's tolerance), and the law's flow uses the named viscosity."""
    from exchange.seal.reynolds import film_conductance
    from exchange.seal.viscosity import coolprop_viscosity

    (tmp_path / "gap.csv").write_text("pressure [Pa],gap [m]\n0,8e-6\n2e6,2e-6\n4e6,0\n")
    scene = _closing_scene(tmp_path, ExponentialGap(10e-6, 1e6, 0.5e-6), 2e-6, 1.0e4, 2.0, 5e10)
    data = {"gap_h0": 0.0, "gap_p0": 0.0, "gap_percolation": 0.0}
    data.update(keys)
    if keys.get("seal_viscosity_model") == "coolprop":
        data["seal_viscosity"] = 0.0
    seal = replace(scene.exchange[0], **data)
    model = build_model(replace(scene, exchange=(seal,)))
    (sm,) = model.geometry["seals"]
    for s in (-6e-5, -2e-5, 1e-6):
        k = sm.law.conductance(s)[0]
        exact = film_conductance(sm.film, sm.path.heights(s))[0]
        assert k == pytest.approx(exact, rel=2e-3, abs=1e-4 * max(sm.law.curve.values)), (s, keys["gap_law"])
    assert model.modelled["seals"]["seal"]["gap law"].startswith(keys["gap_law"])
    if "seal_viscosity_model" in keys:
        assert sm.law.viscosity(300.0) == pytest.approx(coolprop_viscosity(300.0, "Nitrogen"), rel=1e-5)
        assert sm.law.slip_values is not None and "unloading" in model.modelled["seals"]["seal"]["hysteresis"]


def test_flange_scene_is_the_same_on_scipys_integrator():
    """scipy's solve_ivp stepping the same kernels: the same events (the seal's re-opening and closure among them)
    at the same times, the same history."""
    from tests.exchange.engine.test_seat import both, peak_relative

    fast, slow = both(load_scene(FLANGE), rtol=1e-9)
    ef, es = fast.summary["solver"]["event log"], slow.summary["solver"]["event log"]
    assert [label for _, label in ef] == [label for _, label in es]
    assert "seal:kink0" in [label for _, label in ef]
    assert max(abs(a[0] - b[0]) for a, b in zip(ef, es)) <= 1e-8
    assert peak_relative(fast, slow).max() <= 1e-5
