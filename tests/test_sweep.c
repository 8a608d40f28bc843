/* Planning and sweeps (src/sweep.c): a hand-derived three-rod surface, the sweep against the
 * same impacts run one by one, V*_c independent of the other speeds of a scene, a crushing
 * speed reported as its own row, and pruning that changes no reported number. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "assert_rel.h"
#include "cantact.h"

/* Three rods, E = 10, sigma_y = 1 (eps_y = 0.1), H* = 2, l0 = h0 = 1, every area 1:
 *   rod  top  L    k = E s/L  yield y = top + eps_y L  plateau F = E s eps_y
 *   A    0    2    5          0.2                      1
 *   B    0.5  1.5  20/3       0.65                     1
 *   C    1    1    10         1.1                      1
 * Impact 1 with kinetic energy 0.925 from the virgin surface, u_max = 0.8 (A, B yielded,
 * C not touched): work A = 5 (0.2)^2/2 + 1 (0.8 - 0.2) = 0.7, B = (20/3)(0.15)^2/2 +
 * 1 (0.8 - 0.65) = 0.225, total 0.925. Recoverable: F eps_y L / 2 = 0.1 + 0.075 = 0.175, so
 * e1 = sqrt(0.175/0.925) = sqrt(7/37). A releases at 0.8 - 0.2 = 0.6, B at 0.65: u_release =
 * 0.6. V*_c: first yield at 0.2, W = 5 (0.2)^2 / 2 = 0.1, V*_c = sqrt(0.1 / (l0 E h0)) = 0.1.
 * Impact 2, same energy: 0.175 reloads A, B elastically to 0.8; then P = 2 up to C's contact
 * at 1 (0.4, total 0.575); C elastic to 1.1 (2 (0.1) + 10 (0.1)^2/2 = 0.25, total 0.825);
 * then P = 3: 0.1 more is 1/30, u_max = 1.1 + 1/30. Recoverable 0.1 + 0.075 + 0.05 = 0.225:
 * e2 = sqrt(9/37). Its V*_c: the first yield of the shaken-down state is at 0.8, reached with
 * 0.175: V*_c = sqrt(0.0175). */
static ct_bundle *three_rods(void)
{
    ct_layer L = {.E = 10.0, .sigma_y = 1.0, .Hstar = 2.0, .l0 = 1.0, .h0 = 1.0};
    double top[3] = {0.0, 0.5, 1.0}, area[3] = {1.0, 1.0, 1.0};
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 3, top, area), CT_OK);
    return b;
}

static void three_rods_on_paper(void **state)
{
    (void)state;
    ct_bundle *b = three_rods();
    const double V = sqrt(0.925 / 10.0);
    ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 2};
    ct_impact_opts_default(&spec.opts);
    ct_sweep_row rows[2];
    assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
    for (int i = 0; i < 2; i++)
        assert_int_equal(rows[i].status, CT_OK);
    assert_rel(rows[0].r.u_max, 0.8, 1e-14);
    assert_rel(rows[0].r.e, sqrt(7.0 / 37.0), 1e-14);
    assert_rel(rows[0].r.e_closed, sqrt(7.0 / 37.0), 1e-14);
    assert_rel(rows[0].r.u_release, 0.6, 1e-14);
    assert_rel(rows[0].r.V_star_crit, 0.1, 1e-14);
    assert_rel(rows[1].r.u_contact, 0.6, 1e-14);
    assert_rel(rows[1].r.u_max, 1.1 + 1.0 / 30.0, 1e-14);
    assert_rel(rows[1].r.e, sqrt(9.0 / 37.0), 1e-14);
    assert_rel(rows[1].r.e_closed, sqrt(9.0 / 37.0), 1e-14);
    assert_rel(rows[1].r.V_star_crit, sqrt(0.0175), 1e-14);
    assert_rel(rows[1].r.u_release, 1.1 + 1.0 / 30.0 - 0.2, 1e-14);
    /* the same two impacts through ct_impact, which carries the state in the bundle */
    for (int i = 0; i < 2; i++) {
        ct_impact_result r;
        assert_int_equal(ct_impact(b, 0.925, NULL, &r), CT_OK);
        assert_rel(r.e, i ? sqrt(9.0 / 37.0) : sqrt(7.0 / 37.0), 1e-14);
    }
    ct_bundle_free(b);
}

static ct_params base(void)
{
    ct_params p = {
        .fx = 1.5, .fz = 1.3, .l0 = 1.0, .h0 = 1.0, .Hstar = 10.0, .E = 500.0, .sigma_y = 1.0};
    return p;
}

static int no_op_observer(const ct_sweep_row *row, int phase, const ct_bundle *b, const ct_curve *c,
                          void *ctx)
{
    (void)row, (void)phase, (void)b, (void)c;
    ++*(int *)ctx;
    return 0;
}

/* The sweep (one curve for all speeds, impacts by its shifts, closed forms in shared passes)
 * against the plain loop: a fresh bundle per speed, ct_impact after ct_impact. The first
 * impacts are the very same computation (bitwise); later ones take another path (the
 * shifted curve instead of a rebuilt one) and agree to rounding. An observer forces the
 * state-carrying path of the sweep itself, which must agree too. */
static void sweep_equals_one_by_one(void **state)
{
    (void)state;
    ct_params p = base();
    enum { NV = 7, IMP = 4 };
    const double V[NV] = {3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 2e-2};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 80, INFINITY), CT_OK);
    ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = IMP};
    ct_impact_opts_default(&spec.opts);
    ct_sweep_row rows[NV * IMP], carried[NV * IMP];
    assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
    int calls = 0;
    spec.observe = no_op_observer;
    spec.observe_ctx = &calls;
    assert_int_equal(ct_sweep(b, &spec, carried), CT_OK);
    assert_int_equal(calls, 2 * NV * IMP);
    for (size_t v = 0; v < NV; v++) {
        ct_bundle *one;
        assert_int_equal(ct_cantor_bundle(&one, &p, CT_REP_STAGES, 80, INFINITY), CT_OK);
        for (int i = 0; i < IMP; i++) {
            ct_impact_result r;
            const ct_sweep_row *row = &rows[v * IMP + (size_t)i],
                               *cr = &carried[v * IMP + (size_t)i];
            assert_int_equal(ct_impact(one, V[v] * V[v] * ct_energy_scale(&p), NULL, &r), CT_OK);
            assert_int_equal(row->status, CT_OK);
            assert_int_equal(row->impact, i + 1);
            assert_int_equal(row->r.elastic, r.elastic);
            if (i == 0) {
                assert_memory_equal(&row->r.e, &r.e, sizeof r.e);
                assert_memory_equal(&row->r.e_closed, &r.e_closed, sizeof r.e);
                assert_memory_equal(&row->r.u_max, &r.u_max, sizeof r.e);
            }
            const ct_impact_result *got[2] = {&row->r, &cr->r};
            for (int g = 0; g < 2; g++) {
                assert_rel(got[g]->e, r.e, 1e-13);
                assert_rel(got[g]->e_closed, r.e_closed, 1e-13);
                assert_rel(got[g]->u_max, r.u_max, 1e-14);
                assert_rel(got[g]->u_release, r.u_release, 1e-14);
                assert_rel(got[g]->V_star_crit, r.V_star_crit, 1e-13);
                assert_rel(got[g]->W_unload, r.W_unload, 1e-13);
            }
        }
        ct_bundle_free(one);
    }
    ct_bundle_free(b);
}

/* Issue 11's bug: pruning the rods no impact reaches took away the ones between u_max and
 * the first yield, and V*_c of a scene whose speeds are all below it came out 3 % low. */
static void vstar_crit_does_not_depend_on_the_other_speeds(void **state)
{
    (void)state;
    ct_params p = base();
    const double alone[1] = {2e-4}, with_fast[2] = {2e-4, 1e-3};
    double Vc[2];
    for (int k = 0; k < 2; k++) {
        ct_cantor_plan plan = {.params = p,
                               .depth = 12,
                               .representation = CT_REP_STAGES,
                               .depth_tolerance = 1e-12,
                               .V_star = k ? with_fast : alone,
                               .nvel = k ? 2 : 1,
                               .impacts = 1};
        ct_impact_opts_default(&plan.opts);
        ct_bundle *b;
        ct_plan_info info;
        assert_int_equal(ct_cantor_plan_build(&plan, &b, &info), CT_OK);
        assert_true(info.omitted > 0); /* something was left out, or this tests nothing */
        ct_sweep_spec spec = {.V_star = plan.V_star, .nvel = plan.nvel, .impacts = 1};
        spec.opts = plan.opts;
        ct_sweep_row rows[2];
        assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
        assert_int_equal(rows[0].r.elastic, 1);
        Vc[k] = rows[0].r.V_star_crit;
        ct_bundle_free(b);
    }
    /* the reference: every rod kept; V*_c from the closed-form critical energy */
    ct_bundle *full;
    double Wc, uy;
    assert_int_equal(ct_cantor_bundle(&full, &p, CT_REP_STAGES, 12, INFINITY), CT_OK);
    assert_int_equal(ct_critical_energy(full, &Wc, &uy), CT_OK);
    assert_rel(Vc[0], sqrt(Wc / ct_energy_scale(&p)), 1e-14);
    assert_rel(Vc[1], sqrt(Wc / ct_energy_scale(&p)), 1e-14);
    ct_bundle_free(full);
}

