/* The validation grid of scripts/validate: how far the paper's asymptotic law and series are
 * from the exact rods (and from each other), in P(u) and in e. One CSV row per surface:
 *   fx,fz,E_over_sigma_y,H_over_h0,alpha,
 *   dP_asym_series_004,dP_asym_exact_004,dP_series_exact_004,   max rel. dev., u/h0 <= 0.04
 *   dP_asym_series_1,dP_asym_exact_1,dP_series_exact_1,         max rel. dev., u/h0 <= 1
 *   V_star_crit,V_star_h0,de_asym_exact,de_series_exact,de_consistent_exact,de_printed_consistent
 * e deviations are absolute, over V* from just above V*_c to V*_h0, the largest V* at which
 * both the exact rods and the asymptotic law keep u_max <= h0 (the law's domain: it is
 * softer than the rods there, so its own u_max reaches h0 first); they are empty when the
 * surface first yields beyond u = h0 (eps_y H* >= h0), so that no impact in range yields.
 *
 * Exit status: 0 done; 1 when something that must work in this range did not (the exact
 * rods, the series, the asymptotic law within u <= h0, any of the laws' impacts up to V*_h0)
 * or a printed value leaves its bounds (a deviation not finite, an e outside [0, 1]); each
 * such failure is one line on stderr. 2: bad usage.
 * Usage: ct_validate [--quick]
 *        ct_validate curve FX FZ E_OVER_SIGMA_Y H_OVER_H0 UMAX_OVER_H0 */
#include "cantact.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double rel(double a, double b)
{
    return fabs(a - b) / fabs(b);
}

/* One line on stderr naming the surface; returns 1 (a failure) for the caller to count. */
static int complain(const ct_params *p, const char *what, const char *detail)
{
    fprintf(stderr, "ct_validate: fx %g, fz %g, E/sigma_y %g, H*/h0 %g: %s: %s\n", p->fx, p->fz,
            p->E, p->Hstar, what, detail);
    return 1;
}

/* A CSV field: empty when the value is not known (NAN). */
static void field(double v)
{
    if (isnan(v))
        fputs(",", stdout);
    else
        printf(",%.6g", v);
}

/* ct_validate curve FX FZ E H UMAX: load 0..UMAX then unload, exact rods beside the laws. The
 * asymptotic law's fields are empty beyond u = h0, outside its domain. */
static int curve(char **argv)
{
    ct_params p = {atof(argv[2]), atof(argv[3]), 1.0, 1.0, atof(argv[5]), atof(argv[4]), 1.0};
    double um = atof(argv[6]);
    ct_bundle *b;
    if (ct_params_validate(&p)) {
        fprintf(stderr, "ct_validate: %s\n", ct_error_message());
        return 2;
    }
    if (!(um > 0.0 && um < p.Hstar)) {
        fprintf(stderr, "ct_validate: UMAX = %g: must satisfy 0 < UMAX < H* = %g\n", um, p.Hstar);
        return 2;
    }
    if (ct_cantor_bundle(&b, &p, CT_REP_STAGES, 120, INFINITY))
        return complain(&p, "bundle", ct_error_message());
    int bad = 0;
    printf("u_over_h0,branch,P_exact,P_series,P_asymptotic,P_asymptotic_consistent\n");
    for (int k = 0; k <= 400 && !bad; k++) {
        double u = um * k / 400.0, ps = NAN, pa = NAN;
        int sa = ct_asym_load(&p, u, &pa);
        if (ct_series_load(&p, u, &ps) || (sa && sa != CT_ERANGE))
            bad = complain(&p, "loading curve", ct_error_message());
        printf("%.10g,load,%.10g", u, ct_bundle_force(b, u));
        field(ps);
        field(pa);
        field(pa);
        putchar('\n');
    }
    ct_bundle_advance(b, um);
    printf("\n\n"); /* gnuplot index 1: unloading */
    double lo = ct_bundle_first_contact(b), hbar = um - p.Hstar * p.sigma_y / p.E;
    lo = lo < hbar ? lo : hbar;
    lo = lo > 0 ? lo : 0;
    for (int k = 400; k >= 0 && !bad; k--) {
        double u = k == 400 ? um : lo + (um - lo) * k / 400.0, ps = NAN, pa = NAN, pc = NAN;
        int sa = ct_asym_unload(&p, um, u, 0, &pa), sc = ct_asym_unload(&p, um, u, 1, &pc);
        if (ct_series_unload(&p, um, u, &ps) || (sa && sa != CT_ERANGE) || (sc && sc != CT_ERANGE))
            bad = complain(&p, "unloading curve", ct_error_message());
        printf("%.10g,unload,%.10g", u, ct_bundle_force(b, u));
        field(ps);
        field(pa);
        field(pc);
        putchar('\n');
    }
    ct_bundle_free(b);
    return bad;
}

