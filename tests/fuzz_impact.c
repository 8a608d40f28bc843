/* libFuzzer target: impacts on arbitrary surfaces, every rule and path. The bytes choose a
 * Cantor surface over the whole valid range (fx up to 1e3, fz in (1, 2), H* / h0 up to 1e6,
 * E/sigma_y up to 1e9), its representation and depth, up to 8 speeds (V* from 1e-150 to 1), 1-4
 * impacts, the rule, its nodes and the sweep path. Whatever the library computes must hold what
 * docs/model.md says: e finite in [0, 1], exactly 1 for an elastic impact, u_max finite and below
 * H*, and the energy balance W(u_max) = kinetic energy to the solve's tolerance or the rounding
 * floor of u. A refusal (a status with a message) is fine; a wrong number is a crash here. Build
 * and run: scripts/fuzz [SECONDS] impact. */
#include "cantact.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const uint8_t *data;
    size_t size, at;
} bytes;

/* The next 16 bits as a fraction in [0, 1] (0 when the input is used up). */
static double next_unit(bytes *b)
{
    unsigned v = 0;
    for (int k = 0; k < 2; k++)
        v = (v << 8) | (b->at < b->size ? b->data[b->at++] : 0u);
    return v / 65535.0;
}

/* lo * (hi / lo)^t: log-uniform over [lo, hi]. */
static double log_between(bytes *b, double lo, double hi)
{
    return lo * pow(hi / lo, next_unit(b));
}