/* Pruned and full bundles give the same rows (impacts carried over, segments too). */
static void pruning_changes_no_reported_number(void **state)
{
    (void)state;
    ct_params p = base();
    const double V[3] = {5e-5, 2e-3, 8e-3};
    for (int rep = 0; rep < 2; rep++) {
        ct_cantor_plan plan = {.params = p,
                               .depth = 10,
                               .representation = rep ? CT_REP_SEGMENTS : CT_REP_STAGES,
                               .depth_tolerance = 1e-12,
                               .V_star = V,
                               .nvel = 3,
                               .impacts = 3};
        ct_impact_opts_default(&plan.opts);
        ct_bundle *pruned, *full;
        ct_plan_info info;
        assert_int_equal(ct_cantor_plan_build(&plan, &pruned, &info), CT_OK);
        assert_true(info.omitted > 0);
        plan.keep_all_rods = 1;
        assert_int_equal(ct_cantor_plan_build(&plan, &full, &info), CT_OK);
        assert_int_equal(info.omitted, 0);
        ct_sweep_spec spec = {.V_star = V, .nvel = 3, .impacts = 3};
        spec.opts = plan.opts;
        ct_sweep_row a[9], b[9];
        assert_int_equal(ct_sweep(pruned, &spec, a), CT_OK);
        assert_int_equal(ct_sweep(full, &spec, b), CT_OK);
        for (int k = 0; k < 9; k++) {
            assert_int_equal(a[k].status, CT_OK);
            assert_rel(a[k].r.e, b[k].r.e, 1e-14);
            assert_rel(a[k].r.u_max, b[k].r.u_max, 1e-14);
            assert_rel(a[k].r.u_release, b[k].r.u_release, 1e-14);
            assert_rel(a[k].r.V_star_crit, b[k].r.V_star_crit, 1e-14);
        }
        ct_bundle_free(pruned);
        ct_bundle_free(full);
    }
}

/* A speed that crushes the layer fails its own row (and its later impacts are not run);
 * the others compute. Under stop_on_error the sweep returns that status and message. */
static void crushing_speed_is_one_row(void **state)
{
    (void)state;
    ct_params p = base();
    const double V[3] = {1e-3, 50.0, 2e-3};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 30, INFINITY), CT_OK);
    ct_sweep_spec spec = {.V_star = V, .nvel = 3, .impacts = 2};
    ct_impact_opts_default(&spec.opts);
    ct_sweep_row rows[6];
    assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
    assert_int_equal(rows[0].status, CT_OK);
    assert_int_equal(rows[1].status, CT_OK);
    assert_int_equal(rows[2].status, CT_ERANGE);
    assert_non_null(strstr(rows[2].message, "crushed"));
    assert_int_equal(rows[3].status, CT_ESKIPPED);
    assert_int_equal(rows[4].status, CT_OK);
    assert_int_equal(rows[5].status, CT_OK);
    spec.stop_on_error = 1;
    assert_int_equal(ct_sweep(b, &spec, rows), CT_ERANGE);
    assert_non_null(strstr(ct_error_message(), "V* = 50"));
    ct_bundle_free(b);
}

/* The rod path (no curve; Newton's method on the rod sums, all speeds together) against the
 * curve path: stage rods at the fractal depth with repeated impacts, segments after their
 * state carries over, and arbitrary tops. A crushing speed fails the same way on both. */
static void rod_path_equals_curve_path(void **state)
{
    (void)state;
    ct_params p = base();
    enum { NV = 8, IMP = 3 };
    const double V[NV] = {3e-5, 1e-4, 2e-4, 1e-3, 3e-3, 1e-2, 3e-2, 60.0};
    ct_bundle *b[3];
    assert_int_equal(ct_cantor_bundle(&b[0], &p, CT_REP_STAGES, 147, INFINITY), CT_OK);
    assert_int_equal(ct_cantor_bundle(&b[1], &p, CT_REP_SEGMENTS, 12, INFINITY), CT_OK);
    double top[500], area[500];
    for (int k = 0; k < 500; k++) { /* tops spread over [0, 2 h0), areas summing to l0 */
        top[k] = 2.0 * fmod(0.618033988749895 * k, 1.0);
        area[k] = 1.0 / 500.0;
    }
    ct_layer L = {.E = 500.0, .sigma_y = 1.0, .Hstar = 10.0, .l0 = 1.0, .h0 = 1.0};
    assert_int_equal(ct_bundle_from_rods(&b[2], &L, 500, top, area), CT_OK);
    for (int k = 0; k < 3; k++) {
        ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = IMP};
        ct_impact_opts_default(&spec.opts);
        ct_sweep_row c[NV * IMP], r[NV * IMP];
        spec.path = CT_PATH_CURVE;
        assert_int_equal(ct_sweep(b[k], &spec, c), CT_OK);
        spec.path = CT_PATH_RODS;
        assert_int_equal(ct_sweep(b[k], &spec, r), CT_OK);
        for (int q = 0; q < NV * IMP; q++) {
            assert_int_equal(r[q].status, c[q].status);
            if (c[q].status)
                continue;
            assert_int_equal(r[q].r.elastic, c[q].r.elastic);
            assert_rel(r[q].r.e, c[q].r.e, 1e-13);
            assert_rel(r[q].r.e_closed, c[q].r.e_closed, 1e-13);
            assert_rel(r[q].r.u_max, c[q].r.u_max, 1e-14);
            assert_rel(r[q].r.u_release, c[q].r.u_release, 1e-14);
            assert_rel(r[q].r.V_star_crit, c[q].r.V_star_crit, 1e-13);
        }
        assert_int_equal(c[(NV - 1) * IMP].status, CT_ERANGE); /* V* = 60 crushes */
        for (int q = (NV - 1) * IMP; q < NV * IMP; q++)        /* and says so on both paths */
            assert_true(strstr(c[q].message, q == (NV - 1) * IMP ? "crushed" : "not run") &&
                        strstr(r[q].message, q == (NV - 1) * IMP ? "crushed" : "not run"));
        ct_bundle_free(b[k]);
    }
}

/* Two rods over five impacts, E = 100, sigma_y = 1 (eps_y = 0.01), H* = 10, l0 = h0 = 1:
 *   rod  top   L     area   k = E s/L  yield          plateau F
 *   A    0     10    1      10         0.1            1
 *   B    0.12  9.88  0.988  10         0.12 + 0.0988  0.988
 * Every impact has kinetic energy W0 = 0.095. A yields in the first impact and stays on its
 * plateau whenever it is loaded past its previous maximum; B never yields (checked below).
 * Loaded from the virgin surface to u in [0.12, 0.2188]: W(u) = 0.05 + (u - 0.1) +
 * 5 (u - 0.12)^2 (A: 10 (0.1)^2/2 elastic, then F = 1 on the plateau; B: 10 (u - 0.12)^2/2).
 * After a maximum U, A releases at U - 0.1 and reloads elastically to U (storing 0.05 again),
 * B is unchanged; so impact k reaches u_k with
 *   0.05 + (u_k - U) + 5 (u_k - 0.12)^2 = W0,   U = u_{k-1} (u_0 = 0.1: the virgin surface).
 * With x_k = u_k - 0.12 and c = W0 - 0.05 = 0.045: 5 x_k^2 + x_k - (c + x_{k-1}) = 0,
 *   x_k = (-1 + sqrt(1 + 20 (c + x_{k-1}))) / 10,   x_0 = -0.02.
 * What comes back is A's elastic energy on its plateau, 0.05, and B's, 5 x_k^2:
 *   e_k = sqrt((0.05 + 5 x_k^2) / W0).
 * A releases at u_k - 0.1 = x_k + 0.02 < 0.12 (B's contact): u_release = x_k + 0.02. The
 * critical energy of the state before impact k is what reaches the first yield: 0.05 for
 * the virgin surface (A at 0.1), then 0.05 + 5 x_{k-1}^2 (A back at its maximum u_{k-1});
 * V*_c = sqrt(W_c / (l0 E h0)) = sqrt(W_c / 100). The fixed point x* = sqrt(c/5) = 0.0949
 * stays below B's yield at x = 0.0988, so B never yields; e rises to sqrt(0.095/0.095) = 1
 * as the surface shakes down. */
