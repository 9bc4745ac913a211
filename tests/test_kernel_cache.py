"""The numba cache of the compiled path is dropped when any of its modules changes (exchange.kernel_cache)."""
import shutil

from exchange import kernel_cache


def test_stale_kernels_are_purged_when_a_compiled_module_changes(tmp_path, monkeypatch):
    pkg = tmp_path / "exchange"
    (tmp_path / "cavity" / "__pycache__").mkdir(parents=True)
    (pkg / "__pycache__").mkdir(parents=True)
    for name in ("compiled_rhs.py", "compiled_solver.py", "orifice.py"):
        (pkg / name).write_text("@njit\nx = 1\n")
    (pkg / "network.py").write_text("z = 1\n")  # no numba kernel: not a source of the path
    (tmp_path / "cavity" / "rk_compiled.py").write_text("@njit\ny = 1\n")
    monkeypatch.setattr(kernel_cache, "HERE", pkg)
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    cached = [pkg / "__pycache__" / "compiled_solver.solve-312.py311.nbi",
              tmp_path / "cavity" / "__pycache__" / "rk_compiled.dense_eval-9.py311.1.nbc"]
    other = tmp_path / "cavity" / "__pycache__" / "gas.something-1.py311.nbi"
    for f in cached + [other]:
        f.write_text("")
    assert kernel_cache.purge_stale()  # no stamp yet: purged, stamped
    assert not any(f.exists() for f in cached) and other.exists()
    for f in cached:
        f.write_text("")
    assert not kernel_cache.purge_stale()  # same sources: the cache is kept
    assert all(f.exists() for f in cached)
    (pkg / "network.py").write_text("z = 2\n")
    assert not kernel_cache.purge_stale()
    (pkg / "orifice.py").write_text("@njit\nx = 2\n")  # an inlined law changed
    assert kernel_cache.purge_stale() and not any(f.exists() for f in cached)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert not kernel_cache.purge_stale()
    shutil.rmtree(tmp_path / "cavity")
