"""Restitution, ensembles, the load curve, the paper's laws and e(V*) tables: NumPy arrays in,
NumPy arrays out, every call through libcantact's own path (the same as `cantact run`)."""
import errno
import math
import os
import re
import stat

import numpy as np

from . import _check as chk
from . import _keys
from ._errors import check as _ok, error, invalid, memory, size_text
from ._ffi import ffi, lib
from . import _bodies
from ._bodies import body_of
from ._results import Restitution, finite_info
from ._surfaces import Surface, cantor_params, random_cantor, surface_of
from ._work import Work

# The paper's laws by the library's names (ct_law_name).
LAWS = {ffi.string(lib.ct_law_name(k)).decode(): k
        for k in (lib.CT_LAW_SERIES, lib.CT_LAW_ASYMPTOTIC, lib.CT_LAW_ASYMPTOTIC_CONSISTENT)}

# Python's keyword arguments of a run are the library's run keys (ct_run_keys_table), parsed
# through their rows (_keys.RunKeys): impacts and mass are [impact]'s; quadrature, nodes,
# tolerance, check, path, threads, errors (on_error, in Python's words raise and rows) the
# [solver]'s; a table's tolerance, interpolation, max_nodes, check_points and V_star range the
# [table]'s; realisations and split the [ensemble]'s. Speeds (V_star, speed) are arrays, each
# number finite and > 0 (the speeds rows' rule), V* from mass and speed by ct_V_star_of.
RESTITUTION_KEYS = {"impacts": "impact.impacts", "mass": "impact.mass",
                    "quadrature": "solver.quadrature", "nodes": "solver.nodes",
                    "tolerance": "solver.tolerance", "check": "solver.check",
                    "path": "solver.path", "errors": "solver.on_error"}
ENSEMBLE_KEYS = dict(RESTITUTION_KEYS, threads="solver.threads", split="ensemble.split",
                     realisations="ensemble.realisations")
TABLE_KEYS = {"mass": "impact.mass", "quadrature": "solver.quadrature", "nodes": "solver.nodes",
              "check": "solver.check", "path": "solver.path", "tolerance": "table.tolerance",
              "interpolation": "table.interpolation", "max_nodes": "table.max_nodes",
              "check_points": "table.check_points", "V_star": "table.V_star"}


def _run_keys(where, names, **given):
    """The run's keys with the keyword arguments given parsed through their rows (names:
    argument -> "section.name"); where names the call in the library's messages."""
    keys = _keys.RunKeys(where)
    for name, value in given.items():
        keys.set(names[name], value, name)
    return keys


def _speeds(surface, V_star, mass, speed, keys, name="V_star"):
    """V* from V_star, or from mass (impact.mass, parsed into keys) and speed as the CLI
    computes it: the library's ct_V_star_of(m, v, l0, E, h0) = sqrt(m / (2 l0 E h0)) v with
    the surface's physical l0, E and h0 (its parameters as given)."""
    if V_star is not None:
        if mass is not None or speed is not None:
            raise invalid("give either V_star or mass and speed, not both")
        return chk.array(name, V_star, positive=True)
    if mass is None or speed is None:
        raise invalid("needs V_star, or both mass and speed")
    keys.set("impact.mass", mass, "mass")
    m = keys.values.mass
    v = chk.array("speed", speed, positive=True)
    l0, E, h0 = surface._physical_scales()
    with memory(f"speed: V* of {v.size} speeds ({size_text(v.size, 8)})"):
        V = np.fromiter((lib.ct_V_star_of(m, x, l0, E, h0) for x in v),
                        dtype=np.float64, count=v.size)
    bad = ~(np.isfinite(V) & (V > 0))
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise invalid(f"speed[{k}] = {v[k]!r} with mass {m!r} gives V* = {V[k]!r}: not a "
                      "finite number > 0")
    return V


def restitution(surface, V_star=None, *, mass=None, speed=None, body=None, impacts=1,
                quadrature="breakpoints", nodes=64, tolerance=1e-14, check=True, path="auto",
                errors="raise", time=False, progress=None):
    """e and the rest of each impact: for each speed, `impacts` impacts from the virgin surface
    (the plastic strain carried from one to the next). Speeds as V_star (dimensionless) or as
    mass and speed (in the units of the surface's parameters: V* = sqrt(m v^2/(2 l0 E h0));
    the body's mass: per unit depth for a strip or cylinder on a line, its mass on a map).
    body: what strikes the rods (cantact.Flat, Cylinder, Sphere or Body; None: the flat
    strip), met by the library's build (docs/model.md §14); a surface that cannot carry it is
    refused in the library's words.
    errors="raise" raises the first failed impact's error (the library's message, its V* and
    impact); errors="rows" returns failed rows with their status and message instead.
    time=True adds each impact in time (t_contact_over_tau, t_load_over_tau,
    t_unload_over_tau, P_peak_over_PY, e_kinematic, unload_period_over_tau,
    dem_time_step_over_tau; MODEL.md §11). progress: True for a bar on stderr, or a callable
    progress(done, total) of the speeds done. Ctrl-C stops the sweep within a fraction of a
    second (KeyboardInterrupt)."""
    surface = surface_of("surface", surface)
    body = body_of("body", body)
    work = Work(progress, "restitution", "speeds")
    keys = _run_keys("restitution()", RESTITUTION_KEYS, impacts=impacts, quadrature=quadrature,
                     nodes=nodes, tolerance=tolerance, check=check, path=path, errors=errors)
    V = _speeds(surface, V_star, mass, speed, keys)
    solver = keys.solver()
    impacts = int(keys.values.impacts)
    time = chk.flag("time", time)
    # the rows and the arrays made of them: a request too large is OutOfMemory naming its size
    n = V.size * impacts
    with memory(f"restitution: {n} result rows ({V.size} speeds x {impacts} impacts; "
                f"{size_text(n, ffi.sizeof('ct_sweep_row'))} for the library's rows)"):
        rows = ffi.new("ct_sweep_row[]", n)
        b, info = surface._build(V, impacts, solver.opts, body=body)
        spec = ffi.new("ct_sweep_spec *")
        speeds = ffi.from_buffer("double[]", V)
        spec.V_star = speeds
        spec.nvel = V.size
        spec.impacts = impacts
        spec.opts = solver.opts
        spec.stop_on_error = 0 if solver.skip_failed else 1
        spec.path = solver.path
        spec.dynamics = 1 if time else 0
        spec.progress = work.callback
        spec.interrupt = work.flag
        work.run(lambda: lib.ct_sweep(b, spec, rows))
        return Restitution(V, impacts, rows, lib.ct_bundle_layer(b), info, surface, bool(time))


