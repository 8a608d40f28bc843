#!/usr/bin/env python3
"""Scatter in LAMMPS (gran/hooke/history/cantact ... scatter SEED): each new contact takes e at
a probability p drawn from (SEED, its atoms' ids, its first step) from the quantile columns of
a table of samples (docs/dem.md, "Scatter: a table of samples"). Driven by test.sh.

    scatter_test.py --lib L --loader P --table SAMPLES.csv --plain-table E.csv --work DIR
                    --cantact-library libcantact.so.0 --cantact-python DIR
                    [--pairs 400] [--speed 0.5] [--v-per-V-star 1000] [--seed 2026]
                    [--dt 1e-8] [--alpha 0.01]

--pairs independent head-on pairs of 2 mm steel spheres (Kn = 1e5 N/m, no friction, no
gravity), all at the relative speed --speed, in one run at --dt; the table's speeds mapped by
--v-per-V-star (V* = speed / S). The references are the table's own reader (Python's
cantact.read_table, libcantact, which evaluates with cantact_table.h's functions) and a
Philox4x64-10 written here (checked against Random123's published known-answer vectors), never
the style's output. Checks (each fails the run):
  1. the distribution: the rebound ratios' empirical distribution against the table's at that
     speed, F(x) = P(Q(U) <= x), U uniform in [0, 1], Q the table's piecewise-linear quantile
     function: its values Q(p) at p = 0, the table's p_j and 1 by the reader (the clamped ends
     are atoms of F of mass p_first and 1 - p_last), linear in p between them (the reader's
     rule, checked here at points between). Kolmogorov-Smirnov: D_n = sup |F_n - F| must be
     below the critical value c(alpha) / sqrt(n) (c = 1.63 at alpha = 1 %, the asymptotic
     Kolmogorov value; conservative for an F with atoms). The drawn p (printed by `report`)
     must pass the same test against the uniform distribution;
  2. every contact: its p is this script's Philox4x64-10 of key (SEED, "scatter" in ASCII),
     counter (smaller id, larger id, first step, 0), (first word >> 11) 2^-53, to the bit; its e
     is the reader's quantile(V*, p) to the bit; its rebound ratio is that e within --tol (1e-4,
     the integrator's error at dt = 1e-8 s); every pair has separated;
  3. it can fail: the same KS test on the same rebounds against the table's mean alone (no
     scatter) and against its quantiles at 1.1 V* (a 10 % wrong v_per_V_star) must reject;
  4. two MPI ranks (`processors * 1 1`: every pair split across them, newton off, so both
     ranks set up each contact) give the serial run's final x and v to the bit (skipped, and
     said so, when mpirun cannot start 2 ranks);
  5. without `scatter` the same run rebounds with the table's mean e (the reader's, to the bit
     in the report, the ratios within --tol), and no p is reported;
  6. refusals at setup, one line each: `scatter` with a constant e, and with a table without
     quantile columns (--plain-table).
"""
import argparse
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from collide_test import Runner, read_final  # noqa: E402

R = 0.002          # m, sphere radius (both spheres)
RHO = 7800.0       # kg/m^3
KN = 1e5           # N/m
T0 = 1e-6          # s, flight before touching
MASS = RHO * 4.0 / 3.0 * math.pi * R ** 3
ROW = 20           # pairs per row of the y-z grid
PITCH = 0.006      # m between pairs in y and z

REPORT = re.compile(r"^cantact: contact (\d+) (\d+) step (\d+) v_n (\S+) e (\S+) zeta \S+ "
                    r"meff \S+ gamma_n \S+(?: p (\S+))?$", re.M)

# ---- Philox4x64-10 (Salmon et al., SC11; Random123's philox.h), written out here ----
MASK64 = (1 << 64) - 1
PHILOX_M = (0xD2E7470EE14C6C93, 0xCA5A826395121157)
PHILOX_W = (0x9E3779B97F4A7C15, 0xBB67AE8584CAA73B)
SCATTER_KEY = 0x73636174746572    # "scatter" in ASCII


def philox4x64_10(ctr, key):
    c, k = list(ctr), list(key)
    for rnd in range(10):
        if rnd:
            k = [(k[0] + PHILOX_W[0]) & MASK64, (k[1] + PHILOX_W[1]) & MASK64]
        p0, p1 = PHILOX_M[0] * c[0], PHILOX_M[1] * c[2]
        c = [(p1 >> 64) ^ c[1] ^ k[0], p1 & MASK64, (p0 >> 64) ^ c[3] ^ k[1], p0 & MASK64]
    return c


