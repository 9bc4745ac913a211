"""The scene documentation is in sync with the code, and its complete example runs."""
import re
from pathlib import Path

from cases.scene.docs import BEGIN, END, key_reference
from cases.run.runner import run
from cases.model.build import build_model
from cases.scene.files import load_scene

ROOT = Path(__file__).resolve().parents[1]


def test_key_reference_is_current():
    text = (ROOT / "docs" / "scenes.md").read_text()
    assert text.split(BEGIN)[1].split(END)[0].strip() == key_reference().strip(), \
        "run: python -m cases.scene.docs --write"


def test_documented_example_runs_and_is_the_main_scene(tmp_path):
    text = (ROOT / "docs" / "scenes.md").read_text()
    block = re.search(r"```toml\n(.*?)```", text, re.S).group(1)
    path = ROOT / "cases" / "_doc_example.toml"
    path.write_text(block)
    try:
        scene = load_scene(path)
        r = run(build_model(scene))
    finally:
        path.unlink()
    main = run(build_model(load_scene(ROOT / "cases" / "airbag_vented.toml")))
    p_doc = r.summary["cavities"]["cushion"]["peak pressure [Pa]"]
    assert p_doc == main.summary["cavities"]["cushion"]["peak pressure [Pa]"]
    assert 1.5e5 < p_doc < 3e5
