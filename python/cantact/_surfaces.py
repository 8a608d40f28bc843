"""Surfaces: each describes itself and builds its rods (a bundle) for the speeds asked.

A Cantor or random Cantor surface is computed in dimensionless form, as the cantact program
does (l0 = h0 = sigma_y = 1, H* = H, E = E/sigma_y): the model depends on its dimensionless
groups alone, and the results (u/h0, P/P_Y, V*) are the same bits as `cantact run`'s. A rod set
(Rods) is the library's kind `rods` (ct_surface_*: its keys, defaults and checks are the
program's `surface.type = rods`), computed in the units given; its results are made
dimensionless by its h0, sigma_y and l0. A new kind of surface is a class with the same four
members: kind, _params (or None), _physical_scales() (l0, E, h0 as given: V* from mass and
speed), _build()."""
import numpy as np

from . import _check as chk
from ._errors import check, invalid
from ._ffi import (CT_DEPTH_AUTO, CT_DEPTH_FRACTAL, CT_MAX_RANDOM_DEPTH,
                   CT_MAX_SEGMENTS_DEPTH, CT_MAX_STAGES_DEPTH, CT_MAX_THREADS, ffi, lib)

REPRESENTATIONS = {"stages": lib.CT_REP_STAGES, "segments": lib.CT_REP_SEGMENTS}
DISTRIBUTIONS = {"lognormal": lib.CT_RATIO_LOGNORMAL, "uniform": lib.CT_RATIO_UNIFORM}


def _cantor_params(fx, fz, H, E, sigma_y, h0, l0):
    """(physical, dimensionless) ct_params, validated, computed as the CLI computes them."""
    fx = chk.real("fx", fx, 1.0)
    fz = chk.real("fz", fz, 1.0, 2.0)
    H = chk.real("H", H, 1.0)
    E = chk.real("E", E, 0.0)
    sigma_y = chk.real("sigma_y", sigma_y, 0.0)
    h0 = chk.real("h0", h0, 0.0)
    l0 = chk.real("l0", l0, 0.0)
    if not E > sigma_y:
        raise invalid(f"E = {E!r}: must be > sigma_y = {sigma_y!r} (yield strain < 1)")
    physical = ffi.new("ct_params *", {"fx": fx, "fz": fz, "l0": l0, "h0": h0,
                                       "Hstar": H * h0, "E": E, "sigma_y": sigma_y})
    check(lib.ct_params_validate(physical))
    p = physical[0]
    dimensionless = ffi.new("ct_params *", {"fx": fx, "fz": fz, "l0": 1.0, "h0": 1.0,
                                            "Hstar": p.Hstar / p.h0, "E": p.E / p.sigma_y,
                                            "sigma_y": 1.0})
    check(lib.ct_params_validate(dimensionless))  # E/sigma_y times H may overflow
    return physical, dimensionless


def _threads(threads):
    return chk.integer("threads", threads, 0, CT_MAX_THREADS)


def _info(b, depth=-1, bound=0.0):
    return {"depth": int(depth), "bound": float(bound), "rods": int(lib.ct_bundle_size(b)),
            "omitted": int(lib.ct_bundle_omitted(b))}


