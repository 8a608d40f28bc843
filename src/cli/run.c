/* `cantact run`: the scene's surface built as rods and swept, its outputs held in a list
 * (each a file opened first, written as the sweep goes or after it, published together). */
#include "run.h"

#include "args.h"
#include "ensemble.h"
#include "history.h"
#include "number.h"
#include "output.h"
#include "ranks.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/statvfs.h>

/* The outputs of a run besides a bounce sequence and an ensemble, in the order of their
 * files: the e table at output.file, the others beside it (FILE_curve.csv, ...) when there
 * are several. */
typedef struct {
    unsigned bit;
    const char *tag;
    ct_out out;
    char *path;
    int opened;
} run_output;

typedef struct {
    run_output o[5]; /* e, curve, profile, history, bearing */
    size_t n;
} output_list;

static const struct {
    unsigned bit;
    const char *tag;
} output_kinds[] = {{CT_OUT_E, "e"},
                    {CT_OUT_CURVE, "curve"},
                    {CT_OUT_PROFILE, "profile"},
                    {CT_OUT_HISTORY, "history"},
                    {CT_OUT_BEARING, "bearing"}};
#define NOUTPUTS (sizeof output_kinds / sizeof output_kinds[0])

static FILE *output_file(const output_list *l, unsigned bit)
{
    for (size_t k = 0; k < l->n; k++)
        if (l->o[k].bit == bit && l->o[k].opened)
            return l->o[k].out.f;
    return NULL;
}

/* Opens every output asked for: an unwritable path, or one that is an input of the run,
 * fails before any work is done. -1 with the message in err, -2 when it was said already. */
static int open_outputs(output_list *l, const ct_scene *sc, char *err, size_t errlen)
{
    memset(l, 0, sizeof *l);
    size_t items = 0;
    for (size_t k = 0; k < NOUTPUTS; k++)
        items += !!(sc->what & output_kinds[k].bit);
    if (items > 1 && !strcmp(sc->output, "-")) {
        snprintf(err, errlen,
                 "output.what names several outputs: set output.file (or -o FILE) to a path");
        return -1;
    }
    const char *paths[NOUTPUTS];
    for (size_t k = 0; k < NOUTPUTS; k++) {
        if (!(sc->what & output_kinds[k].bit))
            continue;
        run_output *o = &l->o[l->n++];
        o->bit = output_kinds[k].bit;
        o->tag = output_kinds[k].tag;
        o->path = items > 1 && o->bit != CT_OUT_E ? ct_cli_derived_path(sc->output, o->tag)
                                                  : strdup(sc->output);
        if (!o->path) {
            snprintf(err, errlen, "out of memory");
            return -1;
        }
        paths[l->n - 1] = o->path;
    }
    if (ct_cli_outputs_not_inputs(sc, paths, l->n, NULL, 0) >= 0)
        return -2;
    for (size_t k = 0; k < l->n; k++) {
        if (ct_out_open(&l->o[k].out, l->o[k].path, err, errlen))
            return -1;
        l->o[k].opened = 1;
    }
    return 0;
}

/* All outputs land together or none does. */
static int commit_outputs(output_list *l, char *err, size_t errlen)
{
    ct_out *outs[NOUTPUTS];
    size_t n = 0;
    for (size_t k = 0; k < l->n; k++)
        if (l->o[k].opened) {
            outs[n++] = &l->o[k].out;
            l->o[k].opened = 0;
        }
    return ct_out_commit_all(outs, n, err, errlen);
}

static void close_outputs(output_list *l)
{
    for (size_t k = 0; k < l->n; k++) {
        if (l->o[k].opened)
            ct_out_abort(&l->o[k].out);
        free(l->o[k].path);
    }
    memset(l, 0, sizeof *l);
}

/* ---- the curve output ---- */

/* What the run writes while the sweep goes: curve branches and histories, of the impacts
 * that computed. */
typedef struct {
    const ct_scene *sc;
    FILE *curve, *history;
    int compare;
    ct_curve *post; /* the post-impact state's curve (the unloading branch) */
} run_observer;

