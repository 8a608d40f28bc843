/* Impacts: e against an independent solution (closed-form rod energies summed in long
 * double, u_max by GSL's Brent solver), the critical velocity, monotonicity in V*,
 * repeated impacts, the crushed layer, composite rules. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <string.h>

#include "assert_rel.h"
#include "cantact.h"
#include "internal.h"

static ct_params base(void)
{
    ct_params p = {
        .fx = 1.5, .fz = 1.3, .l0 = 1.0, .h0 = 1.0, .Hstar = 10.0, .E = 500.0, .sigma_y = 1.0};
    return p;
}

/* ---- an independent virgin-surface model, straight from docs/model.md §2-3 ---- */
typedef struct {
    ct_params p;
    long N;
} ref_model;

static long double ref_strain(const ref_model *m, long i, long double u, long double *s,
                              long double *L)
{
    long double fx = m->p.fx, fz = m->p.fz;
    long double l = m->p.l0 * powl(fx, -i), h = m->p.h0 * powl(fz, -i);
    *s = i < m->N ? l * (1.0L - 1.0L / fx) : l;
    *L = m->p.Hstar - h;
    return (u - h) / *L;
}

static double ref_work(double u, void *ctx)
{
    const ref_model *m = ctx;
    long double eps_y = (long double)m->p.sigma_y / m->p.E, W = 0.0L;
    for (long i = 0; i <= m->N; i++) {
        long double s, L, e = ref_strain(m, i, u, &s, &L);
        if (e <= 0)
            continue;
        W += m->p.E * s * L * (e <= eps_y ? e * e / 2 : eps_y * e - eps_y * eps_y / 2);
    }
    return (double)W;
}

static double ref_recoverable(const ref_model *m, double umax)
{
    long double eps_y = (long double)m->p.sigma_y / m->p.E, W = 0.0L;
    for (long i = 0; i <= m->N; i++) {
        long double s, L, e = ref_strain(m, i, umax, &s, &L);
        if (e <= 0)
            continue;
        long double d = e < eps_y ? e : eps_y;
        W += m->p.E * s * L * d * d / 2;
    }
    return (double)W;
}

typedef struct {
    ref_model *m;
    double W;
} root_ctx;

static double residual(double u, void *ctx)
{
    root_ctx *c = ctx;
    return ref_work(u, c->m) - c->W;
}

static double ref_umax(ref_model *m, double W)
{
    root_ctx c = {m, W};
    gsl_function F = {residual, &c};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_root_fsolver_set(s, &F, 0.0, m->p.Hstar * 0.999999);
    double u = 0.0;
    for (int it = 0; it < 500; it++) {
        gsl_root_fsolver_iterate(s);
        u = gsl_root_fsolver_root(s);
        double lo = gsl_root_fsolver_x_lower(s), hi = gsl_root_fsolver_x_upper(s);
        if (gsl_root_test_interval(lo, hi, 0.0, 1e-15) == GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(s);
    return u;
}

static void e_against_independent_solution(void **state)
{
    (void)state;
    ct_params p = base();
    long depths[] = {0, 1, 5, 20};
    double Vs[] = {3e-4, 2e-3, 2e-2};
    for (int d = 0; d < 4; d++)
        for (int v = 0; v < 3; v++) {
            ref_model m = {p, depths[d]};
            double W = Vs[v] * Vs[v] * ct_energy_scale(&p);
            ct_bundle *b;
            assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, depths[d], INFINITY), CT_OK);
            ct_impact_result r;
            assert_int_equal(ct_impact(b, W, NULL, &r), CT_OK);
            double umax = ref_umax(&m, W);
            assert_rel(r.u_max, umax, 1e-12);
            double e_ref = sqrt(ref_recoverable(&m, umax) / W);
            /* P(u) is evaluated from u - top, which loses log10(top / (u - top)) digits
             * near contact (up to 3 here): hence 1e-12 rather than 1e-15 */
            assert_rel(r.e_closed, e_ref, 1e-11);
            assert_rel(r.e, e_ref, 1e-11);
            assert_true(r.quad_error <= 1e-12);
            assert_rel(r.W_load, W, 1e-12);
            ct_bundle_free(b);
        }
}

