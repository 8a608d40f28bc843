/* Random Cantor surfaces (src/surface/random_cantor.c, docs/model.md §10): the generator and its
 * keying, each rod against the geometry recomputed here in long double from the drawn ratios,
 * the ratio distributions' moments, clipping and its count, spread 0 against the
 * deterministic surface, and independence of the thread count. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <Random123/philox.h>
#include <cmocka.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assert_rel.h"
#include "cantact.h"

static ct_random_cantor surface(ct_ratio_dist dist, double sx, double sz, long depth)
{
    ct_random_cantor rc = {
        .params =
            {.fx = 1.5, .fz = 1.3, .l0 = 2.0, .h0 = 0.5, .Hstar = 5.0, .E = 500.0, .sigma_y = 1.0},
        .dist = dist,
        .fx_spread = sx,
        .fz_spread = sz,
        .depth = depth,
        .seed = 12345};
    return rc;
}

/* Philox4x64-10 itself (Random123's known-answer vectors), and the keying the library
 * promises: key (seed, realisation), counter (g, 0, 0, 0), uniforms from the top 53 bits.
 * The ratios are recomputed here from the raw generator. */
static void generator_and_keying(void **state)
{
    (void)state;
    philox4x64_ctr_t c = {{0, 0, 0, 0}};
    philox4x64_key_t k = {{0, 0}};
    philox4x64_ctr_t r = philox4x64(c, k);
    assert_true(r.v[0] == 0x16554d9eca36314cULL && r.v[1] == 0xdb20fe9d672d0fdcULL &&
                r.v[2] == 0xd7e772cee186176bULL && r.v[3] == 0x7e68b68aec7ba23bULL);
    c = (philox4x64_ctr_t){{0x243f6a8885a308d3ULL, 0x13198a2e03707344ULL, 0xa4093822299f31d0ULL,
                            0x082efa98ec4e6c89ULL}};
    k = (philox4x64_key_t){{0x452821e638d01377ULL, 0xbe5466cf34e90c6cULL}};
    r = philox4x64(c, k);
    assert_true(r.v[0] == 0xa528f45403e61d95ULL && r.v[1] == 0x38c72dbd566e9788ULL &&
                r.v[2] == 0xa5a1610e72fd18b5ULL && r.v[3] == 0x57bd43b5e52b7fe6ULL);

    ct_random_cantor rc = surface(CT_RATIO_UNIFORM, 0.2, 0.1, 6);
    for (uint64_t real = 0; real < 3; real++)
        for (uint64_t g = 1; g < 127; g++) {
            philox4x64_ctr_t cg = {{g, 0, 0, 0}};
            philox4x64_key_t kg = {{rc.seed, real}};
            philox4x64_ctr_t o = philox4x64(cg, kg);
            long double u0 = ((long double)(o.v[0] >> 11) + 0.5L) / 9007199254740992.0L;
            long double u1 = ((long double)(o.v[1] >> 11) + 0.5L) / 9007199254740992.0L;
            double fx, fz;
            int clipped;
            assert_int_equal(ct_random_cantor_ratios(&rc, real, g, &fx, &fz, &clipped), CT_OK);
            assert_int_equal(clipped, 0);
            assert_rel(fx, 1.5L * (1.0L + 0.2L * (2.0L * u0 - 1.0L)), 4e-16);
            assert_rel(fz, 1.3L * (1.0L + 0.1L * (2.0L * u1 - 1.0L)), 4e-16);
        }
    /* log-normal: Box-Muller from the same two uniforms (spreads that never clip here) */
    rc = surface(CT_RATIO_LOGNORMAL, 0.05, 0.04, 6);
    for (uint64_t g = 1; g < 127; g++) {
        philox4x64_ctr_t cg = {{g, 0, 0, 0}};
        philox4x64_key_t kg = {{rc.seed, 2}};
        philox4x64_ctr_t o = philox4x64(cg, kg);
        long double u0 = ((long double)(o.v[0] >> 11) + 0.5L) / 9007199254740992.0L;
        long double u1 = ((long double)(o.v[1] >> 11) + 0.5L) / 9007199254740992.0L;
        long double rad = sqrtl(-2.0L * logl(u0)), ang = 2.0L * 3.14159265358979323846L * u1;
        double fx, fz;
        assert_int_equal(ct_random_cantor_ratios(&rc, 2, g, &fx, &fz, NULL), CT_OK);
        assert_rel(fx, 1.5L * expl(0.05L * rad * cosl(ang)), 1e-14);
        assert_rel(fz, 1.3L * expl(0.04L * rad * sinl(ang)), 1e-14);
    }
    double fx, fz;
    assert_int_equal(ct_random_cantor_ratios(&rc, 0, 0, &fx, &fz, NULL), CT_EINVAL);
    assert_int_equal(ct_random_cantor_ratios(&rc, 0, 127, &fx, &fz, NULL), CT_EINVAL);
}

