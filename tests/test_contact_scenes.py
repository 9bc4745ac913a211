"""Contact through scenes (issue 7): CPRESS per node, restitution of a dropped body, the relief valve's opening."""
import copy
import math
from pathlib import Path

import numpy as np
import pytest

from exchange.contact import ContactDamping, Hard, LinearPenalty, Softened, cpress
from cases.scene.errors import SceneError
from cases.run.runner import run_scene
from cases.scene.files import read_scene_data, scene_from_dict
from cases.model.seat_contact import STATUS_CODES, SeatContact

CASES = Path(__file__).resolve().parents[1] / "cases"
SEAT = "meshes/relief_seat.obj"  # annulus r = 5..6 mm, 144 nodes, 96 quads
SEAT_AREA = 3.445891474609362e-05  # its polygonal area [m^2]


def poppet_scene(contact: dict, *, end=0.002, preload=12.5, velocity=0.0, axis=(0.0, 0.0, 1.0), z=0.0025,
                 body=None) -> dict:
    """A rigid tank at ambient and a 10 g box poppet resting on (or moving at) the relief valve's seat mesh."""
    b = {"name": "poppet", "box": [0.0, 0.0, z, 0.016, 0.016, 0.005], "axis": list(axis), "mass": 0.01,
         "spring_preload": preload, "initial_velocity": velocity, **(body or {})}
    if not preload:
        del b["spring_preload"]
    return {"time": {"end": end, "output_interval": end / 20}, "solver": {"rtol": 1e-10},
            "cavity": [{"name": "tank", "pressure": 101325.0, "temperature": 293.15, "volume": 1e-3}],
            "body": [b], "contact": [{"name": "seat", "body": "poppet", "seat_mesh": SEAT, **contact}]}


def run_dict(data):
    return run_scene(scene_from_dict(data, CASES / "test_scene.toml"))


@pytest.mark.parametrize("contact", [{"pressure_overclosure": "hard"},
                                     {"pressure_overclosure": "hard", "damping": "coefficient", "mu0": 1e4,
                                      "damping_clearance": 1e-4}])
def test_static_poppet_cpress_is_force_over_area_on_every_seat_node(contact):
    force = 12.5
    res = run_dict(poppet_scene(contact, preload=force))
    cp, status = res.contact["cpress"], res.contact["status"]
    assert cp.shape == (21, 144) and np.all(status == STATUS_CODES["closed"])
    assert np.max(np.abs(cp / (force / SEAT_AREA) - 1.0)) <= 1e-9
    assert float(cp[-1] @ res.contact["nodal_area"]) == pytest.approx(force, rel=1e-12)
    summary = res.summary["contact"]["seat"]
    assert summary["peak CPRESS [Pa]"] == pytest.approx(force / SEAT_AREA, rel=1e-12)
    assert summary["reseats"] == summary["lift-offs"] == 0
    assert res.column("poppet.displacement")[-1] == 0.0


def test_static_poppet_on_a_stiff_critically_damped_penalty_seat_settles_to_force_over_area():
    force = 12.5
    res = run_dict(poppet_scene({"pressure_overclosure": "linear", "stiffness": 1e13, "damping": "critical_fraction",
                                 "critical_fraction": 1.0}, preload=force, end=0.005))
    cp = res.contact["cpress"][-1]
    assert np.all(res.contact["status"][-1] == STATUS_CODES["closed"])
    assert np.max(np.abs(cp / (force / SEAT_AREA) - 1.0)) <= 1e-9


@pytest.mark.parametrize("law", [{"pressure_overclosure": "linear", "stiffness": 1e12},
                                 {"pressure_overclosure": "exponential", "clearance": 1e-5, "pressure": 1e5}])
