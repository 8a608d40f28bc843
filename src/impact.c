/* Energy balance of one impact (MODEL.md §7, Eqs. 39-41): u_max, unloading, e; the
 * critical velocity; repeated impacts carry the rods' state; the truncation depth. */
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

void ct_impact_opts_default(ct_impact_opts *opts)
{
    opts->rule = CT_QUAD_BREAKPOINTS;
    opts->nodes = 64;
    opts->tolerance = 1e-14;
}

int ct_critical_energy(ct_bundle *b, double *energy, double *u_yield)
{
    double u0 = ct_bundle_first_contact(b), uy = ct_bundle_first_yield(b);
    if (!isfinite(u0) || !isfinite(uy))
        return ct_error_set(CT_EINVAL, "critical energy: the bundle holds no rod");
    *u_yield = uy;
    *energy = ct_bundle_work(b, u0, uy);
    return CT_OK;
}

static int force_batch(const double *u, size_t m, double *P, void *ctx)
{
    return ct_bundle_force_many((ct_bundle *)ctx, u, m, P);
}

int ct_solve_umax(ct_bundle *b, double W, double tolerance, double *u_max)
{
    const ct_params *p = ct_bundle_params(b);
    double u0 = ct_bundle_first_contact(b);
    if (!isfinite(W) || W < 0.0)
        return ct_error_set(CT_EINVAL, "impact energy %g: must be finite and >= 0", W);
    if (!(tolerance > 0.0 && tolerance < 1.0))
        return ct_error_set(CT_EINVAL, "tolerance = %g: must satisfy 0 < tolerance < 1", tolerance);
    if (!isfinite(u0))
        return ct_error_set(CT_EINVAL, "u_max: the bundle holds no rod");
    if (W == 0.0) {
        *u_max = u0;
        return CT_OK;
    }
    if (!(u0 < p->Hstar))
        return ct_error_set(CT_ERANGE, "first contact at u = %g is not above H* = %g", u0,
                            p->Hstar);
    double W_crushed = ct_bundle_work(b, u0, p->Hstar);
    if (!(W < W_crushed))
        return ct_error_set(CT_ERANGE,
                            "impact energy %.6g reaches u_max >= H* = %g (the layer would be "
                            "crushed, strains >= 1): outside the model; lower V* or raise H",
                            W, p->Hstar);

    double *pts;
    size_t n;
    int st = ct_bundle_breakpoints(b, u0, p->Hstar, &pts, &n);
    if (st)
        return st;
    /* W(u) is convex and piecewise quadratic with knots at the breakpoints: find the piece
     * holding the target, then solve that quadratic exactly. Large bundles are memory-bound,
     * so each pass over their rods evaluates W at up to 63 breakpoints (a 64-section); small
     * ones are compute-bound and bisect. */
    const size_t per_pass = ct_bundle_size(b) >= CT_PARALLEL_MIN_RODS ? 63 : 1;
    double x[63], Wx[63], Wa = 0.0; /* W(pts[0]) = W(u0) = 0 */
    size_t idx[63];
    size_t lo = 0, hi = n - 1; /* W(pts[lo]) <= W < W(pts[hi]) */
    while (hi - lo > 1) {
        size_t span = hi - lo, k = span - 1 < per_pass ? span - 1 : per_pass;
        for (size_t j = 0; j < k; j++) {
            idx[j] = lo + (j + 1) * span / (k + 1);
            x[j] = pts[idx[j]];
        }
        if ((st = ct_bundle_work_many(b, u0, x, k, Wx))) {
            free(pts);
            return st;
        }
        size_t new_lo = lo, new_hi = hi;
        for (size_t j = 0; j < k; j++) {
            if (Wx[j] <= W) {
                new_lo = idx[j];
                Wa = Wx[j];
            } else {
                new_hi = idx[j];
                break;
            }
        }
        lo = new_lo;
        hi = new_hi;
    }
    double a = pts[lo], c = pts[hi];
    free(pts);
    double ac[2] = {a, c}, Pac[2];
    if ((st = ct_bundle_force_many(b, ac, 2, Pac)))
        return st;
    double Pa = Pac[0], Pc = Pac[1];
    double slope = (Pc - Pa) / (c - a);
    double R = W - Wa;
    double disc = Pa * Pa + 2.0 * slope * R;
    double denom = Pa + sqrt(disc > 0.0 ? disc : 0.0);
    double u = denom > 0.0 ? a + 2.0 * R / denom : c;
    if (u > c)
        u = c;
    if (u < a)
        u = a;
    /* One Newton step against the summed closed form mops up rounding in slope. */
    for (int it = 0; it < 3; it++) {
        double r = ct_bundle_work(b, u0, u) - W;
        if (fabs(r) <= tolerance * W)
            break;
        double P = ct_bundle_force(b, u);
        if (!(P > 0.0))
            break;
        double next = u - r / P;
        u = next < a ? a : next > c ? c : next;
    }
    /* Near first contact W(u) is ill-conditioned: u - top loses digits, so the residual
     * cannot fall below what a few ulps of u change; accept that rounding floor. */
    double resid = fabs(ct_bundle_work(b, u0, u) - W);
    double rounding_floor = 8.0 * DBL_EPSILON * fabs(u) * ct_bundle_force(b, u);
    if (!(resid <= tolerance * W || resid <= rounding_floor) &&
        u - u0 <= 16.0 * DBL_EPSILON * fabs(u0))
        return ct_error_set(CT_ENOCONV,
                            "u_max solve: the penetration u_max - u_contact (%.3g) is below the "
                            "resolution of u near %.17g: this impact is too weak to resolve on "
                            "rods this stiff (raise V*)",
                            u - u0, u0);
    if (!(resid <= tolerance * W || resid <= rounding_floor))
        return ct_error_set(CT_ENOCONV,
                            "u_max solve: |W(u) - W| / W = %.3g after the exact piece and Newton "
                            "steps, above the tolerance %.3g",
                            resid / W, tolerance);
    *u_max = u;
    return CT_OK;
}