/* The build draws its ratios a batch at a time (eight lanes at once where the CPU has
 * AVX-512) and sorts the rods by a radix sort of their tops: every rod's top must be bitwise
 * the piece's depth computed here in double from ct_random_cantor_ratios (one ratio at a
 * time, by the very division of the builder), and the rods sorted by top with ties in piece
 * order, spread 0 (every piece of a stage at one depth) included. */
static void rods_bitwise_and_sorted(void **state)
{
    (void)state;
    const ct_ratio_dist dists[2] = {CT_RATIO_UNIFORM, CT_RATIO_LOGNORMAL};
    const double spreads[3] = {0.0, 0.05, 0.5};
    for (int d = 0; d < 2; d++)
        for (int q = 0; q < 3; q++) {
            ct_random_cantor rc = surface(dists[d], spreads[q], spreads[q] / 2, 11);
            const size_t n = ((size_t)2 << rc.depth) - 1;
            double *h = malloc(n * sizeof *h);
            h[0] = rc.params.h0;
            for (size_t g = 1; g < n; g++) {
                double fx, fz;
                assert_int_equal(ct_random_cantor_ratios(&rc, 3, g, &fx, &fz, NULL), CT_OK);
                h[g] = h[(g - 1) / 2] / fz;
            }
            ct_bundle *b;
            assert_int_equal(ct_random_cantor_bundle(&b, &rc, 3, 1), CT_OK);
            double prev_top = -INFINITY;
            uint64_t prev_g = 0;
            for (size_t k = 0; k < n; k++) {
                uint64_t g;
                ct_rod_info info;
                assert_int_equal(ct_random_cantor_piece(b, k, &g), CT_OK);
                assert_int_equal(ct_bundle_rod(b, k, &info), CT_OK);
                assert_memory_equal(&info.top, &h[g], sizeof info.top);
                assert_true(info.top > prev_top || (info.top == prev_top && g > prev_g));
                prev_top = info.top;
                prev_g = g;
            }
            free(h);
            ct_bundle_free(b);
        }
}

/* Every rod of a realisation against its piece recomputed from the drawn ratios: piece g's
 * width is l0 times the product of 1/(2 fx_k) down its path, its depth h0 divided by the
 * product of the fz_k; a middle keeps the width less its two children's, a tip all of it. */