class Ensemble:
    """The samples of an ensemble of random realisations: e, u_max_over_h0, V_star_crit and
    status have shape (realisations, len(V_star), impacts); fx_clipped, fz_clipped count the
    clipped draws of each realisation (of `draws` each). stats(quantity) summarises them.
    Landings (landings()) are samples alike: `realisations` then numbers the landings, x and y
    hold each one's apex (the surface's length unit; y NaN on a line; NaN for realisations)."""

    def __init__(self, V_star, impacts, s, h0):
        R, n = int(s.count), int(s.nrows)
        shape = (R, V_star.size, impacts)

        def take(ptr, dtype, count):
            return np.frombuffer(ffi.buffer(ptr, count * np.dtype(dtype).itemsize),
                                 dtype=dtype).copy()

        self.V_star = V_star
        self.impacts = impacts
        self.first = int(s.first)
        self.realisations = np.arange(self.first, self.first + R, dtype=np.uint64)
        self.e = take(s.e, np.float64, R * n).reshape(shape)
        self.u_max_over_h0 = take(s.u_max, np.float64, R * n).reshape(shape) / h0
        self.V_star_crit = take(s.V_star_crit, np.float64, R * n).reshape(shape)
        self.status = take(s.status, np.intc, R * n).reshape(shape).astype(int)
        ok = self.status == 0
        for name in ("e", "u_max_over_h0", "V_star_crit"):
            chk.finite_result(name, getattr(self, name), ok, where=lambda k, name=name: (
                f"realisation {self.first + int(k[0])}, V* = {V_star[k[1]]!r}, impact "
                f"{k[2] + 1}: {name}"))
        self.fx_clipped = take(s.fx_clipped, np.uint64, R)
        self.fz_clipped = take(s.fz_clipped, np.uint64, R)
        self.x = take(s.x, np.float64, R)
        self.y = take(s.y, np.float64, R)
        self.draws = int(s.draws)
        # NaN: no closed-form check ran
        self.quadrature_error_max = chk.finite_result("quadrature_error_max",
                                                      float(s.quad_error_max), may_be_nan=True)
        self.message = ffi.string(s.message).decode(errors="replace")

    def stats(self, quantity="e"):
        """Statistics over the realisations of each row (library's ct_sample_stats: mean, sd,
        sem = sd/sqrt(n), type-7 quantiles q05, q50, q95, NaN samples left out): a dict of
        arrays of shape (len(V_star), impacts); n = 0 and NaN where no sample computed."""
        x = chk.choice("quantity", quantity, {"e": self.e, "u_max_over_h0": self.u_max_over_h0,
                                              "V_star_crit": self.V_star_crit})
        R = x.shape[0]
        flat = np.ascontiguousarray(x.reshape(R, -1))
        nrows = flat.shape[1]
        keys = ("mean", "sd", "sem", "q05", "q50", "q95")
        out = {k: np.full(nrows, np.nan) for k in keys}
        out["n"] = np.zeros(nrows, dtype=int)
        work = ffi.new("double[]", R)
        st = ffi.new("ct_stats *")
        buf = ffi.from_buffer("double[]", flat)
        for q in range(nrows):
            if lib.ct_sample_stats(buf + q, R, nrows, work, st) != lib.CT_OK:
                continue  # no sample of this row computed
            out["n"][q] = st.n
            for k in keys:
                out[k][q] = getattr(st, k)
        for k in keys:  # sd and sem are NaN for one sample (the library's n - 1)
            chk.finite_result(f"{quantity} {k}", out[k], out["n"] >= (2 if k in ("sd", "sem")
                                                                     else 1),
                              where=lambda i, k=k: f"row {int(i[0])}: {quantity} {k}")
        return {k: v.reshape(x.shape[1:]) for k, v in out.items()}

    def __repr__(self):
        return (f"<Ensemble: {self.e.shape[0]} realisations x {self.V_star.size} speeds x "
                f"{self.impacts} impacts>")


def ensemble(surface, V_star=None, *, mass=None, speed=None, body=None, realisations, first=0,
             impacts=1, quadrature="breakpoints", nodes=64, tolerance=1e-14, check=True,
             path="auto", threads=0, split="auto", errors="raise", progress=None):
    """Realisations first .. first + realisations - 1 of a RandomCantor surface, each built,
    swept and dropped by the library (ct_ensemble: the samples do not depend on the thread
    count or the split). errors="raise" raises the lowest failing realisation's error;
    errors="rows" keeps failed samples as NaN with their status. body: what strikes every
    realisation (None: the flat strip), each sample bit for bit that realisation's own
    restitution(RandomCantor(..., realisation=k), body=...). progress: True for a bar on stderr, or a
    callable progress(done, total) of the realisations done. Ctrl-C stops it within a
    fraction of a second (KeyboardInterrupt)."""
    surface = surface_of("surface", surface)
    body = body_of("body", body)
    work = Work(progress, "ensemble", "realisations")
    ok, why = surface.supports("ensemble")
    if not ok:  # the kind's reason
        raise invalid(f"surface: a {type(surface).__name__} of type = {surface.kind}: {why}")
    keys = _run_keys("ensemble()", ENSEMBLE_KEYS, impacts=impacts, quadrature=quadrature,
                     nodes=nodes, tolerance=tolerance, check=check, path=path, threads=threads,
                     split=split, errors=errors, realisations=realisations)
    V = _speeds(surface, V_star, mass, speed, keys)
    count = int(keys.values.realisations)
    first = chk.integer("first", first, 0, 2**64 - 1 - count)
    rc, _ = random_cantor(surface)
    return _samples(surface, body, rc[0], None, V, keys, first, count, work, "realisations")


