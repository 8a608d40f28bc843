/* Energy balance of one impact (docs/model.md §7, Eqs. 39-41): u_max, unloading, e; the
 * critical velocity. The load curve of the pre-impact state answers everything the
 * breakpoint rule needs in O(log n); the bundle is read for the release point, the
 * closed-form check and the composite rules. */
#include "internal.h"
#include "rod.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

void ct_impact_opts_default(ct_impact_opts *opts)
{
    opts->rule = CT_QUAD_BREAKPOINTS;
    opts->nodes = 64;
    opts->tolerance = 1e-14;
    opts->check = CT_CHECK_ALL;
}

/* The energy that makes the first rod of b's state yield, rod by rod from the distances
 * between contacts: rod k yields first, at y = c_k + eps_y L_k, when rod i (contact c_i) has
 * the elastic strain ((c_k - c_i) + eps_y L_k) / L_i. The positions themselves round to ulps
 * of y, which a rod's elastic range eps_y L can be far below (E / sigma_y = 1e20 on Cantor tips
 * 5e-9 deep: V*_c was 3.5e-6 off); the differences of contacts carry it. One pass, compensated. */
static double critical_by_rods(const ct_bundle *b)
{
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays((ct_bundle *)b, &top, &length, &area, &eps_p); /* read only */
    const ct_layer *L = ct_bundle_layer(b);
    const double eps_y = L->sigma_y / L->E;
    const size_t n = ct_bundle_size(b);
    size_t k = 0;
    for (size_t i = 1; i < n; i++)
        if (ct_rod_yield(top[i], length[i], eps_p[i], eps_y) <
            ct_rod_yield(top[k], length[k], eps_p[k], eps_y))
            k = i;
    const double ck = ct_rod_contact(top[k], length[k], eps_p[k]), reach = eps_y * length[k];
    double s = 0.0, c = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double d = ((ck - ct_rod_contact(top[i], length[i], eps_p[i])) + reach) / length[i];
        if (d > 0.0)
            ct_add_comp(&s, &c, ct_rod_energy_of(d, 0.5 * L->E * area[i] * length[i], eps_y));
    }
    return s + c;
}

/* Whether W at the first yield y, from positions that round to ulps of y, carries V*_c to
 * worse than CT_UNLOAD_DIFF_E: its error P(y) ulp(y) against W(y). */
static int critical_lost(double y, double W, double P)
{
    return !(DBL_EPSILON * fabs(y) * P <= CT_UNLOAD_DIFF_E * W);
}

double ct_critical_by_rods(const ct_bundle *b, const ct_curve *c)
{
    const double y = ct_curve_first_yield(c);
    if (!isfinite(y) || !critical_lost(y, ct_curve_work(c, y), ct_curve_force(c, y)))
        return NAN;
    return critical_by_rods(b);
}

int ct_critical_energy(const ct_bundle *b, double *energy, double *u_yield)
{
    CT_NEED(b);
    CT_NEED(energy);
    CT_NEED(u_yield);
    double u0 = ct_bundle_first_contact(b), uy = ct_bundle_first_yield(b);
    if (!isfinite(u0) || !isfinite(uy))
        return ct_error_set(CT_EINVAL, "critical energy: the bundle holds no rod");
    *u_yield = uy;
    *energy = ct_bundle_work(b, u0, uy);
    if (critical_lost(uy, *energy, ct_bundle_force(b, uy)))
        *energy = critical_by_rods(b);
    return CT_OK;
}

int ct_unload_lost(double W_sum, double W_unload)
{
    /* a few ulps of the terms, 4 eps W_sum, move e by that over 2 W_unload of itself */
    return !(2.0 * DBL_EPSILON * W_sum <= CT_UNLOAD_DIFF_E * W_unload);
}

int ct_energy_check(double W, double V_star)
{
    if (isfinite(W) && W >= DBL_MIN)
        return CT_OK;
    return ct_error_set(CT_EINVAL,
                        "V* = %g gives the impact energy V*^2 l0 E h0 = %g: not a finite number "
                        "of at least %g, the smallest normal double (below it the impact is "
                        "elastic, e = 1, but not computable)",
                        V_star, W, DBL_MIN);
}

