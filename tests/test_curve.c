/* The load curve (src/curve.c): against the rod-by-rod sums at every breakpoint and between
 * them, for Cantor stages and segments, arbitrary tops and states with a loading history;
 * cumulative work and dissipation against the closed forms per rod; the release point;
 * thread-count independence; a const bundle evaluated from two threads at once. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "assert_rel.h"
#include "cantact.h"
#include "internal.h"

static ct_params base(void)
{
    ct_params p = {
        .fx = 1.5, .fz = 1.3, .l0 = 1.0, .h0 = 1.0, .Hstar = 3.0, .E = 200.0, .sigma_y = 1.0};
    return p;
}

/* n rods with pseudo-random tops in [0, 2.5) and areas, from a fixed seed */
static ct_bundle *random_bundle(size_t n, unsigned seed)
{
    double *top = malloc(n * sizeof *top), *area = malloc(n * sizeof *area);
    assert_non_null(top);
    assert_non_null(area);
    uint64_t s = 0x9E3779B97F4A7C15u ^ seed;
    for (size_t k = 0; k < n; k++) {
        s = s * 6364136223846793005u + 1442695040888963407u;
        top[k] = 2.5 * (double)(s >> 11) / 9007199254740992.0;
        s = s * 6364136223846793005u + 1442695040888963407u;
        area[k] = 1e-3 * (0.1 + (double)(s >> 11) / 9007199254740992.0);
    }
    ct_layer L = {.E = 200.0, .sigma_y = 1.0, .Hstar = 3.0, .l0 = 1.0, .h0 = 1.0};
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, n, top, area), CT_OK);
    free(top);
    free(area);
    return b;
}

/* The rounding scales of the rod-by-rod sums at u: each rod's elastic strain
 * (u - top)/L - eps_p carries an error of about eps (|u| + top + eps_p L)/L, so its force one
 * of eps k (|u| + top + eps_p L) (k = E s/L) and its work one of eps P_k (|u| + top + eps_p L).
 * The curve's own breakpoints carry the same rounding (they are top + eps_p L). Sums of
 * these over the rods in contact bound what the two may differ by. */
static void rounding_scales(const ct_bundle *b, double u, double *force_scale, double *work_scale)
{
    const ct_layer *L = ct_bundle_layer(b);
    double fs = 0.0, ws = 0.0;
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        ct_rod_info r;
        assert_int_equal(ct_bundle_rod(b, k, &r), CT_OK);
        double contact = r.top + r.plastic_strain * r.length;
        if (!(u >= contact)) /* at contact, the rod sum's rounding may already count */
            continue;
        double reach = fabs(u) + r.top + r.plastic_strain * r.length;
        double d = fmin((u - r.top) / r.length - r.plastic_strain, L->sigma_y / L->E);
        d = fmax(fabs(d), DBL_EPSILON * reach / r.length); /* at contact, d is the rounding */
        fs += L->E * r.area / r.length * reach;
        ws += L->E * r.area * d * reach;
    }
    *force_scale = fs;
    *work_scale = ws;
}

