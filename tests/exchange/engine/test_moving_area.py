"""Leakage surfaces on a vertex trajectory on the engine: the same histories on its two integrators (compiled
DOP853 and scipy's), and the area the solver used equal to blockage.evaluate of the surface placed at each output
time (brute force)."""
from dataclasses import replace

import numpy as np
import pytest

import blockage
from cases.model.build import build_model
from cases.run.runner import run
from cases.scene.files import load_scene, scene_from_dict
from tests.conftest import ROOT
from tests.scenes import tank
from tests.test_blockage_over_time import TOL, grid_vent, tilted_plate


def both_integrators(model):
    runs = [run(replace(model, options=replace(model.options, integrator=i))) for i in ("compiled", "scipy")]
    assert [r.summary["solver"]["path"] for r in runs] == ["compiled", "compiled, solve_ivp"]
    return runs


def largest_difference(fast, slow) -> float:
    scale = np.maximum(np.max(np.abs(slow.history), axis=0), 1e-300)
    return float(np.max(np.abs(fast.history - slow.history) / scale))


def test_bag_unfold_has_the_same_history_on_both_integrators():
    """The library's bag (also in tests/exchange/engine/test_engine.py's library comparison): its vent is cut from the cavity's
    mesh series and blocked by the bag's own top sheet. The two integrators take the same steps; every column of the
    history agrees to 2.4e-8 of its peak (the vent's flow, where round-off in the error estimate grows while it
    nears equilibrium; 2.5e-10 in pressure), far inside ``ventsim check``'s 1e-6."""
    fast, slow = both_integrators(build_model(load_scene(ROOT / "cases" / "bag_unfold.toml")))
    assert fast.summary["solver"]["steps"] == slow.summary["solver"]["steps"]
    assert largest_difference(fast, slow) < 1e-7
    area = fast.history[:, fast.columns.index("vent.area [m^2]")]
    t = fast.history[:, 0]
    assert np.all(area[t < 0.0058] == 0.0) and np.all(area[t > 0.0059] == 2.0e-4)


def stretching_vent(tmp_path):
    """A 20 mm vent of 6 x 6 quads given as its own series: it stretches in x and y (1 → 1.4 → 1.1) and rises
    1.2 mm for 4 ms into a fixed plate tilted along x, so that its x ≈ 0 columns of nodes touch briefly while the
    faces' areas change."""
    grid_vent(tmp_path / "vent.obj")
    tilted_plate().export(tmp_path / "plate.ply")
    x0 = blockage.LeakageSurface.read(tmp_path / "vent.obj")
    times = np.array([0.0, 0.008, 0.01, 0.012, 0.02, 0.03])
    lift = np.array([0.0, 0.0, 1.2e-3, 0.0, 0.0, 0.0])
    stretch = np.array([1.0, 1.2, 1.4, 1.3, 1.1, 1.1])
    frames = np.stack([x0.vertices * [s, s, 1.0] + [0.0, 0.0, z] for s, z in zip(stretch, lift)])
    np.savez(tmp_path / "vent.npz", times=times, vertices=frames, faces=np.asarray(x0.faces))
    data = tank(pressure=2.0e5)
    data["time"] = {"end": 0.03, "output_interval": 0.00025}
    data["body"] = [{"name": "plate", "mesh": "plate.ply", "axis": [0, 0, -1]}]
    data["exchange"] = [{"name": "vent", "from": "tank", "leakage_surface": "vent.npz", "blocked_by": ["plate"],
                         "contact_tolerance": TOL}]
    return build_model(scene_from_dict(data, tmp_path / "scene.toml")), (times, frames, x0.faces)


def test_a_stretching_vent_series_with_a_brief_contact_has_the_brute_force_area(tmp_path):
    """The compiled path's area at every output time equals the leak area blockage.evaluate finds on the surface
    moved there (its own active nodes, its own face areas): it would differ if the blocked weights or the face
    areas between frames were wrong; and the histories agree on both integrators."""
    model, (times, frames, faces) = stretching_vent(tmp_path)
    track = model.network.areas[0].track
    assert len(track.crossings) >= 4 and 0 < max(track.actives) < len(track.source.initial)  # partly blocked
    assert set(times) <= set(model.network.breakpoints)  # the face areas' kinks are stops
    fast, slow = both_integrators(model)
    assert largest_difference(fast, slow) < 100 * model.options.rtol
    plate = blockage.Blocker(tilted_plate())
    t, area = fast.history[:, 0], fast.history[:, fast.columns.index("vent.area [m^2]")]
    checked = blocked = 0
    for tk, ak in zip(t, area):
        if np.min(np.abs(track.crossings - tk)) < 1e-9:
            continue  # the state at a crossing itself is a right limit, the search's to time
        i = min(max(np.searchsorted(times, tk, side="right") - 1, 0), len(times) - 2)
        w = min((tk - times[i]) / (times[i + 1] - times[i]), 1.0)
        surface = blockage.LeakageSurface((1 - w) * frames[i] + w * frames[i + 1], faces)
        truth = blockage.evaluate(surface, [plate], TOL)
        assert ak == pytest.approx(truth.leak_area, rel=1e-12), tk
        checked += 1
        blocked += truth.obstruction_area > 0.0
    assert checked > 100 and 4 <= blocked < checked


def test_the_smallest_leakage_area_of_a_stretching_vent_is_the_brute_force_minimum(tmp_path):
    """summary.json's minimum leakage area of a vent whose faces change area within each interval: the smallest of
    blockage.evaluate on the surface moved to 3,001 times (and to both sides of each crossing), not the blocked
    interval at the reference face areas (which the stretched faces never have while blocked)."""
    model, (times, frames, faces) = stretching_vent(tmp_path)
    info = run(model).summary["blockage"]["vent"]
    plate = blockage.Blocker(tilted_plate())
    track = model.network.areas[0].track

    def brute(tk):
        i = min(max(np.searchsorted(times, tk, side="right") - 1, 0), len(times) - 2)
        w = min((tk - times[i]) / (times[i + 1] - times[i]), 1.0)
        surface = blockage.LeakageSurface((1 - w) * frames[i] + w * frames[i + 1], faces)
        return blockage.evaluate(surface, [plate], TOL).leak_area

    grid = np.unique(np.concatenate([np.linspace(0.0, 0.03, 3001), track.crossings - 1e-13, track.crossings + 1e-13]))
    truth = min(brute(tk) for tk in grid)
    assert info["minimum leakage area [m^2]"] == pytest.approx(truth, rel=1e-9)
    t_min = info["minimum leakage area time [s]"]
    assert min(brute(t_min + 1e-13), brute(t_min - 1e-13)) == pytest.approx(truth, rel=1e-9)
    reference = track.areas[int(np.argmin(track.areas))]  # the old figure: frame-0 face areas
    assert reference < 0.99 * truth