static int crushed(double W, double Hstar)
{
    return ct_error_set(CT_ERANGE,
                        "impact energy %.6g reaches u_max >= H* = %g (the layer would be "
                        "crushed, strains >= 1): outside the model; lower the speed or raise H",
                        W, Hstar);
}

/* u_max on the curve where its work is W, with the model's limits: no rod, crushed layer,
 * and (when `resolve`: an impact that yields, whose e depends on it) a penetration below the
 * resolution of u. An elastic impact has e = 1 whatever its u_max's last digits. W_impact:
 * the impact's own kinetic energy, which the messages name (W less the dissipation to an
 * earlier maximum, for a repeated impact on the first curve). */
static int curve_umax(const ct_curve *c, double W, double W_impact, double Hstar, int resolve,
                      double *u_max)
{
    double u0 = ct_curve_first_contact(c);
    if (!isfinite(W) || W < 0.0)
        return ct_error_set(CT_EINVAL, "impact energy %g: must be finite and >= 0", W_impact);
    if (!isfinite(u0))
        return ct_error_set(CT_EINVAL, "u_max: the bundle holds no rod");
    if (W == 0.0) {
        *u_max = u0;
        return CT_OK;
    }
    if (!(u0 < Hstar))
        return ct_error_set(CT_ERANGE, "first contact at u = %g is not above H* = %g", u0, Hstar);
    if (!(W < ct_curve_work(c, Hstar)))
        return crushed(W_impact, Hstar);
    double u = ct_curve_inverse_work(c, W);
    if (!(u < Hstar))
        return crushed(W_impact, Hstar);
    /* Near first contact P(u) is ill-conditioned: u - top loses digits, so a penetration of
     * a few ulps of u carries no information about e. */
    if (resolve && !(u - u0 > 16.0 * DBL_EPSILON * fabs(u0)))
        return ct_error_set(CT_ENOCONV,
                            "u_max solve: the penetration u_max - u_contact (%.3g) is below the "
                            "resolution of u near %.17g: this impact is too weak to resolve on "
                            "rods this stiff (raise V*)",
                            u - u0, u0);
    *u_max = u;
    return CT_OK;
}

int ct_solve_umax(const ct_bundle *b, double W, double tolerance, double *u_max)
{
    CT_NEED(b);
    CT_NEED(u_max);
    ct_curve *c;
    int st;
    if (!(tolerance > 0.0 && tolerance < 1.0))
        return ct_error_set(CT_EINVAL, "tolerance = %g: must satisfy 0 < tolerance < 1", tolerance);
    if ((st = ct_curve_alloc(&c)))
        return st;
    if (!(st = ct_curve_build(c, b)))
        st = curve_umax(c, W, W, ct_bundle_layer(b)->Hstar, 1, u_max);
    ct_curve_free(c);
    return st;
}

/* Rod evaluations one composite quadrature may cost (about a minute on one core): beyond it
 * the run is refused rather than left to hang. */
#define CT_MAX_QUAD_ROD_EVALS 5e10

typedef struct {
    const ct_bundle *b;
    double u_adv; /* -INFINITY: the current state */
} force_ctx;

static int force_batch(const double *u, size_t m, double *P, void *ctx)
{
    const force_ctx *f = ctx;
    return ct_bundle_force_after(f->b, f->u_adv, u, m, P);
}

/* A composite rule over the rod-by-rod force of the state after u_adv on [lo, hi]. */
static int composite(const ct_bundle *b, double u_adv, double lo, double hi,
                     const ct_impact_opts *opts, double *result, double *abserr)
{
    double cost = (double)opts->nodes * (double)ct_bundle_size(b) * 1.5;
    if (cost > CT_MAX_QUAD_ROD_EVALS)
        return ct_error_set(CT_ENOCONV,
                            "%s quadrature with %zu nodes on %zu rods would need %.2g rod "
                            "evaluations (limit %.0e): use the breakpoints rule, fewer nodes or "
                            "a smaller depth",
                            ct_quad_rule_name(opts->rule), opts->nodes, ct_bundle_size(b), cost,
                            CT_MAX_QUAD_ROD_EVALS);
    force_ctx f = {b, u_adv};
    return ct_integrate_batch(force_batch, &f, lo, hi, opts->rule, opts->nodes, NULL, 0, result,
                              abserr);
}

