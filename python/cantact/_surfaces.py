"""Surfaces: one generic Surface(kind, **keys) over the library's surface handle, and the
named classes as conveniences over it.

A Surface is a kind of the library (ct_surface_kind_name: cantor, random_cantor, profile, rods)
set up by that kind's keys: each keyword argument is the row of the same name
(ct_surface_kind_keys; "section.name" as well), given to ct_surface_set as text, then the keys
are checked together (ct_surface_check) and the surface prepared (ct_surface_prepare: a file
read and levelled, the scales fixed), and built into rods for the speeds asked
(ct_surface_build with a ct_build_request). Its keys, ranges, defaults and messages are the
kind's own, the same as a scene's (the program's `surface.type = kind`): the module types
none of them. threads and depth_tolerance are the run's rows (solver.threads,
solver.depth_tolerance) that a build takes; periodic is the body table's row of section
surface (surface.periodic, ct_body_keys_table: the surface repeats as far as a curved body's
face reaches), which a build gives the library in the ct_body of its request with the body
struck (_bodies.py).

A Cantor or random Cantor surface is computed in dimensionless form, as the cantact program
does (l0 = h0 = sigma_y = 1, H* = H, E = E/sigma_y): the results (u/h0, P/P_Y, V*) are the
same bits as `cantact run`'s. Other kinds are computed in the units given; their results are
made dimensionless by their layer's h0, sigma_y and l0."""
import re

import numpy as np

from . import _bodies
from . import _check as chk
from . import _keys
from ._errors import check, error, invalid
from ._ffi import ffi, lib
from ._results import Restitution


def _plan_info(info):
    return {"depth": int(info.depth), "bound": float(info.bound), "rods": int(info.rods),
            "omitted": int(info.omitted)}


def _info(b, depth=-1, bound=0.0):
    return {"depth": int(depth), "bound": float(bound), "rods": int(lib.ct_bundle_size(b)),
            "omitted": int(lib.ct_bundle_omitted(b))}


class _Default:
    """An argument not given: the library's default."""

    def __repr__(self):
        return "the library's default"


_DEFAULT = _Default()