def _samples(surface, body, rc, rods, V, keys, first, count, work, what, seed=0):
    """The samples (ct_ensemble) first .. first + count - 1: realisations of rc (a
    ct_random_cantor), or landings on rods (not None: a built, unmet bundle) of the body."""
    solver = keys.solver()
    impacts = int(keys.values.impacts)
    spec = ffi.new("ct_ensemble_spec *")
    if rc is not None:
        spec.surface = rc
    spec.first = first
    spec.count = count
    speeds = ffi.from_buffer("double[]", V)
    spec.V_star = speeds
    spec.nvel = V.size
    spec.impacts = impacts
    spec.opts = solver.opts
    spec.path = solver.path
    spec.stop_on_error = 0 if solver.skip_failed else 1
    spec.threads = solver.threads
    spec.split = keys.values.split
    spec.progress = work.callback
    spec.interrupt = work.flag
    struck = _bodies.request(body, surface._body_keys)  # kept alive with spec
    if rods is not None:
        struck.landings = count
        struck.seed = seed
        spec.rods = rods
    spec.body = struck
    spec.scales = surface._scales[0]
    nrows = V.size * impacts
    # 3 doubles and a status per sample, in the library and again in the arrays returned
    with memory(f"{what[:-1]}s: {count * nrows} samples ({count} {what} x {nrows} rows; "
                f"{size_text(count * nrows, 3 * 8 + ffi.sizeof('int'))} each in the library "
                "and in the arrays returned)"):
        out = ffi.new("ct_ensemble_samples **")
        _ok(lib.ct_ensemble_samples_alloc(out, first, count, nrows))
        s = ffi.gc(out[0], lib.ct_ensemble_samples_free)
        work.run(lambda: lib.ct_ensemble(spec, s))
        return Ensemble(V, impacts, s, surface._units()["u"])


def landings(surface, V_star=None, *, mass=None, speed=None, body, landings, seed=0, first=0,
             impacts=1, quadrature="breakpoints", nodes=64, tolerance=1e-14, check=True,
             path="auto", threads=0, split="auto", errors="raise", progress=None):
    """Landings first .. first + landings - 1 of a curved body (Sphere, Cylinder) on a surface:
    apex positions drawn uniformly where the face stays on the surface (anywhere in a period
    of a periodic one; ct_body_landing_region), landing k a function of (seed, k) alone, each
    struck at every speed (ct_ensemble with the surface's rods: the samples do not depend on
    the thread count or the split). Each landing is bit for bit restitution(surface, body=the
    same body at its apex). The result is an Ensemble whose x and y are the apexes. The
    CLI's [body] landings and seed."""
    surface = surface_of("surface", surface)
    body = body_of("body", body)
    if _bodies.is_default(body):
        raise invalid("body: the flat strip lands everywhere alike: landings need a curved "
                      "body (Sphere or Cylinder)")
    ok, why = surface.supports("landings")
    if not ok:  # the kind's reason
        raise invalid(f"surface: a {type(surface).__name__} of type = {surface.kind}: {why}")
    work = Work(progress, "landings", "landings")
    keys = _run_keys("landings()", ENSEMBLE_KEYS, impacts=impacts, quadrature=quadrature,
                     nodes=nodes, tolerance=tolerance, check=check, path=path, threads=threads,
                     split=split, errors=errors)
    count = chk.integer("landings", landings, 1, 2**64 - 1)
    seed = chk.integer("seed", seed, 0, 2**64 - 1)
    first = chk.integer("first", first, 0, 2**64 - 1 - count)
    V = _speeds(surface, V_star, mass, speed, keys)
    rods, _ = surface._build(V, int(keys.values.impacts), keys.solver().opts, body=body,
                             unmet=True)
    return _samples(surface, body, None, rods, V, keys, first, count, work, "landings", seed)


# ---- the load curve ----------------------------------------------------------------------


class LoadCurve:
    """P(u) of a surface's state (virgin, or after being loaded to `after`), exactly: the
    piecewise-linear curve of the library (ct_curve_*). Dimensionless: u in h0, P in
    P_Y = sigma_y l0, W and the dissipation in P_Y h0. breakpoints: the sorted breakpoints
    (u/h0); force, work, dissipation, release take arrays of u/h0, inverse_work of W. body:
    what presses on the rods (None: the flat strip), as in restitution()."""

    def __init__(self, surface, V_star=None, after=None, body=None):
        surface = surface_of("surface", surface)
        body = body_of("body", body)
        if V_star is None:
            word = surface._depth_word()
            if word is not None:
                raise invalid(f"depth = {word!r} is chosen for the smallest impact: "
                              "give V_star (the speeds the curve is for)")
            V_star = [1.0]
        V = chk.array("V_star", V_star, positive=True)
        keys = _keys.RunKeys("load_curve()")
        keys.set("solver.check", False, "check")
        b, info = surface._build(V, 1, keys.solver().opts, keep_all=True, body=body)
        self.info = finite_info(info)
        self._units = surface._units()
        if after is not None:
            u_adv = chk.real("after", after, 0.0, lo_closed=True) * self._units["u"]
            out = ffi.new("ct_bundle **")
            _ok(lib.ct_bundle_clone(out, b))
            b = ffi.gc(out[0], lib.ct_bundle_free)
            lib.ct_bundle_advance(b, u_adv)
        self._bundle = b  # the curve reads it no more, but keep the state's rods with it
        c = ffi.new("ct_curve **")
        _ok(lib.ct_curve_alloc(c))
        self._curve = ffi.gc(c[0], lib.ct_curve_free)
        _ok(lib.ct_curve_build(self._curve, b))
        n = lib.ct_curve_size(self._curve)
        pts = lib.ct_curve_points(self._curve)
        self.breakpoints = np.frombuffer(ffi.buffer(pts, n * 8), dtype=np.float64).copy()
        self.breakpoints /= self._units["u"]
        chk.finite_result("breakpoints", self.breakpoints)
        self.first_contact = chk.finite_result(
            "first_contact", lib.ct_curve_first_contact(self._curve) / self._units["u"])
        self.first_yield = chk.finite_result(
            "first_yield", lib.ct_curve_first_yield(self._curve) / self._units["u"])

    def _map(self, what, fn, x, name, unit_in, unit_out, nonnegative=False):
        given = chk.array(name, x, nonnegative=nonnegative)
        with memory(f"{what}: {given.size} values ({size_text(given.size, 8)})"), \
                np.errstate(over="ignore"):  # a value beyond doubles in the library's units:
            a = given * self._units[unit_in]  # inf, and its result refused below
            out = np.fromiter((fn(self._curve, v) for v in a), dtype=np.float64,
                              count=a.size) / self._units[unit_out]
        return chk.finite_result(what, out,
                                 where=lambda k: f"{what}({name} = {given[k[0]]!r})")

    def force(self, u):
        """P/P_Y at u/h0 (0 below the first contact)."""
        return self._map("force", lib.ct_curve_force, u, "u", "u", "P")

    def work(self, u):
        """W/(P_Y h0) from the first contact to u/h0."""
        return self._map("work", lib.ct_curve_work, u, "u", "u", "W")

    def dissipation(self, u):
        """The plastic work/(P_Y h0) of loading the state to u/h0."""
        return self._map("dissipation", lib.ct_curve_dissipation, u, "u", "u", "W")

    def release(self, u):
        """The release point/h0 after loading to u/h0."""
        return self._map("release", lib.ct_curve_release, u, "u", "u", "u")

    def inverse_work(self, W):
        """u/h0 where the work from the first contact is W (in P_Y h0), W >= 0."""
        return self._map("inverse_work", lib.ct_curve_inverse_work, W, "W", "W", "u",
                         nonnegative=True)