def test_preloaded_poppet_on_a_soft_seat_starts_at_rest_in_equilibrium(law):
    """No damping: a poppet started at zero overclosure would ring for ever; it starts where the seat carries F."""
    force = 12.5
    res = run_dict(poppet_scene(law, preload=force, end=0.005))
    s = res.column("poppet.displacement")
    assert np.ptp(s) <= 1e-12 * abs(s[0]) and res.column("poppet.velocity") == pytest.approx(0.0, abs=1e-15)
    assert np.all(res.contact["status"] == STATUS_CODES["closed"])
    assert np.max(np.abs(res.contact["cpress"] / (force / SEAT_AREA) - 1.0)) <= 1e-9
    if law["pressure_overclosure"] == "linear":  # overclosure h = F / (k A)
        assert abs(s[0]) == pytest.approx(force / (1e12 * SEAT_AREA), rel=1e-9)


@pytest.mark.parametrize("zeta", [0.0, 0.03, 0.3])
def test_dropped_body_rebounds_with_damped_oscillator_restitution(zeta):
    """A 10 g body at 1.5 m/s enters a linear-penalty seat with critical fraction ζ, gravity off: it leaves
    with speed ratio exp(−ζπ/√(1−ζ²)) (the contact's exit is a switch located on the dense output)."""
    k_pen, v0, m = 1e10, 1.5, 0.01
    period = 2 * math.pi * math.sqrt(m / (k_pen * SEAT_AREA))
    contact = {"pressure_overclosure": "linear", "stiffness": k_pen}
    if zeta:
        contact.update(damping="critical_fraction", critical_fraction=zeta)
    res = run_dict(poppet_scene(contact, preload=0.0, velocity=v0, axis=(0.0, 0.0, -1.0), end=2 * period))
    restitution = -res.column("poppet.velocity")[-1] / v0
    assert restitution == pytest.approx(math.exp(-zeta * math.pi / math.sqrt(1 - zeta ** 2)), abs=1e-6)
    kinds = [e for e in res.model.network.contact_log]
    assert [k for _, k, _, _ in kinds] == ["separate"]  # it starts touching, then leaves once


def test_critically_damped_drop_does_not_rebound():
    k_pen, v0, m = 1e10, 1.5, 0.01
    omega = math.sqrt(k_pen * SEAT_AREA / m)
    res = run_dict(poppet_scene({"pressure_overclosure": "linear", "stiffness": k_pen, "damping": "critical_fraction",
                                 "critical_fraction": 1.0}, preload=0.0, velocity=v0, axis=(0.0, 0.0, -1.0),
                                end=20 / omega))
    s = res.column("poppet.displacement")
    assert np.all(s[1:] > 0.0) and res.model.network.contact_log == []
    t = res.column("time")
    assert np.allclose(s, v0 * t * np.exp(-omega * t), rtol=1e-6, atol=1e-15)


def constant_cp_relief_valve():
    data = read_scene_data(CASES / "relief_valve.toml")
    data = copy.deepcopy(data)
    data["species"] = [{"name": "gas", "molar_mass": 0.029, "cp": [29.0]}]
    data["ambient"]["gas"] = data["cavity"][0]["gas"] = data["cavity"][0]["inflator"][0]["gas"] = {"gas": 1.0}
    data["time"]["end"] = 0.1
    return data


def test_relief_valve_lifts_at_the_preload_pressure_and_the_closed_form_time():
    """Constant-cp gas: the rigid adiabatic fill is p = p0 + γRṁT·t/V, so the first lift-off time is known."""
    data = constant_cp_relief_valve()
    res = run_dict(data)
    c = res.summary["contact"]["seat"]
    R = 8.314462618 / 0.029
    gamma = 29.0 / (29.0 - 8.314462618)
    body, cav = data["body"][0], data["cavity"][0]
    p_open = 101325.0 + body["spring_preload"] / body["pressure_area"]
    t_open = (p_open - cav["pressure"]) * cav["volume"] / (gamma * R * 0.002 * 293.15)
    assert c["opening pressure predicted [Pa]"] == pytest.approx(p_open, rel=1e-15)
    assert c["opening pressure max relative error [-]"] <= 1e-6
    assert c["lift-off times [s]"][0] == pytest.approx(t_open, rel=1e-8)
    assert c["reseats"] >= 1 and c["lift-offs"] >= c["reseats"]
    assert res.summary["mass balance"]["chamber"]["relative imbalance [-]"] < 1e-12


