"""The module's boundary (python/cantact/_errors.py states the rule): numbers given become the
doubles they stand for or are refused saying what is true of them; no bare Python exception
leaves a public call (MemoryError included: OutOfMemory naming the size asked for, whatever the
size); and no NaN or inf is handed back as a result of a call that succeeded."""
import decimal
import fractions
import inspect
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import cantact
from cantact import _check

IN = cantact.InvalidInput


def obj(*values):
    return np.array(values, dtype=object)


# ---- numbers given --------------------------------------------------------------------------

# One rod (top 0, area 1, length H* = 1000, E = 100, sigma_y = 1: eps_y = 0.01, k = E / L =
# 0.1), l0 = h0 = 1: W = l0 E h0 V*^2 = 100 V*^2; it yields at W_c = k (eps_y L)^2 / 2 = 5 and
# gives back W_c: e = sqrt(5 / W) = sqrt(0.05) / V*; u_max = u_y + (W - W_c) (the plateau's
# force is sigma_y * area = 1) = 10 + 100 V*^2 - 5, below H* for V* = 1, 2.
def test_exact_integers_in_object_arrays_are_numbers():
    rod = cantact.Rods(obj(0), obj(1), E=100, Hstar=1000, l0=1, h0=1)
    r = cantact.restitution(rod, V_star=obj(1, 2))
    V = np.array([1.0, 2.0])
    np.testing.assert_allclose(r.e[:, 0], np.sqrt(0.05) / V, rtol=1e-14)
    np.testing.assert_allclose(r.u_max_over_h0[:, 0], 5.0 + 100.0 * V * V, rtol=1e-14)
    # the same bits as floats, for every argument that takes numbers
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    same = cantact.Cantor(fx=obj(1.5)[0], fz=np.array(1.3), H=obj(10)[0], E=np.array(500))
    assert same.params == s.params
    a = cantact.restitution(s, mass=1e-3, speed=obj(1, 2, 3))
    b = cantact.restitution(s, mass=1e-3, speed=[1.0, 2.0, 3.0])
    assert np.array_equal(a.e, b.e) and np.array_equal(a.V_star, b.V_star)
    assert np.array_equal(cantact.series_load(s, obj(0, 1)), cantact.series_load(s, [0.0, 1.0]))
    assert np.array_equal(cantact.zeta_of_e(obj(0, 1), law="clipped"), [math.inf, 0.0])
    # 2^53 and 2^60 are doubles exactly
    assert cantact.Rods([0], obj(2**60), E=100, Hstar=1000).area[0] == 2.0**60
    assert cantact.Rods([0], np.array([2**53]), E=100, Hstar=1000).area[0] == 2.0**53
    # the ends of the 64-bit integers that doubles hold
    assert _check._reals("x", np.array([-2**63, 2**63 - 1024])).tolist() == [-2.0**63,
                                                                             2.0**63 - 1024]
    assert _check._reals("x", np.array([2**64 - 2048], dtype=np.uint64))[0] == 2.0**64 - 2048


@pytest.mark.parametrize("given", [
    2**53 + 1, np.uint64(2**64 - 1), obj(1, 2**53 + 1), np.array([1, 2**53 + 1]),
    np.array([2**64 - 1], dtype=np.uint64), np.array([2**62, 2**63 - 1])])
def test_integers_no_double_holds_refused_as_such(given):
    with pytest.raises(IN, match=r"^area(\[\d\])? = \d+: an integer no double holds exactly "
                                 r"\(the nearest is [0-9.e+]+\)"):
        cantact.Rods(np.zeros(np.size(given)), given, E=100, Hstar=1000)