static void check_curve(const ct_bundle *b)
{
    ct_curve *c;
    assert_int_equal(ct_curve_alloc(&c), CT_OK);
    assert_int_equal(ct_curve_build(c, b), CT_OK);
    const double *x = ct_curve_points(c);
    const size_t n = ct_curve_size(c);
    assert_true(n >= 2);
    assert_true(x[0] == ct_bundle_first_contact(b));
    assert_true(ct_curve_first_yield(c) == ct_bundle_first_yield(b));
    const double eps = DBL_EPSILON;
    for (size_t k = 0; k < n; k++) {
        if (k)
            assert_true(x[k] > x[k - 1]); /* sorted and distinct */
        for (int between = 0; between < 2; between++) {
            double u = between ? (k + 1 < n ? 0.5 * (x[k] + x[k + 1]) : x[k] + 0.25) : x[k];
            double fs, ws;
            rounding_scales(b, u, &fs, &ws);
            double P = ct_bundle_force(b, u), Pc = ct_curve_force(c, u);
            if (!(fabs(Pc - P) <= 8.0 * eps * (fs + fabs(P))))
                fail_msg("P(%.17g): curve %.17g, rods %.17g, scale %.3g", u, Pc, P, fs);
            /* the work from first contact, and what loading to u dissipates: the loading work
             * less the recoverable energy, both closed forms rod by rod */
            double W = ct_bundle_work(b, x[0], u), Wc = ct_curve_work(c, u);
            double D = W - ct_bundle_elastic_energy(b, u), Dc = ct_curve_dissipation(c, u);
            if (!(fabs(Wc - W) <= 8.0 * eps * (ws + W)))
                fail_msg("W(%.17g): curve %.17g, rods %.17g, scale %.3g", u, Wc, W, ws);
            if (!(fabs(Dc - D) <= 8.0 * eps * (ws + W)))
                fail_msg("D(%.17g): curve %.17g, rods %.17g, scale %.3g", u, Dc, D, ws);
            /* the release point after loading to u, and W's inverse */
            double r = ct_bundle_release(b, u), rc = ct_curve_release(c, u);
            if (!(fabs(rc - r) <= 8.0 * eps * fabs(u)))
                fail_msg("release(%.17g): curve %.17g, rods %.17g", u, rc, r);
            if (Wc > 0.0) {
                double ui = ct_curve_inverse_work(c, Wc);
                if (!(fabs(ui - u) <=
                      8.0 * eps * fabs(u) + 8.0 * eps * (ws + Wc) / fmax(Pc, 1e-300)))
                    fail_msg("inverse W(%.17g) = %.17g", u, ui);
            }
        }
    }
    /* beyond the last breakpoint every rod sits on its plateau: P is flat, exactly (no
     * rounding residue of the slope sum may tilt it), and equals the plateau sum */
    const ct_layer *L = ct_bundle_layer(b);
    double far1 = x[n - 1] + 0.25 * (L->Hstar - x[n - 1]),
           far2 = x[n - 1] + 0.9 * (L->Hstar - x[n - 1]);
    if (!(ct_curve_force(c, far1) == ct_curve_force(c, far2)))
        fail_msg("P beyond the last breakpoint tilts: %.17g at %.17g, %.17g at %.17g",
                 ct_curve_force(c, far1), far1, ct_curve_force(c, far2), far2);
    assert_rel(ct_curve_force(c, far2), ct_bundle_force(b, far2), 8.0 * eps);
    /* below first contact: nothing */
    assert_true(ct_curve_force(c, x[0] - 0.1) == 0.0 && ct_curve_work(c, x[0] - 0.1) == 0.0);
    ct_curve_free(c);
}

static void stages_virgin_and_after_history(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 40, INFINITY), CT_OK);
    check_curve(b);
    ct_bundle_advance(b, 0.33);
    check_curve(b);
    ct_bundle_advance(b, 0.2); /* unloading changes nothing */
    ct_bundle_advance(b, 0.9);
    check_curve(b);
    ct_bundle_free(b);
}

static void segments_and_arbitrary_tops(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, 11, INFINITY), CT_OK);
    check_curve(b);
    ct_bundle_advance(b, 0.33);
    check_curve(b);
    ct_bundle_free(b);
    b = random_bundle(3000, 1);
    check_curve(b);
    ct_bundle_advance(b, 1.0);
    check_curve(b);
    ct_bundle_free(b);
}

/* Stage rods and segment rods are two representations of one surface: their curves hold the
 * same breakpoints (the pieces of a stage merge into one event pair) and the same P. */
