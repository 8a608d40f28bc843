#!/usr/bin/env python3
"""Head-on collisions of 2 mm steel spheres in LAMMPS with the pair style
gran/hooke/history/cantact (driven by test.sh with Debian's stock lmp and the add-on, or by
selfbuilt.sh with a self-built lmp: --builtin or --plugin).

Checks, each of which fails the run (exit 1):
  1. rebound ratio = e_table(v) within --tol (1e-4) at dt = --dt (1e-8 s), for every speed, with
     and without limit_damping, for two free spheres (v = their relative normal approach speed,
     meff = m/2) and for a sphere against a frozen one (fix freeze: meff = m); every contact has
     ended. These runs stop in the middle of the contacts and delete far dummy atoms, so that
     every pair's atoms swap their local order and each contact continues from the other atom's
     copy of its history (transfer_history);
  2. every contact's e, printed by the style (report), is bit for bit the reader's e_table of
     the speed it printed, that speed is v to 1e-15, meff is m/2 or m, gamma_n = 2 zeta
     sqrt(kn/meff), and zeta gives e back by this script's own statement of the relation
     (e_of_zeta below);
  3. pair_coeff per type pair, constant e 0.1 and 0.05 with limit_damping (overdamped: zeta > 1)
     give those rebounds within --tol;
  4. with a constant e (keyword `e` and a flat table file), the style's trajectories equal stock
     gran/hooke/history given the style's gamma_n, to the bit (%.17g dumps), head-on without
     friction (both relations) and oblique with friction (gamma_t NULL = gamma_n / 2);
  5. a negative control: v_per_V_star 10 % off must be caught by check 1;
  6. two MPI ranks (each pair split across them, ghost contacts, newton off) give the serial
     run's final state to the bit (skipped, and said so, when mpirun cannot start 2 ranks);
  7. contacts at speeds above the table's last node (1.5 and 2 times its speed) rebound with
     the nearest end's e, with one warning naming the speed and the range the table knows, and
     compute pair's vector counts 3 contacts, 2 outside; with `outside error` the run stops
     with that message; a pair_coeff table without v_per_V_star is refused at setup (it was
     taken as e = 1 for every contact); no run of 1 reports a contact outside its table.
--quick: 1-3 only. Also prints the worst errors at dt = 1e-7 and 1e-6 s (not checked: the
integrator's error, first order in dt).
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import time

R = 0.002          # m, sphere radius
RHO = 7800.0       # kg/m^3
KN = 1e5           # N/m
T0 = 1e-6          # s, flight before touching
T_END = 2.0e-4     # s, run length: flight + the longest contact (about 1.3e-4 s) + margin
MASS = RHO * 4.0 / 3.0 * math.pi * R ** 3


def speeds(n=10, lo=0.02, hi=6.0):
    return [lo * (hi / lo) ** (k / (n - 1)) for k in range(n)]


def e_of_zeta(z, law):
    """this script's own statement of the two relations (independent of the style's code):
    law 0, tension allowed: e = exp(-pi z / sqrt(1 - z^2)), 0 for z >= 1; law 1, force clipped at
    zero: ln e = -2 z h, h = acos(z)/sqrt(1 - z^2) (z < 1; = x (pi - 2 atan x) / (2 z) with
    x = z / sqrt(1 - z^2)), 1 (z = 1), acosh(z)/sqrt(z^2 - 1) (z > 1)"""
    if z <= 0.0:
        return 1.0
    if law == 0:
        return math.exp(-math.pi * z / math.sqrt(1.0 - z * z)) if z < 1.0 else 0.0
    if z < 1.0:
        x = z / math.sqrt(1.0 - z * z)
        return math.exp(-x * (math.pi - 2.0 * math.atan(x)))
    h = 1.0 if z == 1.0 else math.acosh(z) / math.sqrt(z * z - 1.0)
    return math.exp(-2.0 * z * h)


def scene(vs, frozen, oblique):
    """atoms: (id, type, x, y, z, vx); free pair k: ids 2k+1, 2k+2 moving at +-v/2; frozen pair
    k: ids 2n+2k+1, 2n+2k+2, a type-1 sphere at v against a frozen type-2 sphere"""
    atoms = []
    n = len(vs)
    for k, v in enumerate(vs):
        gap = v * T0
        y = 0.01 * k
        dz = 0.5 * R if oblique else 0.0
        hx = 0.5 * math.sqrt(4 * R * R - dz * dz)    # half the x distance at first touch
        atoms.append((2 * k + 1, 1, -(hx + 0.5 * gap), y, 0.0, 0.5 * v))
        atoms.append((2 * k + 2, 1, hx + 0.5 * gap, y, dz, -0.5 * v))
        if frozen:
            atoms.append((2 * n + 2 * k + 1, 1, -(R + gap), y, 0.01, v))
            atoms.append((2 * n + 2 * k + 2, 2, R, y, 0.01, 0.0))
    return sorted(atoms)    # create_atoms numbers them in this order


def lammps_input(path, pair_style, pair_coeff, dt, vs, frozen, oblique, final, dump=None,
                 dump_every=0, loader=None, t_end=T_END, flip=False, thermo=None):
    """flip: the run stops in the middle of the contacts (t = T0 + 5e-5 s) and deletes as many
    far-away dummy atoms, created first, as there are spheres: LAMMPS fills each hole with the
    last atom, so every pair's two atoms swap their local order (atom sorting is off) and each
    contact goes on from the other atom's copy of its history (Pair::transfer_history)"""
    atoms = scene(vs, frozen, oblique)
    steps = int(round(t_end / dt))
    ymax = 0.01 * len(vs)
    L = []
    L.append("units si")
    L.append("atom_style sphere")
    L.append("atom_modify map array")
    L.append("boundary f f f")
    L.append("newton off")
    L.append("comm_modify vel yes")
    # a small skin: the lists are rebuilt during the fast contacts, so their history is carried
    L.append("neighbor 0.0002 bin")
    L.append("neigh_modify delay 0 every 1 check yes")
    L.append("region box block -0.02 0.02 -0.01 %.17g -0.01 0.02 units box" % ymax)
    L.append("create_box 2 box")
    ndummy = len(atoms) if flip else 0
    if flip:
        L.append("atom_modify sort 0 0.0")
        for d in range(ndummy):
            L.append("create_atoms 2 single %.17g %.17g 0.015 units box"
                     % (-0.018 + 0.0045 * (d % 9), -0.009 + 0.0045 * (d // 9)))
    for (i, t, x, y, z, vx) in atoms:
        L.append("create_atoms %d single %.17g %.17g %.17g units box" % (t, x, y, z))
    L.append("set group all diameter %.17g" % (2 * R))
    L.append("set group all density %.17g" % RHO)
    L.append("velocity all set 0 0 0 units box")
    for (i, t, x, y, z, vx) in atoms:
        if vx != 0.0:
            L.append("set atom %d vx %.17g" % (i + ndummy, vx))
    L.append("group frozen type 2")
    if loader and loader[0] == "plugin":
        L.append("plugin load %s" % loader[1])
    elif loader:
        L.append("python cantact_load input 2 SELF %s format ps file %s" % (loader[0], loader[1]))
        L.append("python cantact_load invoke")
    L.append(pair_style)
    L.append(pair_coeff)
    L.append("fix integrate all nve/sphere")
    L.append("fix wall frozen freeze")
    L.append("timestep %.17g" % dt)
    if thermo:  # compute pair's vector, printed at the first and last step
        L.append("compute p all pair gran/hooke/history/cantact")
        L.append("thermo_style custom step %s" % thermo)
    L.append("thermo %d" % steps)
    if dump:
        L.append("dump traj all custom %d %s id x y z vx vy vz omegax omegay omegaz"
                 % (dump_every, dump))
        L.append('dump_modify traj format float %.17g sort id')
    if flip:
        first = int(round((T0 + 5e-5) / dt))
        L.append("group dummies id 1:%d" % ndummy)
        L.append("run %d" % first)
        L.append("delete_atoms group dummies compress no")
        L.append("run %d" % (steps - first))
    else:
        L.append("run %d" % steps)
    L.append("write_dump all custom %s id x y z vx vy vz modify format float %%.17g sort id"
             % final)
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")
    return ndummy    # the spheres' ids are those of scene() + ndummy


class Runner:
    def __init__(self, lmp, work, mpirun=None):
        self.lmp = lmp
        self.work = work
        self.mpirun = mpirun
        self.times = []

    def run(self, name, inp, nproc=1, fails=False):
        cmd = [self.lmp, "-in", inp, "-log", "none", "-nocite"]
        if nproc > 1:
            cmd = self.mpirun + ["-np", str(nproc)] + cmd
        t = time.time()
        p = subprocess.run(cmd, cwd=self.work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           universal_newlines=True)
        dt = time.time() - t
        self.times.append((name, dt))
        if fails:  # a run that must stop with an error: its output
            if p.returncode == 0:
                raise SystemExit("collide_test: lmp did not fail (%s)" % name)
            return p.stdout
        if p.returncode != 0:
            sys.stdout.write(p.stdout[-3000:])
            raise SystemExit("collide_test: lmp failed (%s, exit %d)" % (name, p.returncode))
        return p.stdout


def read_final(path, offset=0):
    atoms = {}
    with open(path) as f:
        lines = f.read().splitlines()
    k = lines.index([l for l in lines if l.startswith("ITEM: ATOMS")][0])
    for l in lines[k + 1:]:
        w = l.split()
        if int(w[0]) > offset:
            atoms[int(w[0]) - offset] = [float(s) for s in w[1:]]
    return atoms


REPORT = re.compile(r"^cantact: contact (\d+) (\d+) step (\d+) v_n (\S+) e (\S+) zeta (\S+) "
                    r"meff (\S+) gamma_n (\S+)$", re.M)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--lib", help="libcantact_lammps.so (the add-on for Debian's lmp)")
    ap.add_argument("--loader", help="cantact_load.py (with --lib)")
    ap.add_argument("--plugin", help="a plugin .so for a LAMMPS with the PLUGIN package "
                    "(`plugin load` instead of --lib/--loader)")
    ap.add_argument("--builtin", action="store_true",
                    help="the style is compiled into --lmp (dropped into its source tree)")
    ap.add_argument("--table", required=True)
    ap.add_argument("--e-of-speed", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--tol", type=float, default=1e-4)
    ap.add_argument("--dt", type=float, default=1e-8)
    ap.add_argument("--more-dt", default="1e-7,1e-6")
    ap.add_argument("--no-mpi", action="store_true")
    ap.add_argument("--quick", action="store_true",
                    help="checks 1 and 2 at --dt only (no other dt, bit for bit, control, MPI)")
    a = ap.parse_args()

    work = os.path.abspath(a.work)
    os.makedirs(work, exist_ok=True)
    if a.builtin:
        loader = None
    elif a.plugin:
        loader = ("plugin", os.path.abspath(a.plugin))
    elif a.lib and a.loader:
        loader = (os.path.abspath(a.lib), os.path.abspath(a.loader))
    else:
        ap.error("give --lib and --loader, or --plugin, or --builtin")
    table = os.path.abspath(a.table)
    mpirun = None
    if not a.no_mpi and shutil.which("mpirun"):
        mpirun = ["mpirun", "--oversubscribe"]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            mpirun.append("--allow-run-as-root")
    runner = Runner(a.lmp, work, mpirun)
    failures = []
    counts = [0, 0]    # checks passed, failed

    def check(ok, msg):
        counts[0 if ok else 1] += 1
        if not ok:
            failures.append(msg)
    vs = speeds()
    n = len(vs)

    def e_table(speed_list, extra=()):
        out = subprocess.run([a.e_of_speed, table] + list(extra) + ["%.17g" % s for s in speed_list],
                             stdout=subprocess.PIPE, universal_newlines=True, check=True).stdout
        return [float(l.split()[1]) for l in out.splitlines()]

    e_ref = e_table(vs)
    # what the table knows: e = 1 up to v_c, its nodes from V_first to V_last (times vpv)
    with open(table) as f:
        text = f.read()
    vpv = float(re.search(r"^#\s*v_per_V_star\s*=\s*(\S+)", text, re.M).group(1))
    v_c = vpv * float(re.search(r"^#\s*V_star_crit\s*=\s*(\S+)", text, re.M).group(1))
    rows = [l for l in text.splitlines() if l[:1].isdigit()]
    V_first, V_last = float(rows[0].split(",")[0]), float(rows[-1].split(",")[0])
    v_top = V_last * vpv    # the fastest speed the table knows
    # every test speed well inside what the table knows (not at its end to a rounding): no run
    # may warn of a contact outside it
    inside = all(v <= v_c * (1 - 1e-9) or V_first * vpv * (1 + 1e-9) <= v <= v_top * (1 - 1e-9)
                 for v in vs)
    frictionless = "%.17g 0.0 0.0 0.0 0" % KN  # Kn Kt gamma_t xmu dampflag

    def table_run(law, dt, tag, extra="", nproc=1):
        ld = " limit_damping" if law else ""
        inp = os.path.join(work, "in.%s" % tag)
        final = "final.%s" % tag
        off = lammps_input(inp, "pair_style gran/hooke/history/cantact %s table %s%s report 1000%s"
                           % (frictionless, table, ld, extra), "pair_coeff * *", dt, vs, True,
                           False, final, loader=loader, flip=True)
        out = runner.run(tag, inp, nproc)
        # the report's ids, as scene()'s
        out = REPORT.sub(lambda m: "cantact: contact %d %d step %s v_n %s e %s zeta %s meff %s "
                         "gamma_n %s" % ((int(m.group(1)) - off, int(m.group(2)) - off)
                                         + m.groups()[2:]), out)
        return read_final(os.path.join(work, final), off), out

    def rebounds(atoms):
        """(free ratios, frozen ratios, all separated); the left sphere of a pair is the one at
        the smaller x, the mobile one of a frozen pair the left one too"""
        free, froz, sep = [], [], True
        for k, v in enumerate(vs):
            a1, a2 = sorted((atoms[2 * k + 1], atoms[2 * k + 2]))
            free.append((a2[3] - a1[3]) / v)
            sep = sep and (a2[0] - a1[0]) > 2 * R
            b1, b2 = sorted((atoms[2 * n + 2 * k + 1], atoms[2 * n + 2 * k + 2]))
            froz.append(-b1[3] / v)
            sep = sep and (b2[0] - b1[0]) > 2 * R
        return free, froz, sep

    # ---- 1 and 2: the table at dt, both laws; then the other time steps, printed only ----
    worst = {}
    finals = {}
    for law in (0, 1):
        lname = "limit_damping" if law else "stock damping"
        more = [] if a.quick else [float(s) for s in a.more_dt.split(",") if s]
        for dt in [a.dt] + more:
            tag = "table.law%d.dt%g" % (law, dt)
            atoms, out = table_run(law, dt, tag)
            check(not inside or "outside table" not in out,
                  "%s: a contact outside the table reported" % tag)
            finals[(law, dt)] = atoms
            free, froz, sep = rebounds(atoms)
            check(sep, "%s: some spheres still in contact at the end" % tag)
            ef = [f - e for f, e in zip(free, e_ref)]
            ez = [f - e for f, e in zip(froz, e_ref)]
            worst[(law, dt)] = (max(abs(x) for x in ef), max(abs(x) for x in ez))
            if dt == a.dt:
                print("\n%s, dt = %g s: rebound ratio - e_table(v)" % (lname, dt))
                print("  %-10s %-20s %-12s %-12s" % ("v m/s", "e_table", "free pair", "vs frozen"))
                for k, v in enumerate(vs):
                    print("  %-10.4g %-20.17g %+-12.3e %+-12.3e" % (v, e_ref[k], ef[k], ez[k]))
                for what, errs in (("free", ef), ("frozen", ez)):
                    for k, x in enumerate(errs):
                        check(abs(x) <= a.tol, "%s %s v = %.4g: |ratio - e_table| = %.3g > %g"
                              % (tag, what, vs[k], abs(x), a.tol))
                # 2: the report lines
                reps = REPORT.findall(out)
                check(len(reps) == 2 * n, "%s: %d contacts reported, %d expected" % (tag, len(reps), 2 * n))
                ev = e_table([float(r[3]) for r in reps])
                for r, e_helper in zip(reps, ev):
                    i, j = int(r[0]), int(r[1])
                    vn, e, z, meff, gn = (float(s) for s in r[3:])
                    k = (min(i, j) - 1) // 2 % n
                    check(abs(vn - vs[k]) <= 1e-15 * vs[k],
                          "%s: contact %d-%d v_n %.17g, not %.17g" % (tag, i, j, vn, vs[k]))
                    check(e == e_helper, "%s: contact %d-%d: e %.17g, the reader gives %.17g"
                          % (tag, i, j, e, e_helper))
                    m_expect = MASS / 2 if min(i, j) <= 2 * n else MASS
                    check(abs(meff - m_expect) <= 1e-12 * m_expect,
                          "%s: contact %d-%d meff %.17g, not %.17g" % (tag, i, j, meff, m_expect))
                    check(abs(gn - 2.0 * z * math.sqrt(KN / meff)) <= 1e-14 * max(gn, 1e-300),
                          "%s: contact %d-%d gamma_n %.17g != 2 zeta sqrt(kn/meff)" % (tag, i, j, gn))
                    check(abs(e_of_zeta(z, law) - e) <= 1e-12,
                          "%s: contact %d-%d: zeta %.17g gives e %.17g, not %.17g"
                          % (tag, i, j, z, e_of_zeta(z, law), e))
                print("  %d contacts reported: e bit for bit the reader's, zeta -> e by the law "
                      "(%s) checked" % (len(reps), "force clipped" if law else "tension allowed"))

    # ---- per type pair (pair_coeff), overdamped: e below e^-2 with limit_damping ----
    tag = "coeff.overdamped"
    inp = os.path.join(work, "in." + tag)
    e11, e12 = 0.1, 0.05
    lammps_input(inp, "pair_style gran/hooke/history/cantact %s limit_damping report 1000"
                 % frictionless, "pair_coeff 1 1 e %g\npair_coeff 1 2 e %g\npair_coeff 2 2 e 1"
                 % (e11, e12), a.dt, vs, True, False, "final." + tag, loader=loader,
                 t_end=4e-4)    # overdamped and clipped: the spheres fly apart still overlapping
    out = runner.run(tag, inp)
    free, froz, sep = rebounds(read_final(os.path.join(work, "final." + tag)))
    check(sep, "%s: some spheres still in contact at the end" % tag)
    wf = max(abs(x - e11) for x in free)
    wz = max(abs(x - e12) for x in froz)
    check(wf <= a.tol and wz <= a.tol, "%s: |ratio - e| = %.3g (free), %.3g (frozen) > %g"
          % (tag, wf, wz, a.tol))
    reps = REPORT.findall(out)
    zetas = sorted(set(float(r[5]) for r in reps))
    check(len(reps) == 2 * n and len(zetas) == 2 and min(zetas) > 1.0,
          "%s: %d contacts, zeta %s: 2 values > 1 expected" % (tag, len(reps), zetas))
    for r in reps:
        z, e = float(r[5]), float(r[4])
        check(abs(e_of_zeta(z, 1) - e) <= 1e-12, "%s: zeta %.17g gives e %.17g, not %.17g"
              % (tag, z, e_of_zeta(z, 1), e))
    print("\npair_coeff per type pair, limit_damping, overdamped (zeta %s): e %g (free pairs), "
          "%g (vs frozen): worst |ratio - e| %.3e, %.3e at dt = %g"
          % (" ".join("%.6g" % z for z in zetas), e11, e12, wf, wz, a.dt))

    print("\nworst |rebound ratio - e_table(v)| over %d speeds %.3g .. %.3g m/s:" % (n, vs[0], vs[-1]))
    print("  %-16s %-10s %-12s %-12s" % ("damping", "dt s", "free pair", "vs frozen"))
    for (law, dt), (wf, wz) in sorted(worst.items(), key=lambda t: (t[0][0], t[0][1])):
        print("  %-16s %-10g %-12.3e %-12.3e%s" % ("limit_damping" if law else "stock", dt, wf, wz,
                                                  "  (checked: <= %g)" % a.tol if dt == a.dt else ""))

    if a.quick:
        return finish(runner, failures, counts)

    # ---- speeds outside the table: the nearest end's e, one warning, counted; or an error ----
    vs_out = [0.5 * v_top, 1.5 * v_top, 2.0 * v_top]
    e_out = e_table(vs_out)
    for policy in ("warn", "error"):
        tag = "outside.%s" % policy
        inp = os.path.join(work, "in." + tag)
        lammps_input(inp, "pair_style gran/hooke/history/cantact %s table %s outside %s"
                     % (frictionless, table, policy), "pair_coeff * *", a.dt, vs_out, False,
                     False, "final." + tag, loader=loader, thermo="c_p[1] c_p[2]")
        out = runner.run(tag, inp, fails=policy == "error")
        if policy == "error":
            check("outside table" in out and "(outside error)" in out,
                  "%s: no error naming the table: %s" % (tag, out[-500:]))
            continue
        warns = [l for l in out.splitlines() if "outside table" in l]
        check(len(warns) == 1 and "WARNING" in warns[0] and (".. %.6g" % v_top) in warns[0]
              and any("v_n = %.6g" % v in warns[0] for v in vs_out[1:]),
              "%s: one warning naming the speed and the table's end expected, got %s"
              % (tag, warns))
        rows = [l.split() for l in out.splitlines() if re.match(r"^\s*\d+\s+\S+\s+\S+\s*$", l)]
        check(bool(rows) and [float(x) for x in rows[-1][1:]] == [3.0, 2.0],
              "%s: compute pair's vector %s, not 3 contacts of which 2 outside"
              % (tag, rows[-1:] if rows else None))
        atoms = read_final(os.path.join(work, "final." + tag))
        for k, v in enumerate(vs_out):
            a1, a2 = sorted((atoms[2 * k + 1], atoms[2 * k + 2]))
            ratio = (a2[3] - a1[3]) / v
            check(abs(ratio - e_out[k]) <= a.tol and (k == 0 or e_out[k] == e_out[-1]),
                  "%s: v = %.4g: ratio %.9g, the table's end e %.9g" % (tag, v, ratio, e_out[k]))
        print("\noutside the table (it knows v_n up to %.6g m/s): v = %s m/s: nearest end's e, "
              "one warning, compute pair counts 3 contacts, 2 outside; with `outside error`: "
              "stopped" % (v_top, ", ".join("%.4g" % v for v in vs_out)))
    # a table of a pair_coeff of its own, without v_per_V_star: refused at setup (it was not
    # checked: V* = v_n / NaN went as no approach, e = 1 for every contact)
    nov = os.path.join(work, "no_v_per_V_star.csv")
    with open(table) as f, open(nov, "w") as g:
        g.write("".join(l for l in f if not l.startswith("# v_per_V_star")))
    tag = "coeff.no_v_per_V_star"
    inp = os.path.join(work, "in." + tag)
    lammps_input(inp, "pair_style gran/hooke/history/cantact %s e 0.5" % frictionless,
                 "pair_coeff * * table %s" % nov, a.dt, vs_out[:1], False, False, "final." + tag,
                 loader=loader)
    out = runner.run(tag, inp, fails=True)
    check("has no v_per_V_star" in out, "%s: not refused: %s" % (tag, out[-400:]))

    # ---- 4: negative control: a 10 % wrong v_per_V_star must fail check 1 ----
    atoms, _ = table_run(0, a.dt, "negative", extra=" v_per_V_star %.17g" % (1.1 * vpv))
    free, froz, _ = rebounds(atoms)
    wneg = max(abs(f - e) for f, e in zip(free + froz, e_ref + e_ref))
    print("\nnegative control (v_per_V_star x 1.1): worst |ratio - e_table| = %.3g: %s"
          % (wneg, "caught" if wneg > a.tol else "NOT caught"))
    check(wneg > a.tol, "negative control: a 10 % wrong v_per_V_star was not caught")

    # ---- 3: bit for bit against stock gran/hooke/history ----
    flat = os.path.join(work, "flat_e0.5.csv")
    with open(flat, "w") as f:
        f.write("# a flat table: e = 0.5 at every speed\n# interpolation = monotone_cubic\n"
                "# V_star_crit = 0\n# v_per_V_star = 1\n# nodes = 2\nV_star,e,de_dlnV_star\n"
                "1e-30,0.5,0\n1e30,0.5,0\n")
    print("\nbit for bit against stock gran/hooke/history (dumps of x, v, omega every 200 steps, "
          "%.17g):")
    for law, oblique in ((0, False), (1, False), (0, True)):
        ld = " limit_damping" if law else ""
        if oblique:
            forces = "%.17g NULL NULL 0.5 1" % KN     # friction; gamma_t = gamma_n / 2
        else:
            forces = frictionless
        dumps = {}
        gns = set()
        for src_name, src in (("e", "e 0.5"), ("flat", "table %s" % flat)):
            tag = "bit.law%d.obl%d.%s" % (law, oblique, src_name)
            inp = os.path.join(work, "in." + tag)
            lammps_input(inp, "pair_style gran/hooke/history/cantact %s %s%s report 1000"
                         % (forces, src, ld), "pair_coeff * *", 1e-7, vs, False, oblique,
                         "final." + tag, dump="dump." + tag, dump_every=200, loader=loader)
            out = runner.run(tag, inp)
            gns |= set(r[7] for r in REPORT.findall(out))
            dumps[src_name] = os.path.join(work, "dump." + tag)
        check(len(gns) == 1, "bit law %d: gamma_n values %s: one expected" % (law, sorted(gns)))
        if len(gns) != 1:
            continue
        gn = gns.pop()
        tag = "bit.law%d.obl%d.stock" % (law, oblique)
        inp = os.path.join(work, "in." + tag)
        f = forces.split()
        stock_args = "%s %s %s %s %s %s" % (f[0], f[1], gn, f[2], f[3], f[4])
        lammps_input(inp, "pair_style gran/hooke/history %s%s" % (stock_args, ld), "pair_coeff * *",
                     1e-7, vs, False, oblique, "final." + tag, dump="dump." + tag, dump_every=200)
        runner.run(tag, inp)
        ref = open(os.path.join(work, "dump." + tag)).read()
        nlines = ref.count("\n")
        for src_name, path in dumps.items():
            same = open(path).read() == ref
            print("  %-15s %-12s e = 0.5 (%s): gamma_n %s: %s (%d lines)"
                  % ("limit_damping" if law else "stock damping",
                     "oblique+fric" if oblique else "head-on", src_name, gn,
                     "identical" if same else "DIFFERENT", nlines))
            check(same, "%s: differs from stock gran/hooke/history %s" % (path, stock_args))
        # the dumps must show the collisions (and spin with friction), else they prove nothing
        snaps = ref.split("ITEM: ATOMS")
        first = [l.split() for l in snaps[1].splitlines()[1:]]
        last = [l.split() for l in snaps[-1].splitlines()[1:]]
        hit = all(u[4:7] != w[4:7] for u, w in zip(first, last))
        spun = all(any(float(x) != 0.0 for x in w[7:10]) for w in last)
        check(hit and spun == oblique, "%s: every sphere must collide%s" % (
            tag, " and spin" if oblique else " without spin"))

    # ---- 5: two MPI ranks ----
    if mpirun is None:
        print("\nMPI: SKIPPED (no mpirun, or --no-mpi)")
    else:
        probe = subprocess.run(mpirun + ["-np", "2", "true"], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
        if probe.returncode != 0:
            print("\nMPI: SKIPPED (mpirun cannot start 2 ranks here)")
        else:
            atoms, _ = table_run(0, a.dt, "mpi2", nproc=2)
            same = all(atoms[i] == finals[(0, a.dt)][i] for i in finals[(0, a.dt)])
            print("\nMPI: 2 ranks (pairs split across them), stock damping, dt = %g: final x, v %s "
                  "the serial run's" % (a.dt, "identical to" if same else "DIFFERENT from"))
            check(same, "2 MPI ranks differ from 1")

    return finish(runner, failures, counts)


def finish(runner, failures, counts):
    print("\nlmp runs (wall time, s):")
    for name, t in runner.times:
        print("  %-28s %.2f" % (name, t))
    print("  %-28s %.2f" % ("total", sum(t for _, t in runner.times)))
    if failures:
        print("\nFAILED:")
        for f in failures:
            print("  " + f)
    print("\n%d passed, %d failed" % (counts[0], counts[1]))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
