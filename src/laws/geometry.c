/* The Cantor prefractal's geometry (docs/model.md §1-2): its parameters checked, stage lengths
 * and depths (Eqs. 1-2), the ratios alpha and beta (Eqs. 18, 28), the dimension (Eq. 3), the
 * stage sums of Eqs. 16-17, where each piece lies, and the energy scale of V*. Used by the
 * laws and by the kinds that build Cantor rods; it knows nothing of rods. */
#include "internal.h"

#include <math.h>
#include <stddef.h>

static int check_positive(const char *name, double v)
{
    if (!isfinite(v) || !(v > 0.0))
        return ct_error_set(CT_EINVAL, "%s = %g: must be finite and > 0", name, v);
    return CT_OK;
}

int ct_params_validate(const ct_params *p)
{
    int st;
    if (!p)
        return ct_error_set(CT_EINVAL, "parameters: NULL");
    if (!isfinite(p->fx) || !(p->fx > 1.0))
        return ct_error_set(CT_EINVAL, "fx = %g: must satisfy fx > 1 (finite)", p->fx);
    if (!isfinite(p->fz) || !(p->fz > 1.0 && p->fz < 2.0))
        return ct_error_set(CT_EINVAL, "fz = %g: must satisfy 1 < fz < 2", p->fz);
    if ((st = check_positive("l0", p->l0)) || (st = check_positive("h0", p->h0)))
        return st;
    if (!isfinite(p->Hstar) || !(p->Hstar > p->h0))
        return ct_error_set(CT_EINVAL, "H* = %g: must be finite and > h0 = %g", p->Hstar, p->h0);
    /* E, sigma_y and the energy scales: the checks every rod set's layer passes */
    const ct_layer L = {
        .E = p->E, .sigma_y = p->sigma_y, .Hstar = p->Hstar, .l0 = p->l0, .h0 = p->h0};
    return ct_layer_validate(&L);
}

/* exp(-i log f), which is 0 (not NaN) for huge i and exact for f -> 1 via log1p. */
static double power_down(double f, double i)
{
    return exp(-i * log1p(f - 1.0));
}

double ct_stage_length(const ct_params *p, double i)
{
    return p->l0 * power_down(p->fx, i); /* Eq. 1 */
}

double ct_stage_depth(const ct_params *p, double i)
{
    return p->h0 * power_down(p->fz, i); /* Eq. 2 */
}

/* 1 - 1/fx = (fx - 1)/fx: fx - 1 is exact (Sterbenz) for fx in (1, 2]. */
static double one_minus_inv(double f)
{
    return (f - 1.0) / f;
}

double ct_stage_area(const ct_params *p, double i)
{
    return p->l0 * one_minus_inv(p->fx) * power_down(p->fx, i);
}

double ct_alpha(const ct_params *p)
{
    return log1p(p->fx - 1.0) / log1p(p->fz - 1.0); /* Eq. 28 */
}

double ct_beta(const ct_params *p)
{
    return 1.0 / (p->fx * p->fz); /* Eq. 18 */
}

static double log_inv_beta(const ct_params *p)
{
    return log1p(p->fx - 1.0) + log1p(p->fz - 1.0);
}

double ct_one_minus_beta(const ct_params *p)
{
    return -expm1(-log_inv_beta(p));
}

double ct_dimension(const ct_params *p)
{
    /* Eq. 3: D = 1 - ln fz / ln(2 fx) + ln 2 / ln(2 fx) */
    double ln2fx = log(2.0) + log1p(p->fx - 1.0);
    return 1.0 + (log(2.0) - log1p(p->fz - 1.0)) / ln2fx;
}

double ct_sum_area(const ct_params *p, double n1, double n2)
{
    if (n2 < n1)
        return 0.0;
    /* Eq. 16: l_{n1} - l_{n2+1} = l_{n1} (1 - fx^-(n2+1-n1)) */
    double lf = log1p(p->fx - 1.0);
    if (isinf(n2))
        return ct_stage_length(p, n1);
    return ct_stage_length(p, n1) * -expm1(-(n2 + 1.0 - n1) * lf);
}

double ct_sum_depth_area(const ct_params *p, double n1, double n2)
{
    if (n2 < n1)
        return 0.0;
    /* Eq. 17: h0 l0 (1 - 1/fx) (beta^n1 - beta^(n2+1)) / (1 - beta), written as
     * beta^n1 (1 - beta^(n2+1-n1)) / (1 - beta) with expm1 so that beta -> 1 loses nothing. */
    double lb = log_inv_beta(p);
    double head = exp(-n1 * lb);
    double ratio = isinf(n2) ? 1.0 / -expm1(-lb) : expm1(-(n2 + 1.0 - n1) * lb) / expm1(-lb);
    return p->h0 * p->l0 * one_minus_inv(p->fx) * head * ratio;
}

double ct_energy_scale(const ct_params *p)
{
    return p->l0 * p->E * p->h0;
}

int ct_piece_extent(const ct_params *p, long depth, long stage, size_t j, double *x_left,
                    double *x_right)
{
    CT_NEED(p);
    CT_NEED(x_left);
    CT_NEED(x_right);
    if (stage < 0 || stage > depth || stage > 62 || j >> stage)
        return ct_error_set(CT_EINVAL, "piece %zu of stage %ld: outside a depth-%ld prefractal", j,
                            stage, depth);
    /* The parent segment at stage i spans [left, left + w_i], w_i = l0 (2 fx)^-i; bit s of j
     * (from the top) says whether the right child was kept at stage s. */
    double two_fx = 2.0 * p->fx, left = 0.0, w = p->l0;
    for (long s = 1; s <= stage; s++) {
        double w_next = w / two_fx;
        if ((j >> (stage - s)) & 1u)
            left += w - w_next;
        w = w_next;
    }
    if (stage < depth) {
        double w_child = w / two_fx;
        *x_left = left + w_child;
        *x_right = left + w - w_child;
    } else {
        *x_left = left;
        *x_right = left + w;
    }
    return CT_OK;
}