static void rods_against_the_ratios(void **state)
{
    (void)state;
    const ct_ratio_dist dists[2] = {CT_RATIO_UNIFORM, CT_RATIO_LOGNORMAL};
    for (int d = 0; d < 2; d++)
        for (long depth = 0; depth <= 9; depth += 3) {
            /* spreads that do not clip here: a clipped f = 1 + eps leaves a middle of width
             * w eps, which the reference below cannot resolve (it subtracts) */
            ct_random_cantor rc = surface(dists[d], d ? 0.1 : 0.3, d ? 0.05 : 0.2, depth);
            const size_t n = ((size_t)2 << depth) - 1;
            long double *w = malloc(n * sizeof *w), *h = malloc(n * sizeof *h),
                        *left = malloc(n * sizeof *left);
            w[0] = rc.params.l0;
            h[0] = rc.params.h0;
            left[0] = 0.0L;
            for (size_t g = 1; g < n; g++) {
                double fx, fz;
                int clipped;
                assert_int_equal(ct_random_cantor_ratios(&rc, 5, g, &fx, &fz, &clipped), CT_OK);
                assert_int_equal(clipped, 0);
                const size_t parent = (g - 1) / 2;
                w[g] = w[parent] / (2.0L * fx);
                h[g] = h[parent] / fz;
                left[g] = g % 2 ? left[parent] : left[parent] + w[parent] - w[g];
            }
            ct_bundle *b;
            assert_int_equal(ct_random_cantor_bundle(&b, &rc, 5, 1), CT_OK);
            assert_int_equal(ct_bundle_size(b), n);
            assert_string_equal(ct_bundle_surface(b), "random_cantor");
            unsigned char *seen = calloc(n, 1);
            long double total = 0.0L;
            double prev_top = 0.0;
            for (size_t k = 0; k < n; k++) {
                uint64_t g;
                ct_rod_info info;
                assert_int_equal(ct_random_cantor_piece(b, k, &g), CT_OK);
                assert_true(g < n && !seen[g]);
                seen[g] = 1;
                assert_int_equal(ct_bundle_rod(b, k, &info), CT_OK);
                const int tip = 2 * g + 1 >= n;
                long double a = tip ? w[g] : w[g] - w[2 * g + 1] - w[2 * g + 2];
                long double xl = tip ? left[g] : left[g] + w[2 * g + 1];
                long double xr = tip ? left[g] + w[g] : left[2 * g + 2];
                assert_rel(info.top, h[g], 64 * DBL_EPSILON);
                assert_rel(info.area, a, 64 * DBL_EPSILON);
                assert_rel(info.length, rc.params.Hstar - h[g], 8 * DBL_EPSILON);
                assert_true(fabsl(info.x_left - xl) <= 16 * DBL_EPSILON * rc.params.l0);
                assert_true(fabsl(info.x_right - xr) <= 16 * DBL_EPSILON * rc.params.l0);
                assert_true(info.plastic_strain == 0.0);
                long stage = 0;
                while (((size_t)2 << stage) - 1 <= g)
                    stage++;
                assert_int_equal(info.stage, stage);
                assert_true(info.top >= prev_top); /* sorted, shallowest first */
                prev_top = info.top;
                total += info.area;
            }
            assert_rel(total, rc.params.l0, 1e-14); /* the pieces tile [0, l0] */
            free(seen);
            free(w);
            free(h);
            free(left);
            ct_bundle_free(b);
        }
}

/* The distributions' moments over 2e5 splits: uniform on f (1 +- s) (mean f, variance
 * (f s)^2 / 3, range), log-normal (ln(f_k / f) has mean 0 and sd s; fx_k and fz_k
 * uncorrelated). Tolerances: 6 standard errors. */
static void ratio_distributions(void **state)
{
    (void)state;
    enum { N = 200000 };
    ct_random_cantor rc = surface(CT_RATIO_UNIFORM, 0.2, 0.2, 20);
    long double sx = 0, sxx = 0, sz = 0, szz = 0;
    for (uint64_t g = 1; g <= N; g++) {
        double fx, fz;
        ct_random_cantor_ratios(&rc, 1, g, &fx, &fz, NULL);
        assert_true(fx > 1.5 * 0.8 && fx < 1.5 * 1.2 && fz > 1.3 * 0.8 && fz < 1.3 * 1.2);
        sx += fx;
        sxx += (fx - 1.5L) * (fx - 1.5L);
        sz += fz;
        szz += (fz - 1.3L) * (fz - 1.3L);
    }
    const long double vx = 0.3L * 0.3L / 3.0L, vz = 0.26L * 0.26L / 3.0L;
    assert_true(fabsl(sx / N - 1.5L) < 6.0L * sqrtl(vx / N));
    assert_true(fabsl(sz / N - 1.3L) < 6.0L * sqrtl(vz / N));
    assert_true(fabsl(sxx / N - vx) < 6.0L * vx * sqrtl(0.8L / N)); /* var of U^2: 4/5 var^2 */
    assert_true(fabsl(szz / N - vz) < 6.0L * vz * sqrtl(0.8L / N));

    rc = surface(CT_RATIO_LOGNORMAL, 0.05, 0.04, 20);
    long double mx = 0, mxx = 0, mz = 0, mzz = 0, mxz = 0;
    for (uint64_t g = 1; g <= N; g++) {
        double fx, fz;
        ct_random_cantor_ratios(&rc, 1, g, &fx, &fz, NULL);
        long double x = logl(fx / 1.5L) / 0.05L, z = logl(fz / 1.3L) / 0.04L;
        mx += x;
        mxx += x * x;
        mz += z;
        mzz += z * z;
        mxz += x * z;
    }
    assert_true(fabsl(mx / N) < 6.0L / sqrtl(N));
    assert_true(fabsl(mz / N) < 6.0L / sqrtl(N));
    assert_true(fabsl(mxx / N - 1.0L) < 6.0L * sqrtl(2.0L / N));
    assert_true(fabsl(mzz / N - 1.0L) < 6.0L * sqrtl(2.0L / N));
    assert_true(fabsl(mxz / N) < 6.0L / sqrtl(N));
}

