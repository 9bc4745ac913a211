"""The ``ventsim`` command: run a scene, check the case library, render pictures.

Exit codes: 0 success; 1 ``ventsim check`` found a case off its reference; 2 a bad scene or command line (one
line on stderr naming the file and the key); 130 interrupted (Ctrl-C).
"""
from __future__ import annotations

import argparse
import logging
import sys
import time
from pathlib import Path

from cases.decks.commands import add_import_parser, add_units_argument
from cases.scene.errors import SceneError

__all__ = ["main", "EXIT_OK", "EXIT_CHECK_FAILED", "EXIT_BAD_INPUT", "EXIT_INTERRUPTED"]

EXIT_OK, EXIT_CHECK_FAILED, EXIT_BAD_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130
log = logging.getLogger("ventsim")


def _configure_logging(args) -> None:
    """Messages of the ``ventsim`` logger on stderr: warnings only with --quiet, timings too with --verbose."""
    level = logging.WARNING if getattr(args, "quiet", False) else (
        logging.DEBUG if getattr(args, "verbose", False) else logging.INFO)
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("ventsim: %(message)s"))
    log.handlers[:] = [handler]
    log.setLevel(level)
    log.propagate = False


def _run(args) -> int:
    from cases.decks.commands import scene_for_run
    from cases.results.output import check_out, output_set, write_results
    from cases.run.runner import RunError, run_scene

    check_out(args.out)  # before the run, not after it
    start = time.process_time()
    scene, deck = scene_for_run(args.scene, args.out, args.units, args.quiet)
    try:
        results = run_scene(scene, progress=not args.quiet, max_wall=args.max_wall, strict=args.strict)
    except RunError as exc:
        if exc.partial is not None:
            with output_set(args.out) as stage:
                _keep_imported(args.out, stage)
                write_results(exc.partial, stage)
            raise RunError(exc.file, f"{str(exc).split(': ', 1)[1]} (wrote what it had into {args.out})") from None
        raise
    if deck is not None:
        results.summary.setdefault("modelled", {})["deck"] = deck.modelled()
    log.debug("built and solved in %.2f s CPU", time.process_time() - start)
    start = time.process_time()
    with output_set(args.out) as stage:
        _keep_imported(args.out, stage)
        paths = write_results(results, stage)
        log.debug("wrote history, summary and plot in %.2f s CPU", time.process_time() - start)
        if getattr(args, "render", False):
            from cases.results.pictures import write_pictures

            start = time.process_time()
            pics = write_pictures(results, stage, times=args.times)
            paths.update({f"{k} {i}": p for k, v in pics.items() for i, p in enumerate(v)})
            log.debug("rendered in %.2f s CPU", time.process_time() - start)
    paths = {k: Path(args.out) / Path(p).relative_to(stage) for k, p in paths.items()}
    for message in results.summary.get("warnings", []):
        print(f"ventsim: warning: {message}", file=sys.stderr)
    if not args.quiet:
        _report(results, paths)
    return EXIT_OK


def _keep_imported(out, stage) -> None:
    """A deck run imported its scene into ``out/scene``: it belongs to the new output set too."""
    import shutil

    if (Path(out) / "scene").is_dir():
        shutil.copytree(Path(out) / "scene", Path(stage) / "scene")


def _report(results, paths) -> None:
    for name, cav in results.summary["cavities"].items():
        print(f"{name}: peak pressure {cav['peak pressure [Pa]']:.6g} Pa at {cav['peak pressure time [s]']:.6g} s")
    for name, c in results.summary.get("contact", {}).items():
        opened = (f", opens at {c['opening pressures [Pa]'][0]:.9g} Pa (preload predicts "
                  f"{c['opening pressure predicted [Pa]']:.9g} Pa)" if "opening pressures [Pa]" in c else "")
        print(f"{name}: {c['lift-offs']} lift-offs, {c['reseats']} reseats, peak CPRESS "
              f"{c['peak CPRESS [Pa]']:.6g} Pa{opened}")
    st = results.summary["solver"]
    print(f"solver {st['method']}: {st['steps']} steps, {st['rhs_calls']} RHS calls, {st['events']} events, "
          f"{st['wall time [s]']:.3f} s")
    print("wrote " + ", ".join(str(p) for p in paths.values()))


