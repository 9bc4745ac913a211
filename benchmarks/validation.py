"""Vessel discharge and filling experiments: ventsim (real gas, vessel walls) and HydDown against the measurements.

Cases (cases/validation/, set-ups and measurements as collected by HydDown, MIT, cases/validation/LICENSE.HydDown):
N2 150 bar discharge (Haque et al. 1992, I1; p, gas T top and bottom, wall T inner and outer), air 7.9 bar
discharge (p, mean gas T), air filling from 3.7 kPa (no measured history), H2 100 bar discharge and filling
(Woodfield et al.; p, gas T high and low; the filling also at its measured mass flow), H2 138 bar discharges
(Byrnes et al. runs 7 and 8; p, mean gas and wall T), He 700 bar from a Type IV tank (KIT; p, mean gas T), H2
700 bar from a Type IV tank at a prescribed flow (GasTeF; gas T low, mean, high, outer wall T), methane/ethane
120 bar (Haque et al.; p, mean gas T, inner wall T), H2 filling of a Type III tank (Dicken and Mérida; no
measured history in the collection), H2 fillings of a steel tank from 50 to 240 bar at 5, 10 and 30 MPa/min
(Striednig et al.; mean gas T; the flow closed at 240 bar) and the air filling from 3.7 kPa at 295 K (p, upper gas
probe).

For each: ventsim's error against the measurement (pressure [bar] and gas temperature [K], RMS and max over the
measured points, the model interpolated linearly onto them; the gas temperature against the mean of its probes;
the wall against the mean of its probes, compared with the model's lumped wall, inner or outer layer as the probe
sits), the extreme gas temperature (the minimum of a discharge, the maximum of a filling) computed and measured
(probe mean, and the extreme probe), and CPU and wall times: ventsim build + run (best of 10 or more over at
least 3 s, CoolProp's fluid loaded once beforehand; the compiled engine, CoolProp's calls hosted) and HydDown's
HydDown(setup) + run() (best of 5, in its own interpreter); on a shared machine the CPU times are the steadier
figure. HydDown runs when an
interpreter that imports it is found (HYDDOWN_PYTHON, /work/venv-hyddown/bin/python, or this one); its rows are
skipped otherwise. Plots of measured against computed p and T (and wall T) go to OUT/validation.png (default
out/benchmarks).

Requires: numpy, matplotlib; HydDown optional (a separate venv: python3 -m venv /work/venv-hyddown &&
/work/venv-hyddown/bin/pip install hyddown).

Usage::

    python benchmarks/validation.py [--out DIR] [--only WORD ...]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from cases.model.build import build_model  # noqa: E402
from cases.run.runner import run  # noqa: E402
from cases.scene.files import load_scene  # noqa: E402

HERE = ROOT / "cases" / "validation"


class Case(NamedTuple):
    """A validation scene, its HydDown set-up, the stem of its measured CSVs (None: no measurement), its gas and
    wall probes, and the model's wall column the wall probes are compared with."""

    scene: str
    setup: str
    stem: str | None
    gas: tuple = ()
    wall: tuple = ()
    wall_column: str = "wall_temperature"

    @property
    def hyddown_wall(self) -> str:
        """HydDown's wall history compared with the probes: the surface the probe sits on (its inner or outer
        wall, as the model's column), else its mean wall."""
        if self.wall_column == "outer_wall_temperature":
            return "T_wall_outer"
        return "T_wall_inner" if self.wall == ("wall_inner",) else "T_wall"


CASES = (Case("n2_150bar_discharge", "N2_Exp_I1.yml", "n2_150bar", ("gas_high", "gas_low"), ("wall_inner", "wall_outer")),
         Case("air_790kPa_discharge", "Air_790kPa_21mm.yml", "air_790kPa", ("gas_mean",)),
         Case("air_3_7kPa_filling", "Air_3-7kPa_21mm.yml", None),
         Case("h2_100bar_discharge", "dischargeH2_woodfield.yml", "h2_100bar", ("gas_high", "gas_low")),
         Case("h2_100bar_filling", "fillingH2_woodfield.yml", "h2_100bar_filling", ("gas_high", "gas_low")),
         Case("h2_100bar_filling_measured_flow", "", "h2_100bar_filling", ("gas_high", "gas_low")),
         Case("h2_138bar_discharge_run7", "Byrnes_run7.yml", "h2_138bar_run7", ("gas_mean",), ("wall_mean",)),
         Case("h2_138bar_discharge_run8", "Byrnes_run8.yml", "h2_138bar_run8", ("gas_mean",), ("wall_mean",)),
         Case("he_700bar_typeIV_discharge", "kit_composite.yml", "he_700bar", ("gas_mean",)),
         Case("h2_700bar_typeIV_discharge", "demiguel.yml", "h2_700bar", ("gas_mean",), ("wall_outer",),
              "outer_wall_temperature"),
         Case("ng_120bar_discharge", "NG_Exp.yml", "ng_120bar", ("gas_mean",), ("wall_inner",)),
         Case("h2_typeIII_filling", "dickens_typeIII.yml", None),
         *(Case(f"h2_striednig_{rate}MPa_min_filling", f"Striednig_fillingH2_{rate}MPa_min.yml",
                f"h2_striednig_{rate}MPa_min", ("gas_mean",)) for rate in (5, 10, 30)),
         Case("air_3_7kPa_filling_271mm", "Air_3-7kPa_271mm.yml", "air_3_7kPa_271mm", ("gas_high",)))


