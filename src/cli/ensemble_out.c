/* An ensemble's outputs (see ensemble_out.h): the samples of a run, or of the parts cantact
 * merge reads back, written as the statistics per speed and as the realisations CSV. The
 * realisations CSV prints every sample round-trip exact (%.17g), so that merge reads partial
 * outputs back into the very same numbers and writes the same bytes as one run over all
 * realisations; the statistics are computed from the samples in realisation order. */
#include "ensemble_out.h"
#include "args.h"
#include "number.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- samples in the output's units ---- */

void ct_ens_table_free(ct_ens_table *t)
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
    free(t->x);
    free(t->y);
    memset(t, 0, sizeof *t);
}

int ct_ens_table_alloc(ct_ens_table *t, uint64_t first, uint64_t count, size_t nrows, int landings)
{
    memset(t, 0, sizeof *t);
    t->landings = landings;
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
    t->x = malloc((size_t)count * sizeof(double));
    t->y = malloc((size_t)count * sizeof(double));
    if (!t->e || !t->u || !t->vc || !t->err || !t->cx || !t->cz || !t->x || !t->y) {
        ct_ens_table_free(t);
        return -1;
    }
    for (uint64_t r = 0; r < count; r++)
        t->x[r] = t->y[r] = NAN;
    return 0;
}

/* ---- writers ---- */

static void put_field(FILE *f, double x)
{
    fputc(',', f);
    if (isfinite(x))
        ct_put_double(f, x);
}

int ct_ens_landings_plane(const ct_scene *sc)
{
    return sc->body.landings && !strcmp(ct_body_name((size_t)sc->body.shape), "sphere");
}

const char *ct_ens_samples_header(const ct_scene *sc)
{
    static const char *const headers[3][2] = {
        {"realisation,impact,V_star,u_max_over_h0,e,V_star_crit,fx_clipped,fz_clipped",
         "realisation,impact,V_star,u_max_over_h0,e,V_star_crit,fx_clipped,fz_clipped,error"},
        {"landing,x,impact,V_star,u_max_over_h0,e,V_star_crit",
         "landing,x,impact,V_star,u_max_over_h0,e,V_star_crit,error"},
        {"landing,x,y,impact,V_star,u_max_over_h0,e,V_star_crit",
         "landing,x,y,impact,V_star,u_max_over_h0,e,V_star_crit,error"}};
    const int kind = !sc->body.landings ? 0 : ct_ens_landings_plane(sc) ? 2 : 1;
    return headers[kind][sc->skip_failed != 0];
}

/* The surface (kind, ratios, layer, depth, seed, spreads; a deterministic surface's own line
 * for landings, with the landings' seed), the error mode and the body. */
void ct_ens_identity(const ct_scene *sc, const ct_plan_info *built, char *buf, size_t len)
{
    char line[600], body[200];
    if (sc->body.landings) {
        ct_surface_table_line(sc->surface, built, line, sizeof line);
    } else {
        ct_random_cantor rc;
        ct_surface_random_cantor(sc->surface, &rc, NULL);
        ct_plan_info info = {.depth = rc.depth, .rods = ((size_t)2 << rc.depth) - 1};
        ct_surface_table_line(sc->surface, &info, line, sizeof line);
    }
    ct_body_describe(&sc->body, body, sizeof body); /* a part under another body is another run */
    if (sc->body.landings)
        snprintf(buf, len,
                 CT_ENS_LANDINGS_HEAD "%s; impacts %ld; solver.on_error = %s; %s; seed %llu", line,
                 sc->impacts, sc->skip_failed ? "skip" : "stop", body,
                 (unsigned long long)sc->body.seed);
    else
        snprintf(buf, len, CT_ENS_ID_HEAD "%s; impacts %ld; solver.on_error = %s%s%s", line,
                 sc->impacts, sc->skip_failed ? "skip" : "stop", body[0] ? "; " : "", body);
}

