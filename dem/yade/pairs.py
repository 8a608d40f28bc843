"""e(v) per pair of materials in Yade: two materials (two particle types), three pairs of them,
each with the table dem/pair_tables.py wrote for that pair's reduced radius and mass
(docs/dem.md, "e(v) for a pair of particles"), given to cantact_yade.Damping(pairs=...).

    yade -n -x pairs.py --type R1:RHO1 --type R2:RHO2 --tables DIR [--dt 1e-8] [--tol 1e-4]
                        [--swap | --control]

DIR holds e_1_1.csv, e_1_2.csv, e_2_2.csv (dem/pair_tables.py -o DIR, types in the same
order). Head-on, k_n = 1e5 N/m, no gravity, no friction, every pair (1-1, 1-2, 2-2) at 5 speeds
from 0.003 to 0.3 m/s, all in one run; the pairs are keyed three ways (1-1 by the materials'
labels, 1-2 by their ids, 2-2 by the Material object), so each kind of key is used.

Checks (exit 1 on any failure): every pair's rebound ratio is e of its own table at its speed
within --tol; each contact's e is bit for bit its pair's table's (read here with
cantact.read_table, not through the runner); the tables' v_per_V_star follow the pairs' reduced
masses (v_per_V_star^2 m_red the same, to 1e-12); and, before the run, that the runner refuses
bad pairs in one line (no table at all, a key that is not two materials, a pair given twice, a
contact whose materials have no table). --swap gives the 1-1 and 2-2 tables the other way
round: the rebound check must then fail. --control runs both in one Yade (O.reset() between):
the right tables must pass and the swapped ones fail (test.sh runs it so)."""
import math
import os
import sys
import time
import types

# yade runs the script with its own globals (__file__ is yade's): the script is argv[0]
sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
import cantact_yade  # noqa: E402

SPEEDS = (0.003, 0.01, 0.03, 0.1, 0.3)
PAIRS = ((1, 1), (1, 2), (2, 2))
K_N = 1e5


def parse(argv):
    opts = {"dt": 1e-8, "tol": 1e-4, "types": [], "tables": None, "swap": False, "control": False}
    k = 0
    while k < len(argv):
        a = argv[k]
        if a in ("--dt", "--tol", "--type", "--tables"):
            if k + 1 >= len(argv):
                raise SystemExit(f"pairs.py: {a} needs a value")
            v = argv[k + 1]
            k += 1
            if a == "--type":
                try:
                    r, rho = (float(x) for x in v.split(":"))
                except ValueError:
                    r = rho = -1.0
                if not (0.0 < r < math.inf and 0.0 < rho < math.inf):
                    raise SystemExit(f"pairs.py: --type {v}: give RADIUS:DENSITY (m, kg/m^3), "
                                     "both > 0")
                opts["types"].append((r, rho))
            elif a == "--tables":
                opts["tables"] = v
            else:
                try:
                    opts[a[2:]] = float(v)
                except ValueError:
                    raise SystemExit(f"pairs.py: {a} {v}: not a number")
        elif a == "--swap":
            opts["swap"] = True
        elif a == "--control":
            opts["control"] = True
        else:
            raise SystemExit(f"pairs.py: unknown argument {a} (see the docstring)")
        k += 1
    if len(opts["types"]) != 2 or not opts["tables"]:
        raise SystemExit("pairs.py: give --type twice and --tables DIR")
    return opts


def refuses(fn, words):
    """fn() raises ValueError whose one-line message holds every word"""
    try:
        fn()
    except ValueError as e:
        msg = str(e)
        return "\n" not in msg and all(w in msg for w in words), msg
    return False, "no error"


