/* Error against run time (issue 6): every way cantact can give e for one scene, side by
 * side. Scene: fx = 1.5, fz = 1.3, H* / h0 = 10, E/sigma_y = 500, one impact at V* = 1e-3
 * (u_max/h0 = 0.088, twelve times V*_c).
 *
 * Methods: the asymptotic law (printed and consistent Eq. 38), the series, stage rods at the
 * auto depth (1e-12) and at the fractal depth, segment rods at depths 8, 10, ..., 26; the rod
 * methods with the exact breakpoint rule and with the composite rules (trapezoid, Simpson,
 * 3-point Gauss) at K = 8 ... 4096 nodes.
 *
 * Reference: e_ref = e of stage rods at the fractal depth from the closed-form energies
 * (no quadrature). P error: max over u_j = j u_ref / 64 (j = 1..64, u_ref its u_max) of
 * |P(u_j) - P_ref(u_j)| / P_ref(u_ref), virgin loading.
 *
 * Timing: one impact on a built bundle (reset + ct_impact); a warm-up, then `runs` timed
 * runs (each repeating the call until it lasts >= 10 ms), median per call. The bundle's
 * construction is timed once (build_seconds). A configuration predicted to take longer than
 * the budget (seconds for warm-up + runs) is skipped and listed as such.
 *
 * Usage: bench_methods [--quick] [--budget SECONDS] [--runs N]
 * CSV on stdout, '#' lines are comments. */
#include "cantact.h"
#include "internal.h"
#include "common.h"

#include <math.h>

#define SAMPLES 64

static const ct_params P = {
    .fx = 1.5, .fz = 1.3, .l0 = 1.0, .h0 = 1.0, .Hstar = 10.0, .E = 500.0, .sigma_y = 1.0};
static const double V_STAR = 1e-3;

static int runs = 5;
static double e_ref, u_ref, P_ref[SAMPLES];

static void fail(const char *what)
{
    fprintf(stderr, "bench_methods: %s: %s\n", what, ct_error_message());
    exit(1);
}

typedef int (*job_fn)(void *ctx, double *e);

/* Median seconds per call over `runs` runs after one warm-up run. */
static int time_job(job_fn job, void *ctx, double *e, double *median)
{
    double t[64];
    int calls = 1, st;
    for (;;) { /* warm-up, and find how many calls make 10 ms */
        double t0 = bench_now();
        for (int c = 0; c < calls; c++)
            if ((st = job(ctx, e)))
                return st;
        if (bench_now() - t0 >= 0.01 || calls >= (1 << 20))
            break;
        calls *= 2;
    }
    for (int r = 0; r < runs; r++) {
        double t0 = bench_now();
        for (int c = 0; c < calls; c++)
            if ((st = job(ctx, e)))
                return st;
        t[r] = (bench_now() - t0) / calls;
    }
    *median = bench_median(t, runs);
    return CT_OK;
}

typedef struct {
    ct_law law;
    double W;
} law_ctx;

static int law_job(void *ctx, double *e)
{
    law_ctx *c = ctx;
    double u;
    return ct_law_impact(&P, c->law, c->W, &u, e);
}

typedef struct {
    ct_bundle *b;
    ct_impact_opts opts;
    double W;
    int closed;
} rod_ctx;

static int rod_job(void *ctx, double *e)
{
    rod_ctx *c = ctx;
    ct_impact_result r;
    ct_bundle_reset(c->b);
    int st = ct_impact(c->b, c->W, &c->opts, &r);
    *e = c->closed ? r.e_closed : r.e;
    return st;
}

static double p_error_law(ct_law law)
{
    double worst = 0.0;
    for (int j = 0; j < SAMPLES; j++) {
        double u = u_ref * (j + 1) / SAMPLES;
        double Pu;
        if (law == CT_LAW_SERIES ? ct_series_load(&P, u, &Pu) : ct_asym_load(&P, u, &Pu))
            fail(ct_law_name(law));
        worst = fmax(worst, fabs(Pu - P_ref[j]) / P_ref[SAMPLES - 1]);
    }
    return worst;
}

static void sample_u(double *u)
{
    for (int j = 0; j < SAMPLES; j++)
        u[j] = u_ref * (j + 1) / SAMPLES;
}

static double p_error_rods(ct_bundle *b)
{
    double u[SAMPLES], Pu[SAMPLES], worst = 0.0;
    sample_u(u);
    ct_bundle_reset(b);
    if (ct_bundle_force_many(b, u, SAMPLES, Pu))
        fail("force");
    for (int j = 0; j < SAMPLES; j++)
        worst = fmax(worst, fabs(Pu[j] - P_ref[j]) / P_ref[SAMPLES - 1]);
    return worst;
}

