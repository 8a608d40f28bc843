/* cantact run of a scene with samples: the realisations of [ensemble] (all of them, or the range
 * --realisations a:b) or a curved body's landings (body.landings, or --landings a:b), on one
 * process or shared among MPI ranks and gathered on rank 0, then written by ensemble_out.c after
 * they are converted to the output's units. */
#include "ensemble.h"
#include "args.h"
#include "ensemble_out.h"
#include "ranks.h"
#include "output.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The library's samples in output units: u_max / h0; a failed row's text is its status's. */
static int table_from_samples(ct_ens_table *t, const ct_ensemble_samples *s, double h0,
                              int landings)
{
    if (ct_ens_table_alloc(t, s->first, s->count, s->nrows, landings))
        return -1;
    for (size_t k = 0; k < (size_t)s->count * s->nrows; k++) {
        t->e[k] = s->e[k];
        t->u[k] = s->u_max[k] / h0;
        t->vc[k] = s->V_star_crit[k];
        t->err[k] = s->status[k] ? (char *)ct_strerror(s->status[k]) : NULL;
    }
    memcpy(t->cx, s->fx_clipped, (size_t)s->count * sizeof(uint64_t));
    memcpy(t->cz, s->fz_clipped, (size_t)s->count * sizeof(uint64_t));
    memcpy(t->x, s->x, (size_t)s->count * sizeof(double));
    memcpy(t->y, s->y, (size_t)s->count * sizeof(double));
    return 0;
}

static int parse_range(const char *text, const char *opt, const char *key, uint64_t R, uint64_t *a,
                       uint64_t *b, char *err, size_t errlen)
{
    const char *colon = strchr(text, ':');
    char *end;
    unsigned long long x, y;
    errno = 0;
    if (!colon || !(text[0] >= '0' && text[0] <= '9') || !(colon[1] >= '0' && colon[1] <= '9'))
        goto bad;
    x = strtoull(text, &end, 10);
    if (end != colon || errno)
        goto bad;
    y = strtoull(colon + 1, &end, 10);
    if (*end || errno)
        goto bad;
    if (!(x < y && y <= R)) {
        snprintf(err, errlen, "%s %s: must satisfy 0 <= a < b <= %s = %llu", opt, text, key,
                 (unsigned long long)R);
        return -1;
    }
    *a = x;
    *b = y;
    return 0;
bad:
    snprintf(err, errlen, "%s %s: expected a:b (%s a .. b - 1)", opt, text, opt + 2);
    return -1;
}

typedef struct {
    ct_progress *prog;
} progress_ctx;

static void show_progress(size_t done, size_t total, void *ctx)
{
    (void)total;
    ct_progress *prog = ctx;
    while (prog->done < done)
        ct_progress_step(prog);
}

void ct_cli_samples_spec(const ct_scene *sc, const ct_cli_samples *s, uint64_t first,
                         uint64_t count, ct_ensemble_spec *spec)
{
    *spec = (ct_ensemble_spec){.surface = s->surface,
                               .first = first,
                               .count = count,
                               .V_star = sc->V_star,
                               .nvel = sc->nvel,
                               .impacts = sc->impacts,
                               .opts = sc->opts,
                               .path = sc->path,
                               .stop_on_error = !sc->skip_failed,
                               .threads = sc->threads,
                               .split = sc->split,
                               .body = &sc->body,
                               .scales = sc->scales,
                               .rods = s->rods};
}

/* This rank's samples my_a .. my_b - 1 into *mine (NULL when none); msg gets the error. */
static int run_block(const ct_scene *sc, const ct_cli_samples *samples, uint64_t my_a,
                     uint64_t my_b, ct_ensemble_samples **mine, char *msg, size_t msglen)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    ct_progress prog;
    ct_progress_start(&prog, ct_mpi_rank() == 0 ? (size_t)(my_b - my_a) : 0);
    int st = CT_OK;
    if (my_b > my_a) {
        st = ct_ensemble_samples_alloc(mine, my_a, my_b - my_a, nrows);
        if (!st) {
            ct_ensemble_spec spec;
            ct_cli_samples_spec(sc, samples, my_a, my_b - my_a, &spec);
            spec.progress = ct_mpi_rank() == 0 ? show_progress : NULL;
            spec.progress_ctx = &prog;
            st = ct_ensemble(&spec, *mine);
            /* a failed impact is a sample: rank 0 reports the lowest of all ranks */
            if (st && (*mine)->failed_realisation != UINT64_MAX)
                st = CT_OK;
        }
        if (st)
            snprintf(msg, msglen, "%s", ct_error_message());
    }
    ct_progress_end(&prog);
    return st;
}

