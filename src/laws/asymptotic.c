/* The paper's asymptotic law (docs/model.md §6, Eqs. 25-38) and its energies in closed form. The
 * public functions check their inputs and return a status; the static *_value functions below
 * them assume checked parameters and 0 <= u <= u_max <= h0. */
#include "internal.h"

#include <math.h>

typedef struct {
    double h0, H, eps_y, alpha, fx, K, c, PY;
} law_consts;

static law_consts consts(const ct_params *p)
{
    law_consts k;
    k.h0 = p->h0;
    k.H = p->Hstar / p->h0;
    k.eps_y = p->sigma_y / p->E;
    k.alpha = ct_alpha(p);
    k.fx = p->fx;
    /* (fx - 1) beta / (1 - beta), and K = 1 - that = (1 - 1/fz) / (1 - beta) > 0 */
    k.c = (p->fx - 1.0) * ct_beta(p) / ct_one_minus_beta(p);
    k.K = ((p->fz - 1.0) / p->fz) / ct_one_minus_beta(p);
    k.PY = p->sigma_y * p->l0; /* Eq. 20 */
    return k;
}

static double chi_of(const law_consts *k, double u)
{
    return (u - k->H * k->h0 * k->eps_y) / (k->h0 * (1.0 - k->eps_y)); /* Eq. 30 */
}

/* Eq. 34's and Eq. 38's brackets are differences of powers of x and chi, or of u_max and
 * chi_M, which differ by about eps_y H: as printed, terms of order 1 whose sum is of order
 * eps_y (the load) or eps_y^2 (the unloading work), so e lost every digit from E/sigma_y ~ 1e10
 * (0.073 instead of 7.0e-8 at 1e16, 0 from 1e18). Written below in those small differences:
 * d = x - chi = eps_y (H - x) / (1 - eps_y) (Eq. 30), and powers of 1 - r, r = d / x, less 1. */

/* (1 - r)^p - 1 for 0 <= r <= 1, without cancellation as r -> 0. */
static double pow_less_one(double r, double p)
{
    return r < 1.0 ? expm1(p * log1p(-r)) : -1.0;
}

/* x - chi(x) [units of h0]: what the plastic stages' release shifts by (Eq. 30). */
static double chi_gap(const law_consts *k, double x)
{
    return k->eps_y * (k->H - x) / (1.0 - k->eps_y);
}

/* int from 1 - r to 1 of (y^p - (1 - r)^p) dy, of order p r^2 / 2: its binomial series where
 * p r < 1/2 (terms falling by p r / 2 or faster, no growth for large p), else the closed form
 * (1 - (1 - r)^(p+1)) / (p + 1) - r (1 - r)^p, which then loses at most a few ulps. */
static double power_excess_integral(double r, double p)
{
    if (!(p * r < 0.5))
        return -pow_less_one(r, p + 1.0) / (p + 1.0) - r * (1.0 + pow_less_one(r, p));
    /* sum_{k>=2} -r c_{k-1} (k - 1)/k with c_j = binomial(p, j) (-r)^j */
    double c = -p * r, sum = 0.0;
    for (int j = 1; j < 200; j++) {
        double term = -r * c * j / (j + 1.0);
        sum += term;
        if (!(fabs(term) > 1e-17 * fabs(sum)))
            break;
        c *= (p - j) / (j + 1.0) * -r;
    }
    return sum;
}

static double load_value(const law_consts *k, double u)
{
    if (!(u > 0.0))
        return 0.0;
    double x = u / k->h0, chi = chi_of(k, u), a = k->alpha;
    if (chi <= 0.0) /* Eq. 33 */
        return k->PY * k->K * pow(x, 1.0 + a) / (k->eps_y * k->fx * k->H);
    /* Eq. 34: x (x^a - chi^a) - c (x^(1+a) - chi^(1+a)), each difference x^p ((1 - r)^p - 1) */
    double r = chi_gap(k, x) / x;
    double br = pow(x, 1.0 + a) * (k->c * pow_less_one(r, 1.0 + a) - pow_less_one(r, a));
    return k->PY * (br / (k->eps_y * k->H * k->fx) + pow(chi, a) / k->fx);
}

