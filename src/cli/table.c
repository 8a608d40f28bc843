/* `cantact table SCENE`: e(V*) of the first impact on the scene's surface as a table whose
 * interpolation reproduces the exact model within [table] tolerance at every checked point
 * (ct_table_build), written by ct_table_write for include/cantact_table.h and other readers. */
#include "table.h"

#include "args.h"
#include "ensemble.h"
#include "output.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef CT_VERSION
#define CT_VERSION "unknown"
#endif

const char *const ct_cli_table_help =
    "Usage: cantact table SCENE.ini [--set section.key=value]... [-o FILE] [-q]\n"
    "\n"
    "Tabulates e of the first impact on the scene's surface (any kind: cantact kinds) against\n"
    "V* on an adaptive grid: nodes are added (at the load curve's kinks first, else at interval\n"
    "middles in ln V*) until the interpolation reproduces the exact model within [table]\n"
    "tolerance at every checked point (check_points inside each interval); V*_c is a node and\n"
    "e = 1 exactly below it. The worst error found is printed and written in the header. The\n"
    "run fails (exit 1, no output) rather than write a table that misses its tolerance. On a\n"
    "terminal, stderr shows the exact impacts computed of those planned so far.\n"
    "\n"
    "Writes CSV: '# key = value' header lines (scene, surface, units, interpolation and its\n"
    "formula, V_star_crit, tolerance, worst_error, v_per_V_star when [impact] gives mass),\n"
    "then V_star,e,de_dlnV_star. include/cantact_table.h reads it (C99, no dependencies).\n"
    "\n"
    "Scene keys ([table]):\n"
    "  tolerance = 1e-6           largest |e_table - e|, absolute (1e-13 .. 0.5)\n"
    "  V_star = from:to           the range (default: the range of [impact]'s speeds)\n"
    "  interpolation = monotone_cubic | linear   (both in ln V*)\n"
    "  max_nodes = 100000         the run fails rather than exceed it\n"
    "  check_points = 16          points checked inside every interval (1 .. 1000)\n"
    "[impact] impacts is not used: a table is of the first impact on the virgin surface.\n"
    "\n"
    "With samples (body.landings, or [ensemble] realisations of a random surface) the table is\n"
    "of their statistics: e is the mean over the samples and, per node, e at each of [table]\n"
    "quantiles (columns e_p<p>); every sample is computed at [table] grid speeds equally\n"
    "spaced in ln V*, and the nodes are grid points added until every grid point of every\n"
    "column is within the tolerance (cantact_table.h: ct_tab_eval_quantile).\n"
    "  quantiles = 0.01, 0.05, ..., 0.95, 0.99   probabilities in (0, 1] (at most 64)\n"
    "  grid = 2000                speeds every sample is computed at (2 .. 1e6)\n"
    "  quantile_tolerance = tolerance   the quantile columns' (each has a kink wherever two\n"
    "                             samples' e cross: far more than the mean)\n"
    "\n"
    "Options:\n"
    "  --set section.key=value   override a scene key (each once; key= unsets it)\n"
    "  -o FILE                   same as --set output.file=FILE ('-' for stdout)\n"
    "  -q                        no summary on stderr\n"
    "  -h, --help                this help\n";

static void show_progress(size_t done, size_t total, void *ctx)
{
    ct_progress_to(ctx, done, total);
}

/* The surface planned for the table's range (depth auto from its smallest speed, the rods its
 * largest reaches) and the table built on it, its progress (exact impacts computed of those
 * planned so far) on a terminal. */
/* The table of a scene's samples (landings or realisations) over the same range: the mean and
 * quantiles of e (ct_table_build_samples); *what says what the samples are. */
static int build_samples_table(const ct_scene *sc, const ct_table_spec *spec, ct_table **t,
                               ct_plan_info *info, char *what, size_t len, char *why, size_t whylen)
{
    ct_cli_samples s;
    int st = ct_cli_samples_prepare(sc, &s, why, whylen);
    if (st)
        return st;
    *info = s.info;
    if (s.landings)
        snprintf(what, len, "body.landings = %llu, body.seed = %llu", (unsigned long long)s.count,
                 (unsigned long long)sc->body.seed);
    else
        snprintf(what, len, "ensemble.realisations = %llu", (unsigned long long)s.count);
    ct_ensemble_spec es;
    ct_cli_samples_spec(sc, &s, 0, s.count, &es);
    ct_table_quantiles q = {.p = sc->table_p,
                            .np = sc->table_np,
                            .grid = (size_t)sc->table_grid,
                            .tolerance = sc->table_qtol};
    st = ct_table_build_samples(t, &es, spec, &q);
    ct_cli_samples_free(&s);
    return st;
}