static void two_rods_five_impacts_on_paper(void **state)
{
    (void)state;
    enum { IMP = 5 };
    ct_layer L = {.E = 100.0, .sigma_y = 1.0, .Hstar = 10.0, .l0 = 1.0, .h0 = 1.0};
    const double top[2] = {0.0, 0.12}, area[2] = {1.0, 0.988}, W0 = 0.095;
    long double x[IMP + 1], e[IMP + 1], Vc[IMP + 1];
    x[0] = -0.02L;
    for (int k = 1; k <= IMP; k++) {
        x[k] = (-1.0L + sqrtl(1.0L + 20.0L * (0.045L + x[k - 1]))) / 10.0L;
        e[k] = sqrtl((0.05L + 5.0L * x[k] * x[k]) / 0.095L);
        Vc[k] = sqrtl((k == 1 ? 0.05L : 0.05L + 5.0L * x[k - 1] * x[k - 1]) / 100.0L);
        assert_true(x[k] < 0.0988L); /* B stays elastic */
    }
    const double V = sqrt(W0 / 100.0);
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 2, top, area), CT_OK);
    /* the shifted curve (the sweep's fast path), the rod path, and the state-carrying path
     * (an observer), then ct_impact after ct_impact on the bundle itself */
    const ct_sweep_path paths[] = {CT_PATH_CURVE, CT_PATH_RODS, CT_PATH_CURVE};
    for (int q = 0; q < 4; q++) {
        ct_sweep_row rows[IMP];
        int calls = 0;
        if (q < 3) {
            ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = IMP, .path = paths[q]};
            ct_impact_opts_default(&spec.opts);
            if (q == 2) {
                spec.observe = no_op_observer;
                spec.observe_ctx = &calls;
            }
            assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
        } else {
            for (int k = 0; k < IMP; k++) {
                rows[k].status = ct_impact(b, W0, NULL, &rows[k].r);
                assert_int_equal(rows[k].status, CT_OK);
            }
        }
        for (int k = 1; k <= IMP; k++) {
            const ct_impact_result *r = &rows[k - 1].r;
            assert_int_equal(rows[k - 1].status, CT_OK);
            assert_false(r->elastic);
            assert_rel(r->u_max, (double)(0.12L + x[k]), 1e-14);
            assert_rel(r->e, (double)e[k], 1e-13);
            assert_rel(r->u_release, (double)(x[k] + 0.02L), 1e-13);
            assert_rel(r->u_contact, k == 1 ? 0.0 : (double)(x[k - 1] + 0.02L), 1e-13);
            assert_rel(r->V_star_crit, (double)Vc[k], 1e-13);
            if (q != 1) /* the rod path is the closed form itself */
                assert_rel(r->e_closed, (double)e[k], 1e-13);
        }
        if (q == 2)
            assert_int_equal(calls, 2 * IMP);
    }
    ct_bundle_free(b);
}

/* One rod struck three times on the rod path, by hand: top 0, area 1, H* = L = 10, E = 1e6,
 * sigma_y = 1 (eps_y = 1e-6), l0 = 1, h0 = 10. Yield at u_y = eps_y L = 1e-5 with the elastic
 * energy E s L eps_y^2 / 2 = 5e-6 stored; then the plateau force F = E s eps_y = 1. Every
 * impact has V* = 7.7781745930520228e-07, kinetic energy W = V*^2 l0 E h0 = 6.05e-6:
 *   impact 1: 5e-6 + F (u_1 - 1e-5) = 6.05e-6, u_1 = 1.105e-5;
 *   impact k: the rod, released at u_{k-1} - 1e-5, reloads elastically to u_{k-1} (5e-6 stored
 *   again), then 1.05e-6 more on the plateau: u_k = u_{k-1} + 1.05e-6.
 * Each time the rod gives back its elastic energy 5e-6: e = sqrt(5 / 6.05) = sqrt(100 / 121)
 * = 10/11, exactly. The second impact's Newton iteration used to start at H* = 10, whose first
 * step rounds to an ulp of 10 (2e-15, 1e-10 of u_2) and landed left of the root: refused with
 * |W(u) - W| / W = 1.2e-10. Then random rod sets on the rod path against the curve path: of
 * 30 with 1 to 2000 rods and E/sigma_y up to 1e7 over three impacts 5 failed so; of 200 with up
 * to 500 rods and E/sigma_y up to 1e20 over four impacts 148 failed, first impacts too (from a
 * grid point 20 times the root the first step landed 30 ulps left of it). */
static void rod_path_repeated_impacts(void **state)
{
    (void)state;
    ct_layer L = {.E = 1e6, .sigma_y = 1.0, .Hstar = 10.0, .l0 = 1.0, .h0 = 10.0};
    const double top = 0.0, area = 1.0, V = 7.7781745930520228e-07;
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 1, &top, &area), CT_OK);
    for (int path = CT_PATH_CURVE; path <= CT_PATH_RODS; path++) {
        ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 3, .path = path};
        ct_impact_opts_default(&spec.opts);
        ct_sweep_row rows[3];
        assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
        for (int k = 0; k < 3; k++) {
            if (rows[k].status)
                fail_msg("path %d, impact %d: %s", path, k + 1, rows[k].message);
            assert_false(rows[k].r.elastic);
            assert_rel(rows[k].r.u_max, 1.105e-5 + 1.05e-6 * k, 1e-13);
            assert_true(fabs(rows[k].r.e - 10.0 / 11.0) <= 1e-14);
        }
    }
    ct_bundle_free(b);
    /* random rod sets: tops over [0, 1), areas over a decade; 30 of 1 to 2000 rods with
     * E/sigma_y from 1e2 to 1e7, three impacts; 200 of 1 to 500 rods with E/sigma_y up to
     * 1e20, four impacts */
    uint64_t x = 88172645463325252u;
#define NEXT() (x ^= x << 13, x ^= x >> 7, x ^= x << 17, (double)(x >> 11) * 0x1p-53)
    enum { SETS = 230, NV = 4, IMP = 4, MAXN = 2000 };
    double *tops = malloc(MAXN * sizeof(double)), *areas = malloc(MAXN * sizeof(double));
    assert_non_null(tops);
    assert_non_null(areas);
    for (int set = 0; set < SETS; set++) {
        const int stiff = set >= 30, imp = stiff ? IMP : 3;
        const size_t n = set == 0 ? 1 : 1 + (size_t)(NEXT() * (stiff ? 499 : MAXN - 1));
        double sum = 0.0;
        for (size_t k = 0; k < n; k++) {
            tops[k] = k == 0 ? 0.0 : NEXT();
            areas[k] = pow(10.0, NEXT());
            sum += areas[k];
        }
        const double E = pow(10.0, 2.0 + (stiff ? 18.0 : 5.0) * NEXT());
        ct_layer R = {.E = E, .sigma_y = 1.0, .Hstar = 10.0, .l0 = sum, .h0 = 1.0};
        assert_int_equal(ct_bundle_from_rods(&b, &R, n, tops, areas), CT_OK);
        double Wc, uy;
        assert_int_equal(ct_critical_energy(b, &Wc, &uy), CT_OK);
        double Vs[NV];
        for (int v = 0; v < NV; v++) /* 1.01 to 1e4 times V*_c, below a crushed layer */
            Vs[v] = sqrt(Wc * pow(10.0, 0.005 + 4.0 * NEXT()) / (R.l0 * R.E * R.h0));
        ct_sweep_row c[NV * IMP], r[NV * IMP];
        ct_sweep_spec spec = {.V_star = Vs, .nvel = NV, .impacts = imp, .path = CT_PATH_CURVE};
        ct_impact_opts_default(&spec.opts);
        assert_int_equal(ct_sweep(b, &spec, c), CT_OK);
        spec.path = CT_PATH_RODS;
        assert_int_equal(ct_sweep(b, &spec, r), CT_OK);
        for (int q = 0; q < NV * imp; q++) {
            if (r[q].status != c[q].status)
                fail_msg("set %d (%zu rods, E %g), V* %g impact %ld: rods %d (%s), curve %d (%s)",
                         set, n, R.E, r[q].V_star, r[q].impact, r[q].status, r[q].message,
                         c[q].status, c[q].message);
            if (c[q].status) { /* only a crushed layer, the same on both */
                assert_true(c[q].status == CT_ERANGE || c[q].status == CT_ESKIPPED);
                continue;
            }
            assert_int_equal(r[q].r.elastic, c[q].r.elastic);
            assert_rel(r[q].r.u_max, c[q].r.u_max, 1e-13);
            /* the release point of an earlier maximum: u_max's rounding, not its own */
            assert_true(fabs(r[q].r.u_contact - c[q].r.u_contact) <= 1e-13 * c[q].r.u_max);
            if (!(fabs(r[q].r.e - c[q].r.e) <= 1e-13 * c[q].r.e + c[q].r.e_rounding))
                fail_msg("set %d, V* %g impact %ld: e %.17g (rods) vs %.17g (curve)", set,
                         r[q].V_star, r[q].impact, r[q].r.e, c[q].r.e);
            assert_rel(r[q].r.V_star_crit, c[q].r.V_star_crit, 1e-12);
        }
        ct_bundle_free(b);
    }
