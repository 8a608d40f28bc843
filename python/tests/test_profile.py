"""cantact.Profile (a measured surface, MODEL.md §9) against references that do not come from
the module: a bearing curve counted by hand, the independent NumPy computation of the same
rods (tests/profile_reference.py), and the cantact program, which must agree to the last bit
(the same library path) for e, V* and the fit."""
import csv
import math
import os
import subprocess
import sys
import warnings

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
    raises(cantact.InvalidInput, "needs one of surface.H", cantact.Profile, dektak, H=10,
           Hstar=1e-5, **m)
    raises(cantact.InvalidInput, "needs one of surface.H", cantact.Profile, dektak, **m)
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
    raises(cantact.InvalidInput, r"depth band \[2e-07, 1e-07\] empty", p.fit,
           depths=(2e-7, 1e-7))
    raises(cantact.InvalidInput, "dimension", p.fit, dimension="boxes")
    raises(cantact.InvalidInput, "ascending", p.bearing, [2e-7, 1e-7])
    assert not math.isnan(p.fit()["D"])


def test_bad_arrays_and_paths(dektak):
    # every array and path argument checked in Python: an InvalidInput naming it, never
    # NumPy's ValueError or ComplexWarning, nor Python's TypeError
    m = dict(E=2e11, sigma_y=4e8, H=2)
    z = [0.0, 1e-6, -2e-6, 3e-6]
    grid = 1e-7 * np.arange(12.0).reshape(3, 4) ** 2
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        IN = cantact.InvalidInput
        raises(IN, r"^z: must hold real numbers, got dtype <U1", cantact.Profile,
               z=["a", "b", "c"], dx=1.0, **m)
        raises(IN, r"^z: .*got a string", cantact.Profile, z="abc", dx=1.0, **m)
        raises(IN, r"^z: .*got booleans", cantact.Profile,
               z=np.array([True, False, True, False]), dx=1.0, **m)
        raises(IN, r"^z: .*got dtype complex128", cantact.Profile, z=np.array(z) + 1j, dx=1.0,
               **m)
        raises(IN, r"^z\[2\] = None: must be a real number, got NoneType", cantact.Profile,
               z=np.array([0.0, 1.0, None, 2.0], dtype=object), dx=1.0, **m)
        raises(IN, r"^z: not an array of numbers", cantact.Profile, z=[[0.0, 1.0], [2.0]],
               dx=1.0, dy=1.0, **m)
        raises(IN, r"^z\[1\] = nan: must be finite", cantact.Profile, z=[0, np.nan, 1, 2],
               dx=1.0, **m)
        raises(IN, r"^z\[2\] = -inf: must be finite", cantact.Profile, z=[0, 1, -np.inf, 2],
               dx=1.0, **m)
        g = grid.copy()
        g[1, 2] = np.inf
        raises(IN, r"^z\[1, 2\] = inf: must be finite \(or NaN", cantact.Profile, z=g, dx=1.0,
               dy=1.0, **m)
        raises(IN, r"^z: 0 dimensions \(shape \(\)\): must have 1 or 2", cantact.Profile,
               z=1.0, dx=1.0, **m)
        raises(IN, r"^z: 3 dimensions \(shape \(2, 2, 2\)\)", cantact.Profile,
               z=np.arange(8.0).reshape(2, 2, 2), dx=1.0, dy=1.0, **m)
        raises(IN, r"^z: shape \(0,\): must not be empty", cantact.Profile, z=[], dx=1.0, **m)
        raises(IN, r"^z: shape \(0, 3\): must not be empty", cantact.Profile,
               z=np.zeros((0, 3)), dx=1.0, dy=1.0, **m)
        raises(IN, r"^z: shape \(3, 0\): must not be empty", cantact.Profile,
               z=np.zeros((3, 0)), dx=1.0, dy=1.0, **m)
        # x: 1-D, real, finite, as many as z, strictly increasing
        raises(IN, r"^x: .*got a string", cantact.Profile, z=z, x="abcd", **m)
        raises(IN, r"^x: .*got booleans", cantact.Profile, z=z,
               x=np.array([False, True, True, True]), **m)
        raises(IN, r"^x: .*got dtype complex128", cantact.Profile, z=z,
               x=np.arange(4.0) + 1j, **m)
        raises(IN, r"^x: 2 dimensions", cantact.Profile, z=z, x=[[0, 1], [2, 3]], **m)
        raises(IN, r"^x: 0 dimensions", cantact.Profile, z=z, x=1.0, **m)
        raises(IN, r"^x\[2\] = nan: must be finite", cantact.Profile, z=z, x=[0, 1, np.nan, 3],
               **m)
        raises(IN, r"^x and z: 3 and 4 points", cantact.Profile, z=z, x=[0, 1, 2], **m)
        raises(IN, r"^x\[3\] = 2.0: not increasing: must be > x\[2\]",
               cantact.Profile, z=z, x=[0, 1, 3, 2], **m)
        raises(IN, r"^x\[1\] = 0.0: not increasing: must be > x\[0\]",
               cantact.Profile, z=z, x=[0, 0, 1, 2], **m)
        # spacings, trim, H, Hstar: finite real numbers, > 0 (H: > 1)
        raises(IN, r"^dx = '1': must be a real number", cantact.Profile, z=z, dx="1", **m)
        raises(IN, r"^dx = True: must be a real number", cantact.Profile, z=z, dx=True, **m)
        raises(IN, r"^dx = 0.0: must be > 0", cantact.Profile, z=z, dx=0.0, **m)
        raises(IN, r"^dx = nan: must be finite", cantact.Profile, z=grid, dx=np.nan, dy=1.0,
               **m)
        raises(IN, r"^dy = -1.0: must be > 0", cantact.Profile, z=grid, dx=1.0, dy=-1.0, **m)
        raises(IN, r"^dy = 1j: must be a real number", cantact.Profile, z=grid, dx=1.0, dy=1j,
               **m)
        raises(IN, r"^trim = '1': must be a real number", cantact.Profile, z=z, dx=1.0,
               trim="1", **m)
        raises(IN, r"^Profile\(\): surface.trim_k = -1.0: must be > 0", cantact.Profile, z=z,
               dx=1.0, trim=-1.0, **m)
        raises(IN, r"^H = '2': must be a real number", cantact.Profile, z=z, dx=1.0, H="2",
               E=2e11, sigma_y=4e8)
        raises(IN, r"^Profile\(\): surface.Hstar = inf: not a finite number", cantact.Profile,
               z=z, dx=1.0, Hstar=np.inf, E=2e11, sigma_y=4e8)
        # file: a str, bytes or os.PathLike naming a file
        raises(IN, r"^file = 123: must be a path \(str, bytes or os.PathLike\), got int",
               cantact.Profile, file=123, **m)
        raises(IN, r"^file = True: must be a path", cantact.Profile, True, **m)
        raises(IN, r"^file = \['a.csv'\]: must be a path", cantact.Profile, ["a.csv"], **m)
        raises(IN, r"^file = '': must not be empty", cantact.Profile, "", **m)
        raises(IN, r"^file = 'a\\x00b': must not contain a NUL", cantact.Profile, "a\0b", **m)
        # what stays accepted: a path as bytes, a grid with NaN, integer heights and positions
        assert cantact.Profile(os.fsencode(dektak), **m).source == "dektak"
        g = grid.copy()
        g[0, 1] = np.nan
        assert cantact.Profile(z=g, dx=1.0, dy=1.0, **m).invalid == 1
        assert cantact.Profile(z=[0, 3, 1, 2], x=np.arange(4), **m).stats["Rt"] > 0