/* Draws outside the valid ranges are moved to the nearest double inside and counted; the
 * bundle's counts are those of all its splits. */
static void clipping_is_counted(void **state)
{
    (void)state;
    ct_random_cantor rc = surface(CT_RATIO_LOGNORMAL, 0.4, 0.5, 8);
    const uint64_t n = ((uint64_t)2 << 8) - 1;
    uint64_t nx = 0, nz = 0;
    for (uint64_t g = 1; g < n; g++) {
        double fx, fz;
        int clipped;
        ct_random_cantor_ratios(&rc, 3, g, &fx, &fz, &clipped);
        assert_true(fx > 1.0 && fz > 1.0 && fz < 2.0);
        if (clipped & 1) {
            nx++;
            assert_true(fx == 1.0 + DBL_EPSILON);
        }
        if (clipped & 2) {
            nz++;
            assert_true(fz == 1.0 + DBL_EPSILON || fz == 2.0 - DBL_EPSILON);
        }
    }
    /* P(fx_k < 1) = P(Z < -ln 1.5 / 0.4) = 0.156, P(fz_k outside (1, 2)) = 0.32 */
    assert_true(nx > 40 && nz > 100);
    ct_bundle *b;
    uint64_t cx, cz, draws;
    assert_int_equal(ct_random_cantor_bundle(&b, &rc, 3, 0), CT_OK);
    assert_int_equal(ct_random_cantor_clipped(b, &cx, &cz, &draws), CT_OK);
    assert_true(cx == nx && cz == nz && draws == n - 1);
    ct_bundle_free(b);
    /* a uniform spread that keeps inside the ranges clips nothing */
    rc = surface(CT_RATIO_UNIFORM, 0.3, 0.2, 8);
    assert_int_equal(ct_random_cantor_bundle(&b, &rc, 3, 0), CT_OK);
    assert_int_equal(ct_random_cantor_clipped(b, &cx, &cz, &draws), CT_OK);
    assert_true(cx == 0 && cz == 0);
    ct_bundle_free(b);
    /* a bundle of another kind has no draws */
    ct_params p = rc.params;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 4, INFINITY), CT_OK);
    assert_int_equal(ct_random_cantor_clipped(b, &cx, &cz, &draws), CT_EINVAL);
    ct_bundle_free(b);
}

/* Width ratios beyond what doubles hold: a draw that overflows (f_x = 1.7e308 (1 + 0.5 (2U - 1))
 * is inf for U > 0.5 or so) is clipped to the largest double and counted, never inf (its
 * middle's area was inf/inf = NaN); a surface whose pieces then fall below the smallest normal
 * double is refused naming the piece, not swept as 'crushed' everywhere. */
