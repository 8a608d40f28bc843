#!/usr/bin/python3
"""The numbers behind scripts/sphere_continuum (docs/validation.md, "A smooth sphere: the rods
beside the continuum"): a rigid steel ball on a smooth Winkler bed of rods (the CLI's results on
a grid of point rods, and the bed's closed forms of docs/model.md §14) beside a rigid ball on an
elastic-perfectly-plastic half-space: Hertz's loading and Thornton's (1997) restitution.

Usage: sphere_continuum.py params           the parameters, as shell assignments
       sphere_continuum.py analyse OUTDIR    from the CLI's outputs in OUTDIR: the reference
                                             curves (loading.csv, restitution.csv), the CLI's
                                             loading in newtons (curve_load.csv), the fits and
                                             the grid's error (fits.gp, summary.md); exit 1
                                             when a check fails
"""
import csv
import math
import os
import sys

import numpy as np
from scipy.optimize import brentq

# A steel ball on a steel-like bed: E, Poisson's ratio, yield stress, radius, density
E, NU, SIGMA_Y, R, RHO = 2e11, 0.3, 4e8, 5e-3, 7850.0
MASS = 4.0 / 3.0 * math.pi * R**3 * RHO
# the ball is rigid, so the contact's effective modulus is the half-space's alone
E_STAR = E / (1.0 - NU**2)
# Thornton's limiting contact pressure: the rods' own yield stress
P_LIMIT = SIGMA_Y
# Thornton's yield onset: the Hertzian maximum pressure 2 E* a / (pi R) reaches p_y
A_Y = math.pi * R * P_LIMIT / (2.0 * E_STAR)
DELTA_Y = A_Y**2 / R
P_Y = 4.0 / 3.0 * E_STAR * math.sqrt(R) * DELTA_Y**1.5
V_Y = math.sqrt(2.0 * (0.4 * P_Y * DELTA_Y) / MASS)  # (2/5) P_y delta_y = (1/2) m v_y^2
# the rods' length L: their elastic P(u) = (E/L) pi (R u^2 - u^3/3) meets Hertz's at (delta_y, P_y)
LENGTH = E * math.pi * (R * DELTA_Y**2 - DELTA_Y**3 / 3.0) / P_Y
U_Y = SIGMA_Y / E * LENGTH
# the grid: point rods of spacing SPACING (and half of it) on a disc of radius DISC about the
# apex; the speeds; the impacts whose load curves are compared with the closed forms
SPACING, DISC = 1e-6, 5e-4
SPEEDS = (1e-4, 1.0, 41)
CURVE_SPEEDS = (0.01, 1.0)
TOP_DECADE = (0.1, 1.0)
# the scene's reference scales (u in H0, P in SIGMA_Y L0)
H0, L0 = 1e-6, 1e-6
# stated bounds on the 1 um grid's relative error in P(u) (u/u_y bands) and absolute in e
P_BANDS = ((0.1, 0.3, 3e-3), (0.3, 1.0, 1e-3), (1.0, 10.0, 3e-4), (10.0, 1e3, 2e-4))
E_BOUND = 2e-4


def rods_force(u):
    """P(u) [N] of the smooth bed under the sphere, the continuum limit (docs/model.md §14)."""
    if u <= U_Y:
        return E / LENGTH * math.pi * (R * u * u - u**3 / 3.0)
    s = u - U_Y
    return math.pi * SIGMA_Y * (2.0 * R * s - s * s + (R - u) * U_Y + 2.0 / 3.0 * U_Y**2)


def rods_work(u):
    """W_load(u) [J]: the integral of rods_force from 0 to u."""
    k = E / LENGTH * math.pi
    if u <= U_Y:
        return k * (R * u**3 / 3.0 - u**4 / 12.0)
    s = u - U_Y
    return k * (R * U_Y**3 / 3.0 - U_Y**4 / 12.0) + math.pi * SIGMA_Y * (
        R * s * s - s**3 / 3.0 - U_Y * s * s / 2.0 + (R * U_Y - U_Y**2 / 3.0) * s)


def rods_recovered(u):
    """W_unload(u) [J]: the elastic energy the rods hold at u_max = u, sum of E s L
    min(eps, eps_y)^2 / 2 over the bed, dA = 2 pi (R - f) df."""
    k = E / LENGTH * math.pi
    if u <= U_Y:
        return k * ((R - u) * u**3 / 3.0 + u**4 / 4.0)
    s = u - U_Y
    return k * (U_Y**2 * (R * s - s * s / 2.0) + (R - u) * U_Y**3 / 3.0 + U_Y**4 / 4.0)


