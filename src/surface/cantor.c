/* The Cantor surface (docs/model.md §1-2): parameter validation, the geometry of Eqs. 1-3, 16-18,
 * 28, the prefractal as rods (stages or segments) with its metadata, and the truncation depth. */
#include "kind.h"

#include <float.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int check_positive(const char *name, double v)
{
    if (!isfinite(v) || !(v > 0.0))
        return ct_error_set(CT_EINVAL, "%s = %g: must be finite and > 0", name, v);
    return CT_OK;
}

int ct_params_validate(const ct_params *p)
{
    int st;
    if (!p)
        return ct_error_set(CT_EINVAL, "parameters: NULL");
    if (!isfinite(p->fx) || !(p->fx > 1.0))
        return ct_error_set(CT_EINVAL, "fx = %g: must satisfy fx > 1 (finite)", p->fx);
    if (!isfinite(p->fz) || !(p->fz > 1.0 && p->fz < 2.0))
        return ct_error_set(CT_EINVAL, "fz = %g: must satisfy 1 < fz < 2", p->fz);
    if ((st = check_positive("l0", p->l0)) || (st = check_positive("h0", p->h0)))
        return st;
    if (!isfinite(p->Hstar) || !(p->Hstar > p->h0))
        return ct_error_set(CT_EINVAL, "H* = %g: must be finite and > h0 = %g", p->Hstar, p->h0);
    /* E, sigma_y and the energy scales: the checks every rod set's layer passes */
    const ct_layer L = {
        .E = p->E, .sigma_y = p->sigma_y, .Hstar = p->Hstar, .l0 = p->l0, .h0 = p->h0};
    return ct_layer_validate(&L);
}

/* exp(-i log f), which is 0 (not NaN) for huge i and exact for f -> 1 via log1p. */
static double power_down(double f, double i)
{
    return exp(-i * log1p(f - 1.0));
}

double ct_stage_length(const ct_params *p, double i)
{
    return p->l0 * power_down(p->fx, i); /* Eq. 1 */
}

double ct_stage_depth(const ct_params *p, double i)
{
    return p->h0 * power_down(p->fz, i); /* Eq. 2 */
}

/* 1 - 1/fx = (fx - 1)/fx: fx - 1 is exact (Sterbenz) for fx in (1, 2]. */
static double one_minus_inv(double f)
{
    return (f - 1.0) / f;
}

double ct_stage_area(const ct_params *p, double i)
{
    return p->l0 * one_minus_inv(p->fx) * power_down(p->fx, i);
}

double ct_alpha(const ct_params *p)
{
    return log1p(p->fx - 1.0) / log1p(p->fz - 1.0); /* Eq. 28 */
}

double ct_beta(const ct_params *p)
{
    return 1.0 / (p->fx * p->fz); /* Eq. 18 */
}

static double log_inv_beta(const ct_params *p)
{
    return log1p(p->fx - 1.0) + log1p(p->fz - 1.0);
}

double ct_one_minus_beta(const ct_params *p)
{
    return -expm1(-log_inv_beta(p));
}

double ct_dimension(const ct_params *p)
{
    /* Eq. 3: D = 1 - ln fz / ln(2 fx) + ln 2 / ln(2 fx) */
    double ln2fx = log(2.0) + log1p(p->fx - 1.0);
    return 1.0 + (log(2.0) - log1p(p->fz - 1.0)) / ln2fx;
}

double ct_sum_area(const ct_params *p, double n1, double n2)
{
    if (n2 < n1)
        return 0.0;
    /* Eq. 16: l_{n1} - l_{n2+1} = l_{n1} (1 - fx^-(n2+1-n1)) */
    double lf = log1p(p->fx - 1.0);
    if (isinf(n2))
        return ct_stage_length(p, n1);
    return ct_stage_length(p, n1) * -expm1(-(n2 + 1.0 - n1) * lf);
}

