/* The paper's series (docs/model.md §5, Eqs. 12-24) for the infinite fractal, and the impact
 * energy balance (Eqs. 39-41) under it (src/laws/law.c chooses among the laws). */
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

static double lfz(const ct_params *p)
{
    return log1p(p->fz - 1.0);
}

/* First stage in contact at u: the smallest i with h_i < u (0 when u > h0). */
static double first_contact_stage(const ct_params *p, double u)
{
    double x = log(p->h0 / u) / lfz(p);
    if (x < 0.0)
        return 0.0;
    return floor(x) + 1.0;
}

/* First plastic stage at u under the exact yield test of Eq. 29: fz^-i <= chi; INFINITY
 * when chi <= 0 (Eq. 31 with n_c + 1 = ceil(-ln chi / ln fz)). */
static double first_plastic_stage(const ct_params *p, double u)
{
    double eps_y = p->sigma_y / p->E;
    double chi = (u - p->Hstar * eps_y) / (p->h0 * (1.0 - eps_y)); /* Eq. 30 */
    if (chi <= 0.0)
        return INFINITY;
    double x = ceil(-log(chi) / lfz(p));
    return x < 0.0 ? 0.0 : x;
}

/* (E/H*) sum_{i=a}^{b} s_i (u - h_i) (Eq. 14) */
static double elastic_sum(const ct_params *p, double u, double a, double b)
{
    if (b < a)
        return 0.0;
    return p->E / p->Hstar * (u * ct_sum_area(p, a, b) - ct_sum_depth_area(p, a, b));
}

static double series_load_value(const ct_params *p, double u)
{
    if (!(u > 0.0))
        return 0.0;
    double n1 = first_contact_stage(p, u), np = first_plastic_stage(p, u);
    if (np < n1)
        np = n1; /* clamp n_c >= n */
    /* Eq. 15: elastic stages n+1..n_c, plastic n_c+1..inf at sigma_y */
    return elastic_sum(p, u, n1, np - 1.0) + p->sigma_y * ct_stage_length(p, np);
}

static double series_unload_value(const ct_params *p, double u_max, double u)
{
    double np = first_plastic_stage(p, u_max); /* n-bar_c + 1 */
    if (!(u > 0.0))
        return 0.0;
    double n1 = first_contact_stage(p, u);
    double eps_y = p->sigma_y / p->E;
    /* elastic stages (i <= n-bar_c) follow their loading line (Eq. 22, first sum) */
    double P = elastic_sum(p, u, n1, np - 1.0);
    if (isinf(np))
        return P;
    /* plastic stages touch while u >= h-bar_i = u_max - eps_y (H* - h_i), i.e. while
     * h_i <= (u - u_max + eps_y H*) / eps_y; each at E s_i ((u - u_max)/H* + eps_y) (Eq. 24) */
    double hcut = (u - u_max + eps_y * p->Hstar) / eps_y;
    if (!(hcut > 0.0))
        return P;
    double first = hcut >= p->h0 ? 0.0 : ceil(log(p->h0 / hcut) / lfz(p));
    if (first < np)
        first = np;
    double factor = (u - u_max) / p->Hstar + eps_y;
    if (factor > 0.0)
        P += p->E * ct_stage_length(p, first) * factor;
    return P;
}

/* The parameters, then a displacement `name` = u [length]: CT_EINVAL unless finite and >= 0,
 * CT_ERANGE beyond H* (strains >= 1: the layer would be crushed). */
static int check_u(const ct_params *p, const char *name, double u)
{
    int st;
    if ((st = ct_params_validate(p)))
        return st;
    if (!isfinite(u) || u < 0.0)
        return ct_error_set(CT_EINVAL, "series: %s = %g: must be finite and >= 0", name, u);
    if (u > p->Hstar)
        return ct_error_set(CT_ERANGE,
                            "series: %s = %.17g is beyond H* = %.17g (strains >= 1: the layer "
                            "would be crushed)",
                            name, u, p->Hstar);
    return CT_OK;
}

int ct_series_load(const ct_params *p, double u, double *P)
{
    CT_NEED(P);
    int st = check_u(p, "u", u);
    if (st)
        return st;
    *P = series_load_value(p, u);
    return CT_OK;
}

