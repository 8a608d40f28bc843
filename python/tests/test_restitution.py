"""restitution() against references that do not come from the code under test: one rod in
closed form (MODEL.md §3), a two-rod surface derived by hand, and the cantact program's CSV for
the shipped scenes, which must agree to the last bit (the same library path)."""
import csv
import math

import numpy as np
import pytest

import cantact


def g17(x):
    return "%.17g" % x


# One rod: top t, length L = H* - t, area 1, E = 100, sigma_y = 1 (eps_y = 0.01), l0 = h0 = 1.
# k = E/L = 100 for L = 1; yields at u_y = t + eps_y L = t + 0.01 with W_c = k (0.01)^2 / 2 =
# 0.005, V*_c = sqrt(W_c / (l0 E h0)) = sqrt(5e-5). Beyond: W = E L (eps_y eps - eps_y^2 / 2)
# = (u - t) - 0.005, so u_max = t + W + 0.005; it gives back E L eps_y^2 / 2 = 0.005:
# e = sqrt(0.005 / W); release at u_max - eps_y L. Impact 2 of the same W reloads to u_max
# elastically (0.005) and goes W - 0.005 further on the plateau: e again sqrt(0.005 / W).
@pytest.mark.parametrize("top", [0.0, 0.25])
def test_single_rod_closed_form(top):
    rod = cantact.Rods([top], [1.0], E=100.0, Hstar=top + 1.0, l0=1.0, h0=1.0)
    W = np.array([0.001, 0.005 * (1 - 1e-9), 0.02, 0.2, 0.45])
    V = np.sqrt(W / 100.0)
    r = cantact.restitution(rod, V_star=V, impacts=2)
    assert (r.status == 0).all()
    elastic = W <= 0.005
    assert np.array_equal(r.elastic[:, 0], elastic)
    np.testing.assert_allclose(r.V_star_crit[:, 0], math.sqrt(5e-5), rtol=1e-15)
    e = np.where(elastic, 1.0, np.sqrt(0.005 / W))
    np.testing.assert_allclose(r.e[:, 0], e, rtol=2e-15)
    u_el = top + np.sqrt(2 * W / 100.0)
    u_pl = top + W + 0.005
    np.testing.assert_allclose(r.u_max_over_h0[:, 0], np.where(elastic, u_el, u_pl), rtol=1e-14)
    np.testing.assert_allclose(r.u_contact_over_h0[:, 0], top, atol=1e-300)
    np.testing.assert_allclose(r.u_release_over_h0[~elastic, 0], u_pl[~elastic] - 0.01,
                               rtol=1e-14)
    np.testing.assert_allclose(r.e[~elastic, 1], np.sqrt(0.005 / W[~elastic]), rtol=1e-14)
    np.testing.assert_allclose(r.u_max_over_h0[~elastic, 1], u_pl[~elastic] + W[~elastic] - 0.005,
                               rtol=1e-14)
    # the closed-form check agrees
    np.testing.assert_allclose(r.e_closed_form[:, 0], e, rtol=2e-15)


# Two rods, E = 10, sigma_y = 1 (eps_y = 0.1), H* = 2, l0 = h0 = 1, areas 1: A (top 0, L = 2,
# k = 5, yields at 0.2), B (top 0.5, L = 1.5, k = 20/3, yields at 0.65). Loading the virgin
# surface to u: W = 5u^2/2 to 0.2 (W_c = 0.1, V*_c = 0.1); then W = 0.1 + (u - 0.2), D = u - 0.2
# (W - D = 0.1); from 0.5, s = u - 0.5: W = 0.4 + s + (10/3) s^2, W - D = 0.1 + (10/3) s^2; from
# 0.65: W = 0.625 + 2 (u - 0.65), W - D = 0.175. e = sqrt((W - D)/W), V* = sqrt(W/10).
def two_rods_expected(W):
    if W <= 0.1:
        return 1.0, math.sqrt(2 * W / 5)
    if W <= 0.4:
        return math.sqrt(0.1 / W), 0.2 + (W - 0.1)
    if W <= 0.625:
        s = (-1 + math.sqrt(1 + (40 / 3) * (W - 0.4))) / (20 / 3)
        return math.sqrt((0.1 + (10 / 3) * s * s) / W), 0.5 + s
    return math.sqrt(0.175 / W), 0.65 + (W - 0.625) / 2