double ct_sum_depth_area(const ct_params *p, double n1, double n2)
{
    if (n2 < n1)
        return 0.0;
    /* Eq. 17: h0 l0 (1 - 1/fx) (beta^n1 - beta^(n2+1)) / (1 - beta), written as
     * beta^n1 (1 - beta^(n2+1-n1)) / (1 - beta) with expm1 so that beta -> 1 loses nothing. */
    double lb = log_inv_beta(p);
    double head = exp(-n1 * lb);
    double ratio = isinf(n2) ? 1.0 / -expm1(-lb) : expm1(-(n2 + 1.0 - n1) * lb) / expm1(-lb);
    return p->h0 * p->l0 * one_minus_inv(p->fx) * head * ratio;
}

double ct_energy_scale(const ct_params *p)
{
    return p->l0 * p->E * p->h0;
}

int ct_piece_extent(const ct_params *p, long depth, long stage, size_t j, double *x_left,
                    double *x_right)
{
    CT_NEED(p);
    CT_NEED(x_left);
    CT_NEED(x_right);
    if (stage < 0 || stage > depth || stage > 62 || j >> stage)
        return ct_error_set(CT_EINVAL, "piece %zu of stage %ld: outside a depth-%ld prefractal", j,
                            stage, depth);
    /* The parent segment at stage i spans [left, left + w_i], w_i = l0 (2 fx)^-i; bit s of j
     * (from the top) says whether the right child was kept at stage s. */
    double two_fx = 2.0 * p->fx, left = 0.0, w = p->l0;
    for (long s = 1; s <= stage; s++) {
        double w_next = w / two_fx;
        if ((j >> (stage - s)) & 1u)
            left += w - w_next;
        w = w_next;
    }
    if (stage < depth) {
        double w_child = w / two_fx;
        *x_left = left + w_child;
        *x_right = left + w - w_child;
    } else {
        *x_left = left;
        *x_right = left + w;
    }
    return CT_OK;
}

/* ---- the prefractal as rods ---- */

typedef struct {
    ct_params p;
    ct_representation rep;
    long depth;
    size_t first_rod; /* global index of rod 0 (stages: the first stage kept) */
} cantor_meta;

/* Stage of segment rod with global index g: g = 2^i - 1 + j, 0 <= j < 2^i. */
static long segment_stage(size_t g)
{
    long i = 0;
    while (((size_t)1 << (i + 1)) - 1 <= g)
        i++;
    return i;
}

static void cantor_rod_info(const void *meta, size_t k, ct_rod_info *info)
{
    const cantor_meta *m = meta;
    size_t g = k + m->first_rod;
    if (m->rep == CT_REP_STAGES) {
        info->stage = (long)g; /* merged pieces have no single position: x stays NaN */
        return;
    }
    long i = segment_stage(g);
    info->stage = i;
    ct_piece_extent(&m->p, m->depth, i, g - (((size_t)1 << i) - 1), &info->x_left, &info->x_right);
}

static void *cantor_clone(const void *meta)
{
    cantor_meta *m = malloc(sizeof *m);
    if (m)
        *m = *(const cantor_meta *)meta;
    return m;
}

static const ct_rod_meta_kind cantor_kind = {"cantor", cantor_rod_info, cantor_clone, free};

void ct_cantor_layer(const ct_params *p, ct_layer *layer)
{
    layer->E = p->E;
    layer->sigma_y = p->sigma_y;
    layer->Hstar = p->Hstar;
    layer->l0 = p->l0;
    layer->h0 = p->h0;
}

long ct_cantor_depth(const ct_bundle *b)
{
    const cantor_meta *m = ct_bundle_surface_meta(b, &cantor_kind);
    return m ? m->depth : -1;
}

int ct_cantor_representation(const ct_bundle *b)
{
    const cantor_meta *m = ct_bundle_surface_meta(b, &cantor_kind);
    return m ? (int)m->rep : -1;
}

