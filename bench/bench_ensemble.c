/* Issue 16's ensemble inside one process: R realisations of a random Cantor surface at depth
 * 16 (131071 rods each; fx 1.5, fz 1.3 with 10 % / 5 % log-normal spread, H 10, E/sigma_y
 * 500) x 100 speeds (V* = 1e-4 .. 1e-2, log), ct_ensemble with 1 and 2 threads (whole
 * realisations per thread, and one realisation's rods shared), with the closed-form check
 * on every realisation (all), on every eighth (auto, the CLI's default) and off (none). The whole
 * process with mpirun: scripts/bench. Prints CSV:
 * realisations,depth,speeds,threads,split,check,seconds,ms_per_realisation Usage: bench_ensemble
 * [--quick] [REALISATIONS]  (default 1000; --quick: 20) */
#include "cantact.h"
#include "common.h"

#include <math.h>

enum { NV = 100 };

int main(int argc, char **argv)
{
    const int quick = argc > 1 && !strcmp(argv[1], "--quick");
    const char *arg = argc > 1 + quick ? argv[1 + quick] : NULL;
    const uint64_t R = arg ? strtoull(arg, NULL, 10) : quick ? 20 : 1000;
    static double V[NV];
    for (int k = 0; k < NV; k++)
        V[k] = 1e-4 * pow(100.0, (double)k / (NV - 1));
    ct_ensemble_spec sp = {.surface = {.params = {.fx = 1.5,
                                                  .fz = 1.3,
                                                  .l0 = 1.0,
                                                  .h0 = 1.0,
                                                  .Hstar = 10.0,
                                                  .E = 500.0,
                                                  .sigma_y = 1.0},
                                       .dist = CT_RATIO_LOGNORMAL,
                                       .fx_spread = 0.1,
                                       .fz_spread = 0.05,
                                       .depth = 16,
                                       .seed = 1},
                           .first = 0,
                           .count = R,
                           .V_star = V,
                           .nvel = NV,
                           .impacts = 1};
    ct_impact_opts_default(&sp.opts);
    bench_machine(stdout);
    printf("realisations,depth,speeds,threads,split,check,seconds,ms_per_realisation\n");
    const struct {
        int threads;
        ct_ensemble_split split;
    } cases[] = {{1, CT_SPLIT_REALISATIONS}, {2, CT_SPLIT_REALISATIONS}, {2, CT_SPLIT_RODS}};
    double sink = 0.0;
    /* the check: every realisation (all), every eighth (auto, the CLI's default), none */
    const int checks[] = {CT_CHECK_ALL, CT_CHECK_AUTO, CT_CHECK_NONE};
    for (size_t h = 0; h < sizeof checks / sizeof checks[0]; h++)
        for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
            if (!quick && cases[c].split == CT_SPLIT_RODS)
                continue; /* small surfaces go by realisation; --quick shows why */
            sp.threads = cases[c].threads;
            sp.split = cases[c].split;
            sp.opts.check = checks[h];
            ct_ensemble_samples *s;
            if (ct_ensemble_samples_alloc(&s, 0, R, NV)) {
                fprintf(stderr, "bench_ensemble: %s\n", ct_error_message());
                return 1;
            }
            double t0 = bench_now();
            if (ct_ensemble(&sp, s)) {
                fprintf(stderr, "bench_ensemble: %s\n", ct_error_message());
                return 1;
            }
            double t = bench_now() - t0;
            sink += s->e[R * NV / 2];
            printf("%llu,16,%d,%d,%s,%s,%.4g,%.4g\n", (unsigned long long)R, NV, sp.threads,
                   sp.split == CT_SPLIT_RODS ? "rods" : "realisations",
                   checks[h] == CT_CHECK_ALL    ? "all"
                   : checks[h] == CT_CHECK_AUTO ? "auto"
                                                : "none",
                   t, 1e3 * t / (double)R);
            fflush(stdout);
            ct_ensemble_samples_free(s);
        }
    printf("# checksum %.17g\n", sink);
    return 0;
}
