/* Planning (which depth, which rods a scene can leave out) and sweeps over speeds x impacts.
 * Every front-end (the CLI, the drivers in tools/, the benchmarks, a Python binding) calls
 * these: the policy lives here once. */
#include "internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int check_speeds(const double *V, size_t n)
{
    if (n && !V)
        return ct_error_set(CT_EINVAL, "speeds: NULL array for %zu speeds", n);
    for (size_t k = 0; k < n; k++)
        if (!isfinite(V[k]) || !(V[k] > 0.0))
            return ct_error_set(CT_EINVAL, "V* = %g (speed %zu): must be finite and > 0", V[k], k);
    return CT_OK;
}

int ct_cantor_plan_build(const ct_cantor_plan *plan, ct_bundle **out, ct_plan_info *info)
{
    const ct_params *p = &plan->params;
    int st;
    *out = NULL;
    if ((st = ct_params_validate(p)) || (st = check_speeds(plan->V_star, plan->nvel)))
        return st;
    if (plan->nvel == 0)
        return ct_error_set(CT_EINVAL, "plan: no speeds");
    if (plan->impacts < 1)
        return ct_error_set(CT_EINVAL, "impacts = %ld: must be >= 1", plan->impacts);
    double vmin = INFINITY, vmax = 0.0;
    for (size_t k = 0; k < plan->nvel; k++) {
        vmin = plan->V_star[k] < vmin ? plan->V_star[k] : vmin;
        vmax = plan->V_star[k] > vmax ? plan->V_star[k] : vmax;
    }
    const double scale = ct_energy_scale(p);
    long depth = plan->depth;
    double bound = 0.0;
    if (depth == CT_DEPTH_FRACTAL)
        st = ct_fractal_depth(p, vmin * vmin * scale, &depth, &bound);
    else if (depth == CT_DEPTH_AUTO)
        st = ct_auto_depth(p, vmin * vmin * scale, plan->depth_tolerance, &depth, &bound);
    else if (depth < 0)
        st = ct_error_set(CT_EINVAL, "depth = %ld: must be >= 0, auto or fractal", depth);
    if (st)
        return st;

    /* Rods deeper than every displacement the plan reaches can never be touched, and can be
     * left out, provided none of them decides a reported number: the deepest u_max (the
     * largest speed, on the cheap and exact stage rods, impacts carried over), and the first
     * yield of the virgin surface, which fixes V*_c even when every impact is elastic. If
     * the probe fails (a crushed layer), nothing is left out: the sweep reports that row. */
    double u_reach = INFINITY;
    if (!plan->keep_all_rods) {
        ct_bundle *probe;
        if ((st = ct_cantor_bundle(&probe, p, CT_REP_STAGES, depth, INFINITY)))
            return st;
        double reach = ct_bundle_first_yield(probe);
        int ok = 1;
        for (long i = 0; i < plan->impacts && ok; i++) {
            ct_impact_result r;
            ok = ct_impact(probe, vmax * vmax * scale, &plan->opts, &r) == CT_OK;
            if (ok && r.u_max > reach)
                reach = r.u_max;
        }
        ct_bundle_free(probe);
        if (ok)
            u_reach = reach * (1.0 + 1e-9);
    }
    ct_bundle *b;
    if ((st = ct_cantor_bundle(&b, p, plan->representation, depth, u_reach)))
        return st;
    ct_bundle_set_threads(b, plan->threads);
    if (info) {
        info->depth = depth;
        info->bound = bound;
        info->rods = ct_bundle_size(b);
        info->omitted = ct_bundle_omitted(b);
        info->u_reach = u_reach;
    }
    *out = b;
    return CT_OK;
}

static void fail_row(ct_sweep_row *row, int status, const char *message)
{
    row->status = status;
    snprintf(row->message, sizeof row->message, "%s", message);
}

static void copy_state(ct_bundle *dst, const ct_bundle *src)
{
    double *t, *l, *a, *p, *ts, *ls, *as, *ps;
    ct_bundle_arrays(dst, &t, &l, &a, &p);
    ct_bundle_arrays((ct_bundle *)src, &ts, &ls, &as, &ps); /* read only */
    memcpy(p, ps, ct_bundle_size(src) * sizeof(double));
}

