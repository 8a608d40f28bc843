"""Bodies from Python (docs/model.md §14): a Sphere, a Cylinder or the Flat strip struck on a
surface gives the bits of `cantact run` (and `cantact table`) with the same [body] and
[surface] periodic: a sphere on the shipped X3P map, a cylinder on a periodic Cantor surface of
one rod per piece, a sphere and a cylinder on rods placed by x and y (from a rod file with
those columns), with failed rows' messages. A body's keys are the library's rows
(ct_body_keys_table), asked here of the library itself; a surface that cannot carry a body is
refused with the library's message. The speed columns are sqrt(2) V* and e sqrt(2) V*."""
import csv
import math
import re
import subprocess

import numpy as np
import pytest

import cantact

ffi, lib = cantact.ffi, cantact.lib
IN = cantact.InvalidInput


def text(p):
    return None if p == ffi.NULL else ffi.string(p).decode()


def g17(x):
    return "%.17g" % x


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def assert_as_the_cli(rows, r):
    """Every column the CLI's e table and Restitution share, as text (empty: NaN), the rows'
    order (speed, then impact), and a failed row's message as its error column."""
    assert len(rows) == r.e.size
    digits = {c["name"]: c["digits"] for c in cantact.COLUMNS}
    shared = [h for h in rows[0] if h in digits and h != "V_star"
              and isinstance(getattr(r, h, None), np.ndarray)]
    assert {"e", "u_max_over_h0", "V_star_crit", "u_release_over_h0"} <= set(shared)
    for q, row in enumerate(rows):
        k, i = divmod(q, r.impacts)
        assert int(row["impact"]) == i + 1 and row["V_star"] == g17(r.V_star[k])
        for h in shared:
            x = getattr(r, h)[k, i]
            if h == "elastic":
                want = str(int(x)) if r.status[k, i] == 0 else ""
            elif math.isnan(x):
                want = ""
            else:
                want = ("%." + str(digits[h]) + "g") % x
            assert row[h] == want, (h, k, i, row[h], want)
        assert row.get("error", "") == r.message[k, i], (k, i)


def speeds(rows, impacts=1):
    return np.array([float(row["V_star"]) for row in rows[::impacts]])


# ---- the same bits as the program --------------------------------------------------------


def test_sphere_on_the_map_as_the_cli(run_cli, source):
    """examples/scenes/sphere.ini: a ball of R = 2.5 mm on a periodic X3P map (a profile)."""
    rows = read_csv(run_cli("run", f"{source}/examples/scenes/sphere.ini"))
    m = cantact.Profile(f"{source}/examples/data/map128.x3p", H=10, E=2e11, sigma_y=4e8,
                        periodic=True)
    assert m.periodic
    ball = cantact.Sphere(2.5e-3)
    r = cantact.restitution(m, V_star=speeds(rows), body=ball, check="auto")
    assert_as_the_cli(rows, r)
    assert (r.status == 0).all() and not r.elastic.all()
    # the body moved the rods (the map's copies within its reach): not the flat strip's
    flat = cantact.restitution(m, V_star=speeds(rows)[:3], check="auto")
    assert (flat.u_max_over_h0[:, 0] != r.u_max_over_h0[:3, 0]).all()
    assert r.info["rods"] > flat.info["rods"] == 128 * 128
    # with the mass and speeds in m/s the scene gives: V* by ct_V_star_of, the same speeds
    v = np.geomspace(1e-5, 0.3, 31)
    byv = cantact.restitution(m, mass=5.14e-4, speed=v[:4], body=ball, check="auto")
    np.testing.assert_allclose(byv.V_star, speeds(rows)[:4], rtol=2e-15)  # the lists' rounding


CYLINDER = ["--set", "surface.representation=segments", "--set", "surface.depth=8",
            "--set", "body.shape=cylinder", "--set", "body.radius=5", "--set",
            "body.position=0.3", "--set", "impact.impacts=2", "--set",
            "impact.velocity=0.01:5:7:log", "--set", "solver.on_error=skip"]