# Random123's known-answer vectors for philox4x64 with 10 rounds (its kat_vectors file)
PHILOX_KAT = (
    ((0, 0, 0, 0), (0, 0),
     (0x16554d9eca36314c, 0xdb20fe9d672d0fdc, 0xd7e772cee186176b, 0x7e68b68aec7ba23b)),
    ((0x243f6a8885a308d3, 0x13198a2e03707344, 0xa4093822299f31d0, 0x082efa98ec4e6c89),
     (0x452821e638d01377, 0xbe5466cf34e90c6c),
     (0xa528f45403e61d95, 0x38c72dbd566e9788, 0xa5a1610e72fd18b5, 0x57bd43b5e52b7fe6)),
)


def scatter_p(seed, tag_i, tag_j, step):
    """the p the style documents: a pure function of (seed, the pair, the first step)"""
    r = philox4x64_10((min(tag_i, tag_j), max(tag_i, tag_j), step, 0), (seed, SCATTER_KEY))
    return math.ldexp(float(r[0] >> 11), -53)


# ---- the table's distribution at one speed: F(x) = P(Q(U) <= x) ----
class Distribution:
    """Q piecewise linear through the knots (p_k, q_k), non-decreasing, p from 0 to 1"""

    def __init__(self, ps, qs):
        self.p, self.q = list(ps), list(qs)

    def cdf(self, x):
        """F(x) = sup{p: Q(p) <= x}"""
        p, q = self.p, self.q
        if x < q[0]:
            return 0.0
        if x >= q[-1]:
            return 1.0
        j = max(k for k in range(len(q)) if q[k] <= x)    # q[j] <= x < q[j + 1]
        return p[j] + (x - q[j]) / (q[j + 1] - q[j]) * (p[j + 1] - p[j])

    def cdf_left(self, x):
        """F(x-) = inf{p: Q(p) >= x}"""
        p, q = self.p, self.q
        if x <= q[0]:
            return 0.0
        if x > q[-1]:
            return 1.0
        j = min(k for k in range(len(q)) if q[k] >= x)    # q[j - 1] < x <= q[j]
        return p[j - 1] + (x - q[j - 1]) / (q[j] - q[j - 1]) * (p[j] - p[j - 1])


def ks_statistic(sample, dist):
    """D_n = sup_x |F_n(x) - F(x)| for a right-continuous F with atoms: at the order statistics
    x_(i), max(i/n - F(x_(i)), F(x_(i)-) - (i-1)/n), ties counted as steps of F_n"""
    xs = sorted(sample)
    n = len(xs)
    d = 0.0
    for i, x in enumerate(xs, 1):
        d = max(d, i / n - dist.cdf(x), dist.cdf_left(x) - (i - 1) / n)
    return d