int ct_cantor_bundle(ct_bundle **out, const ct_params *p, ct_representation rep, long depth,
                     double u_reach)
{
    CT_NEED(out);
    int st;
    *out = NULL;
    if ((st = ct_params_validate(p)))
        return st;
    if (rep != CT_REP_STAGES && rep != CT_REP_SEGMENTS)
        return ct_error_set(CT_EINVAL, "representation %d: must be stages or segments", rep);
    long max_depth = rep == CT_REP_STAGES ? CT_MAX_STAGES_DEPTH : CT_MAX_SEGMENTS_DEPTH;
    if (depth < 0 || depth > max_depth)
        return ct_error_set(CT_EINVAL, "depth = %ld: must satisfy 0 <= depth <= %ld for %s", depth,
                            max_depth, rep == CT_REP_STAGES ? "stages" : "segments");
    if (isnan(u_reach))
        return ct_error_set(CT_EINVAL, "u_reach is NaN");

    /* Stages whose top lies deeper than u_reach can never be touched. Tops decrease with
     * the stage index, so these are the first stages. */
    long first = 0;
    while (first < depth + 1 && ct_stage_depth(p, (double)first) > u_reach)
        first++;
    size_t total, first_rod;
    if (rep == CT_REP_STAGES) {
        total = (size_t)depth + 1;
        first_rod = (size_t)first;
    } else {
        total = ((size_t)1 << (depth + 1)) - 1;
        first_rod = ((size_t)1 << first) - 1;
    }
    cantor_meta *meta = malloc(sizeof *meta);
    if (!meta)
        return ct_error_set(CT_ENOMEM, "cantor surface: out of memory");
    *meta = (cantor_meta){*p, rep, depth, first_rod};
    char what[96];
    snprintf(what, sizeof what, "depth %ld %s", depth,
             rep == CT_REP_STAGES ? "stages" : "segments");
    ct_layer layer;
    ct_cantor_layer(p, &layer);
    ct_bundle *b;
    if ((st = ct_bundle_create(&b, &layer, total - first_rod, what))) {
        free(meta);
        return st;
    }
    ct_bundle_set_surface(b, &cantor_kind, meta, first_rod);
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays(b, &top, &length, &area, &eps_p);
    if (rep == CT_REP_STAGES) {
        for (long i = first; i <= depth; i++) {
            size_t k = (size_t)(i - first);
            top[k] = ct_stage_depth(p, (double)i);
            length[k] = p->Hstar - top[k];
            area[k] = i < depth ? ct_stage_area(p, (double)i) : ct_stage_length(p, (double)i);
            eps_p[k] = 0.0;
        }
    } else {
        for (long i = first; i <= depth; i++) {
            size_t pieces = (size_t)1 << i;
            size_t k0 = pieces - 1 - first_rod;
            double t = ct_stage_depth(p, (double)i), l = p->Hstar - t;
            /* middles carry s_i / 2^i, the tips l_N / 2^N */
            double a = (i < depth ? ct_stage_area(p, (double)i) : ct_stage_length(p, (double)i)) *
                       ldexp(1.0, (int)-i);
            ct_bundle_fill(b, k0, pieces, t, l, a);
        }
    }
    *out = b;
    return CT_OK;
}

/* ---- the truncation depth ---- */

/* Bound on |P_N(u) - P_inf(u)| for any common history: the force of a rod is Lipschitz in
 * its top depth h with constant E H* / (H* - h0)^2 (strain and plastic strain both vary as
 * (u - H*)/(H* - h)^2), each difference is also at most E eps_y, and the tip lumps area l_N
 * of tops in [0, h_N]. */
static double force_bound(const ct_params *p, long N)
{
    double lN = ct_stage_length(p, (double)N), hN = ct_stage_depth(p, (double)N);
    double eps_y = p->sigma_y / p->E, gap = p->Hstar - p->h0;
    double lip = hN * p->Hstar / (gap * gap);
    return p->E * lN * (lip < eps_y ? lip : eps_y);
}

/* Depths from here on reuse the u_max of this depth as an upper bound, so the search
 * costs nothing more for deep surfaces. */