/* The impact from the state that c's state reaches when loaded to U (U = -INFINITY: c's
 * state itself). Beyond U that state's curve is c's, shifted: P' = P, W'(u) = W(u) - D(U),
 * D'(u) = D(u) - D(U), and its first yield is U. Returns CT_ESKIPPED when the impact would
 * stay below U (there the state's curve is not c's). Fills everything but the closed
 * forms. */
int ct_impact_on_curve(const ct_curve *c, const ct_layer *L, double U, double W_U, double W,
                       const ct_impact_opts *opts, ct_impact_result *res)
{
    int st;
    const double scale = L->l0 * L->E * L->h0;
    if ((st = ct_energy_check(W, sqrt(W / scale))))
        return st;
    if (!ct_quad_rule_name(opts->rule))
        return ct_error_set(CT_EINVAL, "quadrature rule %d: unknown", (int)opts->rule);
    if (!(opts->tolerance > 0.0 && opts->tolerance < 1.0))
        return ct_error_set(CT_EINVAL, "tolerance = %g: must satisfy 0 < tolerance < 1",
                            opts->tolerance);
    const int shifted = U > -INFINITY;
    const double x0 = ct_curve_first_contact(c);
    if (!isfinite(x0))
        return ct_error_set(CT_EINVAL, "impact: the bundle holds no rod");
    const double D_U = shifted ? ct_curve_dissipation(c, U) : 0.0;
    const double u0 = shifted ? ct_curve_release(c, U) : x0;
    /* the state's energy to its first yield (back to U: W(U) - D(U)), or the rods' W_U where
     * the curve lost its digits */
    const double W_crit = !isnan(W_U) ? W_U
                          : shifted   ? ct_curve_work(c, U) - D_U
                                      : ct_curve_work(c, ct_curve_first_yield(c));
    res->kinetic_energy = W;
    res->V_star = sqrt(W / scale);
    res->V_star_crit = sqrt(W_crit / scale);
    res->u_contact = u0;
    res->elastic = W <= W_crit;
    if (shifted && res->elastic)
        return CT_ESKIPPED; /* below U: the caller evaluates the state itself */
    if ((st = curve_umax(c, W + D_U, W, L->Hstar, !res->elastic, &res->u_max)))
        return st;
    const double u = res->u_max;
    if (shifted && !res->elastic && !(u - u0 > 16.0 * DBL_EPSILON * fabs(u0)))
        return ct_error_set(CT_ENOCONV,
                            "u_max solve: the penetration u_max - u_contact (%.3g) is below the "
                            "resolution of u near %.17g: this impact is too weak to resolve on "
                            "rods this stiff (raise V*)",
                            u - u0, u0);
    const double W_u = ct_curve_work(c, u), D_u = ct_curve_dissipation(c, u);
    res->W_load = W_u - D_U;
    res->W_unload = res->elastic ? res->W_load : res->W_load - (D_u - D_U);
    /* W_unload as the difference W_load - D loses digits where little comes back: its
     * rounding, a few ulps of W(u), D(u) and D(U), moves e by that over 2 W_unload of itself
     * (at E / sigma_y = 1e16, e = 4.8e-8, it was 1.2 % off; at 1e20, 0). Beyond
     * CT_UNLOAD_DIFF_E the caller sums the elastic energy given back rod by rod instead (NaN
     * marks it: a caller that does not is refused by ct_impact_finish, never given a wrong e). */
    if (!res->elastic && ct_unload_lost(W_u + D_u + D_U, res->W_unload))
        res->W_unload = NAN;
    res->u_release = res->elastic ? u0 : ct_curve_release(c, u);
    res->W_load_closed = res->W_unload_closed = res->e_closed = res->quad_error = NAN;
    res->e_rounding = 0.0;
    return CT_OK;
}