def load_curve(surface, V_star=None, after=None, body=None):
    """The load curve of a surface under a body (see LoadCurve)."""
    return LoadCurve(surface, V_star, after, body)


# ---- the paper's laws --------------------------------------------------------------------


def _law_surface(surface):
    """The dimensionless ct_params of a surface of type = cantor (the laws' parameters)."""
    if not isinstance(surface, Surface) or surface.kind != "cantor":
        raise invalid(f"surface: the paper's laws model the deterministic Cantor surface "
                      f"(type = cantor), got {type(surface).__name__}"
                      + (f" of type = {surface.kind}" if isinstance(surface, Surface) else ""))
    return cantor_params(surface)[1]


def _pointwise(what, fn, x, errors):
    """Calls fn(k, out) for k < x.size; a failure raises (errors="raise") or gives NaN; a
    non-finite value with a status of success is refused (OutsideModel)."""
    mode = chk.choice("errors", errors, {"raise": "raise", "nan": "nan"})
    with memory(f"{what}: {x.size} values ({size_text(x.size, 8)})"):
        out = np.full(x.size, np.nan)
        ok = np.zeros(x.size, dtype=bool)
    val = ffi.new("double *")
    for k in range(x.size):
        st = fn(k, val)
        if st == lib.CT_OK:
            out[k] = val[0]
            ok[k] = True
        elif mode == "raise":
            raise error(st, f"[{k}]: " + ffi.string(lib.ct_error_message()).decode())
    return chk.finite_result(what, out, ok, where=lambda k: f"{what}(u = {x[k[0]]!r})")


def series_load(surface, u, errors="raise"):
    """The paper's series (Eqs. 12-21, Eq. 15 between nodes): P/P_Y at u/h0."""
    p = _law_surface(surface)
    x = chk.array("u", u, nonnegative=True)
    return _pointwise("series_load", lambda k, v: lib.ct_series_load(p, x[k], v), x, errors)


def series_unload(surface, u_max, u, errors="raise"):
    """The series unloading from u_max/h0 (Eqs. 22-24): P/P_Y at u/h0."""
    p = _law_surface(surface)
    um = chk.real("u_max", u_max, 0.0, lo_closed=True)
    x = chk.array("u", u, nonnegative=True)
    return _pointwise("series_unload", lambda k, v: lib.ct_series_unload(p, um, x[k], v), x,
                      errors)


def asym_load(surface, u, errors="raise"):
    """The asymptotic law (Eqs. 33-34): P/P_Y at u/h0 (u <= h0)."""
    p = _law_surface(surface)
    x = chk.array("u", u, nonnegative=True)
    return _pointwise("asym_load", lambda k, v: lib.ct_asym_load(p, x[k], v), x, errors)


def asym_unload(surface, u_max, u, consistent=False, errors="raise"):
    """Asymptotic unloading from u_max/h0, Eq. 38 as printed or (consistent=True) with its
    second branch derived consistently from Eq. 23: P/P_Y at u/h0."""
    p = _law_surface(surface)
    um = chk.real("u_max", u_max, 0.0, lo_closed=True)
    x = chk.array("u", u, nonnegative=True)
    c = 1 if chk.flag("consistent", consistent) else 0
    return _pointwise("asym_unload", lambda k, v: lib.ct_asym_unload(p, um, x[k], c, v), x,
                      errors)


def law_restitution(surface, V_star=None, *, mass=None, speed=None, law="asymptotic",
                    errors="raise"):
    """e and u_max/h0 of one impact on the virgin fractal under one of the paper's laws
    (ct_law_impact): "series", "asymptotic" (Eq. 38 as printed) or "asymptotic_consistent".
    Returns (e, u_max_over_h0); errors="nan" gives NaN where the law does not apply."""
    p = _law_surface(surface)
    V = _speeds(surface, V_star, mass, speed, _keys.RunKeys("law_restitution()"))
    which = chk.choice("law", law, LAWS)
    scale = lib.ct_energy_scale(p)
    mode = chk.choice("errors", errors, {"raise": "raise", "nan": "nan"})
    with memory(f"law_restitution: {V.size} speeds ({size_text(V.size, 3 * 8)})"), \
            np.errstate(over="ignore"):  # an energy beyond doubles: the library refuses inf
        W = V * V * scale  # the kinetic energy, as a sweep computes it
        e = np.full(V.size, np.nan)
        u = np.full(V.size, np.nan)
        ok = np.zeros(V.size, dtype=bool)
    um, ev = ffi.new("double *"), ffi.new("double *")
    for k in range(V.size):
        st = lib.ct_law_impact(p, which, W[k], um, ev)
        if st == lib.CT_OK:
            e[k], u[k], ok[k] = ev[0], um[0], True
        elif mode == "raise":
            raise error(st, f"V* = {V[k]!r}: " + ffi.string(lib.ct_error_message()).decode())
    for name, x in (("e", e), ("u_max_over_h0", u)):
        chk.finite_result(name, x, ok, where=lambda k, name=name: f"V* = {V[k[0]]!r}: {name}")
    return e, u