static void single_rod_closed_form(void **state)
{
    (void)state;
    /* depth 0: one rod, top h0, length H* - h0, area l0. Past yield,
     * W = E s L (eps_y eps - eps_y^2/2) gives eps; e^2 = (eps_y^2/2) / (eps_y eps - eps_y^2/2). */
    ct_params p = base();
    double eps_y = p.sigma_y / p.E, L = p.Hstar - p.h0, s = p.l0;
    double W = 4.0 * p.E * s * L * eps_y * eps_y / 2; /* four times the elastic capacity */
    double eps = (W / (p.E * s * L) + eps_y * eps_y / 2) / eps_y;
    double e = sqrt(eps_y * eps_y / 2 / (eps_y * eps - eps_y * eps_y / 2));
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 0, INFINITY), CT_OK);
    ct_impact_result r;
    assert_int_equal(ct_impact(b, W, NULL, &r), CT_OK);
    assert_rel(r.e, 0.5, 1e-14);
    assert_rel(r.e, e, 1e-14);
    assert_rel(r.u_max, p.h0 + eps * L, 1e-14);
    assert_rel(r.u_release, p.h0 + (eps - eps_y) * L, 1e-13);
    ct_bundle_free(b);
}

/* The closed-form check fails a wrong e: one rod past yield (e = 0.5 in closed form) gives a
 * result that passes; the same result with e off by 1e-9 (beyond CT_CHECK_E_BOUND + 2
 * e_rounding) fails with CT_ENOCONV, by 1e-13 passes; unchecked results and composite rules
 * (whose difference is their quadrature error, reported, not a fault) pass. */
static void check_fails_a_wrong_e(void **state)
{
    (void)state;
    ct_params p = base();
    double eps_y = p.sigma_y / p.E, W = 4.0 * p.E * p.l0 * (p.Hstar - p.h0) * eps_y * eps_y / 2;
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 0, INFINITY), CT_OK);
    ct_impact_opts o;
    ct_impact_opts_default(&o);
    ct_impact_result r;
    assert_int_equal(ct_impact(b, W, &o, &r), CT_OK);
    assert_rel(r.e_closed, 0.5, 1e-14);
    assert_true(r.e_rounding < 1e-11); /* the bound stays below the 1e-9 tried */
    assert_int_equal(ct_impact_check(&o, &r), CT_OK);
    ct_impact_result bad = r;
    bad.e = r.e_closed + 1e-9;
    assert_int_equal(ct_impact_check(&o, &bad), CT_ENOCONV);
    assert_non_null(strstr(ct_error_message(), "closed-form check"));
    bad.e = r.e_closed - 1e-13;
    assert_int_equal(ct_impact_check(&o, &bad), CT_OK);
    bad.e = r.e_closed + 1e-9;
    bad.e_closed = NAN; /* unchecked */
    assert_int_equal(ct_impact_check(&o, &bad), CT_OK);
    bad.e_closed = r.e_closed;
    o.rule = CT_QUAD_TRAPEZOID;
    assert_int_equal(ct_impact_check(&o, &bad), CT_OK);
    ct_bundle_free(b);
}

static void critical_velocity(void **state)
{
    (void)state;
    ct_params p = base();
    long N = 30;
    ref_model m = {p, N};
    double eps_y = p.sigma_y / p.E;
    double hN = p.h0 * pow(p.fz, -(double)N);
    double u_c = eps_y * p.Hstar + (1.0 - eps_y) * hN; /* docs/model.md §7 at depth N */
    double V_c = sqrt(ref_work(u_c, &m) / ct_energy_scale(&p));
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, N, INFINITY), CT_OK);
    double Wc, uy;
    assert_int_equal(ct_critical_energy(b, &Wc, &uy), CT_OK);
    assert_rel(uy, u_c, 1e-14);
    ct_impact_result r;
    double below = 0.999 * V_c, above = 1.001 * V_c;
    assert_int_equal(ct_impact(b, below * below * ct_energy_scale(&p), NULL, &r), CT_OK);
    assert_true(r.e == 1.0 && r.elastic == 1);
    assert_rel(r.V_star_crit, V_c, 1e-12);
    assert_int_equal(ct_impact(b, above * above * ct_energy_scale(&p), NULL, &r), CT_OK);
    assert_true(r.e < 1.0 && r.elastic == 0);
    ct_bundle_free(b);
}

