"""The module holds no key, range, default or column of its own: for every kind of surface and
every run key, its keyword arguments are the library's rows (names and defaults), and a value
just inside or just outside each range gets the same answer as from the library itself, asked
here directly through its C API (ct_surface_new/_set/_check/_prepare, ct_key_parse,
ct_run_keys_solver): accepted with the same value stored, or refused with the same message.
Restitution's columns are ct_sweep_columns' and each value is ct_column_values'."""
import inspect
import math

import numpy as np
import pytest

import cantact

ffi, lib = cantact.ffi, cantact.lib
IN = cantact.InvalidInput


def text(p):
    return None if p == ffi.NULL else ffi.string(p).decode()


def kind_rows(kind):
    n = ffi.new("size_t *")
    for k in range(lib.ct_surface_kind_count()):
        if text(lib.ct_surface_kind_name(k)) == kind:
            rows = lib.ct_surface_kind_keys(k, n)
            return [rows + i for i in range(n[0])]
    raise KeyError(kind)


def run_rows():
    n = ffi.new("size_t *")
    rows = lib.ct_run_keys_table(n)
    return {f"{text(rows[i].section)}.{text(rows[i].name)}": rows + i for i in range(n[0])}


def key(row):
    return f"{text(row.section)}.{text(row.name)}"


def default(row):
    return text(getattr(row, "def"))


def message():
    return ffi.string(lib.ct_error_message()).decode()


# ---- the library's own answers --------------------------------------------------------------


def library_surface(kind, where, keys, rods=None):
    """What the library answers to a surface of kind with keys {"section.name": text}, in the
    table's order (rods: arrays for ct_surface_set_rods): (None, {key: value}) when it takes
    it, (message, None) when it refuses it."""
    out = ffi.new("ct_surface **")
    assert lib.ct_surface_new(out, kind.encode()) == 0
    s = ffi.gc(out[0], lib.ct_surface_free)
    w = where.encode()
    for row in kind_rows(kind):
        if key(row) in keys:
            if lib.ct_surface_set(s, row.section, row.name, keys[key(row)].encode(), w):
                return message(), None
    if rods is not None:
        arrays = [ffi.new("double[]", list(a)) for a in rods]
        assert lib.ct_surface_set_rods(s, len(rods[0]), *arrays[:2],
                                       arrays[2] if len(arrays) > 2 else ffi.NULL) == 0
    if lib.ct_surface_check(s, w) or lib.ct_surface_prepare(s, ffi.NULL):
        return message(), None
    v = ffi.new("double *")
    values = {}
    for row in kind_rows(kind):
        if lib.ct_surface_value(s, row.section, row.name, v) == 0:
            values[key(row)] = v[0]
    return None, values


def python_surface(make):
    """(None, the surface) or (message, None)."""
    try:
        return None, make()
    except cantact.Error as exc:
        return exc.message, None


def number_text(x):
    return repr(float(x))


def tries(row):
    """(value, text) pairs just inside and just outside the row's range (its words, a word
    that is none of them; an integer's ends and one past; a count's)."""
    t = row.type
    out = []
    if t == lib.CT_KEY_NUMBER:
        for end, closed, inward in ((row.lo, row.flags & lib.CT_KEY_LO_CLOSED, math.inf),
                                    (row.hi, row.flags & lib.CT_KEY_HI_CLOSED, -math.inf)):
            if math.isinf(end):
                continue
            inside = end if closed else math.nextafter(end, inward)
            outside = math.nextafter(end, -inward) if closed else end
            out += [(inside, number_text(inside)), (outside, number_text(outside))]
        out.append((math.nan, "nan"))
    elif t in (lib.CT_KEY_INTEGER, lib.CT_KEY_DEPTH):
        lo, hi = int(row.lo), int(row.hi)
        out += [(v, str(v)) for v in (lo - 1, lo, hi, hi + 1)]
    elif t == lib.CT_KEY_COUNT:
        out += [(v, str(v)) for v in (-1, 0, 2**64 - 1, 2**64)]
    if t in (lib.CT_KEY_WORD, lib.CT_KEY_DEPTH) and row.words != ffi.NULL:
        out += [(w, w) for w in text(row.words).split("|")] + [("none_of_them", "none_of_them")]
    return out


