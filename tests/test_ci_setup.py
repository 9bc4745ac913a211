""".ci/setup's virtual-environment step (``bash .ci/setup venv``) on a Debian python3 without python3-venv, simulated
by a stand-in interpreter whose ``-m venv`` fails as Debian's does (and leaves a half-made .venv), and stand-in
apt-get and sudo: no network, no root, a second or two."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
VERSION = f"{sys.version_info[0]}.{sys.version_info[1]}"
#: What Debian's python3 prints when python3-venv is missing (bookworm, python3.11; the version is this one's).
DEBIAN = f"""The virtual environment was not created successfully because ensurepip is not
available.  On Debian/Ubuntu systems, you need to install the python3-venv
package using the following command.

    apt install python{VERSION}-venv

You may need to use sudo with that command.  After installing the python3-venv
package, recreate your virtual environment.
"""


def script(path: Path, text: str) -> Path:
    path.write_text("#!/usr/bin/env bash\n" + text)
    path.chmod(0o755)
    return path


@pytest.fixture
def debian(tmp_path):
    """(run(), repo, log): a copy of .ci/setup in ``repo``; run(apt_works) runs ``bash .ci/setup venv`` there with
    the stand-ins first on PATH; ``log`` collects the apt-get calls."""
    repo, bin_ = tmp_path / "repo", tmp_path / "bin"
    (repo / ".ci").mkdir(parents=True)
    bin_.mkdir()
    shutil.copy(ROOT / ".ci" / "setup", repo / ".ci" / "setup")
    marker, log = tmp_path / "venv-installed", tmp_path / "apt.log"
    good = script(tmp_path / "good_python", f'exec "{sys.executable}" "$@"\n')
    script(bin_ / "python3", f"""if [ "$1" = -m ] && [ "$2" = venv ]; then
  mkdir -p "$3/bin"
  if [ -e "{marker}" ]; then cp "{good}" "$3/bin/python"; exit 0; fi
  touch "$3/bin/python"; chmod +x "$3/bin/python"  # Debian leaves a .venv without pip behind
  cat <<'EOF'
{DEBIAN}
Failing command: $3/bin/python3
EOF
  exit 1
fi
exec "{sys.executable}" "$@"
""")
    script(bin_ / "sudo", 'exec "$@"\n')

    def run(apt_works: bool):
        works = f'[ "$1" = install ] && touch "{marker}"\nexit 0\n'
        offline = '[ "$1" = update ] && exit 0\necho "E: Unable to locate package" >&2\nexit 100\n'
        body = f'echo "$*" >> "{log}"\n' + (works if apt_works else offline)
        script(bin_ / "apt-get", body)
        env = dict(os.environ, PATH=f"{bin_}{os.pathsep}{os.environ['PATH']}", PYTHON="python3")
        return subprocess.run(["bash", str(repo / ".ci" / "setup"), "venv"], cwd=tmp_path, env=env,
                              capture_output=True, text=True, timeout=60)

    return run, repo, log


def test_debian_without_python3_venv_is_one_line_saying_what_to_install(debian):
    run, repo, log = debian
    proc = run(apt_works=False)
    assert proc.returncode == 1
    lines = proc.stderr.strip().splitlines()
    assert lines[-1].startswith("setup: error: 'python3 -m venv' cannot make a virtual environment")
    assert f"sudo apt install python{VERSION}-venv" in lines[-1] and "(or python3-venv)" in lines[-1]
    assert "Traceback" not in proc.stderr and "Failing command" not in proc.stderr
    assert not (repo / ".venv").exists()  # the half-made environment is gone: the next run does not reuse it
    calls = log.read_text()  # apt-get was tried first: the versioned package, then python3-venv
    assert f"install -y -qq python{VERSION}-venv" in calls and "install -y -qq python3-venv" in calls


def test_with_apt_get_it_installs_python3_venv_and_goes_on(debian):
    run, repo, log = debian
    proc = run(apt_works=True)
    assert proc.returncode == 0, proc.stderr
    assert f"installing Debian's python{VERSION}-venv" in proc.stderr
    assert (repo / ".venv" / "bin" / "python").is_file()
    again = run(apt_works=True)
    assert again.returncode == 0 and "reusing the virtual environment .venv" in again.stderr
