"""Write a run's results atomically: history.csv, summary.json, history.png, and with contact contact.npz
(per seat node CPRESS [Pa] and status at the output times) (temp file, then rename).

``ventsim run`` writes them as one set (:func:`output_set`): into a fresh hidden folder beside ``--out``, which
then replaces ``--out`` as a whole, so a run killed at any moment leaves either the complete earlier set or the
complete new one, never a mix; hidden folders and temp files of an earlier killed run are removed first.
"""
from __future__ import annotations

import fnmatch
import json
import os
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path

import numpy as np

__all__ = ["atomic_path", "write_history", "write_summary", "history_figure", "plot_history", "write_results",
           "check_out", "output_set", "remove_temp_files", "OUTPUT_NAMES"]

#: What an output folder of ``ventsim run`` may hold (patterns): only such a folder is replaced as a whole.
OUTPUT_NAMES = ("history.csv", "summary.json", "history.png", "contact.npz", "*.png", "*.gif", "vtk", "scene")


@contextmanager
def atomic_path(target: Path):
    """Yield a temporary path next to ``target``; on success it replaces ``target`` in one rename.

    A failure while writing leaves any previous ``target`` untouched and removes the temporary file.
    """
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix, dir=target.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, target)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def write_history(path: Path, columns: list, history: np.ndarray) -> None:
    """CSV with a header of names and units, full double precision."""
    with atomic_path(path) as tmp:
        np.savetxt(tmp, history, delimiter=",", header=",".join(columns), comments="", fmt="%.17g")


def _plain(obj):
    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if isinstance(obj, np.generic):
        return obj.item()
    return obj


def write_summary(path: Path, summary: dict) -> None:
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(_plain(summary), indent=2) + "\n")


