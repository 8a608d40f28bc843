/* Measured surfaces in the CLI (type = profile): reading and levelling the profile, its rods,
 * the fitted Cantor surface beside it (what = compare, bearing), the levelled profile (what =
 * profile), and `cantact fit`. Units: the profile is read in metres (the scene's unit keys
 * convert it), E and sigma_y in Pa; the surface's l0 is its length (a line, per unit depth) or
 * area (a grid), its h0 the peak-to-valley depth Rt, so V* = sqrt(m v^2 / (2 l0 E h0)). */
#include "measured.h"

#include "number.h"
#include "output.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The CLI's own errors here (the library's ct_error_set is not exported): the message of the
 * last failure, this file's or the library's. */
static char message[512];
static int own_message;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int
cli_error(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    own_message = 1;
    return status;
}

const char *ct_cli_measured_message(void)
{
    return own_message ? message : ct_error_message();
}

int ct_cli_profile_prepare(ct_scene *sc, int quiet)
{
    own_message = 0;
    char *path = NULL;
    const char *file = sc->profile_file;
    if (file[0] != '/' && sc->scene_dir) {
        size_t n = strlen(sc->scene_dir) + strlen(file) + 1;
        if (!(path = malloc(n)))
            return cli_error(CT_ENOMEM, "out of memory");
        snprintf(path, n, "%s%s", sc->scene_dir, file);
        file = path;
    }
    int st = ct_profile_read(file, &sc->read_opts, &sc->profile);
    free(path);
    if (st)
        return st;
    ct_profile *p = sc->profile;
    /* H* and the fit's bands are given in the file's units, known now */
    sc->Hstar_given *= p->z_unit;
    for (int k = 0; k < 4; k++)
        sc->fit_band[k] *= k < 2 ? p->z_unit : p->x_unit;
    ct_profile_stats raw, s;
    size_t clipped = 0;
    if ((st = ct_profile_stats_of(p, &raw)) || (st = ct_profile_level(p, sc->detrend)) ||
        (sc->trim_k > 0.0 && (st = ct_profile_trim(p, sc->trim_k, &clipped))) ||
        (st = ct_profile_stats_of(p, &s)))
        return st;
    if (!(s.Rt > 0.0))
        return cli_error(CT_EINVAL, "%s: all heights are equal after levelling: no roughness",
                         sc->profile_file);
    ct_params *q = &sc->params;
    q->h0 = s.Rt;
    q->l0 = s.length;
    q->Hstar = sc->Hstar_given > 0.0 ? sc->Hstar_given : sc->H_over_Rt * s.Rt;
    if (!(q->Hstar > s.Rt))
        return cli_error(CT_EINVAL,
                         "surface.Hstar = %g m: must exceed the profile's peak-to-valley depth "
                         "Rt = %g m after levelling",
                         q->Hstar, s.Rt);
    sc->physical = *q;
    if (sc->speeds_are_velocities) { /* V* = sqrt(m / (2 l0 E h0)) v with this l0 and h0 */
        const double f = sqrt(sc->mass / (2.0 * q->l0 * q->E * q->h0));
        for (size_t k = 0; k < sc->nvel; k++) {
            sc->V_star[k] *= f;
            double W = sc->V_star[k] * sc->V_star[k] * q->l0 * q->E * q->h0;
            if (!(isfinite(W) && W > 0.0))
                return cli_error(CT_EINVAL,
                                 "impact.velocity (value %zu) gives an impact energy %g on "
                                 "this profile: not a finite number > 0",
                                 k + 1, W);
        }
        sc->speeds_are_velocities = 0;
    }
    if (!quiet) {
        fprintf(stderr,
                "cantact: %s (%s): %zu points%s, levelled (%s): Rq %.4g m, Rt %.4g m (raw Rt "
                "%.4g m), l0 %.4g m%s, H* %.4g m",
                sc->profile_file, p->source, p->n, p->ny > 1 ? " on a grid" : "",
                sc->detrend == CT_DETREND_NONE     ? "none"
                : sc->detrend == CT_DETREND_MEAN   ? "mean"
                : sc->detrend == CT_DETREND_LINEAR ? "linear"
                                                   : "quadratic",
                s.Rq, s.Rt, raw.Rt, s.length, p->ny > 1 ? "^2" : "", q->Hstar);
        if (p->invalid)
            fprintf(stderr, ", %zu invalid points left out", p->invalid);
        if (sc->trim_k > 0.0)
            fprintf(stderr, ", %zu heights clipped at mean + %g Rq", clipped, sc->trim_k);
        fputc('\n', stderr);
    }
    if (sc->what & (CT_OUT_COMPARE | CT_OUT_BEARING)) {
        const double *b = sc->fit_band;
        sc->fit.dimension = sc->fit_dimension;
        if ((st = ct_profile_fit_of(p, b[0], b[1], b[2], b[3], &sc->fit)))
            return st;
        sc->have_fit = 1;
    }
    return CT_OK;
}