def lammps_input(path, pair_style, dt, t_end, npairs, speed, final, loader, processors=True):
    """pair k: atoms 2k+1 (x < 0) and 2k+2 (x > 0) head-on along x at -+speed/2, touching at
    t = T0, on a grid in y and z; `processors * 1 1` cuts the box at x = 0 (on 2 ranks every
    pair is split across them)"""
    rows = (npairs + ROW - 1) // ROW
    L = ["units si", "atom_style sphere", "atom_modify map array", "boundary f f f", "newton off",
         "comm_modify vel yes", "neighbor 0.0002 bin", "neigh_modify delay 0 every 1 check yes"]
    if processors:
        L.append("processors * 1 1")
    L.append("region box block -0.02 0.02 -0.01 %.17g -0.01 %.17g units box"
             % (PITCH * ROW, PITCH * rows))
    L.append("create_box 1 box")
    gap = speed * T0
    for k in range(npairs):
        y, z = PITCH * (k % ROW), PITCH * (k // ROW)
        L.append("create_atoms 1 single %.17g %.17g %.17g units box" % (-(R + 0.5 * gap), y, z))
        L.append("create_atoms 1 single %.17g %.17g %.17g units box" % (R + 0.5 * gap, y, z))
    L.append("set group all diameter %.17g" % (2 * R))
    L.append("set group all density %.17g" % RHO)
    L.append("velocity all set 0 0 0 units box")
    L.append("group left id %s" % " ".join("%d" % (2 * k + 1) for k in range(npairs)))
    L.append("group right subtract all left")
    L.append("velocity left set %.17g 0 0 units box" % (0.5 * speed))
    L.append("velocity right set %.17g 0 0 units box" % (-0.5 * speed))
    L.append("python cantact_load input 2 SELF %s format ps file %s" % loader)
    L.append("python cantact_load invoke")
    L.append(pair_style)
    L.append("pair_coeff * *")
    L.append("fix integrate all nve/sphere")
    L.append("timestep %.17g" % dt)
    steps = int(round(t_end / dt))
    L.append("thermo %d" % max(steps, 1))
    L.append("run %d" % steps)
    L.append("write_dump all custom %s id x y z vx vy vz modify format float %%.17g sort id"
             % final)
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--lib", required=True, help="libcantact_lammps.so")
    ap.add_argument("--loader", required=True, help="cantact_load.py")
    ap.add_argument("--table", required=True, help="a table of samples (# quantiles)")
    ap.add_argument("--plain-table", required=True, help="a table without quantile columns "
                    "(for the refusal)")
    ap.add_argument("--work", required=True)
    ap.add_argument("--cantact-library", help="libcantact.so.0 (the reader; default: where "
                    "the cantact Python package looks)")
    ap.add_argument("--cantact-python", required=True, help="the directory of the cantact "
                    "Python package")
    ap.add_argument("--pairs", type=int, default=400)
    ap.add_argument("--speed", type=float, default=0.5, help="m/s, relative")
    ap.add_argument("--v-per-V-star", type=float, default=1000.0)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--dt", type=float, default=1e-8)
    ap.add_argument("--tol", type=float, default=1e-4)
    ap.add_argument("--alpha", type=float, default=0.01, choices=(0.05, 0.01, 0.001))
    ap.add_argument("--no-mpi", action="store_true")
    a = ap.parse_args()
    for p, what in ((a.lib, "--lib"), (a.loader, "--loader"), (a.table, "--table"),
                    (a.plain_table, "--plain-table"), (a.cantact_library, "--cantact-library")):
        if p is not None and not os.path.isfile(p):
            ap.error("%s %s: no such file" % (what, p))
    if not (a.pairs >= 20 and a.speed > 0 and a.v_per_V_star > 0 and a.dt > 0 and a.seed >= 0):
        ap.error("--pairs >= 20, --speed, --v-per-V-star, --dt > 0 and --seed >= 0")
    if a.cantact_library:
        os.environ["CANTACT_LIBRARY"] = os.path.abspath(a.cantact_library)
    sys.path.insert(0, os.path.abspath(a.cantact_python))
    import cantact  # noqa: E402  (the table's own reader)

    work = os.path.abspath(a.work)
    os.makedirs(work, exist_ok=True)
    loader = (os.path.abspath(a.lib), os.path.abspath(a.loader))
    table = os.path.abspath(a.table)
    mpirun = None
    if not a.no_mpi:
        import shutil
        if shutil.which("mpirun"):
            mpirun = ["mpirun", "--oversubscribe"]
            if hasattr(os, "geteuid") and os.geteuid() == 0:
                mpirun.append("--allow-run-as-root")
    runner = Runner(a.lmp, work, mpirun)
    failures = []
    counts = [0, 0]

    def check(ok, msg):
        counts[0 if ok else 1] += 1
        if not ok:
            failures.append(msg)

    # the generator written here reproduces Random123's published vectors
    for ctr, key, want in PHILOX_KAT:
        check(tuple(philox4x64_10(ctr, key)) == want, "this script's Philox4x64-10 misses "
              "Random123's known answer for counter %s" % (ctr,))

    # ---- the table's distribution at V* = speed / S, by its reader ----
    t = cantact.read_table(table)
    if t.p is None:
        raise SystemExit("scatter_test: %s has no quantile columns" % table)
    n = a.pairs
    S = a.v_per_V_star
    V = a.speed / S
    knots_p = [0.0] + [float(p) for p in t.p] + [1.0]

    def knots_at(Vs):
        return [float(x) for x in t.quantile(Vs, knots_p)]

    q = knots_at(V)
    dist = Distribution(knots_p, q)
    # the reader is linear in p between the knots (the rule F is built on)
    worst_lin = 0.0
    for k in range(len(knots_p) - 1):
        for w in (0.25, 0.5, 0.75):
            pm = knots_p[k] + w * (knots_p[k + 1] - knots_p[k])
            worst_lin = max(worst_lin, abs(float(t.quantile(V, pm)) - (q[k] + w * (q[k + 1] - q[k]))))
    check(worst_lin <= 1e-12, "the reader's Q(V*, p) is not linear in p between the table's p "
          "(%.3g off): the distribution below would not be the table's" % worst_lin)
    e_mean = float(t(V))
    print("table %s: %d quantile columns p = %g .. %g; at V* = %g (v = %g m/s, v_per_V_star %g): "
          "Q(0) = Q(%g) = %.6f, Q(0.5) = %.6f, Q(%g) = Q(1) = %.6f, mean e %.6f"
          % (os.path.basename(table), len(t.p), t.p[0], t.p[-1], V, a.speed, S, t.p[0], q[0],
             float(t.quantile(V, 0.5)), t.p[-1], q[-1], e_mean))

    # the run: the longest contact (the least e, the most damping; tension law) and a margin
    meff = MASS / 2.0
    l = -math.log(max(q[0], 1e-3))
    zeta = l / math.sqrt(math.pi ** 2 + l * l)
    t_end = T0 + 1.1 * math.pi / (math.sqrt(KN / meff) * math.sqrt(1.0 - zeta * zeta))
    frictionless = "%.17g 0.0 0.0 0.0 0" % KN

    def run(tag, extra, nproc=1):
        inp = os.path.join(work, "in." + tag)
        lammps_input(inp, "pair_style gran/hooke/history/cantact %s table %s v_per_V_star %.17g "
                     "report %d%s" % (frictionless, table, S, 2 * n, extra), a.dt, t_end, n,
                     a.speed, "final." + tag, loader)
        out = runner.run(tag, inp, nproc)
        atoms = read_final(os.path.join(work, "final." + tag))
        ratios, apart = [], True
        for k in range(n):
            a1, a2 = atoms[2 * k + 1], atoms[2 * k + 2]
            ratios.append((a2[3] - a1[3]) / a.speed)
            apart = apart and a2[0] - a1[0] > 2 * R
        return atoms, ratios, apart, REPORT.findall(out)

    # ---- 1, 2: the scatter run ----
    atoms1, ratios, apart, reps = run("scatter", " scatter %d" % a.seed)
    check(apart, "scatter: some spheres still in contact at the end")
    check(len(reps) == n and sorted((int(r[0]) - 1) // 2 for r in reps) == list(range(n)),
          "scatter: %d contacts reported, %d expected (one per pair)" % (len(reps), n))
    e_of_pair, p_drawn = {}, []
    bad_p = bad_e = 0
    for r in reps:
        i, j, step = int(r[0]), int(r[1]), int(r[2])
        vn, e = float(r[3]), float(r[4])
        if not r[5]:
            bad_p += 1
            continue
        p = float(r[5])
        p_drawn.append(p)
        if p != scatter_p(a.seed, i, j, step):
            bad_p += 1
        if e != float(t.quantile(vn / S, p)):
            bad_e += 1
        e_of_pair[(min(i, j) - 1) // 2] = e
    check(bad_p == 0, "scatter: %d contacts' p are not Philox4x64-10 of (seed, ids, step)" % bad_p)
    check(bad_e == 0, "scatter: %d contacts' e are not the reader's quantile(V*, p)" % bad_e)
    misses = [k for k in range(n) if k in e_of_pair and not abs(ratios[k] - e_of_pair[k]) <= a.tol]
    worst = max((abs(ratios[k] - e_of_pair[k]) for k in e_of_pair), default=math.nan)
    check(not misses and len(e_of_pair) == n, "scatter: %d rebound ratios off their contact's e "
          "by more than %g (worst %.3g)" % (len(misses), a.tol, worst))
    c_alpha = {0.05: 1.36, 0.01: 1.63, 0.001: 1.95}[a.alpha]
    crit = c_alpha / math.sqrt(n)
    D = ks_statistic(ratios, dist)
    D_p = ks_statistic(p_drawn, Distribution([0.0, 1.0], [0.0, 1.0])) if p_drawn else math.inf
    check(D < crit, "KS: the rebound ratios' distribution is not the table's: D = %.4f >= %.4f"
          % (D, crit))
    check(D_p < crit, "KS: the drawn p are not uniform: D = %.4f >= %.4f" % (D_p, crit))
    try:
        from scipy.stats import kstwo
        pval = lambda d: "p-value %.3g" % kstwo.sf(d, n)  # noqa: E731
    except ImportError:
        pval = lambda d: "p-value not computed (no SciPy)"  # noqa: E731
    print("scatter %d, %d head-on pairs at %g m/s, dt = %g s: every contact's p Philox4x64-10 of "
          "(seed, ids, first step) and its e the reader's Q(V*, p), bit for bit; rebound ratio - "
          "e: worst %.2e (tolerance %g)" % (a.seed, n, a.speed, a.dt, worst, a.tol))
    print("Kolmogorov-Smirnov, n = %d, alpha = %g: critical value %.2f / sqrt(n) = %.4f" %
          (n, a.alpha, c_alpha, crit))
    print("  rebound ratios against the table's Q at V* = %g: D = %.4f (%s): %s"
          % (V, D, pval(D), "accepted" if D < crit else "REJECTED"))
    print("  the drawn p against uniform [0, 1):            D = %.4f (%s): %s"
          % (D_p, pval(D_p), "accepted" if D_p < crit else "REJECTED"))
    lo, hi = sum(1 for p in p_drawn if p < t.p[0]), sum(1 for p in p_drawn if p > t.p[-1])
    print("  at the clamped ends: %d draws with p < %g took Q(%g) = %.6f, %d with p > %g took "
          "Q(%g) = %.6f (expected %.1f and %.1f)" % (lo, t.p[0], t.p[0], q[0], hi, t.p[-1],
                                                     t.p[-1], q[-1], n * t.p[0],
                                                     n * (1 - t.p[-1])))

    # ---- 3: it can fail ----
    D_mean = ks_statistic(ratios, Distribution([0.0, 1.0], [e_mean, e_mean]))
    D_far = ks_statistic(ratios, Distribution(knots_p, knots_at(1.1 * V)))
    check(D_mean >= crit, "negative control: the mean alone passed the KS test (D = %.4f)" % D_mean)
    check(D_far >= crit, "negative control: the quantiles at 1.1 V* passed the KS test (D = %.4f)"
          % D_far)
    print("  negative controls, the same rebounds against the table's mean alone: D = %.4f; "
          "against its Q at 1.1 V*: D = %.4f: %s"
          % (D_mean, D_far, "both rejected" if min(D_mean, D_far) >= crit else "NOT rejected"))

    # ---- 4: two MPI ranks ----
    if mpirun is None:
        print("MPI: SKIPPED (no mpirun, or --no-mpi)")
    else:
        import subprocess
        probe = subprocess.run(mpirun + ["-np", "2", "true"], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
        if probe.returncode != 0:
            print("MPI: SKIPPED (mpirun cannot start 2 ranks here)")
        else:
            atoms2, ratios2, _, _ = run("scatter.mpi2", " scatter %d" % a.seed, nproc=2)
            same = atoms2 == atoms1
            nsame = sum(1 for k in range(n) if ratios2[k] == ratios[k])
            check(same, "2 MPI ranks differ from 1 (%d of %d rebounds identical)" % (nsame, n))
            print("MPI: 2 ranks (every pair split across them, newton off): %d of %d rebounds "
                  "and every final x, v %s the serial run's" % (nsame, n, "identical to" if same
                                                                   else "NOT all identical to"))

    # ---- 5: without scatter, the mean ----
    _, ratios0, apart0, reps0 = run("mean", "")
    check(apart0, "mean: some spheres still in contact at the end")
    check(len(reps0) == n and all(not r[5] for r in reps0),
          "mean: %d contacts reported (%d expected), p reported without scatter" % (len(reps0), n))
    bad = sum(1 for r in reps0 if float(r[4]) != float(t(float(r[3]) / S)))
    check(bad == 0, "mean: %d contacts' e are not the reader's mean e" % bad)
    worst0 = max(abs(x - e_mean) for x in ratios0)
    check(worst0 <= a.tol, "mean: rebound ratios off the table's mean e %.9f by up to %.3g"
          % (e_mean, worst0))
    print("without scatter: every contact's e the table's mean %.9f (bit for bit the reader's), "
          "rebound ratios within %.2e of it" % (e_mean, worst0))

    # ---- 6: refusals at setup ----
    for tag, src, want in (("refuse.constant", "e 0.5", "scatter needs a table of samples, but "
                            "types 1 1 have the constant e 0.5"),
                           ("refuse.plain", "table %s" % os.path.abspath(a.plain_table),
                            "has no quantile columns")):
        inp = os.path.join(work, "in." + tag)
        lammps_input(inp, "pair_style gran/hooke/history/cantact %s %s scatter %d"
                     % (frictionless, src, a.seed), a.dt, 0.0, 1, a.speed,
                     "final." + tag, loader, processors=False)
        out = runner.run(tag, inp, fails=True)
        line = [l for l in out.splitlines() if "ERROR" in l]
        check(len(line) == 1 and want in line[0], "%s: not refused in one line naming why: %s"
              % (tag, out[-400:]))
        print("refused: scatter with %s: %s" % ("a constant e" if "constant" in tag else
                                                "a table without quantile columns",
                                                line[0].strip() if line else "(no ERROR line)"))

    print("\nlmp runs (wall time, s):")
    for name, tm in runner.times:
        print("  %-28s %.2f" % (name, tm))
    if failures:
        print("\nFAILED:")
        for f in failures:
            print("  " + f)
    print("\nscatter: %d passed, %d failed" % tuple(counts))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
