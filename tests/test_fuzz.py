"""Issue 14: a seeded mutator over the library scenes (tests/fuzz_scenes.py): no traceback, no hang, no non-finite
success. The seed and the count come from VENTSIM_FUZZ_SEED and VENTSIM_FUZZ_COUNT (default 1 and 300)."""
import os
import sys

import pytest

from tests.fuzz_scenes import campaign, settings


@pytest.mark.skipif(not hasattr(os, "fork") or sys.platform == "darwin", reason="forks a child per mutation")
def test_mutated_library_scenes_end_in_a_clean_error_or_a_finite_run(tmp_path):
    seed, count = settings(1, 300)
    res = campaign(seed, count, tmp_path, wall=4.0, timeout=20.0)  # CI time: a run over 4 s stops cleanly
    c = res["counts"]
    print(f"seed {seed}, {count} mutations: {dict(c)}; slowest {res['max wall [s]']:.1f} s")
    assert sum(c.values()) == count
    assert c["clean error"] > count // 3 and c["legal run"] > count // 10  # the mutator reaches both outcomes
    bad = [f"{name}: {what}: {out['kind']}: {(out['detail'].strip().splitlines() or [''])[-1][:200]}"
           for name, what, out in res["bad"]]
    assert not bad, "\n".join(bad)