#define DEPTH_PROBE 64

typedef struct {
    const ct_params *p;
    double W_min;
    int tips;
    double u_up; /* u_max at DEPTH_PROBE, < 0 until computed */
} depth_ctx;

/* u_max and P there of the virgin depth-N prefractal under energy W. *resolved (when not
 * NULL) says whether the penetration u_max - u_contact is above the resolution of u; where it
 * is not, u is still an upper bound of u_max to rounding (the curve's inverse). */
static int solve_virgin(const ct_params *p, long N, double W, double *u, double *P, int *resolved)
{
    ct_bundle *b;
    ct_curve *c;
    int st = ct_cantor_bundle(&b, p, CT_REP_STAGES, N, INFINITY);
    if (st)
        return st;
    if ((st = ct_curve_alloc(&c))) {
        ct_bundle_free(b);
        return st;
    }
    if (!(st = ct_curve_build(c, b))) {
        *u = ct_curve_inverse_work(c, W);
        *P = ct_curve_force(c, *u);
        double u0 = ct_curve_first_contact(c);
        int ok = *u - u0 > 16.0 * DBL_EPSILON * fabs(u0);
        if (resolved)
            *resolved = ok;
        if (!ok && !resolved)
            st = ct_error_set(CT_ENOCONV,
                              "u_max solve: the penetration u_max - u_contact (%.3g) is below the "
                              "resolution of u near %.17g: this impact is too weak to resolve on "
                              "rods this stiff (raise V*)",
                              *u - u0, u0);
        else if (!(*u < p->Hstar))
            st = ct_error_set(CT_ERANGE,
                              "impact energy %.6g reaches u_max >= H* = %g (the layer would be "
                              "crushed, strains >= 1): outside the model; lower V* or raise H",
                              W, p->Hstar);
    }
    ct_curve_free(c);
    ct_bundle_free(b);
    return st;
}

/* The truncated surface is softer than any deeper one on a virgin loading (deeper tips only
 * add strain), so its u_max bounds theirs from above: the energy bound is safe. */
static int depth_bound(depth_ctx *c, long N, double *bound)
{
    const ct_params *p = c->p;
    double dP = force_bound(p, N), u, P;
    int st;
    if (N < DEPTH_PROBE) {
        /* an impact too weak to resolve on this prefractal's tips (their top is far from the
         * plane) needs a deeper one, whose tips lie closer: no bound here */
        int resolved;
        if ((st = solve_virgin(p, N, c->W_min, &u, &P, &resolved)))
            return st;
        double rel_W = dP * u / c->W_min, rel_P = P > 0.0 ? dP / P : INFINITY;
        *bound = !resolved ? INFINITY : rel_W > rel_P ? rel_W : rel_P;
    } else {
        int resolved; /* u is an upper bound of u_max either way */
        if (c->u_up < 0.0 && (st = solve_virgin(p, DEPTH_PROBE, c->W_min, &c->u_up, &P, &resolved)))
            return st;
        /* P(u_max) >= W / u_max as P rises with u: dP u_up / W bounds both ratios */
        *bound = dP * c->u_up / c->W_min;
    }
    if (c->tips) {
        /* first yield of the prefractal: eps_y H* + (1 - eps_y) h_N, of the fractal eps_y H* */
        double eps_y = p->sigma_y / p->E;
        double rel_tip = (1.0 - eps_y) * ct_stage_depth(p, (double)N) / (eps_y * p->Hstar);
        *bound = *bound > rel_tip ? *bound : rel_tip;
    }
    return CT_OK;
}