class Surface:
    """A surface of one kind of the library: Surface(kind, **keys), kind one of
    cantact.KINDS (cantor, random_cantor, profile, rods), every keyword one of that kind's
    keys (cantact.KINDS[kind]: its rows, with their ranges, defaults and docs; "section.name"
    names one too), set as the program sets `surface.type = kind` and its keys from a scene:
    the same values accepted, the same refused with the same words. threads (solver.threads)
    and depth_tolerance (solver.depth_tolerance) are the run's keys a build takes. E.g.
    Surface("cantor", fx=1.5, fz=1.3, H=10, E=500), Surface("rods", rods="0:1, 0.5:1",
    Hstar=2, E=10), Surface("profile", file="scan.csv", H=10, E=2e11, sigma_y=4e8). periodic
    (surface.periodic, the body table's row of the surface: True or False, or the row's
    words): the surface repeats as far as a curved body's face reaches (a Cantor surface with
    period l0, a profile or map as measured) instead of ending at its border. layer and
    physical: the layer as built and as given; value(key): a key's value as parsed; note: what
    the library says of the surface prepared ("" when nothing)."""

    def __init__(self, kind, *, threads=_DEFAULT, depth_tolerance=_DEFAULT, **keys):
        self._setup(kind, keys, threads, depth_tolerance)

    # ---- the handle ----

    def _setup(self, kind, keys, threads=_DEFAULT, depth_tolerance=_DEFAULT, prepare=True,
               names=None):
        """The handle of kind with keys set, checked and (prepare) prepared; the run's keys a
        build takes. names: the keyword argument that gave a key, where it is not the key's
        own name (for the messages of a value's type)."""
        name = kind if isinstance(kind, str) and "\0" not in kind else None
        self.kind = name
        where = self._scene().encode()
        out = ffi.new("ct_surface **")
        st = lib.ct_surface_new(out, name.encode(errors="replace") if name is not None else b"")
        if st != lib.CT_OK:  # the library names the kinds
            shown = _keys.shown(kind if name is not None else chk._text(kind))
            raise error(st, f"{where.decode()}: surface.type = {shown}: {_keys.message()}")
        s = ffi.gc(out[0], lib.ct_surface_free)
        self._surface = s
        self._rows = _keys.KINDS[name]
        run = _keys.RunKeys(where.decode())
        if threads is not _DEFAULT:
            run.set("solver.threads", threads, "threads")
        if depth_tolerance is not _DEFAULT:
            run.set("solver.depth_tolerance", depth_tolerance, "depth_tolerance")
        solver = run.solver()
        self.threads = int(solver.threads)
        self.depth_tolerance = float(solver.depth_tolerance)
        by_name = {}
        for r in self._rows:
            by_name.setdefault(r.name, r)
            by_name[f"{r.section}.{r.name}"] = r
        given, own = {}, {}
        for key, value in keys.items():
            if key in _bodies.SURFACE_ROWS:  # the surface's row of the body table: periodic
                own[key] = value
                continue
            row = by_name.get(key)
            if row is None:  # not this kind's: the library says which kinds take it
                self._set_other(key, value, where)
            given[(row.section, row.name)] = (key, value)
        for r in self._rows:  # in the table's order, as a scene's keys
            if (r.section, r.name) in given:
                key, value = given[(r.section, r.name)]
                check(lib.ct_surface_set(s, r.section.encode(), r.name.encode(),
                                         _keys.text(r, (names or {}).get(key, key), value),
                                         where))
        self._given = {f"{sec}.{nm}": v[1] for (sec, nm), v in given.items()}
        self._before_check(s)
        check(lib.ct_surface_check(s, where))
        # after the kind's keys, as the program reads a scene: surface.periodic into the ct_body
        # a build gives the library
        self._body_keys = _bodies.defaults()
        for key, value in own.items():
            r = _bodies.SURFACE_ROWS[key]
            _bodies.parse(self._body_keys, r, value, key, where.decode())
            self._given[f"{r.section}.{r.name}"] = value
        if prepare:
            check(lib.ct_surface_prepare(s, ffi.NULL))
            self._scales = ffi.new("ct_scales *")
            lib.ct_surface_scales(s, self._scales)

    def _set_other(self, key, value, where):
        """A key of no row of this kind: the library's refusal (which kinds take it, or that
        none does)."""
        section, _, name = key.rpartition(".")
        if not section:
            section = next((r.section for rows in _keys.KINDS.values() for r in rows
                            if r.name == name), "surface")
        shown = value if isinstance(value, str) else chk._text(value)
        check(lib.ct_surface_set(self._surface, section.encode(errors="replace"),
                                 name.encode(errors="replace"),
                                 shown.encode(errors="replace"), where))
        raise invalid(f"{key}: not a key of type = {self.kind}")  # the library refused it

    def _before_check(self, s):
        """What a named class gives the handle besides keys (Rods: its arrays)."""

    def _scene(self):
        """Where the keys are given, for the library's messages (as a scene's file:line)."""
        return f"Surface({self.kind!r})" if self.kind is not None else "Surface()"

    # ---- what the library says of it ----

    def value(self, key):
        """A key's value as parsed ("section.name" or its name), its default when not given:
        a number, an integer, a depth (auto -1, fractal -2), a count or a word's index."""
        row = self._row(key)
        out = ffi.new("double *")
        check(lib.ct_surface_value(self._surface, row.section.encode(), row.name.encode(), out))
        return out[0]

    def _row(self, key):
        if isinstance(key, str):
            for r in self._rows:
                if key in (r.name, f"{r.section}.{r.name}"):
                    return r
        raise invalid(f"{chk._text(key)}: not a key of type = {self.kind} (its keys: "
                      f"{', '.join(r.name for r in self._rows)})")

    def is_set(self, key):
        """True when the key was given."""
        r = self._row(key)
        return bool(lib.ct_surface_is_set(self._surface, r.section.encode(), r.name.encode()))

    def supports(self, output):
        """(True, None), or (False, why) when the kind does not give the output ("ensemble",
        "compare", ...: ct_surface_kind_supports)."""
        why = ffi.new("const char **")
        given = output.encode(errors="replace") if isinstance(output, str) else b""
        ok = lib.ct_surface_kind_supports(lib.ct_surface_kind_index(self._surface),
                                          given.replace(b"\0", b" "), why)
        return (True, None) if ok else (False, _keys._text_of(why[0]))

    @property
    def periodic(self):
        """True when the surface repeats under a curved body (surface.periodic)."""
        return bool(self._body_keys.periodic)

    @property
    def note(self):
        """What the library says of the surface prepared (what was read, levelled, clipped),
        "" when nothing."""
        return ffi.string(lib.ct_surface_note(self._surface)).decode(errors="replace")

    @property
    def layer(self):
        """E, sigma_y, Hstar, l0 and h0 of the rods as built (a Cantor surface's:
        dimensionless; a rod set's in metres when a unit is given)."""
        L = self._scales.layer
        return {k: getattr(L, k) for k in ("E", "sigma_y", "Hstar", "l0", "h0")}

    @property
    def physical(self):
        """E, sigma_y, Hstar, l0 and h0 as given (the units of mass and speed)."""
        L = self._scales.physical
        return {k: getattr(L, k) for k in ("E", "sigma_y", "Hstar", "l0", "h0")}

    def _physical_scales(self):
        L = self._scales.physical
        return L.l0, L.E, L.h0

    def _units(self):
        """What makes the rods' lengths, forces and energies dimensionless: h0, P_Y = sigma_y
        l0 and P_Y h0 of the layer as built (ct_scales)."""
        sc = self._scales
        return {"1": 1.0, "u": sc.layer.h0, "P": sc.force_unit, "W": sc.energy_unit}

    def _depth_word(self):
        """The word of a depth chosen from the speeds (a Cantor surface's "auto" or
        "fractal"), None for a depth given or a kind without one."""
        for r in self._rows:
            if r.type == lib.CT_KEY_DEPTH:
                v = int(self.value(f"{r.section}.{r.name}"))
                if v < 0:
                    return r.words[-1 - v]
        return None

    def _request(self, V, impacts, opts, keep_all, body=None):
        """The ct_build_request (and what it points to, to be kept with it) for speeds V,
        impacts each, options opts, with the body struck (None: the flat strip) on this
        surface (its periodic)."""
        req = ffi.new("ct_build_request *")
        speeds = ffi.from_buffer("double[]", V)
        req.V_star = speeds
        req.nvel = V.size
        req.impacts = impacts
        req.opts = opts
        req.keep_all_rods = 1 if keep_all else 0
        req.threads = self.threads
        req.depth_tolerance = self.depth_tolerance
        struck = _bodies.request(body, self._body_keys)
        req.body = struck
        return req, (speeds, struck)

    def _build(self, V_star, impacts, opts, keep_all=False, body=None, unmet=False):
        """The rods for speeds V_star (impacts each, options opts: a ct_impact_opts) as the
        body (a Body; None: the flat strip) meets them (unmet: as built for it, before it
        meets them: what landings meet at each apex), and what the build found (depth, bound,
        rods, omitted)."""
        V = np.ascontiguousarray(V_star, dtype=np.float64)
        req, kept = self._request(V, impacts, opts, keep_all, body)
        out = ffi.new("ct_bundle **")
        info = ffi.new("ct_plan_info *")
        build = lib.ct_surface_build_unmet if unmet else lib.ct_surface_build
        check(build(self._surface, req, out, info))
        return ffi.gc(out[0], lib.ct_bundle_free), _plan_info(info)

    def __repr__(self):
        keys = ", ".join(f"{k}={v!r}" for k, v in self._given.items())
        return f"Surface({self.kind!r}{', ' if keys else ''}{keys})"