int ct_cli_profile_bundle(const ct_scene *sc, ct_bundle **b, ct_plan_info *info)
{
    int st = ct_profile_bundle(b, sc->profile, sc->params.E, sc->params.sigma_y, sc->params.Hstar);
    if (st)
        return st;
    ct_bundle_set_threads(*b, sc->threads);
    info->depth = -1;
    info->bound = 0.0;
    info->rods = ct_bundle_size(*b);
    info->omitted = ct_bundle_omitted(*b);
    info->u_reach = INFINITY;
    return CT_OK;
}

/* The fitted Cantor surface in dimensionless form (l0 = h0 = sigma_y = 1) with the scene's
 * layer: H* / h0_fit, E / sigma_y. CT_ERANGE when the fit leaves Eq. 3's ranges. */
static int fitted_params(const ct_scene *sc, ct_params *c)
{
    const ct_profile_fit *f = &sc->fit;
    *c = (ct_params){.fx = f->fx,
                     .fz = f->fz,
                     .l0 = 1.0,
                     .h0 = 1.0,
                     .Hstar = sc->params.Hstar / f->h0,
                     .E = sc->params.E / sc->params.sigma_y,
                     .sigma_y = 1.0};
    if (ct_params_validate(c))
        return cli_error(CT_ERANGE,
                         "the fitted Cantor surface (fx %g, fz %g, H*/h0 %g) is outside the "
                         "model's ranges: %s",
                         f->fx, f->fz, c->Hstar, ct_error_message());
    return CT_OK;
}

int ct_cli_profile_compare(const ct_scene *sc, const ct_sweep_row *rows, size_t nrows, double *out)
{
    own_message = 0;
    for (size_t k = 0; k < 3 * nrows; k++)
        out[k] = NAN;
    ct_params c;
    int st = fitted_params(sc, &c);
    if (st)
        return st;
    /* the impact energy per unit depth (a grid's over its extent in y) in the fitted surface's
     * units: W / (sigma_y l0_fit h0_fit), so V*_fit = sqrt(W / (l0_fit E h0_fit)) */
    const ct_profile *p = sc->profile;
    const double depth = p->ny > 1 ? (double)p->ny * p->dy : 1.0;
    const double scale = sc->fit.l0 * sc->params.E * sc->fit.h0;
    double *V = malloc((nrows ? nrows : 1) * sizeof(double));
    ct_sweep_row *cr = malloc((nrows ? nrows : 1) * sizeof *cr);
    size_t m = 0;
    if (!V || !cr) {
        free(V);
        free(cr);
        return cli_error(CT_ENOMEM, "compare: out of memory");
    }
    for (size_t k = 0; k < nrows; k++)
        if (!rows[k].status && rows[k].impact == 1)
            V[m++] = sqrt(rows[k].r.kinetic_energy / depth / scale);
    if (m) {
        ct_cantor_plan plan = {.params = c,
                               .depth = CT_DEPTH_FRACTAL,
                               .representation = CT_REP_STAGES,
                               .depth_tolerance = 1e-12,
                               .V_star = V,
                               .nvel = m,
                               .impacts = 1,
                               .threads = sc->threads};
        ct_impact_opts_default(&plan.opts);
        ct_bundle *b;
        ct_plan_info info;
        if (!(st = ct_cantor_plan_build(&plan, &b, &info))) {
            ct_sweep_spec spec = {.V_star = V, .nvel = m, .impacts = 1, .opts = plan.opts};
            st = ct_sweep(b, &spec, cr);
            ct_bundle_free(b);
        }
    }
    size_t q = 0;
    for (size_t k = 0; k < nrows && !st; k++) {
        if (rows[k].status || rows[k].impact != 1)
            continue;
        out[3 * k + 2] = V[q];
        if (!cr[q].status)
            out[3 * k] = cr[q].r.e;
        double um, e;
        if (ct_law_impact(&c, CT_LAW_ASYMPTOTIC, V[q] * V[q] * c.E, &um, &e) == CT_OK)
            out[3 * k + 1] = e;
        q++;
    }
    free(V);
    free(cr);
    return st;
}

