"""cantact.Profile (a measured surface, MODEL.md §9) against references that do not come from
the module: a bearing curve counted by hand, the independent NumPy computation of the same
rods (tests/profile_reference.py), and the cantact program, which must agree to the last bit
(the same library path) for e, V* and the fit."""
import csv
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import cantact


@pytest.fixture(scope="module")
def dektak(source):
    return os.path.join(source, "tests", "data", "dektak-1.csv")


SPEEDS = [0.003, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0]


def test_bearing_counted_by_hand():
    # four samples 1 um apart at 0, -1, -2, -3 um, not levelled: every sample's share is
    # 1 um (the ends get the whole distance to their one neighbour), so phi steps by 1/4 at
    # each depth; Rt = 3 um, l0 = 4 um
    p = cantact.Profile(z=[0.0, -1e-6, -2e-6, -3e-6], dx=1e-6, detrend="none", E=2e11,
                        sigma_y=4e8, H=2)
    np.testing.assert_array_equal(p.bearing([0.0, 0.5e-6, 1e-6, 2.5e-6, 3e-6, 1.0]),
                                  [0.25, 0.25, 0.5, 0.75, 1.0, 1.0])
    assert p.stats["Rt"] == pytest.approx(3e-6, rel=1e-15)
    assert p.layer["l0"] == pytest.approx(4e-6, rel=1e-15)
    assert p.layer["h0"] == p.stats["Rt"] and p.layer["Hstar"] == 2 * p.stats["Rt"]
    assert p.source == "arrays" and p.invalid == 0


def test_dektak_against_numpy_reference(dektak, source):
    p = cantact.Profile(dektak, E=2e11, sigma_y=4e8, H=10)
    r = cantact.restitution(p, mass=1e-3, speed=SPEEDS)
    ref = subprocess.run([sys.executable, os.path.join(source, "tests", "profile_reference.py"),
                          dektak, "1e-6", "10", "2e11", "4e8", "1e-3", *map(str, SPEEDS)],
                         check=True, capture_output=True, text=True).stdout.splitlines()
    rows = [line.split(",") for line in ref if line[:1].isdigit()]
    Rq, Rt, l0 = map(float, [line for line in ref if line.startswith("#")][0].split()[1:])
    assert len(rows) == len(SPEEDS)
    np.testing.assert_allclose(r.V_star, [float(x[1]) for x in rows], rtol=1e-9)
    np.testing.assert_allclose(r.e[:, 0], [float(x[2]) for x in rows], rtol=0, atol=1e-9)
    assert p.stats["Rq"] == pytest.approx(Rq, rel=1e-9)
    assert p.stats["Rt"] == pytest.approx(Rt, rel=1e-9)
    assert p.layer["l0"] == pytest.approx(l0, rel=1e-9)


def test_dektak_as_the_cli(dektak, tmp_path, run_cli, cli):
    scene = tmp_path / "d.ini"
    scene.write_text(f"[surface]\ntype = profile\nfile = {dektak}\nH = 10\n[material]\n"
                     f"E = 2e11\nsigma_y = 4e8\n[impact]\nmass = 1e-3\n"
                     f"velocity = {', '.join(map(str, SPEEDS))}\n")
    rows = list(csv.DictReader(open(run_cli("run", str(scene)))))
    p = cantact.Profile(dektak, E=2e11, sigma_y=4e8, H=10)
    r = cantact.restitution(p, mass=1e-3, speed=SPEEDS)
    assert [float(x["e"]) for x in rows] == list(r.e[:, 0])
    assert [float(x["V_star"]) for x in rows] == list(r.V_star)
    subprocess.run([cli, "fit", dektak, "-o", str(tmp_path / "fit.csv")], check=True)
    fit = {row[0]: row[1:] for row in csv.reader(
        line for line in open(tmp_path / "fit.csv") if line[0] != "#")}
    f = p.fit()
    for key, name in (("alpha", "alpha"), ("h0", "h0_m"), ("D", "D"), ("fx", "fx"),
                      ("fz", "fz"), ("D_structure", "D_structure"), ("D_spectrum", "D_spectrum")):
        assert f[key] == float(fit[name][0]), key
    assert f["bearing"]["points"] == int(fit["alpha"][3])
    s = cantact.Profile(dektak, E=2e11, sigma_y=4e8, H=10).fit(dimension="structure")
    assert s["D"] == s["D_structure"] != f["D"]