/* Fails row i of a speed and marks the speed's later impacts as not run. */
static void fail_from(ct_sweep_row *rows, size_t impacts, size_t v, size_t i, int status,
                      const char *message)
{
    ct_sweep_row *row = &rows[v * impacts + i];
    fail_row(row, status, message);
    char msg[sizeof row->message];
    snprintf(msg, sizeof msg, "not run: impact %ld of V* = %g failed", row->impact, row->V_star);
    for (size_t j = i + 1; j < impacts; j++)
        fail_row(&rows[v * impacts + j], CT_ESKIPPED, msg);
}

/* One speed by carrying the state in `work`: curve rebuilt after every plastic impact. The
 * general path (observers, composite rules, impacts that stay below an earlier maximum). */
static int speed_by_state(const ct_bundle *b, const ct_curve *first, ct_curve *later,
                          ct_bundle *work, const ct_sweep_spec *s, size_t v, ct_sweep_row *rows)
{
    const ct_layer *L = ct_bundle_layer(b);
    const double W = s->V_star[v] * s->V_star[v] * L->l0 * L->E * L->h0;
    const size_t impacts = (size_t)s->impacts;
    int st, changed = 0;
    copy_state(work, b);
    for (size_t i = 0; i < impacts; i++) {
        ct_sweep_row *row = &rows[v * impacts + i];
        const ct_curve *c = first;
        if (changed) {
            if ((st = ct_curve_build(later, work)))
                return st;
            c = later;
        }
        row->status = ct_impact_eval(work, c, W, &s->opts, &row->r);
        if (row->status) {
            fail_from(rows, impacts, v, i, row->status, ct_error_message());
            return CT_OK;
        }
        row->message[0] = '\0';
        if (s->observe && (st = s->observe(row, 0, work, c, s->observe_ctx)))
            return st;
        if (!row->r.elastic) {
            ct_bundle_advance(work, row->r.u_max);
            changed = 1;
        }
        if (s->observe && (st = s->observe(row, 1, work, NULL, s->observe_ctx)))
            return st;
    }
    return CT_OK;
}

/* The first failed row in order, under stop_on_error. */
static int first_failure(const ct_sweep_row *rows, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (rows[k].status && rows[k].status != CT_ESKIPPED)
            return ct_error_set(rows[k].status, "V* = %.17g, impact %ld: %s", rows[k].V_star,
                                rows[k].impact, rows[k].message);
    return CT_OK;
}