def api_checks(paths):
    """the runner's refusals, with stand-in materials (id, label) as Yade's carry them"""
    fails = []
    t11 = paths[(1, 1)]
    cases = [
        ("no table, no pairs", lambda: cantact_yade.Damping(), ["give a table", "pairs="]),
        ("a key of one material", lambda: cantact_yade.Damping(pairs={("a",): t11}),
         ["two materials"]),
        ("a key of a float", lambda: cantact_yade.Damping(pairs={("a", 1.5): t11}),
         ["its id (int)", "1.5"]),
        ("a pair given twice", lambda: cantact_yade.Damping(pairs={("a", "b"): t11,
                                                                   ("b", "a"): t11}),
         ["same pair"]),
        ("a table of no file", lambda: cantact_yade.Damping(pairs={("a", "b"): 3}),
         ["a path or a cantact.Table"]),
    ]
    for name, fn, words in cases:
        ok, msg = refuses(fn, words)
        if not ok:
            fails.append(f"api: {name}: {msg}")
    a = types.SimpleNamespace(id=0, label="a")
    b = types.SimpleNamespace(id=1, label="")
    c = types.SimpleNamespace(id=2, label="c")
    d = cantact_yade.Damping(pairs={("a", 1): t11})
    if d.table_of(b, a) is not d.table_of(a, b):
        fails.append("api: (a, b) and (b, a) differ")
    ok, msg = refuses(lambda: d.table_of(a, c), ["no table", "'a' (id 0)", "'c' (id 2)"])
    if not ok:
        fails.append(f"api: a contact of a pair not listed: {msg}")
    d = cantact_yade.Damping(pairs={("a", "a"): t11, (0, 0): paths[(2, 2)]})
    ok, msg = refuses(lambda: d.table_of(a, a), ["different tables"])
    if not ok:
        fails.append(f"api: a pair named by label and by id with two tables: {msg}")
    d = cantact_yade.Damping(t11, pairs={("a", "c"): paths[(2, 2)]})
    if d.table_of(a, b) is not d.table or d.table_of(c, a) is d.table:
        fails.append("api: the default table for the pairs not listed")
    return fails


def run(opts, paths, ref, m_red, swap):
    """one run of every pair at every speed; (misses beyond --tol, other failures)"""
    from yade import O
    from yade.minieigenHP import Vector3
    from yade.wrapper import (Bo1_Sphere_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom,
                              InsertionSortCollider, InteractionLoop,
                              Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_ViscElPhys_Basic,
                              NewtonIntegrator, ViscElMat)
    from yade import utils

    O.reset()
    dt, tol = opts["dt"], opts["tol"]
    failed = 0
    # two materials in series give the contact's kn: 2 k_n each; cn = 0 until the runner sets it
    mats = []
    for t, (r, rho) in enumerate(opts["types"], 1):
        mats.append(ViscElMat(kn=2 * K_N, ks=0, cn=0, cs=0, frictionAngle=0, density=rho,
                              label="type%d" % t))
        O.materials.append(mats[-1])
    given = dict(paths)
    if swap:
        given[(1, 1)], given[(2, 2)] = paths[(2, 2)], paths[(1, 1)]
    damping = cantact_yade.Damping(pairs={("type1", "type1"): given[(1, 1)],
                                          (mats[1].id, mats[0].id): given[(1, 2)],
                                          (mats[1], mats[1]): given[(2, 2)]})
    bodies = []
    j = 0
    for p in PAIRS:
        (ra, _), (rb, _) = opts["types"][p[0] - 1], opts["types"][p[1] - 1]
        for v in SPEEDS:
            phase = (0.5 + 0.6180339887498949 * j) % 1.0  # first touch part of the way into a step
            gap = v * dt * (2.0 + phase)
            y = 0.01 * j
            a = O.bodies.append(utils.sphere((0, y, 0), ra, material=mats[p[0] - 1]))
            b = O.bodies.append(utils.sphere((ra + rb + gap, y, 0), rb, material=mats[p[1] - 1]))
            ma, mb = O.bodies[a].state.mass, O.bodies[b].state.mass
            O.bodies[a].state.vel = Vector3(mb / (ma + mb) * v, 0, 0)
            O.bodies[b].state.vel = Vector3(-ma / (ma + mb) * v, 0, 0)
            bodies.append((a, b, p, v))
            j += 1
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                                 [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                                 [Law2_ScGeom_ViscElPhys_Basic()]),
                 damping.engine(),
                 NewtonIntegrator(damping=0, gravity=(0, 0, 0))]
    damping.check_engines()
    O.dt = dt
    t_long = math.pi / math.sqrt(K_N / max(m_red.values()))  # the slowest pair's undamped contact
    start = time.time()
    limit = int(20 * t_long / dt)
    chunk = max(100, int(0.05 * t_long / dt))
    while O.iter < limit:
        O.run(chunk, True)
        apart = all(O.bodies[a].state.vel[0] - O.bodies[b].state.vel[0] < 0
                    for a, b, _, _ in bodies)
        if apart and len([i for i in O.interactions if i.isReal]) == 0:
            break
    elapsed = time.time() - start
    print("pair,v_impact_m_s,e_table,e_yade,e_yade_minus_e_table")
    worst = {p: 0.0 for p in PAIRS}
    misses = 0
    for a, b, p, v in bodies:
        e_table = float(ref[p].e_of_speed(v)[0])
        e_yade = -(O.bodies[a].state.vel[0] - O.bodies[b].state.vel[0]) / v
        d = e_yade - e_table
        worst[p] = max(worst[p], abs(d))
        print(f"{p[0]}-{p[1]},{v!r},{e_table:.17g},{e_yade:.17g},{d:.3g}")
        if not abs(d) <= tol:
            misses += 1
    # each contact's e, bit for bit its pair's table's (the log: id1, id2, iter, v_n, e, ...)
    pair_of = {}
    for a, b, p, _ in bodies:
        pair_of[(a, b)] = pair_of[(b, a)] = p
    for id1, id2, _, v_n, e, _, _ in damping.log:
        p = pair_of[(id1, id2)]
        if not swap and e != float(ref[p].e_of_speed(v_n)[0]):
            print(f"FAIL: contact {id1}-{id2} (pair {p[0]}-{p[1]}): e {e!r} is not its table's")
            failed += 1
    if damping.contacts != len(bodies):
        print(f"FAIL: {damping.contacts} contacts set up, expected {len(bodies)}")
        failed += 1
    if O.iter >= limit:
        print(f"FAIL: the pairs had not separated after {O.iter} steps")
        failed += 1
    if damping.outside:
        print(f"FAIL: {damping.outside} impact speeds outside their table")
        failed += 1
    print(f"pairs.py: dt = {dt:g} s{' (1-1 and 2-2 tables swapped)' if opts['swap'] else ''}: "
          f"worst |e_yade - e of the pair's table| "
          + ", ".join(f"{p[0]}-{p[1]} {worst[p]:.3g}" for p in PAIRS)
          + f"; {misses} of {len(bodies)} beyond {tol:g}; {O.iter} steps in {elapsed:.2f} s")
    return misses, failed


