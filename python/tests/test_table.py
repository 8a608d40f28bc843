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
            f.write("# nodes = %d\nV_star,e,de_dlnV_star\n" % t.V_star.size)
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


# ---- Table.save, v_per_V_star, the damping relations ----------------------------------------

# A C program on include/cantact_table.h alone (compiled by the test): "load FILE" prints the
# header's numbers and e at the V* read from stdin, "zeta LAW" / "e LAW" the damping relations
# at the numbers read from stdin, all as %a (exact bits).
_READER_C = r"""
#include "cantact_table.h"
int main(int argc, char **argv)
{
    double x;
    if (argc == 3 && !strcmp(argv[1], "load")) {
        ct_tab t;
        char err[512];
        if (ct_tab_load(&t, argv[2], err, sizeof err)) {
            fprintf(stderr, "%s\n", err);
            return 1;
        }
        printf("%zu %a %a %a %a %d\n", t.n, t.V_star_crit, t.v_per_V_star, t.tolerance,
               t.worst_error, t.rule);
        while (scanf("%lf", &x) == 1)
            printf("%a\n", ct_tab_eval(&t, x));
        ct_tab_free(&t);
        return 0;
    }
    if (argc == 3 && !strcmp(argv[1], "read")) {
        ct_tab t;
        char err[1024];
        const int why = ct_tab_read(&t, argv[2], err, sizeof err);
        if (why) {
            fprintf(stderr, "%d %s\n", why, err);
            return 1;
        }
        printf("%zu %a %a %a %a %a %d\n", t.n, t.V_star_crit, t.v_per_V_star, t.tolerance,
               t.worst_error, t.worst_V_star, t.rule);
        for (size_t i = 0; i < t.n; i++)
            printf("%a %a %a\n", t.V_star[i], t.e[i], t.slope[i]);
        ct_tab_free(&t);
        return 0;
    }
    if (argc == 3) {
        const int law = atoi(argv[2]);
        while (scanf("%lf", &x) == 1)
            printf("%a\n", argv[1][0] == 'z' ? ct_tab_zeta_of_e(x, law) : ct_tab_e_of_zeta(x, law));
        return 0;
    }
    return 2;
}
"""


@pytest.fixture(scope="session")
def c_reader(source, tmp_path_factory):
    """The compiled reader (C99, no fused multiply-add: the port's operations exactly)."""
    import shutil
    import subprocess
    cc = shutil.which("cc") or shutil.which("gcc")
    if not cc:
        pytest.skip("no C compiler to build the header's reader")
    d = tmp_path_factory.mktemp("reader")
    (d / "reader.c").write_text(_READER_C)
    exe = d / "reader"
    subprocess.run([cc, "-std=c99", "-O2", "-ffp-contract=off", f"-I{source}/include",
                    str(d / "reader.c"), "-o", str(exe), "-lm"], check=True)

    def run(*args, numbers=(), status=False):
        out = subprocess.run([str(exe), *map(str, args)], check=not status, capture_output=True,
                             text=True, errors="replace",
                             input="".join("%r\n" % float(x) for x in numbers))
        if status:  # (exit status, stdout lines, stderr)
            return out.returncode, out.stdout.split("\n")[:-1], out.stderr
        return out.stdout.split("\n")[:-1]

    return run


def _bits(values):
    return [float.fromhex(v) if isinstance(v, str) else float(v) for v in values]