/* A curve branch: the breakpoints in [lo, hi] (when fewer than 1e5) and a uniform grid, P
 * from the state's load curve; the kind's comparison columns on the first impact. */
static int write_branch(FILE *f, const run_observer *o, const ct_curve *c, const ct_layer *L,
                        double V, long impact, double lo, double hi, int unload)
{
    enum { GRID = 200 };
    const double *x = ct_curve_points(c), h0 = L->h0, PY = L->sigma_y * L->l0;
    size_t n = ct_curve_size(c), a = 0, z = n;
    while (a < n && !(x[a] > lo))
        a++;
    while (z > a && !(x[z - 1] < hi))
        z--;
    size_t use = z - a < 100000 ? z - a : 0;
    double *u = malloc((use + GRID + 1) * sizeof(double));
    if (!u)
        return CT_ENOMEM;
    /* merge the (sorted) breakpoints with the (sorted) grid */
    size_t m = 0, i = a, g = 0;
    while (i < a + use || g <= GRID) {
        double ug = g <= GRID ? lo + (hi - lo) * g / GRID : INFINITY;
        double ub = i < a + use ? x[i] : INFINITY;
        double next = ub < ug ? ub : ug;
        if (ub < ug)
            i++;
        else
            g++;
        if (!m || next != u[m - 1])
            u[m++] = next;
    }
    const char *const *names;
    const size_t ncmp = o->compare ? ct_surface_curve_compare_columns(o->sc->surface, &names) : 0;
    for (size_t j = 0; j < m; j++) {
        size_t k = unload ? m - 1 - j : j;
        ct_put_double(f, V);
        fprintf(f, ",%ld,", impact);
        ct_put_double(f, u[k] / h0);
        fputc(',', f);
        ct_put_double(f, ct_curve_force(c, u[k]) / PY);
        fprintf(f, ",%s", unload ? "unload" : "load");
        double laws[8];
        for (size_t q = 0; q < ncmp; q++)
            laws[q] = NAN;
        if (impact == 1) /* the laws at the same u, unloading from the exact u_max (hi) */
            ct_surface_curve_compare(o->sc->surface, unload, hi, u[k], laws);
        for (size_t q = 0; q < ncmp; q++) {
            fputc(',', f);
            if (isfinite(laws[q]))
                ct_put_double(f, laws[q]);
        }
        fputc('\n', f);
    }
    free(u);
    return CT_OK;
}

static int observe(const ct_sweep_row *row, int phase, const ct_bundle *b, const ct_curve *c,
                   void *ctx)
{
    run_observer *o = ctx;
    const ct_scene *sc = o->sc;
    const ct_layer *L = ct_bundle_layer(b);
    int st = CT_OK;
    if (phase == 0 && o->history && (st = ct_cli_history_rows(o->history, sc, row, b)))
        return st;
    if (phase == 0 && o->curve)
        st = write_branch(o->curve, o, c, L, row->V_star, row->impact, row->r.u_contact,
                          row->r.u_max, 0);
    if (phase == 1 && o->curve && !(st = ct_curve_build(o->post, b)))
        st = write_branch(o->curve, o, o->post, L, row->V_star, row->impact, row->r.u_release,
                          row->r.u_max, 1);
    return st;
}

static void show_progress(size_t done, size_t total, void *ctx)
{
    (void)total;
    ct_progress *prog = ctx;
    while (prog->done < done)
        ct_progress_step(prog);
}

/* 1 when the e table carries the contact time and the peak force in the scene's units without
 * the time columns: a mass is given (issue 38: whenever mass and speed are given). */
static int physical_time(const ct_scene *sc)
{
    return sc->mass > 0.0 && !(sc->what & CT_OUT_TIME);
}

/* The time columns' contact time and peak force (their places in the column table). */
static void contact_columns(const ct_column *cols, size_t n, size_t at[2])
{
    at[0] = at[1] = 0;
    for (size_t k = 0; k < n; k++) {
        if (!strcmp(cols[k].name, "t_contact_over_tau"))
            at[0] = k;
        if (!strcmp(cols[k].name, "P_peak_over_PY"))
            at[1] = k;
    }
}

