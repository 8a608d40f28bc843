/* Ensembles of samples: random Cantor realisations (docs/model.md §10) or a curved body's landings
 * on one surface (§14): every sample's rods are built (a realisation) or met (a landing), swept
 * and dropped, its samples stored at its own index; statistics are computed afterwards from
 * the samples in realisation order. So the output depends neither on the thread count nor on
 * the split (whole realisations per thread, or one realisation's rods shared by the threads),
 * nor on how a caller shares realisations among processes and gathers them back.
 *
 * OpenMP here (besides bundle.c and the curve's event sort): the parallel axis of an ensemble
 * is the realisation, which bundle.c knows nothing of. Each iteration owns its bundle and
 * writes only its own realisation's slots; nothing is reduced across threads but integer
 * counts and the lowest failing realisation (a minimum: exact in any order). */
#include "internal.h"
#include "body/body.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

int ct_ensemble_samples_alloc(ct_ensemble_samples **out, uint64_t first, uint64_t count,
                              size_t nrows)
{
    *out = NULL;
    if (count == 0 || nrows == 0)
        return ct_error_set(CT_EINVAL, "ensemble samples: %llu realisations of %zu rows: need >= 1",
                            (unsigned long long)count, nrows);
    if (count > SIZE_MAX / nrows / (3 * sizeof(double) + sizeof(int)))
        return ct_error_set(CT_ENOMEM,
                            "ensemble samples: %llu realisations x %zu rows cannot be "
                            "addressed",
                            (unsigned long long)count, nrows);
    const size_t n = (size_t)count * nrows;
    const double need = (double)n * (3 * sizeof(double) + sizeof(int));
    if (need > 0.5 * (double)ct_available_memory())
        return ct_error_set(CT_ENOMEM,
                            "ensemble samples: %llu realisations x %zu rows need %.3g GiB, more "
                            "than half the memory available",
                            (unsigned long long)count, nrows, need / 1073741824.0);
    ct_ensemble_samples *s = calloc(1, sizeof *s);
    if (!s)
        return ct_error_set(CT_ENOMEM, "ensemble samples: out of memory");
    s->first = first;
    s->count = count;
    s->nrows = nrows;
    s->e = malloc(n * sizeof(double));
    s->u_max = malloc(n * sizeof(double));
    s->V_star_crit = malloc(n * sizeof(double));
    s->status = malloc(n * sizeof(int));
    s->fx_clipped = calloc((size_t)count, sizeof(uint64_t));
    s->fz_clipped = calloc((size_t)count, sizeof(uint64_t));
    s->x = malloc((size_t)count * sizeof(double));
    s->y = malloc((size_t)count * sizeof(double));
    if (!s->e || !s->u_max || !s->V_star_crit || !s->status || !s->fx_clipped || !s->fz_clipped ||
        !s->x || !s->y) {
        ct_ensemble_samples_free(s);
        return ct_error_set(CT_ENOMEM, "ensemble samples: out of memory");
    }
    for (size_t k = 0; k < n; k++) {
        s->e[k] = s->u_max[k] = s->V_star_crit[k] = NAN;
        s->status[k] = CT_ESKIPPED;
    }
    for (uint64_t r = 0; r < count; r++)
        s->x[r] = s->y[r] = NAN;
    *out = s;
    return CT_OK;
}

void ct_ensemble_samples_free(ct_ensemble_samples *s)
{
    if (!s)
        return;
    free(s->e);
    free(s->u_max);
    free(s->V_star_crit);
    free(s->status);
    free(s->fx_clipped);
    free(s->fz_clipped);
    free(s->x);
    free(s->y);
    free(s);
}

/* The lowest failure seen by one worker (realisations come to a worker in increasing order). */
typedef struct {
    uint64_t realisation; /* UINT64_MAX: none */
    size_t row;
    int status;
    char message[240];
} failure;

/* What a worker keeps from one realisation to the next: its bundle (refilled in place) and
 * its curve (rebuilt in place), so that a realisation allocates nothing: on a VM, fresh pages
 * for each realisation's ~340 bytes per rod cost twice the computation. */
typedef struct {
    ct_bundle *b;
    ct_curve *curve;
    const ct_body_site *site; /* landings: the surface prepared once for every apex */
    double lo[2], hi[2];      /* landings: the region the apexes are drawn from */
} workspace;

/* The rods sample first + slot is swept on, into *met: a realisation built (or refilled) in
 * ws->b and, under a curved body, met by it (a copy: the realisation's own rods stay to be
 * refilled), as ct_surface_build shifts a realisation's; or a landing: the site met at the
 * landing's apex (stored in out). *met is ws->b or the caller's to free. */