def _csv(name: str) -> tuple:
    t, v = np.loadtxt(HERE / "data" / f"{name}.csv", delimiter=",", skiprows=1).T
    return t, v


def _probe_mean(stem: str, probes: tuple) -> tuple | None:
    """The mean of the probes' histories on the first probe's times (or None without probes)."""
    if not probes:
        return None
    t, v = _csv(f"{stem}_{probes[0]}")
    return t, np.mean([v] + [np.interp(t, *_csv(f"{stem}_{p}")) for p in probes[1:]], axis=0)


def measured(case: Case) -> dict:
    if case.stem is None:
        return {}
    out = {"T": _probe_mean(case.stem, case.gas), "T_wall": _probe_mean(case.stem, case.wall)}
    if (HERE / "data" / f"{case.stem}_pressure.csv").exists():
        t, p = _csv(f"{case.stem}_pressure")
        out["p"] = (t, p * 1e5)
    out["T probes"] = {name: _csv(f"{case.stem}_{name}") for name in case.gas}
    return {k: v for k, v in out.items() if v is not None}


def run_ventsim(case: Case, repeats: int = 10, span: float = 3.0) -> dict:
    """ventsim's run of ``case``: the best of ``repeats`` runs or more, repeated over at least ``span`` seconds (a
    run takes 20-200 ms: ten in a row can all fall in one busy spell of a shared machine, which HydDown's five
    runs of 0.2-20 s each outlast)."""
    path = HERE / f"{case.scene}.toml"
    build_model(load_scene(path))  # loads CoolProp's fluid and fits the species once
    wall = cpu = float("inf")
    until, k = time.perf_counter() + span, 0
    while k < repeats or (time.perf_counter() < until and k < 50 * repeats):
        k += 1
        start, start_cpu = time.perf_counter(), time.process_time()
        r = run(build_model(load_scene(path)))
        wall, cpu = min(wall, time.perf_counter() - start), min(cpu, time.process_time() - start_cpu)
    return {"time": r.column("time"), "p": r.column("vessel.pressure"), "T": r.column("vessel.temperature"),
            "T_wall": r.column(f"vessel.{case.wall_column}"), "wall time [s]": wall, "cpu time [s]": cpu,
            "rhs": r.summary["solver"]["rhs_calls"], "path": r.summary["solver"]["path"]}


def hyddown_python() -> str | None:
    for exe in (os.environ.get("HYDDOWN_PYTHON"), "/work/venv-hyddown/bin/python", sys.executable):
        if exe and Path(exe).exists() and subprocess.run([exe, "-c", "import hyddown"],
                                                         capture_output=True).returncode == 0:
            return exe
    return None


