"""A seeded mutator over the library scenes, as a careless user would edit them, and a runner that sorts each
mutated scene's ``ventsim run`` into: a clean error, a legal run, a traceback, a hang or a non-finite success.

Each mutation runs in a forked child (the parent has imported and compiled everything once) with a wall budget
(``--max-wall``) and a harder kill timeout: a child that outlives the kill timeout is a hang. Run it alone with
another seed and count::

    VENTSIM_FUZZ_SEED=7 VENTSIM_FUZZ_COUNT=700 python3 -m tests.fuzz_scenes
"""
from __future__ import annotations

import io
import json
import math
import os
import random
import re
import select
import signal
import sys
import time
import tomllib
import traceback
from collections import Counter
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import numpy as np

from .toml_write import dumps

ROOT = Path(__file__).resolve().parents[1]
FILE_SUFFIXES = (".csv", ".ply", ".obj", ".stl", ".npz", ".off")
#: Shortened end time per library case (a fraction of the scene's own) so that a legal run stays cheap.
END_FRACTION = 0.05
WALL_BUDGET = 15.0      # --max-wall of each run [s]
KILL_TIMEOUT = 60.0     # a child still running after this is a hang [s] (the campaign of issue 14: 60 s)

#: A vent area this far below zero [m^2] is round-off of an area difference (the blocked-area track gives
#: -1e-19 m^2 for a fully blocked 2 cm^2 vent, -5e-13 m^2 for one of 1000 m^2), not a negative area.
AREA_ROUND_OFF = 1e-9
NUMBERS = (0.0, -1.0, 1e-300, 1e-9, 1e6, 1e300, -1e300, math.nan, math.inf, -math.inf, 3, 0.5)
FACTORS = (0.0, -1.0, 1e-6, 1e-3, 1e3, 1e6, 1e300)
WRONG_TYPES = ("four", True, False, [1.0, 2.0], {"a": 1}, "", 29.1, "false", 0)


def _library():
    from cases.run.library import CASES, HERE

    return {name: HERE / rel for name, rel in CASES.items()}


def _absolute_files(node, base: Path):
    """``node`` with every relative file name made absolute (the mutated scene is written elsewhere)."""
    if isinstance(node, dict):
        return {k: _absolute_files(v, base) for k, v in node.items()}
    if isinstance(node, list):
        return [_absolute_files(v, base) for v in node]
    if isinstance(node, str) and node.lower().endswith(FILE_SUFFIXES):
        return str((base / node).resolve())
    return node