static int search_depth(const ct_params *p, double W_min, double tol, int tips, long *depth,
                        double *bound)
{
    int st;
    if ((st = ct_params_validate(p)))
        return st;
    if (!(tol > 0.0 && tol < 1.0))
        return ct_error_set(CT_EINVAL, "depth tolerance = %g: must satisfy 0 < tol < 1", tol);
    if (!isfinite(W_min) || !(W_min > 0.0))
        return ct_error_set(CT_EINVAL, "depth auto: impact energy %g must be finite and > 0",
                            W_min);
    depth_ctx c = {p, W_min, tips, -1.0};
    long hi = 1;
    double b_hi;
    for (;;) {
        if ((st = depth_bound(&c, hi, &b_hi)))
            return st;
        if (b_hi <= tol)
            break;
        if (hi >= CT_MAX_STAGES_DEPTH / 2)
            return ct_error_set(CT_ENOCONV,
                                "depth auto: even %ld stages leave a truncation bound of %.3g "
                                "> tolerance %.3g (fx, fz too close to 1); raise the tolerance "
                                "or give a depth",
                                hi, b_hi, tol);
        hi *= 2;
    }
    long lo = hi / 2; /* bound(lo) > tol or lo = 0 */
    while (hi - lo > 1) {
        long mid = lo + (hi - lo) / 2;
        double b_mid;
        if ((st = depth_bound(&c, mid, &b_mid)))
            return st;
        if (b_mid <= tol) {
            hi = mid;
            b_hi = b_mid;
        } else {
            lo = mid;
        }
    }
    *depth = hi;
    *bound = b_hi;
    return CT_OK;
}

int ct_auto_depth(const ct_params *p, double W_min, double tol, long *depth, double *bound)
{
    CT_NEED(depth);
    CT_NEED(bound);
    return search_depth(p, W_min, tol, 0, depth, bound);
}

int ct_fractal_depth(const ct_params *p, double W_min, long *depth, double *bound)
{
    CT_NEED(depth);
    CT_NEED(bound);
    return search_depth(p, W_min, 1e-15, 1, depth, bound);
}

int ct_cantor_choose_depth(const ct_params *p, long setting, double V_min, double tol, long *depth,
                           double *bound)
{
    CT_NEED(p);
    CT_NEED(depth);
    CT_NEED(bound);
    *bound = 0.0;
    if (setting >= 0) {
        *depth = setting;
        return CT_OK;
    }
    const double W_min = V_min * V_min * ct_energy_scale(p);
    if (setting == CT_DEPTH_FRACTAL)
        return ct_fractal_depth(p, W_min, depth, bound);
    if (setting == CT_DEPTH_AUTO)
        return ct_auto_depth(p, W_min, tol, depth, bound);
    return ct_error_set(CT_EINVAL, "depth = %ld: must be >= 0, auto or fractal", setting);
}

/* ---- the kind (src/surface/kind.h): keys, checks, rods, and the outputs only it gives ---- */

typedef struct {
    ct_cantor_keys k;   /* fx, fz, H, h0, l0; E, sigma_y */
    long depth;         /* >= 0, CT_DEPTH_AUTO, CT_DEPTH_FRACTAL */
    int representation; /* ct_representation */
    ct_params params;   /* computed: dimensionless (l0 = h0 = sigma_y = 1) */
    ct_params physical; /* as given */
} cantor_config;

#define AT(field) offsetof(cantor_config, field)
static const ct_key cantor_keys[] = {
    CT_CANTOR_SURFACE_ROWS(cantor_config, k,
                           "horizontal ratio: stage n keeps 1/fx of stage n-1's length",
                           "vertical ratio: the recess depth shrinks by 1/fz per stage"),
    {"surface", "depth", CT_KEY_DEPTH, 0.0, CT_MAX_STAGES_DEPTH, 0, "auto|fractal",
     "must satisfy 0 <= depth <= 100000000", "auto",
     "prefractal depth N; auto: truncation bound below solver.depth_tolerance; fractal: the "
     "limit to double precision",
     AT(depth)},
    {"surface", "representation", CT_KEY_WORD, 0, 0, 0, "stages|segments",
     "must be stages or segments", "stages",
     "one rod per stage (pieces merged, exact) or one per piece (depth <= 40)", AT(representation)},
    CT_CANTOR_MATERIAL_ROWS(cantor_config, k),
};
#undef AT

