"""CLI conventions: --version, --quiet, --verbose, documented exit codes, a progress bar that is quiet off a
terminal and ends at 100 % on one, and a message before numba compiles."""
import io
import logging
import subprocess
import sys
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import pytest

import ventsim
from cases import cli
from cavity.integration import integrate
from exchange.engine.engine import _announce_compilation

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "cases/verification/blowdown_choked.toml"


def ventsim_cli(*args):
    return subprocess.run([sys.executable, "-m", "cases.cli", *map(str, args)], cwd=ROOT, capture_output=True,
                          text=True)


def test_version():
    out = ventsim_cli("--version")
    assert out.returncode == 0 and out.stdout.strip() == f"ventsim {ventsim.__version__}"


def test_exit_codes_and_quiet_verbose(tmp_path):
    quiet = ventsim_cli("run", SCENE, "--out", tmp_path / "q", "--quiet")
    assert (quiet.returncode, quiet.stdout, quiet.stderr) == (cli.EXIT_OK, "", "")
    verbose = ventsim_cli("run", SCENE, "--out", tmp_path / "v", "--verbose")
    assert verbose.returncode == 0 and "ventsim: rendered" not in verbose.stderr
    assert "ventsim: built and solved in" in verbose.stderr and "\r" not in verbose.stderr  # no bar in a log
    bad = ventsim_cli("run", tmp_path / "missing.toml")
    assert bad.returncode == cli.EXIT_BAD_INPUT and bad.stderr.count("\n") == 1
    assert ventsim_cli("check", "no_such_case").returncode == cli.EXIT_BAD_INPUT
    assert "exit codes: 0 success" in ventsim_cli("--help").stdout


class Terminal(io.StringIO):
    def isatty(self):
        return True


@pytest.mark.parametrize("tty", [True, False])
def test_the_integration_bar_ends_at_100_percent_on_a_terminal_and_is_silent_otherwise(monkeypatch, tty):
    stream = Terminal() if tty else io.StringIO()
    monkeypatch.setattr(sys, "stderr", stream)
    monkeypatch.setattr("cavity.progress.DELAY", 0.0)  # show the bar at once
    from cases.model.build import build_model
    from cases.scene.files import load_scene

    model = build_model(load_scene(ROOT / "cases" / "verification" / "blowdown_choked.toml"))
    net = model.network
    traj = integrate(net, net.initial_state(), 0.0, 0.5, replace(model.options, method="RK45"), progress=True)
    assert traj.path == "compiled, solve_ivp" and traj.t_final == 0.5
    text = stream.getvalue()
    if tty:
        assert text.splitlines()[-1].split("\r")[-1].startswith("ventsim: 100.0%")
    else:
        assert text == ""


def test_a_message_before_numba_compiles(tmp_path, monkeypatch):
    logger, said = logging.getLogger("ventsim"), []
    handler = logging.Handler()
    handler.emit = lambda record: said.append(record.getMessage())
    monkeypatch.setattr(logger, "handlers", [handler])
    monkeypatch.setattr(logger, "level", logging.INFO)
    missing = SimpleNamespace(signatures=[], _cache=SimpleNamespace(_cache_file=SimpleNamespace(
        _index_path=str(tmp_path / "solve.nbi"))))
    _announce_compilation(missing)
    assert len(said) == 1 and "compiling the engine with numba" in said[0]
    (tmp_path / "solve.nbi").write_bytes(b"")
    _announce_compilation(missing)  # cached on disk: nothing to say
    _announce_compilation(SimpleNamespace(signatures=["compiled"]))  # compiled in this process
    assert len(said) == 1


def test_the_install_warm_up_covers_the_compiled_path_and_the_blockage_kernels():
    from cases import warmup
    from cases.model.build import build_model
    from cases.run.runner import run
    from cases.scene.files import load_scene

    models = [build_model(load_scene(warmup.HERE / name)) for name in warmup.SCENES]
    assert run(models[0]).trajectory.path == "compiled"
    assert models[1].geometry is not None  # a blocked leakage surface: the blockage kernels
    assert models[2].network.areas[0].track.moving is not None  # a vent on a mesh series: the moving-area law


def test_warmup_writes_the_packages_bytecode(tmp_path):
    """A run reads bytecode instead of compiling every module from source, even under PYTHONDONTWRITEBYTECODE."""
    import importlib.util

    from cases.warmup import compile_bytecode

    sources = [tmp_path / "cases" / "__init__.py", tmp_path / "cases" / "model" / "build.py",
               tmp_path / "cavity" / "x.py"]
    for f in sources:
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_text("VALUE = 1\n")
    compile_bytecode(tmp_path)
    assert all(Path(importlib.util.cache_from_source(f)).is_file() for f in sources)


def test_the_program_freezes_the_heap_before_exit_a_python_caller_does_not(tmp_path):
    """``ventsim`` as the program leaves its objects to the OS at exit (gc.freeze); main(argv) from Python does not."""
    out = tmp_path / "out"
    args = ["run", "cases/verification/blowdown_choked.toml", "--out", str(out), "--quiet"]
    probe = ("import gc, sys\nfrom cases.cli import main\n"
             f"sys.argv = ['ventsim'] + {args!r}\nmain()\nprint(gc.get_freeze_count() > 0)\n"
             f"gc.unfreeze()\nmain({args!r})\nprint(gc.get_freeze_count() > 0)")
    done = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True, text=True, check=True)
    assert done.stdout.split() == ["True", "False"]
    assert (out / "history.csv").is_file()
