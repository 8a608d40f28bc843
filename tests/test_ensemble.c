/* Ensembles (src/ensemble.c): the statistics against GSL's, the samples against each
 * realisation built and swept on its own, independence of threads, split and of how the
 * realisations are cut into ranges, failed impacts, and spread 0 against the deterministic
 * surface. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assert_rel.h"
#include "cantact.h"

/* ct_sample_stats against GSL: mean, sample sd (n - 1), quantiles by
 * gsl_stats_quantile_from_sorted_data (type 7, the definition ct_stats states), the standard
 * error sd / sqrt(n); NaN samples left out; n = 1 has no spread. */
static void stats_against_gsl(void **state)
{
    (void)state;
    const size_t ns[] = {2, 3, 4, 10, 21, 101, 1000};
    double x[2000], ref[1000], work[2000];
    unsigned long long seed = 88172645463325252ULL;
    for (size_t t = 0; t < sizeof ns / sizeof ns[0]; t++) {
        const size_t n = ns[t];
        size_t m = 0;
        for (size_t k = 0; k < 2 * n; k++) { /* every other one NaN: stride 1 over 2n */
            seed ^= seed << 13, seed ^= seed >> 7, seed ^= seed << 17;
            double v = 0.3 + (double)(seed >> 11) * 0x1p-53 * (k % 3 ? 1.0 : 0.01);
            x[k] = k % 2 ? NAN : v;
            if (!(k % 2))
                ref[m++] = v;
        }
        ct_stats s;
        assert_int_equal(ct_sample_stats(x, 2 * n, 1, work, &s), CT_OK);
        assert_int_equal(s.n, n);
        gsl_sort(ref, 1, n);
        assert_rel(s.mean, gsl_stats_mean(ref, 1, n), 1e-15);
        assert_rel(s.sd, gsl_stats_sd(ref, 1, n), 1e-13);
        assert_rel(s.sem, gsl_stats_sd(ref, 1, n) / sqrt((double)n), 1e-13);
        assert_rel(s.q05, gsl_stats_quantile_from_sorted_data(ref, 1, n, 0.05), 1e-15);
        assert_rel(s.q50, gsl_stats_median_from_sorted_data(ref, 1, n), 1e-15);
        assert_rel(s.q95, gsl_stats_quantile_from_sorted_data(ref, 1, n, 0.95), 1e-15);
        /* a stride picks every other sample: the same numbers */
        ct_stats s2;
        assert_int_equal(ct_sample_stats(x, n, 2, work, &s2), CT_OK);
        assert_true(s2.mean == s.mean && s2.q95 == s.q95 && s2.sd == s.sd);
    }
    /* quantiles of 0..10 by hand: h = 10 p */
    double v[11];
    for (int k = 0; k < 11; k++)
        v[k] = 10.0 - k;
    ct_stats s;
    assert_int_equal(ct_sample_stats(v, 11, 1, work, &s), CT_OK);
    assert_rel(s.q05, 0.5, 1e-15);
    assert_rel(s.q50, 5.0, 1e-15);
    assert_rel(s.q95, 9.5, 1e-15);
    assert_rel(s.mean, 5.0, 1e-15);
    assert_rel(s.sd, sqrt(11.0), 1e-15); /* sum (k - 5)^2 = 110, / 10 */
    assert_rel(s.sem, 1.0, 1e-15);
    assert_true(ct_quantile_sorted(v + 10, 1, 0.95) == 0.0);
    double one = 0.25, nan = NAN;
    assert_int_equal(ct_sample_stats(&one, 1, 1, work, &s), CT_OK);
    assert_true(s.n == 1 && s.mean == 0.25 && s.q05 == 0.25 && s.q95 == 0.25);
    assert_true(isnan(s.sd) && isnan(s.sem));
    assert_int_equal(ct_sample_stats(&nan, 1, 1, work, &s), CT_EINVAL);
}

enum { NV = 5, IMP = 2, NROWS = NV * IMP };
static const double V[NV] = {1e-4, 4e-4, 1.5e-3, 5e-3, 1.5e-2};