@pytest.fixture(scope="module")
def profile_file(tmp_path_factory):
    """A small measured profile (x, z in um): its keys are asked of the library many times."""
    p = tmp_path_factory.mktemp("seam") / "line.csv"
    x = np.arange(200)
    z = 0.3 * np.sin(0.37 * x) + 0.1 * np.cos(2.9 * x)
    p.write_text("x_um,z_um\n" + "".join(f"{a!r},{b!r}\n" for a, b in zip(x * 0.5, z)))
    return str(p)


def bases(profile_file):
    """Keys every kind takes, as Python values and as the library's text."""
    return {
        "cantor": {"fx": 1.5, "fz": 1.3, "H": 10.0, "E": 500.0},
        "random_cantor": {"fx": 1.5, "fz": 1.3, "H": 10.0, "E": 500.0, "depth": 4},
        "rods": {"rods": "0:1, 0.5:1", "Hstar": 2.0, "E": 10.0},
        "profile": {"file": profile_file, "H": 10.0, "E": 2e11, "sigma_y": 4e8},
    }


# Python's words of the body table's surface row (periodic=True is surface.periodic = true)
PERIODIC = {True: "true", False: "false"}


def as_text(row, value):
    if isinstance(value, bool) and key(row) == "surface.periodic":
        return PERIODIC[value]
    if isinstance(value, str):
        return value
    if isinstance(value, float) or row.type == lib.CT_KEY_NUMBER:
        return number_text(value)
    return str(value)


def assert_same(python, library, what):
    (pm, ps), (lm, lv) = python, library
    assert pm == lm, (what, pm, lm)
    if ps is not None:  # taken by both: the same values stored
        for k, v in lv.items():
            got = ps.value(k)
            assert got == v or (math.isnan(got) and math.isnan(v)), (what, k, got, v)


# ---- every kind's keys: the generic Surface ---------------------------------------------------


@pytest.mark.parametrize("kind", list(cantact.KINDS))
def test_surface_takes_the_kinds_rows_with_their_answers(kind, profile_file):
    rows = kind_rows(kind)
    assert [key(r) for r in rows] == [f"{r.section}.{r.name}" for r in cantact.KINDS[kind]]
    base = bases(profile_file)[kind]
    by_name = {text(r.name): r for r in rows}
    where = f"Surface({kind!r})"
    tried = 0
    for row in rows:
        name = text(row.name)
        for value, given in tries(row):
            keys = dict(base, **{name: value})
            lib_keys = {key(by_name[k]): as_text(by_name[k], v) for k, v in keys.items()}
            lib_keys[key(row)] = given
            python = python_surface(lambda: cantact.Surface(kind, **keys))
            assert_same(python, library_surface(kind, where, lib_keys), (kind, name, value))
            tried += 1
        # "section.name" names it too
        if name in base:
            m, s = python_surface(lambda: cantact.Surface(kind, **dict(
                {k: v for k, v in base.items() if k != name}, **{key(row): base[name]})))
            assert m is None and s.is_set(name)
    assert tried >= len(rows)
    # a key of another kind, or of none: the library's refusal
    other = "spacing" if kind != "profile" else "fx"
    m, _ = python_surface(lambda: cantact.Surface(kind, **dict(base, **{other: 1.0})))
    assert m.startswith(f"{where}: surface.{other} = 1.0: only for surface.type = ")
    m, _ = python_surface(lambda: cantact.Surface(kind, **dict(base, bogus=1.0)))
    assert m == f"{where}: surface.bogus: unknown key"


def test_surface_kinds_are_the_registry():
    names = [text(lib.ct_surface_kind_name(k)) for k in range(lib.ct_surface_kind_count())]
    assert list(cantact.KINDS) == names
    with pytest.raises(IN) as info:
        cantact.Surface("fractal", fx=1.5)
    out = ffi.new("ct_surface **")
    assert lib.ct_surface_new(out, b"fractal") == lib.CT_EINVAL
    assert info.value.message == f"Surface('fractal'): surface.type = fractal: {message()}"


# ---- the named classes: their arguments are the rows --------------------------------------

NAMED = {"cantor": cantact.Cantor, "random_cantor": cantact.RandomCantor,
         "rods": cantact.Rods, "profile": cantact.Profile}
