"""Every Python block marked ``<!-- runnable -->`` in docs/*.md runs, from the repository's root, and its own
assertions hold (they check the figures the text quotes)."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MARK = re.compile(r"<!-- runnable -->\s*```python\n(.*?)```", re.S)
EXAMPLES = [(md, i, code) for md in sorted((ROOT / "docs").glob("*.md"))
            for i, code in enumerate(MARK.findall(md.read_text()))]


def test_the_docs_have_runnable_examples():
    assert {md.name for md, _, _ in EXAMPLES} >= {"blockage.md", "contact.md"}


@pytest.mark.parametrize("md,index,code", EXAMPLES, ids=[f"{md.name}#{i}" for md, i, _ in EXAMPLES])
def test_doc_example_runs(md, index, code, monkeypatch):
    assert "assert " in code, f"{md.name}#{index}: a doc example must check the figures it shows"
    monkeypatch.chdir(ROOT)
    exec(compile(code, f"{md.name}#{index}", "exec"), {"__name__": "doc_example"})
