/* The sweep of issue 11 inside one process: planning (fractal depth, pruning) and ct_sweep
 * over 2000 speeds (fx 1.5, fz 1.3, H = H*:h0 = 10, E/sigma_y 500, V* = 1e-4..1e-2 log, stage
 * rods), 1 and 10 impacts per speed, with and without the closed-form check. The whole
 * process adds the program's start and its CSV writing: scripts/bench measures that, and
 * /bin/true beside it.
 * Prints CSV: case,impacts,check,rods,median_seconds,us_per_impact
 * Usage: bench_sweep [--quick] */
#include "cantact.h"
#include "common.h"

#include <math.h>

enum { NV = 2000 };

static void fail(const char *what)
{
    fprintf(stderr, "bench_sweep: %s: %s\n", what, ct_error_message());
    exit(1);
}

int main(int argc, char **argv)
{
    const int quick = argc > 1 && !strcmp(argv[1], "--quick");
    const int runs = quick ? 5 : 21;
    static double V[NV];
    for (int k = 0; k < NV; k++)
        V[k] = 1e-4 * pow(100.0, (double)k / (NV - 1));
    ct_cantor_plan plan = {
        .params =
            {.fx = 1.5, .fz = 1.3, .l0 = 1.0, .h0 = 1.0, .Hstar = 10.0, .E = 500.0, .sigma_y = 1.0},
        .depth = CT_DEPTH_FRACTAL,
        .representation = CT_REP_STAGES,
        .depth_tolerance = 1e-12,
        .V_star = V,
        .nvel = NV,
        .impacts = 10};
    ct_impact_opts_default(&plan.opts);
    bench_machine(stdout);
    printf("case,impacts,check,rods,median_seconds,us_per_impact\n");
    static ct_sweep_row rows[NV * 10];
    double t[21], sink = 0.0;
    ct_bundle *b = NULL;
    ct_plan_info info;
    for (int r = 0; r < runs; r++) {
        ct_bundle_free(b);
        double t0 = bench_now();
        if (ct_cantor_plan_build(&plan, &b, &info))
            fail("plan");
        t[r] = bench_now() - t0;
    }
    printf("plan,10,-,%zu,%.6g,\n", info.rods, bench_median(t, runs));
    for (int impacts = 1; impacts <= 10; impacts += 9)
        for (int check = 1; check >= 0; check--) {
            ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = impacts};
            spec.opts = plan.opts;
            spec.opts.check = check;
            for (int r = 0; r < runs; r++) {
                double t0 = bench_now();
                if (ct_sweep(b, &spec, rows))
                    fail("sweep");
                t[r] = bench_now() - t0;
                sink += rows[NV * impacts - 1].r.e;
            }
            double m = bench_median(t, runs);
            printf("sweep,%d,%s,%zu,%.6g,%.4g\n", impacts, check ? "closed" : "none", info.rods, m,
                   1e6 * m / (NV * impacts));
        }
    printf("# checksum %.17g\n", sink);
    ct_bundle_free(b);
    return 0;
}
