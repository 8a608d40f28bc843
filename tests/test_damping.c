/* e <-> damping ratio of a linear spring-dashpot normal contact (include/cantact_table.h:
 * ct_tab_e_of_zeta, ct_tab_zeta_of_e), both laws, against a direct numerical integration of
 * m delta'' = -(k delta + c delta') from delta = 0, delta' = v, with each law's end: the
 * tension-allowed contact ends when delta returns to 0, the clipped one when k delta + c delta'
 * reaches 0. The integrator is the classical Runge-Kutta method (RK4) with a fixed step h and
 * the end located inside its step by bisection on the step length; its error is estimated by
 * step doubling (the same run at h and h/2: RK4's error is ~h^4, so the h/2 run's is about
 * |e_h - e_h/2| / 15) and every tolerance below is that estimate (times 15, a margin) plus
 * the rounding of the steps, none taken from the code under test. Then round trips, the
 * boundary zeta = 1 (e = e^-2 for the clipped law) against the series derived by hand, the
 * overdamped tension law (the overlap never returns to 0), bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "cantact_table.h"

/* Units m = k = 1 (omega = 1), c = 2 zeta, impact speed 1: e is the speed when it ends. */
typedef struct {
    double zeta;
    int law;
} osc;

static void deriv(const osc *o, double d, double v, double *dd, double *dv)
{
    *dd = v;
    *dv = -(d + 2.0 * o->zeta * v);
}

static void rk4(const osc *o, double d, double v, double h, double *d1, double *v1)
{
    double k1d, k1v, k2d, k2v, k3d, k3v, k4d, k4v;
    deriv(o, d, v, &k1d, &k1v);
    deriv(o, d + 0.5 * h * k1d, v + 0.5 * h * k1v, &k2d, &k2v);
    deriv(o, d + 0.5 * h * k2d, v + 0.5 * h * k2v, &k3d, &k3v);
    deriv(o, d + h * k3d, v + h * k3v, &k4d, &k4v);
    *d1 = d + h / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
    *v1 = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
}

/* what ends the contact: the overlap (tension) or the force (clipped) */
static double end_function(const osc *o, double d, double v)
{
    return o->law == CT_TAB_TENSION ? d : d + 2.0 * o->zeta * v;
}

/* The rebound speed from the integration with step h (the end located by bisection on the last
 * step's length to the last bit), and the number of steps taken. */
static double integrate(const osc *o, double h, long *steps)
{
    double d = 0.0, v = 1.0;
    long n = 0;
    for (;;) {
        double d1, v1;
        rk4(o, d, v, h, &d1, &v1);
        n++;
        assert_true(n < 100000000L);
        if (end_function(o, d1, v1) > 0.0) {
            d = d1;
            v = v1;
            continue;
        }
        double a = 0.0, b = h; /* end_function > 0 at a, <= 0 at b */
        for (;;) {
            const double s = 0.5 * (a + b);
            if (!(s > a && s < b))
                break; /* a and b are neighbours */
            double ds, vs;
            rk4(o, d, v, s, &ds, &vs);
            if (end_function(o, ds, vs) > 0.0)
                a = s;
            else
                b = s;
        }
        rk4(o, d, v, b, &d1, &v1);
        *steps = n;
        return -v1;
    }
}

/* The integrated e and its error bound: the fastest rate of the oscillator is at most
 * omega (1 + 2 zeta), so h (1 + 2 zeta) = 2e-3 keeps RK4 far inside its stability region and
 * in its asymptotic range, where the h/2 run's truncation error is |e_h - e_h/2| / 15. The
 * bound is twice |e_h - e_h/2| (30 times that estimate) plus n epsilon e for the rounding of
 * the n steps of the h/2 run (each step's rounding is relative to a state that decays as the
 * solution does: at most epsilon of the final e per step, added up without cancellation). */
static double integrated_e(double zeta, int law, double *bound)
{
    const osc o = {zeta, law};
    const double h = 2e-3 / (1.0 + 2.0 * zeta);
    long n1, n2;
    const double e1 = integrate(&o, h, &n1), e2 = integrate(&o, 0.5 * h, &n2);
    *bound = 2.0 * fabs(e1 - e2) + (double)n2 * DBL_EPSILON * e2;
    return e2;
}