static int build_table(const ct_scene *sc, ct_bundle **b, ct_table **t, ct_plan_info *info,
                       char *samples, size_t len, char *why, size_t whylen)
{
    double range[2] = {sc->table_V_min, sc->table_V_max};
    ct_build_request req;
    ct_scene_request(sc, 0, &req);
    req.V_star = range;
    req.nvel = 2;
    req.impacts = 1;
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = range[0];
    spec.V_max = range[1];
    spec.tolerance = sc->table_tolerance;
    spec.interpolation = sc->table_interpolation;
    spec.max_nodes = (size_t)sc->table_max_nodes;
    spec.check_points = (size_t)sc->table_check_points;
    spec.opts = sc->opts;
    spec.path = sc->path;
    const int of_samples = sc->realisations || sc->body.landings;
    int st = of_samples ? CT_OK : ct_surface_build(sc->surface, &req, b, info);
    if (st)
        return st;
    ct_progress prog;
    ct_progress_start(&prog, 2);
    prog.unit = of_samples ? "samples" : "exact impacts (more while intervals fail)";
    if (prog.enabled) {
        spec.progress = show_progress;
        spec.progress_ctx = &prog;
    }
    st = of_samples ? build_samples_table(sc, &spec, t, info, samples, len, why, whylen)
                    : ct_table_build(t, *b, &spec);
    ct_progress_end(&prog);
    return st;
}

int ct_cli_table(int argc, char **argv)
{
    ct_args a;
    ct_scene sc;
    int rc = ct_args_parse(&a, argc, argv, "table", NULL, 1);
    if (rc < 0 && a.help) {
        fputs(ct_cli_table_help, stdout);
        rc = EXIT_DONE;
    }
    if (rc < 0)
        rc = ct_cli_load_scene(&a, "table", &sc);
    if (rc >= 0) {
        ct_args_free(&a);
        return rc;
    }
    rc = EXIT_USAGE;
    const char *scene = a.positional[0];
    ct_out out = {0};
    int opened = 0, st;
    ct_bundle *b = NULL;
    ct_table *t = NULL;
    ct_plan_info info;
    char err[600];
    if (ct_out_open(&out, sc.output, err, sizeof err)) {
        ct_cli_fail("%s", err);
        goto done;
    }
    opened = 1;
    char samples[200] = "", why[1024] = "";
    if ((st = build_table(&sc, &b, &t, &info, samples, sizeof samples, why, sizeof why))) {
        /* samples that cannot be prepared say why in why */
        ct_cli_fail_scene(&sc, st, why[0] ? why : ct_error_message());
        rc = ct_cli_status_exit(st);
        goto done;
    }
    char line[800], body[200];
    ct_surface_table_line(sc.surface, &info, line, 600);
    ct_body_describe(&sc.body, body, sizeof body);
    if (body[0]) /* a table made for a ball says so */
        snprintf(line + strlen(line), sizeof line - strlen(line), "; %s", body);
    ct_table_meta meta = {.version = CT_VERSION,
                          .scene = scene,
                          .surface = line,
                          .tolerance = sc.table_tolerance,
                          .check_points = (size_t)sc.table_check_points,
                          .v_per_V_star = NAN,
                          .samples = samples[0] ? samples : NULL,
                          .grid = (size_t)sc.table_grid};
    if (sc.mass > 0.0) /* V* = sqrt(m / (2 l0 E h0)) v, as the scene converts speeds */
        meta.v_per_V_star = 1.0 / ct_V_star_of(sc.mass, 1.0, sc.scales.physical.l0,
                                               sc.scales.physical.E, sc.scales.physical.h0);
    ct_table_write(out.f, t, &meta);
    ct_table_info in;
    ct_table_get_info(t, &in);
    if (!a.quiet && ct_table_quantile_count(t))
        fprintf(stderr,
                "cantact: table of the mean and %zu quantiles of e over %s: %zu nodes on V* %.6g "
                ".. %.6g, %s: worst error of the mean %.3g (tolerance %.3g), of a quantile %.3g "
                "(tolerance %.3g), over %zu checked grid points of %ld (%zu impacts)\n",
                ct_table_quantile_count(t), samples, ct_table_size(t), sc.table_V_min,
                sc.table_V_max, ct_interp_name(ct_table_interpolation(t)), in.worst_error,
                sc.table_tolerance, ct_table_quantile_worst_error(t),
                ct_table_quantile_tolerance(t), in.checked, sc.table_grid, in.evaluations);
    else if (!a.quiet)
        fprintf(stderr,
                "cantact: table of %zu nodes (%zu at kinks) on V* %.6g .. %.6g, %s: worst "
                "|e_table - e| = %.3g at V* = %.6g over %zu checked points (tolerance %.3g; "
                "%zu exact impacts, %zu rounds)\n",
                ct_table_size(t), in.kinks, sc.table_V_min, sc.table_V_max,
                ct_interp_name(ct_table_interpolation(t)), in.worst_error, in.worst_V_star,
                in.checked, sc.table_tolerance, in.evaluations, in.rounds);
    opened = 0;
    if (ct_out_commit(&out, err, sizeof err)) {
        ct_cli_fail("%s", err);
        goto done;
    }
    rc = EXIT_DONE;
done:
    if (opened)
        ct_out_abort(&out);
    ct_table_free(t);
    ct_bundle_free(b);
    ct_scene_free(&sc);
    ct_args_free(&a);
    return rc;
}