# ---- e <-> damping ratio of a linear spring-dashpot contact ---------------------------------
# A line-by-line port of include/cantact_table.h's ct_tab_e_of_zeta and ct_tab_zeta_of_e (the
# same operations in the same order, libm's acos, acosh, exp, log and sqrt through math): the
# same bits as the C functions (python/tests/test_table.py compiles the header and compares).
# The relations, their ranges and derivations are in the header's first comment.

DAMPING_LAWS = {"tension": 0, "clipped": 1}  # CT_TAB_TENSION, CT_TAB_CLIPPED
_PI = 3.14159265358979323846


def _clipped_loss(zeta):
    """-ln e of the clipped law, 2 zeta h(zeta), at a finite zeta >= 0."""
    if zeta < 1.0:
        h = math.acos(zeta) / math.sqrt((1.0 - zeta) * (1.0 + zeta))
    elif zeta > 1.0:
        h = math.acosh(zeta) / (math.sqrt(zeta - 1.0) * math.sqrt(zeta + 1.0))
    else:
        h = 1.0
    return 2.0 * zeta * h


def _clipped_loss_slope(zeta):
    t = 1.0 - zeta
    h = 0.5 * _clipped_loss(zeta) / (zeta if zeta > 0.0 else 1.0)
    if abs(t) < 1e-4:
        dh = -1.0 / 3.0 - 4.0 * t / 15.0
    else:
        dh = (zeta * h - 1.0) / (t * (1.0 + zeta))
    return 2.0 * (h if zeta > 0.0 else _PI / 2.0) + 2.0 * zeta * dh


def _e_of_zeta(zeta, law):
    if law == 0:
        return math.exp(-_PI * zeta / math.sqrt((1.0 - zeta) * (1.0 + zeta))) if zeta < 1.0 \
            else 0.0
    if math.isinf(zeta):
        return 0.0
    return math.exp(-_clipped_loss(zeta))


def _zeta_of_e(e, law):
    if e == 1.0:
        return 0.0
    if e == 0.0:
        return 1.0 if law == 0 else math.inf
    L = -math.log(e)
    if law == 0:
        return L / math.sqrt(_PI * _PI + L * L)
    if L <= 2.0:
        a = _PI - 2.0
        lo, hi = 0.0, 1.0
        z = 2.0 * L / (_PI + math.sqrt(max(_PI * _PI - 4.0 * a * L, 0.0)))
    else:
        lo, hi = 1.0, math.exp(0.5 * L)
        z = 0.5 * hi + 0.5
    best, best_f = z, math.inf
    for _ in range(200):
        f = _clipped_loss(z) - L
        if abs(f) < best_f:
            best, best_f = z, abs(f)
        if f == 0.0:
            break
        if f < 0.0:
            lo = z
        else:
            hi = z
        nxt = z - f / _clipped_loss_slope(z)
        if not (lo < nxt < hi):
            nxt = math.sqrt(lo * hi) if (lo > 0.0 and hi > 4.0 * lo) else lo + 0.5 * (hi - lo)
        if not (lo < nxt < hi):
            break
        if abs(nxt - z) <= 2e-16 * z:
            best = nxt
            break
        z = nxt
    return best


def _damping_map(name, value, law, fn, check):
    law_code = chk.choice("law", law, DAMPING_LAWS)
    a = chk._reals(name, value)
    flat = a.reshape(-1)
    for k, x in enumerate(flat.tolist()):
        if not check(x):
            where = f"{name}[{k}]" if a.ndim else name
            raise invalid(f"{where} = {x!r}: must be "
                          + ("in [0, 1]" if name == "e" else "a number >= 0 (or inf)"))
    with memory(f"{name}: {flat.size} values ({size_text(flat.size, 8)})"):
        out = np.fromiter((fn(x, law_code) for x in flat.tolist()), dtype=np.float64,
                          count=flat.size).reshape(a.shape)
    return float(out) if a.ndim == 0 else out


def zeta_of_e(e, *, law):
    """The damping ratio zeta = c / (2 sqrt(m k)) of a linear spring-dashpot normal contact
    (F = k delta + c delta') that rebounds with e: law "tension" (the contact ends at zero
    overlap: zeta = -ln e / sqrt(pi^2 + ln^2 e), < 1; 1 for e = 0) or "clipped" (the force is
    max(0, F), as Yade's Law2_ScGeom_ViscElPhys_Basic and LAMMPS's limit_damping: the root of
    ln e = -2 zeta h(zeta); zeta > 1 below e = e^-2; inf for e = 0). e in [0, 1], a number or
    an array (same shape back). include/cantact_table.h's ct_tab_zeta_of_e, the same bits."""
    return _damping_map("e", e, law, _zeta_of_e, lambda x: 0.0 <= x <= 1.0)


def e_of_zeta(zeta, *, law):
    """e of a linear spring-dashpot contact of damping ratio zeta >= 0 (inf allowed: e = 0)
    under law "tension" (exp(-pi zeta / sqrt(1 - zeta^2)), 0 for zeta >= 1) or "clipped"
    (exp(-2 zeta h(zeta)), h = acos(zeta) / sqrt(1 - zeta^2), 1 at 1, acosh(zeta) /
    sqrt(zeta^2 - 1) above). include/cantact_table.h's ct_tab_e_of_zeta, the same bits."""
    return _damping_map("zeta", zeta, law, _e_of_zeta, lambda x: x >= 0.0)