int ct_series_unload(const ct_params *p, double u_max, double u, double *P)
{
    CT_NEED(P);
    int st;
    if ((st = check_u(p, "u_max", u_max)) || (st = check_u(p, "u", u)))
        return st;
    *P = series_unload_value(p, u_max, u);
    return CT_OK;
}

/* ---- energies of the series by breakpoint quadrature ---- */

/* Stages carried as breakpoints: down to h_M <= 1e-18 h0 (or 2e5 stages); the remaining
 * interval next to the accumulation point gets one Gauss pair, its error far below 1e-15. */
static long series_stages(const ct_params *p)
{
    double M = ceil(log(1e18) / lfz(p));
    return M > 200000.0 ? 200000 : (long)M;
}

typedef double (*law_force)(const ct_params *p, double u_max, double u);

static double load_force(const ct_params *p, double u_max, double u)
{
    (void)u_max;
    return series_load_value(p, u);
}

/* Piecewise-linear integrand between sorted breakpoints: per interval, the values at the two
 * Gauss points define the line (jumps sit on breakpoints). */
typedef struct {
    double a, b, Pa, slope, W_before;
} piece;

static int build_pieces(const ct_params *p, law_force f, double u_max, double *pts, size_t n,
                        piece **out)
{
    const double g = 0.57735026918962576451;
    *out = NULL;
    piece *pc = malloc((n ? n : 1) * sizeof *pc);
    if (!pc)
        return ct_error_set(CT_ENOMEM, "series: out of memory");
    double W = 0.0;
    for (size_t k = 0; k + 1 < n; k++) {
        double a = pts[k], b = pts[k + 1], mid = 0.5 * (a + b), half = 0.5 * (b - a);
        double x1 = mid - half * g, x2 = mid + half * g;
        double P1 = f(p, u_max, x1), P2 = f(p, u_max, x2);
        pc[k].a = a;
        pc[k].b = b;
        pc[k].slope = x2 > x1 ? (P2 - P1) / (x2 - x1) : 0.0;
        pc[k].Pa = P1 - pc[k].slope * (x1 - a);
        pc[k].W_before = W;
        W += half * (P1 + P2);
    }
    if (n)
        pc[n - 1] = (piece){pts[n - 1], pts[n - 1], 0.0, 0.0, W};
    *out = pc;
    return CT_OK;
}

static size_t series_load_points(const ct_params *p, double hi, double *pts)
{
    long M = series_stages(p);
    double eps_y = p->sigma_y / p->E;
    size_t n = 0;
    pts[n++] = 0.0;
    pts[n++] = hi;
    for (long i = 0; i <= M; i++) {
        double h = ct_stage_depth(p, (double)i), y = eps_y * p->Hstar + (1.0 - eps_y) * h;
        if (h > 0.0 && h < hi)
            pts[n++] = h;
        if (y < hi)
            pts[n++] = y;
    }
    pts[n++] = eps_y * p->Hstar < hi ? eps_y * p->Hstar : 0.0;
    return ct_sort_unique(pts, n);
}

/* sum_{i >= n} s_i h_i^2 = l0 (1 - 1/fx) h0^2 gamma^n / (1 - gamma), gamma = 1/(fx fz^2). */
static double tail_depth2_area(const ct_params *p, double n)
{
    const double lg = log1p(p->fx - 1.0) + 2.0 * log1p(p->fz - 1.0);
    return p->l0 * ((p->fx - 1.0) / p->fx) * p->h0 * p->h0 * exp(-n * lg) / -expm1(-lg);
}

/* Eq. 22-24's unloading work from u_max, stage by stage in closed form: an elastic stage in
 * contact gives back E s_i (u_max - h_i)^2 / (2 H*) along its loading line; a plastic one
 * (i >= n-bar_c + 1, Eq. 29) carries E s_i ((u - u_max)/H* + eps_y) from its release point
 * u_max - eps_y (H* - h_i) up, E s_i eps_y^2 (H* - h_i)(H* + h_i) / (2 H*) in all. Stages 0 .. M
 * one by one, the deeper ones (h_i <= 1e-18 h0) by their geometric sums. *bound: the rounding
 * of u_max carried into the elastic terms, 2 eps u_max / (u_max - h_i) of each; *closest: the
 * smallest u_max - h_i among them. */
