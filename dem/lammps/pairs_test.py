#!/usr/bin/env python3
"""e(v) per pair of particle types in LAMMPS (gran/hooke/history/cantact, pair_coeff I J table
FILE): two particle types, three type pairs, each with the table dem/pair_tables.py wrote for
that pair's reduced radius and mass (docs/dem.md, "e(v) for a pair of particles"). Driven by
test.sh.

    pairs_test.py --lib L --loader P --e-of-speed E --work DIR
                  --type R1:RHO1 --type R2:RHO2 --tables DIR_OF_e_I_J.csv [--dt 1e-8] [--tol 1e-4]

Head-on collisions, no gravity, no friction, Kn = 1e5 N/m, one run per damping relation with
every pair (1-1, 1-2, 2-2) at each of 5 speeds 0.003 .. 0.3 m/s. Checks (each fails the run):
  1. every pair's rebound ratio is e of ITS table at its speed (e_of_speed, the C reader)
     within --tol at --dt, both relations; every contact ended;
  2. each contact's reported e is its pair's table's bit for bit, meff is the pair's reduced
     mass m_I m_J/(m_I + m_J) to 1e-12 (computed here from R and rho), and the tables'
     v_per_V_star follow the reduced masses: v_per_V_star^2 m_IJ is the same for the three
     (V* = sqrt(m v^2 / (2 l0 E h0))) to 1e-12;
  3. it can fail: the same run with the 1-1 and 2-2 tables swapped must fail check 1.
"""
import argparse
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from collide_test import REPORT, Runner, read_final  # noqa: E402

KN = 1e5
T0 = 1e-6
SPEEDS = (0.003, 0.01, 0.03, 0.1, 0.3)
PAIRS = ((1, 1), (1, 2), (2, 2))


def particle(text):
    parts = text.split(":")
    try:
        r, rho = (float(p) for p in parts) if len(parts) == 2 else (None, None)
    except ValueError:
        r, rho = None, None
    if r is None or not (0.0 < r < math.inf and 0.0 < rho < math.inf):
        raise argparse.ArgumentTypeError("%r: give RADIUS:DENSITY (m, kg/m^3), both > 0" % text)
    return r, rho