static void stage_and_segment_curves_agree(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *st, *sg;
    ct_curve *a, *b;
    assert_int_equal(ct_cantor_bundle(&st, &p, CT_REP_STAGES, 14, INFINITY), CT_OK);
    assert_int_equal(ct_cantor_bundle(&sg, &p, CT_REP_SEGMENTS, 14, INFINITY), CT_OK);
    ct_bundle_advance(st, 0.5);
    ct_bundle_advance(sg, 0.5);
    assert_int_equal(ct_curve_alloc(&a), CT_OK);
    assert_int_equal(ct_curve_alloc(&b), CT_OK);
    assert_int_equal(ct_curve_build(a, st), CT_OK);
    assert_int_equal(ct_curve_build(b, sg), CT_OK);
    assert_int_equal(ct_curve_size(a), ct_curve_size(b));
    for (size_t k = 0; k < ct_curve_size(a); k++) {
        double u = ct_curve_points(a)[k];
        assert_true(u == ct_curve_points(b)[k]);
        assert_rel(ct_curve_force(a, u + 1e-3), ct_curve_force(b, u + 1e-3), 1e-14);
        assert_rel(ct_curve_work(a, u + 1e-3), ct_curve_work(b, u + 1e-3), 1e-14);
    }
    ct_curve_free(a);
    ct_curve_free(b);
    ct_bundle_free(st);
    ct_bundle_free(sg);
}

/* A rod whose yield point rounds onto its contact point (length 1e-12, stiff) is
 * rigid-plastic at this resolution: its plateau must still be in P, as in the rod sum. */
static void rigid_plastic_rod_keeps_its_plateau(void **state)
{
    (void)state;
    ct_layer L = {.E = 1e9, .sigma_y = 1.0, .Hstar = 1.0, .l0 = 1.0, .h0 = 1.0};
    double top[2] = {1.0 - 1e-12, 0.5}, area[2] = {0.25, 0.75};
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 2, top, area), CT_OK);
    ct_curve *c;
    assert_int_equal(ct_curve_alloc(&c), CT_OK);
    assert_int_equal(ct_curve_build(c, b), CT_OK);
    double u = 1.0 - 0.5e-12; /* rod 0 on its plateau, rod 1 too */
    assert_rel(ct_curve_force(c, u), ct_bundle_force(b, u), 1e-15);
    assert_rel(ct_curve_force(c, u), 1.0, 1e-15); /* E s eps_y summed: 0.25 + 0.75 */
    ct_curve_free(c);
    ct_bundle_free(b);
}

/* The curve does not depend on the thread count: a bundle far above the parallel
 * threshold, arbitrary tops after a history (many runs to merge), 1 and 2 threads. */
static void compare_threads(ct_bundle *b);

static void bitwise_identical_for_any_thread_count(void **state)
{
    (void)state;
    ct_bundle *b = random_bundle(60000, 2);
    ct_bundle_advance(b, 0.8);
    compare_threads(b);
    ct_bundle_free(b);
    /* segments above the threshold, after a history: runs merged within fixed blocks */
    ct_params p = base();
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, 16, INFINITY), CT_OK);
    ct_bundle_advance(b, 0.45);
    compare_threads(b);
    ct_bundle_free(b);
}

static void compare_threads(ct_bundle *b)
{
    ct_curve *c[2];
    /* a team from 64 rods: the curve's parallel passes and merges run on these bundles */
    ct_bundle_set_parallel_min(b, 1);
    for (int t = 0; t < 2; t++) {
        ct_bundle_set_threads(b, t + 1);
        assert_int_equal(ct_curve_alloc(&c[t]), CT_OK);
        assert_int_equal(ct_curve_build(c[t], b), CT_OK);
    }
    size_t n = ct_curve_size(c[0]);
    assert_int_equal(n, ct_curve_size(c[1]));
    assert_memory_equal(ct_curve_points(c[0]), ct_curve_points(c[1]), n * sizeof(double));
    for (size_t k = 0; k + 1 < n; k++) {
        double u = 0.5 * (ct_curve_points(c[0])[k] + ct_curve_points(c[0])[k + 1]);
        double v0[4] = {ct_curve_force(c[0], u), ct_curve_work(c[0], u),
                        ct_curve_dissipation(c[0], u), ct_curve_release(c[0], u)};
        double v1[4] = {ct_curve_force(c[1], u), ct_curve_work(c[1], u),
                        ct_curve_dissipation(c[1], u), ct_curve_release(c[1], u)};
        assert_memory_equal(v0, v1, sizeof v0);
    }
    ct_curve_free(c[0]);
    ct_curve_free(c[1]);
}