def test_numbers_beyond_doubles_refused_naming_them():
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    cases = [(10**400, "an integer of 401 digits"), (-10**5000, "-an integer of 5001 digits"),
             (fractions.Fraction(10**400, 3), "Fraction"), (decimal.Decimal("1e400"), "Decimal"),
             (fractions.Fraction(1, 10**400), "Fraction"), (decimal.Decimal("1e-400"), "Decimal")]
    if np.finfo(np.longdouble).max > 1e308:  # a long double wider than a double
        cases += [(np.longdouble("1e400"), "1e"), (np.longdouble("1e-400"), "1e")]
    for value, shown in cases:
        with pytest.raises(IN, match=rf"^mass = {shown}.*: beyond double precision"):
            cantact.restitution(s, mass=value, speed=[1.0])
        with pytest.raises(IN, match=rf"^speed\[1\] = {shown}.*: beyond double precision"):
            cantact.restitution(s, mass=1.0, speed=obj(1, value))
    if np.finfo(np.longdouble).max > 1e308:
        with pytest.raises(IN, match=r"^speed\[1\] = 1e\+400: beyond double precision"):
            cantact.restitution(s, mass=1.0, speed=np.array([1, np.longdouble("1e400")]))
    # numbers that are no real numbers, said so
    with pytest.raises(IN, match=r"^V_star\[1\] = None: must be a real number, got NoneType"):
        cantact.restitution(s, V_star=obj(1e-3, None))
    with pytest.raises(IN, match=r"^mass: must be one real number, got an array of shape"):
        cantact.restitution(s, mass=np.array([1.0, 2.0]), speed=1.0)
    with pytest.raises(IN, match=r"^mass = Decimal\('sNaN'\): no double stands for it"):
        cantact.restitution(s, mass=decimal.Decimal("sNaN"), speed=1.0)
    # bytes are no numbers (NumPy would read b"1" as 49), the values under a mask no data
    for given in (b"1", bytearray(b"1"), memoryview(b"1")):
        with pytest.raises(IN, match=r"^speed: must be a number or an array of numbers, got"):
            cantact.restitution(s, mass=1.0, speed=given)
    with pytest.raises(IN, match=r"^speed: a masked array with 1 masked values"):
        cantact.restitution(s, mass=1.0, speed=np.ma.masked_array([1.0, 2.0], mask=[0, 1]))
    unmasked = cantact.restitution(s, mass=1e-3, speed=np.ma.masked_array([1.0, 2.0]))
    assert np.array_equal(unmasked.e, cantact.restitution(s, mass=1e-3, speed=[1.0, 2.0]).e)


# ---- memory ---------------------------------------------------------------------------------

# A process whose address space is limited to 1 GiB above what it maps at the start: every
# request below needs more (none is computed), from 10^7 rows to 10^9, and must raise
# OutOfMemory naming its size.
CHILD = r"""
import resource
import numpy as np, cantact

def mapped():
    for line in open("/proc/self/status"):
        if line.startswith("VmSize:"):
            return int(line.split()[1]) * 1024

limit = mapped() + (1 << 30)
resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
rc = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=4)
many = lambda n: np.broadcast_to(1e-3, (n,))  # n speeds in no memory
cases = {
    "rows_1e7": lambda: cantact.restitution(s, V_star=many(10), impacts=10**6),
    "rows_1e7_speeds": lambda: cantact.restitution(s, V_star=many(10**7)),
    "rows_1e9": lambda: cantact.restitution(s, V_star=many(1000), impacts=10**6),
    "V_star_1e9": lambda: cantact.restitution(s, V_star=many(10**9)),
    "speed_1e9": lambda: cantact.restitution(s, mass=1.0, speed=many(10**9)),
    "samples_1e8": lambda: cantact.ensemble(rc, V_star=many(100), impacts=10**6,
                                            realisations=1),
    "u_1e9": lambda: cantact.series_load(s, many(10**9)),
    "e_1e9": lambda: cantact.zeta_of_e(many(10**9), law="tension"),
}
for name, call in cases.items():
    try:
        call()
        print(name, "computed")
    except cantact.OutOfMemory as exc:
        print(name, "OutOfMemory", exc.message)
    except BaseException as exc:
        print(name, "other", type(exc).__name__, repr(exc))
"""


def test_out_of_memory_names_the_size_for_every_size():
    p = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True,
                       timeout=300, env=dict(os.environ, OMP_NUM_THREADS="2"))
    assert p.returncode == 0, p.stderr
    got = dict(line.split(" ", 1) for line in p.stdout.splitlines())
    want = {
        "rows_1e7": "restitution: 10000000 result rows (10 speeds x 1000000 impacts",
        "rows_1e7_speeds": "restitution: 10000000 result rows (10000000 speeds x 1 impacts",
        "rows_1e9": "restitution: 1000000000 result rows (1000 speeds x 1000000 impacts",
        "V_star_1e9": "V_star: a copy of 1000000000 numbers (1000000000 x 8 bytes = 8 GB)",
        "speed_1e9": "speed: a copy of 1000000000 numbers",
        "samples_1e8": "100000000",
        "u_1e9": "u: a copy of 1000000000 numbers",
        "e_1e9": "e: a copy of 1000000000 numbers",
    }
    for name, text in want.items():
        assert got.get(name, "").startswith("OutOfMemory ") and text in got[name], (
            name, got.get(name))


# ---- results --------------------------------------------------------------------------------