def cantor(**keys):
    return cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=8, representation="segments",
                          **keys)


@pytest.mark.parametrize("periodic", [True, False])
def test_cylinder_on_a_cantor_surface_as_the_cli(run_cli, source, periodic):
    """A cylinder (R = 5 l0, its apex at x = 0.3 l0) on the Cantor surface of one rod per
    piece, depth 8, repeating (every impact runs) or not (the faster ones reach the border
    and fail, the library's message in the row)."""
    rows = read_csv(run_cli("run", f"{source}/examples/scenes/cantor.ini", *CYLINDER,
                            "--set", f"surface.periodic={str(periodic).lower()}"))
    s = cantor(periodic=periodic)
    r = cantact.restitution(s, V_star=speeds(rows, 2), impacts=2, check="auto", errors="rows",
                            body=cantact.Cylinder(5, position=0.3))
    assert_as_the_cli(rows, r)
    if periodic:
        assert (r.status == 0).all() and (r.e < 1).any()
    else:
        assert (r.status[-1] == [lib.CT_ERANGE, lib.CT_ESKIPPED]).all()
        assert "reaches the border of the surface" in r.message[-1, 0]


def test_cylinder_table_as_the_cli(run_cli, source):
    path = run_cli("table", f"{source}/examples/scenes/cantor.ini", *CYLINDER[:-2], "--set",
                   "surface.periodic=true", "--set", "table.tolerance=1e-4")
    f = cantact.read_table(path)
    s = cantor(periodic=True)  # the scene's speeds, 0.01 .. 5 with its mass: V* 1e-5 .. 5e-3
    t = cantact.table(s, mass=1e-3, speed=(0.01, 5.0), tolerance=1e-4,
                      body=cantact.Cylinder(5, position=0.3))
    assert f.V_star.tobytes() == t.V_star.tobytes() and f.e.tobytes() == t.e.tobytes()
    assert f.slope.tobytes() == t.slope.tobytes() and f.V_star_crit == t.V_star_crit
    assert t.V_star[0] == pytest.approx(1e-5, rel=1e-15) and f.v_per_V_star == t.v_per_V_star
    flat = cantact.table(s, mass=1e-3, speed=(0.01, 5.0), tolerance=1e-4)
    assert flat.V_star_crit != t.V_star_crit


def rod_set(tmp_path, areal):
    """12 x 12 rods (a line of 144 when not areal) at 0.1 spacing with tops of our own, as a
    rod file with columns x (and y), and as arrays."""
    rng = np.random.default_rng(3)
    n = 12
    x, y = (a.ravel() for a in np.meshgrid(np.arange(n) * 0.1, np.arange(n) * 0.1))
    if not areal:
        x, y = np.arange(n * n) * 0.1, None
    top = rng.uniform(0, 0.05, n * n)
    area = np.full(n * n, 0.01)
    f = tmp_path / "rods.csv"
    f.write_text(("top,area,x,y\n" if areal else "top,area,x\n") + "".join(
        f"{t!r},{a!r},{u!r}" + (f",{w!r}\n" if areal else "\n")
        for t, a, u, w in zip(top, area, x, y if areal else x)))
    return f, top, area, x, y


@pytest.mark.parametrize("shape", ["sphere", "cylinder"])
def test_rods_placed_by_x_and_y_as_the_cli(run_cli, tmp_path, shape):
    areal = shape == "sphere"
    f, top, area, x, y = rod_set(tmp_path, areal)
    at = (0.52, 0.47) if areal else (7.33,)
    scene = tmp_path / "scene.ini"
    scene.write_text(f"[surface]\ntype = rods\nfile = {f.name}\nHstar = 1\n[body]\nshape = "
                     f"{shape}\nradius = 2\nposition = {', '.join(map(repr, at))}\n"
                     "[material]\nE = 100\n[impact]\nV_star = 1e-4:0.3:9:log\nimpacts = 2\n"
                     "[solver]\non_error = skip\n")
    rows = read_csv(run_cli("run", str(scene)))
    rods = cantact.Rods(top, area, E=100, Hstar=1, x=x, y=y)
    body = cantact.Body(shape, radius=2, position=at)
    r = cantact.restitution(rods, V_star=speeds(rows, 2), impacts=2, check="auto",
                            errors="rows", body=body)
    assert_as_the_cli(rows, r)
    assert (r.status[:, 0] == 0).any() and (r.status[:, 0] == lib.CT_ERANGE).any()
    assert (r.e[r.status == 0] < 1).any()


