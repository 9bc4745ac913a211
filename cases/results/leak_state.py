"""The state of a blocked leakage surface at a time t: one definition shared by history.csv's area and blocked
fraction, the pictures and the VTK series.

The leakage area is the solver's: the exchange's area track (:class:`cases.model.area_track.AreaTrack`) at the geometry
parameter θ(t) (t itself, or the dynamic body's displacement), i.e. the obstruction of the active set found by the
crossing search, ``A_leak = A_total − (1 − permeability)·A_obstructed`` (or ``effective_area·(1 − …)``,
:func:`blockage.areas.leak_area`). The active nodes and the blocked fraction of each face (``N_c / N_e``) come
from the same active set (``track.active_at(θ)``); the node gaps drawn and written (the distance to the nearest
blocking face) from :func:`blockage.evaluate` on the surface placed at θ. The blocked fraction of the exchange is
``1 − A_leak / A_open`` with ``A_open`` the leakage area of the same surface with no node active.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import blockage
from blockage.areas import active_counts


__all__ = ["LeakState", "theta_at", "thetas_at", "leak_area_at", "open_area_at", "leak_state"]


@dataclass(frozen=True)
class LeakState:
    """Exchange ``j``'s leakage surface at time ``t`` [s]: ``surface`` (placed at θ), ``active (n,) bool``,
    ``face_fraction (m,)`` N_c/N_e, ``distances (n,)`` [m] (inf beyond 4 × the contact tolerance),
    ``leak_area`` and ``open_area`` [m^2]."""

    t: float
    surface: object
    active: np.ndarray
    face_fraction: np.ndarray
    distances: np.ndarray
    leak_area: float
    open_area: float

    @property
    def blocked_fraction(self) -> float:
        """``1 − A_leak / A_open`` [-] (0 with no open area)."""
        return 1.0 - self.leak_area / self.open_area if self.open_area > 0.0 else 0.0


def theta_at(model, trajectory, t: float) -> float:
    """The geometry parameter at time t: t itself, or the dynamic body's displacement [m]."""
    driver = model.geometry["driver"]
    return t if driver.dynamic is None else float(trajectory(t)[model.network.body_offset])


def thetas_at(model, trajectory, times) -> np.ndarray:
    """:func:`theta_at` at many sorted times at once (one read of the trajectory)."""
    times = np.asarray(times, dtype=float)
    if model.geometry["driver"].dynamic is None:
        return times.copy()
    return trajectory.sample(times)[:, model.network.body_offset]


def leak_area_at(track, theta: float) -> float:
    """The track's leakage area at θ [m^2] (what the solver uses: :meth:`AreaTrack.__call__`)."""
    return float(track(theta))


def open_area_at(track, theta: float) -> float:
    """The track's leakage area at θ with no node active [m^2]."""
    return track.open_area(theta)


def leak_state(model, trajectory, j: int, t: float) -> LeakState:
    """Exchange ``j``'s leakage surface and its blockage at time ``t`` [s] (see the module docstring)."""
    geo, spec = model.geometry, model.scene.exchange[j]
    surface, positions = geo["surfaces"][j]
    track = geo["areas"][j].track
    th = theta_at(model, trajectory, t)
    leak = surface.with_vertices(positions(th, None))
    tol = spec.contact_tolerance
    res = blockage.evaluate(leak, geo["driver"].placed(spec.blocked_by)(th), tol, cutoff=4 * tol)
    active = np.asarray(track.active_at(th), dtype=bool)
    if hasattr(track.source, "face_fractions"):  # an FE code's rule: its own face fractions (whole elements, SDFBLK)
        fraction = track.source.face_fractions(th)
    else:
        fraction = active_counts(active, leak.faces, leak.face_sizes) / np.asarray(leak.face_sizes, dtype=float)
    return LeakState(t, leak, active, np.clip(fraction, 0.0, 1.0), res.distances, leak_area_at(track, th),
                     open_area_at(track, th))
