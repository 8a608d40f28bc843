/* The impact in time (docs/model.md §11, src/dynamics.c): a single linear rod (t_c = pi sqrt(m/k)
 * exactly, a symmetric history), an elastic impact (t_load = t_unload, e_kinematic = 1), a
 * plateau worked by hand, a deep surface against GSL's adaptive ODE integration of
 * m u'' = -P(u) with P summed rod by rod (loading, then unloading from the state the rods
 * are left in), energy conservation at every event, and the sweep's rows against impacts
 * run one by one. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assert_rel.h"
#include "cantact.h"

#define PI 3.14159265358979323846

static ct_bundle *one_rod(double E, double top, double area)
{
    ct_layer L = {.E = E, .sigma_y = 1.0, .Hstar = 10.0, .l0 = 1.0, .h0 = 1.0};
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 1, &top, &area), CT_OK);
    return b;
}

/* k = E s / L = 100 * 1 / 10 = 10, m = 2: t_c = pi sqrt(m / k), the history symmetric. */
static void single_linear_rod(void **state)
{
    (void)state;
    ct_bundle *b = one_rod(100.0, 0.0, 1.0);
    const double m = 2.0, k = 10.0, v1 = 0.05; /* stays below the yield point 0.1 */
    ct_impact_result r;
    ct_dynamics d;
    ct_history h;
    assert_int_equal(ct_impact_history(b, m, v1, 101, &r, &d, &h), CT_OK);
    assert_true(r.elastic && r.e == 1.0);
    assert_rel(d.t_contact, PI * sqrt(m / k), 1e-15);
    assert_rel(d.t_load, d.t_unload, 1e-15);
    assert_rel(d.P_peak, v1 * sqrt(m * k), 1e-15); /* k A, A = v1 / omega */
    assert_rel(d.period_min, 2.0 * PI * sqrt(m / k), 1e-15);
    assert_true(d.e_kinematic == 1.0 && d.v2 == d.v1);
    /* the grid: u(t) = (v1 / omega) sin(omega t), and u(t) = u(t_c - t) */
    const double w = sqrt(k / m);
    size_t grid = 0;
    for (size_t i = 0; i < h.n; i++) {
        const ct_history_point *q = &h.points[i];
        assert_true(fabs(q->u - v1 / w * sin(w * q->t)) <= 1e-15 * v1 / w);
        assert_true(fabs(q->v - v1 * cos(w * q->t)) <= 1e-15 * v1);
        if (i)
            assert_true(q->t >= h.points[i - 1].t);
        grid += !q->event;
    }
    assert_int_equal(grid, 101);
    ct_history_free(&h);
    ct_bundle_free(b);
}

/* One rod past its yield point, by hand: k = 10, m = 1, yield at u = 0.1 with F = 1; from
 * v1 = 1 the harmonic arc u = sin(omega t) / omega reaches 0.1 at t1 = asin(0.1 omega) / omega
 * with speed cos(omega t1), then the plateau decelerates it by F / m = 1 in t2 = cos(omega t1).
 * Unloading from rest at u_max along k (u - u_max + 0.1) is a quarter period, pi / (2 omega),
 * and the rod gives back F^2 / (2k) = 0.05: v2 = sqrt(0.1). */
static void plateau_by_hand(void **state)
{
    (void)state;
    ct_bundle *b = one_rod(100.0, 0.0, 1.0);
    ct_impact_result r;
    ct_dynamics d;
    assert_int_equal(ct_impact_history(b, 1.0, 1.0, 0, &r, &d, NULL), CT_OK);
    const double w = sqrt(10.0), t1 = asin(0.1 * w) / w, t2 = cos(w * t1);
    assert_false(r.elastic);
    assert_rel(d.t_load, t1 + t2, 1e-14);
    assert_rel(d.t_unload, PI / (2.0 * w), 1e-14);
    assert_rel(d.P_peak, 1.0, 1e-15);
    assert_rel(d.v2, sqrt(0.1), 1e-14);
    assert_rel(d.dissipated, 0.5 - 0.05, 1e-14);
    assert_rel(d.e_kinematic, r.e, 1e-14);
    ct_bundle_free(b);
}