class Cantor:
    """The deterministic Cantor surface (MODEL.md §2): f_x, f_z, H = H*/h0, E and sigma_y
    (only E/sigma_y matters), h0 and l0 (scales only). depth: an integer N >= 0, "auto" (the
    smallest depth whose truncation changes forces and energies by less than depth_tolerance,
    relative to the smallest impact asked) or "fractal" (the limit to double precision);
    representation: "stages" (one rod per stage) or "segments" (one per piece, depth <= 40)."""

    kind = "cantor"

    def __init__(self, fx, fz, H, E, sigma_y=1.0, h0=1.0, l0=1.0, depth="auto",
                 representation="stages", depth_tolerance=1e-12, threads=0):
        self._physical, self._params = _cantor_params(fx, fz, H, E, sigma_y, h0, l0)
        if isinstance(depth, str):
            self._depth = chk.choice("depth", depth, {"auto": CT_DEPTH_AUTO,
                                                      "fractal": CT_DEPTH_FRACTAL})
        else:
            self._depth = chk.integer("depth", depth, 0, CT_MAX_STAGES_DEPTH)
        self._rep = chk.choice("representation", representation, REPRESENTATIONS)
        if self._rep == lib.CT_REP_SEGMENTS and not 0 <= self._depth <= CT_MAX_SEGMENTS_DEPTH:
            raise invalid(f"representation = 'segments': needs an integer depth 0 .. "
                          f"{CT_MAX_SEGMENTS_DEPTH}, got {depth!r}")
        self.depth_tolerance = chk.real("depth_tolerance", depth_tolerance, 0.0, 1e-2)
        self.threads = _threads(threads)
        self.depth = depth
        self.representation = representation

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

    def _physical_scales(self):
        p = self._physical[0]
        return p.l0, p.E, p.h0

    def _build(self, V_star, impacts, opts, keep_all=False):
        V = np.ascontiguousarray(V_star, dtype=np.float64)
        plan = ffi.new("ct_cantor_plan *")
        plan.params = self._params[0]
        plan.depth = self._depth
        plan.representation = self._rep
        plan.depth_tolerance = self.depth_tolerance
        speeds = ffi.from_buffer("double[]", V)
        plan.V_star = speeds
        plan.nvel = V.size
        plan.impacts = impacts
        plan.opts = opts[0]
        plan.keep_all_rods = 1 if keep_all else 0
        plan.threads = self.threads
        out = ffi.new("ct_bundle **")
        info = ffi.new("ct_plan_info *")
        check(lib.ct_cantor_plan_build(plan, out, info))
        b = ffi.gc(out[0], lib.ct_bundle_free)
        return b, {"depth": int(info.depth), "bound": float(info.bound), "rods": int(info.rods),
                   "omitted": int(info.omitted)}

    def __repr__(self):
        p = self._params[0]
        return (f"Cantor(fx={p.fx!r}, fz={p.fz!r}, H={p.Hstar!r}, E/sigma_y={p.E!r}, "
                f"depth={self.depth!r}, representation={self.representation!r})")


class RandomCantor:
    """A random Cantor surface (MODEL.md §10): every split draws its ratios around fx and fz
    (distribution "lognormal" or "uniform", spreads fx_spread, fz_spread), Philox keyed by
    (seed, realisation): one realisation is a pure function of them. depth: an integer
    0 .. 30 (2^(depth+1) - 1 rods). ensemble() runs many realisations."""

    kind = "random_cantor"

    def __init__(self, fx, fz, H, E, depth, sigma_y=1.0, h0=1.0, l0=1.0,
                 distribution="lognormal", fx_spread=0.0, fz_spread=0.0, seed=0, realisation=0,
                 threads=0):
        self._physical, self._params = _cantor_params(fx, fz, H, E, sigma_y, h0, l0)
        self._rc = ffi.new("ct_random_cantor *")
        self._rc.params = self._params[0]
        self._rc.dist = chk.choice("distribution", distribution, DISTRIBUTIONS)
        self._rc.fx_spread = chk.real("fx_spread", fx_spread, 0.0, lo_closed=True)
        self._rc.fz_spread = chk.real("fz_spread", fz_spread, 0.0, lo_closed=True)
        self._rc.depth = chk.integer("depth", depth, 0, CT_MAX_RANDOM_DEPTH)
        self._rc.seed = chk.integer("seed", seed, 0, 2**64 - 1)
        check(lib.ct_random_cantor_validate(self._rc))
        self.realisation = chk.integer("realisation", realisation, 0, 2**64 - 1)
        self.threads = _threads(threads)
        self.distribution = distribution

    params = Cantor.params
    alpha = Cantor.alpha
    beta = Cantor.beta
    dimension = Cantor.dimension

    def _physical_scales(self):
        p = self._physical[0]
        return p.l0, p.E, p.h0

    def _build(self, V_star, impacts, opts, keep_all=False):
        out = ffi.new("ct_bundle **")
        check(lib.ct_random_cantor_bundle(out, self._rc, self.realisation, self.threads))
        b = ffi.gc(out[0], lib.ct_bundle_free)
        fx, fz, draws = ffi.new("uint64_t *"), ffi.new("uint64_t *"), ffi.new("uint64_t *")
        check(lib.ct_random_cantor_clipped(b, fx, fz, draws))
        info = _info(b, self._rc.depth)
        info.update(fx_clipped=int(fx[0]), fz_clipped=int(fz[0]), draws=int(draws[0]))
        return b, info

    def __repr__(self):
        rc = self._rc
        return (f"RandomCantor(fx={rc.params.fx!r}, fz={rc.params.fz!r}, H={rc.params.Hstar!r}, "
                f"E/sigma_y={rc.params.E!r}, depth={rc.depth}, "
                f"distribution={self.distribution!r}, fx_spread={rc.fx_spread!r}, "
                f"fz_spread={rc.fz_spread!r}, seed={rc.seed}, realisation={self.realisation})")


