"""The sweep's outputs: its records (``variants/<id>/row.json``), ``results.csv`` and ``results.parquet`` (one
row per variant), the progress line, and ``sweep.png``, each main response (peak pressure, min leakage area)
against each varied key.

In the picture, one panel per (response, key): every finished variant as a dot, and when a key takes few distinct
values the mean response at each value as a line (the key's main effect over the others). Failed variants are
left out.
"""
from __future__ import annotations

import csv
import json
import math
import time
from pathlib import Path

import numpy as np

from cavity.progress import ProgressBar

from cases.results.output import atomic_path
from cases.sweep.folder import RESULTS_CSV, RESULTS_PARQUET, ROW

__all__ = ["flat", "arrow_column", "write_table", "ResultsTable", "load_records", "Progress", "responses",
           "plot_sweep", "sweep_figure", "sweep_title"]


# ------------------------------------------------------------------------------------------ records and tables

def flat(record: dict) -> dict:
    """A record as one flat row: id, status, the inputs by key, the figures, wall time, error."""
    return {"id": record["id"], "status": record["status"], **record["inputs"], **record["figures"],
            "wall_time [s]": record["wall_time [s]"], "error": record["error"]}


def _columns(records: list, keys) -> list:
    inputs = dict.fromkeys(list(keys) + [k for r in records for k in r["inputs"]])
    figs = dict.fromkeys(k for r in records for k in r["figures"])
    return ["id", "status", *inputs, *figs, "wall_time [s]", "error"]


def arrow_column(values: list):
    """A pyarrow array: float64 for numbers, bool for booleans, otherwise strings; None is null."""
    import pyarrow as pa

    given = [v for v in values if v is not None]
    if given and all(isinstance(v, bool) for v in given):
        return pa.array(values, pa.bool_())
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in given):
        return pa.array([None if v is None else float(v) for v in values], pa.float64())
    return pa.array([None if v is None else str(v) for v in values], pa.string())