/* Below V*_c nothing yields: the body comes back as it came, e_kinematic = 1 exactly. */
static void elastic_impact_is_symmetric(void **state)
{
    (void)state;
    ct_params p = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 40, INFINITY), CT_OK);
    const double m = p.E * p.l0 / p.h0, V = 5e-5, v1 = sqrt(2.0) * V * p.h0;
    ct_impact_result r;
    ct_dynamics d;
    assert_int_equal(ct_impact_history(b, m, v1, 0, &r, &d, NULL), CT_OK);
    assert_true(r.elastic);
    assert_true(d.t_load == d.t_unload && d.e_kinematic == 1.0);
    ct_bundle_free(b);
}

/* ---- the ODE reference: m u'' = -P(u), P summed rod by rod ---- */
typedef struct {
    const ct_bundle *b;
    double m;
} ode_ctx;

static int rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const ode_ctx *c = params;
    dydt[0] = y[1];
    dydt[1] = -ct_bundle_force(c->b, y[0]) / c->m;
    return GSL_SUCCESS;
}

/* Integrates from (u, v) at t = 0 until g(y) = y[which] - level changes sign; returns the
 * crossing time and state, located to 1e-15 relative by bisection on re-integrations. */
static double integrate_to(const ode_ctx *c, double u, double v, int which, double level,
                           double y_out[2])
{
    gsl_odeiv2_system sys = {rhs, NULL, 2, (void *)c};
    gsl_odeiv2_driver *d =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-6, 1e-14, 1e-14);
    double y[2] = {u, v}, t = 0.0, dt = 1e-3;
    double sign0 = y[which] - level;
    /* march until the sign changes */
    for (int it = 0; it < 1000000; it++) {
        double y1[2] = {y[0], y[1]}, t1 = t;
        gsl_odeiv2_driver_reset(d);
        assert_int_equal(gsl_odeiv2_driver_apply(d, &t1, t + dt, y1), GSL_SUCCESS);
        if ((y1[which] - level) * sign0 <= 0.0)
            break;
        y[0] = y1[0], y[1] = y1[1], t = t1;
    }
    /* bisect the step that crosses */
    double lo = 0.0, hi = dt;
    for (int it = 0; it < 60 && hi - lo > 1e-16 * (t + hi); it++) {
        double mid = 0.5 * (lo + hi), y1[2] = {y[0], y[1]}, t1 = t;
        gsl_odeiv2_driver_reset(d);
        assert_int_equal(gsl_odeiv2_driver_apply(d, &t1, t + mid, y1), GSL_SUCCESS);
        if ((y1[which] - level) * sign0 > 0.0)
            lo = mid;
        else
            hi = mid;
    }
    double y1[2] = {y[0], y[1]}, t1 = t;
    gsl_odeiv2_driver_reset(d);
    assert_int_equal(gsl_odeiv2_driver_apply(d, &t1, t + lo, y1), GSL_SUCCESS);
    y_out[0] = y1[0];
    y_out[1] = y1[1];
    gsl_odeiv2_driver_free(d);
    return t + 0.5 * (lo + hi);
}

/* A deep surface (40 stage rods) struck twice: t_load, t_unload, P_peak and v2 against the
 * ODE, to 1e-9. The second impact starts from the state the first left (its reloading runs
 * along the unloading line). */
