"""Numba when installed, plain Python otherwise (same code, same answers, slower).

The compiled kernels are written in the subset of Python that numba compiles; when
numba is missing, :func:`njit` returns the function unchanged, so the package still works (slowly) and can be tested without a compiler.

>>> HAVE_NUMBA in (True, False)
True
"""

try:  # pragma: no cover - depends on the environment
    import numba as _numba

    HAVE_NUMBA = True

    def njit(*args, **kwargs):
        """``numba.njit`` with ``cache=True`` and ``error_model='numpy'`` by default."""
        kwargs.setdefault("cache", True)
        kwargs.setdefault("error_model", "numpy")
        return _numba.njit(*args, **kwargs)

except ImportError:  # pragma: no cover - depends on the environment
    HAVE_NUMBA = False

    def njit(*args, **kwargs):
        """Identity decorator standing in for ``numba.njit``."""
        if len(args) == 1 and callable(args[0]) and not kwargs:
            return args[0]
        return lambda function: function


__all__ = ["HAVE_NUMBA", "njit"]