/* e from W_load and W_unload, and the closed forms' check when they are given (not NaN). */
int ct_impact_finish(double P_max, const ct_impact_opts *opts, ct_impact_result *res)
{
    const int checked = !isnan(res->W_load_closed);
    const double u = res->u_max, W = res->kinetic_energy;
    if (checked) {
        /* the solve's tolerance, against the closed form summed rod by rod; near first
         * contact the residual cannot fall below what a few ulps of u change */
        double resid = fabs(res->W_load_closed - W);
        double floor = 8.0 * DBL_EPSILON * fabs(u) * P_max;
        /* an elastic penetration of a few ulps of u: P(u) there is 0 or nearly so, and W
         * changes more from one double to the next than the residual can say (e = 1 whatever
         * u_max is; curve_umax lets such impacts through for that reason) */
        const int unresolved = res->elastic && !(u - res->u_contact > 16.0 * DBL_EPSILON * fabs(u));
        if (!(resid <= opts->tolerance * W || resid <= floor || unresolved))
            return ct_error_set(CT_ENOCONV,
                                "u_max solve: |W(u) - W| / W = %.3g against the closed form rod "
                                "by rod, above the tolerance %.3g",
                                resid / W, opts->tolerance);
    }
    if (res->elastic) {
        /* No rod yields: the state is unchanged and every joule comes back (e = 1 exactly). */
        res->e = 1.0;
        res->e_rounding = 0.0;
        if (checked) {
            res->W_unload_closed = res->W_load_closed;
            res->e_closed = 1.0;
            res->quad_error = 0.0;
        }
        return CT_OK;
    }
    if (!(res->W_load > 0.0) || !(res->W_unload >= 0.0))
        return ct_error_set(CT_ENOCONV,
                            "%s quadrature gave W_load = %g, W_unload = %g: not a valid "
                            "energy pair",
                            ct_quad_rule_name(opts->rule), res->W_load, res->W_unload);
    res->e = sqrt(res->W_unload / res->W_load); /* Eq. 41, the right way up */
    /* W_unload <= W_load exactly. P is evaluated from u - top, which loses digits when the
     * penetration u_max - u_contact, or the unloading interval u_max - u_release (eps_y-thin
     * for stiff rods), is small against u itself: e carries a rounding error of about
     * eps u_max / (that interval). Within it, e may land above 1; that excess is rounding,
     * not restitution. */
    double kappa = fabs(u) / (u - res->u_contact);
    double kappa_unload = fabs(u) / (u - res->u_release);
    /* and u_max itself is known to an ulp or so: where a stiff rod has just touched, P(u_max)
     * is large and one ulp of u moves W_unload (and W_load) by P ulp(u), which the intervals
     * above do not see */
    double kappa_force = P_max > 0.0 ? P_max * fabs(u) / res->W_unload : 0.0;
    kappa = kappa > kappa_unload ? kappa : kappa_unload;
    kappa = kappa > kappa_force ? kappa : kappa_force;
    res->e_rounding = 64.0 * DBL_EPSILON * (kappa > 1.0 ? kappa : 1.0);
    if (res->e > 1.0 && res->e <= 1.0 + res->e_rounding)
        res->e = 1.0;
    if (res->e > 1.0)
        return ct_error_set(CT_ENOCONV,
                            "%s quadrature gave e = %.17g > 1 beyond its rounding bound %.3g: "
                            "not a valid result",
                            ct_quad_rule_name(opts->rule), res->e, res->e_rounding);
    if (checked) {
        if (!(res->W_load_closed > 0.0) || !(res->W_unload_closed >= 0.0))
            return ct_error_set(CT_ENOCONV, "closed forms gave W_load = %g, W_unload = %g",
                                res->W_load_closed, res->W_unload_closed);
        res->e_closed = sqrt(res->W_unload_closed / res->W_load_closed);
        if (res->e_closed > 1.0 && res->e_closed <= 1.0 + res->e_rounding)
            res->e_closed = 1.0;
        res->quad_error = fabs(res->e - res->e_closed);
        return ct_impact_check(opts, res);
    }
    return CT_OK;
}