def cantor_params(surface):
    """(physical, dimensionless) ct_params of a Cantor or random Cantor surface, as the kind
    computed them: its ratios and its layer as given and as built (l0 = h0 = sigma_y = 1, H*
    = H, E = E/sigma_y)."""
    fx, fz = surface.value("surface.fx"), surface.value("surface.fz")
    out = []
    for L in (surface._scales.physical, surface._scales.layer):
        out.append(ffi.new("ct_params *", {"fx": fx, "fz": fz, "l0": L.l0, "h0": L.h0,
                                           "Hstar": L.Hstar, "E": L.E, "sigma_y": L.sigma_y}))
    return tuple(out)


class Cantor(Surface):
    """The deterministic Cantor surface (MODEL.md §2), Surface("cantor", ...): f_x, f_z, H =
    H*/h0, E and sigma_y (only E/sigma_y matters), h0 and l0 (scales only). depth: an integer
    N >= 0, "auto" (the smallest depth whose truncation changes forces and energies by less
    than depth_tolerance, relative to the smallest impact asked) or "fractal" (the limit to
    double precision); representation: "stages" (one rod per stage) or "segments" (one per
    piece, depth <= 40, which a curved body needs); periodic: the surface repeats with period
    l0 under a curved body."""

    def __init__(self, fx, fz, H, E, sigma_y=1.0, h0=1.0, l0=1.0, depth="auto",
                 representation="stages", depth_tolerance=1e-12, threads=0, periodic=False):
        self._setup("cantor", dict(fx=fx, fz=fz, H=H, h0=h0, l0=l0, depth=depth,
                                   representation=representation, E=E, sigma_y=sigma_y,
                                   periodic=periodic),
                    threads, depth_tolerance)
        self._physical, self._params = cantor_params(self)
        self.depth = depth
        self.representation = representation

    def _scene(self):
        return "Cantor()"

    @property
    def params(self):
        """The parameters as given (fx, fz, l0, h0, Hstar, E, sigma_y)."""
        p = self._physical[0]
        return {k: getattr(p, k) for k in ("fx", "fz", "l0", "h0", "Hstar", "E", "sigma_y")}

    @property
    def alpha(self):
        """ln fx / ln fz (Eq. 28)."""
        return lib.ct_alpha(self._params)

    @property
    def beta(self):
        """1 / (fx fz) (Eq. 18)."""
        return lib.ct_beta(self._params)

    @property
    def dimension(self):
        """The fractal dimension D (Eq. 3)."""
        return lib.ct_dimension(self._params)

    def _build(self, V_star, impacts, opts, keep_all=False, body=None):
        if not keep_all or not _bodies.is_default(body):
            return super()._build(V_star, impacts, opts, keep_all, body)
        # The whole surface (the load curve's) under the flat strip: the kind's build refuses
        # to keep every rod beyond depth 20, a limit of what = profile, which writes every
        # piece; the curve needs every rod at any depth, planned as the kind plans them
        # (ct_cantor_plan_build) from the kind's own parameters and settings. (A curved body
        # goes through the kind's build, which applies it.)
        V = np.ascontiguousarray(V_star, dtype=np.float64)
        plan = ffi.new("ct_cantor_plan *")
        plan.params = self._params[0]
        plan.depth = int(self.value("surface.depth"))
        plan.representation = int(self.value("surface.representation"))
        plan.depth_tolerance = self.depth_tolerance
        speeds = ffi.from_buffer("double[]", V)
        plan.V_star = speeds
        plan.nvel = V.size
        plan.impacts = impacts
        plan.opts = opts
        plan.keep_all_rods = 1
        plan.threads = self.threads
        out = ffi.new("ct_bundle **")
        info = ffi.new("ct_plan_info *")
        check(lib.ct_cantor_plan_build(plan, out, info))
        return ffi.gc(out[0], lib.ct_bundle_free), _plan_info(info)

    def __repr__(self):
        p = self._params[0]
        return (f"Cantor(fx={p.fx!r}, fz={p.fz!r}, H={p.Hstar!r}, E/sigma_y={p.E!r}, "
                f"depth={self.depth!r}, representation={self.representation!r})")


