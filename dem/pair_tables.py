#!/usr/bin/env python3
"""One cantact e(V*) table per pair of particle types, for a DEM engine (docs/dem.md, "e(v) for
a pair of particles").

    dem/pair_tables.py SCENE.ini --type R1:RHO1 --type R2:RHO2 [...] -o DIR
                       [--cantact PATH] [--set SECTION.KEY=VALUE]... [-q]

Particle type I is a sphere of radius R_I (m) and density RHO_I (kg/m^3), m_I = 4/3 pi R_I^3
RHO_I. For every pair of types I <= J it runs

    cantact table SCENE --set body.shape=sphere --set body.radius=R_IJ --set impact.mass=m_IJ
                        [--set ...] -o DIR/e_I_J.csv

with the reduced radius R_IJ = R_I R_J / (R_I + R_J) and the reduced mass m_IJ = m_I m_J /
(m_I + m_J): the assumption (docs/dem.md) that the contact of two rough spheres is a rigid
sphere of the reduced radius and mass striking the surface that carries the roughness. SCENE
must be an areal surface in SI units (an X3P map, or rods placed by x and y, lengths in m, E in
Pa), as scripts/scenes/dem_pair_table.ini is; a line surface (Cantor, a line profile) cannot
carry a sphere and cantact says so. Each table's v_per_V_star is then that pair's, so the
engine converts its speeds (LAMMPS: pair_coeff I J table DIR/e_I_J.csv; Yade: cantact_yade.
Damping(pairs={...})). Prints one line per pair: the types, R_IJ, m_IJ and the file.
Exit 0 when every table is written; 2 on bad arguments, 1 when cantact fails: either way one
line on stderr (cantact's own message named with the pair).
"""
import argparse
import math
import os
import subprocess
import sys


class Parser(argparse.ArgumentParser):
    def error(self, message):
        """one line, not argparse's usage and message"""
        sys.stderr.write("%s: %s (--help: the usage)\n" % (self.prog, message))
        sys.exit(2)


def particle(text):
    """R:RHO -> (R, RHO), both finite and > 0"""
    parts = text.split(":")
    try:
        r, rho = (float(p) for p in parts) if len(parts) == 2 else (None, None)
    except ValueError:
        r, rho = None, None
    if r is None or not (0.0 < r < math.inf and 0.0 < rho < math.inf):
        raise argparse.ArgumentTypeError(
            "%r: give RADIUS:DENSITY, in m and kg/m^3, both > 0 (e.g. 2e-3:7850)" % text)
    return r, rho


def mass(r, rho):
    return rho * 4.0 / 3.0 * math.pi * r ** 3


def reduced(a, b):
    return a * b / (a + b)


def pairs(types):
    """[(I, J, R_IJ, m_IJ)] for I <= J, types numbered from 1"""
    out = []
    for i, (ri, rhoi) in enumerate(types, 1):
        for j, (rj, rhoj) in enumerate(types, 1):
            if j >= i:
                out.append((i, j, reduced(ri, rj), reduced(mass(ri, rhoi), mass(rj, rhoj))))
    return out


def main(argv=None):
    here = os.path.dirname(os.path.abspath(__file__))
    ap = Parser(
        prog="pair_tables.py", formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__.split("\n\n", 1)[0] + "\n\n" + __doc__.split("\n\n", 2)[2])
    ap.add_argument("scene", metavar="SCENE.ini", help="an areal surface in SI units")
    ap.add_argument("--type", dest="types", action="append", type=particle, required=True,
                    metavar="R:RHO", help="a particle type: radius (m) and density (kg/m^3); "
                    "types are numbered 1, 2, ... in the order given")
    ap.add_argument("-o", dest="outdir", required=True, metavar="DIR",
                    help="the tables go to DIR/e_I_J.csv (DIR is created)")
    ap.add_argument("--cantact", default=os.path.join(here, "..", "build", "cantact"),
                    help="the cantact program (default: build/cantact of this checkout)")
    ap.add_argument("--set", dest="sets", action="append", default=[], metavar="KEY=VALUE",
                    help="passed to cantact table (not body.shape, body.radius, impact.mass)")
    ap.add_argument("-q", action="store_true", help="no line per pair")
    a = ap.parse_args(argv)
    if not os.path.isfile(a.scene):
        ap.error("%s: no such scene" % a.scene)
    if not (os.path.isfile(a.cantact) and os.access(a.cantact, os.X_OK)):
        ap.error("--cantact %s: not an executable (build the project: ninja -C build)" % a.cantact)
    for s in a.sets:
        key = s.split("=", 1)[0].strip()
        if key in ("body.shape", "body.radius", "impact.mass"):
            ap.error("--set %s: pair_tables.py sets %s itself (from --type)" % (s, key))
    os.makedirs(a.outdir, exist_ok=True)
    for i, j, r, m in pairs(a.types):
        path = os.path.join(a.outdir, "e_%d_%d.csv" % (i, j))
        cmd = [a.cantact, "table", "-q", a.scene, "--set", "body.shape=sphere",
               "--set", "body.radius=%.17g" % r, "--set", "impact.mass=%.17g" % m]
        for s in a.sets:
            cmd += ["--set", s]
        cmd += ["-o", path]
        p = subprocess.run(cmd, stderr=subprocess.PIPE, universal_newlines=True)
        if p.returncode != 0:
            said = "; ".join(l.strip() for l in p.stderr.splitlines() if l.strip())
            sys.stderr.write("pair_tables.py: types %d %d (R %.6g m, m %.6g kg): cantact table "
                             "exit %d: %s\n" % (i, j, r, m, p.returncode, said or "no message"))
            return 1
        if not a.q:
            print("types %d %d: R_red %.6g m, m_red %.6g kg: %s" % (i, j, r, m, path))
    return 0


if __name__ == "__main__":
    sys.exit(main())