/* The scene's sweep (speeds, impacts, rule, path, the time columns), progress into prog: the
 * whole sweep and the streamed one start from it. */
static ct_sweep_spec spec_of(const ct_scene *sc, ct_progress *prog)
{
    return (ct_sweep_spec){
        .V_star = sc->V_star,
        .nvel = sc->nvel,
        .impacts = sc->impacts,
        .opts = sc->opts,
        .stop_on_error = !sc->skip_failed,
        .progress = prog->enabled ? show_progress : NULL, /* a bar on a terminal only */
        .progress_ctx = prog,
        .path = sc->path,
        /* with a history too: an impact whose motion fails is then a failed row (skipped
         * under on_error = skip), not a history that ends the run */
        .dynamics = !!(sc->what & (CT_OUT_TIME | CT_OUT_HISTORY)) || physical_time(sc),
    };
}

/* ---- the e table ---- */

static void field(ct_line *l, double x, int digits)
{
    ct_line_char(l, ',');
    if (isfinite(x)) {
        if (digits == 3)
            ct_line_g3(l, x);
        else
            ct_line_double(l, x);
    }
}

static void write_e_header(FILE *f, const ct_scene *sc)
{
    const ct_column *cols;
    const size_t n = ct_sweep_columns(&cols);
    const char *sep = "";
    for (size_t k = 0; k < n; k++, sep = ",")
        if (!strcmp(cols[k].group, "e"))
            fprintf(f, "%s%s", sep, cols[k].name);
    if (sc->what & CT_OUT_COMPARE) {
        const char *const *names;
        const size_t m = ct_surface_compare_columns(sc->surface, &names);
        for (size_t k = 0; k < m; k++)
            fprintf(f, ",%s", names[k]);
    }
    if (sc->what & CT_OUT_TIME)
        ct_cli_time_header(f, sc);
    for (size_t k = 0; k < n && sc->mass > 0.0; k++) /* with a mass, the speeds themselves */
        if (!strcmp(cols[k].group, "speed"))
            fprintf(f, ",%s", cols[k].physical);
    if (physical_time(sc)) { /* and the contact time and the peak force */
        size_t at[2];
        contact_columns(cols, n, at);
        fprintf(f, ",%s,%s", cols[at[0]].physical, ct_cli_physical_name(&cols[at[1]], sc));
    }
    fprintf(f, "%s\n", sc->skip_failed ? ",error" : "");
}

/* One row: the e columns, the kind's comparison columns, the time columns, and (with
 * solver.on_error = skip) the error; a failed impact has its impact and V* and empty fields
 * up to its reason. */
static void write_e_row(FILE *f, const ct_scene *sc, const ct_cli_columns *ec,
                        const ct_cli_columns *tc, const ct_cli_columns *sp, const ct_sweep_row *row,
                        const double *cmp, size_t ncmp)
{
    const ct_column *cols = ec->cols;
    const size_t *at = ec->at, n = ec->n;
    const ct_layer *L = &sc->scales.layer;
    ct_line line, *l = &line;
    ct_line_start(l, f);
    ct_line_long(l, row->impact);
    ct_line_char(l, ',');
    ct_line_double(l, row->V_star);
    for (size_t q = 0; q < n; q++) {
        const ct_column *c = &cols[at[q]];
        const double v = row->status ? NAN : ct_column_value(c, row, L);
        if (c->type != 'd' && !row->status) {
            ct_line_char(l, ',');
            ct_line_long(l, (long)v);
        } else {
            field(l, v, c->digits);
        }
    }
    for (size_t q = 0; q < ncmp; q++)
        field(l, row->status ? NAN : cmp[q], 17);
    if (sc->what & CT_OUT_TIME)
        ct_cli_time_row(l, sc, tc, row);
    if (sc->mass > 0.0) { /* the speeds in the scene's units */
        const double tau = ct_time_scale(&sc->scales, sc->mass);
        for (size_t q = 0; q < sp->n; q++)
            field(l,
                  row->status
                      ? NAN
                      : ct_column_physical(&cols[sp->at[q]], row, L, &sc->scales.physical, tau),
                  17);
        if (physical_time(sc)) {
            size_t at[2];
            contact_columns(cols, ct_sweep_columns(&cols), at);
            for (int q = 0; q < 2; q++)
                field(l,
                      row->status
                          ? NAN
                          : ct_column_physical(&cols[at[q]], row, L, &sc->scales.physical, tau),
                      17);
        }
    }
    if (row->status) {
        ct_line_str(l, ",\"");
        for (const char *m = row->message; *m; m++)
            ct_line_char(l, *m == '"' ? '\'' : *m);
        ct_line_str(l, "\"\n");
    } else {
        if (sc->skip_failed)
            ct_line_char(l, ',');
        ct_line_char(l, '\n');
    }
    ct_line_flush(l);
}