void ct_cantor_keys_defaults(ct_cantor_keys *k)
{
    k->h0 = k->l0 = k->sigma_y = 1.0;
}

int ct_cantor_keys_check(ct_surface *s, const ct_cantor_keys *k, const char *scene,
                         ct_params *physical, ct_params *params)
{
    int st;
    if (!(k->E > k->sigma_y))
        return ct_surface_key_error(s, "material", "E", CT_EINVAL,
                                    "must be > sigma_y (yield strain sigma_y/E < 1)");
    *physical = (ct_params){.fx = k->fx,
                            .fz = k->fz,
                            .l0 = k->l0,
                            .h0 = k->h0,
                            .Hstar = k->H * k->h0,
                            .E = k->E,
                            .sigma_y = k->sigma_y};
    if ((st = ct_params_validate(physical)))
        return ct_error_set(st, "%s: %s", scene, ct_error_message());
    *params = *physical;
    params->Hstar = physical->Hstar / physical->h0;
    params->E = physical->E / physical->sigma_y;
    params->l0 = params->h0 = params->sigma_y = 1.0;
    if ((st = ct_params_validate(params)))
        return ct_error_set(st, "%s: %s", scene, ct_error_message());
    return CT_OK;
}

static void cantor_defaults(void *config)
{
    cantor_config *c = config;
    ct_cantor_keys_defaults(&c->k);
    c->depth = CT_DEPTH_AUTO;
    c->representation = CT_REP_STAGES;
}

/* The shared keys (E/sigma_y times H* / h0 may overflow, so both forms are validated), then
 * the representation's depth. */
static int cantor_check(ct_surface *s, const char *scene)
{
    cantor_config *c = s->config;
    int st = ct_cantor_keys_check(s, &c->k, scene, &c->physical, &c->params);
    if (st)
        return st;
    if (c->representation == CT_REP_SEGMENTS) {
        if (c->depth < 0) {
            size_t k;
            ct_kind_key(s->kind, "surface", "depth", &k);
            return ct_error_set(CT_EINVAL,
                                "%s: surface.representation = segments: needs an integer "
                                "surface.depth (0..%d)",
                                s->where[k] ? s->where[k] : scene, CT_MAX_SEGMENTS_DEPTH);
        }
        if (c->depth > CT_MAX_SEGMENTS_DEPTH)
            return ct_surface_key_error(s, "surface", "depth", CT_EINVAL,
                                        "segments allow 0 <= depth <= 40");
    }
    return CT_OK;
}

static int cantor_prepare(ct_surface *s, const char *dir)
{
    (void)dir;
    const cantor_config *c = s->config;
    ct_layer built, given;
    ct_cantor_layer(&c->params, &built);
    ct_cantor_layer(&c->physical, &given);
    ct_scales_of(&s->scales, &built, &given);
    return CT_OK;
}

static int cantor_build(const ct_surface *s, const ct_build_request *r, ct_bundle **out,
                        ct_plan_info *info)
{
    const cantor_config *c = s->config;
    ct_cantor_plan plan = {
        .params = c->params,
        .depth = c->depth,
        .representation = (ct_representation)c->representation,
        .depth_tolerance = r->depth_tolerance,
        .V_star = r->V_star,
        .nvel = r->nvel,
        .impacts = r->impacts,
        .opts = r->opts,
        .keep_all_rods = r->keep_all_rods,
        .threads = r->threads,
    };
    int st = ct_cantor_plan_build(&plan, out, info);
    if (!st && r->keep_all_rods && info->depth > 20) {
        ct_bundle_free(*out);
        *out = NULL;
        return ct_error_set(CT_EINVAL,
                            "profile: depth %ld has 2^%ld pieces; the profile is written for "
                            "depth <= 20 (set surface.depth)",
                            info->depth, info->depth + 1);
    }
    return st;
}