static void deep_surface_against_ode(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    ct_params p = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 40, INFINITY), CT_OK);
    const double m = 3.0, V = 3e-3, v1 = V * sqrt(2.0 * p.l0 * p.E * p.h0 / m);
    for (int impact = 0; impact < 2; impact++) {
        ct_impact_result r;
        ct_dynamics d;
        assert_int_equal(ct_impact_history(b, m, v1, 0, &r, &d, NULL), CT_OK);
        assert_false(r.elastic);
        ode_ctx c = {b, m};
        double y[2];
        /* loading: from first contact at v1 until v = 0 */
        double t_load = integrate_to(&c, ct_bundle_first_contact(b), v1, 1, 0.0, y);
        double u_max = y[0], P_peak = ct_bundle_force(b, u_max);
        assert_rel(d.t_load, t_load, 1e-9);
        assert_rel(d.P_peak, P_peak, 1e-9);
        assert_rel(r.u_max, u_max, 1e-9);
        /* unloading: the rods left at u_max, from rest until the release point */
        ct_bundle_advance(b, r.u_max);
        /* the stiffest unloading piece is the top one: every rod in contact, E s / L each */
        double k_top = 0.0;
        for (size_t q = 0; q < ct_bundle_size(b); q++) {
            ct_rod_info ri;
            assert_int_equal(ct_bundle_rod(b, q, &ri), CT_OK);
            if (ri.top + ri.plastic_strain * ri.length < r.u_max)
                k_top += p.E * ri.area / ri.length;
        }
        assert_rel(d.k_unload_max, k_top, 1e-12);
        assert_rel(d.period_min, 2.0 * PI * sqrt(m / k_top), 1e-12);
        double release = ct_bundle_first_contact(b);
        double t_unload = integrate_to(&c, r.u_max, 0.0, 0, release, y);
        assert_rel(d.t_unload, t_unload, 1e-9);
        assert_rel(d.v2, -y[1], 1e-9);
        assert_rel(d.e_kinematic, r.e, 1e-12);
    }
    ct_bundle_free(b);
}

/* Energy: 1/2 m v^2 + W(u) = 1/2 m v1^2 at every loading event, W summed rod by rod in
 * closed form; and 1/2 m v^2 + W_unload(u) = 1/2 m v2^2 on unloading. */
static void energy_at_every_event(void **state)
{
    (void)state;
    ct_params p = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 60, INFINITY), CT_OK);
    const double m = p.E * p.l0 / p.h0, v1 = sqrt(2.0) * 2e-3;
    ct_impact_result r;
    ct_dynamics d;
    ct_history h;
    assert_int_equal(ct_impact_history(b, m, v1, 50, &r, &d, &h), CT_OK);
    const double W_kin = 0.5 * m * v1 * v1, u0 = ct_bundle_first_contact(b);
    ct_bundle *after;
    assert_int_equal(ct_bundle_clone(&after, b), CT_OK);
    ct_bundle_advance(after, r.u_max);
    const double rel = ct_bundle_first_contact(after), W_back = 0.5 * m * d.v2 * d.v2;
    size_t events = 0;
    for (size_t i = 0; i < h.n; i++) {
        const ct_history_point *q = &h.points[i];
        double kin = 0.5 * m * q->v * q->v;
        if (!q->unloading) {
            double E = kin + ct_bundle_work(b, u0, q->u);
            if (!(fabs(E - W_kin) <= 1e-13 * W_kin))
                fail_msg("loading point %zu (event %d): energy %.17g vs %.17g", i, q->event, E,
                         W_kin);
        } else {
            double E = kin + ct_bundle_work(after, rel, q->u);
            if (!(fabs(E - W_back) <= 1e-13 * W_kin))
                fail_msg("unloading point %zu (event %d): energy %.17g vs %.17g", i, q->event, E,
                         W_back);
        }
        events += q->event;
        /* P of the history against the rods' own sum at the same u */
        double P = q->unloading ? ct_bundle_force(after, q->u) : ct_bundle_force(b, q->u);
        assert_true(fabs(q->P - P) <= 1e-12 * d.P_peak);
    }
    assert_true(events > 40);
    assert_true(h.points[h.n - 1].t == d.t_contact);
    assert_rel(-h.points[h.n - 1].v, d.v2, 1e-12);
    ct_history_free(&h);
    ct_bundle_free(after);
    ct_bundle_free(b);
}

static int no_op(const ct_sweep_row *row, int phase, const ct_bundle *b, const ct_curve *c,
                 void *ctx)
{
    (void)row, (void)phase, (void)b, (void)c, (void)ctx;
    return 0;
}

/* The sweep's time columns: its fast path (one curve, repeated impacts by the unloading curve
 * of each maximum) against its state-carrying path (an observer), and the first impact
 * against ct_impact_history with the sweep's mass E l0 / h0. */
static void compare_paths(ct_bundle *b, const ct_params *pp);