static ct_ensemble_spec spec_of(long depth, double spread, uint64_t first, uint64_t count)
{
    ct_ensemble_spec sp = {.surface = {.params = {.fx = 1.5,
                                                  .fz = 1.3,
                                                  .l0 = 1.0,
                                                  .h0 = 1.0,
                                                  .Hstar = 10.0,
                                                  .E = 500.0,
                                                  .sigma_y = 1.0},
                                       .dist = CT_RATIO_LOGNORMAL,
                                       .fx_spread = spread,
                                       .fz_spread = spread / 2,
                                       .depth = depth,
                                       .seed = 2024},
                           .first = first,
                           .count = count,
                           .V_star = V,
                           .nvel = NV,
                           .impacts = IMP,
                           .threads = 1};
    ct_impact_opts_default(&sp.opts);
    return sp;
}

static ct_ensemble_samples *run(const ct_ensemble_spec *sp)
{
    ct_ensemble_samples *s;
    assert_int_equal(ct_ensemble_samples_alloc(&s, sp->first, sp->count, NROWS), CT_OK);
    assert_int_equal(ct_ensemble(sp, s), CT_OK);
    return s;
}

static int same_samples(const ct_ensemble_samples *a, const ct_ensemble_samples *b, size_t off)
{
    const size_t n = (size_t)a->count * a->nrows;
    return !memcmp(a->e, b->e + off, n * sizeof(double)) &&
           !memcmp(a->u_max, b->u_max + off, n * sizeof(double)) &&
           !memcmp(a->V_star_crit, b->V_star_crit + off, n * sizeof(double)) &&
           !memcmp(a->status, b->status + off, n * sizeof(int));
}

typedef struct {
    size_t calls, last;
} progress_log;

static void progress(size_t done, size_t total, void *ctx)
{
    progress_log *p = ctx;
    assert_true(done == p->last + 1 && total == 12);
    p->calls++;
    p->last = done;
}

/* Each realisation's samples are what its own bundle and sweep give, bit for bit; the clip
 * counts are its bundle's; realisations differ. */
static void samples_are_the_realisations(void **state)
{
    (void)state;
    ct_ensemble_spec sp = spec_of(9, 0.3, 7, 12);
    progress_log log = {0, 0};
    sp.progress = progress;
    sp.progress_ctx = &log;
    sp.threads = 2;
    sp.split = CT_SPLIT_REALISATIONS;
    ct_ensemble_samples *s = run(&sp);
    assert_int_equal(log.calls, 12);
    assert_true(s->draws == ((uint64_t)2 << 9) - 2);
    for (uint64_t r = 0; r < 12; r++) {
        ct_bundle *b;
        assert_int_equal(ct_random_cantor_bundle(&b, &sp.surface, 7 + r, 1), CT_OK);
        ct_sweep_spec sw = {.V_star = V, .nvel = NV, .impacts = IMP, .opts = sp.opts};
        ct_sweep_row rows[NROWS];
        assert_int_equal(ct_sweep(b, &sw, rows), CT_OK);
        uint64_t cx, cz, d;
        ct_random_cantor_clipped(b, &cx, &cz, &d);
        assert_true(s->fx_clipped[r] == cx && s->fz_clipped[r] == cz);
        for (size_t q = 0; q < NROWS; q++) {
            const size_t k = (size_t)r * NROWS + q;
            assert_int_equal(s->status[k], rows[q].status);
            assert_true(s->e[k] == rows[q].r.e);
            assert_true(s->u_max[k] == rows[q].r.u_max);
            assert_true(s->V_star_crit[k] == rows[q].r.V_star_crit);
            assert_true(s->quad_error_max >= rows[q].r.quad_error);
            if (r > 0 && !rows[q].r.elastic)
                assert_true(s->e[k] != s->e[k - NROWS]);
        }
        ct_bundle_free(b);
    }
    assert_true(s->failed_realisation == UINT64_MAX && s->message[0] == '\0');
    ct_ensemble_samples_free(s);
}

/* The same samples for 1 and 2 threads, either split, and for the range cut in two pieces:
 * what makes byte-identical outputs across threads, processes and job arrays. */