/* docs/model.md §8: e falls with V* in the paper's range u_max/h0 < 0.04. */
static void e_non_increasing_in_V(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 60, INFINITY), CT_OK);
    double prev = 2.0;
    int below = 0, above = 0;
    for (int k = 0; k <= 400; k++) {
        double V = 1e-5 * pow(10.0, 2.0 * k / 400.0);
        ct_bundle_reset(b);
        ct_impact_result r;
        assert_int_equal(ct_impact(b, V * V * ct_energy_scale(&p), NULL, &r), CT_OK);
        if (r.u_max > 0.04 * p.h0)
            break;
        assert_true(r.e >= 0.0 && r.e <= 1.0);
        if (!(r.e <= prev))
            fail_msg("e(%g) = %.17g > e at the previous V* = %.17g", V, r.e, prev);
        below += r.e == 1.0;
        above += r.e < 1.0;
        prev = r.e;
    }
    assert_true(below > 10 && above > 10);
    ct_bundle_free(b);
}

/* Beyond the paper's range the exact rods show e rising with V* while the most recently
 * touched stage is still elastic (here stage 10: u_max between h_10 = 0.0725 and its yield
 * point 0.0924): it stores energy without loss faster than the rest dissipates. The
 * independent model of this file shows the same rise, so it is physics, not a bug. */
static void e_rises_past_a_stage_top_beyond_the_papers_range(void **state)
{
    (void)state;
    ct_params p = base();
    long N = 60;
    ref_model m = {p, N};
    double V1 = 1.02925e-3, V2 = 1.06703e-3; /* u_max = 0.0901, 0.0924 */
    double e_lib[2], e_ref[2], Vs[2] = {V1, V2};
    for (int k = 0; k < 2; k++) {
        ct_bundle *b;
        assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, N, INFINITY), CT_OK);
        ct_impact_result r;
        double W = Vs[k] * Vs[k] * ct_energy_scale(&p);
        assert_int_equal(ct_impact(b, W, NULL, &r), CT_OK);
        double umax = ref_umax(&m, W);
        e_ref[k] = sqrt(ref_recoverable(&m, umax) / W);
        e_lib[k] = r.e;
        assert_rel(e_lib[k], e_ref[k], 1e-11);
        assert_true(r.u_max > 0.04 * p.h0);
        ct_bundle_free(b);
    }
    assert_true(e_ref[1] > e_ref[0] + 1e-4);
    assert_true(e_lib[1] > e_lib[0] + 1e-4);
}

static void repeated_impacts_shake_down(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 50, INFINITY), CT_OK);
    double W = 1e-3 * 1e-3 * ct_energy_scale(&p), prev = 0.0, prev_u = 0.0;
    for (int k = 0; k < 30; k++) {
        ct_impact_result r;
        assert_int_equal(ct_impact(b, W, NULL, &r), CT_OK);
        assert_true(r.e >= prev - 1e-13);
        assert_true(r.u_max >= prev_u - 1e-15);
        prev = r.e;
        prev_u = r.u_max;
    }
    assert_true(prev > 0.9); /* nearly shaken down after 30 impacts */
    ct_bundle_free(b);
}

static void crushed_layer_refused(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 10, INFINITY), CT_OK);
    ct_impact_result r;
    double V = 1.0; /* W = 500 >> sigma_y l0 H* = 10 */
    assert_int_equal(ct_impact(b, V * V * ct_energy_scale(&p), NULL, &r), CT_ERANGE);
    assert_non_null(strstr(ct_error_message(), "H*"));
    assert_int_equal(ct_impact(b, NAN, NULL, &r), CT_EINVAL);
    assert_int_equal(ct_impact(b, -1.0, NULL, &r), CT_EINVAL);
    ct_bundle_free(b);
}

static void composite_rules_converge_to_exact(void **state)
{
    (void)state;
    ct_params p = base();
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 40, INFINITY), CT_OK);
    double W = 3e-3 * 3e-3 * ct_energy_scale(&p);
    ct_quad_rule rules[] = {CT_QUAD_TRAPEZOID, CT_QUAD_SIMPSON, CT_QUAD_GAUSS};
    for (int q = 0; q < 3; q++) {
        double err_coarse = 0.0, err_fine = 0.0;
        size_t Ks[] = {16, 4096};
        for (int k = 0; k < 2; k++) {
            ct_impact_opts o;
            ct_impact_opts_default(&o);
            o.rule = rules[q];
            o.nodes = Ks[k];
            ct_bundle_reset(b);
            ct_impact_result r;
            assert_int_equal(ct_impact(b, W, &o, &r), CT_OK);
            *(k ? &err_fine : &err_coarse) = r.quad_error;
        }
        assert_true(err_fine < err_coarse / 100.0);
        assert_true(err_fine < 1e-5);
    }
    ct_bundle_free(b);
}

