/* Ensembles in the CLI. A run computes the samples of its realisations (all of [ensemble]
 * realisations, or the range --realisations a:b), on one process or shared among MPI ranks
 * and gathered on rank 0; the statistics are computed from the samples in realisation order,
 * after they are converted to the output's units. A run's realisations CSV prints every
 * sample round-trip exact (%.17g), so `cantact merge` reads partial outputs back into the very
 * same numbers and writes the same bytes as one run over all realisations. */
#include "ensemble.h"
#include "args.h"
#include "ranks.h"
#include "number.h"
#include "output.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int status_exit(int st)
{
    return ct_cli_status_exit(st);
}

static void fail_line(const char *msg)
{
    fprintf(stderr, "cantact: %s\n", msg);
}

/* ---- a single realisation as a run's surface ---- */

/* ---- samples in the output's units ---- */

typedef struct {
    uint64_t first, count;
    size_t nrows;
    double *e, *u, *vc; /* e, u_max / h0, V*_c: [r * nrows + q], NaN where failed */
    char **err;         /* a failed row's error text (NULL: computed) */
    int owns_err;       /* merge: the texts were read and are freed */
    uint64_t *cx, *cz;  /* clipped ratios per realisation */
} table;

static void table_free(table *t)
{
    if (t->err && t->owns_err)
        for (size_t k = 0; k < t->count * t->nrows; k++)
            free(t->err[k]);
    free(t->e);
    free(t->u);
    free(t->vc);
    free(t->err);
    free(t->cx);
    free(t->cz);
    memset(t, 0, sizeof *t);
}

static int table_alloc(table *t, uint64_t first, uint64_t count, size_t nrows)
{
    memset(t, 0, sizeof *t);
    t->first = first;
    t->count = count;
    t->nrows = nrows;
    const size_t n = (size_t)count * nrows;
    t->e = malloc(n * sizeof(double));
    t->u = malloc(n * sizeof(double));
    t->vc = malloc(n * sizeof(double));
    t->err = calloc(n, sizeof(char *));
    t->cx = calloc((size_t)count, sizeof(uint64_t));
    t->cz = calloc((size_t)count, sizeof(uint64_t));
    if (!t->e || !t->u || !t->vc || !t->err || !t->cx || !t->cz) {
        table_free(t);
        return -1;
    }
    return 0;
}

/* The library's samples in output units: u_max / h0; a failed row's text is its status's. */
static int table_from_samples(table *t, const ct_ensemble_samples *s, double h0)
{
    if (table_alloc(t, s->first, s->count, s->nrows))
        return -1;
    for (size_t k = 0; k < (size_t)s->count * s->nrows; k++) {
        t->e[k] = s->e[k];
        t->u[k] = s->u_max[k] / h0;
        t->vc[k] = s->V_star_crit[k];
        t->err[k] = s->status[k] ? (char *)ct_strerror(s->status[k]) : NULL;
    }
    memcpy(t->cx, s->fx_clipped, (size_t)s->count * sizeof(uint64_t));
    memcpy(t->cz, s->fz_clipped, (size_t)s->count * sizeof(uint64_t));
    return 0;
}

/* ---- writers ---- */

static void put_field(FILE *f, double x)
{
    fputc(',', f);
    if (isfinite(x))
        ct_put_double(f, x);
}

static const char *realisations_header(int skip)
{
    return skip ? "realisation,impact,V_star,u_max_over_h0,e,V_star_crit,fx_clipped,fz_clipped,"
                  "error"
                : "realisation,impact,V_star,u_max_over_h0,e,V_star_crit,fx_clipped,fz_clipped";
}

/* What identifies a part's scene: its surface (kind, ratios, layer, depth, seed, spreads) and
 * its error mode; the first line of a realisations CSV, checked by cantact merge. */
static void identity(const ct_scene *sc, char *buf, size_t len)
{
    ct_random_cantor rc;
    ct_surface_random_cantor(sc->surface, &rc, NULL);
    ct_plan_info info = {.depth = rc.depth, .rods = ((size_t)2 << rc.depth) - 1};
    char line[600];
    ct_surface_table_line(sc->surface, &info, line, sizeof line);
    snprintf(buf, len, "# realisations of surface = %s; impacts %ld; solver.on_error = %s", line,
             sc->impacts, sc->skip_failed ? "skip" : "stop");
}

static void write_realisations(FILE *f, const ct_scene *sc, const table *t)
{
    const size_t impacts = (size_t)sc->impacts;
    for (uint64_t r = 0; r < t->count; r++)
        for (size_t q = 0; q < t->nrows; q++) {
            const size_t k = (size_t)r * t->nrows + q;
            fprintf(f, "%llu,%zu,", (unsigned long long)(t->first + r), q % impacts + 1);
            ct_put_double(f, sc->V_star[q / impacts]);
            put_field(f, t->u[k]);
            put_field(f, t->e[k]);
            put_field(f, t->vc[k]);
            fprintf(f, ",%llu,%llu", (unsigned long long)t->cx[r], (unsigned long long)t->cz[r]);
            if (sc->skip_failed) {
                fputc(',', f);
                if (t->err[k]) {
                    fputc('"', f);
                    for (const char *m = t->err[k]; *m; m++)
                        fputc(*m == '"' ? '\'' : *m, f);
                    fputc('"', f);
                }
            }
            fputc('\n', f);
        }
}