static void samples_do_not_depend_on_how_they_are_computed(void **state)
{
    (void)state;
    ct_ensemble_spec sp = spec_of(11, 0.2, 0, 9);
    ct_ensemble_samples *ref = run(&sp);
    const int threads[3] = {2, 2, 3};
    const ct_ensemble_split splits[3] = {CT_SPLIT_REALISATIONS, CT_SPLIT_RODS, CT_SPLIT_AUTO};
    for (int k = 0; k < 3; k++) {
        sp.threads = threads[k];
        sp.split = splits[k];
        ct_ensemble_samples *s = run(&sp);
        assert_true(same_samples(s, ref, 0));
        ct_ensemble_samples_free(s);
    }
    sp.threads = 2;
    sp.first = 0;
    sp.count = 4;
    ct_ensemble_samples *a = run(&sp);
    sp.first = 4;
    sp.count = 5;
    ct_ensemble_samples *b = run(&sp);
    assert_true(same_samples(a, ref, 0));
    assert_true(same_samples(b, ref, 4 * NROWS));
    ct_ensemble_samples_free(a);
    ct_ensemble_samples_free(b);
    ct_ensemble_samples_free(ref);
}

/* The default check's stride over the realisations: the count of checked ones by hand, and
 * which are checked seen in quad_error_max (NaN when no row was checked): realisations 1 .. 7
 * are not, 8 is; the samples are the same checked or not (the check adds, it never alters). */
static void check_stride(void **state)
{
    (void)state;
    ct_impact_opts o;
    ct_impact_opts_default(&o);
    o.check = CT_CHECK_AUTO;
    assert_true(ct_ensemble_checked(&o, 0, 20) == 3); /* 0, 8, 16 */
    assert_true(ct_ensemble_checked(&o, 0, 1) == 1);
    assert_true(ct_ensemble_checked(&o, 5, 3) == 0); /* 5, 6, 7 */
    assert_true(ct_ensemble_checked(&o, 5, 4) == 1); /* 8 */
    assert_true(ct_ensemble_checked(&o, 8, 1) == 1);
    assert_true(ct_ensemble_checked(&o, 9, 15) == 1); /* 16 */
    assert_true(ct_ensemble_checked(&o, 9, 16) == 2); /* 16, 24 */
    assert_true(ct_ensemble_checked(&o, 1000, 1000) == 125);
    assert_true(ct_ensemble_checked(&o, 3, 0) == 0);
    assert_true(ct_ensemble_checked(&o, UINT64_MAX - 3, 8) == 0); /* UINT64_MAX - 7 is 8k */
    assert_true(ct_ensemble_checked(&o, UINT64_MAX - 7, 8) == 1);
    assert_true(ct_ensemble_checked(&o, UINT64_MAX - 8, UINT64_MAX) == 1);
    o.check = CT_CHECK_ALL;
    assert_true(ct_ensemble_checked(&o, 5, 3) == 3);
    o.check = CT_CHECK_NONE;
    assert_true(ct_ensemble_checked(&o, 0, 20) == 0);
    ct_ensemble_spec sp = spec_of(9, 0.3, 1, 7);
    sp.opts.check = CT_CHECK_AUTO;
    ct_ensemble_samples *none = run(&sp);
    assert_true(isnan(none->quad_error_max));
    sp.count = 8;
    ct_ensemble_samples *one = run(&sp);
    assert_true(one->quad_error_max >= 0.0 && one->quad_error_max < 1e-12);
    sp.opts.check = CT_CHECK_ALL;
    ct_ensemble_samples *all = run(&sp);
    assert_true(all->quad_error_max >= one->quad_error_max);
    assert_true(same_samples(one, all, 0) && same_samples(none, all, 0));
    ct_ensemble_samples_free(none);
    ct_ensemble_samples_free(one);
    ct_ensemble_samples_free(all);
}

/* Spread 0: every realisation is the deterministic surface (bit for bit the same as each
 * other, so sd = 0 and every quantile is the mean); e to 1e-12 of the stage rods'. */
static void spread_zero_ensemble(void **state)
{
    (void)state;
    ct_ensemble_spec sp = spec_of(10, 0.0, 100, 6);
    sp.threads = 2;
    ct_ensemble_samples *s = run(&sp);
    ct_bundle *c;
    assert_int_equal(ct_cantor_bundle(&c, &sp.surface.params, CT_REP_STAGES, 10, INFINITY), CT_OK);
    ct_sweep_spec sw = {.V_star = V, .nvel = NV, .impacts = IMP, .opts = sp.opts};
    ct_sweep_row rows[NROWS];
    assert_int_equal(ct_sweep(c, &sw, rows), CT_OK);
    double work[6];
    for (size_t q = 0; q < NROWS; q++) {
        ct_stats st;
        assert_int_equal(ct_sample_stats(s->e + q, 6, NROWS, work, &st), CT_OK);
        assert_true(st.sd == 0.0 && st.q05 == st.mean && st.q95 == st.mean);
        assert_rel(st.mean, rows[q].r.e, 1e-12);
    }
    ct_bundle_free(c);
    ct_ensemble_samples_free(s);
}