def scene_speeds(lo, hi, count):
    """impact.velocity = lo:hi:count:log as the scene parser makes the list."""
    v = [lo * math.exp(k / (count - 1) * (math.log(hi) - math.log(lo))) for k in range(count)]
    v[-1] = hi
    return v


def test_compare_as_the_cli(source, dektak, run_cli):
    # scripts/scenes/dektak.ini: what = e,compare; the fit redone on the depths the impacts
    # reach, then the fitted Cantor surface's e, the asymptotic law's and its V*
    rows = list(csv.DictReader(open(run_cli("run", os.path.join(source, "scripts", "scenes",
                                                                "dektak.ini")))))
    p = cantact.Profile(file=dektak, E=2e11, sigma_y=4e8, H=10)
    r = cantact.restitution(p, mass=0.01, speed=scene_speeds(0.001, 3.0, 30))
    assert [float(x["V_star"]) for x in rows] == list(r.V_star)
    assert [float(x["e"]) for x in rows] == list(r.e[:, 0])
    c = p.compare(r)
    assert set(c) == {"e_cantor_fit", "e_asymptotic_fit", "V_star_cantor_fit"}
    for name, values in c.items():
        assert values.shape == r.e.shape
        cli = [math.nan if x[name] == "" else float(x[name]) for x in rows]
        assert np.array_equal(cli, values[:, 0], equal_nan=True), name
    assert not np.isnan(c["e_cantor_fit"]).any() and np.isnan(c["e_asymptotic_fit"]).any()
    # the fit it used: the one on the depths the impacts reach
    f = p.fit(on_reach=r)
    assert f["band"] == "impacts" and f["note"] == ""
    assert f["bearing"]["lo"] >= p.fit()["bearing"]["lo"] and f["alpha"] != p.fit()["alpha"]
    W = r.kinetic_energy[:, 0]
    assert np.array_equal(c["V_star_cantor_fit"][:, 0],
                          np.sqrt(W / (f["l0"] * p.layer["E"] * f["h0"])))
    # with a depth band given, no refit: as [fit] depths, that band's fit
    band = (1e-7, 3e-7)
    fb = p.fit(depths=band)
    assert fb["band"] == "given" and fb["alpha"] != f["alpha"]
    g = p.compare(r, depths=band)
    assert np.array_equal(g["V_star_cantor_fit"][:, 0],
                          np.sqrt(W / (fb["l0"] * p.layer["E"] * fb["h0"])))
    # later impacts and failed rows have none
    r2 = cantact.restitution(p, mass=0.01, speed=[0.01, 0.1], impacts=2)
    c2 = p.compare(r2)
    assert np.isnan(c2["e_cantor_fit"][:, 1]).all() and not np.isnan(c2["e_cantor_fit"][:, 0]).any()
    with pytest.raises(cantact.InvalidInput, match="another surface"):
        cantact.Profile(file=dektak, E=2e11, sigma_y=4e8, H=10).compare(r)
    with pytest.raises(cantact.InvalidInput, match="must be a Restitution"):
        p.compare(r.e)
    with pytest.raises(cantact.InvalidInput, match="depths and on_reach"):
        p.fit(depths=band, on_reach=r)