def main():
    opts = parse(sys.argv[1:])
    paths = {p: os.path.join(opts["tables"], "e_%d_%d.csv" % p) for p in PAIRS}
    for p in paths.values():
        if not os.path.isfile(p):
            raise SystemExit(f"pairs.py: {p}: no such table (dem/pair_tables.py writes it)")
    status = 0
    fails = api_checks(paths)
    for f in fails:
        print("FAIL: " + f)
    if fails:
        status = 1
    else:
        print("ok: cantact_yade refuses bad pairs in one line (no table, a bad key, a pair twice, "
              "a file that is no table, a contact of no pair, two tables for one pair)")

    # the tables, read here (the reference: not through the runner)
    ref = {p: cantact.read_table(path) for p, path in paths.items()}
    mass = [None] + [rho * 4.0 / 3.0 * math.pi * r ** 3 for r, rho in opts["types"]]
    m_red = {(i, j): mass[i] * mass[j] / (mass[i] + mass[j]) for i, j in PAIRS}
    c = [ref[p].v_per_V_star ** 2 * m_red[p] for p in PAIRS]
    if not max(c) - min(c) <= 1e-12 * max(c):
        print(f"FAIL: the tables' v_per_V_star^2 m_red differ ({c}): a table not written for "
              "its pair's reduced mass")
        status = 1

    misses, failed = run(opts, paths, ref, m_red, opts["swap"])
    status = 1 if (misses or failed) else status
    if opts["control"] and not opts["swap"]:
        # the check can fail: the same run with the 1-1 and 2-2 tables swapped must miss
        misses, failed = run(opts, paths, ref, m_red, True)
        if failed or not misses:
            print("FAIL: the 1-1 and 2-2 tables swapped " + ("failed otherwise" if failed else
                  "passed the check: it cannot fail"))
            status = 1
        else:
            print(f"ok: with the 1-1 and 2-2 tables swapped, {misses} of "
                  f"{len(SPEEDS) * len(PAIRS)} rebounds miss their pair's table: the check fails")
    return status


import cantact  # noqa: E402

cantact_yade.main_guard(main)