static int sample_rods(const ct_ensemble_spec *sp, ct_ensemble_samples *out, uint64_t slot,
                       int threads, workspace *ws, ct_bundle **met)
{
    const uint64_t r = out->first + slot;
    int st;
    *met = NULL;
    if (sp->rods) {
        double pos[2];
        ct_body_landing(ws->lo, ws->hi, sp->body->seed, r, pos);
        out->x[slot] = pos[0];
        out->y[slot] = pos[1];
        if ((st = ct_body_site_meet(ws->site, pos, met)))
            return st;
        ct_bundle_set_threads(*met, threads);
        return CT_OK;
    }
    if (ws->b)
        st = ct_random_cantor_refill(ws->b, &sp->surface, r);
    else
        st = ct_random_cantor_bundle(&ws->b, &sp->surface, r, threads);
    if (st)
        return st;
    *met = ws->b;
    if (sp->body && ct_body_curved(sp->body)) {
        if ((st = ct_bundle_clone(met, ws->b)))
            return st;
        if ((st = ct_body_apply(sp->body, &sp->scales, met, NULL))) {
            ct_bundle_free(*met);
            *met = NULL;
            return st;
        }
        ct_bundle_set_threads(*met, threads);
    }
    return CT_OK;
}

/* Builds realisation first + slot with `threads` threads, sweeps it and stores its samples.
 * Returns a status only for what ends the ensemble (memory); failed impacts are samples. */
static int run_one(const ct_ensemble_spec *sp, ct_ensemble_samples *out, uint64_t slot, int threads,
                   ct_sweep_row *rows, failure *fail, double *quad_error, workspace *ws)
{
    const uint64_t r = out->first + slot;
    const size_t nrows = out->nrows;
    int st;
    if (!ws->curve && (st = ct_curve_alloc(&ws->curve)))
        return st;
    ct_bundle *met;
    if ((st = sample_rods(sp, out, slot, threads, ws, &met)))
        return st;
    ct_sweep_spec sw = {.V_star = sp->V_star,
                        .nvel = sp->nvel,
                        .impacts = sp->impacts,
                        .opts = sp->opts,
                        .path = sp->path,
                        .curve = ws->curve,
                        .interrupt = sp->interrupt};
    if (sp->opts.check == CT_CHECK_AUTO && r % CT_ENSEMBLE_CHECK_STRIDE != 0)
        sw.opts.check = CT_CHECK_NONE; /* the check's stride over the realisations */
    st = ct_sweep(met, &sw, rows);
    if (met != ws->b)
        ct_bundle_free(met);
    uint64_t draws;
    if (!sp->rods)
        ct_random_cantor_clipped(ws->b, &out->fx_clipped[slot], &out->fz_clipped[slot], &draws);
    if (st)
        return st;
    for (size_t q = 0; q < nrows; q++) {
        const size_t k = (size_t)slot * nrows + q;
        const ct_sweep_row *row = &rows[q];
        out->status[k] = row->status;
        if (row->status == CT_OK) {
            if (row->r.quad_error > *quad_error ||
                (isnan(*quad_error) && !isnan(row->r.quad_error)))
                *quad_error = row->r.quad_error;
            out->e[k] = row->r.e;
            out->u_max[k] = row->r.u_max;
            out->V_star_crit[k] = row->r.V_star_crit;
        } else if (row->status != CT_ESKIPPED && fail->realisation == UINT64_MAX) {
            fail->realisation = r;
            fail->row = q;
            fail->status = row->status;
            snprintf(fail->message, sizeof fail->message, "%s %llu, V* = %.17g, impact %ld: %s",
                     sp->rods ? "landing" : "realisation", (unsigned long long)r, row->V_star,
                     row->impact, row->message);
        }
    }
    return CT_OK;
}

uint64_t ct_ensemble_checked(const ct_impact_opts *opts, uint64_t first, uint64_t count)
{
    if (!opts || opts->check == CT_CHECK_NONE)
        return opts && opts->rule == CT_QUAD_CLOSED ? count : 0;
    if (opts->check != CT_CHECK_AUTO || opts->rule == CT_QUAD_CLOSED)
        return count;
    if (count == 0)
        return 0;
    /* the multiples of the stride up to the last realisation less those below first (up to
     * x: x / stride + 1); a range past UINT64_MAX ends there */
    const uint64_t k = CT_ENSEMBLE_CHECK_STRIDE,
                   last = count - 1 > UINT64_MAX - first ? UINT64_MAX : first + (count - 1);
    return (last / k + 1) - (first == 0 ? 0 : (first - 1) / k + 1);
}