def _slots(node, path=()):
    """Every (path, value) of a leaf or a table in ``node``, paths as tuples of keys and indices."""
    yield path, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _slots(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _slots(v, path + (i,))


def _get(node, path):
    for p in path:
        node = node[p]
    return node


def _set(node, path, value):
    _get(node, path[:-1])[path[-1]] = value


def _delete(node, path):
    parent = _get(node, path[:-1])
    del parent[path[-1]]


# ------------------------------------------------------------------------------------------------ mutations

def m_number(rng, data, work):
    """A number replaced by an extreme, zero, negative or non-finite one, or scaled."""
    slots = [p for p, v in _slots(data) if p and isinstance(v, (int, float)) and not isinstance(v, bool)]
    if not slots:
        return "no number"
    p = rng.choice(slots)
    v = _get(data, p)
    new = v * rng.choice(FACTORS) if rng.random() < 0.5 else rng.choice(NUMBERS)
    _set(data, p, new)
    return f"{p} = {new!r}"


def m_type(rng, data, work):
    """A value of the wrong type (a string for a number, a number for a string, a list, a table...)."""
    slots = [p for p, v in _slots(data) if p and not isinstance(v, (dict, list)) or (p and isinstance(v, list)
                                                                                     and not v or p and
                                                                                     isinstance(v, list) and
                                                                                     not isinstance(v[0], dict))]
    p = rng.choice(slots)
    new = rng.choice(WRONG_TYPES)
    _set(data, p, new)
    return f"{p} = {new!r}"


def m_delete(rng, data, work):
    """A key or a whole table left out."""
    slots = [p for p, _ in _slots(data) if p]
    p = rng.choice(slots)
    _delete(data, p)
    return f"del {p}"


def m_typo(rng, data, work):
    """A key misspelt."""
    slots = [p for p, v in _slots(data) if p and isinstance(p[-1], str)]
    p = rng.choice(slots)
    k = p[-1]
    i = rng.randrange(len(k))
    typo = k[:i] + k[i + 1:] if len(k) > 1 and rng.random() < 0.5 else k[:i] + rng.choice("aeiours_") + k[i:]
    parent = _get(data, p[:-1])
    parent[typo] = parent.pop(k)
    return f"{p} -> {typo!r}"


def m_name(rng, data, work):
    """A name or a reference changed: to a misspelling, 'ambient', an existing other name, a duplicate."""
    slots = [p for p, v in _slots(data) if p and isinstance(v, str) and p[-1] in
             ("name", "from", "to", "pressure_cavity", "body", "seat") or p and p[-1] in ("blocked_by", "wrapped_by")]
    if not slots:
        return "no name"
    p = rng.choice(slots)
    names = [v for q, v in _slots(data) if q and q[-1] == "name" and isinstance(v, str)]
    new = rng.choice(["ambient", "cushin", "tank2", "", *names])
    _set(data, p, [new] if isinstance(_get(data, p), list) else new)
    return f"{p} = {new!r}"


def m_composition(rng, data, work):
    """A gas composition broken: fractions that do not sum to 1, an unknown or list-valued species."""
    slots = [p for p, v in _slots(data) if p and p[-1] == "gas" and isinstance(v, dict)]
    if not slots:
        return "no gas"
    p = rng.choice(slots)
    gas = dict(_get(data, p))
    kind = rng.randrange(5)
    if kind == 0:
        gas = {k: v * 1.1 for k, v in gas.items()}
    elif kind == 1:
        gas["Unobtainium"] = 0.1
    elif kind == 2:
        gas = {next(iter(gas)): [1.0]}
    elif kind == 3:
        gas = {k: -v for k, v in gas.items()}
    else:
        gas = {"CO2": 0.5, "H2O": 0.5}
    _set(data, p, gas)
    return f"{p} = {gas!r}"


def m_time(rng, data, work):
    """time / solver keys at the edge: a very long run, a tiny or huge output interval, tiny max_step, bad rtol."""
    choice = rng.randrange(7)
    t = data.setdefault("time", {})
    s = data.setdefault("solver", {})
    end = t.get("end", 0.1) if isinstance(t.get("end"), (int, float)) else 0.1
    if choice == 0:
        t["end"] = end * rng.choice((1e3, 1e6))
    elif choice == 1:
        t["output_interval"] = rng.choice((1e-7, 1e-12, 1e300))
    elif choice == 2:
        s["max_step"] = rng.choice((1e-12, 1e-9))
    elif choice == 3:
        s["rtol"] = rng.choice((1e30, 0.0, 1.0, 1e-20, -1e-6))
    elif choice == 4:
        s["method"] = rng.choice(("Radau", "LSODA", "BDF", "RK23", "dop853", "Euler"))
    elif choice == 5:
        s["atol"] = rng.choice((1e30, 1.0, -1.0))
    else:
        t["end"] = rng.choice((0.0, -1.0, 1e-12))
    return f"time {t} solver {s}"


def _tables(data):
    return [p for p, v in _slots(data) if p and isinstance(v, str) and v.endswith(".csv")]


def m_csv(rng, data, work):
    """A table file rewritten: encodings, underscores, NaN, duplicate times, comments and a header, negative or
    huge values, a million rows, one column, empty."""
    slots = _tables(data)
    if not slots:
        return "no table"
    p = rng.choice(slots)
    src = Path(_get(data, p))
    text = src.read_text() if src.is_file() else "time,y\n0,1\n1,1\n"
    lines = text.splitlines()
    kind = rng.randrange(11)
    dst = work / f"mut_{kind}.csv"
    if kind == 0:
        dst.write_bytes(text.encode("utf-16"))
    elif kind == 1:
        dst.write_bytes(("# température °C\n" + text).encode("latin-1"))
    elif kind == 2:
        dst.write_bytes(bytes(rng.randrange(256) for _ in range(400)))
    elif kind == 3:
        dst.write_text("\n".join(ln.replace(".", "_", 1) for ln in lines) + "\n")
    elif kind == 4:
        dst.write_text("\n".join(lines[:2] + [lines[-1].split(",")[0] + ",nan"] + lines[2:]) + "\n")
    elif kind == 5:
        dst.write_text("\n".join(lines + [lines[-1]]) + "\n")
    elif kind == 6:
        dst.write_text("# a comment\n" + text)
    elif kind == 7:
        dst.write_text("\n".join(ln if i == 0 else ",".join([ln.split(",")[0], str(-1e6 * (i + 1))])
                                 for i, ln in enumerate(lines)) + "\n")
    elif kind == 8:
        n = 1_000_000
        x = np.linspace(0.0, 1.0, n)
        dst.write_text("t,y\n" + "\n".join(f"{a:.9g},1" for a in x[:: max(1, n // 1_000_000)]) + "\n")
    elif kind == 9:
        dst.write_text("\n".join(ln.split(",")[0] for ln in lines) + "\n")
    else:
        dst.write_text("")
    _set(data, p, str(dst))
    return f"{p}: csv kind {kind}"


def m_mesh(rng, data, work):
    """A mesh file replaced: no faces, a NaN vertex, millimetres, inside out, a second inside-out shell, a
    directory, a list, a bowtie vertex."""
    import trimesh

    slots = [p for p, v in _slots(data) if p and isinstance(v, str) and v.endswith((".ply", ".obj", ".stl"))]
    if not slots:
        return "no mesh"
    p = rng.choice(slots)
    kind = rng.randrange(8)
    sphere = trimesh.creation.icosphere(subdivisions=2, radius=0.2)
    dst = work / f"mut_{kind}.ply"
    if kind == 0:
        dst.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
                       "0 0 0\n1 0 0\n0 1 0\n")
    elif kind == 1:
        v = sphere.vertices.copy()
        v[0] = np.nan
        trimesh.Trimesh(v, sphere.faces, process=False).export(dst)
    elif kind == 2:
        src = Path(_get(data, p))
        m = trimesh.load(src, force="mesh") if src.is_file() else sphere
        m.apply_scale(1000.0)
        dst = dst.with_suffix(src.suffix or ".ply")
        m.export(dst)
    elif kind == 3:
        s = sphere.copy()
        s.invert()
        s.export(dst)
    elif kind == 4:
        inner = trimesh.creation.icosphere(subdivisions=1, radius=0.05)
        inner.invert()
        trimesh.util.concatenate([sphere, inner]).export(dst)
    elif kind == 5:
        dst = work / "a_directory.ply"
        dst.mkdir(exist_ok=True)
    elif kind == 6:
        _set(data, p, [str(_get(data, p))])
        return f"{p} as a list"
    else:
        a = trimesh.creation.icosphere(subdivisions=1, radius=0.1)
        b = a.copy()
        b.apply_translation(2.0 * a.vertices[0])  # b's antipode of vertex 0 lands on a's vertex 0
        trimesh.Trimesh(np.vstack([a.vertices, b.vertices]), np.vstack([a.faces, b.faces + len(a.vertices)]),
                        process=True).export(dst)
    _set(data, p, str(dst))
    return f"{p}: mesh kind {kind}"


def m_body(rng, data, work):
    """A body's axis or rotation axis zero, subdivisions absurd or not a number, a sphere of negative radius."""
    bodies = data.get("body")
    if not isinstance(bodies, list) or not bodies:
        data.setdefault("cavity", [{}])
        return m_number(rng, data, work)
    b = rng.choice(bodies)
    kind = rng.randrange(6)
    if kind == 0:
        b["axis"] = [0.0, 0.0, 0.0]
    elif kind == 1:
        b["rotation_axis"] = [0.0, 0.0, 0.0]
        b["rotation_table"] = str(ROOT / "cases" / "data" / "headform_motion.csv")
    elif kind == 2:
        b["sphere_subdivisions"] = rng.choice((20, -1, "four", 2.5))
    elif kind == 3:
        b["sphere"] = [0.0, 0.0, 0.2, -0.05]
    elif kind == 4:
        b["axis"] = [1.0, 0.0]
    else:
        b["box"] = [0.0, 0.0, 0.0, 0.0, 0.1, 0.1]
    return f"body {b.get('name')}: kind {kind}"


def m_structure(rng, data, work):
    """A list of tables given as one table, a table given as a list, an empty list."""
    slots = [p for p, v in _slots(data) if p and isinstance(v, (dict, list)) and len(p) <= 2]
    p = rng.choice(slots)
    v = _get(data, p)
    if isinstance(v, list):
        new = v[0] if v and rng.random() < 0.6 else []
    else:
        new = [v] if rng.random() < 0.5 else "table"
    _set(data, p, new)
    return f"{p} restructured"


def m_vent(rng, data, work):
    """Exchange keys at the edge: a pop vent armed above its pressure at t = 0, a huge effective area or Cd,
    a negative amplitude, explicit effective_area = 0, a reversed open/close time."""
    ex = data.get("exchange")
    if not isinstance(ex, list) or not ex:
        return m_number(rng, data, work)
    e = rng.choice(ex)
    kind = rng.randrange(6)
    if kind == 0:
        e["pop_pressure"] = 1.0
    elif kind == 1:
        e["effective_area"] = 1e3
    elif kind == 2:
        e["discharge_coefficient"] = 1e300
    elif kind == 3:
        e["amplitude"] = -1.0
    elif kind == 4:
        e["effective_area"] = 0.0
    else:
        e["open_time"], e["close_time"] = 0.5, 0.1
    return f"exchange {e.get('name')}: kind {kind}"


def m_units(rng, data, work):
    """A [units] table that does not fit: another system than the numbers and files are written in (its checks on
    or off), an unknown system, or exemptions that name no key or are not a list of names."""
    units = data.setdefault("units", {})
    kind = rng.randrange(4)
    if kind == 0:
        units["system"] = rng.choice(("mm-t-s", "mm-kg-ms"))
    elif kind == 1:
        units.update(system=rng.choice(("mm-t-s", "mm-kg-ms")), check=False)
    elif kind == 2:
        units["system"] = rng.choice(("mm", "MKS", "", 3, "si"))
    else:
        units["unchecked"] = rng.choice((["cavity[0].volume"], ["no.such.key"], "cavity[0].volume", [1], []))
    return f"units = {units!r}"


MUTATIONS = (m_number, m_type, m_delete, m_typo, m_name, m_composition, m_time, m_csv, m_mesh, m_body,
             m_structure, m_vent, m_units)


def encoding_text(rng, text: str) -> bytes:
    """The scene text in a wrong encoding (UTF-16, Latin-1 with an accent, or binary garbage)."""
    kind = rng.randrange(3)
    if kind == 0:
        return text.encode("utf-16")
    if kind == 1:
        return ("# scène\n" + text).encode("latin-1", errors="replace")
    return bytes(rng.randrange(256) for _ in range(300))


def mutate(rng, name: str, path: Path, work: Path) -> tuple:
    """A mutated copy of library case ``name`` written into ``work``; returns (scene path, description)."""
    data = _absolute_files(tomllib.loads(path.read_text()), path.parent)
    if isinstance(data.get("time"), dict) and isinstance(data["time"].get("end"), (int, float)):
        data["time"]["end"] *= END_FRACTION
        data["time"].pop("output_interval", None)
    scene = work / "scene.toml"
    if rng.random() < 0.05:
        scene.write_bytes(encoding_text(rng, dumps(data)))
        return scene, "encoding"
    mutation = rng.choice(MUTATIONS)
    try:
        what = mutation(rng, data, work)
    except (IndexError, KeyError, TypeError, ValueError) as exc:  # the mutation did not apply: leave the scene
        what = f"{mutation.__name__} not applied ({exc})"
    scene.write_text(dumps(data))
    return scene, f"{mutation.__name__}: {what}"


# ------------------------------------------------------------------------------------------------ running

def _child(scene: Path, out: Path, wall: float) -> dict:
    from cases.cli import main

    err, code = io.StringIO(), None
    try:
        with redirect_stderr(err), redirect_stdout(io.StringIO()):
            code = main(["run", str(scene), "--out", str(out), "--quiet", "--max-wall", str(wall)])
    except BaseException:  # noqa: BLE001 - anything escaping main is what we count
        return {"kind": "traceback", "detail": traceback.format_exc()}
    text = err.getvalue()
    if "Traceback" in text:
        return {"kind": "traceback", "detail": text}
    if code == 0:
        return {"kind": _success_kind(out), "detail": text}
    errors = [ln for ln in text.splitlines() if ln.startswith("ventsim: error:")]
    if code == 2 and len(errors) == 1:
        named = names_file_and_key(errors[0], scene)
        return {"kind": "clean error" if named else "error without file or key", "detail": errors[0]}
    return {"kind": "traceback", "detail": f"exit {code}: {text}"}


#: A key as an error names it: ``cavity[0].inflator[1].mass_flow``, ``time.end``, ``exchange``.
_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\[\d+\])?(\.[A-Za-z_0-9]+(\[\d+\])?)*")
#: Errors about the file as a whole, which have no key to name (its line and column are named instead).
_WHOLE_FILE = ("not valid TOML", "scene file", "is not UTF-8")


def names_file_and_key(line: str, scene: Path) -> bool:
    """True when the error line names the scene file and then a key (or is about the file as a whole).

    >>> names_file_and_key("ventsim: error: s.toml: cavity[0].volume: 50 m^3 ...", Path("s.toml"))
    True
    >>> names_file_and_key("ventsim: error: the solver failed", Path("s.toml"))
    False
    """
    head = f"ventsim: error: {scene}: "
    if not line.startswith(head):
        return False
    rest = line[len(head):]
    where = rest.split(": ", 1)[0]
    return bool(_KEY.fullmatch(where)) or any(w in rest for w in _WHOLE_FILE)


def _success_kind(out: Path) -> str:
    """'legal run', or 'non-finite success' when the history has a non-finite or impossible value."""
    try:
        with (out / "history.csv").open() as fh:
            header = fh.readline().strip().split(",")
        h = np.loadtxt(out / "history.csv", delimiter=",", skiprows=1, ndmin=2)
        summary = json.loads((out / "summary.json").read_text(), parse_constant=lambda c: math.nan)
    except (OSError, ValueError):
        return "non-finite success"
    if not np.all(np.isfinite(h)) or h.shape[0] < 2 or h[0, 0] != 0.0:
        return "non-finite success"
    for i, c in enumerate(header):
        if c.endswith((".pressure [Pa]", ".temperature [K]")) and np.any(h[:, i] <= 0):
            return "non-finite success"
        if c.endswith(".area [m^2]") and np.any(h[:, i] < -AREA_ROUND_OFF):
            return "non-finite success"
    if "nan" in json.dumps(summary).lower().replace("nan\"", ""):
        return "non-finite success"
    return "legal run"


def run_one(scene: Path, out: Path, wall: float = WALL_BUDGET, timeout: float = KILL_TIMEOUT) -> dict:
    """Run ``ventsim run scene --max-wall wall`` in a forked child, killed after ``timeout`` [s]; its outcome as
    {"kind", "detail", "wall"}."""
    r, w = os.pipe()
    start = time.monotonic()
    pid = os.fork()
    if pid == 0:  # the child
        os.close(r)
        try:
            outcome = _child(scene, out, wall)
            os.write(w, json.dumps(outcome).encode())
        finally:
            os._exit(0)
    os.close(w)
    chunks, deadline = [], start + timeout
    with os.fdopen(r, "rb") as fh:
        while True:
            left = deadline - time.monotonic()
            ready = select.select([fh], [], [], max(left, 0.0))[0] if left > 0 else []
            if not ready:
                os.kill(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
                return {"kind": "hang", "detail": f"still running after {timeout} s", "wall": timeout}
            chunk = os.read(fh.fileno(), 1 << 16)
            if not chunk:
                break
            chunks.append(chunk)
    os.waitpid(pid, 0)
    try:
        outcome = json.loads(b"".join(chunks).decode())
    except ValueError:
        outcome = {"kind": "traceback", "detail": "the child died without a word"}
    outcome["wall"] = time.monotonic() - start
    return outcome


def warm_up(library) -> None:
    """Compile what the runs use before the first fork: the numba kernels of every library case, in a separate
    process (its caches are written to disk; a blockage kernel run in this parent made forked children hang),
    and here the imports and matplotlib's first figure (forked children inherit them)."""
    import subprocess
    import tempfile

    from cases import cli  # noqa: F401
    from cases.results.output import plot_history

    code = ("import tomllib, sys; from pathlib import Path; from cases.scene.files import scene_from_dict; "
            "from cases.model.build import build_model; from cases.run.runner import run\n"
            "for p in sys.argv[1:]:\n"
            "    d = tomllib.loads(Path(p).read_text()); d['time']['end'] *= 0.01; d['time'].pop('output_interval', None)\n"
            "    run(build_model(scene_from_dict(d, p)))\n")
    subprocess.run([sys.executable, "-c", code, *map(str, library.values())], check=True, cwd=ROOT,
                   capture_output=True)
    with tempfile.TemporaryDirectory() as tmp:  # matplotlib's import and first figure, once
        plot_history(Path(tmp) / "h.png", ["time [s]", "a.pressure [Pa]"], np.array([[0.0, 1.0], [1.0, 2.0]]))


def campaign(seed: int, count: int, work: Path, *, log=None, wall: float = WALL_BUDGET,
             timeout: float = KILL_TIMEOUT) -> dict:
    """``count`` mutations from ``seed``, each run with ``--max-wall wall`` and killed (a hang) after ``timeout``
    [s]; returns {"counts": Counter, "bad": [(case, what, outcome)], "max wall [s]", "mean wall [s]"}."""
    cases = _library()
    warm_up(cases)
    rng = random.Random(seed)
    counts, bad, walls = Counter(), [], []
    names = sorted(cases)
    for k in range(count):
        name = names[k % len(names)] if k < len(names) else rng.choice(names)
        here = work / f"m{k:04d}"
        here.mkdir(parents=True)
        scene, what = mutate(rng, name, cases[name], here)
        outcome = run_one(scene, here / "out", wall, timeout)
        counts[outcome["kind"]] += 1
        walls.append(outcome["wall"])
        if outcome["kind"] not in ("clean error", "legal run"):
            bad.append((name, what, outcome))
        if log is not None:
            log(f"{k:4d} {name:24s} {outcome['kind']:18s} {outcome['wall']:6.2f} s  {what[:90]}"
                + ("" if outcome["kind"] in ("clean error", "legal run") else
                   "\n      " + (outcome["detail"].strip().splitlines() or ["(no message)"])[-1][:300]))
    return {"counts": counts, "bad": bad, "max wall [s]": max(walls, default=0.0),
            "mean wall [s]": float(np.mean(walls)) if walls else 0.0}


def settings(default_seed: int = 1, default_count: int = 300) -> tuple:
    """(seed, count) from VENTSIM_FUZZ_SEED and VENTSIM_FUZZ_COUNT, else the defaults."""
    return (int(os.environ.get("VENTSIM_FUZZ_SEED", default_seed)),
            int(os.environ.get("VENTSIM_FUZZ_COUNT", default_count)))


def main() -> int:
    """Run a campaign (VENTSIM_FUZZ_SEED, VENTSIM_FUZZ_COUNT, and VENTSIM_FUZZ_WALL / VENTSIM_FUZZ_KILL [s]);
    print a line per mutation, the figures, and last a JSON line of them (for tests/test_fuzz.py)."""
    import tempfile

    seed, count = settings(7, 700)
    wall = float(os.environ.get("VENTSIM_FUZZ_WALL", WALL_BUDGET))
    kill = float(os.environ.get("VENTSIM_FUZZ_KILL", KILL_TIMEOUT))
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="ventsim-fuzz-") as tmp:
        res = campaign(seed, count, Path(tmp), log=lambda s: print(s, flush=True), wall=wall, timeout=kill)
    c = res["counts"]
    print(f"seed {seed}, {count} mutations in {time.monotonic() - start:.0f} s: "
          f"{c['traceback']} tracebacks, {c['error without file or key']} errors without file or key, {c['hang']} hangs, {c['non-finite success']} non-finite successes, "
          f"{c['clean error']} clean errors, {c['legal run']} legal runs; slowest run {res['max wall [s]']:.1f} s")
    bad = [f"{name}: {what}: {out['kind']}: {(out['detail'].strip().splitlines() or [''])[-1][:200]}"
           for name, what, out in res["bad"]]
    print(json.dumps({"counts": dict(c), "bad": bad, "max wall [s]": res["max wall [s]"]}))
    return 1 if res["bad"] else 0


if __name__ == "__main__":
    sys.exit(main())
