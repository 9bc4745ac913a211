"""Parameter sweeps on Dask: ``ventsim sweep`` and :func:`sweep`, its Python equivalent for notebooks.

A sweep runs many variants of one scene, each a set of values written at dotted keys of the scene's TOML data
(:mod:`cases.sweep.design`), on Dask's distributed scheduler: a ``LocalCluster`` of single-threaded worker
processes on this machine, or an existing scheduler (``scheduler="tcp://host:8786"``). Each variant is run by
:func:`run_variant` (scene data in, a record out; a task runs one, or a few when they are many and cheap): it
validates the data with ``scene_from_dict`` against the original scene's path, runs it and writes
``DIR/variants/<id>/`` (``history.csv``, ``summary.json``, and ``row.json`` last, the variant's record and its
"finished" mark). A bad value fails its variant only, with the scene's one-line error. ``DIR/results.csv`` and
``DIR/results.parquet`` (one row per variant: id, status, inputs, summary figures, wall time, error) are
rewritten atomically as records arrive, at most once a second, and at the end; ``DIR/sweep.png`` plots the main
responses against each varied key (:mod:`cases.sweep.plot`).

Running the same sweep again skips the variants that have a ``row.json`` (resumable); ``retry_failed`` re-runs
failed ones. A variant whose worker died (status ``lost``) has no ``row.json`` and is run again.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import logging
import os
import signal
import time
import traceback
import uuid
from dataclasses import dataclass, field
from pathlib import Path

from cases.scene.errors import SceneError
from cases.sweep.folder import DESIGNS, MANIFEST, PLOT, RESULTS_CSV, RESULTS_PARQUET, ROW, write_json

__all__ = ["sweep", "SweepResult", "Plan", "plan_sweep", "run_variant", "run_variants", "batch_size", "figures",
           "dask_client", "add_sweep_parser", "RESULTS_CSV", "RESULTS_PARQUET", "PLOT", "MANIFEST"]



@dataclass(frozen=True)
class Plan:
    """What a sweep will run: the scene (absolute path and parsed data), the varied keys and the variants."""

    scene: Path
    data: dict
    keys: tuple
    steps: dict                          # key -> resolved steps into data
    variants: tuple                      # ((id, {key: value}), ...) in design order

    def scene_data(self, inputs: dict) -> dict:
        """The scene's data with ``inputs`` written in (a copy)."""
        from cases.sweep.design import apply_variant

        return apply_variant(self.data, self.steps, inputs)


def plan_sweep(scene, vary=None, *, design="full", samples=None, seed=0, variants=None) -> Plan:
    """Read the scene, make the design and check every key against the scene, before anything runs."""
    from cases.scene.files import read_scene_data, scene_from_dict
    from cases.sweep.design import make_design, resolve_key, variant_id

    shown = Path(scene)
    data = read_scene_data(shown)
    scene_from_dict(data, shown)  # the scene itself is valid
    rows = make_design(vary, design, samples=samples, seed=seed, variants=variants)
    keys = tuple(dict.fromkeys(k for r in rows for k in r))
    steps = {k: resolve_key(data, k, shown) for k in keys}
    return Plan(shown.resolve(), data, keys, steps, tuple((variant_id(r), r) for r in rows))


# ------------------------------------------------------------------------------------------ one variant (worker)

def figures(results) -> dict:
    """A run's summary figures: per cavity peak pressure, its time and final pressure; per exchange min area."""
    import numpy as np

    out = {}
    for name, cav in results.summary["cavities"].items():
        out[f"{name}.peak_pressure [Pa]"] = cav["peak pressure [Pa]"]
        out[f"{name}.peak_pressure_time [s]"] = cav["peak pressure time [s]"]
        out[f"{name}.final_pressure [Pa]"] = cav["final pressure [Pa]"]
    for c in results.columns:
        if c.endswith(".area [m^2]"):
            name = c[:-len(".area [m^2]")]
            out[f"{name}.min_area [m^2]"] = float(np.min(results.column(f"{name}.area")))
    return out


