"""Checks of one scene value that is not a plain scalar: a gas composition, a vector, a list of names, cp
coefficients, a number-or-table. Each is used twice, by the TOML converters of :mod:`cases.scene.files` and by
:func:`cases.scene.validate.validate_scene` on a scene built in Python, so both meet the same messages."""
from __future__ import annotations

import math

from cavity.tables import Table

from cases.scene.errors import SceneError

__all__ = ["composition", "vector", "names_list", "cp_coefficients", "table_value", "FRACTION_SUM_TOLERANCE"]

#: Fractions of a gas composition must sum to 1 within this.
FRACTION_SUM_TOLERANCE = 1e-9


def _number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def composition(value, path, where) -> dict:
    """A gas composition {species = fraction}: text names, finite fractions >= 0 summing to 1 (within 1e-9).

    >>> composition({"N2": 0.79, "O2": 0.21}, "s.toml", "gas")
    {'N2': 0.79, 'O2': 0.21}
    >>> composition({"N2": 1.1}, "s.toml", "cavity[0].gas")
    Traceback (most recent call last):
    ...
    cases.scene.errors.SceneError: s.toml: cavity[0].gas: fractions sum to 1.1; expected 1 (within 1e-09)
    """
    if not isinstance(value, dict) or not value:
        raise SceneError(path, where, f"expected a table {{species = fraction}}, got {value!r}")
    for k, v in value.items():
        if not isinstance(k, str) or not k:
            raise SceneError(path, where, f"expected species names as text, got {k!r}")
        if not _number(v) or v < 0:
            raise SceneError(path, f"{where}.{k}", f"expected a fraction >= 0 (a number), got {v!r}")
    total = math.fsum(value.values())
    if abs(total - 1.0) > FRACTION_SUM_TOLERANCE:
        raise SceneError(path, where, f"fractions sum to {total!r}; expected 1 (within {FRACTION_SUM_TOLERANCE})")
    return dict(value)


def vector(value, n: int, path, where, *, nonzero: bool = False) -> tuple:
    """A list of ``n`` finite numbers as a tuple; ``nonzero``: not all zero (a direction).

    >>> vector([0, 0, 1], 3, "s.toml", "body[0].axis", nonzero=True)
    (0.0, 0.0, 1.0)
    >>> vector([0, 0, 0], 3, "s.toml", "body[0].axis", nonzero=True)
    Traceback (most recent call last):
    ...
    cases.scene.errors.SceneError: s.toml: body[0].axis: a direction cannot be the zero vector (0, 0, 0)
    """
    if not isinstance(value, (list, tuple)) or len(value) != n or not all(_number(x) for x in value):
        raise SceneError(path, where, f"expected a list of {n} finite numbers, got {value!r}")
    out = tuple(float(x) for x in value)
    if nonzero and not any(out):
        raise SceneError(path, where, f"a direction cannot be the zero vector ({', '.join('0' for _ in out)})")
    return out


def names_list(value, path, where, what: str = "body") -> tuple:
    """A list of names (text)."""
    if not isinstance(value, (list, tuple)) or not all(isinstance(x, str) for x in value):
        raise SceneError(path, where, f"expected a list of {what} names (text), got {value!r}")
    return tuple(value)


def cp_coefficients(value, path, where) -> tuple:
    """The cp polynomial: a list of 1 to 6 finite numbers (a, b, c, d, e, f).

    >>> cp_coefficients("29", "s.toml", "species[0].cp")
    Traceback (most recent call last):
    ...
    cases.scene.errors.SceneError: s.toml: species[0].cp: expected a list of 1 to 6 numbers (a, b, c, d, e, f), got '29'
    """
    if (not isinstance(value, (list, tuple)) or not 1 <= len(value) <= 6
            or not all(_number(x) for x in value)):
        raise SceneError(path, where, f"expected a list of 1 to 6 numbers (a, b, c, d, e, f), got {value!r}")
    return tuple(float(x) for x in value)


def table_value(value, path, where, *, allow_none: bool = True):
    """A scene built in Python: a number, a :class:`~cavity.tables.Table` (or None where optional)."""
    if value is None and allow_none:
        return value
    if isinstance(value, Table) or _number(value):
        return value
    raise SceneError(path, where, f"expected a finite number or a Table (in a TOML file: a CSV file name), "
                                  f"got {value!r}")