# ---- the body's rows are the library's -----------------------------------------------------


def body_rows():
    n = ffi.new("size_t *")
    rows = lib.ct_body_keys_table(n)
    return {f"{text(rows[i].section)}.{text(rows[i].name)}": rows + i for i in range(n[0])}


def library_body(given):
    """What ct_key_parse makes of {"section.name": text} in the table's order, from the
    defaults: (None, the ct_body's bytes) or (the key refused and why, None)."""
    b = ffi.new("ct_body *")
    lib.ct_body_defaults(b)
    for k, row in body_rows().items():
        if k in given and lib.ct_key_parse(row, given[k].encode(), b):
            return (k, given[k], ffi.string(lib.ct_error_message()).decode()), None
    return None, bytes(ffi.buffer(b))


def test_bodies_and_rows_are_the_librarys():
    assert cantact.BODIES == tuple(text(lib.ct_body_name(k)) for k in range(lib.ct_body_count()))
    assert cantact.BODIES == ("flat", "cylinder", "sphere")
    assert [f"{r.section}.{r.name}" for r in cantact.BODY_ROWS] == list(body_rows())
    for name in cantact.BODIES:
        assert cantact.Body(name).shape == name
    assert cantact.Flat().shape == "flat" and cantact.Flat().position is None
    assert bytes(ffi.buffer(cantact.Flat()._body)) == library_body({})[1]


POINTS = [(0.25, "0.25"), ((0.25,), "0.25"), ((0.25, -1.5), "0.25, -1.5"),
          ((1.0, 2.0, 3.0), "1.0, 2.0, 3.0"), ((), ""), (math.nan, "nan"),
          ((0.0, math.inf), "0.0, inf"), (np.array([0.5, 0.125]), "0.5, 0.125")]
RADII = [(5e-324, "5e-324"), (0.0, "0.0"), (-1.0, "-1.0"), (math.inf, "inf"),
         (math.nan, "nan"), (2.5e-3, "0.0025")]


@pytest.mark.parametrize("shape", ["flat", "cylinder", "sphere", "ball"])
def test_body_keys_get_the_librarys_answers(shape):
    cases = [({"radius": v}, {"body.radius": t}) for v, t in RADII]
    cases += [({"radius": 1.0, "position": v}, {"body.radius": "1.0", "body.position": t})
              for v, t in POINTS]
    for keys, given in cases:
        why, want = library_body(dict(given, **{"body.shape": shape}))
        try:
            got = bytes(ffi.buffer(cantact.Body(shape, **keys)._body))
            assert why is None and got == want, (shape, keys, why)
        except IN as exc:
            assert why is not None, (shape, keys, exc.message)
            assert exc.message == f"Body(): {why[0]} = {why[1]}: {why[2]}", (shape, keys)
    # the named classes are the rows' too, in their own call's name
    with pytest.raises(IN) as exc:
        cantact.Sphere(-1.0)
    why = library_body({"body.radius": "-1.0"})[0][2]
    assert exc.value.message == f"Sphere(): body.radius = -1.0: {why}"
    with pytest.raises(IN, match=r"^Cylinder\(\): body.position = 1.0, 2.0, 3.0: must be x"):
        cantact.Cylinder(1.0, position=(1, 2, 3))
    # a type Python does not take: the module's words, naming the argument
    for bad in ("1, 2", b"1", None, [1.0, "2"], True, 1j):
        with pytest.raises(IN):
            cantact.Body("sphere", radius=1.0, position=bad)
    with pytest.raises(IN, match="not a key of a body"):
        cantact.Body("sphere", radius=1.0, size=2)
    with pytest.raises(IN, match="surface.periodic is the surface's key"):
        cantact.Body("sphere", radius=1.0, periodic=True)


