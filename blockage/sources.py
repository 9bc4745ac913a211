"""Weak links from derived objects (trees, leakage surfaces) back to the mesh they came from.

A :class:`blockage.Blocker` or :class:`blockage.LeakageSurface` remembers its source
mesh only to recognise self-contact (the same mesh object used as leak and as
blocker). Holding it weakly lets the per-mesh caches of :mod:`blockage.api` drop
their entries when the caller drops the mesh.

>>> import trimesh
>>> mesh = trimesh.creation.box()
>>> link = source_link(mesh)
>>> link() is mesh, source_link(None)() is None
(True, True)
"""

import weakref

__all__ = ["source_link"]


def source_link(obj):
    """A callable returning ``obj`` (weakly held when possible; ``None`` once it is gone)."""
    if obj is None:
        return lambda: None
    try:
        return weakref.ref(obj)
    except TypeError:
        return lambda: obj