# ---- e(V*) tables ------------------------------------------------------------------------


class Table:
    """An e(V*) table (ct_table): nodes V_star, e and slope (de/d ln V*), its interpolation
    ("monotone_cubic" or "linear", in ln V*) and, when built, what the build checked (info:
    V_star_crit, worst_error, worst_V_star, checked, kinks, rounds, evaluations). Calling it
    evaluates the interpolation (the library's, which include/cantact_table.h shares): e = 1 at
    and below V_star_crit, the nearest end's e outside the nodes (covers() says where the table
    knows e). v_per_V_star: the impact speed per unit V* (from table(..., mass=m) or the
    file's key; None when unknown), which e_of_speed() uses; save() writes the file
    include/cantact_table.h reads. A table of samples (`cantact table` of landings or
    realisations) has e as their mean and, per node, e at probabilities p: p (array),
    e_quantiles and slope_quantiles (len(p) x nodes); quantile(V_star, p) evaluates them
    (cantact_table.h's ct_tab_eval_quantile). Otherwise p is None."""

    def __init__(self, handle, tolerance=None):
        self._t = handle
        n = lib.ct_table_size(handle)

        def arr(ptr):
            return np.frombuffer(ffi.buffer(ptr, n * 8), dtype=np.float64).copy()

        self.V_star = arr(lib.ct_table_V_star(handle))
        self.e = arr(lib.ct_table_e(handle))
        self.slope = arr(lib.ct_table_slope(handle))
        nq = lib.ct_table_quantile_count(handle)
        self.p = np.frombuffer(ffi.buffer(lib.ct_table_p(handle), nq * 8),
                               dtype=np.float64).copy() if nq else None
        self.e_quantiles = np.array([arr(lib.ct_table_e_quantile(handle, j)) for j in range(nq)])
        self.slope_quantiles = np.array([arr(lib.ct_table_slope_quantile(handle, j))
                                         for j in range(nq)])
        self.samples = int(lib.ct_table_samples(handle)) if nq else None
        rule = lib.ct_table_interpolation(handle)
        self.interpolation = ffi.string(lib.ct_interp_name(rule)).decode()
        info = ffi.new("ct_table_info *")
        lib.ct_table_get_info(handle, info)
        self.info = {k: getattr(info, k) for k in ("V_star_crit", "worst_error", "worst_V_star",
                                                   "checked", "kinks", "rounds", "evaluations")}
        self.V_star_crit = info.V_star_crit
        self.tolerance = tolerance
        self.v_per_V_star = None
        # what the file's header says beyond the numbers: the version, scene and surface lines,
        # check_points (points checked inside every interval), for save()
        self.header = {"version": None, "scene": None, "surface": None, "check_points": None}

    def __call__(self, V_star):
        V = chk.array("V_star", V_star, positive=True)
        return np.array([lib.ct_table_eval(self._t, v) for v in V], dtype=np.float64)

    def quantile(self, V_star, p):
        """e at V_star and probability p (arrays broadcast together) of a table of samples:
        each quantile column at V_star, non-decreasing in p, linear in p between columns, the
        nearest column outside the first and last p."""
        if self.p is None:
            raise invalid("quantile: the table has no quantile columns (a table of samples has "
                          "them: cantact table with body.landings or [ensemble])")
        V = chk.array("V_star", V_star, positive=True)
        P = chk.array("p", p, finite=True)
        if ((P < 0) | (P > 1)).any():
            raise invalid("p: must be in [0, 1]")
        V, P = np.broadcast_arrays(V, P)
        return np.array([lib.ct_table_eval_quantile(self._t, v, q)
                         for v, q in zip(V.ravel(), P.ravel())]).reshape(V.shape)

    def e_of_speed(self, speed):
        """e at impact speeds in the units of the mass that gave v_per_V_star: e(speed /
        v_per_V_star), as ct_tab_e_of_speed computes it."""
        if self.v_per_V_star is None:
            raise invalid("e_of_speed: the table has no v_per_V_star (build it with mass=..., "
                          "or set table.v_per_V_star)")
        v = chk.array("speed", speed, positive=True)
        return self(v / self.v_per_V_star)

    def save(self, path, *, scene=None, surface=None, version=None, v_per_V_star=None):
        """Writes the table as `cantact table` writes it (ct_table_write: '# key = value' lines,
        then V_star,e,de_dlnV_star rows, every number as %.17g), the file
        include/cantact_table.h and read_table() read. scene, surface, version: the header's
        text (default: what the table was read with, else left out; version "" as the library
        writes it without one); v_per_V_star: overrides the table's (written when known). A
        key the table does not know (tolerance, worst_error, its place, the points checked) is
        left out rather than written as NaN, which the C reader refuses; `# nodes` (the number
        of rows, by which the readers tell a cut file) is always written. As the program
        writes its outputs: into a temporary file beside the path, flushed to the disk, then
        renamed over it, so that a failure (a full disk) raises IOFailure and leaves the
        path as it was (a symbolic link to a file: its target is replaced; a device or a FIFO
        is written in place)."""
        name = chk.path("path", path)
        h = self.header
        scene = h["scene"] if scene is None else scene
        surface = h["surface"] if surface is None else surface
        version = (h["version"] or "") if version is None else version
        for key, text in (("scene", scene), ("surface", surface), ("version", version)):
            if text is not None and (not isinstance(text, str) or "\n" in text or "\r" in text):
                raise invalid(f"{key} = {text!r}: must be one line of text")
        vpv = self.v_per_V_star if v_per_V_star is None else chk.real(
            "v_per_V_star", v_per_V_star, 0.0)

        def g(x):
            return "%.17g" % x

        def known(x):
            return x is not None and math.isfinite(x)

        info = self.info
        lines = [f"# cantact {version} table: e of the first impact on the virgin surface "
                 "against V*"]
        if scene is not None:
            lines.append(f"# scene = {scene}")
        if surface is not None:
            lines.append(f"# surface = {surface}")
        lines.append("# units: V_star = sqrt(m v^2 / (2 l0 E h0)) dimensionless; e "
                     "dimensionless; de_dlnV_star = de/d(ln V_star) dimensionless")
        lines.append(f"# interpolation = {self.interpolation}")
        if self.interpolation == "linear":
            lines.append("# rule: in x = ln V_star on the interval [x_i, x_i+1] holding x, t = "
                         "(x - x_i) / (x_i+1 - x_i): e = e_i + (e_i+1 - e_i) t, kept between e_i "
                         "and e_i+1 (against rounding; de_dlnV_star is not used: 0)")
        else:
            lines.append("# rule: in x = ln V_star on the interval [x_i, x_i+1] holding x, h = "
                         "x_i+1 - x_i, t = (x - x_i) / h, d = de_dlnV_star: e = e_i + (e_i+1 - "
                         "e_i) t^2 (3 - 2 t) + h t (1 - t) ((1 - t) d_i - t d_i+1), kept between "
                         "e_i and e_i+1 (against rounding)")
        lines.append("# rule: e = 1 exactly for V_star <= V_star_crit; outside the nodes above "
                     "it, the nearest end's e (the table does not cover it)")
        lines.append(f"# V_star_crit = {g(self.V_star_crit)}")
        if known(self.tolerance):
            lines.append(f"# tolerance = {g(self.tolerance)}")
        if known(info.get("worst_error")):
            lines.append(f"# worst_error = {g(info['worst_error'])}")
            if known(info.get("worst_V_star")):
                lines.append(f"# worst_error_at_V_star = {g(info['worst_V_star'])}")
            elif h.get("worst_at_none"):
                lines.append("# worst_error_at_V_star = none (no point above V_star_crit in "
                             "the range)")
        if info.get("checked") is not None and h["check_points"]:
            lines.append(f"# checked = {info['checked']} points against the exact model "
                         f"({h['check_points']} equally spaced in ln V_star inside every "
                         "interval above V_star_crit; the nodes are exact)")
        if info.get("kinks") is not None:
            lines.append(f"# nodes = {self.V_star.size} ({info['kinks']} at kinks of e, where "
                         "u_max reaches a rod's contact or yield point)")
        else:
            lines.append(f"# nodes = {self.V_star.size}")
        if vpv is not None:
            lines.append(f"# v_per_V_star = {g(vpv)} (impact speed = V_star * v_per_V_star, in "
                         "the units of the scene's mass, l0, E and h0)")
        header = "V_star,e,de_dlnV_star"
        if self.p is not None:  # a table of samples keeps its quantile columns
            lines.append(f"# quantiles = {self.p.size} (e at each p over the {self.samples} "
                         "samples: the columns e_p<p>)")
            lines.append("# rule: e at (V_star, p): each column e_p<p> at V_star by the rule "
                         "above, kept non-decreasing in p (a running maximum), then linear in p "
                         "between the two columns about p (outside the first and last p, the "
                         "nearest column); e is the mean over the samples")
            header += "".join(f",e_p{q:.6g},de_p{q:.6g}_dlnV_star" for q in self.p.tolist())
        lines.append(header)
        for i, (V, e, d) in enumerate(zip(self.V_star.tolist(), self.e.tolist(),
                                          self.slope.tolist())):
            cols = "".join(f",{g(q[i])},{g(dq[i])}" for q, dq in
                           zip(self.e_quantiles, self.slope_quantiles))
            lines.append(f"{g(V)},{g(e)},{g(d)}{cols}")
        try:  # the text read from a file keeps its bytes (surrogateescape, as read)
            data = ("\n".join(lines) + "\n").encode("utf-8", errors="surrogateescape")
        except UnicodeEncodeError as exc:
            raise invalid(f"scene, surface or version: {exc.object[exc.start:exc.end]!r} cannot "
                          "be written as UTF-8") from None
        _write_replacing(name, data)

    def covers(self, V_star):
        """True where the table knows e: at or below V*_c, or within its nodes."""
        V = chk.array("V_star", V_star, positive=True)
        return (V <= self.V_star_crit) | ((V >= self.V_star[0]) & (V <= self.V_star[-1]))

    def __repr__(self):
        return (f"<Table: {self.V_star.size} nodes, {self.interpolation}, V* "
                f"{self.V_star[0]:.6g} .. {self.V_star[-1]:.6g}, worst error "
                f"{self.info['worst_error']:.3g}>")