/* What the rows written so far held: failures (the first one kept) and the closed-form
 * check's coverage. */
typedef struct {
    size_t rows, failed, ok, checked, checked_speeds;
    ct_sweep_row first_failed;
} row_tally;

/* Checks rows and writes them to the e table (f NULL: checks only), counting into t. */
static int write_e_rows(FILE *f, const ct_scene *sc, const ct_sweep_row *rows, size_t nrows,
                        const double *cmp, size_t ncmp, row_tally *t)
{
    char err[512];
    ct_cli_columns ec, tc, sp;
    if (f && (ct_cli_columns_of(&ec, "e") || ct_cli_columns_of(&tc, "time") ||
              ct_cli_columns_of(&sp, "speed"))) {
        ct_cli_fail("the e table has more than %d columns of a group", CT_CLI_COLUMNS);
        return EXIT_FAILED;
    }
    for (size_t k = 0; k < nrows; k++) {
        const ct_sweep_row *row = &rows[k];
        if (row->status == CT_OK && !(isfinite(row->r.e) && isfinite(row->r.u_max))) {
            ct_cli_fail("V* = %g impact %ld: a non-finite result", row->V_star, row->impact);
            return EXIT_FAILED;
        }
        if (((sc->what & CT_OUT_TIME) || physical_time(sc)) &&
            ct_cli_time_check(row, err, sizeof err)) {
            ct_cli_fail("%s", err); /* two computations of the rebound disagree: a defect */
            return EXIT_FAILED;
        }
        if (row->status && !t->failed++)
            t->first_failed = *row;
        t->rows++;
        t->ok += row->status == CT_OK;
        t->checked += row->status == CT_OK && !isnan(row->r.e_closed);
        t->checked_speeds += row->impact == 1 && row->status == CT_OK && !isnan(row->r.e_closed);
        if (f)
            write_e_row(f, sc, &ec, &tc, &sp, row, cmp ? cmp + ncmp * k : NULL, ncmp);
    }
    return EXIT_DONE;
}

/* The notes after the e table: failed impacts, and what a sampled check covered. */
static void tally_notes(const row_tally *t, const ct_scene *sc, size_t rods, int quiet)
{
    if (quiet)
        return;
    if (sc->opts.check == CT_CHECK_AUTO && t->checked > 0 && t->checked < t->ok)
        fprintf(stderr,
                "cantact: closed-form check: every impact of %zu of %zu speeds, a sample (%zu rods "
                "x %zu rows = %.3g rod evaluations, above the budget %.0f: the slowest, the "
                "fastest, the two around V*_c, log-spaced between; solver.check = all checks "
                "every one)\n",
                t->checked_speeds, sc->nvel, rods, t->rows, (double)rods * (double)t->rows,
                CT_CHECK_BUDGET);
    if (t->failed)
        fprintf(stderr,
                "cantact: %zu of %zu impacts failed or not run (first: V* = %g, impact %ld: %s)\n",
                t->failed, t->rows, t->first_failed.V_star, t->first_failed.impact,
                t->first_failed.message);
}

/* ---- run ---- */