def test_save_writes_the_cli_file(run_cli, source, tmp_path):
    """The file `cantact table` writes for the DEM scene (SI units, [impact] mass): read back
    and saved, and built in Python from the same surface and mass and saved, byte for byte."""
    path = run_cli("table", f"{source}/scripts/scenes/dem_table.ini")
    cli_text = path.read_bytes()
    f = cantact.read_table(path)
    f.save(tmp_path / "again.csv")
    assert (tmp_path / "again.csv").read_bytes() == cli_text
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=200e9, sigma_y=400e6, h0=1e-6, l0=1e-3)
    t = cantact.table(s, V_star=(1e-5, 1e-2), mass=1e-3, tolerance=1e-6)
    # v_per_V_star = sqrt(2 l0 E h0 / m) = sqrt(2 1e-3 200e9 1e-6 / 1e-3) = sqrt(4e5)
    assert t.v_per_V_star == f.v_per_V_star
    assert t.v_per_V_star == pytest.approx(math.sqrt(4e5), rel=1e-15)
    t.save(tmp_path / "py.csv", scene=f.header["scene"], surface=f.header["surface"],
           version=f.header["version"])
    assert (tmp_path / "py.csv").read_bytes() == cli_text
    # e at speeds: V* = v / v_per_V_star
    v = np.array([0.02, 0.3, 6.0])
    assert t.e_of_speed(v).tobytes() == t(v / t.v_per_V_star).tobytes()
    # mass and speed give the same table and v_per_V_star
    u = cantact.table(s, mass=1e-3, speed=(1e-5 * t.v_per_V_star, 1e-2 * t.v_per_V_star),
                      tolerance=1e-6)
    assert u.v_per_V_star == t.v_per_V_star and u.V_star.size == t.V_star.size


def test_saved_table_read_by_c_to_the_same_bits(c_reader, tmp_path):
    rods = cantact.Rods([0.0, 0.5], [1.0, 1.0], E=10.0, Hstar=2.0, l0=1.0, h0=1.0)
    for rule in ("monotone_cubic", "linear"):
        t = cantact.table(rods, V_star=(0.05, 0.5), tolerance=1e-6, interpolation=rule,
                          mass=2.0)
        t.save(tmp_path / "t.csv")
        V = np.geomspace(0.01, 1.0, 2001)
        head, *values = c_reader("load", tmp_path / "t.csv", numbers=V)
        n, Vc, vpv, tol, worst, code = head.split()
        assert int(n) == t.V_star.size and float.fromhex(Vc) == t.V_star_crit
        assert float.fromhex(vpv) == t.v_per_V_star == 1.0 / math.sqrt(2.0 / 2.0 / 10.0)
        assert float.fromhex(tol) == 1e-6 and float.fromhex(worst) == t.info["worst_error"]
        assert int(code) == (0 if rule == "monotone_cubic" else 1)
        assert np.array(_bits(values)).tobytes() == t(V).tobytes()
        back = cantact.read_table(tmp_path / "t.csv")
        assert back(V).tobytes() == t(V).tobytes() and back.v_per_V_star == t.v_per_V_star
    # a table that does not know its tolerance or worst error: those keys are left out (the C
    # reader refuses a NaN), and the file still loads
    bare = tmp_path / "bare.csv"
    with open(bare, "w") as f:
        f.write("# interpolation = linear\n# V_star_crit = 0.5\n# nodes = 2\n"
                "V_star,e,de_dlnV_star\n1,0.8,0\n4,0.4,0\n")
    b = cantact.read_table(bare)
    b.save(tmp_path / "bare2.csv", v_per_V_star=3.0)
    text = (tmp_path / "bare2.csv").read_text()
    assert "tolerance" not in text and "worst_error" not in text and "nan" not in text
    head, mid = c_reader("load", tmp_path / "bare2.csv", numbers=[2.0])
    assert float.fromhex(head.split()[2]) == 3.0 and float.fromhex(mid) == pytest.approx(0.6)
    with pytest.raises(cantact.InvalidInput, match="one line"):
        b.save(tmp_path / "x.csv", scene="a\nb")
    with pytest.raises(cantact.IOFailure, match="cannot write"):
        b.save(tmp_path / "no" / "such" / "dir.csv")
    with pytest.raises(cantact.InvalidInput, match="no v_per_V_star"):
        b.e_of_speed(1.0)