def rods_e(v):
    """e of the smooth bed (continuum) at impact speed v [m/s]: e = sqrt(W_unload / W_load)."""
    w = 0.5 * MASS * v * v
    hi = U_Y
    while rods_work(hi) < w:
        hi *= 2.0
    u = brentq(lambda x: rods_work(x) - w, 0.0, hi, xtol=1e-300, rtol=1e-15, maxiter=500)
    return min(1.0, math.sqrt(rods_recovered(u) / rods_work(u))), u


def hertz_force(d):
    return 4.0 / 3.0 * E_STAR * math.sqrt(R) * d**1.5


def thornton_force(d):
    """Thornton's loading: Hertz to delta_y, then P_y + pi p_y R (delta - delta_y)."""
    return hertz_force(d) if d <= DELTA_Y else P_Y + math.pi * P_LIMIT * R * (d - DELTA_Y)


def thornton_e(v):
    """Thornton (1997), Eq. for e of an elastic-perfectly-plastic sphere, v > v_y."""
    if v <= V_Y:
        return 1.0
    r = V_Y / v
    return (math.sqrt(6.0 * math.sqrt(3.0) / 5.0) * math.sqrt(1.0 - r * r / 6.0) *
            (r / (r + 2.0 * math.sqrt(6.0 / 5.0 - r * r / 5.0)))**0.25)


def thornton_e_from_rules(v):
    """The same e from Thornton's loading and unloading rules, energies in closed form: loading
    as thornton_force; unloading Hertzian with the contact's radius of curvature R_p = 4 E* a^3 /
    (3 P_max) at a^2 = R delta_max, which gives back 3 P_max^2 / (10 E* a)."""
    w = 0.5 * MASS * v * v
    w_y = 0.4 * P_Y * DELTA_Y
    k = math.pi * P_LIMIT * R
    x = (w - w_y) / (0.5 * P_Y + 0.5 * math.sqrt(P_Y * P_Y + 2.0 * k * (w - w_y)))
    p_max, a = P_Y + k * x, math.sqrt(R * (DELTA_Y + x))
    return math.sqrt(3.0 * p_max**2 / (10.0 * E_STAR * a) / w)


def speeds():
    lo, hi, n = SPEEDS
    return np.geomspace(lo, hi, n)


def params():
    for name, value in (("E", E), ("nu", NU), ("sigma_y", SIGMA_Y), ("radius", R),
                        ("mass", MASS), ("Estar", E_STAR), ("delta_y", DELTA_Y), ("P_y", P_Y),
                        ("v_y", V_Y), ("L", LENGTH), ("u_y", U_Y), ("spacing", SPACING),
                        ("disc", DISC), ("h0", H0), ("l0", L0)):
        print("%s=%.17g" % (name, value))
    print("speeds=%.17g:%.17g:%d:log" % SPEEDS)
    print("curve_speeds='%s'" % ", ".join("%.17g" % v for v in CURVE_SPEEDS))


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def curve_errors(rows):
    """Load branch of a CLI curve: [(u/u_y, relative error against the closed form)]."""
    out = []
    for r in rows:
        u = float(r["u_over_h0"]) * H0
        if r["branch"] != "load" or u <= 0.0:
            continue
        p = float(r["P_over_PY"]) * SIGMA_Y * L0
        out.append((u / U_Y, abs(p / rods_force(u) - 1.0)))
    return out


def band_max(errors, lo, hi):
    sel = [e for x, e in errors if lo <= x < hi]
    return max(sel) if sel else float("nan")


def slope(x, y):
    return np.polyfit(np.log(x), np.log(y), 1)[0]


