/* Integration rules over a 1-D function with known breakpoints. The breakpoint rule is
 * exact (up to rounding) for continuous piecewise-linear integrands such as a bundle's P(u);
 * the composite rules ignore breakpoints and exist for the error-versus-time study.
 *
 * Every rule is a list of nodes and weights: the integrand is asked for all nodes at once
 * (a bundle then assembles P at every node in one pass over its rods) and the weighted
 * values are summed in node order. */
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

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
    case CT_QUAD_CLOSED:
        return "closed";
    }
    return NULL;
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

/* Nodes x[0..K) and weights w of a composite rule with K usable nodes on [a, b]. */
static void composite_nodes(ct_quad_rule rule, double a, double b, size_t K, double *x, double *w)
{
    if (rule == CT_QUAD_GAUSS) {
        const double g = 0.77459666924148337704; /* sqrt(3/5) */
        size_t panels = K / 3;
        double h = (b - a) / (double)panels, half = 0.5 * h;
        for (size_t k = 0; k < panels; k++) {
            double mid = a + ((double)k + 0.5) * h;
            x[3 * k] = mid - half * g;
            x[3 * k + 1] = mid;
            x[3 * k + 2] = mid + half * g;
            w[3 * k] = w[3 * k + 2] = half * 5.0 / 9.0;
            w[3 * k + 1] = half * 8.0 / 9.0;
        }
        return;
    }
    size_t m = K - 1;
    double h = (b - a) / (double)m;
    for (size_t k = 0; k < K; k++) {
        x[k] = k == m ? b : a + (double)k * h;
        if (rule == CT_QUAD_TRAPEZOID)
            w[k] = (k == 0 || k == m ? 0.5 : 1.0) * h;
        else /* Simpson */
            w[k] = (k == 0 || k == m ? 1.0 : k % 2 ? 4.0 : 2.0) * h / 3.0;
    }
}

/* Breakpoint rule: the trapezoid rule on a, the sorted points inside (a, b), and b. Exact
 * for a continuous integrand that is linear between breakpoints. Returns the node count. */
static size_t breakpoint_nodes(double a, double b, const double *pts, size_t npts, double *x,
                               double *w)
{
    size_t K = 0;
    x[K++] = a;
    for (size_t k = 0; k < npts; k++)
        if (pts[k] > x[K - 1] && pts[k] < b)
            x[K++] = pts[k];
    x[K++] = b;
    for (size_t k = 0; k < K; k++)
        w[k] = 0.5 * ((k + 1 < K ? x[k + 1] : x[k]) - (k > 0 ? x[k - 1] : x[k]));
    return K;
}

/* sum w f(x) over nodes; *abs_sum gets sum |w f(x)| */
static int weighted_sum(ct_batch_function f, void *ctx, const double *x, const double *w, size_t K,
                        double *y, double *result, double *abs_sum)
{
    int st = f(x, K, y, ctx);
    if (st)
        return st;
    double s = 0.0, a = 0.0;
    for (size_t k = 0; k < K; k++) {
        s += w[k] * y[k];
        a += fabs(w[k] * y[k]);
    }
    *result = s;
    if (abs_sum)
        *abs_sum = a;
    return CT_OK;
}

int ct_integrate_batch(ct_batch_function f, void *ctx, double a, double b, ct_quad_rule rule,
                       size_t nodes, const double *points, size_t npoints, double *result,
                       double *abserr)
{
    CT_NEED(f);
    CT_NEED(result);
    if (!isfinite(a) || !isfinite(b) || a > b)
        return ct_error_set(CT_EINVAL, "integral over [%g, %g]: need finite a <= b", a, b);
    if (!ct_quad_rule_name(rule) || rule == CT_QUAD_CLOSED)
        return ct_error_set(CT_EINVAL, "quadrature rule %d: unknown", (int)rule);
    if (rule == CT_QUAD_BREAKPOINTS) {
        if (npoints && !points)
            return ct_error_set(CT_EINVAL, "breakpoints rule: points is NULL for %zu points",
                                npoints);
        /* the rule is exact only on sorted breakpoints: unsorted ones are an error, not a
         * silently wrong integral */
        for (size_t k = 0; k < npoints; k++)
            if (!isfinite(points[k]) || (k && !(points[k] >= points[k - 1])))
                return ct_error_set(CT_EINVAL,
                                    "breakpoints rule: point %zu = %g is not finite or not "
                                    "sorted ascending",
                                    k, points[k]);
    }
    if ((rule == CT_QUAD_BREAKPOINTS ? npoints : nodes) > SIZE_MAX / (3 * sizeof(double)) - 2)
        return ct_error_set(CT_ENOMEM, "%s with %zu nodes: cannot be addressed",
                            ct_quad_rule_name(rule), rule == CT_QUAD_BREAKPOINTS ? npoints : nodes);
    size_t K = rule == CT_QUAD_BREAKPOINTS ? npoints + 2 : usable_nodes(rule, nodes);
    if (K == 0)
        return ct_error_set(CT_EINVAL, "%s with %zu nodes: needs at least %d nodes",
                            ct_quad_rule_name(rule), nodes, rule == CT_QUAD_TRAPEZOID ? 2 : 3);
    if (a == b) {
        *result = 0.0;
        if (abserr)
            *abserr = 0.0;
        return CT_OK;
    }
    double *buf = malloc(3 * K * sizeof(double));
    if (!buf)
        return ct_error_set(CT_ENOMEM, "%s with %zu nodes: out of memory", ct_quad_rule_name(rule),
                            K);
    double *x = buf, *w = buf + K, *y = buf + 2 * K, abs_sum;
    int st;
    if (rule == CT_QUAD_BREAKPOINTS) {
        K = breakpoint_nodes(a, b, points, npoints, x, w);
        st = weighted_sum(f, ctx, x, w, K, y, result, &abs_sum);
        if (!st && abserr)
            *abserr = 4.0 * DBL_EPSILON * abs_sum; /* exact rule: only rounding remains */
    } else {
        composite_nodes(rule, a, b, K, x, w);
        st = weighted_sum(f, ctx, x, w, K, y, result, NULL);
        if (!st && abserr) {
            /* the same rule on about half the nodes: a cheap, honest error indicator */
            size_t Kc = usable_nodes(rule, (K + 1) / 2);
            double coarse = 0.0;
            if (Kc) {
                composite_nodes(rule, a, b, Kc, x, w);
                st = weighted_sum(f, ctx, x, w, Kc, y, &coarse, NULL);
            }
            *abserr = Kc ? fabs(*result - coarse) : INFINITY;
        }
    }
    free(buf);
    if (st)
        return st;
    if (!isfinite(*result))
        return ct_error_set(CT_ENOCONV, "integral over [%g, %g] is not finite", a, b);
    return CT_OK;
}

typedef struct {
    ct_function f;
    void *ctx;
} scalar_ctx;

static int scalar_batch(const double *x, size_t m, double *y, void *ctx)
{
    const scalar_ctx *c = ctx;
    for (size_t k = 0; k < m; k++)
        y[k] = c->f(x[k], c->ctx);
    return CT_OK;
}

int ct_integrate(ct_function f, void *ctx, double a, double b, ct_quad_rule rule, size_t nodes,
                 const double *points, size_t npoints, double *result, double *abserr)
{
    CT_NEED(f);
    CT_NEED(result);
    scalar_ctx c = {f, ctx};
    return ct_integrate_batch(scalar_batch, &c, a, b, rule, nodes, points, npoints, result, abserr);
}
