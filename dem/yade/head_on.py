"""Two steel spheres (radius 2 mm, 7850 kg/m^3) head-on in Yade, k_n = 1e5 N/m, no gravity, no
friction, at several speeds at once (one pair per speed, far apart): each pair's rebound ratio
against the cantact table's e at its impact speed. Yade's law clips the normal force at 0, so
cantact_yade sets cn from the clipped law's relation; NewtonIntegrator damping = 0.

    yade -n -x head_on.py TABLE.csv [--dt 1e-8] [--tol 1e-4] [--speeds 0.02,0.05,...]
                                    [--no-first-step] [--no-dt-compensation] [--law clipped]

--law tension sets cn from the tension law's relation (wrong for Yade's clipped force: the
test runs it to see the check fail), --no-first-step and --no-dt-compensation turn off
cantact_yade's corrections (to measure what they do).

Prints one row per pair and the worst |e_yade - e_table|; exits 1 if it is above --tol (or a
contact was not set up, or a pair did not separate), 0 otherwise. Needs cantact (python/)
and cantact_yade (beside this file) on the path: dem/yade/test.sh sets it up."""
import math
import os
import sys
import time

# yade runs the script with its own globals (__file__ is yade's): the script is argv[0]
sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
import cantact_yade  # noqa: E402


def parse(argv):
    opts = {"dt": 1e-8, "tol": 1e-4, "first_step": True, "dt_compensation": True, "law": "clipped",
            "speeds": [0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 4.0, 6.0], "table": None}
    k = 0
    while k < len(argv):
        a = argv[k]
        if a in ("--dt", "--tol", "--speeds", "--law"):
            if k + 1 >= len(argv):
                raise SystemExit(f"head_on.py: {a} needs a value")
            v = argv[k + 1]
            k += 1
            if a == "--speeds":
                opts["speeds"] = [float(x) for x in v.split(",")]
            elif a == "--law":
                opts["law"] = v
            else:
                opts[a[2:]] = float(v)
        elif a == "--no-first-step":
            opts["first_step"] = False
        elif a == "--no-dt-compensation":
            opts["dt_compensation"] = False
        elif a.startswith("-"):
            raise SystemExit(f"head_on.py: unknown option {a}")
        else:
            opts["table"] = a
        k += 1
    if not opts["table"]:
        raise SystemExit(__doc__)
    return opts


def main():
    from yade import O
    from yade.minieigenHP import Vector3
    from yade.wrapper import (Bo1_Sphere_Aabb, ForceResetter, Ig2_Sphere_Sphere_ScGeom,
                              InsertionSortCollider, InteractionLoop,
                              Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_ViscElPhys_Basic,
                              NewtonIntegrator, ViscElMat)
    from yade import utils

    opts = parse(sys.argv[1:])
    dt, r, k_n = opts["dt"], 2e-3, 1e5
    damping = cantact_yade.Damping(opts["table"], law=opts["law"], first_step=opts["first_step"],
                                   dt_compensation=opts["dt_compensation"])
    # two materials in series give the contact's kn: 2 k_n each; cn = 0 until the runner sets it
    mat = O.materials.append(ViscElMat(kn=2 * k_n, ks=0, cn=0, cs=0, frictionAngle=0,
                                       density=7850))
    pairs = []
    for j, v in enumerate(opts["speeds"]):
        # first touch part of the way into the third step, a different part for every pair
        phase = (0.5 + 0.6180339887498949 * j) % 1.0
        gap = v * dt * (2.0 + phase)
        y = 10 * r * j
        a = O.bodies.append(utils.sphere((0, y, 0), r, material=mat))
        b = O.bodies.append(utils.sphere((2 * r + gap, y, 0), r, material=mat))
        O.bodies[a].state.vel = Vector3(0.5 * v, 0, 0)
        O.bodies[b].state.vel = Vector3(-0.5 * v, 0, 0)
        pairs.append((a, b, v))
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                                 [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                                 [Law2_ScGeom_ViscElPhys_Basic()]),
                 damping.engine(),
                 NewtonIntegrator(damping=0, gravity=(0, 0, 0))]
    damping.check_engines()
    O.dt = dt
    m = O.bodies[0].state.mass
    t_contact = math.pi / math.sqrt(k_n / (0.5 * m))  # undamped; damping only lengthens it
    start = time.time()
    limit = int(20 * t_contact / dt)
    chunk = max(100, int(0.05 * t_contact / dt))
    while O.iter < limit:
        O.run(chunk, True)
        apart = all(O.bodies[a].state.vel[0] - O.bodies[b].state.vel[0] < 0 for a, b, _ in pairs)
        if apart and len([i for i in O.interactions if i.isReal]) == 0:
            break
    elapsed = time.time() - start
    status = 0
    print(f"v_impact_m_s,e_table,zeta_{opts['law']},e_yade,e_yade_minus_e_table")
    worst = 0.0
    for a, b, v in pairs:
        e_table = float(damping.table.e_of_speed(v)[0])
        e_yade = -(O.bodies[a].state.vel[0] - O.bodies[b].state.vel[0]) / v
        d = e_yade - e_table
        worst = max(worst, abs(d))
        print(f"{v!r},{e_table:.17g},{cantact.zeta_of_e(e_table, law=opts['law']):.17g},"
              f"{e_yade:.17g},{d:.3g}")
        if not abs(d) <= opts["tol"]:
            status = 1
    if damping.contacts != len(pairs):
        print(f"head_on.py: {damping.contacts} contacts set up, expected {len(pairs)}")
        status = 1
    if O.iter >= limit:
        print(f"head_on.py: the pairs had not separated after {O.iter} steps")
        status = 1
    if damping.outside:
        print(f"head_on.py: {damping.outside} impact speeds outside the table")
    print(f"head_on.py: dt = {dt:g} s ({t_contact / dt:.0f} steps per undamped contact), "
          f"law {opts['law']}, first_step = {opts['first_step']}, dt_compensation = "
          f"{opts['dt_compensation']}: "
          f"worst |e_yade - e_table| = {worst:.3g} (tolerance {opts['tol']:g}), {O.iter} steps "
          f"in {elapsed:.2f} s")
    return status


import cantact  # noqa: E402

cantact_yade.main_guard(main)