static const char *const stat_names[] = {"mean", "sd", "sem", "q05", "q50", "q95"};

static void write_ensemble_header(FILE *f)
{
    static const char *const quantities[] = {"e", "u_max_over_h0", "V_star_crit"};
    fputs("impact,V_star,realisations", f);
    for (int q = 0; q < 3; q++)
        for (int s = 0; s < 6; s++)
            fprintf(f, ",%s_%s", quantities[q], stat_names[s]);
    fputs(",e_deterministic\n", f);
}

/* One row per speed and impact: the statistics over the realisations in realisation order,
 * and e of the deterministic surface (NaN: it failed). *sem_max gets the largest standard
 * error of mean e, *at its row. */
static int write_ensemble(FILE *f, const ct_scene *sc, const table *t, const double *e_det,
                          double *sem_max, size_t *at)
{
    const size_t impacts = (size_t)sc->impacts;
    double *work = malloc((size_t)t->count * sizeof(double));
    if (!work)
        return CT_ENOMEM;
    *sem_max = NAN;
    *at = 0;
    for (size_t q = 0; q < t->nrows; q++) {
        const double *cols[3] = {t->e + q, t->u + q, t->vc + q};
        ct_stats st[3];
        int ok[3];
        for (int c = 0; c < 3; c++)
            ok[c] = ct_sample_stats(cols[c], (size_t)t->count, t->nrows, work, &st[c]) == CT_OK;
        fprintf(f, "%zu,", q % impacts + 1);
        ct_put_double(f, sc->V_star[q / impacts]);
        fprintf(f, ",%zu", ok[0] ? st[0].n : (size_t)0);
        for (int c = 0; c < 3; c++) {
            const double v[6] = {st[c].mean, st[c].sd, st[c].sem, st[c].q05, st[c].q50, st[c].q95};
            for (int s = 0; s < 6; s++)
                put_field(f, ok[c] ? v[s] : NAN);
        }
        put_field(f, e_det[q]);
        fputc('\n', f);
        if (ok[0] && (st[0].sem > *sem_max || (isnan(*sem_max) && !isnan(st[0].sem)))) {
            *sem_max = st[0].sem;
            *at = q;
        }
    }
    free(work);
    return CT_OK;
}

/* e of the deterministic surface at the same centres and depth (stage rods: the same rods
 * as spread 0, merged), for every speed and impact; NaN where an impact fails. */
static int deterministic_e(const ct_scene *sc, double *e_det)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    ct_random_cantor rc;
    ct_bundle *b;
    int st = ct_surface_random_cantor(sc->surface, &rc, NULL);
    if (!st)
        st = ct_cantor_bundle(&b, &rc.params, CT_REP_STAGES, rc.depth, INFINITY);
    if (st)
        return st;
    ct_sweep_row *rows = malloc(nrows * sizeof *rows);
    if (!rows) {
        ct_bundle_free(b);
        return CT_ENOMEM;
    }
    ct_bundle_set_threads(b, sc->threads);
    ct_sweep_spec spec = {.V_star = sc->V_star,
                          .nvel = sc->nvel,
                          .impacts = sc->impacts,
                          .opts = sc->opts,
                          .path = sc->path};
    st = ct_sweep(b, &spec, rows);
    for (size_t q = 0; q < nrows; q++)
        e_det[q] = !st && rows[q].status == CT_OK ? rows[q].r.e : NAN;
    free(rows);
    ct_bundle_free(b);
    return st;
}

/* The outputs of an ensemble: the statistics (FILE) and the samples (FILE, or
 * FILE_realisations when both are written). */
typedef struct {
    ct_out ens, real;
    int opened_ens, opened_real;
    char *real_path;
} outputs;

/* Opens the outputs: -1 with the message in err, -2 when it was said already (an output
 * that is an input: the scene, or one of parts, nparts of them). */