@pytest.mark.parametrize("kind", list(cantact.KINDS))
def test_periodic_is_the_surfaces_row(kind, source):
    base = {"cantor": {"fx": 1.5, "fz": 1.3, "H": 10.0, "E": 500.0},
            "random_cantor": {"fx": 1.5, "fz": 1.3, "H": 10.0, "E": 500.0, "depth": 4},
            "rods": {"rods": "0:1, 0.5:1", "Hstar": 2.0, "E": 10.0},
            "profile": {"file": f"{source}/tests/data/dektak-1.csv", "H": 10.0, "E": 2e11,
                        "sigma_y": 4e8}}[kind]
    row = body_rows()["surface.periodic"]
    for value, given in [(True, "true"), (False, "false"), ("true", "true"),
                         ("false", "false"), ("yes", "yes"), ("True", "True")]:
        b = ffi.new("ct_body *")
        refused = lib.ct_key_parse(row, given.encode(), b)
        why = ffi.string(lib.ct_error_message()).decode()
        for key in ("periodic", "surface.periodic"):
            try:
                s = cantact.Surface(kind, **base, **{key: value})
                assert not refused and s.periodic == bool(b.periodic), (kind, value)
            except IN as exc:
                assert refused, (kind, value, exc.message)
                assert exc.message == f"Surface({kind!r}): surface.periodic = {given}: {why}"
    with pytest.raises(IN, match="must be True or False"):
        cantact.Surface(kind, **base, periodic=1)
    assert not cantact.Surface(kind, **base).periodic  # the row's default, false


def test_the_request_carries_the_body_and_periodic(monkeypatch):
    """What reaches ct_surface_build: the body's shape, radius and position as parsed, and
    the surface's periodic."""
    seen = []

    class Stop(Exception):
        pass

    class Spy:
        def __getattr__(self, name):
            if name == "ct_surface_build":
                def build(s, req, out, info):
                    b = req.body
                    seen.append(None if b == ffi.NULL else
                                (b.shape, b.radius, b.position[0], b.position[1], b.periodic))
                    raise Stop()
                return build
            return getattr(lib, name)

    s = cantor(periodic=True)
    monkeypatch.setattr(cantact._surfaces, "lib", Spy())
    for body in (None, cantact.Flat(), cantact.Cylinder(0.5, position=0.25),
                 cantact.Sphere(2.0, position=(1.0, -2.0))):
        for call in (lambda: cantact.restitution(s, V_star=[1e-3], body=body),
                     lambda: cantact.table(s, V_star=(1e-3, 1e-2), body=body),
                     lambda: cantact.load_curve(s, V_star=[1e-3], body=body)):
            try:
                call()
            except Stop:
                pass
    # load_curve under the flat strip (None, Flat()) plans the Cantor surface itself
    assert len(seen) == 4 * 3 - 2
    nan = math.nan
    want = [(0, 0.0, nan, nan, 1)] * 4 + [(1, 0.5, 0.25, nan, 1)] * 3 + [(2, 2.0, 1.0, -2.0, 1)] * 3
    for got, w in zip(seen, want):
        assert got[0] == w[0] and got[1] == w[1] and got[4] == w[4], (got, w)
        for a, b in zip(got[2:4], w[2:4]):
            assert a == b or (math.isnan(a) and math.isnan(b)), (got, w)


# ---- what refuses, in the library's words ----------------------------------------------------