static void die(const char *what, const ct_sweep_row *row)
{
    fprintf(stderr, "fuzz_impact: %s (V* = %.17g, impact %ld: e = %.17g, u_max = %.17g)\n", what,
            row->V_star, row->impact, row->r.e, row->r.u_max);
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size, 0};
    ct_params p = {.l0 = 1.0, .h0 = 1.0, .sigma_y = 1.0};
    p.fx = 1.0 + log_between(&b, 1e-9, 999.0);
    p.fz = 1.0 + log_between(&b, 1e-9, 0.999);
    p.Hstar = 1.0 + log_between(&b, 1e-9, 1e6);
    p.E = 1.0 + log_between(&b, 1e-3, 1e9);
    if (ct_params_validate(&p) != CT_OK)
        return 0;
    const int segments = next_unit(&b) < 0.25;
    const long depth = segments ? (long)(next_unit(&b) * 10.0) : (long)(next_unit(&b) * 200.0);
    size_t nv = 1 + (size_t)(next_unit(&b) * 7.0);
    double V[8];
    for (size_t k = 0; k < nv; k++)
        V[k] = log_between(&b, 1e-150, 1.0); /* far below V*_c too (issue 24, item 12) */
    ct_impact_opts opts;
    ct_impact_opts_default(&opts);
    opts.rule = (ct_quad_rule)(int)(next_unit(&b) * 4.999);
    opts.nodes = 3 + (size_t)(next_unit(&b) * 300.0);
    const long impacts = 1 + (long)(next_unit(&b) * 3.0);
    const ct_sweep_path path = (ct_sweep_path)(int)(next_unit(&b) * 2.999);

    ct_bundle *bundle;
    if (ct_cantor_bundle(&bundle, &p, segments ? CT_REP_SEGMENTS : CT_REP_STAGES, depth,
                         INFINITY) != CT_OK)
        return 0;
    ct_sweep_spec spec = {.V_star = V, .nvel = nv, .impacts = impacts, .opts = opts, .path = path};
    ct_sweep_row rows[8 * 4];
    int st = ct_sweep(bundle, &spec, rows);
    if (st != CT_OK && st != CT_ENOMEM && st != CT_ENOCONV)
        abort(); /* the spec is valid: only resources or a solve may fail */
    for (size_t q = 0; st == CT_OK && q < nv * (size_t)impacts; q++) {
        const ct_sweep_row *row = &rows[q];
        if (row->status != CT_OK) {
            if (!row->message[0])
                die("a failed row without a message", row);
            continue;
        }
        const ct_impact_result *r = &row->r;
        if (!isfinite(r->e) || r->e < 0.0 || r->e > 1.0)
            die("e outside [0, 1]", row);
        if (r->elastic && r->e != 1.0)
            die("an elastic impact with e != 1", row);
        if (!isfinite(r->u_max) || !(r->u_max < p.Hstar) || !isfinite(r->V_star_crit))
            die("u_max or V*_c not finite, or u_max beyond H*", row);
        if (opts.rule == CT_QUAD_BREAKPOINTS || opts.rule == CT_QUAD_CLOSED) {
            /* the balance: P beyond the state's earlier maximum is the virgin P, so the
             * virgin force at u_max gives the rounding floor of the solve */
            double W = r->kinetic_energy, Wl = r->W_load;
            double floor = 64.0 * DBL_EPSILON * fabs(r->u_max) * ct_bundle_force(bundle, r->u_max);
            /* an elastic penetration below the resolution of u (V* = 1e-150 on a rod first
             * touched at u = 1) has no W(u) to balance: e = 1 whatever u_max (model.md) */
            const int unresolved =
                r->elastic && !(r->u_max - r->u_contact > 16.0 * DBL_EPSILON * fabs(r->u_max));
            if (!(fabs(Wl - W) <= 1e-12 * W + floor) && !unresolved)
                die("energy balance broken", row);
        }
    }
    /* differential: the curve path and the rod path are independent evaluations of the same
     * impacts (an O(log n) curve against Newton's method on rod sums); where both compute,
     * they agree within the rounding each states */
    if (st == CT_OK && (opts.rule == CT_QUAD_BREAKPOINTS || opts.rule == CT_QUAD_CLOSED)) {
        ct_sweep_row other[8 * 4];
        spec.path = path == CT_PATH_RODS ? CT_PATH_CURVE : CT_PATH_RODS;
        if (ct_sweep(bundle, &spec, other) == CT_OK)
            for (size_t q = 0; q < nv * (size_t)impacts; q++) {
                const ct_sweep_row *a = &rows[q], *c = &other[q];
                if (a->status != CT_OK || c->status != CT_OK)
                    continue;
                double tol = 1e-9 + 4.0 * (a->r.e_rounding + c->r.e_rounding);
                if (!(fabs(a->r.e - c->r.e) <= tol)) { /* elastic may flip at W = W_c */
                    fprintf(stderr, "fuzz_impact: paths disagree: e %.17g vs %.17g (tol %.3g)\n",
                            a->r.e, c->r.e, tol);
                    die("the curve and rod paths disagree", a);
                }
            }
    }
    /* differential: the lean curve is the full curve held otherwise: the same bits in every
     * row (it refuses, with CT_EINVAL, only a work that rounds to a non-monotone sequence) */
    if (st == CT_OK && (opts.rule == CT_QUAD_BREAKPOINTS || opts.rule == CT_QUAD_CLOSED)) {
        ct_sweep_row full[8 * 4], lean[8 * 4];
        spec.path = CT_PATH_CURVE;
        const int sf = ct_sweep(bundle, &spec, full);
        spec.path = CT_PATH_LEAN;
        const int sl = ct_sweep(bundle, &spec, lean);
        if (sf == CT_OK && sl != CT_EINVAL) {
            if (sl != CT_OK)
                die("the lean curve failed where the full one ran", &full[0]);
            for (size_t q = 0; q < nv * (size_t)impacts; q++) {
                const ct_sweep_row *a = &full[q], *c = &lean[q];
                if (a->status != c->status)
                    die("the lean and full curves give different statuses", a);
                if (a->status != CT_OK)
                    continue;
                const double fa[] = {a->r.u_contact, a->r.u_max, a->r.u_release,  a->r.W_load,
                                     a->r.W_unload,  a->r.e,     a->r.e_rounding, a->r.V_star_crit};
                const double fc[] = {c->r.u_contact, c->r.u_max, c->r.u_release,  c->r.W_load,
                                     c->r.W_unload,  c->r.e,     c->r.e_rounding, c->r.V_star_crit};
                if (memcmp(fa, fc, sizeof fa) || a->r.elastic != c->r.elastic)
                    die("the lean and full curves differ", a);
            }
        }
    }
    ct_bundle_free(bundle);
    return 0;
}