static void write_realisations(FILE *f, const ct_scene *sc, const ct_ens_table *t)
{
    const size_t impacts = (size_t)sc->impacts;
    const int plane = ct_ens_landings_plane(sc);
    for (uint64_t r = 0; r < t->count; r++)
        for (size_t q = 0; q < t->nrows; q++) {
            const size_t k = (size_t)r * t->nrows + q;
            fprintf(f, "%llu", (unsigned long long)(t->first + r));
            if (t->landings) {
                put_field(f, t->x[r]);
                if (plane)
                    put_field(f, t->y[r]);
            }
            fprintf(f, ",%zu,", q % impacts + 1);
            ct_put_double(f, sc->V_star[q / impacts]);
            put_field(f, t->u[k]);
            put_field(f, t->e[k]);
            put_field(f, t->vc[k]);
            if (!t->landings)
                fprintf(f, ",%llu,%llu", (unsigned long long)t->cx[r],
                        (unsigned long long)t->cz[r]);
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

static void write_ensemble_header(FILE *f, int landings, int speeds)
{
    static const char *const quantities[] = {"e", "u_max_over_h0", "V_star_crit"};
    fputs(landings ? "impact,V_star,landings" : "impact,V_star,realisations", f);
    for (int q = 0; q < 3; q++)
        for (int s = 0; s < 6; s++)
            fprintf(f, ",%s_%s", quantities[q], stat_names[s]);
    /* beside landings: e with the apex where body.position puts it (the middle by default) */
    fputs(landings ? ",e_at_position" : ",e_deterministic", f);
    /* with a mass, the impact speed in the scene's units (m/s for SI scenes), last */
    fputs(speeds ? ",v_impact_m_per_s\n" : "\n", f);
}

/* One row per speed and impact: the statistics over the realisations in realisation order,
 * and e of the deterministic surface (NaN: it failed). *sem_max gets the largest standard
 * error of mean e, *at its row. */
static int write_ensemble(FILE *f, const ct_scene *sc, const ct_ens_table *t, const double *e_det,
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
        if (sc->mass > 0.0) /* V* = sqrt(m / (2 l0 E h0)) v, as the scene converts speeds */
            put_field(f, sc->V_star[q / impacts] /
                             ct_V_star_of(sc->mass, 1.0, sc->scales.physical.l0,
                                          sc->scales.physical.E, sc->scales.physical.h0));
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
 * as spread 0, merged), for every speed and impact; NaN where an impact fails. Beside landings,
 * e of the one run with the apex at body.position (the middle of the surface by default). */
static int deterministic_e(const ct_scene *sc, double *e_det)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    ct_random_cantor rc;
    ct_bundle *b;
    int st = CT_OK;
    if (sc->body.landings) {
        ct_build_request req;
        ct_scene_request(sc, 0, &req);
        st = ct_surface_build(sc->surface, &req, &b, NULL);
    } else if (!(st = ct_surface_random_cantor(sc->surface, &rc,
                                               NULL))) { /* under a curved body one rod per piece,
                                                            met by the body as the samples are */
        const int curved = sc->body.shape != 0;
        st = ct_cantor_bundle(&b, &rc.params, curved ? CT_REP_SEGMENTS : CT_REP_STAGES, rc.depth,
                              INFINITY);
        if (!st && curved && (st = ct_body_meet(&sc->body, &sc->scales, &b)))
            ct_bundle_free(b);
    }
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

int ct_ens_open_outputs(ct_ens_outputs *o, const ct_scene *sc, unsigned what,
                        const char *const *parts, size_t nparts, char *err, size_t errlen)
{
    memset(o, 0, sizeof *o);
    /* the samples: realisations, or landings */
    const unsigned samples = what & (CT_OUT_REALISATIONS | CT_OUT_LANDINGS);
    const int both = (what & CT_OUT_ENSEMBLE) && samples;
    if (both && !strcmp(sc->output, "-")) {
        snprintf(err, errlen,
                 "output.what names several outputs: set output.file (or -o FILE) to a path");
        return -1;
    }
    if (samples) {
        const char *suffix = samples & CT_OUT_LANDINGS ? "landings" : "realisations";
        o->real_path = both ? ct_cli_derived_path(sc->output, suffix) : strdup(sc->output);
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
    if (samples) {
        if (ct_out_open(&o->real, o->real_path, err, errlen))
            return -1;
        o->opened_real = 1;
    }
    return 0;
}

void ct_ens_close_outputs(ct_ens_outputs *o)
{
    if (o->opened_ens)
        ct_out_abort(&o->ens);
    if (o->opened_real)
        ct_out_abort(&o->real);
    free(o->real_path);
    memset(o, 0, sizeof *o);
}

/* The statistics output: its header and rows, with e of the deterministic surface beside them.
 * *det_empty counts the rows where that e is empty; det_why gets why, when the deterministic
 * surface failed as a whole. */
static int write_statistics(FILE *f, const ct_scene *sc, const ct_ens_table *t, double *sem_max,
                            size_t *at, size_t *det_empty, char *det_why, size_t why_len)
{
    double *e_det = malloc(t->nrows * sizeof(double));
    int st = e_det ? deterministic_e(sc, e_det) : CT_ENOMEM;
    if (e_det && st) { /* the reference failed as a whole: its column stays empty */
        snprintf(det_why, why_len, "%s", ct_error_message());
        for (size_t q = 0; q < t->nrows; q++)
            e_det[q] = NAN;
    }
    for (size_t q = 0; e_det && q < t->nrows; q++)
        *det_empty += isnan(e_det[q]);
    write_ensemble_header(f, t->landings, sc->mass > 0.0);
    st = e_det ? write_ensemble(f, sc, t, e_det, sem_max, at) : CT_ENOMEM;
    free(e_det);
    return st;
}

/* The summary on stderr: the clipped ratios, the largest standard error of mean e (sem_max, at
 * row at), the failed impacts, and e_deterministic where it is empty. */
static void summary(const ct_scene *sc, const ct_ens_table *t, double sem_max, size_t at,
                    size_t det_empty, const char *det_why)
{
    uint64_t cx = 0, cz = 0;
    size_t failed = 0;
    for (uint64_t r = 0; r < t->count; r++) {
        cx += t->cx[r];
        cz += t->cz[r];
    }
    for (size_t k = 0; k < (size_t)t->count * t->nrows; k++)
        failed += t->err[k] != NULL;
    const char *of = t->landings ? "landings" : "realisations";
    if (!t->landings) {
        ct_random_cantor rc;
        ct_surface_random_cantor(sc->surface, &rc, NULL);
        const double draws = (double)t->count * (double)(((uint64_t)2 << rc.depth) - 2);
        fprintf(stderr,
                "cantact: ratios clipped into the valid ranges: fx %llu of %.0f draws (%.3g %%), "
                "fz %llu (%.3g %%)\n",
                (unsigned long long)cx, draws, draws > 0 ? 100.0 * (double)cx / draws : 0.0,
                (unsigned long long)cz, draws > 0 ? 100.0 * (double)cz / draws : 0.0);
    }
    if (isfinite(sem_max))
        fprintf(stderr,
                "cantact: standard error of mean e over %llu %s: at most %.3g "
                "(V* = %g, impact %zu); it falls as 1/sqrt(%s)\n",
                (unsigned long long)t->count, of, sem_max, sc->V_star[at / (size_t)sc->impacts],
                at % (size_t)sc->impacts + 1, of);
    if (failed)
        fprintf(stderr,
                "cantact: %zu of %zu impacts failed or not run (left out of the "
                "statistics)\n",
                failed, (size_t)t->count * t->nrows);
    const char *det = t->landings ? "e_at_position" : "e_deterministic";
    if (det_why[0])
        fprintf(stderr, "cantact: ensemble: %s left empty: %s\n", det, det_why);
    else if (det_empty)
        fprintf(stderr,
                "cantact: ensemble: %s empty in %zu of %zu rows (the %s impact failed or was not "
                "run)\n",
                det, det_empty, t->nrows,
                t->landings ? "apex at body.position's" : "deterministic surface's");
}

int ct_ens_write_outputs(ct_ens_outputs *o, const ct_scene *sc, const ct_ens_table *t, int quiet)
{
    char err[512];
    if (o->opened_real) {
        char id[800];
        ct_ens_identity(sc, &t->info, id, sizeof id);
        fprintf(o->real.f, "%s\n%s\n", id, ct_ens_samples_header(sc));
        write_realisations(o->real.f, sc, t);
    }
    double sem_max = NAN;
    size_t at = 0, det_empty = 0;
    char det_why[300] = "";
    if (o->opened_ens &&
        write_statistics(o->ens.f, sc, t, &sem_max, &at, &det_empty, det_why, sizeof det_why)) {
        ct_cli_fail("ensemble statistics: out of memory");
        return EXIT_FAILED;
    }
    ct_out *outs[2];
    size_t nouts = 0;
    if (o->opened_ens)
        outs[nouts++] = &o->ens;
    if (o->opened_real)
        outs[nouts++] = &o->real;
    o->opened_ens = o->opened_real = 0; /* published together or dropped together */
    if (ct_out_commit_all(outs, nouts, err, sizeof err)) {
        ct_cli_fail("%s", err);
        return EXIT_USAGE;
    }
    if (!quiet)
        summary(sc, t, sem_max, at, det_empty, det_why);
    return EXIT_DONE;
}