def run_variant(data: dict, path, out_dir, inputs: dict | None = None, timeout: float | None = None) -> dict:
    """Validate, run and write one variant; return its record (never raises for a bad variant).

    ``timeout`` [s]: the integration's wall-time budget (``max_wall`` of :func:`cases.run.runner.run`); a variant
    that exceeds it is recorded as failed with the time and state where it stopped.

    ``data`` is the scene's TOML data with the variant's values in, ``path`` the original scene file (relative
    table names resolve against it), ``out_dir`` the variant's folder (its name is the variant's id). The record
    is ``{"id", "status": "ok" | "failed", "inputs", "figures", "wall_time [s]", "error"}``; it is also written to
    ``out_dir/row.json``, last.
    """
    from cases.model.build import build_model
    from cases.results.output import remove_temp_files, write_history, write_summary
    from cases.run.runner import run
    from cases.scene.files import scene_from_dict

    out_dir = Path(out_dir)
    record = {"id": out_dir.name, "status": "ok", "inputs": dict(inputs or {}), "figures": {},
              "wall_time [s]": None, "error": ""}
    start = time.perf_counter()
    remove_temp_files(out_dir)  # of a worker killed while writing this variant before
    try:
        results = run(build_model(scene_from_dict(data, path)), max_wall=timeout)
        record["figures"] = figures(results)
        results.summary["variant"] = {"id": record["id"], "inputs": record["inputs"]}
        write_history(out_dir / "history.csv", results.columns, results.history)
        write_summary(out_dir / "summary.json", results.summary)
    except SceneError as exc:
        record.update(status="failed", error=str(exc))
    except Exception as exc:  # a failing variant must not stop the sweep: record it, keep the traceback
        record.update(status="failed", error=f"{type(exc).__name__}: {exc}".splitlines()[0])
        out_dir.mkdir(parents=True, exist_ok=True)
        (out_dir / "error.txt").write_text(traceback.format_exc())
    record["wall_time [s]"] = time.perf_counter() - start
    write_json(out_dir / ROW, record)
    return record


def run_variants(batch: list, path, timeout: float | None = None) -> list:
    """Several variants in one task, ``batch`` = [(data, out_dir, inputs), ...]: for cheap variants, fewer tasks
    to schedule. Each variant is written (and recorded) as it finishes, as with :func:`run_variant`."""
    return [run_variant(data, path, out_dir, inputs, timeout) for data, out_dir, inputs in batch]


# ------------------------------------------------------------------------------------------ running on Dask

@contextlib.contextmanager
def dask_client(scheduler=None, workers=None, n_tasks=1):
    """A Dask client: connected to ``scheduler`` (an address), or to a new LocalCluster of ``workers``
    single-threaded worker processes (default: one per core, at most ``n_tasks``), closed on exit."""
    from dask.distributed import Client, LocalCluster

    if scheduler:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as exc:
            from cases.sweep.design import SweepError

            raise SweepError(f"--scheduler {scheduler}: cannot connect ({exc})") from None
        with client:
            if workers:
                client.wait_for_workers(workers)
            yield client
        return
    n = workers or max(1, min(os.cpu_count() or 1, n_tasks))
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                           silence_logs=logging.ERROR)
    try:
        with Client(cluster) as client:
            yield client
    finally:
        with _quiet("distributed"):
            cluster.close()


@contextlib.contextmanager
def _quiet(name: str):
    """Only critical log records of logger ``name`` (Dask's shutdown chatter after an interrupt)."""
    logger = logging.getLogger(name)
    level = logger.level
    logger.setLevel(logging.CRITICAL)
    try:
        yield
    finally:
        logger.setLevel(level)


def _outcomes(result, batch: list, out: Path) -> list:
    """The records of a finished task (``batch`` = [(id, inputs), ...]), or, if it gave an exception instead
    (its worker died, it was cancelled), each variant's ``row.json`` if it got that far, else a ``lost`` record:
    not the variant's fault, so it has no ``row.json`` and runs again next time."""
    if isinstance(result, list):
        return result
    try:
        message = f"{type(result).__name__}: {result}".splitlines()[0]
    except Exception:  # an exception whose str() fails
        message = type(result).__name__
    records = []
    for vid, inputs in batch:
        try:
            records.append(json.loads((out / "variants" / vid / ROW).read_text()))
        except (OSError, ValueError):
            records.append({"id": vid, "status": "lost", "inputs": inputs, "figures": {}, "wall_time [s]": None,
                            "error": message})
    return records


