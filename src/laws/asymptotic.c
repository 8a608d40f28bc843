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

static double load_value(const law_consts *k, double u)
{
    if (!(u > 0.0))
        return 0.0;
    double x = u / k->h0, chi = chi_of(k, u), a = k->alpha;
    if (chi <= 0.0) /* Eq. 33 */
        return k->PY * k->K * pow(x, 1.0 + a) / (k->eps_y * k->fx * k->H);
    /* Eq. 34 */
    double br = x * (pow(x, a) - pow(chi, a)) - k->c * (pow(x, 1.0 + a) - pow(chi, 1.0 + a));
    return k->PY * (br / (k->eps_y * k->H * k->fx) + pow(chi, a) / k->fx);
}

static double work_load_value(const law_consts *k, double u)
{
    if (!(u > 0.0))
        return 0.0;
    double a = k->alpha, h0 = k->h0, pre = k->PY / (k->eps_y * k->H * k->fx);
    double uy = k->eps_y * k->H * h0, x_end = u < uy ? u / h0 : uy / h0;
    /* Eq. 33 from 0: pre K h0 x^(2+a) / (2+a) */
    double W = pre * k->K * h0 * pow(x_end, 2.0 + a) / (2.0 + a);
    if (u <= uy)
        return W;
    /* Eq. 34 from uy to u, with u = h0 ((1 - eps_y) chi + eps_y H), du = h0 (1 - eps_y) dchi */
    double x = u / h0, chi = chi_of(k, u), xy = uy / h0, e1 = 1.0 - k->eps_y;
    double I_x1a = h0 * (pow(x, 2.0 + a) - pow(xy, 2.0 + a)) / (2.0 + a); /* int x^(1+a) du */
    double I_xchi =
        h0 * e1 *
        (e1 * pow(chi, a + 2.0) / (a + 2.0) + k->eps_y * k->H * pow(chi, a + 1.0) / (a + 1.0));
    double I_chi1a = h0 * e1 * pow(chi, 2.0 + a) / (2.0 + a);
    double I_chia = h0 * e1 * pow(chi, 1.0 + a) / (1.0 + a);
    W += pre * ((I_x1a - I_xchi) - k->c * (I_x1a - I_chi1a)) + k->PY * I_chia / k->fx;
    return W;
}

/* Eq. 38's two branches. */
static double unload_value(const law_consts *k, double u_max, double u, int consistent)
{
    double a = k->alpha, h0 = k->h0, chiM = chi_of(k, u_max); /* Eq. 36 */
    double hbar_inf = u_max - k->eps_y * k->H * h0;           /* Eq. 37 */
    if (chiM <= 0.0)                                          /* no yield: unloading = loading */
        return load_value(k, u);
    if (!(u > hbar_inf))
        return 0.0;
    double x = u / h0, xm = u_max / h0;
    if (u >= h0 * chiM) {
        double br = x * (pow(x, a) - pow(chiM, a)) - k->c * (pow(x, 1.0 + a) - pow(chiM, 1.0 + a));
        return k->PY * (br / (k->eps_y * k->fx * k->H) +
                        ((x - xm) / (k->eps_y * k->H) + 1.0) * pow(chiM, a) / k->fx);
    }
    double t = (u - hbar_inf) / (k->eps_y * h0);
    double P = k->PY * pow(t, a + 1.0) / (k->fx * k->H);
    return consistent ? P * k->K : P;
}

static double work_unload_value(const law_consts *k, double u_max, int consistent)
{
    double a = k->alpha, h0 = k->h0, chiM = chi_of(k, u_max);
    if (chiM <= 0.0)
        return work_load_value(k, u_max);
    double hbar_inf = u_max - k->eps_y * k->H * h0, u_c = h0 * chiM;
    if (u_c > u_max)
        u_c = u_max;
    /* branch 2 on [hbar_inf, u_c]: PY/(fx H) ((u - hbar)/(eps_y h0))^(a+1) */
    double t = (u_c - hbar_inf) / (k->eps_y * h0);
    double W2 = k->PY / (k->fx * k->H) * k->eps_y * h0 * pow(t, a + 2.0) / (a + 2.0);
    if (consistent)
        W2 *= k->K;
    /* branch 1 on [u_c, u_max] */
    double x1 = u_c / h0, x2 = u_max / h0, pre = k->PY / (k->eps_y * k->fx * k->H);
    double I_x1a = h0 * (pow(x2, 2.0 + a) - pow(x1, 2.0 + a)) / (2.0 + a);
    double I_x = h0 * (x2 * x2 - x1 * x1) / 2.0, I_1 = h0 * (x2 - x1);
    double ca = pow(chiM, a), ca1 = pow(chiM, 1.0 + a);
    double W1 = pre * ((I_x1a - ca * I_x) - k->c * (I_x1a - ca1 * I_1)) +
                k->PY * ca / k->fx * ((I_x - x2 * I_1) / (k->eps_y * k->H) + I_1);
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