def test_levelling_that_points_cannot_determine():
    """A grid of one column (collinear points) cannot be levelled by a plane, a 2 x 2 grid not
    by a quadric: InvalidInput, never GSL's default handler aborting the interpreter."""
    z = np.sin(np.arange(64.0))[:, None]  # 64 rows of one point: all at x = 0
    with pytest.raises(cantact.InvalidInput, match="do not determine a linear fit"):
        cantact.Profile(z=z, dx=1.0, dy=1.0, E=2.0, sigma_y=1.0, H=2.0)
    with pytest.raises(cantact.InvalidInput, match="do not determine a quadratic fit"):
        cantact.Profile(z=np.array([[0.0, 1.0], [2.0, 0.5]]), dx=1.0, dy=1.0, E=2.0,
                        sigma_y=1.0, H=2.0, detrend="quadratic")
    # the same grid levelled by its mean only is a surface
    p = cantact.Profile(z=z, dx=1.0, dy=1.0, E=2.0, sigma_y=1.0, H=2.0, detrend="mean")
    assert p.stats["Rt"] > 0


def test_micro_sign_is_u(tmp_path):
    """unit="µm" (the micro sign) and "μm" (the Greek mu) are um, as typed where µm is printed;
    without a unit the message names the key that gives it."""
    x = np.linspace(0.0, 100.0, 201)
    z = 0.3 * np.sin(x / 3.0) + 0.1 * np.cos(x * 1.7)
    path = tmp_path / "p.txt"
    np.savetxt(path, np.column_stack([x, z]))
    r = {}
    for unit in ("um", "µm", "μm"):
        p = cantact.Profile(str(path), E=2e11, sigma_y=4e8, H=10, unit=unit)
        r[unit] = cantact.restitution(p, V_star=[1e-3, 1e-2]).e
    assert np.array_equal(r["um"], r["µm"]) and np.array_equal(r["um"], r["μm"])
    with pytest.raises(cantact.InvalidInput, match=r"give surface\.unit \(m, mm, um or nm"):
        cantact.Profile(str(path), E=2e11, sigma_y=4e8, H=10)