int ct_impact_check(const ct_impact_opts *opts, const ct_impact_result *res)
{
    CT_NEED(opts);
    CT_NEED(res);
    if (opts->rule != CT_QUAD_BREAKPOINTS || isnan(res->e_closed))
        return CT_OK;
    /* the breakpoints rule is exact: beyond rounding, a difference is a wrong e */
    const double bound = CT_CHECK_E_BOUND + 2.0 * res->e_rounding;
    if (!(fabs(res->e - res->e_closed) <= bound))
        return ct_error_set(CT_ENOCONV,
                            "closed-form check: e = %.17g on the load curve, %.17g rod by rod "
                            "(difference %.3g above its bound %.3g): not a valid result",
                            res->e, res->e_closed, fabs(res->e - res->e_closed), bound);
    return CT_OK;
}

int ct_reach_check(const ct_bundle *b, double u_max)
{
    char why[240];
    const double limit = ct_bundle_reach(b, why, sizeof why);
    if (!(u_max > limit))
        return CT_OK;
    return ct_error_set(CT_ERANGE, "u_max/h0 = %.6g: %s", u_max / ct_bundle_layer(b)->h0, why);
}

int ct_impact_eval(const ct_bundle *b, const ct_curve *c, double W, const ct_impact_opts *opts,
                   ct_impact_result *res)
{
    CT_NEED(b);
    CT_NEED(c);
    CT_NEED(res);
    ct_impact_opts defaults;
    if (!opts) {
        ct_impact_opts_default(&defaults);
        opts = &defaults;
    }
    int st;
    if ((st = ct_impact_on_curve(c, ct_bundle_layer(b), -INFINITY, ct_critical_by_rods(b, c), W,
                                 opts, res)) ||
        (st = ct_reach_check(b, res->u_max)))
        return st;
    const double u0 = res->u_contact, u = res->u_max;
    if (opts->check || opts->rule == CT_QUAD_CLOSED) {
        res->W_load_closed = ct_bundle_work(b, u0, u);
        res->W_unload_closed = res->elastic ? res->W_load_closed : ct_bundle_elastic_energy(b, u);
    }
    switch (opts->rule) {
    case CT_QUAD_BREAKPOINTS:
        if (isnan(res->W_unload)) /* the difference lost its digits: rod by rod */
            res->W_unload =
                isnan(res->W_unload_closed) ? ct_bundle_elastic_energy(b, u) : res->W_unload_closed;
        break;
    case CT_QUAD_CLOSED:
        res->W_load = res->W_load_closed;
        res->W_unload = res->W_unload_closed;
        break;
    default: {
        double err_load, err_unload = 0.0;
        if ((st = composite(b, -INFINITY, u0, u, opts, &res->W_load, &err_load)))
            return st;
        res->W_unload = res->W_load;
        if (!res->elastic &&
            (st = composite(b, u, res->u_release, u, opts, &res->W_unload, &err_unload)))
            return st;
        /* a rule that ignores P's kinks can return more energy than went in: e > 1 is a
         * failed quadrature, never a result */
        if (res->W_unload > res->W_load)
            return ct_error_set(CT_ENOCONV,
                                "%s quadrature with %zu nodes gave W_unload = %.6g > W_load = "
                                "%.6g (e = %.6g > 1; error estimates %.2g and %.2g): a failed "
                                "quadrature; use more nodes or the breakpoints rule",
                                ct_quad_rule_name(opts->rule), opts->nodes, res->W_unload,
                                res->W_load, sqrt(res->W_unload / res->W_load), err_unload,
                                err_load);
        break;
    }
    }
    return ct_impact_finish(ct_curve_force(c, u), opts, res);
}

int ct_impact(ct_bundle *b, double W, const ct_impact_opts *opts, ct_impact_result *res)
{
    CT_NEED(b);
    CT_NEED(res);
    ct_curve *c;
    int st;
    if ((st = ct_curve_alloc(&c)))
        return st;
    if (!(st = ct_curve_build(c, b)) && !(st = ct_impact_eval(b, c, W, opts, res)) && !res->elastic)
        ct_bundle_advance(b, res->u_max);
    ct_curve_free(c);
    return st;
}
