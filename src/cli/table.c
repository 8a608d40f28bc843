/* `cantact table SCENE`: e(V*) of the first impact on the scene's surface as a table whose
 * interpolation reproduces the exact model within [table] tolerance at every checked point
 * (ct_table_build), written as CSV for include/cantact_table.h and other readers. */
#include "table.h"

#include "ensemble.h"
#include "number.h"
#include "output.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef CT_VERSION
#define CT_VERSION "unknown"
#endif

enum { EXIT_DONE = 0, EXIT_FAILED = 1, EXIT_USAGE = 2 };

const char *const ct_cli_table_help =
    "Usage: cantact table SCENE.ini [--set section.key=value]... [-o FILE] [-q]\n"
    "\n"
    "Tabulates e of the first impact on the scene's surface against V* on an adaptive grid:\n"
    "nodes are added (at the load curve's kinks first, else at interval middles in ln V*)\n"
    "until the interpolation reproduces the exact model within [table] tolerance at every\n"
    "checked point (check_points inside each interval); V*_c is a node and e = 1 exactly\n"
    "below it. The worst error found is printed and written in the header. The run fails\n"
    "(exit 1, no output) rather than write a table that misses its tolerance.\n"
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
    "Options:\n"
    "  --set section.key=value   override a scene key (repeatable)\n"
    "  -o FILE                   same as --set output.file=FILE ('-' for stdout)\n"
    "  -q                        no summary on stderr\n"
    "  -h, --help                this help\n";

static void fail_line(const char *msg)
{
    fprintf(stderr, "cantact: %s\n", msg);
}

static int status_exit(int st)
{
    return (st == CT_EINVAL || st == CT_ERANGE || st == CT_EIO) ? EXIT_USAGE : EXIT_FAILED;
}

static void put_value(FILE *f, const char *key, double v)
{
    fprintf(f, "# %s = ", key);
    ct_put_double(f, v);
    fputc('\n', f);
}

static void write_table(FILE *f, const char *scene, const ct_scene *sc, const ct_plan_info *info,
                        const ct_table *t, double v_per_V)
{
    ct_table_info in;
    ct_table_get_info(t, &in);
    const ct_params *p = &sc->params;
    fprintf(f, "# cantact %s table: e of the first impact on the virgin surface against V*\n",
            CT_VERSION);
    fprintf(f, "# scene = %s\n", scene);
    fprintf(f,
            "# surface = %s: fx = %.17g, fz = %.17g, H*/h0 = %.17g, E/sigma_y = %.17g, depth %ld, "
            "%zu rods",
            sc->surface_type == CT_SURFACE_RANDOM_CANTOR ? "random_cantor" : "cantor", p->fx, p->fz,
            p->Hstar / p->h0, p->E / p->sigma_y, info->depth, info->rods);
    if (sc->surface_type == CT_SURFACE_RANDOM_CANTOR)
        fprintf(f, ", seed %llu, realisation %llu, spreads %.17g %.17g",
                (unsigned long long)sc->seed, (unsigned long long)sc->realisation, sc->fx_spread,
                sc->fz_spread);
    fputc('\n', f);
    fputs("# units: V_star = sqrt(m v^2 / (2 l0 E h0)) dimensionless; e dimensionless; "
          "de_dlnV_star = de/d(ln V_star) dimensionless\n",
          f);
    fprintf(f, "# interpolation = %s\n", ct_interp_name(ct_table_interpolation(t)));
    if (ct_table_interpolation(t) == CT_INTERP_LINEAR)
        fputs("# rule: in x = ln V_star on the interval [x_i, x_i+1] holding x, t = (x - x_i) / "
              "(x_i+1 - x_i): e = e_i + (e_i+1 - e_i) t (de_dlnV_star is not used: 0)\n",
              f);
    else
        fputs("# rule: in x = ln V_star on the interval [x_i, x_i+1] holding x, h = x_i+1 - x_i, "
              "t = (x - x_i) / h, d = de_dlnV_star: e = e_i + (e_i+1 - e_i) t^2 (3 - 2 t) + "
              "h t (1 - t) ((1 - t) d_i - t d_i+1)\n",
              f);
    fputs("# rule: e = 1 exactly for V_star <= V_star_crit; outside the nodes above it, the "
          "nearest end's e (the table does not cover it)\n",
          f);
    put_value(f, "V_star_crit", in.V_star_crit);
    put_value(f, "tolerance", sc->table_tolerance);
    put_value(f, "worst_error", in.worst_error);
    put_value(f, "worst_error_at_V_star", in.worst_V_star);
    fprintf(f,
            "# checked = %zu points against the exact model (%ld equally spaced in ln V_star "
            "inside every interval above V_star_crit; the nodes are exact)\n",
            in.checked, sc->table_check_points);
    fprintf(f,
            "# nodes = %zu (%zu at kinks of e, where u_max reaches a rod's contact or yield "
            "point)\n",
            ct_table_size(t), in.kinks);
    if (isfinite(v_per_V))
        fprintf(f,
                "# v_per_V_star = %.17g (impact speed = V_star * v_per_V_star, in the units of "
                "the scene's mass, l0, E and h0)\n",
                v_per_V);
    fputs("V_star,e,de_dlnV_star\n", f);
    const double *V = ct_table_V_star(t), *e = ct_table_e(t), *d = ct_table_slope(t);
    for (size_t i = 0; i < ct_table_size(t); i++) {
        ct_put_double(f, V[i]);
        fputc(',', f);
        ct_put_double(f, e[i]);
        fputc(',', f);
        ct_put_double(f, d[i]);
        fputc('\n', f);
    }
}