static void sweep_rows_against_one_by_one(void **state)
{
    (void)state;
    ct_params p = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 80, INFINITY), CT_OK);
    compare_paths(b, &p);
    ct_bundle_free(b);
    /* arbitrary tops and areas: the unloading curve's runs are not monotone (a sort) */
    double top[400], area[400];
    for (int k = 0; k < 400; k++) {
        top[k] = 0.8 * fmod(0.618033988749895 * k, 1.0);
        area[k] = (1.0 + fmod(0.7548776662466927 * k, 1.0)) / 600.0;
    }
    ct_layer L;
    ct_cantor_layer(&p, &L);
    assert_int_equal(ct_bundle_from_rods(&b, &L, 400, top, area), CT_OK);
    compare_paths(b, &p);
    /* a state with plastic strain already (its rods no longer yield in the order they touch:
     * the general unloading curve, sorted) */
    ct_bundle_advance(b, 0.5);
    compare_paths(b, &p);
    ct_bundle_free(b);
}

static void compare_paths(ct_bundle *b, const ct_params *pp)
{
    const ct_params p = *pp;
    enum { NV = 5, IMP = 4 };
    const double V[NV] = {5e-5, 2e-4, 1e-3, 4e-3, 1e-2};
    ct_sweep_row fast[NV * IMP], slow[NV * IMP];
    ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = IMP, .dynamics = 1};
    ct_impact_opts_default(&spec.opts);
    assert_int_equal(ct_sweep(b, &spec, fast), CT_OK);
    spec.observe = no_op;
    assert_int_equal(ct_sweep(b, &spec, slow), CT_OK);
    for (int q = 0; q < NV * IMP; q++) {
        assert_int_equal(fast[q].status, CT_OK);
        assert_int_equal(slow[q].status, CT_OK);
        const ct_dynamics *a = &fast[q].dyn, *c = &slow[q].dyn;
        assert_rel(a->t_load, c->t_load, 1e-11);
        assert_rel(a->t_unload, c->t_unload, 1e-11);
        assert_rel(a->P_peak, c->P_peak, 1e-12);
        assert_rel(a->period_min, c->period_min, 1e-12);
        assert_rel(a->e_kinematic, fast[q].r.e, 1e-12);
        assert_rel(c->e_kinematic, slow[q].r.e, 1e-12);
    }
    for (int v = 0; v < NV; v++) {
        ct_impact_result r;
        ct_dynamics d;
        assert_int_equal(ct_impact_history(b, p.E, sqrt(2.0) * V[v], 0, &r, &d, NULL), CT_OK);
        assert_rel(fast[v * IMP].dyn.t_contact, d.t_contact, 1e-14);
        assert_rel(fast[v * IMP].dyn.P_peak, d.P_peak, 1e-14);
    }
}

/* t / tau depends only on the dimensionless groups (docs/model.md §11), in any units of the
 * layer. One rod (top 0, area 1) of length L = H* = h0 = lambda, E = 1000, sigma_y = 1,
 * l0 = 1, struck at V* = 0.01 with the sweep's mass m = E l0 / h0 = 1000 / lambda, whose
 * stiffness k = E s / L = 1000 / lambda gives omega = sqrt(k / m) = 1 (tau = 1). W = V*^2 l0 E
 * h0 = 0.1 lambda, v1 = sqrt(2 W / m) = sqrt(2) V* lambda; yield at u_y = eps_y L = 1e-3
 * lambda, reached on the harmonic arc u = v1 sin(t) at t1 = asin(u_y / v1) with speed
 * v1 cos(t1); then the plateau F = E s eps_y = 1 decelerates it by F / m = lambda / 1000 in
 * t2 = 1000 v1 cos(t1) / lambda. Unloading from rest along k is a quarter period, pi / 2; the
 * rod gives back F eps_y L / 2 = 5e-4 lambda: e = sqrt(5e-4 / 0.1) = sqrt(0.005). P_peak = F,
 * the unloading period 2 pi. For lambda = 1e-160 the layer's speeds (1e-162) have squares
 * below the doubles (e_kinematic was NaN), for 1e160 and 1e300 above them (inf): every
 * figure must be the same. On the sweep's fast path, its state-carrying path (an observer)
 * and ct_impact_history with its history. */