def test_two_rods_by_hand():
    rods = cantact.Rods([0.0, 0.5], [1.0, 1.0], E=10.0, Hstar=2.0, l0=1.0, h0=1.0)
    W = np.array([0.05, 0.1, 0.2, 0.4, 0.5, 0.625, 1.0, 3.0])
    r = cantact.restitution(rods, V_star=np.sqrt(W / 10.0))
    for k, w in enumerate(W):
        e, u = two_rods_expected(w)
        assert r.e[k, 0] == pytest.approx(e, rel=2e-15)
        assert r.u_max_over_h0[k, 0] == pytest.approx(u, rel=1e-14)
    assert r.V_star_crit[0, 0] == pytest.approx(0.1, rel=1e-15)
    # mass and speed: V* = sqrt(m v^2 / (2 l0 E h0)) = v sqrt(m / 20)
    r2 = cantact.restitution(rods, mass=2.0, speed=np.sqrt(W / 10.0) * math.sqrt(10.0))
    np.testing.assert_allclose(r2.e[:, 0], r.e[:, 0], rtol=1e-15)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def assert_rows_match_cli(rows, r):
    """Every field of the CLI's e rows against the module's arrays, as text (%.17g)."""
    assert len(rows) == r.V_star.size * r.impacts
    for q, row in enumerate(rows):
        k, i = divmod(q, r.impacts)
        assert int(row["impact"]) == i + 1
        assert row["V_star"] == g17(r.V_star[k])
        assert row["u_max_over_h0"] == g17(r.u_max_over_h0[k, i])
        assert row["e"] == g17(r.e[k, i])
        assert row["e_closed_form"] == g17(r.e_closed_form[k, i])
        assert row["quadrature_error"] == "%.3g" % r.quadrature_error[k, i]
        assert row["V_star_crit"] == g17(r.V_star_crit[k, i])
        assert row["u_release_over_h0"] == g17(r.u_release_over_h0[k, i])
        assert int(row["elastic"]) == int(r.elastic[k, i])


def test_default_scene_as_the_cli(run_cli, source):
    rows = read_csv(run_cli("run", f"{source}/scripts/scenes/default.ini"))
    V = np.array([float(row["V_star"]) for row in rows])
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    assert_rows_match_cli(rows, cantact.restitution(s, V_star=V))


def test_repeated_impacts_fractal_depth_as_the_cli(run_cli, source):
    rows = read_csv(run_cli("run", f"{source}/scripts/scenes/default.ini", "--set",
                            "surface.depth=fractal", "--set", "impact.impacts=3"))
    V = np.array([float(row["V_star"]) for row in rows[::3]])
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth="fractal")
    assert_rows_match_cli(rows, cantact.restitution(s, V_star=V, impacts=3))


def test_mass_and_speed_in_si_units_as_the_cli(run_cli, source):
    # scripts/scenes/dem_table.ini: h0 = 1e-6 m, l0 = 1e-3 m, E = 200 GPa, sigma_y = 400 MPa
    rows = read_csv(run_cli("run", f"{source}/scripts/scenes/dem_table.ini"))
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=200e9, sigma_y=400e6, h0=1e-6, l0=1e-3)
    speeds = np.array([0.01 * math.exp(k / 12 * (math.log(6) - math.log(0.01))) for k in range(13)])
    speeds[-1] = 6.0  # as the scene's from:to:count:log list
    assert_rows_match_cli(rows, cantact.restitution(s, mass=1e-3, speed=speeds))


def test_random_realisation_as_the_cli(run_cli, tmp_path):
    scene = tmp_path / "r.ini"
    scene.write_text("[surface]\ntype = random_cantor\nfx = 1.5\nfz = 1.3\nH = 10\ndepth = 9\n"
                     "fx_spread = 0.1\nfz_spread = 0.05\nseed = 7\nrealisation = 3\n"
                     "[material]\nE = 500\n[impact]\nV_star = 1e-4, 1e-3, 5e-3\nimpacts = 2\n")
    rows = read_csv(run_cli("run", str(scene)))
    s = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=9, fx_spread=0.1,
                             fz_spread=0.05, seed=7, realisation=3)
    assert_rows_match_cli(rows, cantact.restitution(s, V_star=[1e-4, 1e-3, 5e-3], impacts=2))