def analyse(out):
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    # 1. Thornton's formula against his rules, over the speeds above v_y
    v_all = speeds()
    rules = max(abs(thornton_e(v) / thornton_e_from_rules(v) - 1.0) for v in v_all if v > V_Y)
    check(rules < 1e-12, "Thornton's formula against his loading and unloading rules: %.3g" % rules)

    # 2. the grids' P(u) against the closed forms, by band of u/u_y; both grids
    grids = {}
    for tag, h in (("1um", SPACING), ("05um", SPACING / 2)):
        errs = curve_errors(read_csv(os.path.join(out, "loadcurve_%s_curve.csv" % tag)))
        grids[tag] = [band_max(errs, lo, hi) for lo, hi, _ in P_BANDS]
    for (lo, hi, bound), e1, e2 in zip(P_BANDS, grids["1um"], grids["05um"]):
        check(e1 < bound, "P(u) on the 1 um grid, u/u_y in [%g, %g): %.3g >= %g" % (lo, hi, e1, bound))
        if not math.isnan(e2):
            check(e2 < e1 / 2, "halving the spacing: u/u_y in [%g, %g): %.3g, then %.3g" % (lo, hi, e1, e2))

    # 3. e of both grids against the continuum
    e_rows = {tag: read_csv(os.path.join(out, "e_%s.csv" % tag)) for tag in ("1um", "05um")}
    v_cli = np.array([float(r["v_impact_m_per_s"]) for r in e_rows["1um"]])
    e_cli = np.array([float(r["e"]) for r in e_rows["1um"]])
    e_half = np.array([float(r["e"]) for r in e_rows["05um"]])
    e_cont = np.array([rods_e(v)[0] for v in v_cli])
    de1, de2 = np.max(np.abs(e_cli - e_cont)), np.max(np.abs(e_half - e_cont))
    check(de1 < E_BOUND, "e on the 1 um grid against the bed's closed form: %.3g >= %g" % (de1, E_BOUND))
    check(de2 < de1 / 2, "halving the spacing: |de| %.3g, then %.3g" % (de1, de2))

    # 4. slopes: loading (elastic: CLI over [0.1, 1] u_y; plastic: the top decade of u of the
    # largest impact), e over the top decade of speeds
    load = [r for r in read_csv(os.path.join(out, "loadcurve_1um_curve.csv")) if r["branch"] == "load"]
    top_v = float(load[-1]["V_star"])
    u = np.array([float(r["u_over_h0"]) * H0 for r in load if float(r["V_star"]) == top_v])
    p = np.array([float(r["P_over_PY"]) * SIGMA_Y * L0 for r in load if float(r["V_star"]) == top_v])
    el = (u >= 0.1 * U_Y) & (u <= U_Y)
    pl = u >= u.max() / 10
    s_el, s_pl = slope(u[el], p[el]), slope(u[pl], p[pl])
    d_pl = np.geomspace(u.max() / 10, u.max(), 50)
    s_th_pl = slope(d_pl, [thornton_force(d) for d in d_pl])
    top = (v_cli >= TOP_DECADE[0] * (1 - 1e-9)) & (v_cli <= TOP_DECADE[1] * (1 + 1e-9))
    s_rods = slope(v_cli[top], e_cli[top])
    s_cont = slope(v_cli[top], e_cont[top])
    v_top = np.geomspace(*TOP_DECADE, 50)
    s_th = slope(v_top, [thornton_e(v) for v in v_top])
    check(abs(s_el - 2.0) < 0.01, "rods' elastic loading slope %.4f, not 2" % s_el)
    check(abs(s_rods + 0.5) < 0.02, "rods' e slope over the top decade %.4f, not -1/2" % s_rods)
    check(abs(s_rods - s_cont) < 1e-3, "rods' e slope %.5f against the closed form's %.5f" % (s_rods, s_cont))
    check(abs(s_th + 0.25) < 0.01, "Thornton's e slope over the top decade %.4f, not -1/4" % s_th)

    # the reference curves for the plot, and the CLI's loading in newtons
    u_max = u.max()
    with open(os.path.join(out, "loading.csv"), "w") as f:
        f.write("u_m,P_rods_closed_form_N,P_hertz_N,P_thornton_N\n")
        for x in np.geomspace(0.05 * DELTA_Y, u_max, 400):
            f.write("%.9g,%.9g,%.9g,%.9g\n" % (x, rods_force(x), hertz_force(x), thornton_force(x)))
    with open(os.path.join(out, "curve_load.csv"), "w") as f:
        f.write("u_m,P_N\n")  # thinned to log-spaced points for the plot
        for k in sorted(set(np.searchsorted(u, np.geomspace(0.05 * DELTA_Y, u_max, 120)))):
            if k < len(u):
                f.write("%.9g,%.9g\n" % (u[k], p[k]))
    # the far-above-yield forms: rods e^2 -> u_y / u_max with pi R sigma_y u_max^2 = m v^2 / 2;
    # Thornton's e -> sqrt(6 sqrt3 / 5) (v_y / (2 sqrt(6/5) v))^(1/4)
    rods_far = lambda v: math.sqrt(U_Y / (v * math.sqrt(MASS / (2 * math.pi * R * SIGMA_Y))))
    th_far = lambda v: math.sqrt(6 * math.sqrt(3) / 5) * (V_Y / (2 * math.sqrt(1.2) * v))**0.25
    with open(os.path.join(out, "restitution.csv"), "w") as f:
        f.write("v_m_per_s,e_rods_closed_form,e_thornton,e_rods_far,e_thornton_far\n")
        for v in np.geomspace(SPEEDS[0], SPEEDS[1], 400):
            f.write("%.9g,%.9g,%.9g,%.9g,%.9g\n" % (v, rods_e(v)[0], thornton_e(v), rods_far(v), th_far(v)))

    # first yield of the rods (the apex rod at u_y)
    v_y_rods = math.sqrt(2 * rods_work(U_Y) / MASS)
    at = lambda v: (float(np.interp(np.log(v), np.log(v_cli), e_cli)), thornton_e(v))
    with open(os.path.join(out, "fits.gp"), "w") as f:
        for name, value in (("s_el", s_el), ("s_pl", s_pl), ("s_th_pl", s_th_pl), ("s_rods", s_rods),
                            ("s_th", s_th), ("v_y", V_Y), ("v_y_rods", v_y_rods),
                            ("delta_y", DELTA_Y), ("P_y", P_Y), ("u_y", U_Y), ("L", LENGTH),
                            ("u_max", u_max)):
            f.write("%s = %.17g\n" % (name, value))
    n1 = sum(1 for _ in open(os.path.join(out, "rods_1um.csv"))) - 1
    n2 = sum(1 for _ in open(os.path.join(out, "rods_05um.csv"))) - 1
    lines = [
        "| quantity | value |", "|---|---|",
        "| ball | steel: R = %g mm, rho = %g kg/m^3, m = %.4g g, rigid |" % (R * 1e3, RHO, MASS * 1e3),
        "| half-space (Hertz, Thornton) | E = %g GPa, nu = %g: E* = E/(1 - nu^2) = %.4g GPa; p_y = sigma_y = %g MPa |"
        % (E / 1e9, NU, E_STAR / 1e9, P_LIMIT / 1e6),
        "| Thornton's yield onset | a_y = %.4g um, delta_y = %.4g nm, P_y = %.4g N, v_y = %.4g mm/s |"
        % (A_Y * 1e6, DELTA_Y * 1e9, P_Y, V_Y * 1e3),
        "| rods | E = %g GPa, sigma_y = %g MPa, L = H* = %.4g um (P(delta_y) = P_y), u_y = eps_y L = %.4g nm = %.4g delta_y, first yield at %.4g mm/s = %.4g v_y |"
        % (E / 1e9, SIGMA_Y / 1e6, LENGTH * 1e6, U_Y * 1e9, U_Y / DELTA_Y, v_y_rods * 1e3, v_y_rods / V_Y),
        "| grid | point rods on a square lattice of spacing %g um inside a disc of radius %g mm: %d rods (halved: %d) |"
        % (SPACING * 1e6, DISC * 1e3, n1, n2),
        "| P(u) error, 1 um grid (0.5 um) | " + "; ".join(
            "u/u_y in [%g, %g): %.2g (%s)" % (lo, hi, e1, "%.2g" % e2 if not math.isnan(e2) else "-")
            for (lo, hi, _), e1, e2 in zip(P_BANDS, grids["1um"], grids["05um"])) + " |",
        "| e error against the bed's closed form | 1 um: %.2g; 0.5 um: %.2g (largest over the speeds) |" % (de1, de2),
        "| loading slopes | rods %.4f for u in [0.1, 1] u_y (Hertz 1.5); top decade of u: rods %.4f, Thornton %.4f |"
        % (s_el, s_pl, s_th_pl),
        "| e slopes, %g..%g m/s | rods %.4f (the bed's closed form %.4f), Thornton %.4f |"
        % (TOP_DECADE[0], TOP_DECADE[1], s_rods, s_cont, s_th),
        "| e at 0.01, 0.1, 1 m/s | rods %s; Thornton %s |" % (
            ", ".join("%.3f" % at(v)[0] for v in (0.01, 0.1, 1.0)),
            ", ".join("%.3f" % at(v)[1] for v in (0.01, 0.1, 1.0))),
        "| u_max at 1 m/s | %.4g um = %.4g u_y (strain %.3g at the apex) |"
        % (rods_e(1.0)[1] * 1e6, rods_e(1.0)[1] / U_Y, rods_e(1.0)[1] / LENGTH),
        "| Thornton's formula against his rules | %.2g (largest relative difference) |" % rules,
    ]
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    for what in failures:
        print("sphere_continuum: check failed: " + what, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    if sys.argv[1:] == ["params"]:
        params()
    elif len(sys.argv) == 3 and sys.argv[1] == "analyse":
        sys.exit(analyse(sys.argv[2]))
    else:
        sys.exit(__doc__)