# A named class's arguments that are data, not keys (the kind takes them another way)
DATA = {"rods": {"top", "area", "length", "x", "y"}, "profile": {"x", "z", "dx", "dy"}}
# Rows a named class does not take as an argument of the same name, and what takes them
ELSEWHERE = {
    "rods": {"surface.file": "Surface('rods', file=...)",
             "surface.rods": "Surface('rods', rods=...); Rods takes arrays"},
    "profile": {"surface.trim": "trim=k is trim = rq with trim_k = k",
                "surface.trim_k": "Profile's trim",
                "fit.depth_lo": "Profile.fit(depths=...)", "fit.depth_hi": "Profile.fit()",
                "fit.lag_lo": "Profile.fit(lags=...)", "fit.lag_hi": "Profile.fit()",
                "fit.dimension": "Profile.fit(dimension=...)"},
}
# The run's rows a surface's build takes
BUILD = {"threads": "solver.threads", "depth_tolerance": "solver.depth_tolerance"}


def body_rows():
    n = ffi.new("size_t *")
    rows = lib.ct_body_keys_table(n)
    return {key(rows + i): rows + i for i in range(n[0])}


# The body table's rows of section surface (periodic): every surface takes them
SURFACE_BODY = {text(r.name): r for r in body_rows().values() if text(r.section) == "surface"}


def stored(row, given):
    """The bytes ct_key_parse stores for the text given, or None when it refuses it."""
    buf = ffi.new("char[]", int(row.offset) + 16)
    if lib.ct_key_parse(row, given.encode(), buf):
        return None
    size = {lib.CT_KEY_NUMBER: 8, lib.CT_KEY_INTEGER: 8, lib.CT_KEY_DEPTH: 8,
            lib.CT_KEY_COUNT: 8, lib.CT_KEY_WORD: 4, lib.CT_KEY_RANGE: 16}[row.type]
    return bytes(ffi.buffer(buf + int(row.offset), size))


def same_default(row, python_default):
    """A Python default stands for the row's: both parse to the same stored value, or the
    row's is none or a description (not a value) and Python's None (not given)."""
    lib_default = stored(row, default(row)) if default(row) else None
    if lib_default is None:
        return python_default is None or python_default is inspect.Parameter.empty
    if python_default in (None, inspect.Parameter.empty):
        return False
    return stored(row, as_text(row, python_default)) == lib_default


@pytest.mark.parametrize("kind", list(NAMED))
def test_named_classes_take_the_kinds_rows(kind, profile_file):
    cls = NAMED[kind]
    params = {n: p for n, p in inspect.signature(cls.__init__).parameters.items()
              if n != "self"}
    rows = {text(r.name): r for r in kind_rows(kind)}
    runs = run_rows()
    # every argument is a row of the kind, a run's row a build takes, or data
    for name, p in params.items():
        if name in DATA.get(kind, ()):
            continue
        if name == "trim" and kind == "profile":
            assert p.default is None and default(rows["trim"]) == "none"
            continue
        row = rows.get(name) or runs.get(BUILD.get(name, "")) or SURFACE_BODY.get(name)
        assert row is not None, f"{cls.__name__}({name}=...): an argument of its own"
        required = bool(row.flags & lib.CT_KEY_REQUIRED)
        if required and p.default is inspect.Parameter.empty:
            continue
        assert same_default(row, p.default) or (required and name == "file"), (
            f"{cls.__name__}({name}={p.default!r}): the row's default is {default(row)!r}")
    # every row is an argument of the same name, or taken elsewhere (said where)
    for r in kind_rows(kind):
        if text(r.name) not in params:
            assert key(r) in ELSEWHERE.get(kind, {}), f"{kind}: {key(r)} is no argument"
    for name in SURFACE_BODY:  # every surface repeats or not
        assert name in params, f"{cls.__name__}: no {name}="
    # the arguments' answers are the library's
    base = bases(profile_file)[kind]
    where = f"{cls.__name__}()"
    data = {}
    if kind == "rods":
        base = {k: v for k, v in base.items() if k != "rods"}
        data = {"top": [0.0, 0.5], "area": [1.0, 1.0]}
    for name in params:
        row = rows.get(name)
        if row is None or key(row) in ELSEWHERE.get(kind, {}) or row.type == lib.CT_KEY_TEXT:
            continue
        for value, given in tries(row):
            keys = dict(base, **{name: value})
            lib_keys = {key(rows[k]): as_text(rows[k], v) for k, v in keys.items()}
            lib_keys[key(row)] = given
            python = python_surface(lambda: cls(**data, **keys))
            library = library_surface(kind, where, lib_keys,
                                      rods=(data["top"], data["area"]) if data else None)
            assert_same(python, library, (kind, name, value))


