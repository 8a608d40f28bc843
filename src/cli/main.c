/* cantact: the command-line program. Subcommands: run, geometry. */
#include "cantact.h"
#include "output.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef CT_VERSION
#define CT_VERSION "unknown"
#endif

enum { EXIT_DONE = 0, EXIT_FAILED = 1, EXIT_USAGE = 2 };

static const char *main_help =
    "Usage: cantact <subcommand> [options] [SCENE.ini]\n"
    "\n"
    "Coefficient of restitution e of a Cantor-fractal rough surface made of\n"
    "elastic-perfectly-plastic rods (Cantor stages built explicitly as rods).\n"
    "\n"
    "Subcommands:\n"
    "  run SCENE        compute what the scene's [output] what asks for (e, curve, profile,\n"
    "                   compare)\n"
    "  geometry SCENE   print the Cantor geometry of the scene's surface\n"
    "\n"
    "Options:\n"
    "  -h, --help       this help (also: cantact <subcommand> --help)\n"
    "  --version        print the version\n"
    "\n"
    "Exit status: 0 done, 1 the computation failed, 2 bad input or usage.\n";

static const char *run_help =
    "Usage: cantact run SCENE.ini [--set section.key=value]... [-o FILE]\n"
    "\n"
    "Reads the scene, builds the surface as rods and, for each V* in input order, runs\n"
    "[impact] impacts impacts from the virgin surface (the rods' state carried from one\n"
    "impact to the next). Writes CSV (header row; u in h0, P in P_Y = sigma_y l0):\n"
    "  e:       impact,V_star,u_max_over_h0,e,e_closed_form,quadrature_error,\n"
    "           V_star_crit,u_release_over_h0,elastic\n"
    "  curve:   V_star,impact,u_over_h0,P_over_PY,branch (load|unload)\n"
    "  compare: adds e_series,e_asymptotic,e_asymptotic_consistent to e rows and the laws'\n"
    "           P(u) to curve rows (first impact; the laws model the virgin fractal)\n"
    "  profile: stage,x_left_over_l0,x_right_over_l0,top_over_h0,residual_top_over_h0\n"
    "With several items in [output] what, FILE holds e and the others go to FILE with\n"
    "_curve / _profile before its extension. Outputs appear only when complete.\n"
    "\n"
    "Options:\n"
    "  --set section.key=value   override a scene key (repeatable)\n"
    "  -o FILE                   same as --set output.file=FILE ('-' for stdout)\n"
    "  -q                        no summary on stderr\n"
    "  -h, --help                this help\n"
    "\n"
    "Scene keys: [surface] fx fz H h0 l0 depth representation; [material] E sigma_y;\n"
    "[impact] V_star | mass velocity, impacts; [solver] quadrature nodes tolerance\n"
    "depth_tolerance threads; [output] file what. See README.md.\n";

static const char *geometry_help =
    "Usage: cantact geometry SCENE.ini [--set section.key=value]...\n"
    "\n"
    "Prints alpha, beta, D and, per stage, l_i/l0, h_i/h0, s_i/l0 and the rod length\n"
    "(H* - h_i)/h0 of the scene's surface at its depth (auto: the depth the run would use).\n";

static void fail_line(const char *msg)
{
    fprintf(stderr, "cantact: %s\n", msg);
}

static int status_exit(int st)
{
    return (st == CT_EINVAL || st == CT_ERANGE || st == CT_EIO) ? EXIT_USAGE : EXIT_FAILED;
}

typedef struct {
    const char *scene;
    const char **sets;
    size_t nsets;
    int quiet;
    int help;
} cli_args;

static int parse_args(int argc, char **argv, cli_args *a)
{
    memset(a, 0, sizeof *a);
    a->sets = calloc((size_t)argc + 1, sizeof(char *));
    static char obuf[4096];
    if (!a->sets) {
        fail_line("out of memory");
        return EXIT_FAILED;
    }
    for (int k = 0; k < argc; k++) {
        const char *s = argv[k];
        if (!strcmp(s, "-h") || !strcmp(s, "--help")) {
            a->help = 1;
        } else if (!strcmp(s, "-q")) {
            a->quiet = 1;
        } else if (!strcmp(s, "--set") || !strcmp(s, "-o")) {
            if (k + 1 >= argc) {
                fprintf(stderr, "cantact: %s needs a value\n", s);
                return EXIT_USAGE;
            }
            if (!strcmp(s, "-o")) {
                snprintf(obuf, sizeof obuf, "output.file=%s", argv[++k]);
                a->sets[a->nsets++] = obuf;
            } else {
                a->sets[a->nsets++] = argv[++k];
            }
        } else if (!strncmp(s, "--set=", 6)) {
            a->sets[a->nsets++] = s + 6;
        } else if (s[0] == '-' && s[1]) {
            fprintf(stderr, "cantact: unknown option %s (see --help)\n", s);
            return EXIT_USAGE;
        } else if (!a->scene) {
            a->scene = s;
        } else {
            fprintf(stderr, "cantact: only one scene file, got %s and %s\n", a->scene, s);
            return EXIT_USAGE;
        }
    }
    return EXIT_DONE;
}