def _check(args) -> int:
    from cases.run.library import CASES, check_all, format_table

    unknown = [n for n in args.cases if n not in CASES]
    if unknown:
        from cases.scene.schema import suggest

        raise SceneError("ventsim check", "", f"unknown case {unknown[0]!r}{suggest(unknown[0], CASES)}; "
                                               f"cases: {', '.join(CASES)}")
    checks = check_all(args.cases or None, update=args.update)
    print(format_table(checks))
    return EXIT_OK if all(c.passed for c in checks) else EXIT_CHECK_FAILED


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not (value > 0 and value < float("inf")):
        raise argparse.ArgumentTypeError(f"expected a number of seconds > 0, got {text!r}")
    return value


def parser() -> argparse.ArgumentParser:
    from cases.run.provenance import version

    p = argparse.ArgumentParser(prog="ventsim", description="Gas cavities venting through blockable leakage surfaces.",
                                epilog="exit codes: 0 success, 1 a checked case is off its reference, 2 bad scene or "
                                       "command line, 130 interrupted")
    p.add_argument("--version", action="version", version=f"ventsim {version()}")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run a scene file and write history.csv, summary.json, history.png")
    r.add_argument("scene", type=Path, help="scene TOML file, or an Abaqus .inp / LS-DYNA .k deck")
    r.add_argument("--out", type=Path, default=Path("out"), help="output folder (default: out)")
    r.add_argument("--quiet", action="store_true", help="print nothing but errors and warnings (no progress bar)")
    r.add_argument("--verbose", action="store_true", help="also print the CPU time of each phase")
    r.add_argument("--max-wall", type=_seconds, default=None, metavar="SECONDS",
                   help="stop the integration after this wall time (overrides [limits] wall)")
    r.add_argument("--strict", action="store_true",
                   help="stop with an error when a leakage node's contact intervals cannot all be certified "
                        "(as [blockage] strict = true)")
    r.add_argument("--render", action="store_true",
                   help="also draw each blocked leakage surface off screen: PNGs, a GIF and a VTK series (.pvd)")
    r.add_argument("--times", type=float, nargs="+", default=None,
                   help="times [s] of the PNGs (default: t = 0 and the time of the smallest leakage area)")
    add_units_argument(r)
    r.set_defaults(func=_run)
    c = sub.add_parser("check", help="run the case library and compare with the reference histories")
    c.add_argument("cases", nargs="*", help="case names (default: all)")
    c.add_argument("--update", action="store_true", help="write the reference histories instead of comparing")
    c.set_defaults(func=_check)
    from cases.sweep.parallel import add_sweep_parser
    from cases.run.compare_command import add_compare_parser
    add_sweep_parser(sub)
    add_compare_parser(sub)
    add_import_parser(sub)
    return p


def main(argv=None) -> int:
    """The command; ``argv`` None: the process's own command line (then the process ends right after)."""
    args = parser().parse_args(argv)
    _configure_logging(args)
    program = argv is None
    if program:
        _freeze_heap()  # what the imports so far left (numba's above all) lives to the end
    try:
        return args.func(args)
    except SceneError as exc:
        print(f"ventsim: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("ventsim: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    finally:
        if program:
            _freeze_heap()


def _freeze_heap() -> None:
    """Move every object to the garbage collector's permanent generation (``gc.freeze``): the collections during
    the run and the interpreter's shutdown then no longer traverse the ~200,000 objects numba, scipy and trimesh
    leave (0.08 s of CPU during the main job, 0.3-0.5 s at its exit). Only when ventsim is the program: objects
    made later are collected as usual, the outputs are written and closed before the second call, and atexit
    handlers still run; a Python caller of ``main(argv)`` keeps its collector as it was."""
    import gc

    gc.freeze()


if __name__ == "__main__":
    sys.exit(main())
