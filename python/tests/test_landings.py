"""Landings from Python (cantact.landings, the CLI's [body] landings and seed): apexes drawn
uniformly over the region where the face stays on the surface (its bounds computed here from
the geometry), landing k a function of (seed, k) alone, each landing bit for bit
cantact.restitution with the body's apex there, the same bits for 1 and 2 threads and either
split and as `cantact run` writes them; what cannot land is refused."""
import csv
import math
import os
import subprocess

import numpy as np
import pytest

import cantact

IN = cantact.InvalidInput
K = np.arange(201, dtype=float)
TOP = 0.5 * (1 + np.sin(K * 1.7))
RHO = math.sqrt(2 * (2 * 100 - 2))  # sqrt(H* (2R - H*)): H* = 2, R = 100
V = [1e-3, 1e-2]


def rods():
    return cantact.Rods(TOP, np.ones(201), E=500, Hstar=2, x=K)


def run(**kw):
    args = dict(body=cantact.Cylinder(100), landings=40, seed=5, impacts=2)
    args.update(kw)
    return cantact.landings(rods(), V, **args)


def test_each_landing_is_the_run_at_its_apex():
    L = run()
    assert L.e.shape == (40, 2, 2) and (L.status == 0).all()
    assert np.isnan(L.y).all() and (L.realisations == np.arange(40)).all()
    for k in (0, 13, 39):
        one = cantact.restitution(rods(), V, body=cantact.Cylinder(100, position=L.x[k]),
                                  impacts=2)
        assert np.array_equal(one.e, L.e[k]) and np.array_equal(one.u_max_over_h0,
                                                                L.u_max_over_h0[k])


def test_uniform_over_the_region():
    L = run(landings=1000, impacts=1, threads=2)
    w = 200 - 2 * RHO
    u = (L.x - RHO) / w
    assert ((u >= 0) & (u <= 1)).all()
    # Kolmogorov-Smirnov against the uniform law at 1 % (critical value 1.63 / sqrt(n))
    s = np.sort(u)
    n = s.size
    d = max(np.max(np.arange(1, n + 1) / n - s), np.max(s - np.arange(n) / n))
    assert d < 1.63 / math.sqrt(n)


def test_a_landing_is_a_function_of_seed_and_index():
    a, b = run(landings=12), run(landings=4, first=8)
    assert np.array_equal(a.x[8:], b.x) and np.array_equal(a.e[8:], b.e)
    assert not np.array_equal(a.x, run(landings=12, seed=6).x)


def test_threads_and_split_give_the_same_bits():
    a = run(threads=1)
    for kw in (dict(threads=2), dict(threads=2, split="rods")):
        b = run(**kw)
        assert np.array_equal(a.x, b.x) and np.array_equal(a.e, b.e)


def test_as_the_cli_writes_them(tmp_path):
    with open(tmp_path / "rods.csv", "w") as f:
        f.write("top,area,x\n")
        for k in range(201):
            f.write("%.17g,1,%d\n" % (TOP[k], k))
    (tmp_path / "c.ini").write_text(
        "[surface]\ntype = rods\nfile = rods.csv\nHstar = 2\n[body]\nshape = cylinder\n"
        "radius = 100\nlandings = 40\nseed = 5\n[material]\nE = 500\n[impact]\n"
        "V_star = 0.001, 0.01\nimpacts = 2\n[output]\nwhat = landings\n")
    subprocess.run([os.environ["CANTACT_CLI"], "run", "-q", str(tmp_path / "c.ini"), "-o",
                    str(tmp_path / "l.csv")], check=True)
    with open(tmp_path / "l.csv") as f:
        rows = list(csv.DictReader(f.readlines()[1:]))
    L = run()
    assert len(rows) == L.e.size
    for r in rows:
        k, v, i = int(r["landing"]), V.index(float(r["V_star"])), int(r["impact"]) - 1
        assert r["x"] == "%.17g" % L.x[k] and float(r["e"]) == L.e[k, v, i]


def test_what_cannot_land_is_refused():
    with pytest.raises(IN, match="landings need a curved body"):
        cantact.landings(rods(), V, body=None, landings=3)
    with pytest.raises(IN, match="no apex keeps its face on the surface"):
        run(body=cantact.Cylinder(1e4))
    rc = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=6, fx_spread=0.1)
    with pytest.raises(IN, match="landings"):
        cantact.landings(rc, V, body=cantact.Cylinder(10), landings=3)
    with pytest.raises(IN, match="landings"):
        run(landings=0)
    with pytest.raises(IN, match="seed"):
        run(seed=-1)


def test_a_table_of_landings_read_and_saved(tmp_path):
    """`cantact table` of landings: read_table gives its quantile columns, quantile() is e at
    the columns at the nodes (their own values, the median column's at p = 0.5), and save()
    writes them back so that the file reads as it was (a table of samples kept whole)."""
    with open(tmp_path / "rods.csv", "w") as f:
        f.write("top,area,x\n")
        for k in range(201):
            f.write("%.17g,1,%d\n" % (TOP[k], k))
    (tmp_path / "c.ini").write_text(
        "[surface]\ntype = rods\nfile = rods.csv\nHstar = 2\n[body]\nshape = cylinder\n"
        "radius = 100\nlandings = 30\nseed = 5\n[material]\nE = 500\n[impact]\n"
        "V_star = 0.001, 0.01\n[table]\ntolerance = 1e-3\ngrid = 2000\n"
        "quantiles = 0.1, 0.5, 0.9\n")
    subprocess.run([os.environ["CANTACT_CLI"], "table", "-q", str(tmp_path / "c.ini"), "-o",
                    str(tmp_path / "t.csv")], check=True)
    t = cantact.read_table(tmp_path / "t.csv")
    assert t.p.tolist() == [0.1, 0.5, 0.9] and t.e_quantiles.shape == (3, t.V_star.size)
    assert np.array_equal(t.quantile(t.V_star, 0.5), t.e_quantiles[1])
    assert (t.e_quantiles[0] <= t.e_quantiles[2]).all()
    t.save(tmp_path / "u.csv")
    u = cantact.read_table(tmp_path / "u.csv")
    assert np.array_equal(u.e_quantiles, t.e_quantiles)
    assert np.array_equal(u.slope_quantiles, t.slope_quantiles)
    assert np.array_equal(u.quantile(t.V_star, 0.3), t.quantile(t.V_star, 0.3))
    with pytest.raises(IN, match="p: must be in"):
        t.quantile(1e-3, 1.5)
    plain = cantact.table(rods(), V_star=(1e-3, 1e-2), tolerance=1e-3)
    with pytest.raises(IN, match="no quantile columns"):
        plain.quantile(1e-3, 0.5)