def run_hyddown(exe: str, setup: str) -> dict | None:
    """HydDown's run of ``setup`` (best of 5), or None with its last error line printed when it refuses the set-up
    (HydDown 0.50's input check rejects keys of other versions, e.g. ``calculation.eta``)."""
    done = subprocess.run([exe, str(ROOT / "benchmarks" / "_hyddown_run.py"), str(HERE / "hyddown" / setup), "5"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        print(f"| {setup} | HydDown failed: {(done.stderr.strip().splitlines() or ['?'])[-1]} |")
        return None
    d = json.loads(done.stdout.strip().splitlines()[-1])
    return {k: np.asarray(v) if isinstance(v, list) else v for k, v in d.items()}


def errors(model: dict, meas: tuple, key: str, scale: float = 1.0) -> tuple:
    """(RMS, max |error|) of model[key] interpolated onto the measured points, divided by ``scale``."""
    t, v = meas
    e = (np.interp(t, model["time"], model[key]) - v) / scale
    return float(np.sqrt(np.mean(e ** 2))), float(np.max(np.abs(e)))


def extremes(model: dict, meas: dict) -> tuple:
    """(computed, measured probe mean, measured extreme probe) of the gas temperature: minima of a discharge (the
    model cools further below its start than it warms above it), maxima of a filling (HydDown's filling dips
    a few mK below its start in the first steps)."""
    T = model["T"]
    cools = T[0] - np.min(T) > np.max(T) - T[0]
    pick = np.min if cools else np.max
    if "T" not in meas:
        return float(pick(T)), np.nan, np.nan
    probes = [v for _, v in meas["T probes"].values()]
    return float(pick(T)), float(pick(meas["T"][1])), float(pick([pick(v) for v in probes]))


def rows_of(name: str, label: str, model: dict, meas: dict) -> str:
    p = errors(model, meas["p"], "p", 1e5) if "p" in meas else (np.nan, np.nan)
    T = errors(model, meas["T"], "T") if "T" in meas else (np.nan, np.nan)
    T_model, T_mean, T_probe = extremes(model, meas)
    wall = errors(model, meas["T_wall"], "T_wall") if "T_wall" in meas else (np.nan, np.nan)
    return (f"| {name} | {label} | {p[0]:.3f} | {p[1]:.3f} | {T[0]:.2f} | {T[1]:.2f} | {T_model:.2f} | "
            f"{T_mean:.2f}; {T_probe:.2f} | {wall[0]:.2f} | {model['cpu time [s]']:.3f} | "
            f"{model['wall time [s]']:.3f} |")


def plot(results: list, out: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cols = min(len(results), 6)
    rows = -(-len(results) // cols)
    fig, axes = plt.subplots(2 * rows, cols, figsize=(4.5 * cols, 6.5 * rows), squeeze=False)
    for k, (name, meas, ours, theirs) in enumerate(results):
        ax_p, ax_T = axes[2 * (k // cols), k % cols], axes[2 * (k // cols) + 1, k % cols]
        for model, style, who in ((ours, "-", "ventsim"), (theirs, "--", "HydDown")):
            if model is None:
                continue
            ax_p.plot(model["time"], model["p"] / 1e5, style, label=who)
            ax_T.plot(model["time"], model["T"], style, label=f"{who} gas")
            ax_T.plot(model["time"], model["T_wall"], style, label=f"{who} wall", alpha=0.6)
        if "p" in meas:
            ax_p.plot(meas["p"][0], meas["p"][1] / 1e5, "ko", ms=4, label="measured")
        for probe, (t, v) in meas.get("T probes", {}).items():
            ax_T.plot(t, v, "o", ms=4, mfc="none", label=f"measured {probe}")
        if "T_wall" in meas:
            ax_T.plot(*meas["T_wall"], "ks", ms=3, label="measured wall (mean)")
        ax_p.set_title(name, fontsize=8)
        ax_p.set(ylabel="pressure [bar]")
        ax_T.set(xlabel="time [s]", ylabel="temperature [K]")
        ax_p.legend(fontsize=7)
        ax_T.legend(fontsize=7)
    fig.tight_layout()
    path = out / "validation.png"
    fig.savefig(path, dpi=90)
    return path


def main(argv=None) -> int:
    args = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    args.add_argument("--out", default=str(ROOT / "out" / "benchmarks"))
    args.add_argument("--only", nargs="*", default=(), help="run only the cases whose scene name contains one of these")
    parsed = args.parse_args(argv)
    out = Path(parsed.out)
    out.mkdir(parents=True, exist_ok=True)
    print(__doc__.split("\n")[0])
    exe = hyddown_python()
    print(f"HydDown: {exe or 'not found (its rows are skipped)'}\n")
    print("| case | code | p RMS [bar] | p max [bar] | T RMS [K] | T max [K] | T min (max) computed [K] | "
          "T min (max) measured [K]: probe mean; extreme probe | wall T RMS [K] | CPU time [s] | wall time [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    results, speed = [], []
    for case in [c for c in CASES if not parsed.only or any(word in c.scene for word in parsed.only)]:
        meas = measured(case)
        ours = run_ventsim(case)
        print(rows_of(case.scene, f"ventsim ({ours['rhs']} RHS, {ours['path']})", ours, meas), flush=True)
        theirs = run_hyddown(exe, case.setup) if exe and case.setup else None
        if theirs is not None:
            theirs["T_wall"] = theirs[case.hyddown_wall]
            print(rows_of(case.scene, "HydDown", theirs, meas))
            dev = np.max(np.abs(np.interp(theirs["time"], ours["time"], ours["p"]) - theirs["p"])) / 1e5
            speed.append((case.scene, theirs["cpu time [s]"] / ours["cpu time [s]"],
                          theirs["wall time [s]"] / ours["wall time [s]"], dev))
        results.append((case.scene, meas, ours, theirs))
    for scene, cpu, wall, dev in speed:
        print(f"\n{scene}: HydDown / ventsim CPU time {cpu:.1f}x, wall time {wall:.1f}x; largest "
              f"|p_ventsim - p_HydDown| {dev:.3f} bar", end="")
    print(f"\n\nplot: {plot(results, out)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
