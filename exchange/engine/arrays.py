"""Copies between arrays inside numba kernels, element by element.

An array assigned to a slice (``out[:n] = a``, ``K[0] = f``) makes numba compile, in the kernel that does it, the
path that formats a shape mismatch into its error message: 3.6-4 s of CPU on a cold cache, and code that every cached
kernel holding it loads again at each run. :func:`copy_into` makes the same copy without it.
"""
from __future__ import annotations

from numba import njit

__all__ = ["copy_into"]


@njit(cache=True)
def copy_into(dst, src):
    """``dst[i] = src[i]`` for every i of the 1-D ``src`` (``dst`` at least as long; views are written through)."""
    for i in range(src.size):
        dst[i] = src[i]