int ct_cli_table(int argc, char **argv)
{
    const char **sets = calloc((size_t)argc + 1, sizeof(char *));
    char *obuf = NULL, err[600];
    const char *scene = NULL;
    size_t nsets = 0;
    int quiet = 0, rc = EXIT_USAGE, loaded = 0, opened = 0, st;
    ct_scene sc;
    ct_out out = {0};
    ct_bundle *b = NULL;
    ct_table *t = NULL;
    if (!sets) {
        fail_line("out of memory");
        return EXIT_FAILED;
    }
    for (int k = 0; k < argc; k++) {
        const char *s = argv[k];
        if (!strcmp(s, "-h") || !strcmp(s, "--help")) {
            fputs(ct_cli_table_help, stdout);
            rc = EXIT_DONE;
            goto done;
        } else if (!strcmp(s, "-q")) {
            quiet = 1;
        } else if (!strcmp(s, "--set") || !strcmp(s, "-o")) {
            if (k + 1 >= argc) {
                fprintf(stderr, "cantact: %s needs a value\n", s);
                goto done;
            }
            if (!strcmp(s, "-o")) {
                const char *path = argv[++k];
                size_t n = strlen(path) + sizeof "output.file=";
                free(obuf);
                if (!(obuf = malloc(n))) {
                    fail_line("out of memory");
                    rc = EXIT_FAILED;
                    goto done;
                }
                snprintf(obuf, n, "output.file=%s", path);
            } else {
                sets[nsets++] = argv[++k];
            }
        } else if (!strncmp(s, "--set=", 6)) {
            sets[nsets++] = s + 6;
        } else if (s[0] == '-' && s[1]) {
            fprintf(stderr, "cantact: unknown option %s (see cantact table --help)\n", s);
            goto done;
        } else if (!scene) {
            scene = s;
        } else {
            fprintf(stderr, "cantact: only one scene file, got %s and %s\n", scene, s);
            goto done;
        }
    }
    if (obuf)
        sets[nsets++] = obuf; /* -o is applied last, as a --set output.file */
    if (!scene) {
        fail_line("table: missing SCENE.ini (see cantact table --help)");
        goto done;
    }
    if (ct_scene_load(&sc, scene, sets, nsets)) {
        fail_line(ct_scene_message());
        goto done;
    }
    loaded = 1;
    if (ct_out_same_file(scene, sc.output)) {
        fprintf(stderr, "cantact: output.file = %s: is the scene file itself\n", sc.output);
        goto done;
    }
    if (sc.realisations) {
        snprintf(err, sizeof err,
                 "table: %s has [ensemble] realisations: a table is of one surface (without "
                 "[ensemble], surface.realisation names it)",
                 scene);
        fail_line(err);
        goto done;
    }
    ct_scene_make_dimensionless(&sc);
    if ((st = ct_params_validate(&sc.params))) {
        fprintf(stderr, "cantact: %s: %s\n", scene, ct_error_message());
        goto done;
    }
    if (ct_out_open(&out, sc.output, err, sizeof err)) {
        fail_line(err);
        goto done;
    }
    opened = 1;

    /* the surface, planned for the table's range (depth auto from its smallest speed, the
     * rods its largest reaches) */
    ct_plan_info info;
    double range[2] = {sc.table_V_min, sc.table_V_max};
    if (sc.surface_type == CT_SURFACE_RANDOM_CANTOR) {
        st = ct_cli_random_surface(&sc, &b, &info);
    } else {
        ct_cantor_plan plan = {.params = sc.params,
                               .depth = sc.depth,
                               .representation = sc.representation,
                               .depth_tolerance = sc.depth_tolerance,
                               .V_star = range,
                               .nvel = 2,
                               .impacts = 1,
                               .opts = sc.opts,
                               .threads = sc.threads};
        st = ct_cantor_plan_build(&plan, &b, &info);
    }
    if (st) {
        fail_line(ct_error_message());
        rc = status_exit(st);
        goto done;
    }
    ct_bundle_set_threads(b, sc.threads);
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = range[0];
    spec.V_max = range[1];
    spec.tolerance = sc.table_tolerance;
    spec.interpolation = sc.table_interpolation;
    spec.max_nodes = (size_t)sc.table_max_nodes;
    spec.check_points = (size_t)sc.table_check_points;
    spec.opts = sc.opts;
    spec.path = sc.path;
    if ((st = ct_table_build(&t, b, &spec))) {
        fail_line(ct_error_message());
        rc = status_exit(st);
        goto done;
    }
    double v_per_V = NAN;
    if (sc.mass > 0.0) /* V* = sqrt(m / (2 l0 E h0)) v, as the scene converts speeds */
        v_per_V = 1.0 / sqrt(sc.mass / (2.0 * ct_energy_scale(&sc.physical)));
    write_table(out.f, scene, &sc, &info, t, v_per_V);
    ct_table_info in;
    ct_table_get_info(t, &in);
    if (!quiet)
        fprintf(stderr,
                "cantact: table of %zu nodes (%zu at kinks) on V* %.6g .. %.6g, %s: worst "
                "|e_table - e| = %.3g at V* = %.6g over %zu checked points (tolerance %.3g; "
                "%zu exact impacts, %zu rounds)\n",
                ct_table_size(t), in.kinks, range[0], range[1], ct_interp_name(spec.interpolation),
                in.worst_error, in.worst_V_star, in.checked, spec.tolerance, in.evaluations,
                in.rounds);
    opened = 0;
    if (ct_out_commit(&out, err, sizeof err)) {
        fail_line(err);
        goto done;
    }
    rc = EXIT_DONE;
done:
    if (opened)
        ct_out_abort(&out);
    ct_table_free(t);
    ct_bundle_free(b);
    if (loaded)
        ct_scene_free(&sc);
    free(sets);
    free(obuf);
    return rc;
}