int ct_cli_profile_refit(ct_scene *sc, const ct_sweep_row *rows, size_t nrows, int quiet)
{
    own_message = 0;
    if (!sc->have_fit || sc->fit_band[0] > 0.0 || sc->fit_band[1] > 0.0)
        return CT_OK; /* no fit, or its depths given */
    double lo = INFINITY, hi = 0.0;
    for (size_t k = 0; k < nrows; k++)
        if (!rows[k].status) {
            lo = fmin(lo, rows[k].r.u_max);
            hi = fmax(hi, rows[k].r.u_max);
        }
    /* from the shallowest reach (not above the default band's start, the 20th highest
     * point: above it the curve is a few samples) to the deepest (not below Rt) */
    lo = fmax(lo, sc->fit.bearing.lo);
    hi = fmin(hi, sc->fit.stats.Rt);
    ct_profile_fit f = sc->fit;
    if (!(hi > lo) || ct_profile_fit_bearing(sc->profile, lo, hi, &f)) {
        if (!quiet)
            fprintf(stderr,
                    "cantact: fit: the depths the impacts reach, %.4g .. %.4g m, give no bearing "
                    "fit (%s): the default band kept\n",
                    lo, hi, hi > lo ? ct_error_message() : "an empty band");
        return CT_OK;
    }
    sc->fit = f;
    sc->fit_band_from_impacts = 1;
    if (!quiet)
        fprintf(stderr,
                "cantact: fit on the depths the impacts reach, %.4g .. %.4g m: alpha %.4g, h0 "
                "%.4g m, D %.4g (%s), fx %.4g, fz %.4g\n",
                f.bearing.lo, f.bearing.hi, f.alpha, f.h0, f.D,
                f.dimension == CT_DIM_STRUCTURE  ? "structure"
                : f.dimension == CT_DIM_SPECTRUM ? "spectrum"
                                                 : "variation",
                f.fx, f.fz);
    return CT_OK;
}