/* Depth the run uses: the scene's, or auto for the smallest impact energy. */
static int choose_depth(const ct_scene *sc, long *depth, double *bound)
{
    *bound = 0.0;
    if (sc->depth >= 0) {
        *depth = sc->depth;
        return CT_OK;
    }
    double vmin = INFINITY;
    for (size_t k = 0; k < sc->nvel; k++)
        vmin = sc->V_star[k] < vmin ? sc->V_star[k] : vmin;
    double W_min = vmin * vmin * ct_energy_scale(&sc->params);
    if (sc->depth == CT_DEPTH_FRACTAL)
        return ct_fractal_depth(&sc->params, W_min, depth, bound);
    return ct_auto_depth(&sc->params, W_min, sc->depth_tolerance, depth, bound);
}

static char *derived_path(const char *path, const char *tag)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    size_t n = strlen(path);
    char *out = malloc(n + strlen(tag) + 2);
    if (!out)
        return NULL;
    if (dot && (!slash || dot > slash) && dot != path)
        sprintf(out, "%.*s_%s%s", (int)(dot - path), path, tag, dot);
    else
        sprintf(out, "%s_%s", path, tag);
    return out;
}

/* A curve branch: the breakpoints in [lo, hi] (when fewer than 1e5) and a uniform grid. */
static int write_branch(FILE *f, ct_bundle *b, double V, long impact, double lo, double hi,
                        const char *branch, double h0, double PY, int compare)
{
    const ct_params *p = ct_bundle_params(b);
    enum { GRID = 200 };
    double *pts = NULL;
    size_t n = 0;
    int st = ct_bundle_breakpoints(b, lo, hi, &pts, &n);
    if (st)
        return st;
    size_t use = n < 100000 ? n : 0;
    double *u = malloc((use + GRID + 1) * sizeof(double));
    if (!u) {
        free(pts);
        return CT_ENOMEM;
    }
    size_t m = 0;
    for (size_t k = 0; k < use; k++)
        u[m++] = pts[k];
    for (int k = 0; k <= GRID; k++)
        u[m++] = lo + (hi - lo) * k / GRID;
    free(pts);
    /* sort (insertion on a nearly sorted merge is fine at this size) */
    for (size_t i = 1; i < m; i++) {
        double x = u[i];
        size_t j = i;
        while (j > 0 && u[j - 1] > x) {
            u[j] = u[j - 1];
            j--;
        }
        u[j] = x;
    }
    int unload = !strcmp(branch, "unload");
    for (size_t i = 0; i < m; i++) {
        size_t k = unload ? m - 1 - i : i;
        if (i > 0 && u[k] == u[unload ? k + 1 : k - 1])
            continue;
        double P = ct_bundle_force(b, u[k]);
        fprintf(f, "%.17g,%ld,%.17g,%.17g,%s", V, impact, u[k] / h0, P / PY, branch);
        if (compare && impact == 1) {
            /* the laws at the same u, unloading from the exact u_max (hi) */
            double ps = 0.0, pa = 0.0, pc = 0.0;
            int ss = unload ? ct_series_unload(p, hi, u[k], &ps) : ct_series_load(p, u[k], &ps);
            int sa = unload ? ct_asym_unload(p, hi, u[k], 0, &pa) : ct_asym_load(p, u[k], &pa);
            int sc = unload ? ct_asym_unload(p, hi, u[k], 1, &pc) : sa;
            double laws[3] = {ss ? NAN : ps, sa ? NAN : pa, sc ? NAN : unload ? pc : pa};
            for (int l = 0; l < 3; l++) {
                if (isfinite(laws[l]))
                    fprintf(f, ",%.17g", laws[l] / PY);
                else
                    fputc(',', f); /* outside the law (asymptotic beyond u = h0) */
            }
        } else if (compare) {
            fputs(",,,", f);
        }
        fputc('\n', f);
    }
    free(u);
    return CT_OK;
}