static int open_outputs(outputs *o, const ct_scene *sc, unsigned what, const char *const *parts,
                        size_t nparts, char *err, size_t errlen)
{
    memset(o, 0, sizeof *o);
    const int both = (what & CT_OUT_ENSEMBLE) && (what & CT_OUT_REALISATIONS);
    if (both && !strcmp(sc->output, "-")) {
        snprintf(err, errlen,
                 "output.what names several outputs: set output.file (or -o FILE) to a path");
        return -1;
    }
    if (what & CT_OUT_REALISATIONS) {
        o->real_path = both ? ct_cli_derived_path(sc->output, "realisations") : strdup(sc->output);
        if (!o->real_path) {
            snprintf(err, errlen, "out of memory");
            return -1;
        }
    }
    const char *paths[2] = {(what & CT_OUT_ENSEMBLE) ? sc->output : NULL, o->real_path};
    if (ct_cli_outputs_not_inputs(sc, paths, 2, parts, nparts) >= 0)
        return -2;
    if (what & CT_OUT_ENSEMBLE) {
        if (ct_out_open(&o->ens, sc->output, err, errlen))
            return -1;
        o->opened_ens = 1;
    }
    if (what & CT_OUT_REALISATIONS) {
        if (ct_out_open(&o->real, o->real_path, err, errlen))
            return -1;
        o->opened_real = 1;
    }
    return 0;
}

static void close_outputs(outputs *o)
{
    if (o->opened_ens)
        ct_out_abort(&o->ens);
    if (o->opened_real)
        ct_out_abort(&o->real);
    free(o->real_path);
    memset(o, 0, sizeof *o);
}

/* Writes what was asked from the samples and commits. Returns an exit status. */
static int write_outputs(outputs *o, const ct_scene *sc, const table *t, int quiet)
{
    char err[512];
    if (o->opened_real) {
        char id[800];
        identity(sc, id, sizeof id);
        fprintf(o->real.f, "%s\n%s\n", id, realisations_header(sc->skip_failed));
        write_realisations(o->real.f, sc, t);
    }
    double sem_max = NAN;
    size_t at = 0, det_empty = 0;
    char det_why[300] = "";
    if (o->opened_ens) {
        double *e_det = malloc(t->nrows * sizeof(double));
        int st = e_det ? deterministic_e(sc, e_det) : CT_ENOMEM;
        if (e_det && st) { /* the reference failed as a whole: its column stays empty */
            snprintf(det_why, sizeof det_why, "%s", ct_error_message());
            for (size_t q = 0; q < t->nrows; q++)
                e_det[q] = NAN;
        }
        for (size_t q = 0; e_det && q < t->nrows; q++)
            det_empty += isnan(e_det[q]);
        write_ensemble_header(o->ens.f);
        st = e_det ? write_ensemble(o->ens.f, sc, t, e_det, &sem_max, &at) : CT_ENOMEM;
        free(e_det);
        if (st) {
            fail_line("ensemble statistics: out of memory");
            return EXIT_FAILED;
        }
    }
    ct_out *outs[2];
    size_t nouts = 0;
    if (o->opened_ens)
        outs[nouts++] = &o->ens;
    if (o->opened_real)
        outs[nouts++] = &o->real;
    o->opened_ens = o->opened_real = 0; /* published together or dropped together */
    if (ct_out_commit_all(outs, nouts, err, sizeof err)) {
        fail_line(err);
        return EXIT_USAGE;
    }
    if (!quiet) {
        uint64_t cx = 0, cz = 0;
        size_t failed = 0;
        for (uint64_t r = 0; r < t->count; r++) {
            cx += t->cx[r];
            cz += t->cz[r];
        }
        for (size_t k = 0; k < (size_t)t->count * t->nrows; k++)
            failed += t->err[k] != NULL;
        ct_random_cantor rc;
        ct_surface_random_cantor(sc->surface, &rc, NULL);
        const double draws = (double)t->count * (double)(((uint64_t)2 << rc.depth) - 2);
        fprintf(stderr,
                "cantact: ratios clipped into the valid ranges: fx %llu of %.0f draws (%.3g %%), "
                "fz %llu (%.3g %%)\n",
                (unsigned long long)cx, draws, draws > 0 ? 100.0 * (double)cx / draws : 0.0,
                (unsigned long long)cz, draws > 0 ? 100.0 * (double)cz / draws : 0.0);
        if (isfinite(sem_max))
            fprintf(stderr,
                    "cantact: standard error of mean e over %llu realisations: at most %.3g "
                    "(V* = %g, impact %zu); it falls as 1/sqrt(realisations)\n",
                    (unsigned long long)t->count, sem_max, sc->V_star[at / (size_t)sc->impacts],
                    at % (size_t)sc->impacts + 1);
        if (failed)
            fprintf(stderr,
                    "cantact: %zu of %zu impacts failed or not run (left out of the "
                    "statistics)\n",
                    failed, (size_t)t->count * t->nrows);
        if (det_why[0])
            fprintf(stderr, "cantact: ensemble: e_deterministic left empty: %s\n", det_why);
        else if (det_empty)
            fprintf(stderr,
                    "cantact: ensemble: e_deterministic empty in %zu of %zu rows (the "
                    "deterministic surface's impact failed or was not run)\n",
                    det_empty, t->nrows);
    }
    return EXIT_DONE;
}

/* ---- run ---- */