ROD_UNITS = ("m", "mm", "um", "nm")


def _optional(name, value, lo, lo_closed=False):
    return None if value is None else chk.real(name, value, lo, lo_closed=lo_closed)


class Rods:
    """Your own surface as rods (MODEL.md §3-4, docs/model.md §12), the library's kind `rods`
    (as `surface.type = rods` of the cantact program): top[k] is rod k's depth below the
    reference plane (0 <= top, and top < H* for rods without lengths), area[k] its area (> 0),
    length[k] (optional, > 0) its length (default H* - top), in one Winkler layer with E and
    sigma_y. The layer's thickness:
    Hstar, or H = H*/h0, or, for rods that give their lengths, none of them (H* is then the
    shallowest rod bottom, min(top + length), where the first rod reaches strain 1). l0 and h0
    are the reference length and depth of the outputs (V*, u/h0, P/P_Y = P/(sigma_y l0)):
    by default l0 is the total area and h0 the deepest top (H* when every top is 0). unit
    ("m", "mm", "um", "nm"): the unit of tops, areas, lengths, Hstar, h0 and l0, converted to
    metres (default: none, the units given). Computed in those units."""

    kind = "rods"
    _params = None

    def __init__(self, top, area, E, Hstar=None, sigma_y=1.0, l0=None, h0=None, H=None,
                 length=None, unit=None, threads=0):
        # every argument checked before the library sees any of them
        top = chk.array("top", top, nonnegative=True)
        area = chk.array("area", area, positive=True)
        if top.size != area.size:
            raise invalid(f"top and area: {top.size} and {area.size} rods: must be as many")
        if length is not None:
            length = chk.array("length", length, positive=True)
            if length.size != top.size:
                raise invalid(f"top and length: {top.size} and {length.size} rods: must be as "
                              "many")
        E = chk.real("E", E, 0.0)
        sigma_y = chk.real("sigma_y", sigma_y, 0.0)
        if not E > sigma_y:
            raise invalid(f"E = {E!r}: must be > sigma_y = {sigma_y!r} (yield strain < 1)")
        Hstar = _optional("Hstar", Hstar, 0.0)
        H = _optional("H", H, 1.0)
        h0 = _optional("h0", h0, 0.0)
        l0 = _optional("l0", l0, 0.0)
        if unit is not None:
            chk.choice("unit", unit, dict.fromkeys(ROD_UNITS))
        if Hstar is not None and H is not None:
            raise invalid("H (a multiple of h0) or Hstar (a length): give one, not both")
        if length is not None and (Hstar is not None or H is not None):
            raise invalid(f"{'Hstar' if Hstar is not None else 'H'}: not with rods that give "
                          "their lengths (H* is where the first of them reaches strain 1)")
        if length is None and Hstar is None and H is None:
            raise invalid("Hstar or H (or a length for every rod): give one")
        if Hstar is not None and (top >= Hstar).any():
            k = int(np.flatnonzero(top >= Hstar)[0])
            raise invalid(f"top[{k}] = {top[k]!r}: must be < Hstar = {Hstar!r}")
        self.threads = _threads(threads)
        out = ffi.new("ct_surface **")
        check(lib.ct_surface_new(out, b"rods"))
        s = ffi.gc(out[0], lib.ct_surface_free)
        where = b"Rods()"
        check(lib.ct_surface_set_rods(
            s, top.size, ffi.from_buffer("double[]", top), ffi.from_buffer("double[]", area),
            ffi.NULL if length is None else ffi.from_buffer("double[]", length)))
        for key, value in (("Hstar", Hstar), ("H", H), ("h0", h0), ("l0", l0)):
            if value is not None:
                check(lib.ct_surface_set(s, b"surface", key.encode(),
                                         repr(float(value)).encode(), where))
        if unit is not None:
            check(lib.ct_surface_set(s, b"surface", b"unit", unit.encode(), where))
        for key, value in (("E", E), ("sigma_y", sigma_y)):
            check(lib.ct_surface_set(s, b"material", key.encode(),
                                     repr(float(value)).encode(), where))
        check(lib.ct_surface_check(s, where))
        check(lib.ct_surface_prepare(s, ffi.NULL))
        self._surface = s
        self._scales = ffi.new("ct_scales *")
        lib.ct_surface_scales(s, self._scales)
        self.top, self.area, self.length, self.unit = top, area, length, unit

    @property
    def layer(self):
        """E, sigma_y, Hstar, l0 and h0 of the rods as built (in metres when a unit is given)."""
        L = self._scales.layer
        return {k: getattr(L, k) for k in ("E", "sigma_y", "Hstar", "l0", "h0")}

    def _physical_scales(self):
        L = self._scales.physical
        return L.l0, L.E, L.h0

    def _build(self, V_star, impacts, opts, keep_all=False):
        V = np.ascontiguousarray(V_star, dtype=np.float64)
        req = ffi.new("ct_build_request *")
        speeds = ffi.from_buffer("double[]", V)
        req.V_star = speeds
        req.nvel = V.size
        req.impacts = impacts
        req.opts = opts[0]
        req.keep_all_rods = 1 if keep_all else 0
        req.threads = self.threads
        req.depth_tolerance = 1e-12
        out = ffi.new("ct_bundle **")
        info = ffi.new("ct_plan_info *")
        check(lib.ct_surface_build(self._surface, req, out, info))
        b = ffi.gc(out[0], lib.ct_bundle_free)
        return b, _info(b)

    def __repr__(self):
        L = self._scales.layer
        return (f"Rods({self.top.size} rods, E={L.E!r}, sigma_y={L.sigma_y!r}, "
                f"Hstar={L.Hstar!r}, l0={L.l0!r}, h0={L.h0!r})")