def random_cantor(surface):
    """The generator settings (ct_random_cantor) and realisation of a random Cantor surface."""
    rc = ffi.new("ct_random_cantor *")
    realisation = ffi.new("uint64_t *")
    check(lib.ct_surface_random_cantor(surface._surface, rc, realisation))
    return rc, int(realisation[0])


class RandomCantor(Surface):
    """A random Cantor surface (MODEL.md §10), Surface("random_cantor", ...): every split
    draws its ratios around fx and fz (distribution "lognormal" or "uniform", spreads
    fx_spread, fz_spread), Philox keyed by (seed, realisation): one realisation is a pure
    function of them. depth: an integer 0 .. 30 (2^(depth+1) - 1 rods). ensemble() runs many
    realisations. periodic: the realisation repeats with period l0 under a curved body."""

    def __init__(self, fx, fz, H, E, depth, sigma_y=1.0, h0=1.0, l0=1.0,
                 distribution="lognormal", fx_spread=0.0, fz_spread=0.0, seed=0, realisation=0,
                 threads=0, periodic=False):
        self._setup("random_cantor", dict(fx=fx, fz=fz, H=H, h0=h0, l0=l0, depth=depth,
                                          distribution=distribution, fx_spread=fx_spread,
                                          fz_spread=fz_spread, seed=seed,
                                          realisation=realisation, E=E, sigma_y=sigma_y,
                                          periodic=periodic),
                    threads)
        self._physical, self._params = cantor_params(self)
        self._rc, _ = random_cantor(self)
        self.distribution = distribution

    @property
    def realisation(self):
        """The realisation this surface is (surface.realisation)."""
        return random_cantor(self)[1]

    def _scene(self):
        return "RandomCantor()"

    params = Cantor.params
    alpha = Cantor.alpha
    beta = Cantor.beta
    dimension = Cantor.dimension

    def _build(self, V_star, impacts, opts, keep_all=False, body=None):
        b, info = super()._build(V_star, impacts, opts, keep_all, body)
        fx, fz, draws = ffi.new("uint64_t *"), ffi.new("uint64_t *"), ffi.new("uint64_t *")
        st = lib.ct_random_cantor_clipped(b, fx, fz, draws)
        if st != lib.CT_OK and not _bodies.is_default(body):
            # the rods a curved body met are the body's (their tops shifted), and the library
            # tells the generator's counts of its own bundle only
            info.update(fx_clipped=None, fz_clipped=None, draws=None)
            return b, info
        check(st)
        info.update(fx_clipped=int(fx[0]), fz_clipped=int(fz[0]), draws=int(draws[0]))
        return b, info

    def __repr__(self):
        rc = self._rc
        return (f"RandomCantor(fx={rc.params.fx!r}, fz={rc.params.fz!r}, H={rc.params.Hstar!r}, "
                f"E/sigma_y={rc.params.E!r}, depth={rc.depth}, "
                f"distribution={self.distribution!r}, fx_spread={rc.fx_spread!r}, "
                f"fz_spread={rc.fz_spread!r}, seed={rc.seed}, realisation={self.realisation})")


def _given(**keys):
    """The keys given (not None)."""
    return {k: v for k, v in keys.items() if v is not None}