def test_damping_relations_are_the_headers(c_reader):
    """The port gives the C functions' bits, at e from 1e-300 to 1 and zeta from 1e-12 to
    1e150 and the ends."""
    rng = np.random.default_rng(11)
    es = np.concatenate([10.0 ** -np.linspace(0, 300, 3001), rng.random(2000),
                         [0.0, 1.0, math.exp(-2.0), 1 - 1e-16, 5e-324]])
    zetas = np.concatenate([[0.0, 1.0, math.inf, 1 - 1e-12, 1 + 1e-12],
                            np.geomspace(1e-12, 1e150, 3001), rng.random(1000) * 3])
    for law, code in cantact.DAMPING_LAWS.items():
        z = cantact.zeta_of_e(es, law=law)
        assert z.tobytes() == np.array(_bits(c_reader("zeta", code, numbers=es))).tobytes()
        e = cantact.e_of_zeta(zetas, law=law)
        assert e.tobytes() == np.array(_bits(c_reader("e", code, numbers=zetas))).tobytes()


def test_damping_relations_values_and_refusals():
    # tension: e = exp(-pi zeta / sqrt(1 - zeta^2)), by hand at zeta = 0.6 (sqrt(0.64) = 0.8)
    assert cantact.e_of_zeta(0.6, law="tension") == pytest.approx(math.exp(-0.75 * math.pi),
                                                                  rel=1e-15)
    assert cantact.zeta_of_e(math.exp(-0.75 * math.pi), law="tension") == pytest.approx(0.6,
                                                                                        rel=1e-15)
    # clipped at zeta = 0.6: x = 0.75, e = exp(-0.75 (pi - 2 atan 0.75))
    x = 0.75
    assert cantact.e_of_zeta(0.6, law="clipped") == pytest.approx(
        math.exp(-x * (math.pi - 2 * math.atan(x))), rel=1e-14)
    assert cantact.e_of_zeta(1.0, law="clipped") == math.exp(-2.0)
    assert cantact.zeta_of_e(math.exp(-2.0), law="clipped") == pytest.approx(1.0, abs=3e-16)
    # zeta = 2: s = sqrt(3), e = exp(-2 zeta acosh(zeta) / s)
    assert cantact.e_of_zeta(2.0, law="clipped") == pytest.approx(
        math.exp(-4 * math.acosh(2) / math.sqrt(3)), rel=1e-14)
    assert cantact.zeta_of_e(0.0, law="clipped") == math.inf
    assert cantact.zeta_of_e(0.0, law="tension") == 1.0
    assert cantact.e_of_zeta(5.0, law="tension") == 0.0
    a = cantact.zeta_of_e([[0.5, 0.25]], law="clipped")
    assert a.shape == (1, 2) and isinstance(cantact.zeta_of_e(0.5, law="clipped"), float)
    for bad in (-0.1, 1.0000000000000002, math.nan):
        with pytest.raises(cantact.InvalidInput, match="must be in"):
            cantact.zeta_of_e(bad, law="clipped")
    with pytest.raises(cantact.InvalidInput, match=r"e\[1\]"):
        cantact.zeta_of_e([0.5, 2.0], law="tension")
    for bad in (-1e-300, math.nan, -math.inf):
        with pytest.raises(cantact.InvalidInput, match=">= 0"):
            cantact.e_of_zeta(bad, law="tension")
    for law in ("Clipped", None, 1):
        with pytest.raises(cantact.InvalidInput, match="law"):
            cantact.zeta_of_e(0.5, law=law)
    with pytest.raises(TypeError):
        cantact.zeta_of_e(0.5)  # the law must be named: the two relations differ by far


# ---- one acceptance rule: read_table is include/cantact_table.h's reader ------------------