/* A speed that crushes the layer: with stop_on_error the ensemble fails naming the lowest
 * realisation; without, that speed's samples are NaN with their status and the rest stand. */
static void failed_impacts(void **state)
{
    (void)state;
    static const double Vc[2] = {1e-3, 60.0};
    ct_ensemble_spec sp = spec_of(8, 0.2, 3, 5);
    sp.V_star = Vc;
    sp.nvel = 2;
    sp.impacts = 1;
    sp.threads = 2;
    ct_ensemble_samples *s;
    assert_int_equal(ct_ensemble_samples_alloc(&s, 3, 5, 2), CT_OK);
    assert_int_equal(ct_ensemble(&sp, s), CT_OK);
    for (size_t r = 0; r < 5; r++) {
        assert_int_equal(s->status[2 * r], CT_OK);
        assert_true(s->e[2 * r] > 0.0 && s->e[2 * r] < 1.0);
        assert_int_equal(s->status[2 * r + 1], CT_ERANGE);
        assert_true(isnan(s->e[2 * r + 1]));
    }
    assert_true(s->failed_realisation == 3 && s->failed_row == 1);
    assert_non_null(strstr(s->message, "realisation 3, V* = 60"));
    sp.stop_on_error = 1;
    assert_int_equal(ct_ensemble(&sp, s), CT_ERANGE);
    assert_true(s->failed_realisation == 3);
    assert_non_null(strstr(ct_error_message(), "realisation 3"));
    ct_ensemble_samples_free(s);
    /* a spec that does not match its samples */
    sp.V_star = V;
    sp.nvel = NV;
    assert_int_equal(ct_ensemble_samples_alloc(&s, 0, 5, 2), CT_OK);
    assert_int_equal(ct_ensemble(&sp, s), CT_EINVAL);
    ct_ensemble_samples_free(s);
}

/* An ensemble whose interrupt flag is set stops (CT_EINTR) on either split; set by the
 * progress callback at the first realisation done, the realisations not yet started are not. */
typedef struct {
    size_t calls;
    volatile int *stop;
} stopping;

static void stop_at_first(size_t done, size_t total, void *ctx)
{
    (void)done;
    (void)total;
    stopping *g = ctx;
    g->calls++;
    *g->stop = 1;
}

static void interrupt_stops_the_ensemble(void **state)
{
    (void)state;
    for (int split = CT_SPLIT_REALISATIONS; split <= CT_SPLIT_RODS; split++) {
        ct_ensemble_spec sp = spec_of(9, 0.3, 0, 40);
        sp.threads = 2;
        sp.split = (ct_ensemble_split)split;
        volatile int stop = 1;
        sp.interrupt = &stop;
        ct_ensemble_samples *s;
        assert_int_equal(ct_ensemble_samples_alloc(&s, sp.first, sp.count, NROWS), CT_OK);
        assert_int_equal(ct_ensemble(&sp, s), CT_EINTR);
        assert_string_equal(ct_error_message(), "interrupted");
        stop = 0;
        stopping g = {0, &stop};
        sp.progress = stop_at_first;
        sp.progress_ctx = &g;
        assert_int_equal(ct_ensemble(&sp, s), CT_EINTR);
        /* one realisation at a time: none after the first; else those under way */
        if (split == CT_SPLIT_RODS)
            assert_int_equal(g.calls, 1);
        else
            assert_true(g.calls >= 1 && g.calls <= 3);
        ct_ensemble_samples_free(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(stats_against_gsl),
        cmocka_unit_test(samples_are_the_realisations),
        cmocka_unit_test(samples_do_not_depend_on_how_they_are_computed),
        cmocka_unit_test(check_stride),
        cmocka_unit_test(spread_zero_ensemble),
        cmocka_unit_test(failed_impacts),
        cmocka_unit_test(interrupt_stops_the_ensemble),
    };
    return cmocka_run_group_tests_name("ensemble", tests, NULL, NULL);
}