static void row(const char *method, long depth, size_t rods, const char *rule, size_t nodes,
                int threads, double build, double t, double e, double perr, const char *note)
{
    printf("%s,%ld,%zu,%s,%zu,%d,%.6g,%.6g,%d,%.17g,%.3g,%.3g,%s\n", method, depth, rods, rule,
           nodes, threads, build, t, runs, e, fabs(e - e_ref), perr, note);
    fflush(stdout);
}

static void skipped(const char *method, long depth, size_t rods, const char *rule, size_t nodes,
                    int threads, double build, double predicted, double perr)
{
    char note[96];
    snprintf(note, sizeof note, "skipped: predicted %.3g s per call", predicted);
    printf("%s,%ld,%zu,%s,%zu,%d,%.6g,,0,,,%.3g,%s\n", method, depth, rods, rule, nodes, threads,
           build, perr, note);
    fflush(stdout);
}

/* Breakpoints of b's load curve in [lo, hi], ends included. */
static size_t curve_points_in(const ct_bundle *b, double lo, double hi)
{
    ct_curve *c;
    if (ct_curve_alloc(&c) || ct_curve_build(c, b))
        fail("curve");
    const double *x = ct_curve_points(c);
    size_t n = 2;
    for (size_t k = 0; k < ct_curve_size(c); k++)
        n += x[k] > lo && x[k] < hi;
    ct_curve_free(c);
    return n;
}

typedef struct {
    const ct_bundle *b;
    const ct_curve *c;
    ct_impact_opts opts;
    double W;
} curve_ctx;

/* One more speed on a surface whose load curve is built: what each speed of a sweep costs. */
static int curve_job(void *ctx, double *e)
{
    curve_ctx *c = ctx;
    ct_impact_result r;
    int st = ct_impact_eval(c->b, c->c, c->W, &c->opts, &r);
    *e = r.e;
    return st;
}

/* All quadrature variants on one bundle. */
static void rod_rows(const char *method, ct_bundle *b, double build, int threads, long Kmax,
                     double budget)
{
    double W = V_STAR * V_STAR * ct_energy_scale(&P);
    double perr = p_error_rods(b);
    size_t rods = ct_bundle_size(b);
    long depth = ct_cantor_depth(b);
    rod_ctx c = {b, {0}, W, 0};
    ct_impact_opts_default(&c.opts);
    double e, t_bp;
    if (time_job(rod_job, &c, &e, &t_bp))
        fail(method);
    /* nodes of the breakpoint rule, to scale the composite rules' cost from */
    ct_impact_result r;
    ct_bundle_reset(b);
    if (ct_impact(b, W, &c.opts, &r))
        fail(method);
    size_t nu = curve_points_in(b, r.u_release, r.u_max);
    ct_bundle_reset(b);
    size_t nl = curve_points_in(b, r.u_contact, r.u_max);
    row(method, depth, rods, "breakpoints", nl + nu, threads, build, t_bp, e, perr, "");

    /* the curve built once (its build timed as build_seconds), then per speed an O(log n)
     * lookup: without and with the closed-form check rod by rod */
    ct_bundle_reset(b);
    ct_curve *curve;
    double t0 = bench_now();
    if (ct_curve_alloc(&curve) || ct_curve_build(curve, b))
        fail("curve");
    double t_build = bench_now() - t0;
    for (int check = 0; check < 2; check++) {
        curve_ctx cc = {b, curve, c.opts, W};
        cc.opts.check = check;
        double t_curve;
        if (time_job(curve_job, &cc, &e, &t_curve))
            fail(method);
        row(method, depth, rods, check ? "curve+check" : "curve", ct_curve_size(curve), threads,
            t_build, t_curve, e, perr, "per further speed on the built curve");
    }
    ct_curve_free(curve);

    const ct_quad_rule rules[3] = {CT_QUAD_TRAPEZOID, CT_QUAD_SIMPSON, CT_QUAD_GAUSS};
    for (int q = 0; q < 3; q++) {
        for (long K = 8; K <= Kmax; K *= 2) {
            /* node evaluations per impact: 1.5 K for each energy (the rule and its
             * half-node error estimate) against nl + nu for the breakpoint rule */
            double predicted = t_bp * (1.0 + 3.0 * (double)K / (double)(nl + nu));
            if (predicted * (runs + 1) > budget) {
                skipped(method, depth, rods, ct_quad_rule_name(rules[q]), (size_t)K, threads, build,
                        predicted, perr);
                continue;
            }
            c.opts.rule = rules[q];
            c.opts.nodes = (size_t)K;
            double t;
            int st = time_job(rod_job, &c, &e, &t);
            if (st) {
                char note[160];
                snprintf(note, sizeof note, "refused: %s", ct_error_message());
                for (char *s = note; *s; s++)
                    if (*s == ',')
                        *s = ';';
                printf("%s,%ld,%zu,%s,%ld,%d,%.6g,,0,,,%.3g,%s\n", method, depth, rods,
                       ct_quad_rule_name(rules[q]), K, threads, build, perr, note);
                continue;
            }
            row(method, depth, rods, ct_quad_rule_name(rules[q]), (size_t)K, threads, build, t, e,
                perr, "");
        }
    }
    /* the closed-form energies on the same rods: no quadrature at all */
    ct_impact_opts_default(&c.opts);
    c.opts.rule = CT_QUAD_CLOSED;
    c.closed = 1;
    double t;
    if (time_job(rod_job, &c, &e, &t))
        fail(method);
    row(method, depth, rods, "closed", 0, threads, build, t, e, perr, "closed-form energies");
}