@pytest.mark.parametrize("top, area, length", [
    ([0.0, 0.5], [1.0, 0.0], None), ([0.0, -1e-300], [1.0, 1.0], None),
    ([0.0, math.inf], [1.0, 1.0], None), ([0.0, 0.5], [1.0, math.nan], None),
    ([0.0, 2.0], [1.0, 1.0], None), ([0.0, 0.5], [1.0, 1.0], [1.0, 0.0]),
    ([0.0, 0.5], [1.0, 1.0], [1.0, -math.inf]), ([0.0, 0.5], [5e-324, 1.0], None)])
def test_rods_arrays_are_judged_by_the_kind(top, area, length):
    keys = {"E": 10.0} if length is not None else {"E": 10.0, "Hstar": 2.0}
    python = python_surface(lambda: cantact.Rods(top, area, length=length, **keys))
    library = library_surface("rods", "Rods()", {f"{'material' if k == 'E' else 'surface'}."
                                                 f"{k}": number_text(v) for k, v in keys.items()},
                              rods=(top, area) + ((length,) if length else ()))
    assert_same(python, library, (top, area, length))


def test_profile_trim_is_the_kinds_trim_k(profile_file):
    base = bases(profile_file)["profile"]
    rows = {text(r.name): r for r in kind_rows("profile")}
    for value, given in tries(rows["trim_k"]):
        lib_keys = {key(rows[k]): as_text(rows[k], v) for k, v in base.items()}
        lib_keys.update({"surface.trim": "rq", "surface.trim_k": given})
        assert_same(python_surface(lambda: cantact.Profile(**base, trim=value)),
                    library_surface("profile", "Profile()", lib_keys), value)


def test_profile_arrays_keys_are_the_kinds(profile_file):
    """Heights as arrays (which the kind does not read) have their keys judged by the kind as
    a file's are."""
    z = np.sin(0.37 * np.arange(200)) * 1e-7
    for bad in ({"H": 1.0}, {"Hstar": 0.0}, {"H": 10.0, "Hstar": 1e-6}, {"H": None},
                {"E": 3e8}, {"sigma_y": -1.0}, {"detrend": "cubic"}, {"trim": 0.0},
                {"trim": math.inf}, {"threads": 1025}):
        keys = dict(bases(profile_file)["profile"], **bad)
        del keys["file"]
        keys = {k: v for k, v in keys.items() if v is not None}
        with pytest.raises(IN) as a:
            cantact.Profile(z=z, dx=1e-6, **keys)
        with pytest.raises(IN) as f:
            cantact.Profile(profile_file, **keys)
        assert a.value.message == f.value.message, bad


# ---- the run's keys ---------------------------------------------------------------------------


class Reached(Exception):
    """The call got to the library's computation: its arguments were all taken."""


class Stop:
    """The library, but its computations (a sweep, an ensemble, a table) stop the call with
    their spec, so that a value at the end of a range is checked without being computed."""

    def __getattr__(self, name):
        real = getattr(lib, name)
        if name in ("ct_sweep", "ct_ensemble", "ct_table_build"):
            def stop(*args):
                raise Reached(args)
            return stop
        if name == "ct_ensemble_samples_alloc":  # the samples are never computed
            return lambda out, first, count, nrows: real(out, first, 1, 1)
        return real


def rods():
    return cantact.Rods([0.0], [1.0], E=100.0, Hstar=1000.0, l0=1.0, h0=1.0)


def random():
    return cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=0)


