/* The impact in time (issue 15): the history of one impact on the default surface at the
 * fractal depth (148 stage rods), with and without a 200-point grid, and the 2000-speed sweep
 * of bench/scenes/sweep2000.ini in one process with and without the time columns. The whole
 * process (start, scene, CSV) is timed by scripts/bench.
 * Prints CSV: case,V_star,grid,median_seconds,us_per_impact
 * Usage: bench_dynamics [--quick] */
#include "cantact.h"
#include "common.h"

#include <math.h>

enum { NV = 2000 };

static void fail(const char *what)
{
    fprintf(stderr, "bench_dynamics: %s: %s\n", what, ct_error_message());
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
        .impacts = 1,
        .keep_all_rods = 1};
    ct_impact_opts_default(&plan.opts);
    ct_bundle *b;
    ct_plan_info info;
    if (ct_cantor_plan_build(&plan, &b, &info))
        fail("plan");
    bench_machine(stdout);
    printf("# default surface, fractal depth %ld, %zu stage rods; m = E l0 / h0 (t in tau)\n",
           info.depth, info.rods);
    printf("case,V_star,grid,median_seconds,us_per_impact\n");
    double t[21], sink = 0.0;
    const double m = plan.params.E, Vs[] = {1e-4, 1e-3, 1e-2};
    for (int q = 0; q < 3; q++)
        for (size_t grid = 0; grid <= 200; grid += 200) {
            const int reps = quick ? 200 : 2000;
            for (int r = 0; r < runs; r++) {
                double t0 = bench_now();
                for (int k = 0; k < reps; k++) {
                    ct_impact_result res;
                    ct_dynamics d;
                    ct_history h;
                    if (ct_impact_history(b, m, sqrt(2.0) * Vs[q], grid, &res, &d,
                                          grid ? &h : NULL))
                        fail("history");
                    sink += d.t_contact;
                    if (grid)
                        ct_history_free(&h);
                }
                t[r] = (bench_now() - t0) / reps;
            }
            double med = bench_median(t, runs);
            printf("history,%g,%zu,%.6g,%.4g\n", Vs[q], grid, med, 1e6 * med);
        }
    static ct_sweep_row rows[NV];
    for (int dyn = 0; dyn <= 1; dyn++) {
        ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = 1, .dynamics = dyn};
        spec.opts = plan.opts;
        for (int r = 0; r < runs; r++) {
            double t0 = bench_now();
            if (ct_sweep(b, &spec, rows))
                fail("sweep");
            t[r] = bench_now() - t0;
            sink += rows[NV - 1].dyn.t_contact;
        }
        double med = bench_median(t, runs);
        printf("sweep%s,1e-4..1e-2,0,%.6g,%.4g\n", dyn ? "_time" : "", med, 1e6 * med / NV);
    }
    printf("# checksum %.17g\n", sink);
    ct_bundle_free(b);
    return 0;
}
