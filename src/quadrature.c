/* Integration rules over a 1-D function with known breakpoints. The breakpoint rule is
 * exact (up to rounding) for piecewise-linear integrands such as a bundle's P(u); the
 * composite rules ignore breakpoints and exist for the error-versus-time study. */
#include "internal.h"

#include <float.h>
#include <math.h>

const char *ct_quad_rule_name(ct_quad_rule rule)
{
    switch (rule) {
    case CT_QUAD_BREAKPOINTS:
        return "breakpoints";
    case CT_QUAD_TRAPEZOID:
        return "trapezoid";
    case CT_QUAD_SIMPSON:
        return "simpson";
    case CT_QUAD_GAUSS:
        return "gauss";
    }
    return NULL;
}

/* 2-point Gauss-Legendre on [a, b]: exact for cubics, so for every linear piece. */
static double gauss2(ct_function f, void *ctx, double a, double b, double *abs_sum)
{
    const double x = 0.57735026918962576451; /* 1/sqrt(3) */
    double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    double f1 = f(mid - half * x, ctx), f2 = f(mid + half * x, ctx);
    *abs_sum += half * (fabs(f1) + fabs(f2));
    return half * (f1 + f2);
}

static double breakpoint_rule(ct_function f, void *ctx, double a, double b, const double *pts,
                              size_t npts, double *abs_sum)
{
    double sum = 0.0, left = a;
    for (size_t k = 0; k < npts; k++) {
        if (!(pts[k] > left && pts[k] < b))
            continue;
        sum += gauss2(f, ctx, left, pts[k], abs_sum);
        left = pts[k];
    }
    return sum + gauss2(f, ctx, left, b, abs_sum);
}

static double trapezoid(ct_function f, void *ctx, double a, double b, size_t K)
{
    size_t m = K - 1;
    double h = (b - a) / (double)m;
    double s = 0.5 * (f(a, ctx) + f(b, ctx));
    for (size_t k = 1; k < m; k++)
        s += f(a + (double)k * h, ctx);
    return s * h;
}

static double simpson(ct_function f, void *ctx, double a, double b, size_t K)
{
    size_t m = K - 1; /* even */
    double h = (b - a) / (double)m;
    double s = f(a, ctx) + f(b, ctx);
    for (size_t k = 1; k < m; k++)
        s += (k % 2 ? 4.0 : 2.0) * f(a + (double)k * h, ctx);
    return s * h / 3.0;
}

static double gauss3(ct_function f, void *ctx, double a, double b, size_t K)
{
    const double x = 0.77459666924148337704; /* sqrt(3/5) */
    size_t panels = K / 3;
    double h = (b - a) / (double)panels, s = 0.0;
    for (size_t k = 0; k < panels; k++) {
        double mid = a + ((double)k + 0.5) * h, half = 0.5 * h;
        s += half *
             (5.0 * f(mid - half * x, ctx) + 8.0 * f(mid, ctx) + 5.0 * f(mid + half * x, ctx)) /
             9.0;
    }
    return s;
}

/* The usable node count of a composite rule: trapezoid K >= 2, Simpson odd K >= 3,
 * Gauss a multiple of 3, at least 3. */
static size_t usable_nodes(ct_quad_rule rule, size_t K)
{
    switch (rule) {
    case CT_QUAD_TRAPEZOID:
        return K >= 2 ? K : 0;
    case CT_QUAD_SIMPSON:
        K = K % 2 ? K : K - 1;
        return K >= 3 ? K : 0;
    case CT_QUAD_GAUSS:
        return K >= 3 ? K / 3 * 3 : 0;
    default:
        return 0;
    }
}

static double composite(ct_function f, void *ctx, double a, double b, ct_quad_rule rule, size_t K)
{
    switch (rule) {
    case CT_QUAD_TRAPEZOID:
        return trapezoid(f, ctx, a, b, K);
    case CT_QUAD_SIMPSON:
        return simpson(f, ctx, a, b, K);
    default:
        return gauss3(f, ctx, a, b, K);
    }
}

int ct_integrate(ct_function f, void *ctx, double a, double b, ct_quad_rule rule, size_t nodes,
                 const double *points, size_t npoints, double *result, double *abserr)
{
    if (!isfinite(a) || !isfinite(b) || a > b)
        return ct_error_set(CT_EINVAL, "integral over [%g, %g]: need finite a <= b", a, b);
    if (a == b) {
        *result = 0.0;
        if (abserr)
            *abserr = 0.0;
        return CT_OK;
    }
    if (rule == CT_QUAD_BREAKPOINTS) {
        double abs_sum = 0.0;
        *result = breakpoint_rule(f, ctx, a, b, points, npoints, &abs_sum);
        if (abserr)
            *abserr = 4.0 * DBL_EPSILON * abs_sum; /* exact rule: only rounding remains */
    } else {
        if (!ct_quad_rule_name(rule))
            return ct_error_set(CT_EINVAL, "quadrature rule %d: unknown", (int)rule);
        size_t K = usable_nodes(rule, nodes);
        if (K == 0)
            return ct_error_set(CT_EINVAL, "%s with %zu nodes: needs at least %d nodes",
                                ct_quad_rule_name(rule), nodes, rule == CT_QUAD_TRAPEZOID ? 2 : 3);
        *result = composite(f, ctx, a, b, rule, K);
        if (abserr) {
            /* the same rule on about half the nodes: a cheap, honest error indicator */
            size_t Kc = usable_nodes(rule, (K + 1) / 2);
            *abserr = Kc ? fabs(*result - composite(f, ctx, a, b, rule, Kc)) : INFINITY;
        }
    }
    if (!isfinite(*result))
        return ct_error_set(CT_ENOCONV, "integral over [%g, %g] is not finite", a, b);
    return CT_OK;
}