# Every run row: the call and argument that take it (the argument's name is the row's unless
# said), or why Python has none.
RUN = {
    "impact.V_star": "restitution(V_star=...): an array, each number finite and > 0",
    "impact.velocity": "restitution(speed=...): an array, each number finite and > 0",
    "impact.drop_height": "the program's: a body dropped from rest",
    "impact.sequence": "the program's: bounce sequences",
    "impact.gravity": "the program's: bounce sequences and drops",
    "impact.stop_speed": "the program's: bounce sequences",
    "impact.mass": (cantact.restitution, "mass"),
    "impact.impacts": (cantact.ensemble, "impacts"),
    "solver.quadrature": (cantact.restitution, "quadrature"),
    "solver.nodes": (cantact.restitution, "nodes"),
    "solver.tolerance": (cantact.restitution, "tolerance"),
    "solver.depth_tolerance": (cantact.Cantor, "depth_tolerance"),
    "solver.threads": (cantact.ensemble, "threads"),
    "solver.on_error": (cantact.restitution, "errors"),
    "solver.check": (cantact.restitution, "check"),
    "solver.path": (cantact.restitution, "path"),
    "table.tolerance": (cantact.table, "tolerance"),
    "table.V_star": (cantact.table, "V_star"),
    "table.interpolation": (cantact.table, "interpolation"),
    "table.max_nodes": (cantact.table, "max_nodes"),
    "table.check_points": (cantact.table, "check_points"),
    "table.quantiles": "the program's: tables of samples (read_table reads them: quantile())",
    "table.grid": "the program's: tables of samples",
    "table.quantile_tolerance": "the program's: tables of samples",
    "ensemble.realisations": (cantact.ensemble, "realisations"),
    "ensemble.split": (cantact.ensemble, "split"),
}
# Python's words for a row's words (the rows' own are taken too), and its one default of its own
WORDS = {"solver.on_error": {"raise": "stop", "rows": "skip"},
         "solver.check": {True: "all", False: "none"}}
OWN_DEFAULT = {"solver.check": "check=True: every impact also in closed form (the program's "
                               "auto samples a large sweep)"}
WHERE = {cantact.restitution: "restitution()", cantact.ensemble: "ensemble()",
         cantact.table: "table()", cantact.Cantor: "Cantor()"}


def call(fn, name, value):
    """fn with the argument name = value and everything else valid."""
    if fn is cantact.Cantor:
        return fn(fx=1.5, fz=1.3, H=10, E=500, **{name: value})
    if fn is cantact.restitution:
        kw = {"V_star": [1e-3]} if name != "mass" else {"speed": [1.0]}
        return fn(rods(), **kw, **{name: value})
    if fn is cantact.ensemble:
        kw = dict({"V_star": [1e-3], "realisations": 2}, **{name: value})
        return fn(random(), **kw)
    kw = dict({"V_star": (1e-3, 1e-2), "tolerance": 1e-3}, **{name: value})
    return fn(rods(), **kw)


def run_tries(row):
    if row.type == lib.CT_KEY_RANGE:
        return [((1e-3, 1e-2), "0.001:0.01"), ((1e-2, 1e-3), "0.01:0.001"),
                ((1e-3,), "0.001"), ((1e-3, 1e-3), "0.001:0.001")]
    return tries(row)


def test_run_keys_are_the_rows(monkeypatch):
    runs = run_rows()
    assert set(RUN) == set(runs), "a run row Python does not say it takes or leaves"
    assert [f"{r.section}.{r.name}" for r in cantact.RUN_ROWS] == list(runs)
    defaults = ffi.new("ct_run_keys *")
    lib.ct_run_keys_defaults(defaults)
    for k, how in RUN.items():
        if isinstance(how, str):
            continue
        fn, name = how
        row = runs[k]
        assert name == text(row.name) or k in WORDS or k == "table.V_star", (k, name)
        # the default: the row's (parsed as the program parses it)
        p = inspect.signature(fn).parameters[name]
        words = WORDS.get(k, {})
        d = p.default
        if d is not inspect.Parameter.empty:
            d = words.get(d, d)
        if k in OWN_DEFAULT:
            assert d != default(row), k
        elif d in (None, inspect.Parameter.empty):  # none: the row has none either
            assert default(row) == "" or k == "table.V_star", (k, default(row))
        else:  # what ct_run_keys_defaults holds
            lib_default = bytes(ffi.buffer(ffi.cast("char *", defaults) + int(row.offset),
                                           len(stored(row, as_text(row, d)))))
            assert stored(row, as_text(row, d)) == lib_default, (k, p.default, default(row))
        # values just inside and outside: the library's answer
        monkeypatch.setattr(cantact._api, "lib", Stop())
        for value, given in run_tries(row):
            buf = ffi.new("ct_run_keys *")
            lib.ct_run_keys_defaults(buf)
            refused = lib.ct_key_parse(row, given.encode(), buf)
            why = message()
            if not refused:
                solver = ffi.new("ct_run_solver *")
                if lib.ct_run_keys_solver(buf, solver):
                    refused, why = True, message()
            pv = next((w for w, lw in words.items() if lw == value
                       and type(w) is not bool), value) if words else value
            if k == "solver.check" and value in ("all", "none"):
                pv = value == "all"
            try:
                call(fn, name, pv)
                got = None
            except Reached:
                got = None
            except cantact.InvalidInput as exc:
                got = exc.message
            if refused:
                assert got == f"{WHERE[fn]}: {k} = {given}: {why}", (k, value, got, why)
            else:
                assert got is None, (k, value, got)
        monkeypatch.undo()