/* One surface's CSV row; returns 1 when a check failed (said on stderr), else 0. */
static int surface_row(const ct_params *p, int quick)
{
    int bad = 0;
    double dev[2][3] = {{NAN, NAN, NAN}, {NAN, NAN, NAN}};
    double Vc = NAN, V_h0 = NAN, de[4] = {NAN, NAN, NAN, NAN};
    ct_bundle *bd = NULL;
    /* depth 120 at these ratios: tips below 1e-5 h0, areas below 1e-9 l0 */
    if (ct_cantor_bundle(&bd, p, CT_REP_STAGES, 120, INFINITY)) {
        bad = complain(p, "bundle", ct_error_message());
        goto print;
    }
    for (int r = 0; r < 2; r++)
        for (int j = 0; j < 3; j++)
            dev[r][j] = 0.0;
    for (int k = 0; k <= 800 && !bad; k++) {
        double u = 1e-4 * pow(1e4, k / 800.0); /* 1e-4 .. 1 */
        double Pe = ct_bundle_force(bd, u), Ps, Pa;
        if (ct_series_load(p, u, &Ps) || ct_asym_load(p, u, &Pa)) {
            bad = complain(p, "P(u)", ct_error_message());
            break;
        }
        double v[3] = {rel(Pa, Ps), rel(Pa, Pe), rel(Ps, Pe)};
        for (int j = 0; j < 3; j++) {
            if (!isfinite(v[j])) {
                char why[160];
                snprintf(why, sizeof why, "P_exact %g, P_series %g, P_asymptotic %g", Pe, Ps, Pa);
                bad = complain(p, "a relative deviation of P(u) is not finite", why);
                break;
            }
            for (int r = 0; r < 2; r++)
                if (r == 1 || u <= 0.04)
                    dev[r][j] = v[j] > dev[r][j] ? v[j] : dev[r][j];
        }
    }
    double Wc, uy, W_h0 = ct_bundle_work(bd, 0.0, p->h0), W_asym_h0, scale = ct_energy_scale(p);
    if (ct_critical_energy(bd, &Wc, &uy)) {
        bad = complain(p, "critical energy", ct_error_message());
        goto print;
    }
    if (ct_asym_work_load(p, p->h0, &W_asym_h0)) {
        bad = complain(p, "asymptotic work to h0", ct_error_message());
        goto print;
    }
    /* strictly inside the law's domain: at W_asym_h0 itself its u_max would be h0 */
    double W_end = fmin(W_h0, (1.0 - 1e-9) * W_asym_h0);
    Vc = sqrt(Wc / scale);
    V_h0 = sqrt(W_end / scale);
    if (!(Vc > 0.0 && isfinite(V_h0))) {
        bad = complain(p, "V*_c or V*_h0 not a positive number", "");
        goto print;
    }
    if (uy >= p->h0)
        goto print; /* no impact within u_max <= h0 yields: no e range */
    if (!(V_h0 > 1.001 * Vc)) {
        bad = complain(p, "first yield below h0 but no e range", "V*_h0 <= 1.001 V*_c");
        goto print;
    }
    for (int j = 0; j < 4; j++)
        de[j] = 0.0;
    int n = quick ? 8 : 30;
    for (int k = 0; k < n && !bad; k++) {
        double V = 1.001 * Vc * pow(V_h0 / (1.001 * Vc), k / (n - 1.0));
        double W = V * V * scale, el[3], um;
        ct_impact_result r;
        ct_bundle_reset(bd);
        if (ct_impact(bd, W, NULL, &r)) {
            bad = complain(p, "exact impact", ct_error_message());
            break;
        }
        if (!(r.e >= 0.0 && r.e <= 1.0)) {
            bad = complain(p, "exact impact", "e outside [0, 1]");
            break;
        }
        for (int l = 0; l < 3 && !bad; l++) {
            if (ct_law_impact(p, (ct_law)l, W, &um, &el[l]))
                bad = complain(p, ct_law_name((ct_law)l), ct_error_message());
            else if (!(el[l] >= 0.0 && el[l] <= 1.0))
                bad = complain(p, ct_law_name((ct_law)l), "e outside [0, 1]");
        }
        if (bad)
            break;
        double v[4] = {fabs(el[1] - r.e), fabs(el[0] - r.e), fabs(el[2] - r.e),
                       fabs(el[1] - el[2])};
        for (int j = 0; j < 4; j++)
            de[j] = v[j] > de[j] ? v[j] : de[j];
    }
    if (bad)
        for (int j = 0; j < 4; j++)
            de[j] = NAN;
print:
    ct_bundle_free(bd);
    printf("%g,%g,%g,%g,%.6g", p->fx, p->fz, p->E, p->Hstar, ct_alpha(p));
    for (int r = 0; r < 2; r++)
        for (int j = 0; j < 3; j++)
            field(dev[r][j]);
    field(Vc);
    field(V_h0);
    for (int j = 0; j < 4; j++)
        field(de[j]);
    putchar('\n');
    return bad;
}