static double work_load_value(const law_consts *k, double u)
{
    if (!(u > 0.0))
        return 0.0;
    double a = k->alpha, h0 = k->h0, x = u / h0, uy = k->eps_y * k->H * h0;
    if (u <= uy) /* Eq. 33 from 0: P_Y K h0 x^(2+a) / ((2+a) eps_y H fx) */
        return k->PY * k->K * h0 * pow(x, 2.0 + a) / ((2.0 + a) * k->eps_y * k->H * k->fx);
    /* Eq. 33 to the first yield x_y = eps_y H, then Eq. 34 from there (u = h0 ((1 - eps_y) chi
     * + eps_y H)): the terms in x_y^(2+a) cancel, and so do the chi^(1+a) / (1 + a) of the
     * bracket and of the plastic stages, which leaves, with K = 1 - c,
     * P_Y h0 [K (x^(2+a) - chi^(2+a)) / eps_y + (1 + K - eps_y) chi^(2+a)] / ((2+a) H fx) */
    double chi = chi_of(k, u), r = chi_gap(k, x) / x;
    double diff = -pow(x, 2.0 + a) * pow_less_one(r, 2.0 + a) / k->eps_y;
    return k->PY * h0 * (k->K * diff + (1.0 + k->K - k->eps_y) * pow(chi, 2.0 + a)) /
           ((2.0 + a) * k->H * k->fx);
}

/* Eq. 38's two branches. Branch 1, as printed, is P_Y [(x (x^a - chi_M^a) - c (x^(1+a) -
 * chi_M^(1+a))) / (eps_y H fx) + ((x - x_M) / (eps_y H) + 1) chi_M^a / fx]; with K = 1 - c and
 * x_M - chi_M = chi_gap(x_M) it is P_Y [chi_M^(1+a) / (fx H) + K (x^(1+a) - chi_M^(1+a)) /
 * (eps_y H fx)]: its value at chi_M, where branch 2 starts, and a rise of order 1. */
static double unload_value(const law_consts *k, double u_max, double u, int consistent)
{
    double a = k->alpha, h0 = k->h0, chiM = chi_of(k, u_max); /* Eq. 36 */
    if (chiM <= 0.0)                                          /* no yield: unloading = loading */
        return load_value(k, u);
    double x = u / h0, xm = u_max / h0;
    double t = (x - xm) / k->eps_y + k->H; /* (u - hbar_inf) / (eps_y h0), Eq. 37 */
    if (!(t > 0.0))
        return 0.0;
    double above = (x - xm) + chi_gap(k, xm); /* x - chi_M */
    if (above >= 0.0) {
        double rise = -pow(x, 1.0 + a) * pow_less_one(above / x, 1.0 + a);
        return k->PY *
               (pow(chiM, 1.0 + a) / (k->fx * k->H) + k->K * rise / (k->eps_y * k->H * k->fx));
    }
    double P = k->PY * pow(t, a + 1.0) / (k->fx * k->H);
    return consistent ? P * k->K : P;
}

static double work_unload_value(const law_consts *k, double u_max, int consistent)
{
    double a = k->alpha, h0 = k->h0, chiM = chi_of(k, u_max);
    if (chiM <= 0.0)
        return work_load_value(k, u_max);
    /* branch 2 on [hbar_inf, h0 chi_M], where (u - hbar_inf) / (eps_y h0) runs from 0 to chi_M:
     * P_Y/(fx H) eps_y h0 chi_M^(a+2) / (a+2) */
    double W2 = k->PY / (k->fx * k->H) * k->eps_y * h0 * pow(chiM, a + 2.0) / (a + 2.0);
    if (consistent)
        W2 *= k->K;
    /* branch 1 on [h0 chi_M, u_max], a width d = chi_gap(x_M): its value at chi_M times d, and
     * K / (eps_y H fx) times the integral of x^(1+a) - chi_M^(1+a), x_M^(2+a) times
     * power_excess_integral(d / x_M), of order eps_y^2 */
    double xm = u_max / h0, d = chi_gap(k, xm);
    double W1 = k->PY * h0 *
                (d * pow(chiM, 1.0 + a) / (k->fx * k->H) +
                 k->K * pow(xm, 2.0 + a) * power_excess_integral(d / xm, 1.0 + a) /
                     (k->eps_y * k->H * k->fx));
    return W1 + W2;
}

/* The parameters, then a displacement `name` = u [length]: CT_EINVAL unless finite and >= 0,
 * CT_ERANGE beyond h0, where the law's continuous stage index is negative. */
static int check_u(const ct_params *p, const char *name, double u)
{
    int st;
    if ((st = ct_params_validate(p)))
        return st;
    if (!isfinite(u) || u < 0.0)
        return ct_error_set(CT_EINVAL, "asymptotic law: %s = %g: must be finite and >= 0", name, u);
    if (u > p->h0)
        return ct_error_set(CT_ERANGE,
                            "asymptotic law: %s = %.17g is beyond h0 = %.17g, where its continuous "
                            "stage index n = -ln(u/h0)/ln fz is negative",
                            name, u, p->h0);
    return CT_OK;
}

int ct_asym_load(const ct_params *p, double u, double *P)
{
    CT_NEED(P);
    int st = check_u(p, "u", u);
    if (st)
        return st;
    law_consts k = consts(p);
    *P = load_value(&k, u);
    return CT_OK;
}