def lammps_input(path, pair_style, coeffs, dt, t_end, types, final, loader):
    """pair p (1-1, 1-2, 2-2), speed k: atoms 2n+1, 2n+2 (n = p * len(SPEEDS) + k), head-on
    along x, centre of mass at rest, touching at t = T0"""
    mass = [None] + [rho * 4.0 / 3.0 * math.pi * r ** 3 for r, rho in types]
    L = ["units si", "atom_style sphere", "atom_modify map array", "boundary f f f", "newton off",
         "comm_modify vel yes", "neighbor 0.0002 bin", "neigh_modify delay 0 every 1 check yes",
         "region box block -0.02 0.02 -0.01 %.17g -0.01 0.01 units box"
         % (0.01 * len(PAIRS) * len(SPEEDS)),
         "create_box 2 box"]
    vels = []
    n = 0
    for ti, tj in PAIRS:
        ri, rj = types[ti - 1][0], types[tj - 1][0]
        mi, mj = mass[ti], mass[tj]
        for v in SPEEDS:
            y = 0.01 * n
            gap = v * T0
            L.append("create_atoms %d single %.17g %.17g 0 units box" % (ti, -(ri + 0.5 * gap), y))
            L.append("create_atoms %d single %.17g %.17g 0 units box" % (tj, rj + 0.5 * gap, y))
            vels.append((2 * n + 1, mj / (mi + mj) * v))
            vels.append((2 * n + 2, -mi / (mi + mj) * v))
            n += 1
    for t, (r, rho) in enumerate(types, 1):
        L.append("set type %d diameter %.17g" % (t, 2 * r))
        L.append("set type %d density %.17g" % (t, rho))
    L.append("velocity all set 0 0 0 units box")
    for i, vx in vels:
        L.append("set atom %d vx %.17g" % (i, vx))
    L.append("python cantact_load input 2 SELF %s format ps file %s" % loader)
    L.append("python cantact_load invoke")
    L.append(pair_style)
    L.extend(coeffs)
    L.append("fix integrate all nve/sphere")
    L.append("timestep %.17g" % dt)
    steps = int(round(t_end / dt))
    L.append("thermo %d" % steps)
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
    ap.add_argument("--e-of-speed", required=True, help="the e_of_speed helper (test.sh builds it)")
    ap.add_argument("--work", required=True)
    ap.add_argument("--type", dest="types", action="append", type=particle, required=True,
                    metavar="R:RHO", help="the two particle types, as given to pair_tables.py")
    ap.add_argument("--tables", required=True, help="the directory of e_1_1.csv, e_1_2.csv, "
                    "e_2_2.csv (dem/pair_tables.py -o)")
    ap.add_argument("--dt", type=float, default=1e-8)
    ap.add_argument("--tol", type=float, default=1e-4)
    a = ap.parse_args()
    if len(a.types) != 2:
        ap.error("give --type twice (two particle types), not %d times" % len(a.types))
    tables = {}
    for i, j in PAIRS:
        tables[(i, j)] = os.path.abspath(os.path.join(a.tables, "e_%d_%d.csv" % (i, j)))
        if not os.path.isfile(tables[(i, j)]):
            ap.error("--tables %s: no e_%d_%d.csv there (dem/pair_tables.py writes it)"
                     % (a.tables, i, j))
    for p, what in ((a.lib, "--lib"), (a.loader, "--loader"), (a.e_of_speed, "--e-of-speed")):
        if not os.path.isfile(p):
            ap.error("%s %s: no such file" % (what, p))
    if not (a.dt > 0.0 and a.tol > 0.0):
        ap.error("--dt and --tol must be > 0")
    work = os.path.abspath(a.work)
    os.makedirs(work, exist_ok=True)
    loader = (os.path.abspath(a.lib), os.path.abspath(a.loader))
    runner = Runner(a.lmp, work)
    failures = []
    counts = [0, 0]

    def check(ok, msg):
        counts[0 if ok else 1] += 1
        if not ok:
            failures.append(msg)

    mass = [None] + [rho * 4.0 / 3.0 * math.pi * r ** 3 for r, rho in a.types]
    m_red = {(i, j): mass[i] * mass[j] / (mass[i] + mass[j]) for i, j in PAIRS}

    def e_table(path, speeds):
        out = subprocess.run([a.e_of_speed, path] + ["%.17g" % s for s in speeds],
                             stdout=subprocess.PIPE, universal_newlines=True, check=True).stdout
        return [float(l.split()[1]) for l in out.splitlines()]

    # 2: each table's v_per_V_star is its pair's (V* ~ sqrt(m) v: v_per_V_star^2 m constant)
    vpv = {}
    for p, path in tables.items():
        with open(path) as f:
            m = re.search(r"^#\s*v_per_V_star\s*=\s*(\S+)", f.read(), re.M)
        check(m is not None, "%s: no v_per_V_star" % path)
        vpv[p] = float(m.group(1)) if m else math.nan
    c = [vpv[p] ** 2 * m_red[p] for p in PAIRS]
    check(max(c) - min(c) <= 1e-12 * max(c), "the tables' v_per_V_star^2 m_red differ (%s): a "
          "table not written for its pair's reduced mass" % ", ".join("%.17g" % x for x in c))
    print("tables: %s" % "; ".join("%d-%d: m_red %.6g kg, v_per_V_star %.9g"
                                     % (i, j, m_red[(i, j)], vpv[(i, j)]) for i, j in PAIRS))

    # the longest contact: the heaviest pair, damped (stock: pi / (omega sqrt(1 - zeta^2)),
    # zeta < 0.8 for e > 0.017); the clipped contact ends sooner
    t_end = T0 + 1.1 * math.pi * math.sqrt(max(m_red.values()) / KN) / math.sqrt(1 - 0.8 ** 2)
    e_ref = {p: e_table(tables[p], SPEEDS) for p in PAIRS}

    def run(law, tabs, tag):
        """one run; (worst |ratio - e_table| per pair, the lines of the misses)"""
        inp = os.path.join(work, "in." + tag)
        coeffs = ["pair_coeff %d %d table %s" % (i, j, tabs[(i, j)]) for i, j in PAIRS]
        lammps_input(inp, "pair_style gran/hooke/history/cantact %.17g 0.0 0.0 0.0 0%s report 1000"
                     % (KN, " limit_damping" if law else ""), coeffs, a.dt, t_end, a.types,
                     "final." + tag, loader)
        out = runner.run(tag, inp)
        atoms = read_final(os.path.join(work, "final." + tag))
        worst, misses, n = {}, [], 0
        for p in PAIRS:
            worst[p] = 0.0
            for k, v in enumerate(SPEEDS):
                a1, a2 = atoms[2 * n + 1], atoms[2 * n + 2]
                ratio = (a2[3] - a1[3]) / v
                d = ratio - e_ref[p][k]
                worst[p] = max(worst[p], abs(d))
                apart = a2[0] - a1[0] > a.types[p[0] - 1][0] + a.types[p[1] - 1][0]
                if not abs(d) <= a.tol or not apart:
                    misses.append("%s: pair %d-%d, v = %g m/s: ratio %.9f, its table's e %.9f "
                                  "(%+.3e)" % (tag, p[0], p[1], v, ratio, e_ref[p][k], d))
                n += 1
        return worst, misses, out

    for law in (0, 1):
        tag = "pairs.law%d" % law
        worst, misses, out = run(law, tables, tag)
        check(not misses, "; ".join(misses))
        # 2: the report: e bit for bit its pair's table's, meff the pair's reduced mass
        reps = REPORT.findall(out)
        check(len(reps) == len(PAIRS) * len(SPEEDS), "%s: %d contacts reported, %d expected"
              % (tag, len(reps), len(PAIRS) * len(SPEEDS)))
        for r in reps:
            n = (min(int(r[0]), int(r[1])) - 1) // 2
            p = PAIRS[n // len(SPEEDS)]
            vn, e, meff = float(r[3]), float(r[4]), float(r[6])
            check(e == e_table(tables[p], [vn])[0], "%s: contact %s-%s (pair %d-%d): e %.17g is "
                  "not its table's" % (tag, r[0], r[1], p[0], p[1], e))
            check(abs(meff - m_red[p]) <= 1e-12 * m_red[p], "%s: pair %d-%d: meff %.17g, not %.17g"
                  % (tag, p[0], p[1], meff, m_red[p]))
        print("%s, dt = %g s: worst |rebound ratio - e of the pair's table| over %d speeds "
              "%g .. %g m/s: %s (tolerance %g)"
              % ("limit_damping" if law else "stock damping", a.dt, len(SPEEDS), SPEEDS[0],
                 SPEEDS[-1], ", ".join("%d-%d %.2e" % (p[0], p[1], worst[p]) for p in PAIRS),
                 a.tol))

    # 3: the 1-1 and 2-2 tables swapped must fail check 1
    swapped = dict(tables)
    swapped[(1, 1)], swapped[(2, 2)] = tables[(2, 2)], tables[(1, 1)]
    worst, misses, _ = run(0, swapped, "pairs.swapped")
    check(bool(misses), "the 1-1 and 2-2 tables swapped passed the check: it cannot fail")
    print("negative control, the 1-1 and 2-2 tables swapped: %d of %d rebounds off their pair's "
          "table by more than %g (worst %s): %s" % (len(misses), len(PAIRS) * len(SPEEDS), a.tol,
                                                    ", ".join("%d-%d %.2e" % (p[0], p[1], worst[p])
                                                              for p in PAIRS),
                                                    "caught" if misses else "NOT caught"))
    print("\nlmp runs (wall time, s):")
    for name, t in runner.times:
        print("  %-28s %.2f" % (name, t))
    if failures:
        print("\nFAILED:")
        for f in failures:
            print("  " + f)
    print("\npairs: %d passed, %d failed" % tuple(counts))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
