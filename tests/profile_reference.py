#!/usr/bin/env python3
"""An independent reference for a measured line profile (docs/model.md section 9), in NumPy: it
shares no code with cantact. Reads a two-column profile (non-numeric lines skipped), removes
the least-squares line (every sample weighing the same), Rq = the width-weighted rms about the
width-weighted mean (the integral definition on a non-uniform sampling), builds the rods (top depth t_j = max z - z_j, width: half the distance
to the two neighbours, an end sample the distance to its one neighbour; length H* - t_j), and
for each speed v [m/s] of a body of mass m per unit depth finds u_max from the closed-form
loading work by bisection (64 halvings), then e = sqrt(W_unload / W_load) (1 when no rod
yields), and V* = v sqrt(m / (2 l0 E h0)), h0 = Rt, l0 = the summed widths.

Usage: profile_reference.py PROFILE UNIT H E SIGMA_Y MASS V1 [V2 ...]
Prints CSV: v_m_per_s,V_star,e,u_max_m then a line "# Rq Rt l0" with those numbers.
"""
import sys

import numpy as np


def read(path, unit):
    rows = []
    with open(path, "rb") as f:
        for raw in f:
            fields = [s for s in raw.decode("latin-1").replace(",", " ").split() if s]
            try:
                rows.append([float(s) for s in fields[:2]])
            except ValueError:
                continue
    a = np.array([r for r in rows if len(r) == 2])
    return a[:, 0] * unit, a[:, 1] * unit


def main():
    path, unit, H, E, sy, m = sys.argv[1], float(sys.argv[2]), *map(float, sys.argv[3:7])
    v = np.array([float(s) for s in sys.argv[7:]])
    x, z = read(path, unit)
    slope, icpt = np.polyfit(x, z, 1)
    z = z - (slope * x + icpt)
    w = np.empty_like(x)
    w[1:-1] = 0.5 * (x[2:] - x[:-2])
    w[0] = x[1] - x[0]
    w[-1] = x[-1] - x[-2]
    l0 = w.sum()
    zbar = np.sum(w * z) / l0
    Rq = np.sqrt(np.sum(w * (z - zbar) ** 2) / l0)
    top = z.max() - z
    Rt = top.max()
    Hs = H * Rt
    L = Hs - top
    k = E * w * L
    ey = sy / E
    V = v * np.sqrt(m / (2.0 * l0 * E * Rt))
    W = 0.5 * m * v * v

    def work(u):
        d = np.maximum((u - top) / L, 0.0)
        return (k * np.where(d <= ey, 0.5 * d * d, ey * (d - 0.5 * ey))).sum(axis=1)

    lo = np.zeros_like(W)
    hi = np.full_like(W, Hs)
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        below = work(mid[:, None]) <= W
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    u = 0.5 * (lo + hi)
    d = np.maximum((u[:, None] - top) / L, 0.0)
    Wl = work(u[:, None])
    Wu = (0.5 * k * np.minimum(d, ey) ** 2).sum(axis=1)
    e = np.where((d > ey).any(axis=1), np.sqrt(Wu / Wl), 1.0)
    print("v_m_per_s,V_star,e,u_max_m")
    for row in zip(v, V, e, u):
        print("%.17g,%.17g,%.17g,%.17g" % row)
    print("# %.17g %.17g %.17g" % (Rq, Rt, l0))


if __name__ == "__main__":
    main()