/* quadrature = closed: the closed-form energies and nothing else. Its e must match the
 * independent model as the quadrature does, and equal the e_closed of a quadrature run. */
static void closed_rule_is_the_closed_form(void **state)
{
    (void)state;
    ct_params p = base();
    ref_model m = {p, 20};
    double W = 2e-3 * 2e-3 * ct_energy_scale(&p);
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 20, INFINITY), CT_OK);
    ct_impact_opts o;
    ct_impact_opts_default(&o);
    ct_impact_result rq, rc;
    assert_int_equal(ct_impact(b, W, &o, &rq), CT_OK);
    ct_bundle_reset(b);
    o.rule = CT_QUAD_CLOSED;
    assert_int_equal(ct_impact(b, W, &o, &rc), CT_OK);
    assert_true(rc.e == rc.e_closed && rc.quad_error == 0.0);
    assert_true(rc.W_load == rc.W_load_closed && rc.W_unload == rc.W_unload_closed);
    assert_true(rc.e_closed == rq.e_closed);
    double umax = ref_umax(&m, W);
    assert_rel(rc.e, sqrt(ref_recoverable(&m, umax) / W), 1e-11);
    ct_bundle_free(b);
}

/* depth = fractal: converged to double precision against a much deeper explicit surface, in
 * e and in V*_c (whose tip-depth error ct_auto_depth does not control). */
static void fractal_depth_matches_deep_surface(void **state)
{
    (void)state;
    ct_params p = base();
    double V[] = {5e-5, 2e-4, 3e-3};
    double W_min = V[0] * V[0] * ct_energy_scale(&p);
    long N;
    double bound;
    assert_int_equal(ct_fractal_depth(&p, W_min, &N, &bound), CT_OK);
    assert_true(bound <= 1e-15);
    ct_bundle *fr, *deep;
    assert_int_equal(ct_cantor_bundle(&fr, &p, CT_REP_STAGES, N, INFINITY), CT_OK);
    assert_int_equal(ct_cantor_bundle(&deep, &p, CT_REP_STAGES, N + 300, INFINITY), CT_OK);
    for (int k = 0; k < 3; k++) {
        ct_impact_result a, b;
        ct_bundle_reset(fr);
        ct_bundle_reset(deep);
        double W = V[k] * V[k] * ct_energy_scale(&p);
        assert_int_equal(ct_impact(fr, W, NULL, &a), CT_OK);
        assert_int_equal(ct_impact(deep, W, NULL, &b), CT_OK);
        assert_true(fabs(a.e - b.e) <= 1e-14);
        assert_rel(a.V_star_crit, b.V_star_crit, 1e-14);
        assert_rel(a.u_max, b.u_max, 1e-14);
    }
    /* the first yield is eps_y H* in the limit */
    double Wc, uy;
    assert_int_equal(ct_critical_energy(fr, &Wc, &uy), CT_OK);
    ct_bundle_reset(fr);
    assert_int_equal(ct_critical_energy(fr, &Wc, &uy), CT_OK);
    assert_rel(uy, p.sigma_y / p.E * p.Hstar, 1e-14);
    ct_bundle_free(fr);
    ct_bundle_free(deep);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(e_against_independent_solution),
        cmocka_unit_test(single_rod_closed_form),
        cmocka_unit_test(check_fails_a_wrong_e),
        cmocka_unit_test(critical_velocity),
        cmocka_unit_test(e_non_increasing_in_V),
        cmocka_unit_test(e_rises_past_a_stage_top_beyond_the_papers_range),
        cmocka_unit_test(repeated_impacts_shake_down),
        cmocka_unit_test(crushed_layer_refused),
        cmocka_unit_test(composite_rules_converge_to_exact),
        cmocka_unit_test(closed_rule_is_the_closed_form),
        cmocka_unit_test(fractal_depth_matches_deep_surface),
    };
    return cmocka_run_group_tests_name("impact", tests, NULL, NULL);
}