/* Rod evaluations one quadrature may cost (about a minute on one core): beyond it the run is
 * refused rather than left to hang. Deep stage bundles hit it first, as their breakpoint
 * count grows with their rod count. */
#define CT_MAX_QUAD_ROD_EVALS 5e10

/* The energy over [lo, hi] by the chosen rule; `closed` is its closed form, which the
 * closed rule returns as it is. */
static int energy_quadrature(ct_bundle *b, double lo, double hi, const ct_impact_opts *opts,
                             double closed, double *result)
{
    double *pts = NULL, abserr;
    size_t n = 0;
    int st;
    if (opts->rule == CT_QUAD_CLOSED) {
        *result = closed;
        return CT_OK;
    }
    if (opts->rule == CT_QUAD_BREAKPOINTS && (st = ct_bundle_breakpoints(b, lo, hi, &pts, &n)))
        return st;
    double nodes = opts->rule == CT_QUAD_BREAKPOINTS ? (double)n : (double)opts->nodes;
    double cost = nodes * (double)ct_bundle_size(b) * (opts->rule == CT_QUAD_BREAKPOINTS ? 1 : 1.5);
    if (cost > CT_MAX_QUAD_ROD_EVALS) {
        free(pts);
        return ct_error_set(CT_ENOCONV,
                            "%s quadrature with %.3g nodes on %zu rods would need %.2g rod "
                            "evaluations (limit %.0e): fx and fz this close to 1 need more "
                            "stages than this quadrature can afford; give a smaller depth or a "
                            "larger solver.depth_tolerance",
                            ct_quad_rule_name(opts->rule), nodes, ct_bundle_size(b), cost,
                            CT_MAX_QUAD_ROD_EVALS);
    }
    st = ct_integrate_batch(force_batch, b, lo, hi, opts->rule, opts->nodes, pts, n, result,
                            &abserr);
    free(pts);
    return st;
}