static int write_profile(FILE *f, ct_bundle *b, const ct_params *p)
{
    long N = ct_bundle_depth(b);
    if (N > 20) {
        fprintf(stderr,
                "cantact: profile: depth %ld has 2^%ld pieces; the profile is written for "
                "depth <= 20 (set surface.depth)\n",
                N, N + 1);
        return CT_EINVAL;
    }
    fprintf(f, "stage,x_left_over_l0,x_right_over_l0,top_over_h0,residual_top_over_h0\n");
    size_t n = ct_bundle_size(b);
    ct_rod_info first;
    long first_stage = N + 1;
    if (n && !ct_bundle_rod(b, 0, &first))
        first_stage = first.stage;
    /* stage rods stand for all pieces of their stage */
    for (long i = 0; i <= N; i++) {
        double top = ct_stage_depth(p, (double)i), residual = top;
        if (i >= first_stage) {
            ct_rod_info info;
            size_t k = ct_bundle_representation(b) == CT_REP_STAGES
                           ? (size_t)(i - first_stage)
                           : ((size_t)1 << i) - ((size_t)1 << first_stage);
            if (ct_bundle_rod(b, k, &info) == CT_OK)
                residual = info.top + info.plastic_strain * info.length;
        }
        for (size_t j = 0; j < ((size_t)1 << i); j++) {
            double xl, xr;
            ct_piece_extent(p, N, i, j, &xl, &xr);
            if (ct_bundle_representation(b) == CT_REP_SEGMENTS && i >= first_stage) {
                ct_rod_info info;
                size_t k = ((size_t)1 << i) - 1 + j - (((size_t)1 << first_stage) - 1);
                if (ct_bundle_rod(b, k, &info) == CT_OK)
                    residual = info.top + info.plastic_strain * info.length;
            }
            fprintf(f, "%ld,%.17g,%.17g,%.17g,%.17g\n", i, xl / p->l0, xr / p->l0, top / p->h0,
                    residual / p->h0);
        }
    }
    return CT_OK;
}

/* Parses a subcommand's arguments and loads its scene. Returns -1 when the scene is loaded
 * into *sc (the caller goes on), else the exit status to return (help shown, or an error). */
static int load_scene_args(int argc, char **argv, const char *cmd, const char *help, ct_scene *sc,
                           int *quiet)
{
    cli_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc || a.help) {
        if (a.help)
            fputs(help, stdout);
        free(a.sets);
        return rc;
    }
    if (!a.scene) {
        fprintf(stderr, "cantact: %s: missing SCENE.ini (see cantact %s --help)\n", cmd, cmd);
        free(a.sets);
        return EXIT_USAGE;
    }
    int st = ct_scene_load(sc, a.scene, a.sets, a.nsets);
    free(a.sets);
    if (st) {
        fail_line(ct_error_message());
        return EXIT_USAGE;
    }
    *quiet = a.quiet;
    return -1;
}

