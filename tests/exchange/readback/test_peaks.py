"""The peak search on the dense output (cases.results.readback.refine_peak): an interior peak is refined, a peak
at the first or last candidate time costs one probe when the pressure falls into the record, and a peak just
inside the first or last step is still found."""
from __future__ import annotations

import math

import numpy as np
import pytest

from cases.results.readback import refine_peak
from exchange.readback.peaks import EDGE_PROBE


class Counted:
    """p(t) [Pa] that counts its evaluations."""

    def __init__(self, f):
        self.f, self.calls = f, 0

    def __call__(self, t):
        self.calls += 1
        return self.f(t)


def search(f, ts):
    p = Counted(f)
    ts = np.asarray(ts, dtype=float)
    return refine_peak(ts, np.array([f(t) for t in ts]), p), p.calls


def test_interior_peak_is_refined_to_the_parabola_vertex():
    # p = 2e5 − 1e9 (t − 0.0123)², vertex between the candidates 0.01 and 0.02
    (p, t), calls = search(lambda t: 2e5 - 1e9 * (t - 0.0123) ** 2, [0.0, 0.01, 0.02, 0.03])
    assert p == pytest.approx(2e5, rel=1e-15) and t == pytest.approx(0.0123, rel=1e-7)
    assert calls > 3


@pytest.mark.parametrize("edge", ["first", "last"])
def test_a_peak_at_an_end_costs_one_probe_when_the_pressure_falls_inside(edge):
    # a blowdown p0·exp(−t/τ) (largest at the first time), a filling p∞(1 − exp(−t/τ)) (at the last)
    f = (lambda t: 8e5 * math.exp(-t / 3.0)) if edge == "first" else (lambda t: 1e5 * (1.0 - math.exp(-t / 3.0)))
    ts = np.linspace(0.0, 10.0, 11)
    (p, t), calls = search(f, ts)
    k = 0 if edge == "first" else -1
    assert (p, t) == (f(ts[k]), ts[k]) and calls == 1


@pytest.mark.parametrize("edge", ["first", "last"])
def test_a_peak_just_inside_the_end_step_is_searched(edge):
    # the pressure rises for 5 % of the first (last) step, then falls below the end value by the next candidate
    ts = np.linspace(0.0, 1.0, 11)
    at = 0.005 if edge == "first" else 0.995
    (p, t), calls = search(lambda t: 3e5 - 1e8 * (t - at) ** 2, ts)
    assert t == pytest.approx(at, rel=1e-7) and p == pytest.approx(3e5, rel=1e-15) and calls > 2


def test_the_probe_sits_inside_the_end_step():
    seen = []
    refine_peak(np.array([2.0, 3.0]), np.array([5.0, 1.0]), lambda t: seen.append(t) or 0.0)
    assert seen == [2.0 + EDGE_PROBE]
