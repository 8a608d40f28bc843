"""Surfaces: each describes itself and builds its rods (a bundle) for the speeds asked.

A Cantor or random Cantor surface is computed in dimensionless form, as the cantact program
does (l0 = h0 = sigma_y = 1, H* = H, E = E/sigma_y): the model depends on its dimensionless
groups alone, and the results (u/h0, P/P_Y, V*) are the same bits as `cantact run`'s. A rod set
(Rods) is computed in the units given; its results are made dimensionless by its h0, sigma_y
and l0. A new kind of surface is a class with the same four members: kind, _params (or None),
_physical_energy_scale(), _build()."""
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

    def _physical_energy_scale(self):
        return lib.ct_energy_scale(self._physical)

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

    def _physical_energy_scale(self):
        return lib.ct_energy_scale(self._physical)

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


class Rods:
    """Your own surface as rods (MODEL.md §3-4): top[k] is rod k's depth below the reference
    plane (0 <= top < Hstar), area[k] its area (> 0), in one Winkler layer of thickness Hstar
    with E and sigma_y; l0 and h0 are the reference length and depth of the outputs (V*,
    u/h0, P/P_Y = P/(sigma_y l0)). Computed in the units given."""

    kind = "rods"
    _params = None

    def __init__(self, top, area, E, Hstar, sigma_y=1.0, l0=1.0, h0=1.0, threads=0):
        top = chk.array("top", top, nonnegative=True)
        area = chk.array("area", area, positive=True)
        if top.size != area.size:
            raise invalid(f"top and area: {top.size} and {area.size} rods: must be as many")
        self._layer = ffi.new("ct_layer *", {
            "E": chk.real("E", E, 0.0), "sigma_y": chk.real("sigma_y", sigma_y, 0.0),
            "Hstar": chk.real("Hstar", Hstar, 0.0), "l0": chk.real("l0", l0, 0.0),
            "h0": chk.real("h0", h0, 0.0)})
        check(lib.ct_layer_validate(self._layer))
        if (top >= self._layer.Hstar).any():
            k = int(np.flatnonzero(top >= self._layer.Hstar)[0])
            raise invalid(f"top[{k}] = {top[k]!r}: must be < Hstar = {self._layer.Hstar!r}")
        out = ffi.new("ct_bundle **")
        check(lib.ct_bundle_from_rods(out, self._layer, top.size, ffi.from_buffer("double[]", top),
                                      ffi.from_buffer("double[]", area)))
        self._bundle = ffi.gc(out[0], lib.ct_bundle_free)
        self.threads = _threads(threads)
        lib.ct_bundle_set_threads(self._bundle, self.threads)
        self.top, self.area = top, area

    def _physical_energy_scale(self):
        L = self._layer
        return L.l0 * L.E * L.h0  # as the sweep computes it

    def _build(self, V_star, impacts, opts, keep_all=False):
        return self._bundle, _info(self._bundle)

    def __repr__(self):
        L = self._layer
        return f"Rods({self.top.size} rods, E={L.E!r}, sigma_y={L.sigma_y!r}, Hstar={L.Hstar!r})"


SURFACES = (Cantor, RandomCantor, Rods)


def surface_of(name, value):
    """value, checked to be a surface."""
    if not isinstance(value, SURFACES):
        raise invalid(f"{name}: must be a cantact surface (Cantor, RandomCantor or Rods), got "
                      f"{type(value).__name__}")
    return value