/* impact.sequence = bounce: impacts at falling speeds, the state carried (src/cli/history.c). */
static int run_bounce(ct_scene *sc, int quiet)
{
    ct_out out;
    char err[512];
    ct_bundle *b = NULL;
    ct_plan_info info;
    ct_build_request req;
    int st;
    const char *path = sc->output;
    if (ct_cli_outputs_not_inputs(sc, &path, 1, NULL, 0) >= 0)
        return EXIT_USAGE;
    if (ct_out_open(&out, sc->output, err, sizeof err)) {
        ct_cli_fail("%s", err);
        return EXIT_USAGE;
    }
    ct_scene_request(sc, 0, &req);
    if ((st = ct_surface_build(sc->surface, &req, &b, &info))) {
        ct_out_abort(&out);
        ct_cli_fail_scene(sc, st, ct_error_message());
        return ct_cli_status_exit(st);
    }
    if (!quiet) {
        char what[300], body[200];
        ct_surface_describe(sc->surface, &info, what, sizeof what);
        ct_body_describe(&sc->body, body, sizeof body);
        fprintf(stderr, "cantact: bounce sequence on %s%s%s, at most %ld impacts\n", what,
                body[0] ? ", " : "", body, sc->impacts);
    }
    st = ct_cli_bounce(out.f, sc, b, err, sizeof err);
    ct_bundle_free(b);
    if (st) {
        ct_out_abort(&out);
        ct_cli_fail_scene(sc, st, err);
        return ct_cli_status_exit(st);
    }
    if (ct_out_commit(&out, err, sizeof err)) {
        ct_cli_fail("%s", err);
        return EXIT_USAGE;
    }
    return EXIT_DONE;
}

/* The kind's comparison columns for every row (what = compare): NULL when not asked or when
 * they cannot be computed (said on stderr; their fields stay empty). */
static double *compare_columns(ct_scene *sc, const ct_sweep_row *rows, size_t nrows, size_t *ncmp,
                               int quiet, int *oom)
{
    const char *const *names;
    *oom = 0;
    *ncmp = (sc->what & CT_OUT_COMPARE) ? ct_surface_compare_columns(sc->surface, &names) : 0;
    if (!*ncmp)
        return NULL;
    double *cmp = malloc((nrows ? nrows : 1) * *ncmp * sizeof(double));
    if (!cmp) {
        *oom = 1;
        return NULL;
    }
    if (ct_surface_compare(sc->surface, rows, nrows, cmp)) {
        if (!quiet)
            fprintf(stderr, "cantact: compare: %s (its columns stay empty)\n", ct_error_message());
        for (size_t k = 0; k < nrows * *ncmp; k++)
            cmp[k] = NAN;
    }
    return cmp;
}

/* The state what = profile shows: the last speed's impacts replayed on b (the virgin state)
 * as the sweep took them (an impact that yields advances the rods to its u_max), up to the
 * first that failed. Returns how many were replayed. */
static size_t last_speed_state(ct_bundle *b, const ct_scene *sc, const ct_sweep_row *rows)
{
    const size_t impacts = (size_t)sc->impacts;
    const ct_sweep_row *last = rows + (sc->nvel - 1) * impacts;
    size_t done = 0;
    for (; done < impacts && last[done].status == CT_OK; done++)
        if (!last[done].r.elastic)
            ct_bundle_advance(b, last[done].r.u_max);
    return done;
}

/* After failed impacts (solver.on_error = skip) the outputs that follow impacts say what they
 * hold: the curve and history rows of the impacts that computed; the profile the last state
 * computed of the last speed (profiled: the impacts replayed; all of them when none failed or
 * no profile is written). */
static void partial_notes(const row_tally *t, const ct_scene *sc, const output_list *outs,
                          const ct_sweep_row *rows, size_t profiled, int quiet)
{
    if (quiet || !t->failed)
        return;
    const int curve = output_file(outs, CT_OUT_CURVE) != NULL,
              history = output_file(outs, CT_OUT_HISTORY) != NULL;
    const char *which = curve && history ? "curve, history" : curve ? "curve" : "history";
    if ((curve || history) && !t->ok)
        fprintf(stderr, "cantact: %s: no impact computed: the header only\n", which);
    else if (curve || history)
        fprintf(stderr, "cantact: %s: rows of the computed impacts only (%zu of %zu)\n", which,
                t->ok, t->rows);
    const size_t impacts = (size_t)sc->impacts;
    const ct_sweep_row *last = rows + (sc->nvel - 1) * impacts;
    if (profiled == 0)
        fprintf(stderr,
                "cantact: profile: the surface before any impact (impact 1 of V* = %g, the last "
                "speed, failed)\n",
                last->V_star);
    else if (profiled < impacts)
        fprintf(stderr,
                "cantact: profile: the surface after impact %zu of V* = %g, the last computed "
                "(impact %zu failed)\n",
                profiled, last->V_star, profiled + 1);
}