#undef NEXT
    free(tops);
    free(areas);
}

/* A repeated impact that crushes the layer names its own kinetic energy on every path. The rod
 * of rod_path_repeated_impacts (u_y = 1e-5 storing 5e-6, then F = 1) struck with W = 6:
 * u_1 = 1e-5 + (6 - 5e-6) = 6.000005, and impact 2 would reach u_1 + (6 - 5e-6) > H* = 10.
 * On the first curve that impact is solved at W + D(u_1) (the dissipation to the earlier
 * maximum), which its message must not call the impact's energy. */
static void crushing_repeated_impact_names_its_energy(void **state)
{
    (void)state;
    ct_layer L = {.E = 1e6, .sigma_y = 1.0, .Hstar = 10.0, .l0 = 1.0, .h0 = 10.0};
    const double top = 0.0, area = 1.0, W = 6.0, V = sqrt(W / (L.l0 * L.E * L.h0));
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 1, &top, &area), CT_OK);
    char want[64];
    snprintf(want, sizeof want, "impact energy %.6g reaches", V * V * L.l0 * L.E * L.h0);
    for (int q = 0; q < 4; q++) {
        const ct_sweep_path paths[] = {CT_PATH_CURVE, CT_PATH_RODS, CT_PATH_LEAN, CT_PATH_CURVE};
        int calls = 0;
        ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 2, .path = paths[q]};
        ct_impact_opts_default(&spec.opts);
        if (q == 3) { /* the state-carrying path */
            spec.observe = no_op_observer;
            spec.observe_ctx = &calls;
        }
        ct_sweep_row rows[2];
        assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
        assert_int_equal(rows[0].status, CT_OK);
        assert_rel(rows[0].r.u_max, 1e-5 + (W - 5e-6), 1e-14);
        assert_int_equal(rows[1].status, CT_ERANGE);
        if (!strstr(rows[1].message, want))
            fail_msg("path %d: \"%s\" does not say \"%s\"", q, rows[1].message, want);
    }
    ct_bundle_free(b);
}

/* Rods so stiff that almost nothing comes back, by hand: tops 0, 0.1, 0.2, areas 1, H* = 1
 * (lengths 1, 0.9, 0.8), sigma_y = 1, E = 1/eps_y, l0 = 3, h0 = 0.2. An impact of energy
 * W = 0.9 (V*^2 = W / (l0 E h0) = 1.5 / E) yields every rod: W = sum of E s L eps_y^2 / 2 +
 * sigma_y s (u - top - eps_y L) = 3 u - 0.3 - 1.35 eps_y, u_max = 0.4 + 0.45 eps_y. Each rod
 * gives back its elastic energy on the
 * plateau, E s L eps_y^2 / 2 = eps_y L / 2, together R = eps_y (1 + 0.9 + 0.8) / 2 =
 * 1.35 eps_y: e = sqrt(R / W) = sqrt(1.5 eps_y), 1.2e-8 at E = 1e16, 1.2e-10 at 1e20. Impact 2,
 * of the same energy, reloads the rods elastically (R again, every one re-yielding at U) and
 * drives them (0.9 - R) / 3 further, to u_max = 0.7: e the same, and its V*_c from that energy back
 * to U, sqrt(R / (l0 E h0)) = 1.5 / E (impact 1's: rod A's yield energy eps_y / 2, V*_c =
 * sqrt(1 / 1.2) / E). As the difference W_load - D, W_unload was 1e-16 of W_load and e wrong
 * (28 % at 1e16, 0 at 1e20, on the curve), and V*_c of impact 2, from the state's own closed
 * forms or curve, 10 % at 1e16 and 0 at 1e20 on every path: each path must give these to
 * 1e-12. The impact in time needs the unloading interval eps_y L (1e-16 of u_max) resolved: it
 * is refused, naming it; at E = 1e6 it is computed. */
static void stiff_rods_e_on_paper(void **state)
{
    (void)state;
    const double top[3] = {0.0, 0.1, 0.2}, area[3] = {1.0, 1.0, 1.0}, Es[] = {1e16, 1e20, 1e6};
    for (int q = 0; q < 3; q++) {
        const double E = Es[q], eps_y = 1.0 / E, V = sqrt(1.5 / E);
        ct_layer L = {.E = E, .sigma_y = 1.0, .Hstar = 1.0, .l0 = 3.0, .h0 = 0.2};
        ct_bundle *b;
        assert_int_equal(ct_bundle_from_rods(&b, &L, 3, top, area), CT_OK);
        /* the curve's fast path, the rod path, the lean curve, the state-carrying path */
        const ct_sweep_path paths[] = {CT_PATH_CURVE, CT_PATH_RODS, CT_PATH_LEAN, CT_PATH_CURVE};
        for (int k = 0; k < 4; k++) {
            int calls = 0;
            ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 2, .path = paths[k]};
            ct_impact_opts_default(&spec.opts);
            if (k == 3) {
                spec.observe = no_op_observer;
                spec.observe_ctx = &calls;
            }
            ct_sweep_row rows[2];
            assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
            for (int i = 0; i < 2; i++) {
                if (rows[i].status)
                    fail_msg("E %g, path %d, impact %d: %s", E, k, i + 1, rows[i].message);
                assert_false(rows[i].r.elastic);
                assert_rel(rows[i].r.u_max, i ? 0.7 : 0.4 + 0.45 * eps_y, 1e-12);
                assert_rel(rows[i].r.e, sqrt(1.5 * eps_y), 1e-12);
                assert_rel(rows[i].r.V_star_crit, i ? 1.5 / E : sqrt(1.0 / 1.2) / E, 1e-12);
            }
            if (k == 1 || k == 2)
                continue;
            spec.dynamics = 1; /* lean and rods: no curve for the motion */
            spec.path = CT_PATH_CURVE;
            assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
            if (q < 2) {
                assert_int_equal(rows[0].status, CT_ERANGE);
                assert_non_null(strstr(rows[0].message, "unloading interval"));
            } else {
                for (int i = 0; i < 2; i++) {
                    assert_int_equal(rows[i].status, CT_OK);
                    assert_true(fabs(rows[i].dyn.e_kinematic - sqrt(1.5 * eps_y)) <= 1e-12);
                }
            }
        }
        /* one impact through the library's own call */
        ct_impact_result r;
        assert_int_equal(ct_impact(b, 0.9, NULL, &r), CT_OK);
        assert_rel(r.e, sqrt(1.5 * eps_y), 1e-12);
        ct_bundle_free(b);
    }
}

/* V*_c of very stiff rods far from the plane: the Cantor prefractal of depth 73 (f_x = 1.5,
 * f_z = 1.3, H* = 10, l0 = h0 = 1) yields first at its tips, 4.8e-9 deep, whose elastic range
 * eps_y L = 1e-19 at E/sigma_y = 1e20 is 1/50 000 of an ulp of their depth: nothing else is
 * touched then, and V*_c^2 = E l_N (H* - h_N) eps_y^2 / 2 / (l0 E h0), l_N = 1.5^-73,
 * h_N = 1.3^-73 (long double here). From the positions on the curve, or the rods' strains at
 * the rounded yield point, V*_c was 3.5e-6 off on every path; at E/sigma_y = 1e16, 2.7e-11. */
static void stiff_tips_vstar_crit(void **state)
{
    (void)state;
    const double Es[] = {1e16, 1e20};
    for (int q = 0; q < 2; q++) {
        ct_params p = base();
        p.E = Es[q];
        ct_bundle *b;
        assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 73, INFINITY), CT_OK);
        const long double lN = powl(1.5L, -73.0L), hN = powl(1.3L, -73.0L), ey = 1.0L / p.E;
        const double want = (double)(sqrtl(lN * (10.0L - hN) / 2.0L) * ey);
        double Wc, uy;
        assert_int_equal(ct_critical_energy(b, &Wc, &uy), CT_OK);
        assert_rel(sqrt(Wc / p.E), want, 1e-13);
        const double V = 1e-8 / sqrt(p.E / 1e16);
        const ct_sweep_path paths[] = {CT_PATH_CURVE, CT_PATH_RODS, CT_PATH_LEAN, CT_PATH_CURVE};
        for (int k = 0; k < 4; k++) {
            int calls = 0;
            ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 1, .path = paths[k]};
            ct_impact_opts_default(&spec.opts);
            if (k == 3) {
                spec.observe = no_op_observer;
                spec.observe_ctx = &calls;
            }
            ct_sweep_row row;
            assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
            if (row.status)
                fail_msg("E %g, path %d: %s", p.E, k, row.message);
            assert_rel(row.r.V_star_crit, want, 1e-13);
        }
        ct_bundle_free(b);
    }
}