def test_relief_valve_summary_reports_chatter_and_suggested_mu0():
    res = run_scene(CASES / "relief_valve.toml")
    c = res.summary["contact"]["seat"]
    assert c["opening pressure max relative error [-]"] <= 1e-6
    assert c["reseats"] > 5 and len(c["impact speeds [m/s]"]) == c["reseats"]
    assert c["peak viscous (VD) pressure [Pa]"] > 0
    assert c["suggested_mu0 [Pa s/m]"] == pytest.approx(0.01 * c["peak CPRESS [Pa]"] / c["peak body speed [m/s]"])
    assert "hard (kinematic)" in res.summary["modelled"]["contact"]["seat"]
    status = res.contact["status"]
    assert {int(v) for v in np.unique(status)} >= {STATUS_CODES["closed"], STATUS_CODES["VD"]}


LAWS = [Hard(), LinearPenalty(1e9), Softened(c0=2e-4, p0=1e5)]
DAMPINGS = [None, ContactDamping(1e4, c0=3e-4, eta=0.3), ContactDamping(1e4, c0=3e-4, eta=0.0),
            ContactDamping(2e3, style="explicit")]


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("damping", DAMPINGS)
def test_nodal_kernels_match_the_scalar_laws(law, damping):
    """SeatContact evaluates exchange.contact.cpress on arrays: same pressure and status at every node."""
    rng = np.random.default_rng(1)
    n = 200
    g0 = rng.uniform(-4e-4, 6e-4, n)
    g0[:5] = 0.0
    c = SeatContact("c", "b", law, damping, None, g0, np.ones(n), np.full(n, 1e-6), 1.0, np.zeros((n, 3)),
                    np.zeros((0, 3), int))
    for v in (-0.7, 0.0, 1.3):
        p, status = c.nodal(0.0, v, reaction=5e-6 * np.count_nonzero(g0 <= 0))
        for i in range(n):
            ref_p, ref_s = cpress(-g0[i], -v, law, damping, multiplier=5.0 if g0[i] <= 0 else 0.0)
            assert (p[i], status[i]) == (pytest.approx(ref_p, rel=1e-12, abs=1e-9), STATUS_CODES[ref_s]), i


def error(data) -> str:
    with pytest.raises(SceneError) as exc:
        scene_from_dict(data, CASES / "bad.toml")
    return str(exc.value)


@pytest.mark.parametrize("edit, expected", [
    ({"damping": "critical_fraction"}, "contact[0].damping: a critical damping fraction is not available for hard"),
    ({"pressure_overclosure": "linear"}, "contact[0].stiffness: expected a number > 0"),
    ({"pressure_overclosure": "exponential", "clearance": 1e-4}, "contact[0].pressure: expected a number > 0"),
    ({"stifness": 1.0}, "contact[0].stifness: unknown key (did you mean 'stiffness'?)"),
    ({"pressure_overclosure": "soft"}, "expected one of 'hard', 'linear', 'exponential'"),
    ({"mu0": 3.0}, "contact[0].mu0: not used by damping = 'none'"),
    ({"damping": "coefficient"}, "contact[0].mu0: expected a damping coefficient > 0"),
    ({"damping": "coefficient", "mu0": 1.0, "style": "explicit", "damping_clearance": 1e-3},
     "contact[0].style: explicit-style damping acts while closed only"),
    ({"body": "popet"}, "contact[0].body: no body named 'popet' (did you mean 'poppet'?)"),
    ({"seat_mesh": "", "seat": "vent"}, "contact[0].seat: no exchange named 'vent'"),
    ({"seat_mesh": "missing.obj"}, "contact[0].seat_mesh: file 'missing.obj' does not exist"),
])
def test_bad_contact_keys_name_the_key(edit, expected):
    data = poppet_scene({"pressure_overclosure": "hard"})
    data["contact"][0].update(edit)
    if not data["contact"][0]["seat_mesh"]:
        del data["contact"][0]["seat_mesh"]
    assert expected in error(data)