def test_threads_give_the_same_bits():
    s1 = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=14, representation="segments",
                        threads=1)
    s2 = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=14, representation="segments",
                        threads=2)
    V = np.geomspace(1e-4, 1e-2, 7)
    a, b = cantact.restitution(s1, V_star=V), cantact.restitution(s2, V_star=V)
    assert a.e.tobytes() == b.e.tobytes() and a.u_max_over_h0.tobytes() == b.u_max_over_h0.tobytes()


def test_failed_rows_when_asked():
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    r = cantact.restitution(s, V_star=[1e-3, 1.0], impacts=2, errors="rows")
    assert (r.status[0] == 0).all()
    assert r.status[1, 0] == cantact.lib.CT_ERANGE and r.status[1, 1] == cantact.lib.CT_ESKIPPED
    assert "crushed" in r.message[1, 0]
    assert r.message[1, 1] == "not run: impact 1 of V* = 1 failed"
    assert np.isnan(r.e[1]).all() and not r.elastic[1].any()
    # a row's message shares its bytes with the results: a row that succeeded says "", a failed
    # one its message alone (the CLI's error column), on either path and with the time columns
    for path, time in (("curve", False), ("curve", True), ("rods", False)):
        r = cantact.restitution(s, V_star=[1e-3, 1.0, 2e-3], impacts=2, errors="rows", path=path,
                                time=time)
        assert (r.message[[0, 2]] == "").all()
        assert r.message[1, 0] == ("impact energy 500 reaches u_max >= H* = 10 (the layer would be "
                                   "crushed, strains >= 1): outside the model; lower the speed or raise H")
        assert r.message[1, 1] == "not run: impact 1 of V* = 1 failed"


# One linear rod in time (MODEL.md §11): k = E / L = 100, and the sweep's mass is E l0 / h0 =
# 100, so omega = 1 / tau: the contact lasts pi tau exactly whatever the (elastic) speed; its
# peak force is k u_max = k v1 / omega with v1 = sqrt(2) V* (in h0 / tau).
def test_time_single_rod_closed_form():
    rod = cantact.Rods([0.0], [1.0], E=100.0, Hstar=1.0, l0=1.0, h0=1.0)
    V = np.array([1e-4, 5e-4])  # W = 100 V*^2 <= W_c = 0.005
    r = cantact.restitution(rod, V_star=V, time=True)
    assert r.elastic.all()
    np.testing.assert_allclose(r.t_contact_over_tau[:, 0], math.pi, rtol=1e-15)
    np.testing.assert_allclose(r.t_load_over_tau[:, 0], math.pi / 2, rtol=1e-15)
    np.testing.assert_allclose(r.P_peak_over_PY[:, 0], 100.0 * math.sqrt(2) * V, rtol=1e-14)
    assert (r.e_kinematic == 1.0).all()
    plain = cantact.restitution(rod, V_star=V)
    assert np.isnan(plain.t_contact_over_tau).all()
    with pytest.raises(cantact.InvalidInput):
        cantact.restitution(rod, V_star=V, time="yes")


def test_time_columns_as_the_cli(run_cli, source):
    rows = read_csv(run_cli("run", f"{source}/scripts/scenes/default.ini", "--set",
                            "impact.impacts=2", "--set", "output.what=e,time"))
    V = np.array([float(row["V_star"]) for row in rows[::2]])
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    r = cantact.restitution(s, V_star=V, impacts=2, time=True)
    assert_rows_match_cli(rows, r)
    for q, row in enumerate(rows):
        k, i = divmod(q, 2)
        for col in ("t_contact_over_tau", "t_load_over_tau", "t_unload_over_tau",
                    "P_peak_over_PY", "e_kinematic"):
            assert row[col] == g17(getattr(r, col)[k, i]), col
        assert row["unload_period_over_tau"] == g17(r.unload_period_over_tau[k, i])