DETRENDS = {"none": lib.CT_DETREND_NONE, "mean": lib.CT_DETREND_MEAN,
            "linear": lib.CT_DETREND_LINEAR, "quadratic": lib.CT_DETREND_QUADRATIC}
UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "nm": 1e-9}
DIMENSIONS = {"variation": lib.CT_DIM_VARIATION, "structure": lib.CT_DIM_STRUCTURE,
              "spectrum": lib.CT_DIM_SPECTRUM}


def _band(name, band):
    if band is None:
        return 0.0, 0.0
    try:
        lo, hi = band
    except (TypeError, ValueError):
        raise invalid(f"{name} = {band!r}: must be None or a pair (lo, hi)") from None
    lo, hi = chk.real(f"{name}[0]", lo, 0.0), chk.real(f"{name}[1]", hi, 0.0)
    if not hi > lo:
        raise invalid(f"{name} = ({lo!r}, {hi!r}): must have lo < hi")
    return lo, hi


def _line(f):
    return {"lo": f.lo, "hi": f.hi, "points": int(f.n), "slope": f.slope,
            "intercept": f.intercept, "r2": f.r2, "rms_residual_ln": f.residual}


class Profile:
    """A measured surface (MODEL.md §9) as one rod per sample, as `surface.type = profile` of
    the cantact program: a line profile or an X3P grid read from `file` (text/CSV, a Dektak
    export, X3P; lengths converted to metres: `unit` (or x_unit, z_unit) "m", "mm", "um",
    "nm", default what the file's column names state; `spacing` for a file of one column of
    heights, in its x unit), or arrays: `z` 1-D with `x` (increasing) or `dx`, or `z` 2-D
    (rows along x, z[j, i] at x = i dx, y = j dy; NaN: invalid) with `dx` and `dy`, in
    lengths of your choice (E and sigma_y in matching units). Levelled by `detrend` ("none",
    "mean", "linear", "quadratic"), optionally trimmed (`trim` = k: heights above mean + k Rq
    cut there), in a layer of thickness `H` times Rt or `Hstar`. Its h0 is Rt and its l0 the
    length (a grid: the area), so mass and speed give V* = v sqrt(m / (2 l0 E h0)) with m per
    unit depth (a grid: the mass). Computed in the units given; results dimensionless by h0,
    sigma_y and l0 as for Rods."""

    kind = "profile"
    _params = None

    def __init__(self, file=None, *, E, sigma_y, H=None, Hstar=None, x=None, z=None, dx=None,
                 dy=None, unit=None, x_unit=None, z_unit=None, spacing=None, detrend="linear",
                 trim=None, threads=0):
        # every argument checked before the library sees any of them
        E = chk.real("E", E, 0.0)
        sigma_y = chk.real("sigma_y", sigma_y, 0.0)
        how = chk.choice("detrend", detrend, DETRENDS)
        if (H is None) == (Hstar is None):
            raise invalid("H (a multiple of Rt) or Hstar (a length): give exactly one")
        H = None if H is None else chk.real("H", H, 1.0)
        Hstar = None if Hstar is None else chk.real("Hstar", Hstar, 0.0)
        trim = None if trim is None else chk.real("trim", trim, 0.0)
        threads = _threads(threads)
        out = ffi.new("ct_profile **")
        if file is not None:
            path = chk.path("file", file)
            if z is not None or x is not None or dx is not None or dy is not None:
                raise invalid("file, or x/z/dx/dy arrays: give one of them")
            if unit is not None and (x_unit is not None or z_unit is not None):
                raise invalid("unit, or x_unit and z_unit: give one of them")
            opts = ffi.new("ct_profile_read_opts *")
            opts.x_unit = chk.choice("x_unit", x_unit or unit, UNITS) if (x_unit or unit) else 0.0
            opts.z_unit = chk.choice("z_unit", z_unit or unit, UNITS) if (z_unit or unit) else 0.0
            opts.dx = 0.0 if spacing is None else chk.real("spacing", spacing, 0.0)
            check(lib.ct_profile_read(path, opts, out))
        else:
            if z is None:
                raise invalid("a profile needs a file or heights z")
            if unit is not None or x_unit is not None or z_unit is not None or spacing is not None:
                raise invalid("unit, x_unit, z_unit, spacing: for files only (arrays are read "
                              "in their own units)")
            # a line: finite heights; a grid (rows along x): NaN marks an invalid point
            zz = chk.real_array("z", z, ndims=(1, 2), nan_ndims=(2,))
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
                    check(lib.ct_profile_from_line(out, zz.size, ffi.from_buffer("double[]", xx),
                                                   0.0, ffi.from_buffer("double[]", zz)))
                else:
                    check(lib.ct_profile_from_line(out, zz.size, ffi.NULL,
                                                   chk.real("dx", dx, 0.0),
                                                   ffi.from_buffer("double[]", zz)))
            else:
                if x is not None:
                    raise invalid("a grid z (2-D): x is for a line profile; give dx and dy")
                if dx is None or dy is None:
                    raise invalid("a grid z (2-D): give dx and dy (missing: "
                                  + " and ".join(n for n, v in (("dx", dx), ("dy", dy)) if v is None)
                                  + ")")
                check(lib.ct_profile_from_grid(out, zz.shape[1], zz.shape[0],
                                               chk.real("dx", dx, 0.0), chk.real("dy", dy, 0.0),
                                               ffi.from_buffer("double[]", zz)))
        self._profile = ffi.gc(out[0], lib.ct_profile_free)
        check(lib.ct_profile_level(self._profile, how))
        self.clipped = 0
        if trim is not None:
            clipped = ffi.new("size_t *")
            check(lib.ct_profile_trim(self._profile, trim, clipped))
            self.clipped = int(clipped[0])
        st = ffi.new("ct_profile_stats *")
        check(lib.ct_profile_stats_of(self._profile, st))
        self.stats = {k: getattr(st, k) for k in ("mean", "Ra", "Rq", "Rt", "length")}
        hs = H * st.Rt if H is not None else Hstar
        b = ffi.new("ct_bundle **")
        check(lib.ct_profile_bundle(b, self._profile, E, sigma_y, hs))
        self._bundle = ffi.gc(b[0], lib.ct_bundle_free)
        self.threads = threads
        lib.ct_bundle_set_threads(self._bundle, self.threads)
        self.detrend = detrend

    @property
    def layer(self):
        """E, sigma_y, Hstar, l0 (the length or area) and h0 (= Rt) of the rods."""
        L = lib.ct_bundle_layer(self._bundle)
        return {k: getattr(L, k) for k in ("E", "sigma_y", "Hstar", "l0", "h0")}

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
        from ._api import Restitution  # _api imports this module
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
        f.dimension = chk.choice("dimension", dimension, DIMENSIONS)
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
            self._profile, f, lib.ct_bundle_layer(self._bundle), ffi.from_buffer("double[]", W),
            W.size, self.threads, ffi.from_buffer("double[]", out["e_cantor_fit"]),
            ffi.from_buffer("double[]", out["e_asymptotic_fit"]),
            ffi.from_buffer("double[]", out["V_star_cantor_fit"])))
        for k, v in out.items():  # NaN: not computed (see above); inf never a result
            chk.finite_result(k, v, may_be_nan=True)
        return {k: v.reshape(shape) for k, v in out.items()}

    def _physical_scales(self):
        L = lib.ct_bundle_layer(self._bundle)
        return L.l0, L.E, L.h0

    def _build(self, V_star, impacts, opts, keep_all=False):
        return self._bundle, _info(self._bundle)

    def __repr__(self):
        p, L = self._profile, lib.ct_bundle_layer(self._bundle)
        shape = f"{p.nx} points" if p.ny == 1 else f"{p.nx} x {p.ny} grid"
        return (f"Profile({self.source}, {shape}, {int(p.n)} rods, Rt={L.h0!r}, "
                f"E={L.E!r}, sigma_y={L.sigma_y!r}, Hstar={L.Hstar!r})")


SURFACES = (Cantor, RandomCantor, Rods, Profile)


def surface_of(name, value):
    """value, checked to be a surface."""
    if not isinstance(value, SURFACES):
        raise invalid(f"{name}: must be a cantact surface (Cantor, RandomCantor, Rods or Profile), got "
                      f"{type(value).__name__}")
    return value