static void ratios_beyond_doubles(void **state)
{
    (void)state;
    const ct_ratio_dist dists[2] = {CT_RATIO_UNIFORM, CT_RATIO_LOGNORMAL};
    const double fx[2] = {1.7e308, 1e300}, spread[2] = {0.5, 10.0};
    for (int d = 0; d < 2; d++) {
        ct_random_cantor rc = surface(dists[d], spread[d], 0.0, 6);
        rc.params.fx = fx[d];
        uint64_t over = 0;
        for (uint64_t g = 1; g < ((uint64_t)2 << 6) - 1; g++) {
            double x, z;
            int clipped;
            assert_int_equal(ct_random_cantor_ratios(&rc, 0, g, &x, &z, &clipped), CT_OK);
            assert_true(isfinite(x) && x > 1.0);
            if (x == DBL_MAX) {
                assert_true(clipped & 1);
                over++;
            }
        }
        /* uniform: U > 0.56 overflows, ~55 of 126 draws; lognormal: Z > 1.9, ~3.6 */
        if (!(d ? over >= 1 : over > 30))
            fail_msg("%s: %llu of 126 draws overflowed", d ? "lognormal" : "uniform",
                     (unsigned long long)over);
        ct_bundle *b = NULL;
        assert_int_equal(ct_random_cantor_bundle(&b, &rc, 0, 0), CT_ERANGE);
        assert_null(b);
        assert_non_null(strstr(ct_error_message(), "smallest normal double"));
    }
    /* large but holdable: f_x = 1e30 at depth 6 keeps every piece above 1e-185 */
    ct_random_cantor rc = surface(CT_RATIO_UNIFORM, 0.5, 0.0, 6);
    rc.params.fx = 1e30;
    ct_bundle *b;
    assert_int_equal(ct_random_cantor_bundle(&b, &rc, 0, 0), CT_OK);
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        ct_rod_info info;
        assert_int_equal(ct_bundle_rod(b, k, &info), CT_OK);
        assert_true(info.area >= DBL_MIN && isfinite(info.area));
    }
    ct_bundle_free(b);
}

/* Spread 0 is the deterministic surface: the same pieces (stage, x-extent) with tops and areas
 * equal to (2 i + 4) ulps at stage i, not bit for bit: cantor.c computes h0 f^-i in one
 * exp/log (no drift over deep stages), a random piece multiplies its own i ratios. So e,
 * u_max and V*_c agree to rounding: 1e-12 relative, for both distributions, several
 * surfaces (f close to 1 too) and repeated impacts. */
static void spread_zero_is_the_deterministic_surface(void **state)
{
    (void)state;
    const double fxs[3] = {1.5, 1.0001, 3.0}, fzs[3] = {1.3, 1.0001, 1.9};
    const double V[6] = {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 2e-2};
    for (int d = 0; d < 2; d++)
        for (int s = 0; s < 3; s++) {
            ct_random_cantor rc = surface(d ? CT_RATIO_LOGNORMAL : CT_RATIO_UNIFORM, 0.0, 0.0, 12);
            rc.params.fx = fxs[s];
            rc.params.fz = fzs[s];
            rc.params.l0 = rc.params.h0 = 1.0;
            rc.params.Hstar = 10.0;
            ct_bundle *r, *c;
            assert_int_equal(ct_random_cantor_bundle(&r, &rc, 9, 0), CT_OK);
            assert_int_equal(ct_cantor_bundle(&c, &rc.params, CT_REP_SEGMENTS, 12, INFINITY),
                             CT_OK);
            uint64_t cx, cz, draws;
            ct_random_cantor_clipped(r, &cx, &cz, &draws);
            assert_true(cx == 0 && cz == 0);
            for (size_t k = 0; k < ct_bundle_size(r); k++) {
                uint64_t g;
                ct_rod_info a, b;
                ct_random_cantor_piece(r, k, &g);
                ct_bundle_rod(r, k, &a);
                ct_bundle_rod(c, (size_t)g, &b);
                assert_int_equal(a.stage, b.stage);
                const double tol = (2.0 * (double)a.stage + 4.0) * DBL_EPSILON;
                assert_rel(a.top, b.top, tol);
                assert_rel(a.area, b.area, tol);
                assert_true(fabs(a.x_left - b.x_left) <= tol);
                assert_true(fabs(a.x_right - b.x_right) <= tol);
            }
            ct_sweep_spec spec = {.V_star = V, .nvel = 6, .impacts = 2};
            ct_impact_opts_default(&spec.opts);
            ct_sweep_row rr[12], cr[12];
            assert_int_equal(ct_sweep(r, &spec, rr), CT_OK);
            assert_int_equal(ct_sweep(c, &spec, cr), CT_OK);
            for (int q = 0; q < 12; q++) {
                assert_int_equal(rr[q].status, cr[q].status);
                if (cr[q].status)
                    continue;
                assert_rel(rr[q].r.e, cr[q].r.e, 1e-12);
                assert_rel(rr[q].r.u_max, cr[q].r.u_max, 1e-12);
                assert_rel(rr[q].r.V_star_crit, cr[q].r.V_star_crit, 1e-12);
            }
            ct_bundle_free(r);
            ct_bundle_free(c);
        }
}