def table(surface, V_star=None, *, mass=None, speed=None, body=None, tolerance=1e-6,
          interpolation="monotone_cubic", max_nodes=100000, check_points=16,
          quadrature="breakpoints", nodes=64, check=True, path="auto", progress=None):
    """e(V*) of the first impact on the virgin surface as a table whose interpolation meets
    `tolerance` (absolute, in e) at every checked point (ct_table_build): V_star = (from, to),
    or mass and speed = (from, to). A mass (with either) sets the table's v_per_V_star =
    sqrt(2 l0 E h0 / m), the impact speed per unit V* with the surface's physical l0, E, h0, as
    `cantact table` writes it from [impact] mass (1 / ct_V_star_of(m, 1, l0, E, h0)). body:
    what strikes the rods (None: the flat strip), as in restitution(). Raises NoConvergence
    when max_nodes would not do. progress: True for a bar on stderr, or a callable
    progress(done, total) of the exact impacts computed of those planned so far (the total
    grows as rounds split intervals). Ctrl-C stops the build within a fraction of a second
    (KeyboardInterrupt)."""
    surface = surface_of("surface", surface)
    body = body_of("body", body)
    work = Work(progress, "table", "exact impacts")
    keys = _run_keys("table()", TABLE_KEYS, tolerance=tolerance, interpolation=interpolation,
                     max_nodes=max_nodes, check_points=check_points, quadrature=quadrature,
                     nodes=nodes, check=check, path=path)
    if V_star is not None and mass is not None and speed is None:
        V = _speeds(surface, V_star, None, None, keys)  # the range in V*; the mass for
        keys.set("impact.mass", mass, "mass")           # v_per_V_star
    else:
        V = _speeds(surface, V_star, mass, speed, keys)
    keys.set("table.V_star", V, "V_star")  # the range (from, to) of V*
    k = keys.values
    solver = keys.solver()
    spec = ffi.new("ct_table_spec *")
    lib.ct_table_spec_default(spec)
    spec.V_min, spec.V_max = k.table_range[0], k.table_range[1]
    spec.tolerance = k.table_tolerance
    spec.interpolation = k.interpolation
    spec.max_nodes = k.max_nodes
    spec.check_points = k.check_points
    spec.opts = solver.opts
    spec.path = solver.path
    spec.progress = work.callback
    spec.interrupt = work.flag
    b, _ = surface._build(np.array([spec.V_min, spec.V_max]), 1, solver.opts, body=body)
    out = ffi.new("ct_table **")
    work.run(lambda: lib.ct_table_build(out, b, spec))
    t = Table(ffi.gc(out[0], lib.ct_table_free), spec.tolerance)
    t.header["check_points"] = int(spec.check_points)
    t.header["worst_at_none"] = not math.isfinite(t.info["worst_V_star"])
    if mass is not None:
        l0, E, h0 = surface._physical_scales()
        t.v_per_V_star = 1.0 / lib.ct_V_star_of(k.mass, 1.0, l0, E, h0)
    return t


