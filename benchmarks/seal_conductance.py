"""Cost of a seal's conductance curve against mesh size, and a 1 s run of a leaking vessel through closure.

A ring seal face (r = 20..25 mm, quads) under a rigid flat flange on linear penalty contact (1e13 Pa/m) with
Persson's gap law (u0 1 µm, p* 100 MPa, u_c 2 µm, h_max 10 µm), flat or tilted by 1e-5 rad. For each mesh:
the film's build (chart, element stiffness), the curve's build (Reynolds solves, knots) over s in [−4, 6] µm at
rtol 1e-3 (the default load tolerance rtol·range), one Reynolds solve, and one evaluation of the tabulated curve.
Then "1 s of physical time": a 1 L nitrogen vessel at 5 bar leaks through the 20k-node seal while the flange
closes as s(t) = −4 µm + 10 µm·t², integrated by scipy's DOP853 (rtol 1e-8) with the closure as a terminal
event; CPU for build + run. Process CPU seconds (time.process_time), this machine, shared.

With ``--picture PATH``: the channel height over the tilted 1,408-node ring 50 nm before the flange closes it
(docs/figures/seal_gap_field.png).

Requires: numpy, scipy; matplotlib for the picture.

Usage::

    PYTHONPATH=$PWD python benchmarks/seal_conductance.py [--picture docs/figures/seal_gap_field.png]
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from exchange.seal.conductance import conductance_curve  # noqa: E402
from exchange.seal.film import seal_film  # noqa: E402
from exchange.seal.gap_laws import PerssonGap  # noqa: E402
from exchange.seal.load_paths import DisplacementPath  # noqa: E402
from exchange.seal.meshes import annulus_mesh, flat_flange_seat  # noqa: E402
from exchange.seal.outputs import gap_picture, seal_outputs  # noqa: E402
from exchange.seal.reynolds import film_conductance  # noqa: E402

GAP = PerssonGap(u0=1e-6, p_star=1e8, u_c=2e-6, h_max=10e-6)
LAW = np.array([1.0, 1e13, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.025])
MESHES = ((10, 128), (20, 250), (40, 500))


def build(n_radial, n_angular, slope):
    """(film, curve, seconds: film, curve, one solve, one evaluation)."""
    t0 = time.process_time()
    v, f = annulus_mesh(0.020, 0.025, n_radial, n_angular)
    film = seal_film(v, f)
    t1 = time.process_time()
    path = DisplacementPath(flat_flange_seat(v, film.areas, 1e-6, slope=slope), LAW, GAP)
    curve = conductance_curve(film, path, -4e-6, 6e-6, rtol=1e-3)
    t2 = time.process_time()
    film_conductance(film, path.heights(0.0))
    t3 = time.process_time()
    for _ in range(1000):
        curve(1.5e-6)
    t4 = time.process_time()
    return film, curve, path, (t1 - t0, t2 - t1, t3 - t2, (t4 - t3) / 1000)


def vessel_run(curve):
    """CPU [s] and statistics of 1 s of a vessel leaking through the seal until the flange closes it."""
    V, R, T, mu, p_amb = 1e-3, 296.8, 293.15, 1.76e-5, 1.01325e5

    def s_of(t):
        return -4e-6 + 10e-6 * t * t

    def rhs(t, y):
        p = y[0] * R * T / V
        return [-curve(s_of(t)) * (p * p - p_amb * p_amb) / (24 * mu * R * T)]

    def closes(t, y):
        return s_of(t) - curve.closure
    closes.terminal = True
    t0 = time.process_time()
    run = solve_ivp(rhs, (0.0, 1.0), [5e5 * V / (R * T)], method="DOP853", rtol=1e-8, atol=1e-15, events=closes)
    return time.process_time() - t0, run


def picture(path):
    """Draw the tilted small ring's gap field 50 nm before closure; print its outputs."""
    film, curve, seat_path, _ = build(*MESHES[0], 1e-5)
    s = curve.closure - 0.05e-6
    print(f"50 nm before closure: {seal_outputs(film, seat_path, s, curve.closure)}")
    gap_picture(film, seat_path.heights(s), seat_path.in_contact(s), path,
                f"tilted flange 50 nm before closure (s* = {curve.closure * 1e6:.4f} µm)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", type=Path, help="draw the gap field of the tilted small ring here (PNG)")
    args = parser.parse_args(argv)
    if args.picture:
        picture(args.picture)
    print(f"{'nodes':>7} {'tilt':>6} {'film [s]':>9} {'curve [s]':>10} {'solves':>7} {'knots':>6} "
          f"{'1 solve [ms]':>13} {'eval [us]':>10} {'closure s* [um]':>16}")
    for n_radial, n_angular in MESHES:
        for slope in (0.0, 1e-5):
            film, curve, path, (t_film, t_curve, t_solve, t_eval) = build(n_radial, n_angular, slope)
            print(f"{film.n_nodes:7d} {slope:6.0e} {t_film:9.3f} {t_curve:10.3f} {curve.solves:7d} "
                  f"{len(curve.knots):6d} {t_solve * 1e3:13.1f} {t_eval * 1e6:10.1f} {curve.closure * 1e6:16.9f}")
    t_run, run = vessel_run(curve)
    total = t_film + t_curve + t_run
    print(f"1 s run, {film.n_nodes} nodes, tilted: closes at t = {run.t_events[0][0]:.12f} s "
          f"({run.nfev} RHS calls); CPU film {t_film:.2f} + curve {t_curve:.2f} + run {t_run:.3f} = {total:.2f} s")


if __name__ == "__main__":
    main()