/* The sweep with its observer, then the outputs written after it. */
static int sweep_and_write(ct_scene *sc, output_list *outs, ct_bundle *b, int quiet)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    run_observer obs = {.sc = sc,
                        .curve = output_file(outs, CT_OUT_CURVE),
                        .history = output_file(outs, CT_OUT_HISTORY),
                        .compare = !!(sc->what & CT_OUT_COMPARE)};
    int st, rc = EXIT_DONE, oom;
    ct_sweep_row *rows = malloc((nrows ? nrows : 1) * sizeof *rows);
    if (!rows) {
        ct_cli_fail("%zu result rows: out of memory", nrows);
        return EXIT_FAILED;
    }
    if (obs.curve) {
        const char *const *names;
        const size_t m = obs.compare ? ct_surface_curve_compare_columns(sc->surface, &names) : 0;
        fputs("V_star,impact,u_over_h0,P_over_PY,branch", obs.curve);
        for (size_t k = 0; k < m; k++)
            fprintf(obs.curve, ",%s", names[k]);
        fputc('\n', obs.curve);
    }
    if (obs.history)
        ct_cli_history_header(obs.history, sc);
    if (obs.curve && (st = ct_curve_alloc(&obs.post))) {
        free(rows);
        ct_cli_fail("%s", ct_error_message());
        return ct_cli_status_exit(st);
    }
    ct_progress prog;
    ct_progress_start(&prog, sc->nvel);
    ct_sweep_spec spec = spec_of(sc, &prog);
    spec.observe = (obs.curve || obs.history) ? observe : NULL;
    spec.observe_ctx = &obs;
    st = ct_sweep(b, &spec, rows);
    ct_progress_end(&prog);
    ct_curve_free(obs.post);
    FILE *fp = output_file(outs, CT_OUT_PROFILE), *fb = output_file(outs, CT_OUT_BEARING);
    if (!st)
        st = ct_surface_after_sweep(sc->surface, rows, nrows);
    ct_cli_notes(sc->surface, quiet);
    if (!st && fb)
        st = ct_surface_write_bearing(sc->surface, fb);
    /* the profile: the last speed's surface after its impacts (a kind whose profile shows no
     * state: as read); after a failed impact, the last state computed, which a note names */
    size_t profiled = (size_t)sc->impacts;
    if (!st && fp && ct_surface_profile_shows_state(sc->surface))
        profiled = last_speed_state(b, sc, rows);
    if (!st && fp)
        st = ct_surface_write_profile(sc->surface, b, fp);
    if (st) {
        ct_cli_fail_scene(sc, st, ct_error_message());
        free(rows);
        return ct_cli_status_exit(st);
    }
    size_t ncmp;
    double *cmp = compare_columns(sc, rows, nrows, &ncmp, quiet, &oom);
    row_tally t = {0};
    if (oom)
        ct_cli_fail("compare: out of memory");
    else
        rc = write_e_rows(output_file(outs, CT_OUT_E), sc, rows, nrows, cmp, ncmp, &t);
    if (rc == EXIT_DONE && !oom) {
        tally_notes(&t, sc, ct_bundle_size(b), quiet);
        partial_notes(&t, sc, outs, rows, profiled, quiet);
    }
    free(cmp);
    free(rows);
    return oom ? EXIT_FAILED : rc;
}

/* ---- the sweep streamed ---- */

/* Rows per block of a streamed sweep (272 bytes each on x86-64: 4.5 MB), whole speeds: a block
 * holds max(1, 16384 / impacts) speeds. */
#define STREAM_ROWS 16384