def test_bad_body_force_keys():
    data = poppet_scene({}, body={"pressure_area": 1e-4})
    assert "body[0].pressure_cavity: give pressure_area and pressure_cavity together" in error(data)
    data = poppet_scene({}, body={"pressure_area": 1e-4, "pressure_cavity": "tnak"})
    assert "did you mean 'tank'?" in error(data)
    data = poppet_scene({}, body={"mass": 0.0})
    assert "body[0].spring_preload: only a dynamic body (mass > 0) feels forces" in error(data)


def test_vtk_frames_of_the_seat_carry_cpress_and_status(tmp_path):
    pytest.importorskip("pyvista")
    from cases.results.pictures import frames_for
    from cases.results.render_vtk import leak_polydata

    data = constant_cp_relief_valve()
    data["time"]["end"] = 0.085
    res = run_dict(data)
    lift = res.summary["contact"]["seat"]["lift-off times [s]"][0]
    j = res.model.network.contact.exchange
    closed, opened = (leak_polydata(f) for f in frames_for(res, j, [0.0, lift + 1e-4]))
    assert np.allclose(closed.point_data["CPRESS"], 15.0 / SEAT_AREA, rtol=1e-9)
    assert set(closed.point_data["status"]) == {STATUS_CODES["closed"]}
    assert set(opened.point_data["status"]) == {STATUS_CODES["VD"]}
    assert np.all(opened.point_data["CPRESS"] < 0.0)  # damping resists the opening


def test_hard_contact_stops_a_falling_body_and_then_carries_its_weight():
    """Dropped from 1 mm under gravity onto a hard seat: impact at √(2h/g) with speed √(2gh), perfectly plastic
    (kinematic contact), then held with CPRESS = m·g / A on every node."""
    h, g, m = 1e-3, 9.81, 0.01
    res = run_dict(poppet_scene({"pressure_overclosure": "hard"}, preload=0.0, axis=(0.0, 0.0, -1.0),
                                z=0.0025 + h, end=0.03, body={"gravity": g}))
    c = res.summary["contact"]["seat"]
    assert c["reseats"] == 1 and c["lift-offs"] == 0
    assert c["reseat times [s]"][0] == pytest.approx(math.sqrt(2 * h / g), rel=1e-9)
    assert c["impact speeds [m/s]"][0] == pytest.approx(math.sqrt(2 * g * h), rel=1e-9)
    assert res.column("poppet.displacement")[-1] == h and res.column("poppet.velocity")[-1] == 0.0
    assert np.max(np.abs(res.contact["cpress"][-1] / (m * g / SEAT_AREA) - 1.0)) <= 1e-9
    assert np.all(res.contact["cpress"][0] == 0.0) and np.all(res.contact["status"][0] == STATUS_CODES["open"])


def test_outputs_hold_nodal_cpress_and_the_contact_summary(tmp_path):
    import json

    from cases.results.output import write_results

    res = run_dict(poppet_scene({"pressure_overclosure": "hard"}, preload=12.5))
    paths = write_results(res, tmp_path)
    with np.load(paths["contact"]) as data:
        assert data["cpress"].shape == (21, 144) and data["status"].dtype == np.uint8
        assert np.allclose(data["cpress"], 12.5 / SEAT_AREA, rtol=1e-9)
        assert list(data["status_codes"]) == ["open", "closed", "VD"]
    summary = json.loads(paths["summary"].read_text())
    assert summary["contact"]["seat"]["peak CPRESS [Pa]"] == pytest.approx(12.5 / SEAT_AREA, rel=1e-12)
    assert "suggested_mu0 [Pa s/m]" in summary["contact"]["seat"]
    assert "seat.max_cpress [Pa]" in paths["history"].read_text().splitlines()[0]
