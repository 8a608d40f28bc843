/* The kind "cantor" (docs/model.md §1-2): its keys, checks, rods (planned by cantor_rods.c)
 * and the outputs only it gives. The geometry of Eqs. 1-3, 16-18, 28 is src/laws/geometry.c's. */
#include "kind.h"

#include <float.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

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

const ct_kind ct_kind_cantor = {
    .name = "cantor",
    .summary = "the deterministic Cantor prefractal of the paper, one rod per stage or per piece",
    .keys = cantor_keys,
    .nkeys = sizeof cantor_keys / sizeof cantor_keys[0],
    .config_size = sizeof(cantor_config),
    .defaults = cantor_defaults,
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
