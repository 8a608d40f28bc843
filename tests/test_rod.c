/* The rod law (docs/model.md §3) against its closed forms, Eqs. 4-11. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>

#include "rod.h"

/* A rod of top depth 0.3, length 9.7 (H* = 10), area 0.25, E = 500, eps_y = 0.002. */
static const double top = 0.3, L = 9.7, s = 0.25, E = 500.0, eps_y = 0.002;

#define assert_close(a, b, rel)                                                                    \
    assert_true(fabs((a) - (b)) <= (rel)*fmax(fabs(a), fabs(b)) + 1e-300)

static double u_yield(void)
{
    return eps_y * L + top; /* Eq. 6 */
}

static void elastic_line(void **state)
{
    (void)state;
    for (int k = 1; k < 100; k++) {
        double u = top + (u_yield() - top) * k / 100.0;
        double strain = (u - top) / L;                                                  /* Eq. 4 */
        assert_close(ct_rod_force(u, top, L, s, 0.0, E, eps_y), E * strain * s, 1e-14); /* Eq. 5 */
        assert_true(ct_rod_advance(u, top, L, 0.0, eps_y) == 0.0);
    }
}

static void yield_onset_and_plateau(void **state)
{
    (void)state;
    double uy = u_yield();
    assert_close(ct_rod_force(uy, top, L, s, 0.0, E, eps_y), E * eps_y * s, 1e-14);
    /* just below: elastic and strictly less; just above: the plateau sigma_y s (Eq. 7) */
    assert_true(ct_rod_force(uy * (1 - 1e-9), top, L, s, 0.0, E, eps_y) < E * eps_y * s);
    for (double u = uy * 1.001; u < 9.0; u *= 1.3)
        assert_true(ct_rod_force(u, top, L, s, 0.0, E, eps_y) == E * eps_y * s);
    assert_true(ct_rod_advance(uy * (1 - 1e-12), top, L, 0.0, eps_y) == 0.0);
    assert_true(ct_rod_advance(uy * 1.01, top, L, 0.0, eps_y) > 0.0);
}

static void unloading_line_and_residual(void **state)
{
    (void)state;
    double umax = 0.5;
    double eps_max = (umax - top) / L;
    double ep = ct_rod_advance(umax, top, L, 0.0, eps_y);
    assert_close(ep, eps_max - eps_y, 1e-13); /* Eq. 10 */
    double release = top + ep * L;
    for (int k = 1; k <= 50; k++) {
        double u = release + (umax - release) * k / 50.0;
        double eq11 = E * eps_y * s * ((u - umax) / (L * eps_y) + 1.0); /* Eq. 11 */
        assert_close(ct_rod_force(u, top, L, s, ep, E, eps_y), eq11, 1e-11);
        /* unloading never changes the plastic strain */
        assert_true(ct_rod_advance(u, top, L, ep, eps_y) == ep);
    }
}

static void contact_lost_and_no_tension(void **state)
{
    (void)state;
    double ep = ct_rod_advance(0.6, top, L, 0.0, eps_y);
    double release = ct_rod_contact(top, L, ep);
    /* Eq. 11's line from u_max = 0.6 reaches P = 0 at u_max - eps_y L */
    assert_close(release, 0.6 - eps_y * L, 1e-14);
    /* at the release point the force vanishes up to the rounding of u - top */
    assert_true(ct_rod_force(release, top, L, s, ep, E, eps_y) <= E * s * 1e-15);
    assert_true(ct_rod_force(release * (1 + 1e-9), top, L, s, ep, E, eps_y) > 0.0);
    for (double u = release - 1e-9; u > -5.0; u -= 0.37)
        assert_true(ct_rod_force(u, top, L, s, ep, E, eps_y) == 0.0);
    assert_true(ct_rod_force(-1e300, top, L, s, 0.0, E, eps_y) == 0.0);
}

static void reload_yields_only_past_previous_max(void **state)
{
    (void)state;
    double umax = 0.55;
    double ep = ct_rod_advance(umax, top, L, 0.0, eps_y);
    double release = ct_rod_contact(top, L, ep);
    /* reload along the elastic line back to umax: no new yield */
    for (int k = 0; k <= 20; k++) {
        double u = release + (umax - release) * k / 20.0;
        double line = E * s * ((u - top) / L - ep);
        assert_close(ct_rod_force(u, top, L, s, ep, E, eps_y), fmax(line, 0.0), 1e-11);
        assert_true(ct_rod_advance(u, top, L, ep, eps_y) == ep);
    }
    assert_close(ct_rod_yield(top, L, ep, eps_y), umax, 1e-14);
    double ep2 = ct_rod_advance(umax + 0.01, top, L, ep, eps_y);
    assert_true(ep2 > ep);
    assert_close(ep2, (umax + 0.01 - top) / L - eps_y, 1e-13);
}

static void work_balance(void **state)
{
    (void)state;
    /* Elastic: W = E s L eps^2 / 2, all recoverable. */
    double u = top + 0.5 * eps_y * L, eps = (u - top) / L;
    assert_close(ct_rod_work(top, u, top, L, s, 0.0, E, eps_y), E * s * L * eps * eps / 2, 1e-14);
    assert_close(ct_rod_elastic_energy(u, top, L, s, 0.0, E, eps_y), E * s * L * eps * eps / 2,
                 1e-14);
    /* Yielded: W = E s L (eps_y eps - eps_y^2 / 2) = recoverable + dissipated. */
    double umax = 0.9;
    eps = (umax - top) / L;
    double W = ct_rod_work(-1.0, umax, top, L, s, 0.0, E, eps_y);
    assert_close(W, E * s * L * (eps_y * eps - eps_y * eps_y / 2), 1e-13);
    double ep = ct_rod_advance(umax, top, L, 0.0, eps_y);
    double recoverable = ct_rod_elastic_energy(umax, top, L, s, ep, E, eps_y);
    double dissipated = E * eps_y * s * ep * L; /* plateau force times plastic shortening */
    assert_close(recoverable, E * s * L * eps_y * eps_y / 2, 1e-12);
    assert_close(W, recoverable + dissipated, 1e-12);
    /* The work along the unloading state equals the recoverable energy. */
    assert_close(ct_rod_work(ct_rod_contact(top, L, ep), umax, top, L, s, ep, E, eps_y),
                 recoverable, 1e-11);
    /* The work of the force law against a fine midpoint sum of ct_rod_force. */
    long n = 200000;
    double a = top - 0.1, b = 0.7, sum = 0.0, h = (b - a) / n;
    for (long k = 0; k < n; k++)
        sum += ct_rod_force(a + (k + 0.5) * h, top, L, s, 0.0, E, eps_y) * h;
    assert_close(ct_rod_work(a, b, top, L, s, 0.0, E, eps_y), sum, 1e-8);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(elastic_line),
        cmocka_unit_test(yield_onset_and_plateau),
        cmocka_unit_test(unloading_line_and_residual),
        cmocka_unit_test(contact_lost_and_no_tension),
        cmocka_unit_test(reload_yields_only_past_previous_max),
        cmocka_unit_test(work_balance),
    };
    return cmocka_run_group_tests_name("rod", tests, NULL, NULL);
}