int main(int argc, char **argv)
{
    int quick = 0;
    double budget = 60.0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            quick = 1;
        else if (!strcmp(argv[i], "--budget") && i + 1 < argc)
            budget = atof(argv[++i]);
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_methods [--quick] [--budget SECONDS] [--runs N]\n");
            return 2;
        }
    }
    if (runs < 5 || runs > 64 || !(budget > 0.0)) {
        fprintf(stderr, "bench_methods: need 5 <= runs <= 64 and budget > 0\n");
        return 2;
    }
    if (quick && budget > 3.0)
        budget = 3.0;
    const long max_depth = quick ? 20 : 26, Kmax = quick ? 1024 : 4096;
    int threads = ct_default_threads();
    double W = V_STAR * V_STAR * ct_energy_scale(&P);

    /* reference: stage rods at the fractal depth, closed-form energies */
    long Nf, Na;
    double bound;
    if (ct_fractal_depth(&P, W, &Nf, &bound) || ct_auto_depth(&P, W, 1e-12, &Na, &bound))
        fail("depth");
    ct_bundle *ref;
    ct_impact_result r;
    if (ct_cantor_bundle(&ref, &P, CT_REP_STAGES, Nf, INFINITY) || ct_impact(ref, W, NULL, &r))
        fail("reference");
    e_ref = r.e_closed;
    u_ref = r.u_max;
    double u[SAMPLES];
    sample_u(u);
    ct_bundle_reset(ref);
    if (ct_bundle_force_many(ref, u, SAMPLES, P_ref))
        fail("reference force");
    ct_bundle_free(ref);

    bench_machine(stdout);
    printf("# scene: fx=1.5 fz=1.3 H*/h0=10 E/sigma_y=500 V*=%g; e_ref=%.17g (stage rods, "
           "fractal depth %ld, closed-form energies); u_max/h0=%.6g; budget %.3g s per "
           "configuration\n",
           V_STAR, e_ref, Nf, u_ref, budget);
    printf("method,depth,rods,rule,nodes,threads,build_seconds,median_seconds,runs,e,abs_e_error,"
           "max_rel_P_error,note\n");

    const ct_law laws[3] = {CT_LAW_ASYMPTOTIC, CT_LAW_ASYMPTOTIC_CONSISTENT, CT_LAW_SERIES};
    for (int k = 0; k < 3; k++) {
        law_ctx c = {laws[k], W};
        double e, t;
        if (time_job(law_job, &c, &e, &t))
            fail(ct_law_name(laws[k]));
        row(ct_law_name(laws[k]), -1, 0, k == 2 ? "breakpoints" : "closed", 0, 1, 0.0, t, e,
            p_error_law(laws[k]), "");
    }

    const struct {
        const char *name;
        long depth;
    } stage_runs[2] = {{"stages-auto", Na}, {"stages-fractal", Nf}};
    for (int k = 0; k < 2; k++) {
        ct_bundle *b;
        double t0 = bench_now();
        if (ct_cantor_bundle(&b, &P, CT_REP_STAGES, stage_runs[k].depth, INFINITY))
            fail("stages");
        double build = bench_now() - t0;
        rod_rows(stage_runs[k].name, b, build, threads, Kmax, budget);
        ct_bundle_free(b);
    }
    for (long N = 8; N <= max_depth; N += 2) {
        ct_bundle *b;
        double t0 = bench_now();
        if (ct_cantor_bundle(&b, &P, CT_REP_SEGMENTS, N, INFINITY))
            fail("segments");
        double build = bench_now() - t0;
        fprintf(stderr, "bench_methods: segments depth %ld (%zu rods)\n", N, ct_bundle_size(b));
        rod_rows("segments", b, build, threads, Kmax, budget);
        ct_bundle_free(b);
    }
    return 0;
}
