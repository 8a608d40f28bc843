#!/usr/bin/env python3
"""The exact rod model of cantact, one velocity at a time with scipy.optimize.brentq.

The baseline of issue 11: how a researcher would write the sweep in NumPy without thinking
about speed. Stage rods of a depth-N prefractal (docs/model.md sections 2-4: rod i < N has its top
at h_i = h0 fz^-i and area s_i = l0 (1 - 1/fx) fx^-i, the tip rod N has area l_N = l0 fx^-N;
every rod reaches down to H*, so L_i = H* - h_i), elastic-perfectly-plastic, virgin before
the impact; units sigma_y = l0 = h0 = 1, kinetic energy W = V*^2 l0 E h0 (docs/model.md section 1).
For each velocity: if W is at most the work to first yield (u_y = min_i h_i + eps_y L_i),
e = 1; otherwise u_max solves

    sum_i E s_i L_i w((u - h_i) / L_i) = W,   w(d) = 0 (d <= 0), d^2/2 (d <= eps_y),
                                                 eps_y (d - eps_y/2) beyond,

found by scipy.optimize.brentq on [0, H*) (rtol = 4 eps, the smallest brentq accepts, and a
tiny xtol, so u_max is within a few ulps), and e = sqrt(sum_i E s_i L_i min(d_i, eps_y)^2/2 / W)
(docs/model.md section 7). It shares no code with cantact nor with numpy_sweep.py (the vectorised
bisection): scripts/bench compares its e with cantact's row by row, besides timing it.

Timing covers the computation only (building the rods and solving every velocity), as in
numpy_sweep.py: not the interpreter start, the imports, reading arguments nor the CSV check.
It is the median of 5 timed runs after a warm-up run.

Usage: numpy_brentq.py N FX FZ HSTAR E_OVER_SIGMA VMIN VMAX COUNT [CANTACT_CSV]
Prints: numpy_seconds=<median of 5> velocities=<count> [max_abs_e_difference=<...>]
"""
import sys
import time

import numpy as np
from scipy.optimize import brentq


def rods(N, fx, fz, H):
    """Top depth, area and length of the N + 1 stage rods (l0 = h0 = 1)."""
    i = np.arange(N + 1, dtype=np.float64)
    top = fz ** -i
    area = (1.0 - 1.0 / fx) * fx ** -i
    area[N] = fx ** -float(N)
    return top, area, H - top


def restitution(N, fx, fz, H, E, V):
    eps_y = 1.0 / E  # sigma_y = 1
    top, area, L = rods(N, fx, fz, H)
    k = E * area * L

    def loading_work(u):
        d = (u - top) / L
        w = np.where(d <= 0.0, 0.0,
                     np.where(d <= eps_y, 0.5 * d * d, eps_y * (d - 0.5 * eps_y)))
        return np.sum(k * w)

    def elastic_energy(u):
        d = np.clip((u - top) / L, 0.0, eps_y)
        return np.sum(0.5 * k * d * d)

    W_yield = loading_work(np.min(top + eps_y * L))
    e = np.ones(len(V))
    for j, v in enumerate(V):
        W = v * v * E  # V*^2 l0 E h0
        if W <= W_yield:
            continue
        u_max = brentq(lambda u: loading_work(u) - W, 0.0, H,
                       xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=200)
        e[j] = np.sqrt(elastic_energy(u_max) / W)
    return e


def main():
    if len(sys.argv) not in (9, 10):
        sys.exit(__doc__.split("Usage: ")[1].split("\n")[0].join(["usage: ", ""]))
    N = int(sys.argv[1])
    fx, fz, H, E, vmin, vmax = map(float, sys.argv[2:8])
    count = int(sys.argv[8])
    V = np.geomspace(vmin, vmax, count)
    times = []
    for _ in range(6):  # a warm-up and 5 timed runs
        t0 = time.perf_counter()
        e = restitution(N, fx, fz, H, E, V)
        times.append(time.perf_counter() - t0)
    out = "numpy_seconds=%.6g velocities=%d" % (float(np.median(times[1:])), count)
    if len(sys.argv) == 10:
        ours = np.genfromtxt(sys.argv[9], delimiter=",", names=True)
        if "impact" in ours.dtype.names:
            ours = ours[ours["impact"] == 1]
        if len(ours) != count or np.max(np.abs(ours["V_star"] / V - 1)) > 1e-12:
            sys.exit("numpy_brentq.py: %s does not hold the same %d speeds" % (sys.argv[9], count))
        out += " max_abs_e_difference=%.3g" % float(np.max(np.abs(ours["e"] - e)))
    print(out)


if __name__ == "__main__":
    main()