/* 200 e from 1e-6 to 1 (geometric) and e = 1: zeta_of_e's zeta rebounds with e in the
 * integration, under both laws (the clipped one through both branches: e^-2 = 0.135). */
static void zeta_of_e_against_integration(void **state)
{
    (void)state;
    double worst[2] = {0, 0};
    for (int law = CT_TAB_TENSION; law <= CT_TAB_CLIPPED; law++)
        for (int i = 0; i <= 200; i++) {
            const double e = i == 200 ? 1.0 : 1e-6 * pow(1e6, i / 200.0);
            const double zeta = ct_tab_zeta_of_e(e, law);
            assert_true(zeta >= 0.0 && isfinite(zeta));
            double bound;
            const double got = integrated_e(zeta, law, &bound);
            if (!(fabs(got - e) <= bound))
                fail_msg("law %d: e = %.17g: zeta_of_e = %.17g rebounds with %.17g in the "
                         "integration (|diff| %.3g > its error bound %.3g)",
                         law, e, zeta, got, fabs(got - e), bound);
            worst[law] = fmax(worst[law], fabs(got - e) / bound);
            /* the branch: the clipped law needs zeta > 1 below e^-2, tension never */
            if (law == CT_TAB_TENSION)
                assert_true(zeta < 1.0);
            else
                assert_true((e < exp(-2.0)) == (zeta > 1.0));
        }
    printf("zeta_of_e: largest |diff| / bound: tension %.3g, clipped %.3g\n", worst[0], worst[1]);
}

/* e_of_zeta on a grid of zeta of its own, against the integration: 0 .. 0.99 (and past 1 to
 * 1000 for the clipped law, e down to 2.5e-7). */
static void e_of_zeta_against_integration(void **state)
{
    (void)state;
    static const double extra[] = {0.0,   1e-9, 1e-4, 0.999, 0.9999, 1.0,   1.0001,
                                   1.001, 1.5,  3.0,  10.0,  100.0,  1000.0};
    for (int law = CT_TAB_TENSION; law <= CT_TAB_CLIPPED; law++)
        for (int i = 0; i < 100 + (int)(sizeof extra / sizeof extra[0]); i++) {
            const double zeta = i < 100 ? 0.01 * i : extra[i - 100];
            if (law == CT_TAB_TENSION && zeta >= 0.99)
                continue; /* e < 3e-10, then e = 0: overdamped_tension below */
            double bound;
            const double got = integrated_e(zeta, law, &bound), e = ct_tab_e_of_zeta(zeta, law);
            if (!(fabs(got - e) <= bound))
                fail_msg("law %d: zeta = %.17g: e_of_zeta = %.17g, integration %.17g (|diff| "
                         "%.3g > its error bound %.3g)",
                         law, zeta, e, got, fabs(got - e), bound);
        }
}

/* The closed-form solution of delta'' + 2 zeta delta' + delta = 0, delta(0) = 0, delta'(0) = 1,
 * with F = delta + 2 zeta delta' (the force) and the law's end located by bisection on t to
 * the last bit, evaluated in double: zeta < 1 with w = sqrt(1 - zeta^2), delta =
 * exp(-zeta t) sin(w t) / w; zeta = 1, delta = t exp(-t); zeta > 1 with s = sqrt(zeta^2 - 1),
 * q = zeta + s, r1 = -1/q, r2 = -q, delta = (exp(r1 t) - exp(r2 t)) / (r1 - r2) and F =
 * (q^2 exp(r2 t) - exp(r1 t) / q^2) / (r1 - r2) (1 + 2 zeta r1 = -1/q^2, 1 + 2 zeta r2 = -q^2:
 * no cancellation). At the clipped end delta'' = 0, so delta' there does not feel t's error.
 * Independent of the header's acos / acosh / atan forms; its rounding: exp of zeta t ~ ln e
 * (relative epsilon ln e), and near zeta = 1 from above the difference r1 - r2 = 2 s (epsilon
 * / s). Returns e = -delta' at the end. */