static void cantor_describe(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    const cantor_config *c = s->config;
    char how[96];
    if (c->depth >= 0)
        snprintf(how, sizeof how, "given");
    else
        snprintf(how, sizeof how, "%s: truncation bound %.2g",
                 c->depth == CT_DEPTH_FRACTAL ? "fractal limit" : "auto", info->bound);
    snprintf(buf, len, "%s, depth %ld (%s), %zu rods, %zu left out as never touched",
             c->representation == CT_REP_STAGES ? "stage rods" : "segment rods", info->depth, how,
             info->rods, info->omitted);
}

static void cantor_table_line(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    const ct_params *p = &((const cantor_config *)s->config)->params;
    snprintf(
        buf, len,
        "cantor: fx = %.17g, fz = %.17g, H*/h0 = %.17g, E/sigma_y = %.17g, depth %ld, %zu rods",
        p->fx, p->fz, p->Hstar / p->h0, p->E / p->sigma_y, info->depth, info->rods);
}

/* One row per piece of every stage (stage rods stand for all pieces of their stage), with its
 * x-extent and top, and the top after the impacts (the residual: top + plastic strain L). */
static int cantor_write_profile(const ct_surface *s, const ct_bundle *b, FILE *f)
{
    const ct_params *p = &((const cantor_config *)s->config)->params;
    const long N = ct_cantor_depth(b);
    const int stages = ct_cantor_representation(b) == CT_REP_STAGES;
    const size_t n = ct_bundle_size(b);
    ct_rod_info info;
    long first_stage = N + 1;
    if (n && !ct_bundle_rod(b, 0, &info))
        first_stage = info.stage;
    fputs("stage,x_left_over_l0,x_right_over_l0,top_over_h0,residual_top_over_h0\n", f);
    for (long i = 0; i <= N; i++) {
        double top = ct_stage_depth(p, (double)i), residual = top;
        if (i >= first_stage) {
            size_t k =
                stages ? (size_t)(i - first_stage) : ((size_t)1 << i) - ((size_t)1 << first_stage);
            if (ct_bundle_rod(b, k, &info) == CT_OK)
                residual = info.top + info.plastic_strain * info.length;
        }
        for (size_t j = 0; j < ((size_t)1 << i); j++) {
            double xl, xr;
            ct_piece_extent(p, N, i, j, &xl, &xr);
            if (!stages && i >= first_stage) {
                size_t k = ((size_t)1 << i) - 1 + j - (((size_t)1 << first_stage) - 1);
                if (ct_bundle_rod(b, k, &info) == CT_OK)
                    residual = info.top + info.plastic_strain * info.length;
            }
            fprintf(f, "%ld,%.17g,%.17g,%.17g,%.17g\n", i, xl / p->l0, xr / p->l0, top / p->h0,
                    residual / p->h0);
        }
    }
    return CT_OK;
}

static const char *const law_e_names[] = {"e_series", "e_asymptotic", "e_asymptotic_consistent"};
static const char *const law_P_names[] = {"P_series_over_PY", "P_asymptotic_over_PY",
                                          "P_asymptotic_consistent_over_PY"};

/* The paper's laws model the first impact on the virgin fractal; where a law does not apply
 * (u_max > h0, e > 1) its value is NaN. */
static int cantor_compare(ct_surface *s, const ct_sweep_row *rows, size_t n, double *out)
{
    const ct_params *p = &((const cantor_config *)s->config)->params;
    for (size_t k = 0; k < n; k++) {
        if (rows[k].status || rows[k].impact != 1)
            continue;
        for (int law = CT_LAW_SERIES; law <= CT_LAW_ASYMPTOTIC_CONSISTENT; law++) {
            double um, el;
            if (ct_law_impact(p, (ct_law)law, rows[k].r.kinetic_energy, &um, &el) == CT_OK)
                out[3 * k + (size_t)law] = el;
        }
    }
    return CT_OK;
}

/* The laws' P at u (unloading from u_max when unload), in P_Y; NaN where a law does not
 * apply. */