class Rods(Surface):
    """Your own surface as rods (MODEL.md §3-4, docs/model.md §12), Surface("rods", ...) with
    the rods as arrays (ct_surface_set_rods) instead of surface.file or surface.rods: top[k]
    is rod k's depth below the reference plane (0 <= top, and top < H* for rods without
    lengths), area[k] its area (> 0), length[k] (optional, > 0) its length (default H* - top),
    in one Winkler layer with E and sigma_y. The layer's thickness: Hstar, or H = H*/h0, or,
    for rods that give their lengths, none of them (H* is then the shallowest rod bottom,
    min(top + length), where the first rod reaches strain 1). l0 and h0 are the reference
    length and depth of the outputs (V*, u/h0, P/P_Y = P/(sigma_y l0)): by default l0 is the
    total area and h0 the deepest top (H* when every top is 0). unit ("m", "mm", "um", "nm"):
    the unit of tops, areas, lengths, Hstar, h0 and l0, converted to metres (default: none,
    the units given). x[k] (and y[k]): where rod k stands, in the unit of the tops, its
    footprint a point (ct_surface_set_rods_at, as a rod file's columns x and y): rods placed by
    x carry a Cylinder, by x and y a Sphere. Computed in those units; every check is the
    kind's. periodic: as every surface's, though rods given by points have no extent to repeat
    (the library refuses it under a curved body)."""

    def __init__(self, top, area, E, Hstar=None, sigma_y=1.0, l0=None, h0=None, H=None,
                 length=None, unit=None, threads=0, x=None, y=None, periodic=False):
        # the arrays' types and shapes here, their values (and every key) the kind's
        top = chk.array("top", top, finite=False)
        area = chk.array("area", area, finite=False)
        if top.size != area.size:
            raise invalid(f"top and area: {top.size} and {area.size} rods: must be as many")
        given = {}
        for name, a in (("length", length), ("x", x), ("y", y)):
            if a is not None:
                given[name] = chk.array(name, a, finite=False)
                if given[name].size != top.size:
                    raise invalid(f"top and {name}: {top.size} and {given[name].size} rods: "
                                  "must be as many")
        self.top, self.area, self.length, self.unit = top, area, given.get("length"), unit
        self.x, self.y = given.get("x"), given.get("y")
        self._setup("rods", _given(unit=unit, Hstar=Hstar, H=H, h0=h0, l0=l0, E=E,
                                   sigma_y=sigma_y, periodic=periodic), threads)

    def _before_check(self, s):
        def at(a):
            return ffi.NULL if a is None else ffi.from_buffer("double[]", a)

        check(lib.ct_surface_set_rods_at(s, self.top.size, at(self.top), at(self.area),
                                         at(self.length), at(self.x), at(self.y)))

    def _scene(self):
        return "Rods()"

    def __repr__(self):
        L = self._scales.physical  # as given (the layer as built may be in other units)
        return (f"Rods({self.top.size} rods, E={L.E!r}, sigma_y={L.sigma_y!r}, "
                f"Hstar={L.Hstar!r}, l0={L.l0!r}, h0={L.h0!r})")


def _band(name, band):
    """A fit's band (lo, hi) as two doubles ((0, 0): the default); the library judges it."""
    if band is None:
        return 0.0, 0.0
    try:
        lo, hi = band
    except (TypeError, ValueError):
        raise invalid(f"{name} = {band!r}: must be None or a pair (lo, hi)") from None
    return chk._double(f"{name}[0]", lo), chk._double(f"{name}[1]", hi)


def _line(f):
    return {"lo": f.lo, "hi": f.hi, "points": int(f.n), "slope": f.slope,
            "intercept": f.intercept, "r2": f.r2, "rms_residual_ln": f.residual}