static size_t block_speeds(const ct_scene *sc)
{
    const size_t n = STREAM_ROWS / (size_t)sc->impacts;
    return n ? n : 1;
}

typedef struct {
    FILE *f;
    const ct_scene *sc;
    row_tally t;
    int rc;
} stream_ctx;

static int emit_rows(const ct_sweep_row *rows, size_t n, void *ctx)
{
    stream_ctx *c = ctx;
    c->rc = write_e_rows(c->f, c->sc, rows, n, NULL, 0, &c->t);
    return c->rc != EXIT_DONE;
}

/* Whether the run's outputs can be written block by block as the sweep goes: the e table
 * and its time columns only (the curve, history and profile outputs observe the sweep; a
 * kind's comparison columns and bearing curve are computed from all rows). */
static int streamable(const ct_scene *sc)
{
    return !(sc->what &
             (CT_OUT_CURVE | CT_OUT_HISTORY | CT_OUT_PROFILE | CT_OUT_COMPARE | CT_OUT_BEARING)) &&
           sc->nvel > block_speeds(sc);
}

/* The sweep in blocks of speeds, each written as soon as it is computed (ct_sweep_blocks):
 * the same bytes as the whole sweep, in memory of one block. */
static int sweep_streamed(ct_scene *sc, output_list *outs, const ct_bundle *b, int quiet)
{
    ct_progress prog;
    ct_progress_start(&prog, sc->nvel);
    const ct_sweep_spec spec = spec_of(sc, &prog);
    stream_ctx c = {output_file(outs, CT_OUT_E), sc, {0}, EXIT_DONE};
    int st = ct_sweep_blocks(b, &spec, block_speeds(sc), emit_rows, &c);
    ct_progress_end(&prog);
    if (c.rc != EXIT_DONE)
        return c.rc;                  /* said already */
    ct_cli_notes(sc->surface, quiet); /* (no kind's after-sweep step: what needs it is not
                                        streamed) */
    if (st) {
        ct_cli_fail_scene(sc, st, ct_error_message());
        return ct_cli_status_exit(st);
    }
    tally_notes(&c.t, sc, ct_bundle_size(b), quiet);
    return EXIT_DONE;
}

static int run_sweep(ct_scene *sc, int quiet);

int ct_cli_run(int argc, char **argv, const char *help)
{
    static const ct_opt opts[] = {{"--realisations", NULL}, {"--landings", NULL}, {NULL, NULL}};
    ct_args a;
    ct_scene sc;
    int rc = ct_args_parse(&a, argc, argv, "run", opts, 1);
    if (rc < 0 && a.help) {
        fputs(help, stdout);
        rc = EXIT_DONE;
    }
    if (rc < 0)
        rc = ct_cli_load_scene(&a, "run", &sc);
    if (rc >= 0) {
        ct_args_free(&a);
        return rc;
    }
    const char *range = ct_args_extra(&a, "--realisations"),
               *lrange = ct_args_extra(&a, "--landings");
    if ((range && !sc.realisations) || (lrange && !sc.body.landings)) {
        ct_cli_fail(range ? "--realisations: the scene has no [ensemble] realisations"
                          : "--landings: the scene has no body.landings");
        rc = EXIT_USAGE;
    } else if (sc.realisations || sc.body.landings) {
        /* samples: realisations of a random surface, or landings (src/cli/ensemble.c) */
        rc = ct_cli_ensemble_run(&sc, a.quiet, range ? range : lrange);
    } else if (ct_mpi_size() > 1) {
        ct_cli_fail("under MPI only samples ([ensemble] realisations, body.landings) are shared "
                    "among processes");
        rc = EXIT_USAGE;
    } else if (sc.bounce) { /* a bounce sequence: its own table */
        rc = run_bounce(&sc, a.quiet);
    } else {
        rc = run_sweep(&sc, a.quiet);
    }
    ct_scene_free(&sc);
    ct_args_free(&a);
    return rc;
}