static void cantor_curve_compare(const ct_surface *s, int unload, double u_max, double u,
                                 double *out)
{
    const ct_params *p = &((const cantor_config *)s->config)->params;
    const double PY = p->sigma_y * p->l0;
    double ps = 0.0, pa = 0.0, pc = 0.0;
    int ss = unload ? ct_series_unload(p, u_max, u, &ps) : ct_series_load(p, u, &ps);
    int sa = unload ? ct_asym_unload(p, u_max, u, 0, &pa) : ct_asym_load(p, u, &pa);
    int sc = unload ? ct_asym_unload(p, u_max, u, 1, &pc) : sa;
    out[0] = ss ? NAN : ps / PY;
    out[1] = sa ? NAN : pa / PY;
    out[2] = sc ? NAN : (unload ? pc : pa) / PY;
}

/* The stages at the depth a run would use (auto: for the smallest speed asked). */
static int cantor_write_geometry(const ct_surface *s, const ct_build_request *r, FILE *f)
{
    const cantor_config *c = s->config;
    const ct_params *p = &c->params;
    double vmin = INFINITY, bound;
    for (size_t k = 0; k < r->nvel; k++)
        vmin = r->V_star[k] < vmin ? r->V_star[k] : vmin;
    long depth;
    int st = ct_cantor_choose_depth(p, c->depth, vmin, r->depth_tolerance, &depth, &bound);
    if (st)
        return st;
    fprintf(f, "# fx = %g, fz = %g, H*/h0 = %g, E/sigma_y = %g\n", p->fx, p->fz, p->Hstar / p->h0,
            p->E / p->sigma_y);
    fprintf(f, "# alpha = %.17g, beta = %.17g, D = %.17g, depth = %ld\n", ct_alpha(p), ct_beta(p),
            ct_dimension(p), depth);
    fputs("stage,l_over_l0,h_over_h0,s_over_l0,rod_length_over_h0\n", f);
    const long shown = depth < 60 ? depth : 60;
    for (long i = 0; i <= shown; i++) {
        double a = i < depth ? ct_stage_area(p, (double)i) : ct_stage_length(p, (double)i);
        double h = ct_stage_depth(p, (double)i);
        fprintf(f, "%ld,%.17g,%.17g,%.17g,%.17g\n", i, ct_stage_length(p, (double)i) / p->l0,
                h / p->h0, a / p->l0, (p->Hstar - h) / p->h0);
    }
    if (shown < depth)
        fprintf(f, "# ... %ld more stages\n", depth - shown);
    return CT_OK;
}

static const ct_refusal cantor_refusals[] = {
    {"bearing", "a bearing-area curve is written for measured surfaces (type = profile); the "
                "Cantor surface's is the power law (d/h0)^alpha, alpha in cantact geometry"},
    {"ensemble", "ensembles are of random surfaces: surface.type = random_cantor"},
    {"realisations", "ensembles are of random surfaces: surface.type = random_cantor"},
    {"merge", "merge combines the parts of an ensemble of a random_cantor surface"},
    {"fit", "cantact fit fits a Cantor surface to a measured profile (type = profile or a "
            "profile file)"},
    {NULL, NULL},
};

const ct_kind ct_kind_cantor = {
    .name = "cantor",
    .summary = "the deterministic Cantor prefractal of the paper, one rod per stage or per piece",
    .keys = cantor_keys,
    .nkeys = sizeof cantor_keys / sizeof cantor_keys[0],
    .config_size = sizeof(cantor_config),
    .defaults = cantor_defaults,
    .gives = "profile compare geometry",
    .refusals = cantor_refusals,
    .check = cantor_check,
    .prepare = cantor_prepare,
    .build = cantor_build,
    .describe = cantor_describe,
    .table_line = cantor_table_line,
    .write_profile = cantor_write_profile,
    .profile_shows_state = 1,
    .ncompare = 3,
    .compare_names = law_e_names,
    .compare = cantor_compare,
    .ncurve_compare = 3,
    .curve_compare_names = law_P_names,
    .curve_compare = cantor_curve_compare,
    .write_geometry = cantor_write_geometry,
};