def test_arrays_as_a_file(tmp_path):
    # a one-column file at a spacing, and the same heights as an array: the same rods
    z = 1e-7 * np.sin(0.37 * np.arange(500)) + 3e-8 * np.cos(2.9 * np.arange(500))
    (tmp_path / "z.txt").write_text("z_nm\n" + "\n".join("%.17g" % (v * 1e9) for v in z))
    a = cantact.Profile(tmp_path / "z.txt", spacing=500.0, unit="nm", E=2e11, sigma_y=4e8, H=10)
    b = cantact.Profile(z=z, dx=500e-9, E=2e11, sigma_y=4e8, H=10)
    V = np.geomspace(1e-4, 1e-2, 9)
    ea, eb = (cantact.restitution(s, V_star=V).e for s in (a, b))
    np.testing.assert_allclose(ea, eb, rtol=0, atol=1e-13)
    x = 500e-9 * np.arange(500)
    c = cantact.Profile(z=z, x=x, E=2e11, sigma_y=4e8, H=10)
    np.testing.assert_allclose(cantact.restitution(c, V_star=V).e, eb, rtol=0, atol=1e-13)
    assert a.source == "text"


def test_grid_leaves_out_invalid_points():
    rng = np.random.default_rng(7)
    z = 1e-7 * rng.normal(size=(16, 24))
    z[3, 5] = z[10, 0] = np.nan
    g = cantact.Profile(z=z, dx=1e-6, dy=2e-6, E=2e11, sigma_y=4e8, H=5)
    assert g.invalid == 2
    assert g.heights.shape == (16, 24) and np.isnan(g.heights).sum() == 2
    assert g.layer["l0"] == pytest.approx((16 * 24 - 2) * 2e-12, rel=1e-12)  # the valid area
    r = cantact.restitution(g, V_star=[1e-3])
    assert r.status[0, 0] == 0 and 0 < r.e[0, 0] <= 1


def raises(exc, match, fn, *args, **kw):
    with pytest.raises(exc, match=match) as info:
        fn(*args, **kw)
    assert isinstance(info.value, cantact.Error)
    return info.value


def test_bad_input(tmp_path, dektak):
    m = dict(E=2e11, sigma_y=4e8)
    raises(cantact.IOFailure, "nothere.csv", cantact.Profile, tmp_path / "nothere.csv", H=10, **m)
    raises(cantact.InvalidInput, "exactly one", cantact.Profile, dektak, H=10, Hstar=1e-5, **m)
    raises(cantact.InvalidInput, "exactly one", cantact.Profile, dektak, **m)
    raises(cantact.InvalidInput, "must exceed", cantact.Profile, dektak, Hstar=1e-7, **m)
    raises(cantact.InvalidInput, "unit", cantact.Profile, dektak, unit="furlong", H=10, **m)
    raises(cantact.InvalidInput, "give one", cantact.Profile, dektak, z=[1, 2, 3], H=10, **m)
    raises(cantact.InvalidInput, "all heights are equal", cantact.Profile, z=[1.0] * 5, dx=1.0,
           H=10, **m)
    raises(cantact.InvalidInput, "at least 3", cantact.Profile, z=[0.0, 1.0], dx=1.0, H=10, **m)
    raises(cantact.InvalidInput, "not increasing", cantact.Profile, z=[0.0, 1.0, 0.5],
           x=[0.0, 2.0, 1.0], H=10, **m)
    raises(cantact.InvalidInput, "dimensions", cantact.Profile, z=np.zeros((2, 2, 2)), dx=1.0,
           H=10, **m)
    (tmp_path / "bad.csv").write_text("x_um,z_um\n0,1\n1,oops\n2,3\n")
    raises(cantact.InvalidInput, "bad.csv:3", cantact.Profile, tmp_path / "bad.csv", H=10, **m)
    p = cantact.Profile(dektak, H=10, **m)
    raises(cantact.InvalidInput, "depths", p.fit, depths=(2e-7, 1e-7))
    raises(cantact.InvalidInput, "dimension", p.fit, dimension="boxes")
    raises(cantact.InvalidInput, "ascending", p.bearing, [2e-7, 1e-7])
    assert not math.isnan(p.fit()["D"])
