/* Sweeps over speeds x impacts of one bundle of rods: every front-end (the CLI, the drivers in
 * tools/, the benchmarks, a Python binding) calls these, so the policy lives here once. A sweep
 * knows only rods: planning which rods a scene needs is each kind's (src/surface/). */
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

int ct_check_speeds(const double *V, size_t n)
{
    if (n && !V)
        return ct_error_set(CT_EINVAL, "speeds: NULL array for %zu speeds", n);
    for (size_t k = 0; k < n; k++)
        if (!isfinite(V[k]) || !(V[k] > 0.0))
            return ct_error_set(CT_EINVAL, "V* = %g (speed %zu): must be finite and > 0", V[k], k);
    return CT_OK;
}

static void fail_row(ct_sweep_row *row, int status, const char *message)
{
    row->status = status;
    if (message != row->message) /* the row's own message may be passed: keep it */
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
/* The mass of the sweep's impacts in time: E l0 / h0, so that tau = sqrt(m h0 / (E l0)) = 1. */
static double unit_mass(const ct_layer *L)
{
    return L->E * L->l0 / L->h0;
}

static int speed_by_state(const ct_bundle *b, const ct_curve *first, ct_curve *later,
                          ct_bundle *work, const ct_sweep_spec *s, size_t v, ct_sweep_row *rows,
                          ct_dyn_work *dw, const unsigned char *check)
{
    const ct_layer *L = ct_bundle_layer(b);
    const double W = s->V_star[v] * s->V_star[v] * L->l0 * L->E * L->h0;
    const size_t impacts = (size_t)s->impacts;
    int st, changed = 0;
    double W_U = NAN; /* the state's energy back to its maximum, rod by rod (ct_impact_on_curve) */
    ct_impact_opts opts = s->opts; /* the closed-form check for the sampled speeds */
    opts.check = check[v] ? CT_CHECK_ALL : CT_CHECK_NONE;
    copy_state(work, b);
    for (size_t i = 0; i < impacts; i++) {
        ct_sweep_row *row = &rows[v * impacts + i];
        const ct_curve *c = first;
        if (ct_interrupted(s->interrupt))
            return ct_error_interrupted();
        if (changed) {
            if ((st = ct_curve_build(later, work)))
                return st;
            c = later;
        }
        row->status = ct_impact_eval(work, c, W, &opts, &row->r);
        if (row->status) {
            fail_from(rows, impacts, v, i, row->status, ct_error_message());
            return CT_OK;
        }
        row->message[0] = '\0';
        if (!isnan(W_U)) /* the state's own curve lost it too: its elastic ranges, eps_y L */
            row->r.V_star_crit = sqrt(W_U / (L->l0 * L->E * L->h0));
        if (dw) { /* the impact in time on its own state's curve */
            ct_dyn_reset(dw);
            if ((row->status = ct_dyn_impact(dw, c, &row->r, unit_mass(L), &row->dyn, 0, NULL))) {
                fail_from(rows, impacts, v, i, row->status, ct_error_message());
                return CT_OK;
            }
        }
        if (s->observe && (st = s->observe(row, 0, work, c, s->observe_ctx)))
            return st;
        if (!row->r.elastic) {
            const double u = row->r.u_max;
            W_U = ct_unload_lost(ct_curve_work(c, u) + ct_curve_dissipation(c, u), row->r.W_unload)
                      ? row->r.W_unload
                      : NAN;
            ct_bundle_advance(work, u);
            changed = 1;
        }
        if (s->observe && (st = s->observe(row, 1, work, NULL, s->observe_ctx)))
            return st;
    }
    return CT_OK;
}

/* ---- the rod path: no curve, all speeds of an impact round solved together ---- */

#define GRID 24        /* shared starting points of the Newton iterations (virgin state) */
#define MAX_NEWTON 400 /* iterations; each is one pass over the rods for all open speeds */

/* The rod path's workspace for m impacts (and the GRID starting points). */
typedef struct {
    double *u0, *u, *Wc;                 /* per impact: its contact, u_max iterate, V*_c energy */
    double *adv, *a0, *a1, *Wl, *Wu, *P; /* the batched closed forms' nodes and results */
    size_t *open_;
} rods_ws;

/* Where each state starts, and the energy that makes its first rod yield: W_crit0 on the
 * virgin state; else (the state's first yield is U) its energy to get back there. A state
 * advanced to U starts its Newton iteration on the tangent of its work at U: W is convex on
 * it as on the virgin state, so the tangent's root lies right of the root, next to it (from
 * H* instead, the first step's W(H*) - W rounds to an ulp of H*, which can put the iterate
 * left of a root much nearer the plane than H*, digits the iteration never gets back). */
static int rods_start(const ct_bundle *b, size_t m, const double *U, const double *W_U,
                      double W_crit0, double x0, const double *W, const rods_ws *ws,
                      const volatile int *interrupt)
{
    double *u0 = ws->u0, *Wc = ws->Wc, *Wl = ws->Wl, *P = ws->P;
    const double Hstar = ct_bundle_layer(b)->Hstar;
    size_t *open_ = ws->open_, q = 0;
    int st;
    for (size_t j = 0; j < m; j++) {
        u0[j] = U[j] > -INFINITY ? ct_bundle_release(b, U[j]) : x0;
        ws->u[j] = Hstar;
        if (U[j] > -INFINITY) {
            ws->adv[q] = U[j];
            ws->a0[q] = u0[j];
            ws->a1[q] = U[j];
            open_[q++] = j;
        } else {
            Wc[j] = W_crit0;
        }
    }
    /* the force at U from b's own state (the same as the advanced state's, where its elastic
     * strains (U - top) / L - eps_p may have lost eps_y's digits and clamp to noise) */
    for (size_t k = 0; k < q; k++) {
        ws->adv[q + k] = -INFINITY;
        ws->a0[q + k] = x0;
        ws->a1[q + k] = ws->a1[k];
    }
    if (q &&
        (st = ct_bundle_closed_many(b, ws->adv, ws->a0, ws->a1, 2 * q, Wl, ws->Wu, P, interrupt)))
        return st;
    for (size_t k = 0; k < q; k++) {
        const size_t j = open_[k];
        Wc[j] = isnan(W_U[j]) ? Wl[k] : W_U[j];
        const double t = U[j] + (W[j] - Wc[j]) / P[q + k]; /* the tangent at U */
        if (P[q + k] > 0.0 && t < Hstar)
            ws->u[j] = t > u0[j] ? t : u0[j];
    }
    return CT_OK;
}

/* A shared geometric grid on the virgin state brackets every virgin speed from the right:
 * its iterate starts at the first grid point whose work exceeds its energy. */
static int rods_bracket(const ct_bundle *b, size_t m, const double *U, const double *W, double x0,
                        const rods_ws *ws, const volatile int *interrupt)
{
    const double Hstar = ct_bundle_layer(b)->Hstar;
    double g[GRID], gW[GRID], gWu[GRID], gP[GRID], lo = x0 > 0.0 ? x0 : 0.0;
    double first = fmax(lo, 1e-9 * Hstar);
    int st;
    for (int k = 0; k < GRID; k++) {
        g[k] = first * pow(Hstar / first, (double)(k + 1) / GRID);
        ws->adv[k] = -INFINITY;
        ws->a0[k] = x0;
    }
    g[GRID - 1] = Hstar;
    if ((st = ct_bundle_closed_many(b, ws->adv, ws->a0, g, GRID, gW, gWu, gP, interrupt)))
        return st;
    int below = 0; /* a speed whose root lies left of the grid's first point */
    for (size_t j = 0; j < m; j++)
        if (U[j] == -INFINITY) {
            for (int k = 0; k < GRID; k++)
                if (gW[k] > W[j]) {
                    ws->u[j] = g[k];
                    break;
                }
            below |= !(W[j] >= gW[0]);
        }
    if (!below)
        return CT_OK;
    /* Far below V*_c on a deep tip (V* ~ 1e-130: u_max ~ 1e-73) Newton would halve its way
     * down from the grid, hundreds of steps: a second geometric grid from the first contact
     * (or the smallest normal double) up to the first grid point brackets those speeds. */
    const double top = g[0], low = x0 > 0.0 ? x0 : DBL_MIN;
    for (int k = 0; k < GRID; k++)
        g[k] = low * pow(top / low, (double)(k + 1) / GRID);
    g[GRID - 1] = top;
    if ((st = ct_bundle_closed_many(b, ws->adv, ws->a0, g, GRID, gW, gWu, gP, interrupt)))
        return st;
    for (size_t j = 0; j < m; j++)
        if (U[j] == -INFINITY && ws->u[j] == top)
            for (int k = 0; k < GRID; k++)
                if (gW[k] > W[j]) {
                    ws->u[j] = g[k];
                    break;
                }
    return CT_OK;
}

/* The row of an impact of energy W (V*_c's energy Wc) whose Newton iteration stopped at u,
 * from its contact u0, with the closed forms Wl, Wu and the force P there. */
static void rods_row(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *r, double W,
                     double Wc, double u0, double u, double Wl, double Wu, double P)
{
    const ct_layer *L = ct_bundle_layer(b);
    const double scale = L->l0 * L->E * L->h0, Hstar = L->Hstar;
    ct_impact_result *res = &r->r;
    res->kinetic_energy = W;
    res->V_star = sqrt(W / scale);
    res->V_star_crit = sqrt(Wc / scale);
    res->u_contact = u0;
    res->u_max = u;
    res->elastic = W <= Wc;
    res->W_load = res->W_load_closed = Wl;
    res->W_unload = res->W_unload_closed = res->elastic ? Wl : Wu;
    res->e_closed = res->quad_error = NAN;
    r->status = CT_OK;
    if (!(u < Hstar)) /* W(H*) <= W (Newton stays at H*), or the root rounds
                       * onto H*: strains of 1, a crushed layer */
        r->status = ct_error_set(CT_ERANGE,
                                 "impact energy %.6g reaches u_max >= H* = %g (the "
                                 "layer would be crushed, strains >= 1): outside "
                                 "the model; lower the speed or raise H",
                                 W, Hstar);
    else if (!res->elastic && !(u - u0 > 16.0 * DBL_EPSILON * fabs(u0)))
        r->status =
            ct_error_set(CT_ENOCONV,
                         "u_max solve: the penetration u_max - u_contact (%.3g) is below the "
                         "resolution of u near %.17g: this impact is too weak to resolve on rods "
                         "this stiff (raise V*)",
                         u - u0, u0);
    else {
        /* the release point first: the rounding bound of e reads it */
        res->u_release = res->elastic ? u0 : ct_bundle_release(b, u);
        r->status = ct_impact_finish(P, &s->opts, res);
    }
    if (r->status == CT_OK)
        r->message[0] = '\0';
    else
        fail_row(r, r->status, ct_error_message());
}

/* One impact round on the rod path: row r[j] (j < m) has the state b advanced to U[j] and
 * kinetic energy W[j]. u_max by Newton's method on the closed-form work summed rod by rod:
 * W(u) is convex, so from any point right of the root the iterates fall monotonically onto
 * it; each iteration evaluates every open speed in one pass over the rods. A long step rounds
 * to ulps of where it starts, which can put the iterate left of a root far nearer the plane
 * (from H*, or a grid point 20 times the root: |W(u) - W| / W up to 1e-7 was refused there):
 * from the left the iterate steps back right, past the root by convexity, within the bracket
 * of the iterates seen (bisected when the step leaves it), until the residual meets the
 * tolerance or its rounding floor, or the bracket holds no double between its ends. */
static int rods_round(const ct_bundle *b, const ct_sweep_spec *s, size_t m, ct_sweep_row **r,
                      const double *U, const double *W_U, const double *W, double W_crit0,
                      double x0)
{
    const double tol = s->opts.tolerance;
    int st = CT_OK;
    double *buf = malloc((5 * m + 6 * (2 * m + GRID)) * sizeof(double));
    size_t *open_ = malloc((m + 1) * sizeof(size_t));
    if (!buf || !open_) {
        free(buf);
        free(open_);
        return ct_error_set(CT_ENOMEM, "rod path of %zu impacts: out of memory", m);
    }
    /* the closed forms' nodes: room for the grid, or two per impact (rods_start) */
    const size_t nodes = 2 * m + GRID;
    double *u0 = buf, *u = u0 + m, *Wc = u + m, *lo = Wc + m, *hi = lo + m, *adv = hi + m,
           *a0 = adv + nodes, *a1 = a0 + nodes, *Wl = a1 + nodes, *Wu = Wl + nodes, *P = Wu + nodes;
    const rods_ws ws = {u0, u, Wc, adv, a0, a1, Wl, Wu, P, open_};
    if ((st = rods_start(b, m, U, W_U, W_crit0, x0, W, &ws, s->interrupt)) ||
        (st = rods_bracket(b, m, U, W, x0, &ws, s->interrupt)))
        goto done;
    /* Newton from the right */
    size_t nopen = 0;
    for (size_t j = 0; j < m; j++) {
        lo[j] = u0[j];
        hi[j] = INFINITY;
        open_[nopen++] = j;
    }
    for (int it = 0; nopen && it < MAX_NEWTON; it++) {
        for (size_t k = 0; k < nopen; k++) {
            size_t j = open_[k];
            adv[k] = U[j];
            a0[k] = u0[j];
            a1[k] = u[j];
        }
        if ((st = ct_bundle_closed_many(b, adv, a0, a1, nopen, Wl, Wu, P, s->interrupt)))
            goto done;
        size_t still = 0;
        for (size_t k = 0; k < nopen; k++) {
            size_t j = open_[k];
            double resid = Wl[k] - W[j];
            double floor = 8.0 * DBL_EPSILON * fabs(u[j]) * P[k];
            double next = P[k] > 0.0 ? u[j] - resid / P[k] : u[j];
            next = next < u0[j] ? u0[j] : next;
            int done = fabs(resid) <= tol * W[j] || fabs(resid) <= floor;
            if (!done && resid < 0.0) { /* left of the root: back right, within the bracket */
                lo[j] = u[j];
                if (!(next > lo[j] && next < hi[j]))
                    next = lo[j] + 0.5 * (hi[j] - lo[j]);
                done = !(next > lo[j] && next < hi[j]);
            } else if (!done) {
                hi[j] = u[j];
                done = !(next < u[j]);
            }
            if (done) {
                rods_row(b, s, r[j], W[j], Wc[j], u0[j], u[j], Wl[k], Wu[k], P[k]);
                continue;
            }
            u[j] = next;
            open_[still++] = j;
        }
        nopen = still;
    }
    for (size_t k = 0; k < nopen; k++)
        fail_row(r[open_[k]], CT_ENOCONV, "u_max solve: Newton's method did not converge");
done:
    free(buf);
    free(open_);
    return st;
}

/* Every impact of every speed on the rod path, round by round (impact 1 of all speeds, then
 * impact 2, ...): the state of a speed is b advanced to the largest u_max it reached. */
static int sweep_by_rods(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows)
{
    const ct_layer *L = ct_bundle_layer(b);
    const double scale = L->l0 * L->E * L->h0;
    const size_t impacts = (size_t)s->impacts, nv = s->nvel;
    double W_crit0, uy;
    int st;
    if ((st = ct_critical_energy(b, &W_crit0, &uy)))
        return st;
    const double x0 = ct_bundle_first_contact(b);
    /* per speed: its maximum U and (WU) the state's energy back there when the impact that
     * reached U gave back too little for its closed forms on the advanced state (their elastic
     * strains, (U - top) / L - eps_p, lose eps_y's digits): that impact's W_unload */
    double *U = malloc(4 * (nv + 1) * sizeof(double)), *W = U ? U + nv + 1 : NULL;
    double *WU = U ? W + nv + 1 : NULL, *WUr = U ? WU + nv + 1 : NULL;
    ct_sweep_row **r = malloc((nv + 1) * sizeof *r);
    size_t *which = malloc((nv + 1) * sizeof *which);
    double *Ur = malloc((nv + 1) * sizeof *Ur);
    if (!U || !r || !which || !Ur) {
        st = ct_error_set(CT_ENOMEM, "rod path of %zu speeds: out of memory", nv);
        goto done;
    }
    for (size_t v = 0; v < nv; v++) {
        U[v] = -INFINITY;
        WU[v] = NAN;
    }
    for (size_t i = 0; i < impacts; i++) {
        size_t m = 0;
        for (size_t v = 0; v < nv; v++) {
            if (i > 0 && rows[v * impacts + i - 1].status)
                continue; /* the speed failed: its later impacts stay "not run" */
            r[m] = &rows[v * impacts + i];
            Ur[m] = U[v];
            WUr[m] = WU[v];
            W[m] = s->V_star[v] * s->V_star[v] * scale;
            which[m++] = v;
        }
        if ((st = rods_round(b, s, m, r, Ur, WUr, W, W_crit0, x0)))
            goto done;
        for (size_t k = 0; k < m; k++) {
            size_t v = which[k];
            const ct_impact_result *res = &r[k]->r;
            if (r[k]->status) {
                fail_from(rows, impacts, v, i, r[k]->status, r[k]->message);
            } else if (!res->elastic && res->u_max > U[v]) {
                U[v] = res->u_max;
                /* W(u) + D(u) of the curve path: W_load and the dissipation W_load - W_unload */
                WU[v] = ct_unload_lost(2.0 * res->W_load - res->W_unload, res->W_unload)
                            ? res->W_unload
                            : NAN;
            }
        }
        if (s->progress)
            s->progress((i + 1) * nv / impacts, nv, s->progress_ctx);
    }
done:
    free(U);
    free(r);
    free(which);
    free(Ur);
    return st;
}

/* Whether the sweep only asks its first curve's queries (the fast path, nothing handed out):
 * then the curve may be lean. */
static int queries_only(const ct_sweep_spec *s)
{
    return !s->observe && !s->dynamics &&
           (s->opts.rule == CT_QUAD_BREAKPOINTS || s->opts.rule == CT_QUAD_CLOSED);
}

/* Whether the sweep's curve is lean (ct_sweep_path). Auto: from CT_LEAN_RODS rods, when the
 * rows are few beside the rods (a lean query sweeps up to 32 breakpoints: about 25 times a
 * full one's cost, while its build costs two thirds of the full build) or when the full curve
 * would take over a quarter of the memory available. *events: the curve's events, counted
 * here when needed (SIZE_MAX: not yet). */
static int use_lean(const ct_bundle *b, const ct_sweep_spec *s, size_t *events)
{
    if (!queries_only(s))
        return 0;
    if (s->path != CT_PATH_AUTO)
        return s->path == CT_PATH_LEAN;
    const size_t rods = ct_bundle_size(b), rows = s->nvel * (size_t)s->impacts;
    if (rods < CT_LEAN_RODS)
        return 0;
    if (rows <= rods / 8)
        return 1;
    if (*events == SIZE_MAX)
        *events = ct_curve_events(b);
    const double need = ct_curve_bytes(*events);
    return need >= CT_MEMORY_CHECK_MIN && need > 0.25 * (double)ct_available_memory();
}

/* Whether the rod path serves this sweep better than a curve (ct_sweep_path). */
static int use_rods(const ct_bundle *b, const ct_sweep_spec *s)
{
    if (!queries_only(s))
        return 0;
    if (s->path != CT_PATH_AUTO)
        return s->path == CT_PATH_RODS;
    size_t events = ct_curve_events(b);
    const double need =
        use_lean(b, s, &events) ? ct_curve_lean_bytes(events) : ct_curve_bytes(events);
    return (need >= CT_MEMORY_CHECK_MIN && need > 0.5 * (double)ct_available_memory()) ||
           (events > 4000000 && s->nvel * (size_t)s->impacts <= 32);
}

/* The first failed row in order, under stop_on_error. */
/* Rows whose u_max passes what the rods describe (a curved body's face reaching past the
 * surface's border) fail, naming the reach; a later impact of the same speed is not run. */
static void reach_check(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows)
{
    char why[8];
    if (!(ct_bundle_reach(b, why, sizeof why) < INFINITY))
        return;
    const size_t impacts = (size_t)s->impacts;
    for (size_t v = 0; v < s->nvel; v++)
        for (size_t i = 0, failed = 0; i < impacts; i++) {
            ct_sweep_row *row = &rows[v * impacts + i];
            if (failed && row->status != CT_ESKIPPED)
                fail_row(row, CT_ESKIPPED, "not run: an earlier impact of this speed failed");
            else if (!failed && row->status == CT_OK && ct_reach_check(b, row->r.u_max))
                fail_row(row, CT_ERANGE, ct_error_message());
            failed |= row->status != CT_OK && row->status != CT_ESKIPPED;
        }
}

static int first_failure(const ct_sweep_row *rows, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (rows[k].status && rows[k].status != CT_ESKIPPED)
            return ct_error_set(rows[k].status, "V* = %.17g, impact %ld: %s", rows[k].V_star,
                                rows[k].impact, rows[k].message);
    return CT_OK;
}

/* Every row "not run" until it is. */
static void rows_not_run(const ct_sweep_spec *s, ct_sweep_row *rows)
{
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
}

/* A speed and its index, ordered by V* then index (qsort: no shared state, thread-safe). */
typedef struct {
    double V;
    size_t v;
} speed_at;

static int by_V(const void *a, const void *b)
{
    const speed_at *x = a, *y = b;
    return x->V < y->V ? -1 : x->V > y->V ? 1 : (x->v > y->v) - (x->v < y->v);
}

static void take_speed(unsigned char *mask, size_t v, size_t *n)
{
    *n += !mask[v];
    mask[v] = 1;
}

/* The speeds whose impacts get the closed-form check (CT_CHECK_AUTO, cantact.h): all while
 * rods x rows <= CT_CHECK_BUDGET, else the slowest, the fastest, the two around V*_c and the
 * speeds nearest to log-spaced V* between them, up to max(CT_CHECK_MIN_SPEEDS, budget / (rods
 * x impacts)). A function of the speeds and the surface alone: any thread count, the same. */
static int check_speeds_of(const ct_sweep_spec *s, size_t rods, double V_crit, unsigned char *mask)
{
    const size_t nv = s->nvel, impacts = (size_t)s->impacts;
    const int all = s->opts.check == CT_CHECK_ALL || s->opts.rule == CT_QUAD_CLOSED;
    const double per_speed = (double)(rods ? rods : 1) * (double)impacts;
    double want = floor(CT_CHECK_BUDGET / per_speed);
    want = want < CT_CHECK_MIN_SPEEDS ? CT_CHECK_MIN_SPEEDS : want;
    if (all || s->opts.check == CT_CHECK_NONE || want >= (double)nv) {
        memset(mask, all || s->opts.check != CT_CHECK_NONE, nv);
        return CT_OK;
    }
    speed_at *ord = malloc(nv * sizeof *ord);
    if (!ord)
        return ct_error_set(CT_ENOMEM, "closed-form check of %zu speeds: out of memory", nv);
    for (size_t v = 0; v < nv; v++)
        ord[v] = (speed_at){s->V_star[v], v};
    qsort(ord, nv, sizeof *ord, by_V);
    memset(mask, 0, nv);
    size_t n = 0, crit = 0; /* crit: the first speed above V*_c in that order */
    while (crit < nv && ord[crit].V <= V_crit)
        crit++;
    take_speed(mask, ord[0].v, &n);
    take_speed(mask, ord[nv - 1].v, &n);
    if (crit > 0)
        take_speed(mask, ord[crit - 1].v, &n);
    if (crit < nv)
        take_speed(mask, ord[crit].v, &n);
    const double lo = log(ord[0].V), hi = log(ord[nv - 1].V);
    const size_t k = (size_t)want;
    for (size_t q = 1; q + 1 < k && n < k; q++) { /* nearest to log-spaced targets */
        const double t = lo + (hi - lo) * (double)q / (double)(k - 1);
        size_t a = 0, z = nv - 1; /* log V of ord[a] <= t < log V of ord[z] */
        while (z - a > 1) {
            size_t mid = a + (z - a) / 2;
            if (log(ord[mid].V) <= t)
                a = mid;
            else
                z = mid;
        }
        take_speed(mask, t - log(ord[a].V) <= log(ord[z].V) - t ? ord[a].v : ord[z].v, &n);
    }
    for (size_t q = 0; n < k && q < nv; q++) /* speeds that share targets: spread evenly */
        take_speed(mask, ord[(q * 7919) % nv].v, &n);
    free(ord);
    return CT_OK;
}

/* A curve sweep's workspace. */
typedef struct {
    ct_curve *first, *later;         /* the bundle's curve; a state's (general path) */
    ct_bundle *work;                 /* the state (general path) */
    double *adv, *u0, *u1, *Wl, *Wu; /* the batched closed forms' nodes and results */
    size_t *slot;                    /* row -> its place in the batched closed forms */
    unsigned char *by_state;         /* per speed: left to the general path */
    unsigned char *check;            /* per speed: its impacts get the closed-form check */
    ct_dyn_work *dw;                 /* the impacts in time */
    ct_dyn_work **forks;             /* dw's forks, for the other threads' speeds */
    int nforks, fork_cap;            /* made, room for */
    double crit0; /* the first curve's critical energy rod by rod, or NaN (ct_critical_by_rods) */
    double dyn_held;    /* bytes each of dw and its forks may hold from earlier blocks */
    size_t done, shown; /* the block's speeds done, and the count last reported as progress */
} sweep_ws;

/* Reports progress (done speeds of the block's) when the count has grown: callers see it rise. */
static void progress_to(const ct_sweep_spec *s, sweep_ws *w, size_t done)
{
    if (s->progress && done > w->shown) {
        w->shown = done;
        s->progress(done, s->nvel, s->progress_ctx);
    }
}

/* Rod evaluations per slice of the closed-form batch when progress is reported (about a tenth
 * of a second on the CI machine): the slices' sums are the batch's, bit for bit. */
#define CT_PROGRESS_SLICE_WORK 67108864.0

/* The fast path's closed forms of m impacts (the check's and W_unload's left to the rods), in
 * slices when progress is reported, the fast speeds (nfast) counted done in proportion. */
static int fast_batch(const ct_bundle *b, const ct_sweep_spec *s, sweep_ws *w, size_t m,
                      size_t nfast)
{
    /* whole multiples of two node chunks (of 64 nodes) per thread: bundle.c shares a slice's
     * chunks among the threads, evenly then */
    const size_t rods = ct_bundle_size(b) ? ct_bundle_size(b) : 1;
    const size_t unit = 128 * (size_t)ct_bundle_threads(b);
    size_t slice = (size_t)floor(CT_PROGRESS_SLICE_WORK / (double)rods / (double)unit + 0.5) * unit;
    slice = slice < unit ? unit : slice;
    if (!s->progress)
        slice = m;
    for (size_t i0 = 0; i0 < m;) {
        const size_t n = m - i0 < 2 * slice ? m - i0 : slice; /* the last one takes the rest */
        int st = ct_bundle_closed_many(b, w->adv + i0, w->u0 + i0, w->u1 + i0, n, w->Wl + i0,
                                       w->Wu + i0, NULL, s->interrupt);
        if (st)
            return st;
        i0 += n;
        progress_to(s, w, (size_t)((double)nfast * (double)i0 / (double)m));
    }
    return CT_OK;
}

/* The fast path's impacts on the first curve: an impact that reaches past the state's earlier
 * maximum U sees the first curve shifted (ct_impact_on_curve), and impacts of equal energy
 * always do, so every impact costs O(log n). A speed with an impact that stays below U is
 * left to the general path (by_state). Impacts go round by round (impact 1 of every speed,
 * then impact 2, ...): a row whose W_unload is left to the rods gets it in one pass over them
 * for its round when the speed's next impact needs it (its energy back to U), else in the
 * batch with the check's nodes (when closed and its speed is checked), *m of them. */
static int fast_impacts(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows, sweep_ws *w,
                        int closed, size_t *m)
{
    const ct_layer *L = ct_bundle_layer(b);
    const double scale = L->l0 * L->E * L->h0;
    const size_t impacts = (size_t)s->impacts, nv = s->nvel;
    *m = 0;
    /* per speed: its maximum U, its energy back there rod by rod (or NaN), whether it goes
     * on; the round's rows for the rods (their nodes, results and speeds) */
    double *U = malloc(7 * (nv + 1) * sizeof(double)), *W_U = U + nv + 1, *ra = W_U + nv + 1,
           *r0 = ra + nv + 1, *r1 = r0 + nv + 1, *rWl = r1 + nv + 1, *rWu = rWl + nv + 1;
    size_t *rv = malloc((nv + 1) * sizeof(size_t));
    unsigned char *on = malloc(nv + 1);
    if (!U || !rv || !on) {
        free(U);
        free(rv);
        free(on);
        return ct_error_set(CT_ENOMEM, "sweep of %zu speeds: out of memory", nv);
    }
    for (size_t v = 0; v < nv; v++) {
        U[v] = -INFINITY;
        W_U[v] = w->crit0;
        on[v] = 1;
    }
    for (size_t i = 0; i < impacts; i++) {
        size_t nr = 0;
        for (size_t v = 0; v < nv; v++) {
            if (v % 4096 == 0 && ct_interrupted(s->interrupt)) {
                free(U);
                free(rv);
                free(on);
                return ct_error_interrupted();
            }
            if (!on[v])
                continue;
            ct_sweep_row *row = &rows[v * impacts + i];
            const double W = s->V_star[v] * s->V_star[v] * scale;
            int rs = ct_impact_on_curve(w->first, L, U[v], W_U[v], W, &s->opts, &row->r);
            if (rs == CT_ESKIPPED) {
                w->by_state[v] = 1;
                on[v] = 0;
                continue;
            }
            if (rs) {
                fail_from(rows, impacts, v, i, rs, ct_error_message());
                on[v] = 0;
                continue;
            }
            row->status = CT_OK;
            row->message[0] = '\0';
            const int lost = isnan(row->r.W_unload), now = lost && i + 1 < impacts;
            if (now) {
                ra[nr] = U[v];
                r0[nr] = row->r.u_contact;
                r1[nr] = row->r.u_max;
                rv[nr++] = v;
            }
            if ((closed && w->check[v]) || (lost && !now)) {
                w->slot[v * impacts + i] = *m;
                w->adv[*m] = U[v];
                w->u0[*m] = row->r.u_contact;
                w->u1[*m] = row->r.u_max;
                (*m)++;
            }
            if (!row->r.elastic) {
                U[v] = row->r.u_max;
                W_U[v] = NAN;
            }
        }
        const int rs =
            nr ? ct_bundle_closed_many(b, ra, r0, r1, nr, rWl, rWu, NULL, s->interrupt) : CT_OK;
        if (rs == CT_EINTR) {
            free(U);
            free(rv);
            free(on);
            return rs;
        }
        for (size_t k = 0; k < nr; k++) {
            const size_t v = rv[k];
            if (rs) {
                fail_from(rows, impacts, v, i, rs, ct_error_message());
                on[v] = 0;
            } else {
                rows[v * impacts + i].r.W_unload = W_U[v] = rWu[k];
            }
        }
    }
    free(U);
    free(rv);
    free(on);
    return CT_OK;
}

/* The fast path's speed v after the batched closed forms: its rows finished (e, the check). */
static void fast_finish(const ct_sweep_spec *s, ct_sweep_row *rows, const sweep_ws *w, int closed,
                        size_t v)
{
    const size_t impacts = (size_t)s->impacts;
    for (size_t i = 0; i < impacts; i++) {
        ct_sweep_row *row = &rows[v * impacts + i];
        if (row->status)
            break;
        if (isnan(row->r.W_unload)) /* left to the batch by fast_impacts */
            row->r.W_unload = w->Wu[w->slot[v * impacts + i]];
        if (closed && w->check[v]) {
            const size_t q = w->slot[v * impacts + i];
            row->r.W_load_closed = w->Wl[q];
            row->r.W_unload_closed = row->r.elastic ? w->Wl[q] : w->Wu[q];
            if (s->opts.rule == CT_QUAD_CLOSED) {
                row->r.W_load = row->r.W_load_closed;
                row->r.W_unload = row->r.W_unload_closed;
            }
        }
        int rs = ct_impact_finish(ct_curve_force(w->first, row->r.u_max), &s->opts, &row->r);
        if (rs) {
            fail_from(rows, impacts, v, i, rs, ct_error_message());
            break;
        }
    }
}

/* Speed v's impacts in time on the first curve and the unloading curve of each maximum, in
 * workspace dw. */
static void fast_speed_dynamics(const ct_sweep_spec *s, ct_sweep_row *rows, ct_dyn_work *dw,
                                double m, size_t v)
{
    const size_t impacts = (size_t)s->impacts;
    ct_dyn_reset(dw);
    for (size_t i = 0; i < impacts; i++) {
        ct_sweep_row *row = &rows[v * impacts + i];
        if (row->status)
            break;
        int rs = ct_dyn_impact_fast(dw, &row->r, m, &row->dyn);
        if (rs) {
            fail_from(rows, impacts, v, i, rs, ct_error_message());
            break;
        }
    }
}

/* Rows below which the fast path's impacts in time stay on one thread: a speed's take a few
 * microseconds, and on the 2-core CI machine (a VM) a team's start costs 0.1 ms to several ms;
 * whole processes with the time columns there: 2000 speeds 8.8 ms on one thread, 13.6 ms on
 * two; 9000 rows 23.5 / 24.1 ms; 20000 rows 53.7 / 46.3 ms (medians, docs/benchmarks.md). The
 * CLI's blocks of whole speeds (16384 rows at most) reach it at any count of impacts. */
#define CT_DYN_PARALLEL_MIN 12288

/* The threads the fast path's impacts in time may take: each thread's unloading curves grow
 * with its impacts, to what the deepest impact of the block needs (ct_dyn_work_thread_bytes);
 * what the workspaces of earlier blocks hold already is theirs. As many threads as the memory
 * available holds (the same rows), and CT_ENOMEM naming the bytes when one thread's would not
 * fit. */
static int dyn_threads(const ct_bundle *b, const ct_sweep_spec *s, const ct_sweep_row *rows,
                       sweep_ws *w, int *team)
{
    double u_max = -INFINITY;
    for (size_t v = 0; v < s->nvel; v++)
        for (size_t i = 0; !w->by_state[v] && i < (size_t)s->impacts; i++) {
            const ct_sweep_row *row = &rows[v * (size_t)s->impacts + i];
            u_max = row->status == CT_OK && row->r.u_max > u_max ? row->r.u_max : u_max;
        }
    if (!(u_max > -INFINITY))
        return CT_OK;
    const double per = ct_dyn_work_thread_bytes(w->dw, u_max),
                 more = per > w->dyn_held ? per - w->dyn_held : 0.0; /* a workspace of before */
    /* the parent and the forks made hold dyn_held already; a new fork holds nothing */
    double need = 0.0;
    for (int t = 0; t < *team; t++)
        need += t <= w->nforks ? more : per;
    if (need < CT_MEMORY_CHECK_MIN)
        return CT_OK;
    const double avail = (double)ct_available_memory();
    if (more > 0.9 * avail)
        return ct_error_set(
            CT_ENOMEM,
            "impact in time on %zu rods: its unloading curves need %.3g GiB, more "
            "than 90 %% of the %.3g GiB of memory available: leave out the time columns, "
            "or take fewer rods",
            ct_bundle_size(b), per / 1073741824.0, avail / 1073741824.0);
    while (*team > 1 && need > 0.9 * avail)
        need -= --*team <= w->nforks ? more : per;
    w->dyn_held = per > w->dyn_held ? per : w->dyn_held;
    return CT_OK;
}

/* The fast path's impacts in time. Every speed starts from the first curve's state, so the
 * speeds are independent: they are shared among the threads, each with its own workspace (a
 * fork of w->dw, kept for the next block), and every row is the same for any thread count. */
static int fast_dynamics(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows,
                         sweep_ws *w)
{
    int st;
    const double m = unit_mass(ct_bundle_layer(b));
    int team = ct_bundle_threads(b);
#ifdef _OPENMP
    if (omp_in_parallel())
        team = 1;
#endif
    if (s->nvel * (size_t)s->impacts < CT_DYN_PARALLEL_MIN)
        team = 1;
    if ((st = dyn_threads(b, s, rows, w, &team)))
        return st;
    if (team - 1 > w->fork_cap) { /* the first block, or more threads than before */
        ct_dyn_work **f = realloc(w->forks, (size_t)(team - 1) * sizeof *f);
        if (f) {
            w->forks = f;
            w->fork_cap = team - 1;
        }
    }
    if (team - 1 > w->fork_cap)
        team = w->fork_cap + 1;
    while (w->nforks < team - 1 && !ct_dyn_work_fork(w->dw, m, &w->forks[w->nforks]))
        w->nforks++;
    if (team > w->nforks + 1)
        team = w->nforks + 1; /* a fork out of memory: fewer threads, the same rows */
#pragma omp parallel num_threads(team) if (team > 1)
    {
        ct_dyn_work *dw = w->dw;
#ifdef _OPENMP
        if (omp_get_thread_num() > 0)
            dw = w->forks[omp_get_thread_num() - 1];
#endif
#pragma omp for schedule(dynamic, 16)
        for (size_t v = 0; v < s->nvel; v++)
            if (!w->by_state[v] && !ct_interrupted(s->interrupt))
                fast_speed_dynamics(s, rows, dw, m, v);
    }
    return ct_interrupted(s->interrupt) ? ct_error_interrupted() : CT_OK;
}

/* The fast path (every impact on the first curve, the closed-form check of all rows in
 * shared passes over the rods). */
static int sweep_fast(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows, sweep_ws *w)
{
    const size_t nrows = s->nvel * (size_t)s->impacts;
    const int closed = s->opts.check || s->opts.rule == CT_QUAD_CLOSED;
    int st;
    /* the batch's nodes: the check's, and any row's W_unload rod by rod */
    if (!(w->adv = malloc((nrows + 1) * sizeof(double))) ||
        !(w->u0 = malloc((nrows + 1) * sizeof(double))) ||
        !(w->u1 = malloc((nrows + 1) * sizeof(double))) ||
        !(w->Wl = malloc((nrows + 1) * sizeof(double))) ||
        !(w->Wu = malloc((nrows + 1) * sizeof(double))) ||
        !(w->slot = malloc((nrows + 1) * sizeof(size_t))))
        return ct_error_set(CT_ENOMEM, "sweep of %zu impacts: out of memory", nrows);
    size_t m, nfast = 0;
    if ((st = fast_impacts(b, s, rows, w, closed, &m)))
        return st;
    for (size_t v = 0; v < s->nvel; v++)
        nfast += !w->by_state[v];
    if ((st = fast_batch(b, s, w, m, nfast)))
        return st;
    for (size_t v = 0; v < s->nvel; v++)
        if (!w->by_state[v])
            fast_finish(s, rows, w, closed, v);
    if (w->dw && (st = fast_dynamics(b, s, rows, w)))
        return st;
    w->done = nfast;
    progress_to(s, w, w->done);
    return CT_OK;
}

/* The general path for the speeds that need it (all of them when not fast): one state
 * carried per speed, its curve rebuilt after every plastic impact. */
static int sweep_by_state(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows,
                          sweep_ws *w, int fast)
{
    const size_t impacts = (size_t)s->impacts, nrows = s->nvel * impacts;
    int st;
    if ((w->dw && (st = ct_dyn_memory_check(b, CT_DYN_BY_STATE, s->impacts))) ||
        (st = ct_curve_alloc(&w->later)) || (st = ct_bundle_clone(&w->work, b)))
        return st;
    for (size_t v = 0; v < s->nvel; v++) {
        if (fast && !w->by_state[v])
            continue;
        for (size_t i = 0; i < impacts; i++)
            fail_row(&rows[v * impacts + i], CT_ESKIPPED, "not run");
        if ((st = speed_by_state(b, w->first, w->later, w->work, s, v, rows, w->dw, w->check)))
            return st;
        if (s->stop_on_error && (st = first_failure(rows, nrows)))
            return st;
        progress_to(s, w, ++w->done);
    }
    return CT_OK;
}

/* The spec's own checks: speeds, impacts and every impact energy. */
static int sweep_valid(const ct_bundle *b, const ct_sweep_spec *s)
{
    int st;
    if ((st = ct_check_speeds(s->V_star, s->nvel)))
        return st;
    if (s->impacts < 1)
        return ct_error_set(CT_EINVAL, "impacts = %ld: must be >= 1", s->impacts);
    const ct_layer *L = ct_bundle_layer(b);
    for (size_t v = 0; v < s->nvel; v++)
        if ((st =
                 ct_energy_check(s->V_star[v] * s->V_star[v] * L->l0 * L->E * L->h0, s->V_star[v])))
            return st;
    return CT_OK;
}

/* What every block of a curve sweep shares: the curve of b's state, the impacts in time
 * prepared on it, and the closed-form check's speeds over the whole spec. */
static int sweep_prepare(const ct_bundle *b, const ct_sweep_spec *s, sweep_ws *w,
                         unsigned char **mask)
{
    int st;
    const ct_layer *L = ct_bundle_layer(b);
    /* the impact in time takes the full curve and more (it grew to 24 GB and was killed by
     * the kernel on fx = fz = 1 + 1e-6, 37 million rods): refused up front, with the figure */
    if (s->dynamics && ((st = ct_dyn_memory_check(b, CT_DYN_SWEEP, s->impacts)) ||
                        (st = ct_dyn_work_alloc(&w->dw))))
        return st;
    size_t events = SIZE_MAX;
    const int lean = use_lean(b, s, &events);
    if (s->curve && !lean) /* the caller's workspace: its arrays are reused */
        w->first = s->curve;
    else if ((st = ct_curve_alloc(&w->first)))
        return st;
    /* a lean curve that cannot be (W not monotone in its rounding) is a full one, unless
     * the lean one was asked for */
    if (lean && (st = ct_curve_build_lean(w->first, b)) != CT_ESKIPPED) {
        if (st)
            return st;
    } else if (lean && s->path == CT_PATH_LEAN) {
        return ct_error_set(CT_EINVAL, "solver.path = lean: this bundle's cumulative work rounds "
                                       "to a sequence that is not monotone: take the full curve "
                                       "(solver.path = curve or auto)");
    } else if ((st = ct_curve_build(w->first, b))) {
        return st;
    }
    if (ct_interrupted(s->interrupt))
        return ct_error_interrupted();
    if (w->dw && (st = ct_dyn_prepare(w->dw, w->first, L)))
        return st;
    w->crit0 = ct_critical_by_rods(b, w->first);
    if (!(*mask = malloc(s->nvel ? s->nvel : 1)))
        return ct_error_set(CT_ENOMEM, "sweep of %zu speeds: out of memory", s->nvel);
    const double W_crit = ct_curve_work(w->first, ct_curve_first_yield(w->first));
    return check_speeds_of(s, ct_bundle_size(b), sqrt(W_crit / (L->l0 * L->E * L->h0)), *mask);
}

/* The per-block arrays of a curve sweep, freed after each block. */
static void sweep_ws_end_block(sweep_ws *w)
{
    free(w->adv);
    free(w->u0);
    free(w->u1);
    free(w->Wl);
    free(w->Wu);
    free(w->slot);
    free(w->by_state);
    free(w->check);
    ct_curve_free(w->later);
    ct_bundle_free(w->work);
    w->adv = w->u0 = w->u1 = w->Wl = w->Wu = NULL;
    w->slot = NULL;
    w->by_state = w->check = NULL;
    w->later = NULL;
    w->work = NULL;
}

static void sweep_ws_free(sweep_ws *w, const ct_sweep_spec *s)
{
    for (int k = 0; k < w->nforks; k++)
        ct_dyn_work_free(w->forks[k]);
    free(w->forks);
    ct_dyn_work_free(w->dw);
    if (w->first != s->curve)
        ct_curve_free(w->first);
    sweep_ws_end_block(w);
}

/* The rows of s's speeds (a block of a sweep, or all of it) on the prepared curve, the check
 * on the speeds mask marks. */
static int sweep_block(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows, sweep_ws *w,
                       const unsigned char *mask)
{
    int st = CT_OK;
    const size_t nrows = s->nvel * (size_t)s->impacts;
    rows_not_run(s, rows);
    w->done = w->shown = 0;
    if (!(w->by_state = calloc(s->nvel ? s->nvel : 1, 1)) ||
        !(w->check = malloc(s->nvel ? s->nvel : 1))) {
        st = ct_error_set(CT_ENOMEM, "sweep of %zu speeds: out of memory", s->nvel);
        goto done;
    }
    memcpy(w->check, mask, s->nvel);
    const int fast =
        !s->observe && (s->opts.rule == CT_QUAD_BREAKPOINTS || s->opts.rule == CT_QUAD_CLOSED);
    if (fast && (st = sweep_fast(b, s, rows, w)))
        goto done;
    int need_state = !fast;
    for (size_t v = 0; v < s->nvel && !need_state; v++)
        need_state = w->by_state[v];
    if (need_state && (st = sweep_by_state(b, s, rows, w, fast)))
        goto done;
    reach_check(b, s, rows);
    if (s->stop_on_error)
        st = first_failure(rows, nrows);
done:
    if (ct_interrupted(s->interrupt))
        st = ct_error_interrupted();
    sweep_ws_end_block(w);
    return st;
}

int ct_sweep(const ct_bundle *b, const ct_sweep_spec *s, ct_sweep_row *rows)
{
    CT_NEED(b);
    int st;
    if (!s || (s->nvel && !rows))
        return ct_error_set(CT_EINVAL, "sweep: NULL spec or rows");
    if ((st = sweep_valid(b, s)))
        return st;
    if (use_rods(b, s)) {
        rows_not_run(s, rows);
        if ((st = sweep_by_rods(b, s, rows)))
            return st;
        if (ct_interrupted(s->interrupt))
            return ct_error_interrupted();
        reach_check(b, s, rows);
        return s->stop_on_error ? first_failure(rows, s->nvel * (size_t)s->impacts) : CT_OK;
    }
    sweep_ws w = {0};
    unsigned char *mask = NULL;
    if (!(st = sweep_prepare(b, s, &w, &mask)))
        st = sweep_block(b, s, rows, &w, mask);
    free(mask);
    sweep_ws_free(&w, s);
    return st;
}

/* A block's progress, reported as the whole sweep's. */
typedef struct {
    const ct_sweep_spec *s;
    size_t offset;
} block_progress;

static void progress_of_block(size_t done, size_t total, void *ctx)
{
    (void)total;
    const block_progress *p = ctx;
    p->s->progress(p->offset + done, p->s->nvel, p->s->progress_ctx);
}

int ct_sweep_blocks(const ct_bundle *b, const ct_sweep_spec *s, size_t block, ct_rows_fn emit,
                    void *ctx)
{
    CT_NEED(b);
    CT_NEED(emit);
    int st;
    if (!s)
        return ct_error_set(CT_EINVAL, "sweep: NULL spec");
    if (s->observe)
        return ct_error_set(CT_EINVAL, "sweep in blocks: observers need the whole sweep");
    if (block < 1)
        return ct_error_set(CT_EINVAL, "sweep in blocks: block = 0 speeds");
    if ((st = sweep_valid(b, s)))
        return st;
    const size_t impacts = (size_t)s->impacts, nb = block < s->nvel ? block : s->nvel;
    ct_sweep_row *rows = malloc((nb ? nb : 1) * impacts * sizeof *rows);
    if (!rows)
        return ct_error_set(CT_ENOMEM, "sweep in blocks of %zu speeds: out of memory", nb);
    const int rods = use_rods(b, s);
    sweep_ws w = {0};
    unsigned char *mask = NULL;
    if (!rods)
        st = sweep_prepare(b, s, &w, &mask);
    for (size_t v0 = 0; !st && v0 < s->nvel; v0 += nb) {
        const size_t n = s->nvel - v0 < nb ? s->nvel - v0 : nb;
        if (ct_interrupted(s->interrupt)) {
            st = ct_error_interrupted();
            break;
        }
        block_progress bp = {s, v0};
        ct_sweep_spec sub = *s;
        sub.V_star = s->V_star + v0;
        sub.nvel = n;
        sub.progress = s->progress ? progress_of_block : NULL;
        sub.progress_ctx = &bp;
        if (rods) {
            rows_not_run(&sub, rows);
            if (!(st = sweep_by_rods(b, &sub, rows))) {
                reach_check(b, &sub, rows);
                if (sub.stop_on_error)
                    st = first_failure(rows, n * impacts);
            }
            if (ct_interrupted(s->interrupt))
                st = ct_error_interrupted();
        } else {
            st = sweep_block(b, &sub, rows, &w, mask + v0);
        }
        if (st == CT_EINTR)
            break;
        if (st && st != CT_ENOMEM) { /* a failed row under stop_on_error: its block is shown */
            const int failed = st;
            for (size_t k = 0; k < n * impacts; k++)
                rows[k].speed += v0;
            char why[512];
            snprintf(why, sizeof why, "%s", ct_error_message());
            emit(rows, n * impacts, ctx);
            st = ct_error_set(failed, "%s", why);
            break;
        }
        for (size_t k = 0; !st && k < n * impacts; k++)
            rows[k].speed += v0;
        if (!st && emit(rows, n * impacts, ctx))
            st = ct_error_set(CT_ESKIPPED, "sweep in blocks: stopped by the caller");
    }
    free(mask);
    free(rows);
    if (!rods)
        sweep_ws_free(&w, s);
    return st;
}
