/* The validation grid of scripts/validate: how far the paper's asymptotic law and series are
 * from the exact rods (and from each other), in P(u) and in e. One CSV row per surface:
 *   fx,fz,E_over_sigma_y,H_over_h0,alpha,
 *   dP_asym_series_004,dP_asym_exact_004,dP_series_exact_004,   max rel. dev., u/h0 <= 0.04
 *   dP_asym_series_1,dP_asym_exact_1,dP_series_exact_1,         max rel. dev., u/h0 <= 1
 *   V_star_crit,V_star_h0,de_asym_exact,de_series_exact,de_consistent_exact,de_printed_consistent
 * (e deviations absolute, over V* from V*_c to the V* whose u_max is h0; empty when the
 * surface first yields beyond u = h0). Usage: ct_validate [--quick] */
#include "cantact.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double rel(double a, double b)
{
    return fabs(a - b) / fabs(b);
}

/* ct_validate curve FX FZ E H UMAX: load 0..UMAX then unload, exact rods beside the laws */
static int curve(char **argv)
{
    ct_params p = {atof(argv[2]), atof(argv[3]), 1.0, 1.0, atof(argv[5]), atof(argv[4]), 1.0};
    double um = atof(argv[6]);
    ct_bundle *b;
    if (ct_params_validate(&p) || ct_bundle_alloc(&b, &p, CT_REP_STAGES, 120, INFINITY)) {
        fprintf(stderr, "ct_validate: %s\n", ct_error_message());
        return 2;
    }
    printf("u_over_h0,branch,P_exact,P_series,P_asymptotic,P_asymptotic_consistent\n");
    for (int k = 0; k <= 400; k++) {
        double u = um * k / 400.0, ps = NAN, pa = NAN;
        ct_series_load(&p, u, &ps);
        ct_asym_load(&p, u, &pa); /* stays NAN beyond u = h0 */
        printf("%.10g,load,%.10g,%.10g,%.10g,%.10g\n", u, ct_bundle_force(b, u), ps, pa, pa);
    }
    ct_bundle_advance(b, um);
    printf("\n\n"); /* gnuplot index 1: unloading */
    double lo = ct_bundle_first_contact(b), hbar = um - p.Hstar * p.sigma_y / p.E;
    lo = lo < hbar ? lo : hbar;
    lo = lo > 0 ? lo : 0;
    for (int k = 400; k >= 0; k--) {
        double u = lo + (um - lo) * k / 400.0;
        double ps = NAN, pa = NAN, pc = NAN;
        ct_series_unload(&p, um, u, &ps);
        ct_asym_unload(&p, um, u, 0, &pa);
        ct_asym_unload(&p, um, u, 1, &pc);
        printf("%.10g,unload,%.10g,%.10g,%.10g,%.10g\n", u, ct_bundle_force(b, u), ps, pa, pc);
    }
    ct_bundle_free(b);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 7 && !strcmp(argv[1], "curve"))
        return curve(argv);
    int quick = argc > 1 && !strcmp(argv[1], "--quick");
    double fxs[] = {1.2, 1.5, 1.8}, fzs[] = {1.1, 1.3, 1.5, 1.7, 1.9};
    double Es[] = {100.0, 300.0, 1000.0}, Hs[] = {3.0, 10.0, 100.0};
    int nfx = quick ? 1 : 3, nfz = quick ? 2 : 5, nE = quick ? 1 : 3, nH = quick ? 1 : 3;
    printf("fx,fz,E_over_sigma_y,H_over_h0,alpha,dP_asym_series_004,dP_asym_exact_004,"
           "dP_series_exact_004,dP_asym_series_1,dP_asym_exact_1,dP_series_exact_1,V_star_crit,"
           "V_star_h0,de_asym_exact,de_series_exact,de_consistent_exact,de_printed_consistent\n");
    for (int a = 0; a < nfx; a++)
        for (int b = 0; b < nfz; b++)
            for (int c = 0; c < nE; c++)
                for (int d = 0; d < nH; d++) {
                    ct_params p = {fxs[a], fzs[b], 1.0, 1.0, Hs[d], Es[c], 1.0};
                    ct_bundle *bd;
                    /* depth 120 at these ratios: tips below 1e-5 h0, areas below 1e-9 l0 */
                    if (ct_bundle_alloc(&bd, &p, CT_REP_STAGES, 120, INFINITY)) {
                        fprintf(stderr, "ct_validate: %s\n", ct_error_message());
                        return 1;
                    }
                    double dev[2][3] = {{0}};
                    for (int k = 0; k <= 800; k++) {
                        double u = 1e-4 * pow(1e4, k / 800.0); /* 1e-4 .. 1 */
                        double Pe = ct_bundle_force(bd, u), Ps, Pa;
                        if (ct_series_load(&p, u, &Ps) || ct_asym_load(&p, u, &Pa)) {
                            fprintf(stderr, "ct_validate: %s\n", ct_error_message());
                            return 1;
                        }
                        double v[3] = {rel(Pa, Ps), rel(Pa, Pe), rel(Ps, Pe)};
                        for (int r = 0; r < 2; r++)
                            if (r == 1 || u <= 0.04)
                                for (int j = 0; j < 3; j++)
                                    dev[r][j] = v[j] > dev[r][j] ? v[j] : dev[r][j];
                    }
                    double Wc, uy, scale = ct_energy_scale(&p);
                    ct_critical_energy(bd, &Wc, &uy);
                    double W1 = ct_bundle_work(bd, 0.0, p.h0);
                    double Vc = sqrt(Wc / scale), V1 = sqrt(W1 / scale);
                    printf("%g,%g,%g,%g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g", p.fx, p.fz,
                           p.E, p.Hstar, ct_alpha(&p), dev[0][0], dev[0][1], dev[0][2], dev[1][0],
                           dev[1][1], dev[1][2], Vc, V1);
                    if (uy >= p.h0) {
                        printf(",,,,\n");
                        ct_bundle_free(bd);
                        continue;
                    }
                    double de[4] = {0};
                    int n = quick ? 8 : 30, failed = 0;
                    for (int k = 0; k < n && !failed; k++) {
                        double V = 1.001 * Vc * pow(V1 / (1.001 * Vc), k / (n - 1.0));
                        double W = V * V * scale, el[3], um;
                        ct_impact_result r;
                        ct_bundle_reset(bd);
                        if (ct_impact(bd, W, NULL, &r)) {
                            failed = 1;
                            break;
                        }
                        for (int l = 0; l < 3 && !failed; l++)
                            failed = ct_law_impact(&p, (ct_law)l, W, &um, &el[l]) != CT_OK;
                        if (failed)
                            break;
                        double v[4] = {fabs(el[1] - r.e), fabs(el[0] - r.e), fabs(el[2] - r.e),
                                       fabs(el[1] - el[2])};
                        for (int j = 0; j < 4; j++)
                            de[j] = v[j] > de[j] ? v[j] : de[j];
                    }
                    if (failed)
                        printf(",,,,\n"); /* a law refused (u_max >= H*): no e range */
                    else
                        printf(",%.6g,%.6g,%.6g,%.6g\n", de[0], de[1], de[2], de[3]);
                    ct_bundle_free(bd);
                }
    return 0;
}