def test_non_finite_results_of_a_success_refused():
    x = np.array([[1.0, 2.0], [np.nan, np.inf]])
    ok = np.array([[True, True], [False, False]])
    assert _check.finite_result("x", x, ok) is x  # only failed rows hold them
    with pytest.raises(cantact.OutsideModel, match=r"^x\[1, 0\] = nan: not a finite number"):
        _check.finite_result("x", x)
    with pytest.raises(cantact.OutsideModel, match=r"^here = inf: not a finite number"):
        _check.finite_result("x", x, may_be_nan=True, where=lambda k: "here")
    x[1, 1] = 3.0
    assert _check.finite_result("x", x, may_be_nan=True) is x  # NaN: "not computed"
    with pytest.raises(cantact.OutsideModel, match=r"^x\[1, 0\] = nan"):
        _check.finite_result("x", x)
    assert _check.finite_result("y", 2.5) == 2.5
    with pytest.raises(cantact.OutsideModel, match=r"^y = -inf"):
        _check.finite_result("y", -math.inf)


class SweepThatLies:
    """The library, but its sweep leaves `change(rows)` in the rows it computed with CT_OK:
    what a defect of the C side would hand to the module."""

    def __init__(self, change):
        self._change = change

    def __getattr__(self, name):
        return getattr(cantact.lib, name)

    def ct_sweep(self, b, spec, rows):
        status = cantact.lib.ct_sweep(b, spec, rows)
        self._change(rows)
        return status


@pytest.mark.parametrize("field, value, time, refused", [
    ("dyn.t_contact", math.nan, True, r"^V\* = 0.002, impact 1: t_contact_over_tau = nan: "
                                      r"not a finite number"),
    ("dyn.period_min", math.inf, True, r"^V\* = 0.002, impact 1: unload_period_over_tau = inf"),
    ("dyn.P_peak", -math.inf, True, r"^V\* = 0.002, impact 1: P_peak_over_PY = -inf"),
    ("r.e", math.nan, False, r"^V\* = 0.002, impact 1: e = nan"),
    ("r.V_star_crit", math.inf, False, r"^V\* = 0.002, impact 1: V_star_crit = inf"),
    ("r.kinetic_energy", math.inf, False, r"kinetic_energy = inf"),
    ("r.e_closed", math.inf, False, r"e_closed_form = inf"),
    ("r.e_closed", math.nan, False, None),  # NaN: the closed form did not check this row
    ("dyn.t_contact", math.nan, False, None),  # not asked for: NaN in every row
])
def test_restitution_refuses_a_non_finite_number_of_a_success(monkeypatch, field, value, time,
                                                              refused):
    group, name = field.split(".")

    def change(rows):
        setattr(getattr(rows[1], group), name, value)

    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    monkeypatch.setattr(cantact._api, "lib", SweepThatLies(change))
    if refused:
        with pytest.raises(cantact.OutsideModel, match=refused):
            cantact.restitution(s, V_star=[1e-3, 2e-3], time=time)
    else:
        r = cantact.restitution(s, V_star=[1e-3, 2e-3], time=time)
        assert np.isfinite(r.e).all()

    def fail(rows):  # a failed row keeps its NaN: the row says why
        change(rows)
        rows[1].status = cantact.lib.CT_ERANGE

    monkeypatch.setattr(cantact._api, "lib", SweepThatLies(fail))
    r = cantact.restitution(s, V_star=[1e-3, 2e-3], time=time, errors="rows")
    assert r.status[1, 0] == cantact.lib.CT_ERANGE and np.isnan(r.e[1, 0])


class LibThatLies:
    """The library, with some functions replaced by lie(real function, *arguments)."""

    def __init__(self, **lies):
        self._lies = lies

    def __getattr__(self, name):
        real = getattr(cantact.lib, name)
        lie = self._lies.get(name)
        return real if lie is None else (lambda *args: lie(real, *args))


def _set(status, out, value):
    out[0] = value
    return status


def _ensemble_nan(real, spec, samples):
    status = real(spec, samples)
    samples.e[1] = math.nan  # realisation 1's sample, with status CT_OK
    return status


def _stats_inf(real, x, n, stride, work, out):
    status = real(x, n, stride, work, out)
    out.q95 = math.inf
    return status


def _fit_nan(real, *args):
    status = real(*args)
    args[-1].D_spectrum = math.nan
    return status


def _fitted_inf(real, *args):
    status = real(*args)
    args[-3][0] = math.inf  # e_cantor_fit of the first impact
    return status


def _build_nan(real, surface, request, out, info):
    status = real(surface, request, out, info)
    info.bound = math.nan
    return status


