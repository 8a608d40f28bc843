/* Quadrature rules: convergence order on a smooth integrand, exactness of the breakpoint
 * rule on a piecewise-linear one. References are antiderivatives. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>

#include "cantact.h"

static double smooth(double x, void *ctx)
{
    (void)ctx;
    return exp(x) * sin(3.0 * x);
}

/* antiderivative of e^x sin 3x: e^x (sin 3x - 3 cos 3x) / 10 */
static double smooth_integral(double a, double b)
{
    double F_b = exp(b) * (sin(3 * b) - 3 * cos(3 * b)) / 10,
           F_a = exp(a) * (sin(3 * a) - 3 * cos(3 * a)) / 10;
    return F_b - F_a;
}

static double order_of(ct_quad_rule rule, size_t K1, size_t K2)
{
    double r1, r2, exact = smooth_integral(0.0, 2.0);
    assert_int_equal(ct_integrate(smooth, NULL, 0.0, 2.0, rule, K1, NULL, 0, &r1, NULL), CT_OK);
    assert_int_equal(ct_integrate(smooth, NULL, 0.0, 2.0, rule, K2, NULL, 0, &r2, NULL), CT_OK);
    /* panels double from K1 to K2: error ratio 2^order */
    return log2(fabs(r1 - exact) / fabs(r2 - exact));
}

static void composite_orders(void **state)
{
    (void)state;
    double o_trap = order_of(CT_QUAD_TRAPEZOID, 33, 65); /* 32 -> 64 intervals */
    double o_simp = order_of(CT_QUAD_SIMPSON, 33, 65);   /* 32 -> 64 intervals */
    double o_gauss = order_of(CT_QUAD_GAUSS, 24, 48);    /* 8 -> 16 panels */
    assert_true(fabs(o_trap - 2.0) < 0.05);
    assert_true(fabs(o_simp - 4.0) < 0.1);
    assert_true(fabs(o_gauss - 6.0) < 0.2);
}

/* |x - 0.3| + 2 max(x - 1.1, 0) - max(0.7 - x, 0): kinks at 0.3, 0.7, 1.1 */
static double kinked(double x, void *ctx)
{
    (void)ctx;
    return fabs(x - 0.3) + 2.0 * fmax(x - 1.1, 0.0) - fmax(0.7 - x, 0.0);
}

static void breakpoint_rule_is_exact(void **state)
{
    (void)state;
    const double pts[] = {-1.0, 0.3, 0.7, 1.1, 5.0}; /* outside points are ignored */
    double r, err;
    assert_int_equal(ct_integrate(kinked, NULL, 0.0, 2.0, CT_QUAD_BREAKPOINTS, 0, pts, 5, &r, &err),
                     CT_OK);
    /* by hand: int |x-0.3| = 0.045 + 1.445 = 1.49; int 2 max(x-1.1,0) = 0.81;
     * int max(0.7-x,0) = 0.245 */
    double exact = 1.49 + 0.81 - 0.245;
    assert_true(fabs(r - exact) <= 4e-16 * exact);
    assert_true(err >= 0.0 && err < 1e-14);
    /* without the breakpoints the composite rules are not exact */
    double rt;
    assert_int_equal(ct_integrate(kinked, NULL, 0.0, 2.0, CT_QUAD_GAUSS, 12, NULL, 0, &rt, NULL),
                     CT_OK);
    assert_true(fabs(rt - exact) > 1e-6);
}

static void bad_input(void **state)
{
    (void)state;
    double r;
    assert_int_equal(ct_integrate(smooth, NULL, 1.0, 0.0, CT_QUAD_TRAPEZOID, 10, NULL, 0, &r, NULL),
                     CT_EINVAL);
    assert_int_equal(ct_integrate(smooth, NULL, 0.0, NAN, CT_QUAD_TRAPEZOID, 10, NULL, 0, &r, NULL),
                     CT_EINVAL);
    assert_int_equal(ct_integrate(smooth, NULL, 0.0, 1.0, CT_QUAD_SIMPSON, 2, NULL, 0, &r, NULL),
                     CT_EINVAL);
    assert_int_equal(ct_integrate(smooth, NULL, 0.0, 1.0, (ct_quad_rule)9, 20, NULL, 0, &r, NULL),
                     CT_EINVAL);
    /* node counts whose buffer size overflows size_t: refused, not a heap overflow */
    const size_t huge[] = {((size_t)1 << 61) + 1, SIZE_MAX, SIZE_MAX / 24};
    for (int k = 0; k < 3; k++) {
        int st =
            ct_integrate(smooth, NULL, 0.0, 1.0, CT_QUAD_TRAPEZOID, huge[k], NULL, 0, &r, NULL);
        assert_int_equal(st, CT_ENOMEM);
    }
    /* unsorted or non-finite breakpoints: refused, not a silently wrong integral */
    const double unsorted[] = {0.3, 1.1, 0.7}, nan_pt[] = {0.3, NAN};
    assert_int_equal(
        ct_integrate(kinked, NULL, 0.0, 2.0, CT_QUAD_BREAKPOINTS, 0, unsorted, 3, &r, NULL),
        CT_EINVAL);
    assert_int_equal(
        ct_integrate(kinked, NULL, 0.0, 2.0, CT_QUAD_BREAKPOINTS, 0, nan_pt, 2, &r, NULL),
        CT_EINVAL);
    assert_int_equal(
        ct_integrate(kinked, NULL, 0.0, 2.0, CT_QUAD_BREAKPOINTS, 0, NULL, 2, &r, NULL), CT_EINVAL);
    /* NULL function or result */
    assert_int_equal(ct_integrate(NULL, NULL, 0.0, 1.0, CT_QUAD_TRAPEZOID, 10, NULL, 0, &r, NULL),
                     CT_EINVAL);
    assert_int_equal(
        ct_integrate(smooth, NULL, 0.0, 1.0, CT_QUAD_TRAPEZOID, 10, NULL, 0, NULL, NULL),
        CT_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(composite_orders),
        cmocka_unit_test(breakpoint_rule_is_exact),
        cmocka_unit_test(bad_input),
    };
    return cmocka_run_group_tests_name("quadrature", tests, NULL, NULL);
}