def test_a_surface_that_cannot_carry_the_body_is_the_librarys_refusal(cli, source):
    """A sphere on a line (the Cantor surface of one rod per piece): InvalidInput with the
    message the program prints, and the same for a curved body on stage rods (how many of
    them stand nowhere depends on the speeds, the scene's, 0.01 .. 1 with its mass, and for
    load_curve, which keeps every rod, on the depth alone)."""
    for keys, sets in (({}, ["--set", "body.shape=sphere", "--set", "body.radius=5"]),
                       ({"representation": "stages"}, ["--set", "body.shape=cylinder",
                                                       "--set", "body.radius=5"])):
        p = subprocess.run([cli, "run", "-q", f"{source}/examples/scenes/cantor.ini", "--set",
                            "surface.depth=8", "--set", "surface.representation="
                            + keys.get("representation", "segments"), *sets, "-o",
                            "/dev/null"], capture_output=True, text=True)
        assert p.returncode == 2
        s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=8,
                           representation=keys.get("representation", "segments"))
        body = cantact.Sphere(5) if not keys else cantact.Cylinder(5)
        V = np.geomspace(1e-5, 1e-3, 5)
        for name, call in (("restitution", lambda: cantact.restitution(s, V_star=V, body=body)),
                           ("table", lambda: cantact.table(s, V_star=(V[0], V[-1]), body=body)),
                           ("load_curve", lambda: cantact.load_curve(s, V_star=V, body=body))):
            with pytest.raises(IN) as exc:
                call()
            got = exc.value.message
            if name == "load_curve":  # every stage rod, 9 at depth 8, where the speeds reach 1
                got = re.sub(r"^(.*: )9 of the 9 rods", r"\g<1>1 of the 1 rods", got)
            assert p.stderr == f"cantact: {got}\n", name
    # rods placed by points repeat nowhere; a sphere needs x and y of its apex; y without x
    rods = cantact.Rods([0.0, 0.01], [1.0, 1.0], E=10, Hstar=1, x=[0.0, 1.0], y=[0.0, 1.0])
    with pytest.raises(IN, match="^surface.periodic = true: rods given by points"):
        cantact.restitution(cantact.Rods([0.0, 0.01], [1.0, 1.0], E=10, Hstar=1, x=[0.0, 1.0],
                                         y=[0.0, 1.0], periodic=True),
                            V_star=[1e-3], body=cantact.Sphere(5))
    with pytest.raises(IN, match="^body.position = 0.5: a sphere's apex needs x and y"):
        cantact.restitution(rods, V_star=[1e-3], body=cantact.Sphere(5, position=0.5))
    with pytest.raises(IN, match="y without x"):
        cantact.Rods([0.0, 0.01], [1.0, 1.0], E=10, Hstar=1, y=[0.0, 1.0])
    with pytest.raises(IN, match="top and x: 2 and 3 rods"):
        cantact.Rods([0.0, 0.01], [1.0, 1.0], E=10, Hstar=1, x=[0.0, 1.0, 2.0])
    with pytest.raises(IN, match="x = nan: must be finite"):
        cantact.Rods([0.0, 0.01], [1.0, 1.0], E=10, Hstar=1, x=[0.0, math.nan])
    with pytest.raises(IN, match="body: must be a cantact body"):
        cantact.restitution(rods, V_star=[1e-3], body="sphere")