def _hostile_tables(text, source):
    """(name, bytes) of table files: the whole file `text` (bytes, a `cantact table` output),
    tests/fuzz_corpus_table, and copies with one header value, one row, or the structure
    changed: numbers Python's float() reads and strtod does not (and the reverse), cut files,
    repeated or late keys, NUL and non-UTF-8 bytes, line ends, long lines."""
    import glob
    import os
    out = [("whole", text)]
    for p in sorted(glob.glob(os.path.join(source, "tests", "fuzz_corpus_table", "*"))):
        with open(p, "rb") as f:
            out.append((os.path.basename(p), f.read()))
    lines = text.split(b"\n")[:-1]
    head = lines.index(b"V_star,e,de_dlnV_star")
    n = len(lines) - head - 1

    def key_line(key):
        return next(i for i, ln in enumerate(lines) if ln.startswith(b"# " + key + b" ="))

    def with_line(i, new):
        return b"\n".join(lines[:i] + ([new] if new is not None else []) + lines[i + 1:]) + b"\n"

    values = {
        b"v_per_V_star": [b"-1", b"0", b"0.4_5", b"1_000", b"0x1p-3", b"0X1.8P+2", b"inf",
                          b"nan", b"1e400", b"1e-400", b"4.9e-324", b"", b"+2", b".5", b"5.",
                          b"1e5x", b"0x", "\u0662".encode(), b"1,5", b"2e", b"2 (comment)",
                          b"\xff"],
        b"tolerance": [b"abc", b"0x1.0c6f7a0b5ed8dp-20", b"-1", b"nan", b"1_0", b"1e-6;",
                       b"1e-6\t(tab)"],
        b"V_star_crit": [b"-0", b"-1", b"0x0p+0", b"1e-5", b"9.2e-05junk", b"1e-5_0",
                         b"0." + b"0" * 70 + b"1"],
        b"worst_error": [b"0x1p-20", b"1__0", b"infinity"],
        b"worst_error_at_V_star": [b"none", b"None", b"NONE", b"abc", b"1e-3", b"0x1p-9",
                                   b"none(x)"],
        b"nodes": [b"%d" % (n + 1), b"%d" % (n - 1), b"0", b"1", b"1e3", b"0x10", b"+%d" % n,
                   b"%d.0" % n, b"00%d" % n, b"9" * 30, b"%d_0" % n, "\u0663".encode()],
        b"interpolation": [b"linear", b"Linear", b"cubic", b"monotone_cubic;"],
    }
    for key, vals in values.items():
        i = key_line(key)
        for v in vals:
            out.append((f"{key.decode()}={v!r}", with_line(i, b"# " + key + b" = " + v)))
        out.append((f"{key.decode()} twice", with_line(i, lines[i] + b"\n" + lines[i])))
        out.append((f"{key.decode()} missing", with_line(i, None)))
        out.append((f"{key.decode()} late", with_line(i, None)[:-1] + b"\n" + lines[i] + b"\n"))
    row = head + 1 + n // 2
    V, e, d = lines[row].split(b",")
    for name, new in [("hex row", b",".join(float(x).hex().encode() for x in (V, e, d))),
                      ("underscore", V + b"," + e[:3] + b"_" + e[3:] + b"," + d),
                      ("spaces", b" " + V + b" , " + e + b"\t, " + d + b" "),
                      ("four fields", lines[row] + b",0"), ("empty field", V + b",," + d),
                      ("inf slope", V + b"," + e + b",inf"), ("plus", b"+" + lines[row]),
                      ("e above 1", V + b",1.0000000000000002," + d),
                      ("long number", V + b"," + e + b"0" * 70 + b"," + d),
                      ("NUL", V + b",\0" + e + b"," + d), ("unicode digit", "\u0661".encode() +
                                                           b"," + e + b"," + d)]:
        out.append((name, with_line(row, new)))
    out += [
        ("cut at a row", b"\n".join(lines[:row]) + b"\n"),
        ("cut in a row", b"\n".join(lines[:row]) + b"\n" + lines[row][:-3]),
        ("no last line break", text[:-1]),
        ("row beyond", text + b"1e9,0.001,0\n"),
        ("twice", text + text),
        ("blank lines", with_line(row, lines[row] + b"\n\n\r\n") + b"\n"),
        ("CRLF", text.replace(b"\n", b"\r\n")),
        ("CR only", text.replace(b"\n", b"\r")),
        ("BOM", b"\xef\xbb\xbf" + text),
        ("latin-1 scene", with_line(key_line(b"scene"), b"# scene = caf\xe9 \xff")),
        ("long prose", with_line(key_line(b"scene"), b"# scene = " + b"x" * 3000)),
        ("long key", with_line(key_line(b"tolerance"), lines[key_line(b"tolerance")] +
                               b" " + b"x" * 3000)),
        ("empty", b""), ("header only", b"\n".join(lines[:head + 1]) + b"\n"),
        ("no column header", b"\n".join(lines[:head] + lines[head + 1:]) + b"\n"),
    ]
    return out


