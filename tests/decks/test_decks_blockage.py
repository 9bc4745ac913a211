"""The blockage deck's vent area against A_e·N_c/N_e at the plate positions: by brute force
(blockage.reference) and by the analytic distance from a vent node to the plate rectangle."""
from __future__ import annotations

import numpy as np
import pytest
import trimesh

import blockage
from blockage.reference import evaluate_reference
from cases.decks import deck_scene
from cases.run.library import HERE
from cases.run.runner import run_scene

A_EFF, SPEED, H, C0 = 2.0e-4, 2.0, 0.0005, 0.001  # effective area [m^2], plate speed [m/s], gap, clearance [m]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("blockage")
    scene, imported = deck_scene(HERE / "decks" / "vented_box_blockage.inp", tmp / "scene.toml")
    return run_scene(scene), tmp, imported


def analytic_leak_area(t):
    """A_eff·(1 − Σ A_e N_c/N_e / Σ A_e) with N_c counted from the exact node-to-rectangle distance."""
    x0, x1, y0, y1 = -0.15 + SPEED * t, -0.03 + SPEED * t, 0.04, 0.16
    blocked_area = 0.0
    for i in (1, 2):  # the 2 x 2 vent elements of 0.05 m, from x, y = 0.05 to 0.15
        for j in (1, 2):
            corners = [(0.05 * (i + a), 0.05 * (j + b)) for a, b in ((0, 0), (1, 0), (1, 1), (0, 1))]
            n_c = sum(np.hypot(np.hypot(max(x0 - x, 0, x - x1), max(y0 - y, 0, y - y1)), H) <= C0
                      for x, y in corners)
            blocked_area += 0.05 * 0.05 * n_c / 4
    return A_EFF * (1.0 - blocked_area / 0.01)


def test_vent_area_is_the_unblocked_fraction_of_the_effective_area(run):
    results, tmp, imported = run
    vent = blockage.LeakageSurface.read(tmp / imported.data["exchange"][0]["leakage_surface"])
    plate = trimesh.load(tmp / imported.data["body"][0]["mesh"], force="mesh")
    t, area = results.column("time"), results.column("vent.area")
    checked = set()
    for k in range(0, len(t), 4):
        shift = np.eye(4)
        shift[0, 3] = SPEED * t[k]
        ref = evaluate_reference(vent, [(plate, shift)], C0, effective_area=A_EFF)
        assert abs(area[k] - ref.leak_area) <= 1e-15 * A_EFF, t[k]
        assert abs(area[k] - analytic_leak_area(t[k])) <= 1e-15 * A_EFF, t[k]
        checked.add(round(area[k] / A_EFF * 12))  # 12ths: N_c/N_e steps of the four elements
    assert len(checked) >= 4  # open, partly blocked (several fractions), closed
    assert area[0] == A_EFF and area[-1] == 0.0


def test_node_based_vent_loses_the_share_of_its_active_nodes(tmp_path):
    """*SURFACE, TYPE=NODE as the leakage surface: area = A_eff·(1 − active nodes / all), the nodes counted by the
    analytic distance to the plate rectangle (Abaqus: node-based surface, blocked fraction of the nodes)."""
    deck = (HERE / "decks" / "vented_box_blockage.inp").read_text().replace(
        "*SURFACE, NAME=VENT_SURF\n VENT_ELS, SPOS",
        "*NSET, NSET=VENT_NODES, ELSET=VENT_ELS\n*SURFACE, NAME=VENT_SURF, TYPE=NODE\n VENT_NODES")
    (tmp_path / "vented_box_mesh.inp").write_text((HERE / "decks" / "vented_box_mesh.inp").read_text())
    (tmp_path / "nodes.inp").write_text(deck)
    scene, imported = deck_scene(tmp_path / "nodes.inp", tmp_path / "out" / "s.toml")
    assert imported.data["exchange"][0]["leakage_nodes"] == "nodes/vent_leak_nodes.csv"
    r = run_scene(scene)
    t, area = r.column("time"), r.column("vent.area")
    grid = [(0.05 * i, 0.05 * j) for i in (1, 2, 3) for j in (1, 2, 3)]
    for k in range(0, len(t), 4):
        x0, x1 = -0.15 + SPEED * t[k], -0.03 + SPEED * t[k]
        active = sum(np.hypot(np.hypot(max(x0 - x, 0, x - x1), max(0.04 - y, 0, y - 0.16)), H) <= C0
                     for x, y in grid)
        assert abs(area[k] - A_EFF * (1 - active / 9)) <= 1e-15 * A_EFF, t[k]
    assert area[0] == A_EFF and area[-1] == 0.0


def test_edge_to_edge_contact_formulation_sets_edge_contact(tmp_path):
    deck = (HERE / "decks" / "vented_box_blockage.inp").read_text().replace(
        "*CONTACT INCLUSIONS, ALL EXTERIOR",
        "*CONTACT INCLUSIONS, ALL EXTERIOR\n*CONTACT FORMULATION, TYPE=EDGE TO EDGE")
    (tmp_path / "vented_box_mesh.inp").write_text((HERE / "decks" / "vented_box_mesh.inp").read_text())
    (tmp_path / "edges.inp").write_text(deck)
    scene, imported = deck_scene(tmp_path / "edges.inp", tmp_path / "out" / "s.toml")
    assert imported.data["exchange"][0]["edge_contact"] is True and scene.exchange[0].edge_contact
    assert not any("CONTACT FORMULATION" in i for i in imported.ignored)