def read_table(path):
    """A table file (written by `cantact table` or Table.save) as a Table evaluated by the
    library. The file is read by include/cantact_table.h's reader itself (ct_table_read), so
    read_table accepts exactly the files the C reader accepts, to the same numbers: InvalidInput
    (its one-line message naming file:line) for any other, IOFailure when the file cannot be
    opened or read."""
    name = chk.path("path", path)  # a file name, never a descriptor
    out = ffi.new("ct_table **")
    file = ffi.new("ct_table_file_info *")
    _ok(lib.ct_table_read(out, name, file))

    def given(x):
        return x if math.isfinite(x) else None

    t = Table(ffi.gc(out[0], lib.ct_table_free), given(file.tolerance))
    # what the build found, as far as the file tells it (None: not in the file)
    for k in ("worst_error", "worst_V_star", "checked", "kinks", "rounds", "evaluations"):
        t.info[k] = None
    t.info["worst_error"] = given(file.worst_error)
    t.info["worst_V_star"] = given(file.worst_V_star)
    t.v_per_V_star = given(file.v_per_V_star)
    # the header's prose, which the reader skips, for save(): the version, scene and surface
    # text, the points checked and the nodes at kinks
    meta = {"version": None, "scene": None, "surface": None, "check_points": None}
    try:
        with open(name, "rb") as f:
            for raw in f:
                if not raw.startswith(b"#"):
                    break  # the column header: the rows follow
                m = _HEADER_LINE.match(raw.rstrip(b"\r\n").decode("utf-8", "surrogateescape"))
                if not m:
                    continue
                d = {k: v for k, v in m.groupdict().items() if v is not None}
                for k in ("version", "scene", "surface"):
                    if k in d:
                        meta[k] = d[k]
                if "checked" in d:
                    t.info["checked"] = int(d["checked"])
                    meta["check_points"] = int(d["points_each"])
                if "kinks" in d:
                    t.info["kinks"] = int(d["kinks"])
                if "none" in d:
                    meta["worst_at_none"] = True
    except OSError as exc:
        raise error(lib.CT_EIO, f"{os.fsdecode(name)}: cannot read: {exc.strerror}") from None
    t.header = meta
    return t


def _write_replacing(name, data):
    """data (bytes) into the file `name` (bytes) the way the program writes its outputs
    (src/cli/output.c): a temporary file beside it (the file's permissions, or 0666 less the
    umask for a new one), written, flushed to the disk, renamed over it; on any failure the
    temporary is removed and IOFailure raised, and the file is as it was. A symbolic link to a
    regular file: the target is replaced; a device or a FIFO (/dev/stdout): written in place."""
    shown = os.fsdecode(name)

    def fail(what):
        return error(lib.CT_EIO, f"{shown}: cannot write: {what}")

    target, st = name, None
    try:
        if os.path.islink(name) and os.path.exists(name) and os.path.isfile(name):
            target = os.path.realpath(name)
        st = os.stat(target)
    except FileNotFoundError:
        if os.path.islink(name):
            raise fail("a symbolic link whose target does not exist") from None
    except OSError as exc:
        raise fail(exc.strerror) from None
    mode = None
    if st is not None:
        if stat.S_ISDIR(st.st_mode):
            raise fail("is a directory")
        if not os.access(target, os.W_OK):
            raise fail(os.strerror(errno.EACCES))
        if not stat.S_ISREG(st.st_mode):  # a device or a FIFO: nothing to rename over
            try:
                with open(target, "wb") as f:
                    f.write(data)
            except OSError as exc:
                raise fail(exc.strerror) from None
            return
        mode = stat.S_IMODE(st.st_mode)
    tmp, fd = None, -1
    try:
        for _ in range(100):
            tmp = target + b".tmp" + os.urandom(4).hex().encode()
            try:  # 0666 less the umask, as a new file gets
                fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o666)
                break
            except FileExistsError:
                continue
        if fd < 0:
            raise FileExistsError(errno.EEXIST, "no free temporary name")
        if mode is not None:
            os.fchmod(fd, mode)
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view):]
        os.fsync(fd)
        os.close(fd)
        fd = -1
        os.replace(tmp, target)
        tmp = None
    except OSError as exc:
        raise fail(exc.strerror or str(exc)) from None
    finally:
        if fd >= 0:
            os.close(fd)
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass


# The header lines read_table keeps for save(): the version, scene and surface text, the points
# checked (and how many inside every interval) and the nodes at kinks, as ct_table_write
# writes them.
_HEADER_LINE = re.compile(
    r"# cantact (?P<version>.*) table: e of the first impact on the virgin surface against V\*$"
    r"|# scene = (?P<scene>.*)$"
    r"|# surface = (?P<surface>.*)$"
    r"|# checked = (?P<checked>[0-9]+) points against the exact model \((?P<points_each>[0-9]+) "
    r"equally spaced"
    r"|# nodes = [0-9]+ \((?P<kinks>[0-9]+) at kinks"
    r"|# worst_error_at_V_star = (?P<none>none)\b")
