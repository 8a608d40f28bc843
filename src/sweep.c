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
    const size_t impacts = (size_t)s->impacts;
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
    const int carry = impacts > 1 || s->observe;
    if ((st = ct_curve_alloc(&first)) || (st = ct_curve_build(first, b)))
        goto done;
    if (carry && ((st = ct_curve_alloc(&later)) || (st = ct_bundle_clone(&work, b))))
        goto done;

    for (size_t v = 0; v < s->nvel; v++) {
        const double W = s->V_star[v] * s->V_star[v] * scale;
        if (carry)
            copy_state(work, b);
        for (size_t i = 0; i < impacts; i++) {
            ct_sweep_row *row = &rows[v * impacts + i];
            const ct_bundle *state = carry ? work : b;
            const ct_curve *c = first;
            if (i > 0) {
                if ((st = ct_curve_build(later, work)))
                    goto done;
                c = later;
            }
            row->status = ct_impact_eval(state, c, W, &s->opts, &row->r);
            if (row->status) {
                fail_row(row, row->status, ct_error_message());
                char msg[sizeof row->message];
                snprintf(msg, sizeof msg, "not run: impact %ld of V* = %g failed", row->impact,
                         row->V_star);
                for (size_t j = i + 1; j < impacts; j++)
                    fail_row(&rows[v * impacts + j], CT_ESKIPPED, msg);
                if (s->stop_on_error) {
                    st = row->status;
                    ct_error_set(st, "V* = %.17g, impact %ld: %s", row->V_star, row->impact,
                                 row->message);
                    goto done;
                }
                break;
            }
            row->message[0] = '\0';
            if (s->observe && (st = s->observe(row, 0, state, c, s->observe_ctx)))
                goto done;
            if (carry && !row->r.elastic)
                ct_bundle_advance(work, row->r.u_max);
            if (s->observe && (st = s->observe(row, 1, state, NULL, s->observe_ctx)))
                goto done;
        }
        if (s->progress)
            s->progress(v + 1, s->nvel, s->progress_ctx);
    }
done:
    ct_curve_free(first);
    ct_curve_free(later);
    ct_bundle_free(work);
    return st;
}