def test_what_a_body_cannot_reach_from_python():
    """An ensemble under a curved body: each realisation's samples the bits of its own
    restitution under the body (the flat strip the same as none); a Profile of arrays is made
    rods outside the kind's build."""
    rc = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=6, fx_spread=0.1, seed=2)
    a = cantact.ensemble(rc, V_star=[1e-3, 3e-3], realisations=3)
    b = cantact.ensemble(rc, V_star=[1e-3, 3e-3], realisations=3, body=cantact.Flat())
    assert a.e.tobytes() == b.e.tobytes()
    rp = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=6, fx_spread=0.1, seed=2,
                              periodic=True)
    c = cantact.ensemble(rp, V_star=[1e-3, 3e-3], realisations=3, body=cantact.Cylinder(5))
    for k in range(3):
        own = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=6, fx_spread=0.1, seed=2,
                                   realisation=k, periodic=True)
        r = cantact.restitution(own, V_star=[1e-3, 3e-3], body=cantact.Cylinder(5))
        assert c.e[k].tobytes() == r.e.tobytes()
    assert c.e.tobytes() != a.e.tobytes()  # the body is not dropped
    # one realisation struck by the cylinder instead, repeating
    one = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=6, fx_spread=0.1, seed=2,
                               realisation=1, periodic=True)
    r = cantact.restitution(one, V_star=[1e-3, 3e-3], body=cantact.Cylinder(5))
    assert (r.status == 0).all() and r.info["fx_clipped"] is None
    assert cantact.restitution(one, V_star=[1e-3]).info["draws"] == 2**7 - 2
    z = np.sin(np.arange(200) * 0.37) * 1e-6
    p = cantact.Profile(z=z, dx=1e-6, E=2e11, sigma_y=4e8, H=10)
    with pytest.raises(IN, match="a Profile of arrays"):
        cantact.restitution(p, V_star=[1e-3], body=cantact.Cylinder(1e-3))
    assert (cantact.restitution(p, V_star=[1e-3], body=cantact.Flat()).status == 0).all()


# ---- the body's rods, the curve and the speeds -----------------------------------------------


def test_flat_body_is_the_strip_bit_for_bit():
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    V = np.geomspace(1e-4, 1e-2, 9)
    a = cantact.restitution(s, V_star=V, impacts=2)
    b = cantact.restitution(s, V_star=V, impacts=2, body=cantact.Flat())
    for c in ("e", "u_max_over_h0", "V_star_crit", "u_release_over_h0"):
        assert getattr(a, c).tobytes() == getattr(b, c).tobytes(), c


def test_load_curve_under_the_body_is_the_impacts():
    """The curve of the rods a cylinder meets: its first contact is the impacts', its work to
    each u_max their loading work, and it is not the flat strip's."""
    s = cantor(periodic=True)
    body = cantact.Cylinder(5, position=0.3)
    V = np.geomspace(1e-4, 4e-3, 6)
    r = cantact.restitution(s, V_star=V, body=body)
    c = cantact.load_curve(s, V_star=V, body=body)
    assert c.first_contact == r.u_contact_over_h0[0, 0]
    np.testing.assert_allclose(c.work(r.u_max_over_h0[:, 0]), r.W_load_over_PY_h0[:, 0],
                               rtol=1e-12)
    flat = cantact.load_curve(s, V_star=V)
    assert (c.force(r.u_max_over_h0[:, 0]) != flat.force(r.u_max_over_h0[:, 0])).all()


def test_speed_columns():
    """v1 = sqrt(2) V* and v2 = e v1, in h0 / tau: the column table's speed group."""
    names = [c["name"] for c in cantact.COLUMNS if c["group"] == "speed"]
    assert names == ["v_impact_over_h0_per_tau", "v_rebound_over_h0_per_tau"]
    assert [c["physical"] for c in cantact.COLUMNS if c["group"] == "speed"] == [
        "v_impact_m_per_s", "v_rebound_m_per_s"]
    s = cantor(periodic=True)
    V = np.geomspace(1e-5, 5e-3, 9)
    r = cantact.restitution(s, V_star=V, impacts=2, body=cantact.Cylinder(5))
    assert (r.e < 1).any() and (r.e == 1).any()
    v1 = math.sqrt(2) * V[:, None] * np.ones((1, 2))
    np.testing.assert_allclose(r.v_impact_over_h0_per_tau, v1, rtol=4e-16, atol=0)
    np.testing.assert_allclose(r.v_rebound_over_h0_per_tau, r.e * v1, rtol=6e-16, atol=0)
    # NaN where a row failed, as every column
    f = cantact.restitution(s, V_star=[1e-3, 1.0], errors="rows")
    assert np.isnan(f.v_impact_over_h0_per_tau[1]).all()
    assert np.isnan(f.v_rebound_over_h0_per_tau[1]).all()
