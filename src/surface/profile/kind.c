/* The kind "profile" (src/surface/kind.h): a measured profile's keys, its reading and
 * levelling, its rods, and the fitted Cantor surface its outputs compare with (what = compare,
 * bearing; cantact fit). */
#include "surface/kind.h"
#include "profile.h"
#include "number.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char unit_words[] = "m|mm|um|nm";
static const double unit_metres[] = {1.0, 1e-3, 1e-6, 1e-9};

typedef struct {
    char *file;               /* [surface] */
    int unit, x_unit, z_unit; /* indices into unit_words (read only when given) */
    double spacing;           /* one column of heights at this spacing [x unit]; 0: two */
    int detrend;              /* ct_detrend */
    int trim;                 /* 0 none, 1 rq */
    double trim_k;            /* clip at mean + trim_k Rq */
    double H, Hstar;          /* H* = H Rt, or H* [z unit] */
    double E, sigma_y;        /* [material], Pa */
    double band[4];           /* [fit] depth_lo depth_hi [z unit], lag_lo lag_hi [x unit] */
    int dimension;            /* ct_dimension_method */
    /* prepared */
    ct_profile *profile; /* levelled (and trimmed) */
    ct_profile_stats stats;
    ct_layer layer;       /* as built: in units (a power of two of the given ones) */
    ct_layer physical;    /* as given */
    ct_build_units units; /* built per given */
    double band_m[4];     /* the bands in metres (0: the default) */
    ct_profile_fit fit;
    int have_fit, fit_from_impacts;
} profile_config;