# Every other call that hands back the library's numbers: a non-finite one with a status of
# success (or from a function without one) is refused naming the figure.
@pytest.mark.parametrize("module, lies, call, refused", [
    ("_api", {"ct_ensemble": _ensemble_nan},
     lambda s, rc, p: cantact.ensemble(rc, V_star=[1e-3], realisations=2),
     r"^realisation 1, V\* = 0.001, impact 1: e = nan"),
    ("_api", {"ct_sample_stats": _stats_inf},
     lambda s, rc, p: cantact.ensemble(rc, V_star=[1e-3], realisations=2).stats("e"),
     r"^row 0: e q95 = inf"),
    ("_api", {"ct_law_impact": lambda real, p, law, W, u, e: (real(p, law, W, u, e),
                                                              _set(0, e, math.nan))[1]},
     lambda s, rc, p: cantact.law_restitution(s, V_star=[1e-3]), r"^V\* = 0.001: e = nan"),
    ("_api", {"ct_series_load": lambda real, p, u, P: _set(0, P, math.inf)},
     lambda s, rc, p: cantact.series_load(s, [0.5]), r"^series_load\(u = 0.5\) = inf"),
    ("_api", {"ct_asym_unload": lambda real, p, um, u, c, P: _set(0, P, math.nan)},
     lambda s, rc, p: cantact.asym_unload(s, 0.5, [0.25]), r"^asym_unload\(u = 0.25\) = nan"),
    ("_api", {"ct_curve_force": lambda real, c, u: math.nan},
     lambda s, rc, p: cantact.load_curve(s, V_star=[1e-3]).force([0.5]),
     r"^force\(u = 0.5\) = nan"),
    ("_api", {"ct_curve_first_yield": lambda real, c: math.inf},
     lambda s, rc, p: cantact.load_curve(s, V_star=[1e-3]), r"^first_yield = inf"),
    ("_surfaces", {"ct_surface_build": _build_nan},
     lambda s, rc, p: cantact.restitution(s, V_star=[1e-3]), r"^info bound = nan"),
    ("_surfaces", {"ct_profile_fit_of": _fit_nan}, lambda s, rc, p: p.fit(),
     r"^D_spectrum = nan"),
    ("_surfaces", {"ct_profile_fitted_e": _fitted_inf},
     lambda s, rc, p: p.compare(cantact.restitution(p, V_star=[1e-3])),
     r"^e_cantor_fit\[0\] = inf"),
])
def test_every_result_of_a_success_is_finite(monkeypatch, module, lies, call, refused):
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    rc = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=3)
    walk = np.cumsum(np.random.default_rng(1).standard_normal(512)) * 1e-8
    p = cantact.Profile(z=walk, dx=1e-6, E=2e11, sigma_y=4e8, H=10)
    call(s, rc, p)  # the library as it is: numbers
    monkeypatch.setattr(getattr(cantact, module), "lib", LibThatLies(**lies))
    with pytest.raises(cantact.OutsideModel, match=refused):
        call(s, rc, p)


def test_load_curve_refuses_a_result_beyond_doubles():
    # u/h0 = 1e308 is 2e308 in the rods' units (h0 = 2): no number, refused naming it
    c = cantact.load_curve(cantact.Rods([0], [1], E=10, Hstar=2), V_star=[1e-3])
    with pytest.raises(cantact.OutsideModel, match=r"^work\(u = 1e\+308\) = "):
        c.work([0.5, 1e308])


# ---- every public call ----------------------------------------------------------------------


def public_callables():
    """(name, callable) of every public function, class and method the module exports."""
    out = []
    for name in cantact.__all__:
        obj_ = getattr(cantact, name)
        if isinstance(obj_, type) and issubclass(obj_, BaseException):
            continue
        if inspect.isfunction(obj_):
            out.append((name, obj_))
        elif isinstance(obj_, type):
            for key, value in vars(obj_).items():
                if key.startswith("_") and key not in ("__init__", "__call__"):
                    continue
                fn = value.fget if isinstance(value, property) else value
                if inspect.isfunction(fn):
                    out.append((f"{name}.{key}", fn))
    return out


def test_every_public_call_is_behind_the_boundary():
    calls = public_callables()
    assert len(calls) > 30
    bare = [name for name, fn in calls if not getattr(fn, "__cantact_boundary__", False)]
    assert not bare


HOSTILE = [None, "1", b"1", 1j, True, [], [[1.0], [1.0, 2.0]], {}, object(), 10**400,
           -10**5000, 2**53 + 1, obj(1, 2), obj(10**400), math.nan, math.inf, -1, 0, 1e308,
           np.zeros((2, 2)), np.array(["a"]), lambda: 0]