int ct_impact(ct_bundle *b, double W, const ct_impact_opts *opts, ct_impact_result *res)
{
    ct_impact_opts defaults;
    if (!opts) {
        ct_impact_opts_default(&defaults);
        opts = &defaults;
    }
    int st;
    double scale = ct_energy_scale(ct_bundle_params(b));
    double W_crit, u_yield;
    if (!isfinite(W) || !(W > 0.0))
        return ct_error_set(CT_EINVAL, "impact energy %g: must be finite and > 0", W);
    if ((st = ct_critical_energy(b, &W_crit, &u_yield)))
        return st;
    res->kinetic_energy = W;
    res->V_star = sqrt(W / scale);
    res->V_star_crit = sqrt(W_crit / scale);
    res->u_contact = ct_bundle_first_contact(b);
    if ((st = ct_solve_umax(b, W, opts->tolerance, &res->u_max)))
        return st;
    res->W_load_closed = ct_bundle_work(b, res->u_contact, res->u_max);
    if ((st = energy_quadrature(b, res->u_contact, res->u_max, opts, res->W_load_closed,
                                &res->W_load)))
        return st;

    if (W <= W_crit) {
        /* No rod yields: the state is unchanged and every joule comes back (e = 1 exactly). */
        res->elastic = 1;
        res->u_release = res->u_contact;
        res->W_unload = res->W_load;
        res->W_unload_closed = res->W_load_closed;
        res->e = res->e_closed = 1.0;
        res->quad_error = 0.0;
        res->e_rounding = 0.0;
        return CT_OK;
    }
    res->elastic = 0;
    ct_bundle_advance(b, res->u_max);
    res->u_release = ct_bundle_first_contact(b);
    res->W_unload_closed = ct_bundle_elastic_energy(b, res->u_max); /* Eq. 40 in closed form */
    if ((st = energy_quadrature(b, res->u_release, res->u_max, opts, res->W_unload_closed,
                                &res->W_unload)))
        return st;
    if (!(res->W_load > 0.0) || !(res->W_unload >= 0.0))
        return ct_error_set(CT_ENOCONV,
                            "%s quadrature gave W_load = %g, W_unload = %g: not a valid "
                            "energy pair",
                            ct_quad_rule_name(opts->rule), res->W_load, res->W_unload);
    res->e = sqrt(res->W_unload / res->W_load); /* Eq. 41, the right way up */
    res->e_closed = sqrt(res->W_unload_closed / res->W_load_closed);
    res->quad_error = fabs(res->e - res->e_closed);
    /* W_unload <= W_load exactly. P is evaluated from u - top, which loses digits when the
     * penetration u_max - u_contact, or the unloading interval u_max - u_release (eps_y-thin
     * for stiff rods), is small against u itself: e carries a rounding error of about
     * eps u_max / (that interval). Within it, e and
     * e_closed may land above 1; that excess is rounding, not restitution. */
    double kappa = fabs(res->u_max) / (res->u_max - res->u_contact);
    double kappa_unload = fabs(res->u_max) / (res->u_max - res->u_release); /* eps_y-thin */
    kappa = kappa > kappa_unload ? kappa : kappa_unload;
    res->e_rounding = 64.0 * DBL_EPSILON * (kappa > 1.0 ? kappa : 1.0);
    if (res->e > 1.0 && res->e <= 1.0 + res->e_rounding)
        res->e = 1.0;
    if (res->e_closed > 1.0 && res->e_closed <= 1.0 + res->e_rounding)
        res->e_closed = 1.0;
    return CT_OK;
}

/* Bound on |P_N(u) - P_inf(u)| for any common history: the force of a rod is Lipschitz in
 * its top depth h with constant E H* / (H* - h0)^2 (strain and plastic strain both vary as
 * (u - H*)/(H* - h)^2), each difference is also at most E eps_y, and the tip lumps area l_N
 * of tops in [0, h_N]. */
static double force_bound(const ct_params *p, long N)
{
    double lN = ct_stage_length(p, (double)N), hN = ct_stage_depth(p, (double)N);
    double eps_y = p->sigma_y / p->E, gap = p->Hstar - p->h0;
    double lip = hN * p->Hstar / (gap * gap);
    return p->E * lN * (lip < eps_y ? lip : eps_y);
}

