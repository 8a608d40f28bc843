#!/usr/bin/env bash
# The claims of docs/validation.md, "A smooth sphere: the rods beside the continuum", on the
# page's grid (point rods of spacing 1 um, every top 0) under the page's ball (rigid steel,
# R = 5 mm) and layer (E 200 GPa, sigma_y 400 MPa, L chosen so the rods' elastic P(u) meets
# Hertz's at Thornton's yield onset), against references written here from the closed forms of
# docs/model.md §14: the CLI's P(u) within the page's stated error of the grid; the elastic
# loading's log-log slope 2 (Hertz: 3/2); e = 1 up to the rods' first yield, at 1.5 delta_y;
# e within the stated error of the bed's closed-form e, and the slope of log e against log v over
# the top decade (0.1 .. 1 m/s) within 0.02 of -1/2 and within 1e-3 of the closed form's.
# Usage: test_sphere_continuum.sh CANTACT SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
py=/usr/bin/python3

# the page's parameters, and L from Hertz's P at Thornton's yield onset (p_y = sigma_y)
read -r mass L < <($py -c '
import math
E, nu, sy, R, rho = 2e11, 0.3, 4e8, 5e-3, 7850.0
Es = E / (1 - nu * nu)
dy = (math.pi * R * sy / (2 * Es)) ** 2 / R
Py = 4 / 3 * Es * math.sqrt(R) * dy ** 1.5
print("%.17g %.17g" % (4 / 3 * math.pi * R ** 3 * rho, E * math.pi * (R * dy * dy - dy ** 3 / 3) / Py))')

# rods_DISC: point rods at (i, j) um inside a disc of DISC um, area 1 um^2, top 0
grid() {
    awk -v n="$1" 'BEGIN { print "x,y,top,area"
        for (i = -n; i <= n; i++) for (j = -n; j <= n; j++)
            if (i * i + j * j <= n * n) printf "%de-6,%de-6,0,1e-12\n", i, j }' >"$tmp/rods_$1.csv"
    cat >"$tmp/s_$1.ini" <<INI
[surface]
type = rods
file = rods_$1.csv
unit = m
Hstar = $L
h0 = 1e-6
l0 = 1e-6
[body]
shape = sphere
radius = 5e-3
position = 0, 0
[material]
E = 2e11
sigma_y = 4e8
[impact]
mass = $mass
INI
}

# 1. P(u) on a disc of 0.1 mm (the contact stays inside it up to 0.02 m/s, u_max = 6.4 u_y)
grid 100
"$ct" run -q "$tmp/s_100.ini" --set impact.velocity=0.02 --set output.what=e,curve \
    -o "$tmp/c.csv" 2>"$tmp/err" || bad "the curve run failed: $(cat "$tmp/err")"
# 2. e on the page's disc of 0.5 mm: just below and above the rods' first yield (1.957 mm/s),
# and the top decade
grid 500
top=$(awk 'BEGIN { for (k = 0; k <= 10; k++) printf ",%.17g", 10 ^ (k / 10 - 1) }')
"$ct" run -q "$tmp/s_500.ini" --set "impact.velocity=0.0019,0.002$top" -o "$tmp/e.csv" \
    2>"$tmp/err" || bad "the e run failed: $(cat "$tmp/err")"

$py - "$tmp/c_curve.csv" "$tmp/e.csv" "$L" "$mass" <<'PY' && ok || bad "the page's claims (above)"
import csv, math, sys
curve, etable, L, m = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
E, sy, R = 2e11, 4e8, 5e-3
uy = sy / E * L
k = E / L * math.pi
def force(u):  # the smooth bed's P(u) under the sphere
    if u <= uy:
        return k * (R * u * u - u ** 3 / 3)
    s = u - uy
    return math.pi * sy * (2 * R * s - s * s + (R - u) * uy + 2 / 3 * uy * uy)
def work(u):  # its integral
    if u <= uy:
        return k * (R * u ** 3 / 3 - u ** 4 / 12)
    s = u - uy
    return k * (R * uy ** 3 / 3 - uy ** 4 / 12) + math.pi * sy * (
        R * s * s - s ** 3 / 3 - uy * s * s / 2 + (R * uy - uy * uy / 3) * s)
def recovered(u):  # the rods' elastic energy at u_max = u
    if u <= uy:
        return work(u)
    s = u - uy
    return k * (uy * uy * (R * s - s * s / 2) + (R - u) * uy ** 3 / 3 + uy ** 4 / 4)
def e_bed(v):
    w, lo, hi = 0.5 * m * v * v, 0.0, L
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if work(mid) < w else (lo, mid)
    u = 0.5 * (lo + hi)
    return min(1.0, math.sqrt(recovered(u) / work(u)))
def slope(x, y):
    if len(x) < 5:
        return float("nan")
    x, y = [math.log(a) for a in x], [math.log(b) for b in y]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    return sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
fails = []
# the page's stated error of the 1 um grid, by band of u/u_y
bands = ((0.1, 0.3, 3e-3), (0.3, 1.0, 1e-3), (1.0, 10.0, 3e-4))
worst = [0.0] * len(bands)
count = [0] * len(bands)
us, ps = [], []
for r in csv.DictReader(open(curve)):
    u, p = float(r["u_over_h0"]) * 1e-6, float(r["P_over_PY"]) * sy * 1e-6
    if r["branch"] != "load" or u <= 0:
        continue
    for i, (lo, hi, _) in enumerate(bands):
        if lo <= u / uy < hi:
            worst[i] = max(worst[i], abs(p / force(u) - 1))
            count[i] += 1
    if 0.1 * uy <= u <= uy:
        us.append(u)
        ps.append(p)
for (lo, hi, bound), w, n in zip(bands, worst, count):
    if n < 20 or not w < bound:
        fails.append("P(u), u/u_y in [%g, %g): %d points, worst %.3g (stated %g)" % (lo, hi, n, w, bound))
s_el = slope(us, ps)
if not abs(s_el - 2) < 0.01:
    fails.append("elastic loading slope %.5f over %d points, not 2" % (s_el, len(us)))
rows = list(csv.DictReader(open(etable)))
v = [float(r["v_impact_m_per_s"]) for r in rows]
e = [float(r["e"]) for r in rows]
if not (e[0] == 1.0 and e[1] < 1.0):
    fails.append("e at 1.9 and 2.0 mm/s: %r, %r (first yield at 1.957 mm/s)" % (e[0], e[1]))
de = max(abs(a - e_bed(b)) for a, b in zip(e, v))
if not de < 2e-4:
    fails.append("e against the bed's closed form: %.3g (stated 2e-4)" % de)
s_rods, s_bed = slope(v[2:], e[2:]), slope(v[2:], [e_bed(x) for x in v[2:]])
if not (abs(s_rods + 0.5) < 0.02 and abs(s_rods - s_bed) < 1e-3):
    fails.append("slope of log e over 0.1 .. 1 m/s %.5f (closed form %.5f), not -1/2" % (s_rods, s_bed))
for f in fails:
    print("FAIL: " + f)
print("P(u) worst by band %s; elastic slope %.5f; |de| %.2g; e slope %.5f (closed form %.5f)"
      % (["%.2g" % w for w in worst], s_el, de, s_rods, s_bed))
sys.exit(1 if fails else 0)
PY

finish
