"""The user documentation (README.md and docs/*.md) reads as documentation: no work notes (issue numbers,
"acceptance", sessions), no paths outside the repository; README links the pages a new user needs; docs/scenes.md
names the README's main job and the solver that runs by default."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))

#: (pattern, what it is): each is a finding in user documentation.
FORBIDDEN = [
    (r"(?i)\bissues?\s*#?\s*\d+", "an issue number"),
    (r"(?i)\b(the|this|that) issue\b|\bissue's\b", "a reference to a work item"),
    (r"(?i)\bacceptance\b", "a work item's acceptance"),
    (r"(?i)\bthis session\b|\bthe brief\b|\bworktree\b", "a work note"),
    (r"(?i)\bhelpers? (session|branch|compiled)\b", "a work note"),
    (r"shared/", "a path outside the repository"),
    (r"/work/", "a path outside the repository"),
    (r"(?<![\w.])\.\./", "a path outside the repository"),
]


def findings(text: str) -> list:
    """(line number, what, line) of every forbidden pattern in ``text``.

    >>> findings("see shared/PHYSICS.md (issue 7)")[0][:2], findings("the helpers are inlined")
    ((1, 'an issue number'), [])
    """
    out = []
    for number, line in enumerate(text.splitlines(), 1):
        out += [(number, what, line.strip()) for pattern, what in FORBIDDEN if re.search(pattern, line)]
    return out


def test_the_patterns_find_work_notes():
    notes = ["## 0. Issue 6 acceptance", "Contact mechanics (issue 7)", "see `/work/shared/PHYSICS.md`",
             "the issue's 5 K", "in a run of this session", "load 1-2 while a helper compiled", "(../shared/x)"]
    assert all(findings(n) for n in notes)
    fine = ["the numba helpers are inlined", "a tissue model", "`--out /data/study`", "out/benchmarks/x.png"]
    assert not any(findings(f) for f in fine)


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_no_work_notes_or_outside_paths(page):
    found = findings(page.read_text(encoding="utf-8"))
    assert not found, f"{page.name}: " + "; ".join(f"line {n}: {what}: {line!r}" for n, what, line in found)


def test_readme_links_the_pages_a_new_user_needs_and_they_exist():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    for page in ("docs/getting-started.md", "docs/physics.md"):
        assert page in readme
    for page in set(re.findall(r"docs/[\w-]+\.md", readme)):
        assert (ROOT / page).is_file(), page


def test_scenes_doc_names_the_main_job_and_the_default_solver():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    main = re.search(r"ventsim run (cases/\S+\.toml)", readme).group(1)
    scenes = (ROOT / "docs" / "scenes.md").read_text(encoding="utf-8")
    mentions = [m.end() for m in re.finditer(r"README's main job", scenes)]
    assert mentions and all(main in scenes[m:m + 80] for m in mentions), main
    integration = scenes.split("## Integration")[1].split("\n## ")[0]
    assert "DOP853" in integration and "compiled" in integration.split("solve_ivp")[0]


def test_getting_started_installs_with_the_readme_command():
    first = re.compile(r"```bash\n(.*?)```", re.S)
    readme = first.search((ROOT / "README.md").read_text(encoding="utf-8")).group(1).strip()
    guide = first.search((ROOT / "docs" / "getting-started.md").read_text(encoding="utf-8")).group(1).strip()
    assert guide == readme