/* The two curves bitwise the same: breakpoints, and force, work, dissipation and release
 * between them. */
static void assert_curves_equal(const ct_bundle *a, const ct_bundle *b)
{
    ct_curve *c[2];
    const ct_bundle *of[2] = {a, b};
    for (int t = 0; t < 2; t++) {
        assert_int_equal(ct_curve_alloc(&c[t]), CT_OK);
        assert_int_equal(ct_curve_build(c[t], of[t]), CT_OK);
    }
    size_t n = ct_curve_size(c[0]);
    assert_int_equal(n, ct_curve_size(c[1]));
    assert_memory_equal(ct_curve_points(c[0]), ct_curve_points(c[1]), n * sizeof(double));
    for (size_t k = 0; k < n; k++) {
        double u = k + 1 < n ? 0.5 * (ct_curve_points(c[0])[k] + ct_curve_points(c[0])[k + 1])
                             : ct_curve_points(c[0])[k] + 0.1;
        double v[2][4];
        for (int t = 0; t < 2; t++) {
            v[t][0] = ct_curve_force(c[t], u);
            v[t][1] = ct_curve_work(c[t], u);
            v[t][2] = ct_curve_dissipation(c[t], u);
            v[t][3] = ct_curve_release(c[t], u);
        }
        assert_memory_equal(v[0], v[1], sizeof v[0]);
    }
    assert_memory_equal(&(double){ct_curve_first_yield(c[0])},
                        &(double){ct_curve_first_yield(c[1])}, sizeof(double));
    ct_curve_free(c[0]);
    ct_curve_free(c[1]);
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Rods sorted by top and virgin (a random Cantor realisation) have their events merged as
 * they are made; the same rods with two of them swapped go through the layout and the merge
 * sort.
 * Both curves must be bitwise the same, also where the merge as made gives up: two runs of
 * one top across a block boundary, and a contact at another rod's yield. */
static void events_merged_as_made(void **state)
{
    (void)state;
    enum { N = 5000 };
    ct_layer L = {.E = 200.0, .sigma_y = 1.0, .Hstar = 3.0, .l0 = 1.0, .h0 = 1.0};
    double *top = malloc(N * sizeof *top), *area = malloc(N * sizeof *area),
           *rtop = malloc(N * sizeof *rtop), *rarea = malloc(N * sizeof *rarea);
    for (int variant = 0; variant < 3; variant++) {
        uint64_t s = 0x243F6A8885A308D3u + (uint64_t)variant;
        for (size_t k = 0; k < N; k++) {
            s = s * 6364136223846793005u + 1442695040888963407u;
            top[k] = 2.5 * (double)(s >> 11) / 9007199254740992.0;
        }
        qsort(top, N, sizeof *top, by_value);
        if (variant == 1) /* rods 2047 and 2048: one top, two blocks, so two runs */
            top[2048] = top[2047];
        if (variant == 2) { /* rod 100 touches where rod 0 yields */
            const double eps_y = L.sigma_y / L.E;
            top[100] = top[0] + (0.0 + eps_y) * (L.Hstar - top[0]);
            qsort(top, N, sizeof *top, by_value);
        }
        for (size_t k = 0; k < N; k++) {
            s = s * 6364136223846793005u + 1442695040888963407u;
            area[k] = 1e-3 * (0.1 + (double)(s >> 11) / 9007199254740992.0);
            rtop[k] = top[k];
            rarea[k] = area[k];
        }
        /* rods 2048 and 2049 swapped: the contacts out of order, and no two rods of one top
         * next to each other (they would be one run) */
        rtop[2048] = top[2049];
        rarea[2048] = area[2049];
        rtop[2049] = top[2048];
        rarea[2049] = area[2048];
        ct_bundle *sorted, *swapped;
        assert_int_equal(ct_bundle_from_rods(&sorted, &L, N, top, area), CT_OK);
        assert_int_equal(ct_bundle_from_rods(&swapped, &L, N, rtop, rarea), CT_OK);
        ct_bundle_set_threads(sorted, 1);
        assert_curves_equal(sorted, swapped);
        if (variant == 0)
            compare_threads(sorted); /* one thread: merged as made; two: the blocks' passes */
        ct_bundle_free(sorted);
        ct_bundle_free(swapped);
    }
    free(top);
    free(area);
    free(rtop);
    free(rarea);
}

/* ---- W's inverse near the top of the doubles ---- */

/* The work from the virgin state to u and the force at u of rods (tops, areas, lengths
 * H* - top), the closed forms of docs/model.md §3 summed in long double. */
static long double rods_work(const ct_layer *L, size_t n, const double *top, const double *area,
                             long double u, long double *force)
{
    const long double eps_y = (long double)L->sigma_y / L->E;
    long double W = 0.0L, P = 0.0L;
    for (size_t k = 0; k < n; k++) {
        const long double len = (long double)L->Hstar - top[k], eps = (u - top[k]) / len,
                          Esl = (long double)L->E * area[k] * len;
        if (eps <= 0.0L)
            continue;
        W += eps <= eps_y ? Esl * eps * eps / 2 : Esl * (eps_y * eps - eps_y * eps_y / 2);
        P += (long double)L->E * area[k] * (eps < eps_y ? eps : eps_y);
    }
    *force = P;
    return W;
}

/* ct_curve_inverse_work(W) against the closed forms: the u whose work is W to its rounding, or
 * inf where that u lies beyond the doubles (a u of W - 0.5 ulp(DBL_MAX) may be either). */
static void check_inverse(const ct_layer *L, size_t n, const double *top, const double *area,
                          double W)
{
    ct_bundle *b;
    ct_curve *c;
    assert_int_equal(ct_bundle_from_rods(&b, L, n, top, area), CT_OK);
    assert_int_equal(ct_curve_alloc(&c), CT_OK);
    assert_int_equal(ct_curve_build(c, b), CT_OK);
    const double u = ct_curve_inverse_work(c, W);
    long double P = 0.0L;
    if (u == INFINITY) { /* only if the u of W lies beyond DBL_MAX, to rounding */
        const long double W_max = rods_work(L, n, top, area, DBL_MAX, &P);
        if (!(W_max < W + 8.0L * DBL_EPSILON * (W + P * DBL_MAX)))
            fail_msg("E %g, area %g: inverse W(%.17g) = inf, but W(DBL_MAX) = %.17Lg", L->E,
                     area[0], W, W_max);
    } else {
        const long double Wu = isfinite(u) ? rods_work(L, n, top, area, u, &P) : NAN;
        if (!(fabsl(Wu - W) <= 8.0L * DBL_EPSILON * (W + P * u)))
            fail_msg("E %g, area %g: inverse W(%.17g) = %.17g, whose work is %.17Lg", L->E, area[0],
                     W, u, Wu);
    }
    ct_curve_free(c);
    ct_bundle_free(b);
}

/* W above DBL_MAX / 2 made 2 (W - W_x) overflow: on a plateau sqrt(inf) sqrt(0) is NaN and
 * the piece's start came back (u = 0.015 for W = 1.7e308), on an elastic piece NaN. Now the
 * u whose work is W, or inf where it leaves the doubles. */
static void inverse_work_near_the_top_of_the_doubles(void **state)
{
    (void)state;
    const double Ws[] = {1e300, 8.98e307, 8.99e307, 9e307, 1.7e308, DBL_MAX};
    const size_t nW = sizeof Ws / sizeof *Ws;
    /* one rod: a plateau beyond u_y = 0.015 of force 2, 1 and 0.5 (its u beyond the doubles
     * for W above DBL_MAX / 2) */
    const ct_layer plateau = {.E = 200.0, .sigma_y = 1.0, .Hstar = 3.0, .l0 = 1.0, .h0 = 1.0};
    const double top0 = 0.0;
    for (size_t i = 0; i < nW; i++)
        for (double s = 2.0; s >= 0.5; s *= 0.5)
            check_inverse(&plateau, 1, &top0, &s, Ws[i]);
    /* two stiff rods, both elastic from u = 10 to 50 with a work of 1.0e308 on that piece
     * (2 R and k R overflow), then one plateau and a force of 5e306 beyond u = 55 */
    const ct_layer stiff = {.E = 1e306, .sigma_y = 5e305, .Hstar = 100.0, .l0 = 1.0, .h0 = 1.0};
    const double tops[] = {0.0, 10.0}, areas[] = {5.0, 5.0};
    const double Wp[] = {2.5e306, 5e307, 9e307, 1e308, 1.05e308, 1.7e308, DBL_MAX};
    for (size_t i = 0; i < sizeof Wp / sizeof *Wp; i++)
        check_inverse(&stiff, 2, tops, areas, Wp[i]);
    /* a plateau force of 1.35e308 beyond u_y = 1.8 (W 1.215e308 there): P + hypot(P, 0)
     * overflows while 2 R does not */
    const ct_layer strong = {.E = 1e306, .sigma_y = 9e305, .Hstar = 2.0, .l0 = 1.0, .h0 = 1.0};
    const double wide = 150.0, Ws_strong[] = {1e307, 1e308, 1.3e308, 1.5e308, DBL_MAX};
    for (size_t i = 0; i < sizeof Ws_strong / sizeof *Ws_strong; i++)
        check_inverse(&strong, 1, &top0, &wide, Ws_strong[i]);
}

/* ---- a const bundle evaluated from two threads at once ---- */
typedef struct {
    const ct_bundle *b;
    double P[64], W[64], E;
    size_t curve_points;
    int status;
} worker;

static void *evaluate(void *arg)
{
    worker *w = arg;
    double u[64];
    for (int i = 0; i < 64; i++)
        u[i] = 0.02 * i;
    ct_curve *c;
    w->status = ct_bundle_force_many(w->b, u, 64, w->P);
    w->status |= ct_bundle_work_many(w->b, 0.0, u, 64, w->W);
    w->E = ct_bundle_elastic_energy(w->b, 0.7) + ct_bundle_force(w->b, 0.6);
    w->status |= ct_curve_alloc(&c);
    if (!w->status)
        w->status = ct_curve_build(c, w->b);
    w->curve_points = ct_curve_size(c);
    ct_curve_free(c);
    return NULL;
}

static void const_bundle_from_two_threads(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    /* segments above the parallel threshold: each thread's sums use a team of their own */
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, 15, INFINITY), CT_OK);
    ct_bundle_advance(b, 0.4);
    worker ref = {.b = b}, w[2] = {{.b = b}, {.b = b}};
    evaluate(&ref);
    assert_int_equal(ref.status, CT_OK);
    pthread_t th[2];
    for (int t = 0; t < 2; t++)
        assert_int_equal(pthread_create(&th[t], NULL, evaluate, &w[t]), 0);
    for (int t = 0; t < 2; t++) {
        assert_int_equal(pthread_join(th[t], NULL), 0);
        assert_int_equal(w[t].status, CT_OK);
        assert_memory_equal(w[t].P, ref.P, sizeof ref.P);
        assert_memory_equal(w[t].W, ref.W, sizeof ref.W);
        assert_memory_equal(&w[t].E, &ref.E, sizeof ref.E);
        assert_int_equal(w[t].curve_points, ref.curve_points);
    }
    ct_bundle_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(stages_virgin_and_after_history),
        cmocka_unit_test(segments_and_arbitrary_tops),
        cmocka_unit_test(stage_and_segment_curves_agree),
        cmocka_unit_test(rigid_plastic_rod_keeps_its_plateau),
        cmocka_unit_test(bitwise_identical_for_any_thread_count),
        cmocka_unit_test(events_merged_as_made),
        cmocka_unit_test(const_bundle_from_two_threads),
        cmocka_unit_test(inverse_work_near_the_top_of_the_doubles),
    };
    return cmocka_run_group_tests_name("curve", tests, NULL, NULL);
}
