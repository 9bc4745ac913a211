"""The ``ventsim compare`` command line: run a scene under several blockage rules and write the comparison.

``ventsim compare SCENE.toml --rules exact,abaqus,radioss [--step 1e-6] [--lag N] [--sweep 1e-4,1e-5,1e-6]
--out DIR`` writes ``DIR/compare.csv`` (printed too), ``DIR/compare.png`` (the histories overlaid),
``DIR/faces_<exchange>_<rule>.png`` (per-face blocked fraction minus exact's where the areas differ most) and, with
``--sweep``, ``DIR/sweep.csv`` and ``DIR/sweep.png`` (each rule's distance to exact against the step).
"""
from __future__ import annotations

import logging
from pathlib import Path

__all__ = ["add_compare_parser", "compare"]

log = logging.getLogger("ventsim")


def compare(scene_path, rules: list, out, *, step=None, lag=None, sweep=(), say=None) -> dict:
    """Run and write everything (module docstring); returns {"rows", "sweep", "paths"}."""
    from cases.results.compare_plots import plot_face_difference, plot_histories, plot_sweep, worst_instant
    from cases.results.fe_pressure import scene_fe_pressures
    from cases.results.output import output_set
    from cases.run.compare import comparison, fe_rows, time_tracks, format_table, run_rule, sweep_rows, write_rows
    from cases.scene.errors import SceneError
    from cases.scene.files import load_scene, read_scene_data

    scene_path = Path(scene_path)
    base = load_scene(scene_path)  # every problem of the scene itself first, as `ventsim run` reports it
    if step is None and not base.blockage.step and any(r != "exact" for r in rules):
        raise SceneError(scene_path, "blockage.step", "the FE rules need the explicit time step: give --step or "
                                                     "[blockage] step")
    data = read_scene_data(scene_path)
    say = say or (lambda text: None)
    runs = []
    for rule in rules:
        runs.append(run_rule(scene_path, data, rule, None if rule == "exact" else step, lag))
        say(f"{rule}: done")
    rows = comparison(runs)
    rows += fe_rows(base, list(rows[0]))
    swept = sweep_rows(scene_path, data, rules, list(sweep), runs[0], lag, say) if sweep else []
    paths = {}
    with output_set(Path(out)) as stage:
        stage = Path(stage)
        write_rows(stage / "compare.csv", rows)
        plot_histories(stage / "compare.png", runs, scene_fe_pressures(base))
        paths.update(table=stage / "compare.csv", plot=stage / "compare.png")
        exact = runs[0]
        for run in runs[1:]:
            tracks = exact.results.model.network.areas
            for j, ga in enumerate(tracks):
                if ga is None:
                    continue
                name = exact.results.model.network.exchanges[j].name
                t, _ = worst_instant(time_tracks(run.results)[name], time_tracks(exact.results)[name],
                                     base.time.end)
                picture = stage / f"faces_{name}_{run.rule}.png"
                plot_face_difference(picture, run, exact, j, t)
                paths[f"faces {name} {run.rule}"] = picture
        if swept:
            write_rows(stage / "sweep.csv", swept)
            plot_sweep(stage / "sweep.png", swept)
            paths.update(sweep=stage / "sweep.csv", sweep_plot=stage / "sweep.png")
        paths = {k: Path(out) / Path(p).relative_to(stage) for k, p in paths.items()}
    print(format_table(rows))
    if swept:
        print(format_table(swept))
    return {"rows": rows, "sweep": swept, "paths": paths}


def _command(args) -> int:
    from cases.run.compare import parse_rules, parse_steps

    rules = parse_rules(args.rules)
    sweep = parse_steps(args.sweep) if args.sweep else ()
    step = parse_steps(args.step, "--step")[0] if args.step is not None else None
    done = compare(args.scene, rules, args.out, step=step, lag=args.lag, sweep=sweep,
                   say=None if args.quiet else log.info)
    if not args.quiet:
        print("wrote " + ", ".join(str(p) for p in done["paths"].values()))
    return 0


def add_compare_parser(sub) -> None:
    c = sub.add_parser("compare", help="run a scene under several blockage rules (exact, abaqus, radioss, "
                                       "lsdyna_cpm, lsdyna_cpg) and compare them")
    c.add_argument("scene", type=Path, help="scene TOML file (with prescribed motion)")
    c.add_argument("--rules", default="exact,abaqus,radioss,lsdyna_cpm,lsdyna_cpg",
                   help="rules separated by commas (exact is always run: the reference)")
    c.add_argument("--step", default=None, metavar="SECONDS",
                   help="the FE rules' explicit time step (default: the scene's [blockage] step)")
    c.add_argument("--lag", type=int, default=None, metavar="CYCLES",
                   help="cycles between the flags and their use (default: each rule's own, radioss 1)")
    c.add_argument("--sweep", default="", metavar="STEPS",
                   help="steps [s] separated by commas: each FE rule's distance to exact against the step")
    c.add_argument("--out", type=Path, default=Path("compare"), help="output folder (default: compare)")
    c.add_argument("--quiet", action="store_true", help="print nothing but the table and errors")
    c.set_defaults(func=_command)