def batch_size(n_todo: int, n_threads: int) -> int:
    """Variants per task when not given: 1, up to 8 when there are many variants per worker thread (at least
    20 tasks per thread remain, so the last tasks leave little idle time).

    >>> batch_size(12, 2), batch_size(200, 2), batch_size(10_000, 2)
    (1, 5, 8)
    """
    return max(1, min(8, n_todo // (20 * max(1, n_threads))))


@contextlib.contextmanager
def _deferred_interrupt():
    """Ctrl-C as a flag, checked between results: a KeyboardInterrupt raised inside one of Dask's callbacks
    would be swallowed there. A second Ctrl-C raises at once. Untouched if SIGINT is ignored or not the main
    thread's to handle."""
    hits = []
    try:
        previous = signal.getsignal(signal.SIGINT)
        if previous in (signal.SIG_IGN, None):
            raise ValueError
        signal.signal(signal.SIGINT, lambda *_: (hits.append(1), signal.signal(signal.SIGINT, previous)))
    except ValueError:  # signal only works in the main thread
        yield hits
        return
    try:
        yield hits
    finally:
        signal.signal(signal.SIGINT, previous)


def _execute(client, plan: Plan, todo: list, out: Path, table, progress, on_row, batch=None, timeout=None) -> None:
    """Submit the variants as tasks of ``batch`` variants (default :func:`batch_size`); record each as its task
    completes (into ``table``, a ResultsTable); on any interruption cancel the rest."""
    from dask.distributed import as_completed

    from cases.sweep.plot import flat

    k = batch or batch_size(len(todo), sum(client.nthreads().values()))
    chunks = [todo[i:i + k] for i in range(0, len(todo), k)]
    tag = uuid.uuid4().hex[:8]
    futures = client.map(run_variants, [[(plan.scene_data(inputs), str(out / "variants" / vid), inputs)
                                         for vid, inputs in chunk] for chunk in chunks],
                         path=str(plan.scene), timeout=timeout, key=[f"ventsim-variants-{chunk[0][0]}-{tag}" for chunk in chunks])
    pending = dict(zip(futures, chunks))
    done = as_completed(futures, with_results=True)  # results are fetched in the background, as they finish
    try:
        with _deferred_interrupt() as interrupted:
            while pending:
                if interrupted:
                    raise KeyboardInterrupt
                finished = done.next_batch(block=False)
                if not finished:
                    time.sleep(0.02)
                for fut, result in finished:
                    records = _outcomes(result, pending.pop(fut), out)
                    fut.release()
                    for record in records:
                        table.add(record)
                        progress.update(record)
                        if on_row is not None:
                            on_row(flat(record))
    finally:
        if pending:
            client.cancel(list(pending))
        table.flush()


# ------------------------------------------------------------------------------------------ the API

@dataclass
class SweepResult:
    """A finished (or resumed) sweep: its folder, varied keys, rows (this design, design order), counts."""

    out: Path
    keys: tuple
    rows: list
    ran: int                             # variants run by this call
    skipped: int                         # finished before (resumed)
    paths: dict = field(default_factory=dict)

    @property
    def counts(self) -> dict:
        return {s: sum(r["status"] == s for r in self.rows) for s in ("ok", "failed", "lost")}

    @property
    def failed(self) -> list:
        return [r for r in self.rows if r["status"] != "ok"]

    def table(self):
        """The rows as a ``pyarrow.Table`` (``.to_pandas()`` if pandas is installed)."""
        import pyarrow as pa

        from cases.sweep.plot import arrow_column

        cols = list(dict.fromkeys(c for r in self.rows for c in r))
        return pa.table({c: arrow_column([r.get(c) for r in self.rows]) for c in cols})


def sweep(scene, vary=None, *, out, design: str = "full", samples=None, seed: int = 0, variants=None,
          scheduler=None, workers=None, client=None, batch=None, retry_failed: bool = False, plot: bool = True,
          progress: bool = True, on_row=None, timeout: float | None = None) -> SweepResult:
    """Run the variants of ``scene`` on Dask into folder ``out``; skip those finished there before.

    ``vary``: {key: values}, values a list or text as on the command line (``"linspace(1e-4,4e-4,4)"``), combined
    by ``design`` (``"full"`` factorial, ``"list"``: i-th values together, ``"lhs"``: a Latin hypercube of
    ``samples`` points, ``seed``); or ``variants``: a CSV file (a header of keys) or a list of {key: value}.
    ``scheduler``: an address to connect to; otherwise a LocalCluster of ``workers`` processes. ``client``: an
    existing ``dask.distributed.Client`` to use (left open). ``batch``: variants per task (default: see
    :func:`batch_size`). ``on_row(row)`` is called with each new flat row. ``timeout`` [s]: each variant's
    integration wall-time budget (a variant over it fails). One sweep at a time writes a folder (a lock file,
    ``.sweep.lock``, held while it runs: a second one fails at once).
    """
    from cases.sweep.folder import check_manifest, folder_lock

    plan = plan_sweep(scene, vary, design=design, samples=samples, seed=seed, variants=variants)
    out = Path(out).resolve()
    with folder_lock(out):
        check_manifest(out, plan)
        return _sweep_locked(plan, out, scheduler, workers, client, batch, retry_failed, plot, progress, on_row,
                             timeout)


def _sweep_locked(plan, out, scheduler, workers, client, batch, retry_failed, plot, progress, on_row, timeout):
    from cases.sweep.plot import Progress, ResultsTable, flat, load_records, plot_sweep

    before = load_records(out)
    todo = [(vid, inputs) for vid, inputs in plan.variants
            if vid not in before or (retry_failed and before[vid]["status"] != "ok")]
    table = ResultsTable(out, plan.keys, [vid for vid, _ in plan.variants], before)
    bar = Progress(len(plan.variants), len(plan.variants) - len(todo), enabled=progress)
    try:
        if todo:
            with contextlib.nullcontext(client) if client is not None else \
                    dask_client(scheduler, workers, len(todo)) as c:
                _execute(c, plan, todo, out, table, bar, on_row, batch, timeout)
    finally:
        bar.close()
    paths = table.flush()
    rows = [flat(r) for r in table.ordered([vid for vid, _ in plan.variants])]
    if plot:
        png = plot_sweep(out / PLOT, rows, plan.keys, str(plan.data.get("title", "")))
        paths.update({"plot": png} if png else {})
    return SweepResult(out, plan.keys, rows, len(todo), len(plan.variants) - len(todo), paths)


# ------------------------------------------------------------------------------------------ the command

def add_sweep_parser(sub) -> argparse.ArgumentParser:
    """Register ``ventsim sweep`` on the subparsers ``sub`` of the ``ventsim`` command."""
    s = sub.add_parser("sweep", help="run variants of a scene on Dask (full factorial, list, Latin hypercube, "
                                     "CSV) into results.csv/.parquet, resumable",
                       description="Run many variants of a scene on Dask's distributed scheduler. See "
                                   "docs/sweeps.md.")
    s.add_argument("scene", type=Path, help="scene TOML file")
    s.add_argument("--vary", action="append", default=[], metavar="KEY=VALUES",
                   help="a dotted key and its values: exchange.vent.area=1e-4,2e-4 or time.end=linspace(0.05,0.1,6)"
                        " (lhs: lo:hi); repeat for more keys")
    s.add_argument("--variants", type=Path, metavar="CSV", help="variants from a CSV file (a header of keys)")
    s.add_argument("--design", choices=DESIGNS, default="full",
                   help="combine the --vary values: full factorial (default), list (i-th together), lhs")
    s.add_argument("--samples", type=int, help="lhs: number of variants")
    s.add_argument("--seed", type=int, default=0, help="lhs: random seed (default 0)")
    s.add_argument("--out", type=Path, required=True, help="sweep folder (re-use it to resume)")
    s.add_argument("--scheduler", metavar="ADDRESS", help="connect to this Dask scheduler instead of starting a "
                                                          "LocalCluster")
    s.add_argument("--workers", type=int, help="LocalCluster worker processes (default: one per core); with "
                                               "--scheduler: wait for this many workers")
    s.add_argument("--batch", type=int, metavar="N", help="variants per Dask task (default: 1, more when there "
                                                          "are many cheap variants per worker)")
    s.add_argument("--retry-failed", action="store_true", help="run failed variants again")
    s.add_argument("--variant-timeout", type=float, metavar="SECONDS",
                   help="wall-time budget of each variant's integration; a variant over it is recorded as failed")
    s.add_argument("--no-plot", action="store_true", help="do not write sweep.png")
    s.add_argument("--quiet", action="store_true", help="print nothing but errors")
    s.set_defaults(func=_cli)
    return s


def _cli(args) -> int:
    from cases.sweep.design import SweepError, parse_vary

    for name in ("workers", "batch"):
        if getattr(args, name) is not None and getattr(args, name) < 1:
            raise SweepError(f"--{name} {getattr(args, name)}: expected a number >= 1")
    if args.variant_timeout is not None and not 0 < args.variant_timeout < float("inf"):
        raise SweepError(f"--variant-timeout {args.variant_timeout}: expected a number of seconds > 0")
    res = sweep(args.scene, parse_vary(args.vary), out=args.out, design=args.design, samples=args.samples,
                seed=args.seed, variants=args.variants, scheduler=args.scheduler, workers=args.workers,
                batch=args.batch, retry_failed=args.retry_failed, plot=not args.no_plot, progress=not args.quiet,
                timeout=args.variant_timeout)
    n = res.counts
    if not args.quiet:
        lost = f", {n['lost']} lost (run again to retry)" if n["lost"] else ""
        print(f"{len(res.rows)} variants: {n['ok']} ok, {n['failed']} failed{lost} "
              f"({res.ran} run now, {res.skipped} finished before)")
        for r in res.failed[:5]:
            print(f"  {r['status']} {r['id']} ({', '.join(f'{k}={r.get(k)}' for k in res.keys)}): {r['error']}")
        print("wrote " + ", ".join(str(p) for p in res.paths.values()))
    return 0 if n["ok"] == len(res.rows) else 1