static int run_sweep(ct_scene *sc, int quiet)
{
    output_list outs;
    char err[512];
    ct_bundle *b = NULL;
    ct_plan_info info;
    ct_build_request req;
    int st, rc;
    /* the result rows (speeds x impacts) are held in memory unless streamed: refuse up front
     * what would not fit, with the figure (1e6 speeds x 1e6 impacts are allowed by the scene's
     * ranges; streamed, a block holds whole speeds: 1e6 impacts of one speed are 272 MB) */
    /* an impact's history is held whole while written (about 48 bytes a point) */
    const double hist = (sc->what & CT_OUT_HISTORY) ? (double)sc->history_points * 48.0 : 0.0;
    if (hist >= CT_MEMORY_CHECK_MIN && hist > 0.9 * (double)ct_available_memory()) {
        ct_cli_fail("output.history_points = %zu: an impact's history needs about %.3g GiB (48 "
                    "bytes a point), more than the %.3g GiB of memory available",
                    sc->history_points, hist / 1073741824.0,
                    (double)ct_available_memory() / 1073741824.0);
        return EXIT_FAILED;
    }
    const size_t held = streamable(sc) ? block_speeds(sc) : sc->nvel;
    const double bytes = (double)held * (double)sc->impacts * (double)sizeof(ct_sweep_row);
    const double avail = bytes < CT_MEMORY_CHECK_MIN ? INFINITY : (double)ct_available_memory();
    if (bytes > 0.9 * avail) {
        ct_cli_fail("%zu speeds x %ld impacts = %.3g result rows need %.3g GiB, more than the "
                    "%.3g GiB of memory available: split the scene",
                    sc->nvel, sc->impacts, (double)sc->nvel * (double)sc->impacts,
                    bytes / 1073741824.0, avail / 1073741824.0);
        return EXIT_FAILED;
    }
    if ((st = open_outputs(&outs, sc, err, sizeof err))) {
        if (st == -1)
            ct_cli_fail("%s", err);
        close_outputs(&outs);
        return EXIT_USAGE;
    }
    FILE *fe = output_file(&outs, CT_OUT_E);
    struct statvfs fs;
    /* streamed, the rows are not held but written: refuse up front, with the figure, a table
     * its filesystem cannot take (at least 100 bytes a row, 200 with the time columns) */
    const double rows = (double)sc->nvel * (double)sc->impacts,
                 need = rows * ((sc->what & CT_OUT_TIME) ? 200.0 : 100.0);
    if (streamable(sc) && fe && !fstatvfs(fileno(fe), &fs) &&
        need > (double)fs.f_bavail * (double)fs.f_frsize) {
        ct_cli_fail("%zu speeds x %ld impacts = %.3g result rows need at least %.3g GiB of "
                    "output, more than the %.3g GiB free where it is written: split the scene",
                    sc->nvel, sc->impacts, rows, need / 1073741824.0,
                    (double)fs.f_bavail * (double)fs.f_frsize / 1073741824.0);
        close_outputs(&outs);
        return EXIT_FAILED;
    }
    ct_scene_request(sc, !!(sc->what & CT_OUT_PROFILE), &req);
    if ((st = ct_surface_build(sc->surface, &req, &b, &info))) {
        ct_cli_fail_scene(sc, st, ct_error_message());
        close_outputs(&outs);
        return ct_cli_status_exit(st);
    }
    if (!quiet) {
        char what[300], body[200];
        ct_surface_describe(sc->surface, &info, what, sizeof what);
        ct_body_describe(&sc->body, body, sizeof body);
        fprintf(stderr, "cantact: %s%s%s, %d thread(s)\n", what, body[0] ? ", " : "", body,
                ct_bundle_set_threads(b, sc->threads));
    }
    sc->areal = ct_cli_bundle_areal(b);
    if (fe)
        write_e_header(fe, sc);
    rc =
        streamable(sc) ? sweep_streamed(sc, &outs, b, quiet) : sweep_and_write(sc, &outs, b, quiet);
    ct_bundle_free(b);
    if (rc == EXIT_DONE && commit_outputs(&outs, err, sizeof err)) {
        ct_cli_fail("%s", err);
        rc = EXIT_USAGE;
    }
    close_outputs(&outs);
    return rc;
}
