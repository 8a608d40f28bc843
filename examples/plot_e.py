#!/usr/bin/python3
"""e(V*) of three surfaces through the Python module, plotted with matplotlib (Agg: no
display needed). Usage: examples/plot_e.py [OUT.png]   (default e_three_surfaces.png)

From the build tree: CANTACT_LIBRARY=build/libcantact.so.0 PYTHONPATH=python examples/plot_e.py
After meson install, the module finds the installed library by itself."""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import cantact  # noqa: E402

V = np.geomspace(1e-5, 1e-2, 400)
E_over_sigma_y, H = 500.0, 10.0

# a rough profile of our own: a random walk (a self-affine profile, D = 1.5) sampled at
# 4096 points over l0 = 1, levelled so that its peak-to-valley depth is h0 = 1; every sample
# is a rod whose top lies (peak - z) below the highest point (docs/model.md §9)
rng = np.random.default_rng(2)
z = np.cumsum(rng.standard_normal(4096))
z -= np.polyval(np.polyfit(np.arange(z.size), z, 1), np.arange(z.size))  # detrend
top = (z.max() - z) / (z.max() - z.min())
surfaces = {
    "Cantor, $f_x$ = 1.5, $f_z$ = 1.3": cantact.Cantor(fx=1.5, fz=1.3, H=H, E=E_over_sigma_y),
    "random Cantor (spread 0.1, 0.05), depth 14":
        cantact.RandomCantor(fx=1.5, fz=1.3, H=H, E=E_over_sigma_y, depth=14, fx_spread=0.1,
                             fz_spread=0.05, seed=1),
    "a random-walk profile, 4096 rods":
        cantact.Rods(top, np.full(top.size, 1.0 / top.size), E=E_over_sigma_y, Hstar=H),
}

fig, ax = plt.subplots(figsize=(7, 4.2), dpi=110)
for label, surface in surfaces.items():
    r = cantact.restitution(surface, V_star=V)
    line, = ax.semilogx(V, r.e[:, 0], label=label)
    ax.plot(r.V_star_crit[0, 0], 1.0, "o", color=line.get_color(), ms=4)
ax.set_xlabel(r"$V^* = \sqrt{m v_1^2 / (2 l_0 E h_0)}$")
ax.set_ylabel("coefficient of restitution e")
ax.set_title(r"e($V^*$), $E/\sigma_y$ = 500, $H^*/h_0$ = 10 (dots: $V^*_c$)", fontsize=10)
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8, loc="lower left")
fig.tight_layout()
out = sys.argv[1] if len(sys.argv) > 1 else "e_three_surfaces.png"
fig.savefig(out)
print(out)