/* b planned for the speeds V (stage rods at `depth`, 1e-12 bound) and its sweep on `path`: one
 * impact per speed into rows. */
static ct_bundle *planned_sweep(const ct_params *p, const double *V, size_t n, int depth, int path,
                                ct_sweep_row *rows)
{
    ct_cantor_plan plan = {.params = *p,
                           .depth = depth,
                           .representation = CT_REP_STAGES,
                           .depth_tolerance = 1e-12,
                           .V_star = V,
                           .nvel = n,
                           .impacts = 1};
    ct_impact_opts_default(&plan.opts);
    ct_bundle *b;
    ct_plan_info info;
    if (ct_cantor_plan_build(&plan, &b, &info))
        fail_msg("plan: %s", ct_error_message());
    ct_sweep_spec spec = {.V_star = V, .nvel = n, .impacts = 1, .opts = plan.opts};
    spec.path = (ct_sweep_path)path;
    assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
    return b;
}

/* A speed far below V*_c (1e-17) is an elastic impact with e = 1 exactly: neither the depth
 * search nor the u_max solve may refuse it because its penetration is below the resolution of
 * u at shallow depths. Its u_max against the paper's series (Eq. 15: stage sums with
 * h_i << H*, exact here to about u/H*), on both sweep paths. */
static void tiny_speed_is_elastic_not_an_error(void **state)
{
    (void)state;
    ct_params p = base();
    const double V[] = {1e-17, 1e-12, 1e-3};
    for (int depth = CT_DEPTH_FRACTAL; depth <= CT_DEPTH_AUTO; depth++)
        for (int path = CT_PATH_CURVE; path <= CT_PATH_RODS; path++) {
            ct_sweep_row rows[3];
            ct_bundle *b = planned_sweep(&p, V, 3, depth, path, rows);
            for (int k = 0; k < 2; k++) {
                if (rows[k].status)
                    fail_msg("V* = %g: %s", V[k], rows[k].message);
                assert_true(rows[k].r.elastic && rows[k].r.e == 1.0);
                double W = V[k] * V[k] * ct_energy_scale(&p), um, e;
                assert_int_equal(ct_law_impact(&p, CT_LAW_SERIES, W, &um, &e), CT_OK);
                assert_rel(rows[k].r.u_max, um, 1e-8);
            }
            assert_int_equal(rows[2].status, CT_OK);
            assert_false(rows[2].r.elastic);
            ct_bundle_free(b);
        }
}

/* ct_sweep_blocks hands out the rows of ct_sweep, bit for bit and in order, for any block
 * size: 300 speeds in random order (some crushed: failed rows) x 3 impacts, with and without
 * the impacts in time, on the curve path (the sampled check chosen over all speeds: 64 rods x
 * 900 rows is beyond its budget at depth 63, segments) and the rod path, in skip mode; under
 * stop_on_error the first failure is returned after its block. */
typedef struct {
    ct_sweep_row *rows;
    size_t n, calls;
} collected;

static int collect(const ct_sweep_row *rows, size_t n, void *ctx)
{
    collected *c = ctx;
    memcpy(c->rows + c->n, rows, n * sizeof *rows);
    c->n += n;
    c->calls++;
    return 0;
}

static int stop_after_one(const ct_sweep_row *rows, size_t n, void *ctx)
{
    (void)rows, (void)n;
    return ++*(int *)ctx >= 1;
}

static void blocks_equal_the_whole_sweep(void **state)
{
    (void)state;
    ct_params p = base();
    enum { NV = 300, IMP = 3 };
    static double V[NV];
    uint64_t x = 12345;
    for (size_t v = 0; v < NV; v++) { /* a fixed pseudo-random order over 1e-5 .. 0.3 */
        x = x * 6364136223846793005ULL + 1442695040888963407ULL;
        V[v] = 1e-5 * pow(3e4, (double)(x >> 11) * 0x1p-53);
    }
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, 10, INFINITY), CT_OK);
    static ct_sweep_row whole[NV * IMP], got[NV * IMP];
    const size_t blocks[] = {1, 7, 64, NV, 1000};
    for (int path = CT_PATH_CURVE; path <= CT_PATH_RODS; path++)
        for (int dyn = 0; dyn <= (path == CT_PATH_CURVE); dyn++) {
            ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = IMP, .path = path};
            ct_impact_opts_default(&spec.opts);
            spec.opts.check = CT_CHECK_AUTO;
            spec.dynamics = dyn;
            assert_int_equal(ct_sweep(b, &spec, whole), CT_OK);
            size_t failed = 0, unchecked = 0;
            for (size_t k = 0; k < NV * IMP; k++) {
                failed += whole[k].status != CT_OK;
                unchecked += whole[k].status == CT_OK && isnan(whole[k].r.e_closed);
            }
            assert_true(failed > 0 && failed < NV * IMP / 2); /* crushed speeds */
            if (path == CT_PATH_CURVE)
                assert_true(unchecked > 0); /* the check sampled */
            for (size_t q = 0; q < sizeof blocks / sizeof *blocks; q++) {
                collected c = {got, 0, 0};
                assert_int_equal(ct_sweep_blocks(b, &spec, blocks[q], collect, &c), CT_OK);
                assert_int_equal(c.n, NV * IMP);
                assert_int_equal(c.calls, (NV + blocks[q] - 1) / blocks[q]);
                for (size_t k = 0; k < NV * IMP; k++) {
                    const ct_sweep_row *a = &whole[k], *g = &got[k];
                    const int ok = a->status == CT_OK; /* results, or a message: never both */
                    if (a->speed != g->speed || a->impact != g->impact || a->status != g->status ||
                        (ok && memcmp(&a->r, &g->r, sizeof a->r)) ||
                        (ok && dyn && memcmp(&a->dyn, &g->dyn, sizeof a->dyn)) ||
                        strcmp(a->message, g->message))
                        fail_msg("path %d, dynamics %d, block %zu: row %zu differs", path, dyn,
                                 blocks[q], k);
                }
            }
            /* stop_on_error: the first failure, after its block was handed out */
            spec.stop_on_error = 1;
            collected c = {got, 0, 0};
            assert_int_equal(ct_sweep_blocks(b, &spec, 16, collect, &c), CT_ERANGE);
            size_t first = 0;
            while (whole[first].status == CT_OK || whole[first].status == CT_ESKIPPED)
                first++;
            assert_true(c.n > first && c.n <= first + 16 * IMP);
            /* the caller stops */
            int calls = 0;
            spec.stop_on_error = 0;
            assert_int_equal(ct_sweep_blocks(b, &spec, 16, stop_after_one, &calls), CT_ESKIPPED);
            assert_int_equal(calls, 1);
        }
    ct_sweep_spec bad = {.V_star = V, .nvel = NV, .impacts = 1};
    ct_impact_opts_default(&bad.opts);
    assert_int_equal(ct_sweep_blocks(b, &bad, 0, collect, NULL), CT_EINVAL);
    bad.observe = no_op_observer;
    assert_int_equal(ct_sweep_blocks(b, &bad, 8, collect, NULL), CT_EINVAL);
    ct_bundle_free(b);
}

/* A caller's callback that gives the bundle more threads after the first block: the impacts
 * in time of the next blocks then run on a larger team (the workspace's forks grow). */
typedef struct {
    collected c;
    ct_bundle *b;
} growing;

static int collect_and_grow(const ct_sweep_row *rows, size_t n, void *ctx)
{
    growing *g = ctx;
    ct_bundle_set_threads(g->b, 4);
    return collect(rows, n, &g->c);
}

/* Blocks large enough for the impacts in time to be shared among threads (12288 rows and
 * more), run on 2 threads and then, from the second block, on 4: every row bit for bit the
 * rows of the whole sweep on one thread. */
static void dynamics_blocks_on_threads(void **state)
{
    (void)state;
    ct_params p = base();
    enum { NV = 30000 };
    double *V = malloc(NV * sizeof *V);
    ct_sweep_row *whole = malloc(NV * sizeof *whole), *got = malloc(NV * sizeof *got);
    assert_non_null(V);
    assert_non_null(whole);
    assert_non_null(got);
    for (size_t v = 0; v < NV; v++)
        V[v] = 1e-4 * pow(100.0, (double)v / (NV - 1));
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 30, INFINITY), CT_OK);
    ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = 1, .dynamics = 1};
    ct_impact_opts_default(&spec.opts);
    spec.opts.check = CT_CHECK_NONE;
    ct_bundle_set_threads(b, 1);
    assert_int_equal(ct_sweep(b, &spec, whole), CT_OK);
    ct_bundle_set_threads(b, 2);
    growing g = {{got, 0, 0}, b};
    assert_int_equal(ct_sweep_blocks(b, &spec, 13000, collect_and_grow, &g), CT_OK);
    assert_int_equal(g.c.n, NV);
    assert_int_equal(g.c.calls, 3);
    for (size_t k = 0; k < NV; k++) {
        assert_int_equal(whole[k].status, CT_OK);
        if (got[k].status != CT_OK || memcmp(&whole[k].r, &got[k].r, sizeof whole[k].r) ||
            memcmp(&whole[k].dyn, &got[k].dyn, sizeof whole[k].dyn))
            fail_msg("row %zu differs", k);
    }
    ct_bundle_free(b);
    free(V);
    free(whole);
    free(got);
}