static int check_spec(const ct_ensemble_spec *sp, const ct_ensemble_samples *out)
{
    int st;
    if (!sp || !out)
        return ct_error_set(CT_EINVAL, "ensemble: NULL spec or samples");
    if (sp->rods && !ct_body_curved(sp->body))
        return ct_error_set(CT_EINVAL, "body.landings: the flat strip lands everywhere alike: "
                                       "landings need a curved body (body.shape)");
    if (!sp->rods && (st = ct_random_cantor_validate(&sp->surface)))
        return st;
    if (sp->count == 0 || sp->first > UINT64_MAX - sp->count)
        return ct_error_set(CT_EINVAL, "ensemble: %s %llu + %llu: need count >= 1",
                            sp->rods ? "landings" : "realisations", (unsigned long long)sp->first,
                            (unsigned long long)sp->count);
    if (sp->nvel == 0 || !sp->V_star)
        return ct_error_set(CT_EINVAL, "ensemble: no speeds");
    if (sp->impacts < 1)
        return ct_error_set(CT_EINVAL, "impacts = %ld: must be >= 1", sp->impacts);
    if (out->first != sp->first || out->count != sp->count ||
        out->nrows != sp->nvel * (size_t)sp->impacts)
        return ct_error_set(CT_EINVAL,
                            "ensemble: samples allocated for realisations %llu + %llu "
                            "of %zu rows, spec asks %llu + %llu of %zu",
                            (unsigned long long)out->first, (unsigned long long)out->count,
                            out->nrows, (unsigned long long)sp->first,
                            (unsigned long long)sp->count, sp->nvel * (size_t)sp->impacts);
    return CT_OK;
}

/* One ensemble while it runs: what its workers share. */
typedef struct {
    const ct_ensemble_spec *sp;
    ct_ensemble_samples *out;
    int workers, by_realisation;
    failure *fails;     /* per worker */
    ct_sweep_row *rows; /* nrows per worker */
    workspace *ws;      /* per worker */
    /* under stop_on_error, realisations above the lowest failure seen are not started: every
     * realisation below it still is, so the failure reported is the lowest of all */
    uint64_t stop_at, done;
    int fatal;
    char fatal_msg[256];
} ensemble_run;

/* Every realisation of the ensemble, by the workers (each at its own slots). */
static void run_all(ensemble_run *e)
{
    const ct_ensemble_spec *sp = e->sp;
    ct_ensemble_samples *out = e->out;
    const size_t nrows = out->nrows;
    const ptrdiff_t count = (ptrdiff_t)sp->count;
#pragma omp parallel for schedule(dynamic, 1) num_threads(e->workers) if (e->workers > 1)
    for (ptrdiff_t slot = 0; slot < count; slot++) {
        int w = 0;
#ifdef _OPENMP
        w = omp_get_thread_num();
#endif
        uint64_t limit, r = out->first + (uint64_t)slot;
        int stop;
#pragma omp atomic read
        limit = e->stop_at;
#pragma omp atomic read
        stop = e->fatal;
        if (stop || r > limit || ct_interrupted(sp->interrupt))
            continue;
        double qe = NAN;
        int s = run_one(sp, out, (uint64_t)slot, e->by_realisation ? 1 : sp->threads,
                        e->rows + (size_t)w * nrows, &e->fails[w], &qe, &e->ws[w]);
#pragma omp critical(ct_ensemble_state)
        {
            if (s && !e->fatal) {
#pragma omp atomic write
                e->fatal = s;
                snprintf(e->fatal_msg, sizeof e->fatal_msg, "%s %llu: %s",
                         sp->rods ? "landing" : "realisation", (unsigned long long)r,
                         ct_error_message());
            }
            if (sp->stop_on_error && e->fails[w].realisation < e->stop_at) {
#pragma omp atomic write
                e->stop_at = e->fails[w].realisation;
            }
            if (qe > out->quad_error_max || (isnan(out->quad_error_max) && !isnan(qe)))
                out->quad_error_max = qe; /* a maximum: exact in any order */
            e->done++;
            if (sp->progress)
                sp->progress((size_t)e->done, (size_t)sp->count, sp->progress_ctx);
        }
    }
}

/* The lowest failing realisation of all workers into out (and, under stop_on_error, its
 * status). */
static int lowest_failure(const ensemble_run *e)
{
    const failure *lowest = NULL;
    for (int w = 0; w < e->workers; w++)
        if (e->fails[w].realisation != UINT64_MAX &&
            (!lowest || e->fails[w].realisation < lowest->realisation))
            lowest = &e->fails[w];
    if (!lowest)
        return CT_OK;
    e->out->failed_realisation = lowest->realisation;
    e->out->failed_row = lowest->row;
    snprintf(e->out->message, sizeof e->out->message, "%s", lowest->message);
    return e->sp->stop_on_error ? ct_error_set(lowest->status, "%s", lowest->message) : CT_OK;
}