def write_table(out: Path, records: list, keys, *, parquet: bool = True) -> dict:
    """``results.csv`` (floats in full precision) and (with ``parquet``) ``results.parquet`` of ``records``, each
    atomically."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    cols = _columns(records, keys)
    rows = [flat(r) for r in records]
    paths = {"results": Path(out) / RESULTS_CSV, "parquet": Path(out) / RESULTS_PARQUET}
    with atomic_path(paths["results"]) as tmp, tmp.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols)
        w.writerows([["" if r.get(c) is None else r.get(c) for c in cols] for r in rows])
    if not parquet:
        return {"results": paths["results"]}
    table = pa.table({c: arrow_column([r.get(c) for r in rows]) for c in cols})
    with atomic_path(paths["parquet"]) as tmp:
        pq.write_table(table, tmp)
    return paths


class ResultsTable:
    """The sweep folder's records (by id); rewrites results.csv after every record (a killed sweep leaves it
    current) and results.parquet at most every ``every`` seconds."""

    def __init__(self, out: Path, keys, order: list, records: dict, every: float = 1.0):
        self.out, self.keys, self.records, self.every = out, keys, dict(records), every
        self.rank = {vid: i for i, vid in enumerate(order)}
        self.last, self.dirty = -math.inf, True

    def ordered(self, ids=None) -> list:
        """Records in design order (then any older ones, by id); only ``ids`` if given."""
        chosen = self.records if ids is None else [i for i in ids if i in self.records]
        return [self.records[i] for i in sorted(chosen, key=lambda i: (self.rank.get(i, math.inf), i))]

    def add(self, record: dict) -> None:
        self.records[record["id"]] = record
        self.dirty = True
        if time.monotonic() - self.last >= self.every:
            self.flush()
        else:
            write_table(self.out, self.ordered(), self.keys, parquet=False)

    def flush(self) -> dict:
        """Rewrite the result files if anything changed; a large table is rewritten less often (at most 5% of
        the time is spent writing it)."""
        paths = {"results": self.out / RESULTS_CSV, "parquet": self.out / RESULTS_PARQUET}
        if self.dirty or not all(p.is_file() for p in paths.values()):
            start = time.monotonic()
            paths = write_table(self.out, self.ordered(), self.keys)
            self.last, self.dirty = time.monotonic(), False
            self.every = max(self.every, 20.0 * (self.last - start))
        return paths


def load_records(out: Path) -> dict:
    """The finished variants of a sweep folder: every ``variants/<id>/row.json`` (status ok or failed)."""
    records = {}
    for p in sorted((out / "variants").glob(f"*/{ROW}")):
        try:
            r = json.loads(p.read_text())
        except (OSError, ValueError):
            continue  # damaged: run it again
        if isinstance(r, dict) and r.get("status") in ("ok", "failed") and r.get("id") == p.parent.name:
            records[r["id"]] = r
    return records


# ------------------------------------------------------------------------------------------ progress

class Progress:
    """The sweep's progress bar (:class:`cavity.progress.ProgressBar` over the variants: done, failed, finished
    before), shown only on a terminal."""

    def __init__(self, total: int, before: int, enabled: bool = True, stream=None):
        self.done = self.failed = 0
        self.bar = ProgressBar(total, desc="sweep", unit="variant", enabled=enabled, delay=0.0, stream=stream,
                               initial=before, integer=True)

    def update(self, record: dict) -> None:
        self.done += 1
        self.failed += record["status"] != "ok"
        self.bar.advance(1, postfix=f"{self.failed} failed" if self.failed else None)

    def close(self) -> None:
        self.bar.close()


# ------------------------------------------------------------------------------------------ the picture

#: (column suffix, axis label suffix, factor from SI)
RESPONSES = (("peak_pressure [Pa]", "peak pressure [kPa]", 1e-3), ("min_area [m^2]", "min area [mm²]", 1e6))
MAX_PANELS = 8  # keys, and responses, drawn at most


def responses(rows: list) -> list:
    """The response columns present in ``rows``: every cavity's peak pressure, then every exchange's min area."""
    out = []
    for suffix, _, _ in RESPONSES:
        for r in rows:
            out += [c for c in r if c.endswith("." + suffix) and c not in out]
    return out


def _positions(values: list) -> tuple:
    """x positions of ``values``: numbers as they are, anything else as categories 0, 1, ... (with labels)."""
    if all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in values):
        return np.array([math.nan if v is None else float(v) for v in values]), None
    labels = list(dict.fromkeys(str(v) for v in values if v is not None))
    return np.array([math.nan if v is None else labels.index(str(v)) for v in values], float), labels


def _panel(ax, x, y, labels) -> None:
    from matplotlib.ticker import MaxNLocator

    ok = np.isfinite(x) & np.isfinite(y)
    ax.plot(x[ok], y[ok], "o", ms=3.5, alpha=0.6, color="C0")
    levels = np.unique(x[ok])
    if 1 < len(levels) <= 25:
        ax.plot(levels, [y[ok][x[ok] == v].mean() for v in levels], "-", color="C1", lw=1.5, label="mean")
    if labels is not None:
        ax.set_xticks(range(len(labels)), labels, rotation=30, fontsize=8)
    else:
        ax.xaxis.set_major_locator(MaxNLocator(5))
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-3, 4), useOffset=False)
    ax.tick_params(labelsize=8)
    ax.grid(True, alpha=0.3)


def sweep_title(title: str, n_ok: int, width_inches: float, fontsize: float = 10.0) -> str:
    """The figure's title: ``title`` wrapped to lines that fit ``width_inches`` (a character of the default sans font
    is at most ~0.6 em wide), then the number of variants.

    >>> sweep_title("peak pressure of the cushion against the vent's discharge coefficient", 12, 2.0).splitlines()
    ['peak pressure of the', 'cushion against the', "vent's discharge", 'coefficient', '12 variants']
    """
    import textwrap

    columns = max(int(width_inches * 72.0 / (0.6 * fontsize)), 10)
    lines = textwrap.wrap(title, columns, break_long_words=True) if title else []
    return "\n".join(lines + [f"{n_ok} variants"])


def sweep_figure(rows: list, keys, title: str = ""):
    """The response-against-key grid of ``rows`` (flat result rows) as a matplotlib Figure; None if nothing to draw.
    Constrained layout keeps the (wrapped) title, labels and ticks inside the figure."""
    ok = [r for r in rows if r.get("status") == "ok"]
    resp = responses(ok)[:MAX_PANELS]
    keys = list(keys)[:MAX_PANELS]
    if not ok or not resp or not keys:
        return None
    from matplotlib.figure import Figure

    fig = Figure(figsize=(3.4 * len(keys) + 0.8, 2.5 * len(resp) + 0.8), layout="constrained")
    axes = fig.subplots(len(resp), len(keys), squeeze=False, sharex="col", sharey="row")
    for j, key in enumerate(keys):
        x, labels = _positions([r.get(key) for r in ok])
        for i, col in enumerate(resp):
            suffix, label, factor = next(s for s in RESPONSES if col.endswith(s[0]))
            y = np.array([math.nan if r.get(col) is None else r[col] for r in ok], float) * factor
            _panel(axes[i, j], x, y, labels)
            if j == 0:
                axes[i, j].set_ylabel(f"{col[:-len(suffix) - 1]} {label}", fontsize=9)
        axes[-1, j].set_xlabel(key, fontsize=9)
    fig.suptitle(sweep_title(title, len(ok), fig.get_figwidth() - 0.3), fontsize=10)
    return fig


def plot_sweep(path: Path, rows: list, keys, title: str = "") -> Path | None:
    """Write :func:`sweep_figure` of ``rows`` to the PNG ``path``; None if nothing to draw."""
    fig = sweep_figure(rows, keys, title)
    if fig is None:
        return None
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=100, format="png")
    return Path(path)