static void exact_state(double zeta, double t, double *d, double *v, double *F)
{
    if (zeta < 1.0) {
        const double w = sqrt((1.0 - zeta) * (1.0 + zeta)), ex = exp(-zeta * t);
        *d = ex * sin(w * t) / w;
        *v = ex * (cos(w * t) - zeta * sin(w * t) / w);
        *F = *d + 2.0 * zeta * *v;
    } else if (zeta == 1.0) {
        *d = t * exp(-t);
        *v = (1.0 - t) * exp(-t);
        *F = (2.0 - t) * exp(-t); /* delta + 2 delta' */
    } else {
        const double sq = sqrt(zeta - 1.0) * sqrt(zeta + 1.0), q = zeta + sq;
        const double r1 = -1.0 / q, r2 = -q, a = exp(r1 * t), b = exp(r2 * t), D = r1 - r2;
        *d = (a - b) / D;
        *v = (r1 * a - r2 * b) / D;
        *F = (q * q * b - a / q / q) / D;
    }
}

static double closed_form_e(double zeta, int law)
{
    double lo = 0.0, hi = 1.0, d, v, F;
    /* the end: the overlap (tension, zeta < 1) or the force (clipped) turns <= 0 */
    if (law == CT_TAB_TENSION) {
        const double w = sqrt((1.0 - zeta) * (1.0 + zeta));
        lo = 1.5 / w; /* < pi / w: d > 0 */
        hi = 4.5 / w; /* > pi / w, < 2 pi / w: d < 0 */
    } else {
        for (;;) {
            exact_state(zeta, hi, &d, &v, &F);
            if (F <= 0.0)
                break;
            lo = hi;
            hi *= 2.0;
        }
    }
    for (;;) {
        const double t = lo > 0.0 && hi > 4.0 * lo ? sqrt(lo * hi) : 0.5 * (lo + hi);
        if (!(t > lo && t < hi))
            break;
        exact_state(zeta, t, &d, &v, &F);
        if ((law == CT_TAB_TENSION ? d : F) > 0.0)
            lo = t;
        else
            hi = t;
    }
    exact_state(zeta, hi, &d, &v, &F);
    return -v;
}

/* Both directions against the closed form, from e = 1e-300 to 1 and zeta = 1e-12 to 1e6 (the
 * clipped law; tension to 0.999), to its rounding stated above plus, for zeta_of_e, the
 * rounding of zeta itself (d(ln e)/dzeta times epsilon zeta: pi / (1 - zeta^2)^(3/2) for
 * tension, <= pi clipped). */
static void against_closed_form(void **state)
{
    (void)state;
    double worst[2] = {0, 0};
    for (int law = CT_TAB_TENSION; law <= CT_TAB_CLIPPED; law++) {
        for (int i = 0; i < 2000; i++) {
            const double e = pow(10.0, -300.0 * i / 1999.0), L = -log(e);
            const double z = ct_tab_zeta_of_e(e, law);
            if (z == 0.0) {
                assert_true(e == 1.0);
                continue;
            }
            const double got = closed_form_e(z, law);
            const double slope =
                law == CT_TAB_TENSION ? CT_TAB_PI / pow((1.0 - z) * (1.0 + z), 1.5) : CT_TAB_PI;
            double tol = 32.0 * DBL_EPSILON * (fmax(1.0, L) + slope * z);
            if (z > 1.0)
                tol += 8.0 * DBL_EPSILON / sqrt((z - 1.0) * (z + 1.0));
            if (!(fabs(got / e - 1.0) <= tol))
                fail_msg("law %d: e = %.17g: zeta_of_e = %.17g, closed form's e %.17g (rel "
                         "%.3g > %.3g)",
                         law, e, z, got, got / e - 1.0, tol);
            worst[law] = fmax(worst[law], fabs(got / e - 1.0) / tol);
        }
        for (int i = 0; i < 2000; i++) {
            const double top = law == CT_TAB_TENSION ? 0.999 : 1e6;
            const double z = top * pow(1e-12 / top, i / 1999.0);
            const double e = ct_tab_e_of_zeta(z, law), got = closed_form_e(z, law), L = -log(e);
            double tol = 32.0 * DBL_EPSILON * fmax(1.0, L);
            if (z > 1.0)
                tol += 8.0 * DBL_EPSILON / sqrt((z - 1.0) * (z + 1.0));
            if (!(fabs(got / e - 1.0) <= tol))
                fail_msg("law %d: zeta = %.17g: e_of_zeta = %.17g, closed form's e %.17g (rel "
                         "%.3g > %.3g)",
                         law, z, e, got, got / e - 1.0, tol);
            worst[law] = fmax(worst[law], fabs(got / e - 1.0) / tol);
        }
    }
    printf("closed form: largest |rel diff| / tolerance: tension %.3g, clipped %.3g\n", worst[0],
           worst[1]);
}