def test_run_values_reach_the_library(monkeypatch):
    """The values taken are the ones the library parsed, passed on as they are."""
    seen = {}

    class Spy(Stop):
        def __getattr__(self, name):
            if name in ("ct_sweep", "ct_ensemble", "ct_table_build"):
                def stop(*args):
                    seen[name] = args
                    raise Reached()
                return stop
            return super().__getattr__(name)

    monkeypatch.setattr(cantact._api, "lib", Spy())
    with pytest.raises(Reached):
        cantact.restitution(rods(), V_star=[1e-3], quadrature="gauss", nodes=100000000,
                            tolerance=math.nextafter(1e-3, 0), check=False, path="lean",
                            errors="rows", impacts=3)
    spec = seen["ct_sweep"][1]
    assert (spec.opts.rule, spec.opts.nodes, spec.opts.tolerance, spec.opts.check) == (
        lib.CT_QUAD_GAUSS, 100000000, math.nextafter(1e-3, 0), 0)
    assert (spec.path, spec.stop_on_error, spec.impacts) == (lib.CT_PATH_LEAN, 0, 3)
    with pytest.raises(Reached):
        cantact.ensemble(random(), V_star=[1e-3], realisations=1000000000, impacts=1000000,
                         threads=1024, split="rods", check="closed")
    spec = seen["ct_ensemble"][0]
    assert (spec.count, spec.impacts, spec.threads, spec.split, spec.opts.check) == (
        1000000000, 1000000, 1024, lib.CT_SPLIT_RODS, 1)
    with pytest.raises(Reached):
        cantact.table(rods(), V_star=(1e-3, 1e-2), tolerance=math.nextafter(0.5, 0),
                      interpolation="linear", max_nodes=10000000, check_points=1000)
    spec = seen["ct_table_build"][2]
    assert (spec.V_min, spec.V_max, spec.tolerance, spec.interpolation, spec.max_nodes,
            spec.check_points) == (1e-3, 1e-2, math.nextafter(0.5, 0), lib.CT_INTERP_LINEAR,
                                   10000000, 1000)


# ---- the columns ------------------------------------------------------------------------------


def test_restitution_columns_are_the_librarys():
    p = ffi.new("const ct_column **")
    n = lib.ct_sweep_columns(p)
    table = [text(p[0][k].name) for k in range(n)]
    assert [c["name"] for c in cantact.COLUMNS] == table
    r = cantact.restitution(rods(), V_star=[1e-3, 0.5], impacts=2, time=True)
    attrs = sorted(k for k, v in vars(r).items() if not k.startswith("_")
                   and isinstance(v, np.ndarray) and v.dtype == np.float64 and v.shape == r.e.shape)
    columns = [text(p[0][k].name) for k in range(n)
               if p[0][k].type in (b"d", b"w") and text(p[0][k].name) != "V_star"]
    assert attrs == sorted(columns + ["kinetic_energy"])


def test_every_column_value_is_ct_column_values(monkeypatch):
    """ct_column_values answering each column with its index in the table: every attribute of
    that column holds it, so no value is computed in Python."""
    p = ffi.new("const ct_column **")
    n = lib.ct_sweep_columns(p)
    base = int(ffi.cast("uintptr_t", p[0]))
    size = ffi.sizeof("ct_column")

    def marks(c, rows, count, layer, out):
        for q in range(count):
            out[q] = 1000.0 + (int(ffi.cast("uintptr_t", c)) - base) / size

    class Marks:
        def __getattr__(self, name):
            if name == "ct_column_values":
                return marks
            return getattr(lib, name)

    monkeypatch.setattr(cantact._results, "lib", Marks())
    r = cantact.restitution(rods(), V_star=[1e-3, 0.5], impacts=2, time=True)
    for k in range(n):
        c = p[0][k]
        name = text(c.name)
        if c.type in (b"d", b"w") and name != "V_star":
            assert (getattr(r, name) == 1000.0 + k).all(), name