/* Rank 0: the samples of every rank (or their failure) into the outputs. */
static int report(ct_ens_outputs *o, const ct_scene *sc, const ct_ensemble_samples *all,
                  const ct_plan_info *info, int st, const char *err, int quiet)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    ct_ens_table t;
    if (st) {
        ct_cli_fail_scene(sc, st, err);
        return ct_cli_status_exit(st);
    }
    if (!sc->skip_failed && all->failed_realisation != UINT64_MAX) {
        /* solver.on_error = stop: the lowest failing realisation, then row */
        const size_t k = (size_t)(all->failed_realisation - all->first) * nrows + all->failed_row;
        ct_cli_fail_scene(sc, all->status[k], all->message);
        return ct_cli_status_exit(all->status[k]);
    }
    if (table_from_samples(&t, all, sc->scales.layer.h0, sc->body.landings != 0)) {
        ct_cli_fail("ensemble: out of memory");
        return EXIT_FAILED;
    }
    t.info = *info;
    int rc = ct_ens_write_outputs(o, sc, &t, quiet);
    const uint64_t n = ct_ensemble_checked(&sc->opts, all->first, all->count);
    const char *of = sc->body.landings ? "landings" : "realisations";
    if (!quiet && rc == EXIT_DONE && isfinite(all->quad_error_max) && n == all->count)
        fprintf(
            stderr,
            "cantact: closed-form check of every one of the %s: max |e - e_closed_form| = %.3g\n",
            of, all->quad_error_max);
    else if (!quiet && rc == EXIT_DONE && isfinite(all->quad_error_max))
        fprintf(stderr,
                "cantact: closed-form check of %llu of %llu %s (those whose index is a "
                "multiple of %d; solver.check = all checks every one): max |e - e_closed_form| = "
                "%.3g\n",
                (unsigned long long)n, (unsigned long long)all->count, of, CT_ENSEMBLE_CHECK_STRIDE,
                all->quad_error_max);
    else if (!quiet && rc == EXIT_DONE && sc->opts.check == CT_CHECK_AUTO && n == 0)
        fprintf(stderr,
                "cantact: closed-form check of none of %s %llu .. %llu (it covers those "
                "whose index is a multiple of %d; solver.check = all checks every one)\n",
                of, (unsigned long long)all->first,
                (unsigned long long)(all->first + all->count - 1), CT_ENSEMBLE_CHECK_STRIDE);
    ct_ens_table_free(&t);
    return rc;
}

int ct_cli_samples_prepare(const ct_scene *sc, ct_cli_samples *s, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    s->landings = sc->body.landings != 0;
    s->count = s->landings ? sc->body.landings : sc->realisations;
    if (!s->landings) {
        ct_surface_random_cantor(sc->surface, &s->surface, NULL);
        snprintf(s->line, sizeof s->line,
                 "random cantor surface, depth %ld (%zu rods per realisation)", s->surface.depth,
                 ((size_t)2 << s->surface.depth) - 1);
        return CT_OK;
    }
    /* landings: the surface's rods as built for the body, not met by it (each landing meets
     * them at its apex) */
    ct_build_request req;
    ct_scene_request(sc, 0, &req);
    int st = ct_surface_build_unmet(sc->surface, &req, &s->rods, &s->info);
    double lo[2], hi[2];
    if (!st)
        st = ct_body_landing_region(&sc->body, &sc->scales, s->rods, lo, hi);
    if (st) {
        snprintf(err, errlen, "%s", ct_error_message());
        ct_cli_samples_free(s);
        return st;
    }
    char line[400], body[200];
    ct_surface_describe(sc->surface, &s->info, line, sizeof line);
    ct_body_describe(&sc->body, body, sizeof body);
    if (!isnan(lo[1]))
        snprintf(s->line, sizeof s->line,
                 "%s %s; landings drawn over x %.6g .. %.6g, y %.6g .. %.6g", line, body, lo[0],
                 hi[0], lo[1], hi[1]);
    else
        snprintf(s->line, sizeof s->line, "%s %s; landings drawn over x %.6g .. %.6g", line, body,
                 lo[0], hi[0]);
    return CT_OK;
}

