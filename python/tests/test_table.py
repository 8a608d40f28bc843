"""e(V*) tables from Python: the slopes against SciPy's PchipInterpolator (an independent
monotone cubic), the claimed error against restitution() at points of our own, the file the
program writes read back to the same bits, the DEM reader's rule."""
import math

import numpy as np
import pytest

import cantact

scipy_interpolate = pytest.importorskip("scipy.interpolate")


def test_cubic_slopes_as_scipy_and_error_claimed():
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    t = cantact.table(s, V_star=(1e-5, 1e-2), tolerance=1e-6)
    assert t.interpolation == "monotone_cubic" and t.info["worst_error"] <= 1e-6
    c0 = int(np.flatnonzero(t.V_star >= t.V_star_crit)[0])
    assert t.V_star[c0] == t.V_star_crit  # V*_c is a node
    x = np.array([math.log(v) for v in t.V_star[c0:]])  # libm's log, as the library's
    d = scipy_interpolate.PchipInterpolator(x, t.e[c0:]).derivative()(x)
    np.testing.assert_allclose(t.slope[c0:], d, rtol=1e-12, atol=1e-15)
    assert (t.slope[:c0] == 0).all() and (t.e[:c0] == 1).all()
    # points of our own, between the build's check points
    rng = np.random.default_rng(5)
    V = np.exp(rng.uniform(np.log(1e-5), np.log(1e-2), 3000))
    exact = cantact.restitution(s, V_star=V).e[:, 0]
    assert np.max(np.abs(t(V) - exact)) <= 1.05e-6
    assert (t(V[V <= t.V_star_crit]) == 1.0).all()


def test_linear_rule_and_the_hand_derived_surface():
    rods = cantact.Rods([0.0, 0.5], [1.0, 1.0], E=10.0, Hstar=2.0, l0=1.0, h0=1.0)
    t = cantact.table(rods, V_star=(0.01, 0.5), tolerance=1e-5, interpolation="linear")
    assert t.V_star_crit == pytest.approx(0.1, rel=1e-15)
    for V in (0.1, 0.2, 0.25):  # V*_c and the two kinks are nodes
        assert np.min(np.abs(t.V_star / V - 1)) < 1e-14
    # linear in ln V* between nodes
    V = np.sqrt(t.V_star[5] * t.V_star[6])
    assert t([V])[0] == pytest.approx(0.5 * (t.e[5] + t.e[6]), rel=1e-14)


def test_file_of_the_cli_reads_back_to_the_same_bits(run_cli, source):
    path = run_cli("table", f"{source}/scripts/scenes/default.ini", "--set",
                   "table.tolerance=1e-5")
    f = cantact.read_table(path)
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    t = cantact.table(s, V_star=(1e-5, 1e-2), tolerance=1e-5)
    assert f.V_star.tobytes() == t.V_star.tobytes() and f.e.tobytes() == t.e.tobytes()
    assert f.slope.tobytes() == t.slope.tobytes() and f.V_star_crit == t.V_star_crit
    V = np.geomspace(1e-6, 2e-2, 2001)
    assert f(V).tobytes() == t(V).tobytes()
    assert f.info["worst_error"] == t.info["worst_error"]
    assert list(f.covers([1e-6, 5e-3, 2e-2])) == [True, True, False]


def test_max_nodes_refused():
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    with pytest.raises(cantact.NoConvergence) as exc:
        cantact.table(s, V_star=(1e-5, 1e-2), tolerance=1e-9, max_nodes=50)
    assert "max_nodes = 50" in exc.value.message


def test_read_table_refuses_what_is_no_table(tmp_path):
    """A file name only (never a descriptor), IOFailure for a missing file as the library
    gives it, and the slopes of a monotone cubic checked as include/cantact_table.h does."""
    with pytest.raises(cantact.InvalidInput, match="path = 42: must be a path"):
        cantact.read_table(42)
    with pytest.raises(cantact.IOFailure, match="cannot open"):
        cantact.read_table(tmp_path / "none.csv")
    rods = cantact.Rods([0.0, 0.5], [1.0, 1.0], E=10.0, Hstar=2.0, l0=1.0, h0=1.0)
    t = cantact.table(rods, V_star=(0.05, 0.5), tolerance=1e-6)

    def write(path, slope):
        with open(path, "w") as f:
            f.write("# interpolation = monotone_cubic\n# V_star_crit = %.17g\n" % t.V_star_crit)
            f.write("V_star,e,de_dlnV_star\n")
            for V, e, d in zip(t.V_star, t.e, slope):
                f.write("%.17g,%.17g,%.17g\n" % (V, e, d))

    write(tmp_path / "t.csv", t.slope)
    back = cantact.read_table(tmp_path / "t.csv")
    assert back(t.V_star).tobytes() == t(t.V_star).tobytes()
    k = int(np.flatnonzero((t.V_star > t.V_star_crit) & (t.slope != 0))[0])
    for bad in (-500.0, 1e300):
        slope = t.slope.copy()
        slope[k] = bad
        write(tmp_path / "bad.csv", slope)
        with pytest.raises(cantact.InvalidInput, match="not those of a monotone cubic"):
            cantact.read_table(tmp_path / "bad.csv")