def shown(value):
    """value for a message: a number of too many digits for repr (Python refuses 4300) by its
    size."""
    if isinstance(value, int) and value.bit_length() > 1000:
        return f"<an int of {value.bit_length()} bits>"
    return repr(value)[:40]


def test_hostile_arguments_raise_only_the_module_errors(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a path argument given "1" writes ./1
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=6)
    rc = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=3)
    rods = cantact.Rods([0.0, 0.5], [1.0, 1.0], E=10, Hstar=2)
    walk = np.cumsum(np.random.default_rng(1).standard_normal(512)) * 1e-8
    prof = cantact.Profile(z=walk, dx=1e-6, E=2e11, sigma_y=4e8, H=10)
    res = cantact.restitution(prof, V_star=[1e-3])
    curve = cantact.load_curve(s, V_star=[1e-3])
    ens = cantact.ensemble(rc, V_star=[1e-3], realisations=2)
    tab = cantact.table(s, V_star=(1e-4, 1e-3), tolerance=1e-3)
    saved = tmp_path / "t.csv"
    tab.save(saved)
    # (callable, positional arguments, keyword arguments) that work
    calls = [
        (cantact.Cantor, (1.5, 1.3, 10, 500), {"depth": 6}),
        (cantact.Surface, ("random_cantor",), {"fx": 1.5, "fz": 1.3, "H": 10, "E": 500,
                                              "depth": 3, "seed": 2, "threads": 1}),
        (cantact.Surface, ("rods",), {"rods": "0:1, 0.5:1", "Hstar": 2, "unit": "mm",
                                      "E": 10}),
        (s.value, ("surface.depth",), {}), (s.supports, ("ensemble",), {}),
        (cantact.RandomCantor, (1.5, 1.3, 10, 500, 3), {"fx_spread": 0.1}),
        (cantact.Rods, ([0.0, 0.5], [1.0, 1.0]), {"E": 10, "Hstar": 2}),
        (cantact.Profile, (), {"z": np.sin(np.arange(32.0)) * 1e-7, "dx": 1e-6, "E": 2e11,
                               "sigma_y": 4e8, "H": 10}),
        (cantact.restitution, (s, [1e-3]), {"impacts": 2}),
        (cantact.restitution, (rods,), {"mass": 1.0, "speed": [0.1]}),
        (cantact.ensemble, (rc, [1e-3]), {"realisations": 2}),
        (cantact.load_curve, (s, [1e-3]), {"after": 0.5}),
        (curve.force, ([0.5],), {}), (curve.inverse_work, ([0.5],), {}),
        (cantact.series_load, (s, [0.5]), {}), (cantact.series_unload, (s, 1.0, [0.5]), {}),
        (cantact.asym_load, (s, [0.5]), {}), (cantact.asym_unload, (s, 1.0, [0.5]), {}),
        (cantact.law_restitution, (s, [1e-3]), {"law": "series"}),
        (cantact.zeta_of_e, ([0.5],), {"law": "clipped"}),
        (cantact.e_of_zeta, ([0.5],), {"law": "tension"}),
        (cantact.strerror, (1,), {}),
        (ens.stats, ("e",), {}),
        (prof.bearing, ([1e-7],), {}), (prof.fit, (), {"lags": (2e-6, 5e-5)}),
        (prof.compare, (res,), {}),
        (tab, ([1e-3],), {}), (tab.covers, ([1e-3],), {}),
        (tab.save, (tmp_path / "u.csv",), {}), (cantact.read_table, (saved,), {}),
        (cantact.table, (s, (1e-4, 1e-3)), {"tolerance": 1e-3, "max_nodes": 50}),
    ]
    escaped, tried = [], 0
    for fn, args, kwargs in calls:
        fn(*args, **kwargs)  # works as given
        slots = [("arg", k) for k in range(len(args))] + [("kw", k) for k in kwargs]
        for kind, key in slots:
            for bad in HOSTILE:
                a, kw = list(args), dict(kwargs)
                if kind == "arg":
                    a[key] = bad
                else:
                    kw[key] = bad
                tried += 1
                try:
                    with np.errstate(all="ignore"):
                        fn(*a, **kw)
                except cantact.Error:
                    pass
                except BaseException as exc:  # noqa: B902 - what the test is for
                    escaped.append(f"{getattr(fn, '__qualname__', fn)} {key}={shown(bad)}: "
                                   f"{type(exc).__name__}: {exc}")
    assert not escaped, "\n".join(escaped)
    assert tried == len(HOSTILE) * sum(len(a) + len(k) for _, a, k in calls)