void ct_cli_samples_free(ct_cli_samples *s)
{
    ct_bundle_free(s->rods);
    s->rods = NULL;
}

int ct_cli_ensemble_run(const ct_scene *sc, int quiet, const char *range)
{
    const int rank = ct_mpi_rank(), size = ct_mpi_size();
    const int landings = sc->body.landings != 0;
    const uint64_t N = landings ? sc->body.landings : sc->realisations;
    char err[1024] = "", msg[300] = "";
    uint64_t a = 0, b = N;
    int rc = EXIT_DONE;
    if (range && parse_range(range, landings ? "--landings" : "--realisations",
                             landings ? "body.landings" : "ensemble.realisations", N, &a, &b, err,
                             sizeof err)) {
        if (rank == 0)
            ct_cli_fail("%s", err);
        return EXIT_USAGE;
    }
    /* a range writes its samples, for cantact merge */
    const unsigned what = range ? (landings ? CT_OUT_LANDINGS : CT_OUT_REALISATIONS) : sc->what;
    ct_ens_outputs o;
    memset(&o, 0, sizeof o);
    int ok = 1;
    int opened = rank == 0 ? ct_ens_open_outputs(&o, sc, what, NULL, 0, err, sizeof err) : 0;
    if (opened == -1)
        ct_cli_fail("%s", err);
    if (opened)
        ok = 0;
    ct_cli_samples samples;
    memset(&samples, 0, sizeof samples);
    if (ok && ct_cli_samples_prepare(sc, &samples, err, sizeof err)) { /* alike on every rank */
        if (rank == 0)
            ct_cli_fail_scene(sc, CT_EINVAL, err);
        ok = 0;
    }
    if (!ct_mpi_bcast_int(ok)) {
        ct_ens_close_outputs(&o);
        ct_cli_samples_free(&samples);
        return EXIT_USAGE;
    }
    /* this rank's block of samples */
    const uint64_t n = b - a;
    const uint64_t my_a = a + n * (uint64_t)rank / (uint64_t)size;
    const uint64_t my_b = a + n * (uint64_t)(rank + 1) / (uint64_t)size;
    const int threads = sc->threads > 0 ? sc->threads : ct_default_threads();
    if (rank == 0 && !quiet)
        fprintf(stderr, "cantact: %s%s %llu..%llu of %llu, %d process(es), %d thread(s) each\n",
                samples.line, landings ? "; landings" : ", realisations", (unsigned long long)a,
                (unsigned long long)(b - 1), (unsigned long long)N, size, threads);
    err[0] = '\0';
    ct_ensemble_samples *mine = NULL, *all = NULL;
    int st = run_block(sc, &samples, my_a, my_b, &mine, msg, sizeof msg);
    const ct_plan_info info = samples.info;
    const long depth = samples.surface.depth;
    ct_cli_samples_free(&samples);
    if (size > 1) {
        st = ct_mpi_gather(mine, st, msg, a, n, sc->nvel * (size_t)sc->impacts, &all, err,
                           sizeof err);
        if (rank == 0 && all)
            all->draws = landings ? 0 : ((uint64_t)2 << depth) - 2;
    } else {
        all = mine;
        mine = NULL;
        snprintf(err, sizeof err, "%s", msg);
    }
    if (rank == 0)
        rc = report(&o, sc, all, &info, st, err, quiet);
    ct_ens_close_outputs(&o);
    ct_ensemble_samples_free(mine);
    ct_ensemble_samples_free(all);
    return ct_mpi_bcast_int(rc);
}