static int count_calls(const ct_sweep_row *row, int phase, const ct_bundle *b, const ct_curve *c,
                       void *ctx)
{
    (void)row, (void)phase, (void)b, (void)c;
    ++*(int *)ctx;
    return 0;
}

static void time_is_scale_free(void **state)
{
    (void)state;
    const double lambdas[] = {1.0, 1e-160, 0x1p-1000, 1e160, 1e300};
    const double V = 0.01, top = 0.0, area = 1.0;
    const double t1 = asin(1e-3 / (sqrt(2.0) * V)), t2 = 1000.0 * sqrt(2.0) * V * cos(t1);
    for (size_t q = 0; q < sizeof lambdas / sizeof lambdas[0]; q++) {
        const double lam = lambdas[q];
        ct_layer L = {.E = 1000.0, .sigma_y = 1.0, .Hstar = lam, .l0 = 1.0, .h0 = lam};
        ct_bundle *b;
        assert_int_equal(ct_bundle_from_rods(&b, &L, 1, &top, &area), CT_OK);
        for (int path = 0; path < 3; path++) {
            ct_dynamics d;
            ct_impact_result r;
            ct_history h = {0};
            int calls = 0;
            if (path < 2) {
                ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 1, .dynamics = 1};
                ct_impact_opts_default(&spec.opts);
                if (path == 1) {
                    spec.observe = count_calls;
                    spec.observe_ctx = &calls;
                }
                ct_sweep_row row;
                assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
                if (row.status)
                    fail_msg("lambda %g, path %d: %s", lam, path, row.message);
                d = row.dyn;
                r = row.r;
            } else {
                const double m = L.E * L.l0 / L.h0, v1 = sqrt(2.0) * V * lam;
                if (ct_impact_history(b, m, v1, 20, &r, &d, &h))
                    fail_msg("lambda %g, history: %s", lam, ct_error_message());
                assert_rel(d.v1, v1, 1e-15);
                for (size_t i = 0; i < h.n; i++) { /* every point finite, in the layer's units */
                    const ct_history_point *p = &h.points[i];
                    assert_true(isfinite(p->t) && isfinite(p->u) && isfinite(p->v) &&
                                isfinite(p->P));
                    assert_true(p->u >= -1e-15 * lam && p->u <= 1.01 * r.u_max);
                    assert_true(p->P >= 0.0 && p->P <= 1.0 + 1e-15);
                    assert_true(p->t >= 0.0 && p->t <= d.t_contact * (1.0 + 1e-15));
                }
                assert_rel(h.points[h.n - 1].t, d.t_contact, 1e-15);
                assert_rel(-h.points[h.n - 1].v, d.v2, 1e-12);
                ct_history_free(&h);
            }
            assert_false(r.elastic);
            assert_rel(r.e, sqrt(0.005), 1e-13);
            assert_rel(d.t_load, t1 + t2, 1e-13);
            assert_rel(d.t_unload, PI / 2.0, 1e-13);
            assert_rel(d.t_contact, t1 + t2 + PI / 2.0, 1e-13);
            assert_rel(d.P_peak, 1.0, 1e-13);
            assert_rel(d.e_kinematic, sqrt(0.005), 1e-13);
            assert_rel(d.period_min, 2.0 * PI, 1e-13);
            assert_rel(d.k_unload_max, 1000.0 / lam, 1e-13);
            assert_rel(d.v2, sqrt(0.005) * sqrt(2.0) * V * lam, 1e-13);
            assert_rel(d.dissipated, 0.1 * lam * (1.0 - 0.005), 1e-13);
        }
        ct_bundle_free(b);
    }
    /* a deep Cantor surface (its first pieces by their moments, W^2: beyond the doubles for
     * E l0 h0 = 5e302) against itself at unit scale, two impacts per speed */
    enum { NV = 3, IMP = 2 };
    const double Vs[NV] = {2e-4, 1e-3, 1e-2},
                 scale[][2] = {{1e150, 1e150}, {1e-150, 1e-150}, {1e-100, 1e100}, {1e100, 1e-100}};
    ct_sweep_row ref[NV * IMP], row[NV * IMP];
    for (int q = -1; q < 4; q++) {
        ct_params p = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1};
        if (q >= 0) {
            p.h0 = scale[q][0];
            p.l0 = scale[q][1];
            p.Hstar = 10.0 * p.h0;
        }
        ct_bundle *b;
        assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 60, INFINITY), CT_OK);
        ct_sweep_spec spec = {.V_star = Vs, .nvel = NV, .impacts = IMP, .dynamics = 1};
        ct_impact_opts_default(&spec.opts);
        ct_sweep_row *r = q < 0 ? ref : row;
        assert_int_equal(ct_sweep(b, &spec, r), CT_OK);
        for (int k = 0; k < NV * IMP && q >= 0; k++) {
            if (r[k].status)
                fail_msg("h0 %g, l0 %g, row %d: %s", p.h0, p.l0, k, r[k].message);
            const ct_dynamics *a = &r[k].dyn, *c = &ref[k].dyn;
            assert_rel(a->t_load, c->t_load, 1e-12);
            assert_rel(a->t_unload, c->t_unload, 1e-12);
            assert_rel(a->e_kinematic, c->e_kinematic, 1e-12);
            assert_rel(a->P_peak / p.l0, c->P_peak, 1e-12);
            assert_rel(a->period_min, c->period_min, 1e-12);
        }
        ct_bundle_free(b);
    }
}