int ct_sweep(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows)
{
    int st;
    if (!s || (s->nvel && !rows))
        return ct_error_set(CT_EINVAL, "sweep: NULL spec or rows");
    if ((st = check_speeds(s->V_star, s->nvel)))
        return st;
    if (s->impacts < 1)
        return ct_error_set(CT_EINVAL, "impacts = %ld: must be >= 1", s->impacts);
    const ct_layer *L = ct_bundle_layer(b);
    const double scale = L->l0 * L->E * L->h0;
    const size_t impacts = (size_t)s->impacts, nrows = s->nvel * impacts;
    for (size_t v = 0; v < s->nvel; v++)
        for (size_t i = 0; i < impacts; i++) {
            ct_sweep_row *row = &rows[v * impacts + i];
            memset(row, 0, sizeof *row);
            row->speed = v;
            row->impact = (long)i + 1;
            row->V_star = s->V_star[v];
            fail_row(row, CT_ESKIPPED, "not run");
        }

    ct_curve *first = NULL, *later = NULL;
    ct_bundle *work = NULL;
    double *adv = NULL, *u0 = NULL, *u1 = NULL, *Wl = NULL, *Wu = NULL;
    size_t *slot = NULL; /* row -> its place in the batched closed forms */
    unsigned char *by_state = NULL;
    if ((st = ct_curve_alloc(&first)) || (st = ct_curve_build(first, b)))
        goto done;
    by_state = calloc(s->nvel ? s->nvel : 1, 1);
    if (!by_state) {
        st = ct_error_set(CT_ENOMEM, "sweep of %zu speeds: out of memory", s->nvel);
        goto done;
    }
    /* Fast path: an impact that reaches past the state's earlier maximum U sees the first
     * curve shifted (ct_impact_on_curve), and impacts of equal energy always do, so every
     * impact costs O(log n); the closed-form check of all rows shares passes over the rods. */
    const int fast =
        !s->observe && (s->opts.rule == CT_QUAD_BREAKPOINTS || s->opts.rule == CT_QUAD_CLOSED);
    const int closed = s->opts.check || s->opts.rule == CT_QUAD_CLOSED;
    if (fast) {
        if (closed && (!(adv = malloc((nrows + 1) * sizeof(double))) ||
                       !(u0 = malloc((nrows + 1) * sizeof(double))) ||
                       !(u1 = malloc((nrows + 1) * sizeof(double))) ||
                       !(Wl = malloc((nrows + 1) * sizeof(double))) ||
                       !(Wu = malloc((nrows + 1) * sizeof(double))) ||
                       !(slot = malloc((nrows + 1) * sizeof(size_t))))) {
            st = ct_error_set(CT_ENOMEM, "sweep of %zu impacts: out of memory", nrows);
            goto done;
        }
        size_t m = 0;
        for (size_t v = 0; v < s->nvel; v++) {
            const double W = s->V_star[v] * s->V_star[v] * scale;
            double U = -INFINITY;
            for (size_t i = 0; i < impacts; i++) {
                ct_sweep_row *row = &rows[v * impacts + i];
                int rs = ct_impact_on_curve(first, L, U, W, &s->opts, &row->r);
                if (rs == CT_ESKIPPED) {
                    by_state[v] = 1;
                    break;
                }
                if (rs) {
                    fail_from(rows, impacts, v, i, rs, ct_error_message());
                    break;
                }
                row->status = CT_OK;
                row->message[0] = '\0';
                if (closed) {
                    slot[v * impacts + i] = m;
                    adv[m] = U;
                    u0[m] = row->r.u_contact;
                    u1[m] = row->r.u_max;
                    m++;
                }
                if (!row->r.elastic)
                    U = row->r.u_max;
            }
            if (s->progress && !by_state[v])
                s->progress(v + 1, s->nvel, s->progress_ctx);
        }
        if (closed && (st = ct_bundle_closed_many(b, adv, u0, u1, m, Wl, Wu)))
            goto done;
        for (size_t v = 0; v < s->nvel; v++) {
            if (by_state[v])
                continue;
            for (size_t i = 0; i < impacts; i++) {
                ct_sweep_row *row = &rows[v * impacts + i];
                if (row->status)
                    break;
                if (closed) {
                    const size_t q = slot[v * impacts + i];
                    row->r.W_load_closed = Wl[q];
                    row->r.W_unload_closed = row->r.elastic ? Wl[q] : Wu[q];
                    if (s->opts.rule == CT_QUAD_CLOSED) {
                        row->r.W_load = row->r.W_load_closed;
                        row->r.W_unload = row->r.W_unload_closed;
                    }
                }
                int rs = ct_impact_finish(first, &s->opts, &row->r);
                if (rs) {
                    fail_from(rows, impacts, v, i, rs, ct_error_message());
                    break;
                }
            }
        }
    }
    int need_state = !fast;
    for (size_t v = 0; v < s->nvel && !need_state; v++)
        need_state = by_state[v];
    if (need_state) {
        if ((st = ct_curve_alloc(&later)) || (st = ct_bundle_clone(&work, b)))
            goto done;
        for (size_t v = 0; v < s->nvel; v++) {
            if (fast && !by_state[v])
                continue;
            for (size_t i = 0; i < impacts; i++)
                fail_row(&rows[v * impacts + i], CT_ESKIPPED, "not run");
            if ((st = speed_by_state(b, first, later, work, s, v, rows)))
                goto done;
            if (s->stop_on_error && (st = first_failure(rows, nrows)))
                goto done;
            if (s->progress)
                s->progress(v + 1, s->nvel, s->progress_ctx);
        }
    }
    if (s->stop_on_error)
        st = first_failure(rows, nrows);
done:
    ct_curve_free(first);
    ct_curve_free(later);
    ct_bundle_free(work);
    free(adv);
    free(u0);
    free(u1);
    free(Wl);
    free(Wu);
    free(slot);
    free(by_state);
    return st;
}