#define AT(field) offsetof(profile_config, field)
static const ct_key profile_keys[] = {
    {"surface", "file", CT_KEY_TEXT, 0, 0, CT_KEY_REQUIRED | CT_KEY_FILE, NULL, "must be a path",
     "",
     "the profile: text/CSV (x z, or z with spacing), a Dektak export or an X3P file; relative "
     "to the scene's directory",
     AT(file)},
    {"surface", "unit", CT_KEY_WORD, 0, 0, 0, unit_words, "must be m, mm, um or nm",
     "what the file's column names state", "the file's length unit for x and z", AT(unit)},
    {"surface", "x_unit", CT_KEY_WORD, 0, 0, 0, unit_words, "must be m, mm, um or nm", "unit",
     "the file's unit of x", AT(x_unit)},
    {"surface", "z_unit", CT_KEY_WORD, 0, 0, 0, unit_words, "must be m, mm, um or nm", "unit",
     "the file's unit of z", AT(z_unit)},
    {"surface", "spacing", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL,
     "must be > 0 (one column of heights at this spacing, in x_unit)", "",
     "a file of one column of heights: their spacing [x unit]", AT(spacing)},
    {"surface", "detrend", CT_KEY_WORD, 0, 0, 0, "none|mean|linear|quadratic",
     "must be none, mean, linear or quadratic", "linear",
     "levelling: the least-squares mean, line (plane) or parabola (quadric) removed", AT(detrend)},
    {"surface", "trim", CT_KEY_WORD, 0, 0, 0, "none|rq",
     "must be none or rq (clip at mean + trim_k Rq)", "none",
     "spikes: rq clips heights above mean + trim_k Rq", AT(trim)},
    {"surface", "trim_k", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "3",
     "the clip level of trim = rq, in Rq", AT(trim_k)},
    {"surface", "H", CT_KEY_NUMBER, 1.0, INFINITY, 0, NULL,
     "must satisfy H > 1 (H* = H Rt must exceed the peak-to-valley depth)", "",
     "H* as a multiple of the peak-to-valley depth Rt (or give Hstar)", AT(H)},
    {"surface", "Hstar", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "",
     "H* in the file's z unit (or give H)", AT(Hstar)},
    {"material", "E", CT_KEY_NUMBER, 0.0, INFINITY, CT_KEY_REQUIRED, NULL, "must be > 0", "",
     "Young's modulus [Pa]", AT(E)},
    {"material", "sigma_y", CT_KEY_NUMBER, 0.0, INFINITY, CT_KEY_REQUIRED, NULL, "must be > 0", "",
     "yield stress [Pa]", AT(sigma_y)},
    {"fit", "depth_lo", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0 (in the file's unit)",
     "the 20th highest point", "the bearing fit's shallowest depth [z unit]", AT(band[0])},
    {"fit", "depth_hi", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0 (in the file's unit)",
     "phi = 0.1", "the bearing fit's deepest depth [z unit]", AT(band[1])},
    {"fit", "lag_lo", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0 (in the file's unit)",
     "2 spacings", "the dimension estimators' shortest lag [x unit]", AT(band[2])},
    {"fit", "lag_hi", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0 (in the file's unit)",
     "a tenth of the length", "the dimension estimators' longest lag [x unit]", AT(band[3])},
    {"fit", "dimension", CT_KEY_WORD, 0, 0, 0, "variation|structure|spectrum",
     "must be variation, structure or spectrum", "variation", "the estimate of D that enters Eq. 3",
     AT(dimension)},
};
#undef AT

static void profile_defaults(void *config)
{
    profile_config *c = config;
    c->detrend = CT_DETREND_LINEAR;
    c->dimension = CT_DIM_VARIATION;
}

static void profile_release(void *config)
{
    profile_config *c = config;
    ct_profile_free(c->profile);
    c->profile = NULL;
}

static int profile_check(ct_surface *s, const char *scene)
{
    profile_config *c = s->config;
    if (ct_surface_given(s, "surface", "trim_k") && c->trim != 1)
        return ct_surface_key_error(s, "surface", "trim_k", CT_EINVAL,
                                    "only with surface.trim = rq");
    if (c->trim == 1 && !ct_surface_given(s, "surface", "trim_k"))
        c->trim_k = 3.0;
    if (c->trim == 0)
        c->trim_k = 0.0;
    if (ct_surface_given(s, "surface", "H") == ct_surface_given(s, "surface", "Hstar"))
        return ct_error_set(CT_EINVAL,
                            "%s: type = profile needs one of surface.H (H* as a multiple of the "
                            "peak-to-valley depth) and surface.Hstar (in z_unit)",
                            scene);
    if (!(c->E > c->sigma_y))
        return ct_surface_key_error(s, "material", "E", CT_EINVAL,
                                    "must be > sigma_y (yield strain sigma_y/E < 1)");
    return CT_OK;
}

static const char *detrend_name(int d)
{
    static const char *const names[] = {"none", "mean", "linear", "quadratic"};
    return d >= 0 && d < 4 ? names[d] : "?";
}

static int profile_prepare(ct_surface *s, const char *dir)
{
    profile_config *c = s->config;
    profile_release(c);
    c->have_fit = c->fit_from_impacts = 0;
    ct_profile_read_opts opts = {0.0, 0.0, 0.0}; /* a unit 0: the one the file states */
    if (ct_surface_given(s, "surface", "unit"))
        opts.x_unit = opts.z_unit = unit_metres[c->unit];
    if (ct_surface_given(s, "surface", "x_unit"))
        opts.x_unit = unit_metres[c->x_unit];
    if (ct_surface_given(s, "surface", "z_unit"))
        opts.z_unit = unit_metres[c->z_unit];
    opts.dx = c->spacing;
    char *path = ct_path_join(dir, c->file);
    if (!path)
        return ct_error_set(CT_ENOMEM, "out of memory");
    int st = ct_profile_read_giving(
        path, &opts, "surface.unit (m, mm, um or nm; or surface.x_unit and surface.z_unit)",
        &c->profile);
    free(path);
    if (st)
        return st;
    ct_profile *p = c->profile;
    /* H* and the fit's bands are given in the file's units, known now */
    const double Hstar = c->Hstar * p->z_unit;
    for (int k = 0; k < 4; k++)
        c->band_m[k] = c->band[k] * (k < 2 ? p->z_unit : p->x_unit);
    ct_profile_stats raw = {
        .Rt = ct_profile_heights_span(p)}; /* only Rt is asked of the raw heights */
    size_t clipped = 0;
    if ((st = ct_profile_level(p, c->detrend)) ||
        (c->trim_k > 0.0 && (st = ct_profile_trim(p, c->trim_k, &clipped))) ||
        (st = ct_profile_stats_of(p, &c->stats))) {
        return ct_error_set(st, "%s: %s", c->file, ct_error_message()); /* the file named */
    }
    const ct_profile_stats *q = &c->stats;
    if (!isfinite(raw.Rt) || !isfinite(q->Rt))
        return ct_error_set(CT_EINVAL,
                            "%s: the heights span more than doubles hold (peak to valley %g m "
                            "raw, %g m levelled): state them in a unit that fits",
                            c->file, raw.Rt, q->Rt);
    if (!(q->Rt > 0.0))
        return ct_error_set(CT_EINVAL, "%s: all heights are equal after levelling: no roughness",
                            c->file);
    c->physical = (ct_layer){.E = c->E,
                             .sigma_y = c->sigma_y,
                             .Hstar = Hstar > 0.0 ? Hstar : c->H * q->Rt,
                             .l0 = q->length,
                             .h0 = q->Rt};
    if (!(c->physical.Hstar > q->Rt))
        return ct_error_set(CT_EINVAL,
                            "surface.Hstar = %g m: must exceed the profile's peak-to-valley depth "
                            "Rt = %g m after levelling",
                            c->physical.Hstar, q->Rt);
    /* built in units of metres and pascals times powers of two (ct_build_units_of: metres and
     * pascals for scales within [2^-64, 2^64]), so that e does not depend on the scale */
    ct_build_units_of(&c->physical, p->ny > 1, &c->units);
    if ((st = ct_layer_built(&c->physical, &c->units, &c->layer))) { /* named */
        return ct_error_set(st, "%s: %s; from %zu points at a spacing of %g m, Rt %g m", c->file,
                            ct_error_message(), p->n, p->ny > 1 ? p->dx : q->length / (double)p->n,
                            q->Rt);
    }
    ct_scales_of(&s->scales, &c->layer, &c->physical);
    ct_surface_note_set(s,
                        "%s (%s): %zu points%s, levelled (%s): Rq %.4g m, Rt %.4g m (raw Rt %.4g "
                        "m), l0 %.4g m%s, H* %.4g m",
                        c->file, p->source, p->n, p->ny > 1 ? " on a grid" : "",
                        detrend_name(c->detrend), q->Rq, q->Rt, raw.Rt, q->length,
                        p->ny > 1 ? "^2" : "", c->physical.Hstar);
    size_t n = strlen(s->note);
    if (p->invalid)
        n += (size_t)snprintf(s->note + n, sizeof s->note - n, ", %zu invalid points left out",
                              p->invalid);
    if (c->trim_k > 0.0 && n < sizeof s->note)
        snprintf(s->note + n, sizeof s->note - n, ", %zu heights clipped at mean + %g Rq", clipped,
                 c->trim_k);
    return CT_OK;
}

static int profile_build(const ct_surface *s, const ct_build_request *r, ct_bundle **out,
                         ct_plan_info *info)
{
    const profile_config *c = s->config;
    *out = NULL;
    const ct_layer *g = &c->physical; /* the profile's statistics as it stands */
    int st = ct_profile_bundle_of(out, c->profile, &c->stats, g->E, g->sigma_y, g->Hstar,
                                  r->threads, &c->units);
    if (st)
        return st;
    info->depth = -1;
    info->bound = 0.0;
    info->rods = ct_bundle_size(*out);
    info->omitted = ct_bundle_omitted(*out);
    info->u_reach = INFINITY;
    return CT_OK;
}

/* The fit the outputs compare with: on the bands given, else the defaults (ct_profile_fit_of). */
static int need_fit(ct_surface *s)
{
    profile_config *c = s->config;
    if (c->have_fit)
        return CT_OK;
    c->fit.dimension = (ct_dimension_method)c->dimension;
    const double *b = c->band_m;
    int st = ct_profile_fit_of(c->profile, b[0], b[1], b[2], b[3], &c->fit);
    if (st)
        return st;
    c->have_fit = 1;
    return CT_OK;
}

/* After the sweep, with a fit and no [fit] depth band given: the bearing fit redone on the
 * depths the impacts reached (docs/model.md §9); the default band is kept, and said, when
 * that band holds no fit. */
static int profile_after_sweep(ct_surface *s, const ct_sweep_row *rows, size_t n)
{
    profile_config *c = s->config;
    if (!c->have_fit || c->band_m[0] > 0.0 || c->band_m[1] > 0.0)
        return CT_OK;
    double *u = malloc((n ? n : 1) * sizeof *u);
    if (!u)
        return ct_error_set(CT_ENOMEM, "fit: out of memory");
    for (size_t k = 0; k < n; k++) /* in metres */
        u[k] = rows[k].status ? NAN : rows[k].r.u_max / c->units.length;
    ct_profile_fit f;
    int st = ct_profile_fit_on_reach(c->profile, &c->fit, u, n, &f);
    free(u);
    if (st == CT_ENOMEM)
        return st;
    if (st) {
        ct_surface_note_set(s, "fit: %s: the default band kept", ct_error_message());
        return CT_OK;
    }
    static const char *const names[] = {"variation", "structure", "spectrum"};
    c->fit = f;
    c->fit_from_impacts = 1;
    ct_surface_note_set(s,
                        "fit on the depths the impacts reach, %.4g .. %.4g m: alpha %.4g, h0 "
                        "%.4g m, D %.4g (%s), fx %.4g, fz %.4g",
                        f.bearing.lo, f.bearing.hi, f.alpha, f.h0, f.D,
                        names[f.dimension - CT_DIM_VARIATION], f.fx, f.fz);
    return CT_OK;
}

static const char *const fit_e_names[] = {"e_cantor_fit", "e_asymptotic_fit", "V_star_cantor_fit"};

/* For every first impact: e of the fitted Cantor surface (exact rods, fractal depth), of the
 * asymptotic law with the fitted parameters, and the fitted surface's V*, at the row's energy. */
static int profile_compare(ct_surface *s, const ct_sweep_row *rows, size_t n, double *out)
{
    profile_config *c = s->config;
    int st = need_fit(s);
    if (st)
        return st;
    double *W = malloc((n ? n : 1) * 4 * sizeof(double));
    if (!W)
        return ct_error_set(CT_ENOMEM, "compare: out of memory");
    double *ef = W + n, *ea = ef + n, *vf = ea + n;
    const ct_build_units *un = &c->units; /* the energies in joules (per metre) */
    for (size_t k = 0; k < n; k++)
        W[k] = !rows[k].status && rows[k].impact == 1
                   ? rows[k].r.kinetic_energy / un->length / un->area / un->stress
                   : NAN;
    st = ct_profile_fitted_e(c->profile, &c->fit, &c->physical, W, n, 0, ef, ea, vf);
    for (size_t k = 0; k < n && !st; k++) {
        out[3 * k] = ef[k];
        out[3 * k + 1] = ea[k];
        out[3 * k + 2] = vf[k];
    }
    free(W);
    return st;
}

static int profile_ready(ct_surface *s, const char *output)
{
    if (!strcmp(output, "compare") || !strcmp(output, "bearing") || !strcmp(output, "fit"))
        return need_fit(s);
    return CT_OK;
}

/* what = bearing: phi(d) on 400 depths log-spaced from 1e-4 Rt to Rt, beside the fit. */
static int profile_write_bearing(const ct_surface *s, FILE *f)
{
    const profile_config *c = s->config;
    if (!c->have_fit)
        return ct_error_set(CT_EINVAL, "bearing: the profile has not been fitted");
    const ct_profile_fit *fit = &c->fit;
    const double Rt = fit->stats.Rt;
    enum { N = 400 };
    double d[N], phi[N];
    for (int k = 0; k < N; k++)
        d[k] = Rt * pow(1e-4, 1.0 - (double)k / (N - 1));
    int st = ct_profile_bearing(c->profile, N, d, phi);
    if (st)
        return st;
    fprintf(f,
            "# bearing fit: phi = (d / h0)^alpha, alpha = %.6g, h0 = %.6g m, on d in [%.4g, "
            "%.4g] m (%s; %zu points, R^2 %.4f, rms residual %.3g in ln phi)\n",
            fit->alpha, fit->h0, fit->bearing.lo, fit->bearing.hi,
            c->band_m[0] > 0.0 || c->band_m[1] > 0.0 ? "the band given"
            : c->fit_from_impacts                    ? "the depths the impacts reach"
                                                     : "the default band",
            fit->bearing.n, fit->bearing.r2, fit->bearing.residual);
    fprintf(f,
            "# Cantor fit (Eq. 3): D = %.17g, fx = %.17g, fz = %.17g, h0 = %.17g m, l0 = %.17g m\n",
            fit->D, fit->fx, fit->fz, fit->h0, fit->l0);
    fputs("d_m,d_over_Rt,phi,phi_fit\n", f);
    for (int k = 0; k < N; k++) {
        const double pf = d[k] < fit->h0 ? pow(d[k] / fit->h0, fit->alpha) : 1.0;
        ct_put_double(f, d[k]);
        fputc(',', f);
        ct_put_double(f, d[k] / Rt);
        fputc(',', f);
        ct_put_double(f, phi[k]);
        fputc(',', f);
        ct_put_double(f, pf);
        fputc('\n', f);
    }
    return CT_OK;
}

/* what = profile: the heights after levelling (a grid: x, y, z of the valid points). */
static int profile_write_levelled(const ct_surface *s, const ct_bundle *b, FILE *f)
{
    (void)b;
    const ct_profile *p = ((const profile_config *)s->config)->profile;
    if (p->ny > 1) {
        fputs("x_m,y_m,z_m\n", f);
        for (size_t j = 0; j < p->nx * p->ny; j++) {
            if (isnan(p->z[j]))
                continue;
            ct_put_double(f, (double)(j % p->nx) * p->dx);
            fputc(',', f);
            ct_put_double(f, (double)(j / p->nx) * p->dy);
            fputc(',', f);
            ct_put_double(f, p->z[j]);
            fputc('\n', f);
        }
        return CT_OK;
    }
    fputs("x_m,z_m\n", f);
    for (size_t j = 0; j < p->nx; j++) {
        ct_put_double(f, p->x ? p->x[j] : (double)j * p->dx);
        fputc(',', f);
        ct_put_double(f, p->z[j]);
        fputc('\n', f);
    }
    return CT_OK;
}

static int profile_write_fit(ct_surface *s, FILE *f)
{
    int st = need_fit(s);
    if (st)
        return st;
    const profile_config *c = s->config;
    return ct_profile_fit_write(f, &c->fit, c->profile->source, c->profile->n);
}

int ct_surface_profile(const ct_surface *s, const ct_profile **p, ct_profile_fit *fit)
{
    CT_NEED(s);
    if (s->kind != &ct_kind_profile || !s->prepared)
        return ct_error_set(CT_EINVAL, "surface %s: not a prepared profile", s->kind->name);
    const profile_config *c = s->config;
    if (p)
        *p = c->profile;
    if (fit && !c->have_fit)
        return ct_error_set(CT_EINVAL, "the profile has not been fitted");
    if (fit)
        *fit = c->fit;
    return CT_OK;
}

static void profile_describe(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    (void)s;
    snprintf(buf, len, "measured surface, %zu rods", info->rods);
}

static void profile_table_line(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    const profile_config *c = s->config;
    const ct_layer *L = &c->physical;
    snprintf(buf, len,
             "profile: %s (%s), %zu rods, l0 = %.17g m, h0 = Rt = %.17g m, H* = %.17g m, E = "
             "%.17g Pa, sigma_y = %.17g Pa, detrend %s",
             c->file, c->profile->source, info->rods, L->l0, L->h0, L->Hstar, L->E, L->sigma_y,
             detrend_name(c->detrend));
}

const ct_kind ct_kind_profile = {
    .name = "profile",
    .summary = "a measured line profile or areal topography (text, Dektak, X3P), one rod per "
               "sample",
    .keys = profile_keys,
    .nkeys = sizeof profile_keys / sizeof profile_keys[0],
    .config_size = sizeof(profile_config),
    .defaults = profile_defaults,
    .check = profile_check,
    .prepare = profile_prepare,
    .build = profile_build,
    .release = profile_release,
    .ready = profile_ready,
    .describe = profile_describe,
    .table_line = profile_table_line,
    .write_profile = profile_write_levelled,
    .ncompare = 3,
    .compare_names = fit_e_names,
    .compare = profile_compare,
    .after_sweep = profile_after_sweep,
    .write_bearing = profile_write_bearing,
    .write_fit = profile_write_fit,
};