int ct_cli_write_bearing(FILE *f, const ct_scene *sc)
{
    const ct_profile_fit *fit = &sc->fit;
    const double Rt = fit->stats.Rt;
    enum { N = 400 };
    double d[N], phi[N];
    for (int k = 0; k < N; k++) /* log-spaced from 1e-4 Rt to Rt */
        d[k] = Rt * pow(1e-4, 1.0 - (double)k / (N - 1));
    int st = ct_profile_bearing(sc->profile, N, d, phi);
    if (st)
        return st;
    fprintf(f,
            "# bearing fit: phi = (d / h0)^alpha, alpha = %.6g, h0 = %.6g m, on d in [%.4g, "
            "%.4g] m (%s; %zu points, R^2 %.4f, rms residual %.3g in ln phi)\n",
            fit->alpha, fit->h0, fit->bearing.lo, fit->bearing.hi,
            sc->fit_band[0] > 0.0 || sc->fit_band[1] > 0.0 ? "the band given"
            : sc->fit_band_from_impacts                    ? "the depths the impacts reach"
                                                           : "the default band",
            fit->bearing.n, fit->bearing.r2, fit->bearing.residual);
    fprintf(f,
            "# Cantor fit (Eq. 3): D = %.17g, fx = %.17g, fz = %.17g, h0 = %.17g m, l0 = %.17g m\n",
            fit->D, fit->fx, fit->fz, fit->h0, fit->l0);
    fputs("d_m,d_over_Rt,phi,phi_fit\n", f);
    for (int k = 0; k < N; k++) {
        double pf = d[k] < fit->h0 ? pow(d[k] / fit->h0, fit->alpha) : 1.0;
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

int ct_cli_write_levelled(FILE *f, const ct_scene *sc)
{
    const ct_profile *p = sc->profile;
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

static void fit_row(FILE *f, const char *name, double value, const ct_fit_line *l)
{
    fprintf(f, "%s,", name);
    ct_put_double(f, value);
    if (l)
        fprintf(f, ",%.6g,%.6g,%zu,%.6f,%.4g\n", l->lo, l->hi, l->n, l->r2, l->residual);
    else
        fputs(",,,,,\n", f);
}

void ct_cli_write_fit(FILE *f, const ct_profile_fit *fit, const char *source, size_t n)
{
    static const char *const names[] = {"variation", "structure", "spectrum"};
    const ct_fit_line *used = fit->dimension == CT_DIM_STRUCTURE  ? &fit->structure
                              : fit->dimension == CT_DIM_SPECTRUM ? &fit->spectrum
                                                                  : &fit->variation;
    fprintf(f,
            "# %s: %zu points; bands: bearing depths [m], variation window widths and "
            "structure-function lags [m], spectrum wavenumbers [1/m]; D (into Eq. 3) from the "
            "%s estimate\n",
            source, n, names[fit->dimension - CT_DIM_VARIATION]);
    fputs("quantity,value,band_lo,band_hi,points,r2,rms_residual_ln\n", f);
    fit_row(f, "Rq_m", fit->stats.Rq, NULL);
    fit_row(f, "Ra_m", fit->stats.Ra, NULL);
    fit_row(f, "Rt_m", fit->stats.Rt, NULL);
    fit_row(f, "alpha", fit->alpha, &fit->bearing);
    fit_row(f, "h0_m", fit->h0, &fit->bearing);
    fit_row(f, "D_variation", fit->D_variation, &fit->variation);
    fit_row(f, "D_structure", fit->D_structure, &fit->structure);
    fit_row(f, "D_spectrum", fit->D_spectrum, &fit->spectrum);
    fit_row(f, "D", fit->D, used);
    fit_row(f, "fx", fit->fx, NULL);
    fit_row(f, "fz", fit->fz, NULL);
    fit_row(f, "l0_m", fit->l0, NULL);
}

static const char *fit_help =
    "Usage: cantact fit PROFILE [options]\n"
    "       cantact fit SCENE.ini [--set section.key=value]... [-o FILE]\n"
    "\n"
    "Levels a measured profile (text/CSV, Dektak export or X3P) and fits the Cantor surface it\n"
    "looks like (MODEL.md section 9): Rq, Ra, Rt; alpha and h0 from the bearing-area curve\n"
    "phi(d) = (d / h0)^alpha; D from the variation (box-counting) method, the structure\n"
    "function S(tau) ~ tau^(2 (2 - D)) and the power spectrum C(q) ~ q^-(5 - 2D) (all three\n"
    "reported, one used); then fx, fz by Eq. 3 and l0.\n"
    "Writes CSV: quantity,value,band_lo,band_hi,points,r2,rms_residual_ln (lengths in m).\n"
    "\n"
    "Options (with a PROFILE; a scene gives them as [surface] and [fit] keys):\n"
    "  --unit U        the file's length unit for x and z: m, mm, um, nm (default: the one\n"
    "                  its column names state, as a Dektak export's do; X3P: none, metres)\n"
    "  --x-unit U, --z-unit U   each on its own\n"
    "  --spacing DX    one column of heights at spacing DX (in the x unit)\n"
    "  --detrend D     none, mean, linear (default), quadratic\n"
    "  --trim K        clip heights above mean + K Rq (spikes; default: none)\n"
    "  --dimension M   the D that enters Eq. 3: variation (default), structure, spectrum\n"
    "  --depths A:B    the bearing fit's depth band in the z unit (default: from the 20th\n"
    "                  highest point to where phi = 0.1)\n"
    "  --lags A:B      the lag band of the dimension estimators in the x unit (default: 2\n"
    "                  spacings to a tenth of the length)\n"
    "  -o FILE         write the table there ('-': stdout, the default)\n"
    "  -h, --help      this help\n";

static int band_arg(const char *s, double *lo, double *hi)
{
    char *end;
    *lo = strtod(s, &end);
    if (end == s || *end != ':')
        return -1;
    const char *t = end + 1;
    *hi = strtod(t, &end);
    return end == t || *end || !(*lo > 0.0) || !(*hi > *lo) ? -1 : 0;
}

static double unit_arg(const char *s)
{
    return !strcmp(s, "m")    ? 1.0
           : !strcmp(s, "mm") ? 1e-3
           : !strcmp(s, "um") ? 1e-6
           : !strcmp(s, "nm") ? 1e-9
                              : 0.0;
}

int ct_cli_fit_main(int argc, char **argv)
{
    const char *input = NULL, *out_path = "-";
    const char **sets = calloc((size_t)argc + 1, sizeof *sets);
    size_t nsets = 0;
    double xu = 0.0, zu = 0.0, dx = 0.0, trim = 0.0, band[4] = {0, 0, 0, 0};
    int detrend = CT_DETREND_LINEAR, dimension = CT_DIM_VARIATION, file_opts = 0;
    if (!sets) {
        fputs("cantact: out of memory\n", stderr);
        return 1;
    }
#define NEED_VALUE()                                                                               \
    do {                                                                                           \
        if (k + 1 >= argc) {                                                                       \
            fprintf(stderr, "cantact: fit: %s needs a value\n", a);                                \
            free(sets);                                                                            \
            return 2;                                                                              \
        }                                                                                          \
    } while (0)
    for (int k = 0; k < argc; k++) {
        const char *a = argv[k];
        int bad = 0;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fputs(fit_help, stdout);
            free(sets);
            return 0;
        } else if (!strcmp(a, "-o")) {
            NEED_VALUE();
            out_path = argv[++k];
        } else if (!strcmp(a, "--set")) {
            NEED_VALUE();
            sets[nsets++] = argv[++k];
        } else if (!strcmp(a, "--unit") || !strcmp(a, "--x-unit") || !strcmp(a, "--z-unit")) {
            NEED_VALUE();
            double u = unit_arg(argv[++k]);
            bad = !(u > 0.0);
            if (strcmp(a, "--z-unit"))
                xu = u;
            if (strcmp(a, "--x-unit"))
                zu = u;
            file_opts = 1;
        } else if (!strcmp(a, "--spacing")) {
            NEED_VALUE();
            char *end;
            dx = strtod(argv[++k], &end);
            bad = *end || !(dx > 0.0) || !isfinite(dx);
            file_opts = 1;
        } else if (!strcmp(a, "--detrend")) {
            NEED_VALUE();
            const char *v = argv[++k];
            detrend = !strcmp(v, "none")        ? 0
                      : !strcmp(v, "mean")      ? 1
                      : !strcmp(v, "linear")    ? 2
                      : !strcmp(v, "quadratic") ? 3
                                                : -1;
            bad = detrend < 0;
            file_opts = 1;
        } else if (!strcmp(a, "--trim")) {
            NEED_VALUE();
            char *end;
            trim = strtod(argv[++k], &end);
            bad = *end || !(trim > 0.0) || !isfinite(trim);
            file_opts = 1;
        } else if (!strcmp(a, "--dimension")) {
            NEED_VALUE();
            dimension = ct_scene_dimension_of(argv[++k]);
            bad = dimension < 0;
            file_opts = 1;
        } else if (!strcmp(a, "--depths") || !strcmp(a, "--lags")) {
            NEED_VALUE();
            int i = !strcmp(a, "--lags") ? 2 : 0;
            bad = band_arg(argv[++k], &band[i], &band[i + 1]) != 0;
            file_opts = 1;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "cantact: fit: unknown option %s (see cantact fit --help)\n", a);
            free(sets);
            return 2;
        } else if (!input) {
            input = a;
        } else {
            fprintf(stderr, "cantact: fit: one input, got %s and %s\n", input, a);
            free(sets);
            return 2;
        }
        if (bad) {
            fprintf(stderr, "cantact: fit: %s %s: not a valid value (see cantact fit --help)\n", a,
                    argv[k]);
            free(sets);
            return 2;
        }
    }
#undef NEED_VALUE
    if (!input) {
        fputs("cantact: fit: missing PROFILE or SCENE.ini (see cantact fit --help)\n", stderr);
        free(sets);
        return 2;
    }
    ct_scene sc;
    const size_t len = strlen(input);
    const int scene = len > 4 && !strcmp(input + len - 4, ".ini");
    int st;
    if (scene) {
        if (file_opts) {
            fputs("cantact: fit: with a scene, give the profile's options as its keys (--set)\n",
                  stderr);
            free(sets);
            return 2;
        }
        st = ct_scene_load(&sc, input, sets, nsets);
        free(sets);
        if (st) {
            fprintf(stderr, "cantact: %s\n", ct_scene_message());
            return 2;
        }
        if (sc.surface_type != CT_SURFACE_PROFILE) {
            fprintf(stderr, "cantact: fit: %s: surface.type must be profile\n", input);
            ct_scene_free(&sc);
            return 2;
        }
        sc.speeds_are_velocities = 0; /* the fit needs no speeds */
    } else {
        free(sets);
        memset(&sc, 0, sizeof sc);
        sc.surface_type = CT_SURFACE_PROFILE;
        if (!(sc.profile_file = strdup(input))) {
            fputs("cantact: out of memory\n", stderr);
            return 1;
        }
        sc.read_opts = (ct_profile_read_opts){xu, zu, dx};
        sc.detrend = (ct_detrend)detrend;
        sc.trim_k = trim;
        sc.H_over_Rt = 2.0; /* no rods are built: any layer will do */
        sc.params.E = 2.0;
        sc.params.sigma_y = 1.0;
        memcpy(sc.fit_band, band, sizeof band);
        sc.fit_dimension = (ct_dimension_method)dimension;
    }
    sc.what |= CT_OUT_BEARING; /* fit it */
    char err[512];
    ct_out out;
    if (ct_out_open(&out, out_path, err, sizeof err)) {
        fprintf(stderr, "cantact: %s\n", err);
        ct_scene_free(&sc);
        return 2;
    }
    if ((st = ct_cli_profile_prepare(&sc, 1))) {
        fprintf(stderr, "cantact: %s\n", ct_cli_measured_message());
        ct_out_abort(&out);
        ct_scene_free(&sc);
        return st == CT_EINVAL || st == CT_EIO || st == CT_ERANGE ? 2 : 1;
    }
    ct_cli_write_fit(out.f, &sc.fit, sc.profile->source, sc.profile->n);
    ct_scene_free(&sc);
    if (ct_out_commit(&out, err, sizeof err)) {
        fprintf(stderr, "cantact: %s\n", err);
        return 2;
    }
    return 0;
}
