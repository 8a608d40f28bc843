#!/usr/bin/env python3
"""The exact rod model of cantact, vectorised with NumPy, for the speed comparison of issue 6.

Stage rods of a depth-N prefractal (docs/model.md sections 2-4: rod i < N has its top at
h_i = h0 fz^-i, area s_i = l0 (1 - 1/fx) fx^-i, the tip rod N has area l_N = l0 fx^-N; all
rods reach down to H*), elastic-perfectly-plastic, virgin before each impact. For every
velocity at once: u_max from the closed-form loading work W(u) = sum E s L w((u - h)/L) by
bisection (64 halvings of [0, H*], below double resolution), then the recoverable energy
sum E s L min(d, eps_y)^2 / 2 and e = sqrt(W_unload / W_load), e = 1 where no rod yields.

This is an independent implementation (it shares no code with cantact): scripts/bench
compares its e with cantact's, row by row, besides timing it.

Usage: numpy_sweep.py N FX FZ HSTAR E_OVER_SIGMA VMIN VMAX COUNT [CANTACT_CSV]
Prints: numpy_seconds=<median of 5> velocities=<count> [max_abs_e_difference=<...>]
"""
import sys
import time

import numpy as np


def sweep(N, fx, fz, H, E, V):
    l0 = h0 = 1.0
    sigma_y = 1.0
    eps_y = sigma_y / E
    i = np.arange(N + 1, dtype=np.float64)
    top = h0 * fz ** -i
    area = l0 * (fx - 1.0) / fx * fx ** -i
    area[N] = l0 * fx ** -float(N)
    L = H - top
    k = E * area * L  # work scale per rod
    W = V * V * (l0 * E * h0)  # kinetic energies, one per velocity

    def work(u):  # u: (velocities, 1) -> (velocities,)
        d = np.maximum((u - top) / L, 0.0)
        w = np.where(d <= eps_y, 0.5 * d * d, eps_y * (d - 0.5 * eps_y))
        return (k * w).sum(axis=1)

    lo = np.zeros_like(W)
    hi = np.full_like(W, H)
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        below = work(mid[:, None]) <= W
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    u = 0.5 * (lo + hi)[:, None]
    d = np.maximum((u - top) / L, 0.0)
    W_load = work(u)
    W_unload = (0.5 * k * np.minimum(d, eps_y) ** 2).sum(axis=1)
    e = np.sqrt(W_unload / W_load)
    return np.where((d > eps_y).any(axis=1), e, 1.0)


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
        e = sweep(N, fx, fz, H, E, V)
        times.append(time.perf_counter() - t0)
    out = "numpy_seconds=%.6g velocities=%d" % (float(np.median(times[1:])), count)
    if len(sys.argv) == 10:
        ours = np.genfromtxt(sys.argv[9], delimiter=",", names=True)
        out += " max_abs_e_difference=%.3g" % float(np.max(np.abs(ours["e"] - e)))
    print(out)


if __name__ == "__main__":
    main()