def test_read_table_accepts_what_the_c_reader_accepts(run_cli, source, c_reader, tmp_path):
    """The Python reader and ct_tab_read on one corpus of hostile files: each is accepted by
    both, to the same bits, or refused by both with the same one-line message (InvalidInput for
    a file that is no table, IOFailure for one that cannot be read), never another exception.
    Before, read_table took v_per_V_star = -1, 0.4_5 (float() reads 0.45) and refused hex
    floats, and `tolerance = abc` raised a bare ValueError."""
    text = run_cli("table", f"{source}/scripts/scenes/default.ini", "--set",
                   "table.tolerance=1e-4").read_bytes()
    text = text.replace(b"\nV_star,e,de_dlnV_star\n", b"\n# v_per_V_star = 2.5\nV_star,e,de_dlnV_star\n")
    corpus = _hostile_tables(text, source)
    accepted = refused = 0
    V = np.geomspace(1e-6, 2e-2, 301)
    for k, (name, data) in enumerate(corpus):
        path = tmp_path / f"{k}.csv"
        path.write_bytes(data)
        code, out, err = c_reader("read", path, status=True)
        try:
            t = cantact.read_table(path)
        except cantact.Error as exc:
            assert code == 1, f"{name}: C accepts, Python refuses: {exc.message}"
            why, message = err.rstrip("\n").split(" ", 1)
            assert type(exc) is {"1": cantact.InvalidInput, "2": cantact.IOFailure}[why], name
            assert exc.message == message, name
            refused += 1
            continue
        assert code == 0, f"{name}: Python accepts, C refuses: {err}"
        head, *rows = out
        n, Vc, vpv, tol, worst, worst_at, rule = head.split()
        assert int(n) == t.V_star.size and float.fromhex(Vc) == t.V_star_crit, name
        for c_value, py_value in ((vpv, t.v_per_V_star), (tol, t.tolerance),
                                  (worst, t.info["worst_error"]),
                                  (worst_at, t.info["worst_V_star"])):
            c_value = float.fromhex(c_value)
            assert (py_value is None and math.isnan(c_value)) or py_value == c_value, name
        assert t.interpolation == ("linear" if rule == "1" else "monotone_cubic"), name
        nodes = np.array([[float.fromhex(x) for x in r.split()] for r in rows])
        assert nodes[:, 0].tobytes() == t.V_star.tobytes(), name
        assert nodes[:, 1].tobytes() == t.e.tobytes(), name
        assert nodes[:, 2].tobytes() == t.slope.tobytes(), name
        _, *values = c_reader("load", path, numbers=V)
        assert np.array(_bits(values)).tobytes() == t(V).tobytes(), name
        accepted += 1
    assert accepted >= 15 and refused >= 80, (accepted, refused)