class Profile(Surface):
    """A measured surface (MODEL.md §9) as one rod per sample: a file, Surface("profile", ...)
    as `surface.type = profile` of the cantact program reads it (text/CSV, a Dektak export,
    X3P; lengths converted to metres: `unit` (or x_unit, z_unit) "m", "mm", "um", "nm",
    default what the file's column names state; `spacing` for a file of one column of
    heights, in its x unit), or arrays: `z` 1-D with `x` (increasing) or `dx`, or `z` 2-D
    (rows along x, z[j, i] at x = i dx, y = j dy; NaN: invalid) with `dx` and `dy`, in
    lengths of your choice (E and sigma_y in matching units). Levelled by `detrend` ("none",
    "mean", "linear", "quadratic"), optionally trimmed (`trim` = k: heights above mean + k Rq
    cut there: surface.trim = rq, trim_k = k), in a layer of thickness `H` times Rt or `Hstar`
    (in the unit of the heights as given: the file's z unit, or the arrays'). Its h0 is Rt and
    its l0 the length (a grid: the area), so mass and speed give V* = v sqrt(m / (2 l0 E h0))
    with m per unit depth (a grid: the mass). Computed in metres (a file) or the arrays'
    units; results dimensionless by h0, sigma_y and l0 as for Rods. Every key and its check is
    the kind's; arrays, which the kind does not take, are levelled, trimmed and made rods by
    the same library calls its preparation makes. A line carries a Cylinder, a grid (an X3P
    map) a Sphere; periodic: the profile or map repeats as measured under a curved body. A
    curved body meets a profile read from a file (the kind's build applies it); heights given
    as arrays are made rods outside the kind's build, which no body reaches: they carry the
    flat strip only."""

    def __init__(self, file=None, *, E, sigma_y, H=None, Hstar=None, x=None, z=None, dx=None,
                 dy=None, unit=None, x_unit=None, z_unit=None, spacing=None, detrend="linear",
                 trim=None, threads=0, periodic=False):
        keys = _given(H=H, Hstar=Hstar, detrend=detrend, E=E, sigma_y=sigma_y,
                      periodic=periodic)
        if trim is not None:
            keys.update(trim="rq", trim_k=trim)
        self.detrend = detrend
        if file is not None:
            if z is not None or x is not None or dx is not None or dy is not None:
                raise invalid("file, or x/z/dx/dy arrays: give one of them")
            keys.update(_given(file=file, unit=unit, x_unit=x_unit, z_unit=z_unit,
                               spacing=spacing))
            self._setup("profile", keys, threads, names={"trim_k": "trim"})
            p = ffi.new("const ct_profile **")
            check(lib.ct_surface_profile(self._surface, p, ffi.NULL))
            self._profile = p[0]
            self._bundle = None
            m = re.search(r", (\d+) heights clipped at mean", self.note)
            self.clipped = int(m.group(1)) if m else 0
        else:
            self._from_arrays(keys, threads, x, z, dx, dy, unit, x_unit, z_unit, spacing)
        st = ffi.new("ct_profile_stats *")
        check(lib.ct_profile_stats_of(self._profile, st))
        self.stats = {k: getattr(st, k) for k in ("mean", "Ra", "Rq", "Rt", "length")}

    def _scene(self):
        return "Profile()"

    def _from_arrays(self, keys, threads, x, z, dx, dy, unit, x_unit, z_unit, spacing):
        """A profile of arrays: the keys set and checked by the kind (its surface.file, which
        the kind requires and never reads here, stands for the arrays), then the profile made,
        levelled, trimmed and made rods as the kind's preparation makes them."""
        if z is None:
            raise invalid("a profile needs a file or heights z")
        if unit is not None or x_unit is not None or z_unit is not None or spacing is not None:
            raise invalid("unit, x_unit, z_unit, spacing: for files only (arrays are read "
                          "in their own units)")
        # a line: finite heights; a grid (rows along x): NaN marks an invalid point
        zz = chk.real_array("z", z, ndims=(1, 2), nan_ndims=(2,))
        out = ffi.new("ct_profile **")
        if zz.ndim == 1:
            if dy is not None:
                raise invalid("a line profile z (1-D): dy is for a grid (2-D z)")
            if (x is None) == (dx is None):
                raise invalid("a line profile z: give x (positions) or dx (spacing), "
                              + ("not both" if x is not None else "one of them"))
            if x is not None:
                xx = chk.real_array("x", x, ndims=(1,))
                if xx.shape != zz.shape:
                    raise invalid(f"x and z: {xx.size} and {zz.size} points: must be as many")
                down = np.flatnonzero(np.diff(xx) <= 0)
                if down.size:
                    k = int(down[0]) + 1
                    raise invalid(f"x[{k}] = {xx[k]!r}: not increasing: must be > "
                                  f"x[{k - 1}] = {xx[k - 1]!r}")
                line = (xx, 0.0)
            else:
                line = (None, chk.real("dx", dx, 0.0))
        else:
            if x is not None:
                raise invalid("a grid z (2-D): x is for a line profile; give dx and dy")
            if dx is None or dy is None:
                raise invalid("a grid z (2-D): give dx and dy (missing: "
                              + " and ".join(n for n, v in (("dx", dx), ("dy", dy)) if v is None)
                              + ")")
            grid = (chk.real("dx", dx, 0.0), chk.real("dy", dy, 0.0))
        keys["file"] = "arrays"
        self._setup("profile", keys, threads, prepare=False, names={"trim_k": "trim"})
        if zz.ndim == 1:
            xx, step = line
            at = ffi.NULL if xx is None else ffi.from_buffer("double[]", xx)
            check(lib.ct_profile_from_line(out, zz.size, at, step,
                                           ffi.from_buffer("double[]", zz)))
        else:
            check(lib.ct_profile_from_grid(out, zz.shape[1], zz.shape[0], grid[0], grid[1],
                                           ffi.from_buffer("double[]", zz)))
        self._profile = ffi.gc(out[0], lib.ct_profile_free)
        check(lib.ct_profile_level(self._profile, int(self.value("surface.detrend"))))
        self.clipped = 0
        trim_k = self.value("surface.trim_k")  # 0 without surface.trim = rq
        if trim_k > 0.0:
            clipped = ffi.new("size_t *")
            check(lib.ct_profile_trim(self._profile, trim_k, clipped))
            self.clipped = int(clipped[0])
        st = ffi.new("ct_profile_stats *")
        check(lib.ct_profile_stats_of(self._profile, st))
        hs = self.value("surface.H") * st.Rt if self.is_set("H") else self.value("surface.Hstar")
        b = ffi.new("ct_bundle **")
        check(lib.ct_profile_bundle(b, self._profile, self.value("material.E"),
                                    self.value("material.sigma_y"), hs))
        self._bundle = ffi.gc(b[0], lib.ct_bundle_free)
        lib.ct_bundle_set_threads(self._bundle, self.threads)

    def _layer(self):
        """The rods' layer (const ct_layer *)."""
        if self._bundle is not None:
            return lib.ct_bundle_layer(self._bundle)
        return ffi.addressof(self._scales[0], "layer")

    @property
    def layer(self):
        """E, sigma_y, Hstar, l0 (the length or area) and h0 (= Rt) of the rods."""
        L = self._layer()
        return {k: getattr(L, k) for k in ("E", "sigma_y", "Hstar", "l0", "h0")}

    @property
    def physical(self):
        """The layer as given: a profile's is the layer as built."""
        return self.layer

    @property
    def source(self):
        """What was read: "text", "dektak", "x3p", or "arrays"."""
        return ffi.string(self._profile.source).decode("utf-8", "replace")

    @property
    def invalid(self):
        """Grid points left out (the X3P mask, or NaN)."""
        return int(self._profile.invalid)

    @property
    def heights(self):
        """The heights after levelling (a copy): 1-D for a line, (ny, nx) for a grid."""
        p = self._profile
        n = p.nx * p.ny
        z = np.frombuffer(ffi.buffer(p.z, n * 8), dtype=np.float64).copy()
        return z if p.ny == 1 else z.reshape(p.ny, p.nx)

    def bearing(self, d):
        """phi(d): the fraction of the area whose top lies within depth d of the highest point
        (d ascending, in the profile's length unit)."""
        d = chk.array("d", d, nonnegative=True)
        if (np.diff(d) < 0).any():
            raise invalid("d: must be ascending")
        phi = np.empty_like(d)
        check(lib.ct_profile_bearing(self._profile, d.size, ffi.from_buffer("double[]", d),
                                     ffi.from_buffer("double[]", phi)))
        return phi

    def _own_rows(self, name, result):
        """result, checked to be a Restitution of this profile."""
        if not isinstance(result, Restitution):
            raise invalid(f"{name}: must be a Restitution (cantact.restitution of this "
                          f"profile), got {type(result).__name__}")
        if result._surface is not self:
            raise invalid(f"{name}: a Restitution of another surface: give "
                          "cantact.restitution(this profile, ...)")
        return result

    def _fit_of(self, dimension, depths, lags, on_reach):
        """The ct_profile_fit as `cantact run` makes it: on the bands given (default: the
        defaults), then, with no depth band given and a Restitution on_reach, the bearing fit
        redone on the depths its impacts reached (ct_profile_fit_on_reach on the u_max of
        every impact that ran; the first fit kept when that band holds none). Returns the fit,
        which band its bearing fit is on ("given", "impacts", "default") and the library's
        reason when the refit was not made ("" otherwise)."""
        f = ffi.new("ct_profile_fit *")
        f.dimension = _keys.parse(self._row("fit.dimension"), dimension, "dimension",
                                  self._scene())
        d_lo, d_hi = _band("depths", depths)
        t_lo, t_hi = _band("lags", lags)
        check(lib.ct_profile_fit_of(self._profile, d_lo, d_hi, t_lo, t_hi, f))
        if depths is not None:
            return f, "given", ""
        if on_reach is None:
            return f, "default", ""
        u = np.ascontiguousarray(on_reach._u_max.ravel(), dtype=np.float64)
        g = ffi.new("ct_profile_fit *")
        st = lib.ct_profile_fit_on_reach(self._profile, f, ffi.from_buffer("double[]", u),
                                         u.size, g)
        if st == lib.CT_ENOMEM:
            check(st)
        if st != lib.CT_OK:
            return f, "default", ffi.string(lib.ct_error_message()).decode(errors="replace")
        return g, "impacts", ""

    def fit(self, dimension="variation", depths=None, lags=None, on_reach=None):
        """The Cantor surface the profile looks like (as `cantact fit`): alpha and h0 from the
        bearing curve on `depths` (lo, hi) (default: the 20th highest point to phi = 0.1), D
        three ways on `lags` (lo, hi) (default: 2 spacings to a tenth of the length), the one
        `dimension` names in Eq. 3, then fx, fz and l0. on_reach: a Restitution of this
        profile: the bearing fit redone on the depths its impacts reached, as `cantact run`
        does for compare and bearing (ct_profile_fit_on_reach; the default band kept when
        those depths hold no fit); not with depths. A dict; the fits' bands, point counts, r2
        and rms residuals under "bearing", "variation", "structure", "spectrum"; "band" says
        which depths the bearing fit is on ("given", "impacts" or "default") and "note" why a
        refit on the impacts' depths was not made ("" when it was, or not asked)."""
        if on_reach is not None:
            self._own_rows("on_reach", on_reach)
            if depths is not None:
                raise invalid("depths and on_reach: give one (the depths of the bearing fit, or "
                              "the impacts whose depths set them)")
        f, band, note = self._fit_of(dimension, depths, lags, on_reach)
        r = {k: getattr(f, k) for k in ("alpha", "h0", "D_variation", "D_structure",
                                         "D_spectrum", "D", "fx", "fz", "l0")}
        r["dimension"] = dimension
        for k in ("bearing", "variation", "structure", "spectrum"):
            r[k] = _line(getattr(f, k))
        r.update({k: getattr(f.stats, k) for k in ("Rq", "Ra", "Rt")})
        for k, v in list(r.items()):  # a fit that succeeded: every figure a number
            for name, x in (v.items() if isinstance(v, dict) else ((None, v),)):
                if isinstance(x, float):
                    chk.finite_result(k if name is None else f"{k}.{name}", x)
        r["band"] = band
        r["note"] = note
        return r

    def compare(self, result, dimension="variation", depths=None, lags=None):
        """The fitted Cantor surface beside the profile, as `cantact run` writes what =
        compare: for every first impact of result (cantact.restitution of this profile), e of
        the fitted surface's exact rods at its fractal depth (e_cantor_fit), e of the
        asymptotic law with the fitted parameters (e_asymptotic_fit) and the fitted surface's
        V* (V_star_cantor_fit), at the impact's kinetic energy (ct_profile_fitted_e). The fit:
        ct_profile_fit_of on the bands given (dimension, depths, lags as in fit()), then, with
        no depths given, redone on the depths result's impacts reached (fit(on_reach=result)).
        A dict of arrays shaped like result.e: NaN after the first impact, where a row failed
        and where the law does not apply. Raises the library's error (e.g. OutsideModel)
        when the fitted surface leaves the model's ranges."""
        result = self._own_rows("result", result)
        f, _, _ = self._fit_of(dimension, depths, lags, result)
        shape = result.e.shape
        W = np.ascontiguousarray(result.kinetic_energy, dtype=np.float64).copy()
        W[:, 1:] = np.nan  # the first impact on the virgin surface only
        W = W.ravel()
        out = {k: np.full(W.size, np.nan) for k in ("e_cantor_fit", "e_asymptotic_fit",
                                                      "V_star_cantor_fit")}
        check(lib.ct_profile_fitted_e(
            self._profile, f, self._layer(), ffi.from_buffer("double[]", W),
            W.size, self.threads, ffi.from_buffer("double[]", out["e_cantor_fit"]),
            ffi.from_buffer("double[]", out["e_asymptotic_fit"]),
            ffi.from_buffer("double[]", out["V_star_cantor_fit"])))
        for k, v in out.items():  # NaN: not computed (see above); inf never a result
            chk.finite_result(k, v, may_be_nan=True)
        return {k: v.reshape(shape) for k, v in out.items()}

    def _physical_scales(self):
        L = self._layer()
        return L.l0, L.E, L.h0

    def _units(self):
        if self._bundle is None:
            return super()._units()
        # arrays, which the kind does not prepare: its ct_scales' units of the same layer
        L = self._layer()
        PY = L.sigma_y * L.l0
        return {"1": 1.0, "u": L.h0, "P": PY, "W": PY * L.h0}

    def _build(self, V_star, impacts, opts, keep_all=False, body=None):
        if self._bundle is None:
            return super()._build(V_star, impacts, opts, keep_all, body)
        if not _bodies.is_default(body):
            raise invalid(f"body = {body!r}: a Profile of arrays is made rods outside the "
                          "kind's build (ct_surface_build reads its heights from a file), "
                          "where no body meets them: give the heights as a file for a curved "
                          "body")
        return self._bundle, _info(self._bundle)

    def __repr__(self):
        p, L = self._profile, self._layer()
        shape = f"{p.nx} points" if p.ny == 1 else f"{p.nx} x {p.ny} grid"
        return (f"Profile({self.source}, {shape}, {int(p.n)} rods, Rt={L.h0!r}, "
                f"E={L.E!r}, sigma_y={L.sigma_y!r}, Hstar={L.Hstar!r})")


def surface_of(name, value):
    """value, checked to be a surface."""
    if not isinstance(value, Surface):
        raise invalid(f"{name}: must be a cantact surface (Surface, Cantor, RandomCantor, Rods "
                      f"or Profile), got {type(value).__name__}")
    return value
