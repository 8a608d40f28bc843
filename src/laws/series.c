/* The paper's series (docs/model.md §5, Eqs. 12-24) for the infinite fractal, and the impact
 * energy balance (Eqs. 39-41) under it (src/laws/law.c chooses among the laws). */
#include "internal.h"

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
    /* unloading: tops of the elastic stages, release points of the plastic ones */
    double np = first_plastic_stage(p, *u_max), hbar = *u_max - eps_y * p->Hstar;
    size_t m = 0;
    pts[m++] = hbar;
    pts[m++] = *u_max;
    for (long i = 0; i <= M; i++) {
        double h = ct_stage_depth(p, (double)i);
        double b = i >= np ? *u_max - eps_y * (p->Hstar - h) : h;
        if (b > hbar && b < *u_max)
            pts[m++] = b;
    }
    m = ct_sort_unique(pts, m);
    piece *pu = NULL;
    st = build_pieces(p, series_unload_value, *u_max, pts, m, &pu);
    if (!st && pu && m >= 2) {
        double Wu = pu[m - 1].W_before;
        *e = sqrt(Wu / W);
        free(pu);
    }
    free(pts);
    return st;
}