/* A realisation is a pure function of (seed, realisation): the same with 1 or 2 threads
 * (stages wide enough to be split among threads), another for another index or seed. */
static void realisations_are_pure(void **state)
{
    (void)state;
    ct_random_cantor rc = surface(CT_RATIO_LOGNORMAL, 0.2, 0.1, 15);
    ct_bundle *a, *b, *c, *d;
    assert_int_equal(ct_random_cantor_bundle(&a, &rc, 4, 1), CT_OK);
    assert_int_equal(ct_random_cantor_bundle(&b, &rc, 4, 2), CT_OK);
    assert_int_equal(ct_random_cantor_bundle(&c, &rc, 5, 2), CT_OK);
    rc.seed++;
    assert_int_equal(ct_random_cantor_bundle(&d, &rc, 4, 2), CT_OK);
    size_t same_c = 0, same_d = 0;
    for (size_t k = 0; k < ct_bundle_size(a); k++) {
        ct_rod_info x, y, z, w;
        ct_bundle_rod(a, k, &x);
        ct_bundle_rod(b, k, &y);
        ct_bundle_rod(c, k, &z);
        ct_bundle_rod(d, k, &w);
        assert_true(memcmp(&x, &y, sizeof x) == 0);
        same_c += x.top == z.top;
        same_d += x.top == w.top;
    }
    assert_true(same_c < 10 && same_d < 10);
    ct_bundle *e;
    assert_int_equal(ct_bundle_clone(&e, a), CT_OK); /* the clone keeps the pieces */
    uint64_t g1, g2;
    ct_random_cantor_piece(a, 1234, &g1);
    ct_random_cantor_piece(e, 1234, &g2);
    assert_true(g1 == g2);
    ct_bundle_free(a);
    ct_bundle_free(b);
    ct_bundle_free(c);
    ct_bundle_free(d);
    ct_bundle_free(e);
}

static void invalid_surfaces(void **state)
{
    (void)state;
    ct_random_cantor rc = surface(CT_RATIO_UNIFORM, 1.0, 0.0, 4);
    ct_bundle *b = (ct_bundle *)1;
    assert_int_equal(ct_random_cantor_bundle(&b, &rc, 0, 0), CT_EINVAL);
    assert_null(b);
    assert_non_null(strstr(ct_error_message(), "fx_spread"));
    rc = surface(CT_RATIO_LOGNORMAL, 0.1, 10.5, 4);
    assert_int_equal(ct_random_cantor_validate(&rc), CT_EINVAL);
    rc = surface(CT_RATIO_LOGNORMAL, 0.1, -0.1, 4);
    assert_int_equal(ct_random_cantor_validate(&rc), CT_EINVAL);
    rc = surface(CT_RATIO_LOGNORMAL, NAN, 0.1, 4);
    assert_int_equal(ct_random_cantor_validate(&rc), CT_EINVAL);
    rc = surface(CT_RATIO_LOGNORMAL, 0.1, 0.1, CT_MAX_RANDOM_DEPTH + 1);
    assert_int_equal(ct_random_cantor_validate(&rc), CT_EINVAL);
    rc = surface((ct_ratio_dist)7, 0.1, 0.1, 4);
    assert_int_equal(ct_random_cantor_validate(&rc), CT_EINVAL);
    rc = surface(CT_RATIO_LOGNORMAL, 0.1, 0.1, 4);
    rc.params.fz = 2.0;
    assert_int_equal(ct_random_cantor_validate(&rc), CT_EINVAL);
    rc = surface(CT_RATIO_LOGNORMAL, 0.0, 0.0, 30); /* 2^31 rods: refused with the figure */
    assert_int_equal(ct_random_cantor_bundle(&b, &rc, 0, 0), CT_ENOMEM);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(generator_and_keying),
        cmocka_unit_test(rods_against_the_ratios),
        cmocka_unit_test(rods_bitwise_and_sorted),
        cmocka_unit_test(ratio_distributions),
        cmocka_unit_test(clipping_is_counted),
        cmocka_unit_test(ratios_beyond_doubles),
        cmocka_unit_test(spread_zero_is_the_deterministic_surface),
        cmocka_unit_test(realisations_are_pure),
        cmocka_unit_test(invalid_surfaces),
    };
    return cmocka_run_group_tests_name("random", tests, NULL, NULL);
}