int ct_ensemble(const ct_ensemble_spec *sp, ct_ensemble_samples *out)
{
    int st;
    if ((st = check_spec(sp, out)))
        return st;
    const size_t nrows = out->nrows;
    /* landings: the surface prepared once (its rods read, its copies laid out), met at each
     * apex by every worker */
    ct_body_site *site = NULL;
    double lo[2] = {NAN, NAN}, hi[2] = {NAN, NAN};
    if (sp->rods && ((st = ct_body_site_new(sp->body, &sp->scales, sp->rods, &site)) ||
                     (st = ct_body_site_region(site, lo, hi)))) {
        ct_body_site_free(site);
        return st;
    }
    const size_t rods = sp->rods ? ct_bundle_size(sp->rods) : ((size_t)2 << sp->surface.depth) - 1;
    const int team = sp->threads > 0 ? sp->threads : ct_default_threads();
    ensemble_run e = {.sp = sp, .out = out, .stop_at = UINT64_MAX};
    e.by_realisation =
        sp->split == CT_SPLIT_REALISATIONS || (sp->split == CT_SPLIT_AUTO && team > 1 &&
                                               sp->count >= 2 && rods <= CT_ENSEMBLE_SPLIT_RODS);
    e.workers = e.by_realisation ? team : 1;
    out->draws = sp->rods ? 0 : rods - 1;
    out->message[0] = '\0';
    out->failed_realisation = UINT64_MAX;
    out->failed_row = 0;
    out->quad_error_max = NAN;

    e.fails = malloc((size_t)e.workers * sizeof *e.fails);
    e.rows = malloc((size_t)e.workers * nrows * sizeof *e.rows);
    e.ws = calloc((size_t)e.workers, sizeof *e.ws);
    if (!e.fails || !e.rows || !e.ws) {
        free(e.fails);
        free(e.rows);
        free(e.ws);
        ct_body_site_free(site);
        return ct_error_set(CT_ENOMEM, "ensemble: out of memory");
    }
    for (int w = 0; w < e.workers; w++) {
        e.fails[w].realisation = UINT64_MAX;
        e.ws[w].site = site;
        memcpy(e.ws[w].lo, lo, sizeof lo);
        memcpy(e.ws[w].hi, hi, sizeof hi);
    }
    run_all(&e);
    free(e.rows);
    for (int k = 0; k < e.workers; k++) {
        ct_bundle_free(e.ws[k].b);
        ct_curve_free(e.ws[k].curve);
    }
    free(e.ws);
    ct_body_site_free(site);
    st = ct_interrupted(sp->interrupt) ? ct_error_interrupted()
         : e.fatal                     ? ct_error_set(e.fatal, "%s", e.fatal_msg)
                                       : lowest_failure(&e);
    free(e.fails);
    return st;
}

/* ---- statistics ---- */

double ct_quantile_sorted(const double *sorted, size_t n, double p)
{
    const double h = (double)(n - 1) * p;
    const double fl = floor(h);
    const size_t i = (size_t)fl;
    if (i + 1 >= n)
        return sorted[n - 1];
    return sorted[i] + (h - fl) * (sorted[i + 1] - sorted[i]);
}

int ct_sample_stats(const double *x, size_t n, size_t stride, double *work, ct_stats *out)
{
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (!isnan(x[k * stride]))
            work[m++] = x[k * stride];
    if (m == 0)
        return ct_error_set(CT_EINVAL, "statistics: none of %zu samples is a number", n);
    double s = 0.0, c = 0.0;
    for (size_t k = 0; k < m; k++)
        ct_add_comp(&s, &c, work[k]); /* compensated, in the order given */
    const double mean = (s + c) / (double)m;
    s = c = 0.0;
    for (size_t k = 0; k < m; k++) /* two passes: no cancellation of sum x^2 - n mean^2 */
        ct_add_comp(&s, &c, (work[k] - mean) * (work[k] - mean));
    out->n = m;
    out->mean = mean;
    out->sd = m > 1 ? sqrt((s + c) / (double)(m - 1)) : NAN;
    out->sem = m > 1 ? out->sd / sqrt((double)m) : NAN;
    qsort(work, m, sizeof(double), ct_cmp_double);
    out->q05 = ct_quantile_sorted(work, m, 0.05);
    out->q50 = ct_quantile_sorted(work, m, 0.5);
    out->q95 = ct_quantile_sorted(work, m, 0.95);
    return CT_OK;
}
