"""``ventsim compare``: one scene run under several blockage rules, side by side.

Each rule is the scene with its [blockage] table replaced (:mod:`cases.scene.blockage_rule`); ``exact`` is always
run, as the reference. Per rule the table gives the blocked area·time (∫ (A_open − A_leak) dt over the blocked
exchanges, :mod:`cases.run.area_integrals`), its L1 distance to exact (∫ |A_rule − A_exact| dt), the leak mass
(what left the cavities for the ambient), each cavity's peak pressure and its time, and their differences to
exact; with ``[fe_run] abstat`` the FE run's own peak pressure is a row too. A sweep over the step shows how each
rule converges to exact, or to a limit of its own (``docs/fe_rules.md``).
"""
from __future__ import annotations

import copy
import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from blockage.fe_rules import RULES

from cases.run.area_integrals import area_distance, blocked_area_time
from cases.scene.errors import SceneError

__all__ = ["RuleRun", "run_rule", "time_tracks", "rule_row", "comparison", "sweep_rows", "write_rows", "format_table",
           "parse_rules", "parse_steps"]


@dataclass
class RuleRun:
    """A finished run of the scene under ``rule`` with ``step`` [s] (0 for exact) and ``lag`` cycles."""

    rule: str
    step: float
    lag: int
    results: object


def parse_rules(text: str) -> list:
    """The rules of ``--rules a,b,c``, exact first (added when missing); an unknown one is a SceneError.

    >>> parse_rules("radioss,abaqus")
    ['exact', 'radioss', 'abaqus']
    """
    from cases.scene.schema import suggest

    rules = [r.strip() for r in text.split(",") if r.strip()]
    for r in rules:
        if r not in RULES:
            raise SceneError("ventsim compare", "--rules", f"unknown rule {r!r}{suggest(r, RULES)}; rules: "
                                                           f"{', '.join(RULES)}")
    return ["exact"] + [r for r in dict.fromkeys(rules) if r != "exact"]


def parse_steps(text: str, option: str = "--sweep") -> list:
    """The steps [s] of ``--sweep 1e-4,1e-5`` (or ``option``), each > 0, largest first."""
    try:
        steps = [float(s) for s in text.split(",") if s.strip()]
    except ValueError:
        steps = [float("nan")]
    if not steps or not all(s > 0 and np.isfinite(s) for s in steps):
        raise SceneError("ventsim compare", option, f"expected steps [s] > 0 separated by commas, got {text!r}")
    return sorted(set(steps), reverse=True)


def run_rule(path: Path, data: dict, rule: str, step: float | None, lag: int | None = None):
    """:class:`RuleRun` of the scene (TOML dict ``data`` of file ``path``) under ``rule``: its [blockage] table
    keeps its other keys, with ``rule``, ``step`` (the scene's own when None) and ``lag_cycles`` set."""
    from cases.model.build import build_model
    from cases.model.fe_sampling import fe_rule
    from cases.run.runner import run
    from cases.scene.files import scene_from_dict

    data = copy.deepcopy(data)
    table = dict(data.get("blockage", {}))
    table["rule"] = rule
    if rule == "exact":
        table.pop("step", None)
        table.pop("lag_cycles", None)
    else:
        if step is not None:
            table["step"] = step
        if lag is not None:
            table["lag_cycles"] = lag
    data["blockage"] = table
    scene = scene_from_dict(data, path)
    results = run(build_model(scene))
    fe = fe_rule(scene.blockage)
    return RuleRun(rule, fe.step if rule != "exact" else 0.0, fe.lag if rule != "exact" else 0, results)


def time_tracks(results) -> dict:
    """{exchange name: its leakage area as a track of time} of the blocked exchanges of a run: the area track itself
    with prescribed motion, the steps the run took (:func:`cases.run.area_integrals.time_steps`) with a dynamic
    body."""
    from cases.run.area_integrals import time_steps

    geo = results.model.geometry
    if geo is None:
        return {}
    names = [e.name for e in results.model.network.exchanges]
    return {names[j]: ga.track if ga.by_time else time_steps(ga.track, results.trajectory, j)
            for j, ga in enumerate(geo["areas"]) if ga is not None}