/* The tension law at zeta >= 1: the overlap stays > 0 (no rebound in finite time) and the
 * speed dies away, through 40 time constants of the slow mode, 1 / (zeta - s); e_of_zeta = 0
 * there, and zeta_of_e(0) = 1 (critical damping, the least zeta that gives e = 0). */
static void overdamped_tension(void **state)
{
    (void)state;
    static const double zetas[] = {1.0, 1.0 + 1e-9, 1.5, 3.0, 20.0};
    for (size_t k = 0; k < sizeof zetas / sizeof zetas[0]; k++) {
        const osc o = {zetas[k], CT_TAB_TENSION};
        const double s = sqrt(o.zeta * o.zeta - 1.0), T = 40.0 / (o.zeta - s);
        const double h = 2e-3 / (1.0 + 2.0 * o.zeta);
        double d = 0.0, v = 1.0;
        rk4(&o, d, v, h, &d, &v);
        for (double t = h; t < T; t += h) {
            rk4(&o, d, v, h, &d, &v);
            if (!(d > 0.0))
                fail_msg("zeta = %g: the overlap returned to 0 at t = %g", o.zeta, t);
        }
        assert_true(fabs(v) < 1e-15); /* e^-40 of the slow mode */
        assert_true(ct_tab_e_of_zeta(o.zeta, CT_TAB_TENSION) == 0.0);
    }
    assert_true(ct_tab_e_of_zeta(INFINITY, CT_TAB_TENSION) == 0.0);
    assert_true(ct_tab_zeta_of_e(0.0, CT_TAB_TENSION) == 1.0);
    /* just below 1 the rebound vanishes continuously: e = exp(-pi / sqrt(2 (1 - zeta))) */
    assert_true(ct_tab_e_of_zeta(1.0 - 1e-3, CT_TAB_TENSION) < 1e-30);
}

/* ln e = -2 zeta h(zeta) of the clipped law about zeta = 1: with u = zeta - 1,
 * h = 1 - u/3 + 2u^2/15 - ... (acos(1 - t) = sqrt(2t) (1 + t/12 + 3t^2/160 + ...) over
 * sqrt(1 - zeta^2) = sqrt(2t) (1 - t/4 - t^2/32 - ...), t = -u; the same series continues
 * acosh(zeta) / sqrt(zeta^2 - 1) above 1), so ln e = -2 - 4u/3 + 2u^2/5 + O(u^3), |O(u^3)| <
 * |u|^3 for |u| <= 1e-3 (its coefficient is -16/105). Both branches must meet it. */
static void clipped_at_critical(void **state)
{
    (void)state;
    const double e2 = exp(-2.0);
    assert_true(ct_tab_e_of_zeta(1.0, CT_TAB_CLIPPED) == e2);
    assert_true(fabs(ct_tab_zeta_of_e(e2, CT_TAB_CLIPPED) - 1.0) <= 2.0 * DBL_EPSILON);
    static const double us[] = {1e-3, 1e-5, 1e-7, 1e-9, 1e-12, 1e-15};
    for (size_t k = 0; k < sizeof us / sizeof us[0]; k++)
        for (int sign = -1; sign <= 1; sign += 2) {
            const double u = sign * us[k];
            const double series = -2.0 - 4.0 * u / 3.0 + 0.4 * u * u;
            const double got = log(ct_tab_e_of_zeta(1.0 + u, CT_TAB_CLIPPED));
            if (!(fabs(got - series) <= fabs(u * u * u) + 8.0 * DBL_EPSILON))
                fail_msg("zeta = 1 %+g: ln e = %.17g, series %.17g", u, got, series);
            /* and back: the root of the series' e */
            const double z = ct_tab_zeta_of_e(exp(series), CT_TAB_CLIPPED);
            if (!(fabs(z - (1.0 + u)) <= 1.5 * fabs(u * u * u) + 16.0 * DBL_EPSILON))
                fail_msg("e = exp(%.17g): zeta_of_e = %.17g, expected 1 %+g", series, z, u);
        }
    /* the underdamped branch reaches only e^-2: every e above has zeta < 1 */
    assert_true(ct_tab_zeta_of_e(e2 * (1.0 + 1e-13), CT_TAB_CLIPPED) < 1.0);
    assert_true(ct_tab_zeta_of_e(e2 * (1.0 - 1e-13), CT_TAB_CLIPPED) > 1.0);
}