static int cmd_run(int argc, char **argv)
{
    ct_scene sc;
    int quiet, st;
    int rc = load_scene_args(argc, argv, "run", run_help, &sc, &quiet);
    if (rc >= 0)
        return rc;
    const ct_params *p = &sc.params;
    ct_set_threads(sc.threads);
    int nitems = !!(sc.what & CT_OUT_E) + !!(sc.what & CT_OUT_CURVE) + !!(sc.what & CT_OUT_PROFILE);
    if (nitems > 1 && !strcmp(sc.output, "-")) {
        fail_line("output.what names several outputs: set output.file (or -o FILE) to a path");
        ct_scene_free(&sc);
        return EXIT_USAGE;
    }

    /* open every output first: an unwritable path fails before any work is done */
    ct_out out_e = {0}, out_curve = {0}, out_profile = {0};
    ct_bundle *b = NULL;
    long depth;
    double bound;
    char err[512];
    int opened_e = 0, opened_c = 0, opened_p = 0;
    const char *first_path = sc.output;
    char *curve_path = NULL, *profile_path = NULL;
    rc = EXIT_DONE;
    if (sc.what & CT_OUT_E) {
        if (ct_out_open(&out_e, first_path, err, sizeof err))
            goto io_fail;
        opened_e = 1;
    }
    if (sc.what & CT_OUT_CURVE) {
        curve_path = nitems > 1 ? derived_path(sc.output, "curve") : strdup(sc.output);
        if (!curve_path || ct_out_open(&out_curve, curve_path, err, sizeof err))
            goto io_fail;
        opened_c = 1;
    }
    if (sc.what & CT_OUT_PROFILE) {
        profile_path = nitems > 1 ? derived_path(sc.output, "profile") : strdup(sc.output);
        if (!profile_path || ct_out_open(&out_profile, profile_path, err, sizeof err))
            goto io_fail;
        opened_p = 1;
    }

    double scale = ct_energy_scale(p), vmax = 0.0;
    for (size_t k = 0; k < sc.nvel; k++)
        vmax = sc.V_star[k] > vmax ? sc.V_star[k] : vmax;
    if ((st = choose_depth(&sc, &depth, &bound)))
        goto lib_fail;

    /* Rods deeper than the largest displacement any impact reaches can never be touched:
     * find it on the (cheap, exact) stage rods, then leave those rods out. */
    double u_reach = INFINITY;
    {
        ct_bundle *probe;
        if ((st = ct_bundle_alloc(&probe, p, CT_REP_STAGES, depth, INFINITY)))
            goto lib_fail;
        double umax = 0.0;
        for (long i = 0; i < sc.impacts && !st; i++) {
            ct_impact_result r;
            st = ct_impact(probe, vmax * vmax * scale, &sc.opts, &r);
            umax = r.u_max > umax ? r.u_max : umax;
        }
        ct_bundle_free(probe);
        if (st)
            goto lib_fail;
        u_reach = umax * (1.0 + 1e-9);
    }
    if (sc.what & CT_OUT_PROFILE)
        u_reach = INFINITY; /* the profile shows the whole surface */
    if ((st = ct_bundle_alloc(&b, p, sc.representation, depth, u_reach)))
        goto lib_fail;
    if (!quiet) {
        char how[96];
        if (sc.depth >= 0)
            snprintf(how, sizeof how, "given");
        else
            snprintf(how, sizeof how, "%s: truncation bound %.2g",
                     sc.depth == CT_DEPTH_FRACTAL ? "fractal limit" : "auto", bound);
        fprintf(stderr,
                "cantact: %s, depth %ld (%s), %zu rods, %zu left out as never touched, "
                "%d thread(s)\n",
                sc.representation == CT_REP_STAGES ? "stage rods" : "segment rods", depth, how,
                ct_bundle_size(b), ct_bundle_omitted(b), ct_set_threads(0));
    }

    int compare = !!(sc.what & CT_OUT_COMPARE);
    if (opened_e)
        fprintf(out_e.f,
                "impact,V_star,u_max_over_h0,e,e_closed_form,quadrature_error,"
                "V_star_crit,u_release_over_h0,elastic%s\n",
                compare ? ",e_series,e_asymptotic,e_asymptotic_consistent" : "");
    if (opened_c)
        fprintf(out_curve.f, "V_star,impact,u_over_h0,P_over_PY,branch%s\n",
                compare ? ",P_series_over_PY,P_asymptotic_over_PY,P_asymptotic_consistent_over_PY"
                        : "");
    ct_progress prog;
    ct_progress_start(&prog, sc.nvel * (size_t)sc.impacts);
    double PY = p->sigma_y * p->l0;
    for (size_t v = 0; v < sc.nvel && !st; v++) {
        ct_bundle_reset(b);
        for (long i = 1; i <= sc.impacts && !st; i++) {
            ct_impact_result r;
            double W = sc.V_star[v] * sc.V_star[v] * scale;
            double u0 = ct_bundle_first_contact(b);
            if (opened_c) {
                /* the loading branch follows the pre-impact state */
                double um;
                if ((st = ct_solve_umax(b, W, sc.opts.tolerance, &um)) ||
                    (st = write_branch(out_curve.f, b, sc.V_star[v], i, u0, um, "load", p->h0, PY,
                                       compare)))
                    break;
            }
            if ((st = ct_impact(b, W, &sc.opts, &r)))
                break;
            if (!isfinite(r.e) || !isfinite(r.e_closed) || !isfinite(r.u_max)) {
                st = CT_ENOCONV;
                snprintf(err, sizeof err, "V* = %g impact %ld: a non-finite result", sc.V_star[v],
                         i);
                fail_line(err);
                rc = EXIT_FAILED;
                goto cleanup;
            }
            if (opened_e) {
                fprintf(out_e.f, "%ld,%.17g,%.17g,%.17g,%.17g,%.3g,%.17g,%.17g,%d", i, sc.V_star[v],
                        r.u_max / p->h0, r.e, r.e_closed, r.quad_error, r.V_star_crit,
                        r.u_release / p->h0, r.elastic);
                if (compare && i == 1) {
                    /* the paper's laws model the first impact on the virgin fractal; where a
                     * law does not apply (u_max > h0, e > 1) its field stays empty */
                    for (int law = CT_LAW_SERIES; law <= CT_LAW_ASYMPTOTIC_CONSISTENT; law++) {
                        double um, el;
                        if (ct_law_impact(p, (ct_law)law, W, &um, &el) == CT_OK)
                            fprintf(out_e.f, ",%.17g", el);
                        else
                            fputc(',', out_e.f);
                    }
                } else if (compare) {
                    fputs(",,,", out_e.f);
                }
                fputc('\n', out_e.f);
            }
            if (opened_c && (st = write_branch(out_curve.f, b, sc.V_star[v], i, r.u_release,
                                               r.u_max, "unload", p->h0, PY, compare)))
                break;
            ct_progress_step(&prog);
        }
    }
    ct_progress_end(&prog);
    if (st)
        goto lib_fail;
    if (opened_p && (st = write_profile(out_profile.f, b, p))) {
        rc = EXIT_USAGE;
        goto cleanup;
    }
    if ((opened_e && ct_out_commit(&out_e, err, sizeof err)) ||
        (opened_c && ct_out_commit(&out_curve, err, sizeof err)) ||
        (opened_p && ct_out_commit(&out_profile, err, sizeof err))) {
        opened_e = opened_c = opened_p = 0; /* commit aborted what it could not write */
        fail_line(err);
        rc = EXIT_USAGE;
        goto cleanup;
    }
    opened_e = opened_c = opened_p = 0;
    goto cleanup;

lib_fail:
    fail_line(ct_error_message());
    rc = status_exit(st);
    goto cleanup;
io_fail:
    fail_line(err);
    rc = EXIT_USAGE;
cleanup:
    if (opened_e)
        ct_out_abort(&out_e);
    if (opened_c)
        ct_out_abort(&out_curve);
    if (opened_p)
        ct_out_abort(&out_profile);
    ct_bundle_free(b);
    free(curve_path);
    free(profile_path);
    ct_scene_free(&sc);
    return rc;
}