/* Depths from here on reuse the u_max of this depth as an upper bound, so the search
 * costs nothing more for deep surfaces. */
#define DEPTH_PROBE 64

typedef struct {
    const ct_params *p;
    double W_min;
    int tips;
    double u_up; /* u_max at DEPTH_PROBE, < 0 until computed */
} depth_ctx;

static int solve_virgin(const ct_params *p, long N, double W, double *u, double *P)
{
    ct_bundle *b;
    int st = ct_bundle_alloc(&b, p, CT_REP_STAGES, N, INFINITY);
    if (st)
        return st;
    st = ct_solve_umax(b, W, 1e-12, u);
    if (!st)
        *P = ct_bundle_force(b, *u);
    ct_bundle_free(b);
    return st;
}

/* The truncated surface is softer than any deeper one on a virgin loading (deeper tips only
 * add strain), so its u_max bounds theirs from above: the energy bound is safe. */
static int depth_bound(depth_ctx *c, long N, double *bound)
{
    const ct_params *p = c->p;
    double dP = force_bound(p, N), u, P;
    int st;
    if (N < DEPTH_PROBE) {
        if ((st = solve_virgin(p, N, c->W_min, &u, &P)))
            return st;
        double rel_W = dP * u / c->W_min, rel_P = P > 0.0 ? dP / P : INFINITY;
        *bound = rel_W > rel_P ? rel_W : rel_P;
    } else {
        if (c->u_up < 0.0 && (st = solve_virgin(p, DEPTH_PROBE, c->W_min, &c->u_up, &P)))
            return st;
        /* P(u_max) >= W / u_max as P rises with u: dP u_up / W bounds both ratios */
        *bound = dP * c->u_up / c->W_min;
    }
    if (c->tips) {
        /* first yield of the prefractal: eps_y H* + (1 - eps_y) h_N, of the fractal eps_y H* */
        double eps_y = p->sigma_y / p->E;
        double rel_tip = (1.0 - eps_y) * ct_stage_depth(p, (double)N) / (eps_y * p->Hstar);
        *bound = *bound > rel_tip ? *bound : rel_tip;
    }
    return CT_OK;
}

static int search_depth(const ct_params *p, double W_min, double tol, int tips, long *depth,
                        double *bound)
{
    int st;
    if ((st = ct_params_validate(p)))
        return st;
    if (!(tol > 0.0 && tol < 1.0))
        return ct_error_set(CT_EINVAL, "depth tolerance = %g: must satisfy 0 < tol < 1", tol);
    if (!isfinite(W_min) || !(W_min > 0.0))
        return ct_error_set(CT_EINVAL, "depth auto: impact energy %g must be finite and > 0",
                            W_min);
    depth_ctx c = {p, W_min, tips, -1.0};
    long hi = 1;
    double b_hi;
    for (;;) {
        if ((st = depth_bound(&c, hi, &b_hi)))
            return st;
        if (b_hi <= tol)
            break;
        if (hi >= CT_MAX_STAGES_DEPTH / 2)
            return ct_error_set(CT_ENOCONV,
                                "depth auto: even %ld stages leave a truncation bound of %.3g "
                                "> tolerance %.3g (fx, fz too close to 1); raise the tolerance "
                                "or give a depth",
                                hi, b_hi, tol);
        hi *= 2;
    }
    long lo = hi / 2; /* bound(lo) > tol or lo = 0 */
    while (hi - lo > 1) {
        long mid = lo + (hi - lo) / 2;
        double b_mid;
        if ((st = depth_bound(&c, mid, &b_mid)))
            return st;
        if (b_mid <= tol) {
            hi = mid;
            b_hi = b_mid;
        } else {
            lo = mid;
        }
    }
    *depth = hi;
    *bound = b_hi;
    return CT_OK;
}

int ct_auto_depth(const ct_params *p, double W_min, double tol, long *depth, double *bound)
{
    return search_depth(p, W_min, tol, 0, depth, bound);
}

int ct_fractal_depth(const ct_params *p, double W_min, long *depth, double *bound)
{
    return search_depth(p, W_min, 1e-15, 1, depth, bound);
}