def leak_mass(results) -> float:
    """Mass that left the cavities for the ambient over the run [kg] (initial + inflow − final, summed)."""
    return float(sum(c["initial [kg]"] + c["inflow [kg]"] - c["final [kg]"]
                     for c in results.summary["mass balance"].values()))


def rule_row(run: RuleRun, exact: RuleRun | None) -> dict:
    """One row of the table (see the module docstring)."""
    t_end = run.results.model.scene.time.end
    tracks, ref = time_tracks(run.results), time_tracks(exact.results) if exact is not None else {}
    row = {"rule": run.rule, "step [s]": run.step, "lag [cycles]": run.lag,
           "blocked area*time [m^2 s]": sum(blocked_area_time(tr, 0.0, t_end) for tr in tracks.values()),
           "|A - A_exact| area*time [m^2 s]": sum(area_distance(tr, ref[n], 0.0, t_end) for n, tr in tracks.items()
                                                 if n in ref),
           "leak mass [kg]": leak_mass(run.results)}
    for name, cav in run.results.summary["cavities"].items():
        row[f"{name} peak pressure [Pa]"] = cav["peak pressure [Pa]"]
        row[f"{name} peak pressure time [s]"] = cav["peak pressure time [s]"]
    if exact is not None:
        base = rule_row(exact, None)
        for key in ("blocked area*time [m^2 s]", "leak mass [kg]") + tuple(k for k in row if "peak pressure" in k):
            row[f"delta {key}"] = row[key] - base[key]
    return row


def fe_rows(scene, columns) -> list:
    """Rows of the FE run's own peak pressures ([fe_run] abstat), empty when the scene names none."""
    from cases.results.fe_pressure import scene_fe_pressures

    found = scene_fe_pressures(scene)
    if not found:
        return []
    row = {c: "" for c in columns}
    row["rule"] = "FE run (abstat)"
    for name, fe in found.items():
        p, t = fe.peak()
        row[f"{name} peak pressure [Pa]"], row[f"{name} peak pressure time [s]"] = p, t
    return [row]


def comparison(runs: list) -> list:
    """The rows of every run, exact first, each with its differences to exact."""
    exact = next(r for r in runs if r.rule == "exact")
    return [rule_row(r, exact if r is not exact else None) for r in runs]


def sweep_rows(path: Path, data: dict, rules: list, steps: list, exact: RuleRun, lag=None, progress=None) -> list:
    """Per FE rule and step: the distance of its area history, leak mass and peak pressures to exact."""
    rows = []
    for rule in (r for r in rules if r != "exact"):
        for step in steps:
            run = run_rule(path, data, rule, step, lag)
            row = rule_row(run, exact)
            rows.append({k: row[k] for k in row if k in ("rule", "step [s]", "lag [cycles]") or
                         k.startswith(("|A", "delta"))})
            if progress is not None:
                progress(f"sweep {rule} step {step:g} s done")
    return rows


def write_rows(path: Path, rows: list) -> None:
    """Rows (dicts) as CSV with the union of their keys as header, written atomically."""
    from cases.results.output import atomic_path

    columns = list(dict.fromkeys(k for r in rows for k in r))
    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=columns, restval="")
            w.writeheader()
            for r in rows:
                w.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in r.items()})


def format_table(rows: list) -> str:
    """The comparison as a text table: one line per rule, the main figures."""
    keys = [k for k in rows[0] if k in ("rule", "step [s]", "lag [cycles]", "blocked area*time [m^2 s]",
                                        "|A - A_exact| area*time [m^2 s]", "leak mass [kg]")
            or (k.endswith(("peak pressure [Pa]", "peak pressure time [s]")) and not k.startswith("delta"))]
    keys += [k for k in rows[-1] if k.startswith("delta") and k.endswith(("[Pa]", "[kg]"))]
    out = ["  ".join(f"{k:>18.18}" if i else f"{k:<16.16}" for i, k in enumerate(keys))]
    for r in rows:
        cells = []
        for i, k in enumerate(keys):
            v = r.get(k, "")
            text = f"{v:.6g}" if isinstance(v, (float, np.floating)) else str(v)
            cells.append(f"{text:>18.18}" if i else f"{text:<16.16}")
        out.append("  ".join(cells))
    return "\n".join(out)