static int cmd_geometry(int argc, char **argv)
{
    ct_scene sc;
    int quiet, st;
    int rc = load_scene_args(argc, argv, "geometry", geometry_help, &sc, &quiet);
    if (rc >= 0)
        return rc;
    (void)quiet;
    const ct_params *p = &sc.params;
    long depth;
    double bound;
    if ((st = choose_depth(&sc, &depth, &bound))) {
        fail_line(ct_error_message());
        ct_scene_free(&sc);
        return status_exit(st);
    }
    printf("# fx = %g, fz = %g, H*/h0 = %g, E/sigma_y = %g\n", p->fx, p->fz, p->Hstar / p->h0,
           p->E / p->sigma_y);
    printf("# alpha = %.17g, beta = %.17g, D = %.17g, depth = %ld\n", ct_alpha(p), ct_beta(p),
           ct_dimension(p), depth);
    printf("stage,l_over_l0,h_over_h0,s_over_l0,rod_length_over_h0\n");
    long shown = depth < 60 ? depth : 60;
    for (long i = 0; i <= shown; i++) {
        double s = i < depth ? ct_stage_area(p, (double)i) : ct_stage_length(p, (double)i);
        double h = ct_stage_depth(p, (double)i);
        printf("%ld,%.17g,%.17g,%.17g,%.17g\n", i, ct_stage_length(p, (double)i) / p->l0, h / p->h0,
               s / p->l0, (p->Hstar - h) / p->h0);
    }
    if (shown < depth)
        printf("# ... %ld more stages\n", depth - shown);
    ct_scene_free(&sc);
    return EXIT_DONE;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fputs("cantact: missing subcommand (try cantact --help)\n", stderr);
        return EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help")) {
        fputs(main_help, stdout);
        return EXIT_DONE;
    }
    if (!strcmp(cmd, "--version")) {
        printf("cantact %s\n", CT_VERSION);
        return EXIT_DONE;
    }
    if (!strcmp(cmd, "run"))
        return cmd_run(argc - 2, argv + 2);
    if (!strcmp(cmd, "geometry"))
        return cmd_geometry(argc - 2, argv + 2);
    fprintf(stderr, "cantact: unknown subcommand '%s' (try cantact --help)\n", cmd);
    return EXIT_USAGE;
}
