/* Measures where the OpenMP force assembly starts to pay: one force evaluation on segment
 * bundles of 2^11 - 1 ... 2^21 - 1 rods, serial against the thread team (all threads).
 * Prints CSV: rods,threads,serial_ns,parallel_ns,speedup; then the smallest size at which
 * the team is at least 10% faster (the value for CT_PARALLEL_MIN_RODS).
 * Then the same for building the load curve (its event passes and merge sort) on rod sets of
 * 2^12 ... 2^20 rods with scattered tops after a history (many runs to merge): the curve
 * uses a team from 64 x CT_PARALLEL_MIN_RODS rods. Both in one warm process: a short run
 * also pays the team's start and its spinning workers, which this does not see. */
#include "cantact.h"
#include "internal.h"
#include "common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static double time_force(ct_bundle *b, double *sink)
{
    /* calls enough to last >= 20 ms, median of 7 */
    double t[7];
    int calls = 1;
    for (;;) {
        double t0 = bench_now();
        for (int c = 0; c < calls; c++)
            *sink += ct_bundle_force(b, 0.2 + 1e-9 * c);
        if (bench_now() - t0 > 0.02)
            break;
        calls *= 2;
    }
    for (int r = 0; r < 7; r++) {
        double t0 = bench_now();
        for (int c = 0; c < calls; c++)
            *sink += ct_bundle_force(b, 0.2 + 1e-9 * c);
        t[r] = (bench_now() - t0) / calls;
    }
    return bench_median(t, 7);
}

static double time_curve(ct_curve *c, const ct_bundle *b)
{
    double t[7];
    for (int r = -1; r < 7; r++) { /* one warm-up */
        double t0 = bench_now();
        if (ct_curve_build(c, b)) {
            fprintf(stderr, "bench_threshold: %s\n", ct_error_message());
            exit(1);
        }
        if (r >= 0)
            t[r] = bench_now() - t0;
    }
    return bench_median(t, 7);
}

static int curve_thresholds(int threads)
{
    ct_layer L = {.E = 200.0, .sigma_y = 1.0, .Hstar = 3.0, .l0 = 1.0, .h0 = 1.0};
    ct_curve *c;
    if (ct_curve_alloc(&c))
        return 1;
    size_t threshold = 0;
    printf("curve_rods,threads,serial_ms,parallel_ms,speedup\n");
    for (int lg = 12; lg <= 20; lg++) {
        const size_t n = (size_t)1 << lg;
        double *top = malloc(n * sizeof(double)), *area = malloc(n * sizeof(double));
        ct_bundle *b;
        if (!top || !area)
            return 1;
        for (size_t k = 0; k < n; k++) {
            top[k] = 0.4 * fmod(0.6180339887498949 * (double)k, 1.0);
            area[k] = 1.0 / (double)n;
        }
        if (ct_bundle_from_rods(&b, &L, n, top, area)) {
            fprintf(stderr, "bench_threshold: %s\n", ct_error_message());
            return 1;
        }
        free(top);
        free(area);
        ct_bundle_advance(b, 0.3);
        ct_bundle_set_parallel_min(b, SIZE_MAX);
        double ts = time_curve(c, b);
        ct_bundle_set_parallel_min(b, 0);
        double tp = time_curve(c, b);
        printf("%zu,%d,%.3f,%.3f,%.3f\n", n, threads, 1e3 * ts, 1e3 * tp, ts / tp);
        if (!threshold && ts / tp >= 1.1)
            threshold = n;
        ct_bundle_free(b);
    }
    ct_curve_free(c);
    printf("# curve: team >= 10%% faster from %zu rods (the curve's team from 64 x %d = %d)\n",
           threshold, CT_PARALLEL_MIN_RODS, 64 * CT_PARALLEL_MIN_RODS);
    return 0;
}

int main(void)
{
    ct_params p = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1};
    int threads = ct_default_threads();
    double sink = 0.0;
    size_t threshold = 0;
    bench_machine(stdout);
    printf("rods,threads,serial_ns,parallel_ns,speedup\n");
    for (long depth = 10; depth <= 20; depth++) {
        ct_bundle *b;
        if (ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, depth, INFINITY)) {
            fprintf(stderr, "bench_threshold: %s\n", ct_error_message());
            return 1;
        }
        ct_bundle_advance(b, 0.3);
        ct_bundle_set_parallel_min(b, SIZE_MAX);
        double ts = time_force(b, &sink);
        ct_bundle_set_parallel_min(b, 0);
        double tp = time_force(b, &sink);
        printf("%zu,%d,%.1f,%.1f,%.3f\n", ct_bundle_size(b), threads, 1e9 * ts, 1e9 * tp, ts / tp);
        if (!threshold && ts / tp >= 1.1)
            threshold = ct_bundle_size(b);
        ct_bundle_free(b);
    }
    printf("# team >= 10%% faster from %zu rods (CT_PARALLEL_MIN_RODS = %d)%s\n", threshold,
           CT_PARALLEL_MIN_RODS, sink == 42.0 ? " " : "");
    return curve_thresholds(threads);
}