static int parse_range(const char *text, uint64_t R, uint64_t *a, uint64_t *b, char *err,
                       size_t errlen)
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
        snprintf(err, errlen,
                 "--realisations %s: must satisfy 0 <= a < b <= ensemble.realisations = %llu", text,
                 (unsigned long long)R);
        return -1;
    }
    *a = x;
    *b = y;
    return 0;
bad:
    snprintf(err, errlen, "--realisations %s: expected a:b (realisations a .. b - 1)", text);
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

/* This rank's realisations my_a .. my_b - 1 into *mine (NULL when none); msg gets the error. */
static int run_block(const ct_scene *sc, const ct_random_cantor *surface, uint64_t my_a,
                     uint64_t my_b, ct_ensemble_samples **mine, char *msg, size_t msglen)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    ct_progress prog;
    ct_progress_start(&prog, ct_mpi_rank() == 0 ? (size_t)(my_b - my_a) : 0);
    int st = CT_OK;
    if (my_b > my_a) {
        st = ct_ensemble_samples_alloc(mine, my_a, my_b - my_a, nrows);
        if (!st) {
            ct_ensemble_spec spec = {.surface = *surface,
                                     .first = my_a,
                                     .count = my_b - my_a,
                                     .V_star = sc->V_star,
                                     .nvel = sc->nvel,
                                     .impacts = sc->impacts,
                                     .opts = sc->opts,
                                     .path = sc->path,
                                     .stop_on_error = !sc->skip_failed,
                                     .threads = sc->threads,
                                     .split = sc->split,
                                     .progress = ct_mpi_rank() == 0 ? show_progress : NULL,
                                     .progress_ctx = &prog};
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
static int report(outputs *o, const ct_scene *sc, const ct_ensemble_samples *all, int st,
                  const char *err, int quiet)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    table t;
    if (st) {
        fail_line(err);
        return status_exit(st);
    }
    if (!sc->skip_failed && all->failed_realisation != UINT64_MAX) {
        /* solver.on_error = stop: the lowest failing realisation, then row */
        const size_t k = (size_t)(all->failed_realisation - all->first) * nrows + all->failed_row;
        fail_line(all->message);
        return status_exit(all->status[k]);
    }
    if (table_from_samples(&t, all, sc->scales.layer.h0)) {
        fail_line("ensemble: out of memory");
        return EXIT_FAILED;
    }
    int rc = write_outputs(o, sc, &t, quiet);
    const uint64_t n = ct_ensemble_checked(&sc->opts, all->first, all->count);
    if (!quiet && rc == EXIT_DONE && isfinite(all->quad_error_max) && n == all->count)
        fprintf(stderr,
                "cantact: closed-form check of every realisation: max |e - e_closed_form| = %.3g\n",
                all->quad_error_max);
    else if (!quiet && rc == EXIT_DONE && isfinite(all->quad_error_max))
        fprintf(stderr,
                "cantact: closed-form check of %llu of %llu realisations (those whose index is a "
                "multiple of %d; solver.check = all checks every one): max |e - e_closed_form| = "
                "%.3g\n",
                (unsigned long long)n, (unsigned long long)all->count, CT_ENSEMBLE_CHECK_STRIDE,
                all->quad_error_max);
    else if (!quiet && rc == EXIT_DONE && sc->opts.check == CT_CHECK_AUTO && n == 0)
        fprintf(stderr,
                "cantact: closed-form check of none of realisations %llu .. %llu (it covers those "
                "whose index is a multiple of %d; solver.check = all checks every one)\n",
                (unsigned long long)all->first, (unsigned long long)(all->first + all->count - 1),
                CT_ENSEMBLE_CHECK_STRIDE);
    table_free(&t);
    return rc;
}

int ct_cli_ensemble_run(const ct_scene *sc, int quiet, const char *range)
{
    const int rank = ct_mpi_rank(), size = ct_mpi_size();
    char err[512] = "", msg[300] = "";
    uint64_t a = 0, b = sc->realisations;
    int rc = EXIT_DONE;
    if (range && parse_range(range, sc->realisations, &a, &b, err, sizeof err)) {
        if (rank == 0)
            fail_line(err);
        return EXIT_USAGE;
    }
    /* a range writes its samples, for cantact merge */
    const unsigned what = range ? CT_OUT_REALISATIONS : sc->what;
    outputs o;
    memset(&o, 0, sizeof o);
    int ok = 1;
    int opened = rank == 0 ? open_outputs(&o, sc, what, NULL, 0, err, sizeof err) : 0;
    if (opened == -1)
        fail_line(err);
    if (opened)
        ok = 0;
    if (!ct_mpi_bcast_int(ok)) {
        close_outputs(&o);
        return EXIT_USAGE;
    }
    ct_random_cantor surface;
    ct_surface_random_cantor(sc->surface, &surface, NULL);
    /* this rank's block of realisations */
    const uint64_t n = b - a;
    const uint64_t my_a = a + n * (uint64_t)rank / (uint64_t)size;
    const uint64_t my_b = a + n * (uint64_t)(rank + 1) / (uint64_t)size;
    if (rank == 0 && !quiet)
        fprintf(stderr,
                "cantact: random cantor surface, depth %ld (%zu rods per realisation), "
                "realisations %llu..%llu of %llu, %d process(es), %d thread(s) each\n",
                surface.depth, ((size_t)2 << surface.depth) - 1, (unsigned long long)a,
                (unsigned long long)(b - 1), (unsigned long long)sc->realisations, size,
                sc->threads > 0 ? sc->threads : ct_default_threads());
    ct_ensemble_samples *mine = NULL, *all = NULL;
    int st = run_block(sc, &surface, my_a, my_b, &mine, msg, sizeof msg);
    if (size > 1) {
        st = ct_mpi_gather(mine, st, msg, a, n, sc->nvel * (size_t)sc->impacts, &all, err,
                           sizeof err);
        if (rank == 0 && all)
            all->draws = ((uint64_t)2 << surface.depth) - 2;
    } else {
        all = mine;
        mine = NULL;
        snprintf(err, sizeof err, "%s", msg);
    }
    if (rank == 0)
        rc = report(&o, sc, all, st, err, quiet);
    close_outputs(&o);
    ct_ensemble_samples_free(mine);
    ct_ensemble_samples_free(all);
    return ct_mpi_bcast_int(rc);
}

/* ---- merge ---- */

const char *const ct_cli_merge_help =
    "Usage: cantact merge SCENE.ini PART.csv... [--set section.key=value]... [-o FILE] [-q]\n"
    "\n"
    "Combines the realisations CSVs that runs of SCENE.ini with --realisations a:b wrote (e.g.\n"
    "the tasks of a job array) into what the scene's [output] what asks for (ensemble and/or\n"
    "realisations): the same bytes as one run over all realisations. Every realisation\n"
    "0 .. ensemble.realisations - 1 must be in exactly one part; the parts' speeds and impacts\n"
    "must be the scene's.\n"
    "\n"
    "Options:\n"
    "  --set section.key=value   override a scene key (repeatable; as for the runs)\n"
    "  -o FILE                   same as --set output.file=FILE ('-' for stdout)\n"
    "  -q                        no summary on stderr\n"
    "  -h, --help                this help\n";

/* Splits a line at commas into at most max fields, the error field (quoted, last) whole. */
static int split_fields(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    while (n < max) {
        fields[n++] = p;
        if (*p == '"') { /* a quoted error: to the closing quote at the end */
            char *q = strrchr(p + 1, '"');
            if (!q)
                return -1;
            *q = '\0';
            fields[n - 1] = p + 1;
            return q[1] ? -1 : n;
        }
        char *c = strchr(p, ',');
        if (!c)
            return n;
        *c = '\0';
        p = c + 1;
    }
    return -1;
}

static int read_double(const char *s, double *x)
{
    char *end;
    if (!*s) {
        *x = NAN;
        return 0;
    }
    errno = 0;
    *x = strtod(s, &end);
    return *end || errno ? -1 : 0;
}

static int read_u64(const char *s, uint64_t *x)
{
    char *end;
    if (!(*s >= '0' && *s <= '9'))
        return -1;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    *x = (uint64_t)v;
    return *end || errno ? -1 : 0;
}

/* A row of a realisations CSV is a few numbers and an error message: longer is no part. */
#define PART_LINE_MAX 4096

/* The next line of f into buf (PART_LINE_MAX + 1 bytes) without its line end (\n or \r\n):
 * 1, 0 at the end, -1 when longer than PART_LINE_MAX (the rest of it is not read), -2 at a
 * NUL byte (no text cantact writes has one; read as a string, the line would end there). */
static int part_line(FILE *f, char *buf)
{
    size_t n = 0;
    int c;
    while ((c = getc_unlocked(f)) != EOF && c != '\n') {
        if (c == '\0') {
            buf[n] = '\0';
            return -2;
        }
        if (n == PART_LINE_MAX)
            return -1;
        buf[n++] = (char)c;
    }
    if (c == EOF && n == 0)
        return 0;
    if (n && buf[n - 1] == '\r')
        n--;
    buf[n] = '\0';
    return 1;
}

/* The identity line of a part begins so (identity()). */
#define PART_ID_HEAD "# realisations of surface = "

/* Up to 40 bytes of s from byte `from` on, for a message: bytes a terminal does not show
 * (a BOM, a tab, control characters) as \xHH, "..." where cut. */
static void excerpt(char *buf, size_t len, const char *s, size_t from)
{
    size_t n = 0, k = 0;
    if (from > 0)
        n += (size_t)snprintf(buf, len, "...");
    for (; s[from + k] && k < 40 && n + 8 < len; k++) {
        const unsigned char c = (unsigned char)s[from + k];
        n += (size_t)snprintf(buf + n, len - n, c >= 0x20 && c < 0x7f ? "%c" : "\\x%02X", c);
    }
    if (s[from + k] && n + 4 < len)
        snprintf(buf + n, len - n, "...");
    else if (n == 0 && len)
        buf[0] = '\0';
}

/* A line that is not the expected one, in one line: where they part and what follows in
 * each (two texts that look alike, or differ past what a message shows, are told apart). */
static void mismatch(char *err, size_t errlen, const char *where, const char *what,
                     const char *line, const char *want)
{
    size_t at = 0;
    while (line[at] && line[at] == want[at])
        at++;
    const size_t from = at > 20 ? at - 20 : 0;
    char got[150], exp[150];
    excerpt(got, sizeof got, line, from);
    excerpt(exp, sizeof exp, want, from);
    snprintf(err, errlen, "%.160s: %.60s: from byte %zu it says '%s', expected '%s'", where, what,
             at + 1, got, exp);
}

/* Reads and checks a part's first two lines (into line): this scene's identity, after a
 * UTF-8 byte order mark if one comes first (an editor's), then the header. 0, or -1 with
 * the message in err. */
static int part_head(FILE *f, const char *path, const ct_scene *sc, char *line, char *err,
                     size_t errlen)
{
    char id[800], where[300];
    identity(sc, id, sizeof id);
    for (long lineno = 1; lineno <= 2; lineno++) {
        const int got = part_line(f, line);
        snprintf(where, sizeof where, "%s:%ld", path, lineno);
        if (got == 0 && ferror(f))
            snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        else if (got == 0)
            snprintf(err, errlen, "%s: %s: not a realisations CSV", path,
                     lineno == 1 ? "empty" : "no header");
        else if (got == -1)
            snprintf(err, errlen, "%s: a line longer than %d bytes: not a realisations CSV", where,
                     PART_LINE_MAX);
        else if (got == -2 && lineno == 1 &&
                 ((line[0] == '\xFF' && line[1] == '\xFE') ||
                  (line[0] == '\xFE' && line[1] == '\xFF')))
            snprintf(err, errlen, "%s: UTF-16 text: a part is the UTF-8 that cantact writes", path);
        else if (got == -2)
            snprintf(err, errlen, "%s: a NUL byte: not a realisations CSV", where);
        if (got <= 0)
            return -1;
        const char *text = line;
        if (lineno == 1 && !strncmp(text, "\xEF\xBB\xBF", 3))
            text += 3;
        if (lineno == 1 && !strcmp(text, id))
            continue;
        if (lineno == 2 && !strcmp(text, realisations_header(sc->skip_failed)))
            return 0;
        if (lineno == 1 && strncmp(text, PART_ID_HEAD, strlen(PART_ID_HEAD)))
            snprintf(err, errlen,
                     "%s: not a part of an ensemble run (its first line is not '" PART_ID_HEAD
                     "...', which cantact run --realisations a:b writes first)",
                     path);
        else if (lineno == 1)
            mismatch(err, errlen, where, "not a part of this scene", text, id);
        else
            mismatch(err, errlen, where, "not a realisations CSV of this scene", text,
                     realisations_header(sc->skip_failed));
        return -1;
    }
    return 0;
}

/* The values of one row as the run would have written them: e in [0, 1], u_max and V*_c
 * finite and >= 0, u_max below H*, clip counts at most the draws; empty only for a failed impact (a
 * row with its error), and failed impacts only in a scene with solver.on_error = skip. NULL or why
 * not. */
static const char *row_values(const ct_scene *sc, double u, double e, double vc, uint64_t cx,
                              uint64_t cz, const char *error)
{
    ct_random_cantor rc;
    ct_surface_random_cantor(sc->surface, &rc, NULL);
    const uint64_t draws = ((uint64_t)2 << rc.depth) - 2;
    if (cx > draws || cz > draws)
        return "more clipped ratios than draws";
    if (error && *error)
        return isnan(e) && isnan(u) && isnan(vc) ? NULL : "a failed impact with numbers";
    if (isnan(e) || isnan(u) || isnan(vc))
        return sc->skip_failed ? "empty numbers without an error"
                               : "empty numbers in a part of a "
                                 "scene that stops on errors";
    if (!(e >= 0.0 && e <= 1.0))
        return "e outside [0, 1]";
    if (!(isfinite(u) && u >= 0.0) || !(isfinite(vc) && vc >= 0.0))
        return "u_max_over_h0 or V_star_crit not a finite number >= 0";
    const ct_layer *L = &sc->scales.layer;
    if (!(u < L->Hstar / L->h0)) /* u_max >= H* is a crushed layer: refused, never a row */
        return "u_max_over_h0 not below H*/h0 (a crushed layer)";
    return NULL;
}

/* The data rows of a part (its lines after the identity and the header), its head checked:
 * -1 with the message in err when it is no part of this scene, cannot be read or has a line
 * that no part has (too long, a NUL byte). */
static long long part_rows(const char *path, const ct_scene *sc, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    char *line = malloc(PART_LINE_MAX + 1);
    long long n = -1,
              blank = 0; /* empty lines: harmless at the end (an editor's), not among rows */
    int got = 0;
    if (!line)
        snprintf(err, errlen, "out of memory");
    else if (!part_head(f, path, sc, line, err, errlen)) {
        n = 0;
        while ((got = part_line(f, line)) > 0 && !(line[0] && blank))
            line[0] ? n++ : blank++;
        const long long lineno = n + blank + 3;
        if (got > 0)
            snprintf(err, errlen, "%s:%lld: an empty line among the rows: not a realisations CSV",
                     path, lineno - 1);
        else if (got == -1)
            snprintf(err, errlen, "%s:%lld: a line longer than %d bytes: not a realisations CSV",
                     path, lineno, PART_LINE_MAX);
        else if (got == -2)
            snprintf(err, errlen, "%s:%lld: a NUL byte: not a realisations CSV", path, lineno);
        else if (ferror(f))
            snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        if (got != 0 || ferror(f))
            n = -1;
    }
    fclose(f);
    free(line);
    return n;
}

/* Reads one part into t; seen[r] marks the realisations read. Returns 0 or -1 (err set). */
static int read_part(const char *path, const ct_scene *sc, table *t, unsigned char *seen, char *err,
                     size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    const size_t impacts = (size_t)sc->impacts, nrows = t->nrows;
    const int nf = sc->skip_failed ? 9 : 8;
    char *line = malloc(PART_LINE_MAX + 1);
    long lineno = 2;
    int rc = -1, got;
    uint64_t r_cur = UINT64_MAX;
    size_t q_next = 0;
    if (!line) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    if (part_head(f, path, sc, line, err, errlen))
        goto done;
    while ((got = part_line(f, line)) != 0) {
        lineno++;
        if (got < 0) {
            if (got == -1)
                snprintf(err, errlen, "%s:%ld: a line longer than %d bytes: not a realisations CSV",
                         path, lineno, PART_LINE_MAX);
            else
                snprintf(err, errlen, "%s:%ld: a NUL byte: not a realisations CSV", path, lineno);
            goto done;
        }
        if (!line[0]) /* at the end: part_rows refused one among the rows */
            continue;
        char *fields[9];
        uint64_t r, impact, cx, cz;
        double V, u, e, vc;
        if (split_fields(line, fields, nf) != nf || read_u64(fields[0], &r) ||
            read_u64(fields[1], &impact) || read_double(fields[2], &V) ||
            read_double(fields[3], &u) || read_double(fields[4], &e) ||
            read_double(fields[5], &vc) || read_u64(fields[6], &cx) || read_u64(fields[7], &cz)) {
            snprintf(err, errlen, "%s:%ld: malformed row (expected %s)", path, lineno,
                     realisations_header(sc->skip_failed));
            goto done;
        }
        const char *why = row_values(sc, u, e, vc, cx, cz, nf == 9 ? fields[8] : NULL);
        if (why) {
            snprintf(err, errlen, "%s:%ld: %s: not what a run writes", path, lineno, why);
            goto done;
        }
        if (r >= t->count) {
            snprintf(err, errlen,
                     "%s:%ld: realisation %llu: the scene has ensemble.realisations = %llu", path,
                     lineno, (unsigned long long)r, (unsigned long long)t->count);
            goto done;
        }
        if (r != r_cur) {
            if (r_cur != UINT64_MAX && q_next != nrows) {
                snprintf(err, errlen, "%s:%ld: realisation %llu has %zu rows, the scene %zu", path,
                         lineno, (unsigned long long)r_cur, q_next, nrows);
                goto done;
            }
            if (seen[r]) {
                snprintf(err, errlen, "%s:%ld: realisation %llu appears twice", path, lineno,
                         (unsigned long long)r);
                goto done;
            }
            seen[r] = 1;
            r_cur = r;
            q_next = 0;
        }
        const size_t q = q_next++;
        if (q >= nrows || impact != q % impacts + 1 || V != sc->V_star[q / impacts]) {
            snprintf(err, errlen,
                     "%s:%ld: V* = %s, impact %s: not the scene's row %zu of realisation %llu "
                     "(the parts must come from runs of this scene)",
                     path, lineno, fields[2], fields[1], q + 1, (unsigned long long)r);
            goto done;
        }
        const size_t k = (size_t)r * nrows + q;
        t->e[k] = e;
        t->u[k] = u;
        t->vc[k] = vc;
        t->cx[r] = cx;
        t->cz[r] = cz;
        if (nf == 9 && fields[8][0] && !(t->err[k] = strdup(fields[8]))) {
            snprintf(err, errlen, "out of memory");
            goto done;
        }
    }
    if (r_cur != UINT64_MAX && q_next != nrows) {
        snprintf(err, errlen, "%s: realisation %llu has %zu rows, the scene %zu", path,
                 (unsigned long long)r_cur, q_next, nrows);
        goto done;
    }
    if (ferror(f)) {
        snprintf(err, errlen, "%s: read error", path);
        goto done;
    }
    rc = 0;
done:
    free(line);
    fclose(f);
    return rc;
}

int ct_cli_merge(int argc, char **argv)
{
    char err[600];
    ct_args a;
    ct_scene sc;
    int loaded = 0, quiet;
    table t;
    memset(&t, 0, sizeof t);
    unsigned char *seen = NULL;
    outputs o;
    memset(&o, 0, sizeof o);
    int rc = ct_args_parse(&a, argc, argv, "merge", NULL, 64);
    if (rc < 0 && a.help) {
        fputs(ct_cli_merge_help, stdout);
        rc = EXIT_DONE;
    }
    if (rc < 0 && a.npos < 2) {
        fail_line("merge: needs SCENE.ini and at least one PART.csv (see cantact merge --help)");
        rc = EXIT_USAGE;
    }
    if (rc < 0)
        rc = ct_cli_load_scene(&a, "merge", &sc);
    if (rc >= 0) {
        ct_args_free(&a);
        return rc;
    }
    loaded = 1;
    quiet = a.quiet;
    rc = EXIT_USAGE;
    const char *scene = a.positional[0];
    if (!sc.realisations) {
        snprintf(err, sizeof err, "merge: %s has no [ensemble] realisations", scene);
        fail_line(err);
        goto done;
    }
    const size_t nrows = sc.nvel * (size_t)sc.impacts;
    /* the table is sized by what the parts hold: they must hold every realisation once */
    long long rows = 0;
    for (size_t p = 1; p < a.npos; p++) {
        long long n = part_rows(a.positional[p], &sc, err, sizeof err);
        if (n < 0) {
            fail_line(err);
            goto done;
        }
        rows += n;
    }
    if ((unsigned long long)rows != (unsigned long long)sc.realisations * nrows) {
        if (rows % (long long)nrows == 0)
            snprintf(err, sizeof err,
                     "merge: the parts hold %lld rows, %lld realisations of %zu rows; the scene "
                     "has ensemble.realisations = %llu (every realisation must be in exactly one "
                     "part)",
                     rows, rows / (long long)nrows, nrows, (unsigned long long)sc.realisations);
        else
            snprintf(err, sizeof err,
                     "merge: the parts hold %lld rows, not whole realisations of %zu rows (the "
                     "scene's %zu speeds x %ld impacts); ensemble.realisations = %llu needs %llu "
                     "(every realisation must be in exactly one part)",
                     rows, nrows, sc.nvel, sc.impacts, (unsigned long long)sc.realisations,
                     (unsigned long long)sc.realisations * nrows);
        fail_line(err);
        goto done;
    }
    /* every realisation's samples are held: refuse up front what would not fit, as run does */
    const double bytes = (double)sc.realisations * ((double)nrows * 4.0 + 3.0) * sizeof(double);
    if (bytes > 0.5 * (double)ct_available_memory()) {
        snprintf(err, sizeof err,
                 "merge: %llu realisations x %zu rows need %.3g GiB, more than half the %.3g GiB "
                 "of memory available",
                 (unsigned long long)sc.realisations, nrows, bytes / 1073741824.0,
                 (double)ct_available_memory() / 1073741824.0);
        fail_line(err);
        goto done;
    }
    if (table_alloc(&t, 0, sc.realisations, nrows) ||
        !(seen = calloc((size_t)sc.realisations, 1))) {
        fail_line("merge: out of memory");
        rc = EXIT_FAILED;
        goto done;
    }
    t.owns_err = 1;
    for (size_t k = 0; k < (size_t)sc.realisations * nrows; k++)
        t.e[k] = t.u[k] = t.vc[k] = NAN;
    /* open the outputs first: an unwritable path fails before any reading */
    int opened = open_outputs(&o, &sc, sc.what, a.positional + 1, a.npos - 1, err, sizeof err);
    if (opened) {
        if (opened == -1)
            fail_line(err);
        goto done;
    }
    for (size_t p = 1; p < a.npos; p++)
        if (read_part(a.positional[p], &sc, &t, seen, err, sizeof err)) {
            fail_line(err);
            goto done;
        }
    /* every realisation is now in exactly one part: the parts held R x nrows rows, none twice,
     * each with nrows rows of an index below R */
    rc = write_outputs(&o, &sc, &t, quiet);
done:
    close_outputs(&o);
    table_free(&t);
    free(seen);
    if (loaded)
        ct_scene_free(&sc);
    ct_args_free(&a);
    return rc;
}