int main(int argc, char **argv)
{
    if (argc == 7 && !strcmp(argv[1], "curve"))
        return curve(argv);
    int quick = argc == 2 && !strcmp(argv[1], "--quick");
    if (argc > 2 || (argc == 2 && !quick)) {
        fprintf(stderr, "usage: ct_validate [--quick]\n"
                        "       ct_validate curve FX FZ E_OVER_SIGMA_Y H_OVER_H0 UMAX_OVER_H0\n");
        return 2;
    }
    double fxs[] = {1.2, 1.5, 1.8}, fzs[] = {1.1, 1.3, 1.5, 1.7, 1.9};
    double Es[] = {100.0, 300.0, 1000.0}, Hs[] = {3.0, 10.0, 100.0};
    int nfx = quick ? 1 : 3, nfz = quick ? 2 : 5, nE = quick ? 1 : 3, nH = quick ? 1 : 3;
    int failed = 0, surfaces = 0;
    printf("fx,fz,E_over_sigma_y,H_over_h0,alpha,dP_asym_series_004,dP_asym_exact_004,"
           "dP_series_exact_004,dP_asym_series_1,dP_asym_exact_1,dP_series_exact_1,V_star_crit,"
           "V_star_h0,de_asym_exact,de_series_exact,de_consistent_exact,de_printed_consistent\n");
    for (int a = 0; a < nfx; a++)
        for (int b = 0; b < nfz; b++)
            for (int c = 0; c < nE; c++)
                for (int d = 0; d < nH; d++) {
                    ct_params p = {fxs[a], fzs[b], 1.0, 1.0, Hs[d], Es[c], 1.0};
                    failed += surface_row(&p, quick);
                    surfaces++;
                }
    if (failed)
        fprintf(stderr, "ct_validate: %d of %d surfaces failed a check\n", failed, surfaces);
    return failed ? 1 : 0;
}
