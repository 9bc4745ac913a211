"""The case library: every scene with a reference history, and the regression check that compares them.

A case passes when each history column differs from its reference by at most ``RTOL`` times the column's
largest magnitude. The scenes integrate at rtol 1e-8, so a change of machine or library version moves the
histories by far less than 1e-6; a change of physics or numerics moves them by more.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cases.results.output import write_history
from cases.run.runner import run_scene

__all__ = ["CASES", "RTOL", "CaseCheck", "check_case", "check_all", "reference_path"]

HERE = Path(__file__).resolve().parents[1]  # the cases/ folder: the library scenes
#: Regression tolerance: error relative to each column's largest magnitude.
RTOL = 1e-6
CASES = {
    "blowdown_choked": "verification/blowdown_choked.toml",
    "blowdown_isothermal": "verification/blowdown_isothermal.toml",
    "blowdown_subsonic": "verification/blowdown_subsonic.toml",
    "fill_constant": "verification/fill_constant.toml",
    "compression_mesh": "verification/compression_mesh.toml",
    "airbag_vented": "airbag_vented.toml",
    "airbag_impactor": "airbag_impactor.toml",
    "airbag_impactor_dynamic": "airbag_impactor_dynamic.toml",
    "seal_vent": "seal_vent.toml",
    "seal_vent_nodes": "seal_vent_nodes.toml",
    "vent_bar_edge": "vent_bar_edge.toml",
    "bag_unfold": "bag_unfold.toml",
    "relief_valve": "relief_valve.toml",
    "relief_valve_undamped": "relief_valve_undamped.toml",
    "seal_flange": "seal_flange.toml",
    "deck_box_blowdown": "decks/box_blowdown.toml",
    "deck_vented_box_blockage": "decks/vented_box_blockage.toml",
    "deck_hydraulic_two_cavity": "decks/hydraulic_two_cavity.toml",
    "deck_wang_nefske_bag": "decks/wang_nefske_bag.toml",
}
#: cases whose scene is the TOML twin of a deck: the deck is run too and must give the twin's history to TWIN_RTOL
DECK_TWINS = {"deck_box_blowdown": "decks/box_blowdown.inp",
              "deck_vented_box_blockage": "decks/vented_box_blockage.inp",
              "deck_hydraulic_two_cavity": "decks/hydraulic_two_cavity.inp",
              "deck_wang_nefske_bag": "decks/wang_nefske_bag.k"}
TWIN_RTOL = 1e-12


@dataclass
class CaseCheck:
    name: str
    error: float
    worst_column: str
    passed: bool
    wall: float
    message: str = ""
    path: str = ""  # the integrator that ran (summary.json's solver.path)


def reference_path(name: str) -> Path:
    return HERE / "reference" / f"{name}.csv"


def column_errors(columns, history, ref_columns, reference) -> dict:
    """Per column of the reference: max |sim − ref| / max |ref| (inf when the shapes differ or a reference column
    is missing; columns added since the reference was written are not compared)."""
    if set(ref_columns) <= set(columns) and len(history) == len(reference):
        history = history[:, [list(columns).index(c) for c in ref_columns]]
        columns = list(ref_columns)
    if list(columns) != list(ref_columns) or history.shape != reference.shape:
        return {"(shape or columns)": np.inf}
    scale = np.maximum(np.max(np.abs(reference), axis=0), 1e-300)
    err = np.max(np.abs(history - reference), axis=0) / scale
    return dict(zip(columns, err))


def read_reference(path: Path):
    with path.open() as fh:
        header = fh.readline().strip().split(",")
    return header, np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def check_case(name: str, *, update: bool = False) -> CaseCheck:
    """Run case ``name`` and compare it with (or, with ``update``, write) its reference history."""
    start = time.perf_counter()
    results = run_scene(HERE / CASES[name])
    wall = time.perf_counter() - start
    path = results.summary["solver"]["path"]
    ref = reference_path(name)
    if update:
        write_history(ref, results.columns, results.history)
        return CaseCheck(name, 0.0, "", True, wall, "reference written", path)
    if not ref.is_file():
        return CaseCheck(name, np.inf, "", False, wall, f"no reference {ref.name}: run ventsim check --update", path)
    errors = column_errors(results.columns, results.history, *read_reference(ref))
    worst = max(errors, key=errors.get)
    if name in DECK_TWINS:
        twin = _deck_twin_error(name, results)
        if twin > TWIN_RTOL:
            return CaseCheck(name, twin, "(deck vs twin)", False, wall, f"deck differs from its twin by {twin:.2e}",
                             path)
    return CaseCheck(name, float(errors[worst]), worst, errors[worst] <= RTOL, wall, path=path)


def _deck_twin_error(name: str, twin_results) -> float:
    """Largest column error between the deck's run and its TOML twin's."""
    import tempfile

    from cases.decks import deck_scene

    with tempfile.TemporaryDirectory() as tmp:
        scene, _ = deck_scene(HERE / DECK_TWINS[name], Path(tmp) / "scene.toml")
        deck = run_scene(scene)
    errors = column_errors(deck.columns, deck.history, twin_results.columns, twin_results.history)
    return float(max(errors.values()))


def check_all(names=None, *, update: bool = False) -> list:
    return [check_case(n, update=update) for n in (names or CASES)]


def format_table(checks) -> str:
    rows = [f"{'case':<26} {'status':<6} {'max error':>10} {'tolerance':>10} {'wall [s]':>9}  {'path':<9} "
            f"worst column"]
    for c in checks:
        status = "PASS" if c.passed else "FAIL"
        rows.append(f"{c.name:<26} {status:<6} {c.error:>10.2e} {RTOL:>10.0e} {c.wall:>9.3f}  {c.path:<9} "
                    f"{c.worst_column}{(' ' + c.message) if c.message else ''}")
    n_fail = sum(not c.passed for c in checks)
    rows.append(f"{len(checks) - n_fail} passed, {n_fail} failed")
    return "\n".join(rows)