/* e -> zeta -> e to the rounding of ln e, and zeta -> e -> zeta to what e's own rounding
 * allows (e holds ln e to about 1e-16 absolute, so zeta to 1e-16 / (d(-ln e)/dzeta) = 1e-16 /
 * ct_tab's slope, bounded below by 1 / (2 zeta) for zeta > 1 and by 1 below: 2 zeta h's slope
 * falls from pi to 4/3 on [0, 1] and is 2/zeta (1 + o(1)) for large zeta). */
static void round_trips(void **state)
{
    (void)state;
    for (int law = CT_TAB_TENSION; law <= CT_TAB_CLIPPED; law++) {
        for (int i = 0; i <= 20000; i++) {
            const double e = pow(10.0, -300.0 * i / 20000.0);
            const double z = ct_tab_zeta_of_e(e, law), back = ct_tab_e_of_zeta(z, law);
            /* zeta itself is rounded: ln e moves by d(ln e)/dzeta = pi / (1 - zeta^2)^(3/2)
             * (tension; <= pi for the clipped law) times zeta's rounding */
            const double L = -log(e), slope = law == CT_TAB_TENSION
                                                  ? CT_TAB_PI / pow((1 - z) * (1 + z), 1.5)
                                                  : CT_TAB_PI;
            if (!(fabs(log(back) + L) <= 8.0 * DBL_EPSILON * (fmax(1.0, L) + slope * z)))
                fail_msg("law %d: e = %.17g -> zeta %.17g -> e %.17g", law, e, z, back);
        }
        const double top = law == CT_TAB_TENSION ? 0.97 : 1e6;
        for (int i = 0; i <= 20000; i++) {
            const double z = i == 0 ? 0.0 : top * pow(1e-12 / top, (double)(i - 1) / 19999.0);
            const double e = ct_tab_e_of_zeta(z, law), back = ct_tab_zeta_of_e(e, law);
            const double slope_min = z > 1.0 ? 0.5 / z : 1.0;
            const double L = -log(e);
            const double tol = 4.0 * DBL_EPSILON * fmax(1.0, L) / slope_min + 4.0 * DBL_EPSILON * z;
            if (!(fabs(back - z) <= tol))
                fail_msg("law %d: zeta = %.17g -> e %.17g -> zeta %.17g (diff %.3g > %.3g)", law, z,
                         e, back, back - z, tol);
        }
    }
    /* monotone: e falls as zeta rises */
    for (int law = CT_TAB_TENSION; law <= CT_TAB_CLIPPED; law++) {
        double prev = 2.0;
        for (int i = 0; i <= 5000; i++) {
            const double e = ct_tab_e_of_zeta(i * (law == CT_TAB_TENSION ? 2e-4 : 1e-3), law);
            assert_true(e <= prev);
            prev = e;
        }
    }
}

/* The whole input domain, as a DEM code may hand it over (e from a table; e = 1 + 2^-52 and
 * e = -1.9e-36 came out of tables at the slope limit before the reader kept e between the
 * nodes, tests/test_table.c): e at every binade from the smallest subnormal to 1 (256 mantissas
 * each), the 256 doubles below 1, 0 and 1; zeta at every binade up to DBL_MAX, and infinity.
 * Every result is defined: zeta_of_e >= 0 and finite but for e = 0 under the clipped law
 * (+infinity, as stated), never rising with e; e_of_zeta in [0, 1], never rising with zeta.
 * Just outside the domain (one ulp above 1, the smallest negative number) NaN says so. */