static double series_unload_work(const ct_params *p, double u_max, long M, double *bound,
                                 double *closest)
{
    const double eps_y = p->sigma_y / p->E, Hs = p->Hstar, np = first_plastic_stage(p, u_max);
    double elastic = 0.0, plastic = 0.0;
    *bound = 0.0;
    *closest = INFINITY;
    for (long i = 0; i <= M; i++) {
        const double h = ct_stage_depth(p, (double)i), s = ct_stage_area(p, (double)i);
        if ((double)i >= np) {
            plastic += s * (Hs - h) * (Hs + h);
        } else if (h < u_max) {
            const double d = u_max - h, term = s * d * d;
            elastic += term;
            *bound += term * 2.0 * DBL_EPSILON * u_max / d;
            *closest = d < *closest ? d : *closest;
        }
    }
    /* the stages below M: h_i <= 1e-18 h0, so h_i^2 is nothing beside H*^2; the elastic ones
     * (down to np) by sum s_i (u - h_i)^2 = u^2 A - 2 u B + C, h_i far below u */
    const double deep = (double)M + 1.0;
    if (np > deep) {
        const double last = isinf(np) ? INFINITY : np - 1.0;
        elastic += u_max * u_max * ct_sum_area(p, deep, last) -
                   2.0 * u_max * ct_sum_depth_area(p, deep, last) + tail_depth2_area(p, deep) -
                   (isinf(np) ? 0.0 : tail_depth2_area(p, np));
        plastic += isinf(np) ? 0.0 : Hs * Hs * ct_sum_area(p, np, INFINITY);
    } else {
        plastic += Hs * Hs * ct_sum_area(p, deep, INFINITY);
    }
    const double scale = p->E / (2.0 * Hs);
    *bound *= scale;
    return scale * (elastic + eps_y * eps_y * plastic);
}

int ct_series_impact(const ct_params *p, double W, double *u_max, double *e)
{
    long M = series_stages(p);
    double eps_y = p->sigma_y / p->E;
    double *pts = malloc((size_t)(2 * M + 8) * sizeof(double));
    if (!pts)
        return ct_error_set(CT_ENOMEM, "series: out of memory");
    size_t n = series_load_points(p, p->Hstar, pts);
    piece *pc = NULL;
    int st = build_pieces(p, load_force, 0.0, pts, n, &pc);
    if (st || n < 2) { /* n >= 2: 0 and H* are always there */
        free(pts);
        free(pc);
        return st ? st : ct_error_set(CT_EINVAL, "series: no interval to integrate");
    }
    if (!(W < pc[n - 1].W_before)) {
        free(pts);
        free(pc);
        return ct_error_set(CT_ERANGE, "series: impact energy %.6g reaches u_max >= H* = %g", W,
                            p->Hstar);
    }
    size_t lo = 0, hi = n - 1; /* W(pts[lo]) <= W < W(pts[hi]) */
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (pc[mid].W_before <= W)
            lo = mid;
        else
            hi = mid;
    }
    piece q = pc[lo];
    double R = W - q.W_before, disc = q.Pa * q.Pa + 2.0 * q.slope * R;
    double den = q.Pa + sqrt(disc > 0.0 ? disc : 0.0);
    double u = den > 0.0 ? q.a + 2.0 * R / den : q.b;
    *u_max = u < q.b ? u : q.b;
    free(pc);
    if (*u_max <= eps_y * p->Hstar) { /* no stage yields: chi <= 0 */
        free(pts);
        *e = 1.0;
        return CT_OK;
    }
    free(pts);
    /* unloading in closed form stage by stage: its quadrature between the breakpoints of
     * [u_max - eps_y H*, u_max] lost the eps_y-thin span in u_max's rounding (e was 1.2e-4 off
     * at E/sigma_y = 1e16, 0 at 1e18) */
    double bound, closest;
    const double Wu = series_unload_work(p, *u_max, M, &bound, &closest);
    if (!(bound <= 1e-13 * Wu))
        return ct_error_set(CT_ENOCONV,
                            "series: W_unload at u_max/h0 = %.17g hangs on u_max's rounding to "
                            "%.2g of itself (an elastic stage's top within %.3g h0 of u_max): e "
                            "not resolved",
                            *u_max / p->h0, bound / Wu, closest / p->h0);
    *e = sqrt(Wu / W);
    return CT_OK;
}