# The rods kind (src/surface/rods.c) from Python and from a scene: the same rods inline, the
# same defaults (h0 the deepest top, l0 the total area), mass and speed through ct_V_star_of.
def test_rods_as_the_cli_scene(run_cli, tmp_path):
    top, area = [0.0, 0.2, 0.05], [0.5, 0.3, 0.2]
    speeds = [0.01, 0.1, 0.3, 1.0, 1.5]
    scene = tmp_path / "rods.ini"
    scene.write_text("[surface]\ntype = rods\nrods = "
                     + ", ".join(f"{t!r}:{a!r}" for t, a in zip(top, area))
                     + "\nHstar = 3.0\n[material]\nE = 200.0\nsigma_y = 2.5\n[impact]\n"
                     f"mass = 3.0\nvelocity = {', '.join(map(repr, speeds))}\nimpacts = 2\n")
    rows = read_csv(run_cli("run", str(scene)))
    rods = cantact.Rods(top, area, E=200.0, Hstar=3.0, sigma_y=2.5)
    assert rods.layer["h0"] == 0.2 and rods.layer["l0"] == 1.0 and rods.layer["Hstar"] == 3.0
    r = cantact.restitution(rods, mass=3.0, speed=speeds, impacts=2)
    assert (r.status == 0).all() and not r.elastic[2:].any()
    assert len(rows) == r.e.size
    for q, row in enumerate(rows):
        k, i = divmod(q, 2)
        assert float(row["V_star"]) == r.V_star[k]
        assert float(row["e"]) == r.e[k, i], (k, i)
        assert float(row["u_max_over_h0"]) == r.u_max_over_h0[k, i], (k, i)


def test_rods_defaults_of_the_kind():
    # every top 0: h0 is H*; lengths given: H* the shallowest bottom, no Hstar
    flat = cantact.Rods([0.0, 0.0], [1.0, 3.0], E=10.0, Hstar=2.0)
    assert flat.layer == {"E": 10.0, "sigma_y": 1.0, "Hstar": 2.0, "l0": 4.0, "h0": 2.0}
    own = cantact.Rods([0.1, 0.4], [1.0, 1.0], E=10.0, length=[1.0, 0.5])
    assert own.layer["Hstar"] == 0.9 and own.layer["h0"] == 0.4
    # lengths replace H* - top: at u = 0.15 (u/h0 = 0.375) rod 1 has strain 0.05 / 1.0 (not
    # 0.05 / 0.8), stress 0.5, force 0.5 = 0.25 P_Y (P_Y = sigma_y l0 = 2)
    c = cantact.load_curve(own)
    assert c.force([0.375])[0] == pytest.approx(0.25, rel=1e-14)
    mm = cantact.Rods([0.1, 0.4], [1.0, 1.0], E=10.0, H=3.0, unit="mm")
    assert mm.layer["h0"] == 0.4e-3 and mm.layer["Hstar"] == pytest.approx(1.2e-3, rel=1e-15)
    with pytest.raises(cantact.InvalidInput, match="not with rods that give their lengths"):
        cantact.Rods([0.1], [1.0], E=10.0, Hstar=2.0, length=[1.0])
    with pytest.raises(cantact.InvalidInput, match="needs surface.Hstar or surface.H"):
        cantact.Rods([0.1], [1.0], E=10.0)
    with pytest.raises(cantact.InvalidInput, match="unit = km: must be m, mm, um or nm"):
        cantact.Rods([0.1], [1.0], E=10.0, Hstar=2.0, unit="km")
    with pytest.raises(cantact.InvalidInput, match="h0 = '1': must be a real number"):
        cantact.Rods([0.1], [1.0], E=10.0, Hstar=2.0, h0="1")
    with pytest.raises(cantact.InvalidInput, match="rod 1: length = 0: must be finite and > 0"):
        cantact.Rods([0.1], [1.0], E=10.0, length=[0.0])
    # the library's own check, with its message
    with pytest.raises(cantact.InvalidInput, match="every top is 0"):
        cantact.Rods([0.0], [1.0], E=10.0, H=2.0)


def test_lean_curve_gives_the_full_curves_bits():
    # path="lean": the curve held as its sorted events (docs/library.md); every number the same
    # double as the full curve's, on a Cantor surface and on scattered rods, three impacts
    V = np.geomspace(1e-5, 1e-1, 40)
    tops = np.mod(0.618033988749895 * np.arange(3000), 1.0)
    for s in (cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500),
              cantact.Rods(tops, np.full(3000, 1.0 / 3000), E=500.0, Hstar=10.0, l0=1.0, h0=1.0)):
        a = cantact.restitution(s, V_star=V, impacts=3, errors="rows", path="curve")
        b = cantact.restitution(s, V_star=V, impacts=3, errors="rows", path="lean")
        assert (a.status == b.status).all() and (a.status == 0).sum() >= 30
        for name in ("e", "u_max_over_h0", "V_star_crit", "e_closed_form"):
            assert getattr(a, name).tobytes() == getattr(b, name).tobytes(), name