static void whole_domain(void **state)
{
    (void)state;
    size_t checked = 0;
    for (int law = CT_TAB_TENSION; law <= CT_TAB_CLIPPED; law++) {
        double prev = INFINITY, last_e = -1.0;
        for (int ex = -1075; ex <= 0; ex++)
            for (int m = 0; m < 256; m++) {
                const double e = ex == -1075 ? ldexp((double)m, -1074) : ldexp(1.0 + m / 256.0, ex);
                if (e >= 1.0 || !(e > last_e))
                    continue; /* rounded to a subnormal already taken */
                last_e = e;
                const double z = ct_tab_zeta_of_e(e, law);
                if (!(z >= 0.0 && (isfinite(z) || (e == 0.0 && law == CT_TAB_CLIPPED))) ||
                    !(z <= prev))
                    fail_msg("law %d: zeta_of_e(%a) = %a (after %a)", law, e, z, prev);
                prev = z;
                checked++;
            }
        for (int k = 256; k >= 0; k--) { /* the doubles below 1, rising, and 1 */
            const double e = 1.0 - k * 0x1p-53, z = ct_tab_zeta_of_e(e, law);
            if (!(z >= 0.0 && z <= prev && (k > 0 || z == 0.0)))
                fail_msg("law %d: zeta_of_e(1 - %d ulp) = %a", law, k, z);
            prev = z;
        }
        prev = 1.0;
        double last_z = -1.0;
        for (int ex = -1074; ex <= 1024; ex++)
            for (int m = 0; m < 64; m++) {
                double z = ex == -1074 ? ldexp((double)m, -1074) : ldexp(1.0 + m / 64.0, ex);
                if (isinf(z))
                    z = m == 0 ? INFINITY : DBL_MAX;
                if (!(z > last_z))
                    continue;
                last_z = z;
                const double e = ct_tab_e_of_zeta(z, law);
                if (!(e >= 0.0 && e <= 1.0 && e <= prev))
                    fail_msg("law %d: e_of_zeta(%a) = %a (after %a)", law, z, e, prev);
                prev = e;
                checked++;
            }
        assert_true(isnan(ct_tab_zeta_of_e(1.0 + 0x1p-52, law)));
        assert_true(isnan(ct_tab_zeta_of_e(-0x1p-1074, law)));
    }
    assert_true(checked > 600000);
}

static void ends_and_bad_input(void **state)
{
    (void)state;
    for (int law = CT_TAB_TENSION; law <= CT_TAB_CLIPPED; law++) {
        assert_true(ct_tab_zeta_of_e(1.0, law) == 0.0);
        assert_true(ct_tab_e_of_zeta(0.0, law) == 1.0);
        assert_true(ct_tab_e_of_zeta(INFINITY, law) == 0.0);
        static const double bad_e[] = {-1e-300, -1.0, 1.0000000000000002, 2.0, INFINITY, -INFINITY};
        for (size_t k = 0; k < sizeof bad_e / sizeof bad_e[0]; k++)
            assert_true(isnan(ct_tab_zeta_of_e(bad_e[k], law)));
        assert_true(isnan(ct_tab_zeta_of_e(NAN, law)));
        assert_true(isnan(ct_tab_e_of_zeta(NAN, law)));
        assert_true(isnan(ct_tab_e_of_zeta(-1e-300, law)));
        assert_true(isnan(ct_tab_e_of_zeta(-INFINITY, law)));
        /* the smallest e there is */
        const double tiny = ct_tab_zeta_of_e(4.9406564584124654e-324, law);
        assert_true(isfinite(tiny) && tiny > 0.0);
    }
    assert_true(isinf(ct_tab_zeta_of_e(0.0, CT_TAB_CLIPPED)));
    /* e ~ 1 / (2 zeta)^2 for large zeta (clipped): zeta = 1e100 gives e ~ 2.5e-201 */
    const double big = ct_tab_e_of_zeta(1e100, CT_TAB_CLIPPED);
    assert_true(big > 0.0 && fabs(big * 4e200 - 1.0) < 1e-12);
    for (int law = -1; law <= 3; law += 4) {
        assert_true(isnan(ct_tab_zeta_of_e(0.5, law)));
        assert_true(isnan(ct_tab_e_of_zeta(0.5, law)));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(zeta_of_e_against_integration),
        cmocka_unit_test(e_of_zeta_against_integration),
        cmocka_unit_test(against_closed_form),
        cmocka_unit_test(overdamped_tension),
        cmocka_unit_test(clipped_at_critical),
        cmocka_unit_test(round_trips),
        cmocka_unit_test(whole_domain),
        cmocka_unit_test(ends_and_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