/* A figure the doubles cannot carry is refused, naming it, never returned as inf or NaN:
 * one rod of stiffness k = E s / L = 1e-300 / 2e7 = 5e-308 under a body of mass 1.7e308 (an
 * elastic impact) rings for t_contact = pi sqrt(m / k) = 1.83e308, above the largest double,
 * while t_load = t_unload = 9.2e307 are not. */
static void figure_beyond_doubles_is_refused(void **state)
{
    (void)state;
    ct_layer L = {.E = 1e-300, .sigma_y = 1e-303, .Hstar = 2e7, .l0 = 1.0, .h0 = 2e7};
    const double top = 0.0, area = 1.0, m = 1.7e308, k = 1e-300 / 2e7;
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 1, &top, &area), CT_OK);
    ct_impact_result r;
    ct_dynamics d;
    /* half the yield energy E s L eps_y^2 / 4 = 1e-300 * 2e7 * 1e-6 / 4 */
    const double W = 5e-300, v1 = sqrt(2.0 * W) / sqrt(m);
    assert_true(PI * (sqrt(m) / sqrt(k)) > DBL_MAX && PI / 2.0 * (sqrt(m) / sqrt(k)) < DBL_MAX);
    assert_int_equal(ct_impact_history(b, m, v1, 0, &r, &d, NULL), CT_ERANGE);
    assert_non_null(strstr(ct_error_message(), "t_contact = inf"));
    ct_bundle_free(b);
}

static void bad_input(void **state)
{
    (void)state;
    ct_bundle *b = one_rod(100.0, 0.0, 1.0);
    ct_impact_result r;
    ct_dynamics d;
    assert_int_equal(ct_impact_history(b, 0.0, 1.0, 0, &r, &d, NULL), CT_EINVAL);
    assert_int_equal(ct_impact_history(b, 1.0, NAN, 0, &r, &d, NULL), CT_EINVAL);
    assert_int_equal(ct_impact_history(NULL, 1.0, 1.0, 0, &r, &d, NULL), CT_EINVAL);
    assert_int_equal(ct_impact_history(b, 1.0, 1.0, 0, &r, NULL, NULL), CT_EINVAL);
    assert_int_equal(ct_impact_history(b, 1.0, 100.0, 0, &r, &d, NULL), CT_ERANGE); /* crushed */
    ct_history_free(NULL);
    ct_bundle_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(single_linear_rod),
        cmocka_unit_test(plateau_by_hand),
        cmocka_unit_test(elastic_impact_is_symmetric),
        cmocka_unit_test(deep_surface_against_ode),
        cmocka_unit_test(energy_at_every_event),
        cmocka_unit_test(sweep_rows_against_one_by_one),
        cmocka_unit_test(time_is_scale_free),
        cmocka_unit_test(figure_beyond_doubles_is_refused),
        cmocka_unit_test(bad_input),
    };
    return cmocka_run_group_tests_name("dynamics", tests, NULL, NULL);
}