/* A row holds its results or its message in the same bytes (cantact.h): no room for the
 * results beside a full message; a row that succeeded says "", a failed one its message, and
 * a row not run the impact that stopped it, on both paths, with the impacts in time, whatever
 * the rows held before and by ct_sweep_blocks alike; a row copied keeps its message. */
static void row_holds_results_or_its_message(void **state)
{
    (void)state;
    assert_true(sizeof(ct_sweep_row) <
                offsetof(ct_sweep_row, message) + 240 + sizeof(ct_impact_result));
    assert_int_equal(offsetof(ct_sweep_row, message) + 8, offsetof(ct_sweep_row, r));
    assert_true(offsetof(ct_sweep_row, dyn) + sizeof(ct_dynamics) <=
                offsetof(ct_sweep_row, message) + 240);
    ct_params p = base();
    const double V[3] = {1e-3, 50.0, 2e-3};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 30, INFINITY), CT_OK);
    for (int path = CT_PATH_CURVE; path <= CT_PATH_RODS; path++)
        for (int dyn = 0; dyn <= (path == CT_PATH_CURVE); dyn++) {
            ct_sweep_spec spec = {.V_star = V, .nvel = 3, .impacts = 2, .path = path};
            ct_impact_opts_default(&spec.opts);
            spec.dynamics = dyn;
            ct_sweep_row rows[6], got[6];
            memset(rows, 'x', sizeof rows); /* what the rows held before: no NUL anywhere */
            assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
            collected c = {got, 0, 0};
            memset(got, 'x', sizeof got);
            assert_int_equal(ct_sweep_blocks(b, &spec, 1, collect, &c), CT_OK);
            for (int k = 0; k < 6; k++) {
                const ct_sweep_row *row = &rows[k], *g = &got[k];
                assert_int_equal(row->status,
                                 (k / 2 == 1) ? (k == 2 ? CT_ERANGE : CT_ESKIPPED) : CT_OK);
                assert_non_null(memchr(row->message, '\0', sizeof row->message));
                assert_string_equal(row->message, g->message);
                if (row->status == CT_OK) {
                    assert_string_equal(row->message, "");
                    assert_true(row->r.e > 0.0 && row->r.e < 1.0 && !row->r.elastic);
                    assert_true(!dyn || (row->dyn.e_kinematic > 0.0 && row->dyn.t_contact > 0.0));
                }
            }
            assert_string_equal(
                rows[2].message,
                "impact energy 1.25e+06 reaches u_max >= H* = 10 (the layer would be "
                "crushed, strains >= 1): outside the model; lower the speed or raise H");
            assert_string_equal(rows[3].message, "not run: impact 1 of V* = 50 failed");
            ct_sweep_row copy = rows[3];
            memset(&rows[3], 'x', sizeof rows[3]);
            assert_string_equal(copy.message, "not run: impact 1 of V* = 50 failed");
            /* rows that held failures, reused by a sweep whose impacts all succeed */
            const double slow[3] = {1e-3, 3e-3, 2e-3};
            spec.V_star = slow;
            assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
            for (int k = 0; k < 6; k++)
                assert_true(rows[k].status == CT_OK && rows[k].message[0] == '\0');
        }
    ct_bundle_free(b);
}

/* Far below V*_c, down to the smallest energy a double holds normally (V* = 1e-150: W ~ 1e-297
 * in these units), the impact is elastic and computed: u_max against a bisection of the rods'
 * closed-form work (no curve, no quadratic) and e = 1 exactly. At V* = 1e-130 the curve's
 * inverse squared P ~ 1e-206 (underflow: |W(u) - W| / W = 0.66). A subnormal energy is refused. */
static void tiny_energies_down_to_the_smallest_double(void **state)
{
    (void)state;
    ct_params p = base();
    const double V[] = {1e-100, 1e-130, 1e-150};
    for (int path = CT_PATH_CURVE; path <= CT_PATH_RODS; path++) {
        ct_sweep_row rows[3];
        ct_bundle *b = planned_sweep(&p, V, 3, CT_DEPTH_AUTO, path, rows);
        for (int k = 0; k < 3; k++) {
            if (rows[k].status)
                fail_msg("path %d, V* = %g: %s", path, V[k], rows[k].message);
            assert_true(rows[k].r.elastic && rows[k].r.e == 1.0 && rows[k].r.e_closed == 1.0);
            /* u_max by bisection on the doubles' bit patterns (ordered like the positive
             * doubles) of the rods' closed-form work: no curve, no quadratic */
            const double W = V[k] * V[k] * ct_energy_scale(&p), x0 = ct_bundle_first_contact(b);
            uint64_t lo, hi;
            double d = x0;
            memcpy(&lo, &d, 8);
            d = ct_bundle_layer(b)->Hstar;
            memcpy(&hi, &d, 8);
            while (hi - lo > 1) {
                uint64_t mid = lo + (hi - lo) / 2;
                memcpy(&d, &mid, 8);
                if (ct_bundle_work(b, x0, d) < W)
                    lo = mid;
                else
                    hi = mid;
            }
            memcpy(&d, &hi, 8);
            assert_rel(rows[k].r.u_max, d, 4.0 * DBL_EPSILON);
        }
        const double sub = 1e-160; /* W ~ 1e-317: subnormal */
        ct_sweep_spec bad = {.V_star = &sub, .nvel = 1, .impacts = 1};
        ct_impact_opts_default(&bad.opts);
        bad.path = (ct_sweep_path)path;
        assert_int_equal(ct_sweep(b, &bad, rows), CT_EINVAL);
        assert_non_null(strstr(ct_error_message(), "smallest normal double"));
        ct_bundle_free(b);
    }
}

/* An elastic impact whose penetration is below the resolution of u (rods whose first contact
 * is at u = 1, not 0: a penetration of 1e-20 rounds to nothing) is still e = 1 exactly: there
 * is no dissipation to resolve. One rod, top 1, area 1, L = H* - 1 = 9, E = 500: u_max =
 * 1 + sqrt(2 W L / E) = 1 + 6e-21, which is 1 in double precision (to the 16 ulps of u the
 * solves resolve). Both sweep paths and ct_impact agree. */
static void tiny_speed_on_offset_rods_is_elastic(void **state)
{
    (void)state;
    ct_layer L = {.E = 500.0, .sigma_y = 1.0, .Hstar = 10.0, .l0 = 1.0, .h0 = 1.0};
    const double top[1] = {1.0}, area[1] = {1.0};
    const double W = 1e-39, V = sqrt(W / 500.0);
    assert_true(sqrt(2.0 * W * 9.0 / 500.0) < 0.5 * DBL_EPSILON); /* below the resolution */
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 1, top, area), CT_OK);
    for (int path = CT_PATH_CURVE; path <= CT_PATH_RODS; path++) {
        ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 2, .path = (ct_sweep_path)path};
        ct_impact_opts_default(&spec.opts);
        ct_sweep_row rows[2];
        assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
        for (int k = 0; k < 2; k++) {
            if (rows[k].status)
                fail_msg("path %d, impact %d: %s", path, k + 1, rows[k].message);
            assert_true(rows[k].r.elastic && rows[k].r.e == 1.0);
            /* the root, 1 + 6e-21, to the resolution of u the solve claims (16 ulps) */
            if (!(fabs(rows[k].r.u_max - 1.0) <= 16.0 * DBL_EPSILON))
                fail_msg("path %d: u_max - 1 = %g", path, rows[k].r.u_max - 1.0);
        }
    }
    ct_impact_result r;
    assert_int_equal(ct_impact(b, W, NULL, &r), CT_OK);
    assert_true(r.elastic && r.e == 1.0 && fabs(r.u_max - 1.0) <= 16.0 * DBL_EPSILON);
    ct_bundle_free(b);
}

/* A layer 1e-9 thick over stages that barely shrink (fz = 1 + 3e-8), 200 stages: where a rod
 * so stiff has just touched at u_max, one ulp of u moves W by P ulp(u), and e is known only to
 * that. The fuzz target found the rod path 2.5e-6 from the curve path with a stated rounding
 * of 2.4e-9 (read before its release point was set, and blind to P(u_max)). Against a long
 * double solve of the same rods, both paths now state a bound that holds. */