int ct_asym_work_load(const ct_params *p, double u, double *W)
{
    CT_NEED(W);
    int st = check_u(p, "u", u);
    if (st)
        return st;
    law_consts k = consts(p);
    *W = work_load_value(&k, u);
    return CT_OK;
}

int ct_asym_unload(const ct_params *p, double u_max, double u, int consistent, double *P)
{
    CT_NEED(P);
    int st;
    if ((st = check_u(p, "u_max", u_max)) || (st = check_u(p, "u", u)))
        return st;
    law_consts k = consts(p);
    *P = unload_value(&k, u_max, u, consistent);
    return CT_OK;
}

int ct_asym_work_unload(const ct_params *p, double u_max, int consistent, double *W)
{
    CT_NEED(W);
    int st = check_u(p, "u_max", u_max);
    if (st)
        return st;
    law_consts k = consts(p);
    *W = work_unload_value(&k, u_max, consistent);
    return CT_OK;
}

/* Root u of work_load_value(u) = target in (lo, hi), where W(lo) < target < W(hi), 0 < lo and W
 * increases with derivative P = load_value > 0. Newton steps on ln W against ln u (W is close to
 * a power of u, so they converge in a few steps from anywhere), at least 1/4 tol relative long
 * so that the bracket closes; a bisection of ln u whenever a step leaves the bracket or is not
 * half the one before last. Converged when the bracket is within tol of its lower end;
 * CT_ENOCONV otherwise. Hand-written rather than GSL's Brent: GSL reports failures through
 * its process-wide error handler, which a library must neither call nor switch off. */
static int solve_work(const law_consts *k, double target, double lo, double hi, double tol,
                      double *root)
{
    double W_lo = work_load_value(k, lo), W_hi = work_load_value(k, hi);
    double x = hi, Wx = W_hi, step = INFINITY, step_before = INFINITY;
    for (int it = 0; it < 200; it++) {
        if (hi - lo <= tol * lo) {
            *root = target - W_lo <= W_hi - target ? lo : hi;
            return CT_OK;
        }
        double P = load_value(k, x), next = NAN;
        if (Wx > 0.0 && P > 0.0)
            next = x * exp(log(target / Wx) * Wx / (x * P));
        double min_step = 0.25 * tol * x;
        if (fabs(next - x) < min_step)
            next = Wx > target ? x - min_step : x + min_step;
        if (!(next > lo && next < hi) || !(fabs(next - x) <= 0.5 * step_before))
            next = sqrt(lo) * sqrt(hi);
        step_before = step;
        step = fabs(next - x);
        x = next;
        Wx = work_load_value(k, x);
        if (Wx == target) {
            *root = x;
            return CT_OK;
        }
        if (Wx < target) {
            lo = x;
            W_lo = Wx;
        } else {
            hi = x;
            W_hi = Wx;
        }
    }
    return ct_error_set(CT_ENOCONV,
                        "asymptotic law: u_max solve for W = %.17g left the bracket [%.17g, "
                        "%.17g] wider than %g relative after 200 steps",
                        target, lo, hi, tol);
}

int ct_asym_impact(const ct_params *p, int consistent, double W, double *u_max, double *e)
{
    law_consts k = consts(p);
    double h0 = p->h0, uy = k.eps_y * k.H * h0; /* first yield, chi = 0 */
    double W_top = work_load_value(&k, h0);
    if (!(W < W_top))
        return ct_error_set(CT_ERANGE,
                            "asymptotic law: impact energy %.6g reaches u_max > h0 = %g (it needs "
                            "W < %.6g), where the law's stage index n = -ln(u/h0)/ln fz is "
                            "negative",
                            W, h0, W_top);
    double W_y = uy < h0 ? work_load_value(&k, uy) : W_top;
    if (W <= W_y) {
        /* no stage yields: invert Eq. 33's work pre K h0 x^(2+a) / (2+a), e = 1 exactly */
        double a = k.alpha, pre = k.PY / (k.eps_y * k.H * k.fx);
        double u = h0 * pow((2.0 + a) * W / (pre * k.K * h0), 1.0 / (2.0 + a));
        double top = uy < h0 ? uy : h0;
        *u_max = u < top ? u : top;
        *e = 1.0;
        return CT_OK;
    }
    /* W_y < W < W_top: the root lies in (uy, h0) */
    double u = h0;
    int st = solve_work(&k, W, uy, h0, 1e-15, &u);
    if (st)
        return st;
    double Wl = work_load_value(&k, u), Wu = work_unload_value(&k, u, consistent);
    if (!(Wu >= 0.0) || !(Wl > 0.0))
        return ct_error_set(CT_ENOCONV, "asymptotic law: energies W_load = %g, W_unload = %g", Wl,
                            Wu);
    *u_max = u;
    *e = sqrt(Wu / Wl);
    return CT_OK;
}
