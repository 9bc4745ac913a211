"""An Abaqus deck with the default HARD contact (no *SURFACE BEHAVIOR) and *BLOCKAGE: contact at gap <= 0, a
plate resting at gap exactly 0 on 9 of the 15 vent nodes blocks A_e·N_c/N_e of each element."""
from __future__ import annotations

from pathlib import Path

import numpy as np

import tests.closed_forms as cf
from cases.decks import deck_scene
from cases.run.runner import run_scene

DECK = Path(__file__).parent / "hard_contact_rest.inp"
A_EFF, CD, V, P0, T0, M, CP = 2.0e-4, 0.6, 0.008, 3.0e5, 293.15, 0.0289, 29.1


def test_a_plate_resting_at_gap_zero_blocks_its_nodes_and_the_vent_blows_down_choked(tmp_path):
    scene, imported = deck_scene(DECK, tmp_path / "scene.toml")
    assert imported.data["exchange"][0]["contact_tolerance"] == 0.0  # HARD: contact at gap <= 0
    r = run_scene(scene)
    # strip of 4 x 2 elements 0.05 m square, nodes at x = 0 .. 0.2; the plate touches x = 0, 0.05, 0.1:
    # elements with x in [0, 0.1] have N_c/N_e = 1, those in [0.1, 0.15] 1/2, the last two 0
    blocked = sum(0.05 * 0.05 * f for f in (1, 1, 1, 1, 0.5, 0.5, 0, 0))
    area = A_EFF * (1.0 - blocked / (8 * 0.05 * 0.05))
    np.testing.assert_allclose(r.column("vent.area"), area, rtol=1e-15)
    gamma, R = CP / (CP - cf.R_U), cf.R_U / M
    tau = cf.blowdown_tau(V, CD, area, gamma, R, T0)
    t, p = r.column("time"), r.column("box.pressure")
    p_ref = np.array([cf.choked_adiabatic_pressure(x, P0, tau, gamma) for x in t])
    assert p_ref.min() >= 101325.0 * ((gamma + 1) / 2) ** (gamma / (gamma - 1))  # choked all along
    assert np.max(np.abs(p / p_ref - 1)) <= 1e-6