static void stiff_rod_at_contact_states_its_rounding(void **state)
{
    (void)state;
    const ct_params p = {.fx = 999.99999999999989,
                         .fz = 1.0000000295721865,
                         .l0 = 1.0,
                         .h0 = 1.0,
                         .Hstar = 1.0000000010502346,
                         .E = 36.217722947291264,
                         .sigma_y = 1.0};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 199, INFINITY), CT_OK);
    const size_t n = ct_bundle_size(b);
    const double V = 1e-9;
    const long double W = (long double)V * V * ct_energy_scale(&p), ey = 1.0L / p.E;
    long double *t = malloc(3 * n * sizeof *t), *L = t + n, *A = L + n;
    assert_non_null(t);
    for (size_t k = 0; k < n; k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        t[k] = r.top, L[k] = r.length, A[k] = r.area;
    }
    long double lo = 0.0L, hi = p.Hstar, wu = 0.0L; /* bisection on the closed forms */
    for (int it = 0; it < 300; it++) {
        long double u = (lo + hi) / 2, w = 0.0L;
        for (size_t k = 0; k < n; k++) {
            long double e = (u - t[k]) / L[k];
            if (e > 0.0L)
                w += e <= ey ? p.E * A[k] * L[k] * e * e / 2
                             : p.E * A[k] * L[k] * (ey * e - ey * ey / 2);
        }
        if (w < W)
            lo = u;
        else
            hi = u;
    }
    for (size_t k = 0; k < n; k++) {
        long double e = (lo - t[k]) / L[k], m = e < ey ? e : ey;
        if (e > 0.0L)
            wu += p.E * A[k] * L[k] * m * m / 2;
    }
    const double e_ref = (double)sqrtl(wu / W);
    for (int path = CT_PATH_CURVE; path <= CT_PATH_RODS; path++) {
        ct_sweep_spec s = {.V_star = &V, .nvel = 1, .impacts = 1, .path = (ct_sweep_path)path};
        ct_impact_opts_default(&s.opts);
        ct_sweep_row row;
        assert_int_equal(ct_sweep(b, &s, &row), CT_OK);
        assert_int_equal(row.status, CT_OK);
        if (!(fabs(row.r.e - e_ref) <= row.r.e_rounding))
            fail_msg("path %d: e = %.17g, the long double solve %.17g: off by %.3g, beyond the "
                     "stated rounding %.3g",
                     path, row.r.e, e_ref, fabs(row.r.e - e_ref), row.r.e_rounding);
        assert_true(row.r.e_rounding < 1e-3); /* an honest bound, not a shrug */
    }
    free(t);
    ct_bundle_free(b);
}

/* The same bits from the lean curve as from the full one (CT_PATH_LEAN: sorted events and
 * checkpoints, docs/library.md) for every field of every row: Cantor stages (long runs of
 * identical rods, ties across blocks), segments, scattered tops, quantised tops with many
 * equal ones of different areas (ties in the events' order), -0 and +0, runs across the
 * 2048-rod blocks, a plastic state, three impacts per speed, the check on every row. */
static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static void lean_curve_equals_full_curve_bit_for_bit(void **state)
{
    (void)state;
    ct_params p = base();
    enum { NV = 10, IMP = 3, NB = 7, NR = 5000 };
    const double V[NV] = {1e-6, 3e-5, 1e-4, 2e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 60.0};
    ct_bundle *b[NB];
    assert_int_equal(ct_cantor_bundle(&b[0], &p, CT_REP_STAGES, 147, INFINITY), CT_OK);
    assert_int_equal(ct_cantor_bundle(&b[1], &p, CT_REP_SEGMENTS, 12, INFINITY), CT_OK);
    static double top[NR], area[NR];
    ct_layer L = {.E = 500.0, .sigma_y = 1.0, .Hstar = 10.0, .l0 = 1.0, .h0 = 1.0};
    for (int k = 0; k < NR; k++) { /* scattered */
        top[k] = 2.0 * fmod(0.618033988749895 * k, 1.0);
        area[k] = 1.0 / NR;
    }
    assert_int_equal(ct_bundle_from_rods(&b[2], &L, NR, top, area), CT_OK);
    for (int k = 0; k < NR; k++) { /* quantised: 13 levels, runs of 3, -0 beside +0 */
        top[k] = (k / 3 % 13) * 0.125;
        if (top[k] == 0.0 && k % 2)
            top[k] = -0.0;
        area[k] = (1.0 + (k / 3 % 7)) / (4.0 * NR);
    }
    assert_int_equal(ct_bundle_from_rods(&b[3], &L, NR, top, area), CT_OK);
    assert_int_equal(ct_bundle_clone(&b[4], b[3]), CT_OK);
    ct_bundle_advance(b[4], 0.4);  /* a plastic state: contacts and lengths of its own */
    for (int k = 0; k < NR; k++) { /* one long run across blocks, then scattered */
        top[k] = k < 3000 ? 0.5 : fmod(0.7548776662466927 * k, 1.0);
        area[k] = 1.0 / NR;
    }
    assert_int_equal(ct_bundle_from_rods(&b[5], &L, NR, top, area), CT_OK);
    /* a long rod at 0 that yields last (at 1) and 200 short ones above it that yield first:
     * the release point is the long rod's contact, from a checkpoint far ahead */
    ct_surface *sf;
    assert_int_equal(ct_surface_new(&sf, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(sf, "material", "E", "100", "test"), CT_OK);
    assert_int_equal(ct_surface_set(sf, "material", "sigma_y", "1", "test"), CT_OK);
    double len[201];
    for (int k = 0; k < 201; k++) {
        top[k] = k ? 0.01 + 0.002 * (k - 1) : 0.0;
        area[k] = k ? 1.0 / 200 : 1.0;
        len[k] = k ? 1.0 : 100.0;
    }
    assert_int_equal(ct_surface_set_rods(sf, 201, top, area, len), CT_OK);
    assert_int_equal(ct_surface_check(sf, "test"), CT_OK);
    assert_int_equal(ct_surface_prepare(sf, NULL), CT_OK);
    ct_build_request req = {.V_star = V, .nvel = 1, .impacts = 1};
    ct_impact_opts_default(&req.opts);
    assert_int_equal(ct_surface_build(sf, &req, &b[6], NULL), CT_OK);
    ct_surface_free(sf);
    static ct_sweep_row c[NV * IMP], l[NV * IMP];
    for (int k = 0; k < NB; k++) {
        ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = IMP};
        ct_impact_opts_default(&spec.opts);
        spec.opts.check = CT_CHECK_ALL;
        spec.path = CT_PATH_CURVE;
        assert_int_equal(ct_sweep(b[k], &spec, c), CT_OK);
        spec.path = CT_PATH_LEAN;
        assert_int_equal(ct_sweep(b[k], &spec, l), CT_OK);
        int ok = 0;
        for (int q = 0; q < NV * IMP; q++) {
            assert_int_equal(l[q].status, c[q].status);
            ok += c[q].status == CT_OK;
            const ct_impact_result *x = &c[q].r, *y = &l[q].r;
            const double fx[] = {x->kinetic_energy,  x->V_star,     x->u_contact, x->u_max,
                                 x->u_release,       x->W_load,     x->W_unload,  x->W_load_closed,
                                 x->W_unload_closed, x->e,          x->e_closed,  x->quad_error,
                                 x->e_rounding,      x->V_star_crit};
            const double fy[] = {y->kinetic_energy,  y->V_star,     y->u_contact, y->u_max,
                                 y->u_release,       y->W_load,     y->W_unload,  y->W_load_closed,
                                 y->W_unload_closed, y->e,          y->e_closed,  y->quad_error,
                                 y->e_rounding,      y->V_star_crit};
            for (size_t f = 0; f < sizeof fx / sizeof fx[0]; f++)
                if (!same_bits(fx[f], fy[f]))
                    fail_msg("bundle %d, row %d, field %zu: full %.17g, lean %.17g", k, q, f, fx[f],
                             fy[f]);
            assert_int_equal(x->elastic, y->elastic);
        }
        assert_true(ok >= 2 * IMP); /* rows that ran, not only failures */
        ct_bundle_free(b[k]);
    }
}

/* A lean curve large enough for its sort and its sweep to take threads (its events sorted by
 * buckets on the threads; its yields made whole on one thread while another sweeps): every
 * field of every row the same bits for 1, 2 and 3 threads and as the full curve's. Scattered
 * tops with runs of equal ones (ties across the sort's buckets and the sweep's parts), a
 * plastic state (contacts of their own), three impacts, the check on every row. */