def test_read_table_refusals_name_the_line():
    """The items of the issue, each refused in one line naming file:line (InvalidInput), and
    a hex float read to its exact value."""
    import tempfile
    base = ("# interpolation = linear\n# V_star_crit = 0.1\n# nodes = 2\n{extra}"
            "V_star,e,de_dlnV_star\n1,1,0\n2,0.5,0\n")
    with tempfile.TemporaryDirectory() as d:
        p = f"{d}/t.csv"
        for extra, message in (
                ("# v_per_V_star = -1\n", "t.csv:4: v_per_V_star = -1: not a number > 0"),
                ("# v_per_V_star = 0.4_5\n", "t.csv:4: v_per_V_star = 0.4_5: not a number"),
                ("# v_per_V_star = 1,5\n", "t.csv:4: v_per_V_star = 1,5: not a number"),
                ("# tolerance = abc\n", "t.csv:4: tolerance = abc: not a number"),
                ("# tolerance = -1e-6\n", "t.csv:4: tolerance = -1e-6: not a number > 0"),
                ("# nodes = 2\n", "t.csv:4: # nodes given twice")):
            with open(p, "w") as f:
                f.write(base.format(extra=extra))
            with pytest.raises(cantact.InvalidInput) as exc:
                cantact.read_table(p)
            assert message in exc.value.message and "\n" not in exc.value.message
        with open(p, "w") as f:
            f.write(base.format(extra="# v_per_V_star = 0x1.8p+1\n").replace("2,0.5", "0x2p0,0.5"))
        t = cantact.read_table(p)
        assert t.v_per_V_star == 3.0 and t.V_star[1] == 2.0
        with open(p, "w") as f:  # a cut file: two rows declared, one there
            f.write(base.format(extra="").replace("2,0.5,0\n", ""))
        with pytest.raises(cantact.InvalidInput, match="t.csv:5: 1 rows where # nodes = 2: the "
                                                       "file is cut"):
            cantact.read_table(p)


def test_save_on_a_full_disk_keeps_the_old_table(run_cli, source, tmp_path):
    """Table.save on a full disk (a file size limit, RLIMIT_FSIZE: writes past it fail with
    EFBIG as on a full file system): IOFailure, and the good table is as it was, no temporary
    file left; saving to a new path leaves no file. Before, save wrote in place: the good table
    was cut to the limit."""
    import os
    import resource
    import subprocess
    import sys
    good = run_cli("table", f"{source}/scripts/scenes/dem_table.ini")
    before = good.read_bytes()
    assert len(before) > 60000
    script = ("import sys, cantact\nt = cantact.read_table(sys.argv[1])\ntry:\n"
              "    t.save(sys.argv[2])\nexcept cantact.IOFailure as exc:\n"
              "    print(exc.message)\n    sys.exit(3)\n")

    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (30000, 30000))

    for target in (good, tmp_path / "new.csv"):
        r = subprocess.run([sys.executable, "-c", script, str(good), str(target)],
                           preexec_fn=limit, capture_output=True, text=True)
        assert r.returncode == 3, r.stderr
        assert r.stdout == f"{target}: cannot write: File too large\n"
        assert good.read_bytes() == before
        assert sorted(os.listdir(tmp_path)) == [good.name]
    # without the limit it is written whole, with the file's permissions kept, through a
    # symbolic link to its target, and a new file gets 0666 less the umask
    t = cantact.read_table(good)
    os.chmod(good, 0o640)
    t.save(good)
    assert good.read_bytes() == before and (os.stat(good).st_mode & 0o777) == 0o640
    link = tmp_path / "link.csv"
    link.symlink_to(good.name)
    t.save(link)
    assert link.is_symlink() and good.read_bytes() == before
    mask = os.umask(0o022)
    try:
        t.save(tmp_path / "fresh.csv")
    finally:
        os.umask(mask)
    assert (os.stat(tmp_path / "fresh.csv").st_mode & 0o777) == 0o644
    assert sorted(os.listdir(tmp_path)) == sorted([good.name, "link.csv", "fresh.csv"])
    with pytest.raises(cantact.IOFailure, match="is a directory"):
        t.save(tmp_path)
    t.save("/dev/null")  # a device: written in place, never replaced
