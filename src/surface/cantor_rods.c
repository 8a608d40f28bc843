/* The Cantor prefractal as rods (docs/model.md §2, §4): one rod per stage or per piece, with
 * each rod's stage and x-extent; the truncation depth that keeps a stated bound; and the plan
 * of a scene (its depth, and the rods deeper than every impact reaches, left out). */
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

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

static const ct_rod_meta_kind cantor_kind = {"cantor", cantor_rod_info, cantor_clone, free, NULL,
                                             NULL};

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
                              "crushed, strains >= 1): outside the model; lower the speed or "
                              "raise H",
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

/* ---- the plan of a scene ---- */

int ct_cantor_plan_build(const ct_cantor_plan *plan, ct_bundle **out, ct_plan_info *info)
{
    CT_NEED(plan);
    CT_NEED(out);
    const ct_params *p = &plan->params;
    int st;
    *out = NULL;
    if ((st = ct_params_validate(p)) || (st = ct_check_speeds(plan->V_star, plan->nvel)))
        return st;
    if (plan->nvel == 0)
        return ct_error_set(CT_EINVAL, "plan: no speeds");
    if (plan->impacts < 1)
        return ct_error_set(CT_EINVAL, "impacts = %ld: must be >= 1", plan->impacts);
    double vmin = INFINITY, vmax = 0.0;
    for (size_t k = 0; k < plan->nvel; k++) {
        vmin = plan->V_star[k] < vmin ? plan->V_star[k] : vmin;
        vmax = plan->V_star[k] > vmax ? plan->V_star[k] : vmax;
    }
    const double scale = ct_energy_scale(p);
    long depth = plan->depth;
    double bound = 0.0;
    if (depth == CT_DEPTH_FRACTAL)
        st = ct_fractal_depth(p, vmin * vmin * scale, &depth, &bound);
    else if (depth == CT_DEPTH_AUTO)
        st = ct_auto_depth(p, vmin * vmin * scale, plan->depth_tolerance, &depth, &bound);
    else if (depth < 0)
        st = ct_error_set(CT_EINVAL, "depth = %ld: must be >= 0, auto or fractal", depth);
    if (st)
        return st;

    /* Rods deeper than every displacement the plan reaches can never be touched, and can be
     * left out, provided none of them decides a reported number: the deepest u_max (the
     * largest speed, on the cheap and exact stage rods, impacts carried over), and the first
     * yield of the virgin surface, which fixes V*_c even when every impact is elastic. If
     * the probe fails (a crushed layer), nothing is left out: the sweep reports that row. */
    double u_reach = INFINITY;
    if (!plan->keep_all_rods) {
        ct_bundle *probe;
        if ((st = ct_cantor_bundle(&probe, p, CT_REP_STAGES, depth, INFINITY)))
            return st;
        double reach = ct_bundle_first_yield(probe);
        int ok = 1;
        ct_sweep_row *rows = malloc((size_t)plan->impacts * sizeof *rows);
        ct_sweep_spec spec = {.V_star = &vmax, .nvel = 1, .impacts = plan->impacts};
        spec.opts = plan->opts;
        spec.opts.rule = CT_QUAD_BREAKPOINTS; /* only u_max is needed: the exact rule */
        spec.opts.check = 0;
        st = rows ? ct_sweep(probe, &spec, rows) : ct_error_set(CT_ENOMEM, "plan: out of memory");
        if (st) {
            ct_bundle_free(probe);
            free(rows);
            return st;
        }
        for (long i = 0; i < plan->impacts && ok; i++) {
            ok = rows[i].status == CT_OK;
            if (ok && rows[i].r.u_max > reach)
                reach = rows[i].r.u_max;
        }
        free(rows);
        ct_bundle_free(probe);
        if (ok)
            u_reach = reach * (1.0 + 1e-9);
    }
    ct_bundle *b;
    if ((st = ct_cantor_bundle(&b, p, plan->representation, depth, u_reach)))
        return st;
    ct_bundle_set_threads(b, plan->threads);
    if (info) {
        info->depth = depth;
        info->bound = bound;
        info->rods = ct_bundle_size(b);
        info->omitted = ct_bundle_omitted(b);
        info->u_reach = u_reach;
    }
    *out = b;
    return CT_OK;
}