def history_figure(columns: list, history: np.ndarray, title: str = "", overlay: dict | None = None):
    """The history figure as a matplotlib ``Figure`` (Agg), for interactive use: the panels of
    :func:`cases.results.history_plot.history_panels` (pressure, temperature, mass flows, exchange areas and, where
    the scene has them, blocked fractions, body displacements and peak contact pressure against time); ``overlay``
    {cavity: FePressure} draws an FE run's pressure dashed over ventsim's (:mod:`cases.results.fe_pressure`).
    ``history.png`` is drawn without matplotlib (:func:`plot_history`)."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    from cases.results.history_plot import history_panels

    panels = history_panels(columns, history, overlay)
    fig = Figure(figsize=(8, 2.3 * len(panels)))
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (label, series) in zip(axes, panels):
        for name, t, values, dashed in series:
            if dashed:
                ax.plot(t, values, "--", color="k", lw=1, label=name)
            else:
                ax.plot(t, values, label=name)
        ax.set_ylabel(label)
        ax.yaxis.set_major_locator(MaxNLocator(5))  # fewer ticks: each costs a text layout when drawn
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8, loc="best")
    axes[-1].set_xlabel("time [ms]")
    if title:
        fig.suptitle(title, fontsize=10, y=1.0 - 0.12 / fig.get_figheight())
    height = fig.get_figheight()  # fixed margins [in] instead of tight_layout, which costs a whole extra draw
    fig.subplots_adjust(left=0.1, right=0.98, top=1.0 - 0.45 / height, bottom=0.5 / height, hspace=0.55 / 2.3)
    return fig


def plot_history(path: Path, columns: list, history: np.ndarray, title: str = "", overlay=None) -> None:
    """The history figure written to the PNG ``path`` (:func:`cases.results.history_plot.draw_history`: Pillow,
    the panels of :func:`history_figure` without importing matplotlib)."""
    from cases.results.history_plot import draw_history

    image = draw_history(columns, history, title, overlay)
    with atomic_path(path) as tmp:  # zlib level 1: a fifth of the default's time for a slightly larger file
        image.save(tmp, format="PNG", compress_level=1)


def write_results(results, out: Path) -> dict:
    """All outputs of a run into folder ``out``; returns {kind: path}."""
    out = Path(out)
    paths = {"history": out / "history.csv", "summary": out / "summary.json", "plot": out / "history.png"}
    write_history(paths["history"], results.columns, results.history)
    write_summary(paths["summary"], results.summary)
    from cases.results.fe_pressure import scene_fe_pressures

    plot_history(paths["plot"], results.columns, results.history, results.model.scene.title,
                 scene_fe_pressures(results.model.scene))
    from cases.results.seal_outputs import write_seal_pictures

    for k, picture in enumerate(write_seal_pictures(results, out)):
        paths[f"seal{k}"] = picture
    if getattr(results, "contact", None) is not None:
        paths["contact"] = out / "contact.npz"
        with atomic_path(paths["contact"]) as tmp:
            with open(tmp, "wb") as fh:
                np.savez_compressed(fh, **results.contact)
    return paths


def check_out(out: Path) -> None:
    """Refuse, before a run, an ``--out`` that is a file, or a folder holding files a run did not write (it is
    replaced as a whole); raises SceneError."""
    from cases.scene.errors import SceneError

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise SceneError(out, "--out", "is a file; expected an output folder (new, or one of an earlier run)")
    if out.is_dir():
        foreign = sorted(p.name for p in out.iterdir() if not _ours(p.name))
        if foreign:
            raise SceneError(out, "--out", f"holds files a run did not write ({', '.join(foreign[:3])}"
                                           f"{', ...' if len(foreign) > 3 else ''}); the folder is replaced as a "
                                           "whole: choose a new or empty folder")
    parent = out.resolve().parent
    if parent.exists() and not os.access(parent, os.W_OK):
        raise SceneError(out, "--out", f"cannot write in {str(parent)!r}")


def _stale(out: Path) -> list:
    """Hidden leftovers of earlier runs into ``out``: staging and old folders beside it."""
    parent, name = out.parent, out.name
    found = [p for p in parent.glob(f".{name}.new-*")] + [p for p in parent.glob(f".{name}.old-*")]
    return found


def remove_temp_files(folder: Path) -> None:
    """Remove the temp files :func:`atomic_path` left in ``folder`` when a writer was killed."""
    folder = Path(folder)
    if folder.is_dir():
        for p in folder.glob(".*"):
            if p.is_file() and _temp_file(p.name):
                p.unlink(missing_ok=True)


def _temp_file(name: str) -> bool:
    """A temp file of :func:`atomic_path` for one of the outputs or a sweep variant's row.json
    (``.history.csv.k2j3.csv``)."""
    return any(name.startswith(f".{n}.") for n in OUTPUT_NAMES + ("row.json",) if "*" not in n)


def _ours(name: str) -> bool:
    return _temp_file(name) or any(fnmatch.fnmatch(name, pat) for pat in OUTPUT_NAMES)


def _clean(out: Path) -> None:
    """Remove what a killed run left; if it was killed between its two renames, put the old set back first."""
    olds = [p / "set" for p in sorted(out.parent.glob(f".{out.name}.old-*")) if (p / "set").is_dir()]
    if not out.exists() and olds:
        os.replace(olds[-1], out)
    for p in _stale(out):
        shutil.rmtree(p, ignore_errors=True)
    remove_temp_files(out)


@contextmanager
def output_set(out: Path):
    """Yield a fresh hidden folder beside ``out`` to write a run's outputs into; on success it replaces ``out``
    as a whole (the earlier set, if any, is removed after the swap). A failure leaves ``out`` as it was."""
    out = Path(out)
    check_out(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    _clean(out)
    stage = Path(tempfile.mkdtemp(prefix=f".{out.name}.new-", dir=out.parent))
    try:
        yield stage
        os.chmod(stage, 0o777 & ~_umask())
        if out.exists():
            old = Path(tempfile.mkdtemp(prefix=f".{out.name}.old-", dir=out.parent))
            os.replace(out, old / "set")
            os.replace(stage, out)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.replace(stage, out)
    finally:
        if stage.exists():
            shutil.rmtree(stage, ignore_errors=True)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