static void large_lean_curve_on_threads(void **state)
{
    (void)state;
    enum { NV = 6, IMP = 3, NR = 300000 };
    const double V[NV] = {3e-5, 2e-4, 1e-3, 1e-2, 0.1, 3.0};
    double *top = malloc(NR * sizeof *top), *area = malloc(NR * sizeof *area);
    assert_non_null(top);
    assert_non_null(area);
    ct_layer L = {.E = 500.0, .sigma_y = 1.0, .Hstar = 10.0, .l0 = 1.0, .h0 = 1.0};
    for (int k = 0; k < NR; k++) {
        const double f = fmod(0.7548776662466927 * k, 1.0);
        top[k] = k % 5 ? f * f : (k / 5 % 97) / 97.0; /* every fifth on one of 97 levels */
        area[k] = (1.0 + k % 3) / (2.0 * NR);
    }
    ct_bundle *b[2];
    assert_int_equal(ct_bundle_from_rods(&b[0], &L, NR, top, area), CT_OK);
    assert_int_equal(ct_bundle_clone(&b[1], b[0]), CT_OK);
    ct_bundle_advance(b[1], 0.3);
    free(top);
    free(area);
    static ct_sweep_row c[NV * IMP], l[NV * IMP];
    for (int k = 0; k < 2; k++) {
        ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = IMP};
        ct_impact_opts_default(&spec.opts);
        spec.opts.check = CT_CHECK_ALL;
        spec.path = CT_PATH_CURVE;
        assert_int_equal(ct_bundle_set_threads(b[k], 1), 1);
        assert_int_equal(ct_sweep(b[k], &spec, c), CT_OK);
        for (int threads = 1; threads <= 3; threads++) {
            assert_int_equal(ct_bundle_set_threads(b[k], threads), threads);
            spec.path = CT_PATH_LEAN;
            assert_int_equal(ct_sweep(b[k], &spec, l), CT_OK);
            int ok = 0;
            for (int q = 0; q < NV * IMP; q++) {
                assert_int_equal(l[q].status, c[q].status);
                ok += c[q].status == CT_OK;
                const ct_impact_result *x = &c[q].r, *y = &l[q].r;
                const double fx[] = {x->u_contact,       x->u_max,      x->u_release,
                                     x->W_load,          x->W_unload,   x->W_load_closed,
                                     x->W_unload_closed, x->e,          x->e_closed,
                                     x->quad_error,      x->e_rounding, x->V_star_crit};
                const double fy[] = {y->u_contact,       y->u_max,      y->u_release,
                                     y->W_load,          y->W_unload,   y->W_load_closed,
                                     y->W_unload_closed, y->e,          y->e_closed,
                                     y->quad_error,      y->e_rounding, y->V_star_crit};
                for (size_t f = 0; f < sizeof fx / sizeof fx[0]; f++)
                    if (!same_bits(fx[f], fy[f]))
                        fail_msg("bundle %d, %d threads, row %d, field %zu: full %.17g, lean "
                                 "%.17g",
                                 k, threads, q, f, fx[f], fy[f]);
            }
            assert_true(ok >= 3 * IMP); /* rows that ran, not only failures */
        }
        ct_bundle_free(b[k]);
    }
}

/* ---- stopping a sweep (cantact.h: the spec's interrupt) ---- */

/* Every path stops at its first check when the flag is already set: CT_EINTR, "interrupted". */
static void interrupt_set_stops_every_path(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, 8, INFINITY), CT_OK);
    const double V[3] = {1e-4, 1e-3, 1e-2};
    static ct_sweep_row rows[3 * 2];
    const volatile int stop = 1;
    for (int path = CT_PATH_AUTO; path <= CT_PATH_LEAN; path++)
        for (int variant = 0; variant < 3; variant++) {
            ct_sweep_spec spec = {.V_star = V, .nvel = 3, .impacts = 2, .path = path};
            ct_impact_opts_default(&spec.opts);
            spec.dynamics = variant == 1 && path != CT_PATH_RODS && path != CT_PATH_LEAN;
            if (variant == 2) { /* the general path: a composite rule carries every state */
                spec.opts.rule = CT_QUAD_GAUSS;
                spec.path = CT_PATH_CURVE;
            }
            assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
            spec.interrupt = &stop;
            assert_int_equal(ct_sweep(b, &spec, rows), CT_EINTR);
            assert_string_equal(ct_error_message(), "interrupted");
            assert_int_equal(ct_sweep_blocks(b, &spec, 1, collect, &(collected){rows, 0, 0}),
                             CT_EINTR);
        }
    ct_bundle_free(b);
}

/* Progress of a sweep whose closed-form check is one long batch over many rods: reported in
 * slices of the batch (more than one call before the last, the count rising), and the rows
 * the same bits as without progress; a callback that sets the flag at its first call stops
 * the batch there. */
typedef struct {
    size_t calls, last, total;
    int rising;
    volatile int *stop_at_first;
    double first_at; /* when the first call came [s, CLOCK_MONOTONIC] */
} progress_log;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void log_progress(size_t done, size_t total, void *ctx)
{
    progress_log *g = ctx;
    g->rising &= done > g->last && done <= total;
    g->last = done;
    g->total = total;
    if (!g->calls++)
        g->first_at = now();
    if (g->stop_at_first)
        *g->stop_at_first = 1;
}

static void progress_in_slices_changes_no_bit(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, 16, INFINITY), CT_OK);
    assert_true(ct_bundle_size(b) > 100000); /* slices of 512 impacts: 512 and 588 */
    enum { NV = 1100 };
    static double V[NV];
    for (size_t v = 0; v < NV; v++)
        V[v] = 1e-4 * pow(1e2, (double)v / (NV - 1));
    static ct_sweep_row plain[NV], seen[NV];
    for (int threads = 1; threads <= 2; threads++) {
        ct_bundle_set_threads(b, threads);
        ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = 1, .path = CT_PATH_CURVE};
        ct_impact_opts_default(&spec.opts); /* the check of every row: one batch of NV impacts */
        assert_int_equal(ct_sweep(b, &spec, plain), CT_OK);
        progress_log g = {.rising = 1};
        spec.progress = log_progress;
        spec.progress_ctx = &g;
        const double start = now();
        assert_int_equal(ct_sweep(b, &spec, seen), CT_OK);
        const double took = now() - start;
        assert_true(g.calls >= 2); /* the batch in slices */
        /* nothing reported before the first slice: the batch is nearly all of the sweep's time,
         * its first of 2 or 3 slices over a quarter of it */
        if (!(g.first_at - start > 0.25 * took))
            fail_msg("%d threads: first progress after %.3f of %.3f s", threads, g.first_at - start,
                     took);
        assert_true(g.rising);
        assert_int_equal(g.last, NV);
        assert_int_equal(g.total, NV);
        for (size_t k = 0; k < NV; k++) {
            assert_int_equal(plain[k].status, CT_OK);
            assert_int_equal(seen[k].status, CT_OK);
            assert_false(isnan(seen[k].r.e_closed));
            if (memcmp(&plain[k].r, &seen[k].r, sizeof plain[k].r))
                fail_msg("%d threads: row %zu differs with progress", threads, k);
        }
        volatile int stop = 0;
        progress_log h = {.rising = 1, .stop_at_first = &stop};
        spec.progress_ctx = &h;
        spec.interrupt = &stop;
        assert_int_equal(ct_sweep(b, &spec, seen), CT_EINTR);
        assert_int_equal(h.calls, 1); /* stopped in the batch, before its next slice */
        assert_true(h.last < NV);
    }
    ct_bundle_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(three_rods_on_paper),
        cmocka_unit_test(sweep_equals_one_by_one),
        cmocka_unit_test(vstar_crit_does_not_depend_on_the_other_speeds),
        cmocka_unit_test(pruning_changes_no_reported_number),
        cmocka_unit_test(crushing_speed_is_one_row),
        cmocka_unit_test(rod_path_equals_curve_path),
        cmocka_unit_test(two_rods_five_impacts_on_paper),
        cmocka_unit_test(rod_path_repeated_impacts),
        cmocka_unit_test(crushing_repeated_impact_names_its_energy),
        cmocka_unit_test(stiff_rods_e_on_paper),
        cmocka_unit_test(stiff_tips_vstar_crit),
        cmocka_unit_test(tiny_speed_is_elastic_not_an_error),
        cmocka_unit_test(blocks_equal_the_whole_sweep),
        cmocka_unit_test(dynamics_blocks_on_threads),
        cmocka_unit_test(row_holds_results_or_its_message),
        cmocka_unit_test(tiny_energies_down_to_the_smallest_double),
        cmocka_unit_test(tiny_speed_on_offset_rods_is_elastic),
        cmocka_unit_test(stiff_rod_at_contact_states_its_rounding),
        cmocka_unit_test(lean_curve_equals_full_curve_bit_for_bit),
        cmocka_unit_test(large_lean_curve_on_threads),
        cmocka_unit_test(interrupt_set_stops_every_path),
        cmocka_unit_test(progress_in_slices_changes_no_bit),
    };
    return cmocka_run_group_tests_name("sweep", tests, NULL, NULL);
}
